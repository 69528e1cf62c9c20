//! C4's exact bonus analysis on small instances (`claims::c4::{Instance, bonus_analysis,
//! bonus_sets}`), each piece against a brute force written here:
//!
//! * `goal_paths`: every simple path from `x1` to a goal (stopping at the first goal, parallel
//!   moves counted apart) by a depth-first walk over node sequences; its step bound against the
//!   number of simple prefixes (one search step per prefix whose nodes before the last are not
//!   goals): the search succeeds with that many steps and refuses with one fewer.
//! * `policy_count`: `Π |U(x)|` over the non-goal states reachable from `x1` without passing a
//!   goal (a closure computed here), with the running product checked against the limit in
//!   increasing state order ("as soon as it exceeds").
//! * `policy_averages`: every policy decoded from a mixed-radix index and walked `n` moves (a
//!   goal reached: `(L, 1, moves + 1)`; otherwise the walk is then on its cycle, which is walked
//!   once round).
//! * `least_mean_cycle`: the least mean over the simple cycles (node sequences, least node first)
//!   of the goal-avoiding part reachable from `x1`.
//! * `bonus_analysis`: `L*` and the distinct `S*` from the brute-force paths; the exact set at
//!   every grid bonus against the definition (`π*`'s reset cycle `(L* + M)/S*` is the least mean
//!   of every simple cycle of the reset graph, where each goal's one arc is the reset to `x1`
//!   costing `M`); the printed and the corrected sets against their formulas evaluated at each
//!   grid bonus; and the refusals (states, policies, search steps) by hand.
//!
//! Kills the mutants of those functions (kernel-only mutation cycle, docs/mutants.md).

// Index loops over states read better than iterator chains in these brute forces.
#![allow(clippy::needless_range_loop)]

mod support;

use support::SplitMix;
use truecost_kernel::claims::c4::{
    bonus_analysis, bonus_sets, BonusError, BonusSets, Instance, Interval, MAX_BONUS_STATES,
};
use truecost_kernel::claims::exact::Q;

/// A random instance: 1 to `max_states` states, 0 to 3 moves each (`dead_ends`: a non-goal
/// state may have none; otherwise every non-goal state has at least one), costs in
/// `min_cost..=max_cost`, each state a goal with probability 1/3, a random initial state.
fn random_instance(
    draw: &mut SplitMix,
    max_states: u64,
    min_cost: i64,
    max_cost: i64,
    dead_ends: bool,
) -> Instance {
    let n = 1 + draw.below(max_states) as usize;
    let is_goal: Vec<bool> = (0..n).map(|_| draw.below(3) == 0).collect();
    let moves = (0..n)
        .map(|x| {
            let least = if dead_ends || is_goal[x] { 0 } else { 1 };
            let degree = least + draw.below(4 - least);
            (0..degree)
                .map(|_| {
                    let y = draw.below(n as u64) as usize;
                    let c = min_cost + draw.below((max_cost - min_cost + 1) as u64) as i64;
                    (y, c)
                })
                .collect()
        })
        .collect();
    let initial = draw.below(n as u64) as usize;
    Instance {
        initial,
        is_goal,
        moves,
    }
}

/// The states reachable from `x1` without passing through a goal (goals reached included).
fn brute_reach(inst: &Instance) -> Vec<bool> {
    let n = inst.moves.len();
    let mut reach = vec![false; n];
    reach[inst.initial] = true;
    let mut changed = true;
    while changed {
        changed = false;
        for x in 0..n {
            if reach[x] && !inst.is_goal[x] {
                for &(y, _) in &inst.moves[x] {
                    if !reach[y] {
                        reach[y] = true;
                        changed = true;
                    }
                }
            }
        }
    }
    reach
}

/// Every simple goal path `(L, S)` (S = states on it) and the number of simple prefixes.
fn brute_paths(inst: &Instance) -> (Vec<(i64, i64)>, u64) {
    fn walk(inst: &Instance, seq: &mut Vec<usize>, cost: i64, out: &mut Vec<(i64, i64)>) -> u64 {
        let last = *seq.last().unwrap();
        if inst.is_goal[last] {
            out.push((cost, seq.len() as i64));
            return 1;
        }
        let mut prefixes = 1;
        for &(y, c) in &inst.moves[last] {
            if !seq.contains(&y) {
                seq.push(y);
                prefixes += walk(inst, seq, cost + c, out);
                seq.pop();
            }
        }
        prefixes
    }
    let mut out = Vec::new();
    let prefixes = walk(inst, &mut vec![inst.initial], 0, &mut out);
    out.sort();
    (out, prefixes)
}

/// `Π |U(x)|` over the reachable non-goal states in increasing order, `None` as soon as the
/// running product exceeds `limit` (or overflows).
fn brute_count(inst: &Instance, limit: u64) -> Option<u64> {
    let reach = brute_reach(inst);
    let mut product: u64 = 1;
    for x in 0..inst.moves.len() {
        if reach[x] && !inst.is_goal[x] {
            product = product.checked_mul(inst.moves[x].len() as u64)?;
            if product > limit {
                return None;
            }
        }
    }
    Some(product)
}

/// Every policy's `(c, r, k)`, sorted (empty when a reachable non-goal state has no move).
fn brute_averages(inst: &Instance) -> Vec<(i64, i64, i64)> {
    let n = inst.moves.len();
    let reach = brute_reach(inst);
    let free: Vec<usize> = (0..n).filter(|&x| reach[x] && !inst.is_goal[x]).collect();
    if free.iter().any(|&x| inst.moves[x].is_empty()) {
        return Vec::new();
    }
    let total: usize = free.iter().map(|&x| inst.moves[x].len()).product();
    let mut out = Vec::new();
    for index in 0..total {
        let mut choice = vec![0; n];
        let mut rest = index;
        for &x in &free {
            choice[x] = rest % inst.moves[x].len();
            rest /= inst.moves[x].len();
        }
        let step = |x: usize| inst.moves[x][choice[x]];
        let mut x = inst.initial;
        let mut cost = 0;
        let mut reached = None;
        for moves in 0..=n {
            if inst.is_goal[x] {
                reached = Some((cost, 1, moves as i64 + 1));
                break;
            }
            if moves == n {
                break;
            }
            let (y, c) = step(x);
            cost += c;
            x = y;
        }
        if let Some(a) = reached {
            out.push(a);
            continue;
        }
        // After n moves without a goal the walk is on its cycle: go round it once.
        let start = x;
        let (mut w, mut len) = (0, 0);
        loop {
            let (y, c) = step(x);
            w += c;
            len += 1;
            x = y;
            if x == start {
                break;
            }
        }
        out.push((w, 0, len));
    }
    out.sort();
    out
}

/// Every simple cycle `(weight, length, resets)` of a graph given as arcs
/// `(from, to, weight, resets)`, over node sequences with the least node first, among `allowed`.
fn brute_cycles(
    n: usize,
    arcs: &[(usize, usize, i64, i64)],
    allowed: &[bool],
) -> Vec<(i64, i64, i64)> {
    fn extend(
        seq: &mut Vec<usize>,
        w: i64,
        r: i64,
        arcs: &[(usize, usize, i64, i64)],
        allowed: &[bool],
        out: &mut Vec<(i64, i64, i64)>,
    ) {
        let last = *seq.last().unwrap();
        for &(a, b, c, rc) in arcs {
            if a != last || !allowed[b] {
                continue;
            }
            if b == seq[0] {
                out.push((w + c, seq.len() as i64, r + rc));
            } else if b > seq[0] && !seq.contains(&b) {
                seq.push(b);
                extend(seq, w + c, r + rc, arcs, allowed, out);
                seq.pop();
            }
        }
    }
    let mut out = Vec::new();
    for v in 0..n {
        if allowed[v] {
            extend(&mut vec![v], 0, 0, arcs, allowed, &mut out);
        }
    }
    out
}

/// `Lav(Ĉ)`: the least mean of the goal-avoiding cycles reachable from `x1`.
fn brute_least_mean(inst: &Instance) -> Option<Q> {
    let n = inst.moves.len();
    let reach = brute_reach(inst);
    let allowed: Vec<bool> = (0..n).map(|x| reach[x] && !inst.is_goal[x]).collect();
    let arcs: Vec<(usize, usize, i64, i64)> = (0..n)
        .flat_map(|x| inst.moves[x].iter().map(move |&(y, c)| (x, y, c, 0)))
        .collect();
    brute_cycles(n, &arcs, &allowed)
        .into_iter()
        .map(|(w, l, _)| Q::new(w as i128, l as i128))
        .min()
}

/// Grid of bonuses: every point given, midpoints, `±1/1000` beside each, far out; negatives only.
fn negative_grid(points: &[Q]) -> Vec<Q> {
    let mut pts: Vec<Q> = points.to_vec();
    pts.extend([Q::int(-1), Q::new(-1, 3), Q::int(-7)]);
    let mut g = support::rational_grid(&pts);
    g.retain(|m| *m < Q::ZERO);
    g
}

fn ends(iv: &Interval) -> Vec<Q> {
    use truecost_kernel::claims::c4::End;
    [iv.lo, iv.hi]
        .into_iter()
        .filter_map(|e| match e {
            End::Closed(q) | End::Open(q) => Some(q),
            End::Unbounded => None,
        })
        .collect()
}

#[test]
fn goal_paths_and_their_step_bound_against_a_walk_over_node_sequences() {
    let mut draw = SplitMix(0xC4_0101);
    let mut nonempty = 0;
    for _ in 0..2000 {
        let inst = random_instance(&mut draw, 6, -2, 3, true);
        let (paths, prefixes) = brute_paths(&inst);
        let mut got = inst.goal_paths(prefixes).expect("enough steps");
        got.sort();
        assert_eq!(got, paths, "{inst:?}");
        assert_eq!(
            inst.goal_paths(prefixes - 1),
            Err(BonusError::SearchTooLong {
                steps: prefixes - 1
            }),
            "{inst:?}"
        );
        nonempty += usize::from(!paths.is_empty());
    }
    assert!(nonempty > 500, "{nonempty}");
}

#[test]
fn goal_paths_by_hand() {
    // x1 = 0 -> 1 (cost 2) -> goal 3 (cost 3); 0 -> 2 (cost 1) -> 1 (cost 1); 1 -> 0 back;
    // 2 -> goal 3 (cost 7). Paths: 0-1-3 (5, 3), 0-2-1-3 (5, 4), 0-2-3 (8, 3).
    let inst = Instance {
        initial: 0,
        is_goal: vec![false, false, false, true],
        moves: vec![
            vec![(1, 2), (2, 1)],
            vec![(0, 4), (3, 3)],
            vec![(1, 1), (3, 7)],
            vec![(0, 1)],
        ],
    };
    let mut paths = inst.goal_paths(100).unwrap();
    paths.sort();
    assert_eq!(paths, vec![(5, 3), (5, 4), (8, 3)]);
    // Prefixes: [0], [0 1], [0 1 3], [0 2], [0 2 1], [0 2 1 3], [0 2 3]: 7 steps.
    assert!(inst.goal_paths(7).is_ok());
    assert_eq!(
        inst.goal_paths(6),
        Err(BonusError::SearchTooLong { steps: 6 })
    );
    // x1 a goal: the one path of one state.
    let at_goal = Instance {
        initial: 1,
        is_goal: vec![false, true],
        moves: vec![vec![(1, 1)], vec![(0, 1)]],
    };
    assert_eq!(at_goal.goal_paths(1), Ok(vec![(0, 1)]));
}

#[test]
fn policy_count_against_the_product_of_action_counts() {
    let mut draw = SplitMix(0xC4_0102);
    for _ in 0..2000 {
        let inst = random_instance(&mut draw, 7, 0, 3, true);
        let full = brute_count(&inst, u64::MAX).unwrap();
        for limit in [0, 1, 2, 3, full.saturating_sub(1), full, full + 1, u64::MAX] {
            assert_eq!(
                inst.policy_count(limit),
                brute_count(&inst, limit),
                "{inst:?}, limit {limit}"
            );
        }
    }
    // By hand: states 0, 1 free (2 and 3 moves), 2 a goal (4 moves, not counted), 3 not
    // reachable (5 moves, not counted), 4 reachable only through the goal (not counted).
    let inst = Instance {
        initial: 0,
        is_goal: vec![false, false, true, false, false],
        moves: vec![
            vec![(1, 1), (2, 1)],
            vec![(0, 1), (1, 1), (2, 1)],
            vec![(4, 1); 4],
            vec![(0, 1); 5],
            vec![(0, 1); 6],
        ],
    };
    assert_eq!(inst.policy_count(6), Some(6));
    assert_eq!(inst.policy_count(5), None);
    assert_eq!(inst.policy_count(u64::MAX), Some(6));
}

#[test]
fn policy_averages_against_walks_of_every_policy() {
    let mut draw = SplitMix(0xC4_0103);
    let mut cycles = 0;
    for _ in 0..2000 {
        let dead_ends = draw.below(4) == 0;
        let inst = random_instance(&mut draw, 6, -2, 3, dead_ends);
        let count = brute_count(&inst, u64::MAX).unwrap();
        let expected = brute_averages(&inst);
        let mut got = inst
            .policy_averages(count.max(1))
            .expect("within the limit");
        got.sort();
        assert_eq!(got, expected, "{inst:?}");
        if count > 1 {
            assert_eq!(inst.policy_averages(count - 1), None, "{inst:?}");
        }
        cycles += expected.iter().filter(|a| a.1 == 0).count();
    }
    assert!(cycles > 1000, "{cycles}");
}

#[test]
fn policy_averages_by_hand() {
    // x1 = 0: to 1 (cost 2) or to the goal 2 (cost 5); 1: to itself (cost 3), back to 0 (cost
    // 1) or to the goal (cost 1).
    let inst = Instance {
        initial: 0,
        is_goal: vec![false, false, true],
        moves: vec![vec![(1, 2), (2, 5)], vec![(1, 3), (0, 1), (2, 1)], vec![]],
    };
    let mut got = inst.policy_averages(6).unwrap();
    got.sort();
    // (0->1, 1->1): cycle 1-1, (3, 0, 1); (0->1, 1->0): cycle 0-1-0, (3, 0, 2);
    // (0->1, 1->2): goal after 2 moves, (3, 1, 3); (0->2, any of 3): (5, 1, 2) three times.
    assert_eq!(
        got,
        vec![
            (3, 0, 1),
            (3, 0, 2),
            (3, 1, 3),
            (5, 1, 2),
            (5, 1, 2),
            (5, 1, 2)
        ]
    );
    assert_eq!(inst.policy_averages(5), None);
}

#[test]
fn least_mean_cycle_against_the_simple_cycles_of_the_goal_avoiding_part() {
    let mut draw = SplitMix(0xC4_0104);
    let mut some = 0;
    for _ in 0..2000 {
        let inst = random_instance(&mut draw, 6, -2, 3, true);
        let expected = brute_least_mean(&inst);
        assert_eq!(inst.least_mean_cycle(), Ok(expected), "{inst:?}");
        some += usize::from(expected.is_some());
    }
    assert!(some > 500, "{some}");
}

#[test]
fn least_mean_cycle_by_hand() {
    // Reachable goal-avoiding cycles from x1 = 1: 1-2-1 (mean 5/2) and 2-2 (mean 4); the cycle
    // 0-0 (mean -5) is not reachable from x1, the cycle 3-4-3 (mean 1) only through the goal 5,
    // and 1-5-1 passes the goal.
    let inst = Instance {
        initial: 1,
        is_goal: vec![false, false, false, false, false, true],
        moves: vec![
            vec![(0, -5)],
            vec![(2, 2), (5, 0)],
            vec![(1, 3), (2, 4)],
            vec![(4, 1)],
            vec![(3, 1)],
            vec![(3, 0), (1, -9)],
        ],
    };
    assert_eq!(inst.least_mean_cycle(), Ok(Some(Q::new(5, 2))));
    // x1 a goal: no goal-avoiding cycle at all.
    let at_goal = Instance {
        initial: 5,
        ..inst.clone()
    };
    assert_eq!(at_goal.least_mean_cycle(), Ok(None));
    // From x1 = 3 (not a goal) the cycle 3-4-3 counts.
    let from_three = Instance { initial: 3, ..inst };
    assert_eq!(from_three.least_mean_cycle(), Ok(Some(Q::int(1))));
}

/// Whether `m` lies in the printed formula's set, evaluated from its definition:
/// `A(u) = (1 − S(u)/S*)·(S(u)·L*/(S*·L(u)) − 1)`, `max_{S(u)<S*} A(u) ≤ M ≤ min_{S(u)>S*} A(u)`,
/// `M ≤ S*·Lav − L*`, `M < 0`.
fn in_printed(paths: &[(i64, i64)], lstar: i64, s: i64, lav: Option<Q>, m: Q) -> bool {
    let (lq, sq) = (Q::int(lstar as i128), Q::int(s as i128));
    paths.iter().all(|&(l, su)| {
        let (l, su) = (Q::int(l as i128), Q::int(su as i128));
        if su == sq {
            return true;
        }
        // A(u) = ((S* − S(u))/S*) · ((S(u)·L* − S*·L(u))/(S*·L(u))).
        let a = (sq - su) / sq * ((su * lq - sq * l) / (sq * l));
        if su < sq {
            a <= m
        } else {
            m <= a
        }
    }) && lav.is_none_or(|lav| m <= sq * lav - lq)
        && m < Q::ZERO
}

/// Whether `m` lies in the corrected formula's set: `T(u) = (S*·L(u) − S(u)·L*)/(S(u) − S*)`,
/// `max_{S(u)<S*} T(u) ≤ M ≤ min{min_{S(u)>S*} T(u), S*·Lav − L*}`, `M < 0`.
fn in_corrected(paths: &[(i64, i64)], lstar: i64, s: i64, lav: Option<Q>, m: Q) -> bool {
    let (lq, sq) = (Q::int(lstar as i128), Q::int(s as i128));
    paths.iter().all(|&(l, su)| {
        let (l, su) = (Q::int(l as i128), Q::int(su as i128));
        if su == sq {
            return true;
        }
        let t = (sq * l - su * lq) / (su - sq);
        if su < sq {
            t <= m
        } else {
            m <= t
        }
    }) && lav.is_none_or(|lav| m <= sq * lav - lq)
        && m < Q::ZERO
}

/// The three sets of every `S*` against the definition (exact) and the formulas (printed,
/// corrected) on a grid of bonuses; `bonus_sets` gives the same answer.
#[test]
fn bonus_sets_against_the_reset_graph_and_the_formulas() {
    let mut draw = SplitMix(0xC4_0105);
    let (mut analysed, mut printed_some, mut several) = (0, 0, 0);
    for _ in 0..1500 {
        let inst = random_instance(&mut draw, 5, 0, 3, false);
        let n = inst.moves.len();
        let got = bonus_analysis(&inst, 1 << 16);
        assert_eq!(bonus_sets(&inst, 1 << 16), Ok(got.clone().unwrap()));
        let (paths, _) = brute_paths(&inst);
        let Some(lstar) = paths.iter().map(|p| p.0).min() else {
            assert_eq!(got, Ok(None), "{inst:?}");
            continue;
        };
        let sets = got.unwrap().expect("a goal path");
        let mut sstars: Vec<i64> = paths.iter().filter(|p| p.0 == lstar).map(|p| p.1).collect();
        sstars.sort();
        sstars.dedup();
        assert_eq!(
            sets.iter().map(|s| s.optimal_states).collect::<Vec<_>>(),
            sstars
        );
        let lav = brute_least_mean(&inst);
        // The reset graph: goals' moves replaced by one arc to x1 (one reset).
        let reach = brute_reach(&inst);
        let mut arcs = Vec::new();
        for x in 0..n {
            if inst.is_goal[x] {
                arcs.push((x, inst.initial, 0, 1));
            } else {
                arcs.extend(inst.moves[x].iter().map(|&(y, c)| (x, y, c, 0)));
            }
        }
        let cycles = brute_cycles(n, &arcs, &reach);
        analysed += 1;
        several += usize::from(sets.len() > 1);
        for set in &sets {
            let s = set.optimal_states;
            assert_eq!(set.optimal_cost, lstar, "{inst:?}");
            assert_eq!(set.least_mean_cycle, lav, "{inst:?}");
            let mut pts = ends(&set.exact);
            pts.extend(ends(&set.corrected));
            if let Some(p) = set.printed {
                pts.extend(ends(&p));
            }
            let zero_elsewhere = paths.iter().any(|&(l, su)| su != s && l == 0);
            assert_eq!(set.printed.is_none(), zero_elsewhere, "{inst:?}");
            printed_some += usize::from(set.printed.is_some());
            for m in negative_grid(&pts) {
                let own = (Q::int(lstar as i128) + m) / Q::int(s as i128);
                let least = cycles
                    .iter()
                    .map(|&(w, len, r)| {
                        (Q::int(w as i128) + Q::int(r as i128) * m) / Q::int(len as i128)
                    })
                    .min()
                    .expect("the reset cycle of pi*");
                assert!(own >= least);
                assert_eq!(
                    set.exact.contains(m),
                    own == least,
                    "exact {} at M = {m}: {inst:?}",
                    set.exact
                );
                assert_eq!(
                    set.corrected.contains(m),
                    in_corrected(&paths, lstar, s, lav, m),
                    "corrected {} at M = {m}: {inst:?}",
                    set.corrected
                );
                if let Some(p) = set.printed {
                    assert_eq!(
                        p.contains(m),
                        in_printed(&paths, lstar, s, lav, m),
                        "printed {p} at M = {m}: {inst:?}"
                    );
                }
            }
        }
    }
    assert!(
        analysed > 600 && printed_some > 300 && several > 10,
        "{analysed} {printed_some} {several}"
    );
}

/// A chain `0 -> 1 -> … -> len − 1` (the goal), each move costing 1.
fn chain(len: usize) -> Instance {
    let mut is_goal = vec![false; len];
    is_goal[len - 1] = true;
    Instance {
        initial: 0,
        is_goal,
        moves: (0..len)
            .map(|x| {
                if x + 1 < len {
                    vec![(x + 1, 1)]
                } else {
                    vec![]
                }
            })
            .collect(),
    }
}

#[test]
fn bonus_analysis_refusals_by_hand() {
    // Exactly MAX_BONUS_STATES reachable states: analysed; one more: refused.
    let at_bound = bonus_analysis(&chain(MAX_BONUS_STATES), 1)
        .unwrap()
        .unwrap();
    let states = MAX_BONUS_STATES as i64;
    assert_eq!(at_bound.len(), 1);
    assert_eq!(at_bound[0].optimal_cost, states - 1);
    assert_eq!(at_bound[0].optimal_states, states);
    assert_eq!(at_bound[0].least_mean_cycle, None);
    assert_eq!(
        bonus_analysis(&chain(MAX_BONUS_STATES + 1), 1),
        Err(BonusError::TooManyStates {
            states: MAX_BONUS_STATES + 1
        })
    );
    // 2 · 3 = 6 policies: refused below 6, analysed at 6.
    let six = Instance {
        initial: 0,
        is_goal: vec![false, false, true],
        moves: vec![vec![(1, 1), (2, 3)], vec![(0, 1), (1, 1), (2, 1)], vec![]],
    };
    assert_eq!(
        bonus_analysis(&six, 5),
        Err(BonusError::TooManyPolicies { limit: 5 })
    );
    assert_eq!(bonus_sets(&six, 5), Ok(None));
    assert!(bonus_analysis(&six, 6).unwrap().is_some());
    // No goal reachable (the goal 2 only from the unreachable 1), 9 policies: no analysis,
    // whatever the limit.
    let no_goal = Instance {
        initial: 0,
        is_goal: vec![false, false, true, false],
        moves: vec![
            vec![(0, 1), (3, 1), (3, 2)],
            vec![(2, 1)],
            vec![],
            vec![(0, 1), (3, 1), (0, 2)],
        ],
    };
    assert_eq!(bonus_analysis(&no_goal, 1), Ok(None));
    assert_eq!(bonus_sets(&no_goal, 1), Ok(None));
    // A dead end: state 0 (reachable, no move) makes the policy count 0, so limit 1 passes;
    // the goal-path search from x1 = 1 takes 4 steps ([1], [1 0], [1 2], [1 2] again), within
    // 1 · (3 states + 1). No policy: no constraint, every negative bonus in every set.
    let dead_end = Instance {
        initial: 1,
        is_goal: vec![false, false, true],
        moves: vec![vec![], vec![(0, 1), (2, 2), (2, 4)], vec![]],
    };
    assert_eq!(dead_end.policy_count(1), Some(0));
    assert_eq!(
        bonus_analysis(&dead_end, 1),
        Ok(Some(vec![BonusSets {
            optimal_cost: 2,
            optimal_states: 2,
            least_mean_cycle: None,
            exact: Interval::negative(),
            printed: Some(Interval::negative()),
            corrected: Interval::negative(),
        }]))
    );
}

/// One instance computed by hand: x1 = 0 -> goal 2 directly (cost 4, S = 2) or through 1 (costs
/// 1 + 1, S = 3); 1 also loops on itself (cost 3). `L* = 2`, `S* = 3`, `Lav = 3`.
#[test]
fn bonus_sets_by_hand() {
    let inst = Instance {
        initial: 0,
        is_goal: vec![false, false, true],
        moves: vec![vec![(2, 4), (1, 1)], vec![(2, 1), (1, 3)], vec![]],
    };
    let sets = bonus_analysis(&inst, 10).unwrap().unwrap();
    assert_eq!(sets.len(), 1);
    let set = &sets[0];
    assert_eq!((set.optimal_cost, set.optimal_states), (2, 3));
    assert_eq!(set.least_mean_cycle, Some(Q::int(3)));
    // Exact: (2 + M)/3 <= (4 + M)/2 (M >= -8) and <= 3 (M <= 7): [-8, 0).
    // Corrected: T(u) for S(u) = 2 < 3: (3·4 − 2·2)/(2 − 3) = -8; cycle bound 3·3 − 2 = 7.
    // Printed: A(u) = (1 − 2/3)·(2·2/(3·4) − 1) = (1/3)·(−2/3) = −2/9: [−2/9, 0).
    let mut exact = Interval::negative();
    exact.at_least(Q::int(-8));
    assert_eq!(set.exact, exact);
    assert_eq!(set.corrected, exact);
    let mut printed = Interval::negative();
    printed.at_least(Q::new(-2, 9));
    assert_eq!(set.printed, Some(printed));
    assert_eq!(set.exact.to_string(), "[-8, 0)");
    assert_eq!(printed.to_string(), "[-2/9, 0)");
}

/// Each refusal names its bound in one line (`verify --claim C4` prints it).
#[test]
fn bonus_error_messages_name_their_bounds() {
    let policies = BonusError::TooManyPolicies { limit: 5 }.to_string();
    assert!(
        policies.starts_with("more than 5 stationary policies"),
        "{policies}"
    );
    let steps = BonusError::SearchTooLong { steps: 7 }.to_string();
    assert!(steps.contains("more than 7 steps"), "{steps}");
    let states = BonusError::TooManyStates { states: 1025 }.to_string();
    assert!(
        states.starts_with("1025 states") && states.ends_with(&MAX_BONUS_STATES.to_string()),
        "{states}"
    );
    let internal = BonusError::Internal("Karp disagrees".into()).to_string();
    assert_eq!(internal, "internal error: Karp disagrees");
    for message in [policies, steps, states, internal] {
        assert!(!message.contains('\n'), "{message}");
    }
}
