//! Prime factorisations of the Chudnovsky series' `P` and `Q`, used to remove their common
//! factors during binary splitting (the "sieve" method of gmp-chudnovsky).
//!
//! The term ratio is `p(a)/q(a)` with `p(a) = (6a−5)(2a−1)(6a−1)` and
//! `q(a) = a³·640320³/24`. Both are products of integers at most `6a`, so a table of smallest
//! prime factors up to `6·terms` factors every leaf, and products and common divisors of
//! leaves are merges of sorted factor lists.

use malachite_nz::natural::Natural;

/// Smallest prime factor of every integer in `[2, limit]` (sieve of Eratosthenes).
pub(super) struct Sieve {
    spf: Vec<u32>,
}

impl Sieve {
    /// A table for every integer up to `limit` (at most `u32::MAX`).
    pub(super) fn new(limit: u64) -> Sieve {
        let n = usize::try_from(limit).expect("π sieve: limit fits in memory") + 1;
        assert!(
            limit <= u64::from(u32::MAX),
            "π sieve: limit {limit} above 2^32"
        );
        let mut spf = vec![0u32; n];
        for i in 2..n {
            if spf[i] == 0 {
                // `i` is prime: it is the smallest prime factor of its multiples not yet marked,
                // the first of which is i² (smaller ones have a smaller prime factor).
                for j in (i.saturating_mul(i)..n).step_by(i) {
                    if spf[j] == 0 {
                        spf[j] = i as u32;
                    }
                }
                spf[i] = i as u32;
            }
        }
        Sieve { spf }
    }

    /// `n^times` as a factor list (`n` at least 1 and within the table).
    pub(super) fn factor(&self, mut n: u64, times: u32) -> Factors {
        let mut out = Vec::new();
        while n > 1 {
            let p = self.spf[n as usize];
            let mut e = 0;
            while n.is_multiple_of(u64::from(p)) {
                n /= u64::from(p);
                e += 1;
            }
            out.push((p, e * times));
        }
        // Smallest prime factors come out in increasing order.
        Factors(out)
    }
}

/// A positive integer as its prime factorisation: `(prime, exponent)` pairs, primes strictly
/// increasing, exponents positive. The empty list is 1.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub(super) struct Factors(pub(super) Vec<(u32, u32)>);

impl Factors {
    /// `640320³/24 = 2^15·3^2·5^3·23^3·29^3`, the constant factor of every `q(a)`.
    pub(super) fn q_constant() -> Factors {
        Factors(vec![(2, 15), (3, 2), (5, 3), (23, 3), (29, 3)])
    }

    /// Whether this is 1.
    pub(super) fn is_one(&self) -> bool {
        self.0.is_empty()
    }

    /// The product `self · other`.
    pub(super) fn times(&self, other: &Factors) -> Factors {
        let (a, b) = (&self.0, &other.0);
        let mut out = Vec::with_capacity(a.len() + b.len());
        let (mut i, mut j) = (0, 0);
        while i < a.len() && j < b.len() {
            match a[i].0.cmp(&b[j].0) {
                std::cmp::Ordering::Less => {
                    out.push(a[i]);
                    i += 1;
                }
                std::cmp::Ordering::Greater => {
                    out.push(b[j]);
                    j += 1;
                }
                std::cmp::Ordering::Equal => {
                    out.push((a[i].0, a[i].1 + b[j].1));
                    i += 1;
                    j += 1;
                }
            }
        }
        out.extend_from_slice(&a[i..]);
        out.extend_from_slice(&b[j..]);
        Factors(out)
    }

    /// The greatest common divisor (the smaller exponent of every common prime).
    pub(super) fn gcd(&self, other: &Factors) -> Factors {
        let mut out = Vec::new();
        let mut rest = other.0.iter().peekable();
        for &(p, e) in &self.0 {
            while rest.next_if(|&&(q, _)| q < p).is_some() {}
            if let Some(&(_, f)) = rest.next_if(|&&(q, _)| q == p) {
                out.push((p, e.min(f)));
            }
        }
        Factors(out)
    }

    /// The quotient `self / d`, for a divisor `d` of `self`.
    pub(super) fn over(&self, d: &Factors) -> Factors {
        let mut out = Vec::with_capacity(self.0.len());
        let mut rest = d.0.iter().peekable();
        for &(p, e) in &self.0 {
            let e = match rest.next_if(|&&(q, _)| q == p) {
                Some(&(_, f)) => e.checked_sub(f).expect("π factors: not a divisor"),
                None => e,
            };
            if e > 0 {
                out.push((p, e));
            }
        }
        assert!(rest.next().is_none(), "π factors: not a divisor");
        Factors(out)
    }

    /// The integer itself: primes packed into machine words, then a balanced product tree.
    pub(super) fn value(&self) -> Natural {
        let mut words = Vec::new();
        let mut word = 1u64;
        for &(p, e) in &self.0 {
            for _ in 0..e {
                match word.checked_mul(u64::from(p)) {
                    Some(w) => word = w,
                    None => {
                        words.push(Natural::from(word));
                        word = u64::from(p);
                    }
                }
            }
        }
        words.push(Natural::from(word));
        product(&words)
    }
}

/// The product of `w` (not empty), halves first.
fn product(w: &[Natural]) -> Natural {
    match w {
        [x] => x.clone(),
        _ => {
            let (l, r) = w.split_at(w.len() / 2);
            product(l) * product(r)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use malachite_base::num::arithmetic::traits::{Gcd, Pow};

    /// Trial division, the oracle for the sieve.
    fn trial(mut n: u64) -> Vec<(u32, u32)> {
        let mut out = Vec::new();
        let mut p = 2;
        while n > 1 {
            let mut e = 0;
            while n.is_multiple_of(p) {
                n /= p;
                e += 1;
            }
            if e > 0 {
                out.push((p as u32, e));
            }
            p += 1;
        }
        out
    }

    #[test]
    fn the_sieve_factors_as_trial_division_does() {
        let sieve = Sieve::new(3000);
        assert_eq!(sieve.factor(1, 3), Factors::default());
        for n in 1..=3000 {
            let want: Vec<_> = trial(n).into_iter().map(|(p, e)| (p, 2 * e)).collect();
            assert_eq!(sieve.factor(n, 2).0, want, "n = {n}");
            assert_eq!(sieve.factor(n, 1).value(), Natural::from(n), "n = {n}");
        }
        // The last entry of the table is filled too.
        assert_eq!(Sieve::new(49).factor(49, 1).0, vec![(7, 2)]);
        assert_eq!(Sieve::new(47).factor(47, 1).0, vec![(47, 1)]);
    }

    #[test]
    fn the_constant_is_640320_cubed_over_24() {
        let c = Natural::from(640320u32);
        assert_eq!(
            Factors::q_constant().value(),
            &c * &c * &c / Natural::from(24u32)
        );
        assert_eq!(Factors::q_constant().value(), 10939058860032000u64);
    }

    #[test]
    fn products_quotients_and_gcds_agree_with_the_integers() {
        let sieve = Sieve::new(600);
        for a in 1..=600u64 {
            for b in [1, 2, 7, 12, 30, 64, 97, 210, 360, 512, 599, 600] {
                let (fa, fb) = (sieve.factor(a, 3), sieve.factor(b, 2));
                let (na, nb) = (fa.value(), fb.value());
                assert_eq!(na, Natural::from(a).pow(3));
                let g = fa.gcd(&fb);
                assert_eq!(g.value(), (&na).gcd(&nb), "gcd({a}³, {b}²)");
                assert_eq!(g.is_one(), g.value() == 1u32);
                let prod = fa.times(&fb);
                assert_eq!(prod.value(), &na * &nb, "{a}³·{b}²");
                assert_eq!(prod.over(&fb), fa, "{a}³·{b}² / {b}²");
                assert_eq!(prod.over(&fa), fb, "{a}³·{b}² / {a}³");
                assert_eq!(fa.over(&g).value(), &na / g.value(), "{a}³ / gcd");
            }
        }
    }

    #[test]
    fn a_long_product_spans_many_words() {
        let sieve = Sieve::new(10_000);
        let mut f = Factors::default();
        let mut n = Natural::from(1u32);
        for k in 9_000..10_000u64 {
            f = f.times(&sieve.factor(k, 1));
            n *= Natural::from(k);
        }
        assert_eq!(f.value(), n);
    }

    #[test]
    #[should_panic(expected = "not a divisor")]
    fn dividing_by_a_non_divisor_is_refused() {
        let sieve = Sieve::new(100);
        let _ = sieve.factor(12, 1).over(&sieve.factor(8, 1));
    }

    #[test]
    #[should_panic(expected = "not a divisor")]
    fn dividing_by_a_missing_prime_is_refused() {
        let sieve = Sieve::new(100);
        let _ = sieve.factor(12, 1).over(&sieve.factor(5, 1));
    }
}
