//! What makes CBMC not finish, found statically in the sources (a text scan, no parser):
//!
//! * **recursion** anywhere in `kernel/src` — a function that calls itself (nested `fn` items
//!   included) or a cycle of calls; CBMC bounds recursion by the loop unwind and unrolls every
//!   frame's loops again, so code a harness may reach has none;
//! * a `Vec` **`push`**, a **sort** (`sort`, `sort_unstable`, `sort_by…`) or **`format!`** in a
//!   kernel function that a harness reaches: a symbolic number of pushes makes every later loop
//!   run to the unwind bound, std's sort and the formatting machinery are executed
//!   symbolically. Reachability is computed from the bodies of `proofs/src` through the call
//!   graph by names (over-approximated: a method call `.f(` reaches every kernel method named
//!   `f`; the operator traits' methods — `add`, `mul`, `cmp`, … — count as reached, since `+`
//!   or `<` call them without naming them);
//! * a **loop in a contract clause**: a `#[kani::requires(…)]` or `#[kani::ensures(…)]` of a
//!   kernel function that reaches (through the kernel's call graph, as above) a function with
//!   a `while`, `loop` or `for` loop. A clause is evaluated at every call a verified stub
//!   replaces, so a loop there (Euclid's, for coprimality) would be unrolled at each of them.
//!   Iterator adaptors (`all`, `any`, an array's `map`) are not counted: in the clauses they
//!   run over a move's successor pairs (at most 2) or a fixed array of 4–6 operands. Operators
//!   (`+`, `<` on a kernel type) in a clause are not followed;
//! * an **unwind below a literal loop bound** in a harness (`for _ in 0..K` with `K` a literal
//!   and `#[kani::unwind(N)]`, `N ≤ K`). The loops bounded by the harnesses' named constants
//!   and the kernel's loops are audited by `tests/unwind_bounds.rs`, which derives each count.
//!
//! Code under `#[cfg(not(kani))]` is not compiled under Kani and is skipped; so are unit-test
//! modules. Calls through function pointers or closures stored in variables are not followed.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

mod source_scan;
use source_scan::{blank, body_open, close_of, drop_test_modules, is_ident};

/// A function of the scanned code.
#[derive(Clone, Debug)]
struct Function {
    /// Where it is (`file`).
    file: String,
    /// Its name.
    name: String,
    /// The type of the `impl` block it belongs to (`None`: a free or nested function).
    owner: Option<String>,
    /// Its body, nested items included.
    body: String,
    /// Where its `fn` keyword is in the scanned text.
    at: usize,
}

/// Blanks the items gated by `#[cfg(not(kani))]` (not compiled under Kani).
fn drop_not_kani(text: &str) -> String {
    let b: Vec<char> = text.chars().collect();
    let mut out = b.clone();
    let s: String = b.iter().collect();
    let mut from = 0;
    while let Some(k) = s[from..].find("#[cfg(not(kani))]").map(|k| k + from) {
        let after = k + "#[cfg(not(kani))]".len();
        let mut depth = 0i32;
        let mut end = b.len();
        for j in after..b.len() {
            match b[j] {
                '(' | '[' => depth += 1,
                ')' | ']' => depth -= 1,
                '{' if depth == 0 => {
                    end = close_of(&b, j);
                    break;
                }
                ';' if depth == 0 => {
                    end = j + 1;
                    break;
                }
                _ => {}
            }
        }
        for c in out.iter_mut().take(end).skip(k) {
            if *c != '\n' {
                *c = ' ';
            }
        }
        from = end.min(s.len());
    }
    out.into_iter().collect()
}

/// The self type of an `impl` header (`impl<I: X> Add for Q<I>` → `Q`).
fn impl_type(header: &str) -> String {
    let h = header.trim();
    let after_for = match h.find(" for ") {
        Some(k) => &h[k + 5..],
        None => {
            // Skip `impl` and its generic parameters.
            let rest = h.trim_start_matches("impl").trim_start();
            if rest.starts_with('<') {
                let mut depth = 0;
                let mut cut = rest.len();
                for (i, c) in rest.char_indices() {
                    match c {
                        '<' => depth += 1,
                        '>' => {
                            depth -= 1;
                            if depth == 0 {
                                cut = i + 1;
                                break;
                            }
                        }
                        _ => {}
                    }
                }
                &rest[cut..]
            } else {
                rest
            }
        }
    };
    after_for
        .trim()
        .chars()
        .take_while(|&c| is_ident(c))
        .collect()
}

/// Every function with a body in `code` (blanked), nested ones too, with its `impl` type.
fn functions_in(file: &str, code: &str) -> Vec<Function> {
    let b: Vec<char> = code.chars().collect();
    // The impl blocks: (open brace, close, type).
    let mut impls: Vec<(usize, usize, String)> = Vec::new();
    let word_at = |i: usize, w: &str| {
        let n = w.len();
        i + n <= b.len()
            && b[i..i + n].iter().copied().eq(w.chars())
            && (i == 0 || !is_ident(b[i - 1]))
            && b.get(i + n).is_none_or(|&c| !is_ident(c))
    };
    for i in 0..b.len() {
        if word_at(i, "impl") {
            if let Some(open) = (i..b.len()).find(|&j| b[j] == '{' || b[j] == ';') {
                if b[open] == '{' {
                    let header: String = b[i..open].iter().collect();
                    impls.push((open, close_of(&b, open), impl_type(&header)));
                }
            }
        }
    }
    let mut out = Vec::new();
    for i in 0..b.len() {
        if !word_at(i, "fn") {
            continue;
        }
        let name: String = b[i + 2..]
            .iter()
            .skip_while(|c| c.is_whitespace())
            .take_while(|&&c| is_ident(c))
            .collect();
        let Some(open) = body_open(&b, i + 2) else {
            continue;
        };
        let end = close_of(&b, open);
        // The innermost impl that contains it, unless a function body lies in between.
        let owner = impls
            .iter()
            .filter(|(o, c, _)| *o < i && i < *c)
            .max_by_key(|(o, _, _)| *o)
            .filter(|(o, _, _)| {
                !out.iter()
                    .any(|f: &(usize, usize, Function)| f.0 > *o && f.0 < i && i < f.1)
            })
            .map(|(_, _, t)| t.clone());
        out.push((
            open,
            end,
            Function {
                file: file.to_string(),
                name,
                owner,
                body: b[open..end].iter().collect(),
                at: i,
            },
        ));
    }
    out.into_iter().map(|(_, _, f)| f).collect()
}

/// A call in a body: how the callee is named.
#[derive(Clone, Debug, PartialEq)]
enum Call {
    /// `f(…)`.
    Bare(String),
    /// `Self::f(…)` or `self.f(…)`.
    OnSelf(String),
    /// `T::f(…)` (`T` a type or module, generic arguments dropped).
    Path(String, String),
    /// `x.f(…)` on any other receiver.
    Method(String),
}

/// The calls in `body` (identifiers followed by `(`, optionally after a turbofish; macros and
/// keywords excluded).
fn calls(body: &str) -> Vec<Call> {
    let b: Vec<char> = body.chars().collect();
    let mut out = Vec::new();
    let mut i = 0;
    while i < b.len() {
        if !is_ident(b[i]) || (i > 0 && is_ident(b[i - 1])) || b[i].is_ascii_digit() {
            i += 1;
            continue;
        }
        let start = i;
        while i < b.len() && is_ident(b[i]) {
            i += 1;
        }
        let name: String = b[start..i].iter().collect();
        let mut k = i;
        if b.get(k) == Some(&':') && b.get(k + 1) == Some(&':') && b.get(k + 2) == Some(&'<') {
            k = close_angle(&b, k + 2);
        }
        while k < b.len() && b[k] == ' ' {
            k += 1;
        }
        if b.get(k) != Some(&'(')
            || ["if", "while", "match", "for", "return", "in", "fn"].contains(&name.as_str())
        {
            continue;
        }
        // What precedes the name.
        let mut p = start;
        while p > 0 && b[p - 1].is_whitespace() {
            p -= 1;
        }
        let call = if p >= 1 && b[p - 1] == '.' {
            let recv: String = b[..p - 1]
                .iter()
                .rev()
                .take_while(|&&c| is_ident(c))
                .collect::<Vec<_>>()
                .into_iter()
                .rev()
                .collect();
            let before_recv = p - 1 - recv.len();
            if recv == "self" && (before_recv == 0 || !matches!(b[before_recv - 1], '.' | ':')) {
                Call::OnSelf(name)
            } else {
                Call::Method(name)
            }
        } else if p >= 2 && b[p - 1] == ':' && b[p - 2] == ':' {
            // The segment before `::`, generic arguments skipped.
            let mut q = p - 2;
            if q > 0 && b[q - 1] == '>' {
                let mut depth = 0;
                while q > 0 {
                    q -= 1;
                    match b[q] {
                        '>' => depth += 1,
                        '<' => {
                            depth -= 1;
                            if depth == 0 {
                                break;
                            }
                        }
                        _ => {}
                    }
                }
                if q >= 2 && b[q - 1] == ':' && b[q - 2] == ':' {
                    q -= 2;
                }
            }
            let seg: String = b[..q]
                .iter()
                .rev()
                .take_while(|&&c| is_ident(c))
                .collect::<Vec<_>>()
                .into_iter()
                .rev()
                .collect();
            if seg == "Self" {
                Call::OnSelf(name)
            } else {
                Call::Path(seg, name)
            }
        } else if p >= 1 && b[p - 1] == '!' {
            continue;
        } else {
            Call::Bare(name)
        };
        out.push(call);
    }
    out
}

fn close_angle(b: &[char], open: usize) -> usize {
    let mut depth = 0;
    for (j, &c) in b.iter().enumerate().skip(open) {
        match c {
            '<' => depth += 1,
            '>' => {
                depth -= 1;
                if depth == 0 {
                    return j + 1;
                }
            }
            _ => {}
        }
    }
    b.len()
}

/// The functions a call may reach. `certain`: only calls whose target the text pins down
/// (bare, `Self::`/`self.`, `Type::`); otherwise `.f(` reaches every method named `f` too.
fn targets(fs: &[Function], caller: &Function, call: &Call, certain: bool) -> Vec<usize> {
    let pick = |pred: &dyn Fn(&Function) -> bool| -> Vec<usize> {
        fs.iter()
            .enumerate()
            .filter(|(_, f)| pred(f))
            .map(|(i, _)| i)
            .collect()
    };
    match call {
        Call::Bare(n) => {
            // A function of the caller's own file shadows the others of that name.
            let local = pick(&|f| &f.name == n && f.owner.is_none() && f.file == caller.file);
            if local.is_empty() {
                pick(&|f| &f.name == n && f.owner.is_none())
            } else {
                local
            }
        }
        Call::OnSelf(n) => pick(&|f| &f.name == n && f.owner == caller.owner),
        Call::Path(seg, n) => {
            if seg.starts_with(|c: char| c.is_ascii_uppercase()) {
                pick(&|f| &f.name == n && f.owner.as_deref() == Some(seg.as_str()))
            } else {
                pick(&|f| &f.name == n && f.owner.is_none())
            }
        }
        Call::Method(n) if !certain => pick(&|f| &f.name == n && f.owner.is_some()),
        Call::Method(_) => Vec::new(),
    }
}

/// `file::name` (or `file::Type::name`) of a function.
fn label(f: &Function) -> String {
    match &f.owner {
        Some(t) => format!("{}::{}::{}", f.file, t, f.name),
        None => format!("{}::{}", f.file, f.name),
    }
}

/// Functions on a cycle of certain calls (a function calling itself included).
fn recursion(fs: &[Function]) -> Vec<String> {
    let edges: Vec<BTreeSet<usize>> = fs
        .iter()
        .map(|f| {
            calls(&f.body)
                .iter()
                .flat_map(|c| targets(fs, f, c, true))
                .collect()
        })
        .collect();
    let mut out = Vec::new();
    for start in 0..fs.len() {
        // Is `start` reachable from its own successors?
        let mut seen = vec![false; fs.len()];
        let mut stack: Vec<usize> = edges[start].iter().copied().collect();
        let mut cyclic = false;
        while let Some(x) = stack.pop() {
            if x == start {
                cyclic = true;
                break;
            }
            if !std::mem::replace(&mut seen[x], true) {
                stack.extend(edges[x].iter().copied());
            }
        }
        if cyclic {
            out.push(label(&fs[start]));
        }
    }
    out
}

/// The operator traits' methods: called by `+`, `-`, `*`, `/`, unary `-`, comparisons.
const OPERATORS: [&str; 7] = ["add", "sub", "mul", "div", "neg", "cmp", "partial_cmp"];

/// The kernel functions reachable from the `roots` (functions of the harness code).
fn reached(kernel: &[Function], roots: &[Function]) -> BTreeSet<usize> {
    let mut stack: Vec<usize> = kernel
        .iter()
        .enumerate()
        .filter(|(_, f)| f.owner.is_some() && OPERATORS.contains(&f.name.as_str()))
        .map(|(i, _)| i)
        .collect();
    for r in roots {
        // A harness's `Self::`/`self.` calls are its own code's, never the kernel's.
        let unowned = Function {
            owner: Some(String::new()),
            ..r.clone()
        };
        for c in calls(&r.body) {
            stack.extend(targets(kernel, &unowned, &c, false));
        }
    }
    closure(kernel, stack, false)
}

/// The integer types' own methods that the clauses call (`x.checked_add(y)` on an `i128`): a
/// method call of one of these names on a receiver other than `self` is taken to be the
/// integer's, not a kernel method of the same name (`Q::checked_add`).
const INTEGER_METHODS: [&str; 4] = ["checked_add", "checked_sub", "checked_mul", "signum"];

/// The kernel functions reachable from the calls of `root` (code inside the kernel: its
/// `Self::`/`self.` calls are its own type's), operators not followed, and the integers'
/// methods ([`INTEGER_METHODS`]) taken as the integers'.
fn reached_from_kernel(kernel: &[Function], root: &Function) -> BTreeSet<usize> {
    let stack = calls(&root.body)
        .iter()
        .filter(|c| !is_integer_method(c))
        .flat_map(|c| targets(kernel, root, c, false))
        .collect();
    closure(kernel, stack, true)
}

fn is_integer_method(c: &Call) -> bool {
    matches!(c, Call::Method(n) if INTEGER_METHODS.contains(&n.as_str()))
}

/// Everything reachable from `stack` through the calls of the kernel's functions (`integers`:
/// the integers' methods taken as the integers', [`INTEGER_METHODS`]).
fn closure(kernel: &[Function], mut stack: Vec<usize>, integers: bool) -> BTreeSet<usize> {
    let mut seen = BTreeSet::new();
    while let Some(x) = stack.pop() {
        if seen.insert(x) {
            for c in calls(&kernel[x].body) {
                if integers && is_integer_method(&c) {
                    continue;
                }
                stack.extend(targets(kernel, &kernel[x], &c, false));
            }
        }
    }
    seen
}

/// What CBMC cannot finish in a reached function's body: `push`, a sort, `format!`.
fn expensive(body: &str) -> Vec<&'static str> {
    [
        (".push(", "Vec push"),
        (".sort(", "sort"),
        (".sort_unstable(", "sort_unstable"),
        (".sort_by(", "sort_by"),
        (".sort_by_key(", "sort_by_key"),
        (".sort_unstable_by(", "sort_unstable_by"),
        (".sort_unstable_by_key(", "sort_unstable_by_key"),
        ("format!(", "format!"),
    ]
    .iter()
    .filter(|(pat, _)| body.contains(pat))
    .map(|&(_, what)| what)
    .collect()
}

/// Whether `body` has a `while`, `loop` or `for … in` loop.
fn has_loop(body: &str) -> bool {
    let b: Vec<char> = body.chars().collect();
    let word_at = |i: usize, w: &str| {
        let n = w.chars().count();
        i + n <= b.len()
            && b[i..i + n].iter().copied().eq(w.chars())
            && (i == 0 || !is_ident(b[i - 1]))
            && b.get(i + n).is_none_or(|&c| !is_ident(c))
    };
    (0..b.len()).any(|i| {
        if word_at(i, "while") {
            return true;
        }
        if word_at(i, "loop") {
            return b[i + 4..].iter().find(|c| !c.is_whitespace()) == Some(&'{');
        }
        if word_at(i, "for") {
            // `for pat in expr {`, not `impl Trait for Type` nor `for<'a>`.
            let rest: String = b[i + 3..]
                .iter()
                .take_while(|&&c| c != '{' && c != ';')
                .collect();
            return rest.contains(" in ");
        }
        false
    })
}

/// The contract clauses of the functions in `code`: for each `#[kani::requires(…)]` and
/// `#[kani::ensures(…)]`, a pseudo-function whose body is the clause, named after the function
/// it belongs to (the next `fn`) and owned by that function's type.
fn contract_clauses(file: &str, code: &str, fs: &[Function]) -> Vec<Function> {
    let b: Vec<char> = code.chars().collect();
    let mut out = Vec::new();
    for attr in ["#[kani::requires(", "#[kani::ensures("] {
        let mut from = 0;
        while let Some(k) = code[from..].find(attr).map(|k| k + from) {
            let open = code[..k + attr.len() - 1].chars().count();
            let close = close_of(&b, open);
            from = k + attr.len();
            let Some(owner) = fs
                .iter()
                .filter(|f| f.file == file && f.at > open)
                .min_by_key(|f| f.at)
            else {
                continue;
            };
            out.push(Function {
                name: format!("{} ({})", owner.name, &attr[8..attr.len() - 1]),
                body: b[open..close].iter().collect(),
                at: open,
                ..owner.clone()
            });
        }
    }
    out
}

/// The contract clauses of `kernel_files` (`(file, prepared code)`) that reach a looping
/// kernel function, as `clause of f reaches g, which loops`.
fn clause_findings(kernel: &[Function], kernel_files: &[(String, String)]) -> Vec<String> {
    let mut out = Vec::new();
    for (file, code) in kernel_files {
        for clause in contract_clauses(file, code, kernel) {
            for i in reached_from_kernel(kernel, &clause) {
                if has_loop(&kernel[i].body) {
                    out.push(format!(
                        "contract clause {} reaches {}, which loops",
                        label(&clause),
                        label(&kernel[i])
                    ));
                }
            }
        }
    }
    out
}

/// `(file, text)` blanked and stripped of unit tests and `cfg(not(kani))` items.
fn prepare(file: &str, text: &str) -> (String, String) {
    (
        file.to_string(),
        drop_not_kani(&drop_test_modules(&blank(text))),
    )
}

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for e in std::fs::read_dir(dir).expect("dir") {
        let p = e.expect("entry").path();
        if p.is_dir() {
            rust_files(&p, out);
        } else if p.extension().is_some_and(|x| x == "rs") {
            out.push(p);
        }
    }
}

/// The prepared sources under `dir`, `(file relative to dir, code)`.
fn load_files(dir: &Path) -> Vec<(String, String)> {
    let mut files = Vec::new();
    rust_files(dir, &mut files);
    files.sort();
    files
        .iter()
        .map(|p| {
            let rel = p
                .strip_prefix(dir)
                .expect("inside")
                .to_string_lossy()
                .to_string();
            prepare(&rel, &std::fs::read_to_string(p).expect("source"))
        })
        .collect()
}

fn load(dir: &Path) -> Vec<Function> {
    load_files(dir)
        .iter()
        .flat_map(|(file, code)| functions_in(file, code))
        .collect()
}

/// Everything the scan rejects, given the kernel's functions and the harness code's.
fn findings(kernel: &[Function], harness_code: &[Function]) -> Vec<String> {
    let mut out: Vec<String> = recursion(kernel)
        .into_iter()
        .map(|f| format!("recursion: {f}"))
        .collect();
    for i in reached(kernel, harness_code) {
        for what in expensive(&kernel[i].body) {
            out.push(format!(
                "{what} in {}, reached by a harness",
                label(&kernel[i])
            ));
        }
    }
    out
}

/// `(harness, unwind, literal loop bound)` where a harness's literal `for … in 0..K` (or
/// `0..=K`) needs more unrollings than its `#[kani::unwind(N)]` gives.
fn literal_unwind_findings(file: &str, text: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut unwind: Option<Option<u64>> = None;
    let mut current: Option<(String, Option<u64>)> = None;
    let mut depth = 0i64;
    for line in text.lines() {
        let t = line.trim();
        if t == "#[kani::proof]" || t.starts_with("#[kani::proof_for_contract(") {
            unwind = Some(None);
        } else if let (Some(u), Some(rest)) = (unwind.as_mut(), t.strip_prefix("#[kani::unwind(")) {
            *u = rest.trim_end_matches(")]").parse().ok();
        } else if let (Some(u), true) = (unwind, t.starts_with("pub fn ") || t.starts_with("fn ")) {
            let name = t.trim_start_matches("pub ").trim_start_matches("fn ");
            current = Some((name.split('(').next().unwrap_or("").to_string(), u));
            unwind = None;
            depth = 0;
        }
        if let Some((name, u)) = &current {
            if let Some(k) = t.find(" in 0..") {
                let rest = &t[k + " in 0..".len()..];
                let inclusive = rest.starts_with('=');
                let digits: String = rest
                    .trim_start_matches('=')
                    .chars()
                    .take_while(|c| c.is_ascii_digit())
                    .collect();
                if let Ok(bound) = digits.parse::<u64>() {
                    let iterations = bound + u64::from(inclusive);
                    if u.is_none_or(|u| u <= iterations) {
                        out.push(format!(
                            "{file}::{name}: unwind {u:?}, but a loop runs {iterations} times"
                        ));
                    }
                }
            }
            depth += t.matches('{').count() as i64 - t.matches('}').count() as i64;
            if depth <= 0 && t.contains('}') {
                current = None;
            }
        }
    }
    out
}

/// Findings in kernel code the harnesses reach that is accepted as it is, each with why the
/// lengths involved are concrete under Kani (none).
const PENDING: [&str; 0] = [];

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("workspace")
        .to_path_buf()
}

/// The kernel has no recursion, and no harness reaches a `push`, a sort or `format!`; no
/// harness's literal loop bound exceeds its unwind.
#[test]
fn the_kernel_code_the_harnesses_reach_is_feasible_for_cbmc() {
    let kernel = load(&root().join("kernel/src"));
    let harness_code = load(&root().join("proofs/src"));
    assert!(
        kernel.len() > 100 && harness_code.len() > 20,
        "the scan sees the code"
    );
    // Not vacuous: the harnesses reach the kernel code they are about.
    let names: BTreeSet<String> = reached(&kernel, &harness_code)
        .into_iter()
        .map(|i| label(&kernel[i]))
        .collect();
    for f in [
        "claims/qlearning.rs::QProblem::update",
        "claims/exact.rs::gcd",
        "claims/exact.rs::lowest_terms",
        "claims/exact.rs::Q::ratio",
        "solvers/dijkstra.rs::to_goals",
    ] {
        assert!(names.contains(f), "{f} not reached: {names:?}");
    }
    let mut problems = findings(&kernel, &harness_code);
    // Known, in a file outside this crate's reach: each must still be found (so that the entry
    // goes once the code changes), and nothing else may be.
    for known in PENDING {
        let at = problems.iter().position(|p| p == known);
        assert!(
            at.is_some(),
            "no longer found, drop it from PENDING: {known}"
        );
        problems.remove(at.expect("found"));
    }
    let mut files = Vec::new();
    rust_files(&root().join("proofs/src"), &mut files);
    for p in files {
        let text = std::fs::read_to_string(&p).expect("source");
        let file = p.file_name().expect("name").to_string_lossy().to_string();
        problems.extend(literal_unwind_findings(&file, &text));
    }
    assert_eq!(problems, Vec::<String>::new());
}

/// No contract clause of the kernel reaches a loop: `lowest_terms`' coprimality is a Bézout
/// identity on its witness, not Euclid on the result. Not vacuous: every contract's clauses are
/// seen, and they reach the clause functions they are written with.
#[test]
fn no_contract_clause_reaches_a_loop() {
    let files = load_files(&root().join("kernel/src"));
    let kernel: Vec<Function> = files
        .iter()
        .flat_map(|(file, code)| functions_in(file, code))
        .collect();
    let clauses: Vec<String> = files
        .iter()
        .flat_map(|(file, code)| contract_clauses(file, code, &kernel))
        .map(|c| label(&c))
        .collect();
    for c in [
        "claims/exact.rs::lowest_terms (requires)",
        "claims/exact.rs::lowest_terms (ensures)",
        "claims/exact.rs::gcd (ensures)",
        "claims/exact.rs::Q::checked_add (ensures)",
        "claims/exact.rs::Q::checked_mul (requires)",
        "claims/exact.rs::Q::checked_mul (ensures)",
        "value.rs::Units::checked_plus (ensures)",
        "claims/qlearning.rs::QProblem::update (requires)",
        "claims/qlearning.rs::QProblem::update (ensures)",
    ] {
        assert!(clauses.iter().any(|x| x == c), "{c} not seen: {clauses:?}");
    }
    let lowest = files
        .iter()
        .flat_map(|(file, code)| contract_clauses(file, code, &kernel))
        .find(|c| label(c) == "claims/exact.rs::lowest_terms (ensures)")
        .expect("seen");
    let reached: BTreeSet<String> = reached_from_kernel(&kernel, &lowest)
        .into_iter()
        .map(|i| label(&kernel[i]))
        .collect();
    for f in ["is_lowest_form", "same_value", "is_bezout_one", "product"] {
        assert!(
            reached.contains(&format!("claims/exact.rs::{f}")),
            "{f}: {reached:?}"
        );
    }
    assert_eq!(clause_findings(&kernel, &files), Vec::<String>::new());
}

/// A clause that reaches a loop is found — Euclid on the result for coprimality, directly and
/// through a method on `self` — and clauses that reach only straight-line code (a Bézout
/// identity) are not.
#[test]
fn planted_loop_in_a_contract_clause_is_found() {
    let kernel = r#"
        fn coprime(mut a: u32, mut b: u32) -> bool { while b != 0 { (a, b) = (b, a % b); } a == 1 }
        fn bezout(a: i32, x: i32, b: i32, y: i32) -> bool { a * x + b * y == 1 }
        fn sum_all(v: &[u32]) -> u32 { let mut s = 0; for k in 0..v.len() { s += v[k]; } s }
        #[kani::ensures(|r: &(u32, u32)| coprime(r.0, r.1))]
        pub fn reduce(n: u32, d: u32) -> (u32, u32) { (n, d) }
        #[kani::ensures(|r: &(i32, i32, i32, i32)| bezout(r.0, r.2, r.1, r.3))]
        pub fn witnessed(n: i32, d: i32) -> (i32, i32, i32, i32) { (n, d, 0, 0) }
        struct W(Vec<u32>);
        impl W {
            fn total(&self) -> u32 { sum_all(&self.0) }
            #[kani::requires(self.total() > 0)]
            pub fn first(&self) -> u32 { loop { break self.0[0]; } }
        }
        impl Iterator for W { type Item = u32; fn next(&mut self) -> Option<u32> { None } }
    "#;
    let (file, code) = prepare("k.rs", kernel);
    let fs = functions_in(&file, &code);
    let found = clause_findings(&fs, &[(file, code)]);
    assert_eq!(
        found,
        [
            "contract clause k.rs::W::first (requires) reaches k.rs::sum_all, which loops",
            "contract clause k.rs::reduce (ensures) reaches k.rs::coprime, which loops",
        ]
    );
    // The loop detector: `while`, `loop {`, `for … in`; not `impl … for`, nor a name.
    assert!(has_loop("{ loop { } }") && has_loop("{ for x in v { } }"));
    assert!(!has_loop("{ impl Iterator for W { } let looping = 1; }"));
}

fn planted(kernel: &str, harness: &str) -> Vec<String> {
    let (kf, kc) = prepare("k.rs", kernel);
    let (hf, hc) = prepare("h.rs", harness);
    findings(&functions_in(&kf, &kc), &functions_in(&hf, &hc))
}

/// Planted recursion is found: a function calling itself, a nested `fn` calling itself, a
/// method calling itself through `Self::`/`self.`, two functions calling each other. A method
/// calling another type's method of the same name is not recursion.
#[test]
fn planted_recursion_is_found() {
    let kernel = r#"
        fn depth(n: u32) -> u32 { if n == 0 { 0 } else { 1 + depth(n - 1) } }
        pub fn outer(v: &[u32]) -> u32 {
            fn walk(k: usize, v: &[u32]) -> u32 { if k == 0 { 0 } else { v[k] + walk(k - 1, v) } }
            walk(v.len() - 1, v)
        }
        struct T(u32);
        impl T {
            fn shrink(&self) -> u32 { if self.0 == 0 { 0 } else { T(self.0 - 1).shrink() + self.again() } }
            fn again(&self) -> u32 { Self::again(self) }
        }
        fn ping(n: u32) -> u32 { if n == 0 { 0 } else { pong(n - 1) } }
        fn pong(n: u32) -> u32 { ping(n) }
        struct Q(i32);
        impl Ord for Q { fn cmp(&self, o: &Self) -> std::cmp::Ordering { self.0.cmp(&o.0) } }
        // fn commented(n: u32) -> u32 { commented(n) }
        fn fine(n: u32) -> u32 { let s = "fine(n)"; n + s.len() as u32 }
    "#;
    let found = planted(kernel, "");
    for f in [
        "recursion: k.rs::depth",
        "recursion: k.rs::walk",
        "recursion: k.rs::T::again",
        "recursion: k.rs::ping",
        "recursion: k.rs::pong",
    ] {
        assert!(found.contains(&f.to_string()), "{f} missing from {found:?}");
    }
    for f in ["outer", "Q::cmp", "fine", "commented"] {
        assert!(
            !found
                .iter()
                .any(|x| x.ends_with(&format!("::{f}")) && x.starts_with("recursion")),
            "{f}: {found:?}"
        );
    }
}

/// A `push`, a sort and `format!` in a kernel function a harness reaches are found, also
/// through a method call and an operator; the same in an unreached function, under
/// `#[cfg(not(kani))]` or in a unit-test module are not.
#[test]
fn planted_push_sort_and_format_are_found_where_reached() {
    let kernel = r#"
        pub fn grow(n: usize) -> Vec<u8> { let mut v = Vec::new(); for _ in 0..n { v.push(0); } v }
        pub fn ordered(mut v: Vec<u8>) -> Vec<u8> { v.sort_unstable(); helper(); v }
        fn helper() -> String { format!("{}", 1) }
        pub struct W(u8);
        impl W { pub fn label(&self) -> usize { let mut v = vec![1]; v.sort(); v.len() } }
        impl std::ops::Add for W { type Output = W; fn add(self, o: W) -> W { let mut v = Vec::new(); v.push(o.0); W(v[0]) } }
        pub fn unreached() { let mut v = Vec::new(); v.push(1); }
        pub fn gated() -> u8 {
            #[cfg(not(kani))]
            { let mut v = Vec::new(); v.push(1); }
            0
        }
        #[cfg(test)]
        mod tests { fn t() { let mut v = Vec::new(); v.push(1); } }
    "#;
    let harness = r#"
        #[kani::proof]
        pub fn h() {
            let v = grow(kani::any());
            let w = ordered(v);
            let x = W(1).label() + gated() as usize;
        }
    "#;
    let found = planted(kernel, harness);
    for f in [
        "Vec push in k.rs::grow, reached by a harness",
        "sort_unstable in k.rs::ordered, reached by a harness",
        "format! in k.rs::helper, reached by a harness",
        "sort in k.rs::W::label, reached by a harness",
        "Vec push in k.rs::W::add, reached by a harness",
    ] {
        assert!(found.contains(&f.to_string()), "{f} missing from {found:?}");
    }
    for f in ["unreached", "gated", "t"] {
        assert!(
            !found.iter().any(|x| x.contains(&format!("::{f},"))),
            "{f}: {found:?}"
        );
    }
    assert_eq!(found.len(), 5, "{found:?}");
}

/// An unwind below a literal loop bound is found; a sufficient one is not.
#[test]
fn planted_unwind_too_small_is_found() {
    let source = r#"
#[kani::proof]
#[kani::unwind(3)]
pub fn too_small() {
    for _ in 0..5 {
        kani::assume(true);
    }
}

#[kani::proof]
#[kani::unwind(6)]
pub fn enough() {
    for _ in 0..=4 {
        kani::assume(true);
    }
}

#[kani::proof]
pub fn no_unwind() {
    for k in 0..2 {
        kani::assume(k < 2);
    }
}
"#;
    let found = literal_unwind_findings("p.rs", source);
    assert_eq!(
        found,
        [
            "p.rs::too_small: unwind Some(3), but a loop runs 5 times",
            "p.rs::no_unwind: unwind None, but a loop runs 2 times",
        ]
    );
}
