//! Exact fractions in lowest terms: one value ([`reduced`]), a greatest common divisor
//! ([`gcd`]), and the many numerators of a policy evaluation over their one common denominator
//! ([`reduced_all`], which the exact optimum's values go through before they are printed).
//!
//! The gcds run on `dashu`'s Lehmer gcd, subquadratic where `num-bigint`'s binary gcd takes a
//! step per bit.

use super::barrett::Barrett;
use super::ntt::mul;
use dashu_base::{BitTest, DivRem, Gcd};
use dashu_int::UBig;
use num_bigint::BigInt;
use num_traits::{One, Signed, Zero};

/// `n/d` in lowest terms (`d > 0`), reduced with `dashu`'s Lehmer gcd: on numbers of tens of
/// thousands of digits it is hundreds of times faster than `num-bigint`'s binary gcd, which
/// made printing the exact values of a 50×50 grid take longer than computing them.
///
/// ```
/// use num_bigint::BigInt;
/// use truecost::algebra::lowest_terms::reduced;
/// assert_eq!(reduced(&BigInt::from(-6), &BigInt::from(4)).to_string(), "-3/2");
/// ```
pub fn reduced(n: &BigInt, d: &BigInt) -> crate::value::Rational {
    assert!(
        d > &BigInt::zero(),
        "reduced: the denominator must be positive"
    );
    let (un, ud) = (magnitude(n), magnitude(d));
    let g = (&un).gcd(&ud);
    divided(n, &un, d, &ud, &g)
}

/// `gcd(a, b) ≥ 0` by `dashu`'s gcd (`gcd(0, 0) = 0`): `num-bigint`'s binary gcd takes a
/// step per bit even when one operand is small, quadratic in the other's length.
///
/// ```
/// use num_bigint::BigInt;
/// use truecost::algebra::lowest_terms::gcd;
/// let big = BigInt::from(3).pow(5000) * 14;
/// assert_eq!(gcd(&big, &BigInt::from(-21)), BigInt::from(21));
/// assert_eq!(gcd(&BigInt::from(0), &BigInt::from(-4)), BigInt::from(4));
/// assert_eq!(gcd(&BigInt::from(0), &BigInt::from(0)), BigInt::from(0));
/// ```
pub fn gcd(a: &BigInt, b: &BigInt) -> BigInt {
    if a.is_zero() || b.is_zero() {
        return (a + b).abs();
    }
    let (ua, ub) = (magnitude(a), magnitude(b));
    from_ubig(&(&ua).gcd(&ub))
}

/// `|x|` as a `dashu` integer.
pub(crate) fn magnitude(x: &BigInt) -> UBig {
    UBig::from_words(&x.magnitude().to_u64_digits())
}

/// A `dashu` natural number as a `num-bigint` integer.
fn from_ubig(x: &UBig) -> BigInt {
    BigInt::from(num_bigint::BigUint::from_bytes_le(&x.to_le_bytes()))
}

/// `n/d` (`d > 0`, `un = |n|`, `ud = d`) divided through by their common factor `g`.
fn divided(n: &BigInt, un: &UBig, d: &BigInt, ud: &UBig, g: &UBig) -> crate::value::Rational {
    if *g == UBig::ONE {
        return crate::value::Rational::new_raw(n.clone(), d.clone());
    }
    let rn = from_ubig(&(un / g));
    let rn = if n < &BigInt::zero() { -rn } else { rn };
    crate::value::Rational::new_raw(rn, from_ubig(&(ud / g)))
}

/// `nᵢ/d` in lowest terms for many numerators over one denominator `d > 0`, equal to
/// [`reduced`] of each.
///
/// `d = S·R` is split into its smooth part `S` (the prime powers `pᵉ` of `d` with primes below
/// [`SMOOTH_PRIMES_BELOW`], found by trial division) and the rest `R`, coprime to `S`; then
/// `gcd(nᵢ, d) = gcd(nᵢ, S)·gcd(nᵢ, R)`. The first factor is taken prime by prime: the power of
/// 2 from the trailing zeros, and an odd `p` costs one remainder by a word unless it divides
/// `nᵢ` (then `gcd(nᵢ mod pᵉ, pᵉ)`; a policy evaluation's values share their common factors
/// with `d` in small primes). The second is batched over all numerators: every `gcd(nᵢ, R)`
/// divides `h = gcd(R, Πᵢ nᵢ mod R)` (the product taken by a balanced tree in parallel, one
/// product and one Barrett reduction per numerator, and one gcd of numbers of `d`'s size), so
/// `gcd(nᵢ, R) = gcd(nᵢ mod h, h)`, and `h = 1` (no prime of `R` divides any numerator) is the
/// usual case. With `R = 1` there is no product at all.
///
/// ```
/// use num_bigint::BigInt;
/// use truecost::algebra::lowest_terms::reduced_all;
/// let n: Vec<BigInt> = [-6, 0, 5, 12, 18, -9, 7].into_iter().map(BigInt::from).collect();
/// let r = reduced_all(&n.iter().collect::<Vec<_>>(), &BigInt::from(36));
/// let text: Vec<String> = r.iter().map(|v| v.to_string()).collect();
/// assert_eq!(text, ["-1/6", "0", "5/36", "1/3", "1/2", "-1/4", "7/36"]);
/// ```
pub fn reduced_all(numerators: &[&BigInt], d: &BigInt) -> Vec<crate::value::Rational> {
    use rayon::prelude::*;
    use std::collections::HashMap;
    assert!(
        d > &BigInt::zero(),
        "reduced_all: the denominator must be positive"
    );
    let ud = magnitude(d);
    let (powers, rough) = smooth_factors(&ud);
    let magnitudes: Vec<UBig> = numerators.par_iter().map(|n| magnitude(n)).collect();
    // gcd(nᵢ, S) for every numerator (1 for nᵢ = 0, whose value is 0/1 anyway).
    let common: Vec<UBig> = magnitudes
        .par_iter()
        .map(|un| smooth_gcd(un, &powers))
        .collect();
    // h = gcd(R, Π nᵢ mod R) over the non-zero numerators.
    let h = if rough == UBig::ONE {
        UBig::ONE
    } else {
        let nonzero: Vec<&UBig> = magnitudes.iter().filter(|m| !m.is_zero()).collect();
        let product = product_modulo(&nonzero, &rough);
        if product.is_zero() {
            rough.clone()
        } else {
            (&rough).gcd(&product)
        }
    };
    // The reduced denominators d/gᵢ, each distinct one computed (and converted) once.
    let mut denominators: HashMap<UBig, BigInt> = HashMap::new();
    let factors: Vec<UBig> = magnitudes
        .par_iter()
        .zip(common)
        .map(|(un, g)| {
            if h == UBig::ONE || un.is_zero() {
                g
            } else {
                let r = un % &h;
                let extra = if r.is_zero() { h.clone() } else { (&h).gcd(&r) };
                g * extra
            }
        })
        .collect();
    for g in &factors {
        denominators.entry(g.clone()).or_insert_with(|| {
            if *g == UBig::ONE {
                d.clone()
            } else {
                from_ubig(&(&ud / g))
            }
        });
    }
    numerators
        .par_iter()
        .zip(magnitudes)
        .zip(factors)
        .map(|((n, un), g)| {
            if un.is_zero() {
                return crate::value::Rational::new_raw(BigInt::zero(), BigInt::one());
            }
            let m = if g == UBig::ONE {
                (*n).clone()
            } else {
                from_ubig(&(un / &g))
            };
            let m = if n.is_negative() && !m.is_negative() {
                -m
            } else {
                m
            };
            crate::value::Rational::new_raw(m, denominators[&g].clone())
        })
        .collect()
}

/// Primes below this bound make up the smooth part of [`reduced_all`]'s denominator.
pub const SMOOTH_PRIMES_BELOW: u32 = 1 << 16;

/// A prime power `pᵉ` dividing a number exactly (`p` below [`SMOOTH_PRIMES_BELOW`]).
struct PrimePower {
    prime: u64,
    exponent: usize,
    power: UBig,
}

/// The prime powers of `x > 0` with primes below [`SMOOTH_PRIMES_BELOW`] (increasing primes),
/// and the rest of `x` (no prime factor below the bound).
fn smooth_factors(x: &UBig) -> (Vec<PrimePower>, UBig) {
    let mut rest = x.clone();
    let mut powers = Vec::new();
    let twos = rest.trailing_zeros().unwrap_or(0);
    if twos > 0 {
        rest >>= twos;
        powers.push(PrimePower {
            prime: 2,
            exponent: twos,
            power: UBig::ONE << twos,
        });
    }
    let bound = SMOOTH_PRIMES_BELOW as usize;
    let mut composite = vec![false; bound];
    for p in 3..bound {
        if composite[p] {
            continue;
        }
        for multiple in (p * p..bound).step_by(p) {
            composite[multiple] = true;
        }
        if p % 2 == 0 || &rest % (p as u64) != 0 {
            continue;
        }
        let word = UBig::from(p as u64);
        let mut power = UBig::ONE;
        let mut exponent = 0;
        loop {
            let (q, r) = (&rest).div_rem(&word);
            if !r.is_zero() {
                break;
            }
            rest = q;
            power *= &word;
            exponent += 1;
        }
        powers.push(PrimePower {
            prime: p as u64,
            exponent,
            power,
        });
    }
    (powers, rest)
}

/// `(S, R)` with `x = S·R`: `S` the product of the prime powers of `x` (`x > 0`) with primes
/// below [`SMOOTH_PRIMES_BELOW`], `R` the rest (no prime factor below the bound).
#[cfg(test)]
fn smooth_part(x: &UBig) -> (UBig, UBig) {
    let (powers, rest) = smooth_factors(x);
    (powers.iter().map(|p| &p.power).product(), rest)
}

/// `gcd(n, S)` for `S` the product of `powers` (1 for `n = 0`): `2^min(v₂(n), e)` from the
/// trailing zeros; an odd `p` that does not divide `n` contributes nothing, one that does
/// contributes `gcd(n mod pᵉ, pᵉ)`. Whether `p` divides `n` is read off `n` modulo a product of
/// up to four of the odd primes (below 2¹⁶ each, so the product fits in a word): one
/// remainder by a word for every four primes.
fn smooth_gcd(n: &UBig, powers: &[PrimePower]) -> UBig {
    let mut g = UBig::ONE;
    if n.is_zero() {
        return g;
    }
    if let Some(two) = powers.iter().find(|p| p.prime == 2) {
        g <<= n.trailing_zeros().unwrap_or(0).min(two.exponent);
    }
    let odd: Vec<&PrimePower> = powers.iter().filter(|p| p.prime != 2).collect();
    for group in odd.chunks(4) {
        let product: u64 = group.iter().map(|p| p.prime).product();
        let r = n % product;
        for p in group {
            if r.is_multiple_of(p.prime) {
                let r = n % &p.power;
                g *= if r.is_zero() {
                    p.power.clone()
                } else {
                    (&p.power).gcd(&r)
                };
            }
        }
    }
    g
}

/// `Π values mod m` (`m > 1`; values non-zero), by a balanced product tree whose halves are
/// taken in parallel, every product reduced modulo `m` by [`Barrett`]: one product and one
/// reduction per value. A value more than a word wider than `m` is reduced first (by the same
/// Barrett reduction up to twice `m`'s width, by a long division beyond).
fn product_modulo(values: &[&UBig], m: &UBig) -> UBig {
    const SLACK: usize = 128;
    let k = m.bit_len();
    let barrett = Barrett::with_slack(m, SLACK);
    let leaf = |v: &UBig| -> UBig {
        let bits = v.bit_len();
        if bits <= k + SLACK / 2 {
            v.clone()
        } else if bits <= 2 * k + SLACK {
            barrett.reduce(v.clone())
        } else {
            v % m
        }
    };
    // Every operand of a product is below 2^(k + SLACK/2), so every product is below
    // 2^(2k + SLACK).
    fn tree(values: &[&UBig], leaf: &(dyn Fn(&UBig) -> UBig + Sync), barrett: &Barrett) -> UBig {
        match values {
            [] => UBig::ONE,
            [v] => leaf(v),
            _ if values.len() <= 8 => values[1..].iter().fold(leaf(values[0]), |acc, v| {
                barrett.reduce(mul(&acc, &leaf(v)))
            }),
            _ => {
                let (left, right) = values.split_at(values.len() / 2);
                let (a, b) =
                    rayon::join(|| tree(left, leaf, barrett), || tree(right, leaf, barrett));
                barrett.reduce(mul(&a, &b))
            }
        }
    }
    tree(values, &leaf, &barrett)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The smooth part at the bound, by hand: 65,521 is the largest prime below 2¹⁶ and goes to
    /// `S` with 2⁵ and 3²; 65,537 (the next prime above 2¹⁶) and the Mersenne prime 2⁶¹ − 1 stay
    /// in `R`; 1 is all rest-free.
    #[test]
    fn the_smooth_part_takes_the_primes_below_the_bound() {
        let big = |v: u64| UBig::from(v);
        let mersenne = big((1 << 61) - 1);
        let smooth = big(32 * 9 * 65_521);
        let rough = big(65_537) * &mersenne * &mersenne;
        assert_eq!(smooth_part(&(&smooth * &rough)), (smooth.clone(), rough));
        assert_eq!(smooth_part(&smooth), (smooth, UBig::ONE));
        assert_eq!(smooth_part(&mersenne), (UBig::ONE, mersenne));
        assert_eq!(smooth_part(&UBig::ONE), (UBig::ONE, UBig::ONE));
    }

    use num_integer::Integer;
    use num_rational::BigRational;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// A random natural number of `bits` bits (the top bit set).
    fn random_ubig(rng: &mut ChaCha8Rng, bits: usize) -> UBig {
        let words: Vec<u64> = (0..bits.div_ceil(64)).map(|_| rng.next_u64()).collect();
        let bytes: Vec<u8> = words.iter().flat_map(|w| w.to_le_bytes()).collect();
        let x = UBig::from_le_bytes(&bytes) >> (64 * words.len() - bits);
        x | (UBig::ONE << (bits - 1))
    }

    /// A number in `lo..hi`.
    fn between(rng: &mut ChaCha8Rng, lo: usize, hi: usize) -> usize {
        lo + (rng.next_u64() % (hi - lo) as u64) as usize
    }

    fn to_big(x: &UBig) -> BigInt {
        BigInt::from(num_bigint::BigUint::from_bytes_le(&x.to_le_bytes()))
    }

    /// The Mersenne primes 2⁶¹ − 1 and 2⁸⁹ − 1 and 65,537: primes above the smooth bound.
    fn large_primes() -> Vec<BigInt> {
        vec![
            (BigInt::one() << 61) - 1,
            (BigInt::one() << 89) - 1,
            BigInt::from(65_537),
        ]
    }

    /// `reduced_all` against `num-rational`'s reduction (its own binary gcd) of every value, on
    /// denominators with small primes (powers of 2, 3 and the largest prime below the bound),
    /// large primes (to the first and higher powers) and a random rough part, and numerators
    /// with planted common factors: small prime powers, a large prime, the whole rough part,
    /// `d` itself, 0 and negative values.
    #[test]
    fn every_value_is_reduced_as_num_rational_reduces_it() {
        let mut rng = ChaCha8Rng::seed_from_u64(52);
        let large = large_primes();
        for case in 0..12 {
            let small: BigInt = BigInt::from(2).pow(between(&mut rng, 0, 70) as u32)
                * BigInt::from(3).pow(between(&mut rng, 0, 30) as u32)
                * BigInt::from(65_521).pow(between(&mut rng, 0, 3) as u32);
            let mut rough = to_big(&random_ubig(&mut rng, 64 + 400 * (case % 4)));
            for p in &large {
                rough *= p.pow(between(&mut rng, 0, 3) as u32);
            }
            let d = &small * &rough;
            let count = 1 + (case * 7) % 40;
            let numerators: Vec<BigInt> = (0..count)
                .map(|i| {
                    let bits = 1 + between(&mut rng, 0, 900);
                    let base = to_big(&random_ubig(&mut rng, bits));
                    let planted = match between(&mut rng, 0, 8) {
                        0 => base * BigInt::from(2).pow(between(&mut rng, 0, 80) as u32),
                        1 => base * BigInt::from(3).pow(between(&mut rng, 1, 40) as u32),
                        2 => base * &large[i % large.len()],
                        3 => base * &rough,
                        4 => base * &d,
                        5 => BigInt::zero(),
                        _ => base,
                    };
                    if rng.next_u32() % 10 < 3 {
                        -planted
                    } else {
                        planted
                    }
                })
                .collect();
            let refs: Vec<&BigInt> = numerators.iter().collect();
            let got = reduced_all(&refs, &d);
            assert_eq!(got.len(), numerators.len());
            for (n, r) in numerators.iter().zip(&got) {
                let want = BigRational::new(n.clone(), d.clone());
                assert_eq!(r.numer(), want.numer(), "case {case}: {n}/{d}");
                assert_eq!(r.denom(), want.denom(), "case {case}: {n}/{d}");
                assert_eq!(reduced(n, &d), want, "case {case}");
            }
        }
    }

    /// A large prime of `d` dividing exactly one numerator among many makes `h` that prime;
    /// only that numerator's value loses it.
    #[test]
    fn a_large_prime_in_one_numerator_among_many_is_found() {
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        let p = (BigInt::one() << 89) - 1;
        let d = &p * to_big(&random_ubig(&mut rng, 3000)) * 12;
        for planted_at in [0, 17, 99] {
            let numerators: Vec<BigInt> = (0..100)
                .map(|i| {
                    let n = to_big(&random_ubig(&mut rng, 3100));
                    if i == planted_at {
                        n * &p
                    } else {
                        n
                    }
                })
                .collect();
            let refs: Vec<&BigInt> = numerators.iter().collect();
            for (i, (n, r)) in numerators.iter().zip(reduced_all(&refs, &d)).enumerate() {
                let want = BigRational::new(n.clone(), d.clone());
                assert_eq!(r, want, "numerator {i}");
                assert_eq!(
                    r.denom().is_multiple_of(&p),
                    i != planted_at,
                    "numerator {i}"
                );
            }
        }
    }

    /// `gcd(n, S)` prime by prime against `num-integer`'s gcd with `S`, for numerators with
    /// each prime power below, at and above its exponent in `S`.
    #[test]
    fn the_smooth_gcd_is_the_gcd_with_the_smooth_part() {
        let mut rng = ChaCha8Rng::seed_from_u64(3);
        let s = BigInt::from(2).pow(40) * BigInt::from(3).pow(25) * 65_521 * 7;
        let d = &s * ((BigInt::one() << 61) - 1);
        let (powers, rest) = smooth_factors(&magnitude(&d));
        assert_eq!(to_big(&rest), (BigInt::one() << 61) - 1);
        for (twos, threes, others) in [
            (0u32, 0u32, 1i64),
            (39, 24, 65_521),
            (40, 25, 7),
            (41, 26, 7 * 65_521 * 65_521),
            (100, 3, 5),
        ] {
            let n = to_big(&random_ubig(&mut rng, 500))
                * BigInt::from(2).pow(twos)
                * BigInt::from(3).pow(threes)
                * others;
            assert_eq!(
                to_big(&smooth_gcd(&magnitude(&n), &powers)),
                n.gcd(&s),
                "2^{twos} 3^{threes} {others}"
            );
        }
        assert_eq!(smooth_gcd(&UBig::ZERO, &powers), UBig::ONE);
    }

    /// Eleven odd primes (three groups of the word-sized products, the last one short), each
    /// dividing the numerators to a random power below, at or above its exponent in `S`.
    #[test]
    fn the_smooth_gcd_reads_every_group_of_odd_primes() {
        let mut rng = ChaCha8Rng::seed_from_u64(12);
        let primes = [3u64, 5, 7, 11, 13, 17, 19, 23, 65_497, 65_519, 65_521];
        let s = primes
            .iter()
            .zip(1u32..)
            .fold(BigInt::from(8), |acc, (&p, e)| acc * BigInt::from(p).pow(e));
        let d = &s * ((BigInt::one() << 127) - 1);
        let (powers, _) = smooth_factors(&magnitude(&d));
        assert_eq!(powers.len(), 12);
        for _ in 0..60 {
            let n = primes
                .iter()
                .fold(to_big(&random_ubig(&mut rng, 300)), |acc, &p| {
                    acc * BigInt::from(p).pow(rng.next_u32() % 14)
                });
            assert_eq!(
                to_big(&smooth_gcd(&magnitude(&n), &powers)),
                n.gcd(&s),
                "{n}"
            );
        }
    }

    /// The product tree modulo `m` against the product of all values taken whole, then one
    /// remainder (`num-bigint`), for counts around the tree's sequential cut and values narrower
    /// than, as wide as and far wider than `m`.
    #[test]
    fn the_product_tree_modulo_m_is_the_remainder_of_the_whole_product() {
        let mut rng = ChaCha8Rng::seed_from_u64(11);
        for (count, m_bits, widths) in [
            (1, 100, 50..60),
            (2, 64, 60..70),
            (8, 700, 650..760),
            (9, 700, 700..701),
            (17, 1000, 900..1100),
            (40, 300, 100..3000),
            // Around the reductions' bounds, k + 64 and 2k + 128 bits.
            (12, 300, 362..367),
            (12, 300, 726..731),
            // Factors of transformed products (more than a hundred words).
            (9, 9000, 7000..20000),
        ] {
            let m = random_ubig(&mut rng, m_bits) | UBig::ONE;
            let values: Vec<UBig> = (0..count)
                .map(|_| {
                    let bits = between(&mut rng, widths.start, widths.end);
                    random_ubig(&mut rng, bits)
                })
                .collect();
            let refs: Vec<&UBig> = values.iter().collect();
            let whole: BigInt = values.iter().map(to_big).product();
            assert_eq!(
                to_big(&product_modulo(&refs, &m)),
                whole % to_big(&m),
                "{count} values"
            );
        }
    }
}
