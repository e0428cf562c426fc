//! A link's `<visual>` elements and the robot's named `<material>`s: what a picture of the
//! robot needs (kinematic tables ignore them).
//!
//! Read with the same parser, number rules and positions as the joints: `<origin xyz rpy>`
//! gives the same transform as a joint's origin, numbers are finite and separated by ASCII
//! whitespace. Geometry sizes must not be negative. A problem in one visual or material
//! is kept as that item's error instead of failing the whole URDF, so a robot whose
//! pictures are broken still has a table.

use super::{attribute, first_child, Parser};
use crate::error::{Error, ErrorKind, Position, Result};
use crate::math::Mat4;
use roxmltree::Node;

/// The shape of a `<visual>`'s `<geometry>`: its first child element.
#[derive(Clone, Debug, PartialEq)]
pub enum Geometry {
    /// `<box size="x y z">`: a box centred on the visual's origin.
    Box {
        /// The side lengths along x, y and z.
        size: [f64; 3],
    },
    /// `<cylinder radius length>`: a cylinder about the visual's z axis, centred on its
    /// origin.
    Cylinder {
        /// The radius.
        radius: f64,
        /// The length along z.
        length: f64,
    },
    /// `<sphere radius>`, centred on the visual's origin.
    Sphere {
        /// The radius.
        radius: f64,
    },
    /// `<mesh filename scale>`: a mesh file (loading it is the caller's business).
    Mesh {
        /// The file name as written (`package://…`, `file://…` or a relative path; empty
        /// when the attribute is absent).
        filename: String,
        /// The scale along x, y and z (`1 1 1` when absent).
        scale: [f64; 3],
    },
    /// A `<geometry>` without a child element.
    Empty,
    /// A child element URDF does not define (its local name).
    Other {
        /// The element's local name.
        element: String,
    },
}

/// A `<material>`: a name, a colour, or both.
#[derive(Clone, Debug, PartialEq)]
pub struct Material {
    /// The `name` attribute, if any.
    pub name: Option<String>,
    /// `<color rgba>`: red, green, blue and alpha as written (finite; URDF means them in
    /// [0, 1], clamping is the caller's choice), if given.
    pub rgba: Option<[f64; 4]>,
}

/// One `<visual>` of a link.
#[derive(Clone, Debug, PartialEq)]
pub struct Visual {
    /// `T_link←visual`, from `<origin xyz rpy>` exactly as a joint's origin is read (the
    /// identity where absent).
    pub origin: Mat4,
    /// The shape; `None` when the visual has no `<geometry>`.
    pub geometry: Option<Geometry>,
    /// The visual's own `<material>`, if any; a material given only by name is one of
    /// [`Urdf::materials`](super::Urdf::materials).
    pub material: Option<Material>,
    /// Where the `<visual>` element starts.
    pub position: Option<Position>,
}

impl<'input> Parser<'_, 'input> {
    /// The `<visual>` children of the `<link>` named `link`.
    pub(super) fn visuals(&self, node: Node<'_, 'input>, link: &str) -> Vec<Result<Visual>> {
        let what = format!("link '{link}'");
        node.children()
            .filter(|c| c.is_element() && c.tag_name().name() == "visual")
            .map(|v| self.visual(v, &what))
            .collect()
    }

    /// The `<material>` children of the root.
    pub(super) fn materials(&self, root: Node<'_, 'input>) -> Vec<Result<Material>> {
        root.children()
            .filter(|c| c.is_element() && c.tag_name().name() == "material")
            .map(|m| self.material(m, "<material>"))
            .collect()
    }

    fn visual(&self, node: Node<'_, 'input>, what: &str) -> Result<Visual> {
        let geometry = match first_child(node, "geometry") {
            Some(g) => Some(self.geometry(g, what)?),
            None => None,
        };
        let material = match first_child(node, "material") {
            Some(m) => Some(self.material(m, what)?),
            None => None,
        };
        Ok(Visual {
            origin: self.origin(node, what)?,
            geometry,
            material,
            position: self.node_pos(node),
        })
    }

    fn material(&self, node: Node<'_, 'input>, what: &str) -> Result<Material> {
        let rgba = match first_child(node, "color") {
            Some(c) => self.numbers::<4>(c, "rgba", what)?,
            None => None,
        };
        Ok(Material {
            name: attribute(node, "name").map(|a| a.value().to_string()),
            rgba,
        })
    }

    fn geometry(&self, node: Node<'_, 'input>, what: &str) -> Result<Geometry> {
        let Some(g) = node.children().find(|c| c.is_element()) else {
            return Ok(Geometry::Empty);
        };
        let size = |name: &str| -> Result<f64> {
            let [x] = self.size::<1>(g, name, what)?;
            Ok(x)
        };
        Ok(match g.tag_name().name() {
            "box" => Geometry::Box {
                size: self.size::<3>(g, "size", what)?,
            },
            "cylinder" => Geometry::Cylinder {
                radius: size("radius")?,
                length: size("length")?,
            },
            "sphere" => Geometry::Sphere {
                radius: size("radius")?,
            },
            "mesh" => Geometry::Mesh {
                filename: attribute(g, "filename").map_or(String::new(), |a| a.value().into()),
                scale: self.numbers::<3>(g, "scale", what)?.unwrap_or([1.0; 3]),
            },
            other => Geometry::Other {
                element: other.to_string(),
            },
        })
    }

    /// A required attribute of `N` finite numbers, none negative.
    fn size<const N: usize>(
        &self,
        node: Node<'_, 'input>,
        name: &str,
        what: &str,
    ) -> Result<[f64; N]> {
        let element = node.tag_name().name();
        let Some(v) = self.numbers::<N>(node, name, what)? else {
            return Err(Error::new(
                ErrorKind::MissingAttribute,
                format!("{what}: <{element}> has no attribute '{name}'"),
            )
            .at(self.node_pos(node)));
        };
        if v.iter().any(|&x| x < 0.0) {
            let pos = attribute(node, name).and_then(|a| self.value_pos(&a));
            return Err(Error::new(
                ErrorKind::InvalidNumber,
                format!("{what}: <{element} {name}>: a size cannot be negative"),
            )
            .at(pos));
        }
        Ok(v)
    }
}
