//! Engine failures: a panic in an engine caught as one line describing it ([`caught`]), raised
//! again through the levels above ([`raise`]), and the prefix that marks it in a report
//! ([`ENGINE_FAILED`]). The runner wraps every engine in [`caught`], and the harness and
//! proptest engines wrap each case.

use std::any::Any;
use std::collections::VecDeque;
use std::panic::{catch_unwind, resume_unwind, AssertUnwindSafe};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Mutex, Once};

/// The prefix of an engine line's mode when the engine panicked (the panic's message follows),
/// and of a shard entry's value when the site's work panicked (never JSON, so never a value).
pub const ENGINE_FAILED: &str = "engine failed: ";

/// A panic already caught and described: raised again through the levels above the one that
/// caught it (a shard's site, a proptest run), which keep its description.
struct Described(String);

/// Engines running under [`caught`] now (the panic hook is silent while there are any).
static CATCHING: AtomicUsize = AtomicUsize::new(0);
/// Whether the stand-in's panic hook was installed before [`caught`]'s (which then passes
/// every panic on to it, since it records where the harness bodies it runs panic).
static OUTERMOST: AtomicBool = AtomicBool::new(false);
/// The latest panics under [`caught`] that reached the hook (at most [`RECENT_PANICS`]): their
/// messages and locations, for [`caught`] to find where the panic it caught happened.
static RECENT: Mutex<VecDeque<(String, String)>> = Mutex::new(VecDeque::new());
const RECENT_PANICS: usize = 256;

/// The payload of the panic that asks whether the stand-in's hook is above [`caught`]'s.
struct Probe;

fn message_of(payload: &(dyn Any + Send)) -> String {
    payload
        .downcast_ref::<&str>()
        .map(|s| s.to_string())
        .or_else(|| payload.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "a panic without a message".into())
}

fn install_hook() {
    static INSTALL: Once = Once::new();
    INSTALL.call_once(|| {
        let previous = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            if info.payload().is::<Probe>() {
                OUTERMOST.store(true, Ordering::SeqCst);
                return;
            }
            if CATCHING.load(Ordering::SeqCst) == 0 {
                return previous(info);
            }
            // A panic of a harness body that the stand-in runs silently (on any thread, during
            // any catch) is the stand-in's to record: recorded here it would crowd out the
            // places of the panics being caught.
            if truecost_proofs::standin::__quiet() {
                if OUTERMOST.load(Ordering::SeqCst) {
                    previous(info);
                }
                return;
            }
            let at = info.location().map_or(String::new(), |l| l.to_string());
            let mut recent = RECENT.lock().unwrap_or_else(|e| e.into_inner());
            if recent.len() == RECENT_PANICS {
                recent.pop_front();
            }
            recent.push_back((message_of(info.payload()), at));
            drop(recent);
            if OUTERMOST.load(Ordering::SeqCst) {
                previous(info);
            }
        }));
        // The stand-in installs its hook over this one unless it did already: a silenced probe
        // panic reaches this hook only in that case.
        truecost_proofs::standin::__panics(|| std::panic::panic_any(Probe));
    });
}

/// Runs `f`, an engine, and catches a panic in it — on this thread or on a rayon worker whose
/// work it waits for (rayon raises a worker's panic again in the caller) — as its description:
/// the panic message and where it panicked, escaped to one line. No panic message reaches
/// stderr meanwhile (unless the stand-in's hook was installed first: it then prints them).
///
/// ```
/// use truecost::claims::caught::caught;
/// assert_eq!(caught(|| 6 * 7), Ok(42));
/// let failure = caught(|| -> u8 { panic!("value out of range\nsecond line") }).unwrap_err();
/// assert!(failure.starts_with("value out of range\\nsecond line (at "), "{failure}");
/// ```
pub fn caught<T>(f: impl FnOnce() -> T) -> Result<T, String> {
    install_hook();
    if CATCHING.fetch_add(1, Ordering::SeqCst) == 0 {
        RECENT.lock().unwrap_or_else(|e| e.into_inner()).clear();
    }
    let result = catch_unwind(AssertUnwindSafe(f));
    // The panic's place is read before this catch ends: a catch that starts once none is
    // running (on another thread) clears the places recorded.
    let result = result.map_err(|payload| {
        if let Some(Described(text)) = payload.downcast_ref::<Described>() {
            return text.clone();
        }
        let message = message_of(&*payload);
        let at = RECENT
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .iter()
            .rev()
            .find(|(m, l)| *m == message && !l.is_empty())
            .map(|(_, l)| format!(" (at {l})"))
            .unwrap_or_default();
        crate::echo::one_line(&format!("{message}{at}"))
    });
    CATCHING.fetch_sub(1, Ordering::SeqCst);
    result
}

/// Raises a failure that [`caught`] described again, to the [`caught`] around the engine (its
/// description kept; no panic message printed).
pub fn raise(failure: String) -> ! {
    resume_unwind(Box::new(Described(failure)))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An engine that panics, on the calling thread or on a rayon worker (the panic raised
    /// again in the caller by rayon), is caught as its message and location; one that does
    /// not returns its value; a failure raised again keeps its description through a second
    /// [`caught`].
    #[test]
    fn a_panicking_engine_is_caught_with_its_message_and_location() {
        use rayon::prelude::*;
        assert_eq!(caught(|| 6 * 7), Ok(42));
        let here = caught(|| -> u8 { panic!("planted: {}", 3) }).unwrap_err();
        assert!(
            here.starts_with("planted: 3 (at src/claims/caught.rs:"),
            "{here}"
        );
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(2)
            .build()
            .unwrap();
        let on_worker = caught(|| {
            pool.install(|| {
                (0..10_000u32)
                    .into_par_iter()
                    .map(|i| {
                        assert!(i != 7_777, "planted at {i}");
                        u64::from(i)
                    })
                    .sum::<u64>()
            })
        })
        .unwrap_err();
        assert!(
            on_worker.starts_with("planted at 7777 (at src/claims/caught.rs:"),
            "{on_worker}"
        );
        let again = caught(|| caught(|| -> u8 { panic!("inner") }).unwrap_or_else(|f| raise(f)));
        assert!(again.unwrap_err().starts_with("inner (at "));
    }
}
