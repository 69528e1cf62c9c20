//! Independent oracles: enumeration of every deterministic stationary policy
//! of a tiny problem, the exact cost of each policy's trajectory under every functional of
//! docs/spec.md §1, exact minimum mean cycles by Karp's algorithm and by enumerating simple cycles.
//!
//! Nothing here knows the formulas of docs/spec.md §6: a claim is checked by comparing what these
//! brute-force computations give with what the claim states.

use std::fmt;

use super::exact::{power, ExactInt, Ext, Frac, FracExt, Q};
use super::tiny::{Tiny, MAX_DEGREE, MAX_STATES};

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
    // The choices of each state, in order: `choices[x][..count[x]]`.
    let mut choices = [[0u8; MAX_DEGREE + 1]; MAX_STATES];
    let mut count = [0usize; MAX_STATES];
    for x in 0..n {
        let deg = t.deg[x] as usize;
        let goal = t.is_goal(x);
        let first_move = usize::from(goal);
        if goal {
            choices[x][0] = TERMINATE;
        }
        let moves = if !goal || goal_may_move { deg } else { 0 };
        for k in 0..moves {
            choices[x][first_move + k] = k as Choice;
        }
        count[x] = first_move + moves;
    }
    // The policies in the order of an odometer over the states' choices, state 0 the most
    // significant digit: the `i`-th policy's digits are `i` in the mixed radix `count`.
    let total: usize = count[..n].iter().product();
    let mut out = vec![[0u8; MAX_STATES]; total];
    for (i, p) in out.iter_mut().enumerate() {
        let mut rest = i;
        for x in (0..n).rev() {
            p[x] = choices[x][rest % count[x]];
            rest /= count[x];
        }
    }
    out
}

/// The stage costs of a trajectory: `prefix` then `cycle` repeated forever. A trajectory that
/// terminates at a goal has the cycle `[0]` (frozen, docs/spec.md §1) and `terminates = true`.
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

/// A functional of a stage sequence that is linear in the stages (docs/spec.md §1, §6 C2); its discount
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
        self.to_string()
    }
}

impl<I: ExactInt> fmt::Display for Functional<I> {
    /// `total`, `discounted(alpha=1/2)`, `average over 4 stages`, … (formatted only when
    /// printed: the oracles that build a `Functional` never format it).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Functional::Total => write!(f, "total"),
            Functional::Discounted(a) => write!(f, "discounted(alpha={a})"),
            Functional::Average => write!(f, "average"),
            Functional::HorizonTotal(k) => write!(f, "total over {k} stages"),
            Functional::HorizonDiscounted(k, a) => {
                write!(f, "discounted(alpha={a}) over {k} stages")
            }
            Functional::HorizonAverage(k) => write!(f, "average over {k} stages"),
        }
    }
}

/// The stages of a trajectory in order (the prefix, then the cycle forever), with the stage
/// values mapped by `sign` (`1` for costs, `-1` for rewards `r = -l`). The position in the cycle
/// wraps by comparison with its length, never by a remainder: a model checker unrolls the loops
/// that read stages, and a remainder by the symbolic cycle length would be a divider circuit in
/// every unrolled copy.
#[derive(Clone, Copy, Debug)]
struct Stages<'a> {
    tr: &'a Trajectory,
    sign: i64,
    /// Whether the next stage is in the cycle.
    in_cycle: bool,
    /// The next stage's index in the prefix or the cycle.
    at: usize,
}

impl<'a> Stages<'a> {
    fn new(tr: &'a Trajectory, sign: i64) -> Stages<'a> {
        Stages {
            tr,
            sign,
            in_cycle: tr.prefix_len == 0,
            at: 0,
        }
    }
}

impl Iterator for Stages<'_> {
    type Item = i64;

    #[inline]
    fn next(&mut self) -> Option<i64> {
        let v = if self.in_cycle {
            let v = self.tr.cycle[self.at];
            self.at += 1;
            if self.at == self.tr.cycle_len {
                self.at = 0;
            }
            v
        } else {
            let v = self.tr.prefix[self.at];
            self.at += 1;
            if self.at == self.tr.prefix_len {
                (self.in_cycle, self.at) = (true, 0);
            }
            v
        };
        Some(self.sign * v)
    }
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
                    (0..tr.prefix_len)
                        .map(|k| (sign * tr.prefix[k]) as i128)
                        .sum(),
                ))
            }
        }
        Functional::Discounted(a) => {
            let mut value = Q::ZERO;
            let mut power = Q::ONE;
            for k in 0..tr.prefix_len {
                value = value + power * Q::int((sign * tr.prefix[k]) as i128);
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
        Functional::HorizonTotal(h) => Ext::Fin(Q::int(
            Stages::new(tr, sign).take(h).map(|v| v as i128).sum(),
        )),
        Functional::HorizonDiscounted(h, a) => {
            let mut value = Q::ZERO;
            let mut power = Q::ONE;
            for v in Stages::new(tr, sign).take(h) {
                value = value + power * Q::int(v as i128);
                power = power * a;
            }
            Ext::Fin(value)
        }
        Functional::HorizonAverage(h) => Ext::Fin(Q::new(
            Stages::new(tr, sign).take(h).map(|v| v as i128).sum(),
            h as i128,
        )),
    }
}

/// `f(0) + … + f(n − 1)`, checked.
#[inline]
fn sum_of<I: ExactInt>(n: usize, f: impl Fn(usize) -> I) -> I {
    (0..n).fold(I::ZERO, |acc, k| acc.add_exact(f(k)))
}

/// The sum of the first `h` stages of `tr` (values mapped by `sign`), checked.
#[inline]
fn horizon_sum<I: ExactInt>(tr: &Trajectory, h: usize, sign: i64) -> I {
    Stages::new(tr, sign)
        .take(h)
        .fold(I::ZERO, |acc, v| acc.add_exact(I::from_i64(v)))
}

/// The same value as [`evaluate`], as an unnormalised fraction (the engines' fast path):
/// discounted sums use `α = a/b` with integer numerator and denominator over `b^p (b^c − a^c)`.
/// Generic over the integer width `I`; every operation is checked (an overflow panics).
pub fn evaluate_fast<I: ExactInt>(
    tr: &Trajectory,
    functional: Functional<I>,
    sign: i64,
) -> FracExt<I> {
    let s = |k: usize| I::from_i64(sign * tr.prefix[k]);
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
            n: horizon_sum(tr, h, sign),
            d: I::ONE,
        }),
        Functional::HorizonDiscounted(h, alpha) => {
            let (a, b) = (alpha.numer(), alpha.denom());
            let n = Stages::new(tr, sign)
                .take(h)
                .enumerate()
                .fold(I::ZERO, |acc, (k, v)| {
                    acc.add_exact(
                        I::from_i64(v)
                            .mul_exact(power(a, k))
                            .mul_exact(power(b, h - 1 - k)),
                    )
                });
            FracExt::Fin(Frac {
                n,
                d: power(b, h.saturating_sub(1)),
            })
        }
        Functional::HorizonAverage(h) => FracExt::Fin(Frac {
            n: horizon_sum(tr, h, sign),
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

/// One node of the current path of a depth-first search over simple paths
/// (`simple_paths`): the node, the index of its next arc to examine, and the weight and the
/// number of arcs of the path up to the node.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Frame {
    node: usize,
    next: usize,
    weight: i64,
    arcs: usize,
}

/// What a depth-first search over simple paths does with an arc (`simple_paths`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Step {
    /// Ignores it.
    Skip,
    /// The path ends with it (a path is found).
    End,
    /// Extends the path with it and searches on from its head.
    Enter,
}

/// Runs `search` with a fixed-capacity stack of frames and the on-path flags of `n` nodes: fixed
/// arrays when `n` is at most [`MAX_STATES`] (every tiny problem, every problem of the Kani
/// harnesses: no length there is symbolic), buffers of `n` entries otherwise. A search over
/// simple paths keeps at most one frame per node.
pub(crate) fn with_search_space<R>(
    n: usize,
    search: impl FnOnce(&mut [Frame], &mut [bool]) -> R,
) -> R {
    if n <= MAX_STATES {
        search(
            &mut [Frame::default(); MAX_STATES],
            &mut [false; MAX_STATES],
        )
    } else {
        search(&mut vec![Frame::default(); n], &mut vec![false; n])
    }
}

/// Depth-first search over the simple paths from `start`, iterative, on an explicit stack
/// (`frames`, fixed capacity: one frame per node on the current path). `arc(v, k)` is the
/// `k`-th arc `(head, weight)` of `v` (`None` past the last); `step(head, on_path)` says what
/// the search does with an arc; `visit(step, weight, arcs)` is called for every arc that ends
/// or extends the path (`step` is [`Step::End`] or [`Step::Enter`]), with the weight and the
/// number of arcs of the path it ends or extends to, in depth-first order (an arc's whole
/// subtree before the next arc); an error from `visit` stops the search. `on_path` is all
/// `false` on entry and, unless the search stopped, on return.
///
/// Each round of the outer loop pops one frame, after scanning arcs down from the frame on top
/// (an inner loop): on the C4 harnesses' problems (3 non-goal states, at most 2 moves each) at
/// most 7 frames and at most 6 arcs per round, within their unwind bound (9).
pub(crate) fn simple_paths<E>(
    frames: &mut [Frame],
    on_path: &mut [bool],
    start: usize,
    arc: impl Fn(usize, usize) -> Option<(usize, i64)>,
    step: impl Fn(usize, bool) -> Step,
    mut visit: impl FnMut(Step, i64, usize) -> Result<(), E>,
) -> Result<(), E> {
    frames[0] = Frame {
        node: start,
        next: 0,
        weight: 0,
        arcs: 0,
    };
    on_path[start] = true;
    let mut len = 1;
    while len > 0 {
        loop {
            let top = frames[len - 1];
            let Some((head, w)) = arc(top.node, top.next) else {
                break;
            };
            frames[len - 1].next = top.next + 1;
            let s = step(head, on_path[head]);
            if s == Step::Skip {
                continue;
            }
            let (weight, arcs) = (top.weight + w, top.arcs + 1);
            visit(s, weight, arcs)?;
            if s == Step::Enter {
                on_path[head] = true;
                frames[len] = Frame {
                    node: head,
                    next: 0,
                    weight,
                    arcs,
                };
                len += 1;
            }
        }
        len -= 1;
        on_path[frames[len].node] = false;
    }
    Ok(())
}

/// Every simple cycle of the graph (each once, rooted at its smallest node) as
/// `(total weight, length)`, in depth-first order: roots in increasing order, arcs in the
/// order of `arcs`.
///
/// The search from each root follows only arcs into nodes `≥ root` that can reach the root
/// again among such nodes (a backward search first), over the arcs in compressed rows: a node on
/// no cycle through the root is never entered, so an acyclic graph costs `O(n·m)` whatever its
/// number of paths. Both searches are iterative, on stacks of fixed capacity (`simple_paths`);
/// they run twice, to count the cycles and then to write them into a buffer of that length.
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
    // Two runs of one search: the first counts the cycles, the second writes them into a
    // buffer of that length (no buffer grows while a search runs).
    let mut count = 0;
    each_simple_cycle(n, arcs, |_, _| count += 1);
    let mut out = vec![(0i64, 0usize); count];
    let mut len = 0;
    each_simple_cycle(n, arcs, |weight, arcs| {
        out[len] = (weight, arcs);
        len += 1;
    });
    out
}

/// Calls `found(weight, length)` for every simple cycle, in the order of [`simple_cycles`].
/// The arcs are kept in compressed rows (forward and backward), built by counting.
fn each_simple_cycle(n: usize, arcs: &[(usize, usize, i64)], mut found: impl FnMut(i64, usize)) {
    // Row `v` of the forward arcs is `forward[out_first[v]..out_first[v + 1]]`, in the order of
    // `arcs`; likewise the tails of the arcs into `v` in `backward`.
    let mut out_first = vec![0usize; n + 1];
    let mut in_first = vec![0usize; n + 1];
    for &(a, b, _) in arcs {
        out_first[a + 1] += 1;
        in_first[b + 1] += 1;
    }
    for v in 0..n {
        out_first[v + 1] += out_first[v];
        in_first[v + 1] += in_first[v];
    }
    let mut forward = vec![(0usize, 0i64); arcs.len()];
    let mut backward = vec![0usize; arcs.len()];
    let mut out_fill = out_first.clone();
    let mut in_fill = in_first.clone();
    for &(a, b, w) in arcs {
        forward[out_fill[a]] = (b, w);
        out_fill[a] += 1;
        backward[in_fill[b]] = a;
        in_fill[b] += 1;
    }
    let mut back = vec![false; n];
    // The backward search's stack: each node enters it at most once per root.
    let mut stack = vec![0usize; n];
    with_search_space(n, |frames, on_path| {
        for root in 0..n {
            // The nodes >= root that reach root through nodes >= root.
            back.iter_mut().for_each(|b| *b = false);
            back[root] = true;
            stack[0] = root;
            let mut len = 1;
            while len > 0 {
                len -= 1;
                let v = stack[len];
                for &a in &backward[in_first[v]..in_first[v + 1]] {
                    if a > root && !back[a] {
                        back[a] = true;
                        stack[len] = a;
                        len += 1;
                    }
                }
            }
            let searched = simple_paths(
                frames,
                on_path,
                root,
                |v, k| forward[out_first[v]..out_first[v + 1]].get(k).copied(),
                |b, on| {
                    if b == root {
                        Step::End
                    } else if b > root && back[b] && !on {
                        Step::Enter
                    } else {
                        Step::Skip
                    }
                },
                |s, weight, len| {
                    if s == Step::End {
                        found(weight, len);
                    }
                    Ok::<(), std::convert::Infallible>(())
                },
            );
            if let Err(never) = searched {
                match never {}
            }
        }
    });
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

/// Every simple path from `x1 = 0` to the goal as `(cost L, number of states S)`, in
/// depth-first order (moves in each state's order); iterative, on a stack of fixed capacity
/// (`simple_paths`).
pub fn simple_goal_paths(t: &Tiny) -> Vec<(i64, usize)> {
    if t.is_goal(0) {
        return vec![(0, 1)];
    }
    let mut out = Vec::new();
    let searched = with_search_space(t.states(), |frames, on| {
        simple_paths(
            frames,
            on,
            0,
            |x, k| t.moves(x).get(k).map(|m| (m.to as usize, m.cost as i64)),
            |y, on| {
                if on {
                    Step::Skip
                } else if t.is_goal(y) {
                    Step::End
                } else {
                    Step::Enter
                }
            },
            |s, cost, moves| {
                if s == Step::End {
                    out.push((cost, moves + 1));
                }
                Ok::<(), std::convert::Infallible>(())
            },
        )
    });
    if let Err(never) = searched {
        match never {}
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every sequence of `len` distinct nodes of `0..n`, in lexicographic order (an odometer
    /// over `[0, n)^len`, the tuples with a repeated node dropped).
    fn node_sequences(n: usize, len: usize) -> Vec<Vec<usize>> {
        let mut out = Vec::new();
        let mut digits = vec![0usize; len];
        loop {
            if (0..len).all(|i| !digits[..i].contains(&digits[i])) {
                out.push(digits.clone());
            }
            let Some(k) = (0..len).rev().find(|&k| digits[k] + 1 < n) else {
                return out;
            };
            digits[k] += 1;
            digits[k + 1..].iter_mut().for_each(|d| *d = 0);
        }
    }

    /// Every way to walk the node sequence `nodes` (closed back to its first node if `closed`)
    /// over the parallel arcs of `lists` (`lists[v]`: `v`'s arcs in order): per walk, the
    /// positions of the arcs taken in their lists, and the walk's weight and number of arcs.
    fn walks(lists: &[Vec<(usize, i64)>], nodes: &[usize], closed: bool) -> Vec<(Vec<usize>, i64)> {
        let hops: Vec<(usize, usize)> = (0..nodes.len())
            .filter_map(|i| match nodes.get(i + 1) {
                Some(&b) => Some((nodes[i], b)),
                None => closed.then_some((nodes[i], nodes[0])),
            })
            .collect();
        // The choices of parallel arcs for every hop: an odometer over their positions.
        let choices: Vec<Vec<usize>> = hops
            .iter()
            .map(|&(a, b)| {
                (0..lists[a].len())
                    .filter(|&k| lists[a][k].0 == b)
                    .collect()
            })
            .collect();
        if choices.iter().any(Vec::is_empty) {
            return Vec::new();
        }
        let mut out = Vec::new();
        let mut at = vec![0usize; hops.len()];
        loop {
            let positions: Vec<usize> = (0..hops.len()).map(|i| choices[i][at[i]]).collect();
            let weight = (0..hops.len())
                .map(|i| lists[hops[i].0][positions[i]].1)
                .sum();
            out.push((positions, weight));
            let Some(k) = (0..hops.len())
                .rev()
                .find(|&k| at[k] + 1 < choices[k].len())
            else {
                return out;
            };
            at[k] += 1;
            at[k + 1..].iter_mut().for_each(|d| *d = 0);
        }
    }

    /// The simple cycles by brute force over node sequences (rooted at their least node), in
    /// depth-first order: by root, then by the positions of their arcs in their lists.
    fn brute_cycles(n: usize, arcs: &[(usize, usize, i64)]) -> Vec<(i64, usize)> {
        let mut lists = vec![Vec::new(); n];
        for &(a, b, w) in arcs {
            lists[a].push((b, w));
        }
        let mut found = Vec::new();
        for len in 1..=n {
            for nodes in node_sequences(n, len) {
                if nodes.iter().all(|&v| v >= nodes[0]) {
                    for (positions, w) in walks(&lists, &nodes, true) {
                        found.push(((nodes[0], positions), (w, len)));
                    }
                }
            }
        }
        found.sort();
        found.into_iter().map(|(_, c)| c).collect()
    }

    /// A small deterministic generator for the test graphs.
    fn draw(seed: &mut u64, k: u64) -> u64 {
        *seed ^= *seed << 13;
        *seed ^= *seed >> 7;
        *seed ^= *seed << 17;
        *seed % k
    }

    /// Move lists of a random tiny problem: 1 to `MAX_STATES` states, 0 to 3 moves each, costs
    /// below `costs`.
    fn random_lists(seed: &mut u64, costs: u64) -> Vec<Vec<(u8, u8)>> {
        let n = 1 + draw(seed, MAX_STATES as u64) as usize;
        (0..n)
            .map(|_| {
                (0..draw(seed, 4))
                    .map(|_| (draw(seed, n as u64) as u8, draw(seed, costs) as u8))
                    .collect()
            })
            .collect()
    }

    /// The iterative search enumerates the simple cycles of the brute force, in the same order,
    /// on random graphs of 1 to 5 nodes with parallel arcs and self-loops, on a 7-node ring with
    /// chords (its 7-cycle fills the fixed array of `MAX_STATES` frames) and on an 8-node ring
    /// (beyond the array: the buffer).
    #[test]
    fn simple_cycles_are_the_brute_forces_in_its_order() {
        let mut seed = 0x9E37_79B9_7F4A_7C15u64;
        let mut nonempty = 0;
        for _ in 0..1500 {
            let n = 1 + draw(&mut seed, 5) as usize;
            let m = draw(&mut seed, 3 * n as u64 + 1);
            let arcs: Vec<(usize, usize, i64)> = (0..m)
                .map(|_| {
                    let a = draw(&mut seed, n as u64) as usize;
                    let b = draw(&mut seed, n as u64) as usize;
                    (a, b, draw(&mut seed, 7) as i64 - 2)
                })
                .collect();
            let got = simple_cycles(n, &arcs);
            assert_eq!(got, brute_cycles(n, &arcs), "{n} {arcs:?}");
            nonempty += usize::from(!got.is_empty());
        }
        assert!(nonempty > 500, "{nonempty}");
        for n in [MAX_STATES, MAX_STATES + 1] {
            let mut arcs: Vec<(usize, usize, i64)> = (0..n).map(|v| (v, (v + 1) % n, 1)).collect();
            arcs.extend([(3, 1, 5), (5, 0, 2), (2, 2, 9), (n - 1, 0, 4)]);
            let got = simple_cycles(n, &arcs);
            assert!(
                got.contains(&(n as i64, n)),
                "the Hamiltonian cycle: {got:?}"
            );
            assert_eq!(got, brute_cycles(n, &arcs));
        }
    }

    /// The policies in the order of the literal construction: one state at a time, every
    /// policy so far extended by each of the state's choices in turn (termination first at the
    /// goal), on random problems of 1 to 7 states with 0 to 3 moves per state.
    #[test]
    fn policies_are_the_state_by_state_extension_in_its_order() {
        let mut seed = 0x2545_F491_4F6C_DD1Du64;
        let mut many = 0;
        for _ in 0..400 {
            let lists = random_lists(&mut seed, 3);
            let n = lists.len();
            let t = Tiny::from_lists(&lists);
            for goal_may_move in [false, true] {
                let mut literal = vec![[0u8; MAX_STATES]];
                for x in 0..n {
                    let mut choices = Vec::new();
                    if t.is_goal(x) {
                        choices.push(TERMINATE);
                    }
                    if !t.is_goal(x) || goal_may_move {
                        choices.extend(0..t.moves(x).len() as u8);
                    }
                    let mut next = Vec::new();
                    for p in &literal {
                        for &c in &choices {
                            let mut q = *p;
                            q[x] = c;
                            next.push(q);
                        }
                    }
                    literal = next;
                }
                let got = policies(&t, goal_may_move);
                assert_eq!(got, literal, "{lists:?} {goal_may_move}");
                many += usize::from(got.len() > 8);
            }
        }
        assert!(many > 50, "{many}");
    }

    /// The goal paths of the brute force (node sequences from 0 whose last node, and only it,
    /// is the goal) in depth-first order: by the positions of their moves in their lists.
    fn brute_goal_paths(t: &Tiny) -> Vec<(i64, usize)> {
        let n = t.states();
        let lists: Vec<Vec<(usize, i64)>> = (0..n)
            .map(|x| {
                t.moves(x)
                    .iter()
                    .map(|m| (m.to as usize, m.cost as i64))
                    .collect()
            })
            .collect();
        let mut found = Vec::new();
        for len in 1..=n {
            for nodes in node_sequences(n, len) {
                let ends = nodes.iter().position(|&v| t.is_goal(v)) == Some(len - 1);
                if nodes[0] == 0 && ends {
                    for (positions, w) in walks(&lists, &nodes, false) {
                        found.push((positions, (w, len)));
                    }
                }
            }
        }
        found.sort();
        found.into_iter().map(|(_, p)| p).collect()
    }

    /// `simple_goal_paths` and C4's `Instance::goal_paths` (the same search, through the
    /// fixed array or, past `MAX_STATES` states, the buffer) list the brute force's goal paths
    /// in its order, on random tiny problems with 1 to 7 states, on a chain of 7 states with
    /// parallel moves (its longest path keeps 6 frames) and on a chain of 8 states.
    #[test]
    fn goal_paths_are_the_brute_forces_in_its_order() {
        use crate::claims::c4::Instance;
        let mut seed = 0x0123_4567_89AB_CDEFu64;
        let mut several = 0;
        let check = |t: &Tiny, inst: &Instance| {
            let brute = brute_goal_paths(t);
            assert_eq!(simple_goal_paths(t), brute, "{}", t.describe());
            let wide: Vec<(i64, usize)> = inst
                .goal_paths(u64::MAX)
                .expect("no bound")
                .into_iter()
                .map(|(l, s)| (l, s as usize))
                .collect();
            assert_eq!(wide, brute, "{inst:?}");
            brute.len()
        };
        for _ in 0..1500 {
            let lists = random_lists(&mut seed, 5);
            let t = Tiny::from_lists(&lists);
            several += usize::from(check(&t, &Instance::from_tiny(&t)) >= 2);
        }
        assert!(several > 150, "{several}");
        let chain = |n: usize| -> Vec<Vec<(u8, u8)>> {
            (0..n)
                .map(|x| {
                    if x + 1 == n {
                        vec![]
                    } else {
                        vec![(x as u8 + 1, 1), (x as u8 + 1, 2), (0, 0)]
                    }
                })
                .collect()
        };
        let t = Tiny::from_lists(&chain(MAX_STATES));
        assert_eq!(check(&t, &Instance::from_tiny(&t)), 1 << (MAX_STATES - 1));
        // Eight states: a tiny problem cannot hold them; the instance (and the buffer) can.
        let lists = chain(MAX_STATES + 1);
        let inst = Instance {
            initial: 0,
            is_goal: (0..=MAX_STATES).map(|x| x == MAX_STATES).collect(),
            moves: lists
                .iter()
                .map(|l| l.iter().map(|&(y, c)| (y as usize, c as i64)).collect())
                .collect(),
        };
        let paths = inst.goal_paths(u64::MAX).expect("no bound");
        assert_eq!(paths.len(), 1 << MAX_STATES);
        // Depth-first: the cheapest first, the dearest last.
        assert_eq!(paths[0], (MAX_STATES as i64, MAX_STATES as i64 + 1));
        assert_eq!(
            paths[paths.len() - 1],
            (2 * MAX_STATES as i64, MAX_STATES as i64 + 1)
        );
    }

    /// The stages of a trajectory, read by position counters that wrap by comparison, are
    /// `prefix[k]` then `cycle[(k − p) mod c]`.
    #[test]
    fn stages_wrap_around_the_cycle() {
        for (prefix_len, cycle_len) in [(0, 1), (0, 3), (2, 1), (3, 4), (7, 7)] {
            let mut tr = Trajectory {
                prefix: [0; MAX_STATES],
                prefix_len,
                cycle: [0; MAX_STATES],
                cycle_len,
                terminates: false,
                visits_goal: false,
            };
            for k in 0..MAX_STATES {
                tr.prefix[k] = 10 + k as i64;
                tr.cycle[k] = 100 + k as i64;
            }
            let got: Vec<i64> = Stages::new(&tr, -1).take(40).collect();
            let want: Vec<i64> = (0..40)
                .map(|k| {
                    -if k < prefix_len {
                        tr.prefix[k]
                    } else {
                        tr.cycle[(k - prefix_len) % cycle_len]
                    }
                })
                .collect();
            assert_eq!(got, want, "{prefix_len} {cycle_len}");
        }
    }

    /// Functionals print as they are named in reports.
    #[test]
    fn functionals_print_their_names() {
        let half = Q::new(1, 2);
        let names: Vec<String> = [
            Functional::Total,
            Functional::Discounted(half),
            Functional::Average,
            Functional::HorizonTotal(3),
            Functional::HorizonDiscounted(3, half),
            Functional::HorizonAverage(4),
        ]
        .iter()
        .map(Functional::name)
        .collect();
        assert_eq!(
            names,
            [
                "total",
                "discounted(alpha=1/2)",
                "average",
                "total over 3 stages",
                "discounted(alpha=1/2) over 3 stages",
                "average over 4 stages"
            ]
        );
    }

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
