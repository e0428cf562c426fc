//! Mimic joints end to end (issue #30): `ppoe eval` on `test_data/urdf/gripper.urdf` takes
//! the independent joint values and returns the PPOE of the full chain, checked against an
//! oracle written here from the URDF's numbers: the tip pose is the product of the
//! per-joint homogeneous transforms `Origin_k·Motion_k(θ_k)` (4×4, `ppoe_test_robots`'
//! matrix4), with each mimic joint's value `multiplier·master + offset` clipped to its own
//! limits; the covariance is the first-order sum `Σᵢ Ad(Gᵢ⁻¹)·covᵢ·Ad(Gᵢ⁻¹)ᵀ` of the model
//! `T = D₁·Exp(ξ₁)·…·Dₙ·Exp(ξₙ)·M`, with `Gᵢ⁻¹ = T⁻¹·Fᵢ(θ)·Fᵢ(0)⁻¹` (Fᵢ the frame of joint
//! i's child link from the same product) and dense 6×6 matrices. pytransform3d ignores
//! `<mimic>`, so it is no oracle here.

mod common;
use common::*;
use serde_json::{json, Value};

use ppoe_test_robots::matrix4::{exp, inv, mul, M4};

type M6 = [[f64; 6]; 6];

/// `<origin xyz rpy>`: `[[Rz(y)·Ry(p)·Rx(r), xyz], [0, 1]]`.
fn origin(xyz: [f64; 3], rpy: [f64; 3]) -> M4 {
    let r = mul(
        &mul(
            &exp(&[0.0, 0.0, rpy[2], 0.0, 0.0, 0.0]),
            &exp(&[0.0, rpy[1], 0.0, 0.0, 0.0, 0.0]),
        ),
        &exp(&[rpy[0], 0.0, 0.0, 0.0, 0.0, 0.0]),
    );
    let mut t = r;
    for i in 0..3 {
        t[i][3] = xyz[i];
    }
    t
}

/// A joint's motion in its child frame: a rotation about `axis` or a translation along it.
fn motion(prismatic: bool, axis: [f64; 3], theta: f64) -> M4 {
    let a = axis.map(|x| x * theta);
    if prismatic {
        exp(&[0.0, 0.0, 0.0, a[0], a[1], a[2]])
    } else {
        exp(&[a[0], a[1], a[2], 0.0, 0.0, 0.0])
    }
}

/// The frames of the chain base → left_tip of gripper.urdf at the full joint values
/// `full` (shoulder, elbow, left_finger, curl): the child frame of each moving joint, and
/// the tip. The numbers are the file's.
fn left_frames(full: [f64; 4]) -> ([M4; 4], M4) {
    let shoulder = mul(
        &origin([0.0, 0.0, 0.1], [0.0; 3]),
        &motion(false, [0.0, 0.0, 1.0], full[0]),
    );
    let elbow = mul(
        &shoulder,
        &mul(
            &origin([0.0, 0.0, 0.3], [0.0, 0.2, 0.0]),
            &motion(false, [0.0, 1.0, 0.0], full[1]),
        ),
    );
    let palm = mul(&elbow, &origin([0.25, 0.0, 0.0], [0.1, 0.0, 0.3]));
    let finger = mul(
        &palm,
        &mul(
            &origin([0.05, 0.02, 0.0], [0.0; 3]),
            &motion(true, [0.0, 1.0, 0.0], full[2]),
        ),
    );
    let curl = mul(
        &finger,
        &mul(
            &origin([0.03, 0.0, 0.0], [0.0, 0.0, 0.5]),
            &motion(false, [0.0, 0.0, 1.0], full[3]),
        ),
    );
    let tip = mul(&curl, &origin([0.02, 0.0, 0.0], [0.0; 3]));
    ([shoulder, elbow, finger, curl], tip)
}

/// The full joint vector from (shoulder, elbow, right_finger), by the file's couplings and
/// limits: left_finger = 0.8·right_finger + 0.005 in [0, 0.03], curl = −0.5·elbow + 0.1 in
/// [−1, 1]; shoulder and elbow in [−2, 2].
fn full(q: [f64; 3]) -> [f64; 4] {
    [
        q[0].clamp(-2.0, 2.0),
        q[1].clamp(-2.0, 2.0),
        (0.8 * q[2] + 0.005).clamp(0.0, 0.03),
        (-0.5 * q[1] + 0.1).clamp(-1.0, 1.0),
    ]
}

/// `Ad(T) = [[R, 0], [[p]×R, R]]`, dense.
fn adjoint(t: &M4) -> M6 {
    let mut ad = [[0.0; 6]; 6];
    let p = [t[0][3], t[1][3], t[2][3]];
    let px = [[0.0, -p[2], p[1]], [p[2], 0.0, -p[0]], [-p[1], p[0], 0.0]];
    for i in 0..3 {
        for j in 0..3 {
            ad[i][j] = t[i][j];
            ad[i + 3][j + 3] = t[i][j];
            ad[i + 3][j] = (0..3).map(|k| px[i][k] * t[k][j]).sum();
        }
    }
    ad
}

fn mul6(a: &M6, b: &M6) -> M6 {
    std::array::from_fn(|i| std::array::from_fn(|j| (0..6).map(|k| a[i][k] * b[k][j]).sum()))
}

fn transpose6(a: &M6) -> M6 {
    std::array::from_fn(|i| std::array::from_fn(|j| a[j][i]))
}

/// A PSD covariance per joint, `A·Aᵀ` with a hand-picked A (rotation and translation,
/// coupled), scaled by 1e-2 so that Σ ≈ 1e-4.
fn cov(i: usize) -> M6 {
    let a: M6 = std::array::from_fn(|r| {
        std::array::from_fn(|c| {
            let x = ((r + 2 * c + 3 * i) % 5) as f64 - 2.0;
            if c <= r {
                1e-2 * (x + if r == c { 0.5 } else { 0.0 })
            } else {
                0.0
            }
        })
    });
    mul6(&a, &transpose6(&a))
}

/// The oracle: tip pose and right covariance for independent values `q`.
fn oracle(q: [f64; 3]) -> (M4, M6) {
    let theta = full(q);
    let (frames, tip) = left_frames(theta);
    let (home_frames, _) = left_frames([0.0; 4]);
    let tip_inv = inv(&tip);
    let mut sigma = [[0.0; 6]; 6];
    for i in 0..4 {
        let g_inv = mul(&mul(&tip_inv, &frames[i]), &inv(&home_frames[i]));
        let ad = adjoint(&g_inv);
        let term = mul6(&mul6(&ad, &cov(i)), &transpose6(&ad));
        for r in 0..6 {
            for c in 0..6 {
                sigma[r][c] += term[r][c];
            }
        }
    }
    (tip, sigma)
}

fn eval(tip: &str, cases: &Value) -> Value {
    let text = cases.to_string();
    let u = urdf("gripper.urdf");
    let out = run_bytes(
        &[
            "eval",
            "--urdf",
            u.to_str().unwrap(),
            "--base",
            "base",
            "--tip",
            tip,
        ],
        text.as_bytes(),
    );
    assert!(out.status.success(), "{}", stderr(&out));
    serde_json::from_slice(&out.stdout).unwrap()
}

fn max_diff<const R: usize, const C: usize>(a: &Value, b: &[[f64; C]; R]) -> f64 {
    let mut worst: f64 = 0.0;
    for (r, row) in b.iter().enumerate() {
        for (c, x) in row.iter().enumerate() {
            worst = worst.max((a[r][c].as_f64().unwrap() - x).abs());
        }
    }
    worst
}

#[test]
fn eval_takes_independent_values_and_matches_the_oracle() {
    // Inside every limit; left_finger clipped to 0.03 (0.8·0.04 + 0.005 = 0.037); curl
    // clipped to 1 (−0.5·(−1.9) + 0.1 = 1.05).
    let qs = [[0.3, -0.4, 0.02], [-0.5, 1.2, 0.04], [0.7, -1.9, 0.01]];
    let covs: Vec<M6> = (0..4).map(cov).collect();
    let cases: Vec<Value> = qs
        .iter()
        .map(|q| json!({"thetas": q, "covs": covs}))
        .collect();
    let out = eval("left_tip", &json!({ "cases": cases }));
    assert_eq!(
        out["chain"]["inputs"],
        json!(["shoulder", "elbow", "right_finger"])
    );
    assert_eq!(
        out["chain"]["mimic"][2],
        json!({"master": "right_finger", "multiplier": 0.8, "offset": 0.005})
    );
    for (q, r) in qs.iter().zip(out["results"].as_array().unwrap()) {
        let (pose, sigma) = oracle(*q);
        let clipped: Vec<f64> = serde_json::from_value(r["thetas_clipped"].clone()).unwrap();
        for (a, b) in clipped.iter().zip(full(*q)) {
            assert!((a - b).abs() < 1e-15, "{q:?}: {clipped:?}");
        }
        assert!(max_diff(&r["pose"], &pose) < 1e-12, "{q:?}: {}", r["pose"]);
        let scale = sigma.iter().flatten().fold(0.0_f64, |m, x| m.max(x.abs()));
        let d = max_diff(&r["cov"], &sigma);
        assert!(d < 1e-10 * scale, "{q:?}: {d} of {scale}");
    }
}

#[test]
fn a_wrong_number_of_values_names_the_inputs() {
    let covs: Vec<M6> = (0..4).map(cov).collect();
    let u = urdf("gripper.urdf");
    let text = json!({"cases": [{"thetas": [0.1, 0.2, 0.01, 0.3], "covs": covs}]}).to_string();
    let out = run_bytes(
        &[
            "eval",
            "--urdf",
            u.to_str().unwrap(),
            "--base",
            "base",
            "--tip",
            "left_tip",
        ],
        text.as_bytes(),
    );
    assert_eq!(out.status.code(), Some(1));
    let e = stderr(&out);
    for m in [
        "case 0",
        "4 joint values",
        "3 independent",
        "right_finger",
        "mimic",
    ] {
        assert!(e.contains(m), "{e:?} lacks {m:?}");
    }
}

#[test]
fn the_other_finger_has_no_coupling() {
    // base → right_tip passes the master, not the mimic joint: three independent joints,
    // and no "inputs"/"mimic" in the output.
    let zero = [[0.0; 6]; 6];
    let out = eval(
        "right_tip",
        &json!({"cases": [{"thetas": [0.0, 0.0, 0.01], "covs": [zero, zero, zero]}]}),
    );
    assert!(out["chain"].get("inputs").is_none());
    assert_eq!(
        out["chain"]["joints"],
        json!(["shoulder", "elbow", "right_finger"])
    );
}

#[test]
fn links_and_tables_name_the_master() {
    let u = urdf("gripper.urdf");
    let out = run(&["links", "--urdf", u.to_str().unwrap()]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains("mimic of right_finger: 0.8·right_finger + 0.005"),
        "{text}"
    );
    let args = [
        "table",
        "--urdf",
        u.to_str().unwrap(),
        "--base",
        "base",
        "--tip",
        "left_tip",
        "--name",
        "ARM",
    ];
    let out = run(&args);
    let src = String::from_utf8_lossy(&out.stdout);
    assert!(
        src.contains("mimic of `elbow`: θ = -0.5·θ_master + 0.1"),
        "{src}"
    );
    assert!(src.contains("pub const ARM_COUPLING: ppoe::chain::Coupling<'static, f64>"));
    assert!(src.contains("ppoe::chain::Mimic::new(2, 0.8, 0.005)"));
    let mut c_args = args.to_vec();
    c_args.extend(["--lang", "c"]);
    let out = run(&c_args);
    assert_eq!(out.status.code(), Some(1));
    assert!(stderr(&out).contains("mimic joints (left_finger, curl)"));
}

#[test]
fn fit_samples_give_the_independent_values() {
    let u = urdf("gripper.urdf");
    let eye = [
        [1.0, 0.0, 0.0, 0.0],
        [0.0, 1.0, 0.0, 0.0],
        [0.0, 0.0, 1.0, 0.0],
        [0.0, 0.0, 0.0, 1.0],
    ];
    let text = json!({"samples": [{"thetas": [0.1, 0.2, 0.01, 0.3], "pose": eye}]}).to_string();
    let out = run_bytes(
        &[
            "fit",
            "--urdf",
            u.to_str().unwrap(),
            "--base",
            "base",
            "--tip",
            "left_tip",
            "--model",
            "joint",
        ],
        text.as_bytes(),
    );
    assert_eq!(out.status.code(), Some(1));
    let e = stderr(&out);
    for m in [
        "sample 0",
        "4 joint values",
        "3 independent",
        "right_finger",
    ] {
        assert!(e.contains(m), "{e:?} lacks {m:?}");
    }
}
