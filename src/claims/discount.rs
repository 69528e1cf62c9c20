//! `truecost discount` (beyond the paper): the exact set of discount factors
//! `α ∈ (0, 1)` for which a discount-optimal policy fails to reach the goal from `x1`.
//!
//! A stationary policy's trajectory from `x1` is a simple path to a goal (it then terminates at
//! cost 0) or a *lasso* (a simple path into a cycle) avoiding the goals. Its discounted cost is
//! a rational function of `α`. A discount-optimal policy fails to reach the goal at `α` iff the
//! least lasso value is `≤` the least goal-path value (ties count: "a" discount-optimal policy).
//! The set changes only at roots in `(0,1)` of the differences of a lasso's and a path's value;
//! those roots are isolated exactly (Sturm sequences) and compared as algebraic numbers, and
//! membership is decided exactly at each root and at a rational point between consecutive ones.
//!
//! Lemmas used before enumerating (each proved in its doc line): no goal reachable → `(0,1)`;
//! no goal-avoiding cycle reachable → `∅`; all reachable move costs equal `c > 0` → `∅`
//! (a path of `d` moves costs `c(1−α^d)/(1−α) < c/(1−α)` ≤ any lasso).

use std::cmp::Ordering;

use num_traits::{One, Signed, Zero};

use crate::algebra::intervals::{pieces_of_members, DiscountSet, Piece, Point};
use crate::algebra::poly::{isolate_roots, Algebraic, Poly};
use crate::model::Problem;
use crate::value::Rational;

/// The most depth-first steps the enumeration of goal paths and lassos may take.
pub const MAX_SEARCH_STEPS: u64 = 2_000_000;

/// The most polynomial coefficients the enumerated trajectories may hold together (a lasso
/// of `k` stages holds about `2k`); bounds the memory of the enumeration.
pub const MAX_COEFFICIENTS: u64 = 1_000_000;

/// The most work the breakpoint search may do, checked before it starts: `pairs² · (d + 1)³`
/// with `pairs` = lassos × paths and `d` the largest degree of a difference polynomial (each
/// candidate root is tested against every pair by Sturm sequences of cubic cost). Measured: a
/// 3 × 3 grid with costs 1–4 (696 pairs, degree 17, ≈ 2.8·10⁹ units) took 5 minutes, so this
/// bound keeps a run to seconds.
pub const MAX_PAIR_WORK: u64 = 200_000_000;

/// The most bits one stage cost may take (numerator and denominator together, about 10³⁰⁰):
/// root isolation on polynomials whose coefficients are such costs grows with a high power of
/// their size (measured on a 3-state problem: costs of 10³⁰⁰ take about a second, 10¹⁰⁰⁰ a
/// minute and a half), so larger costs are refused before any work.
pub const MAX_COST_BITS: u64 = 1024;

/// Why the analysis cannot run. Each refusal names the bound that was reached (every
/// search with a combinatorial blow-up is bounded while it runs).
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum DiscountError {
    /// Too many trajectories for the exact enumeration.
    #[error("the problem has more than {0} goal paths or goal-avoiding lassos from x1: too large for the exact parametric analysis")]
    TooLarge(usize),
    /// A stage cost too large for exact root isolation in bounded time.
    #[error("a stage cost takes {0} bits (numerator and denominator): at most {MAX_COST_BITS} for the exact parametric analysis")]
    CostBits(u64),
    /// The enumeration went past one of its effort bounds.
    #[error("the enumeration of goal paths and lassos from x1 passed its bound of {bound} {what}: too large for the exact parametric analysis")]
    Effort {
        /// What was counted.
        what: &'static str,
        /// The bound.
        bound: u64,
    },
}

/// Discounted value of a stage sequence `prefix` then `cycle` forever, as `(N, D)`:
/// `N = P(α)(1 − α^k) + α^s C(α)`, `D = 1 − α^k` (`s`, `k` the lengths), formed in time linear
/// in `s + k` (no general polynomial product).
fn value(prefix: &[Rational], cycle: &[Rational]) -> (Poly, Poly) {
    if cycle.is_empty() {
        return (Poly::new(prefix.to_vec()), Poly::from_i64(&[1]));
    }
    let (s, k) = (prefix.len(), cycle.len());
    let mut n = vec![Rational::zero(); s + k];
    for (i, p) in prefix.iter().enumerate() {
        n[i] += p;
        n[i + k] -= p;
    }
    for (i, c) in cycle.iter().enumerate() {
        n[s + i] += c;
    }
    let mut d = vec![Rational::zero(); k + 1];
    d[0] = Rational::one();
    d[k] = -Rational::one();
    (Poly::new(n), Poly::new(d))
}

struct Trajectories {
    paths: Vec<(Poly, Poly)>,
    lassos: Vec<(Poly, Poly)>,
}

/// The bounds of the enumeration of trajectories, checked as it runs.
#[derive(Clone, Copy)]
struct Bounds {
    /// The most goal paths, and the most goal-avoiding lassos, stored.
    trajectories: usize,
    /// The most depth-first steps ([`MAX_SEARCH_STEPS`]).
    steps: u64,
    /// The most coefficients stored ([`MAX_COEFFICIENTS`]).
    coefficients: u64,
}

/// Every goal path and goal-avoiding lasso from `x1`, each bound checked as the search runs.
fn trajectories(problem: &Problem, bounds: Bounds) -> Result<Trajectories, DiscountError> {
    struct Walk<'a> {
        problem: &'a Problem,
        pos: Vec<usize>,
        costs: Vec<Rational>,
        out: Trajectories,
        bounds: Bounds,
        steps: u64,
        coefficients: u64,
    }
    impl Walk<'_> {
        /// Counts a stored trajectory of `stages` stages (its `(N, D)` holds at most
        /// `(stages + 1) + (stages + 1)` coefficients) and checks every bound.
        fn stored(&mut self, stages: usize) -> Result<(), DiscountError> {
            self.coefficients += 2 * stages as u64 + 2;
            let most = self.bounds.trajectories;
            if self.out.paths.len() > most || self.out.lassos.len() > most {
                return Err(DiscountError::TooLarge(most));
            }
            if self.coefficients > self.bounds.coefficients {
                return Err(DiscountError::Effort {
                    what: "polynomial coefficients",
                    bound: self.bounds.coefficients,
                });
            }
            Ok(())
        }
    }
    impl Walk<'_> {
        /// Enters `x` at the current depth: counts a search step; at a goal stores the path
        /// (and the search goes no further: `false`); otherwise marks `x` on the path (`true`).
        fn enter(&mut self, x: usize) -> Result<bool, DiscountError> {
            self.steps += 1;
            if self.steps > self.bounds.steps {
                return Err(DiscountError::Effort {
                    what: "search steps",
                    bound: self.bounds.steps,
                });
            }
            if self.problem.is_goal(x) {
                self.out.paths.push(value(&self.costs, &[]));
                self.stored(self.costs.len())?;
                return Ok(false);
            }
            self.pos[x] = self.costs.len();
            Ok(true)
        }
    }
    /// Depth-first over simple paths from `start`, with an explicit stack (a path may be as
    /// long as the problem has states: recursion would overflow the thread's stack). Each
    /// frame is a state on the path and the index of its next move to try.
    fn dfs(w: &mut Walk, start: usize) -> Result<(), DiscountError> {
        let problem = w.problem;
        let mut stack: Vec<(usize, usize)> = Vec::new();
        if w.enter(start)? {
            stack.push((start, 0));
        }
        while let Some((x, next)) = stack.last_mut() {
            let x = *x;
            let Some(m) = problem.moves(x).get(*next) else {
                // Every move of x tried: x leaves the path, and so does the move into it.
                w.pos[x] = usize::MAX;
                stack.pop();
                if !stack.is_empty() {
                    w.costs.pop();
                }
                continue;
            };
            *next += 1;
            let y = m.successor;
            w.costs.push(m.cost.clone());
            if w.pos[y] != usize::MAX {
                let s = w.pos[y];
                let lasso = value(&w.costs[..s], &w.costs[s..]);
                w.out.lassos.push(lasso);
                w.stored(w.costs.len())?;
                w.costs.pop();
            } else if w.enter(y)? {
                stack.push((y, 0));
            } else {
                w.costs.pop();
            }
        }
        Ok(())
    }
    let mut walk = Walk {
        problem,
        pos: vec![usize::MAX; problem.states()],
        costs: Vec::new(),
        out: Trajectories {
            paths: Vec::new(),
            lassos: Vec::new(),
        },
        bounds,
        steps: 0,
        coefficients: 0,
    };
    dfs(&mut walk, problem.initial())?;
    Ok(walk.out)
}

/// Checks, before the breakpoint search, that its work (`pairs² · (d + 1)³`, see
/// [`MAX_PAIR_WORK`]) stays within its bound.
fn check_pair_work(t: &Trajectories) -> Result<(), DiscountError> {
    let degree =
        |(n, d): &(Poly, Poly)| n.degree().unwrap_or(0).max(d.degree().unwrap_or(0)) as u64;
    let pairs = (t.lassos.len() as u64).saturating_mul(t.paths.len() as u64);
    let d = t.lassos.iter().map(degree).max().unwrap_or(0)
        + t.paths.iter().map(degree).max().unwrap_or(0);
    let work = pairs
        .saturating_mul(pairs)
        .saturating_mul((d + 1).saturating_pow(3));
    if work > MAX_PAIR_WORK {
        return Err(DiscountError::Effort {
            what: "units of breakpoint work (pairs^2 x (degree+1)^3)",
            bound: MAX_PAIR_WORK,
        });
    }
    Ok(())
}

fn min_value(list: &[(Poly, Poly)], a: &Rational) -> Option<Rational> {
    list.iter().map(|(n, d)| n.eval(a) / d.eval(a)).min()
}

fn member_rational(t: &Trajectories, a: &Rational) -> bool {
    match (min_value(&t.lassos, a), min_value(&t.paths, a)) {
        (None, _) => false,
        (Some(_), None) => true,
        (Some(l), Some(p)) => l <= p,
    }
}

fn member_algebraic(t: &Trajectories, b: &Algebraic) -> bool {
    if t.lassos.is_empty() {
        return false;
    }
    t.lassos.iter().any(|(nl, dl)| {
        t.paths.iter().all(|(np, dp)| {
            // sign(V_l − V_p) = sign(N_l D_p − N_p D_l) since D > 0 on (0,1).
            b.sign_of(&nl.mul(dp).sub(&np.mul(dl))) != Ordering::Greater
        })
    })
}

/// The exact set of `α ∈ (0,1)` for which a discount-optimal policy fails to reach a goal from
/// `x1`. `limit` bounds the number of paths and lassos enumerated; [`MAX_SEARCH_STEPS`],
/// [`MAX_COEFFICIENTS`] and [`MAX_PAIR_WORK`] bound the rest of the work, so a
/// large problem is refused within seconds, naming the bound it reached.
///
/// ```
/// use truecost::claims::discount::discount_set;
/// let p = truecost::model::file::from_json(r#"{"initial":0,"goals":[1],
///   "actions":[[{"to":0,"cost":"1"},{"to":1,"cost":"3"}],[]]}"#).unwrap();
/// // stay: 1/(1-a); go: 3. Staying is optimal iff a <= 2/3.
/// let s = discount_set(&p, 1000).unwrap();
/// assert_eq!(s.pieces.len(), 1);
/// assert!(s.pieces[0].hi_closed);
/// ```
pub fn discount_set(problem: &Problem, limit: usize) -> Result<DiscountSet, DiscountError> {
    let whole = |method: &str| DiscountSet {
        pieces: vec![Piece {
            lo: Point::Zero,
            lo_closed: false,
            hi: Point::One,
            hi_closed: false,
        }],
        method: method.into(),
    };
    let empty = |method: &str| DiscountSet {
        pieces: Vec::new(),
        method: method.into(),
    };
    let bits = (0..problem.states())
        .flat_map(|x| problem.moves(x))
        .map(|m| m.cost.numer().bits() + m.cost.denom().bits())
        .max()
        .unwrap_or(0);
    if bits > MAX_COST_BITS {
        return Err(DiscountError::CostBits(bits));
    }
    if problem.is_goal(problem.initial()) {
        return Ok(empty("x1 is a goal: every policy has reached it"));
    }
    // Reachability without passing a goal.
    let n = problem.states();
    let mut seen = vec![false; n];
    seen[problem.initial()] = true;
    let mut stack = vec![problem.initial()];
    let mut goal_reachable = false;
    let mut costs: Vec<Rational> = Vec::new();
    while let Some(x) = stack.pop() {
        for m in problem.moves(x) {
            costs.push(m.cost.clone());
            if problem.is_goal(m.successor) {
                goal_reachable = true;
            } else if !seen[m.successor] {
                seen[m.successor] = true;
                stack.push(m.successor);
            }
        }
    }
    if !goal_reachable {
        return Ok(whole(
            "lemma: no goal is reachable from x1, so every policy fails to reach it",
        ));
    }
    // A goal-avoiding cycle exists iff the non-goal part reachable from x1 has a cycle; every
    // non-goal state there has a move (problem files require it), so test via the core.
    let mut core: Vec<bool> = seen.clone();
    loop {
        let mut changed = false;
        for x in 0..n {
            if core[x] && !problem.moves(x).iter().any(|m| core[m.successor]) {
                core[x] = false;
                changed = true;
            }
        }
        if !changed {
            break;
        }
    }
    if !core.iter().any(|&c| c) {
        return Ok(empty(
            "lemma: no goal-avoiding cycle is reachable from x1, so every policy reaches a goal",
        ));
    }
    if costs.iter().all(|c| c == &costs[0]) && costs[0].is_positive() {
        return Ok(empty(
            "lemma: every reachable move costs the same c > 0; a goal path of d moves costs c(1-a^d)/(1-a) < c/(1-a), \
the cost of any lasso",
        ));
    }
    let bounds = Bounds {
        trajectories: limit,
        steps: MAX_SEARCH_STEPS,
        coefficients: MAX_COEFFICIENTS,
    };
    let t = trajectories(problem, bounds)?;
    check_pair_work(&t)?;
    // Candidate breakpoints.
    let mut polys: Vec<Poly> = Vec::new();
    for (nl, dl) in &t.lassos {
        for (np, dp) in &t.paths {
            let f = nl.mul(dp).sub(&np.mul(dl));
            if !f.is_zero() {
                // Roots at 0 never lie in (0,1): divide out the factors of x.
                let mut f = f;
                while f.coefficients().first().is_some_and(|c| c.is_zero()) {
                    f = f.div_rem(&Poly::monomial(1)).0;
                }
                let sf = f.squarefree();
                if !polys.contains(&sf) {
                    polys.push(sf);
                }
            }
        }
    }
    let mut roots: Vec<Algebraic> = Vec::new();
    for p in &polys {
        for r in isolate_roots(p, &Rational::zero(), &Rational::one()) {
            if !roots.iter().any(|q| q.compare(&r) == Ordering::Equal) {
                roots.push(r);
            }
        }
    }
    roots.sort_by(|a, b| a.compare(b));
    // Make the brackets disjoint, inside (0,1), and in increasing order.
    let half = |r: &mut Algebraic| {
        let w = &r.hi - &r.lo;
        r.refine_to(&(w / Rational::from_integer(2.into())));
    };
    for i in 0..roots.len() {
        while roots[i].lo.is_zero() || roots[i].hi >= Rational::one() {
            half(&mut roots[i]);
        }
        if i > 0 {
            while roots[i - 1].hi >= roots[i].lo {
                half(&mut roots[i - 1]);
                half(&mut roots[i]);
            }
        }
    }
    // Membership on the gaps (at a rational strictly inside) and at the roots.
    let mut points: Vec<(Point, bool)> = Vec::new(); // each root and whether it is in the set
    let mut gaps: Vec<bool> = Vec::new();
    let two = Rational::from_integer(2.into());
    let mut lo = Rational::zero();
    for r in &roots {
        gaps.push(member_rational(&t, &((&lo + &r.lo) / &two)));
        points.push((Point::Root(r.clone()), member_algebraic(&t, r)));
        lo = r.hi.clone();
    }
    gaps.push(member_rational(&t, &((&lo + Rational::one()) / &two)));
    let ends: Vec<Point> = points.iter().map(|p| p.0.clone()).collect();
    let mut member = Vec::with_capacity(gaps.len() + points.len());
    for (i, &g) in gaps.iter().enumerate() {
        member.push(g);
        if let Some(p) = points.get(i) {
            member.push(p.1);
        }
    }
    let pieces = pieces_of_members(&ends, &member);
    Ok(DiscountSet {
        pieces,
        method: format!(
            "exact parametric analysis: {} goal paths and {} goal-avoiding lassos from x1, {} breakpoint candidates in (0,1)",
            t.paths.len(),
            t.lassos.len(),
            roots.len()
        ),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::claims::tiny::Tiny;

    /// The search with these bounds: the numbers of paths and lassos, or its refusal.
    fn search(
        lists: &[Vec<(u8, u8)>],
        most: usize,
        steps: u64,
        coefficients: u64,
    ) -> Result<(usize, usize), DiscountError> {
        let p: Problem = Tiny::from_lists(lists).to_problem();
        let bounds = Bounds {
            trajectories: most,
            steps,
            coefficients,
        };
        trajectories(&p, bounds).map(|t| (t.paths.len(), t.lassos.len()))
    }

    /// The enumeration's bounds at their edges, worked out by hand. Problem A: `0 → 1`, `0 ↺`,
    /// `1 → 2` (goal), `1 → 0`. The search visits 0, 1, 2 (3 steps) and stores the path
    /// 0 1 2 (2 stages: 6 coefficients), the lasso 0 1 0 (2 stages: 6) and the lasso 0 0
    /// (1 stage: 4): 16 coefficients, 1 path, 2 lassos. Each bound is met exactly, then passed
    /// by one.
    #[test]
    fn the_bounds_of_the_enumeration_by_hand() {
        let a = [vec![(1, 1), (0, 2)], vec![(2, 1), (0, 1)], vec![]];
        assert_eq!(search(&a, 2, 3, 16), Ok((1, 2)));
        let refused = |what, bound| Err(DiscountError::Effort { what, bound });
        assert_eq!(search(&a, 2, 2, 16), refused("search steps", 2));
        assert_eq!(search(&a, 2, 3, 15), refused("polynomial coefficients", 15));
        let too_many = |most| Err(DiscountError::TooLarge(most));
        // Two lassos, one path: one lasso too many.
        assert_eq!(search(&a, 1, 3, 16), too_many(1));
        // Problem B: `0 → 1` (goal), `0 ↺`: one path, one lasso, each exactly at the bound 1.
        let b = [vec![(1, 1), (0, 2)], vec![]];
        assert_eq!(search(&b, 1, 2, 8), Ok((1, 1)));
        assert_eq!(search(&b, 0, 2, 8), too_many(0));
        // Problem C: two moves `0 → 1` (goal), no lasso: one path too many.
        let c = [vec![(1, 1), (1, 2)], vec![]];
        assert_eq!(search(&c, 2, 3, 8), Ok((2, 0)));
        assert_eq!(search(&c, 1, 3, 8), too_many(1));
    }

    /// A path as long as the problem has states is searched without recursion: a chain of
    /// 100,000 states (far deeper than a test thread's stack allows a recursive search) whose
    /// last state reaches the goal or loops on itself gives one path and one lasso, each of
    /// 100,000 stages.
    #[test]
    fn a_long_chain_is_searched_without_overflowing_the_stack() {
        use crate::model::Move;
        let n = 100_000;
        let one = Rational::one();
        let mut actions: Vec<Vec<Move>> = (0..n - 1)
            .map(|x| {
                vec![Move {
                    successor: x + 1,
                    cost: one.clone(),
                }]
            })
            .collect();
        actions.push(vec![
            Move {
                successor: n,
                cost: one.clone(),
            },
            Move {
                successor: n - 1,
                cost: one.clone(),
            },
        ]);
        actions.push(vec![]);
        let p = Problem::new(actions, 0, vec![n]).unwrap();
        let bounds = Bounds {
            trajectories: 10,
            steps: MAX_SEARCH_STEPS,
            coefficients: MAX_COEFFICIENTS,
        };
        let t = trajectories(&p, bounds).unwrap();
        assert_eq!((t.paths.len(), t.lassos.len()), (1, 1));
        assert_eq!(t.paths[0].0.degree(), Some(n - 1), "n stages: degree n - 1");
        assert_eq!(t.lassos[0].1.degree(), Some(1), "a cycle of one stage");
    }

    /// Stage costs are bounded in size before any work: 10³⁰⁰ (997 + 1 bits: numerator and
    /// denominator) is analysed, 10³⁰⁹ (1027 + 1 bits) is refused at once, naming the bound.
    #[test]
    fn huge_costs_are_refused_before_the_analysis() {
        let file = |cost: &str| {
            crate::model::file::from_json(&format!(
                r#"{{"initial":0,"goals":[2],"actions":[[{{"to":0,"cost":"{cost}"}},{{"to":1,"cost":"3"}}],[{{"to":0,"cost":"1"}},{{"to":2,"cost":"{cost}"}}],[]]}}"#
            ))
            .unwrap()
        };
        assert!(discount_set(&file("1e300"), 1000).is_ok());
        let started = std::time::Instant::now();
        assert_eq!(
            discount_set(&file("1e309"), 1000),
            Err(DiscountError::CostBits(1028))
        );
        assert!(started.elapsed().as_millis() < 1000);
    }
}
