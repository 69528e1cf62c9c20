//! `.github/workflows/kani.yml` runs every harness of `proofs/src` under a pinned Kani: its
//! matrix names exactly the `#[kani::proof]` and `#[kani::proof_for_contract]` harnesses
//! (`module::name`, as `--harness … --exact` matches them), the version is an exact release
//! pinned once (`KANI_VERSION`) and named by `docs/guide/kani.md`, and each job runs
//! `cargo kani --harness … --exact` from `proofs/` with `--fail-uncoverable` and a timeout.
//! A line-based reading of the YAML (no YAML parser in the dependency tree).

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("workspace")
        .to_path_buf()
}

/// `module::name` of every public harness in `proofs/src/*.rs` (a `#[kani::proof]` or
/// `#[kani::proof_for_contract(…)]` line, then attributes, then `pub fn name`).
fn harnesses_in(sources: &[(String, String)]) -> BTreeSet<String> {
    let mut out = BTreeSet::new();
    for (module, text) in sources {
        let mut open = false;
        for t in text.lines().map(str::trim) {
            if t == "#[kani::proof]" || t.starts_with("#[kani::proof_for_contract(") {
                open = true;
            } else if open && t.starts_with("pub fn ") {
                let name = t["pub fn ".len()..].split('(').next().expect("name");
                out.insert(format!("{module}::{name}"));
                open = false;
            } else if open && !t.starts_with("#[") {
                open = false; // a private harness (the stand-in's own tests)
            }
        }
    }
    out
}

fn sources() -> Vec<(String, String)> {
    let mut v = Vec::new();
    for e in std::fs::read_dir(root().join("proofs/src")).expect("proofs/src") {
        let path = e.expect("entry").path();
        let module = path
            .file_stem()
            .expect("stem")
            .to_string_lossy()
            .to_string();
        v.push((module, std::fs::read_to_string(&path).expect("source")));
    }
    v
}

/// The entries of the list under `harness:` in the matrix.
fn matrix(yaml: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut indent = None;
    for line in yaml.lines() {
        let t = line.trim_start();
        let depth = line.len() - t.len();
        if t == "harness:" {
            indent = Some(depth);
            continue;
        }
        if let Some(d) = indent {
            match t.strip_prefix("- ") {
                Some(item) if depth > d => out.push(item.trim().to_string()),
                _ if t.is_empty() => {}
                _ => indent = None,
            }
        }
    }
    out
}

/// The pinned version: `KANI_VERSION: "x.y.z"` (digits and dots only).
fn pinned_version(yaml: &str) -> Option<String> {
    let line = yaml
        .lines()
        .find(|l| l.trim_start().starts_with("KANI_VERSION:"))?;
    let v = line.split(':').nth(1)?.trim().trim_matches('"');
    let parts: Vec<&str> = v.split('.').collect();
    (parts.len() == 3
        && parts
            .iter()
            .all(|p| !p.is_empty() && p.bytes().all(|b| b.is_ascii_digit())))
    .then(|| v.to_string())
}

/// Everything wrong with `yaml` given the harnesses of the sources.
fn problems(yaml: &str, harnesses: &BTreeSet<String>) -> Vec<String> {
    let mut p = Vec::new();
    let listed = matrix(yaml);
    let set: BTreeSet<String> = listed.iter().cloned().collect();
    if set.len() != listed.len() {
        p.push("a harness is listed twice".to_string());
    }
    for h in harnesses.difference(&set) {
        p.push(format!("not in the matrix: {h}"));
    }
    for h in set.difference(harnesses) {
        p.push(format!("not a harness of proofs/src: {h}"));
    }
    if pinned_version(yaml).is_none() {
        p.push("KANI_VERSION is not an exact x.y.z release".to_string());
    }
    for needed in [
        "cargo install --locked kani-verifier --version \"$KANI_VERSION\"",
        "cargo kani setup",
        "working-directory: proofs",
        "cargo kani --harness \"${{ matrix.harness }}\" --exact",
        "-Z unstable-options --fail-uncoverable",
        "timeout-minutes:",
    ] {
        if !yaml.contains(needed) {
            p.push(format!("missing: {needed}"));
        }
    }
    p
}

#[test]
fn the_workflow_runs_every_harness_under_the_pinned_kani() {
    let yaml = std::fs::read_to_string(root().join(".github/workflows/kani.yml")).expect("yaml");
    let harnesses = harnesses_in(&sources());
    // 16 claim and planner harnesses, 6 contract proofs.
    assert_eq!(harnesses.len(), 22, "{harnesses:?}");
    assert_eq!(problems(&yaml, &harnesses), Vec::<String>::new());
    let version = pinned_version(&yaml).expect("pinned");
    let guide = std::fs::read_to_string(root().join("docs/guide/kani.md")).expect("guide");
    assert!(
        guide.contains(&format!("Kani {version}")),
        "the guide names Kani {version}"
    );
    // The manifest Kani reads from proofs/ enables what the harnesses use.
    let manifest = std::fs::read_to_string(root().join("proofs/Cargo.toml")).expect("manifest");
    for flag in [
        "function-contracts = true",
        "stubbing = true",
        "fail-uncoverable = true",
    ] {
        assert!(manifest.contains(flag), "proofs/Cargo.toml: {flag}");
    }
}

/// The checks find a missing harness, an extra one, a floating version and a missing flag.
#[test]
fn planted_workflow_mistakes_are_found() {
    let sources = vec![(
        "c9".to_string(),
        "#[kani::proof]\n#[kani::unwind(3)]\npub fn a() {}\n#[kani::proof_for_contract(f)]\npub fn b() {}\n#[kani::proof]\nfn private() {}\n".to_string(),
    )];
    let h = harnesses_in(&sources);
    assert_eq!(h, ["c9::a", "c9::b"].map(String::from).into());
    let good = "env:\n  KANI_VERSION: \"0.65.0\"\njobs:\n  x:\n    timeout-minutes: 10\n    strategy:\n      matrix:\n        harness:\n          - c9::a\n          - c9::b\n    steps:\n      - run: |\n          cargo install --locked kani-verifier --version \"$KANI_VERSION\"\n          cargo kani setup\n      - working-directory: proofs\n        run: cargo kani --harness \"${{ matrix.harness }}\" --exact -Z unstable-options --fail-uncoverable\n";
    assert_eq!(problems(good, &h), Vec::<String>::new());
    let missing = good.replace("          - c9::b\n", "");
    assert_eq!(problems(&missing, &h), ["not in the matrix: c9::b"]);
    let extra = good.replace("- c9::b\n", "- c9::b\n          - c9::c\n");
    assert_eq!(problems(&extra, &h), ["not a harness of proofs/src: c9::c"]);
    let floating = good.replace("\"0.65.0\"", "latest");
    assert_eq!(
        problems(&floating, &h),
        ["KANI_VERSION is not an exact x.y.z release"]
    );
    let lax = good.replace(" -Z unstable-options --fail-uncoverable", "");
    assert_eq!(
        problems(&lax, &h),
        ["missing: -Z unstable-options --fail-uncoverable"]
    );
}
