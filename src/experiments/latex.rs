//! LaTeX renderings of the reproduction reports: per problem (and `γ`), a
//! table of our results and, with `--against-published`, the paper's published value beside
//! ours with the verdict, as the Markdown shows them; then the reproduction summary.
//!
//! The output is a fragment for `\input` (it needs `booktabs` and `longtable`). Times are shown
//! only when asked for (`with_times`): without them the rendering is a pure function of the
//! settings in reference mode, which a snapshot pins.

use std::fmt::Write as _;

use super::deterministic::{Report, RowSummary};
use super::published::{Comparison, Summary, Verdict, REPOSITORY};
use super::stochastic;

/// Escapes text for LaTeX and sets the Greek letters and symbols our tables use in math mode.
///
/// ```
/// use truecost::experiments::latex::tex;
/// assert_eq!(tex("ε-decay 1→0.1, 50 % & more_s"), r"$\varepsilon$-decay 1$\to$0.1, 50 \% \& more\_s");
/// assert_eq!(tex("|Δ| 0.5 ≤ 1, 3 $"), r"$|\Delta|$ 0.5 $\le$ 1, 3 \$");
/// ```
pub fn tex(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    // Adjacent math pieces merge (`|Δ|` is `$|\Delta|$`, never `$|$$\Delta$…`).
    let math = |out: &mut String, body: &str| {
        if out.ends_with('$') && !out.ends_with("\\$") {
            out.pop();
        } else {
            out.push('$');
        }
        out.push_str(body);
        out.push('$');
    };
    for c in s.chars() {
        if let Some(escaped) = crate::echo::tex_special(c) {
            out.push_str(escaped);
            continue;
        }
        match c {
            'ε' => math(&mut out, r"\varepsilon"),
            'π' => math(&mut out, r"\pi"),
            'γ' => math(&mut out, r"\gamma"),
            'ρ' => math(&mut out, r"\rho"),
            'ω' => math(&mut out, r"\omega"),
            'Δ' => math(&mut out, r"\Delta"),
            '±' => math(&mut out, r"\pm"),
            '→' => math(&mut out, r"\to"),
            '≤' => math(&mut out, r"\le"),
            '×' => math(&mut out, r"\times"),
            '÷' => math(&mut out, r"\div"),
            '|' => math(&mut out, "|"),
            '<' => math(&mut out, "<"),
            '>' => math(&mut out, ">"),
            '–' => out.push_str("--"),
            _ => out.push(c),
        }
    }
    out
}

/// A verdict with its numbers (as the text and Markdown tables give it), escaped.
fn verdict(v: &Verdict) -> String {
    tex(&v.to_string())
}

fn number(x: Option<f64>, digits: usize) -> String {
    x.map_or("--".into(), |v| format!("{v:.digits$}"))
}

fn pm(mean: Option<f64>, std: Option<f64>, digits: usize) -> String {
    match (mean, std) {
        (Some(m), Some(s)) => format!("{m:.digits$} $\\pm$ {s:.digits$}"),
        _ => "--".into(),
    }
}

fn percent(x: Option<f64>) -> String {
    x.map_or("--".into(), |r| format!("{:.0}\\,\\%", 100.0 * r))
}

/// A longtable: `columns` (LaTeX column spec), a header, and rows of cells (already LaTeX).
fn longtable(s: &mut String, columns: &str, header: &[&str], rows: &[Vec<String>]) {
    let _ = writeln!(s, "\\begin{{longtable}}{{{columns}}}\n\\toprule");
    let _ = writeln!(s, "{} \\\\\n\\midrule\n\\endhead", header.join(" & "));
    for r in rows {
        let _ = writeln!(s, "{} \\\\", r.join(" & "));
    }
    let _ = writeln!(s, "\\bottomrule\n\\end{{longtable}}");
}

/// The published values beside ours, one line per (row, metric); times left out unless asked.
fn comparison<'a>(
    s: &mut String,
    rows: impl Iterator<Item = (String, Option<&'a Comparison>)>,
    with_times: bool,
) {
    let mut cells = Vec::new();
    for (label, c) in rows {
        let Some(c) = c else { continue };
        for (metric, v) in &c.agreement {
            if !with_times && matches!(v, Verdict::Machine { .. }) {
                continue;
            }
            cells.push(vec![
                label.clone(),
                tex(metric),
                tex(&c.published_text.get(metric).cloned().unwrap_or_default()),
                c.ours
                    .get(metric)
                    .copied()
                    .flatten()
                    .map_or("--".into(), |o| tex(&format!("{o}"))),
                verdict(v),
            ]);
        }
    }
    if cells.is_empty() {
        return;
    }
    let _ = writeln!(s, "\n\\paragraph{{Against published.}}");
    longtable(
        s,
        "llrrp{0.4\\linewidth}",
        &["Row", "Metric", "Published", "Ours", "Verdict"],
        &cells,
    );
}

/// The closing counts, every `differs` line, and the sources.
fn summary(s: &mut String, summary: Option<&Summary>) {
    let Some(summary) = summary else { return };
    let _ = writeln!(
        s,
        "\n\\subsection*{{Reproduction summary}}\nAgainst published ({}): {} metrics compared: {} exact, {} consistent, {} differs, {} machine (run times).",
        tex(REPOSITORY),
        summary.compared,
        summary.exact,
        summary.consistent,
        summary.differs,
        summary.machine
    );
    if !summary.differs_lines.is_empty() {
        let _ = writeln!(s, "\\begin{{itemize}}");
        for l in &summary.differs_lines {
            let _ = writeln!(s, "\\item differs: {}", tex(l));
        }
        let _ = writeln!(s, "\\end{{itemize}}");
    }
    let commits: std::collections::BTreeSet<&str> =
        summary.sources.iter().map(|x| x.commit.as_str()).collect();
    let _ = writeln!(
        s,
        "Sources: {} CSV files of the paper's repository at commits {} (\\texttt{{data/published/sources.csv}} names each file, commit and machine).",
        summary.sources.len(),
        tex(&commits
            .into_iter()
            .map(|c| &c[..c.len().min(12)])
            .collect::<Vec<_>>()
            .join(", "))
    );
}

/// `reproduce deterministic --format latex`.
///
/// ```
/// use truecost::experiments::deterministic::{against_published, run, Settings};
/// use truecost::experiments::latex;
/// use truecost::planning::Mode;
/// let settings = Settings { problems: vec![16], samples: 2, mode: Mode::Reference,
///     ..Settings::default() };
/// let mut report = run(&settings, &|_| {}).unwrap();
/// against_published(&mut report, &settings).unwrap();
/// let t = latex::deterministic(&report, false);
/// // Published 28 actions for model-free Dijkstra on Problem 16, ours 28: exact.
/// assert!(t.contains("Model-free Dijkstra & mean\\_actions & 28.0 & 28 & exact \\\\"));
/// assert!(!t.contains("machine (ours"));
/// ```
pub fn deterministic(report: &Report, with_times: bool) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "% truecost reproduce deterministic: {}",
        report.settings()
    );
    let _ = writeln!(s, "% model: {}", report.model);
    let _ = writeln!(s, "% needs \\usepackage{{booktabs,longtable}}");
    let mut header = vec![
        "Algorithm",
        "Actions (mean $\\pm$ std)",
        "Iterations",
        "Converged",
        "Path states",
        "Optimal paths",
    ];
    if with_times {
        header.extend(["Run time s (mean $\\pm$ std)", "ns/action"]);
    }
    let columns = format!("l{}", "r".repeat(header.len() - 1));
    for p in &report.problems {
        let rows: Vec<&RowSummary> = report.rows.iter().filter(|r| r.problem == *p).collect();
        let _ = writeln!(s, "\n\\subsection*{{Problem {p}}}");
        let cells: Vec<Vec<String>> = rows
            .iter()
            .map(|r| {
                if let Some(note) = &r.note {
                    return vec![
                        tex(&r.label()),
                        format!(
                            "\\multicolumn{{{}}}{{l}}{{{}}}",
                            header.len() - 1,
                            tex(note)
                        ),
                    ];
                }
                let paths = match (r.shortest_path, r.longest_path) {
                    (Some(a), Some(b)) if a == b => a.to_string(),
                    (Some(a), Some(b)) => format!("{a}--{b}"),
                    _ => "--".into(),
                };
                let mut c = vec![
                    tex(&r.label()),
                    pm(r.mean_actions, r.std_actions, 1),
                    pm(r.mean_iterations, r.std_iterations, 2),
                    percent(r.convergence_rate),
                    paths,
                    percent(r.optimal_path_rate),
                ];
                if with_times {
                    c.push(pm(r.mean_time_s, r.std_time_s, 5));
                    c.push(number(r.mean_ns_per_action, 1));
                }
                c
            })
            .collect();
        longtable(&mut s, &columns, &header, &cells);
        comparison(
            &mut s,
            rows.iter()
                .map(|r| (tex(&r.label()), r.comparison.as_ref())),
            with_times,
        );
    }
    summary(&mut s, report.against_published.as_ref());
    s
}

/// `reproduce stochastic --format latex`.
pub fn stochastic(report: &stochastic::Report, with_times: bool) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "% truecost reproduce stochastic: {}", report.settings());
    let _ = writeln!(s, "% model: {}", report.model);
    let _ = writeln!(s, "% needs \\usepackage{{booktabs,longtable}}");
    let mut header = vec![
        "Algorithm",
        "Actions (mean $\\pm$ std)",
        "Episodes/sweeps",
        "Converged",
        "$V(x_1)$ mean",
        "max $|V-G^*|$",
    ];
    if with_times {
        header.extend(["Run time s (mean $\\pm$ std)", "ns/action"]);
    }
    let columns = format!("l{}", "r".repeat(header.len() - 1));
    for p in &report.problems {
        for g in &report.gammas {
            let rows = report.rows_of(*p, g);
            let optimum = rows.first().map_or("--", |r| r.optimum_initial.as_str());
            let _ = writeln!(
                s,
                "\n\\subsection*{{Problem {p}, $\\gamma = {}$ ($G^*(x_1) = {}$)}}",
                tex(g),
                tex(optimum)
            );
            let cells: Vec<Vec<String>> = rows
                .iter()
                .map(|r| {
                    if r.samples == 0 || (r.note.is_some() && r.mean_actions.is_none()) {
                        return vec![
                            tex(&r.label()),
                            format!(
                                "\\multicolumn{{{}}}{{l}}{{{}}}",
                                header.len() - 1,
                                tex(r.note.as_deref().unwrap_or(""))
                            ),
                        ];
                    }
                    let mut c = vec![
                        tex(&r.label()),
                        pm(r.mean_actions, r.std_actions, 1),
                        pm(r.mean_iterations, r.std_iterations, 2),
                        percent(r.convergence_rate),
                        number(r.mean_value_initial, 3),
                        tex(r.max_error.as_deref().unwrap_or("–")),
                    ];
                    if with_times {
                        c.push(pm(r.mean_time_s, r.std_time_s, 5));
                        c.push(number(r.mean_ns_per_action, 1));
                    }
                    c
                })
                .collect();
            longtable(&mut s, &columns, &header, &cells);
            comparison(
                &mut s,
                rows.iter()
                    .map(|r| (tex(&r.label()), r.comparison.as_ref())),
                with_times,
            );
        }
    }
    summary(&mut s, report.against_published.as_ref());
    s
}
