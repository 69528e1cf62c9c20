//! `truecost discount` on deterministic problems is answered by the parametric policy analysis
//! (`objectives::parametric`, successor chains) and the set of `α` where a discount-optimal
//! policy fails to reach the goal from `x1` is read off its breakpoints
//! (`objectives::failure_set`). Checked here:
//! * against the enumeration of goal paths and lassos (`claims::discount::discount_set`, the
//!   engine claim C3 uses) on every paper problem (both step costs), every deterministic file
//!   in `problems/` and 200 random small problems: the same pieces, compared as algebraic
//!   numbers, with the same closedness;
//! * against brute force (every stationary policy, its discounted cost from every state
//!   written down exactly along its trajectory) at the rational sample of every interval, at
//!   every rational breakpoint and at `k/17`: the least and greatest success from `x1` over
//!   the discount-optimal policies, the reported policy's optimality and the set's membership.

use std::cmp::Ordering;

use truecost::algebra::intervals::{DiscountSet, Point};
use truecost::claims::discount::discount_set;
use truecost::model::{Move, Problem};
use truecost::objectives::parametric::discount_breakpoints;
use truecost::objectives::{failure_set, Model};
use truecost::problems::{GridLayout, StepCost};
use truecost::value::Rational;

fn q(s: &str) -> Rational {
    s.parse().unwrap()
}

/// Whether two sets have the same pieces: ends equal as algebraic numbers, same closedness.
fn same_set(a: &DiscountSet, b: &DiscountSet) -> bool {
    let same_point = |x: &Point, y: &Point| match (x, y) {
        (Point::Zero, Point::Zero) | (Point::One, Point::One) => true,
        (Point::Root(r), Point::Root(s)) => r.compare(s) == Ordering::Equal,
        _ => false,
    };
    a.pieces.len() == b.pieces.len()
        && a.pieces.iter().zip(&b.pieces).all(|(x, y)| {
            same_point(&x.lo, &y.lo)
                && same_point(&x.hi, &y.hi)
                && x.lo_closed == y.lo_closed
                && x.hi_closed == y.hi_closed
        })
}

fn inside(set: &DiscountSet, a: &Rational) -> bool {
    let cmp = |p: &Point| match p {
        Point::Zero => Ordering::Less,
        Point::One => Ordering::Greater,
        Point::Root(r) => r.cmp_rational(a),
    };
    set.pieces.iter().any(|piece| {
        let lo = cmp(&piece.lo);
        let hi = cmp(&piece.hi);
        (lo == Ordering::Less || (lo == Ordering::Equal && piece.lo_closed))
            && (hi == Ordering::Greater || (hi == Ordering::Equal && piece.hi_closed))
    })
}

fn parametric_set(p: &Problem) -> DiscountSet {
    let m = Model::from_deterministic(p, "test".into()).unwrap();
    failure_set(&discount_breakpoints(&m).unwrap())
}

fn text(s: &DiscountSet) -> String {
    truecost::algebra::intervals::set_text(s)
}

#[test]
fn both_engines_agree_on_the_paper_problems() {
    for id in 0..=18 {
        for step in [StepCost::Unit, StepCost::Euclidean] {
            let p = GridLayout::exact(id).unwrap().to_problem(step);
            let old = discount_set(&p, 20_000).unwrap();
            let new = parametric_set(&p);
            assert!(
                same_set(&old, &new),
                "problem {id} {step:?}: enumeration {} vs parametric {}",
                text(&old),
                text(&new)
            );
        }
    }
    // Problem 6 has no path to its goal; the others' unit costs never make a lasso better.
    let six = parametric_set(&GridLayout::exact(6).unwrap().to_problem(StepCost::Unit));
    assert_eq!(text(&six), "(0, 1)");
}

#[test]
fn both_engines_agree_on_the_problem_files() {
    let mut compared = 0;
    for dir in ["problems", "problems/counterexamples"] {
        for entry in std::fs::read_dir(dir).unwrap() {
            let path = entry.unwrap().path();
            if path.extension().is_none_or(|e| e != "json") {
                continue;
            }
            let Ok(truecost::stochastic::file::ProblemFile::Deterministic(p)) =
                truecost::stochastic::file::read(&path)
            else {
                continue;
            };
            let old = discount_set(&p, 20_000).unwrap();
            let new = parametric_set(&p);
            assert!(
                same_set(&old, &new),
                "{}: enumeration {} vs parametric {}",
                path.display(),
                text(&old),
                text(&new)
            );
            compared += 1;
        }
    }
    assert!(compared >= 5, "{compared} deterministic files");
    // The worked example (docs/spec.md §6): (0, α*] with α* the root of 5α⁴ − α³ − α² − α − 1
    // (0.91635458253384933778…, by hand from the lasso 0 ↺ (cost 1 forever) against the
    // path 0 → 1 → … → 5 costing 1 + 2α + 3α² + 4α³ + 5α⁴).
    let p = truecost::model::file::read(std::path::Path::new("problems/discount-example.json"))
        .unwrap();
    let s = parametric_set(&p);
    assert_eq!(s.pieces.len(), 1);
    assert!(!s.pieces[0].lo_closed && s.pieces[0].hi_closed);
    let dec = |t: &str| truecost::value::parse_rational(t).unwrap();
    assert!(inside(&s, &dec("0.9163545825")) && !inside(&s, &dec("0.9163545826")));
}

/// A small deterministic random number generator (splitmix64), seeded.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
}

/// A random problem: 2 to 5 states, `x1 = 0`, the last state a goal (sometimes another one,
/// sometimes with moves of its own), 0 to 3 moves per state (0: a dead end, rarely), costs
/// among 0, 1/2, 1, 2, 3, 5/2.
fn random_problem(rng: &mut Rng) -> Problem {
    let n = 2 + rng.below(4);
    let costs = ["0", "1/2", "1", "2", "3", "5/2"];
    let mut goals = vec![n - 1];
    if n > 2 && rng.below(5) == 0 {
        goals.push(1 + rng.below(n - 2));
    }
    let moves = (0..n)
        .map(|_| {
            let k = if rng.below(12) == 0 {
                0
            } else {
                1 + rng.below(3)
            };
            (0..k)
                .map(|_| Move {
                    successor: rng.below(n),
                    cost: q(costs[rng.below(costs.len())]),
                })
                .collect()
        })
        .collect();
    Problem::new(moves, 0, goals).unwrap()
}

/// Brute force at `α`: per stationary policy (a move index per non-goal state with moves), its
/// discounted cost from every state (`None`: the trajectory enters a dead end, `+∞`) and
/// whether its trajectory from `x1` reaches a goal.
struct Brute {
    /// Per policy: values per state, success from x1.
    policies: Vec<(Vec<usize>, Vec<Option<Rational>>, bool)>,
    best: Vec<Option<Rational>>,
}

fn trajectory_value(
    p: &Problem,
    choice: &[usize],
    x: usize,
    a: &Rational,
) -> (Option<Rational>, bool) {
    let mut pos = vec![usize::MAX; p.states()];
    let mut costs: Vec<Rational> = Vec::new();
    let mut y = x;
    loop {
        if p.is_goal(y) {
            let mut v = Rational::from_integer(0.into());
            for c in costs.iter().rev() {
                v = c + a * v;
            }
            return (Some(v), true);
        }
        if p.moves(y).is_empty() {
            return (None, false);
        }
        if pos[y] != usize::MAX {
            // Cycle from position s: V = Σ_{i<s} α^i c_i + α^s (Σ_j α^j c_{s+j}) / (1 − α^k).
            let s = pos[y];
            let k = costs.len() - s;
            let mut cycle = Rational::from_integer(0.into());
            for c in costs[s..].iter().rev() {
                cycle = c + a * cycle;
            }
            let mut ak = Rational::from_integer(1.into());
            for _ in 0..k {
                ak *= a;
            }
            let mut v = cycle / (Rational::from_integer(1.into()) - ak);
            for c in costs[..s].iter().rev() {
                v = c + a * v;
            }
            return (Some(v), false);
        }
        pos[y] = costs.len();
        let m = &p.moves(y)[choice[y]];
        costs.push(m.cost.clone());
        y = m.successor;
    }
}

fn brute(p: &Problem, a: &Rational) -> Brute {
    let n = p.states();
    let free: Vec<usize> = (0..n)
        .filter(|&x| !p.is_goal(x) && !p.moves(x).is_empty())
        .collect();
    let mut choice = vec![0usize; n];
    let mut policies = Vec::new();
    loop {
        let mut values = Vec::with_capacity(n);
        let mut success = false;
        for x in 0..n {
            let (v, s) = trajectory_value(p, &choice, x, a);
            if x == p.initial() {
                success = s;
            }
            values.push(v);
        }
        policies.push((choice.clone(), values, success));
        // Next choice vector (odometer over the free states).
        let mut i = 0;
        while i < free.len() {
            let x = free[i];
            choice[x] += 1;
            if choice[x] < p.moves(x).len() {
                break;
            }
            choice[x] = 0;
            i += 1;
        }
        if i == free.len() {
            break;
        }
    }
    let best = (0..n)
        .map(|x| policies.iter().filter_map(|(_, v, _)| v[x].clone()).min())
        .collect();
    Brute { policies, best }
}

impl Brute {
    /// Whether a policy is discount-optimal: its value equals the optimum at every state with
    /// a finite optimum.
    fn optimal(&self, values: &[Option<Rational>]) -> bool {
        self.best
            .iter()
            .zip(values)
            .all(|(b, v)| b.is_none() || b == v)
    }

    /// (some optimal policy fails from x1, some optimal policy reaches the goal from x1).
    fn outcomes(&self) -> (bool, bool) {
        let optimal = self.policies.iter().filter(|(_, v, _)| self.optimal(v));
        let (mut fails, mut succeeds) = (false, false);
        for (_, _, s) in optimal {
            fails |= !s;
            succeeds |= *s;
        }
        (fails, succeeds)
    }
}

/// Checks the analysis of `p` against brute force at the sample of every interval, at every
/// rational breakpoint and at `k/17`.
fn check_against_brute_force(p: &Problem, label: &str) {
    let m = Model::from_deterministic(p, label.into()).unwrap();
    let d = discount_breakpoints(&m).unwrap();
    let set = failure_set(&d);
    let one = Rational::from_integer(1.into());
    let zero = Rational::from_integer(0.into());
    // x1 with no finite value (only dead ends ahead, no goal path): every policy fails.
    if brute(p, &q("1/2")).best[p.initial()].is_none() {
        assert_eq!(text(&set), "(0, 1)", "{label}");
        return;
    }
    let check_at = |a: &Rational, success: Option<&truecost::objectives::Bounds>, what: &str| {
        let b = brute(p, a);
        let (fails, succeeds) = b.outcomes();
        assert_eq!(
            inside(&set, a),
            fails,
            "{label}: membership at {a} ({what})"
        );
        if let Some(s) = success {
            assert_eq!(s.min < one, fails, "{label}: least success at {a} ({what})");
            assert_eq!(
                s.max == one,
                succeeds,
                "{label}: greatest success at {a} ({what})"
            );
            assert!(
                s.min == zero || s.min == one,
                "{label}: deterministic success"
            );
        }
    };
    for interval in &d.intervals {
        check_at(
            &interval.sample,
            Some(&interval.achievement.success),
            "sample",
        );
        // The reported policy is discount-optimal at the sample.
        let b = brute(p, &interval.sample);
        // Indices in U(x) of the model: the model keeps the moves not into dead ends, in order.
        let pruned: Vec<Vec<usize>> = (0..p.states())
            .map(|x| {
                (0..p.moves(x).len())
                    .filter(|&i| {
                        let y = p.moves(x)[i].successor;
                        b.best[y].is_some() || p.is_goal(y)
                    })
                    .collect()
            })
            .collect();
        let original: Vec<usize> = (0..p.states())
            .map(|x| match interval.policy[x] {
                Some(i) => pruned[x][i],
                None => 0,
            })
            .collect();
        for x in 0..p.states() {
            if interval.policy[x].is_some() {
                let (v, _) = trajectory_value(p, &original, x, &interval.sample);
                assert_eq!(
                    v, b.best[x],
                    "{label}: the reported policy at state {x}, alpha {}",
                    interval.sample
                );
            }
        }
    }
    for bp in &d.breakpoints {
        if let Some(r) = bp.at.as_rational() {
            check_at(r, Some(&bp.achievement.success), "breakpoint");
        }
    }
    for k in 1..17 {
        let a = Rational::new(k.into(), 17.into());
        check_at(&a, None, "k/17");
    }
}

#[test]
fn both_engines_agree_on_200_random_small_problems_and_with_brute_force() {
    let mut rng = Rng(0x5EED_2026);
    let (mut nonempty, mut breakpoints) = (0, 0);
    for i in 0..200 {
        let p = random_problem(&mut rng);
        let label = format!(
            "random problem {i}: {:?}",
            (0..p.states())
                .map(|x| p
                    .moves(x)
                    .iter()
                    .map(|m| (m.successor, m.cost.to_string()))
                    .collect::<Vec<_>>())
                .collect::<Vec<_>>()
        );
        let old = discount_set(&p, 20_000).unwrap();
        let new = parametric_set(&p);
        assert!(
            same_set(&old, &new),
            "{label}: enumeration {} vs parametric {}",
            text(&old),
            text(&new)
        );
        check_against_brute_force(&p, &label);
        nonempty += usize::from(!new.pieces.is_empty());
        let m = Model::from_deterministic(&p, "count".into()).unwrap();
        breakpoints += discount_breakpoints(&m).unwrap().breakpoints.len();
    }
    // The sample is not degenerate: many non-empty sets and breakpoints.
    assert!(nonempty >= 40, "{nonempty} non-empty sets");
    assert!(breakpoints >= 40, "{breakpoints} breakpoints");
}

#[test]
fn the_worked_example_against_brute_force() {
    let p = truecost::model::file::read(std::path::Path::new("problems/discount-example.json"))
        .unwrap();
    check_against_brute_force(&p, "discount-example");
}

/// A dead end is never entered by a discount-optimal policy: 0 → 1 (cost 0, a dead end) or
/// 0 → 2 (goal, cost 5) or 0 ↺ (cost 1). Without the dead end the lasso is better iff
/// `1/(1 − α) ≤ 5`, i.e. `α ≤ 4/5` (by hand).
#[test]
fn dead_ends_are_never_optimal() {
    let mv = |successor: usize, cost: &str| Move {
        successor,
        cost: q(cost),
    };
    let p = Problem::new(
        vec![vec![mv(1, "0"), mv(2, "5"), mv(0, "1")], vec![], vec![]],
        0,
        vec![2],
    )
    .unwrap();
    let s = parametric_set(&p);
    assert_eq!(text(&s), "(0, 4/5]");
    assert!(same_set(&s, &discount_set(&p, 100).unwrap()));
}

fn mv(successor: usize, cost: &str) -> Move {
    Move {
        successor,
        cost: q(cost),
    }
}

/// A piece closed on the left and open at 1: from 0 the path 0 → 1 → 2 → goal costs
/// `0 + 0·α + 3α²`, the lasso 0 → 3 ↺ costs `1 + 0` (by hand). The lasso is at least as good
/// iff `3α² ≥ 1`: the set is `[1/√3, 1)`, with `1/√3 = 0.57735026918962576450…`.
#[test]
fn a_piece_starting_at_an_irrational_breakpoint() {
    let p = Problem::new(
        vec![
            vec![mv(1, "0"), mv(3, "1")],
            vec![mv(2, "0")],
            vec![mv(4, "3")],
            vec![mv(3, "0")],
            vec![],
        ],
        0,
        vec![4],
    )
    .unwrap();
    let s = parametric_set(&p);
    assert!(
        same_set(&s, &discount_set(&p, 100).unwrap()),
        "{}",
        text(&s)
    );
    assert_eq!(s.pieces.len(), 1);
    assert!(s.pieces[0].lo_closed && !s.pieces[0].hi_closed);
    assert_eq!(s.pieces[0].hi, Point::One);
    let dec = |t: &str| truecost::value::parse_rational(t).unwrap();
    assert!(!inside(&s, &dec("0.5773502691")) && inside(&s, &dec("0.5773502692")));
    assert!(
        text(&s).starts_with("[0.57735026918962576450"),
        "{}",
        text(&s)
    );
    check_against_brute_force(&p, "left-closed piece");
}

/// A single point: the path 0 → 1 → goal costs `0 + α`, the lasso 0 → 2 → 3 → 4 ↺ costs
/// `1/4 + 0·α + α² + 0`; the lasso is at least as good iff `1/4 + α² ≤ α`, i.e.
/// `(α − 1/2)² ≤ 0` (by hand), so it is optimal at `α = 1/2` only, where both tie: the set is
/// `{1/2}` although neither neighbouring interval belongs to it.
#[test]
fn a_tie_at_a_single_point() {
    let p = Problem::new(
        vec![
            vec![mv(1, "0"), mv(2, "1/4")],
            vec![mv(5, "1")],
            vec![mv(3, "0")],
            vec![mv(4, "1")],
            vec![mv(4, "0")],
            vec![],
        ],
        0,
        vec![5],
    )
    .unwrap();
    let s = parametric_set(&p);
    assert_eq!(text(&s), "{1/2}");
    assert!(same_set(&s, &discount_set(&p, 100).unwrap()));
    check_against_brute_force(&p, "single point");
}
