//! The Kani harness registry (`claims::harnesses`) against the harness sources
//! in `proofs/src/` and the table of bodies `verify` runs (`truecost_proofs::harnesses`): every
//! `#[kani::proof]` and `#[kani::proof_for_contract(…)]` is registered under its file, with the
//! source's `#[kani::unwind]`, `#[kani::should_panic]` and stated sample count, and its doc
//! comment states the domain the registry gives; the table has every registered harness, in the
//! registry's order, with the same `should_panic` and sample count; and the stand-in's run of
//! each has the registry's mode, executions, choice bits and failures. (This cross-check lives
//! here, not in the proofs crate, so that the proofs crate does not depend on `truecost`.)

use std::collections::BTreeMap;
use std::path::Path;

use truecost::claims::harnesses::{
    not_run, of_claim, reported, run_standin, StandinMode, HARNESSES,
};

#[derive(Debug, Default)]
struct Source {
    file: String,
    doc: String,
    unwind: Option<u32>,
    should_panic: bool,
    samples: Option<u64>,
}

fn number<T: std::str::FromStr>(line: &str, attr: &str) -> Option<T> {
    let rest = line.split(attr).nth(1)?;
    let inner = rest.split(')').next()?.replace('_', "");
    inner.trim().parse().ok()
}

/// Every harness of `proofs/src/*.rs`, parsed from the source text.
fn sources() -> BTreeMap<String, Source> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("proofs/src");
    let mut out = BTreeMap::new();
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    files.sort();
    for path in files {
        let text = std::fs::read_to_string(&path).unwrap();
        let file = path.file_name().unwrap().to_string_lossy().to_string();
        let mut doc = String::new();
        let mut current: Option<Source> = None;
        for line in text.lines() {
            let t = line.trim();
            if let Some(d) = t.strip_prefix("///") {
                doc.push(' ');
                doc.push_str(d.trim());
                continue;
            }
            if t == "#[kani::proof]" || t.starts_with("#[kani::proof_for_contract(") {
                current = Some(Source {
                    file: file.clone(),
                    doc: std::mem::take(&mut doc),
                    ..Source::default()
                });
                continue;
            }
            if let Some(s) = current.as_mut() {
                if t.starts_with("#[kani::unwind(") {
                    s.unwind = number(t, "unwind(");
                } else if t == "#[kani::should_panic]" {
                    s.should_panic = true;
                } else if t.contains("kani::samples(") {
                    assert!(t.starts_with("#[cfg_attr(not(kani), kani::samples("), "{t}");
                    s.samples = number(t, "samples(");
                } else if let Some(rest) = t.strip_prefix("pub fn ") {
                    let name = rest.split('(').next().unwrap().to_string();
                    let s = current.take().unwrap();
                    assert!(out.insert(name, s).is_none(), "duplicate harness name");
                } else if t.starts_with("fn ") {
                    // A private harness: the stand-in's own tests in lib.rs, not a registered
                    // harness (the table `verify` runs names public ones only).
                    assert_eq!(file, "lib.rs", "{file}: a harness must be pub: {t}");
                    current = None;
                } else if !t.starts_with("#[") {
                    panic!("{file}: unexpected line between #[kani::proof] and its fn: {t}");
                }
            }
            if !t.starts_with("#[") {
                doc.clear();
            }
        }
    }
    out
}

fn standin_samples() -> u64 {
    let text = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("kani-standin/src/lib.rs"),
    )
    .unwrap();
    let line = text
        .lines()
        .find(|l| l.starts_with("pub const SAMPLES: u64 = "))
        .expect("the stand-in states its default sample count");
    line.trim_start_matches("pub const SAMPLES: u64 = ")
        .trim_end_matches(';')
        .replace('_', "")
        .parse()
        .unwrap()
}

#[test]
fn registry_matches_the_harness_sources() {
    let src = sources();
    let default_samples = standin_samples();
    assert_eq!(default_samples, 20_000);
    let registered: Vec<&str> = HARNESSES.iter().map(|h| h.name).collect();
    let in_sources: Vec<&str> = src.keys().map(String::as_str).collect();
    let mut sorted = registered.clone();
    sorted.sort_unstable();
    assert_eq!(sorted, in_sources, "every harness registered, nothing else");
    for h in HARNESSES {
        let s = &src[h.name];
        assert_eq!(h.file, s.file, "{}", h.name);
        assert_eq!(h.unwind, s.unwind, "{}: unwind", h.name);
        assert_eq!(h.should_panic, s.should_panic, "{}: should_panic", h.name);
        match h.mode {
            StandinMode::Sampled => assert_eq!(
                h.executions,
                s.samples.unwrap_or(default_samples),
                "{}: the stated sample count",
                h.name
            ),
            StandinMode::Exhaustive => {
                assert!(
                    s.samples.is_none(),
                    "{}: an exhaustive harness states no samples",
                    h.name
                );
                assert!(
                    h.name.ends_with("_exhaustive_small"),
                    "{}: named as such",
                    h.name
                );
                assert!(
                    s.doc.contains("exhaustive variant"),
                    "{}: documented as such",
                    h.name
                );
            }
        }
        // Wide harnesses state their width in their doc comment, as the registry does.
        if h.choice_bits >= 32 {
            assert_eq!(h.mode, StandinMode::Sampled, "{}", h.name);
            assert!(
                s.doc.contains(&format!("2^{}", h.choice_bits)),
                "{}: the doc comment states the width 2^{} (choice bits): {}",
                h.name,
                h.choice_bits,
                s.doc
            );
        }
        // A printed claim's harness says it must fail; a corrected one does not.
        assert_eq!(
            h.proves.starts_with("FAILS as expected"),
            h.should_panic,
            "{}",
            h.name
        );
        assert_eq!(h.failing > 0, h.should_panic, "{}", h.name);
        assert!(!h.kani_adds.is_empty(), "{}", h.name);
    }
}

/// The registry against the stand-in's runs of `truecost_proofs::harnesses()`: every harness
/// once, in the registry's order, and each run's mode, executions, choice bits and failing count
/// are the entry's; every run passes its own checks (no unexpected failure, a `should_panic`
/// harness refuted by an assertion, not vacuous, every cover satisfied); a contract proof's run
/// checks its function's contract on some call, and its entry is a lemma named after it.
#[test]
fn registry_matches_the_stand_in_runs() {
    use truecost_proofs::standin::Mode;
    let all = truecost_proofs::harnesses();
    let names: Vec<&str> = all.iter().map(|h| h.name).collect();
    let registered: Vec<&str> = HARNESSES.iter().map(|h| h.name).collect();
    assert_eq!(names, registered, "the table and the registry, in order");
    for h in &all {
        let entry = HARNESSES
            .iter()
            .find(|e| e.name == h.name)
            .expect("registered");
        assert_eq!(h.should_panic, entry.should_panic, "{}", h.name);
        let s = h.explore();
        assert_eq!(s.verdict(), Ok(()), "{s}");
        let mode = match s.mode {
            Mode::Exhaustive => StandinMode::Exhaustive,
            Mode::Sampled => StandinMode::Sampled,
        };
        assert_eq!(mode, entry.mode, "{s}");
        assert_eq!(s.executions, entry.executions, "{s}");
        assert_eq!(s.choice_bits, entry.choice_bits, "{s}");
        assert_eq!(s.failures, entry.failing, "{s}");
        // Wide domains only, but for the named small variants.
        assert_eq!(
            h.name.ends_with("_exhaustive_small"),
            entry.choice_bits < 32,
            "{}",
            h.name
        );
        // Not nearly vacuous: at least one execution in twenty is not pruned.
        assert!(s.executions - s.pruned >= s.executions / 20, "{s}");
        // A contract proof: its function's contract checked, registered as that lemma.
        if let Some(f) = h.contract {
            assert!(s.contract_calls > 0, "{s}");
            let function = f.rsplit("::").next().expect("a name");
            assert!(
                entry.claim.starts_with("contracts: ") && entry.claim.ends_with(function),
                "{}: {}",
                h.name,
                entry.claim
            );
            assert!(entry.proves.contains("proof_for_contract"), "{}", h.name);
        } else {
            assert!(!entry.claim.starts_with("contracts: "), "{}", h.name);
        }
    }
    // The six contract proofs are registered (and so reported by `verify`).
    assert_eq!(
        HARNESSES
            .iter()
            .filter(|h| h.claim.starts_with("contracts: "))
            .count(),
        6
    );
}

/// The table `verify` runs is the registry: the same harnesses in the same order, with the
/// source's `should_panic` and the registry's sample count (what a sampled run executes).
#[test]
fn the_table_verify_runs_is_the_registry() {
    let table = truecost_proofs::harnesses();
    let names: Vec<&str> = table.iter().map(|h| h.name).collect();
    let registered: Vec<&str> = HARNESSES.iter().map(|h| h.name).collect();
    assert_eq!(names, registered);
    for (t, h) in table.iter().zip(HARNESSES) {
        assert_eq!(t.should_panic, h.should_panic, "{}", h.name);
        if h.mode == StandinMode::Sampled {
            assert_eq!(t.samples, h.executions, "{}", h.name);
        }
    }
}

/// Every claim has a wide harness; run here, each is sampled, does what it states (a
/// `should_panic` one is refuted as expected, by an assertion), hits every cover, and its line
/// says it was run here by the stand-in and is not a Kani result. Not run, the line says so.
#[test]
fn every_claim_has_a_wide_harness_run_here_by_the_stand_in() {
    let table = truecost_proofs::harnesses();
    for id in ["C1", "C1-corrected", "C2", "C3", "C4", "C4-corrected"] {
        let hs = of_claim(id);
        assert!(!hs.is_empty(), "{id}");
        let names: Vec<&str> = hs.iter().map(|h| h.name).collect();
        for (h, run) in hs.iter().zip(run_standin(&table, &names)) {
            assert_eq!(run.problem, None, "{}", h.name);
            assert_eq!(run.covers_hit, run.covers, "{}", h.name);
            assert_eq!(run.should_panic, run.failures > 0, "{}", h.name);
            let e = reported(h, &run);
            assert!(
                e.mode.starts_with(&format!(
                    "run here by the stand-in: sampled {} executions, {} failures",
                    h.executions, run.failures
                )),
                "{id}: {}",
                e.mode
            );
            assert!(e.mode.ends_with("; not a Kani result"), "{}", e.mode);
            assert!(!e.mode.contains("HARNESS FAILS"), "{}", e.mode);
            assert_eq!(
                e.mode.contains("refuted as expected"),
                h.should_panic,
                "{}",
                e.mode
            );
            assert_eq!((e.cases, e.failures), (run.executions, run.failures));
            let skipped = not_run(h);
            assert!(skipped
                .mode
                .starts_with("NOT run by this verify (--no-harnesses)"));
            assert!(skipped.mode.contains("Kani itself not run here"));
            assert!(
                skipped
                    .mode
                    .contains(&format!("{} choice bits", h.choice_bits)),
                "{}",
                skipped.mode
            );
        }
    }
    // C1-corrected: the three inductive steps (Parts A and B, the sandwich).
    assert_eq!(of_claim("C1-corrected").len(), 3);
    // The small exhaustive variant states its exact number of choice sequences.
    let ex = of_claim("C3-example");
    let run = &run_standin(&table, &[ex[0].name])[0];
    assert_eq!(run.mode, "exhaustive");
    let line = reported(ex[0], run).mode;
    assert!(
        line.starts_with(&format!(
            "run here by the stand-in: exhaustive, every one of {} choice sequences, 0 failures",
            ex[0].executions
        )),
        "{line}"
    );
}

/// `(major, minor)` of a `rust-version` such as `"1.88"` or `"1.60.0"` (`None`: not declared).
fn version(v: &serde_json::Value) -> Option<(u32, u32)> {
    let mut parts = v
        .as_str()?
        .split('.')
        .map(|p| p.parse::<u32>().expect("a number"));
    Some((parts.next()?, parts.next().unwrap_or(0)))
}

/// Every workspace crate's `rust-version` is at least what each crate it
/// depends on (normal and build dependencies, transitively, every feature, on the host platform)
/// declares,
/// so a toolchain that the manifest accepts can build it (the previous 1.80 could not: z3 and
/// proptest need 1.88). The other side — no std API newer than `rust-version` is used — is
/// clippy's `incompatible_msrv` lint, which `cargo clippy -- -D warnings` enforces.
#[test]
fn rust_version_covers_every_dependency() {
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".to_string());
    // The host's dependency graph: offline, `cargo metadata` can only read the manifests that
    // a build on this platform fetched (a fresh machine has no Windows-only crates).
    let rustc = std::process::Command::new("rustc")
        .arg("-vV")
        .output()
        .expect("rustc runs");
    let host = String::from_utf8_lossy(&rustc.stdout)
        .lines()
        .find_map(|l| l.strip_prefix("host: ").map(str::to_string))
        .expect("rustc -vV names the host");
    let out = std::process::Command::new(cargo)
        .args(["metadata", "--offline", "--format-version", "1"])
        .args(["--filter-platform", &host])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("cargo runs");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let m: serde_json::Value = serde_json::from_slice(&out.stdout).expect("metadata JSON");
    let packages: BTreeMap<&str, &serde_json::Value> = m["packages"]
        .as_array()
        .expect("packages")
        .iter()
        .map(|p| (p["id"].as_str().expect("id"), p))
        .collect();
    let nodes: BTreeMap<&str, &serde_json::Value> = m["resolve"]["nodes"]
        .as_array()
        .expect("nodes")
        .iter()
        .map(|n| (n["id"].as_str().expect("id"), n))
        .collect();
    let mut members = 0;
    for id in m["workspace_members"].as_array().expect("members") {
        let id = id.as_str().expect("id");
        let name = packages[id]["name"].as_str().expect("name");
        let own = version(&packages[id]["rust_version"])
            .unwrap_or_else(|| panic!("{name} declares no rust-version"));
        let (mut seen, mut stack) = (std::collections::BTreeSet::new(), vec![id]);
        while let Some(x) = stack.pop() {
            for d in nodes[x]["deps"].as_array().expect("deps") {
                let runtime = d["dep_kinds"]
                    .as_array()
                    .expect("kinds")
                    .iter()
                    .any(|k| k["kind"].is_null() || k["kind"] == "build");
                let dep = d["pkg"].as_str().expect("pkg");
                if runtime && seen.insert(dep) {
                    stack.push(dep);
                }
            }
        }
        for dep in seen {
            if let Some(needed) = version(&packages[dep]["rust_version"]) {
                assert!(
                    own >= needed,
                    "{name} says rust-version {own:?} but {} needs {needed:?}",
                    packages[dep]["name"]
                );
            }
        }
        members += 1;
    }
    assert_eq!(
        members, 6,
        "truecost, kernel, proofs, the stand-in and its macros, the Python bindings"
    );
}
