//! No harness compares whole arrays, slices or vectors with `==` / `!=` (or `assert_eq!`-family
//! macros), in its own source or in the kernel code it reaches.
//!
//! Why: on arrays and slices of integers Rust's `==` is a `memcmp`, and CBMC's `memcmp` loops
//! once per **byte**; `#[kani::unwind(N)]` bounds that loop too, so `==` on `[i64; 24]` needs
//! unwind 193 and fails its unwinding assertion at any smaller bound (a failure even for a
//! `should_panic` harness). On other element types `==` is an element loop that the unwind must
//! cover as well. The harnesses compare element by element instead.
//!
//! How (a source scan, not type checking): comments and string literals are blanked; every
//! function of the scanned code is taken separately; a name is a *container* when it is a
//! parameter or `let` binding whose type mentions `[`, `Vec<` or `Values`, or whose initializer
//! is an array expression (`[…]`), `vec![…]`, `Vec::…`, `values()`, `….to_vec()`, `….collect()`,
//! a call of a scanned function declared to return an array or `Vec`, a container field, or a
//! copy (`x`, `*x`, `x.clone()`) of a container. A *container field* is a field of a struct
//! declared in the scanned files or the kernel whose type mentions `[` or `Vec<`, unless another
//! struct there has a field of that name with a scalar type (`Exploration::index` is a vector,
//! the walk's `Node::index` a `u32`: the scan cannot tell them apart). An operand of
//! `==`, `!=` or of `assert_eq!`, `assert_ne!`, `debug_assert_eq!`, `debug_assert_ne!` is a
//! container when it is such a name, a container field (`….cost_to_go`), a range slice
//! (`x[a..b]`), an array literal, `vec![…]`, or such a call; indexing one element (`v[p]`)
//! makes it a scalar again.
//!
//! What it cannot see: fields whose name is ambiguous (above); element types (it flags containers of any element type, which is
//! stricter than needed); containers reached through closure parameters, generic returns or
//! method chains on unknown types (`*h == v` is caught only because `v` is known); comparisons
//! inside called functions that are not in the scanned list below. The list is the kernel code
//! the harnesses call: `model.rs`, `value.rs`, `solvers/*.rs`, `claims::{exact, oracle, tiny,
//! c2, c3, c4}` (whole files but their unit tests), and `claims::qlearning::QProblem::{update,
//! updatable}` (the rest of `qlearning.rs`, the exhaustive order search, is never called by a
//! harness).

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

mod source_scan;
use source_scan::{blank, close_of, drop_test_modules, functions, is_ident};

/// A comparison the scan rejects: file, line and the text of the comparison.
#[derive(Debug, PartialEq)]
struct Finding {
    file: String,
    line: usize,
    text: String,
}

/// The position of the bracket that opens the group closing at `close`.
fn open_of(b: &[char], close: usize) -> usize {
    let mut depth = 0i32;
    for j in (0..=close).rev() {
        match b[j] {
            ')' | ']' | '}' => depth += 1,
            '(' | '[' | '{' => {
                depth -= 1;
                if depth == 0 {
                    return j;
                }
            }
            _ => {}
        }
    }
    0
}

/// Whether a type mentions an array, a slice or a vector.
fn container_type(t: &str) -> bool {
    t.contains('[') || t.contains("Vec<") || t.contains("Values")
}

/// Struct fields (`name: Type,` lines) whose type is a container, and those whose type is not
/// (the caller drops a name found in both: the scan cannot tell the structs apart).
fn fields_by_kind(code: &str) -> (BTreeSet<String>, BTreeSet<String>) {
    let (mut out, mut scalar) = (BTreeSet::new(), BTreeSet::new());
    let b: Vec<char> = code.chars().collect();
    let mut decls = String::new();
    let mut from = 0;
    while let Some(k) = code[from..].find("struct ").map(|k| k + from) {
        from = k + 7;
        if k > 0 && is_ident(b[k - 1]) {
            continue;
        }
        if let Some(open) = (from..b.len()).find(|&j| matches!(b[j], '{' | ';' | '(')) {
            if b[open] == '{' {
                let end = close_of(&b, open);
                decls.extend(b[open + 1..end - 1].iter());
                decls.push('\n');
                from = end;
            }
        }
    }
    for line in decls.lines() {
        let l = line
            .trim()
            .trim_start_matches("pub(crate) ")
            .trim_start_matches("pub ");
        if let Some((name, ty)) = l.split_once(':') {
            let name = name.trim();
            if !name.is_empty() && name.chars().all(is_ident) && l.ends_with(',') {
                if container_type(ty) {
                    out.insert(name.to_string());
                } else {
                    scalar.insert(name.to_string());
                }
            }
        }
    }
    (out, scalar)
}

/// Names of functions (in `code`) declared to return a container.
fn container_functions(code: &str) -> BTreeSet<String> {
    functions(code)
        .into_iter()
        .filter(|(_, sig, _)| sig.split_once("->").is_some_and(|(_, r)| container_type(r)))
        .map(|(name, _, _)| name)
        .collect()
}

/// What the scan knows about the code around one function.
struct Known<'a> {
    fields: &'a BTreeSet<String>,
    fns: &'a BTreeSet<String>,
    names: BTreeSet<String>,
}

impl Known<'_> {
    /// Whether the expression `e` (an operand or an initializer) is a whole container.
    fn container(&self, e: &str) -> bool {
        let e = e.trim();
        let e = e
            .trim_start_matches(['&', '*'])
            .trim_start_matches("mut ")
            .trim();
        if e.is_empty() {
            return false;
        }
        if e.starts_with('[') || e.starts_with("vec!") || e.starts_with("Vec::") {
            return true;
        }
        let b: Vec<char> = e.chars().collect();
        let last = b.len() - 1;
        if b[last] == ']' {
            let open = open_of(&b, last);
            let inside: String = b[open + 1..last].iter().collect();
            return inside.contains("..");
        }
        if b[last] == ')' {
            let open = open_of(&b, last);
            let callee: String = b[..open].iter().collect();
            let (receiver, method) = match callee.rfind(['.', ':']) {
                Some(k) => (&callee[..k], &callee[k + 1..]),
                None => ("", callee.as_str()),
            };
            return match method {
                "to_vec" | "collect" | "values" => true,
                "clone" => self.container(receiver.trim_end_matches(':')),
                m => self.fns.contains(m),
            };
        }
        // A field read, possibly after a call (`f(x).cost_to_go`), or a plain name.
        let tail = b.iter().rev().take_while(|&&c| is_ident(c)).count();
        let name: String = b[b.len() - tail..].iter().collect();
        match b.len().checked_sub(tail + 1).map(|k| b[k]) {
            Some('.') => self.fields.contains(&name),
            None => self.names.contains(&name),
            Some(_) => false,
        }
    }
}

/// The operand to the left of position `at` (exclusive) and to the right of `from`.
fn operands(b: &[char], at: usize, from: usize) -> (String, String) {
    let operand_char = |c: char| is_ident(c) || c == '.' || c == ':' || c == '&' || c == '*';
    // Left.
    let mut i = at;
    while i > 0 && b[i - 1].is_whitespace() {
        i -= 1;
    }
    let end = i;
    while i > 0 {
        let c = b[i - 1];
        if c == ')' || c == ']' {
            i = open_of(b, i - 1);
        } else if c == '&' && i > 1 && b[i - 2] == '&' {
            break;
        } else if operand_char(c) {
            i -= 1;
        } else {
            break;
        }
    }
    let left: String = b[i..end].iter().collect();
    // Right.
    let mut j = from;
    while j < b.len() && b[j].is_whitespace() {
        j += 1;
    }
    let start = j;
    while j < b.len() {
        let c = b[j];
        if c == '(' || c == '[' {
            j = close_of(b, j);
        } else if c == '!' && matches!(b.get(j + 1), Some('[') | Some('(')) {
            j += 1;
        } else if c == '&' && b.get(j + 1) == Some(&'&') {
            break;
        } else if operand_char(c) {
            j += 1;
        } else {
            break;
        }
    }
    let right: String = b[start..j].iter().collect();
    (left, right)
}

/// The comma-separated top-level arguments of the bracket group opening at `open`.
fn arguments(b: &[char], open: usize) -> Vec<String> {
    let end = close_of(b, open) - 1;
    let mut args = Vec::new();
    let (mut depth, mut start) = (0i32, open + 1);
    for j in open + 1..end {
        match b[j] {
            '(' | '[' | '{' => depth += 1,
            ')' | ']' | '}' => depth -= 1,
            ',' if depth == 0 => {
                args.push(b[start..j].iter().collect());
                start = j + 1;
            }
            _ => {}
        }
    }
    args.push(b[start..end].iter().collect());
    args
}

/// Container bindings of one function: its parameters and `let`s (see the module comment).
fn bindings(sig: &str, body: &str, known: &mut Known) {
    if let Some(params) = sig.find('(') {
        let b: Vec<char> = sig.chars().collect();
        let open = sig[..params].chars().count();
        for p in arguments(&b, open) {
            if let Some((name, ty)) = p.split_once(':') {
                let name = name.trim().trim_start_matches("mut ").trim();
                if container_type(ty) && name.chars().all(is_ident) {
                    known.names.insert(name.to_string());
                }
            }
        }
    }
    // Two passes, so that a copy of a container bound later in the text is seen.
    for _ in 0..2 {
        for stmt in body.split(';') {
            let Some(k) = stmt.find("let ") else { continue };
            let rest = &stmt[k + 4..];
            let Some(eq) = rest.find('=').filter(|&e| !rest[e..].starts_with("==")) else {
                continue;
            };
            let (pattern, init) = (&rest[..eq], &rest[eq + 1..]);
            let (pattern, ty) = match pattern.split_once(':') {
                Some((p, t)) => (p, t),
                None => (pattern, ""),
            };
            let pattern = pattern.trim();
            let init = init.trim();
            if pattern.starts_with('(') && init.starts_with('(') {
                // `let (a, b) = (x, y);`
                let pb: Vec<char> = pattern.chars().collect();
                let ib: Vec<char> = init.chars().collect();
                for (p, e) in arguments(&pb, 0).iter().zip(arguments(&ib, 0).iter()) {
                    let p = p.trim().trim_start_matches("mut ").trim();
                    if known.container(e) {
                        known.names.insert(p.to_string());
                    }
                }
                continue;
            }
            let name = pattern.trim_start_matches("mut ").trim();
            if name.chars().all(is_ident) && (container_type(ty) || known.container(init)) {
                known.names.insert(name.to_string());
            }
        }
    }
}

/// Every whole-container comparison in `code` (one file's text, `file` its name).
/// `fields` and `fns` are the container fields and container-returning functions known
/// from all scanned files; `only` restricts the scan to the named functions.
fn scan(
    file: &str,
    code: &str,
    fields: &BTreeSet<String>,
    fns: &BTreeSet<String>,
    only: Option<&[&str]>,
) -> Vec<Finding> {
    let code = drop_test_modules(&blank(code));
    let all: Vec<char> = code.chars().collect();
    let mut found = Vec::new();
    for (name, sig, body) in functions(&code) {
        if only.is_some_and(|names| !names.contains(&name.as_str())) {
            continue;
        }
        let mut known = Known {
            fields,
            fns,
            names: BTreeSet::new(),
        };
        bindings(&sig, &body, &mut known);
        let b: Vec<char> = body.chars().collect();
        let body_at = code.find(&body).unwrap_or(0);
        let line_of = |k: usize| {
            all[..code[..body_at].chars().count() + k]
                .iter()
                .filter(|&&c| c == '\n')
                .count()
                + 1
        };
        let mut report = |k: usize, text: String| {
            found.push(Finding {
                file: file.to_string(),
                line: line_of(k),
                text: text.split_whitespace().collect::<Vec<_>>().join(" "),
            })
        };
        for k in 0..b.len().saturating_sub(1) {
            let op = (b[k] == '=' || b[k] == '!') && b[k + 1] == '=';
            let single = k == 0 || !matches!(b[k - 1], '=' | '<' | '>' | '!');
            if op && single && b.get(k + 2) != Some(&'=') {
                let (l, r) = operands(&b, k, k + 2);
                if known.container(&l) || known.container(&r) {
                    report(k, format!("{l} {}= {r}", b[k]));
                }
            }
        }
        let text: String = b.iter().collect();
        for mac in ["assert_eq!", "assert_ne!"] {
            let mut from = 0;
            while let Some(k) = text[from..].find(mac).map(|k| k + from) {
                from = k + mac.len();
                let open = text[..from].chars().count();
                if b.get(open) != Some(&'(') {
                    continue;
                }
                let args = arguments(&b, open);
                if args.iter().take(2).any(|a| known.container(a)) {
                    let start = text[..k].chars().count();
                    let prefix = if text[..k].ends_with("debug_") {
                        "debug_"
                    } else {
                        ""
                    };
                    report(
                        start,
                        format!("{prefix}{mac}({})", args[..2.min(args.len())].join(",")),
                    );
                }
            }
        }
    }
    found
}

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// The scanned code: every harness source, and the kernel code the harnesses reach (`None`: the whole file but its unit tests; `Some`: these functions only).
fn scanned() -> Vec<(PathBuf, Option<&'static [&'static str]>)> {
    let mut files: Vec<(PathBuf, Option<&'static [&'static str]>)> = Vec::new();
    let mut harnesses: Vec<PathBuf> = std::fs::read_dir(root().join("proofs/src"))
        .expect("proofs/src")
        .map(|e| e.expect("entry").path())
        .filter(|p| p.extension().is_some_and(|x| x == "rs"))
        .collect();
    harnesses.sort();
    files.extend(harnesses.into_iter().map(|p| (p, None)));
    for k in [
        "kernel/src/model.rs",
        "kernel/src/value.rs",
        "kernel/src/solvers/mod.rs",
        "kernel/src/solvers/dijkstra.rs",
        "kernel/src/solvers/exploration.rs",
        "kernel/src/solvers/value_iteration.rs",
        "kernel/src/claims/exact.rs",
        "kernel/src/claims/oracle.rs",
        "kernel/src/claims/tiny.rs",
        "kernel/src/claims/c2.rs",
        "kernel/src/claims/c3.rs",
        "kernel/src/claims/c4.rs",
    ] {
        files.push((root().join(k), None));
    }
    files.push((
        root().join("kernel/src/claims/qlearning.rs"),
        Some(&["update", "updatable"]),
    ));
    files
}

/// Container fields and functions known from every scanned file.
fn known_everywhere() -> (BTreeSet<String>, BTreeSet<String>) {
    let (mut fields, mut scalar) = (BTreeSet::new(), BTreeSet::new());
    let mut fns = BTreeSet::new();
    for (p, _) in scanned() {
        let code = drop_test_modules(&blank(&std::fs::read_to_string(&p).expect("source")));
        let (c, s) = fields_by_kind(&code);
        fields.extend(c);
        scalar.extend(s);
        fns.extend(container_functions(&code));
    }
    (fields.difference(&scalar).cloned().collect(), fns)
}

#[test]
fn no_harness_compares_whole_arrays_or_vectors() {
    let (fields, fns) = known_everywhere();
    let mut all = Vec::new();
    for (path, only) in scanned() {
        let code = std::fs::read_to_string(&path).expect("source");
        let name = path
            .strip_prefix(root())
            .unwrap_or(&path)
            .display()
            .to_string();
        all.extend(scan(&name, &code, &fields, &fns, only));
    }
    assert!(
        all.is_empty(),
        "whole-container comparisons (CBMC's memcmp loops once per byte; compare element-wise): {all:#?}"
    );
}

/// The scan is not blind: the comparisons this project had (C1 as printed's `v == before` on
/// `[i64; 24]`, the exploration's `debug_assert!(partner == reverse_partners(…))`) and the
/// other forms it claims to see are found; element-wise code is not.
#[test]
fn the_scan_finds_planted_comparisons() {
    let fields: BTreeSet<String> = ["cost_to_go".to_string()].into();
    let fns: BTreeSet<String> = ["reverse_partners".to_string()].into();
    let hits = |code: &str| scan("planted.rs", code, &fields, &fns, None);
    let c1 = "
        fn printed() {
            let mut v = values();
            for _round in 0..6 {
                let before = v;
                for p in 0..=6 { q.update(&mut v, p); }
                if v == before {
                    kani::assert(v[0] == 0, \"v == before in a string is not code\");
                }
            }
        }";
    let h = hits(c1);
    assert_eq!(h.len(), 1, "{h:?}");
    assert_eq!((h[0].line, h[0].text.as_str()), (7, "v == before"));
    let partner = "
        fn from_csr_paired(first: Vec<u32>, successor: Vec<u32>, partner: Vec<u32>) -> Self {
            debug_assert!(partner == reverse_partners(&first, &successor));
        }";
    assert_eq!(hits(partner).len(), 1);
    // The call alone, on either side.
    let call = "fn f(p: &Graph) -> bool { reverse_partners(a, b) != p.x }";
    assert_eq!(hits(call).len(), 1);
    for (code, what) in [
        ("fn f(a: [u8; 4], b: [u8; 4]) -> bool { a != b }", "array parameters"),
        ("fn f(a: &[u32]) -> bool { a == &[1, 2] }", "slice parameter"),
        ("fn f(x: &V) { let d = g.to_vec(); assert!(x.cost_to_go == d); }", "field, to_vec"),
        ("fn f(g: &G) { let d = to_goals(g).cost_to_go; kani::assert(vi(g).cost_to_go == d, \"\"); }", "field of a call"),
        ("fn f() { let a = vec![1]; debug_assert_eq!(a, other); }", "debug_assert_eq!"),
        ("fn f() { let (mut lo, mut hi) = (values(), values()); assert!(lo != hi); }", "tuple let"),
        ("fn f(v: &Values) { let w = *v; let h = 1; if h == 2 && w == *v {} }", "copy"),
        ("fn f(s: &[i64]) { if s[1..3] == t[0..2] {} }", "range slices"),
        ("fn f() { let v: Vec<u32> = make(); let c = v.clone(); assert_ne!(c, w); }", "clone"),
    ] {
        assert_eq!(hits(code).len(), 1, "{what}: {code}");
    }
    // Element-wise code, scalars and comments pass.
    for code in [
        "fn f(a: [i64; 4], b: [i64; 4]) -> bool { let mut s = true; for i in 0..4 { s &= a[i] == b[i]; } s }",
        "fn f(v: Vec<u32>) -> bool { v.len() == 3 && v[0] != 1 }",
        "fn f(x: u8) -> bool { // v == before\n x == 2 }",
        "fn f(d: &Solution) { kani::assert(d.cost_to_go[3] == Units(0), \"\"); }",
        "fn f(v: &[Units]) -> bool { v.iter().all(|x| *x == Units(0)) }",
    ] {
        assert!(hits(code).is_empty(), "{code}: {:?}", hits(code));
    }
}
