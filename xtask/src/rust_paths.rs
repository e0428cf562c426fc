//! The crate-internal paths a Rust source file names, for `cargo xtask layers`: a small
//! lexer (comments, strings and character literals skipped) and a reader of `use` trees
//! and of paths in code. Not a Rust parser: it knows `mod NAME { … }` blocks (so that
//! `super` inside `mod tests` means the file's module), `use` trees and `a::b::c` paths,
//! which is all the module graph needs.

use std::collections::BTreeSet;

/// A lexical token: an identifier (`$crate` gives `crate`), `::`, or one other character.
#[derive(Clone, Debug, PartialEq)]
enum Token {
    Ident(String),
    PathSep,
    Punct(char),
}

/// Skips a string literal whose opening quote is at `i` (escapes honoured); returns the
/// index after it.
fn skip_string(c: &[char], mut i: usize) -> usize {
    i += 1;
    while i < c.len() && c[i] != '"' {
        i += if c[i] == '\\' { 2 } else { 1 };
    }
    i + 1
}

/// Skips a raw string `r#…#"…"#…#` starting at the `r` at `i`.
fn skip_raw_string(c: &[char], mut i: usize) -> usize {
    i += 1;
    let mut hashes = 0;
    while c.get(i) == Some(&'#') {
        hashes += 1;
        i += 1;
    }
    i += 1; // the opening quote
    while i < c.len() {
        if c[i] == '"' && (1..=hashes).all(|k| c.get(i + k) == Some(&'#')) {
            return i + 1 + hashes;
        }
        i += 1;
    }
    i
}

/// Skips a comment starting at `i` (`//…` to the end of the line, `/*…*/` nested).
fn skip_comment(c: &[char], mut i: usize) -> usize {
    if c.get(i + 1) == Some(&'/') {
        while i < c.len() && c[i] != '\n' {
            i += 1;
        }
        return i;
    }
    let mut depth = 0;
    while i < c.len() {
        if c[i] == '/' && c.get(i + 1) == Some(&'*') {
            depth += 1;
            i += 2;
        } else if c[i] == '*' && c.get(i + 1) == Some(&'/') {
            depth -= 1;
            i += 2;
            if depth == 0 {
                return i;
            }
        } else {
            i += 1;
        }
    }
    i
}

/// Skips a character literal at `i`, or only the quote of a lifetime (`'a`).
fn skip_quote(c: &[char], i: usize) -> usize {
    if c.get(i + 1) == Some(&'\\') {
        let mut j = i + 2;
        while j < c.len() && c[j] != '\'' {
            j += 1;
        }
        j + 1
    } else if c.get(i + 2) == Some(&'\'') {
        i + 3
    } else {
        i + 1
    }
}

fn is_ident(ch: char) -> bool {
    ch.is_alphanumeric() || ch == '_'
}

fn tokens(text: &str) -> Vec<Token> {
    let c: Vec<char> = text.chars().collect();
    let mut out = Vec::new();
    let mut i = 0;
    while i < c.len() {
        let ch = c[i];
        let next = c.get(i + 1).copied();
        if ch.is_whitespace() {
            i += 1;
        } else if ch == '/' && matches!(next, Some('/' | '*')) {
            i = skip_comment(&c, i);
        } else if ch == '"' {
            i = skip_string(&c, i);
        } else if ch == 'r'
            && (next == Some('"') || next == Some('#') && matches!(c.get(i + 2), Some('#' | '"')))
        {
            i = skip_raw_string(&c, i);
        } else if ch == '\'' {
            i = skip_quote(&c, i);
        } else if ch == ':' && next == Some(':') {
            out.push(Token::PathSep);
            i += 2;
        } else if is_ident(ch) || ch == '$' && next.is_some_and(is_ident) {
            let start = if ch == '$' { i + 1 } else { i };
            i = start;
            while i < c.len() && is_ident(c[i]) {
                i += 1;
            }
            out.push(Token::Ident(c[start..i].iter().collect()));
        } else {
            out.push(Token::Punct(ch));
            i += 1;
        }
    }
    out
}

/// The crate-internal paths (from the crate root, e.g. `["se3", "Transform"]`) that the
/// file of module `module` names; `modules` are the crate's module files, which tell a
/// relative path into a child module from one into another crate.
pub fn paths(module: &[String], text: &str, modules: &BTreeSet<Vec<String>>) -> Vec<Vec<String>> {
    let t = tokens(text);
    let mut out = Vec::new();
    // One entry per open brace: the inline module it opens, if any.
    let mut braces: Vec<Option<String>> = Vec::new();
    let mut i = 0;
    while i < t.len() {
        let here: Vec<String> = module
            .iter()
            .cloned()
            .chain(braces.iter().flatten().cloned())
            .collect();
        match &t[i] {
            Token::Punct('{') => {
                let inline = match (i >= 2).then(|| (&t[i - 2], &t[i - 1])) {
                    Some((Token::Ident(m), Token::Ident(name))) if m == "mod" => Some(name.clone()),
                    _ => None,
                };
                braces.push(inline);
                i += 1;
            }
            Token::Punct('}') => {
                braces.pop();
                i += 1;
            }
            Token::Ident(kw) if kw == "use" => {
                let mut pos = i + 1;
                let mut tree = Vec::new();
                use_tree(&t, &mut pos, Vec::new(), &mut tree);
                out.extend(tree.iter().filter_map(|p| absolute(&here, p, modules)));
                i = pos;
            }
            Token::Ident(_)
                if t.get(i + 1) == Some(&Token::PathSep)
                    && (i == 0 || t[i - 1] != Token::PathSep) =>
            {
                let mut p = Vec::new();
                while let Some(Token::Ident(s)) = t.get(i) {
                    p.push(s.clone());
                    if t.get(i + 1) != Some(&Token::PathSep) {
                        break;
                    }
                    i += 2;
                }
                out.extend(absolute(&here, &p, modules));
                i += 1;
            }
            _ => i += 1,
        }
    }
    out
}

/// Reads a `use` tree at `pos` (after `use`), appending its full paths to `out`.
fn use_tree(t: &[Token], pos: &mut usize, mut prefix: Vec<String>, out: &mut Vec<Vec<String>>) {
    loop {
        match t.get(*pos) {
            Some(Token::Ident(s)) => {
                if s != "self" || prefix.is_empty() {
                    prefix.push(s.clone());
                }
                *pos += 1;
                if t.get(*pos) == Some(&Token::PathSep) {
                    *pos += 1;
                    continue;
                }
                if matches!(t.get(*pos), Some(Token::Ident(a)) if a == "as") {
                    *pos += 2;
                }
                out.push(prefix);
                return;
            }
            Some(Token::Punct('{')) => {
                *pos += 1;
                while !matches!(t.get(*pos), None | Some(Token::Punct('}'))) {
                    use_tree(t, pos, prefix.clone(), out);
                    if t.get(*pos) == Some(&Token::Punct(',')) {
                        *pos += 1;
                    }
                }
                *pos += 1;
                return;
            }
            Some(Token::Punct('*')) => {
                *pos += 1;
                out.push(prefix);
                return;
            }
            _ => return,
        }
    }
}

/// `path` as named in module `here`, from the crate root; `None` if it leads out of the
/// crate (another crate, a type's associated item, a generic parameter).
fn absolute(
    here: &[String],
    path: &[String],
    modules: &BTreeSet<Vec<String>>,
) -> Option<Vec<String>> {
    let first = path.first()?;
    let mut rest = &path[1..];
    let mut base: Vec<String> = match first.as_str() {
        "crate" => Vec::new(),
        "self" => here.to_vec(),
        "super" => {
            let mut b = here.to_vec();
            b.pop()?;
            while rest.first().is_some_and(|s| s == "super") {
                b.pop()?;
                rest = &rest[1..];
            }
            b
        }
        _ => {
            // A child module of this one, or not a path into the crate.
            let mut child = here.to_vec();
            child.push(first.clone());
            if !modules.contains(&child) {
                return None;
            }
            child
        }
    };
    base.extend(rest.iter().cloned());
    Some(base)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn m(s: &str) -> Vec<String> {
        s.split('/')
            .filter(|x| !x.is_empty())
            .map(str::to_string)
            .collect()
    }

    fn mods(list: &[&str]) -> BTreeSet<Vec<String>> {
        list.iter().map(|s| m(s)).collect()
    }

    #[test]
    fn use_trees_and_code_paths() {
        let text = r#"
            //! use crate::doc_only;
            use crate::{a::X, b::{self, Y as Z}};
            use super::sibling::W;
            pub(crate) use child::V;
            let s = "crate::in_string";
            fn f<'a>(c: char) { crate::c::g(); Self::H; T::ZERO; let q = '{'; }
            mod tests { use super::*; }
        "#;
        let modules = mods(&["", "a", "b", "c", "p", "p/me", "p/me/child", "p/sibling"]);
        let got = paths(&m("p/me"), text, &modules);
        let want = [
            "a/X",
            "b",
            "b/Y",
            "p/sibling/W",
            "p/me/child/V",
            "c/g",
            "p/me",
        ];
        assert_eq!(got, want.map(m).to_vec());
    }
}
