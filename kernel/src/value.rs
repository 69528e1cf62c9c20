//! The arithmetic core of the cost-to-go value types (docs/spec.md §1, §2): the [`CostValue`] trait the
//! planners are generic over, its fast exact implementation [`Units`], and `f64` for the
//! reference mode of docs/spec.md §7.
//!
//! A cost-to-go `G(x)` is a non-negative rational or `+∞` (no goal reachable). What needs big
//! rationals — the exact extended rationals themselves (`truecost::value::Extended`), the value
//! of one unit, rendering a value as exact text — lives in `truecost::value`
//! (`truecost::value::ExactValue`), so this crate, which the Kani harnesses verify, has no
//! dependencies.

use std::cmp::Ordering;
use std::fmt;

/// The value type a planner computes with (docs/spec.md §2).
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
    /// An order-preserving image in `u64`, if the type has one: for all `a`, `b` with keys,
    /// `a.order_key().cmp(&b.order_key()) == a.compare(b)`. Planners may then order by the
    /// key (a machine integer) instead of calling [`CostValue::compare`]; a type returns
    /// either `Some` for every value or `None` for every value. The default is `None`.
    ///
    /// ```
    /// use truecost_kernel::value::{CostValue, Units};
    /// assert!(Units(2).order_key() < Units(3).order_key());
    /// assert!(0.5f64.order_key() < f64::INFINITY.order_key());
    /// ```
    #[inline]
    fn order_key(&self) -> Option<u64> {
        None
    }
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

impl Units {
    /// Extended addition that reports overflow: `+∞` absorbs (`Some(+∞)`); the sum of two
    /// finite counts is `Some` exactly when it is below `u64::MAX` (which would read as `+∞`),
    /// and `None` otherwise. [`CostValue::plus`] is this, panicking on `None`.
    ///
    /// ```
    /// use truecost_kernel::value::{CostValue, Units};
    /// assert_eq!(Units(2).checked_plus(&Units(3)), Some(Units(5)));
    /// assert_eq!(Units(u64::MAX - 1).checked_plus(&Units(1)), None);
    /// assert_eq!(Units(7).checked_plus(&Units::infinity()), Some(Units::infinity()));
    /// ```
    ///
    /// Contract (proved by `proofs::contracts::units_checked_plus_is_exact`): stated on the
    /// sum taken in `u128`, where it cannot wrap.
    #[kani::ensures(|r: &Option<Units>| units_plus_spec(self.0, other.0, *r))]
    #[inline]
    pub fn checked_plus(&self, other: &Units) -> Option<Units> {
        if self.0 == u64::MAX || other.0 == u64::MAX {
            return Some(Units(u64::MAX));
        }
        match self.0.checked_add(other.0) {
            Some(s) if s != u64::MAX => Some(Units(s)),
            _ => None,
        }
    }
}

/// The guarantee of [`Units::checked_plus`] on counts `a`, `b` (`u64::MAX` is `+∞`): `+∞` if
/// either is `+∞`; otherwise the exact sum when it is below `u64::MAX`, and `None` exactly when
/// it is not (computed in `u128`).
pub fn units_plus_spec(a: u64, b: u64, r: Option<Units>) -> bool {
    let exact = a as u128 + b as u128;
    match r {
        _ if a == u64::MAX || b == u64::MAX => r == Some(Units(u64::MAX)),
        Some(s) => s.0 as u128 == exact && exact < u64::MAX as u128,
        None => exact >= u64::MAX as u128,
    }
}

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
        // The graph constructor proves `states × max cost < u64::MAX`; planners never add more
        // than `states` stage costs, so this cannot fail. If it ever did, failing loudly is the
        // only acceptable outcome: a wrapped or saturated sum would be a silently wrong number.
        match self.checked_plus(other) {
            Some(s) => s,
            None => panic!("exact cost overflow: the Units bound was violated (a truecost bug)"),
        }
    }
    #[inline]
    fn compare(&self, other: &Self) -> Ordering {
        self.0.cmp(&other.0)
    }
    /// The count itself (`+∞` is `u64::MAX`, above every finite count).
    #[inline]
    fn order_key(&self) -> Option<u64> {
        Some(self.0)
    }
}

/// `f64` is the value type of the reference mode only (docs/spec.md §7). It is not exact.
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
    /// The bits of `total_cmp`'s order, as an unsigned integer: negative values have all
    /// bits but the sign flipped, non-negative ones the sign bit set, so that unsigned
    /// comparison of the keys is `f64::total_cmp`.
    #[inline]
    fn order_key(&self) -> Option<u64> {
        let bits = self.to_bits();
        Some(if bits >> 63 == 1 {
            !bits
        } else {
            bits | 1 << 63
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn order_keys_preserve_the_planners_order() {
        let floats = [
            f64::NEG_INFINITY,
            -1e300,
            -1.5,
            -f64::MIN_POSITIVE,
            -0.0,
            0.0,
            f64::MIN_POSITIVE / 2.0,
            f64::MIN_POSITIVE,
            0.1 + 0.2,
            0.3,
            42.105_263_157_894_73,
            42.105_263_157_894_74,
            1e300,
            f64::INFINITY,
        ];
        for a in floats {
            for b in floats {
                assert_eq!(
                    a.order_key().cmp(&b.order_key()),
                    a.compare(&b),
                    "{a} vs {b}"
                );
            }
        }
        let units = [
            Units(0),
            Units(1),
            Units(41),
            Units(u64::MAX - 1),
            Units::infinity(),
        ];
        for a in units {
            for b in units {
                assert_eq!(a.order_key().cmp(&b.order_key()), a.compare(&b));
            }
        }
    }
}
