//! The SMT encoding of C2: a hand-checked structure's obligations, the trust checks,
//! a mutation test (a planted wrong reward makes the proof fail, and the model replays), and
//! the SMT-LIB files parsing back to the same answers. Smoke scope only.

mod common;

use common::smt::{assert_files_parse_back, assert_refuted};
use truecost::claims::smt::c2::{self, lassos, Plant};
use truecost::claims::smt::{run, solve, Answer, Obligation, Replay, Role, SmtVerdict, TIMEOUT_MS};
use truecost::claims::tiny::Tiny;
use truecost::claims::Scope;

/// The structure `0: ->0, ->1; 1 (goal)`: x1 may loop forever (cost l1 per stage) or move to
/// the goal (cost l2) and terminate.
const LOOP_OR_GOAL: &str = "0: ->0 (l1), ->1 (l2); 1 (goal)";

/// The obligation of `structure` with `role` whose lemma contains `lemma`.
fn find<'a>(
    obligations: &'a [Obligation],
    structure: &str,
    role: &Role,
    lemma: &str,
) -> &'a Obligation {
    obligations
        .iter()
        .find(|o| o.structure == structure && &o.role == role && o.lemma.contains(lemma))
        .unwrap_or_else(|| panic!("no {role:?} obligation '{lemma}' for {structure}"))
}

#[test]
fn hand_checked_structure() {
    let t = Tiny::from_lists(&[vec![(0, 0), (1, 0)], vec![]]);
    // Two classes of stationary policies from x1: loop forever, or go to the goal and stop.
    let ls = lassos(&t, true);
    assert_eq!(ls.len(), 2);
    assert_eq!((ls[0].prefix.len(), ls[0].cycle.len()), (0, 1));
    assert!(ls[1].terminates && ls[1].prefix.len() == 1);

    let enc = c2::encoding(Scope::Smoke);
    let hyp = find(
        &enc.obligations,
        LOOP_OR_GOAL,
        &Role::Hypotheses,
        "every functional",
    );
    let expected = "(set-info :smt-lib-version 2.6)\n(set-logic QF_LRA)\n\
(set-info :source |truecost 0.1.0: C2 / argmin cost = argmax reward (r = -l), every functional / \
0: ->0 (l1), ->1 (l2); 1 (goal) / hypotheses satisfiable|)\n\
(declare-const l1 Real)\n(declare-const l2 Real)\n(assert (>= l1 0.0))\n(assert (>= l2 0.0))\n(check-sat)\n(exit)\n";
    assert_eq!(hyp.smtlib(None), expected);

    let proof = find(
        &enc.obligations,
        LOOP_OR_GOAL,
        &Role::Proof,
        "every functional",
    );
    let text = proof.smtlib(None);
    // Values derived by hand from the lassos. Total: looping is +inf iff l1 > 0, the goal
    // lasso costs l2. Discounted (1/2): looping costs l1/(1 - 1/2) = 2 l1, its reward is the
    // same sum over the negated stages; the goal lasso costs l2 + (1/2)·0/(1 − 1/2).
    for fragment in [
        "(c0_0_pinf (> l1 0.0))",
        "(c0_1 l2)",
        "(r0_0_ninf (< (- l1) 0.0))",
        "(c1_0 (* 2.0 l1))",
        "(r1_0 (* 2.0 (- l1)))",
        "(c1_1 (+ (* 1.0 l2) (* 1.0 0.0)))",
        // Average: the loop's cycle mean l1; the terminated lasso stays at cost 0.
        "(c3_0 (* 1.0 l1))",
        "(c3_1 (* 1.0 0.0))",
    ] {
        assert!(text.contains(fragment), "{fragment} not in\n{text}");
    }
    assert_eq!(solve(proof, TIMEOUT_MS), Answer::Unsat);
    assert!(matches!(solve(hyp, TIMEOUT_MS), Answer::Sat(Some(_))));

    // Discounted for every real α: the loop costs l1/(1 − α) = N/D with N = D·0 + l1, the goal
    // lasso l2/1; the reward's numerators have the negated stages.
    let every_alpha = find(&enc.obligations, LOOP_OR_GOAL, &Role::Proof, "every alpha");
    let text = every_alpha.smtlib(None);
    assert!(text.contains("(set-logic QF_NRA)"));
    for fragment in [
        "(assert (and (> a 0.0) (< a 1.0)))",
        "(c0_n (+ (* (- 1.0 (* 1.0 a)) 0.0) l1))",
        "(c0_d (- 1.0 (* 1.0 a)))",
        "(c1_n l2)",
        "(c1_d 1.0)",
        "(r0_n (+ (* (- 1.0 (* 1.0 a)) 0.0) (- l1)))",
        "(r1_n (- l2))",
    ] {
        assert!(text.contains(fragment), "{fragment} not in\n{text}");
    }
    assert_eq!(solve(every_alpha, TIMEOUT_MS), Answer::Unsat);
}

#[test]
fn trust_checks_answer_as_required_and_replay() {
    let enc = c2::encoding(Scope::Smoke);
    let replay = enc.replay;
    let dropped = enc
        .obligations
        .iter()
        .filter(|o| matches!(o.role, Role::Dropped(_)))
        .count();
    // Every 1–2-state structure with at least two lassos, and the sup-of-stages check.
    assert!(dropped >= 10, "{dropped}");
    let out = run(enc, TIMEOUT_MS);
    assert_eq!(out.verdict, SmtVerdict::Proved, "{:?}", out.notes);
    assert_eq!(out.summary.proofs, out.summary.proofs_unsat);
    assert_eq!(out.summary.trust_checks, out.summary.trust_ok);
    assert_eq!(out.summary.unknown, 0);
    let mut replayed = 0;
    for s in &out.solved {
        if let Role::Dropped(_) = s.obligation.role {
            let Answer::Sat(Some(m)) = &s.answer else {
                panic!("{:?}: {:?}", s.obligation.structure, s.answer)
            };
            assert!(matches!(
                replay(&s.obligation, m),
                Replay::Confirmed(_, None)
            ));
            replayed += 1;
        }
    }
    assert_eq!(replayed, dropped);
}

#[test]
fn planted_wrong_reward_breaks_the_proof() {
    for plant in [Plant::RewardNotNegated, Plant::MaxOfStages] {
        assert_refuted(c2::encoding_with(Scope::Smoke, plant));
    }
}

#[test]
fn files_parse_back_to_the_same_answers() {
    let enc = c2::encoding(Scope::Smoke);
    let obligations: Vec<Obligation> = enc.obligations.into_iter().step_by(3).collect();
    let solved = truecost::claims::smt::discharge(obligations, TIMEOUT_MS);
    assert_files_parse_back(&solved, &["QF_LRA", "QF_LIRA", "QF_NRA"]);
}

/// `Lasso::stage` by hand: a prefix of one move, then a cycle of three repeated for ever, so
/// stage `k ≥ 1` is the cycle's move `(k − 1) mod 3` (a cycle whose length divides twice the
/// prefix would not tell `k − 1` from `k + 1`); a terminating lasso's stages after its prefix
/// are the termination stage.
#[test]
fn lasso_stages_by_hand() {
    let l = c2::Lasso {
        prefix: vec![(0, 0)],
        cycle: vec![(1, 0), (2, 0), (3, 0)],
        terminates: false,
        visits_goal: false,
    };
    let stages: Vec<Option<c2::MoveId>> = (0..8).map(|k| l.stage(k)).collect();
    let (a, b, c) = (Some((1, 0)), Some((2, 0)), Some((3, 0)));
    assert_eq!(stages, [Some((0, 0)), a, b, c, a, b, c, a]);
    let ends = c2::Lasso {
        prefix: vec![(0, 1), (1, 1)],
        cycle: vec![],
        terminates: true,
        visits_goal: true,
    };
    let stages: Vec<Option<c2::MoveId>> = (0..4).map(|k| ends.stage(k)).collect();
    assert_eq!(stages, [Some((0, 1)), Some((1, 1)), None, None]);
}

/// The every-α obligation's replay reads `α` back and asks the oracle at that `α`: a model
/// of the loop-or-goal structure at `α = 1/2` (where C2 holds) is answered by the oracle, not
/// refused; an `α` whose denominator reaches 2^20 is refused as not fitting the oracle.
#[test]
fn the_every_alpha_replay_asks_the_oracle_at_the_models_alpha() {
    use truecost::claims::smt::Model;
    use truecost::value::Rational;
    let enc = c2::encoding(Scope::Smoke);
    let every_alpha = find(&enc.obligations, LOOP_OR_GOAL, &Role::Proof, "every alpha");
    let model = |a: Rational| Model {
        values: vec![
            ("l1".into(), Rational::from_integer(1.into())),
            ("l2".into(), Rational::from_integer(3.into())),
            ("a".into(), a),
        ],
    };
    let half = Rational::new(1.into(), 2.into());
    match (enc.replay)(every_alpha, &model(half)) {
        Replay::NotConfirmed(why) => assert!(
            why.contains("the oracle finds argmin cost = argmax reward at alpha = 1/2"),
            "{why}"
        ),
        other => panic!("{other:?}"),
    }
    let fine = Rational::new(1.into(), (1i64 << 20).into());
    match (enc.replay)(every_alpha, &model(fine)) {
        Replay::NotConfirmed(why) => assert_eq!(why, "alpha does not fit the oracle"),
        other => panic!("{other:?}"),
    }
    let just_fits = Rational::new(1.into(), ((1i64 << 20) - 1).into());
    match (enc.replay)(every_alpha, &model(just_fits)) {
        Replay::NotConfirmed(why) => assert!(why.contains("the oracle finds"), "{why}"),
        other => panic!("{other:?}"),
    }
}
