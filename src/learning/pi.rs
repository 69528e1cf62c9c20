//! The base-4 digits of π, computed with exact big-integer arithmetic (docs/spec.md §2: the universal
//! plan reads them; no digits file is shipped).
//!
//! π = 3.0210 0333 1222 2020 … in base 4: each hexadecimal digit of π (3.243F6A88…) is two
//! base-4 digits (checked by the test `first_base4_digits_are_0210`).
//!
//! Method: the Chudnovsky series by binary splitting (both halves, and then their products,
//! in parallel; in ranges of up to 4096 terms the common factors of `P` and `Q` are divided out,
//! found from prime factorisations by a sieve; the last merge multiplies operands cut to the
//! precision needed, with a proven bound on the error), one division of `Q` by `T` side by side
//! with an integer square root, and one product, all on big integers (`malachite-nz`, whose FFT
//! multiplication makes the 10^7-digit period a matter of seconds). The result is an
//! integer `a` with `|π·2^B − a| ≤ 4`; digits are returned only when both ends of that
//! enclosure agree on them, otherwise the precision is raised, so every digit returned is
//! proven. Digits are cached in the process and, for long prefixes, on disk (see
//! [`cache_dir`]); a cache file is used only if its checksum and its first 64 digits verify.

use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex, OnceLock};

use malachite_base::num::arithmetic::traits::{DivExact, FloorSqrt, ModPowerOf2, UnsignedAbs};
use malachite_base::num::basic::traits::{One, Zero};
use malachite_base::num::logic::traits::SignificantBits;
use malachite_nz::integer::Integer;
use malachite_nz::natural::Natural;

mod factors;
use factors::{Factors, Sieve};

/// Hexadecimal digits of π after the point (public knowledge), for self-checks.
pub const PI_HEX_FRACTION: &str =
    "243F6A8885A308D313198A2E03707344A4093822299F31D0082EFA98EC4E6C89";

/// The first `count` base-4 digits of π after the point.
///
/// ```
/// let d = truecost::learning::pi::fractional_base4_digits(16);
/// assert_eq!(d, vec![0, 2, 1, 0, 0, 3, 3, 3, 1, 2, 2, 2, 2, 0, 2, 0]); // 0x243F6A88
/// ```
pub fn fractional_base4_digits(count: usize) -> Vec<u8> {
    digits(count)[..count].to_vec()
}

/// A shared, cached prefix of at least `count` base-4 digits of π after the point (it may be
/// longer). Cheap to call repeatedly.
pub fn digits(count: usize) -> Arc<Vec<u8>> {
    static CACHE: OnceLock<Mutex<Arc<Vec<u8>>>> = OnceLock::new();
    let cache = CACHE.get_or_init(|| Mutex::new(Arc::new(Vec::new())));
    let mut held = cache.lock().unwrap_or_else(|e| e.into_inner());
    if held.len() < count {
        // Grow geometrically so that callers asking in chunks do not recompute often.
        let want = count.max(2 * held.len()).max(1 << 12);
        *held = Arc::new(load_or_compute(want, cache_dir()));
    }
    Arc::clone(&held)
}

/// Where long digit prefixes are cached: `$TRUECOST_CACHE_DIR`, else `$XDG_CACHE_HOME/truecost`,
/// else `$HOME/.cache/truecost`; `None` if none is set. Cache failures only cost time.
pub fn cache_dir() -> Option<PathBuf> {
    if let Some(d) = std::env::var_os("TRUECOST_CACHE_DIR") {
        return Some(PathBuf::from(d));
    }
    if let Some(d) = std::env::var_os("XDG_CACHE_HOME") {
        return Some(PathBuf::from(d).join("truecost"));
    }
    std::env::var_os("HOME").map(|h| PathBuf::from(h).join(".cache").join("truecost"))
}

/// Prefixes at least this long are cached on disk.
const DISK_CACHE_MIN: usize = 1 << 20;

/// `count` digits, read from (and after computing, written to) the cache folder `dir` when
/// `count` is at least [`DISK_CACHE_MIN`].
fn load_or_compute(count: usize, dir: Option<PathBuf>) -> Vec<u8> {
    let dir = dir.filter(|_| count >= DISK_CACHE_MIN);
    if let Some(found) = dir.as_deref().and_then(|d| load_cached(d, count)) {
        return found;
    }
    let digits = compute(count);
    if let Some(d) = &dir {
        store_cached(d, &digits);
    }
    digits
}

/// Computes `count` digits exactly (see the module documentation).
pub fn compute(count: usize) -> Vec<u8> {
    let mut guard = 64usize;
    loop {
        let bits = 2 * count + guard;
        let approx = pi_scaled(bits);
        let lo = (&approx - Natural::from(4u8)) >> guard;
        let hi = (&approx + Natural::from(4u8)) >> guard;
        if lo == hi {
            return base4_fraction(&lo, count);
        }
        guard *= 2;
    }
}

/// The fractional base-4 digits of `v = ⌊π·4^count⌋` (whose integer part is 3).
fn base4_fraction(v: &Natural, count: usize) -> Vec<u8> {
    let limbs = v.to_limbs_asc();
    (0..count)
        .map(|k| {
            let pair = count - 1 - k; // position of digit k counted from the least significant
            let limb = limbs.get(pair / 32).copied().unwrap_or(0);
            ((limb >> (2 * (pair % 32))) & 3) as u8
        })
        .collect()
}

/// An integer within 4 of `π·2^bits`: `π = 426880·√10005·Q/T` (Chudnovsky).
///
/// `Q/T` comes cut to `bits + 80` bits ([`series_ratio`]); then `u = ⌊Q'·2^(bits+32)/T'⌋` and
/// `r = ⌊√10005·2^bits⌋` are computed side by side, and the result is
/// `⌊426880·r·u / 2^(bits+32)⌋`. Error: `r` loses < 1, scaled by `426880·Q/T ≈ 0.0314`; `u`
/// loses < 1, scaled by `426880·√10005/2^32 < 0.01`; the ratio's cut (relative `2^−(bits+74)`)
/// moves a result below `4·2^bits` by less than `2^−72`; the tail of the series beyond `terms`
/// is below `2^−bits`; the last floor loses < 1. Total < 2 ≤ 4.
fn pi_scaled(bits: usize) -> Natural {
    // Each term adds log2(151931373056000) ≈ 47.11 bits; two spare terms bound the tail far
    // below one unit.
    let terms = (bits as u64) / 47 + 2;
    let bits = bits as u64;
    let (q, t) = series_ratio(terms, bits + 80);
    // The division runs on one core: the square root takes the other.
    let (u, root) = rayon::join(
        || q.shifted(bits + 32) / t.shifted(0),
        || (Natural::from(10005u32) << (2 * bits)).floor_sqrt(),
    );
    // root·u as two half products side by side.
    let h = u.significant_bits() / 2;
    let low = (&u).mod_power_of_2(h);
    let (high, low) = rayon::join(|| &root * (u >> h), || &root * low);
    (Natural::from(426880u32) * ((high << h) + low)) >> (bits + 32)
}

/// A positive number `m·2^e` held as mantissa and exponent.
struct Scaled {
    m: Natural,
    e: u64,
}

impl Scaled {
    /// `m·2^(e + by)` as an integer.
    fn shifted(&self, by: u64) -> Natural {
        &self.m << (self.e + by)
    }
}

/// `x` cut to its `keep` most significant bits: `(x', e)` with `x'·2^e ∈ (x − 2^e, x]`
/// (`>>` on an `Integer` rounds toward −∞), so `|x'·2^e − x| < 2^(1−keep)·|x|`.
fn top(x: &Integer, keep: u64) -> (Integer, u64) {
    let e = x.significant_bits().saturating_sub(keep);
    (x >> e, e)
}

/// `a·2^ea + b·2^eb` exactly, as `(s, e)` with `s·2^e` equal to it and `e = min(ea, eb)`.
fn add_scaled(a: Integer, ea: u64, b: Integer, eb: u64) -> (Integer, u64) {
    let e = ea.min(eb);
    ((a << (ea - e)) + (b << (eb - e)), e)
}

/// `Q(0, terms)` and `T(0, terms)` of the series, each as `m·2^e` with `m` at most `k` bits,
/// such that `Q'/T' = (Q/T)·(1 + ε)`, `|ε| < 2^(6−k)`; the common power of two is removed
/// from both exponents (the smaller one is 0).
///
/// The two halves are split exactly; the last merge, `Q = Q_L·Q_R` and
/// `T = Q_R·T_L + P_L·T_R`, multiplies operands cut to `k` bits ([`top`]), since Q and T
/// carry about 105 bits a term where the ratio needs 47, and cuts `P_L·T_R`, smaller than
/// `Q_R·T_L` by a factor `2^d` (about 47 bits a term of the right half), to `k − d` bits.
/// With `δ = 2^(1−k)`: each cut product is within `3δ` of its value (relative); their sum,
/// aligned by left shifts only, within `6δ·|Q_R·T_L| ≤ 12δ·|T|` (as `|T| ≥ |Q_R·T_L|/2` when
/// `d ≥ 2`, which the series always has: `d ≈ 47·(terms − m) ≥ 43`); cutting both results to `k`
/// bits again adds `δ` each; so `|ε| < (1 + 4.01δ)/(1 − 13.01δ) − 1 < 18δ < 2^(6−k)`.
fn series_ratio(terms: u64, k: u64) -> (Scaled, Scaled) {
    let m = terms / 2;
    let sieve = Sieve::new(6 * terms);
    let (left, right) = rayon::join(
        || binary_split(&sieve, 0, m, true),
        || binary_split(&sieve, m, terms, false),
    );
    // log2|Q_R·T_L| ≥ b(Q_R) + b(T_L) − 2 and log2|P_L·T_R| < b(P_L) + b(T_R).
    let d = (right.q.significant_bits() + left.t.significant_bits())
        .saturating_sub(2 + left.p.significant_bits() + right.t.significant_bits());
    assert!(d >= 2, "π series: P_L·T_R is not below Q_R·T_L (d = {d})");
    let k2 = k.saturating_sub(d).max(64);
    let cut_product = |x: &Integer, y: &Integer, keep: u64| {
        let ((x, ex), (y, ey)) = (top(x, keep), top(y, keep));
        (x * y, ex + ey)
    };
    let ((q, eq), ((a, ea), (b, eb))) = rayon::join(
        || cut_product(&left.q, &right.q, k),
        || {
            rayon::join(
                || cut_product(&right.q, &left.t, k),
                || cut_product(&left.p, &right.t, k2),
            )
        },
    );
    let (t, et) = add_scaled(a, ea, b, eb);
    let ((q, cq), (t, ct)) = (top(&q, k), top(&t, k));
    let (eq, et) = (eq + cq, et + ct);
    let low = eq.min(et);
    (
        Scaled {
            m: q.unsigned_abs(),
            e: eq - low,
        },
        Scaled {
            m: t.unsigned_abs(),
            e: et - low,
        },
    )
}

struct Split {
    p: Integer,
    q: Integer,
    t: Integer,
    /// The factorisations of `|P|` and `Q`, kept only for ranges of at most
    /// [`COMMON_FACTOR_TERMS`] terms (empty above).
    fp: Factors,
    fq: Factors,
}

/// Binary splitting of the Chudnovsky series over terms `[a, b)`:
/// `P = P_L·P_R`, `Q = Q_L·Q_R`, `T = Q_R·T_L + P_L·T_R`. `need_p`: whether the caller uses
/// `P` (only left halves do), which saves the largest products.
///
/// In ranges of at most [`COMMON_FACTOR_TERMS`] terms, `g = gcd(P_L, Q_R)` (from the factor
/// lists, `sieve`) is first divided out of `P_L` and `Q_R`. Then `g` divides `T` too, and the
/// merge gives `P/g`, `Q/g`, `T/g`: every ratio the series reads (`P/Q`, `T/Q`) is unchanged,
/// and the numbers are about a third smaller.
fn binary_split(sieve: &Sieve, a: u64, b: u64, need_p: bool) -> Split {
    let factored = b - a <= COMMON_FACTOR_TERMS;
    if b - a == 1 {
        return leaf(sieve, a, factored);
    }
    let m = (a + b) / 2;
    let parallel = b - a > PARALLEL_TERMS;
    let (mut left, mut right) = if parallel {
        rayon::join(
            || binary_split(sieve, a, m, true),
            || binary_split(sieve, m, b, need_p),
        )
    } else {
        (
            binary_split(sieve, a, m, true),
            binary_split(sieve, m, b, need_p),
        )
    };
    let (mut fp, mut fq) = (Factors::default(), Factors::default());
    if factored {
        let g = left.fp.gcd(&right.fq);
        if !g.is_one() {
            let v = Integer::from(g.value());
            left.p = (&left.p).div_exact(&v);
            right.q = (&right.q).div_exact(&v);
            left.fp = left.fp.over(&g);
            right.fq = right.fq.over(&g);
        }
        fq = left.fq.times(&right.fq);
        if need_p {
            fp = left.fp.times(&right.fp);
        }
    }
    let p = || {
        if need_p {
            &left.p * &right.p
        } else {
            Integer::ZERO
        }
    };
    if !parallel {
        return Split {
            p: p(),
            q: &left.q * &right.q,
            t: &right.q * &left.t + &left.p * &right.t,
            fp,
            fq,
        };
    }
    // Large ranges: the (up to) four products side by side, so that the top of the tree, where
    // few ranges are left, keeps both cores busy too.
    let ((p, q), (qt, pt)) = rayon::join(
        || rayon::join(p, || &left.q * &right.q),
        || rayon::join(|| &right.q * &left.t, || &left.p * &right.t),
    );
    Split {
        p,
        q,
        t: qt + pt,
        fp,
        fq,
    }
}

/// The term `a` alone: `P = p(a)`, `Q = q(a)`, `T = ±p(a)·(13591409 + 545140134a)` (and
/// `P = Q = 1` for `a = 0`), with their factorisations when `factored`.
fn leaf(sieve: &Sieve, a: u64, factored: bool) -> Split {
    if a == 0 {
        return Split {
            p: Integer::ONE,
            q: Integer::ONE,
            t: Integer::from(13591409u64),
            fp: Factors::default(),
            fq: Factors::default(),
        };
    }
    // (6a−5)(2a−1)(6a−1) < 72a³ fits in u128 for every a this module can be asked for.
    let p = Integer::from(u128::from(6 * a - 5) * u128::from(2 * a - 1) * u128::from(6 * a - 1));
    let q = Integer::from(u128::from(a) * u128::from(a) * u128::from(a))
        * Integer::from(10939058860032000u64);
    let t = &p * Integer::from(13591409u128 + 545140134u128 * u128::from(a));
    let t = if a % 2 == 1 { -t } else { t };
    let (fp, fq) = if factored {
        (
            sieve
                .factor(6 * a - 5, 1)
                .times(&sieve.factor(2 * a - 1, 1))
                .times(&sieve.factor(6 * a - 1, 1)),
            Factors::q_constant().times(&sieve.factor(a, 3)),
        )
    } else {
        (Factors::default(), Factors::default())
    };
    Split { p, q, t, fp, fq }
}

/// Ranges of more terms than this are split in parallel (rayon tasks); smaller ones
/// sequentially, where a task would cost more than it saves.
const PARALLEL_TERMS: u64 = 4096;

/// Common factors are removed in ranges of at most this many terms. Higher up, the exact
/// divisions by `g` cost more than the smaller products save (measured: docs/speed.md).
const COMMON_FACTOR_TERMS: u64 = 4096;

fn cache_file(dir: &Path, count: usize) -> PathBuf {
    dir.join(format!("pi-base4-{count}.bin"))
}

/// FNV-1a over the digits: detects a damaged cache file.
fn checksum(digits: &[u8]) -> u64 {
    digits.iter().fold(0xcbf29ce484222325u64, |h, &d| {
        (h ^ u64::from(d)).wrapping_mul(0x100000001b3)
    })
}

/// The digits of [`PI_HEX_FRACTION`] in base 4.
pub fn known_prefix() -> Vec<u8> {
    PI_HEX_FRACTION
        .chars()
        .flat_map(|c| {
            let v = c.to_digit(16).expect("hex") as u8;
            [v >> 2, v & 3]
        })
        .collect()
}

/// The `count` digits cached in `dir`, if its file is there and verifies: its length, every
/// digit below 4, the checksum in its first 8 bytes, and the known prefix.
fn load_cached(dir: &Path, count: usize) -> Option<Vec<u8>> {
    // Only a regular file (a FIFO would block), and never more than the file's exact size.
    let path = cache_file(dir, count);
    if !std::fs::metadata(&path).ok()?.is_file() {
        return None;
    }
    let bytes = crate::bounded::read_bytes(&path, 8 + count as u64, "the digit cache").ok()?;
    let (head, body) = bytes.split_at_checked(8)?;
    let digits: Vec<u8> = body.to_vec();
    let expected = u64::from_le_bytes(head.try_into().ok()?);
    let known = known_prefix();
    (digits.len() == count
        && digits.iter().all(|&d| d < 4)
        && checksum(&digits) == expected
        && digits[..known.len().min(count)] == known[..known.len().min(count)])
        .then_some(digits)
}

/// Writes `digits` with their checksum into `dir` (created if missing), through a temporary
/// file and a rename so that a reader never sees a partial file. Failures only cost time.
fn store_cached(dir: &Path, digits: &[u8]) {
    let path = cache_file(dir, digits.len());
    let _ = std::fs::create_dir_all(dir);
    let mut bytes = checksum(digits).to_le_bytes().to_vec();
    bytes.extend_from_slice(digits);
    let tmp = path.with_extension(format!("tmp{}", std::process::id()));
    if std::fs::write(&tmp, &bytes).is_ok() {
        let _ = std::fs::rename(&tmp, &path);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use malachite_base::num::arithmetic::traits::Pow;

    #[test]
    fn first_digits_are_the_hex_digits_of_pi() {
        let known = known_prefix();
        assert_eq!(compute(known.len()), known);
        assert_eq!(&known[..8], &[0, 2, 1, 0, 0, 3, 3, 3]);
    }

    #[test]
    fn prefixes_agree_across_precisions() {
        let long = compute(20_000);
        for n in [1, 2, 3, 31, 32, 33, 1000, 4097] {
            assert_eq!(compute(n), long[..n], "n = {n}");
        }
    }

    /// `⌊426880·⌊√10005·2^bits⌋·Q/T⌋` with `Q` and `T` exact: the formula with no cut, which
    /// is within `1.04` below `π·2^bits`, as `pi_scaled` is within `1.05`.
    fn pi_scaled_uncut(bits: usize) -> Natural {
        let (_, q, t) = plain_split(0, (bits as u64) / 47 + 2);
        let root = (Natural::from(10005u32) << (2 * bits)).floor_sqrt();
        (Natural::from(426880u32) * root * q.unsigned_abs()) / t.unsigned_abs()
    }

    /// `(P, Q, T)` over `[a, b)` by the recurrence alone: no common factors removed, no
    /// threads, leaves written from the series' definition. The oracle for [`binary_split`].
    fn plain_split(a: u64, b: u64) -> (Integer, Integer, Integer) {
        if b - a == 1 {
            let i = |x: u64| Integer::from(x);
            if a == 0 {
                return (i(1), i(1), i(13591409));
            }
            let p = i(6 * a - 5) * i(2 * a - 1) * i(6 * a - 1);
            let q = i(a).pow(3) * i(640320).pow(3) / i(24);
            let sign = if a % 2 == 1 { i(0) - i(1) } else { i(1) };
            let t = sign * &p * (i(13591409) + i(545140134) * i(a));
            return (p, q, t);
        }
        let m = (a + b) / 2;
        let ((pl, ql, tl), (pr, qr, tr)) = (plain_split(a, m), plain_split(m, b));
        (&pl * pr, &ql * &qr, qr * tl + pl * tr)
    }

    #[test]
    fn removing_common_factors_keeps_the_ratios_and_shrinks_the_numbers() {
        let ranges = [
            (0, 2),
            (0, 3),
            (1, 2),
            (5, 17),
            (0, 64),
            (100, 131),
            (0, 300),
        ];
        let long = [(0, COMMON_FACTOR_TERMS), (7, 2 * COMMON_FACTOR_TERMS + 9)];
        for (a, b) in ranges.into_iter().chain(long) {
            let sieve = Sieve::new(6 * b);
            let s = binary_split(&sieve, a, b, true);
            let (p, q, t) = plain_split(a, b);
            // P/Q and T/Q unchanged: P·Q' = P'·Q and T·Q' = T'·Q.
            assert_eq!(&p * &s.q, &s.p * &q, "P/Q over [{a}, {b})");
            assert_eq!(&t * &s.q, &s.t * &q, "T/Q over [{a}, {b})");
            // Q' divides Q (only common factors go), and something goes wherever a merge has a
            // left half other than the term 0 (whose P is 1).
            assert_eq!(&q % &s.q, 0u32, "[{a}, {b})");
            if b - a >= 2 && (a, b) != (0, 2) {
                assert!(s.q < q, "nothing removed over [{a}, {b})");
            }
            // The factor lists describe the numbers they travel with.
            if b - a <= COMMON_FACTOR_TERMS {
                assert_eq!(Integer::from(s.fp.value()), s.p, "[{a}, {b})");
                assert_eq!(Integer::from(s.fq.value()), s.q, "[{a}, {b})");
            }
            // Without P (right halves), Q and T are the same.
            let r = binary_split(&sieve, a, b, false);
            assert_eq!((r.q, r.t), (s.q, s.t), "[{a}, {b})");
        }
    }

    #[test]
    fn the_cut_ratio_agrees_with_the_uncut_formula() {
        let sizes = (1..400)
            .map(|i| 3 * i)
            .chain([4_999, 5_000, 65_536, 200_001]);
        for bits in sizes {
            let (a, b) = (
                Integer::from(pi_scaled(bits)),
                Integer::from(pi_scaled_uncut(bits)),
            );
            assert!((a - b).unsigned_abs() <= 2u32, "bits = {bits}");
        }
    }

    #[test]
    fn scaled_sums_align_either_exponent() {
        let i = Integer::from;
        assert_eq!(add_scaled(i(3), 5, i(-1), 2), (i(23), 2));
        assert_eq!(add_scaled(i(-1), 2, i(3), 5), (i(23), 2));
        assert_eq!(add_scaled(i(7), 4, i(1), 4), (i(8), 4));
        assert_eq!(top(&i(-45), 3), (i(-6), 3)); // −45 = 101101₂: ⌊−45/8⌋ = −6
        assert_eq!(top(&i(45), 8), (i(45), 0));
    }

    #[test]
    fn the_checksum_is_fnv_1a() {
        // The FNV-1a 64-bit test vectors of its authors: "" and "a".
        assert_eq!(checksum(b""), 0xcbf29ce484222325);
        assert_eq!(checksum(b"a"), 0xaf63dc4c8601ec8c);
    }

    #[test]
    fn cache_files_are_used_only_when_they_verify() {
        let tmp = tempfile::tempdir().unwrap();
        let dir = tmp.path().join("nested").join("cache");
        let digits = compute(1000);
        store_cached(&dir, &digits);
        assert_eq!(load_cached(&dir, 1000), Some(digits.clone()));
        assert_eq!(load_cached(&dir, 999), None);
        let file = cache_file(&dir, 1000);
        let write = |body: &[u8], sum: u64| {
            let mut bytes = sum.to_le_bytes().to_vec();
            bytes.extend_from_slice(body);
            std::fs::write(&file, bytes).unwrap();
        };
        let mut changed = digits.clone();
        changed[500] ^= 1;
        write(&changed, checksum(&digits)); // a damaged digit
        assert_eq!(load_cached(&dir, 1000), None);
        // A consistent file is accepted: its checksum and first 64 digits are what is checked.
        write(&changed, checksum(&changed));
        assert_eq!(load_cached(&dir, 1000), Some(changed.clone()));
        let mut wrong_head = digits.clone();
        wrong_head[3] ^= 1;
        write(&wrong_head, checksum(&wrong_head)); // not π's first digits
        assert_eq!(load_cached(&dir, 1000), None);
        let mut big = digits.clone();
        big[700] = 4;
        write(&big, checksum(&big)); // not a base-4 digit
        assert_eq!(load_cached(&dir, 1000), None);
        write(&digits[..999], checksum(&digits[..999])); // too short for its name
        assert_eq!(load_cached(&dir, 1000), None);
        std::fs::write(&file, [1, 2, 3]).unwrap(); // no room for the checksum
        assert_eq!(load_cached(&dir, 1000), None);
    }

    /// The cache is read only from a regular file and never past its exact size: a FIFO in
    /// its place is skipped at once (no blocking open), a longer file is not read to its end.
    #[test]
    fn cache_files_that_are_pipes_or_too_long_are_skipped() {
        let tmp = tempfile::tempdir().unwrap();
        let digits = compute(100);
        store_cached(tmp.path(), &digits);
        let file = cache_file(tmp.path(), 100);
        let mut long = std::fs::read(&file).unwrap();
        long.extend_from_slice(&[0; 4096]);
        std::fs::write(&file, &long).unwrap();
        assert_eq!(load_cached(tmp.path(), 100), None);
        std::fs::remove_file(&file).unwrap();
        let status = std::process::Command::new("mkfifo")
            .arg(&file)
            .status()
            .unwrap();
        assert!(status.success());
        assert_eq!(load_cached(tmp.path(), 100), None);
    }

    #[test]
    fn only_long_prefixes_go_to_disk() {
        let tmp = tempfile::tempdir().unwrap();
        let dir = tmp.path().to_path_buf();
        let short = load_or_compute(DISK_CACHE_MIN - 1, Some(dir.clone()));
        assert_eq!(short.len(), DISK_CACHE_MIN - 1);
        assert!(!cache_file(&dir, DISK_CACHE_MIN - 1).exists());
        let long = load_or_compute(DISK_CACHE_MIN, Some(dir.clone()));
        assert_eq!(long[..short.len()], short[..]);
        assert_eq!(load_cached(&dir, DISK_CACHE_MIN), Some(long.clone()));
        // A verified file is what a later call returns (here: one with a changed last digit).
        let mut marked = long.clone();
        *marked.last_mut().unwrap() ^= 1;
        store_cached(&dir, &marked);
        assert_eq!(load_or_compute(DISK_CACHE_MIN, Some(dir.clone())), marked);
        assert_eq!(load_or_compute(DISK_CACHE_MIN, None), long);
    }

    #[test]
    fn first_base4_digits_are_0210() {
        // π = 3.0210 0333 1222 … in base 4 (hexadecimal 3.243F6A88…, two base-4 digits per
        // hexadecimal digit): not 1032, a transposition easy to make.
        let d = compute(12);
        assert_ne!(&d[..4], &[1, 0, 3, 2]);
        assert_eq!(&d[4..12], &[0, 3, 3, 3, 1, 2, 2, 2]);
    }

    /// The hexadecimal digits of π from position `n` (0-based, after the point), by the
    /// Bailey–Borwein–Plouffe digit-extraction formula in `f64`: an oracle independent of the
    /// series, the square root and the big-integer library. Returns the first 4 digits, which
    /// `f64` gets right for every `n` used here (error ≈ n·2⁻⁵³ ≪ 16⁻⁴).
    fn bbp_hex_digits(n: u64) -> [u8; 4] {
        fn series(j: u64, n: u64) -> f64 {
            let mut s = 0.0f64;
            for k in 0..=n {
                let m = 8 * k + j;
                let mut pow = 1u64;
                let (mut base, mut e) = (16 % m, n - k);
                while e > 0 {
                    if e & 1 == 1 {
                        pow = pow * base % m;
                    }
                    base = base * base % m;
                    e >>= 1;
                }
                s = (s + pow as f64 / m as f64).fract();
            }
            let mut k = n + 1;
            loop {
                let term = 16f64.powi(-((k - n) as i32)) / (8 * k + j) as f64;
                if term < 1e-17 {
                    break;
                }
                s += term;
                k += 1;
            }
            s
        }
        let x = 4.0 * series(1, n) - 2.0 * series(4, n) - series(5, n) - series(6, n);
        let mut f = x.rem_euclid(1.0);
        let mut out = [0u8; 4];
        for d in &mut out {
            f *= 16.0;
            *d = f.floor() as u8;
            f -= f.floor();
        }
        out
    }

    #[test]
    fn deep_digits_agree_with_bbp_digit_extraction() {
        let positions = [1_000u64, 77_777, 250_000];
        let d = compute(2 * 250_004);
        for n in positions {
            let ours: Vec<u8> = (0..4)
                .map(|i| {
                    let at = 2 * (n as usize + i);
                    4 * d[at] + d[at + 1]
                })
                .collect();
            assert_eq!(ours, bbp_hex_digits(n), "hex position {n}");
        }
        // The oracle itself against the known prefix.
        assert_eq!(bbp_hex_digits(0), [2, 4, 3, 15]);
    }

    #[test]
    fn the_shared_prefix_grows_and_stays_consistent() {
        let a = digits(100);
        let b = digits(50_000);
        assert!(b.len() >= 50_000);
        assert_eq!(a[..100], b[..100]);
    }
}
