//! Barrett reduction modulo a fixed big modulus: the quotient estimated from a reciprocal
//! computed once, two products of transformed factors ([`super::ntt`]) per reduction. Used by
//! the lifting's conversions ([`super::linear`]), lowest terms' product modulo the rough part
//! ([`super::lowest_terms`]) and the decimal text's splits ([`super::radix`]).

use super::ntt::{Transformed, Wrapped};
use dashu_base::BitTest;
use dashu_int::UBig;

/// Barrett reduction modulo a fixed `m`, the reciprocal `μ = ⌊2^(2k+slack)/m⌋` computed once:
/// two multiplications instead of a long division (which is quadratic in `dashu` at these
/// sizes), each by a factor whose transforms are kept ([`super::ntt::Transformed`]). The
/// product `q̂·m` is needed only modulo a number above the remainder: where `m` is long enough,
/// modulo `2^(64n) + 1` by transforms of half the length ([`Wrapped`]).
pub(crate) struct Barrett {
    m: UBig,
    k: usize,
    /// Extra bits allowed above `2^(2k)` in the argument of [`reduce`](Self::reduce).
    slack: usize,
    /// `μ`, transformed for products with the argument's top bits.
    mu: Transformed,
    /// `m`, transformed for the products `q̂·m`.
    product: Product,
}

/// How a Barrett reduction multiplies its quotients by `m`.
enum Product {
    /// Whole products, `m`'s transforms kept.
    Kept(Transformed),
    /// Modulo `2^(64n) + 1` with `2^(64n) > 4m`, where that is shorter than the whole product.
    Wrapped(Wrapped),
}

impl Barrett {
    /// Reduction of arguments below `2^(2k)` (`k` the bits of `m > 0`).
    pub(crate) fn new(m: &UBig) -> Self {
        Self::with_slack(m, 0)
    }

    /// Reduction of arguments below `2^(2k+slack)`.
    pub(crate) fn with_slack(m: &UBig, slack: usize) -> Self {
        let k = m.bit_len();
        // Both products' other factors, `⌊t/2^(k−1)⌋` and the quotient, are below
        // 2^(k+1+slack).
        let words = (k + slack + 1).div_ceil(64);
        // The remainder before the correction is below 3m < 2^(k+2), the quotient below
        // 2^(k+1+slack): both below 2^(k+2+slack).
        let whole = (m.as_words().len() + words).next_power_of_two();
        let product = match Wrapped::new(m, k + 2 + slack, whole) {
            Some(wrapped) => Product::Wrapped(wrapped),
            None => Product::Kept(Transformed::new(m, words)),
        };
        Barrett {
            m: m.clone(),
            k,
            slack,
            mu: Transformed::new(&((UBig::ONE << (2 * k + slack)) / m), words),
            product,
        }
    }

    /// `t mod m` for `0 ≤ t < 2^(2k+slack)`. With `t' = ⌊t/2^(k−1)⌋` and the estimate
    /// `q̂ = ⌊t'·μ/2^(k+1+slack)⌋`, each of the three floors loses less than 1 against `t/m`
    /// (`t' < 2^(k+1+slack)` and `2^(k−1) ≤ m`), so `q̂` is short by at most 2.
    pub(crate) fn reduce(&self, t: UBig) -> UBig {
        self.div_rem(t).1
    }

    /// `(⌊t/m⌋, t mod m)` for `0 ≤ t < 2^(2k+slack)`, the quotient as in
    /// [`reduce`](Self::reduce).
    pub(crate) fn div_rem(&self, t: UBig) -> (UBig, UBig) {
        let mut q = self.mu.mul(&(&t >> (self.k - 1))) >> (self.k + 1 + self.slack);
        let mut r = match &self.product {
            Product::Kept(kept) => t - kept.mul(&q),
            // t − q̂·m lies in [0, 3m), below 2^(64n) + 1: it is its own residue.
            Product::Wrapped(wrapped) => wrapped.difference(&t, &q),
        };
        while r >= self.m {
            r -= &self.m;
            q += UBig::ONE;
        }
        (q, r)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    #[test]
    fn barrett_reduction_agrees_with_division() {
        let mut rng = ChaCha8Rng::seed_from_u64(9);
        for words in [1usize, 3, 40, 200] {
            let words_of = |rng: &mut ChaCha8Rng, k: usize| -> UBig {
                let w: Vec<u64> = (0..k).map(|_| rng.next_u64()).collect();
                UBig::from_le_bytes(&w.iter().flat_map(|x| x.to_le_bytes()).collect::<Vec<_>>())
            };
            let m = words_of(&mut rng, words) + UBig::from(3u8);
            let b = Barrett::new(&m);
            for _ in 0..50 {
                let t = words_of(&mut rng, 2 * words) % (&m * &m);
                assert_eq!(b.reduce(t.clone()), &t % &m);
                assert_eq!(b.div_rem(t.clone()), (&t / &m, &t % &m));
            }
            assert_eq!(b.reduce(&m * &m - UBig::ONE), (&m * &m - UBig::ONE) % &m);
            // Multiples of m, and their neighbours: where the estimate falls short by one, the
            // remainder before the correction is m itself, which must become 0.
            for c in [1u64, 2, 3, 1 << 20, u64::MAX] {
                let c = UBig::from(c) % &m;
                if c == UBig::ZERO {
                    continue;
                }
                for t in [&c * &m, &c * &m - UBig::ONE, &c * &m + UBig::ONE] {
                    assert_eq!(b.div_rem(t.clone()), (&t / &m, &t % &m));
                }
            }
            for _ in 0..50 {
                let c = words_of(&mut rng, words) % &m;
                let t = &c * &m;
                assert_eq!(b.div_rem(t.clone()), (c, UBig::ZERO));
            }
            // With slack: arguments up to 2^(2k+slack) − 1, against the remainder of a division.
            for slack in [1usize, 7, 64, 130] {
                let b = Barrett::with_slack(&m, slack);
                let top = (UBig::ONE << (2 * m.bit_len() + slack)) - UBig::ONE;
                for t in [top.clone(), &top >> 1usize, (&m << slack) * &m - UBig::ONE] {
                    assert_eq!(b.reduce(t.clone()), t % &m, "slack {slack}");
                }
                for _ in 0..20 {
                    let t = words_of(&mut rng, 2 * words + slack.div_ceil(64) + 1) % &top;
                    assert_eq!(b.reduce(t.clone()), t % &m, "slack {slack}");
                }
            }
        }
    }

    #[test]
    fn the_largest_arguments_take_kept_and_wrapped_transforms_of_the_shortest_lengths() {
        for (words, slack) in [
            (200usize, 0usize),
            (200, 1),
            (200, 63),
            (200, 64),
            (333, 130),
        ] {
            let m = (UBig::ONE << (64 * words - 1)) + UBig::from(12_345u32);
            let k = m.bit_len();
            let b = Barrett::with_slack(&m, slack);
            let top = (UBig::ONE << (2 * k + slack)) - UBig::ONE;
            // The factors of div_rem's two products at the largest argument, and one word
            // more than the longer of them: kept transforms for both, none for that (the
            // transforms are no longer than the products need).
            let shifted = (&top >> (k - 1)).as_words().len();
            let quotient = (&top / &m).as_words().len();
            let longest = shifted.max(quotient);
            assert!(b.mu.transforms(shifted), "{words}, {slack}");
            assert!(!b.mu.transforms(longest + 1), "{words}, {slack}");
            // q̂·m is wrapped: modulo 2^(64n) + 1 with 2^(64n) > 4m and the quotient below
            // 2^(64n), n the shortest such power of two, half the whole product's length.
            let Product::Wrapped(wrapped) = &b.product else {
                panic!("{words}, {slack}: not wrapped");
            };
            let n = wrapped.words();
            assert!(n.is_power_of_two(), "{words}, {slack}");
            let limit = UBig::ONE << (64 * n);
            assert!(
                limit > &m * UBig::from(4u8) && limit > &top / &m,
                "{words}, {slack}"
            );
            assert!(
                UBig::ONE << (32 * n) <= &m << (slack + 2),
                "{words}, {slack}"
            );
            assert_eq!(2 * n, (m.as_words().len() + longest).next_power_of_two());
            assert_eq!(b.div_rem(top.clone()), (&top / &m, &top % &m));
        }
        // Below the kept threshold nothing is wrapped, and m's products are dashu's.
        let m = (UBig::ONE << (64 * 40)) + UBig::from(7u8);
        let b = Barrett::new(&m);
        assert!(matches!(&b.product, Product::Kept(kept) if !kept.transforms(41)));
        let t = &m * &m - UBig::from(3u8);
        assert_eq!(b.div_rem(t.clone()), (&t / &m, &t % &m));
    }
}
