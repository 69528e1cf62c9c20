//! Engine 4: SMT proofs over the reals (`docs/proofs/`, `docs/guide/verify.md`).
//!
//! A claim is *proved* by proof obligations whose **unsatisfiability** is the proof: each
//! obligation states the hypotheses and the negated conclusion over real (or integer) unknowns —
//! costs, initial values, the bonus `M`, the discount `α` — for one structure or for one local
//! lemma that holds on every graph of a given out-degree. Each obligation is written as
//! standard SMT-LIB 2.6 text ([`Obligation::smtlib`]); Z3 (through the `z3` crate, the system
//! libz3) parses and solves exactly that text, and `verify --smt-out DIR` writes it, so that
//! cvc5 or Yices can re-check every file without trusting truecost.
//!
//! Trust checks (PROOFS.md) are obligations too, with the opposite expectation: the
//! hypotheses alone are satisfiable (no vacuous proof), and the encoding with one hypothesis
//! dropped, or with the printed statement, is satisfiable (it finds the known failure). A
//! `sat` answer's model is read back as exact rationals ([`Model`]) for the claim to replay
//! through its exact oracle before anything is reported. `unknown` or a timeout is
//! [`Answer::Unknown`]: never a proof.
//!
//! The claims' encodings live beside their oracles' modules: [`c1`] (C1, C1-corrected), [`c2`],
//! [`c3`] (C3, C3-example), [`c4`] (C4, C4-corrected); their arguments are in `docs/proofs/`.

pub mod c1;
pub mod c2;
pub mod c3;
pub mod c4;
pub mod term;

use std::fmt::Write as _;
use std::path::Path;
use std::str::FromStr;
use std::time::Instant;

use num_bigint::BigInt;
use rayon::prelude::*;
use serde::Serialize;

use crate::value::Rational;

/// The SMT-LIB logic an obligation is stated in.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum Logic {
    /// Quantifier-free linear real arithmetic.
    QfLra,
    /// Quantifier-free linear arithmetic over integers and reals.
    QfLira,
    /// Quantifier-free nonlinear real arithmetic (polynomials in `α`).
    QfNra,
    /// Quantifier-free nonlinear arithmetic over integers and reals (a round count, an
    /// integer, times a cost).
    QfNira,
}

impl Logic {
    /// The SMT-LIB name.
    pub fn name(self) -> &'static str {
        match self {
            Logic::QfLra => "QF_LRA",
            Logic::QfLira => "QF_LIRA",
            Logic::QfNra => "QF_NRA",
            Logic::QfNira => "QF_NIRA",
        }
    }
}

/// The sort of a declared constant.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum Sort {
    /// `Real`.
    Real,
    /// `Int`.
    Int,
    /// `Bool`.
    Bool,
}

impl Sort {
    fn name(self) -> &'static str {
        match self {
            Sort::Real => "Real",
            Sort::Int => "Int",
            Sort::Bool => "Bool",
        }
    }
}

/// What an obligation is for, and so which answer it must get.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Role {
    /// Hypotheses ∧ ¬conclusion: must be `unsat` (this is the proof).
    Proof,
    /// The hypotheses alone: must be `sat` (the proof is not vacuous).
    Hypotheses,
    /// The proof obligation with the named hypothesis dropped: must be `sat` (the hypothesis is
    /// needed, and the encoding can find a failure).
    Dropped(String),
    /// The statement as printed (or a planted wrong threshold): must be `sat`, and the model
    /// must replay as a counterexample through the exact oracle.
    Printed,
}

impl Role {
    /// The answer this role requires.
    pub fn expected(&self) -> Status {
        match self {
            Role::Proof => Status::Unsat,
            _ => Status::Sat,
        }
    }

    /// A short name for indexes and reports.
    pub fn name(&self) -> String {
        match self {
            Role::Proof => "proof".into(),
            Role::Hypotheses => "hypotheses satisfiable".into(),
            Role::Dropped(h) => format!("without {h}"),
            Role::Printed => "as printed".into(),
        }
    }
}

/// `sat` or `unsat`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Status {
    /// Satisfiable.
    Sat,
    /// Unsatisfiable.
    Unsat,
}

impl Status {
    /// `sat` / `unsat`.
    pub fn name(self) -> &'static str {
        match self {
            Status::Sat => "sat",
            Status::Unsat => "unsat",
        }
    }
}

/// One proof obligation (or trust check): declarations and assertions in SMT-LIB 2.6.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Obligation {
    /// The claim (`C1-corrected`, `C4`, …).
    pub claim: String,
    /// The lemma or family (`A1 preserve Q >= Q*`, `interval = oracle`, …).
    pub lemma: String,
    /// The structure or local shape it is about (`successor with 3 pairs`, a tiny problem's
    /// description, …).
    pub structure: String,
    /// What it is for.
    pub role: Role,
    /// Its logic.
    pub logic: Logic,
    /// Declared constants.
    pub decls: Vec<(String, Sort)>,
    /// Assertions (SMT-LIB terms of sort Bool).
    pub asserts: Vec<String>,
}

impl Obligation {
    /// A new obligation with no declarations yet.
    pub fn new(claim: &str, lemma: &str, structure: &str, role: Role, logic: Logic) -> Self {
        Obligation {
            claim: claim.into(),
            lemma: lemma.into(),
            structure: structure.into(),
            role,
            logic,
            decls: Vec::new(),
            asserts: Vec::new(),
        }
    }

    /// Declares a constant and returns its name.
    pub fn declare(&mut self, name: &str, sort: Sort) -> String {
        debug_assert!(
            !self.decls.iter().any(|(n, _)| n == name),
            "{name} declared twice"
        );
        self.decls.push((name.to_string(), sort));
        name.to_string()
    }

    /// Adds an assertion.
    pub fn assert(&mut self, term: String) {
        self.asserts.push(term);
    }

    /// The same obligation with another role (and so another expected answer), keeping every
    /// assertion; callers add or remove assertions to make a trust check.
    pub fn with_role(&self, role: Role) -> Self {
        let mut o = self.clone();
        o.role = role;
        o
    }

    /// The obligation as a standard SMT-LIB 2.6 script: `set-logic`, `set-info :status` (when
    /// known), declarations, assertions, `check-sat`, `exit`.
    ///
    /// ```
    /// use truecost::claims::smt::{Logic, Obligation, Role, Sort, Status};
    /// let mut o = Obligation::new("demo", "x < x", "none", Role::Proof, Logic::QfLra);
    /// let x = o.declare("x", Sort::Real);
    /// o.assert(format!("(< {x} {x})"));
    /// let text = o.smtlib(Some(Status::Unsat));
    /// assert!(text.starts_with("(set-info :smt-lib-version 2.6)\n(set-logic QF_LRA)\n"));
    /// assert!(text.contains("(set-info :status unsat)"));
    /// assert!(text.contains("(declare-const x Real)"));
    /// ```
    pub fn smtlib(&self, status: Option<Status>) -> String {
        let mut s = String::new();
        let _ = writeln!(s, "(set-info :smt-lib-version 2.6)");
        let _ = writeln!(s, "(set-logic {})", self.logic.name());
        let _ = writeln!(
            s,
            "(set-info :source |truecost {}: {} / {} / {} / {}|)",
            env!("CARGO_PKG_VERSION"),
            self.claim,
            self.lemma.replace('|', "/"),
            self.structure.replace('|', "/"),
            self.role.name()
        );
        if let Some(st) = status {
            let _ = writeln!(s, "(set-info :status {})", st.name());
        }
        for (n, sort) in &self.decls {
            let _ = writeln!(s, "(declare-const {n} {})", sort.name());
        }
        for a in &self.asserts {
            let _ = writeln!(s, "(assert {a})");
        }
        s.push_str("(check-sat)\n(exit)\n");
        s
    }
}

/// Exact values of the declared constants in a satisfying assignment.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Model {
    /// `(name, value)` for every declared real or integer constant; booleans as 0/1.
    pub values: Vec<(String, Rational)>,
}

impl Model {
    /// The value of `name`.
    pub fn get(&self, name: &str) -> Option<&Rational> {
        self.values.iter().find(|(n, _)| n == name).map(|(_, v)| v)
    }
}

/// Z3's answer.
#[derive(Clone, Debug, PartialEq)]
pub enum Answer {
    /// Unsatisfiable.
    Unsat,
    /// Satisfiable, with the model (`None` when a value is not rational, e.g. an algebraic
    /// number of a nonlinear model).
    Sat(Option<Model>),
    /// `unknown`, a timeout, or a parse failure (the reason).
    Unknown(String),
}

impl Answer {
    /// `sat`, `unsat` or `unknown`.
    pub fn name(&self) -> &'static str {
        match self {
            Answer::Unsat => "unsat",
            Answer::Sat(_) => "sat",
            Answer::Unknown(_) => "unknown",
        }
    }

    /// The status, if decided.
    pub fn status(&self) -> Option<Status> {
        match self {
            Answer::Unsat => Some(Status::Unsat),
            Answer::Sat(_) => Some(Status::Sat),
            Answer::Unknown(_) => None,
        }
    }
}

/// The solver's name and version (`Z3 4.8.12`).
pub fn solver_version() -> String {
    format!("Z3 {}", z3::full_version())
}

/// Parses a Z3 numeral as printed: `3`, `3.0`, `(- 3.0)`, `(/ 1.0 3.0)`, `(- (/ 1.0 3.0))`,
/// `true`/`false` (as 1/0). `None` for anything else (e.g. `root-obj`).
///
/// ```
/// use truecost::claims::smt::parse_numeral;
/// use truecost::value::Rational;
/// assert_eq!(parse_numeral("(- (/ 7.0 2.0))"), Some(Rational::new((-7).into(), 2.into())));
/// assert_eq!(parse_numeral("12"), Some(Rational::from_integer(12.into())));
/// assert_eq!(parse_numeral("(root-obj (+ (^ x 2) (- 2)) 1)"), None);
/// ```
pub fn parse_numeral(s: &str) -> Option<Rational> {
    let s = s.trim();
    match s {
        "true" => return Some(Rational::from_integer(1.into())),
        "false" => return Some(Rational::from_integer(0.into())),
        _ => {}
    }
    if let Some(inner) = s.strip_prefix("(- ").and_then(|r| r.strip_suffix(')')) {
        return parse_numeral(inner).map(|v| -v);
    }
    if let Some(inner) = s.strip_prefix("(/ ").and_then(|r| r.strip_suffix(')')) {
        let mut parts = inner.split_whitespace();
        let (a, b) = (parts.next()?, parts.next()?);
        if parts.next().is_some() {
            return None;
        }
        let (a, b) = (parse_numeral(a)?, parse_numeral(b)?);
        if b == Rational::from_integer(0.into()) {
            return None;
        }
        return Some(a / b);
    }
    let (int_part, frac) = match s.split_once('.') {
        Some((i, f)) => (i, f),
        None => (s, ""),
    };
    if int_part.is_empty()
        || !int_part.bytes().all(|b| b.is_ascii_digit())
        || !frac.bytes().all(|b| b.is_ascii_digit())
    {
        return None;
    }
    let digits = format!("{int_part}{frac}");
    let n = BigInt::from_str(&digits).ok()?;
    let d = num_traits::pow(BigInt::from(10), frac.len());
    Some(Rational::new(n, d))
}

/// Solves one obligation with Z3 (the solver of this thread), within `timeout_ms`.
///
/// ```
/// use truecost::claims::smt::{solve, Answer, Logic, Obligation, Role, Sort};
/// use truecost::value::Rational;
/// let r = |n: i64| Rational::from_integer(n.into());
/// let mut o = Obligation::new("demo", "x > 1 and x < 2", "none", Role::Hypotheses, Logic::QfLra);
/// let x = o.declare("x", Sort::Real);
/// o.assert(format!("(and (> {x} 1.0) (< {x} 2.0))"));
/// match solve(&o, 10_000) {
///     Answer::Sat(Some(m)) => {
///         let v = m.get("x").unwrap();
///         assert!(*v > r(1) && *v < r(2));
///     }
///     other => panic!("{other:?}"),
/// }
/// o.assert(format!("(< {x} 0.0)"));
/// assert_eq!(solve(&o, 10_000), Answer::Unsat);
/// ```
pub fn solve(ob: &Obligation, timeout_ms: u32) -> Answer {
    let a = solve_reusing(ob, timeout_ms);
    // A model that is replayed (and may be printed) must not depend on what this thread's
    // Z3 context solved before — the report would then depend on thread scheduling, and a
    // shard would see another model than the whole run: re-solve a
    // satisfiable obligation in a fresh context.
    if matches!(a, Answer::Sat(_)) && ob.role != Role::Hypotheses {
        return z3::with_z3_config(&z3::Config::new(), || {
            let solver = fresh_solver(ob.logic.name(), timeout_ms);
            answer(&solver, ob)
        });
    }
    a
}

thread_local! {
    /// This thread's linear solvers, one per logic and timeout (see [`solve_reusing`]).
    static SOLVERS: std::cell::RefCell<Vec<(Logic, u32, z3::Solver)>> =
        const { std::cell::RefCell::new(Vec::new()) };
}

fn solve_reusing(ob: &Obligation, timeout_ms: u32) -> Answer {
    // Linear obligations reuse one solver per thread and logic (push, assert, check, pop):
    // creating a Z3 solver costs tens of milliseconds, solving a small linear obligation well
    // under one. Nonlinear ones get a fresh solver, so that Z3 chooses its complete nonlinear
    // procedure (nlsat) rather than the incremental one.
    if matches!(ob.logic, Logic::QfNra | Logic::QfNira) {
        let solver = fresh_solver(ob.logic.name(), timeout_ms);
        return answer(&solver, ob);
    }
    SOLVERS.with(|cell| {
        let mut solvers = cell.borrow_mut();
        let k = match solvers
            .iter()
            .position(|(l, t, _)| *l == ob.logic && *t == timeout_ms)
        {
            Some(k) => k,
            None => {
                solvers.push((
                    ob.logic,
                    timeout_ms,
                    fresh_solver(ob.logic.name(), timeout_ms),
                ));
                solvers.len() - 1
            }
        };
        let solver = &solvers[k].2;
        solver.push();
        let a = answer(solver, ob);
        solver.pop(1);
        a
    })
}

fn fresh_solver(logic: &str, timeout_ms: u32) -> z3::Solver {
    let solver = z3::Solver::new_for_logic(logic).unwrap_or_default();
    let mut params = z3::Params::new();
    params.set_u32("timeout", timeout_ms);
    solver.set_params(&params);
    solver
}

/// Asserts the obligation's script (without its `set-logic` line, which the solver already
/// has) in `solver`'s current scope and reads the answer.
fn answer(solver: &z3::Solver, ob: &Obligation) -> Answer {
    let before = solver.get_assertions().len();
    let script: String = ob
        .smtlib(None)
        .lines()
        .filter(|l| !l.starts_with("(set-logic ") && !l.starts_with("(set-info "))
        .map(|l| format!("{l}\n"))
        .collect();
    solver.from_string(script);
    let parsed = solver.get_assertions().len() - before;
    if parsed != ob.asserts.len() {
        return Answer::Unknown(format!(
            "Z3 parsed {parsed} of {} assertions",
            ob.asserts.len()
        ));
    }
    match solver.check() {
        z3::SatResult::Unsat => Answer::Unsat,
        z3::SatResult::Unknown => Answer::Unknown(
            solver
                .get_reason_unknown()
                .unwrap_or_else(|| "unknown".into()),
        ),
        z3::SatResult::Sat => {
            let Some(model) = solver.get_model() else {
                return Answer::Sat(None);
            };
            let mut values = Vec::new();
            for (name, sort) in &ob.decls {
                let text = match sort {
                    Sort::Real => model
                        .eval(&z3::ast::Real::new_const(name.as_str()), true)
                        .map(|v| v.to_string()),
                    Sort::Int => model
                        .eval(&z3::ast::Int::new_const(name.as_str()), true)
                        .map(|v| v.to_string()),
                    Sort::Bool => model
                        .eval(&z3::ast::Bool::new_const(name.as_str()), true)
                        .map(|v| v.to_string()),
                };
                match text.as_deref().and_then(parse_numeral) {
                    Some(v) => values.push((name.clone(), v)),
                    None => return Answer::Sat(None),
                }
            }
            Answer::Sat(Some(Model { values }))
        }
    }
}

/// Re-solves an SMT-LIB script (e.g. a file written by `--smt-out`) with Z3 and returns its
/// status (`None` for `unknown`). The logic is read from its `set-logic` line.
///
/// ```
/// use truecost::claims::smt::{solve_text, Status};
/// let text = "(set-logic QF_LRA)\n(declare-const x Real)\n(assert (< x x))\n(check-sat)\n";
/// assert_eq!(solve_text(text, 10_000), Some(Status::Unsat));
/// ```
pub fn solve_text(text: &str, timeout_ms: u32) -> Option<Status> {
    let logic = text
        .lines()
        .find_map(|l| l.trim().strip_prefix("(set-logic "))
        .and_then(|r| r.strip_suffix(')'));
    let solver = logic
        .and_then(z3::Solver::new_for_logic)
        .unwrap_or_default();
    let mut params = z3::Params::new();
    params.set_u32("timeout", timeout_ms);
    solver.set_params(&params);
    solver.from_string(text);
    match solver.check() {
        z3::SatResult::Unsat => Some(Status::Unsat),
        z3::SatResult::Sat => Some(Status::Sat),
        z3::SatResult::Unknown => None,
    }
}

/// One obligation's result.
#[derive(Clone, Debug, PartialEq)]
pub struct Solved {
    /// The obligation.
    pub obligation: Obligation,
    /// Z3's answer.
    pub answer: Answer,
    /// Wall-clock seconds (never pinned).
    pub seconds: f64,
}

impl Solved {
    /// Whether the answer is the one the role requires. A `Printed` obligation is a search
    /// for a counterexample on one structure: either decided answer is acceptable (the claim
    /// is refuted when at least one is `sat` and replays).
    pub fn as_expected(&self) -> bool {
        match self.obligation.role {
            Role::Printed => self.answer.status().is_some(),
            _ => self.answer.status() == Some(self.obligation.role.expected()),
        }
    }
}

/// Solves every obligation (in parallel; the order of the result is the order given).
pub fn discharge(obligations: Vec<Obligation>, timeout_ms: u32) -> Vec<Solved> {
    obligations
        .into_par_iter()
        .with_min_len(4)
        .map(|o| {
            let start = Instant::now();
            let answer = solve(&o, timeout_ms);
            Solved {
                obligation: o,
                answer,
                seconds: start.elapsed().as_secs_f64(),
            }
        })
        .collect()
}

/// Checks, before any work, that `dir` can receive the obligation files: it is created if
/// missing, and must be an empty directory.
pub fn prepare_out_dir(dir: &Path) -> Result<(), String> {
    if dir.exists() {
        if !dir.is_dir() {
            return Err(format!("--smt-out {}: not a directory", dir.display()));
        }
        let mut entries = std::fs::read_dir(dir)
            .map_err(|e| format!("--smt-out {}: cannot read: {e}", dir.display()))?;
        if entries.next().is_some() {
            return Err(format!(
                "--smt-out {}: the directory is not empty (the index would mix runs)",
                dir.display()
            ));
        }
    }
    std::fs::create_dir_all(dir)
        .map_err(|e| format!("--smt-out {}: cannot create: {e}", dir.display()))
}

/// Writes every solved obligation as an SMT-LIB file under `dir/<claim>/`, with
/// `(set-info :status …)` stating Z3's answer, and appends one line per file to the index
/// `dir/index.tsv` (`file, claim, lemma, structure, role, expected, z3`).
pub fn write_files(dir: &Path, solved: &[Solved]) -> Result<(), String> {
    let index_path = dir.join("index.tsv");
    let mut index = if index_path.exists() {
        std::fs::read_to_string(&index_path)
            .map_err(|e| format!("cannot read {}: {e}", index_path.display()))?
    } else {
        "file\tclaim\tlemma\tstructure\trole\texpected\tz3\n".to_string()
    };
    for (k, s) in solved.iter().enumerate() {
        let o = &s.obligation;
        let sub = o.claim.to_lowercase();
        let folder = dir.join(&sub);
        std::fs::create_dir_all(&folder)
            .map_err(|e| format!("cannot create {}: {e}", folder.display()))?;
        let role = match &o.role {
            Role::Proof => "proof",
            Role::Hypotheses => "hyp",
            Role::Dropped(_) => "dropped",
            Role::Printed => "printed",
        };
        let name = format!("{k:06}-{role}.smt2");
        let path = folder.join(&name);
        std::fs::write(&path, o.smtlib(s.answer.status()))
            .map_err(|e| format!("cannot write {}: {e}", path.display()))?;
        let clean = |t: &str| t.replace(['\t', '\n'], " ");
        let _ = writeln!(
            index,
            "{sub}/{name}\t{}\t{}\t{}\t{}\t{}\t{}",
            clean(&o.claim),
            clean(&o.lemma),
            clean(&o.structure),
            clean(&o.role.name()),
            if o.role == Role::Printed {
                "sat-or-unsat"
            } else {
                o.role.expected().name()
            },
            s.answer.name()
        );
    }
    std::fs::write(&index_path, index)
        .map_err(|e| format!("cannot write {}: {e}", index_path.display()))
}

/// The SMT engine's summary for one claim.
#[derive(Clone, Debug, PartialEq)]
pub struct Summary {
    /// Proof obligations (role `proof`).
    pub proofs: u64,
    /// Proof obligations answered `unsat`.
    pub proofs_unsat: u64,
    /// Trust checks (`Hypotheses` and `Dropped`).
    pub trust_checks: u64,
    /// Trust checks answered as required (`sat`).
    pub trust_ok: u64,
    /// Searches for a counterexample of a printed statement (`Printed`).
    pub printed: u64,
    /// Those answered `sat`.
    pub printed_sat: u64,
    /// Obligations answered `unknown` (or timed out).
    pub unknown: u64,
    /// Wall-clock seconds over all obligations (sum of per-obligation times).
    pub seconds: f64,
}

impl Summary {
    /// Counts the answers.
    pub fn of(solved: &[Solved]) -> Summary {
        let mut s = Summary {
            proofs: 0,
            proofs_unsat: 0,
            trust_checks: 0,
            trust_ok: 0,
            printed: 0,
            printed_sat: 0,
            unknown: 0,
            seconds: 0.0,
        };
        for x in solved {
            s.seconds += x.seconds;
            if matches!(x.answer, Answer::Unknown(_)) {
                s.unknown += 1;
            }
            if x.obligation.role == Role::Proof {
                s.proofs += 1;
                s.proofs_unsat += u64::from(x.answer == Answer::Unsat);
            } else if x.obligation.role == Role::Printed {
                s.printed += 1;
                s.printed_sat += u64::from(matches!(x.answer, Answer::Sat(_)));
            } else {
                s.trust_checks += 1;
                s.trust_ok += u64::from(x.as_expected());
            }
        }
        s
    }

    /// Whether this is a proof: every proof obligation `unsat`, every trust check as
    /// required, at least one of each, nothing unknown.
    pub fn proved(&self) -> bool {
        self.proofs > 0
            && self.proofs_unsat == self.proofs
            && self.trust_checks > 0
            && self.trust_ok == self.trust_checks
            && self.unknown == 0
    }
}

/// What replaying a `sat` model through the claim's exact oracle showed.
#[derive(Clone, Debug, PartialEq)]
pub enum Replay {
    /// The model, in exact rationals, is a real failure of the statement the obligation
    /// encodes (the printed claim, or the claim without the dropped hypothesis): what fails,
    /// and the counterexample to report (for `Printed`).
    Confirmed(String, Option<super::Counterexample>),
    /// The exact oracle does not confirm the model: the encoding is wrong somewhere.
    NotConfirmed(String),
    /// This obligation's models are not replayed (hypotheses-satisfiable checks).
    NotApplicable,
}

/// A claim's SMT encoding: its obligations and how to replay a model.
pub struct Encoding {
    /// The claim id (`C1-corrected`, …).
    pub claim: &'static str,
    /// The scope, in words ("every structure with ≤ 4 states …; costs, values and bonuses:
    /// all reals").
    pub scope: String,
    /// Every obligation, trust checks included, in a deterministic order.
    pub obligations: Vec<Obligation>,
    /// Replays a `sat` model of a `Printed` or `Dropped` obligation exactly.
    pub replay: fn(&Obligation, &Model) -> Replay,
}

/// The verdict the SMT engine gives a claim.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SmtVerdict {
    /// Every proof obligation `unsat`, every trust check as required.
    Proved,
    /// A `Printed` obligation was `sat` and its model replayed as a counterexample.
    Refuted,
    /// Anything else.
    Inconclusive,
}

/// The SMT engine's result for one claim.
#[derive(Clone, Debug, PartialEq)]
pub struct Outcome {
    /// The claim id.
    pub claim: &'static str,
    /// The scope in words.
    pub scope: String,
    /// The verdict.
    pub verdict: SmtVerdict,
    /// Counts and time.
    pub summary: Summary,
    /// The first replayed counterexample of a `Printed` obligation.
    pub counterexample: Option<super::Counterexample>,
    /// Findings: trust checks that failed, unknowns, replays.
    pub notes: Vec<String>,
    /// Every obligation with its answer (for `--smt-out`).
    pub solved: Vec<Solved>,
}

/// Default per-obligation timeout (milliseconds).
pub const TIMEOUT_MS: u32 = 60_000;

/// An answer as a shard records it: rationals as `n/d` text.
#[derive(serde::Serialize, serde::Deserialize)]
pub enum AnswerRecord {
    /// `unsat`.
    Unsat,
    /// `sat`, with the model's values as text (`None`: a model that is not rational).
    Sat(Option<Vec<(String, String)>>),
    /// `unknown`, and why.
    Unknown(String),
}

/// One obligation's result as a shard records it.
#[derive(serde::Serialize, serde::Deserialize)]
pub struct SolvedRecord {
    answer: AnswerRecord,
    seconds: f64,
}

impl SolvedRecord {
    /// The record of `s`.
    pub fn of(s: &Solved) -> SolvedRecord {
        SolvedRecord {
            answer: match &s.answer {
                Answer::Unsat => AnswerRecord::Unsat,
                Answer::Sat(m) => AnswerRecord::Sat(m.as_ref().map(|m| {
                    m.values
                        .iter()
                        .map(|(n, v)| (n.clone(), v.to_string()))
                        .collect()
                })),
                Answer::Unknown(why) => AnswerRecord::Unknown(why.clone()),
            },
            seconds: s.seconds,
        }
    }

    /// The solved obligation this record is of (`obligation`: the obligation it answers).
    pub fn solved(self, obligation: Obligation) -> Solved {
        let answer = match self.answer {
            AnswerRecord::Unsat => Answer::Unsat,
            AnswerRecord::Unknown(why) => Answer::Unknown(why),
            AnswerRecord::Sat(values) => Answer::Sat(values.and_then(|values| {
                let values: Option<Vec<(String, Rational)>> = values
                    .into_iter()
                    .map(|(n, v)| Rational::from_str(&v).ok().map(|v| (n, v)))
                    .collect();
                // An unreadable value reads as a non-rational model: it cannot replay.
                values.map(|values| Model { values })
            })),
        };
        Solved {
            obligation,
            answer,
            seconds: self.seconds,
        }
    }
}

/// The SMT encoding of claim `id` (one of the claims of `verify`'s report), if it has one: its
/// obligations listed, none of them solved (Z3 is not run).
///
/// ```
/// use truecost::claims::{smt, Scope};
/// let enc = smt::encoding("C2", Scope::Smoke).unwrap();
/// assert_eq!(enc.claim, "C2");
/// assert!(!enc.obligations.is_empty());
/// assert!(smt::encoding("C9", Scope::Smoke).is_none());
/// ```
pub fn encoding(id: &str, scope: super::Scope) -> Option<Encoding> {
    match id {
        "C1" => Some(c1::printed()),
        "C1-corrected" => Some(c1::corrected(scope)),
        "C2" => Some(c2::encoding(scope)),
        "C3" => Some(c3::encoding(scope)),
        "C3-example" => Some(c3::example_encoding(scope)),
        "C4" => Some(c4::encoding_printed(scope)),
        "C4-corrected" => Some(c4::encoding(scope)),
        _ => None,
    }
}

/// Solves a claim's obligations, replays its models, and decides the SMT verdict.
pub fn run(mut enc: Encoding, timeout_ms: u32) -> Outcome {
    let solved = discharge(std::mem::take(&mut enc.obligations), timeout_ms);
    judge(&enc, solved)
}

/// The SMT verdict of a claim from its obligations `solved` (every obligation of `enc`, in
/// order, with Z3's answer): replays its models through the claim's exact oracle and decides.
pub fn judge(enc: &Encoding, solved: Vec<Solved>) -> Outcome {
    let summary = Summary::of(&solved);
    let mut notes = Vec::new();
    let mut counterexample = None;
    let mut printed_confirmed = false;
    let mut replay_failed = false;
    for s in &solved {
        let o = &s.obligation;
        if let Answer::Unknown(why) = &s.answer {
            notes.push(format!(
                "smt: {} / {} / {}: unknown ({why}): inconclusive",
                o.lemma,
                o.structure,
                o.role.name()
            ));
            continue;
        }
        if !s.as_expected() {
            notes.push(format!(
                "smt: {} / {} / {}: expected {}, Z3 answered {}",
                o.lemma,
                o.structure,
                o.role.name(),
                o.role.expected().name(),
                s.answer.name()
            ));
        }
        if let Answer::Sat(model) = &s.answer {
            if matches!(o.role, Role::Printed | Role::Dropped(_) | Role::Proof) {
                let replayed = match model {
                    Some(m) => (enc.replay)(o, m),
                    None => Replay::NotConfirmed("the model is not rational".into()),
                };
                match replayed {
                    Replay::Confirmed(what, ce) => {
                        if o.role == Role::Printed || o.role == Role::Proof {
                            printed_confirmed = true;
                            if counterexample.is_none() {
                                counterexample = ce;
                                notes.push(format!(
                                    "smt: {} / {}: {what} (model replayed exactly)",
                                    o.lemma, o.structure
                                ));
                            }
                        }
                    }
                    Replay::NotConfirmed(why) => {
                        replay_failed = true;
                        notes.push(format!(
                            "smt: {} / {} / {}: the model does not replay ({why}): inconclusive",
                            o.lemma,
                            o.structure,
                            o.role.name()
                        ));
                    }
                    Replay::NotApplicable => {}
                }
            }
        }
    }
    let has_printed = solved.iter().any(|s| s.obligation.role == Role::Printed);
    let verdict = if replay_failed || summary.unknown > 0 {
        SmtVerdict::Inconclusive
    } else if has_printed {
        if printed_confirmed && summary.printed_sat > 0 && summary.trust_ok == summary.trust_checks
        {
            SmtVerdict::Refuted
        } else {
            SmtVerdict::Inconclusive
        }
    } else if summary.proved() {
        SmtVerdict::Proved
    } else if printed_confirmed {
        // A proof obligation of a corrected claim was satisfiable and replayed: refuted.
        SmtVerdict::Refuted
    } else {
        SmtVerdict::Inconclusive
    };
    Outcome {
        claim: enc.claim,
        scope: enc.scope.clone(),
        verdict,
        summary,
        counterexample,
        notes,
        solved,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn int(n: i64) -> Rational {
        Rational::from_integer(n.into())
    }

    #[test]
    fn numerals_z3_does_not_print_are_refused() {
        // Each of these has digits around its one stray character, so a check that let it
        // through would hand BigInt a string it parses (`+3`, `-3`, `5`, `35_0`).
        for s in ["+3", "-3", ".5", "3.5_0", "3._5", "", "(- )", "(/ 1.0 0.0)"] {
            assert_eq!(parse_numeral(s), None, "{s:?}");
        }
        assert_eq!(
            parse_numeral("0.25"),
            Some(Rational::new(1.into(), 4.into()))
        );
        assert_eq!(parse_numeral("3.0"), Some(int(3)));
        assert_eq!(parse_numeral(" (- 3) "), Some(int(-3)));
        assert_eq!(parse_numeral("false"), Some(int(0)));
        assert_eq!(parse_numeral("true"), Some(int(1)));
    }

    /// `x_i < x_(i+1) + 1/3` for i < n, closed by `x_n + n < x_0`: unsatisfiable, and (at
    /// n = 500) long enough that Z3 needs well over a millisecond to say so.
    fn a_long_cycle(n: usize) -> Obligation {
        let mut o = Obligation::new("test", "cycle", "none", Role::Hypotheses, Logic::QfLra);
        let xs: Vec<String> = (0..=n)
            .map(|i| o.declare(&format!("x{i}"), Sort::Real))
            .collect();
        for w in xs.windows(2) {
            o.assert(format!("(< {} (+ {} (/ 1.0 3.0)))", w[0], w[1]));
        }
        o.assert(format!("(< (+ {} {}.0) {})", xs[n], n, xs[0]));
        o
    }

    fn linear(logic: Logic) -> Obligation {
        let mut o = Obligation::new("test", "x > 0", "none", Role::Hypotheses, logic);
        let x = o.declare("x", Sort::Real);
        o.assert(format!("(> {x} 0.0)"));
        o
    }

    #[test]
    fn a_thread_keeps_one_linear_solver_per_logic_and_timeout() {
        // A fresh thread, so that its solvers are only the ones made here.
        std::thread::spawn(|| {
            let solvers = || SOLVERS.with(|cell| cell.borrow().len());
            for (logic, timeout, expected) in [
                (Logic::QfLra, 10_000, 1),
                (Logic::QfLra, 10_000, 1),
                (Logic::QfLira, 10_000, 2),
                (Logic::QfLra, 20_000, 3),
                (Logic::QfLira, 20_000, 4),
                (Logic::QfLira, 10_000, 4),
                (Logic::QfNra, 10_000, 4),
            ] {
                assert!(matches!(solve(&linear(logic), timeout), Answer::Sat(_)));
                assert_eq!(solvers(), expected, "{logic:?} {timeout}");
            }
        })
        .join()
        .unwrap();
    }

    #[test]
    fn a_thread_s_solver_is_reused_only_with_its_own_timeout() {
        // A fresh process, so that its solvers are only the ones made here: the solver made
        // with a timeout of 1 ms must not answer an obligation given 100 s.
        in_a_child_process(
            "claims::smt::tests::a_thread_s_solver_is_reused_only_with_its_own_timeout",
            || {
                let _ = solve(&a_long_cycle(1), 1);
                let a = solve(&a_long_cycle(500), 100_000);
                assert_eq!(a, Answer::Unsat);
            },
        );
    }

    /// How long a child of [`in_a_child_process`] may run before it is taken for hung.
    const CHILD_SECONDS: u64 = 15;

    /// Runs `check` in a child process (this test binary, running only the test `name`), at
    /// most three times while the child hangs. The tests whose timeouts expire need it: the
    /// timer pool of the Z3 library that Debian ships (4.8.12) can deadlock when a timer expires
    /// (Z3Prover/z3#5990; every thread asleep in about one run in twenty of
    /// `a_fresh_solver_keeps_its_timeout` on 2 cores), and a hung Z3 can only be left
    /// behind by killing its process. A child runs well under a second, so one still running
    /// after [`CHILD_SECONDS`] is taken for hung. A child that exits with a failure fails the
    /// test with its output; three hung children fail it too.
    fn in_a_child_process(name: &str, check: impl FnOnce()) {
        const CHILD: &str = "TRUECOST_SMT_TEST_CHILD";
        if std::env::var_os(CHILD).is_some() {
            check();
            return;
        }
        let exe = std::env::current_exe().expect("the test binary's path");
        for _ in 0..3 {
            let mut child = std::process::Command::new(&exe)
                .args(["--exact", name, "--test-threads", "1"])
                .env(CHILD, "1")
                .stdout(std::process::Stdio::piped())
                .stderr(std::process::Stdio::piped())
                .spawn()
                .expect("the test binary starts");
            let start = std::time::Instant::now();
            while start.elapsed() < std::time::Duration::from_secs(CHILD_SECONDS) {
                if child.try_wait().expect("the child's status").is_some() {
                    let out = child.wait_with_output().expect("the child's output");
                    let text = String::from_utf8_lossy(&out.stdout);
                    assert!(
                        out.status.success() && text.contains("1 passed"),
                        "{text}{}",
                        String::from_utf8_lossy(&out.stderr)
                    );
                    return;
                }
                std::thread::sleep(std::time::Duration::from_millis(50));
            }
            let _ = child.kill();
            let _ = child.wait();
        }
        panic!("Z3 hung three times in {name} (the timer pool's deadlock, above)");
    }

    /// The solver a nonlinear obligation gets is made with the obligation's timeout: given
    /// 1 ms, the 2000-step cycle of [`a_long_cycle`] (unsatisfiable, but Z3's nonlinear
    /// procedure needs tens of milliseconds to say so) must come back `unknown` (a timeout),
    /// never `unsat` — a solver made without the timeout would prove it. Stated in QF_NRA,
    /// so that [`solve`] makes its solver here rather than take one from the thread's cache
    /// (and because, in QF_LRA, Z3 was seen to prove such a cycle despite a 1 ms timeout);
    /// a fresh process all the same.
    #[test]
    fn a_fresh_solver_keeps_its_timeout() {
        in_a_child_process(
            "claims::smt::tests::a_fresh_solver_keeps_its_timeout",
            || {
                let mut o = a_long_cycle(2000);
                o.logic = Logic::QfNra;
                let a = solve(&o, 1);
                assert!(matches!(a, Answer::Unknown(_)), "{a:?}");
            },
        );
    }

    fn solved(role: Role, answer: Answer) -> Solved {
        Solved {
            obligation: linear(Logic::QfLra).with_role(role),
            answer,
            seconds: 0.0,
        }
    }

    /// `Solved::as_expected` by the roles' contract: a proof must be `unsat`, a hypotheses or
    /// dropped-hypothesis check `sat`, a printed search either decided answer; `unknown` is
    /// never as expected. Six of the eleven cases must be false.
    #[test]
    fn as_expected_follows_the_role() {
        let sat = || Answer::Sat(None);
        let unknown = || Answer::Unknown("timeout".into());
        let dropped = || Role::Dropped("h".into());
        for (role, answer, expected) in [
            (Role::Proof, Answer::Unsat, true),
            (Role::Proof, sat(), false),
            (Role::Proof, unknown(), false),
            (Role::Hypotheses, sat(), true),
            (Role::Hypotheses, Answer::Unsat, false),
            (dropped(), sat(), true),
            (dropped(), Answer::Unsat, false),
            (dropped(), unknown(), false),
            (Role::Printed, sat(), true),
            (Role::Printed, Answer::Unsat, true),
            (Role::Printed, unknown(), false),
        ] {
            let s = solved(role.clone(), answer.clone());
            assert_eq!(s.as_expected(), expected, "{role:?} {answer:?}");
        }
    }

    /// One proof `unsat`, one trust check as required, nothing unknown: a proof. Each of
    /// "at least one proof obligation" and "at least one trust check" is needed: with no
    /// proof obligation (0 of 0 unsat) or no trust check (0 of 0 as required) every
    /// equality still holds, and it must not be a proof.
    #[test]
    fn a_proof_needs_a_proof_obligation_and_a_trust_check() {
        let one_of_each = Summary {
            proofs: 1,
            proofs_unsat: 1,
            trust_checks: 1,
            trust_ok: 1,
            printed: 0,
            printed_sat: 0,
            unknown: 0,
            seconds: 0.0,
        };
        assert!(one_of_each.proved());
        let no_proof = Summary {
            proofs: 0,
            proofs_unsat: 0,
            ..one_of_each.clone()
        };
        assert!(!no_proof.proved());
        let no_trust_check = Summary {
            trust_checks: 0,
            trust_ok: 0,
            ..one_of_each
        };
        assert!(!no_trust_check.proved());
    }

    /// `x > 0`: satisfiable.
    fn satisfiable(role: Role) -> Obligation {
        linear(Logic::QfLra).with_role(role)
    }

    /// `x < x`: unsatisfiable.
    fn unsatisfiable(role: Role) -> Obligation {
        let mut o = Obligation::new("test", "x < x", "none", role, Logic::QfLra);
        let x = o.declare("x", Sort::Real);
        o.assert(format!("(< {x} {x})"));
        o
    }

    fn encoding(
        obligations: Vec<Obligation>,
        replay: fn(&Obligation, &Model) -> Replay,
    ) -> Encoding {
        Encoding {
            claim: "test",
            scope: "hand-built".into(),
            obligations,
            replay,
        }
    }

    /// A dropped-hypothesis check whose model does not replay makes the run inconclusive even
    /// though, counted, it is a proof (its one proof obligation `unsat`, its one trust check
    /// `sat` as required, nothing unknown): a model the exact oracle does not confirm means
    /// the encoding is wrong somewhere.
    #[test]
    fn a_model_that_does_not_replay_makes_a_proof_inconclusive() {
        let out = run(
            encoding(
                vec![
                    unsatisfiable(Role::Proof),
                    satisfiable(Role::Dropped("x > 0".into())),
                ],
                |_, _| Replay::NotConfirmed("planted".into()),
            ),
            10_000,
        );
        assert!(out.summary.proved(), "{:?}", out.summary);
        assert_eq!(out.verdict, SmtVerdict::Inconclusive);
    }

    /// A printed search whose model replays would refute the claim (no trust check, so all of
    /// them, none, are as required), but another printed search came back `unknown` — here a
    /// parse failure: its assertion names an undeclared constant, so Z3 parses 0 of its 1
    /// assertions (in QF_NRA, so that the failure is in a solver of its own) — and anything
    /// unknown makes the run inconclusive.
    #[test]
    fn an_unknown_makes_a_refutation_inconclusive() {
        let mut broken = Obligation::new("test", "broken", "none", Role::Printed, Logic::QfNra);
        broken.assert("(> undeclared 0.0)".into());
        let out = run(
            encoding(vec![satisfiable(Role::Printed), broken], |_, _| {
                Replay::Confirmed("planted".into(), None)
            }),
            10_000,
        );
        assert_eq!((out.summary.printed_sat, out.summary.unknown), (1, 1));
        assert_eq!(out.verdict, SmtVerdict::Inconclusive);
    }

    /// A claim with a printed search is refuted only when a printed search is `sat` (and its
    /// model replays): here the printed search is `unsat` (no counterexample on its
    /// structure) and only a proof obligation is `sat` with a model that replays, and there
    /// is no trust check (so all of them, none, are as required). `Refuted` is documented as
    /// "a Printed obligation was sat and its model replayed": not the case, so inconclusive.
    #[test]
    fn a_printed_claim_is_refuted_only_by_a_sat_printed_search() {
        let out = run(
            encoding(
                vec![unsatisfiable(Role::Printed), satisfiable(Role::Proof)],
                |_, _| Replay::Confirmed("planted".into(), None),
            ),
            10_000,
        );
        assert_eq!(
            (out.summary.printed_sat, out.summary.proofs_unsat),
            (0, 0),
            "{:?}",
            out.summary
        );
        assert_eq!(out.verdict, SmtVerdict::Inconclusive);
    }
}
