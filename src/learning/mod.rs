//! Learning (docs/spec.md §2): Q-learning, its exploration plans, and the base-4 digits of π that the
//! universal plan reads.

pub mod pi;
pub mod plan;
pub mod q_learning;
pub mod stochastic_q;
