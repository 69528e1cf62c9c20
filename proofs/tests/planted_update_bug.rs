//! A planted bug in the `ρ = 1` update is caught by the stand-in runs of the C1 harnesses: the
//! harnesses' statements run with an update that applies truecost's `QProblem::update` and then
//! moves the new value by one (an off-by-one in `l(x,u) + min Q̂`, either way), and with one
//! that never updates pair 0 (an unfair round). Each must fail; the real update must pass.

use truecost_kernel::claims::qlearning::{QProblem, Values};
use truecost_proofs::c1;

/// The real update, then one less on the updated pair.
fn one_below(q: &QProblem, v: &mut Values, p: usize) {
    q.update(v, p);
    if q.updatable(p) {
        v[p] -= 1;
    }
}

/// The real update, then one more on the updated pair.
fn one_above(q: &QProblem, v: &mut Values, p: usize) {
    q.update(v, p);
    if q.updatable(p) {
        v[p] += 1;
    }
}

/// The real update on every pair but pair 0, which is never updated.
fn skips_pair_zero(q: &QProblem, v: &mut Values, p: usize) {
    if p != 0 {
        q.update(v, p);
    }
}

fn run(h: kani::Harness, body: fn(), samples: u64) -> kani::Summary {
    kani::Harness { body, ..h }.explore_with(samples)
}

#[test]
fn an_update_one_below_the_rule_breaks_q_at_least_q_star() {
    let h = c1::c1_corrected_round_lifts_the_exact_level::HARNESS;
    let s = run(h, || c1::lifts_the_exact_level(one_below), 2000);
    let why = s.verdict().expect_err("the planted bug is caught");
    assert!(s.failures > 0, "{s}");
    assert!(why.contains("(Lemma A"), "{why}");
    // The same run with the real update passes.
    let s = run(h, || c1::lifts_the_exact_level(QProblem::update), 2000);
    assert_eq!(s.verdict(), Ok(()), "{s}");
}

#[test]
fn an_update_one_above_the_rule_or_an_unfair_round_is_caught() {
    let s = run(
        c1::c1_corrected_round_is_monotone_below_q_star::HARNESS,
        || c1::is_monotone_below_q_star(one_above),
        2000,
    );
    let why = s.verdict().expect_err("the planted bug is caught");
    assert!(why.contains("Q <= Q* is preserved"), "{why}");
    let s = run(
        c1::c1_corrected_round_raises_the_floor_by_c::HARNESS,
        || c1::raises_the_floor_by_c(skips_pair_zero),
        2000,
    );
    let why = s.verdict().expect_err("an unfair round is caught");
    assert!(why.contains("J_{t+c}"), "{why}");
}
