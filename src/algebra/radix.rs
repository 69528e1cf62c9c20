//! The decimal text of many big integers of about the same size: divide and conquer by the
//! powers `P_j = 10^(19·2^j)`, each with a Barrett reciprocal whose transforms
//! ([`super::ntt`]) are computed once for all the numbers. A number below `P_j` splits into its
//! quotient and remainder by `P_{j−1}`, both written with exactly `19·2^(j−1)` digits (leading
//! zeros), down to numbers of a few words, which `malachite` converts. Each split is a Barrett
//! division: two products, of the number's top half by the reciprocal and of the quotient by
//! the power.
//!
//! The values of an exact optimum share their size (10⁴ values of 36,000 digits each at
//! 10⁴ states and γ = 0.999), so the table of powers is built once and each conversion costs a
//! few products of transformed factors per level.

use super::barrett::Barrett;
use super::lowest_terms::magnitude;
use dashu_base::BitTest;
use dashu_int::UBig;
use num_bigint::BigInt;
use num_traits::Signed;

/// `10¹⁹`, the largest power of ten in a word.
const WORD_POWER: u64 = 10_000_000_000_000_000_000;

/// Powers of fewer words than this have no Barrett reciprocal: a number below the square of
/// such a power is converted by `malachite` (whose conversion is fast at these sizes: with
/// `dashu`'s instead, 10⁴ conversions of 36,000 digits took about 20 % longer). With 96 the
/// leaves are below `P₇ = 10²⁴³²` (127 words); a conversion of 36,000 digits took 1.13 times as
/// long with leaves below `P₅` (32 words), 1.05 times below `P₆` and 1.11 times below `P₈`
/// (`cargo bench --bench big_integers -- decimal/radix`, alternated, two rounds).
const LEAF_WORDS: usize = 96;

/// One power `P_j = 10^(19·2^j)`.
struct Level {
    power: UBig,
    /// `19·2^j`, the digits of a remainder by `P_j`.
    digits: usize,
    /// Division by `P_j` for numbers below `P_j²`, where `P_j` has [`LEAF_WORDS`] words or more
    /// (the powers grow with `j`, so the levels without one are the first ones, `P₀` among
    /// them).
    barrett: Option<Barrett>,
}

/// The powers for the decimal text of integers of up to a given size.
pub struct DecimalPowers {
    levels: Vec<Level>,
}

impl DecimalPowers {
    /// Powers for numbers below `2^bits` (larger ones are converted by `malachite` alone).
    ///
    /// ```
    /// use num_bigint::BigInt;
    /// use truecost::algebra::radix::DecimalPowers;
    /// let x = num_traits::pow(BigInt::from(3), 20_000) - 1;
    /// let powers = DecimalPowers::new(32_000);
    /// assert_eq!(powers.text(&x), x.to_string());
    /// assert_eq!(powers.text(&-x.clone()), (-x).to_string());
    /// ```
    pub fn new(bits: u64) -> Self {
        let mut levels = Vec::new();
        let mut power = UBig::from(WORD_POWER);
        let mut digits = 19;
        // Up to the first P_j with P_j² ≥ 2^(2(b−1)) above 2^(bits+62), b the bits of P_j.
        loop {
            let last = 2 * power.bit_len() as u64 > bits + 64;
            let next = (!last).then(|| &power * &power);
            let barrett = (power.as_words().len() >= LEAF_WORDS).then(|| Barrett::new(&power));
            levels.push(Level {
                power,
                digits,
                barrett,
            });
            match next {
                Some(next) => power = next,
                None => break,
            }
            digits *= 2;
        }
        DecimalPowers { levels }
    }

    /// The decimal text of `x`, the same string as `x.to_string()`.
    pub fn text(&self, x: &BigInt) -> String {
        let magnitude = magnitude(x);
        let mut out = Vec::with_capacity(magnitude.as_words().len() * 20 + 1);
        if x.is_negative() {
            out.push(b'-');
        }
        self.write(magnitude, &mut out, &mut malachite_text);
        String::from_utf8(out).expect("digits and a sign only")
    }

    /// The digits of `x` (no leading zeros; "0" for zero), the pieces the powers do not split
    /// (the leaves) converted by `leaf`.
    fn write(&self, x: UBig, out: &mut Vec<u8>, leaf: Leaf) {
        let top = self.levels.last().expect("at least one level");
        // Below 2^(2(b−1)) ≤ P², b the bits of the largest power P.
        if x.bit_len() > 2 * (top.power.bit_len() - 1) {
            out.extend_from_slice(leaf(&x).as_bytes());
            return;
        }
        // The smallest j with x < P_j², then leading digits by P_j.
        let j = self
            .levels
            .iter()
            .position(|l| x.bit_len() <= l.power.bit_len())
            .unwrap_or(self.levels.len() - 1);
        self.leading(x, j, out, leaf);
    }

    /// The digits of `x < P_j²` without leading zeros.
    fn leading(&self, x: UBig, j: usize, out: &mut Vec<u8>, leaf: Leaf) {
        let level = &self.levels[j];
        match &level.barrett {
            None => out.extend_from_slice(leaf(&x).as_bytes()),
            // j ≥ 1: P₀ has no reciprocal.
            Some(_) if x < level.power => self.leading(x, j - 1, out, leaf),
            Some(barrett) => {
                let (q, r) = barrett.div_rem(x);
                self.leading(q, j, out, leaf);
                self.padded(r, j, out, leaf);
            }
        }
    }

    /// The digits of `x < P_j`, exactly `19·2^j` of them (leading zeros).
    fn padded(&self, x: UBig, j: usize, out: &mut Vec<u8>, leaf: Leaf) {
        match j
            .checked_sub(1)
            .and_then(|i| self.levels[i].barrett.as_ref())
        {
            Some(barrett) => {
                let (q, r) = barrett.div_rem(x);
                self.padded(q, j - 1, out, leaf);
                self.padded(r, j - 1, out, leaf);
            }
            None => {
                let text = leaf(&x);
                out.resize(out.len() + self.levels[j].digits - text.len(), b'0');
                out.extend_from_slice(text.as_bytes());
            }
        }
    }
}

/// The conversion of the leaves, the numbers the powers do not split.
type Leaf<'a> = &'a mut dyn FnMut(&UBig) -> String;

/// The decimal text of `x` by `malachite`'s conversion.
fn malachite_text(x: &UBig) -> String {
    malachite_nz::natural::Natural::from_limbs_asc(x.as_words()).to_string()
}

#[cfg(test)]
mod tests {
    use super::*;
    use num_traits::{One, Zero};
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    fn random(rng: &mut ChaCha8Rng, words: usize) -> BigInt {
        let w: Vec<u64> = (0..words).map(|_| rng.next_u64()).collect();
        BigInt::from(num_bigint::BigUint::from_slice(
            &w.iter()
                .flat_map(|&x| [x as u32, (x >> 32) as u32])
                .collect::<Vec<_>>(),
        ))
    }

    #[test]
    fn texts_agree_with_num_bigint_on_random_numbers_of_many_sizes() {
        let mut rng = ChaCha8Rng::seed_from_u64(8);
        let powers = DecimalPowers::new(64 * 2000);
        for words in [
            1, 2, 5, 23, 24, 25, 47, 48, 49, 100, 113, 500, 999, 1000, 1875, 2000,
        ] {
            for _ in 0..3 {
                let x = random(&mut rng, words);
                assert_eq!(powers.text(&x), x.to_string(), "{words} words");
                assert_eq!(powers.text(&-x.clone()), (-x).to_string(), "{words} words");
            }
        }
        // Beyond the table: converted whole.
        let x = random(&mut rng, 4500);
        assert_eq!(powers.text(&x), x.to_string());
    }

    #[test]
    fn powers_of_ten_and_their_neighbours_keep_every_zero() {
        let powers = DecimalPowers::new(64 * 600);
        assert_eq!(powers.text(&BigInt::zero()), "0");
        let ten = BigInt::from(10);
        for k in [
            0usize, 1, 18, 19, 20, 37, 38, 39, 76, 152, 304, 455, 456, 457, 608, 912, 1216, 2432,
            4864, 9728, 11_000,
        ] {
            let p = num_traits::pow(ten.clone(), k);
            for x in [
                &p - BigInt::one(),
                p.clone(),
                &p + BigInt::one(),
                &p * 7 + 3,
            ] {
                if x.is_zero() {
                    continue;
                }
                assert_eq!(powers.text(&x), x.to_string(), "10^{k} neighbour");
            }
        }
        // A number whose middle is all zeros.
        let x = num_traits::pow(ten.clone(), 5000) * 12345 + 67;
        assert_eq!(powers.text(&x), x.to_string());
    }

    /// The leaves of `x`'s conversion: the numbers handed to `malachite`, in words.
    fn leaves(powers: &DecimalPowers, x: &BigInt) -> Vec<usize> {
        let mut words = Vec::new();
        let mut out = Vec::new();
        powers.write(magnitude(x), &mut out, &mut |leaf: &UBig| {
            words.push(leaf.as_words().len());
            malachite_text(leaf)
        });
        assert_eq!(String::from_utf8(out).unwrap(), x.to_string());
        words
    }

    #[test]
    fn numbers_within_the_table_are_split_into_small_leaves_and_larger_ones_converted_whole() {
        let mut rng = ChaCha8Rng::seed_from_u64(10);
        let powers = DecimalPowers::new(64 * 1000);
        // A leaf is below P_j² for a power P_j without a reciprocal (fewer than LEAF_WORDS
        // words), so it has fewer than 2·LEAF_WORDS words.
        let w = 2 * LEAF_WORDS;
        for words in [1, w - 1, w, w + 1, 400, 999, 1000] {
            let x = random(&mut rng, words);
            let leaves = leaves(&powers, &x);
            assert!(
                leaves.iter().all(|&w| w < 2 * LEAF_WORDS),
                "{words}: {leaves:?}"
            );
            let expected = if words < 2 * LEAF_WORDS { 1 } else { 2 };
            assert!(leaves.len() >= expected, "{words}: {leaves:?}");
        }
        // The largest power P has b bits: numbers of up to 2(b−1) bits are split, larger
        // ones converted whole.
        let b = powers.levels.last().unwrap().power.bit_len();
        let at = (BigInt::one() << (2 * (b - 1))) - 1;
        let leaves_at = leaves(&powers, &at);
        assert!(leaves_at.len() > 1 && leaves_at.iter().all(|&w| w < 2 * LEAF_WORDS));
        for x in [at + 1, BigInt::one() << (2 * b), random(&mut rng, 5000)] {
            assert_eq!(leaves(&powers, &x), vec![magnitude(&x).as_words().len()]);
        }
    }

    #[test]
    fn a_small_table_still_converts_large_numbers() {
        let mut rng = ChaCha8Rng::seed_from_u64(9);
        let powers = DecimalPowers::new(10);
        for words in [1, 30, 300] {
            let x = random(&mut rng, words);
            assert_eq!(powers.text(&x), x.to_string());
        }
    }
}
