//! The exact sparse solver's public edges (`src/stochastic/linear.rs`): emptiness, the band
//! ordering's widths on patterns whose bandwidth is known by hand, and the refusal of a band
//! too wide for memory, which must name the width the ordering actually has (issue 14: the
//! mutants `is_empty → true`, `bandwidths → (0, 0)` and the width `lower + upper + 1` →
//! `lower + upper` survived the solver's other tests).

use num_bigint::BigInt;
use truecost::stochastic::linear::{solve_exact, BandOrdering, LinearError, SparseSystem};

#[test]
fn emptiness_and_length_follow_the_rows_pushed() {
    let mut s = SparseSystem::new();
    assert!(s.is_empty());
    assert_eq!(s.len(), 0);
    let z = solve_exact(&s).unwrap();
    assert!(z.numerators.is_empty());
    s.push_row(&[(0, 2)], 3).unwrap();
    assert!(!s.is_empty());
    assert_eq!(s.len(), 1);
    let z = solve_exact(&s).unwrap();
    // 2·z = 3.
    assert_eq!(
        &z.numerators[0] * BigInt::from(2),
        &z.denominator * BigInt::from(3)
    );
}

/// The rows of `A` with the given off-diagonal pattern and a dominant diagonal.
fn pattern(n: usize, neighbours: impl Fn(usize) -> Vec<usize>) -> SparseSystem {
    let mut s = SparseSystem::new();
    for i in 0..n {
        let others = neighbours(i);
        let mut entries = vec![(i, 2 * others.len() as i64 + 1)];
        entries.extend(others.into_iter().map(|j| (j, -1)));
        s.push_row(&entries, 1).unwrap();
    }
    s
}

#[test]
fn bandwidths_of_hand_known_patterns() {
    // Diagonal: no off-diagonal entry in any ordering.
    assert_eq!(
        BandOrdering::new(&pattern(5, |_| vec![])).bandwidths(),
        (0, 0)
    );
    // A path 0 – 1 – … – 5: bandwidth 1 is optimal and Cuthill–McKee from an end finds it.
    let path = pattern(6, |i| {
        let mut v = Vec::new();
        if i > 0 {
            v.push(i - 1);
        }
        if i < 5 {
            v.push(i + 1);
        }
        v
    });
    assert_eq!(BandOrdering::new(&path).bandwidths(), (1, 1));
    // A star: the centre has n − 1 neighbours, so in any ordering one of them is at least
    // ⌈(n − 1)/2⌉ positions away; the pattern is symmetric, so lower = upper.
    let n = 9;
    let star = pattern(n, |i| if i == 0 { (1..n).collect() } else { vec![0] });
    let (lower, upper) = BandOrdering::new(&star).bandwidths();
    assert_eq!(lower, upper);
    assert!((n.div_ceil(2) - 1..n).contains(&lower), "{lower}");
}

#[test]
fn a_band_too_wide_is_refused_with_the_ordering_s_width() {
    // A star of 40 000 unknowns: width ≥ 40 000 so n·width > 2^28 band entries.
    let n = 40_000;
    let star = pattern(n, |i| if i == 0 { (1..n).collect() } else { vec![0] });
    let (lower, upper) = BandOrdering::new(&star).bandwidths();
    assert!(lower >= (n - 1) / 2 && upper >= (n - 1) / 2);
    assert_eq!(
        solve_exact(&star),
        Err(LinearError::TooWide {
            states: n,
            width: lower + upper + 1,
        })
    );
}
