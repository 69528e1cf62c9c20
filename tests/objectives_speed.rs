//! The objectives' expected truecost and number of steps of the reported policy, which
//! `Model::solve` takes from `G*` (truecost objective) or from one exact solve reduced at the
//! initial states only (`evaluate_at`), against a full exact evaluation of the reported policy
//! at every state (`evaluate`) taken at the initial distribution by hand: on the paper's
//! problems (both noise models, both step costs, several `γ`), every benchmark grid pattern,
//! and the Gymnasium environments (Taxi draws its initial state from 300 states).

use num_traits::{One, Zero};
use truecost::envs::EnvSpec;
use truecost::objectives::{Model, Objective};
use truecost::problems::StepCost;
use truecost::stochastic::benchmark::{pattern_grid, CostRange, GridPattern};
use truecost::stochastic::grid::exact_grid;
use truecost::stochastic::policy_iteration::evaluate;
use truecost::stochastic::{NoiseModel, Predictability, StochasticAction, StochasticProblem};
use truecost::value::{Extended, Rational};

/// `Σ p·v` over the model's initial distribution of per-state values, `+∞` if any is.
fn expected(model: &Model, values: &[Extended]) -> Extended {
    let mut sum = Rational::zero();
    for (x, p) in &model.initial {
        match &values[*x] {
            Extended::Finite(v) => sum += v * p,
            Extended::Infinite => return Extended::Infinite,
        }
    }
    Extended::Finite(sum)
}

/// The model's problem with every action costing 1 where the episode runs, 0 where it is over.
fn unit_costs(model: &Model) -> StochasticProblem {
    let p = &model.problem;
    let actions = (0..p.states())
        .map(|x| {
            p.actions(x)
                .map(|a| StochasticAction {
                    cost: if model.terminal[x] {
                        Rational::zero()
                    } else {
                        Rational::one()
                    },
                    outcomes: p.outcomes(a).to_vec(),
                })
                .collect::<Vec<_>>()
        })
        .collect();
    StochasticProblem::new(actions, p.initial(), p.goals().to_vec()).unwrap()
}

/// Checks every objective's reported cost and steps against the full evaluation; returns how
/// many of the truecost objective's costs were finite.
fn check(model: &Model, what: &str) -> usize {
    let units = unit_costs(model);
    let mut finite = 0;
    for objective in [
        Objective::Truecost,
        Objective::Reach,
        Objective::Discounted(Rational::new(9.into(), 10.into())),
    ] {
        let s = model.solve(&objective).unwrap();
        let truecost = expected(model, &evaluate(&model.problem, &s.policy).unwrap());
        let steps = expected(model, &evaluate(&units, &s.policy).unwrap());
        let name = objective.name();
        assert_eq!(s.truecost, truecost, "{what}, {name}: expected truecost");
        if objective == Objective::Reach && truecost.finite().is_none() {
            // The reach objective skips the steps where the cost is infinite: improper there.
            assert!(s.steps.finite().is_none(), "{what}, reach: steps");
        } else {
            assert_eq!(s.steps, steps, "{what}, {name}: expected steps");
        }
        if objective == Objective::Truecost {
            assert_eq!(
                s.truecost, s.value_initial,
                "{what}: G* at the initial state"
            );
            finite += usize::from(truecost.finite().is_some());
        }
    }
    finite
}

#[test]
fn paper_problems_report_the_cost_and_steps_of_their_own_policy() {
    let mut finite = 0;
    for (id, gamma) in [(3, "0.9"), (10, "0.99"), (6, "0.9"), (16, "1/2"), (10, "1")] {
        for noise in [NoiseModel::Paper, NoiseModel::Reference] {
            for step in [StepCost::Unit, StepCost::Euclidean] {
                let g = Predictability::parse(gamma).unwrap();
                let p = exact_grid(id, step, noise, &g).unwrap();
                let model = Model::from_problem(p, format!("problem {id}"));
                finite += check(
                    &model,
                    &format!("problem {id}, gamma {gamma}, {noise:?}, {step:?}"),
                );
            }
        }
    }
    assert!(finite >= 12, "{finite} finite costs");
}

#[test]
fn benchmark_grids_report_the_cost_and_steps_of_their_own_policy() {
    for pattern in GridPattern::ALL {
        let grid = pattern_grid(6, 7, pattern, CostRange::DEFAULT, 3).unwrap();
        let p = StochasticProblem::from_deterministic(
            &grid,
            NoiseModel::Paper,
            &Predictability::parse("0.95").unwrap(),
        )
        .unwrap();
        let model = Model::from_problem(p, pattern.name().into());
        assert_eq!(check(&model, pattern.name()), 1, "{}", pattern.name());
    }
}

#[test]
fn environments_report_the_cost_and_steps_of_their_own_policy() {
    for spec in [
        "frozenlake",
        "frozenlake:slippery=false",
        "cliffwalking",
        "taxi",
    ] {
        let env = EnvSpec::parse(spec).unwrap().build().unwrap();
        let model = Model::from_environment(&env).unwrap();
        check(&model, spec);
    }
}
