(** * Claim C3: the dangers of discounting (the paper's discounting proposition)

    - [c3_printed_iff_quartic]: the worked example's printed inequality
      [1/(1-alpha) < sum_{i=1..5} i alpha^(i-1)] holds exactly when
      [5 alpha^4 - alpha^3 - alpha^2 - alpha - 1 < 0], for every real [alpha] in [(0,1)].
    - [c3_alpha_star]: that quartic has exactly one root [alpha_star] in [(0,1)]; it lies strictly
      between the two rationals [alpha_lo] and [alpha_hi] ([alpha_hi - alpha_lo = 2^-100]), and
      the quartic is negative exactly on [(0, alpha_star)].
    - [c3_example_threshold]: in the worked example (SPEC §6, C3; the claims registry's
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
    the series ([C2.discounted]), not closed forms. *)

From Coq Require Import Reals Lra Lia QArith Qround Qreals List.
From Truecost Require Import Model Paths C1 C2 QReal.
Import ListNotations.

Open Scope R_scope.

(** ** The printed inequality and the quartic *)

(** [5 alpha^4 - alpha^3 - alpha^2 - alpha - 1]: the printed inequality with the denominator
    cleared (the registry's threshold polynomial). *)
Definition quartic (a : R) : R := 5 * a ^ 4 - a ^ 3 - a ^ 2 - a - 1.

(** The right-hand side as printed: [sum_{i=1..5} i alpha^(i-1)] (summed over [k = i - 1]). *)
Definition printed_rhs (a : R) : R := sum_f_R0 (fun k => INR (S k) * a ^ k) 4.

(** The printed inequality: [1/(1-alpha) < sum_{i=1..5} i alpha^(i-1)]. *)
Definition printed (a : R) : Prop := / (1 - a) < printed_rhs a.

Lemma printed_rhs_poly a : printed_rhs a = 1 + 2 * a + 3 * a ^ 2 + 4 * a ^ 3 + 5 * a ^ 4.
Proof. unfold printed_rhs; simpl; ring. Qed.

(** C3's worked example, the printed form: for every real [alpha] in [(0,1)], the printed
    inequality holds iff the quartic is negative. *)
Theorem c3_printed_iff_quartic a : 0 < a < 1 -> printed a <-> quartic a < 0.
Proof.
  intros Ha; unfold printed; rewrite printed_rhs_poly.
  assert (Hd : 0 < 1 - a) by lra.
  assert (Key : (1 + 2 * a + 3 * a ^ 2 + 4 * a ^ 3 + 5 * a ^ 4) * (1 - a) - 1
                = - a * quartic a) by (unfold quartic; ring).
  split; intros H.
  - apply (Rmult_lt_compat_r (1 - a)) in H; [|lra].
    rewrite Rinv_l in H by lra.
    assert (0 < a * - quartic a) by nra.
    destruct (Rlt_or_le (quartic a) 0) as [|Hq]; [auto|].
    assert (a * - quartic a <= 0) by nra; lra.
  - assert (0 < a * - quartic a) by (apply Rmult_lt_0_compat; lra).
    apply (Rmult_lt_reg_r (1 - a)); [lra|].
    rewrite Rinv_l by lra; lra.
Qed.

(** ** The threshold [alpha_star]: bracket and uniqueness *)

(** The quartic over [Q], to evaluate it exactly at the bracket's ends. *)
Definition quartic_Q (q : Q) : Q := 5 * (q * q * q * q) - q * q * q - q * q - q - 1.

Lemma quartic_Q_R q : Q2R (quartic_Q q) = quartic (Q2R q).
Proof.
  unfold quartic_Q, quartic.
  rewrite !Q2R_minus, !Q2R_mult.
  replace (Q2R 5) with 5 by (unfold Q2R; simpl; lra).
  rewrite Q2R_1.
  simpl; ring.
Qed.

(** The bracket of [alpha_star] that [truecost verify] prints ([src/claims/alpha.rs]): two dyadic
    rationals [2^-100] apart. *)
Definition alpha_lo : Q := 580808718285461345641984028243 # 633825300114114700748351602688.
Definition alpha_hi : Q := 1161617436570922691283968056487 # 1267650600228229401496703205376.

Lemma alpha_bracket_width : (alpha_hi - alpha_lo == 1 # 1267650600228229401496703205376)%Q.
Proof. vm_compute; reflexivity. Qed.

Lemma quartic_lo : quartic (Q2R alpha_lo) < 0.
Proof.
  rewrite <- quartic_Q_R; rewrite <- Q2R_0.
  apply Qlt_Rlt; vm_compute; reflexivity.
Qed.

Lemma quartic_hi : 0 < quartic (Q2R alpha_hi).
Proof.
  rewrite <- quartic_Q_R; rewrite <- Q2R_0.
  apply Qlt_Rlt; vm_compute; reflexivity.
Qed.

Lemma bracket_in_01 : 0 < Q2R alpha_lo /\ Q2R alpha_lo < Q2R alpha_hi /\ Q2R alpha_hi < 1.
Proof.
  rewrite <- Q2R_0.
  rewrite <- Q2R_1.
  repeat split; apply Qlt_Rlt; vm_compute; reflexivity.
Qed.

(** The sign of the quartic changes once on [(0, +oo)]: [quartic x / x^4] is increasing. *)
Lemma quartic_sign_mono a b : 0 < a < b -> 0 <= quartic a -> 0 < quartic b.
Proof.
  intros [Ha Hab] Hqa.
  assert (Id : a ^ 4 * quartic b - b ^ 4 * quartic a
               = a ^ 3 * b ^ 3 * (b - a) + a ^ 2 * b ^ 2 * ((b - a) * (b + a))
                 + a * b * ((b - a) * (b * b + a * b + a * a))
                 + (b - a) * ((b + a) * (b * b + a * a))) by (unfold quartic; ring).
  assert (Hb : 0 < b) by lra.
  assert (Hba : 0 < b - a) by lra.
  assert (0 < a ^ 3 * b ^ 3 * (b - a)).
  { apply Rmult_lt_0_compat; auto; apply Rmult_lt_0_compat; apply pow_lt; auto. }
  assert (0 <= a ^ 2 * b ^ 2 * ((b - a) * (b + a))).
  { apply Rmult_le_pos; [apply Rmult_le_pos; apply pow_le; lra|]; nra. }
  assert (0 <= a * b * ((b - a) * (b * b + a * b + a * a))).
  { apply Rmult_le_pos; [nra|]; apply Rmult_le_pos; nra. }
  assert (0 <= (b - a) * ((b + a) * (b * b + a * a))).
  { apply Rmult_le_pos; [lra|]; apply Rmult_le_pos; nra. }
  assert (0 <= b ^ 4 * quartic a) by (apply Rmult_le_pos; [apply pow_le; lra | auto]).
  assert (Ha4 : 0 < a ^ 4) by (apply pow_lt; auto).
  assert (0 < a ^ 4 * quartic b) by lra.
  destruct (Rlt_or_le 0 (quartic b)) as [|Hq]; [auto|].
  assert (a ^ 4 * quartic b <= 0) by nra; lra.
Qed.

Lemma quartic_continuous : continuity quartic.
Proof. unfold quartic; reg. Qed.

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

(** ** Stationary policies, their trajectories and stage costs *)

(** A stationary deterministic policy: one action per state. It is admissible in [P] when it
    picks, at every state, one of the state's actions ([uT] only at the goal). *)
Definition spolicy := nat -> action.

Definition valid_policy (P : problem) (pi : spolicy) : Prop :=
  forall x, (x < nstates P)%nat -> In (pi x) (actions P x).

(** [state_at P pi x k]: the state after [k] stages from [x] under [pi] ([uT] freezes the
    goal, SPEC §1). *)
Fixpoint state_at (P : problem) (pi : spolicy) (x : nat) (k : nat) : nat :=
  match k with
  | O => x
  | S k' => target P (state_at P pi x k') (pi (state_at P pi x k'))
  end.

(** The stage costs [l(x_k, pi(x_k))], [k = 0, 1, ...] (the [k]-th stage is the paper's
    [k+1]-th), as reals. *)
Definition stages (P : problem) (pi : spolicy) (x : nat) : sequence :=
  fun k => Q2R (cost P (state_at P pi x k) (pi (state_at P pi x k))).

(** [pi]'s trajectory from [x] visits the goal. *)
Definition reaches_goal (P : problem) (pi : spolicy) (x : nat) : Prop :=
  exists k, state_at P pi x k = goal P.

(** [pi] is discount-optimal from [x1 = 0]: admissible, its discounted cost [v] exists, and no
    admissible stationary policy has a smaller one ([C2.minimises] with [C2.discounted]). *)
Definition disc_optimal (P : problem) (alpha : R) (pi : spolicy) : Prop :=
  minimises spolicy (valid_policy P) (discounted alpha) (fun s => stages P s 0) pi.

(** [pi]'s true (undiscounted) cost from [x1 = 0] is [+oo]: its partial sums are unbounded. *)
Definition infinite_true_cost (P : problem) (pi : spolicy) : Prop :=
  forall B, exists K, B < partial (stages P pi 0) K.

(** ** Discounted sums *)

Lemma discounted_const a : 0 <= a < 1 -> discounted a (fun _ => 1) (/ (1 - a)).
Proof.
  intros Ha; unfold discounted.
  apply (total_extensional (fun k => 1 * a ^ k)); [intro; ring|].
  apply GP_infinite; rewrite Rabs_right; lra.
Qed.

Lemma partial_S s n : partial s (S n) = partial s n + s n.
Proof. reflexivity. Qed.

Lemma partial_ext_lt s t K : (forall k, (k < K)%nat -> s k = t k) -> partial s K = partial t K.
Proof.
  induction K as [|K IH]; intros H; [reflexivity|].
  rewrite !partial_S, (H K) by lia; f_equal; apply IH; intros k Hk; apply H; lia.
Qed.

Lemma partial_add s a b : partial s (a + b) = partial s a + partial (fun k => s (a + k)%nat) b.
Proof.
  induction b as [|b IH]; [rewrite Nat.add_0_r; simpl; ring|].
  rewrite Nat.add_succ_r, !partial_S, IH; ring.
Qed.

Lemma partial_le s t K : (forall k, (k < K)%nat -> s k <= t k) -> partial s K <= partial t K.
Proof.
  induction K as [|K IH]; intros H; simpl; [lra|].
  pose proof (H K ltac:(lia)).
  assert (partial s K <= partial t K) by (apply IH; intros; apply H; lia).
  lra.
Qed.

(** A series of nonnegative terms is at least each of its partial sums. *)
Lemma total_ge_partial t w K : total t w -> (forall k, 0 <= t k) -> partial t K <= w.
Proof.
  intros Ht Hpos.
  assert (Hg : Un_growing (sum_f_R0 t)) by (intro n; simpl; pose proof (Hpos (S n)); lra).
  destruct K as [|K].
  - apply Rle_trans with (sum_f_R0 t 0); [simpl; apply Hpos|].
    apply (growing_ineq (sum_f_R0 t)); [exact Hg | exact Ht].
  - rewrite <- sum_f_R0_partial; apply (growing_ineq (sum_f_R0 t)); [exact Hg | exact Ht].
Qed.

(** Stage costs at least 1, and at least 2 at stage 1: the discounted cost is at least
    [1/(1-alpha) + alpha]. *)
Lemma discounted_ge_stay a s v :
  0 < a < 1 -> (forall k, 1 <= s k) -> 2 <= s 1%nat -> discounted a s v ->
  / (1 - a) + a <= v.
Proof.
  intros Ha H1 H2 Hv.
  destruct (discounted_linear a) as [Hplus Hscale].
  pose proof (Hplus _ _ _ _ Hv (Hscale (-1) _ _ (discounted_const a ltac:(lra)))) as Hd.
  unfold discounted in Hd.
  pose proof (total_ge_partial _ _ 2 Hd) as Hp.
  assert (0 <= partial (fun k => a ^ k * (s k + -1 * 1)) 2 - a).
  { simpl; pose proof (H1 O); nra. }
  assert (partial (fun k => a ^ k * (s k + -1 * 1)) 2 <= v + -1 * / (1 - a)).
  { apply Hp; intro k; apply Rmult_le_pos; [apply pow_le; lra|]; pose proof (H1 k); lra. }
  lra.
Qed.

(** ** The worked example *)

(** [X = {0..5}], goal 5, [x1 = 0]; at every state the move [Move 0] is [u = -1] and
    [Move 1] is [u = +1], with [f(x,u) = min(5, max(0, x+u))] ([ex3_f]) and [l(x,u) = x+1];
    the goal has [uT] and its two moves. *)
Definition ex3 : problem := {|
  nstates := 6;
  goal := 5;
  moves := fun x => [(pred x, inject_Z (Z.of_nat (S x)));
                     (Nat.min 5 (S x), inject_Z (Z.of_nat (S x)))]
|}.

Lemma ex3_f x :
  (x <= 5)%nat ->
  Z.of_nat (target ex3 x (Move 0)) = Z.min 5 (Z.max 0 (Z.of_nat x - 1)) /\
  Z.of_nat (target ex3 x (Move 1)) = Z.min 5 (Z.max 0 (Z.of_nat x + 1)).
Proof.
  intros Hx; unfold target; simpl.
  do 6 (destruct x as [|x]; [split; reflexivity|]); lia.
Qed.

Lemma ex3_cost x i : (i < 2)%nat -> Q2R (cost ex3 x (Move i)) = INR x + 1.
Proof.
  intros Hi; assert (E : cost ex3 x (Move i) = inject_Z (Z.of_nat (S x))).
  { destruct i as [|[|i]]; [reflexivity | reflexivity | lia]. }
  rewrite E, Q2R_inject_Z, <- INR_IZR_INZ, S_INR; auto.
Qed.

Lemma ex3_actions x : (x < 5)%nat -> actions ex3 x = [Move 0; Move 1].
Proof.
  intros Hx; unfold actions.
  replace (Nat.eqb x (goal ex3)) with false by (symmetry; apply Nat.eqb_neq; simpl; lia).
  reflexivity.
Qed.

Lemma ex3_valid_lt pi x : valid_policy ex3 pi -> (x < 5)%nat -> pi x = Move 0 \/ pi x = Move 1.
Proof.
  intros Hv Hx; specialize (Hv x ltac:(simpl; lia)); rewrite ex3_actions in Hv by auto.
  simpl in Hv; intuition.
Qed.

Lemma ex3_target_le x a : (x <= 5)%nat -> (target ex3 x a <= 5)%nat.
Proof.
  intros Hx; destruct a as [|[|[|i]]]; unfold target; cbn -[Nat.min]; try lia.
  destruct i; simpl; lia.
Qed.

Lemma ex3_state_le pi k : (state_at ex3 pi 0 k <= 5)%nat.
Proof. induction k as [|k IH]; simpl; [lia | apply ex3_target_le; auto]. Qed.

(** The least state where [pi] moves down, if it does so below the goal. *)
Lemma ex3_first_down pi :
  valid_policy ex3 pi ->
  (forall y, (y < 5)%nat -> pi y = Move 1) \/
  exists j, (j < 5)%nat /\ pi j = Move 0 /\ forall y, (y < j)%nat -> pi y = Move 1.
Proof.
  intros Hv.
  enough (forall m, (m <= 5)%nat ->
            (forall y, (y < m)%nat -> pi y = Move 1) \/
            exists j, (j < m)%nat /\ pi j = Move 0 /\ forall y, (y < j)%nat -> pi y = Move 1)
    as H by (apply H; lia).
  induction m as [|m IH]; intros Hm; [left; intros; lia|].
  destruct (IH ltac:(lia)) as [Hall|(j & Hj & Hd & Hu)].
  - destruct (ex3_valid_lt pi m Hv ltac:(lia)) as [Hd|Hu].
    + right; exists m; repeat split; auto.
    + left; intros y Hy; destruct (Nat.eq_dec y m) as [->|]; [auto | apply Hall; lia].
  - right; exists j; repeat split; auto; lia.
Qed.

(** Below the first down-move [j], the trajectory from 0 never passes [j]. *)
Lemma ex3_below_down pi j :
  pi j = Move 0 -> (forall y, (y < j)%nat -> pi y = Move 1) ->
  forall k, (state_at ex3 pi 0 k <= j)%nat.
Proof.
  intros Hd Hu k; induction k as [|k IH]; simpl; [lia|].
  destruct (Nat.eq_dec (state_at ex3 pi 0 k) j) as [E|Ne].
  - rewrite E, Hd; unfold target; cbn -[Nat.min]; lia.
  - rewrite (Hu (state_at ex3 pi 0 k) ltac:(lia)); unfold target; cbn -[Nat.min]; lia.
Qed.

(** Every admissible stationary policy from 0 falls in one of three cases: it stays at 0
    forever ([stay]), it goes straight to the goal and terminates ([reach]), or it never
    terminates and moves up from 0 ([other]). *)
Lemma ex3_policy_cases pi :
  valid_policy ex3 pi ->
  pi 0%nat = Move 0 \/
  (pi 5%nat = Term /\ forall y, (y < 5)%nat -> pi y = Move 1) \/
  (pi 0%nat = Move 1 /\ forall k, pi (state_at ex3 pi 0 k) <> Term).
Proof.
  intros Hv.
  destruct (ex3_first_down pi Hv) as [Hall|(j & Hj & Hd & Hu)].
  - assert (Ht : pi 5%nat = Term \/ pi 5%nat <> Term)
      by (destruct (pi 5%nat); [left | right]; congruence).
    destruct Ht as [Ht|Ht]; [right; left; auto|].
    right; right; split; [apply Hall; lia|]; intros k.
    pose proof (ex3_state_le pi k) as Hle.
    destruct (Nat.eq_dec (state_at ex3 pi 0 k) 5) as [->|Ne]; auto.
    rewrite Hall by lia; discriminate.
  - destruct j as [|j]; [left; auto|].
    right; right; split; [apply Hu; lia|]; intros k.
    pose proof (ex3_below_down pi (S j) Hd Hu k).
    destruct (ex3_valid_lt pi (state_at ex3 pi 0 k) Hv ltac:(lia)) as [-> | ->]; discriminate.
Qed.

Lemma ex3_move_of pi x :
  valid_policy ex3 pi -> (x <= 5)%nat -> pi x <> Term -> exists i, (i < 2)%nat /\ pi x = Move i.
Proof.
  intros Hv Hx Ht.
  destruct (Nat.eq_dec x 5) as [->|Ne].
  - specialize (Hv 5%nat ltac:(simpl; lia)); simpl in Hv.
    destruct Hv as [E|[E|[E|[]]]]; [congruence | exists 0%nat | exists 1%nat]; auto.
  - destruct (ex3_valid_lt pi x Hv ltac:(lia)) as [E|E]; [exists 0%nat | exists 1%nat]; auto.
Qed.

(** Case [stay]: the stage costs are all 1 and the goal is never visited. *)
Lemma ex3_stay pi :
  pi 0%nat = Move 0 ->
  (forall k, stages ex3 pi 0 k = 1) /\ ~ reaches_goal ex3 pi 0.
Proof.
  intros H0.
  assert (Hs : forall k, state_at ex3 pi 0 k = 0%nat).
  { induction k as [|k IH]; simpl; [auto | rewrite IH, H0; reflexivity]. }
  split.
  - intros k; unfold stages; rewrite Hs, H0, ex3_cost by lia; simpl; ring.
  - intros (k & E); rewrite Hs in E; discriminate.
Qed.

(** Case [reach]: the stage costs are [1, 2, 3, 4, 5, 0, 0, ...]. *)
Lemma ex3_reach pi :
  pi 5%nat = Term -> (forall y, (y < 5)%nat -> pi y = Move 1) ->
  (forall k, stages ex3 pi 0 k = if Nat.ltb k 5 then INR k + 1 else 0) /\ reaches_goal ex3 pi 0.
Proof.
  intros H5 Hu.
  assert (Hs : forall k, state_at ex3 pi 0 k = Nat.min k 5).
  { induction k as [|k IH]; [reflexivity|]; simpl state_at; rewrite IH.
    destruct (Nat.lt_ge_cases k 5) as [Hk|Hk].
    - rewrite Nat.min_l by lia; rewrite Hu by auto; unfold target; cbn -[Nat.min]; lia.
    - rewrite Nat.min_r by lia; rewrite H5; unfold target; lia. }
  split.
  - intros k; unfold stages; rewrite Hs.
    destruct (Nat.ltb_spec k 5) as [Hk|Hk].
    + rewrite Nat.min_l, Hu, ex3_cost by lia; auto.
    + rewrite Nat.min_r, H5 by lia; unfold cost; unfold Q2R; simpl; field.
  - exists 5%nat; rewrite Hs; reflexivity.
Qed.

(** Case [other]: every stage costs at least 1, and stage 1 costs 2. *)
Lemma ex3_other pi :
  valid_policy ex3 pi -> pi 0%nat = Move 1 -> (forall k, pi (state_at ex3 pi 0 k) <> Term) ->
  (forall k, 1 <= stages ex3 pi 0 k) /\ stages ex3 pi 0 1%nat = 2.
Proof.
  intros Hv H0 Ht.
  assert (Hk : forall k, stages ex3 pi 0 k = INR (state_at ex3 pi 0 k) + 1).
  { intros k; unfold stages.
    destruct (ex3_move_of pi _ Hv (ex3_state_le pi k) (Ht k)) as (i & Hi & ->).
    apply ex3_cost; auto. }
  split.
  - intros k; rewrite Hk; pose proof (pos_INR (state_at ex3 pi 0 k)); lra.
  - rewrite Hk; simpl; rewrite H0; unfold target; simpl; lra.
Qed.

(** The values of the three cases. *)
Lemma ex3_reach_value a pi :
  pi 5%nat = Term -> (forall y, (y < 5)%nat -> pi y = Move 1) ->
  discounted a (stages ex3 pi 0) (printed_rhs a).
Proof.
  intros H5 Hu; destruct (ex3_reach pi H5 Hu) as [Hs _].
  unfold discounted.
  assert (E : partial (fun k => a ^ k * stages ex3 pi 0 k) 5 = printed_rhs a).
  { rewrite printed_rhs_poly; simpl partial; rewrite !Hs; simpl; ring. }
  rewrite <- E; apply total_eventually_zero.
  intros k Hk; rewrite Hs; destruct (Nat.ltb_spec k 5); [lia | ring].
Qed.

(** Every admissible policy's discounted cost is [1/(1-alpha)] (it stays at 0), the printed
    sum (it goes straight to the goal and terminates), or at least [1/(1-alpha) + alpha]. *)
Lemma ex3_values a pi v :
  0 < a < 1 -> valid_policy ex3 pi -> discounted a (stages ex3 pi 0) v ->
  (v = / (1 - a) /\ ~ reaches_goal ex3 pi 0) \/ v = printed_rhs a \/ / (1 - a) + a <= v.
Proof.
  intros Ha Hv Hval.
  destruct (ex3_policy_cases pi Hv) as [H0|[[H5 Hu]|[H0 Ht]]].
  - left; destruct (ex3_stay pi H0) as [Hs Hn]; split; auto.
    apply (discounted_single_valued a (stages ex3 pi 0)); auto.
    apply (total_extensional (fun k => a ^ k * 1)); [intro k; rewrite Hs; auto|].
    apply discounted_const; lra.
  - right; left; apply (discounted_single_valued a (stages ex3 pi 0)); auto.
    apply ex3_reach_value; auto.
  - right; right; destruct (ex3_other pi Hv H0 Ht) as [H1 H2].
    apply (discounted_ge_stay a (stages ex3 pi 0)); auto; lra.
Qed.

Lemma nat_above B : exists K, B < INR K.
Proof.
  destruct (archimed B) as [H _].
  destruct (Z_lt_le_dec 0 (up B)) as [Hp|Hn].
  - exists (Z.to_nat (up B)); rewrite INR_IZR_INZ, Z2Nat.id by lia; lra.
  - exists 0%nat; apply IZR_le in Hn; simpl; lra.
Qed.

(** The two policies that matter: stay at 0, or go straight to the goal and terminate. *)
Definition stay_pi : spolicy := fun x => if Nat.eqb x 5 then Term else Move 0.
Definition reach_pi : spolicy := fun x => if Nat.eqb x 5 then Term else Move 1.

Lemma stay_valid : valid_policy ex3 stay_pi.
Proof.
  intros x Hx; simpl in Hx; unfold stay_pi.
  destruct (Nat.eqb_spec x 5) as [->|Ne]; [simpl; auto|].
  rewrite ex3_actions by lia; simpl; auto.
Qed.

Lemma reach_valid : valid_policy ex3 reach_pi.
Proof.
  intros x Hx; simpl in Hx; unfold reach_pi.
  destruct (Nat.eqb_spec x 5) as [->|Ne]; [simpl; auto|].
  rewrite ex3_actions by lia; simpl; auto.
Qed.

Lemma stay_value a : 0 < a < 1 -> discounted a (stages ex3 stay_pi 0) (/ (1 - a)).
Proof.
  intros Ha; destruct (ex3_stay stay_pi eq_refl) as [Hs _].
  apply (total_extensional (fun k => a ^ k * 1)); [intro k; rewrite Hs; auto|].
  apply discounted_const; lra.
Qed.

Lemma reach_value a : discounted a (stages ex3 reach_pi 0) (printed_rhs a).
Proof.
  apply ex3_reach_value; [reflexivity|].
  intros y Hy; unfold reach_pi; destruct (Nat.eqb_spec y 5); [lia | auto].
Qed.

Lemma reach_reaches : reaches_goal ex3 reach_pi 0.
Proof.
  apply (ex3_reach reach_pi eq_refl).
  intros y Hy; unfold reach_pi; destruct (Nat.eqb_spec y 5); [lia | auto].
Qed.

(** C3's worked example (the paper's discounting proposition, its example; SPEC §6 C3; the
    claims registry's C3-example: "the discount-optimal policy from 0 avoids the goal exactly
    when 1/(1-alpha) < sum_{i=1..5} i alpha^(i-1)"). For every real [alpha] in [(0,1)]:
    a discount-optimal policy exists; every discount-optimal policy avoids the goal iff the
    printed inequality holds, iff [5 alpha^4 - alpha^3 - alpha^2 - alpha - 1 < 0]; and then
    every discount-optimal policy has infinite true cost.
    Policies: the stationary deterministic ones ([spolicy], admissible: [valid_policy]);
    "optimal" means least discounted cost from [x1 = 0] among them, the discounted cost being
    the sum of the series ([C2.discounted]). *)
Theorem c3_example_threshold a :
  0 < a < 1 ->
  (exists pi, disc_optimal ex3 a pi) /\
  ((forall pi, disc_optimal ex3 a pi -> ~ reaches_goal ex3 pi 0) <-> printed a) /\
  (printed a <-> quartic a < 0) /\
  (printed a -> forall pi, disc_optimal ex3 a pi -> infinite_true_cost ex3 pi).
Proof.
  intros Ha.
  assert (Hpos : 0 < / (1 - a)) by (apply Rinv_0_lt_compat; lra).
  assert (Hreach_opt : printed_rhs a <= / (1 - a) -> disc_optimal ex3 a reach_pi).
  { intros Hle; split; [apply reach_valid|]; exists (printed_rhs a); split; [apply reach_value|].
    intros s w Hs Hw; destruct (ex3_values a s w Ha Hs Hw) as [[->_]|[->|Hge]]; lra. }
  assert (Hstay_opt : printed a -> disc_optimal ex3 a stay_pi).
  { intros Hp; unfold printed in Hp; split; [apply stay_valid|].
    exists (/ (1 - a)); split; [apply stay_value; auto|].
    intros s w Hs Hw; destruct (ex3_values a s w Ha Hs Hw) as [[->_]|[->|Hge]]; lra. }
  (* Under the printed inequality, every optimal policy stays at 0. *)
  assert (Honly : printed a -> forall pi, disc_optimal ex3 a pi ->
                  pi 0%nat = Move 0).
  { intros Hp pi (Hv & v & Hval & Hmin); unfold printed in Hp.
    pose proof (Hmin stay_pi _ stay_valid (stay_value a Ha)) as Hle.
    destruct (ex3_policy_cases pi Hv) as [H0|[[H5 Hu]|[H0 Ht]]]; auto; exfalso.
    - pose proof (discounted_single_valued a _ _ _ Hval (ex3_reach_value a pi H5 Hu)); lra.
    - destruct (ex3_other pi Hv H0 Ht) as [H1 H2].
      pose proof (discounted_ge_stay a _ _ Ha H1 ltac:(lra) Hval); lra. }
  split; [|split; [|split]].
  - destruct (Rlt_or_le (/ (1 - a)) (printed_rhs a)) as [Hp|Hp].
    + exists stay_pi; apply Hstay_opt; auto.
    + exists reach_pi; apply Hreach_opt; auto.
  - split.
    + intros Hall; destruct (Rlt_or_le (/ (1 - a)) (printed_rhs a)) as [Hp|Hp]; [auto|].
      exfalso; apply (Hall reach_pi (Hreach_opt Hp)), reach_reaches.
    + intros Hp pi Hopt; apply (ex3_stay pi (Honly Hp pi Hopt)).
  - apply c3_printed_iff_quartic; auto.
  - intros Hp pi Hopt B.
    destruct (ex3_stay pi (Honly Hp pi Hopt)) as [Hs _].
    destruct (nat_above B) as (K & HK).
    exists (S K).
    assert (E : forall K, partial (stages ex3 pi 0) K = INR K).
    { induction K0 as [|K0 IH]; simpl partial; [simpl; ring|rewrite IH, Hs, S_INR; ring]. }
    rewrite E; rewrite S_INR; lra.
Qed.

(** ** C3 for every finite problem: the certificate *)

(** Action sequences from [x1 = 0] and the states they visit. The problem is deterministic, so
    every policy, history-dependent or not, produces one, and each is produced by the
    open-loop policy that applies it: optimality over these is optimality over all policies. *)
Definition trajectory (P : problem) (x : nat -> nat) (a : nat -> action) : Prop :=
  x O = 0%nat /\ forall k, In (a k) (actions P (x k)) /\ x (S k) = target P (x k) (a k).

Definition traj_stages (P : problem) (r : (nat -> nat) * (nat -> action)) : sequence :=
  fun k => Q2R (cost P (fst r k) (snd r k)).

(** [r] is discount-optimal from [x1 = 0] among ALL policies ([C2.minimises]). *)
Definition traj_optimal (P : problem) (alpha : R) (r : (nat -> nat) * (nat -> action)) : Prop :=
  minimises _ (fun r => trajectory P (fst r) (snd r)) (discounted alpha) (traj_stages P) r.

(** A stationary policy's states and actions form a trajectory. *)
Lemma stationary_trajectory P pi :
  valid_policy P pi -> wf P ->
  trajectory P (state_at P pi 0) (fun k => pi (state_at P pi 0 k)).
Proof.
  intros Hv HP; split; [reflexivity|]; intros k; split; [|reflexivity].
  apply Hv; induction k as [|k IH]; simpl; [destruct HP; lia|].
  destruct (proj1 (in_actions _ _ _) (Hv _ IH)) as [[E _]|(i & E & Hi)]; rewrite E.
  - unfold target; auto.
  - apply (wf_move P HP); auto.
Qed.

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

(** C3 with truecost's certificate (the paper's discounting proposition; SPEC §6 C3; the
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

(** C3 from the registry's hypothesis (the paper's discounting proposition; SPEC §6 C3; the
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

(** ** The worked example over all policies *)

Lemma ex3_wf : wf ex3.
Proof.
  split; [simpl; lia|]; intros x Hx y l Hin; simpl in Hx.
  assert (Hl : (0 <= inject_Z (Z.of_nat (S x)))%Q).
  { change 0%Q with (inject_Z 0); rewrite <- Zle_Qle; lia. }
  destruct Hin as [E|[E|[]]]; inversion E; subst; split; auto; cbn -[Nat.min]; try lia.
  do 6 (destruct x as [|x]; [simpl; lia|]); lia.
Qed.

Lemma least_witness (Pr : nat -> Prop) :
  (forall k, Pr k \/ ~ Pr k) ->
  forall k, Pr k -> exists j, (j <= k)%nat /\ Pr j /\ forall i, (i < j)%nat -> ~ Pr i.
Proof.
  intros Hdec k Hk.
  assert (H : forall N, (forall i, (i < N)%nat -> ~ Pr i) \/
                        exists j, (j < N)%nat /\ Pr j /\ forall i, (i < j)%nat -> ~ Pr i).
  { induction N as [|N IH]; [left; intros; lia|].
    destruct IH as [Hall|(j & Hj & Hp & Hb)]; [|right; exists j; repeat split; auto; lia].
    destruct (Hdec N) as [Hp|Hn].
    - right; exists N; repeat split; auto.
    - left; intros i Hi; destruct (Nat.eq_dec i N) as [->|]; [auto | apply Hall; lia]. }
  destruct (H (S k)) as [Hall|(j & Hj & Hp & Hb)]; [exfalso; apply (Hall k); auto; lia|].
  exists j; repeat split; auto; lia.
Qed.

Section ExampleAll.
Variable alpha : R.
Hypothesis Ha : 0 < alpha < 1.
Variables (x : nat -> nat) (a : nat -> action).
Hypothesis Hr : trajectory ex3 x a.
Notation c := (traj_stages ex3 (x, a)).

Lemma ex3_traj_le k : (x k <= 5)%nat.
Proof.
  destruct Hr as [H0 Hs]; induction k as [|k IH]; [rewrite H0; lia|].
  rewrite (proj2 (Hs k)); apply ex3_target_le; auto.
Qed.

Lemma ex3_traj_move k :
  a k <> Term -> c k = INR (x k) + 1 /\ (x (S k) <= S (x k))%nat.
Proof.
  intros Ht; destruct Hr as [_ Hs]; destruct (Hs k) as [Hin E].
  apply in_actions in Hin as [[? _]|(i & Ei & Hi)]; [congruence|].
  simpl in Hi; unfold traj_stages; simpl fst; simpl snd; rewrite Ei, ex3_cost by lia.
  split; [auto|]; rewrite E, Ei; unfold target.
  destruct i as [|[|i]]; [| |lia]; cbn -[Nat.min]; lia.
Qed.

Lemma ex3_traj_term k : a k = Term -> x k = 5%nat /\ c k = 0.
Proof.
  intros Ht; destruct Hr as [_ Hs]; destruct (Hs k) as [Hin _]; rewrite Ht in Hin.
  apply in_actions in Hin as [[_ E]|(i & Ei & _)]; [|discriminate].
  split; [exact E|]; unfold traj_stages; simpl; rewrite Ht; unfold cost, Q2R; simpl; lra.
Qed.

Lemma ex3_traj_nonneg k : 0 <= c k.
Proof.
  destruct (action_eq_dec (a k) Term) as [E|E].
  - rewrite (proj2 (ex3_traj_term k E)); lra.
  - rewrite (proj1 (ex3_traj_move k E)); pose proof (pos_INR (x k)); lra.
Qed.

(** Stage costs at least 1, and at least 2 at stage [j]: at least [1/(1-alpha) + alpha^j]. *)
Lemma ex3_ge_stay_at j v :
  (forall k, 1 <= c k) -> 2 <= c j -> discounted alpha c v -> / (1 - alpha) + alpha ^ j <= v.
Proof.
  intros H1 H2 Hv.
  destruct (discounted_linear alpha) as [Hplus Hscale].
  pose proof (Hplus _ _ _ _ Hv (Hscale (-1) _ _ (discounted_const alpha ltac:(lra)))) as Hd.
  unfold discounted in Hd.
  assert (Hpos : forall k, 0 <= alpha ^ k * (c k + -1 * 1)).
  { intros k; apply Rmult_le_pos; [apply pow_le; lra|]; pose proof (H1 k); lra. }
  pose proof (total_ge_partial _ _ (S j) Hd Hpos) as Hp.
  assert (0 <= partial (fun k => alpha ^ k * (c k + -1 * 1)) j).
  { clear Hp; induction j as [|j IH]; simpl; [lra|].
    pose proof (Hpos j); assert (0 <= partial (fun k => alpha ^ k * (c k + -1 * 1)) j); [|lra].
    clear IH H2; induction j as [|j IH]; simpl; [lra|]; pose proof (Hpos j); lra. }
  rewrite partial_S in Hp.
  assert (alpha ^ j <= alpha ^ j * (c j + -1 * 1)).
  { assert (0 < alpha ^ j) by (apply pow_lt; lra); nra. }
  lra.
Qed.

(** A policy that terminates first at stage [T = m + 5] climbed to the goal: its stage costs
    before [T] are at least [1] and, over the last five stages, [1, 2, 3, 4, 5]. *)
Lemma ex3_term_bound T v :
  a T = Term -> (forall k, (k < T)%nat -> a k <> Term) -> discounted alpha c v ->
  exists m, (T = m + 5)%nat /\
    (1 - alpha ^ m) / (1 - alpha) + alpha ^ m * printed_rhs alpha <= v.
Proof.
  intros HT Hb Hv.
  destruct (ex3_traj_term T HT) as [HxT _].
  assert (Hclimb : forall j, (j <= T)%nat -> (5 <= x (T - j) + j)%nat).
  { induction j as [|j IH]; intros Hj; [rewrite Nat.sub_0_r; lia|].
    destruct (ex3_traj_move (T - S j) (Hb (T - S j)%nat ltac:(lia))) as [_ Hle].
    replace (S (T - S j)) with (T - j)%nat in Hle by lia; specialize (IH ltac:(lia)); lia. }
  assert (H5 : (5 <= T)%nat).
  { pose proof (Hclimb T ltac:(lia)) as H; rewrite Nat.sub_diag, (proj1 Hr) in H; lia. }
  exists (T - 5)%nat; split; [lia|]; set (m := (T - 5)%nat).
  assert (Hck : forall k, (k < T)%nat -> INR (S k) - INR m <= c k /\ 1 <= c k).
  { intros k Hk; destruct (ex3_traj_move k (Hb k Hk)) as [Ec _]; rewrite Ec.
    pose proof (Hclimb (T - k)%nat ltac:(lia)) as H; replace (T - (T - k))%nat with k in H by lia.
    assert (INR (S k) <= INR (x k) + 1 + INR m).
    { rewrite <- S_INR, <- plus_INR; apply le_INR; unfold m; lia. }
    pose proof (pos_INR (x k)); lra. }
  assert (Hp := total_ge_partial _ _ T Hv
                  (fun k => Rmult_le_pos _ _ (pow_le alpha k ltac:(lra)) (ex3_traj_nonneg k))).
  replace T with (m + 5)%nat in Hp by (unfold m; lia).
  rewrite partial_add in Hp.
  assert (Hpre : partial (fun k => alpha ^ k * 1) m <= partial (fun k => alpha ^ k * c k) m).
  { clear Hp; assert (Hmle : (m <= T)%nat) by (unfold m; lia).
    assert (H1 : forall k, (k < T)%nat -> 1 <= c k) by (intros; apply Hck; auto).
    clearbody m; clear -H1 Hmle Ha.
    induction m as [|m IH]; simpl; [lra|].
    pose proof (IH ltac:(lia)); pose proof (H1 m ltac:(lia)).
    assert (0 <= alpha ^ m) by (apply pow_le; lra); nra. }
  assert (Hpost : alpha ^ m * printed_rhs alpha
                  <= partial (fun k => alpha ^ (m + k) * c (m + k)%nat) 5).
  { rewrite printed_rhs_poly.
    assert (Hc : forall j, (j < 5)%nat -> INR (S j) <= c (m + j)%nat).
    { intros j Hj; destruct (Hck (m + j)%nat ltac:(unfold m; lia)) as [H _].
      rewrite S_INR, plus_INR in H; rewrite S_INR; lra. }
    apply Rle_trans with (partial (fun k => alpha ^ (m + k) * INR (S k)) 5).
    - simpl partial; rewrite !pow_add; simpl; lra.
    - apply partial_le; intros k Hk; apply Rmult_le_compat_l; [apply pow_le; lra | auto]. }
  pose proof (geom_partial alpha m) as Hg.
  assert (E : partial (fun k => alpha ^ k * 1) m = (1 - alpha ^ m) / (1 - alpha))
    by (apply (Rmult_eq_reg_r (1 - alpha)); [rewrite Hg; field|]; lra).
  lra.
Qed.
Lemma ex3_ge_stay v : (forall k, 1 <= c k) -> discounted alpha c v -> / (1 - alpha) <= v.
Proof.
  intros H1 Hv.
  destruct (discounted_linear alpha) as [Hplus Hscale].
  pose proof (Hplus _ _ _ _ Hv (Hscale (-1) _ _ (discounted_const alpha ltac:(lra)))) as Hd.
  assert (Hpos : forall k, 0 <= alpha ^ k * (c k + -1 * 1)).
  { intros k; apply Rmult_le_pos; [apply pow_le; lra|]; pose proof (H1 k); lra. }
  pose proof (total_ge_partial _ _ 0 Hd Hpos) as Hp; simpl in Hp; lra.
Qed.

(** Every policy's discounted cost is at least [min(1/(1-alpha), printed sum)]; under the
    printed inequality, only staying at 0 forever attains [1/(1-alpha)]. *)
Lemma ex3_all_lower v :
  discounted alpha c v ->
  (printed alpha -> v <= / (1 - alpha) -> forall k, x k = 0%nat /\ c k = 1) /\
  (~ printed alpha -> printed_rhs alpha <= v).
Proof.
  intros Hv.
  assert (Hterm : forall k, a k = Term ->
            exists m, (1 - alpha ^ m) / (1 - alpha) + alpha ^ m * printed_rhs alpha <= v).
  { intros k Hk.
    destruct (least_witness (fun k => a k = Term)
                (fun k => match action_eq_dec (a k) Term with
                          | left E => or_introl E | right E => or_intror E end) k Hk)
      as (T & _ & HT & Hb).
    destruct (ex3_term_bound T v HT Hb Hv) as (m & _ & H); eauto. }
  assert (Hd : 0 < 1 - alpha) by lra.
  assert (Hid : forall m, (1 - alpha ^ m) / (1 - alpha) + alpha ^ m * printed_rhs alpha
                          = / (1 - alpha) + alpha ^ m * (printed_rhs alpha - / (1 - alpha)))
    by (intros; field; lra).
  split.
  - intros Hp Hle.
    assert (Hnt : forall k, a k <> Term).
    { intros k Hk; destruct (Hterm k Hk) as (m & Hm); rewrite Hid in Hm.
      assert (0 < alpha ^ m) by (apply pow_lt; lra).
      unfold printed in Hp; nra. }
    assert (Hx0 : forall k, x k = 0%nat).
    { intros k; destruct (Nat.eq_dec (x k) 0) as [|Ne]; [auto|exfalso].
      assert (H1 : forall j, 1 <= c j).
      { intros j; rewrite (proj1 (ex3_traj_move j (Hnt j))); pose proof (pos_INR (x j)); lra. }
      assert (2 <= c k).
      { rewrite (proj1 (ex3_traj_move k (Hnt k))).
        assert (1 <= INR (x k)) by (apply (le_INR 1); lia); lra. }
      pose proof (ex3_ge_stay_at k v H1 H Hv); assert (0 < alpha ^ k) by (apply pow_lt; lra); lra. }
    intros k; split; [auto|]; rewrite (proj1 (ex3_traj_move k (Hnt k))), Hx0; simpl; ring.
  - intros Hnp; unfold printed in Hnp; apply Rnot_lt_le; intros Hlt.
    assert (Hnt : forall k, a k <> Term).
    { intros k Hk; destruct (Hterm k Hk) as (m & Hm); rewrite Hid in Hm.
      assert (0 < alpha ^ m) by (apply pow_lt; lra).
      assert (alpha ^ m <= 1).
      { clear -Ha; induction m as [|m IH]; simpl; [lra|].
        assert (0 <= alpha ^ m) by (apply pow_le; lra); nra. }
      nra. }
    assert (H1 : forall j, 1 <= c j).
    { intros j; rewrite (proj1 (ex3_traj_move j (Hnt j))); pose proof (pos_INR (x j)); lra. }
    pose proof (ex3_ge_stay v H1 Hv); lra.
Qed.
End ExampleAll.


(** C3's worked example over ALL policies (the paper's discounting proposition, its example;
    SPEC §6 C3; the claims registry's C3-example): for every real [alpha] in [(0,1)], a
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
    proposition; SPEC §6 C3): if a goal-reaching policy exists and some admissible policy's
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

(** ** The engine's certificate: cost 1 on the lasso only *)

Lemma map_seq_dup (f : nat -> nat) a m :
  ~ NoDup (map f (seq a m)) ->
  exists i j, (a <= i)%nat /\ (i < j)%nat /\ (j < a + m)%nat /\ f i = f j.
Proof.
  revert a; induction m as [|m IH]; intros a H; [exfalso; apply H; constructor|].
  simpl in H; destruct (in_dec Nat.eq_dec (f a) (map f (seq (S a) m))) as [Hin|Hout].
  - apply in_map_iff in Hin as (j & E & Hj); apply in_seq in Hj.
    exists a, j; repeat split; auto; lia.
  - destruct (IH (S a)) as (i & j & H1 & H2 & H3 & E).
    + intros Hnd; apply H; constructor; auto.
    + exists i, j; repeat split; auto; lia.
Qed.

Section Lasso.
Variables (P : problem) (pi : spolicy).
Hypothesis HP : wf P.
Hypothesis Hv : valid_on_path P pi.
Notation st := (state_at P pi 0).

Lemma st_lt k : (st k < nstates P)%nat.
Proof. apply valid_on_path_lt; auto. Qed.

(** The path of a stationary policy is a lasso: every state it visits, it visits within the
    first [n] stages. *)
Lemma st_lasso k : exists j, (j < nstates P)%nat /\ st k = st j.
Proof.
  set (n := nstates P).
  assert (Hdup : exists i j, (i < j)%nat /\ (j <= n)%nat /\ st i = st j).
  { destruct (map_seq_dup st 0 (S n)) as (i & j & _ & H2 & H3 & E);
      [|exists i, j; repeat split; auto; lia].
    intros Hnd; pose proof (NoDup_incl_length Hnd (l' := seq 0 n)) as H.
    rewrite map_length, !seq_length in H; enough (S n <= n)%nat by lia.
    apply H; intros z Hz; apply in_map_iff in Hz as (t & <- & _); apply in_seq; split; [lia|].
    apply st_lt. }
  destruct Hdup as (i & j & Hij & Hjn & E).
  assert (Hper : forall d, st (i + d + (j - i)) = st (i + d)).
  { induction d as [|d IH]; [rewrite Nat.add_0_r; replace (i + (j - i))%nat with j by lia; auto|].
    replace (i + S d + (j - i))%nat with (S (i + d + (j - i))) by lia.
    replace (i + S d)%nat with (S (i + d)) by lia; simpl; rewrite IH; reflexivity. }
  induction k as [k IH] using (well_founded_induction lt_wf).
  destruct (Nat.lt_ge_cases k n) as [Hk|Hk]; [exists k; auto|].
  destruct (IH (k - (j - i))%nat ltac:(lia)) as (j' & Hj' & E').
  exists j'; split; auto; rewrite <- E'.
  replace k with (i + (k - (j - i) - i) + (j - i))%nat at 1 by lia; rewrite Hper.
  f_equal; lia.
Qed.

(** The engine's marking: [pi]'s move on the states of its lasso from [x1], nothing
    elsewhere. *)
Definition lasso_marks (x : nat) : option nat :=
  if existsb (fun k => Nat.eqb (st k) x) (seq 0 (nstates P)) then policy_marks pi x else None.

Hypothesis Hng : forall k, st k <> goal P.

Lemma lasso_on k : lasso_marks (st k) = policy_marks pi (st k).
Proof.
  unfold lasso_marks; destruct (st_lasso k) as (j & Hj & E).
  replace (existsb _ _) with true; [reflexivity|]; symmetry; apply existsb_exists.
  exists j; split; [apply in_seq; lia | apply Nat.eqb_eq; auto].
Qed.

Lemma lasso_move k : exists i, pi (st k) = Move i /\ (i < length (moves P (st k)))%nat.
Proof.
  destruct (proj1 (in_actions _ _ _) (Hv k)) as [[_ E]|(i & E & Hi)];
    [exfalso; apply (Hng k E) | eauto].
Qed.

(** Following the marks from [x1] is following [pi]. *)
Lemma lasso_walk k : marked_walk P lasso_marks k = st k.
Proof.
  induction k as [|k IH]; [reflexivity|]; simpl; rewrite IH, lasso_on.
  destruct (lasso_move k) as (i & E & _); unfold policy_marks; rewrite E; reflexivity.
Qed.

Lemma lasso_marks_avoid : marks_avoid_goal P lasso_marks.
Proof.
  intros k; rewrite lasso_walk; split; [apply Hng|].
  destruct (lasso_move k) as (i & E & Hi); exists i; rewrite lasso_on.
  unfold policy_marks; rewrite E; auto.
Qed.
End Lasso.

(** C3 with the certificate truecost's C3 engine builds (the kernel's [claims::c3::certificate]):
    for a stationary policy [pi] whose path from [x1] never visits the goal (the engine takes,
    at each state, the first move into the goal-avoiding core), cost 1 on the moves of [pi]'s
    lasso from [x1], [K = floor(1/((1-alpha0) alpha0^(n-2))) + 1] on every other move; for
    every real [alpha] in [(0, alpha0]], every discount-optimal policy (among all policies)
    follows the lasso, never reaches the goal, and has infinite true cost. *)
Corollary c3_engine_lasso P pi alpha0 alpha :
  wf P -> valid_on_path P pi -> (forall k, state_at P pi 0 k <> goal P) ->
  (0 < alpha0 < 1)%Q -> 0 < alpha <= Q2R alpha0 ->
  let C := engine_certificate P (lasso_marks P pi) alpha0 (nstates P) in
  (forall x i, (i < length (moves P x))%nat -> (0 < cost C x (Move i))%Q) /\
  (exists r, traj_optimal C alpha r) /\
  forall r, traj_optimal C alpha r ->
    (forall k, fst r k = state_at P pi 0 k /\ fst r k <> goal P /\ traj_stages C r k = 1) /\
    (forall B, exists N, B < partial (traj_stages C r) N).
Proof.
  intros HP Hv Hng Ha0 Ha C.
  assert (Hm := lasso_marks_avoid P pi HP Hv Hng).
  destruct (c3_certificate_engine P (lasso_marks P pi) alpha0 (nstates P) alpha Hm Ha0 Ha)
    as (Hpos & Hex & Hall).
  split; [exact Hpos|]; split; [exact Hex|]; intros r Hr; destruct (Hall r Hr) as [H1 H2].
  split; [|exact H2]; intros k; destruct (H1 k) as (E & A & B); repeat split; auto.
  rewrite E; apply lasso_walk; auto.
Qed.

(** ** The engine's construction: the goal-avoiding core and the first move into it *)

(** The kernel's [goal_avoiding_core]: the greatest set of non-goal states each with a move
    into the set, computed by [n + 1] rounds of removal from the non-goal states. *)
Definition core_init (P : problem) : list bool :=
  map (fun x => negb (Nat.eqb x (goal P))) (seq 0 (nstates P)).
Definition core_step (P : problem) (w : list bool) : list bool :=
  map (fun x => nth x w false && existsb (fun yl => nth (fst yl) w false) (moves P x))
      (seq 0 (nstates P)).
Fixpoint core_iter (P : problem) (k : nat) : list bool :=
  match k with O => core_init P | S k' => core_step P (core_iter P k') end.
Definition in_core (P : problem) (x : nat) : bool := nth x (core_iter P (S (nstates P))) false.

(** The engine's policy: at each state, the first move into the core. *)
Fixpoint first_idx (f : nat * Q -> bool) (l : list (nat * Q)) : option nat :=
  match l with
  | [] => None
  | a :: t => if f a then Some 0%nat else option_map S (first_idx f t)
  end.
Definition core_pi (P : problem) : spolicy := fun x =>
  match first_idx (fun yl => in_core P (fst yl)) (moves P x) with
  | Some i => Move i
  | None => Term
  end.

Lemma first_idx_some f l i :
  first_idx f l = Some i -> (i < length l)%nat /\ f (nth i l (0%nat, 0%Q)) = true.
Proof.
  revert i; induction l as [|a t IH]; intros i H; simpl in H; [discriminate|].
  destruct (f a) eqn:E; [inversion H; subst; simpl; auto; split; [lia|auto]|].
  destruct (first_idx f t) as [j|] eqn:Ej; simpl in H; [|discriminate].
  inversion H; subst; destruct (IH j eq_refl); simpl; split; [lia|auto].
Qed.

Lemma first_idx_exists f l : existsb f l = true -> exists i, first_idx f l = Some i.
Proof.
  induction l as [|a t IH]; simpl; [discriminate|]; intros H.
  destruct (f a); [eauto|]; destruct (IH H) as (i & Ei); rewrite Ei; simpl; eauto.
Qed.

Lemma existsb_ext_in {A} (f g : A -> bool) l :
  (forall a, In a l -> f a = g a) -> existsb f l = existsb g l.
Proof.
  induction l as [|a t IH]; intros H; simpl; [reflexivity|].
  rewrite H by (left; auto); rewrite IH by (intros; apply H; right; auto); reflexivity.
Qed.

Lemma forallb_false {A} (f : A -> bool) l :
  forallb f l = false -> exists a, In a l /\ f a = false.
Proof.
  induction l as [|a t IH]; simpl; [discriminate|]; intros H.
  destruct (f a) eqn:E; [simpl in H; destruct (IH H) as (b & Hb & Eb); eauto|eauto].
Qed.

Section Core.
Variable P : problem.
Hypothesis HP : wf P.
Notation n := (nstates P).
Notation c k x := (nth x (core_iter P k) false).

Lemma core_len k : length (core_iter P k) = n.
Proof. destruct k; simpl; unfold core_init, core_step; rewrite map_length, seq_length; auto. Qed.

Lemma core_out k x : (n <= x)%nat -> c k x = false.
Proof. intros H; apply nth_overflow; rewrite core_len; auto. Qed.

Lemma core_S k x :
  c (S k) x = c k x && existsb (fun yl => c k (fst yl)) (moves P x).
Proof.
  destruct (Nat.lt_ge_cases x n) as [Hx|Hx].
  - simpl; unfold core_step; rewrite nth_map_seq by auto; reflexivity.
  - rewrite !core_out by auto; reflexivity.
Qed.

Lemma core_mono k x : c (S k) x = true -> c k x = true.
Proof. rewrite core_S; intros H; apply andb_prop in H; tauto. Qed.

Lemma core_goal k : c k (goal P) = false.
Proof.
  induction k as [|k IH].
  - simpl; unfold core_init; rewrite nth_map_seq by (destruct HP; auto).
    rewrite Nat.eqb_refl; reflexivity.
  - rewrite core_S, IH; reflexivity.
Qed.

Definition stable k : Prop := forall x, c (S k) x = c k x.

Lemma stable_S k : stable k -> stable (S k).
Proof.
  intros H x.
  assert (E : existsb (fun yl => c (S k) (fst yl)) (moves P x)
              = existsb (fun yl => c k (fst yl)) (moves P x))
    by (apply existsb_ext_in; intros; apply H).
  rewrite (core_S (S k) x), E, (H x) at 1; rewrite <- core_S; reflexivity.
Qed.

Lemma stable_from j : stable j -> forall m x, c (j + m) x = c j x.
Proof.
  intros H m; induction m as [|m IH]; intros x; [rewrite Nat.add_0_r; reflexivity|].
  assert (Hs : stable (j + m)).
  { clear IH; induction m as [|m IHm]; [rewrite Nat.add_0_r; auto|].
    rewrite Nat.add_succ_r; apply stable_S; auto. }
  rewrite Nat.add_succ_r, Hs; apply IH.
Qed.

Definition core_count k : nat := length (filter (fun x => c k x) (seq 0 n)).

Lemma filter_lt (f g : nat -> bool) l :
  (forall a, In a l -> f a = true -> g a = true) ->
  (exists a, In a l /\ g a = true /\ f a = false) ->
  (length (filter f l) < length (filter g l))%nat.
Proof.
  induction l as [|b t IH]; intros Hfg (a & Ha & Hg & Hf); [destruct Ha|].
  assert (Hle : forall l, (forall a, In a l -> f a = true -> g a = true) ->
                (length (filter f l) <= length (filter g l))%nat).
  { clear; induction l as [|b t IH]; intros H; simpl; [lia|].
    destruct (f b) eqn:Ef; [rewrite (H b ltac:(left; auto) Ef); simpl|destruct (g b); simpl];
      specialize (IH (fun a Ha => H a (or_intror Ha))); lia. }
  simpl; destruct Ha as [<-|Ha].
  - rewrite Hf, Hg; simpl.
    pose proof (Hle t (fun a Ha => Hfg a (or_intror Ha))); lia.
  - assert (IH' := IH (fun a Ha => Hfg a (or_intror Ha)) (ex_intro _ a (conj Ha (conj Hg Hf)))).
    destruct (f b) eqn:Ef; [rewrite (Hfg b ltac:(left; auto) Ef); simpl; lia|].
    destruct (g b); simpl; lia.
Qed.

Lemma stable_dec k : stable k \/ (core_count (S k) < core_count k)%nat.
Proof.
  destruct (forallb (fun x => Bool.eqb (c (S k) x) (c k x)) (seq 0 n)) eqn:E.
  - left; intros x; destruct (Nat.lt_ge_cases x n) as [Hx|Hx].
    + rewrite forallb_forall in E; apply Bool.eqb_prop, E, in_seq; lia.
    + rewrite !core_out by auto; reflexivity.
  - right; apply filter_lt.
    + intros a _; apply core_mono.
    + destruct (forallb_false _ _ E) as (x & Hx & Hne).
      exists x; split; [exact Hx|].
      destruct (c k x) eqn:E1, (c (S k) x) eqn:E2; simpl in Hne; try discriminate; auto.
      rewrite (core_mono k x E2) in E1; discriminate.
Qed.
Lemma filter_len_le (f : nat -> bool) l : (length (filter f l) <= length l)%nat.
Proof. induction l as [|a t IH]; simpl; [lia|]; destruct (f a); simpl; lia. Qed.

(** The removal rounds stabilise within [n] rounds. *)
Lemma core_stable : exists j, (j <= n)%nat /\ stable j.
Proof.
  assert (H : forall k, (exists j, (j <= k)%nat /\ stable j) \/
                        (core_count k + k <= core_count 0)%nat).
  { induction k as [|k IH]; [right; lia|].
    destruct IH as [(j & Hj & Hs)|IH]; [left; exists j; split; [lia|auto]|].
    destruct (stable_dec k) as [Hs|Hlt]; [left; exists k; split; [lia|auto]|right; lia]. }
  destruct (H n) as [Hj|Hc]; [exact Hj|].
  assert (H0 : (core_count 0 <= n)%nat)
    by (unfold core_count; rewrite <- (seq_length n 0) at 2; apply filter_len_le).
  exists n; split; [lia|]; intros x.
  destruct (c n x) eqn:Ex.
  - exfalso; destruct (Nat.lt_ge_cases x n) as [Hx|Hx];
      [|rewrite core_out in Ex by auto; discriminate].
    assert (Hin : In x (filter (fun x => c n x) (seq 0 n)))
      by (apply filter_In; split; [apply in_seq; lia|auto]).
    assert (1 <= core_count n)%nat.
    { unfold core_count; destruct (filter (fun x => c n x) (seq 0 n)); [destruct Hin|simpl; lia]. }
    lia.
  - destruct (c (S n) x) eqn:E'; [|reflexivity]; rewrite (core_mono n x E') in Ex; discriminate.
Qed.

Lemma in_core_fix x : nth x (core_iter P (S (S n))) false = in_core P x.
Proof.
  destruct core_stable as (j & Hj & Hs); unfold in_core.
  replace (S (S n)) with (j + (S (S n) - j))%nat by lia.
  replace (S n) with (j + (S n - j))%nat at 2 by lia.
  rewrite !(stable_from j Hs); reflexivity.
Qed.

(** The core is a post-fixed point: its states are not the goal and have a move into it. *)
Lemma in_core_next x :
  in_core P x = true -> x <> goal P /\ existsb (fun yl => in_core P (fst yl)) (moves P x) = true.
Proof.
  intros H; split.
  - intros ->; unfold in_core in H; rewrite core_goal in H; discriminate.
  - rewrite <- in_core_fix, core_S in H; apply andb_prop in H; tauto.
Qed.

(** If [x1] is in the core, the engine's policy stays in the core from [x1]: its path never
    visits the goal, and it picks a move at every stage. *)
Lemma core_path :
  in_core P 0 = true ->
  forall k, in_core P (state_at P (core_pi P) 0 k) = true /\
    exists i, core_pi P (state_at P (core_pi P) 0 k) = Move i /\
              (i < length (moves P (state_at P (core_pi P) 0 k)))%nat.
Proof.
  intros H0.
  assert (Hstep : forall x, in_core P x = true ->
            exists i, core_pi P x = Move i /\ (i < length (moves P x))%nat /\
                      in_core P (target P x (Move i)) = true).
  { intros x Hx; destruct (in_core_next x Hx) as [_ He].
    destruct (first_idx_exists _ _ He) as (i & Ei).
    destruct (first_idx_some _ _ _ Ei) as [Hi Hf].
    exists i; unfold core_pi; rewrite Ei; repeat split; auto.
    unfold target; rewrite (nth_indep _ (x, 0%Q) (0%nat, 0%Q)) by auto; exact Hf. }
  assert (Hin : forall k, in_core P (state_at P (core_pi P) 0 k) = true).
  { induction k as [|k IH]; [exact H0|].
    destruct (Hstep _ IH) as (i & E & Hi & Hn); simpl; rewrite E; exact Hn. }
  intros k; split; [apply Hin|]; destruct (Hstep _ (Hin k)) as (i & E & Hi & _); eauto.
Qed.
End Core.


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
