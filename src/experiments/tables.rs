//! The experiments' reports as text, Markdown, CSV and JSON (the LaTeX renderer is
//! [`super::latex`]): one table per problem with the paper's rows, the published numbers beside
//! ours with their verdicts (`--against-published`) and the reproduction summary.
//! Every format names the mode or noise model, the tolerance and the seed.

use std::fmt::Write as _;

use super::deterministic::{Report, RowSummary};
use super::published::{Comparison, Summary, Verdict};
use super::stochastic;

/// A format of a report's tables.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Table {
    /// Aligned text.
    Text,
    /// A JSON array of rows (an object with the comparison when there is one).
    Json,
    /// Comma-separated values with a header (and `# ` summary lines).
    Csv,
    /// Markdown tables.
    Markdown,
}

/// Renders a stochastic report in a format. Every format names the noise model, tolerance and
/// seed (JSON and CSV in every row).
///
/// ```
/// use truecost::experiments::stochastic::{run, Settings};
/// use truecost::experiments::tables::{stochastic, Table};
/// let settings = Settings { problems: vec![16], samples: 1, episodes: 20, max_steps: 50,
///     ..Settings::default() };
/// let report = run(&settings, &|_| {}).unwrap();
/// let csv = stochastic(&report, Table::Csv);
/// // A header and one line per row: 3 γ × (2 ρ × 2 ε learning rows + 2 VIs).
/// assert_eq!(csv.lines().count(), 1 + 3 * 6);
/// assert!(stochastic(&report, Table::Text).contains("noise paper; tolerance relative; seed 0"));
/// ```
pub fn stochastic(report: &stochastic::Report, format: Table) -> String {
    match format {
        Table::Json => json(&report.rows, report.against_published.as_ref()),
        Table::Csv => csv_rows(
            &STOCHASTIC_CSV_COLUMNS,
            &report.rows,
            |r| r.comparison.as_ref(),
            |c| match c {
                "episodes" => Some(report.episodes.to_string()),
                "max_steps" => Some(report.max_steps.to_string()),
                _ => None,
            },
            report.against_published.as_ref(),
        ),
        Table::Markdown | Table::Text => stochastic_table(report, format),
    }
}

/// The columns of the stochastic CSV file, in order.
const STOCHASTIC_CSV_COLUMNS: [&str; 35] = [
    "problem",
    "gamma",
    "algorithm",
    "rho",
    "epsilon",
    "samples",
    "optimum_initial",
    "mean_time_s",
    "std_time_s",
    "convergence_rate",
    "mean_actions_converged",
    "mean_actions",
    "std_actions",
    "mean_ns_per_action",
    "mean_iterations",
    "std_iterations",
    "initial_within_rate",
    "mean_actions_initial_within",
    "mean_episode_initial_within",
    "mean_time_initial_within_s",
    "goal_discovery_rate",
    "mean_actions_goal_discovered",
    "mean_time_goal_discovered_s",
    "mean_value_initial",
    "max_error",
    "shortest_path",
    "longest_path",
    "goal_reached_rate",
    "optimal_path_rate",
    "noise",
    "tolerance",
    "seed",
    "episodes",
    "max_steps",
    "note",
];

const STOCHASTIC_HEADER: [&str; 11] = [
    "algorithm",
    "run time s (mean ± std)",
    "actions (mean ± std)",
    "ns/action",
    "episodes/sweeps (mean ± std)",
    "converged",
    "goal discovered: actions / s",
    "V(x1) within: actions / episode / s",
    "V(x1) mean, max |V-G*|",
    "greedy path states",
    "optimal paths",
];

fn stochastic_cells(row: &stochastic::RowSummary) -> Vec<String> {
    let label = row.label();
    if row.samples == 0 || (row.note.is_some() && row.mean_actions.is_none()) {
        let mut c = vec![label, row.note.clone().unwrap_or_default()];
        c.resize(STOCHASTIC_HEADER.len(), String::new());
        return c;
    }
    let learning = row.algorithm == "q-learning";
    let paths = match (row.shortest_path, row.longest_path) {
        (Some(a), Some(b)) if a == b => a.to_string(),
        (Some(a), Some(b)) => format!("{a}–{b}"),
        _ => "–".into(),
    };
    let pct = |x: Option<f64>| x.map_or("–".into(), |r| format!("{:.0} %", 100.0 * r));
    vec![
        label,
        pm(row.mean_time_s, row.std_time_s, 5),
        pm(row.mean_actions, row.std_actions, 1),
        opt(row.mean_ns_per_action, 1),
        pm(row.mean_iterations, row.std_iterations, 2),
        pct(row.convergence_rate),
        if learning {
            format!(
                "{} / {}",
                opt(row.mean_actions_goal_discovered, 1),
                opt(row.mean_time_goal_discovered_s, 5)
            )
        } else {
            "–".into()
        },
        if learning {
            format!(
                "{} / {} / {}",
                opt(row.mean_actions_initial_within, 1),
                opt(row.mean_episode_initial_within, 1),
                opt(row.mean_time_initial_within_s, 5)
            )
        } else {
            pct(row.initial_within_rate)
        },
        format!(
            "{}, {}",
            opt(row.mean_value_initial, 3),
            row.max_error.as_deref().unwrap_or("–")
        ),
        paths,
        pct(row.optimal_path_rate),
    ]
}

fn stochastic_table(report: &stochastic::Report, format: Table) -> String {
    let mut s = String::new();
    let title = format!("truecost reproduce stochastic — {}", report.settings());
    let notes = [
        format!("model: {}", report.model),
        "Learning rows: means of actions, episodes and times to an event are over the samples \
         that reached it; greedy paths are simulated once per sample (outcomes sampled, capped at \
         100001 steps) and count x1 and the goal. VI rows: the reference code's rules (from 1e30, \
         decrease only, stop at change <= 0.1), actions = its counted outcome terms; 'converged' \
         = every tracked state within tolerance."
            .to_string(),
    ];
    let markdown = format == Table::Markdown;
    if markdown {
        let _ = writeln!(s, "# {title}\n");
        for n in &notes {
            let _ = writeln!(s, "{n}\n");
        }
    } else {
        let _ = writeln!(s, "{title}");
        for n in &notes {
            let _ = writeln!(s, "{n}");
        }
    }
    for p in &report.problems {
        for g in &report.gammas {
            let rows = report.rows_of(*p, g);
            let optimum = rows.first().map_or("–", |r| r.optimum_initial.as_str());
            let cells: Vec<Vec<String>> = rows.iter().map(|r| stochastic_cells(r)).collect();
            if markdown {
                let _ = writeln!(s, "## Problem {p}, γ = {g} (G*(x1) = {optimum})\n");
                s += &markdown_table(&STOCHASTIC_HEADER, &cells);
                s += &comparison_table(
                    rows.iter()
                        .map(|r| (stochastic_cells(r)[0].clone(), r.comparison.as_ref())),
                    true,
                );
            } else {
                let _ = writeln!(s, "\nProblem {p}, γ = {g} (G*(x1) = {optimum})");
                s += &text_table(&STOCHASTIC_HEADER, &cells);
                s += &comparison_table(
                    rows.iter()
                        .map(|r| (stochastic_cells(r)[0].clone(), r.comparison.as_ref())),
                    false,
                );
            }
        }
    }
    s + &summary_text(report.against_published.as_ref(), markdown)
}
/// Renders a deterministic report in a format. Every format names the mode, model and seed.
///
/// ```
/// use truecost::experiments::deterministic::{run, Settings};
/// use truecost::experiments::tables::{deterministic, Table};
/// let settings = Settings { problems: vec![16], samples: 1, ..Settings::default() };
/// let report = run(&settings, &|_| {}).unwrap();
/// let md = deterministic(&report, Table::Markdown);
/// assert!(md.contains("Model-free Dijkstra"));
/// let json: serde_json::Value = serde_json::from_str(&deterministic(&report, Table::Json)).unwrap();
/// assert_eq!(json.as_array().unwrap().len(), 11); // the paper's 11 rows
/// ```
pub fn deterministic(report: &Report, format: Table) -> String {
    match format {
        Table::Json => json(&report.rows, report.against_published.as_ref()),
        Table::Csv => csv(report),
        Table::Markdown => markdown(report),
        Table::Text => text(report),
    }
}

/// The columns of the CSV file, in order.
const CSV_COLUMNS: [&str; 34] = [
    "problem",
    "algorithm",
    "epsilon",
    "epsilon_final",
    "plan",
    "samples",
    "mean_time_s",
    "std_time_s",
    "convergence_rate",
    "mean_actions_converged",
    "mean_actions",
    "std_actions",
    "mean_planner_actions",
    "mean_ns_per_action",
    "mean_iterations",
    "std_iterations",
    "shortest_path",
    "longest_path",
    "goal_reached_rate",
    "optimal_path_rate",
    "loops",
    "initial_optimal_rate",
    "mean_actions_initial_optimal",
    "mean_time_initial_optimal_s",
    "goal_discovery_rate",
    "mean_actions_goal_discovered",
    "mean_time_goal_discovered_s",
    "mode",
    "seed",
    "value_type",
    "episodes",
    "max_steps",
    "model",
    "note",
];

fn csv(report: &Report) -> String {
    csv_rows(
        &CSV_COLUMNS,
        &report.rows,
        |r| r.comparison.as_ref(),
        |c| match c {
            "episodes" => Some(report.episodes.to_string()),
            "max_steps" => Some(report.max_steps.to_string()),
            "model" => Some(quote(&report.model)),
            _ => None,
        },
        report.against_published.as_ref(),
    )
}

/// A CSV file of `rows`: a header of `columns` (then the comparison's columns), each row's
/// cells from its JSON fields unless `fixed` gives the column's cell, and the summary lines.
fn csv_rows<T: serde::Serialize>(
    columns: &[&str],
    rows: &[T],
    comparison: impl Fn(&T) -> Option<&Comparison>,
    fixed: impl Fn(&str) -> Option<String>,
    summary: Option<&Summary>,
) -> String {
    let metrics = comparison_metrics(rows.iter().map(&comparison));
    let mut s = columns.join(",") + &comparison_csv_header(&metrics) + "\n";
    for row in rows {
        let value = serde_json::to_value(row).expect("serialisable");
        let cells: Vec<String> = columns
            .iter()
            .map(|&c| {
                fixed(c).unwrap_or_else(|| match &value[c] {
                    serde_json::Value::Null => String::new(),
                    serde_json::Value::String(t) => quote(t),
                    other => other.to_string(),
                })
            })
            .collect();
        s += &(cells.join(",") + &comparison_csv_cells(comparison(row), &metrics) + "\n");
    }
    s + &summary_csv(summary)
}

/// A CSV cell: quoted when it contains a separator or a quote.
fn quote(t: &str) -> String {
    if t.contains([',', '"', '\n']) {
        format!("\"{}\"", t.replace('"', "\"\""))
    } else {
        t.to_string()
    }
}

/// `mean ± std` with a sensible number of digits.
fn pm(mean: Option<f64>, std: Option<f64>, digits: usize) -> String {
    match (mean, std) {
        (Some(m), Some(s)) => format!("{m:.digits$} ± {s:.digits$}"),
        _ => "–".into(),
    }
}

fn opt(x: Option<f64>, digits: usize) -> String {
    x.map_or("–".into(), |v| format!("{v:.digits$}"))
}

/// The table cells of a row (shared by text and Markdown).
fn cells(row: &RowSummary) -> Vec<String> {
    if let Some(note) = &row.note {
        let mut c = vec![row.label(), note.clone()];
        c.resize(HEADER.len(), String::new());
        return c;
    }
    let paths = match (row.shortest_path, row.longest_path) {
        (Some(a), Some(b)) if a == b => a.to_string(),
        (Some(a), Some(b)) => format!("{a}–{b}"),
        _ => "–".into(),
    };
    vec![
        row.label(),
        pm(row.mean_time_s, row.std_time_s, 5),
        pm(row.mean_actions, row.std_actions, 1),
        opt(row.mean_ns_per_action, 1),
        pm(row.mean_iterations, row.std_iterations, 2),
        row.convergence_rate
            .map_or("–".into(), |r| format!("{:.1} %", 100.0 * r)),
        format!(
            "{} / {}",
            opt(row.mean_actions_goal_discovered, 1),
            opt(row.mean_time_goal_discovered_s, 5)
        ),
        format!(
            "{} / {}",
            opt(row.mean_actions_initial_optimal, 1),
            opt(row.mean_time_initial_optimal_s, 5)
        ),
        paths,
        format!(
            "{}{}",
            row.optimal_path_rate
                .map_or("–".into(), |r| format!("{:.0} %", 100.0 * r)),
            if row.loops > 0 {
                format!(", {} loops", row.loops)
            } else {
                String::new()
            }
        ),
    ]
}

const HEADER: [&str; 10] = [
    "algorithm",
    "run time s (mean ± std)",
    "actions (mean ± std)",
    "ns/action",
    "iterations (mean ± std)",
    "converged",
    "goal discovered: actions / s",
    "V(x1) optimal: actions / s",
    "path states",
    "optimal paths",
];

fn preamble(report: &Report) -> Vec<String> {
    vec![
        format!("truecost reproduce deterministic — {}", report.settings()),
        format!("model: {}", report.model),
        "Q-learning: ρ = 1, Q₀ = 0, greedy = first minimiser in action order; means of actions \
         and times to an event are over the samples that reached it; path states count x1 and \
         the goal; π rows share one digit stream, problems in the order listed."
            .into(),
    ]
}

fn markdown(report: &Report) -> String {
    let mut s = String::new();
    let pre = preamble(report);
    let _ = writeln!(s, "# {}\n", pre[0]);
    for line in &pre[1..] {
        let _ = writeln!(s, "{line}\n");
    }
    for p in &report.problems {
        let _ = writeln!(s, "## Problem {p}\n");
        let rows: Vec<Vec<String>> = report
            .rows
            .iter()
            .filter(|r| r.problem == *p)
            .map(cells)
            .collect();
        s += &markdown_table(&HEADER, &rows);
        s += &comparison_table(
            report
                .rows
                .iter()
                .filter(|r| r.problem == *p)
                .map(|r| (r.label(), r.comparison.as_ref())),
            true,
        );
    }
    s + &summary_text(report.against_published.as_ref(), true)
}

fn text(report: &Report) -> String {
    let mut s = String::new();
    for line in preamble(report) {
        let _ = writeln!(s, "{line}");
    }
    for p in &report.problems {
        let summaries: Vec<&RowSummary> = report.rows.iter().filter(|r| r.problem == *p).collect();
        let rows: Vec<Vec<String>> = summaries.iter().map(|r| cells(r)).collect();
        // Rows that were not run carry a note; it does not widen the columns.
        let measured = || {
            rows.iter()
                .zip(&summaries)
                .filter(|(_, s)| s.note.is_none())
                .map(|(r, _)| r)
        };
        let widths = column_widths(&HEADER, measured());
        let line = |cells: &[String]| aligned(cells, &widths);
        let _ = writeln!(s, "\nProblem {p}");
        let header: Vec<String> = HEADER.iter().map(|h| h.to_string()).collect();
        let _ = writeln!(s, "{}", line(&header));
        for (r, summary) in rows.iter().zip(&summaries) {
            match &summary.note {
                None => {
                    let _ = writeln!(s, "{}", line(r));
                }
                Some(note) => {
                    let pad = widths[0].saturating_sub(r[0].chars().count());
                    let _ = writeln!(s, "{}{}  {note}", r[0], " ".repeat(pad));
                }
            }
        }
        s += &comparison_table(
            summaries.iter().map(|r| (r.label(), r.comparison.as_ref())),
            false,
        );
    }
    s + &summary_text(report.against_published.as_ref(), false)
}

/// The width of each column: its widest cell among `header` and `rows`.
fn column_widths<'a>(
    header: &[&str],
    rows: impl Iterator<Item = &'a Vec<String>> + Clone,
) -> Vec<usize> {
    (0..header.len())
        .map(|c| {
            rows.clone()
                .map(|r| r[c].chars().count())
                .chain([header[c].chars().count()])
                .max()
                .unwrap_or(0)
        })
        .collect()
}

/// One line of an aligned text table: cells padded to `widths`, two spaces apart.
fn aligned(cells: &[String], widths: &[usize]) -> String {
    cells
        .iter()
        .zip(widths)
        .map(|(c, &w)| format!("{c}{}", " ".repeat(w.saturating_sub(c.chars().count()))))
        .collect::<Vec<_>>()
        .join("  ")
        .trim_end()
        .to_string()
}

/// JSON: the rows; with `--against-published` an object `{"rows": […], "against_published":
/// {counts, differs_lines, sources}}`.
fn json<T: serde::Serialize>(rows: &[T], summary: Option<&Summary>) -> String {
    let mut s = match summary {
        None => serde_json::to_string_pretty(rows),
        Some(summary) => serde_json::to_string_pretty(&serde_json::json!({
            "rows": rows,
            "against_published": summary,
        })),
    }
    .expect("serialisable");
    s.push('\n');
    s
}

/// Every metric compared in any row, sorted.
fn comparison_metrics<'a>(rows: impl Iterator<Item = Option<&'a Comparison>>) -> Vec<String> {
    let set: std::collections::BTreeSet<&String> =
        rows.flatten().flat_map(|c| c.agreement.keys()).collect();
    set.into_iter().cloned().collect()
}

/// `,published_M,agreement_M` for each metric.
fn comparison_csv_header(metrics: &[String]) -> String {
    metrics
        .iter()
        .map(|m| format!(",published_{m},agreement_{m}"))
        .collect()
}

/// The published value (as published) and the verdict of each metric (empty when none).
fn comparison_csv_cells(c: Option<&Comparison>, metrics: &[String]) -> String {
    metrics
        .iter()
        .map(|m| {
            let published = c
                .and_then(|c| c.published_text.get(m))
                .cloned()
                .unwrap_or_default();
            let verdict = c
                .and_then(|c| c.agreement.get(m))
                .map_or(String::new(), Verdict::to_string);
            format!(",{},{}", quote(&published), quote(&verdict))
        })
        .collect()
}

/// The summary as trailing `# ` lines of a CSV file (with `--against-published` only).
fn summary_csv(summary: Option<&Summary>) -> String {
    summary.map_or(String::new(), |s| {
        s.lines().iter().map(|l| format!("# {l}\n")).collect()
    })
}

const COMPARISON_HEADER: [&str; 5] = ["row", "metric", "published", "ours", "verdict"];

/// The published numbers beside ours, one line per (row, metric); empty without comparisons.
fn comparison_table<'a>(
    rows: impl Iterator<Item = (String, Option<&'a Comparison>)>,
    markdown: bool,
) -> String {
    let mut cells: Vec<Vec<String>> = Vec::new();
    for (label, c) in rows {
        let Some(c) = c else { continue };
        for (metric, verdict) in &c.agreement {
            cells.push(vec![
                label.clone(),
                metric.clone(),
                c.published_text.get(metric).cloned().unwrap_or_default(),
                c.ours
                    .get(metric)
                    .copied()
                    .flatten()
                    .map_or("–".into(), |o| format!("{o}")),
                verdict.to_string(),
            ]);
        }
    }
    if cells.is_empty() {
        return String::new();
    }
    let mut s = String::new();
    if markdown {
        let _ = writeln!(s, "Against published:\n");
        s += &markdown_table(&COMPARISON_HEADER, &cells);
    } else {
        let _ = writeln!(s, "Against published:");
        s += &text_table(&COMPARISON_HEADER, &cells);
    }
    s
}

/// A Markdown table with a blank line after it.
fn markdown_table(header: &[&str], rows: &[Vec<String>]) -> String {
    let mut s = format!(
        "| {} |\n|{}\n",
        header.join(" | "),
        "---|".repeat(header.len())
    );
    for r in rows {
        let _ = writeln!(s, "| {} |", r.join(" | "));
    }
    s + "\n"
}

/// An aligned text table: each column as wide as its widest cell.
fn text_table(header: &[&str], rows: &[Vec<String>]) -> String {
    let widths = column_widths(header, rows.iter());
    let header: Vec<String> = header.iter().map(|h| h.to_string()).collect();
    let mut s = String::new();
    for r in std::iter::once(&header).chain(rows) {
        let _ = writeln!(s, "{}", aligned(r, &widths));
    }
    s
}

/// The closing summary and the sources (with `--against-published` only).
fn summary_text(summary: Option<&Summary>, markdown: bool) -> String {
    let Some(summary) = summary else {
        return String::new();
    };
    let mut s = String::new();
    let lines = summary.lines();
    if markdown {
        let _ = writeln!(s, "## Reproduction summary\n");
        let _ = writeln!(s, "{}\n", lines[0]);
        for l in &lines[1..] {
            let _ = writeln!(s, "- {l}");
        }
        if lines.len() > 1 {
            s.push('\n');
        }
    } else {
        let _ = writeln!(s, "\nReproduction summary");
        for l in &lines {
            let _ = writeln!(s, "{l}");
        }
    }
    let files = summary.sources.len();
    let commits: std::collections::BTreeSet<&str> =
        summary.sources.iter().map(|x| x.commit.as_str()).collect();
    let _ = writeln!(
        s,
        "{}Sources: {files} CSV files of the paper's repository at commits {} (data/published/sources.csv names each file, commit and machine).",
        if markdown { "\n" } else { "" },
        commits.into_iter().map(|c| &c[..c.len().min(12)]).collect::<Vec<_>>().join(", ")
    );
    s
}
