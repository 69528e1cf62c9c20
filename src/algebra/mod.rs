//! Exact algebra, general and free of the planning model: it depends on the value types
//! ([`crate::value`]) and the big-number crates only, and is the part another project could
//! reuse.
//!
//! * [`poly`] — univariate polynomials with rational coefficients, Sturm sequences, real-root
//!   isolation and real algebraic numbers; [`poly::roots`] — Descartes/Vincent–Collins–Akritas
//!   root isolation in `(0, 1)`, exact comparison of roots and minimal polynomials.
//! * [`intervals`] — subsets of `(0, 1)` as unions of intervals with algebraic ends, and their
//!   exact text.
//! * [`linear`] — exact rational linear algebra: the sparse solver of policy evaluation (Dixon
//!   p-adic lifting over a band or sparse LU modulo word-size primes, rational reconstruction,
//!   exact verification) and its `f64` twin.
//! * [`ordering`] — fill-reducing orderings (nested dissection) of a symmetric sparsity pattern
//!   and its symbolic factorisation (elimination tree, row subtrees).
//! * [`ntt`] — products of big natural numbers by number-theoretic transforms modulo three
//!   primes and the Chinese remainder theorem.
//! * [`radix`] — the decimal text of many big integers of about the same size.
//! * [`lowest_terms`] — exact reduction of fractions, one at a time or many over a common
//!   denominator.
//! * [`annihilator`] — modular methods: the minimal polynomial of a Krylov sequence of an
//!   integer matrix (Berlekamp–Massey modulo word-size primes, Chinese remaindering).
//!
//! The stochastic solvers, the parametric discount engine ([`crate::objectives`]) and the
//! claims engine ([`crate::claims`]) build on it.

pub mod annihilator;
mod barrett;
pub mod intervals;
pub mod linear;
pub mod lowest_terms;
mod modular;
pub mod ntt;
pub mod ordering;
pub mod poly;
pub mod radix;
mod sparse_lu;

/// A uniform draw from `lo..hi` (tests of the algebra modules).
#[cfg(test)]
pub(crate) fn uniform<T: TryInto<i128> + TryFrom<i128>>(
    rng: &mut rand_chacha::ChaCha8Rng,
    lo: T,
    hi: T,
) -> T {
    use rand::Rng;
    let (lo, hi): (i128, i128) = (
        lo.try_into().ok().expect("in i128"),
        hi.try_into().ok().expect("in i128"),
    );
    let word = (rng.next_u64() as u128) << 64 | rng.next_u64() as u128;
    T::try_from(lo + (word % (hi - lo) as u128) as i128)
        .ok()
        .expect("within the range")
}
