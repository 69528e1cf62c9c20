//! What a Python call names: an environment spec (`--env`), a problem file (`--file`), or a
//! problem file's text exported in memory by the Gymnasium importer. Each is turned into the
//! [`Model`] the command line builds for the same input.

use std::path::PathBuf;

use truecost::model::file::FileObjective;
use truecost::objectives::{Model, Source};
use truecost::stochastic::file::{from_json_with_objective, read_with_objective, ProblemFile};
use truecost::stochastic::{NoiseModel, Predictability, StochasticProblem};

/// The input of a call.
pub enum Input {
    /// `--env SPEC`: one of the benchmarks truecost builds itself.
    Env(String),
    /// `--file FILE`.
    File(PathBuf),
    /// A problem file's text (`truecost-stochastic/1`), with the name reports give it.
    Text {
        /// The JSON text.
        json: String,
        /// The model's name.
        name: String,
    },
}

fn text(e: impl ToString) -> String {
    e.to_string()
}

impl Input {
    /// The input of the Python layer's `(kind, text, name)`: kind `env`, `file` or `json`.
    pub fn new(kind: &str, text: String, name: Option<String>) -> Result<Self, String> {
        match kind {
            "env" => Ok(Input::Env(text)),
            "file" => Ok(Input::File(PathBuf::from(text))),
            "json" => Ok(Input::Text {
                json: text,
                name: name.unwrap_or_else(|| "exported environment".into()),
            }),
            other => Err(format!(
                "unknown input kind {} (env, file, json)",
                truecost::echo::echo(other)
            )),
        }
    }

    /// The problem file of [`Input::File`] or [`Input::Text`] and its name (`None` for an
    /// environment).
    fn problem_file(&self) -> Result<Option<(ProblemFile, FileObjective, String)>, String> {
        Ok(match self {
            Input::Env(_) => None,
            Input::File(path) => {
                let (file, extra) = read_with_objective(path).map_err(text)?;
                Some((file, extra, format!("file {}", path.display())))
            }
            Input::Text { json, name } => {
                let (file, extra) = from_json_with_objective(json).map_err(text)?;
                Some((file, extra, name.clone()))
            }
        })
    }

    /// The model of `solve --objective` and `compare`: [`Source::load`] (a deterministic file
    /// with the paper's noise model at `γ = 1`, i.e. its moves as single outcomes).
    pub fn model(&self) -> Result<Model, String> {
        match self {
            Input::Env(spec) => Source::Env(spec.clone()).load(),
            Input::File(path) => Source::File {
                path: path.clone(),
                noise: NoiseModel::default(),
                gamma: None,
                names: Default::default(),
            }
            .load(),
            Input::Text { json, name } => {
                let (file, extra) = from_json_with_objective(json).map_err(text)?;
                let problem = match file {
                    ProblemFile::Deterministic(d) => StochasticProblem::from_deterministic(
                        &d,
                        NoiseModel::default(),
                        &Predictability::one(),
                    )
                    .map_err(text)?,
                    ProblemFile::Stochastic(s) => *s,
                };
                Ok(Model::from_problem(problem, name.clone()).with_file_objective(&extra))
            }
        }
    }

    /// The model of `discount`: a deterministic file through
    /// [`Model::from_deterministic_file`] (moves into dead ends removed), everything else as
    /// [`Self::model`].
    pub fn discount_model(&self) -> Result<Model, String> {
        match self.problem_file()? {
            Some((ProblemFile::Deterministic(p), extra, name)) => {
                Model::from_deterministic_file(&p, name, &extra).map_err(text)
            }
            Some((ProblemFile::Stochastic(p), extra, name)) => {
                Ok(Model::from_problem(*p, name).with_file_objective(&extra))
            }
            None => self.model(),
        }
    }
}
