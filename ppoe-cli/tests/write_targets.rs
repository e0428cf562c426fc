//! What `--out` paths that are not plain files get (issue class: output): a symbolic link
//! is kept and the file it points to replaced atomically; a device or a FIFO is written
//! through, never renamed over; a regular file is replaced by a rename. Each command's
//! bytes are compared with the same command writing into an empty directory.
#![cfg(unix)]

mod common;
use common::*;
use std::os::unix::fs::{symlink, FileTypeExt, MetadataExt};
use std::path::{Path, PathBuf};

/// `ppoe mesh` (written through a writer) of two seed cases into `dir`.
fn mesh(dir: &Path) -> std::process::Output {
    let args = seed_args("mesh", &["--grid", "4", "--out", dir.to_str().unwrap()]);
    run_bytes(&refs(&args), seed_cases(2).as_bytes())
}

/// `ppoe render --format png` (written through a path) of one seed case into `dir`.
fn render(dir: &Path) -> std::process::Output {
    let args = seed_args("render", &["--grid", "4", "--out", dir.to_str().unwrap()]);
    run_bytes(&refs(&args), seed_cases(1).as_bytes())
}

/// What `command` writes as `name` into an empty directory.
fn reference(command: fn(&Path) -> std::process::Output, tag: &str, name: &str) -> Vec<u8> {
    let dir = fresh_dir(&format!("targets-reference-{tag}"));
    success(&command(&dir));
    std::fs::read(dir.join(name)).unwrap()
}

/// The names in `dir`, sorted (a leftover temporary file would show).
fn names(dir: &Path) -> Vec<String> {
    let mut n: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    n.sort();
    n
}

#[test]
fn a_link_to_a_file_is_kept_and_its_target_replaced() {
    let want = reference(mesh, "link", "ppoe-mesh-0.obj");
    let out = fresh_dir("targets-link-out");
    let elsewhere = fresh_dir("targets-link-elsewhere");
    let real = elsewhere.join("real.obj");
    std::fs::write(&real, b"previous").unwrap();
    symlink(&real, out.join("ppoe-mesh-0.obj")).unwrap();
    // A relative link that points to nothing yet: the file is created there.
    symlink(
        "../targets-link-elsewhere/new.obj",
        out.join("ppoe-mesh-1.obj"),
    )
    .unwrap();
    success(&mesh(&out));
    for (link, target) in [
        ("ppoe-mesh-0.obj", "real.obj"),
        ("ppoe-mesh-1.obj", "new.obj"),
    ] {
        let meta = std::fs::symlink_metadata(out.join(link)).unwrap();
        assert!(meta.file_type().is_symlink(), "{link} was replaced");
        assert!(std::fs::metadata(elsewhere.join(target)).unwrap().is_file());
    }
    assert_eq!(std::fs::read(&real).unwrap(), want);
    assert_eq!(names(&out), ["ppoe-mesh-0.obj", "ppoe-mesh-1.obj"]);
    assert_eq!(names(&elsewhere), ["new.obj", "real.obj"]);
}

#[test]
fn a_regular_file_is_replaced_by_a_rename() {
    let want = reference(mesh, "regular", "ppoe-mesh-0.obj");
    let out = fresh_dir("targets-regular");
    let file = out.join("ppoe-mesh-0.obj");
    std::fs::write(&file, b"previous").unwrap();
    // A second name for the old file: a rename leaves it alone, writing in place would not.
    std::fs::hard_link(&file, out.join("old")).unwrap();
    let before = std::fs::metadata(&file).unwrap().ino();
    success(&mesh(&out));
    assert_eq!(std::fs::read(&file).unwrap(), want);
    assert_ne!(std::fs::metadata(&file).unwrap().ino(), before);
    assert_eq!(std::fs::read(out.join("old")).unwrap(), b"previous");
    assert_eq!(names(&out), ["old", "ppoe-mesh-0.obj", "ppoe-mesh-1.obj"]);
}

#[test]
fn a_link_to_dev_null_is_written_through() {
    let out = fresh_dir("targets-null");
    symlink("/dev/null", out.join("ppoe-mesh-0.obj")).unwrap();
    symlink("/dev/null", out.join("ppoe-render-0.png")).unwrap();
    success(&mesh(&out));
    success(&render(&out));
    for link in ["ppoe-mesh-0.obj", "ppoe-render-0.png"] {
        let meta = std::fs::symlink_metadata(out.join(link)).unwrap();
        assert!(meta.file_type().is_symlink(), "{link} was replaced");
        assert_eq!(
            std::fs::read_link(out.join(link)).unwrap(),
            Path::new("/dev/null")
        );
    }
    assert!(std::fs::metadata("/dev/null")
        .unwrap()
        .file_type()
        .is_char_device());
    assert_eq!(
        names(&out),
        ["ppoe-mesh-0.obj", "ppoe-mesh-1.obj", "ppoe-render-0.png"]
    );
}

/// Makes a FIFO at `path` and reads it whole in a thread.
fn fifo_reader(path: &Path) -> std::thread::JoinHandle<Vec<u8>> {
    let made = std::process::Command::new("mkfifo")
        .arg(path)
        .status()
        .unwrap();
    assert!(made.success());
    let path: PathBuf = path.to_path_buf();
    std::thread::spawn(move || std::fs::read(path).unwrap())
}

/// What the reader of the FIFO at `path` got once the writer is done; a reader still
/// waiting for a writer (nothing was written) is let go with nothing rather than hanging.
fn fifo_bytes(path: &Path, reader: std::thread::JoinHandle<Vec<u8>>) -> Vec<u8> {
    use std::os::unix::fs::OpenOptionsExt;
    let meta = std::fs::symlink_metadata(path).unwrap();
    assert!(
        meta.file_type().is_fifo(),
        "{} was replaced",
        path.display()
    );
    // Linux's O_NONBLOCK: opening for writing fails at once when no reader waits.
    let _ = std::fs::OpenOptions::new()
        .write(true)
        .custom_flags(0o4000)
        .open(path);
    reader.join().unwrap()
}

#[cfg(target_os = "linux")]
#[test]
fn a_fifo_is_written_through_not_replaced() {
    let want_obj = reference(mesh, "fifo-obj", "ppoe-mesh-0.obj");
    let want_png = reference(render, "fifo-png", "ppoe-render-0.png");
    let out = fresh_dir("targets-fifo");
    let (obj, png) = (out.join("ppoe-mesh-0.obj"), out.join("ppoe-render-0.png"));
    let reader = fifo_reader(&obj);
    success(&mesh(&out));
    assert_eq!(fifo_bytes(&obj, reader), want_obj);
    let reader = fifo_reader(&png);
    success(&render(&out));
    assert_eq!(fifo_bytes(&png, reader), want_png);
}

/// 60 seed samples of the joint model, as `ppoe fit`'s input.
fn fit_input() -> String {
    let c = ppoe_build::Config::new(urdf("seed.urdf"))
        .base("linkmount")
        .tip("tcp")
        .chain()
        .unwrap();
    let joints: Vec<ppoe::chain::Joint<f64>> = c
        .to_core_joints()
        .iter()
        .map(ppoe::chain::Joint::from_f64)
        .collect();
    let home = ppoe::Transform::from_f64(&c.home_transform());
    let truth: Vec<_> = joints
        .iter()
        .map(|j| ppoe::chain::screw_noise(&j.screw, 1e-4))
        .collect();
    let samples = ppoe_fit::simulate::samples(&joints, &home, &truth, None, 60, 5);
    let s: Vec<serde_json::Value> = samples
        .iter()
        .map(|s| serde_json::json!({"thetas": s.thetas, "pose": s.pose}))
        .collect();
    serde_json::json!({ "samples": s }).to_string()
}

/// `fit --out` a link to `/dev/stdout` (a link, not `/dev/stdout` itself: were it
/// renamed over, only the test's link would be lost).
#[test]
fn fit_out_to_stdout_prints_the_fit() {
    let input = fit_input();
    let plain = run_bytes(
        &refs(&seed_args("fit", &["--model", "joint"])),
        input.as_bytes(),
    );
    success(&plain);
    let dir = fresh_dir("targets-fit-stdout");
    let link = dir.join("noise.json");
    symlink("/dev/stdout", &link).unwrap();
    let args = seed_args(
        "fit",
        &["--model", "joint", "--out", link.to_str().unwrap()],
    );
    let through = run_bytes(&refs(&args), input.as_bytes());
    success(&through);
    assert!(!plain.stdout.is_empty());
    assert_eq!(through.stdout, plain.stdout);
    let meta = std::fs::symlink_metadata(&link).unwrap();
    assert!(meta.file_type().is_symlink(), "the link was replaced");
    assert_eq!(names(&dir), ["noise.json"]);
}
