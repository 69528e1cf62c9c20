//! Kani harnesses for truecost (see `../shared/KANI.md` and the README section "Running the
//! proofs with Kani").
//!
//! This member is deliberately small until the claims issue lands: it will hold one harness
//! source per claim and solver lemma, run symbolically by `cargo kani -p truecost-proofs` and,
//! through a stand-in crate named `kani`, by explicit-state enumeration under `cargo test`.
//! Until then it only re-exports the library it will check, so that the workspace layout, the
//! `cfg(kani)` lint declaration and the build are in place.

pub use truecost;
