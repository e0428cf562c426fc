//! The code of a generated table with the text of its comments and literals removed: an
//! oracle for escaping that shares no code with ppoe-build. A table generated for hostile
//! names must have the same skeleton as the same table with plain names; a name that ends
//! a comment or a literal changes it.

/// Rust source without its comments (`//` to the end of the line; `/* */`, nested) and with
/// every string literal emptied (`""`). Only `\n` ends a line comment, as for rustc.
pub fn rust_skeleton(src: &str) -> String {
    skeleton(src.as_bytes(), true)
}

/// C source after translation phases 1 and 2 (trigraphs replaced, backslash-newline
/// removed) without its comments (`/* */`, not nested; `//` to the end of the line) and with
/// every string literal emptied.
pub fn c_skeleton(src: &str) -> String {
    let phase1 = trigraphs(src.as_bytes());
    let mut phase2 = Vec::with_capacity(phase1.len());
    let mut i = 0;
    while i < phase1.len() {
        if phase1[i] == b'\\' && phase1.get(i + 1) == Some(&b'\n') {
            i += 2;
        } else {
            phase2.push(phase1[i]);
            i += 1;
        }
    }
    skeleton(&phase2, false)
}

fn trigraphs(s: &[u8]) -> Vec<u8> {
    let mut out = Vec::with_capacity(s.len());
    let mut i = 0;
    while i < s.len() {
        let t = match (s[i], s.get(i + 1), s.get(i + 2)) {
            (b'?', Some(b'?'), Some(&c)) => match c {
                b'=' => Some(b'#'),
                b'(' => Some(b'['),
                b'/' => Some(b'\\'),
                b')' => Some(b']'),
                b'\'' => Some(b'^'),
                b'<' => Some(b'{'),
                b'!' => Some(b'|'),
                b'>' => Some(b'}'),
                b'-' => Some(b'~'),
                _ => None,
            },
            _ => None,
        };
        match t {
            Some(c) => {
                out.push(c);
                i += 3;
            }
            None => {
                out.push(s[i]);
                i += 1;
            }
        }
    }
    out
}

fn skeleton(s: &[u8], nested: bool) -> String {
    let mut out = Vec::with_capacity(s.len());
    let mut i = 0;
    while i < s.len() {
        match (s[i], s.get(i + 1)) {
            (b'/', Some(b'/')) => {
                while i < s.len() && s[i] != b'\n' {
                    i += 1;
                }
            }
            (b'/', Some(b'*')) => {
                let mut depth = 1;
                i += 2;
                while i < s.len() && depth > 0 {
                    if s[i] == b'*' && s.get(i + 1) == Some(&b'/') {
                        depth -= 1;
                        i += 2;
                    } else if nested && s[i] == b'/' && s.get(i + 1) == Some(&b'*') {
                        depth += 1;
                        i += 2;
                    } else {
                        i += 1;
                    }
                }
                out.extend_from_slice(b"/**/");
            }
            (b'"', _) => {
                i += 1;
                while i < s.len() && s[i] != b'"' {
                    i += if s[i] == b'\\' { 2 } else { 1 };
                }
                i += 1;
                out.extend_from_slice(b"\"\"");
            }
            (c, _) => {
                out.push(c);
                i += 1;
            }
        }
    }
    String::from_utf8_lossy(&out).into_owned()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn removes_comments_and_literals() {
        assert_eq!(
            rust_skeleton("a // x\nb \"q\\\"\" /* /* */ */ c"),
            "a \nb \"\" /**/ c"
        );
        assert_eq!(
            c_skeleton("a /* x */ b // y\\\nz\nc \"s\""),
            "a /**/ b \nc \"\""
        );
        assert_eq!(c_skeleton("/* a ??/\n*/ b"), "/**/ b");
        // What an unescaped name would do: the code after it becomes part of the skeleton.
        assert_ne!(rust_skeleton("// x\ny\n"), rust_skeleton("// xy\n"));
    }
}
