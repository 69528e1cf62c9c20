(** * The discounted certificate checker as a Coq function, and its soundness.

    The discounted objective (greatest expected discounted reward, [0 < alpha < 1]) over the
    model of [CertificateCheck] read differently: a state's flag marks a terminal state (value
    0, the episode ends there) and an action's first component is its expected reward [r].
    With [Q(x, a) = r(x, a) + alpha * sum_y p(y|x,a) V y], [check_discounted] accepts when
    [0 < alpha < 1], every action is well formed (successors are states, probabilities
    positive and of total mass 1), and at every state [x] of the model [V x] is finite with
    [V x = 0] and no action chosen if [x] is terminal, and otherwise the policy names an action
    of [x] with [V x = Q(x, pi x)] and [V x >= Q(x, a)] for every action [a]: [V] is the fixed
    point [V = max_a Q(., a)].

    Soundness: if [check_discounted] accepts, (1) [V] solves the policy's equation at every
    state ([check_discounted_policy]), and (2) every solution [J] of any stationary policy
    [mu]'s equation ([J = 0] at terminal states, [J x = r(x, mu x) + alpha * sum_y p J y]
    elsewhere; [mu]'s expected discounted reward is its unique solution) is at most [V]
    ([check_discounted_optimal]). The proof is the maximum principle with [alpha]: where
    [D = J - V] is largest, [D <= alpha * max D], so [max D <= 0]. *)

From Coq Require Import QArith List Lqa Bool Arith Lia.
From Truecost Require Import Certificate CertificateCheck.
Import ListNotations.

Open Scope Q_scope.

(** [Q(x, a) = r(x, a) + alpha * sum_y p(y|x,a) V y]. *)
Definition dq_of (alpha : Q) (V : list (option Q)) (a : action) : Q :=
  fst a + alpha * sum_p (vq V) (snd a).

(** The reward of the action [mu] takes at [x]. *)
Definition mu_reward (m : model) (mu : nat -> nat) (x : nat) : Q :=
  match nth_error (acts m x) (mu x) with Some a => fst a | None => 0 end.

Definition dstate_ok (m : model) (alpha : Q) (V : list (option Q)) (pi : list (option nat))
    (x : nat) : bool :=
  forallb (well_formed (length m)) (acts m x) &&
  match val V x with
  | None => false
  | Some v =>
      if goalb m x then Qeq_bool v 0 && nopol pi x
      else
        match picked m (nth x pi None) x with
        | Some a => Qeq_bool v (dq_of alpha V a)
        | None => false
        end
        && forallb (fun a => Qle_bool (dq_of alpha V a) v) (acts m x)
  end.

(** The checker. *)
Definition check_discounted (m : model) (alpha : Q) (V : list (option Q))
    (pi : list (option nat)) : bool :=
  negb (Qle_bool alpha 0) && negb (Qle_bool 1 alpha)
  && forallb (dstate_ok m alpha V pi) (seq 0 (length m)).

(** ** Soundness *)

Lemma wf_facts : forall n a, well_formed n a = true ->
  (forall y p, In (y, p) (snd a) -> (y < n)%nat /\ 0 < p) /\ mass (snd a) == 1.
Proof.
  intros n a H. unfold well_formed in H. apply andb_true_iff in H. destruct H as [H Hm].
  split; [| apply Qeq_bool_iff; exact Hm].
  intros y p Hy. rewrite forallb_forall in H. specialize (H (y, p) Hy). simpl in H.
  apply andb_true_iff in H. destruct H as [H1 H2].
  split; [apply Nat.ltb_lt; exact H1 |].
  apply negb_true_iff in H2. destruct (Qlt_le_dec 0 p) as [Hp | Hp]; [exact Hp |].
  apply Qle_bool_iff in Hp. congruence.
Qed.

Section Sound.

  Variable m : model.
  Variable alpha : Q.
  Variable V : list (option Q).
  Variable pi : list (option nat).
  Hypothesis accepted : check_discounted m alpha V pi = true.

  Lemma alpha_range : 0 < alpha /\ alpha < 1.
  Proof.
    unfold check_discounted in accepted. apply andb_true_iff in accepted.
    destruct accepted as [H _]. apply andb_true_iff in H. destruct H as [H1 H2].
    apply negb_true_iff in H1. apply negb_true_iff in H2. split.
    - destruct (Qlt_le_dec 0 alpha) as [H | H]; [exact H |].
      apply Qle_bool_iff in H. congruence.
    - destruct (Qlt_le_dec alpha 1) as [H | H]; [exact H |].
      apply Qle_bool_iff in H. congruence.
  Qed.

  Lemma dok_at : forall x, (x < length m)%nat -> dstate_ok m alpha V pi x = true.
  Proof.
    intros x Hx. unfold check_discounted in accepted. apply andb_true_iff in accepted.
    destruct accepted as [_ H]. rewrite forallb_forall in H. apply H. apply in_seq. lia.
  Qed.

  (** (1) The policy: every state of the model has a finite value, 0 at terminal states, and
      elsewhere the policy names an action whose [Q] is the value. *)
  Theorem check_discounted_policy : forall x, (x < length m)%nat ->
    exists v, val V x = Some v /\ (goalb m x = true -> v == 0) /\
      (goalb m x = false -> exists a, picked m (nth x pi None) x = Some a /\ v == dq_of alpha V a).
  Proof.
    intros x Hx. pose proof (dok_at x Hx) as H. unfold dstate_ok in H.
    apply andb_true_iff in H. destruct H as [_ H].
    destruct (val V x) as [v |]; [| discriminate]. exists v. split; [reflexivity |].
    destruct (goalb m x).
    - split; [| discriminate]. intros _. apply andb_true_iff in H. destruct H as [H _].
      apply Qeq_bool_iff. exact H.
    - split; [discriminate |]. intros _. apply andb_true_iff in H. destruct H as [H _].
      destruct (picked m (nth x pi None) x) as [a |]; [| discriminate].
      exists a. split; [reflexivity | apply Qeq_bool_iff; exact H].
  Qed.

  (** (2) Optimality: every solution of a stationary policy's equation is at most [V]. *)
  Theorem check_discounted_optimal : forall (mu : nat -> nat) (J : nat -> Q),
    (forall x, (x < length m)%nat -> goalb m x = false ->
       exists a, nth_error (acts m x) (mu x) = Some a) ->
    (forall x, (x < length m)%nat -> goalb m x = true -> J x == 0) ->
    (forall x, (x < length m)%nat -> goalb m x = false ->
       J x == mu_reward m mu x + alpha * sum_p J (mu_out m mu x)) ->
    forall x, (x < length m)%nat -> J x <= vq V x.
  Proof.
    intros mu J Hact HJ HJeq x Hx.
    destruct alpha_range as [Ha0 Ha1].
    set (S := seq 0 (length m)).
    set (D := fun y => J y - vq V y).
    assert (HS : forall y, In y S <-> (y < length m)%nat).
    { intros y. unfold S. rewrite in_seq. lia. }
    destruct (exists_max D S) as [z [Hz Hmax]].
    { intros He. assert (Hin : In x S) by (apply HS; exact Hx). rewrite He in Hin. destruct Hin. }
    assert (Hxz : D x <= D z) by (apply Hmax; apply HS; exact Hx).
    enough (Hz0 : D z <= 0) by (unfold D in Hxz, Hz0; lra).
    apply HS in Hz.
    destruct (check_discounted_policy z Hz) as [v [Hv [Hgoal Hpol]]].
    destruct (goalb m z) eqn:Hg.
    - unfold D. rewrite (HJ z Hz Hg). unfold vq. rewrite Hv. rewrite (Hgoal eq_refl). lra.
    - destruct (Hact z Hz Hg) as [a Ha].
      pose proof (dok_at z Hz) as H. unfold dstate_ok in H. apply andb_true_iff in H.
      destruct H as [Hwf H]. rewrite Hv, Hg in H. apply andb_true_iff in H.
      destruct H as [_ Hopt]. rewrite forallb_forall in Hopt.
      assert (HaIn : In a (acts m z)) by exact (nth_error_In _ _ Ha).
      specialize (Hopt a HaIn). apply Qle_bool_iff in Hopt.
      rewrite forallb_forall in Hwf. destruct (wf_facts _ a (Hwf a HaIn)) as [Hout Hmass].
      assert (Hsum : sum_p D (snd a) <= mass (snd a) * D z).
      { apply sum_p_upper.
        - intros y p Hy. destruct (Hout y p Hy). lra.
        - intros y p Hy. apply Hmax. apply HS. apply (Hout y p Hy). }
      rewrite Hmass in Hsum.
      assert (HJz : J z == fst a + alpha * sum_p J (snd a)).
      { rewrite (HJeq z Hz Hg). unfold mu_reward, mu_out. rewrite Ha. reflexivity. }
      (* D z = J z - v <= (r + alpha sum p J) - (r + alpha sum p V) = alpha sum p D. *)
      assert (HDz : D z <= alpha * sum_p D (snd a)).
      { assert (Hvz : vq V z = v) by (unfold vq; rewrite Hv; reflexivity).
        unfold D at 2. rewrite sum_p_minus. unfold D. rewrite Hvz.
        unfold dq_of in Hopt. rewrite HJz.
        assert (E : alpha * (sum_p J (snd a) - sum_p (vq V) (snd a))
                    == alpha * sum_p J (snd a) - alpha * sum_p (vq V) (snd a)) by ring.
        rewrite E. lra. }
      assert (Hle : alpha * sum_p D (snd a) <= alpha * (1 * D z)).
      { apply mult_le_l; lra. }
      destruct (Qlt_le_dec 0 (D z)) as [Hpos | Hnp]; [| exact Hnp].
      exfalso.
      assert (Hlt : alpha * D z < 1 * D z) by (apply Qmult_lt_r; assumption).
      assert (E1 : 1 * D z == D z) by ring.
      rewrite E1 in Hle, Hlt. lra.
  Qed.

End Sound.
