//! The module layering of `src/`, read from the source text (std only).
//!
//! The graph is derived from the paths the code names, with comments (doc comments and their
//! doctests included), string literals and character literals removed first: every path that
//! starts with `crate::`, `truecost::` (the library, as the binary's `src/cli/` names it) or
//! `super::` (resolved against the file's own module), use-trees such as
//! `use crate::{a, b::{c, d}}` expanded into one path per leaf. A file's module is its place
//! under `src/`: `src/a/b.rs` is `a::b`, `src/a/mod.rs` is `a`, `src/lib.rs` and `src/main.rs`
//! are the roots. Two rules:
//!
//! * **Layering** ([`LAYERS`]): a top-level module of `src/` names only modules of strictly
//!   lower layers. Two modules of the same layer name neither each other, and every top-level
//!   module must be placed in a layer (a new module is placed before it may pass).
//! * **No cycles between siblings**: inside each folder module (`src/a/` for `a`), the child
//!   modules (files `a/x.rs`, and folders `a/y/` with everything under them) form a graph —
//!   `x → y` when a file of `x` names `a::y` through `super::y`, `crate::a::y`, or a
//!   `super::`/`crate::` use-tree that reaches it — and that graph has no cycle, of any length.
//!   The parent and its children are exempt: `a/mod.rs` naming `a::x`, or `a/x.rs` naming
//!   an item of `a` itself (`super::Verdict`), are not sibling edges. The top level (`src/`)
//!   is left to the layering rule, which is stricter.

use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::{Path, PathBuf};

/// The layers of `src/`'s top-level modules, lowest first. Shared utilities sit at the bottom;
/// then the exact values; the exact algebra built on them alone (polynomials and their real
/// roots, algebraic numbers, exact rational and modular linear algebra), which the stochastic
/// solvers, the claims engines and the objectives all use; the planning graph, the paper's
/// problems and the deterministic solvers; the stochastic model; the learners and the formats of
/// the field (Storm's DRN, PRISM); the claims engines (docs/spec.md §6); the Gymnasium
/// environments; the three objectives over any stochastic model, which load environments; the
/// paper's experiments; the figures drawn from problems, environments and experiment reports;
/// and the command line on top, which parses, calls one library function and prints.
const LAYERS: &[&[&str]] = &[
    &["echo"],
    &["atomic", "bounded"],
    &["value"],
    &["algebra"],
    &["model", "certificate"],
    &["problems", "solvers"],
    &["planning", "stochastic"],
    &["learning", "formats"],
    &["claims"],
    &["envs"],
    &["objectives", "experiments"],
    &["figures"],
    &["cli"],
];

fn src_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("src")
}

/// Every `.rs` file under `dir`, sorted.
fn rust_files(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for entry in fs::read_dir(&d).unwrap_or_else(|e| panic!("{}: {e}", d.display())) {
            let path = entry.expect("directory entry").path();
            if path.is_dir() {
                stack.push(path);
            } else if path.extension().is_some_and(|e| e == "rs") {
                out.push(path);
            }
        }
    }
    out.sort();
    out
}

/// The module path of a file under `src/` (`a/b.rs` → `[a, b]`, `a/mod.rs` → `[a]`,
/// `lib.rs` and `main.rs` → `[]`).
fn module_of(rel: &Path) -> Vec<String> {
    let mut parts: Vec<String> = rel
        .components()
        .map(|c| c.as_os_str().to_string_lossy().into_owned())
        .collect();
    let last = parts.pop().expect("a file name");
    let stem = last.strip_suffix(".rs").expect("a .rs file").to_string();
    let at_root = parts.is_empty();
    if stem != "mod" && !(at_root && (stem == "lib" || stem == "main")) {
        parts.push(stem);
    }
    parts
}

/// The code of a Rust file with comments, string literals and character literals blanked
/// (replaced by spaces; newlines kept), so that only real paths remain.
fn code_only(text: &str) -> String {
    let s: Vec<char> = text.chars().collect();
    let mut out = String::with_capacity(text.len());
    let blank = |out: &mut String, c: char| out.push(if c == '\n' { '\n' } else { ' ' });
    let mut i = 0;
    while i < s.len() {
        let c = s[i];
        let next = s.get(i + 1).copied();
        if c == '/' && next == Some('/') {
            while i < s.len() && s[i] != '\n' {
                i += 1;
            }
        } else if c == '/' && next == Some('*') {
            // Block comments nest in Rust.
            let mut depth = 0;
            while i < s.len() {
                if s[i] == '/' && s.get(i + 1) == Some(&'*') {
                    depth += 1;
                    i += 2;
                } else if s[i] == '*' && s.get(i + 1) == Some(&'/') {
                    depth -= 1;
                    i += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    blank(&mut out, s[i]);
                    i += 1;
                }
            }
        } else if c == 'r'
            && (next == Some('"') || next == Some('#'))
            && !s[..i]
                .last()
                .is_some_and(|p| p.is_alphanumeric() || *p == '_')
        {
            // A raw string r"…" or r#"…"#.
            let mut j = i + 1;
            let mut hashes = 0;
            while s.get(j) == Some(&'#') {
                hashes += 1;
                j += 1;
            }
            if s.get(j) != Some(&'"') {
                out.push(c);
                i += 1;
                continue;
            }
            j += 1;
            loop {
                if j >= s.len() {
                    break;
                }
                if s[j] == '"' && (0..hashes).all(|k| s.get(j + 1 + k) == Some(&'#')) {
                    j += 1 + hashes;
                    break;
                }
                blank(&mut out, s[j]);
                j += 1;
            }
            out.push(' ');
            i = j;
        } else if c == '"' {
            i += 1;
            while i < s.len() && s[i] != '"' {
                if s[i] == '\\' {
                    i += 1;
                }
                if let Some(&ch) = s.get(i) {
                    blank(&mut out, ch);
                }
                i += 1;
            }
            i += 1;
            out.push(' ');
        } else if c == '\'' {
            // A character literal ('x', '\n', '\u{1F600}') or a lifetime ('a).
            if next == Some('\\') {
                i += 2;
                while i < s.len() && s[i] != '\'' {
                    i += 1;
                }
                i += 1;
                out.push(' ');
            } else if s.get(i + 2) == Some(&'\'') {
                i += 3;
                out.push(' ');
            } else {
                out.push(c);
                i += 1;
            }
        } else {
            out.push(c);
            i += 1;
        }
    }
    out
}

/// The tokens that matter for paths: identifiers, `::`, `{`, `}`, `,`, `*`; anything else is
/// a separator (`;`).
fn tokens(code: &str) -> Vec<String> {
    let s: Vec<char> = code.chars().collect();
    let mut out = Vec::new();
    let mut i = 0;
    while i < s.len() {
        let c = s[i];
        if c.is_alphanumeric() || c == '_' || c == '$' {
            let start = i;
            while i < s.len() && (s[i].is_alphanumeric() || s[i] == '_' || s[i] == '$') {
                i += 1;
            }
            out.push(s[start..i].iter().collect());
        } else if c == ':' && s.get(i + 1) == Some(&':') {
            out.push("::".into());
            i += 2;
        } else if matches!(c, '{' | '}' | ',' | '*') {
            out.push(c.to_string());
            i += 1;
        } else if c.is_whitespace() {
            i += 1;
        } else {
            out.push(";".into());
            i += 1;
        }
    }
    out
}

/// Parses a use-tree (or a plain path) at `toks[*i]` onward, below `prefix`; pushes every
/// leaf path (a glob `*` and `self` end at their prefix).
fn use_tree(toks: &[String], i: &mut usize, prefix: Vec<String>, out: &mut Vec<Vec<String>>) {
    let mut path = prefix;
    loop {
        match toks.get(*i).map(String::as_str) {
            Some("{") => {
                *i += 1;
                loop {
                    match toks.get(*i).map(String::as_str) {
                        Some("}") => {
                            *i += 1;
                            return;
                        }
                        Some(",") => *i += 1,
                        None => return,
                        Some(_) => {
                            let before = *i;
                            use_tree(toks, i, path.clone(), out);
                            if *i == before {
                                *i += 1;
                            }
                        }
                    }
                }
            }
            Some("*") | Some("self") => {
                *i += 1;
                out.push(path);
                return;
            }
            Some(t) if t.starts_with(|c: char| c.is_alphanumeric() || c == '_') => {
                path.push(t.to_string());
                *i += 1;
                if toks.get(*i).map(String::as_str) == Some("::") {
                    *i += 1;
                } else {
                    out.push(path);
                    return;
                }
            }
            _ => {
                out.push(path);
                return;
            }
        }
    }
}

/// Every module path the code of a file in module `here` names, made absolute.
fn named_paths(code: &str, here: &[String]) -> Vec<Vec<String>> {
    let toks = tokens(code);
    let mut out = Vec::new();
    let mut i = 0;
    while i < toks.len() {
        let t = toks[i].as_str();
        let starts_path = i == 0 || toks[i - 1] != "::";
        if !starts_path || !matches!(t, "crate" | "truecost" | "super") {
            i += 1;
            continue;
        }
        // The module the path is relative to.
        let mut base: Vec<String> = if t == "super" {
            // `super` of `a/b.rs` (module a::b) is `a`; of `a/mod.rs` (module a) it is the root.
            let mut b = here.to_vec();
            b.pop();
            b
        } else {
            Vec::new()
        };
        i += 1;
        if toks.get(i).map(String::as_str) != Some("::") {
            continue;
        }
        i += 1;
        while toks.get(i).map(String::as_str) == Some("super") {
            base.pop();
            i += 1;
            if toks.get(i).map(String::as_str) == Some("::") {
                i += 1;
            }
        }
        use_tree(&toks, &mut i, base, &mut out);
    }
    out
}

/// One file: its path under `src/`, its module, and the module paths it names.
struct SourceFile {
    rel: PathBuf,
    module: Vec<String>,
    names: Vec<Vec<String>>,
}

fn read_sources() -> Vec<SourceFile> {
    let src = src_dir();
    rust_files(&src)
        .into_iter()
        .map(|path| {
            let rel = path.strip_prefix(&src).expect("under src").to_path_buf();
            let module = module_of(&rel);
            let text = fs::read_to_string(&path).expect("readable source");
            let names = named_paths(&code_only(&text), &module);
            SourceFile { rel, module, names }
        })
        .collect()
}

fn all_modules(files: &[SourceFile]) -> BTreeSet<Vec<String>> {
    files.iter().map(|f| f.module.clone()).collect()
}

/// For every top-level module of `src/`, the top-level modules its files name, with witnesses
/// (each file that names it, with the first path it names).
fn top_level_graph(files: &[SourceFile]) -> BTreeMap<String, BTreeMap<String, String>> {
    let modules = all_modules(files);
    let tops: BTreeSet<String> = modules
        .iter()
        .filter(|m| m.len() == 1)
        .map(|m| m[0].clone())
        .collect();
    let mut graph: BTreeMap<String, BTreeMap<String, String>> = BTreeMap::new();
    for f in files {
        let Some(from) = f.module.first() else {
            continue;
        };
        for p in &f.names {
            let Some(to) = p.first() else { continue };
            if to != from && tops.contains(to) {
                let witnesses = graph.entry(from.clone()).or_default().entry(to.clone());
                let file = f.rel.display().to_string();
                let w = witnesses.or_default();
                if !w.contains(&file) {
                    let sep = if w.is_empty() { "" } else { "; " };
                    w.push_str(&format!("{sep}{file} names {}", p.join("::")));
                }
            }
        }
    }
    graph
}

/// For every folder module below the top level, the edges between its children: `(folder,
/// from child, to child)` with a witness.
fn sibling_graph(
    files: &[SourceFile],
) -> BTreeMap<Vec<String>, BTreeMap<(String, String), String>> {
    let modules = all_modules(files);
    let mut graph: BTreeMap<Vec<String>, BTreeMap<(String, String), String>> = BTreeMap::new();
    for f in files {
        // Every folder module strictly above the file's module, below the root.
        for depth in 1..f.module.len() {
            let folder = &f.module[..depth];
            let from = &f.module[depth];
            for p in &f.names {
                if p.len() <= depth || p[..depth] != *folder {
                    continue;
                }
                let to = &p[depth];
                if to == from || !modules.contains(&p[..=depth]) {
                    continue;
                }
                graph
                    .entry(folder.to_vec())
                    .or_default()
                    .entry((from.clone(), to.clone()))
                    .or_insert_with(|| format!("{} names {}", f.rel.display(), p.join("::")));
            }
        }
    }
    graph
}

/// A cycle in a directed graph given as edges, if any (as the list of its nodes).
fn find_cycle(edges: &BTreeSet<(String, String)>) -> Option<Vec<String>> {
    let nodes: BTreeSet<&String> = edges.iter().flat_map(|(a, b)| [a, b]).collect();
    // 0 unvisited, 1 on the stack, 2 done.
    let mut state: BTreeMap<&String, u8> = nodes.iter().map(|n| (*n, 0)).collect();
    fn visit<'a>(
        n: &'a String,
        edges: &'a BTreeSet<(String, String)>,
        state: &mut BTreeMap<&'a String, u8>,
        stack: &mut Vec<&'a String>,
    ) -> Option<Vec<String>> {
        state.insert(n, 1);
        stack.push(n);
        for (_, m) in edges.iter().filter(|(a, _)| a == n) {
            match state[m] {
                1 => {
                    let at = stack.iter().position(|s| *s == m).expect("on the stack");
                    let mut cycle: Vec<String> =
                        stack[at..].iter().map(|s| s.to_string()).collect();
                    cycle.push(m.clone());
                    return Some(cycle);
                }
                0 => {
                    if let Some(c) = visit(m, edges, state, stack) {
                        return Some(c);
                    }
                }
                _ => {}
            }
        }
        stack.pop();
        state.insert(n, 2);
        None
    }
    for n in &nodes {
        if state[*n] == 0 {
            let mut stack = Vec::new();
            if let Some(c) = visit(n, edges, &mut state, &mut stack) {
                return Some(c);
            }
        }
    }
    None
}

fn layer_of(module: &str) -> Option<usize> {
    LAYERS.iter().position(|l| l.contains(&module))
}

#[test]
fn every_top_level_module_has_a_layer() {
    let files = read_sources();
    let unplaced: Vec<String> = all_modules(&files)
        .into_iter()
        .filter(|m| m.len() == 1 && layer_of(&m[0]).is_none())
        .map(|m| m[0].clone())
        .collect();
    assert!(
        unplaced.is_empty(),
        "top-level modules of src/ without a layer in LAYERS: {unplaced:?}"
    );
    let placed: Vec<&str> = LAYERS.iter().flat_map(|l| l.iter().copied()).collect();
    let known = all_modules(&files);
    let stale: Vec<&&str> = placed
        .iter()
        .filter(|m| !known.contains(&vec![m.to_string()]))
        .collect();
    assert!(
        stale.is_empty(),
        "LAYERS names no module of src/: {stale:?}"
    );
}

#[test]
fn top_level_modules_import_only_lower_layers() {
    let files = read_sources();
    let graph = top_level_graph(&files);
    let mut violations = Vec::new();
    for (from, targets) in &graph {
        for (to, witness) in targets {
            let (Some(lf), Some(lt)) = (layer_of(from), layer_of(to)) else {
                continue; // reported by every_top_level_module_has_a_layer
            };
            if lt >= lf {
                violations.push(format!(
                    "{from} (layer {lf}) names {to} (layer {lt}): {witness}"
                ));
            }
        }
    }
    assert!(
        violations.is_empty(),
        "imports that do not go down the layers:\n  {}",
        violations.join("\n  ")
    );
}

#[test]
fn no_cycle_between_sibling_modules() {
    let files = read_sources();
    let mut cycles = Vec::new();
    for (folder, edges) in sibling_graph(&files) {
        let pairs: BTreeSet<(String, String)> = edges.keys().cloned().collect();
        if let Some(cycle) = find_cycle(&pairs) {
            let witnesses: Vec<String> = cycle
                .windows(2)
                .map(|w| edges[&(w[0].clone(), w[1].clone())].clone())
                .collect();
            cycles.push(format!(
                "in {}: {} ({})",
                folder.join("::"),
                cycle.join(" → "),
                witnesses.join("; ")
            ));
        }
    }
    assert!(
        cycles.is_empty(),
        "sibling modules that name each other:\n  {}",
        cycles.join("\n  ")
    );
}

/// Pairs `(from, to)` of top-level modules where `from` names nothing of `to` although the
/// layers would allow it: the discount engine takes its arithmetic from the algebra layer, not
/// from the claims engine that checks it.
const APART: &[(&str, &str)] = &[("objectives", "claims")];

/// The edges of `graph` that [`APART`]-style `pairs` forbid, with their witnesses.
fn forbidden_edges(
    graph: &BTreeMap<String, BTreeMap<String, String>>,
    pairs: &[(&str, &str)],
) -> Vec<String> {
    pairs
        .iter()
        .filter_map(|&(from, to)| {
            let witness = graph.get(from)?.get(to)?;
            Some(format!("{from} names {to}: {witness}"))
        })
        .collect()
}

#[test]
fn modules_kept_apart_name_nothing_of_each_other() {
    let forbidden = forbidden_edges(&top_level_graph(&read_sources()), APART);
    assert!(
        forbidden.is_empty(),
        "imports between modules kept apart:\n  {}",
        forbidden.join("\n  ")
    );
}

/// The check of [`APART`] on a planted import: a file of `objectives` naming
/// `claims::discount::discount_set` is found, with its witness; one naming `algebra` is not.
#[test]
fn a_planted_import_between_modules_kept_apart_is_found() {
    let file = |rel: &str, names: &[&str]| {
        let rel = PathBuf::from(rel);
        SourceFile {
            module: module_of(&rel),
            rel,
            names: names
                .iter()
                .map(|n| n.split("::").map(String::from).collect())
                .collect(),
        }
    };
    let files = [
        file("objectives/mod.rs", &["algebra::intervals::Point"]),
        file(
            "objectives/parametric.rs",
            &["claims::discount::discount_set"],
        ),
        file("claims/mod.rs", &["algebra::poly::Poly"]),
        file("algebra/mod.rs", &[]),
    ];
    assert_eq!(
        forbidden_edges(&top_level_graph(&files), APART),
        ["objectives names claims: objectives/parametric.rs names claims::discount::discount_set"]
    );
    assert!(forbidden_edges(&top_level_graph(&files[..1]), APART).is_empty());
}

/// The reader itself, on small texts: comments, strings and characters hide their paths; use
/// trees expand; `super` resolves against the file's module.
#[test]
fn the_reader_finds_paths_in_code_only() {
    let here: Vec<String> = vec!["claims".into(), "registry".into()];
    let code = code_only(
        "// crate::figures in a comment\n/* crate::cli /* nested */ */\n\
         let s = \"crate::envs\"; let r = r#\"crate::envs\"#; let c = '\"'; fn f<'a>() {}\n\
         use super::{harnesses::{self, Harness}, report};\nuse crate::value::Rational;\n\
         x = truecost::stochastic::decimal(y); use super::super::model::Graph;",
    );
    let names = named_paths(&code, &here);
    let joined: BTreeSet<String> = names.iter().map(|p| p.join("::")).collect();
    let expected: BTreeSet<String> = [
        "claims::harnesses",
        "claims::harnesses::Harness",
        "claims::report",
        "value::Rational",
        "stochastic::decimal",
        "model::Graph",
    ]
    .into_iter()
    .map(String::from)
    .collect();
    assert_eq!(joined, expected);
    let edges: BTreeSet<(String, String)> = [("a", "b"), ("b", "c"), ("c", "a")]
        .into_iter()
        .map(|(a, b)| (a.to_string(), b.to_string()))
        .collect();
    assert!(find_cycle(&edges).is_some());
    let chain: BTreeSet<(String, String)> = [("a", "b"), ("b", "c"), ("a", "c")]
        .into_iter()
        .map(|(a, b)| (a.to_string(), b.to_string()))
        .collect();
    assert_eq!(find_cycle(&chain), None);
}

/// Pairs `(from, to)` of modules below the top level where `from` (and every module under it)
/// names nothing of `to`: `verify`'s shard module selects and merges the units of the plan
/// without calling into the registry that plans them, the runner that runs them, or the plan's
/// own types (it sees a unit only as the way shards share it).
const APART_INSIDE: &[(&str, &str)] = &[
    ("claims::shard", "claims::registry"),
    ("claims::shard", "claims::runner"),
    ("claims::shard", "claims::plan"),
];

/// The paths of `files` that [`APART_INSIDE`]-style `pairs` forbid, with their witnesses.
fn forbidden_inside(files: &[SourceFile], pairs: &[(&str, &str)]) -> Vec<String> {
    let split = |m: &str| -> Vec<String> { m.split("::").map(String::from).collect() };
    let mut out = Vec::new();
    for &(from, to) in pairs {
        let (from, to) = (split(from), split(to));
        for f in files.iter().filter(|f| f.module.starts_with(&from)) {
            if let Some(p) = f.names.iter().find(|p| p.starts_with(&to)) {
                out.push(format!(
                    "{} names {}: {} names {}",
                    from.join("::"),
                    to.join("::"),
                    f.rel.display(),
                    p.join("::")
                ));
            }
        }
    }
    out
}

#[test]
fn modules_kept_apart_inside_a_folder_name_nothing_of_each_other() {
    let files = read_sources();
    assert!(
        files.iter().any(|f| f.module == ["claims", "shard"]),
        "the shard module is where APART_INSIDE expects it"
    );
    let forbidden = forbidden_inside(&files, APART_INSIDE);
    assert!(
        forbidden.is_empty(),
        "imports between modules kept apart:\n  {}",
        forbidden.join("\n  ")
    );
}

/// The check of [`APART_INSIDE`] on the shard module's own source with a planted import of the
/// registry (a `use` and a path in an expression, each on its own): both are found, and the
/// source as it is passes.
#[test]
fn a_planted_import_of_the_registry_in_the_shard_module_is_found() {
    let rel = PathBuf::from("claims/shard.rs");
    let text = fs::read_to_string(src_dir().join(&rel)).expect("the shard module's source");
    let file = |text: &str| SourceFile {
        module: module_of(&rel),
        rel: rel.clone(),
        names: named_paths(&code_only(text), &module_of(&rel)),
    };
    assert!(forbidden_inside(&[file(&text)], APART_INSIDE).is_empty());
    for planted in [
        "use super::registry::{plan, Options};\n",
        "fn f() { let _ = crate::claims::registry::IDS; }\n",
        "use super::runner;\n",
    ] {
        let found = forbidden_inside(&[file(&format!("{text}{planted}"))], APART_INSIDE);
        assert_eq!(found.len(), 1, "{planted}: {found:?}");
        assert!(
            found[0].starts_with("claims::shard names claims::r"),
            "{found:?}"
        );
    }
    // A comment or a string naming the registry is not an import.
    let quoted = format!("{text}// super::registry::plan\nconst S: &str = \"super::registry\";\n");
    assert!(forbidden_inside(&[file(&quoted)], APART_INSIDE).is_empty());
}
