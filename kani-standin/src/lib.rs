//! A stand-in for Kani's `kani` crate, used only when not compiling under Kani. Same public names and signatures as Kani's API (`any`, `any_where`, `assume`,
//! `assert`, `cover`, `Arbitrary`, the attributes); different engine: every `kani::any()` is a
//! choice point, and [`Harness::explore`] re-executes the harness body.
//!
//! * **Exhaustive** when every choice has at most 2^16 values and every execution's choices at
//!   most 2^22 combinations: depth-first over every choice sequence (`assume(false)` prunes a
//!   branch; a failing assertion reports the exact choice sequence).
//! * **Sampled** as soon as one choice is wider (a `u32`, an `i32`, ...) or one execution's
//!   choices span more than 2^22 combinations ([`EXHAUSTIVE_BITS`]): a stated number of
//!   seeded executions ([`SAMPLES`], or the harness's `#[cfg_attr(not(kani), kani::samples(N))]`),
//!   boundary values first (the first [`BOUNDARY_EXECUTIONS`] executions draw every integer from
//!   its boundary set: `MIN`, `MIN + 1`, `-1`, `0`, `1`, `2`, `MAX - 1`, `MAX`), then uniform
//!   values mixed with boundary values (one choice in eight). The summary says `sampled`; a
//!   sampled run is evidence, never a proof.
//!
//! **What the figures count.** An exhaustive run counts its *choice sequences*: every
//! combination of values the body's `kani::any()` calls can return, each executed once, so the
//! count is exact (two sequences may still build the same problem, e.g. `any::<u8>() % 3`). A
//! sampled run counts its executions and how many of them drew a *distinct* choice sequence
//! (boundary values repeat), and states the width of the domain in **choice bits**: the largest
//! `Σ log2 |choice|` of one execution. Choice bits measure nondeterminism, not distinct inputs:
//! a harness that draws an unused `u8` has 8 more bits and no more inputs.
//!
//! **Covers.** `kani::cover!(cond, "msg")` records, per call site, in how many non-pruned
//! executions it was reached and its condition held; the `cover!` calls written in a harness
//! body are also known statically (`#[kani::proof]` lists their messages), so a cover that no
//! execution reaches is seen too. The stand-in judges covers as Kani does with
//! `--fail-uncoverable` ([`FAIL_UNCOVERABLE`]): a harness fails when one of its covers is never
//! satisfied in a non-pruned execution. Kani without that flag only reports an unsatisfiable or
//! unreachable cover; the project's Kani workflow and `proofs/Cargo.toml` pass the flag, because
//! a cover is what shows that the branch a harness is about is reachable under its `assume`s.
//! One difference remains: a cover in a shared function that no execution reaches is invisible
//! here (Kani reports it unreachable and, with the flag, fails).
//!
//! **Contracts.** `#[kani::requires(cond)]`, `#[kani::ensures(|result| cond)]` (with `old(e)`)
//! and `#[kani::modifies(…)]` wrap a function. Outside a harness run the wrapper costs one
//! thread-local read per call and changes nothing. Inside a run, at every call: the
//! precondition is *assumed* when the harness is `#[kani::proof_for_contract]` of that function
//! (as Kani assumes it for the function under verification) and *asserted* otherwise (a caller
//! that violates it fails, as at a `#[kani::stub_verified]` call under Kani); every
//! postcondition is asserted after the body. `#[kani::stub_verified(f)]` therefore runs the real
//! `f` with its contract checked — where Kani *assumes* the postcondition, the stand-in checks
//! that the assumption holds on every path it runs. `#[kani::stub(f, g)]` is not applied (the
//! stand-in cannot replace a call made in another crate): the real `f` runs, and the summary
//! lists the stub. A `proof_for_contract` run that never calls its function fails.
//!
//! **Vacuity.** A harness whose every execution is pruned by `assume` fails.
//!
//! Nothing here is symbolic: it is not Kani. As under Kani's `#[kani::should_panic]`, a panic is
//! the expected failure: Kani turns `kani::assert`, `assert!`, `panic!` and Rust's arithmetic
//! overflow checks (`attempt to …`, compiled in by `-C overflow-checks=on`) into checks of class
//! `assertion`, and `should_panic` passes when every failed check is of that class. (Kani's other
//! classes — unwinding assertions, pointer and undefined-behaviour checks — have no counterpart
//! in a stand-in run.) An overflow is still recorded in [`Summary::overflow`].

use std::cell::{Cell, RefCell};
use std::collections::HashSet;
use std::fmt;
use std::hash::{Hash, Hasher};
use std::panic::{catch_unwind, AssertUnwindSafe, Location};
use std::sync::Once;

pub use kani_standin_macros::{
    ensures, modifies, proof, proof_for_contract, requires, samples, should_panic, solver, stub,
    stub_verified, unwind, Arbitrary,
};

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
/// The stand-in judges covers as `cargo kani --fail-uncoverable` does: an unsatisfied cover
/// fails the harness (see the crate docs).
pub const FAIL_UNCOVERABLE: bool = true;

struct AssumeFailed;

/// A cover call site and what the executions did with it.
struct CoverSite {
    message: &'static str,
    location: Option<&'static Location<'static>>,
    reached: u64,
    satisfied: u64,
}

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
    /// The values chosen in this execution.
    choices: Vec<u128>,
    covers: Vec<CoverSite>,
    /// This execution's cover events: (site, condition).
    pending: Vec<(usize, bool)>,
    /// Calls of the contract's function in this execution.
    pending_target_calls: u64,
    /// Calls of the contract's function in non-pruned executions.
    target_calls: u64,
}

impl Explorer {
    fn cover(&mut self, cond: bool, message: &'static str, at: &'static Location<'static>) {
        let i = match self
            .covers
            .iter()
            .position(|c| c.message == message && c.location == Some(at))
        {
            Some(i) => i,
            None => {
                self.covers.push(CoverSite {
                    message,
                    location: Some(at),
                    reached: 0,
                    satisfied: 0,
                });
                self.covers.len() - 1
            }
        };
        self.pending.push((i, cond));
    }

    /// Ends an execution: its cover events count unless it was pruned.
    fn settle_covers(&mut self, pruned: bool) {
        let pending = std::mem::take(&mut self.pending);
        let calls = std::mem::take(&mut self.pending_target_calls);
        if pruned {
            return;
        }
        self.target_calls += calls;
        let mut reached = vec![false; self.covers.len()];
        let mut satisfied = vec![false; self.covers.len()];
        for (i, cond) in pending {
            reached[i] = true;
            satisfied[i] |= cond;
        }
        for (c, (r, s)) in self
            .covers
            .iter_mut()
            .zip(reached.into_iter().zip(satisfied))
        {
            c.reached += u64::from(r);
            c.satisfied += u64::from(s);
        }
    }
}

thread_local! {
    static EXPLORER: RefCell<Option<Explorer>> = const { RefCell::new(None) };
    static QUIET: RefCell<bool> = const { RefCell::new(false) };
    static LAST_PANIC: RefCell<Option<String>> = const { RefCell::new(None) };
    /// Inside a harness run (contracts are checked).
    static CHECKING: Cell<bool> = const { Cell::new(false) };
    /// The function whose contract the running harness proves (`proof_for_contract`).
    static TARGET: Cell<Option<&'static str>> = const { Cell::new(None) };
}

/// Whether contracts are checked: inside a stand-in harness run. Called by every function
/// carrying a contract attribute; outside a run this read is all the wrapper costs.
#[doc(hidden)]
#[inline]
pub fn __contract_checks() -> bool {
    CHECKING.with(Cell::get)
}

/// Whether `name` in module `module` is the function named by the running harness's
/// `proof_for_contract(path)`: the path's last segment is `name`, and each of its other
/// lower-case segments (modules; type names and generic arguments are skipped) is a segment of
/// `module`. Records the call.
#[doc(hidden)]
pub fn __contract_is_target(module: &str, name: &str) -> bool {
    let Some(target) = TARGET.with(Cell::get) else {
        return false;
    };
    let is = path_names(target, module, name);
    if is {
        EXPLORER.with(|e| {
            if let Some(x) = e.borrow_mut().as_mut() {
                x.pending_target_calls += 1;
            }
        });
    }
    is
}

fn path_names(target: &str, module: &str, name: &str) -> bool {
    let mut segments: Vec<&str> = Vec::new();
    let mut depth = 0usize;
    let mut start = 0usize;
    let bytes = target.as_bytes();
    let mut i = 0;
    while i < bytes.len() {
        match bytes[i] {
            b'<' => depth += 1,
            b'>' => depth = depth.saturating_sub(1),
            b':' if depth == 0 && bytes.get(i + 1) == Some(&b':') => {
                segments.push(&target[start..i]);
                i += 2;
                start = i;
                continue;
            }
            _ => {}
        }
        i += 1;
    }
    segments.push(&target[start..]);
    let strip = |s: &str| s.split('<').next().unwrap_or("").to_string();
    let Some((last, rest)) = segments.split_last() else {
        return false;
    };
    if strip(last) != name {
        return false;
    }
    let modules: Vec<&str> = module.split("::").collect();
    rest.iter()
        .map(|s| strip(s))
        .filter(|s| s.starts_with(|c: char| c.is_ascii_lowercase()))
        .all(|s| s == "crate" || s == "self" || s == "super" || modules.contains(&s.as_str()))
}

/// A precondition at a call inside a harness run: assumed for the function under
/// `proof_for_contract`, asserted otherwise.
#[doc(hidden)]
#[track_caller]
pub fn __contract_requires(cond: bool, target: bool, function: &str, text: &str) {
    if target {
        assume(cond);
    } else if !cond {
        panic!("precondition of {function} violated by its caller: {text}");
    }
}

/// A postcondition after a call inside a harness run: asserted.
#[doc(hidden)]
#[track_caller]
pub fn __contract_ensures(cond: bool, function: &str, text: &str) {
    if !cond {
        panic!("postcondition of {function} violated: {text}");
    }
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
            let v = if from_boundaries {
                boundary(x)
            } else {
                uniform(x)
            };
            x.choices.push(v);
            return v;
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
        x.choices.push(v as u128);
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

/// Fails the harness unless `cond` holds (the failure is reported at the caller's location).
#[track_caller]
pub fn assert(cond: bool, msg: &'static str) {
    if !cond {
        panic!("{msg}");
    }
}

/// A coverage goal: records, for this call site, whether `cond` held (see the crate docs).
/// Outside a harness run it does nothing.
#[track_caller]
pub fn cover(cond: bool, msg: &'static str) {
    let at = Location::caller();
    EXPLORER.with(|e| {
        if let Some(x) = e.borrow_mut().as_mut() {
            x.cover(cond, msg, at);
        }
    });
}

/// `kani::cover!(...)`, with Kani's messages: `cover!()` is `"cover location"`, `cover!(c)` is
/// `"cover condition: c"`.
#[macro_export]
macro_rules! cover {
    () => {
        $crate::cover(true, "cover location")
    };
    ($cond:expr $(,)?) => {
        $crate::cover($cond, concat!("cover condition: ", stringify!($cond)))
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

/// A cover of a harness and what its run did with it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Cover {
    /// Its message (`cover!(c, "msg")`), or Kani's message for `cover!()` / `cover!(c)`.
    pub message: String,
    /// `file:line:column` of the call (`None`: written in the body but never reached).
    pub location: Option<String>,
    /// Non-pruned executions that reached it.
    pub reached: u64,
    /// Non-pruned executions that reached it with its condition true.
    pub satisfied: u64,
}

impl Cover {
    /// Satisfied in some non-pruned execution.
    pub fn hit(&self) -> bool {
        self.satisfied > 0
    }
}

/// The first failing execution of a run.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Failure {
    /// The panic message.
    pub message: String,
    /// Where it panicked (`file:line:column`), when known.
    pub location: Option<String>,
    /// The values its `kani::any()` calls returned, in order (choice indices: an integer's is
    /// `value - MIN`).
    pub choices: Vec<u128>,
}

/// The outcome of running a harness.
#[derive(Clone, Debug, PartialEq)]
pub struct Summary {
    /// Harness name.
    pub name: String,
    /// Whether the harness is `#[kani::should_panic]`.
    pub should_panic: bool,
    /// Exhaustive or sampled.
    pub mode: Mode,
    /// Executions of the body (exhaustive: every choice sequence, once).
    pub executions: u64,
    /// Distinct choice sequences among the executions (exhaustive: all of them).
    pub distinct: u64,
    /// Executions pruned by `assume`.
    pub pruned: u64,
    /// Executions that failed (an assertion failed or the body panicked).
    pub failures: u64,
    /// The domain's width in choice bits: the largest `Σ log2 |choice|` of one execution
    /// (rounded down). Bits of nondeterminism, not a count of distinct inputs.
    pub choice_bits: u32,
    /// Every cover of the harness: the ones reached (by call site), then the ones written in
    /// its body that no execution reached.
    pub covers: Vec<Cover>,
    /// The first failing execution.
    pub first_failure: Option<Failure>,
    /// The first arithmetic overflow (a failure like any other: under Kani an overflow check is
    /// of class `assertion`, so it is also an expected failure of a `should_panic` harness).
    pub overflow: Option<String>,
    /// The function whose contract the harness proves (`proof_for_contract`).
    pub contract: Option<String>,
    /// Calls of that function in non-pruned executions (0 fails the run).
    pub contract_calls: u64,
    /// `#[kani::stub(f, g)]` of the harness: not applied by the stand-in (the real `f` ran).
    pub stubs_not_applied: Vec<String>,
    /// Why the run stopped early (too many executions for exhaustive mode).
    pub stopped: Option<String>,
}

impl Summary {
    /// Covers satisfied in some non-pruned execution.
    pub fn covers_hit(&self) -> usize {
        self.covers.iter().filter(|c| c.hit()).count()
    }

    /// `Ok` when the harness did what it states: no failure (or, `should_panic`, some failure),
    /// not every execution pruned, every cover satisfied, and a `proof_for_contract` harness's
    /// function called in some non-pruned execution. `Err` says why not.
    pub fn verdict(&self) -> Result<(), String> {
        let name = &self.name;
        if let Some(why) = &self.stopped {
            return Err(format!("{name}: {why}"));
        }
        if self.executions > 0 && self.pruned == self.executions {
            return Err(format!(
                "{name} is vacuous: every execution was pruned by assume"
            ));
        }
        match (&self.first_failure, self.should_panic) {
            (Some(f), false) => {
                return Err(format!(
                    "{name} fails: {}{}; choice sequence {:?}",
                    f.message,
                    f.location
                        .as_ref()
                        .map_or(String::new(), |l| format!(" (at {l})")),
                    f.choices
                ))
            }
            (None, true) => return Err(format!("{name} was expected to fail but passed")),
            (Some(_), true) | (None, false) => {}
        }
        if let (Some(f), 0) = (&self.contract, self.contract_calls) {
            return Err(format!(
                "{name} proves the contract of {f} but no non-pruned execution calls it"
            ));
        }
        let live = self.executions - self.pruned;
        if let Some(c) = self.covers.iter().find(|c| !c.hit()) {
            return Err(match &c.location {
                None => format!(
                    "{name}: cover \"{}\" was never reached in {live} non-pruned executions",
                    c.message
                ),
                Some(at) => format!(
                    "{name}: cover \"{}\" ({at}) was never satisfied in {live} non-pruned executions (reached in {})",
                    c.message, c.reached
                ),
            });
        }
        Ok(())
    }
}

impl fmt::Display for Summary {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "kani-standin: {}: ", self.name)?;
        match self.mode {
            Mode::Exhaustive => write!(
                f,
                "exhaustive (every one of {} choice sequences; {} pruned by assume)",
                self.executions, self.pruned
            )?,
            Mode::Sampled => write!(
                f,
                "sampled ({} executions, {} distinct choice sequences, seeded, boundary values first; {} pruned by assume)",
                self.executions, self.distinct, self.pruned
            )?,
        }
        write!(
            f,
            ", {} failing; covers {}/{} satisfied; domain {} choice bits",
            self.failures,
            self.covers_hit(),
            self.covers.len(),
            self.choice_bits
        )?;
        if let Some(c) = &self.contract {
            write!(
                f,
                "; contract of {c}: {} calls checked",
                self.contract_calls
            )?;
        }
        if !self.stubs_not_applied.is_empty() {
            write!(
                f,
                "; stubs not applied by the stand-in (the real function ran): {}",
                self.stubs_not_applied.join(", ")
            )?;
        }
        Ok(())
    }
}

fn install_hook() {
    static HOOK: Once = Once::new();
    HOOK.call_once(|| {
        let previous = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            if info.payload().is::<AssumeFailed>() {
                return;
            }
            if QUIET.with(|q| *q.borrow()) {
                let at = info.location().map(|l| l.to_string());
                LAST_PANIC.with(|p| *p.borrow_mut() = at);
                return;
            }
            previous(info);
        }));
    });
}

fn is_overflow(msg: &str) -> bool {
    msg.starts_with("attempt to ")
}

/// Whether this thread is running a body with the stand-in's panic hook silent (a harness run
/// or [`__panics`]): its panics are the stand-in's to record, not anyone else's.
#[doc(hidden)]
pub fn __quiet() -> bool {
    QUIET.with(|q| *q.borrow())
}

/// Runs `f` with the stand-in's panic hook silent; `true` if it panicked. (Used to ask whether
/// this build checks arithmetic overflow.)
#[doc(hidden)]
pub fn __panics(f: impl FnOnce()) -> bool {
    install_hook();
    let previous = QUIET.with(|q| std::mem::replace(&mut *q.borrow_mut(), true));
    let panicked = catch_unwind(AssertUnwindSafe(f)).is_err();
    QUIET.with(|q| *q.borrow_mut() = previous);
    panicked
}

/// A harness as the stand-in runs it: `#[kani::proof]` defines one next to every harness
/// function, as `<harness>::HARNESS` (a module of the same name).
#[derive(Clone, Copy, Debug)]
pub struct Harness {
    /// The harness function's name.
    pub name: &'static str,
    /// `#[kani::should_panic]`.
    pub should_panic: bool,
    /// Executions in sampled mode (the stated `kani::samples(N)`, else [`SAMPLES`]).
    pub samples: u64,
    /// Messages of the `cover!` calls written in the body (each must be satisfied).
    pub covers: &'static [&'static str],
    /// `proof_for_contract(path)`: the path of the function whose contract it proves.
    pub contract: Option<&'static str>,
    /// `stub_verified(path)` of the harness (under Kani: the function replaced by its contract).
    pub stub_verified: &'static [&'static str],
    /// `stub(f, g)` of the harness, as written (not applied by the stand-in).
    pub stubs: &'static [&'static str],
    /// The body.
    pub body: fn(),
}

impl Harness {
    /// Runs the harness with its stated executions; never panics on the outcome (see
    /// [`Summary::verdict`]).
    pub fn explore(&self) -> Summary {
        self.explore_with(self.samples)
    }

    /// [`Harness::explore`] with `samples` executions in sampled mode (an exhaustive run
    /// enumerates every choice sequence regardless).
    pub fn explore_with(&self, samples: u64) -> Summary {
        explore(self, samples)
    }

    /// Runs the harness; panics with the reason and the summary if [`Summary::verdict`] is not
    /// `Ok` (a failing assertion names its choice sequence). What the `#[test]` that
    /// `#[kani::proof]` adds calls.
    pub fn check(&self) -> Summary {
        let s = self.explore();
        if let Err(why) = s.verdict() {
            panic!("kani-standin: {why}; {s}");
        }
        s
    }
}

/// Runs a harness over every choice (or a seeded sample of [`SAMPLES`] executions); panics with
/// the reason (a failing choice sequence, a `should_panic` harness that never fails or fails by
/// an arithmetic overflow, every execution pruned, a cover never satisfied).
#[doc(hidden)]
pub fn __run(name: &'static str, should_panic: bool, body: fn()) -> Summary {
    __run_with(name, should_panic, SAMPLES, body)
}

/// [`__run`] with a stated number of executions for sampled mode.
#[doc(hidden)]
pub fn __run_with(name: &'static str, should_panic: bool, samples: u64, body: fn()) -> Summary {
    Harness {
        name,
        should_panic,
        samples,
        covers: &[],
        contract: None,
        stub_verified: &[],
        stubs: &[],
        body,
    }
    .check()
}

fn same_message(a: &str, b: &str) -> bool {
    a.split_whitespace().eq(b.split_whitespace())
        || a.chars()
            .filter(|c| !c.is_whitespace())
            .eq(b.chars().filter(|c| !c.is_whitespace()))
}

fn choice_hash(choices: &[u128]) -> u64 {
    let mut h = std::collections::hash_map::DefaultHasher::new();
    choices.hash(&mut h);
    h.finish()
}

fn explore(h: &Harness, samples: u64) -> Summary {
    install_hook();
    let name = h.name;
    let fresh = |mode| Summary {
        name: name.to_string(),
        should_panic: h.should_panic,
        mode,
        executions: 0,
        distinct: 0,
        pruned: 0,
        failures: 0,
        choice_bits: 0,
        covers: Vec::new(),
        first_failure: None,
        overflow: None,
        contract: h.contract.map(str::to_string),
        contract_calls: 0,
        stubs_not_applied: h.stubs.iter().map(|s| s.to_string()).collect(),
        stopped: None,
    };
    let mut summary = fresh(Mode::Exhaustive);
    let nested = EXPLORER.with(|e| e.borrow_mut().replace(Explorer::default()).is_some());
    assert!(
        !nested,
        "kani-standin: {name}: a harness run inside a harness run"
    );
    let quiet_before = QUIET.with(|q| std::mem::replace(&mut *q.borrow_mut(), true));
    CHECKING.with(|c| c.set(true));
    TARGET.with(|t| t.set(h.contract));
    let mut seen: HashSet<u64> = HashSet::new();
    loop {
        EXPLORER.with(|e| {
            let mut e = e.borrow_mut();
            let x = e.as_mut().expect("explorer");
            x.pos = 0;
            x.bits = 0.0;
            x.execution = summary.executions;
            x.choices.clear();
            x.pending.clear();
        });
        LAST_PANIC.with(|p| *p.borrow_mut() = None);
        let outcome = catch_unwind(AssertUnwindSafe(h.body));
        summary.executions += 1;
        let pruned = matches!(&outcome, Err(p) if p.is::<AssumeFailed>());
        let (wide, sampled, choices) = EXPLORER.with(|e| {
            let mut e = e.borrow_mut();
            let x = e.as_mut().expect("explorer");
            x.settle_covers(pruned);
            (x.wide_seen, x.sampled, x.choices.clone())
        });
        if sampled {
            seen.insert(choice_hash(&choices));
        }
        match outcome {
            Ok(()) => {}
            Err(_) if pruned => summary.pruned += 1,
            Err(p) => {
                summary.failures += 1;
                let msg = p
                    .downcast_ref::<&str>()
                    .map(|s| s.to_string())
                    .or_else(|| p.downcast_ref::<String>().cloned())
                    .unwrap_or_default();
                if is_overflow(&msg) {
                    summary.overflow.get_or_insert(msg.clone());
                }
                if summary.first_failure.is_none() {
                    summary.first_failure = Some(Failure {
                        message: msg,
                        location: LAST_PANIC.with(|p| p.borrow_mut().take()),
                        choices,
                    });
                }
            }
        }
        if wide && !sampled {
            // Restart in sampled mode.
            summary = fresh(Mode::Sampled);
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
        if !sampled && summary.executions >= MAX_EXHAUSTIVE {
            summary.stopped = Some(format!(
                "more than {MAX_EXHAUSTIVE} executions in exhaustive mode; shrink the harness domains"
            ));
            break;
        }
    }
    let x = EXPLORER.with(|e| e.borrow_mut().take()).expect("explorer");
    QUIET.with(|q| *q.borrow_mut() = quiet_before);
    CHECKING.with(|c| c.set(false));
    TARGET.with(|t| t.set(None));
    summary.contract_calls = x.target_calls;
    summary.choice_bits = x.max_bits.floor() as u32;
    summary.distinct = match summary.mode {
        Mode::Exhaustive => summary.executions,
        Mode::Sampled => seen.len() as u64,
    };
    summary.covers = x
        .covers
        .iter()
        .map(|c| Cover {
            message: c.message.to_string(),
            location: c.location.map(|l| l.to_string()),
            reached: c.reached,
            satisfied: c.satisfied,
        })
        .collect();
    for &m in h.covers {
        if !summary.covers.iter().any(|c| same_message(&c.message, m)) {
            summary.covers.push(Cover {
                message: m.to_string(),
                location: None,
                reached: 0,
                satisfied: 0,
            });
        }
    }
    summary
}

// The macros name the stand-in `::kani`, as the crates that use it do (its own tests too).
#[cfg(test)]
extern crate self as kani;

#[cfg(test)]
mod tests {
    use super::*;

    fn harness(name: &'static str, covers: &'static [&'static str], body: fn()) -> Harness {
        Harness {
            name,
            should_panic: false,
            samples: 200,
            covers,
            contract: None,
            stub_verified: &[],
            stubs: &[],
            body,
        }
    }

    /// A cover whose condition holds on one choice of 256 is hit (exhaustive: on exactly one
    /// execution); one whose condition never holds fails the harness, naming the cover.
    #[test]
    fn a_cover_never_satisfied_fails_and_one_satisfied_passes() {
        fn hit() {
            let v: u8 = any();
            cover!(v == 200, "two hundred");
        }
        let s = harness("hit", &[], hit).explore();
        assert_eq!(s.verdict(), Ok(()), "{s}");
        assert_eq!(s.covers.len(), 1);
        assert_eq!((s.covers[0].reached, s.covers[0].satisfied), (256, 1));
        assert_eq!(s.covers[0].message, "two hundred");
        assert!(s.covers[0].location.as_deref().unwrap().contains("lib.rs"));
        fn missed() {
            let v: u8 = any();
            cover!(v.count_ones() > 8, "more than eight bits set");
        }
        let s = harness("missed", &[], missed).explore();
        let why = s.verdict().unwrap_err();
        assert!(
            why.contains("cover \"more than eight bits set\"") && why.contains("never satisfied"),
            "{why}"
        );
        assert_eq!(s.covers_hit(), 0);
        // The panicking entry point fails too.
        assert!(catch_unwind(|| __run("missed", false, missed)).is_err());
    }

    /// A cover reached only in pruned executions is not satisfied.
    #[test]
    fn a_cover_hit_only_in_pruned_executions_does_not_count() {
        fn pruned_after() {
            let v: u8 = any();
            cover!(v == 7, "seven");
            assume(v != 7);
        }
        let s = harness("pruned_after", &[], pruned_after).explore();
        assert_eq!(
            (s.pruned, s.covers[0].reached, s.covers[0].satisfied),
            (1, 255, 0)
        );
        assert!(s.verdict().is_err());
    }

    /// A cover written in the body but never reached (its branch is dead under the assume)
    /// fails; the same cover reachable passes. The static list is what `#[kani::proof]`
    /// extracts from the body.
    #[test]
    fn a_cover_never_reached_fails() {
        fn dead() {
            let v: u8 = any();
            assume(v < 10);
            if v > 20 {
                cover!(true, "big");
            }
        }
        let s = harness("dead", &["big"], dead).explore();
        assert_eq!(s.covers.len(), 1);
        assert_eq!(s.covers[0].location, None);
        let why = s.verdict().unwrap_err();
        assert!(why.contains("\"big\" was never reached"), "{why}");
        fn live() {
            let v: u8 = any();
            assume(v < 30);
            if v > 20 {
                cover!(true, "big");
            }
        }
        let s = harness("live", &["big"], live).explore();
        assert_eq!(s.verdict(), Ok(()));
        assert_eq!((s.covers.len(), s.covers[0].satisfied), (1, 9));
        // Kani's message for `cover!(cond)`, matched whatever the spacing.
        fn plain() {
            let v: bool = any();
            cover!(v);
        }
        let s = harness("plain", &["cover condition: v"], plain).explore();
        assert_eq!(s.verdict(), Ok(()));
        assert_eq!(s.covers.len(), 1);
    }

    /// Sampled harnesses: covers on a wide domain, the distinct count below the executions
    /// (boundary values repeat), the width in choice bits; every execution pruned fails.
    #[test]
    fn sampled_covers_distinct_sequences_and_vacuity() {
        fn wide() {
            let (a, b): (u64, u64) = (any(), any());
            cover!(a == u64::MAX, "max");
            cover!(a > 1 << 40 && b > 1 << 40, "both large");
        }
        let s = harness("wide", &[], wide).explore_with(3000);
        assert_eq!(
            (s.mode, s.executions, s.choice_bits),
            (Mode::Sampled, 3000, 128)
        );
        assert_eq!(s.verdict(), Ok(()), "{s}");
        // The first 1000 executions draw each u64 from 8 boundary values: at most 64 distinct
        // pairs among them.
        assert!(s.distinct <= 64 + 2000 && s.distinct > 64, "{s}");
        fn never() {
            let a: u64 = any();
            assume(a.count_ones() > 64);
        }
        let s = harness("never", &[], never).explore_with(100);
        assert!(s.verdict().unwrap_err().contains("vacuous"));
    }

    /// A failing assertion names its message, its caller's location and choices; a
    /// should_panic harness that fails by an assertion or by an overflow passes (both are
    /// assertion-class checks under Kani), one that never fails does not.
    #[test]
    fn failures_and_should_panic() {
        fn bad() {
            let v: u8 = any();
            assert(v != 3, "three is bad");
        }
        const BAD_LINE: u32 = line!() - 2;
        let s = harness("bad", &[], bad).explore();
        assert_eq!(s.failures, 1);
        let why = s.verdict().unwrap_err();
        assert!(
            why.contains("three is bad") && why.contains("choice sequence [3]"),
            "{why}"
        );
        // #[track_caller]: the location is the call in `bad`, not the body of `assert`.
        let at = s.first_failure.unwrap().location.unwrap();
        assert!(at.contains(&format!("lib.rs:{BAD_LINE}:")), "{at}");
        let mut expected = harness("bad", &[], bad);
        expected.should_panic = true;
        assert_eq!(expected.explore().verdict(), Ok(()));
        fn fine() {
            let _: bool = any();
        }
        let mut never_fails = harness("fine", &[], fine);
        never_fails.should_panic = true;
        assert!(never_fails
            .explore()
            .verdict()
            .unwrap_err()
            .contains("expected to fail"));
        fn overflows() {
            let v: u8 = any();
            let _ = std::hint::black_box(v) + 255;
        }
        if __panics(|| {
            let _ = std::hint::black_box(u8::MAX) + 1;
        }) {
            let mut o = harness("overflows", &[], overflows);
            o.should_panic = true;
            let s = o.explore();
            assert_eq!(s.verdict(), Ok(()), "{s}");
            assert!(s.overflow.as_deref().unwrap().starts_with("attempt to add"));
            // Not should_panic: the overflow fails the harness.
            let s = harness("overflows", &[], overflows).explore();
            assert!(s.verdict().unwrap_err().contains("attempt to add"));
        }
    }

    /// `halve(x)` guarantees an exact half of an even input (a wrong variant breaks it).
    #[requires(x % 2 == 0)]
    #[ensures(|r: &i32| *r + *r == x)]
    fn halve(x: i32) -> i32 {
        x / 2
    }

    #[requires(x % 2 == 0)]
    #[ensures(|r: &i32| *r + *r == x)]
    fn halve_wrongly(x: i32) -> i32 {
        if x == 6 {
            return 2; // planted: `return` inside the body is checked too
        }
        x / 2
    }

    /// `bump(v, i)` adds one to `v[i]` and leaves the rest (`old` is the value before the call).
    #[requires(i < v.len())]
    #[modifies(v)]
    #[ensures(|_| (0..v.len()).all(|k| v[k] == old(*v)[k] + u8::from(k == i)))]
    fn bump(v: &mut [u8; 3], i: usize) {
        v[i] += 1;
    }

    fn with_contract(name: &'static str, contract: Option<&'static str>, body: fn()) -> Summary {
        Harness {
            contract,
            ..harness(name, &[], body)
        }
        .explore()
    }

    /// Outside a run a contract changes nothing (no check: `halve(3)` is `1`); inside a run a
    /// caller that violates the precondition fails, a body that breaks the postcondition
    /// fails, and under `proof_for_contract` the precondition prunes instead.
    #[test]
    fn contracts_are_checked_only_inside_runs() {
        assert_eq!(halve(3), 1);
        assert_eq!(halve_wrongly(6), 2);
        assert!(!__contract_checks());
        fn caller_violates() {
            let x: u8 = any();
            let _ = halve(i32::from(x));
        }
        let s = with_contract("caller_violates", None, caller_violates);
        assert!(
            s.verdict()
                .unwrap_err()
                .contains("precondition of halve violated"),
            "{s}"
        );
        assert_eq!(s.failures, 128);
        fn proves_halve() {
            let x: u8 = any();
            let _ = halve(i32::from(x));
        }
        let s = with_contract("proves_halve", Some("halve"), proves_halve);
        assert_eq!(s.verdict(), Ok(()), "{s}");
        assert_eq!((s.pruned, s.contract_calls), (128, 128), "{s}");
        fn proves_wrong() {
            let x: u8 = any();
            let _ = halve_wrongly(i32::from(x));
        }
        let s = with_contract("proves_wrong", Some("self::halve_wrongly"), proves_wrong);
        let why = s.verdict().unwrap_err();
        assert!(
            why.contains("postcondition of halve_wrongly violated"),
            "{why}"
        );
        assert_eq!((s.failures, s.first_failure.unwrap().choices), (1, vec![6]));
        // A proof_for_contract run that never calls its function proves nothing.
        fn never_calls() {
            let _: bool = any();
        }
        let s = with_contract("never_calls", Some("halve"), never_calls);
        assert!(s
            .verdict()
            .unwrap_err()
            .contains("no non-pruned execution calls it"));
        // The target is matched by name and module: another module's `halve` is not it.
        let s = with_contract("other", Some("elsewhere::halve"), proves_halve);
        assert!(s.verdict().is_err(), "{s}");
    }

    /// `old(e)` is `e` before the call: the frame condition of `bump` holds, and a body that
    /// writes a second entry would break it.
    #[test]
    fn old_values_are_taken_before_the_body() {
        fn bumps() {
            let mut v: [u8; 3] = [any::<bool>().into(), 5, 7];
            let i = usize::from(any::<bool>());
            bump(&mut v, i);
            assert(v[2] == 7, "v[2] untouched");
        }
        let s = with_contract("bumps", Some("bump"), bumps);
        assert_eq!((s.verdict(), s.contract_calls), (Ok(()), 4), "{s}");
        assert!(path_names(
            "crate::tests::bump",
            "kani_standin::tests",
            "bump"
        ));
        assert!(path_names(
            "truecost_kernel::claims::exact::Q::<i16>::checked_add",
            "truecost_kernel::claims::exact",
            "checked_add"
        ));
        assert!(!path_names(
            "truecost_kernel::value::Units::checked_add",
            "truecost_kernel::claims::exact",
            "checked_add"
        ));
    }
}
