//! The link/joint tree of a parsed URDF, indexed both ways: each link's parent joint and
//! child joints, and the root links. Parsing checked that every link has at most one
//! parent and that there is no cycle, so every walk up the tree ends; nothing here
//! recurses, so trees of any depth are fine.

use super::{Joint, Link, Urdf};
use std::collections::HashMap;

/// The tree of a [`Urdf`], built once by [`Urdf::tree`].
#[derive(Clone, Debug)]
pub struct Tree<'a> {
    urdf: &'a Urdf,
    parent: HashMap<&'a str, &'a Joint>,
    children: HashMap<&'a str, Vec<&'a Joint>>,
}

impl Urdf {
    /// The link/joint tree, indexed for walks up and down.
    pub fn tree(&self) -> Tree<'_> {
        let mut parent = HashMap::new();
        let mut children: HashMap<&str, Vec<&Joint>> = HashMap::new();
        for j in &self.joints {
            parent.insert(j.child.as_str(), j);
            children.entry(j.parent.as_str()).or_default().push(j);
        }
        Tree {
            urdf: self,
            parent,
            children,
        }
    }
}

impl<'a> Tree<'a> {
    /// The links no joint has as its child, in document order.
    pub fn roots(&self) -> impl Iterator<Item = &'a Link> + '_ {
        self.urdf
            .links
            .iter()
            .filter(|l| !self.parent.contains_key(l.name.as_str()))
    }

    /// The joint whose child is `link` (`None` for a root or an unknown name).
    pub fn parent(&self, link: &str) -> Option<&'a Joint> {
        self.parent.get(link).copied()
    }

    /// The joints whose parent is `link`, in document order.
    pub fn children(&self, link: &str) -> &[&'a Joint] {
        self.children.get(link).map_or(&[], Vec::as_slice)
    }

    /// The joints from `link` up to `base`, the joint of `link` first: empty when `link` is
    /// `base`, `None` when `link` is not at or below `base`.
    pub fn joints_above(&self, link: &str, base: &str) -> Option<Vec<&'a Joint>> {
        let mut out = Vec::new();
        let mut cur = link;
        // One step per joint at most: the tree has no cycle, the bound makes that certain.
        for _ in 0..=self.urdf.joints.len() {
            if cur == base {
                return Some(out);
            }
            let j = self.parent(cur)?;
            out.push(j);
            cur = j.parent.as_str();
        }
        None
    }
}
