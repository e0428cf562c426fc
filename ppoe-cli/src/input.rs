//! Decoding an input read once ([`crate::load::read`]): every JSON input and noise model
//! passes through [`text`], the one place a UTF-8 byte-order mark (as Windows editors
//! write) is dropped, and every JSON text the CLI parses itself passes through
//! [`parse_json`], the one place JSON is parsed (ppoe-build's strict reader: repeated keys
//! are refused). The URDF is decoded by `ppoe-build`'s reader.

use serde::de::DeserializeOwned;

/// The UTF-8 byte-order mark.
const BOM: &[u8] = "\u{feff}".as_bytes();

/// The text of `bytes`: UTF-8, a leading byte-order mark dropped.
///
/// # Errors
/// Not UTF-8; the error's offset counts from after the byte-order mark.
pub fn text(bytes: &[u8]) -> Result<&str, std::str::Utf8Error> {
    std::str::from_utf8(bytes.strip_prefix(BOM).unwrap_or(bytes))
}

/// Parses the JSON `text` (from [`text`]) as `T`, once, with ppoe-build's strict reader
/// (a repeated key is an error, as is nesting beyond its depth bound).
///
/// # Errors
/// Malformed JSON (ppoe-build's [`ErrorKind::Json`](ppoe_build::ErrorKind::Json) error,
/// with its line and column, or naming the repeated key) or JSON of another shape (a
/// [`serde_json::Error`]), as an [`anyhow::Error`]; callers name the input.
pub fn parse_json<T: DeserializeOwned>(text: &str) -> anyhow::Result<T> {
    // [`text`] dropped the one mark allowed; ppoe-build's reader would drop a second.
    if text.starts_with('\u{feff}') {
        anyhow::bail!("1:1: JSON: a second byte-order mark");
    }
    let value = ppoe_build::json::parse(text)?;
    Ok(serde_json::from_value(value)?)
}

/// `true` if `e`, from [`parse_json`], says the JSON is well-formed but of another shape
/// (callers then name the shape they expected).
pub fn is_shape_error(e: &anyhow::Error) -> bool {
    e.downcast_ref::<serde_json::Error>()
        .is_some_and(serde_json::Error::is_data)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_byte_order_mark_is_dropped_once() {
        assert_eq!(text(b"\xef\xbb\xbf{}").unwrap(), "{}");
        assert_eq!(text(b"{}").unwrap(), "{}");
        // Only a leading mark: a second one is text (the JSON parser rejects it).
        assert_eq!(text(b"\xef\xbb\xbf\xef\xbb\xbf1").unwrap(), "\u{feff}1");
        assert!(
            parse_json::<serde_json::Value>(text(b"\xef\xbb\xbf\xef\xbb\xbf1").unwrap()).is_err()
        );
    }

    #[test]
    fn the_offset_of_a_bad_byte_counts_after_the_mark() {
        assert_eq!(text(b"\xef\xbb\xbfab\xff").unwrap_err().valid_up_to(), 2);
        assert_eq!(text(b"ab\xff").unwrap_err().valid_up_to(), 2);
    }

    #[test]
    fn shape_errors_are_told_from_syntax_errors() {
        let shape = parse_json::<Vec<f64>>("[\"x\"]").unwrap_err();
        let syntax = parse_json::<Vec<f64>>("[1,").unwrap_err();
        assert!(is_shape_error(&shape));
        assert!(!is_shape_error(&syntax));
        assert!(syntax.to_string().contains("1:3"), "{syntax}");
    }

    #[test]
    fn a_repeated_key_is_refused() {
        let e =
            parse_json::<serde_json::Value>("{\"samples\": [],\n \"samples\": [1]}").unwrap_err();
        assert!(e.to_string().contains("duplicate key \"samples\""), "{e}");
        assert!(!is_shape_error(&e));
    }
}
