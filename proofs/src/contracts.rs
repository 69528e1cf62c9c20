//! The kernel's contracts, each proved once (`#[kani::proof_for_contract]`), so that the claim
//! harnesses can use them through `#[kani::stub_verified]` instead of running the code: no C1
//! harness runs the `ρ = 1` update's loop, no harness but [`lowest_terms_has_a_bezout_witness`]
//! runs Euclid's loop.
//!
//! A contract states what the function guarantees, independently of how it computes
//! (`claims::exact::spec`, `claims::qlearning::update_spec`, `value::units_plus_spec`), and
//! without a loop: a common divisor, the exact value by cross-multiplication, coprime parts by a
//! Bézout witness that `lowest_terms` returns (`num·x + den·y = 1`), `None` only on overflow,
//! the `ρ = 1` rule as a minimum. `lowest_terms` (extended Euclid) is the only loop of
//! `claims::exact`: `gcd`, `Q::ratio` and `Q`'s operations call it, so with it replaced by its
//! contract they are straight-line code. Under Kani (`-Z function-contracts`, set in
//! `proofs/Cargo.toml`) each harness below assumes the precondition at its call and checks the
//! postcondition; the stand-in does the same on the executions it runs.
//!
//! Loops CBMC unrolls (`tests/unwind_bounds.rs`): the extended Euclid loop on 16-bit operands —
//! by Lamé's theorem at most `1 + 22` iterations for magnitudes up to 32767 — in
//! [`lowest_terms_has_a_bezout_witness`] only; the update harness's frame check reads the 24
//! values.

use truecost_kernel::claims::exact::{gcd, lowest_terms, Q};
use truecost_kernel::claims::qlearning::{QProblem, Terminal, Values, MAX_PAIRS};
use truecost_kernel::value::Units;

use crate::symbolic::{any_structure, learner, values, MOVES, TERMINAL};

/// `gcd` on any two `i16` values (the precondition excludes `i16::MIN`, whose magnitude does
/// not fit): non-negative, zero exactly when both are, a divisor of both. `lowest_terms` is
/// its contract (no loop: `|b|` divided by the reduced denominator). Domain 2^32.
#[kani::proof_for_contract(truecost_kernel::claims::exact::gcd)]
#[kani::stub_verified(truecost_kernel::claims::exact::lowest_terms)]
#[kani::solver(kissat)]
pub fn gcd_divides_both() {
    let (a, b): (i16, i16) = (kani::any(), kani::any());
    let g = gcd(a, b);
    kani::cover!(g > 1, "a non-trivial common divisor");
    kani::cover!(a == 0 && b != 0, "one operand zero");
    kani::cover!(a < 0 && b < 0, "two negative operands");
}

/// `lowest_terms(n, d)` at `i16` on any values (precondition: `d ≠ 0`, neither is
/// `i16::MIN`): the value `n/d` exactly, a positive denominator, and a Bézout witness
/// `num·x + den·y = 1` (so coprime parts). Domain 2^32. Unwind 24: the extended Euclid loop on
/// magnitudes up to 32767 (Lamé: 23), the one Euclid loop any harness unrolls.
#[kani::proof_for_contract(truecost_kernel::claims::exact::lowest_terms)]
#[kani::unwind(24)]
#[kani::solver(kissat)]
pub fn lowest_terms_has_a_bezout_witness() {
    let (n, d): (i16, i16) = (kani::any(), kani::any());
    let l = lowest_terms(n, d);
    kani::cover!(l.den < d.abs(), "a fraction that reduces");
    kani::cover!(d < 0 && l.num > 0, "a negative denominator flips the sign");
    kani::cover!(n == 0, "zero");
}

/// Any `Q<i16>` with numerator and denominator in `[-127, 127]` (denominator non-zero), built
/// by `Q::ratio` (its `lowest_terms` replaced by the proven contract under Kani).
fn any_small_q() -> Q<i16> {
    let n = kani::any_where(|v: &i8| *v != i8::MIN) as i16;
    let d = kani::any_where(|v: &i8| *v != i8::MIN && *v != 0) as i16;
    Q::ratio(n, d)
}

/// `Q::<i16>::checked_add` on any two fractions with parts in `[-127, 127]` and on any two
/// integers (`i16`, so that the overflow branch is reached): a `Some` has a positive
/// denominator and exactly the sum, `None` only when the unreduced sum does not fit.
/// `lowest_terms` is its contract (no Euclid here). Domain 2^33 (which kind of operands, then
/// 32 bits).
#[kani::proof_for_contract(Q::<i16>::checked_add)]
#[kani::stub_verified(truecost_kernel::claims::exact::lowest_terms)]
#[kani::solver(kissat)]
pub fn checked_add_is_exact() {
    let (a, b) = if kani::any() {
        (any_small_q(), any_small_q())
    } else {
        let (x, y): (i16, i16) = (kani::any(), kani::any());
        (Q::integer(x), Q::integer(y))
    };
    let r = a.checked_add(b);
    kani::cover!(r.is_none(), "a sum that does not fit");
    kani::cover!(r.is_some_and(|q| q.denom() > 1), "a proper fraction");
}

/// `Q::<i16>::checked_mul` on any two fractions with parts in `[-127, 127]` (every product
/// fits) and on any two integers (`i16`: products that do not fit): a `Some` has a positive
/// denominator and exactly the product, `None` only when the unreduced product does not fit.
/// `lowest_terms` (the cross-cancelling and the final reduction) is its contract. Domain 2^33.
#[kani::proof_for_contract(Q::<i16>::checked_mul)]
#[kani::stub_verified(truecost_kernel::claims::exact::lowest_terms)]
#[kani::solver(kissat)]
pub fn checked_mul_is_exact() {
    let (a, b) = if kani::any() {
        (any_small_q(), any_small_q())
    } else {
        let (x, y): (i16, i16) = (kani::any(), kani::any());
        (Q::integer(x), Q::integer(y))
    };
    let r = a.checked_mul(b);
    kani::cover!(r.is_none(), "a product that does not fit");
    kani::cover!(r.is_some_and(|q| q.signum() < 0), "a negative product");
}

/// `Units::checked_plus` on any two `u64` counts: `+∞` absorbs, a sum below `u64::MAX` is
/// exact, `None` exactly when it is not. Domain 2^128; no loop.
#[kani::proof_for_contract(truecost_kernel::value::Units::checked_plus)]
pub fn units_checked_plus_is_exact() {
    let (a, b): (u64, u64) = (kani::any(), kani::any());
    let r = Units(a).checked_plus(&Units(b));
    kani::cover!(r.is_none(), "an overflow is reported");
    kani::cover!(r.is_some_and(|s| s.0 != u64::MAX), "a finite sum");
}

/// `QProblem::update` on any structure of the C1 family (successors and `u16` costs
/// symbolic), any `i32` values, any pair (the termination pair included, held or updated):
/// the `ρ = 1` rule (`update_spec`: the pair's new value is `l + Q̂` of some successor pair and
/// at most that of every one) and no other value changes (asserted here over the 24 values;
/// Kani also checks the contract's `modifies(&v[p])`). Domain 2^377 (144 + 224 + 8 + 1
/// choice bits).
/// Unwind 25: the frame check reads the 24 values.
#[kani::proof_for_contract(truecost_kernel::claims::qlearning::QProblem::update)]
#[kani::unwind(25)]
pub fn update_is_the_rho_one_rule() {
    let s = any_structure(0);
    let terminal = if kani::any() {
        Terminal::HeldAtZero
    } else {
        Terminal::Updated
    };
    let q: QProblem = learner(&s, terminal);
    let mut v: Values = values();
    for p in 0..=TERMINAL {
        v[p] = kani::any::<i32>() as i64;
    }
    let p = (kani::any::<u8>() % (TERMINAL as u8 + 1)) as usize;
    let old = v;
    let before = v[p];
    q.update(&mut v, p);
    // The frame condition (`modifies(&v[p])`, checked by Kani itself), element by element.
    for k in 0..MAX_PAIRS {
        kani::assert(k == p || v[k] == old[k], "no other value changes");
    }
    kani::cover!(p < MOVES && v[p] < before, "a move pair's value falls");
    kani::cover!(p < MOVES && v[p] > before, "a move pair's value rises");
    kani::cover!(
        p == TERMINAL && terminal == Terminal::HeldAtZero,
        "the held termination pair"
    );
}
