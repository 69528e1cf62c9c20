//! Learning (SPEC §2): Q-learning and its exploration plans.

pub mod pi;
