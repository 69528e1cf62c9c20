//! The engine's answers as Python objects: every number exact (`fractions.Fraction` built from
//! the numerator's and denominator's integers, `math.inf` for `+∞`), in plain dicts and lists
//! that `truecost/__init__.py` wraps in its result classes.

use num_bigint::BigInt;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyFloat, PyList};

use truecost::algebra::intervals::{point_text as set_point_text, set_text, DiscountSet, Point};
use truecost::algebra::poly::roots::{Reduction, Root};
use truecost::objectives::parametric::{Achievement, DiscountAnalysis};
use truecost::objectives::report::{discount_method, point_text, policy_indices};
use truecost::objectives::{Bounds, Model, Objective, Solution};
use truecost::value::{parse_rational, Extended, Rational};

use crate::Error;

/// A value of the extended reals: a `Fraction`, or `math.inf`.
fn extended<'py>(py: Python<'py>, v: &Extended) -> PyResult<Bound<'py, PyAny>> {
    match v {
        Extended::Finite(r) => r.into_pyobject(py),
        Extended::Infinite => Ok(PyFloat::new(py, f64::INFINITY).into_any()),
    }
}

fn extended_list<'py>(py: Python<'py>, values: &[Extended]) -> PyResult<Bound<'py, PyList>> {
    let items = values
        .iter()
        .map(|v| extended(py, v))
        .collect::<PyResult<Vec<_>>>()?;
    PyList::new(py, items)
}

fn bounds(d: &Bound<'_, PyDict>, key: &str, b: &Bounds) -> PyResult<()> {
    d.set_item(key, (&b.min, &b.max))
}

/// One objective's solution (`solve --objective`, a row of `compare`); `expected_truecost` and
/// `expected_steps` are `None` where they were not computed (the reach objective without its
/// cost, [`truecost::objectives::Solution::costs_computed`]), as the command line leaves them
/// out.
pub fn solution<'py>(py: Python<'py>, model: &Model, s: &Solution) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("source", &model.name)?;
    d.set_item("objective", s.objective.name())?;
    let alpha = match &s.objective {
        Objective::Discounted(a) => Some(a),
        _ => None,
    };
    d.set_item("alpha", alpha)?;
    d.set_item("rewards", model.reward_source)?;
    d.set_item("states", model.problem.states())?;
    d.set_item("initial_states", model.initial.len())?;
    d.set_item("value", extended(py, &s.value_initial)?)?;
    d.set_item("values", extended_list(py, &s.values)?)?;
    d.set_item("policy", policy_indices(model, s))?;
    bounds(&d, "success", &s.success)?;
    d.set_item("policy_success", &s.policy_success)?;
    let computed = |v| s.costs_computed.then(|| extended(py, v)).transpose();
    d.set_item("expected_truecost", computed(&s.truecost)?)?;
    d.set_item("expected_steps", computed(&s.steps)?)?;
    d.set_item("terminal_bonus", model.terminal_bonus.as_ref())?;
    Ok(d)
}

fn rational(text: &str) -> PyResult<Rational> {
    parse_rational(text).map_err(|e| Error::new_err(format!("internal error (please report): {e}")))
}

fn integers(p: &truecost::algebra::poly::Poly) -> Vec<BigInt> {
    p.coefficients().iter().map(|c| c.to_integer()).collect()
}

/// An algebraic point as a dict: `exact` (a `Fraction` or `None`), `interval` (two
/// `Fraction`s isolating it), `polynomial` (integer coefficients, constant first), `minimal`
/// (the polynomial is proved irreducible), `decimal` (correctly rounded to 30 digits).
fn root<'py>(py: Python<'py>, r: &Root) -> PyResult<Bound<'py, PyDict>> {
    let t = point_text(r);
    let mut reduced = r.clone();
    reduced.reduce();
    let d = PyDict::new(py);
    let exact = t.exact.as_deref().map(rational).transpose()?;
    d.set_item("exact", exact)?;
    d.set_item(
        "interval",
        (rational(&t.bracket.0)?, rational(&t.bracket.1)?),
    )?;
    d.set_item("polynomial", integers(&reduced.polynomial()))?;
    d.set_item("minimal", t.minimal)?;
    d.set_item("decimal", t.decimal)?;
    Ok(d)
}

/// An end of a piece of the failure set, in the shape of [`root`], with the command line's
/// text of it.
fn point<'py>(py: Python<'py>, p: &Point) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    let exact = match p {
        Point::Zero => Some(Rational::from_integer(0.into())),
        Point::One => Some(Rational::from_integer(1.into())),
        Point::Root(a) => a.as_rational(),
    };
    match (&exact, p) {
        (Some(q), _) => {
            d.set_item("interval", (q, q))?;
            d.set_item("polynomial", vec![-q.numer().clone(), q.denom().clone()])?;
            d.set_item("minimal", true)?;
            d.set_item("decimal", truecost::algebra::poly::decimal_rounded(q, 30))?;
        }
        (None, Point::Root(a)) => {
            let mut b = a.clone();
            b.refine_to(&Rational::new(BigInt::from(1), BigInt::from(1) << 100u32));
            let (poly, how) = b.reduced_polynomial();
            d.set_item("interval", (&b.lo, &b.hi))?;
            d.set_item("polynomial", integers(&poly.primitive()))?;
            d.set_item("minimal", how == Reduction::Minimal)?;
            d.set_item("decimal", b.decimal_rounded(30))?;
        }
        (None, _) => unreachable!("0 and 1 are rational"),
    }
    d.set_item("exact", exact)?;
    d.set_item("text", set_point_text(p))?;
    Ok(d)
}

fn achievement(d: &Bound<'_, PyDict>, a: &Achievement) -> PyResult<()> {
    let py = d.py();
    bounds(d, "success", &a.success)?;
    d.set_item(
        "truecost",
        (
            extended(py, &a.truecost_min)?,
            extended(py, &a.truecost_max)?,
        ),
    )
}

fn failure_set<'py>(py: Python<'py>, set: &DiscountSet) -> PyResult<Bound<'py, PyList>> {
    let pieces = set
        .pieces
        .iter()
        .map(|p| {
            let d = PyDict::new(py);
            d.set_item("lo", point(py, &p.lo)?)?;
            d.set_item("lo_closed", p.lo_closed)?;
            d.set_item("hi", point(py, &p.hi)?)?;
            d.set_item("hi_closed", p.hi_closed)?;
            Ok(d)
        })
        .collect::<PyResult<Vec<_>>>()?;
    PyList::new(py, pieces)
}

/// `discount`'s analysis: breakpoints, intervals and the failure set.
pub fn discount<'py>(
    py: Python<'py>,
    model: &Model,
    analysis: &DiscountAnalysis,
    set: &DiscountSet,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("source", &model.name)?;
    d.set_item("rewards", model.reward_source)?;
    d.set_item("initial_states", model.initial.len())?;
    d.set_item("method", discount_method(analysis))?;
    d.set_item("deterministic", analysis.deterministic)?;
    let mut breakpoints = Vec::with_capacity(analysis.breakpoints.len());
    for b in &analysis.breakpoints {
        let e = root(py, &b.at)?;
        e.set_item("touch", b.touch)?;
        e.set_item("ties", b.ties.clone())?;
        achievement(&e, &b.achievement)?;
        breakpoints.push(e);
    }
    d.set_item("breakpoints", PyList::new(py, breakpoints)?)?;
    let mut intervals = Vec::with_capacity(analysis.intervals.len());
    for (i, interval) in analysis.intervals.iter().enumerate() {
        let e = PyDict::new(py);
        // Interval i lies between breakpoints i - 1 and i (0 and 1 at the ends).
        e.set_item("lo", i.checked_sub(1))?;
        e.set_item("hi", (i < analysis.breakpoints.len()).then_some(i))?;
        e.set_item("sample", &interval.sample)?;
        e.set_item("policy", interval.policy.clone())?;
        e.set_item("optimal", interval.optimal.clone())?;
        achievement(&e, &interval.achievement)?;
        intervals.push(e);
    }
    d.set_item("intervals", PyList::new(py, intervals)?)?;
    d.set_item("failure_set", failure_set(py, set)?)?;
    d.set_item("failure_set_text", set_text(set))?;
    Ok(d)
}
