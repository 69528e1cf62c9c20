//! The Rust checker and the Coq checker (`proofs/coq/CertificateCheck.v`, run by `vm_compute`)
//! agree: on 1,200 certificates of small random problems — 600 as the exact solver writes them,
//! 600 tampered (a value off by 10^-30, another action, a finite state claimed `inf`, an `inf`
//! state claimed finite, an index out of range, a goal's value changed) — both give the same
//! verdict, every untampered certificate is accepted by both, and most tampered ones are
//! rejected by both. One `coqc` call decides all of them.

use truecost::certificate::{self, coq, Certificate, CertifiedObjective, Identity, Mdp};
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

/// The exact solver's certificate of `p`, read back.
fn solved(p: &StochasticProblem, mdp: &Mdp) -> Certificate {
    let opt = truecost::stochastic::policy_iteration::optimum(p).unwrap();
    let record = certificate::ProblemRecord {
        source: "problem".into(),
        name: "random".into(),
        gamma: None,
        noise: None,
        step_cost: None,
        sha256: certificate::sha256_hex(mdp.canonical_text().as_bytes()),
        sha256_of: certificate::CANONICAL_FORMAT.into(),
    };
    let text = truecost::stochastic::certified::optimum_certificate(
        p,
        &opt,
        &CertifiedObjective::Truecost,
        &record,
    );
    certificate::parse(&text).unwrap()
}

/// One tampering of kind `kind` (1 to 6) at a random state, if the certificate has a state it
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
        _ => return false,
    }
    true
}

#[test]
fn the_rust_and_coq_checkers_agree_on_1200_certificates() {
    let mut rng = Rng(0x5EED_CE27_1F1C_A7E5);
    let mut cases = Vec::new();
    let (mut valid, mut tampered) = (0, 0);
    while valid < 600 || tampered < 600 {
        let p = random_problem(&mut rng);
        let mdp = problem_mdp(&p);
        let mut c = solved(&p, &mdp);
        let is_tampered = valid >= 600 || (tampered < 600 && rng.below(2) == 0);
        if is_tampered {
            let kind = 1 + rng.below(6);
            if !tamper(&mut c, &mdp, kind, &mut rng) {
                continue;
            }
            tampered += 1;
        } else {
            valid += 1;
        }
        let rust = certificate::check(&mdp, Identity::Canonical, &c);
        coq::coq_applies(&mdp, &c).unwrap();
        cases.push((is_tampered, rust, coq::coq_case(&mdp, &c)));
    }
    let terms: Vec<String> = cases.iter().map(|(_, _, t)| t.clone()).collect();
    let verdicts = coq::coq_verdicts(&terms).unwrap();
    assert_eq!(verdicts.len(), 1200);
    let mut rejected = 0;
    for ((is_tampered, rust, term), coq) in cases.iter().zip(&verdicts) {
        assert_eq!(rust.is_ok(), *coq, "Rust {rust:?}, Coq {coq} on {term}");
        if !is_tampered {
            assert!(coq, "an untampered certificate rejected: {rust:?}");
        } else if !coq {
            rejected += 1;
        }
    }
    // Another action may tie, and a value moved in an unreachable corner may still be a
    // certificate; but most tamperings break a condition.
    assert!(rejected >= 450, "only {rejected} of 600 tampered rejected");
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
    assert!(certificate::check(&mdp, Identity::Canonical, &lying).is_err());
}
