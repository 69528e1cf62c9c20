//! Exact solution of the sparse linear systems of policy evaluation (docs/spec.md §3: the exact
//! optimum), and an `f64` twin for warm starts.
//!
//! A system `A·z = r` has small integer entries (`|A_ij| < 2⁶²`, `|r_i| < 2¹⁰⁰`) and a
//! non-singular `A` whose symmetric permutations all have non-zero leading principal minors
//! (true for `I − P` with `P` the transition matrix of a proper policy restricted to its
//! transient states: every principal submatrix is again `I − P'` with `P'` transient). The
//! exact solver is **Dixon's p-adic lifting**:
//!
//! 1. order the unknowns by reverse Cuthill–McKee (a 20×20 grid becomes a band of width ≈ 20),
//!    and, by nested dissection ([`super::ordering`]), count the entries of a sparse factor
//!    (about `n·log n` on a grid where the band has `n·√n`);
//! 2. factor `A = LU` modulo a prime `p < 2³¹`, inside the band or, when it has fewer entries,
//!    as a sparse `LU` in the nested-dissection order (`sparse_lu.rs`); no pivoting is
//!    needed in either (a zero pivot modulo `p` — probability about `n/p` per pivot — just
//!    moves on to the next prime), and each lifting step is one forward and one back
//!    substitution in that factor;
//! 3. lift: `z_k = A⁻¹ r_k mod p`, `r_{k+1} = (r_k − A z_k)/p` (exact, and `|r_k|` stays below
//!    `Σ|A_ij| + |r_0|/p^k`, so every step is word arithmetic); `Σ z_k p^k ≡ z (mod p^K)`.
//!    From 500 unknowns two primes are lifted at once, one thread each (on every machine, so
//!    the steps are the same everywhere; on one core the threads take turns), for half the steps, and the two expansions combined by
//!    the Chinese remainder theorem into `z mod (p₁p₂)^K` (`linear/lanes.rs`);
//! 4. rational reconstruction with one common denominator `d` (half-way extended Euclid with
//!    Lehmer's acceleration, `linear/reconstruction.rs`), first tried (on three probe
//!    unknowns) geometrically often, then at the step count predicted in `f64` from
//!    `log2 |det A|` (the band LU's pivots) and `max |z|`, then every 2% more steps;
//!    the `p`-adic digits become integers by divide and conquer (`dashu`), and the numerators
//!    `N = d·z` come from a few *seeds* (`d·x mod p^K'` on about half the digits, Barrett
//!    reduction) and exact propagation along rows with a single unknown left (a peel plan from
//!    the sparsity pattern: a `w×h` grid needs about one seed per band level) — with a general
//!    fallback that reconstructs every unknown (a 100×100 grid in seconds, not hours);
//! 5. **verification**: the candidate `z = N/d` is accepted only if `A·N = d·r` holds exactly
//!    in big integers. The answer is therefore exact whatever happened before (every estimate
//!    above only schedules work); lifting goes on (up to the Hadamard bound, after which
//!    reconstruction is guaranteed) until it holds.

mod lanes;
mod reconstruction;
mod residual;

use dashu_base::{BitTest, DivRem, SquareRoot, UnsignedAbs};
use dashu_int::{IBig, UBig};
use num_bigint::BigInt;
use num_traits::{One, Signed, Zero};

use super::ordering::{factor_entries, nested_dissection, Graph, Symbolic};
use super::sparse_lu::{LuPattern, Modulus, SparseModularLu};
use lanes::Lane;
use reconstruction::reconstruct;

/// A square sparse integer system `A·z = r`.
#[derive(Clone, Debug, Default)]
pub struct SparseSystem {
    row_first: Vec<usize>,
    col: Vec<u32>,
    val: Vec<i64>,
    rhs: Vec<i128>,
}

/// Why a system could not be solved.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum LinearError {
    /// The matrix is singular (or has a singular leading principal minor in every ordering
    /// tried), which policy evaluation of a proper policy never produces.
    #[error("the linear system is singular")]
    Singular,
    /// An entry or right-hand side beyond the solver's word-size limits.
    #[error("a coefficient of the linear system is too large for the exact solver")]
    TooLarge,
    /// The band of the reordered matrix would not fit in memory.
    #[error("the linear system ({states} unknowns, band width {width} after reordering) is too large for the exact solver's band storage (at most 2^28 entries)")]
    TooWide {
        /// Unknowns.
        states: usize,
        /// Band width `lower + upper + 1`.
        width: usize,
    },
}

/// The most band entries the solvers allocate (2 GiB of `u64`).
const MAX_BAND_ENTRIES: usize = 1 << 28;

fn check_band(n: usize, ordering: &BandOrdering) -> Result<(), LinearError> {
    let width = ordering.lower + ordering.upper + 1;
    if n.saturating_mul(width) > MAX_BAND_ENTRIES {
        Err(LinearError::TooWide { states: n, width })
    } else {
        Ok(())
    }
}

impl SparseSystem {
    /// An empty system (no rows yet).
    pub fn new() -> Self {
        SparseSystem {
            row_first: vec![0],
            ..Default::default()
        }
    }

    /// Appends a row: its entries `(column, value)` (duplicates are added) and right-hand side.
    ///
    /// ```
    /// use truecost::algebra::linear::SparseSystem;
    /// use truecost::algebra::linear::LinearError;
    /// let mut s = SparseSystem::new();
    /// // Duplicate columns are added: 2x + x = 3.
    /// s.push_row(&[(0, 2), (0, 1)], 3).unwrap();
    /// assert_eq!(s.row(0).collect::<Vec<_>>(), [(0, 3)]);
    /// assert_eq!(s.rhs(0), 3);
    /// assert_eq!(s.push_row(&[(0, 1 << 62)], 0), Err(LinearError::TooLarge));
    /// ```
    pub fn push_row(&mut self, entries: &[(usize, i64)], rhs: i128) -> Result<(), LinearError> {
        let start = self.col.len();
        for &(c, v) in entries {
            if let Some(i) = self.col[start..].iter().position(|&k| k as usize == c) {
                self.val[start + i] = self.val[start + i]
                    .checked_add(v)
                    .filter(|s| s.unsigned_abs() < 1 << 62)
                    .ok_or(LinearError::TooLarge)?;
            } else {
                if v.unsigned_abs() >= 1 << 62 {
                    return Err(LinearError::TooLarge);
                }
                self.col
                    .push(u32::try_from(c).map_err(|_| LinearError::TooLarge)?);
                self.val.push(v);
            }
        }
        if rhs.unsigned_abs() >= 1 << 100 {
            return Err(LinearError::TooLarge);
        }
        self.rhs.push(rhs);
        self.row_first.push(self.col.len());
        Ok(())
    }

    /// The number of rows (= unknowns).
    ///
    /// ```
    /// use truecost::algebra::linear::SparseSystem;
    /// let mut s = SparseSystem::new();
    /// assert!(s.is_empty());
    /// s.push_row(&[(0, 1)], 0).unwrap();
    /// assert_eq!((s.len(), s.is_empty()), (1, false));
    /// ```
    pub fn len(&self) -> usize {
        self.rhs.len()
    }

    /// Whether the system has no rows.
    pub fn is_empty(&self) -> bool {
        self.rhs.is_empty()
    }

    /// The entries `(column, value)` of row `i`.
    pub fn row(&self, i: usize) -> impl Iterator<Item = (usize, i64)> + '_ {
        let r = self.row_first[i]..self.row_first[i + 1];
        self.col[r.clone()]
            .iter()
            .zip(&self.val[r])
            .map(|(&c, &v)| (c as usize, v))
    }

    /// The right-hand side of row `i`.
    pub fn rhs(&self, i: usize) -> i128 {
        self.rhs[i]
    }

    /// Whether `A·N = d·r` holds exactly.
    ///
    /// ```
    /// use truecost::algebra::linear::SparseSystem;
    /// use num_bigint::BigInt;
    /// // 2x = 1: x = 1/2 is N = 1, d = 2 (also N = 3, d = 6); N = 1, d = 3 is not.
    /// let mut s = SparseSystem::new();
    /// s.push_row(&[(0, 2)], 1).unwrap();
    /// assert!(s.satisfied_by(&[BigInt::from(1)], &BigInt::from(2)));
    /// assert!(s.satisfied_by(&[BigInt::from(3)], &BigInt::from(6)));
    /// assert!(!s.satisfied_by(&[BigInt::from(1)], &BigInt::from(3)));
    /// ```
    pub fn satisfied_by(&self, numerators: &[BigInt], denominator: &BigInt) -> bool {
        (0..self.len()).all(|i| {
            let mut lhs = BigInt::zero();
            for (c, v) in self.row(i) {
                lhs += &numerators[c] * v;
            }
            lhs == denominator * BigInt::from(self.rhs[i])
        })
    }
}

/// An exact solution `z_i = numerators[i] / denominator` (`denominator > 0`, a common
/// denominator, not necessarily the least).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ExactSolution {
    /// The numerators.
    pub numerators: Vec<BigInt>,
    /// The common denominator.
    pub denominator: BigInt,
    /// Lifting steps performed (each one solve modulo a prime; with two lanes, both lanes' steps
    /// together).
    pub lifting_steps: usize,
}

/// The symmetric-pattern band ordering shared by the exact and `f64` solvers.
#[derive(Clone, Debug)]
pub struct BandOrdering {
    /// `order[new] = old`.
    order: Vec<usize>,
    /// `position[old] = new`.
    position: Vec<usize>,
    lower: usize,
    upper: usize,
}

impl BandOrdering {
    /// Reverse Cuthill–McKee on the pattern of `A + Aᵀ`, each connected part started from a
    /// pseudo-peripheral node (lowest index among equals, so the ordering is deterministic).
    pub fn new(system: &SparseSystem) -> Self {
        let n = system.len();
        let mut adjacency = vec![Vec::new(); n];
        for i in 0..n {
            for (j, _) in system.row(i) {
                if i != j {
                    adjacency[i].push(j);
                    adjacency[j].push(i);
                }
            }
        }
        for list in &mut adjacency {
            list.sort_unstable();
            list.dedup();
        }
        let degree: Vec<usize> = adjacency.iter().map(Vec::len).collect();
        let mut placed = vec![false; n];
        let mut order = Vec::with_capacity(n);
        let bfs = |start: usize, placed: &[bool]| -> (Vec<usize>, Vec<usize>) {
            // Returns the BFS order and levels restricted to unplaced nodes.
            let mut level = vec![usize::MAX; n];
            let mut seq = vec![start];
            level[start] = 0;
            let mut head = 0;
            while head < seq.len() {
                let v = seq[head];
                head += 1;
                let mut next: Vec<usize> = adjacency[v]
                    .iter()
                    .copied()
                    .filter(|&w| !placed[w] && level[w] == usize::MAX)
                    .collect();
                next.sort_by_key(|&w| (degree[w], w));
                for w in next {
                    level[w] = level[v] + 1;
                    seq.push(w);
                }
            }
            (seq, level)
        };
        for seed in 0..n {
            if placed[seed] {
                continue;
            }
            // Pseudo-peripheral start: the least-degree node of this part, then repeatedly the
            // least-degree node of the last BFS level.
            let (part, _) = bfs(seed, &placed);
            let mut start = part
                .iter()
                .copied()
                .min_by_key(|&v| (degree[v], v))
                .unwrap_or(seed);
            let mut depth = 0;
            for _ in 0..4 {
                let (seq, level) = bfs(start, &placed);
                let far = level[*seq.last().expect("non-empty")];
                if far <= depth {
                    break;
                }
                depth = far;
                start = seq
                    .iter()
                    .copied()
                    .filter(|&v| level[v] == far)
                    .min_by_key(|&v| (degree[v], v))
                    .expect("non-empty level");
            }
            let (seq, _) = bfs(start, &placed);
            for &v in &seq {
                placed[v] = true;
            }
            order.extend(seq);
        }
        order.reverse();
        let mut position = vec![0; n];
        for (new, &old) in order.iter().enumerate() {
            position[old] = new;
        }
        let (mut lower, mut upper) = (0, 0);
        for i in 0..n {
            for (j, _) in system.row(i) {
                let (a, b) = (position[i], position[j]);
                if a > b {
                    lower = lower.max(a - b);
                } else {
                    upper = upper.max(b - a);
                }
            }
        }
        BandOrdering {
            order,
            position,
            lower,
            upper,
        }
    }

    /// `(lower, upper)` bandwidths after reordering.
    ///
    /// ```
    /// use truecost::algebra::linear::{BandOrdering, SparseSystem};
    /// // A path 0 – 1 – 2 – 3 (tridiagonal, each unknown coupled to its neighbours) in a scrambled
    /// // numbering 0, 2, 3, 1: reordered, it is tridiagonal again.
    /// let mut s = SparseSystem::new();
    /// for (i, nbrs) in [(0, vec![2]), (1, vec![3]), (2, vec![0, 3]), (3, vec![2, 1])] {
    ///     let mut row: Vec<(usize, i64)> = vec![(i, 4)];
    ///     row.extend(nbrs.into_iter().map(|j| (j, -1)));
    ///     s.push_row(&row, 1).unwrap();
    /// }
    /// assert_eq!(BandOrdering::new(&s).bandwidths(), (1, 1));
    /// ```
    pub fn bandwidths(&self) -> (usize, usize) {
        (self.lower, self.upper)
    }
}

/// A banded matrix in reordered coordinates: row `i` holds columns `i−lower ..= i+upper`.
#[derive(Clone, Debug)]
struct Band<T> {
    n: usize,
    lower: usize,
    upper: usize,
    data: Vec<T>,
}

impl<T: Copy + Default> Band<T> {
    fn new(
        system: &SparseSystem,
        ordering: &BandOrdering,
        convert: impl Fn(i64) -> T,
        add: impl Fn(T, T) -> T,
    ) -> Self {
        let n = system.len();
        let width = ordering.lower + ordering.upper + 1;
        let mut band = Band {
            n,
            lower: ordering.lower,
            upper: ordering.upper,
            data: vec![T::default(); n * width],
        };
        for i in 0..n {
            for (j, v) in system.row(i) {
                let (a, b) = (ordering.position[i], ordering.position[j]);
                let k = band.index(a, b);
                band.data[k] = add(band.data[k], convert(v));
            }
        }
        band
    }

    #[inline]
    fn index(&self, i: usize, j: usize) -> usize {
        i * (self.lower + self.upper + 1) + (j + self.lower - i)
    }
}

/// `LU` of a band modulo a prime `p < 2³¹` (unit lower `L` stored below the diagonal, pivots'
/// inverses kept separately).
struct ModularLu {
    band: Band<u64>,
    /// `p − entry` for every band entry (`L` below the diagonal, `U` above), as `u32`.
    negated: Vec<u32>,
    inverse_pivot: Vec<u64>,
    p: u64,
}

fn pow_mod(mut b: u64, mut e: u64, p: u64) -> u64 {
    let mut r = 1;
    b %= p;
    while e > 0 {
        if e & 1 == 1 {
            r = r * b % p;
        }
        b = b * b % p;
        e >>= 1;
    }
    r
}

impl ModularLu {
    fn factor(system: &SparseSystem, ordering: &BandOrdering, p: u64) -> Option<Self> {
        let pi = p as i64;
        let mut band = Band::new(
            system,
            ordering,
            |v| v.rem_euclid(pi) as u64,
            |a, b| (a + b) % p,
        );
        let n = band.n;
        let mut inverse_pivot = vec![0; n];
        #[allow(clippy::needless_range_loop)] // k indexes the band and the pivots alike
        for k in 0..n {
            let pivot = band.data[band.index(k, k)];
            if pivot == 0 {
                return None;
            }
            let inv = pow_mod(pivot, p - 2, p);
            inverse_pivot[k] = inv;
            let last_row = (k + band.lower).min(n - 1);
            let last_col = (k + band.upper).min(n - 1);
            for i in k + 1..=last_row {
                let ik = band.index(i, k);
                let a = band.data[ik];
                if a == 0 {
                    continue;
                }
                let l = a * inv % p;
                band.data[ik] = l;
                let ml = p - l;
                let kk = band.index(k, k);
                let ii = band.index(i, k);
                for off in 1..=last_col - k {
                    let u = band.data[kk + off];
                    if u != 0 {
                        let t = ii + off;
                        band.data[t] = (band.data[t] + ml * u) % p;
                    }
                }
            }
        }
        let negated = band.data.iter().map(|&v| ((p - v) % p) as u32).collect();
        Some(ModularLu {
            band: Band {
                data: Vec::new(),
                ..band
            },
            negated,
            inverse_pivot,
            p,
        })
    }

    /// Solves `LU·y = b` in place (reordered coordinates; entries of `y` below `p`).
    fn solve(&self, y: &mut [u64]) {
        let (n, lower, upper) = (self.band.n, self.band.lower, self.band.upper);
        let m = Modulus::new(self.p);
        let width = lower + upper + 1;
        let neg = &self.negated;
        for i in 0..n {
            let first = i.saturating_sub(lower);
            let base = i * width + (first + lower - i);
            let acc = y[i] as u128 + dot(&neg[base..base + (i - first)], &y[first..i]);
            y[i] = m.reduce_wide(acc);
        }
        for i in (0..n).rev() {
            let last = (i + upper).min(n - 1);
            let base = i * width + lower + 1;
            let acc = y[i] as u128 + dot(&neg[base..base + (last - i)], &y[i + 1..=last]);
            y[i] = m.mul(m.reduce_wide(acc), self.inverse_pivot[i]);
        }
    }
}

/// `Σ a_k·b_k` for entries below 2³¹: products below 2⁶², summed four at a time in `u64`
/// (below 2⁶⁴) and only then in `u128`, so the compiler can use 32×32→64 multiplies.
#[inline]
fn dot(a: &[u32], b: &[u64]) -> u128 {
    let mut total = 0u128;
    let (ac, bc) = (a.chunks_exact(4), b.chunks_exact(4));
    let (ar, br) = (ac.remainder(), bc.remainder());
    for (x, y) in ac.zip(bc) {
        let s = x[0] as u64 * (y[0] as u32) as u64
            + x[1] as u64 * (y[1] as u32) as u64
            + x[2] as u64 * (y[2] as u32) as u64
            + x[3] as u64 * (y[3] as u32) as u64;
        total += s as u128;
    }
    for (&x, &y) in ar.iter().zip(br) {
        total += (x as u64 * y) as u128;
    }
    total
}

/// Primes just below 2³¹, in decreasing order (trial division; only a few are ever needed).
fn primes() -> impl Iterator<Item = u64> {
    (1u64 << 20..(1u64 << 31) - 1).rev().filter(|&c| {
        c % 2 == 1
            && (3..)
                .step_by(2)
                .take_while(|d| d * d <= c)
                .all(|d| c % d != 0)
    })
}

/// `t mod m` as the symmetric residue in `(−m/2, m/2]`.
fn symmetric(t: UBig, m: &UBig, half: &UBig) -> IBig {
    if &t > half {
        IBig::from(t) - IBig::from(m.clone())
    } else {
        IBig::from(t)
    }
}

/// The solution lifted so far, `x ≡ A⁻¹·r` modulo a modulus `m` that grows with the lifting:
/// one prime's `p`-adic digits ([`Digits`]), or two primes' combined by the Chinese remainder
/// theorem ([`lanes::Combined`]). Reconstruction ([`attempt`]) reads it only through these.
trait Expansion: Sync {
    /// Readies the conversions for the digits lifted so far.
    fn prepare(&mut self);
    /// The modulus `m` of [`value`](Self::value).
    fn modulus(&self) -> UBig;
    /// `x_j mod m`, in `[0, m)`.
    fn value(&self, j: usize) -> UBig;
    /// The fewest packed rows of digits whose modulus exceeds `2^bits`, when fewer than all
    /// (`None`: all the digits are needed).
    fn prefix_rows(&self, bits: f64) -> Option<usize>;
    /// The modulus of the first `rows` packed rows.
    fn prefix_modulus(&self, rows: usize) -> UBig;
    /// `x_j` modulo [`prefix_modulus`](Self::prefix_modulus)`(rows)`.
    fn prefix(&self, j: usize, rows: usize) -> UBig;
}

/// The lifted digits of one prime `p`: `rows[k][j]` is the `k`-th base-`p²` digit of unknown
/// `j` (two lifting steps packed per `u64`), and the powers `(p²)^(2^i)` for
/// divide-and-conquer conversion.
struct Digits {
    rows: Vec<Vec<u64>>,
    p: u64,
    /// Lifting steps stored (`2·rows.len()` or one less).
    steps: usize,
    powers: Vec<UBig>,
}

impl Digits {
    fn new(p: u64) -> Self {
        Digits {
            rows: Vec::new(),
            p,
            steps: 0,
            powers: Vec::new(),
        }
    }

    /// Stores the digit `y[position[j]]` of every unknown `j` (one lifting step).
    fn push(&mut self, y: &[u64], position: &[usize]) {
        if self.steps.is_multiple_of(2) {
            self.rows.push(position.iter().map(|&new| y[new]).collect());
        } else {
            let p = self.p;
            let last = self.rows.last_mut().expect("pushed at the even step");
            for (d, &new) in last.iter_mut().zip(position) {
                *d += y[new] * p;
            }
        }
        self.steps += 1;
    }

    /// The value of the first `rows` packed digits of unknown `j` (that is, modulo
    /// `p^(2·rows)`), by divide and conquer (quasi-linear, unlike Horner's rule).
    fn column(&self, j: usize, rows: usize) -> UBig {
        let column: Vec<u64> = self.rows[..rows].iter().map(|row| row[j]).collect();
        self.convert(&column)
    }

    fn convert(&self, digits: &[u64]) -> UBig {
        if digits.len() <= 16 {
            let mut acc = UBig::ZERO;
            for &d in digits.iter().rev() {
                acc = acc * (self.p * self.p) + d;
            }
            return acc;
        }
        let level = (usize::BITS - 1 - (digits.len() - 1).leading_zeros()) as usize;
        let h = 1usize << level;
        self.convert(&digits[..h]) + self.convert(&digits[h..]) * &self.powers[level]
    }
}

impl Expansion for Digits {
    /// Makes `powers` long enough for the current number of digits.
    fn prepare(&mut self) {
        if self.powers.is_empty() {
            self.powers.push(UBig::from(self.p * self.p));
        }
        while (1usize << self.powers.len()) < self.rows.len() {
            let last = self.powers.last().expect("non-empty");
            let square = last * last;
            self.powers.push(square);
        }
    }

    /// `p^steps`.
    fn modulus(&self) -> UBig {
        UBig::from(self.p).pow(self.steps)
    }

    fn value(&self, j: usize) -> UBig {
        self.column(j, self.rows.len())
    }

    /// An even number of steps (whole packed digits), fewer than those lifted.
    fn prefix_rows(&self, bits: f64) -> Option<usize> {
        let rows = ((bits / (self.p as f64).log2() / 2.0).ceil() as usize).max(1);
        (2 * rows < self.steps).then_some(rows)
    }

    fn prefix_modulus(&self, rows: usize) -> UBig {
        UBig::from(self.p).pow(2 * rows)
    }

    fn prefix(&self, j: usize, rows: usize) -> UBig {
        self.column(j, rows)
    }
}

/// Converts a `dashu` integer to a `num-bigint` one (linear time).
fn to_num(x: &IBig) -> BigInt {
    let (sign, magnitude) = x.clone().into_parts();
    let magnitude = num_bigint::BigUint::from_bytes_le(&magnitude.to_le_bytes());
    if sign == dashu_base::Sign::Negative {
        -BigInt::from(magnitude)
    } else {
        BigInt::from(magnitude)
    }
}

use super::barrett::Barrett;
pub use super::lowest_terms::{gcd, reduced, reduced_all, SMOOTH_PRIMES_BELOW};

/// How to recover the numerators from a few of them: `seeds` are computed from the digits;
/// then each step `(i, j)` solves row `i` of `A·N = d·r` for `N_j`, all its other unknowns
/// being known by then. Computed from the sparsity pattern alone (greedy: a row with a single
/// unknown is used as soon as there is one; otherwise the next unknown in band order becomes a
/// seed).
struct PeelPlan {
    seeds: Vec<usize>,
    steps: Vec<(usize, usize)>,
}

impl PeelPlan {
    fn new(system: &SparseSystem, ordering: &BandOrdering) -> Self {
        let n = system.len();
        let mut rows_of = vec![Vec::new(); n];
        let mut unknown = vec![0usize; n];
        for (i, count) in unknown.iter_mut().enumerate() {
            for (j, v) in system.row(i) {
                if v != 0 {
                    rows_of[j].push(i);
                    *count += 1;
                }
            }
        }
        let mut known = vec![false; n];
        let mut queue: Vec<usize> = Vec::new();
        let (mut seeds, mut steps) = (Vec::new(), Vec::new());
        let mut learn = |j: usize, known: &mut [bool], queue: &mut Vec<usize>| {
            known[j] = true;
            for &i in &rows_of[j] {
                unknown[i] -= 1;
                if unknown[i] == 1 {
                    queue.push(i);
                }
            }
        };
        let mut next = 0;
        let mut count = 0;
        while count < n {
            if let Some(i) = queue.pop() {
                let Some(j) = system
                    .row(i)
                    .find(|&(j, v)| v != 0 && !known[j])
                    .map(|(j, _)| j)
                else {
                    continue;
                };
                steps.push((i, j));
                learn(j, &mut known, &mut queue);
                count += 1;
            } else {
                while known[ordering.order[next]] {
                    next += 1;
                }
                let j = ordering.order[next];
                seeds.push(j);
                learn(j, &mut known, &mut queue);
                count += 1;
            }
        }
        PeelPlan { seeds, steps }
    }

    /// The numerators from the seeds' values; `None` if a division is not exact (the seeds or
    /// `d` are wrong).
    fn propagate(
        &self,
        system: &SparseSystem,
        seeds: Vec<(usize, IBig)>,
        d: &IBig,
    ) -> Option<Vec<IBig>> {
        let mut value: Vec<Option<IBig>> = vec![None; system.len()];
        for (j, v) in seeds {
            value[j] = Some(v);
        }
        for &(i, j) in &self.steps {
            let mut rest = d * IBig::from(system.rhs[i]);
            let mut coefficient = 0i64;
            for (c, v) in system.row(i) {
                if c == j {
                    coefficient = v;
                } else if v != 0 {
                    rest -= value[c].as_ref().expect("known by the plan") * IBig::from(v);
                }
            }
            let (q, r) = rest.div_rem(IBig::from(coefficient));
            if r != IBig::ZERO {
                return None;
            }
            value[j] = Some(q);
        }
        value.into_iter().collect()
    }
}

/// Unknowns spread evenly whose denominators widen the common denominator when the three first
/// probes' do not give every numerator.
const EXTRA_PROBES: usize = 32;

/// One reconstruction attempt after `steps` lifting steps (`None`: more lifting is needed).
///
/// 1. Rational reconstruction of a few probe unknowns modulo `m = p^steps` gives a candidate
///    common denominator `d`.
/// 2. Fast path: the numerators `N = d·z` need only `p^K' > 2·max|N|` (about half the digits):
///    with `K'` from `d` and the `f64` estimate `log2_max` of `max|z|`, `N_i` is the symmetric
///    residue of `d·x_i mod p^K'`, computed this way only for the seeds of a [`PeelPlan`];
///    every other numerator follows from one equation of `A·N = d·r` by an exact division by
///    a word (a grid needs about one seed per level of the band ordering). Accepted only if
///    `A·N = d·r` holds exactly. If it is not, `d` is widened by [`EXTRA_PROBES`] more probes
///    and the fast path tried once more (the three probes' denominators may all miss a factor
///    that whole classes of states have, as on grids with many ties: there, the general path
///    below took 20 s of a 100×100 solve).
/// 3. Otherwise every numerator modulo `m`, widening `d` by a further reconstruction where a
///    residue is not small, then the fast path with that `d`, else the same exact check.
fn attempt(
    system: &SparseSystem,
    digits: &mut dyn Expansion,
    log2_max: f64,
    plan: &PeelPlan,
) -> Option<(Vec<BigInt>, BigInt)> {
    use rayon::prelude::*;
    let n = system.len();
    digits.prepare();
    let m = digits.modulus();
    let half = &m >> 1usize;
    let bound = half.sqrt();
    let digits = &*digits;
    let mut d = UBig::ONE;
    let residue = |j: usize, d: &UBig| -> UBig { (d * digits.value(j)) % &m };
    let widen = |j: usize, d: &mut UBig| -> Option<()> {
        let t = residue(j, d);
        let small = symmetric(t.clone(), &m, &half).unsigned_abs() <= bound;
        if !small {
            let (_, b) = reconstruct(&t, &m, &bound)?;
            *d *= b;
            if *d > bound {
                return None;
            }
        }
        Some(())
    };
    let mut probes = vec![0, n / 2, n - 1];
    probes.dedup();
    for &j in &probes {
        widen(j, &mut d)?;
    }
    let check = |numerators: &[IBig], d: &UBig| -> bool {
        let d = IBig::from(d.clone());
        (0..n).into_par_iter().all(|i| {
            let mut lhs = IBig::ZERO;
            for (c, v) in system.row(i) {
                lhs += &numerators[c] * IBig::from(v);
            }
            lhs == &d * IBig::from(system.rhs[i])
        })
    };
    let finish = |numerators: Vec<IBig>, d: &UBig| {
        (
            numerators.par_iter().map(to_num).collect(),
            to_num(&IBig::from(d.clone())),
        )
    };
    // 2. Fast path on a prefix of the digits (whole packed digits).
    let fast = |d: &UBig| -> Option<Vec<IBig>> {
        let needed_bits = d.bit_len() as f64 + log2_max.max(0.0) + 16.0;
        if !log2_max.is_finite() {
            return None;
        }
        let rows = digits.prefix_rows(needed_bits)?;
        let m = digits.prefix_modulus(rows);
        let half = &m >> 1usize;
        let barrett = Barrett::new(&m);
        let seeds: Vec<(usize, IBig)> = plan
            .seeds
            .par_iter()
            .map(|&j| {
                let t = barrett.reduce(d * digits.prefix(j, rows));
                (j, symmetric(t, &m, &half))
            })
            .collect();
        let numerators = plan.propagate(system, seeds, &IBig::from(d.clone()))?;
        check(&numerators, d).then_some(numerators)
    };
    if let Some(numerators) = fast(&d) {
        return Some(finish(numerators, &d));
    }
    // 2b. The three probes' denominators may all lack a factor of the common one (on regular
    // grids whole classes of states share one): widen `d` by more probes, spread over the
    // unknowns, and try the fast path again; a probe that cannot be reconstructed yet leaves
    // it to the general path.
    if log2_max.is_finite() {
        let mut wider = d.clone();
        let spread = (1..EXTRA_PROBES).map(|k| k * (n - 1) / EXTRA_PROBES);
        if spread.into_iter().all(|j| widen(j, &mut wider).is_some()) && wider != d {
            if let Some(numerators) = fast(&wider) {
                return Some(finish(numerators, &wider));
            }
        }
    }
    // 3. Every numerator modulo m, widening d where needed.
    let all = |d: &UBig| -> Vec<Option<IBig>> {
        (0..n)
            .into_par_iter()
            .map(|j| {
                let t = symmetric(residue(j, d), &m, &half);
                ((&t).unsigned_abs() <= bound).then_some(t)
            })
            .collect()
    };
    let mut numerators = all(&d);
    let failed: Vec<usize> = (0..n).filter(|&j| numerators[j].is_none()).collect();
    if !failed.is_empty() {
        for &j in &failed {
            widen(j, &mut d)?;
        }
        // The widened `d` may already give every numerator by the fast path.
        if let Some(numerators) = fast(&d) {
            return Some(finish(numerators, &d));
        }
        numerators = all(&d);
    }
    let numerators: Vec<IBig> = numerators.into_iter().collect::<Option<_>>()?;
    check(&numerators, &d).then(|| finish(numerators, &d))
}

/// Bits after which the reconstruction of the exact solution is guaranteed: with `H` the
/// Hadamard bound on `|det A|` (rows of integer norm ≥ 1, so every minor is ≤ `H` too), Cramer's
/// rule gives a common denominator `D ≤ H` and numerators `|N_i| ≤ n·max|r|·H`; the vector
/// reconstruction needs `p^K > 2·max(N, D)²`.
fn hadamard_bits(system: &SparseSystem) -> u64 {
    let mut bits = 0.0f64;
    for i in 0..system.len() {
        let norm2: f64 = system.row(i).map(|(_, v)| (v as f64) * (v as f64)).sum();
        bits += 0.5 * norm2.max(1.0).log2();
    }
    let rhs = system
        .rhs
        .iter()
        .map(|r| r.unsigned_abs() as f64)
        .fold(1.0, f64::max);
    (2.0 * (bits + rhs.log2() + (system.len() as f64 + 1.0).log2()) + 8.0).ceil() as u64
}

/// Progress of an exact solve, reported after every lifting step (for a progress bar).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LiftProgress {
    /// Lifting steps done so far.
    pub steps: usize,
    /// The steps expected (an `f64` estimate of `2·log_p(|det A|·max|z|)`; reconstruction is
    /// first tried there).
    pub expected: usize,
}

/// Solves `A·z = r` exactly (module docs). The result satisfies `A·N = d·r` exactly.
///
/// ```
/// use truecost::algebra::linear::{solve_exact, SparseSystem};
/// use num_bigint::BigInt;
/// // 3x - y = 1, -x + 3y = 2  →  x = 5/8, y = 7/8
/// let mut s = SparseSystem::new();
/// s.push_row(&[(0, 3), (1, -1)], 1).unwrap();
/// s.push_row(&[(0, -1), (1, 3)], 2).unwrap();
/// let z = solve_exact(&s).unwrap();
/// assert_eq!(&z.numerators[0] * BigInt::from(8), &z.denominator * BigInt::from(5));
/// assert_eq!(&z.numerators[1] * BigInt::from(8), &z.denominator * BigInt::from(7));
/// ```
pub fn solve_exact(system: &SparseSystem) -> Result<ExactSolution, LinearError> {
    solve_exact_with(system, &mut |_| {})
}

/// [`solve_exact`], calling `progress` after every lifting step.
///
/// ```
/// use truecost::algebra::linear::{solve_exact_with, SparseSystem};
/// use num_bigint::BigInt;
/// // 2x = 1: x = 1/2 (the progress reports ignored).
/// let mut s = SparseSystem::new();
/// s.push_row(&[(0, 2)], 1).unwrap();
/// let z = solve_exact_with(&s, &mut |_| {}).unwrap();
/// assert_eq!(&z.numerators[0] * BigInt::from(2), z.denominator);
/// ```
pub fn solve_exact_with(
    system: &SparseSystem,
    progress: &mut dyn FnMut(LiftProgress),
) -> Result<ExactSolution, LinearError> {
    solve_exact_general(system, progress, true)
}

fn solve_exact_general(
    system: &SparseSystem,
    progress: &mut dyn FnMut(LiftProgress),
    fast_path: bool,
) -> Result<ExactSolution, LinearError> {
    let solver = Solver {
        fast_path,
        factor: FactorChoice::Cheaper,
        lanes: Lanes::for_system(system),
    };
    solve_exact_factored(system, progress, solver)
}

/// How many primes are lifted at once ([`lanes`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Lanes {
    /// One prime.
    One,
    /// Two primes, one per thread, combined by the Chinese remainder theorem.
    Two,
}

/// Systems with fewer unknowns are lifted with one prime: a step there costs less than
/// starting a thread, and the second factorisation and the combination are not repaid.
const TWO_LANES_FROM: usize = 500;

impl Lanes {
    /// Two lanes for systems of at least [`TWO_LANES_FROM`] unknowns, one otherwise — on any
    /// machine, so that the steps reported are the same everywhere (on one core the two
    /// threads take turns).
    fn for_system(system: &SparseSystem) -> Self {
        if system.len() >= TWO_LANES_FROM {
            Lanes::Two
        } else {
            Lanes::One
        }
    }
}

/// The choices of an exact solve (all but the default ones are for tests).
#[derive(Clone, Copy, Debug)]
struct Solver {
    /// Whether numerators may come from a prefix of the digits and the peel plan.
    fast_path: bool,
    factor: FactorChoice,
    lanes: Lanes,
}

/// Which modular factor the lifting solves with.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum FactorChoice {
    /// The one with the fewer (weighted) entries ([`SPARSE_ENTRY_COST`]).
    Cheaper,
    /// The band, always (tests).
    #[cfg_attr(not(test), allow(dead_code))]
    Band,
    /// The sparse factor, always (tests).
    #[cfg_attr(not(test), allow(dead_code))]
    Sparse,
}

fn solve_exact_factored(
    system: &SparseSystem,
    progress: &mut dyn FnMut(LiftProgress),
    solver: Solver,
) -> Result<ExactSolution, LinearError> {
    let n = system.len();
    if n == 0 {
        return Ok(ExactSolution {
            numerators: Vec::new(),
            denominator: BigInt::one(),
            lifting_steps: 0,
        });
    }
    let ordering = BandOrdering::new(system);
    check_band(n, &ordering)?;
    let max_bits = hadamard_bits(system);
    // Where reconstruction should first succeed: Cramer's rule gives the common denominator
    // |det A| and numerators |det A|·|z_i|; reconstruction needs p^K > 2·max(N, D)². Both are
    // estimated in f64 (a schedule only: every answer is verified exactly).
    let (z, log2_det) = solve_f64_ordered(system, &ordering);
    let log2_max = z.iter().map(|v| v.abs()).fold(1.0f64, f64::max).log2();
    let expected_bits = if log2_det.is_finite() && log2_max.is_finite() {
        (2.0 * (log2_det + log2_max) + 2.0).max(0.0)
    } else {
        max_bits as f64
    };
    let sparse = sparse_pattern(system, &ordering, solver.factor);
    let lanes = match solver.lanes {
        Lanes::One => 1,
        Lanes::Two => 2,
    };
    // Primes whose factorisation has no zero pivot, used `lanes` at a time.
    let mut factors = Vec::with_capacity(lanes);
    for p in primes().take(8) {
        let factor = match &sparse {
            Some(pattern) => SparseModularLu::factor(pattern, |i| system.row(i), Modulus::new(p))
                .map(ModularFactor::Sparse),
            None => ModularLu::factor(system, &ordering, p).map(ModularFactor::Band),
        };
        let Some(lu) = factor else {
            continue;
        };
        factors.push(lu);
        if factors.len() < lanes {
            continue;
        }
        let expected = (expected_bits / (factors[0].p() as f64).log2()).ceil() as usize + 1;
        let schedule = Schedule {
            max_bits,
            expected,
            log2_max,
            fast_path: solver.fast_path,
        };
        let solution = match &factors[..] {
            [lu] => lift(system, &ordering, lu, &schedule, progress)?,
            [a, b] => lanes::lift_two(system, &ordering, [a, b], &schedule, progress)?,
            _ => unreachable!("one or two lanes"),
        };
        if let Some(solution) = solution {
            return Ok(solution);
        }
        factors.clear();
    }
    Err(LinearError::Singular)
}

/// The factor a lifting step solves with modulo `p`.
enum ModularFactor<'a> {
    /// The band `LU` in reverse Cuthill–McKee order.
    Band(ModularLu),
    /// The sparse `LU` in nested-dissection order.
    Sparse(SparseModularLu<'a>),
}

impl ModularFactor<'_> {
    fn p(&self) -> u64 {
        match self {
            ModularFactor::Band(lu) => lu.p,
            ModularFactor::Sparse(lu) => lu.p(),
        }
    }

    /// `(order, position)` of the factor's numbering (`order[new] = old`).
    fn permutation<'s>(&'s self, band: &'s BandOrdering) -> (&'s [usize], &'s [usize]) {
        match self {
            ModularFactor::Band(_) => (&band.order, &band.position),
            ModularFactor::Sparse(lu) => lu.permutation(),
        }
    }

    /// Solves `LU·y = b` in place, in the factor's numbering.
    fn solve(&self, y: &mut [u64]) {
        match self {
            ModularFactor::Band(lu) => lu.solve(y),
            ModularFactor::Sparse(lu) => lu.solve(y),
        }
    }
}

/// A sparse `LU`'s substitution reads a column index per entry where the band's reads
/// consecutive entries: the sparse factor is used when its entries, weighted by this ratio, are
/// fewer than the band's (on the walls 100×100 grid the two have 86,793 and 99,099 entries and
/// a solve took the same processor time within the measurement's noise; on the random one,
/// 410,669 and 2,009,799 — docs/speed.md).
const SPARSE_ENTRY_COST: f64 = 1.5;

/// The pattern of the sparse `LU` in nested-dissection order ([`super::ordering`]) when its
/// substitutions cost less than the band's (the symbolic factorisation is counted first and
/// built only then; it has fewer entries than the band, which is within the memory limit).
fn sparse_pattern(
    system: &SparseSystem,
    band: &BandOrdering,
    choice: FactorChoice,
) -> Option<LuPattern> {
    if choice == FactorChoice::Band {
        return None;
    }
    let n = system.len();
    let graph = Graph::from_entries(
        n,
        (0..n).flat_map(|i| system.row(i).map(move |(j, _)| (i, j))),
    );
    let order = nested_dissection(&graph);
    let sparse = n + 2 * factor_entries(&graph, &order);
    let band_entries = n * (band.lower + band.upper + 1);
    let sparse_cheaper = SPARSE_ENTRY_COST * (sparse as f64) < band_entries as f64;
    (sparse_cheaper || choice == FactorChoice::Sparse)
        .then(|| LuPattern::new(Symbolic::new(&graph, order)))
}

/// When to try reconstruction (all `f64` estimates; answers are verified exactly).
struct Schedule {
    /// The Hadamard bound: reconstruction is guaranteed after this many bits.
    max_bits: u64,
    /// The lifting steps expected from `log2 |det A|`.
    expected: usize,
    /// `log2 max |z_i|`.
    log2_max: f64,
    /// Whether numerators may come from a prefix of the digits and the peel plan (always,
    /// except in the tests of the general path).
    fast_path: bool,
}

impl Schedule {
    /// What [`attempt`] is given for `log2 max |z_i|`: the estimate on the fast path, `NaN`
    /// (no estimate: reconstruct every unknown) otherwise.
    fn estimate(&self) -> f64 {
        if self.fast_path {
            self.log2_max
        } else {
            f64::NAN
        }
    }
}

/// The next reconstruction attempt after one at `done` (in steps, or rows of steps): 1.5 times
/// as far below `expected` (a smaller denominator shows up early), at `expected`, then every
/// 2% more — and at least `gap` later.
fn next_attempt(done: usize, expected: usize, gap: usize) -> usize {
    if done < expected {
        ((done * 3).div_ceil(2)).max(done + gap).min(expected)
    } else {
        done + (done / 50).max(gap)
    }
}

/// Dixon lifting with one prime; `None` if the bound was reached without a verified solution
/// (only possible if `A` is singular).
fn lift(
    system: &SparseSystem,
    ordering: &BandOrdering,
    lu: &ModularFactor,
    schedule: &Schedule,
    progress: &mut dyn FnMut(LiftProgress),
) -> Result<Option<ExactSolution>, LinearError> {
    let bits_per_step = (lu.p() as f64).log2();
    let max_steps = (schedule.max_bits as f64 / bits_per_step).ceil() as usize + 2;
    let expected = schedule.expected.min(max_steps);
    let mut lane = Lane::new(system, ordering, lu);
    let plan = PeelPlan::new(system, ordering);
    let mut next_try = 4usize.min(expected);
    let mut steps = 0usize;
    while steps < max_steps {
        lane.step()?;
        steps += 1;
        progress(LiftProgress { steps, expected });
        if steps == next_try || steps == max_steps {
            next_try = next_attempt(steps, expected, 2);
            if let Some((numerators, denominator)) =
                attempt(system, &mut lane.digits, schedule.estimate(), &plan)
            {
                return Ok(Some(ExactSolution {
                    numerators,
                    denominator,
                    lifting_steps: steps,
                }));
            }
        }
    }
    Ok(None)
}

/// Solves `A·z = r` in `f64` by banded LU without pivoting, in the same ordering (for warm
/// starts only; never reported as a value).
///
/// ```
/// use truecost::algebra::linear::{solve_f64, SparseSystem};
/// // 3x − y = 1, −x + 3y = 2: x = 5/8, y = 7/8 (exact in binary).
/// let mut s = SparseSystem::new();
/// s.push_row(&[(0, 3), (1, -1)], 1).unwrap();
/// s.push_row(&[(0, -1), (1, 3)], 2).unwrap();
/// let z = solve_f64(&s).unwrap();
/// assert!((z[0] - 0.625).abs() < 1e-12 && (z[1] - 0.875).abs() < 1e-12);
/// ```
pub fn solve_f64(system: &SparseSystem) -> Result<Vec<f64>, LinearError> {
    let ordering = BandOrdering::new(system);
    check_band(system.len(), &ordering)?;
    Ok(solve_f64_ordered(system, &ordering).0)
}

/// [`solve_f64`] with a precomputed ordering; also `log2 |det A|` from the pivots.
fn solve_f64_ordered(system: &SparseSystem, ordering: &BandOrdering) -> (Vec<f64>, f64) {
    let factor = FloatFactor::with_ordering(system, ordering.clone());
    let rhs: Vec<f64> = system.rhs.iter().map(|&r| r as f64).collect();
    (factor.solve(&rhs), factor.log2_det)
}

/// The `f64` band LU factor of a system (reverse Cuthill–McKee ordering, no pivoting), kept to
/// solve the same matrix for many right-hand sides (the mixed-precision refinement of
/// `stochastic::refine`). Only ever proposes values; never reported.
#[derive(Clone, Debug)]
pub struct FloatFactor {
    ordering: BandOrdering,
    band: Band<f64>,
    /// `log2 |det A|` from the pivots (an `f64` estimate).
    pub log2_det: f64,
}

impl FloatFactor {
    /// Factors `A` of `system` (its right-hand side is not used).
    pub fn new(system: &SparseSystem) -> Result<Self, LinearError> {
        let ordering = BandOrdering::new(system);
        check_band(system.len(), &ordering)?;
        Ok(Self::with_ordering(system, ordering))
    }

    fn with_ordering(system: &SparseSystem, ordering: BandOrdering) -> Self {
        let mut band = Band::new(system, &ordering, |v| v as f64, |a, b| a + b);
        let n = band.n;
        let mut log2_det = 0.0;
        for k in 0..n {
            let pivot = band.data[band.index(k, k)];
            log2_det += pivot.abs().log2();
            let last_row = (k + band.lower).min(n.saturating_sub(1));
            let last_col = (k + band.upper).min(n.saturating_sub(1));
            for i in k + 1..=last_row {
                let ik = band.index(i, k);
                let l = band.data[ik] / pivot;
                band.data[ik] = l;
                if l == 0.0 {
                    continue;
                }
                let kk = band.index(k, k);
                for off in 1..=last_col - k {
                    let t = ik + off;
                    band.data[t] -= l * band.data[kk + off];
                }
            }
        }
        FloatFactor {
            ordering,
            band,
            log2_det,
        }
    }

    /// `A⁻¹·rhs` in `f64` (`rhs` in the system's numbering).
    ///
    /// ```
    /// use truecost::algebra::linear::{FloatFactor, SparseSystem};
    /// // One factor of [[3, −1], [−1, 3]] (det 8), two right-hand sides: (1, 2) → (5/8, 7/8),
    /// // (2, −2) → (1/2, −1/2).
    /// let mut s = SparseSystem::new();
    /// s.push_row(&[(0, 3), (1, -1)], 0).unwrap();
    /// s.push_row(&[(0, -1), (1, 3)], 0).unwrap();
    /// let f = FloatFactor::new(&s).unwrap();
    /// assert!((f.log2_det - 3.0).abs() < 1e-12);
    /// let close = |a: Vec<f64>, b: [f64; 2]| a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-12);
    /// assert!(close(f.solve(&[1.0, 2.0]), [0.625, 0.875]));
    /// assert!(close(f.solve(&[2.0, -2.0]), [0.5, -0.5]));
    /// ```
    pub fn solve(&self, rhs: &[f64]) -> Vec<f64> {
        let (band, ordering) = (&self.band, &self.ordering);
        let n = band.n;
        let mut y: Vec<f64> = (0..n).map(|new| rhs[ordering.order[new]]).collect();
        for i in 0..n {
            let first = i.saturating_sub(band.lower);
            let mut acc = y[i];
            for (j, yj) in y.iter().enumerate().take(i).skip(first) {
                acc -= band.data[band.index(i, j)] * yj;
            }
            y[i] = acc;
        }
        for i in (0..n).rev() {
            let last = (i + band.upper).min(n.saturating_sub(1));
            let mut acc = y[i];
            for (j, yj) in y.iter().enumerate().take(last + 1).skip(i + 1) {
                acc -= band.data[band.index(i, j)] * yj;
            }
            y[i] = acc / band.data[band.index(i, i)];
        }
        (0..n).map(|old| y[ordering.position[old]]).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// `hadamard_bits` by hand: `2·(Σ ½·log2 max(‖row‖², 1) + log2 max(max|r|, 1) +
    /// log2(n + 1)) + 8`, rounded up. The identity of size 2 with right-hand sides 1:
    /// `2·log2 3 + 8 = 11.17` gives 12; rows `(3, 4)` and `(0, 1)` with right-hand sides 8
    /// and −2: `2·(log2 5 + 0 + 3 + log2 3) + 8 = 2·6.91 + 8 = 21.81` gives 22.
    #[test]
    fn hadamard_bits_by_hand() {
        let mut s = SparseSystem::new();
        s.push_row(&[(0, 1)], 1).unwrap();
        s.push_row(&[(1, 1)], 1).unwrap();
        assert_eq!(hadamard_bits(&s), 12);
        let mut s = SparseSystem::new();
        s.push_row(&[(0, 3), (1, 4)], 8).unwrap();
        s.push_row(&[(1, 1)], -2).unwrap();
        assert_eq!(hadamard_bits(&s), 22);
    }

    /// The symmetric residue of `t` modulo an odd `m` is in `(−m/2, m/2]`: with `m = 7` and
    /// `half = 7 >> 1 = 3`, the residues 0..=3 stay, 4..=6 become −3..=−1 (3 stays 3: at
    /// `t = half` the residue is `half`, not `half − m = −4`, which is outside the range).
    #[test]
    fn symmetric_residues_by_hand() {
        let m = UBig::from(7u8);
        let half = &m >> 1usize;
        let got: Vec<IBig> = (0u8..7)
            .map(|t| symmetric(UBig::from(t), &m, &half))
            .collect();
        let want: Vec<IBig> = [0, 1, 2, 3, -3, -2, -1]
            .into_iter()
            .map(IBig::from)
            .collect();
        assert_eq!(got, want);
    }

    /// Rational reconstruction at its bound, by hand: modulo 101 with bound 3, `3/2 ≡ 3·51 = 153
    /// ≡ 52` and `−3/2 ≡ 49`; Euclid's remainders of (101, 52) are 52, 49, 3 with cofactors
    /// 1, −1, 2, so the search stops at the remainder 3 = the bound (`|a| ≤ bound` allows it).
    /// 7 has none: `a ≡ 7·b` is 7, 14 or 21 for `b ≤ 3`, none of them within ±3.
    #[test]
    fn reconstruction_accepts_a_numerator_at_the_bound() {
        let (m, bound) = (UBig::from(101u8), UBig::from(3u8));
        let got = |t: u8| reconstruct(&UBig::from(t), &m, &bound);
        assert_eq!(got(52), Some((IBig::from(3), UBig::from(2u8))));
        assert_eq!(got(49), Some((IBig::from(-3), UBig::from(2u8))));
        assert_eq!(got(3), Some((IBig::from(3), UBig::ONE)));
        assert_eq!(got(7), None);
    }

    /// A random sparse system shaped like policy evaluation: `s·z_i − Σ w·z_j = r_i` with
    /// `Σ w < s` on random neighbours.
    fn random_system(n: usize, seed: u64) -> SparseSystem {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let mut s = SparseSystem::new();
        for i in 0..n {
            let diag = 50 + (rng.next_u32() % 400) as i64;
            let mut entries = vec![(i, diag)];
            let mut budget = diag - 1;
            for _ in 0..4 {
                let j = (rng.next_u32() as usize) % n;
                let w = 1 + (rng.next_u32() as i64) % (budget / 4).max(1);
                if budget - w < 0 {
                    break;
                }
                budget -= w;
                entries.push((j, -w));
            }
            let rhs = (rng.next_u32() % 1000) as i128 - 300;
            s.push_row(&entries, rhs).unwrap();
        }
        s
    }

    #[test]
    fn fast_and_general_paths_give_the_same_verified_solution() {
        for (n, seed) in [(1, 0), (7, 1), (40, 2), (150, 3)] {
            let system = random_system(n, seed);
            let fast = solve_exact(&system).unwrap();
            let general = solve_exact_general(&system, &mut |_| {}, false).unwrap();
            assert!(system.satisfied_by(&fast.numerators, &fast.denominator));
            assert!(system.satisfied_by(&general.numerators, &general.denominator));
            // The same rationals: N_f/d_f = N_g/d_g.
            for (a, b) in fast.numerators.iter().zip(&general.numerators) {
                assert_eq!(a * &general.denominator, b * &fast.denominator, "n = {n}");
            }
        }
    }

    /// `A⁻¹·r` by Gaussian elimination over the rationals with row pivoting (`num`'s
    /// `BigRational`, independent of the modular solvers).
    fn rational_solve(system: &SparseSystem) -> Vec<num_rational::BigRational> {
        use num_rational::BigRational;
        let n = system.len();
        let mut a: Vec<Vec<BigRational>> = (0..n)
            .map(|i| {
                let mut row = vec![BigRational::zero(); n + 1];
                for (j, v) in system.row(i) {
                    row[j] += BigRational::from_integer(v.into());
                }
                row[n] = BigRational::from_integer(system.rhs(i).into());
                row
            })
            .collect();
        for k in 0..n {
            let r = (k..n).find(|&r| !a[r][k].is_zero()).expect("non-singular");
            a.swap(k, r);
            let pivot_row = a[k].clone();
            for (i, row) in a.iter_mut().enumerate() {
                if i != k && !row[k].is_zero() {
                    let f = &row[k] / &pivot_row[k];
                    for (x, y) in row[k..].iter_mut().zip(&pivot_row[k..]) {
                        *x -= &f * y;
                    }
                }
            }
        }
        (0..n).map(|i| &a[i][n] / &a[i][i]).collect()
    }

    /// Both modular factors, and the choice between them, with one prime or two lanes
    /// ([`lanes`]) and on the fast and the general path, give the values of Gaussian
    /// elimination over the rationals on random systems shaped like policy evaluation.
    #[test]
    fn band_and_sparse_factors_give_the_rational_solution() {
        use num_rational::BigRational;
        for (n, seed) in [(1, 0), (2, 5), (9, 7), (40, 2), (120, 3)] {
            let system = random_system(n, seed);
            let want = rational_solve(&system);
            for factor in [
                FactorChoice::Band,
                FactorChoice::Sparse,
                FactorChoice::Cheaper,
            ] {
                for (lanes, fast_path) in
                    [(Lanes::One, true), (Lanes::Two, true), (Lanes::Two, false)]
                {
                    let solver = Solver {
                        fast_path,
                        factor,
                        lanes,
                    };
                    let mut reports = 0;
                    let z = solve_exact_factored(&system, &mut |_| reports += 1, solver).unwrap();
                    let got: Vec<BigRational> = z
                        .numerators
                        .iter()
                        .map(|v| BigRational::new(v.clone(), z.denominator.clone()))
                        .collect();
                    assert_eq!(got, want, "n = {n}, {solver:?}");
                    // One progress report per solve modulo a prime; two lanes solve in whole
                    // rows of two steps each.
                    assert_eq!(reports, z.lifting_steps, "{solver:?}");
                    if lanes == Lanes::Two {
                        assert!(z.lifting_steps.is_multiple_of(4), "{solver:?}");
                    }
                }
            }
        }
    }

    /// A leading principal minor divisible by the first prime: `[[p, 1], [1, 1]]·z = (3, 1)`
    /// with `p` the first prime tried (minors `p` and `p − 1`, non-zero over the integers;
    /// `z = (2/(p − 1), (p − 3)/(p − 1))` by hand). Nested dissection keeps the order 0, 1 of
    /// two unknowns, so the sparse factor meets the pivot `p ≡ 0` and must move on to the next
    /// prime; the band solver meets it if its ordering puts unknown 0 first (otherwise its
    /// pivots are 1 and `p − 1`). Both return the exact answer.
    #[test]
    fn a_pivot_that_vanishes_modulo_the_first_prime_moves_on_to_the_next() {
        use num_rational::BigRational;
        let p = primes().next().unwrap();
        let mut system = SparseSystem::new();
        system.push_row(&[(0, p as i64), (1, 1)], 3).unwrap();
        system.push_row(&[(0, 1), (1, 1)], 1).unwrap();
        // The sparse factor in the order 0, 1 fails modulo p and factors modulo the next prime.
        let graph = Graph::from_entries(2, [(0, 1)]);
        let pattern = LuPattern::new(Symbolic::new(&graph, vec![0, 1]));
        assert!(SparseModularLu::factor(&pattern, |i| system.row(i), Modulus::new(p)).is_none());
        let q = primes().nth(1).unwrap();
        assert!(SparseModularLu::factor(&pattern, |i| system.row(i), Modulus::new(q)).is_some());
        assert_eq!(nested_dissection(&graph), [0, 1]);
        let want = [
            BigRational::new(2.into(), (p - 1).into()),
            BigRational::new((p - 3).into(), (p - 1).into()),
        ];
        // With two lanes the sparse factor lifts modulo the second and the third primes.
        for factor in [FactorChoice::Band, FactorChoice::Sparse] {
            for lanes in [Lanes::One, Lanes::Two] {
                let solver = Solver {
                    fast_path: true,
                    factor,
                    lanes,
                };
                let z = solve_exact_factored(&system, &mut |_| {}, solver).unwrap();
                for (v, w) in z.numerators.iter().zip(&want) {
                    assert_eq!(
                        &BigRational::new(v.clone(), z.denominator.clone()),
                        w,
                        "{solver:?}"
                    );
                }
            }
        }
    }

    /// `solve_f64` (warm starts and schedules only) against the system's own rows and against
    /// the exact solve (the band LU's update and substitution mutants survived otherwise).
    #[test]
    fn the_f64_solve_has_a_small_residual_and_agrees_with_the_exact_solve() {
        use num_traits::ToPrimitive;
        for (n, seed) in [(1, 0), (2, 5), (7, 1), (40, 2), (150, 3)] {
            let system = random_system(n, seed);
            let z = solve_f64(&system).unwrap();
            assert_eq!(z.len(), n);
            // The residual, from the rows as pushed (not from the solver's band).
            for i in 0..n {
                let lhs: f64 = system.row(i).map(|(j, v)| v as f64 * z[j]).sum();
                let scale: f64 = system.row(i).map(|(j, v)| (v as f64 * z[j]).abs()).sum();
                let r = system.rhs[i] as f64;
                assert!(
                    (lhs - r).abs() <= 1e-9 * (scale + r.abs() + 1.0),
                    "n = {n}, row {i}: {lhs} against {r}"
                );
            }
            // And the exact solution, rounded.
            let exact = solve_exact(&system).unwrap();
            for (i, numerator) in exact.numerators.iter().enumerate() {
                let want = reduced(numerator, &exact.denominator).to_f64().unwrap();
                assert!(
                    (z[i] - want).abs() <= 1e-9 * want.abs().max(1.0),
                    "n = {n}, z[{i}] = {} against {want}",
                    z[i]
                );
            }
        }
    }

    #[test]
    fn the_peel_plan_recovers_every_numerator_from_its_seeds() {
        // A 6×6 grid pattern: seeds about one per band level, not one per unknown.
        let side = 6;
        let mut system = SparseSystem::new();
        for i in 0..side * side {
            let (r, c) = (i / side, i % side);
            let mut e = vec![(i, 10)];
            for (dr, dc) in [(-1i64, 0i64), (0, -1), (0, 1), (1, 0)] {
                let (rr, cc) = (r as i64 + dr, c as i64 + dc);
                if (0..side as i64).contains(&rr) && (0..side as i64).contains(&cc) {
                    e.push(((rr * side as i64 + cc) as usize, -2));
                }
            }
            system.push_row(&e, 1 + (i % 3) as i128).unwrap();
        }
        let ordering = BandOrdering::new(&system);
        let plan = PeelPlan::new(&system, &ordering);
        assert!(
            plan.seeds.len() < side * side / 2,
            "{} seeds",
            plan.seeds.len()
        );
        assert_eq!(plan.seeds.len() + plan.steps.len(), side * side);
        let exact = solve_exact(&system).unwrap();
        let to_ibig = |x: &BigInt| IBig::from_le_bytes(&x.to_signed_bytes_le());
        let seeds = plan
            .seeds
            .iter()
            .map(|&j| (j, to_ibig(&exact.numerators[j])))
            .collect();
        let d = to_ibig(&exact.denominator);
        let got = plan.propagate(&system, seeds, &d).unwrap();
        let want: Vec<IBig> = exact.numerators.iter().map(to_ibig).collect();
        assert_eq!(got, want);
        // A wrong seed is caught by an inexact division (or, failing that, the final check).
        let mut bad: Vec<(usize, IBig)> = plan
            .seeds
            .iter()
            .map(|&j| (j, to_ibig(&exact.numerators[j])))
            .collect();
        bad[0].1 += IBig::ONE;
        match plan.propagate(&system, bad, &d) {
            None => {}
            Some(v) => assert!(!system.satisfied_by(
                &v.iter().map(to_num).collect::<Vec<_>>(),
                &exact.denominator
            )),
        }
    }
}
