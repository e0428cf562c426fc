//! Non-finite results (issue class: JSON overflow): JSON has no infinity, and the output
//! uses `null` for an infinite joint limit, so a result that overflows is an error with
//! nothing on standard output, never a `null` in the pose or covariance.

mod common;
use common::*;

/// One seed case with `var·I` as every joint's covariance.
fn case(var: f64) -> String {
    serde_json::json!({"cases": [{"thetas": vec![0.1; 6], "covs": vec![diag(var); 6]}]}).to_string()
}

#[test]
fn an_overflowing_covariance_is_an_error() {
    // With v·I as each joint's covariance, each joint adds Ad·vI·Adᵀ, whose rotation block
    // is v·R·Rᵀ = v·I: the tool's rotation variances are 6v. 6·6e37 > f32::MAX = 3.40e38
    // and 6·5e307 > f64::MAX = 1.80e308, while every input is finite in its scalar.
    for (scalar, var) in [("f32", 6e37), ("f64", 5e307)] {
        let o = run_bytes(
            &refs(&seed_args("eval", &["--scalar", scalar])),
            case(var).as_bytes(),
        );
        let line = one_line_error(&o, 1);
        assert!(
            line.contains("case 0") && line.contains("not finite"),
            "{scalar}: {line}"
        );
        assert!(o.stdout.is_empty(), "{scalar}: partial output");
    }
}

#[test]
fn large_finite_results_are_written_and_null_means_only_an_infinite_limit() {
    let o = run_bytes(&refs(&seed_args("eval", &[])), case(1e300).as_bytes());
    success(&o);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let r = &v["results"][0];
    for part in ["pose", "cov", "thetas_clipped"] {
        assert!(!r[part].to_string().contains("null"), "{part}");
    }
    // The seed's joints 4 to 6 have no limits: null there, as documented.
    assert_eq!(v["chain"]["limits"][3], serde_json::json!([null, null]));
    assert!(r["cov"][0][0].as_f64().unwrap() >= 6e300);
}
