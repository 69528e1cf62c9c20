//! The SMT encodings of C3-example and C3: hand-checked obligations, the trust
//! checks, mutation tests (a planted wrong threshold or interval makes the proof fail, and the
//! model replays), and the SMT-LIB files parsing back to the same answers. Smoke scope only.

mod common;

use common::smt::{assert_files_parse_back, assert_refuted};
use truecost::claims::exact::Q;
use truecost::claims::smt::c2::lassos;
use truecost::claims::smt::c3::{self, THRESHOLD};
use truecost::claims::smt::{
    discharge, run, solve, Answer, Encoding, Replay, Role, SmtVerdict, Status, TIMEOUT_MS,
};
use truecost::claims::tiny::Tiny;
use truecost::claims::Scope;
use truecost::value::Rational;

fn q(n: i64, d: i64) -> Rational {
    Rational::new(n.into(), d.into())
}

#[test]
fn the_threshold_is_the_oracles_polynomial() {
    // The claim's 5α⁴ − α³ − α² − α − 1, against the exact oracle's polynomial derived from the
    // printed inequality.
    let p = truecost::claims::alpha::printed_polynomial().primitive();
    let c: Vec<Rational> = THRESHOLD.iter().map(|&c| q(c, 1)).collect();
    assert_eq!(p.coefficients(), &c[..]);
}

#[test]
fn worked_example_lassos_by_hand() {
    // From 0 a stationary policy loops at 0 (down), turns back at 1..4 (a 2-cycle m-1 <-> m),
    // or reaches 5 and then terminates, loops at 5, or cycles 5 <-> 4: 1 + 4 + 3 lassos.
    let ls = lassos(&truecost::claims::alpha::worked_example(), true);
    assert_eq!(ls.len(), 8);
    assert_eq!(ls.iter().filter(|l| l.visits_goal).count(), 3);
    assert_eq!(ls.iter().filter(|l| l.terminates).count(), 1);
}

#[test]
fn printed_inequality_obligation_text() {
    let enc = c3::example_encoding(Scope::Smoke);
    let o = enc
        .obligations
        .iter()
        .find(|o| o.lemma.starts_with("printed"))
        .expect("the printed-inequality obligation");
    let expected = "(set-info :smt-lib-version 2.6)\n(set-logic QF_NRA)\n\
(set-info :source |truecost 0.1.0: C3-example / printed 1/(1-alpha) < sum i alpha^(i-1) iff threshold < 0 / none / proof|)\n\
(set-info :status unsat)\n\
(declare-const a Real)\n(declare-const L Real)\n\
(declare-const p0 Real)\n(declare-const p1 Real)\n(declare-const p2 Real)\n(declare-const p3 Real)\n(declare-const p4 Real)\n\
(assert (and (> a 0.0) (< a 1.0)))\n\
(assert (= (* L (- 1.0 a)) 1.0))\n\
(assert (= p0 (- 1.0)))\n(assert (= p1 (- 1.0)))\n(assert (= p2 (- 1.0)))\n(assert (= p3 (- 1.0)))\n(assert (= p4 5.0))\n\
(assert (not (= (< L (+ 1.0 (* 2.0 a) (* 3.0 a a) (* 4.0 a a a) (* 5.0 a a a a))) \
(< (+ p0 (* p1 a) (* p2 a a) (* p3 a a a) (* p4 a a a a)) 0.0))))\n\
(check-sat)\n(exit)\n";
    assert_eq!(o.smtlib(Some(Status::Unsat)), expected);
    assert_eq!(solve(o, TIMEOUT_MS), Answer::Unsat);
}

#[test]
fn certificate_of_the_two_state_structure_by_hand() {
    // x1 loops (0 -> 0) or moves to the goal 1. The certificate at 9/10 puts cost 1 on the
    // loop and K = floor(1/(1 - 9/10)) + 1 = 11 on the goal move (at 1/2: K = 3; the larger
    // wins). The loop costs 1/(1-α), the goal path 11: the loop is strictly better iff
    // 11(1 − α) > 1, i.e. α < 10/11, which holds on [1/2, 9/10].
    let t = Tiny::from_lists(&[vec![(0, 0), (1, 0)], vec![]]);
    let c = c3::interval_certificate(&t, c3::interval()).expect("the hypotheses hold");
    assert_eq!(c.describe(), "0: ->0 (1), ->1 (11); 1 (goal)");
    let enc = c3::encoding(Scope::Smoke);
    let of = |role: &Role| {
        enc.obligations
            .iter()
            .find(|o| o.structure == "0: ->0 (1), ->1 (11); 1 (goal)" && &o.role == role)
            .expect("an obligation")
    };
    let proof = of(&Role::Proof);
    assert_eq!(
        proof.asserts,
        vec![
            "(and (> a 0.0) (< a 1.0))".to_string(),
            "(>= a (/ 1.0 2.0))".into(),
            "(<= a (/ 9.0 10.0))".into(),
            "(<= (* 11.0 (+ 1.0 (* (- 1.0) a))) (* 1.0 1.0))".into(),
        ]
    );
    assert_eq!(solve(proof, TIMEOUT_MS), Answer::Unsat);
    // Without α ≤ 9/10 the goal path wins for α ≥ 10/11.
    let dropped = of(&Role::Dropped("alpha <= 9/10".into()));
    match solve(dropped, TIMEOUT_MS) {
        Answer::Sat(Some(m)) => {
            assert!(*m.get("a").unwrap() >= q(10, 11) && *m.get("a").unwrap() < q(1, 1));
            assert!(matches!(
                (enc.replay)(dropped, &m),
                Replay::Confirmed(_, None)
            ));
        }
        other => panic!("{other:?}"),
    }
}

fn assert_trust(enc: Encoding) {
    let replay = enc.replay;
    let out = run(enc, TIMEOUT_MS);
    assert_eq!(out.verdict, SmtVerdict::Proved, "{:?}", out.notes);
    assert_eq!(out.summary.trust_checks, out.summary.trust_ok);
    assert!(out.summary.trust_checks >= 5);
    for s in &out.solved {
        if let Role::Dropped(_) = s.obligation.role {
            let Answer::Sat(Some(m)) = &s.answer else {
                panic!("{}: {:?}", s.obligation.structure, s.answer)
            };
            assert!(matches!(
                replay(&s.obligation, m),
                Replay::Confirmed(_, None)
            ));
        }
    }
}

#[test]
fn example_trust_checks() {
    assert_trust(c3::example_encoding(Scope::Smoke));
}

#[test]
fn certificate_trust_checks() {
    assert_trust(c3::encoding(Scope::Smoke));
}

#[test]
fn planted_wrong_threshold_breaks_the_example_proof() {
    // 10α − 9: its root 9/10 lies below α* ≈ 0.916.
    assert_refuted(c3::example_encoding_with(&[q(-9, 1), q(10, 1)]));
}

#[test]
fn planted_wrong_interval_breaks_the_certificate_proof() {
    // Up to 99/100 the goal path of cost 11 beats the loop's 1/(1 − α) = 100.
    assert_refuted(c3::encoding_with(
        Scope::Smoke,
        (Q::new(1, 2), Q::new(99, 100)),
    ));
}

#[test]
fn files_parse_back_to_the_same_answers() {
    let mut obligations = c3::example_encoding(Scope::Smoke).obligations;
    obligations.extend(
        c3::encoding(Scope::Smoke)
            .obligations
            .into_iter()
            .step_by(3),
    );
    let solved = discharge(obligations, TIMEOUT_MS);
    assert_files_parse_back(&solved, &["QF_NRA"]);
}

/// The C3-example replay refuses a model whose `α` is outside `(0, 1)` (at either end, or
/// beyond it) before asking the oracle, and answers one inside it.
#[test]
fn the_example_replay_refuses_an_alpha_outside_the_unit_interval() {
    use truecost::claims::smt::Model;
    const BELOW: &str = "threshold < 0: every discount-optimal policy from 0 avoids the goal";
    let enc = c3::example_encoding(Scope::Smoke);
    let o = enc
        .obligations
        .iter()
        .find(|o| o.lemma == BELOW)
        .expect("the below-threshold obligation");
    let model = |a: Rational| Model {
        values: vec![("a".into(), a)],
    };
    for (a, text) in [
        (q(3, 2), "3/2"),
        (q(-1, 2), "-1/2"),
        (q(1, 1), "1"),
        (q(0, 1), "0"),
    ] {
        match c3::example_replay(o, &model(a)) {
            Replay::NotConfirmed(why) => {
                assert_eq!(why, format!("alpha = {text} is not in (0,1)"))
            }
            other => panic!("alpha = {text}: {other:?}"),
        }
    }
    // Inside: with no threshold coefficients in the model the polynomial is 0, so "below"
    // (threshold < 0) is not met: the exact solve is asked and does not confirm.
    match c3::example_replay(o, &model(q(1, 2))) {
        Replay::NotConfirmed(why) => assert_eq!(
            why,
            format!("the exact solve at alpha = 1/2 does not confirm the failure of '{BELOW}'")
        ),
        other => panic!("{other:?}"),
    }
}
