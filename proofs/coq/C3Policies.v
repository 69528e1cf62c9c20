(** * C3, shared: stationary policies, their trajectories and stage costs, discounted sums

    The objects C3's three parts speak of ([C3Example.v]: the worked example; [C3Certificate.v]:
    the certificate for every finite problem; [C3Engine.v]: the engine's construction): a
    stationary policy, the trajectory and stage costs it produces, its true cost, and the
    discounted sums of [C2.discounted]. [C3.v] states the main theorems. *)

From Coq Require Import Reals Lra Lia QArith Qround Qreals List.
From Truecost Require Import Model Paths C1 C2 QReal.
Import ListNotations.

Open Scope R_scope.

(** ** Stationary policies, their trajectories and stage costs *)

(** A stationary deterministic policy: one action per state. It is admissible in [P] when it
    picks, at every state, one of the state's actions ([uT] only at the goal). *)
Definition spolicy := nat -> action.

Definition valid_policy (P : problem) (pi : spolicy) : Prop :=
  forall x, (x < nstates P)%nat -> In (pi x) (actions P x).

(** [state_at P pi x k]: the state after [k] stages from [x] under [pi] ([uT] freezes the
    goal, docs/spec.md §1). *)
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

(** Every real is below some natural number. *)
Lemma nat_above B : exists K, B < INR K.
Proof.
  destruct (archimed B) as [H _].
  destruct (Z_lt_le_dec 0 (up B)) as [Hp|Hn].
  - exists (Z.to_nat (up B)); rewrite INR_IZR_INZ, Z2Nat.id by lia; lra.
  - exists 0%nat; apply IZR_le in Hn; simpl; lra.
Qed.

(** ** Trajectories: every policy, history-dependent or not *)

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
