//! The SMT engine on claim C1: a hand-checked obligation, the trust checks,
//! a planted wrong threshold, the printed claim's replayed counterexample, and the
//! `--smt-out` files re-solved to their declared status.

use truecost::claims::smt::{self, c1, solve, solve_text, Answer, Role, SmtVerdict, Status};
use truecost::claims::Scope;

/// A1 for a successor with one pair, written by hand: `l ≥ 0`, `Q*(y) ≥ 0`, `G*(y) = Q*(y)`,
/// `v = Q(y) ≥ Q*(y)`, and the negated conclusion `l + v < l + G*(y)`.
const A1_ONE_PAIR: &str = "(set-info :smt-lib-version 2.6)
(set-logic QF_LRA)
(set-info :source |truecost 0.1.0: C1-corrected / A1: Q >= Q* is preserved by one update / any graph; successor y with 1 pair(s) / proof|)
(set-info :status unsat)
(declare-const l Real)
(declare-const qy0 Real)
(declare-const sy0 Real)
(declare-const gy Real)
(declare-const v Real)
(assert (>= l 0.0))
(assert (>= sy0 0.0))
(assert (and (<= gy sy0) (= gy sy0)))
(assert (and (<= v qy0) (= v qy0)))
(assert (>= qy0 sy0))
(assert (< (+ l v) (+ l gy)))
(check-sat)
(exit)
";

#[test]
fn the_first_local_lemma_is_the_hand_written_obligation() {
    let enc = c1::corrected(Scope::Smoke);
    let proof = enc
        .obligations
        .iter()
        .find(|o| o.role == Role::Proof)
        .expect("a proof obligation");
    assert_eq!(proof.smtlib(Some(Status::Unsat)), A1_ONE_PAIR);
    assert_eq!(solve(proof, 10_000), Answer::Unsat);
    assert_eq!(solve_text(A1_ONE_PAIR, 10_000), Some(Status::Unsat));
    // Its hypotheses twin comes first and is satisfiable, with a model meeting them exactly.
    let hyp = &enc.obligations[0];
    assert_eq!(hyp.role, Role::Hypotheses);
    assert_eq!(hyp.asserts.len() + 1, proof.asserts.len());
    match solve(hyp, 10_000) {
        Answer::Sat(Some(m)) => {
            let (qy, sy) = (m.get("qy0").unwrap(), m.get("sy0").unwrap());
            assert!(qy >= sy, "Q >= Q* in the model");
            assert_eq!(m.get("v"), Some(qy));
            assert_eq!(m.get("gy"), Some(sy));
        }
        other => panic!("hypotheses: {other:?}"),
    }
}

#[test]
fn c1_corrected_is_proved_in_the_smoke_scope_with_every_trust_check() {
    let out = smt::run(c1::corrected(Scope::Smoke), smt::TIMEOUT_MS);
    assert_eq!(out.verdict, SmtVerdict::Proved, "{:?}", out.notes);
    let s = &out.summary;
    assert!(s.proofs > 20, "{s:?}");
    assert_eq!(s.proofs, s.proofs_unsat);
    assert_eq!(s.trust_checks, s.trust_ok);
    assert_eq!(s.unknown, 0);
    // Every proof obligation has a satisfiable twin, and the dropped hypotheses are tried.
    let roles =
        |f: &dyn Fn(&Role) -> bool| out.solved.iter().filter(|x| f(&x.obligation.role)).count();
    assert!(roles(&|r| *r == Role::Hypotheses) >= roles(&|r| *r == Role::Proof));
    for h in ["H2", "costs >= c > 0", "H0"] {
        assert!(
            out.solved.iter().any(|x| matches!(&x.obligation.role,
                Role::Dropped(d) if d.starts_with(h))
                && x.answer.status() == Some(Status::Sat)),
            "dropping {h} finds a failure"
        );
    }
}

#[test]
fn a_planted_wrong_round_bound_is_rejected() {
    // R1 = max h(f(x,u)) instead of 1 + max h(f(x,u)).
    let out = smt::run(
        c1::corrected_with_round_bound(Scope::Smoke, 0),
        smt::TIMEOUT_MS,
    );
    assert_ne!(out.verdict, SmtVerdict::Proved);
    let failing: Vec<_> = out
        .solved
        .iter()
        .filter(|x| x.obligation.role == Role::Proof && x.answer.status() == Some(Status::Sat))
        .collect();
    assert!(!failing.is_empty());
    assert!(failing
        .iter()
        .all(|x| x.obligation.lemma.starts_with("A: ")));
    // The statement's own bound passes on the same structures.
    let good = smt::run(
        c1::corrected_with_round_bound(Scope::Smoke, 1),
        smt::TIMEOUT_MS,
    );
    assert_eq!(good.verdict, SmtVerdict::Proved);
}

#[test]
fn c1_as_printed_is_satisfiable_and_its_model_replays() {
    let out = smt::run(c1::printed(), smt::TIMEOUT_MS);
    assert_eq!(out.verdict, SmtVerdict::Refuted, "{:?}", out.notes);
    let ce = out.counterexample.expect("a replayed counterexample");
    assert!(
        ce.summary.contains("never") || ce.summary.contains("repeat"),
        "{}",
        ce.summary
    );
    assert!(
        ce.problem_file.contains("truecost-problem"),
        "{}",
        ce.problem_file
    );
}

#[test]
fn smt_out_files_parse_back_and_re_solve_to_their_status() {
    let dir = tempfile::tempdir().unwrap();
    let out_dir = dir.path().join("smt");
    smt::prepare_out_dir(&out_dir).unwrap();
    let out = smt::run(c1::corrected(Scope::Smoke), smt::TIMEOUT_MS);
    smt::write_files(&out_dir, &out.solved).unwrap();
    let index = std::fs::read_to_string(out_dir.join("index.tsv")).unwrap();
    let rows: Vec<&str> = index.lines().skip(1).collect();
    assert_eq!(rows.len(), out.solved.len());
    for row in rows {
        let cols: Vec<&str> = row.split('\t').collect();
        assert_eq!(cols.len(), 7, "{row}");
        let text = std::fs::read_to_string(out_dir.join(cols[0])).unwrap();
        assert!(text.contains("(set-logic QF_"), "{}", cols[0]);
        assert!(!text.contains("(get-model)") && !text.contains("(set-option"));
        let declared = if text.contains("(set-info :status unsat)") {
            Status::Unsat
        } else {
            assert!(text.contains("(set-info :status sat)"), "{}", cols[0]);
            Status::Sat
        };
        assert_eq!(declared.name(), cols[6], "{row}");
        assert_eq!(cols[5], cols[6], "expected answer: {row}");
        assert_eq!(solve_text(&text, 60_000), Some(declared), "{}", cols[0]);
    }
    // A second run into the same, now non-empty, directory is refused before any work.
    let e = smt::prepare_out_dir(&out_dir).unwrap_err();
    assert!(e.contains("not empty"), "{e}");
}

#[test]
fn an_unknown_answer_is_inconclusive_never_proved() {
    use truecost::claims::smt::{Encoding, Logic, Obligation, Replay, Sort};
    // A proof obligation Z3 cannot read (an undeclared symbol): `solve` answers unknown.
    let mut bad = Obligation::new("demo", "unreadable", "none", Role::Proof, Logic::QfLra);
    let x = bad.declare("x", Sort::Real);
    bad.assert(format!("(< {x} undeclared)"));
    assert!(matches!(solve(&bad, 10_000), Answer::Unknown(_)));
    // Its satisfiable twin, so that every trust check passes and only the unknown decides.
    let mut hyp = Obligation::new("demo", "unreadable", "none", Role::Hypotheses, Logic::QfLra);
    let y = hyp.declare("y", Sort::Real);
    hyp.assert(format!("(> {y} 0.0)"));
    let out = smt::run(
        Encoding {
            claim: "demo",
            scope: "one obligation".into(),
            obligations: vec![hyp, bad],
            replay: |_, _| Replay::NotApplicable,
        },
        smt::TIMEOUT_MS,
    );
    assert_eq!(out.verdict, SmtVerdict::Inconclusive);
    assert_eq!(out.summary.unknown, 1);
    assert!(
        out.notes.iter().any(|n| n.contains("unknown")),
        "{:?}",
        out.notes
    );
}

/// Part B's round count with `R` the integer ceiling: the statement's bound, made from
/// `c1::ROUND_BOUND`, is proved (B4 unsat, its hypotheses sat), and the same encoding made
/// from a bound with the ceiling one too low, `R = max(R1, ceil((max Q* - m)/c) - 1)`, gets a
/// satisfiable B4 whose model replays exactly as a bound that stops short: the SMT engine
/// refutes it.
#[test]
fn a_planted_ceiling_minus_one_is_refuted_by_the_smt_engine() {
    use truecost::claims::c1::{RoundBound, ROUND_BOUND};
    let b4 = |enc: &smt::Encoding| {
        enc.obligations
            .iter()
            .filter(|o| o.lemma.starts_with("B4: "))
            .cloned()
            .collect::<Vec<_>>()
    };
    let good = c1::corrected_with(Scope::Smoke, ROUND_BOUND);
    let good_b4 = b4(&good);
    assert_eq!(good_b4.len(), 2, "a proof and its hypotheses twin");
    for o in &good_b4 {
        assert_eq!(o.logic.name(), "QF_NIRA");
        assert!(o
            .decls
            .iter()
            .any(|(n, s)| n == "R" && *s == smt::Sort::Int));
        let expected = o.role.expected();
        assert_eq!(solve(o, 60_000).status(), Some(expected), "{}", o.lemma);
    }
    assert_eq!(
        good_b4[0].lemma,
        "B4: R = max(R1, ceil((max Q* - min(0, min Q0)) / c)) with R1 = 1 + max over moves (x,u) of h(f(x,u)): R rounds reach level max Q*"
    );

    let planted = RoundBound {
        ceil_offset: -1,
        ..ROUND_BOUND
    };
    let enc = c1::corrected_with(Scope::Smoke, planted);
    assert!(enc
        .scope
        .contains("ceil((max Q* - min(0, min Q0)) / c) - 1"));
    let out = smt::run(enc, smt::TIMEOUT_MS);
    assert_eq!(out.verdict, SmtVerdict::Refuted, "{:?}", out.notes);
    let sat: Vec<_> = out
        .solved
        .iter()
        .filter(|x| x.obligation.role == Role::Proof && x.answer.status() == Some(Status::Sat))
        .collect();
    assert_eq!(sat.len(), 1, "only B4 fails");
    assert!(sat[0]
        .obligation
        .lemma
        .contains("ceil((max Q* - min(0, min Q0)) / c) - 1"));
    assert!(
        out.notes
            .iter()
            .any(|n| n.contains("the bound stops short")),
        "{:?}",
        out.notes
    );
}

/// The printed claim's obligations carry C1's own label: `--smt-out` writes them under
/// `c1/`, and the index names them `C1`, apart from C1-corrected's.
#[test]
fn printed_obligations_are_exported_under_c1() {
    let out = smt::run(c1::printed(), smt::TIMEOUT_MS);
    assert!(!out.solved.is_empty());
    assert!(out.solved.iter().all(|s| s.obligation.claim == "C1"));
    let dir = tempfile::tempdir().unwrap();
    smt::write_files(dir.path(), &out.solved).unwrap();
    let index = std::fs::read_to_string(dir.path().join("index.tsv")).unwrap();
    let rows: Vec<&str> = index.lines().skip(1).collect();
    assert_eq!(rows.len(), out.solved.len());
    for row in rows {
        let cols: Vec<&str> = row.split('\t').collect();
        assert!(cols[0].starts_with("c1/"), "{row}");
        assert_eq!(cols[1], "C1", "{row}");
    }
    assert!(!dir.path().join("c1-corrected").exists());
}
