//! What `solve --objective`, `compare` and `discount` print: exact strings, with decimals
//! beside them (correctly rounded to the digits shown), in JSON, text, Markdown and LaTeX.

use serde_json::{json, Value};

use super::{Bounds, Model, Objective, ObjectiveError, Solution};
use crate::stochastic::decimal;
use crate::value::{Extended, Rational};

/// Significant digits of the decimals printed beside exact values.
pub const DIGITS: usize = 12;

/// An exact value as text (`inf` for `+∞`).
pub fn exact(v: &Extended) -> String {
    v.to_string()
}

fn rational(r: &Rational) -> Extended {
    Extended::Finite(r.clone())
}

/// The success probability: the exact string if every optimal policy has the same, else
/// `{"min", "max"}`.
pub fn success_json(b: &Bounds) -> Value {
    if b.min == b.max {
        json!(exact(&rational(&b.min)))
    } else {
        json!({"min": exact(&rational(&b.min)), "max": exact(&rational(&b.max))})
    }
}

fn success_text(b: &Bounds) -> String {
    if b.min == b.max {
        decimal(&rational(&b.min), DIGITS)
    } else {
        format!(
            "{} to {}",
            decimal(&rational(&b.min), DIGITS),
            decimal(&rational(&b.max), DIGITS)
        )
    }
}

/// The JSON key of an objective's value at the initial distribution.
pub fn value_key(o: &Objective) -> &'static str {
    match o {
        Objective::Truecost => "cost_to_go_initial",
        Objective::Reach => "reach_probability_initial",
        Objective::Discounted(_) => "discounted_value_initial",
    }
}

/// The policy as action indices in `U(x)` (Gymnasium's action numbers for environments).
pub fn policy_indices(model: &Model, s: &Solution) -> Vec<Option<usize>> {
    s.policy
        .iter()
        .enumerate()
        .map(|(x, a)| a.map(|a| a - model.problem.actions(x).start))
        .collect()
}

/// The JSON report of one objective.
pub fn solution_json(model: &Model, s: &Solution) -> Value {
    let alpha = match &s.objective {
        Objective::Discounted(a) => Some(exact(&rational(a))),
        _ => None,
    };
    let mut v = json!({
        "source": model.name,
        "objective": s.objective.name(),
        "alpha": alpha,
        "rewards": model.reward_source,
        "states": model.problem.states(),
        "initial_states": model.initial.len(),
        "success_probability": success_json(&s.success),
        "policy_success_probability": exact(&rational(&s.policy_success)),
        "terminal_bonus": model.terminal_bonus.as_ref().map(|m| exact(&rational(m))),
        "policy": policy_indices(model, s),
        "values": s.values.iter().map(exact).collect::<Vec<_>>(),
    });
    // Present when computed (always, except the reach objective without its cost where that
    // is finite: `solve --objective reach` without `--with-cost`).
    if s.costs_computed {
        v["expected_truecost"] = json!(exact(&s.truecost));
        v["expected_steps"] = json!(exact(&s.steps));
    }
    v[value_key(&s.objective)] = json!(exact(&s.value_initial));
    v[format!("{}_decimal", value_key(&s.objective))] = json!(decimal(&s.value_initial, DIGITS));
    v
}

/// The text report of one objective.
pub fn solution_text(model: &Model, s: &Solution) -> String {
    let mut out = String::new();
    let objective = match &s.objective {
        Objective::Discounted(a) => format!("discounted, alpha = {a} ({})", model.reward_source),
        o => o.name().to_string(),
    };
    let uniform = model.initial.iter().all(|(_, p)| *p == model.initial[0].1);
    let initial = match model.initial.len() {
        1 => format!("state {}", model.initial[0].0),
        k if uniform => format!("uniform over {k} states (values are expectations)"),
        k => format!("drawn from {k} states (values are expectations)"),
    };
    let value = exact(&s.value_initial);
    let value = if value.len() > 60 {
        format!("({} characters)", value.len())
    } else {
        value
    };
    let rows = [
        ("source", model.name.clone()),
        ("objective", objective),
        ("initial", initial),
        (
            value_key(&s.objective),
            format!("{value} ~ {}", decimal(&s.value_initial, DIGITS)),
        ),
        ("success probability", success_text(&s.success)),
        (
            "policy success",
            decimal(&rational(&s.policy_success), DIGITS),
        ),
        ("expected truecost", policy_cost(s, &s.truecost)),
        ("expected steps", policy_cost(s, &s.steps)),
    ];
    for (k, v) in rows {
        out.push_str(&format!("{k:<26}{v}\n"));
    }
    if let Some(m) = &model.terminal_bonus {
        out.push_str(&format!(
            "{:<26}{m} (Proposition 4's M: the delivery's +20)\n",
            "terminal bonus"
        ));
    }
    let policy: Vec<String> = policy_indices(model, s)
        .iter()
        .map(|a| a.map_or("-".into(), |a| a.to_string()))
        .collect();
    out.push_str(&format!(
        "{:<26}{}\n",
        "policy (action per state)",
        policy.join(" ")
    ));
    out
}

/// The decimal of the reported policy's expected truecost or steps, or that it was not
/// computed ([`Solution::costs_computed`]).
fn policy_cost(s: &Solution, v: &Extended) -> String {
    if s.costs_computed {
        decimal(v, DIGITS)
    } else {
        "not computed (finite; --with-cost computes it)".into()
    }
}

/// One row of `compare`.
#[derive(Clone, Debug)]
pub struct CompareRow {
    /// The objective.
    pub objective: Objective,
    /// Its solution.
    pub solution: Solution,
}

/// Solves every objective: truecost, reach and discounted for each `α` given.
pub fn compare(model: &Model, alphas: &[Rational]) -> Result<Vec<CompareRow>, ObjectiveError> {
    let mut objectives = vec![Objective::Truecost, Objective::Reach];
    objectives.extend(alphas.iter().cloned().map(Objective::Discounted));
    objectives
        .into_iter()
        .map(|o| {
            model.solve(&o).map(|solution| CompareRow {
                objective: o,
                solution,
            })
        })
        .collect()
}

fn label(o: &Objective) -> String {
    match o {
        Objective::Discounted(a) => format!("discounted a={}", short_decimal(a)),
        o => o.name().to_string(),
    }
}

/// The comparison as JSON.
pub fn compare_json(model: &Model, rows: &[CompareRow]) -> Value {
    json!({
        "source": model.name,
        "rewards": model.reward_source,
        "initial_states": model.initial.len(),
        "rows": rows.iter().map(|r| {
            let s = &r.solution;
            let mut v = json!({
                "objective": r.objective.name(),
                "alpha": match &r.objective { Objective::Discounted(a) => Some(a.to_string()), _ => None },
                "value_initial": exact(&s.value_initial),
                "success_probability": success_json(&s.success),
                "expected_truecost": exact(&s.truecost),
                "expected_steps": exact(&s.steps),
            });
            v[value_key(&r.objective)] = json!(exact(&s.value_initial));
            v
        }).collect::<Vec<_>>(),
    })
}

/// `α` as a short decimal (`0.99`), or `p/q` if its expansion does not end within 12 digits.
fn short_decimal(a: &Rational) -> String {
    let d = decimal(&rational(a), DIGITS);
    let d = if d.contains('.') && !d.contains('e') {
        d.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        d
    };
    if crate::value::parse_rational(&d).ok().as_ref() == Some(a) {
        d
    } else {
        a.to_string()
    }
}

/// A table cell: integers exactly, other values as 6 significant digits.
fn cell(v: &Extended) -> String {
    match v {
        Extended::Finite(r) if r.is_integer() => r.to_string(),
        v => decimal(v, 6),
    }
}

/// The comparison's cells as decimals: objective, value, success, truecost, steps.
fn cells(rows: &[CompareRow]) -> Vec<[String; 5]> {
    rows.iter()
        .map(|r| {
            let s = &r.solution;
            [
                label(&r.objective),
                cell(&s.value_initial),
                match (&s.success.min, &s.success.max) {
                    (a, b) if a == b => cell(&rational(a)),
                    (a, b) => format!("{}..{}", cell(&rational(a)), cell(&rational(b))),
                },
                cell(&s.truecost),
                cell(&s.steps),
            ]
        })
        .collect()
}

const HEADER: [&str; 5] = [
    "objective",
    "optimal value",
    "success probability",
    "expected truecost",
    "expected steps",
];

/// The comparison as an aligned text table.
pub fn compare_text(model: &Model, rows: &[CompareRow]) -> String {
    let body = cells(rows);
    let mut width = HEADER.map(str::len);
    for row in &body {
        for (w, c) in width.iter_mut().zip(row) {
            *w = (*w).max(c.len());
        }
    }
    let line = |cells: &[String]| {
        cells
            .iter()
            .zip(width)
            .map(|(c, w)| format!("{c:<w$}"))
            .collect::<Vec<_>>()
            .join("  ")
            .trim_end()
            .to_string()
    };
    let mut out = format!(
        "{} ({}; decimals of exact values)\n",
        model.name, model.reward_source
    );
    out.push_str(&line(&HEADER.map(String::from)));
    out.push('\n');
    for row in &body {
        out.push_str(&line(row));
        out.push('\n');
    }
    out
}

/// The comparison as a Markdown table.
pub fn compare_markdown(model: &Model, rows: &[CompareRow]) -> String {
    let mut out = format!(
        "**{}** ({})\n\n| {} |\n|{}\n",
        model.name,
        model.reward_source,
        HEADER.join(" | "),
        "---|".repeat(5)
    );
    for row in cells(rows) {
        out.push_str(&format!("| {} |\n", row.join(" | ")));
    }
    out
}

/// The comparison as a LaTeX tabular.
pub fn compare_latex(model: &Model, rows: &[CompareRow]) -> String {
    let esc = |s: &str| {
        s.replace('_', "\\_")
            .replace('%', "\\%")
            .replace("inf", "$\\infty$")
    };
    let mut out = format!(
        "% {} ({})\n\\begin{{tabular}}{{lrrrr}}\n\\hline\n{} \\\\\n\\hline\n",
        model.name,
        model.reward_source,
        HEADER.join(" & ")
    );
    for row in cells(rows) {
        let row: Vec<String> = row.iter().map(|c| esc(c)).collect();
        out.push_str(&format!("{} \\\\\n", row.join(" & ")));
    }
    out.push_str("\\hline\n\\end{tabular}\n");
    out
}

/// The facts `problems --env SPEC` lists: sizes, goals and traps, and the exact `G*` and
/// greatest success probability at the initial distribution.
pub fn facts(model: &Model) -> Result<Value, ObjectiveError> {
    let p = &model.problem;
    let truecost = model.solve(&Objective::Truecost)?;
    let reach = model.solve(&Objective::Reach)?;
    let traps = (0..p.states())
        .filter(|&x| model.terminal[x] && !p.is_goal(x))
        .count();
    Ok(json!({
        "source": model.name,
        "states": p.states(),
        "actions": p.action_total(),
        "outcomes": p.outcome_total(),
        "initial_states": model.initial.len(),
        "goals": p.goals().len(),
        "traps": traps,
        "terminal_bonus": model.terminal_bonus.as_ref().map(|m| m.to_string()),
        "cost_to_go_initial": exact(&truecost.value_initial),
        "reach_probability_initial": exact(&reach.value_initial),
        "reach_probability_initial_decimal": decimal(&reach.value_initial, DIGITS),
    }))
}

/// A breakpoint's exact description: a rational, or the unique root of a primitive integer
/// polynomial in a rational bracket of width at most `2^-100 < 1e-30`, with its decimal
/// correctly rounded to 30 digits. The polynomial is the factor vanishing at the point
/// ([`crate::algebra::poly::roots::Root::reduce`]): the minimal polynomial when proved irreducible, else
/// square-free without rational roots.
pub struct PointText {
    /// The value correctly rounded to 30 digits after the point (the exact value when it
    /// has at most 30 digits, zero-padded).
    pub decimal: String,
    /// The value correctly rounded to 12 digits after the point (short forms).
    pub short: String,
    /// `p/q` if the point is rational.
    pub exact: Option<String>,
    /// The polynomial (for an irrational point).
    pub polynomial: Option<String>,
    /// Its degree.
    pub degree: usize,
    /// Whether the polynomial is proved irreducible over `Q` (the minimal polynomial).
    pub minimal: bool,
    /// The bracket's ends (`lo < α < hi`; both equal the point if rational).
    pub bracket: (String, String),
}

/// Digits after the point of the short decimals of breakpoints (tables and interval ends).
pub const SHORT_DIGITS: usize = 12;

/// The text of a breakpoint (refined to a bracket of width at most `2^-100`).
pub fn point_text(r: &crate::algebra::poly::roots::Root) -> PointText {
    let mut r = r.clone();
    r.reduce();
    r.refine_to(&Rational::new(
        num_bigint::BigInt::from(1),
        num_bigint::BigInt::from(1) << 100u32,
    ));
    let rat = |x: &Rational| crate::algebra::intervals::rat(x);
    PointText {
        decimal: r.decimal(30),
        short: r.decimal(SHORT_DIGITS),
        exact: r.as_rational().map(rat),
        polynomial: (!r.exact).then(|| r.polynomial().to_string()),
        degree: if r.exact {
            1
        } else {
            r.polynomial().degree().unwrap_or(0)
        },
        minimal: r.exact || r.reduction == crate::algebra::poly::roots::Reduction::Minimal,
        bracket: (rat(&r.lo), rat(&r.hi)),
    }
}

fn achievement_json(a: &super::parametric::Achievement) -> Value {
    json!({
        "success_probability": success_json(&a.success),
        "success_probability_decimal": success_text(&a.success),
        "truecost": if a.truecost_min == a.truecost_max {
            json!(exact(&a.truecost_min))
        } else {
            json!({"min": exact(&a.truecost_min), "max": exact(&a.truecost_max)})
        },
    })
}

fn end_json(r: Option<&crate::algebra::poly::roots::Root>, none: &str) -> Value {
    match r {
        None => json!(none),
        Some(r) => {
            let t = point_text(r);
            json!(t.exact.unwrap_or(t.decimal))
        }
    }
}

/// `discount --env|--file` as JSON: every breakpoint exactly (polynomial and bracket), every
/// interval with a rational sample point, an optimal policy, the success probability and
/// truecost of its optimal policies.
pub fn discount_json(model: &Model, d: &super::parametric::DiscountAnalysis) -> Value {
    json!({
        "source": model.name,
        "rewards": model.reward_source,
        "initial_states": model.initial.len(),
        "method": discount_method(d),
        "decimals": DECIMALS_NOTE,
        "breakpoints": d.breakpoints.iter().map(|b| {
            let t = point_text(&b.at);
            let mut v = json!({
                "alpha": t.exact.clone().unwrap_or(t.decimal.clone()),
                "alpha_decimal": t.decimal,
                "exact": t.exact,
                "polynomial": t.polynomial,
                "polynomial_degree": t.degree,
                "polynomial_minimal": t.minimal,
                "bracket": [t.bracket.0, t.bracket.1],
                "touch": b.touch,
                "ties": b.ties.iter().map(|(x, a)| json!({"state": x, "optimal_actions": a})).collect::<Vec<_>>(),
            });
            merge(&mut v, achievement_json(&b.achievement));
            v
        }).collect::<Vec<_>>(),
        "intervals": d.intervals.iter().map(|i| {
            let mut v = json!({
                "lo": end_json(i.lo.as_ref(), "0"),
                "hi": end_json(i.hi.as_ref(), "1"),
                "sample_alpha": i.sample.to_string(),
                "policy": i.policy,
                "optimal_actions": i.optimal,
            });
            merge(&mut v, achievement_json(&i.achievement));
            v
        }).collect::<Vec<_>>(),
    })
}

fn merge(v: &mut Value, extra: Value) {
    if let (Some(o), Value::Object(e)) = (v.as_object_mut(), extra) {
        o.extend(e);
    }
}

/// How the breakpoints were obtained, in one line.
pub fn discount_method(d: &super::parametric::DiscountAnalysis) -> String {
    if d.deterministic {
        return format!(
            "exact parametric policy analysis, deterministic: {} probes (exact policy iteration at rational alpha), {} states where the episode runs, values along successor chains of degree <= {}; roots isolated exactly (Descartes bisection), brackets <= 2^-100",
            d.probes, d.running_states, d.degree
        );
    }
    format!(
        "exact parametric policy analysis: {} probes (exact policy iteration at rational alpha), {} states where the episode runs, value denominators of degree <= {}; roots isolated exactly (Descartes bisection), brackets <= 2^-100",
        d.probes, d.running_states, d.degree
    )
}

fn truecost_text(a: &super::parametric::Achievement) -> String {
    if a.truecost_min == a.truecost_max {
        decimal(&a.truecost_min, DIGITS)
    } else {
        format!(
            "{} to {}",
            decimal(&a.truecost_min, DIGITS),
            decimal(&a.truecost_max, DIGITS)
        )
    }
}

fn short_point(r: Option<&crate::algebra::poly::roots::Root>, none: &str) -> String {
    match r {
        None => none.into(),
        Some(r) => {
            let t = point_text(r);
            t.exact.unwrap_or_else(|| format!("{}...", t.short))
        }
    }
}

fn ties_text(b: &super::parametric::Breakpoint) -> String {
    b.ties
        .iter()
        .map(|(x, a)| {
            format!(
                "state {x}: {{{}}}",
                a.iter()
                    .map(ToString::to_string)
                    .collect::<Vec<_>>()
                    .join(",")
            )
        })
        .collect::<Vec<_>>()
        .join("; ")
}

/// How the decimals of `discount` are made, in one line.
pub const DECIMALS_NOTE: &str = "every decimal is correctly rounded to the digits shown (to nearest); '...' marks a value whose expansion goes on";

/// `discount --env|--file` as text. Every decimal is correctly rounded to the digits shown
/// (to nearest, a tie away from zero): breakpoints to 30 digits after the point, interval ends
/// to 12, probabilities and truecosts to 12 significant digits; `...` after a decimal marks a
/// value whose expansion goes on (an irrational breakpoint).
pub fn discount_text(model: &Model, d: &super::parametric::DiscountAnalysis) -> String {
    let mut out = format!(
        "source       {}\nrewards      {} (discounted, maximised)\nmethod       {}\ndecimals     {DECIMALS_NOTE}\nbreakpoints  {} (alpha in (0,1) where the set of discount-optimal policies changes)\n",
        model.name,
        model.reward_source,
        discount_method(d),
        d.breakpoints.len()
    );
    for (k, i) in d.intervals.iter().enumerate() {
        out.push_str(&format!(
            "alpha in ({}, {}): success probability {}, truecost {}\n",
            short_point(i.lo.as_ref(), "0"),
            short_point(i.hi.as_ref(), "1"),
            success_text(&i.achievement.success),
            truecost_text(&i.achievement)
        ));
        if let Some(b) = d.breakpoints.get(k) {
            let t = point_text(&b.at);
            let what = match (&t.exact, &t.polynomial) {
                (Some(q), _) => format!("alpha = {q} exactly"),
                (None, Some(p)) if t.minimal && p.len() <= 120 => format!(
                    "alpha = {}... (the root of the minimal polynomial {p} in ({}, {}))",
                    t.decimal, t.bracket.0, t.bracket.1
                ),
                (None, Some(p)) if p.len() <= 120 => format!(
                    "alpha = {}... (the root of {p} in ({}, {}); square-free, no rational roots, irreducibility not proved)",
                    t.decimal, t.bracket.0, t.bracket.1
                ),
                _ if t.minimal => format!(
                    "alpha = {}... (the root of a degree-{} minimal polynomial in ({}, {}); see --format json)",
                    t.decimal, t.degree, t.bracket.0, t.bracket.1
                ),
                _ => format!(
                    "alpha = {}... (the root of a polynomial with this root (degree {}, square-free, no rational roots; irreducibility not proved) in ({}, {}); see --format json)",
                    t.decimal, t.degree, t.bracket.0, t.bracket.1
                ),
            };
            out.push_str(&format!(
                "  breakpoint {}: {what}\n    {}: {}\n    at the breakpoint: success probability {}, truecost {}\n",
                k + 1,
                if b.touch { "tie at this point only (same optimal policies on both sides)" } else { "optimal actions at the point where they change" },
                ties_text(b),
                success_text(&b.achievement.success),
                truecost_text(&b.achievement)
            ));
        }
    }
    out
}

fn discount_rows(d: &super::parametric::DiscountAnalysis) -> Vec<[String; 3]> {
    let mut rows = Vec::new();
    for (k, i) in d.intervals.iter().enumerate() {
        rows.push([
            format!(
                "({}, {})",
                short_point(i.lo.as_ref(), "0"),
                short_point(i.hi.as_ref(), "1")
            ),
            success_text(&i.achievement.success),
            truecost_text(&i.achievement),
        ]);
        if let Some(b) = d.breakpoints.get(k) {
            rows.push([
                format!("= {}", short_point(Some(&b.at), "")),
                success_text(&b.achievement.success),
                truecost_text(&b.achievement),
            ]);
        }
    }
    rows
}

const DISCOUNT_HEADER: [&str; 3] = ["alpha", "success probability", "truecost"];

/// `discount --env|--file` as a Markdown table (intervals and breakpoints in order).
pub fn discount_markdown(model: &Model, d: &super::parametric::DiscountAnalysis) -> String {
    let mut out = format!(
        "**{}** ({}, discounted): {} breakpoints; decimals correctly rounded to the digits shown\n\n| {} |\n|---|---|---|\n",
        model.name,
        model.reward_source,
        d.breakpoints.len(),
        DISCOUNT_HEADER.join(" | ")
    );
    for row in discount_rows(d) {
        out.push_str(&format!("| {} |\n", row.join(" | ")));
    }
    out
}

/// `discount --env|--file` as a LaTeX tabular.
pub fn discount_latex(model: &Model, d: &super::parametric::DiscountAnalysis) -> String {
    let esc = |s: &str| {
        s.replace('_', "\\_")
            .replace("inf", "$\\infty$")
            .replace(" to ", "--")
    };
    let mut out = format!(
        "% {} ({}, discounted): {} breakpoints; decimals correctly rounded to the digits shown\n\\begin{{tabular}}{{lrr}}\n\\hline\n$\\alpha$ & success probability & truecost \\\\\n\\hline\n",
        model.name,
        model.reward_source,
        d.breakpoints.len()
    );
    for row in discount_rows(d) {
        let row: Vec<String> = row.iter().map(|c| esc(c)).collect();
        out.push_str(&format!("{} \\\\\n", row.join(" & ")));
    }
    out.push_str("\\hline\n\\end{tabular}\n");
    out
}
