//! The brute-force policy-enumeration oracles of the claims engine: the kernel's
//! `truecost_kernel::claims::oracle` (bignum-free, run by the Kani harnesses on symbolic
//! structures), re-exported under this path.

pub use truecost_kernel::claims::oracle::*;
