//! The Rust checker and the Coq checkers agree: on 1,200 truecost certificates of small random
//! problems — 600 as the exact solver writes them, 600 tampered (a value off by 10^-30, another
//! action, a finite state claimed `inf`, an `inf` state claimed finite, an index out of range,
//! a goal's value changed, an improper policy that solves its own equation) — and on 400
//! discounted ones (200 optimal, 200 tampered: a value off by 10^-30, a non-optimal action, an
//! index out of range, a terminal state's value changed), the extracted checker
//! (`proofs/coq/extract`, [`coq::coq_check`]'s path) and the Rust checker give the same verdict
//! on every one, every untampered certificate is accepted, and most tampered ones are rejected.
//! `vm_compute` (`coq::coq_verdicts`, one `coqc` call) decides every fourth case too, with the
//! same verdicts.

use num_traits::{One, Zero};
use truecost::certificate::{self, coq, Certificate, CertifiedObjective, Identity, Mdp, MdpAction};
use truecost::stochastic::certified::problem_mdp;
use truecost::stochastic::{Outcome, OutcomeKind, StochasticAction, StochasticProblem};
use truecost::value::Rational;

/// xorshift64*: a fixed stream, so a failure is reproducible.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
}

fn r(n: i64, d: i64) -> Rational {
    Rational::new(n.into(), d.into())
}

/// A random problem: 2 to 6 states, the last a goal; every other state 0 to 3 actions, each
/// of cost 0 to 3 with 1 to 3 outcomes whose probabilities are multiples of 1/4 or 1/3.
fn random_problem(rng: &mut Rng) -> StochasticProblem {
    let n = 2 + rng.below(5);
    let actions = (0..n)
        .map(|x| {
            if x == n - 1 {
                return Vec::new();
            }
            (0..rng.below(4))
                .map(|_| {
                    let parts = 1 + rng.below(3);
                    let den = if parts == 3 { 3 } else { 4 };
                    // Split `den` into `parts` positive integers.
                    let mut left = den;
                    let mut weights = Vec::new();
                    for k in 0..parts {
                        let w = if k + 1 == parts {
                            left
                        } else {
                            1 + rng.below(left - (parts - k - 1))
                        };
                        left -= w;
                        weights.push(w);
                    }
                    StochasticAction {
                        cost: r(rng.below(4) as i64, 1),
                        outcomes: weights
                            .iter()
                            .map(|w| Outcome {
                                successor: rng.below(n),
                                probability: r(*w as i64, den as i64),
                                kind: OutcomeKind::Listed,
                            })
                            .collect(),
                    }
                })
                .collect()
        })
        .collect();
    StochasticProblem::new(actions, 0, vec![n - 1]).expect("a well-formed problem")
}

/// The record of a random problem (the canonical export's SHA-256).
fn record(mdp: &Mdp) -> certificate::ProblemRecord {
    certificate::ProblemRecord {
        source: "problem".into(),
        name: "random".into(),
        gamma: None,
        noise: None,
        step_cost: None,
        sha256: certificate::sha256_hex(mdp.canonical_text().as_bytes()),
        sha256_of: certificate::CANONICAL_FORMAT.into(),
        goal_label: None,
        cost_reward: None,
    }
}

/// The exact solver's certificate of `p`, read back.
fn solved(p: &StochasticProblem, mdp: &Mdp) -> Certificate {
    let opt = truecost::stochastic::policy_iteration::optimum(p).unwrap();
    let text = truecost::stochastic::certified::optimum_certificate(
        p,
        &opt,
        &CertifiedObjective::Truecost,
        &record(mdp),
    );
    certificate::parse(&text).unwrap()
}

/// `r(x, a) + α Σ_y p(y | x, a) v(y)`.
fn discounted_q(a: &MdpAction, alpha: &Rational, v: &[Rational]) -> Rational {
    let mut q = a.reward.clone();
    for (y, p) in &a.outcomes {
        q += alpha * p * &v[*y];
    }
    q
}

/// The value of `pol` under discount `alpha`: the solution of `v(x) = Q(x, pol(x))` at
/// non-terminal states, `v = 0` at terminal ones, by Gauss–Jordan elimination over the
/// rationals (`I − α P` is invertible for `α < 1`).
fn discounted_value(mdp: &Mdp, alpha: &Rational, pol: &[usize]) -> Vec<Rational> {
    let n = mdp.states();
    let mut m: Vec<Vec<Rational>> = (0..n)
        .map(|x| {
            let mut row = vec![Rational::zero(); n + 1];
            row[x] = Rational::one();
            if !mdp.terminal[x] {
                let a = &mdp.actions[x][pol[x]];
                for (y, p) in &a.outcomes {
                    row[*y] -= alpha * p;
                }
                row[n] = a.reward.clone();
            }
            row
        })
        .collect();
    for col in 0..n {
        let pivot = (col..n).find(|&r| !m[r][col].is_zero()).unwrap();
        m.swap(col, pivot);
        let lead = m[col][col].clone();
        for e in m[col].iter_mut().skip(col) {
            *e = &*e / &lead;
        }
        let pivot_row = m[col].clone();
        for (_, row) in m.iter_mut().enumerate().filter(|(r, _)| *r != col) {
            let f = row[col].clone();
            if !f.is_zero() {
                for (e, p) in row.iter_mut().zip(&pivot_row).skip(col) {
                    *e -= &f * p;
                }
            }
        }
    }
    m.into_iter().map(|row| row[n].clone()).collect()
}

/// The discounted optimum of `mdp` by policy iteration (each state switches to an action of
/// strictly greater `Q` while there is one), as a certificate.
fn discounted_solved(mdp: &Mdp, alpha: &Rational) -> Certificate {
    let n = mdp.states();
    let mut pol = vec![0; n];
    loop {
        let v = discounted_value(mdp, alpha, &pol);
        let mut changed = false;
        for x in (0..n).filter(|&x| !mdp.terminal[x]) {
            let mut best = discounted_q(&mdp.actions[x][pol[x]], alpha, &v);
            for (i, a) in mdp.actions[x].iter().enumerate() {
                let q = discounted_q(a, alpha, &v);
                if q > best {
                    best = q;
                    pol[x] = i;
                    changed = true;
                }
            }
        }
        if !changed {
            return Certificate {
                objective: CertifiedObjective::Discounted(alpha.clone()),
                problem: record(mdp),
                values: v.into_iter().map(Some).collect(),
                policy: (0..n)
                    .map(|x| (!mdp.terminal[x]).then_some(pol[x] as u64))
                    .collect(),
            };
        }
    }
}

/// One tampering of a discounted certificate, of kind `kind` (1 to 4): a value off by
/// 10^-30, another action, an index out of range, a terminal state's value changed.
fn tamper_discounted(c: &mut Certificate, mdp: &Mdp, kind: usize, rng: &mut Rng) -> bool {
    let n = c.values.len();
    let inner: Vec<usize> = (0..n).filter(|&x| !mdp.terminal[x]).collect();
    let pick = |list: &[usize], rng: &mut Rng| list[rng.below(list.len())];
    match kind {
        1 => {
            let x = rng.below(n);
            let tiny = Rational::new(1.into(), num_bigint::BigInt::from(10).pow(30));
            let v = c.values[x].take().unwrap();
            c.values[x] = Some(v + tiny);
        }
        2 if inner.iter().any(|&x| mdp.actions[x].len() > 1) => {
            let choice: Vec<usize> = inner
                .iter()
                .copied()
                .filter(|&x| mdp.actions[x].len() > 1)
                .collect();
            let x = pick(&choice, rng);
            let k = mdp.actions[x].len();
            let i = c.policy[x].unwrap() as usize;
            c.policy[x] = Some(((i + 1 + rng.below(k - 1)) % k) as u64);
        }
        3 if !inner.is_empty() => {
            let x = pick(&inner, rng);
            c.policy[x] = Some(mdp.actions[x].len() as u64 + rng.below(3) as u64);
        }
        4 => {
            let t = mdp.terminal.iter().position(|t| *t).unwrap();
            c.values[t] = Some(r(-1, 2));
        }
        _ => return false,
    }
    true
}

/// One tampering of kind `kind` (1 to 7) at a random state, if the certificate has a state it
/// applies to.
fn tamper(c: &mut Certificate, mdp: &Mdp, kind: usize, rng: &mut Rng) -> bool {
    let n = c.values.len();
    let finite: Vec<usize> = (0..n)
        .filter(|&x| c.values[x].is_some() && !mdp.goal[x])
        .collect();
    let infinite: Vec<usize> = (0..n).filter(|&x| c.values[x].is_none()).collect();
    let pick = |list: &[usize], rng: &mut Rng| list[rng.below(list.len())];
    let tiny = Rational::new(1.into(), num_bigint::BigInt::from(10).pow(30));
    match kind {
        1 if !finite.is_empty() => {
            let x = pick(&finite, rng);
            let v = c.values[x].take().unwrap();
            c.values[x] = Some(if rng.below(2) == 0 {
                v + tiny
            } else {
                v - tiny
            });
        }
        2 if finite.iter().any(|&x| mdp.actions[x].len() > 1) => {
            let with_choice: Vec<usize> = finite
                .iter()
                .copied()
                .filter(|&x| mdp.actions[x].len() > 1)
                .collect();
            let x = pick(&with_choice, rng);
            let i = c.policy[x].unwrap() as usize;
            c.policy[x] =
                Some(((i + 1 + rng.below(mdp.actions[x].len() - 1)) % mdp.actions[x].len()) as u64);
        }
        3 if !finite.is_empty() => {
            let x = pick(&finite, rng);
            c.values[x] = None;
            c.policy[x] = None;
        }
        4 if !infinite.is_empty() => {
            let x = pick(&infinite, rng);
            c.values[x] = Some(r(rng.below(5) as i64, 1));
            c.policy[x] = (!mdp.actions[x].is_empty()).then_some(0);
        }
        5 if !finite.is_empty() => {
            let x = pick(&finite, rng);
            c.policy[x] = Some(mdp.actions[x].len() as u64);
        }
        6 => {
            let g = mdp.goal.iter().position(|g| *g).unwrap();
            c.values[g] = Some(r(1, 2));
        }
        // Another action, its value re-solved at that state alone (V(x) = l + Σ p V with x's
        // own value on both sides): a policy that may loop, whose equation holds at x.
        7 if !finite.is_empty() => {
            let x = pick(&finite, rng);
            let k = mdp.actions[x].len();
            let i = rng.below(k);
            let a = &mdp.actions[x][i];
            if a.outcomes.iter().any(|(y, _)| c.values[*y].is_none()) {
                return false;
            }
            let mut rest = a.cost.clone();
            let mut own = Rational::zero();
            for (y, p) in &a.outcomes {
                if *y == x {
                    own += p;
                } else {
                    rest += p * c.values[*y].as_ref().unwrap();
                }
            }
            if own.is_one() {
                if !a.cost.is_zero() {
                    return false;
                }
                c.values[x] = Some(Rational::zero());
            } else {
                c.values[x] = Some(rest / (Rational::one() - own));
            }
            c.policy[x] = Some(i as u64);
        }
        _ => return false,
    }
    true
}

/// One case: whether it was tampered, the Rust checker's verdict, the model and certificate.
type Case = (bool, bool, Mdp, Certificate);

/// Both Coq checkers' verdicts agree with the Rust checker's on every case (`vm_compute` on
/// every fourth), every untampered case is accepted; the number of tampered cases rejected.
fn agree(cases: &[Case]) -> usize {
    let checker = coq::extracted_checker().unwrap();
    let mut rejected = 0;
    for (is_tampered, rust, mdp, c) in cases {
        coq::coq_applies(mdp, c).unwrap();
        let input = coq::checker_input(mdp, c);
        let coq = coq::extracted_verdict(&checker, &input).unwrap();
        assert_eq!(*rust, coq, "Rust {rust}, extracted Coq {coq} on\n{input}");
        if !is_tampered {
            assert!(coq, "an untampered certificate rejected:\n{input}");
        } else if !coq {
            rejected += 1;
        }
    }
    let sample: Vec<&Case> = cases.iter().step_by(4).collect();
    let terms: Vec<String> = sample
        .iter()
        .map(|(_, _, mdp, c)| coq::coq_case(mdp, c))
        .collect();
    let verdicts = coq::coq_verdicts(&terms).unwrap();
    assert_eq!(verdicts.len(), sample.len());
    for ((_, rust, _, _), vm) in sample.iter().zip(&verdicts) {
        assert_eq!(rust, vm, "Rust {rust}, vm_compute {vm}");
    }
    rejected
}

/// `2 · half` cases: `half` certificates as `make` writes them and `half` tampered by
/// `tamper` (which says whether it applied), in a random order, with the Rust checker's verdicts.
fn cases(
    rng: &mut Rng,
    half: usize,
    mut make: impl FnMut(&mut Rng) -> (Mdp, Certificate),
    mut tamper: impl FnMut(&mut Certificate, &Mdp, &mut Rng) -> bool,
) -> Vec<Case> {
    let mut out = Vec::new();
    let (mut valid, mut tampered) = (0, 0);
    while valid < half || tampered < half {
        let (mdp, mut c) = make(rng);
        let is_tampered = valid >= half || (tampered < half && rng.below(2) == 0);
        if is_tampered {
            if !tamper(&mut c, &mdp, rng) {
                continue;
            }
            tampered += 1;
        } else {
            valid += 1;
        }
        let rust = certificate::check(&mdp, Identity::Canonical, &c).is_ok();
        out.push((is_tampered, rust, mdp, c));
    }
    out
}

#[test]
fn the_rust_and_coq_checkers_agree_on_1200_truecost_certificates() {
    let mut rng = Rng(0x5EED_CE27_1F1C_A7E5);
    let cases = cases(
        &mut rng,
        600,
        |rng| {
            let p = random_problem(rng);
            let mdp = problem_mdp(&p);
            let c = solved(&p, &mdp);
            (mdp, c)
        },
        |c, mdp, rng| {
            let kind = 1 + rng.below(7);
            tamper(c, mdp, kind, rng)
        },
    );
    assert_eq!(cases.len(), 1200);
    let rejected = agree(&cases);
    // Another action may tie, and a value moved in an unreachable corner may still be a
    // certificate; but most tamperings break a condition.
    assert!(rejected >= 450, "only {rejected} of 600 tampered rejected");
}

#[test]
fn the_rust_and_coq_checkers_agree_on_400_discounted_certificates() {
    let mut rng = Rng(0xD15C_0947_ED00_0001);
    let alphas = [r(1, 2), r(2, 3), r(9, 10), r(99, 100)];
    let cases = cases(
        &mut rng,
        200,
        |rng| {
            let mdp = problem_mdp(&random_problem(rng));
            let alpha = &alphas[rng.below(alphas.len())];
            let c = discounted_solved(&mdp, alpha);
            // The optimum is the fixed point V = max_a Q(., a), derived here independently.
            let v: Vec<Rational> = c.values.iter().map(|v| v.clone().unwrap()).collect();
            for x in (0..mdp.states()).filter(|&x| !mdp.terminal[x]) {
                let best = mdp.actions[x]
                    .iter()
                    .map(|a| discounted_q(a, alpha, &v))
                    .max()
                    .unwrap();
                assert_eq!(v[x], best);
            }
            (mdp, c)
        },
        |c, mdp, rng| {
            let kind = 1 + rng.below(4);
            tamper_discounted(c, mdp, kind, rng)
        },
    );
    assert_eq!(cases.len(), 400);
    let rejected = agree(&cases);
    assert!(rejected >= 150, "only {rejected} of 200 tampered rejected");
}

/// A hint cannot make the Coq checker accept: the certificate of a problem with an `inf`
/// state, accepted with the computed hints, is rejected when the state claims value 0 (the
/// state loops at cost 0 forever: 0 solves its own equation, but no policy is proper).
#[test]
fn the_coq_checker_rejects_an_improper_zero_cost_loop() {
    // 0 -> 0 at cost 0 (a loop), 1 -> 2 (goal) at cost 1.
    let p = StochasticProblem::new(
        vec![
            vec![StochasticAction {
                cost: r(0, 1),
                outcomes: vec![Outcome {
                    successor: 0,
                    probability: r(1, 1),
                    kind: OutcomeKind::Listed,
                }],
            }],
            vec![StochasticAction {
                cost: r(1, 1),
                outcomes: vec![Outcome {
                    successor: 2,
                    probability: r(1, 1),
                    kind: OutcomeKind::Listed,
                }],
            }],
            vec![],
        ],
        1,
        vec![2],
    )
    .unwrap();
    let mdp = problem_mdp(&p);
    let c = solved(&p, &mdp);
    assert_eq!(c.values, vec![None, Some(r(1, 1)), Some(r(0, 1))]);
    let mut lying = c.clone();
    lying.values[0] = Some(r(0, 1));
    lying.policy[0] = Some(0);
    let verdicts =
        coq::coq_verdicts(&[coq::coq_case(&mdp, &c), coq::coq_case(&mdp, &lying)]).unwrap();
    assert_eq!(verdicts, [true, false]);
    let checker = coq::extracted_checker().unwrap();
    assert!(coq::extracted_verdict(&checker, &coq::checker_input(&mdp, &c)).unwrap());
    assert!(!coq::extracted_verdict(&checker, &coq::checker_input(&mdp, &lying)).unwrap());
    assert!(certificate::check(&mdp, Identity::Canonical, &lying).is_err());
}
