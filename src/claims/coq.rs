//! Engine 5: the Coq development in `proofs/coq/` — theorems about **every** finite planning
//! problem (SPEC §6; `docs/proofs/`), re-checked by `coqc` on the machine that runs `verify`.
//!
//! The development's sources are embedded in the binary ([`SOURCES`], in `_CoqProject`
//! order), so that what is re-checked is what this build was made from. [`recheck`] refuses
//! sources that admit anything ([`scan_sources`]: `Admitted`, `admit`, `Axiom`, `Parameter`, …
//! outside comments), writes them to a fresh directory, compiles each with
//! `coqc -R <dir> Truecost`, and runs `Print Assumptions` on every theorem of [`THEOREMS`]. A
//! theorem is accepted when Coq answers "Closed under the global context", or lists only the
//! standard library's axioms of the real numbers ([`ALLOWED_AXIOMS`]); any other axiom,
//! parameter, section variable, or a missing theorem is refused ([`parse_assumptions`]).
//!
//! Nothing is claimed for a check that did not run: without `coqc` on `PATH` the outcome is
//! [`Outcome::NotAvailable`], and `verify` says the proof was not re-checked on this machine.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

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
    },
    Theorem {
        claim: "C1-corrected",
        kind: Kind::Proves,
        name: "Truecost.C1.c1_corrected_from_above",
        file: "proofs/coq/C1.v",
        statement: "Part A: Q0 >= Q* on every pair and Q0(xg,uT) = 0: after any number >= R1 = 1 + max h(f(x,u)) of \
rounds, Q = Q*",
        weaker: Some(RATIONALS),
    },
    Theorem {
        claim: "C1-corrected",
        kind: Kind::Proves,
        name: "Truecost.C1.c1_corrected_from_below",
        file: "proofs/coq/C1.v",
        statement: "Part B: every move costs >= c > 0, m <= Q0 and Q* <= qm on every move pair, Q0(xg,uT) = 0: after \
any number r >= R1 of rounds with qm - m <= r c, Q = Q*",
        weaker: Some(RATIONALS),
    },
    Theorem {
        claim: "C1-corrected",
        kind: Kind::Proves,
        name: "Truecost.C1.c1_paper_form",
        file: "proofs/coq/C1.v",
        statement: "the paper's form: under (H0)-(H2), for every infinite update sequence in which every move pair \
occurs infinitely often, there is N such that Q = Q* after every k >= N updates",
        weaker: Some(RATIONALS),
    },
    Theorem {
        claim: "C2",
        kind: Kind::Proves,
        name: "Truecost.C2.c2_cost_reward_equivalence",
        file: "proofs/coq/C2.v",
        statement: "for any type of policies, any admissible set and any odd cost functional F (F(-s) = -F(s) on a \
domain closed under negation; partial functionals allowed): pi minimises F(l) iff it maximises F(-l)",
        weaker: None,
    },
    Theorem {
        claim: "C2",
        kind: Kind::Proves,
        name: "Truecost.C2.c2_linear",
        file: "proofs/coq/C2.v",
        statement: "every linear (and extensional) cost functional is odd: C2 for every linear functional",
        weaker: None,
    },
    Theorem {
        claim: "C2",
        kind: Kind::Proves,
        name: "Truecost.C2.c2_total",
        file: "proofs/coq/C2.v",
        statement: "the total cost (the series of stage costs, where it converges): minimiser iff maximiser of the \
total reward",
        weaker: None,
    },
    Theorem {
        claim: "C2",
        kind: Kind::Proves,
        name: "Truecost.C2.c2_discounted",
        file: "proofs/coq/C2.v",
        statement: "the discounted cost, for every discount factor alpha: minimiser iff maximiser of the \
discounted reward",
        weaker: None,
    },
    Theorem {
        claim: "C2",
        kind: Kind::Proves,
        name: "Truecost.C2.c2_average",
        file: "proofs/coq/C2.v",
        statement: "the long-run average cost (the limit of the means, where it exists): minimiser iff maximiser \
of the average reward",
        weaker: None,
    },
    Theorem {
        claim: "C2",
        kind: Kind::Proves,
        name: "Truecost.C2.c2_horizon_total",
        file: "proofs/coq/C2.v",
        statement: "the K-stage total cost, for every horizon K",
        weaker: None,
    },
    Theorem {
        claim: "C2",
        kind: Kind::Proves,
        name: "Truecost.C2.c2_horizon_discounted",
        file: "proofs/coq/C2.v",
        statement: "the K-stage discounted cost, for every horizon K and discount factor",
        weaker: None,
    },
    Theorem {
        claim: "C2",
        kind: Kind::Proves,
        name: "Truecost.C2.c2_horizon_average",
        file: "proofs/coq/C2.v",
        statement: "the K-stage average cost, for every horizon K",
        weaker: None,
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
    },
    Theorem {
        claim: "C3-example",
        kind: Kind::Proves,
        name: "Truecost.C3.c3_printed_iff_quartic",
        file: "proofs/coq/C3.v",
        statement: "for every real alpha in (0,1), the printed inequality holds iff 5a^4 - a^3 - a^2 - a - 1 < 0",
        weaker: None,
    },
    Theorem {
        claim: "C3-example",
        kind: Kind::Proves,
        name: "Truecost.C3.c3_alpha_star",
        file: "proofs/coq/C3.v",
        statement: "the quartic has exactly one root alpha* in (0,1), negative below it and positive above it, and alpha* \
lies strictly between two rationals 2^-100 apart (more than 30 digits)",
        weaker: None,
    },
    Theorem {
        claim: "C4",
        kind: Kind::Refutes,
        name: "Truecost.C4.c4_as_printed_refuted",
        file: "proofs/coq/C4.v",
        statement: "on the counterexample verify prints (0 -> 1 cost 0, 0 -> goal cost 1, 1 -> goal cost 0; x1 = 0) \
and for every bonus M in [-3, -1/3): the printed interval excludes M, yet pi* is average-cost optimal against every run",
        weaker: None,
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
    },
    Theorem {
        claim: "C4-corrected",
        kind: Kind::Proves,
        name: "Truecost.C4.pistar_exists",
        file: "proofs/coq/C4.v",
        statement: "whenever the goal is reachable from x1, an optimal single-shot path pi* exists and is simple, so \
c4_corrected applies to every such problem",
        weaker: None,
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
    },
    Theorem {
        claim: "C4",
        kind: Kind::Refutes,
        name: "Truecost.C4.c4_as_printed_refuted_positive_costs",
        file: "proofs/coq/C4.v",
        statement: "on 0 -> 1 cost 1, 1 -> goal cost 1, 0 -> goal cost 3 (x1 = 0; every move cost positive) and for \
every bonus M in [-5, -5/27): the printed interval excludes M, yet pi* is average-cost optimal against every run",
        weaker: None,
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

/// How a re-check ended.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Outcome {
    /// Every file compiled and every theorem's assumptions were printed (see
    /// [`Check::theorems`]).
    Checked,
    /// `coqc` could not be run (the reason): nothing was re-checked.
    NotAvailable(String),
    /// The sources use a forbidden word ([`scan_sources`]): not compiled.
    SourcesRefused(Vec<String>),
    /// A file did not compile (the file and Coq's message). The files before it compiled,
    /// and the theorems of those files were still asked about ([`Check::theorems`]).
    BuildFailed(String),
}

/// One theorem's result.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct TheoremCheck {
    /// The fully qualified name.
    pub name: String,
    /// What `Print Assumptions` said.
    pub assumptions: Assumptions,
}

/// The result of one re-check of the Coq development.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Check {
    /// `coqc`'s version (`8.16.1`), when it ran.
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
    pub fn theorem(&self, name: &str) -> Option<&Assumptions> {
        self.theorems
            .iter()
            .find(|t| t.name == name)
            .map(|t| &t.assumptions)
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
            && self.theorems.iter().all(|t| t.assumptions.accepted())
    }
}

/// The message of [`Outcome::NotAvailable`] when `coqc` is not on `PATH`.
pub const NOT_FOUND: &str = "coqc not found: install Coq (Debian/Ubuntu: apt-get install -y coq; the README's prerequisites)";

/// `coqc --version`'s version number (`8.16.1`), or why `coqc` cannot be run.
pub fn coqc_version() -> Result<String, String> {
    let out = Command::new("coqc")
        .arg("--version")
        .output()
        .map_err(|e| {
            if e.kind() == std::io::ErrorKind::NotFound {
                NOT_FOUND.to_string()
            } else {
                format!("coqc cannot be run: {e}")
            }
        })?;
    let text = String::from_utf8_lossy(&out.stdout);
    let first = text.lines().next().unwrap_or("");
    match first.split("version ").nth(1) {
        Some(v) if out.status.success() => Ok(v.trim().to_string()),
        _ => Err(format!("coqc --version printed {first:?}")),
    }
}

/// Re-checks the embedded development ([`SOURCES`]) against [`THEOREMS`] with the `coqc` on
/// `PATH` (see [`recheck_sources`]).
pub fn recheck() -> Check {
    let names: Vec<&str> = THEOREMS.iter().map(|t| t.name).collect();
    recheck_sources(SOURCES, &names)
}

/// A fresh, empty directory under the system's temporary directory.
fn fresh_dir() -> Result<PathBuf, String> {
    use std::sync::atomic::{AtomicU64, Ordering};
    static COUNT: AtomicU64 = AtomicU64::new(0);
    let nanos = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_nanos());
    let dir = std::env::temp_dir().join(format!(
        "truecost-coq-{}-{nanos}-{}",
        std::process::id(),
        COUNT.fetch_add(1, Ordering::Relaxed)
    ));
    std::fs::create_dir_all(&dir).map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
    Ok(dir)
}

/// Runs `coqc -R <src> Truecost <file>` in `cwd`: whether it succeeded, its stdout as
/// printed, and the failure's message (stdout and stderr on one line; empty on success).
fn coqc_run(src: &Path, cwd: &Path, file: &str) -> (bool, String, String) {
    let out = match Command::new("coqc")
        .arg("-R")
        .arg(src)
        .arg("Truecost")
        .arg(file)
        .current_dir(cwd)
        .output()
    {
        Ok(out) => out,
        Err(e) => return (false, String::new(), format!("coqc cannot be run: {e}")),
    };
    let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
    if out.status.success() {
        return (true, stdout, String::new());
    }
    let stderr = String::from_utf8_lossy(&out.stderr);
    // One line: the message goes into the report's notes.
    let message = format!("{stdout}\n{stderr}")
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ");
    (false, stdout, message)
}

/// [`coqc_run`]: stdout, or the failure's message.
fn coqc(src: &Path, cwd: &Path, file: &str) -> Result<String, String> {
    match coqc_run(src, cwd, file) {
        (true, stdout, _) => Ok(stdout),
        (false, _, message) => Err(message),
    }
}

/// Re-checks a development: refuses it if [`scan_sources`] finds anything; otherwise writes
/// `sources` (in order) to a fresh directory, compiles each with `coqc -R <dir> Truecost`,
/// then runs `Print Assumptions` on each of `theorems` (fully qualified names, `Truecost.` +
/// module path + name) — all in one coqtop process, a theorem it could not answer again in a
/// file of its own — and classifies the output
/// ([`parse_assumptions`]); a theorem Coq cannot find is [`Assumptions::Missing`]. The
/// directory is removed afterwards.
pub fn recheck_sources(sources: &[(&str, &str)], theorems: &[&str]) -> Check {
    let started = Instant::now();
    let mut check = Check {
        version: None,
        outcome: Outcome::Checked,
        theorems: Vec::new(),
        files: 0,
        seconds: 0.0,
    };
    let finish = |mut c: Check| {
        c.seconds = started.elapsed().as_secs_f64();
        c
    };
    let refused = scan_sources(sources);
    if !refused.is_empty() {
        check.outcome = Outcome::SourcesRefused(refused);
        return finish(check);
    }
    match coqc_version() {
        Ok(v) => check.version = Some(v),
        Err(why) => {
            check.outcome = Outcome::NotAvailable(why);
            return finish(check);
        }
    }
    if sources.is_empty() {
        check.outcome = Outcome::BuildFailed("no source files".into());
        return finish(check);
    }
    let base = match fresh_dir() {
        Ok(d) => d,
        Err(why) => {
            check.outcome = Outcome::BuildFailed(why);
            return finish(check);
        }
    };
    let result = compile_and_ask(&base, sources, theorems, &mut check);
    let _ = std::fs::remove_dir_all(&base);
    if let Err(why) = result {
        check.outcome = Outcome::BuildFailed(why);
    }
    finish(check)
}

fn compile_and_ask(
    base: &Path,
    sources: &[(&str, &str)],
    theorems: &[&str],
    check: &mut Check,
) -> Result<(), String> {
    let src = base.join("src");
    let ask = base.join("ask");
    for d in [&src, &ask] {
        std::fs::create_dir_all(d).map_err(|e| format!("cannot create {}: {e}", d.display()))?;
    }
    for (name, text) in sources {
        if name.contains('/') || name.contains('\\') || !name.ends_with(".v") {
            return Err(format!("{name}: not a plain .v file name"));
        }
        let path = src.join(name);
        std::fs::write(&path, text).map_err(|e| format!("cannot write {}: {e}", path.display()))?;
    }
    // Each file depends only on the files before it (`_CoqProject` order): the files compiled
    // before a failure are sound, and their theorems are still asked about.
    let mut failed = None;
    for (name, _) in sources {
        if let Err(e) = coqc(&src, &src, name) {
            failed = Some(format!("{name} does not compile: {e}"));
            break;
        }
        check.files += 1;
    }
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
    // One coqtop process asks about every theorem of the compiled files, each answer after a
    // marker; a theorem whose answer is not followed by the next marker (Coq stopped there,
    // e.g. at a missing name) is asked again on its own.
    let asked: Vec<&str> = theorems
        .iter()
        .copied()
        .filter(|t| uncompiled(t).is_none())
        .collect();
    let marker = |k: usize| format!("<<truecost-ask {k}>>");
    let mut batch = String::new();
    let mut modules: Vec<String> = asked.iter().map(|t| module_name(t)).collect();
    modules.sort();
    modules.dedup();
    if !modules.is_empty() {
        batch.push_str(&format!("Require {}.\n", modules.join(" ")));
    }
    for (k, name) in asked.iter().enumerate() {
        batch.push_str(&format!(
            "Goal True. idtac \"{}\". Abort.\nPrint Assumptions {name}.\n",
            marker(k)
        ));
    }
    batch.push_str(&format!(
        "Goal True. idtac \"{}\". Abort.\n",
        marker(asked.len())
    ));
    let write = |file: &str, text: &str| {
        std::fs::write(ask.join(file), text)
            .map_err(|e| format!("cannot write {}: {e}", ask.join(file).display()))
    };
    write("Batch.v", &batch)?;
    // On a failure, the answers printed before it are kept.
    let (_, out, _) = coqc_run(&src, &ask, "Batch.v");
    let answer = |k: usize| {
        let from = out.find(&marker(k))? + marker(k).len();
        let to = out[from..].find(&marker(k + 1))? + from;
        Some(parse_assumptions(&out[from..to]))
    };
    let mut batch_answers = asked.iter().enumerate().map(|(k, _)| answer(k));
    for (k, name) in theorems.iter().enumerate() {
        let assumptions = if let Some(file) = uncompiled(name) {
            Assumptions::Missing(format!("{file} was not compiled: an earlier file failed"))
        } else if let Some(a) = batch_answers.next().flatten() {
            a
        } else {
            let file = format!("Ask{k}.v");
            let module = module_name(name);
            write(
                &file,
                &format!("Require {module}.\nPrint Assumptions {name}.\n"),
            )?;
            match coqc(&src, &ask, &file) {
                Ok(out) => parse_assumptions(&out),
                Err(why) => Assumptions::Missing(why),
            }
        };
        check.theorems.push(TheoremCheck {
            name: name.to_string(),
            assumptions,
        });
    }
    match failed {
        Some(why) => Err(why),
        None => Ok(()),
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
