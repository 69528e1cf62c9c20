//! Shared by the kernel's integration tests: a deterministic generator of small planning graphs,
//! a value type without an order key, and brute-force reference answers written independently
//! of the planners (plain loops over the adjacency lists the tests build).
#![allow(dead_code)] // each test crate uses a different part of this module

use std::cmp::Ordering;

use truecost_kernel::claims::exact::Q;
use truecost_kernel::claims::tiny::Tiny;
use truecost_kernel::model::Graph;
use truecost_kernel::value::{CostValue, Units};

/// splitmix64: a tiny deterministic generator for the tests' random graphs.
pub struct SplitMix(pub u64);

impl SplitMix {
    /// The next 64 random bits.
    pub fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in `0..n` (n > 0; the tiny modulo bias does not matter here).
    pub fn below(&mut self, n: u64) -> u64 {
        self.next() % n
    }
}

/// A planning graph as plain data: ordered move lists `(successor, cost)` with integer costs,
/// the initial node and the goals (increasing).
#[derive(Clone, Debug)]
pub struct Plain {
    pub adjacency: Vec<Vec<(usize, u64)>>,
    pub initial: usize,
    pub goals: Vec<usize>,
}

impl Plain {
    /// A random graph of 1 to `max_nodes` nodes; costs in `min_cost..=max_cost` (few distinct
    /// costs, so many ties), each node a goal with probability 1/4.
    pub fn random(draw: &mut SplitMix, max_nodes: u64, min_cost: u64, max_cost: u64) -> Plain {
        let n = 1 + draw.below(max_nodes) as usize;
        let mut adjacency = vec![Vec::new(); n];
        for _ in 0..draw.below(3 * n as u64 + 1) {
            let x = draw.below(n as u64) as usize;
            let y = draw.below(n as u64) as usize;
            let c = min_cost + draw.below(max_cost - min_cost + 1);
            adjacency[x].push((y, c));
        }
        let goals = (0..n).filter(|_| draw.below(4) == 0).collect();
        let initial = draw.below(n as u64) as usize;
        Plain {
            adjacency,
            initial,
            goals,
        }
    }

    pub fn nodes(&self) -> usize {
        self.adjacency.len()
    }

    pub fn is_goal(&self, v: usize) -> bool {
        self.goals.contains(&v)
    }

    /// The kernel's graph over any value type built from integer costs.
    pub fn graph<V: CostValue>(&self, value: impl Fn(u64) -> V) -> Graph<V> {
        let adjacency = self
            .adjacency
            .iter()
            .map(|list| list.iter().map(|&(y, c)| (y, value(c))).collect())
            .collect();
        Graph::from_adjacency(
            adjacency,
            self.initial,
            &self.goals,
            (0..self.nodes()).collect(),
            (),
        )
    }

    pub fn units(&self) -> Graph<Units> {
        self.graph(Units)
    }

    pub fn floats(&self) -> Graph<f64> {
        self.graph(|c| c as f64)
    }

    pub fn no_key(&self) -> Graph<NoKey> {
        self.graph(NoKey)
    }

    /// `G*` by Bellman–Ford over the integer costs (`None` = `+∞`).
    pub fn optimal_costs(&self) -> Vec<Option<u64>> {
        let n = self.nodes();
        let mut g: Vec<Option<u64>> = (0..n).map(|v| self.is_goal(v).then_some(0)).collect();
        for _ in 0..n {
            for x in 0..n {
                for &(y, c) in &self.adjacency[x] {
                    if let Some(gy) = g[y] {
                        if g[x].is_none_or(|gx| c + gy < gx) {
                            g[x] = Some(c + gy);
                        }
                    }
                }
            }
        }
        g
    }

    /// The cost of a path given by its nodes, taking the cheapest move between consecutive
    /// nodes (panics if two consecutive nodes are not joined by a move).
    pub fn walk_cost(&self, path: &[usize]) -> u64 {
        path.windows(2)
            .map(|w| {
                self.adjacency[w[0]]
                    .iter()
                    .filter(|&&(y, _)| y == w[1])
                    .map(|&(_, c)| c)
                    .min()
                    .expect("consecutive path nodes are joined by a move")
            })
            .sum()
    }
}

/// An exact value type with no order key (the default `order_key` = `None`), so that Dijkstra
/// runs on its `Compared` frontier (a heap of entries compared with `CostValue::compare`)
/// instead of the `Keyed` one. `u64::MAX` is `+∞`.
#[derive(Clone, Copy, Debug, PartialEq, PartialOrd)]
pub struct NoKey(pub u64);

impl CostValue for NoKey {
    const EXACT: bool = true;
    fn zero() -> Self {
        NoKey(0)
    }
    fn infinity() -> Self {
        NoKey(u64::MAX)
    }
    fn is_finite(&self) -> bool {
        self.0 != u64::MAX
    }
    fn plus(&self, other: &Self) -> Self {
        if self.0 == u64::MAX || other.0 == u64::MAX {
            NoKey(u64::MAX)
        } else {
            NoKey(self.0 + other.0)
        }
    }
    fn compare(&self, other: &Self) -> Ordering {
        self.0.cmp(&other.0)
    }
}

/// A cost-to-go of the kernel as `Option<u64>` (`None` = `+∞`), for comparison with the brute
/// force.
pub fn finite<V: CostValue>(values: &[V], raw: impl Fn(&V) -> u64) -> Vec<Option<u64>> {
    values
        .iter()
        .map(|v| v.is_finite().then(|| raw(v)))
        .collect()
}

/// Every end point given and 0, the midpoints between consecutive ones, points just beside each
/// (`±1/1000`) and points far out (`∓100`): a convex set of rationals whose ends are among the
/// points is decided by its members on this grid (shared by the C4 interval and instance tests
/// and `tests/claims_algebra.rs`).
pub fn rational_grid(points: &[Q]) -> Vec<Q> {
    let mut pts: Vec<Q> = points.to_vec();
    pts.push(Q::ZERO);
    pts.sort();
    pts.dedup();
    let mut g = pts.clone();
    for w in pts.windows(2) {
        g.push((w[0] + w[1]) * Q::new(1, 2));
    }
    for &p in &pts {
        g.push(p - Q::new(1, 1000));
        g.push(p + Q::new(1, 1000));
    }
    g.push(pts[0] - Q::int(100));
    g.push(pts[pts.len() - 1] + Q::int(100));
    g.sort();
    g.dedup();
    g
}

/// A random tiny problem of 2–4 states, each with one or two moves of cost 0–2 to any state
/// (the family of the Q-learning round tests).
pub fn random_tiny(draw: &mut SplitMix) -> Tiny {
    let n = 2 + draw.below(3) as usize;
    let lists: Vec<Vec<(u8, u8)>> = (0..n)
        .map(|_| {
            (0..1 + draw.below(2))
                .map(|_| (draw.below(n as u64) as u8, draw.below(3) as u8))
                .collect()
        })
        .collect();
    Tiny::from_lists(&lists)
}
