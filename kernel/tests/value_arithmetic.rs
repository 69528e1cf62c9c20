//! Pins the value types' arithmetic core (`kernel/src/value.rs`): `Units::plus` panics on an
//! overflow instead of returning `+∞`, `is_finite` of `Units` and `f64` on finite and infinite
//! values, and the default `order_key` of a value type that does not define one (`None`, which
//! sends Dijkstra to its compared frontier).
//!
//! Why: the mutation run of 1 Dec 2026 (`--re '^kernel/src/[^/]+\.rs'`) left `Units::plus`'s
//! overflow guard, both `is_finite`s and the default `order_key` untested by the kernel's own
//! tests. Expected values are the definitions (`u64::MAX` is `+∞`).

mod support;
use support::NoKey;
use truecost_kernel::value::{CostValue, Units};

#[test]
fn units_are_finite_below_the_maximum() {
    for v in [0, 1, 41, u64::MAX - 1] {
        assert!(Units(v).is_finite(), "{v}");
    }
    assert!(!Units(u64::MAX).is_finite());
    assert!(!Units::infinity().is_finite());
    assert!(Units::zero().is_finite());
}

#[test]
fn f64_is_finite_except_at_infinity() {
    for v in [0.0, -0.0, 1.5, 1e300, f64::MIN_POSITIVE] {
        assert!(CostValue::is_finite(&v), "{v}");
    }
    assert!(!CostValue::is_finite(&f64::INFINITY));
    assert!(!CostValue::is_finite(&<f64 as CostValue>::infinity()));
    assert_eq!(<f64 as CostValue>::zero(), 0.0);
}

#[test]
fn units_plus_is_exact_and_infinity_absorbs() {
    assert_eq!(Units(2).plus(&Units(3)), Units(5));
    assert_eq!(Units(u64::MAX - 2).plus(&Units(1)), Units(u64::MAX - 1));
    assert_eq!(Units(7).plus(&Units::infinity()), Units::infinity());
    assert_eq!(Units::infinity().plus(&Units(7)), Units::infinity());
    assert_eq!(Units(0).plus(&Units(0)), Units(0));
}

#[test]
#[should_panic(expected = "exact cost overflow")]
fn a_units_sum_reaching_the_infinity_code_panics() {
    // u64::MAX - 1 + 1 = u64::MAX would read as +∞: it must not be returned.
    let _ = Units(u64::MAX - 1).plus(&Units(1));
}

#[test]
#[should_panic(expected = "exact cost overflow")]
fn a_wrapping_units_sum_panics() {
    let _ = Units(u64::MAX - 1).plus(&Units(5));
}

#[test]
fn a_value_type_without_keys_has_none() {
    // support::NoKey keeps the trait's default `order_key`.
    assert_eq!(NoKey(0).order_key(), None);
    assert_eq!(NoKey(5).order_key(), None);
    assert_eq!(NoKey::infinity().order_key(), None);
    assert_eq!(Units(5).order_key(), Some(5));
}
