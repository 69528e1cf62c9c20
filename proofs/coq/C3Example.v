(** * C3, the worked example: the printed inequality, the threshold [alpha_star], the example over all policies

    The worked example of the paper's discounting proposition (the claims
    registry's C3-example): the printed inequality and its quartic ([printed_iff_quartic]), the
    bracket of the quartic's root ([alpha_lo], [alpha_hi], [quartic_lo], [quartic_hi]), the
    example's stationary policies ([c3_example_threshold]) and all its policies (section
    [ExampleAll]). [C3.v] states the main theorems ([c3_printed_iff_quartic], [c3_alpha_star],
    [c3_example_threshold_all]). *)

From Coq Require Import Reals Lra Lia QArith Qround Qreals List.
From Truecost Require Import Model Paths C1 C2 QReal C3Policies C3Certificate.
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
Lemma printed_iff_quartic a : 0 < a < 1 -> printed a <-> quartic a < 0.
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

(** C3's worked example (the paper's discounting proposition, its example; docs/spec.md §6 C3; the
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
  - apply printed_iff_quartic; auto.
  - intros Hp pi Hopt B.
    destruct (ex3_stay pi (Honly Hp pi Hopt)) as [Hs _].
    destruct (nat_above B) as (K & HK).
    exists (S K).
    assert (E : forall K, partial (stages ex3 pi 0) K = INR K).
    { induction K0 as [|K0 IH]; simpl partial; [simpl; ring|rewrite IH, Hs, S_INR; ring]. }
    rewrite E; rewrite S_INR; lra.
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


