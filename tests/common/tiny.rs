//! Tiny random models written as problem files, and their optima by brute force: every
//! deterministic stationary policy evaluated by exact Gauss–Jordan elimination, nothing from
//! the code under test. The certificate fuzzer (`tests/fuzz_inputs.rs`) checks what `check`
//! accepts against these.

use num_traits::{One, Zero};

use super::Q;

/// An action: its stage cost, its reward (if the file gives rewards) and its outcomes
/// `(successor, probability)`.
#[derive(Clone, Debug)]
pub struct Action {
    /// The stage cost `l(x, a) ≥ 0`.
    pub cost: Q,
    /// The reward `r(x, a)`; without one the discounted objective rewards `-l(x, a)`.
    pub reward: Option<Q>,
    /// Distinct successors with positive probabilities summing to 1.
    pub outcomes: Vec<(usize, Q)>,
}

/// A tiny model: goals have no actions, every other state has at least one (the readers refuse
/// a non-goal state without actions).
#[derive(Clone, Debug)]
pub struct Tiny {
    /// Per state, whether it is a goal.
    pub goals: Vec<bool>,
    /// Per state, its actions in file order.
    pub actions: Vec<Vec<Action>>,
    /// Whether every action has one outcome (written as a deterministic file).
    pub deterministic: bool,
}

/// `c/d` with `low ≤ c ≤ high` and `1 ≤ d ≤ 3`, drawn with `below`.
fn fraction(below: &mut impl FnMut(u64) -> u64, low: i64, high: i64) -> Q {
    let top = low + below((high - low + 1) as u64) as i64;
    super::frac(top, 1 + below(3) as i64)
}

/// A policy: per state the index of its action, `None` for none.
pub type Policy = Vec<Option<usize>>;

/// Solves the `k × (k + 1)` augmented system `a` in place by Gauss–Jordan elimination with
/// exact rationals: afterwards `a[i][k]` is unknown `i`. `regular` says why a pivot exists.
pub fn gauss_jordan(a: &mut [Vec<Q>], regular: &str) {
    let k = a.len();
    for col in 0..k {
        let pivot = (col..k).find(|&r| !a[r][col].is_zero()).expect(regular);
        a.swap(col, pivot);
        let inv = Q::one() / &a[col][col];
        let row: Vec<Q> = a[col].iter().map(|v| v * &inv).collect();
        for (r, other) in a.iter_mut().enumerate() {
            if r != col && !other[col].is_zero() {
                let f = other[col].clone();
                for (o, p) in other.iter_mut().zip(&row).skip(col) {
                    *o -= p * &f;
                }
            }
        }
        a[col] = row;
    }
}

impl Tiny {
    /// A random model of 2 to 5 states drawn with `below(n)` (a number in `0..n`): the last
    /// state a goal, sometimes another; 1 to 3 actions a non-goal state; costs `c/d` with
    /// `c < 5`, `d ≤ 3`; rewards (when `rewards`) `r/d` with `|r| ≤ 3`; one outcome an action
    /// (`deterministic`) or 1 to 3 distinct ones with weights 1 to 3.
    pub fn random(below: &mut impl FnMut(u64) -> u64, deterministic: bool, rewards: bool) -> Tiny {
        let n = 2 + below(4) as usize;
        let mut goals = vec![false; n];
        goals[n - 1] = true;
        if below(3) == 0 {
            goals[below(n as u64) as usize] = true;
        }
        let actions = (0..n)
            .map(|x| {
                if goals[x] {
                    return Vec::new();
                }
                let count = [1, 1, 2, 2, 3, 3][below(6) as usize];
                (0..count)
                    .map(|_| {
                        let cost = fraction(below, 0, 4);
                        let reward = rewards.then(|| fraction(below, -3, 3));
                        let width = if deterministic { 1 } else { 1 + below(3) };
                        let mut successors: Vec<usize> = Vec::new();
                        for _ in 0..width {
                            let y = below(n as u64) as usize;
                            if !successors.contains(&y) {
                                successors.push(y);
                            }
                        }
                        let weights: Vec<i64> =
                            successors.iter().map(|_| 1 + below(3) as i64).collect();
                        let total: i64 = weights.iter().sum();
                        let outcomes = successors
                            .into_iter()
                            .zip(weights)
                            .map(|(y, w)| (y, super::frac(w, total)))
                            .collect();
                        Action {
                            cost,
                            reward,
                            outcomes,
                        }
                    })
                    .collect()
            })
            .collect();
        Tiny {
            goals,
            actions,
            deterministic,
        }
    }

    /// The number of states.
    pub fn states(&self) -> usize {
        self.goals.len()
    }

    /// The problem file: `truecost-problem/1` (moves `{"to", "cost"}`) when deterministic,
    /// `truecost-stochastic/1` otherwise; initial state 0.
    pub fn file(&self) -> String {
        let lists: Vec<String> = self
            .actions
            .iter()
            .map(|list| {
                let actions: Vec<String> = list
                    .iter()
                    .map(|a| {
                        let reward = a
                            .reward
                            .as_ref()
                            .map_or(String::new(), |r| format!(r#", "reward": "{r}""#));
                        if self.deterministic {
                            format!(
                                r#"{{"to": {}, "cost": "{}"{reward}}}"#,
                                a.outcomes[0].0, a.cost
                            )
                        } else {
                            let outs: Vec<String> = a
                                .outcomes
                                .iter()
                                .map(|(y, p)| format!(r#"{{"to": {y}, "p": "{p}"}}"#))
                                .collect();
                            format!(
                                r#"{{"cost": "{}"{reward}, "outcomes": [{}]}}"#,
                                a.cost,
                                outs.join(", ")
                            )
                        }
                    })
                    .collect();
                format!("[{}]", actions.join(", "))
            })
            .collect();
        let goals: Vec<String> = (0..self.states())
            .filter(|&x| self.goals[x])
            .map(|x| x.to_string())
            .collect();
        let tag = if self.deterministic {
            "truecost-problem/1"
        } else {
            "truecost-stochastic/1"
        };
        format!(
            "{{\"format\": \"{tag}\", \"states\": {}, \"initial\": 0, \"goals\": [{}],\n \"actions\": [{}]}}\n",
            self.states(),
            goals.join(", "),
            lists.join(",\n  ")
        )
    }

    /// Whether the episode ends at `x` in the discounted objective (a goal or no action).
    pub fn terminal(&self, x: usize) -> bool {
        self.goals[x] || self.actions[x].is_empty()
    }

    /// The reward of an action in the discounted objective.
    pub fn reward(a: &Action) -> Q {
        a.reward.clone().unwrap_or_else(|| -a.cost.clone())
    }

    /// Every policy choosing an action at each state that has one.
    pub fn policies(&self) -> Vec<Policy> {
        let mut all: Vec<Policy> = vec![Vec::new()];
        for list in &self.actions {
            all = all
                .into_iter()
                .flat_map(|p| {
                    let choices: Vec<Option<usize>> = if list.is_empty() {
                        vec![None]
                    } else {
                        (0..list.len()).map(Some).collect()
                    };
                    choices.into_iter().map(move |c| {
                        let mut q = p.clone();
                        q.push(c);
                        q
                    })
                })
                .collect();
        }
        all
    }

    /// The successors of `x` under `policy` (none at goals and where it chooses nothing).
    fn successors(&self, policy: &Policy, x: usize) -> Vec<usize> {
        match policy[x] {
            Some(i) if !self.goals[x] => self.actions[x][i].outcomes.iter().map(|o| o.0).collect(),
            _ => Vec::new(),
        }
    }

    /// The states from which a state of `target` is reachable along `policy`'s outcomes.
    fn reaching(&self, policy: &Policy, target: &[bool]) -> Vec<bool> {
        let mut can = target.to_vec();
        loop {
            let mut changed = false;
            for x in 0..self.states() {
                if !can[x] && self.successors(policy, x).iter().any(|&y| can[y]) {
                    can[x] = true;
                    changed = true;
                }
            }
            if !changed {
                return can;
            }
        }
    }

    /// Solves `V(x) = constant(x) + weight · Σ_y p(y | x, policy(x)) V(y)` on `unknown`
    /// (the other states' values `known`).
    fn solve(
        &self,
        policy: &Policy,
        unknown: &[usize],
        known: &dyn Fn(usize) -> Q,
        constant: &dyn Fn(&Action) -> Q,
        weight: &Q,
    ) -> Vec<Q> {
        let m = unknown.len();
        let mut a = vec![vec![Q::zero(); m + 1]; m];
        for (i, &x) in unknown.iter().enumerate() {
            let act = &self.actions[x][policy[x].expect("an unknown state acts")];
            a[i][i] += Q::one();
            a[i][m] = constant(act);
            for (y, p) in &act.outcomes {
                match unknown.iter().position(|z| z == y) {
                    Some(j) => a[i][j] -= p * weight,
                    None => a[i][m] += p * weight * known(*y),
                }
            }
        }
        gauss_jordan(&mut a, "the policy's system is regular");
        a.into_iter().map(|row| row[m].clone()).collect()
    }

    /// The expected cost to a goal of `policy` from each state, `None` where it does not reach
    /// a goal with probability 1 (from `x`, every state it can reach must reach a goal).
    pub fn truecost_of(&self, policy: &Policy) -> Vec<Option<Q>> {
        let n = self.states();
        let can = self.reaching(policy, &self.goals);
        let proper: Vec<bool> = (0..n)
            .map(|x| {
                let mut seen = vec![false; n];
                let mut stack = vec![x];
                seen[x] = true;
                while let Some(y) = stack.pop() {
                    if !can[y] {
                        return false;
                    }
                    for z in self.successors(policy, y) {
                        if !seen[z] {
                            seen[z] = true;
                            stack.push(z);
                        }
                    }
                }
                true
            })
            .collect();
        let unknown: Vec<usize> = (0..n).filter(|&x| proper[x] && !self.goals[x]).collect();
        let solved = self.solve(
            policy,
            &unknown,
            &|_| Q::zero(),
            &|a| a.cost.clone(),
            &Q::one(),
        );
        let mut values: Vec<Option<Q>> = (0..n).map(|x| self.goals[x].then(Q::zero)).collect();
        for (x, v) in unknown.into_iter().zip(solved) {
            values[x] = Some(v);
        }
        values
    }

    /// The expected discounted reward of `policy` at `alpha` (0 at terminal states); `None` if
    /// it chooses no action at a state that is not terminal.
    pub fn discounted_of(&self, policy: &Policy, alpha: &Q) -> Option<Vec<Q>> {
        let n = self.states();
        let unknown: Vec<usize> = (0..n).filter(|&x| !self.terminal(x)).collect();
        if unknown.iter().any(|&x| policy[x].is_none()) {
            return None;
        }
        let solved = self.solve(policy, &unknown, &|_| Q::zero(), &Self::reward, alpha);
        let mut values = vec![Q::zero(); n];
        for (x, v) in unknown.into_iter().zip(solved) {
            values[x] = v;
        }
        Some(values)
    }

    /// The probability that `policy` reaches a goal from each state (0 where it chooses
    /// nothing).
    pub fn reach_of(&self, policy: &Policy) -> Vec<Q> {
        let n = self.states();
        let can = self.reaching(policy, &self.goals);
        let unknown: Vec<usize> = (0..n).filter(|&x| can[x] && !self.goals[x]).collect();
        let goals = self.goals.clone();
        let known = move |y: usize| if goals[y] { Q::one() } else { Q::zero() };
        let solved = self.solve(policy, &unknown, &known, &|_| Q::zero(), &Q::one());
        let mut values: Vec<Q> = (0..n).map(&known).collect();
        for (x, v) in unknown.into_iter().zip(solved) {
            values[x] = v;
        }
        values
    }

    /// The truecost optimum: per state the least [`Tiny::truecost_of`] over every policy.
    pub fn truecost_optimum(&self) -> Vec<Option<Q>> {
        let mut best: Vec<Option<Q>> = vec![None; self.states()];
        for p in self.policies() {
            for (b, v) in best.iter_mut().zip(self.truecost_of(&p)) {
                if let Some(v) = v {
                    if b.as_ref().is_none_or(|b| &v < b) {
                        *b = Some(v);
                    }
                }
            }
        }
        best
    }

    /// The discounted optimum at `alpha`: per state the greatest [`Tiny::discounted_of`].
    pub fn discounted_optimum(&self, alpha: &Q) -> Vec<Q> {
        self.greatest(|p| self.discounted_of(p, alpha).expect("every policy acts"))
    }

    /// The greatest reach probability: per state the greatest [`Tiny::reach_of`].
    pub fn reach_optimum(&self) -> Vec<Q> {
        self.greatest(|p| self.reach_of(p))
    }

    fn greatest(&self, value: impl Fn(&Policy) -> Vec<Q>) -> Vec<Q> {
        let mut best: Option<Vec<Q>> = None;
        for p in self.policies() {
            let v = value(&p);
            best = Some(match best {
                None => v,
                Some(b) => b.into_iter().zip(v).map(|(b, v)| b.max(v)).collect(),
            });
        }
        best.expect("at least one policy")
    }

    /// The discounted `Q(x, a) = r(x, a) + α Σ_y p(y | x, a) V(y)`.
    pub fn q_discounted(&self, x: usize, a: usize, alpha: &Q, values: &[Q]) -> Q {
        let act = &self.actions[x][a];
        let future: Q = act
            .outcomes
            .iter()
            .map(|(y, p)| p * &values[*y])
            .fold(Q::zero(), |s, t| s + t);
        Self::reward(act) + alpha * future
    }
}
