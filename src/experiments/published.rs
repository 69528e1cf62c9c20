//! The paper's published numbers beside ours.
//!
//! # Data
//!
//! `data/published/` ships the numbers of the paper's public CSV files (repository
//! `filkata123/valit_q_comparison`, `sims/`), compiled into the binary so that a fresh clone
//! needs nothing else: `deterministic.csv` and `stochastic.csv` hold one published metric per
//! line (the value and, where published, its population standard deviation, as the text of the
//! source file), `sources.csv` names for each source file the commit it was read at, the
//! machine that timed it and its number of samples. `data/published/README.md` says which file
//! feeds which row.
//!
//! # Verdicts ([`Verdict`])
//!
//! * `exact` — a count that is a pure function of the algorithm and the settings (reference
//!   mode, the paper's run length, a deterministic row: model-free planners, greedy ε = 0, and
//!   the π rows when the digit stream is in the paper's position) equals the published value
//!   **exactly** (our mean as an exact rational against the published decimal text). Unequal:
//!   `differs`.
//! * `consistent` — otherwise, for sampled metrics: a rate whose difference from the published
//!   rate lies within the 99 % two-sample binomial bound `z·√(p̄(1−p̄)(1/n₁+1/n₂))` (pooled `p̄`,
//!   `z = 2.5758`); a mean whose difference lies within the 99 % two-sample bound
//!   `t·√(s²(1/n₁+1/n₂))` with the pooled variance `s² = (n₁s₁²+n₂s₂²)/(n₁+n₂)` (population
//!   standard deviations, as published; pooling keeps the bound sound when we ran few
//!   samples) and `t` Student's 99 % quantile with `n₁+n₂−2` degrees of freedom ([`t99`]; it
//!   is `z` in the limit, and matters for means over the few runs that reached an event, see
//!   [`conditional_samples`]). Extremes (shortest and longest path) and flags have no sampling tolerance:
//!   equal is `consistent`.
//! * `differs` — outside those bounds, or one side has no value; the difference is given.
//! * `machine` — run times: the ratio ours / published, and for run times the row's time
//!   relative to model-free Dijkstra's on the same problem, published and ours, so the
//!   *relative* finding compares across machines.

use std::collections::BTreeMap;

use num_traits::ToPrimitive;
use serde::Serialize;

use crate::value::{parse_rational, Rational};

/// The 99 % two-sided normal quantile.
pub const Z99: f64 = 2.5758;

/// Student's two-sided 99 % quantile `t₀.₉₉₅(df)` (tabulated to 3 decimals; between table
/// entries interpolated linearly in `1/df`; [`Z99`] beyond).
///
/// ```
/// use truecost::experiments::published::{t99, Z99};
/// assert_eq!(t99(6), 3.707);
/// assert!(t99(198) > Z99 && t99(198) < 2.617);
/// assert!(t99(0).is_infinite());
/// ```
pub fn t99(df: u64) -> f64 {
    const TABLE: [(u64, f64); 34] = [
        (1, 63.657),
        (2, 9.925),
        (3, 5.841),
        (4, 4.604),
        (5, 4.032),
        (6, 3.707),
        (7, 3.499),
        (8, 3.355),
        (9, 3.250),
        (10, 3.169),
        (11, 3.106),
        (12, 3.055),
        (13, 3.012),
        (14, 2.977),
        (15, 2.947),
        (16, 2.921),
        (17, 2.898),
        (18, 2.878),
        (19, 2.861),
        (20, 2.845),
        (21, 2.831),
        (22, 2.819),
        (23, 2.807),
        (24, 2.797),
        (25, 2.787),
        (26, 2.779),
        (27, 2.771),
        (28, 2.763),
        (29, 2.756),
        (30, 2.750),
        (40, 2.704),
        (60, 2.660),
        (120, 2.617),
        (u64::MAX, Z99),
    ];
    if df == 0 {
        return f64::INFINITY;
    }
    let k = TABLE
        .iter()
        .position(|&(d, _)| d >= df)
        .expect("the last entry is unbounded");
    let (d1, t1) = TABLE[k];
    if d1 == df || k == 0 {
        return t1;
    }
    let (d0, t0) = TABLE[k - 1];
    let inv = |d: u64| if d == u64::MAX { 0.0 } else { 1.0 / d as f64 };
    let w = (inv(d0) - inv(df)) / (inv(d0) - inv(d1));
    t0 + w * (t1 - t0)
}

const DETERMINISTIC_CSV: &str = include_str!("../../data/published/deterministic.csv");
const STOCHASTIC_CSV: &str = include_str!("../../data/published/stochastic.csv");
const SOURCES_CSV: &str = include_str!("../../data/published/sources.csv");

/// The repository the published numbers come from.
pub const REPOSITORY: &str = "github.com/filkata123/valit_q_comparison";

/// A source file of published numbers.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct Source {
    /// Path in [`REPOSITORY`].
    pub file: String,
    /// The commit it was read at (the last one that changed it).
    pub commit: String,
    /// The machine that timed it.
    pub machine: String,
    /// Samples per row.
    pub samples: u64,
}

/// One published metric.
#[derive(Clone, Debug, PartialEq)]
pub struct PublishedValue {
    /// The text as published.
    pub text: String,
    /// Its exact value.
    pub value: Rational,
    /// The published population standard deviation, if any.
    pub std: Option<f64>,
    /// Samples behind it.
    pub samples: u64,
    /// Index into [`Published::sources`].
    pub source: usize,
}

impl PublishedValue {
    /// The value as the nearest `f64` (for display and statistical bounds only).
    pub fn approx(&self) -> f64 {
        self.value.to_f64().unwrap_or(f64::NAN)
    }
}

/// A row key of the published tables: the problem, then the row's words (deterministic:
/// algorithm and ε; stochastic: γ, algorithm, ρ, ε), numbers as exact rationals so that
/// `0.90` and `0.9` agree.
pub type RowKey = (usize, Vec<KeyPart>);

/// One word of a row key.
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum KeyPart {
    /// A name.
    Name(String),
    /// A number.
    Number(Rational),
    /// Not applicable.
    None,
}

impl KeyPart {
    /// A number when the text is one, else a name; empty text is [`KeyPart::None`].
    pub fn parse(text: &str) -> KeyPart {
        let t = text.trim();
        if t.is_empty() {
            return KeyPart::None;
        }
        match parse_rational(t) {
            Ok(r) => KeyPart::Number(r),
            Err(_) => KeyPart::Name(t.to_string()),
        }
    }
}

/// The published numbers of one experiment.
#[derive(Clone, Debug, PartialEq)]
pub struct Published {
    /// Every source file.
    pub sources: Vec<Source>,
    /// Row → metric → value.
    pub rows: BTreeMap<RowKey, BTreeMap<String, PublishedValue>>,
}

/// Why the shipped data could not be read (a damaged checkout; one line).
#[derive(Debug, thiserror::Error)]
#[error("published data {file}, line {line}: {message}")]
pub struct DataError {
    file: &'static str,
    line: usize,
    message: String,
}

fn sources() -> Result<Vec<Source>, DataError> {
    let err = |line, message: String| DataError {
        file: "sources.csv",
        line,
        message,
    };
    let mut out = Vec::new();
    for (i, l) in SOURCES_CSV.lines().enumerate().skip(1) {
        let f: Vec<&str> = l.split(',').collect();
        if f.len() != 4 {
            return Err(err(i + 1, format!("{} fields, expected 4", f.len())));
        }
        out.push(Source {
            file: f[0].into(),
            commit: f[1].into(),
            machine: f[2].into(),
            samples: f[3]
                .parse()
                .map_err(|_| err(i + 1, format!("samples {:?}", f[3])))?,
        });
    }
    Ok(out)
}

/// Reads a long-format file: `problem, key words…, metric, value, std, file`.
fn read(text: &str, file: &'static str, key_words: usize) -> Result<Published, DataError> {
    let sources = sources()?;
    let mut rows: BTreeMap<RowKey, BTreeMap<String, PublishedValue>> = BTreeMap::new();
    let width = key_words + 5;
    for (i, l) in text.lines().enumerate().skip(1) {
        let err = |message: String| DataError {
            file,
            line: i + 1,
            message,
        };
        let f: Vec<&str> = l.split(',').collect();
        if f.len() != width {
            return Err(err(format!("{} fields, expected {width}", f.len())));
        }
        let problem: usize = f[0]
            .parse()
            .map_err(|_| err(format!("problem {:?}", f[0])))?;
        let key: Vec<KeyPart> = f[1..=key_words].iter().map(|t| KeyPart::parse(t)).collect();
        let metric = f[key_words + 1];
        let text = f[key_words + 2];
        let value = parse_rational(text).map_err(|e| err(e.to_string()))?;
        let std = match f[key_words + 3] {
            "" => None,
            s => Some(
                parse_rational(s)
                    .map_err(|e| err(e.to_string()))?
                    .to_f64()
                    .unwrap_or(f64::NAN),
            ),
        };
        let source = sources
            .iter()
            .position(|s| s.file == f[key_words + 4])
            .ok_or_else(|| err(format!("unknown source {}", f[key_words + 4])))?;
        let previous = rows.entry((problem, key)).or_default().insert(
            metric.to_string(),
            PublishedValue {
                text: text.to_string(),
                value,
                std,
                samples: sources[source].samples,
                source,
            },
        );
        if previous.is_some() {
            return Err(err(format!("metric {metric} given twice")));
        }
    }
    Ok(Published { sources, rows })
}

/// The published deterministic rows; key words: algorithm, ε (empty for planners; `1` for
/// ε-decay, its first episode's ε).
///
/// ```
/// use truecost::experiments::published::{deterministic, KeyPart};
/// let p = deterministic().unwrap();
/// let key = (10, vec![KeyPart::parse("model-free-dijkstra"), KeyPart::None]);
/// assert_eq!(p.rows[&key]["mean_actions"].text, "4423.0");
/// ```
pub fn deterministic() -> Result<Published, DataError> {
    read(DETERMINISTIC_CSV, "deterministic.csv", 2)
}

/// The published stochastic rows; key words: γ, algorithm, ρ, ε (empty for VI).
///
/// ```
/// use truecost::experiments::published::{stochastic, KeyPart};
/// let p = stochastic().unwrap();
/// let key = (10, ["0.999", "stochastic-async-vi", "", ""].map(KeyPart::parse).to_vec());
/// assert_eq!(p.rows[&key]["mean_actions"].text, "178292.0");
/// ```
pub fn stochastic() -> Result<Published, DataError> {
    read(STOCHASTIC_CSV, "stochastic.csv", 4)
}

/// What kind of quantity a metric is (decides its verdict rule).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// A wall time (`machine`).
    Time,
    /// A fraction of samples.
    Rate,
    /// A mean over samples (with a standard deviation).
    Mean,
    /// An extreme over samples or a flag: no sampling tolerance.
    Extreme,
}

/// Our side of a metric.
#[derive(Clone, Debug, PartialEq)]
pub struct Observed {
    /// Samples behind it.
    pub n: u64,
    /// The value (for display and statistical bounds).
    pub mean: f64,
    /// Population standard deviation over the samples.
    pub std: f64,
    /// The exact value, for counts.
    pub exact: Option<Rational>,
}

/// Our side of a row's published metrics, collected from its samples by name (the deterministic
/// and stochastic runners' `observe` share it; each knows its own `Sample` type).
pub struct Observations<'a, S> {
    samples: &'a [S],
    metrics: BTreeMap<&'static str, Observed>,
}

impl<'a, S> Observations<'a, S> {
    /// No metric yet, over `samples`.
    pub fn new(samples: &'a [S]) -> Self {
        Observations {
            samples,
            metrics: BTreeMap::new(),
        }
    }

    /// The number of samples.
    pub fn n(&self) -> u64 {
        self.samples.len() as u64
    }

    /// How many samples satisfy `pred`.
    pub fn hits(&self, pred: impl Fn(&S) -> bool) -> u64 {
        self.samples.iter().filter(|s| pred(s)).count() as u64
    }

    /// Records `metric` when there is a value.
    pub fn put(&mut self, metric: &'static str, value: Option<Observed>) {
        if let Some(v) = value {
            self.metrics.insert(metric, v);
        }
    }

    /// The exact mean of the counts that `get` gives (samples without one left out).
    pub fn count(&mut self, metric: &'static str, get: impl Fn(&S) -> Option<u64>) {
        let v: Vec<u64> = self.samples.iter().filter_map(get).collect();
        self.put(metric, Observed::counts(&v));
    }

    /// The mean of the times that `get` gives.
    pub fn time(&mut self, metric: &'static str, get: impl Fn(&S) -> Option<f64>) {
        let v: Vec<f64> = self.samples.iter().filter_map(get).collect();
        self.put(metric, Observed::times(&v));
    }

    /// The fraction of samples satisfying `pred`.
    pub fn rate(&mut self, metric: &'static str, pred: impl Fn(&S) -> bool) {
        let (hits, n) = (self.hits(pred), self.n());
        self.put(metric, Observed::rate(hits, n));
    }

    /// The metrics collected.
    pub fn finish(self) -> BTreeMap<&'static str, Observed> {
        self.metrics
    }
}

impl Observed {
    /// The mean of integer counts, exact (`None` for no samples).
    ///
    /// ```
    /// use truecost::experiments::published::Observed;
    /// let o = Observed::counts(&[1, 2]).unwrap();
    /// assert_eq!((o.mean, o.std, o.n), (1.5, 0.5, 2));
    /// assert_eq!(o.exact.unwrap().to_string(), "3/2");
    /// ```
    pub fn counts(values: &[u64]) -> Option<Observed> {
        let n = values.len() as u64;
        if n == 0 {
            return None;
        }
        let sum: u128 = values.iter().map(|&v| u128::from(v)).sum();
        let exact = Rational::new(sum.into(), u128::from(n).into());
        let floats: Vec<f64> = values.iter().map(|&v| v as f64).collect();
        let (mean, std) = super::stats::mean_std(&floats)?;
        Some(Observed {
            n,
            mean,
            std,
            exact: Some(exact),
        })
    }

    /// The mean of times (no exact value).
    pub fn times(values: &[f64]) -> Option<Observed> {
        let (mean, std) = super::stats::mean_std(values)?;
        Some(Observed {
            n: values.len() as u64,
            mean,
            std,
            exact: None,
        })
    }

    /// `hits / n`, exact.
    pub fn rate(hits: u64, n: u64) -> Option<Observed> {
        (n > 0).then(|| {
            let p = hits as f64 / n as f64;
            Observed {
                n,
                mean: p,
                std: (p * (1.0 - p)).sqrt(),
                exact: Some(Rational::new(hits.into(), n.into())),
            }
        })
    }

    /// One exact integer (an extreme or a flag) over `n` samples.
    pub fn value(v: u64, n: u64) -> Observed {
        Observed {
            n,
            mean: v as f64,
            std: 0.0,
            exact: Some(Rational::from_integer(v.into())),
        }
    }
}

/// The verdict on one metric.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(tag = "verdict", rename_all = "kebab-case")]
pub enum Verdict {
    /// Equal, exactly.
    Exact,
    /// Within the stated statistical tolerance.
    Consistent {
        /// `|ours − published|`.
        difference: f64,
        /// The 99 % bound it is within (0 for extremes and flags).
        bound: f64,
    },
    /// Not equal (exact comparisons) or outside the bound.
    Differs {
        /// `ours − published` (`null` when one side has no value).
        difference: Option<f64>,
        /// Why, in words.
        reason: String,
    },
    /// A wall time on another machine.
    Machine {
        /// Ours / published.
        ratio: Option<f64>,
        /// Published time of the row / published time of model-free Dijkstra (run times).
        relative_published: Option<f64>,
        /// Our time of the row / our time of model-free Dijkstra (run times).
        relative_ours: Option<f64>,
    },
}

impl Verdict {
    /// `exact`, `consistent`, `differs` or `machine`.
    pub fn name(&self) -> &'static str {
        match self {
            Verdict::Exact => "exact",
            Verdict::Consistent { .. } => "consistent",
            Verdict::Differs { .. } => "differs",
            Verdict::Machine { .. } => "machine",
        }
    }
}

/// The verdict in words, with its numbers — as every report format prints it.
///
/// ```
/// use truecost::experiments::published::Verdict;
/// let v = Verdict::Consistent { difference: 0.01, bound: 0.12 };
/// assert_eq!(v.to_string(), "consistent (|Δ| 0.0100 ≤ 0.1200)");
/// let m = Verdict::Machine { ratio: Some(0.5), relative_published: Some(135.0), relative_ours: None };
/// assert_eq!(m.to_string(), "machine (ours/published 0.500); ÷ model-free Dijkstra: published 135.0×, ours –");
/// ```
impl std::fmt::Display for Verdict {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let times = |x: Option<f64>| x.map_or("–".into(), |x| format!("{x:.1}×"));
        match self {
            Verdict::Exact => write!(f, "exact"),
            Verdict::Consistent { difference, bound } => {
                write!(f, "consistent (|Δ| {difference:.4} ≤ {bound:.4})")
            }
            Verdict::Differs { difference, reason } => write!(
                f,
                "differs (Δ {}; {reason})",
                difference.map_or("–".into(), |d| format!("{d:+.4}"))
            ),
            Verdict::Machine {
                ratio,
                relative_published,
                relative_ours,
            } => {
                write!(
                    f,
                    "machine (ours/published {})",
                    ratio.map_or("–".into(), |r| format!("{r:.3}"))
                )?;
                if relative_published.is_some() || relative_ours.is_some() {
                    write!(
                        f,
                        "; ÷ model-free Dijkstra: published {}, ours {}",
                        times(*relative_published),
                        times(*relative_ours)
                    )?;
                }
                Ok(())
            }
        }
    }
}

/// Judges one non-time metric (see the module documentation). `exact_comparable`: the row is a
/// pure function of the settings, and the settings are the published ones.
///
/// ```
/// use truecost::experiments::published::{judge, Kind, Observed, PublishedValue, Verdict};
/// use truecost::value::parse_rational;
/// let published = |t: &str, std| PublishedValue { text: t.into(), value: parse_rational(t).unwrap(),
///     std, samples: 100, source: 0 };
/// let ours = Observed::counts(&[4423]).unwrap();
/// assert_eq!(judge(Kind::Mean, &published("4423.0", Some(0.0)), Some(&ours), true), Verdict::Exact);
/// assert_eq!(judge(Kind::Mean, &published("4424.0", Some(0.0)), Some(&ours), true).name(), "differs");
/// // 70 of 100 against 5 of 10: the difference 0.2 is within the 99 % bound.
/// let rate = Observed::rate(5, 10).unwrap();
/// assert_eq!(judge(Kind::Rate, &published("0.7", None), Some(&rate), false).name(), "consistent");
/// let rate = Observed::rate(0, 10).unwrap();
/// assert_eq!(judge(Kind::Rate, &published("1.0", None), Some(&rate), false).name(), "differs");
/// ```
pub fn judge(
    kind: Kind,
    published: &PublishedValue,
    ours: Option<&Observed>,
    exact_comparable: bool,
) -> Verdict {
    let Some(ours) = ours else {
        return Verdict::Differs {
            difference: None,
            reason: "ours has no value".into(),
        };
    };
    let p = published.approx();
    let difference = ours.mean - p;
    let differs = |reason: String| Verdict::Differs {
        difference: Some(difference),
        reason,
    };
    let exact_equal = ours.exact.as_ref() == Some(&published.value);
    if kind != Kind::Time && exact_comparable && ours.exact.is_some() {
        return if exact_equal {
            Verdict::Exact
        } else {
            differs("a count of the published settings, not equal".into())
        };
    }
    match kind {
        Kind::Time => Verdict::Machine {
            ratio: (p > 0.0).then(|| ours.mean / p),
            relative_published: None,
            relative_ours: None,
        },
        Kind::Extreme => {
            if exact_equal {
                Verdict::Consistent {
                    difference: 0.0,
                    bound: 0.0,
                }
            } else {
                differs("an extreme or flag over samples, not equal".into())
            }
        }
        Kind::Rate => {
            let (n1, n2) = (ours.n as f64, published.samples as f64);
            let pooled = (ours.mean * n1 + p * n2) / (n1 + n2);
            let bound = Z99 * (pooled * (1.0 - pooled) * (1.0 / n1 + 1.0 / n2)).sqrt();
            within(difference, bound, exact_equal, "99 % binomial")
        }
        Kind::Mean => {
            let s2 = published.std.unwrap_or(0.0);
            let (n1, n2) = (ours.n as f64, published.samples as f64);
            // Pooled variance: robust when we ran few samples (their spread says little).
            let pooled = (n1 * ours.std * ours.std + n2 * s2 * s2) / (n1 + n2);
            let df = (ours.n + published.samples).saturating_sub(2);
            let bound = t99(df) * (pooled * (1.0 / n1 + 1.0 / n2)).sqrt();
            within(difference, bound, exact_equal, "99 % two-sample")
        }
    }
}

fn within(difference: f64, bound: f64, exact_equal: bool, what: &str) -> Verdict {
    if exact_equal || difference.abs() <= bound {
        Verdict::Consistent {
            difference: difference.abs(),
            bound,
        }
    } else {
        Verdict::Differs {
            difference: Some(difference),
            reason: format!("outside the {what} bound {bound:.6}"),
        }
    }
}

/// Published metrics and verdicts of one row (JSON `published` and `agreement`).
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Comparison {
    /// Metric → published value.
    pub published: BTreeMap<String, f64>,
    /// Metric → verdict.
    pub agreement: BTreeMap<String, Verdict>,
    /// Metric → our value (for side-by-side tables).
    #[serde(skip)]
    pub ours: BTreeMap<String, Option<f64>>,
    /// Metric → published text (for side-by-side tables).
    #[serde(skip)]
    pub published_text: BTreeMap<String, String>,
}

/// The published samples behind a mean taken over the samples that reached an event (the
/// paper's code averages the convergence action over the converged runs only): the published
/// rate of that event times the samples (`docs/reproduction.md`). Counting all samples would
/// make the statistical bound too narrow: Problem 12's ε-decay convergence action rests on the
/// 4 converged runs of 100.
///
/// ```
/// use std::collections::BTreeMap;
/// use truecost::experiments::published::{conditional_samples, PublishedValue};
/// use truecost::value::parse_rational;
/// let v = |t: &str| PublishedValue { text: t.into(), value: parse_rational(t).unwrap(),
///     std: None, samples: 100, source: 0 };
/// let row = BTreeMap::from([("convergence_rate".to_string(), v("0.04")),
///     ("mean_actions_converged".to_string(), v("346250.0"))]);
/// assert_eq!(conditional_samples("mean_actions_converged", &row["mean_actions_converged"], &row).samples, 4);
/// assert_eq!(conditional_samples("mean_actions", &row["mean_actions_converged"], &row).samples, 100);
/// ```
pub fn conditional_samples(
    metric: &str,
    value: &PublishedValue,
    row: &BTreeMap<String, PublishedValue>,
) -> PublishedValue {
    let event = match metric {
        "mean_actions_converged" => "convergence_rate",
        "mean_actions_initial_within" | "mean_time_initial_within_s" => "initial_within_rate",
        _ => return value.clone(),
    };
    let Some(rate) = row.get(event) else {
        return value.clone();
    };
    let reached = (rate.value.clone() * Rational::from_integer(value.samples.into()))
        .round()
        .to_integer();
    let samples = u64::try_from(reached)
        .unwrap_or(value.samples)
        .clamp(1, value.samples);
    PublishedValue {
        samples,
        ..value.clone()
    }
}

/// Compares one row: every published metric against `ours(metric)`; `kind(metric)` decides
/// the rule. Metrics we do not measure at all (`kind` is `None`) are left out.
pub fn compare_row(
    published: &BTreeMap<String, PublishedValue>,
    kind: impl Fn(&str) -> Option<Kind>,
    ours: impl Fn(&str) -> Option<Observed>,
    exact_comparable: bool,
) -> Comparison {
    let mut c = Comparison::default();
    for (metric, value) in published {
        let Some(k) = kind(metric) else { continue };
        let o = ours(metric);
        let value = &conditional_samples(metric, value, published);
        c.published.insert(metric.clone(), value.approx());
        c.published_text.insert(metric.clone(), value.text.clone());
        c.ours.insert(metric.clone(), o.as_ref().map(|o| o.mean));
        c.agreement.insert(
            metric.clone(),
            judge(k, value, o.as_ref(), exact_comparable),
        );
    }
    c
}

impl Comparison {
    /// The run time (`mean_time_s`): published and ours.
    pub fn run_time(&self) -> (Option<f64>, Option<f64>) {
        (
            self.published.get("mean_time_s").copied(),
            self.ours.get("mean_time_s").copied().flatten(),
        )
    }

    /// Fills the relative run time of this row: its `mean_time_s` over model-free Dijkstra's
    /// (`dijkstra`: published and ours, from [`Comparison::run_time`] of that row).
    pub fn relate_time(&mut self, dijkstra: (Option<f64>, Option<f64>)) {
        let (p, o) = self.run_time();
        if let Some(Verdict::Machine {
            relative_published,
            relative_ours,
            ..
        }) = self.agreement.get_mut("mean_time_s")
        {
            let ratio = |x: Option<f64>, d: Option<f64>| {
                x.zip(d).filter(|(_, d)| *d > 0.0).map(|(x, d)| x / d)
            };
            *relative_published = ratio(p, dijkstra.0);
            *relative_ours = ratio(o, dijkstra.1);
        }
    }
}

/// The closing summary.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Summary {
    /// Metrics compared.
    pub compared: u64,
    /// `exact` verdicts.
    pub exact: u64,
    /// `consistent` verdicts.
    pub consistent: u64,
    /// `differs` verdicts.
    pub differs: u64,
    /// `machine` verdicts (run times).
    pub machine: u64,
    /// One line per `differs`.
    pub differs_lines: Vec<String>,
    /// The sources compared against.
    pub sources: Vec<Source>,
}

impl Summary {
    /// Counts the verdicts of a row labelled `row`.
    pub fn add(&mut self, row: &str, c: &Comparison) {
        for (metric, v) in &c.agreement {
            self.compared += 1;
            match v {
                Verdict::Exact => self.exact += 1,
                Verdict::Consistent { .. } => self.consistent += 1,
                Verdict::Machine { .. } => self.machine += 1,
                Verdict::Differs { difference, reason } => {
                    self.differs += 1;
                    let ours = c.ours.get(metric).copied().flatten();
                    self.differs_lines.push(format!(
                        "{row}, {metric}: published {}, ours {}, difference {} ({reason})",
                        c.published_text.get(metric).map_or("–", String::as_str),
                        ours.map_or("none".into(), |o| format!("{o}")),
                        difference.map_or("–".into(), |d| format!("{d:+}")),
                    ));
                }
            }
        }
    }

    /// The summary in lines of text.
    pub fn lines(&self) -> Vec<String> {
        let mut out = vec![format!(
            "Against published ({REPOSITORY}): {} metrics compared: {} exact, {} consistent, {} differs, {} machine (run times)",
            self.compared, self.exact, self.consistent, self.differs, self.machine
        )];
        for l in &self.differs_lines {
            out.push(format!("differs: {l}"));
        }
        out
    }
}
