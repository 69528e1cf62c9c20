//! Replays of derandomized Q-learning (`ρ = 1`, docs/spec.md §2) on a problem file, round by round, in
//! exact arithmetic: the command behind every C1 counterexample
//! (`truecost learn --file F --q0 … --order … --rounds N`).
//!
//! The pairs are every move of every state, in file order, and at each goal its termination
//! action `uT` first (`f(xg, uT) = xg`, `l = 0`, docs/spec.md §1). A *round* updates every updatable pair
//! once, in the named fair order, with `Q(x,u) ← l(x,u) + min_{u'} Q(f(x,u), u')`. `Q*` comes from
//! an independent exact Bellman–Ford on the file's rational costs. Verdicts:
//! * `converged at round r` — `Q = Q*` at the end of round `r` (then forever: `Q*` is a fixed
//!   point of every update when it is finite);
//! * `never converges: round-end values repeat from round k` — under a periodic order (cyclic,
//!   reverse, far-first) the same round-end values, not `Q*`, recur, so they recur forever;
//! * `not converged within N rounds`.

use std::collections::HashMap;
use std::fmt::Write as _;

use num_traits::Zero;
use serde::Serialize;

use super::qlearning::{Order, Terminal};
use crate::model::Problem;
use crate::value::{parse_rational, Rational};

/// A fair order of updates, made of rounds (every updatable pair once per round).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ReplayOrder {
    /// Pairs in index order (states in file order; at a goal `uT` first, then the moves).
    Cyclic,
    /// Pairs in reverse index order.
    Reverse,
    /// The adversary: pairs whose successor is farthest from the goal first (`h` = fewest moves
    /// of an optimal path; unreachable first), ties in index order.
    FarFirst,
    /// A fresh pseudo-random permutation every round (splitmix64 Fisher–Yates, seeded; the same
    /// stream as the claims engine's random order).
    Random(u64),
}

impl ReplayOrder {
    /// The command-line name (`cyclic`, `reverse`, `far-first`, `random`).
    pub fn name(self) -> &'static str {
        match self {
            ReplayOrder::Cyclic => "cyclic",
            ReplayOrder::Reverse => "reverse",
            ReplayOrder::FarFirst => "far-first",
            ReplayOrder::Random(_) => "random",
        }
    }
}

/// The claims engine's order as a replay order: the same schedule (its random order draws the
/// same permutations from the same seed), so a counterexample's replay command can name it.
///
/// ```
/// use truecost::claims::qlearning::Order;
/// use truecost::claims::replay::ReplayOrder;
/// assert_eq!(ReplayOrder::from(Order::FarFirst).name(), "far-first");
/// assert_eq!(ReplayOrder::from(Order::Random(7)), ReplayOrder::Random(7));
/// ```
impl From<Order> for ReplayOrder {
    fn from(order: Order) -> ReplayOrder {
        match order {
            Order::Cyclic => ReplayOrder::Cyclic,
            Order::Reverse => ReplayOrder::Reverse,
            Order::FarFirst => ReplayOrder::FarFirst,
            Order::Random(seed) => ReplayOrder::Random(seed),
        }
    }
}

/// Initial values `Q₀`.
#[derive(Clone, Debug, PartialEq)]
pub enum InitialValues {
    /// The same value on every pair (a held termination pair is 0 nonetheless).
    Constant(Rational),
    /// One value per pair, in pair order.
    PerPair(Vec<Rational>),
}

impl InitialValues {
    /// Parses `--q0`: one exact value (`"0"`, `"-1"`, `"1/2"`) for every pair, or a comma-
    /// separated list with one value per pair in pair order.
    ///
    /// ```
    /// use truecost::claims::replay::InitialValues;
    /// assert!(matches!(InitialValues::parse("-1").unwrap(), InitialValues::Constant(_)));
    /// assert!(matches!(InitialValues::parse("0,1/2,-3").unwrap(), InitialValues::PerPair(v) if v.len() == 3));
    /// assert!(InitialValues::parse("1,x").is_err());
    /// ```
    pub fn parse(text: &str) -> Result<InitialValues, String> {
        let values: Vec<Rational> = text
            .split(',')
            .map(|t| parse_rational(t).map_err(|e| format!("--q0: {e}")))
            .collect::<Result<_, _>>()?;
        Ok(if values.len() == 1 {
            InitialValues::Constant(values.into_iter().next().expect("one"))
        } else {
            InitialValues::PerPair(values)
        })
    }
}

/// One state–action pair of a replay.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ReplayPair {
    /// `x`.
    pub state: usize,
    /// `f(x, u)`.
    pub to: usize,
    /// `l(x, u)` (exact text).
    pub cost: String,
    /// Whether this is the goal's termination action `uT`.
    pub terminal: bool,
    /// `Q*(x, u)` (exact text, `inf` when the goal is unreachable from `f(x, u)`).
    pub optimum: String,
}

/// How a replay ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(tag = "kind", rename_all = "kebab-case")]
pub enum ReplayVerdict {
    /// `Q = Q*` at the end of this round (0 = initially) and from then on.
    Converged {
        /// The round.
        round: u64,
    },
    /// Round-end values repeat from round `from` with this period, never `Q*` (periodic orders).
    NeverConverges {
        /// First round of the repetition.
        from: u64,
        /// Period in rounds.
        period: u64,
    },
    /// Not `Q*` after this many rounds.
    NotConverged {
        /// Rounds run.
        rounds: u64,
    },
}

impl ReplayVerdict {
    /// The verdict line.
    pub fn line(&self) -> String {
        match self {
            ReplayVerdict::Converged { round } => format!("converged at round {round}"),
            ReplayVerdict::NeverConverges { from, .. } => {
                format!("never converges: round-end values repeat from round {from}")
            }
            ReplayVerdict::NotConverged { rounds } => {
                format!("not converged within {rounds} rounds")
            }
        }
    }
}

/// A finished replay: the pairs, the values at the end of every round (round 0 = `Q₀`), the
/// verdict.
#[derive(Clone, Debug, PartialEq)]
pub struct Replay {
    /// The pairs, in pair (and cyclic) order.
    pub pairs: Vec<ReplayPair>,
    /// The order.
    pub order: ReplayOrder,
    /// Treatment of the termination pairs.
    pub terminal: Terminal,
    /// `values[r][p]`: `Q(p)` at the end of round `r`.
    pub values: Vec<Vec<Rational>>,
    /// The verdict.
    pub verdict: ReplayVerdict,
}

/// Largest number of rounds a replay runs.
pub const MAX_ROUNDS: u64 = 100_000;

/// Largest number of values a replay keeps (`(rounds + 1) × pairs`): the report lists every
/// round's values, and the check for repeating rounds remembers them, so the product is
/// bounded before the first round runs.
pub const MAX_VALUES: u64 = 5_000_000;

struct Pairs {
    state: Vec<usize>,
    to: Vec<usize>,
    cost: Vec<Rational>,
    terminal: Vec<bool>,
    first: Vec<usize>,
}

fn pairs_of(p: &Problem) -> Pairs {
    let mut out = Pairs {
        state: vec![],
        to: vec![],
        cost: vec![],
        terminal: vec![],
        first: vec![],
    };
    for x in 0..p.states() {
        out.first.push(out.state.len());
        if p.is_goal(x) {
            out.state.push(x);
            out.to.push(x);
            out.cost.push(Rational::zero());
            out.terminal.push(true);
        }
        for m in p.moves(x) {
            out.state.push(x);
            out.to.push(m.successor);
            out.cost.push(m.cost.clone());
            out.terminal.push(false);
        }
    }
    out.first.push(out.state.len());
    out
}

/// `G*` (exact, `None` = `+∞`) and `h` (fewest moves of an optimal path) by Bellman–Ford.
/// `G*` and `h` (fewest moves of an optimal path) of every state: Dijkstra backwards from the
/// goals on the lexicographic key `(cost, moves)`. Costs are `≥ 0`, so the key of a move,
/// `(l, 1)`, is non-negative in that order, and the least key of a state is `(G*(x), h(x))`:
/// the least cost, and among the paths of least cost the fewest moves. `O(m log n)`, so a long
/// chain costs no more than a short grid.
fn cost_to_go(p: &Problem) -> (Vec<Option<Rational>>, Vec<Option<u64>>) {
    use std::cmp::Reverse;
    use std::collections::BinaryHeap;
    let n = p.states();
    let mut into: Vec<Vec<(usize, &Rational)>> = vec![Vec::new(); n];
    for x in 0..n {
        for m in p.moves(x) {
            into[m.successor].push((x, &m.cost));
        }
    }
    let mut g: Vec<Option<Rational>> = vec![None; n];
    let mut h: Vec<Option<u64>> = vec![None; n];
    let mut done = vec![false; n];
    let mut heap = BinaryHeap::new();
    for x in (0..n).filter(|&x| p.is_goal(x)) {
        g[x] = Some(Rational::zero());
        h[x] = Some(0);
        heap.push(Reverse((Rational::zero(), 0u64, x)));
    }
    while let Some(Reverse((gy, hy, y))) = heap.pop() {
        if std::mem::replace(&mut done[y], true) {
            continue;
        }
        for &(x, cost) in &into[y] {
            let key = (cost + &gy, hy + 1);
            let better = match (&g[x], h[x]) {
                (Some(gx), Some(hx)) => (&key.0, key.1) < (gx, hx),
                _ => true,
            };
            if !done[x] && better {
                g[x] = Some(key.0.clone());
                h[x] = Some(key.1);
                heap.push(Reverse((key.0, key.1, x)));
            }
        }
    }
    (g, h)
}

fn splitmix(state: &mut u64) -> u64 {
    *state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
    let mut z = *state;
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// Runs derandomized Q-learning on `problem` from `q0` under `order` for at most `rounds`
/// rounds (docs/spec.md §2 with `ρ = 1`; claim C1). With [`Terminal::HeldAtZero`]
/// the termination pairs are 0 and never updated (H0 of C1-corrected); with
/// [`Terminal::Updated`] they are ordinary pairs (C1 as printed).
///
/// ```
/// use truecost::claims::qlearning::Terminal;
/// use truecost::claims::replay::{replay, InitialValues, ReplayOrder};
/// use truecost::model::file;
/// // State 0: a zero-cost self-loop and a move of cost 1 to the goal 1. Started at 0 (below
/// // Q* = 1), the self-loop keeps Q(0,->0) = 0 forever.
/// let p = file::from_json(r#"{"initial": 0, "goals": [1],
///     "actions": [[{"to": 0, "cost": "0"}, {"to": 1, "cost": "1"}], []]}"#).unwrap();
/// let r = replay(&p, &InitialValues::parse("0").unwrap(), ReplayOrder::Cyclic, Terminal::HeldAtZero, 10).unwrap();
/// assert_eq!(r.verdict.line(), "never converges: round-end values repeat from round 1");
/// ```
pub fn replay(
    problem: &Problem,
    q0: &InitialValues,
    order: ReplayOrder,
    terminal: Terminal,
    rounds: u64,
) -> Result<Replay, String> {
    if rounds > MAX_ROUNDS {
        return Err(format!("--rounds {rounds}: at most {MAX_ROUNDS}"));
    }
    let pairs = pairs_of(problem);
    let count = pairs.state.len();
    let kept = (rounds + 1).saturating_mul(count as u64);
    if kept > MAX_VALUES {
        return Err(format!(
            "--rounds {rounds} on {count} state-action pairs keeps {kept} values (every round's, for the report): at most {MAX_VALUES}; give fewer rounds"
        ));
    }
    let held = |p: usize| pairs.terminal[p] && terminal == Terminal::HeldAtZero;
    let mut v: Vec<Rational> = match q0 {
        InitialValues::Constant(c) => vec![c.clone(); count],
        InitialValues::PerPair(list) => {
            if list.len() != count {
                return Err(format!(
                    "--q0 lists {} values but the problem has {count} state-action pairs (goals' termination pairs included)",
                    list.len()
                ));
            }
            list.clone()
        }
    };
    for p in 0..count {
        if held(p) {
            if matches!(q0, InitialValues::PerPair(_)) && !v[p].is_zero() {
                return Err(format!(
                    "--q0: the termination pair of goal {} is held at 0 (--terminal held); give it 0",
                    pairs.state[p]
                ));
            }
            v[p] = Rational::zero();
        }
    }
    let (g, h) = cost_to_go(problem);
    let optimum: Vec<Option<Rational>> = (0..count)
        .map(|p| {
            if pairs.terminal[p] {
                Some(Rational::zero())
            } else {
                g[pairs.to[p]].as_ref().map(|gy| &pairs.cost[p] + gy)
            }
        })
        .collect();
    let is_optimal = |v: &[Rational]| (0..count).all(|p| optimum[p].as_ref() == Some(&v[p]));
    let mut sequence: Vec<usize> = (0..count).filter(|&p| !held(p)).collect();
    match order {
        ReplayOrder::Cyclic | ReplayOrder::Random(_) => {}
        ReplayOrder::Reverse => sequence.reverse(),
        ReplayOrder::FarFirst => {
            sequence.sort_by_key(|&p| (std::cmp::Reverse(h[pairs.to[p]].unwrap_or(u64::MAX)), p))
        }
    }
    let mut rng = match order {
        ReplayOrder::Random(seed) => seed ^ 0x9E37_79B9_7F4A_7C15,
        _ => 0,
    };
    let mut values = vec![v.clone()];
    let mut seen: HashMap<Vec<Rational>, u64> = HashMap::new();
    seen.insert(v.clone(), 0);
    let mut verdict = ReplayVerdict::NotConverged { rounds };
    if is_optimal(&v) {
        verdict = ReplayVerdict::Converged { round: 0 };
    } else {
        for round in 1..=rounds {
            if let ReplayOrder::Random(_) = order {
                for i in (1..sequence.len()).rev() {
                    let z = splitmix(&mut rng);
                    sequence.swap(i, (z % (i as u64 + 1)) as usize);
                }
            }
            for &p in &sequence {
                let y = pairs.to[p];
                let best = v[pairs.first[y]..pairs.first[y + 1]]
                    .iter()
                    .min()
                    .expect("every state of a problem file has an action")
                    .clone();
                v[p] = &pairs.cost[p] + best;
            }
            values.push(v.clone());
            if is_optimal(&v) {
                verdict = ReplayVerdict::Converged { round };
                break;
            }
            if !matches!(order, ReplayOrder::Random(_)) {
                if let Some(&k) = seen.get(&v) {
                    verdict = ReplayVerdict::NeverConverges {
                        from: k,
                        period: round - k,
                    };
                    break;
                }
                seen.insert(v.clone(), round);
            }
        }
    }
    let text = |r: &Option<Rational>| r.as_ref().map_or("inf".to_string(), |r| r.to_string());
    Ok(Replay {
        pairs: (0..count)
            .map(|p| ReplayPair {
                state: pairs.state[p],
                to: pairs.to[p],
                cost: pairs.cost[p].to_string(),
                terminal: pairs.terminal[p],
                optimum: text(&optimum[p]),
            })
            .collect(),
        order,
        terminal,
        values,
        verdict,
    })
}

impl Replay {
    /// The label of pair `p`: `Q(x,uT)` or `Q(x->y)`.
    pub fn label(&self, p: usize) -> String {
        let pair = &self.pairs[p];
        if pair.terminal {
            format!("Q({},uT)", pair.state)
        } else {
            format!("Q({}->{})", pair.state, pair.to)
        }
    }

    /// The replay as text: the pairs with `Q*`, one line of values per round, the verdict.
    pub fn text(&self) -> String {
        let mut s = String::new();
        let _ = writeln!(
            s,
            "derandomized Q-learning (rho = 1), {} order, termination pairs {}, exact arithmetic",
            self.order.name(),
            match self.terminal {
                Terminal::Updated => "updated like every pair (as printed)",
                Terminal::HeldAtZero => "held at 0 (H0)",
            }
        );
        let stars: Vec<String> = (0..self.pairs.len())
            .map(|p| format!("{}={}", self.label(p), self.pairs[p].optimum))
            .collect();
        let _ = writeln!(s, "Q*: {}", stars.join(" "));
        for (r, v) in self.values.iter().enumerate() {
            let vals: Vec<String> = (0..v.len())
                .map(|p| format!("{}={}", self.label(p), v[p]))
                .collect();
            let _ = writeln!(s, "round {r}: {}", vals.join(" "));
        }
        let _ = writeln!(s, "{}", self.verdict.line());
        s
    }

    /// The replay as JSON (`pairs`, `rounds` with exact value strings, `verdict`).
    pub fn json(&self) -> String {
        let rounds: Vec<serde_json::Value> = self
            .values
            .iter()
            .enumerate()
            .map(|(r, v)| {
                serde_json::json!({
                    "round": r,
                    "values": v.iter().map(|x| x.to_string()).collect::<Vec<_>>(),
                })
            })
            .collect();
        let value = serde_json::json!({
            "algorithm": "derandomized Q-learning (rho = 1)",
            "order": self.order.name(),
            "seed": match self.order { ReplayOrder::Random(s) => Some(s), _ => None },
            "terminal": match self.terminal { Terminal::Updated => "updated", Terminal::HeldAtZero => "held" },
            "pairs": self.pairs,
            "rounds": rounds,
            "verdict": self.verdict,
            "verdict_line": self.verdict.line(),
        });
        serde_json::to_string_pretty(&value).expect("serialisable") + "\n"
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Move;

    /// `G*` and `h` by hand: from 0 the goal 2 costs 5 directly and 1 + 1 through 1, so
    /// `G*(0) = 2` (not the first value found, 5) and `h(0) = 2` (the fewest moves of an
    /// *optimal* path, not the one move of the direct one); 3 has no path (`+∞`, no `h`).
    /// Both orders of 0's moves: the direct move scanned first, then last. And `h` is the
    /// fewest moves among optimal paths when there are several.
    #[test]
    fn cost_to_go_and_fewest_moves_of_an_optimal_path_by_hand() {
        let mv = |successor, cost: i64| Move {
            successor,
            cost: Rational::from_integer(cost.into()),
        };
        let int = |v: i64| Some(Rational::from_integer(v.into()));
        for moves_of_0 in [vec![mv(2, 5), mv(1, 1)], vec![mv(1, 1), mv(2, 5)]] {
            let moves = vec![moves_of_0, vec![mv(2, 1)], vec![], vec![mv(3, 1)]];
            let p = Problem::new(moves, 0, vec![2]).unwrap();
            let (g, h) = cost_to_go(&p);
            assert_eq!(g, vec![int(2), int(1), int(0), None]);
            assert_eq!(h, vec![Some(2), Some(1), Some(0), None]);
        }
        // Two optimal paths from 1, of two moves (through 0, scanned first) and of one: h(1)
        // is the fewer, 1.
        let moves = vec![vec![mv(2, 1)], vec![mv(0, 1), mv(2, 2)], vec![]];
        let (g, h) = cost_to_go(&Problem::new(moves, 1, vec![2]).unwrap());
        assert_eq!(g, vec![int(1), int(2), int(0)]);
        assert_eq!(h, vec![Some(1), Some(1), Some(0)]);
    }

    /// A chain listed from its far end (the order in which a sweep over the states moves the
    /// goal's value one state per sweep) gets `G*` and `h` of every state at once: 20,000
    /// states, and a shortcut of equal cost but more moves that `h` must not take.
    #[test]
    fn a_long_chain_gets_its_cost_to_go_without_quadratic_sweeps() {
        let n = 20_000;
        let one = Rational::from_integer(1.into());
        let mut moves: Vec<Vec<Move>> = (0..n - 1)
            .map(|x| {
                vec![Move {
                    successor: x + 1,
                    cost: one.clone(),
                }]
            })
            .collect();
        moves.push(vec![]);
        // From 0 also a move straight to n − 3 of cost n − 3: equal cost, one move.
        moves[0].push(Move {
            successor: n - 3,
            cost: Rational::from_integer(((n - 3) as i64).into()),
        });
        let p = Problem::new(moves, 0, vec![n - 1]).unwrap();
        let started = std::time::Instant::now();
        let (g, h) = cost_to_go(&p);
        for x in [1, 2, n / 2, n - 2, n - 1] {
            assert_eq!(
                g[x],
                Some(Rational::from_integer(((n - 1 - x) as i64).into()))
            );
            assert_eq!(h[x], Some((n - 1 - x) as u64));
        }
        assert_eq!(g[0], Some(Rational::from_integer(((n - 1) as i64).into())));
        assert_eq!(h[0], Some(3), "the shortcut: 1 move, then 2");
        assert!(started.elapsed().as_secs() < 20, "{:?}", started.elapsed());
    }

    /// The values a replay keeps are bounded before the first round: `(rounds + 1) × pairs`
    /// up to `MAX_VALUES` runs, one round more is refused, naming the bound.
    #[test]
    fn rounds_times_pairs_is_bounded_before_the_run() {
        let wide: Vec<Vec<Move>> = (0..1000)
            .map(|_| {
                (0..100)
                    .map(|_| Move {
                        successor: 1000,
                        cost: Rational::from_integer(1.into()),
                    })
                    .collect()
            })
            .chain([vec![]])
            .collect();
        let p = Problem::new(wide, 0, vec![1000]).unwrap();
        let q0 = InitialValues::parse("0").unwrap();
        // 100,001 pairs (the goal's termination pair included): 49 × 100,001 values for 48
        // rounds fit, 50 × 100,001 for 49 do not.
        let run = |rounds| replay(&p, &q0, ReplayOrder::Cyclic, Terminal::Updated, rounds);
        assert_eq!(
            run(48).unwrap().verdict,
            ReplayVerdict::Converged { round: 1 }
        );
        let e = run(49).unwrap_err();
        assert!(
            e.contains("100001 state-action pairs") && e.contains("at most 5000000"),
            "{e}"
        );
    }

    /// `--rounds` may be `MAX_ROUNDS` exactly, not one more, and the bound is checked before any
    /// round runs: from `Q₀ = Q*` (the move of cost 1 to the goal) a replay allowed
    /// `MAX_ROUNDS` rounds is converged at round 0.
    #[test]
    fn rounds_up_to_max_rounds_are_accepted() {
        let one = Move {
            successor: 1,
            cost: Rational::from_integer(1.into()),
        };
        let p = Problem::new(vec![vec![one], vec![]], 0, vec![1]).unwrap();
        let q0 = InitialValues::parse("1,0").unwrap();
        let run = |rounds| replay(&p, &q0, ReplayOrder::Cyclic, Terminal::Updated, rounds);
        assert_eq!(
            run(MAX_ROUNDS).unwrap().verdict,
            ReplayVerdict::Converged { round: 0 }
        );
        assert_eq!(
            run(MAX_ROUNDS + 1).unwrap_err(),
            format!("--rounds {}: at most {MAX_ROUNDS}", MAX_ROUNDS + 1)
        );
    }
}
