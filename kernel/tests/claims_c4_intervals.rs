//! C4's intervals of bonuses (`claims::c4::{Interval, End, witness}`), against the brute-force
//! meaning of an interval: the conjunction of the half-lines that built it, decided on a grid of
//! rationals around every end point (every end point, the midpoints between consecutive ones,
//! points `±1/1000` beside each and points far out: a convex set whose ends are among the points
//! is decided by this grid). Random cases come from `support::SplitMix`; the hand cases pin the
//! text form and the corners a random case rarely reaches (an `empty` flag set over ends that
//! would contain points, a witness found only below every end, above every end, or when no end is
//! negative).
//!
//! Kills the mutants of `Interval::{contains, at_least, at_most, normalise, same_set, ends}`,
//! `Display for Interval` and `witness` (kernel-only mutation cycle, docs/mutants.md).

mod support;

use support::{rational_grid as grid, SplitMix};
use truecost_kernel::claims::c4::{witness, End, Interval};
use truecost_kernel::claims::exact::Q;

/// A half-line constraint on the bonus `M`.
#[derive(Clone, Copy, Debug)]
enum Half {
    Ge(Q),
    Gt(Q),
    Le(Q),
    Lt(Q),
}

fn holds(c: Half, m: Q) -> bool {
    match c {
        Half::Ge(a) => m >= a,
        Half::Gt(a) => m > a,
        Half::Le(b) => m <= b,
        Half::Lt(b) => m < b,
    }
}

fn member(cs: &[Half], m: Q) -> bool {
    cs.iter().all(|&c| holds(c, m))
}

fn point(c: Half) -> Q {
    match c {
        Half::Ge(a) | Half::Gt(a) | Half::Le(a) | Half::Lt(a) => a,
    }
}

fn small_q(draw: &mut SplitMix) -> Q {
    Q::new(draw.below(17) as i128 - 8, 1 + draw.below(4) as i128)
}

/// A random end of a starting interval and its half-line (none when unbounded).
fn random_end(draw: &mut SplitMix, lower: bool) -> (End, Option<Half>) {
    let q = small_q(draw);
    match (draw.below(3), lower) {
        (0, _) => (End::Unbounded, None),
        (1, true) => (End::Closed(q), Some(Half::Ge(q))),
        (1, false) => (End::Closed(q), Some(Half::Le(q))),
        (_, true) => (End::Open(q), Some(Half::Gt(q))),
        (_, false) => (End::Open(q), Some(Half::Lt(q))),
    }
}

/// A non-empty starting interval with its half-lines, then up to five operations
/// (`true`: `at_least`, `false`: `at_most`).
fn random_case(draw: &mut SplitMix) -> (Interval, Vec<Half>, Vec<(bool, Q)>) {
    loop {
        let (lo, c_lo) = random_end(draw, true);
        let (hi, c_hi) = random_end(draw, false);
        let cs: Vec<Half> = c_lo.into_iter().chain(c_hi).collect();
        let pts: Vec<Q> = cs.iter().map(|&c| point(c)).collect();
        if !grid(&pts).into_iter().any(|m| member(&cs, m)) {
            continue;
        }
        let ops = (0..draw.below(6))
            .map(|_| (draw.below(2) == 0, small_q(draw)))
            .collect();
        let iv = Interval {
            lo,
            hi,
            empty: false,
        };
        return (iv, cs, ops);
    }
}

fn apply(iv: &mut Interval, cs: &mut Vec<Half>, ops: &[(bool, Q)]) {
    for &(least, q) in ops {
        if least {
            iv.at_least(q);
            cs.push(Half::Ge(q));
        } else {
            iv.at_most(q);
            cs.push(Half::Le(q));
        }
    }
}

/// Membership and emptiness after every operation equal the conjunction of the half-lines, on
/// the grid; so does membership of the starting interval.
#[test]
fn membership_is_the_intersection_of_half_lines() {
    let mut draw = SplitMix(0xC4_0001);
    for _ in 0..3000 {
        let (start, cs0, ops) = random_case(&mut draw);
        let mut pts: Vec<Q> = cs0.iter().map(|&c| point(c)).collect();
        pts.extend(ops.iter().map(|o| o.1));
        let g = grid(&pts);
        for &m in &g {
            assert_eq!(start.contains(m), member(&cs0, m), "{start} at {m}");
        }
        let mut iv = start;
        let mut cs = cs0.clone();
        for k in 0..ops.len() {
            apply(&mut iv, &mut cs, &ops[k..k + 1]);
            for &m in &g {
                assert_eq!(
                    iv.contains(m),
                    member(&cs, m),
                    "{iv} at {m} after {start} and {:?}",
                    &ops[..=k]
                );
            }
            assert_eq!(
                iv.empty,
                !g.iter().any(|&m| member(&cs, m)),
                "{iv} after {start} and {:?}",
                &ops[..=k]
            );
        }
    }
}

/// `same_set` is set equality; `witness` finds a negative bonus in the symmetric difference
/// exactly when one exists (both sets intersected with `M < 0` first, as C4 does).
#[test]
fn same_set_is_set_equality_and_witness_is_in_the_symmetric_difference() {
    let mut draw = SplitMix(0xC4_0002);
    let mut witnessed = 0;
    for _ in 0..3000 {
        let (mut a, mut ca, oa) = random_case(&mut draw);
        let (mut b, mut cb, ob) = random_case(&mut draw);
        apply(&mut a, &mut ca, &oa);
        apply(&mut b, &mut cb, &ob);
        let pts: Vec<Q> = ca.iter().chain(&cb).map(|&c| point(c)).collect();
        let g = grid(&pts);
        let equal = g.iter().all(|&m| member(&ca, m) == member(&cb, m));
        assert_eq!(a.same_set(&b), equal, "{a} vs {b}");
        assert!(a.same_set(&a) && b.same_set(&b), "{a}, {b}");
        let mut an = a;
        an.at_most(Q::ZERO);
        ca.push(Half::Lt(Q::ZERO));
        let mut bn = b;
        bn.at_most(Q::ZERO);
        cb.push(Half::Lt(Q::ZERO));
        let differs = g
            .iter()
            .any(|&m| m < Q::ZERO && member(&ca, m) != member(&cb, m));
        match witness(&an, &bn) {
            Some(m) => {
                witnessed += 1;
                assert!(m < Q::ZERO, "witness {m} of {an} vs {bn}");
                assert_ne!(
                    member(&ca, m),
                    member(&cb, m),
                    "witness {m} of {an} vs {bn}"
                );
            }
            None => assert!(!differs, "no witness for {an} vs {bn}"),
        }
    }
    // The cases are not all trivial: many pairs differ.
    assert!(witnessed > 500, "{witnessed}");
}

fn iv(lo: End, hi: End) -> Interval {
    Interval {
        lo,
        hi,
        empty: false,
    }
}

#[test]
fn interval_ends_by_hand() {
    let neg = Interval::negative();
    assert_eq!(neg.to_string(), "(-inf, 0)");
    assert!(neg.contains(Q::new(-1, 1000)) && !neg.contains(Q::ZERO));
    let mut iv = Interval::negative();
    iv.at_least(Q::new(-3, 2));
    assert_eq!(iv.to_string(), "[-3/2, 0)");
    iv.at_least(Q::int(-2)); // a smaller lower bound changes nothing
    assert_eq!(iv.to_string(), "[-3/2, 0)");
    iv.at_least(Q::int(-1)); // a larger one replaces it
    assert_eq!(iv.to_string(), "[-1, 0)");
    iv.at_most(Q::int(-1));
    assert_eq!(iv.to_string(), "[-1, -1]");
    assert!(iv.contains(Q::int(-1)) && !iv.empty);
    iv.at_most(Q::new(-3, 2));
    assert!(iv.empty);
    assert_eq!(iv.to_string(), "empty");
    assert!(!iv.contains(Q::int(-1)));
    // An open end at the same point is kept open; a closed bound there changes nothing.
    let mut open = Interval {
        lo: End::Open(Q::int(-2)),
        hi: End::Unbounded,
        empty: false,
    };
    open.at_least(Q::int(-2));
    assert_eq!(open.to_string(), "(-2, +inf)");
    open.at_most(Q::int(-2));
    assert!(open.empty);
    let mut top = Interval::negative();
    top.at_most(Q::ZERO);
    assert_eq!(top.to_string(), "(-inf, 0)");
    top.at_least(Q::ZERO);
    assert!(top.empty);
    // Equal sets, different building orders; two empty sets are equal.
    let mut a = Interval::negative();
    a.at_most(Q::int(-1));
    a.at_least(Q::int(-4));
    let mut b = Interval::negative();
    b.at_least(Q::int(-4));
    b.at_most(Q::int(-1));
    b.at_most(Q::int(-1));
    assert!(a.same_set(&b) && a == b);
    assert_eq!(witness(&a, &b), None);
    let mut c = a;
    c.at_most(Q::int(-5));
    let mut d = b;
    d.at_least(Q::int(0));
    assert!(c.same_set(&d));
    assert!(!c.same_set(&a));
    assert!(witness(&c, &a).is_some_and(|m| a.contains(m)));
}

/// Every kind of end in the text form.
#[test]
fn text_form_of_every_kind_of_end() {
    let (a, b) = (Q::new(-7, 2), Q::int(3));
    assert_eq!(iv(End::Closed(a), End::Closed(b)).to_string(), "[-7/2, 3]");
    assert_eq!(iv(End::Closed(a), End::Open(b)).to_string(), "[-7/2, 3)");
    assert_eq!(iv(End::Open(a), End::Closed(b)).to_string(), "(-7/2, 3]");
    assert_eq!(iv(End::Open(a), End::Open(b)).to_string(), "(-7/2, 3)");
    assert_eq!(iv(End::Unbounded, End::Closed(b)).to_string(), "(-inf, 3]");
    assert_eq!(
        iv(End::Closed(a), End::Unbounded).to_string(),
        "[-7/2, +inf)"
    );
    assert_eq!(
        iv(End::Unbounded, End::Unbounded).to_string(),
        "(-inf, +inf)"
    );
    let mut gone = iv(End::Closed(a), End::Closed(b));
    gone.empty = true;
    assert_eq!(gone.to_string(), "empty");
}

/// The `empty` flag wins over ends that would contain points, in `contains` and `same_set`;
/// `same_set` compares each end.
#[test]
fn empty_flag_and_end_by_end_equality() {
    let (a, b) = (Q::int(-2), Q::int(-1));
    let full = iv(End::Unbounded, End::Unbounded);
    let mut nothing = full;
    nothing.empty = true;
    for m in [Q::int(-100), a, b, Q::ZERO, Q::int(5)] {
        assert!(full.contains(m));
        assert!(!nothing.contains(m));
    }
    let closed = iv(End::Closed(a), End::Closed(b));
    let mut closed_empty = closed;
    closed_empty.empty = true;
    assert!(!closed.same_set(&closed_empty) && !closed_empty.same_set(&closed));
    assert!(closed_empty.same_set(&nothing) && nothing.same_set(&closed_empty));
    assert!(!full.same_set(&nothing) && !nothing.same_set(&full));
    // Same upper end, different lower end; same lower end, different upper end.
    assert!(!closed.same_set(&iv(End::Open(a), End::Closed(b))));
    assert!(!closed.same_set(&iv(End::Closed(a), End::Open(b))));
    assert!(!closed.same_set(&iv(End::Closed(Q::int(-3)), End::Closed(b))));
    assert!(closed.same_set(&iv(End::Closed(a), End::Closed(b))));
    // Each end of a non-empty interval decides membership on its own.
    assert!(closed.contains(a) && closed.contains(b) && closed.contains(Q::new(-3, 2)));
    assert!(!closed.contains(Q::new(-5, 2)) && !closed.contains(Q::new(-1, 2)));
    let open = iv(End::Open(a), End::Open(b));
    assert!(!open.contains(a) && !open.contains(b) && open.contains(Q::new(-3, 2)));
    assert!(!open.contains(Q::new(-5, 2)) && !open.contains(Q::new(-1, 2)));
}

/// A witness that only a candidate below every end, above every end, or (with no negative end)
/// `-1` can find.
#[test]
fn witness_candidates_outside_the_ends() {
    let neg = Interval::negative();
    // No negative end at all: the only candidate is -1.
    let mut nothing = neg;
    nothing.at_most(Q::int(-1));
    nothing.at_least(Q::ZERO);
    assert!(nothing.empty);
    let mut nothing_no_ends = neg;
    nothing_no_ends.empty = true;
    assert_eq!(witness(&neg, &nothing_no_ends), Some(Q::int(-1)));
    assert_eq!(witness(&nothing_no_ends, &neg), Some(Q::int(-1)));
    // The sets differ only below -2: the candidate -2 - 1.
    let mut from_minus_two = neg;
    from_minus_two.at_least(Q::int(-2));
    assert_eq!(witness(&neg, &from_minus_two), Some(Q::int(-3)));
    // The sets differ only between -1/4 and 0: the candidate (-1/4)/2.
    let mut below_quarter = neg;
    below_quarter.at_most(Q::new(-1, 4));
    assert_eq!(witness(&neg, &below_quarter), Some(Q::new(-1, 8)));
    // The sets differ only strictly between -3 and -1: the midpoint -2.
    let open = iv(End::Open(Q::int(-3)), End::Open(Q::int(-1)));
    let mut split = open;
    split.empty = true;
    assert_eq!(witness(&open, &split), Some(Q::int(-2)));
    // The sets differ only at an end point itself.
    let closed = iv(End::Closed(Q::int(-3)), End::Open(Q::int(-1)));
    assert_eq!(witness(&open, &closed), Some(Q::int(-3)));
    assert_eq!(witness(&closed, &closed), None);
    assert_eq!(witness(&neg, &neg), None);
}
