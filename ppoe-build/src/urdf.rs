//! URDF parsing: the links and joints of a `<robot>`, with each joint's child-to-parent
//! transform, axis and limits computed as pytransform3d's `UrdfTransformManager` does.
//!
//! What is read (everything else — `<collision>`, `<inertial>`, `<transmission>`,
//! `<gazebo>`, `<dynamics>`, `<safety_controller>`, comments, processing instructions — is
//! ignored):
//!
//! * the root element must be `<robot name="…">`;
//! * its direct `<link name>` children, then its direct `<joint name type>` children with
//!   their first `<parent link>`, `<child link>`, `<origin xyz rpy>`, `<axis xyz>`,
//!   `<limit lower upper>` and `<mimic joint multiplier offset>` children;
//! * for the pictures, each link's `<visual>` children and the robot's top-level
//!   `<material>`s ([`Visual`], [`Material`]). A malformed visual never fails the parse (a
//!   table does not depend on it): it is kept as an error in [`Link::visuals`], for the
//!   tools that draw it to report.
//!
//! Element names are matched on their local name, so XML namespaces are ignored (prefixes
//! must still be declared: roxmltree, like any conforming parser, rejects undeclared ones).
//! Attributes are looked up without a namespace.
//!
//! Lenient where pytransform3d is lenient:
//! * `<origin>` may be absent, and so may either of its attributes (zero);
//! * `<axis>` may be absent (axis (1, 0, 0)) and need not be a unit vector (normalised by
//!   division by its norm);
//! * `<limit>` may be absent, and so may `lower` (−∞) or `upper` (+∞) — also on continuous
//!   joints; fixed joints get (0, 0);
//! * numbers in `xyz`/`rpy` may be separated by any ASCII whitespace (spaces, tabs,
//!   newlines, also as character references), with leading and trailing whitespace; a limit
//!   may have surrounding whitespace.
//!
//! Strict elsewhere: exactly three numbers per vector; NaN or ±∞ in `xyz`, `rpy` or an axis;
//! NaN in a limit (±∞ is accepted there: it is what a missing limit means); duplicate link or
//! joint names; a joint whose parent or child link does not exist; unknown joint types; a
//! link with two parents; a cycle. `planar` and `floating` joints are accepted here and
//! rejected only if they lie on a chain that is extracted (pytransform3d rejects them
//! anywhere). Limits that admit no finite position (`lower > upper`, `lower = +∞`,
//! `upper = −∞`) are kept as written here and rejected ([`ErrorKind::InvalidLimits`]) only
//! for the moving joints of an extracted chain, like a zero axis (pytransform3d does not
//! check them at all and clips every value to `upper`).
//!
//! Finite but huge numbers (`1e300`) are accepted; if the products along a chain overflow,
//! extracting that chain is a [`ErrorKind::NonFinite`] error naming the joint.
//!
//! A DTD is allowed, but its internal entities may expand the document by at most 1 MiB in
//! total (every reference charged its entity's fully expanded size, checked before the XML
//! parser runs): a small URDF whose entities would expand to gigabytes is an
//! [`ErrorKind::Xml`] error, not an exhausted memory.
//!
//! Nothing here recurses: the tree checks walk the parent links with explicit loops, so a
//! serial chain of 10⁴ or more links (or a cycle through them) is no problem.

use crate::error::{Error, ErrorKind, Position, Result};
use crate::math;
use roxmltree::{Attribute, Document, Node};
use std::collections::HashMap;

mod tree;
mod visual;

pub use tree::Tree;
pub use visual::{Geometry, Material, Visual};

/// A joint type as written in the URDF.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum JointType {
    /// `revolute`: rotation with limits.
    Revolute,
    /// `continuous`: rotation without limits (limits may still be given).
    Continuous,
    /// `prismatic`: translation.
    Prismatic,
    /// `fixed`: no motion; folded into the neighbouring transforms.
    Fixed,
    /// `planar`: not supported on a chain.
    Planar,
    /// `floating`: not supported on a chain.
    Floating,
}

impl JointType {
    /// The URDF spelling.
    pub fn as_str(self) -> &'static str {
        match self {
            JointType::Revolute => "revolute",
            JointType::Continuous => "continuous",
            JointType::Prismatic => "prismatic",
            JointType::Fixed => "fixed",
            JointType::Planar => "planar",
            JointType::Floating => "floating",
        }
    }

    /// `true` for revolute, continuous and prismatic joints.
    pub fn is_moving(self) -> bool {
        matches!(
            self,
            JointType::Revolute | JointType::Continuous | JointType::Prismatic
        )
    }
}

/// A `<link>`.
#[derive(Clone, Debug, PartialEq)]
pub struct Link {
    /// The link's name.
    pub name: String,
    /// Where the `<link>` element starts.
    pub position: Option<Position>,
    /// Its `<visual>` children in document order, each as read or the error that makes it
    /// unusable (malformed numbers, a negative size).
    pub visuals: Vec<Result<Visual>>,
}

/// A `<joint>` with its home-pose data.
#[derive(Clone, Debug, PartialEq)]
pub struct Joint {
    /// The joint's name.
    pub name: String,
    /// Its type.
    pub joint_type: JointType,
    /// The parent link.
    pub parent: String,
    /// The child link.
    pub child: String,
    /// The child-to-parent transform `[[Rz(y)·Ry(p)·Rx(r), xyz], [0, 1]]` of `<origin>`
    /// (row-major 4×4).
    pub child2parent: [[f64; 4]; 4],
    /// The axis in the child frame, normalised (`(1, 0, 0)` if absent; a zero axis stays
    /// zero and is rejected when the joint is used as a moving joint of a chain).
    pub axis: [f64; 3],
    /// Lower limit: `lower` of `<limit>`, −∞ if absent; 0 for fixed joints.
    pub lower: f64,
    /// Upper limit: `upper` of `<limit>`, +∞ if absent; 0 for fixed joints.
    pub upper: f64,
    /// The joint's `<mimic>` element, if any: its value follows another joint's.
    pub mimic: Option<Mimic>,
    /// Where the `<joint>` element starts.
    pub position: Option<Position>,
    /// Where the `xyz` value of `<axis>` starts (if given).
    pub axis_position: Option<Position>,
    /// Where the `link` value of `<child>` starts.
    pub child_position: Option<Position>,
    /// Where the `<mimic>` element starts (if any).
    pub mimic_position: Option<Position>,
    /// Where the `<limit>` element starts (if any).
    pub limit_position: Option<Position>,
}

/// A `<mimic joint multiplier offset>` element: the joint's value is
/// `multiplier·θ_master + offset`.
///
/// Read for every joint when the file is loaded (a missing `joint`, a malformed or
/// non-finite number is an error there, as everywhere in the file); whether the master
/// exists, moves and is not itself in a mimic cycle is checked only for the joints of an
/// extracted chain ([`Urdf::chain`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Mimic {
    /// The master joint's name (`joint`, required).
    pub joint: String,
    /// `multiplier`, 1 if absent (URDF's default).
    pub multiplier: f64,
    /// `offset`, 0 if absent (URDF's default; radians or metres).
    pub offset: f64,
}

/// A parsed URDF: the robot's links and joints in document order.
#[derive(Clone, Debug, PartialEq)]
pub struct Urdf {
    /// The robot's name.
    pub name: String,
    /// The links in document order.
    pub links: Vec<Link>,
    /// The joints in document order.
    pub joints: Vec<Joint>,
    /// The named materials declared at the top level, in document order, each as read or
    /// the error that makes it unusable (a malformed colour).
    pub materials: Vec<Result<Material>>,
}

impl Urdf {
    /// Parses URDF text. Never panics; every problem is an [`Error`].
    pub fn parse(text: &str) -> Result<Self> {
        let text = text.strip_prefix('\u{feff}').unwrap_or(text);
        crate::dtd::check(text, |offset| end_position(&text[..offset]))?;
        let options = roxmltree::ParsingOptions {
            allow_dtd: true,
            ..roxmltree::ParsingOptions::default()
        };
        let doc = Document::parse_with_options(text, options).map_err(|e| {
            let position = match e {
                // roxmltree reports these at 1:1; the problem is at the end of the input.
                roxmltree::Error::UnexpectedEndOfStream | roxmltree::Error::UnclosedRootNode => {
                    end_position(text)
                }
                _ => Position {
                    line: e.pos().row,
                    column: e.pos().col,
                },
            };
            Error::new(ErrorKind::Xml, format!("malformed XML: {e}")).at(Some(position))
        })?;
        Parser {
            doc: &doc,
            lines: LineIndex::new(doc.input_text()),
        }
        .robot()
    }

    /// Parses URDF bytes (must be UTF-8, with or without a byte-order mark).
    pub fn parse_bytes(bytes: &[u8]) -> Result<Self> {
        match std::str::from_utf8(bytes) {
            Ok(text) => Self::parse(text),
            Err(e) => {
                // The prefix is valid UTF-8 by construction.
                let prefix = std::str::from_utf8(&bytes[..e.valid_up_to()]).unwrap_or("");
                let position = end_position(prefix);
                Err(Error::new(
                    ErrorKind::Xml,
                    format!(
                        "malformed XML: the file is not UTF-8 (invalid byte at offset {})",
                        e.valid_up_to()
                    ),
                )
                .at(Some(position)))
            }
        }
    }

    /// The link named `name`.
    pub fn link(&self, name: &str) -> Option<&Link> {
        self.links.iter().find(|l| l.name == name)
    }

    /// The joint named `name`.
    pub fn joint(&self, name: &str) -> Option<&Joint> {
        self.joints.iter().find(|j| j.name == name)
    }
}

/// The position just after the last character of `text`.
fn end_position(text: &str) -> Position {
    let line = text.matches('\n').count() + 1;
    let column = text.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    Position {
        line: u32::try_from(line).unwrap_or(u32::MAX),
        column: u32::try_from(column).unwrap_or(u32::MAX),
    }
}

struct Parser<'a, 'input> {
    doc: &'a Document<'input>,
    lines: LineIndex<'input>,
}

/// Byte offset → line and column, as roxmltree's `text_pos_at` counts them (lines split at
/// `\n`, columns in characters, both from 1), without rescanning the text from its start
/// for every position (which made parsing quadratic in the file size).
struct LineIndex<'input> {
    text: &'input str,
    /// Byte offset of the start of each line.
    starts: Vec<usize>,
}

impl<'input> LineIndex<'input> {
    fn new(text: &'input str) -> Self {
        let mut starts = vec![0];
        starts.extend(
            text.bytes()
                .enumerate()
                .filter(|&(_, b)| b == b'\n')
                .map(|(i, _)| i + 1),
        );
        Self { text, starts }
    }

    fn position(&self, offset: usize) -> Position {
        let mut offset = offset.min(self.text.len());
        while !self.text.is_char_boundary(offset) {
            offset -= 1;
        }
        // The number of line starts at or before `offset` (≥ 1: the first is 0).
        let line = self.starts.partition_point(|&s| s <= offset);
        let start = self.starts[line - 1];
        let column = self.text[start..offset].chars().count() + 1;
        Position {
            line: u32::try_from(line).unwrap_or(u32::MAX),
            column: u32::try_from(column).unwrap_or(u32::MAX),
        }
    }
}

/// `" at line:column"` for a message, or nothing.
fn at(position: Option<Position>) -> String {
    position.map_or(String::new(), |p| format!(" at {p}"))
}

/// Shortens an attribute value for a message.
fn shown(value: &str) -> String {
    const MAX: usize = 60;
    if value.chars().count() <= MAX {
        format!("{value:?}")
    } else {
        let head: String = value.chars().take(MAX).collect();
        format!("{head:?}…")
    }
}

fn attribute<'a, 'input>(node: Node<'a, 'input>, name: &str) -> Option<Attribute<'a, 'input>> {
    node.attributes()
        .find(|a| a.namespace().is_none() && a.name() == name)
}

fn first_child<'a, 'input>(node: Node<'a, 'input>, name: &str) -> Option<Node<'a, 'input>> {
    node.children()
        .find(|c| c.is_element() && c.tag_name().name() == name)
}

impl<'input> Parser<'_, 'input> {
    fn pos(&self, offset: usize) -> Option<Position> {
        Some(self.lines.position(offset))
    }

    fn node_pos(&self, node: Node<'_, 'input>) -> Option<Position> {
        self.pos(node.range().start)
    }

    fn value_pos(&self, attr: &Attribute<'_, 'input>) -> Option<Position> {
        self.pos(attr.range_value().start)
    }

    /// A required, non-empty attribute.
    fn required(&self, node: Node<'_, 'input>, name: &str, what: &str) -> Result<String> {
        match attribute(node, name) {
            Some(a) if !a.value().is_empty() => Ok(a.value().to_string()),
            Some(a) => Err(Error::new(
                ErrorKind::MissingAttribute,
                format!("{what}: attribute '{name}' is empty"),
            )
            .at(self.value_pos(&a))),
            None => Err(Error::new(
                ErrorKind::MissingAttribute,
                format!(
                    "{what}: <{}> has no attribute '{name}'",
                    node.tag_name().name()
                ),
            )
            .at(self.node_pos(node))),
        }
    }

    fn robot(&self) -> Result<Urdf> {
        let root = self.doc.root_element();
        if root.tag_name().name() != "robot" {
            return Err(Error::new(
                ErrorKind::NotARobot,
                format!(
                    "the root element is <{}>, not <robot>: not a URDF file",
                    root.tag_name().name()
                ),
            )
            .at(self.node_pos(root)));
        }
        let name = self.required(root, "name", "<robot>")?;
        let (links, link_index) = self.links(root)?;
        let joints = self.joints(root, &link_index)?;
        check_tree(&links, &joints)?;
        let materials = self.materials(root);
        Ok(Urdf {
            name,
            links,
            joints,
            materials,
        })
    }

    /// The `<link>` children of the root, in document order, and the index of each name.
    fn links(&self, root: Node<'_, 'input>) -> Result<(Vec<Link>, HashMap<String, usize>)> {
        let mut links: Vec<Link> = Vec::new();
        let mut link_index: HashMap<String, usize> = HashMap::new();
        for node in root
            .children()
            .filter(|c| c.is_element() && c.tag_name().name() == "link")
        {
            let link_name = self.required(node, "name", "<link>")?;
            let position = self.node_pos(node);
            if let Some(&first) = link_index.get(&link_name) {
                return Err(Error::new(
                    ErrorKind::DuplicateName,
                    format!(
                        "link '{link_name}' is defined twice (first{})",
                        at(links[first].position)
                    ),
                )
                .at(position));
            }
            link_index.insert(link_name.clone(), links.len());
            let visuals = self.visuals(node, &link_name);
            links.push(Link {
                name: link_name,
                position,
                visuals,
            });
        }
        Ok((links, link_index))
    }

    /// The `<joint>` children of the root, in document order.
    fn joints(
        &self,
        root: Node<'_, 'input>,
        link_index: &HashMap<String, usize>,
    ) -> Result<Vec<Joint>> {
        let mut joints: Vec<Joint> = Vec::new();
        let mut joint_index: HashMap<String, usize> = HashMap::new();
        for node in root
            .children()
            .filter(|c| c.is_element() && c.tag_name().name() == "joint")
        {
            let joint = self.joint(node, link_index)?;
            if let Some(&first) = joint_index.get(&joint.name) {
                return Err(Error::new(
                    ErrorKind::DuplicateName,
                    format!(
                        "joint '{}' is defined twice (first{})",
                        joint.name,
                        at(joints[first].position)
                    ),
                )
                .at(joint.position));
            }
            joint_index.insert(joint.name.clone(), joints.len());
            joints.push(joint);
        }
        Ok(joints)
    }

    fn joint(&self, node: Node<'_, 'input>, links: &HashMap<String, usize>) -> Result<Joint> {
        let position = self.node_pos(node);
        let name = self.required(node, "name", "<joint>")?;
        let what = format!("joint '{name}'");
        let joint_type = self.joint_type(node, &what)?;
        let (parent, _) = self.link_ref(node, "parent", &what, links)?;
        let (child, child_position) = self.link_ref(node, "child", &what, links)?;
        let child2parent = self.origin(node, &what)?;
        let (axis, axis_position) = self.axis(node, joint_type, &what)?;
        let (lower, upper, limit_position) = self.limits(node, joint_type, &what)?;
        let mimic_node = first_child(node, "mimic");
        let mimic = match mimic_node {
            Some(m) => Some(self.mimic(m, &what)?),
            None => None,
        };
        Ok(Joint {
            name,
            joint_type,
            parent,
            child,
            child2parent,
            axis,
            lower,
            upper,
            mimic,
            position,
            axis_position,
            child_position,
            mimic_position: mimic_node.and_then(|m| self.node_pos(m)),
            limit_position,
        })
    }

    /// The `type` attribute: one of URDF's six joint types.
    fn joint_type(&self, node: Node<'_, 'input>, what: &str) -> Result<JointType> {
        let type_str = self.required(node, "type", what)?;
        Ok(match type_str.as_str() {
            "revolute" => JointType::Revolute,
            "continuous" => JointType::Continuous,
            "prismatic" => JointType::Prismatic,
            "fixed" => JointType::Fixed,
            "planar" => JointType::Planar,
            "floating" => JointType::Floating,
            other => {
                let attr = attribute(node, "type");
                return Err(Error::new(
                    ErrorKind::UnsupportedJointType,
                    format!(
                        "{what}: type {} is not a URDF joint type (revolute, continuous, \
                         prismatic, fixed, planar, floating)",
                        shown(other)
                    ),
                )
                .at(attr
                    .and_then(|a| self.value_pos(&a))
                    .or(self.node_pos(node))));
            }
        })
    }

    /// The child-to-parent transform of `<origin xyz rpy>` (identity where absent).
    fn origin(&self, node: Node<'_, 'input>, what: &str) -> Result<math::Mat4> {
        let (xyz, rpy) = match first_child(node, "origin") {
            Some(origin) => (
                self.vec3(origin, "xyz", what)?.unwrap_or([0.0; 3]),
                self.vec3(origin, "rpy", what)?,
            ),
            None => ([0.0; 3], None),
        };
        // As pytransform3d: the Euler product is evaluated whenever `rpy` is given (even
        // "0 0 0", which only affects the sign of zeros), the identity otherwise.
        let rotation = match rpy {
            Some(rpy) => math::rotation_from_rpy(rpy),
            None => [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
        };
        Ok(math::transform_from(&rotation, xyz))
    }

    /// The normalised `<axis xyz>` ((1, 0, 0) where absent) and where its value starts.
    fn axis(
        &self,
        node: Node<'_, 'input>,
        joint_type: JointType,
        what: &str,
    ) -> Result<([f64; 3], Option<Position>)> {
        // pytransform3d reads the axis of moving joints only; a fixed joint's axis is
        // ignored (it may even be zero).
        if joint_type != JointType::Fixed {
            if let Some(axis_node) = first_child(node, "axis") {
                if let Some(v) = self.vec3(axis_node, "xyz", what)? {
                    let at = attribute(axis_node, "xyz").and_then(|a| self.value_pos(&a));
                    return Ok((math::normalized(v), at));
                }
            }
        }
        Ok(([1.0, 0.0, 0.0], None))
    }

    /// `<limit lower upper>` (−∞/+∞ where absent, (0, 0) for fixed joints) and where the
    /// element starts.
    fn limits(
        &self,
        node: Node<'_, 'input>,
        joint_type: JointType,
        what: &str,
    ) -> Result<(f64, f64, Option<Position>)> {
        if joint_type == JointType::Fixed {
            return Ok((0.0, 0.0, None));
        }
        let Some(limit) = first_child(node, "limit") else {
            return Ok((f64::NEG_INFINITY, f64::INFINITY, None));
        };
        let lower = self
            .limit(limit, "lower", what)?
            .unwrap_or(f64::NEG_INFINITY);
        let upper = self.limit(limit, "upper", what)?.unwrap_or(f64::INFINITY);
        Ok((lower, upper, self.node_pos(limit)))
    }

    /// `<parent link>` / `<child link>`: present, non-empty, naming an existing link.
    fn link_ref(
        &self,
        node: Node<'_, 'input>,
        element: &str,
        what: &str,
        links: &HashMap<String, usize>,
    ) -> Result<(String, Option<Position>)> {
        let Some(el) = first_child(node, element) else {
            return Err(Error::new(
                ErrorKind::MissingAttribute,
                format!("{what}: no <{element}> element"),
            )
            .at(self.node_pos(node)));
        };
        let link = self.required(el, "link", what)?;
        let pos = attribute(el, "link").and_then(|a| self.value_pos(&a));
        if !links.contains_key(&link) {
            return Err(Error::new(
                ErrorKind::UnknownLink,
                format!("{what}: <{element} link={}>: no such link", shown(&link)),
            )
            .at(pos));
        }
        Ok((link, pos))
    }

    /// An optional attribute holding exactly three finite numbers separated by whitespace.
    fn vec3(&self, node: Node<'_, 'input>, name: &str, what: &str) -> Result<Option<[f64; 3]>> {
        self.numbers::<3>(node, name, what)
    }

    /// An optional attribute holding exactly `N` finite numbers separated by whitespace.
    fn numbers<const N: usize>(
        &self,
        node: Node<'_, 'input>,
        name: &str,
        what: &str,
    ) -> Result<Option<[f64; N]>> {
        let Some(attr) = attribute(node, name) else {
            return Ok(None);
        };
        let element = node.tag_name().name();
        let value = attr.value();
        let pos = self.value_pos(&attr);
        let context = || format!("{what}: <{element} {name}={}>", shown(value));
        let mut out = [0.0; N];
        let mut count = 0;
        for token in value.split_ascii_whitespace() {
            let x: f64 = token.parse().map_err(|_| {
                Error::new(
                    ErrorKind::InvalidNumber,
                    format!("{}: {} is not a number", context(), shown(token)),
                )
                .at(pos)
            })?;
            if count < N {
                out[count] = x;
            }
            count += 1;
        }
        if count != N {
            return Err(Error::new(
                ErrorKind::InvalidNumber,
                format!("{}: expected {N} numbers, found {count}", context()),
            )
            .at(pos));
        }
        if let Some(i) = out.iter().position(|x| !x.is_finite()) {
            return Err(Error::new(
                ErrorKind::NonFinite,
                format!(
                    "{}: {} is {}; {} must be finite",
                    context(),
                    if N == 1 {
                        "the value".to_string()
                    } else {
                        format!("component {}", i + 1)
                    },
                    out[i],
                    if element == "mimic" {
                        "a mimic coupling"
                    } else {
                        "geometry"
                    }
                ),
            )
            .at(pos));
        }
        Ok(Some(out))
    }

    /// `<mimic joint multiplier offset>`: `joint` required, the numbers finite (1 and 0
    /// where absent).
    fn mimic(&self, node: Node<'_, 'input>, what: &str) -> Result<Mimic> {
        let joint = self.required(node, "joint", what)?;
        let [multiplier] = self
            .numbers::<1>(node, "multiplier", what)?
            .unwrap_or([1.0]);
        let [offset] = self.numbers::<1>(node, "offset", what)?.unwrap_or([0.0]);
        Ok(Mimic {
            joint,
            multiplier,
            offset,
        })
    }

    /// An optional limit: one number, ±∞ allowed, NaN not.
    fn limit(&self, node: Node<'_, 'input>, name: &str, what: &str) -> Result<Option<f64>> {
        let Some(attr) = attribute(node, name) else {
            return Ok(None);
        };
        let value = attr.value();
        let pos = self.value_pos(&attr);
        let x: f64 = value
            .trim_matches(|c: char| c.is_ascii_whitespace())
            .parse()
            .map_err(|_| {
                Error::new(
                    ErrorKind::InvalidNumber,
                    format!("{what}: <limit {name}={}>: not a number", shown(value)),
                )
                .at(pos)
            })?;
        if x.is_nan() {
            return Err(Error::new(
                ErrorKind::NonFinite,
                format!(
                    "{what}: <limit {name}={}>: NaN is not a limit",
                    shown(value)
                ),
            )
            .at(pos));
        }
        Ok(Some(x))
    }
}

/// Every link has at most one parent joint, and following parents never comes back.
fn check_tree(links: &[Link], joints: &[Joint]) -> Result<()> {
    let mut parent_joint: HashMap<&str, usize> = HashMap::new();
    for (j, joint) in joints.iter().enumerate() {
        if joint.parent == joint.child {
            return Err(Error::new(
                ErrorKind::Cycle,
                format!(
                    "joint '{}': link '{}' is its own parent",
                    joint.name, joint.child
                ),
            )
            .at(joint.child_position.or(joint.position)));
        }
        if let Some(&first) = parent_joint.get(joint.child.as_str()) {
            return Err(Error::new(
                ErrorKind::MultipleParents,
                format!(
                    "link '{}' has two parents: joint '{}' (parent link '{}') and joint '{}' \
                     (parent link '{}')",
                    joint.child, joints[first].name, joints[first].parent, joint.name, joint.parent
                ),
            )
            .at(joint.child_position.or(joint.position)));
        }
        parent_joint.insert(joint.child.as_str(), j);
    }
    // 0 = unvisited, 1 = on the current walk, 2 = known to reach a root.
    let mut state: HashMap<&str, u8> = HashMap::new();
    for link in links {
        let mut walk: Vec<&str> = Vec::new();
        let mut cur = link.name.as_str();
        loop {
            match state.get(cur).copied().unwrap_or(0) {
                2 => break,
                1 => return Err(cycle_error(&walk, cur, &parent_joint, joints)),
                _ => {}
            }
            state.insert(cur, 1);
            walk.push(cur);
            match parent_joint.get(cur) {
                Some(&j) => cur = joints[j].parent.as_str(),
                None => break,
            }
        }
        for l in walk {
            state.insert(l, 2);
        }
    }
    Ok(())
}

/// The error for a cycle found by [`check_tree`]: `walk` reached `cur` a second time.
fn cycle_error(
    walk: &[&str],
    cur: &str,
    parent_joint: &HashMap<&str, usize>,
    joints: &[Joint],
) -> Error {
    let start = walk.iter().position(|l| *l == cur).unwrap_or(0);
    let mut names: Vec<&str> = walk[start..].to_vec();
    names.push(cur);
    // A long cycle is shown by its first and last links.
    const SHOWN: usize = 6;
    let more = format!("… ({} more links)", names.len().saturating_sub(2 * SHOWN));
    if names.len() > 2 * SHOWN + 1 {
        let tail = names.split_off(names.len() - SHOWN);
        names.truncate(SHOWN);
        names.push(&more);
        names.extend(tail);
    }
    let joint = parent_joint.get(cur).map(|&j| &joints[j]);
    Error::new(
        ErrorKind::Cycle,
        format!(
            "the links form a cycle (each link's parent is the next): {}",
            names.join(" → ")
        ),
    )
    .at(joint.and_then(|j| j.child_position.or(j.position)))
}
