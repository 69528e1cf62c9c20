//! Certified answers: a certificate states an optimal value per state and a policy, and
//! [`check`] re-checks it against a problem read afresh, in exact arithmetic, with no solver
//! code — only the model (plain data, [`Mdp`]), big rationals and SHA-256. Whatever computed
//! the certificate, an accepted one is optimal for the reasons below.
//!
//! Notation: `n` states; `U(x)` the ordered actions of `x`; `l(x, a)` the stage cost,
//! `r(x, a)` the expected reward, `p(y | x, a)` the outcome probabilities (exact, summing to
//! 1: checked); `V` the certificate's values, `π` its policy, `F = {x : V(x) finite}`.
//! A policy `μ` is *proper from x* if, from `x`, it reaches a goal with probability 1; its
//! truecost `J_μ(x)` is then the expected total stage cost until the goal (`+∞` if it is not
//! proper from `x`). Stationary policies throughout.
//!
//! # Truecost (least expected cost among policies that reach a goal with probability 1)
//!
//! With `Q(x, a) = l(x, a) + Σ_y p(y | x, a) V(y)`:
//!
//! 1. **goal** — `V(g) = 0` at every goal `g` (goals terminate at no cost).
//! 2. **policy** — at every non-goal `x ∈ F`, `π(x)` indexes `U(x)`.
//! 3. **closed** — every outcome of `π(x)`, `x ∈ F`, is in `F`.
//! 4. **evaluation** — `V(x) = Q(x, π(x))` exactly at every non-goal `x ∈ F`.
//! 5. **optimality** — `V(x) ≤ Q(x, a)` for every non-goal `x ∈ F` and every `a ∈ U(x)`
//!    whose outcomes are all in `F`.
//! 6. **proper** — from every `x ∈ F` a goal is reachable in the graph of `π`'s outcomes.
//! 7. **infinite** — no state outside `F` lies in `W*`, the greatest set `W` such that from
//!    every state of `W` a goal can be reached (with positive probability, by a path) using
//!    only actions all of whose outcomes are in `W`. The checker computes `W*` itself (from
//!    `W` = all states, keep the states that reach a goal that way, repeat until stable).
//!
//! Why these suffice:
//!
//! * *`π` is proper from every state of `F`, and `J_π = V` on `F`.* By 3, `F` is closed under
//!   `π`; by 6 a goal is reachable from every state of `F` in the finite Markov chain of `π`
//!   restricted to `F`, so the goals are reached with probability 1. Then `J_π` is the unique
//!   solution of `J = l_π + P_π J` on `F` with `J = 0` at goals, and `V` solves it (1, 4).
//! * *No policy is proper from a state outside `F`.* Let `μ` be proper from `x` and `R` the
//!   states reachable from `x` under `μ`. `μ` is proper from every state of `R`, so from each a
//!   goal is reachable within `R` using `μ`'s actions, whose outcomes stay in `R`. Every `W` of
//!   the iteration contains `R` (induction: if `R ⊆ W`, `μ`'s actions on `R` keep to `W`, so
//!   `R` survives the round), hence `x ∈ R ⊆ W*`, and 7 puts `x` in `F`. So `V(x) = inf` is the
//!   truecost optimum outside `F`.
//! * *`V(x) ≤ J_μ(x)` for every `μ` proper from `x ∈ F` (maximum principle).* With `R` as above,
//!   `R ⊆ W* ⊆ F`, so every action `μ` takes on `R` has its outcomes in `F` and 5 applies:
//!   `V ≤ l_μ + P_μ V` on the non-goals of `R`, while `J_μ = l_μ + P_μ J_μ` there. Hence
//!   `D = V − J_μ` satisfies `D ≤ P_μ D` on non-goals of `R` and `D = 0` at goals. Let `M` be the
//!   maximum of `D` over `R` and `A` the states where it is attained. If `M > 0`, `A` has no
//!   goal, and at `z ∈ A`, `M = D(z) ≤ Σ p D ≤ M` forces every outcome of `μ(z)` into `A`: `A`
//!   is closed under `μ` and holds no goal, so `μ` is not proper from `z` — a contradiction.
//!   So `M ≤ 0`: `V(x) ≤ J_μ(x)`, and `V = J_π` attains it.
//!
//! In Coq (`proofs/coq/Certificate.v`, re-checked by `verify`'s Coq level): the maximum
//! principle is `Truecost.Certificate.maximum_principle`, the optimality of `V` against every
//! policy proper on a closed set is `Truecost.Certificate.certificate_optimal`, and "no policy
//! is proper from a state outside `W*`" is `Truecost.Certificate.proper_inside_Wstar` (every
//! round of the checker's iteration contains every closed set from which a policy is proper).
//! The first point — a policy proper on `F` has `J_π` as the unique solution of its equations
//! — is the standard fact about absorbing Markov chains, argued here, not proved in Coq.
//!
//! Nothing above uses `l ≥ 0` (the readers refuse negative stage costs anyway), and the
//! conditions are checked exactly: values over one common denominator, each `Q` as an integer
//! numerator over a positive integer denominator, compared by cross-multiplication.
//!
//! # Deterministic `G*`
//!
//! The deterministic planners' `G*` (Dijkstra, VI) is the truecost objective of a model whose
//! every action has one outcome `f(x, a)` with probability 1: the same conditions read
//! `V(g) = 0`, `V(x) = l(x, π(x)) + V(f(x, π(x)))`, `V(x) ≤ l(x, a) + V(f(x, a))`, the path of
//! `π` from every finite state reaches a goal (6), and `W*` is the set of states with a path
//! to a goal. The checker also checks that every action has exactly one outcome
//! (**deterministic**).
//!
//! # Discounted (greatest expected discounted reward, `0 < α < 1`)
//!
//! Terminal states (goals, traps, action-less states) end the episode: their value is 0.
//! With `Q(x, a) = r(x, a) + α Σ_y p(y | x, a) V(y)`: **alpha** `0 < α < 1`; **finite** every
//! value is finite; **goal** `V = 0` and `π = null` at terminal states; **policy** `π(x)`
//! indexes `U(x)` at every other state; **evaluation** `V(x) = Q(x, π(x))`; **optimality**
//! `V(x) ≥ Q(x, a)` for every `a`. Then `V = max_a Q(·, a)`: `V` is the fixed point of the
//! Bellman operator, a contraction of modulus `α` in the maximum norm, hence `V = V*`; and
//! `V = Q(·, π)` makes `V` the value of `π` (the unique fixed point of its own contraction),
//! so `π` is optimal.
//!
//! # Reach (greatest probability of reaching a goal)
//!
//! With `Q(x, a) = Σ_y p(y | x, a) V(y)` and `Z = {x : V(x) = 0}`: **range** every value is
//! finite and in `[0, 1]`; **goal** `V = 1` and `π = null` at goals; **policy** `π(x)` indexes
//! `U(x)` at every non-goal `x ∉ Z`, `π = null` on `Z`; **evaluation** `V(x) = Q(x, π(x))`
//! exactly at every non-goal `x ∉ Z`; **optimality** `V(x) ≥ Q(x, a)` for every non-goal `x`
//! and every `a ∈ U(x)`; **proper** from every non-goal `x ∉ Z` a goal or a state of `Z` is
//! reachable in the graph of `π`'s outcomes. These are the two halves of the certificates
//! Storm emits for reachability, made exact: an *inductive* upper bound and a lower bound by a
//! policy whose absorption a ranking (here the graph search) guarantees; with exact values one
//! vector serves as both.
//!
//! * *Upper bound: no policy (even history-dependent) reaches a goal from `x` with probability
//!   above `V(x)`.* Let `Φ(W)(x) = 1` at goals, `max_a Q_W(x, a)` elsewhere (0 without
//!   actions). `Φ` is monotone, and goal, optimality and range give `Φ(V) ≤ V` (at a state
//!   without actions `Φ(V) = 0 ≤ V`). The probability that a policy reaches a goal within `k`
//!   steps is at most `Φ^k(0)` (induction on `k`, conditioning on the first step), and
//!   `Φ^k(0) ≤ Φ^k(V) ≤ V`; let `k → ∞`.
//! * *Lower bound: `π` reaches a goal from `x` with probability at least `V(x)`.* Make the goals
//!   and `Z` absorbing: by **proper**, from every other state `π` reaches them with positive
//!   probability, so with probability 1. Let `J(x)` be the probability of being absorbed at a
//!   goal; `J = 1` at goals, `0` on `Z`, `J = P_π J` elsewhere, and `V` satisfies the same
//!   (goal, evaluation, `V = 0` on `Z`). `D = V − J` has `D = 0` on the absorbing states and
//!   `D = P_π D` elsewhere, so `D ≤ 0` by the maximum principle above
//!   (`Truecost.Certificate.maximum_principle` with the goals and `Z` as its goals): `V ≤ J`,
//!   and `J` is at most the probability that `π` (continued anyhow on `Z`) reaches a goal.
//!
//! So `V` is the greatest reach probability from every state and `π` attains it. The upper
//! bound is argued here, not proved in Coq.
//!
//! # Discount breakpoints
//!
//! `discount --certificate` writes the breakpoints of the discount analysis and, between
//! them, the optimal policies with their values as rational functions of `α`; [`discount`]
//! checks them with exact Sturm sequences ([`sturm`]), its module docs give the conditions
//! and why they suffice.
//!
//! # The verified checker
//!
//! [`coq`] runs the same truecost conditions as a Coq function (`proofs/coq/CertificateCheck.v`)
//! whose soundness is proved in Coq for every finite model
//! (`Truecost.CertificateCheck.check_policy`, `Truecost.CertificateCheck.check_optimal`), and
//! the discounted conditions as another (`proofs/coq/CertificateDiscounted.v`;
//! `Truecost.CertificateDiscounted.check_discounted_policy`,
//! `Truecost.CertificateDiscounted.check_discounted_optimal`: the maximum principle with `α`),
//! both extracted to OCaml and run by `truecost check --coq`.
//!
//! # The problem
//!
//! The checker never reads the certificate's problem: the caller re-reads it, and the
//! certificate's SHA-256 must be that of the problem file's bytes (`--file`) or of the model's
//! [canonical export](Mdp::canonical_text) (`--problem`, `--env`), and its state count that of
//! the model (**problem**).

mod check;
mod conditions;
pub mod coq;
pub mod discount;
mod format;
mod mdp;
mod reach;
mod sha256;
pub mod sturm;

pub use check::{check, Acceptance, Checked, Identity, Rejection, CONDITIONS};
pub use format::value_text;
pub use format::{
    over_capacity, parse, parse_exact, push_integer, write, write_over, write_over_to, Certificate,
    CertifiedObjective, ProblemRecord, DECIMAL_BITS, FORMAT,
};
pub use mdp::{Mdp, MdpAction, CANONICAL_FORMAT};
pub use sha256::{sha256_hex, Sha256};
