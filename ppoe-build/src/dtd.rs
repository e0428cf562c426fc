//! A bound on what the internal entities of a URDF's DTD expand to, checked before the XML
//! parser sees the text.
//!
//! roxmltree stops exponential entity nesting ("billion laughs": at most 255 references
//! inside one top-level reference, 10 levels deep) but not a document that references a
//! large entity many times: 100 KB of text can ask for gigabytes (one 40 KB entity, another
//! of 250 references to it, 1000 references to that), and the parser would build every
//! byte of it before any error could be reported. A URDF needs no entities at all, so this
//! module allows only a small total: every reference in the document body is charged the
//! fully expanded size of its entity, and the document is refused when the sum exceeds
//! [`EXPANSION_BUDGET`]. The count is an upper bound (references inside comments or CDATA,
//! which are not expanded, are charged too), computed in time linear in the text.
//!
//! The prolog and the internal subset are read with the grammar roxmltree uses, so that
//! every entity roxmltree would declare is seen here; text this reader cannot follow is
//! refused as a malformed DTD (roxmltree would refuse it too).

use crate::error::{Error, ErrorKind, Position, Result};
use std::collections::HashMap;

/// The most bytes the document's entity references may expand to, in total (1 MiB).
pub const EXPANSION_BUDGET: u64 = 1 << 20;

/// Entity nesting deeper than this is charged as unbounded (roxmltree refuses more than 10
/// levels anyway); this keeps the size computation's recursion shallow.
const MAX_DEPTH: usize = 16;

/// Checks that the entity references of `text` expand to at most [`EXPANSION_BUDGET`]
/// bytes. `position` maps a byte offset to a line and column for the error.
pub(crate) fn check(text: &str, position: impl Fn(usize) -> Position) -> Result<()> {
    let Some(doctype) = doctype_start(text) else {
        return Ok(());
    };
    let malformed = |what: &str| {
        Error::new(
            ErrorKind::Xml,
            format!("malformed XML: the DTD cannot be read: {what}"),
        )
        .at(Some(position(doctype)))
    };
    let Some((entities, body)) = internal_subset(text, doctype).map_err(malformed)? else {
        return Ok(());
    };
    if entities.is_empty() {
        return Ok(());
    }
    let mut sizes = Sizes {
        entities: &entities,
        memo: HashMap::new(),
    };
    let mut total: u64 = 0;
    let mut worst: Option<(&str, u64, u64)> = None; // name, size, references
    let mut counts: HashMap<&str, u64> = HashMap::new();
    for name in references(&text[body..]) {
        if entities.contains_key(name) {
            *counts.entry(name).or_insert(0) += 1;
        }
    }
    for (&name, &n) in &counts {
        let size = sizes.of(name, 0);
        let charge = size.saturating_mul(n);
        total = total.saturating_add(charge);
        if worst.is_none_or(|(_, s, k)| s.saturating_mul(k) < charge) {
            worst = Some((name, size, n));
        }
    }
    match worst {
        Some((name, size, n)) if total > EXPANSION_BUDGET => Err(Error::new(
            ErrorKind::Xml,
            format!(
                "the DTD's entities expand the document by {} ({n} reference{} to '&{name};' \
                 alone, {} each), more than the {EXPANSION_BUDGET} bytes allowed: a URDF needs \
                 no entities — expand them in the file (or with xacro) or remove the DTD",
                bytes(total),
                if n == 1 { "" } else { "s" },
                bytes(size),
            ),
        )
        .at(Some(position(doctype)))),
        _ => Ok(()),
    }
}

fn bytes(n: u64) -> String {
    if n == u64::MAX {
        "an unbounded number of bytes (nested too deeply or in a cycle)".to_string()
    } else {
        format!("{n} bytes")
    }
}

/// The expanded size of each entity, memoised (linear in the DTD's size).
struct Sizes<'a, 'input> {
    entities: &'a HashMap<&'input str, &'input str>,
    memo: HashMap<&'input str, u64>,
}

impl<'input> Sizes<'_, 'input> {
    fn of(&mut self, name: &'input str, depth: usize) -> u64 {
        if let Some(&s) = self.memo.get(name) {
            return s;
        }
        let Some(&value) = self.entities.get(name) else {
            return 0;
        };
        if depth > MAX_DEPTH {
            return u64::MAX;
        }
        let mut size = value.len() as u64;
        for r in references(value) {
            if self.entities.contains_key(r) {
                size = size.saturating_add(self.of(r, depth + 1));
            }
        }
        self.memo.insert(name, size);
        size
    }
}

/// The names `x` of every `&x;` in `text` (character references included; the caller
/// keeps the declared names).
fn references(text: &str) -> impl Iterator<Item = &str> {
    text.split('&').skip(1).filter_map(|after| {
        let end = after.find(';')?;
        let name = &after[..end];
        (!name.is_empty() && name.len() <= 256 && !name.contains(char::is_whitespace))
            .then_some(name)
    })
}

/// The offset of `<!DOCTYPE` if the prolog has one: after an optional XML declaration,
/// comments, processing instructions and white space (XML's `prolog`; a DOCTYPE anywhere
/// else is an error for the parser).
fn doctype_start(text: &str) -> Option<usize> {
    let mut i = 0;
    loop {
        i += text[i..].len() - text[i..].trim_start_matches(is_space).len();
        let rest = &text[i..];
        if rest.starts_with("<!DOCTYPE") {
            return Some(i);
        }
        let close = if rest.starts_with("<!--") {
            "-->"
        } else if rest.starts_with("<?") {
            "?>"
        } else {
            return None;
        };
        i += rest.find(close)? + close.len();
    }
}

fn is_space(c: char) -> bool {
    matches!(c, ' ' | '\t' | '\n' | '\r')
}

/// Entity name → value.
type Entities<'input> = HashMap<&'input str, &'input str>;

/// The entities of the internal subset of the DOCTYPE at `start` and the offset where the
/// document body begins; `None` if the DOCTYPE has no internal subset.
fn internal_subset(text: &str, start: usize) -> Result<Option<(Entities<'_>, usize)>, &str> {
    // '<!DOCTYPE' S Name (S ExternalID)? S? then '[' or '>': skip quoted literals.
    let mut i = start + "<!DOCTYPE".len();
    loop {
        match text[i..]
            .find(['[', '>', '"', '\''])
            .map(|k| (k, &text[i + k..]))
        {
            Some((_, rest)) if rest.starts_with('>') => return Ok(None),
            Some((k, rest)) if rest.starts_with('[') => {
                i += k + 1;
                break;
            }
            Some((k, rest)) => {
                let quote = &rest[..1];
                let end = rest[1..].find(quote).ok_or("an unterminated literal")?;
                i += k + 1 + end + 1;
            }
            None => return Err("no '[' or '>' after <!DOCTYPE"),
        }
    }
    let mut entities = Entities::new();
    loop {
        i += text[i..].len() - text[i..].trim_start_matches(is_space).len();
        let rest = &text[i..];
        let skip_to = |close: &str| rest.find(close).map(|k| k + close.len());
        let step = if rest.starts_with("<!ENTITY") {
            entity(rest, &mut entities)?
        } else if rest.starts_with("<!--") {
            skip_to("-->").ok_or("an unterminated comment")?
        } else if rest.starts_with("<?") {
            skip_to("?>").ok_or("an unterminated processing instruction")?
        } else if ["<!ELEMENT", "<!ATTLIST", "<!NOTATION"]
            .iter()
            .any(|d| rest.starts_with(d))
        {
            skip_to(">").ok_or("an unterminated declaration")?
        } else if let Some(after) = rest.strip_prefix(']') {
            let gap = after.len() - after.trim_start_matches(is_space).len();
            if !after[gap..].starts_with('>') {
                return Err("no '>' after the internal subset");
            }
            return Ok(Some((entities, i + 1 + gap + 1)));
        } else {
            return Err("an unknown declaration in the internal subset");
        };
        i += step;
    }
}

/// Reads `<!ENTITY [%] name (value | external id) >` at the start of `rest`, records a
/// literal value (external entities are not loaded: they expand to nothing) and returns the
/// declaration's length. A name declared twice is charged its longer value.
fn entity<'input>(
    rest: &'input str,
    entities: &mut Entities<'input>,
) -> Result<usize, &'static str> {
    let mut i = "<!ENTITY".len();
    let skip_spaces = |i: usize| i + rest[i..].len() - rest[i..].trim_start_matches(is_space).len();
    i = skip_spaces(i);
    if rest[i..].starts_with('%') {
        i = skip_spaces(i + 1);
    }
    let name_len = rest[i..]
        .find(|c: char| is_space(c) || matches!(c, '"' | '\'' | '>'))
        .ok_or("an unterminated entity declaration")?;
    let name = &rest[i..i + name_len];
    i = skip_spaces(i + name_len);
    loop {
        let k = rest[i..]
            .find(['>', '"', '\''])
            .ok_or("an unterminated entity declaration")?;
        let c = rest[i + k..].chars().next().unwrap_or('>');
        if c == '>' {
            return Ok(i + k + 1);
        }
        let start = i + k + 1;
        let len = rest[start..]
            .find(c)
            .ok_or("an unterminated entity value")?;
        let value = &rest[start..start + len];
        if k == 0 && entities.get(name).is_none_or(|v| v.len() < value.len()) {
            entities.insert(name, value);
        }
        i = start + len + 1;
    }
}
