//! The finite model a certificate is checked against: states `0..n`, per state an ordered list
//! of actions, each with a stage cost, an expected reward and outcomes with exact
//! probabilities; goal and terminal flags. Plain data: whoever reads a problem (a problem file,
//! a paper problem, an environment) fills it in, and nothing here depends on a solver.

use num_traits::{One, Signed, ToPrimitive, Zero};

use crate::value::Rational;

/// One action: `l(x, u)`, the reward `r(x, u)` of the discounted objective, and the outcomes
/// `(y, p(y | x, u))`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct MdpAction {
    /// The stage cost (truecost, deterministic G*).
    pub cost: Rational,
    /// The expected reward (discounted objective).
    pub reward: Rational,
    /// The successors with their probabilities.
    pub outcomes: Vec<(usize, Rational)>,
}

/// A finite Markov decision process with goals (truecost) and terminal states (discounted).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Mdp {
    /// Per state: a goal (value 0, the episode ends; its own actions play no part).
    pub goal: Vec<bool>,
    /// Per state: the episode ends there (discounted value 0): goals, traps, action-less states.
    pub terminal: Vec<bool>,
    /// Per state: its actions, in order (a certificate's policy names an index into this list).
    pub actions: Vec<Vec<MdpAction>>,
}

/// The tag on the first line of [`Mdp::canonical_text`].
pub const CANONICAL_FORMAT: &str = "truecost-canonical-mdp/1";

impl Mdp {
    /// The number of states.
    pub fn states(&self) -> usize {
        self.actions.len()
    }

    /// Why this is not a well-formed model, if it is not: the flags and action lists disagree
    /// in length, a successor is not a state, a probability is outside `(0, 1]`, or an
    /// action's probabilities do not sum to exactly 1. The first violation, in one line.
    pub fn malformed(&self) -> Option<String> {
        let n = self.states();
        if self.goal.len() != n || self.terminal.len() != n {
            return Some(format!(
                "the model has {n} action lists, {} goal flags and {} terminal flags",
                self.goal.len(),
                self.terminal.len()
            ));
        }
        for (x, list) in self.actions.iter().enumerate() {
            for (i, a) in list.iter().enumerate() {
                let mut total = Rational::zero();
                for (y, p) in &a.outcomes {
                    if *y >= n {
                        return Some(format!(
                            "state {x}, action {i}: successor {y} is not a state"
                        ));
                    }
                    if !p.is_positive() || p > &Rational::one() {
                        return Some(format!(
                            "state {x}, action {i}: probability {p} is not in (0, 1]"
                        ));
                    }
                    total += p;
                }
                if !total.is_one() {
                    return Some(format!(
                        "state {x}, action {i}: probabilities sum to {total}, not 1"
                    ));
                }
            }
        }
        None
    }

    /// The canonical export whose SHA-256 a certificate for `--problem` or `--env` carries:
    /// UTF-8 lines, `\n`-terminated —
    ///
    /// ```text
    /// truecost-canonical-mdp/1
    /// states <n>
    /// state <x> <goal 0|1> <terminal 0|1> <number of actions>     (for x = 0..n, in order)
    /// action <cost> <reward> <outcomes> <y>:<p> <y>:<p> ...       (its actions, in order)
    /// ```
    ///
    /// every number as its reduced fraction `p/q` (or the integer `p` when `q = 1`), outcomes in
    /// the model's order.
    ///
    /// ```
    /// use truecost::certificate::{Mdp, MdpAction};
    /// let r = |s: &str| s.parse().unwrap();
    /// let m = Mdp {
    ///     goal: vec![false, true],
    ///     terminal: vec![false, true],
    ///     actions: vec![vec![MdpAction { cost: r("3/2"), reward: r("-3/2"), outcomes: vec![(1, r("1"))] }], vec![]],
    /// };
    /// assert_eq!(m.canonical_text(), "truecost-canonical-mdp/1\nstates 2\nstate 0 0 0 1\naction 3/2 -3/2 1 1:1\nstate 1 1 1 0\n");
    /// ```
    pub fn canonical_text(&self) -> String {
        use std::fmt::Write;
        let mut s = String::new();
        let _ = writeln!(s, "{CANONICAL_FORMAT}");
        let _ = writeln!(s, "states {}", self.states());
        for (x, list) in self.actions.iter().enumerate() {
            let _ = writeln!(
                s,
                "state {x} {} {} {}",
                u8::from(self.goal[x]),
                u8::from(self.terminal[x]),
                list.len()
            );
            for a in list {
                s.push_str("action ");
                push_ratio(&mut s, &a.cost);
                s.push(' ');
                push_ratio(&mut s, &a.reward);
                let _ = write!(s, " {}", a.outcomes.len());
                for (y, p) in &a.outcomes {
                    let _ = write!(s, " {y}:");
                    push_ratio(&mut s, p);
                }
                s.push('\n');
            }
        }
        s
    }
}

/// Appends `r` as its `Display` writes it (`p/q`, or `p` when `q = 1`), through machine
/// integers when they hold it (no big-integer text, no allocation).
fn push_ratio(s: &mut String, r: &Rational) {
    use std::fmt::Write;
    let _ = match (r.numer().to_i64(), r.denom().to_u64()) {
        (Some(n), Some(1)) => write!(s, "{n}"),
        (Some(n), Some(d)) => write!(s, "{n}/{d}"),
        _ => write!(s, "{r}"),
    };
}

#[cfg(test)]
mod tests {
    use super::push_ratio;
    use crate::value::Rational;
    use num_bigint::BigInt;

    #[test]
    fn ratios_are_written_as_display_writes_them() {
        let big: BigInt = num_traits::pow(BigInt::from(2), 70);
        let cases = [
            Rational::from_integer(0.into()),
            Rational::from_integer((-5).into()),
            Rational::new(3.into(), 2.into()),
            Rational::new((-3).into(), 2.into()),
            Rational::new(i64::MIN.into(), 1.into()),
            Rational::new(1.into(), u64::MAX.into()),
            Rational::new(big.clone(), 3.into()),
            Rational::new(1.into(), big.clone()),
            Rational::new(-big, 7.into()),
            // Not reduced: written as stored, as Display writes it.
            Rational::new_raw(6.into(), 4.into()),
            Rational::new_raw(5.into(), 1.into()),
        ];
        for r in &cases {
            let mut s = String::new();
            push_ratio(&mut s, r);
            assert_eq!(s, r.to_string());
        }
    }
}
