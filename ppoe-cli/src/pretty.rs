//! Indented JSON for people (`eval --pretty`, `ppoe fit`'s files) in which an array of
//! scalars (a vector, a matrix row) stays on one line: a 6×6 covariance takes 6 lines, not
//! 50 as with `serde_json::to_string_pretty` alone. It is that output with each innermost
//! array joined onto one line, so the fields keep their order, the numbers are written
//! exactly as serde_json writes them (shortest round trip) and the text stays JSON. One
//! exception keeps a 6×6 readable where it is stored flat: the 36 numbers of a
//! `"covariance"` (ROS's row-major layout, `eval --format ros`) are written six a line.

use serde::Serialize;

/// `value` as indented JSON (two spaces) with every array that holds no array or object
/// on one line (`[1.5, 2.0]`); no trailing newline.
///
/// # Errors
/// Those of `serde_json::to_string_pretty`.
pub fn to_string<T: Serialize + ?Sized>(value: &T) -> serde_json::Result<String> {
    Ok(join_flat_arrays(&serde_json::to_string_pretty(value)?))
}

/// The end (index after) of the string literal that starts at `b[i] == '"'`.
fn string_end(b: &[u8], mut i: usize) -> usize {
    i += 1;
    while i < b.len() {
        match b[i] {
            b'\\' => i += 2,
            b'"' => return i + 1,
            _ => i += 1,
        }
    }
    b.len()
}

/// The index of the `]` closing the array at `b[i] == '['` if nothing in it is an array
/// or an object; `None` otherwise.
fn flat_array_end(b: &[u8], mut i: usize) -> Option<usize> {
    i += 1;
    while i < b.len() {
        match b[i] {
            b'"' => i = string_end(b, i),
            b'[' | b'{' => return None,
            b']' => return Some(i),
            _ => i += 1,
        }
    }
    None
}

/// JSON text with the whitespace between the tokens of each flat array replaced by one
/// space after a comma (whitespace outside strings is not significant in JSON, and a
/// scalar holds none outside a string); a flat `"covariance"` of 36 entries six a line.
fn join_flat_arrays(text: &str) -> String {
    let b = text.as_bytes();
    let mut out = Vec::with_capacity(b.len());
    let mut i = 0;
    // The flat array being joined, if any: its `]` and, for a wrapped covariance, the
    // indentation of its rows.
    let mut end: Option<(usize, Option<usize>)> = None;
    let mut commas = 0;
    while i < b.len() {
        match b[i] {
            b'"' => {
                let e = string_end(b, i);
                out.extend_from_slice(&b[i..e]);
                i = e;
                continue;
            }
            b'[' if end.is_none() => {
                end = flat_array_end(b, i).map(|e| (e, wrap_indent(&out, &b[i..e])));
                commas = 0;
                if let Some((_, Some(pad))) = end {
                    out.push(b'[');
                    new_line(&mut out, pad);
                    i += 1;
                    continue;
                }
            }
            b']' if end.is_some_and(|(e, _)| e == i) => {
                if let Some((_, Some(pad))) = end {
                    new_line(&mut out, pad - 2);
                }
                end = None;
            }
            b' ' | b'\n' | b'\r' | b'\t' if end.is_some() => {
                i += 1;
                continue;
            }
            _ => {}
        }
        out.push(b[i]);
        if let (b',', Some((_, wrap))) = (b[i], end) {
            commas += 1;
            match wrap {
                Some(pad) if commas % 6 == 0 => new_line(&mut out, pad),
                _ => out.push(b' '),
            }
        }
        i += 1;
    }
    // Only ASCII whitespace was removed and ASCII spaces added: still UTF-8.
    String::from_utf8(out).unwrap_or_else(|_| text.to_string())
}

/// For a flat array `array` (from its `[` to before its `]`) just after `out`: the
/// indentation of its rows if it is a `"covariance"` of 36 entries (that of its line plus
/// two), else `None`.
fn wrap_indent(out: &[u8], array: &[u8]) -> Option<usize> {
    let entries = array.iter().filter(|c| **c == b',').count() + 1;
    if entries != 36 || !out.ends_with(b"\"covariance\": ") {
        return None;
    }
    let line = out.rsplit(|c| *c == b'\n').next().unwrap_or(out);
    Some(line.iter().take_while(|c| **c == b' ').count() + 2)
}

/// A line break and `pad` spaces.
fn new_line(out: &mut Vec<u8>, pad: usize) {
    out.push(b'\n');
    out.extend(std::iter::repeat_n(b' ', pad));
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_matrix_row_per_line_fields_in_order() {
        let v = serde_json::json!({"z": [[1.5, 2], [3, -0.0]], "b": ["a, [b]", "\"]"], "c": [], "d": {}});
        let text = to_string(&v).unwrap();
        // Written by hand: what a person should see.
        let expected = "{\n  \"b\": [\"a, [b]\", \"\\\"]\"],\n  \"c\": [],\n  \"d\": {},\n  \"z\": [\n    [1.5, 2],\n    [3, -0.0]\n  ]\n}";
        assert_eq!(text, expected);
        let back: serde_json::Value = serde_json::from_str(&text).unwrap();
        assert_eq!(back, v);
        #[derive(Serialize)]
        struct Ordered {
            second: u8,
            first: [f64; 2],
        }
        let text = to_string(&Ordered {
            second: 1,
            first: [0.1, 1e-300],
        })
        .unwrap();
        assert_eq!(text, "{\n  \"second\": 1,\n  \"first\": [0.1, 1e-300]\n}");
    }

    #[test]
    fn a_flat_covariance_six_a_line() {
        let flat: Vec<f64> = (0..36).map(f64::from).collect();
        let v = serde_json::json!({"r": {"covariance": flat, "x": [1, 2]}, "covariance": [1, 2]});
        let text = to_string(&v).unwrap();
        let rows: Vec<String> = (0..6)
            .map(|r| {
                let row: Vec<String> = (0..6).map(|c| format!("{}.0", 6 * r + c)).collect();
                format!("      {}", row.join(", "))
            })
            .collect();
        // Written by hand; only the 36-entry covariance is wrapped.
        let expected = format!(
            "{{\n  \"covariance\": [1, 2],\n  \"r\": {{\n    \"covariance\": [\n{}\n    ],\n    \"x\": [1, 2]\n  }}\n}}",
            rows.join(",\n")
        );
        assert_eq!(text, expected);
        let back: serde_json::Value = serde_json::from_str(&text).unwrap();
        assert_eq!(back, v);
    }
}
