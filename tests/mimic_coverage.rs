//! `ppoe::chain::Coupling`: the expansion of independent joint values into a chain's full
//! joint vector (mimic joints), every error path, in f64 and f32. Expected values are
//! written out by hand from `θ = multiplier·q[master] + offset`.

use ppoe::chain::{Coupling, JointSource, Mimic};
use ppoe::Error;

/// A gripper-like chain of four joints on three inputs: joint 2 mimics joint 0 (on the
/// chain), joint 3 mimics input 2, which is no chain joint (a finger off the path).
const SOURCES: [JointSource<f64>; 4] = [
    JointSource::Input(0),
    JointSource::Input(1),
    JointSource::Mimic(Mimic::new(0, 2.0, 0.25)),
    JointSource::Mimic(Mimic::new(2, -0.5, -0.125)),
];
const GRIPPER: Coupling<'static, f64> = Coupling::new(3, &SOURCES);

#[test]
fn expands_inputs_and_mimic_joints() {
    let mut full = [f64::NAN; 4];
    GRIPPER.expand(&[0.5, -1.0, 0.75], &mut full).unwrap();
    // 2·0.5 + 0.25 = 1.25; −0.5·0.75 − 0.125 = −0.5 (all exact in binary).
    assert_eq!(full, [0.5, -1.0, 1.25, -0.5]);
}

#[test]
fn f32_expands_like_f64() {
    let sources = [
        JointSource::Input(0),
        JointSource::Mimic(Mimic::new(0, 3.0_f32, 1.0)),
    ];
    let mut full = [0.0_f32; 2];
    Coupling::new(1, &sources)
        .expand(&[0.5], &mut full)
        .unwrap();
    assert_eq!(full, [0.5, 2.5]);
}

#[test]
fn inputs_are_copied_bit_for_bit() {
    // −0 stays −0: an input joint is copied, not computed as 1·q + 0.
    let mut full = [0.0; 4];
    GRIPPER.expand(&[-0.0, -0.0, 1.0], &mut full).unwrap();
    assert!(full[0].is_sign_negative() && full[1].is_sign_negative());
}

#[test]
fn length_mismatches() {
    let mut full = [0.0; 4];
    assert_eq!(
        GRIPPER.expand(&[0.0; 2], &mut full),
        Err(Error::LengthMismatch)
    );
    assert_eq!(
        GRIPPER.expand(&[0.0; 4], &mut full),
        Err(Error::LengthMismatch)
    );
    assert_eq!(
        GRIPPER.expand(&[0.0; 3], &mut [0.0; 3]),
        Err(Error::LengthMismatch)
    );
}

#[test]
fn master_out_of_range() {
    let sources = [
        JointSource::Input(0),
        JointSource::Mimic(Mimic::new(1, 1.0, 0.0)),
    ];
    let c = Coupling::new(1, &sources);
    assert_eq!(c.check(), Err(Error::IndexOutOfRange));
    assert_eq!(c.expand(&[0.0], &mut [0.0; 2]), Err(Error::IndexOutOfRange));
    let input = [JointSource::<f64>::Input(3)];
    assert_eq!(
        Coupling::new(1, &input).expand(&[0.0], &mut [0.0]),
        Err(Error::IndexOutOfRange)
    );
    assert!(Error::IndexOutOfRange.to_string().contains("out of range"));
}

#[test]
fn non_finite_coupling_or_input() {
    for (m, o) in [
        (f64::NAN, 0.0),
        (f64::INFINITY, 0.0),
        (1.0, f64::NEG_INFINITY),
    ] {
        let sources = [JointSource::Mimic(Mimic::new(0, m, o))];
        let c = Coupling::new(1, &sources);
        assert_eq!(c.check(), Err(Error::NonFinite));
        assert_eq!(c.expand(&[0.0], &mut [0.0]), Err(Error::NonFinite));
    }
    let mut full = [0.0; 4];
    assert_eq!(
        GRIPPER.expand(&[0.0, f64::NAN, 0.0], &mut full),
        Err(Error::NonFinite)
    );
}

#[test]
fn overflow_is_reported() {
    let sources = [JointSource::Mimic(Mimic::new(0, 1e300, 0.0))];
    assert_eq!(
        Coupling::new(1, &sources).expand(&[1e10], &mut [0.0]),
        Err(Error::Overflow)
    );
    let f32_sources = [JointSource::Mimic(Mimic::new(0, 1e30_f32, 0.0))];
    assert_eq!(
        Coupling::new(1, &f32_sources).expand(&[1e10], &mut [0.0]),
        Err(Error::Overflow)
    );
}
