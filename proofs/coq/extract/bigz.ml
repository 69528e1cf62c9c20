(* zarith's integers, under a name that the code extracted from Coq (which has modules Z and
   Pos of its own) cannot shadow. *)
include Z
