//! The fixed-iteration mode shared by `benches/planners.rs` and `benches/learning.rs`: with
//! `TRUECOST_BENCH_ITERATIONS=N` a bench binary runs each of its rows `N` times without
//! criterion (for callgrind counts), `TRUECOST_BENCH_ONLY=<row>` selects one row, and
//! `TRUECOST_BENCH_REPORT=1` times every call on its own (docs/speed.md, side-by-side rounds).

use std::time::{Duration, Instant};

/// `TRUECOST_BENCH_ITERATIONS`, if set: run each row this many times and exit.
pub fn fixed_iterations() -> Option<u64> {
    std::env::var("TRUECOST_BENCH_ITERATIONS")
        .ok()
        .map(|v| v.parse().expect("TRUECOST_BENCH_ITERATIONS is a count"))
}

/// Whether `row` runs: every row unless `TRUECOST_BENCH_ONLY` names another.
pub fn wanted(row: &str) -> bool {
    std::env::var("TRUECOST_BENCH_ONLY").map_or(true, |only| only == row)
}

/// Calls `run` `iterations` times, each call timed on its own; returns the last call's result
/// and, when `TRUECOST_BENCH_REPORT` is set and there was a call, the median and minimum time.
pub fn timed_calls<T>(
    iterations: u64,
    mut run: impl FnMut() -> T,
) -> (Option<T>, Option<(Duration, Duration)>) {
    let mut times = Vec::with_capacity(iterations as usize);
    let mut last = None;
    for _ in 0..iterations {
        let start = Instant::now();
        last = Some(std::hint::black_box(run()));
        times.push(start.elapsed());
    }
    times.sort();
    let report = std::env::var_os("TRUECOST_BENCH_REPORT").is_some() && !times.is_empty();
    (last, report.then(|| (times[times.len() / 2], times[0])))
}
