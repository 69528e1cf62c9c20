(** * The bridge for C3 and C4: C3.v's and C4.v's terms evaluated against the kernel's oracles

    The theorems of C4.v ([c4_corrected], [c4_corrected_sufficient], [c4_corrected_necessary])
    are about [corrected_interval], a bound over every simple goal path from [x1] and every
    goal-avoiding simple cycle reachable from [x1]; those of C3 ([C3.c3_engine],
    [C3Engine.c3_engine_lasso], [C3Certificate.c3_certificate_engine]) about [in_core],
    [core_pi], [lasso_marks], [cert_K] and [engine_certificate]. This file gives computable enumerations of the simple
    goal paths ([goal_paths]) and of the goal-avoiding simple cycles ([avoid_cycles]), proves
    them exact ([goal_paths_spec], [avoid_cycles_spec]), and computes from them [L* = G*(x1)],
    the values of [S*] ([sstars]), [Lav(C^)] ([Lav]) and the corrected interval's ends
    ([c_lo], [c_hi]); [corrected_interval_bounds] proves that a bonus lies in
    [corrected_interval] iff it lies between [c_lo] and [c_hi], and [c4_corrected_computed]
    restates [c4_corrected] with these ends. [neg_interval_spec]: the kernel's form of the
    interval (ends closed or open, [M < 0] included) is the same set of bonuses. C3.v's
    definitions are computable as they stand and are evaluated directly.

    The kernel's test [kernel/tests/coq_bridge_c34.rs] writes problems of [claims::tiny]'s
    enumeration together with the kernel's values (the simple goal paths' [(L(u), S(u))], the
    bonus sets of [claims::c4::bonus_analysis], [Lav(C^)] of [Instance::least_mean_cycle], the
    goal-avoiding core and the certificates of [claims::c3::certificate]) and evaluates
    [check_all] below on them by [vm_compute]; [check_problem_sound] says what zero mismatches
    mean. *)

From Coq Require Import String Reals Lra Lia QArith Qreals List.
From Coq Require Lqa.
From Truecost Require Import Model Paths C2 QReal C3 C4.
From Truecost Require Bridge.
From Truecost Require Export BridgeCommon.
Import ListNotations.

Open Scope Q_scope.

(** ** Walks of bounded length, simple goal paths, goal-avoiding simple cycles *)

(** Every valid walk from [x] with at most [k] moves, in lexicographic order of the move
    indices (a walk before its extensions): the order of the kernel's depth-first search. *)
Fixpoint walks_from (P : problem) (k x : nat) : list (list nat) :=
  match k with
  | O => [[]]
  | S k' => [] :: flat_map (fun i => map (cons i) (walks_from P k' (target P x (Move i))))
                   (seq 0 (length (moves P x)))
  end.

Fixpoint nodupb (l : list nat) : bool :=
  match l with [] => true | a :: t => negb (existsb (Nat.eqb a) t) && nodupb t end.

(** The walk from [x] never visits the goal. *)
Definition avoids_goal (P : problem) (x : nat) (w : list nat) : bool :=
  negb (existsb (Nat.eqb (goal P)) (trace P x w)).

(** The simple goal paths from [x1 = 0] ([C4.simple_goal_path]). *)
Definition goal_paths (P : problem) : list (list nat) :=
  filter (fun u => Nat.eqb (wend P 0 u) (goal P) && nodupb (trace P 0 u))
         (walks_from P (pred (nstates P)) 0).

(** [y] is reachable from [x1] by a walk avoiding the goal ([C4.reach_avoid]). *)
Definition reach_avoidb (P : problem) (y : nat) : bool :=
  existsb (fun p => Nat.eqb (wend P 0 p) y && avoids_goal P 0 p)
          (walks_from P (pred (nstates P)) 0).

Definition cycle_okb (P : problem) (x : nat) (c : list nat) : bool :=
  negb (Nat.eqb (length c) 0) && Nat.eqb (wend P x c) x && nodupb (tl (trace P x c))
  && avoids_goal P x c.

(** The goal-avoiding simple cycles reachable from [x1] avoiding the goal
    ([C4.avoiding_cycle]), each with its start state. *)
Definition avoid_cycles (P : problem) : list (nat * list nat) :=
  flat_map (fun x => if reach_avoidb P x
                     then map (pair x) (filter (cycle_okb P x) (walks_from P (nstates P) x))
                     else [])
           (seq 0 (nstates P)).

(** ** The terms of C4-corrected *)

Fixpoint qmax_opt (l : list Q) : option Q :=
  match l with
  | [] => None
  | a :: t => match qmax_opt t with None => Some a | Some m => Some (Qmax2 a m) end
  end.

Fixpoint qmin_opt (l : list Q) : option Q :=
  match l with
  | [] => None
  | a :: t => match qmin_opt t with None => Some a | Some m => Some (Qmin2 a m) end
  end.

Definition qnat (k : nat) : Q := inject_Z (Z.of_nat k).

(** [(L(u), S(u))] of every simple goal path from [x1]. *)
Definition path_LS (P : problem) : list (Q * nat)%type :=
  map (fun u => (wcost P 0 u, S (length u))) (goal_paths P).

(** The values of [S*]: the numbers of states of the optimal simple goal paths from [x1]
    (cost [L* = G*(x1)]), increasing. *)
Definition sstars_of (g : option Q) (P : problem) : list nat :=
  match g with
  | None => []
  | Some l => filter (fun s => existsb (fun u => Nat.eqb (S (length u)) s &&
                                                   Qeq_bool (wcost P 0 u) l) (goal_paths P))
                     (seq 1 (nstates P))
  end.

Definition sstars (P : problem) : list nat := sstars_of (Gstar P 0) P.

(** [T(u) = (S_star L(u) - S(u) L_star) / (S(u) - S_star)] (C4.v's [T_of]). *)
Definition T_Q (s : nat) (Ls Lu : Q) (su : nat) : Q :=
  (qnat s * Lu - qnat su * Ls) / (qnat su - qnat s).

Definition T_below (P : problem) (s : nat) (Ls : Q) : list Q :=
  map (fun u => T_Q s Ls (wcost P 0 u) (S (length u)))
      (filter (fun u => Nat.ltb (S (length u)) s) (goal_paths P)).

Definition T_above (P : problem) (s : nat) (Ls : Q) : list Q :=
  map (fun u => T_Q s Ls (wcost P 0 u) (S (length u)))
      (filter (fun u => Nat.ltb s (S (length u))) (goal_paths P)).

(** The mean cost of every goal-avoiding simple cycle, and the least: [Lav(C^)] ([None]: no
    such cycle, [+oo]). *)
Definition cycle_means (P : problem) : list Q :=
  map (fun xc => wcost P (fst xc) (snd xc) / qnat (length (snd xc))) (avoid_cycles P).

Definition Lav (P : problem) : option Q := qmin_opt (cycle_means P).

(** The corrected interval's ends: [max{T(u) : S(u) < S*}] ([None]: [-oo]) and
    [min{ min{T(u) : S(u) > S*}, S* Lav(C^) - L* }] ([None]: [+oo]). *)
Definition c_lo (P : problem) (s : nat) (Ls : Q) : option Q := qmax_opt (T_below P s Ls).

Definition c_hi (P : problem) (s : nat) (Ls : Q) : option Q :=
  omin (qmin_opt (T_above P s Ls)) (option_map (fun l => qnat s * l - Ls) (Lav P)).

(** ** The kernel's form of an interval of bonuses *)

Definition Qlt_bool (a b : Q) : bool := negb (Qle_bool b a).

(** An end: unbounded, closed or open (the kernel's [claims::c4::End]). *)
Inductive iend := Unb | Cl (q : Q) | Op (q : Q).

(** The set [{M : M < 0, lo <= M <= hi}] as the kernel writes it: the lower end closed or
    unbounded, the upper end closed below [0] and [0] open otherwise, and whether it is
    empty. *)
Definition neg_interval (lo hi : option Q) : (iend * iend * bool)%type :=
  let l := match lo with None => Unb | Some a => Cl a end in
  let h := match hi with Some b => if Qlt_bool b 0 then Cl b else Op 0 | None => Op 0 end in
  let e := match l, h with
           | Cl a, Cl b => Qlt_bool b a
           | Cl a, Op b => Qle_bool b a
           | _, _ => false
           end in
  (l, h, e).

(** Membership, as the kernel's [Interval::contains]. *)
Definition iv_contains (iv : (iend * iend * bool)%type) (m : Q) : bool :=
  let '(l, h, e) := iv in
  negb e &&
  match l with Unb => true | Cl a => Qle_bool a m | Op a => Qlt_bool a m end &&
  match h with Unb => true | Cl b => Qle_bool m b | Op b => Qlt_bool m b end.

(** ** The values *)

Definition states (P : problem) : list nat := seq 0 (nstates P).

Record values := {
  v_Lstar : option Q;                                  (** [G*(x1)] *)
  v_paths : list (Q * nat)%type;                            (** [path_LS] *)
  v_Lav : option Q;                                    (** [Lav(C^)] *)
  v_sets : list (Q * nat * option Q * (iend * iend * bool))%type;
    (** for every [S*]: [L*], [S*], [Lav(C^)], the corrected interval with [M < 0] *)
  v_core : list bool;                                  (** [in_core] of every state *)
  v_certs : list (option (list (list Q)))
    (** for every [alpha0]: the engine certificate's move costs, state by state, when the
        engine builds one ([x1] in the core and the goal reachable) *)
}.

(** C3's engine certificate for [alpha0] (C3.v's [engine_certificate] with [lasso_marks] of
    [core_pi], [n] states), its move costs state by state. *)
Definition cert_costs (P : problem) (alpha0 : Q) : list (list Q) :=
  let C := engine_certificate P (lasso_marks P (core_pi P)) alpha0 (nstates P) in
  map (fun x => map snd (moves C x)) (states P).

(** The engine builds a certificate when [x1] is in the goal-avoiding core and the goal is
    reachable from [x1] ([g] is [G*(x1)]). *)
Definition engine_builds (g : option Q) (P : problem) : bool :=
  in_core P 0 && match g with Some _ => true | None => false end.

(** The values, given [g = G*(x1)]. *)
Definition values_of (g : option Q) (P : problem) (alphas : list Q) : values := {|
  v_Lstar := g;
  v_paths := path_LS P;
  v_Lav := Lav P;
  v_sets := match g with
            | None => []
            | Some l => map (fun s => (l, s, Lav P, neg_interval (c_lo P s l) (c_hi P s l)))
                            (sstars_of g P)
            end;
  v_core := map (in_core P) (states P);
  v_certs := map (fun a => if engine_builds g P then Some (cert_costs P a) else None) alphas
|}.

(** The values, from Model.v's [Gstar] and C3.v's and this file's definitions. *)
Definition model_values (P : problem) (alphas : list Q) : values :=
  values_of (Gstar P 0) P alphas.

(** The same, with [G*(x1)] evaluated once by Bridge.v's [bfl_shared] (Model.v's [bfl]
    re-evaluates the previous list once per state: exponential in the number of states). *)
Definition shared_values (P : problem) (alphas : list Q) : values :=
  values_of (nth 0 (Bridge.bfl_shared P (nstates P)) None) P alphas.

(** What the checker evaluates is [model_values]. *)
Theorem shared_values_eq P alphas : shared_values P alphas = model_values P alphas.
Proof.
  unfold shared_values, model_values; rewrite Bridge.bfl_shared_eq; reflexivity.
Qed.

(** ** Exactness of the enumerations *)

Lemma walks_from_spec P k x w :
  In w (walks_from P k x) <-> wvalid P x w /\ (length w <= k)%nat.
Proof.
  revert x w; induction k as [|k IH]; intros x w; simpl.
  - split; [intros [<-|[]]; simpl; auto|].
    intros [_ H]; destruct w; [auto|simpl in H; lia].
  - rewrite in_flat_map; split.
    + intros [<-|(i & Hi & Hw)]; [simpl; split; [auto|lia]|].
      apply in_map_iff in Hw as (w' & <- & Hw'); apply IH in Hw' as [Hv Hl].
      apply in_seq in Hi; simpl; split; [split; [lia|auto]|lia].
    + intros [Hv Hl]; destruct w as [|i w']; [left; auto|right].
      destruct Hv as [Hi Hv]; exists i; split; [apply in_seq; lia|].
      apply in_map; apply IH; simpl in Hl; split; [auto|lia].
Qed.

Lemma existsb_eqb a l : existsb (Nat.eqb a) l = true <-> In a l.
Proof.
  rewrite existsb_exists; split.
  - intros (b & Hb & E); apply Nat.eqb_eq in E; subst; auto.
  - intros H; exists a; split; [auto|apply Nat.eqb_refl].
Qed.

Lemma nodupb_spec l : nodupb l = true <-> NoDup l.
Proof.
  induction l as [|a t IH]; simpl; [split; auto; constructor|].
  rewrite andb_true_iff, negb_true_iff, IH; split.
  - intros [H1 H2]; constructor; auto; intros Hin; apply existsb_eqb in Hin; congruence.
  - intros H; inversion H; subst; split; auto.
    destruct (existsb (Nat.eqb a) t) eqn:E; auto; apply existsb_eqb in E; contradiction.
Qed.

Lemma avoids_goal_spec P x w : avoids_goal P x w = true <-> ~ In (goal P) (trace P x w).
Proof.
  unfold avoids_goal; rewrite negb_true_iff; split.
  - intros E H; apply existsb_eqb in H; congruence.
  - intros H; destruct (existsb _ _) eqn:E; auto; apply existsb_eqb in E; contradiction.
Qed.

Section Exact.
Variable P : problem.
Hypothesis HP : wf P.
Notation n := (nstates P).

Lemma n_pos : (0 < n)%nat.
Proof. destruct HP; lia. Qed.

(** The states of a walk are states: a walk whose states are distinct has fewer than [n]
    moves. *)
Lemma nodup_length x w :
  (x < n)%nat -> wvalid P x w -> NoDup (trace P x w) -> (length w < n)%nat.
Proof.
  intros Hx Hw Hnd; pose proof (NoDup_incl_length Hnd (l' := seq 0 n)) as H.
  rewrite trace_length, seq_length in H; apply H.
  intros z Hz; apply in_seq; split; [lia|]; simpl; eapply trace_lt; eauto.
Qed.

Lemma nodup_tl_length x w :
  (x < n)%nat -> wvalid P x w -> NoDup (tl (trace P x w)) -> (length w <= n)%nat.
Proof.
  intros Hx Hw Hnd; pose proof (NoDup_incl_length Hnd (l' := seq 0 n)) as H.
  replace (length (tl (trace P x w))) with (length w) in H
    by (pose proof (trace_length P x w) as L; destruct (trace P x w); simpl in *; lia).
  rewrite seq_length in H; apply H.
  intros z Hz; apply in_seq; split; [lia|]; simpl; eapply trace_lt; eauto.
  destruct (trace P x w); [destruct Hz|right; exact Hz].
Qed.

(** Every simple goal path from [x1], and nothing else, is in [goal_paths]. *)
Theorem goal_paths_spec u : In u (goal_paths P) <-> simple_goal_path P u.
Proof.
  unfold goal_paths, simple_goal_path, reaches; rewrite filter_In, walks_from_spec.
  rewrite andb_true_iff, Nat.eqb_eq, nodupb_spec; split; [tauto|].
  intros [[Hv He] Hnd]; repeat split; auto.
  pose proof (nodup_length 0 u n_pos Hv Hnd); lia.
Qed.

Lemma trace_cons x w : trace P x w = x :: tl (trace P x w).
Proof. destruct w; reflexivity. Qed.

(** Cutting out a closed part of a walk keeps its states among the walk's. *)
Lemma trace_cut x w1 w2 w3 z :
  wend P x w1 = wend P x (w1 ++ w2) ->
  In z (trace P x (w1 ++ w3)) -> In z (trace P x (w1 ++ w2 ++ w3)).
Proof.
  intros E; rewrite wend_app in E; rewrite !(trace_app P x w1), !in_app_iff.
  intros [H|H]; [left; auto|right].
  rewrite (trace_app P (wend P x w1) w2 w3), <- E.
  rewrite (trace_cons (wend P x w1) w2); simpl; apply in_app_iff; right; exact H.
Qed.

(** A walk avoiding the goal can be shortened to fewer than [n] moves, with the same end,
    still avoiding the goal. *)
Lemma avoid_short x w :
  (x < n)%nat -> wvalid P x w -> ~ In (goal P) (trace P x w) ->
  exists w', wvalid P x w' /\ wend P x w' = wend P x w /\ ~ In (goal P) (trace P x w') /\
             (length w' < n)%nat.
Proof.
  intros Hx; remember (length w) as m eqn:Hm; revert w Hm.
  induction m as [m IH] using (well_founded_induction lt_wf); intros w Hm Hw Hg.
  destruct (ListDec.NoDup_dec Nat.eq_dec (trace P x w)) as [Hnd|Hnd].
  - exists w; repeat split; auto; apply (nodup_length x w); auto.
  - destruct (repeat_split P x w Hnd) as (w1 & w2 & w3 & -> & Hne & E).
    assert (Hv : wvalid P x (w1 ++ w3)).
    { apply wvalid_app in Hw as [Hw1 Hw23]; apply wvalid_app in Hw23 as [Hw2 Hw3].
      apply wvalid_app; split; auto; rewrite wend_app in E; rewrite E; auto. }
    destruct (IH (length (w1 ++ w3))) with (w := w1 ++ w3) as (w' & Hv' & He' & Hg' & Hl');
      auto.
    + subst m; rewrite !app_length; destruct w2; [congruence|simpl; lia].
    + intros H; apply Hg, (trace_cut x w1 w2 w3); auto.
    + exists w'; repeat split; auto.
      rewrite He', !wend_app; rewrite wend_app in E; rewrite <- E; reflexivity.
Qed.

Theorem reach_avoidb_spec y : reach_avoidb P y = true <-> reach_avoid P y.
Proof.
  unfold reach_avoidb, reach_avoid; rewrite existsb_exists; split.
  - intros (p & Hp & E); apply walks_from_spec in Hp as [Hv _].
    apply andb_true_iff in E as [E1 E2]; apply Nat.eqb_eq in E1; apply avoids_goal_spec in E2.
    exists p; auto.
  - intros (p & Hv & He & Hg).
    destruct (avoid_short 0 p n_pos Hv Hg) as (p' & Hv' & He' & Hg' & Hl').
    exists p'; split; [apply walks_from_spec; split; [auto|lia]|].
    apply andb_true_iff; split; [apply Nat.eqb_eq; congruence|apply avoids_goal_spec; auto].
Qed.

(** Every goal-avoiding simple cycle reachable from [x1] avoiding the goal, and nothing else,
    is in [avoid_cycles]. *)
Theorem avoid_cycles_spec x c : In (x, c) (avoid_cycles P) <-> avoiding_cycle P x c.
Proof.
  unfold avoid_cycles, avoiding_cycle; rewrite in_flat_map; split.
  - intros (y & Hy & Hin); destruct (reach_avoidb P y) eqn:Ey; [|destruct Hin].
    apply in_map_iff in Hin as (c' & E & Hc); inversion E; subst y c'; clear E.
    apply filter_In in Hc as [Hw Hok]; apply walks_from_spec in Hw as [Hv _].
    unfold cycle_okb in Hok; rewrite !andb_true_iff, negb_true_iff, Nat.eqb_eq in Hok.
    destruct Hok as [[[H0 He] Hnd] Hg].
    apply nodupb_spec in Hnd; apply avoids_goal_spec in Hg.
    apply reach_avoidb_spec in Ey; auto.
    repeat split; auto; intros ->; simpl in H0; discriminate.
  - intros (Hne & Hv & He & Hnd & Hg & Hr).
    assert (Hx : (x < n)%nat).
    { destruct Hr as (p & Hp & Ep & _); rewrite <- Ep; apply wend_lt; auto; apply n_pos. }
    exists x; split; [apply in_seq; lia|].
    rewrite (proj2 (reach_avoidb_spec x) Hr); apply in_map, filter_In; split.
    + apply walks_from_spec; split; auto; apply (nodup_tl_length x c); auto.
    + unfold cycle_okb; rewrite !andb_true_iff, negb_true_iff, Nat.eqb_eq, nodupb_spec.
      repeat split; auto; [destruct c; [congruence|reflexivity]|].
      apply avoids_goal_spec; auto.
Qed.

End Exact.

(** ** Minima and maxima of lists *)

Lemma qmax_opt_some l m : qmax_opt l = Some m -> In m l /\ forall x, In x l -> x <= m.
Proof.
  revert m; induction l as [|a t IH]; intros m H; simpl in H; [discriminate|].
  destruct (qmax_opt t) as [m'|] eqn:E; inversion H; subst; clear H.
  - destruct (IH m' eq_refl) as [Hin Hle]; split.
    + destruct (Qmax2_cases a m') as [-> | ->]; [left|right]; auto.
    + intros x [<-|Hx]; [apply Qmax2_l|].
      apply Qle_trans with m'; [auto|apply Qmax2_r].
  - destruct t as [|b t]; [|simpl in E; destruct (qmax_opt t); discriminate].
    split; [left; auto|intros x [<-|[]]; apply Qle_refl].
Qed.

Lemma qmax_opt_in l x : In x l -> exists m, qmax_opt l = Some m /\ x <= m.
Proof.
  intros Hx; destruct (qmax_opt l) as [m|] eqn:E.
  - exists m; split; auto; apply (proj2 (qmax_opt_some l m E)); auto.
  - destruct l as [|a t]; [destruct Hx|simpl in E; destruct (qmax_opt t); discriminate].
Qed.

Lemma qmin_opt_some l m : qmin_opt l = Some m -> In m l /\ forall x, In x l -> m <= x.
Proof.
  revert m; induction l as [|a t IH]; intros m H; simpl in H; [discriminate|].
  destruct (qmin_opt t) as [m'|] eqn:E; inversion H; subst; clear H.
  - destruct (IH m' eq_refl) as [Hin Hle]; split.
    + destruct (Qmin2_cases a m') as [-> | ->]; [left|right]; auto.
    + intros x [<-|Hx]; [apply Qmin2_l|].
      apply Qle_trans with m'; [apply Qmin2_r|auto].
  - destruct t as [|b t]; [|simpl in E; destruct (qmin_opt t); discriminate].
    split; [left; auto|intros x [<-|[]]; apply Qle_refl].
Qed.

Lemma qmin_opt_in l x : In x l -> exists m, qmin_opt l = Some m /\ m <= x.
Proof.
  intros Hx; destruct (qmin_opt l) as [m|] eqn:E.
  - exists m; split; auto; apply (proj2 (qmin_opt_some l m E)); auto.
  - destruct l as [|a t]; [destruct Hx|simpl in E; destruct (qmin_opt t); discriminate].
Qed.

(** ** The corrected interval is the interval between [c_lo] and [c_hi] *)

Open Scope R_scope.

Lemma Q2R_qnat k : Q2R (qnat k) = INR k.
Proof. apply Q2R_nat. Qed.

Lemma T_Q_R P s Ls u :
  S (length u) <> s ->
  Q2R (T_Q s Ls (wcost P 0 u) (S (length u))) = T_of P (INR s) (Q2R Ls) u.
Proof.
  intros Hne; unfold T_Q, T_of, L_of, S_of.
  assert (Hd : ~ (qnat (S (length u)) - qnat s == 0)%Q).
  { intros E; apply Qeq_eqR in E; rewrite Q2R_minus, !Q2R_qnat, Q2R_0 in E.
    apply Hne, INR_eq; lra. }
  rewrite Q2R_div, Q2R_minus, !Q2R_mult, Q2R_minus, !Q2R_qnat by exact Hd; reflexivity.
Qed.

Lemma mean_R P x c :
  c <> [] -> Q2R (wcost P x c / qnat (length c)) = mean_of P x c.
Proof.
  intros Hne; unfold mean_of.
  assert (Hd : ~ (qnat (length c) == 0)%Q).
  { intros E; apply Qeq_eqR in E; rewrite Q2R_qnat, Q2R_0 in E.
    destruct c; [congruence|]; simpl length in E; rewrite S_INR in E.
    pose proof (pos_INR (length c)); lra. }
  rewrite Q2R_div, Q2R_qnat by exact Hd; reflexivity.
Qed.

(** A bonus [Mr] lies between two optional ends ([None]: unbounded). *)
Definition in_bounds (lo hi : option Q) (Mr : R) : Prop :=
  (forall l, lo = Some l -> Q2R l <= Mr) /\ (forall h, hi = Some h -> Mr <= Q2R h).

(** The computed ends are C4.v's interval: for every finite problem, every [S* > 0] and
    [L*], a bonus satisfies [corrected_interval] (every simple goal path's [T(u)] bound and
    every goal-avoiding simple cycle's bound) iff it lies in [[c_lo, c_hi]]. *)
Theorem corrected_interval_bounds P s Ls Mr :
  wf P -> (0 < s)%nat ->
  corrected_interval P (INR s) (Q2R Ls) Mr <-> in_bounds (c_lo P s Ls) (c_hi P s Ls) Mr.
Proof.
  intros HP Hs; unfold corrected_interval, in_bounds, c_lo, c_hi; split.
  - intros (HT1 & HT2 & HC); split.
    + intros l Hl; apply qmax_opt_some in Hl as [Hin _].
      unfold T_below in Hin; apply in_map_iff in Hin as (u & <- & Hu).
      apply filter_In in Hu as [Hu Hlt]; apply Nat.ltb_lt in Hlt.
      rewrite T_Q_R by lia; apply HT1; [apply goal_paths_spec; auto|].
      unfold S_of; apply lt_INR; auto.
    + intros h Hh; destruct (omin_cases _ _ _ Hh) as [E|E].
      * apply qmin_opt_some in E as [Hin _].
        unfold T_above in Hin; apply in_map_iff in Hin as (u & <- & Hu).
        apply filter_In in Hu as [Hu Hlt]; apply Nat.ltb_lt in Hlt.
        rewrite T_Q_R by lia; apply HT2; [apply goal_paths_spec; auto|].
        unfold S_of; apply lt_INR; auto.
      * destruct (Lav P) as [lv|] eqn:El; inversion E; subst h; clear E.
        apply qmin_opt_some in El as [Hin _].
        unfold cycle_means in Hin; apply in_map_iff in Hin as ([x c] & <- & Hxc).
        apply avoid_cycles_spec in Hxc; auto; simpl fst; simpl snd.
        rewrite Q2R_minus, Q2R_mult, Q2R_qnat, mean_R by (destruct Hxc; auto).
        apply HC; auto.
  - intros [Hlo Hhi]; split; [|split].
    + intros u Hu Hlt; unfold S_of in Hlt; apply INR_lt in Hlt.
      assert (Hin : In (T_Q s Ls (wcost P 0 u) (S (length u))) (T_below P s Ls)).
      { apply (in_map (fun u => T_Q s Ls (wcost P 0 u) (S (length u)))), filter_In.
        split; [apply goal_paths_spec; auto|apply Nat.ltb_lt; auto]. }
      destruct (qmax_opt_in _ _ Hin) as (m & Em & Hle).
      rewrite <- T_Q_R by lia; apply Qle_Rle in Hle; specialize (Hlo m Em); lra.
    + intros u Hu Hlt; unfold S_of in Hlt; apply INR_lt in Hlt.
      assert (Hin : In (T_Q s Ls (wcost P 0 u) (S (length u))) (T_above P s Ls)).
      { apply (in_map (fun u => T_Q s Ls (wcost P 0 u) (S (length u)))), filter_In.
        split; [apply goal_paths_spec; auto|apply Nat.ltb_lt; auto]. }
      destruct (qmin_opt_in _ _ Hin) as (m & Em & Hle).
      destruct (omin_le_l _ (option_map (fun l => qnat s * l - Ls)%Q (Lav P)) m Em)
        as (h & Eh & Hh).
      rewrite <- T_Q_R by lia; apply Qle_Rle in Hle, Hh; specialize (Hhi h Eh); lra.
    + intros x c Hc.
      assert (Hin : In (wcost P x c / qnat (length c))%Q (cycle_means P)).
      { apply (in_map (fun xc => wcost P (fst xc) (snd xc) / qnat (length (snd xc)))%Q
                      _ (x, c)), avoid_cycles_spec; auto. }
      destruct (qmin_opt_in _ _ Hin) as (lv & El & Hle); unfold Lav.
      destruct (omin_le_r (qmin_opt (T_above P s Ls))
                  (option_map (fun l => qnat s * l - Ls)%Q (qmin_opt (cycle_means P)))
                  (qnat s * lv - Ls)%Q) as (h & Eh & Hh); [rewrite El; reflexivity|].
      specialize (Hhi h Eh); apply Qle_Rle in Hle, Hh.
      rewrite Q2R_minus, Q2R_mult, Q2R_qnat in Hh; rewrite <- mean_R by (destruct Hc; auto).
      pose proof (pos_INR s); nra.
Qed.

(** C4-corrected ([C4.c4_corrected]) with the computed ends: for every finite problem, every
    optimal simple goal path [u*] from [x1] ([S* = |u*| + 1] states, cost [L* = G*(x1)]) and
    every rational bonus [M], [pi*] is average-cost optimal iff [c_lo <= M <= c_hi]. *)
Corollary c4_corrected_computed P ustar Lstar M :
  wf P -> Gstar P 0 = Some Lstar -> simple_goal_path P ustar -> (wcost P 0 ustar == Lstar)%Q ->
  average_optimal P (Q2R M) (cyc_x P M 0 (ustar ++ [0%nat])) (cyc_c P M 0 (ustar ++ [0%nat])) <->
  in_bounds (c_lo P (S (length ustar)) Lstar) (c_hi P (S (length ustar)) Lstar) (Q2R M).
Proof.
  intros HP HG Hu HL; rewrite (c4_corrected P ustar Lstar M HP HG Hu HL).
  apply (corrected_interval_bounds P (S (length ustar)) Lstar (Q2R M) HP ltac:(lia)).
Qed.

(** The values of [S*] are those of the optimal simple goal paths. *)
Theorem sstars_spec P Lstar s :
  wf P -> Gstar P 0 = Some Lstar ->
  In s (sstars P) <->
  exists ustar, simple_goal_path P ustar /\ (wcost P 0 ustar == Lstar)%Q /\ S (length ustar) = s.
Proof.
  intros HP HG; unfold sstars, sstars_of; rewrite HG, filter_In, existsb_exists, in_seq; split.
  - intros (_ & u & Hu & E); apply andb_true_iff in E as [E1 E2].
    apply Nat.eqb_eq in E1; apply Qeq_bool_iff in E2.
    exists u; repeat split; auto; apply goal_paths_spec; auto.
  - intros (u & Hu & Hc & Es).
    assert (Hl := nodup_length P HP 0 u (n_pos P HP) (proj1 (proj1 Hu)) (proj2 Hu)).
    split; [lia|]; exists u; split; [apply goal_paths_spec; auto|].
    apply andb_true_iff; split; [apply Nat.eqb_eq; auto|apply Qeq_bool_iff; auto].
Qed.

Lemma qltb_true a b : Qlt_bool a b = true <-> (a < b)%Q.
Proof.
  unfold Qlt_bool; rewrite negb_true_iff; split; intros H.
  - apply Qnot_le_lt; intros H'; apply Qle_bool_iff in H'; congruence.
  - destruct (Qle_bool b a) eqn:E; auto; apply Qle_bool_iff in E.
    exfalso; apply (Qlt_not_le _ _ H E).
Qed.

Lemma qltb_false a b : Qlt_bool a b = false <-> (b <= a)%Q.
Proof. unfold Qlt_bool; rewrite negb_false_iff; apply Qle_bool_iff. Qed.

Lemma qleb_false a b : Qle_bool a b = false <-> (b < a)%Q.
Proof.
  split; intros H.
  - apply Qnot_le_lt; intros H'; apply Qle_bool_iff in H'; congruence.
  - destruct (Qle_bool a b) eqn:E; auto; apply Qle_bool_iff in E.
    exfalso; apply (Qlt_not_le _ _ H E).
Qed.

Lemma neg_interval_Q lo hi m :
  iv_contains (neg_interval lo hi) m = true <->
  (m < 0 /\ (forall l, lo = Some l -> l <= m) /\ (forall h, hi = Some h -> m <= h))%Q.
Proof.
  destruct lo as [a|], hi as [b|];
    [destruct (Qlt_bool b 0) eqn:Eb | | destruct (Qlt_bool b 0) eqn:Eb | ];
    unfold neg_interval, iv_contains; rewrite ?Eb; cbv beta iota zeta;
    rewrite ?andb_true_iff, ?negb_true_iff, ?qltb_true, ?qltb_false, ?qleb_false,
      ?Qle_bool_iff in *;
    split; intros H;
    repeat match goal with
      | H : _ /\ _ |- _ => destruct H
      | H : forall l, Some ?a = Some l -> _ |- _ => specialize (H a eq_refl)
      | H : forall l, None = Some l -> _ |- _ => clear H
      | |- _ /\ _ => split
      | |- forall l, Some _ = Some l -> _ => let q := fresh in let E := fresh in
                                             intros q E; inversion E; subst q; clear E
      | |- forall l, None = Some l -> _ => let q := fresh in let E := fresh in
                                          intros q E; discriminate E
      | |- true = true => reflexivity
      end;
    try Lqa.lra.
Qed.

(** The kernel's form of the interval is the corrected interval intersected with [M < 0]:
    for every rational [m], [iv_contains (neg_interval lo hi) m] iff [m < 0] and
    [lo <= m <= hi]. *)
Theorem neg_interval_spec lo hi m :
  iv_contains (neg_interval lo hi) m = true <-> Q2R m < 0 /\ in_bounds lo hi (Q2R m).
Proof.
  rewrite neg_interval_Q; unfold in_bounds.
  assert (R0 : (m < 0)%Q <-> Q2R m < 0).
  { split; intros H; [apply Qlt_Rlt in H|apply Rlt_Qlt]; rewrite Q2R_0 in *; auto. }
  rewrite R0; split; intros (H1 & H2 & H3); (split; [exact H1|split]);
    intros q E; [apply Qle_Rle, H2 | apply Qle_Rle, H3 | apply Rle_Qle, H2 | apply Rle_Qle, H3];
    exact E.
Qed.

(** ** The checker *)

Open Scope Q_scope.

(** What the kernel computed for one problem. *)
Record expected := {
  e_Lstar : option Q;
  e_paths : list (Q * nat)%type;
  e_Lav : option Q;
  e_sets : list (Q * nat * option Q * (iend * iend * bool))%type;
  e_core : list bool;
  e_certs : list (Q * option (list (list Q)))%type   (** [alpha0] and the certificate's costs *)
}.

Definition end_eqb (a b : iend) : bool :=
  match a, b with
  | Unb, Unb => true
  | Cl u, Cl v | Op u, Op v => Qeq_bool u v
  | _, _ => false
  end.

Definition iv_eqb (a b : (iend * iend * bool)%type) : bool :=
  let '(l, h, e) := a in let '(l', h', e') := b in end_eqb l l' && end_eqb h h' && Bool.eqb e e'.

Definition path_eqb (a b : (Q * nat)%type) : bool := Qeq_bool (fst a) (fst b) && Nat.eqb (snd a) (snd b).

Definition set_eqb (a b : (Q * nat * option Q * (iend * iend * bool))%type) : bool :=
  let '(l, s, lv, iv) := a in let '(l', s', lv', iv') := b in
  Qeq_bool l l' && Nat.eqb s s' && oq_eqb lv lv' && iv_eqb iv iv'.

Definition cert_eqb (a b : option (list (list Q))) : bool :=
  match a, b with
  | Some u, Some v => list_eqb (list_eqb Qeq_bool) u v
  | None, None => true
  | _, _ => false
  end.

(** Mismatches of problem number [i], and the number of values compared. *)
Definition check_problem (i : nat) (P : problem) (e : expected) : list mismatch * nat :=
  let v := shared_values P (map fst (e_certs e)) in
  ((tag i "Lstar"%string (positions_differ oq_eqb O [v_Lstar v] [e_Lstar e])
    ++ tag i "paths"%string (positions_differ path_eqb O (v_paths v) (e_paths e))
    ++ tag i "Lav"%string (positions_differ oq_eqb O [v_Lav v] [e_Lav e])
    ++ tag i "sets"%string (positions_differ set_eqb O (v_sets v) (e_sets e))
    ++ tag i "core"%string (positions_differ Bool.eqb O (v_core v) (e_core e))
    ++ tag i "cert"%string (positions_differ cert_eqb O (v_certs v) (map snd (e_certs e))))%list,
   (2 + List.length (e_paths e) + List.length (e_sets e) + List.length (e_core e)
    + List.length (e_certs e))%nat).

Definition check_all (ps : list (problem * expected)) : nat * nat * list mismatch :=
  check_from check_problem 0 ps.

(** When [check_problem] reports no mismatch, C3.v's and C4.v's values (through this file's
    exact enumerations) are the kernel's: [G*(x1)], [Lav(C^)] and every simple goal path's
    [(L(u), S(u))] equal as rationals (paths in the kernel's order); for every [S*], [L*],
    [S*], [Lav(C^)] and the corrected interval with [M < 0] (ends, open or closed, and
    emptiness) equal; the goal-avoiding core equal state by state; for every [alpha0], the
    engine certificate's costs equal move by move, or neither side builds one. *)
Theorem check_problem_sound :
  forall i P e, fst (check_problem i P e) = [] ->
  let v := model_values P (map fst (e_certs e)) in
  (oq_eqb (v_Lstar v) (e_Lstar e) = true /\
   Forall2 (fun a b => path_eqb a b = true) (v_paths v) (e_paths e) /\
   oq_eqb (v_Lav v) (e_Lav e) = true /\
   Forall2 (fun a b => set_eqb a b = true) (v_sets v) (e_sets e) /\
   v_core v = e_core e /\
   Forall2 (fun a b => cert_eqb a b = true) (v_certs v) (map snd (e_certs e)))%type.
Proof.
  intros i P e H v; unfold check_problem in H; rewrite shared_values_eq in H; fold v in H.
  cbn [fst] in H.
  apply app_eq_nil in H as [H1 H]; apply app_eq_nil in H as [H2 H].
  apply app_eq_nil in H as [H3 H]; apply app_eq_nil in H as [H4 H].
  apply app_eq_nil in H as [H5 H6].
  unfold tag in H1, H2, H3, H4, H5, H6; apply map_eq_nil in H1, H2, H3, H4, H5, H6.
  apply positions_differ_nil in H1, H2, H3, H4, H5, H6.
  inversion H1; inversion H3; subst.
  repeat split; auto; apply bool_list_eq; auto.
Qed.

(** [cert_costs] lists the move costs of C3.v's engine certificate: the costs [c3_engine]
    speaks of. *)
Lemma cert_costs_spec P alpha0 x i :
  (x < nstates P)%nat -> (i < length (moves P x))%nat ->
  nth i (nth x (cert_costs P alpha0) []) 0 =
  cost (engine_certificate P (lasso_marks P (core_pi P)) alpha0 (nstates P)) x (Move i).
Proof.
  intros Hx Hi; unfold cert_costs, states; rewrite nth_map_seq by auto.
  unfold cost; rewrite (nth_indep _ 0 (snd (x, 0))).
  - apply map_nth.
  - rewrite map_length; simpl; rewrite recost_length; auto.
Qed.
