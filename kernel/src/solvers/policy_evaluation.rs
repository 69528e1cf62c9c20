//! Exact policy evaluation: the total cost `L(π, x) = Σ_{k≥1} l(x_k, π(x_k))` of a
//! deterministic stationary policy from every state (docs/spec.md §1).
//!
//! Convention (consistent with `G* = +∞` where no goal is reachable): a trajectory that never
//! reaches a goal and terminates — it runs into a node where `π` is undefined, or circles
//! forever, even around a zero-cost cycle — has true cost `+∞`: the task is never accomplished.

use crate::model::{Decision, Graph};
use crate::value::CostValue;

/// `L(π, v)` for every node `v`, in `O(|X|)`.
///
/// ```
/// use truecost_kernel::model::{Decision, Graph};
/// use truecost_kernel::solvers::policy_evaluation::evaluate_policy;
/// let g = Graph::<f64>::from_adjacency(vec![vec![(1, 2.0)], vec![(0, 0.0), (2, 3.0)], vec![]],
///     0, &[2], vec![0, 1, 2], ());
/// let reach = [Some(Decision::Move(0)), Some(Decision::Move(1)), Some(Decision::Terminate)];
/// assert_eq!(evaluate_policy(&g, &reach), vec![5.0, 3.0, 0.0]);
/// let circle = [Some(Decision::Move(0)), Some(Decision::Move(0)), Some(Decision::Terminate)];
/// assert_eq!(evaluate_policy(&g, &circle), vec![f64::INFINITY, f64::INFINITY, 0.0]);
/// ```
pub fn evaluate_policy<V: CostValue, U>(
    graph: &Graph<V, U>,
    policy: &[Option<Decision>],
) -> Vec<V> {
    const UNSEEN: u8 = 0;
    const ON_STACK: u8 = 1;
    const DONE: u8 = 2;
    let n = graph.nodes();
    let mut value: Vec<Option<V>> = vec![None; n];
    let mut state = vec![UNSEEN; n];
    let mut stack = Vec::new();
    for start in 0..n {
        if state[start] != UNSEEN {
            continue;
        }
        // Walk forward until a resolved node, a terminating or stuck node, or a cycle. Every
        // node left on the stack applies a valid move to the next one.
        let mut x = start;
        let tail = loop {
            if state[x] == DONE {
                break value[x].clone().expect("resolved");
            }
            if state[x] == ON_STACK {
                break V::infinity(); // a cycle that never terminates
            }
            let resolved = match policy[x] {
                Some(Decision::Terminate) if graph.is_goal(x) => V::zero(),
                Some(Decision::Move(i)) if i < graph.degree(x) => {
                    state[x] = ON_STACK;
                    stack.push((x, i));
                    x = graph.edges(x).nth(i).expect("index checked").0;
                    continue;
                }
                _ => V::infinity(),
            };
            value[x] = Some(resolved.clone());
            state[x] = DONE;
            break resolved;
        };
        // Unwind, accumulating stage costs back to the start.
        let mut acc = tail;
        while let Some((y, i)) = stack.pop() {
            let (_, c) = graph.edges(y).nth(i).expect("index checked");
            acc = c.plus(&acc);
            value[y] = Some(acc.clone());
            state[y] = DONE;
        }
    }
    value
        .into_iter()
        .map(|v| v.expect("every node resolved"))
        .collect()
}
