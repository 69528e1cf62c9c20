//! Derandomized Q-learning (`ρ = 1`) on tiny problems, for claim C1: the kernel's
//! `truecost_kernel::claims::qlearning` (bignum-free; its update is what the Kani harnesses of
//! C1 verify), re-exported under this path.

pub use truecost_kernel::claims::qlearning::*;
