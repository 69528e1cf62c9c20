//! Products of big natural numbers by number-theoretic transforms: the convolution of the two
//! numbers' 64-bit words is computed modulo three primes below 2⁵⁰ (each `≡ 1 mod 2²²`) by
//! `tfhe-ntt`'s negacyclic transforms — zero-padded to twice the words, so nothing wraps round
//! — and each coefficient is recovered exactly by the Chinese remainder theorem, since it is
//! below `min(words)·(2⁶⁴−1)² < p₁p₂p₃` (Garner's formula; eight coefficients at a time with
//! AVX-512 IFMA where the processor has it, `ntt/ifma.rs`); then the carries are propagated.
//!
//! At the sizes of an exact optimum's values (10⁴ states at γ = 0.999: numbers of 120,000
//! bits) one product takes about a third of `dashu`'s Toom–Cook product. A factor used many
//! times (a modulus, a Barrett reciprocal) is transformed once: [`Transformed`]. Below
//! [`THRESHOLD_WORDS`] words ([`KEPT_THRESHOLD_WORDS`] with a factor transformed once), and
//! above [`MAX_WORDS`], the product is `dashu`'s.

use super::modular::inv_mod;
use dashu_int::UBig;
use std::collections::HashMap;
use std::sync::{Arc, Mutex, OnceLock};
use tfhe_ntt::prime64::Plan;

#[cfg(target_arch = "x86_64")]
mod ifma;
mod wrapped;

pub(crate) use wrapped::Wrapped;

/// The three primes, each `k·2²² + 1` below 2⁵⁰ (so transforms of up to 2²¹ points exist, and
/// `tfhe-ntt` takes its 52-bit multiply-add path where the processor has one).
pub const PRIMES: [u64; 3] = [
    1_125_899_831_345_153,
    1_125_899_818_762_241,
    1_125_899_726_487_553,
];

/// The smaller operand's words from which [`mul`] transforms (below, `dashu`'s product is as
/// fast or faster: at 96 words they are within 10 %, at 128 words the transforms take 0.7 of
/// the time, at 512 a third).
pub const THRESHOLD_WORDS: usize = 112;

/// The smaller operand's words from which a [`Transformed`] factor's products transform: one
/// transform of three is saved, and with the other factor's transform kept a product of two
/// numbers of 64 words takes 1.7 µs against `dashu`'s 2.6 µs (48 words: 1.5 µs and 1.6 µs;
/// 80 words: 2.8 µs and 3.5 µs).
pub const KEPT_THRESHOLD_WORDS: usize = 64;

/// The words of a product above which [`mul`] falls back to `dashu`: transforms of at most
/// 2¹⁷ points, whose tables (kept for every length used, 4 words a point and prime) take
/// 13 MB at that length, 26 MB for all lengths. The primes allow 2²¹ points, and the
/// coefficients' bound `2²⁰·(2⁶⁴−1)² < p₁p₂p₃` holds up to there.
pub const MAX_WORDS: usize = 1 << 17;
const _: () = assert!(MAX_WORDS <= 1 << 21, "the primes' longest transform");

/// `a·b`, by transforms when both have at least [`THRESHOLD_WORDS`] words and the product at
/// most [`MAX_WORDS`].
///
/// ```
/// use dashu_int::UBig;
/// use truecost::algebra::ntt::mul;
/// let a = (UBig::ONE << 10_000) - UBig::ONE;
/// let b = (UBig::ONE << 9_000) + UBig::from(12345u32);
/// assert_eq!(mul(&a, &b), &a * &b);
/// ```
pub fn mul(a: &UBig, b: &UBig) -> UBig {
    let (la, lb) = (a.as_words().len(), b.as_words().len());
    if !transforms(la, lb) {
        return a * b;
    }
    let plans = plans(points(la + lb));
    let mut x = plans.transform(a.as_words());
    let y = plans.transform(b.as_words());
    plans.multiply(&mut x, &y);
    plans.product(&mut x, la + lb)
}

/// Whether [`mul`] multiplies factors of `la` and `lb` words by transforms.
fn transforms(la: usize, lb: usize) -> bool {
    la.min(lb) >= THRESHOLD_WORDS && la + lb <= MAX_WORDS
}

/// A factor transformed once for products with factors of up to `other` words.
pub struct Transformed {
    value: UBig,
    /// `None` where `x` or `other` is below [`KEPT_THRESHOLD_WORDS`] words, or the product
    /// above [`MAX_WORDS`].
    transform: Option<(Arc<Plans>, Box<[u64]>)>,
    other: usize,
}

impl Transformed {
    /// `x`, for products `x·y` with `y` of at most `other` words (longer ones are multiplied
    /// as [`mul`] does).
    ///
    /// ```
    /// use dashu_int::UBig;
    /// use truecost::algebra::ntt::Transformed;
    /// let m = (UBig::ONE << 8_000) - UBig::from(59u32);
    /// let t = Transformed::new(&m, 130);
    /// let y = (UBig::ONE << 8_200) / UBig::from(7u32);
    /// assert_eq!(t.mul(&y), &m * &y);
    /// ```
    pub fn new(x: &UBig, other: usize) -> Self {
        let lx = x.as_words().len();
        let transform =
            (lx.min(other) >= KEPT_THRESHOLD_WORDS && lx + other <= MAX_WORDS).then(|| {
                let plans = plans(points(lx + other));
                let residues = plans.transform(x.as_words());
                (plans, residues)
            });
        Transformed {
            value: x.clone(),
            transform,
            other,
        }
    }

    /// The factor.
    pub fn value(&self) -> &UBig {
        &self.value
    }

    /// Whether the product with a factor of `words` words uses the kept transforms (otherwise
    /// [`mul`] computes it from scratch).
    ///
    /// ```
    /// use dashu_int::UBig;
    /// use truecost::algebra::ntt::Transformed;
    /// let t = Transformed::new(&((UBig::ONE << 8_000) - UBig::ONE), 130);
    /// assert!(t.transforms(130) && !t.transforms(131));
    /// ```
    pub fn transforms(&self, words: usize) -> bool {
        self.transform.is_some() && (KEPT_THRESHOLD_WORDS..=self.other).contains(&words)
    }

    /// `x·y`.
    pub fn mul(&self, y: &UBig) -> UBig {
        let ly = y.as_words().len();
        match &self.transform {
            Some((plans, residues)) if self.transforms(ly) => {
                let mut t = plans.transform(y.as_words());
                plans.multiply(&mut t, residues);
                plans.product(&mut t, self.value.as_words().len() + ly)
            }
            _ => mul(&self.value, y),
        }
    }
}

/// The transform length for a product of `words` words: a power of two, at least 16
/// (`tfhe-ntt`'s smallest).
fn points(words: usize) -> usize {
    words.next_power_of_two().max(16)
}

/// The plans of one transform length, shared by every product of that length.
fn plans(n: usize) -> Arc<Plans> {
    static CACHE: OnceLock<Mutex<HashMap<usize, Arc<Plans>>>> = OnceLock::new();
    let cache = CACHE.get_or_init(|| Mutex::new(HashMap::new()));
    let mut map = cache.lock().unwrap_or_else(|e| e.into_inner());
    map.entry(n)
        .or_insert_with(|| Arc::new(Plans::new(n)))
        .clone()
}

/// `a·w mod p` for a fixed `w < p < 2⁶³` and any `a < 2⁶⁴` (Shoup: `w' = ⌊w·2⁶⁴/p⌋`).
#[derive(Clone, Copy)]
struct Shoup {
    w: u64,
    w_shoup: u64,
}

impl Shoup {
    fn new(w: u64, p: u64) -> Self {
        Shoup {
            w,
            w_shoup: (((w as u128) << 64) / p as u128) as u64,
        }
    }

    /// `a·w mod p`: the estimate `q = ⌊a·w'/2⁶⁴⌋` is `⌊a·w/p⌋` or one less, so
    /// `a·w − q·p` (computed modulo 2⁶⁴) is below `2p`.
    #[inline]
    fn mul(self, a: u64, p: u64) -> u64 {
        let q = ((a as u128 * self.w_shoup as u128) >> 64) as u64;
        let r = a.wrapping_mul(self.w).wrapping_sub(q.wrapping_mul(p));
        below(r, p)
    }
}

/// Three transforms of one length and the constants of the Chinese remainder theorem.
struct Plans {
    n: usize,
    plans: [Plan; 3],
    /// `⌊(2⁶⁴−1)/pᵢ⌋`, for reducing words.
    reciprocals: [u64; 3],
    garner: Garner,
}

impl Plans {
    fn new(n: usize) -> Self {
        let plan = |p: u64| Plan::try_new(n, p).expect("each prime is 1 modulo 2^22");
        Plans {
            n,
            plans: PRIMES.map(plan),
            reciprocals: PRIMES.map(|p| u64::MAX / p),
            garner: Garner::new(),
        }
    }

    /// The three transforms of a number's words, one after the other.
    fn transform(&self, words: &[u64]) -> Box<[u64]> {
        let n = self.n;
        let mut out = vec![0u64; 3 * n].into_boxed_slice();
        for (k, (chunk, plan)) in out.chunks_exact_mut(n).zip(&self.plans).enumerate() {
            let (p, m) = (PRIMES[k], self.reciprocals[k]);
            for (r, &w) in chunk.iter_mut().zip(words) {
                *r = below(word_remainder(w, p, m), p);
            }
            plan.fwd(chunk);
        }
        out
    }

    /// `x ← x·y` point by point (and divided by `n`, which the inverse transform expects).
    fn multiply(&self, x: &mut [u64], y: &[u64]) {
        let n = self.n;
        for ((xc, yc), plan) in x
            .chunks_exact_mut(n)
            .zip(y.chunks_exact(n))
            .zip(&self.plans)
        {
            plan.mul_assign_normalize(xc, yc);
        }
    }

    /// The number whose words' convolution `t` holds (transformed), `words` words at most.
    fn product(&self, t: &mut [u64], words: usize) -> UBig {
        self.inverse(t);
        let (out, carry) = self.recombine(t, words);
        debug_assert!(carry == [0, 0, 0], "the product has the words given");
        UBig::from_words(&out)
    }

    /// The inverse transforms: `t` then holds each coefficient's residues, one prime after
    /// the other.
    fn inverse(&self, t: &mut [u64]) {
        for (chunk, plan) in t.chunks_exact_mut(self.n).zip(&self.plans) {
            plan.inv(chunk);
        }
    }

    /// The words `Σ_{k<words} X_k·2^(64k)` of the coefficients `X_k` whose residues `t` holds
    /// (one prime after the other, each below its prime), and the carry left above them (three
    /// words).
    fn recombine(&self, t: &[u64], words: usize) -> (Vec<u64>, [u64; 3]) {
        let n = self.n;
        let (r0, rest) = t.split_at(n);
        let (r1, r2) = rest.split_at(n);
        let mut out = vec![0u64; words];
        // The pending carry: a number below 2¹⁵¹ in three words.
        let mut carry = [0u64; 3];
        #[cfg(target_arch = "x86_64")]
        let done = if ifma::available() {
            ifma::recombine(&self.garner, [r0, r1, r2], &mut out, &mut carry)
        } else {
            0
        };
        #[cfg(not(target_arch = "x86_64"))]
        let done = 0;
        for k in done..words {
            out[k] = accumulate(&mut carry, self.garner.coefficient(r0[k], r1[k], r2[k]));
        }
        (out, carry)
    }
}

/// Garner's recombination of a convolution's coefficient from its residues modulo the three
/// [`PRIMES`] `p₁, p₂, p₃`: `X = a + p₁·t₁ + p₁p₂·t₂` with `t₁ = (b − a)·p₁⁻¹ mod p₂` and
/// `t₂ = (c − a − p₁·t₁)·(p₁p₂)⁻¹ mod p₃`, the one number below `p₁p₂p₃` that is `≡ a, b, c`.
struct Garner {
    /// `p₁⁻¹ mod p₂`.
    inv01: Shoup,
    /// `(p₁p₂)⁻¹ mod p₃`.
    inv012: Shoup,
    /// `p₂⁻¹ mod p₃`.
    inv12: Shoup,
}

impl Garner {
    fn new() -> Self {
        let [p0, p1, p2] = PRIMES;
        let p0p1_mod_p2 = ((p0 as u128 * p1 as u128) % p2 as u128) as u64;
        Garner {
            inv01: Shoup::new(inv_mod(p0 % p1, p1), p1),
            inv012: Shoup::new(inv_mod(p0p1_mod_p2, p2), p2),
            inv12: Shoup::new(inv_mod(p1 % p2, p2), p2),
        }
    }

    /// The coefficient `X < p₁p₂p₃ < 2¹⁵⁰` with residues `a < p₁`, `b < p₂`, `c < p₃`, as
    /// three words (least significant first).
    #[inline]
    fn coefficient(&self, a: u64, b: u64, c: u64) -> [u64; 3] {
        let [p0, p1, p2] = PRIMES;
        let p0p1 = p0 as u128 * p1 as u128;
        let (pl, ph) = (p0p1 as u64 as u128, p0p1 >> 64);
        // x₀₁ = a + p₁·t₁ ≡ a (mod p₁), ≡ b (mod p₂).
        let t1 = self.inv01.mul(b + p1 - below(a, p1), p1);
        let x01 = a as u128 + p0 as u128 * t1 as u128;
        // t₂ = (c − x₀₁)·(p₁p₂)⁻¹ = (c − a)·(p₁p₂)⁻¹ − t₁·p₂⁻¹ (mod p₃): the first product
        // does not wait for t₁.
        let u = self.inv012.mul(c + p2 - below(a, p2), p2);
        let t2 = below(u + p2 - self.inv12.mul(t1, p2), p2);
        // X = x₀₁ + p₁p₂·t₂.
        let low = x01 + pl * t2 as u128; // < 2¹¹⁵
        let high = (low >> 64) + ph * t2 as u128; // < 2⁸⁸
        [low as u64, high as u64, (high >> 64) as u64]
    }
}

/// Adds the coefficient `x` (three words) to the pending `carry` and returns the word that is
/// complete: the coefficient of `2^(64k)` adds into the words from `k` on.
#[inline]
fn accumulate(carry: &mut [u64; 3], x: [u64; 3]) -> u64 {
    let s0 = carry[0] as u128 + x[0] as u128;
    let s1 = carry[1] as u128 + x[1] as u128 + (s0 >> 64);
    let s2 = carry[2] as u128 + x[2] as u128 + (s1 >> 64);
    *carry = [s1 as u64, s2 as u64, (s2 >> 64) as u64];
    s0 as u64
}

/// `w − ⌊w·m/2⁶⁴⌋·p` for `m = ⌊(2⁶⁴−1)/p⌋`: `w mod p` or `w mod p + p`. With `2⁶⁴ − 1 = m·p + ρ`
/// and `R` the low word of `w·m`, it is `(w·(ρ+1) + R·p)/2⁶⁴ < ρ + 1 + p ≤ 2p`.
#[inline]
fn word_remainder(w: u64, p: u64, m: u64) -> u64 {
    w - ((w as u128 * m as u128) >> 64) as u64 * p
}

/// `x mod p` for `x < 2p` without a branch: `x − p` wraps round above `x` when `x < p`.
#[inline]
fn below(x: u64, p: u64) -> u64 {
    x.min(x.wrapping_sub(p))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algebra::modular::is_prime;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    fn random(rng: &mut ChaCha8Rng, words: usize) -> UBig {
        let w: Vec<u64> = (0..words).map(|_| rng.next_u64()).collect();
        UBig::from_words(&w)
    }

    #[test]
    fn the_primes_are_primes_one_modulo_two_to_the_22_and_bound_the_coefficients() {
        for p in PRIMES {
            assert!(is_prime(p), "{p}");
            assert_eq!(p % (1 << 22), 1, "{p}");
            assert!(p < 1 << 50);
        }
        // A coefficient of a product of at most 2²¹ words (the primes' longest transform) is
        // below 2²⁰·(2⁶⁴−1)², which must be below p₁p₂p₃.
        let product = UBig::from(PRIMES[0]) * UBig::from(PRIMES[1]) * UBig::from(PRIMES[2]);
        let max = UBig::from(1u64 << 20) * UBig::from(u64::MAX) * UBig::from(u64::MAX);
        assert!(max < product);
    }

    #[test]
    fn products_agree_with_dashu_on_random_and_extreme_words() {
        let mut rng = ChaCha8Rng::seed_from_u64(3);
        let sizes = [
            (112, 112),
            (112, 113),
            (130, 400),
            (500, 37),
            (1000, 1000),
            (1024, 1024),
            (1025, 1023),
            (1875, 1875),
            (3000, 700),
        ];
        for (la, lb) in sizes {
            let (a, b) = (random(&mut rng, la), random(&mut rng, lb));
            assert_eq!(mul(&a, &b), &a * &b, "{la} × {lb} words");
            assert_eq!(
                Transformed::new(&a, lb).mul(&b),
                &a * &b,
                "{la} × {lb} words"
            );
        }
        // Every word 2⁶⁴ − 1: the largest coefficients, at the length where the transform is
        // full.
        for words in [112, 1024, 2048] {
            let ones = (UBig::ONE << (64 * words)) - UBig::ONE;
            assert_eq!(mul(&ones, &ones), &ones * &ones, "{words} words of ones");
        }
        // Zero, one and small factors go through dashu.
        let a = random(&mut rng, 300);
        for b in [UBig::ZERO, UBig::ONE, UBig::from(7u32)] {
            assert_eq!(mul(&a, &b), &a * &b);
            assert_eq!(Transformed::new(&a, 300).mul(&b), &a * &b);
        }
    }

    /// Residue triples: random ones, and every combination of 0, 1, `p − 1` and `p − 2`.
    fn residue_triples(rng: &mut ChaCha8Rng, random: usize) -> Vec<[u64; 3]> {
        let edges = |p: u64| [0, 1, p - 2, p - 1];
        let mut triples = Vec::new();
        for a in edges(PRIMES[0]) {
            for b in edges(PRIMES[1]) {
                for c in edges(PRIMES[2]) {
                    triples.push([a, b, c]);
                }
            }
        }
        triples.extend((0..random).map(|_| PRIMES.map(|p| rng.next_u64() % p)));
        triples
    }

    #[test]
    fn garner_recombines_each_residue_triple_into_the_one_coefficient_below_the_product() {
        let garner = Garner::new();
        let product = PRIMES.iter().map(|&p| UBig::from(p)).product::<UBig>();
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        for [a, b, c] in residue_triples(&mut rng, 5000) {
            let x = UBig::from_words(&garner.coefficient(a, b, c));
            assert!(x < product, "{a}, {b}, {c}");
            for (r, p) in [a, b, c].into_iter().zip(PRIMES) {
                assert_eq!(&x % UBig::from(p), UBig::from(r), "{a}, {b}, {c} mod {p}");
            }
        }
    }

    /// The words of `Σ X_k·2^(64k)` by the portable loop alone.
    fn recombined(garner: &Garner, triples: &[[u64; 3]]) -> (Vec<u64>, [u64; 3]) {
        let mut carry = [0; 3];
        let words = triples
            .iter()
            .map(|&[a, b, c]| accumulate(&mut carry, garner.coefficient(a, b, c)))
            .collect();
        (words, carry)
    }

    #[test]
    fn carries_add_up_the_coefficients_into_the_number() {
        let garner = Garner::new();
        let mut rng = ChaCha8Rng::seed_from_u64(8);
        let triples = residue_triples(&mut rng, 300);
        let (words, carry) = recombined(&garner, &triples);
        let mut all = words.clone();
        all.extend(carry);
        let sum = triples.iter().rev().fold(UBig::ZERO, |acc, &[a, b, c]| {
            (acc << 64) + UBig::from_words(&garner.coefficient(a, b, c))
        });
        assert_eq!(UBig::from_words(&all), sum);
    }

    /// On a processor with AVX-512 IFMA the products recombine eight coefficients at a time
    /// (`ifma::recombine`); its words and carry must be the portable loop's, on residues at
    /// their edges and random ones, for lengths around multiples of eight. (Without those
    /// instructions there is nothing to compare: the portable loop alone is used, and the
    /// other tests check it.)
    #[cfg(target_arch = "x86_64")]
    #[test]
    fn the_vector_recombination_gives_the_portable_words_and_carry() {
        if !ifma::available() {
            eprintln!("this processor has no AVX-512 IFMA: only the portable recombination runs");
            return;
        }
        let garner = Garner::new();
        let mut rng = ChaCha8Rng::seed_from_u64(9);
        let all = residue_triples(&mut rng, 2000);
        for len in [0, 7, 8, 9, 63, 64, 65, all.len()] {
            let triples = &all[all.len() - len..];
            let [r0, r1, r2] = [0, 1, 2].map(|i| triples.iter().map(|t| t[i]).collect::<Vec<_>>());
            let mut out = vec![0; len];
            let mut carry = [0; 3];
            let done = ifma::recombine(&garner, [&r0, &r1, &r2], &mut out, &mut carry);
            assert_eq!(done, len / 8 * 8);
            for k in done..len {
                out[k] = accumulate(&mut carry, garner.coefficient(r0[k], r1[k], r2[k]));
            }
            assert_eq!(
                (out, carry),
                recombined(&garner, triples),
                "{len} coefficients"
            );
        }
    }

    /// The vector recombination is used exactly where the processor reports both features
    /// (Linux's `/proc/cpuinfo` flags, read independently of the standard library's
    /// detection).
    #[cfg(all(target_arch = "x86_64", target_os = "linux"))]
    #[test]
    fn the_vector_recombination_is_used_where_the_processor_has_ifma() {
        let cpuinfo = std::fs::read_to_string("/proc/cpuinfo").expect("/proc/cpuinfo");
        let flags: Vec<&str> = cpuinfo
            .lines()
            .find_map(|l| l.strip_prefix("flags"))
            .expect("a flags line")
            .split_whitespace()
            .collect();
        let has = |f: &str| flags.contains(&f);
        assert_eq!(ifma::available(), has("avx512f") && has("avx512ifma"));
    }

    /// The inverse transforms hand over residues below their primes, which the recombination
    /// (and its 52-bit lanes) assume.
    #[test]
    fn inverse_transforms_give_residues_below_their_primes() {
        let mut rng = ChaCha8Rng::seed_from_u64(10);
        let plans = plans(1024);
        let ones = vec![u64::MAX; 512];
        let words: Vec<u64> = (0..512).map(|_| rng.next_u64()).collect();
        for (x, y) in [(&ones, &ones), (&words, &ones), (&words, &words)] {
            let mut t = plans.transform(x);
            plans.multiply(&mut t, &plans.transform(y));
            for (chunk, plan) in t.chunks_exact_mut(1024).zip(&plans.plans) {
                plan.inv(chunk);
            }
            for (chunk, p) in t.chunks_exact(1024).zip(PRIMES) {
                assert!(chunk.iter().all(|&r| r < p), "{p}");
            }
        }
    }

    /// Products transform from [`THRESHOLD_WORDS`] words in the shorter factor up to
    /// [`MAX_WORDS`] in the product (the path only changes the time, so it is checked here).
    #[test]
    fn products_transform_between_the_thresholds() {
        let (t, max) = (THRESHOLD_WORDS, MAX_WORDS);
        assert!(transforms(t, t) && transforms(t, max - t) && transforms(max - t, t));
        assert!(!transforms(t - 1, t) && !transforms(t, t - 1) && !transforms(t - 1, 5000));
        assert!(!transforms(t, max - t + 1) && !transforms(max / 2 + 1, max / 2));
    }

    #[test]
    fn a_transformed_factor_serves_shorter_and_longer_factors() {
        let mut rng = ChaCha8Rng::seed_from_u64(4);
        let m = random(&mut rng, 900);
        let t = Transformed::new(&m, 900);
        assert_eq!(t.value(), &m);
        for words in [1, 63, 64, 65, 111, 112, 200, 899, 900, 901, 2000] {
            let y = random(&mut rng, words);
            assert_eq!(t.mul(&y), &m * &y, "{words} words");
            assert_eq!(t.transforms(words), (64..=900).contains(&words), "{words}");
        }
        // Factors from the kept threshold on: both at 64 words transform, at 63 neither.
        for (lx, other) in [(64, 64), (63, 64), (64, 63), (63, 63)] {
            let (x, y) = (random(&mut rng, lx), random(&mut rng, other));
            let t = Transformed::new(&x, other);
            assert_eq!(t.transform.is_some(), lx.min(other) >= 64, "{lx}, {other}");
            assert_eq!(t.mul(&y), &x * &y, "{lx} × {other} words");
        }
        // A factor below the threshold is never transformed.
        let small = Transformed::new(&UBig::from(5u32), 900);
        assert!(small.transform.is_none());
        let y = random(&mut rng, 900);
        assert_eq!(small.mul(&y), &y * UBig::from(5u32));
    }

    /// The words' reduction: `w − ⌊w·m/2⁶⁴⌋·p < 2p`, so one conditional subtraction gives
    /// `w mod p`, at the largest words and at random ones.
    #[test]
    fn a_word_is_reduced_with_one_subtraction() {
        let mut rng = ChaCha8Rng::seed_from_u64(6);
        for p in PRIMES {
            let m = u64::MAX / p;
            let words = (0..1000u64)
                .map(|k| u64::MAX - k)
                .chain((1..1000u64).map(|k| (u64::MAX / p - k) * p + p - 1))
                .chain((0..5000).map(|_| rng.next_u64()));
            for w in words {
                let t = word_remainder(w, p, m);
                assert!(t < 2 * p, "p = {p}, w = {w}");
                assert_eq!(below(t, p), w % p, "p = {p}, w = {w}");
            }
        }
    }

    #[test]
    fn shoup_multiplication_agrees_with_the_remainder() {
        let mut rng = ChaCha8Rng::seed_from_u64(5);
        for p in PRIMES {
            for _ in 0..2000 {
                let w = rng.next_u64() % p;
                let a = rng.next_u64();
                let s = Shoup::new(w, p);
                assert_eq!(s.mul(a, p) as u128, a as u128 * w as u128 % p as u128);
            }
            assert_eq!(
                Shoup::new(p - 1, p).mul(u64::MAX, p) as u128,
                (u64::MAX as u128 * (p as u128 - 1)) % p as u128
            );
            let inv = inv_mod(12345, p);
            assert_eq!(inv as u128 * 12345 % p as u128, 1);
        }
    }
}
