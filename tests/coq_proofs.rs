//! The Coq development (`proofs/coq/`) re-checked by `coqc`, through the very function
//! `truecost verify` calls (`claims::coq::recheck`): every main theorem must be present and
//! accepted by `Print Assumptions` (closed, or only the standard library's axioms of the
//! reals; C1's, over the rationals, closed). Without `coqc` these tests fail with the install line: there is no silent skip.
//!
//! The re-check itself is exercised on small developments written here: one whose theorems
//! are closed or use only the reals' axioms, one that assumes a variable outside any section
//! (which the source scan does not see and `Print Assumptions` does), one that admits a lemma
//! (refused before compiling), and a theorem that does not exist.

use std::time::Duration;

use truecost::claims::coq::{self, Assumptions, Outcome, Settings, ALLOWED_AXIOMS, THEOREMS};

/// The re-check's settings for a small development: no pinned statements (every theorem is
/// then refused for that reason; these tests look at what `Print Assumptions` said).
fn unpinned() -> Settings {
    Settings {
        pins: vec![],
        ..Settings::with_timeout(Duration::from_secs(120))
    }
}

/// What `Print Assumptions` said about `name`.
fn assumptions<'a>(check: &'a coq::Check, name: &str) -> Option<&'a Assumptions> {
    check.theorem(name).map(|t| &t.assumptions)
}

fn require_coqc() -> String {
    match coq::coqc_version() {
        Ok(v) => v,
        Err(why) => panic!("{why}"),
    }
}

#[test]
fn every_main_theorem_is_rechecked_and_accepted() {
    require_coqc();
    let check = coq::recheck(Duration::from_secs(coq::TIMEOUT_SECONDS));
    assert_eq!(check.outcome, Outcome::Checked, "{check:?}");
    assert_eq!(check.files, coq::SOURCES.len());
    assert_eq!(check.theorems.len(), THEOREMS.len());
    for t in THEOREMS {
        let checked = check
            .theorem(t.name)
            .unwrap_or_else(|| panic!("{} not asked", t.name));
        assert!(checked.accepted(), "{}: {:?}", t.name, checked.refused);
        let a = &checked.assumptions;
        assert!(a.accepted(), "{}: {}", t.name, a.describe());
        if let Assumptions::Allowed(axioms) = a {
            assert!(axioms.iter().all(|x| ALLOWED_AXIOMS.contains(&x.as_str())));
        }
    }
    assert!(check.all_accepted());
    // C1's theorems are over Coq's rationals and need no axiom at all.
    for t in THEOREMS.iter().filter(|t| t.claim.starts_with("C1")) {
        assert_eq!(
            assumptions(&check, t.name),
            Some(&Assumptions::Closed),
            "{}",
            t.name
        );
    }
}

const CLEAN: &str = "Require Import QArith Reals Lra.
(* A comment that says Admitted and Axiom: ignored. *)
Lemma over_q : ((1 # 2) + (1 # 2) == 1)%Q.
Proof. reflexivity. Qed.
Lemma over_r : forall x : R, (x + 0 = x)%R.
Proof. intros; lra. Qed.
";

#[test]
fn a_small_development_closed_and_with_the_reals_axioms() {
    let version = require_coqc();
    let check = coq::recheck_sources(
        &[("A.v", CLEAN)],
        &[
            "Truecost.A.over_q",
            "Truecost.A.over_r",
            "Truecost.A.absent",
        ],
        &unpinned(),
    );
    assert_eq!(check.outcome, Outcome::Checked, "{check:?}");
    assert_eq!(check.version.as_deref(), Some(version.as_str()));
    assert_eq!(check.files, 1);
    assert_eq!(
        assumptions(&check, "Truecost.A.over_q"),
        Some(&Assumptions::Closed)
    );
    match assumptions(&check, "Truecost.A.over_r") {
        Some(Assumptions::Allowed(a)) => {
            assert!(
                a.contains(&"ClassicalDedekindReals.sig_forall_dec".to_string()),
                "{a:?}"
            )
        }
        other => panic!("{other:?}"),
    }
    match assumptions(&check, "Truecost.A.absent") {
        Some(Assumptions::Missing(why)) => assert!(why.contains("not found"), "{why}"),
        other => panic!("{other:?}"),
    }
    assert!(!check.all_accepted());
}

/// A variable declared outside any section is an assumption the source scan does not look
/// for; `Print Assumptions` lists it, and the theorem is refused.
#[test]
fn an_assumption_the_scan_misses_is_refused_by_print_assumptions() {
    require_coqc();
    let text = "Variable oops : False.\nLemma bad : 0 = 1.\nProof. destruct oops. Qed.\n";
    assert!(coq::scan_sources(&[("B.v", text)]).is_empty());
    let check = coq::recheck_sources(&[("B.v", text)], &["Truecost.B.bad"], &unpinned());
    assert_eq!(check.outcome, Outcome::Checked, "{check:?}");
    match assumptions(&check, "Truecost.B.bad") {
        Some(Assumptions::Forbidden(what)) => {
            assert_eq!(what, &["B.oops (Axioms)"])
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn admitted_sources_are_refused_before_compiling() {
    let text = "Lemma bad : 0 = 1.\nProof.\nAdmitted.\n";
    let check = coq::recheck_sources(
        &[("A.v", CLEAN), ("C.v", text)],
        &["Truecost.C.bad"],
        &unpinned(),
    );
    assert_eq!(
        check.outcome,
        Outcome::SourcesRefused(vec!["C.v:3: Admitted".into()])
    );
    assert_eq!(check.files, 0);
    assert!(check.theorems.is_empty());
}

/// A file that does not compile fails the build; the theorems of the files compiled before it
/// are still judged, and those of the failed file (and after) are missing.
#[test]
fn a_file_that_does_not_compile_is_a_failed_build() {
    require_coqc();
    let broken = "Lemma x : True.\nProof. exact 0. Qed.\n";
    let check = coq::recheck_sources(
        &[("A.v", CLEAN), ("D.v", broken)],
        &["Truecost.A.over_q", "Truecost.D.x"],
        &unpinned(),
    );
    match &check.outcome {
        Outcome::BuildFailed(why) => assert!(why.starts_with("D.v does not compile"), "{why}"),
        other => panic!("{other:?}"),
    }
    assert_eq!(check.files, 1);
    assert_eq!(
        assumptions(&check, "Truecost.A.over_q"),
        Some(&Assumptions::Closed)
    );
    assert_eq!(
        assumptions(&check, "Truecost.D.x"),
        Some(&Assumptions::Missing(
            "D.v was not compiled: an earlier file failed".into()
        ))
    );
    assert!(!check.all_accepted());
}
