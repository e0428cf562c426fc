//! Strings that try to break out of generated source: every one is meant to end a comment
//! or a literal, splice lines, or inject code in Rust or C if it reached the output raw.
//! An injection compiles to `compile_error!` / `#error`, so a table that lets one through
//! fails to build instead of silently gaining an item.

/// The corpus: line breaks of every kind, comment delimiters, C line splices and trigraphs,
/// NUL and other controls, bidirectional controls, quotes and backslashes, non-ASCII.
pub const HOSTILE_STRINGS: &[&str] = &[
    "x\ncompile_error!(\"injected by a newline\");",
    "x\r\ncompile_error!(\"injected by CR LF\");",
    "x\rcompile_error!(\"injected by a bare CR\");",
    "x\u{2028}compile_error!(\"U+2028\");\u{2029}",
    "x\u{85}y\u{b}z\u{c}w",
    "*/ compile_error!(\"end of a block comment\"); /*",
    "x */\n#error injected after the end of a C comment\n/*",
    "/* nested /* comment",
    "\n#error injected by a newline in C\n",
    "x\\\n#error injected by a line splice",
    "tail backslash\\",
    "x??/\n#error injected by a trigraph splice",
    "trigraph tail ??/",
    "??= ??( ??) ??' ??< ??! ??> ??-",
    "nul\u{0}byte\u{1}\u{1f}\u{7f}",
    "\u{202e}reversed\u{202c} \u{2066}isolate\u{2069} \u{200f}\u{61c}",
    "\"quote\" 'single' `tick` \\backslash\\ \\\"",
    "\\u{a}compile_error!(\"fake escape\");",
    "名前 ünïcødé \u{1f527} \u{fffd}",
    "\u{feff}bom \u{200b}zero width \u{e000}private \u{ffff}",
    "// line comment\n//",
];
