//! The optimal-actions overlay of a problem drawn from its states' positions (the paper's grid
//! problems, problem files): every exactly optimal action
//! ([`crate::objectives::actions::optimal_actions`]: exact `Q`-value equal to the optimal value,
//! used by some optimal stationary policy) as an arrow to the state it aims at, several arrows
//! where actions tie, and the legend that says so. The benchmarks' maps use the same legend
//! ([`super::envs`]).

use super::render::{ActionGlyph, LegendEntry, LegendKey, Overlay};
use crate::objectives::actions::optimal_actions;
use crate::objectives::{Model, Solution};

/// Every optimal action of every state as an arrow to `aims_at(action)` (a global action id of
/// [`Model::problem`]: the state its move aims at), ties as several arrows, with the legend
/// (`place`: what a state is called in it, e.g. "grid point").
///
/// ```
/// use truecost::figures::policy::actions_overlay;
/// use truecost::figures::render::{ActionGlyph, Overlay};
/// use truecost::model::file::from_json;
/// use truecost::objectives::{Model, Objective};
/// // Two paths of cost 2 from 0 to the goal 3 (through 1 or 2): a tie at 0.
/// let p = from_json(r#"{"initial":0,"goals":[3],"actions":[
///   [{"to":1,"cost":"1"},{"to":2,"cost":"1"}],[{"to":3,"cost":"1"}],[{"to":3,"cost":"1"}],[]]}"#).unwrap();
/// let m = Model::from_deterministic(&p, "tie".into()).unwrap();
/// let s = m.solve(&Objective::Truecost).unwrap();
/// let to = |a: usize| m.problem.outcomes(a)[0].successor;
/// let Overlay::Actions { actions, legend } = actions_overlay(&m, &s, to, "state") else { panic!() };
/// assert_eq!(actions[0], vec![ActionGlyph::Move(1), ActionGlyph::Move(2)]);
/// assert_eq!(actions[1], vec![ActionGlyph::Move(3)]);
/// assert!(actions[3].is_empty()); // the goal
/// assert_eq!(legend.len(), 2); // an arrow, and several arrows at one state
/// ```
pub fn actions_overlay(
    model: &Model,
    s: &Solution,
    aims_at: impl Fn(usize) -> usize,
    place: &str,
) -> Overlay {
    let optimal = optimal_actions(model, s);
    let actions: Vec<Vec<ActionGlyph>> = optimal
        .iter()
        .map(|list| {
            list.iter()
                .map(|&a| ActionGlyph::Move(aims_at(a)))
                .collect()
        })
        .collect();
    let tied = optimal.iter().any(|list| list.len() > 1);
    let legend = legend(&actions, tied, place, "an obstacle", false);
    Overlay::Actions { actions, legend }
}

/// The legend of an optimal-actions overlay: an entry for each kind of glyph the figure
/// shows — arrows, several glyphs at one `place` (tied actions), bars (moves into `obstacle`)
/// — and none for what it does not show.
pub(crate) fn legend(
    actions: &[Vec<ActionGlyph>],
    tied: bool,
    place: &str,
    obstacle: &str,
    slippery: bool,
) -> Vec<LegendEntry> {
    let shown = |blocked: bool| {
        actions
            .iter()
            .flatten()
            .any(|g| matches!(g, ActionGlyph::Blocked { .. }) == blocked)
    };
    let mut legend = Vec::new();
    if shown(false) {
        legend.push(LegendEntry {
            key: LegendKey::Arrow,
            text: format!("arrow: an optimal action, towards the {place} its move aims at (alone at a {place}: the only optimal action)"),
        });
    }
    if tied {
        legend.push(LegendEntry {
            key: LegendKey::Tie,
            text: format!("several at one {place}: tied optimal actions (exactly equal Q-values), each chosen by some optimal policy"),
        });
    }
    if shown(true) {
        legend.push(LegendEntry {
            key: LegendKey::Blocked,
            text: format!(
                "bar: an optimal action whose move aims into {obstacle}: the agent stays in place{}",
                if slippery { " unless it slips" } else { "" }
            ),
        });
    }
    legend
}
