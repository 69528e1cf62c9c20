//! Engine 5: the Coq development in `proofs/coq/` — theorems about **every** finite planning
//! problem (and about the paper's worked example; `docs/proofs/`), re-checked by `coqc` on the
//! machine that runs `verify`.
//!
//! The development's sources are embedded in the binary ([`SOURCES`], in `_CoqProject`
//! order), so that what is re-checked is what this build was made from. [`recheck`] refuses
//! sources that admit anything ([`scan_sources`]: `Admitted`, `admit`, `Axiom`, `Parameter`, …
//! outside comments); makes sure the program called `coqc` behaves as Coq (a false lemma
//! fails, a true one compiles to a `.vo` file with the expected `Check` and
//! `Print Assumptions`); compiles each source with `coqc -R <dir> Truecost`; and asks `Check`
//! and `Print Assumptions` about every theorem of [`THEOREMS`]. A theorem is accepted only
//! when its statement is exactly the pinned one and `Print Assumptions` lists exactly the
//! pinned axioms ([`PINNED`], [`judge`]), each among the standard library's axioms of the real
//! numbers ([`ALLOWED_AXIOMS`]): a theorem weakened under its own name compiles, and only the
//! comparison of statements notices it.
//!
//! Nothing is claimed for a check that did not run: without `coqc` on `PATH` the outcome is
//! [`Outcome::NotAvailable`]; a `coqc` that does not behave as Coq is [`Outcome::NotCoq`]; one
//! that does not finish within the time limit is stopped ([`Outcome::TimedOut`]).

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use serde::{Deserialize, Serialize};

/// What a Coq theorem says about its claim.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Kind {
    /// The theorem proves the claim (for every finite problem).
    Proves,
    /// The theorem refutes the claim as printed (a concrete counterexample, in Coq).
    Refutes,
}

/// One main theorem of the Coq development.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub struct Theorem {
    /// The claim of the registry it is about (`C1`, `C1-corrected`, `C2`).
    pub claim: &'static str,
    /// Whether it proves or refutes that claim.
    pub kind: Kind,
    /// The fully qualified name (`Truecost.C1.c1_corrected`).
    pub name: &'static str,
    /// The file that proves it, from the repository's root.
    pub file: &'static str,
    /// The statement, in one line.
    pub statement: &'static str,
    /// How the formal statement is weaker than the paper's, if it is.
    pub weaker: Option<&'static str>,
    /// What the theorem quantifies over: the verdict's label follows it.
    pub scope: Quantifier,
}

/// What a theorem of [`THEOREMS`] is about, read off its Coq statement: every finite problem
/// (a `forall P : Model.problem`), the paper's worked example (one fixed problem and its
/// discount threshold), or one counterexample to a printed statement.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Quantifier {
    /// Every finite problem of the model (or every functional, for C2).
    EveryFiniteProblem,
    /// The paper's worked example of C3: one fixed problem.
    PaperExample,
    /// One concrete counterexample to a statement as printed.
    Counterexample,
    /// Every finite Markov decision process (the soundness of `truecost check`'s conditions).
    EveryFiniteMdp,
}

impl Quantifier {
    /// In words, for the report's scope line.
    ///
    /// ```
    /// use truecost::claims::coq::Quantifier;
    /// assert_eq!(Quantifier::PaperExample.describe(), "the paper's worked example (one fixed problem)");
    /// ```
    pub fn describe(self) -> &'static str {
        match self {
            Quantifier::EveryFiniteProblem => "every finite problem",
            Quantifier::PaperExample => "the paper's worked example (one fixed problem)",
            Quantifier::Counterexample => "one counterexample (a fixed problem)",
            Quantifier::EveryFiniteMdp => "every finite Markov decision process",
        }
    }
}

/// The main theorems, claim by claim: a claim reaches the Coq level only when every theorem
/// listed for it is re-checked and accepted.
pub const THEOREMS: &[Theorem] = &[
    Theorem {
        claim: "C1",
        kind: Kind::Refutes,
        name: "Truecost.C1.c1_as_printed_refuted",
        file: "proofs/coq/C1.v",
        statement: "on loop2 (0->0 at cost 0, 0->goal at cost 1; well-formed, every state reaching the goal), from \
Q0 = 0 with every pair updated once per round in the cyclic order (the termination pair by the printed rule), \
Q != Q* after every number of rounds",
        weaker: None,
        scope: Quantifier::Counterexample,
    },
    Theorem {
        claim: "C1",
        kind: Kind::Refutes,
        name: "Truecost.C1.c1_as_printed_refuted_positive_costs",
        file: "proofs/coq/C1.v",
        statement: "on back2 (0->goal and goal->0, each at cost 1; well-formed, every state reaching the goal, every \
move cost positive), from Q0 = -1 at the goal's move and 0 elsewhere (so Q0(xg,uT) = 0) with every pair updated once \
per round in the cyclic order (the termination pair by the printed rule), Q != Q* after every number of rounds",
        weaker: None,
        scope: Quantifier::Counterexample,
    },
    Theorem {
        claim: "C1-corrected",
        kind: Kind::Proves,
        name: "Truecost.C1.c1_corrected",
        file: "proofs/coq/C1.v",
        statement: "for every well-formed finite problem in which every state reaches the goal (H1), every Q0 with \
Q0(xg,uT) = 0 (H0; the termination pair held) and round_bound P Q0 = Some R (H2: Q0 >= Q*, or every move costs \
>= c > 0), and every list of at least R rounds (each updating every move pair at least once, in any order): \
Q = Q* at the end of the rounds and after any further updates",
        weaker: Some(RATIONALS),
        scope: Quantifier::EveryFiniteProblem,
    },
    Theorem {
        claim: "C1-corrected",
        kind: Kind::Proves,
        name: "Truecost.C1.c1_corrected_from_above",
        file: "proofs/coq/C1.v",
        statement: "Part A: Q0 >= Q* on every pair and Q0(xg,uT) = 0: after any number >= R1 = 1 + max h(f(x,u)) of \
rounds, Q = Q*",
        weaker: Some(RATIONALS),
        scope: Quantifier::EveryFiniteProblem,
    },
    Theorem {
        claim: "C1-corrected",
        kind: Kind::Proves,
        name: "Truecost.C1.c1_corrected_from_below",
        file: "proofs/coq/C1.v",
        statement: "Part B: every move costs >= c > 0, m <= Q0 and Q* <= qm on every move pair, Q0(xg,uT) = 0: after \
any number r >= R1 of rounds with qm - m <= r c, Q = Q*",
        weaker: Some(RATIONALS),
        scope: Quantifier::EveryFiniteProblem,
    },
    Theorem {
        claim: "C1-corrected",
        kind: Kind::Proves,
        name: "Truecost.C1.c1_paper_form",
        file: "proofs/coq/C1.v",
        statement: "the paper's form: under (H0)-(H2), for every infinite update sequence in which every move pair \
occurs infinitely often, there is N such that Q = Q* after every k >= N updates",
        weaker: Some(RATIONALS),
        scope: Quantifier::EveryFiniteProblem,
    },
    Theorem {
        claim: "C2",
        kind: Kind::Proves,
        name: "Truecost.C2.c2_cost_reward_equivalence",
        file: "proofs/coq/C2.v",
        statement: "for any type of policies, any admissible set and any odd cost functional F (F(-s) = -F(s) on a \
domain closed under negation; partial functionals allowed): pi minimises F(l) iff it maximises F(-l)",
        weaker: None,
        scope: Quantifier::EveryFiniteProblem,
    },
    Theorem {
        claim: "C2",
        kind: Kind::Proves,
        name: "Truecost.C2.c2_linear",
        file: "proofs/coq/C2.v",
        statement: "every linear (and extensional) cost functional is odd: C2 for every linear functional",
        weaker: None,
        scope: Quantifier::EveryFiniteProblem,
    },
    Theorem {
        claim: "C2",
        kind: Kind::Proves,
        name: "Truecost.C2.c2_total",
        file: "proofs/coq/C2.v",
        statement: "the total cost (the series of stage costs, where it converges): minimiser iff maximiser of the \
total reward",
        weaker: None,
        scope: Quantifier::EveryFiniteProblem,
    },
    Theorem {
        claim: "C2",
        kind: Kind::Proves,
        name: "Truecost.C2.c2_discounted",
        file: "proofs/coq/C2.v",
        statement: "the discounted cost, for every discount factor alpha: minimiser iff maximiser of the \
discounted reward",
        weaker: None,
        scope: Quantifier::EveryFiniteProblem,
    },
    Theorem {
        claim: "C2",
        kind: Kind::Proves,
        name: "Truecost.C2.c2_average",
        file: "proofs/coq/C2.v",
        statement: "the long-run average cost (the limit of the means, where it exists): minimiser iff maximiser \
of the average reward",
        weaker: None,
        scope: Quantifier::EveryFiniteProblem,
    },
    Theorem {
        claim: "C2",
        kind: Kind::Proves,
        name: "Truecost.C2.c2_horizon_total",
        file: "proofs/coq/C2.v",
        statement: "the K-stage total cost, for every horizon K",
        weaker: None,
        scope: Quantifier::EveryFiniteProblem,
    },
    Theorem {
        claim: "C2",
        kind: Kind::Proves,
        name: "Truecost.C2.c2_horizon_discounted",
        file: "proofs/coq/C2.v",
        statement: "the K-stage discounted cost, for every horizon K and discount factor",
        weaker: None,
        scope: Quantifier::EveryFiniteProblem,
    },
    Theorem {
        claim: "C2",
        kind: Kind::Proves,
        name: "Truecost.C2.c2_horizon_average",
        file: "proofs/coq/C2.v",
        statement: "the K-stage average cost, for every horizon K",
        weaker: None,
        scope: Quantifier::EveryFiniteProblem,
    },
    Theorem {
        claim: "C3",
        kind: Kind::Proves,
        name: "Truecost.C3.c3_registry",
        file: "proofs/coq/C3.v",
        statement: "for every well-formed finite problem whose goal is reachable from x1 and with a stationary policy whose \
path from x1 never reaches the goal, and for EVERY alpha in (0,1): there are stage costs, strictly positive on every move \
(termination 0), on the same states and successors, for which a discount-optimal trajectory exists (among all \
trajectories, not only stationary ones) and every discount-optimal trajectory avoids the goal and has unbounded total cost",
        weaker: Some(C3_STRONGER),
        scope: Quantifier::EveryFiniteProblem,
    },
    Theorem {
        claim: "C3",
        kind: Kind::Proves,
        name: "Truecost.C3.c3_engine",
        file: "proofs/coq/C3.v",
        statement: "the certificate verify's C3 engine builds (cost 1 on the goal-avoiding lasso's moves, \
K = floor(1/((1-alpha0) alpha0^(n-2))) + 1 on every other move) works for every real alpha in (0, alpha0]: every \
discount-optimal trajectory follows the lasso, pays 1 per stage and has unbounded total cost",
        weaker: None,
        scope: Quantifier::EveryFiniteProblem,
    },
    Theorem {
        claim: "C3-example",
        kind: Kind::Proves,
        name: "Truecost.C3.c3_example_threshold_all",
        file: "proofs/coq/C3.v",
        statement: "on the worked example (X = {0..5}, goal 5, f(x,u) = min(5, max(0, x+u)), l = x+1) and for every real \
alpha in (0,1): a discount-optimal trajectory exists, every one avoids the goal iff 1/(1-alpha) < sum_{i=1..5} i \
alpha^(i-1), iff 5a^4 - a^3 - a^2 - a - 1 < 0, and then has unbounded total cost",
        weaker: None,
        scope: Quantifier::PaperExample,
    },
    Theorem {
        claim: "C3-example",
        kind: Kind::Proves,
        name: "Truecost.C3.c3_printed_iff_quartic",
        file: "proofs/coq/C3.v",
        statement: "for every real alpha in (0,1), the printed inequality holds iff 5a^4 - a^3 - a^2 - a - 1 < 0",
        weaker: None,
        scope: Quantifier::PaperExample,
    },
    Theorem {
        claim: "C3-example",
        kind: Kind::Proves,
        name: "Truecost.C3.c3_alpha_star",
        file: "proofs/coq/C3.v",
        statement: "the quartic has exactly one root alpha* in (0,1), negative below it and positive above it, and alpha* \
lies strictly between two rationals 2^-100 apart (more than 30 digits)",
        weaker: None,
        scope: Quantifier::PaperExample,
    },
    Theorem {
        claim: "C3-example",
        kind: Kind::Proves,
        name: "Truecost.C3Example.alpha_bracket_width",
        file: "proofs/coq/C3Example.v",
        statement: "the two rationals that bracket alpha* in c3_alpha_star differ by exactly 2^-100",
        weaker: None,
        scope: Quantifier::PaperExample,
    },
    Theorem {
        claim: "C4",
        kind: Kind::Refutes,
        name: "Truecost.C4.c4_as_printed_refuted",
        file: "proofs/coq/C4.v",
        statement: "on the counterexample verify prints (0 -> 1 cost 0, 0 -> goal cost 1, 1 -> goal cost 0; x1 = 0) \
and for every bonus M in [-3, -1/3): the printed interval excludes M, yet pi* is average-cost optimal against every run",
        weaker: None,
        scope: Quantifier::Counterexample,
    },
    Theorem {
        claim: "C4",
        kind: Kind::Refutes,
        name: "Truecost.C4.c4_as_printed_refuted_positive_costs",
        file: "proofs/coq/C4.v",
        statement: "on 0 -> 1 cost 1, 1 -> goal cost 1, 0 -> goal cost 3 (x1 = 0; every move cost positive) and for \
every bonus M in [-5, -5/27): the printed interval excludes M, yet pi* is average-cost optimal against every run",
        weaker: None,
        scope: Quantifier::Counterexample,
    },
    Theorem {
        claim: "C4-corrected",
        kind: Kind::Proves,
        name: "Truecost.C4.c4_corrected",
        file: "proofs/coq/C4.v",
        statement: "for every well-formed finite deterministic problem, every optimal simple goal path u* from x1 (cost L*, \
S* states) and every bonus M: the run that repeats u* and the reset is average-cost optimal against every run (every \
policy, history-dependent or not) iff max{T(u) : S(u) < S*} <= M <= min{ min{T(u) : S(u) > S*}, S*.Lav(C) - L* } \
over simple goal paths u from x1 and goal-avoiding cycles C reachable from x1",
        weaker: Some(C4_WEAKER),
        scope: Quantifier::EveryFiniteProblem,
    },
    Theorem {
        claim: "C4-corrected",
        kind: Kind::Proves,
        name: "Truecost.C4.pistar_exists",
        file: "proofs/coq/C4.v",
        statement: "whenever the goal is reachable from x1, an optimal single-shot path pi* exists and is simple, so \
c4_corrected applies to every such problem",
        weaker: None,
        scope: Quantifier::EveryFiniteProblem,
    },
    Theorem {
        claim: "certificates",
        kind: Kind::Proves,
        name: "Truecost.Certificate.maximum_principle",
        file: "proofs/coq/Certificate.v",
        statement: "for every finite set S of states closed under a policy's outcomes (non-negative probabilities \
summing to 1) from each of whose states a goal is reachable along outcomes of positive probability: every D with \
D = 0 at the goals of S and D(x) <= sum_y p(y|x) D(y) at its other states has D <= 0 on S",
        weaker: None,
        scope: Quantifier::EveryFiniteMdp,
    },
    Theorem {
        claim: "certificates",
        kind: Kind::Proves,
        name: "Truecost.Certificate.certificate_optimal",
        file: "proofs/coq/Certificate.v",
        statement: "for S and a policy mu as in maximum_principle: values V with V = 0 at goals and \
V(x) <= c(x, mu(x)) + sum_y p V(y) elsewhere (the checker's goal and optimality conditions) are at most mu's \
expected cost J (J = 0 at goals, J(x) = c(x, mu(x)) + sum_y p J(y)) on S",
        weaker: None,
        scope: Quantifier::EveryFiniteMdp,
    },
    Theorem {
        claim: "certificates",
        kind: Kind::Proves,
        name: "Truecost.Certificate.proper_inside_Wstar",
        file: "proofs/coq/Certificate.v",
        statement: "for every finite MDP and every set R closed under a stationary policy mu, from each of whose \
states mu reaches a goal along outcomes of positive probability: R lies in every round of the checker's W* \
iteration (from all states, keep those reaching a goal by actions whose outcomes all stay in the previous round), \
so a state outside W* has no proper policy",
        weaker: None,
        scope: Quantifier::EveryFiniteMdp,
    },
    Theorem {
        claim: "certificates",
        kind: Kind::Proves,
        name: "Truecost.CertificateCheck.check_policy",
        file: "proofs/coq/CertificateCheck.v",
        statement: "for every finite model (goal flags, actions with costs and outcomes) and every certificate \
(values, policy, hints) that the Coq checker check accepts: at every finite non-goal state the policy's action has \
all its outcomes finite, the value solves the policy's equation exactly, and a goal is reachable along the policy's \
outcomes",
        weaker: None,
        scope: Quantifier::EveryFiniteMdp,
    },
    Theorem {
        claim: "certificates",
        kind: Kind::Proves,
        name: "Truecost.CertificateCheck.check_optimal",
        file: "proofs/coq/CertificateCheck.v",
        statement: "for every finite model and every certificate that check accepts: for every stationary policy mu, \
every set S closed under mu's outcomes from each of whose states mu reaches a goal, and every J solving mu's \
equations on S (its expected cost), every state of S has a finite value, at most J",
        weaker: None,
        scope: Quantifier::EveryFiniteMdp,
    },
    Theorem {
        claim: "certificates",
        kind: Kind::Proves,
        name: "Truecost.CertificateDiscounted.check_discounted_policy",
        file: "proofs/coq/CertificateDiscounted.v",
        statement: "for every finite model (terminal flags, actions with rewards and outcomes), every alpha and \
every certificate (values, policy) that the discounted checker check_discounted accepts: every state has a finite \
value, 0 at terminal states, and elsewhere the policy names an action whose r + alpha * sum p V is the value",
        weaker: None,
        scope: Quantifier::EveryFiniteMdp,
    },
    Theorem {
        claim: "certificates",
        kind: Kind::Proves,
        name: "Truecost.CertificateDiscounted.check_discounted_optimal",
        file: "proofs/coq/CertificateDiscounted.v",
        statement: "for every finite model and every certificate that check_discounted accepts (so 0 < alpha < 1): \
for every stationary policy mu and every J solving mu's discounted equations (J = 0 at terminal states, \
J = r + alpha * sum p J elsewhere: its expected discounted reward), J <= V at every state",
        weaker: None,
        scope: Quantifier::EveryFiniteMdp,
    },
];

/// What the C1 theorems are weaker than the paper's statement in.
const RATIONALS: &str =
    "costs and initial values are rationals (Coq's Q, computable for the bridge to the \
kernel's oracles), not reals";

/// Where the C3 theorem is stronger than the registry's statement.
const C3_STRONGER: &str =
    "stronger, not weaker: the costs exist for every alpha in (0,1), not for one; costs are \
rationals (Coq's Q)";

/// Where the C4-corrected theorem differs from the registry's statement.
const C4_WEAKER: &str =
    "costs and the bonus are rationals (Coq's Q); the equivalence is proved for every M, and \
for M < 0 it is the registry's statement";

/// The theorems of `claim`, in table order.
///
/// ```
/// use truecost::claims::coq::theorems_of;
/// assert!(theorems_of("C1-corrected").iter().any(|t| t.name == "Truecost.C1.c1_corrected"));
/// assert!(theorems_of("C9").is_empty());
/// ```
pub fn theorems_of(claim: &str) -> Vec<&'static Theorem> {
    THEOREMS.iter().filter(|t| t.claim == claim).collect()
}

/// The development's `_CoqProject`, embedded.
pub const COQ_PROJECT: &str = include_str!("../../proofs/coq/_CoqProject");

/// The development's sources `(file name, text)`, in `_CoqProject` order (a test checks the
/// order against [`COQ_PROJECT`]).
pub const SOURCES: &[(&str, &str)] = &[
    ("Model.v", include_str!("../../proofs/coq/Model.v")),
    ("Paths.v", include_str!("../../proofs/coq/Paths.v")),
    ("C1.v", include_str!("../../proofs/coq/C1.v")),
    ("C2.v", include_str!("../../proofs/coq/C2.v")),
    (
        "BridgeCommon.v",
        include_str!("../../proofs/coq/BridgeCommon.v"),
    ),
    ("Bridge.v", include_str!("../../proofs/coq/Bridge.v")),
    ("BridgeRun.v", include_str!("../../proofs/coq/BridgeRun.v")),
    ("QReal.v", include_str!("../../proofs/coq/QReal.v")),
    (
        "C3Policies.v",
        include_str!("../../proofs/coq/C3Policies.v"),
    ),
    (
        "C3Certificate.v",
        include_str!("../../proofs/coq/C3Certificate.v"),
    ),
    ("C3Example.v", include_str!("../../proofs/coq/C3Example.v")),
    ("C3Engine.v", include_str!("../../proofs/coq/C3Engine.v")),
    ("C3.v", include_str!("../../proofs/coq/C3.v")),
    ("C4.v", include_str!("../../proofs/coq/C4.v")),
    ("BridgeC34.v", include_str!("../../proofs/coq/BridgeC34.v")),
    (
        "Certificate.v",
        include_str!("../../proofs/coq/Certificate.v"),
    ),
    (
        "CertificateCheck.v",
        include_str!("../../proofs/coq/CertificateCheck.v"),
    ),
    (
        "CertificateDiscounted.v",
        include_str!("../../proofs/coq/CertificateDiscounted.v"),
    ),
];

/// The axioms `Print Assumptions` may list, exactly as Coq 8.16 prints their names: the
/// standard library's classical axioms of its real numbers (`Reals`), and functional
/// extensionality, on which the library's construction of `R` rests. Nothing else.
pub const ALLOWED_AXIOMS: &[&str] = &[
    "ClassicalDedekindReals.sig_forall_dec",
    "ClassicalDedekindReals.sig_not_dec",
    "FunctionalExtensionality.functional_extensionality_dep",
];

/// The `.v` files named by a `_CoqProject`'s text, in order (options such as `-R . Truecost`
/// and `#` comments skipped).
///
/// ```
/// use truecost::claims::coq::project_files;
/// let text = "-R . Truecost\n# the model first\nModel.v\nC1.v C2.v\n";
/// assert_eq!(project_files(text), ["Model.v", "C1.v", "C2.v"]);
/// ```
pub fn project_files(text: &str) -> Vec<String> {
    let mut out = Vec::new();
    for line in text.lines() {
        let line = line.split('#').next().unwrap_or("");
        let mut words = line.split_whitespace().peekable();
        while let Some(w) = words.next() {
            if w.starts_with('-') {
                // An option and its arguments (`-R dir name`, `-Q dir name`, `-arg x`).
                let args = match w {
                    "-R" | "-Q" => 2,
                    "-arg" | "-I" => 1,
                    _ => 0,
                };
                for _ in 0..args {
                    words.next();
                }
            } else if w.ends_with(".v") {
                out.push(w.to_string());
            }
        }
    }
    out
}

/// What `Print Assumptions` said about one theorem.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Assumptions {
    /// "Closed under the global context": no axiom at all.
    Closed,
    /// Only axioms of [`ALLOWED_AXIOMS`] (listed as printed).
    Allowed(Vec<String>),
    /// Something else: axioms, parameters or section variables outside the allowed list, or
    /// output that could not be read (listed).
    Forbidden(Vec<String>),
    /// The theorem is not in the development (Coq's message).
    Missing(String),
}

impl Assumptions {
    /// Whether the theorem is accepted (closed, or only allowed axioms).
    pub fn accepted(&self) -> bool {
        matches!(self, Assumptions::Closed | Assumptions::Allowed(_))
    }

    /// In words, for the report.
    ///
    /// ```
    /// use truecost::claims::coq::Assumptions;
    /// assert_eq!(Assumptions::Closed.describe(), "closed under the global context (no axioms)");
    /// ```
    pub fn describe(&self) -> String {
        match self {
            Assumptions::Closed => "closed under the global context (no axioms)".into(),
            Assumptions::Allowed(a) => format!(
                "only the standard library's axioms of the reals: {}",
                a.join(", ")
            ),
            Assumptions::Forbidden(a) => format!("FORBIDDEN assumptions: {}", a.join(", ")),
            Assumptions::Missing(why) => format!("MISSING from the development ({why})"),
        }
    }
}

/// Classifies the output of `Print Assumptions` for one theorem (Coq 8.16's format): the
/// line "Closed under the global context", or blocks headed `Axioms:`, `Section Variables:`,
/// `Constants relying on type-in-type:`, … whose entries start in the first column (a
/// continuation line starts with a space or with `:`). Only `Axioms:` entries named in
/// [`ALLOWED_AXIOMS`] are allowed; an entry of any other block is forbidden, and so is output
/// that is neither.
///
/// ```
/// use truecost::claims::coq::{parse_assumptions, Assumptions};
/// assert_eq!(parse_assumptions("Closed under the global context\n"), Assumptions::Closed);
/// let out = "Axioms:\nfoo : False\n";
/// assert_eq!(parse_assumptions(out), Assumptions::Forbidden(vec!["foo (Axioms)".into()]));
/// ```
pub fn parse_assumptions(output: &str) -> Assumptions {
    if output
        .lines()
        .any(|l| l.trim() == "Closed under the global context")
    {
        return Assumptions::Closed;
    }
    let mut header: Option<String> = None;
    let mut allowed = Vec::new();
    let mut forbidden = Vec::new();
    for line in output.lines() {
        if line.trim().is_empty() || line.starts_with(' ') || line.starts_with('\t') {
            continue; // a continuation of the previous entry's type
        }
        if line.starts_with(':') {
            continue; // `name` on one line, `: type` on the next
        }
        if line.ends_with(':') && !line.contains(" : ") {
            header = Some(line.trim_end_matches(':').trim().to_string());
            continue;
        }
        let name = line
            .split(" : ")
            .next()
            .unwrap_or(line)
            .split_whitespace()
            .next()
            .unwrap_or(line)
            .to_string();
        match header.as_deref() {
            Some("Axioms") if ALLOWED_AXIOMS.contains(&name.as_str()) => allowed.push(name),
            Some(h) => forbidden.push(format!("{name} ({h})")),
            None => forbidden.push(format!("unreadable output: {line}")),
        }
    }
    if forbidden.is_empty() && allowed.is_empty() {
        let first = output.lines().find(|l| !l.trim().is_empty()).unwrap_or("");
        forbidden.push(format!("unreadable output: {first:?}"));
    }
    if forbidden.is_empty() {
        Assumptions::Allowed(allowed)
    } else {
        Assumptions::Forbidden(forbidden)
    }
}

/// The vernacular words that admit something without proof: a source that uses any of them
/// (outside comments and strings) is refused before it is compiled.
pub const FORBIDDEN_WORDS: &[&str] = &[
    "Admitted",
    "admit",
    "give_up",
    "Axiom",
    "Axioms",
    "Parameter",
    "Parameters",
    "Conjecture",
    "Conjectures",
];

/// `text` with its comments (nested `(* … *)`) and string literals blanked out, newlines
/// kept (so line numbers stay).
fn code_only(text: &str) -> String {
    let b: Vec<char> = text.chars().collect();
    let mut out = String::with_capacity(text.len());
    let (mut depth, mut in_string, mut i) = (0usize, false, 0usize);
    while i < b.len() {
        let c = b[i];
        let next = b.get(i + 1).copied();
        if in_string {
            if c == '"' && next == Some('"') {
                i += 2; // an escaped quote
                out.push_str("  ");
                continue;
            }
            if c == '"' {
                in_string = false;
            }
            out.push(if c == '\n' { '\n' } else { ' ' });
        } else if c == '(' && next == Some('*') {
            depth += 1;
            out.push_str("  ");
            i += 2;
            continue;
        } else if depth > 0 && c == '*' && next == Some(')') {
            depth -= 1;
            out.push_str("  ");
            i += 2;
            continue;
        } else if depth > 0 {
            out.push(if c == '\n' { '\n' } else { ' ' });
        } else if c == '"' {
            in_string = true;
            out.push(' ');
        } else {
            out.push(c);
        }
        i += 1;
    }
    out
}

/// Every use of a [`FORBIDDEN_WORDS`] word outside comments and strings, as
/// `file:line: word` (empty when the sources are acceptable). Words are whole identifiers:
/// `admit_rule` or `Axiomatic` are not uses.
///
/// ```
/// use truecost::claims::coq::scan_sources;
/// let ok = ("A.v", "(* Admitted in a comment *) Lemma a : True. Proof. exact I. Qed.");
/// assert!(scan_sources(&[ok]).is_empty());
/// let bad = ("B.v", "Lemma b : False.\nProof. admit. Admitted.");
/// assert_eq!(scan_sources(&[bad]), ["B.v:2: admit", "B.v:2: Admitted"]);
/// ```
pub fn scan_sources(sources: &[(&str, &str)]) -> Vec<String> {
    let mut found = Vec::new();
    for (file, text) in sources {
        for (n, line) in code_only(text).lines().enumerate() {
            let ident = |c: char| c.is_alphanumeric() || c == '_' || c == '\'';
            for word in line.split(|c: char| !ident(c)) {
                if FORBIDDEN_WORDS.contains(&word) {
                    found.push(format!("{file}:{}: {word}", n + 1));
                }
            }
        }
    }
    found
}

/// The pinned statements and axioms of [`THEOREMS`] (the format of [`parse_pins`]): what
/// `Check` and `Print Assumptions` print for each theorem with Coq 8.16.1, generated from a
/// real `coqc` by `TRUECOST_PIN_COQ=1 cargo test -p truecost --test coq_trust` (which fails,
/// printing the difference, whenever the file is not what `coqc` prints).
pub const PINNED: &str = include_str!("../../proofs/coq/statements.txt");

/// One theorem's pinned statement and axioms.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Pin {
    /// The fully qualified name.
    pub name: String,
    /// The axioms `Print Assumptions` lists, sorted (empty: closed under the global context).
    pub axioms: Vec<String>,
    /// The statement as `Check` prints it ([`CHECK_PREAMBLE`]), whitespace collapsed.
    pub statement: String,
}

/// Reads pinned statements: blocks of three lines `theorem NAME`, `axioms closed` (or the
/// axioms' names separated by spaces) and `statement TEXT`; blank lines and `#` comments
/// between blocks.
///
/// ```
/// use truecost::claims::coq::{parse_pins, render_pins};
/// let text = "# pinned\ntheorem T.A.a\naxioms closed\nstatement 1 = 1\n";
/// let pins = parse_pins(text).unwrap();
/// assert_eq!((pins[0].name.as_str(), pins[0].statement.as_str()), ("T.A.a", "1 = 1"));
/// assert!(pins[0].axioms.is_empty());
/// assert_eq!(parse_pins(&render_pins(&pins)).unwrap(), pins);
/// assert!(parse_pins("theorem T.A.a\nstatement 1 = 1\n").is_err());
/// ```
pub fn parse_pins(text: &str) -> Result<Vec<Pin>, String> {
    let mut lines = text
        .lines()
        .enumerate()
        .filter(|(_, l)| !l.trim().is_empty() && !l.starts_with('#'));
    let mut pins = Vec::new();
    while let Some((n, first)) = lines.next() {
        let field = |line: Option<(usize, &str)>, key: &str| -> Result<String, String> {
            let (n, l) = line.ok_or_else(|| format!("the file ends before `{key}`"))?;
            l.strip_prefix(key)
                .and_then(|rest| rest.strip_prefix(' '))
                .map(|rest| rest.trim().to_string())
                .ok_or_else(|| format!("line {}: expected `{key} ...`", n + 1))
        };
        let name = field(Some((n, first)), "theorem")?;
        let axioms = field(lines.next(), "axioms")?;
        let statement = field(lines.next(), "statement")?;
        let mut axioms: Vec<String> = match axioms.as_str() {
            "closed" => vec![],
            list => list.split_whitespace().map(str::to_string).collect(),
        };
        axioms.sort();
        pins.push(Pin {
            name,
            axioms,
            statement,
        });
    }
    Ok(pins)
}

/// The text of a pinned-statements file for `pins` (read back by [`parse_pins`]).
pub fn render_pins(pins: &[Pin]) -> String {
    let mut s = String::from(
        "# The statement (as `Check` prints it after the preamble of claims::coq::CHECK_PREAMBLE,\n\
# whitespace collapsed) and the axioms (`Print Assumptions`) of every Coq theorem that\n\
# `truecost verify` cites, as Coq 8.16.1 prints them. Generated, never edited by hand:\n\
#   TRUECOST_PIN_COQ=1 cargo test -p truecost --test coq_trust\n",
    );
    for p in pins {
        let axioms = if p.axioms.is_empty() {
            "closed".to_string()
        } else {
            p.axioms.join(" ")
        };
        s.push_str(&format!(
            "\ntheorem {}\naxioms {axioms}\nstatement {}\n",
            p.name, p.statement
        ));
    }
    s
}

/// The pinned statements of this build ([`PINNED`]).
pub fn pins() -> Result<Vec<Pin>, String> {
    parse_pins(PINNED).map_err(|e| format!("proofs/coq/statements.txt: {e}"))
}

/// What the file that asks Coq about the theorems starts with: the notations `Check` prints
/// with (reals, rationals, lists), and a line width and depth that print every statement on
/// one line and in full. The pinned statements are printed this way.
pub const CHECK_PREAMBLE: &str = "From Coq Require Import Reals QArith List.
Set Printing Width 1000000.
Set Printing Depth 1000000.
";

/// The type of `Check name.`'s output (`name` on one line, `: type` from the next), whitespace
/// collapsed; `None` when the output is not of that form.
///
/// ```
/// use truecost::claims::coq::parse_check;
/// assert_eq!(parse_check("C3.w\n     : forall a : R,\n  a = a\n").as_deref(), Some("forall a : R, a = a"));
/// assert_eq!(parse_check("Closed under the global context\n"), None);
/// ```
pub fn parse_check(output: &str) -> Option<String> {
    let lines: Vec<&str> = output.lines().filter(|l| !l.trim().is_empty()).collect();
    let at = lines
        .iter()
        .position(|l| l.starts_with(char::is_whitespace) && l.trim_start().starts_with(": "))?;
    if at == 0 || lines[..at].iter().any(|l| l.contains(' ')) {
        return None;
    }
    let text = lines[at..].join(" ");
    let statement = text
        .trim_start()
        .strip_prefix(':')?
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ");
    (!statement.is_empty()).then_some(statement)
}

/// `text` with every control character except newline and tab, and every Unicode
/// bidirectional override, shown escaped (`\x1b`, `\r`, `\u{202e}`): what `coqc` prints
/// reaches every format of the report as plain text.
///
/// ```
/// use truecost::claims::coq::escape_output;
/// assert_eq!(escape_output("a\x1b[31mred\r\n\tb\u{202e}"), "a\\x1b[31mred\\r\n\tb\\u{202e}");
/// ```
pub fn escape_output(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '\n' | '\t' => out.push(c),
            '\r' => out.push_str("\\r"),
            c if (c as u32) < 0x20 || c as u32 == 0x7f => {
                out.push_str(&format!("\\x{:02x}", c as u32))
            }
            c if c.is_control()
                || matches!(c, '\u{202a}'..='\u{202e}' | '\u{2066}'..='\u{2069}') =>
            {
                out.push_str(&format!("\\u{{{:x}}}", c as u32))
            }
            c => out.push(c),
        }
    }
    out
}

/// How a re-check ended.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Outcome {
    /// Every file compiled and every theorem's statement and assumptions were printed (see
    /// [`Check::theorems`]).
    Checked,
    /// `coqc` could not be run (the reason): nothing was re-checked.
    NotAvailable(String),
    /// The sources use a forbidden word ([`scan_sources`]): not compiled.
    SourcesRefused(Vec<String>),
    /// A file did not compile (the file and Coq's message). The files before it compiled,
    /// and the theorems of those files were still asked about ([`Check::theorems`]).
    BuildFailed(String),
    /// The program called `coqc` did not behave as Coq (what it did): a false lemma
    /// compiled, a true one did not, no `.vo` file was written, or its `Check` and
    /// `Print Assumptions` output was not Coq's. Nothing it said is trusted.
    NotCoq(String),
    /// `coqc` did not finish within the re-check's time limit and was stopped (what it was
    /// doing). Nothing is trusted.
    TimedOut(String),
}

/// One theorem's result.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct TheoremCheck {
    /// The fully qualified name.
    pub name: String,
    /// What `Print Assumptions` said.
    pub assumptions: Assumptions,
    /// The statement as `Check` printed it in this run ([`parse_check`]; escaped), if it did.
    pub statement: Option<String>,
    /// Why the theorem is not accepted (`None`: accepted): missing, a forbidden assumption,
    /// a statement or an axiom list other than the pinned one ([`judge`]).
    pub refused: Option<String>,
}

impl TheoremCheck {
    /// Whether the theorem is accepted: its statement and its axioms are the pinned ones.
    pub fn accepted(&self) -> bool {
        self.refused.is_none()
    }
}

/// Judges one theorem against its pin: `None` when Coq printed exactly the pinned statement
/// and `Print Assumptions` listed exactly the pinned axioms (each of them in
/// [`ALLOWED_AXIOMS`]); otherwise the reason it is refused.
///
/// ```
/// use truecost::claims::coq::{judge, Assumptions, Pin};
/// let pin = Pin { name: "T.a".into(), axioms: vec![], statement: "1 = 1".into() };
/// assert_eq!(judge(Some(&pin), Some("1 = 1"), &Assumptions::Closed), None);
/// let weaker = judge(Some(&pin), Some("True"), &Assumptions::Closed).unwrap();
/// assert!(weaker.starts_with("Coq's statement differs from the pinned one"), "{weaker}");
/// ```
pub fn judge(
    pin: Option<&Pin>,
    statement: Option<&str>,
    assumptions: &Assumptions,
) -> Option<String> {
    if let Assumptions::Missing(_) | Assumptions::Forbidden(_) = assumptions {
        return Some(assumptions.describe());
    }
    let Some(pin) = pin else {
        return Some("no pinned statement for it (proofs/coq/statements.txt)".into());
    };
    let Some(statement) = statement else {
        return Some("Coq printed no statement for it (Check)".into());
    };
    if statement != pin.statement {
        return Some(format!(
            "Coq's statement differs from the pinned one: Coq states `{statement}`; pinned: `{}`",
            pin.statement
        ));
    }
    let mut expected = pin.axioms.clone();
    expected.sort();
    expected.dedup();
    if let Some(bad) = expected
        .iter()
        .find(|a| !ALLOWED_AXIOMS.contains(&a.as_str()))
    {
        return Some(format!("the pinned axiom {bad} is not an allowed axiom"));
    }
    let mut listed = match assumptions {
        Assumptions::Allowed(a) => a.clone(),
        _ => vec![],
    };
    listed.sort();
    listed.dedup();
    if listed != expected {
        let extra: Vec<&str> = listed
            .iter()
            .filter(|a| !expected.contains(a))
            .map(String::as_str)
            .collect();
        let missing: Vec<&str> = expected
            .iter()
            .filter(|a| !listed.contains(a))
            .map(String::as_str)
            .collect();
        let list = |v: &[&str]| {
            if v.is_empty() {
                "none".to_string()
            } else {
                v.join(", ")
            }
        };
        return Some(format!(
            "Print Assumptions does not list exactly the pinned axioms: extra {}; missing {}",
            list(&extra),
            list(&missing)
        ));
    }
    None
}

/// The result of one re-check of the Coq development.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Check {
    /// `coqc`'s version (`8.16.1`, escaped), when it ran.
    pub version: Option<String>,
    /// How it ended.
    pub outcome: Outcome,
    /// Every theorem asked about, in table order (empty unless `coqc` ran on the sources; a
    /// theorem of a file left uncompiled by a failure is [`Assumptions::Missing`]).
    pub theorems: Vec<TheoremCheck>,
    /// The number of source files compiled.
    pub files: usize,
    /// Wall-clock seconds of the whole re-check (never part of a pinned report).
    #[serde(skip)]
    pub seconds: f64,
}

impl Check {
    /// The result for the theorem `name`, if it was asked about.
    pub fn theorem(&self, name: &str) -> Option<&TheoremCheck> {
        self.theorems.iter().find(|t| t.name == name)
    }

    /// `Coq <version>` (or `Coq` when it did not run).
    pub fn coq(&self) -> String {
        match &self.version {
            Some(v) => format!("Coq {v}"),
            None => "Coq".into(),
        }
    }

    /// Whether every theorem asked about was re-checked and accepted.
    pub fn all_accepted(&self) -> bool {
        self.outcome == Outcome::Checked
            && !self.theorems.is_empty()
            && self.theorems.iter().all(TheoremCheck::accepted)
    }

    /// Whether `coqc` was trusted in this run: it ran, behaved as Coq and finished in time
    /// (the sources compiled, or failed to compile, as Coq's own verdict).
    pub fn trusted(&self) -> bool {
        matches!(self.outcome, Outcome::Checked | Outcome::BuildFailed(_))
    }
}

/// The message of [`Outcome::NotAvailable`] when `coqc` is not on `PATH`.
pub const NOT_FOUND: &str = "coqc not found: install Coq (Debian/Ubuntu: apt-get install -y coq; the README's prerequisites)";

/// The default time limit of a whole re-check, in seconds (`verify --coq-timeout`): the
/// development compiles in well under a minute on 2 cores.
pub const TIMEOUT_SECONDS: u64 = 600;

/// How to re-check: which program is `coqc`, the time limit of the whole re-check, and the
/// pinned statements to compare with.
#[derive(Clone, Debug)]
pub struct Settings {
    /// The program run as `coqc` (looked up on `PATH` unless a path).
    pub coqc: std::ffi::OsString,
    /// The time limit of the whole re-check (every `coqc` call shares it).
    pub timeout: Duration,
    /// The pinned statements and axioms ([`pins`]).
    pub pins: Vec<Pin>,
}

impl Settings {
    /// `coqc` from `PATH`, this build's pins ([`pins`]; none if the file cannot be read, so
    /// that every theorem is refused), and the time limit `timeout`.
    pub fn with_timeout(timeout: Duration) -> Settings {
        Settings {
            coqc: "coqc".into(),
            timeout,
            pins: pins().unwrap_or_default(),
        }
    }
}

/// `coqc --version`'s version number (`8.16.1`), or why `coqc` cannot be run (a 60 s limit).
pub fn coqc_version() -> Result<String, String> {
    let dir = process::TempDir::new()?;
    let coqc = process::Coqc::new("coqc".as_ref(), Duration::from_secs(60), dir.path());
    match version(&coqc) {
        Ok(v) => Ok(v),
        Err(Failure::Absent(why) | Failure::NotCoq(why) | Failure::TimedOut(why)) => Err(why),
        Err(Failure::Interrupted(sig)) => {
            drop(dir);
            process::reraise(sig)
        }
    }
}

/// Why a re-check stopped before judging the theorems.
enum Failure {
    /// `coqc` cannot be run.
    Absent(String),
    /// It did not behave as Coq.
    NotCoq(String),
    /// It ran out of time.
    TimedOut(String),
    /// SIGINT or SIGTERM arrived (the signal's number).
    Interrupted(i32),
}

impl Failure {
    fn from_stop(stop: process::Stop, doing: &str) -> Failure {
        match stop {
            process::Stop::TimedOut(limit) => Failure::TimedOut(format!(
                "coqc did not finish within {limit} s (the re-check's limit, --coq-timeout) while {doing}; stopped"
            )),
            process::Stop::Interrupted(sig) => Failure::Interrupted(sig),
            process::Stop::Spawn(e) if e.kind() == std::io::ErrorKind::NotFound => {
                Failure::Absent(NOT_FOUND.into())
            }
            process::Stop::Spawn(e) => Failure::Absent(format!("coqc cannot be run: {e}")),
        }
    }
}

fn version(coqc: &process::Coqc) -> Result<String, Failure> {
    let out = coqc
        .run(&["--version".as_ref()], coqc.dir())
        .map_err(|s| Failure::from_stop(s, "printing its version"))?;
    let first = out.stdout.lines().next().unwrap_or("").to_string();
    match first.split("version ").nth(1) {
        Some(v) if out.success => Ok(v.trim().to_string()),
        _ => Err(Failure::Absent(format!("coqc --version printed {first:?}"))),
    }
}

/// Re-checks the embedded development ([`SOURCES`]) against [`THEOREMS`] with the `coqc` on
/// `PATH` and this build's pinned statements, stopping `coqc` after `timeout` (see
/// [`recheck_sources`]).
pub fn recheck(timeout: Duration) -> Check {
    let names: Vec<&str> = THEOREMS.iter().map(|t| t.name).collect();
    recheck_sources(SOURCES, &names, &Settings::with_timeout(timeout))
}

/// Re-checks a development: refuses it if [`scan_sources`] finds anything; otherwise, in a
/// fresh temporary directory,
/// 1. asks `coqc --version`;
/// 2. makes sure `coqc` behaves as Coq: a false lemma (`a + b = a + b + 1` for numbers drawn
///    for this run) must fail, a true one must compile to a `.vo` file, and its `Check` and
///    `Print Assumptions` must print its statement and "Closed under the global context";
/// 3. writes `sources` (in order) and compiles each with `coqc -R <dir> Truecost`, each
///    compile required to write its `.vo` file;
/// 4. asks `Check` and `Print Assumptions` about each of `theorems` (fully qualified names,
///    `Truecost.` + module path + name) — all in one `coqc` process, a theorem it could not
///    answer again in a file of its own — and judges each against `settings.pins` ([`judge`]):
///    the statement and the axiom list must be exactly the pinned ones.
///
/// Every `coqc` runs in its own process group and the whole re-check shares
/// `settings.timeout`: past it, the group is killed ([`Outcome::TimedOut`]). SIGINT and
/// SIGTERM received meanwhile kill the group too, remove the directory, and then end the
/// process by the same signal. The directory is removed on every way out (a panic included).
/// Everything `coqc` prints is escaped ([`escape_output`]).
pub fn recheck_sources(sources: &[(&str, &str)], theorems: &[&str], settings: &Settings) -> Check {
    let started = Instant::now();
    let mut check = Check {
        version: None,
        outcome: Outcome::Checked,
        theorems: Vec::new(),
        files: 0,
        seconds: 0.0,
    };
    let refused = scan_sources(sources);
    if !refused.is_empty() {
        check.outcome = Outcome::SourcesRefused(refused);
        return check;
    }
    let signals = process::Signals::install();
    let result = process::TempDir::new()
        .map_err(Failure::Absent)
        .and_then(|dir| {
            let coqc = process::Coqc::new(&settings.coqc, settings.timeout, dir.path());
            let result = run_checks(&coqc, sources, theorems, settings, &mut check);
            drop(dir);
            result
        });
    drop(signals);
    match result {
        Ok(None) => {}
        Ok(Some(why)) => check.outcome = Outcome::BuildFailed(why),
        Err(Failure::Absent(why)) => check.outcome = Outcome::NotAvailable(why),
        Err(Failure::NotCoq(why)) => check.outcome = Outcome::NotCoq(why),
        Err(Failure::TimedOut(why)) => check.outcome = Outcome::TimedOut(why),
        Err(Failure::Interrupted(sig)) => process::reraise(sig),
    }
    if let Some(sig) = process::Signals::received() {
        process::reraise(sig);
    }
    if !check.trusted() {
        // Nothing said by a coqc that was not trusted reaches the report as a result.
        check.theorems.clear();
        check.files = 0;
    }
    check.seconds = started.elapsed().as_secs_f64();
    check
}

/// The canaries of one run: a false lemma and a true one over numbers drawn for the run, so
/// that no fixed output passes for Coq's.
fn canaries() -> (String, String, String) {
    let nanos = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.subsec_nanos());
    let (a, b) = (1 + nanos % 97, 1 + (nanos / 97) % 89);
    let statement = format!("{a} + {b} = {}", a + b);
    let false_lemma = format!(
        "Lemma canary_false : {a} + {b} = {}.\nProof. reflexivity. Qed.\n",
        a + b + 1
    );
    let true_lemma = format!(
        "{CHECK_PREAMBLE}Lemma canary_true : {statement}.\nProof. reflexivity. Qed.\n{}",
        ask_text(&["canary_true"], 0)
    );
    (false_lemma, true_lemma, statement)
}

/// The questions about `names`: per theorem `k`, a marker, `Check`, a marker and
/// `Print Assumptions`; a last marker after them.
fn ask_text(names: &[&str], first: usize) -> String {
    let mut s = String::new();
    for (k, name) in names.iter().enumerate() {
        s.push_str(&format!(
            "Goal True. idtac \"{}\". Abort.\nCheck {name}.\nGoal True. idtac \"{}\". Abort.\nPrint Assumptions {name}.\n",
            marker("check", first + k),
            marker("assumptions", first + k)
        ));
    }
    s.push_str(&format!(
        "Goal True. idtac \"{}\". Abort.\n",
        marker("check", first + names.len())
    ));
    s
}

fn marker(what: &str, k: usize) -> String {
    format!("<<truecost-{what} {k}>>")
}

/// The answer to question `k` of [`ask_text`] in `out`: the statement and the assumptions,
/// when both markers around it were printed.
fn answer(out: &str, k: usize) -> Option<(Option<String>, Assumptions)> {
    let (check, assumptions) = (marker("check", k), marker("assumptions", k));
    let from = out.find(&check)? + check.len();
    let mid = out[from..].find(&assumptions)? + from;
    let to = out[mid..].find(&marker("check", k + 1))? + mid;
    Some((
        parse_check(&out[from..mid]),
        parse_assumptions(&out[mid + assumptions.len()..to]),
    ))
}

/// Steps 1–4 of [`recheck_sources`] in `coqc`'s directory; `Ok(Some(why))` when a source did
/// not compile (the theorems of the files before it still judged).
fn run_checks(
    coqc: &process::Coqc,
    sources: &[(&str, &str)],
    theorems: &[&str],
    settings: &Settings,
    check: &mut Check,
) -> Result<Option<String>, Failure> {
    let base = coqc.dir();
    let src = base.join("src");
    let ask = base.join("ask");
    let canary = base.join("canary");
    for d in [&src, &ask, &canary] {
        std::fs::create_dir_all(d)
            .map_err(|e| Failure::Absent(format!("cannot create {}: {e}", d.display())))?;
    }
    let write = |path: PathBuf, text: &str| {
        std::fs::write(&path, text)
            .map_err(|e| Failure::Absent(format!("cannot write {}: {e}", path.display())))
    };
    check.version = Some(version(coqc)?);
    // 2. The canaries.
    let (false_lemma, true_lemma, statement) = canaries();
    write(canary.join("CanaryFalse.v"), &false_lemma)?;
    write(canary.join("CanaryTrue.v"), &true_lemma)?;
    let run = |cwd: &Path, file: &str, doing: &str| {
        coqc.run(
            &[
                "-R".as_ref(),
                src.as_os_str(),
                "Truecost".as_ref(),
                file.as_ref(),
            ],
            cwd,
        )
        .map_err(|s| Failure::from_stop(s, doing))
    };
    let out = run(&canary, "CanaryFalse.v", "compiling a false lemma")?;
    if out.success || canary.join("CanaryFalse.vo").exists() {
        return Err(Failure::NotCoq(format!(
            "it accepted a false lemma: {}",
            false_lemma.lines().next().unwrap_or("")
        )));
    }
    let out = run(&canary, "CanaryTrue.v", "compiling a true lemma")?;
    if !out.success {
        return Err(Failure::NotCoq(format!(
            "it refused a true lemma ({statement}): {}",
            out.message()
        )));
    }
    if !nonempty(&canary.join("CanaryTrue.vo")) {
        return Err(Failure::NotCoq(
            "it wrote no CanaryTrue.vo for a true lemma".into(),
        ));
    }
    match answer(&out.stdout, 0) {
        Some((Some(s), Assumptions::Closed)) if s == statement => {}
        other => {
            return Err(Failure::NotCoq(format!(
                "Check and Print Assumptions on a true lemma ({statement}, no axioms) printed {:?}",
                other.map(|(s, a)| (s, a.describe()))
            )))
        }
    }
    // 3. The sources, each depending only on the files before it (`_CoqProject` order): the
    // files compiled before a failure are sound, and their theorems are still asked about.
    for (name, text) in sources {
        if name.contains('/') || name.contains('\\') || !name.ends_with(".v") {
            return Err(Failure::Absent(format!("{name}: not a plain .v file name")));
        }
        write(src.join(name), text)?;
    }
    let mut failed = None;
    for (name, _) in sources {
        let out = run(&src, name, &format!("compiling {name}"))?;
        if !out.success {
            failed = Some(format!("{name} does not compile: {}", out.message()));
            break;
        }
        if !nonempty(&src.join(format!("{name}o"))) {
            return Err(Failure::NotCoq(format!(
                "it reported {name} compiled but wrote no {name}o"
            )));
        }
        check.files += 1;
    }
    // 4. The theorems.
    let module_of = |file: &str| format!("Truecost.{}", file.trim_end_matches(".v"));
    let module_name = |name: &str| name.rsplit_once('.').map_or("", |(m, _)| m).to_string();
    let uncompiled = |name: &str| {
        let module = module_name(name);
        sources
            .iter()
            .position(|(f, _)| module_of(f) == module)
            .filter(|&i| i >= check.files)
            .map(|i| sources[i].0)
    };
    let asked: Vec<&str> = theorems
        .iter()
        .copied()
        .filter(|t| uncompiled(t).is_none())
        .collect();
    let require = |names: &[&str]| {
        let mut modules: Vec<String> = names.iter().map(|t| module_name(t)).collect();
        modules.sort();
        modules.dedup();
        modules.retain(|m| !m.is_empty());
        if modules.is_empty() {
            String::new()
        } else {
            format!("Require {}.\n", modules.join(" "))
        }
    };
    write(
        ask.join("Batch.v"),
        &format!("{CHECK_PREAMBLE}{}{}", require(&asked), ask_text(&asked, 0)),
    )?;
    // On a failure (a missing theorem), the answers printed before it are kept.
    let out = run(&ask, "Batch.v", "asking about the theorems")?;
    let mut batch_answers = (0..asked.len()).map(|k| answer(&out.stdout, k));
    for (k, name) in theorems.iter().enumerate() {
        let (statement, assumptions) = if let Some(file) = uncompiled(name) {
            (
                None,
                Assumptions::Missing(format!("{file} was not compiled: an earlier file failed")),
            )
        } else if let Some(a) = batch_answers.next().flatten() {
            a
        } else {
            let file = format!("Ask{k}.v");
            write(
                ask.join(&file),
                &format!(
                    "{CHECK_PREAMBLE}{}{}",
                    require(&[name]),
                    ask_text(&[name], 0)
                ),
            )?;
            let out = run(&ask, &file, &format!("asking about {name}"))?;
            match answer(&out.stdout, 0) {
                Some(a) if out.success => a,
                _ if !out.success => (None, Assumptions::Missing(out.message())),
                _ => (
                    None,
                    Assumptions::Forbidden(vec![format!(
                        "unreadable output: {:?}",
                        out.stdout.lines().next().unwrap_or("")
                    )]),
                ),
            }
        };
        let pin = settings.pins.iter().find(|p| p.name == *name);
        check.theorems.push(TheoremCheck {
            name: name.to_string(),
            refused: judge(pin, statement.as_deref(), &assumptions),
            assumptions,
            statement,
        });
    }
    Ok(failed)
}

fn nonempty(path: &Path) -> bool {
    std::fs::metadata(path).is_ok_and(|m| m.is_file() && m.len() > 0)
}

/// Running `coqc` under a time limit, in its own process group, and what SIGINT and SIGTERM
/// do meanwhile; the temporary directory removed on every way out.
pub mod process {
    use std::ffi::OsStr;
    use std::fs::File;
    use std::path::{Path, PathBuf};
    use std::process::{Command, Stdio};
    use std::sync::atomic::{AtomicI32, Ordering};
    use std::sync::Mutex;
    use std::time::{Duration, Instant};

    /// A fresh directory under the system's temporary directory, removed when dropped
    /// (also while a panic unwinds).
    pub struct TempDir(PathBuf);

    impl TempDir {
        /// Creates `truecost-coq-<pid>-<nanos>-<count>`.
        pub fn new() -> Result<TempDir, String> {
            use std::sync::atomic::AtomicU64;
            static COUNT: AtomicU64 = AtomicU64::new(0);
            let nanos = std::time::SystemTime::now()
                .duration_since(std::time::UNIX_EPOCH)
                .map_or(0, |d| d.as_nanos());
            let dir = std::env::temp_dir().join(format!(
                "truecost-coq-{}-{nanos}-{}",
                std::process::id(),
                COUNT.fetch_add(1, Ordering::Relaxed)
            ));
            // Only the directory itself: a temporary directory (TMPDIR) that does not exist is
            // an error, never created.
            std::fs::create_dir(&dir)
                .map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
            Ok(TempDir(dir))
        }

        /// The directory.
        pub fn path(&self) -> &Path {
            &self.0
        }
    }

    impl Drop for TempDir {
        fn drop(&mut self) {
            let _ = std::fs::remove_dir_all(&self.0);
        }
    }

    /// Why a `coqc` call did not run to its end.
    #[derive(Debug)]
    pub enum Stop {
        /// The re-check's time limit (seconds) passed: the process group was killed.
        TimedOut(u64),
        /// SIGINT or SIGTERM (the number) arrived: the process group was killed.
        Interrupted(i32),
        /// It could not be started.
        Spawn(std::io::Error),
    }

    /// What one `coqc` call printed (escaped) and whether it succeeded.
    pub struct Ran {
        /// Exit status 0.
        pub success: bool,
        /// Standard output.
        pub stdout: String,
        /// Standard error.
        pub stderr: String,
    }

    impl Ran {
        /// Standard output and error on one line (for a failure's message).
        pub fn message(&self) -> String {
            format!("{}\n{}", self.stdout, self.stderr)
                .split_whitespace()
                .collect::<Vec<_>>()
                .join(" ")
        }
    }

    /// The `coqc` program of one re-check: its deadline and its directory.
    pub struct Coqc {
        program: std::ffi::OsString,
        deadline: Instant,
        limit: u64,
        dir: PathBuf,
    }

    impl Coqc {
        /// `program`, stopped `timeout` from now, its output kept under `dir`.
        pub fn new(program: &OsStr, timeout: Duration, dir: &Path) -> Coqc {
            Coqc {
                program: program.to_owned(),
                deadline: Instant::now() + timeout,
                limit: timeout.as_secs(),
                dir: dir.to_path_buf(),
            }
        }

        /// The re-check's directory.
        pub fn dir(&self) -> &Path {
            &self.dir
        }

        /// Runs `coqc args` in `cwd` in a process group of its own, its output in files (no
        /// pipe to fill), polling for its end, the deadline, and SIGINT/SIGTERM; killed with
        /// its group on either of the latter.
        pub fn run(&self, args: &[&OsStr], cwd: &Path) -> Result<Ran, Stop> {
            let out_path = self.dir.join("coqc.stdout");
            let err_path = self.dir.join("coqc.stderr");
            let out = File::create(&out_path).map_err(Stop::Spawn)?;
            let err = File::create(&err_path).map_err(Stop::Spawn)?;
            let mut command = Command::new(&self.program);
            command
                .args(args)
                .current_dir(cwd)
                .stdin(Stdio::null())
                .stdout(out)
                .stderr(err);
            #[cfg(unix)]
            {
                use std::os::unix::process::CommandExt;
                command.process_group(0);
            }
            let mut child = command.spawn().map_err(Stop::Spawn)?;
            let stop = loop {
                match child.try_wait() {
                    Ok(Some(status)) => {
                        let read = |p: &Path| {
                            super::escape_output(&String::from_utf8_lossy(
                                &std::fs::read(p).unwrap_or_default(),
                            ))
                        };
                        return Ok(Ran {
                            success: status.success(),
                            stdout: read(&out_path),
                            stderr: read(&err_path),
                        });
                    }
                    Ok(None) => {}
                    Err(e) => break Stop::Spawn(e),
                }
                if let Some(sig) = Signals::received() {
                    break Stop::Interrupted(sig);
                }
                if Instant::now() >= self.deadline {
                    break Stop::TimedOut(self.limit);
                }
                std::thread::sleep(Duration::from_millis(20));
            };
            kill_group(&mut child);
            Err(stop)
        }
    }

    #[cfg(unix)]
    mod sys {
        use std::ffi::c_int;
        extern "C" {
            pub fn signal(signum: c_int, handler: usize) -> usize;
            pub fn kill(pid: c_int, sig: c_int) -> c_int;
            pub fn raise(sig: c_int) -> c_int;
        }
        pub const SIGINT: c_int = 2;
        pub const SIGKILL: c_int = 9;
        pub const SIGTERM: c_int = 15;
        /// `SIG_DFL`.
        pub const DEFAULT: usize = 0;
    }

    /// Kills `child` and its process group, and reaps it.
    fn kill_group(child: &mut std::process::Child) {
        #[cfg(unix)]
        if let Ok(pid) = i32::try_from(child.id()) {
            // SAFETY: kill(2) on the process group this child leads (`process_group(0)`).
            unsafe {
                sys::kill(-pid, sys::SIGKILL);
            }
        }
        let _ = child.kill();
        let _ = child.wait();
    }

    static RECEIVED: AtomicI32 = AtomicI32::new(0);
    /// How many re-checks hold the handlers, and the handlers they replaced.
    static INSTALLED: Mutex<(usize, [usize; 2])> = Mutex::new((0, [0; 2]));

    #[cfg(unix)]
    extern "C" fn record(sig: std::ffi::c_int) {
        RECEIVED.store(sig, Ordering::SeqCst);
    }

    /// SIGINT and SIGTERM recorded instead of ending the process, while a re-check runs
    /// (the `coqc` call polling for them kills its group; the re-check then removes its
    /// directory and ends the process by the same signal, [`reraise`]). Dropped by the last
    /// re-check, the previous handlers are back.
    pub struct Signals(());

    impl Signals {
        /// Installs the recording handler (once for concurrent re-checks).
        pub fn install() -> Signals {
            let mut installed = INSTALLED.lock().unwrap_or_else(|e| e.into_inner());
            if installed.0 == 0 {
                #[cfg(unix)]
                // SAFETY: `record` only stores to an atomic, which is async-signal-safe.
                unsafe {
                    let handler = record as extern "C" fn(std::ffi::c_int) as usize;
                    installed.1 = [
                        sys::signal(sys::SIGINT, handler),
                        sys::signal(sys::SIGTERM, handler),
                    ];
                }
            }
            installed.0 += 1;
            Signals(())
        }

        /// The signal received while the handlers were installed, if any.
        pub fn received() -> Option<i32> {
            match RECEIVED.load(Ordering::SeqCst) {
                0 => None,
                sig => Some(sig),
            }
        }
    }

    impl Drop for Signals {
        fn drop(&mut self) {
            let mut installed = INSTALLED.lock().unwrap_or_else(|e| e.into_inner());
            installed.0 -= 1;
            if installed.0 == 0 {
                #[cfg(unix)]
                // SAFETY: puts back the handlers `install` replaced.
                unsafe {
                    sys::signal(sys::SIGINT, installed.1[0]);
                    sys::signal(sys::SIGTERM, installed.1[1]);
                }
            }
        }
    }

    /// Ends the process by `sig` with its default action (after the re-check cleaned up), as
    /// if the handler had never been installed; exit status `128 + sig` if that returns.
    pub fn reraise(sig: i32) -> ! {
        #[cfg(unix)]
        // SAFETY: resets the disposition of a signal to the default and raises it.
        unsafe {
            sys::signal(sig, sys::DEFAULT);
            sys::raise(sig);
        }
        std::process::exit(128 + sig)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Coq 8.16.1's own output, as printed for a theorem proved with `lra` over `Reals`.
    const REALS: &str = "Axioms:
ClassicalDedekindReals.sig_forall_dec
  : forall P : nat -> Prop,
    (forall n : nat, {P n} + {~ P n}) ->
    {n : nat | ~ P n} + {forall n : nat, P n}
FunctionalExtensionality.functional_extensionality_dep
  : forall (A : Type) (B : A -> Type) (f g : forall x : A, B x),
    (forall x : A, f x = g x) -> f = g
";

    #[test]
    fn closed_output_is_clean() {
        assert_eq!(
            parse_assumptions("Closed under the global context\n"),
            Assumptions::Closed
        );
    }

    #[test]
    fn the_reals_axioms_are_allowed_and_named() {
        assert_eq!(
            parse_assumptions(REALS),
            Assumptions::Allowed(vec![
                "ClassicalDedekindReals.sig_forall_dec".into(),
                "FunctionalExtensionality.functional_extensionality_dep".into(),
            ])
        );
        let with_not_dec = format!(
            "Axioms:\nClassicalDedekindReals.sig_not_dec : forall P : Prop, {{~ ~ P}} + {{~ P}}\n{}",
            &REALS["Axioms:\n".len()..]
        );
        match parse_assumptions(&with_not_dec) {
            Assumptions::Allowed(a) => assert_eq!(a.len(), 3, "{a:?}"),
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn any_other_axiom_is_forbidden_even_beside_allowed_ones() {
        let out = format!("{REALS}foo : False\n");
        assert_eq!(
            parse_assumptions(&out),
            Assumptions::Forbidden(vec!["foo (Axioms)".into()])
        );
        // An admitted lemma is printed as an axiom of its own statement.
        assert!(!parse_assumptions("Axioms:\nad : 2 = 3\n").accepted());
        // A name that merely ends like an allowed one is not it.
        assert!(
            !parse_assumptions("Axioms:\nMy.ClassicalDedekindReals.sig_not_dec : True\n")
                .accepted()
        );
    }

    /// Section variables (Coq 8.16 prints the name and, on the next line, `: type`), and the
    /// other blocks, are forbidden; so is output that is neither format.
    #[test]
    fn section_variables_and_unknown_output_are_forbidden() {
        assert_eq!(
            parse_assumptions("Section Variables:\nv\n: nat\n"),
            Assumptions::Forbidden(vec!["v (Section Variables)".into()])
        );
        assert!(!parse_assumptions("Constants relying on type-in-type:\nbad\n").accepted());
        assert!(!parse_assumptions("").accepted());
        assert!(!parse_assumptions("Welcome\n").accepted());
    }

    #[test]
    fn the_scan_ignores_comments_strings_and_longer_identifiers() {
        let text = "(* Axiom (* nested Admitted *) still comment: admit *)\n\
Definition s := \"Parameter \"\" Axiom\".\n\
Lemma admit_free : True. Proof. exact I. Qed.\n\
Definition Axiomatic := 1.";
        assert!(scan_sources(&[("A.v", text)]).is_empty());
        let bad = "Lemma x : True.\n(* fine *) Parameter p : nat.\nAxiom a : False.\nConjecture c : False.";
        assert_eq!(
            scan_sources(&[("B.v", bad)]),
            ["B.v:2: Parameter", "B.v:3: Axiom", "B.v:4: Conjecture"]
        );
    }

    /// Each theorem's label follows its pinned Coq statement: "every finite problem" exactly
    /// for the statements that quantify over every problem of the model (`P : Model.problem`)
    /// or, for C2, over every type of policies (`Pi : Type`); the worked example's and the
    /// counterexamples' statements name one fixed problem.
    #[test]
    fn each_label_follows_the_quantifier_of_the_pinned_statement() {
        let pins = pins().unwrap();
        for t in THEOREMS {
            let pin = pins.iter().find(|p| p.name == t.name).expect(t.name);
            let st = &pin.statement;
            let general = st.contains("P : Model.problem") || st.contains("(Pi : Type)");
            assert_eq!(
                general,
                t.scope == Quantifier::EveryFiniteProblem,
                "{}: {st}",
                t.name
            );
            assert_eq!(
                t.kind == Kind::Refutes,
                t.scope == Quantifier::Counterexample
            );
        }
        // The worked example's statements name it, or its quartic and bracket.
        for t in THEOREMS
            .iter()
            .filter(|t| t.scope == Quantifier::PaperExample)
        {
            let st = &pins.iter().find(|p| p.name == t.name).unwrap().statement;
            assert!(
                ["C3Example.ex3", "C3Example.quartic", "C3Example.alpha_lo"]
                    .iter()
                    .any(|w| st.contains(w)),
                "{st}"
            );
        }
    }

    /// Check's output: the type after the name's line, whatever the line breaks; anything
    /// else (an error, Print Assumptions' output) is no statement.
    #[test]
    fn check_output_is_read_as_its_type() {
        assert_eq!(
            parse_check("C3.x\n     : forall a : R,\n       a = a\n").as_deref(),
            Some("forall a : R, a = a")
        );
        assert_eq!(parse_check("Error: The reference x was not found\n"), None);
        assert_eq!(parse_check("Axioms:\nfoo : False\n"), None);
        assert_eq!(parse_check("     : True\n"), None);
    }

    /// The embedded sources are the files `_CoqProject` lists, in its order, and the table's
    /// files are among them.
    #[test]
    fn the_embedded_sources_follow_the_coq_project() {
        let listed = project_files(COQ_PROJECT);
        let embedded: Vec<&str> = SOURCES.iter().map(|(n, _)| *n).collect();
        assert_eq!(embedded, listed);
        for t in THEOREMS {
            let file = t
                .file
                .strip_prefix("proofs/coq/")
                .expect("under proofs/coq");
            assert!(embedded.contains(&file), "{}", t.file);
            let module = t.name.rsplit_once('.').unwrap().0;
            assert_eq!(format!("Truecost.{}", file.trim_end_matches(".v")), module);
        }
    }
}
