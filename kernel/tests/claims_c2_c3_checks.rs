//! Pins the per-problem checks of claims C2 and C3 (`kernel/src/claims/c2.rs`, `c3.rs`):
//! C2's functionals and its comparison count (the equivalence holds on every problem, so the
//! check finds no failure), C3's goal-avoiding core, goal reachability, the certificate's costs
//! (1 on the lasso from `x1`, `K = ⌊1/((1−α) α^{n−2})⌋ + 1` elsewhere) and the oracle deciding
//! whether a discount-optimal policy avoids the goal.
//!
//! Why: with the kernel's own tests only, nothing pinned these (the claim runners' tests are in
//! `truecost`). Expected values: by hand, and by brute force written here (walks of `|X|`
//! moves for the core, a closure for reachability, every policy evaluated with the normalised
//! `evaluate` for the oracle).

use truecost_kernel::claims::c2;
use truecost_kernel::claims::c3::{
    alphas, certificate, goal_avoiding_core, goal_reachable, optimal_policy_avoids_goal,
};
use truecost_kernel::claims::exact::{Ext, Q};
use truecost_kernel::claims::oracle::{evaluate, policies, trajectory, Functional};
use truecost_kernel::claims::tiny::{Family, FamilySpec, Tiny};

/// Every canonical problem of 2 to `max_states` states, 1–2 moves per non-goal state, 0–1 at
/// the goal (4 states: distinct successors, to keep the scope small).
fn problems(max_states: usize, costs: Vec<u8>) -> Vec<Tiny> {
    (2..=max_states)
        .flat_map(|states| {
            let spec = FamilySpec {
                states,
                initial_fixed: true,
                degree: (1, 2),
                goal_degree: (0, 1),
                costs: costs.clone(),
                distinct_successors: states > 3,
            };
            Family::new(&spec).canonical().collect::<Vec<_>>()
        })
        .collect()
}

#[test]
fn c2_checks_every_functional_from_every_start() {
    let half = Q::new(1, 2);
    assert_eq!(
        c2::functionals(),
        vec![
            Functional::Total,
            Functional::Discounted(half),
            Functional::Discounted(Q::new(9, 10)),
            Functional::Average,
            Functional::HorizonTotal(3),
            Functional::HorizonDiscounted(3, half),
            Functional::HorizonAverage(4),
        ]
    );
    let fs = c2::functionals();
    for t in problems(3, vec![0, 2]) {
        for starts in [1, 2, 9] {
            let (failure, comparisons) = c2::check_problem(&t, &fs, starts);
            assert_eq!(failure, None, "{t:?}");
            assert_eq!(comparisons, (starts.min(t.states()) * fs.len()) as u64);
        }
    }
}

/// States with a walk of `|X|` moves that never enters the goal (then a cycle avoids it).
fn core_by_walks(t: &Tiny) -> Vec<bool> {
    let n = t.states();
    let mut can: Vec<bool> = (0..n).map(|x| !t.is_goal(x)).collect();
    for _ in 0..n {
        can = (0..n)
            .map(|x| !t.is_goal(x) && t.moves(x).iter().any(|m| can[m.to as usize]))
            .collect();
    }
    can
}

fn reachable_from_0(t: &Tiny) -> Vec<bool> {
    let n = t.states();
    let mut seen = vec![false; n];
    seen[0] = true;
    for _ in 0..n {
        for x in 0..n {
            if seen[x] {
                for m in t.moves(x) {
                    seen[m.to as usize] = true;
                }
            }
        }
    }
    seen
}

#[test]
fn c3_core_and_reachability_match_the_brute_force() {
    for t in problems(4, vec![0]) {
        let core = goal_avoiding_core(&t);
        assert_eq!(&core[..t.states()], &core_by_walks(&t)[..], "{t:?}");
        assert!(core[t.states()..].iter().all(|&w| !w));
        assert_eq!(goal_reachable(&t), reachable_from_0(&t)[t.goal()], "{t:?}");
    }
}

#[test]
fn c3_alphas_and_certificate_costs() {
    assert_eq!(alphas(), [Q::new(1, 2), Q::new(9, 10)]);
    // K = ⌊1/((1−α) α^{n−2})⌋ + 1 by hand, for n = 2, 3, 4.
    let k = |alpha: Q, n: usize| -> u8 {
        match (alpha == Q::new(1, 2), n) {
            (true, 2) => 3,   // 1/(1/2) = 2
            (true, 3) => 5,   // 1/(1/4) = 4
            (true, 4) => 9,   // 1/(1/8) = 8
            (false, 2) => 11, // 1/(1/10) = 10
            (false, 3) => 12, // 100/9
            (false, 4) => 13, // 1000/81
            _ => unreachable!(),
        }
    };
    let mut certified = 0;
    for t in problems(4, vec![0]) {
        let core = core_by_walks(&t);
        let hypotheses = core[0] && reachable_from_0(&t)[t.goal()];
        for alpha in alphas() {
            let Some(c) = certificate(&t, alpha) else {
                assert!(!hypotheses, "{t:?} {alpha}");
                continue;
            };
            assert!(hypotheses, "{t:?} {alpha}");
            certified += 1;
            let big = k(alpha, t.states());
            // The lasso from 0: at each state the first move into the core, cost 1.
            let mut lasso = vec![None; t.states()];
            let mut x = 0;
            while lasso[x].is_none() {
                let i = t
                    .moves(x)
                    .iter()
                    .position(|m| core[m.to as usize])
                    .expect("a core state has a move into the core");
                lasso[x] = Some(i);
                x = t.moves(x)[i].to as usize;
            }
            for (y, marked) in lasso.iter().enumerate() {
                assert_eq!(c.moves(y).len(), t.moves(y).len());
                for (i, (m, o)) in c.moves(y).iter().zip(t.moves(y)).enumerate() {
                    assert_eq!(m.to, o.to);
                    let expected = if *marked == Some(i) { 1 } else { big };
                    assert_eq!(m.cost, expected, "{t:?} {alpha} at {y}, move {i}");
                }
            }
            // The claim itself: under these costs a discount-optimal policy avoids the goal.
            assert!(optimal_policy_avoids_goal(&c, alpha), "{t:?} {alpha}");
        }
    }
    assert!(certified > 20, "{certified} certificates");
}

#[test]
fn c3_certificate_needs_k_to_fit_a_byte() {
    // 4 states, α = 1/100: K = ⌊1/((99/100)(1/10000))⌋ + 1 = 10102 does not fit in a u8.
    let t = Tiny::from_lists(&[vec![(1, 0), (3, 0)], vec![(2, 0)], vec![(1, 0)], vec![]]);
    assert!(certificate(&t, Q::new(1, 2)).is_some());
    assert_eq!(certificate(&t, Q::new(1, 100)), None);
    // 3 states, α = 1/100: K = ⌊1/((99/100)(1/100))⌋ + 1 = 102 fits.
    let t = Tiny::from_lists(&[vec![(1, 0), (2, 0)], vec![(1, 0)], vec![]]);
    let c = certificate(&t, Q::new(1, 100)).expect("K = 102 fits");
    assert_eq!(c.moves(0)[1].cost, 102);
    assert_eq!(c.moves(0)[0].cost, 1);
}

/// Whether some discount-optimal policy from 0 avoids the goal on a cycle of positive costs,
/// every policy evaluated with the normalised `evaluate`.
fn avoids_by_brute_force(t: &Tiny, alpha: Q) -> bool {
    let values: Vec<(Q, bool)> = policies(t, false)
        .iter()
        .map(|p| {
            let tr = trajectory(t, p, 0);
            let Ext::Fin(v) = evaluate(&tr, Functional::Discounted(alpha), 1) else {
                panic!("discounted values are finite");
            };
            let avoids = !tr.visits_goal
                && !tr.terminates
                && tr.cycle[..tr.cycle_len].iter().all(|&c| c > 0);
            (v, avoids)
        })
        .collect();
    let Some(best) = values.iter().map(|&(v, _)| v).min() else {
        return false;
    };
    values.iter().any(|&(v, avoids)| v == best && avoids)
}

#[test]
fn c3_oracle_finds_a_goal_avoiding_optimal_policy_exactly_when_one_exists() {
    let (mut yes, mut no) = (0, 0);
    for t in problems(3, vec![0, 2]) {
        for alpha in [Q::new(1, 2), Q::new(9, 10)] {
            let expected = avoids_by_brute_force(&t, alpha);
            assert_eq!(
                optimal_policy_avoids_goal(&t, alpha),
                expected,
                "{t:?} {alpha}"
            );
            if expected {
                yes += 1;
            } else {
                no += 1;
            }
        }
    }
    assert!(yes > 20 && no > 20, "{yes} yes, {no} no");
}

#[test]
fn c3_oracle_counts_a_goal_avoiding_policy_tied_with_an_earlier_optimum() {
    // 0: [→1 (2), →0 (1)], goal 1. At α = 1/2 the first policy (to the goal) costs 2 and the
    // second (the loop) 1/(1 − 1/2) = 2: tied, and the later one avoids the goal.
    let t = Tiny::from_lists(&[vec![(1, 2), (0, 1)], vec![]]);
    assert!(optimal_policy_avoids_goal(&t, Q::new(1, 2)));
    assert!(avoids_by_brute_force(&t, Q::new(1, 2)));
    // At α = 9/10 the loop costs 10 > 2: the optimum reaches the goal.
    assert!(!optimal_policy_avoids_goal(&t, Q::new(9, 10)));
    // The same with the moves swapped: the avoiding policy comes first.
    let t = Tiny::from_lists(&[vec![(0, 1), (1, 2)], vec![]]);
    assert!(optimal_policy_avoids_goal(&t, Q::new(1, 2)));
}
