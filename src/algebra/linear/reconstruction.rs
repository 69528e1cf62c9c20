//! Rational reconstruction (step 4 of [`super`]'s module docs): the half-way extended Euclid
//! of `(m, t)`, stopped at the first remainder `≤ bound`, accelerated by Lehmer's method.
//!
//! While the remainders are long, the quotients of Euclid's algorithm are read off their
//! leading 63 bits (Knuth, TAOCP vol. 2, §4.5.2, Algorithm L): a run of quotients that both
//! bounds of the leading bits agree on is exactly the run the full numbers give, and its
//! product, a 2×2 matrix of words, is applied to the remainders and the cofactors at once — one
//! pass over the long numbers for a few dozen quotients instead of one long division each.
//! The run's remainders decrease, so if its last one is above the bound, none before it stopped
//! the search; a run that would end at or below the bound is discarded, and the search ends
//! with one long division per quotient, as without the acceleration.

use dashu_base::{BitTest, DivRem, Gcd, UnsignedAbs};
use dashu_int::{IBig, UBig};

/// Remainders shorter than this take one long division per quotient.
const LEHMER_FROM_BITS: usize = 192;

/// Rational reconstruction: `a/b ≡ t (mod m)` with `|a| ≤ bound`, `0 < b ≤ bound`, if any
/// (`0 ≤ t < m`; half-way extended Euclid).
pub(super) fn reconstruct(t: &UBig, m: &UBig, bound: &UBig) -> Option<(IBig, UBig)> {
    let mut e = Euclid::new(t, m);
    let mut lehmer = true;
    while &e.r1 > bound {
        if lehmer && e.r0.bit_len() >= LEHMER_FROM_BITS {
            if let Some([a, b, c, d]) = quotient_run(&e.r0, &e.r1) {
                let (u, v) = (IBig::from(e.r0.clone()), IBig::from(e.r1.clone()));
                let next = UBig::try_from(combine(c, &u, d, &v)).expect("a remainder");
                if &next > bound {
                    e.r0 = UBig::try_from(combine(a, &u, b, &v)).expect("a remainder");
                    e.r1 = next;
                    (e.s0, e.s1) = (combine(a, &e.s0, b, &e.s1), combine(c, &e.s0, d, &e.s1));
                    continue;
                }
                // The run passes the bound: finish one quotient at a time.
                lehmer = false;
            }
        }
        e.divide();
    }
    e.fraction(bound)
}

/// The extended Euclid of `(m, t)`: consecutive remainders `r0 > r1` and their cofactors
/// `s0, s1` of `t` (`r ≡ s·t mod m`).
struct Euclid {
    r0: UBig,
    r1: UBig,
    s0: IBig,
    s1: IBig,
}

impl Euclid {
    fn new(t: &UBig, m: &UBig) -> Self {
        Euclid {
            r0: m.clone(),
            r1: t.clone(),
            s0: IBig::ZERO,
            s1: IBig::ONE,
        }
    }

    /// One quotient by a long division.
    fn divide(&mut self) {
        let (q, r) = (&self.r0).div_rem(&self.r1);
        self.r0 = std::mem::replace(&mut self.r1, r);
        let s = &self.s0 - IBig::from(q) * &self.s1;
        self.s0 = std::mem::replace(&mut self.s1, s);
    }

    /// The fraction `r1/s1` where the search stopped, if it is one (`s1 ≠ 0`, `|s1| ≤ bound`,
    /// in lowest terms), with a positive denominator.
    fn fraction(self, bound: &UBig) -> Option<(IBig, UBig)> {
        if self.s1 == IBig::ZERO {
            return None;
        }
        let (sign, b) = self.s1.into_parts();
        let a = IBig::from_parts(sign, self.r1);
        (&b <= bound && (&a).unsigned_abs().gcd(&b) == UBig::ONE).then_some((a, b))
    }
}

/// `a·x + b·y`.
fn combine(a: i128, x: &IBig, b: i128, y: &IBig) -> IBig {
    IBig::from(a) * x + IBig::from(b) * y
}

/// The matrix `[[A, B], [C, D]]` of the longest run of Euclid's quotients of `(u, v)`
/// (`u > v`) that the leading 63 bits of `u` and the same bits of `v` determine, such that the
/// remainders after the run are `(A·u + B·v, C·u + D·v)` (Algorithm L); `None` when not even
/// one quotient is determined.
fn quotient_run(u: &UBig, v: &UBig) -> Option<[i128; 4]> {
    let shift = u.bit_len() - 63;
    let high = |w: &UBig| -> i128 {
        let top: UBig = w >> shift;
        u64::try_from(top).expect("63 bits") as i128
    };
    let (mut x, mut y) = (high(u), high(v));
    let (mut a, mut b, mut c, mut d) = (1i128, 0i128, 0i128, 1i128);
    while y + c != 0 && y + d != 0 {
        let q = (x + a).div_euclid(y + c);
        if q != (x + b).div_euclid(y + d) {
            break;
        }
        (a, c) = (c, a - q * c);
        (b, d) = (d, b - q * d);
        (x, y) = (y, x - q * y);
    }
    (b != 0).then_some([a, b, c, d])
}

#[cfg(test)]
mod tests {
    use super::*;
    use dashu_base::RemEuclid;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// The half-way extended Euclid with one long division per quotient (the definition).
    fn by_division(t: &UBig, m: &UBig, bound: &UBig) -> Option<(IBig, UBig)> {
        let mut e = Euclid::new(t, m);
        while &e.r1 > bound {
            e.divide();
        }
        e.fraction(bound)
    }

    fn random_bits(rng: &mut ChaCha8Rng, bits: usize) -> UBig {
        let mut x = UBig::ZERO;
        for _ in 0..bits.div_ceil(64) {
            x = (x << 64usize) + UBig::from(rng.next_u64());
        }
        x >> (64 * bits.div_ceil(64) - bits)
    }

    /// Lehmer's runs give the same answer as one division per quotient: on random residues
    /// (mostly none), on fractions `a/b` with `|a|, b` near the bound (found exactly), and with
    /// bounds at every size, including runs that end next to the bound.
    #[test]
    fn lehmer_runs_agree_with_one_division_per_quotient() {
        let mut rng = ChaCha8Rng::seed_from_u64(31);
        let mut found = 0;
        for bits in [100usize, 200, 300, 700, 2000, 6000] {
            for _ in 0..12 {
                let m = random_bits(&mut rng, bits) | (UBig::ONE << (bits - 1)) | UBig::ONE;
                let half = &m >> 1usize;
                let bound = dashu_base::SquareRoot::sqrt(&half);
                let t = random_bits(&mut rng, bits) % &m;
                assert_eq!(reconstruct(&t, &m, &bound), by_division(&t, &m, &bound));
                // a/b mod m with |a|, b ≤ bound, b coprime to m.
                let b = (random_bits(&mut rng, bits / 2 - 2) | UBig::ONE) % &bound + UBig::ONE;
                let a = random_bits(&mut rng, bits / 2 - 2) % &bound;
                let (g, inverse, _) = dashu_base::ExtendedGcd::gcd_ext(&b, &m);
                if g != UBig::ONE {
                    continue;
                }
                let inverse = inverse.rem_euclid(IBig::from(m.clone()));
                for sign in [1i8, -1] {
                    let signed = IBig::from(a.clone()) * IBig::from(sign);
                    let t = (signed.clone() * IBig::from(inverse.clone()))
                        .rem_euclid(IBig::from(m.clone()));
                    let want = by_division(&t, &m, &bound);
                    assert_eq!(reconstruct(&t, &m, &bound), want);
                    if let Some((x, y)) = want {
                        // The reduced fraction of a/b.
                        assert_eq!(x * IBig::from(b.clone()), signed * IBig::from(y));
                        found += 1;
                    }
                }
                // Smaller bounds: the search ends early, at every length of the remainders.
                for k in [3usize, 4, 5] {
                    let small = &bound >> (bits / k);
                    assert_eq!(reconstruct(&t, &m, &small), by_division(&t, &m, &small));
                }
            }
        }
        assert!(found > 100, "{found} fractions reconstructed");
    }

    /// A run's matrix maps `(u, v)` to the remainders after its quotients, checked against
    /// that many long divisions.
    #[test]
    fn a_quotient_run_is_that_many_divisions() {
        let mut rng = ChaCha8Rng::seed_from_u64(32);
        for bits in [200usize, 1000, 5000] {
            for _ in 0..20 {
                let u = random_bits(&mut rng, bits) | (UBig::ONE << (bits - 1));
                let shorter = bits - rng.next_u32() as usize % 40;
                let v = random_bits(&mut rng, shorter) % &u;
                let Some([a, b, c, d]) = quotient_run(&u, &v) else {
                    continue;
                };
                let (x, y) = (IBig::from(u.clone()), IBig::from(v.clone()));
                let (new_u, new_v) = (combine(a, &x, b, &y), combine(c, &x, d, &y));
                let (mut r0, mut r1) = (u.clone(), v.clone());
                let mut steps = 0;
                while IBig::from(r0.clone()) != new_u {
                    let r = &r0 % &r1;
                    r0 = std::mem::replace(&mut r1, r);
                    steps += 1;
                    assert!(steps < 200, "no remainder matches the run");
                }
                assert_eq!(IBig::from(r1), new_v);
            }
        }
    }
}
