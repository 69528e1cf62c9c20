(** * The bridge for the Q-learning simulator: Model.v's [run] against the kernel's updates

    C1's theorems are about Model.v's [update] (the termination pair held, (H0)) and
    [update_printed] (every pair by the printed rule), run through a list of pairs ([run],
    [run_printed]). The kernel simulates the same updates ([QProblem::update] with
    [Terminal::HeldAtZero] or [Terminal::Updated]; [QProblem::run] runs rounds of them and
    decides [Q = Q*] after each round). The kernel's test [kernel/tests/coq_bridge_run.rs]
    writes problems together with runs of the kernel's simulator (initial values, the
    rounds as lists of pair indices, and after every round the kernel's values and whether
    they equal [Q*]) and evaluates [check_all] below on them: zero mismatches means Model.v's
    [run] produces the kernel's values, round after round, and [exactb] (which is C1.v's
    [exact], [exactb_exact]) agrees with the kernel's verdict. *)

From Coq Require Import QArith List String.
From Truecost Require Import Model C1.
From Truecost Require Bridge.
From Truecost Require Export BridgeCommon.
Import ListNotations.

Open Scope Q_scope.

(** ** Runs, round by round *)

(** The [i]-th pair of [pairs P]. *)
Definition pair_at (P : problem) (i : nat) : nat * action := nth i (pairs P) (O, Term).

(** One round: the pairs with the indices [r], in order, by [update] ([held]) or
    [update_printed]. *)
Definition round (P : problem) (held : bool) (q : qvec) (r : list nat) : qvec :=
  let ps := map (pair_at P) r in if held then run P q ps else run_printed P q ps.

(** The values after each round of [rs], starting from [q] (itself first). *)
Fixpoint trajectory (P : problem) (held : bool) (q : qvec) (rs : list (list nat)) : list qvec :=
  match rs with
  | [] => [q]
  | r :: rs' => q :: trajectory P held (round P held q r) rs'
  end.

(** The values of every pair, in [pairs] order. *)
Definition values_of (P : problem) (q : qvec) : list Q :=
  map (fun p => q (fst p) (snd p)) (pairs P).

(** [Q = Q*] on every pair, decided. *)
Definition exactb (P : problem) (q : qvec) : bool :=
  forallb (fun p => match Qstar P (fst p) (snd p) with
                    | Some v => Qeq_bool (q (fst p) (snd p)) v
                    | None => false
                    end) (pairs P).

Lemma exactb_exact P q : exactb P q = true <-> exact P q.
Proof.
  unfold exactb, exact; rewrite forallb_forall; split.
  - intros H x a Hp; specialize (H (x, a) Hp); cbn [fst snd] in H; revert H.
    destruct (Qstar P x a) as [v|]; intros H; [|discriminate].
    exists v; split; [reflexivity | apply Qeq_bool_iff; exact H].
  - intros H [x a] Hp; cbn [fst snd]; destruct (H x a Hp) as (v & -> & Hv).
    apply Qeq_bool_iff; exact Hv.
Qed.

(** [exactb] reading [G*] from [g] (which is [bfl P (nstates P)], computed once). *)
Definition exactb_in (g : list (option Q)) (P : problem) (q : qvec) : bool :=
  forallb (fun p => match Bridge.Qstar_in g P (fst p) (snd p) with
                    | Some v => Qeq_bool (q (fst p) (snd p)) v
                    | None => false
                    end) (pairs P).

Lemma exactb_in_eq P q : exactb_in (Bridge.bfl_shared P (nstates P)) P q = exactb P q.
Proof. rewrite Bridge.bfl_shared_eq; reflexivity. Qed.

(** ** The checker *)

(** One run of the kernel's simulator: the initial values (in [pairs] order), whether the
    termination pair is held, the rounds (pair indices), and after round [0, 1, ...] the
    kernel's values and its verdict [Q = Q*]. *)
Record run_case := {
  r_q0 : list Q;
  r_held : bool;
  r_rounds : list (list nat);
  r_after : list (list Q * bool)
}.

(** What the kernel computed for one problem: its runs. *)
Definition expected := list run_case.

(** The values and verdicts of Model.v's [run] (or [run_printed]) on one case, [exactb]
    evaluated with [G*] computed once ([exactb_in_eq]). *)
Definition model_after (P : problem) (c : run_case) : list (list Q * bool) :=
  let g := Bridge.bfl_shared P (nstates P) in
  map (fun q => (values_of P q, exactb_in g P q))
      (trajectory P (r_held c) (qvec_of P (r_q0 c)) (r_rounds c)).

Definition after_eqb (a b : list Q * bool) : bool :=
  list_eqb Qeq_bool (fst a) (fst b) && Bool.eqb (snd a) (snd b).

(** The mismatches of one case, number [k] of the problem: position [100 k + r] for a
    difference after round [r]. *)
Definition check_case (i k : nat) (P : problem) (c : run_case) : list mismatch :=
  tag i "run"%string (map (fun r => (100 * k + r)%nat)
                          (positions_differ after_eqb O (model_after P c) (r_after c))).

Fixpoint check_cases (i k : nat) (P : problem) (cs : list run_case) : list mismatch :=
  match cs with
  | [] => []
  | c :: cs' => check_case i k P c ++ check_cases i (S k) P cs'
  end.

Definition values_count (cs : list run_case) : nat :=
  fold_right (fun c acc => fold_right (fun a n => S (List.length (fst a)) + n) acc (r_after c))%nat
             O cs.

(** Mismatches of problem number [i], and the number of values compared. *)
Definition check_problem (i : nat) (P : problem) (e : expected) : list mismatch * nat :=
  (check_cases i 0 P e, values_count e).

Definition check_all (ps : list (problem * expected)) : nat * nat * list mismatch :=
  check_from check_problem 0 ps.

(** When a case reports no mismatch, Model.v's [run] (held) or [run_printed] gives the
    kernel's values after every round, and C1.v's [exact] holds after a round iff the
    kernel says [Q = Q*]. *)
Theorem check_case_sound i k P c :
  check_case i k P c = [] ->
  Forall2 (fun q a => Forall2 (fun u v => Qeq_bool u v = true) (values_of P q) (fst a) /\
                      (exact P q <-> snd a = true))
          (trajectory P (r_held c) (qvec_of P (r_q0 c)) (r_rounds c)) (r_after c).
Proof.
  unfold check_case, tag; intros H; apply map_eq_nil in H; apply map_eq_nil in H.
  apply positions_differ_nil in H; unfold model_after in H.
  revert H; generalize (r_after c);
    generalize (trajectory P (r_held c) (qvec_of P (r_q0 c)) (r_rounds c)).
  intros l; induction l as [|q l IH]; intros r H; inversion H as [|x y l' r' Hxy Hrest]; subst;
    constructor; auto.
  unfold after_eqb in Hxy; apply andb_true_iff in Hxy as [H1 H2]; cbn [fst snd] in *.
  split; [apply list_eqb_Forall2; exact H1|].
  apply Bool.eqb_prop in H2; rewrite <- H2, exactb_in_eq, exactb_exact; tauto.
Qed.
