//! The seed example's robot, from a table generated at **build time** (`build.rs` runs
//! `ppoe-build` on `test_data/urdf/seed.urdf`, base `linkmount`, tip `tcp`): no URDF is
//! parsed at run time. Also the seed's joint values and covariances (those of
//! pytransform3d's probabilistic forward kinematics example).

use crate::visuals::Visuals;
use ppoe::Mat6;

include!(concat!(env!("OUT_DIR"), "/seed_table.rs"));
include!(concat!(env!("OUT_DIR"), "/seed_frames.rs"));

/// The seed robot with its visual geometry (blue, orange and black cylinders, as the seed
/// example draws it): `test_data/urdf/seed_visuals.urdf`, same chain as `seed.urdf`.
pub const VISUALS_URDF: &str = include_str!("../assets/seed_visuals.urdf");

/// The seed robot's visuals, for the demo's pictures.
///
/// # Errors
/// Only if the embedded file were malformed (a test parses it).
pub fn visuals() -> anyhow::Result<Visuals> {
    let urdf = ppoe_build::Urdf::parse(VISUALS_URDF)?;
    let names: Vec<&str> = SEED.joints.iter().map(|j| j.name).collect();
    let (v, notices) = Visuals::from_urdf(&urdf, SEED.base, &names, None)?;
    anyhow::ensure!(notices.is_empty(), "seed visuals: {}", notices.join("; "));
    Ok(v)
}

/// The seed table as a host-side chain (the values it holds, its joints' home frames), for
/// folding a calibration into it at run time (`demo --noise`).
pub fn robot_chain() -> ppoe_build::RobotChain {
    ppoe_build::RobotChain {
        robot: "seed".to_string(),
        base: SEED.base.to_string(),
        tip: SEED.tip.to_string(),
        joints: SEED
            .joints
            .iter()
            .zip(SEED_JOINT_FRAMES)
            .map(|(j, home_frame)| ppoe_build::ChainJoint {
                name: j.name.to_string(),
                kind: j.kind,
                screw: j.screw.0,
                lower: j.lower,
                upper: j.upper,
                home_frame,
            })
            .collect(),
        home: SEED.home.to_matrix4(),
        coupling: None,
    }
}

/// The seed's joint direction `thetas = [1, 1, 1, 0, 1, 0]`; its initial state is
/// `-0.5·thetas` and frame `step` of the animation is `angle(step)·thetas`.
pub const THETAS: [f64; 6] = [1.0, 1.0, 1.0, 0.0, 1.0, 0.0];

/// The seed's joint covariances: 0.05 rad² about the base z axis for joint1, about the
/// base y axis for joints 2, 3 and 5, zero for joints 4 and 6 (as pytransform3d's example).
pub fn covs() -> [Mat6<f64>; 6] {
    let mut covs = [Mat6::zeros(); 6];
    covs[0].0[2][2] = 0.05;
    for i in [1, 2, 4] {
        covs[i].0[1][1] = 0.05;
    }
    covs
}

/// The joint values at `step` of an `n_frames` animation:
/// `0.5·cos(2π(0.5 + step/n_frames))·thetas` (frame 0 is the initial state
/// `-0.5·thetas`, bit for bit).
pub fn thetas_at(step: usize, n_frames: usize) -> [f64; 6] {
    let angle = 0.5 * (2.0 * std::f64::consts::PI * (0.5 + step as f64 / n_frames as f64)).cos();
    THETAS.map(|t| angle * t)
}

/// The initial state `-0.5·thetas`.
pub fn initial_thetas() -> [f64; 6] {
    THETAS.map(|t| -0.5 * t)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn runtime_chain() -> ppoe_build::RobotChain {
        let urdf = concat!(env!("CARGO_MANIFEST_DIR"), "/assets/seed.urdf");
        ppoe_build::Config::new(urdf)
            .base("linkmount")
            .tip("tcp")
            .chain()
            .unwrap()
    }

    #[test]
    fn build_time_table_equals_runtime_chain() {
        let rt = runtime_chain();
        let core: ppoe::chain::Chain<f64, 6> = rt.to_core_chain().unwrap();
        assert_eq!(SEED, core);
        assert_eq!(SEED.base, "linkmount");
        assert_eq!(SEED.tip, "tcp");
        for (a, b) in SEED.joints.iter().zip(&rt.joints) {
            assert_eq!(a.name, b.name);
            assert_eq!(a.screw.0.map(f64::to_bits), b.screw.map(f64::to_bits));
            assert_eq!(a.lower.to_bits(), b.lower.to_bits());
            assert_eq!(a.upper.to_bits(), b.upper.to_bits());
        }
        assert_eq!(SEED.home.to_matrix4(), rt.home);
    }

    #[test]
    fn build_time_frames_equal_runtime_frames() {
        let rt = runtime_chain();
        let frames = rt.home_frames();
        assert_eq!(frames.as_slice(), SEED_JOINT_FRAMES.as_slice());
        // Each joint's screw axis passes through its frame's origin.
        for (j, f) in SEED.joints.iter().zip(&SEED_JOINT_FRAMES) {
            let q = [f[0][3], f[1][3], f[2][3]];
            let w = [j.screw.0[0], j.screw.0[1], j.screw.0[2]];
            let v = [
                q[1] * w[2] - q[2] * w[1],
                q[2] * w[0] - q[0] * w[2],
                q[0] * w[1] - q[1] * w[0],
            ];
            for (k, vk) in v.iter().enumerate() {
                assert!((vk - j.screw.0[3 + k]).abs() < 1e-12, "{}", j.name);
            }
        }
    }

    #[test]
    fn visuals_file_has_the_seed_chain_and_eight_visuals() {
        let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/assets/");
        let vis = ppoe_build::Config::new(format!("{dir}seed_visuals.urdf"))
            .base("linkmount")
            .tip("tcp")
            .chain()
            .unwrap();
        let rt = runtime_chain();
        assert_eq!(vis.joints, rt.joints);
        assert_eq!(vis.home, rt.home);
        let v = visuals().unwrap();
        let bodies = v.place(&[crate::picture::geom::IDENTITY; 7]);
        // link1, link4, link6: one cylinder each; link2, link5: hub and segment; link3: hub.
        assert_eq!(bodies.len(), 8);
        assert_eq!(VISUALS_URDF.matches("<visual>").count(), 8);
    }

    #[test]
    fn robot_chain_holds_the_table() {
        let rt = runtime_chain();
        let mine = robot_chain();
        assert_eq!((mine.joints, mine.home), (rt.joints, rt.home));
    }

    #[test]
    fn frame_zero_is_the_initial_state() {
        assert_eq!(thetas_at(0, 200), initial_thetas());
    }
}
