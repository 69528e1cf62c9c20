//! `cargo kani -p truecost-proofs` compiles only what the harnesses verify.
//!
//! `cargo kani` passes `--cfg=kani` to cargo through `RUSTFLAGS`, so cargo evaluates the
//! `[target.'cfg(not(kani))'.…]` tables of `proofs/Cargo.toml` with it; `cargo tree` under the
//! same `RUSTFLAGS` therefore lists exactly the crates Kani's build compiles (Kani's own `kani`
//! crate aside, which it injects). The assertion: that list is this crate and the bignum-free
//! kernel, nothing else — in particular none of clap, plotters, rayon, indicatif, z3 or a
//! big-integer crate (num-bigint, num-rational, dashu).

use std::collections::BTreeSet;
use std::process::Command;

/// The package names in `cargo tree -p truecost-proofs` with the given `RUSTFLAGS` and edge
/// kinds (`normal`, or `all` for dev-dependencies too).
fn tree(rustflags: &str, edges: &str) -> BTreeSet<String> {
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".to_string());
    let out = Command::new(cargo)
        .args(["tree", "--offline", "-p", "truecost-proofs", "-e", edges])
        .args(["--prefix", "none", "--format", "{p}"])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .env("RUSTFLAGS", rustflags)
        .env_remove("CARGO_ENCODED_RUSTFLAGS")
        .output()
        .expect("cargo runs");
    assert!(
        out.status.success(),
        "cargo tree failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout)
        .expect("utf-8")
        .lines()
        .filter_map(|l| l.split_whitespace().next())
        .map(str::to_string)
        .collect()
}

/// The crates that must never reach Kani's build.
fn forbidden(name: &str) -> bool {
    [
        "clap",
        "plotters",
        "rayon",
        "indicatif",
        "z3",
        "num-",
        "dashu",
        "serde",
    ]
    .iter()
    .any(|f| name == f.trim_end_matches('-') || name.starts_with(f))
}

#[test]
fn under_cfg_kani_the_proofs_build_is_the_kernel_alone() {
    let lean: BTreeSet<String> = ["truecost-kernel", "truecost-proofs"]
        .map(str::to_string)
        .into();
    for edges in ["normal", "all"] {
        let crates = tree("--cfg kani", edges);
        let bad: Vec<&String> = crates.iter().filter(|c| forbidden(c)).collect();
        assert!(bad.is_empty(), "-e {edges}: Kani's build pulls {bad:?}");
        assert_eq!(crates, lean, "-e {edges}: Kani's build is not lean");
    }
}

/// The check above is not vacuous: without `--cfg kani` the same command sees the stand-in
/// and its macros' dependencies (a `cfg(not(kani))` dependency), so `cargo tree` does evaluate
/// the cfg; and the forbidden list matches the crates it names.
#[test]
fn without_cfg_kani_the_stand_in_appears() {
    let normal = tree("", "normal");
    for name in ["kani-standin", "kani-standin-macros", "syn"] {
        assert!(normal.contains(name), "{name} missing from {normal:?}");
    }
    for name in [
        "clap",
        "num-bigint",
        "num-rational",
        "rayon",
        "z3",
        "serde_json",
    ] {
        assert!(forbidden(name), "{name}");
    }
    assert!(!forbidden("truecost-kernel") && !forbidden("syn"));
}

/// No import cycle: the proofs crate depends on `truecost` in no way (normal and
/// dev-dependencies, with or without `--cfg kani`); `truecost` depends on it (to run the
/// harness bodies in `verify`) and checks its harness registry against it in its own tests.
#[test]
fn the_proofs_crate_does_not_depend_on_truecost() {
    for rustflags in ["", "--cfg kani"] {
        let crates = tree(rustflags, "normal,dev");
        assert!(crates.contains("truecost-kernel"), "{crates:?}");
        assert!(!crates.contains("truecost"), "{rustflags:?}: {crates:?}");
    }
}
