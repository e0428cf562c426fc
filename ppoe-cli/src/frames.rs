//! Joint frames for drawing: the frame of each moving joint's child link at the home pose
//! (`L_j = T_base←child_j`, computed from the URDF as `ppoe-build` computes the screw axes),
//! and the frames along the chain at given joint values,
//! `T_base←child_i(θ) = Exp(S₁θ₁)·…·Exp(Sᵢθᵢ)·L_i`.
//!
//! Shared with `build.rs` (through `#[path]`), which bakes the seed robot's home frames into
//! a `const` next to its table, so this file uses nothing but `ppoe-build` and `std`.

use ppoe_build::{RobotChain, Urdf};

/// A row-major 4×4 homogeneous transform.
pub type Mat4 = [[f64; 4]; 4];

fn mul4(a: &Mat4, b: &Mat4) -> Mat4 {
    let mut out = [[0.0; 4]; 4];
    for (i, row) in out.iter_mut().enumerate() {
        for (j, x) in row.iter_mut().enumerate() {
            *x = (0..4).map(|k| a[i][k] * b[k][j]).sum();
        }
    }
    out
}

const IDENTITY: Mat4 = [
    [1.0, 0.0, 0.0, 0.0],
    [0.0, 1.0, 0.0, 0.0],
    [0.0, 0.0, 1.0, 0.0],
    [0.0, 0.0, 0.0, 1.0],
];

/// The home frame `L_j = T_base←child_j` of every moving joint of `chain` (base to tip):
/// the product of the `<origin>` transforms from the base link down to the joint's child
/// link, accumulated from the link end as pytransform3d does. The joint's axis passes
/// through the origin of this frame.
pub fn joint_home_frames(urdf: &Urdf, chain: &RobotChain) -> Result<Vec<Mat4>, String> {
    let mut out = Vec::with_capacity(chain.joints.len());
    for cj in &chain.joints {
        let joint = urdf
            .joint(&cj.name)
            .ok_or_else(|| format!("joint '{}' is not in the URDF", cj.name))?;
        let mut t = joint.child2parent;
        let mut cur = joint.parent.as_str();
        let mut steps = 0;
        while cur != chain.base {
            let parent =
                urdf.joints.iter().find(|j| j.child == cur).ok_or_else(|| {
                    format!("link '{cur}' is not below the base '{}'", chain.base)
                })?;
            t = mul4(&parent.child2parent, &t);
            cur = parent.parent.as_str();
            steps += 1;
            if steps > urdf.joints.len() {
                return Err(format!("a cycle above link '{cur}'"));
            }
        }
        out.push(t);
    }
    Ok(out)
}

/// The identity transform (the base frame).
#[allow(dead_code)] // not used by build.rs
pub fn identity() -> Mat4 {
    IDENTITY
}
