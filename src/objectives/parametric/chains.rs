//! Probes of a deterministic model with memory (module docs of [`super`], steps 1′–3).
//!
//! A deterministic policy's value at a state is a rational function fixed by the actions along
//! the state's successor chain, and an advantage polynomial is fixed by the action and the two
//! values it compares. Neighbouring regions of `(0, 1)` have policies that differ at a few
//! states, so nearly every advantage polynomial of a probe was met at the probe before (on
//! the benchmark grids of `export --grid`, over 99 % of them). [`ChainMemory`] keeps them
//! between probes:
//!
//! * **Values** are interned: a state's value is named by its action and its successor's
//!   value (a chain ending where the episode is over), or by the actions around its cycle
//!   from the state (a state on a cycle). Equal names have equal values, so each value
//!   polynomial is built once, from its successor's.
//! * **Advantages** are keyed by the action and the names of the two values; each polynomial
//!   is built once (as in the search without memory) and its roots in `(0, 1)` are all
//!   isolated, with the sign of the polynomial on every gap between them. The sign at a probe
//!   `t` is read off the roots (a probe at a root is refused, as without memory), and the
//!   region's ends are the walks from `t` over all of `(0, 1)` — the region of the full
//!   search, found without evaluating the advantages again.
//! * **Roots** are kept once each with a floating-point window around their bracket; a
//!   comparison that the windows cannot decide narrows the brackets for good (by halving, so
//!   they stay the brackets of the bisection) while they are wider than the windows' margin,
//!   then leaves it to the exact comparison; roots found equal join one class, and the order
//!   of classes found distinct is kept, so each exact comparison is made once and equal roots
//!   leave the probe as clones of one root.
//! * **The optimal policy at `t`** is found by exact policy iteration on these signs, started
//!   from the policy of the probe before (a neighbouring region's, usually a few switches
//!   away) or, at the first probe, from the floating-point policy iteration.
//!
//! The memory is cleared when it holds more than [`MAX_MEMORY_WORDS`] words of polynomial
//! coefficients (counted, so the analysis is the same on every machine). The work of a probe
//! is counted in words of the arithmetic it does: the polynomials it builds, the isolation of
//! their roots ([`isolation`]), every sign of a root's polynomial at a probe and every halving
//! of a bracket ([`AT_A_POINT`] times [`evaluation`]: degree-many products of numbers that grow
//! with the degree times the point's bits by numbers of the point's bits, so the square of the
//! point's words), 100 halvings per exact comparison of two roots, and 16 units per advantage
//! read from memory and per running state of each policy evaluated (hash lookups).

use std::cmp::Ordering;
use std::collections::HashMap;
use std::sync::Arc;

use num_bigint::BigInt;
use num_traits::{One, Zero};

use super::{
    advantage_polynomial, between, chains, float_optimum, int_poly, one_point, poly_add_scaled,
    successor, zero_point, Advantage, ParametricError, Region,
};
use crate::algebra::poly::roots::{integer_sign, roots_in_unit_interval, Root};
use crate::model::StateId;
use crate::objectives::Model;
use crate::value::Rational;

/// The most words of polynomial coefficients [`ChainMemory`] keeps (about 256 MiB); past it
/// the memory is cleared before the next probe.
pub const MAX_MEMORY_WORDS: usize = 1 << 25;

/// The name of a value (module docs): equal names, equal rational functions.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
enum Name {
    /// The state's action and its successor's value (`None`: the episode is over there).
    Path(usize, Option<u32>),
    /// The actions around the state's cycle, from the state.
    Cycle(Vec<usize>),
}

/// A value `N / D`: the index of its denominator (`R`, or `R (1 − α^k)`) and its numerator.
struct Value {
    den: usize,
    num: Vec<BigInt>,
}

/// The counted work of reading an advantage from memory, and of naming one state's value in a
/// policy evaluation (hash lookups: measured at about 16 words of arithmetic each).
const READ: u128 = 16;

/// The margin of the floating-point windows of [`Points`]: far above the error of rounding a
/// rational in `[0, 1]` to the nearest `f64` (at most `2^-54`).
const MARGIN: f64 = 1.0 / (1u64 << 50) as f64;

/// The most halvings spent separating two distinct roots' windows, or a root's window from a
/// probe, before the exact comparison is left to decide each time.
const MAX_SEPARATION: usize = 96;

/// Halvings of two overlapping windows before [`Root::compare`] decides (it tells equal roots
/// apart from distinct ones closer than the windows).
const SEPARATION_BEFORE_EXACT: usize = 24;

/// A bracket narrower than this many times [`MARGIN`] is not halved to part windows: its
/// window is then within a margin of its narrowest, so halving it cannot part two windows
/// less than a margin apart, and would only lengthen the bracket's numbers (each halving adds
/// a bit to them, and a sign there costs the square of their words: [`evaluation`]).
const FINE: f64 = 1.0;

/// The counted work of a sign of a root's polynomial at a probe or at a bracket's midpoint,
/// in [`evaluation`]s: besides Horner's products, the midpoint's normalisation, the root's
/// bracket and the window's conversion to floating point. Measured in release (7 Dec 2026,
/// timed inside one run each, on the twelve chains of 200 states of the guide's table and on
/// the 20 × 20 and 30 × 30 benchmark grids): these signs and halvings took 29 to 45 times the
/// time per [`evaluation`] unit that the isolation of roots takes per unit of [`isolation`].
const AT_A_POINT: u128 = 32;

/// A root with its bracket in floating point, widened by [`MARGIN`]: windows apart decide a
/// comparison without rational arithmetic.
struct Located {
    root: Root,
    lo: f64,
    hi: f64,
    /// The degree and coefficient bits of the root's advantage polynomial (for [`evaluation`]).
    degree: usize,
    bits: u64,
}

/// The counted work of the sign of a degree-`degree` integer polynomial with `bits`-bit
/// coefficients at a rational whose denominator takes `point_bits` bits, in products of words:
/// homogeneous Horner ([`crate::algebra::poly::roots::homogeneous`]) takes `degree + 1` steps,
/// each multiplying the sum (up to `bits + degree · point_bits` bits) by the point's numerator
/// and a coefficient by a power of its denominator (up to `degree · point_bits` bits), so the
/// work grows with the square of the point's bits. Measured in release on degrees 5 to 200,
/// coefficients of 64 to 3000 bits and points of 64 to 20000 bits: 1.2·10⁸ to 1.8·10⁹ units a
/// second throughout.
pub fn evaluation(degree: usize, bits: u64, point_bits: u64) -> u128 {
    let d = degree as u128 + 1;
    let (bits, point) = (u128::from(bits), u128::from(point_bits));
    let power = d * point / 64 + 1;
    d * (((bits + d * point) / 64 + 1) * (point / 64 + 1) + (bits / 64 + 1) * power)
}

/// The counted work of isolating the roots of a degree-`degree` polynomial with `bits`-bit
/// coefficients in `(0, 1)`, `roots` of them, to brackets of `2^-100`: a Taylor shift per root
/// and one more (`degree²` additions on numbers of `bits + degree` bits), and about 100 halvings
/// per root, each an [`evaluation`] at a point of about 100 bits.
pub fn isolation(degree: usize, bits: u64, roots: usize) -> u128 {
    let d = degree as u128 + 1;
    let shift = d * d * ((u128::from(bits) + d) / 64 + 1);
    (roots as u128 + 1) * shift + roots as u128 * 100 * evaluation(degree, bits, 100)
}

impl Located {
    fn new(root: Root, degree: usize, bits: u64) -> Located {
        let mut located = Located {
            root,
            lo: 0.0,
            hi: 1.0,
            degree,
            bits,
        };
        located.window();
        located
    }

    /// The counted work of one halving or sign at the current bracket ([`AT_A_POINT`]
    /// evaluations).
    fn cost(&self) -> u128 {
        let point = self.root.lo.denom().bits().max(self.root.hi.denom().bits()) + 1;
        AT_A_POINT * evaluation(self.degree, self.bits, point)
    }

    /// The window of the current bracket.
    fn window(&mut self) {
        use num_traits::ToPrimitive;
        self.lo = self.root.lo.to_f64().unwrap_or(0.0) - MARGIN;
        self.hi = self.root.hi.to_f64().unwrap_or(1.0) + MARGIN;
    }

    /// Whether the bracket is exact or narrower than [`FINE`] margins: comparisons leave it
    /// to the exact test rather than halve it.
    fn fine(&self) -> bool {
        self.root.exact || self.hi - self.lo < (2.0 + FINE) * MARGIN
    }

    fn halve(&mut self) {
        self.root.halve();
        self.window();
    }
}

/// The roots met (module docs), each with a window that comparisons narrow for good (by
/// halving, so the brackets stay those of the bisection), the classes of roots found
/// equal (union–find), so that each equality is decided once, and the order of the classes
/// found distinct by the exact comparison, so that each of those is decided once too.
struct Points {
    points: Vec<Located>,
    class: Vec<u32>,
    /// The order of two classes (by their representatives when compared) decided exactly.
    decided: HashMap<(u32, u32), Ordering>,
    /// The counted work of the halvings, signs and exact comparisons done ([`evaluation`]).
    work: u128,
}

impl Points {
    fn new() -> Points {
        Points {
            points: Vec::new(),
            class: Vec::new(),
            decided: HashMap::new(),
            work: 0,
        }
    }

    fn insert(&mut self, root: Root, degree: usize, bits: u64) -> u32 {
        let id = u32::try_from(self.points.len()).expect("fewer than 2^32 roots");
        self.points.push(Located::new(root, degree, bits));
        self.class.push(id);
        id
    }

    fn find(&mut self, mut id: u32) -> u32 {
        while self.class[id as usize] != id {
            let up = self.class[self.class[id as usize] as usize];
            self.class[id as usize] = up;
            id = up;
        }
        id
    }

    /// Entry `id` against the rational `t` (`tf`: `t` in floating point).
    fn cmp_rational(&mut self, id: u32, t: &Rational, tf: f64) -> Ordering {
        let p = &self.points[id as usize];
        if p.hi < tf {
            return Ordering::Less;
        }
        if tf < p.lo {
            return Ordering::Greater;
        }
        self.work += AT_A_POINT * evaluation(p.degree, p.bits, t.denom().bits());
        let order = p.root.cmp_rational(t);
        // Narrowed past t, so the next probes near t decide by the window.
        let mut rounds = 0;
        while order != Ordering::Equal && rounds < MAX_SEPARATION && {
            let p = &self.points[id as usize];
            p.lo <= tf && tf <= p.hi && !p.fine()
        } {
            self.work += self.points[id as usize].cost();
            self.points[id as usize].halve();
            rounds += 1;
        }
        order
    }

    fn compare(&mut self, a: u32, b: u32) -> Ordering {
        let apart = |p: &Located, q: &Located| {
            if p.hi < q.lo {
                Some(Ordering::Less)
            } else if q.hi < p.lo {
                Some(Ordering::Greater)
            } else {
                None
            }
        };
        if let Some(o) = apart(&self.points[a as usize], &self.points[b as usize]) {
            return o;
        }
        let (ca, cb) = (self.find(a), self.find(b));
        if ca == cb {
            return Ordering::Equal;
        }
        if let Some(&o) = self.decided.get(&(ca, cb)) {
            return o;
        }
        // Distinct roots part after a few halvings (while the brackets are wider than the
        // windows' margin); equal ones, and distinct ones closer than the margin, are decided
        // exactly, once.
        for _ in 0..SEPARATION_BEFORE_EXACT {
            let mut halved = false;
            for id in [a, b] {
                let p = &mut self.points[id as usize];
                if !p.fine() {
                    self.work += p.cost();
                    p.halve();
                    halved = true;
                }
            }
            if !halved {
                break;
            }
            if let Some(o) = apart(&self.points[a as usize], &self.points[b as usize]) {
                return o;
            }
        }
        // An exact comparison: charged as 100 halvings of both.
        self.work += 100 * (self.points[a as usize].cost() + self.points[b as usize].cost());
        let order = self.points[a as usize]
            .root
            .compare(&self.points[b as usize].root);
        if order == Ordering::Equal {
            self.class[ca as usize] = cb;
        } else {
            self.decided.insert((ca, cb), order);
            self.decided.insert((cb, ca), order.reverse());
        }
        order
    }

    /// Whether root `r` lies inside `(lo, hi)` (`None`: 0, 1), or in its closure.
    fn within(&mut self, r: u32, lo: Option<u32>, hi: Option<u32>, closed: bool) -> bool {
        let keep = |o: Ordering, away: Ordering| o == away || (closed && o == Ordering::Equal);
        lo.is_none_or(|l| keep(self.compare(r, l), Ordering::Greater))
            && hi.is_none_or(|h| keep(self.compare(r, h), Ordering::Less))
    }

    /// The root of `id`'s class: equal roots come out as clones of one root, which
    /// [`Root::compare`] finds equal without refining.
    fn root(&mut self, id: u32) -> Root {
        let id = self.find(id);
        self.points[id as usize].root.clone()
    }
}

/// [`ParametricError::Work`] when `total` has passed `budget` (the caller fills in the counts
/// of the analysis).
fn over_budget(total: u128, budget: u128) -> Result<(), ParametricError> {
    if total > budget {
        return Err(ParametricError::Work {
            probes: 0,
            work: total,
            reserved: 0,
            regions: 0,
            gaps: 0,
            bound: budget,
        });
    }
    Ok(())
}

/// An advantage polynomial's roots in `(0, 1)` (ids in [`Points`]), increasing, and its sign
/// on the `roots + 1` gaps they leave.
struct Isolated {
    roots: Vec<u32>,
    signs: Vec<Ordering>,
}

impl Isolated {
    /// How many roots lie left of `t`, and the sign at `t` (`None`: `t` is a root).
    fn locate(&self, points: &mut Points, t: &Rational, tf: f64) -> (usize, Option<Ordering>) {
        for (i, &r) in self.roots.iter().enumerate() {
            match points.cmp_rational(r, t, tf) {
                Ordering::Less => continue,
                Ordering::Equal => return (i, None),
                Ordering::Greater => return (i, Some(self.signs[i])),
            }
        }
        (self.roots.len(), Some(self.signs[self.roots.len()]))
    }
}

/// Values and advantage polynomials of the policies met so far (module docs).
pub struct ChainMemory {
    /// The lcm of the stage rewards' denominators over every action where the episode runs.
    big_r: BigInt,
    names: HashMap<Name, u32>,
    values: Vec<Value>,
    /// Denominators `R`, `R (1 − α^k)`, by cycle length `k` (0: `R`).
    dens: Vec<Vec<BigInt>>,
    den_index: HashMap<usize, usize>,
    advantages: HashMap<(usize, u32, Option<u32>), Option<Arc<Isolated>>>,
    points: Points,
    words: usize,
    /// Cleared past this many words ([`MAX_MEMORY_WORDS`] in the analysis).
    max_words: usize,
    /// The optimal policy of the last probe: the next probe starts from it.
    last: Option<Vec<Option<usize>>>,
    /// The largest degree of a value ([`super::MAX_CHAIN_DEGREE`] in the analysis).
    degree_bound: usize,
    /// The work a probe may bring the total to ([`Self::set_budget`]).
    budget: u128,
}

/// Words of an integer polynomial's coefficients.
fn words(p: &[BigInt]) -> usize {
    p.iter()
        .map(|c| c.bits().div_ceil(64).max(1) as usize)
        .sum()
}

impl ChainMemory {
    /// An empty memory for `model`'s running states, cleared past `max_words` words, refusing
    /// values of degree over `degree_bound`.
    pub fn new(
        model: &Model,
        running: &[StateId],
        max_words: usize,
        degree_bound: usize,
    ) -> ChainMemory {
        use num_integer::Integer;
        let mut big_r = BigInt::one();
        for &x in running {
            for a in model.problem.actions(x) {
                big_r = big_r.lcm(model.reward[a].denom());
            }
        }
        let mut memory = ChainMemory {
            big_r,
            names: HashMap::new(),
            values: Vec::new(),
            dens: Vec::new(),
            den_index: HashMap::new(),
            advantages: HashMap::new(),
            points: Points::new(),
            words: 0,
            max_words,
            last: None,
            degree_bound,
            budget: u128::MAX,
        };
        memory.clear();
        memory
    }

    fn clear(&mut self) {
        self.names.clear();
        self.values.clear();
        self.advantages.clear();
        self.points = Points::new();
        self.dens = vec![vec![self.big_r.clone()]];
        self.den_index = HashMap::from([(0, 0)]);
        self.words = 0;
    }

    /// The total work the next probes may reach: a probe stops, with
    /// [`ParametricError::Work`], as soon as its counted work takes the total past it (checked
    /// after each policy evaluated and each advantage built or located, so a probe never runs
    /// on past the bound by more than one advantage's work).
    pub fn set_budget(&mut self, budget: u128) {
        self.budget = budget;
    }

    /// [`ParametricError::Work`] when the total `work` (with the work of [`Points`] not yet
    /// added) has passed the budget; the caller fills in the counts of the analysis.
    fn within_budget(&self, work: u128) -> Result<(), ParametricError> {
        over_budget(work + self.points.work, self.budget)
    }

    /// The index of the denominator `R (1 − α^k)` (`R` for `k = 0`).
    fn den(&mut self, k: usize) -> usize {
        if let Some(&i) = self.den_index.get(&k) {
            return i;
        }
        let mut d = vec![BigInt::zero(); k + 1];
        d[0] = self.big_r.clone();
        d[k] = -self.big_r.clone();
        self.dens.push(d);
        self.den_index.insert(k, self.dens.len() - 1);
        self.dens.len() - 1
    }

    /// The names of a policy's values (per state; unused where the episode is over), the
    /// largest degree among them, and the words of the values built. Refuses a chain longer
    /// than the memory's degree bound.
    fn evaluate(
        &mut self,
        model: &Model,
        running: &[StateId],
        policy: &[Option<usize>],
    ) -> Result<(Vec<u32>, usize, u128), ParametricError> {
        let n = model.problem.states();
        let action = |x: StateId| policy[x].expect("a policy acts where the episode runs");
        let bound = self.degree_bound;
        let too_long = |degree: usize| {
            (degree > bound).then_some(ParametricError::ChainDegree { degree, bound })
        };
        let reward = |a: usize, big_r: &BigInt| -> BigInt {
            (&model.reward[a] * Rational::from_integer(big_r.clone())).to_integer()
        };
        let mut id = vec![0u32; n];
        let (mut degree, mut built) = (0usize, 0u128);
        for (x, cycle) in chains(model, running, policy) {
            let name = match &cycle {
                Some(cycle) => Name::Cycle(cycle.iter().map(|&c| action(c)).collect()),
                None => {
                    let y = successor(model, action(x));
                    Name::Path(action(x), (!model.terminal[y]).then(|| id[y]))
                }
            };
            let known = self.names.get(&name).copied();
            let i = match known {
                Some(i) => i,
                None => {
                    let value = match &cycle {
                        Some(cycle) => {
                            if let Some(e) = too_long(cycle.len()) {
                                return Err(e);
                            }
                            Value {
                                den: self.den(cycle.len()),
                                num: cycle
                                    .iter()
                                    .map(|&c| reward(action(c), &self.big_r))
                                    .collect(),
                            }
                        }
                        None => {
                            let y = successor(model, action(x));
                            let (den, k) = if model.terminal[y] {
                                (0, 0)
                            } else {
                                let den = self.values[id[y] as usize].den;
                                (den, self.dens[den].len() - 1)
                            };
                            // N_x = r_x (D / R) + α N_y.
                            let unscaled: Vec<BigInt> = if k == 0 {
                                vec![BigInt::one()]
                            } else {
                                let mut u = vec![BigInt::zero(); k + 1];
                                u[0] = BigInt::one();
                                u[k] = -BigInt::one();
                                u
                            };
                            let mut num: Vec<BigInt> = Vec::new();
                            poly_add_scaled(
                                &mut num,
                                &unscaled,
                                &reward(action(x), &self.big_r),
                                0,
                            );
                            if !model.terminal[y] {
                                let ny = &self.values[id[y] as usize].num;
                                poly_add_scaled(&mut num, ny, &BigInt::one(), 1);
                            }
                            let deg = num.len().saturating_sub(1).max(k);
                            if let Some(e) = too_long(deg) {
                                return Err(e);
                            }
                            Value { den, num }
                        }
                    };
                    let w = words(&value.num);
                    built += w as u128;
                    self.words += w;
                    self.values.push(value);
                    let i = u32::try_from(self.values.len() - 1).expect("fewer than 2^32 values");
                    self.names.insert(name, i);
                    i
                }
            };
            let v = &self.values[i as usize];
            degree = degree
                .max(v.num.len().saturating_sub(1))
                .max(self.dens[v.den].len() - 1);
            id[x] = i;
        }
        Ok((id, degree, built))
    }

    /// The isolated advantage of `a` at `x` (a state where the episode runs) under the values
    /// `id`, built if new; the words built.
    fn advantage(
        &mut self,
        model: &Model,
        x: StateId,
        a: usize,
        id: &[u32],
    ) -> (Option<Arc<Isolated>>, u128) {
        let y = successor(model, a);
        let key = (a, id[x], (!model.terminal[y]).then(|| id[y]));
        if let Some(found) = self.advantages.get(&key) {
            return (found.clone(), READ);
        }
        let value = |z: StateId| {
            let v = &self.values[id[z] as usize];
            (v.den, v.num.as_slice())
        };
        let (c, _, _) = advantage_polynomial(model, x, a, &value, &self.dens);
        let mut built = words(&c) as u128;
        let degree = c.len().saturating_sub(1);
        let bits = c.iter().map(BigInt::bits).max().unwrap_or(0);
        let isolated = (!c.iter().all(Zero::is_zero)).then(|| {
            let roots = roots_in_unit_interval(&int_poly(&c));
            built += isolation(degree, bits, roots.len());
            let signs = (0..=roots.len())
                .map(|i| {
                    let lo = if i == 0 {
                        zero_point()
                    } else {
                        roots[i - 1].clone()
                    };
                    let hi = roots.get(i).cloned().unwrap_or_else(one_point);
                    integer_sign(&c, &between(&lo, &hi))
                })
                .collect();
            let roots = roots
                .into_iter()
                .map(|r| self.points.insert(r, degree, bits))
                .collect();
            Arc::new(Isolated { roots, signs })
        });
        self.words += words(&c);
        self.advantages.insert(key, isolated.clone());
        (isolated, built + READ)
    }

    /// The probe at the rational `t` (module docs of [`super`], step 3): `None` if `t` is a root
    /// of some non-zero advantage of the optimal policy there. Adds the probe's counted work
    /// to `work` (module docs: words built, roots isolated, signs and halvings) and the largest
    /// value degree of its policy to `degree`.
    pub fn probe(
        &mut self,
        model: &Model,
        running: &[StateId],
        t: &Rational,
        degree: &mut usize,
        work: &mut u128,
    ) -> Result<Option<Region>, ParametricError> {
        let region = self.probe_counted(model, running, t, degree, work);
        *work += std::mem::take(&mut self.points.work);
        region
    }

    /// [`Self::probe`] without the work of [`Points`].
    fn probe_counted(
        &mut self,
        model: &Model,
        running: &[StateId],
        t: &Rational,
        degree: &mut usize,
        work: &mut u128,
    ) -> Result<Option<Region>, ParametricError> {
        let p = &model.problem;
        if self.words > self.max_words {
            self.clear();
        }
        let mut policy = match self.last.take() {
            Some(policy) => policy,
            None => float_optimum(model, running, t),
        };
        let tf = {
            use num_traits::ToPrimitive;
            t.to_f64().unwrap_or(0.5)
        };
        let mut restarted = false;
        // Exact policy iteration on the advantages' signs at t: every state with an improving
        // action switches to its first one (the values grow strictly, so no policy repeats).
        let found = loop {
            let (id, deg, built) = match self.evaluate(model, running, &policy) {
                Ok(v) => v,
                // A start too far off: start again from exact iteration.
                Err(ParametricError::ChainDegree { .. }) if !restarted => {
                    restarted = true;
                    policy = super::deterministic_optimum(model, running, t);
                    continue;
                }
                Err(e) => return Err(e),
            };
            // The chains walked and the values named: a unit per running state.
            *work += built + READ * running.len() as u128;
            self.within_budget(*work)?;
            // Per other action: its advantage (`None`: identically zero) with the number of
            // its roots left of t and its sign at t (`None`: t is a root).
            let mut found = Vec::new();
            let mut improved = false;
            for &x in running {
                let mut better = None;
                for a in p.actions(x).filter(|&a| Some(a) != policy[x]) {
                    let (isolated, built) = self.advantage(model, x, a, &id);
                    *work += built;
                    let located = isolated.map(|i| {
                        let (first, sign) = i.locate(&mut self.points, t, tf);
                        (i, first, sign)
                    });
                    self.within_budget(*work)?;
                    if located
                        .as_ref()
                        .is_some_and(|l| l.2 == Some(Ordering::Greater))
                    {
                        better = better.or(Some(a));
                    }
                    found.push((a, located));
                }
                if better.is_some() {
                    policy[x] = better;
                    improved = true;
                }
            }
            if !improved {
                *degree = (*degree).max(deg);
                break found;
            }
        };
        self.last = Some(policy.clone());
        // The region: every advantage negative at t, walked both ways over all its roots.
        let mut persistent = Vec::new();
        let mut walks: Vec<(usize, Arc<Isolated>, usize)> = Vec::new();
        for (a, located) in found {
            let Some((isolated, first, sign)) = located else {
                persistent.push(a);
                continue;
            };
            match sign {
                None => return Ok(None),
                Some(Ordering::Less) => {}
                Some(_) => {
                    return Err(ParametricError::Internal(format!(
                        "the policy optimal at alpha = {t} has a positive advantage there"
                    )))
                }
            }
            if !isolated.roots.is_empty() {
                walks.push((a, isolated, first));
            }
        }
        // The walks compare roots (halving their brackets, counted by `Points`): the budget is
        // checked after each advantage, as while the policy was found.
        let budget = self.budget;
        let points = &mut self.points;
        let (mut lo, mut hi): (Option<u32>, Option<u32>) = (None, None);
        let mut touches: Vec<u32> = Vec::new();
        for (_, isolated, first) in &walks {
            over_budget(*work + points.work, budget)?;
            let (roots, signs) = (&isolated.roots, &isolated.signs);
            for i in *first..roots.len() {
                if signs[i + 1] == Ordering::Greater {
                    if hi.is_none_or(|h| points.compare(roots[i], h) == Ordering::Less) {
                        hi = Some(roots[i]);
                    }
                    break;
                }
                touches.push(roots[i]);
            }
            for i in (0..*first).rev() {
                if signs[i] == Ordering::Greater {
                    if lo.is_none_or(|l| points.compare(roots[i], l) == Ordering::Greater) {
                        lo = Some(roots[i]);
                    }
                    break;
                }
                touches.push(roots[i]);
            }
        }
        // Only the roots in the region's closure matter to its optimal sets.
        let mut advantages = Vec::new();
        for (a, isolated, _) in &walks {
            over_budget(*work + points.work, budget)?;
            let mut roots = Vec::new();
            for &r in &isolated.roots {
                if points.within(r, lo, hi, true) {
                    roots.push(points.root(r));
                }
            }
            if !roots.is_empty() {
                advantages.push(Advantage { action: *a, roots });
            }
        }
        touches.sort_unstable();
        touches.dedup();
        let mut inside = Vec::new();
        for r in touches {
            if points.within(r, lo, hi, false) {
                inside.push(points.root(r));
            }
        }
        let touches = inside;
        let (lo, hi) = (lo.map(|l| points.root(l)), hi.map(|h| points.root(h)));
        Ok(Some(Region {
            lo,
            hi,
            policy,
            persistent,
            advantages,
            touches,
        }))
    }
}
