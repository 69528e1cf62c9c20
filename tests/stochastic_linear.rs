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

/// One row's entries `(column, value)`.
type Row = Vec<(usize, i64)>;

/// A random system shaped like policy evaluation: `s·z_i − Σ w·z_j = r_i` with `Σ w < s` on
/// random neighbours (strictly diagonally dominant, so LU without pivoting is stable).
fn random_system(n: usize, seed: u64) -> (SparseSystem, Vec<Row>, Vec<i128>) {
    use rand::{Rng, SeedableRng};
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    let (mut s, mut rows, mut rhs) = (SparseSystem::new(), Vec::new(), Vec::new());
    for i in 0..n {
        let diag = 50 + (rng.next_u32() % 400) as i64;
        let mut entries = vec![(i, diag)];
        let mut budget = diag - 1;
        for _ in 0..4 {
            let j = (rng.next_u32() as usize) % n;
            let w = 1 + (rng.next_u32() as i64) % (budget / 4).max(1);
            if j == i || budget - w < 0 {
                continue;
            }
            budget -= w;
            entries.push((j, -w));
        }
        let r = (rng.next_u32() % 1000) as i128 - 300;
        s.push_row(&entries, r).unwrap();
        rows.push(entries);
        rhs.push(r);
    }
    (s, rows, rhs)
}

#[test]
fn the_f64_solve_has_a_small_residual_and_agrees_with_the_exact_solve() {
    for (n, seed) in [(1, 0), (2, 5), (7, 1), (40, 2), (150, 3)] {
        let (system, rows, rhs) = random_system(n, seed);
        let z = truecost::stochastic::linear::solve_f64(&system).unwrap();
        assert_eq!(z.len(), n);
        // The residual, computed here from the rows as given (not from the solver's band).
        for (i, (entries, r)) in rows.iter().zip(&rhs).enumerate() {
            let lhs: f64 = entries.iter().map(|&(j, v)| v as f64 * z[j]).sum();
            let scale: f64 = entries.iter().map(|&(j, v)| (v as f64 * z[j]).abs()).sum();
            assert!(
                (lhs - *r as f64).abs() <= 1e-9 * (scale + (*r as f64).abs() + 1.0),
                "n = {n}, row {i}: {lhs} against {r}"
            );
        }
        // And the exact solution, rounded.
        let exact = solve_exact(&system).unwrap();
        for (i, numerator) in exact.numerators.iter().enumerate() {
            let want = f64_of(numerator, &exact.denominator);
            assert!(
                (z[i] - want).abs() <= 1e-9 * want.abs().max(1.0),
                "n = {n}, z[{i}] = {} against {want}",
                z[i]
            );
        }
    }
}

/// `n/d` rounded (numerator and denominator can both exceed `f64`'s range).
fn f64_of(n: &BigInt, d: &BigInt) -> f64 {
    use num_traits::ToPrimitive;
    truecost::stochastic::linear::reduced(n, d)
        .to_f64()
        .unwrap()
}
