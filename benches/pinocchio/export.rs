//! The robots as a C++ header for the Pinocchio harness (benches/pinocchio/fk_bench.cpp):
//! the same chains ppoe-build extracts, written joint by joint as Pinocchio builds a model
//! (parent-to-joint placement, joint axis in the joint frame, tip placement), with test
//! configurations and ppoe's f64 forward kinematics of each as the expected tip poses.
//!
//! urdfdom rejects the seed URDF, so the model does not come from Pinocchio's parser: the
//! frames are ppoe-build's home frames `L_i` (base ← joint i at θ = 0), and the placement of
//! joint i is `L_{i−1}⁻¹·L_i`, the tip's `L_n⁻¹·M`. A joint whose axis is −x, −y or −z in its
//! frame gets its frame turned by π about the next axis (the axis becomes +x, +y or +z), so
//! that Pinocchio can use its specialised RX/RY/RZ joints, which a URDF importer would
//! also pick; any other axis becomes a `JointModelRevoluteUnaligned`.

#![allow(dead_code)] // only the ops bench binary exports

use super::robots::{self, Robot};
use ppoe::chain::ChainView;
use std::fmt::Write as _;

type M4 = [[f64; 4]; 4];

const IDENTITY: M4 = [
    [1.0, 0.0, 0.0, 0.0],
    [0.0, 1.0, 0.0, 0.0],
    [0.0, 0.0, 1.0, 0.0],
    [0.0, 0.0, 0.0, 1.0],
];

fn mul(a: &M4, b: &M4) -> M4 {
    std::array::from_fn(|i| std::array::from_fn(|j| (0..4).map(|k| a[i][k] * b[k][j]).sum()))
}

/// Inverse of a rigid transform (Rᵀ, −Rᵀp).
fn inv(a: &M4) -> M4 {
    let mut m = [[0.0; 4]; 4];
    for i in 0..3 {
        for j in 0..3 {
            m[i][j] = a[j][i];
        }
        m[i][3] = -(0..3).map(|k| a[k][i] * a[k][3]).sum::<f64>();
    }
    m[3][3] = 1.0;
    m
}

/// Rotation by π about axis `k` (0 = x, 1 = y, 2 = z).
fn half_turn(k: usize) -> M4 {
    let mut m = IDENTITY;
    for i in (0..3).filter(|&i| i != k) {
        m[i][i] = -1.0;
    }
    m
}

/// Joint type code for the harness (0, 1, 2 = RX, RY, RZ; 3 = unaligned) and the axis in
/// the (possibly turned) joint frame; the frame is turned in place for a negative axis.
fn joint_axis(frame: &mut M4, screw: &[f64; 6]) -> (usize, [f64; 3]) {
    let a: [f64; 3] = std::array::from_fn(|i| (0..3).map(|k| frame[k][i] * screw[k]).sum());
    for k in 0..3 {
        let off: f64 = (0..3).filter(|&i| i != k).map(|i| a[i].abs()).sum();
        if off < 1e-14 && (a[k].abs() - 1.0).abs() < 1e-14 {
            if a[k] < 0.0 {
                *frame = mul(frame, &half_turn((k + 1) % 3));
            }
            return (k, std::array::from_fn(|i| if i == k { 1.0 } else { 0.0 }));
        }
    }
    (3, a)
}

fn placement(m: &M4) -> String {
    let v: Vec<String> = (0..3)
        .flat_map(|i| (0..3).map(move |j| (i, j)))
        .map(|(i, j)| format!("{:e}", m[i][j]))
        .chain((0..3).map(|i| format!("{:e}", m[i][3])))
        .collect();
    format!("{{{}}}", v.join(", "))
}

/// One robot's header section: arrays in namespace `r_<name>` and a `RobotTable` entry.
fn robot_section(r: &Robot, cases: &[Vec<f64>], out: &mut String) -> String {
    let rc = robots::robot_chain(r);
    let (joints, home) = robots::core_chain::<f64>(&rc);
    let chain = ChainView {
        joints: &joints,
        home,
    };
    let n = rc.joints.len();
    let (mut kinds, mut axes, mut places) = (vec![], vec![], vec![]);
    let mut prev = IDENTITY;
    for j in &rc.joints {
        assert!(
            matches!(j.kind, ppoe_build::JointKind::Revolute),
            "{}: the Pinocchio export handles revolute joints only",
            r.file
        );
        let mut frame = j.home_frame;
        let (kind, axis) = joint_axis(&mut frame, &j.screw);
        places.push(placement(&mul(&inv(&prev), &frame)));
        kinds.push(kind.to_string());
        axes.push(format!("{{{:e}, {:e}, {:e}}}", axis[0], axis[1], axis[2]));
        prev = frame;
    }
    let tip = placement(&mul(&inv(&prev), &rc.home));
    let mut expected = vec![];
    for q in cases {
        assert_eq!(q.len(), n, "{}: case length", r.file);
        for (j, t) in rc.joints.iter().zip(q) {
            assert!(
                *t >= j.lower && *t <= j.upper,
                "{}: case outside limits",
                r.file
            );
        }
        let m = chain.forward_kinematics(q).expect("ppoe FK").to_matrix4();
        expected.push(placement(&m));
    }
    let flat = |v: &[Vec<f64>]| {
        let s: Vec<String> = v.iter().flatten().map(|x| format!("{x:e}")).collect();
        s.join(", ")
    };
    let name = r.name;
    let _ = writeln!(
        out,
        "namespace r_{name} {{\nconst int kind[] = {{{}}};\nconst double axis[][3] = {{{}}};\n\
         const double place[][12] = {{{}}};\nconst double tip[12] = {};\nconst double q[] = {{{}}};\n\
         const double expected[][12] = {{{}}};\n}}  // namespace r_{name}",
        kinds.join(", "),
        axes.join(", "),
        places.join(",\n  "),
        tip,
        flat(cases),
        expected.join(",\n  ")
    );
    format!(
        "{{\"{name}\", {n}, {}, r_{name}::kind, r_{name}::axis, r_{name}::place, r_{name}::tip, \
         r_{name}::q, r_{name}::expected}}",
        cases.len()
    )
}

/// Writes `<dir>/robots.hpp` for the seed robot and the 7-joint arm. The first case of each
/// is its benchmark configuration (the same as the criterion benches').
pub fn write_header(dir: &str) {
    let seed_cases = vec![
        vec![-0.5, -0.5, -0.5, 0.0, -0.5, 0.0],
        vec![0.3, 0.7, -1.2, 2.0, -0.4, 1.1],
        vec![-0.9, -0.2, 0.9, -2.5, 1.3, -3.0],
    ];
    let arm_cases = vec![
        robots::arm7_thetas::<f64>(),
        vec![-1.2, 0.8, -2.1, -0.5, 2.4, 3.1, -2.2],
        vec![2.5, -1.5, 1.7, -2.9, -1.9, 0.2, 1.0],
    ];
    let mut body = String::from(
        "// Generated by the ops bench binary (PPOE_PINOCCHIO_EXPORT); do not edit.\n\
         // Robots of test_data/urdf as ppoe-build extracts them; see benches/pinocchio/export.rs.\n\
         #pragma once\n\
         struct RobotTable { const char* name; int n; int cases; const int* kind;\n\
         \x20 const double (*axis)[3]; const double (*place)[12]; const double* tip;\n\
         \x20 const double* q; const double (*expected)[12]; };\n",
    );
    let mut entries = vec![];
    for (r, cases) in [(&robots::SEED, seed_cases), (&robots::ARM7, arm_cases)] {
        entries.push(robot_section(r, &cases, &mut body));
    }
    let _ = writeln!(
        body,
        "const RobotTable kRobots[] = {{\n  {}\n}};",
        entries.join(",\n  ")
    );
    let path = format!("{dir}/robots.hpp");
    let tmp = format!("{path}.tmp");
    std::fs::write(&tmp, body).expect("write robots.hpp");
    std::fs::rename(&tmp, &path).expect("rename robots.hpp");
    println!("wrote {path}");
}
