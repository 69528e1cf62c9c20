(** * The bridge: Model.v's definitions evaluated against the kernel's oracles

    The theorems of this development are about the definitions of [Model.v] ([Gstar], [Qstar],
    [hstar], [R1], [round_bound]). The kernel crate computes the same quantities with its own
    oracles ([claims::oracle::optimal_cost_to_go], [QProblem::optimum],
    [QProblem::optimal_steps], [QProblem::round_bound]); its test [kernel/tests/coq_bridge.rs]
    writes problems of [claims::tiny]'s enumeration together with the kernel's values as Coq
    terms, and evaluates [check_all] below on them. Zero mismatches means the definitions the
    proofs are about are the ones the kernel computes, on every problem checked.

    [model_values] is made of Model.v's definitions only. Evaluating it directly repeats work
    (in [bfl] and [hbl] each step re-evaluates the previous list once per state, and every
    [Gstar]/[hstar] call starts over), which is exponential in the number of states; so the
    checker evaluates [shared_values], the same definitions with each intermediate list computed
    once, and [shared_values_eq] proves the two equal for every problem and every [q0]: what
    [check_all] compares is [model_values]. *)

From Coq Require Import QArith List String.
From Truecost Require Import Model.
From Truecost Require Export BridgeCommon.
Import ListNotations.

Open Scope Q_scope.

(** ** The values, from Model.v's definitions *)

Record values := {
  v_Gstar : list (option Q);          (** [G*] of every state *)
  v_Qstar : list (option Q);          (** [Q*] of every pair, in [pairs] order *)
  v_h : list (option nat);            (** [h] of every state *)
  v_R1 : option nat;                  (** [R1] *)
  v_rounds : list (option nat)        (** [round_bound] of each given [q0] *)
}.

Definition states (P : problem) : list nat := seq 0 (nstates P).

Definition model_values (P : problem) (q0s : list qvec) : values := {|
  v_Gstar := map (Gstar P) (states P);
  v_Qstar := map (fun p => Qstar P (fst p) (snd p)) (pairs P);
  v_h := map (hstar P) (states P);
  v_R1 := R1 P;
  v_rounds := map (round_bound P) q0s
|}.

(** ** The same values, each intermediate list computed once *)

(** [bfl] with the previous list let-bound. *)
Fixpoint bfl_shared (P : problem) (k : nat) : list (option Q) :=
  match k with
  | O => map (bf_start P) (seq 0 (nstates P))
  | S k' => let prev := bfl_shared P k' in
            map (bf_step P (fun y => nth y prev None)) (seq 0 (nstates P))
  end.

Lemma bfl_shared_eq : forall P k, bfl_shared P k = bfl P k.
Proof. intros P k; induction k as [|k IH]; simpl; [reflexivity|rewrite IH; reflexivity]. Qed.

(** [tight], [hb_step], [hbl] reading [G*] from the list [g] (which is [bfl P (nstates P)]). *)
Definition tight_in (g : list (option Q)) (x : nat) (yl : nat * Q) : bool :=
  match nth x g None, nth (fst yl) g None with
  | Some gx, Some gy => Qeq_bool (snd yl + gy) gx
  | _, _ => false
  end.

Definition hb_step_in (g : list (option Q)) (P : problem) (h : nat -> option nat) (x : nat)
  : option nat :=
  if Nat.eqb x (goal P) then Some 0%nat
  else nmin (h x)
         (nminl (map (fun yl => if tight_in g x yl then option_map S (h (fst yl)) else None)
                     (moves P x))).

Fixpoint hbl_in (g : list (option Q)) (P : problem) (k : nat) : list (option nat) :=
  match k with
  | O => map (fun x => if Nat.eqb x (goal P) then Some 0%nat else None) (seq 0 (nstates P))
  | S k' => let prev := hbl_in g P k' in
            map (hb_step_in g P (fun y => nth y prev None)) (seq 0 (nstates P))
  end.

Lemma hbl_in_eq : forall P k, hbl_in (bfl P (nstates P)) P k = hbl P k.
Proof. intros P k; induction k as [|k IH]; simpl; [reflexivity|rewrite IH; reflexivity]. Qed.

(** [Qstar], [R1], [above], [qmax_star], [round_bound] reading [G*] from [g] and [h] from
    [hs] (which is [hbl P (nstates P)]). *)
Definition Qstar_in (g : list (option Q)) (P : problem) (x : nat) (a : action) : option Q :=
  match a with
  | Term => Some 0
  | Move _ => option_map (Qplus (cost P x a)) (nth (target P x a) g None)
  end.

Definition R1_in (hs : list (option nat)) (P : problem) : option nat :=
  fold_right
    (fun p acc =>
       match acc, nth (target P (fst p) (snd p)) hs None with
       | Some r, Some k => Some (Nat.max r (S k))
       | _, _ => None
       end)
    (Some 0%nat) (move_pairs P).

Definition above_in (g : list (option Q)) (P : problem) (q0 : qvec) : bool :=
  forallb (fun p => match Qstar_in g P (fst p) (snd p) with
                    | Some v => Qle_bool v (q0 (fst p) (snd p))
                    | None => false
                    end) (move_pairs P).

Definition qmax_star_in (g : list (option Q)) (P : problem) : option Q :=
  fold_right
    (fun p acc =>
       match acc, Qstar_in g P (fst p) (snd p) with
       | Some a, Some v => Some (Qmax2 a v)
       | _, _ => None
       end)
    (Some 0) (move_pairs P).

Definition round_bound_in (g : list (option Q)) (hs : list (option nat)) (P : problem)
  (q0 : qvec) : option nat :=
  match R1_in hs P with
  | None => None
  | Some r1 =>
      if above_in g P q0 then Some r1
      else match min_cost P with
           | None => None
           | Some c =>
               if Qle_bool c 0 then None
               else match qmax_star_in g P with
                    | None => None
                    | Some qm => Some (Nat.max r1 (ceil_rounds (qm - m0 P q0) c))
                    end
           end
  end.

Definition shared_values (P : problem) (q0s : list qvec) : values :=
  let g := bfl_shared P (nstates P) in
  let hs := hbl_in g P (nstates P) in {|
  v_Gstar := map (fun x => nth x g None) (states P);
  v_Qstar := map (fun p => Qstar_in g P (fst p) (snd p)) (pairs P);
  v_h := map (fun x => nth x hs None) (states P);
  v_R1 := R1_in hs P;
  v_rounds := map (round_bound_in g hs P) q0s
|}.

(** What the checker evaluates is Model.v's values. *)
Theorem shared_values_eq : forall P q0s, shared_values P q0s = model_values P q0s.
Proof.
  intros P q0s; unfold shared_values.
  rewrite bfl_shared_eq, hbl_in_eq; reflexivity.
Qed.

(** ** The checker *)

(** What the kernel computed for one problem. *)
Record expected := {
  e_Gstar : list (option Q);
  e_Qstar : list (option Q);
  e_h : list (option nat);
  e_R1 : option nat;
  e_rounds : list (list Q * option nat)   (** [q0] in [pairs] order, and its round bound *)
}.

(** Mismatches of problem number [i], and the number of values compared. *)
Definition check_problem (i : nat) (P : problem) (e : expected) : list mismatch * nat :=
  let v := shared_values P (map (fun r => qvec_of P (fst r)) (e_rounds e)) in
  ((tag i "Gstar"%string (positions_differ oq_eqb O (v_Gstar v) (e_Gstar e))
    ++ tag i "Qstar"%string (positions_differ oq_eqb O (v_Qstar v) (e_Qstar e))
    ++ tag i "h"%string (positions_differ on_eqb O (v_h v) (e_h e))
    ++ tag i "R1"%string (positions_differ on_eqb O [v_R1 v] [e_R1 e])
    ++ tag i "round_bound"%string (positions_differ on_eqb O (v_rounds v) (map snd (e_rounds e))))%list,
   (List.length (e_Gstar e) + List.length (e_Qstar e) + List.length (e_h e) + 1
    + List.length (e_rounds e))%nat).

Definition check_all (ps : list (problem * expected)) : nat * nat * list mismatch :=
  check_from check_problem 0 ps.

(** When [check_problem] reports no mismatch, Model.v's values are the expected ones: [G*] and
    [Q*] equal as rationals (state by state, pair by pair), [h], [R1] and every round bound
    equal. *)
Theorem check_problem_sound :
  forall i P e, fst (check_problem i P e) = [] ->
  let v := model_values P (map (fun r => qvec_of P (fst r)) (e_rounds e)) in
  (Forall2 (fun a b => oq_eqb a b = true) (v_Gstar v) (e_Gstar e) /\
   Forall2 (fun a b => oq_eqb a b = true) (v_Qstar v) (e_Qstar e) /\
   v_h v = e_h e /\ v_R1 v = e_R1 e /\ v_rounds v = map snd (e_rounds e))%type.
Proof.
  intros i P e H v; unfold check_problem in H; subst v; rewrite <- shared_values_eq.
  simpl in H.
  destruct (positions_differ oq_eqb O _ (e_Gstar e)) eqn:G; [|discriminate].
  destruct (positions_differ oq_eqb O _ (e_Qstar e)) eqn:Q; [|discriminate].
  destruct (positions_differ on_eqb O _ (e_h e)) eqn:Hh; [|discriminate].
  destruct (on_eqb _ (e_R1 e)) eqn:E; [|discriminate].
  destruct (positions_differ on_eqb O _ (map snd (e_rounds e))) eqn:Rb; [|discriminate].
  apply positions_differ_nil in G, Q, Hh, Rb.
  repeat split; [exact G|exact Q| | |].
  - apply on_eqb_list_eq, Hh.
  - apply on_eqb_eq, E.
  - apply on_eqb_list_eq, Rb.
Qed.
