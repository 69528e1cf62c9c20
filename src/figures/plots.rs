//! The paper's plots from an experiment report: goal discovery against ε
//! (normalised per problem, in "easy" and "hard" problem groups) and convergence rate against
//! ε for the deterministic runner; run time against ρ and convergence rate against ρ and ε for
//! the stochastic one (one series per γ). Every caption names the model, the seed and the
//! sample count.
//!
//! Grouping rule (ours, stated on every plot): a problem is *hard* when its optimal path has
//! more moves than the median over the plotted problems, *easy* otherwise. Goal discovery is
//! measured in actions (reproducible bit for bit; proportional to time) and normalised per
//! problem by its largest value over ε, so problems of different sizes can be averaged.

use std::collections::BTreeMap;

use super::chart::{LineChart, Series};
use crate::experiments::deterministic::{Report, RowSummary};
use crate::experiments::stochastic;
use crate::problems::GridLayout;

/// The plots of a deterministic report, each with a file stem.
///
/// ```no_run
/// # use truecost::experiments::deterministic::Report;
/// # fn f(report: &Report) {
/// for (stem, chart) in truecost::figures::plots::deterministic(report) {
///     let canvas = chart.draw(900, 600).unwrap();
///     canvas.save(std::path::Path::new(&format!("{stem}.svg"))).unwrap();
/// }
/// # }
/// ```
pub fn deterministic(report: &Report) -> Vec<(String, LineChart)> {
    let discovery: Curves = epsilon_metric(&report.rows, |r| r.mean_actions_goal_discovered)
        .into_iter()
        .map(|(id, c)| (id, normalised(&c)))
        .collect();
    let convergence: Curves = epsilon_metric(&report.rows, |r| r.convergence_rate)
        .into_iter()
        .map(|(id, c)| {
            (
                id,
                c.into_iter().filter_map(|(e, v)| Some((e, v?))).collect(),
            )
        })
        .collect();
    let (easy, hard) = groups(discovery.keys().copied());
    let caption = format!(
        "{}; seed {}; {} samples per row, {} episodes x {} steps; hard = optimal path longer than the median ({} moves)",
        report.model,
        report.seed,
        report.samples,
        report.episodes,
        report.max_steps,
        median_moves(discovery.keys().copied()).map_or("-".into(), |m| m.to_string()),
    );
    let by_group = |curves: &Curves| -> Vec<Series> {
        [("easy", &easy), ("hard", &hard)]
            .into_iter()
            .filter(|(_, ids)| !ids.is_empty())
            .map(|(name, ids)| Series {
                name: format!("{name} ({})", join(ids)),
                points: average(ids.iter().filter_map(|id| curves.get(id).cloned())),
            })
            .collect()
    };
    vec![
        (
            "goal_discovery_vs_epsilon".to_string(),
            LineChart {
                title: "Goal discovery against ε (Q-learning, random exploration)".into(),
                caption: caption.clone(),
                x_label: "ε".into(),
                y_label: "actions to goal discovery (normalised per problem)".into(),
                series: by_group(&discovery),
                x_categories: Vec::new(),
                y_range: Some((0.0, 1.0)),
            },
        ),
        (
            "convergence_rate_vs_epsilon".to_string(),
            LineChart {
                title: "Convergence rate against ε (Q-learning, random exploration)".into(),
                caption,
                x_label: "ε".into(),
                y_label: "fraction of samples with V = G* everywhere".into(),
                series: by_group(&convergence),
                x_categories: Vec::new(),
                y_range: Some((0.0, 1.0)),
            },
        ),
    ]
}

/// The plots of a stochastic report, each with a file stem: mean run time against ρ and
/// convergence rate against ρ and against ε, one series per `γ`, each point the mean over the
/// report's problems and the other parameter's values (Q-learning rows only). ρ and ε are
/// categories in the order given (a decaying rate 1/n^ω or ε-decay is not a number).
///
/// ```no_run
/// # use truecost::experiments::stochastic::Report;
/// # fn f(report: &Report) {
/// for (stem, chart) in truecost::figures::plots::stochastic(report) {
///     chart.draw(900, 600).unwrap().save(std::path::Path::new(&format!("{stem}.svg"))).unwrap();
/// }
/// # }
/// ```
pub fn stochastic(report: &stochastic::Report) -> Vec<(String, LineChart)> {
    let learning: Vec<&stochastic::RowSummary> = report
        .rows
        .iter()
        .filter(|r| r.algorithm == "q-learning")
        .collect();
    let rhos = categories(learning.iter().filter_map(|r| r.rho.clone()));
    let epsilons = categories(learning.iter().filter_map(|r| r.epsilon.clone()));
    let caption = format!(
        "{}; seed {}; {} samples per row, {} episodes x {} steps; mean over problems {}",
        report.model,
        report.seed,
        report.samples,
        report.episodes,
        report.max_steps,
        join(&report.problems),
    );
    let chart = |title: &str,
                 x_label: &str,
                 y_label: &str,
                 x: &[String],
                 key: fn(&stochastic::RowSummary) -> Option<&String>,
                 metric: fn(&stochastic::RowSummary) -> Option<f64>,
                 y_range: Option<(f64, f64)>,
                 other: &str| LineChart {
        title: title.into(),
        caption: format!("{caption} and {other}"),
        x_label: x_label.into(),
        y_label: y_label.into(),
        series: report
            .gammas
            .iter()
            .map(|g| Series {
                name: format!("γ = {g}"),
                points: x
                    .iter()
                    .enumerate()
                    .filter_map(|(k, value)| {
                        let ys: Vec<f64> = learning
                            .iter()
                            .filter(|r| &r.gamma == g && key(r) == Some(value))
                            .filter_map(|r| metric(r))
                            .collect();
                        (!ys.is_empty())
                            .then(|| (k as f64, ys.iter().sum::<f64>() / ys.len() as f64))
                    })
                    .collect(),
            })
            .collect(),
        x_categories: x.to_vec(),
        y_range,
    };
    let over_epsilons = format!("ε in {{{}}}", epsilons.join(", "));
    let over_rhos = format!("ρ in {{{}}}", rhos.join(", "));
    vec![
        (
            "run_time_vs_rho".to_string(),
            chart(
                "Run time against ρ (stochastic Q-learning)",
                "learning rate ρ",
                "mean wall time of a run (s, this machine)",
                &rhos,
                |r| r.rho.as_ref(),
                |r| r.mean_time_s,
                None,
                &over_epsilons,
            ),
        ),
        (
            "convergence_rate_vs_rho".to_string(),
            chart(
                "Convergence rate against ρ (stochastic Q-learning)",
                "learning rate ρ",
                "fraction of samples within tolerance everywhere",
                &rhos,
                |r| r.rho.as_ref(),
                |r| r.convergence_rate,
                Some((0.0, 1.0)),
                &over_epsilons,
            ),
        ),
        (
            "convergence_rate_vs_epsilon".to_string(),
            chart(
                "Convergence rate against ε (stochastic Q-learning)",
                "exploration ε",
                "fraction of samples within tolerance everywhere",
                &epsilons,
                |r| r.epsilon.as_ref(),
                |r| r.convergence_rate,
                Some((0.0, 1.0)),
                &over_rhos,
            ),
        ),
    ]
}

/// Distinct values in first-seen order.
fn categories(values: impl Iterator<Item = String>) -> Vec<String> {
    let mut out: Vec<String> = Vec::new();
    for v in values {
        if !out.contains(&v) {
            out.push(v);
        }
    }
    out
}

/// Per problem, a curve of points `(ε, value)`.
type Curves = BTreeMap<usize, Vec<(f64, f64)>>;

/// Per problem: `(ε, metric)` of the constant-ε random-exploration Q-learning rows.
fn epsilon_metric(
    rows: &[RowSummary],
    metric: impl Fn(&RowSummary) -> Option<f64>,
) -> BTreeMap<usize, Vec<(f64, Option<f64>)>> {
    let mut curves: BTreeMap<usize, Vec<(f64, Option<f64>)>> = BTreeMap::new();
    for r in rows.iter().filter(|r| r.algorithm == "q-learning") {
        if let Some(e) = r.epsilon {
            curves.entry(r.problem).or_default().push((e, metric(r)));
        }
    }
    for c in curves.values_mut() {
        c.sort_by(|a, b| a.0.total_cmp(&b.0));
    }
    curves
}

/// Divides a curve by its largest value; missing values are dropped.
fn normalised(curve: &[(f64, Option<f64>)]) -> Vec<(f64, f64)> {
    let max = curve.iter().filter_map(|p| p.1).fold(0.0f64, f64::max);
    curve
        .iter()
        .filter_map(|&(e, v)| Some((e, v? / if max > 0.0 { max } else { 1.0 })))
        .collect()
}

/// Pointwise mean over curves sharing x values.
fn average(curves: impl Iterator<Item = Vec<(f64, f64)>>) -> Vec<(f64, f64)> {
    let mut sums: BTreeMap<u64, (f64, f64, u32)> = BTreeMap::new();
    for curve in curves {
        for (x, y) in curve {
            let entry = sums.entry(x.to_bits()).or_insert((x, 0.0, 0));
            entry.1 += y;
            entry.2 += 1;
        }
    }
    let mut points: Vec<(f64, f64)> = sums
        .into_values()
        .map(|(x, s, n)| (x, s / f64::from(n)))
        .collect();
    points.sort_by(|a, b| a.0.total_cmp(&b.0));
    points
}

fn optimal_moves(id: usize) -> Option<u64> {
    GridLayout::exact(id).ok()?.facts().optimal_moves
}

fn median_moves(ids: impl Iterator<Item = usize>) -> Option<u64> {
    let mut moves: Vec<u64> = ids.filter_map(optimal_moves).collect();
    moves.sort_unstable();
    moves.get(moves.len().checked_sub(1)? / 2).copied()
}

/// (easy, hard) problem ids by the median rule.
fn groups(ids: impl Iterator<Item = usize> + Clone) -> (Vec<usize>, Vec<usize>) {
    let median = median_moves(ids.clone());
    ids.filter(|&id| optimal_moves(id).is_some())
        .partition(|&id| optimal_moves(id) <= median)
}

fn join(ids: &[usize]) -> String {
    ids.iter()
        .map(|i| i.to_string())
        .collect::<Vec<_>>()
        .join(", ")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn normalising_divides_by_the_maximum() {
        let c = [(0.0, Some(10.0)), (0.5, None), (1.0, Some(40.0))];
        assert_eq!(normalised(&c), vec![(0.0, 0.25), (1.0, 1.0)]);
    }

    #[test]
    fn averaging_is_pointwise() {
        let a = vec![(0.0, 1.0), (1.0, 3.0)];
        let b = vec![(0.0, 3.0)];
        assert_eq!(average([a, b].into_iter()), vec![(0.0, 2.0), (1.0, 3.0)]);
    }

    #[test]
    fn groups_split_at_the_median_optimal_path() {
        // Published optimal moves: 0 → 17, 1 → 27, 2 → 29, 3 → 90.
        let (easy, hard) = groups([0usize, 1, 2, 3].into_iter());
        assert_eq!(easy, vec![0, 1]);
        assert_eq!(hard, vec![2, 3]);
    }
}
