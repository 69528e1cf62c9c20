//! Claim C3 (docs/spec.md §6), general form — the certificate and its oracle: if a goal-reaching
//! policy exists and some policy reaches a cycle avoiding the goal, then there are costs `l`
//! and a discount factor `α` for which a discount-optimal policy has infinite true cost.
//!
//! The certificate (costs `l` for a given `α`) comes from a construction: cost 1 on the moves
//! of a goal-avoiding lasso from `x1`, cost `K > 1/((1-α) α^{n-2})` elsewhere. It is *checked*
//! by the exact oracle ([`optimal_policy_avoids_goal`]: every stationary policy evaluated
//! exactly), never trusted. The claim runner is `truecost::claims::c3`.

use super::exact::{ExactInt, Frac, FracExt, Q};
use super::oracle::{evaluate_fast, policies, trajectory, Functional};
use super::tiny::{Tiny, MAX_STATES};

/// The discount factors for which a certificate is required.
pub fn alphas() -> [Q; 2] {
    [Q::new(1, 2), Q::new(9, 10)]
}

/// States from which an infinite walk avoiding the goal exists (greatest fixed point).
pub fn goal_avoiding_core(t: &Tiny) -> [bool; MAX_STATES] {
    let n = t.states();
    let mut w = [false; MAX_STATES];
    for (x, wx) in w.iter_mut().enumerate().take(n) {
        *wx = !t.is_goal(x);
    }
    loop {
        let mut changed = false;
        for x in 0..n {
            if w[x] && !t.moves(x).iter().any(|m| w[m.to as usize]) {
                w[x] = false;
                changed = true;
            }
        }
        if !changed {
            return w;
        }
    }
}

/// Whether the goal is reachable from `x1 = 0`.
pub fn goal_reachable(t: &Tiny) -> bool {
    // A stack of fixed capacity: every state enters it at most once.
    let mut seen = [false; MAX_STATES];
    let mut stack = [0usize; MAX_STATES];
    let mut len = 1;
    seen[0] = true;
    while len > 0 {
        len -= 1;
        let x = stack[len];
        if t.is_goal(x) {
            return true;
        }
        for m in t.moves(x) {
            if !seen[m.to as usize] {
                seen[m.to as usize] = true;
                stack[len] = m.to as usize;
                len += 1;
            }
        }
    }
    false
}

/// The certificate construction for `alpha` (see the module doc). `None` if the hypotheses
/// fail or a cost does not fit. Generic over the width `I` of `alpha`'s exact arithmetic.
pub fn certificate<I: ExactInt>(t: &Tiny, alpha: Q<I>) -> Option<Tiny> {
    let w = goal_avoiding_core(t);
    if !w[0] || !goal_reachable(t) {
        return None;
    }
    let n = t.states() as u32;
    let bound = Q::one() / ((Q::one() - alpha) * alpha.pow(n.saturating_sub(2)));
    // `bound > 0` (0 < α < 1), so the truncating quotient is the floor.
    let k = bound.numer().to_i128() / bound.denom().to_i128() + 1;
    let k = u8::try_from(k).ok()?;
    let mut marked = [[false; 3]; MAX_STATES];
    let mut x = 0usize;
    let mut seen = [false; MAX_STATES];
    while !seen[x] {
        seen[x] = true;
        let i = t.moves(x).iter().position(|m| w[m.to as usize])?;
        marked[x][i] = true;
        x = t.moves(x)[i].to as usize;
    }
    let mut c = *t;
    for y in 0..t.states() {
        for i in 0..t.deg[y] as usize {
            c.moves[y][i].cost = if marked[y][i] { 1 } else { k };
        }
    }
    Some(c)
}

/// The oracle: whether some policy that is discount-optimal from `x1 = 0` at `alpha` never
/// reaches the goal and has only positive stage costs on its trajectory. Generic over the
/// width `I` of the exact values (every policy's discounted value, an unnormalised fraction).
pub fn optimal_policy_avoids_goal<I: ExactInt>(t: &Tiny, alpha: Q<I>) -> bool {
    let ps = policies(t, false);
    let mut best: Option<Frac<I>> = None;
    let mut avoid_at_best = false;
    for p in &ps {
        let tr = trajectory(t, p, 0);
        let FracExt::Fin(value) = evaluate_fast(&tr, Functional::Discounted(alpha), 1) else {
            unreachable!("discounted values are finite")
        };
        let avoids =
            !tr.visits_goal && !tr.terminates && tr.cycle[..tr.cycle_len].iter().all(|&c| c > 0);
        match best {
            Some(b) if value > b => {}
            Some(b) if value == b => avoid_at_best |= avoids,
            _ => {
                best = Some(value);
                avoid_at_best = avoids;
            }
        }
    }
    avoid_at_best
}
