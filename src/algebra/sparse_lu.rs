//! Sparse `LU` modulo a word-size prime in a fill-reducing ordering: the factor Dixon lifting
//! ([`super::linear`]) solves with at every step when it has fewer entries than the band.
//!
//! The pattern is the symmetric pattern of `A + Aᵀ`; its symbolic factorisation
//! ([`super::ordering::Symbolic`]) is computed once per system and shared by every prime. The
//! numeric factorisation is Gaussian elimination row by row without pivoting (the systems of
//! policy evaluation have non-zero leading principal minors in every symmetric ordering; a zero
//! pivot modulo `p` makes the factorisation fail, and the caller moves on to the next prime).
//! Entries are residues below `p < 2³¹`; products are below 2⁶² and are reduced by
//! [`Modulus`] (Barrett reduction) instead of a hardware division.

use super::ordering::Symbolic;

/// Reduction modulo a fixed prime `p` with `2²⁰ < p < 2³¹` (Barrett: `μ = ⌊2⁶⁴/p⌋`).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Modulus {
    p: u64,
    mu: u64,
    /// `2⁶⁴ mod p`.
    wrap: u64,
    /// The largest multiple of `p` not above 2⁶³ (keeps lazy sums below 2⁶³ + 2⁶²).
    fold: u64,
}

impl Modulus {
    pub(crate) fn new(p: u64) -> Self {
        assert!(
            (1 << 20..1 << 31).contains(&p),
            "Modulus: p must be in [2^20, 2^31)"
        );
        let mu = u64::MAX / p; // ⌊(2⁶⁴ − 1)/p⌋ = ⌊2⁶⁴/p⌋ since p does not divide 2⁶⁴
        Modulus {
            p,
            mu,
            wrap: ((1u128 << 64) % p as u128) as u64,
            fold: (1u64 << 63) / p * p,
        }
    }

    /// The prime.
    #[inline]
    pub(crate) fn p(&self) -> u64 {
        self.p
    }

    /// `t mod p` for any `t < 2⁶⁴`: `q = ⌊t·μ/2⁶⁴⌋` exceeds `t/p − 2` (`μ > 2⁶⁴/p − 1` and
    /// `t < 2⁶⁴`) and is at most `t/p`, so `t − q·p` is in `[0, 2p)`: one subtraction.
    #[inline]
    pub(crate) fn reduce(&self, t: u64) -> u64 {
        let q = ((t as u128 * self.mu as u128) >> 64) as u64;
        let r = t - q * self.p;
        if r >= self.p {
            r - self.p
        } else {
            r
        }
    }

    /// `t mod p` for `t < 2⁹⁵` (a sum of fewer than 2³² products below 2⁶³): the high word
    /// `h < 2³¹` times `2⁶⁴ mod p` plus the reduced low word is below 2⁶³.
    #[inline]
    pub(crate) fn reduce_wide(&self, t: u128) -> u64 {
        let (high, low) = ((t >> 64) as u64, t as u64);
        debug_assert!(high < 1 << 31);
        self.reduce(high * self.wrap + self.reduce(low))
    }

    /// `a·b mod p` for `a, b < 2³²`.
    #[inline]
    pub(crate) fn mul(&self, a: u64, b: u64) -> u64 {
        self.reduce(a * b)
    }

    /// `s + t`, with `s < 2⁶³` and `t < 2⁶²`, brought back below 2⁶³ by subtracting a multiple
    /// of `p` (the residue modulo `p` is unchanged).
    #[inline]
    fn lazy_add(&self, s: u64, t: u64) -> u64 {
        let sum = s + t;
        if sum >= 1 << 63 {
            sum - self.fold
        } else {
            sum
        }
    }

    /// `a⁻¹ mod p` (`a ≢ 0`) by Fermat's little theorem.
    pub(crate) fn inverse(&self, a: u64) -> u64 {
        let (mut base, mut e, mut r) = (self.reduce(a), self.p - 2, 1);
        while e > 0 {
            if e & 1 == 1 {
                r = self.mul(r, base);
            }
            base = self.mul(base, base);
            e >>= 1;
        }
        r
    }
}

/// `Σ a_k·y[c_k]` for entries and residues below 2³¹ (products below 2⁶², summed four at a
/// time in `u64`, then in `u128`).
#[inline]
fn gather_dot(values: &[u32], columns: &[u32], y: &[u64]) -> u128 {
    let mut total = 0u128;
    let (vc, cc) = (values.chunks_exact(4), columns.chunks_exact(4));
    let (vr, cr) = (vc.remainder(), cc.remainder());
    for (v, c) in vc.zip(cc) {
        let s = v[0] as u64 * y[c[0] as usize]
            + v[1] as u64 * y[c[1] as usize]
            + v[2] as u64 * y[c[2] as usize]
            + v[3] as u64 * y[c[3] as usize];
        total += s as u128;
    }
    for (&v, &c) in vr.iter().zip(cr) {
        total += (v as u64 * y[c as usize]) as u128;
    }
    total
}

/// The pattern of a sparse `LU`: the symbolic factorisation (rows of `L`) and its transpose
/// (rows of `U`, whose pattern is that of `Lᵀ`).
#[derive(Clone, Debug)]
pub(crate) struct LuPattern {
    pub(crate) symbolic: Symbolic,
    upper_first: Vec<usize>,
    upper_columns: Vec<u32>,
}

impl LuPattern {
    pub(crate) fn new(symbolic: Symbolic) -> Self {
        let n = symbolic.order.len();
        let mut counts = vec![0usize; n];
        for &k in &symbolic.lower_columns {
            counts[k as usize] += 1;
        }
        let mut upper_first = Vec::with_capacity(n + 1);
        upper_first.push(0);
        for c in &counts {
            upper_first.push(upper_first.last().expect("non-empty") + c);
        }
        let mut fill = upper_first.clone();
        let mut upper_columns = vec![0u32; symbolic.lower_columns.len()];
        // Rows of L in increasing order: each row of U comes out ascending.
        for i in 0..n {
            for &k in symbolic.lower_row(i) {
                upper_columns[fill[k as usize]] = i as u32;
                fill[k as usize] += 1;
            }
        }
        LuPattern {
            symbolic,
            upper_first,
            upper_columns,
        }
    }

    fn lower_range(&self, i: usize) -> std::ops::Range<usize> {
        self.symbolic.lower_first[i]..self.symbolic.lower_first[i + 1]
    }

    fn upper_range(&self, i: usize) -> std::ops::Range<usize> {
        self.upper_first[i]..self.upper_first[i + 1]
    }
}

/// `A = LU` modulo `p` in the ordering of an [`LuPattern`]: `L` unit lower, the pivots'
/// inverses kept apart, and every stored entry negated (`p − entry`) so that substitution is a
/// sum of products.
pub(crate) struct SparseModularLu<'a> {
    pattern: &'a LuPattern,
    lower: Vec<u32>,
    upper: Vec<u32>,
    inverse_pivot: Vec<u64>,
    modulus: Modulus,
}

impl<'a> SparseModularLu<'a> {
    /// Factors the matrix whose row `old` has the entries `row(old)` (columns in the old
    /// numbering, all inside the pattern) modulo `modulus`; `None` on a zero pivot.
    pub(crate) fn factor<R: Iterator<Item = (usize, i64)>>(
        pattern: &'a LuPattern,
        row: impl Fn(usize) -> R,
        modulus: Modulus,
    ) -> Option<Self> {
        let symbolic = &pattern.symbolic;
        let (n, p) = (symbolic.order.len(), modulus.p());
        let negate = |v: u64| ((p - v) % p) as u32;
        let mut lower = vec![0u32; symbolic.lower_columns.len()];
        let mut upper = vec![0u32; pattern.upper_columns.len()];
        let mut inverse_pivot = vec![0u64; n];
        // Row i of the partially eliminated matrix, entries kept below 2⁶³ (lazy residues).
        let mut x = vec![0u64; n];
        for i in 0..n {
            for (j, v) in row(symbolic.order[i]) {
                let j = symbolic.position[j];
                x[j] = modulus.lazy_add(x[j], v.rem_euclid(p as i64) as u64);
            }
            for idx in pattern.lower_range(i) {
                let k = symbolic.lower_columns[idx] as usize;
                let l = modulus.mul(modulus.reduce(x[k]), inverse_pivot[k]);
                x[k] = 0;
                lower[idx] = negate(l);
                if l == 0 {
                    continue;
                }
                // x_j −= l·U_kj, as x_j += l·(p − U_kj).
                for u in pattern.upper_range(k) {
                    let j = pattern.upper_columns[u] as usize;
                    x[j] = modulus.lazy_add(x[j], l * upper[u] as u64);
                }
            }
            let pivot = modulus.reduce(x[i]);
            x[i] = 0;
            if pivot == 0 {
                return None;
            }
            inverse_pivot[i] = modulus.inverse(pivot);
            for u in pattern.upper_range(i) {
                let j = pattern.upper_columns[u] as usize;
                upper[u] = negate(modulus.reduce(x[j]));
                x[j] = 0;
            }
        }
        Some(SparseModularLu {
            pattern,
            lower,
            upper,
            inverse_pivot,
            modulus,
        })
    }

    /// The prime.
    pub(crate) fn p(&self) -> u64 {
        self.modulus.p()
    }

    /// `(order, position)`: `order[new] = old`, `position[old] = new`.
    pub(crate) fn permutation(&self) -> (&[usize], &[usize]) {
        let symbolic = &self.pattern.symbolic;
        (&symbolic.order, &symbolic.position)
    }

    /// Solves `LU·y = b` in place (new numbering; entries of `y` below `p`).
    pub(crate) fn solve(&self, y: &mut [u64]) {
        let (pattern, m) = (self.pattern, &self.modulus);
        let columns = &pattern.symbolic.lower_columns;
        for i in 0..y.len() {
            let r = pattern.lower_range(i);
            let acc = y[i] as u128 + gather_dot(&self.lower[r.clone()], &columns[r], y);
            y[i] = m.reduce_wide(acc);
        }
        for i in (0..y.len()).rev() {
            let r = pattern.upper_range(i);
            let acc =
                y[i] as u128 + gather_dot(&self.upper[r.clone()], &pattern.upper_columns[r], y);
            y[i] = m.mul(m.reduce_wide(acc), self.inverse_pivot[i]);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algebra::ordering::{nested_dissection, Graph};
    use crate::algebra::uniform;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    const P: u64 = 2_147_483_647; // 2³¹ − 1

    #[test]
    fn barrett_reduction_agrees_with_the_remainder() {
        let mut rng = ChaCha8Rng::seed_from_u64(5);
        for p in [P, 2_147_483_629, (1 << 20) + 7] {
            let m = Modulus::new(p);
            let edges = [0, 1, p - 1, p, p + 1, 2 * p - 1, u64::MAX, 1 << 63, m.fold];
            for t in edges.into_iter().chain((0..2000).map(|_| rng.next_u64())) {
                assert_eq!(m.reduce(t), t % p, "p = {p}, t = {t}");
            }
            let top = (1u128 << 95) - 1;
            for t in [0, top, 1 << 64, (1 << 64) - 1, top - p as u128]
                .into_iter()
                .chain(
                    (0..2000)
                        .map(|_| ((rng.next_u64() as u128) << 64 | rng.next_u64() as u128) >> 33),
                )
            {
                assert_eq!(m.reduce_wide(t) as u128, t % p as u128, "p = {p}, t = {t}");
            }
            for t in [0, (1u64 << 63) - 1, 1 << 62] {
                let s = m.lazy_add(t, (1 << 62) - 1);
                assert!(s < 1 << 63);
                assert_eq!(s % p, (t as u128 + (1 << 62) - 1) as u64 % p);
            }
            for a in [1, 2, p - 1, 12_345] {
                assert_eq!(a * m.inverse(a) % p, 1);
            }
        }
    }

    /// `A·y mod p` in the old numbering, straight from the rows.
    fn multiply(rows: &[Vec<(usize, i64)>], y: &[u64], p: u64) -> Vec<u64> {
        rows.iter()
            .map(|row| {
                row.iter().fold(0i128, |acc, &(j, v)| {
                    (acc + v as i128 * y[j] as i128).rem_euclid(p as i128)
                }) as u64
            })
            .collect()
    }

    fn random_rows(n: usize, seed: u64) -> Vec<Vec<(usize, i64)>> {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        (0..n)
            .map(|i| {
                let mut row = vec![(i, uniform(&mut rng, 20, 1000))];
                for _ in 0..uniform(&mut rng, 0, 4) {
                    row.push((uniform(&mut rng, 0, n), -uniform(&mut rng, 1, 5)));
                }
                row
            })
            .collect()
    }

    fn pattern_of(rows: &[Vec<(usize, i64)>]) -> LuPattern {
        let graph = Graph::from_entries(
            rows.len(),
            rows.iter()
                .enumerate()
                .flat_map(|(i, row)| row.iter().map(move |&(j, _)| (i, j))),
        );
        let order = nested_dissection(&graph);
        LuPattern::new(Symbolic::new(&graph, order))
    }

    /// The solve maps `A·y` back to `y` for random `y` (an independent check: only the rows
    /// are multiplied, not the factor).
    #[test]
    fn the_sparse_factor_inverts_the_matrix_modulo_p() {
        let mut rng = ChaCha8Rng::seed_from_u64(11);
        for (n, seed) in [(1, 0), (5, 1), (60, 2), (400, 3)] {
            let rows = random_rows(n, seed);
            let pattern = pattern_of(&rows);
            let lu =
                SparseModularLu::factor(&pattern, |i| rows[i].iter().copied(), Modulus::new(P))
                    .expect("diagonally dominant: no zero pivot");
            for _ in 0..3 {
                let want: Vec<u64> = (0..n).map(|_| uniform(&mut rng, 0, P)).collect();
                let b = multiply(&rows, &want, P);
                let mut y: Vec<u64> = (0..n).map(|new| b[pattern.symbolic.order[new]]).collect();
                lu.solve(&mut y);
                let got: Vec<u64> = (0..n)
                    .map(|old| y[pattern.symbolic.position[old]])
                    .collect();
                assert_eq!(got, want, "n = {n}");
            }
        }
    }

    /// A zero leading minor modulo `p` in the elimination order is reported (`None`), not
    /// divided by: `[[p, 1], [1, 1]]` in the order 0, 1 has the pivot `p ≡ 0`; `[[p + 2, 1],
    /// [1, 1]]` has the pivots 2 and `1 − 1/2`.
    #[test]
    fn a_zero_pivot_modulo_p_is_refused() {
        let rows = |a: i64| vec![vec![(0, a), (1, 1)], vec![(0, 1), (1, 1)]];
        let graph = Graph::from_entries(2, [(0, 1)]);
        let pattern = LuPattern::new(Symbolic::new(&graph, vec![0, 1]));
        let zero = rows(P as i64);
        assert!(
            SparseModularLu::factor(&pattern, |i| zero[i].iter().copied(), Modulus::new(P))
                .is_none()
        );
        let fine = rows(P as i64 + 2);
        assert!(
            SparseModularLu::factor(&pattern, |i| fine[i].iter().copied(), Modulus::new(P))
                .is_some()
        );
    }
}
