(** * Claim C1: finite-time convergence of derandomized Q-learning (the paper's Proposition 1)

    - [c1_as_printed_refuted]: C1 as printed (docs/spec.md §6; the claims registry's
      [c1::STATEMENT]) fails on the minimal counterexample [loop2];
      [c1_as_printed_refuted_positive_costs]: it fails also with every move cost positive and
      [Q0(xg, uT) = 0] ([back2]).
    - [c1_corrected]: C1-corrected (the claims registry's [c1::corrected_statement] with [c1::ROUND_BOUND];
      [docs/proofs/c1.md]) for EVERY well-formed finite problem, with the round bound
      [round_bound] that [truecost verify] prints; its two parts are
      [c1_corrected_from_above] (Part A) and [c1_corrected_from_below] (Part B).
    - [c1_paper_form]: the paper's form, with an infinite update sequence, as a corollary.
    - [c1_round_bound_tight], [c1_round_bound_tight_above]: both bounds are attained, so
      neither can be lowered by one round. *)

From Coq Require Import QArith Qround List Lia Lqa.
From Truecost Require Import Model Paths.
Import ListNotations.

Open Scope Q_scope.

Arguments target : simpl never.
Arguments cost : simpl never.

(** ** Pairs, actions and single updates *)

Lemma action_eqb_spec a b : action_eqb a b = true <-> a = b.
Proof.
  destruct a as [|i], b as [|j]; simpl; try (split; congruence).
  rewrite Nat.eqb_eq; split; congruence.
Qed.

Lemma action_eq_dec (a b : action) : {a = b} + {a <> b}.
Proof. decide equality; apply Nat.eq_dec. Qed.

Lemma in_pairs P x a : In (x, a) (pairs P) <-> (x < nstates P)%nat /\ In a (actions P x).
Proof.
  unfold pairs; rewrite in_flat_map; split.
  - intros (x' & Hx' & Ha); apply in_map_iff in Ha as (a' & E & Ha'); inversion E; subst.
    apply in_seq in Hx'; split; [lia | auto].
  - intros [Hx Ha]; exists x; split; [apply in_seq; lia | apply in_map_iff; eauto].
Qed.

Lemma in_actions P x a :
  In a (actions P x) <->
  (a = Term /\ x = goal P) \/ (exists i, a = Move i /\ (i < length (moves P x))%nat).
Proof.
  unfold actions; rewrite in_app_iff, in_map_iff; split.
  - intros [H|(i & <- & Hi)]; [|right; exists i; split; auto; apply in_seq in Hi; lia].
    destruct (Nat.eqb_spec x (goal P)); simpl in H; [destruct H as [<-|[]]; left; auto|].
    destruct H.
  - intros [[-> ->]|(i & -> & Hi)]; [left; rewrite Nat.eqb_refl; simpl; auto|].
    right; exists i; split; auto; apply in_seq; lia.
Qed.

Lemma in_move_pairs P p : In p (move_pairs P) <-> In p (pairs P) /\ is_move p = true.
Proof. unfold move_pairs; apply filter_In. Qed.

Lemma run_cons P q p ps : run P q (p :: ps) = run P (update P q p) ps.
Proof. reflexivity. Qed.

Lemma run_app P q a b : run P q (a ++ b) = run P (run P q a) b.
Proof. unfold run; apply fold_left_app. Qed.

Lemma run_printed_app P q a b : run_printed P q (a ++ b) = run_printed P (run_printed P q a) b.
Proof. unfold run_printed; apply fold_left_app. Qed.

Lemma update_same P q x i :
  update P q (x, Move i) x (Move i) = cost P x (Move i) + V P q (target P x (Move i)).
Proof.
  unfold update, update_printed, qset; cbn [snd].
  rewrite Nat.eqb_refl; cbn [andb action_eqb]; rewrite Nat.eqb_refl; reflexivity.
Qed.

Lemma update_other P q x0 a0 x a :
  (x, a) <> (x0, a0) -> update P q (x0, a0) x a = q x a.
Proof.
  intros H; destruct a0 as [|j]; [reflexivity|].
  unfold update, update_printed, qset; cbn [snd].
  destruct (Nat.eqb_spec x x0); [subst|reflexivity].
  destruct (action_eqb a (Move j)) eqn:E; [apply action_eqb_spec in E; congruence|].
  reflexivity.
Qed.

(** ** C1 as printed: refuted *)

(** The cyclic order: every pair of [loop2] once per round, the termination pair included. *)
Definition loop2_round : list (nat * action) := pairs loop2.

Definition q_zero : qvec := fun _ _ => 0.

Lemma loop2_wf : wf loop2.
Proof.
  split; [simpl; lia|].
  intros x Hx y l H; simpl in Hx.
  destruct x as [|[|x]]; simpl in H; [|tauto | lia].
  destruct H as [E|[E|[]]]; inversion E; simpl; split; try lia; lra.
Qed.

(** Every state of [loop2] reaches the goal: the failure is not a [Q* = +oo] artefact. *)
Lemma loop2_reaches : forall x, (x < nstates loop2)%nat -> Gstar loop2 x <> None.
Proof. intros x Hx; simpl in Hx; destruct x as [|[|x]]; [discriminate | discriminate | lia]. Qed.

Definition loop2_inv (q : qvec) : Prop :=
  q 0%nat (Move 0) == 0 /\ 0 <= q 0%nat (Move 1) /\ q 1%nat Term == 0.

Lemma loop2_round_inv q : loop2_inv q -> loop2_inv (run_printed loop2 q loop2_round).
Proof.
  intros (H0 & H1 & H2).
  unfold loop2_inv, run_printed, loop2_round, pairs; simpl.
  unfold update_printed, qset, V, target, cost; simpl.
  pose proof (Qmin2_l (q 0%nat (Move 1)) (q 0%nat (Move 0))).
  pose proof (Qmin2_r (q 0%nat (Move 1)) (q 0%nat (Move 0))).
  destruct (Qmin2_cases (q 0%nat (Move 1)) (q 0%nat (Move 0))) as [E|E]; rewrite E in *; lra.
Qed.

Lemma loop2_rounds_inv k q :
  loop2_inv q -> loop2_inv (run_printed loop2 q (concat (repeat loop2_round k))).
Proof.
  revert q; induction k as [|k IH]; intros q Hq; [exact Hq|].
  change (concat (repeat loop2_round (S k))) with (loop2_round ++ concat (repeat loop2_round k)).
  rewrite run_printed_app.
  apply IH, loop2_round_inv, Hq.
Qed.

(** C1 as printed (the paper's Proposition 1 as printed; the claims registry's
    [c1::STATEMENT]) is false: on [loop2] (well-formed, every state reaching the goal), from
    [Q0 = 0], updating every pair (the termination pair included, by the printed rule) once per
    round in the cyclic order, [Q] differs from [Q*] after every number [k] of rounds:
    [Q(0, self-loop)] stays 0 while [Q*(0, self-loop) = 1]. *)
Theorem c1_as_printed_refuted :
  wf loop2 /\ (forall x, (x < nstates loop2)%nat -> Gstar loop2 x <> None) /\
  (forall p, In p (pairs loop2) -> In p loop2_round) /\
  forall k, ~ (forall x a, In (x, a) (pairs loop2) ->
                 exists v, Qstar loop2 x a = Some v /\
                           run_printed loop2 q_zero (concat (repeat loop2_round k)) x a == v).
Proof.
  split; [exact loop2_wf|]; split; [exact loop2_reaches|]; split; [auto|].
  intros k H.
  destruct (H 0%nat (Move 0) ltac:(vm_compute; auto)) as (v & Ev & Hv).
  vm_compute in Ev; inversion Ev; subst v.
  destruct (loop2_rounds_inv k q_zero ltac:(unfold loop2_inv, q_zero; lra)) as (E & _).
  rewrite E in Hv; discriminate Hv.
Qed.

(** ** C1 as printed: refuted with positive move costs *)

(** Two states, every move of cost 1: [0 -> 1] and [1 -> 0], the goal 1. *)
Definition back2 : problem := {|
  nstates := 2;
  goal := 1;
  moves := fun x => match x with O => [(1%nat, 1)] | 1%nat => [(0%nat, 1)] | _ => [] end
|}.

(** The cyclic order: every pair of [back2] once per round, the termination pair included. *)
Definition back2_round : list (nat * action) := pairs back2.

(** [Q0]: [-1] at the goal's move, [0] elsewhere, so [Q0(xg, uT) = 0] as (H0) asks. *)
Definition q_back : qvec :=
  fun x a => match x, a with 1%nat, Move _ => -1 | _, _ => 0 end.

Lemma back2_wf : wf back2.
Proof.
  split; [simpl; lia|].
  intros x Hx y l H; simpl in Hx.
  destruct x as [|[|x]]; simpl in H; [| | lia];
    destruct H as [E|[]]; inversion E; simpl; split; try lia; lra.
Qed.

Lemma back2_reaches : forall x, (x < nstates back2)%nat -> Gstar back2 x <> None.
Proof. intros x Hx; simpl in Hx; destruct x as [|[|x]]; [discriminate | discriminate | lia]. Qed.

Lemma back2_costs_pos : forall x i, In (x, Move i) (pairs back2) -> 0 < cost back2 x (Move i).
Proof.
  intros x i H; vm_compute in H.
  destruct H as [E|[E|[E|[]]]]; inversion E; subst; reflexivity.
Qed.

(** Some value at the goal is negative. *)
Definition back2_inv (q : qvec) : Prop := q 1%nat Term < 0 \/ q 1%nat (Move 0) < 0.

(** The printed rule sets [Q(xg, uT)] to [min(Q(xg, uT), Q(xg, 1 -> 0))], which is negative. *)
Lemma back2_round_inv q : back2_inv q -> back2_inv (run_printed back2 q back2_round).
Proof.
  intros H; left.
  unfold run_printed, back2_round, pairs; simpl.
  unfold update_printed, qset, V, target, cost; simpl.
  pose proof (Qmin2_l (q 1%nat (Move 0)) (q 1%nat Term)).
  pose proof (Qmin2_r (q 1%nat (Move 0)) (q 1%nat Term)).
  destruct H; lra.
Qed.

Lemma back2_rounds_inv k q :
  back2_inv q -> back2_inv (run_printed back2 q (concat (repeat back2_round k))).
Proof.
  revert q; induction k as [|k IH]; intros q Hq; [exact Hq|].
  change (concat (repeat back2_round (S k))) with (back2_round ++ concat (repeat back2_round k)).
  rewrite run_printed_app.
  apply IH, back2_round_inv, Hq.
Qed.

(** C1 as printed (the paper's Proposition 1 as printed; the claims registry's
    [c1::STATEMENT]) is false also when every move cost is positive and [Q0(xg, uT) = 0]: on
    [back2] (well-formed, every state reaching the goal, every move of cost 1), from [Q0] with
    [-1] at the goal's move [1 -> 0] and [0] elsewhere, updating every pair (the termination pair
    included, by the printed rule) once per round in the cyclic order, [Q] differs from [Q*]
    after every number [k] of rounds: the printed rule updates the termination pair by
    [Q(xg, uT) <- 0 + min_u Q(xg, u)], so from the first round on [Q(xg, uT) < 0 = Q*(xg, uT)]
    and no later update can raise it. *)
Theorem c1_as_printed_refuted_positive_costs :
  wf back2 /\ (forall x, (x < nstates back2)%nat -> Gstar back2 x <> None) /\
  (forall x i, In (x, Move i) (pairs back2) -> 0 < cost back2 x (Move i)) /\
  q_back (goal back2) Term == 0 /\
  (forall p, In p (pairs back2) -> In p back2_round) /\
  forall k, ~ (forall x a, In (x, a) (pairs back2) ->
                 exists v, Qstar back2 x a = Some v /\
                           run_printed back2 q_back (concat (repeat back2_round k)) x a == v).
Proof.
  split; [exact back2_wf|]; split; [exact back2_reaches|]; split; [exact back2_costs_pos|].
  split; [reflexivity|]; split; [auto|].
  intros k H.
  destruct (H 1%nat Term ltac:(vm_compute; auto)) as (v & Ev & Hv).
  destruct (H 1%nat (Move 0) ltac:(vm_compute; auto)) as (w & Ew & Hw).
  vm_compute in Ev, Ew; inversion Ev; inversion Ew; subst v w.
  destruct (back2_rounds_inv k q_back ltac:(right; reflexivity)) as [E|E];
    [rewrite Hv in E | rewrite Hw in E]; discriminate E.
Qed.

(** [ceil(gap / c)] rounds of [c] cover [gap] (the integer ceiling of the round bound). *)
Lemma ceil_rounds_spec gap c L :
  0 < c -> (ceil_rounds gap c <= L)%nat -> gap <= inject_Z (Z.of_nat L) * c.
Proof.
  intros Hc; unfold ceil_rounds; destruct (Qle_bool gap 0) eqn:E; intros HL.
  - apply Qle_bool_iff in E.
    assert (HL0 : 0 <= inject_Z (Z.of_nat L)).
    { change 0 with (inject_Z 0); rewrite <- Zle_Qle; lia. }
    pose proof (Qmult_le_0_compat _ _ HL0 (Qlt_le_weak _ _ Hc)); lra.
  - pose proof (Qle_ceiling (gap / c)) as Hce.
    assert (Hz : (Qceiling (gap / c) <= Z.of_nat L)%Z) by lia.
    rewrite Zle_Qle in Hz.
    assert (Hq : ~ c == 0) by (intro; lra).
    pose proof (Qmult_div_r gap c Hq) as Hd.
    assert (c * (gap / c) <= c * inject_Z (Z.of_nat L)) by (apply Qmult_le_l; auto; lra).
    lra.
Qed.

(** ** C1-corrected: the setting *)

(** [Q = Q*] on every pair. *)
Definition exact (P : problem) (q : qvec) : Prop :=
  forall x a, In (x, a) (pairs P) -> exists v, Qstar P x a = Some v /\ q x a == v.

(** A round: a list of pairs of [P] that updates every move pair at least once (the
    termination pair is held, so it need not occur). *)
Definition round_ok (P : problem) (r : list (nat * action)) : Prop :=
  (forall p, In p r -> In p (pairs P)) /\ (forall p, In p (move_pairs P) -> In p r).

Definition rounds_ok (P : problem) (rs : list (list (nat * action))) : Prop :=
  forall r, In r rs -> round_ok P r.

Section Corrected.
Variable P : problem.
Hypothesis HP : wf P.
(** (H1): every state reaches the goal. *)
Hypothesis H1 : forall x, (x < nstates P)%nat -> Gstar P x <> None.
Notation n := (nstates P).

Definition gs (x : nat) : Q := match Gstar P x with Some g => g | None => 0 end.
Definition qs (x : nat) (a : action) : Q := match Qstar P x a with Some v => v | None => 0 end.

Lemma Gstar_gs x : (x < n)%nat -> Gstar P x = Some (gs x).
Proof. intros Hx; unfold gs; destruct (Gstar P x) eqn:E; [auto | exfalso; exact (H1 x Hx E)]. Qed.

Lemma move_pair x i :
  In (x, Move i) (pairs P) -> (x < n)%nat /\ (i < length (moves P x))%nat.
Proof.
  intros H; apply in_pairs in H as [Hx Ha]; apply in_actions in Ha as [[E _]|(j & E & Hj)];
    [discriminate | inversion E; subst; auto].
Qed.

Lemma term_pair x : In (x, Term) (pairs P) -> x = goal P.
Proof.
  intros H; apply in_pairs in H as [Hx Ha]; apply in_actions in Ha as [[_ E]|(j & E & Hj)];
    [auto | discriminate].
Qed.

Lemma succ_lt x i : In (x, Move i) (pairs P) -> (target P x (Move i) < n)%nat.
Proof. intros H; destruct (move_pair x i H); apply wf_move; auto. Qed.

Lemma succ_pairs x i a :
  In (x, Move i) (pairs P) -> In a (actions P (target P x (Move i))) ->
  In (target P x (Move i), a) (pairs P).
Proof. intros H Ha; apply in_pairs; split; auto; apply succ_lt; auto. Qed.

Lemma qs_move x i :
  In (x, Move i) (pairs P) -> qs x (Move i) = cost P x (Move i) + gs (target P x (Move i)).
Proof. intros H; unfold qs, Qstar; rewrite Gstar_gs by (apply succ_lt; auto); reflexivity. Qed.

Lemma Qstar_qs x a : In (x, a) (pairs P) -> Qstar P x a = Some (qs x a).
Proof.
  intros H; destruct a as [|i]; [reflexivity|].
  rewrite qs_move by auto; unfold Qstar; rewrite Gstar_gs by (apply succ_lt; auto); reflexivity.
Qed.

Lemma gs_goal : gs (goal P) == 0.
Proof.
  destruct (Gstar_goal P HP) as (g & E & Hg); unfold gs; rewrite E; auto.
Qed.

(** [Q*(x,u) >= G*(x)] (Bellman). *)
Lemma qs_ge_gs x a : In (x, a) (pairs P) -> gs x <= qs x a.
Proof.
  intros H; destruct a as [|i].
  - rewrite (term_pair x H); pose proof gs_goal; unfold qs; simpl; lra.
  - destruct (move_pair x i H) as [Hx Hi]; rewrite qs_move by auto.
    destruct (Gstar_le_move P HP x i (gs (target P x (Move i))) Hx Hi) as (gx & Ex & Hle).
    { apply Gstar_gs, succ_lt; auto. }
    rewrite Gstar_gs in Ex by auto; inversion Ex; subst; auto.
Qed.

(** Every state has an optimal pair: [G*(y) = min_u Q*(y,u)] (Bellman). *)
Lemma opt_action y : (y < n)%nat -> exists a, In a (actions P y) /\ qs y a == gs y.
Proof.
  intros Hy; destruct (Nat.eq_dec y (goal P)) as [->|Hng].
  - exists Term; split; [apply in_actions; auto|]; pose proof gs_goal; unfold qs; simpl; lra.
  - destruct (Gstar_opt_move P HP y (gs y) Hy Hng (Gstar_gs y Hy)) as (i & gy & Hi & Ey & E).
    assert (Hp : In (y, Move i) (pairs P)) by (apply in_pairs; split; auto; apply in_actions; eauto).
    exists (Move i); split; [apply in_actions; eauto|].
    rewrite qs_move by auto; rewrite Gstar_gs in Ey by (apply succ_lt; auto).
    inversion Ey; subst; lra.
Qed.

Lemma actions_ne y : (y < n)%nat -> actions P y <> [].
Proof. intros Hy E; destruct (opt_action y Hy) as (a & Ha & _); rewrite E in Ha; destruct Ha. Qed.

Lemma V_glb q y b : (y < n)%nat -> (forall a, In a (actions P y) -> b <= q y a) -> b <= V P q y.
Proof. intros Hy H; unfold V; apply qminl_map_glb; auto; apply actions_ne; auto. Qed.

Lemma V_le q y a : In a (actions P y) -> V P q y <= q y a.
Proof. intros H; unfold V; apply qminl_map_le; auto. Qed.

Lemma V_mono q q' y : (forall a, In a (actions P y) -> q y a <= q' y a) -> V P q y <= V P q' y.
Proof. intros H; unfold V; apply qminl_map_mono; auto. Qed.

(** ** Invariants that hold pair by pair *)

Definition pw (Inv : nat -> action -> Q -> Prop) (q : qvec) : Prop :=
  forall x a, In (x, a) (pairs P) -> Inv x a (q x a).

(** An update changes only the updated pair. *)
Lemma update_pw (Inv : nat -> action -> Q -> Prop) q x a :
  pw Inv q ->
  (forall i, a = Move i -> Inv x a (cost P x a + V P q (target P x a))) ->
  pw Inv (update P q (x, a)).
Proof.
  intros Hq Hnew x' a' H'.
  destruct (Nat.eq_dec x' x) as [->|Hne]; [destruct (action_eq_dec a' a) as [->|Hne]|].
  - destruct a as [|i]; [apply Hq; auto|].
    rewrite update_same; apply (Hnew i); auto.
  - rewrite update_other by congruence; auto.
  - rewrite update_other by congruence; auto.
Qed.

(** A run through a list of pairs keeps an invariant [Inv] kept by every update, and makes
    [Good] every move pair it updates, if an update under [Inv] makes the updated pair
    [Good]. *)
Lemma run_progress (Inv Good : nat -> action -> Q -> Prop) :
  (forall q p, In p (pairs P) -> pw Inv q -> pw Inv (update P q p)) ->
  (forall q x i, In (x, Move i) (pairs P) -> pw Inv q ->
                 Good x (Move i) (update P q (x, Move i) x (Move i))) ->
  forall ps q, (forall p, In p ps -> In p (pairs P)) -> pw Inv q ->
    pw Inv (run P q ps) /\
    forall x i, In (x, Move i) (pairs P) ->
                In (x, Move i) ps \/ Good x (Move i) (q x (Move i)) ->
                Good x (Move i) (run P q ps x (Move i)).
Proof.
  intros Hpres Hprog ps; induction ps as [|p ps IH]; intros q Hps Hq.
  - split; auto; intros x i _ [[]|H]; auto.
  - rewrite run_cons.
    assert (Hp : In p (pairs P)) by (apply Hps; left; auto).
    destruct (IH (update P q p) (fun p' H => Hps p' (or_intror H)) (Hpres q p Hp Hq))
      as [Hi Hg].
    split; auto; intros x i Hxi Hor; apply Hg; auto.
    destruct Hor as [[E|Hin]|Hgood]; [right; subst p; apply Hprog; auto | left; auto|].
    right; destruct p as [x0 a0].
    destruct (Nat.eq_dec x x0) as [<-|Hne]; [destruct (action_eq_dec (Move i) a0) as [<-|Hne]|].
    + apply Hprog; auto.
    + rewrite update_other by congruence; auto.
    + rewrite update_other by congruence; auto.
Qed.

(** After a round, [Good] holds on every move pair. *)
Lemma round_progress (Inv Good : nat -> action -> Q -> Prop) :
  (forall q p, In p (pairs P) -> pw Inv q -> pw Inv (update P q p)) ->
  (forall q x i, In (x, Move i) (pairs P) -> pw Inv q ->
                 Good x (Move i) (update P q (x, Move i) x (Move i))) ->
  forall r q, round_ok P r -> pw Inv q ->
    pw Inv (run P q r) /\
    forall x i, In (x, Move i) (pairs P) -> Good x (Move i) (run P q r x (Move i)).
Proof.
  intros Hpres Hprog r q [Hr Hall] Hq.
  destruct (run_progress Inv Good Hpres Hprog r q Hr Hq) as [H1' H2'].
  split; auto; intros x i H; apply H2'; auto; left; apply Hall, in_move_pairs; auto.
Qed.

(** [Q*] is a fixed point of every update: once [Q = Q*], it stays. *)
Lemma exact_pw q : exact P q <-> pw (fun x a v => v == qs x a) q.
Proof.
  split; intros H x a Hp.
  - destruct (H x a Hp) as (v & Ev & Hv); rewrite Qstar_qs in Ev by auto; inversion Ev; subst; auto.
  - exists (qs x a); split; [apply Qstar_qs; auto | apply H; auto].
Qed.

Lemma V_exact q y : (y < n)%nat -> (forall a, In a (actions P y) -> gs y <= q y a) ->
  (exists a, In a (actions P y) /\ q y a == gs y) -> V P q y == gs y.
Proof.
  intros Hy Hge (a & Ha & Hq).
  pose proof (V_glb q y (gs y) Hy Hge); pose proof (V_le q y a Ha); lra.
Qed.

Theorem exact_update q p : In p (pairs P) -> exact P q -> exact P (update P q p).
Proof.
  rewrite !exact_pw; intros Hp Hq; destruct p as [x a]; apply update_pw; auto.
  intros i ->; rewrite qs_move by auto.
  assert (Hy := succ_lt x i Hp).
  rewrite (V_exact q (target P x (Move i))); auto; [lra| |].
  - intros a' Ha'; rewrite (Hq _ a' (succ_pairs x i a' Hp Ha')); apply qs_ge_gs, succ_pairs; auto.
  - destruct (opt_action _ Hy) as (a' & Ha' & E); exists a'; split; auto.
    rewrite (Hq _ a' (succ_pairs x i a' Hp Ha')); auto.
Qed.

Theorem exact_run q ps :
  (forall p, In p ps -> In p (pairs P)) -> exact P q -> exact P (run P q ps).
Proof.
  revert q; induction ps as [|p ps IH]; intros q Hps Hq; [auto|].
  rewrite run_cons; apply IH; [intros; apply Hps; right; auto|].
  apply exact_update; auto; apply Hps; left; auto.
Qed.

(** ** Part A of [docs/proofs/c1.md]: from above *)

(** [h(f(x,u)) < r]; the termination pair counts as below every [r]. *)
Definition below (r : nat) (x : nat) (a : action) : Prop :=
  a = Term \/ exists k, hstar P (target P x a) = Some k /\ (k < r)%nat.

(** The invariant [I_r]: [Q >= Q*] on every pair, and [Q = Q*] on every pair with
    [h(f(x,u)) <= r - 1] (the termination pair included). *)
Definition InvA (r : nat) (x : nat) (a : action) (v : Q) : Prop :=
  qs x a <= v /\ (below r x a -> v == qs x a).

Lemma InvA_ge_gs r q x i a :
  pw (InvA r) q -> In (x, Move i) (pairs P) -> In a (actions P (target P x (Move i))) ->
  gs (target P x (Move i)) <= q (target P x (Move i)) a.
Proof.
  intros Hq Hp Ha; destruct (Hq _ a (succ_pairs x i a Hp Ha)) as [Hge _].
  pose proof (qs_ge_gs _ a (succ_pairs x i a Hp Ha)); lra.
Qed.

(** A1: if [Q(y,.) >= Q*(y,.)] then [l + V(y) >= Q*(x,u)]. *)
Lemma A1 r q x i :
  pw (InvA r) q -> In (x, Move i) (pairs P) ->
  qs x (Move i) <= cost P x (Move i) + V P q (target P x (Move i)).
Proof.
  intros Hq Hp; rewrite qs_move by auto.
  assert (gs (target P x (Move i)) <= V P q (target P x (Move i))); [|lra].
  apply V_glb; [apply succ_lt; auto|]; intros a Ha; eapply InvA_ge_gs; eauto.
Qed.

(** The successor [y] of a pair with [h(y) <= r] has an exact optimal pair under [I_r]:
    the termination pair if [y] is the goal, else by Descent a pair whose successor has
    [h <= r - 1]. *)
Lemma A2_exact_opt r q y k :
  pw (InvA r) q -> (y < n)%nat -> hstar P y = Some k -> (k <= r)%nat ->
  exists a, In a (actions P y) /\ q y a == gs y.
Proof.
  intros Hq Hy Hk Hkr; destruct (Nat.eq_dec y (goal P)) as [Eg|Hng].
  - exists Term; split; [apply in_actions; auto|].
    assert (Ht : In (y, Term) (pairs P)) by (apply in_pairs; split; auto; apply in_actions; auto).
    destruct (Hq _ _ Ht) as [_ He]; specialize (He (or_introl eq_refl)).
    rewrite Eg in *; pose proof gs_goal; unfold qs in He; simpl in He; lra.
  - destruct (hstar_descent P HP y k Hy Hng Hk) as (j & b & Hj & Ht & Hb & Hbk).
    assert (Hyj : In (y, Move j) (pairs P)).
    { apply in_pairs; split; auto; apply in_actions; eauto. }
    exists (Move j); split; [apply in_actions; eauto|].
    destruct (Hq _ _ Hyj) as [_ He].
    assert (Hbelow : below r y (Move j)) by (right; exists b; split; auto; lia).
    specialize (He Hbelow).
    rewrite qs_move in He by auto.
    destruct (tight_spec P y _ Ht) as (gx & gy & Ex & Ey & E); simpl in Ey, E.
    rewrite Gstar_gs in Ex by auto; rewrite Gstar_gs in Ey by (apply succ_lt; auto).
    inversion Ex; inversion Ey; subst; lra.
Qed.

(** A2: if moreover an optimal pair of [y] is exact, [l + V(y) = Q*(x,u)]. *)
Lemma A2 r q x i k :
  pw (InvA r) q -> In (x, Move i) (pairs P) ->
  hstar P (target P x (Move i)) = Some k -> (k <= r)%nat ->
  cost P x (Move i) + V P q (target P x (Move i)) == qs x (Move i).
Proof.
  intros Hq Hp Hk Hkr; rewrite qs_move by auto.
  assert (Hy := succ_lt x i Hp).
  rewrite (V_exact q (target P x (Move i)) Hy); [lra| |].
  - intros a Ha; eapply InvA_ge_gs; eauto.
  - eapply A2_exact_opt; eauto.
Qed.

(** Every single update keeps [I_r]. *)
Lemma InvA_update r q p : In p (pairs P) -> pw (InvA r) q -> pw (InvA r) (update P q p).
Proof.
  intros Hp Hq; destruct p as [x a]; apply update_pw; auto.
  intros i ->; split; [apply (A1 r); auto|].
  intros [E|(k & Hk & Hkr)]; [discriminate|]; apply (A2 r q x i k); auto; lia.
Qed.

(** Progress: after a round under [I_r], [I_(r+1)] holds. *)
Lemma InvA_round r q round :
  round_ok P round -> pw (InvA r) q -> pw (InvA (S r)) (run P q round).
Proof.
  intros Hr Hq.
  assert (Hprog : forall q' x i, In (x, Move i) (pairs P) -> pw (InvA r) q' ->
            below (S r) x (Move i) -> update P q' (x, Move i) x (Move i) == qs x (Move i)).
  { intros q' x i Hp Hq' [E|(k & Hk & Hkr)]; [discriminate|].
    rewrite update_same; apply (A2 r q' x i k); auto; lia. }
  destruct (round_progress (InvA r) (fun x a v => below (S r) x a -> v == qs x a)
                           (InvA_update r) Hprog round q Hr Hq) as [HI HG].
  { intros x a Hp; destruct (HI x a Hp) as [Hge Hex]; split; auto.
    intros Hb; destruct a as [|i]; [apply Hex; left; auto | apply HG; auto]. }
Qed.

Lemma InvA_rounds rs : forall r q,
  rounds_ok P rs -> pw (InvA r) q -> pw (InvA (r + length rs)) (run P q (concat rs)).
Proof.
  induction rs as [|round rs IH]; intros r q Hrs Hq; simpl.
  - rewrite Nat.add_0_r; auto.
  - rewrite run_app, <- plus_n_Sm.
    apply (IH (S r)); [intros r' H; apply Hrs; right; auto|].
    apply InvA_round; auto; apply Hrs; left; auto.
Qed.

Lemma InvA_mono r r' q : (r' <= r)%nat -> pw (InvA r) q -> pw (InvA r') q.
Proof.
  intros Hle Hq x a Hp; destruct (Hq x a Hp) as [Hge Hex]; split; auto.
  intros [E|(k & Hk & Hkr)]; apply Hex; [left; auto | right; exists k; split; auto; lia].
Qed.

Lemma R1_spec r1 :
  R1 P = Some r1 -> forall p, In p (move_pairs P) ->
  exists k, hstar P (target P (fst p) (snd p)) = Some k /\ (S k <= r1)%nat.
Proof.
  unfold R1; generalize (move_pairs P) as L; intro L; revert r1.
  induction L as [|p L IH]; simpl; intros r1 H p' Hp'; [destruct Hp'|].
  destruct (fold_right _ _ L) as [r|] eqn:E; [|discriminate].
  destruct (hstar P (target P (fst p) (snd p))) as [k|] eqn:Ek; [|discriminate].
  inversion H; subst.
  destruct Hp' as [<-|Hp']; [exists k; split; auto; lia|].
  destruct (IH r eq_refl p' Hp') as (k' & ? & ?); exists k'; split; auto; lia.
Qed.

(** [I_R1] says every pair is exact. *)
Lemma InvA_exact r1 q : R1 P = Some r1 -> pw (InvA r1) q -> exact P q.
Proof.
  intros Hr1 Hq; apply exact_pw; intros x a Hp; destruct (Hq x a Hp) as [_ He]; apply He.
  destruct a as [|i]; [left; auto|right].
  destruct (R1_spec r1 Hr1 (x, Move i)) as (k & Hk & Hkr); [apply in_move_pairs; auto|].
  exists k; split; auto.
Qed.

(** C1-corrected, Part A (the paper's Proposition 1 under (H0), (H1), [Q0 >= Q*]; the claims
    registry's [c1::corrected_statement] with [c1::ROUND_BOUND], first case; [docs/proofs/c1.md], Part A): from the end of
    round [R1 = 1 + max h(f(x,u))] on, [Q = Q*], for every order cut into rounds. *)
Theorem c1_corrected_from_above q0 r1 rs :
  (forall x a, In (x, a) (pairs P) -> exists v, Qstar P x a = Some v /\ v <= q0 x a) ->
  q0 (goal P) Term == 0 ->
  R1 P = Some r1 -> rounds_ok P rs -> (r1 <= length rs)%nat ->
  exact P (run P q0 (concat rs)).
Proof.
  intros Habove H0 Hr1 Hrs Hlen.
  assert (HI0 : pw (InvA 0) q0).
  { intros x a Hp; split.
    - destruct (Habove x a Hp) as (v & Ev & Hv); rewrite Qstar_qs in Ev by auto.
      inversion Ev; subst; auto.
    - intros [->|(k & _ & Hk)]; [|lia].
      rewrite (term_pair x Hp); unfold qs; simpl; auto. }
  apply (InvA_exact r1); auto.
  apply (InvA_mono (0 + length rs)); [lia|]; apply InvA_rounds; auto.
Qed.

(** ** Part B of [docs/proofs/c1.md]: every move costs [>= c > 0], any [Q0] *)

(** The invariant of the lower run: [Q <= Q*], [J_t] ([Q >= min(Q*, t)]), and the
    termination pair held at 0. *)
Definition InvB (t : Q) (x : nat) (a : action) (v : Q) : Prop :=
  v <= qs x a /\ (qs x a <= v \/ t <= v) /\ (a = Term -> v == 0).

Lemma V_bounds t q y :
  (y < n)%nat -> (forall a, In a (actions P y) -> InvB t y a (q y a)) ->
  V P q y <= gs y /\ Qmin2 (gs y) t <= V P q y.
Proof.
  intros Hy Hq; split.
  - destruct (opt_action y Hy) as (a & Ha & E); destruct (Hq a Ha) as [Hle _].
    pose proof (V_le q y a Ha); lra.
  - apply V_glb; auto; intros a Ha.
    assert (Hp : In (y, a) (pairs P)) by (apply in_pairs; auto).
    destruct (Hq a Ha) as [_ [[Hge|Hge] _]].
    + pose proof (qs_ge_gs _ a Hp); pose proof (Qmin2_l (gs y) t); lra.
    + pose proof (Qmin2_r (gs y) t); lra.
Qed.

(** B3 ([Q(y,.) <= Q*(y,.)] gives [l + V(y) <= Q*(x,u)]) and B1 ([l >= c] and
    [Q(y,.) >= min(Q*(y,.), t)] give [l + V(y) >= min(Q*(x,u), t + c)]). *)
Lemma B1_B3 t c q x i :
  pw (InvB t) q -> In (x, Move i) (pairs P) -> c <= cost P x (Move i) ->
  cost P x (Move i) + V P q (target P x (Move i)) <= qs x (Move i) /\
  (qs x (Move i) <= cost P x (Move i) + V P q (target P x (Move i)) \/
   t + c <= cost P x (Move i) + V P q (target P x (Move i))).
Proof.
  intros Hq Hp Hc; rewrite qs_move by auto.
  destruct (V_bounds t q (target P x (Move i))) as [Hle Hm].
  { apply succ_lt; auto. }
  { intros a Ha; apply Hq, succ_pairs; auto. }
  split; [lra|].
  destruct (Qmin2_cases (gs (target P x (Move i))) t) as [E|E]; rewrite E in Hm;
    [left | right]; lra.
Qed.

Section Costs.
Variable c : Q.
Hypothesis Hc : 0 < c.
Hypothesis Hcost : forall x i, In (x, Move i) (pairs P) -> c <= cost P x (Move i).

Lemma InvB_update t q p : In p (pairs P) -> pw (InvB t) q -> pw (InvB t) (update P q p).
Proof.
  intros Hp Hq; destruct p as [x a]; apply update_pw; auto.
  intros i ->; destruct (B1_B3 t c q x i Hq Hp (Hcost x i Hp)) as [Hle [Hge|Hge]].
  - split; auto; split; [left; auto | discriminate].
  - split; auto; split; [right; lra | discriminate].
Qed.

(** After a round under [J_t], [J_(t+c)] holds. *)
Lemma InvB_round t q round :
  round_ok P round -> pw (InvB t) q -> pw (InvB (t + c)) (run P q round).
Proof.
  intros Hr Hq.
  assert (Hprog : forall q' x i, In (x, Move i) (pairs P) -> pw (InvB t) q' ->
            qs x (Move i) <= update P q' (x, Move i) x (Move i) \/
            t + c <= update P q' (x, Move i) x (Move i)).
  { intros q' x i Hp Hq'; rewrite update_same.
    apply (B1_B3 t c q' x i Hq' Hp (Hcost x i Hp)). }
  destruct (round_progress (InvB t) (fun x a v => qs x a <= v \/ t + c <= v)
                           (InvB_update t) Hprog round q Hr Hq) as [HI HG].
  intros x a Hp; destruct (HI x a Hp) as (Hle & _ & Ht); split; [auto|split; [|auto]].
  destruct a as [|i]; [left; unfold qs; simpl; specialize (Ht eq_refl); lra | apply HG; auto].
Qed.

Lemma InvB_mono t t' q : t' <= t -> pw (InvB t) q -> pw (InvB t') q.
Proof.
  intros Hle Hq x a Hp; destruct (Hq x a Hp) as (H1' & [H2|H2] & H3); split; auto; split; auto.
  right; lra.
Qed.

Lemma InvB_rounds rs : forall t q,
  rounds_ok P rs -> pw (InvB t) q ->
  pw (InvB (t + inject_Z (Z.of_nat (length rs)) * c)) (run P q (concat rs)).
Proof.
  induction rs as [|round rs IH]; intros t q Hrs Hq.
  - apply (InvB_mono t); auto; change (inject_Z (Z.of_nat (length []))) with (inject_Z 0).
    change (inject_Z 0) with 0; lra.
  - change (concat (round :: rs)) with (round ++ concat rs); rewrite run_app.
    apply (InvB_mono (t + c + inject_Z (Z.of_nat (length rs)) * c)).
    + change (length (round :: rs)) with (S (length rs)).
      rewrite Nat2Z.inj_succ, <- Z.add_1_r, inject_Z_plus; change (inject_Z 1) with 1; lra.
    + apply IH; [intros r' H; apply Hrs; right; auto|].
      apply InvB_round; auto; apply Hrs; left; auto.
Qed.

End Costs.

(** ** Monotonicity (B2) *)

Definition qle (q q' : qvec) : Prop := forall x a, In (x, a) (pairs P) -> q x a <= q' x a.

Lemma update_mono q q' p : In p (pairs P) -> qle q q' -> qle (update P q p) (update P q' p).
Proof.
  intros Hp Hq x a Ha; destruct p as [x0 [|i]]; [apply Hq; auto|].
  destruct (Nat.eq_dec x x0) as [->|Hne]; [destruct (action_eq_dec a (Move i)) as [->|Hne]|].
  - rewrite !update_same.
    assert (V P q (target P x0 (Move i)) <= V P q' (target P x0 (Move i))); [|lra].
    apply V_mono; intros a' Ha'; apply Hq, succ_pairs; auto.
  - rewrite !update_other by congruence; auto.
  - rewrite !update_other by congruence; auto.
Qed.

Lemma run_mono q q' ps :
  (forall p, In p ps -> In p (pairs P)) -> qle q q' -> qle (run P q ps) (run P q' ps).
Proof.
  revert q q'; induction ps as [|p ps IH]; intros q q' Hps Hq; [auto|].
  rewrite !run_cons; apply IH; [intros; apply Hps; right; auto|].
  apply update_mono; auto; apply Hps; left; auto.
Qed.

Lemma rounds_pairs rs : rounds_ok P rs -> forall p, In p (concat rs) -> In p (pairs P).
Proof.
  intros Hrs p Hp; apply in_concat in Hp as (r & Hr & Hp); apply (proj1 (Hrs r Hr)); auto.
Qed.

(** C1-corrected, Part B (the paper's Proposition 1 under (H0), (H1), every move cost
    [>= c > 0], any [Q0]; the claims registry's [c1::corrected_statement] with [c1::ROUND_BOUND], second case;
    [docs/proofs/c1.md], Part B): the run from [Q0] lies between the runs from [min(Q0, Q* )]
    and [max(Q0, Q* )] (B2); the upper one is exact after [R1] rounds (Part A), the lower one
    once [m + R c >= max Q*] (B1, B3), [m <= Q0] on the move pairs. *)
Theorem c1_corrected_from_below q0 r1 c m qm rs :
  q0 (goal P) Term == 0 ->
  R1 P = Some r1 -> 0 < c ->
  (forall x i, In (x, Move i) (pairs P) -> c <= cost P x (Move i)) ->
  (forall x i, In (x, Move i) (pairs P) -> exists v, Qstar P x (Move i) = Some v /\ v <= qm) ->
  (forall x i, In (x, Move i) (pairs P) -> m <= q0 x (Move i)) ->
  rounds_ok P rs -> (r1 <= length rs)%nat ->
  qm - m <= inject_Z (Z.of_nat (length rs)) * c ->
  exact P (run P q0 (concat rs)).
Proof.
  intros H0 Hr1 Hc Hcost Hqm Hm Hrs Hlen Hgap.
  set (lo := fun x a => Qmin2 (q0 x a) (qs x a)).
  set (hi := fun x a => Qmax2 (q0 x a) (qs x a)).
  assert (Hhi : exact P (run P hi (concat rs))).
  { apply (c1_corrected_from_above hi r1); auto.
    - intros x a Hp; exists (qs x a); split; [apply Qstar_qs; auto | apply Qmax2_r].
    - unfold hi, qs; simpl.
      destruct (Qmax2_cases (q0 (goal P) Term) 0) as [E|E]; rewrite E; lra. }
  assert (Hlo0 : pw (InvB m) lo).
  { intros x a Hp; unfold lo; split; [apply Qmin2_r|].
    destruct a as [|i].
    - unfold qs; simpl; rewrite (term_pair x Hp).
      destruct (Qmin2_cases (q0 (goal P) Term) 0) as [E|E]; rewrite E; split; try left; lra.
    - split; [|discriminate].
      destruct (Qmin2_cases (q0 x (Move i)) (qs x (Move i))) as [E|E]; rewrite E;
        [right; apply Hm; auto | left; lra]. }
  assert (Hlo : exact P (run P lo (concat rs))).
  { pose proof (InvB_rounds c Hc Hcost rs m lo Hrs Hlo0) as HB.
    apply exact_pw; intros x a Hp; destruct (HB x a Hp) as (Hle & [Hge|Hge] & Ht); [lra|].
    destruct a as [|i]; [unfold qs; simpl; apply Ht; auto|].
    destruct (Hqm x i Hp) as (v & Ev & Hv); rewrite Qstar_qs in Ev by auto.
    inversion Ev; subst; lra. }
  assert (Hl : qle (run P lo (concat rs)) (run P q0 (concat rs))).
  { apply run_mono; [apply rounds_pairs; auto|]; intros x a _; apply Qmin2_l. }
  assert (Hh : qle (run P q0 (concat rs)) (run P hi (concat rs))).
  { apply run_mono; [apply rounds_pairs; auto|]; intros x a _; apply Qmax2_l. }
  apply exact_pw; apply exact_pw in Hlo, Hhi; intros x a Hp.
  specialize (Hlo x a Hp); specialize (Hhi x a Hp); specialize (Hl x a Hp); specialize (Hh x a Hp).
  cbv beta in *; lra.
Qed.

(** ** The round bound: what [round_bound] guarantees *)

Lemma above_spec q0 :
  above P q0 = true ->
  forall x i, In (x, Move i) (pairs P) ->
  exists v, Qstar P x (Move i) = Some v /\ v <= q0 x (Move i).
Proof.
  unfold above; rewrite forallb_forall; intros H x i Hp.
  specialize (H (x, Move i) (proj2 (in_move_pairs P _) (conj Hp eq_refl))); cbn [fst snd] in H.
  destruct (Qstar P x (Move i)) as [v|]; [apply Qle_bool_iff in H; eauto | discriminate].
Qed.

Lemma min_cost_in c :
  min_cost P = Some c -> In c (map (fun p => cost P (fst p) (snd p)) (move_pairs P)).
Proof.
  unfold min_cost; intros H.
  destruct (map (fun p => cost P (fst p) (snd p)) (move_pairs P)) as [|c0 cs]; [discriminate|].
  inversion H; subst; apply (qminl_in (c0 :: cs)); discriminate.
Qed.

Lemma min_cost_spec c :
  min_cost P = Some c -> forall x i, In (x, Move i) (pairs P) -> c <= cost P x (Move i).
Proof.
  unfold min_cost; intros H x i Hp.
  assert (Hin : In (x, Move i) (move_pairs P)) by (apply in_move_pairs; auto).
  assert (E : c = qminl (map (fun p => cost P (fst p) (snd p)) (move_pairs P))).
  { destruct (map (fun p => cost P (fst p) (snd p)) (move_pairs P)) as [|c0 cs];
      [discriminate | inversion H; auto]. }
  rewrite E; apply (qminl_map_le (fun p => cost P (fst p) (snd p)) _ (x, Move i) Hin).
Qed.

Lemma qmax_spec qm :
  qmax_star P = Some qm -> forall p, In p (move_pairs P) ->
  exists v, Qstar P (fst p) (snd p) = Some v /\ v <= qm.
Proof.
  unfold qmax_star; generalize (move_pairs P) as L; intro L; revert qm.
  induction L as [|p L IH]; simpl; intros qm H p' Hp'; [destruct Hp'|].
  destruct (fold_right _ _ L) as [a|] eqn:E; [|discriminate].
  destruct (Qstar P (fst p) (snd p)) as [v|] eqn:Ev; [|discriminate].
  inversion H; subst.
  destruct Hp' as [<-|Hp']; [exists v; split; auto; apply Qmax2_r|].
  destruct (IH a eq_refl p' Hp') as (v' & ? & ?); exists v'; split; auto.
  pose proof (Qmax2_l a v); lra.
Qed.

Lemma m0_spec q0 : forall p, In p (move_pairs P) -> m0 P q0 <= q0 (fst p) (snd p).
Proof.
  unfold m0; generalize (move_pairs P) as L; intro L.
  induction L as [|p L IH]; simpl; intros p' Hp'; [destruct Hp'|].
  destruct Hp' as [<-|Hp']; [apply Qmin2_l|].
  eapply Qle_trans; [apply Qmin2_r | apply IH; auto].
Qed.

(** C1-corrected (the paper's Proposition 1, corrected; the claims registry's
    [c1::corrected_statement]; [docs/proofs/c1.md]) for every well-formed finite problem: under (H0)
    [Q0(xg,uT) = 0] (and the termination pair held), (H1) every state reaching the goal, and
    (H2) as checked by [round_bound] ([Q0 >= Q*], or every move cost [>= c > 0]), for every
    list of rounds [rs] (each round: pairs of the problem, every move pair at least once) with
    at least [R = round_bound P q0] rounds, [Q = Q*] at the end of the rounds, and every
    further update keeps [Q = Q*]. *)
Theorem c1_corrected q0 R rs :
  q0 (goal P) Term == 0 ->
  round_bound P q0 = Some R ->
  rounds_ok P rs -> (R <= length rs)%nat ->
  exact P (run P q0 (concat rs)) /\
  forall ps, (forall p, In p ps -> In p (pairs P)) -> exact P (run P q0 (concat rs ++ ps)).
Proof.
  intros H0 HR Hrs Hlen.
  enough (He : exact P (run P q0 (concat rs))).
  { split; auto; intros ps Hps; rewrite run_app; apply exact_run; auto. }
  unfold round_bound in HR.
  destruct (R1 P) as [r1|] eqn:Er1; [|discriminate].
  destruct (above P q0) eqn:Ea.
  - inversion HR; subst R.
    apply (c1_corrected_from_above q0 r1); auto.
    intros x [|i] Hp; [|apply above_spec; auto].
    exists 0; split; [reflexivity | rewrite (term_pair x Hp); lra].
  - destruct (min_cost P) as [c|] eqn:Ec; [|discriminate].
    destruct (Qle_bool c 0) eqn:Ec0; [discriminate|].
    destruct (qmax_star P) as [qm|] eqn:Eq; [|discriminate].
    inversion HR; subst R.
    assert (Hc : 0 < c) by (apply Qnot_le_lt; intro H; apply Qle_bool_iff in H; congruence).
    apply (c1_corrected_from_below q0 r1 c (m0 P q0) qm); auto.
    + apply min_cost_spec; auto.
    + intros x i Hp; apply (qmax_spec qm Eq (x, Move i)); apply in_move_pairs; auto.
    + intros x i Hp; apply (m0_spec q0 (x, Move i)); apply in_move_pairs; auto.
    + lia.
    + apply ceil_rounds_spec; auto; lia.
Qed.

(** Under (H1) and (H2), [round_bound] is finite. *)
Lemma R1_some : exists r1, R1 P = Some r1.
Proof.
  assert (H : forall p, In p (move_pairs P) ->
              exists k, hstar P (target P (fst p) (snd p)) = Some k).
  { intros [x a] Hp; apply in_move_pairs in Hp as [Hp Hm]; destruct a as [|i]; [discriminate|].
    cbn [fst snd]; assert (Hy := succ_lt x i Hp).
    apply (hstar_some P HP _ (gs (target P x (Move i))) Hy (Gstar_gs _ Hy)). }
  revert H; unfold R1; generalize (move_pairs P) as L; intro L.
  induction L as [|p L IH]; intros H; simpl; [eauto|].
  destruct IH as (r & Er); [intros; apply H; right; auto|]; rewrite Er.
  destruct (H p (or_introl eq_refl)) as (k & Ek); rewrite Ek; eauto.
Qed.

Lemma qmax_some : exists qm, qmax_star P = Some qm.
Proof.
  assert (H : forall p, In p (move_pairs P) -> exists v, Qstar P (fst p) (snd p) = Some v).
  { intros [x a] Hp; apply in_move_pairs in Hp as [Hp _]; rewrite Qstar_qs; eauto. }
  revert H; unfold qmax_star; generalize (move_pairs P) as L; intro L.
  induction L as [|p L IH]; intros H; simpl; [eauto|].
  destruct IH as (r & Er); [intros; apply H; right; auto|]; rewrite Er.
  destruct (H p (or_introl eq_refl)) as (k & Ek); rewrite Ek; eauto.
Qed.

Lemma round_bound_some q0 :
  ((forall x a, In (x, a) (pairs P) -> exists v, Qstar P x a = Some v /\ v <= q0 x a) \/
   (exists c, 0 < c /\ forall x i, In (x, Move i) (pairs P) -> c <= cost P x (Move i))) ->
  exists R, round_bound P q0 = Some R.
Proof.
  intros H2; unfold round_bound.
  destruct R1_some as (r1 & ->).
  destruct (above P q0) eqn:Ea; [eauto|].
  destruct H2 as [Hab|(c & Hc & Hcost)].
  - exfalso; assert (above P q0 = true); [|congruence].
    unfold above; apply forallb_forall; intros [x a] Hp; apply in_move_pairs in Hp as [Hp _].
    cbn [fst snd]; destruct (Hab x a Hp) as (v & -> & Hv); apply Qle_bool_iff; auto.
  - destruct (min_cost P) as [c0|] eqn:Ec0.
    + apply min_cost_in, in_map_iff in Ec0 as ([x a] & E & Hp).
      apply in_move_pairs in Hp as [Hp Hm]; destruct a as [|i]; [discriminate|].
      specialize (Hcost x i Hp); cbn [fst snd] in E; subst c0.
      destruct (Qle_bool (cost P x (Move i)) 0) eqn:Ecl; [apply Qle_bool_iff in Ecl; lra|].
      destruct qmax_some as (qm & ->); eauto.
    + exfalso; unfold min_cost in Ec0; unfold above in Ea.
      destruct (move_pairs P); [discriminate | discriminate].
Qed.

(** ** The paper's form: an infinite update sequence *)

Section Infinite.
Variable s : nat -> nat * action.
Hypothesis Hs : forall m, In (s m) (pairs P).
Hypothesis Hfair : forall p, In p (move_pairs P) -> forall k, exists m, (k <= m)%nat /\ s m = p.

Lemma cover L k :
  (forall p, In p L -> In p (move_pairs P)) ->
  exists m, (k <= m)%nat /\ forall p, In p L -> In p (map s (seq k (m - k))).
Proof.
  induction L as [|p L IH]; intros HL; [exists k; split; auto; intros p []|].
  destruct IH as (m1 & Hm1 & H); [intros; apply HL; right; auto|].
  destruct (Hfair p (HL p (or_introl eq_refl)) k) as (j & Hj & Ej).
  exists (Nat.max m1 (S j)); split; [lia|].
  intros p' [<-|Hp'].
  - apply in_map_iff; exists j; split; auto; apply in_seq; lia.
  - destruct (proj1 (in_map_iff _ _ _) (H p' Hp')) as (j' & E & Hj').
    apply in_seq in Hj'; apply in_map_iff; exists j'; split; auto; apply in_seq; lia.
Qed.

(** The sequence cut into [k] rounds. *)
Lemma rounds_exist k :
  exists rs, length rs = k /\ rounds_ok P rs /\ concat rs = map s (seq 0 (length (concat rs))).
Proof.
  induction k as [|k (rs & Hl & Hok & Hc)]; [exists []; simpl; split; auto; split; auto; intros r []|].
  set (N := length (concat rs)) in *.
  destruct (cover (move_pairs P) N (fun p H => H)) as (m & Hm & Hcov).
  exists (rs ++ [map s (seq N (m - N))]).
  assert (E : concat (rs ++ [map s (seq N (m - N))]) = map s (seq 0 m)).
  { rewrite concat_app; simpl; rewrite app_nil_r, Hc, <- map_app; f_equal.
    replace (seq 0 m) with (seq 0 (N + (m - N))) by (f_equal; lia).
    rewrite seq_app; reflexivity. }
  split; [rewrite app_length; simpl; lia|]; split.
  - intros r Hr; apply in_app_iff in Hr as [Hr|[<-|[]]]; [apply Hok; auto|].
    split; [|exact Hcov].
    intros p Hp; apply in_map_iff in Hp as (j & <- & _); apply Hs.
  - rewrite E, map_length, seq_length; auto.
Qed.

(** C1-corrected in the paper's form (Proposition 1: "[Q = Q*] after finitely many steps";
    the claims registry's [c1::corrected_statement] with [c1::ROUND_BOUND]): if every move pair occurs infinitely often in
    the update sequence [s], then under (H0), (H1) and (H2) the values after the first [k]
    updates equal [Q*] for every [k >= N]. *)
Theorem c1_paper_form q0 :
  q0 (goal P) Term == 0 ->
  ((forall x a, In (x, a) (pairs P) -> exists v, Qstar P x a = Some v /\ v <= q0 x a) \/
   (exists c, 0 < c /\ forall x i, In (x, Move i) (pairs P) -> c <= cost P x (Move i))) ->
  exists N, forall k, (N <= k)%nat -> exact P (run P q0 (map s (seq 0 k))).
Proof.
  intros H0 H2.
  destruct (round_bound_some q0 H2) as (R & HR).
  destruct (rounds_exist R) as (rs & Hl & Hok & Hc).
  exists (length (concat rs)); intros k Hk.
  set (N := length (concat rs)) in *.
  replace (seq 0 k) with (seq 0 (N + (k - N))) by (f_equal; lia).
  rewrite seq_app, map_app, Nat.add_0_l, <- Hc.
  apply (c1_corrected q0 R rs); auto; [lia|].
  intros p Hp; apply in_map_iff in Hp as (j & <- & _); apply Hs.
Qed.

End Infinite.

End Corrected.

(** ** The ceiling in the round bound cannot be lowered *)

(** State 0 has a self-loop of cost 1 and a move of cost 5 to the goal 1. From [Q0 = 0] the
    self-loop's value climbs by 1 per round until it meets [Q*(0, self-loop) = 6]. *)
Definition climb : problem := {|
  nstates := 2;
  goal := 1;
  moves := fun x => match x with O => [(0%nat, 1); (1%nat, 5)] | _ => [] end
|}.

Lemma repeat_rounds_ok P r k : round_ok P r -> rounds_ok P (repeat r k).
Proof. intros H r' Hr'; apply repeat_spec in Hr'; subst; auto. Qed.

Lemma pairs_round_ok P : round_ok P (pairs P).
Proof. split; auto; intros p Hp; apply in_move_pairs in Hp as [Hp _]; auto. Qed.

(** The bound [R = max(R1, ceil((max Q* - m) / c))] of C1-corrected is attained: on [climb]
    from [Q0 = 0], [round_bound] is 6, and under the cyclic order [Q <> Q*] after 5 rounds
    while [Q = Q*] after 6. So a bound one round smaller (e.g. [ceil(...) - 1]) is false. *)
Theorem c1_round_bound_tight :
  wf climb /\ (forall x, (x < nstates climb)%nat -> Gstar climb x <> None) /\
  round_bound climb q_zero = Some 6%nat /\
  rounds_ok climb (repeat (pairs climb) 6) /\
  ~ exact climb (run climb q_zero (concat (repeat (pairs climb) 5))) /\
  exact climb (run climb q_zero (concat (repeat (pairs climb) 6))).
Proof.
  assert (Hwf : wf climb).
  { split; [simpl; lia|]; intros x Hx y l H; simpl in Hx.
    destruct x as [|[|x]]; simpl in H; [|tauto | lia].
    destruct H as [E|[E|[]]]; inversion E; simpl; split; try lia; lra. }
  assert (H1 : forall x, (x < nstates climb)%nat -> Gstar climb x <> None).
  { intros x Hx; simpl in Hx; destruct x as [|[|x]]; [discriminate | discriminate | lia]. }
  assert (HR : round_bound climb q_zero = Some 6%nat) by (vm_compute; reflexivity).
  assert (Hok : forall k, rounds_ok climb (repeat (pairs climb) k)).
  { intros k; apply repeat_rounds_ok, pairs_round_ok. }
  split; [auto|]; split; [auto|]; split; [auto|]; split; [auto|]; split.
  - intros H; destruct (H 0%nat (Move 0) ltac:(vm_compute; auto)) as (v & Ev & Hv).
    vm_compute in Ev; inversion Ev; subst v; vm_compute in Hv; discriminate Hv.
  - refine (proj1 (c1_corrected climb Hwf H1 q_zero 6%nat _ _ _ _ _));
      [reflexivity | exact HR | apply Hok | simpl; lia].
Qed.

(** A chain [0 -> 1 -> 2] (goal 2), every move of cost 1, started above [Q*]. *)
Definition chain3 : problem := {|
  nstates := 3;
  goal := 2;
  moves := fun x => match x with O => [(1%nat, 1)] | S O => [(2%nat, 1)] | _ => [] end
|}.

Definition q_ten : qvec := fun _ a => match a with Term => 0 | Move _ => 10 end.

(** The bound [R1 = 1 + max h(f(x,u))] of Part A is attained: on [chain3] from [Q0 = 10 >= Q*],
    [round_bound] is [R1 = 2], and under the cyclic order [Q <> Q*] after 1 round while
    [Q = Q*] after 2. *)
Theorem c1_round_bound_tight_above :
  wf chain3 /\ (forall x, (x < nstates chain3)%nat -> Gstar chain3 x <> None) /\
  round_bound chain3 q_ten = Some 2%nat /\ R1 chain3 = Some 2%nat /\
  ~ exact chain3 (run chain3 q_ten (concat (repeat (pairs chain3) 1))) /\
  exact chain3 (run chain3 q_ten (concat (repeat (pairs chain3) 2))).
Proof.
  assert (Hwf : wf chain3).
  { split; [simpl; lia|]; intros x Hx y l H; simpl in Hx.
    destruct x as [|[|[|x]]]; simpl in H; try tauto; try lia;
      destruct H as [E|[]]; inversion E; simpl; split; try lia; lra. }
  assert (H1 : forall x, (x < nstates chain3)%nat -> Gstar chain3 x <> None).
  { intros x Hx; simpl in Hx; destruct x as [|[|[|x]]]; try discriminate; lia. }
  split; [auto|]; split; [auto|]; split; [vm_compute; reflexivity|].
  split; [vm_compute; reflexivity|]; split.
  - intros H; destruct (H 0%nat (Move 0) ltac:(vm_compute; auto)) as (v & Ev & Hv).
    vm_compute in Ev; inversion Ev; subst v; vm_compute in Hv; discriminate Hv.
  - refine (proj1 (c1_corrected chain3 Hwf H1 q_ten 2%nat _ _ _ _ _));
      [reflexivity | vm_compute; reflexivity | | simpl; lia].
    apply repeat_rounds_ok, pairs_round_ok.
Qed.
