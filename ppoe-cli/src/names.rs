//! Names as the command shows them in messages (control characters escaped, very long
//! names cut), and the nearest link names for an unknown `--base`/`--tip`.

use unicode_normalization::char::is_combining_mark;
use unicode_normalization::UnicodeNormalization;

/// Names longer than this many characters are cut in messages.
const MAX_SHOWN: usize = 64;
/// At most this many candidates are listed.
const MAX_CANDIDATES: usize = 5;

/// `name` fit for a one-line message: control characters (and the quote delimiting names)
/// escaped as `\n`, `\u{1b}`, ...; beyond [`MAX_SHOWN`] characters, the start, an ellipsis
/// and the full length in bytes.
pub fn shown(name: &str) -> String {
    let mut out = String::new();
    for (count, c) in name.chars().enumerate() {
        if count == MAX_SHOWN {
            out.push_str(&format!("… ({} bytes)", name.len()));
            break;
        }
        if c.is_control() || c == '\'' || c == '\\' {
            out.extend(c.escape_default());
        } else {
            out.push(c);
        }
    }
    out
}

/// The form names are compared in: compatibility-decomposed (NFKD), combining marks
/// dropped, lower case. So `café` (NFC), `café` (NFD) and `CAFE` meet.
fn folded(name: &str) -> Vec<char> {
    name.nfkd()
        .filter(|c| !is_combining_mark(*c))
        .flat_map(char::to_lowercase)
        .collect()
}

/// Levenshtein distance of the folded forms (strsim's, on characters).
// strsim's generic distance takes a sized collection by reference, not a slice.
#[allow(clippy::ptr_arg)]
fn distance(a: &Vec<char>, b: &Vec<char>) -> usize {
    strsim::generic_levenshtein(a, b)
}

/// The candidates nearest to `name`, nearest first: those equal after folding (Unicode
/// normalisation, accents, case), then those within an edit distance of a third of the
/// name's length (at least 1), at most [`MAX_CANDIDATES`].
pub fn nearest<'a>(name: &str, candidates: impl IntoIterator<Item = &'a str>) -> Vec<&'a str> {
    let key = folded(name);
    // Very long names are not worth comparing: no link name is near a megabyte.
    if key.len() > 4 * MAX_SHOWN {
        return Vec::new();
    }
    let limit = (key.len() / 3).max(1);
    let mut scored: Vec<(usize, &str)> = candidates
        .into_iter()
        .filter(|c| *c != name)
        .filter_map(|c| {
            let ck = folded(c);
            if ck.len().abs_diff(key.len()) > limit {
                return None;
            }
            let d = distance(&key, &ck);
            (d <= limit).then_some((d, c))
        })
        .collect();
    scored.sort_by(|a, b| a.0.cmp(&b.0).then(a.1.cmp(b.1)));
    scored
        .into_iter()
        .take(MAX_CANDIDATES)
        .map(|(_, c)| c)
        .collect()
}

/// The hint after "link 'x' does not exist": the nearest names, or where to find them all.
pub fn hint<'a>(name: &str, candidates: impl IntoIterator<Item = &'a str>) -> String {
    let near = nearest(name, candidates);
    if near.is_empty() {
        "no link name is near it (`ppoe links --urdf FILE` lists them)".to_string()
    } else {
        let list: Vec<String> = near.iter().map(|n| format!("'{}'", shown(n))).collect();
        format!("did you mean {}?", list.join(", "))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn control_characters_are_escaped() {
        assert_eq!(shown("a\nb\u{1b}[31m"), "a\\nb\\u{1b}[31m");
        assert!(!shown("x\r\t\u{7f}").chars().any(char::is_control));
    }

    #[test]
    fn long_names_are_cut_with_their_length() {
        let long = "é".repeat(1_000_000);
        let s = shown(&long);
        assert!(s.chars().count() < 100, "{}", s.len());
        assert!(s.ends_with("… (2000000 bytes)"), "{s}");
    }

    #[test]
    fn normalisation_and_case_meet() {
        let nfc = "caf\u{e9}";
        let nfd = "cafe\u{301}";
        assert_eq!(nearest(nfd, [nfc, "base"]), vec![nfc]);
        assert_eq!(
            nearest("TOOL0", ["tool0", "tool1", "base_link"]),
            vec!["tool0", "tool1"]
        );
    }

    #[test]
    fn edit_distance_ranks() {
        assert_eq!(distance(&folded("kitten"), &folded("sitting")), 3);
        assert_eq!(nearest("tcpp", ["tcp", "link1", "linkmount"]), vec!["tcp"]);
        assert!(nearest("zzzzzz", ["tcp", "link1"]).is_empty());
    }
}
