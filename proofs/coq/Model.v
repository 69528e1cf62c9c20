(** * The model: finite deterministic planning problems and derandomized Q-learning

    A finite deterministic planning problem of docs/spec.md §1, its optimal cost-to-go [Gstar]
    (G-star of docs/spec.md §1), the optimal state-action values [Qstar] (Q-star), the
    fewest moves on an optimal path [hstar] (h), the [rho = 1] update of derandomized
    Q-learning (docs/spec.md §2, the update of the paper's Proposition 1) and the round bound of
    C1-corrected ([round_bound], the kernel's [QProblem::round_bound]).

    Everything is over the rationals [Q] and computable, so that the bridge test can evaluate
    these very definitions on concrete problems and compare them with the kernel's oracles. *)

From Coq Require Import QArith Qround List Lia Lqa.
Import ListNotations.

Open Scope Q_scope.

(** ** Problems (docs/spec.md §1) *)

(** States are [0 .. nstates - 1], the initial state is [x1 = 0], [goal] is the goal state.
    [moves x] is the action list [U(x)], each action given by its successor and stage cost
    [(f(x,u), l(x,u))], in order. The goal has, in addition, the termination action [uT]
    with [f(xg, uT) = xg] and [l(xg, uT) = 0] (docs/spec.md §1). *)
Record problem := {
  nstates : nat;
  goal : nat;
  moves : nat -> list (nat * Q)
}.

(** Well-formedness: successors are states, stage costs are [>= 0], the goal is a state.
    A non-goal state may have no move (a dead end: [G* = +oo] there). *)
Definition wf (P : problem) : Prop :=
  (goal P < nstates P)%nat /\
  forall x, (x < nstates P)%nat ->
    forall y l, In (y, l) (moves P x) -> (y < nstates P)%nat /\ 0 <= l.

(** An action of a state: the termination action [uT] (only at the goal) or the [i]-th move. *)
Inductive action := Term | Move (i : nat).

Definition action_eqb (a b : action) : bool :=
  match a, b with
  | Term, Term => true
  | Move i, Move j => Nat.eqb i j
  | _, _ => false
  end.

(** The actions of [x] in the kernel's order: [uT] first at the goal, then the moves. *)
Definition actions (P : problem) (x : nat) : list action :=
  (if Nat.eqb x (goal P) then [Term] else []) ++ map Move (seq 0 (length (moves P x))).

(** All state-action pairs, state by state (the kernel's [QProblem::pairs] order). *)
Definition pairs (P : problem) : list (nat * action) :=
  flat_map (fun x => map (fun a => (x, a)) (actions P x)) (seq 0 (nstates P)).

Definition is_move (p : nat * action) : bool :=
  match snd p with Term => false | Move _ => true end.

(** The move pairs (every pair but the goal's termination pair). *)
Definition move_pairs (P : problem) : list (nat * action) := filter is_move (pairs P).

(** [f(x,u)] and [l(x,u)] (docs/spec.md §1); [uT] is a zero-cost self-loop. An out-of-range move
    index (never a pair) reads as a zero-cost self-loop too. *)
Definition target (P : problem) (x : nat) (a : action) : nat :=
  match a with Term => x | Move i => fst (nth i (moves P x) (x, 0)) end.

Definition cost (P : problem) (x : nat) (a : action) : Q :=
  match a with Term => 0 | Move i => snd (nth i (moves P x) (x, 0)) end.

(** ** Minima over lists *)

(** [Qmin2 a b] is the smaller of [a] and [b] (syntactically one of them). *)
Definition Qmin2 (a b : Q) : Q := if Qle_bool a b then a else b.
Definition Qmax2 (a b : Q) : Q := if Qle_bool a b then b else a.

(** The least element of a list; [0] for the empty list (the [V] of a dead-end state, which
    the theorems exclude by (H1): there every state has a pair). *)
Definition qminl (l : list Q) : Q :=
  match l with [] => 0 | a :: t => fold_right Qmin2 a t end.

(** Minima over [Q u {+oo}], [None] standing for [+oo]. *)
Definition omin (a b : option Q) : option Q :=
  match a, b with
  | None, _ => b
  | _, None => a
  | Some u, Some v => Some (Qmin2 u v)
  end.

Definition ominl (l : list (option Q)) : option Q := fold_right omin None l.

Definition nmin (a b : option nat) : option nat :=
  match a, b with
  | None, _ => b
  | _, None => a
  | Some u, Some v => Some (Nat.min u v)
  end.

Definition nminl (l : list (option nat)) : option nat := fold_right nmin None l.

(** ** Paths and their costs (docs/spec.md §1) *)

(** A move sequence from [x] is a list of move indices. [wend] is where it ends, [wcost] its
    cost (the sum of the stage costs), [wvalid] says every index names a move. Appending the
    termination action [uT] at the goal adds cost 0, so "goal-reaching action sequences" and
    "move sequences ending at the goal" have the same costs. *)
Fixpoint wend (P : problem) (x : nat) (w : list nat) : nat :=
  match w with [] => x | i :: w' => wend P (target P x (Move i)) w' end.

Fixpoint wcost (P : problem) (x : nat) (w : list nat) : Q :=
  match w with [] => 0 | i :: w' => cost P x (Move i) + wcost P (target P x (Move i)) w' end.

Fixpoint wvalid (P : problem) (x : nat) (w : list nat) : Prop :=
  match w with
  | [] => True
  | i :: w' => (i < length (moves P x))%nat /\ wvalid P (target P x (Move i)) w'
  end.

(** [w] is a goal-reaching move sequence from [x]. *)
Definition reaches (P : problem) (x : nat) (w : list nat) : Prop :=
  wvalid P x w /\ wend P x w = goal P.

(** ** The optimal cost-to-go [G*] (docs/spec.md §1) *)

(** Bellman-Ford: [bf k x] is the least cost of a goal-reaching move sequence from [x] with at
    most [k] moves ([None] if there is none). Kept as a list of the [nstates] values, so that
    evaluation is polynomial. *)
Definition bf_start (P : problem) (x : nat) : option Q :=
  if Nat.eqb x (goal P) then Some 0 else None.

Definition bf_step (P : problem) (d : nat -> option Q) (x : nat) : option Q :=
  omin (bf_start P x)
       (ominl (map (fun yl => option_map (Qplus (snd yl)) (d (fst yl))) (moves P x))).

Fixpoint bfl (P : problem) (k : nat) : list (option Q) :=
  match k with
  | O => map (bf_start P) (seq 0 (nstates P))
  | S k' => map (bf_step P (fun y => nth y (bfl P k') None)) (seq 0 (nstates P))
  end.

Definition bf (P : problem) (k : nat) (x : nat) : option Q := nth x (bfl P k) None.

(** [G*(x)]: the least cost over goal-reaching action sequences from [x], [None] = [+oo]
    (docs/spec.md §1). Sequences of at most [nstates] moves suffice (costs are [>= 0]: a cheapest
    sequence can be taken without repeated states); [Paths.v] proves that [Gstar] is the least
    cost over ALL goal-reaching sequences, and attained. *)
Definition Gstar (P : problem) (x : nat) : option Q := bf P (nstates P) x.

(** [Q*(x,u) = l(x,u) + G*(f(x,u))] (docs/spec.md §1); [Q*(xg,uT) = 0]. *)
Definition Qstar (P : problem) (x : nat) (a : action) : option Q :=
  match a with
  | Term => Some 0
  | Move _ => option_map (Qplus (cost P x a)) (Gstar P (target P x a))
  end.

(** ** [h]: fewest moves on an optimal path (the kernel's [QProblem::optimal_steps]) *)

(** A move [(x,u)] is optimal ("tight") when [l(x,u) + G*(f(x,u)) = G*(x)], both finite. *)
Definition tight (P : problem) (x : nat) (yl : nat * Q) : bool :=
  match Gstar P x, Gstar P (fst yl) with
  | Some gx, Some gy => Qeq_bool (snd yl + gy) gx
  | _, _ => false
  end.

Definition hb_step (P : problem) (h : nat -> option nat) (x : nat) : option nat :=
  if Nat.eqb x (goal P) then Some 0%nat
  else nmin (h x)
         (nminl (map (fun yl => if tight P x yl then option_map S (h (fst yl)) else None)
                     (moves P x))).

Fixpoint hbl (P : problem) (k : nat) : list (option nat) :=
  match k with
  | O => map (fun x => if Nat.eqb x (goal P) then Some 0%nat else None) (seq 0 (nstates P))
  | S k' => map (hb_step P (fun y => nth y (hbl P k') None)) (seq 0 (nstates P))
  end.

Definition hb (P : problem) (k : nat) (x : nat) : option nat := nth x (hbl P k) None.

(** [h(x)]: the fewest moves of an optimal goal-reaching path from [x] ([None] if the goal
    is unreachable); [Paths.v] proves this meaning. *)
Definition hstar (P : problem) (x : nat) : option nat := hb P (nstates P) x.

(** ** Derandomized Q-learning, [rho = 1] (docs/spec.md §2; the paper's Proposition 1) *)

(** Value vectors: one rational per state-action pair. *)
Definition qvec := nat -> action -> Q.

(** [V(y) = min_u Q(y,u)] over the pairs of [y] (the termination pair included at the goal). *)
Definition V (P : problem) (q : qvec) (y : nat) : Q := qminl (map (q y) (actions P y)).

Definition qset (q : qvec) (x : nat) (a : action) (v : Q) : qvec :=
  fun x' a' => if Nat.eqb x' x && action_eqb a' a then v else q x' a'.

(** The update as printed: [Q(x,u) <- l(x,u) + min_u' Q(f(x,u),u')] for every pair, the
    termination pair included (there a zero-cost self-loop). *)
Definition update_printed (P : problem) (q : qvec) (p : nat * action) : qvec :=
  let '(x, a) := p in qset q x a (cost P x a + V P q (target P x a)).

(** The update with (H0): the termination pair [(xg, uT)] is held (at its initial value, 0
    under H0); [uT] is a pair only at the goal. Every move pair is updated as printed. *)
Definition update (P : problem) (q : qvec) (p : nat * action) : qvec :=
  match snd p with Term => q | Move _ => update_printed P q p end.

(** The values after updating the pairs [ps] in order. *)
Definition run (P : problem) (q : qvec) (ps : list (nat * action)) : qvec :=
  fold_left (update P) ps q.

Definition run_printed (P : problem) (q : qvec) (ps : list (nat * action)) : qvec :=
  fold_left (update_printed P) ps q.

(** ** The round bound of C1-corrected (the kernel's [QProblem::round_bound]) *)

(** [R1 = max over move pairs of 1 + h(f(x,u))], [0] without moves, [None] if some [h] is
    [+oo]. *)
Definition R1 (P : problem) : option nat :=
  fold_right
    (fun p acc =>
       match acc, hstar P (target P (fst p) (snd p)) with
       | Some r, Some k => Some (Nat.max r (S k))
       | _, _ => None
       end)
    (Some 0%nat) (move_pairs P).

(** [Q0 >= Q*] on every move pair (with [Q*] finite). *)
Definition above (P : problem) (q0 : qvec) : bool :=
  forallb (fun p => match Qstar P (fst p) (snd p) with
                    | Some v => Qle_bool v (q0 (fst p) (snd p))
                    | None => false
                    end) (move_pairs P).

(** [c]: the least move cost ([None] without moves). *)
Definition min_cost (P : problem) : option Q :=
  match map (fun p => cost P (fst p) (snd p)) (move_pairs P) with
  | [] => None
  | c :: cs => Some (fold_right Qmin2 c cs)
  end.

(** [max(0, max over move pairs of Q*(x,u) )], [None] if some [Q*] is [+oo]. *)
Definition qmax_star (P : problem) : option Q :=
  fold_right
    (fun p acc =>
       match acc, Qstar P (fst p) (snd p) with
       | Some a, Some v => Some (Qmax2 a v)
       | _, _ => None
       end)
    (Some 0) (move_pairs P).

(** [m = min(0, min Q0)] over move pairs. *)
Definition m0 (P : problem) (q0 : qvec) : Q :=
  fold_right (fun p acc => Qmin2 (q0 (fst p) (snd p)) acc) 0 (move_pairs P).

(** [ceil(gap / c)] as a natural number, [0] when [gap <= 0]. *)
Definition ceil_rounds (gap c : Q) : nat :=
  if Qle_bool gap 0 then 0%nat else Z.to_nat (Qceiling (gap / c)).

(** The bound of C1-corrected: [R1] when [Q0 >= Q*]; otherwise, with every move cost
    [>= c > 0], [max(R1, ceil((max Q* - m) / c))]; [None] if neither hypothesis holds. *)
Definition round_bound (P : problem) (q0 : qvec) : option nat :=
  match R1 P with
  | None => None
  | Some r1 =>
      if above P q0 then Some r1
      else match min_cost P with
           | None => None
           | Some c =>
               if Qle_bool c 0 then None
               else match qmax_star P with
                    | None => None
                    | Some qm => Some (Nat.max r1 (ceil_rounds (qm - m0 P q0) c))
                    end
           end
  end.

(** ** The minimal counterexample of C1 as printed *)

(** Two states: state 0 has a zero-cost self-loop and a move of cost 1 to the goal 1. *)
Definition loop2 : problem := {|
  nstates := 2;
  goal := 1;
  moves := fun x => match x with O => [(0%nat, 0); (1%nat, 1)] | _ => [] end
|}.
