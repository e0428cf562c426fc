//! Strict JSON for every file a ppoe tool reads (noise models now; the CLI's inputs are to
//! follow): one function, [`parse`], that accepts exactly one JSON value and refuses what a
//! lenient parser would silently resolve.
//!
//! * One leading UTF-8 byte order mark is skipped (editors on some systems write one); a
//!   second is a syntax error like any other stray character.
//! * An object with a repeated key is an error naming the key and the position of its
//!   second occurrence: `serde_json` would keep the last value without a word, so a file
//!   with `"samples"` twice would be read as something its author did not see.
//! * Nesting deeper than [`MAX_DEPTH`] arrays and objects is an error (bounded recursion
//!   whatever the input).
//! * Every error has the 1-based line and column (in characters, the BOM not counted)
//!   where it was detected, in [`Error::position`](crate::Error::position).
//!
//! ```
//! let v = ppoe_build::json::parse("\u{feff}{\"model\": \"joint\", \"joints\": []}").unwrap();
//! assert_eq!(v["model"], "joint");
//!
//! let e = ppoe_build::json::parse("{\"samples\": 1,\n \"samples\": 2}").unwrap_err();
//! assert_eq!(e.kind(), ppoe_build::ErrorKind::Json);
//! assert!(e.message().contains("duplicate key \"samples\""), "{e}");
//! assert_eq!(e.position().map(|p| p.line), Some(2));
//! ```

use crate::error::{Error, ErrorKind, Position, Result};
use serde::de::{DeserializeSeed, Error as _, MapAccess, SeqAccess, Visitor};
use serde_json::{Map, Value};
use std::fmt;

/// The deepest nesting of arrays and objects accepted (a `ppoe fit` result nests 4 deep).
pub const MAX_DEPTH: usize = 64;

/// Parses `text` as exactly one strict JSON value (see the module documentation).
///
/// # Errors
///
/// [`ErrorKind::Json`] with a position: a syntax error, trailing characters, a duplicate
/// key (named), nesting deeper than [`MAX_DEPTH`].
pub fn parse(text: &str) -> Result<Value> {
    let body = text.strip_prefix('\u{feff}').unwrap_or(text);
    let mut de = serde_json::Deserializer::from_str(body);
    let value = Strict { depth: 0 }
        .deserialize(&mut de)
        .and_then(|v| de.end().map(|()| v))
        .map_err(|e| error(body, &e))?;
    Ok(value)
}

/// Our error for a `serde_json` error: its message without serde's " at line L column C"
/// (the position goes into [`Error::position`]), the column converted from bytes to
/// characters.
fn error(body: &str, e: &serde_json::Error) -> Error {
    let full = e.to_string();
    let suffix = format!(" at line {} column {}", e.line(), e.column());
    let message = full.strip_suffix(&suffix).unwrap_or(&full);
    let position = (e.line() > 0).then(|| char_position(body, e.line(), e.column()));
    Error::new(ErrorKind::Json, format!("JSON: {message}")).at(position)
}

/// The character position of serde's (line, byte column).
fn char_position(body: &str, line: usize, byte_column: usize) -> Position {
    let text = body.split('\n').nth(line - 1).unwrap_or("");
    let column = text
        .char_indices()
        .take_while(|&(i, _)| i < byte_column.saturating_sub(1))
        .count()
        + 1;
    let clamp = |x: usize| u32::try_from(x).unwrap_or(u32::MAX);
    Position {
        line: clamp(line),
        column: clamp(column),
    }
}

/// A JSON value at nesting depth `depth`, built like `serde_json::Value` but refusing
/// duplicate keys and excessive depth.
#[derive(Clone, Copy)]
struct Strict {
    depth: usize,
}

impl Strict {
    fn inner<E: serde::de::Error>(self) -> Result<Self, E> {
        if self.depth >= MAX_DEPTH {
            return Err(E::custom(format_args!(
                "nested deeper than {MAX_DEPTH} arrays and objects"
            )));
        }
        Ok(Strict {
            depth: self.depth + 1,
        })
    }
}

impl<'de> DeserializeSeed<'de> for Strict {
    type Value = Value;
    fn deserialize<D: serde::Deserializer<'de>>(self, d: D) -> Result<Value, D::Error> {
        d.deserialize_any(self)
    }
}

impl<'de> Visitor<'de> for Strict {
    type Value = Value;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("a JSON value")
    }
    fn visit_bool<E>(self, b: bool) -> Result<Value, E> {
        Ok(Value::Bool(b))
    }
    fn visit_i64<E>(self, x: i64) -> Result<Value, E> {
        Ok(x.into())
    }
    fn visit_u64<E>(self, x: u64) -> Result<Value, E> {
        Ok(x.into())
    }
    fn visit_f64<E>(self, x: f64) -> Result<Value, E> {
        // serde_json yields only finite numbers, which `from` keeps.
        Ok(serde_json::Number::from_f64(x).map_or(Value::Null, Value::Number))
    }
    fn visit_str<E>(self, s: &str) -> Result<Value, E> {
        Ok(Value::String(s.to_owned()))
    }
    fn visit_string<E>(self, s: String) -> Result<Value, E> {
        Ok(Value::String(s))
    }
    fn visit_unit<E>(self) -> Result<Value, E> {
        Ok(Value::Null)
    }
    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Value, A::Error> {
        let inner = self.inner()?;
        let mut items = Vec::new();
        while let Some(v) = seq.next_element_seed(inner)? {
            items.push(v);
        }
        Ok(Value::Array(items))
    }
    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Value, A::Error> {
        let inner = self.inner()?;
        let mut out = Map::new();
        while let Some(key) = map.next_key::<String>()? {
            if out.contains_key(&key) {
                return Err(A::Error::custom(format_args!("duplicate key {key:?}")));
            }
            let value = map.next_value_seed(inner)?;
            out.insert(key, value);
        }
        Ok(Value::Object(out))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn err(text: &str) -> Error {
        parse(text).unwrap_err()
    }

    #[test]
    fn accepts_json_and_one_bom() {
        let v = parse("\u{feff} {\"a\": [1, -2, 0.5, true, null, \"x\"], \"b\": {}}").unwrap();
        assert_eq!(
            v,
            serde_json::json!({"a": [1, -2, 0.5, true, null, "x"], "b": {}})
        );
        assert_eq!(parse("[]").unwrap(), serde_json::json!([]));
    }

    #[test]
    fn refuses_a_second_bom_duplicates_depth_and_trailing_text() {
        let e = err("\u{feff}\u{feff}{}");
        assert_eq!(
            (e.kind(), e.position()),
            (ErrorKind::Json, Some(Position { line: 1, column: 1 }))
        );
        let e = err("{\"a\": {\"k\": 1,\n   \"k\": 2}}");
        assert!(e.message().contains("duplicate key \"k\""), "{e}");
        assert_eq!(e.position().map(|p| p.line), Some(2));
        // The same key in different objects is fine.
        assert!(parse("[{\"k\": 1}, {\"k\": 2}]").is_ok());
        let deep = format!("{}{}", "[".repeat(MAX_DEPTH + 1), "]".repeat(MAX_DEPTH + 1));
        assert!(err(&deep).message().contains("nested deeper"));
        let ok = format!("{}{}", "[".repeat(MAX_DEPTH), "]".repeat(MAX_DEPTH));
        assert!(parse(&ok).is_ok());
        let e = err("{} x");
        assert_eq!(e.position(), Some(Position { line: 1, column: 4 }));
        assert!(err("").position().is_some());
    }

    #[test]
    fn columns_count_characters() {
        // "é" is two bytes: the error at the `x` after it is in character column 8.
        let e = err("[\"é\", 1 x]");
        assert_eq!(e.position(), Some(Position { line: 1, column: 9 }), "{e}");
        assert!(!e.message().contains(" at line "), "{e}");
    }
}
