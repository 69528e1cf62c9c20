//! `truecost._native`: the Python bindings of the truecost library. Each function takes an
//! input (`kind`: `env`, `file` or `json`; `text`: the `--env` spec, the file's path or the
//! problem file's text; `name`: the model's name for `json`), runs the library functions the
//! command line runs for the same input (`solve --objective`, `compare`, `discount`) and
//! returns their answers exactly (`fractions.Fraction`, `math.inf`) in dicts that
//! `python/truecost` wraps. No solver logic lives here.

mod convert;
mod load;
mod run;

use pyo3::prelude::*;
use pyo3::types::PyDict;

use truecost::objectives::parametric::discount_breakpoints_with;
use truecost::objectives::report::compare as compare_objectives;
use truecost::objectives::{failure_set, parse_alpha, parse_objective, PolicyCost};

use load::Input;
use run::interruptible;

pyo3::create_exception!(
    truecost,
    Error,
    pyo3::exceptions::PyValueError,
    "A refusal of truecost: bad input, or a problem beyond the exact engine's bounds. The message is the command line's one-line message."
);

fn input(kind: &str, text: String, name: Option<String>) -> PyResult<Input> {
    Input::new(kind, text, name).map_err(Error::new_err)
}

/// One objective, exactly: `truecost solve --algorithm exact --objective O [--alpha A]
/// [--with-cost]` ([`truecost::objectives::Model::solve_with`]; truecost is the paper's
/// objective, docs/spec.md §3). The reach objective's policy cost is computed only with
/// `with_cost` (or where it is infinite), as on the command line; `with_cost` with another
/// objective is refused with the command line's message.
#[pyfunction]
#[pyo3(signature = (kind, text, name, objective, alpha, with_cost))]
fn solve<'py>(
    py: Python<'py>,
    kind: &str,
    text: String,
    name: Option<String>,
    objective: String,
    alpha: Option<String>,
    with_cost: bool,
) -> PyResult<Bound<'py, PyDict>> {
    if with_cost && objective != "reach" {
        return Err(Error::new_err("--with-cost applies to --objective reach (the other objectives always compute the reported policy's expected truecost and steps)"));
    }
    let input = input(kind, text, name)?;
    let cost = if with_cost {
        PolicyCost::Computed
    } else {
        PolicyCost::IfInfinite
    };
    let (model, solution) = interruptible(py, move |_| {
        let objective = parse_objective(&objective, alpha.as_deref())?;
        let model = input.model()?;
        let solution = model
            .solve_with(&objective, cost)
            .map_err(|e| e.to_string())?;
        Ok((model, solution))
    })?;
    convert::solution(py, &model, &solution)
}

/// Every objective side by side: `truecost compare --alphas A,...`
/// ([`truecost::objectives::report::compare`]).
#[pyfunction]
#[pyo3(signature = (kind, text, name, alphas))]
fn compare<'py>(
    py: Python<'py>,
    kind: &str,
    text: String,
    name: Option<String>,
    alphas: Vec<String>,
) -> PyResult<Bound<'py, PyDict>> {
    let input = input(kind, text, name)?;
    let (model, rows) = interruptible(py, move |_| {
        let alphas = alphas
            .iter()
            .map(|a| parse_alpha(a.trim()))
            .collect::<Result<Vec<_>, _>>()?;
        let model = input.model()?;
        let rows = compare_objectives(&model, &alphas).map_err(|e| e.to_string())?;
        Ok((model, rows))
    })?;
    let d = PyDict::new(py);
    d.set_item("source", &model.name)?;
    d.set_item("rewards", model.reward_source)?;
    let rows = rows
        .iter()
        .map(|r| convert::solution(py, &model, &r.solution))
        .collect::<PyResult<Vec<_>>>()?;
    d.set_item("rows", rows)?;
    Ok(d)
}

/// The exact discount breakpoints: `truecost discount`
/// ([`truecost::objectives::parametric::discount_breakpoints_with`], the set where a
/// discount-optimal policy fails read off them by [`truecost::objectives::failure_set`]).
/// Interrupted between two probes of the analysis.
#[pyfunction]
#[pyo3(signature = (kind, text, name))]
fn discount<'py>(
    py: Python<'py>,
    kind: &str,
    text: String,
    name: Option<String>,
) -> PyResult<Bound<'py, PyDict>> {
    let input = input(kind, text, name)?;
    let (model, analysis) = interruptible(py, move |cancel| {
        let model = input.discount_model()?;
        let analysis = discount_breakpoints_with(&model, &mut |_| cancel.check())
            .map_err(|e| e.to_string())?;
        Ok((model, analysis))
    })?;
    let set = failure_set(&analysis);
    convert::discount(py, &model, &analysis, &set)
}

/// The module `truecost._native`.
#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("Error", m.py().get_type::<Error>())?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("POLL_SECONDS", run::POLL.as_secs_f64())?;
    m.add_function(wrap_pyfunction!(solve, m)?)?;
    m.add_function(wrap_pyfunction!(compare, m)?)?;
    m.add_function(wrap_pyfunction!(discount, m)?)?;
    Ok(())
}
