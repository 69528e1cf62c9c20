(** * Rationals as reals: the rewriting facts the real-valued proofs use

    The computable definitions are over [Q] and the theorems about costs over [R]; [Q2R]
    embeds one into the other ([Coq.QArith.Qreals]). These are the constants and integer
    casts that the proofs of C3, C4 and the C3/C4 bridge rewrite. *)

From Coq Require Import Reals Lra QArith Qreals.

Open Scope R_scope.

Lemma Q2R_0 : Q2R 0 = 0.
Proof. unfold Q2R; simpl; lra. Qed.

Lemma Q2R_1 : Q2R 1 = 1.
Proof. unfold Q2R; simpl; lra. Qed.

Lemma Q2R_inject_Z z : Q2R (inject_Z z) = IZR z.
Proof. unfold Q2R; simpl; field. Qed.

Lemma Q2R_nat k : Q2R (inject_Z (Z.of_nat k)) = INR k.
Proof. rewrite Q2R_inject_Z, <- INR_IZR_INZ; reflexivity. Qed.
