//! The only clock of the project: wall time measured around a call by a runner (docs/spec.md §4, run
//! times), never inside an algorithm.

use std::time::Instant;

/// Wall time since it was started.
///
/// ```
/// let watch = truecost::experiments::clock::Stopwatch::start();
/// let t = watch.seconds();
/// assert!(t >= 0.0);
/// ```
#[derive(Clone, Copy, Debug)]
pub struct Stopwatch {
    start: Instant,
}

impl Stopwatch {
    /// Starts now.
    pub fn start() -> Self {
        Stopwatch {
            start: Instant::now(),
        }
    }

    /// Seconds elapsed.
    pub fn seconds(&self) -> f64 {
        self.start.elapsed().as_secs_f64()
    }
}

/// Runs `f`, returning its result and the wall time it took in seconds.
///
/// ```
/// let (x, t) = truecost::experiments::clock::timed(|| 6 * 7);
/// assert_eq!(x, 42);
/// assert!(t >= 0.0);
/// ```
pub fn timed<T>(f: impl FnOnce() -> T) -> (T, f64) {
    let watch = Stopwatch::start();
    let result = f();
    (result, watch.seconds())
}
