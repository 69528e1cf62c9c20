//! `verify` reports the Kani harnesses as run in its own process by the stand-in, so a bug in a
//! harnessed kernel function shows in the report — a planted bug in `Units::plus` fails the
//! harness run and the report's line — and `--no-harnesses` says plainly they were not run.
//!
//! **How the bug is planted, and why this way.** The harness bodies call the kernel's `Units`
//! directly, so a wrong `plus` cannot be slipped under the real bodies without rebuilding the
//! kernel: a `--cfg` plant would need its own target directory and a rebuild of everything
//! above the kernel (truecost with z3, malachite and plotters: minutes, not the ≤ 60 s this
//! test may cost). Instead `verify`'s runner takes the table of bodies as a parameter
//! (`registry::Options::harnesses`), and the statements of the two `Units::plus` harnesses of
//! `proofs/src/values.rs` are written here once, over the addition they check
//! ([`exact_when_it_fits`], [`reports_every_overflow`]). Given the kernel's `Units` they must
//! pass with every cover hit — so the copies are the harnesses' statements, not strawmen — and
//! given a planted addition (saturating instead of reporting the overflow; off by one) they
//! must fail, in the stand-in's run and in `verify`'s report, whose table is the real one with
//! those two bodies replaced. The test runs the smoke report without SMT or Coq: seconds. A
//! table that panics fails the stand-in's engine: its lines say `engine failed`.

use truecost::claims::registry::{self, Options};
use truecost::claims::{report, Scope, Verdict};
use truecost::value::{CostValue, Units};
use truecost_proofs::standin::{self, Harness};

/// An addition under test: `checked_plus` (`None`: the overflow is reported) and `plus`.
struct Addition {
    checked: fn(u64, u64) -> Option<u64>,
    plus: fn(u64, u64) -> u64,
}

/// The kernel's.
const KERNEL: Addition = Addition {
    checked: |a, b| Units(a).checked_plus(&Units(b)).map(|u| u.0),
    plus: |a, b| Units(a).plus(&Units(b)).0,
};

/// Planted: saturates at the largest finite value instead of reporting the overflow.
const SATURATING: Addition = Addition {
    checked: |a, b| {
        if a == u64::MAX || b == u64::MAX {
            Some(u64::MAX)
        } else {
            Some(a.saturating_add(b).min(u64::MAX - 1))
        }
    },
    plus: |a, b| {
        if a == u64::MAX || b == u64::MAX {
            u64::MAX
        } else {
            a.saturating_add(b).min(u64::MAX - 1)
        }
    },
};

/// Planted: one too many on every finite sum that fits (and reports the overflow one early).
const OFF_BY_ONE: Addition = Addition {
    checked: |a, b| {
        if a == u64::MAX || b == u64::MAX {
            Some(u64::MAX)
        } else {
            a.checked_add(b)
                .and_then(|s| s.checked_add(1))
                .filter(|&s| s != u64::MAX)
        }
    },
    plus: |a, b| {
        if a == u64::MAX || b == u64::MAX {
            u64::MAX
        } else {
            a + b + 1
        }
    },
};

/// The statement of `units_plus_is_exact_when_it_fits` (proofs/src/values.rs) over `add`.
fn exact_when_it_fits(add: &Addition) {
    let (a, b): (u64, u64) = (standin::any(), standin::any());
    let exact = a as u128 + b as u128;
    standin::assume(a == u64::MAX || b == u64::MAX || exact < u64::MAX as u128);
    let s = Units((add.plus)(a, b));
    standin::cover!(a == u64::MAX || b == u64::MAX, "+inf absorbs");
    standin::cover!(a != u64::MAX && b != u64::MAX, "a finite sum that fits");
    if a == u64::MAX || b == u64::MAX {
        standin::assert(!s.is_finite(), "+inf absorbs");
    } else {
        standin::assert(s.0 as u128 == exact, "the exact sum");
        standin::assert(s.is_finite(), "a sum below u64::MAX is finite");
    }
}

/// The statement of `units_plus_reports_every_overflow` (proofs/src/values.rs) over `add`.
fn reports_every_overflow(add: &Addition) {
    let (a, b): (u64, u64) = (standin::any(), standin::any());
    let infinite = a == u64::MAX || b == u64::MAX;
    let exact = a as u128 + b as u128;
    let fits = infinite || exact < u64::MAX as u128;
    let checked = (add.checked)(a, b).map(Units);
    standin::cover!(!fits, "a finite sum that does not fit is reported");
    standin::cover!(
        !fits && exact > u64::MAX as u128,
        "a sum that would wrap is reported"
    );
    standin::cover!(fits && !infinite, "a finite sum that fits");
    standin::cover!(infinite, "+inf absorbs");
    standin::assert(
        checked.is_some() == fits,
        "None exactly when a finite sum does not fit",
    );
    if let Some(s) = checked {
        if infinite {
            standin::assert(!s.is_finite(), "+inf absorbs");
        } else {
            standin::assert(s.is_finite() && s.0 as u128 == exact, "the exact sum");
        }
        standin::assert(s == Units((add.plus)(a, b)), "plus agrees where it fits");
    }
}

const FITS: &str = "units_plus_is_exact_when_it_fits";
const OVERFLOW: &str = "units_plus_reports_every_overflow";

/// The real table's entry `name` with another body.
fn with_body(name: &str, body: fn()) -> Harness {
    let real = truecost_proofs::harnesses()
        .into_iter()
        .find(|h| h.name == name)
        .unwrap_or_else(|| panic!("{name} is a harness of truecost-proofs"));
    Harness { body, ..real }
}

/// The real table with the two `Units::plus` bodies replaced.
fn table_with(fits: fn(), overflow: fn()) -> Vec<Harness> {
    truecost_proofs::harnesses()
        .into_iter()
        .map(|h| match h.name {
            FITS => with_body(FITS, fits),
            OVERFLOW => with_body(OVERFLOW, overflow),
            _ => h,
        })
        .collect()
}

fn saturating_table() -> Vec<Harness> {
    table_with(
        || exact_when_it_fits(&SATURATING),
        || reports_every_overflow(&SATURATING),
    )
}

fn off_by_one_table() -> Vec<Harness> {
    table_with(
        || exact_when_it_fits(&OFF_BY_ONE),
        || reports_every_overflow(&OFF_BY_ONE),
    )
}

/// The copies are the harnesses' statements: over the kernel's addition they pass with every
/// cover hit, as the real harnesses do; over a planted addition the stand-in's run fails and
/// names the assertion.
#[test]
fn a_planted_plus_fails_the_harness_run() {
    for (name, body) in [
        (FITS, (|| exact_when_it_fits(&KERNEL)) as fn()),
        (OVERFLOW, || reports_every_overflow(&KERNEL)),
    ] {
        let real = truecost_proofs::harnesses()
            .into_iter()
            .find(|h| h.name == name)
            .expect("a harness of truecost-proofs");
        let s = real.explore();
        assert_eq!(s.verdict(), Ok(()), "{s}");
        let copy = with_body(name, body).explore();
        assert_eq!(copy.verdict(), Ok(()), "{copy}");
        assert_eq!(copy.covers_hit(), copy.covers.len());
        assert_eq!(copy.covers.len(), s.covers.len(), "{name}: the same covers");
        assert_eq!(copy.executions, s.executions);
    }
    // Saturating: the overflow harness finds an unreported overflow.
    let s = with_body(OVERFLOW, || reports_every_overflow(&SATURATING)).explore();
    let why = s.verdict().expect_err("a saturating plus must fail");
    assert!(
        why.contains("None exactly when a finite sum does not fit"),
        "{why}"
    );
    assert!(s.failures > 0 && why.contains("choice sequence"), "{why}");
    // Off by one: both harnesses fail.
    let s = with_body(FITS, || exact_when_it_fits(&OFF_BY_ONE)).explore();
    assert!(
        s.verdict()
            .expect_err("off by one")
            .contains("the exact sum"),
        "{s}"
    );
    let s = with_body(OVERFLOW, || reports_every_overflow(&OFF_BY_ONE)).explore();
    assert!(s.verdict().is_err() && s.failures > 0, "{s}");
}

/// The engine line of harness `name` in the text report.
fn line<'a>(text: &'a str, name: &str) -> &'a str {
    text.lines()
        .find(|l| l.contains(&format!("kani harness {name} [")))
        .unwrap_or_else(|| panic!("no line for {name} in:\n{text}"))
}

/// `verify`'s report with a planted addition under the two harnesses: their lines say the
/// harness fails, with failures counted and the assertion named, the summary counts them, and
/// the other harnesses' lines are unchanged; with the kernel's addition the same lines pass.
#[test]
fn verify_reports_a_planted_bug_as_a_failing_harness() {
    let options = |table: registry::HarnessTable| Options {
        smt: false,
        coq: false,
        harnesses: Some(table),
        ..Options::default()
    };
    let clean = registry::run(Scope::Smoke, None, &options(truecost_proofs::harnesses)).unwrap();
    let clean_text = report::text(&clean, false);
    for name in [FITS, OVERFLOW] {
        let l = line(&clean_text, name);
        assert!(
            l.contains(" 0 failures") && !l.contains("HARNESS FAILS"),
            "{l}"
        );
    }
    assert!(clean_text.contains(", 0 failing;"), "{clean_text}");
    for (table, failing) in [
        (saturating_table as registry::HarnessTable, vec![OVERFLOW]),
        (off_by_one_table, vec![FITS, OVERFLOW]),
    ] {
        let r = registry::run(Scope::Smoke, None, &options(table)).unwrap();
        let text = report::text(&r, false);
        for name in [FITS, OVERFLOW] {
            let l = line(&text, name);
            if failing.contains(&name) {
                assert!(l.contains("HARNESS FAILS"), "{l}");
                assert!(l.contains("run here by the stand-in: sampled"), "{l}");
                assert!(!l.contains(" 0 failures"), "{l}");
            } else {
                assert_eq!(l, line(&clean_text, name));
            }
        }
        assert!(
            text.contains(&format!(", {} failing;", failing.len())),
            "{text}"
        );
        // The claims are untouched by a lemma's failure; the JSON carries the same lines.
        for (a, b) in r.claims.iter().zip(&clean.claims) {
            assert_eq!(a.verdict, b.verdict, "{}", a.id);
        }
        let json: serde_json::Value = serde_json::from_str(&report::json(&r, false)).unwrap();
        let lemmas = json["harnesses"]["lemmas"].as_array().unwrap();
        let failing_json = lemmas
            .iter()
            .filter(|e| e["mode"].as_str().unwrap().contains("HARNESS FAILS"))
            .count();
        assert_eq!(failing_json, failing.len());
    }
    // No claim of the clean report is inconclusive for a harness's sake.
    assert!(clean
        .claims
        .iter()
        .all(|c| c.verdict != Verdict::Inconclusive));
}

/// `--no-harnesses`: the report says plainly that the harnesses were not run, every harness
/// line says so with 0 cases, and nothing claims a run.
#[test]
fn no_harnesses_says_they_were_not_run() {
    let out = assert_cmd::Command::cargo_bin("truecost")
        .unwrap()
        .args([
            "verify",
            "--no-coq",
            "--no-smt",
            "--no-harnesses",
            "--scope",
            "smoke",
            "--claim",
            "C3",
        ])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(
        text.contains("harnesses: the 2 kani harnesses of proofs/ for these claims were NOT run (--no-harnesses)"),
        "{text}"
    );
    let lines: Vec<&str> = text
        .lines()
        .filter(|l| l.contains("engine: kani harness"))
        .collect();
    assert_eq!(lines.len(), 2, "{text}");
    for l in lines {
        assert!(
            l.contains("[NOT run by this verify (--no-harnesses)"),
            "{l}"
        );
        assert!(l.ends_with("] 0 cases, 0 failures"), "{l}");
        assert!(!l.contains("run here by the stand-in"), "{l}");
    }
}

/// A table of harness bodies that cannot even be built (its function panics): the stand-in's
/// engine fails for every harness of the claim, whose lines say `engine failed` with the
/// panic's message and place, the claim is inconclusive, the other engines still report, and
/// the failure is listed for `verify`'s exit status.
#[test]
fn a_failing_harness_engine_is_reported_and_makes_the_claim_inconclusive() {
    fn unbuildable() -> Vec<Harness> {
        panic!("planted: no table\nof harnesses")
    }
    let options = Options {
        smt: false,
        coq: false,
        harnesses: Some(unbuildable),
        ..Options::default()
    };
    let r = registry::run(Scope::Smoke, Some("C2"), &options).unwrap();
    let c2 = &r.claims[0];
    assert_eq!((c2.id.as_str(), c2.verdict), ("C2", Verdict::Inconclusive));
    let engines: Vec<&str> = c2.engines.iter().map(|e| e.engine.as_str()).collect();
    assert_eq!(
        engines,
        [
            "exhaustive enumeration",
            "kani harness c2_oracle_argmin_cost_is_argmax_reward",
            "proptest"
        ]
    );
    // The enumeration and proptest ran in full (C2 holds: no failures).
    for e in [&c2.engines[0], &c2.engines[2]] {
        assert!(e.cases > 0 && e.failures == 0, "{e:?}");
    }
    let text = report::text(&r, false);
    let harness = line_of(
        &text,
        "  engine: kani harness c2_oracle_argmin_cost_is_argmax_reward",
    );
    assert!(
        harness.starts_with(
            "  engine: kani harness c2_oracle_argmin_cost_is_argmax_reward: engine failed: planted: no table\\nof harnesses (at tests/verify_harnesses.rs:"
        ),
        "{harness}"
    );
    assert_eq!(
        registry::engine_failures(&r),
        ["C2: kani harness c2_oracle_argmin_cost_is_argmax_reward"]
    );
    assert!(text.contains("\nC2  INCONCLUSIVE\n"), "{text}");
}

/// The line of `text` starting with `start`.
fn line_of<'a>(text: &'a str, start: &str) -> &'a str {
    text.lines()
        .find(|l| l.starts_with(start))
        .unwrap_or_else(|| panic!("no line starting {start:?} in:\n{text}"))
}

/// With times, the harnesses line says whether the harness bodies' crate checks overflow, as
/// this test's own build does (the test profile: on), and says nothing of it without times.
#[test]
fn the_harnesses_line_says_which_crates_check_overflow() {
    let this_build = std::panic::catch_unwind(|| {
        std::hint::black_box(std::hint::black_box(u8::MAX) + std::hint::black_box(1u8))
    })
    .is_err();
    let options = Options {
        smt: false,
        coq: false,
        ..Options::default()
    };
    let r = registry::run(Scope::Smoke, Some("C3-example"), &options).unwrap();
    let crates = r
        .harnesses
        .as_ref()
        .unwrap()
        .overflow_checks
        .clone()
        .unwrap();
    // Every crate of a test build is built alike.
    assert!(crates.contains(&("truecost-proofs (the harness bodies)", this_build)));
    assert!(crates.iter().all(|&(_, on)| on == this_build), "{crates:?}");
    let text = report::text(&r, true);
    let timed = line_of(&text, "harnesses: ");
    let state = if this_build { "on in" } else { "are OFF in" };
    assert!(
        timed.contains(&format!("; overflow checks {state} "))
            && timed.contains("truecost-proofs (the harness bodies)"),
        "{timed}"
    );
    assert!(!line_of(&report::text(&r, false), "harnesses: ").contains("overflow"));
}
