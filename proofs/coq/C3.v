(** * Claim C3: the dangers of discounting (the paper's discounting proposition)

    - [c3_printed_iff_quartic]: the worked example's printed inequality
      [1/(1-alpha) < sum_{i=1..5} i alpha^(i-1)] holds exactly when
      [5 alpha^4 - alpha^3 - alpha^2 - alpha - 1 < 0], for every real [alpha] in [(0,1)].
    - [c3_alpha_star]: that quartic has exactly one root [alpha_star] in [(0,1)]; it lies strictly
      between the two rationals [alpha_lo] and [alpha_hi] ([alpha_hi - alpha_lo = 2^-100]), and
      the quartic is negative exactly on [(0, alpha_star)].
    - [c3_example_threshold]: in the worked example (docs/spec.md §6, C3; the claims registry's
      C3-example), for every real [alpha] in [(0,1)], every discount-optimal policy avoids the
      goal iff the printed inequality holds (iff the quartic is negative); below [alpha_star] every
      discount-optimal policy has infinite true cost. Policies: the stationary deterministic
      ones (see the theorem's comment). [c3_example_threshold_all]: the same over ALL
      policies (history-dependent or not).
    - [c3_certificate]: C3 for every finite problem, with truecost's certificate (cost 1 on a
      goal-avoiding lasso from [x1], [K > 1/(1-alpha)] on every other move): for every real
      [alpha] in [(0,1)], every discount-optimal policy -- among ALL policies, history-dependent
      or not -- follows the lasso, never reaches the goal and has infinite true cost.
    - [c3_certificate_engine]: the same with exactly the engine's
      [K = floor(1/((1-alpha0) alpha0^(n-2))) + 1], for every real [alpha] in [(0, alpha0]].
    - [c3_from_policy]: the registry's hypothesis (some stationary policy's path from [x1],
      admissible along it, never visits the goal) gives such a lasso; [c3_registry]: the registry's
      statement itself, for every finite problem and every [alpha] in [(0,1)].
    - [c3_engine_lasso]: the engine's certificate exactly (cost 1 on the moves of a stationary
      policy's lasso from [x1] only, the engine's [K] elsewhere), for every [alpha] in
      [(0, alpha0]]; [st_lasso]: a stationary policy's path is a lasso. [c3_engine]: the
      engine's construction itself (goal-avoiding core [in_core], first move into it
      [core_pi], [lasso_marks], [cert_K]; all computable), whenever [x1] is in the core.

    Everything is over the reals of the standard library; discounted costs are the sums of
    the series ([C2.discounted]), not closed forms.

    The proofs' pieces, by topic: [C3Policies.v] (stationary policies, trajectories, discounted
    sums), [C3Example.v] (the worked example), [C3Certificate.v] (the certificate for every
    finite problem), [C3Engine.v] (the engine's construction). This file states the main
    theorems. *)

From Coq Require Import Reals Lra Lia QArith Qround Qreals List.
From Truecost Require Import Model Paths C1 C2 QReal.
From Truecost Require Export C3Policies C3Certificate C3Example C3Engine.
Import ListNotations.

Open Scope R_scope.

(** C3's worked example, the printed form: for every real [alpha] in [(0,1)], the printed
    inequality holds iff the quartic is negative. *)
Theorem c3_printed_iff_quartic a : 0 < a < 1 -> printed a <-> quartic a < 0.
Proof. exact (printed_iff_quartic a). Qed.

(** The threshold: the quartic has exactly one root [alpha_star] in [(0,1)]; it lies strictly
    inside the bracket; and for every real [alpha] in [(0,1)], the quartic is negative iff
    [alpha < alpha_star] (so [alpha_star] is the only root there). *)
Theorem c3_alpha_star :
  exists astar, 0 < astar < 1 /\ quartic astar = 0 /\
    Q2R alpha_lo < astar < Q2R alpha_hi /\
    forall a, 0 < a < 1 -> (quartic a < 0 <-> a < astar).
Proof.
  destruct bracket_in_01 as (H0 & Hlh & H1).
  destruct (IVT quartic (Q2R alpha_lo) (Q2R alpha_hi) quartic_continuous Hlh quartic_lo quartic_hi)
    as (z & [Hlz Hzh] & Hz).
  assert (Q2R alpha_lo <> z) by (intros <-; pose proof quartic_lo; lra).
  assert (z <> Q2R alpha_hi) by (intros ->; pose proof quartic_hi; lra).
  exists z; repeat split; try lra.
  - intros Hq; destruct (Rlt_or_le a z) as [|Hza]; [auto|].
    destruct (Rle_lt_or_eq_dec z a Hza) as [Hlt|<-]; [|lra].
    pose proof (quartic_sign_mono z a ltac:(lra) ltac:(lra)); lra.
  - intros Hlt; destruct (Rlt_or_le (quartic a) 0) as [|Hq]; [auto|].
    pose proof (quartic_sign_mono a z ltac:(lra) Hq); lra.
Qed.


(** C3's worked example over ALL policies (the paper's discounting proposition, its example;
    docs/spec.md §6 C3; the claims registry's C3-example): for every real [alpha] in [(0,1)], a
    discount-optimal policy exists among all policies (history-dependent or not), every
    discount-optimal policy avoids the goal iff the printed inequality holds (iff the quartic
    is negative, [c3_printed_iff_quartic]), and then every discount-optimal policy stays at 0
    forever and has infinite true cost. *)
Theorem c3_example_threshold_all alpha :
  0 < alpha < 1 ->
  (exists r, traj_optimal ex3 alpha r) /\
  ((forall r, traj_optimal ex3 alpha r -> forall k, fst r k <> goal ex3) <-> printed alpha) /\
  (printed alpha <-> quartic alpha < 0) /\
  (printed alpha -> forall r, traj_optimal ex3 alpha r ->
     forall B, exists N, B < partial (traj_stages ex3 r) N).
Proof.
  intros Ha.
  set (rs := (state_at ex3 stay_pi 0, fun k => stay_pi (state_at ex3 stay_pi 0 k))).
  set (rr := (state_at ex3 reach_pi 0, fun k => reach_pi (state_at ex3 reach_pi 0 k))).
  assert (Hrs : trajectory ex3 (fst rs) (snd rs))
    by apply (stationary_trajectory _ _ stay_valid ex3_wf).
  assert (Hrr : trajectory ex3 (fst rr) (snd rr))
    by apply (stationary_trajectory _ _ reach_valid ex3_wf).
  assert (Vs : discounted alpha (traj_stages ex3 rs) (/ (1 - alpha)))
    by apply (stay_value alpha Ha).
  assert (Vr : discounted alpha (traj_stages ex3 rr) (printed_rhs alpha)) by apply reach_value.
  assert (Hlow := fun r w (Hr : trajectory ex3 (fst r) (snd r))
                      (Hw : discounted alpha (traj_stages ex3 r) w) =>
                    ex3_all_lower alpha Ha (fst r) (snd r) Hr w Hw).
  assert (Hstay : printed alpha -> traj_optimal ex3 alpha rs).
  { intros Hp; split; [exact Hrs|]; exists (/ (1 - alpha)); split; [exact Vs|].
    intros [x a] w Hr Hw; apply Rnot_lt_le; intros Hlt.
    destruct (Hlow (x, a) w Hr Hw) as [H _]; specialize (H Hp ltac:(lra)); simpl in H.
    assert (Hw' : discounted alpha (traj_stages ex3 (x, a)) (/ (1 - alpha))).
    { apply (total_extensional (fun k => alpha ^ k * 1)); [|apply discounted_const; lra].
      intros k; rewrite (proj2 (H k)); reflexivity. }
    pose proof (discounted_single_valued _ _ _ _ Hw Hw'); lra. }
  assert (Hreach : ~ printed alpha -> traj_optimal ex3 alpha rr).
  { intros Hnp; split; [exact Hrr|]; exists (printed_rhs alpha); split; [exact Vr|].
    intros r w Hr Hw; apply (proj2 (Hlow r w Hr Hw) Hnp). }
  assert (Honly : printed alpha -> forall r, traj_optimal ex3 alpha r ->
                  forall k, fst r k = 0%nat /\ traj_stages ex3 r k = 1).
  { intros Hp [x a] (Hr & v & Hv & Hmin).
    pose proof (Hmin rs _ Hrs Vs) as Hle.
    apply (proj1 (ex3_all_lower alpha Ha x a Hr v Hv) Hp Hle). }
  split; [|split; [|split]].
  - destruct (Rlt_or_le (/ (1 - alpha)) (printed_rhs alpha)) as [Hp|Hp].
    + exists rs; apply Hstay; exact Hp.
    + exists rr; apply Hreach; unfold printed; lra.
  - split.
    + intros Hall; destruct (Rlt_or_le (/ (1 - alpha)) (printed_rhs alpha)) as [Hp|Hp]; [exact Hp|].
      exfalso; apply (Hall rr (Hreach ltac:(unfold printed; lra)) 5%nat).
      reflexivity.
    + intros Hp r Hr k; rewrite (proj1 (Honly Hp r Hr k)); discriminate.
  - apply c3_printed_iff_quartic; auto.
  - intros Hp r Hr B; destruct (nat_above B) as (N & HN); exists N.
    assert (E : forall N, partial (traj_stages ex3 r) N = INR N).
    { induction N0 as [|N0 IH]; [reflexivity|].
      rewrite partial_S, IH, (proj2 (Honly Hp r Hr N0)), S_INR; reflexivity. }
    rewrite E; auto.
Qed.

Lemma recost_fst f i l : map fst (recost f i l) = map fst l.
Proof. revert i; induction l as [|[y c] l IH]; intros i; simpl; [|rewrite IH]; reflexivity. Qed.

(** C3 as the claims registry states it, for every finite problem (the paper's discounting
    proposition; docs/spec.md §6 C3): if a goal-reaching policy exists and some admissible policy's
    path from [x1] enters a cycle avoiding the goal (here: a stationary policy whose path never
    visits the goal), then for EVERY discount factor [alpha] in [(0,1)] there are stage costs
    -- on the same states, goal and moves, all strictly positive, termination 0 -- for which a
    discount-optimal policy exists and every discount-optimal policy (among all policies) has
    infinite true cost. *)
Theorem c3_registry P :
  wf P -> (exists w, reaches P 0 w) ->
  (exists pi, valid_on_path P pi /\ forall k, state_at P pi 0 k <> goal P) ->
  forall alpha, 0 < alpha < 1 ->
  exists C, nstates C = nstates P /\ goal C = goal P /\
    (forall x, map fst (moves C x) = map fst (moves P x)) /\
    (forall x i, (i < length (moves C x))%nat -> (0 < cost C x (Move i))%Q) /\
    (exists r, traj_optimal C alpha r) /\
    forall r, traj_optimal C alpha r ->
      (forall k, fst r k <> goal P) /\ forall B, exists N, B < partial (traj_stages C r) N.
Proof.
  intros HP _ (pi & Hv & Hng) alpha Ha.
  destruct (nat_above (/ (1 - alpha))) as (N & HN).
  set (K := inject_Z (Z.of_nat N)).
  assert (HK : / (1 - alpha) < Q2R K) by (unfold K; rewrite Q2R_inject_Z, <- INR_IZR_INZ; auto).
  destruct (c3_from_policy P pi K alpha HP Hv Hng Ha HK) as (Hpos & Hex & Hall).
  exists (certificate P (policy_marks pi) K).
  split; [reflexivity|]; split; [reflexivity|].
  split; [intros x; simpl; apply recost_fst|].
  split; [intros x i Hi; apply Hpos; simpl in Hi; rewrite recost_length in Hi; auto|].
  split; [exact Hex|].
  intros r Hr; destruct (Hall r Hr) as [H1 H2]; split; [|exact H2].
  intros k; apply (proj1 (H1 k)).
Qed.


(** C3 with the certificate of truecost's C3 engine, construction included (the kernel's
    [claims::c3::certificate]: [goal_avoiding_core], the first move into the core at each state
    of the walk from [x1], cost 1 on those moves, [K = floor(1/((1-alpha0) alpha0^(n-2))) + 1]
    on every other move): if [x1] is in the goal-avoiding core, then for every real [alpha] in
    [(0, alpha0]] every discount-optimal policy (among all policies) follows the engine's lasso,
    never reaches the goal, and has infinite true cost. *)
Corollary c3_engine P alpha0 alpha :
  wf P -> in_core P 0 = true -> (0 < alpha0 < 1)%Q -> 0 < alpha <= Q2R alpha0 ->
  let C := engine_certificate P (lasso_marks P (core_pi P)) alpha0 (nstates P) in
  (forall x i, (i < length (moves P x))%nat -> (0 < cost C x (Move i))%Q) /\
  (exists r, traj_optimal C alpha r) /\
  forall r, traj_optimal C alpha r ->
    (forall k, fst r k = state_at P (core_pi P) 0 k /\ fst r k <> goal P /\
               traj_stages C r k = 1) /\
    (forall B, exists N, B < partial (traj_stages C r) N).
Proof.
  intros HP H0 Ha0 Ha.
  assert (Hp := core_path P HP H0).
  apply c3_engine_lasso; auto.
  - intros k; destruct (Hp k) as [_ (i & E & Hi)]; rewrite E; apply in_actions; right; eauto.
  - intros k; destruct (Hp k) as [Hin _]; apply (in_core_next P HP _ Hin).
Qed.
