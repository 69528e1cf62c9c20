(** * C2: cost-reward equivalence, for every linear cost functional

    The paper's remark on costs and rewards, restated as claim C2 of docs/spec.md §6; the claims
    registry's statement ([src/claims/c2.rs], [STATEMENT]) reads: "for any cost functional
    linear in the sequence of stage costs (total, discounted, average, and their finite-horizon
    versions), a policy minimises the cost iff it maximises the reward obtained by negating
    every stage cost (r = -l)."

    Generality. The policies form an arbitrary type [Pi] (action sequences, stationary or
    history-dependent policies, of any problem, finite or not); the admissible ones an arbitrary
    predicate [adm]; [stage pi : nat -> R] is the sequence of stage costs that [pi] incurs. A cost
    functional is a PARTIAL map from sequences to reals, given as a relation [F s v] ("the
    functional takes the value [v] on [s]"), so that a total cost defined only on the sequences
    whose series converges needs no choice operator. The proof uses one property of [F] only:
    [odd F], i.e. [F (-s) (-v)] iff [F s v] (the domain is closed under negation and the
    functional commutes with it). Every linear functional has it ([linear_odd]), and so do the
    instances below, proved one by one: total cost (convergent series, [c2_total]), discounted
    cost ([c2_discounted], with a proof that bounded stage costs give a convergent series when
    [0 < alpha < 1]), long-run average cost ([c2_average]) and the finite-horizon total,
    discounted and average costs ([c2_horizon_total], [c2_horizon_discounted],
    [c2_horizon_average]). The total cost is real-valued on its domain (the sequences whose
    series converges); [c2_total_extended] states C2 for the total cost with values in
    [[-oo, +oo]], so that policies of infinite cost count too. On the model of [Model.v]
    ([c2_model], [c2_model_Gstar]): for every finite problem and state [x], over the goal-reaching
    move sequences from [x] (stage costs [Q2R l], then [0]), minimising the total cost and
    maximising the total reward pick the same sequences, those of cost [G*(x)].

    Everything is over the reals of the standard library; [Print Assumptions] lists only the
    axioms on which the library's construction of [R] rests ([ClassicalDedekindReals]'s
    [sig_forall_dec] and [sig_not_dec], and [functional_extensionality_dep]). *)

From Coq Require Import Reals Lra Lia.

Open Scope R_scope.

(** ** Sequences, functionals, minimisers *)

(** A sequence of stage values, indexed by the stage [k = 0, 1, ...]. *)
Definition sequence := nat -> R.

(** The reward sequence of a cost sequence: every stage negated, [r = -l]. *)
Definition neg (s : sequence) : sequence := fun k => - s k.

(** A cost functional, possibly partial: [F s v] says that it takes the value [v] on [s]. *)
Definition functional := sequence -> R -> Prop.

(** The one property C2 needs: the domain is closed under negation and [F (-s) = - F s]. *)
Definition odd (F : functional) : Prop := forall s v, F s v <-> F (neg s) (- v).

(** Linearity on the domain: sums and scalar multiples of sequences in the domain are in the
    domain, with the sum and multiple of the values. *)
Definition linear (F : functional) : Prop :=
  (forall s t v w, F s v -> F t w -> F (fun k => s k + t k) (v + w)) /\
  (forall c s v, F s v -> F (fun k => c * s k) (c * v)).

(** A functional takes at most one value on each sequence (a partial map). *)
Definition single_valued (F : functional) : Prop := forall s v w, F s v -> F s w -> v = w.

(** The functional depends on the stage values only (not on how the sequence is written). *)
Definition extensional (F : functional) : Prop :=
  forall s t v, (forall k, s k = t k) -> F s v -> F t v.

Section Optimality.

  Variable Pi : Type.
  Variable adm : Pi -> Prop.
  Variable stage : Pi -> sequence.

  (** [pi] minimises [F] of the stage sequences over the admissible policies: it is admissible,
      its stage sequence has a value, and no admissible policy has a smaller one. *)
  Definition minimises (F : functional) (val : Pi -> sequence) (pi : Pi) : Prop :=
    adm pi /\ exists v, F (val pi) v /\ forall sigma w, adm sigma -> F (val sigma) w -> v <= w.

  (** [pi] maximises [F] of the stage sequences over the admissible policies. *)
  Definition maximises (F : functional) (val : Pi -> sequence) (pi : Pi) : Prop :=
    adm pi /\ exists v, F (val pi) v /\ forall sigma w, adm sigma -> F (val sigma) w -> w <= v.

  (** The reward sequence of a policy, [r = -l] stage by stage. *)
  Definition reward (pi : Pi) : sequence := neg (stage pi).

  (** C2 (docs/spec.md §6; [src/claims/c2.rs], [STATEMENT]): for every odd functional [F] -- in
      particular every linear one, see [c2_linear] -- [pi] minimises the cost [F (l)] over the
      admissible policies iff it maximises the reward [F (-l)]. *)
  Theorem c2_cost_reward_equivalence :
    forall F, odd F -> forall pi, minimises F stage pi <-> maximises F reward pi.
  Proof.
    intros F Hodd pi; unfold minimises, maximises, reward; split.
    - intros [Hpi [v [Hv Hmin]]]; split; [exact Hpi|].
      exists (- v); split; [apply (proj1 (Hodd _ _)), Hv|].
      intros sigma w Hs Hw.
      assert (F (stage sigma) (- w)) as H.
      { apply (proj2 (Hodd _ _)); rewrite Ropp_involutive; exact Hw. }
      specialize (Hmin sigma (- w) Hs H); lra.
    - intros [Hpi [v [Hv Hmax]]]; split; [exact Hpi|].
      exists (- v); split.
      + apply (proj2 (Hodd _ _)); rewrite Ropp_involutive; exact Hv.
      + intros sigma w Hs Hw.
        specialize (Hmax sigma (- w) Hs (proj1 (Hodd _ _) Hw)); lra.
  Qed.

End Optimality.

(** ** Linear functionals are odd *)

Lemma linear_odd : forall F, extensional F -> linear F -> odd F.
Proof.
  intros F Hext [_ Hscale] s v; split; intro H.
  - apply (Hext (fun k => -1 * s k)); [intro k; unfold neg; ring|].
    replace (- v) with (-1 * v) by ring; apply Hscale, H.
  - apply (Hext (fun k => -1 * neg s k)); [intro k; unfold neg; ring|].
    replace v with (-1 * - v) by ring; apply Hscale, H.
Qed.

(** C2 for every linear functional, as the registry states it. *)
Corollary c2_linear :
  forall Pi adm (stage : Pi -> sequence) F, extensional F -> linear F ->
  forall pi, minimises Pi adm F stage pi <-> maximises Pi adm F (reward Pi stage) pi.
Proof.
  intros Pi adm stage F Hext Hlin.
  apply c2_cost_reward_equivalence, linear_odd; assumption.
Qed.

(** ** Two ways to build odd functionals *)

(** A limit functional: [F s v] iff the sequence [T s] tends to [v], for a transform [T] of
    the stage sequence that commutes with negation (partial sums, weighted partial sums, running
    means). The domain is the set of [s] for which [T s] converges. *)
Definition limit_of (T : sequence -> sequence) : functional := fun s v => Un_cv (T s) v.

Lemma Un_cv_ext : forall u w l, (forall n, u n = w n) -> Un_cv u l -> Un_cv w l.
Proof.
  intros u w l Heq H eps Heps; destruct (H eps Heps) as [N HN].
  exists N; intros n Hn; rewrite <- Heq; apply HN, Hn.
Qed.

Lemma Un_cv_opp : forall u l, Un_cv u l <-> Un_cv (neg u) (- l).
Proof.
  intros u l; split; intro H.
  - apply CV_opp, H.
  - apply (Un_cv_ext (opp_seq (neg u))); [intro n; unfold opp_seq, neg; ring|].
    rewrite <- (Ropp_involutive l); apply CV_opp, H.
Qed.

Lemma limit_of_odd :
  forall T, (forall s n, T (neg s) n = - T s n) -> odd (limit_of T).
Proof.
  intros T HT s v; unfold limit_of; rewrite Un_cv_opp.
  split; apply Un_cv_ext; intro n; rewrite HT; unfold neg; ring.
Qed.

(** A functional given by a formula on every sequence (the finite-horizon ones). *)
Definition formula (E : sequence -> R) : functional := fun s v => v = E s.

Lemma formula_odd : forall E, (forall s, E (neg s) = - E s) -> odd (formula E).
Proof. intros E HE s v; unfold formula; rewrite HE; split; intro; lra. Qed.

Lemma limit_of_single_valued : forall T, single_valued (limit_of T).
Proof. intros T s v w; apply UL_sequence. Qed.

Lemma formula_single_valued : forall E, single_valued (formula E).
Proof. intros E s v w -> ->; reflexivity. Qed.

(** ** Finite sums *)

(** [partial s K = s 0 + ... + s (K - 1)], the sum of the first [K] stages. *)
Fixpoint partial (s : sequence) (K : nat) : R :=
  match K with O => 0 | S K' => partial s K' + s K' end.

Lemma partial_neg : forall s K, partial (neg s) K = - partial s K.
Proof. intros s K; induction K as [|K IH]; simpl; [ring|rewrite IH; unfold neg; ring]. Qed.

Lemma partial_plus :
  forall s t K, partial (fun k => s k + t k) K = partial s K + partial t K.
Proof. intros s t K; induction K as [|K IH]; simpl; [ring|rewrite IH; ring]. Qed.

Lemma partial_scale : forall c s K, partial (fun k => c * s k) K = c * partial s K.
Proof. intros c s K; induction K as [|K IH]; simpl; [ring|rewrite IH; ring]. Qed.

Lemma partial_ext : forall s t K, (forall k, s k = t k) -> partial s K = partial t K.
Proof. intros s t K H; induction K as [|K IH]; simpl; [reflexivity|rewrite IH, H; reflexivity]. Qed.

(** The standard library's partial sums [sum_f_R0 s n = s 0 + ... + s n] are ours shifted. *)
Lemma sum_f_R0_partial : forall s n, sum_f_R0 s n = partial s (S n).
Proof. intros s n; induction n as [|n IH]; simpl; [ring|rewrite IH; reflexivity]. Qed.

(** ** Total cost: the sum of the series, on the sequences whose series converges *)

(** [total s v]: the series of the stages converges to [v] (the standard library's
    [infinite_sum], i.e. [Un_cv] of the partial sums). *)
Definition total : functional := fun s v => infinite_sum s v.

Lemma total_is_limit : forall s v, total s v <-> limit_of (fun s n => sum_f_R0 s n) s v.
Proof. intros s v; unfold total, limit_of, infinite_sum, Un_cv; tauto. Qed.

Lemma total_single_valued : single_valued total.
Proof. intros s v w; apply uniqueness_sum. Qed.

Lemma total_odd : odd total.
Proof.
  intros s v; rewrite !total_is_limit; apply limit_of_odd.
  intros t n; rewrite !sum_f_R0_partial; apply partial_neg.
Qed.

Lemma total_extensional : extensional total.
Proof.
  intros s t v H Hs; apply total_is_limit; apply total_is_limit in Hs.
  unfold limit_of in *; apply (Un_cv_ext (fun n => sum_f_R0 s n)); [|exact Hs].
  intro n; rewrite !sum_f_R0_partial; apply partial_ext, H.
Qed.

Lemma total_linear : linear total.
Proof.
  split.
  - intros s t v w Hs Ht; apply total_is_limit; unfold limit_of.
    apply (Un_cv_ext (fun n => sum_f_R0 s n + sum_f_R0 t n)).
    + intro n; rewrite plus_sum; reflexivity.
    + apply CV_plus; assumption.
  - intros c s v Hs; apply total_is_limit; unfold limit_of.
    apply (Un_cv_ext (fun n => (fun _ => c) n * sum_f_R0 s n)).
    + intro n; rewrite !sum_f_R0_partial, partial_scale; reflexivity.
    + apply CV_mult; [intros eps Heps; exists O; intros; unfold R_dist;
                      rewrite Rminus_diag_eq, Rabs_R0; lra|exact Hs].
Qed.

(** A stage sequence that is zero from some stage on (a goal-reaching action sequence followed
    by termination, whose stages cost 0) has a total cost: the sum of its first stages. *)
Lemma total_eventually_zero :
  forall s K, (forall k, (K <= k)%nat -> s k = 0) -> total s (partial s K).
Proof.
  intros s K HK eps Heps; exists K; intros n Hn.
  assert (sum_f_R0 s n = partial s K) as ->.
  { rewrite sum_f_R0_partial; replace (S n) with (K + (S n - K))%nat by lia.
    induction (S n - K)%nat as [|j IH]; [rewrite Nat.add_0_r; reflexivity|].
    rewrite Nat.add_succ_r; simpl; rewrite IH, HK by lia; ring. }
  unfold R_dist; rewrite Rminus_diag_eq, Rabs_R0; lra.
Qed.

(** C2 for the total cost, over any admissible set whose stage sequences' series converge
    (the domain; outside it the total has no value and no policy there is a minimiser). *)
Theorem c2_total :
  forall Pi adm (stage : Pi -> sequence) pi,
  minimises Pi adm total stage pi <-> maximises Pi adm total (reward Pi stage) pi.
Proof. intros; apply c2_cost_reward_equivalence, total_odd. Qed.

(** ** Discounted cost *)

(** [discounted alpha s v]: [sum_k alpha^k s k] converges to [v]. *)
Definition discounted (alpha : R) : functional := fun s v => total (fun k => alpha ^ k * s k) v.

Lemma discounted_odd : forall alpha, odd (discounted alpha).
Proof.
  intros alpha s v; unfold discounted; rewrite (total_odd _ v).
  split; intro H; (eapply total_extensional; [|exact H]); intro k; unfold neg; ring.
Qed.

Lemma discounted_single_valued : forall alpha, single_valued (discounted alpha).
Proof. intros alpha s; apply total_single_valued. Qed.

Lemma discounted_linear : forall alpha, linear (discounted alpha).
Proof.
  intro alpha; destruct total_linear as [Hplus Hscale]; unfold discounted; split.
  - intros s t v w Hs Ht; eapply total_extensional; [|apply (Hplus _ _ _ _ Hs Ht)].
    intro k; simpl; ring.
  - intros c s v Hs; eapply total_extensional; [|apply (Hscale c _ _ Hs)].
    intro k; simpl; ring.
Qed.

(** Bounded stage costs have a discounted cost when [0 <= alpha < 1] (every stage cost of a
    finite problem is bounded by the largest one). *)
Lemma discounted_converges :
  forall alpha s M, 0 <= alpha < 1 -> (forall k, Rabs (s k) <= M) ->
  exists v, discounted alpha s v.
Proof.
  intros alpha s M Ha Hs.
  assert (0 <= M) as HM by (specialize (Hs O); pose proof (Rabs_pos (s O)); lra).
  assert {l | Un_cv (fun N => sum_f_R0 (fun k => M * alpha ^ k) N) l} as Hgeom.
  { exists (M * / (1 - alpha)).
    apply (Un_cv_ext (fun N => (fun _ => M) N * sum_f_R0 (fun k => 1 * alpha ^ k) N)).
    - intro n; rewrite !sum_f_R0_partial, <- partial_scale; apply partial_ext; intro; ring.
    - apply CV_mult; [intros eps Heps; exists O; intros; unfold R_dist;
                      rewrite Rminus_diag_eq, Rabs_R0; lra|].
      apply GP_infinite; rewrite Rabs_right; lra. }
  assert {l | Un_cv (fun N => sum_f_R0 (fun k => Rabs (alpha ^ k * s k)) N) l} as Habs.
  { apply (Rseries_CV_comp _ (fun k => M * alpha ^ k)); [|exact Hgeom].
    intro n; split; [apply Rabs_pos|]; simpl.
    rewrite Rabs_mult, (Rabs_right (alpha ^ n)) by (apply Rle_ge, pow_le; lra).
    rewrite (Rmult_comm (alpha ^ n)).
    apply Rmult_le_compat_r; [apply pow_le; lra|apply Hs]. }
  destruct (cv_cauchy_2 _ (cauchy_abs _ (cv_cauchy_1 _ Habs))) as [l Hl].
  exists l; exact Hl.
Qed.

(** C2 for the discounted cost, for every discount factor. *)
Theorem c2_discounted :
  forall alpha Pi adm (stage : Pi -> sequence) pi,
  minimises Pi adm (discounted alpha) stage pi <->
  maximises Pi adm (discounted alpha) (reward Pi stage) pi.
Proof. intros; apply c2_cost_reward_equivalence, discounted_odd. Qed.

(** With [0 < alpha < 1] and bounded stage costs, every admissible policy has a discounted cost
    and a discounted reward, so the two optimisation problems of [c2_discounted] range over the
    whole admissible set. *)
Corollary c2_discounted_bounded :
  forall alpha Pi adm (stage : Pi -> sequence) M,
  0 < alpha < 1 -> (forall pi k, Rabs (stage pi k) <= M) ->
  (forall pi, exists v, discounted alpha (stage pi) v) /\
  (forall pi, exists v, discounted alpha (reward Pi stage pi) v) /\
  (forall pi, minimises Pi adm (discounted alpha) stage pi <->
              maximises Pi adm (discounted alpha) (reward Pi stage) pi).
Proof.
  intros alpha Pi adm stage M Ha HM; split; [|split].
  - intro pi; apply (discounted_converges _ _ M); [lra|apply HM].
  - intro pi; apply (discounted_converges _ _ M); [lra|].
    intro k; unfold reward, neg; rewrite Rabs_Ropp; apply HM.
  - apply c2_discounted.
Qed.

(** ** Long-run average cost *)

(** [average s v]: the mean of the first [N + 1] stages tends to [v]. *)
Definition average : functional :=
  limit_of (fun s N => partial s (S N) / INR (S N)).

Lemma average_odd : odd average.
Proof. apply limit_of_odd; intros s n; rewrite partial_neg; unfold Rdiv; ring. Qed.

Theorem c2_average :
  forall Pi adm (stage : Pi -> sequence) pi,
  minimises Pi adm average stage pi <-> maximises Pi adm average (reward Pi stage) pi.
Proof. intros; apply c2_cost_reward_equivalence, average_odd. Qed.

(** ** Finite-horizon costs ([K] stages) *)

Definition horizon_total (K : nat) : functional := formula (fun s => partial s K).

Definition horizon_discounted (K : nat) (alpha : R) : functional :=
  formula (fun s => partial (fun k => alpha ^ k * s k) K).

Definition horizon_average (K : nat) : functional := formula (fun s => partial s K / INR K).

Lemma horizon_total_linear : forall K, linear (horizon_total K).
Proof.
  intro K; unfold horizon_total, formula; split; intros; subst;
    [rewrite partial_plus|rewrite partial_scale]; reflexivity.
Qed.

Theorem c2_horizon_total :
  forall K Pi adm (stage : Pi -> sequence) pi,
  minimises Pi adm (horizon_total K) stage pi <->
  maximises Pi adm (horizon_total K) (reward Pi stage) pi.
Proof. intros; apply c2_cost_reward_equivalence, formula_odd; intro s; apply partial_neg. Qed.

Theorem c2_horizon_discounted :
  forall K alpha Pi adm (stage : Pi -> sequence) pi,
  minimises Pi adm (horizon_discounted K alpha) stage pi <->
  maximises Pi adm (horizon_discounted K alpha) (reward Pi stage) pi.
Proof.
  intros; apply c2_cost_reward_equivalence, formula_odd; intro s.
  rewrite <- partial_neg; apply partial_ext; intro k; unfold neg; ring.
Qed.

Theorem c2_horizon_average :
  forall K Pi adm (stage : Pi -> sequence) pi,
  minimises Pi adm (horizon_average K) stage pi <->
  maximises Pi adm (horizon_average K) (reward Pi stage) pi.
Proof.
  intros; apply c2_cost_reward_equivalence, formula_odd; intro s.
  rewrite partial_neg; unfold Rdiv; ring.
Qed.

(** ** Total cost with infinite values *)

(** The total cost of docs/spec.md §1 takes values in the extended reals: a policy whose stage costs
    sum to [+oo] (a cycle of positive cost, never reaching the goal) has total cost [+oo], and
    its total reward is [-oo]. [total] above has no value on such a sequence; [total_ext] gives
    it one, and [c2_total_extended] is C2 over the extended reals, with [-oo <= v <= +oo]. *)
Inductive ext := Fin (r : R) | PInf | NInf.

Definition ext_le (a b : ext) : Prop :=
  match a, b with
  | NInf, _ | _, PInf => True
  | Fin x, Fin y => x <= y
  | _, _ => False
  end.

Definition ext_opp (a : ext) : ext :=
  match a with Fin x => Fin (- x) | PInf => NInf | NInf => PInf end.

(** [total_ext s v]: the partial sums of [s] converge to [v], or tend to [+oo] ([v = PInf]) or
    to [-oo] ([v = NInf]) (the standard library's [cv_infty]). *)
Definition total_ext (s : sequence) (v : ext) : Prop :=
  match v with
  | Fin r => total s r
  | PInf => cv_infty (fun n => sum_f_R0 s n)
  | NInf => cv_infty (fun n => - sum_f_R0 s n)
  end.

Lemma cv_infty_ext : forall u w, (forall n, u n = w n) -> cv_infty u -> cv_infty w.
Proof.
  intros u w Heq H M; destruct (H M) as [N HN]; exists N; intros n Hn; rewrite <- Heq; auto.
Qed.

Lemma sum_f_R0_neg : forall s n, sum_f_R0 (neg s) n = - sum_f_R0 s n.
Proof. intros s n; rewrite !sum_f_R0_partial; apply partial_neg. Qed.

Lemma total_ext_odd : forall s v, total_ext s v <-> total_ext (neg s) (ext_opp v).
Proof.
  intros s [r| |]; simpl.
  - apply total_odd.
  - split; apply cv_infty_ext; intro n; rewrite sum_f_R0_neg; ring.
  - split; apply cv_infty_ext; intro n; rewrite sum_f_R0_neg; ring.
Qed.

Lemma ext_opp_involutive : forall a, ext_opp (ext_opp a) = a.
Proof. intros [r| |]; simpl; [rewrite Ropp_involutive|..]; reflexivity. Qed.

Lemma ext_le_opp : forall a b, ext_le a b -> ext_le (ext_opp b) (ext_opp a).
Proof. intros [x| |] [y| |]; simpl; auto; lra. Qed.

Section Extended.

  Variable Pi : Type.
  Variable adm : Pi -> Prop.
  Variable stage : Pi -> sequence.

  (** [minimises] and [maximises] with values in the extended reals. *)
  Definition minimises_ext (F : sequence -> ext -> Prop) (val : Pi -> sequence) (pi : Pi) :=
    adm pi /\
    exists v, F (val pi) v /\ forall sigma w, adm sigma -> F (val sigma) w -> ext_le v w.

  Definition maximises_ext (F : sequence -> ext -> Prop) (val : Pi -> sequence) (pi : Pi) :=
    adm pi /\
    exists v, F (val pi) v /\ forall sigma w, adm sigma -> F (val sigma) w -> ext_le w v.

  (** C2 for the total cost in [[-oo, +oo]] (docs/spec.md §6; [src/claims/c2.rs], [STATEMENT]): [pi]
      minimises the total cost iff it maximises the total reward [r = -l], the policies
      of infinite cost compared too. *)
  Theorem c2_total_extended :
    forall pi, minimises_ext total_ext stage pi <-> maximises_ext total_ext (reward Pi stage) pi.
  Proof.
    intro pi; unfold minimises_ext, maximises_ext, reward; split.
    - intros [Hpi [v [Hv Hmin]]]; split; [exact Hpi|].
      exists (ext_opp v); split; [apply (proj1 (total_ext_odd _ _)), Hv|].
      intros sigma w Hs Hw.
      rewrite <- (ext_opp_involutive w); apply ext_le_opp, (Hmin sigma); [exact Hs|].
      apply (proj2 (total_ext_odd _ _)); rewrite ext_opp_involutive; exact Hw.
    - intros [Hpi [v [Hv Hmax]]]; split; [exact Hpi|].
      exists (ext_opp v); split.
      + apply (proj2 (total_ext_odd _ _)); rewrite ext_opp_involutive; exact Hv.
      + intros sigma w Hs Hw.
        rewrite <- (ext_opp_involutive w); apply ext_le_opp, (Hmax sigma); [exact Hs|].
        apply (proj1 (total_ext_odd _ _)), Hw.
  Qed.

End Extended.

(** ** C2 on the model: goal-reaching move sequences of a finite problem *)

From Coq Require Import QArith Qreals List.
Import ListNotations.
From Truecost Require Import Model Paths.

Open Scope R_scope.

(** The stage costs of the move sequence [w] from [x] (Model.v's [wvalid], [wcost]): the costs
    of its moves, then [0] for ever (termination at the goal, docs/spec.md §1). *)
Fixpoint move_stages (P : problem) (x : nat) (w : list nat) : sequence :=
  match w with
  | nil => fun _ => 0
  | i :: w' => fun k => match k with
                        | O => Q2R (cost P x (Move i))
                        | S k' => move_stages P (target P x (Move i)) w' k'
                        end
  end.

Lemma move_stages_partial :
  forall P x w, partial (move_stages P x w) (length w) = Q2R (wcost P x w).
Proof.
  intros P x w; revert x; induction w as [|i w IH]; intro x; simpl; [apply eq_sym, RMicromega.Q2R_0|].
  rewrite Q2R_plus, <- IH.
  assert (E : forall s a K, partial (fun k => match k with O => a | S k' => s k' end) (S K)
                            = a + partial s K).
  { intros s a K; induction K as [|K IHK]; [simpl; ring|].
    change (partial (fun k => match k with O => a | S k' => s k' end) (S (S K)))
      with (partial (fun k => match k with O => a | S k' => s k' end) (S K) + s K).
    rewrite IHK; simpl; ring. }
  apply E.
Qed.

Lemma move_stages_zero :
  forall P x w k, (length w <= k)%nat -> move_stages P x w k = 0.
Proof.
  intros P x w; revert x; induction w as [|i w IH]; intros x k Hk; [reflexivity|].
  destruct k as [|k]; simpl in Hk; [lia|]; apply IH; lia.
Qed.

(** The total cost of a move sequence is its cost [wcost]. *)
Lemma move_stages_total : forall P x w, total (move_stages P x w) (Q2R (wcost P x w)).
Proof.
  intros P x w; rewrite <- move_stages_partial.
  apply total_eventually_zero; intros k Hk; apply move_stages_zero, Hk.
Qed.

(** C2 on every finite problem of the model: over the goal-reaching move sequences from [x]
    ([reaches P x], Model.v), [w] minimises the total cost iff it maximises the total reward
    [r = -l] -- and ([c2_model_Gstar]) the minimisers are the sequences of cost [G*(x)]. *)
Theorem c2_model :
  forall P x w,
  minimises (list nat) (reaches P x) total (move_stages P x) w <->
  maximises (list nat) (reaches P x) total (reward (list nat) (move_stages P x)) w.
Proof. intros; apply c2_total. Qed.

Theorem c2_model_Gstar :
  forall P x w, wf P -> (x < nstates P)%nat ->
  minimises (list nat) (reaches P x) total (move_stages P x) w <->
  reaches P x w /\ exists g, Gstar P x = Some g /\ (wcost P x w == g)%Q.
Proof.
  intros P x w HP Hx; split.
  - intros [Hw [v [Hv Hmin]]]; split; [exact Hw|].
    rewrite (total_single_valued _ _ _ Hv (move_stages_total P x w)) in Hmin.
    destruct (Gstar_least P HP x w Hx Hw) as (g & Eg & Hle).
    exists g; split; [exact Eg|].
    destruct (Gstar_attained P HP x g Hx Eg) as (w' & Hw' & Hc).
    pose proof (Hmin w' _ Hw' (move_stages_total P x w')) as H.
    rewrite (Qeq_eqR _ _ Hc) in H; apply Rle_Qle in H.
    apply Qle_antisym; assumption.
  - intros [Hw (g & Eg & Hc)]; split; [exact Hw|].
    exists (Q2R (wcost P x w)); split; [apply move_stages_total|].
    intros w' v Hw' Hv.
    rewrite (total_single_valued _ _ _ Hv (move_stages_total P x w')).
    destruct (Gstar_least P HP x w' Hx Hw') as (g' & Eg' & Hle).
    rewrite Eg in Eg'; injection Eg' as <-.
    apply Qle_Rle, (Qle_trans _ g); [rewrite Hc; apply Qle_refl|exact Hle].
Qed.
