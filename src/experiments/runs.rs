//! What every experiment runner shares: the checks of the common settings (problems, samples,
//! run length, threads) and the worker pool the samples run in.

use crate::learning::q_learning::LearningError;
use crate::problems::ProblemError;

/// The most samples per row.
pub const MAX_SAMPLES: u32 = 1 << 20;
/// The most actions one learning run may take (episodes × max steps).
pub const MAX_ACTIONS_PER_RUN: u64 = 1 << 32;
/// The most worker threads (`--threads`; issue 12: a huge count would spawn threads until the
/// system gives out).
pub const MAX_THREADS: usize = 256;

/// Why the common settings of an experiment are refused. Every message is one line.
#[derive(Debug, thiserror::Error)]
pub enum RunError {
    /// A bad problem id.
    #[error(transparent)]
    Problem(#[from] ProblemError),
    /// A problem listed twice.
    #[error("problem {0} is listed twice")]
    DuplicateProblem(usize),
    /// No problem.
    #[error("no problem given")]
    NoProblems,
    /// Samples out of range.
    #[error("the number of samples must be between 1 and {MAX_SAMPLES}, not {0}")]
    Samples(u32),
    /// A run would be too long.
    #[error(
        "episodes x max steps = {0} exceeds the limit of {MAX_ACTIONS_PER_RUN} actions per run"
    )]
    TooLong(u64),
    /// A bad learning parameter.
    #[error(transparent)]
    Learning(#[from] LearningError),
    /// The thread pool could not be built.
    #[error("cannot start {threads} worker threads: {message}")]
    Threads {
        /// Threads asked for.
        threads: usize,
        /// Why not.
        message: String,
    },
}

/// The settings every runner has.
#[derive(Clone, Copy, Debug)]
pub struct RunSettings<'a> {
    /// Paper problem ids, each at most once.
    pub problems: &'a [usize],
    /// Samples per row, `1..=MAX_SAMPLES`.
    pub samples: u32,
    /// Episodes per learning run, at least 1.
    pub episodes: u32,
    /// Steps per episode, at least 1.
    pub max_steps: u32,
    /// Worker threads (`None`: rayon's default), at least 1.
    pub threads: Option<usize>,
}

impl RunSettings<'_> {
    /// Checks the settings (one clear error for the first bad one).
    ///
    /// ```
    /// use truecost::experiments::runs::RunSettings;
    /// let ok = RunSettings { problems: &[0, 10], samples: 5, episodes: 10, max_steps: 10, threads: None };
    /// assert!(ok.validate().is_ok());
    /// let twice = RunSettings { problems: &[3, 3], ..ok };
    /// assert_eq!(twice.validate().unwrap_err().to_string(), "problem 3 is listed twice");
    /// assert!(RunSettings { threads: Some(0), ..ok }.validate().is_err());
    /// assert!(RunSettings { threads: Some(100_000), ..ok }.validate().is_err());
    /// ```
    pub fn validate(&self) -> Result<(), RunError> {
        if self.problems.is_empty() {
            return Err(RunError::NoProblems);
        }
        let count = crate::problems::paper_scenarios().len();
        for (i, &p) in self.problems.iter().enumerate() {
            if p >= count {
                return Err(ProblemError::Unknown {
                    id: p,
                    last: count - 1,
                }
                .into());
            }
            if self.problems[..i].contains(&p) {
                return Err(RunError::DuplicateProblem(p));
            }
        }
        if self.samples == 0 || self.samples > MAX_SAMPLES {
            return Err(RunError::Samples(self.samples));
        }
        if self.episodes == 0 {
            return Err(LearningError::NoEpisodes.into());
        }
        if self.max_steps == 0 {
            return Err(LearningError::NoSteps.into());
        }
        let total = u64::from(self.episodes) * u64::from(self.max_steps);
        if total > MAX_ACTIONS_PER_RUN {
            return Err(RunError::TooLong(total));
        }
        if self.threads == Some(0) {
            return Err(RunError::Threads {
                threads: 0,
                message: "at least one thread is needed".into(),
            });
        }
        if let Some(threads) = self.threads.filter(|&t| t > MAX_THREADS) {
            return Err(RunError::Threads {
                threads,
                message: format!("at most {MAX_THREADS} worker threads are supported"),
            });
        }
        Ok(())
    }
}

/// Checks the `RAYON_NUM_THREADS` environment variable (its value, if set) before any work:
/// rayon's global pool would otherwise try to start that many threads and fail late. Accepted:
/// `0` (rayon's default, one per core) up to [`MAX_THREADS`].
///
/// ```
/// use truecost::experiments::runs::check_thread_variable;
/// assert!(check_thread_variable(None).is_ok());
/// assert!(check_thread_variable(Some("2")).is_ok());
/// assert!(check_thread_variable(Some("100000")).unwrap_err().contains("at most 256"));
/// assert!(check_thread_variable(Some("many")).is_err());
/// ```
pub fn check_thread_variable(value: Option<&str>) -> Result<(), String> {
    let Some(value) = value else {
        return Ok(());
    };
    match value.trim().parse::<usize>() {
        Ok(n) if n <= MAX_THREADS => Ok(()),
        _ => Err(format!(
            "RAYON_NUM_THREADS={} is not a number of worker threads: 0 (one per core) to at most {MAX_THREADS}",
            crate::echo::echo(value)
        )),
    }
}

/// Runs `work` in a pool of `threads` workers (`None`: rayon's global pool).
///
/// ```
/// use truecost::experiments::runs::in_pool;
/// let n = in_pool(Some(2), rayon::current_num_threads).unwrap();
/// assert_eq!(n, 2);
/// ```
pub fn in_pool<T: Send>(
    threads: Option<usize>,
    work: impl FnOnce() -> T + Send,
) -> Result<T, RunError> {
    match threads {
        None => Ok(work()),
        Some(threads) => Ok(rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .map_err(|e| RunError::Threads {
                threads,
                message: e.to_string(),
            })?
            .install(work)),
    }
}

/// `1,2,3`: a list as the reports' titles print it.
///
/// ```
/// assert_eq!(truecost::experiments::runs::comma_list(&[16, 10]), "16,10");
/// ```
pub fn comma_list(items: &[usize]) -> String {
    items
        .iter()
        .map(|p| p.to_string())
        .collect::<Vec<_>>()
        .join(",")
}
