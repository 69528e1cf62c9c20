//! The exact sparse solver's public edges (`src/algebra/linear.rs`): emptiness, the band
//! ordering's widths on patterns whose bandwidth is known by hand, and the refusal of a band
//! too wide for memory, which must name the width the ordering actually has (the
//! mutants `is_empty → true`, `bandwidths → (0, 0)` and the width `lower + upper + 1` →
//! `lower + upper` survived the solver's other tests).

use num_bigint::BigInt;
use truecost::algebra::linear::{solve_exact, BandOrdering, LinearError, SparseSystem};

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

// ---------------------------------------------------------------------------------------------
// The lifting schedule (module docs of linear.rs, `lift`): how many Dixon steps a solve takes.
// Only the answer is verified inside the solver, so a change to the schedule would pass every
// test of the answer; here the steps are held to what the documentation promises, with the
// determinant computed exactly by Bareiss' elimination (independent of the solver).

/// `|det A|` of a dense integer matrix by Bareiss' fraction-free elimination (exact).
fn determinant(mut a: Vec<Vec<BigInt>>) -> BigInt {
    let n = a.len();
    let mut previous = BigInt::from(1);
    let mut sign = 1;
    for k in 0..n {
        if a[k][k] == BigInt::from(0) {
            let Some(r) = (k + 1..n).find(|&r| a[r][k] != BigInt::from(0)) else {
                return BigInt::from(0);
            };
            a.swap(k, r);
            sign = -sign;
        }
        for i in k + 1..n {
            for j in k + 1..n {
                a[i][j] = (&a[i][j] * &a[k][k] - &a[i][k] * &a[k][j]) / &previous;
            }
        }
        previous = a[k][k].clone();
    }
    previous * sign
}

/// `log2 |x|` for a nonzero integer of any size (its top 64 bits in f64).
fn log2(x: &BigInt) -> f64 {
    let bits = x.bits();
    let shift = bits.saturating_sub(64);
    let top: BigInt = x.magnitude().clone().into();
    let top = u64::try_from(top >> shift).unwrap();
    (top as f64).log2() + shift as f64
}

/// The system with the given rows of `A` and right-hand sides below `2^rhs_bits` drawn in row
/// order; and its dense copy (for the determinant).
fn with_random_rhs(
    rng: &mut rand_chacha::ChaCha8Rng,
    rows: Vec<Vec<(usize, i64)>>,
    rhs_bits: u32,
) -> (SparseSystem, Vec<Vec<BigInt>>) {
    use rand::RngExt;
    let n = rows.len();
    let mut system = SparseSystem::new();
    let mut dense = vec![vec![BigInt::from(0); n]; n];
    for (entries, dense_row) in rows.iter().zip(&mut dense) {
        for &(j, v) in entries {
            dense_row[j] = BigInt::from(v);
        }
        let rhs = rng.random_range(-(1i128 << rhs_bits)..1i128 << rhs_bits);
        system.push_row(entries, rhs).unwrap();
    }
    (system, dense)
}

/// A random system with a dominant diagonal (so `det A ≠ 0`), entries below `2^bits` in a band
/// of half-width `w`, right-hand sides below `2^rhs_bits`; and its dense copy.
fn random_banded(
    rng: &mut rand_chacha::ChaCha8Rng,
    n: usize,
    w: usize,
    bits: u32,
    rhs_bits: u32,
) -> (SparseSystem, Vec<Vec<BigInt>>) {
    use rand::RngExt;
    let rows = (0..n)
        .map(|i| {
            let mut entries = Vec::new();
            let mut off = 0i64;
            for j in i.saturating_sub(w)..(i + w + 1).min(n) {
                if j != i && rng.random_range(0..3) > 0 {
                    let v = rng.random_range(-(1i64 << bits) + 1..1i64 << bits);
                    off += v.abs();
                    entries.push((j, v));
                }
            }
            entries.push((i, off + rng.random_range(1..1i64 << bits)));
            entries
        })
        .collect();
    with_random_rhs(rng, rows, rhs_bits)
}

/// `k` copies of one random `s × s` block with a dominant diagonal on the diagonal of `A`
/// (entries below `2^bits`), right-hand sides below `2^rhs_bits`: `|det A| = |det B|^k`, while
/// the answer's denominator divides `det B`, so reconstruction succeeds long before the
/// `expected` estimate (from `det A`) — the schedule's early tries.
fn repeated_block(
    rng: &mut rand_chacha::ChaCha8Rng,
    k: usize,
    s: usize,
    bits: u32,
    rhs_bits: u32,
) -> (SparseSystem, Vec<Vec<BigInt>>) {
    use rand::RngExt;
    let block: Vec<Vec<i64>> = (0..s)
        .map(|i| {
            let mut row: Vec<i64> = (0..s)
                .map(|_| rng.random_range(-(1i64 << bits) + 1..1i64 << bits))
                .collect();
            row[i] = row.iter().map(|v| v.abs()).sum::<i64>() + 1;
            row
        })
        .collect();
    let rows = (0..k)
        .flat_map(|b| {
            block.iter().map(move |row| {
                row.iter()
                    .enumerate()
                    .map(|(j, &v)| (b * s + j, v))
                    .collect()
            })
        })
        .collect();
    with_random_rhs(rng, rows, rhs_bits)
}

/// The lifting steps at which the documented schedule tries a reconstruction, up to `last`:
/// 4 (or `expected` if fewer), then ×1.5 (at least +2) up to `expected`, then every 2 %
/// (at least 2 steps).
fn try_points(expected: usize, last: usize) -> Vec<usize> {
    let mut points = vec![4.min(expected)];
    loop {
        let t = *points.last().unwrap();
        let next = if t < expected {
            (t * 3).div_ceil(2).max(t + 2).min(expected)
        } else {
            t + (t / 50).max(2)
        };
        if next > last {
            return points;
        }
        points.push(next);
    }
}

#[test]
fn lifting_takes_the_steps_the_schedule_documents() {
    use num_integer::Integer;
    use rand::SeedableRng;
    use truecost::algebra::linear::solve_exact_with;
    // Every prime the solver uses lies in (2^30, 2^31): log2 p ≈ 31 (the largest below
    // 2^31 − 1 first).
    let log2_p = 2_147_483_629f64.log2();
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(14);
    let mut cases = 0;
    for (n, w, bits, rhs_bits) in [
        (1, 0, 4, 8),
        (3, 1, 6, 10),
        (6, 2, 10, 20),
        (10, 3, 16, 30),
        (16, 4, 24, 40),
        (24, 3, 30, 60),
        (12, 11, 28, 90),
        // Repeated blocks (n = 0 marks them; w is the block size, the copies are 8).
        (0, 2, 8, 10),
        (0, 3, 20, 20),
        (0, 3, 28, 40),
        (0, 4, 28, 60),
        (0, 6, 30, 90),
    ] {
        for _ in 0..6 {
            let (system, dense) = if n == 0 {
                repeated_block(&mut rng, 8, w, bits, rhs_bits)
            } else {
                random_banded(&mut rng, n, w, bits, rhs_bits)
            };
            let mut seen = Vec::new();
            let z = solve_exact_with(&system, &mut |l| seen.push(l)).unwrap();
            let steps = z.lifting_steps;
            let case = format!("n={n} w={w} bits={bits} rhs_bits={rhs_bits}: {steps} steps");
            // Progress after every step, counting up, with one `expected` throughout.
            assert_eq!(seen.len(), steps, "{case}");
            assert!(
                seen.iter().enumerate().all(|(i, l)| l.steps == i + 1),
                "{case}"
            );
            let expected = seen[0].expected;
            assert!(seen.iter().all(|l| l.expected == expected), "{case}");

            // `expected` is `2·log_p(|det A|·max|z|)` (at least 1 for max|z|) plus two bits,
            // rounded up, plus one step (f64 estimates: allow a boundary either way).
            let det = determinant(dense);
            let g = z
                .numerators
                .iter()
                .fold(z.denominator.clone(), |g, v| g.gcd(v));
            let d_reduced = &z.denominator / &g;
            let n_max = z
                .numerators
                .iter()
                .map(|v| (v / &g).magnitude().clone())
                .max()
                .unwrap();
            let max_z = (log2(&BigInt::from(n_max.clone()).max(BigInt::from(1)))
                - log2(&d_reduced))
            .max(0.0);
            let bits_expected = 2.0 * (log2(&det) + max_z) + 2.0;
            let low = ((bits_expected - 1e-6) / log2_p).ceil() as usize + 1;
            let high = ((bits_expected + 1e-6) / log2_p).ceil() as usize + 1;
            assert!(
                (low..=high).contains(&expected),
                "{case}: expected {expected}, documented {low}..={high}"
            );

            // The steps are a try point of the schedule, …
            assert!(
                try_points(expected, steps).contains(&steps),
                "{case}: not a try point of {expected}"
            );
            // … the returned denominator fits the reconstruction bound `d ≤ sqrt(p^K / 2)`, …
            assert!(
                2.0 * log2(&z.denominator) + 1.0 <= steps as f64 * log2_p,
                "{case}: d too large"
            );
            // … and the solve stops at the first try point where reconstruction is certain
            // (`p^K > 2·max(N, D)²` with the reduced answer's N and D) or earlier.
            let need = 2.0 * log2(&BigInt::from(n_max).max(d_reduced.clone())) + 1.0;
            let certain = try_points(expected, usize::MAX >> 1)
                .into_iter()
                .find(|&t| t as f64 * log2_p > need + 1e-6)
                .unwrap();
            assert!(steps <= certain, "{case}: certain at {certain}");
            cases += 1;
        }
    }
    assert_eq!(cases, 72);
}

/// `push_row`'s word-size limits at their edges: an entry, alone or summed from duplicates of
/// its column, must be below 2^62 in magnitude; a right-hand side below 2^100; a column must
/// fit 32 bits. Each case on a fresh system (a refused row is not to be used further).
#[test]
fn push_row_refuses_entries_from_2_to_the_62_and_right_hand_sides_from_2_to_the_100() {
    let row = |entries: &[(usize, i64)], rhs: i128| SparseSystem::new().push_row(entries, rhs);
    let edge = 1i64 << 62;
    assert_eq!(row(&[(0, edge)], 0), Err(LinearError::TooLarge));
    assert_eq!(row(&[(0, -edge)], 0), Err(LinearError::TooLarge));
    assert_eq!(row(&[(0, edge - 1)], 0), Ok(()));
    assert_eq!(row(&[(0, 1 - edge)], 0), Ok(()));
    let half = 1i64 << 61;
    assert_eq!(row(&[(0, half), (0, half)], 0), Err(LinearError::TooLarge));
    assert_eq!(
        row(&[(0, -half), (1, 1), (0, -half)], 0),
        Err(LinearError::TooLarge)
    );
    // Duplicates are summed: (2^61 + 2^61 − 1)·z = 3·(2^62 − 1) gives z = 3.
    let mut s = SparseSystem::new();
    s.push_row(&[(0, half), (0, half - 1)], 3 * i128::from(edge - 1))
        .unwrap();
    let z = solve_exact(&s).unwrap();
    assert_eq!(z.numerators[0].clone() / &z.denominator, BigInt::from(3));
    assert_eq!(z.numerators[0].clone() % &z.denominator, BigInt::from(0));
    let big = 1i128 << 100;
    assert_eq!(row(&[(0, 1)], big), Err(LinearError::TooLarge));
    assert_eq!(row(&[(0, 1)], -big), Err(LinearError::TooLarge));
    assert_eq!(row(&[(0, 1)], big - 1), Ok(()));
    assert_eq!(row(&[(0, 1)], 1 - big), Ok(()));
    assert_eq!(row(&[(1 << 32, 1)], 0), Err(LinearError::TooLarge));
    assert_eq!(row(&[((1 << 32) - 1, 1)], 0), Ok(()));
}

/// When the f64 estimate of the system is singular but the system is not, the schedule's
/// `expected` falls back to the Hadamard bound (`hadamard_bits`, documented as
/// `2·(Σ ½·log2 ‖row‖² + log2 max|r| + log2(n + 1)) + 8` bits, rows and right-hand sides as
/// f64). The rows `(2^54 + 1, 2^54)` and `(2^54, 2^54 − 1)` have determinant −1 but all round
/// to 2^54 in f64: ‖row‖² = 2^109 each, so `2·(109 + 0 + log2 3) + 8 = 229.2` gives 230 bits
/// and `⌈230 / log2 p⌉ + 1 = 9` steps with p just below 2^31. The solution is still exact:
/// `(1, −1)` for the right-hand sides `(1, 1)`.
#[test]
fn an_f64_singular_estimate_falls_back_to_the_hadamard_bound() {
    use truecost::algebra::linear::solve_exact_with;
    let a = 1i64 << 54;
    let mut s = SparseSystem::new();
    s.push_row(&[(0, a + 1), (1, a)], 1).unwrap();
    s.push_row(&[(0, a), (1, a - 1)], 1).unwrap();
    let mut seen = Vec::new();
    let z = solve_exact_with(&s, &mut |l| seen.push(l)).unwrap();
    // (a+1)·x + a·y = 1 and a·x + (a−1)·y = 1: x = 1, y = −1.
    assert_eq!(&z.numerators[0] / &z.denominator, BigInt::from(1));
    assert_eq!(&z.numerators[1] / &z.denominator, BigInt::from(-1));
    assert!(z.denominator == BigInt::from(1) || z.denominator == BigInt::from(-1));
    let log2_p = 2_147_483_629f64.log2();
    let bits = (2.0 * (109.0 + 3f64.log2()) + 8.0f64).ceil();
    assert_eq!(bits, 230.0);
    let expected = (bits / log2_p).ceil() as usize + 1;
    assert_eq!(expected, 9);
    assert!(
        !seen.is_empty() && seen.iter().all(|l| l.expected == expected),
        "{seen:?}"
    );
}

/// `reduced_all` (shared factors tried first, the rest batched through a product modulo each
/// reduced denominator) gives, for every numerator, the same lowest terms as `num-rational`'s
/// own reduction, on denominators sharing small and large factors with some numerators, zero
/// and negative numerators, and numerators beyond `d²` (the plain division path).
#[test]
fn batched_reduction_agrees_with_reducing_each_fraction() {
    use num_rational::BigRational;
    use rand::{RngExt, SeedableRng};
    use truecost::algebra::linear::{reduced, reduced_all};
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
    let big = |bits: usize, rng: &mut rand_chacha::ChaCha8Rng| -> BigInt {
        let mut x = BigInt::from(1u8);
        for _ in 0..bits.div_ceil(32) {
            x = (x << 32) + BigInt::from(rng.random::<u32>());
        }
        x
    };
    for case in 0..12 {
        let large_factor = big(200 + 100 * case, &mut rng);
        let small = BigInt::from([2u32, 3, 5, 6, 7, 12, 1024, 97][case % 8]);
        let d = match case {
            0 => BigInt::from(1u8),
            1 => big(300, &mut rng) * BigInt::from(2u8) + BigInt::from(1u8),
            _ => &large_factor * &small * big(64, &mut rng),
        };
        let numerators: Vec<BigInt> = (0..40)
            .map(|i| {
                let n = match i % 8 {
                    0 => BigInt::from(0u8),
                    1 => &small * big(100, &mut rng),
                    2 => &large_factor * big(50, &mut rng),
                    3 => &d * big(20, &mut rng),
                    4 => &d * &d * big(40, &mut rng) + BigInt::from(i),
                    5 => BigInt::from(i + 1),
                    _ => big(case * 50 + 30, &mut rng),
                };
                if i % 3 == 0 {
                    -n
                } else {
                    n
                }
            })
            .collect();
        let refs: Vec<&BigInt> = numerators.iter().collect();
        let batched = reduced_all(&refs, &d);
        assert_eq!(batched.len(), numerators.len());
        for (n, r) in numerators.iter().zip(&batched) {
            let expected = BigRational::new(n.clone(), d.clone());
            assert_eq!(r.numer(), expected.numer(), "case {case}: {n}/{d}");
            assert_eq!(r.denom(), expected.denom(), "case {case}: {n}/{d}");
            assert_eq!(r, &reduced(n, &d), "case {case}");
        }
    }
}

/// When the three probe unknowns (first, middle, last) have denominator 1 and the others 7, the
/// probes' common denominator misses the 7: the solver must widen it (more probes, or every
/// unknown) and still return the exact solution with the least common denominator.
#[test]
fn a_factor_missing_from_the_probes_denominators_is_found() {
    for n in [64usize, 301] {
        let probes = [0, n / 2, n - 1];
        let mut s = SparseSystem::new();
        let mut expected = Vec::new();
        for j in 0..n {
            let (diagonal, rhs) = if probes.contains(&j) {
                (1, j as i128 + 1)
            } else {
                (7, j as i128)
            };
            s.push_row(&[(j, diagonal)], rhs).unwrap();
            expected.push(num_rational::BigRational::new(
                BigInt::from(rhs),
                BigInt::from(diagonal),
            ));
        }
        let z = solve_exact(&s).unwrap();
        assert_eq!(z.denominator, BigInt::from(7), "{n}");
        for (j, e) in expected.iter().enumerate() {
            let got =
                num_rational::BigRational::new(z.numerators[j].clone(), z.denominator.clone());
            assert_eq!(&got, e, "{n}: unknown {j}");
        }
    }
}

/// A number from 32-bit limbs, most significant first (`1` when there are none).
fn from_limbs(limbs: &[u32]) -> BigInt {
    limbs
        .iter()
        .fold(BigInt::from(1u8), |x, &l| (x << 32) + BigInt::from(l))
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(64))]

    /// Values sharing a few reduced denominators, as a policy evaluation's do: `d = K·L` with
    /// `L = 2³·3²·5·7·11·13`, each numerator `K·s·m` for a divisor `s` of `L` (so the value is
    /// `m/(L/s)`, reduced further when `m` shares a factor with `L/s`), with zero, negative,
    /// `d`-coprime and `d`-multiple numerators among them. `reduced_all` must give exactly
    /// `num-rational`'s lowest terms for each, whatever order the shared factors are met in.
    #[test]
    fn batched_reduction_of_shared_denominators_is_num_s_reduction(
        k_limbs in proptest::collection::vec(proptest::prelude::any::<u32>(), 0..6),
        picks in proptest::collection::vec(
            (0usize..12, proptest::collection::vec(proptest::prelude::any::<u32>(), 0..4), 0u8..6),
            1..40,
        ),
    ) {
        use num_rational::BigRational;
        use truecost::algebra::linear::reduced_all;
        let big_l = BigInt::from(8u32 * 9 * 5 * 7 * 11 * 13);
        let divisors = [1u32, 2, 3, 4, 6, 8, 12, 72, 35, 143, 5 * 7 * 11 * 13, 8 * 9 * 5 * 7 * 11 * 13];
        let k = from_limbs(&k_limbs);
        let d = &k * &big_l;
        let numerators: Vec<BigInt> = picks
            .iter()
            .map(|(s, m_limbs, kind)| {
                let m = from_limbs(m_limbs);
                let shared = &k * BigInt::from(divisors[*s]) * &m;
                match kind {
                    0 => BigInt::from(0u8),
                    1 => -shared,
                    2 => &m * BigInt::from(17u8) + BigInt::from(1u8),
                    3 => &d * &m,
                    _ => shared,
                }
            })
            .collect();
        let refs: Vec<&BigInt> = numerators.iter().collect();
        let batched = reduced_all(&refs, &d);
        proptest::prop_assert_eq!(batched.len(), numerators.len());
        for (n, r) in numerators.iter().zip(&batched) {
            let expected = BigRational::new(n.clone(), d.clone());
            proptest::prop_assert_eq!(r.numer(), expected.numer(), "{}/{}", n, d);
            proptest::prop_assert_eq!(r.denom(), expected.denom(), "{}/{}", n, d);
        }
    }
}
