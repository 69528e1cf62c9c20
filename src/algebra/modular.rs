//! Arithmetic modulo word-size primes (`p < 2⁶⁴`, products in `u128`): products, powers,
//! inverses and a deterministic primality test, for the modular methods of
//! [`super::annihilator`] and the transforms' primes of [`super::ntt`].

/// `a·b mod p`.
pub(crate) fn mul_mod(a: u64, b: u64, p: u64) -> u64 {
    (u128::from(a) * u128::from(b) % u128::from(p)) as u64
}

/// `bᵉ mod p`.
pub(crate) fn pow_mod(mut b: u64, mut e: u64, p: u64) -> u64 {
    let mut r = 1 % p;
    b %= p;
    while e > 0 {
        if e & 1 == 1 {
            r = mul_mod(r, b, p);
        }
        b = mul_mod(b, b, p);
        e >>= 1;
    }
    r
}

/// The inverse of `a` modulo the prime `p` (`a` not a multiple of `p`; Fermat).
pub(crate) fn inv_mod(a: u64, p: u64) -> u64 {
    pow_mod(a, p - 2, p)
}

/// Whether `n` is prime: Miller–Rabin with the first twelve prime bases, deterministic below
/// `3.3·10²⁴`, so for every `u64`.
pub(crate) fn is_prime(n: u64) -> bool {
    const BASES: [u64; 12] = [2, 3, 5, 7, 11, 13, 17, 19, 23, 29, 31, 37];
    if n < 2 {
        return false;
    }
    for &q in &BASES {
        if n.is_multiple_of(q) {
            return n == q;
        }
    }
    let (mut d, mut s) = (n - 1, 0);
    while d.is_multiple_of(2) {
        d /= 2;
        s += 1;
    }
    BASES.iter().all(|&a| {
        let mut x = pow_mod(a, d, n);
        if x == 1 || x == n - 1 {
            return true;
        }
        for _ in 1..s {
            x = mul_mod(x, x, n);
            if x == n - 1 {
                return true;
            }
        }
        false
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn primality_of_small_numbers_and_of_a_strong_pseudoprime() {
        let small: Vec<u64> = (0..60).filter(|&n| is_prime(n)).collect();
        assert_eq!(
            small,
            [2, 3, 5, 7, 11, 13, 17, 19, 23, 29, 31, 37, 41, 43, 47, 53, 59]
        );
        // A strong pseudoprime to the bases 2, 3, 5, 7 (3215031751 = 151·751·28351).
        assert!(!is_prime(3_215_031_751));
    }

    /// Powers against repeated products (exponents 0 to 40), and Fermat's little theorem for
    /// large exponents, with bases above the modulus and at the ends of the words; the
    /// modulus 1, where every power is 0.
    #[test]
    fn powers_agree_with_repeated_products_and_inverses_invert() {
        let moduli = [
            1u64,
            2,
            7,
            65_537,
            (1 << 61) - 1,
            18_446_744_073_709_551_557,
        ];
        for p in moduli {
            for b in [0, 1, 2, 3, p - 1, p, p.wrapping_add(5), u64::MAX] {
                let mut expected = 1 % p;
                for e in 0..=40 {
                    assert_eq!(pow_mod(b, e, p), expected, "{b}^{e} mod {p}");
                    expected = mul_mod(expected, b % p, p);
                }
                if is_prime(p) && b % p != 0 {
                    assert_eq!(pow_mod(b, p - 1, p), 1, "{b}^(p-1) mod {p}");
                    assert_eq!(mul_mod(inv_mod(b % p, p), b, p), 1, "{b}⁻¹ mod {p}");
                }
            }
        }
        assert_eq!(mul_mod(u64::MAX, u64::MAX, 1 << 63), 1);
    }
}
