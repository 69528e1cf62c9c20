//! The predictability factor `γ` and the two noise models of docs/spec.md §3 and §7.
//!
//! Applying the commanded move `u ∈ U(x)` (with `k = |U(x)| ≥ 1` moves at `x`, termination not
//! counted) yields one of these outcomes, listed in this order:
//!
//! | outcome | [`NoiseModel::Paper`] (default) | [`NoiseModel::Reference`], `k ≥ 2` | `Reference`, `k = 1` |
//! |---|---|---|---|
//! | `f(x,u)` (commanded) | `γ` | `γ` | `γ` |
//! | `f(x,u')` for every other move `u'`, in `U(x)` order | `(1−γ)/k` each | `(1−γ)/(2(k−1))` each | — |
//! | stay at `x` | `(1−γ)/k` | `(1−γ)/2` | `1−γ` |
//!
//! The paper's text spreads `1−γ` uniformly over the *other* actions of `U(x)` plus a "stay"
//! outcome (nature picked another move, or the hold/termination action): `k` outcomes. The
//! paper's code gives stay half of `1−γ` and shares the rest among the other moves, putting
//! everything on stay where there is no other move (a dead end of the grid, `k = 1`). With a
//! single move both models agree (`γ` commanded, `1−γ` stay). Outcomes with probability 0 (all
//! but the commanded one when `γ = 1`) are omitted, so `γ = 1` is the deterministic model.
//!
//! At a **goal** the termination action is deterministic (`G* = 0`, the state is frozen); its
//! moves, if a learner tries them, are perturbed as above (stay = hold). A non-goal state
//! without moves has no action at all: `G* = +∞`.

use num_bigint::BigInt;
use num_traits::{One, Zero};

use super::StochasticError;
use crate::value::{in_unit_interval_open_closed, parse_rational, Rational};

/// The predictability factor `γ ∈ (0, 1]`, exact (docs/spec.md §3).
///
/// ```
/// use truecost::stochastic::Predictability;
/// let g = Predictability::parse("0.999").unwrap();
/// assert_eq!(g.to_string(), "999/1000");
/// assert!(Predictability::parse("1").unwrap().is_deterministic());
/// assert!(Predictability::parse("0").is_err());
/// assert!(Predictability::parse("1.5").is_err());
/// ```
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Predictability(Rational);

impl Predictability {
    /// Parses `γ` from its decimal or fractional text (never through `f64`).
    pub fn parse(text: &str) -> Result<Self, StochasticError> {
        Self::new(parse_rational(text)?)
    }

    /// Checks `γ ∈ (0, 1]`.
    pub fn new(gamma: Rational) -> Result<Self, StochasticError> {
        if in_unit_interval_open_closed(&gamma) {
            Ok(Predictability(gamma))
        } else {
            Err(StochasticError::GammaRange(super::short_text(&gamma)))
        }
    }

    /// `γ = 1`.
    pub fn one() -> Self {
        Predictability(Rational::one())
    }

    /// The exact value.
    pub fn value(&self) -> &Rational {
        &self.0
    }

    /// Whether `γ = 1` (the deterministic model).
    pub fn is_deterministic(&self) -> bool {
        self.0.is_one()
    }
}

impl std::fmt::Display for Predictability {
    /// The exact value: `"999/1000"`, `"1"`.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}", crate::value::Extended::Finite(self.0.clone()))
    }
}

/// How the probability `1 − γ` of not executing the commanded move is spread (table above).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default, clap::ValueEnum, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum NoiseModel {
    /// The paper's text (docs/spec.md §3): `(1−γ)/k` to each other move and to stay.
    #[default]
    Paper,
    /// The paper's code (docs/spec.md §7): stay `(1−γ)/2`, the other moves share `(1−γ)/2`; all of
    /// `1−γ` on stay when there is no other move.
    Reference,
}

impl NoiseModel {
    /// The name used on the command line and in every output.
    pub fn name(self) -> &'static str {
        match self {
            NoiseModel::Paper => "paper",
            NoiseModel::Reference => "reference",
        }
    }

    /// A one-line description for reports.
    pub fn describe(self) -> &'static str {
        match self {
            NoiseModel::Paper => "paper (text: 1-gamma spread uniformly over the other moves and stay)",
            NoiseModel::Reference => "reference (code: stay (1-gamma)/2, other moves share (1-gamma)/2; all on stay with a single move)",
        }
    }

    /// The probabilities `(commanded, each other move, stay)` for a state with `k ≥ 1` moves.
    ///
    /// ```
    /// use truecost::stochastic::{NoiseModel, Predictability};
    /// use truecost::value::parse_rational;
    /// let g = Predictability::parse("0.9").unwrap();
    /// let (c, o, s) = NoiseModel::Paper.split(&g, 4);
    /// assert_eq!((c, o.clone(), s), (parse_rational("0.9").unwrap(), parse_rational("1/40").unwrap(), o));
    /// let (_, o, s) = NoiseModel::Reference.split(&g, 4);
    /// assert_eq!((o, s), (parse_rational("1/60").unwrap(), parse_rational("1/20").unwrap()));
    /// let (_, o, s) = NoiseModel::Reference.split(&g, 1);
    /// assert_eq!((o, s), (parse_rational("0").unwrap(), parse_rational("0.1").unwrap()));
    /// ```
    pub fn split(self, gamma: &Predictability, k: usize) -> (Rational, Rational, Rational) {
        assert!(k >= 1, "a state with no moves has no commanded move");
        let g = gamma.value().clone();
        let rest = Rational::one() - &g;
        let int = |n: usize| Rational::from_integer(BigInt::from(n));
        match self {
            NoiseModel::Paper => {
                let each = &rest / int(k);
                (g, each.clone(), each)
            }
            NoiseModel::Reference if k == 1 => (g, Rational::zero(), rest),
            NoiseModel::Reference => {
                let half = &rest / int(2);
                (g, &half / int(k - 1), half)
            }
        }
    }

    /// The same split as the paper's Python code computes it in `f64` (`(1-γ)/2/(k-1)` …), for
    /// the reference-mode value iteration of docs/spec.md §7.
    pub fn split_f64(self, gamma: f64, k: usize) -> (f64, f64, f64) {
        let rest = 1.0 - gamma;
        match self {
            NoiseModel::Paper => (gamma, rest / k as f64, rest / k as f64),
            NoiseModel::Reference if k == 1 => (gamma, 0.0, rest),
            NoiseModel::Reference => (gamma, rest / 2.0 / (k - 1) as f64, rest / 2.0),
        }
    }
}
