(** * What the bridges share: problems and value vectors from the test's data, the comparison
    of two lists, and the loop over the problems

    A bridge file ([Bridge.v], [BridgeRun.v], [BridgeC34.v]) defines what the kernel computed
    for one problem ([expected]) and how one problem is checked ([check_problem]: the
    mismatches and the number of values compared); [check_from] runs it over every problem
    and prints [(problems checked, values compared, mismatches)], which the kernel's bridge
    tests read. A mismatch is [(problem, field, position)]. *)

From Coq Require Import QArith List String.
From Truecost Require Import Model.
Import ListNotations.

Open Scope Q_scope.

(** ** Problems and value vectors *)

(** The problem with states [0 .. n-1], goal [n - 1], [x1 = 0] and the move lists [ms]
    (state by state): the kernel's [Tiny]. *)
Definition mk (n : nat) (ms : list (list (nat * Q))) : problem :=
  {| nstates := n; goal := Nat.pred n; moves := fun x => nth x ms [] |}.

Fixpoint index_of (p : nat * action) (ps : list (nat * action)) : nat :=
  match ps with
  | [] => O
  | q :: ps' => if Nat.eqb (fst p) (fst q) && action_eqb (snd p) (snd q) then O
                else S (index_of p ps')
  end.

(** The value vector giving the [k]-th pair of [pairs P] the [k]-th entry of [l]. *)
Definition qvec_of (P : problem) (l : list Q) : qvec :=
  fun x a => nth (index_of (x, a) (pairs P)) l 0.

(** ** Comparisons *)

Definition mismatch := (nat * string * nat)%type.

Definition oq_eqb (a b : option Q) : bool :=
  match a, b with Some u, Some v => Qeq_bool u v | None, None => true | _, _ => false end.

Definition on_eqb (a b : option nat) : bool :=
  match a, b with Some u, Some v => Nat.eqb u v | None, None => true | _, _ => false end.

Fixpoint list_eqb {A} (eqb : A -> A -> bool) (l r : list A) : bool :=
  match l, r with
  | [], [] => true
  | a :: l', b :: r' => eqb a b && list_eqb eqb l' r'
  | _, _ => false
  end.

(** The positions where two lists differ (and the position where the shorter one ends). *)
Fixpoint positions_differ {A} (eqb : A -> A -> bool) (k : nat) (l r : list A) : list nat :=
  match l, r with
  | [], [] => []
  | a :: l', b :: r' =>
      let rest := positions_differ eqb (S k) l' r' in if eqb a b then rest else k :: rest
  | _, _ => [k]
  end.

Definition tag (i : nat) (what : string) (ks : list nat) : list mismatch :=
  map (fun k => (i, what, k)) ks.

(** ** The loop over the problems *)

(** Every problem of the list, numbered from [i], checked by [check] (its mismatches and the
    number of values compared): (problems checked, values compared, mismatches). *)
Fixpoint check_from {E} (check : nat -> problem -> E -> list mismatch * nat) (i : nat)
    (ps : list (problem * E)) : nat * nat * list mismatch :=
  match ps with
  | [] => (O, O, [])
  | (P, e) :: ps' =>
      let '(m, c) := check i P e in
      let '(n', c', ms) := check_from check (S i) ps' in
      (S n', (c + c')%nat, m ++ ms)
  end.

(** ** What no mismatch means *)

(** No reported position means equal lists, element by element. *)
Lemma positions_differ_nil :
  forall A (eqb : A -> A -> bool) k l r,
  positions_differ eqb k l r = [] -> Forall2 (fun a b => eqb a b = true) l r.
Proof.
  intros A eqb k l; revert k; induction l as [|a l IH]; intros k [|b r] H; simpl in H;
    try discriminate; [constructor|].
  destruct (eqb a b) eqn:E; [|discriminate]; constructor; [exact E|exact (IH _ _ H)].
Qed.

Lemma oq_eqb_eq : forall a b, oq_eqb a b = true ->
  match a, b with Some u, Some v => u == v | None, None => True | _, _ => False end.
Proof. intros [u|] [v|]; simpl; try discriminate; auto; apply Qeq_bool_iff. Qed.

Lemma on_eqb_eq : forall a b, on_eqb a b = true -> a = b.
Proof.
  intros [u|] [v|]; simpl; try discriminate; auto.
  intro H; apply Nat.eqb_eq in H; subst; reflexivity.
Qed.

Lemma on_eqb_list_eq :
  forall l r, Forall2 (fun a b => on_eqb a b = true) l r -> l = r.
Proof. intros l r H; induction H; [reflexivity|f_equal; [apply on_eqb_eq|]; assumption]. Qed.

Lemma bool_list_eq l r : Forall2 (fun a b => Bool.eqb a b = true) l r -> l = r.
Proof.
  intros H; induction H; [reflexivity|f_equal; [apply Bool.eqb_prop|]; assumption].
Qed.

(** [list_eqb] is elementwise: equal lengths, [eqb] true at every position. *)
Lemma list_eqb_Forall2 {A} (eqb : A -> A -> bool) l r :
  list_eqb eqb l r = true -> Forall2 (fun a b => eqb a b = true) l r.
Proof.
  revert r; induction l as [|a l IH]; intros [|b r] H; simpl in H; try discriminate;
    [constructor|].
  apply andb_true_iff in H as [H1 H2]; constructor; auto.
Qed.
