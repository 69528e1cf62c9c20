//! Independent oracles: enumeration of every deterministic stationary policy
//! of a tiny problem, the exact cost of each policy's trajectory under every functional of
//! SPEC §1, exact minimum mean cycles by Karp's algorithm and by enumerating simple cycles.
//!
//! Nothing here knows the formulas of SPEC §6: a claim is checked by comparing what these
//! brute-force computations give with what the claim states.

use super::exact::{power, ExactInt, Ext, Frac, FracExt, Q};
use super::tiny::{Tiny, MAX_STATES};

/// A decision of a stationary policy at one state: a move index, or [`TERMINATE`].
pub type Choice = u8;
/// The termination action `uT` (goals only).
pub const TERMINATE: Choice = u8::MAX;

/// A deterministic stationary policy: one [`Choice`] per state.
pub type Policy = [Choice; MAX_STATES];

/// Every deterministic stationary policy of `t`. At the goal the choices are termination
/// (first) and then its moves; a non-goal state chooses one of its moves.
pub fn policies(t: &Tiny, goal_may_move: bool) -> Vec<Policy> {
    let n = t.states();
    let mut out = vec![[0u8; MAX_STATES]];
    for x in 0..n {
        let mut choices: Vec<Choice> = Vec::new();
        if t.is_goal(x) {
            choices.push(TERMINATE);
            if goal_may_move {
                choices.extend(0..t.deg[x]);
            }
        } else {
            choices.extend(0..t.deg[x]);
        }
        let mut next = Vec::with_capacity(out.len() * choices.len());
        for p in &out {
            for &c in &choices {
                let mut q = *p;
                q[x] = c;
                next.push(q);
            }
        }
        out = next;
    }
    out
}

/// The stage costs of a trajectory: `prefix` then `cycle` repeated forever. A trajectory that
/// terminates at a goal has the cycle `[0]` (frozen, SPEC §1) and `terminates = true`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Trajectory {
    /// Stage costs before the cycle.
    pub prefix: [i64; MAX_STATES],
    /// Length of the prefix.
    pub prefix_len: usize,
    /// Stage costs of the cycle.
    pub cycle: [i64; MAX_STATES],
    /// Length of the cycle (at least 1).
    pub cycle_len: usize,
    /// Whether the trajectory ends by termination at a goal.
    pub terminates: bool,
    /// Whether the trajectory visits a goal state.
    pub visits_goal: bool,
}

/// Follows `policy` from `start` (exact; no solver involved).
pub fn trajectory(t: &Tiny, policy: &Policy, start: usize) -> Trajectory {
    let mut order = [usize::MAX; MAX_STATES];
    let mut costs = [0i64; MAX_STATES];
    let mut seen_at = [usize::MAX; MAX_STATES];
    let mut x = start;
    let mut k = 0;
    let mut visits_goal = false;
    loop {
        if t.is_goal(x) {
            visits_goal = true;
        }
        if policy[x] == TERMINATE {
            let mut tr = Trajectory {
                prefix: [0; MAX_STATES],
                prefix_len: k,
                cycle: [0; MAX_STATES],
                cycle_len: 1,
                terminates: true,
                visits_goal,
            };
            tr.prefix[..k].copy_from_slice(&costs[..k]);
            return tr;
        }
        if seen_at[x] != usize::MAX {
            let s = seen_at[x];
            let mut tr = Trajectory {
                prefix: [0; MAX_STATES],
                prefix_len: s,
                cycle: [0; MAX_STATES],
                cycle_len: k - s,
                terminates: false,
                visits_goal,
            };
            tr.prefix[..s].copy_from_slice(&costs[..s]);
            tr.cycle[..k - s].copy_from_slice(&costs[s..k]);
            return tr;
        }
        seen_at[x] = k;
        order[k] = x;
        let m = t.moves(x)[policy[x] as usize];
        costs[k] = m.cost as i64;
        k += 1;
        x = m.to as usize;
    }
}

/// A functional of a stage sequence that is linear in the stages (SPEC §1, §6 C2); its discount
/// factors are exact rationals over `I` (`i128` unless stated).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Functional<I: ExactInt = i128> {
    /// `Σ_{k≥1} s_k` in `[-∞, ∞]`.
    Total,
    /// `Σ_{k≥1} α^{k-1} s_k`.
    Discounted(Q<I>),
    /// `lim (1/N) Σ_{k≤N} s_k`.
    Average,
    /// `Σ_{k≤K} s_k`.
    HorizonTotal(usize),
    /// `Σ_{k≤K} α^{k-1} s_k`.
    HorizonDiscounted(usize, Q<I>),
    /// `(1/K) Σ_{k≤K} s_k`.
    HorizonAverage(usize),
}

impl Functional {
    /// A short name such as `discounted(1/2)`.
    pub fn name(&self) -> String {
        self.describe()
    }
}

impl<I: ExactInt> Functional<I> {
    /// A short name such as `discounted(1/2)` (in any width; [`Functional::name`] for `i128`).
    pub fn describe(&self) -> String {
        match self {
            Functional::Total => "total".into(),
            Functional::Discounted(a) => format!("discounted(alpha={a})"),
            Functional::Average => "average".into(),
            Functional::HorizonTotal(k) => format!("total over {k} stages"),
            Functional::HorizonDiscounted(k, a) => format!("discounted(alpha={a}) over {k} stages"),
            Functional::HorizonAverage(k) => format!("average over {k} stages"),
        }
    }
}

/// The stage at position `k` (0-based) of a trajectory, with the stage values mapped by `sign`
/// (`1` for costs, `-1` for rewards `r = -l`).
#[inline]
fn stage(tr: &Trajectory, k: usize, sign: i64) -> i64 {
    let v = if k < tr.prefix_len {
        tr.prefix[k]
    } else {
        tr.cycle[(k - tr.prefix_len) % tr.cycle_len]
    };
    sign * v
}

/// The exact value of `functional` on the trajectory's stage sequence multiplied by `sign`.
///
/// ```
/// use truecost_kernel::claims::exact::{Ext, Q};
/// use truecost_kernel::claims::oracle::{evaluate, policies, trajectory, Functional};
/// use truecost_kernel::claims::tiny::Tiny;
/// // 0 -> 0 (cost 1) forever: discounted value 1/(1-1/2) = 2; reward -2.
/// let t = Tiny::from_lists(&[vec![(0, 1)], vec![]]);
/// let p = policies(&t, false)[0];
/// let tr = trajectory(&t, &p, 0);
/// assert_eq!(evaluate(&tr, Functional::Discounted(Q::new(1, 2)), 1), Ext::Fin(Q::int(2)));
/// assert_eq!(evaluate(&tr, Functional::Discounted(Q::new(1, 2)), -1), Ext::Fin(Q::int(-2)));
/// assert_eq!(evaluate(&tr, Functional::Total, 1), Ext::PosInf);
/// ```
pub fn evaluate(tr: &Trajectory, functional: Functional, sign: i64) -> Ext {
    match functional {
        Functional::Total => {
            let cycle: i64 = (0..tr.cycle_len).map(|j| sign * tr.cycle[j]).sum();
            let any_nonzero = (0..tr.cycle_len).any(|j| tr.cycle[j] != 0);
            if cycle > 0 {
                Ext::PosInf
            } else if cycle < 0 {
                Ext::NegInf
            } else {
                assert!(!any_nonzero, "stage values of one sign only");
                Ext::Fin(Q::int(
                    (0..tr.prefix_len).map(|k| stage(tr, k, sign) as i128).sum(),
                ))
            }
        }
        Functional::Discounted(a) => {
            let mut value = Q::ZERO;
            let mut power = Q::ONE;
            for k in 0..tr.prefix_len {
                value = value + power * Q::int(stage(tr, k, sign) as i128);
                power = power * a;
            }
            let mut cycle = Q::ZERO;
            let mut p = Q::ONE;
            for j in 0..tr.cycle_len {
                cycle = cycle + p * Q::int((sign * tr.cycle[j]) as i128);
                p = p * a;
            }
            Ext::Fin(value + power * cycle / (Q::ONE - p))
        }
        Functional::Average => {
            let s: i128 = (0..tr.cycle_len)
                .map(|j| (sign * tr.cycle[j]) as i128)
                .sum();
            Ext::Fin(Q::new(s, tr.cycle_len as i128))
        }
        Functional::HorizonTotal(h) => {
            Ext::Fin(Q::int((0..h).map(|k| stage(tr, k, sign) as i128).sum()))
        }
        Functional::HorizonDiscounted(h, a) => {
            let mut value = Q::ZERO;
            let mut power = Q::ONE;
            for k in 0..h {
                value = value + power * Q::int(stage(tr, k, sign) as i128);
                power = power * a;
            }
            Ext::Fin(value)
        }
        Functional::HorizonAverage(h) => Ext::Fin(Q::new(
            (0..h).map(|k| stage(tr, k, sign) as i128).sum(),
            h as i128,
        )),
    }
}

/// `f(0) + … + f(n − 1)`, checked.
#[inline]
fn sum_of<I: ExactInt>(n: usize, f: impl Fn(usize) -> I) -> I {
    (0..n).fold(I::ZERO, |acc, k| acc.add_exact(f(k)))
}

/// The same value as [`evaluate`], as an unnormalised fraction (the engines' fast path):
/// discounted sums use `α = a/b` with integer numerator and denominator over `b^p (b^c − a^c)`.
/// Generic over the integer width `I`; every operation is checked (an overflow panics).
pub fn evaluate_fast<I: ExactInt>(
    tr: &Trajectory,
    functional: Functional<I>,
    sign: i64,
) -> FracExt<I> {
    let s = |k: usize| I::from_i64(stage(tr, k, sign));
    let c = |j: usize| I::from_i64(sign * tr.cycle[j]);
    let count = |n: usize| I::from_i64(n as i64);
    match functional {
        Functional::Total => {
            let cycle = sum_of(tr.cycle_len, c);
            if cycle > I::ZERO {
                FracExt::PosInf
            } else if cycle < I::ZERO {
                FracExt::NegInf
            } else {
                FracExt::Fin(Frac {
                    n: sum_of(tr.prefix_len, s),
                    d: I::ONE,
                })
            }
        }
        Functional::Discounted(alpha) => {
            let (a, b) = (alpha.numer(), alpha.denom());
            let (p, cl) = (tr.prefix_len, tr.cycle_len);
            // Q_{j+1} = b·Q_j + s_j·a^j·b gives Σ_{k<j} s_k a^k b^(j−k); likewise the cycle.
            let (mut prefix, mut ap, mut bp) = (I::ZERO, I::ONE, I::ONE);
            for k in 0..p {
                prefix = b
                    .mul_exact(prefix)
                    .add_exact(s(k).mul_exact(ap).mul_exact(b));
                ap = ap.mul_exact(a);
                bp = bp.mul_exact(b);
            }
            let (mut cycle, mut ac, mut bc) = (I::ZERO, I::ONE, I::ONE);
            for j in 0..cl {
                cycle = b
                    .mul_exact(cycle)
                    .add_exact(c(j).mul_exact(ac).mul_exact(b));
                ac = ac.mul_exact(a);
                bc = bc.mul_exact(b);
            }
            let gap = bc.sub_exact(ac);
            FracExt::Fin(Frac {
                n: prefix.mul_exact(gap).add_exact(ap.mul_exact(cycle)),
                d: bp.mul_exact(gap),
            })
        }
        Functional::Average => FracExt::Fin(Frac {
            n: sum_of(tr.cycle_len, c),
            d: count(tr.cycle_len),
        }),
        Functional::HorizonTotal(h) => FracExt::Fin(Frac {
            n: sum_of(h, s),
            d: I::ONE,
        }),
        Functional::HorizonDiscounted(h, alpha) => {
            let (a, b) = (alpha.numer(), alpha.denom());
            FracExt::Fin(Frac {
                n: sum_of(h, |k| {
                    s(k).mul_exact(power(a, k)).mul_exact(power(b, h - 1 - k))
                }),
                d: power(b, h.saturating_sub(1)),
            })
        }
        Functional::HorizonAverage(h) => FracExt::Fin(Frac {
            n: sum_of(h, s),
            d: count(h),
        }),
    }
}

/// `G*(x)` for every state by enumerating every policy and taking the least total cost of a
/// trajectory that terminates at the goal (`None` = `+∞`: no goal reachable). Independent of
/// every planner of `solvers/`.
pub fn optimal_cost_to_go(t: &Tiny) -> [Option<i64>; MAX_STATES] {
    let mut best = [None; MAX_STATES];
    for p in policies(t, false) {
        for (x, b) in best.iter_mut().enumerate().take(t.states()) {
            let tr = trajectory(t, &p, x);
            if tr.terminates {
                let c: i64 = tr.prefix[..tr.prefix_len].iter().sum();
                if b.is_none_or(|v| c < v) {
                    *b = Some(c);
                }
            }
        }
    }
    best
}

/// The minimum mean cycle weight of the directed graph given by `arcs` on `n` nodes, by Karp's
/// algorithm (1978): with `D_k(v)` the least weight of a walk of exactly `k` arcs ending at `v`
/// (from any start), `λ* = min_v max_{k<n} (D_n(v) − D_k(v)) / (n − k)`. `None` if acyclic.
///
/// ```
/// use truecost_kernel::claims::exact::Q;
/// use truecost_kernel::claims::oracle::karp_minimum_mean_cycle;
/// // cycle 0->1->0 of weights 1, 2 (mean 3/2) and a self-loop at 2 of weight 2
/// let arcs = [(0, 1, 1), (1, 0, 2), (2, 2, 2), (1, 2, 0)];
/// assert_eq!(karp_minimum_mean_cycle(3, &arcs), Some(Q::new(3, 2)));
/// ```
pub fn karp_minimum_mean_cycle(n: usize, arcs: &[(usize, usize, i64)]) -> Option<Q> {
    karp_minimum_mean_cycle_in(n, arcs)
}

/// [`karp_minimum_mean_cycle`] with the means exact rationals over `I` (checked: a mean whose
/// numerator or denominator does not fit `I` panics).
pub fn karp_minimum_mean_cycle_in<I: ExactInt>(
    n: usize,
    arcs: &[(usize, usize, i64)],
) -> Option<Q<I>> {
    if n == 0 {
        return None;
    }
    // d[k][v], None = no walk.
    let mut d = vec![vec![None::<i64>; n]; n + 1];
    for v in 0..n {
        d[0][v] = Some(0);
    }
    for k in 1..=n {
        for &(u, v, w) in arcs {
            if let Some(du) = d[k - 1][u] {
                let c = du + w;
                if d[k][v].is_none_or(|x| c < x) {
                    d[k][v] = Some(c);
                }
            }
        }
    }
    let mut best: Option<Q<I>> = None;
    for v in 0..n {
        let Some(dn) = d[n][v] else { continue };
        let mut worst: Option<Q<I>> = None;
        for (k, dk) in d.iter().enumerate().take(n) {
            if let Some(dk) = dk[v] {
                let m = Q::from_i64s(dn - dk, (n - k) as i64);
                if worst.is_none_or(|w| m > w) {
                    worst = Some(m);
                }
            }
        }
        if let Some(w) = worst {
            if best.is_none_or(|b| w < b) {
                best = Some(w);
            }
        }
    }
    best
}

/// Every simple cycle of the graph (each once, rooted at its smallest node) as
/// `(total weight, length)`.
///
/// The search from each root follows only arcs into nodes `≥ root` that can reach the root
/// again among such nodes (a backward search first), over adjacency lists: a node that lies on
/// no cycle through the root is never entered, so an acyclic graph costs `O(n·m)` whatever its
/// number of paths (a 1,021-state chain with parallel moves was exponential before).
///
/// ```
/// use truecost_kernel::claims::oracle::simple_cycles;
/// // 0 <-> 1 (weights 1 and 2), a self-loop at 2 (weight 5), 1 -> 2, and a parallel 0 -> 1.
/// let arcs = [(0, 1, 1), (1, 0, 2), (2, 2, 5), (1, 2, 0), (0, 1, 3)];
/// let mut c = simple_cycles(3, &arcs);
/// c.sort();
/// assert_eq!(c, vec![(3, 2), (5, 1), (5, 2)]);
/// ```
pub fn simple_cycles(n: usize, arcs: &[(usize, usize, i64)]) -> Vec<(i64, usize)> {
    let mut out = Vec::new();
    let mut forward: Vec<Vec<(usize, i64)>> = vec![Vec::new(); n];
    let mut backward: Vec<Vec<usize>> = vec![Vec::new(); n];
    for &(a, b, w) in arcs {
        forward[a].push((b, w));
        backward[b].push(a);
    }
    let mut on_path = vec![false; n];
    let mut back = vec![false; n];
    let mut stack = Vec::new();
    #[allow(clippy::too_many_arguments)]
    fn dfs(
        root: usize,
        v: usize,
        weight: i64,
        len: usize,
        forward: &[Vec<(usize, i64)>],
        back: &[bool],
        on_path: &mut [bool],
        out: &mut Vec<(i64, usize)>,
    ) {
        for &(b, w) in &forward[v] {
            if b == root {
                out.push((weight + w, len + 1));
            } else if b > root && back[b] && !on_path[b] {
                on_path[b] = true;
                dfs(root, b, weight + w, len + 1, forward, back, on_path, out);
                on_path[b] = false;
            }
        }
    }
    for root in 0..n {
        // The nodes >= root that reach root through nodes >= root.
        back.iter_mut().for_each(|b| *b = false);
        back[root] = true;
        stack.push(root);
        while let Some(v) = stack.pop() {
            for &a in &backward[v] {
                if a > root && !back[a] {
                    back[a] = true;
                    stack.push(a);
                }
            }
        }
        on_path[root] = true;
        dfs(root, root, 0, 0, &forward, &back, &mut on_path, &mut out);
        on_path[root] = false;
    }
    out
}

/// The non-goal states reachable from `x1` without passing through the goal, and the arcs
/// among them (the goal-avoiding part of the graph that a policy from `x1` can cycle in).
pub fn goal_avoiding_arcs(t: &Tiny) -> (Vec<bool>, Vec<(usize, usize, i64)>) {
    let n = t.states();
    let mut seen = vec![false; n];
    let mut stack = vec![0usize];
    if t.is_goal(0) {
        return (seen, Vec::new());
    }
    seen[0] = true;
    while let Some(x) = stack.pop() {
        for m in t.moves(x) {
            let y = m.to as usize;
            if !t.is_goal(y) && !seen[y] {
                seen[y] = true;
                stack.push(y);
            }
        }
    }
    let mut arcs = Vec::new();
    for x in 0..n {
        if !seen[x] {
            continue;
        }
        for m in t.moves(x) {
            let y = m.to as usize;
            if seen[y] {
                arcs.push((x, y, m.cost as i64));
            }
        }
    }
    (seen, arcs)
}

/// Every simple path from `x1 = 0` to the goal as `(cost L, number of states S)`.
pub fn simple_goal_paths(t: &Tiny) -> Vec<(i64, usize)> {
    let mut out = Vec::new();
    let mut on = [false; MAX_STATES];
    fn dfs(
        t: &Tiny,
        x: usize,
        cost: i64,
        states: usize,
        on: &mut [bool],
        out: &mut Vec<(i64, usize)>,
    ) {
        if t.is_goal(x) {
            out.push((cost, states));
            return;
        }
        for m in t.moves(x) {
            let y = m.to as usize;
            if !on[y] {
                on[y] = true;
                dfs(t, y, cost + m.cost as i64, states + 1, on, out);
                on[y] = false;
            }
        }
    }
    on[0] = true;
    dfs(t, 0, 0, 1, &mut on, &mut out);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn karp_agrees_with_enumeration_on_a_hand_example() {
        // Cycles: 0->0 (3), 0->1->0 (1+1 = 2 over 2 → 1), 1->2->1 (0+4 → 2).
        let arcs = [(0, 0, 3), (0, 1, 1), (1, 0, 1), (1, 2, 0), (2, 1, 4)];
        assert_eq!(karp_minimum_mean_cycle(3, &arcs), Some(Q::int(1)));
        let mut cycles = simple_cycles(3, &arcs);
        cycles.sort();
        assert_eq!(cycles, vec![(2, 2), (3, 1), (4, 2)]);
    }

    #[test]
    fn trajectory_of_a_lasso() {
        // 0 -> 1 (cost 2), 1 -> 1 (cost 5); goal 2 unreachable under this policy.
        let t = Tiny::from_lists(&[vec![(1, 2)], vec![(1, 5), (2, 1)], vec![]]);
        let tr = trajectory(&t, &[0, 0, TERMINATE, 0, 0, 0, 0], 0);
        assert_eq!(
            (tr.prefix_len, tr.prefix[0], tr.cycle_len, tr.cycle[0]),
            (1, 2, 1, 5)
        );
        assert!(!tr.terminates);
        assert_eq!(evaluate(&tr, Functional::Average, 1), Ext::Fin(Q::int(5)));
        assert_eq!(
            evaluate(&tr, Functional::HorizonTotal(3), 1),
            Ext::Fin(Q::int(12))
        );
    }
}
