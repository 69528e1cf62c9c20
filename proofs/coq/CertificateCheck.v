(** * The certificate checker as a Coq function, and its soundness.

    [check] decides the truecost certificate conditions of [src/certificate/] over a finite
    model given as data, so that [vm_compute] can run it on a certificate written as Coq
    terms. Where the Rust checker searches (properness of the policy, the set [W*]), [check]
    takes the result of the search as a hint and checks it locally: a rank per finite state
    that some positive-probability outcome of the policy decreases (or that reaches a goal),
    and per [inf] state the round of the [W*] iteration that removes it. Hints are not
    trusted: [check_policy] and [check_optimal] hold whatever they are. Like the Rust
    checker, [check] also asks that no action be chosen at goals and [inf] states.

    Soundness: if [check] accepts, then (1) at every finite non-goal state the policy's action
    has all its outcomes finite, the value solves the policy's equation, and a goal is
    reachable along the policy's outcomes (the policy is proper there: [check_policy]); and
    (2) for every
    stationary policy [mu], every set [S] closed under [mu]'s outcomes from each of whose
    states [mu] reaches a goal, and every [J] solving [mu]'s equations on [S] (its expected
    cost), every state of [S] has a finite value, at most [J] ([check_optimal]). *)

From Coq Require Import QArith List Lqa Bool Arith Lia.
From Truecost Require Import Certificate.
Import ListNotations.

Open Scope Q_scope.

(** A model: per state its goal flag and its actions, each a stage cost and outcomes. *)
Definition action := (Q * list (nat * Q))%type.
Definition model := list (bool * list action).

Definition goalb (m : model) (x : nat) : bool := fst (nth x m (false, [])).
Definition acts (m : model) (x : nat) : list action := snd (nth x m (false, [])).
Definition outs (m : model) (x : nat) : list (list (nat * Q)) := map snd (acts m x).
Definition val (V : list (option Q)) (x : nat) : option Q := nth x V None.
Definition vq (V : list (option Q)) (x : nat) : Q :=
  match val V x with Some v => v | None => 0 end.
Definition fin (V : list (option Q)) (x : nat) : bool :=
  match val V x with Some _ => true | None => false end.
Definition rank (rk : list nat) (x : nat) : nat := nth x rk 0%nat.

(** The action a policy (an index per state) takes, its outcomes and its cost. *)
Definition picked (m : model) (i : option nat) (x : nat) : option action :=
  match i with Some i => nth_error (acts m x) i | None => None end.
Definition pol_out (m : model) (pi : list (option nat)) (x : nat) : list (nat * Q) :=
  match picked m (nth x pi None) x with Some a => snd a | None => [] end.
Definition mu_out (m : model) (mu : nat -> nat) (x : nat) : list (nat * Q) :=
  match nth_error (acts m x) (mu x) with Some a => snd a | None => [] end.
Definition mu_cost (m : model) (mu : nat -> nat) (x : nat) : Q :=
  match nth_error (acts m x) (mu x) with Some a => fst a | None => 0 end.

Definition q_of (V : list (option Q)) (a : action) : Q := fst a + sum_p (vq V) (snd a).
Definition all_fin (V : list (option Q)) (a : action) : bool :=
  forallb (fun yp => fin V (fst yp)) (snd a).

(** Successors are states, probabilities positive and of total mass 1. *)
Definition well_formed (n : nat) (a : action) : bool :=
  forallb (fun yp => Nat.ltb (fst yp) n && negb (Qle_bool (snd yp) 0)) (snd a)
  && Qeq_bool (mass (snd a)) 1.

Definition finite_ok (m : model) (V : list (option Q)) (rk : list nat) (x : nat) (v : Q)
    (a : action) : bool :=
  all_fin V a && Qeq_bool v (q_of V a)
  && existsb (fun yp => negb (Qle_bool (snd yp) 0)
                        && (goalb m (fst yp) || Nat.ltb (rank rk (fst yp)) (rank rk x))) (snd a).

Definition removed_ok (V : list (option Q)) (rk : list nat) (x : nat) (a : action) : bool :=
  existsb (fun yp => negb (fin V (fst yp)) && Nat.ltb (rank rk (fst yp)) (rank rk x)) (snd a)
  || forallb (fun yp => negb (fin V (fst yp)) && Nat.eqb (rank rk (fst yp)) (rank rk x)) (snd a).

(** No action is chosen at [x]. *)
Definition nopol (pi : list (option nat)) (x : nat) : bool :=
  match nth x pi None with None => true | Some _ => false end.

Definition state_ok (m : model) (V : list (option Q)) (pi : list (option nat))
    (rk : list nat) (x : nat) : bool :=
  forallb (well_formed (length m)) (acts m x) &&
  if goalb m x then
    match val V x with Some v => Qeq_bool v 0 && nopol pi x | None => false end
  else
    match val V x with
    | Some v =>
        match picked m (nth x pi None) x with
        | Some a => finite_ok m V rk x v a
        | None => false
        end
        && forallb (fun a => negb (all_fin V a) || Qle_bool v (q_of V a)) (acts m x)
    | None => nopol pi x && (Nat.ltb 0 (rank rk x) && forallb (removed_ok V rk x) (acts m x))
    end.

(** The checker. *)
Definition check (m : model) (V : list (option Q)) (pi : list (option nat)) (rk : list nat)
    : bool :=
  forallb (state_ok m V pi rk) (seq 0 (length m)).

(** ** Soundness *)

Section Sound.

  Variable m : model.
  Variable V : list (option Q).
  Variable pi : list (option nat).
  Variable rk : list nat.
  Hypothesis accepted : check m V pi rk = true.

  Lemma ok_at : forall x, (x < length m)%nat -> state_ok m V pi rk x = true.
  Proof.
    intros x Hx. unfold check in accepted. rewrite forallb_forall in accepted.
    apply accepted. apply in_seq. lia.
  Qed.

  Lemma beyond : forall x, (length m <= x)%nat -> goalb m x = false /\ acts m x = [].
  Proof.
    intros x Hx. unfold goalb, acts. rewrite nth_overflow by exact Hx. split; reflexivity.
  Qed.

  Lemma goal_in_range : forall x, goalb m x = true -> (x < length m)%nat.
  Proof.
    intros x Hg. destruct (Nat.lt_ge_cases x (length m)) as [H | H]; [exact H |].
    destruct (beyond x H) as [Hf _]. congruence.
  Qed.

  Lemma action_in_range : forall x a, In a (acts m x) -> (x < length m)%nat.
  Proof.
    intros x a Ha. destruct (Nat.lt_ge_cases x (length m)) as [H | H]; [exact H |].
    destruct (beyond x H) as [_ Hn]. rewrite Hn in Ha. destruct Ha.
  Qed.

  Lemma wf_at : forall x a, In a (acts m x) -> well_formed (length m) a = true.
  Proof.
    intros x a Ha. pose proof (ok_at x (action_in_range x a Ha)) as H.
    unfold state_ok in H. apply andb_true_iff in H. destruct H as [H _].
    rewrite forallb_forall in H. exact (H a Ha).
  Qed.

  Lemma outcome_facts : forall x a y p, In a (acts m x) -> In (y, p) (snd a) ->
    (y < length m)%nat /\ 0 < p.
  Proof.
    intros x a y p Ha Hy. pose proof (wf_at x a Ha) as H. unfold well_formed in H.
    apply andb_true_iff in H. destruct H as [H _]. rewrite forallb_forall in H.
    specialize (H (y, p) Hy). simpl in H. apply andb_true_iff in H. destruct H as [H1 H2].
    split; [apply Nat.ltb_lt; exact H1 |].
    apply negb_true_iff in H2. destruct (Qlt_le_dec 0 p) as [Hp | Hp]; [exact Hp |].
    apply Qle_bool_iff in Hp. congruence.
  Qed.

  Lemma mass_at : forall x a, In a (acts m x) -> mass (snd a) == 1.
  Proof.
    intros x a Ha. pose proof (wf_at x a Ha) as H. unfold well_formed in H.
    apply andb_true_iff in H. destruct H as [_ H]. apply Qeq_bool_iff. exact H.
  Qed.

  (** [survives] is monotone in its set, so the rounds decrease. *)
  Lemma survives_mono : forall g (A : nat -> list (list (nat * Q))) (W W' : nat -> Prop),
    (forall z, W z -> W' z) -> forall x, survives g A W x -> survives g A W' x.
  Proof.
    intros g A W W' Hw x H. induction H as [x Hg | x a y p Hg Ha Hall Hy Hp Hs IH].
    - apply survives_goal. exact Hg.
    - apply (survives_step g A W' x a y p Hg Ha); try assumption.
      intros z q Hz. apply Hw. exact (Hall z q Hz).
  Qed.

  Lemma rounds_step : forall g A k x, rounds g A (S k) x -> rounds g A k x.
  Proof.
    intros g A k. induction k as [| k IH]; intros x H; [exact I |].
    simpl in H |- *. apply (survives_mono g A (rounds g A (S k)) (rounds g A k)); assumption.
  Qed.

  Lemma rounds_le : forall g A j k x, (j <= k)%nat -> rounds g A k x -> rounds g A j x.
  Proof.
    intros g A j k x Hle. induction Hle as [| k Hle IH]; intros H; [exact H |].
    apply IH. apply rounds_step. exact H.
  Qed.

  (** An [inf] state is outside the round its hint names. *)
  Lemma removed : forall k x, (x < length m)%nat -> val V x = None -> rank rk x = k ->
    ~ rounds (goalb m) (outs m) k x.
  Proof.
    intros k. induction k as [k IHk] using lt_wf_ind. intros x Hx Hv Hr Hin.
    destruct k as [| k].
    - pose proof (ok_at x Hx) as H. unfold state_ok in H. rewrite Hv in H.
      destruct (goalb m x); apply andb_true_iff in H; destruct H as [_ H]; [discriminate |].
      apply andb_true_iff in H. destruct H as [_ H].
      apply andb_true_iff in H. destruct H as [H _]. apply Nat.ltb_lt in H. lia.
    - simpl in Hin. revert Hx Hv Hr.
      induction Hin as [x Hg | x a y p Hg Ha Hall Hy Hp Hs IH]; intros Hx Hv Hr.
      + pose proof (ok_at x Hx) as H. unfold state_ok in H.
        rewrite Hg, Hv in H. apply andb_true_iff in H. destruct H; discriminate.
      + apply in_map_iff in Ha. destruct Ha as [act [Hsnd Hact]]. subst a.
        pose proof (ok_at x Hx) as H. unfold state_ok in H.
        rewrite Hg, Hv in H. apply andb_true_iff in H. destruct H as [_ H].
        apply andb_true_iff in H. destruct H as [_ H].
        apply andb_true_iff in H. destruct H as [_ H]. rewrite forallb_forall in H.
        specialize (H act Hact). unfold removed_ok in H. apply orb_true_iff in H.
        destruct H as [H | H].
        * apply existsb_exists in H. destruct H as [[z q] [Hz H]]. simpl in H.
          apply andb_true_iff in H. destruct H as [Hf Hlt]. apply Nat.ltb_lt in Hlt.
          rewrite Hr in Hlt. apply negb_true_iff in Hf. unfold fin in Hf.
          destruct (val V z) eqn:Hvz; [discriminate |].
          destruct (outcome_facts x act z q Hact Hz) as [Hzn _].
          apply (IHk (rank rk z) Hlt z Hzn Hvz eq_refl).
          apply (rounds_le _ _ (rank rk z) k); [lia |]. exact (Hall z q Hz).
        * rewrite forallb_forall in H. specialize (H (y, p) Hy). simpl in H.
          apply andb_true_iff in H. destruct H as [Hf Heq]. apply Nat.eqb_eq in Heq.
          apply negb_true_iff in Hf. unfold fin in Hf.
          destruct (val V y) eqn:Hvy; [discriminate |].
          destruct (outcome_facts x act y p Hact Hy) as [Hyn _].
          apply IH; [exact Hyn | reflexivity | lia].
  Qed.

  (** The facts [state_ok] gives at a finite non-goal state. *)
  Lemma finite_facts : forall x v, (x < length m)%nat -> val V x = Some v -> goalb m x = false ->
    (exists a, picked m (nth x pi None) x = Some a /\ finite_ok m V rk x v a = true) /\
    (forall a, In a (acts m x) -> all_fin V a = true -> v <= q_of V a).
  Proof.
    intros x v Hx Hv Hg. pose proof (ok_at x Hx) as H. unfold state_ok in H.
    rewrite Hg, Hv in H. apply andb_true_iff in H. destruct H as [_ H].
    apply andb_true_iff in H. destruct H as [H1 H2]. split.
    - destruct (picked m (nth x pi None) x) as [a |]; [| discriminate].
      exists a. split; [reflexivity | exact H1].
    - intros a Ha Hf. rewrite forallb_forall in H2. specialize (H2 a Ha).
      rewrite Hf in H2. simpl in H2. apply Qle_bool_iff. exact H2.
  Qed.

  Lemma picked_in : forall i x a, picked m i x = Some a -> In a (acts m x).
  Proof.
    intros [i |] x a H; [| discriminate]. simpl in H. exact (nth_error_In _ _ H).
  Qed.

  (** (1) The policy: at every finite non-goal state of the model, its action keeps to finite
      states, the value solves its equation, and it reaches a goal. *)
  Theorem check_policy : forall x v, (x < length m)%nat -> val V x = Some v ->
    goalb m x = false ->
    exists a, picked m (nth x pi None) x = Some a /\ v == q_of V a /\
      (forall y p, In (y, p) (snd a) -> fin V y = true) /\
      reaches (goalb m) (pol_out m pi) x.
  Proof.
    intros x. remember (rank rk x) as k eqn:Hk. revert x Hk.
    induction k as [k IHk] using lt_wf_ind. intros x Hk v Hx Hv Hg.
    destruct (finite_facts x v Hx Hv Hg) as [[a [Ha Hok]] _].
    unfold finite_ok in Hok. apply andb_true_iff in Hok. destruct Hok as [Hok Hex].
    apply andb_true_iff in Hok. destruct Hok as [Hfin Heq].
    unfold all_fin in Hfin. rewrite forallb_forall in Hfin.
    exists a. split; [exact Ha |]. split; [apply Qeq_bool_iff; exact Heq |].
    split; [intros y p Hy; exact (Hfin (y, p) Hy) |].
    apply existsb_exists in Hex. destruct Hex as [[y p] [Hy H]]. simpl in H.
    apply andb_true_iff in H. destruct H as [Hp Hnext].
    assert (Hp' : 0 < p).
    { apply negb_true_iff in Hp. destruct (Qlt_le_dec 0 p) as [Hlt | Hle]; [exact Hlt |].
      apply Qle_bool_iff in Hle. congruence. }
    assert (Hout : In (y, p) (pol_out m pi x)) by (unfold pol_out; rewrite Ha; exact Hy).
    apply (reaches_step (goalb m) (pol_out m pi) x y p Hg Hout Hp').
    destruct (goalb m y) eqn:Hgy; [apply reaches_goal; exact Hgy |].
    simpl in Hnext. apply Nat.ltb_lt in Hnext.
    pose proof (Hfin (y, p) Hy) as Hfy. simpl in Hfy. unfold fin in Hfy.
    destruct (val V y) as [w |] eqn:Hvy; [| discriminate].
    destruct (outcome_facts x a y p (picked_in _ x a Ha) Hy) as [Hyn _].
    destruct (IHk (rank rk y) ltac:(lia) y eq_refl w Hyn Hvy Hgy) as [a2 [_ [_ [_ Hr]]]].
    exact Hr.
  Qed.

  (** (2) Optimality: against every stationary policy [mu], on every set [S] closed under its
      outcomes from each of whose states it reaches a goal, with [J] its expected cost. *)
  Theorem check_optimal : forall (mu : nat -> nat) (S : list nat) (J : nat -> Q),
    (forall x, In x S -> goalb m x = false -> exists a, nth_error (acts m x) (mu x) = Some a) ->
    (forall x y p, In x S -> goalb m x = false -> In (y, p) (mu_out m mu x) -> In y S) ->
    (forall x, In x S -> reaches (goalb m) (mu_out m mu) x) ->
    (forall x, In x S -> goalb m x = true -> J x == 0) ->
    (forall x, In x S -> goalb m x = false -> J x == mu_cost m mu x + sum_p J (mu_out m mu x)) ->
    forall x, In x S -> exists v, val V x = Some v /\ v <= J x.
  Proof.
    intros mu S J Hact Hclosed Hproper HJ HJeq.
    assert (Hrange : forall x, In x S -> (x < length m)%nat).
    { intros x Hx. destruct (goalb m x) eqn:Hg; [exact (goal_in_range x Hg) |].
      destruct (Hact x Hx Hg) as [a Ha]. exact (action_in_range x a (nth_error_In _ _ Ha)). }
    assert (Hmu : forall x, In x S -> goalb m x = false ->
                  exists a, In a (acts m x) /\ mu_out m mu x = snd a /\ mu_cost m mu x = fst a).
    { intros x Hx Hg. destruct (Hact x Hx Hg) as [a Ha]. exists a.
      unfold mu_out, mu_cost. rewrite Ha. split; [exact (nth_error_In _ _ Ha) | split; reflexivity]. }
    assert (Hfinite : forall x, In x S -> exists v, val V x = Some v).
    { intros x Hx. destruct (val V x) as [v |] eqn:Hv; [exists v; reflexivity |].
      exfalso. apply (removed (rank rk x) x (Hrange x Hx) Hv eq_refl).
      apply (proper_inside_Wstar (goalb m) (outs m) (mu_out m mu) S); try assumption.
      intros z Hz Hg. destruct (Hmu z Hz Hg) as [a [Ha [Ho _]]]. rewrite Ho.
      unfold outs. apply in_map. exact Ha. }
    assert (Hnonneg : forall x y p, In x S -> goalb m x = false -> In (y, p) (mu_out m mu x) -> 0 <= p).
    { intros x y p Hx Hg Hy. destruct (Hmu x Hx Hg) as [a [Ha [Ho _]]]. rewrite Ho in Hy.
      destruct (outcome_facts x a y p Ha Hy) as [_ Hp]. lra. }
    assert (Htotal : forall x, In x S -> goalb m x = false -> mass (mu_out m mu x) == 1).
    { intros x Hx Hg. destruct (Hmu x Hx Hg) as [a [Ha [Ho _]]]. rewrite Ho. exact (mass_at x a Ha). }
    assert (HV : forall x, In x S -> goalb m x = true -> vq V x == 0).
    { intros x Hx Hg. pose proof (ok_at x (Hrange x Hx)) as H. unfold state_ok in H.
      rewrite Hg in H. apply andb_true_iff in H. destruct H as [_ H]. unfold vq.
      destruct (val V x); [| discriminate].
      apply andb_true_iff in H. destruct H as [H _]. apply Qeq_bool_iff; exact H. }
    assert (HVopt : forall x, In x S -> goalb m x = false ->
                    vq V x <= mu_cost m mu x + sum_p (vq V) (mu_out m mu x)).
    { intros x Hx Hg. destruct (Hfinite x Hx) as [v Hv].
      destruct (finite_facts x v (Hrange x Hx) Hv Hg) as [_ Hopt].
      destruct (Hmu x Hx Hg) as [a [Ha [Ho Hc]]]. rewrite Ho, Hc. unfold vq. rewrite Hv.
      apply (Hopt a Ha). unfold all_fin. apply forallb_forall. intros [y p] Hy. simpl.
      rewrite <- Ho in Hy. destruct (Hfinite y (Hclosed x y p Hx Hg Hy)) as [w Hw].
      unfold fin. rewrite Hw. reflexivity. }
    intros x Hx. destruct (Hfinite x Hx) as [v Hv]. exists v. split; [exact Hv |].
    pose proof (certificate_optimal S (goalb m) (mu_out m mu) Hclosed Hnonneg Htotal Hproper
                  (vq V) J (mu_cost m mu) HV HVopt HJ HJeq x Hx) as H.
    unfold vq in H. rewrite Hv in H. exact H.
  Qed.

End Sound.
