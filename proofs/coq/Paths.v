(** * Paths and optimal values: [Gstar] and [hstar] mean what docs/spec.md §1 says

    [Gstar_least] and [Gstar_attained]: [G*(x)] is the least cost over all goal-reaching move
    sequences from [x] (of any length), attained by one, and [+oo] exactly when none exists
    ([Gstar_none]). [Gstar_le_move], [Gstar_opt_move] and [Gstar_goal] are the Bellman equation
    [G*(x) = min_u (l(x,u) + G*(f(x,u)))], [G*(xg) = 0] (docs/spec.md §1: [G*(x) = min_u Q*(x,u)]).
    [hstar_attained] and [hstar_least]: [h(x)] is the fewest moves of an optimal goal-reaching
    sequence from [x]; [hstar_descent] is the Descent step of [docs/proofs/c1.md]. *)

From Coq Require Import QArith List Lia Lqa.
From Truecost Require Import Model.
Import ListNotations.

Open Scope Q_scope.

Arguments target : simpl never.
Arguments cost : simpl never.

(** ** Minima over lists *)

Lemma Qmin2_l a b : Qmin2 a b <= a.
Proof.
  unfold Qmin2; destruct (Qle_bool a b) eqn:E; [lra|].
  apply Qlt_le_weak, Qnot_le_lt; intro H; apply Qle_bool_iff in H; congruence.
Qed.

Lemma Qmin2_r a b : Qmin2 a b <= b.
Proof.
  unfold Qmin2; destruct (Qle_bool a b) eqn:E; [apply Qle_bool_iff; auto | lra].
Qed.

Lemma Qmin2_cases a b : Qmin2 a b = a \/ Qmin2 a b = b.
Proof. unfold Qmin2; destruct (Qle_bool a b); auto. Qed.

Lemma Qmax2_l a b : a <= Qmax2 a b.
Proof.
  unfold Qmax2; destruct (Qle_bool a b) eqn:E; [apply Qle_bool_iff; auto | lra].
Qed.

Lemma Qmax2_r a b : b <= Qmax2 a b.
Proof.
  unfold Qmax2; destruct (Qle_bool a b) eqn:E; [lra|].
  apply Qlt_le_weak, Qnot_le_lt; intro H; apply Qle_bool_iff in H; congruence.
Qed.

Lemma fold_Qmin2_le t a :
  fold_right Qmin2 a t <= a /\ forall x, In x t -> fold_right Qmin2 a t <= x.
Proof.
  induction t as [|b t IH]; simpl; [split; [lra | tauto]|].
  destruct IH as [IH1 IH2]; split.
  - eapply Qle_trans; [apply Qmin2_r | exact IH1].
  - intros x [<-|Hx]; [apply Qmin2_l|].
    eapply Qle_trans; [apply Qmin2_r | auto].
Qed.

Lemma qminl_le l x : In x l -> qminl l <= x.
Proof.
  destruct l as [|a t]; simpl; [tauto|].
  intros [E|Hx]; [subst; apply (proj1 (fold_Qmin2_le t x)) |].
  apply (proj2 (fold_Qmin2_le t a)); auto.
Qed.

Lemma qminl_glb l b : l <> [] -> (forall x, In x l -> b <= x) -> b <= qminl l.
Proof.
  destruct l as [|a t]; [congruence|]; intros _ H; simpl.
  induction t as [|c t IH]; simpl; [apply H; simpl; auto|].
  unfold Qmin2 at 1; destruct (Qle_bool c _).
  - apply H; simpl; auto.
  - apply IH; intros x Hx; apply H; simpl in *; tauto.
Qed.

Lemma qminl_in l : l <> [] -> In (qminl l) l.
Proof.
  destruct l as [|a t]; [congruence|]; intros _; simpl.
  induction t as [|c t IH]; simpl; [auto|].
  destruct (Qmin2_cases c (fold_right Qmin2 a t)) as [->| ->]; simpl; [auto|].
  simpl in IH; tauto.
Qed.

Lemma qminl_map_le {A} (f : A -> Q) l a : In a l -> qminl (map f l) <= f a.
Proof. intros H; apply qminl_le, in_map, H. Qed.

Lemma qminl_map_glb {A} (f : A -> Q) l b :
  l <> [] -> (forall a, In a l -> b <= f a) -> b <= qminl (map f l).
Proof.
  intros Hl H; apply qminl_glb.
  - destruct l; simpl; congruence.
  - intros x Hx; apply in_map_iff in Hx as (a & <- & Ha); auto.
Qed.

Lemma qminl_map_mono {A} (f g : A -> Q) l :
  (forall a, In a l -> f a <= g a) -> qminl (map f l) <= qminl (map g l).
Proof.
  intros H; destruct l as [|a t]; [simpl; lra|].
  apply qminl_map_glb; [congruence|].
  intros b Hb; eapply Qle_trans; [apply qminl_map_le, Hb | auto].
Qed.

Lemma omin_cases a b v : omin a b = Some v -> a = Some v \/ b = Some v.
Proof.
  destruct a as [u|], b as [w|]; simpl; intros H; inversion H; auto.
  destruct (Qmin2_cases u w) as [E|E]; rewrite E; auto.
Qed.

Lemma omin_le_l a b v : a = Some v -> exists w, omin a b = Some w /\ w <= v.
Proof.
  intros ->; destruct b as [u|]; simpl; eexists; split; eauto; [apply Qmin2_l | lra].
Qed.

Lemma omin_le_r a b v : b = Some v -> exists w, omin a b = Some w /\ w <= v.
Proof.
  intros ->; destruct a as [u|]; simpl; eexists; split; eauto; [apply Qmin2_r | lra].
Qed.

Lemma ominl_in l v : ominl l = Some v -> In (Some v) l.
Proof.
  induction l as [|a t IH]; simpl; [congruence|].
  intros H; apply omin_cases in H as [H|H]; auto.
Qed.

Lemma ominl_le l v : In (Some v) l -> exists w, ominl l = Some w /\ w <= v.
Proof.
  induction l as [|a t IH]; simpl; [tauto|].
  intros [->|H].
  - apply omin_le_l; auto.
  - destruct (IH H) as (w & Hw & Hle).
    destruct (omin_le_r a (ominl t) w Hw) as (w' & ? & ?).
    exists w'; split; auto; lra.
Qed.

Lemma nmin_cases a b v : nmin a b = Some v -> a = Some v \/ b = Some v.
Proof.
  destruct a as [u|], b as [w|]; simpl; intros H; inversion H; auto.
  destruct (Nat.min_spec u w) as [[_ E]|[_ E]]; rewrite E; auto.
Qed.

Lemma nmin_le_l a b v : a = Some v -> exists w, nmin a b = Some w /\ (w <= v)%nat.
Proof. intros ->; destruct b as [u|]; simpl; eexists; split; eauto; lia. Qed.

Lemma nmin_le_r a b v : b = Some v -> exists w, nmin a b = Some w /\ (w <= v)%nat.
Proof. intros ->; destruct a as [u|]; simpl; eexists; split; eauto; lia. Qed.

Lemma nminl_in l v : nminl l = Some v -> In (Some v) l.
Proof.
  induction l as [|a t IH]; simpl; [congruence|].
  intros H; apply nmin_cases in H as [H|H]; auto.
Qed.

Lemma nminl_le l v : In (Some v) l -> exists w, nminl l = Some w /\ (w <= v)%nat.
Proof.
  induction l as [|a t IH]; simpl; [tauto|].
  intros [->|H].
  - apply nmin_le_l; auto.
  - destruct (IH H) as (w & Hw & Hle).
    destruct (nmin_le_r a (nminl t) w Hw) as (w' & ? & ?).
    exists w'; split; auto; lia.
Qed.

Lemma nth_map_seq {A} (f : nat -> A) n x d :
  (x < n)%nat -> nth x (map f (seq 0 n)) d = f x.
Proof.
  intros Hx; rewrite (nth_indep _ d (f 0%nat)) by (rewrite map_length, seq_length; auto).
  rewrite map_nth, seq_nth; auto.
Qed.

(** ** Moves and walks *)

Section Walks.
Variable P : problem.
Hypothesis HP : wf P.
Notation n := (nstates P).

Lemma move_in x i :
  (i < length (moves P x))%nat ->
  In (target P x (Move i), cost P x (Move i)) (moves P x).
Proof.
  intros Hi; unfold target, cost; rewrite <- surjective_pairing; apply nth_In; auto.
Qed.

Lemma in_move x y l :
  In (y, l) (moves P x) ->
  exists i, (i < length (moves P x))%nat /\ target P x (Move i) = y /\ cost P x (Move i) = l.
Proof.
  intros H; destruct (In_nth _ _ (x, 0) H) as (i & Hi & E).
  exists i; unfold target, cost; rewrite E; auto.
Qed.

Lemma wf_move x i :
  (x < n)%nat -> (i < length (moves P x))%nat ->
  (target P x (Move i) < n)%nat /\ 0 <= cost P x (Move i).
Proof. intros Hx Hi; apply (proj2 HP x Hx), move_in, Hi. Qed.

Lemma wend_app x a b : wend P x (a ++ b) = wend P (wend P x a) b.
Proof. revert x; induction a; simpl; auto. Qed.

Lemma wcost_app x a b : wcost P x (a ++ b) == wcost P x a + wcost P (wend P x a) b.
Proof. revert x; induction a as [|i a IH]; intros x; simpl; [lra | rewrite IH; lra]. Qed.

Lemma wvalid_app x a b : wvalid P x (a ++ b) <-> wvalid P x a /\ wvalid P (wend P x a) b.
Proof. revert x; induction a as [|i a IH]; intros x; simpl; [tauto | rewrite IH; tauto]. Qed.

Lemma wend_lt x w : (x < n)%nat -> wvalid P x w -> (wend P x w < n)%nat.
Proof.
  revert x; induction w as [|i w IH]; intros x Hx Hw; simpl; auto.
  destruct Hw as [Hi Hw]; apply IH; auto; apply wf_move; auto.
Qed.

Lemma wcost_nonneg x w : (x < n)%nat -> wvalid P x w -> 0 <= wcost P x w.
Proof.
  revert x; induction w as [|i w IH]; intros x Hx Hw; simpl; [lra|].
  destruct Hw as [Hi Hw]; destruct (wf_move x i Hx Hi).
  specialize (IH _ H Hw); lra.
Qed.

(** The states a walk visits. *)
Fixpoint trace (x : nat) (w : list nat) : list nat :=
  x :: match w with [] => [] | i :: w' => trace (target P x (Move i)) w' end.

Lemma trace_length x w : length (trace x w) = S (length w).
Proof. revert x; induction w; intros; simpl; auto. Qed.

Lemma trace_lt x w z : (x < n)%nat -> wvalid P x w -> In z (trace x w) -> (z < n)%nat.
Proof.
  revert x; induction w as [|i w IH]; intros x Hx Hw Hz; simpl in Hz.
  - destruct Hz as [<-|[]]; auto.
  - destruct Hz as [<-|Hz]; auto.
    destruct Hw; apply (IH _ (proj1 (wf_move x i Hx H)) H0 Hz).
Qed.

Lemma in_trace_split x w z :
  In z (trace x w) -> exists w1 w3, w = w1 ++ w3 /\ wend P x w1 = z.
Proof.
  revert x; induction w as [|i w IH]; intros x Hz; simpl in Hz.
  - destruct Hz as [<-|[]]; exists [], []; auto.
  - destruct Hz as [<-|Hz]; [exists [], (i :: w); auto|].
    destruct (IH _ Hz) as (w1 & w3 & -> & E); exists (i :: w1), w3; auto.
Qed.

(** A walk visiting a state twice has a cycle [w2]. *)
Lemma repeat_split x w :
  ~ NoDup (trace x w) ->
  exists w1 w2 w3, w = w1 ++ w2 ++ w3 /\ w2 <> [] /\ wend P x w1 = wend P x (w1 ++ w2).
Proof.
  revert x; induction w as [|i w IH]; intros x Hnd.
  - exfalso; apply Hnd; simpl; constructor; [simpl; auto | constructor].
  - change (trace x (i :: w)) with (x :: trace (target P x (Move i)) w) in Hnd.
    destruct (in_dec Nat.eq_dec x (trace (target P x (Move i)) w)) as [Hin|Hin].
    + destruct (in_trace_split _ _ _ Hin) as (w1 & w3 & -> & E).
      exists [], (i :: w1), w3; simpl; split; [auto | split; [congruence | auto]].
    + destruct (IH (target P x (Move i))) as (w1 & w2 & w3 & -> & Hne & E).
      { intro H; apply Hnd; constructor; auto. }
      exists (i :: w1), w2, w3; simpl; auto.
Qed.

(** Cutting out a cycle: costs are [>= 0], so the walk gets no dearer. *)
Lemma shorten x w :
  (x < n)%nat -> wvalid P x w -> (n <= length w)%nat ->
  exists w', wvalid P x w' /\ wend P x w' = wend P x w /\ wcost P x w' <= wcost P x w
             /\ (length w' < length w)%nat.
Proof.
  intros Hx Hw Hlen.
  assert (Hnd : ~ NoDup (trace x w)).
  { intros Hnd. pose proof (NoDup_incl_length Hnd (l' := seq 0 n)) as H.
    rewrite trace_length, seq_length in H.
    enough (S (length w) <= n)%nat by lia.
    apply H; intros z Hz; apply in_seq; split; [lia|].
    simpl; eapply trace_lt; eauto. }
  destruct (repeat_split _ _ Hnd) as (w1 & w2 & w3 & -> & Hne & E).
  rewrite wend_app in E.
  apply wvalid_app in Hw as [Hw1 Hw23]; apply wvalid_app in Hw23 as [Hw2 Hw3].
  rewrite <- E in Hw3.
  exists (w1 ++ w3); split; [apply wvalid_app; auto|].
  split; [rewrite !wend_app, <- E; auto|].
  split.
  - assert (C1 := wcost_app x w1 (w2 ++ w3)).
    assert (C2 := wcost_app (wend P x w1) w2 w3).
    assert (C3 := wcost_app x w1 w3).
    rewrite <- E in C2.
    pose proof (wcost_nonneg _ w2 (wend_lt _ _ Hx Hw1) Hw2); lra.
  - rewrite !app_length; destruct w2; [congruence | simpl; lia].
Qed.

(** Every walk can be replaced by one with fewer than [n] moves, the same end and no more
    cost. *)
Lemma short_walk x w :
  (x < n)%nat -> wvalid P x w ->
  exists w', wvalid P x w' /\ wend P x w' = wend P x w /\ wcost P x w' <= wcost P x w
             /\ (length w' < n)%nat /\ (length w' <= length w)%nat.
Proof.
  intros Hx; remember (length w) as k eqn:Hk; revert w Hk.
  induction k as [k IH] using (well_founded_induction lt_wf); intros w Hk Hw.
  destruct (Nat.lt_ge_cases k n) as [Hlt|Hge].
  - exists w; repeat split; auto; try lra; lia.
  - destruct (shorten x w Hx Hw ltac:(lia)) as (w' & Hw' & E & C & L).
    destruct (IH (length w') ltac:(lia) w' eq_refl Hw') as (w'' & ? & E' & C' & L' & L'').
    exists w''; repeat split; auto; try congruence; try lra; lia.
Qed.

(** ** Bellman-Ford computes least costs *)

Lemma bf_0 x : (x < n)%nat -> bf P 0 x = bf_start P x.
Proof. intros Hx; unfold bf; simpl; apply nth_map_seq; auto. Qed.

Lemma bf_S k x : (x < n)%nat -> bf P (S k) x = bf_step P (bf P k) x.
Proof. intros Hx; unfold bf at 1; simpl; apply nth_map_seq; auto. Qed.

Lemma bf_sound k x g :
  (x < n)%nat -> bf P k x = Some g ->
  exists w, reaches P x w /\ wcost P x w == g /\ (length w <= k)%nat.
Proof.
  revert x g; induction k as [|k IH]; intros x g Hx H.
  - rewrite bf_0 in H by auto; unfold bf_start in H.
    destruct (Nat.eqb_spec x (goal P)); inversion H; subst.
    exists []; repeat split; simpl; auto; lra.
  - rewrite bf_S in H by auto; unfold bf_step, bf_start in H.
    apply omin_cases in H as [H|H].
    + destruct (Nat.eqb_spec x (goal P)); inversion H; subst.
      exists []; repeat split; simpl; auto; try lra; lia.
    + apply ominl_in, in_map_iff in H as ([y l] & E & Hyl); simpl in E.
      destruct (bf P k y) as [gy|] eqn:Ey; simpl in E; inversion E; subst.
      destruct (in_move _ _ _ Hyl) as (i & Hi & Ht & Hc).
      assert (Hy : (y < n)%nat) by (rewrite <- Ht; apply wf_move; auto).
      destruct (IH _ _ Hy Ey) as (w & [Hw He] & Hc' & Hl).
      exists (i :: w); unfold reaches; simpl; rewrite Ht, Hc; repeat split; auto; try lra; lia.
Qed.

Lemma bf_complete k x w :
  (x < n)%nat -> reaches P x w -> (length w <= k)%nat ->
  exists g, bf P k x = Some g /\ g <= wcost P x w.
Proof.
  revert x w; induction k as [|k IH]; intros x w Hx [Hw He] Hl.
  - destruct w; [|simpl in Hl; lia]; simpl in *.
    rewrite bf_0 by auto; unfold bf_start; rewrite He, Nat.eqb_refl.
    eexists; split; eauto; lra.
  - rewrite bf_S by auto; unfold bf_step.
    destruct w as [|i w]; simpl in *.
    + unfold bf_start; rewrite He, Nat.eqb_refl; apply omin_le_l; auto.
    + destruct Hw as [Hi Hw].
      destruct (wf_move x i Hx Hi) as [Hy Hc].
      destruct (IH _ w Hy (conj Hw He) ltac:(lia)) as (gy & Ey & Hle).
      destruct (ominl_le (map (fun yl => option_map (Qplus (snd yl)) (bf P k (fst yl)))
                              (moves P x)) (cost P x (Move i) + gy)) as (v & Ev & Hv).
      { apply in_map_iff; exists (target P x (Move i), cost P x (Move i)); simpl.
        rewrite Ey; split; auto; apply move_in; auto. }
      destruct (omin_le_r (bf_start P x) _ _ Ev) as (v' & Ev' & Hv').
      exists v'; split; auto; lra.
Qed.

(** ** [G*] is the least cost over goal-reaching sequences (docs/spec.md §1) *)

(** [G*(x)] is attained by a goal-reaching sequence (docs/spec.md §1). *)
Theorem Gstar_attained x g :
  (x < n)%nat -> Gstar P x = Some g -> exists w, reaches P x w /\ wcost P x w == g.
Proof. intros Hx H; destruct (bf_sound _ _ _ Hx H) as (w & ? & ? & _); eauto. Qed.

(** No goal-reaching sequence from [x], of any length, is cheaper than [G*(x)] (docs/spec.md §1). *)
Theorem Gstar_least x w :
  (x < n)%nat -> reaches P x w -> exists g, Gstar P x = Some g /\ g <= wcost P x w.
Proof.
  intros Hx [Hw He].
  destruct (short_walk x w Hx Hw) as (w' & Hw' & E & C & L & _).
  assert (He' : wend P x w' = goal P) by congruence.
  destruct (bf_complete n x w' Hx (conj Hw' He') ltac:(lia)) as (g & Eg & Hg).
  exists g; split; auto; lra.
Qed.

(** [G*(x) = +oo] exactly when the goal cannot be reached from [x]. *)
Theorem Gstar_none x : (x < n)%nat -> Gstar P x = None <-> ~ exists w, reaches P x w.
Proof.
  intros Hx; split.
  - intros H (w & Hw); destruct (Gstar_least x w Hx Hw) as (g & E & _); congruence.
  - intros H; destruct (Gstar P x) eqn:E; auto.
    exfalso; apply H; destruct (Gstar_attained x q Hx E) as (w & ? & _); eauto.
Qed.

Lemma Gstar_nonneg x g : (x < n)%nat -> Gstar P x = Some g -> 0 <= g.
Proof.
  intros Hx H; destruct (Gstar_attained x g Hx H) as (w & [Hw _] & Hc).
  pose proof (wcost_nonneg x w Hx Hw); lra.
Qed.

(** [G*(xg) = 0]. *)
Theorem Gstar_goal : exists g, Gstar P (goal P) = Some g /\ g == 0.
Proof.
  destruct HP as [Hg _].
  destruct (Gstar_least (goal P) [] Hg (conj I eq_refl)) as (g & E & Hle).
  exists g; split; auto; pose proof (Gstar_nonneg _ _ Hg E); simpl in Hle; lra.
Qed.

(** Bellman, one direction: [G*(x) <= l(x,u) + G*(f(x,u))]. *)
Theorem Gstar_le_move x i gy :
  (x < n)%nat -> (i < length (moves P x))%nat ->
  Gstar P (target P x (Move i)) = Some gy ->
  exists gx, Gstar P x = Some gx /\ gx <= cost P x (Move i) + gy.
Proof.
  intros Hx Hi Hy; destruct (wf_move x i Hx Hi) as [Hlt _].
  destruct (Gstar_attained _ _ Hlt Hy) as (w & [Hw He] & Hc).
  destruct (Gstar_least x (i :: w) Hx (conj (conj Hi Hw) He)) as (gx & E & Hle).
  exists gx; split; auto; simpl in Hle; lra.
Qed.

(** Bellman, the other direction: away from the goal, some move is optimal. *)
Theorem Gstar_opt_move x g :
  (x < n)%nat -> x <> goal P -> Gstar P x = Some g ->
  exists i gy, (i < length (moves P x))%nat /\ Gstar P (target P x (Move i)) = Some gy
               /\ g == cost P x (Move i) + gy.
Proof.
  intros Hx Hng H; destruct (Gstar_attained x g Hx H) as (w & [Hw He] & Hc).
  destruct w as [|i w]; [simpl in He; congruence|].
  destruct Hw as [Hi Hw]; simpl in He, Hc.
  destruct (wf_move x i Hx Hi) as [Hy _].
  destruct (Gstar_least _ w Hy (conj Hw He)) as (gy & Ey & Hle).
  destruct (Gstar_le_move x i gy Hx Hi Ey) as (gx & Ex & Hle').
  exists i, gy; repeat split; auto.
  rewrite H in Ex; inversion Ex; subst; lra.
Qed.

(** ** [h]: fewest moves of an optimal path (the kernel's [optimal_steps]) *)

Lemma nmin_nminl_le o L v :
  In (Some v) L -> exists a, nmin o (nminl L) = Some a /\ (a <= v)%nat.
Proof.
  intros H; destruct (nminl_le L v H) as (w & Ew & Hw).
  destruct (nmin_le_r o _ _ Ew) as (a & Ea & Ha); exists a; split; auto; lia.
Qed.

Lemma tight_spec x yl :
  tight P x yl = true ->
  exists gx gy, Gstar P x = Some gx /\ Gstar P (fst yl) = Some gy /\ snd yl + gy == gx.
Proof.
  unfold tight; destruct (Gstar P x) as [gx|], (Gstar P (fst yl)) as [gy|]; try discriminate.
  intros H; apply Qeq_bool_iff in H; eauto.
Qed.

Lemma hb_0 x : (x < n)%nat -> hb P 0 x = if Nat.eqb x (goal P) then Some 0%nat else None.
Proof.
  intros Hx; unfold hb; simpl.
  apply (nth_map_seq (fun x => if Nat.eqb x (goal P) then Some 0%nat else None)); auto.
Qed.

Lemma hb_S k x : (x < n)%nat -> hb P (S k) x = hb_step P (hb P k) x.
Proof. intros Hx; unfold hb at 1; simpl; apply nth_map_seq; auto. Qed.

Lemma hb_goal k : hb P k (goal P) = Some 0%nat.
Proof.
  destruct HP as [Hg _].
  destruct k; [rewrite hb_0 | rewrite hb_S; unfold hb_step]; auto; rewrite Nat.eqb_refl; auto.
Qed.

Lemma hb_succ k x a :
  (x < n)%nat -> hb P k x = Some a -> exists b, hb P (S k) x = Some b /\ (b <= a)%nat.
Proof.
  intros Hx H; rewrite hb_S by auto; unfold hb_step.
  destruct (Nat.eqb x (goal P)); [eexists; split; eauto; lia|].
  apply nmin_le_l; auto.
Qed.

Lemma hb_mono j k x a :
  (j <= k)%nat -> (x < n)%nat -> hb P j x = Some a ->
  exists b, hb P k x = Some b /\ (b <= a)%nat.
Proof.
  intros Hjk Hx H; induction Hjk as [|k Hjk IH]; [exists a; split; auto|].
  destruct IH as (b & Hb & ?); destruct (hb_succ _ _ _ Hx Hb) as (c & ? & ?).
  exists c; split; auto; lia.
Qed.

Lemma hb_descent k x a :
  (x < n)%nat -> x <> goal P -> hb P k x = Some a ->
  exists i b, (i < length (moves P x))%nat
              /\ tight P x (target P x (Move i), cost P x (Move i)) = true
              /\ hb P k (target P x (Move i)) = Some b /\ (S b <= a)%nat.
Proof.
  intros Hx Hng; apply Nat.eqb_neq in Hng as Hng'; revert a.
  induction k as [|k IH]; intros a H.
  - rewrite hb_0, Hng' in H by auto; discriminate.
  - rewrite hb_S in H by auto; unfold hb_step in H; rewrite Hng' in H.
    apply nmin_cases in H as [H|H].
    + destruct (IH a H) as (i & b & Hi & Ht & Hb & Hle).
      destruct (wf_move x i Hx Hi) as [Hy _].
      destruct (hb_succ _ _ _ Hy Hb) as (c & Hc & ?).
      exists i, c; repeat split; auto; lia.
    + apply nminl_in, in_map_iff in H as ([y l] & E & Hyl).
      destruct (tight P x (y, l)) eqn:Ht; [|discriminate].
      simpl in E; destruct (hb P k y) as [b|] eqn:Eb; simpl in E; inversion E; subst.
      destruct (in_move _ _ _ Hyl) as (i & Hi & Hty & Hc).
      assert (Hy : (y < n)%nat) by (rewrite <- Hty; apply wf_move; auto).
      destruct (hb_succ _ _ _ Hy Eb) as (c & Ec & ?).
      exists i, c; rewrite Hty, Hc; repeat split; auto; lia.
Qed.

(** [h(xg) = 0]. *)
Theorem hstar_goal : hstar P (goal P) = Some 0%nat.
Proof. apply hb_goal. Qed.

(** Descent ([docs/proofs/c1.md], Part A): away from the goal, some optimal move leads to a
    state with a smaller [h]. *)
Theorem hstar_descent x a :
  (x < n)%nat -> x <> goal P -> hstar P x = Some a ->
  exists i b, (i < length (moves P x))%nat
              /\ tight P x (target P x (Move i), cost P x (Move i)) = true
              /\ hstar P (target P x (Move i)) = Some b /\ (S b <= a)%nat.
Proof. apply hb_descent. Qed.

(** An optimal goal-reaching sequence: its cost is [G*(x)]. *)
Definition optimal_walk (x : nat) (w : list nat) : Prop :=
  reaches P x w /\ exists g, Gstar P x = Some g /\ wcost P x w == g.

Lemma optimal_walk_goal : optimal_walk (goal P) [].
Proof.
  destruct Gstar_goal as (g & Eg & Hg).
  split; [split; simpl; auto | exists g; simpl; split; auto; lra].
Qed.

Lemma hb_attained k x a :
  (x < n)%nat -> hb P k x = Some a -> exists w, optimal_walk x w /\ length w = a.
Proof.
  revert x a; induction k as [|k IH]; intros x a Hx H.
  { rewrite hb_0 in H by auto; destruct (Nat.eqb_spec x (goal P)); inversion H; subst.
    exists []; split; auto; apply optimal_walk_goal. }
  destruct (Nat.eq_dec x (goal P)) as [->|Hng].
  { rewrite hb_goal in H; inversion H; subst; exists []; split; auto; apply optimal_walk_goal. }
  rewrite hb_S in H by auto; unfold hb_step in H; rewrite (proj2 (Nat.eqb_neq _ _) Hng) in H.
  apply nmin_cases in H as [H|H]; [apply IH; auto|].
  apply nminl_in, in_map_iff in H as ([y l] & E & Hyl).
  destruct (tight P x (y, l)) eqn:Ht; [|discriminate].
  simpl in E; destruct (hb P k y) as [b|] eqn:Eb; simpl in E; inversion E; subst.
  destruct (in_move _ _ _ Hyl) as (i & Hi & Hty & Hc).
  assert (Hy : (y < n)%nat) by (rewrite <- Hty; apply wf_move; auto).
  destruct (IH _ _ Hy Eb) as (w & [[Hw He] (gy' & Ey' & Hcw)] & Hlen).
  destruct (tight_spec _ _ Ht) as (gx & gy & Ex & Ey & Hxy); simpl in Ey, Hxy.
  rewrite Ey in Ey'; inversion Ey'; subst gy'.
  exists (i :: w); split; [|simpl; congruence].
  split; [split; simpl; rewrite Hty; auto|].
  exists gx; split; auto; simpl; rewrite Hty, Hc; lra.
Qed.

Lemma hb_least x w :
  (x < n)%nat -> optimal_walk x w -> exists a, hb P (length w) x = Some a /\ (a <= length w)%nat.
Proof.
  revert x; induction w as [|i w IH]; intros x Hx [[Hw He] (g & Eg & Hc)].
  { simpl in He; subst; rewrite hb_goal; eauto. }
  destruct Hw as [Hi Hw]; simpl in He, Hc.
  destruct (wf_move x i Hx Hi) as [Hy Hl].
  destruct (Gstar_least _ w Hy (conj Hw He)) as (gy & Ey & Hle).
  destruct (Gstar_le_move x i gy Hx Hi Ey) as (gx & Ex & Hle').
  rewrite Eg in Ex; inversion Ex; subst gx.
  assert (Hopt : optimal_walk (target P x (Move i)) w).
  { split; [split; auto | exists gy; split; auto; lra]. }
  destruct (IH _ Hy Hopt) as (b & Eb & Hb).
  destruct (Nat.eq_dec x (goal P)) as [->|Hng]; [rewrite hb_goal; eexists; split; eauto; lia|].
  simpl length; rewrite hb_S by auto; unfold hb_step; rewrite (proj2 (Nat.eqb_neq _ _) Hng).
  assert (HL : In (Some (S b))
                  (map (fun yl => if tight P x yl then option_map S (hb P (length w) (fst yl))
                                  else None) (moves P x))).
  { apply in_map_iff; exists (target P x (Move i), cost P x (Move i)).
    split; [|apply move_in; auto].
    unfold tight; simpl; rewrite Eg, Ey, Eb.
    replace (Qeq_bool _ _) with true; auto; symmetry; apply Qeq_bool_iff; lra. }
  destruct (nmin_nminl_le (hb P (length w) x) _ _ HL) as (a & Ea & Ha).
  exists a; split; [exact Ea | lia].
Qed.

(** [h(x)] is the length of some optimal goal-reaching sequence from [x] ... *)
Theorem hstar_attained x a :
  (x < n)%nat -> hstar P x = Some a -> exists w, optimal_walk x w /\ length w = a.
Proof. apply hb_attained. Qed.

(** ... and no optimal goal-reaching sequence from [x] has fewer moves. *)
Theorem hstar_least x w :
  (x < n)%nat -> optimal_walk x w -> exists a, hstar P x = Some a /\ (a <= length w)%nat.
Proof.
  intros Hx [[Hw He] (g & Eg & Hc)].
  destruct (short_walk x w Hx Hw) as (w' & Hw' & E & C & L & L').
  assert (He' : wend P x w' = goal P) by congruence.
  destruct (Gstar_least x w' Hx (conj Hw' He')) as (g' & Eg' & Hg').
  rewrite Eg in Eg'; inversion Eg'; subst g'.
  assert (Hopt : optimal_walk x w') by (split; [split; auto | exists g; split; auto; lra]).
  destruct (hb_least x w' Hx Hopt) as (a & Ea & Ha).
  destruct (hb_mono (length w') n x a ltac:(lia) Hx Ea) as (b & Eb & Hb).
  exists b; split; auto; lia.
Qed.

(** Under (H1), [h] is finite wherever [G*] is. *)
Theorem hstar_some x g : (x < n)%nat -> Gstar P x = Some g -> exists a, hstar P x = Some a.
Proof.
  intros Hx H; destruct (Gstar_attained x g Hx H) as (w & Hw & Hc).
  destruct (hstar_least x w Hx (conj Hw (ex_intro _ g (conj H Hc)))) as (a & ? & _); eauto.
Qed.

End Walks.

Lemma Qmax2_cases a b : Qmax2 a b = a \/ Qmax2 a b = b.
Proof. unfold Qmax2; destruct (Qle_bool a b); auto. Qed.
