//! A URDF input that looks like xacro (issue #30, point 3): its error ends with the hint to
//! expand it first; an ordinary URDF error has no such hint.

use ppoe_build::error::xacro_hint;
use ppoe_build::Config;
use std::path::PathBuf;

/// A macro file as ROS packages ship them: well-formed XML whose links only the macro
/// call would make.
const MACRO: &str = r#"<?xml version="1.0"?>
<robot name="arm" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="arm" params="prefix">
    <link name="${prefix}base_link"/>
  </xacro:macro>
  <xacro:arm prefix=""/>
</robot>
"#;

fn dir() -> PathBuf {
    let d = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("xacro-hint");
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn chain_error(name: &str, text: &str) -> String {
    let path = dir().join(name);
    std::fs::write(&path, text).unwrap();
    let err = Config::new(&path)
        .base("base_link")
        .tip("tool0")
        .chain()
        .unwrap_err();
    err.to_string()
}

#[test]
fn a_xacro_file_name_gives_the_command_to_run() {
    let e = chain_error("arm.urdf.xacro", MACRO);
    assert!(e.contains("base_link"), "{e}");
    let path = dir().join("arm.urdf.xacro");
    let expected = format!(
        "run: xacro {} > {})",
        path.display(),
        dir().join("arm.urdf").display()
    );
    assert!(e.ends_with(&expected), "{e}");
}

#[test]
fn xacro_content_under_a_urdf_name_gets_the_hint() {
    // Declared namespace: parses, then the links are missing.
    let e = chain_error("declared.urdf", MACRO);
    assert!(
        e.ends_with("(run: xacro robot.urdf.xacro > robot.urdf)"),
        "{e}"
    );
    // An undeclared `xacro:` prefix is malformed XML: the hint still follows.
    let e = chain_error(
        "undeclared.urdf",
        "<robot name=\"r\"><xacro:include filename=\"x\"/></robot>",
    );
    assert!(
        e.contains("malformed XML") && e.contains("looks like xacro"),
        "{e}"
    );
}

#[test]
fn an_ordinary_urdf_error_has_no_hint() {
    let e = chain_error(
        "plain.urdf",
        "<robot name=\"r\"><link name=\"base_link\"/></robot>",
    );
    assert!(
        e.contains("tool0") && !e.contains("looks like xacro"),
        "{e}"
    );
    assert_eq!(xacro_hint("robot.urdf", b"<robot name=\"x\"/>"), None);
    // The name test ignores case; a text mention without the prefix is not xacro.
    assert!(xacro_hint("ARM.XACRO", b"")
        .unwrap()
        .contains("xacro ARM.XACRO > ARM)"));
    assert_eq!(xacro_hint("r.urdf", b"<!-- made by xacro -->"), None);
}
