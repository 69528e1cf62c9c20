//! The residual of Dixon lifting (step 3 of [`super`]'s module docs): `r ← (r − A·z)/p`
//! after each solve modulo `p`, kept in the factor's numbering so that the next right-hand side
//! `r mod p` is read in place.
//!
//! While `Σ_j |A_ij|·p < 2⁶²` for every row and `|r| < 2⁶²`, every partial sum fits in `i64` and
//! the exact division by `p` is a multiplication by `p⁻¹ mod 2⁶⁴`; otherwise the update is done
//! in checked `i128`. Both give the same integers.

use super::{LinearError, SparseSystem};
use crate::algebra::sparse_lu::Modulus;

/// `A` with rows and columns in a factor's numbering, and the current residual.
pub(crate) struct Residual {
    first: Vec<usize>,
    columns: Vec<u32>,
    values: Vec<i64>,
    r: Vec<i128>,
    modulus: Modulus,
    /// `p⁻¹ mod 2⁶⁴`.
    inverse: u64,
    /// Whether `Σ_j |A_ij|·p < 2⁶²` in every row.
    narrow_rows: bool,
    /// Whether `|r_i| < 2⁶²` for every `i`.
    small: bool,
}

/// Below this, sums of a residual entry and a row's products fit in `i64`.
const SMALL: u128 = 1 << 62;

impl Residual {
    /// The residual `r = rhs` of `system` in the numbering `order` (`order[new] = old`,
    /// `position[old] = new`).
    pub(crate) fn new(
        system: &SparseSystem,
        order: &[usize],
        position: &[usize],
        modulus: Modulus,
    ) -> Self {
        let n = system.len();
        let p = modulus.p();
        let (mut first, mut columns, mut values) = (vec![0], Vec::new(), Vec::new());
        let mut narrow_rows = true;
        for &old in order {
            let mut sum = 0u128;
            for (j, v) in system.row(old) {
                columns.push(position[j] as u32);
                values.push(v);
                sum += v.unsigned_abs() as u128;
            }
            narrow_rows &= sum * p as u128 <= SMALL;
            first.push(columns.len());
        }
        let r: Vec<i128> = order.iter().map(|&old| system.rhs(old)).collect();
        // Newton's iteration doubles the correct low bits of the inverse of an odd p: p·p ≡ 1
        // modulo 8, so five steps give 3·2⁵ ≥ 64 bits.
        let mut inverse = p;
        for _ in 0..5 {
            inverse = inverse.wrapping_mul(2u64.wrapping_sub(p.wrapping_mul(inverse)));
        }
        debug_assert_eq!(p.wrapping_mul(inverse), 1);
        let small = r.iter().all(|v| v.unsigned_abs() < SMALL);
        debug_assert_eq!(r.len(), n);
        Residual {
            first,
            columns,
            values,
            r,
            modulus,
            inverse,
            narrow_rows,
            small,
        }
    }

    /// `y = r mod p`, entry by entry in `[0, p)`.
    pub(crate) fn residues(&self, y: &mut [u64]) {
        let (m, p) = (&self.modulus, self.modulus.p());
        for (y, &r) in y.iter_mut().zip(&self.r) {
            *y = match i64::try_from(r) {
                Ok(r) if r >= 0 => m.reduce(r as u64),
                Ok(r) => match m.reduce(r.unsigned_abs()) {
                    0 => 0,
                    t => p - t,
                },
                Err(_) => r.rem_euclid(p as i128) as u64,
            };
        }
    }

    /// `r ← (r − A·z)/p` for `z ≡ A⁻¹·r (mod p)` (entries in `[0, p)`, the factor's numbering);
    /// the division is exact. [`LinearError::TooLarge`] if an intermediate sum leaves `i128`.
    pub(crate) fn update(&mut self, z: &[u64]) -> Result<(), LinearError> {
        let p = self.modulus.p();
        let mut largest = 0u128;
        if self.narrow_rows && self.small {
            for (i, r) in self.r.iter_mut().enumerate() {
                let range = self.first[i]..self.first[i + 1];
                let mut s = *r as i64;
                for (&c, &v) in self.columns[range.clone()].iter().zip(&self.values[range]) {
                    s -= v * z[c as usize] as i64;
                }
                debug_assert_eq!(s.rem_euclid(p as i64), 0);
                let q = s.wrapping_mul(self.inverse as i64);
                largest = largest.max(q.unsigned_abs() as u128);
                *r = q as i128;
            }
        } else {
            let pi = p as i128;
            for (i, r) in self.r.iter_mut().enumerate() {
                let range = self.first[i]..self.first[i + 1];
                let mut s = *r;
                for (&c, &v) in self.columns[range.clone()].iter().zip(&self.values[range]) {
                    s = s
                        .checked_sub(v as i128 * z[c as usize] as i128)
                        .ok_or(LinearError::TooLarge)?;
                }
                debug_assert_eq!(s.rem_euclid(pi), 0);
                let q = s / pi;
                largest = largest.max(q.unsigned_abs());
                *r = q;
            }
        }
        self.small = largest < SMALL;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algebra::uniform;
    use rand::SeedableRng;
    use rand_chacha::ChaCha8Rng;

    /// Each update against the definition computed in `i128` with a division, in a scrambled
    /// numbering, with a matrix narrow enough for the `i64` path and one that is not (entries
    /// near 2⁴⁰), and a right-hand side beyond `i64` that becomes small after a few steps.
    #[test]
    fn the_update_is_the_exact_quotient_on_both_paths() {
        let p = 2_147_483_647u64;
        let modulus = Modulus::new(p);
        let mut rng = ChaCha8Rng::seed_from_u64(3);
        for (n, scale) in [(30usize, 1000i64), (30, 1 << 40)] {
            let mut system = SparseSystem::new();
            let mut rows = Vec::new();
            for i in 0..n {
                let row: Vec<(usize, i64)> = (0..3)
                    .map(|_| (uniform(&mut rng, 0, n), uniform(&mut rng, -scale, scale)))
                    .chain([(i, scale)])
                    .collect();
                let rhs = uniform(&mut rng, -(1i128 << 99), 1i128 << 99);
                system.push_row(&row, rhs).unwrap();
                rows.push(system.row(i).collect::<Vec<_>>());
            }
            let mut order: Vec<usize> = (0..n).collect();
            order.reverse();
            order.swap(0, n / 2);
            let mut position = vec![0; n];
            for (new, &old) in order.iter().enumerate() {
                position[old] = new;
            }
            let mut residual = Residual::new(&system, &order, &position, modulus);
            let mut want: Vec<i128> = (0..n).map(|i| system.rhs(i)).collect();
            for _ in 0..6 {
                let mut y = vec![0u64; n];
                residual.residues(&mut y);
                for old in 0..n {
                    assert_eq!(y[position[old]] as i128, want[old].rem_euclid(p as i128));
                }
                // A z with A·z ≡ r (mod p): any z, after moving r by its offset from A·z.
                let z: Vec<u64> = (0..n).map(|_| uniform(&mut rng, 0, p)).collect();
                for old in 0..n {
                    let az: i128 = rows[old]
                        .iter()
                        .map(|&(j, v)| v as i128 * z[position[j]] as i128)
                        .sum();
                    let off = (want[old] - az).rem_euclid(p as i128);
                    residual.r[position[old]] -= off;
                    let s = want[old] - off - az;
                    assert_eq!(s % p as i128, 0);
                    want[old] = s / p as i128;
                }
                residual.small = residual.r.iter().all(|v| v.unsigned_abs() < SMALL);
                residual.update(&z).unwrap();
                for old in 0..n {
                    assert_eq!(residual.r[position[old]], want[old], "n = {n}");
                }
            }
        }
    }
}
