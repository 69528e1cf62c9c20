//! # truecost-kernel
//!
//! The bignum-free computational kernel of `truecost` (the exact re-implementation of
//! *Relating Reinforcement Learning to Dynamic Programming-Based Planning*, Georgiev, Timperi,
//! Sakçak, LaValle): exactly the code that the Kani harnesses in `proofs/` verify, in a crate
//! with **no dependencies under Kani**, so that `cargo kani -p truecost-proofs` compiles
//! neither big integers nor clap, rayon, plotters, indicatif or z3. Without Kani it depends on
//! the Kani stand-in only, for the contract attributes of `claims::exact::{lowest_terms, gcd,
//! Q::checked_add, Q::checked_mul}`, `value::Units::checked_plus` and
//! `claims::qlearning::QProblem::update` (checked inside stand-in harness runs, inert outside).
//!
//! * [`value`] — the [`value::CostValue`] trait's arithmetic core and [`value::Units`];
//! * [`model`] — the planning graph (its unit left to the caller) and policy decisions;
//! * [`solvers`] — Dijkstra, value iteration, policy evaluation, model-free exploration;
//! * [`claims`] — `i128` rationals, tiny problems, the policy-enumeration oracles, derandomized
//!   Q-learning, and the C2/C3/C4 checks.
//!
//! `truecost` depends on this crate and re-exports every item under its old path
//! (`truecost::solvers::dijkstra`, `truecost::claims::exact::Q`, …); what needs big rationals
//! (exact rendering, the unit of a graph, problem files, the claim runners) stays there.
#![warn(missing_docs)]

pub mod claims;
pub mod model;
pub mod solvers;
pub mod value;

/// Whether this build of the kernel checks integer overflow (`-C overflow-checks`): an
/// overflow in the kernel then panics instead of wrapping. `truecost verify` reports it.
///
/// ```
/// // Tests build with overflow checks (the test profile's default).
/// assert!(truecost_kernel::overflow_checks());
/// ```
#[cfg(not(kani))]
pub fn overflow_checks() -> bool {
    std::panic::catch_unwind(|| {
        let _ = std::hint::black_box(std::hint::black_box(u8::MAX) + std::hint::black_box(1u8));
    })
    .is_err()
}
