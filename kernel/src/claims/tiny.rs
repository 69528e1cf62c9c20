//! Tiny problems for exhaustive small-scope enumeration (engine 1), with symmetry reduction.
//!
//! A [`Tiny`] is a deterministic problem of docs/spec.md §1 in fixed arrays: at most [`MAX_STATES`]
//! states, at most [`MAX_DEGREE`] moves per state, small integer costs. The goal is always the
//! last state and `x1` is state 0. A [`Family`] enumerates every such problem in a stated scope
//! exactly once *up to relabelling of states*: a labelled problem is kept only if it is the
//! lexicographically least among its images under the permutations of the "free" states (all
//! states but the goal and, when `x1` matters, `x1`). The move list of a state is a multiset
//! (its order is irrelevant to every claim), stored sorted.

/// Largest number of states of a tiny problem.
pub const MAX_STATES: usize = 7;
/// Largest number of moves of one state.
pub const MAX_DEGREE: usize = 3;

/// One move `x → to` with integer stage cost `cost`.
#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Debug, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct TinyMove {
    /// `f(x, u)`.
    pub to: u8,
    /// `l(x, u)`.
    pub cost: u8,
}

/// A tiny deterministic problem: states `0..n`, `x1 = 0`, goal `n − 1` (with the termination
/// action of docs/spec.md §1 in addition to its moves). Read back from a file (a shard of `verify`),
/// it is checked like [`Tiny::from_lists`] checks its lists: a tampered file is refused, not
/// indexed out of bounds.
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(try_from = "TinyFields"))]
pub struct Tiny {
    /// `|X|`.
    pub n: u8,
    /// Number of moves per state.
    pub deg: [u8; MAX_STATES],
    /// The moves, sorted per state.
    pub moves: [[TinyMove; MAX_DEGREE]; MAX_STATES],
}

/// The fields of a [`Tiny`] as read, before the checks of [`Tiny::check`].
#[cfg(feature = "serde")]
#[derive(serde::Deserialize)]
struct TinyFields {
    n: u8,
    deg: [u8; MAX_STATES],
    moves: [[TinyMove; MAX_DEGREE]; MAX_STATES],
}

#[cfg(feature = "serde")]
impl TryFrom<TinyFields> for Tiny {
    type Error = &'static str;

    fn try_from(f: TinyFields) -> Result<Tiny, &'static str> {
        let t = Tiny {
            n: f.n,
            deg: f.deg,
            moves: f.moves,
        };
        t.check().map(|()| t)
    }
}

impl Tiny {
    /// An empty problem with `n` states.
    pub fn empty(n: usize) -> Tiny {
        assert!((1..=MAX_STATES).contains(&n));
        Tiny {
            n: n as u8,
            deg: [0; MAX_STATES],
            moves: [[TinyMove::default(); MAX_DEGREE]; MAX_STATES],
        }
    }

    /// Builds a tiny problem from per-state move lists `(to, cost)`.
    ///
    /// ```
    /// use truecost_kernel::claims::tiny::Tiny;
    /// let t = Tiny::from_lists(&[vec![(0, 0), (1, 1)], vec![]]);
    /// assert_eq!(t.goal(), 1);
    /// assert_eq!(t.moves(0).len(), 2);
    /// ```
    pub fn from_lists(lists: &[Vec<(u8, u8)>]) -> Tiny {
        let mut t = Tiny::empty(lists.len());
        for (x, list) in lists.iter().enumerate() {
            assert!(list.len() <= MAX_DEGREE);
            t.deg[x] = list.len() as u8;
            for (k, &(to, cost)) in list.iter().enumerate() {
                assert!((to as usize) < lists.len());
                t.moves[x][k] = TinyMove { to, cost };
            }
        }
        t
    }

    /// Whether the arrays describe a problem: `1 ≤ n ≤ MAX_STATES`, at most [`MAX_DEGREE`]
    /// moves per state, none beyond state `n − 1`, every move's target a state.
    ///
    /// ```
    /// use truecost_kernel::claims::tiny::Tiny;
    /// let mut t = Tiny::from_lists(&[vec![(1, 1)], vec![]]);
    /// assert!(t.check().is_ok());
    /// t.deg[0] = 9;
    /// assert!(t.check().is_err());
    /// ```
    pub fn check(&self) -> Result<(), &'static str> {
        let n = self.n as usize;
        if !(1..=MAX_STATES).contains(&n) {
            return Err("a tiny problem has 1 to 7 states");
        }
        for x in 0..MAX_STATES {
            let d = self.deg[x] as usize;
            if d > MAX_DEGREE || (x >= n && d > 0) {
                return Err("a state has more moves than a tiny problem allows");
            }
            if self.moves[x][..d].iter().any(|m| m.to as usize >= n) {
                return Err("a move leads outside the problem's states");
            }
        }
        Ok(())
    }

    /// Number of states.
    #[inline]
    pub fn states(&self) -> usize {
        self.n as usize
    }

    /// The goal (the last state).
    #[inline]
    pub fn goal(&self) -> usize {
        self.n as usize - 1
    }

    /// Whether `x` is the goal.
    #[inline]
    pub fn is_goal(&self, x: usize) -> bool {
        x + 1 == self.n as usize
    }

    /// The moves of `x`.
    #[inline]
    pub fn moves(&self, x: usize) -> &[TinyMove] {
        &self.moves[x][..self.deg[x] as usize]
    }

    /// Total number of moves.
    pub fn move_count(&self) -> usize {
        (0..self.states()).map(|x| self.deg[x] as usize).sum()
    }

    /// Sum of all stage costs.
    pub fn cost_sum(&self) -> u64 {
        (0..self.states())
            .flat_map(|x| self.moves(x))
            .map(|m| m.cost as u64)
            .sum()
    }

    /// The problem in the library's model (`x1 = 0`, goal `n − 1`), for problem files: any
    /// type built `From<Tiny>` — in `truecost`, `truecost::model::Problem` (its exact rational
    /// costs need big integers, which this crate, verified by Kani, does not depend on).
    pub fn to_problem<P: From<Tiny>>(&self) -> P {
        P::from(*self)
    }

    /// A one-line description: `0: ->1 (1), ->0 (0); 1 (goal)`.
    pub fn describe(&self) -> String {
        self.describe_with(|(x, i)| self.moves(x)[i].cost.to_string())
    }

    /// [`Tiny::describe`] with each move's cost replaced by `label((state, move index))` (e.g.
    /// the name of the SMT unknown that is its cost).
    ///
    /// ```
    /// use truecost_kernel::claims::tiny::Tiny;
    /// let t = Tiny::from_lists(&[vec![(0, 0), (1, 1)], vec![]]);
    /// assert_eq!(t.describe_with(|(x, i)| format!("l{x}{i}")), "0: ->0 (l00), ->1 (l01); 1 (goal)");
    /// ```
    pub fn describe_with(&self, label: impl Fn((usize, usize)) -> String) -> String {
        (0..self.states())
            .map(|x| {
                let list: Vec<String> = self
                    .moves(x)
                    .iter()
                    .enumerate()
                    .map(|(i, m)| format!("->{} ({})", m.to, label((x, i))))
                    .collect();
                let tag = if self.is_goal(x) { " (goal)" } else { "" };
                if list.is_empty() {
                    format!("{x}{tag}")
                } else {
                    format!("{x}{tag}: {}", list.join(", "))
                }
            })
            .collect::<Vec<_>>()
            .join("; ")
    }
}

/// A scope of tiny problems: every problem with this many states, these degrees and costs.
#[derive(Clone, Debug)]
pub struct Family {
    n: usize,
    initial_fixed: bool,
    options: Vec<Vec<TinyMove>>,
    goal_options: Vec<Vec<TinyMove>>,
    perms: Vec<Vec<u8>>,
}

/// The parameters of a [`Family`].
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FamilySpec {
    /// Number of states (goal = last, `x1` = 0).
    pub states: usize,
    /// Whether `x1` is distinguished (excluded from the relabelling symmetry).
    pub initial_fixed: bool,
    /// Inclusive range of the number of moves of a non-goal state.
    pub degree: (usize, usize),
    /// Inclusive range of the number of moves of the goal.
    pub goal_degree: (usize, usize),
    /// The cost set.
    pub costs: Vec<u8>,
    /// Moves of one state have distinct successors (structures without costs: pass `[0]`).
    pub distinct_successors: bool,
}

impl FamilySpec {
    /// A readable statement of the scope.
    pub fn describe(&self) -> String {
        let costs: Vec<String> = self.costs.iter().map(|c| c.to_string()).collect();
        let deg = |(a, b): (usize, usize)| {
            if a == b {
                format!("{a}")
            } else {
                format!("{a}-{b}")
            }
        };
        format!(
            "{} states, {} moves per non-goal state, {} at the goal, costs {{{}}}{}",
            self.states,
            deg(self.degree),
            deg(self.goal_degree),
            costs.join(","),
            if self.distinct_successors {
                ", distinct successors"
            } else {
                ""
            }
        )
    }
}

/// Every multiset of `lo..=hi` moves of `alphabet` (as non-decreasing sequences of its
/// entries; with `distinct`, no two with the same successor), in depth-first preorder: a
/// sequence before its extensions, extensions by earlier entries first. Iterative: `next[k]` is
/// the next entry to try at position `k`.
fn multisets(alphabet: &[TinyMove], lo: usize, hi: usize, distinct: bool) -> Vec<Vec<TinyMove>> {
    let mut out = Vec::new();
    let mut cur: Vec<TinyMove> = Vec::new();
    let mut next: Vec<usize> = vec![0];
    if lo == 0 {
        out.push(Vec::new());
    }
    loop {
        let depth = cur.len();
        let i = next[depth];
        if depth == hi || i == alphabet.len() {
            if depth == 0 {
                return out;
            }
            cur.pop();
            next.pop();
            continue;
        }
        next[depth] = i + 1;
        if distinct && cur.iter().any(|m| m.to == alphabet[i].to) {
            continue;
        }
        cur.push(alphabet[i]);
        next.push(i);
        if cur.len() >= lo {
            out.push(cur.clone());
        }
    }
}

/// Every ordering of `items`, in lexicographic order of the positions they are taken from
/// (the identity first); iterative, by the successor of a permutation of positions.
fn permutations(items: &[u8]) -> Vec<Vec<u8>> {
    let k = items.len();
    let mut at: Vec<usize> = (0..k).collect();
    let mut out = Vec::new();
    loop {
        out.push(at.iter().map(|&i| items[i]).collect());
        // The next permutation of the positions: the longest non-increasing suffix, then the
        // least larger entry swapped in before it, the suffix reversed.
        let Some(p) = (1..k).rev().find(|&j| at[j - 1] < at[j]).map(|j| j - 1) else {
            return out;
        };
        let q = (p + 1..k)
            .rev()
            .find(|&j| at[j] > at[p])
            .expect("a larger entry");
        at.swap(p, q);
        at[p + 1..].reverse();
    }
}

impl Family {
    /// Prepares the enumeration of a scope.
    pub fn new(spec: &FamilySpec) -> Family {
        let n = spec.states;
        assert!((1..=MAX_STATES).contains(&n) && spec.degree.1 <= MAX_DEGREE);
        let mut alphabet = Vec::new();
        for to in 0..n as u8 {
            for &cost in &spec.costs {
                alphabet.push(TinyMove { to, cost });
            }
        }
        alphabet.sort();
        let options = multisets(
            &alphabet,
            spec.degree.0,
            spec.degree.1,
            spec.distinct_successors,
        );
        let goal_options = multisets(
            &alphabet,
            spec.goal_degree.0,
            spec.goal_degree.1,
            spec.distinct_successors,
        );
        let first_free = if spec.initial_fixed { 1 } else { 0 };
        let free: Vec<u8> = (first_free..n.saturating_sub(1)).map(|x| x as u8).collect();
        // Each permutation as a full map old state -> new state; the identity is dropped.
        let perms = permutations(&free)
            .into_iter()
            .map(|image| {
                let mut map: Vec<u8> = (0..n as u8).collect();
                for (k, &x) in free.iter().enumerate() {
                    map[x as usize] = image[k];
                }
                map
            })
            .filter(|map| map.iter().enumerate().any(|(i, &y)| i as u8 != y))
            .collect();
        Family {
            n,
            initial_fixed: spec.initial_fixed,
            options,
            goal_options,
            perms,
        }
    }

    /// Number of labelled problems (before symmetry reduction).
    pub fn labelled_count(&self) -> u64 {
        let mut c = self.goal_options.len() as u64;
        for _ in 0..self.n - 1 {
            c *= self.options.len() as u64;
        }
        c
    }

    /// Every problem of the family once up to relabelling (the canonical ones), in index
    /// order, sequentially (the parallel pass is `truecost::claims::enumerate`).
    ///
    /// ```
    /// use truecost_kernel::claims::tiny::{Family, FamilySpec};
    /// let spec = FamilySpec { states: 2, initial_fixed: false, degree: (1, 1), goal_degree: (0, 0),
    ///     costs: vec![0], distinct_successors: false };
    /// // State 0 has one move, to itself or to the goal.
    /// assert_eq!(Family::new(&spec).canonical().count(), 2);
    /// ```
    pub fn canonical(&self) -> impl Iterator<Item = Tiny> + '_ {
        (0..self.labelled_count())
            .map(|i| self.problem(i))
            .filter(|t| self.is_canonical(t))
    }

    /// The labelled problem with this index (`0..labelled_count()`).
    pub fn problem(&self, mut index: u64) -> Tiny {
        let mut t = Tiny::empty(self.n);
        for x in 0..self.n {
            let opts = if x + 1 == self.n {
                &self.goal_options
            } else {
                &self.options
            };
            let k = (index % opts.len() as u64) as usize;
            index /= opts.len() as u64;
            let list = &opts[k];
            t.deg[x] = list.len() as u8;
            t.moves[x][..list.len()].copy_from_slice(list);
        }
        t
    }

    /// Whether `t` is the representative of its class under relabelling of the free states.
    pub fn is_canonical(&self, t: &Tiny) -> bool {
        let n = self.n;
        for map in &self.perms {
            // Build the image and compare state by state (new numbering).
            let mut inverse = [0u8; MAX_STATES];
            for (old, &new) in map.iter().enumerate() {
                inverse[new as usize] = old as u8;
            }
            let mut decided = false;
            for new in 0..n {
                let old = inverse[new] as usize;
                let mut image = [TinyMove::default(); MAX_DEGREE];
                let d = t.deg[old] as usize;
                for (k, m) in t.moves(old).iter().enumerate() {
                    image[k] = TinyMove {
                        to: map[m.to as usize],
                        cost: m.cost,
                    };
                }
                // In order by insertion (at most MAX_DEGREE moves).
                for k in 1..d {
                    let mut j = k;
                    while j > 0 && image[j - 1] > image[j] {
                        image.swap(j - 1, j);
                        j -= 1;
                    }
                }
                let own = t.moves(new);
                let ord = (own.len(), own).cmp(&(d, &image[..d]));
                match ord {
                    std::cmp::Ordering::Less => {
                        decided = true;
                        break;
                    }
                    std::cmp::Ordering::Greater => return false,
                    std::cmp::Ordering::Equal => {}
                }
            }
            let _ = decided;
        }
        true
    }

    /// Whether `x1` is distinguished.
    pub fn initial_fixed(&self) -> bool {
        self.initial_fixed
    }
}

/// Minimality key of a counterexample: fewer states, then fewer moves, then smaller total
/// cost, then the enumeration index.
pub fn minimality_key(t: &Tiny, extra: u64, index: u64) -> (usize, usize, u64, u64, u64) {
    (t.states(), t.move_count(), t.cost_sum(), extra, index)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every tuple of `len` numbers below `k`, in lexicographic order (an odometer).
    fn tuples(k: usize, len: usize) -> Vec<Vec<usize>> {
        let mut out = Vec::new();
        if k == 0 && len > 0 {
            return out;
        }
        let mut digits = vec![0usize; len];
        loop {
            out.push(digits.clone());
            let Some(p) = (0..len).rev().find(|&p| digits[p] + 1 < k) else {
                return out;
            };
            digits[p] += 1;
            digits[p + 1..].iter_mut().for_each(|d| *d = 0);
        }
    }

    /// `permutations` lists every ordering once, in lexicographic order of positions: the
    /// tuples of distinct positions, filtered from all tuples.
    #[test]
    fn permutations_are_the_distinct_tuples_in_order() {
        for k in 0..=5 {
            let items: Vec<u8> = (0..k as u8).map(|i| 10 + 3 * i).collect();
            let want: Vec<Vec<u8>> = tuples(k, k)
                .into_iter()
                .filter(|t| (0..k).all(|i| !t[..i].contains(&t[i])))
                .map(|t| t.iter().map(|&i| items[i]).collect())
                .collect();
            let got = permutations(&items);
            assert_eq!(got.len(), (1..=k).product::<usize>());
            assert_eq!(got, want, "{k}");
        }
    }

    /// `multisets` lists the non-decreasing tuples of alphabet positions of every length in
    /// `lo..=hi` (distinct successors when asked), in lexicographic order (a tuple before its
    /// extensions).
    #[test]
    fn multisets_are_the_non_decreasing_tuples_in_order() {
        let alphabet: Vec<TinyMove> = [(0, 0), (0, 1), (1, 0), (2, 5)]
            .iter()
            .map(|&(to, cost)| TinyMove { to, cost })
            .collect();
        for (lo, hi) in [(0, 0), (0, 3), (1, 2), (2, 3), (3, 3)] {
            for distinct in [false, true] {
                let mut want: Vec<Vec<usize>> = (lo..=hi)
                    .flat_map(|len| tuples(alphabet.len(), len))
                    .filter(|t| t.windows(2).all(|w| w[0] <= w[1]))
                    .filter(|t| {
                        !distinct
                            || (0..t.len())
                                .all(|i| (0..i).all(|j| alphabet[t[j]].to != alphabet[t[i]].to))
                    })
                    .collect();
                want.sort();
                let want: Vec<Vec<TinyMove>> = want
                    .iter()
                    .map(|t| t.iter().map(|&i| alphabet[i]).collect())
                    .collect();
                assert_eq!(multisets(&alphabet, lo, hi, distinct), want, "{lo} {hi}");
            }
        }
    }

    /// Two free states, one move each to one of 3 states, cost 0: labelled 3·3 with the goal
    /// having no moves; classes under swapping states 0 and 1 (x1 not fixed): hand count.
    #[test]
    fn orbit_count_small() {
        let spec = FamilySpec {
            states: 3,
            initial_fixed: false,
            degree: (1, 1),
            goal_degree: (0, 0),
            costs: vec![0],
            distinct_successors: false,
        };
        let f = Family::new(&spec);
        assert_eq!(f.labelled_count(), 9);
        let kept = (0..9).filter(|&i| f.is_canonical(&f.problem(i))).count();
        // Burnside: (9 labelled + fixed points of the swap) / 2. A problem is fixed by the swap
        // when 0's move is the image of 1's: (0->a, 1->swap(a)) with a in {0,1,2} → 3 fixed.
        assert_eq!(kept, (9 + 3) / 2);
    }
}
