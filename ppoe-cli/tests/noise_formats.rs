//! Issue #30 points 4, 6, 8: datasheet noise (`sigma2` without `cov`, `--joint-sigma`),
//! one JSON shape for poses (eval's output reads back as the core's `UncertainPose`),
//! `eval --format ros`, and `--pretty` with one matrix row per line. Expected values are
//! derived here by hand (screw axes from the URDF's origins and axes, the ROS block
//! permutation, the quaternion by the trace formula), not taken from the command.

mod common;

use common::{fresh_dir, one_line_error, run, success};
use serde_json::{json, Value};
use std::path::Path;

/// A revolute joint about y, 0.5 m up; a prismatic joint along z, 1 m out in x; the tool
/// 0.2 m further out in x.
const URDF: &str = r#"<robot name="two">
  <link name="base"/><link name="upper"/><link name="slider"/><link name="tool"/>
  <joint name="pitch" type="revolute"><parent link="base"/><child link="upper"/>
    <origin xyz="0 0 0.5"/><axis xyz="0 1 0"/><limit lower="-2" upper="2" effort="1" velocity="1"/></joint>
  <joint name="lift" type="prismatic"><parent link="upper"/><child link="slider"/>
    <origin xyz="1 0 0"/><axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="mount" type="fixed"><parent link="slider"/><child link="tool"/>
    <origin xyz="0.2 0 0"/></joint>
</robot>"#;

/// The screw axes by hand: revolute (ω, q × ω), q on the axis at home; prismatic (0, axis).
const SCREWS: [[f64; 6]; 2] = [
    // ω = (0, 1, 0), q = (0, 0, 0.5): q × ω = (−0.5, 0, 0).
    [0.0, 1.0, 0.0, -0.5, 0.0, 0.0],
    [0.0, 0.0, 0.0, 0.0, 0.0, 1.0],
];

const SIGMAS: [f64; 2] = [2e-3, 5e-4];

fn outer(s: &[f64; 6], sigma2: f64) -> Value {
    let rows: Vec<Vec<f64>> = (0..6)
        .map(|i| (0..6).map(|j| sigma2 * s[i] * s[j]).collect())
        .collect();
    json!(rows)
}

/// Writes the URDF, a cases file (joint values only) and a cases file with the hand-made
/// covariances; returns the directory.
fn setup(name: &str) -> std::path::PathBuf {
    let dir = fresh_dir(name);
    std::fs::write(dir.join("two.urdf"), URDF).unwrap();
    let thetas = [[0.3, 0.1], [-0.7, -0.25]];
    let bare: Vec<Value> = thetas.iter().map(|t| json!({"thetas": t})).collect();
    std::fs::write(dir.join("bare.json"), json!({"cases": bare}).to_string()).unwrap();
    let covs: Vec<Value> = (0..2)
        .map(|i| outer(&SCREWS[i], SIGMAS[i] * SIGMAS[i]))
        .collect();
    let full: Vec<Value> = thetas
        .iter()
        .map(|t| json!({"thetas": t, "covs": covs}))
        .collect();
    std::fs::write(dir.join("full.json"), json!({"cases": full}).to_string()).unwrap();
    dir
}

fn eval(dir: &Path, extra: &[&str]) -> std::process::Output {
    let urdf = dir.join("two.urdf");
    let mut args = vec![
        "eval",
        "--urdf",
        urdf.to_str().unwrap(),
        "--base",
        "base",
        "--tip",
        "tool",
    ];
    args.extend_from_slice(extra);
    run(&args)
}

fn eval_ok(dir: &Path, extra: &[&str]) -> Value {
    let out = eval(dir, extra);
    success(&out);
    serde_json::from_slice(&out.stdout).unwrap()
}

#[test]
fn sigma2_files_and_joint_sigma_are_the_hand_made_covariances() {
    let dir = setup("datasheet");
    let p = |f: &str| dir.join(f).to_str().unwrap().to_string();
    let reference = eval_ok(&dir, &["--input", &p("full.json")]);
    let sig = format!("{},{}", SIGMAS[0], SIGMAS[1]);
    let from_flag = eval_ok(&dir, &["--input", &p("bare.json"), "--joint-sigma", &sig]);
    assert_eq!(from_flag, reference);
    let s2 = SIGMAS.map(|s| s * s);
    let file = json!({"model": "joint", "joints": [
        {"name": "pitch", "sigma2": s2[0]}, {"name": "lift", "sigma2": s2[1]}]});
    std::fs::write(dir.join("sigma2.json"), file.to_string()).unwrap();
    let from_file = eval_ok(
        &dir,
        &["--input", &p("bare.json"), "--noise", &p("sigma2.json")],
    );
    assert_eq!(from_file, reference);
    // The equivalent full-cov file gives the same output too.
    let covs: Vec<Value> = (0..2).map(|i| outer(&SCREWS[i], s2[i])).collect();
    let file =
        json!({"joints": [{"name": "pitch", "cov": covs[0]}, {"name": "lift", "cov": covs[1]}]});
    std::fs::write(dir.join("cov.json"), file.to_string()).unwrap();
    let from_cov = eval_ok(
        &dir,
        &["--input", &p("bare.json"), "--noise", &p("cov.json")],
    );
    assert_eq!(from_cov, reference);
    // The same covariances baked into a table.
    let urdf = p("two.urdf");
    let table = |extra: &[&str]| {
        let mut a = vec!["table", "--urdf", &urdf, "--base", "base", "--tip", "tool"];
        a.extend_from_slice(extra);
        let out = run(&a);
        success(&out);
        let text = String::from_utf8(out.stdout).unwrap();
        text[text.find("pub const TWO_NOISE").unwrap()..].to_string()
    };
    let baked = table(&["--joint-sigma", &sig]);
    assert!(
        baked.contains("[-0.0, -2e-6, -0.0, 1e-6, -0.0, -0.0]"),
        "{baked}"
    );
    assert_eq!(baked, table(&["--noise", &p("sigma2.json")]));
}

#[test]
fn joint_sigma_errors() {
    let dir = setup("datasheet-errors");
    let bare = dir.join("bare.json");
    let bare = bare.to_str().unwrap();
    let e = one_line_error(&eval(&dir, &["--input", bare, "--joint-sigma", "1e-3"]), 1);
    assert!(
        e.contains("1 joint sigmas given") && e.contains("2 moving joints (pitch, lift)"),
        "{e}"
    );
    for bad in ["1e-3,-1e-3", "1e-3,inf", "1e-3,NaN"] {
        let e = one_line_error(&eval(&dir, &["--input", bare, "--joint-sigma", bad]), 1);
        assert!(e.contains("joint sigma 1 ('lift')"), "{e}");
    }
    let e = one_line_error(
        &eval(&dir, &["--input", bare, "--joint-sigma", "1e-3,x"]),
        2,
    );
    assert!(e.contains("--joint-sigma"), "{e}");
    let file = dir.join("n.json");
    std::fs::write(
        &file,
        r#"{"joints": [{"name": "pitch", "sigma2": 1e-6}, {"name": "lift"}]}"#,
    )
    .unwrap();
    let n = file.to_str().unwrap();
    let e = one_line_error(
        &eval(
            &dir,
            &["--input", bare, "--noise", n, "--joint-sigma", "1,1"],
        ),
        2,
    );
    assert!(e.contains("cannot be used with"), "{e}");
    let e = one_line_error(&eval(&dir, &["--input", bare, "--noise", n]), 1);
    assert!(
        e.contains("joint 1 ('lift') has neither \"cov\"") && e.contains("n.json"),
        "{e}"
    );
}

/// Eval's default output is the core's serde shape: each result reads as an
/// `UncertainPose` (feature serde), pose and covariance bit for bit.
#[test]
fn eval_results_read_back_as_uncertain_poses() {
    use ppoe::chain::UncertainPose;
    let dir = setup("uncertain-pose");
    let full = dir.join("full.json");
    let out = eval_ok(&dir, &["--input", full.to_str().unwrap()]);
    for r in out["results"].as_array().unwrap() {
        let u: UncertainPose<f64> = serde_json::from_value(r.clone()).unwrap();
        let pose: [[f64; 4]; 4] = serde_json::from_value(r["pose"].clone()).unwrap();
        let cov: [[f64; 6]; 6] = serde_json::from_value(r["cov"].clone()).unwrap();
        assert_eq!(u.pose.to_matrix4(), pose);
        assert_eq!(u.cov.0, cov);
        // And back: the core writes the same pose and covariance.
        let again = serde_json::to_value(u).unwrap();
        assert_eq!((&again["pose"], &again["cov"]), (&r["pose"], &r["cov"]));
    }
}

/// The quaternion (x, y, z, w) of a rotation matrix by the trace formula (w > 0 here).
fn quaternion(r: &[[f64; 4]; 4]) -> [f64; 4] {
    let w = (1.0 + r[0][0] + r[1][1] + r[2][2]).sqrt() / 2.0;
    [
        (r[2][1] - r[1][2]) / (4.0 * w),
        (r[0][2] - r[2][0]) / (4.0 * w),
        (r[1][0] - r[0][1]) / (4.0 * w),
        w,
    ]
}

/// ROS's covariance of a right perturbation by hand: rotate both blocks into the parent
/// frame (δθ = R·ω, δp = R·v), then put translation first.
fn ros_by_hand(r: &[[f64; 4]; 4], cov: &[[f64; 6]; 6]) -> [[f64; 6]; 6] {
    // B = blockdiag(R, R)
    let b = |i: usize, k: usize| if i / 3 == k / 3 { r[i % 3][k % 3] } else { 0.0 };
    let mut rotated = [[0.0; 6]; 6];
    for (i, row) in rotated.iter_mut().enumerate() {
        for (j, x) in row.iter_mut().enumerate() {
            *x = (0..6)
                .flat_map(|k| (0..6).map(move |l| (k, l)))
                .map(|(k, l)| b(i, k) * cov[k][l] * b(j, l))
                .sum();
        }
    }
    let swap = |i: usize| (i + 3) % 6;
    let mut out = [[0.0; 6]; 6];
    for i in 0..6 {
        for j in 0..6 {
            out[i][j] = rotated[swap(i)][swap(j)];
        }
    }
    out
}

#[test]
fn ros_format_is_pose_with_covariance_in_the_parent_frame() {
    let dir = setup("ros");
    let full = dir.join("full.json");
    let full = full.to_str().unwrap();
    let json_out = eval_ok(&dir, &["--input", full]);
    let ros_out = eval_ok(&dir, &["--input", full, "--format", "ros"]);
    assert_eq!(ros_out["chain"], json_out["chain"]);
    for (j, r) in json_out["results"]
        .as_array()
        .unwrap()
        .iter()
        .zip(ros_out["results"].as_array().unwrap())
    {
        let pose: [[f64; 4]; 4] = serde_json::from_value(j["pose"].clone()).unwrap();
        let cov: [[f64; 6]; 6] = serde_json::from_value(j["cov"].clone()).unwrap();
        let p = &r["pose"]["position"];
        assert_eq!(
            [&p["x"], &p["y"], &p["z"]].map(|v| v.as_f64().unwrap()),
            [0, 1, 2].map(|i| pose[i][3])
        );
        let o = &r["pose"]["orientation"];
        let q = [&o["x"], &o["y"], &o["z"], &o["w"]].map(|v| v.as_f64().unwrap());
        let sign = if q[3] < 0.0 { -1.0 } else { 1.0 };
        for (a, b) in q.iter().zip(quaternion(&pose)) {
            assert!((sign * a - b).abs() < 1e-14, "{q:?}");
        }
        let c: Vec<f64> = serde_json::from_value(r["covariance"].clone()).unwrap();
        assert_eq!(c.len(), 36);
        let hand = ros_by_hand(&pose, &cov);
        let scale = hand.iter().flatten().fold(0.0f64, |m, x| m.max(x.abs()));
        for (k, x) in c.iter().enumerate() {
            assert!(
                (x - hand[k / 6][k % 6]).abs() <= 1e-14 * scale,
                "entry {k}: {x} vs {}",
                hand[k / 6][k % 6]
            );
        }
    }
    let e = one_line_error(
        &eval(
            &dir,
            &[
                "--input",
                full,
                "--format",
                "ros",
                "--convention",
                "pytransform3d",
            ],
        ),
        1,
    );
    assert!(e.contains("--convention ppoe or left"), "{e}");
}

#[test]
fn pretty_prints_a_matrix_row_per_line() {
    let dir = setup("pretty");
    let full = dir.join("full.json");
    let out = eval(&dir, &["--input", full.to_str().unwrap(), "--pretty"]);
    success(&out);
    let text = String::from_utf8(out.stdout).unwrap();
    let compact = eval_ok(&dir, &["--input", full.to_str().unwrap()]);
    assert_eq!(serde_json::from_str::<Value>(&text).unwrap(), compact);
    // Rows of 6 on their own lines: 2 screw axes and 2 × 6 covariance rows; rows of 4:
    // the home pose and 2 poses.
    let rows = |n: usize| {
        text.lines()
            .map(|l| l.trim().trim_end_matches(','))
            .filter(|t| t.starts_with('[') && t.ends_with(']') && t.matches(',').count() == n - 1)
            .count()
    };
    assert_eq!((rows(6), rows(4)), (2 + 2 * 6, 4 + 2 * 4), "{text}");
    assert!(text.lines().count() < 60, "{text}");
}

/// The numbers of the demo's printed initial pose (4 rows after its title).
fn demo_pose(extra: &[&str], name: &str) -> Vec<String> {
    let dir = fresh_dir(name);
    let mut args = vec![
        "demo",
        "--frames",
        "1",
        "--grid",
        "2",
        "--out",
        dir.to_str().unwrap(),
    ];
    args.extend_from_slice(extra);
    let out = run(&args);
    success(&out);
    String::from_utf8(out.stdout)
        .unwrap()
        .lines()
        .skip_while(|l| !l.starts_with("initial pose"))
        .skip(1)
        .take(4)
        .flat_map(|l| {
            let cells = l.trim().trim_matches(['[', ']']);
            cells
                .split(',')
                .map(|x| x.trim().to_string())
                .collect::<Vec<_>>()
        })
        .collect()
}

#[test]
fn demo_prints_six_significant_digits_unless_asked() {
    let full = demo_pose(&["--precision", "full"], "demo-full");
    let short = demo_pose(&[], "demo-default");
    let three = demo_pose(&["--precision", "3"], "demo-three");
    assert_eq!((full.len(), short.len(), three.len()), (16, 16, 16));
    for ((f, s), t) in full.iter().zip(&short).zip(&three) {
        let x: f64 = f.parse().unwrap();
        // Full: 17 significant digits, so the value reads back as itself.
        let mantissa = |v: &str| {
            v.split('e')
                .next()
                .unwrap()
                .trim_start_matches('-')
                .replace('.', "")
                .len()
        };
        assert_eq!(
            (mantissa(f), mantissa(s), mantissa(t)),
            (17, 6, 3),
            "{f} {s} {t}"
        );
        let (sv, tv): (f64, f64) = (s.parse().unwrap(), t.parse().unwrap());
        assert!((sv - x).abs() <= 5e-6 * x.abs().max(1e-300), "{s} vs {f}");
        assert!((tv - x).abs() <= 5e-3 * x.abs().max(1e-300), "{t} vs {f}");
    }
    for bad in ["0", "18", "x", "-1"] {
        let dir = fresh_dir("demo-bad-precision");
        let out = run(&["demo", "--precision", bad, "--out", dir.to_str().unwrap()]);
        let e = one_line_error(&out, 2);
        assert!(e.contains("--precision"), "{e}");
    }
}

#[test]
fn demo_takes_joint_sigmas_for_the_seed() {
    let dir = fresh_dir("demo-sigma");
    let out = run(&[
        "demo",
        "--joint-sigma",
        "1e-3,1e-3",
        "--out",
        dir.to_str().unwrap(),
    ]);
    let e = one_line_error(&out, 1);
    assert!(
        e.contains("2 joint sigmas") && e.contains("6 moving joints (joint1, joint2"),
        "{e}"
    );
    // Zero noise: a zero covariance, printed as zeros.
    let zero = demo_pose(&["--joint-sigma", "0,0,0,0,0,0"], "demo-sigma-zero");
    assert_eq!(zero.len(), 16);
}

/// `mesh` and `render` take `--joint-sigma` through the same path as `eval`: the same mesh
/// as with the hand-made covariances.
#[test]
fn mesh_with_joint_sigma_is_the_mesh_of_the_hand_made_covariances() {
    let dir = setup("mesh-sigma");
    let urdf = dir.join("two.urdf");
    let mesh = |input: &str, extra: &[&str], out: &str| {
        let out_dir = dir.join(out);
        let input = dir.join(input);
        let mut a = vec![
            "mesh",
            "--urdf",
            urdf.to_str().unwrap(),
            "--base",
            "base",
            "--tip",
            "tool",
            "--input",
            input.to_str().unwrap(),
            "--format",
            "obj",
            "--grid",
            "4",
            "--out",
            out_dir.to_str().unwrap(),
        ];
        a.extend_from_slice(extra);
        success(&run(&a));
        std::fs::read(out_dir.join("ppoe-mesh-0.obj")).unwrap()
    };
    let sig = format!("{},{}", SIGMAS[0], SIGMAS[1]);
    let reference = mesh("full.json", &[], "ref");
    assert_eq!(
        mesh("bare.json", &["--joint-sigma", &sig], "sig"),
        reference
    );
}
