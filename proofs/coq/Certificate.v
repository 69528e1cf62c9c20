(** * Soundness of the truecost certificate conditions: a discrete maximum principle.

    The checker of [src/certificate/] accepts values [V] and a policy when, among others,
    [V g = 0] at goals and [V x <= Q(x, a) = c(x, a) + sum_y p(y|x,a) V y] for every action
    [a] of a finite non-goal state whose outcomes are all finite ("optimality"). Let [mu] be a
    stationary policy proper from every state of a set [S] closed under its outcomes (for a
    proper [mu] from [x], the states it reaches form such a set, all finite by the "infinite"
    condition), and [J] its expected cost: [J g = 0] at goals and
    [J x = c(x, mu x) + sum_y p(y|x,mu x) J y] elsewhere. Then [V <= J] on [S]
    ([certificate_optimal]). The core is [maximum_principle]: [D = V - J] satisfies
    [D x <= sum_y p D y] at non-goals and [D = 0] at goals; where [D] is largest the outcomes
    stay where it is largest, so a goal reachable from there has the largest [D], which is 0.
    The "infinite" condition rests on [proper_inside_Wstar]: a state from which some policy is
    proper lies in the checker's [W*].

    Properness is the graph condition the checker also uses: from every state of [S] a goal is
    reachable along outcomes of positive probability ([reaches]). States are natural numbers;
    [S] is a list; an outcome list is a list of (successor, probability) pairs. *)

From Coq Require Import QArith List Lqa.
Import ListNotations.

Open Scope Q_scope.

(** [sum_p f l] = [sum_{(y, p) in l} p * f y]. *)
Fixpoint sum_p (f : nat -> Q) (l : list (nat * Q)) : Q :=
  match l with
  | [] => 0
  | (y, p) :: t => p * f y + sum_p f t
  end.

(** [sum_p] of the probabilities alone (their total mass). *)
Fixpoint mass (l : list (nat * Q)) : Q :=
  match l with
  | [] => 0
  | (_, p) :: t => p + mass t
  end.

Lemma mult_le_l : forall p a b, 0 <= p -> a <= b -> p * a <= p * b.
Proof.
  intros p a b Hp Hab. rewrite (Qmult_comm p a), (Qmult_comm p b).
  apply Qmult_le_compat_r; assumption.
Qed.

Lemma sum_p_ext : forall f g l,
  (forall y p, In (y, p) l -> f y == g y) -> sum_p f l == sum_p g l.
Proof.
  intros f g l H. induction l as [| [y p] t IH]; simpl.
  - reflexivity.
  - rewrite (H y p (or_introl eq_refl)).
    rewrite IH; [reflexivity |]. intros y' p' Hi. apply (H y' p'). right. exact Hi.
Qed.

Lemma sum_p_minus : forall f g l,
  sum_p (fun y => f y - g y) l == sum_p f l - sum_p g l.
Proof.
  intros f g l. induction l as [| [y p] t IH]; simpl.
  - ring.
  - rewrite IH. ring.
Qed.

(** If every value is at most [M], the probabilities are non-negative and of total mass 1,
    and the weighted sum is at least [M], then every outcome of positive probability has the
    value [M]. *)
Lemma sum_p_upper : forall f M l,
  (forall y p, In (y, p) l -> 0 <= p) ->
  (forall y p, In (y, p) l -> f y <= M) ->
  sum_p f l <= mass l * M.
Proof.
  intros f M l Hp Hf. induction l as [| [y p] t IH]; simpl.
  - lra.
  - assert (H0 : 0 <= p) by (apply (Hp y p); left; reflexivity).
    assert (H1 : f y <= M) by (apply (Hf y p); left; reflexivity).
    assert (IH' : sum_p f t <= mass t * M).
    { apply IH; intros y' p' Hi; [apply (Hp y' p') | apply (Hf y' p')]; right; exact Hi. }
    assert (p * f y <= p * M).
    { apply mult_le_l; assumption. }
    lra.
Qed.

Lemma sum_p_tight : forall f M l,
  (forall y p, In (y, p) l -> 0 <= p) ->
  (forall y p, In (y, p) l -> f y <= M) ->
  mass l * M <= sum_p f l ->
  forall y p, In (y, p) l -> 0 < p -> f y == M.
Proof.
  intros f M l Hp Hf. induction l as [| [y0 p0] t IH]; simpl; intros Hs y p Hi Hpos.
  - destruct Hi.
  - assert (H0 : 0 <= p0) by (apply (Hp y0 p0); left; reflexivity).
    assert (H1 : f y0 <= M) by (apply (Hf y0 p0); left; reflexivity).
    assert (Ht : sum_p f t <= mass t * M).
    { apply sum_p_upper; intros y' p' Hi'; [apply (Hp y' p') | apply (Hf y' p')]; right; exact Hi'. }
    assert (Hle : p0 * f y0 <= p0 * M) by (apply mult_le_l; assumption).
    destruct Hi as [Heq | Hi].
    + inversion Heq; subst y0 p0.
      (* p * f y = p * M, p > 0. *)
      assert (Hm : p * (M - f y) <= 0) by lra.
      assert (Hn : 0 <= M - f y) by lra.
      assert (Hz : p * (M - f y) == 0).
      { apply Qle_antisym; [exact Hm |].
        apply Qmult_le_0_compat; lra. }
      apply Qmult_integral in Hz. destruct Hz as [Hz | Hz]; lra.
    + apply IH with (p := p); try assumption.
      * intros y' p' Hi'. apply (Hp y' p'). right. exact Hi'.
      * intros y' p' Hi'. apply (Hf y' p'). right. exact Hi'.
      * lra.
Qed.

Section MaximumPrinciple.

  (** The states under consideration, the goals, and the outcomes of the policy [mu]. *)
  Variable S : list nat.
  Variable goal : nat -> bool.
  Variable out : nat -> list (nat * Q).

  Hypothesis closed : forall x y p, In x S -> goal x = false -> In (y, p) (out x) -> In y S.
  Hypothesis nonneg : forall x y p, In x S -> goal x = false -> In (y, p) (out x) -> 0 <= p.
  Hypothesis total : forall x, In x S -> goal x = false -> mass (out x) == 1.

  (** A goal is reachable from [x] along outcomes of positive probability. *)
  Inductive reaches : nat -> Prop :=
  | reaches_goal : forall x, goal x = true -> reaches x
  | reaches_step : forall x y p,
      goal x = false -> In (y, p) (out x) -> 0 < p -> reaches y -> reaches x.

  Hypothesis proper : forall x, In x S -> reaches x.

  Lemma exists_max : forall (D : nat -> Q) (l : list nat),
    l <> [] -> exists m, In m l /\ forall y, In y l -> D y <= D m.
  Proof.
    intros D l. induction l as [| a t IH]; intros Hne.
    - contradiction.
    - destruct t as [| b t'].
      + exists a. split; [left; reflexivity |]. intros y [Hy | []]. subst. lra.
      + destruct IH as [m [Hm Hmax]]; [discriminate |].
        destruct (Qlt_le_dec (D m) (D a)) as [Hlt | Hge].
        * exists a. split; [left; reflexivity |].
          intros y [Hy | Hy]; [subst; lra |]. specialize (Hmax y Hy). lra.
        * exists m. split; [right; exact Hm |].
          intros y [Hy | Hy]; [subst; lra | apply Hmax; exact Hy].
  Qed.

  (** The discrete maximum principle. *)
  Theorem maximum_principle : forall D : nat -> Q,
    (forall x, In x S -> goal x = true -> D x == 0) ->
    (forall x, In x S -> goal x = false -> D x <= sum_p D (out x)) ->
    forall x, In x S -> D x <= 0.
  Proof.
    intros D Hgoal Hsub x Hx.
    destruct (exists_max D S) as [m [Hm Hmax]]; [destruct S; [destruct Hx | discriminate] |].
    assert (Hxm : D x <= D m) by (apply Hmax; exact Hx).
    destruct (Qlt_le_dec 0 (D m)) as [Hpos | Hle]; [| lra].
    exfalso.
    (* Every state of S where D is maximal reaches a goal, which would have D = D m > 0. *)
    assert (Hno : forall z, reaches z -> In z S -> D z == D m -> False).
    { intros z Hr. induction Hr as [z Hg | z y p Hg Hin Hp Hr IH]; intros Hz Heq.
      - specialize (Hgoal z Hz Hg). lra.
      - apply IH.
        + exact (closed z y p Hz Hg Hin).
        + apply (sum_p_tight D (D m) (out z)) with (p := p); try assumption.
          * intros y' p' Hi. exact (nonneg z y' p' Hz Hg Hi).
          * intros y' p' Hi. apply Hmax. exact (closed z y' p' Hz Hg Hi).
          * rewrite (total z Hz Hg). specialize (Hsub z Hz Hg). lra. }
    apply (Hno m (proper m Hm) Hm). reflexivity.
  Qed.

  (** The checker's conditions imply optimality against [mu]: [V] satisfies "goal" and
      "optimality" for [mu]'s actions ([cost] their stage costs), [J] is [mu]'s expected
      cost; then [V <= J] on [S]. *)
  Theorem certificate_optimal : forall (V J cost : nat -> Q),
    (forall x, In x S -> goal x = true -> V x == 0) ->
    (forall x, In x S -> goal x = false -> V x <= cost x + sum_p V (out x)) ->
    (forall x, In x S -> goal x = true -> J x == 0) ->
    (forall x, In x S -> goal x = false -> J x == cost x + sum_p J (out x)) ->
    forall x, In x S -> V x <= J x.
  Proof.
    intros V J cost HV HVopt HJ HJeq x Hx.
    assert (Hg : forall z, In z S -> goal z = true -> (fun y => V y - J y) z == 0).
    { intros z Hz Hgz. simpl. rewrite (HV z Hz Hgz), (HJ z Hz Hgz). ring. }
    assert (Hs : forall z, In z S -> goal z = false ->
                 (fun y => V y - J y) z <= sum_p (fun y => V y - J y) (out z)).
    { intros z Hz Hgz. rewrite sum_p_minus.
      specialize (HVopt z Hz Hgz). specialize (HJeq z Hz Hgz). simpl. lra. }
    pose proof (maximum_principle (fun y => V y - J y) Hg Hs x Hx) as H.
    simpl in H. lra.
  Qed.

End MaximumPrinciple.

(** * States outside [W*] have no proper policy.

    The checker's "infinite" condition asks that no state of value [inf] lie in [W*], which it
    computes from [W] = every state by keeping the states from which a goal is reachable
    using only actions whose outcomes all stay in [W] ([survives]), until nothing changes.
    [acts x] are the outcome lists of [x]'s actions. Whatever the number [k] of rounds,
    the states from which a stationary policy [mu] (choosing among [acts]) is proper — the
    states of a set [R] closed under [mu]'s outcomes, from each of which a goal is reachable
    along them — are all in the [k]-th set ([proper_inside_Wstar]). So a state outside the
    final set has no proper policy, and [inf] is its truecost optimum. (The checker keeps,
    in each round, only states of the previous round; the rounds here decrease anyway, since
    [survives] is monotone in [W], so the sets are the same.) *)

Section Wstar.

  Variable goal : nat -> bool.
  Variable acts : nat -> list (list (nat * Q)).

  (** A goal is reachable from [x] using only actions whose outcomes all satisfy [W]. *)
  Inductive survives (W : nat -> Prop) : nat -> Prop :=
  | survives_goal : forall x, goal x = true -> survives W x
  | survives_step : forall x a y p,
      goal x = false -> In a (acts x) -> (forall z q, In (z, q) a -> W z) ->
      In (y, p) a -> 0 < p -> survives W y -> survives W x.

  (** The [k]-th round, from every state. *)
  Fixpoint rounds (k : nat) : nat -> Prop :=
    match k with
    | O => fun _ => True
    | S k' => survives (rounds k')
    end.

  Theorem proper_inside_Wstar : forall (mu : nat -> list (nat * Q)) (R : list nat),
    (forall x, In x R -> goal x = false -> In (mu x) (acts x)) ->
    (forall x y p, In x R -> goal x = false -> In (y, p) (mu x) -> In y R) ->
    (forall x, In x R -> reaches goal mu x) ->
    forall k x, In x R -> rounds k x.
  Proof.
    intros mu R Hact Hclosed Hproper k.
    induction k as [| k IH]; intros x Hx; simpl; [exact I |].
    specialize (Hproper x Hx).
    induction Hproper as [x Hg | x y p Hg Hin Hp Hr IHr].
    - apply survives_goal. exact Hg.
    - apply (survives_step (rounds k) x (mu x) y p Hg (Hact x Hx Hg)).
      + intros z q Hzq. apply IH. exact (Hclosed x z q Hx Hg Hzq).
      + exact Hin.
      + exact Hp.
      + apply IHr. exact (Hclosed x y p Hx Hg Hin).
  Qed.

End Wstar.
