//! Small exact rationals (`i128` numerator and denominator) for the enumeration engines: the
//! kernel's `truecost_kernel::claims::exact` (bignum-free, verified by the Kani harness
//! `rational_add_and_mul_are_exact`), re-exported under this path.
//! `Q::to_rational` gives the exact [`crate::value::Rational`]:
//!
//! ```
//! use truecost::claims::exact::Q;
//! use truecost::value::{parse_rational, Rational};
//! let r: Rational = Q::new(-6, 4).to_rational();
//! assert_eq!(r, parse_rational("-3/2").unwrap());
//! ```

pub use truecost_kernel::claims::exact::*;
