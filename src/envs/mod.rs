//! Gymnasium's toy-text benchmarks as exact stochastic problems:
//! FrozenLake-v1, CliffWalking-v1 (and its slippery variant) and Taxi-v4, faithful to
//! Gymnasium 1.x — the same state and action numbering, the same outcome lists in the same
//! order, the same rewards and terminations — with every probability exact (FrozenLake's 1/3 is
//! 1/3, not `0.33333333333333337`).
//!
//! * [`EnvSpec`] — the `--env SPEC` text: `frozenlake[:map=4x4|8x8|FILE,slippery=true|false,
//!   success_rate=p/q]`, `cliffwalking[:slippery=true|false]`, `taxi`.
//! * [`Environment`] — Gymnasium's table `P[s][a] = [(p, s', r, terminated), ...]` with exact
//!   `p`, the initial state distribution, the goal and trap states, and the map.
//! * [`Environment::truecost_cost`] — the paper's cost of each outcome:
//!   FrozenLake 1 per step; CliffWalking 1 per step, 100 per fall; Taxi 1 per action (the
//!   delivery included), 10 for an illegal pick-up/drop-off, the delivery's +20 reported as the
//!   terminal bonus `M` of Proposition 4 ([`Environment::terminal_bonus`]).
//!
//! The problem the solvers see is built by [`crate::objectives::Model::from_environment`].

pub mod cliffwalking;
pub mod frozenlake;
pub mod taxi;

use std::path::PathBuf;

use num_traits::{One, Zero};

use crate::model::StateId;
use crate::value::{parse_rational, Rational};

/// Why an environment specification was refused. Every message fits on one line.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum EnvError {
    /// An unknown environment name.
    #[error("unknown environment '{}' (known: frozenlake, cliffwalking, taxi)", crate::echo::echo(.0))]
    UnknownEnvironment(String),
    /// An option the environment does not have.
    #[error("{env}: unknown option '{}' (options: {known})", crate::echo::echo(.option))]
    UnknownOption {
        /// The environment.
        env: &'static str,
        /// The option given.
        option: String,
        /// The options it has.
        known: &'static str,
    },
    /// An option given twice, or without `=`.
    #[error("{0}")]
    Syntax(String),
    /// An option value out of its range or not parseable.
    #[error("{env}: {option}={}: {reason}", crate::echo::echo(.value))]
    Value {
        /// The environment.
        env: &'static str,
        /// The option.
        option: &'static str,
        /// The value given.
        value: String,
        /// Why it was refused.
        reason: String,
    },
    /// A FrozenLake map that cannot be read or is ill formed.
    #[error("frozenlake map {}: {reason}", crate::echo::echo(.path))]
    Map {
        /// The map file.
        path: String,
        /// What is wrong.
        reason: String,
    },
}

/// Which FrozenLake map.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum MapChoice {
    /// Gymnasium's `"4x4"` (the default).
    FourByFour,
    /// Gymnasium's `"8x8"`.
    EightByEight,
    /// A text file: one row per line of `S`, `F`, `H`, `G` (Gymnasium's `desc`).
    File(PathBuf),
}

/// A parsed `--env SPEC`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum EnvSpec {
    /// `frozenlake[:map=…,slippery=…,success_rate=p/q]` (FrozenLake-v1).
    FrozenLake {
        /// The map.
        map: MapChoice,
        /// `is_slippery` (default true).
        slippery: bool,
        /// `success_rate` (default 1/3), exact; only with `slippery=true`.
        success_rate: Rational,
    },
    /// `cliffwalking[:slippery=…]` (CliffWalking-v1; slippery = CliffWalkingSlippery-v1).
    CliffWalking {
        /// `is_slippery` (default false).
        slippery: bool,
    },
    /// `taxi` (Taxi-v4, deterministic: not rainy, no fickle passenger).
    Taxi,
}

fn parse_bool(env: &'static str, option: &'static str, value: &str) -> Result<bool, EnvError> {
    match value {
        "true" => Ok(true),
        "false" => Ok(false),
        _ => Err(EnvError::Value {
            env,
            option,
            value: value.into(),
            reason: "expected true or false".into(),
        }),
    }
}

impl EnvSpec {
    /// Parses `NAME[:KEY=VALUE,...]`. Numbers are exact (`success_rate=0.8` is 4/5).
    ///
    /// ```
    /// use truecost::envs::{EnvSpec, MapChoice};
    /// let s = EnvSpec::parse("frozenlake:map=8x8,success_rate=1/2").unwrap();
    /// let EnvSpec::FrozenLake { map, slippery, success_rate } = s else { panic!() };
    /// assert_eq!((map, slippery, success_rate.to_string()), (MapChoice::EightByEight, true, "1/2".into()));
    /// assert!(EnvSpec::parse("taxi:rainy=true").unwrap_err().to_string().contains("unknown option"));
    /// assert!(EnvSpec::parse("frozenlake:success_rate=1.5").is_err());
    /// ```
    pub fn parse(text: &str) -> Result<Self, EnvError> {
        let (name, options) = match text.split_once(':') {
            Some((n, o)) => (n, o),
            None => (text, ""),
        };
        let mut pairs: Vec<(String, String)> = Vec::new();
        for item in options.split(',').filter(|s| !s.is_empty()) {
            let Some((k, v)) = item.split_once('=') else {
                return Err(EnvError::Syntax(format!(
                    "{}: option '{}' must be KEY=VALUE",
                    crate::echo::echo(name),
                    crate::echo::echo(item)
                )));
            };
            if pairs.iter().any(|(seen, _)| seen == k) {
                return Err(EnvError::Syntax(format!(
                    "{}: option '{}' given twice",
                    crate::echo::echo(name),
                    crate::echo::echo(k)
                )));
            }
            pairs.push((k.to_string(), v.to_string()));
        }
        match name {
            "frozenlake" => {
                const KNOWN: &str = "map, slippery, success_rate";
                let (mut map, mut slippery, mut rate) = (MapChoice::FourByFour, true, None);
                for (k, v) in pairs {
                    match k.as_str() {
                        "map" => {
                            map = match v.as_str() {
                                "4x4" => MapChoice::FourByFour,
                                "8x8" => MapChoice::EightByEight,
                                path => MapChoice::File(PathBuf::from(path)),
                            }
                        }
                        "slippery" => slippery = parse_bool("frozenlake", "slippery", &v)?,
                        "success_rate" => {
                            let bad = |reason: String| EnvError::Value {
                                env: "frozenlake",
                                option: "success_rate",
                                value: v.clone(),
                                reason,
                            };
                            let r = parse_rational(&v).map_err(|e| bad(e.to_string()))?;
                            if r < Rational::zero() || r > Rational::one() {
                                return Err(bad("must be in [0, 1]".into()));
                            }
                            rate = Some(r);
                        }
                        _ => {
                            return Err(EnvError::UnknownOption {
                                env: "frozenlake",
                                option: k,
                                known: KNOWN,
                            })
                        }
                    }
                }
                if rate.is_some() && !slippery {
                    return Err(EnvError::Syntax(
                        "frozenlake: success_rate applies to slippery=true only".into(),
                    ));
                }
                Ok(EnvSpec::FrozenLake {
                    map,
                    slippery,
                    success_rate: rate.unwrap_or_else(|| Rational::new(1.into(), 3.into())),
                })
            }
            "cliffwalking" => {
                let mut slippery = false;
                for (k, v) in pairs {
                    if k == "slippery" {
                        slippery = parse_bool("cliffwalking", "slippery", &v)?;
                    } else {
                        return Err(EnvError::UnknownOption {
                            env: "cliffwalking",
                            option: k,
                            known: "slippery",
                        });
                    }
                }
                Ok(EnvSpec::CliffWalking { slippery })
            }
            "taxi" => match pairs.into_iter().next() {
                Some((k, _)) => Err(EnvError::UnknownOption {
                    env: "taxi",
                    option: k,
                    known: "none: Taxi-v4 deterministic",
                }),
                None => Ok(EnvSpec::Taxi),
            },
            other => Err(EnvError::UnknownEnvironment(other.into())),
        }
    }

    /// The canonical text of this specification (every option spelled out).
    pub fn canonical(&self) -> String {
        match self {
            EnvSpec::FrozenLake {
                map,
                slippery,
                success_rate,
            } => {
                let map = match map {
                    MapChoice::FourByFour => "4x4".to_string(),
                    MapChoice::EightByEight => "8x8".to_string(),
                    MapChoice::File(p) => p.display().to_string(),
                };
                if *slippery {
                    format!("frozenlake:map={map},slippery=true,success_rate={success_rate}")
                } else {
                    format!("frozenlake:map={map},slippery=false")
                }
            }
            EnvSpec::CliffWalking { slippery } => format!("cliffwalking:slippery={slippery}"),
            EnvSpec::Taxi => "taxi".into(),
        }
    }

    /// Builds the environment (reads the map file if one is named).
    pub fn build(&self) -> Result<Environment, EnvError> {
        match self {
            EnvSpec::FrozenLake {
                map,
                slippery,
                success_rate,
            } => frozenlake::build(map, *slippery, success_rate, self.canonical()),
            EnvSpec::CliffWalking { slippery } => Ok(cliffwalking::build(*slippery)),
            EnvSpec::Taxi => Ok(taxi::build()),
        }
    }
}

/// One entry of Gymnasium's `P[s][a]`: `(probability, next_state, reward, terminated)`, the
/// probability exact.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Transition {
    /// The exact probability (may be 0 where Gymnasium lists a zero-probability entry, e.g.
    /// FrozenLake with `success_rate=1`).
    pub probability: Rational,
    /// The next state.
    pub next: StateId,
    /// Gymnasium's reward.
    pub reward: i64,
    /// Gymnasium's `terminated` flag.
    pub terminated: bool,
}

/// Which benchmark, with what its figures need.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Layout {
    /// FrozenLake: the map's rows (`S`, `F`, `H`, `G`).
    FrozenLake {
        /// Gymnasium's `desc`, one string per row.
        desc: Vec<String>,
    },
    /// CliffWalking: 4 × 12, start 36, goal 47, cliff 37..=46.
    CliffWalking,
    /// Taxi: 5 × 5 grid with walls; state `((row·5 + col)·5 + passenger)·4 + destination`.
    Taxi,
}

/// An exact Gymnasium toy-text environment (module docs).
#[derive(Clone, Debug)]
pub struct Environment {
    /// The canonical `--env` text.
    pub spec: String,
    /// Gymnasium's id (`FrozenLake-v1`, ...).
    pub gymnasium_id: &'static str,
    /// The map and numbering.
    pub layout: Layout,
    /// Rows × columns of the drawing grid.
    pub shape: (usize, usize),
    /// Action names in Gymnasium's numbering.
    pub action_names: &'static [&'static str],
    /// `P[s][a]`: the outcomes in Gymnasium's order.
    pub table: Vec<Vec<Vec<Transition>>>,
    /// The initial state distribution (states with positive probability, ascending).
    pub initial: Vec<(StateId, Rational)>,
    /// The goal states (episode over, success).
    pub goals: Vec<StateId>,
    /// The trap states (episode over, failure: FrozenLake's holes).
    pub traps: Vec<StateId>,
}

impl Environment {
    /// `|X|`.
    pub fn states(&self) -> usize {
        self.table.len()
    }

    /// Whether the episode is over on entering `x` (a goal or a trap).
    pub fn is_terminal(&self, x: StateId) -> bool {
        self.goals.contains(&x) || self.traps.contains(&x)
    }

    /// The paper's cost of one outcome: FrozenLake 1 per step; CliffWalking
    /// `−reward` (1 per step, 100 per fall); Taxi 1 per action, 10 for an illegal
    /// pick-up/drop-off, 1 for the delivery (its +20 is [`Self::terminal_bonus`]).
    ///
    /// ```
    /// use truecost::envs::EnvSpec;
    /// let cliff = EnvSpec::parse("cliffwalking").unwrap().build().unwrap();
    /// let fall = &cliff.table[36][1][0]; // right from the start: into the cliff
    /// assert_eq!((fall.next, fall.reward), (36, -100));
    /// assert_eq!(cliff.truecost_cost(fall).to_string(), "100");
    /// ```
    pub fn truecost_cost(&self, t: &Transition) -> Rational {
        let c = match self.layout {
            Layout::FrozenLake { .. } => 1,
            Layout::CliffWalking => -t.reward,
            Layout::Taxi => {
                if t.reward < 0 {
                    -t.reward
                } else {
                    1
                }
            }
        };
        Rational::from_integer(c.into())
    }

    /// The terminal bonus `M` of Proposition 4 (a reward on reaching the goal, as a negative
    /// cost): Taxi's delivery `−20`; `None` for the others (FrozenLake's +1 on the goal is the
    /// success indicator, not a cost).
    pub fn terminal_bonus(&self) -> Option<Rational> {
        match self.layout {
            Layout::Taxi => Some(Rational::from_integer((-20).into())),
            _ => None,
        }
    }
}

/// `(p, q)` as an exact rational.
pub(crate) fn ratio(p: i64, q: i64) -> Rational {
    Rational::new(p.into(), q.into())
}
