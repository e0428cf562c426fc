//! Indented JSON for people (`eval --pretty`, `ppoe fit`'s files) in which an array of
//! scalars (a vector, a matrix row) stays on one line: a 6×6 covariance takes 6 lines, not
//! 50 as with `serde_json::to_string_pretty` alone. It is that output with each innermost
//! array joined onto one line, so the fields keep their order, the numbers are written
//! exactly as serde_json writes them (shortest round trip) and the text stays JSON.

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
/// scalar holds none outside a string).
fn join_flat_arrays(text: &str) -> String {
    let b = text.as_bytes();
    let mut out = Vec::with_capacity(b.len());
    let mut i = 0;
    // `end` is the `]` of the flat array being joined, if any.
    let mut end: Option<usize> = None;
    while i < b.len() {
        match b[i] {
            b'"' => {
                let e = string_end(b, i);
                out.extend_from_slice(&b[i..e]);
                i = e;
                continue;
            }
            b'[' if end.is_none() => end = flat_array_end(b, i),
            b']' if end == Some(i) => end = None,
            b' ' | b'\n' | b'\r' | b'\t' if end.is_some() => {
                i += 1;
                continue;
            }
            _ => {}
        }
        out.push(b[i]);
        if b[i] == b',' && end.is_some() {
            out.push(b' ');
        }
        i += 1;
    }
    // Only ASCII whitespace was removed and ASCII spaces added: still UTF-8.
    String::from_utf8(out).unwrap_or_else(|_| text.to_string())
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
}
