(** * C3 for every finite problem: truecost's certificate

    Cost 1 on a goal-avoiding lasso from [x1], [K > 1/(1-alpha)] on every other move
    ([c3_certificate]); the engine's [K] ([c3_certificate_engine]); the registry's hypothesis
    gives such a lasso ([c3_from_policy]). [C3.v] states the main theorem [c3_registry]. *)

From Coq Require Import Reals Lra Lia QArith Qround Qreals List.
From Truecost Require Import Model Paths C1 C2 QReal C3Policies.
Import ListNotations.

Open Scope R_scope.

(** ** C3 for every finite problem: the certificate *)

(** The certificate's stage costs: cost 1 on the marked move of a marked state, [K] on every
    other move ([mark x = Some i]: the move [i] of [x] is marked). *)
Definition cert_cost (mark : nat -> option nat) (K : Q) (x i : nat) : Q :=
  match mark x with Some j => if Nat.eqb i j then 1%Q else K | None => K end.

Fixpoint recost (f : nat -> Q) (i : nat) (l : list (nat * Q)) : list (nat * Q) :=
  match l with [] => [] | (y, _) :: t => (y, f i) :: recost f (S i) t end.

(** The certificate problem: [P]'s states, goal and successors, the certificate's costs. *)
Definition certificate (P : problem) (mark : nat -> option nat) (K : Q) : problem := {|
  nstates := nstates P;
  goal := goal P;
  moves := fun x => recost (cert_cost mark K x) 0 (moves P x)
|}.

Lemma recost_length f i l : length (recost f i l) = length l.
Proof. revert i; induction l as [|[y c] l IH]; intros i; simpl; auto. Qed.

Lemma recost_nth f i l j d :
  (j < length l)%nat -> nth j (recost f i l) d = (fst (nth j l d), f (i + j)%nat).
Proof.
  revert i j; induction l as [|[y c] l IH]; intros i j Hj; simpl in Hj; [lia|].
  destruct j as [|j]; simpl; [rewrite Nat.add_0_r; auto|].
  rewrite IH by lia; f_equal; f_equal; lia.
Qed.

Lemma cert_actions P mark K x : actions (certificate P mark K) x = actions P x.
Proof. unfold actions; simpl; rewrite recost_length; reflexivity. Qed.

Lemma cert_target P mark K x i :
  (i < length (moves P x))%nat -> target (certificate P mark K) x (Move i) = target P x (Move i).
Proof. intros Hi; unfold target; simpl; rewrite recost_nth by auto; reflexivity. Qed.

Lemma cert_move_cost P mark K x i :
  (i < length (moves P x))%nat -> cost (certificate P mark K) x (Move i) = cert_cost mark K x i.
Proof. intros Hi; unfold cost; simpl; rewrite recost_nth by auto; reflexivity. Qed.

(** The certificate's costs are strictly positive on every move when [K > 0] (termination
    costs 0). *)
Lemma cert_positive P mark K x i :
  (0 < K)%Q -> (i < length (moves P x))%nat -> (0 < cost (certificate P mark K) x (Move i))%Q.
Proof.
  intros HK Hi; rewrite cert_move_cost by auto; unfold cert_cost.
  destruct (mark x) as [j|]; [destruct (Nat.eqb i j)|]; auto; reflexivity.
Qed.

(** The marked walk from [x1 = 0]: follow the marked move of each state. *)
Fixpoint marked_walk (P : problem) (mark : nat -> option nat) (k : nat) : nat :=
  match k with
  | O => 0%nat
  | S k' => let y := marked_walk P mark k' in
            match mark y with Some i => target P y (Move i) | None => y end
  end.

(** The certificate's hypothesis: the marked walk from [x1] never stops and never visits the
    goal (a goal-avoiding lasso from [x1]: some policy's path enters a cycle avoiding the
    goal). *)
Definition marks_avoid_goal (P : problem) (mark : nat -> option nat) : Prop :=
  forall k, marked_walk P mark k <> goal P /\
    exists i, mark (marked_walk P mark k) = Some i /\
              (i < length (moves P (marked_walk P mark k)))%nat.

Section Certificate.
Variables (P : problem) (mark : nat -> option nat) (K : Q) (alpha : R).
Hypothesis Hmark : marks_avoid_goal P mark.
Hypothesis Ha : 0 < alpha < 1.
Hypothesis HK : / (1 - alpha) < Q2R K.
Notation C := (certificate P mark K).

Lemma K_pos : (0 < K)%Q.
Proof.
  apply Rlt_Qlt; rewrite Q2R_0.
  assert (0 < / (1 - alpha)) by (apply Rinv_0_lt_compat; lra); lra.
Qed.

Lemma cert_cost_nonneg x a : In a (actions C x) -> 0 <= Q2R (cost C x a).
Proof.
  intros Ha'; apply in_actions in Ha' as [[-> _]|(i & -> & Hi)].
  - unfold cost, Q2R; simpl; lra.
  - simpl in Hi; rewrite recost_length in Hi.
    pose proof (cert_positive P mark K x i K_pos Hi) as H.
    apply Qlt_Rlt in H; rewrite Q2R_0 in H; lra.
Qed.

(** [r] follows the marks at stage [k]. *)
Definition follows (x : nat -> nat) (a : nat -> action) (k : nat) : Prop :=
  exists i, mark (x k) = Some i /\ a k = Move i.

Lemma follows_dec x a k : follows x a k \/ ~ follows x a k.
Proof.
  unfold follows; destruct (mark (x k)) as [i|].
  - destruct (action_eq_dec (a k) (Move i)) as [E|E]; [left; eauto|].
    right; intros (j & Ej & Ej'); inversion Ej; subst; auto.
  - right; intros (j & Ej & _); discriminate.
Qed.

Lemma first_deviation x a N :
  (forall k, (k < N)%nat -> follows x a k) \/
  exists j, (j < N)%nat /\ ~ follows x a j /\ forall k, (k < j)%nat -> follows x a k.
Proof.
  induction N as [|N IH]; [left; intros; lia|].
  destruct IH as [Hall|(j & Hj & Hn & Hb)]; [|right; exists j; repeat split; auto; lia].
  destruct (follows_dec x a N) as [Hf|Hf].
  - left; intros k Hk; destruct (Nat.eq_dec k N) as [->|]; [auto | apply Hall; lia].
  - right; exists N; repeat split; auto.
Qed.

(** Up to its first deviation, a trajectory is the marked walk and pays 1 per stage. *)
Lemma follow_prefix x a j :
  trajectory C x a -> (forall k, (k < j)%nat -> follows x a k) ->
  (forall k, (k <= j)%nat -> x k = marked_walk P mark k) /\
  (forall k, (k < j)%nat -> Q2R (cost C (x k) (a k)) = 1).
Proof.
  intros [H0 Hs] Hf.
  assert (Hx : forall k, (k <= j)%nat -> x k = marked_walk P mark k).
  { induction k as [|k IH]; intros Hk; [auto|].
    destruct (Hf k ltac:(lia)) as (i & Ei & Ea).
    destruct (Hs k) as [Hin E]; rewrite E, Ea; simpl; rewrite <- (IH ltac:(lia)), Ei.
    apply in_actions in Hin as [[? _]|(i' & Ei' & Hi)]; [congruence|].
    rewrite Ea in Ei'; inversion Ei'; subst i'.
    simpl in Hi; rewrite recost_length in Hi; apply cert_target; auto. }
  split; auto; intros k Hk.
  destruct (Hf k Hk) as (i & Ei & Ea); destruct (Hs k) as [Hin _].
  rewrite Ea in Hin |- *; apply in_actions in Hin as [[? _]|(i' & Ei' & Hi)]; [discriminate|].
  inversion Ei'; subst i'; simpl in Hi; rewrite recost_length in Hi.
  rewrite cert_move_cost by auto; unfold cert_cost; rewrite Ei, Nat.eqb_refl.
  unfold Q2R; simpl; lra.
Qed.

Lemma geom_partial j : partial (fun k => alpha ^ k * 1) j * (1 - alpha) = 1 - alpha ^ j.
Proof.
  induction j as [|j IH]; simpl partial; simpl pow; [ring|].
  rewrite Rmult_plus_distr_r, IH; ring.
Qed.

(** A trajectory that deviates from the marks costs more than [1/(1-alpha)]. *)
Lemma deviation_costs_more x a v :
  trajectory C x a -> (exists k, ~ follows x a k) ->
  discounted alpha (traj_stages C (x, a)) v -> / (1 - alpha) < v.
Proof.
  intros Hr (k0 & Hk0) Hv.
  destruct (first_deviation x a (S k0)) as [Hall|(j & _ & Hn & Hb)];
    [exfalso; apply Hk0, Hall; lia|].
  destruct (follow_prefix x a j Hr Hb) as [Hx Hc].
  destruct Hr as [H0 Hs].
  assert (HKj : Q2R (cost C (x j) (a j)) = Q2R K).
  { destruct (Hmark j) as [Hng (i & Ei & Hi)]; rewrite <- (Hx j) in Hng, Ei, Hi by lia.
    destruct (Hs j) as [Hin _]; apply in_actions in Hin as [[_ E]|(i' & Ea & Hi')];
      [simpl in E; congruence|].
    simpl in Hi'; rewrite recost_length in Hi'.
    rewrite Ea, cert_move_cost by auto; unfold cert_cost; rewrite Ei.
    destruct (Nat.eqb_spec i' i) as [->|]; [|reflexivity].
    exfalso; apply Hn; exists i; auto. }
  assert (Hp : partial (fun k => alpha ^ k * traj_stages C (x, a) k) (S j)
               = partial (fun k => alpha ^ k * 1) j + alpha ^ j * Q2R K).
  { rewrite partial_S; unfold traj_stages at 2; simpl fst; simpl snd; rewrite HKj; f_equal.
    apply partial_ext_lt; intros k Hk; unfold traj_stages; simpl; rewrite Hc; auto. }
  assert (Hge : partial (fun k => alpha ^ k * traj_stages C (x, a) k) (S j) <= v).
  { apply total_ge_partial; [exact Hv|]; intros k; apply Rmult_le_pos; [apply pow_le; lra|].
    apply cert_cost_nonneg, Hs. }
  pose proof (geom_partial j) as Hg.
  assert (Haj : 0 < alpha ^ j) by (apply pow_lt; lra).
  assert (Hinv : / (1 - alpha) * (1 - alpha) = 1) by (apply Rinv_l; lra).
  assert (alpha ^ j * / (1 - alpha) < alpha ^ j * Q2R K) by (apply Rmult_lt_compat_l; auto).
  assert (E : / (1 - alpha) = partial (fun k => alpha ^ k * 1) j + alpha ^ j * / (1 - alpha)).
  { apply (Rmult_eq_reg_r (1 - alpha)); [|lra].
    rewrite Rmult_plus_distr_r, Hg, Rmult_assoc, Hinv; ring. }
  lra.
Qed.

(** The marked walk as a trajectory. *)
Definition marked_actions (k : nat) : action :=
  match mark (marked_walk P mark k) with Some i => Move i | None => Term end.

Lemma marked_trajectory : trajectory C (marked_walk P mark) marked_actions.
Proof.
  split; [reflexivity|]; intros k.
  destruct (Hmark k) as [_ (i & Ei & Hi)]; unfold marked_actions; rewrite Ei; split.
  - rewrite cert_actions; apply in_actions; right; eauto.
  - simpl; rewrite Ei, cert_target; auto.
Qed.

Lemma marked_value :
  discounted alpha (traj_stages C (marked_walk P mark, marked_actions)) (/ (1 - alpha)).
Proof.
  apply (total_extensional (fun k => alpha ^ k * 1)); [|apply discounted_const; lra].
  intros k; f_equal; symmetry.
  destruct (follow_prefix _ _ (S k) marked_trajectory) as [_ Hc].
  - intros k' _; destruct (Hmark k') as [_ (i & Ei & _)]; exists i.
    unfold marked_actions; rewrite Ei; auto.
  - apply Hc; lia.
Qed.

(** C3 with truecost's certificate (the paper's discounting proposition; docs/spec.md §6 C3; the
    claims registry's C3 statement: "if a goal-reaching policy exists and some policy reaches a
    cycle avoiding the goal, then there are stage costs l and a discount factor alpha for which
    a discount-optimal policy has infinite true cost"). For every problem [P], every marking
    whose walk from [x1] avoids the goal forever ([marks_avoid_goal]: a goal-avoiding lasso
    from [x1]), every real [alpha] in [(0,1)] and every [K > 1/(1-alpha)]: in the certificate
    problem (cost 1 on the marked moves, [K] on every other move, all strictly positive;
    termination 0) a discount-optimal policy exists, and EVERY discount-optimal policy --
    among all policies, history-dependent or not -- follows the marked walk forever: it never
    visits the goal, pays 1 at every stage, and its true cost is infinite. The hypothesis that
    a goal-reaching policy exists is not needed. *)
Theorem c3_certificate :
  (exists r, traj_optimal C alpha r) /\
  forall r, traj_optimal C alpha r ->
    (forall k, fst r k = marked_walk P mark k /\ fst r k <> goal P /\ traj_stages C r k = 1) /\
    (forall B, exists N, B < partial (traj_stages C r) N).
Proof.
  (* A trajectory that follows the marks at every stage is the marked walk, paying 1. *)
  assert (Hfollow : forall x a, trajectory C x a -> (forall k, follows x a k) ->
            forall k, x k = marked_walk P mark k /\ traj_stages C (x, a) k = 1).
  { intros x a Hr Hall k.
    destruct (follow_prefix x a (S k) Hr (fun k' _ => Hall k')) as [Hx Hc].
    split; [apply Hx; lia | apply Hc; lia]. }
  (* Every trajectory's discounted cost is at least [1/(1-alpha)]. *)
  assert (Hlow : forall x a w, trajectory C x a ->
                   discounted alpha (traj_stages C (x, a)) w -> / (1 - alpha) <= w).
  { intros x a w Hr Hw; apply Rnot_lt_le; intros Hlt.
    assert (Hall : forall k, follows x a k).
    { intros k; destruct (follows_dec x a k) as [|Hn]; [auto|].
      pose proof (deviation_costs_more x a w Hr (ex_intro _ k Hn) Hw); lra. }
    assert (Hw' : discounted alpha (traj_stages C (x, a)) (/ (1 - alpha))).
    { apply (total_extensional (fun k => alpha ^ k * 1)); [|apply discounted_const; lra].
      intros k; rewrite (proj2 (Hfollow x a Hr Hall k)); auto. }
    pose proof (discounted_single_valued _ _ _ _ Hw Hw'); lra. }
  split.
  - exists (marked_walk P mark, marked_actions); split; [apply marked_trajectory|].
    exists (/ (1 - alpha)); split; [apply marked_value|].
    intros [x a] w Hr Hw; apply (Hlow x a w Hr Hw).
  - intros [x a] (Hr & v & Hv & Hmin); simpl fst in *; simpl snd in *.
    pose proof (Hmin (marked_walk P mark, marked_actions) _ marked_trajectory marked_value) as Hle.
    assert (Hall : forall k, follows x a k).
    { intros k; destruct (follows_dec x a k) as [|Hn]; [auto|].
      pose proof (deviation_costs_more x a v Hr (ex_intro _ k Hn) Hv); lra. }
    assert (Hk : forall k, x k = marked_walk P mark k /\ traj_stages C (x, a) k = 1)
      by (apply Hfollow; auto).
    split.
    + intros k; destruct (Hk k) as [E1 E2]; repeat split; auto.
      rewrite E1; apply (Hmark k).
    + intros B; destruct (nat_above B) as (N & HN); exists N.
      assert (E : forall N, partial (traj_stages C (x, a)) N = INR N).
      { induction N0 as [|N0 IH]; [reflexivity|].
        rewrite partial_S, IH, (proj2 (Hk N0)), S_INR; reflexivity. }
      rewrite E; auto.
Qed.

End Certificate.

(** ** The certificate's [K], as truecost's C3 engine computes it *)

Fixpoint qpow (q : Q) (m : nat) : Q := match m with O => 1%Q | S m' => (q * qpow q m')%Q end.

Lemma qpow_R q m : Q2R (qpow q m) = Q2R q ^ m.
Proof.
  induction m as [|m IH]; simpl; [unfold Q2R; simpl; lra|].
  rewrite Q2R_mult, IH; reflexivity.
Qed.

(** The construction's bound [1/((1-alpha) alpha^(n-2))] and [K = floor(bound) + 1] for [n]
    states (the kernel's [claims::c3::certificate]; [n - 2] saturates at 0). *)
Definition cert_bound (alpha : Q) (n : nat) : Q := (1 / ((1 - alpha) * qpow alpha (n - 2)))%Q.
Definition cert_K (alpha : Q) (n : nat) : Q := inject_Z (Qfloor (cert_bound alpha n) + 1).

(** The certificate's [K], built for a rational [alpha0] in [(0,1)], exceeds [1/(1-alpha)] for
    every real [alpha] in [(0, alpha0]]. *)
Lemma cert_K_large alpha0 n alpha :
  (0 < alpha0 < 1)%Q -> 0 < alpha <= Q2R alpha0 -> / (1 - alpha) < Q2R (cert_K alpha0 n).
Proof.
  intros [H0 H1] Ha.
  apply Qlt_Rlt in H0; apply Qlt_Rlt in H1.
  rewrite Q2R_0 in H0.
  rewrite Q2R_1 in H1.
  set (a := Q2R alpha0) in *.
  assert (Hfl := Qlt_floor (cert_bound alpha0 n)); apply Qlt_Rlt in Hfl.
  unfold cert_K.
  assert (Hpow : 0 < a ^ (n - 2) <= 1).
  { split; [apply pow_lt; lra|].
    induction (n - 2)%nat as [|m IH]; simpl; [lra|].
    assert (0 <= a ^ m) by (apply pow_le; lra); nra. }
  assert (Hne : ~ ((1 - alpha0) * qpow alpha0 (n - 2) == 0)%Q).
  { intros E; apply Qeq_eqR in E; rewrite Q2R_mult, Q2R_minus, qpow_R in E.
    rewrite Q2R_0 in E.
    rewrite Q2R_1 in E.
    fold a in E; nra. }
  unfold cert_bound in Hfl; rewrite Q2R_div, Q2R_mult, Q2R_minus, qpow_R in Hfl by auto.
  rewrite Q2R_1 in Hfl; fold a in Hfl.
  apply Rle_lt_trans with (1 / ((1 - a) * a ^ (n - 2))); [|exact Hfl].
  unfold Rdiv; rewrite Rmult_1_l.
  apply Rinv_le_contravar; [apply Rmult_lt_0_compat; lra|].
  assert ((1 - a) * a ^ (n - 2) <= 1 - a) by nra; lra.
Qed.

(** C3 with exactly the certificate truecost's C3 engine builds for [alpha0] and a problem with
    [n] states: cost 1 on a goal-avoiding lasso from [x1], [K = floor(1/((1-alpha0)
    alpha0^(n-2))) + 1] on every other move. It works for every real discount factor [alpha]
    in [(0, alpha0]] (in particular [alpha = alpha0]): every discount-optimal policy follows
    the lasso, never reaches the goal, and has infinite true cost. *)
Definition engine_certificate P mark alpha0 n := certificate P mark (cert_K alpha0 n).

Corollary c3_certificate_engine P mark alpha0 n alpha
  (C := engine_certificate P mark alpha0 n) :
  marks_avoid_goal P mark -> (0 < alpha0 < 1)%Q -> 0 < alpha <= Q2R alpha0 ->
  (forall x i, (i < length (moves P x))%nat -> (0 < cost C x (Move i))%Q) /\
  (exists r, traj_optimal C alpha r) /\
  forall r, traj_optimal C alpha r ->
    (forall k, fst r k = marked_walk P mark k /\ fst r k <> goal P /\ traj_stages C r k = 1) /\
    (forall B, exists N, B < partial (traj_stages C r) N).
Proof.
  intros Hm Ha0 Ha; unfold C, engine_certificate.
  assert (HK : / (1 - alpha) < Q2R (cert_K alpha0 n)) by (apply cert_K_large; auto).
  assert (Ha1 : 0 < alpha < 1).
  { destruct Ha0 as [_ H1]; apply Qlt_Rlt in H1.
    rewrite Q2R_1 in H1; lra. }
  split; [|apply c3_certificate; auto].
  intros x i Hi; apply cert_positive; auto.
  eapply K_pos; eauto.
Qed.

(** ** From the registry's hypothesis to a marking *)

(** [pi] picks an action of the state at every stage of its path from [x1] (admissible along
    its path; states off the path, dead ends included, are unconstrained). *)
Definition valid_on_path (P : problem) (pi : spolicy) : Prop :=
  forall k, In (pi (state_at P pi 0 k)) (actions P (state_at P pi 0 k)).

Lemma valid_on_path_lt P pi :
  wf P -> valid_on_path P pi -> forall k, (state_at P pi 0 k < nstates P)%nat.
Proof.
  intros HP Hv k; induction k as [|k IH]; [simpl; destruct HP; lia|].
  simpl; destruct (proj1 (in_actions _ _ _) (Hv k)) as [[E _]|(i & E & Hi)]; rewrite E;
    [exact IH | apply (wf_move P HP); auto].
Qed.

(** The marking of a stationary policy: its move at every state ([None] where it terminates). *)
Definition policy_marks (pi : spolicy) (x : nat) : option nat :=
  match pi x with Move i => Some i | Term => None end.

Lemma policy_marks_walk P pi k :
  (forall j, pi (state_at P pi 0 j) <> Term) ->
  marked_walk P (policy_marks pi) k = state_at P pi 0 k.
Proof.
  intros Ht; induction k as [|k IH]; [reflexivity|]; simpl; rewrite IH.
  unfold policy_marks; specialize (Ht k).
  destruct (pi (state_at P pi 0 k)); [congruence | reflexivity].
Qed.

(** If some stationary policy's path from [x1] never visits the goal (it enters a cycle
    avoiding the goal), its moves form a marking whose walk avoids the goal. *)
Lemma policy_marks_avoid P pi :
  wf P -> valid_on_path P pi -> (forall k, state_at P pi 0 k <> goal P) ->
  marks_avoid_goal P (policy_marks pi).
Proof.
  intros HP Hv Hng.
  assert (Hmove : forall k, exists i, pi (state_at P pi 0 k) = Move i /\
                    (i < length (moves P (state_at P pi 0 k)))%nat).
  { intros k; destruct (proj1 (in_actions _ _ _) (Hv k)) as [[_ E]|(i & E & Hi)];
      [exfalso; apply (Hng k E) | eauto]. }
  assert (Ht : forall j, pi (state_at P pi 0 j) <> Term)
    by (intros j; destruct (Hmove j) as (i & E & _); rewrite E; discriminate).
  intros k; rewrite policy_marks_walk by auto; split; [apply Hng|].
  destruct (Hmove k) as (i & E & Hi); exists i; unfold policy_marks; rewrite E; auto.
Qed.

(** C3 from the registry's hypothesis (the paper's discounting proposition; docs/spec.md §6 C3; the
    claims registry's C3 statement): if some stationary policy's path from [x1] (admissible
    along it) never visits the goal, then for every real [alpha] in [(0,1)] and every
    [K > 1/(1-alpha)] the certificate costs (1 on that policy's moves, [K] on every other
    move, all strictly positive; termination 0) make every discount-optimal policy (among all
    policies) avoid the goal and pay 1 per stage: its true cost is infinite. (The registry's
    other hypothesis, a goal-reaching policy, is not needed.) *)
Corollary c3_from_policy P pi K alpha :
  wf P -> valid_on_path P pi -> (forall k, state_at P pi 0 k <> goal P) ->
  0 < alpha < 1 -> / (1 - alpha) < Q2R K ->
  let C := certificate P (policy_marks pi) K in
  (forall x i, (i < length (moves P x))%nat -> (0 < cost C x (Move i))%Q) /\
  (exists r, traj_optimal C alpha r) /\
  forall r, traj_optimal C alpha r ->
    (forall k, fst r k <> goal P /\ traj_stages C r k = 1) /\
    (forall B, exists N, B < partial (traj_stages C r) N).
Proof.
  intros HP Hv Hng Ha HK C.
  assert (Hm := policy_marks_avoid P pi HP Hv Hng).
  split; [intros x i Hi; apply cert_positive; auto; eapply K_pos; eauto|].
  destruct (c3_certificate P (policy_marks pi) K alpha Hm Ha HK) as [Hex Hall].
  split; [exact Hex|]; intros r Hr; destruct (Hall r Hr) as [H1 H2]; split; [|exact H2].
  intros k; destruct (H1 k) as (_ & A & B); auto.
Qed.

