//! What a certificate records of the problem it certifies, and how it is written: the options
//! that rebuild the problem (the model as the checker reads it is
//! [`truecost::objectives::Model::mdp`]), shared by `solve --certificate` on every source and by `discount
//! --certificate`. Parsing and wiring only; the checker is [`truecost::certificate`].

use clap::ValueEnum;

use truecost::certificate::{sha256_hex, Mdp, ProblemRecord, CANONICAL_FORMAT};
use truecost::problems::StepCost;
use truecost::stochastic::NoiseModel;

/// Where a certified problem comes from: the options that rebuild it.
pub struct CertifiedSource<'a> {
    /// `--file`.
    pub file: Option<&'a std::path::Path>,
    /// `--problem`.
    pub problem: Option<usize>,
    /// `--env`.
    pub env: Option<&'a str>,
    /// `--step-cost`.
    pub step: Option<StepCost>,
    /// `--gamma`, as given.
    pub gamma: Option<&'a str>,
    /// `--noise`.
    pub noise: Option<NoiseModel>,
}

fn value_name<T: ValueEnum>(v: &T) -> String {
    v.to_possible_value()
        .expect("no skipped variants")
        .get_name()
        .to_string()
}

impl CertifiedSource<'_> {
    /// The certificate's record of this source: the file's SHA-256, or that of the model's
    /// canonical export (`model`, built only then).
    pub fn record(&self, model: impl FnOnce() -> Mdp) -> Result<ProblemRecord, String> {
        let gamma = self.gamma.map(str::to_string);
        let noise = gamma
            .as_ref()
            .map(|_| value_name(&self.noise.unwrap_or_default()));
        let canonical = |source: &str, name: String, step_cost: Option<String>| ProblemRecord {
            source: source.into(),
            name,
            gamma: gamma.clone(),
            noise: noise.clone(),
            step_cost,
            sha256: sha256_hex(model().canonical_text().as_bytes()),
            sha256_of: CANONICAL_FORMAT.into(),
        };
        Ok(match (self.file, self.problem, self.env) {
            (Some(path), _, _) => {
                let bytes = truecost::bounded::read_bytes(
                    path,
                    truecost::model::file::MAX_FILE_BYTES,
                    "problem files",
                )
                .map_err(|e| format!("--certificate hashes the problem file again: {e}"))?;
                ProblemRecord {
                    source: "file".into(),
                    name: path.display().to_string(),
                    gamma: gamma.clone(),
                    noise: noise.clone(),
                    step_cost: None,
                    sha256: sha256_hex(&bytes),
                    sha256_of: "file bytes".into(),
                }
            }
            (None, Some(id), _) => canonical(
                "problem",
                id.to_string(),
                Some(value_name(&self.step.unwrap_or_default())),
            ),
            (None, None, Some(spec)) => canonical("env", spec.to_string(), None),
            (None, None, None) => return Err("give --problem N, --file FILE or --env SPEC".into()),
        })
    }
}

/// Writes a certificate file whole (a temporary file, then a rename; one line on error).
pub fn write_certificate(path: &std::path::Path, text: &str) -> Result<(), String> {
    truecost::atomic::write(path, text.as_bytes())
}
