//! The exact algebra the claims rely on, each piece against a brute force
//! that shares no code with it:
//!
//! * C4's bonus sets (`c4::bonus_sets`) against the minimum mean cycle of the reset graph, found
//!   by walking every simple cycle (written here, not the library's). The interval algebra
//!   itself (`c4::Interval`, `End`, `witness`) is tested in the kernel
//!   (`kernel/tests/claims_c4_intervals.rs`, where its tests moved so that the kernel-only
//!   mutation cycle sees them).
//! * Enumeration (`oracle`): simple cycles, simple goal paths, policies and trajectories against
//!   enumeration of node sequences and step-by-step simulation; Karp's minimum mean cycle against
//!   the brute-force cycles; every functional against a simulated stage sequence.
//! * Root isolation (`poly`, `alpha`): Sturm counts and isolated roots against polynomials built
//!   from known roots and against sign changes on fine rational grids.
//! * `exact::Q` and `Frac` against big rationals.

// Index loops over states read better than iterator chains in these brute forces.
#![allow(clippy::needless_range_loop)]

use std::cmp::Ordering;

#[path = "../kernel/tests/support/mod.rs"]
mod support; // the kernel tests' grid of rationals (`support::rational_grid`)

use num_bigint::BigInt;
use num_traits::{One, Signed, Zero};
use proptest::prelude::*;
use proptest::test_runner::Config;
use truecost::algebra::poly::{count_roots, decimal, isolate_roots, Algebraic, Poly};
use truecost::claims::c4::{bonus_sets, contains_unscaled, End, Instance, Interval};
use truecost::claims::exact::{ipow, Ext, Frac, FracExt, Q};
use truecost::claims::oracle::{
    evaluate, evaluate_fast, goal_avoiding_arcs, karp_minimum_mean_cycle, optimal_cost_to_go,
    policies, simple_cycles, simple_goal_paths, trajectory, Functional, Policy, TERMINATE,
};
use truecost::claims::sampled::tiny_strategy;
use truecost::claims::tiny::{Tiny, MAX_STATES};
use truecost::value::{parse_rational, Rational};

fn config(cases: u32) -> Config {
    Config {
        cases,
        failure_persistence: None,
        ..Config::default()
    }
}

fn big(n: i64) -> Rational {
    Rational::from_integer(BigInt::from(n))
}

fn bq(n: i64, d: i64) -> Rational {
    Rational::new(BigInt::from(n), BigInt::from(d))
}

fn q_to_big(q: Q) -> Rational {
    bq(q.numer() as i64, q.denom() as i64)
}
// ---------------------------------------------------------------------------------------------
// C4's bonus sets against the reset graph's minimum mean cycle
// ---------------------------------------------------------------------------------------------

/// Every simple cycle of a weighted digraph (rational weights) reachable from `start`, by
/// enumerating node sequences: the brute force behind the C4 check below.
fn reachable_cycle_means(
    n: usize,
    arcs: &[(usize, usize, Rational)],
    start: usize,
) -> Vec<Rational> {
    let mut reach = vec![false; n];
    reach[start] = true;
    let mut changed = true;
    while changed {
        changed = false;
        for (a, b, _) in arcs {
            if reach[*a] && !reach[*b] {
                reach[*b] = true;
                changed = true;
            }
        }
    }
    let mut out = Vec::new();
    // Extend sequences v0 < v1.., v2.. (distinct, all greater than v0) and close back to v0.
    fn extend(
        seq: &mut Vec<usize>,
        w: Rational,
        arcs: &[(usize, usize, Rational)],
        out: &mut Vec<Rational>,
    ) {
        let last = *seq.last().unwrap();
        for (a, b, c) in arcs {
            if *a != last {
                continue;
            }
            if *b == seq[0] {
                out.push((&w + c) / big(seq.len() as i64));
            } else if *b > seq[0] && !seq.contains(b) {
                seq.push(*b);
                extend(seq, &w + c, arcs, out);
                seq.pop();
            }
        }
    }
    for v in 0..n {
        if reach[v] {
            extend(&mut vec![v], Rational::zero(), arcs, &mut out);
        }
    }
    out
}

fn c4_instance() -> impl Strategy<Value = Instance> {
    (2usize..=5).prop_flat_map(|n| {
        prop::collection::vec(prop::collection::vec((0..n, 0i64..=3), 1..=2), n - 1).prop_map(
            move |mut moves| {
                moves.push(Vec::new());
                let mut is_goal = vec![false; n];
                is_goal[n - 1] = true;
                Instance {
                    initial: 0,
                    is_goal,
                    moves,
                }
            },
        )
    })
}

proptest! {
    #![proptest_config(config(400))]

    /// The exact set of bonuses (and the corrected formula's set, which the claim says is the
    /// same) against the definition: `π*` is average-cost optimal at `M` iff its reset cycle's
    /// mean `(L* + M)/S*` is the least mean of every cycle of the reset graph reachable from `x1`
    /// (the goal's one move is the reset to `x1`, one stage costing `M`).
    #[test]
    fn bonus_sets_agree_with_the_reset_graph(inst in c4_instance()) {
        let Some(sets) = bonus_sets(&inst, 1 << 16).unwrap() else {
            // No goal path: the brute force agrees that no path reaches the goal.
            let n = inst.moves.len();
            let arcs: Vec<(usize, usize, Rational)> = (0..n)
                .flat_map(|x| inst.moves[x].iter().map(move |&(y, c)| (x, y, big(c))))
                .collect();
            let mut reach = vec![false; n];
            reach[0] = true;
            for _ in 0..n {
                for (a, b, _) in &arcs {
                    if reach[*a] && !inst.is_goal[*a] {
                        reach[*b] = true;
                    }
                }
            }
            prop_assert!(!reach[n - 1]);
            return Ok(());
        };
        let n = inst.moves.len();
        for s in &sets {
            let mut pts: Vec<Q> = Vec::new();
            for iv in [Some(s.exact), Some(s.corrected), s.printed].into_iter().flatten() {
                for e in [iv.lo, iv.hi] {
                    if let End::Closed(q) | End::Open(q) = e {
                        pts.push(q);
                    }
                }
            }
            pts.extend([Q::int(-1), Q::new(-1, 3), Q::int(-7)]);
            for m in support::rational_grid(&pts).into_iter().filter(|m| *m < Q::ZERO) {
                let mb = q_to_big(m);
                let mut arcs: Vec<(usize, usize, Rational)> = Vec::new();
                for x in 0..n {
                    if inst.is_goal[x] {
                        arcs.push((x, inst.initial, mb.clone()));
                    } else {
                        for &(y, c) in &inst.moves[x] {
                            arcs.push((x, y, big(c)));
                        }
                    }
                }
                let least = reachable_cycle_means(n, &arcs, inst.initial).into_iter().min().unwrap();
                let own = (big(s.optimal_cost) + &mb) / big(s.optimal_states);
                prop_assert!(own >= least);
                let optimal = own == least;
                prop_assert_eq!(s.exact.contains(m), optimal, "exact {} at M = {}", s.exact, m);
                prop_assert_eq!(s.corrected.contains(m), optimal, "corrected {} at M = {}", s.corrected, m);
            }
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Enumeration: cycles, paths, policies, trajectories; Karp
// ---------------------------------------------------------------------------------------------

/// Every simple cycle as `(weight, length)` by enumerating node sequences `v0 < others`,
/// distinct, with every choice among parallel arcs.
fn brute_cycles(n: usize, arcs: &[(usize, usize, i64)]) -> Vec<(i64, usize)> {
    let mut out = Vec::new();
    // Every sequence of distinct nodes as a bit-set walk over permutations by recursion.
    fn seqs(n: usize, seq: &mut Vec<usize>, all: &mut Vec<Vec<usize>>) {
        all.push(seq.clone());
        for v in 0..n {
            if v > seq[0] && !seq.contains(&v) {
                seq.push(v);
                seqs(n, seq, all);
                seq.pop();
            }
        }
    }
    let mut all = Vec::new();
    for v in 0..n {
        seqs(n, &mut vec![v], &mut all);
    }
    for seq in all {
        // Arc choices along seq[0] -> seq[1] -> ... -> seq[0].
        let mut partial: Vec<i64> = vec![0];
        for i in 0..seq.len() {
            let (a, b) = (seq[i], seq[(i + 1) % seq.len()]);
            let ws: Vec<i64> = arcs
                .iter()
                .filter(|(x, y, _)| *x == a && *y == b)
                .map(|t| t.2)
                .collect();
            partial = partial
                .iter()
                .flat_map(|p| ws.iter().map(move |w| p + w))
                .collect();
        }
        out.extend(partial.into_iter().map(|w| (w, seq.len())));
    }
    out.sort();
    out
}

fn digraph() -> impl Strategy<Value = (usize, Vec<(usize, usize, i64)>)> {
    (1usize..=5).prop_flat_map(|n| {
        (
            Just(n),
            prop::collection::vec((0..n, 0..n, -3i64..=5), 0..=9),
        )
    })
}

proptest! {
    #![proptest_config(config(1000))]

    #[test]
    fn simple_cycles_and_karp_against_node_sequences((n, arcs) in digraph()) {
        let mut cycles = simple_cycles(n, &arcs);
        cycles.sort();
        let brute = brute_cycles(n, &arcs);
        prop_assert_eq!(&cycles, &brute);
        let least = brute.iter().map(|&(w, l)| Q::new(w as i128, l as i128)).min();
        prop_assert_eq!(karp_minimum_mean_cycle(n, &arcs), least);
    }
}

#[test]
fn karp_edge_cases() {
    assert_eq!(karp_minimum_mean_cycle(0, &[]), None);
    assert_eq!(karp_minimum_mean_cycle(3, &[(0, 1, 1), (1, 2, 1)]), None);
    assert_eq!(karp_minimum_mean_cycle(1, &[(0, 0, -4)]), Some(Q::int(-4)));
    // A cheap cycle not reachable from node 0 still counts (Karp walks start anywhere).
    assert_eq!(
        karp_minimum_mean_cycle(3, &[(0, 1, 9), (1, 0, 9), (2, 2, 1)]),
        Some(Q::int(1))
    );
    // Parallel arcs: the cheaper one decides.
    assert_eq!(
        karp_minimum_mean_cycle(2, &[(0, 1, 5), (0, 1, 1), (1, 0, 0)]),
        Some(Q::new(1, 2))
    );
}

/// Simple goal paths from `0` by enumerating node sequences (goal only at the end).
fn brute_goal_paths(t: &Tiny) -> Vec<(i64, usize)> {
    let n = t.states();
    let mut out = Vec::new();
    fn walk(t: &Tiny, seq: &mut Vec<usize>, cost: i64, out: &mut Vec<(i64, usize)>) {
        let x = *seq.last().unwrap();
        if t.is_goal(x) {
            out.push((cost, seq.len()));
            return;
        }
        for y in 0..t.states() {
            if seq.contains(&y) {
                continue;
            }
            for m in t.moves(x).iter().filter(|m| m.to as usize == y) {
                seq.push(y);
                walk(t, seq, cost + m.cost as i64, out);
                seq.pop();
            }
        }
    }
    if n > 0 {
        walk(t, &mut vec![0], 0, &mut out);
    }
    out.sort();
    out
}

/// Stage `k` (0-based) of following `p` from `start`, by simulation (0 once terminated).
fn simulated_stages(t: &Tiny, p: &Policy, start: usize, count: usize) -> (Vec<i64>, bool) {
    let mut x = start;
    let mut out = Vec::with_capacity(count);
    let mut visits_goal = false;
    let mut stopped = false;
    for _ in 0..count {
        visits_goal |= t.is_goal(x);
        if stopped || p[x] == TERMINATE {
            stopped = true;
            out.push(0);
            continue;
        }
        let m = t.moves(x)[p[x] as usize];
        out.push(m.cost as i64);
        x = m.to as usize;
    }
    (out, visits_goal)
}

fn frac_to_big(f: FracExt) -> Option<Rational> {
    match f {
        FracExt::Fin(Frac { n, d }) => Some(Rational::new(BigInt::from(n), BigInt::from(d))),
        _ => None,
    }
}

fn ext_to_big(e: Ext) -> Option<Rational> {
    match e {
        Ext::Fin(q) => Some(q_to_big(q)),
        _ => None,
    }
}

proptest! {
    #![proptest_config(config(200))]

    /// Goal paths (two implementations: `oracle::simple_goal_paths` and C4's
    /// `Instance::goal_paths`) against node sequences; `optimal_cost_to_go` against the cheapest
    /// simple path; `goal_avoiding_arcs` against its definition.
    #[test]
    fn goal_paths_and_cost_to_go_against_node_sequences(t in tiny_strategy(5, 3, 2, 4)) {
        let brute = brute_goal_paths(&t);
        let mut a = simple_goal_paths(&t);
        a.sort();
        prop_assert_eq!(&a, &brute);
        let mut b: Vec<(i64, usize)> = Instance::from_tiny(&t)
            .goal_paths(u64::MAX)
            .expect("no step bound")
            .into_iter()
            .map(|(l, s)| (l, s as usize))
            .collect();
        b.sort();
        prop_assert_eq!(&b, &brute);
        let best = optimal_cost_to_go(&t);
        for x in 0..t.states() {
            // From x: the cheapest simple path (costs are non-negative).
            let mut relabel: Vec<Vec<(u8, u8)>> = Vec::new();
            for y in 0..t.states() {
                let yy = if y == x { 0 } else if y == 0 { x } else { y };
                relabel.push(t.moves(yy).iter().map(|m| {
                    let to = m.to as usize;
                    let to = if to == x { 0 } else if to == 0 { x } else { to };
                    (to as u8, m.cost)
                }).collect());
            }
            let from_x = Tiny::from_lists(&relabel);
            let cheapest = if t.is_goal(x) { Some(0) } else { brute_goal_paths(&from_x).iter().map(|p| p.0).min() };
            prop_assert_eq!(best[x], cheapest, "state {}", x);
        }
        let (seen, arcs) = goal_avoiding_arcs(&t);
        // seen: non-goal states reachable from 0 by walks avoiding the goal.
        let mut reach = vec![false; t.states()];
        if !t.is_goal(0) {
            reach[0] = true;
            for _ in 0..t.states() {
                for y in 0..t.states() {
                    for x in 0..t.states() {
                        if reach[x] && !t.is_goal(y) && t.moves(x).iter().any(|m| m.to as usize == y) {
                            reach[y] = true;
                        }
                    }
                }
            }
        }
        prop_assert_eq!(&seen, &reach);
        let mut want: Vec<(usize, usize, i64)> = (0..t.states())
            .filter(|&x| reach[x])
            .flat_map(|x| t.moves(x).iter().filter(|m| reach[m.to as usize]).map(move |m| (x, m.to as usize, m.cost as i64)))
            .collect();
        want.sort();
        let mut got = arcs;
        got.sort();
        prop_assert_eq!(got, want);
    }

    /// Every policy's trajectory against simulation, and every functional (`evaluate` and its
    /// fast path) against sums over the simulated stages.
    #[test]
    fn trajectories_and_functionals_against_simulation(t in tiny_strategy(4, 2, 1, 3), goal_moves in any::<bool>()) {
        let ps = policies(&t, goal_moves);
        let expected: usize = (0..t.states())
            .map(|x| if t.is_goal(x) { 1 + if goal_moves { t.moves(x).len() } else { 0 } } else { t.moves(x).len() })
            .product();
        prop_assert_eq!(ps.len(), expected);
        let mut distinct = ps.clone();
        distinct.sort();
        distinct.dedup();
        prop_assert_eq!(distinct.len(), ps.len());
        // 420 = lcm(1..=7): a window of 420 stages after the prefix is a whole number of cycles.
        const PAST: usize = MAX_STATES;
        const WINDOW: usize = 420;
        for p in ps.iter().take(12) {
            for start in 0..t.states() {
                let tr = trajectory(&t, p, start);
                let (stages, visits_goal) = simulated_stages(&t, p, start, PAST + WINDOW);
                prop_assert_eq!(tr.visits_goal, visits_goal);
                for (k, &s) in stages.iter().enumerate().take(PAST + 2 * MAX_STATES.min(WINDOW)) {
                    let v = if k < tr.prefix_len { tr.prefix[k] } else { tr.cycle[(k - tr.prefix_len) % tr.cycle_len] };
                    prop_assert_eq!(v, s, "stage {}", k);
                }
                prop_assert!(tr.prefix_len + tr.cycle_len <= t.states() + 1);
                for sign in [1i64, -1] {
                    let st: Vec<i64> = stages.iter().map(|s| sign * s).collect();
                    let window: i64 = st[PAST..].iter().sum();
                    let head: i64 = st[..PAST].iter().sum();
                    let total = if window > 0 { Ext::PosInf } else if window < 0 { Ext::NegInf } else { Ext::Fin(Q::int(head as i128)) };
                    let avg = Q::new(window as i128, WINDOW as i128);
                    let mut fs = vec![
                        (Functional::Total, total),
                        (Functional::Average, Ext::Fin(avg)),
                    ];
                    for h in [1usize, 3, 8] {
                        let sum: i64 = st[..h].iter().sum();
                        fs.push((Functional::HorizonTotal(h), Ext::Fin(Q::int(sum as i128))));
                        fs.push((Functional::HorizonAverage(h), Ext::Fin(Q::new(sum as i128, h as i128))));
                        for a in [Q::new(1, 2), Q::new(9, 10)] {
                            let ab = q_to_big(a);
                            let mut v = Rational::zero();
                            let mut pw = Rational::one();
                            for s in &st[..h] {
                                v += &pw * big(*s);
                                pw *= &ab;
                            }
                            let got = ext_to_big(evaluate(&tr, Functional::HorizonDiscounted(h, a), sign)).unwrap();
                            prop_assert_eq!(&got, &v);
                            let fast = frac_to_big(evaluate_fast(&tr, Functional::HorizonDiscounted(h, a), sign)).unwrap();
                            prop_assert_eq!(&fast, &v);
                        }
                    }
                    for (f, want) in fs {
                        prop_assert_eq!(evaluate(&tr, f, sign), want, "{}", f.name());
                        match (evaluate_fast(&tr, f, sign), want) {
                            (FracExt::PosInf, Ext::PosInf) | (FracExt::NegInf, Ext::NegInf) => {}
                            (fe, Ext::Fin(q)) => prop_assert_eq!(frac_to_big(fe), Some(q_to_big(q)), "{}", f.name()),
                            (fe, w) => prop_assert!(false, "{}: {:?} vs {:?}", f.name(), fe, w),
                        }
                    }
                    // Discounted: the simulated partial sum over 64 stages is within the tail
                    // bound α^64·max|s|/(1−α) of the exact value.
                    for a in [Q::new(1, 2), Q::new(3, 4)] {
                        let ab = q_to_big(a);
                        let mut v = Rational::zero();
                        let mut pw = Rational::one();
                        for s in &st[..64] {
                            v += &pw * big(*s);
                            pw *= &ab;
                        }
                        let tail = &pw * big(3) / (Rational::one() - &ab);
                        let exact = ext_to_big(evaluate(&tr, Functional::Discounted(a), sign)).unwrap();
                        prop_assert!((&exact - &v).abs() <= tail);
                        let fast = frac_to_big(evaluate_fast(&tr, Functional::Discounted(a), sign)).unwrap();
                        prop_assert_eq!(&fast, &exact);
                    }
                }
            }
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Exact small rationals
// ---------------------------------------------------------------------------------------------

proptest! {
    #![proptest_config(config(2000))]

    #[test]
    fn small_rationals_against_big_rationals(an in -50i64..=50, ad in -12i64..=12, bn in -50i64..=50, bd in -12i64..=12, k in 0u32..4) {
        prop_assume!(ad != 0 && bd != 0);
        let (a, b) = (Q::new(an as i128, ad as i128), Q::new(bn as i128, bd as i128));
        let (x, y) = (bq(an, ad), bq(bn, bd));
        // Normal form: positive denominator, coprime.
        prop_assert!(a.denom() > 0);
        prop_assert_eq!(q_to_big(a), x.clone());
        prop_assert_eq!(BigInt::from(a.numer()), x.numer().clone());
        prop_assert_eq!(BigInt::from(a.denom()), x.denom().clone());
        prop_assert_eq!(q_to_big(a + b), &x + &y);
        prop_assert_eq!(q_to_big(a - b), &x - &y);
        prop_assert_eq!(q_to_big(a * b), &x * &y);
        prop_assert_eq!(q_to_big(-a), -x.clone());
        if !y.is_zero() {
            prop_assert_eq!(q_to_big(a / b), &x / &y);
        }
        prop_assert_eq!(a.cmp(&b), x.cmp(&y));
        prop_assert_eq!(a == b, x == y);
        prop_assert_eq!(a.is_zero(), x.is_zero());
        prop_assert_eq!(a.signum(), if x.is_positive() { 1 } else if x.is_negative() { -1 } else { 0 });
        prop_assert_eq!(q_to_big(a.pow(k)), num_traits::pow(x.clone(), k as usize));
        prop_assert_eq!(a.to_rational(), x.clone());
        let shown = if x.is_integer() { x.numer().to_string() } else { format!("{}/{}", x.numer(), x.denom()) };
        prop_assert_eq!(a.to_string(), shown);
        // Unnormalised fractions compare by value.
        let (fa, fb) = (Frac { n: (an * 3) as i128, d: (ad * 3).abs() as i128 * ad.signum() as i128 }, Frac { n: bn as i128, d: bd as i128 });
        if fa.d > 0 && fb.d > 0 {
            prop_assert_eq!(fa.cmp(&fb), x.cmp(&y));
            prop_assert_eq!(fa == fb, x == y);
        }
        prop_assert_eq!(BigInt::from(ipow(an as i128, k as usize)), num_traits::pow(BigInt::from(an), k as usize));
    }
}

#[test]
fn small_rationals_refuse_overflow_and_zero_denominators() {
    let huge = Q::int(i128::MAX);
    assert!(std::panic::catch_unwind(|| huge + Q::ONE).is_err());
    assert!(std::panic::catch_unwind(|| huge * Q::int(2)).is_err());
    assert!(std::panic::catch_unwind(|| -Q::int(i128::MIN)).is_err());
    assert!(std::panic::catch_unwind(|| Q::new(1, 0)).is_err());
    assert!(std::panic::catch_unwind(|| Q::ONE / Q::ZERO).is_err());
    assert!(std::panic::catch_unwind(|| ipow(10, 40)).is_err());
    assert_eq!(Ext::NegInf.cmp(&Ext::Fin(Q::int(-1000))), Ordering::Less);
    assert_eq!(Ext::Fin(Q::int(1000)).cmp(&Ext::PosInf), Ordering::Less);
    assert_eq!(Ext::Fin(Q::new(-7, 2)).to_string(), "-7/2");
    assert_eq!(Ext::PosInf.to_string(), "inf");
    assert_eq!(Ext::NegInf.to_string(), "-inf");
}

// ---------------------------------------------------------------------------------------------
// Polynomials and root isolation
// ---------------------------------------------------------------------------------------------

/// `Π (x − r_i)` times `x^2 + c` (no real root when `c > 0`), by hand.
fn from_roots(roots: &[Rational], c: i64) -> Poly {
    let mut p = Poly::from_i64(&[c, 0, 1]);
    for r in roots {
        p = p.mul(&Poly::new(vec![-r.clone(), Rational::one()]));
    }
    p
}

/// The value by powers, not Horner.
fn value(p: &Poly, x: &Rational) -> Rational {
    p.coefficients()
        .iter()
        .enumerate()
        .map(|(i, c)| c * num_traits::pow(x.clone(), i))
        .fold(Rational::zero(), |a, b| a + b)
}

fn rational_root() -> impl Strategy<Value = Rational> {
    (-12i64..=12, 1i64..=4).prop_map(|(n, d)| bq(n, d))
}

fn poly_strategy() -> impl Strategy<Value = Poly> {
    prop::collection::vec(-6i64..=6, 1..=6).prop_map(|c| Poly::from_i64(&c))
}

proptest! {
    #![proptest_config(config(300))]

    /// Ring operations, division, gcd and derivative against evaluation at points.
    #[test]
    fn polynomial_arithmetic_against_evaluation(p in poly_strategy(), q in poly_strategy(), xs in prop::collection::vec(rational_root(), 4)) {
        for x in &xs {
            prop_assert_eq!(p.eval(x), value(&p, x));
            prop_assert_eq!(p.add(&q).eval(x), value(&p, x) + value(&q, x));
            prop_assert_eq!(p.sub(&q).eval(x), value(&p, x) - value(&q, x));
            prop_assert_eq!(p.mul(&q).eval(x), value(&p, x) * value(&q, x));
            prop_assert_eq!(p.scale(&bq(3, 2)).eval(x), value(&p, x) * bq(3, 2));
            prop_assert_eq!(p.sign_at(x), value(&p, x).cmp(&Rational::zero()));
        }
        // Degree and coefficients: no trailing zeros.
        prop_assert!(p.coefficients().last().is_none_or(|c| !c.is_zero()));
        prop_assert_eq!(p.degree(), p.coefficients().len().checked_sub(1));
        prop_assert_eq!(p.is_zero(), p.coefficients().is_empty());
        // Derivative: coefficient i·c_i, and the product rule.
        let d = p.derivative();
        for (i, c) in p.coefficients().iter().enumerate().skip(1) {
            prop_assert_eq!(d.coefficients().get(i - 1).cloned().unwrap_or_else(Rational::zero), c * big(i as i64));
        }
        prop_assert_eq!(p.mul(&q).derivative(), d.mul(&q).add(&p.mul(&q.derivative())));
        if !q.is_zero() {
            let (quo, rem) = p.div_rem(&q);
            prop_assert_eq!(quo.mul(&q).add(&rem), p.clone());
            prop_assert!(rem.is_zero() || rem.degree() < q.degree());
            let g = p.gcd(&q);
            prop_assert!(!g.is_zero());
            prop_assert_eq!(g.coefficients().last().cloned(), Some(Rational::one()));
            prop_assert!(p.div_rem(&g).1.is_zero());
            prop_assert!(q.div_rem(&g).1.is_zero());
            // Greatest: gcd(p·h, q·h) has h as a factor.
            let h = Poly::from_i64(&[-1, 1]);
            if !p.is_zero() {
                prop_assert!(p.mul(&h).gcd(&q.mul(&h)).div_rem(&h).1.is_zero());
            }
        }
        // The primitive integer multiple: integer, coprime, positive lead, same roots.
        let pr = p.primitive();
        if !p.is_zero() {
            prop_assert!(pr.coefficients().iter().all(|c| c.is_integer()));
            prop_assert!(pr.coefficients().last().unwrap().is_positive());
            let ratio = pr.coefficients().last().unwrap() / p.coefficients().last().unwrap();
            prop_assert_eq!(p.scale(&ratio), pr.clone());
            let mut g = BigInt::zero();
            for c in pr.coefficients() {
                g = num_integer::Integer::gcd(&g, c.numer());
            }
            prop_assert!(g.is_one());
            prop_assert_eq!(p.monic(), pr.monic());
        }
    }

    /// Sturm counts and isolated roots against known roots (with multiplicities) and a factor
    /// without real roots.
    #[test]
    fn root_isolation_finds_exactly_the_known_roots(
        roots in prop::collection::vec(rational_root(), 1..=4),
        doubled in any::<bool>(),
        c in 1i64..=5,
        (lo, hi) in (rational_root(), rational_root()).prop_filter("lo < hi", |(a, b)| a < b),
    ) {
        let mut all = roots.clone();
        if doubled {
            all.push(roots[0].clone());
        }
        let p = from_roots(&all, c);
        let mut distinct = roots.clone();
        distinct.sort();
        distinct.dedup();
        // Square-free part: the distinct roots and the quadratic, monic.
        prop_assert_eq!(p.squarefree(), from_roots(&distinct, c).monic());
        let seq = p.squarefree().sturm();
        let in_half_open = distinct.iter().filter(|r| **r > lo && **r <= hi).count();
        prop_assert_eq!(count_roots(&seq, &lo, &hi), in_half_open);
        let open: Vec<&Rational> = distinct.iter().filter(|r| **r > lo && **r < hi).collect();
        let iso = isolate_roots(&p, &lo, &hi);
        prop_assert_eq!(iso.len(), open.len());
        for (a, r) in iso.iter().zip(&open) {
            // Each bracket (lo, hi] holds its root and no other, inside the search interval.
            prop_assert!(&a.lo < *r && *r <= &a.hi, "{} not in ({}, {}]", r, a.lo, a.hi);
            prop_assert!(a.lo >= lo && a.hi <= hi);
            prop_assert_eq!(distinct.iter().filter(|s| **s > a.lo && **s <= a.hi).count(), 1);
            // `as_rational` is partial (linear polynomial or a root at the closed end) but exact.
            if let Some(v) = a.as_rational() {
                prop_assert_eq!(&v, *r);
            }
            prop_assert_eq!(a.is_rational(), a.hi == **r);
            prop_assert_eq!(a.cmp_rational(r), Ordering::Equal);
            prop_assert_eq!(a.cmp_rational(&(*r + bq(1, 1000))), Ordering::Less);
            prop_assert_eq!(a.cmp_rational(&(*r - bq(1, 1000))), Ordering::Greater);
            prop_assert_eq!(a.cmp_rational(&(*r + big(100))), Ordering::Less);
            prop_assert_eq!(a.cmp_rational(&(*r - big(100))), Ordering::Greater);
            let mut b = a.clone();
            b.refine_to(&bq(1, 1 << 20));
            prop_assert!(&b.hi - &b.lo <= bq(1, 1 << 20));
            prop_assert!(&b.lo < *r && *r <= &b.hi);
        }
        for w in iso.windows(2) {
            prop_assert!(w[0].hi <= w[1].lo);
            prop_assert_eq!(w[0].compare(&w[1]), Ordering::Less);
            prop_assert_eq!(w[1].compare(&w[0]), Ordering::Greater);
        }
    }

    /// On arbitrary integer polynomials: every isolated root is a sign change of the square-free
    /// part inside its bracket (or its closed end is a root), brackets are disjoint and sorted, and
    /// every sign change on a grid of step 1/32 lies in a bracket.
    #[test]
    fn root_isolation_against_sign_changes_on_a_grid(p in poly_strategy()) {
        prop_assume!(p.degree().unwrap_or(0) >= 1);
        let (lo, hi) = (big(-4), big(4));
        let sf = p.squarefree();
        let iso = isolate_roots(&p, &lo, &hi);
        for a in &iso {
            let mut b = a.clone();
            b.refine_to(&bq(1, 1 << 12));
            let (slo, shi) = (value(&sf, &b.lo), value(&sf, &b.hi));
            prop_assert!(shi.is_zero() || (slo.is_positive() != shi.is_positive() && !slo.is_zero()), "no sign change in ({}, {}]", b.lo, b.hi);
            prop_assert!(a.lo >= lo && a.hi <= hi && a.lo < a.hi);
        }
        for w in iso.windows(2) {
            prop_assert!(w[0].hi <= w[1].lo);
        }
        let step = bq(1, 32);
        let mut x = lo.clone();
        while x < hi {
            let y = &x + &step;
            let (sx, sy) = (value(&p, &x), value(&p, &y));
            // A root of p in (x, y] (y < hi) must be in some bracket.
            let root_here = y < hi && (sy.is_zero() || (!sx.is_zero() && sx.is_positive() != sy.is_positive()));
            if root_here {
                prop_assert!(iso.iter().any(|a| a.hi > x && a.lo < y), "root in ({}, {}] missed", x, y);
            }
            x = y;
        }
    }
}

/// `Algebraic::from_rational` brackets `q` as the root of `x − q` in `(q − 1, q]`, and
/// `halve_with` halves a bracket exactly, keeping the one root inside (checked by squaring
/// against √2 and by a Sturm count, twenty halvings from `(0, 2]`); `sign_of` needs both.
#[test]
fn rational_brackets_and_halving_by_hand() {
    for q in [bq(1, 2), big(-3), bq(7, 3)] {
        let a = Algebraic::from_rational(q.clone());
        assert_eq!((a.lo.clone(), a.hi.clone()), (&q - big(1), q.clone()));
        assert_eq!(value(&a.poly, &q), big(0));
        assert_eq!(count_roots(&a.poly.sturm(), &a.lo, &a.hi), 1, "{q}");
    }
    let mut sqrt2 = isolate_roots(&Poly::from_i64(&[-2, 0, 1]), &big(0), &big(2))
        .pop()
        .unwrap();
    let seq = sqrt2.poly.sturm();
    let mut width = &sqrt2.hi - &sqrt2.lo;
    for _ in 0..20 {
        sqrt2.halve_with(&seq);
        let w = &sqrt2.hi - &sqrt2.lo;
        assert_eq!(w, &width / big(2));
        width = w;
        assert!(
            &sqrt2.lo * &sqrt2.lo < big(2) && &sqrt2.hi * &sqrt2.hi > big(2),
            "{sqrt2:?}"
        );
        assert_eq!(count_roots(&seq, &sqrt2.lo, &sqrt2.hi), 1);
    }
    // sign_of from the wide bracket (0, 2] of √2, which holds the roots 3/2 of 2x − 3 and 1 of
    // x − 1, and whose closed end 2 is the root of x − 2: each needs halving first.
    let wide = Algebraic {
        poly: Poly::from_i64(&[-2, 0, 1]),
        lo: big(0),
        hi: big(2),
    };
    for (f, sign) in [
        (Poly::from_i64(&[-3, 2]), Ordering::Less), // 2√2 − 3 < 0
        (Poly::from_i64(&[3, -2]), Ordering::Greater), // 3 − 2√2 > 0
        (Poly::from_i64(&[-1, 1]), Ordering::Greater), // √2 − 1 > 0
        (Poly::from_i64(&[-2, 1]), Ordering::Less), // √2 − 2 < 0
        (Poly::from_i64(&[-2, 0, 1]), Ordering::Equal),
        (Poly::from_i64(&[10, -2, -5, 1]), Ordering::Equal), // (x² − 2)(x − 5)
        (Poly::zero(), Ordering::Equal),
    ] {
        assert_eq!(wide.sign_of(&f), sign, "{f}");
    }
}

/// `as_rational` of a linear polynomial is its root `−c₀/c₁`, whatever the leading
/// coefficient: `2x − 3` (as a caller may build it) and `x − 3/2` (monic, as `isolate_roots`
/// gives it) both name 3/2, in a bracket `(1, 2]` whose closed end is not the root.
#[test]
fn a_linear_root_as_a_rational() {
    for poly in [Poly::from_i64(&[-3, 2]), Poly::from_i64(&[-3, 2]).monic()] {
        let a = Algebraic {
            poly,
            lo: big(1),
            hi: big(2),
        };
        assert!(!a.is_rational());
        assert_eq!(a.as_rational(), Some(bq(3, 2)));
    }
    let mut roots = isolate_roots(&Poly::from_i64(&[-3, 2]), &big(0), &big(4));
    assert_eq!(roots.len(), 1);
    assert_eq!(roots.pop().unwrap().as_rational(), Some(bq(3, 2)));
}

/// `decimal` refines the bracket below the last digit before truncating: √(49/50) =
/// 0.98994…, whose isolating bracket from `(0, 2]` ends at 1 or above, is "0" and "0.9", not
/// "1" or "1.0".
#[test]
fn decimals_of_a_root_just_below_a_digit() {
    let r = isolate_roots(&Poly::from_i64(&[-49, 0, 50]), &big(0), &big(2))
        .pop()
        .unwrap();
    assert!(r.hi >= big(1), "{r:?}");
    assert_eq!(r.decimal(0), "0");
    assert_eq!(r.decimal(1), "0.9");
    assert_eq!(r.decimal(4), "0.9899");
}

#[test]
fn algebraic_numbers_by_hand() {
    // ±√2 and ±√3: comparisons with rationals and with each other, decided exactly.
    let sqrt = |k: i64| {
        isolate_roots(&Poly::from_i64(&[-k, 0, 1]), &big(0), &big(10))
            .pop()
            .unwrap()
    };
    let (s2, s3) = (sqrt(2), sqrt(3));
    assert_eq!(s2.compare(&s3), Ordering::Less);
    assert_eq!(s3.compare(&s2), Ordering::Greater);
    // The same number from another polynomial: (x^2 - 2)(x - 5).
    let other = isolate_roots(&Poly::from_i64(&[10, -2, -5, 1]), &big(0), &big(3))
        .pop()
        .unwrap();
    assert_eq!(other.compare(&s2), Ordering::Equal);
    assert_eq!(s2.as_rational(), None);
    assert!(!s2.is_rational());
    for k in 1..200i64 {
        let x = bq(k, 50); // 0.02 .. 3.98
        let want = big(2).cmp(&(&x * &x)); // √2 vs x
        assert_eq!(s2.cmp_rational(&x), want, "{x}");
    }
    assert_eq!(s2.decimal(10), "1.4142135623");
    assert_eq!(s3.decimal(5), "1.73205");
    assert_eq!(decimal(&bq(-29, 20), 1), "-1.5");
    assert_eq!(decimal(&bq(1, 3), 4), "0.3333");
    assert_eq!(decimal(&big(7), 2), "7.00");
    assert_eq!(
        Poly::from_i64(&[-1, 0, -3, 2]).to_string(),
        "2x^3 - 3x^2 - 1"
    );
    assert_eq!(
        Poly::new(vec![bq(1, 2), bq(-3, 4)]).to_string(),
        "-(3/4)x + (1/2)"
    );
    assert_eq!(Poly::zero().to_string(), "0");
    assert_eq!(Poly::monomial(3).degree(), Some(3));
    assert!(std::panic::catch_unwind(|| Poly::monomial(1).div_rem(&Poly::zero())).is_err());
    // No root: an empty isolation, and a root at the open ends is excluded.
    assert!(isolate_roots(&Poly::from_i64(&[1, 0, 1]), &big(-9), &big(9)).is_empty());
    assert!(isolate_roots(&Poly::from_i64(&[7]), &big(-9), &big(9)).is_empty());
    assert!(isolate_roots(&Poly::from_i64(&[-1, 1]), &big(1), &big(9)).is_empty());
    assert!(isolate_roots(&Poly::from_i64(&[-9, 1]), &big(1), &big(9)).is_empty());
}

proptest! {
    #![proptest_config(config(200))]

    /// `decimal` truncates towards −∞: the printed value `v` satisfies `v ≤ x < v + 10^-d`.
    #[test]
    fn decimals_truncate(n in -100_000i64..=100_000, d in 1i64..=999, digits in 1usize..6) {
        let x = bq(n, d);
        let s = decimal(&x, digits);
        let v = parse_rational(&s).unwrap();
        let ulp = Rational::new(BigInt::one(), num_traits::pow(BigInt::from(10), digits));
        prop_assert!(v <= x && x < &v + ulp, "{} for {}", s, x);
        prop_assert_eq!(s.split('.').nth(1).map_or(0, str::len), digits);
    }
}

// ---------------------------------------------------------------------------------------------
// α* of the worked example (C3)
// ---------------------------------------------------------------------------------------------

#[test]
fn printed_inequality_is_the_sign_of_the_polynomial_on_a_grid() {
    use truecost::claims::alpha::{alpha_star, printed_inequality, printed_polynomial};
    // 1/(1-a) < 1 + 2a + 3a^2 + 4a^3 + 5a^4  ⇔  5a^4 - a^3 - a^2 - a - 1 < 0 on (0, 1), by hand.
    let hand = Poly::from_i64(&[-1, -1, -1, -1, 5]);
    // The sign matters (the inequality is `P < 0`), so no normalisation before comparing.
    assert_eq!(printed_polynomial(), hand);
    let star = alpha_star().unwrap();
    for k in 1..1000i64 {
        let a = bq(k, 1000);
        assert_eq!(
            printed_inequality(&a),
            value(&hand, &a).is_negative(),
            "{a}"
        );
        // Below α* the inequality holds, above it fails.
        assert_eq!(
            printed_inequality(&a),
            star.cmp_rational(&a) == Ordering::Greater,
            "{a}"
        );
    }
    // The bracket holds a sign change of the hand polynomial and no grid root.
    assert!(value(&hand, &star.lo).is_negative() && value(&hand, &star.hi).is_positive());
    assert_eq!(
        isolate_roots(&hand, &big(0), &big(1)).len(),
        1,
        "one root in (0, 1)"
    );
    assert_eq!(Algebraic::clone(&star).compare(&star), Ordering::Equal);
    // The printed inequality is strict: at α = 0 both sides are 1 (the one point of [0, 1)
    // where they are equal, since α* is irrational), and 1 < 1 is false.
    assert!(!printed_inequality(&big(0)));
}

/// C3-example's refutation paths (`alpha::check_threshold`, which `alpha::check` runs with `α*`
/// and the printed inequality): a bracket below `α*` (1/2) fails at its upper end, one above it
/// (99/100) at its lower end, and a wrong inequality (`α < 1/2`) at exactly the grid points
/// where it disagrees with `α < α*`; each refutation names what failed, and the true threshold
/// and inequality verify all 101 cases.
#[test]
fn the_worked_example_refutes_a_wrong_threshold_or_a_wrong_inequality() {
    use truecost::claims::alpha::{
        alpha_star, check_threshold, printed_inequality, worked_example,
    };
    use truecost::claims::{ClaimResult, Verdict};
    let t = worked_example();
    let star = alpha_star().unwrap();
    let failures = |r: &ClaimResult| r.engines.iter().map(|e| e.failures).sum::<u64>();
    let ok = check_threshold(&t, &star, printed_inequality);
    assert_eq!(
        (ok.verdict, ok.cases, failures(&ok)),
        (Verdict::Verified, 101, 0)
    );
    let upper = "at the upper end of the bracket an optimal policy avoids the goal";
    let lower = "at the lower end of the bracket an optimal policy reaches the goal";
    for (bracket, failing_end) in [(bq(1, 2), upper), (bq(99, 100), lower)] {
        // The bracket (q − 1/1000, q] of the rational q.
        let mut wrong_star = Algebraic::from_rational(bracket.clone());
        wrong_star.refine_to(&bq(1, 1000));
        assert!(wrong_star.lo > bq(1, 4) && wrong_star.hi == bracket);
        let r = check_threshold(&t, &wrong_star, printed_inequality);
        assert_eq!(
            (r.verdict, r.cases, failures(&r)),
            (Verdict::Refuted, 101, 1),
            "{bracket}"
        );
        assert!(
            r.notes.iter().any(|n| n == failing_end),
            "{bracket}: {:?}",
            r.notes
        );
        let other_end = if failing_end == upper { lower } else { upper };
        assert!(!r.notes.iter().any(|n| n == other_end));
        assert!(!r.notes.iter().any(|n| n.contains("fails at")));
    }
    let wrong: Vec<i64> = (1..100)
        .filter(|&k| (k < 50) != (star.cmp_rational(&bq(k, 100)) == Ordering::Greater))
        .collect();
    assert!(wrong.len() > 10 && wrong[0] == 50, "{wrong:?}");
    let r = check_threshold(&t, &star, |a: &Rational| a < &bq(1, 2));
    assert_eq!((r.verdict, r.cases), (Verdict::Refuted, 101));
    assert_eq!(failures(&r), wrong.len() as u64);
    let listed: Vec<String> = wrong.iter().map(|k| k.to_string()).collect();
    let expected = format!(
        "the equivalence fails at alpha = k/100 for k in {}",
        listed.join(",")
    );
    assert!(r.notes.contains(&expected), "{:?}", r.notes);
}

/// `contains_unscaled` (the environment's own bonus against a scaled set, `verify --claim C4
/// --env`) against `Interval::contains` on the scaled value, for every kind of end, three scales
/// and a grid of quarters through every end point; and beyond `Q`'s range.
#[test]
fn unscaled_membership_agrees_with_scaled_membership() {
    let ends = |v: i128| [End::Unbounded, End::Closed(Q::int(v)), End::Open(Q::int(v))];
    let mut checked = 0;
    for lo_v in -4..=0 {
        for hi_v in lo_v..=1 {
            for lo in ends(lo_v) {
                for hi in ends(hi_v) {
                    for empty in [false, true] {
                        let i = Interval { lo, hi, empty };
                        for scale in [1i64, 2, 3] {
                            for quarter in -24..=8 {
                                let m = Rational::new(quarter.into(), 4.into());
                                let scaled = Q::new(quarter as i128 * scale as i128, 4);
                                assert_eq!(
                                    contains_unscaled(&i, &m, &BigInt::from(scale)),
                                    i.contains(scaled),
                                    "{i:?}, m = {m}, scale {scale}"
                                );
                                checked += 1;
                            }
                        }
                    }
                }
            }
        }
    }
    assert!(checked > 10_000);
    let below = Interval {
        lo: End::Unbounded,
        hi: End::Open(Q::int(0)),
        empty: false,
    };
    let huge = parse_rational("-1e40").unwrap();
    assert!(contains_unscaled(&below, &huge, &BigInt::from(7)));
    assert!(!contains_unscaled(&below, &-huge, &BigInt::from(7)));
}

/// The report's α* is the quartic's root rounded to nearest at 30 digits. The expected digits
/// come from an 80-digit Newton iteration outside truecost (0.91635458253384933778559036811365…):
/// the 31st digit is 6, so the 30th rounds up from 3 to 4, where truncation would keep 3.
#[test]
fn alpha_star_decimal_is_rounded_to_nearest() {
    let a = truecost::claims::alpha::alpha_star().unwrap();
    let report = truecost::claims::report::AlphaStar::new(&a);
    assert_eq!(report.decimal, "0.916354582533849337785590368114");
    assert_eq!(a.decimal(30), "0.916354582533849337785590368113");
}
