//! What every experiment runner shares: the checks of the common settings (problems, samples,
//! run length, threads) and the worker pool the samples run in.

use crate::learning::q_learning::LearningError;
use crate::problems::ProblemError;

/// The most samples per row.
pub const MAX_SAMPLES: u32 = 1 << 20;
/// The most actions one learning run may take (episodes × max steps).
pub const MAX_ACTIONS_PER_RUN: u64 = 1 << 32;
/// The most worker threads (`--threads`: a huge count would spawn threads until the
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
    /// A shard would record more than `reproduce merge` reads.
    #[error(
        "a shard of these settings records {sites} runs, at least {} MiB{}, above the {} MiB that `reproduce merge` reads{}; use fewer --samples or --problems",
        .bytes.div_ceil(1 << 20),
        if *.shards > 1 { format!(" for all {} shards together", .shards) } else { String::new() },
        .limit >> 20,
        if *.shards > 1 { "" } else { " from one shard file" }
    )]
    ShardTooLarge {
        /// Runs (sites) each shard file lists.
        sites: u64,
        /// Shards whose files a merge reads together (1: one file against the per-file limit).
        shards: u32,
        /// The least size in bytes.
        bytes: u64,
        /// The limit in bytes.
        limit: u64,
    },
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

/// The most sample runs a whole (unsharded) experiment keeps at once, unless one row has more
/// samples (then one row: the summary statistics of a row need all of its samples). Rows are
/// run in groups of consecutive rows of at most this many samples and summarised as each group
/// ends, so memory stays bounded by one group whatever `--samples` is (at [`MAX_SAMPLES`],
/// one row of about 150 bytes a sample, plus the π rows' row).
pub const GROUP_SAMPLES: u64 = 1 << 16;

/// The rows `0..rows` (each of `samples` samples) in groups of consecutive rows run together:
/// as many rows as [`GROUP_SAMPLES`] holds, at least one.
///
/// ```
/// use truecost::experiments::runs::row_groups;
/// assert_eq!(row_groups(5, 100), vec![0..5]);
/// assert_eq!(row_groups(3, 1 << 20), vec![0..1, 1..2, 2..3]);
/// assert_eq!(row_groups(5, 1 << 15), vec![0..2, 2..4, 4..5]);
/// ```
pub fn row_groups(rows: usize, samples: u32) -> Vec<std::ops::Range<usize>> {
    let per = (GROUP_SAMPLES / u64::from(samples.max(1))).max(1) as usize;
    (0..rows)
        .step_by(per)
        .map(|start| start..(start + per).min(rows))
        .collect()
}

/// The most samples a group of [`row_groups`] holds: what the memory of a whole run is
/// bounded by (per group of rows run at a time).
///
/// ```
/// use truecost::experiments::runs::{held_samples, MAX_SAMPLES};
/// assert_eq!(held_samples(16 * 10, 100), 16_000);
/// assert_eq!(held_samples(16 * 10, MAX_SAMPLES), 1 << 20);
/// ```
pub fn held_samples(rows: usize, samples: u32) -> u64 {
    row_groups(rows, samples)
        .iter()
        .map(|g| g.len() as u64 * u64::from(samples))
        .max()
        .unwrap_or(0)
}

/// How many of the items `0..total` shard `part` owns (`t mod N = K − 1`), without listing them.
///
/// ```
/// use truecost::claims::shard::Part;
/// use truecost::experiments::runs::owned;
/// let p = Part::parse("2/3").unwrap();
/// assert_eq!(owned(10, p), (0..10).filter(|&t| p.owns(t)).count() as u64);
/// assert_eq!(owned(0, p), 0);
/// ```
pub fn owned(total: u64, part: crate::claims::shard::Part) -> u64 {
    let (k, n) = (u64::from(part.k()), u64::from(part.n()));
    (total + n - k) / n
}

/// The least bytes a site takes in a shard file (the pretty-printed
/// `{"site": "sample run 0", "value": null}` with its indentation and comma).
pub const MIN_SITE_BYTES: u64 = 50;

/// Checks, before any run, that the files of a sharded run of `sites` sites can be merged:
/// every shard file lists every site, so one file takes at least `sites ×`
/// [`MIN_SITE_BYTES`] (at most [`crate::claims::shard::MAX_SHARD_BYTES`]) and the N files at
/// least N times that (at most [`crate::claims::shard::MAX_MERGE_BYTES`]).
///
/// ```
/// use truecost::claims::shard::Part;
/// use truecost::experiments::runs::check_shard_size;
/// assert!(check_shard_size(1000, Part::parse("1/2").unwrap()).is_ok());
/// let err = check_shard_size(16 * 10 << 20, Part::parse("1/2").unwrap()).unwrap_err();
/// assert!(err.to_string().contains("64 MiB"), "{err}");
/// ```
pub fn check_shard_size(sites: u64, part: crate::claims::shard::Part) -> Result<(), RunError> {
    use crate::claims::shard::{MAX_MERGE_BYTES, MAX_SHARD_BYTES};
    let one = sites.saturating_mul(MIN_SITE_BYTES);
    if one > MAX_SHARD_BYTES {
        return Err(RunError::ShardTooLarge {
            sites,
            shards: 1,
            bytes: one,
            limit: MAX_SHARD_BYTES,
        });
    }
    let all = one.saturating_mul(u64::from(part.n()));
    if all > MAX_MERGE_BYTES {
        return Err(RunError::ShardTooLarge {
            sites,
            shards: part.n(),
            bytes: all,
            limit: MAX_MERGE_BYTES,
        });
    }
    Ok(())
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
