//! Source text for names and numbers, shared by every table generator: text safe in a
//! comment, string literals with only printable ASCII, shortest round-trip float literals,
//! const names. Each function guarantees that what it returns cannot change the meaning of
//! the surrounding source (end a comment line, end a string, flip the rendering order of
//! the text around it), whatever the URDF's names contain.

use crate::error::{Error, ErrorKind, Result};
use std::fmt::Write as _;

/// `true` for characters that must not appear raw in generated source, even in a comment:
///
/// * control characters (Unicode category Cc: they could end a line comment or be a bare CR,
///   which rustc rejects in doc comments);
/// * line and paragraph separators (Zl, Zp) and every whitespace other than the ASCII space
///   (editors break lines at some of them);
/// * format characters (Cf), among them the bidirectional controls U+202A–U+202E,
///   U+2066–U+2069, U+200E, U+200F and U+061C, which rustc rejects in comments and literals
///   (lint `text_direction_codepoint_in_comment` / `_in_literal`, deny by default) because
///   they can make source display in an order other than the compiler reads it;
/// * private-use characters and noncharacters (nothing a reader can check).
///
/// The Cf list is Unicode 15's; a format character added later is still valid in a Rust
/// comment (only the bidirectional controls are rejected, and Unicode adds no new ones).
pub fn needs_escape(c: char) -> bool {
    let u = c as u32;
    c.is_control()
        || (c.is_whitespace() && c != ' ')
        || is_format(u)
        || (0xE000..=0xF8FF).contains(&u)
        || (0xF0000..=0x10FFFF).contains(&u)
        || (0xFDD0..=0xFDEF).contains(&u)
        || (u & 0xFFFE) == 0xFFFE
}

/// Unicode general category Cf (format), Unicode 15.
fn is_format(u: u32) -> bool {
    matches!(
        u,
        0x00AD
            | 0x0600..=0x0605
            | 0x061C
            | 0x06DD
            | 0x070F
            | 0x0890..=0x0891
            | 0x08E2
            | 0x180E
            | 0x200B..=0x200F
            | 0x202A..=0x202E
            | 0x2060..=0x2064
            | 0x2066..=0x206F
            | 0xFEFF
            | 0xFFF9..=0xFFFB
            | 0x110BD
            | 0x110CD
            | 0x13430..=0x1343F
            | 0x1BCA0..=0x1BCA3
            | 0x1D173..=0x1D17A
            | 0xE0001
            | 0xE0020..=0xE007F
    )
}

/// Text that is safe inside a comment of generated source: made only by [`comment_text`]
/// (Rust) or [`c_comment_text`] (C), the one escaping path of every name, file name and
/// noise-model string a table generator writes into a comment. The field is private, so a
/// generator cannot produce comment text any other way; `Display` writes it.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct CommentText(String);

impl CommentText {
    /// The escaped text.
    pub fn as_str(&self) -> &str {
        &self.0
    }
}

impl std::fmt::Display for CommentText {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

/// Text for a comment of generated Rust (doc or plain): every character of
/// [`needs_escape`] written as `\u{..}` (a backslash itself stays as it is), so a name can
/// neither end the comment line nor reorder the text around it, and the comment still shows
/// which character it was. `*/` is written `*\/` and `/*` `/\*`, so the text is also safe
/// inside a block comment.
pub fn comment_text(s: &str) -> CommentText {
    escape_comment(s, false)
}

/// Text for a comment of generated C: as [`comment_text`], and further every non-ASCII
/// character (a C compiler need not accept it even in a comment), every backslash (a
/// backslash before the end of the line would splice the next line into the comment) and
/// the second `?` of `??` (trigraphs: `??/` is a backslash in C99) written as `\u{..}`.
/// The result is printable ASCII.
pub fn c_comment_text(s: &str) -> CommentText {
    escape_comment(s, true)
}

/// The one escaping of comment text ([`comment_text`], [`c_comment_text`]).
fn escape_comment(s: &str, c: bool) -> CommentText {
    let mut out = String::with_capacity(s.len());
    let mut prev = '\0';
    for ch in s.chars() {
        let c_only = c && (!ch.is_ascii() || ch == '\\' || (ch == '?' && prev == '?'));
        if needs_escape(ch) || c_only {
            let _ = write!(out, "\\u{{{:x}}}", ch as u32);
        } else if (ch == '/' && prev == '*') || (ch == '*' && prev == '/') {
            out.push('\\');
            out.push(ch);
        } else {
            out.push(ch);
        }
        prev = ch;
    }
    CommentText(out)
}

/// A Rust string literal with only printable ASCII in it: `"` and `\` escaped, everything
/// else outside `' '..='~'` written `\u{..}`. It holds exactly `s`.
pub fn str_lit(s: &str) -> String {
    let mut out = String::with_capacity(s.len() + 2);
    out.push('"');
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            ' '..='~' => out.push(c),
            _ => {
                let _ = write!(out, "\\u{{{:x}}}", c as u32);
            }
        }
    }
    out.push('"');
    out
}

/// A float literal for a table of `f64` (`f32_table` false) or `f32`: the shortest text
/// that parses back to the same value (`{:?}`), `f64::INFINITY` / `f32::NEG_INFINITY` etc.
/// for infinities. For an f32 table, `x` is rounded with `as f32` first (tables hold values
/// that are already f32, so this is exact).
///
/// # Errors
///
/// [`ErrorKind::NonFinite`] for NaN: a table never holds one.
pub fn float_lit(x: f64, f32_table: bool) -> Result<String> {
    let nan = || Error::new(ErrorKind::NonFinite, "NaN in a table");
    if f32_table {
        let y = x as f32;
        match y {
            _ if y.is_nan() => Err(nan()),
            f32::INFINITY => Ok("f32::INFINITY".into()),
            f32::NEG_INFINITY => Ok("f32::NEG_INFINITY".into()),
            _ => Ok(format!("{y:?}")),
        }
    } else {
        match x {
            _ if x.is_nan() => Err(nan()),
            f64::INFINITY => Ok("f64::INFINITY".into()),
            f64::NEG_INFINITY => Ok("f64::NEG_INFINITY".into()),
            _ => Ok(format!("{x:?}")),
        }
    }
}

/// `[a, b, c]` of [`float_lit`]s.
///
/// # Errors
///
/// As [`float_lit`].
pub fn float_array(xs: &[f64], f32_table: bool) -> Result<String> {
    let items = xs
        .iter()
        .map(|&x| float_lit(x, f32_table))
        .collect::<Result<Vec<_>>>()?;
    Ok(format!("[{}]", items.join(", ")))
}

/// The lowercase hex SHA-256 of `bytes`.
pub fn sha256_hex(bytes: &[u8]) -> String {
    use sha2::{Digest, Sha256};
    let digest = Sha256::digest(bytes);
    let mut s = String::with_capacity(64);
    for b in digest {
        let _ = write!(s, "{b:02x}");
    }
    s
}

/// The longest const name accepted (the f32 table adds `_F32`).
pub const MAX_NAME_LEN: usize = 48;

/// Checks that `name` can be the name of a `const` item: ASCII letters, digits and `_`, not
/// starting with a digit, not a keyword, at most [`MAX_NAME_LEN`] characters (the f32 table
/// adds `_F32`). ASCII only, so it is also a valid C identifier (C keywords aside).
///
/// # Errors
///
/// [`ErrorKind::Config`] naming the rule.
pub fn check_const_name(name: &str) -> Result<()> {
    const KEYWORDS: &[&str] = &[
        "_", "as", "async", "await", "break", "const", "continue", "crate", "dyn", "else", "enum",
        "extern", "false", "fn", "for", "gen", "if", "impl", "in", "let", "loop", "match", "mod",
        "move", "mut", "pub", "ref", "return", "self", "Self", "static", "struct", "super",
        "trait", "true", "try", "type", "unsafe", "use", "where", "while", "abstract", "become",
        "box", "do", "final", "macro", "override", "priv", "typeof", "unsized", "virtual", "yield",
    ];
    let valid = !name.is_empty()
        && name.len() <= MAX_NAME_LEN
        && name.bytes().all(|b| b.is_ascii_alphanumeric() || b == b'_')
        && !name.as_bytes()[0].is_ascii_digit()
        && !KEYWORDS.contains(&name);
    if valid {
        Ok(())
    } else {
        Err(Error::new(
            ErrorKind::Config,
            format!(
                "{name:?} is not usable as a const name (ASCII letters, digits and '_', not \
                 starting with a digit, not a keyword, at most {MAX_NAME_LEN} characters)"
            ),
        ))
    }
}

/// A const name from a file stem or robot name: ASCII letters and digits upper-cased, every
/// other character (bidirectional controls and any non-ASCII included) → `_`; `ROBOT_` in
/// front of a name that would start with a digit or be empty; at most [`MAX_NAME_LEN`].
pub fn const_name_from(s: &str) -> String {
    let mut out: String = s
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() {
                c.to_ascii_uppercase()
            } else {
                '_'
            }
        })
        .collect();
    if out.is_empty() || out.as_bytes()[0].is_ascii_digit() || out == "_" {
        out.insert_str(0, "ROBOT_");
    }
    out.truncate(MAX_NAME_LEN);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn literals() {
        let lit = |x: f64| float_lit(x, false).unwrap();
        assert_eq!(lit(1.0), "1.0");
        assert_eq!(lit(-0.0), "-0.0");
        assert_eq!(lit(0.158), "0.158");
        assert_eq!(lit(-3.2679489653813835e-7), "-3.2679489653813835e-7");
        assert_eq!(lit(1e300), "1e300");
        assert_eq!(lit(f64::INFINITY), "f64::INFINITY");
        assert_eq!(lit(f64::NEG_INFINITY), "f64::NEG_INFINITY");
        assert!(float_lit(f64::NAN, false).is_err());
        let lit32 = |x: f64| float_lit(x, true).unwrap();
        assert_eq!(lit32(0.1), "0.1");
        assert_eq!(lit32(0.1f32 as f64), "0.1");
        assert_eq!(lit32(1e300), "f32::INFINITY");
        assert!(float_lit(f64::NAN, true).is_err());
        assert_eq!(float_array(&[1.0, -0.5], false).unwrap(), "[1.0, -0.5]");
        assert_eq!(str_lit("a\"b\\c\u{e9}\n"), "\"a\\\"b\\\\c\\u{e9}\\u{a}\"");
        assert_eq!(str_lit("a\u{202e}b"), "\"a\\u{202e}b\"");
    }

    #[test]
    fn comments_escape_what_could_break_or_reorder_them() {
        for c in [
            '\n',
            '\r',
            '\t',
            '\u{0}',
            '\u{85}',
            '\u{2028}',
            '\u{2029}',
            '\u{a0}',
            '\u{3000}',
            '\u{202a}',
            '\u{202e}',
            '\u{2066}',
            '\u{2069}',
            '\u{200e}',
            '\u{200f}',
            '\u{61c}',
            '\u{feff}',
            '\u{ad}',
            '\u{e0001}',
            '\u{e000}',
            '\u{fffe}',
            '\u{10ffff}',
        ] {
            let t = comment_text(&format!("a{c}b"));
            assert_eq!(
                t.as_str(),
                format!("a\\u{{{:x}}}b", c as u32),
                "{:x}",
                c as u32
            );
            let t = c_comment_text(&format!("a{c}b"));
            assert_eq!(
                t.as_str(),
                format!("a\\u{{{:x}}}b", c as u32),
                "{:x}",
                c as u32
            );
        }
        // Readable names stay readable.
        for s in [
            "joint_1",
            "名前",
            "ünïcødé",
            "ø_ɒ_ß",
            "with space",
            "a\\b \"q\" `c`",
        ] {
            assert_eq!(comment_text(s).as_str(), s);
        }
        assert_eq!(comment_text("a*/b").as_str(), "a*\\/b");
        assert_eq!(comment_text("a/*b").as_str(), "a/\\*b");
        assert_eq!(comment_text("a\\b").as_str(), "a\\b");
    }

    #[test]
    fn c_comments_are_printable_ascii_without_splices_or_trigraphs() {
        assert_eq!(
            c_comment_text("joint_1 (a) [b]").as_str(),
            "joint_1 (a) [b]"
        );
        assert_eq!(c_comment_text("a*/b/*c").as_str(), "a*\\/b/\\*c");
        assert_eq!(c_comment_text("end\\").as_str(), "end\\u{5c}");
        assert_eq!(c_comment_text("x??/y").as_str(), "x?\\u{3f}/y");
        assert_eq!(c_comment_text("???").as_str(), "?\\u{3f}\\u{3f}");
        assert_eq!(c_comment_text("a?b").as_str(), "a?b");
        assert_eq!(
            c_comment_text("\u{e4}\u{1f527}").as_str(),
            "\\u{e4}\\u{1f527}"
        );
    }

    #[test]
    fn names() {
        assert!(check_const_name("SEED").is_ok());
        assert!(check_const_name("_X1").is_ok());
        for bad in [
            "",
            "1A",
            "A-B",
            "fn",
            "Ä",
            "A\u{202e}",
            &"X".repeat(MAX_NAME_LEN + 1),
        ] {
            assert_eq!(
                check_const_name(bad).unwrap_err().kind(),
                ErrorKind::Config,
                "{bad}"
            );
        }
        assert_eq!(const_name_from("seed"), "SEED");
        assert_eq!(const_name_from("ur5-e.v2"), "UR5_E_V2");
        assert_eq!(const_name_from("5dof"), "ROBOT_5DOF");
        assert_eq!(const_name_from(""), "ROBOT_");
        assert_eq!(const_name_from("a\u{202e}b"), "A_B");
    }

    #[test]
    fn sha256_known_value() {
        assert_eq!(
            sha256_hex(b"abc"),
            "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad"
        );
    }
}
