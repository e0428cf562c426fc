//! Golden tests: the SO(3)/SE(3) primitives and every uncertainty operation against the
//! vectors our oracle script (`test_data/reference/generate_core.py`) computed with
//! pytransform3d 3.17.0.
//!
//! Error measure: `max|a − b| / max(1, max|b|)` per output. f64 must be ≤ 1e-12.
//! f32 runs on the same inputs rounded to f32 and is held to [`F32_BOUND`]: inputs carry a
//! relative rounding of 2⁻²⁴ ≈ 6·10⁻⁸ and each operation a few dozen roundings of ε₃₂ =
//! 1.2·10⁻⁷ on values of order 1, so 1·10⁻⁵ leaves a ~10× margin on well-conditioned
//! cases. Ill-conditioned inputs are excluded from the f32 check with the reason stated:
//! the SO(3) logarithm within δ of π has condition ≈ 1/δ.

mod common;
use common::*;
use ppoe::uncertainty::{self, Order};
use ppoe::{se3, so3, Mat3, Matrix, Real, Vec3, Vector};
use serde_json::Value;

const F64_BOUND: f64 = 1e-12;
/// See the module doc for the derivation.
const F32_BOUND: f64 = 1e-5;

fn cases(file: &str) -> Vec<Value> {
    golden(&format!("core/{file}"))["cases"]
        .as_array()
        .expect("cases")
        .clone()
}

fn label(c: &Value) -> String {
    c["label"].as_str().unwrap_or("?").to_string()
}

/// Whether the case is ill-conditioned for f32 (rotation within 1e-3 of π, or a
/// scale so large or small that f32 cannot represent the inputs' precision).
fn f32_ill_conditioned(c: &Value) -> bool {
    let l = label(c);
    l.contains("near_pi") || l.contains("/pi") || l.starts_with("pi") || l.contains("large")
}

/// The expected logarithm: pytransform3d's, except for the `near_pi` cases (π − δ,
/// δ = 10⁻¹⁰…10⁻³), where its axis is off by ≈ ε/δ (skew part, up to 2·10⁻¹⁰) or by up
/// to δ/2 (`√((Sᵢᵢ + 1)/2)` within 10⁻⁶ of π) and ppoe reads the axis from the symmetric
/// part to a few ε: there the oracle is the rotation vector the case was generated from
/// (R is its exponential to rounding, and near π the axis is well-conditioned in R's
/// symmetric part).
fn log_oracle(c: &Value, reference: &str, input: &str) -> Vec<f64> {
    if c["label"] == "near_pi" {
        vecf(&c[input])
    } else {
        vecf(&c[reference])
    }
}

fn so3_case<T: Real>(c: &Value, w: &mut [Worst; 4]) {
    let omega: Vec3<f64> = Vector(vec_n::<3>(&c["omega"]));
    let r: Mat3<f64> = Matrix(mat_n::<3, 3>(&c["R"]));
    let l = label(c);
    if c["R_source"] == "exp" {
        let ours = up_m(&so3::exp(&cast_v::<T, 3>(&omega)));
        w[0].add(rel_err(&flat(&ours), &flat(&r)), &l);
    }
    let log = up_v(&so3::log(&cast_m::<T, 3, 3>(&r)));
    w[1].add(rel_err(&log.0, &log_oracle(c, "log", "omega")), &l);
    let j = up_m(&so3::left_jacobian(&cast_v::<T, 3>(&omega)));
    w[2].add(
        rel_err(&flat(&j), &flat(&Matrix(mat_n::<3, 3>(&c["J"])))),
        &l,
    );
    let ji = up_m(&so3::left_jacobian_inv(&cast_v::<T, 3>(&omega)));
    w[3].add(
        rel_err(&flat(&ji), &flat(&Matrix(mat_n::<3, 3>(&c["J_inv"])))),
        &l,
    );
}

fn run_so3<T: Real>(bound: f64, skip: fn(&Value) -> bool) {
    let mut w = ["so3 exp", "so3 log", "so3 J", "so3 J_inv"]
        .map(|n| Worst::new(&format!("{n} {}", core::any::type_name::<T>())));
    for c in cases("so3.json") {
        if !skip(&c) {
            so3_case::<T>(&c, &mut w);
        }
    }
    for x in &w {
        x.check(bound);
    }
}

#[test]
fn so3_f64() {
    run_so3::<f64>(F64_BOUND, |_| false);
}

#[test]
fn so3_f32() {
    run_so3::<f32>(F32_BOUND, f32_ill_conditioned);
}

fn run_se3<T: Real>(bound: f64, skip: fn(&Value) -> bool) {
    let names = [
        "se3 exp",
        "se3 log",
        "se3 adjoint",
        "se3 J6",
        "se3 J_inv6",
        "se3 Q",
    ];
    let mut w = names.map(|n| Worst::new(&format!("{n} {}", core::any::type_name::<T>())));
    for c in cases("se3.json") {
        if skip(&c) {
            continue;
        }
        let l = label(&c);
        let xi = cast_v::<T, 6>(&Vector(vec_n::<6>(&c["xi"])));
        let t_ref = transform(&c["T_single"]);
        w[0].add(rel_err(&flat_t(&up_t(&se3::exp(&xi))), &flat_t(&t_ref)), &l);
        let log = up_v(&se3::log(&cast_t::<T>(&t_ref)));
        w[1].add(rel_err(&log.0, &log_oracle(&c, "log_single", "xi")), &l);
        let ad = up_m(&cast_t::<T>(&t_ref).adjoint());
        w[2].add(rel_err(&flat(&ad), &flat(&mat6(&c["adjoint"]))), &l);
        w[3].add(
            rel_err(
                &flat(&up_m(&se3::left_jacobian(&xi))),
                &flat(&mat6(&c["J6"])),
            ),
            &l,
        );
        w[4].add(
            rel_err(
                &flat(&up_m(&se3::left_jacobian_inv(&xi))),
                &flat(&mat6(&c["J_inv6"])),
            ),
            &l,
        );
        let q: Mat3<f64> = Matrix(mat_n::<3, 3>(&c["Q"]));
        w[5].add(rel_err(&flat(&up_m(&se3::q_matrix(&xi))), &flat(&q)), &l);
    }
    for x in &w {
        x.check(bound);
    }
}

#[test]
fn se3_f64() {
    run_se3::<f64>(F64_BOUND, |_| false);
}

#[test]
fn se3_f32() {
    run_se3::<f32>(F32_BOUND, f32_ill_conditioned);
}

#[test]
fn screw_axes() {
    let mut w = Worst::new("screw_axis_from_screw_parameters f64");
    for c in cases("screw.json") {
        let q: Vec3<f64> = Vector(vec_n::<3>(&c["q"]));
        let s: Vec3<f64> = Vector(vec_n::<3>(&c["s"]));
        let got = se3::screw_axis(&q, &s, num(&c["h"])).expect("valid screw");
        w.add(rel_err(&got.0, &vec_n::<6>(&c["S"])), &label(&c));
    }
    w.check(F64_BOUND);
    let zero = Vec3::<f64>::zeros();
    assert_eq!(
        se3::screw_axis(&zero, &zero, 0.0),
        Err(ppoe::Error::ZeroAxis)
    );
}

fn run_concat<T: Real>(bound: f64) {
    let ty = core::any::type_name::<T>();
    let mut wg = Worst::new(&format!("concat_globally 4th {ty}"));
    let mut wg2 = Worst::new(&format!("concat_globally 2nd {ty}"));
    let mut wgm = Worst::new(&format!("concat_globally mean {ty}"));
    for c in cases("concat_globally.json") {
        let l = label(&c);
        let (a, ca) = (
            cast_t::<T>(&transform(&c["mean_A2B"])),
            cast_m::<T, 6, 6>(&mat6(&c["cov_A2B"])),
        );
        let (b, cb) = (
            cast_t::<T>(&transform(&c["mean_B2C"])),
            cast_m::<T, 6, 6>(&mat6(&c["cov_B2C"])),
        );
        let (m, cov) = uncertainty::concat_globally(&a, &ca, &b, &cb, Order::Fourth);
        wgm.add(
            rel_err(&flat_t(&up_t(&m)), &flat_t(&transform(&c["mean_A2C"]))),
            &l,
        );
        wg.add(rel_err(&flat(&up_m(&cov)), &flat(&mat6(&c["cov_A2C"]))), &l);
        let (_, cov2) = uncertainty::concat_globally(&a, &ca, &b, &cb, Order::Second);
        wg2.add(
            rel_err(&flat(&up_m(&cov2)), &flat(&mat6(&c["cov_A2C_2nd"]))),
            &l,
        );
    }
    let mut wl = Worst::new(&format!("concat_locally {ty}"));
    for c in cases("concat_locally.json") {
        let l = label(&c);
        let (a, b) = (
            cast_t::<T>(&transform(&c["mean_A2B"])),
            cast_t::<T>(&transform(&c["mean_B2C"])),
        );
        let (ca, cb) = (
            cast_m::<T, 6, 6>(&mat6(&c["cov_A"])),
            cast_m::<T, 6, 6>(&mat6(&c["cov_B"])),
        );
        let (m, cov) = uncertainty::concat_locally(&a, &b, &ca, &cb);
        let e_m = rel_err(&flat_t(&up_t(&m)), &flat_t(&transform(&c["mean_A2C"])));
        let e_c = rel_err(&flat(&up_m(&cov)), &flat(&mat6(&c["cov_A_total"])));
        wl.add(e_m.max(e_c), &l);
    }
    let mut wi = Worst::new(&format!("invert_uncertain_transform {ty}"));
    for c in cases("invert.json") {
        let l = label(&c);
        let (m, cov) = uncertainty::invert(
            &cast_t::<T>(&transform(&c["mean"])),
            &cast_m::<T, 6, 6>(&mat6(&c["cov"])),
        );
        let e_m = rel_err(&flat_t(&up_t(&m)), &flat_t(&transform(&c["mean_inv"])));
        let e_c = rel_err(&flat(&up_m(&cov)), &flat(&mat6(&c["cov_inv"])));
        wi.add(e_m.max(e_c), &l);
    }
    for w in [wg, wg2, wgm, wl, wi] {
        w.check(bound);
    }
}

#[test]
fn concat_and_invert_f64() {
    run_concat::<f64>(F64_BOUND);
}

#[test]
fn concat_and_invert_f32() {
    run_concat::<f32>(F32_BOUND);
}

// pose_fusion.json: tests/fusion_golden.rs.

#[test]
fn estimators() {
    for (file, is_rot) in [
        ("estimate_transform.json", false),
        ("estimate_rotation.json", true),
    ] {
        let mut wm = Worst::new(&format!("{file} mean"));
        let mut wc = Worst::new(&format!("{file} cov"));
        let mut beyond = 0;
        for c in cases(file) {
            let l = label(&c);
            let (mean_key, cov_key) = if c["converged"] == true {
                ("mean", "cov")
            } else if c.get("fixed_point_mean").is_some() {
                beyond += 1;
                ("fixed_point_mean", "fixed_point_cov")
            } else {
                continue;
            };
            let samples = c["samples"].as_array().unwrap();
            let (em, ec, converged) = if is_rot {
                let s: Vec<Mat3<f64>> = samples.iter().map(|x| Matrix(mat_n::<3, 3>(x))).collect();
                let e = uncertainty::estimate_gaussian_rotation(&s).unwrap();
                let rm: Mat3<f64> = Matrix(mat_n::<3, 3>(&c[mean_key]));
                let rc: Mat3<f64> = Matrix(mat_n::<3, 3>(&c[cov_key]));
                (
                    rel_err(&flat(&e.mean), &flat(&rm)),
                    rel_err(&flat(&e.cov), &flat(&rc)),
                    e.converged,
                )
            } else {
                let s: Vec<_> = samples.iter().map(transform).collect();
                let e = uncertainty::estimate_gaussian_transform(&s).unwrap();
                (
                    rel_err(&flat_t(&e.mean), &flat_t(&transform(&c[mean_key]))),
                    rel_err(&flat(&e.cov), &flat(&mat6(&c[cov_key]))),
                    e.converged,
                )
            };
            assert!(converged, "{file} {l}: ours did not converge");
            wm.add(em, &l);
            wc.add(ec, &l);
        }
        println!("{file}: {beyond} cases beyond pytransform3d's 60° limit compared with the consistent fixed point");
        assert!(beyond > 0);
        wm.check(F64_BOUND);
        wc.check(F64_BOUND);
    }
}
