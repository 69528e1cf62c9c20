//! Exploration plans (docs/spec.md §2) and the probabilities of ε-greedy exploration.
//!
//! An exploration plan says which action to apply when ε-greedy explores:
//!
//! * the **random plan** — a uniformly random action of `U(x)`, drawn from a seeded portable
//!   generator ([`ChaCha8Rng`], see [`sample_rng`]);
//! * the **π universal plan** — reads the [`PiStream`]: the digit stream `3, 0, 2, 1, 0, 0, 3, …`
//!   (the integer part of π followed by its base-4 fractional digits). Digit `d` applies the
//!   action at position `d` of the state's ordered action list `U(x)` (0-based); a digit
//!   `≥ |U(x)|` is skipped and the next digit is read. The plan therefore only ever applies the
//!   first four actions of a state, which covers every state of the paper's 4-neighbour grids.
//!
//! Coins (whether ε-greedy explores at a step) are exact: ε is a rational `p/q`
//! ([`Probability`]) and a coin is `uniform{0, …, q−1} < p`, drawn from the same generator as
//! the random plan. `ε = 0` and `ε = 1` draw no coin at all (the paper's "greedy" and "random"
//! policies).

use std::sync::Arc;

use num_bigint::BigInt;
use num_integer::Integer;
use num_traits::{One, Signed, ToPrimitive};
use rand::{Rng, RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

use crate::value::Rational;

/// Why a probability or a schedule of probabilities is not valid.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum ProbabilityError {
    /// Outside `[0, 1]`.
    #[error("{name} = {} is outside [0, 1]", crate::echo::echo(.value))]
    OutOfRange {
        /// The parameter's name (`ε`, …).
        name: &'static str,
        /// The value as text.
        value: String,
    },
    /// The exact value needs a denominator beyond 2^63.
    #[error("{name} = {} has a denominator too large for exact coins (at most 2^63)", crate::echo::echo(.value))]
    TooFine {
        /// The parameter's name.
        name: &'static str,
        /// The value as text.
        value: String,
    },
}

/// An exact probability `numerator / denominator ∈ [0, 1]` (reduced, denominator ≤ 2^63).
///
/// ```
/// use truecost::learning::plan::Probability;
/// use truecost::value::parse_rational;
/// let p = Probability::new("ε", &parse_rational("0.25").unwrap()).unwrap();
/// assert_eq!((p.numerator(), p.denominator()), (1, 4));
/// assert!(Probability::new("ε", &parse_rational("1.5").unwrap()).is_err());
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Probability {
    numerator: u64,
    denominator: u64,
}

/// The largest denominator a [`Probability`] may have.
const MAX_DENOMINATOR: u64 = 1 << 63;

impl Probability {
    /// Never.
    pub const ZERO: Probability = Probability {
        numerator: 0,
        denominator: 1,
    };
    /// Always.
    pub const ONE: Probability = Probability {
        numerator: 1,
        denominator: 1,
    };

    /// The probability `value`, checked to lie in `[0, 1]`; `name` is used in errors.
    pub fn new(name: &'static str, value: &Rational) -> Result<Self, ProbabilityError> {
        let text = || crate::value::Extended::Finite(value.clone()).to_string();
        if value.is_negative() || value > &Rational::one() {
            return Err(ProbabilityError::OutOfRange {
                name,
                value: text(),
            });
        }
        let (n, d) = (value.numer().to_u64(), value.denom().to_u64());
        match (n, d) {
            (Some(numerator), Some(denominator)) if denominator <= MAX_DENOMINATOR => {
                Ok(Probability {
                    numerator,
                    denominator,
                })
            }
            _ => Err(ProbabilityError::TooFine {
                name,
                value: text(),
            }),
        }
    }

    /// `p` in lowest terms.
    pub fn numerator(&self) -> u64 {
        self.numerator
    }

    /// `q` in lowest terms.
    pub fn denominator(&self) -> u64 {
        self.denominator
    }

    /// The exact value.
    pub fn to_rational(self) -> Rational {
        Rational::new(BigInt::from(self.numerator), BigInt::from(self.denominator))
    }

    /// The nearest `f64` (for display only).
    pub fn to_f64(self) -> f64 {
        self.numerator as f64 / self.denominator as f64
    }

    /// An exact coin: true with probability `p/q`. Draws nothing when `p ∈ {0, q}`.
    #[inline]
    pub fn flip(self, rng: &mut ChaCha8Rng) -> bool {
        if self.numerator == 0 {
            false
        } else if self.numerator == self.denominator {
            true
        } else {
            below(rng, self.denominator) < self.numerator
        }
    }
}

/// `rng.random_range(0..range)` for `u64`, `0 < range`, drawing the same words and returning the
/// same value as `rand`'s `UniformInt::<u64>::sample_single` (Canon's method with one extra
/// draw when the first is ambiguous), written out so that the learning loop inlines it: the
/// coin of every Q-learning action goes through here. The test
/// `below_is_rands_random_range` pins the equality for the locked `rand` version.
#[inline(always)]
fn below(rng: &mut ChaCha8Rng, range: u64) -> u64 {
    let wide = u128::from(rng.next_u64()) * u128::from(range);
    let (mut result, low) = ((wide >> 64) as u64, wide as u64);
    if low > range.wrapping_neg() {
        let next = (u128::from(rng.next_u64()) * u128::from(range)) >> 64;
        result += u64::from(low.checked_add(next as u64).is_none());
    }
    result
}

/// How ε varies over the episodes of a run (docs/spec.md §2).
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum EpsilonSchedule {
    /// The same ε in every episode.
    Constant(Probability),
    /// Linear decay: `ε_k = start + (end − start)·k/(E − 1)` in episode `k = 0, …, E − 1` of
    /// `E` episodes, exactly (so `ε_0 = start`, `ε_{E−1} = end`; `E = 1` uses `start`).
    Linear {
        /// ε in the first episode.
        start: Probability,
        /// ε in the last episode (the paper's ε-decay row ends at 0.1).
        end: Probability,
    },
    /// The paper's *code* (reference mode, docs/spec.md §7): `ε ← max(0.1, ε − δ)` in `f64` after every
    /// episode, from `ε = start`, with `δ = (start − 0.1)/E` — `q_learning_functions.py`'s
    /// `epsilon_delta = (epsilon - epsilon_min) / episodes` and
    /// `epsilon = max(epsilon_min, epsilon - epsilon_delta)`. So ε in episode `k` is about
    /// `start − (start − 0.1)·k/E`: 0.1009 in the last of 1000 episodes, where [`Self::Linear`]
    /// (the text) reaches 0.1. Each episode's coin is Python's `random.random() < ε`, whose
    /// probability is exactly `⌈ε·2^53⌉/2^53` ([`python_coin`]).
    CodeDecay {
        /// ε in the first episode.
        start: Probability,
    },
}

/// The floor of the paper's code's ε-decay (`epsilon_min = 0.1`).
const CODE_EPSILON_MIN: f64 = 0.1;

/// The exact probability of Python's coin `random.random() < eps`: `random()` returns `n/2^53`
/// with `n` uniform in `{0, …, 2^53 − 1}`, so the coin is true for the `⌈eps·2^53⌉` values of
/// `n` below `eps·2^53` (a product that is exact in `f64`). `eps` is clamped to `[0, 1]`.
///
/// ```
/// use truecost::learning::plan::python_coin;
/// let p = python_coin(0.5);
/// assert_eq!((p.numerator(), p.denominator()), (1, 2));
/// let q = python_coin(0.1); // 0.1 is 0x3FB999999999999A: 2^53·0.1 = 900719925474099.25
/// // ⌈…⌉ = 900719925474100 over 2^53, in lowest terms:
/// assert_eq!((q.numerator(), q.denominator()), (225179981368525, 1 << 51));
/// assert_eq!(python_coin(1.0), truecost::learning::plan::Probability::ONE);
/// ```
pub fn python_coin(eps: f64) -> Probability {
    const SCALE: u64 = 1 << 53;
    let scaled = (eps.clamp(0.0, 1.0) * SCALE as f64).ceil() as u64;
    let g = scaled.gcd(&SCALE);
    Probability {
        numerator: scaled / g,
        denominator: SCALE / g,
    }
}

/// The ε of the successive episodes of one run (what a learner reads at each episode's start).
///
/// ```
/// use truecost::learning::plan::{EpsilonSchedule, Probability, python_coin};
/// let mut e = EpsilonSchedule::CodeDecay { start: Probability::ONE }.episodes(1000);
/// assert_eq!(e.next_episode().unwrap(), Probability::ONE);
/// let second = e.next_episode().unwrap(); // 1 − 0.9/1000 in f64
/// assert_eq!(second, python_coin(1.0 - 0.9 / 1000.0));
/// ```
#[derive(Clone, Debug)]
pub struct Epsilons {
    schedule: EpsilonSchedule,
    episodes: u32,
    next: u32,
    /// The code's running `f64` ε ([`EpsilonSchedule::CodeDecay`] only).
    code_epsilon: f64,
    /// The code's `f64` decrement ([`EpsilonSchedule::CodeDecay`] only).
    code_delta: f64,
}

impl Epsilons {
    /// ε of the next episode (the first call gives episode 0's).
    pub fn next_episode(&mut self) -> Result<Probability, ProbabilityError> {
        let k = self.next;
        self.next = self.next.saturating_add(1);
        match &self.schedule {
            EpsilonSchedule::CodeDecay { .. } => {
                let p = python_coin(self.code_epsilon);
                self.code_epsilon = CODE_EPSILON_MIN.max(self.code_epsilon - self.code_delta);
                Ok(p)
            }
            other => other.at(k, self.episodes),
        }
    }
}

impl EpsilonSchedule {
    /// The paper's ε-decay row: from `start` down to 0.1 at the last episode.
    pub fn decay_to_one_tenth(start: Probability) -> Self {
        EpsilonSchedule::Linear {
            start,
            end: Probability {
                numerator: 1,
                denominator: 10,
            },
        }
    }

    /// The ε of the episodes of a run of `episodes` episodes, in order.
    pub fn episodes(&self, episodes: u32) -> Epsilons {
        let (code_epsilon, code_delta) = match self {
            EpsilonSchedule::CodeDecay { start } => {
                let s = start.to_f64();
                (s, (s - CODE_EPSILON_MIN) / f64::from(episodes.max(1)))
            }
            _ => (0.0, 0.0),
        };
        Epsilons {
            schedule: self.clone(),
            episodes,
            next: 0,
            code_epsilon,
            code_delta,
        }
    }

    /// ε in episode `k` of `episodes`, exactly.
    ///
    /// ```
    /// use truecost::learning::plan::{EpsilonSchedule, Probability};
    /// let s = EpsilonSchedule::decay_to_one_tenth(Probability::ONE);
    /// assert_eq!(s.at(0, 10).unwrap(), Probability::ONE);
    /// let last = s.at(9, 10).unwrap();
    /// assert_eq!((last.numerator(), last.denominator()), (1, 10));
    /// let mid = s.at(3, 10).unwrap(); // 1 − 0.9·3/9 = 7/10
    /// assert_eq!((mid.numerator(), mid.denominator()), (7, 10));
    /// ```
    pub fn at(&self, k: u32, episodes: u32) -> Result<Probability, ProbabilityError> {
        match self {
            EpsilonSchedule::Constant(p) => Ok(*p),
            EpsilonSchedule::Linear { start, end } => {
                if episodes <= 1 {
                    return Ok(*start);
                }
                let (s, e) = (start.to_rational(), end.to_rational());
                let t = Rational::new(BigInt::from(k), BigInt::from(episodes - 1));
                Probability::new("ε", &(&s + (e - &s) * t))
            }
            EpsilonSchedule::CodeDecay { .. } => {
                let mut run = self.episodes(episodes);
                let mut p = run.next_episode()?;
                for _ in 0..k {
                    p = run.next_episode()?;
                }
                Ok(p)
            }
        }
    }

    /// Checks that every episode's ε is representable (called once before a run).
    pub fn validate(&self, episodes: u32) -> Result<(), ProbabilityError> {
        if let EpsilonSchedule::Linear { start, end } = self {
            // Every ε_k has a denominator dividing lcm(q_s, q_e)·(E − 1).
            let d = BigInt::from(start.denominator).lcm(&BigInt::from(end.denominator))
                * BigInt::from(episodes.max(2) - 1);
            if d > BigInt::from(MAX_DENOMINATOR) {
                return Err(ProbabilityError::TooFine {
                    name: "ε (decay schedule)",
                    value: format!(
                        "{} → {} over {episodes} episodes",
                        start.to_f64(),
                        end.to_f64()
                    ),
                });
            }
        }
        Ok(())
    }

    /// The starting ε.
    pub fn start(&self) -> Probability {
        match self {
            EpsilonSchedule::Constant(p) => *p,
            EpsilonSchedule::Linear { start, .. } | EpsilonSchedule::CodeDecay { start } => *start,
        }
    }
}

/// The portable generator of one sample: [`ChaCha8Rng::seed_from_u64`]`(seed)` on stream
/// `stream` (a pure function of the experiment's seed and the sample's coordinates, so results
/// do not depend on scheduling or thread count).
///
/// ```
/// use rand::RngExt;
/// let mut a = truecost::learning::plan::sample_rng(7, 3);
/// let mut b = truecost::learning::plan::sample_rng(7, 3);
/// assert_eq!(a.random::<u64>(), b.random::<u64>());
/// ```
pub fn sample_rng(seed: u64, stream: u64) -> ChaCha8Rng {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    rng.set_stream(stream);
    rng
}

/// The period of the reference digit stream: the paper's code read the first 10^7 characters of
/// its digit file — "3" and 9 999 999 fractional base-4 digits — and wrapped around to the start
/// (docs/spec.md §7). Both modes use this stream, so a π run is defined for any number of actions.
pub const PI_STREAM_PERIOD: u64 = 10_000_000;

/// At least the first `count` fractional base-4 digits of π (capped at the stream's
/// `PI_STREAM_PERIOD − 1`), from the process-wide cache of [`crate::learning::pi::digits`],
/// which grows geometrically: asking for more digits than cached computes a prefix at least
/// twice as long, so reading a stream costs about as much as computing its longest prefix once.
///
/// ```
/// let d = truecost::learning::plan::pi_digits(8);
/// assert_eq!(&d[..8], &[0, 2, 1, 0, 0, 3, 3, 3]); // π = 3.0210 0333… (base 4)
/// ```
pub fn pi_digits(count: usize) -> Arc<Vec<u8>> {
    crate::learning::pi::digits(count.min((PI_STREAM_PERIOD - 1) as usize))
}

/// The π universal plan's position in the digit stream `3, d1, d2, …, d_{P−1}, 3, d1, …`
/// (`P` = [`PI_STREAM_PERIOD`]). One stream is shared by every π run of an experiment, in a
/// defined order (docs/spec.md §7).
#[derive(Clone, Debug)]
pub struct PiStream {
    position: u64,
    digits: Arc<Vec<u8>>,
}

impl Default for PiStream {
    fn default() -> Self {
        Self::new()
    }
}

impl PiStream {
    /// A stream at its start (the digit 3).
    pub fn new() -> Self {
        PiStream {
            position: 0,
            digits: Arc::new(Vec::new()),
        }
    }

    /// The position of the next digit to be read (`0 ≤ position < P`).
    pub fn position(&self) -> u64 {
        self.position
    }

    /// Makes sure the next `count` digits are computed (so that reading them later does no
    /// arithmetic; runners call this before starting a clock).
    ///
    /// Requests beyond 2^20 digits fetch the whole period at once, so that one cached prefix
    /// (in memory, and on disk, see [`crate::learning::pi::cache_dir`]) serves every later
    /// request of this and later processes.
    pub fn prefetch(&mut self, count: u64) {
        let want = self.position.saturating_add(count);
        let end = if want > 1 << 20 {
            PI_STREAM_PERIOD - 1
        } else {
            want.min(PI_STREAM_PERIOD - 1)
        } as usize;
        if end > self.digits.len() {
            self.digits = pi_digits(end);
        }
    }

    /// The digit at `position`.
    #[inline]
    fn digit(&mut self, position: u64) -> u8 {
        if position == 0 {
            return 3;
        }
        let index = (position - 1) as usize;
        if index >= self.digits.len() {
            self.digits = pi_digits(index + 1);
        }
        self.digits[index]
    }

    /// Reads the next digit (advancing the stream).
    ///
    /// ```
    /// let mut s = truecost::learning::plan::PiStream::new();
    /// let first: Vec<u8> = (0..6).map(|_| s.next_digit()).collect();
    /// assert_eq!(first, vec![3, 0, 2, 1, 0, 0]);
    /// ```
    #[inline]
    pub fn next_digit(&mut self) -> u8 {
        let d = self.digit(self.position);
        self.position += 1;
        if self.position == PI_STREAM_PERIOD {
            self.position = 0;
        }
        d
    }

    /// The plan's action at a state with `actions ≥ 1` actions: digits `≥ actions` are skipped.
    ///
    /// ```
    /// let mut s = truecost::learning::plan::PiStream::new();
    /// // Stream 3, 0, 2, 1, …: with three actions the 3 is skipped.
    /// assert_eq!(s.next_action(3), 0);
    /// assert_eq!(s.next_action(2), 1); // 2 skipped, then 1
    /// ```
    #[inline]
    pub fn next_action(&mut self, actions: usize) -> usize {
        debug_assert!(actions >= 1);
        loop {
            let d = self.next_digit() as usize;
            if d < actions {
                return d;
            }
        }
    }
}

/// Where ε-greedy takes its exploring actions from.
#[derive(Debug)]
pub enum Plan<'a> {
    /// Uniformly random actions from the run's generator.
    Random,
    /// The π universal plan, reading a shared stream.
    Pi(&'a mut PiStream),
}

impl Plan<'_> {
    /// The plan's name in reports (`random` or `pi`).
    pub fn name(&self) -> &'static str {
        match self {
            Plan::Random => "random",
            Plan::Pi(_) => "pi",
        }
    }
}

/// The exploring action of `plan` at a state with `actions ≥ 1` actions.
#[inline]
pub(crate) fn explore(plan: &mut Plan<'_>, rng: &mut ChaCha8Rng, actions: usize) -> usize {
    match plan {
        Plan::Random => rng.random_range(0..actions as u32) as usize,
        Plan::Pi(stream) => stream.next_action(actions),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `below` is `rand`'s `random_range(0..range)` for `u64`: the same values and the same
    /// words drawn, over ranges where the first draw is rarely, often (about half the time:
    /// `2^63 + 1`) and never ambiguous, and the ends `1` and `u64::MAX`.
    #[test]
    fn below_is_rands_random_range() {
        let mut ranges = vec![
            1,
            2,
            3,
            7,
            9,
            10,
            100,
            1000,
            (1 << 32) - 1,
            1 << 32,
            (1 << 32) + 1,
        ];
        ranges.extend([
            1 << 63,
            (1 << 63) + 1,
            (1 << 63) + (1 << 62),
            u64::MAX - 1,
            u64::MAX,
        ]);
        let mut seeds = sample_rng(99, 0);
        ranges.extend(
            (0..20)
                .map(|_| seeds.next_u64() >> (seeds.next_u64() % 64))
                .filter(|&r| r > 0),
        );
        let mut second_draws = 0;
        for (k, &range) in ranges.iter().enumerate() {
            let mut ours = sample_rng(k as u64, 3);
            let mut theirs = sample_rng(k as u64, 3);
            for _ in 0..5000 {
                let before = ours.get_word_pos();
                assert_eq!(
                    below(&mut ours, range),
                    theirs.random_range(0..range),
                    "range {range}"
                );
                assert_eq!(ours.get_word_pos(), theirs.get_word_pos(), "range {range}");
                if ours.get_word_pos() - before == 4 {
                    second_draws += 1;
                }
            }
            assert_eq!(ours.next_u64(), theirs.next_u64());
        }
        // The ambiguous case was exercised (about 2500 times for each range near 2^63).
        assert!(second_draws > 5000, "{second_draws}");
    }

    /// The coin draws nothing at `p ∈ {0, 1}` and is `random_range(0..q) < p` otherwise.
    #[test]
    fn flip_is_a_draw_below_the_numerator() {
        let half = Probability::new("p", &Rational::new(1.into(), 2.into())).unwrap();
        let nine_tenths = Probability::new("p", &Rational::new(9.into(), 10.into())).unwrap();
        for p in [half, nine_tenths] {
            let (mut ours, mut theirs) = (sample_rng(5, 1), sample_rng(5, 1));
            let flips: Vec<bool> = (0..2000).map(|_| p.flip(&mut ours)).collect();
            let expected: Vec<bool> = (0..2000)
                .map(|_| theirs.random_range(0..p.denominator()) < p.numerator())
                .collect();
            assert_eq!(flips, expected);
            let heads = flips.iter().filter(|&&f| f).count() as u64;
            // 2000·p ± 5 standard deviations at most
            let mean = 2000 * p.numerator() / p.denominator();
            assert!(heads.abs_diff(mean) < 120, "{heads} heads for {p:?}");
        }
        let mut rng = sample_rng(5, 1);
        let zero = Probability::new("p", &Rational::from_integer(0.into())).unwrap();
        assert!(!zero.flip(&mut rng) && Probability::ONE.flip(&mut rng));
        assert_eq!(rng.get_word_pos(), 0);
    }
}
