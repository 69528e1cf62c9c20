(** * The certificate checkers, extracted to OCaml.

    [check] (truecost, deterministic [G*]) and [check_discounted] are extracted to
    [extract/checker.ml]; [extract/driver.ml] reads a model and a certificate from a text file
    and runs them. Everything is extracted as Coq defines it except the binary numbers:
    [positive] and [Z] are zarith's arbitrary-precision integers [Z.t] (a [positive] is a
    [Z.t] >= 1; the directives name zarith's module [Z] [Bigz], [extract/bigz.ml], since the
    extracted code has modules [Z] and [Pos] of its own), with the directives below for their constructors, their pattern matching and
    the operations the checkers use. These directives, the extraction itself, OCaml, zarith
    and the driver's reading of the file are trusted; the checkers' soundness is
    [CertificateCheck.check_policy], [CertificateCheck.check_optimal],
    [CertificateDiscounted.check_discounted_policy] and
    [CertificateDiscounted.check_discounted_optimal]. *)

From Coq Require Import Extraction QArith.
From Truecost Require Import CertificateCheck CertificateDiscounted.

Extraction Language OCaml.

(** [bool]: OCaml's booleans. *)
Extract Inductive bool => "bool" [ "true" "false" ].

(** [positive]: [xI p = 2p + 1], [xO p = 2p], [xH = 1]. *)
Extract Inductive positive => "Bigz.t"
  [ "(fun p -> Bigz.succ (Bigz.shift_left p 1))" "(fun p -> Bigz.shift_left p 1)" "Bigz.one" ]
  "(fun fI fO fH p -> if Bigz.equal p Bigz.one then fH () else if Bigz.is_odd p then fI (Bigz.shift_right p 1) else fO (Bigz.shift_right p 1))".

(** [Z]: [Z0 = 0], [Zpos p = p], [Zneg p = -p]. *)
Extract Inductive Z => "Bigz.t"
  [ "Bigz.zero" "(fun p -> p)" "Bigz.neg" ]
  "(fun f0 fp fn z -> let s = Bigz.sign z in if s = 0 then f0 () else if s > 0 then fp z else fn (Bigz.neg z))".

(** The operations on them that [Qplus], [Qmult], [Qeq_bool] and [Qle_bool] use. *)
Extract Constant Pos.add => "Bigz.add".
Extract Constant Pos.mul => "Bigz.mul".
Extract Constant Z.add => "Bigz.add".
Extract Constant Z.mul => "Bigz.mul".
Extract Constant Zeq_bool => "Bigz.equal".
Extract Constant Z.leb => "Bigz.leq".

Extraction "extract/checker.ml" check check_discounted.
