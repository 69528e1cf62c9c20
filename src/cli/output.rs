//! Rendering of listings and reports as text, JSON, CSV and Markdown.

use std::fmt::Write;

use serde_json::{json, Value};

use super::ListFormat;
use truecost::planning::{Mode, PlanReport};
use truecost::problems::Facts;

fn mode_name(mode: Mode) -> &'static str {
    match mode {
        Mode::Exact => "exact (paper text)",
        Mode::Reference => "reference (paper code, f64)",
    }
}

/// The `problems` listing.
pub fn problems(facts: &[Facts], format: ListFormat, mode: Mode) -> String {
    let header = [
        "id",
        "grid_nodes",
        "states",
        "edges",
        "initial",
        "goal",
        "optimal_moves",
        "in_paper",
    ];
    let row = |f: &Facts| {
        vec![
            f.id.to_string(),
            f.grid_nodes.to_string(),
            f.states.to_string(),
            f.edges.to_string(),
            f.initial.to_string(),
            f.goal.to_string(),
            f.optimal_moves
                .map_or("unreachable".to_string(), |m| m.to_string()),
            f.in_paper.to_string(),
        ]
    };
    match format {
        ListFormat::Json => {
            let mut s = serde_json::to_string_pretty(facts).expect("serialisable");
            s.push('\n');
            s
        }
        ListFormat::Csv => {
            let mut s = header.join(",") + "\n";
            for f in facts {
                let mut r = row(f);
                if f.optimal_moves.is_none() {
                    r[6] = String::new();
                }
                s += &(r.join(",") + "\n");
            }
            s
        }
        ListFormat::Markdown => {
            let mut s = format!("| {} |\n", header.join(" | "));
            s += &format!("|{}\n", "---|".repeat(header.len()));
            for f in facts {
                s += &format!("| {} |\n", row(f).join(" | "));
            }
            s
        }
        ListFormat::Text => {
            let rows: Vec<Vec<String>> = facts.iter().map(row).collect();
            let widths: Vec<usize> = (0..header.len())
                .map(|c| {
                    rows.iter()
                        .map(|r| r[c].len())
                        .chain([header[c].len()])
                        .max()
                        .unwrap_or(0)
                })
                .collect();
            let mut s = format!(
                "The paper's grid problems ({}; states and edges: x1's component; optimal_moves: \
                 fewest moves from x1 to the goal)\n",
                mode_name(mode)
            );
            let line = |cells: Vec<String>| {
                cells
                    .iter()
                    .zip(&widths)
                    .map(|(c, w)| format!("{c:>w$}"))
                    .collect::<Vec<_>>()
                    .join("  ")
                    + "\n"
            };
            s += &line(header.iter().map(|h| h.to_string()).collect());
            for r in rows {
                s += &line(r);
            }
            s
        }
    }
}

/// A `solve` report as JSON: the report's fields plus `problem` and `model`.
pub fn report_json(report: &PlanReport, source: &str) -> String {
    let mut value = serde_json::to_value(report).expect("serialisable");
    let obj = value.as_object_mut().expect("an object");
    obj.insert("problem".into(), json!(source));
    obj.insert("model".into(), json!(mode_name(report.mode)));
    if report.mode == Mode::Reference {
        // The reference mode's value is an f64: a JSON number, or null where no goal is
        // reachable (JSON has no infinity, and the string "inf" is not a number).
        let v = report
            .cost_to_go_initial
            .parse::<f64>()
            .ok()
            .filter(|v| v.is_finite());
        obj.insert("cost_to_go_initial".into(), json!(v));
    }
    let mut s = serde_json::to_string_pretty(&Value::Object(obj.clone())).expect("serialisable");
    s.push('\n');
    s
}

/// A `solve` report as readable text.
pub fn report_text(r: &PlanReport, source: &str) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "problem      {source}");
    let _ = writeln!(s, "model        {}", mode_name(r.mode));
    let direction = r
        .dijkstra_direction
        .map(|d| format!(", {}", d.replace('-', " ")))
        .unwrap_or_default();
    let _ = writeln!(
        s,
        "planner      {}{}{}",
        r.algorithm.name(),
        direction,
        if r.model_free {
            ", model-free (explore first)"
        } else {
            ""
        }
    );
    let value_type = match r.value_type {
        "units" => format!("exact (u64 multiples of {})", r.unit),
        "big-rational" => "exact (big rationals)".to_string(),
        other => format!("{other} (not exact)"),
    };
    let _ = writeln!(s, "values       {value_type}");
    if r.reachable {
        let _ = writeln!(s, "G*(x1)       {}", r.cost_to_go_initial);
        let moves = r.path.len().saturating_sub(1);
        let nodes: Vec<String> = r.path.iter().map(|v| v.to_string()).collect();
        let _ = writeln!(s, "path         {moves} moves: {}", nodes.join(" "));
    } else {
        let _ = writeln!(
            s,
            "G*(x1)       inf: no goal is reachable from the initial state"
        );
    }
    let unit = match r.algorithm {
        truecost::planning::Algorithm::Dijkstra => "heap pops",
        _ => "sweeps",
    };
    let _ = writeln!(s, "iterations   {} {unit}", r.iterations);
    if r.model_free {
        let _ = writeln!(
            s,
            "actions      {} = {} exploration + {} planner",
            r.actions, r.exploration_actions, r.planner_actions
        );
    } else {
        let _ = writeln!(s, "actions      {} planner", r.actions);
    }
    s
}
