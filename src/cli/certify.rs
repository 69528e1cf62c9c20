//! The options that name a certified problem, and how a certificate is written: parsing and
//! wiring only. The record itself is [`truecost::stochastic::record::problem_record`], the model
//! as the checker reads it [`truecost::objectives::Model::mdp`], the checker
//! [`truecost::certificate`].

use truecost::certificate::{Mdp, ProblemRecord};
use truecost::formats::drn::DrnNames;
use truecost::problems::StepCost;
use truecost::stochastic::record::{problem_record, Origin};
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
    /// `--goal-label` and `--cost-reward`, for a DRN file.
    pub names: DrnNames,
}

impl CertifiedSource<'_> {
    /// The certificate's record of this source ([`problem_record`]; `model` is built only for
    /// a paper problem or an environment).
    pub fn record(&self, model: impl FnOnce() -> Mdp) -> Result<ProblemRecord, String> {
        let origin = match (self.file, self.problem, self.env) {
            (Some(path), _, _) => Origin::File(path),
            (None, Some(id), _) => Origin::Paper {
                id,
                step: self.step.unwrap_or_default(),
            },
            (None, None, Some(spec)) => Origin::Env(spec),
            (None, None, None) => return Err("give --problem N, --file FILE or --env SPEC".into()),
        };
        let mut record = problem_record(origin, self.gamma, self.noise, model)?;
        record.goal_label.clone_from(&self.names.goal_label);
        record.cost_reward.clone_from(&self.names.cost_reward);
        Ok(record)
    }
}

/// Writes a certificate file whole (a temporary file, then a rename; one line on error).
pub fn write_certificate(path: &std::path::Path, text: &str) -> Result<(), String> {
    truecost::atomic::write(path, text.as_bytes())
}

/// Writes a certificate file whole as `write` streams it, without holding its text (hundreds
/// of megabytes at 10⁴ states) in memory: [`truecost::atomic::replace_with`]'s temporary file,
/// then a rename; a pipe or a terminal is written directly. The temporary's name is
/// unpredictable; the file written is created under it anew with `O_CREAT | O_EXCL` (which
/// follows no symbolic link and opens no file that exists), so nothing planted at that name in
/// the meantime is written through, and written around the page cache where the file system
/// allows it ([`truecost::atomic::DirectFile`]: through the page cache, the kernel's copy of
/// every byte costs as much as making the text). One line on error, naming the path; a pipe
/// closed by its reader is not an error (as for [`truecost::atomic::write`]).
pub fn write_certificate_with(
    path: &std::path::Path,
    write: impl FnOnce(&mut dyn std::io::Write) -> std::io::Result<()>,
) -> Result<(), String> {
    let failed = |e: std::io::Error| {
        format!(
            "cannot write {}: {e}",
            truecost::echo::echo(&path.display().to_string())
        )
    };
    truecost::atomic::replace_with(path, |target| {
        if target == path {
            // A pipe, a socket or a terminal.
            return match std::fs::OpenOptions::new()
                .write(true)
                .open(target)
                .and_then(|mut f| write(&mut f))
            {
                Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => Ok(()),
                other => other.map_err(failed),
            };
        }
        std::fs::remove_file(target).map_err(failed)?;
        let mut file = truecost::atomic::DirectFile::create(target).map_err(failed)?;
        write(&mut file).map_err(failed)?;
        file.finish().map(drop).map_err(failed)
    })
}
