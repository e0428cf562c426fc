//! DTD entities that expand a small URDF to gigabytes (many references to a medium entity,
//! nested entities, references in attribute values) are refused with a clear error before
//! the XML parser builds the text, in bounded memory; a URDF that uses a few small entities
//! still parses.
//!
//! The memory bound is measured, not assumed: this test binary counts every allocation
//! (a counting global allocator) and the test checks the peak. The one test of this file
//! runs the cases one after the other so that the peak is theirs alone.

use ppoe_build::{ErrorKind, Urdf};
use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};

struct Counting;

static CURRENT: AtomicUsize = AtomicUsize::new(0);
static PEAK: AtomicUsize = AtomicUsize::new(0);

// SAFETY: forwards to the system allocator; only counts.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let p = System.alloc(layout);
        if !p.is_null() {
            let now = CURRENT.fetch_add(layout.size(), Ordering::Relaxed) + layout.size();
            PEAK.fetch_max(now, Ordering::Relaxed);
        }
        p
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        System.dealloc(ptr, layout);
        CURRENT.fetch_sub(layout.size(), Ordering::Relaxed);
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

/// The most the parse of one ~100 KB hostile URDF may allocate at once.
const PEAK_LIMIT: usize = 16 << 20;

fn urdf(dtd: &str, body: &str) -> String {
    format!(
        "<?xml version=\"1.0\"?>\n<!DOCTYPE robot [\n{dtd}\n]>\n<robot name=\"r\">\n  \
         <link name=\"a\">{body}</link>\n  <link name=\"b\"/>\n  <joint name=\"j\" \
         type=\"revolute\">\n    <parent link=\"a\"/>\n    <child link=\"b\"/>\n  </joint>\n\
         </robot>\n"
    )
}

/// Hostile URDFs of the quadratic class, each about 100 KB or less.
fn hostile() -> Vec<(&'static str, String)> {
    let medium = "x".repeat(40_000);
    let refs = |name: &str, n: usize| format!("&{name};").repeat(n);
    vec![
        (
            // 40 KB × 1500 references = 60 MB.
            "many references to one medium entity",
            urdf(&format!("<!ENTITY m \"{medium}\">"), &refs("m", 1500)),
        ),
        (
            // 40 KB × 250 = 10 MB per reference of `n`, × 1000 = 10 GB.
            "nested entities",
            urdf(
                &format!(
                    "<!ENTITY m \"{medium}\">\n<!ENTITY n \"{}\">",
                    refs("m", 250)
                ),
                &refs("n", 1000),
            ),
        ),
        (
            // The same in attribute values: 60 attributes of 250 references of 40 KB.
            "attribute-value entities",
            urdf(
                &format!("<!ENTITY m '{medium}'>"),
                &format!(
                    "<visual {}/>",
                    (0..60)
                        .map(|k| format!("a{k}=\"{}\"", refs("m", 250)))
                        .collect::<Vec<_>>()
                        .join(" ")
                ),
            ),
        ),
        (
            // A parameter entity is looked up by name like a general one.
            "parameter entity referenced as a general one",
            urdf(&format!("<!ENTITY % p \"{medium}\">"), &refs("p", 1500)),
        ),
        (
            // Entities declared after a comment and a processing instruction, DOCTYPE
            // after a comment.
            "declarations behind comments",
            urdf(
                &format!("<!-- ]> -->\n<?pi ]> ?>\n<!ELEMENT a ANY>\n<!ENTITY m \"{medium}\">"),
                &refs("m", 1500),
            )
            .replacen(
                "<!DOCTYPE",
                "<!-- <!DOCTYPE x [ ]> -->\n<?pi x?>\n<!DOCTYPE",
                1,
            ),
        ),
    ]
}

#[test]
fn quadratic_entity_expansion_is_refused_in_bounded_memory() {
    for (what, text) in hostile() {
        assert!(text.len() < 120_000, "{what}: {} bytes", text.len());
        let before = CURRENT.load(Ordering::Relaxed);
        PEAK.store(before, Ordering::Relaxed);
        let err = Urdf::parse(&text).expect_err(what);
        let peak = PEAK.load(Ordering::Relaxed) - before;
        assert_eq!(err.kind(), ErrorKind::Xml, "{what}: {err}");
        let msg = err.to_string();
        assert!(
            msg.contains("the DTD's entities expand the document by")
                && msg.contains("more than the 1048576 bytes allowed"),
            "{what}: {msg}"
        );
        // The error points at the DOCTYPE.
        assert!(err.position().is_some(), "{what}");
        assert!(peak < PEAK_LIMIT, "{what}: peak {peak} bytes");
        eprintln!("{what}: refused, peak {peak} bytes: {msg}");
    }

    // Billion laughs is refused too (before roxmltree's own loop detector is reached).
    let mut dtd = String::from("<!ENTITY l0 \"lol\">");
    for k in 1..=9 {
        dtd += &format!(
            "\n<!ENTITY l{k} \"{}\">",
            format!("&l{};", k - 1).repeat(10)
        );
    }
    let err = Urdf::parse(&urdf(&dtd, "&l9;")).unwrap_err();
    assert_eq!(err.kind(), ErrorKind::Xml);

    // Small entities within the budget are expanded as XML says.
    let ok = "<?xml version=\"1.0\"?>\n<!DOCTYPE robot [\n<!ENTITY len \"0.5\">\n\
              <!ENTITY nm 'arm'>\n]>\n<robot name=\"&nm;\">\n  <link name=\"a\"/>\n  \
              <link name=\"b\"/>\n  <joint name=\"j\" type=\"revolute\">\n    \
              <origin xyz=\"&len; 0 &len;\"/>\n    <parent link=\"a\"/>\n    \
              <child link=\"b\"/>\n  </joint>\n</robot>\n";
    let u = Urdf::parse(ok).unwrap();
    assert_eq!(u.name, "arm");
    assert_eq!(u.joints[0].child2parent[0][3], 0.5);
    assert_eq!(u.joints[0].child2parent[2][3], 0.5);

    // Just under the budget is accepted (the bound is not a blanket refusal).
    let under = urdf(
        &format!("<!ENTITY m \"{}\">", "x".repeat(1000)),
        &"&m;".repeat(1000),
    );
    assert!(Urdf::parse(&under).is_ok());
    let over = urdf(
        &format!("<!ENTITY m \"{}\">", "x".repeat(1000)),
        &"&m;".repeat(1049),
    );
    assert_eq!(Urdf::parse(&over).unwrap_err().kind(), ErrorKind::Xml);

    // A DOCTYPE the reader cannot follow is an error, never skipped.
    let unterminated = "<!DOCTYPE robot [ <!ENTITY m \"abc > ]><robot name=\"r\"/>";
    assert_eq!(
        Urdf::parse(unterminated).unwrap_err().kind(),
        ErrorKind::Xml
    );
}
