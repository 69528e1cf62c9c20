//! The paper's grid problems (docs/spec.md §5) in the stochastic model, in both modes (docs/spec.md §7).
//!
//! * [`exact_grid`] — the paper's text: exact geometry, exact step cost (unit or 800/19), exact
//!   probabilities from `γ`'s decimal text.
//! * [`reference_grid`] — the paper's code: its layout and action order, `f64` Euclidean step
//!   costs on its coordinates, probabilities computed in `f64` as that code does, and its
//!   value-iteration rules ([`super::value_iteration::ViOptions::reference`]).
//! * [`exact_twin`] — the exact counterpart of a reference grid (exact geometry, exact step
//!   cost 800/19, same noise model and `γ`), against which the reference runs are measured.

use super::value_iteration::FloatModel;
use super::{NoiseModel, Predictability, StochasticError, StochasticProblem};
use crate::problems::{GridLayout, ProblemError, StepCost};

/// Why a grid could not be built.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum GridError {
    /// Unknown problem id.
    #[error("{0}")]
    Problem(#[from] ProblemError),
    /// Invalid stochastic parameters.
    #[error("{0}")]
    Stochastic(#[from] StochasticError),
}

/// A grid problem as the paper's code runs it: the structure (exact probabilities, for
/// reference) and the `f64` numbers its value iteration uses.
#[derive(Clone, Debug)]
pub struct ReferenceGrid {
    /// The reference layout (its action order) with exact probabilities.
    pub problem: StochasticProblem,
    /// `f64` Euclidean step costs and `f64` probabilities as the reference code computes them.
    pub float: FloatModel,
}

/// Paper problem `id` in the exact stochastic model.
///
/// ```
/// use truecost::problems::StepCost;
/// use truecost::stochastic::{grid::exact_grid, NoiseModel, Predictability};
/// let p = exact_grid(10, StepCost::Unit, NoiseModel::Paper, &Predictability::parse("0.9").unwrap()).unwrap();
/// assert_eq!((p.states(), p.initial(), p.goals()), (400, 41, &[206][..]));
/// ```
pub fn exact_grid(
    id: usize,
    step: StepCost,
    noise: NoiseModel,
    gamma: &Predictability,
) -> Result<StochasticProblem, GridError> {
    let problem = GridLayout::exact(id)?.to_problem(step);
    Ok(StochasticProblem::from_deterministic(
        &problem, noise, gamma,
    )?)
}

/// Paper problem `id` as the reference code runs it (module docs).
pub fn reference_grid(
    id: usize,
    noise: NoiseModel,
    gamma: &Predictability,
) -> Result<ReferenceGrid, GridError> {
    let layout = GridLayout::reference(id)?;
    let problem =
        StochasticProblem::from_deterministic(&layout.to_problem(StepCost::Unit), noise, gamma)?;
    let graph = layout.to_reference_graph();
    let cost: Vec<f64> = (0..graph.nodes())
        .flat_map(|v| graph.edges(v).map(|(_, c)| *c).collect::<Vec<_>>())
        .collect();
    let float =
        FloatModel::reference(&problem, cost).expect("built from a noise model, one cost per move");
    Ok(ReferenceGrid { problem, float })
}

/// The exact counterpart of [`reference_grid`]: exact geometry, step cost 800/19, same noise
/// model and `γ`; `None` if its moves differ from the reference layout's as sets (they agree on
/// all 19 problems; only the order of moves differs, on problems 3, 13, 14, 16).
pub fn exact_twin(
    id: usize,
    noise: NoiseModel,
    gamma: &Predictability,
) -> Result<Option<StochasticProblem>, GridError> {
    let exact = GridLayout::exact(id)?;
    let reference = GridLayout::reference(id)?;
    let same = exact.initial == reference.initial
        && exact.goal == reference.goal
        && exact
            .neighbours
            .iter()
            .zip(&reference.neighbours)
            .all(|(a, b)| {
                let (mut a, mut b) = (a.clone(), b.clone());
                a.sort_unstable();
                b.sort_unstable();
                a == b
            });
    if !same {
        return Ok(None);
    }
    Ok(Some(exact_grid(id, StepCost::Euclidean, noise, gamma)?))
}
