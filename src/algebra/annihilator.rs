//! The minimal polynomial of the Krylov sequence `e_k = A^k e_0` of an integer matrix `A` and
//! an integer vector `e_0` by modular arithmetic: found modulo word-size primes and lifted to
//! the integers by Chinese remaindering. The parametric discount engine takes from it the
//! denominator of a stochastic policy's values (`A` the scaled transition matrix `Q·P`; step 1
//! of the module docs of `objectives::parametric`).
//!
//! **Why integers suffice.** The minimal polynomial `μ` of `e_0` under `A` divides the
//! characteristic polynomial of `A`, which is monic with integer coefficients; by Gauss's
//! lemma the monic `μ` has integer coefficients too. Written as a recurrence,
//! `d_j = [t^(L−j)] μ` (`L = deg μ`), so `d_0 = 1` and `Σ_{j≤L} d_j e_{k−j} = 0` for `k ≥ L`.
//! The roots of `μ` are eigenvalues of `A`, of modulus at most the largest absolute row sum
//! `B` of `A` (Gershgorin), so `|d_j| ≤ C(L, j)·B^j ≤ (1 + B)^L` (Vieta): the symmetric
//! residues modulo a product of primes above `2·(1 + B)^L` are the coefficients themselves,
//! and no rational reconstruction is needed.
//!
//! **Modulo a prime `p`.** The Krylov vectors are computed modulo `p` for `k < 2m` (`m` the
//! dimension; sparse products, `u128` sums reduced once per entry), Berlekamp–Massey
//! (Massey 1969) gives the shortest recurrence of a projection `u·e_k` (unique, as
//! `2·deg μ ≤ 2m` terms are known), and the recurrence is checked on the vectors modulo `p`:
//! if it annihilates them it is the minimal polynomial `μ_p` of `e_0` under `A mod p`, else
//! another projection is tried. `μ mod p` annihilates the sequence modulo `p`, so `μ_p`
//! divides it: `deg μ_p ≤ L`, with equality exactly when `μ_p = μ mod p` (both monic). A prime
//! where the degree is lower is *unlucky* (finitely many are); only the primes of the largest
//! degree met are kept.
//!
//! **Exactness.** The largest degree met may still be too low if every prime so far was
//! unlucky. The caller therefore verifies every candidate exactly (the parametric engine
//! does so in step 1 of its module docs); after a failed verification only primes of a larger degree are accepted. The
//! result does not depend on the primes, the projections or this module's heuristics: a
//! verified annihilator of degree at most `deg μ` is `μ` itself.

use super::modular::{inv_mod, is_prime, mul_mod};
use num_bigint::{BigInt, BigUint};
use num_traits::{One, Signed, ToPrimitive, Zero};

/// Projections tried modulo each prime before the prime is skipped.
pub const PROJECTIONS: usize = 4;

/// Primes below `2^60` in decreasing order (Miller–Rabin with the first twelve prime bases,
/// deterministic below `3.3·10^24`): products of two residues fit 120 bits, so 256 of them add
/// up in a `u128` without overflow.
fn primes() -> impl Iterator<Item = u64> {
    ((1u64 << 59)..(1u64 << 60)).rev().filter(|&n| is_prime(n))
}

/// `x mod p` in `[0, p)`.
fn residue(x: &BigInt, p: u64) -> u64 {
    let r = (x.magnitude() % p).to_u64().expect("a residue is below p");
    if x.is_negative() && r != 0 {
        p - r
    } else {
        r
    }
}

/// `Σ a_i·b_i mod p` for residues below `p < 2^60`: `u128` sums of 256 products at most
/// between reductions.
fn dot_mod(pairs: impl Iterator<Item = (u64, u64)>, p: u64) -> u64 {
    let wide = u128::from(p);
    let (mut acc, mut terms) = (0u128, 0u32);
    for (a, b) in pairs {
        acc += u128::from(a) * u128::from(b);
        terms += 1;
        if terms == 256 {
            acc %= wide;
            terms = 1;
        }
    }
    (acc % wide) as u64
}

/// The connection polynomial `C` (`C_0 = 1`, length `L + 1` for the recurrence length `L`) of
/// the shortest linear recurrence `Σ_{j≤L} C_j s_{k−j} = 0` (`L ≤ k < s.len()`) of `s` modulo
/// the prime `p` (Berlekamp–Massey).
fn berlekamp_massey_mod(s: &[u64], p: u64) -> Vec<u64> {
    let mut c = vec![1u64];
    let mut b = vec![1u64];
    let (mut l, mut shift, mut last) = (0usize, 1usize, 1u64);
    for n in 0..s.len() {
        let d = dot_mod(
            c.iter()
                .take(l + 1)
                .enumerate()
                .map(|(i, &ci)| (ci, s[n - i])),
            p,
        );
        if d == 0 {
            shift += 1;
            continue;
        }
        let factor = mul_mod(d, inv_mod(last, p), p);
        let previous = (2 * l <= n).then(|| c.clone());
        if c.len() < b.len() + shift {
            c.resize(b.len() + shift, 0);
        }
        for (ci, &bi) in c[shift..].iter_mut().zip(&b) {
            *ci = (*ci + p - mul_mod(factor, bi, p)) % p;
        }
        match previous {
            Some(previous) => {
                b = previous;
                l = n + 1 - l;
                last = d;
                shift = 1;
            }
            None => shift += 1,
        }
    }
    c.resize(l + 1, 0);
    c
}

/// The projections `u` of the Krylov sequence tried in turn: all ones first, then
/// pseudo-random weights in `1..=997` (a fixed linear congruential sequence).
fn projection(attempt: usize, m: usize) -> Vec<u64> {
    let mut seed: u64 = 0x9E37_79B9 ^ attempt as u64;
    (0..m)
        .map(|_| {
            if attempt == 0 {
                return 1;
            }
            seed = seed.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1);
            (seed >> 33) % 997 + 1
        })
        .collect()
}

/// The minimal polynomial `μ_p` of `e_0` under `A` modulo the prime `p < 2^60`, as the
/// recurrence `c` (`c_0 = 1`, length `deg μ_p + 1`): Berlekamp–Massey on projections of the
/// first `2m` Krylov vectors, checked on the vectors (`Σ_j c_j e_{L−j} = 0`). `None` if no
/// projection of `PROJECTIONS` passes the check.
fn image(rows: &[Vec<(usize, BigInt)>], start: &[BigInt], p: u64) -> Option<Vec<u64>> {
    let m = start.len();
    let rows: Vec<Vec<(usize, u64)>> = rows
        .iter()
        .map(|row| row.iter().map(|(j, w)| (*j, residue(w, p))).collect())
        .collect();
    let mut krylov: Vec<Vec<u64>> = Vec::with_capacity(2 * m);
    krylov.push(start.iter().map(|x| residue(x, p)).collect());
    for k in 1..2 * m {
        let prev = &krylov[k - 1];
        let next = rows
            .iter()
            .map(|row| dot_mod(row.iter().map(|&(j, w)| (w, prev[j])), p))
            .collect();
        krylov.push(next);
    }
    (0..PROJECTIONS).find_map(|attempt| {
        let u = projection(attempt, m);
        let s: Vec<u64> = krylov
            .iter()
            .map(|e| dot_mod(e.iter().copied().zip(u.iter().copied()), p))
            .collect();
        let c = berlekamp_massey_mod(&s, p);
        let l = c.len() - 1;
        let annihilates = (0..m).all(|i| {
            dot_mod(
                c.iter().enumerate().map(|(j, &cj)| (cj, krylov[l - j][i])),
                p,
            ) == 0
        });
        annihilates.then_some(c)
    })
}

/// Residues of integer coefficients modulo a growing product of primes (Chinese remaindering,
/// Garner's incremental form).
struct Remainders {
    modulus: BigUint,
    values: Vec<BigUint>,
}

impl Remainders {
    fn new(len: usize) -> Remainders {
        Remainders {
            modulus: BigUint::one(),
            values: vec![BigUint::zero(); len],
        }
    }

    /// Adds the residues `r` modulo the prime `p` (not dividing the modulus).
    fn add(&mut self, r: &[u64], p: u64) {
        let scale = inv_mod((&self.modulus % p).to_u64().expect("below p"), p);
        for (x, &ri) in self.values.iter_mut().zip(r) {
            let now = (&*x % p).to_u64().expect("below p");
            let t = mul_mod((ri + p - now) % p, scale, p);
            if t != 0 {
                *x += &self.modulus * t;
            }
        }
        self.modulus *= p;
    }

    /// The integers in `(−M/2, M/2]` with these residues.
    fn symmetric(&self) -> Vec<BigInt> {
        let half = &self.modulus >> 1;
        self.values
            .iter()
            .map(|x| {
                if *x > half {
                    BigInt::from(x.clone()) - BigInt::from(self.modulus.clone())
                } else {
                    BigInt::from(x.clone())
                }
            })
            .collect()
    }
}

/// The candidates for the denominator recurrence `d` (`d_0 = 1`, length `L + 1`) of the Krylov
/// sequence of an integer matrix (sparse rows `(column, entry)`) and start vector, in the
/// order to verify them.
pub struct Search<'a, I: Iterator<Item = u64>> {
    rows: &'a [Vec<(usize, BigInt)>],
    start: &'a [BigInt],
    primes: I,
    /// Primes still allowed (a bound on the work of a search that never succeeds).
    budget: usize,
    /// `1 + B`: the coefficient bound `(1 + B)^L` is its power.
    base: BigUint,
    /// The degree of the primes kept, and their residues.
    degree: Option<usize>,
    remainders: Remainders,
    /// Every degree at most this was rejected by an exact verification.
    rejected: Option<usize>,
}

/// The search with the primes below `2^60`.
///
/// ```
/// use num_bigint::BigInt;
/// use truecost::algebra::annihilator::search;
/// // A swaps the two coordinates: e_0 = (1, 0), e_1 = (0, 1), e_2 = e_0, so the minimal
/// // polynomial of e_0 is t² − 1 and the recurrence e_k − e_(k−2) = 0 reads d = (1, 0, −1).
/// let one = BigInt::from(1);
/// let rows = vec![vec![(1, one.clone())], vec![(0, one.clone())]];
/// let start = vec![one, BigInt::from(0)];
/// let d = search(&rows, &start).candidate().unwrap();
/// assert_eq!(d, [1, 0, -1].map(BigInt::from));
/// ```
pub fn search<'a>(
    rows: &'a [Vec<(usize, BigInt)>],
    start: &'a [BigInt],
) -> Search<'a, impl Iterator<Item = u64>> {
    Search::with_primes(rows, start, primes())
}

impl<'a, I: Iterator<Item = u64>> Search<'a, I> {
    /// The search with the given distinct primes (below `2^60`).
    fn with_primes(rows: &'a [Vec<(usize, BigInt)>], start: &'a [BigInt], primes: I) -> Self {
        let b = rows
            .iter()
            .map(|row| row.iter().fold(BigInt::zero(), |acc, (_, w)| acc + w.abs()))
            .max()
            .unwrap_or_default();
        let base = b.magnitude() + 1u32;
        // Enough primes for the largest degree m and 64 unlucky ones (far more than expected:
        // a prime is unlucky only if it divides one of finitely many non-zero integers).
        let needed = base.pow(start.len() as u32).bits() / 59 + 2;
        Search {
            rows,
            start,
            primes,
            budget: needed as usize + 64,
            base,
            degree: None,
            remainders: Remainders::new(0),
            rejected: None,
        }
    }

    /// The next candidate `d` (`d_0 = 1`), or `None` when the primes allowed run out. After
    /// `None`-free calls, a further call means the last candidate failed its exact
    /// verification: its degree and every lower one are not asked again.
    pub fn candidate(&mut self) -> Option<Vec<BigInt>> {
        if let Some(l) = self.degree.take() {
            self.rejected = Some(l);
        }
        while self.budget > 0 {
            let p = self.primes.next()?;
            self.budget -= 1;
            let Some(c) = image(self.rows, self.start, p) else {
                continue;
            };
            let l = c.len() - 1;
            if self.rejected.is_some_and(|r| l <= r) || self.degree.is_some_and(|d| l < d) {
                continue;
            }
            if self.degree != Some(l) {
                self.degree = Some(l);
                self.remainders = Remainders::new(l + 1);
            }
            self.remainders.add(&c, p);
            let bound = self.base.pow(l as u32) << 1;
            if self.remainders.modulus > bound {
                return Some(self.remainders.symmetric());
            }
        }
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::value::Rational;

    fn ints(c: &[i64]) -> Vec<BigInt> {
        c.iter().map(|&x| BigInt::from(x)).collect()
    }

    /// Dense rows to sparse ones.
    fn sparse(a: &[Vec<i64>]) -> Vec<Vec<(usize, BigInt)>> {
        a.iter()
            .map(|row| {
                row.iter()
                    .enumerate()
                    .filter(|(_, &w)| w != 0)
                    .map(|(j, &w)| (j, BigInt::from(w)))
                    .collect()
            })
            .collect()
    }

    /// The minimal polynomial of `e_0` under `A` as the recurrence `d` (`d_0 = 1`), by exact
    /// elimination: the first `e_L` that is a rational combination of `e_0 … e_{L−1}`.
    fn brute_force(a: &[Vec<i64>], e0: &[i64]) -> Vec<BigInt> {
        let m = e0.len();
        let to_q = |x: i64| Rational::from_integer(BigInt::from(x));
        let mut krylov: Vec<Vec<Rational>> = vec![e0.iter().map(|&x| to_q(x)).collect()];
        loop {
            let l = krylov.len() - 1;
            // Solve Σ_{i<l} x_i e_i = e_l (Gauss–Jordan on the m × (l + 1) augmented matrix).
            let mut rows: Vec<Vec<Rational>> = (0..m)
                .map(|r| (0..=l).map(|i| krylov[i][r].clone()).collect())
                .collect();
            let mut pivots = Vec::new();
            let mut r = 0;
            for col in 0..l {
                let Some(pr) = (r..m).find(|&i| !rows[i][col].is_zero()) else {
                    continue;
                };
                rows.swap(r, pr);
                let pivot = rows[r][col].clone();
                for v in rows[r].iter_mut() {
                    *v = &*v / &pivot;
                }
                for i in 0..m {
                    if i != r && !rows[i][col].is_zero() {
                        let f = rows[i][col].clone();
                        let pivot_row = rows[r].clone();
                        for (v, w) in rows[i].iter_mut().zip(&pivot_row) {
                            *v = &*v - &f * w;
                        }
                    }
                }
                pivots.push(col);
                r += 1;
            }
            let consistent = rows[r..].iter().all(|row| row[l].is_zero());
            if consistent {
                // e_l = Σ x_i e_i, so d = (1, −x_{l−1}, …, −x_0).
                let mut x = vec![Rational::zero(); l];
                for (k, &col) in pivots.iter().enumerate() {
                    x[col] = rows[k][l].clone();
                }
                let mut d = vec![BigInt::one()];
                for i in (0..l).rev() {
                    assert!(x[i].is_integer(), "Gauss's lemma: integer coefficients");
                    d.push(-x[i].to_integer());
                }
                return d;
            }
            let last = krylov[l].clone();
            let next = a
                .iter()
                .map(|row| {
                    row.iter()
                        .zip(&last)
                        .fold(Rational::zero(), |acc, (&w, v)| acc + to_q(w) * v)
                })
                .collect();
            krylov.push(next);
        }
    }

    fn search_all(a: &[Vec<i64>], e0: &[i64]) -> Vec<BigInt> {
        let (rows, start) = (sparse(a), ints(e0));
        search(&rows, &start).candidate().expect("a candidate")
    }

    #[test]
    fn primes_are_prime_and_below_the_bound() {
        let p: Vec<u64> = primes().take(5).collect();
        assert!(p.windows(2).all(|w| w[0] > w[1]));
        assert!(p.iter().all(|&q| q < 1 << 60));
        // The primes just below 2^60 are 2^60 − 93 and 2^60 − 107 (GNU `factor` finds every
        // odd number between them and above composite).
        assert_eq!(p[..2], [(1 << 60) - 93, (1 << 60) - 107]);
    }

    #[test]
    fn berlekamp_massey_finds_known_recurrences() {
        let p = 1_000_003;
        // Fibonacci: s_k = s_{k−1} + s_{k−2}, so C = 1 − t − t².
        let mut s = vec![0u64, 1];
        for k in 2..20 {
            s.push((s[k - 1] + s[k - 2]) % p);
        }
        assert_eq!(berlekamp_massey_mod(&s, p), vec![1, p - 1, p - 1]);
        // s_k = 2 s_{k−1} − 3 s_{k−3} + 5 s_{k−4}, from a start of length 4.
        let mut s = vec![1u64, 7, 2, 9];
        for k in 4..16 {
            let v = (2 * s[k - 1] + 5 * s[k - 4] + 3 * (p - s[k - 3])) % p;
            s.push(v);
        }
        assert_eq!(berlekamp_massey_mod(&s, p), vec![1, p - 2, 0, 3, p - 5]);
        // A sequence zero from the third term: s_k = 0 for k ≥ 2 is a length-2 recurrence
        // with C = 1 (the generator t²).
        assert_eq!(berlekamp_massey_mod(&[4, 1, 0, 0, 0, 0], p), vec![1, 0, 0]);
        // The zero sequence: length 0.
        assert_eq!(berlekamp_massey_mod(&[0, 0, 0, 0], p), vec![1]);
    }

    #[test]
    fn remainders_give_back_signed_integers() {
        let values = [
            BigInt::from(-5),
            BigInt::from(123_456_789_012_345_678u64) * BigInt::from(-98_765_432_109i64),
            BigInt::zero(),
            BigInt::from(1u64 << 62) * BigInt::from(1u64 << 62),
        ];
        let mut r = Remainders::new(values.len());
        for p in primes().take(3) {
            let res: Vec<u64> = values.iter().map(|x| residue(x, p)).collect();
            r.add(&res, p);
        }
        assert_eq!(r.symmetric(), values);
    }

    #[test]
    fn modular_minimal_polynomials_agree_with_elimination() {
        // A substochastic-like matrix (scaled by 3) with a nilpotent part: 2 → 3 → out.
        let a = vec![
            vec![1, 1, 0, 0, 0],
            vec![0, 1, 1, 1, 0],
            vec![0, 0, 0, 3, 0],
            vec![0, 0, 0, 0, 0],
            vec![2, 0, 0, 0, 1],
        ];
        for e0 in [
            vec![-1, -1, -1, -1, -1],
            vec![0, 0, 1, 0, 0],
            vec![0, 0, 0, 0, 0],
            vec![5, -2, 7, 1, 0],
        ] {
            let want = brute_force(&a, &e0);
            assert_eq!(search_all(&a, &e0), want, "e0 = {e0:?}");
        }
        // A trailing zero coefficient (the generator t·(t − 1)): e_0 = (0, 1) under
        // [[0, 1], [0, 1]] gives e_1 = (1, 1) = e_k for k ≥ 1.
        let a = vec![vec![0, 1], vec![0, 1]];
        assert_eq!(search_all(&a, &[0, 1]), ints(&[1, -1, 0]));
        assert_eq!(brute_force(&a, &[0, 1]), ints(&[1, -1, 0]));
        // Pseudo-random 12 × 12 matrices, entries 0..=4 in 3 columns per row.
        let mut seed = 7u64;
        let mut next = |k: u64| {
            seed = seed.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1);
            (seed >> 33) % k
        };
        for _ in 0..6 {
            let m = 12;
            let mut a = vec![vec![0i64; m]; m];
            for row in a.iter_mut() {
                for _ in 0..3 {
                    row[next(m as u64) as usize] = next(5) as i64;
                }
            }
            let e0: Vec<i64> = (0..m).map(|_| next(7) as i64 - 3).collect();
            assert_eq!(search_all(&a, &e0), brute_force(&a, &e0));
        }
    }

    #[test]
    fn unlucky_primes_are_dropped() {
        // A = diag(2, 7), e_0 = (1, 1): μ = (t − 2)(t − 7), d = (1, −9, 14). Modulo 5,
        // A ≡ 2·I and μ_5 = t − 2: degree 1, unlucky.
        let (rows, start) = (sparse(&[vec![2, 0], vec![0, 7]]), ints(&[1, 1]));
        assert_eq!(image(&rows, &start, 5), Some(vec![1, 3]));
        assert_eq!(image(&rows, &start, 101), Some(vec![1, 92, 14]));
        // 5 alone is below the bound 2·(1 + 7) of degree 1; 101 has degree 2 and replaces it;
        // 101·103 passes the bound 2·(1 + 7)² of degree 2.
        let mut search = Search::with_primes(&rows, &start, [5, 101, 103, 107].into_iter());
        assert_eq!(search.candidate(), Some(ints(&[1, -9, 14])));
        // Had it failed its verification: no larger degree exists, so the primes run out.
        assert_eq!(search.candidate(), None);
    }

    #[test]
    fn a_rejected_candidate_gives_way_to_a_larger_degree() {
        // A = diag(2, 7), e_0 = (1, 101·103): modulo 101 and 103, e_0 ≡ (1, 0) and μ_p = t − 2,
        // and 101 alone passes the bound 2·(1 + 7) of degree 1, so the first candidate is
        // the wrong d = (1, −2).
        let (rows, start) = (sparse(&[vec![2, 0], vec![0, 7]]), ints(&[1, 101 * 103]));
        assert_eq!(image(&rows, &start, 103), Some(vec![1, 101]));
        let mut search = Search::with_primes(&rows, &start, [101, 103, 107, 109, 113].into_iter());
        assert_eq!(search.candidate(), Some(ints(&[1, -2])));
        // Rejected (its exact verification fails): 103 (degree 1) is skipped, 107·109 of
        // degree 2 pass the bound 2·(1 + 7)².
        assert_eq!(search.candidate(), Some(ints(&[1, -9, 14])));
        assert_eq!(
            brute_force(&[vec![2, 0], vec![0, 7]], &[1, 101 * 103]),
            ints(&[1, -9, 14])
        );
    }
}
