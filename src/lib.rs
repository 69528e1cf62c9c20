//! # truecost
//!
//! An exact re-implementation of the planning problems, cost models and solvers of
//! *Relating Reinforcement Learning to Dynamic Programming-Based Planning* (Georgiev, Timperi,
//! Sakçak, LaValle), with a reference mode that reproduces the paper's published counts.
//!
//! Architecture (each layer imports only the layers before it; `tests/architecture.rs` checks
//! this from the source): [`echo`] → [`atomic`], [`bounded`] → [`value`] → [`algebra`] (exact
//! polynomials, real algebraic numbers, exact linear algebra) → [`model`] and
//! [`certificate`] (the checker of certificates: plain model data and big rationals only) →
//! [`problems`], [`solvers`] → [`planning`], [`stochastic`] → [`learning`], [`formats`] (Storm's and PRISM's formats) → [`claims`] →
//! [`envs`] → [`objectives`], [`experiments`] → [`figures`] → `cli` (the binary). Beneath them
//! all, the `kernel/` crate `truecost_kernel` (no dependencies under Kani): the value types' arithmetic
//! core ([`value::CostValue`], [`value::Units`]), the planning graph, the planners
//! ([`solvers`]) and the claims' bignum-free oracles (`claims::{exact, tiny, oracle,
//! qlearning}`, the C2/C3/C4 checks) — exactly what the Kani harnesses in `proofs/` verify.
//! This crate re-exports every kernel item under its old path and adds what needs big
//! rationals ([`value::ExactValue`], the unit of [`model::Graph`]).
#![warn(missing_docs)]

pub mod algebra;
pub mod atomic;
pub mod bounded;
pub mod certificate;
pub mod claims;
pub mod echo;
pub mod envs;
pub mod experiments;
pub mod figures;
pub mod formats;
pub mod learning;
pub mod model;
pub mod objectives;
pub mod planning;
pub mod problems;
pub mod solvers;
pub mod stochastic;
pub mod value;
