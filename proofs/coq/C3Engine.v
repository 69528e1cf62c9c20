(** * C3, the engine's construction: the goal-avoiding core, the first move into it, the lasso

    The certificate of truecost's C3 engine exactly: cost 1 on the moves of a stationary
    policy's lasso from [x1] only ([c3_engine_lasso]; [st_lasso]: a stationary policy's path is
    a lasso), built from the goal-avoiding core [in_core] and the first move into it
    [core_pi] (all computable). [C3.v] states the main theorem [c3_engine]. *)

From Coq Require Import Reals Lra Lia QArith Qround Qreals List.
From Truecost Require Import Model Paths C1 C2 QReal C3Policies C3Certificate.
Import ListNotations.

Open Scope R_scope.

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


