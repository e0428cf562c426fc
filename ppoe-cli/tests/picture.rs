//! The pictures end to end through the `ppoe` binary: the demo's PNG shows the seed's
//! URDF visuals in their material colours, its GIF is small, its HTML view is
//! self-contained; `render --format html` works for robots without visuals; primitive
//! and mesh visuals of any URDF are drawn, missing meshes skipped with a notice.
//!
//! Expected colours come from the URDFs' `<material>` values, not from the drawing code.

use serde_json::{json, Value};
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

const BIN: &str = env!("CARGO_BIN_EXE_ppoe");

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

fn tmp(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("ppoe-picture-tests")
        .join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn run(args: &[&str]) -> Output {
    let out = Command::new(BIN)
        .args(args)
        .current_dir(repo())
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "ppoe {args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    out
}

fn decode_png(path: &Path) -> Vec<[u8; 3]> {
    let decoder = png::Decoder::new(std::fs::File::open(path).unwrap());
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut buf).unwrap();
    assert_eq!(info.color_type, png::ColorType::Rgb);
    buf.truncate(info.buffer_size());
    buf.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect()
}

/// Pixels whose colour is the material colour `rgb` under some shading: the same hue
/// (channel ratios within 15 %) and not near white or black.
fn shaded_count(px: &[[u8; 3]], rgb: [f64; 3]) -> usize {
    let m = rgb.iter().cloned().fold(0.0, f64::max);
    px.iter()
        .filter(|p| {
            let pm = p.iter().map(|&c| c as f64).fold(0.0, f64::max);
            pm >= 60.0
                && (0..3).all(|k| (p[k] as f64 / pm - rgb[k] / m).abs() < 0.15)
                && p.iter().map(|&c| c as u32).sum::<u32>() < 3 * 250
        })
        .count()
}

/// The JSON data inside a page written by `--format html`.
fn page_data(html: &str) -> Value {
    let start = html
        .find(r#"<script id="ppoe-data" type="application/json">"#)
        .unwrap();
    let rest = &html[start..];
    let body = &rest[rest.find('>').unwrap() + 1..rest.find("</script>").unwrap()];
    serde_json::from_str(body).unwrap()
}

/// A page that needs no network: no remote address, no external script, style or image.
fn assert_self_contained(html: &str) {
    for bad in [
        "http://",
        "https://",
        "<script src",
        "<link",
        "<img",
        "@import",
    ] {
        assert!(!html.contains(bad), "the page contains {bad}");
    }
}

#[test]
fn demo_draws_the_seed_visuals_and_writes_a_small_gif_and_a_page() {
    let dir = tmp("demo");
    let out = run(&["demo", "--frames", "20", "--out", dir.to_str().unwrap()]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(stdout.contains("ppoe-seed.html"), "{stdout}");
    assert!(String::from_utf8_lossy(&out.stderr).contains("20/20"));

    // seed_visuals.urdf: arm_blue 0.2 0.2 1.0, joint_orange 1.0 0.5 0.0.
    let px = decode_png(&dir.join("ppoe-seed.png"));
    let blue = shaded_count(&px, [0.2, 0.2, 1.0]);
    let orange = shaded_count(&px, [1.0, 0.5, 0.0]);
    assert!(blue > 3000 && orange > 1000, "blue {blue}, orange {orange}");

    // 200 frames must fit in 2.5 MB: 20 frames (one full, 19 differences) in a tenth.
    let gif = std::fs::metadata(dir.join("ppoe-seed.gif")).unwrap().len();
    assert!(gif <= 250_000, "{gif} bytes for 20 frames");

    let html = std::fs::read_to_string(dir.join("ppoe-seed.html")).unwrap();
    assert_self_contained(&html);
    let data = page_data(&html);
    let frames = data["frames"].as_array().unwrap();
    assert_eq!(frames.len(), 20);
    assert!(data["label"].as_str().unwrap().contains("19.9 %"));
    let shapes = data["shapes"].as_array().unwrap();
    assert!(!shapes.is_empty());
    for f in frames {
        let bodies = f["bodies"].as_array().unwrap();
        assert_eq!(bodies.len(), 8, "one body per <visual>");
        for b in bodies {
            let rgb = b["rgb"].clone();
            assert!(
                [json!([51, 51, 255]), json!([255, 128, 0]), json!([0, 0, 0])].contains(&rgb),
                "{rgb}"
            );
        }
    }
}

fn zero_cases(n_joints: usize, n_cases: usize) -> String {
    let mut cov = vec![vec![0.0; 6]; 6];
    cov[2][2] = 0.02;
    cov[3][3] = 1e-4;
    let cases: Vec<Value> = (0..n_cases)
        .map(|c| json!({"thetas": vec![0.1 * c as f64; n_joints], "covs": vec![cov.clone(); n_joints]}))
        .collect();
    json!({ "cases": cases }).to_string()
}

#[test]
fn render_html_works_for_robots_without_visuals() {
    for (urdf, base, tip, n) in [
        ("prismatic.urdf", "base_link", "tool0", 7),
        ("tree.urdf", "base_footprint", "left_tip", 6),
    ] {
        let dir = tmp(&format!("render-{urdf}"));
        let input = dir.join("cases.json");
        std::fs::write(&input, zero_cases(n, 3)).unwrap();
        let path = format!("test_data/urdf/{urdf}");
        let args = [
            "render",
            "--urdf",
            &path,
            "--base",
            base,
            "--tip",
            tip,
            "--input",
            input.to_str().unwrap(),
            "--format",
            "html",
            "--out",
            dir.to_str().unwrap(),
        ];
        run(&args);
        let html = std::fs::read_to_string(dir.join("ppoe-render.html")).unwrap();
        assert_self_contained(&html);
        let data = page_data(&html);
        let frames = data["frames"].as_array().unwrap();
        assert_eq!(frames.len(), 3, "{urdf}");
        for f in frames {
            assert!(f["bodies"].as_array().unwrap().is_empty(), "{urdf}");
            // The stick figure: base, every moving joint, tool.
            assert_eq!(f["joints"].as_array().unwrap().len(), n + 2, "{urdf}");
        }
    }
}

/// A binary STL of a tetrahedron with a 0.2 m base and 0.3 m height.
fn tetrahedron_stl() -> Vec<u8> {
    let v = [
        [0.0f32, 0.0, 0.0],
        [0.2, 0.0, 0.0],
        [0.0, 0.2, 0.0],
        [0.05, 0.05, 0.3],
    ];
    let faces = [[0, 2, 1], [0, 1, 3], [1, 2, 3], [2, 0, 3]];
    let mut out = vec![0u8; 80];
    out.extend_from_slice(&(faces.len() as u32).to_le_bytes());
    for f in faces {
        out.extend_from_slice(&[0u8; 12]);
        for i in f {
            for c in v[i] {
                out.extend_from_slice(&c.to_le_bytes());
            }
        }
        out.extend_from_slice(&[0u8; 2]);
    }
    out
}

const VISUAL_URDF: &str = r#"<?xml version="1.0"?>
<robot name="shapes">
  <material name="magenta"><color rgba="1 0 1 1"/></material>
  <link name="base">
    <visual><origin xyz="0 0 0.05"/><geometry><box size="0.3 0.3 0.1"/></geometry>
      <material name="magenta"/></visual>
  </link>
  <link name="arm">
    <visual><origin xyz="0 0 0.25"/><geometry><sphere radius="0.08"/></geometry>
      <material><color rgba="0 0.8 0 1"/></material></visual>
    <visual><origin xyz="0.1 0 0.4"/><geometry><mesh filename="package://shapes/meshes/tetra.stl"/></geometry>
      <material><color rgba="1 1 0 1"/></material></visual>
    <visual><geometry><mesh filename="meshes/missing.stl"/></geometry></visual>
    <visual><geometry><mesh filename="meshes/tetra.dae"/></geometry></visual>
  </link>
  <link name="tool"/>
  <joint name="yaw" type="revolute">
    <origin xyz="0 0 0.1"/><parent link="base"/><child link="arm"/>
    <axis xyz="0 0 1"/><limit lower="-3" upper="3"/>
  </joint>
  <joint name="mount" type="fixed">
    <origin xyz="0.3 0 0.6"/><parent link="arm"/><child link="tool"/>
  </joint>
</robot>
"#;

/// `ppoe render` of the `shapes` URDF at `urdf`, one case at zero, as PNG into `dir`, with
/// `extra` arguments; its standard error.
fn render_shapes(urdf: &Path, dir: &Path, extra: &[&str]) -> String {
    let input = dir.join("cases.json");
    std::fs::write(&input, zero_cases(1, 1)).unwrap();
    let (urdf, input, out) = (
        urdf.to_str().unwrap(),
        input.to_str().unwrap(),
        dir.to_str().unwrap(),
    );
    let mut args = vec![
        "render", "--urdf", urdf, "--base", "base", "--tip", "tool", "--input", input, "--format",
        "png", "--out", out,
    ];
    args.extend_from_slice(extra);
    String::from_utf8_lossy(&run(&args).stderr).into_owned()
}

#[test]
fn primitives_and_meshes_are_drawn_and_missing_meshes_noted() {
    let dir = tmp("shapes");
    std::fs::create_dir_all(dir.join("meshes")).unwrap();
    std::fs::write(dir.join("meshes/tetra.stl"), tetrahedron_stl()).unwrap();
    std::fs::write(dir.join("meshes/tetra.dae"), "<COLLADA/>").unwrap();
    let urdf = dir.join("shapes.urdf");
    std::fs::write(&urdf, VISUAL_URDF).unwrap();
    let stderr = render_shapes(&urdf, &dir, &[]);
    assert!(stderr.contains("missing.stl' not found"), "{stderr}");
    assert!(stderr.contains("tetra.dae"), "{stderr}");
    let px = decode_png(&dir.join("ppoe-render-0.png"));
    for (name, rgb, min) in [
        ("box", [1.0, 0.0, 1.0], 2000),
        ("sphere", [0.0, 0.8, 0.0], 1000),
        ("mesh", [1.0, 1.0, 0.0], 500),
    ] {
        let n = shaded_count(&px, rgb);
        assert!(n >= min, "{name}: {n} pixels");
    }
}

/// Mesh files that are not regular files, an OBJ naming `/dev/zero` as its material
/// library and a mesh that overflows when scaled: each is skipped (or read without its
/// materials) with a notice naming it, and the picture is written.
#[test]
fn hostile_mesh_files_are_skipped_by_name() {
    let dir = tmp("hostile-meshes");
    std::fs::create_dir_all(dir.join("meshes")).unwrap();
    std::fs::write(dir.join("meshes/tetra.stl"), tetrahedron_stl()).unwrap();
    let obj = "mtllib /dev/zero\nv 0 0 0\nv 0.2 0 0\nv 0 0.2 0\nv 0 0 0.2\n\
               f 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n";
    std::fs::write(dir.join("meshes/tetra.obj"), obj).unwrap();
    let big = obj.replace("v 0.2 0 0", "v 1e30 0 0");
    std::fs::write(dir.join("meshes/big.obj"), big).unwrap();
    let fifo = dir.join("meshes/fifo.stl");
    assert!(Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .unwrap()
        .success());
    std::os::unix::fs::symlink("/dev/zero", dir.join("meshes/zero.stl")).unwrap();
    let urdf = VISUAL_URDF.replace(
        r#"<geometry><mesh filename="meshes/missing.stl"/>"#,
        r#"<geometry><mesh filename="meshes/fifo.stl"/></geometry></visual>
    <visual><geometry><mesh filename="meshes/zero.stl"/></geometry></visual>
    <visual><geometry><mesh filename="meshes/big.obj" scale="1e300 1 1"/></geometry></visual>
    <visual><geometry><mesh filename="meshes/tetra.obj"/>"#,
    );
    let path = dir.join("shapes.urdf");
    std::fs::write(&path, urdf).unwrap();
    let stderr = render_shapes(&path, &dir, &[]);
    for (name, why) in [
        ("fifo.stl", "not a regular file"),
        ("zero.stl", "not a regular file"),
        ("big.obj", "not finite after scaling"),
    ] {
        assert!(
            stderr.lines().any(|l| l.contains(name) && l.contains(why)),
            "{name}: {why}: {stderr}"
        );
    }
    assert!(!stderr.contains("tetra.obj"), "{stderr}");
    assert!(dir.join("ppoe-render-0.png").is_file());
    // A bound below the tetrahedra's 4 triangles reduces them (here to nothing: skipped).
    let stderr = render_shapes(&path, &dir, &["--mesh-triangles", "2"]);
    assert!(
        stderr
            .lines()
            .any(|l| l.contains("tetra.obj") && l.contains("reduc")),
        "{stderr}"
    );
}

/// `render --format html` of the UR-style test robot: its COLLADA meshes (a cube of 12
/// triangles, a millimetre Y-up tetrahedron of 4) are in the page, with the bounding
/// boxes their files' comments derive by hand, when `--package-dir` says where their
/// package is; without it they are skipped as an unknown package and the page is
/// still written.
#[test]
fn collada_meshes_are_drawn_from_their_package_dir() {
    let dir = tmp("collada");
    let input = dir.join("cases.json");
    std::fs::write(&input, zero_cases(3, 1)).unwrap();
    let (i, d) = (input.to_str().unwrap(), dir.to_str().unwrap());
    let args = |extra: &[&'static str]| {
        let mut a = vec![
            "render",
            "--urdf",
            "test_data/urdf/ur_style.urdf",
            "--base",
            "base_link",
            "--tip",
            "tool0",
            "--input",
            i,
            "--format",
            "html",
            "--out",
            d,
        ];
        a.extend_from_slice(extra);
        a
    };
    let package = [
        "--package-dir",
        "ppoe_ur_style=test_data/packages/ppoe_ur_style",
    ];
    let out = run(&args(&package));
    let html = std::fs::read_to_string(dir.join("ppoe-render.html")).unwrap();
    let shapes = page_data(&html)["shapes"].as_array().unwrap().clone();
    let mut found: Vec<(usize, [[f64; 2]; 3])> = shapes
        .iter()
        .map(|s| {
            let mut b = [[f64::INFINITY, f64::NEG_INFINITY]; 3];
            // Flat x, y, z triples, rounded to 1e-7 m (exact for these decimals).
            let v = s["v"].as_array().unwrap();
            for (n, x) in v.iter().enumerate() {
                let (k, x) = (n % 3, x.as_f64().unwrap());
                b[k] = [b[k][0].min(x), b[k][1].max(x)];
            }
            (s["f"].as_array().unwrap().len(), b)
        })
        .collect();
    found.sort_by_key(|(n, _)| *n);
    let cube = [[-0.05, 0.05], [-0.05, 0.05], [0.0, 0.1]];
    let tetra = [[0.0, 0.1], [-0.1, 0.0], [0.0, 0.1]];
    assert_eq!(found, vec![(4, tetra), (12, cube)]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("unknown package 'ppoe_missing_description'"),
        "{stderr}"
    );
    assert!(!stderr.contains("base.dae"), "{stderr}");
    // Without the package's directory: skipped by name, the page written all the same.
    std::fs::remove_file(dir.join("ppoe-render.html")).unwrap();
    let stderr = String::from_utf8_lossy(&run(&args(&[])).stderr).into_owned();
    for mesh in ["base.dae", "shoulder_mm.dae"] {
        assert!(
            stderr.lines().any(|l| l.contains(mesh)
                && l.contains("unknown package 'ppoe_ur_style' (give --package-dir")),
            "{stderr}"
        );
    }
    let html = std::fs::read_to_string(dir.join("ppoe-render.html")).unwrap();
    assert!(page_data(&html)["shapes"].as_array().unwrap().is_empty());
}

/// A `--package-dir` without `=` is a usage error; one that is not a directory an input
/// error naming it.
#[test]
fn bad_package_dirs_are_refused() {
    let dir = tmp("package-dir");
    let input = dir.join("cases.json");
    std::fs::write(&input, zero_cases(3, 1)).unwrap();
    let (i, d) = (input.to_str().unwrap(), dir.to_str().unwrap());
    for (value, code, expected) in [
        ("ppoe_ur_style", 2, "expected NAME=PATH"),
        ("=x", 2, "expected NAME=PATH"),
        (
            "ppoe_ur_style=test_data/urdf/ur_style.urdf",
            1,
            "not a directory",
        ),
    ] {
        let out = Command::new(BIN)
            .args([
                "render",
                "--urdf",
                "test_data/urdf/ur_style.urdf",
                "--base",
                "base_link",
                "--tip",
                "tool0",
                "--input",
                i,
                "--out",
                d,
                "--package-dir",
                value,
            ])
            .current_dir(repo())
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(code), "{value}: {stderr}");
        assert!(stderr.contains(expected), "{value}: {stderr}");
    }
}

/// The vertices of an OBJ written by `ppoe mesh`.
fn obj_vertices(path: &Path) -> Vec<[f64; 3]> {
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .filter_map(|l| l.strip_prefix("v "))
        .map(|l| {
            let v: Vec<f64> = l.split(' ').map(|x| x.parse().unwrap()).collect();
            [v[0], v[1], v[2]]
        })
        .collect()
}

/// Real noise (3 mrad per joint, rotation only) on the UR-style arm, whose 1σ surface is
/// a few millimetres across.
fn small_noise_cases() -> String {
    let mut cov = vec![vec![0.0; 6]; 6];
    for (k, row) in cov.iter_mut().enumerate().take(3) {
        row[k] = 9e-6;
    }
    json!({"cases": [{"thetas": [0.0, 0.5, 0.5], "covs": vec![cov; 3]}]}).to_string()
}

/// `--exaggerate` (issue #30, point 5): `mesh --exaggerate 1` is the mesh of the existing
/// output byte for byte; with 7 every surface vertex is 7 times as far from the tool
/// (the skeleton and the second-order mean unchanged), and the header says ×7.
#[test]
fn exaggerate_scales_the_surface_about_the_tool_and_says_so() {
    let dir = tmp("exaggerate-mesh");
    let input = dir.join("cases.json");
    std::fs::write(&input, small_noise_cases()).unwrap();
    let (i, d) = (input.to_str().unwrap(), dir.to_str().unwrap());
    let mesh = |extra: &[&str], name: &str| {
        let mut a = vec![
            "mesh",
            "--urdf",
            "test_data/urdf/ur_style.urdf",
            "--base",
            "base_link",
            "--tip",
            "tool0",
            "--input",
            i,
            "--grid",
            "5",
            "--out",
            d,
        ];
        a.extend_from_slice(extra);
        run(&a);
        let to = dir.join(name);
        std::fs::rename(dir.join("ppoe-mesh-0.obj"), &to).unwrap();
        to
    };
    let plain = mesh(&[], "plain.obj");
    let one = mesh(&["--exaggerate", "1"], "one.obj");
    let seven = mesh(&["--exaggerate", "7"], "seven.obj");
    assert_eq!(std::fs::read(&plain).unwrap(), std::fs::read(&one).unwrap());
    let (p, s) = (obj_vertices(&plain), obj_vertices(&seven));
    assert_eq!(p.len(), 25 + 5 + 1); // the grid, base + 3 joints + tool, the mean
    assert_eq!(p[25..], s[25..]);
    let tool = p[29];
    let mut largest = 0.0f64;
    for (a, b) in p[..25].iter().zip(&s[..25]) {
        for k in 0..3 {
            let (da, db) = (a[k] - tool[k], b[k] - tool[k]);
            assert!((db - 7.0 * da).abs() <= 1e-12, "{a:?} {b:?}");
            largest = largest.max(da.abs());
        }
    }
    assert!(largest > 1e-4, "the surface is not a point: {largest}");
    let header = std::fs::read_to_string(&seven).unwrap();
    assert!(
        header.contains("surface drawn ×7 about the tool (not to scale)"),
        "{header}"
    );
    assert!(!std::fs::read_to_string(&plain).unwrap().contains("drawn ×"));
}

/// Pictures enlarge a surface too small to see by default, saying so in the legend (the
/// HTML view's label) and on stderr; `--exaggerate 1` draws it at true scale, and a
/// visible surface (the seed's) is not enlarged.
#[test]
fn pictures_enlarge_an_invisible_surface_by_a_labelled_factor() {
    let dir = tmp("exaggerate-html");
    let input = dir.join("cases.json");
    std::fs::write(&input, small_noise_cases()).unwrap();
    let (i, d) = (input.to_str().unwrap(), dir.to_str().unwrap());
    let html = |extra: &[&str]| {
        let mut a = vec![
            "render",
            "--urdf",
            "test_data/urdf/ur_style.urdf",
            "--base",
            "base_link",
            "--tip",
            "tool0",
            "--input",
            i,
            "--format",
            "html",
            "--out",
            d,
        ];
        a.extend_from_slice(extra);
        let out = run(&a);
        let page = std::fs::read_to_string(dir.join("ppoe-render.html")).unwrap();
        let label = page_data(&page)["label"].as_str().unwrap().to_string();
        (label, String::from_utf8_lossy(&out.stderr).into_owned())
    };
    let (label, stderr) = html(&[]);
    // The arm spans about 0.6 m; 3 mrad at ≈0.75 m from the axes gives a surface of a
    // few millimetres: under 1/40 of the arm, enlarged by a round factor of 10 or more.
    let factor: f64 = label
        .split("surface drawn ×")
        .nth(1)
        .and_then(|r| r.split(' ').next())
        .and_then(|k| k.parse().ok())
        .unwrap_or_else(|| panic!("{label}"));
    assert!(factor >= 10.0, "{label}");
    assert!(
        stderr.contains(&format!("drawn ×{factor} about the tool")),
        "{stderr}"
    );
    let (label, stderr) = html(&["--exaggerate", "1"]);
    assert!(
        !label.contains("drawn ×") && !stderr.contains("drawn ×"),
        "{label}"
    );
    let seed = dir.join("seed.json");
    std::fs::write(&seed, zero_cases(6, 1)).unwrap();
    let out = run(&[
        "render",
        "--urdf",
        "test_data/urdf/seed.urdf",
        "--base",
        "linkmount",
        "--tip",
        "tcp",
        "--input",
        seed.to_str().unwrap(),
        "--format",
        "html",
        "--out",
        d,
    ]);
    let page = std::fs::read_to_string(dir.join("ppoe-render.html")).unwrap();
    assert!(!page_data(&page)["label"]
        .as_str()
        .unwrap()
        .contains("drawn ×"));
    assert!(!String::from_utf8_lossy(&out.stderr).contains("drawn ×"));
}

/// A URDF from standard input has no directory: `--package-dir` still finds its package
/// meshes, an absolute `file://` mesh is read, and a relative name is skipped saying why.
#[test]
fn package_dirs_work_for_a_urdf_on_standard_input() {
    use std::io::Write as _;
    let dir = tmp("package-dir-stdin");
    let input = dir.join("cases.json");
    std::fs::write(&input, zero_cases(3, 1)).unwrap();
    let cube = repo().join("test_data/packages/ppoe_ur_style/meshes/visual/base.dae");
    let urdf = std::fs::read_to_string(repo().join("test_data/urdf/ur_style.urdf"))
        .unwrap()
        .replace(
            "package://ppoe_ur_style/meshes/visual/forearm.dae",
            &format!("file://{}", cube.canonicalize().unwrap().display()),
        )
        .replace(
            "package://ppoe_ur_style/meshes/visual/forearm.3ds",
            "meshes/relative.stl",
        );
    let mut child = Command::new(BIN)
        .args([
            "render",
            "--urdf",
            "-",
            "--base",
            "base_link",
            "--tip",
            "tool0",
            "--input",
            input.to_str().unwrap(),
            "--format",
            "html",
            "--out",
            dir.to_str().unwrap(),
            "--package-dir",
            "ppoe_ur_style=test_data/packages/ppoe_ur_style",
        ])
        .current_dir(repo())
        .stdin(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .stdout(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    child
        .stdin
        .take()
        .unwrap()
        .write_all(urdf.as_bytes())
        .unwrap();
    let out = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    assert!(
        stderr.contains("'meshes/relative.stl': a relative name and the URDF has no directory"),
        "{stderr}"
    );
    let html = std::fs::read_to_string(dir.join("ppoe-render.html")).unwrap();
    let data = page_data(&html);
    // The cube and the tetrahedron from the package, and the cube's file again by its
    // file:// name (another name: loaded as a shape of its own).
    assert_eq!(data["shapes"].as_array().unwrap().len(), 3, "{stderr}");
    let bodies = data["frames"][0]["bodies"].as_array().unwrap();
    assert_eq!(bodies.len(), 3, "{stderr}");
}
