//! Engine 2 under `cargo test`: the proptest properties of `truecost::claims::sampled`, with
//! failure persistence in committed regression files (`tests/regressions/`). Refuted claims
//! must fail and shrink to a small counterexample; the corrected ones must hold.

use truecost::claims::sampled;

const CASES: u32 = 256;

#[test]
fn c1_as_printed_fails_and_shrinks_to_a_lone_goal() {
    let r = sampled::c1_printed(CASES, Some("tests/regressions/c1.txt"));
    let (t, _) = r.counterexample.expect("C1 as printed is refuted");
    // The smallest possible problem: one state, the goal.
    assert_eq!(t.states(), 1);
}

#[test]
fn c1_corrected_holds() {
    let r = sampled::c1_corrected(CASES, Some("tests/regressions/c1-corrected.txt"));
    assert!(r.counterexample.is_none(), "{:?}", r.counterexample);
    assert!(r.relevant > 0);
}

#[test]
fn c2_holds() {
    let r = sampled::c2(CASES, Some("tests/regressions/c2.txt"));
    assert!(r.counterexample.is_none(), "{:?}", r.counterexample);
}

#[test]
fn c3_certificates_exist() {
    let r = sampled::c3(CASES, Some("tests/regressions/c3.txt"));
    assert!(r.counterexample.is_none(), "{:?}", r.counterexample);
    assert!(r.relevant > 0);
}

#[test]
fn c4_as_printed_fails_and_shrinks() {
    let r = sampled::c4(true, CASES, Some("tests/regressions/c4.txt"));
    let (t, msg) = r.counterexample.expect("C4 as printed is refuted");
    // A disagreement needs two goal paths of different lengths: at least 3 states.
    assert!(
        t.states() >= 3 && t.states() <= 4,
        "{msg}: {}",
        t.describe()
    );
}

#[test]
fn c4_corrected_holds() {
    let r = sampled::c4(false, CASES, Some("tests/regressions/c4-corrected.txt"));
    assert!(r.counterexample.is_none(), "{:?}", r.counterexample);
}
