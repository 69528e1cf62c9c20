//! Products modulo `F = 2^(64n) + 1` by the negacyclic transforms of `n` points without zero
//! padding: the convolution wraps round, the words of `2^(64n)` and above subtracted from the
//! low ones, which is the product modulo `F` — half the transform length of the whole
//! product. A Barrett reduction ([`super::super::barrett`]) needs no more: its remainder
//! `t − q·m` is known to lie in `[0, 3m)`, below `F`, so it is `(t − q·m) mod F`.
//!
//! A wrapped coefficient `c_k = Σ_{i+j=k} x_i·y_j − Σ_{i+j=k+n} x_i·y_j` may be negative; with
//! `|c_k| ≤ β = n·(2⁶⁴−1)²` the residues are shifted by `β` before the recombination, which
//! then recovers `c_k + β ∈ [0, 2β]`, below `p₁p₂p₃` for `n < 2²⁰` ([`super::MAX_WORDS`] is
//! 2¹⁷); the sum `Σ β·2^(64k)` is subtracted again at the end.

use super::{below, plans, Plans, KEPT_THRESHOLD_WORDS, MAX_WORDS, PRIMES};
use dashu_base::{BitTest, UnsignedAbs};
use dashu_int::{IBig, UBig};
use std::sync::Arc;

/// A factor `x < 2^(64n)` transformed once for products modulo `2^(64n) + 1`.
pub(crate) struct Wrapped {
    n: usize,
    plans: Arc<Plans>,
    residues: Box<[u64]>,
    /// `β mod pᵢ`.
    bias: [u64; 3],
    /// `Σ_{k<n} β·2^(64k)`.
    offset: UBig,
}

impl Wrapped {
    /// `x` for products modulo `2^(64n) + 1`, `n` the smallest power of two (at least 16) with
    /// `2^(64n) > 2^bits`: `None` where `x` has fewer than [`KEPT_THRESHOLD_WORDS`] words, where
    /// `n` is not below `shorter_than` (the length a whole product would take), or above
    /// [`MAX_WORDS`].
    pub(crate) fn new(x: &UBig, bits: usize, shorter_than: usize) -> Option<Self> {
        let n = super::points(bits.div_ceil(64));
        if x.as_words().len() < KEPT_THRESHOLD_WORDS || n >= shorter_than || n > MAX_WORDS {
            return None;
        }
        assert!(x.bit_len() <= bits, "the factor is below 2^bits");
        let plans = plans(n);
        let residues = plans.transform(x.as_words());
        let beta = UBig::from(n) * UBig::from(u64::MAX) * UBig::from(u64::MAX);
        let bias = PRIMES.map(|p| {
            let r = &beta % UBig::from(p);
            u64::try_from(r).expect("below a prime")
        });
        let offset = beta * UBig::from_words(&vec![1; n]);
        Some(Wrapped {
            n,
            plans,
            residues,
            bias,
            offset,
        })
    }

    /// The words `n` of the modulus `2^(64n) + 1`.
    #[cfg(test)]
    pub(crate) fn words(&self) -> usize {
        self.n
    }

    /// `(t − x·y) mod (2^(64n) + 1)`, in `[0, 2^(64n)]`, for `y < 2^(64n)` and any `t ≥ 0`.
    pub(crate) fn difference(&self, t: &UBig, y: &UBig) -> UBig {
        let n = self.n;
        assert!(y.as_words().len() <= n, "the factor has at most n words");
        let mut c = self.plans.transform(y.as_words());
        self.plans.multiply(&mut c, &self.residues);
        self.plans.inverse(&mut c);
        for ((chunk, &b), p) in c.chunks_exact_mut(n).zip(&self.bias).zip(PRIMES) {
            for r in chunk {
                *r = below(*r + b, p);
            }
        }
        let (mut words, carry) = self.plans.recombine(&c, n);
        words.extend(carry);
        // x·y ≡ Σ c_k·2^(64k) = U − offset, U the recombined sum of c_k + β.
        let z = IBig::from(t + &self.offset) - IBig::from(UBig::from_words(&words));
        fermat_residue(z, n)
    }
}

/// `z mod (2^(64n) + 1)` in `[0, 2^(64n)]`: `2^(64n) ≡ −1`, so the number's blocks of `n`
/// words are added with alternating signs, and the sum is brought into range.
fn fermat_residue(z: IBig, n: usize) -> UBig {
    let negative = z < IBig::ZERO;
    let magnitude = z.unsigned_abs();
    let mut sum = IBig::ZERO;
    for (i, block) in magnitude.as_words().chunks(n).enumerate() {
        let block = IBig::from(UBig::from_words(block));
        if i % 2 == 0 {
            sum += block;
        } else {
            sum -= block;
        }
    }
    if negative {
        sum = -sum;
    }
    let f = IBig::from((UBig::ONE << (64 * n)) + UBig::ONE);
    while sum < IBig::ZERO {
        sum += &f;
    }
    while sum >= f {
        sum -= &f;
    }
    UBig::try_from(sum).expect("non-negative")
}

#[cfg(test)]
mod tests {
    use super::*;
    use dashu_base::RemEuclid;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    fn random(rng: &mut ChaCha8Rng, words: usize) -> UBig {
        UBig::from_words(&(0..words).map(|_| rng.next_u64()).collect::<Vec<_>>())
    }

    fn modulus(n: usize) -> UBig {
        (UBig::ONE << (64 * n)) + UBig::ONE
    }

    /// `(t − x·y) mod F` against dashu's remainder, on random factors, factors of all ones (the
    /// largest coefficients, positive before the wrap and negative after), and differences
    /// of every sign and size.
    #[test]
    fn wrapped_differences_agree_with_the_remainder_modulo_the_fermat_number() {
        let mut rng = ChaCha8Rng::seed_from_u64(11);
        for (xw, n) in [(64usize, 64usize), (100, 128), (128, 128), (700, 1024)] {
            let x = random(&mut rng, xw);
            let w = Wrapped::new(&x, 64 * n, 2 * n).expect("shorter than a whole product");
            assert_eq!(w.words(), n);
            let f = modulus(n);
            let ones = (UBig::ONE << (64 * n)) - UBig::ONE;
            let ys = [
                random(&mut rng, n),
                random(&mut rng, n / 2),
                ones.clone(),
                UBig::ZERO,
                UBig::ONE,
            ];
            for y in ys {
                let product = &x * &y;
                let ts = [
                    UBig::ZERO,
                    product.clone(),
                    &product + UBig::from(5u8),
                    &product + &f * UBig::from(3u8),
                    random(&mut rng, 3 * n),
                    (UBig::ONE << (64 * n)) * UBig::from(7u8),
                ];
                for t in ts {
                    let expected = (IBig::from(t.clone()) - IBig::from(product.clone()))
                        .rem_euclid(IBig::from(f.clone()));
                    assert_eq!(w.difference(&t, &y), expected, "{xw} words, n = {n}");
                }
            }
            // The factor itself all ones.
            let w = Wrapped::new(&ones, 64 * n, 2 * n).unwrap();
            let product = &ones * &ones;
            let expected = (IBig::ZERO - IBig::from(product)).rem_euclid(IBig::from(f.clone()));
            assert_eq!(w.difference(&UBig::ZERO, &ones), expected);
        }
    }

    #[test]
    fn a_wrap_is_taken_only_where_it_is_shorter_and_the_factor_long_enough() {
        let x = (UBig::ONE << (64 * 100 - 1)) + UBig::ONE;
        // 100 words need n = 128, which a whole product of 256 points would not save.
        assert!(Wrapped::new(&x, 64 * 100, 256).is_some());
        assert!(Wrapped::new(&x, 64 * 100, 128).is_none());
        // 6,400 bits fit in 100 words; one bit more in 101 (still n = 128), 64·128 + 1 bits
        // need 256.
        assert_eq!(Wrapped::new(&x, 64 * 100 + 1, 256).unwrap().words(), 128);
        assert_eq!(Wrapped::new(&x, 64 * 128 + 1, 1024).unwrap().words(), 256);
        // Below the kept threshold: no transforms.
        let small = UBig::ONE << (64 * (KEPT_THRESHOLD_WORDS - 1) - 1);
        assert!(Wrapped::new(&small, 64 * 64, 1024).is_none());
    }

    #[test]
    fn fermat_residues_of_blocks_with_alternating_signs() {
        let n = 16;
        let f = modulus(n);
        let mut rng = ChaCha8Rng::seed_from_u64(12);
        for words in [0usize, 1, 15, 16, 17, 33, 64, 70] {
            let z = random(&mut rng, words);
            for signed in [IBig::from(z.clone()), -IBig::from(z.clone())] {
                let expected = signed.clone().rem_euclid(IBig::from(f.clone()));
                assert_eq!(fermat_residue(signed, n), expected, "{words} words");
            }
        }
        // F − 1 = 2^(64n) and F itself.
        assert_eq!(
            fermat_residue(IBig::from(&f - UBig::ONE), n),
            &f - UBig::ONE
        );
        assert_eq!(fermat_residue(IBig::from(f.clone()), n), UBig::ZERO);
        assert_eq!(fermat_residue(-IBig::ONE, n), &f - UBig::ONE);
    }
}
