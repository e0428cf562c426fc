//! URDF axes of extreme magnitude: an axis is a direction, so any finite non-zero `xyz`
//! gives its unit vector (closed forms below), however tiny or huge; only a true zero axis
//! is rejected, and its message shows the axis as written.

use ppoe_build::{ErrorKind, Urdf};

const NONE: Option<&[&str]> = None;

/// A two-link robot with one joint of type `ty` whose `<axis xyz>` is `xyz`.
fn robot(ty: &str, xyz: &str) -> String {
    format!(
        "<?xml version=\"1.0\"?>\n<robot name=\"r\"><link name=\"a\"/><link name=\"b\"/>\
         <joint name=\"j\" type=\"{ty}\"><parent link=\"a\"/><child link=\"b\"/>\
         <axis xyz=\"{xyz}\"/></joint></robot>\n"
    )
}

/// The unit direction (ω for revolute, v for prismatic) of the single joint.
fn direction(ty: &str, xyz: &str) -> [f64; 3] {
    let chain = Urdf::parse(&robot(ty, xyz))
        .and_then(|u| u.chain("a", "b", NONE))
        .unwrap_or_else(|e| panic!("{ty} axis {xyz}: {e}"));
    let s = chain.joints[0].screw;
    let k = if ty == "prismatic" { 3 } else { 0 };
    [s[k], s[k + 1], s[k + 2]]
}

fn assert_unit(got: [f64; 3], want: [f64; 3], xyz: &str) {
    for (g, w) in got.iter().zip(want) {
        // One rounding of the normalisation: within 2 ulp of the exact unit vector.
        assert!(
            (g - w).abs() <= 2.0 * f64::EPSILON * w.abs(),
            "axis {xyz}: got {got:?}, want {want:?}"
        );
    }
}

#[test]
fn tiny_huge_and_subnormal_axes_give_the_unit_axis() {
    let r2 = std::f64::consts::FRAC_1_SQRT_2;
    let r3 = 1.0 / 3.0f64.sqrt();
    let r5 = 1.0 / 5.0f64.sqrt();
    let cases: [(&str, [f64; 3]); 9] = [
        ("1e-300 0 0", [1.0, 0.0, 0.0]),
        ("0 1e-200 1e-200", [0.0, r2, r2]),
        ("3e-300 0 -4e-300", [0.6, 0.0, -0.8]),
        ("1e150 1e150 1e150", [r3, r3, r3]),
        ("0 3e300 4e300", [0.0, 0.6, 0.8]),
        ("1e300 1e300 0", [r2, r2, 0.0]),
        ("-1.7e308 0 0", [-1.0, 0.0, 0.0]),
        // Subnormal: the smallest positive double and twice it.
        ("0 5e-324 1e-323", [0.0, r5, 2.0 * r5]),
        ("0 0 -5e-324", [0.0, 0.0, -1.0]),
    ];
    for ty in ["revolute", "continuous", "prismatic"] {
        for (xyz, want) in cases {
            assert_unit(direction(ty, xyz), want, xyz);
        }
    }
}

#[test]
fn ordinary_axes_are_unchanged_by_the_scaling() {
    // In the range where the plain norm is exact the result is numpy's bit for bit.
    assert_eq!(direction("revolute", "0 -3 4"), [0.0, -0.6, 0.8]);
    assert_eq!(direction("prismatic", "0 0 2"), [0.0, 0.0, 1.0]);
}

#[test]
fn a_zero_axis_is_still_rejected_and_shown_as_given() {
    for (xyz, shown) in [
        ("0 0 0", "(0.0, 0.0, 0.0)"),
        ("0 -0 0", "(0.0, -0.0, 0.0)"),
        ("0e300 0 -0e-300", "(0.0, 0.0, -0.0)"),
    ] {
        let e = match Urdf::parse(&robot("revolute", xyz)).and_then(|u| u.chain("a", "b", NONE)) {
            Ok(_) => panic!("axis {xyz} accepted"),
            Err(e) => e,
        };
        assert_eq!(e.kind(), ErrorKind::ZeroAxis, "{xyz}: {e}");
        assert!(
            e.message().contains(shown) && e.message().contains("is zero"),
            "{xyz}: {}",
            e.message()
        );
    }
}
