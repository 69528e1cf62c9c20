//! A stand-in for Kani's `kani` crate (see `../shared/KANI.md`), used only when not compiling
//! under Kani. Same public names and signatures as Kani's API (`any`, `any_where`, `assume`,
//! `assert`, `cover`, `Arbitrary`, the attributes); different engine: every `kani::any()` is a
//! choice point, and [`__run`] re-executes the harness depth-first over **every** choice
//! (`assume(false)` prunes a branch; a failing assertion reports the exact choice sequence).
//! A choice wider than 2^16 values switches the harness to seeded sampling (boundary values
//! first) and the summary says so. Nothing here is symbolic: it is not Kani.

use std::cell::RefCell;
use std::fmt;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::Once;

pub use kani_standin_macros::{proof, should_panic, solver, unwind, Arbitrary};

/// Executions allowed in exhaustive mode before the stand-in refuses (size the harness down).
pub const MAX_EXHAUSTIVE: u64 = 5_000_000;
/// Executions in sampled mode.
pub const SAMPLES: u64 = 20_000;

struct AssumeFailed;

#[derive(Default)]
struct Explorer {
    trail: Vec<(u64, u64)>,
    pos: usize,
    sampled: bool,
    wide_seen: bool,
    rng: u64,
    execution: u64,
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

/// A choice point with `domain` values (`0..domain`); used by the `Arbitrary` impls.
#[doc(hidden)]
pub fn __choose(domain: u64) -> u64 {
    assert!(domain > 0);
    EXPLORER.with(|e| {
        let mut e = e.borrow_mut();
        let Some(x) = e.as_mut() else {
            panic!("kani::any() called outside a harness run");
        };
        if domain > 1 << 16 {
            x.wide_seen = true;
        }
        if x.sampled {
            let boundary = x.execution;
            return match boundary {
                0 => 0,
                1 => domain - 1,
                _ => next_random(&mut x.rng) % domain,
            };
        }
        if domain > 1 << 16 {
            return 0; // the run restarts in sampled mode
        }
        let v = if x.pos < x.trail.len() {
            x.trail[x.pos].0
        } else {
            x.trail.push((0, domain));
            0
        };
        x.pos += 1;
        v
    })
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
                let bits = <$t>::BITS;
                if bits <= 16 {
                    (<$t>::MIN as i128 + __choose(1u64 << bits) as i128) as $t
                } else {
                    let v = __choose(u64::MAX) as u128 | ((__choose(u64::MAX) as u128) << 64);
                    v as $t
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
    /// Seeded sampling (a domain wider than 2^16 values).
    Sampled,
}

/// The outcome of running a harness.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Summary {
    /// Harness name.
    pub name: String,
    /// Exhaustive or sampled.
    pub mode: Mode,
    /// Executions of the body.
    pub executions: u64,
    /// Executions pruned by `assume`.
    pub pruned: u64,
    /// Executions that failed (panicked).
    pub failures: u64,
}

impl fmt::Display for Summary {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "kani-standin: {}: {}, {} executions ({} pruned by assume), {} failing",
            self.name,
            match self.mode {
                Mode::Exhaustive => "exhaustive",
                Mode::Sampled => "sampled (seeded, boundary values first)",
            },
            self.executions,
            self.pruned,
            self.failures
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

/// Runs a harness over every choice (or a seeded sample); panics with the failing choice
/// sequence if a non-`should_panic` harness fails, or if a `should_panic` harness never fails.
#[doc(hidden)]
pub fn __run(name: &str, should_panic: bool, body: fn()) -> Summary {
    install_hook();
    let mut summary = Summary {
        name: name.to_string(),
        mode: Mode::Exhaustive,
        executions: 0,
        pruned: 0,
        failures: 0,
    };
    EXPLORER.with(|e| *e.borrow_mut() = Some(Explorer::default()));
    QUIET.with(|q| *q.borrow_mut() = should_panic);
    let mut first_failure: Option<(String, Vec<u64>)> = None;
    loop {
        EXPLORER.with(|e| {
            let mut e = e.borrow_mut();
            let x = e.as_mut().expect("explorer");
            x.pos = 0;
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
            summary.executions >= SAMPLES
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
    EXPLORER.with(|e| *e.borrow_mut() = None);
    QUIET.with(|q| *q.borrow_mut() = false);
    match (should_panic, first_failure) {
        (false, Some((msg, choices))) => {
            panic!("kani-standin: {name} fails: {msg}; choice sequence {choices:?}; {summary}")
        }
        (true, None) => panic!("kani-standin: {name} was expected to fail but passed: {summary}"),
        _ => summary,
    }
}
