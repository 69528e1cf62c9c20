//! The SMT encodings of C4 and C4-corrected: a hand-written obligation, the trust
//! checks, the mutation test, and the SMT-LIB files read back and re-solved.

use truecost::claims::smt::c4::{self, Formula, Shape};
use truecost::claims::smt::{
    self, solve, write_files, Answer, Logic, Obligation, Replay, Role, SmtVerdict, Sort,
};
use truecost::claims::Scope;
use truecost::value::Rational;

const T: u32 = 60_000;

/// `x1 = 0` with a self-loop `c0` and a move `c1` to the goal `1`.
fn loop_shape() -> Shape {
    Shape {
        n: 2,
        edges: vec![(0, 0), (0, 1)],
    }
}

/// The obligation for the self-loop shape, typed by hand from the statement. The only goal
/// path is `0 -> 1` (S* = 2, L* = c1); the policies are "loop" (average c0/1) and "go"
/// (average (c1 + M)/2). Optimal: (c1+M)·1 <= 2·c0 and (c1+M)·2 <= 2·(c1+M). Corrected
/// interval: no T(u) (one path), so M < 0 and M <= 2·Lav − L* = 2·(1·c0) − c1.
#[test]
fn the_self_loop_obligation_is_the_hand_written_text_and_is_unsat() {
    let ob = c4::obligation(
        "C4-corrected",
        &loop_shape(),
        Formula::Corrected,
        Role::Proof,
    )
    .expect("a goal path exists");
    let expected = "\
(declare-const c0 Real)
(declare-const c1 Real)
(declare-const M Real)
(assert (>= c0 0.0))
(assert (>= c1 0.0))
(assert (< M 0.0))
(assert (not (= (and (<= (* 1.0 (+ c1 M)) (* 2.0 c0)) (<= (* 2.0 (+ c1 M)) (* 2.0 (+ c1 M)))) \
(and (< M 0.0) (<= M (- (* 2.0 (* 1.0 c0)) c1))))))
(check-sat)
(exit)
";
    let text = ob.smtlib(None);
    let body = text.split_once("|)\n").expect("source line").1;
    assert_eq!(body, expected);
    assert!(text.contains("(set-logic QF_LRA)"));
    assert_eq!(solve(&ob, T), Answer::Unsat);
}

/// Without the cycle term the same shape fails: c0 = 0, c1 = 1, M = −1/2 gives π* the average
/// 1/4 while looping costs 0. Z3 must find such a model, and the oracle must confirm it.
#[test]
fn dropping_the_cycle_term_is_sat_and_the_model_replays() {
    let ob = c4::obligation(
        "C4-corrected",
        &loop_shape(),
        Formula::WithoutCycleTerm,
        Role::Dropped("the cycle term".into()),
    )
    .unwrap();
    let Answer::Sat(Some(model)) = solve(&ob, T) else {
        panic!("expected a rational model");
    };
    // By hand: a failure needs (c1 + M)/2 > c0, i.e. the loop beats pi*.
    let get = |n: &str| model.get(n).unwrap().clone();
    let two = Rational::from_integer(2.into());
    assert!((get("c1") + get("M")) / two > get("c0"));
    assert!(matches!(
        c4::replay(&ob, &model),
        Replay::Confirmed(_, None)
    ));
}

/// A model that is no failure must not replay: the hand-chosen c0 = 1, c1 = 1, M = −1 (π*
/// optimal, M inside the interval) is rejected.
#[test]
fn a_non_failure_does_not_replay() {
    let ob = c4::obligation(
        "C4-corrected",
        &loop_shape(),
        Formula::WithoutCycleTerm,
        Role::Dropped("the cycle term".into()),
    )
    .unwrap();
    let r = |n: i64| Rational::from_integer(n.into());
    let model = smt::Model {
        values: vec![
            ("c0".into(), r(1)),
            ("c1".into(), r(1)),
            ("M".into(), r(-1)),
        ],
    };
    assert!(matches!(c4::replay(&ob, &model), Replay::NotConfirmed(_)));
}

#[test]
fn c4_corrected_is_proved_on_the_smoke_scope_with_every_trust_check() {
    let enc = c4::encoding(Scope::Smoke);
    assert_eq!(enc.claim, "C4-corrected");
    assert!(enc.scope.contains("<= 3 states"), "{}", enc.scope);
    let count = |f: &dyn Fn(&Role) -> bool| enc.obligations.iter().filter(|o| f(&o.role)).count();
    let proofs = count(&|r| *r == Role::Proof);
    let hyps = count(&|r| *r == Role::Hypotheses);
    let dropped = count(&|r| matches!(r, Role::Dropped(_)));
    assert!(
        proofs > 10 && hyps > 0 && dropped > 0,
        "{proofs} {hyps} {dropped}"
    );
    let out = smt::run(enc, T);
    assert_eq!(out.verdict, SmtVerdict::Proved, "{:?}", out.notes);
    assert_eq!(out.summary.proofs, proofs as u64);
    assert_eq!(out.summary.trust_ok, (hyps + dropped) as u64);
    // Every dropped-cycle-term model replayed (a failed replay would be a note).
    assert!(
        !out.notes.iter().any(|n| n.contains("does not replay")),
        "{:?}",
        out.notes
    );
    for s in &out.solved {
        if let Role::Dropped(_) = s.obligation.role {
            let Answer::Sat(Some(m)) = &s.answer else {
                panic!("dropped check not sat: {:?}", s.answer)
            };
            assert!(matches!(
                c4::replay(&s.obligation, m),
                Replay::Confirmed(_, None)
            ));
        }
    }
}

/// The printed statement fails, e.g. on the 3-state shape `0 -> 2` (cost a), `0 -> 1 -> 2`
/// (total L): by hand, with a = L = 1 and π* the direct move, the exact condition is
/// (a + M)/2 <= (L + M)/3, i.e. M <= 2L − 3a = −1, while the printed one is
/// M <= A(u) = (1 − 3/2)(3a/(2L) − 1) = −1/4: M = −1/2 breaks it. Z3 must find some failure
/// on every shape of the printed encoding, and the exact oracle must confirm each.
#[test]
fn c4_as_printed_is_refuted_by_a_replayed_model() {
    let enc = c4::encoding_printed(Scope::Smoke);
    assert_eq!(enc.claim, "C4");
    assert!(enc.obligations.iter().all(|o| o.role == Role::Printed));
    assert!(enc.obligations.iter().all(|o| o.logic == Logic::QfNra));
    assert!(enc.obligations.len() >= 2);
    let out = smt::run(enc, T);
    assert_eq!(out.verdict, SmtVerdict::Refuted, "{:?}", out.notes);
    let ce = out.counterexample.expect("a replayed counterexample");
    assert!(ce.summary.contains("printed formula"), "{}", ce.summary);
    assert!(
        ce.summary.contains("exact average-cost oracle"),
        "{}",
        ce.summary
    );
    // The counterexample's problem file is a valid problem with the model's exact costs.
    let p = truecost::model::file::from_json(&ce.problem_file).expect("parses");
    assert_eq!(p.initial(), 0);
    assert_eq!(p.goals(), &[p.states() - 1]);
}

/// The mutation test: a planted wrong threshold (T(u) counted in moves, not states) makes
/// proof obligations sat, and their models replay as failures of the planted formula.
#[test]
fn a_planted_wrong_threshold_is_caught() {
    let enc = c4::encoding_with(Scope::Smoke, Formula::Planted);
    let out = smt::run(enc, T);
    assert_eq!(out.verdict, SmtVerdict::Refuted, "{:?}", out.notes);
    let sat = out
        .solved
        .iter()
        .filter(|s| s.obligation.role == Role::Proof && s.answer.status() == Some(smt::Status::Sat))
        .count();
    assert!(sat > 0);
    let ce = out.counterexample.expect("replayed");
    assert!(ce.summary.contains("planted formula"), "{}", ce.summary);
}

/// Reads an obligation back from its SMT-LIB file (declarations and one-line assertions).
fn parse_back(text: &str) -> (Obligation, String) {
    let logic = if text.contains("(set-logic QF_NRA)") {
        Logic::QfNra
    } else {
        Logic::QfLra
    };
    let status = text
        .lines()
        .find_map(|l| l.strip_prefix("(set-info :status "))
        .and_then(|s| s.strip_suffix(')'))
        .expect("a declared status")
        .to_string();
    let mut ob = Obligation::new("read back", "read back", "read back", Role::Proof, logic);
    for l in text.lines() {
        if let Some(rest) = l.strip_prefix("(declare-const ") {
            let name = rest.strip_suffix(" Real)").expect("real constants only");
            ob.declare(name, Sort::Real);
        } else if let Some(rest) = l.strip_prefix("(assert ") {
            ob.assert(rest.strip_suffix(')').unwrap().to_string());
        } else {
            assert!(
                l.starts_with("(set-") || l == "(check-sat)" || l == "(exit)",
                "non-standard line {l}"
            );
        }
    }
    (ob, status)
}

#[test]
fn the_smtlib_files_parse_back_and_resolve_to_their_status() {
    let dir = tempfile::tempdir().unwrap();
    let mut solved = smt::run(c4::encoding(Scope::Smoke), T).solved;
    solved.extend(smt::run(c4::encoding_printed(Scope::Smoke), T).solved);
    write_files(dir.path(), &solved).unwrap();
    let index = std::fs::read_to_string(dir.path().join("index.tsv")).unwrap();
    assert_eq!(index.lines().count(), solved.len() + 1);
    for line in index.lines().skip(1) {
        let file = line.split('\t').next().unwrap();
        let text = std::fs::read_to_string(dir.path().join(file)).unwrap();
        let (ob, status) = parse_back(&text);
        assert_eq!(solve(&ob, T).name(), status, "{file}");
        assert!(line.ends_with(&format!("\t{status}")), "{line}");
    }
}

/// The printed obligation on `x1 = 0 → 1 → 2` and `0 → 2` (moves c0 0→1, c1 0→2, c2 1→2), by
/// hand. Goal paths: `c1` (S = 2) and `c0 c2` (S = 3). For π* = `c0 c2` the printed `A(u)` of
/// the shorter path `u = c1` divides by `L(u) = c1`, so its case assumes `c1 > 0`; for π* =
/// `c1` the longer path's `L(u) = c0 + c2 > 0`. π*'s own cost is never assumed positive.
/// Optimality: `(L* + M)/S* ≤ (L(u) + M)/S(u)` cross-multiplied; the printed interval:
/// `M ≥ (1 − S(u)/S*)(S(u)L*/(S* L(u)) − 1)` for a shorter `u`, `M ≤` the same for a longer.
#[test]
fn the_printed_obligation_assumes_a_positive_cost_where_it_divides() {
    let shape = Shape {
        n: 3,
        edges: vec![(0, 1), (0, 2), (1, 2)],
    };
    let ob = c4::obligation("C4", &shape, Formula::Printed, Role::Proof).expect("two goal paths");
    let long = "(and (<= (+ c0 c2) c1) (> c1 0.0) (not (= \
(and (<= (* 3.0 (+ (+ c0 c2) M)) (* 3.0 (+ (+ c0 c2) M))) (<= (* 2.0 (+ (+ c0 c2) M)) (* 3.0 (+ c1 M)))) \
(and (< M 0.0) (<= (* (- 1.0 (/ 2.0 3.0)) (- (/ (* 2.0 (+ c0 c2)) (* 3.0 c1)) 1.0)) M)))))";
    let short = "(and (<= c1 (+ c0 c2)) (> (+ c0 c2) 0.0) (not (= \
(and (<= (* 3.0 (+ c1 M)) (* 2.0 (+ (+ c0 c2) M))) (<= (* 2.0 (+ c1 M)) (* 2.0 (+ c1 M)))) \
(and (< M 0.0) (<= M (* (- 1.0 (/ 3.0 2.0)) (- (/ (* 3.0 c1) (* 2.0 (+ c0 c2))) 1.0)))))))";
    let text = ob.smtlib(None);
    let expected = format!("(assert (or {long} {short}))\n");
    assert!(text.contains(&expected), "{expected}not in\n{text}");
    assert!(text.contains("(set-logic QF_NRA)"));
}
