(** * Claim C4: episodic equivalence (the paper's Proposition 4)

    - [c4_as_printed_refuted]: C4 as printed (docs/spec.md §6; the claims registry's [c4::STATEMENT])
      fails on the minimal counterexample that [truecost verify] prints
      ([problems/counterexamples/c4-as-printed.json]): at the bonus [M = -3] the printed
      interval excludes [M], yet [pi*] is average-cost optimal against every run of the
      average-cost problem (every policy, stationary or not).
    - [c4_as_printed_refuted_positive_costs]: it fails also with every move cost positive
      ([c4pos]: for every bonus [-5 <= M < -5/27]).
    - [c4_corrected]: C4-corrected (the registry's [c4::CORRECTED]) for every finite
      deterministic problem with rational costs and bonus: [pi*] is average-cost optimal iff
      [M] lies in the corrected interval ([corrected_interval]). Its two halves are
      [c4_corrected_sufficient] and [c4_corrected_necessary]; the facts they rest on:
      the average of a lasso is its cycle's mean ([las_average], [cyc_average],
      [average_periodic], [average_shift]; a stationary policy's path is a lasso:
      [C3Engine.st_lasso]),
      every run's cost is at least the least simple-cycle mean per stage up to a constant
      ([closed_nonneg], [walk_bound], [run_lower]: the cycle decomposition of walks), and
      the simple cycles of the average-cost problem are the simple goal paths closed by the
      reset and the goal-avoiding simple cycles ([cycles_above]).

    The average-cost problem of a problem [P] with bonus [M]: from [x1 = 0], a stage is a move
    of [P] (its cost [l(x,u)]) or, at the goal, the reset to [x1] (one stage costing [M]). The
    problem is deterministic, so every policy, history-dependent or not, produces one run
    ([reset_run]), and every run is produced by the open-loop policy that follows it:
    optimality over runs is optimality over all policies. Optimality ([average_optimal]) is
    the strong form: the optimal run's average exists, and every run's running mean is
    eventually above it minus any [eps > 0] (so no run does better in [liminf] either). *)

From Coq Require Import Reals Lra Lia QArith Qreals List.
From Coq Require Lqa ListDec Permutation.
From Truecost Require Import Model Paths C2 QReal C3.
Import ListNotations.

Open Scope R_scope.

(** [lra] over [Q]. *)
Local Ltac qlra := Lqa.lra.

(** ** The average-cost problem with a reset bonus *)

(** Stage [k] of a run: the states [x k], [x (S k)] and the stage cost [c k]. At the goal the
    only action is the reset to [x1 = 0], costing [M]; elsewhere a move of [P]. *)
Definition step_ok (P : problem) (M : R) (x : nat -> nat) (c : sequence) (k : nat) : Prop :=
  (x k = goal P /\ x (S k) = 0%nat /\ c k = M) \/
  (x k <> goal P /\ exists i, (i < length (moves P (x k)))%nat /\
     x (S k) = target P (x k) (Move i) /\ c k = Q2R (cost P (x k) (Move i))).

(** A run from [x1 = 0]: the states visited and the stage costs paid. *)
Definition reset_run (P : problem) (M : R) (x : nat -> nat) (c : sequence) : Prop :=
  x O = 0%nat /\ forall k, step_ok P M x c k.

(** The run [(x, c)] is average-cost optimal: its average cost [v] exists ([C2.average]) and no
    run does better, even along a subsequence of horizons: the running mean of every run is
    eventually above [v - eps], for every [eps > 0]. *)
Definition average_optimal (P : problem) (M : R) (x : nat -> nat) (c : sequence) : Prop :=
  reset_run P M x c /\ exists v, average c v /\
    forall x' c', reset_run P M x' c' -> forall eps, 0 < eps ->
      exists N0, forall N, (N0 <= N)%nat -> v - eps <= partial c' (S N) / INR (S N).

(** A potential [h] with [c k + h(x (S k)) - h(x k) >= g] at every stage bounds every run's
    running mean from below: [partial c N >= g N + h(x 0) - h(x N)]. *)
Lemma potential_bound (x : nat -> nat) (c : sequence) (h : nat -> R) g :
  (forall k, g <= c k + h (x (S k)) - h (x k)) ->
  forall N, g * INR N + h (x O) - h (x N) <= partial c N.
Proof.
  intros H N; induction N as [|N IH]; simpl partial; [simpl; lra|].
  rewrite S_INR; specialize (H N); lra.
Qed.

(** ** C4 as printed *)

(** [A(u) = (1 - S(u)/S_star) (S(u) L_star/(S_star L(u)) - 1)] for a goal path with [S(u)]
    states and cost
    [L(u)]. *)
Definition A_printed (Sstar Lstar Su Lu : R) : R :=
  (1 - Su / Sstar) * (Su * Lstar / (Sstar * Lu) - 1).

(** The printed interval: [M < 0] and [a <= M <= min{b, S_star Lav(C^) - L_star}], with
    [a = max A(u)] over the goal paths with [S(u) < S_star], [b = min A(u)] over those with
    [S(u) > S_star] (an empty max is [-oo], an empty min [+oo]), and [lav = None] when no cycle
    avoids the goal ([Lav(C^) = +oo]). [paths] lists [(S(u), L(u))]. *)
Definition printed_interval (Sstar Lstar : R) (paths : list (R * R)) (lav : option R)
    (M : R) : Prop :=
  M < 0 /\
  (forall p, In p paths -> fst p < Sstar -> A_printed Sstar Lstar (fst p) (snd p) <= M) /\
  (forall p, In p paths -> Sstar < fst p -> M <= A_printed Sstar Lstar (fst p) (snd p)) /\
  (forall l, lav = Some l -> M <= Sstar * l - Lstar).

(** The counterexample [verify] prints: states 0, 1, 2, [x1 = 0], goal 2 (no moves); moves
    [0 -> 1] (cost 0), [0 -> 2] (cost 1), [1 -> 2] (cost 0). *)
Definition c4ex : problem := {|
  nstates := 3;
  goal := 2;
  moves := fun x => match x with
                    | O => [(1%nat, 0%Q); (2%nat, 1%Q)]
                    | 1%nat => [(2%nat, 0%Q)]
                    | _ => []
                    end
|}.

Lemma c4ex_wf : wf c4ex.
Proof.
  split; [simpl; lia|]; intros x Hx y l Hin; simpl in Hx.
  destruct x as [|[|[|x]]]; simpl in Hin; try lia;
    repeat destruct Hin as [E|Hin]; try inversion E; subst; try tauto; split; try lia;
    unfold Qle; simpl; lia.
Qed.

(** The single-shot optimum: [G*(x1) = 0]. *)
Lemma c4ex_Gstar : Gstar c4ex 0 = Some 0%Q.
Proof. reflexivity. Qed.

(** The goal paths from [x1]: [0 -> 1 -> 2] (3 states, cost 0: [pi*]) and [0 -> 2] (2 states,
    cost 1). *)
Local Ltac step := unfold target in *; simpl in *.

Lemma c4ex_goal_paths w : reaches c4ex 0 w -> w = [0; 0]%nat \/ w = [1%nat].
Proof.
  intros [Hw He]; unfold target in *.
  destruct w as [|a w]; step; [discriminate|].
  destruct Hw as [Ha Hw]; destruct a as [|[|a]]; step; try lia.
  - destruct w as [|b w]; step; [discriminate|].
    destruct Hw as [Hb Hw]; destruct b as [|b]; step; try lia.
    destruct w as [|c w]; [auto|]; step; destruct Hw as [Hc _]; step; lia.
  - destruct w as [|b w]; [auto|]; step; destruct Hw as [Hb _]; step; lia.
Qed.

Lemma c4ex_pistar : reaches c4ex 0 [0; 0]%nat /\ (wcost c4ex 0 [0; 0]%nat == 0)%Q.
Proof. split; [split; [simpl; unfold target; simpl; lia | reflexivity] | reflexivity]. Qed.

Lemma c4ex_other_path : reaches c4ex 0 [1%nat] /\ (wcost c4ex 0 [1%nat] == 1)%Q.
Proof. split; [split; [simpl; lia | reflexivity] | reflexivity]. Qed.

(** No cycle avoids the goal (no cycle at all without the reset): [Lav(C^) = +oo]. *)
Lemma c4ex_no_cycle x w :
  w <> [] -> wvalid c4ex x w -> wend c4ex x w <> x.
Proof.
  intros Hne Hw; unfold target in *.
  destruct w as [|a w]; [congruence|]; step; destruct Hw as [Ha Hw].
  destruct x as [|[|x]]; step.
  - destruct a as [|[|a]]; step; try lia.
    + destruct w as [|b w]; step; [lia|].
      destruct Hw as [Hb Hw]; destruct b; step; try lia.
      destruct w as [|c w]; step; [lia|]; destruct Hw as [Hc _]; step; lia.
    + destruct w as [|b w]; step; [lia|]; destruct Hw as [Hb _]; step; lia.
  - destruct a; step; try lia.
    destruct w as [|b w]; step; [lia|]; destruct Hw as [Hb _]; step; lia.
  - destruct x; step; lia.
Qed.

(** [pi*]'s run: [0, 1, 2, 0, 1, 2, ...] with stage costs [0, 0, M, 0, 0, M, ...]. *)
Definition pistar_x (k : nat) : nat := k mod 3.
Definition pistar_c (M : R) (k : nat) : R := if Nat.eqb (k mod 3) 2 then M else 0.

Lemma mod3_cases k : (k mod 3 = 0 \/ k mod 3 = 1 \/ k mod 3 = 2)%nat.
Proof. pose proof (Nat.mod_upper_bound k 3 ltac:(lia)); lia. Qed.

Lemma mod3_S k : ((S k) mod 3 = (S (k mod 3)) mod 3)%nat.
Proof.
  replace (S k) with (k + 1)%nat by lia; rewrite Nat.add_mod by lia.
  replace (1 mod 3)%nat with 1%nat by reflexivity; f_equal; lia.
Qed.

Lemma pistar_run M : reset_run c4ex M pistar_x (pistar_c M).
Proof.
  split; [reflexivity|]; intros k; unfold step_ok, pistar_x, pistar_c; simpl goal.
  rewrite mod3_S.
  destruct (mod3_cases k) as [E|[E|E]]; rewrite E; simpl.
  - right; split; [lia|]; exists 0%nat; unfold target, cost; simpl.
    repeat split; [lia | unfold Q2R; simpl; lra].
  - right; split; [lia|]; exists 0%nat; unfold target, cost; simpl.
    repeat split; [lia | unfold Q2R; simpl; lra].
  - left; repeat split; lia.
Qed.

Lemma pistar_c_at M q r :
  (r < 3)%nat -> pistar_c M (3 * q + r) = if Nat.eqb r 2 then M else 0.
Proof.
  intros Hr; unfold pistar_c; rewrite (Nat.add_comm (3 * q)), (Nat.mul_comm 3 q).
  rewrite Nat.mod_add by lia; rewrite Nat.mod_small by lia; reflexivity.
Qed.

Lemma pistar_partial M q :
  partial (pistar_c M) (3 * q) = INR q * M /\
  partial (pistar_c M) (3 * q + 1) = INR q * M /\
  partial (pistar_c M) (3 * q + 2) = INR q * M.
Proof.
  induction q as [|q IH].
  - simpl; unfold pistar_c; simpl; repeat split; ring.
  - destruct IH as (_ & _ & I2).
    assert (C0 : pistar_c M (3 * q + 2) = M) by (rewrite pistar_c_at by lia; reflexivity).
    assert (C1 : pistar_c M (3 * S q) = 0).
    { rewrite <- (Nat.add_0_r (3 * S q)), pistar_c_at by lia; reflexivity. }
    assert (C2 : pistar_c M (3 * S q + 1) = 0) by (rewrite pistar_c_at by lia; reflexivity).
    assert (P0 : partial (pistar_c M) (3 * S q) = INR (S q) * M).
    { replace (3 * S q)%nat with (S (3 * q + 2)) by lia.
      rewrite partial_S, I2, C0, S_INR; ring. }
    assert (P1 : partial (pistar_c M) (3 * S q + 1) = INR (S q) * M).
    { replace (3 * S q + 1)%nat with (S (3 * S q)) by lia; rewrite partial_S, P0, C1; ring. }
    assert (P2 : partial (pistar_c M) (3 * S q + 2) = INR (S q) * M).
    { replace (3 * S q + 2)%nat with (S (3 * S q + 1)) by lia; rewrite partial_S, P1, C2; ring. }
    auto.
Qed.

(** [pi*]'s running mean is within [2/(N+1)] of [M/3], hence its average is [M/3]. *)
Lemma pistar_partial_bounds M N :
  M < 0 -> INR N * (M / 3) <= partial (pistar_c M) N <= INR N * (M / 3) - 2 * (M / 3).
Proof.
  intros HM.
  destruct (Nat.lt_ge_cases (N mod 3) 3) as [Hr|]; [|pose proof (Nat.mod_upper_bound N 3); lia].
  pose proof (Nat.div_mod N 3 ltac:(lia)) as HN.
  set (q := (N / 3)%nat) in *; set (r := (N mod 3)%nat) in *.
  destruct (pistar_partial M q) as (P0 & P1 & P2).
  assert (Hr3 : (r = 0 \/ r = 1 \/ r = 2)%nat) by lia.
  destruct Hr3 as [E|[E|E]]; rewrite E in HN; rewrite HN.
  - rewrite Nat.add_0_r, P0, mult_INR; simpl; split; lra.
  - rewrite P1, plus_INR, mult_INR; simpl; split; lra.
  - rewrite P2, plus_INR, mult_INR; simpl; split; lra.
Qed.

Lemma pistar_average M : M < 0 -> average (pistar_c M) (M / 3).
Proof.
  intros HM eps Heps.
  destruct (nat_above (- 2 * (M / 3) / eps)) as (N0 & HN0).
  exists N0; intros N HN; unfold R_dist.
  pose proof (pistar_partial_bounds M (S N) HM) as [Lo Hi].
  assert (Hpos : 0 < INR (S N)) by (apply lt_0_INR; lia).
  assert (HNge : INR N0 <= INR (S N)) by (apply le_INR; lia).
  assert (Hdiff : 0 <= partial (pistar_c M) (S N) / INR (S N) - M / 3 <= - 2 * (M / 3) / INR (S N)).
  { split.
    - apply (Rmult_le_reg_r (INR (S N))); [auto|].
      unfold Rdiv; rewrite Rmult_minus_distr_r, Rmult_assoc, Rinv_l by lra; lra.
    - apply (Rmult_le_reg_r (INR (S N))); [auto|].
      unfold Rdiv; rewrite Rmult_minus_distr_r, !Rmult_assoc, Rinv_l by lra; lra. }
  rewrite Rabs_right by lra.
  apply Rle_lt_trans with (- 2 * (M / 3) / INR (S N)); [lra|].
  apply (Rmult_lt_reg_r (INR (S N))); [auto|].
  unfold Rdiv; rewrite Rmult_assoc, Rinv_l by lra.
  assert (- 2 * (M / 3) / eps < INR (S N)) as H by lra.
  apply (Rmult_lt_compat_r eps) in H; [|auto].
  unfold Rdiv in H; rewrite Rmult_assoc, Rinv_l in H by lra; lra.
Qed.

(** The potential [h(0) = 0], [h(1) = M/3], [h(2) = 2M/3]: for [-3 <= M], every stage of every
    run satisfies [c k + h(x (S k)) - h(x k) >= M/3] (equality on [pi*]'s cycle, and on the
    other reset cycle [0 -> 2 -> 0] when [M = -3]). *)
Definition c4ex_h (M : R) (x : nat) : R :=
  match x with O => 0 | 1%nat => M / 3 | _ => 2 * M / 3 end.

Lemma c4ex_step_bound M x c k :
  -3 <= M -> step_ok c4ex M x c k -> M / 3 <= c k + c4ex_h M (x (S k)) - c4ex_h M (x k).
Proof.
  intros HM [(E & E' & Ec)|(Ne & i & Hi & E' & Ec)].
  - rewrite E, E', Ec; simpl; lra.
  - rewrite E', Ec; simpl goal in Ne.
    destruct (x k) as [|[|[|y]]]; simpl in Hi; try lia.
    + destruct i as [|[|i]]; try lia; unfold target, cost; simpl; unfold Q2R; simpl; lra.
    + destruct i as [|i]; try lia; unfold target, cost; simpl; unfold Q2R; simpl; lra.
Qed.

(** For [-3 <= M < 0], no run's running mean is ever below [M/3]. *)
Lemma c4ex_runs_bound M x c :
  -3 <= M < 0 -> reset_run c4ex M x c -> forall N, INR N * (M / 3) <= partial c N.
Proof.
  intros HM [H0 Hs] N.
  pose proof (potential_bound x c (c4ex_h M) (M / 3)
                (fun k => c4ex_step_bound M x c k ltac:(lra) (Hs k)) N) as H.
  rewrite H0 in H; simpl c4ex_h at 1 in H.
  assert (c4ex_h M (x N) <= 0) by (destruct (x N) as [|[|y]]; simpl; lra).
  lra.
Qed.

Lemma A_printed_other : A_printed 3 0 2 1 = - / 3.
Proof. unfold A_printed; field. Qed.

(** C4 as printed, refuted (the paper's Proposition 4 as printed; docs/spec.md §6 C4; the claims
    registry's [c4::STATEMENT]), on the minimal counterexample [verify] prints
    ([problems/counterexamples/c4-as-printed.json], at the bonus [M = -3]). In [c4ex]: the
    single-shot optimum is [G*(x1) = 0], attained by [pi* = 0 -> 1 -> 2] ([S* = 3] states,
    [L* = 0]); the only other goal path is [0 -> 2] ([S = 2], [L = 1], so
    [a = A(0 -> 2) = -1/3], and [b = +oo]); no cycle avoids the goal ([Lav(C^) = +oo]). For every
    bonus [M] with [-3 <= M < -1/3] (in particular the printed [M = -3]) the printed interval
    excludes [M], yet [pi*]'s run (the stationary policy [0 -> 1 -> 2 -> reset]) is
    average-cost optimal: its average is [M/3] and no run of the average-cost problem -- no
    policy, stationary or not -- has a running mean below [M/3] at any horizon (a potential
    argument, [c4ex_h]). *)
Theorem c4_as_printed_refuted :
  Gstar c4ex 0 = Some 0%Q /\
  (reaches c4ex 0 [0; 0]%nat /\ (wcost c4ex 0 [0; 0]%nat == 0)%Q) /\
  (reaches c4ex 0 [1%nat] /\ (wcost c4ex 0 [1%nat] == 1)%Q) /\
  (forall w, reaches c4ex 0 w -> w = [0; 0]%nat \/ w = [1%nat]) /\
  (forall x w, w <> [] -> wvalid c4ex x w -> wend c4ex x w <> x) /\
  forall M, -3 <= M < - / 3 ->
    ~ printed_interval 3 0 [(3, 0); (2, 1)] None M /\
    average_optimal c4ex M pistar_x (pistar_c M).
Proof.
  split; [apply c4ex_Gstar|].
  split; [apply c4ex_pistar|].
  split; [apply c4ex_other_path|].
  split; [apply c4ex_goal_paths|].
  split; [apply c4ex_no_cycle|].
  intros M HM; split.
  - intros (_ & Ha & _ & _).
    specialize (Ha (2, 1) ltac:(simpl; auto) ltac:(simpl; lra)); simpl in Ha.
    rewrite A_printed_other in Ha; lra.
  - split; [apply pistar_run|].
    exists (M / 3); split; [apply pistar_average; lra|].
    intros x' c' Hrun eps Heps; exists O; intros N _.
    pose proof (c4ex_runs_bound M x' c' ltac:(lra) Hrun (S N)) as H.
    assert (Hpos : 0 < INR (S N)) by (apply lt_0_INR; lia).
    apply Rle_trans with (M / 3); [lra|].
    apply (Rmult_le_reg_r (INR (S N))); [auto|].
    unfold Rdiv at 2; rewrite Rmult_assoc, Rinv_l by lra; lra.
Qed.

(** ** C4 as printed, refuted with positive move costs *)

(** The counterexample with every move cost positive: states 0, 1, 2, [x1 = 0], goal 2 (no
    moves); moves [0 -> 1] (cost 1), [0 -> 2] (cost 3), [1 -> 2] (cost 1). *)
Definition c4pos : problem := {|
  nstates := 3;
  goal := 2;
  moves := fun x => match x with
                    | O => [(1%nat, 1%Q); (2%nat, 3%Q)]
                    | 1%nat => [(2%nat, 1%Q)]
                    | _ => []
                    end
|}.

Lemma c4pos_costs_pos x i :
  (x < nstates c4pos)%nat -> (i < length (moves c4pos x))%nat -> (0 < cost c4pos x (Move i))%Q.
Proof.
  intros Hx Hi; simpl in Hx; unfold cost.
  destruct x as [|[|[|x]]]; simpl in Hi; try lia;
    [destruct i as [|[|i]] | destruct i as [|i]]; try lia; reflexivity.
Qed.

(** The single-shot optimum: [G*(x1) = 2]. *)
Lemma c4pos_Gstar : Gstar c4pos 0 = Some 2%Q.
Proof. vm_compute; reflexivity. Qed.

(** The goal paths from [x1]: [0 -> 1 -> 2] (3 states, cost 2: [pi*]) and [0 -> 2] (2 states,
    cost 3). *)
Lemma c4pos_goal_paths w : reaches c4pos 0 w -> w = [0; 0]%nat \/ w = [1%nat].
Proof.
  intros [Hw He]; unfold target in *.
  destruct w as [|a w]; step; [discriminate|].
  destruct Hw as [Ha Hw]; destruct a as [|[|a]]; step; try lia.
  - destruct w as [|b w]; step; [discriminate|].
    destruct Hw as [Hb Hw]; destruct b as [|b]; step; try lia.
    destruct w as [|c w]; [auto|]; step; destruct Hw as [Hc _]; step; lia.
  - destruct w as [|b w]; [auto|]; step; destruct Hw as [Hb _]; step; lia.
Qed.

Lemma c4pos_pistar : reaches c4pos 0 [0; 0]%nat /\ (wcost c4pos 0 [0; 0]%nat == 2)%Q.
Proof. split; [split; [simpl; unfold target; simpl; lia | reflexivity] | reflexivity]. Qed.

Lemma c4pos_other_path : reaches c4pos 0 [1%nat] /\ (wcost c4pos 0 [1%nat] == 3)%Q.
Proof. split; [split; [simpl; lia | reflexivity] | reflexivity]. Qed.

(** No cycle avoids the goal (no cycle at all without the reset): [Lav(C^) = +oo]. *)
Lemma c4pos_no_cycle x w :
  w <> [] -> wvalid c4pos x w -> wend c4pos x w <> x.
Proof.
  intros Hne Hw; unfold target in *.
  destruct w as [|a w]; [congruence|]; step; destruct Hw as [Ha Hw].
  destruct x as [|[|x]]; step.
  - destruct a as [|[|a]]; step; try lia.
    + destruct w as [|b w]; step; [lia|].
      destruct Hw as [Hb Hw]; destruct b; step; try lia.
      destruct w as [|c w]; step; [lia|]; destruct Hw as [Hc _]; step; lia.
    + destruct w as [|b w]; step; [lia|]; destruct Hw as [Hb _]; step; lia.
  - destruct a; step; try lia.
    destruct w as [|b w]; step; [lia|]; destruct Hw as [Hb _]; step; lia.
  - destruct x; step; lia.
Qed.

(** [pi*]'s run in [c4pos]: states [0, 1, 2, 0, 1, 2, ...] ([pistar_x]) with stage costs
    [1, 1, M, 1, 1, M, ...]; its average is [g = (2 + M) / 3]. *)
Definition pos_c (M : R) (k : nat) : R := if Nat.eqb (k mod 3) 2 then M else 1.

Definition pos_g (M : R) : R := (2 + M) / 3.

Lemma pos_run M : reset_run c4pos M pistar_x (pos_c M).
Proof.
  split; [reflexivity|]; intros k; unfold step_ok, pistar_x, pos_c; simpl goal.
  rewrite mod3_S.
  destruct (mod3_cases k) as [E|[E|E]]; rewrite E; simpl.
  - right; split; [lia|]; exists 0%nat; unfold target, cost; simpl.
    repeat split; [lia | unfold Q2R; simpl; lra].
  - right; split; [lia|]; exists 0%nat; unfold target, cost; simpl.
    repeat split; [lia | unfold Q2R; simpl; lra].
  - left; repeat split; lia.
Qed.

Lemma pos_c_at M q r :
  (r < 3)%nat -> pos_c M (3 * q + r) = if Nat.eqb r 2 then M else 1.
Proof.
  intros Hr; unfold pos_c; rewrite (Nat.add_comm (3 * q)), (Nat.mul_comm 3 q).
  rewrite Nat.mod_add by lia; rewrite Nat.mod_small by lia; reflexivity.
Qed.

Lemma pos_partial M q :
  partial (pos_c M) (3 * q) = INR q * (2 + M) /\
  partial (pos_c M) (3 * q + 1) = INR q * (2 + M) + 1 /\
  partial (pos_c M) (3 * q + 2) = INR q * (2 + M) + 2.
Proof.
  induction q as [|q IH].
  - simpl; unfold pos_c; simpl; repeat split; ring.
  - destruct IH as (_ & _ & I2).
    assert (C0 : pos_c M (3 * q + 2) = M) by (rewrite pos_c_at by lia; reflexivity).
    assert (C1 : pos_c M (3 * S q) = 1).
    { rewrite <- (Nat.add_0_r (3 * S q)), pos_c_at by lia; reflexivity. }
    assert (C2 : pos_c M (3 * S q + 1) = 1) by (rewrite pos_c_at by lia; reflexivity).
    assert (P0 : partial (pos_c M) (3 * S q) = INR (S q) * (2 + M)).
    { replace (3 * S q)%nat with (S (3 * q + 2)) by lia.
      rewrite partial_S, I2, C0, S_INR; ring. }
    assert (P1 : partial (pos_c M) (3 * S q + 1) = INR (S q) * (2 + M) + 1).
    { replace (3 * S q + 1)%nat with (S (3 * S q)) by lia; rewrite partial_S, P0, C1; ring. }
    assert (P2 : partial (pos_c M) (3 * S q + 2) = INR (S q) * (2 + M) + 2).
    { replace (3 * S q + 2)%nat with (S (3 * S q + 1)) by lia; rewrite partial_S, P1, C2; ring. }
    auto.
Qed.

(** For [-5 <= M < 0], [pi*]'s partial sums stay within [4] above [N g]. *)
Lemma pos_partial_bounds M N :
  -5 <= M < 0 -> INR N * pos_g M <= partial (pos_c M) N <= INR N * pos_g M + 4.
Proof.
  intros HM; unfold pos_g.
  destruct (Nat.lt_ge_cases (N mod 3) 3) as [Hr|]; [|pose proof (Nat.mod_upper_bound N 3); lia].
  pose proof (Nat.div_mod N 3 ltac:(lia)) as HN.
  set (q := (N / 3)%nat) in *; set (r := (N mod 3)%nat) in *.
  destruct (pos_partial M q) as (P0 & P1 & P2).
  assert (Hr3 : (r = 0 \/ r = 1 \/ r = 2)%nat) by lia.
  destruct Hr3 as [E|[E|E]]; rewrite E in HN; rewrite HN.
  - rewrite Nat.add_0_r, P0, mult_INR; simpl; split; lra.
  - rewrite P1, plus_INR, mult_INR; simpl; split; lra.
  - rewrite P2, plus_INR, mult_INR; simpl; split; lra.
Qed.

Lemma pos_average M : -5 <= M < 0 -> average (pos_c M) (pos_g M).
Proof.
  intros HM eps Heps.
  destruct (nat_above (4 / eps)) as (N0 & HN0).
  exists N0; intros N HN; unfold R_dist.
  pose proof (pos_partial_bounds M (S N) HM) as [Lo Hi].
  assert (Hpos : 0 < INR (S N)) by (apply lt_0_INR; lia).
  assert (HNge : INR N0 <= INR (S N)) by (apply le_INR; lia).
  assert (Hdiff : 0 <= partial (pos_c M) (S N) / INR (S N) - pos_g M <= 4 / INR (S N)).
  { split.
    - apply (Rmult_le_reg_r (INR (S N))); [auto|].
      unfold Rdiv; rewrite Rmult_minus_distr_r, Rmult_assoc, Rinv_l by lra; lra.
    - apply (Rmult_le_reg_r (INR (S N))); [auto|].
      unfold Rdiv; rewrite Rmult_minus_distr_r, !Rmult_assoc, Rinv_l by lra; lra. }
  rewrite Rabs_right by lra.
  apply Rle_lt_trans with (4 / INR (S N)); [lra|].
  apply (Rmult_lt_reg_r (INR (S N))); [auto|].
  unfold Rdiv; rewrite Rmult_assoc, Rinv_l by lra.
  assert (4 / eps < INR (S N)) as H by lra.
  apply (Rmult_lt_compat_r eps) in H; [|auto].
  unfold Rdiv in H; rewrite Rmult_assoc, Rinv_l in H by lra; lra.
Qed.

(** The potential [h(0) = 0], [h(1) = g - 1], [h(2) = 2 g - 2]: for [-5 <= M], every stage of
    every run satisfies [c k + h(x (S k)) - h(x k) >= g] (equality on [pi*]'s cycle; on the
    other reset cycle [0 -> 2 -> 0] the slack is [1 + g], zero exactly at [M = -5]). *)
Definition c4pos_h (M : R) (x : nat) : R :=
  match x with O => 0 | 1%nat => pos_g M - 1 | _ => 2 * pos_g M - 2 end.

Lemma c4pos_step_bound M x c k :
  -5 <= M -> step_ok c4pos M x c k -> pos_g M <= c k + c4pos_h M (x (S k)) - c4pos_h M (x k).
Proof.
  intros HM [(E & E' & Ec)|(Ne & i & Hi & E' & Ec)].
  - rewrite E, E', Ec; simpl; unfold pos_g; lra.
  - rewrite E', Ec; simpl goal in Ne.
    destruct (x k) as [|[|[|y]]]; simpl in Hi; try lia.
    + destruct i as [|[|i]]; try lia; unfold target, cost; simpl; unfold Q2R, pos_g; simpl; lra.
    + destruct i as [|i]; try lia; unfold target, cost; simpl; unfold Q2R, pos_g; simpl; lra.
Qed.

(** For [-5 <= M < 0], no run's running mean is ever below [g]. *)
Lemma c4pos_runs_bound M x c :
  -5 <= M < 0 -> reset_run c4pos M x c -> forall N, INR N * pos_g M <= partial c N.
Proof.
  intros HM [H0 Hs] N.
  pose proof (potential_bound x c (c4pos_h M) (pos_g M)
                (fun k => c4pos_step_bound M x c k ltac:(lra) (Hs k)) N) as H.
  rewrite H0 in H; simpl c4pos_h at 1 in H.
  assert (c4pos_h M (x N) <= 0) by (destruct (x N) as [|[|y]]; simpl; unfold pos_g; lra).
  lra.
Qed.

Lemma A_printed_pos : A_printed 3 2 2 3 = - (5 / 27).
Proof. unfold A_printed; field. Qed.

(** C4 as printed, refuted with every move cost positive (the paper's Proposition 4 as
    printed; the claims registry's [c4::STATEMENT]), so the failure is not an
    artefact of zero-cost moves. In [c4pos] (moves [0 -> 1] and [1 -> 2] of cost 1, [0 -> 2]
    of cost 3, goal 2): the single-shot optimum is [G*(x1) = 2], attained by
    [pi* = 0 -> 1 -> 2] ([S* = 3] states, [L* = 2]); the only other goal path is [0 -> 2]
    ([S = 2], [L = 3], so [a = A(0 -> 2) = -5/27], and [b = +oo]); no cycle avoids the goal
    ([Lav(C^) = +oo]). For every bonus [M] with [-5 <= M < -5/27] the printed interval
    excludes [M], yet [pi*]'s run (the stationary policy [0 -> 1 -> 2 -> reset]) is
    average-cost optimal: its average is [(2 + M)/3] and no run of the average-cost problem --
    no policy, stationary or not -- has a running mean below it at any horizon (a potential
    argument, [c4pos_h]). The corrected interval's lower end is
    [T(0 -> 2) = (3 * 3 - 2 * 2) / (2 - 3) = -5]. *)
Theorem c4_as_printed_refuted_positive_costs :
  (forall x i, (x < nstates c4pos)%nat -> (i < length (moves c4pos x))%nat ->
               (0 < cost c4pos x (Move i))%Q) /\
  Gstar c4pos 0 = Some 2%Q /\
  (reaches c4pos 0 [0; 0]%nat /\ (wcost c4pos 0 [0; 0]%nat == 2)%Q) /\
  (reaches c4pos 0 [1%nat] /\ (wcost c4pos 0 [1%nat] == 3)%Q) /\
  (forall w, reaches c4pos 0 w -> w = [0; 0]%nat \/ w = [1%nat]) /\
  (forall x w, w <> [] -> wvalid c4pos x w -> wend c4pos x w <> x) /\
  forall M, -5 <= M < - (5 / 27) ->
    ~ printed_interval 3 2 [(3, 2); (2, 3)] None M /\
    average_optimal c4pos M pistar_x (pos_c M).
Proof.
  split; [apply c4pos_costs_pos|].
  split; [apply c4pos_Gstar|].
  split; [apply c4pos_pistar|].
  split; [apply c4pos_other_path|].
  split; [apply c4pos_goal_paths|].
  split; [apply c4pos_no_cycle|].
  intros M HM; split.
  - intros (_ & Ha & _ & _).
    specialize (Ha (2, 3) ltac:(simpl; auto) ltac:(simpl; lra)); simpl in Ha.
    rewrite A_printed_pos in Ha; lra.
  - split; [apply pos_run|].
    exists (pos_g M); split; [apply pos_average; lra|].
    intros x' c' Hrun eps Heps; exists O; intros N _.
    pose proof (c4pos_runs_bound M x' c' ltac:(lra) Hrun (S N)) as H.
    assert (Hpos : 0 < INR (S N)) by (apply lt_0_INR; lia).
    apply Rle_trans with (pos_g M); [lra|].
    apply (Rmult_le_reg_r (INR (S N))); [auto|].
    unfold Rdiv; rewrite Rmult_assoc, Rinv_l by lra; lra.
Qed.

(** ** C4-corrected for every finite deterministic problem *)

(** Walk lemmas used below. *)
Lemma trace_app P x a b : trace P x (a ++ b) = trace P x a ++ tl (trace P (wend P x a) b).
Proof.
  revert x; induction a as [|i a IH]; intros x; simpl; [destruct b; reflexivity|].
  f_equal; apply IH.
Qed.

Lemma trace_last P x w : exists l, trace P x w = l ++ [wend P x w].
Proof.
  revert x; induction w as [|i w IH]; intros x; simpl; [exists []; reflexivity|].
  destruct (IH (target P x (Move i))) as (l & E); rewrite E; exists (x :: l); reflexivity.
Qed.

Lemma T_algebra S s Lu Ls m :
  0 < S -> 0 < s ->
  (s < S -> (S * Lu - s * Ls) / (s - S) <= m) ->
  (S < s -> m <= (S * Lu - s * Ls) / (s - S)) ->
  (s = S -> Ls <= Lu) ->
  0 <= m + Lu - (Ls + m) / S * s.
Proof.
  intros HS Hs H1 H2 H3.
  enough (0 <= S * m + S * Lu - (Ls + m) * s) as H.
  { replace (m + Lu - (Ls + m) / S * s) with ((S * m + S * Lu - (Ls + m) * s) / S) by (field; lra).
    unfold Rdiv; apply Rmult_le_pos; [auto | left; apply Rinv_0_lt_compat; auto]. }
  destruct (Rtotal_order s S) as [Hlt|[Heq|Hgt]].
  - specialize (H1 Hlt); set (t := (S * Lu - s * Ls) / (s - S)) in H1.
    assert (Ht : t * (s - S) = S * Lu - s * Ls) by (unfold t; field; lra).
    nra.
  - subst s; specialize (H3 eq_refl); nra.
  - specialize (H2 Hgt); set (t := (S * Lu - s * Ls) / (s - S)) in H2.
    assert (Ht : t * (s - S) = S * Lu - s * Ls) by (unfold t; field; lra).
    nra.
Qed.

Lemma cycle_algebra S l W Ls m :
  0 < S -> 0 < l -> m <= S * (W / l) - Ls -> 0 <= W - (Ls + m) / S * l.
Proof.
  intros HS Hl H.
  replace (W - (Ls + m) / S * l) with (l / S * (S * (W / l) - Ls - m)) by (field; lra).
  apply Rmult_le_pos; [|lra]; unfold Rdiv.
  apply Rmult_le_pos; [lra|left; apply Rinv_0_lt_compat; auto].
Qed.

Lemma wend_in_tl P x c : c <> [] -> In (wend P x c) (tl (trace P x c)).
Proof.
  destruct c as [|i w]; [congruence|]; intros _; simpl.
  destruct (trace_last P (target P x (Move i)) w) as (l & El); rewrite El.
  apply in_or_app; right; left; reflexivity.
Qed.

(** ** Averages of periodic stage costs *)

Lemma partial_periodic s p :
  (forall k, s (k + p)%nat = s k) ->
  forall q r, partial s (q * p + r) = INR q * partial s p + partial s r.
Proof.
  intros Hs q; induction q as [|q IH]; intros r; [simpl; ring|].
  replace (S q * p + r)%nat with (p + (q * p + r))%nat by lia.
  rewrite partial_add, S_INR.
  rewrite (partial_ext (fun k => s (p + k)%nat) s) by (intros k; rewrite Nat.add_comm; apply Hs).
  rewrite IH; ring.
Qed.

Lemma partial_abs s r : Rabs (partial s r) <= partial (fun k => Rabs (s k)) r.
Proof.
  induction r as [|r IH]; simpl; [rewrite Rabs_R0; lra|].
  eapply Rle_trans; [apply Rabs_triang | lra].
Qed.

Lemma partial_nonneg_mono s r p :
  (forall k, 0 <= s k) -> (r <= p)%nat -> partial s r <= partial s p.
Proof.
  intros Hs Hrp; replace p with (r + (p - r))%nat by lia.
  rewrite partial_add; enough (0 <= partial (fun k => s (r + k)%nat) (p - r)) by lra.
  induction (p - r)%nat as [|m IH]; simpl; [lra|]; pose proof (Hs (r + m)%nat); lra.
Qed.

(** The average of a periodic stage cost sequence is its mean over one period. *)
Lemma average_periodic s p :
  (0 < p)%nat -> (forall k, s (k + p)%nat = s k) -> average s (partial s p / INR p).
Proof.
  intros Hp Hs.
  set (a := partial s p / INR p).
  set (B := partial (fun k => Rabs (s k)) p + Rabs (partial s p)).
  assert (HpR : 0 < INR p) by (apply lt_0_INR; auto).
  assert (Hbound : forall N, Rabs (partial s N - INR N * a) <= B).
  { intros N; pose proof (Nat.div_mod N p ltac:(lia)) as HN.
    pose proof (Nat.mod_upper_bound N p ltac:(lia)) as Hr.
    set (q := (N / p)%nat) in *; set (r := (N mod p)%nat) in *.
    rewrite HN, (Nat.mul_comm p q), partial_periodic by auto.
    rewrite plus_INR, mult_INR.
    replace (INR q * partial s p + partial s r - (INR q * INR p + INR r) * a)
      with (partial s r - INR r * a) by (unfold a; field; lra).
    eapply Rle_trans; [apply Rabs_triang|]; rewrite Rabs_Ropp.
    unfold B; apply Rplus_le_compat.
    - eapply Rle_trans; [apply partial_abs|].
      apply partial_nonneg_mono; [intros; apply Rabs_pos | lia].
    - unfold a; rewrite Rabs_mult, Rabs_right by (apply Rle_ge, pos_INR).
      unfold Rdiv; rewrite Rabs_mult, (Rabs_right (/ INR p))
        by (left; apply Rinv_0_lt_compat; auto).
      assert (INR r <= INR p) by (apply le_INR; lia).
      assert (0 <= Rabs (partial s p)) by apply Rabs_pos.
      replace (Rabs (partial s p)) with (INR p * (Rabs (partial s p) * / INR p)) at 2
        by (field; lra).
      apply Rmult_le_compat_r; [|auto].
      apply Rmult_le_pos; [auto | left; apply Rinv_0_lt_compat; auto]. }
  assert (HB : 0 <= B).
  { pose proof (Hbound 0%nat) as H; pose proof (Rabs_pos (partial s 0 - INR 0 * a)); lra. }
  intros eps Heps.
  destruct (nat_above (B / eps)) as (N0 & HN0).
  exists N0; intros N HN; unfold R_dist.
  assert (HSN : 0 < INR (S N)) by (apply lt_0_INR; lia).
  assert (HN0' : INR N0 <= INR (S N)) by (apply le_INR; lia).
  replace (partial s (S N) / INR (S N) - a) with ((partial s (S N) - INR (S N) * a) / INR (S N))
    by (field; lra).
  unfold Rdiv; rewrite Rabs_mult, (Rabs_right (/ INR (S N)))
    by (left; apply Rinv_0_lt_compat; auto).
  apply Rle_lt_trans with (B * / INR (S N)).
  { apply Rmult_le_compat_r; [left; apply Rinv_0_lt_compat; auto | apply Hbound]. }
  apply (Rmult_lt_reg_r (INR (S N))); [auto|].
  rewrite Rmult_assoc, Rinv_l by lra.
  assert (B < eps * INR (S N)).
  { assert (B / eps < INR (S N)) by lra.
    apply (Rmult_lt_compat_l eps) in H; [|auto].
    unfold Rdiv in H; replace (eps * (B * / eps)) with B in H by (field; lra); lra. }
  lra.
Qed.

(** A finite prefix does not change an average. *)
Lemma average_shift (s t : sequence) K a :
  (forall k, s (K + k)%nat = t k) -> average t a -> average s a.
Proof.
  intros Hst Ht eps Heps.
  set (B := Rabs (partial s K - INR K * a)).
  destruct (Ht (eps / 2) ltac:(lra)) as (N1 & HN1).
  destruct (nat_above (2 * B / eps)) as (N2 & HN2).
  exists (K + S N1 + N2)%nat; intros N HN; unfold R_dist.
  assert (HSN : 0 < INR (S N)) by (apply lt_0_INR; lia).
  set (M := (N - K)%nat).
  assert (HNM : S N = (K + S M)%nat) by (unfold M; lia).
  assert (Hp : partial s (S N) = partial s K + partial t (S M)).
  { rewrite HNM, partial_add; f_equal; apply partial_ext; auto. }
  specialize (HN1 M ltac:(unfold M; lia)); unfold R_dist in HN1.
  assert (HSM : 0 < INR (S M)) by (apply lt_0_INR; lia).
  assert (Hsplit : partial s (S N) / INR (S N) - a
                   = (partial s K - INR K * a) / INR (S N)
                     + INR (S M) / INR (S N) * (partial t (S M) / INR (S M) - a)).
  { rewrite Hp, HNM, plus_INR; pose proof (pos_INR K); field; repeat split; lra. }
  rewrite Hsplit; eapply Rle_lt_trans; [apply Rabs_triang|].
  assert (HSNge : INR N2 <= INR (S N)) by (apply le_INR; lia).
  assert (H1 : Rabs ((partial s K - INR K * a) / INR (S N)) < eps / 2 \/ B = 0).
  { destruct (Req_dec B 0) as [E|E]; [right; auto|left].
    unfold Rdiv; rewrite Rabs_mult, (Rabs_right (/ INR (S N)))
      by (left; apply Rinv_0_lt_compat; auto).
    fold B; apply (Rmult_lt_reg_r (INR (S N))); [auto|].
    rewrite Rmult_assoc, Rinv_l by lra.
    assert (2 * B / eps < INR (S N)) by lra.
    apply (Rmult_lt_compat_l (eps / 2)) in H; [|lra].
    replace (eps / 2 * (2 * B / eps)) with B in H by (field; lra); lra. }
  assert (H2 : Rabs (INR (S M) / INR (S N) * (partial t (S M) / INR (S M) - a)) < eps / 2).
  { rewrite Rabs_mult, (Rabs_right (INR (S M) / INR (S N))).
    - assert (INR (S M) / INR (S N) <= 1).
      { apply (Rmult_le_reg_r (INR (S N))); [auto|]; unfold Rdiv.
        rewrite Rmult_assoc, Rinv_l, Rmult_1_l, Rmult_1_r by lra; apply le_INR; lia. }
      assert (0 <= INR (S M) / INR (S N)).
      { unfold Rdiv; apply Rmult_le_pos; [lra|left; apply Rinv_0_lt_compat; auto]. }
      pose proof (Rabs_pos (partial t (S M) / INR (S M) - a)); nra.
    - apply Rle_ge; unfold Rdiv; apply Rmult_le_pos; [lra|left; apply Rinv_0_lt_compat; auto]. }
  destruct H1 as [H1|H1]; [lra|].
  unfold Rdiv at 1; rewrite Rabs_mult; fold B; rewrite H1, Rmult_0_l; lra.
Qed.

Lemma firstn_snoc (l : list nat) r :
  (r < length l)%nat -> firstn (S r) l = firstn r l ++ [nth r l 0%nat].
Proof.
  revert r; induction l as [|a l IH]; intros r Hr; simpl in Hr; [lia|].
  destruct r as [|r]; [reflexivity|].
  change (firstn (S (S r)) (a :: l)) with (a :: firstn (S r) l).
  rewrite IH by lia; reflexivity.
Qed.

Section Corrected.
Variable P : problem.
Hypothesis HP : wf P.
Variable M : Q.
Notation n := (nstates P).

(** The average-cost problem as a problem of the model: the goal's only move is the reset to
    [x1 = 0], costing [M]; every other state keeps its moves. (Its costs may be negative: it is
    used for walks and their costs only.) *)
Definition reset_problem : problem := {|
  nstates := n;
  goal := goal P;
  moves := fun x => if Nat.eqb x (goal P) then [(0%nat, M)] else moves P x
|}.
Notation PM := reset_problem.

Lemma PM_moves_goal : moves PM (goal P) = [(0%nat, M)].
Proof. simpl; rewrite Nat.eqb_refl; reflexivity. Qed.

Lemma PM_moves_other x : x <> goal P -> moves PM x = moves P x.
Proof. intros H; simpl; rewrite (proj2 (Nat.eqb_neq _ _) H); reflexivity. Qed.

Lemma PM_target_other x i : x <> goal P -> target PM x (Move i) = target P x (Move i).
Proof. intros H; unfold target; rewrite PM_moves_other by auto; reflexivity. Qed.

Lemma PM_cost_other x i : x <> goal P -> cost PM x (Move i) = cost P x (Move i).
Proof. intros H; unfold cost; rewrite PM_moves_other by auto; reflexivity. Qed.

Lemma PM_step_lt x i :
  (x < n)%nat -> (i < length (moves PM x))%nat -> (target PM x (Move i) < n)%nat.
Proof.
  intros Hx Hi; destruct (Nat.eq_dec x (goal P)) as [->|Ne].
  - rewrite PM_moves_goal in Hi; simpl in Hi; destruct i; [|lia].
    unfold target; rewrite PM_moves_goal; simpl; destruct HP; lia.
  - rewrite PM_moves_other in Hi by auto; rewrite PM_target_other by auto.
    apply (wf_move P HP); auto.
Qed.

Lemma PM_trace_lt x w z : (x < n)%nat -> wvalid PM x w -> In z (trace PM x w) -> (z < n)%nat.
Proof.
  revert x; induction w as [|i w IH]; intros x Hx Hw Hz; simpl in Hz.
  - destruct Hz as [<-|[]]; auto.
  - destruct Hz as [<-|Hz]; auto; destruct Hw as [Hi Hw].
    apply (IH _ (PM_step_lt x i Hx Hi) Hw Hz).
Qed.

Lemma PM_move_cost_ge x i : (x < n)%nat -> (i < length (moves PM x))%nat ->
  (Qmin2 0 M <= cost PM x (Move i))%Q.
Proof.
  intros Hx Hi; destruct (Nat.eq_dec x (goal P)) as [->|Ne].
  - rewrite PM_moves_goal in Hi; simpl in Hi; destruct i; [|lia].
    unfold cost; rewrite PM_moves_goal; simpl; apply Qmin2_r.
  - rewrite PM_moves_other in Hi by auto; rewrite PM_cost_other by auto.
    pose proof (proj2 (wf_move P HP x i Hx Hi)); pose proof (Qmin2_l 0 M); qlra.
Qed.

(** States reachable from [x1 = 0] in the average-cost problem. *)
Definition reachable (x : nat) : Prop := exists p, wvalid PM 0 p /\ wend PM 0 p = x.

Lemma reachable_step x w : reachable x -> wvalid PM x w -> reachable (wend PM x w).
Proof.
  intros (p & Hp & E) Hw; exists (p ++ w); rewrite wvalid_app, wend_app, E; auto.
Qed.

(** The weight of a walk against a candidate average [g]: its cost minus [g] per stage. *)
Definition weight (g : Q) (x : nat) (w : list nat) : Q :=
  (wcost PM x w - g * inject_Z (Z.of_nat (length w)))%Q.

Lemma weight_app g x a b : (weight g x (a ++ b) == weight g x a + weight g (wend PM x a) b)%Q.
Proof.
  unfold weight; rewrite wcost_app, app_length, Nat2Z.inj_add, inject_Z_plus; ring.
Qed.

Lemma weight_cons g x i w :
  (weight g x (i :: w) == cost PM x (Move i) - g + weight g (target PM x (Move i)) w)%Q.
Proof.
  unfold weight; simpl wcost; simpl length; rewrite Nat2Z.inj_succ, <- Z.add_1_r, inject_Z_plus.
  unfold inject_Z at 2; ring.
Qed.

(** A simple cycle of the average-cost problem: a nonempty closed walk whose states (after
    each stage) are distinct. *)
Definition simple_cycle (x : nat) (c : list nat) : Prop :=
  c <> [] /\ wvalid PM x c /\ wend PM x c = x /\ NoDup (tl (trace PM x c)).

Variable g : Q.

(** The min-mean-cycle fact, part 1: if every simple cycle reachable from [x1] has mean cost
    at least [g], so has every closed walk reachable from [x1]. *)
Lemma closed_nonneg :
  (forall x c, reachable x -> simple_cycle x c -> (0 <= weight g x c)%Q) ->
  forall c x, reachable x -> c <> [] -> wvalid PM x c -> wend PM x c = x -> (0 <= weight g x c)%Q.
Proof.
  intros HC c; remember (length c) as m eqn:Hm; revert c Hm.
  induction m as [m IH] using (well_founded_induction lt_wf); intros c Hm x Hx Hne Hw He.
  destruct c as [|i w]; [congruence|].
  set (y := target PM x (Move i)).
  destruct (ListDec.NoDup_dec Nat.eq_dec (trace PM y w)) as [Hnd|Hnd].
  { apply HC; auto; split; [congruence|]; split; [auto|]; split; [auto|]; simpl; exact Hnd. }
  destruct (repeat_split PM y w Hnd) as (w1 & w2 & w3 & -> & Hne2 & E).
  destruct Hw as [Hi Hw]; fold y in Hw.
  apply wvalid_app in Hw as [Hw1 Hw23]; apply wvalid_app in Hw23 as [Hw2 Hw3].
  rewrite wend_app in E.
  set (z := wend PM y w1) in *.
  assert (Hz : reachable z) by (apply (reachable_step x (i :: w1)); auto; split; auto).
  assert (Hc2 : (0 <= weight g z w2)%Q).
  { refine (IH (length w2) _ w2 eq_refl z Hz Hne2 Hw2 (eq_sym E)).
    subst m; simpl; rewrite !app_length; lia. }
  assert (Hw3' : wvalid PM z w3) by (rewrite E; exact Hw3).
  assert (Hv' : wvalid PM x (i :: w1 ++ w3)).
  { split; [auto|]; apply wvalid_app; split; [auto | exact Hw3']. }
  assert (Hz3 : wend PM z w3 = x).
  { rewrite E at 1; change (wend PM y (w1 ++ w2 ++ w3) = x) in He.
    rewrite !wend_app in He; exact He. }
  assert (He' : wend PM x (i :: w1 ++ w3) = x).
  { change (wend PM y (w1 ++ w3) = x); rewrite wend_app; exact Hz3. }
  assert (Hc' : (0 <= weight g x (i :: w1 ++ w3))%Q).
  { refine (IH (length (i :: w1 ++ w3)) _ _ eq_refl x Hx ltac:(congruence) Hv' He').
    subst m; simpl; rewrite !app_length; destruct w2; [congruence|simpl; lia]. }
  rewrite weight_cons in Hc' |- *; fold y in Hc' |- *.
  rewrite weight_app in Hc' |- *; rewrite weight_app; fold z in Hc' |- *.
  rewrite <- E; qlra.
Qed.
Variable D : Q.
Hypothesis HD : forall x i, (x < n)%nat -> (i < length (moves PM x))%nat ->
  (- D <= cost PM x (Move i) - g)%Q.

Lemma edge_bound w x :
  (x < n)%nat -> wvalid PM x w -> (- (inject_Z (Z.of_nat (length w)) * D) <= weight g x w)%Q.
Proof.
  revert x; induction w as [|i w IH]; intros x Hx Hw.
  - unfold weight; simpl; unfold Qle; simpl; lia.
  - destruct Hw as [Hi Hw]; rewrite weight_cons.
    pose proof (IH _ (PM_step_lt x i Hx Hi) Hw); pose proof (HD x i Hx Hi).
    simpl length; rewrite Nat2Z.inj_succ, <- Z.add_1_r, inject_Z_plus.
    unfold inject_Z at 2; qlra.
Qed.

(** The min-mean-cycle fact, part 2: then every walk from a reachable state costs at least [g]
    per stage, up to a constant ([n D]): the walk decomposes into simple cycles and a simple
    path. *)
Lemma walk_bound :
  (0 <= D)%Q ->
  (forall x c, reachable x -> simple_cycle x c -> (0 <= weight g x c)%Q) ->
  forall w x, (x < n)%nat -> reachable x -> wvalid PM x w ->
    (- (inject_Z (Z.of_nat n) * D) <= weight g x w)%Q.
Proof.
  intros HD0 HC w; remember (length w) as m eqn:Hm; revert w Hm.
  induction m as [m IH] using (well_founded_induction lt_wf); intros w Hm x Hx Hr Hw.
  destruct (ListDec.NoDup_dec Nat.eq_dec (trace PM x w)) as [Hnd|Hnd].
  - assert (Hlen : (length w < n)%nat).
    { pose proof (NoDup_incl_length Hnd (l' := seq 0 n)) as H.
      rewrite trace_length, seq_length in H; apply H.
      intros z Hz; apply in_seq; split; [lia|]; simpl; eapply PM_trace_lt; eauto. }
    pose proof (edge_bound w x Hx Hw).
    assert (inject_Z (Z.of_nat (length w)) <= inject_Z (Z.of_nat n))%Q.
    { rewrite <- Zle_Qle; lia. }
    assert (inject_Z (Z.of_nat (length w)) * D <= inject_Z (Z.of_nat n) * D)%Q.
    { apply Qmult_le_compat_r; auto. }
    qlra.
  - destruct (repeat_split PM x w Hnd) as (w1 & w2 & w3 & -> & Hne2 & E).
    apply wvalid_app in Hw as [Hw1 Hw23]; apply wvalid_app in Hw23 as [Hw2 Hw3].
    rewrite wend_app in E; set (z := wend PM x w1) in *.
    assert (Hz : reachable z) by (apply reachable_step; auto).
    assert (Hc2 : (0 <= weight g z w2)%Q) by (apply (closed_nonneg HC w2 z); auto; congruence).
    assert (Hw3' : wvalid PM z w3) by (rewrite E; exact Hw3).
    assert (H13 : (- (inject_Z (Z.of_nat n) * D) <= weight g x (w1 ++ w3))%Q).
    { refine (IH (length (w1 ++ w3)) _ _ eq_refl x Hx Hr _).
      - subst m; rewrite !app_length; destruct w2; [congruence|simpl; lia].
      - apply wvalid_app; split; auto. }
    rewrite weight_app in H13; rewrite !weight_app; fold z in H13 |- *.
    rewrite <- E; qlra.
Qed.

(** The first [N] stages of a run are a walk of the average-cost problem from [x1]. *)
Lemma run_prefix x c :
  reset_run P (Q2R M) x c -> forall N, exists w, length w = N /\ wvalid PM 0 w /\
    wend PM 0 w = x N /\ Q2R (wcost PM 0 w) = partial c N.
Proof.
  intros [H0 Hs] N; induction N as [|N IH].
  - exists []; repeat split; auto; unfold Q2R; simpl; lra.
  - destruct IH as (w & Hl & Hv & He & Hc).
    destruct (Hs N) as [(Eg & E' & Ec)|(Ne & i & Hi & E' & Ec)].
    + exists (w ++ [0%nat]); rewrite app_length, wvalid_app, wend_app, He, Eg; simpl length.
      repeat split; [lia | auto | rewrite PM_moves_goal; simpl; lia | |].
      * simpl; unfold target; rewrite PM_moves_goal; simpl; auto.
      * rewrite (Qeq_eqR _ _ (wcost_app PM 0 w [0%nat])), Q2R_plus, He, Eg, Hc, partial_S, Ec.
        simpl wcost; unfold cost; rewrite PM_moves_goal; simpl.
        rewrite Q2R_plus; rewrite Q2R_0; ring.
    + exists (w ++ [i]); rewrite app_length, wvalid_app, wend_app, He; simpl length.
      repeat split; [lia | auto | rewrite PM_moves_other by auto; auto | |].
      * simpl; rewrite PM_target_other by auto; auto.
      * rewrite (Qeq_eqR _ _ (wcost_app PM 0 w [i])), Q2R_plus, He, Hc, partial_S, Ec.
        simpl wcost; rewrite PM_cost_other by auto.
        rewrite Q2R_plus; rewrite Q2R_0; ring.
Qed.

(** Every run pays at least [g] per stage, up to the constant [n D]. *)
Lemma run_lower x c :
  (0 <= D)%Q ->
  (forall x c, reachable x -> simple_cycle x c -> (0 <= weight g x c)%Q) ->
  reset_run P (Q2R M) x c ->
  forall N, Q2R g * INR N - Q2R (inject_Z (Z.of_nat n) * D) <= partial c N.
Proof.
  intros HD0 HC Hrun N.
  destruct (run_prefix x c Hrun N) as (w & Hl & Hv & _ & Hc).
  assert (H0 : (0 < n)%nat) by (destruct HP; lia).
  pose proof (walk_bound HD0 HC w 0 H0 (ex_intro _ [] (conj I eq_refl)) Hv) as H.
  apply Qle_Rle in H; unfold weight in H.
  rewrite Q2R_minus, Q2R_mult, Q2R_nat, Hl, Q2R_opp, Q2R_mult in H.
  rewrite <- Hc; rewrite Q2R_mult; lra.
Qed.

(** A walk of the average-cost problem that takes no move at the goal is a walk of [P]. *)
Lemma PM_walk_P x w :
  ~ In (goal P) (removelast (trace PM x w)) -> wvalid PM x w ->
  wvalid P x w /\ wend P x w = wend PM x w /\ wcost P x w = wcost PM x w /\
  trace P x w = trace PM x w.
Proof.
  revert x; induction w as [|i w IH]; intros x Hg Hw; [simpl; auto|].
  destruct Hw as [Hi Hw].
  assert (Hx : x <> goal P).
  { intros ->; apply Hg; simpl; destruct (trace PM (target PM (goal P) (Move i)) w) eqn:E;
      [destruct w; discriminate | left; auto]. }
  assert (Hg' : ~ In (goal P) (removelast (trace PM (target PM x (Move i)) w))).
  { intros H; apply Hg; simpl; destruct (trace PM (target PM x (Move i)) w) eqn:E;
      [destruct w; discriminate | right; auto]. }
  rewrite PM_target_other in Hw, Hg' by auto.
  destruct (IH _ Hg' Hw) as (H1 & H2 & H3 & H4).
  rewrite PM_moves_other in Hi by auto.
  simpl; rewrite PM_target_other, PM_cost_other by auto.
  repeat split; auto; congruence.
Qed.

(** Reachable in [P] from [x1] by a walk that avoids the goal. *)
Definition reach_avoid (y : nat) : Prop :=
  exists p, wvalid P 0 p /\ wend P 0 p = y /\ ~ In (goal P) (trace P 0 p).

Lemma reachable_avoid p x :
  (x = goal P \/ reach_avoid x) -> wvalid PM x p ->
  wend PM x p = goal P \/ reach_avoid (wend PM x p).
Proof.
  assert (H0 : goal P = 0%nat \/ reach_avoid 0).
  { destruct (Nat.eq_dec 0 (goal P)) as [E|E]; [left; auto|right].
    exists []; simpl; repeat split; auto; intros [H|[]]; auto. }
  revert x; induction p as [|i p IH]; intros x Hx Hw; [exact Hx|].
  destruct Hw as [Hi Hw]; simpl; apply IH; [|exact Hw].
  destruct Hx as [->|(q & Hq & Eq & Hgq)].
  - rewrite PM_moves_goal in Hi; simpl in Hi; destruct i; [|lia].
    unfold target; rewrite PM_moves_goal; simpl; destruct H0 as [E|E]; [left|right]; auto.
  - assert (Hx : x <> goal P).
    { intros E; apply Hgq; destruct (trace_last P 0 q) as (l & El); rewrite El, Eq, E.
      apply in_or_app; right; left; auto. }
    rewrite PM_target_other by auto; rewrite PM_moves_other in Hi by auto.
    destruct (Nat.eq_dec (target P x (Move i)) (goal P)) as [E|E]; [left; auto|right].
    exists (q ++ [i]); rewrite wvalid_app, wend_app, trace_app, Eq; simpl; repeat split; auto.
    rewrite in_app_iff; intros [H|[H|[]]]; auto.
Qed.

Lemma start_avoid : 0%nat = goal P \/ reach_avoid 0.
Proof.
  destruct (Nat.eq_dec 0 (goal P)) as [E|E]; [left; auto|right].
  exists []; simpl; repeat split; auto; intros [H|[]]; auto.
Qed.

(** ** The statement's terms *)

(** A simple goal path [u] from [x1]: [S(u)] states, cost [L(u)]. *)
Definition simple_goal_path (u : list nat) : Prop := reaches P 0 u /\ NoDup (trace P 0 u).
Definition S_of (u : list nat) : R := INR (S (length u)).
Definition L_of (u : list nat) : R := Q2R (wcost P 0 u).

(** [T(u) = (S_star L(u) - S(u) L_star) / (S(u) - S_star)]. *)
Definition T_of (Ss Ls : R) (u : list nat) : R := (Ss * L_of u - S_of u * Ls) / (S_of u - Ss).

(** A simple cycle [c] at [x] avoiding the goal, [x] reachable from [x1] avoiding the goal;
    its mean cost per stage. *)
Definition avoiding_cycle (x : nat) (c : list nat) : Prop :=
  c <> [] /\ wvalid P x c /\ wend P x c = x /\ NoDup (tl (trace P x c)) /\
  ~ In (goal P) (trace P x c) /\ reach_avoid x.
Definition mean_of (x : nat) (c : list nat) : R := Q2R (wcost P x c) / INR (length c).

(** The corrected interval, its max and mins written as bounds over every simple goal path
    and every goal-avoiding simple cycle (an empty max is [-oo], an empty min [+oo]; the least
    mean over the simple cycles is [Lav(C^)], the least over all cycles):
    [max{T(u) : S(u) < S_star} <= M <=
     min{ min{T(u) : S(u) > S_star}, S_star Lav(C^) - L_star }]. *)
Definition corrected_interval (Ss Ls Mr : R) : Prop :=
  (forall u, simple_goal_path u -> S_of u < Ss -> T_of Ss Ls u <= Mr) /\
  (forall u, simple_goal_path u -> Ss < S_of u -> Mr <= T_of Ss Ls u) /\
  (forall x c, avoiding_cycle x c -> Mr <= Ss * mean_of x c - Ls).

Lemma Q2R_weight x c :
  Q2R (weight g x c) = Q2R (wcost PM x c) - Q2R g * INR (length c).
Proof. unfold weight; rewrite Q2R_minus, Q2R_mult, Q2R_nat; reflexivity. Qed.

Lemma NoDup_snoc_notin (l : list nat) a : NoDup (l ++ [a]) -> ~ In a l.
Proof.
  intros H Hin; apply NoDup_remove_2 in H; apply H; rewrite app_nil_r; auto.
Qed.

(** A simple cycle through the goal, rotated to start there, is the reset followed by a simple
    goal path [u] from [x1]. *)
Lemma cycle_through_goal x c :
  simple_cycle x c -> In (goal P) (tl (trace PM x c)) ->
  exists u, simple_goal_path u /\
    Q2R (weight g x c) = Q2R M + L_of u - Q2R g * INR (S (length u)).
Proof.
  intros (Hne & Hv & He & Hnd) Hin.
  assert (Hin' : In (goal P) (trace PM x c)) by (destruct c; [congruence|right; auto]).
  destruct (in_trace_split PM x c (goal P) Hin') as (c1 & c2 & -> & E1).
  assert (E2 : wend PM (goal P) c2 = x) by (rewrite <- E1, <- wend_app; auto).
  apply wvalid_app in Hv as [Hv1 Hv2]; rewrite E1 in Hv2.
  assert (Hw : (weight g x (c1 ++ c2) == weight g (goal P) (c2 ++ c1))%Q).
  { rewrite !weight_app, E1, E2; Lqa.lra. }
  assert (Hnd' : NoDup (tl (trace PM (goal P) (c2 ++ c1)))).
  { rewrite trace_app, E2; rewrite trace_app, E1 in Hnd.
    assert (Hl1 : trace PM x c1 <> []) by (destruct c1; discriminate).
    assert (Hl2 : trace PM (goal P) c2 <> []) by (destruct c2; discriminate).
    destruct (trace PM x c1) as [|a1 t1]; [congruence|].
    destruct (trace PM (goal P) c2) as [|a2 t2]; [congruence|].
    simpl in Hnd |- *.
    apply (Permutation.Permutation_NoDup (Permutation.Permutation_app_comm _ _)).
    exact Hnd. }
  rewrite (Qeq_eqR _ _ Hw), Q2R_weight.
  destruct (c2 ++ c1) as [|j u] eqn:Ec; [destruct c1, c2; simpl in *; congruence|].
  assert (Hvc : wvalid PM (goal P) (j :: u))
    by (rewrite <- Ec; apply wvalid_app; rewrite E2; auto).
  assert (Hec : wend PM (goal P) (j :: u) = goal P) by (rewrite <- Ec, wend_app, E2; auto).
  destruct Hvc as [Hj Hvu]; rewrite PM_moves_goal in Hj; simpl in Hj.
  destruct j; [|lia].
  assert (Ht0 : target PM (goal P) (Move 0) = 0%nat)
    by (unfold target; rewrite PM_moves_goal; reflexivity).
  assert (Hc0 : cost PM (goal P) (Move 0) = M)
    by (unfold cost; rewrite PM_moves_goal; reflexivity).
  simpl in Hec, Hnd'; rewrite Ht0 in Hec, Hvu, Hnd'.
  assert (Hng : ~ In (goal P) (removelast (trace PM 0 u))).
  { destruct (trace_last PM 0 u) as (l & El); rewrite El, removelast_last.
    rewrite El, Hec in Hnd'; apply NoDup_snoc_notin; auto. }
  destruct (PM_walk_P 0 u Hng Hvu) as (HvP & HeP & HcP & HtP).
  exists u; split; [split; [split; congruence | rewrite HtP; auto]|].
  simpl wcost; simpl length; rewrite Ht0, Hc0, Q2R_plus, <- HcP; unfold L_of; ring.
Qed.

(** A simple cycle that avoids the goal is a goal-avoiding simple cycle of [P], reachable from
    [x1] avoiding the goal, with the same cost. *)
Lemma cycle_avoiding x c :
  reachable x -> simple_cycle x c -> ~ In (goal P) (tl (trace PM x c)) ->
  avoiding_cycle x c /\ wcost PM x c = wcost P x c.
Proof.
  intros Hx (Hne & Hv & He & Hnd) Hout.
  assert (Hxg : x <> goal P).
  { intros E; apply Hout; rewrite <- E at 1; rewrite <- He at 1; apply wend_in_tl; auto. }
  assert (Hng : ~ In (goal P) (trace PM x c)).
  { destruct c as [|i w]; [congruence|]; simpl; intros [E|E]; [congruence|apply Hout; exact E]. }
  assert (Hng' : ~ In (goal P) (removelast (trace PM x c))).
  { intros H; apply Hng; destruct (trace_last PM x c) as (l & El); rewrite El in H |- *.
    rewrite removelast_last in H; apply in_or_app; left; auto. }
  destruct (PM_walk_P x c Hng' Hv) as (HvP & HeP & HcP & HtP).
  assert (Hra : reach_avoid x).
  { destruct Hx as (p & Hp & Ep).
    destruct (reachable_avoid p 0 start_avoid Hp) as [E|E]; rewrite Ep in E; [congruence|auto]. }
  split; [|auto]; repeat split; auto; try congruence; rewrite HtP; auto.
Qed.

(** Under the corrected interval, every simple cycle reachable from [x1] has mean cost at
    least [g = (L_star + M)/S_star]: a cycle through the goal is a simple goal path plus the
    reset (the [T] bounds), a cycle avoiding it is bounded by [Lav(C^)]. *)
Lemma cycles_above sn Lstar :
  Gstar P 0 = Some Lstar -> (0 < sn)%nat ->
  Q2R g = (Q2R Lstar + Q2R M) / INR sn ->
  corrected_interval (INR sn) (Q2R Lstar) (Q2R M) ->
  forall x c, reachable x -> simple_cycle x c -> (0 <= weight g x c)%Q.
Proof.
  intros HG Hsn Hg (HT1 & HT2 & Hcyc) x c Hx Hsc.
  assert (HS : 0 < INR sn) by (apply lt_0_INR; auto).
  assert (H0n : (0 < n)%nat) by (destruct HP; lia).
  apply Rle_Qle; rewrite Q2R_0.
  destruct (in_dec Nat.eq_dec (goal P) (tl (trace PM x c))) as [Hin|Hout].
  - destruct (cycle_through_goal x c Hsc Hin) as (u & Hsp & E); rewrite E, Hg.
    destruct (Gstar_least P HP 0 u H0n (proj1 Hsp)) as (gl & Egl & Hgl).
    rewrite HG in Egl; inversion Egl; subst gl.
    rewrite S_INR.
    pose proof (T_algebra (INR sn) (S_of u) (L_of u) (Q2R Lstar) (Q2R M) HS
                  ltac:(unfold S_of; apply lt_0_INR; lia) (HT1 u Hsp) (HT2 u Hsp)) as H.
    unfold S_of in H; rewrite S_INR in H.
    assert (Hle : Q2R Lstar <= L_of u) by (apply Qle_Rle; auto).
    apply H; intros _; exact Hle.
  - destruct (cycle_avoiding x c Hx Hsc Hout) as [Hac HcP].
    destruct Hsc as (Hne & _).
    rewrite Q2R_weight, Hg.
    pose proof (Hcyc x c Hac) as H; unfold mean_of in H; rewrite <- HcP in H.
    apply cycle_algebra; auto.
    apply lt_0_INR; destruct c; [congruence|simpl; lia].
Qed.

(** A walk of [P] that takes no move at the goal is a walk of the average-cost problem. *)
Lemma P_walk_PM x w :
  ~ In (goal P) (removelast (trace P x w)) -> wvalid P x w ->
  wvalid PM x w /\ wend PM x w = wend P x w /\ wcost PM x w = wcost P x w.
Proof.
  revert x; induction w as [|i w IH]; intros x Hg Hw; [simpl; auto|].
  destruct Hw as [Hi Hw].
  assert (Hx : x <> goal P).
  { intros ->; apply Hg; simpl; destruct (trace P (target P (goal P) (Move i)) w) eqn:E;
      [destruct w; discriminate | left; auto]. }
  assert (Hg' : ~ In (goal P) (removelast (trace P (target P x (Move i)) w))).
  { intros H; apply Hg; simpl; destruct (trace P (target P x (Move i)) w) eqn:E;
      [destruct w; discriminate | right; auto]. }
  destruct (IH _ Hg' Hw) as (H1 & H2 & H3).
  cbn [wvalid wend wcost]; rewrite PM_target_other, PM_cost_other, PM_moves_other by auto.
  repeat split; auto; congruence.
Qed.

(** ** The run that repeats a closed walk from [x1] (a stationary policy's lasso with no
    prefix) *)

(** A stage of the average-cost problem is a stage of a run. *)
Lemma pm_step_ok (x : nat -> nat) (c : sequence) k i :
  (i < length (moves PM (x k)))%nat -> x (S k) = target PM (x k) (Move i) ->
  c k = Q2R (cost PM (x k) (Move i)) -> step_ok P (Q2R M) x c k.
Proof.
  intros Hi E Ec; unfold step_ok; destruct (Nat.eq_dec (x k) (goal P)) as [Eg|Ng].
  - left; rewrite Eg in Hi, E, Ec; rewrite PM_moves_goal in Hi; simpl in Hi.
    destruct i; [|lia].
    rewrite E, Eg, Ec; unfold target, cost; rewrite PM_moves_goal; auto.
  - right; split; [auto|]; exists i.
    rewrite PM_moves_other in Hi by auto; rewrite E, PM_target_other by auto.
    rewrite Ec, PM_cost_other by auto; auto.
Qed.

Definition cyc_x (x0 : nat) (cyc : list nat) (k : nat) : nat :=
  wend PM x0 (firstn (k mod length cyc) cyc).
Definition cyc_a (cyc : list nat) (k : nat) : nat := nth (k mod length cyc) cyc 0%nat.
Definition cyc_c (x0 : nat) (cyc : list nat) (k : nat) : R :=
  Q2R (cost PM (cyc_x x0 cyc k) (Move (cyc_a cyc k))).

Section Cycle.
Variable x0 : nat.
Variable cyc : list nat.
Hypothesis Hne : cyc <> [].
Hypothesis Hv : wvalid PM x0 cyc.
Hypothesis He : wend PM x0 cyc = x0.

Lemma cyc_len : (0 < length cyc)%nat.
Proof. destruct cyc; [congruence | simpl; lia]. Qed.

Lemma cyc_step k :
  (cyc_a cyc k < length (moves PM (cyc_x x0 cyc k)))%nat /\
  cyc_x x0 cyc (S k) = target PM (cyc_x x0 cyc k) (Move (cyc_a cyc k)).
Proof.
  pose proof cyc_len as Hl.
  pose proof (Nat.mod_upper_bound k (length cyc) ltac:(lia)) as Hr.
  unfold cyc_x, cyc_a; set (r := (k mod length cyc)%nat) in *.
  assert (Hsnoc := firstn_snoc cyc r Hr).
  assert (Hvp : wvalid PM x0 (firstn (S r) cyc)).
  { rewrite <- (firstn_skipn (S r) cyc) in Hv; apply wvalid_app in Hv; tauto. }
  rewrite Hsnoc, wvalid_app in Hvp; destruct Hvp as [_ [Hi _]]; split; [exact Hi|].
  pose proof (Nat.div_mod k (length cyc) ltac:(lia)) as Hk; fold r in Hk.
  destruct (Nat.eq_dec (S r) (length cyc)) as [Eq|Ne].
  - rewrite <- (Nat.mod_unique (S k) (length cyc) (S (k / length cyc)) 0) by lia.
    assert (X : wend PM x0 (firstn (S r) cyc)
                = target PM (wend PM x0 (firstn r cyc)) (Move (nth r cyc 0%nat)))
      by (rewrite Hsnoc, wend_app; reflexivity).
    rewrite <- X, Eq, firstn_all, He; reflexivity.
  - rewrite <- (Nat.mod_unique (S k) (length cyc) (k / length cyc) (S r)) by lia.
    rewrite Hsnoc, wend_app; reflexivity.
Qed.

Lemma cyc_step_ok k : step_ok P (Q2R M) (cyc_x x0 cyc) (cyc_c x0 cyc) k.
Proof. destruct (cyc_step k) as [Hi E]; apply (pm_step_ok _ _ k (cyc_a cyc k)); auto. Qed.

Lemma cyc_periodic k : cyc_c x0 cyc (k + length cyc) = cyc_c x0 cyc k.
Proof.
  pose proof cyc_len.
  unfold cyc_c, cyc_x, cyc_a; rewrite <- (Nat.mul_1_l (length cyc)) at 1 3.
  rewrite Nat.mod_add by lia; reflexivity.
Qed.

Lemma cyc_partial r :
  (r <= length cyc)%nat -> partial (cyc_c x0 cyc) r = Q2R (wcost PM x0 (firstn r cyc)).
Proof.
  induction r as [|r IH]; intros Hr; [simpl; unfold Q2R; simpl; lra|].
  rewrite partial_S, IH by lia.
  rewrite firstn_snoc by lia; rewrite (Qeq_eqR _ _ (wcost_app PM x0 _ _)), Q2R_plus.
  unfold cyc_c, cyc_x, cyc_a; rewrite Nat.mod_small by lia; simpl wcost.
  rewrite Q2R_plus; rewrite Q2R_0; ring.
Qed.

Lemma cyc_partial_period : partial (cyc_c x0 cyc) (length cyc) = Q2R (wcost PM x0 cyc).
Proof. rewrite cyc_partial, firstn_all by lia; reflexivity. Qed.

(** The average of a repeated closed walk is its mean cost per stage. *)
Lemma cyc_average : average (cyc_c x0 cyc) (Q2R (wcost PM x0 cyc) / INR (length cyc)).
Proof.
  rewrite <- cyc_partial_period.
  apply average_periodic; [apply cyc_len | apply cyc_periodic].
Qed.
End Cycle.

(** The run that repeats a closed walk from [x1]. *)
Lemma cyc_run cyc :
  cyc <> [] -> wvalid PM 0 cyc -> wend PM 0 cyc = 0%nat ->
  reset_run P (Q2R M) (cyc_x 0 cyc) (cyc_c 0 cyc).
Proof.
  intros Hne Hv He; split; [|apply cyc_step_ok; auto].
  unfold cyc_x; rewrite Nat.mod_0_l by (destruct cyc; [congruence | simpl; lia]); reflexivity.
Qed.

(** [pi*]'s reset cycle: the optimal single-shot path, then the reset. *)
Lemma goal_path_cycle u :
  simple_goal_path u ->
  (u ++ [0%nat]) <> [] /\ wvalid PM 0 (u ++ [0%nat]) /\ wend PM 0 (u ++ [0%nat]) = 0%nat /\
  Q2R (wcost PM 0 (u ++ [0%nat])) = Q2R (wcost P 0 u) + Q2R M /\
  length (u ++ [0%nat]) = S (length u).
Proof.
  intros [[Hv He] Hnd].
  assert (Hng : ~ In (goal P) (removelast (trace P 0 u))).
  { destruct (trace_last P 0 u) as (l & El); rewrite El, removelast_last.
    rewrite El, He in Hnd; apply NoDup_snoc_notin; auto. }
  destruct (P_walk_PM 0 u Hng Hv) as (Hv' & He' & Hc').
  assert (Ht0 : target PM (goal P) (Move 0) = 0%nat)
    by (unfold target; rewrite PM_moves_goal; reflexivity).
  assert (Hc0 : cost PM (goal P) (Move 0) = M) by (unfold cost; rewrite PM_moves_goal; reflexivity).
  repeat split.
  - destruct u; discriminate.
  - apply wvalid_app; split; auto; rewrite He', He; cbn [wvalid].
    rewrite PM_moves_goal; simpl; auto.
  - rewrite wend_app, He', He; cbn [wend]; exact Ht0.
  - rewrite (Qeq_eqR _ _ (wcost_app PM 0 u [0%nat])), Q2R_plus, He', He, Hc'; simpl wcost.
    rewrite Hc0, Q2R_plus; rewrite Q2R_0; ring.
  - rewrite app_length; simpl; lia.
Qed.

(** ** Lassos: a walk from [x1] to [x], then a closed walk at [x] repeated *)

Definition las_x (p : list nat) (x : nat) (c : list nat) (k : nat) : nat :=
  if Nat.ltb k (length p) then wend PM 0 (firstn k p) else cyc_x x c (k - length p).
Definition las_a (p c : list nat) (k : nat) : nat :=
  if Nat.ltb k (length p) then nth k p 0%nat else cyc_a c (k - length p).
Definition las_c (p : list nat) (x : nat) (c : list nat) (k : nat) : R :=
  Q2R (cost PM (las_x p x c k) (Move (las_a p c k))).

Section Lasso.
Variables (p : list nat) (x : nat) (c : list nat).
Hypothesis Hp : wvalid PM 0 p.
Hypothesis Hpx : wend PM 0 p = x.
Hypothesis Hne : c <> [].
Hypothesis Hc : wvalid PM x c.
Hypothesis Hcx : wend PM x c = x.

Lemma las_run : reset_run P (Q2R M) (las_x p x c) (las_c p x c).
Proof.
  split.
  - unfold las_x; destruct (Nat.ltb_spec 0 (length p)); [reflexivity|].
    destruct p; [|simpl in *; lia]; simpl in Hpx; subst x.
    unfold cyc_x; rewrite Nat.mod_0_l by (destruct c; [congruence|simpl; lia]); reflexivity.
  - intros k; destruct (Nat.ltb_spec k (length p)) as [Hk|Hk].
    + assert (Hsn := firstn_snoc p k Hk).
      assert (Hvp : wvalid PM 0 (firstn (S k) p)).
      { rewrite <- (firstn_skipn (S k) p) in Hp; apply wvalid_app in Hp; tauto. }
      rewrite Hsn, wvalid_app in Hvp; destruct Hvp as [_ [Hi _]].
      apply (pm_step_ok _ _ k (nth k p 0%nat)); unfold las_c, las_x, las_a.
      * rewrite (proj2 (Nat.ltb_lt _ _) Hk); exact Hi.
      * rewrite (proj2 (Nat.ltb_lt _ _) Hk).
        assert (X : wend PM 0 (firstn (S k) p)
                    = target PM (wend PM 0 (firstn k p)) (Move (nth k p 0%nat)))
          by (rewrite Hsn, wend_app; reflexivity).
        destruct (Nat.ltb_spec (S k) (length p)) as [Hk'|Hk']; [exact X|].
        rewrite <- X, (firstn_all2 p) by lia; rewrite Hpx.
        replace (S k - length p)%nat with 0%nat by lia.
        unfold cyc_x; rewrite Nat.mod_0_l by (destruct c; [congruence|simpl; lia]); reflexivity.
      * rewrite (proj2 (Nat.ltb_lt _ _) Hk); reflexivity.
    + destruct (cyc_step x c Hne Hc Hcx (k - length p)) as [Hi E].
      apply (pm_step_ok _ _ k (cyc_a c (k - length p))); unfold las_c, las_x, las_a.
      * rewrite (proj2 (Nat.ltb_ge _ _) Hk); exact Hi.
      * rewrite (proj2 (Nat.ltb_ge _ _) Hk), (proj2 (Nat.ltb_ge _ _)) by lia.
        replace (S k - length p)%nat with (S (k - length p)) by lia; exact E.
      * rewrite (proj2 (Nat.ltb_ge _ _) Hk); reflexivity.
Qed.

Lemma las_partial_prefix r :
  (r <= length p)%nat -> partial (las_c p x c) r = Q2R (wcost PM 0 (firstn r p)).
Proof.
  induction r as [|r IH]; intros Hr; [simpl; unfold Q2R; simpl; lra|].
  rewrite partial_S, IH by lia.
  rewrite firstn_snoc by lia; rewrite (Qeq_eqR _ _ (wcost_app PM 0 _ _)), Q2R_plus.
  unfold las_c, las_x, las_a; rewrite (proj2 (Nat.ltb_lt _ _)) by lia; simpl wcost.
  rewrite Q2R_plus; rewrite Q2R_0; ring.
Qed.

(** The lasso's cost after the prefix and [m] turns of the cycle. *)
Lemma las_partial m :
  partial (las_c p x c) (length p + m * length c) =
  Q2R (wcost PM 0 p) + INR m * Q2R (wcost PM x c).
Proof.
  rewrite partial_add, las_partial_prefix, firstn_all by lia.
  rewrite (partial_ext (fun k => las_c p x c (length p + k)%nat) (cyc_c x c)).
  - rewrite <- (Nat.add_0_r (m * length c)), partial_periodic by (apply cyc_periodic; auto).
    rewrite cyc_partial_period by auto; simpl; ring.
  - intros k; unfold las_c, las_x, las_a; rewrite (proj2 (Nat.ltb_ge _ _)) by lia.
    replace (length p + k - length p)%nat with k by lia; reflexivity.
Qed.
(** The average of a lasso is its cycle's mean. *)
Lemma las_average : average (las_c p x c) (Q2R (wcost PM x c) / INR (length c)).
Proof.
  apply (average_shift _ (cyc_c x c) (length p)); [|apply cyc_average; auto].
  intros k; unfold las_c, las_x, las_a; rewrite (proj2 (Nat.ltb_ge _ _)) by lia.
  replace (length p + k - length p)%nat with k by lia; reflexivity.
Qed.
End Lasso.

End Corrected.


(** A lower bound [a N - K] on the partial sums: the running means are eventually above
    [a - eps]. *)
Lemma mean_lower (c : sequence) a K :
  0 <= K -> (forall N, a * INR N - K <= partial c N) ->
  forall eps, 0 < eps ->
    exists N0, forall N, (N0 <= N)%nat -> a - eps <= partial c (S N) / INR (S N).
Proof.
  intros HK H eps Heps.
  destruct (nat_above (K / eps)) as (N0 & HN0); exists N0; intros N HN.
  assert (HSN : 0 < INR (S N)) by (apply lt_0_INR; lia).
  assert (HN0' : INR N0 <= INR (S N)) by (apply le_INR; lia).
  assert (HKe : K <= eps * INR (S N)).
  { assert (K / eps <= INR (S N)) by lra.
    apply (Rmult_le_compat_l eps) in H0; [|lra].
    replace (eps * (K / eps)) with K in H0 by (field; lra); lra. }
  specialize (H (S N)).
  apply (Rmult_le_reg_r (INR (S N))); [auto|].
  unfold Rdiv; rewrite Rmult_assoc, Rinv_l by lra; nra.
Qed.

(** C4-corrected, sufficiency, for every finite deterministic problem (the paper's
    Proposition 4 as corrected; the claims registry's [c4::CORRECTED]): if the bonus [M] lies
    in the corrected interval, then [pi*] -- the stationary policy that follows an optimal
    simple single-shot path [u*] ([S* = |u*| + 1] states, cost [L* = G*(x1)]) and resets --
    is average-cost optimal against every run of the average-cost problem (every policy,
    stationary or not). Costs and [M] are rational. *)
Theorem c4_corrected_sufficient P ustar Lstar M :
  wf P -> Gstar P 0 = Some Lstar -> simple_goal_path P ustar -> (wcost P 0 ustar == Lstar)%Q ->
  corrected_interval P (S_of ustar) (Q2R Lstar) (Q2R M) ->
  average_optimal P (Q2R M) (cyc_x P M 0 (ustar ++ [0%nat])) (cyc_c P M 0 (ustar ++ [0%nat])).
Proof.
  intros HP HG Hu HL Hint.
  destruct (goal_path_cycle P M ustar Hu) as (Hne & Hv & He & Hc & Hl).
  set (sn := S (length ustar)).
  assert (Hsn : (0 < sn)%nat) by (unfold sn; lia).
  set (g := ((Lstar + M) / inject_Z (Z.of_nat sn))%Q).
  assert (Hsn0 : ~ (inject_Z (Z.of_nat sn) == 0)%Q).
  { intros E; apply Qeq_eqR in E; rewrite Q2R_nat in E.
    rewrite Q2R_0 in E.
    pose proof (lt_0_INR sn Hsn); lra. }
  assert (Hg : Q2R g = (Q2R Lstar + Q2R M) / INR sn).
  { unfold g; rewrite Q2R_div, Q2R_plus, Q2R_nat by auto; reflexivity. }
  set (D := Qmax2 0 (g - Qmin2 0 M)).
  assert (HD0 : (0 <= D)%Q) by apply Qmax2_l.
  assert (HD : forall x i, (x < nstates P)%nat -> (i < length (moves (reset_problem P M) x))%nat ->
                 (- D <= cost (reset_problem P M) x (Move i) - g)%Q).
  { intros x i Hx Hi; pose proof (PM_move_cost_ge P HP M x i Hx Hi).
    pose proof (Qmax2_r 0 (g - Qmin2 0 M)); fold D in H0; Lqa.lra. }
  assert (HC := cycles_above P HP M g sn Lstar HG Hsn Hg Hint).
  split; [apply cyc_run; auto|].
  exists (Q2R g); split.
  - rewrite Hg; pose proof (cyc_average P M 0 (ustar ++ [0%nat]) Hne Hv He) as Havg.
    rewrite Hc, Hl, (Qeq_eqR _ _ HL) in Havg; exact Havg.
  - intros x' c' Hrun eps Heps.
    apply (mean_lower c' (Q2R g) (Q2R (inject_Z (Z.of_nat (nstates P)) * D))); auto.
    + rewrite Q2R_mult, Q2R_nat; apply Rmult_le_pos; [apply pos_INR|].
      apply Qle_Rle in HD0; rewrite Q2R_0 in HD0; auto.
    + apply (run_lower P HP M g D HD x' c' HD0 HC Hrun).
Qed.

(** An average-cost optimal value [v] is at most the long-run mean [W / l] of every run whose
    cost after [K + m l] stages is [C + m W]. *)
Lemma opt_le_periodic (v : R) (c : sequence) K l C W :
  (forall eps, 0 < eps ->
     exists N0, forall N, (N0 <= N)%nat -> v - eps <= partial c (S N) / INR (S N)) ->
  (0 < l)%nat -> (forall m, partial c (K + m * l) = C + INR m * W) -> v <= W / INR l.
Proof.
  intros Hopt Hl Hc; apply Rnot_lt_le; intros Hlt.
  assert (HlR : 0 < INR l) by (apply lt_0_INR; auto).
  set (a := W / INR l) in *.
  assert (Ha : a * INR l = W) by (unfold a; field; lra).
  set (eps := (v - a) / 2).
  assert (Heps : 0 < eps) by (unfold eps; lra).
  destruct (Hopt eps Heps) as (N0 & HN0).
  set (B := Rabs (C - a * INR K - eps * INR K) / (eps * INR l)).
  assert (HB : 0 <= B).
  { unfold B, Rdiv; apply Rmult_le_pos; [apply Rabs_pos|].
    left; apply Rinv_0_lt_compat, Rmult_lt_0_compat; auto. }
  destruct (nat_above (B + INR N0)) as (m & Hm).
  assert (HmN0 : (N0 < m)%nat) by (apply INR_lt; lra).
  assert (Hml : (m <= m * l)%nat) by (destruct l; [lia|nia]).
  specialize (HN0 (K + m * l - 1)%nat ltac:(lia)).
  replace (S (K + m * l - 1)) with (K + m * l)%nat in HN0 by lia.
  rewrite Hc, plus_INR, mult_INR in HN0.
  assert (HmR : B < INR m) by (pose proof (pos_INR N0); lra).
  assert (Hden : 0 < INR K + INR m * INR l).
  { pose proof (pos_INR K); assert (1 <= INR m * INR l).
    { rewrite <- mult_INR; apply (le_INR 1); lia. } lra. }
  assert (Hkey : C - a * INR K - eps * INR K < INR m * (eps * INR l)).
  { assert (Rabs (C - a * INR K - eps * INR K) < INR m * (eps * INR l)).
    { unfold B in HmR; apply (Rmult_lt_compat_r (eps * INR l)) in HmR;
        [|apply Rmult_lt_0_compat; auto].
      unfold Rdiv in HmR; rewrite Rmult_assoc, Rinv_l in HmR
        by (apply Rgt_not_eq, Rmult_lt_0_compat; auto).
      lra. }
    pose proof (Rle_abs (C - a * INR K - eps * INR K)); lra. }
  assert (Hlt' : (C + INR m * W) / (INR K + INR m * INR l) < v - eps).
  { apply (Rmult_lt_reg_r (INR K + INR m * INR l)); [auto|].
    unfold Rdiv; rewrite Rmult_assoc, Rinv_l by lra.
    replace (v - eps) with (a + eps) by (unfold eps; field).
    rewrite <- Ha; nra. }
  lra.
Qed.

Lemma T_algebra_conv S s Lu Ls m :
  0 < S -> 0 < s -> (Ls + m) / S <= (Lu + m) / s ->
  (s < S -> (S * Lu - s * Ls) / (s - S) <= m) /\ (S < s -> m <= (S * Lu - s * Ls) / (s - S)).
Proof.
  intros HS Hs H.
  assert (H' : s * (Ls + m) <= S * (Lu + m)).
  { apply (Rmult_le_compat_l (S * s)) in H; [|nra].
    replace (S * s * ((Ls + m) / S)) with (s * (Ls + m)) in H by (field; lra).
    replace (S * s * ((Lu + m) / s)) with (S * (Lu + m)) in H by (field; lra); auto. }
  split; intros Hc; set (t := (S * Lu - s * Ls) / (s - S));
    assert (Ht : t * (s - S) = S * Lu - s * Ls) by (unfold t; field; lra); nra.
Qed.

Lemma cycle_algebra_conv S W l Ls m :
  0 < S -> (Ls + m) / S <= W / l -> m <= S * (W / l) - Ls.
Proof.
  intros HS H; apply (Rmult_le_compat_l S) in H; [|lra].
  replace (S * ((Ls + m) / S)) with (Ls + m) in H by (field; lra); lra.
Qed.

Lemma in_removelast_trace P x w z : In z (removelast (trace P x w)) -> In z (trace P x w).
Proof.
  destruct (trace_last P x w) as (l & El); rewrite El, removelast_last.
  intros H; apply in_or_app; auto.
Qed.

(** C4-corrected, necessity: if [pi*] is average-cost optimal (against every run), then [M]
    lies in the corrected interval: every simple goal path's reset cycle and every lasso onto
    a goal-avoiding simple cycle is a run, with mean [(L(u) + M)/S(u)], resp. [Lav(C)]. *)
Theorem c4_corrected_necessary P ustar Lstar M :
  wf P -> Gstar P 0 = Some Lstar -> simple_goal_path P ustar -> (wcost P 0 ustar == Lstar)%Q ->
  average_optimal P (Q2R M) (cyc_x P M 0 (ustar ++ [0%nat])) (cyc_c P M 0 (ustar ++ [0%nat])) ->
  corrected_interval P (S_of ustar) (Q2R Lstar) (Q2R M).
Proof.
  intros HP HG Hu HL (_ & v & Hv & Hall).
  destruct (goal_path_cycle P M ustar Hu) as (Hne & Hvc & He & Hc & Hl).
  assert (Hv' := cyc_average P M 0 (ustar ++ [0%nat]) Hne Hvc He).
  rewrite Hc, Hl, (Qeq_eqR _ _ HL) in Hv'.
  assert (Ev : v = (Q2R Lstar + Q2R M) / INR (S (length ustar)))
    by (apply (limit_of_single_valued _ _ _ _ Hv Hv')).
  assert (HS : 0 < S_of ustar) by (apply lt_0_INR; lia).
  (* every simple goal path u: its reset cycle *)
  assert (Hpath : forall u, simple_goal_path P u ->
            (Q2R Lstar + Q2R M) / S_of ustar <= (L_of P u + Q2R M) / S_of u).
  { intros u Hsu.
    destruct (goal_path_cycle P M u Hsu) as (Hne' & Hv2 & He2 & Hc2 & Hl2).
    replace ((Q2R Lstar + Q2R M) / S_of ustar) with v by (rewrite Ev; reflexivity).
    unfold S_of; rewrite <- Hl2; unfold L_of; rewrite <- Hc2.
    apply (opt_le_periodic v (cyc_c P M 0 (u ++ [0%nat])) 0 (length (u ++ [0%nat])) 0).
    - intros eps Heps; apply (Hall _ _ (cyc_run P M _ Hne' Hv2 He2) eps Heps).
    - rewrite Hl2; lia.
    - intros m; rewrite <- (Nat.add_0_r (m * length (u ++ [0%nat]))), Nat.add_0_l.
      rewrite partial_periodic by (apply cyc_periodic; auto).
      rewrite cyc_partial_period by auto; simpl partial; ring. }
  split; [|split].
  - intros u Hsu Hlt; pose proof (lt_0_INR _ (Nat.lt_0_succ (length u))) as Hs.
    apply (proj1 (T_algebra_conv _ _ _ _ _ HS Hs (Hpath u Hsu))); auto.
  - intros u Hsu Hlt; pose proof (lt_0_INR _ (Nat.lt_0_succ (length u))) as Hs.
    apply (proj2 (T_algebra_conv _ _ _ _ _ HS Hs (Hpath u Hsu))); auto.
  - intros x c (Hne' & HvP & HeP & Hnd & Hng & p & Hp & Ep & Hgp).
    destruct (P_walk_PM P M 0 p (fun H => Hgp (in_removelast_trace _ _ _ _ H)) Hp)
      as (Hp' & Ep' & _).
    destruct (P_walk_PM P M x c (fun H => Hng (in_removelast_trace _ _ _ _ H)) HvP)
      as (Hc' & Ec' & Wc').
    apply cycle_algebra_conv; auto.
    replace ((Q2R Lstar + Q2R M) / S_of ustar) with v by (rewrite Ev; reflexivity).
    unfold mean_of; rewrite <- Wc'.
    apply (opt_le_periodic v (las_c P M p x c) (length p) (length c)
             (Q2R (wcost (reset_problem P M) 0 p))).
    + intros eps Heps.
      assert (Hrun := las_run P M p x c Hp' ltac:(congruence) Hne' Hc' ltac:(congruence)).
      apply (Hall _ _ Hrun eps Heps).
    + destruct c; [congruence|simpl; lia].
    + intros m; apply las_partial; auto; congruence.
Qed.

(** C4-corrected for every finite deterministic problem whose goal is reachable from [x1]
    (the paper's Proposition 4, corrected; docs/spec.md §6 C4; the claims registry's [c4::CORRECTED]):
    let [u*] be an optimal single-shot path (a simple goal path from [x1] of cost
    [L* = G*(x1)], [S* = |u*| + 1] states; one exists whenever the goal is reachable,
    [Gstar_attained] and [short_walk]), and [pi*] the policy that follows it and resets. Then
    [pi*] is average-cost optimal -- against every run of the average-cost problem, i.e. every
    policy, history-dependent or not -- iff
    [max{T(u) : S(u) < S*} <= M <= min{ min{T(u) : S(u) > S*}, S* Lav(C^) - L* }], with [u]
    over the simple goal paths from [x1] and [C^] over the simple cycles reachable from [x1]
    avoiding the goal ([corrected_interval]). Costs and [M] are rational. The model's bonus is
    [M < 0] (the registry's "and M < 0"); the equivalence holds for every [M]. *)
Theorem c4_corrected P ustar Lstar M :
  wf P -> Gstar P 0 = Some Lstar -> simple_goal_path P ustar -> (wcost P 0 ustar == Lstar)%Q ->
  average_optimal P (Q2R M) (cyc_x P M 0 (ustar ++ [0%nat])) (cyc_c P M 0 (ustar ++ [0%nat])) <->
  corrected_interval P (S_of ustar) (Q2R Lstar) (Q2R M).
Proof.
  intros HP HG Hu HL; split.
  - apply c4_corrected_necessary; auto.
  - apply c4_corrected_sufficient; auto.
Qed.

(** An optimal single-shot path exists whenever the goal is reachable from [x1]: an optimal
    goal-reaching walk with every cycle cut out (cycles cost [>= 0]) is simple and still
    optimal. So [c4_corrected] applies to every finite problem whose goal is reachable. *)
Lemma simple_walk P x w :
  wf P -> (x < nstates P)%nat -> wvalid P x w ->
  exists w', wvalid P x w' /\ wend P x w' = wend P x w /\ (wcost P x w' <= wcost P x w)%Q /\
             NoDup (trace P x w').
Proof.
  intros HP Hx; remember (length w) as m eqn:Hm; revert w Hm.
  induction m as [m IH] using (well_founded_induction lt_wf); intros w Hm Hw.
  destruct (ListDec.NoDup_dec Nat.eq_dec (trace P x w)) as [Hnd|Hnd].
  - exists w; repeat split; auto; apply Qle_refl.
  - destruct (repeat_split P x w Hnd) as (w1 & w2 & w3 & -> & Hne & E).
    rewrite wend_app in E.
    apply wvalid_app in Hw as [Hw1 Hw23]; apply wvalid_app in Hw23 as [Hw2 Hw3].
    assert (Hv13 : wvalid P x (w1 ++ w3)) by (apply wvalid_app; split; auto; rewrite E; auto).
    destruct (IH (length (w1 ++ w3))) with (w := w1 ++ w3) as (w' & Hv' & He' & Hc' & Hnd');
      auto; [subst m; rewrite !app_length; destruct w2; [congruence|simpl; lia]|].
    exists w'; repeat split; auto.
    + rewrite He', !wend_app, <- E; reflexivity.
    + assert (C1 := wcost_app P x w1 (w2 ++ w3)).
      assert (C2 := wcost_app P (wend P x w1) w2 w3).
      assert (C3 := wcost_app P x w1 w3).
      rewrite <- E in C2.
      pose proof (wcost_nonneg P HP _ w2 (wend_lt P HP _ _ Hx Hw1) Hw2); Lqa.lra.
Qed.

Lemma pistar_exists P :
  wf P -> (exists w, reaches P 0 w) ->
  exists ustar Lstar, Gstar P 0 = Some Lstar /\ simple_goal_path P ustar /\
                      (wcost P 0 ustar == Lstar)%Q.
Proof.
  intros HP (w & Hw).
  assert (H0 : (0 < nstates P)%nat) by (destruct HP; lia).
  destruct (Gstar_least P HP 0 w H0 Hw) as (g & Eg & _).
  destruct (Gstar_attained P HP 0 g H0 Eg) as (w0 & [Hv0 He0] & Hc0).
  destruct (simple_walk P 0 w0 HP H0 Hv0) as (u & Hu & Eu & Cu & Nu).
  assert (Hr : reaches P 0 u) by (split; congruence).
  destruct (Gstar_least P HP 0 u H0 Hr) as (g' & Eg' & Hg').
  rewrite Eg in Eg'; inversion Eg'; subst g'.
  exists u, g; repeat split; auto; try congruence; Lqa.lra.
Qed.
