//! The `truecost verify` report and its renderings: text, JSON, Markdown and
//! a LaTeX table. Times appear only when asked for (`with_times`), so the report without them
//! is reproducible byte for byte and pinned by a snapshot.

use std::fmt::Write;

use serde_json::{json, Value};

use super::{ClaimResult, Scope};
use crate::algebra::intervals::rat;
use crate::algebra::poly::Algebraic;

/// `α*` of the worked example of C3.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct AlphaStar {
    /// Lower end of the bracket (`p/q`).
    pub lo: String,
    /// Upper end of the bracket (`p/q`).
    pub hi: String,
    /// The polynomial whose root it is.
    pub polynomial: String,
    /// Rounded to nearest at 30 decimals.
    pub decimal: String,
}

impl AlphaStar {
    /// From the isolated root.
    pub fn new(a: &Algebraic) -> AlphaStar {
        AlphaStar {
            lo: rat(&a.lo),
            hi: rat(&a.hi),
            polynomial: a.poly.primitive().to_string(),
            decimal: a.decimal_rounded(30),
        }
    }
}

/// The command that shows a counterexample's failure: its own replay, or
/// the exact solve of its problem file.
fn replay_command(ce: &super::Counterexample) -> String {
    ce.replay
        .clone()
        .unwrap_or_else(|| format!("truecost solve --file {} --algorithm dijkstra", ce.file))
}

/// What `verify` did with the Kani harnesses of `proofs/`: one line, and the engine lines of the
/// harnesses on truecost's own code that state no claim of the report (the claims' own
/// harnesses are among each claim's engines).
#[derive(Clone, Debug, PartialEq)]
pub struct HarnessSection {
    /// What ran (or that nothing did), how many failed; never a Kani result.
    pub summary: String,
    /// The lemma harnesses (solvers, exact value types), when every claim was selected.
    pub lemmas: Vec<super::EngineRun>,
    /// Whether this build checks integer overflow, for each crate whose code the harnesses
    /// run, as each crate's own probe answers (`None`: nothing ran). Shown with times only: a
    /// property of the build, like the solver's version.
    pub overflow_checks: Option<Vec<(&'static str, bool)>>,
}

impl HarnessSection {
    /// The summary, and with times which crates of this build check overflow.
    ///
    /// ```
    /// use truecost::claims::report::HarnessSection;
    /// let section = |crates: Vec<(&'static str, bool)>| HarnessSection {
    ///     summary: "2 harnesses".into(),
    ///     lemmas: vec![],
    ///     overflow_checks: Some(crates),
    /// };
    /// let both = section(vec![("a", true), ("b", true)]);
    /// assert_eq!(both.line(true), "2 harnesses; overflow checks on in a and b");
    /// assert_eq!(both.line(false), "2 harnesses");
    /// assert_eq!(
    ///     section(vec![("a", true), ("b", false)]).line(true),
    ///     "2 harnesses; overflow checks are OFF in b in this build (an overflow there wraps instead of failing); on in a"
    /// );
    /// ```
    pub fn line(&self, with_times: bool) -> String {
        let Some(crates) = self.overflow_checks.as_ref().filter(|_| with_times) else {
            return self.summary.clone();
        };
        let names = |checked: bool| -> String {
            crates
                .iter()
                .filter(|(_, c)| *c == checked)
                .map(|(name, _)| *name)
                .collect::<Vec<_>>()
                .join(" and ")
        };
        let (on, off) = (names(true), names(false));
        match (on.is_empty(), off.is_empty()) {
            (_, true) => format!("{}; overflow checks on in {on}", self.summary),
            (true, false) => format!(
                "{}; overflow checks are OFF in {off} in this build (an overflow there wraps instead of failing)",
                self.summary
            ),
            (false, false) => format!(
                "{}; overflow checks are OFF in {off} in this build (an overflow there wraps instead of failing); on in {on}",
                self.summary
            ),
        }
    }
}

/// The text of an engine line: what the engine checked (Markdown's claim lines with a colon
/// after the mode), or that it failed.
fn engine_text(e: &super::EngineRun, with_times: bool, colon: bool) -> String {
    if e.mode.starts_with(super::caught::ENGINE_FAILED) {
        return format!("{}: {}", e.engine, e.mode);
    }
    let t = if with_times && e.seconds > 0.0 {
        format!(", {}", rate(e.cases, e.seconds, &e.engine))
    } else {
        String::new()
    };
    let colon = if colon { ":" } else { "" };
    format!(
        "{} [{}]{colon} {} cases, {} failures{t}",
        e.engine, e.mode, e.cases, e.failures
    )
}

/// The whole report.
#[derive(Clone, Debug, PartialEq)]
pub struct Report {
    /// `truecost <version>`.
    pub tool: String,
    /// The git commit the binary was built from (or `unknown`).
    pub commit: String,
    /// The scope run.
    pub scope: Scope,
    /// The claims, in registry order.
    pub claims: Vec<ClaimResult>,
    /// `α*` (C3's worked example).
    pub alpha_star: Option<AlphaStar>,
    /// The SMT solver and its version, when the SMT engine ran (shown with times only: it is
    /// a property of the machine).
    pub solver: Option<String>,
    /// The SMT engine's outcomes, every obligation with its answer (for `--smt-out`).
    pub smt: Vec<super::smt::Outcome>,
    /// The Coq engine's re-check, when it was asked for (`None`: not asked; the report then
    /// says nothing about Coq).
    pub coq: Option<super::coq::Check>,
    /// The Kani harnesses run by the stand-in in this process (`None`: a report built without
    /// the registry says nothing about them).
    pub harnesses: Option<HarnessSection>,
}

/// One line on the Coq re-check: what ran, with which Coq, and what it found (the time only
/// `with_times`).
///
/// ```
/// use truecost::claims::coq::{Check, Outcome};
/// use truecost::claims::report::coq_line;
/// let absent = Check {
///     version: None,
///     outcome: Outcome::NotAvailable("coqc not found".into()),
///     theorems: vec![],
///     files: 0,
///     seconds: 0.0,
/// };
/// assert_eq!(
///     coq_line(&absent, false),
///     "the Coq proofs (proofs/coq) were NOT re-checked on this machine: coqc not found"
/// );
/// ```
pub fn coq_line(check: &super::coq::Check, with_times: bool) -> String {
    use super::coq::Outcome;
    let time = if with_times && check.seconds > 0.0 {
        format!(" ({:.1} s)", check.seconds)
    } else {
        String::new()
    };
    let accepted = check.theorems.iter().filter(|t| t.accepted()).count();
    match &check.outcome {
        Outcome::Checked => format!(
            "the Coq proofs (proofs/coq) re-checked in this run by coqc ({}): {} files compiled, {accepted} of {} \
theorems accepted (statement and Print Assumptions as pinned){time}",
            check.coq(),
            check.files,
            check.theorems.len()
        ),
        Outcome::NotAvailable(why) => {
            format!("the Coq proofs (proofs/coq) were NOT re-checked on this machine: {why}")
        }
        Outcome::NotCoq(what) => format!(
            "the Coq proofs (proofs/coq) were NOT re-checked: coqc did not behave as Coq ({what}){time}"
        ),
        Outcome::TimedOut(what) => {
            format!("the Coq proofs (proofs/coq) were NOT re-checked: {what}{time}")
        }
        Outcome::SourcesRefused(found) => format!(
            "the Coq proofs (proofs/coq) were refused before compiling: {}{time}",
            found.join(", ")
        ),
        Outcome::BuildFailed(why) => format!(
            "the Coq proofs (proofs/coq) did not fully build with coqc ({}): {why}; {} files compiled before it, \
{accepted} of {} theorems accepted (statement and Print Assumptions as pinned){time}",
            check.coq(),
            check.files,
            check.theorems.len()
        ),
    }
}

/// The Coq re-check as JSON: the line, the outcome, and every theorem of the table with its
/// claim, file, what it quantifies over, its statement in words, its statement in Coq
/// (`coq_statement`: as `Check` printed it in this run, or the pinned one when it was not
/// re-checked), what it is weaker than the paper's, and its assumptions.
fn coq_json(check: &super::coq::Check, with_times: bool) -> Value {
    use super::coq::THEOREMS;
    let pins = super::coq::pins().unwrap_or_default();
    let theorems: Vec<Value> = THEOREMS
        .iter()
        .map(|t| {
            let a = check.theorem(t.name);
            let printed = a.and_then(|a| a.statement.clone());
            let pinned = pins
                .iter()
                .find(|p| p.name == t.name)
                .map(|p| p.statement.clone());
            json!({
                "claim": t.claim,
                "theorem": t.name,
                "file": t.file,
                "about": t.scope.describe(),
                "statement": t.statement,
                "coq_statement": printed.clone().or(pinned),
                "coq_statement_from": if printed.is_some() { "Check, in this run" } else { "pinned (not printed in this run)" },
                "weaker_than_paper": t.weaker,
                "rechecked": a.is_some(),
                "accepted": a.is_some_and(|a| a.accepted()),
                "assumptions": a.map(|a| a.assumptions.describe()),
                "refused": a.and_then(|a| a.refused.clone()),
            })
        })
        .collect();
    let mut v = json!({
        "summary": coq_line(check, false),
        "coq_version": check.version,
        "rechecked": check.outcome == super::coq::Outcome::Checked,
        "files": check.files,
        "theorems": theorems,
    });
    if with_times {
        v["seconds"] = json!(check.seconds);
    }
    v
}

fn rate(cases: u64, seconds: f64, engine: &str) -> String {
    let what = if engine.starts_with("smt") {
        "obligations/s"
    } else {
        "cases/s"
    };
    if seconds <= 0.0 {
        "n/a".into()
    } else {
        format!("{:.0} {what}", cases as f64 / seconds)
    }
}

fn engine_json(e: &super::EngineRun, with_times: bool) -> Value {
    let mut v = serde_json::to_value(e).expect("serialisable");
    if with_times && e.seconds > 0.0 {
        v["seconds"] = json!(e.seconds);
        v["cases_per_second"] = json!(e.cases as f64 / e.seconds);
    }
    v
}

fn engine_line(e: &super::EngineRun, with_times: bool) -> String {
    engine_text(e, with_times, false)
}

/// The report as JSON: `{"claims": [{"id", "statement", "verdict", "engine", "scope", "cases",
/// "counterexample", ...}], "alpha_star": {"lo", "hi"}, ...}`.
pub fn json(report: &Report, with_times: bool) -> String {
    let claims: Vec<Value> = report
        .claims
        .iter()
        .map(|c| {
            let mut v = serde_json::to_value(c).expect("serialisable");
            let obj = v.as_object_mut().expect("object");
            obj.insert("verdict".into(), json!(c.verdict.name()));
            if let Some(ce) = &c.counterexample {
                obj.insert(
                    "counterexample".into(),
                    json!({
                        "summary": ce.summary,
                        "problem": ce.problem,
                        "details": ce.details.iter().map(|(k, v)| json!({"name": k, "value": v})).collect::<Vec<_>>(),
                        "file": ce.file,
                        "replay": replay_command(ce),
                        "problem_file": serde_json::from_str::<Value>(&ce.problem_file).expect("valid problem file"),
                    }),
                );
            }
            if with_times {
                let engines = obj.get_mut("engines").and_then(Value::as_array_mut).expect("engines");
                for (e, run) in engines.iter_mut().zip(&c.engines) {
                    if run.seconds > 0.0 {
                        e["seconds"] = json!(run.seconds);
                        e["cases_per_second"] = json!(run.cases as f64 / run.seconds);
                    }
                }
            }
            v
        })
        .collect();
    let mut root = json!({
        "tool": report.tool,
        "scope": report.scope.name(),
        "claims": claims,
        "alpha_star": report.alpha_star.as_ref().map(|a| json!({
            "lo": a.lo, "hi": a.hi, "polynomial": a.polynomial, "decimal": a.decimal,
        })),
    });
    if let Some(check) = &report.coq {
        root["coq"] = coq_json(check, with_times);
    }
    if let Some(h) = &report.harnesses {
        root["harnesses"] = json!({
            "summary": h.line(with_times),
            "lemmas": h.lemmas.iter().map(|e| engine_json(e, with_times)).collect::<Vec<_>>(),
        });
    }
    if with_times {
        root["commit"] = json!(report.commit);
        if let Some(solver) = &report.solver {
            root["solver"] = json!(solver);
        }
    }
    let mut s = serde_json::to_string_pretty(&root).expect("serialisable");
    s.push('\n');
    s
}

/// The report as text.
pub fn text(report: &Report, with_times: bool) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "{} - the paper's four propositions (docs/spec.md), scope {}",
        report.tool,
        report.scope.name()
    );
    if with_times {
        let _ = writeln!(s, "commit {}", report.commit);
        if let Some(solver) = &report.solver {
            let _ = writeln!(s, "smt solver: {solver}");
        }
    }
    if let Some(check) = &report.coq {
        let _ = writeln!(s, "coq: {}", coq_line(check, with_times));
    }
    if let Some(h) = &report.harnesses {
        let _ = writeln!(s, "harnesses: {}", h.line(with_times));
    }
    for c in &report.claims {
        let _ = writeln!(s);
        let _ = writeln!(s, "{}  {}", c.id, c.verdict.name().to_uppercase());
        let _ = writeln!(s, "  statement: {}", c.statement);
        let _ = writeln!(s, "  decided by: {} ({} cases)", c.engine, c.cases);
        let _ = writeln!(s, "  scope: {}", c.scope);
        for e in &c.engines {
            let _ = writeln!(s, "  engine: {}", engine_line(e, with_times));
        }
        if let Some(ce) = &c.counterexample {
            let _ = writeln!(s, "  counterexample: {}", ce.summary);
            let _ = writeln!(s, "    problem (x1 = 0, goal = last state): {}", ce.problem);
            for (k, v) in &ce.details {
                let _ = writeln!(s, "    {k}: {v}");
            }
            let _ = writeln!(s, "    replay: {}", replay_command(ce));
        }
        for n in &c.notes {
            let _ = writeln!(s, "  note: {n}");
        }
    }
    if let Some(h) = report.harnesses.as_ref().filter(|h| !h.lemmas.is_empty()) {
        let _ = writeln!(s);
        let _ = writeln!(
            s,
            "kani harnesses on truecost's own code (lemmas the claims' engines rely on)"
        );
        for e in &h.lemmas {
            let _ = writeln!(s, "  engine: {}", engine_line(e, with_times));
            let _ = writeln!(s, "    scope: {}", e.scope);
        }
    }
    if let Some(a) = &report.alpha_star {
        let _ = writeln!(s);
        let _ = writeln!(
            s,
            "alpha* = {} (rounded to nearest; root of {} in (0,1))",
            a.decimal, a.polynomial
        );
        let _ = writeln!(s, "  lo = {}", a.lo);
        let _ = writeln!(s, "  hi = {}", a.hi);
    }
    s
}

/// The report as Markdown.
pub fn markdown(report: &Report, with_times: bool) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "# {} - the paper's four propositions (docs/spec.md), scope {}\n",
        report.tool,
        report.scope.name()
    );
    if with_times {
        if let Some(solver) = &report.solver {
            let _ = writeln!(s, "SMT solver: {solver}\n");
        }
    }
    if let Some(check) = &report.coq {
        let _ = writeln!(s, "Coq: {}\n", coq_line(check, with_times));
    }
    if let Some(h) = &report.harnesses {
        let _ = writeln!(s, "Kani harnesses: {}\n", h.line(with_times));
    }
    let _ = writeln!(s, "| claim | verdict | engine | cases | scope |");
    let _ = writeln!(s, "|---|---|---|---|---|");
    for c in &report.claims {
        let _ = writeln!(
            s,
            "| {} | {} | {} | {} | {} |",
            c.id,
            c.verdict.name(),
            c.engine,
            c.cases,
            c.scope.replace('|', "/")
        );
    }
    for c in &report.claims {
        let _ = writeln!(
            s,
            "\n## {} ({})\n\n{}\n",
            c.id,
            c.verdict.name(),
            c.statement
        );
        for e in &c.engines {
            let _ = writeln!(s, "- {}", engine_text(e, with_times, true));
        }
        if let Some(ce) = &c.counterexample {
            let _ = writeln!(
                s,
                "\n**Counterexample.** {}\n\n- problem: `{}`",
                ce.summary, ce.problem
            );
            for (k, v) in &ce.details {
                let _ = writeln!(s, "- {k}: `{v}`");
            }
            let _ = writeln!(s, "- file: `{}`", ce.file);
            let _ = writeln!(s, "- replay: `{}`", replay_command(ce));
        }
        for n in &c.notes {
            let _ = writeln!(s, "- note: {n}");
        }
    }
    if let Some(h) = report.harnesses.as_ref().filter(|h| !h.lemmas.is_empty()) {
        let _ = writeln!(s, "\n## Kani harnesses on truecost's own code\n");
        for e in &h.lemmas {
            let _ = writeln!(s, "- {}", engine_line(e, with_times));
        }
    }
    if let Some(a) = &report.alpha_star {
        let _ = writeln!(
            s,
            "\n## alpha*\n\n`{}` (rounded to nearest) is the root of `{}` in (0,1), in `({}, {}]`.",
            a.decimal, a.polynomial, a.lo, a.hi
        );
    }
    s
}

/// Text escaped for LaTeX ([`crate::echo::tex_special`]).
fn tex(s: &str) -> String {
    s.chars()
        .map(|c| crate::echo::tex_special(c).map_or_else(|| c.to_string(), str::to_string))
        .collect()
}

/// The report as a LaTeX table (booktabs), with the tool version and git commit.
pub fn latex(report: &Report) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "% {} (commit {}), truecost verify --scope {}",
        report.tool,
        report.commit,
        report.scope.name()
    );
    let _ = writeln!(s, "\\begin{{table}}[t]\n\\centering\\small");
    let _ = writeln!(s, "\\begin{{tabular}}{{llrl}}\n\\toprule");
    let _ = writeln!(s, "Claim & Verdict & Cases & Engine \\\\\n\\midrule");
    for c in &report.claims {
        let _ = writeln!(
            s,
            "{} & {} & {} & {} \\\\",
            tex(&c.id),
            c.verdict.name(),
            c.cases,
            tex(&c.engine)
        );
    }
    let _ = writeln!(s, "\\bottomrule\n\\end{{tabular}}");
    let alpha = report
        .alpha_star
        .as_ref()
        .map(|a| format!(" $\\alpha^* \\approx {}$.", a.decimal))
        .unwrap_or_default();
    let _ = writeln!(
        s,
        "\\caption{{Machine-checked claims ({}, commit \\texttt{{{}}}, scope {}{}).{alpha}}}",
        tex(&report.tool),
        tex(&report.commit[..report.commit.len().min(12)]),
        report.scope.name(),
        report
            .solver
            .as_ref()
            .map(|v| format!("; SMT solver {}", tex(v)))
            .unwrap_or_default()
            + &report
                .coq
                .as_ref()
                .filter(|c| c.outcome == super::coq::Outcome::Checked)
                .map(|c| format!("; Coq proofs re-checked by {}", tex(&c.coq())))
                .unwrap_or_default()
    );
    let _ = writeln!(s, "\\end{{table}}");
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::claims::{EngineRun, Verdict};

    /// One claim with a timed engine run (10 cases in 2 s: 5 cases/s), an SMT run (6
    /// obligations in 3 s) and an engine run that reports no time (0 s: no rate at all, not
    /// "n/a"), under a tool name and commit that need escaping in LaTeX.
    fn report() -> Report {
        let run = |engine: &str, cases, seconds| EngineRun {
            engine: engine.into(),
            mode: "exhaustive".into(),
            scope: "s".into(),
            cases,
            failures: 0,
            seconds,
        };
        Report {
            tool: "truecost_0.1".into(),
            commit: "abc#def0123456789".into(),
            scope: Scope::Smoke,
            claims: vec![ClaimResult {
                id: "C2_x".into(),
                statement: "st".into(),
                verdict: Verdict::Verified,
                engine: "exhaustive enumeration".into(),
                scope: "a | b".into(),
                cases: 10,
                counterexample: None,
                engines: vec![
                    run("exhaustive enumeration", 10, 2.0),
                    run("smt (z3)", 6, 3.0),
                    run("kani stand-in", 7, 0.0),
                ],
                notes: vec!["n".into()],
            }],
            alpha_star: None,
            solver: None,
            smt: vec![],
            coq: None,
            harnesses: None,
        }
    }

    #[test]
    fn rates_only_for_engine_runs_with_a_time() {
        let r = report();
        let v: Value = serde_json::from_str(&json(&r, true)).unwrap();
        let engines = v["claims"][0]["engines"].as_array().unwrap();
        assert_eq!(engines[0]["seconds"], json!(2.0));
        assert_eq!(engines[0]["cases_per_second"], json!(5.0));
        assert_eq!(engines[1]["cases_per_second"], json!(2.0));
        assert!(engines[2].get("seconds").is_none(), "{}", engines[2]);
        assert!(engines[2].get("cases_per_second").is_none());
        let untimed: Value = serde_json::from_str(&json(&r, false)).unwrap();
        assert!(untimed["claims"][0]["engines"][0].get("seconds").is_none());

        // Every line checked whole, with its newline: a rate of "n/a" would fail too.
        let has = |rendered: &str, line: &str| assert!(rendered.contains(line), "{rendered}");
        let t = text(&r, true);
        has(
            &t,
            "  engine: exhaustive enumeration [exhaustive] 10 cases, 0 failures, 5 cases/s\n",
        );
        has(
            &t,
            "  engine: smt (z3) [exhaustive] 6 cases, 0 failures, 2 obligations/s\n",
        );
        has(
            &t,
            "  engine: kani stand-in [exhaustive] 7 cases, 0 failures\n",
        );
        assert!(!text(&r, false).contains("cases/s"));

        let m = markdown(&r, true);
        has(
            &m,
            "- exhaustive enumeration [exhaustive]: 10 cases, 0 failures, 5 cases/s\n",
        );
        has(&m, "- kani stand-in [exhaustive]: 7 cases, 0 failures\n");
        has(
            &m,
            "| C2_x | verified | exhaustive enumeration | 10 | a / b |\n",
        );
        assert!(!markdown(&r, false).contains("cases/s"));
        assert_eq!(rate(1, 0.0, "x"), "n/a");
    }

    #[test]
    fn latex_escapes_its_special_characters() {
        assert_eq!(
            tex(r"a\b&c%d_e#f{g}h^i~j$k"),
            r"a\textbackslash{}b\&c\%d\_e\#f\{g\}h\^{}i\~{}j\$k"
        );
        let l = latex(&report());
        let lines: Vec<&str> = l.lines().collect();
        assert_eq!(
            lines[0],
            "% truecost_0.1 (commit abc#def0123456789), truecost verify --scope smoke"
        );
        assert!(
            lines.contains(&r"C2\_x & verified & 10 & exhaustive enumeration \\"),
            "{l}"
        );
        assert!(
            lines.contains(&r"\caption{Machine-checked claims (truecost\_0.1, commit \texttt{abc\#def01234}, scope smoke).}"),
            "{l}"
        );
        assert_eq!(lines.last(), Some(&r"\end{table}"));
    }
}
