//! The bignum-free kernels of the claims engine (docs/spec.md §6): the small exact rationals
//! ([`exact`]), the tiny problems and their symmetry-reduced families ([`tiny`]), the
//! policy-enumeration oracles ([`oracle`]), derandomized Q-learning ([`qlearning`]) and the
//! per-problem checks of C2, C3 and C4. The claim runners (scopes, rayon, reports) and
//! everything that converts to or from big rationals are in `truecost::claims`, which
//! re-exports all of this under the same paths.

// Index loops over tiny fixed arrays read better than iterator chains in these oracles.
#![allow(clippy::needless_range_loop)]

pub mod c2;
pub mod c3;
pub mod c4;
pub mod exact;
pub mod oracle;
pub mod qlearning;
pub mod tiny;
