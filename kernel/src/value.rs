//! The arithmetic core of the cost-to-go value types (SPEC §1, §2): the [`CostValue`] trait the
//! planners are generic over, its fast exact implementation [`Units`], and `f64` for the
//! reference mode of SPEC §7.
//!
//! A cost-to-go `G(x)` is a non-negative rational or `+∞` (no goal reachable). What needs big
//! rationals — the exact extended rationals themselves (`truecost::value::Extended`), the value
//! of one unit, rendering a value as exact text — lives in `truecost::value`
//! (`truecost::value::ExactValue`), so this crate, which the Kani harnesses verify, has no
//! dependencies (issue 10, item 3).

use std::cmp::Ordering;
use std::fmt;

/// The value type a planner computes with (SPEC §2: "generic over the value type").
///
/// `plus` is the extended addition of the cost model (`+∞` absorbs); implementations must be
/// exact or, for `f64`, say that they are not.
pub trait CostValue: Clone + PartialEq + PartialOrd + fmt::Debug + Send + Sync + 'static {
    /// Whether values of this type are exact (false only for `f64`).
    const EXACT: bool;
    /// The additive identity (the value of a goal).
    fn zero() -> Self;
    /// `+∞`: no goal is reachable.
    fn infinity() -> Self;
    /// Whether the value is finite.
    fn is_finite(&self) -> bool;
    /// Extended addition: `a + ∞ = ∞`, otherwise the exact (or, for `f64`, rounded) sum.
    fn plus(&self, other: &Self) -> Self;
    /// The total order used by planners (`f64` values here are never NaN).
    fn compare(&self, other: &Self) -> Ordering;
}

/// A count of the problem's cost unit `1/D`; `u64::MAX` stands for `+∞`.
///
/// Every deterministic cost-to-go is a sum of stage costs, so when all stage costs are
/// multiples of `1/D` every value is too. `truecost::model::ExactGraph::new` chooses this type
/// only when `(states + 1) × max stage cost` is below `u64::MAX`, which bounds every value a
/// planner can form, so an addition never wraps; were that bound ever violated, [`Units::plus`]
/// panics rather than return a wrapped or saturated number (Kani harnesses
/// `units_plus_is_exact_when_it_fits`, `units_plus_reports_every_overflow`).
///
/// ```
/// use truecost_kernel::value::{CostValue, Units};
/// assert_eq!(Units(2).plus(&Units(3)), Units(5));
/// assert!(!Units(2).plus(&Units::infinity()).is_finite());
/// ```
#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Debug)]
pub struct Units(pub u64);

impl CostValue for Units {
    const EXACT: bool = true;
    #[inline]
    fn zero() -> Self {
        Units(0)
    }
    #[inline]
    fn infinity() -> Self {
        Units(u64::MAX)
    }
    #[inline]
    fn is_finite(&self) -> bool {
        self.0 != u64::MAX
    }
    #[inline]
    fn plus(&self, other: &Self) -> Self {
        if self.0 == u64::MAX || other.0 == u64::MAX {
            return Units(u64::MAX);
        }
        // The graph constructor proves `states × max cost < u64::MAX`; planners never add more
        // than `states` stage costs, so this cannot fail. If it ever did, failing loudly is the
        // only acceptable outcome: a wrapped or saturated sum would be a silently wrong number.
        match self.0.checked_add(other.0) {
            Some(s) if s != u64::MAX => Units(s),
            _ => panic!("exact cost overflow: the Units bound was violated (a truecost bug)"),
        }
    }
    #[inline]
    fn compare(&self, other: &Self) -> Ordering {
        self.0.cmp(&other.0)
    }
}

/// `f64` is the value type of the reference mode only (SPEC §7). It is not exact.
impl CostValue for f64 {
    const EXACT: bool = false;
    #[inline]
    fn zero() -> Self {
        0.0
    }
    #[inline]
    fn infinity() -> Self {
        f64::INFINITY
    }
    #[inline]
    fn is_finite(&self) -> bool {
        f64::is_finite(*self)
    }
    #[inline]
    fn plus(&self, other: &Self) -> Self {
        self + other
    }
    #[inline]
    fn compare(&self, other: &Self) -> Ordering {
        self.total_cmp(other)
    }
}
