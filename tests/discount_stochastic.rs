//! `discount` on stochastic problems — the exact breakpoints where the
//! discount-optimal policies change, checked against independent means: brute force over all
//! stationary deterministic policies (each evaluated by its own exact Gaussian elimination at
//! rational α's) on small stochastic files, and Bellman-optimality checks by a separate linear
//! solve on FrozenLake 4x4.

use num_bigint::BigInt;
use num_traits::{One, Zero};

use truecost::algebra::poly::roots::Root;
use truecost::envs::EnvSpec;
use truecost::objectives::parametric::{discount_breakpoints, DiscountAnalysis};
use truecost::objectives::Model;
use truecost::stochastic::file::{from_json, ProblemFile};
use truecost::value::{Extended, Rational};

fn q(s: &str) -> Rational {
    s.parse().unwrap()
}

/// Solves `A z = b` exactly (Gaussian elimination with pivot search), `None` if singular.
fn gauss(mut a: Vec<Vec<Rational>>, mut b: Vec<Rational>) -> Option<Vec<Rational>> {
    let n = b.len();
    for c in 0..n {
        let p = (c..n).find(|&r| !a[r][c].is_zero())?;
        a.swap(c, p);
        b.swap(c, p);
        let pivot = a[c].clone();
        for r in 0..n {
            if r != c && !a[r][c].is_zero() {
                let f = &a[r][c] / &pivot[c];
                for (ark, pk) in a[r].iter_mut().zip(&pivot).skip(c) {
                    *ark -= &f * pk;
                }
                let t = &f * &b[c];
                b[r] -= t;
            }
        }
    }
    Some((0..n).map(|i| &b[i] / &a[i][i]).collect())
}

/// `x = base + α M x` on the running states for a policy (`choice[x]` a global action id).
fn discounted_values(m: &Model, choice: &[Option<usize>], alpha: &Rational) -> Vec<Rational> {
    let p = &m.problem;
    let n = p.states();
    let mut a = vec![vec![Rational::zero(); n]; n];
    let mut b = vec![Rational::zero(); n];
    for x in 0..n {
        a[x][x] = Rational::one();
        if m.terminal[x] {
            continue;
        }
        let u = choice[x].unwrap();
        b[x] = m.reward[u].clone();
        for o in p.outcomes(u) {
            if !m.terminal[o.successor] {
                a[x][o.successor] -= alpha * &o.probability;
            }
        }
    }
    gauss(a, b).expect("I - αP is invertible for α < 1")
}

/// Probability of reaching a goal, and expected truecost (`None` = +∞), from the initial
/// distribution, for a policy: states that cannot reach a goal under it get 0 / +∞.
fn success_and_cost(m: &Model, choice: &[Option<usize>]) -> (Rational, Option<Rational>) {
    let p = &m.problem;
    let n = p.states();
    // States that reach a goal with positive probability under the policy.
    let mut reach: Vec<bool> = (0..n).map(|x| p.is_goal(x)).collect();
    loop {
        let mut changed = false;
        for x in 0..n {
            if !reach[x] && !m.terminal[x] {
                if let Some(u) = choice[x] {
                    if p.outcomes(u).iter().any(|o| reach[o.successor]) {
                        reach[x] = true;
                        changed = true;
                    }
                }
            }
        }
        if !changed {
            break;
        }
    }
    let mut a = vec![vec![Rational::zero(); n]; n];
    let mut b = vec![Rational::zero(); n];
    for x in 0..n {
        a[x][x] = Rational::one();
        if p.is_goal(x) {
            b[x] = Rational::one();
        } else if reach[x] {
            for o in p.outcomes(choice[x].unwrap()) {
                a[x][o.successor] -= &o.probability;
            }
        }
    }
    let s = gauss(a, b).unwrap();
    let success: Rational = m.initial.iter().map(|(x, w)| &s[*x] * w).sum();
    if success != Rational::one() {
        return (success, None);
    }
    let mut a = vec![vec![Rational::zero(); n]; n];
    let mut b = vec![Rational::zero(); n];
    for x in 0..n {
        a[x][x] = Rational::one();
        if !p.is_goal(x) && reach[x] {
            let u = choice[x].unwrap();
            b[x] = p.cost(u).clone();
            for o in p.outcomes(u) {
                a[x][o.successor] -= &o.probability;
            }
        }
    }
    let c = gauss(a, b).unwrap();
    (
        success,
        Some(m.initial.iter().map(|(x, w)| &c[*x] * w).sum()),
    )
}

/// Every stationary deterministic policy.
fn all_policies(m: &Model) -> Vec<Vec<Option<usize>>> {
    let p = &m.problem;
    let mut out = vec![vec![None; p.states()]];
    for x in 0..p.states() {
        if m.terminal[x] {
            continue;
        }
        out = out
            .into_iter()
            .flat_map(|pol| {
                p.actions(x).map(move |a| {
                    let mut q = pol.clone();
                    q[x] = Some(a);
                    q
                })
            })
            .collect();
    }
    out
}

/// Brute force at `α`: the optimal action indices per state, and success/truecost bounds
/// over the optimal policies.
struct Brute {
    optimal: Vec<Vec<usize>>,
    success: (Rational, Rational),
    truecost: (Extended, Extended),
}

fn brute(m: &Model, policies: &[Vec<Option<usize>>], alpha: &Rational) -> Brute {
    let p = &m.problem;
    let values: Vec<Vec<Rational>> = policies
        .iter()
        .map(|pol| discounted_values(m, pol, alpha))
        .collect();
    let n = p.states();
    let best: Vec<Rational> = (0..n)
        .map(|x| values.iter().map(|v| v[x].clone()).max().unwrap())
        .collect();
    // A policy is optimal iff its values are the best everywhere.
    let optimal_policies: Vec<usize> = (0..policies.len()).filter(|&i| values[i] == best).collect();
    let mut optimal = vec![Vec::new(); n];
    for x in 0..n {
        if m.terminal[x] {
            continue;
        }
        for a in p.actions(x) {
            if optimal_policies.iter().any(|&i| policies[i][x] == Some(a)) {
                optimal[x].push(a - p.actions(x).start);
            }
        }
    }
    let outcomes: Vec<(Rational, Option<Rational>)> = optimal_policies
        .iter()
        .map(|&i| success_and_cost(m, &policies[i]))
        .collect();
    let ext = |c: &Option<Rational>| c.clone().map_or(Extended::Infinite, Extended::Finite);
    Brute {
        optimal,
        success: (
            outcomes.iter().map(|o| o.0.clone()).min().unwrap(),
            outcomes.iter().map(|o| o.0.clone()).max().unwrap(),
        ),
        truecost: (
            outcomes.iter().map(|o| ext(&o.1)).min().unwrap(),
            outcomes.iter().map(|o| ext(&o.1)).max().unwrap(),
        ),
    }
}

/// Where a rational α falls: `Ok(i)` interval `i`, `Err(k)` breakpoint `k`.
fn locate(d: &DiscountAnalysis, alpha: &Rational) -> Result<usize, usize> {
    for (k, b) in d.breakpoints.iter().enumerate() {
        match b.at.cmp_rational(alpha) {
            std::cmp::Ordering::Greater => return Ok(k),
            std::cmp::Ordering::Equal => return Err(k),
            std::cmp::Ordering::Less => {}
        }
    }
    Ok(d.breakpoints.len())
}

fn tiny() -> Rational {
    Rational::new(BigInt::one(), BigInt::from(10).pow(31))
}

/// Checks the analysis against brute force at many rational α's: a grid of 1/64ths, every
/// interval's sample, and points within 1e-31 outside every breakpoint's bracket refined to
/// at most 1e-30 (so the change is located to that width).
fn check_against_brute_force(m: &Model) -> DiscountAnalysis {
    let d = discount_breakpoints(m).unwrap();
    assert_eq!(d.intervals.len(), d.breakpoints.len() + 1);
    let policies = all_policies(m);
    let mut points: Vec<Rational> = (1..64)
        .map(|k| Rational::new(k.into(), 64.into()))
        .collect();
    points.extend(d.intervals.iter().map(|i| i.sample.clone()));
    for b in &d.breakpoints {
        let mut r: Root = b.at.clone();
        r.refine_to(&Rational::new(BigInt::one(), BigInt::from(10).pow(30)));
        assert!(&r.hi - &r.lo <= Rational::new(BigInt::one(), BigInt::from(10).pow(30)));
        points.push(&r.lo - tiny());
        points.push(&r.hi + tiny());
        if let Some(exact) = r.as_rational() {
            points.push(exact.clone());
        }
    }
    for alpha in &points {
        let bf = brute(m, &policies, alpha);
        match locate(&d, alpha) {
            Ok(i) => {
                let iv = &d.intervals[i];
                assert_eq!(iv.optimal, bf.optimal, "optimal actions at alpha = {alpha}");
                assert_eq!(
                    (&iv.achievement.success.min, &iv.achievement.success.max),
                    (&bf.success.0, &bf.success.1),
                    "success at alpha = {alpha}"
                );
                assert_eq!(
                    (&iv.achievement.truecost_min, &iv.achievement.truecost_max),
                    (&bf.truecost.0, &bf.truecost.1),
                    "truecost at alpha = {alpha}"
                );
                // The reported policy is one of the optimal ones.
                for (x, a) in iv.policy.iter().enumerate() {
                    if let Some(a) = a {
                        assert!(bf.optimal[x].contains(a));
                    }
                }
            }
            Err(k) => {
                let b = &d.breakpoints[k];
                assert_eq!(
                    (&b.achievement.success.min, &b.achievement.success.max),
                    (&bf.success.0, &bf.success.1)
                );
                for (x, actions) in &b.ties {
                    assert_eq!(actions, &bf.optimal[*x], "ties at the rational breakpoint");
                }
            }
        }
    }
    // Consecutive intervals differ unless the breakpoint is a tie at that point only.
    for (k, b) in d.breakpoints.iter().enumerate() {
        assert_eq!(
            b.touch,
            d.intervals[k].optimal == d.intervals[k + 1].optimal,
            "breakpoint {k}"
        );
        assert!(
            !b.ties.is_empty(),
            "a breakpoint changes some state's optimal actions"
        );
    }
    d
}

fn model(text: &str) -> Model {
    match from_json(text).unwrap() {
        ProblemFile::Stochastic(p) => Model::from_problem(*p, "test".into()),
        ProblemFile::Deterministic(d) => Model::from_problem(
            truecost::stochastic::StochasticProblem::from_deterministic(
                &d,
                truecost::stochastic::NoiseModel::Paper,
                &truecost::stochastic::Predictability::one(),
            )
            .unwrap(),
            "test".into(),
        ),
    }
}

#[test]
fn gamble_or_detour_has_one_rational_breakpoint_at_five_sixths() {
    // Safe: 1 then 3; gamble: 1, then the goal or a trap loop costing 1 forever (1/2 each).
    let m = model(
        r#"{"initial":0,"goals":[3],"actions":[
        [{"to":1,"cost":"1"},{"cost":"1","outcomes":[{"to":3,"p":"1/2"},{"to":2,"p":"1/2"}]}],
        [{"to":3,"cost":"3"}],
        [{"to":2,"cost":"1"}],
        []]}"#,
    );
    let d = check_against_brute_force(&m);
    assert_eq!(d.breakpoints.len(), 1);
    assert_eq!(d.breakpoints[0].at.as_rational(), Some(&q("5/6")));
    assert_eq!(d.intervals[0].achievement.success.max, q("1/2"));
    assert_eq!(
        d.intervals[1].achievement.truecost_min,
        Extended::Finite(q("4"))
    );
    // At 5/6 both are optimal: success from 1/2 to 1.
    let b = &d.breakpoints[0];
    assert_eq!(
        (
            b.achievement.success.min.clone(),
            b.achievement.success.max.clone()
        ),
        (q("1/2"), q("1"))
    );
    assert_eq!(b.ties, vec![(0, vec![0, 1])]);
}

/// A small pseudo-random stochastic problem: `n` states (the last is the goal), two actions
/// per state, costs from {0, 1, 2, 5}, two outcomes with probabilities from a small set.
fn random_file(seed: u64, n: usize) -> String {
    let mut s = seed.wrapping_mul(0x2545_F491_4F6C_DD1D) | 1;
    let mut next = |k: u64| {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        s % k
    };
    let probs = ["1/2", "1/3", "1/4", "3/4", "2/3", "1/5"];
    let costs = ["0", "1", "2", "5"];
    let mut states = Vec::new();
    for _ in 0..n - 1 {
        let mut actions = Vec::new();
        for _ in 0..2 {
            let cost = costs[next(4) as usize];
            let (a, b) = (next(n as u64), next(n as u64));
            if next(3) == 0 || a == b {
                actions.push(format!(r#"{{"to":{a},"cost":"{cost}"}}"#));
            } else {
                let p = probs[next(6) as usize];
                let rest = Rational::one() - q(p);
                actions.push(format!(
                    r#"{{"cost":"{cost}","outcomes":[{{"to":{a},"p":"{p}"}},{{"to":{b},"p":"{rest}"}}]}}"#
                ));
            }
        }
        states.push(format!("[{}]", actions.join(",")));
    }
    states.push("[]".into());
    format!(
        r#"{{"initial":0,"goals":[{}],"actions":[{}]}}"#,
        n - 1,
        states.join(",")
    )
}

#[test]
fn random_small_stochastic_problems_agree_with_brute_force() {
    let mut with_breakpoints = 0;
    for seed in 1..=40u64 {
        let n = 3 + (seed % 3) as usize;
        let m = model(&random_file(seed, n));
        let d = check_against_brute_force(&m);
        if !d.breakpoints.is_empty() {
            with_breakpoints += 1;
        }
    }
    // The family is not trivial: many problems have breakpoints.
    assert!(
        with_breakpoints >= 10,
        "{with_breakpoints} problems with breakpoints"
    );
}

/// Whether the policy (global action ids) is discount-optimal at `α`: no action improves on
/// its values (Bellman's optimality condition), checked with a separate exact solve.
fn bellman_optimal(m: &Model, choice: &[Option<usize>], alpha: &Rational) -> bool {
    let p = &m.problem;
    let v = discounted_values(m, choice, alpha);
    (0..p.states()).filter(|&x| !m.terminal[x]).all(|x| {
        p.actions(x).all(|a| {
            let mut qa = m.reward[a].clone();
            for o in p.outcomes(a) {
                if !m.terminal[o.successor] {
                    qa += alpha * &o.probability * &v[o.successor];
                }
            }
            qa <= v[x]
        })
    })
}

#[test]
fn frozenlake_4x4_intervals_check_by_separate_solves() {
    let env = EnvSpec::parse("frozenlake").unwrap().build().unwrap();
    let m = Model::from_environment(&env).unwrap();
    let d = discount_breakpoints(&m).unwrap();
    assert!(!d.breakpoints.is_empty());
    let p = &m.problem;
    let global = |policy: &[Option<usize>]| -> Vec<Option<usize>> {
        policy
            .iter()
            .enumerate()
            .map(|(x, a)| a.map(|a| a + p.actions(x).start))
            .collect()
    };
    let width = Rational::new(BigInt::one(), BigInt::from(10).pow(30));
    for (i, iv) in d.intervals.iter().enumerate() {
        let pol = global(&iv.policy);
        // Optimal at the sample and just inside both ends (brackets of at most 1e-30).
        let mut points = vec![iv.sample.clone()];
        if let Some(lo) = &iv.lo {
            let mut r = lo.clone();
            r.refine_to(&width);
            points.push(&r.hi + tiny());
        }
        if let Some(hi) = &iv.hi {
            let mut r = hi.clone();
            r.refine_to(&width);
            points.push(&r.lo - tiny());
        }
        for a in &points {
            assert!(bellman_optimal(&m, &pol, a), "interval {i} at {a}");
        }
        // Its success probability by a separate solve; one value over the optimal policies.
        let (success, cost) = success_and_cost(&m, &pol);
        assert_eq!(iv.achievement.success.min, success);
        assert_eq!(iv.achievement.success.max, success);
        assert_eq!(
            cost, None,
            "FrozenLake 4x4 slippery: no policy reaches the goal surely"
        );
        // The policy stops being optimal past the next breakpoint (a genuine change).
        if let Some(next) = d.intervals.get(i + 1) {
            if !d.breakpoints[i].touch {
                assert!(!bellman_optimal(&m, &pol, &next.sample));
            }
        }
    }
    // Near α = 1 the discount-optimal policies reach the goal as often as possible: the
    // reach objective's optimum (a separate exact computation) ...
    let reach = m.solve(&truecost::objectives::Objective::Reach).unwrap();
    let last = d.intervals.last().unwrap();
    assert_eq!(
        Extended::Finite(last.achievement.success.max.clone()),
        reach.value_initial
    );
    // ... while for small α they give up success probability (Proposition 3 on FrozenLake).
    assert!(d.intervals[0].achievement.success.max < last.achievement.success.min);
}

mod common;

#[test]
fn discount_env_on_the_command_line() {
    use common::cli::{fails_one_line, json, stdout};
    let v = json(&["discount", "--env", "frozenlake", "--format", "json"]);
    let bps = v["breakpoints"].as_array().unwrap();
    let ivs = v["intervals"].as_array().unwrap();
    assert_eq!(ivs.len(), bps.len() + 1);
    assert!(!bps.is_empty());
    for b in bps {
        // Every irrational breakpoint comes with its polynomial and a bracket ≤ 1e-30.
        let lo: Rational = b["bracket"][0].as_str().unwrap().parse().unwrap();
        let hi: Rational = b["bracket"][1].as_str().unwrap().parse().unwrap();
        assert!(&hi - &lo <= Rational::new(BigInt::one(), BigInt::from(10).pow(30)));
        assert!(b["exact"].is_string() || b["polynomial"].is_string());
        assert!(!b["ties"].as_array().unwrap().is_empty());
    }
    assert_eq!(ivs.last().unwrap()["success_probability"], "14/17");
    assert_eq!(ivs[0]["lo"], "0");
    let md = stdout(&["discount", "--env", "frozenlake", "--format", "markdown"]);
    assert_eq!(
        md.lines().filter(|l| l.starts_with("| (")).count(),
        ivs.len()
    );
    let tex = stdout(&["discount", "--env", "frozenlake", "--format", "latex"]);
    assert!(tex.contains("\\begin{tabular}") && tex.contains("0.823529411765"));
    let text = stdout(&["discount", "--env", "frozenlake"]);
    assert!(text.contains("breakpoint 1: alpha = 0."));
    // A stochastic problem file takes the same path.
    let dir = std::env::temp_dir().join(format!("truecost-d11-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let f = dir.join("gamble.json");
    std::fs::write(
        &f,
        r#"{"initial":0,"goals":[3],"actions":[
        [{"to":1,"cost":"1"},{"cost":"1","outcomes":[{"to":3,"p":"1/2"},{"to":2,"p":"1/2"}]}],
        [{"to":3,"cost":"3"}],[{"to":2,"cost":"1"}],[]]}"#,
    )
    .unwrap();
    let v = json(&[
        "discount",
        "--file",
        f.to_str().unwrap(),
        "--format",
        "json",
    ]);
    assert_eq!(v["breakpoints"][0]["alpha"], "5/6");
    // Refusals: one line each. A stochastic model with 288 running states (slippery
    // FrozenLake on a 17x17 map without holes) is beyond the degree bound; Taxi,
    // deterministic, is not (tests/taxi_gaps.rs).
    let map = dir.join("17x17.txt");
    let mut rows = vec!["F".repeat(17); 17];
    rows[0].replace_range(0..1, "S");
    rows[16].replace_range(16..17, "G");
    std::fs::write(&map, rows.join("\n")).unwrap();
    let spec = format!("frozenlake:map={}", map.display());
    let e = fails_one_line(&["discount", "--env", &spec]);
    assert!(e.contains("288 states") && e.contains("at most 256"), "{e}");
    // --env with --problem: a usage error (exit 2).
    let e = common::cli::fails(&["discount", "--env", "frozenlake", "--problem", "3"], 2);
    assert!(e.contains("cannot be used with"), "{e}");
    let e = fails_one_line(&[
        "verify",
        "--claim",
        "C4",
        "--env",
        "cliffwalking:slippery=true",
    ]);
    assert!(e.contains("stochastic"), "{e}");
    let e = fails_one_line(&["verify", "--claim", "C4", "--env", "taxi"]);
    assert!(e.contains("single initial state"), "{e}");
    let out = stdout(&[
        "verify",
        "--claim",
        "C4",
        "--env",
        "frozenlake:slippery=false",
    ]);
    assert!(out.contains("L* = 6"), "{out}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn decimal_with_no_digits_prints_no_point() {
    use truecost::algebra::poly::decimal;
    assert_eq!(decimal(&q("7/2"), 0), "3");
    assert_eq!(decimal(&q("-7/2"), 0), "-4"); // truncation is towards -inf (floor)
    assert_eq!(decimal(&q("7/2"), 1), "3.5");
}
