//! Names in messages (issue class: names): unknown `--base`/`--tip`/`--joints` list the
//! nearest names (Unicode normalisation, case, edit distance), control characters are
//! escaped, very long names are cut with their length.

mod common;
use common::*;

fn links_error(base: &str, tip: &str) -> String {
    let u = urdf("non_ascii.urdf");
    one_line_error(
        &run(&[
            "eval",
            "--urdf",
            u.to_str().unwrap(),
            "--base",
            base,
            "--tip",
            tip,
        ]),
        1,
    )
}

#[test]
fn a_normalisation_look_alike_gets_the_real_name() {
    // The file spells 'basis_ä' precomposed (NFC); this is 'a' + U+0308 (NFD).
    let line = links_error("basis_a\u{308}", "glied_ö");
    assert!(
        line.contains("base link 'basis_a\u{308}' does not exist"),
        "{line}"
    );
    assert!(line.contains("did you mean 'basis_ä'?"), "{line}");
    let line = links_error("basis_ä", "GLIED_Ö");
    assert!(
        line.contains("tip link") && line.contains("did you mean 'glied_ö'?"),
        "{line}"
    );
}

#[test]
fn a_typo_gets_the_nearest_names_and_a_far_name_the_way_to_list_them() {
    let a = ["eval", "--urdf", "", "--base", "linkmount", "--tip", "tcpp"];
    let u = urdf("seed.urdf");
    let mut a = a.to_vec();
    a[2] = u.to_str().unwrap();
    let line = one_line_error(&run(&a), 1);
    assert!(line.contains("did you mean 'tcp'?"), "{line}");
    a[6] = "gripper_finger";
    let line = one_line_error(&run(&a), 1);
    assert!(line.contains("ppoe links --urdf"), "{line}");
    let j = seed_args("eval", &["--joints", "joint1,jiont2"]);
    let line = one_line_error(&run(&refs(&j)), 1);
    assert!(
        line.contains("joint 'jiont2'") && line.contains("did you mean 'joint2'"),
        "{line}"
    );
}

#[test]
fn control_characters_are_escaped() {
    let line = links_error("basis_ä", "evil\u{1b}[2J\rname");
    assert!(line.contains("evil\\u{1b}[2J\\rname"), "{line}");
    assert!(!line.chars().any(|c| c.is_control()), "{line:?}");
}

#[test]
fn a_huge_name_is_cut_with_its_length() {
    // 100 kB: within the 128 kB a single Linux argument may hold.
    let huge = "x".repeat(100_000);
    let line = links_error("basis_ä", &huge);
    assert!(line.len() < 500, "{} bytes", line.len());
    assert!(line.contains("… (100000 bytes)"), "{line}");
}

#[test]
fn a_huge_name_from_the_urdf_is_cut_too() {
    // A 3 MB joint name comes back in the joint-count error, which lists the joints.
    let name = "j".repeat(3_000_000);
    let text = format!(
        r#"<robot name="r"><link name="a"/><link name="b"/>
        <joint name="{name}" type="revolute"><parent link="a"/><child link="b"/>
        <axis xyz="0 0 1"/><limit lower="-1" upper="1"/></joint></robot>"#
    );
    let dir = fresh_dir("huge-name");
    let u = dir.join("huge.urdf");
    std::fs::write(&u, text).unwrap();
    let input = seed_cases(1); // 6 joints for a 1-joint chain
    let o = run_bytes(
        &[
            "eval",
            "--urdf",
            u.to_str().unwrap(),
            "--base",
            "a",
            "--tip",
            "b",
        ],
        input.as_bytes(),
    );
    let line = one_line_error(&o, 1);
    assert!(line.len() < 3000, "{} bytes", line.len());
    assert!(
        line.contains("1 joints") || line.contains("has 1 joint"),
        "{}",
        &line[..200]
    );
}
