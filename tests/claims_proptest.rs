//! Engine 2 under `cargo test`: the proptest properties of `truecost::claims::sampled`, with
//! failure persistence in committed regression files (`tests/regressions/`). Refuted claims
//! must fail and shrink to a small counterexample; the corrected ones must hold.

use truecost::claims::sampled;

const CASES: u32 = 256;

#[test]
fn c1_as_printed_fails_and_shrinks_to_a_lone_goal() {
    let r = sampled::c1_printed(CASES, Some("tests/regressions/c1.txt"));
    let (t, _) = r.counterexample.expect("C1 as printed is refuted");
    // The smallest possible problem: one state, the goal.
    assert_eq!(t.states(), 1);
}

#[test]
fn c1_corrected_holds() {
    let r = sampled::c1_corrected(CASES, Some("tests/regressions/c1-corrected.txt"));
    assert!(r.counterexample.is_none(), "{:?}", r.counterexample);
    assert!(r.relevant > 0);
}

#[test]
fn c2_holds() {
    let r = sampled::c2(CASES, Some("tests/regressions/c2.txt"));
    assert!(r.counterexample.is_none(), "{:?}", r.counterexample);
}

#[test]
fn c3_certificates_exist() {
    let r = sampled::c3(CASES, Some("tests/regressions/c3.txt"));
    assert!(r.counterexample.is_none(), "{:?}", r.counterexample);
    assert!(r.relevant > 0);
}

#[test]
fn c4_as_printed_fails_and_shrinks() {
    let r = sampled::c4(true, CASES, Some("tests/regressions/c4.txt"));
    let (t, msg) = r.counterexample.expect("C4 as printed is refuted");
    // A disagreement needs two goal paths of different lengths: at least 3 states.
    assert!(
        t.states() >= 3 && t.states() <= 4,
        "{msg}: {}",
        t.describe()
    );
}

#[test]
fn c4_corrected_holds() {
    let r = sampled::c4(false, CASES, Some("tests/regressions/c4-corrected.txt"));
    assert!(r.counterexample.is_none(), "{:?}", r.counterexample);
}

mod discount_cross_check {
    use num_bigint::BigInt;
    use proptest::prelude::*;
    use truecost::algebra::intervals::Point;
    use truecost::claims::alpha::optimal_policies_from_initial;
    use truecost::claims::discount::discount_set;
    use truecost::claims::sampled::tiny_strategy;
    use truecost::value::Rational;

    fn inside(set: &truecost::algebra::intervals::DiscountSet, a: &Rational) -> bool {
        let cmp = |p: &Point| match p {
            Point::Zero => std::cmp::Ordering::Less,
            Point::One => std::cmp::Ordering::Greater,
            Point::Root(r) => r.cmp_rational(a),
        };
        set.pieces.iter().any(|piece| {
            let lo = cmp(&piece.lo);
            let hi = cmp(&piece.hi);
            (lo == std::cmp::Ordering::Less || (lo == std::cmp::Ordering::Equal && piece.lo_closed))
                && (hi == std::cmp::Ordering::Greater
                    || (hi == std::cmp::Ordering::Equal && piece.hi_closed))
        })
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 256, failure_persistence: None, ..ProptestConfig::default() })]
        /// `truecost discount` agrees with the exact solve (every stationary policy) at rational
        /// discount factors `k/40`: a discount-optimal policy from x1 avoids the goal iff `α` is
        /// in the computed set (ties at rational breakpoints count as "a policy avoids").
        #[test]
        fn discount_set_agrees_with_exact_solves(t in tiny_strategy(4, 2, 0, 4)) {
            let problem = t.to_problem();
            let set = discount_set(&problem, 10_000).unwrap();
            for k in 1..40 {
                let a = Rational::new(BigInt::from(k), BigInt::from(40));
                let (all_avoid, all_reach) = optimal_policies_from_initial(&t, &a);
                let member = inside(&set, &a);
                if all_avoid && t.states() > 1 {
                    prop_assert!(member, "alpha = {k}/40: {}", t.describe());
                }
                if all_reach {
                    prop_assert!(!member, "alpha = {k}/40: {}", t.describe());
                }
            }
        }
    }
}

/// The engine runs exactly the number of cases it is given (proptest's own default is also
/// 256, so the count above cannot tell), and reports that number.
#[test]
fn the_engine_runs_the_cases_it_is_given() {
    for cases in [1, 37, 300] {
        let r = sampled::c2(cases, None);
        assert!(r.counterexample.is_none(), "{:?}", r.counterexample);
        assert_eq!(r.cases, u64::from(cases));
        assert!(r.scope.starts_with(&format!("{cases} ")), "{}", r.scope);
    }
}

/// A failure's seed is persisted to the file the engine is given (and nowhere else), in
/// proptest's `cc <seed>` format, so the committed regression files replay it first.
#[test]
fn a_failure_is_persisted_to_the_given_file() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("c1.txt");
    let leaked: &'static str = Box::leak(path.to_str().unwrap().to_owned().into_boxed_str());
    let r = sampled::c1_printed(CASES, Some(leaked));
    assert!(r.counterexample.is_some());
    let text = std::fs::read_to_string(&path).expect("the seed file is written");
    assert!(text.lines().any(|l| l.starts_with("cc ")), "{text}");
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
}
