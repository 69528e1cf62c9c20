//! A stand-in for Kani's `kani` crate (see `../shared/KANI.md`), used only when not compiling
//! under Kani. Same public names and signatures as Kani's API (`any`, `any_where`, `assume`,
//! `assert`, `cover`, `Arbitrary`, the attributes); different engine: every `kani::any()` is a
//! choice point, and [`__run`] re-executes the harness body.
//!
//! * **Exhaustive** when every choice has at most 2^16 values and every execution's choices at
//!   most 2^22 combinations: depth-first over every choice
//!   sequence (`assume(false)` prunes a branch; a failing assertion reports the exact choice
//!   sequence).
//! * **Sampled** as soon as one choice is wider (a `u32`, an `i32`, ...) or one execution's
//!   choices span more than 2^22 combinations ([`EXHAUSTIVE_BITS`]): a stated number of
//!   seeded executions ([`SAMPLES`], or the harness's `#[cfg_attr(not(kani), kani::samples(N))]`),
//!   boundary values first (the first [`BOUNDARY_EXECUTIONS`] executions draw every integer from
//!   its boundary set: `MIN`, `MIN + 1`, `-1`, `0`, `1`, `2`, `MAX - 1`, `MAX`), then uniform
//!   values mixed with boundary values (one choice in eight). The summary says `sampled`; a
//!   sampled run is evidence, never a proof.
//!
//! The summary also states the harness's *domain* in bits (the largest `Σ log2 |choice|` over the
//! executions), which is what a model checker covers symbolically. Nothing here is symbolic: it
//! is not Kani. As under Kani's `#[kani::should_panic]`, only an assertion failure (a
//! `kani::assert`, `assert!` or `panic!`) counts as the expected failure: an arithmetic overflow
//! (`attempt to ...`) fails every harness.

use std::cell::RefCell;
use std::fmt;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::Once;

pub use kani_standin_macros::{proof, samples, should_panic, solver, unwind, Arbitrary};

/// Executions allowed in exhaustive mode before the stand-in refuses (size the harness down).
pub const MAX_EXHAUSTIVE: u64 = 5_000_000;
/// Executions in sampled mode unless the harness states its own number.
pub const SAMPLES: u64 = 20_000;
/// Sampled mode: the first executions draw every integer choice from its boundary values.
pub const BOUNDARY_EXECUTIONS: u64 = 1_000;
/// A choice wider than this many values switches the harness to sampling.
pub const EXHAUSTIVE_CHOICE: u128 = 1 << 16;
/// An execution whose choices span more than 2^this many combinations switches the harness to
/// sampling (about [`MAX_EXHAUSTIVE`]).
pub const EXHAUSTIVE_BITS: f64 = 22.0;

struct AssumeFailed;

#[derive(Default)]
struct Explorer {
    trail: Vec<(u64, u64)>,
    pos: usize,
    sampled: bool,
    wide_seen: bool,
    rng: u64,
    execution: u64,
    bits: f64,
    max_bits: f64,
}

thread_local! {
    static EXPLORER: RefCell<Option<Explorer>> = const { RefCell::new(None) };
    static QUIET: RefCell<bool> = const { RefCell::new(false) };
}

fn next_random(state: &mut u64) -> u64 {
    *state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
    let mut z = *state;
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// A choice point with `domain` values (`0..domain`, at most 2^64); `boundaries` are the indices
/// a sampled run tries first (out-of-range ones are ignored). Used by the `Arbitrary` impls.
#[doc(hidden)]
pub fn __choose_in(domain: u128, boundaries: &[u128]) -> u128 {
    assert!(domain > 0 && domain <= 1 << 64);
    EXPLORER.with(|e| {
        let mut e = e.borrow_mut();
        let Some(x) = e.as_mut() else {
            panic!("kani::any() called outside a harness run");
        };
        x.bits += (domain as f64).log2();
        if x.bits > x.max_bits {
            x.max_bits = x.bits;
        }
        if domain > EXHAUSTIVE_CHOICE || x.bits > EXHAUSTIVE_BITS {
            x.wide_seen = true;
        }
        if x.sampled {
            let uniform = |x: &mut Explorer| (next_random(&mut x.rng) as u128) % domain;
            let boundary = |x: &mut Explorer| {
                let b: Vec<u128> = boundaries.iter().copied().filter(|&b| b < domain).collect();
                if b.is_empty() {
                    uniform(x)
                } else {
                    b[(next_random(&mut x.rng) % b.len() as u64) as usize]
                }
            };
            let from_boundaries =
                x.execution < BOUNDARY_EXECUTIONS || next_random(&mut x.rng).is_multiple_of(8);
            return if from_boundaries {
                boundary(x)
            } else {
                uniform(x)
            };
        }
        if x.wide_seen {
            return 0; // the run restarts in sampled mode
        }
        let domain = domain as u64;
        let v = if x.pos < x.trail.len() {
            x.trail[x.pos].0
        } else {
            x.trail.push((0, domain));
            0
        };
        x.pos += 1;
        v as u128
    })
}

/// A choice point with `domain` values (`0..domain`); used by `#[derive(kani::Arbitrary)]`.
#[doc(hidden)]
pub fn __choose(domain: u64) -> u64 {
    __choose_in(domain as u128, &[0, domain as u128 - 1]) as u64
}

/// Types whose every value `kani::any()` can produce (Kani's trait, same signatures).
pub trait Arbitrary
where
    Self: Sized,
{
    /// Any value.
    fn any() -> Self;
    /// An array of any values.
    fn any_array<const MAX_ARRAY_LENGTH: usize>() -> [Self; MAX_ARRAY_LENGTH] {
        std::array::from_fn(|_| Self::any())
    }
}

macro_rules! int_impl {
    ($($t:ty),*) => {$(
        impl Arbitrary for $t {
            fn any() -> Self {
                // Choices of at most 64 bits: the index is `value - MIN`.
                fn part(bits: u32, min: i128) -> u128 {
                    let domain = 1u128 << bits;
                    let zero = (-min) as u128; // index of the value 0
                    let b = [0, 1, domain - 2, domain - 1, zero, zero + 1, zero + 2, zero.wrapping_sub(1)];
                    __choose_in(domain, &b)
                }
                let bits = <$t>::BITS;
                if bits <= 64 {
                    let min = <$t>::MIN as i128;
                    (min + part(bits, min) as i128) as $t
                } else {
                    // 128 bits: two 64-bit halves (boundary values of each half).
                    let lo = part(64, 0);
                    let hi = part(64, 0);
                    (lo | (hi << 64)) as $t
                }
            }
        }
    )*};
}
int_impl!(u8, u16, u32, u64, u128, usize, i8, i16, i32, i64, i128, isize);

impl Arbitrary for bool {
    fn any() -> Self {
        __choose(2) == 1
    }
}
impl Arbitrary for () {
    fn any() -> Self {}
}
impl Arbitrary for char {
    fn any() -> Self {
        char::from_u32(__choose(0x11_0000) as u32).unwrap_or('\u{0}')
    }
}
impl Arbitrary for f32 {
    fn any() -> Self {
        f32::from_bits(u32::any())
    }
}
impl Arbitrary for f64 {
    fn any() -> Self {
        f64::from_bits(u64::any())
    }
}
impl<T: Arbitrary, const N: usize> Arbitrary for [T; N] {
    fn any() -> Self {
        T::any_array::<N>()
    }
}
impl<T: Arbitrary> Arbitrary for Option<T> {
    fn any() -> Self {
        if bool::any() {
            Some(T::any())
        } else {
            None
        }
    }
}
impl<T: Arbitrary, E: Arbitrary> Arbitrary for Result<T, E> {
    fn any() -> Self {
        if bool::any() {
            Ok(T::any())
        } else {
            Err(E::any())
        }
    }
}
impl<T: Arbitrary> Arbitrary for Box<T> {
    fn any() -> Self {
        Box::new(T::any())
    }
}
macro_rules! tuple_impl {
    ($($n:ident),+) => {
        impl<$($n: Arbitrary),+> Arbitrary for ($($n,)+) {
            fn any() -> Self { ($($n::any(),)+) }
        }
    };
}
tuple_impl!(A);
tuple_impl!(A, B);
tuple_impl!(A, B, C);
tuple_impl!(A, B, C, D);
tuple_impl!(A, B, C, D, E);
tuple_impl!(A, B, C, D, E, F);

/// Any value of `T`.
pub fn any<T: Arbitrary>() -> T {
    T::any()
}

/// Any value of `T` satisfying `f` (`any` then `assume`).
pub fn any_where<T: Arbitrary, F: FnOnce(&T) -> bool>(f: F) -> T {
    let v = T::any();
    assume(f(&v));
    v
}

/// Prunes the current execution unless `cond` holds.
pub fn assume(cond: bool) {
    if !cond {
        std::panic::panic_any(AssumeFailed);
    }
}

/// Fails the harness unless `cond` holds.
pub fn assert(cond: bool, msg: &'static str) {
    if !cond {
        panic!("{msg}");
    }
}

/// A coverage goal (recorded by Kani; nothing to do here).
pub fn cover(_cond: bool, _msg: &'static str) {}

/// `kani::cover!(...)`.
#[macro_export]
macro_rules! cover {
    () => {};
    ($cond:expr $(,)?) => {
        $crate::cover($cond, "cover")
    };
    ($cond:expr, $msg:literal) => {
        $crate::cover($cond, $msg)
    };
}

/// How a harness was run.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Mode {
    /// Every choice enumerated.
    Exhaustive,
    /// Seeded sampling (a choice wider than 2^16 values, or more than 2^22 combinations).
    Sampled,
}

impl Mode {
    /// `exhaustive` or `sampled`.
    pub fn name(self) -> &'static str {
        match self {
            Mode::Exhaustive => "exhaustive",
            Mode::Sampled => "sampled",
        }
    }
}

/// The outcome of running a harness.
#[derive(Clone, Debug, PartialEq)]
pub struct Summary {
    /// Harness name.
    pub name: String,
    /// Exhaustive or sampled.
    pub mode: Mode,
    /// Executions of the body.
    pub executions: u64,
    /// Executions pruned by `assume`.
    pub pruned: u64,
    /// Executions that failed (an assertion failed or the body panicked).
    pub failures: u64,
    /// The domain in bits: the largest `Σ log2 |choice|` of one execution (rounded down).
    pub domain_bits: u32,
}

impl fmt::Display for Summary {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "kani-standin: {}: {} ({} executions{}; {} pruned by assume), {} failing; domain 2^{} choices",
            self.name,
            self.mode.name(),
            self.executions,
            match self.mode {
                Mode::Exhaustive => ", every choice",
                Mode::Sampled => ", seeded, boundary values first",
            },
            self.pruned,
            self.failures,
            self.domain_bits
        )
    }
}

fn install_hook() {
    static HOOK: Once = Once::new();
    HOOK.call_once(|| {
        let previous = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            let quiet = QUIET.with(|q| *q.borrow());
            if info.payload().is::<AssumeFailed>() || quiet {
                return;
            }
            previous(info);
        }));
    });
}

fn is_overflow(msg: &str) -> bool {
    msg.starts_with("attempt to ")
}

/// Runs a harness over every choice (or a seeded sample of [`SAMPLES`] executions); panics with
/// the failing choice sequence if a non-`should_panic` harness fails, if a `should_panic`
/// harness never fails (or fails by an arithmetic overflow), or if every execution was pruned.
#[doc(hidden)]
pub fn __run(name: &str, should_panic: bool, body: fn()) -> Summary {
    __run_with(name, should_panic, SAMPLES, body)
}

/// [`__run`] with a stated number of executions for sampled mode.
#[doc(hidden)]
pub fn __run_with(name: &str, should_panic: bool, samples: u64, body: fn()) -> Summary {
    install_hook();
    let mut summary = Summary {
        name: name.to_string(),
        mode: Mode::Exhaustive,
        executions: 0,
        pruned: 0,
        failures: 0,
        domain_bits: 0,
    };
    EXPLORER.with(|e| *e.borrow_mut() = Some(Explorer::default()));
    QUIET.with(|q| *q.borrow_mut() = should_panic);
    let mut first_failure: Option<(String, Vec<u64>)> = None;
    let mut overflow: Option<String> = None;
    loop {
        EXPLORER.with(|e| {
            let mut e = e.borrow_mut();
            let x = e.as_mut().expect("explorer");
            x.pos = 0;
            x.bits = 0.0;
            x.execution = summary.executions;
        });
        let outcome = catch_unwind(AssertUnwindSafe(body));
        summary.executions += 1;
        let (wide, sampled, trail) = EXPLORER.with(|e| {
            let e = e.borrow();
            let x = e.as_ref().expect("explorer");
            (
                x.wide_seen,
                x.sampled,
                x.trail.iter().map(|t| t.0).collect::<Vec<_>>(),
            )
        });
        match outcome {
            Ok(()) => {}
            Err(p) if p.is::<AssumeFailed>() => summary.pruned += 1,
            Err(p) => {
                summary.failures += 1;
                let msg = p
                    .downcast_ref::<&str>()
                    .map(|s| s.to_string())
                    .or_else(|| p.downcast_ref::<String>().cloned())
                    .unwrap_or_default();
                if is_overflow(&msg) {
                    overflow.get_or_insert(msg.clone());
                }
                first_failure.get_or_insert((msg, trail.clone()));
            }
        }
        if wide && !sampled {
            // Restart in sampled mode.
            summary = Summary {
                mode: Mode::Sampled,
                executions: 0,
                pruned: 0,
                failures: 0,
                ..summary
            };
            first_failure = None;
            overflow = None;
            EXPLORER.with(|e| {
                *e.borrow_mut() = Some(Explorer {
                    sampled: true,
                    wide_seen: true,
                    rng: 0x5EED,
                    ..Explorer::default()
                })
            });
            continue;
        }
        let done = if sampled {
            summary.executions >= samples
        } else {
            EXPLORER.with(|e| {
                let mut e = e.borrow_mut();
                let x = e.as_mut().expect("explorer");
                // Odometer: drop choices beyond this execution, then advance the last one.
                x.trail.truncate(x.pos);
                while let Some(&(v, d)) = x.trail.last() {
                    if v + 1 < d {
                        x.trail.last_mut().expect("non-empty").0 += 1;
                        return false;
                    }
                    x.trail.pop();
                }
                true
            })
        };
        if done {
            break;
        }
        assert!(
            summary.executions < MAX_EXHAUSTIVE,
            "kani-standin: {name}: more than {MAX_EXHAUSTIVE} executions; shrink the harness domains"
        );
    }
    summary.domain_bits = EXPLORER.with(|e| {
        let e = e.borrow();
        e.as_ref().expect("explorer").max_bits.floor() as u32
    });
    EXPLORER.with(|e| *e.borrow_mut() = None);
    QUIET.with(|q| *q.borrow_mut() = false);
    if summary.pruned == summary.executions {
        panic!("kani-standin: {name} is vacuous: every execution was pruned by assume; {summary}");
    }
    match (should_panic, first_failure) {
        (false, Some((msg, choices))) => {
            panic!("kani-standin: {name} fails: {msg}; choice sequence {choices:?}; {summary}")
        }
        (true, None) => panic!("kani-standin: {name} was expected to fail but passed: {summary}"),
        (true, Some(_)) if overflow.is_some() => panic!(
            "kani-standin: {name}: an arithmetic overflow is not the expected failure: {}; {summary}",
            overflow.unwrap_or_default()
        ),
        _ => summary,
    }
}
