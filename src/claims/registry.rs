//! The claims registry (issue 5, item 1): every claim with its statement, the engines that
//! check it, and the Kani harnesses of `proofs/` that state it for symbolic checking.

use std::time::Instant;

use super::harnesses::harness_runs;
use super::report::{AlphaStar, Report};
use super::sampled::{self, PropertyRun};
use super::{alpha, c1, c2, c3, c4, ClaimResult, Counterexample, Scope, Verdict};

/// The claim ids, in report order.
pub const IDS: [&str; 7] = [
    "C1",
    "C1-corrected",
    "C2",
    "C3",
    "C3-example",
    "C4",
    "C4-corrected",
];

fn selected(id: &str, only: Option<&str>) -> bool {
    match only {
        None => true,
        Some(o) => id == o || (id.starts_with(o) && id[o.len()..].starts_with('-')),
    }
}

fn attach(result: &mut ClaimResult, prop: Option<(PropertyRun, f64)>) {
    result.engines.extend(harness_runs(&result.id));
    let Some((p, seconds)) = prop else { return };
    result.engines.push(p.engine_run(seconds));
    if let Some((t, what)) = &p.counterexample {
        let text = format!(
            "proptest shrank a counterexample: {what} ({})",
            t.describe()
        );
        if result.id == "C3" {
            // An existential claim: a structure without a certificate is not a refutation.
            result.verdict = Verdict::Inconclusive;
        } else if result.verdict == Verdict::Verified {
            result.verdict = Verdict::Refuted;
            result.engine = "proptest".into();
            result.counterexample = Some(Counterexample::new(
                t,
                format!("{} counterexample (proptest): {what}", result.id),
                vec![],
                &format!("{}-proptest", result.id.to_lowercase()),
            ));
        }
        result.notes.push(text);
    }
}

fn timed<T>(f: impl FnOnce() -> T) -> (T, f64) {
    let s = Instant::now();
    let v = f();
    (v, s.elapsed().as_secs_f64())
}

/// Runs the selected claims (all when `only` is `None`; `C1` selects `C1` and `C1-corrected`).
pub fn run(scope: Scope, only: Option<&str>) -> Result<Report, String> {
    if let Some(o) = only {
        if !IDS.iter().any(|id| selected(id, Some(o))) {
            return Err(format!("unknown claim '{o}' (known: {})", IDS.join(", ")));
        }
    }
    let n = sampled::cases(scope);
    let mut claims = Vec::new();
    if selected("C1", only) || selected("C1-corrected", only) {
        let (mut a, mut b) = c1::check(scope);
        if selected("C1", only) {
            attach(&mut a, Some(timed(|| sampled::c1_printed(n, None))));
            claims.push(a);
        }
        if selected("C1-corrected", only) {
            attach(&mut b, Some(timed(|| sampled::c1_corrected(n, None))));
            claims.push(b);
        }
    }
    if selected("C2", only) {
        let mut a = c2::check(scope);
        attach(&mut a, Some(timed(|| sampled::c2(n, None))));
        claims.push(a);
    }
    if selected("C3", only) {
        let mut a = c3::check(scope);
        attach(&mut a, Some(timed(|| sampled::c3(n, None))));
        claims.push(a);
    }
    let (mut example, star) = alpha::check();
    if selected("C3-example", only) {
        attach(&mut example, None);
        claims.push(example);
    }
    if selected("C4", only) || selected("C4-corrected", only) {
        let (mut a, mut b) = c4::check(scope);
        if selected("C4", only) {
            attach(&mut a, Some(timed(|| sampled::c4(true, n, None))));
            claims.push(a);
        }
        if selected("C4-corrected", only) {
            attach(&mut b, Some(timed(|| sampled::c4(false, n, None))));
            claims.push(b);
        }
    }
    let alpha_star = star.map(|a| AlphaStar::new(&a));
    Ok(Report {
        tool: format!("truecost {}", env!("CARGO_PKG_VERSION")),
        commit: option_env!("TRUECOST_GIT_COMMIT")
            .unwrap_or("unknown")
            .to_string(),
        scope,
        claims,
        alpha_star,
    })
}
