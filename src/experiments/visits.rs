//! State–action visit counts of one seeded Q-learning run (for the `visits` figure overlay).

use crate::learning::plan::{sample_rng, EpsilonSchedule, Plan, Probability};
use crate::learning::q_learning::{LearningError, LearningValue, QLearner, QLearningConfig};
use crate::model::Graph;
use crate::value::Rational;

/// How often each move of `graph` was applied in a derandomized (ρ = 1, Q₀ = 0) Q-learning run
/// with constant `epsilon` and the random exploration plan, seeded by `seed`; indexed by
/// `(node, action position)` as `counts[node][position]`. Like every run of the learner, it stops
/// as soon as the values have converged to `optimum`.
///
/// ```
/// use truecost::experiments::visits::visit_counts;
/// use truecost::model::Graph;
/// use truecost::solvers::dijkstra;
/// use truecost::value::{parse_rational, Units};
/// let g = Graph::from_adjacency(vec![vec![(1, Units(1))], vec![(0, Units(1)), (2, Units(1))], vec![]],
///     0, &[2], vec![0, 1, 2], num_rational::BigRational::from_integer(1.into()));
/// let optimum = dijkstra::to_goals(&g).cost_to_go;
/// let counts = visit_counts(&g, &optimum, &parse_rational("1").unwrap(), 7, 5, 20).unwrap();
/// assert_eq!(counts.len(), 3);
/// assert!(counts[0][0] >= 1); // the run starts with the only move of x1
/// assert_eq!(counts[2].len(), 1); // the goal has only its termination action
/// ```
pub fn visit_counts<V: LearningValue>(
    graph: &Graph<V>,
    optimum: &[V],
    epsilon: &Rational,
    seed: u64,
    episodes: u32,
    max_steps: u32,
) -> Result<Vec<Vec<u64>>, LearningError> {
    let epsilon = Probability::new("ε", epsilon)?;
    let config = QLearningConfig {
        episodes,
        max_steps,
        ..QLearningConfig::paper(EpsilonSchedule::Constant(epsilon))
    };
    let mut learner = QLearner::new(
        graph,
        optimum,
        V::zero(),
        &config,
        sample_rng(seed, 0),
        Plan::Random,
    )?;
    let mut counts: Vec<Vec<u64>> = (0..graph.nodes())
        .map(|v| vec![0; graph.degree(v) + usize::from(graph.is_goal(v))])
        .collect();
    learner.run_observed(&mut |state: usize, action: usize, _: &V, _: &V, _: &[V]| {
        counts[state][action] += 1;
    });
    Ok(counts)
}
