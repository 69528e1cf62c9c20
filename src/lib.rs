//! # truecost
//!
//! An exact re-implementation of the planning problems, cost models and solvers of
//! *Relating Reinforcement Learning to Dynamic Programming-Based Planning* (Georgiev, Timperi,
//! Sakçak, LaValle), with a reference mode that reproduces the paper's published counts.
//!
//! Architecture (each layer imports only the ones before it):
//! [`value`] → [`model`] → [`problems`] → [`solvers`] → [`learning`] → [`planning`] → [`experiments`] → `cli`
//! (the binary).
#![warn(missing_docs)]

pub mod claims;
pub mod echo;
pub mod envs;
pub mod experiments;
pub mod figures;
pub mod learning;
pub mod model;
pub mod objectives;
pub mod planning;
pub mod problems;
pub mod solvers;
pub mod stochastic;
pub mod value;
