//! `verify --certificates DIR`: certificates (`truecost-certificate/1`) of the exact optima a
//! `verify` run prints and rests its verdicts on, each re-checked by truecost's checker
//! ([`crate::certificate::check`]) before the report is printed, each with the problem file
//! `truecost check --file` rebuilds the problem from.
//!
//! The claims are decided on enumerated tiny problems; their optima are not written out (one
//! file per enumerated problem). What is certified:
//!
//! * the deterministic `G*` of every counterexample's problem the report prints (its `L*`, `Q*`
//!   are `G*` and `l + G*`; a certified `G*(x1)` that is not the printed `L*` is an error);
//! * the discounted optimum of C3's worked example at both ends of the bracket of `α*` — the
//!   exact solves the worked example's verdict rests on — computed as that claim's engine
//!   computes them: every stationary policy evaluated exactly from every state;
//! * with `--claim C4 --file F | --problem N | --env SPEC`, the deterministic `G*` of that
//!   problem ([`certify_optimum`], wired by the command line).

use std::path::{Path, PathBuf};

use num_traits::{One, Zero};
use serde_json::{json, Value};

use super::alpha::{discounted_value, worked_example};
use super::oracle::{policies, trajectory};
use super::report::Report;
use crate::certificate::{self, Acceptance, CertifiedObjective, Identity, Mdp, ProblemRecord};
use crate::stochastic::certified::{optimum_certificate, problem_mdp};
use crate::stochastic::file::{from_json_with_objective, ProblemFile};
use crate::stochastic::record::{problem_record, Origin};
use crate::stochastic::{policy_iteration, NoiseModel, Predictability, StochasticProblem};
use crate::value::Rational;

/// The checker every certificate is re-checked by, as the report names it.
pub const CHECKER: &str = "truecost's checker (truecost::certificate::check)";

/// One certificate written and accepted.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Written {
    /// The certificate's file name in the directory.
    pub certificate: String,
    /// The problem file `truecost check --file` checks it against: a name in the directory, or
    /// the path as given (`None`: a paper problem or an environment, rebuilt by `check
    /// --problem` or `--env`).
    pub problem_file: Option<String>,
    /// `deterministic` or `discounted`.
    pub objective: &'static str,
    /// What it certifies.
    pub certifies: String,
    /// States of the problem.
    pub states: usize,
}

/// The certificates of one run.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Certificates {
    /// The directory, as given.
    pub dir: String,
    /// Every certificate, in the order written.
    pub written: Vec<Written>,
    /// What the run computed and no certificate covers.
    pub not_certified: String,
}

/// An accepted certificate's text and values.
pub struct Certified {
    /// The certificate's text.
    pub text: String,
    /// What the checker established.
    pub acceptance: Acceptance,
    /// The certified values, per state (`None`: `inf`).
    pub values: Vec<Option<Rational>>,
    /// The certified policy: an action index per state.
    pub policy: Vec<Option<u64>>,
}

/// Refuses a `--certificates` directory that cannot take the certificates, in one line, before
/// any work: a path that is not a directory, one that cannot be created, or one in which a file
/// cannot be written (a probe file is created and removed).
///
/// ```
/// use truecost::claims::certificates::prepare_dir;
/// let dir = std::env::temp_dir().join(format!("prepare-doctest-{}", std::process::id()));
/// assert!(prepare_dir(&dir.join("certs")).is_ok());
/// std::fs::write(dir.join("a-file"), "x").unwrap();
/// let e = prepare_dir(&dir.join("a-file")).unwrap_err();
/// assert!(e.contains("not a directory"), "{e}");
/// assert!(prepare_dir(&dir.join("a-file").join("below")).is_err());
/// std::fs::remove_dir_all(&dir).unwrap();
/// ```
pub fn prepare_dir(dir: &Path) -> Result<(), String> {
    let shown = || crate::echo::echo(&dir.display().to_string());
    if dir.exists() && !dir.is_dir() {
        return Err(format!("--certificates {} is not a directory", shown()));
    }
    std::fs::create_dir_all(dir)
        .map_err(|e| format!("cannot create --certificates {}: {e}", shown()))?;
    let probe = dir.join(format!(".truecost-probe-{}", std::process::id()));
    std::fs::write(&probe, b"")
        .and_then(|()| std::fs::remove_file(&probe))
        .map_err(|e| format!("cannot write in --certificates {}: {e}", shown()))
}

/// Checks `text` as `truecost check` does, against `mdp` whose SHA-256 is taken as `identity`
/// says: parsed afresh, then [`certificate::check`]; a rejection is one line naming `what`.
fn accepted(
    text: String,
    mdp: &Mdp,
    identity: Identity<'_>,
    what: &str,
) -> Result<Certified, String> {
    let cert = certificate::parse(&text)
        .map_err(|e| format!("the certificate of {what} does not read back: {e}"))?;
    let acceptance = certificate::check(mdp, identity, &cert)
        .map_err(|r| format!("the certificate of {what} is rejected by {CHECKER}: {r}"))?;
    Ok(Certified {
        text,
        acceptance,
        values: cert.values,
        policy: cert.policy,
    })
}

/// The deterministic `G*` of `problem` (every action one outcome), by the exact optimum
/// ([`policy_iteration::optimum`]), as a certificate (objective `deterministic`) with `record`,
/// re-checked by [`CHECKER`] against `mdp` (the model `truecost check` rebuilds) before it is
/// returned. `what` names the optimum in errors.
pub fn certify_optimum(
    problem: &StochasticProblem,
    mdp: &Mdp,
    identity: Identity<'_>,
    record: &ProblemRecord,
    what: &str,
) -> Result<Certified, String> {
    let opt = policy_iteration::optimum(problem).map_err(|e| format!("{what}: {e}"))?;
    let text = optimum_certificate(problem, &opt, &CertifiedObjective::Deterministic, record);
    accepted(text, mdp, identity, what)
}

/// The certified `G*(x1)` as text (`inf` if infinite), which must be the printed `l_star`
/// when there is one: otherwise one line naming both.
fn at_initial(
    c: &Certified,
    x1: usize,
    l_star: Option<&str>,
    what: &str,
) -> Result<String, String> {
    let g = c.values[x1]
        .as_ref()
        .map_or_else(|| "inf".to_string(), Rational::to_string);
    match l_star {
        Some(l) if l != g => Err(format!(
            "{what}: the certified G*(x1) = {g} is not the L* = {} printed",
            crate::echo::echo(l)
        )),
        _ => Ok(g),
    }
}

/// A deterministic problem file's text as the problem `truecost check --file` rebuilds, and its
/// model.
fn read_problem_file(text: &str) -> Result<(StochasticProblem, Mdp), String> {
    let (file, _) = from_json_with_objective(text).map_err(|e| e.to_string())?;
    let ProblemFile::Deterministic(d) = file else {
        return Err("a counterexample's problem file lists outcomes".into());
    };
    let p = StochasticProblem::from_deterministic(&d, NoiseModel::Paper, &Predictability::one())
        .map_err(|e| e.to_string())?;
    let mdp = problem_mdp(&p);
    Ok((p, mdp))
}

/// Writes `text` to `dir/name` (whole: a temporary file, then a rename).
fn write(dir: &Path, name: &str, text: &str) -> Result<PathBuf, String> {
    let path = dir.join(name);
    crate::atomic::write(&path, text.as_bytes())?;
    Ok(path)
}

/// The deterministic `G*` certificate of a counterexample's problem file (`stem`.json, the
/// text `--counterexamples` writes), with the file, in `dir`; `l_star`: the `L*` the report
/// prints, which the certified `G*(x1)` must be.
fn counterexample(
    dir: &Path,
    claim: &str,
    stem: &str,
    problem_file: &str,
    l_star: Option<&str>,
) -> Result<Written, String> {
    let what = format!("the {claim} counterexample's problem");
    let (p, mdp) = read_problem_file(problem_file).map_err(|e| format!("{what}: {e}"))?;
    let file_name = format!("{stem}.json");
    let path = write(dir, &file_name, problem_file)?;
    let record = problem_record(Origin::File(&path), None, None, || unreachable!())?;
    let identity = Identity::FileBytes(problem_file.as_bytes());
    let c = certify_optimum(&p, &mdp, identity, &record, &what)?;
    let g = at_initial(&c, p.initial(), l_star, &what)?;
    let name = format!("{stem}.cert.json");
    write(dir, &name, &c.text)?;
    Ok(Written {
        certificate: name,
        problem_file: Some(file_name),
        objective: "deterministic",
        certifies: format!("deterministic G* of {what} (G*(x1) = {g})"),
        states: c.acceptance.states,
    })
}

/// The discounted optimum of C3's worked example at `alpha`, as that claim's engine computes it:
/// every stationary policy (the goal terminates) evaluated exactly from every state, the least
/// discounted cost `C(x)`; the certificate's values are the rewards `V(x) = −C(x)` (rewards are
/// the negated costs) and its policy, at each non-goal state, the first action with
/// `V(x) = −l(x, a) + α V(f(x, a))`.
fn worked_example_optimum(alpha: &Rational) -> Result<(Vec<String>, Vec<Option<usize>>), String> {
    let t = worked_example();
    let ps = policies(&t, false);
    let n = t.states();
    let values: Vec<Rational> = (0..n)
        .map(|x| {
            ps.iter()
                .map(|p| discounted_value(&trajectory(&t, p, x), alpha))
                .min()
                .map(|c| -c)
                .expect("a policy")
        })
        .collect();
    let mut policy = Vec::with_capacity(n);
    for x in 0..n {
        if t.is_goal(x) {
            policy.push(None);
            continue;
        }
        let chosen = t.moves(x).iter().position(|m| {
            let q = -Rational::from_integer(num_bigint::BigInt::from(m.cost))
                + alpha * &values[m.to as usize];
            q == values[x]
        });
        if chosen.is_none() {
            return Err(format!(
                "C3's worked example at alpha = {alpha}: no action attains the optimum at state {x}"
            ));
        }
        policy.push(chosen);
    }
    Ok((values.iter().map(|v| v.to_string()).collect(), policy))
}

/// Whether the policy, followed from state 0, reaches the goal (a deterministic walk: it ends
/// at the goal or repeats a state).
fn reaches_goal(policy: &[Option<u64>]) -> bool {
    let t = worked_example();
    let mut x = 0usize;
    for _ in 0..=t.states() {
        if t.is_goal(x) {
            return true;
        }
        let Some(k) = policy[x] else { return false };
        x = t.moves(x)[k as usize].to as usize;
    }
    false
}

/// The worked example's discounted certificates at both ends (`lo < α* < hi`) of the bracket,
/// with its problem file, in `dir`.
fn worked_example_certificates(dir: &Path, lo: &str, hi: &str) -> Result<Vec<Written>, String> {
    let problem: crate::model::Problem = worked_example().to_problem();
    let file_text = crate::model::file::to_json(
        &problem,
        Some("C3's worked example: X = {0..5}, goal 5, f(x,u) = min(5, max(0, x+u)), l(x,u) = x+1"),
    ) + "\n";
    let (_, mdp) = read_problem_file(&file_text)?;
    let file_name = "c3-example.json".to_string();
    let path = write(dir, &file_name, &file_text)?;
    let record = problem_record(Origin::File(&path), None, None, || unreachable!())?;
    let mut out = Vec::new();
    for (end, text, side) in [("lo", lo, "below"), ("hi", hi, "above")] {
        let alpha = crate::value::parse_rational(text)
            .map_err(|e| format!("the bracket of alpha*: {e}"))?;
        if !(alpha > Rational::zero() && alpha < Rational::one()) {
            return Err(format!(
                "the bracket of alpha* has an end {alpha} outside (0, 1)"
            ));
        }
        let what = format!("C3's worked example at alpha = {end} ({side} alpha*)");
        let (values, policy) = worked_example_optimum(&alpha)?;
        let objective = CertifiedObjective::Discounted(alpha);
        let cert = certificate::write(&objective, &record, values, &policy);
        let c = accepted(cert, &mdp, Identity::FileBytes(file_text.as_bytes()), &what)?;
        let from_0 = if reaches_goal(&c.policy) {
            "reaches the goal"
        } else {
            "avoids the goal"
        };
        let name = format!("c3-example-alpha-{end}.cert.json");
        write(dir, &name, &c.text)?;
        out.push(Written {
            certificate: name,
            problem_file: Some(file_name.clone()),
            objective: "discounted",
            certifies: format!(
                "discounted optimum of {what}: the certified optimal policy from 0 {from_0}"
            ),
            states: c.acceptance.states,
        });
    }
    Ok(out)
}

/// The certificates of a whole run's `report`, written to `dir` (prepared by [`prepare_dir`]):
/// the deterministic `G*` of every counterexample's problem, then the worked example's
/// discounted optimum at both ends of `α*`'s bracket (when the report has `α*`).
pub fn of_report(report: &Report, dir: &Path) -> Result<Certificates, String> {
    let mut written = Vec::new();
    for c in &report.claims {
        let Some(ce) = &c.counterexample else {
            continue;
        };
        let stem = Path::new(&ce.file)
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_else(|| c.id.to_lowercase());
        let l_star = ce
            .details
            .iter()
            .find(|(k, _)| k == "L*")
            .map(|(_, v)| v.as_str());
        written.push(counterexample(dir, &c.id, &stem, &ce.problem_file, l_star)?);
    }
    if let Some(a) = &report.alpha_star {
        written.extend(worked_example_certificates(dir, &a.lo, &a.hi)?);
    }
    Ok(Certificates {
        dir: dir.display().to_string(),
        written,
        not_certified:
            "the optima of the enumerated problems the claims are decided on (not written out)"
                .into(),
    })
}

impl Certificates {
    /// What the certificates are of, in one phrase.
    fn covering(&self) -> String {
        let list: Vec<&str> = self.written.iter().map(|w| w.certifies.as_str()).collect();
        if list.is_empty() {
            "none: this run printed no optimum to certify".into()
        } else {
            list.join("; ")
        }
    }

    /// The report's line: how many were written where, how many the checker accepted, of what.
    ///
    /// ```
    /// use truecost::claims::certificates::{Certificates, Written};
    /// let c = Certificates {
    ///     dir: "certs".into(),
    ///     written: vec![Written {
    ///         certificate: "p.cert.json".into(),
    ///         problem_file: Some("p.json".into()),
    ///         objective: "deterministic",
    ///         certifies: "deterministic G* of p".into(),
    ///         states: 2,
    ///     }],
    ///     not_certified: "the rest".into(),
    /// };
    /// assert_eq!(
    ///     c.line(),
    ///     "certificates: 1 written to certs, 1 accepted by truecost's checker (truecost::certificate::check): deterministic G* of p; not certified: the rest"
    /// );
    /// ```
    pub fn line(&self) -> String {
        let n = self.written.len();
        format!(
            "certificates: {n} written to {}, {n} accepted by {CHECKER}: {}; not certified: {}",
            crate::echo::echo(&self.dir),
            self.covering(),
            self.not_certified
        )
    }

    /// The count, the directory and the checker, in one sentence (the LaTeX caption's).
    pub fn summary(&self) -> String {
        let n = self.written.len();
        format!(
            "{n} certificates written to {}, {n} accepted by {CHECKER}",
            crate::echo::echo(&self.dir)
        )
    }

    /// The report's JSON entry.
    pub fn json(&self) -> Value {
        json!({
            "directory": self.dir,
            "written": self.written.len(),
            "accepted": self.written.len(),
            "checker": CHECKER,
            "files": self.written.iter().map(|w| json!({
                "certificate": w.certificate,
                "problem_file": w.problem_file,
                "objective": w.objective,
                "states": w.states,
                "certifies": w.certifies,
            })).collect::<Vec<_>>(),
            "not_certified": self.not_certified,
        })
    }
}

/// The problem of `verify --claim C4 --file | --problem | --env` whose `G*` is certified.
pub enum Single<'a> {
    /// A deterministic problem file (its bytes hashed).
    File(&'a Path),
    /// A paper problem with unit step costs, as `verify --problem N` analyses it.
    Paper(usize),
    /// An environment (`--env SPEC`, the text as given): its model as `truecost check --env`
    /// rebuilds it, and the initial state `x1` of the analysis.
    Env {
        /// The `--env` text.
        spec: &'a str,
        /// The environment's problem.
        problem: &'a StochasticProblem,
        /// The environment's model as the checker reads it.
        mdp: Mdp,
        /// `x1`.
        initial: usize,
    },
}

/// The deterministic `G*` certificate of one problem, written to `dir` (prepared by
/// [`prepare_dir`]) as `<file stem>.cert.json`, `problem-<N>.cert.json` or
/// `env-<spec>.cert.json`, re-checked by [`CHECKER`] first. `l_star`: the `L*` the analysis
/// prints, which the certified `G*(x1)` must be (one line naming both if not).
pub fn of_problem(
    dir: &Path,
    single: Single<'_>,
    l_star: Option<&str>,
) -> Result<Certificates, String> {
    use crate::problems::StepCost;
    let (name, what, problem, mdp, bytes, record, x1);
    let owned: StochasticProblem;
    let mut problem_file = None;
    match single {
        Single::File(path) => {
            let read = crate::bounded::read_bytes(
                path,
                crate::model::file::MAX_FILE_BYTES,
                "problem files",
            )
            .map_err(|e| e.to_string())?;
            let text = String::from_utf8(read.clone())
                .map_err(|_| "the problem file is not UTF-8 text".to_string())?;
            let (p, m) = read_problem_file(&text)?;
            owned = p;
            let stem = path
                .file_stem()
                .map(|s| s.to_string_lossy().into_owned())
                .unwrap_or_else(|| "problem".into());
            name = format!("{stem}.cert.json");
            what = format!("file {}", crate::echo::echo(&path.display().to_string()));
            mdp = m;
            bytes = Some(read);
            problem_file = Some(path.display().to_string());
            record = problem_record(Origin::File(path), None, None, || unreachable!())?;
            problem = &owned;
            x1 = owned.initial();
        }
        Single::Paper(id) => {
            owned = crate::stochastic::grid::exact_grid(
                id,
                StepCost::Unit,
                NoiseModel::Paper,
                &Predictability::one(),
            )
            .map_err(|e| e.to_string())?;
            name = format!("problem-{id}.cert.json");
            what = format!("paper problem {id} (unit step costs)");
            mdp = problem_mdp(&owned);
            bytes = None;
            let origin = Origin::Paper {
                id,
                step: StepCost::Unit,
            };
            record = problem_record(origin, None, None, || mdp.clone())?;
            problem = &owned;
            x1 = owned.initial();
        }
        Single::Env {
            spec,
            problem: p,
            mdp: m,
            initial,
        } => {
            let safe: String = spec
                .chars()
                .map(|c| if c.is_ascii_alphanumeric() { c } else { '_' })
                .collect();
            name = format!("env-{safe}.cert.json");
            what = format!("environment {}", crate::echo::echo(spec));
            record = problem_record(Origin::Env(spec), None, None, || m.clone())?;
            mdp = m;
            bytes = None;
            problem = p;
            x1 = initial;
        }
    }
    let identity = match &bytes {
        Some(b) => Identity::FileBytes(b),
        None => Identity::Canonical,
    };
    let c = certify_optimum(problem, &mdp, identity, &record, &what)?;
    let g = at_initial(&c, x1, l_star, &what)?;
    write(dir, &name, &c.text)?;
    Ok(Certificates {
        dir: dir.display().to_string(),
        written: vec![Written {
            certificate: name,
            problem_file,
            objective: "deterministic",
            certifies: format!("deterministic G* of {what} (G*(x1) = {g}, x1 = state {x1})"),
            states: c.acceptance.states,
        }],
        not_certified: "the bonus sets and Lav(C^), the least mean cost of a goal-avoiding cycle"
            .into(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dir() -> tempfile::TempDir {
        tempfile::tempdir().unwrap()
    }

    /// C1's counterexample problem (`0: ->0 (0), ->1 (1); 1 (goal)`): `G* = (1, 0)`.
    const PROBLEM: &str = r#"{"format": "truecost-problem/1", "states": 2, "initial": 0, "goals": [1],
        "actions": [[{"to": 0, "cost": "0"}, {"to": 1, "cost": "1"}], []]}"#;

    #[test]
    fn a_counterexample_is_certified_with_its_printed_l_star() {
        let d = dir();
        let w = counterexample(d.path(), "C1", "c1", PROBLEM, Some("1")).unwrap();
        assert_eq!(w.certificate, "c1.cert.json");
        assert!(w.certifies.contains("G*(x1) = 1"), "{}", w.certifies);
        let cert =
            certificate::parse(&std::fs::read_to_string(d.path().join("c1.cert.json")).unwrap())
                .unwrap();
        let one = Rational::one();
        assert_eq!(cert.values, vec![Some(one), Some(Rational::zero())]);
        assert_eq!(cert.policy, vec![Some(1), None]);
    }

    /// A printed `L*` that is not the certified `G*(x1)` (a planted wrong number) is an error,
    /// and no certificate is written.
    #[test]
    fn a_printed_l_star_that_is_not_g_star_is_an_error() {
        let d = dir();
        let e = counterexample(d.path(), "C1", "c1", PROBLEM, Some("2")).unwrap_err();
        assert!(e.contains("G*(x1) = 1") && e.contains("L* = 2"), "{e}");
        assert!(!d.path().join("c1.cert.json").exists());
    }

    /// The re-check before writing refuses a wrong value (a planted solver bug: `G*(0) = 2`).
    #[test]
    fn the_recheck_rejects_a_wrong_optimum() {
        let (_, mdp) = read_problem_file(PROBLEM).unwrap();
        let record = ProblemRecord {
            source: "file".into(),
            name: "p.json".into(),
            gamma: None,
            noise: None,
            step_cost: None,
            sha256: certificate::sha256_hex(PROBLEM.as_bytes()),
            sha256_of: "file bytes".into(),
            goal_label: None,
            cost_reward: None,
        };
        let objective = CertifiedObjective::Deterministic;
        let identity = Identity::FileBytes(PROBLEM.as_bytes());
        let good = certificate::write(
            &objective,
            &record,
            vec!["1".into(), "0".into()],
            &[Some(1), None],
        );
        assert!(accepted(good, &mdp, identity, "p").is_ok());
        let bad = certificate::write(
            &objective,
            &record,
            vec!["2".into(), "0".into()],
            &[Some(1), None],
        );
        let e = accepted(bad, &mdp, identity, "p").err().unwrap();
        assert!(e.contains("rejected by truecost's checker"), "{e}");
    }

    /// Below `α*` the worked example's optimum stays at 0 (`−1/(1−α)`), above it goes up.
    #[test]
    fn the_worked_examples_optimum_changes_side_at_alpha_star() {
        let half = Rational::new(1.into(), 2.into());
        let (values, policy) = worked_example_optimum(&half).unwrap();
        assert_eq!(values[0], "-2");
        assert_eq!(policy[0], Some(0));
        let near_one = Rational::new(99.into(), 100.into());
        let (_, policy) = worked_example_optimum(&near_one).unwrap();
        assert_eq!(&policy[..5], &[Some(1); 5]);
        let up: Vec<Option<u64>> = policy.iter().map(|a| a.map(|a| a as u64)).collect();
        assert!(reaches_goal(&up));
        assert!(!reaches_goal(&[
            Some(0),
            Some(1),
            Some(1),
            Some(1),
            Some(1),
            None
        ]));
    }
}
