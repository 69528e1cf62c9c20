//! The repository is self-contained for a reader: the specification is `docs/spec.md`, so no
//! source, proof or document points outside the repository for it, and every relative link of
//! the README and of `docs/` leads to a file that exists.
//!
//! * No file under `README.md`, `docs/**.md`, `src/**.rs`, `kernel/src/**.rs`, `proofs/**` or
//!   `python/**` mentions `../shared` or `SPEC.md`.
//! * `README.md` and `docs/**.md` cite the specification as `docs/spec.md §N`, never as
//!   `SPEC §N`.
//! * Every relative markdown link (`[text](target)`, `[label]: target`) in `README.md` and
//!   `docs/**.md` names an existing file or directory, resolved from the linking file's folder
//!   (a `#fragment` is cut off; `http:`, `https:`, `mailto:` and pure `#anchor` links are not
//!   files). Links inside fenced code blocks and inline code spans are not links.
//!
//! The unit tests at the bottom plant a broken link and forbidden mentions in strings and
//! require the checks to report exactly those.

use std::fs;
use std::path::{Component, Path, PathBuf};

/// Text that must not appear in any scanned file: both point outside the repository.
const FORBIDDEN_EVERYWHERE: [&str; 2] = ["../shared", "SPEC.md"];

/// Text that must not appear in the README and the docs: the specification is cited by its path.
const FORBIDDEN_IN_DOCS: &str = "SPEC §";

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// Every file under `dir` (recursively) whose name ends with one of `exts` (all files when
/// `exts` is empty), sorted. A missing directory gives an error: a scan that reads nothing must
/// not pass.
fn files_under(dir: &Path, exts: &[&str]) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    assert!(dir.is_dir(), "{} is not a directory", dir.display());
    while let Some(d) = stack.pop() {
        let entries = fs::read_dir(&d).unwrap_or_else(|e| panic!("{}: {e}", d.display()));
        for entry in entries {
            let path = entry.expect("a directory entry").path();
            if path.is_dir() {
                stack.push(path);
            } else {
                let name = path.file_name().and_then(|n| n.to_str()).unwrap_or("");
                if exts.is_empty() || exts.iter().any(|e| name.ends_with(e)) {
                    out.push(path);
                }
            }
        }
    }
    out.sort();
    out
}

/// `README.md` and every `.md` file under `docs/`.
fn markdown_files() -> Vec<PathBuf> {
    let mut v = vec![root().join("README.md")];
    v.extend(files_under(&root().join("docs"), &[".md"]));
    v
}

/// Every file the mention checks scan.
fn scanned_files() -> Vec<PathBuf> {
    let r = root();
    let mut v = markdown_files();
    v.extend(files_under(&r.join("src"), &[".rs"]));
    v.extend(files_under(&r.join("kernel/src"), &[".rs"]));
    v.extend(files_under(&r.join("proofs"), &[]));
    v.extend(files_under(&r.join("python"), &[]));
    v
}

/// The lines (1-based) of `text` that contain `needle`, as `line N: <line>`.
fn mentions(text: &str, needle: &str) -> Vec<String> {
    text.lines()
        .enumerate()
        .filter(|(_, l)| l.contains(needle))
        .map(|(i, l)| format!("line {}: {}", i + 1, l.trim()))
        .collect()
}

/// `text` with fenced code blocks and inline code spans blanked out (line structure kept), so
/// that `[a](b)` inside code is not taken for a link.
fn without_code(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut fenced = false;
    for line in text.lines() {
        let trimmed = line.trim_start();
        if trimmed.starts_with("```") || trimmed.starts_with("~~~") {
            fenced = !fenced;
            out.push('\n');
            continue;
        }
        if fenced {
            out.push('\n');
            continue;
        }
        // Inline code: a run of n backticks closes at the next run of exactly n backticks.
        let chars: Vec<char> = line.chars().collect();
        let mut i = 0;
        while i < chars.len() {
            if chars[i] == '`' {
                let n = chars[i..].iter().take_while(|&&c| c == '`').count();
                let mut j = i + n;
                let mut close = None;
                while j < chars.len() {
                    if chars[j] == '`' {
                        let m = chars[j..].iter().take_while(|&&c| c == '`').count();
                        if m == n {
                            close = Some(j + m);
                            break;
                        }
                        j += m;
                    } else {
                        j += 1;
                    }
                }
                match close {
                    Some(end) => {
                        out.extend(std::iter::repeat_n(' ', end - i));
                        i = end;
                    }
                    None => {
                        // An unmatched run is literal text.
                        out.extend(std::iter::repeat_n('`', n));
                        i += n;
                    }
                }
            } else {
                out.push(chars[i]);
                i += 1;
            }
        }
        out.push('\n');
    }
    out
}

/// The link targets of `text`: inline links `[text](target)` (and images), and reference
/// definitions `[label]: target`, each with its 1-based line.
fn link_targets(text: &str) -> Vec<(usize, String)> {
    let mut out = Vec::new();
    for (i, line) in without_code(text).lines().enumerate() {
        let trimmed = line.trim_start();
        if let Some(rest) = trimmed.strip_prefix('[') {
            if let Some(definition) = rest.find(']').and_then(|c| rest[c + 1..].strip_prefix(':')) {
                let target = target_of(definition);
                if !target.is_empty() {
                    out.push((i + 1, target));
                }
            }
        }
        let mut from = 0;
        while let Some(k) = line[from..].find("](") {
            let start = from + k + 2;
            // The target ends at the matching parenthesis (targets may contain balanced ones).
            let mut depth = 1;
            let mut end = None;
            for (j, c) in line[start..].char_indices() {
                match c {
                    '(' => depth += 1,
                    ')' => {
                        depth -= 1;
                        if depth == 0 {
                            end = Some(start + j);
                            break;
                        }
                    }
                    _ => {}
                }
            }
            let Some(end) = end else { break };
            out.push((i + 1, target_of(&line[start..end])));
            from = end;
        }
    }
    out
}

/// The destination of a link's `(…)` or of a reference definition: `<…>` whole, else up to
/// the first blank (a title may follow).
fn target_of(inner: &str) -> String {
    let inner = inner.trim();
    match inner.strip_prefix('<') {
        Some(rest) => rest.split('>').next().unwrap_or("").to_string(),
        None => inner.split_whitespace().next().unwrap_or("").to_string(),
    }
}

/// Whether a link target names a file of the repository (not a URL or an anchor).
fn is_relative_file_link(target: &str) -> bool {
    !(target.is_empty()
        || target.starts_with('#')
        || target.starts_with("http://")
        || target.starts_with("https://")
        || target.starts_with("mailto:"))
}

/// `base/target` with `.` and `..` resolved lexically (no file system access).
fn resolve(base: &Path, target: &str) -> PathBuf {
    let mut out = PathBuf::new();
    for c in base.join(target).components() {
        match c {
            Component::ParentDir => {
                out.pop();
            }
            Component::CurDir => {}
            other => out.push(other),
        }
    }
    out
}

/// The broken relative links of the markdown `text` of a file in folder `dir`, judged by
/// `exists`: `line N: target`.
fn broken_links(dir: &Path, text: &str, exists: impl Fn(&Path) -> bool) -> Vec<String> {
    link_targets(text)
        .into_iter()
        .filter(|(_, t)| is_relative_file_link(t))
        .filter_map(|(line, t)| {
            let path_part = t.split('#').next().unwrap_or("");
            let resolved = resolve(dir, path_part);
            (!exists(&resolved)).then(|| format!("line {line}: {t}"))
        })
        .collect()
}

fn relative(p: &Path) -> String {
    p.strip_prefix(root()).unwrap_or(p).display().to_string()
}

#[test]
fn no_file_points_outside_the_repository_for_the_specification() {
    let files = scanned_files();
    // The scan reads what it claims to read: the README, the spec, a source file, a proof.
    for must in [
        "README.md",
        "docs/spec.md",
        "src/lib.rs",
        "kernel/src/lib.rs",
        "proofs/coq/C1.v",
    ] {
        assert!(
            files.iter().any(|f| relative(f) == must),
            "{must} is not among the scanned files"
        );
    }
    let mut found = Vec::new();
    for f in &files {
        let bytes = fs::read(f).unwrap_or_else(|e| panic!("{}: {e}", f.display()));
        let text = String::from_utf8_lossy(&bytes);
        for needle in FORBIDDEN_EVERYWHERE {
            for m in mentions(&text, needle) {
                found.push(format!("{} mentions {needle:?}, {m}", relative(f)));
            }
        }
    }
    assert!(found.is_empty(), "{}", found.join("\n"));
}

#[test]
fn the_docs_cite_the_specification_by_its_path() {
    let mut found = Vec::new();
    for f in markdown_files() {
        let text = fs::read_to_string(&f).unwrap_or_else(|e| panic!("{}: {e}", f.display()));
        for m in mentions(&text, FORBIDDEN_IN_DOCS) {
            found.push(format!("{} cites {FORBIDDEN_IN_DOCS:?}, {m}", relative(&f)));
        }
    }
    assert!(found.is_empty(), "{}", found.join("\n"));
}

#[test]
fn every_relative_link_of_the_readme_and_the_docs_names_an_existing_file() {
    let files = markdown_files();
    let mut checked = 0;
    let mut broken = Vec::new();
    for f in &files {
        let text = fs::read_to_string(f).unwrap_or_else(|e| panic!("{}: {e}", f.display()));
        let dir = f.parent().expect("a file has a folder");
        checked += link_targets(&text)
            .iter()
            .filter(|(_, t)| is_relative_file_link(t))
            .count();
        for b in broken_links(dir, &text, |p| p.exists()) {
            broken.push(format!("{}: {b}", relative(f)));
        }
    }
    // The README alone links a dozen guides: a parser that finds no links must not pass.
    assert!(checked >= 50, "only {checked} relative links found");
    assert!(broken.is_empty(), "broken links:\n{}", broken.join("\n"));
}

#[test]
fn the_readme_links_the_specification() {
    let text = fs::read_to_string(root().join("README.md")).expect("README.md");
    assert!(
        link_targets(&text).iter().any(|(_, t)| t == "docs/spec.md"),
        "README.md has no link to docs/spec.md"
    );
}

#[test]
fn a_planted_broken_link_is_reported_and_nothing_else() {
    let dir = Path::new("/repo/docs/guide");
    let text = "See [solve](solve.md#two-models), [the spec](../spec.md), [gone](../nowhere.md),\n\
                [web](https://example.org/x.md), [anchor](#top) and ![img](../p.png).\n\
                ```\n[in a fence](../fenced.md)\n```\n\
                Inline `[code](../code.md)` is not a link.\n\
                [ref]: ../../missing/README.md\n";
    let existing = [
        "/repo/docs/guide/solve.md",
        "/repo/docs/spec.md",
        "/repo/docs/p.png",
    ];
    let broken = broken_links(dir, text, |p| existing.iter().any(|e| Path::new(e) == p));
    assert_eq!(
        broken,
        vec![
            "line 1: ../nowhere.md".to_string(),
            "line 7: ../../missing/README.md".to_string(),
        ]
    );
}

#[test]
fn link_targets_are_read_whole() {
    let t = link_targets("a [x](docs/a_(b).md \"title\") and [y](<c d.md>)\n");
    assert_eq!(
        t,
        vec![(1, "docs/a_(b).md".to_string()), (1, "c d.md".to_string())]
    );
}

#[test]
fn planted_mentions_are_found() {
    let text = "//! see ../shared/PROOFS.md\nfine\n// SPEC.md §2\n";
    assert_eq!(
        mentions(text, "../shared"),
        vec!["line 1: //! see ../shared/PROOFS.md".to_string()]
    );
    assert_eq!(
        mentions(text, "SPEC.md"),
        vec!["line 3: // SPEC.md §2".to_string()]
    );
    assert_eq!(
        mentions("the model of SPEC §3\n", FORBIDDEN_IN_DOCS),
        vec!["line 1: the model of SPEC §3".to_string()]
    );
    assert!(mentions("truecost solve --env SPEC\n", FORBIDDEN_IN_DOCS).is_empty());
}

#[test]
fn resolve_walks_up_and_down() {
    assert_eq!(
        resolve(Path::new("/r/docs/guide"), "../../data/x.md"),
        PathBuf::from("/r/data/x.md")
    );
    assert_eq!(
        resolve(Path::new("/r/docs"), "./proofs/c1.md"),
        PathBuf::from("/r/docs/proofs/c1.md")
    );
}
