//! Dixon lifting (steps 3–5 of [`super`]'s module docs) in *lanes*: a lane lifts modulo one
//! prime; two lanes lift modulo two primes `p₁`, `p₂` at once, one per thread, each for about
//! half the steps one lane would take, and their expansions are combined by the Chinese
//! remainder theorem into `x mod (p₁p₂)^K` before the same reconstruction and the same exact
//! verification `A·N = d·r` as with one prime.
//!
//! With `K` packed rows (two steps each) in each lane, `x₁ = x mod P₁` and `x₂ = x mod P₂`
//! (`P_i = p_i^(2K)`) give `x mod P₁P₂ = x₁ + P₁·((x₂ − x₁)·P₁⁻¹ mod P₂)`: one product and one
//! Barrett reduction modulo `P₂` per unknown, done only for the unknowns the reconstruction
//! reads (the probes and the peel plan's seeds on the fast path).

use std::collections::HashMap;
use std::sync::{Arc, Mutex};

use dashu_base::{ExtendedGcd, RemEuclid};
use dashu_int::UBig;

use super::residual::Residual;
use super::{
    attempt, next_attempt, BandOrdering, Digits, ExactSolution, Expansion, LiftProgress,
    LinearError, ModularFactor, PeelPlan, Schedule, SparseSystem,
};
use crate::algebra::barrett::Barrett;
use crate::algebra::sparse_lu::Modulus;

/// One prime's lifting: its factor, the residual `r_k` and the digits `z_k` lifted so far.
pub(super) struct Lane<'a> {
    lu: &'a ModularFactor<'a>,
    position: &'a [usize],
    residual: Residual,
    y: Vec<u64>,
    pub(super) digits: Digits,
}

impl<'a> Lane<'a> {
    pub(super) fn new(
        system: &SparseSystem,
        ordering: &'a BandOrdering,
        lu: &'a ModularFactor<'a>,
    ) -> Self {
        let p = lu.p();
        let (order, position) = lu.permutation(ordering);
        Lane {
            lu,
            position,
            residual: Residual::new(system, order, position, Modulus::new(p)),
            y: vec![0; system.len()],
            digits: Digits::new(p),
        }
    }

    /// One lifting step: `z_k = A⁻¹·r_k mod p`, `r_{k+1} = (r_k − A·z_k)/p` (exact), and `z_k`
    /// stored as the next `p`-adic digit.
    pub(super) fn step(&mut self) -> Result<(), LinearError> {
        self.residual.residues(&mut self.y);
        self.lu.solve(&mut self.y);
        self.residual.update(&self.y)?;
        self.digits.push(&self.y, self.position);
        Ok(())
    }
}

/// `P₁ = p₁^(2·rows)`, `P₂ = p₂^(2·rows)` and what combining residues modulo them needs.
struct Basis {
    first: UBig,
    second: UBig,
    /// `P₁⁻¹ mod P₂`.
    inverse: UBig,
    /// Reduction modulo `P₂`.
    barrett: Barrett,
}

impl Basis {
    fn new(p1: u64, p2: u64, rows: usize) -> Self {
        let first = UBig::from(p1 * p1).pow(rows);
        let second = UBig::from(p2 * p2).pow(rows);
        let (g, s, _) = (&first).gcd_ext(&second);
        assert_eq!(g, UBig::ONE, "distinct primes give coprime powers");
        let inverse = s.rem_euclid(dashu_int::IBig::from(second.clone()));
        Basis {
            barrett: Barrett::new(&second),
            first,
            second,
            inverse,
        }
    }

    /// The `x` in `[0, P₁P₂)` with `x ≡ x₁ (mod P₁)` and `x ≡ x₂ (mod P₂)` (`x₁ < P₁`,
    /// `x₂ < P₂`): `x₁ + P₁·t` with `t = (x₂ − x₁)·P₁⁻¹ mod P₂ < P₂`.
    fn combine(&self, x1: UBig, x2: UBig) -> UBig {
        let low = &x1 % &self.second;
        let difference = if x2 >= low {
            x2 - low
        } else {
            x2 + &self.second - low
        };
        // Both factors are below P₂: the product is below 2^(2k), as the reduction needs.
        let t = self.barrett.reduce(difference * &self.inverse);
        x1 + &self.first * t
    }

    fn modulus(&self) -> UBig {
        &self.first * &self.second
    }
}

/// Two lanes' digits as one expansion modulo `(p₁p₂)^(2K)` ([`Expansion`]), `K` the packed rows
/// of each (the lanes are advanced to the same number of whole rows before every attempt).
pub(super) struct Combined<'d> {
    lanes: [&'d mut Digits; 2],
    /// The basis of all `K` rows (set by [`Expansion::prepare`]).
    full: Option<Basis>,
    /// Bases of shorter prefixes, built when first asked for.
    prefixes: Mutex<HashMap<usize, Arc<Basis>>>,
}

impl<'d> Combined<'d> {
    pub(super) fn new(first: &'d mut Digits, second: &'d mut Digits) -> Self {
        debug_assert_eq!(first.rows.len(), second.rows.len());
        debug_assert!(first.steps.is_multiple_of(2) && first.steps == second.steps);
        Combined {
            lanes: [first, second],
            full: None,
            prefixes: Mutex::new(HashMap::new()),
        }
    }

    fn rows(&self) -> usize {
        self.lanes[0].rows.len()
    }

    fn primes(&self) -> (u64, u64) {
        (self.lanes[0].p, self.lanes[1].p)
    }

    fn basis(&self, rows: usize) -> Arc<Basis> {
        let mut cache = self.prefixes.lock().unwrap_or_else(|e| e.into_inner());
        let (p1, p2) = self.primes();
        cache
            .entry(rows)
            .or_insert_with(|| Arc::new(Basis::new(p1, p2, rows)))
            .clone()
    }
}

impl Expansion for Combined<'_> {
    fn prepare(&mut self) {
        for lane in self.lanes.iter_mut() {
            lane.prepare();
        }
        let (p1, p2) = self.primes();
        self.full = Some(Basis::new(p1, p2, self.rows()));
    }

    fn modulus(&self) -> UBig {
        self.full.as_ref().expect("prepared").modulus()
    }

    fn value(&self, j: usize) -> UBig {
        let rows = self.rows();
        let basis = self.full.as_ref().expect("prepared");
        let [a, b] = &self.lanes;
        basis.combine(a.column(j, rows), b.column(j, rows))
    }

    /// Whole packed rows of both lanes; all of them allowed (every row is full).
    fn prefix_rows(&self, bits: f64) -> Option<usize> {
        let (p1, p2) = self.primes();
        let per_row = 2.0 * ((p1 as f64).log2() + (p2 as f64).log2());
        let rows = ((bits / per_row).ceil() as usize).max(1);
        (rows <= self.rows()).then_some(rows)
    }

    fn prefix_modulus(&self, rows: usize) -> UBig {
        self.basis(rows).modulus()
    }

    fn prefix(&self, j: usize, rows: usize) -> UBig {
        let basis = self.basis(rows);
        let [a, b] = &self.lanes;
        basis.combine(a.column(j, rows), b.column(j, rows))
    }
}

/// Dixon lifting modulo two primes at once, one lane per thread (module docs); `None` if the
/// bound was reached without a verified solution (only possible if `A` is singular).
/// `schedule.expected` counts solves modulo one prime, as [`super::lift`]'s does; so do the
/// progress reports and the returned `lifting_steps` (both lanes' steps together).
pub(super) fn lift_two(
    system: &SparseSystem,
    ordering: &BandOrdering,
    factors: [&ModularFactor; 2],
    schedule: &Schedule,
    progress: &mut dyn FnMut(LiftProgress),
) -> Result<Option<ExactSolution>, LinearError> {
    let (p1, p2) = (factors[0].p(), factors[1].p());
    // One row: two steps in each lane, 2·log2(p₁p₂) bits.
    let bits_per_row = 2.0 * ((p1 as f64).log2() + (p2 as f64).log2());
    let max_rows = (schedule.max_bits as f64 / bits_per_row).ceil() as usize + 1;
    let expected = schedule.expected.min(4 * max_rows);
    let expected_rows = expected.div_ceil(4).max(1);
    let mut first = Lane::new(system, ordering, factors[0]);
    let mut second = Lane::new(system, ordering, factors[1]);
    let plan = PeelPlan::new(system, ordering);
    // Tries, in rows ([`super::next_attempt`]).
    let mut next_try = 1usize.min(expected_rows);
    let mut rows = 0usize;
    while rows < max_rows {
        let target = next_try.min(max_rows);
        let steps = 2 * (target - rows);
        let done = 4 * rows;
        let mut first_lane = |k_steps: usize| {
            (0..k_steps).try_for_each(|k| {
                first.step()?;
                for s in [done + 2 * k + 1, done + 2 * k + 2] {
                    progress(LiftProgress { steps: s, expected });
                }
                Ok::<(), LinearError>(())
            })
        };
        // The second lane on a thread of its own; where none can be started, after the first
        // on this one (the same digits, one core's time).
        let spawned = std::thread::scope(|scope| {
            let other = std::thread::Builder::new()
                .spawn_scoped(scope, || (0..steps).try_for_each(|_| second.step()));
            let mine = first_lane(steps);
            match other {
                Ok(other) => {
                    let theirs = other
                        .join()
                        .unwrap_or_else(|panic| std::panic::resume_unwind(panic));
                    mine.and(theirs).map(|()| true)
                }
                Err(_) => mine.map(|()| false),
            }
        })?;
        if !spawned {
            (0..steps).try_for_each(|_| second.step())?;
        }
        rows = target;
        next_try = next_attempt(rows, expected_rows, 1);
        let mut combined = Combined::new(&mut first.digits, &mut second.digits);
        if let Some((numerators, denominator)) =
            attempt(system, &mut combined, schedule.estimate(), &plan)
        {
            return Ok(Some(ExactSolution {
                numerators,
                denominator,
                lifting_steps: 4 * rows,
            }));
        }
    }
    Ok(None)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algebra::uniform;
    use dashu_base::BitTest;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    const P1: u64 = 2_147_483_629;
    const P2: u64 = 2_147_483_587;

    fn random_below(rng: &mut ChaCha8Rng, m: &UBig) -> UBig {
        let words = m.bit_len() / 64 + 2;
        let mut x = UBig::ZERO;
        for _ in 0..words {
            x = (x << 64usize) + UBig::from(rng.next_u64());
        }
        x % m
    }

    /// The combination against the definition: for `x` below `P₁P₂`, the residues modulo `P₁`
    /// and `P₂` give back `x` (the product computed directly, not from the basis).
    #[test]
    fn the_combination_inverts_the_residues_modulo_the_product() {
        let mut rng = ChaCha8Rng::seed_from_u64(21);
        for rows in [1usize, 2, 7, 40] {
            let basis = Basis::new(P1, P2, rows);
            let product = UBig::from(P1).pow(2 * rows) * UBig::from(P2).pow(2 * rows);
            assert_eq!(basis.modulus(), product);
            let (m1, m2) = (UBig::from(P1).pow(2 * rows), UBig::from(P2).pow(2 * rows));
            let edges = [UBig::ZERO, UBig::ONE, &product - UBig::ONE, m1.clone()];
            let randoms: Vec<UBig> = (0..50).map(|_| random_below(&mut rng, &product)).collect();
            for x in edges.into_iter().chain(randoms) {
                assert_eq!(basis.combine(&x % &m1, &x % &m2), x, "rows = {rows}");
            }
        }
    }

    /// Two lanes' `p`-adic digits of known integers, combined: every value and prefix is the
    /// integer modulo the product of the prime powers, and the prefix asked for is the
    /// shortest whose modulus exceeds `2^bits`.
    #[test]
    fn two_lanes_digits_give_the_value_modulo_the_product() {
        let mut rng = ChaCha8Rng::seed_from_u64(22);
        for rows in [1usize, 3, 9, 20] {
            let top = UBig::ONE << (130 * rows);
            let xs: Vec<UBig> = (0..4).map(|_| random_below(&mut rng, &top)).collect();
            let identity: Vec<usize> = (0..xs.len()).collect();
            let mut lanes = [Digits::new(P1), Digits::new(P2)];
            for lane in lanes.iter_mut() {
                let p = UBig::from(lane.p);
                let mut rest = xs.clone();
                for _ in 0..2 * rows {
                    let digits: Vec<u64> = rest
                        .iter()
                        .map(|x| u64::try_from(x % &p).expect("below p"))
                        .collect();
                    lane.push(&digits, &identity);
                    rest = rest.iter().map(|x| x / &p).collect();
                }
            }
            let [a, b] = &mut lanes;
            let mut combined = Combined::new(a, b);
            combined.prepare();
            let modulus = |r: usize| UBig::from(P1 as u128 * P2 as u128).pow(2 * r);
            assert_eq!(combined.modulus(), modulus(rows));
            for (j, x) in xs.iter().enumerate() {
                assert_eq!(combined.value(j), x % modulus(rows), "rows = {rows}");
                for r in 1..=rows {
                    assert_eq!(combined.prefix_modulus(r), modulus(r));
                    assert_eq!(
                        combined.prefix(j, r),
                        x % modulus(r),
                        "prefix {r} of {rows}"
                    );
                }
            }
            for _ in 0..20 {
                let bits = uniform(&mut rng, 0, 130 * rows as u64) as f64;
                match combined.prefix_rows(bits) {
                    Some(r) => {
                        assert!(modulus(r).bit_len() as f64 > bits, "{bits} bits: {r} rows");
                        assert!(r == 1 || (modulus(r - 1).bit_len() as f64) <= bits + 1.0);
                    }
                    None => assert!(modulus(rows).bit_len() as f64 <= bits + 1.0),
                }
            }
        }
    }
}
