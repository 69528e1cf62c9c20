//! Experiments: configurations as data, runners that wrap the clock around the algorithms, and
//! summaries over seeded samples (docs/spec.md §4).
//!
//! The algorithms never read a clock; only [`clock::Stopwatch`], used by the runners here, does.

pub mod clock;
pub mod deterministic;
pub mod latex;
pub mod published;
pub mod runs;
pub mod stats;
pub mod stochastic;
pub mod tables;
pub mod visits;
