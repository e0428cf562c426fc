//! `serde` support (feature `serde`): hand-written `Serialize` and `Deserialize` for the
//! public data types, so host tools need not mirror them. Deserialisation **validates**:
//! what it returns passes the type's own check, or it is an error.
//!
//! | type | serialised as | validated on read |
//! |---|---|---|
//! | [`Vector<T, N>`] | a sequence of N numbers (a tuple: no length prefix in binary formats) | length |
//! | [`Matrix<T, R, C>`] | R rows, each a sequence of C numbers (row-major, like `self.0`) | lengths |
//! | [`Transform<T>`] | its 4×4 homogeneous matrix, 4 rows of 4 numbers (row-major: `[[R₀₀, R₀₁, R₀₂, x], …, [0, 0, 0, 1]]`) | bottom row exactly `[0, 0, 0, 1]`, [`Transform::check`] |
//! | [`JointKind`] | `"revolute"`, `"continuous"`, `"prismatic"` (URDF's spelling) | |
//! | [`Joint<T>`] | `{ "name", "kind", "screw": [ωx, ωy, ωz, vx, vy, vz], "lower", "upper" }`; a limit is `null` when unbounded (−∞ / +∞: JSON has no infinity) | [`ChainView::check`] of the joint alone |
//! | [`Chain<T, N>`] | `{ "base", "tip", "joints": [N joints], "home": Transform }` | [`ChainView::check`] |
//! | [`ChainView<T>`] | `{ "joints": [joints], "home": Transform }` (serialise only) | |
//! | [`UncertainPose<T>`] | `{ "pose": Transform, "cov": 6×6 rows }` (other fields are ignored) | pose, and [`check_covariance`] |
//! | [`Convention`], [`Error`] | the variant's name, e.g. `"Right"`, `"NotARotation"` | |
//!
//! **One shape for poses across ppoe.** A pose is a 4×4 row-major matrix and a
//! covariance 6×6 rows, rotation first (`(ω, v)`), everywhere: this module, every JSON
//! file the `ppoe` command reads or writes, and `ppoe-build`'s noise models. A result of
//! `ppoe eval` (`{"thetas_clipped", "pose", "cov"}`) therefore reads as an
//! [`UncertainPose`] as it is: [`UncertainPose`] ignores fields it does not know (its
//! two fields are required, so a misspelt one is still an error). Its `cov` is the
//! perturbation `eval` was asked for (`--convention`; the default is the right one,
//! [`Convention::Right`], which is what [`UncertainPose`] means). ROS's shape
//! (translation first, parent frame) is [`crate::interop::ros`]'s, and `ppoe eval
//! --format ros`'s.
//!
//! Joint names are `&'static str`, so [`Joint`] and [`Chain`] implement
//! `Deserialize<'static>` only: they borrow their names from input that lives for the
//! whole program (`include_str!`, a leaked buffer), and a name the format cannot lend as
//! it is (a JSON string with escapes) is an error. Deserialised joints have their
//! displacement constants computed ([`Joint::prepared`]); the constants are not written.
//!
//! Numbers are written as the format writes T: with `serde_json`'s `float_roundtrip`
//! feature a JSON round trip is bit-exact.
//!
//! ```
//! use ppoe::Transform;
//! let t = Transform::<f64>::from_rpy(&[0.1, 0.2, 0.3], [1.0, 2.0, 3.0])?;
//! let json = serde_json::to_string(&t).unwrap();
//! assert!(json.starts_with("[[") && json.ends_with(",[0.0,0.0,0.0,1.0]]"));
//! let back: Transform<f64> = serde_json::from_str(&json).unwrap();
//! assert_eq!(back, t);
//! // Not a rotation: an error, not a wrong transform.
//! let bad = "[[2,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]";
//! assert!(serde_json::from_str::<Transform<f64>>(bad).is_err());
//! # Ok::<(), ppoe::Error>(())
//! ```

use core::fmt;
use core::marker::PhantomData;

use serde::de::{self, Deserialize, Deserializer, SeqAccess, Visitor};
use serde::ser::{self, Serialize, SerializeTuple, Serializer};

use crate::chain::{Chain, ChainView, Convention, Joint, JointKind, UncertainPose};
use crate::error::Error;
use crate::linalg::{Mat6, Matrix, Vec6, Vector};
use crate::scalar::Real;
use crate::se3::Transform;
use crate::uncertainty::check_covariance;

/// Writes `items` as a tuple of known length.
fn serialize_tuple<S: Serializer, E: Serialize>(s: S, items: &[E]) -> Result<S::Ok, S::Error> {
    let mut t = s.serialize_tuple(items.len())?;
    for e in items {
        t.serialize_element(e)?;
    }
    t.end()
}

/// Reads a tuple of exactly N elements of type E into an array (no allocation: a
/// `heapless::Vec` of capacity N).
struct ArrayVisitor<E, const N: usize>(PhantomData<E>);

impl<'de, E: Deserialize<'de>, const N: usize> Visitor<'de> for ArrayVisitor<E, N> {
    type Value = [E; N];

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "a sequence of {N} elements")
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<[E; N], A::Error> {
        let mut buf = heapless::Vec::<E, N>::new();
        while let Some(e) = seq.next_element::<E>()? {
            if buf.push(e).is_err() {
                return Err(de::Error::invalid_length(N + 1, &self));
            }
        }
        let len = buf.len();
        buf.into_array()
            .map_err(|_| de::Error::invalid_length(len, &self))
    }
}

fn deserialize_array<'de, D, E, const N: usize>(d: D) -> Result<[E; N], D::Error>
where
    D: Deserializer<'de>,
    E: Deserialize<'de>,
{
    d.deserialize_tuple(N, ArrayVisitor::<E, N>(PhantomData))
}

impl<T: Serialize, const N: usize> Serialize for Vector<T, N> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        serialize_tuple(s, &self.0)
    }
}

impl<'de, T: Deserialize<'de>, const N: usize> Deserialize<'de> for Vector<T, N> {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        deserialize_array(d).map(Vector)
    }
}

/// One row of a matrix, written as a tuple.
struct Row<'a, T, const C: usize>(&'a [T; C]);

impl<T: Serialize, const C: usize> Serialize for Row<'_, T, C> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        serialize_tuple(s, self.0)
    }
}

impl<T: Serialize, const R: usize, const C: usize> Serialize for Matrix<T, R, C> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut t = s.serialize_tuple(R)?;
        for row in &self.0 {
            t.serialize_element(&Row(row))?;
        }
        t.end()
    }
}

impl<'de, T: Deserialize<'de>, const R: usize, const C: usize> Deserialize<'de>
    for Matrix<T, R, C>
{
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let rows: [Vector<T, C>; R] = deserialize_array(d)?;
        Ok(Matrix(rows.map(|r| r.0)))
    }
}

/// The bottom row every homogeneous transform has.
fn bottom_row<T: Real>() -> [T; 4] {
    [T::ZERO, T::ZERO, T::ZERO, T::ONE]
}

/// A transform is written as its 4×4 homogeneous matrix, row-major (four rows of four
/// numbers), the shape every file of the `ppoe` command uses (`eval`'s `pose` and `home`,
/// `fit`'s samples), so a pose written by one reads back in the other.
impl<T: Real + Serialize> Serialize for Transform<T> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        Matrix(self.to_matrix4()).serialize(s)
    }
}

/// Reads four rows of four; the bottom row must be exactly `[0, 0, 0, 1]` (anything else
/// is not a rigid transform, and silently dropping it would hide a wrong input) and the
/// rotation block must pass [`Transform::check`].
impl<'de, T: Real + Deserialize<'de>> Deserialize<'de> for Transform<T> {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let m = Matrix::<T, 4, 4>::deserialize(d)?;
        if m.0[3] != bottom_row::<T>() {
            return Err(de::Error::custom(
                "the bottom row of a 4×4 transform is not [0, 0, 0, 1]",
            ));
        }
        let t = Transform::from_matrix4(&m.0);
        t.check().map_err(de::Error::custom)?;
        Ok(t)
    }
}

/// The serialised form of [`JointKind`].
#[derive(serde::Serialize, serde::Deserialize)]
#[serde(remote = "JointKind", rename_all = "lowercase")]
enum JointKindRepr {
    Revolute,
    Continuous,
    Prismatic,
}

impl Serialize for JointKind {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        JointKindRepr::serialize(self, s)
    }
}

impl<'de> Deserialize<'de> for JointKind {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        JointKindRepr::deserialize(d)
    }
}

/// The serialised form of [`Convention`].
#[derive(serde::Serialize, serde::Deserialize)]
#[serde(remote = "Convention")]
enum ConventionRepr {
    Right,
    Left,
    Pytransform3d,
}

impl Serialize for Convention {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        ConventionRepr::serialize(self, s)
    }
}

impl<'de> Deserialize<'de> for Convention {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        ConventionRepr::deserialize(d)
    }
}

/// The serialised form of [`Error`].
#[derive(serde::Serialize, serde::Deserialize)]
#[serde(remote = "Error")]
enum ErrorRepr {
    NonFinite,
    NotSymmetric,
    NotPositiveSemidefinite,
    Singular,
    NotARotation,
    ZeroAxis,
    Empty,
    TooFewSamples,
    BufferTooSmall,
    LengthMismatch,
    GridSize,
    InconsistentConstants,
    Overflow,
    NotUnitAxis,
    IndexOutOfRange,
}

impl Serialize for Error {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        ErrorRepr::serialize(self, s)
    }
}

impl<'de> Deserialize<'de> for Error {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        ErrorRepr::deserialize(d)
    }
}

/// The serialised form of [`Joint`]; limits are `None` when unbounded.
#[derive(serde::Serialize, serde::Deserialize)]
#[serde(rename = "Joint", deny_unknown_fields)]
#[serde(bound(serialize = "T: Serialize", deserialize = "T: Deserialize<'de>"))]
struct JointRepr<'a, T> {
    name: &'a str,
    kind: JointKind,
    screw: Vec6<T>,
    lower: Option<T>,
    upper: Option<T>,
}

/// A limit as written: `None` for the unbounded side's infinity; an error for NaN or the
/// other side's infinity (which `null` could not bring back).
fn limit_out<T: Real, E: ser::Error>(x: T, unbounded: T) -> Result<Option<T>, E> {
    if x == unbounded {
        Ok(None)
    } else if x.is_finite() {
        Ok(Some(x))
    } else {
        Err(E::custom(
            "joint limit is NaN or infinite on the wrong side",
        ))
    }
}

impl<T: Real + Serialize> Serialize for Joint<T> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        JointRepr {
            name: self.name,
            kind: self.kind,
            screw: self.screw,
            lower: limit_out(self.lower, T::neg_infinity())?,
            upper: limit_out(self.upper, T::infinity())?,
        }
        .serialize(s)
    }
}

impl<T: Real + Deserialize<'static>> Deserialize<'static> for Joint<T> {
    fn deserialize<D: Deserializer<'static>>(d: D) -> Result<Self, D::Error> {
        let r = JointRepr::<'static, T>::deserialize(d)?;
        let j = Joint::new(
            r.name,
            r.kind,
            r.screw.0,
            r.lower.unwrap_or(T::neg_infinity()),
            r.upper.unwrap_or(T::infinity()),
        )
        .prepared();
        ChainView {
            joints: core::slice::from_ref(&j),
            home: Transform::identity(),
        }
        .check()
        .map_err(de::Error::custom)?;
        Ok(j)
    }
}

/// The joints of a chain, written as a tuple of N.
struct Joints<T, const N: usize>([Joint<T>; N]);

impl<T: Real + Serialize, const N: usize> Serialize for Joints<T, N> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        serialize_tuple(s, &self.0)
    }
}

impl<T: Real + Deserialize<'static>, const N: usize> Deserialize<'static> for Joints<T, N> {
    fn deserialize<D: Deserializer<'static>>(d: D) -> Result<Self, D::Error> {
        deserialize_array(d).map(Joints)
    }
}

/// The serialised form of [`Chain`].
#[derive(serde::Serialize, serde::Deserialize)]
#[serde(rename = "Chain", deny_unknown_fields)]
#[serde(bound(
    serialize = "T: Real + Serialize",
    deserialize = "T: Real + Deserialize<'static>, 'de: 'static"
))]
struct ChainRepr<'a, T, const N: usize> {
    base: &'a str,
    tip: &'a str,
    joints: Joints<T, N>,
    home: Transform<T>,
}

impl<T: Real + Serialize, const N: usize> Serialize for Chain<T, N> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        ChainRepr {
            base: self.base,
            tip: self.tip,
            joints: Joints(self.joints),
            home: self.home,
        }
        .serialize(s)
    }
}

impl<T: Real + Deserialize<'static>, const N: usize> Deserialize<'static> for Chain<T, N> {
    fn deserialize<D: Deserializer<'static>>(d: D) -> Result<Self, D::Error> {
        let r = ChainRepr::<'static, T, N>::deserialize(d)?;
        let c = Chain::new(r.base, r.tip, r.joints.0, r.home);
        c.as_ref().check().map_err(de::Error::custom)?;
        Ok(c)
    }
}

/// A run-time chain view, written like a [`Chain`] without the link names:
/// `{ "joints": [...], "home": Transform }` (write only: a view borrows its joints).
impl<T: Real + Serialize> Serialize for ChainView<'_, T> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeStruct;
        let mut st = s.serialize_struct("ChainView", 2)?;
        st.serialize_field("joints", &JointSlice(self.joints))?;
        st.serialize_field("home", &self.home)?;
        st.end()
    }
}

/// The joints of a view: a sequence of run-time length.
struct JointSlice<'a, T>(&'a [Joint<T>]);

impl<T: Real + Serialize> Serialize for JointSlice<'_, T> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_seq(self.0)
    }
}

/// The serialised form of [`UncertainPose`].
#[derive(serde::Serialize, serde::Deserialize)]
// No deny_unknown_fields: both fields are required, so a misspelling is still an error,
// and a record carrying more (an `eval` result's `thetas_clipped`) reads as it is.
#[serde(rename = "UncertainPose")]
#[serde(bound(
    serialize = "T: Real + Serialize",
    deserialize = "T: Real + Deserialize<'de>"
))]
struct UncertainPoseRepr<T> {
    pose: Transform<T>,
    cov: Mat6<T>,
}

impl<T: Real + Serialize> Serialize for UncertainPose<T> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        UncertainPoseRepr {
            pose: self.pose,
            cov: self.cov,
        }
        .serialize(s)
    }
}

impl<'de, T: Real + Deserialize<'de>> Deserialize<'de> for UncertainPose<T> {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let r = UncertainPoseRepr::<T>::deserialize(d)?;
        check_covariance(&r.cov).map_err(de::Error::custom)?;
        Ok(UncertainPose {
            pose: r.pose,
            cov: r.cov,
        })
    }
}
