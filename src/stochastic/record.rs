//! What a certificate records of the problem it certifies ([`ProblemRecord`]): where the
//! problem comes from, how it was perturbed, and the SHA-256 `truecost check` compares with the
//! problem it rebuilds — of a problem file's bytes, or of the model's canonical export
//! ([`Mdp::canonical_text`]) for a paper problem or an environment. One function for every
//! writer of certificates (`solve`, `discount`, `reproduce`, `verify`).

use std::path::Path;

use clap::ValueEnum;

use super::NoiseModel;
use crate::certificate::{sha256_hex, Mdp, ProblemRecord, CANONICAL_FORMAT};
use crate::problems::StepCost;

/// Where a certified problem comes from: what `truecost check` rebuilds it from.
#[derive(Clone, Copy, Debug)]
pub enum Origin<'a> {
    /// A problem file (`--file`): its bytes are hashed.
    File(&'a Path),
    /// A paper problem (`--problem N`) with its step cost.
    Paper {
        /// The problem number.
        id: usize,
        /// The step cost of a grid move.
        step: StepCost,
    },
    /// An environment (`--env SPEC`, the text as given).
    Env(&'a str),
}

/// The name a value has on the command line (`unit`, `paper`, …).
fn value_name<T: ValueEnum>(v: &T) -> String {
    v.to_possible_value()
        .expect("no skipped variants")
        .get_name()
        .to_string()
}

/// The certificate's record of the problem from `origin`, perturbed by the noise model `noise`
/// (the default one when `None`) with predictability `gamma` (the text as given) when `gamma`
/// is given. The SHA-256 is that of the file's bytes, read again (at most
/// [`crate::model::file::MAX_FILE_BYTES`]), or that of `model`'s canonical export (`model` is
/// built only then). An unreadable file is one line.
///
/// ```
/// use truecost::certificate::sha256_hex;
/// use truecost::problems::StepCost;
/// use truecost::stochastic::record::{problem_record, Origin};
/// use truecost::stochastic::{certified::problem_mdp, grid::exact_grid, NoiseModel, Predictability};
///
/// let dir = std::env::temp_dir().join(format!("record-doctest-{}", std::process::id()));
/// std::fs::create_dir_all(&dir).unwrap();
/// let path = dir.join("g.json");
/// let text = r#"{"initial": 0, "goals": [1], "actions": [[{"to": 1, "cost": "1"}], []]}"#;
/// std::fs::write(&path, text).unwrap();
/// let r = problem_record(Origin::File(&path), None, None, || unreachable!()).unwrap();
/// assert_eq!((r.source.as_str(), r.sha256_of.as_str()), ("file", "file bytes"));
/// assert_eq!(r.sha256, sha256_hex(text.as_bytes()));
/// assert_eq!((r.gamma, r.noise), (None, None));
/// std::fs::remove_dir_all(&dir).unwrap();
///
/// // A paper problem at gamma 0.9: the canonical export's SHA-256, the default noise named.
/// let gamma = Predictability::parse("0.9").unwrap();
/// let p = exact_grid(3, StepCost::Unit, NoiseModel::default(), &gamma).unwrap();
/// let origin = Origin::Paper { id: 3, step: StepCost::Unit };
/// let r = problem_record(origin, Some("0.9"), None, || problem_mdp(&p)).unwrap();
/// assert_eq!((r.name.as_str(), r.step_cost.as_deref()), ("3", Some("unit")));
/// assert_eq!((r.gamma.as_deref(), r.noise.as_deref()), (Some("0.9"), Some("paper")));
/// assert_eq!(r.sha256, sha256_hex(problem_mdp(&p).canonical_text().as_bytes()));
/// ```
pub fn problem_record(
    origin: Origin<'_>,
    gamma: Option<&str>,
    noise: Option<NoiseModel>,
    model: impl FnOnce() -> Mdp,
) -> Result<ProblemRecord, String> {
    let gamma = gamma.map(str::to_string);
    let noise = gamma
        .as_ref()
        .map(|_| value_name(&noise.unwrap_or_default()));
    let canonical = |source: &str, name: String, step_cost: Option<String>| ProblemRecord {
        source: source.into(),
        name,
        gamma: gamma.clone(),
        noise: noise.clone(),
        step_cost,
        sha256: sha256_hex(model().canonical_text().as_bytes()),
        sha256_of: CANONICAL_FORMAT.into(),
        goal_label: None,
        cost_reward: None,
    };
    Ok(match origin {
        Origin::File(path) => {
            let bytes = crate::bounded::read_bytes(
                path,
                crate::model::file::MAX_FILE_BYTES,
                "problem files",
            )
            .map_err(|e| format!("the certificate hashes the problem file again: {e}"))?;
            ProblemRecord {
                source: "file".into(),
                name: path.display().to_string(),
                gamma: gamma.clone(),
                noise: noise.clone(),
                step_cost: None,
                sha256: sha256_hex(&bytes),
                sha256_of: "file bytes".into(),
                goal_label: None,
                cost_reward: None,
            }
        }
        Origin::Paper { id, step } => canonical("problem", id.to_string(), Some(value_name(&step))),
        Origin::Env(spec) => canonical("env", spec.to_string(), None),
    })
}
