//! The `truecost verify` report and its renderings (issue 5, item 8): text, JSON, Markdown and
//! a LaTeX table. Times appear only when asked for (`with_times`), so the report without them
//! is reproducible byte for byte and pinned by a snapshot.

use std::fmt::Write;

use serde_json::{json, Value};

use super::discount::rat;
use super::poly::Algebraic;
use super::{ClaimResult, Scope};

/// `α*` of the worked example of C3.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct AlphaStar {
    /// Lower end of the bracket (`p/q`).
    pub lo: String,
    /// Upper end of the bracket (`p/q`).
    pub hi: String,
    /// The polynomial whose root it is.
    pub polynomial: String,
    /// 30 decimals.
    pub decimal: String,
}

impl AlphaStar {
    /// From the isolated root.
    pub fn new(a: &Algebraic) -> AlphaStar {
        AlphaStar {
            lo: rat(&a.lo),
            hi: rat(&a.hi),
            polynomial: a.poly.primitive().to_string(),
            decimal: a.decimal(30),
        }
    }
}

/// The command that shows a counterexample's failure: its own replay (issue 10, item 4), or
/// the exact solve of its problem file.
fn replay_command(ce: &super::Counterexample) -> String {
    ce.replay
        .clone()
        .unwrap_or_else(|| format!("truecost solve --file {} --algorithm dijkstra", ce.file))
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
        "{} - claims of SPEC 6, scope {}",
        report.tool,
        report.scope.name()
    );
    if with_times {
        let _ = writeln!(s, "commit {}", report.commit);
        if let Some(solver) = &report.solver {
            let _ = writeln!(s, "smt solver: {solver}");
        }
    }
    for c in &report.claims {
        let _ = writeln!(s);
        let _ = writeln!(s, "{}  {}", c.id, c.verdict.name().to_uppercase());
        let _ = writeln!(s, "  statement: {}", c.statement);
        let _ = writeln!(s, "  decided by: {} ({} cases)", c.engine, c.cases);
        let _ = writeln!(s, "  scope: {}", c.scope);
        for e in &c.engines {
            let t = if with_times && e.seconds > 0.0 {
                format!(", {}", rate(e.cases, e.seconds, &e.engine))
            } else {
                String::new()
            };
            let _ = writeln!(
                s,
                "  engine: {} [{}] {} cases, {} failures{t}",
                e.engine, e.mode, e.cases, e.failures
            );
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
    if let Some(a) = &report.alpha_star {
        let _ = writeln!(s);
        let _ = writeln!(
            s,
            "alpha* = {} (root of {} in (0,1))",
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
        "# {} - claims of SPEC 6 (scope {})\n",
        report.tool,
        report.scope.name()
    );
    if with_times {
        if let Some(solver) = &report.solver {
            let _ = writeln!(s, "SMT solver: {solver}\n");
        }
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
            let t = if with_times && e.seconds > 0.0 {
                format!(", {}", rate(e.cases, e.seconds, &e.engine))
            } else {
                String::new()
            };
            let _ = writeln!(
                s,
                "- {} [{}]: {} cases, {} failures{t}",
                e.engine, e.mode, e.cases, e.failures
            );
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
    if let Some(a) = &report.alpha_star {
        let _ = writeln!(
            s,
            "\n## alpha*\n\n`{}` is the root of `{}` in (0,1), in `({}, {}]`.",
            a.decimal, a.polynomial, a.lo, a.hi
        );
    }
    s
}

fn tex(s: &str) -> String {
    s.replace('\\', "\\textbackslash{}")
        .replace('&', "\\&")
        .replace('%', "\\%")
        .replace('_', "\\_")
        .replace('#', "\\#")
        .replace('{', "\\{")
        .replace('}', "\\}")
        .replace('^', "\\^{}")
        .replace('~', "\\~{}")
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
        .map(|a| {
            format!(
                " $\\alpha^* \\approx {}$.",
                &a.decimal[..a.decimal.len().min(22)]
            )
        })
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
    );
    let _ = writeln!(s, "\\end{{table}}");
    s
}
