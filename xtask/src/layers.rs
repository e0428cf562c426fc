//! `cargo xtask layers [SRC_DIR [ARCHITECTURE_MD]]`: the core crate's module graph against
//! the layer rule of ARCHITECTURE.md (defaults: `src/` and `ARCHITECTURE.md` of the
//! workspace root).
//!
//! The layer order is read from ARCHITECTURE.md, from the table after the line
//! [`MARKER`]: one row per layer, top to bottom; every backticked path in a row's second
//! cell is relative to `src/` and must exist, and those without an inner `/` (`so3.rs`,
//! `se3/`) are the row's top-level modules. Every top-level module of `src/` must be in
//! exactly one row.
//!
//! The graph: one node per module file (`lib.rs`, `a.rs` or `a/mod.rs`, `a/b.rs`, …); an
//! edge from a file to the module file every path it names resolves to: `use` trees and
//! paths in code that start with `crate`, `self`, `super` or a child module's name,
//! resolved to the longest prefix that is a module file (comments and literals are
//! skipped). Edges from a module into its own submodules are containment, not use (a
//! folder's `mod.rs` declares, re-exports and calls its files), and are left out.
//!
//! Fails on: a cycle (a strongly connected component of more than one file); an edge from
//! a layer to one below it in the table; a path through the crate root's re-exports
//! (`crate::Real`: it hides the module used); a table that does not match `src/`.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// The line of ARCHITECTURE.md after which the layer table starts.
pub const MARKER: &str = "<!-- layers: checked by `cargo xtask layers` -->";

/// A module path from the crate root: `[]` is `lib.rs`, `["se3", "congruence"]` is
/// `se3/congruence.rs`.
type Module = Vec<String>;

/// One source file: its module path and text.
pub struct SourceFile {
    /// The module the file defines.
    pub module: Module,
    /// Its contents.
    pub text: String,
}

/// One row of the layer table.
#[derive(Debug, PartialEq)]
pub struct Layer {
    /// The row's name (first cell).
    pub name: String,
    /// Its top-level modules.
    pub modules: Vec<String>,
    /// Every path the row names, relative to `src/`.
    pub paths: Vec<String>,
}

/// Runs the check; prints every problem found.
pub fn run(root: &Path, args: &[String]) -> ExitCode {
    let src = args.first().map_or_else(|| root.join("src"), PathBuf::from);
    let arch = args
        .get(1)
        .map_or_else(|| root.join("ARCHITECTURE.md"), PathBuf::from);
    let result = read_sources(&src).and_then(|files| {
        let table = std::fs::read_to_string(&arch)
            .map_err(|e| format!("cannot read {}: {e}", arch.display()))?;
        let layers = parse_layers(&table)?;
        Ok(check(&src, &files, &layers))
    });
    match result {
        Ok(problems) if problems.is_empty() => {
            println!(
                "layers: {} follows {} (no cycle, no upward use)",
                src.display(),
                arch.display()
            );
            ExitCode::SUCCESS
        }
        Ok(problems) => {
            for p in &problems {
                eprintln!("layers: {p}");
            }
            eprintln!("layers: {} problem(s) in {}", problems.len(), src.display());
            ExitCode::FAILURE
        }
        Err(e) => {
            eprintln!("layers: {e}");
            ExitCode::FAILURE
        }
    }
}

/// Every `.rs` file under `src`, with its module path.
fn read_sources(src: &Path) -> Result<Vec<SourceFile>, String> {
    let mut out = Vec::new();
    let mut dirs = vec![src.to_path_buf()];
    while let Some(dir) = dirs.pop() {
        let entries =
            std::fs::read_dir(&dir).map_err(|e| format!("cannot read {}: {e}", dir.display()))?;
        for entry in entries {
            let path = entry.map_err(|e| e.to_string())?.path();
            if path.is_dir() {
                dirs.push(path);
            } else if path.extension().is_some_and(|x| x == "rs") {
                let rel = path.strip_prefix(src).map_err(|e| e.to_string())?;
                let text = std::fs::read_to_string(&path)
                    .map_err(|e| format!("{}: {e}", path.display()))?;
                out.push(SourceFile {
                    module: module_of(rel),
                    text,
                });
            }
        }
    }
    out.sort_by(|a, b| a.module.cmp(&b.module));
    Ok(out)
}

/// The module a file path (relative to `src/`) defines.
fn module_of(rel: &Path) -> Module {
    let mut m: Module = rel
        .iter()
        .map(|c| c.to_string_lossy().into_owned())
        .collect();
    let last = m.pop().unwrap_or_default();
    let stem = last.trim_end_matches(".rs");
    if !(m.is_empty() && stem == "lib" || stem == "mod") {
        m.push(stem.to_string());
    }
    m
}

/// The rows of the table after [`MARKER`] (header and separator rows skipped).
pub fn parse_layers(markdown: &str) -> Result<Vec<Layer>, String> {
    let after = markdown
        .split_once(MARKER)
        .ok_or_else(|| format!("ARCHITECTURE.md has no line {MARKER}"))?
        .1;
    let rows: Vec<&str> = after
        .lines()
        .map(str::trim)
        .skip_while(|l| l.is_empty())
        .take_while(|l| l.starts_with('|'))
        .skip(2)
        .collect();
    let layers: Vec<Layer> = rows
        .iter()
        .map(|r| parse_row(r))
        .collect::<Result<_, _>>()?;
    if layers.is_empty() {
        return Err("the layer table after the marker has no rows".into());
    }
    Ok(layers)
}

fn parse_row(row: &str) -> Result<Layer, String> {
    let cells: Vec<&str> = row.trim_matches('|').split('|').map(str::trim).collect();
    let [name, files, ..] = cells[..] else {
        return Err(format!("layer row {row:?} has fewer than two cells"));
    };
    let paths: Vec<String> = files
        .split('`')
        .skip(1)
        .step_by(2)
        .map(str::to_string)
        .collect();
    let modules = paths
        .iter()
        .filter(|p| !p.trim_end_matches('/').contains('/'))
        .map(|p| p.trim_end_matches('/').trim_end_matches(".rs").to_string())
        .collect();
    Ok(Layer {
        name: name.to_string(),
        modules,
        paths,
    })
}

/// All problems of `files` (read from `src`) against `layers`.
pub fn check(src: &Path, files: &[SourceFile], layers: &[Layer]) -> Vec<String> {
    let mut problems = table_problems(src, files, layers);
    problems.append(&mut graph_problems(files, layers));
    problems
}

/// The cycles, upward uses and uses through the crate root of `files`.
fn graph_problems(files: &[SourceFile], layers: &[Layer]) -> Vec<String> {
    let (graph, mut problems) = build_graph(files);
    problems.extend(
        cycles(&graph)
            .iter()
            .map(|c| format!("import cycle: {}", c.join(" → "))),
    );
    let rank: BTreeMap<&str, usize> = layers
        .iter()
        .enumerate()
        .flat_map(|(i, l)| l.modules.iter().map(move |m| (m.as_str(), i)))
        .collect();
    for (from, tos) in &graph {
        for to in tos {
            let (Some(a), Some(b)) = (top_rank(&rank, from), top_rank(&rank, to)) else {
                continue;
            };
            if b > a {
                problems.push(format!(
                    "{} (layer {}) uses {}, of layer {} below it",
                    file_name(from),
                    layers[a].name,
                    file_name(to),
                    layers[b].name
                ));
            }
        }
    }
    problems
}

fn top_rank(rank: &BTreeMap<&str, usize>, m: &Module) -> Option<usize> {
    m.first().and_then(|t| rank.get(t.as_str()).copied())
}

/// The table against the tree: every path exists, every top-level module in one row.
fn table_problems(src: &Path, files: &[SourceFile], layers: &[Layer]) -> Vec<String> {
    let mut problems = Vec::new();
    for l in layers {
        for p in &l.paths {
            if !src.join(p).exists() {
                problems.push(format!("layer {}: {p} is not in {}", l.name, src.display()));
            }
        }
    }
    let tops: BTreeSet<&String> = files.iter().filter_map(|f| f.module.first()).collect();
    for t in tops {
        let rows: Vec<&str> = layers
            .iter()
            .filter(|l| l.modules.contains(t))
            .map(|l| l.name.as_str())
            .collect();
        if rows.len() != 1 {
            problems.push(format!(
                "module {t} is in {} rows of the layer table ({rows:?}), not one",
                rows.len()
            ));
        }
    }
    problems
}

/// A module's display name: its file.
fn file_name(m: &Module) -> String {
    if m.is_empty() {
        "lib.rs".into()
    } else {
        m.join("/")
    }
}

/// The edges between module files (containment left out), and the paths that go
/// through the crate root's re-exports.
fn build_graph(files: &[SourceFile]) -> (BTreeMap<Module, BTreeSet<Module>>, Vec<String>) {
    let modules: BTreeSet<Module> = files.iter().map(|f| f.module.clone()).collect();
    let mut graph = BTreeMap::new();
    let mut root_uses = Vec::new();
    for f in files {
        let edges: &mut BTreeSet<Module> = graph.entry(f.module.clone()).or_default();
        for path in crate::rust_paths::paths(&f.module, &f.text, &modules) {
            let (target, rest) = resolve(&modules, &path);
            if target.is_empty() && !rest.is_empty() && !f.module.is_empty() {
                root_uses.push(format!(
                    "{} names crate::{} through the crate root: name its module",
                    file_name(&f.module),
                    rest.join("::")
                ));
            }
            if !target.starts_with(&f.module) {
                edges.insert(target);
            }
        }
    }
    (graph, root_uses)
}

/// The module file a path from the crate root lies in (its longest prefix that is one),
/// and the rest of the path.
fn resolve(modules: &BTreeSet<Module>, path: &[String]) -> (Module, Vec<String>) {
    let best = (0..=path.len())
        .rev()
        .find(|n| modules.contains(&path[..*n].to_vec()))
        .unwrap_or(0);
    (path[..best].to_vec(), path[best..].to_vec())
}

/// Every strongly connected component of more than one node, as a cycle through it.
pub fn cycles(graph: &BTreeMap<Module, BTreeSet<Module>>) -> Vec<Vec<String>> {
    let mut out = Vec::new();
    let mut seen = BTreeSet::new();
    for start in graph.keys() {
        if seen.contains(start) {
            continue;
        }
        let component: BTreeSet<&Module> = graph
            .keys()
            .filter(|m| reaches(graph, start, m) && reaches(graph, m, start))
            .collect();
        seen.extend(component.iter().map(|m| (*m).clone()));
        if component.len() > 1 {
            out.push(cycle_through(graph, start, &component));
        }
    }
    out
}

/// Whether `to` can be reached from `from` (every node reaches itself).
fn reaches(graph: &BTreeMap<Module, BTreeSet<Module>>, from: &Module, to: &Module) -> bool {
    let mut stack = vec![from];
    let mut visited = BTreeSet::new();
    while let Some(m) = stack.pop() {
        if m == to {
            return true;
        }
        if visited.insert(m) {
            stack.extend(graph.get(m).into_iter().flatten());
        }
    }
    false
}

/// A shortest cycle from `start` back to it within `component` (breadth first).
fn cycle_through(
    graph: &BTreeMap<Module, BTreeSet<Module>>,
    start: &Module,
    component: &BTreeSet<&Module>,
) -> Vec<String> {
    let mut parent: BTreeMap<&Module, &Module> = BTreeMap::new();
    let mut queue = std::collections::VecDeque::from([start]);
    while let Some(m) = queue.pop_front() {
        for next in graph.get(m).into_iter().flatten() {
            if next == start {
                // m, its parent, …, back to start; then reversed into start → … → start.
                let mut back = vec![file_name(start)];
                let mut at = m;
                while at != start {
                    back.push(file_name(at));
                    at = parent[at];
                }
                back.push(file_name(start));
                back.reverse();
                return back;
            }
            if component.contains(next) && !parent.contains_key(next) {
                parent.insert(next, m);
                queue.push_back(next);
            }
        }
    }
    vec![file_name(start)]
}

#[cfg(test)]
mod tests {
    use super::*;

    fn file(path: &str, text: &str) -> SourceFile {
        SourceFile {
            module: module_of(Path::new(path)),
            text: text.to_string(),
        }
    }

    fn layer(name: &str, modules: &[&str]) -> Layer {
        Layer {
            name: name.into(),
            modules: modules.iter().map(|m| m.to_string()).collect(),
            paths: Vec::new(),
        }
    }

    /// se3 → transport → chain → transport, the shape of the cycle this tool was written
    /// for: reported as a cycle, and se3's use of the lower layer as upward.
    #[test]
    fn a_cycle_and_an_upward_use_fail() {
        let files = [
            file("lib.rs", "pub mod se3; mod transport; pub mod chain;"),
            file("se3.rs", "use crate::transport::Congruence;"),
            file(
                "transport.rs",
                "use crate::chain::ChainView; use crate::se3::Transform;",
            ),
            file(
                "chain.rs",
                "pub use crate::transport::X; fn f() { crate::se3::exp(); }",
            ),
        ];
        let layers = [
            layer("se3", &["se3"]),
            layer("chain", &["chain", "transport"]),
        ];
        let problems = graph_problems(&files, &layers);
        assert!(
            problems.contains(&"import cycle: chain → transport → chain".to_string()),
            "{problems:?}"
        );
        assert!(
            problems
                .contains(&"se3 (layer se3) uses transport, of layer chain below it".to_string()),
            "{problems:?}"
        );
        assert_eq!(problems.len(), 2, "{problems:?}");
    }

    /// A three-file cycle is found whole, whichever file the search starts from.
    #[test]
    fn a_long_cycle_is_reported_once() {
        let files = [
            file("a.rs", "use crate::b::X;"),
            file("b.rs", "use crate::c::{Y, Z};"),
            file("c.rs", "fn f() { super::a::g(); }"),
            file("d.rs", "use crate::a;"),
        ];
        let layers = [layer("all", &["a", "b", "c", "d"])];
        assert_eq!(
            graph_problems(&files, &layers),
            ["import cycle: a → b → c → a"]
        );
    }

    /// A folder's mod.rs using its own files is containment, not a cycle; layers may use
    /// those above them; `mod tests` using `super::*` is the file itself.
    #[test]
    fn containment_and_downward_uses_pass() {
        let files = [
            file("lib.rs", "pub use scalar::Real; mod scalar; mod x;"),
            file(
                "scalar.rs",
                "pub trait Real {} #[cfg(test)] mod tests { use super::*; }",
            ),
            file("x/mod.rs", "mod y; pub use y::Y; fn f() { y::g(); }"),
            file("x/y.rs", "use super::Shared; use crate::scalar::Real;"),
        ];
        let layers = [layer("scalar", &["scalar"]), layer("x", &["x"])];
        assert_eq!(graph_problems(&files, &layers), Vec::<String>::new());
    }

    #[test]
    fn paths_through_the_crate_root_fail() {
        let files = [
            file("lib.rs", "pub use scalar::Real; mod scalar; mod so3;"),
            file("scalar.rs", ""),
            file("so3.rs", "use crate::Real;"),
        ];
        let layers = [layer("scalar", &["scalar"]), layer("so3", &["so3"])];
        assert_eq!(
            graph_problems(&files, &layers),
            ["so3 names crate::Real through the crate root: name its module"]
        );
    }

    #[test]
    fn the_table_is_read_after_the_marker() {
        let md = format!(
            "text\n\n{MARKER}\n\n| layer | files | concept |\n|---|---|---|\n\
             | scalar | `scalar/` (kernels in `scalar/sincos.rs`) | numbers |\n\
             | se3 | `se3/`, `rotation_forms.rs` | transforms |\n\nafter\n"
        );
        let layers = parse_layers(&md).unwrap();
        assert_eq!(layers.len(), 2);
        assert_eq!(layers[0].modules, ["scalar"]);
        assert_eq!(layers[0].paths, ["scalar/", "scalar/sincos.rs"]);
        assert_eq!(layers[1].modules, ["se3", "rotation_forms"]);
        assert!(parse_layers("no marker").is_err());
    }

    /// The repository's own tree follows its ARCHITECTURE.md (what CI's step checks).
    #[test]
    fn this_repository_follows_its_layers() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).parent().unwrap();
        let src = root.join("src");
        let files = read_sources(&src).unwrap();
        let md = std::fs::read_to_string(root.join("ARCHITECTURE.md")).unwrap();
        let problems = check(&src, &files, &parse_layers(&md).unwrap());
        assert_eq!(problems, Vec::<String>::new());
    }
}
