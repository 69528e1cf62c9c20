(* The driver of the certificate checkers extracted from Coq (checker.ml, from
   ../CertificateExtract.v). It reads one model and one certificate from the file named by its
   only argument, runs Checker.check (truecost, deterministic G-star) or
   Checker.check_discounted on them, and prints "accepted" (exit 0) or "rejected" (exit 1).
   Input it cannot read gets one line on stderr and exit 2. It reads nothing but that file.

   The file is whitespace-separated tokens:

     truecost-coq-check 1
     objective truecost                 (or: objective discounted <alpha num> <alpha den>)
     states <n>
     then n times, for the states 0 .. n-1 in order:
       state <flag 0|1> <value: inf | <num> <den>> <policy: - | <index>> <rank> <actions k>
       then k times:  action <num> <den> <outcomes j>  then j times:  <y> <num> <den>
     end

   The flag is "goal" (truecost) or "terminal" (discounted); an action's number is its stage
   cost (truecost) or its expected reward (discounted); the rank is the Coq checker's hint
   (ignored by the discounted checker). Integers are decimal, an optional "-" then digits;
   denominators are positive; indices, ranks and counts are at most 10^6. *)

open Checker

exception Malformed of string

let fail fmt = Printf.ksprintf (fun s -> raise (Malformed s)) fmt

let limit = 1_000_000

(* The tokens of the whole file. *)
let tokens_of (text : string) : string array =
  let out = ref [] and buf = Buffer.create 32 in
  let flush () =
    if Buffer.length buf > 0 then begin
      out := Buffer.contents buf :: !out;
      Buffer.clear buf
    end
  in
  String.iter
    (fun c ->
      match c with
      | ' ' | '\n' | '\t' | '\r' -> flush ()
      | c -> Buffer.add_char buf c)
    text;
  flush ();
  Array.of_list (List.rev !out)

let all_digits s from =
  String.length s > from
  && (let ok = ref true in
      for i = from to String.length s - 1 do
        if s.[i] < '0' || s.[i] > '9' then ok := false
      done;
      !ok)

let integer (s : string) : Bigz.t =
  if all_digits s 0 || (String.length s > 1 && s.[0] = '-' && all_digits s 1) then
    Bigz.of_string s
  else fail "%S is not an integer" s

let positive (s : string) : Bigz.t =
  let z = integer s in
  if Bigz.sign z > 0 then z else fail "denominator %S is not positive" s

let small (s : string) : int =
  if all_digits s 0 && String.length s <= 7 && int_of_string s <= limit then int_of_string s
  else fail "%S is not a natural number of at most 10^6" s

(* Peano naturals, shared: cache.(k) is k. *)
let cache = ref [| O |]

let nat_of (k : int) : nat =
  let have = Array.length !cache in
  if k >= have then begin
    let c = Array.make (k + 1) O in
    Array.blit !cache 0 c 0 have;
    for i = have to k do
      c.(i) <- S c.(i - 1)
    done;
    cache := c
  end;
  !cache.(k)

let rec list_of = function [] -> Nil | x :: t -> Cons (x, list_of t)

let run (path : string) : bool =
  let text =
    try
      let ic = open_in_bin path in
      let s = really_input_string ic (in_channel_length ic) in
      close_in ic;
      s
    with Sys_error e | Failure e -> fail "cannot read the input: %s" e
  in
  let toks = tokens_of text in
  let pos = ref 0 in
  let next () =
    if !pos >= Array.length toks then fail "the input ends early";
    let t = toks.(!pos) in
    incr pos;
    t
  in
  let expect w =
    let t = next () in
    if t <> w then fail "expected %S, found %S" w t
  in
  let fraction () =
    let n = integer (next ()) in
    let d = positive (next ()) in
    { qnum = n; qden = d }
  in
  expect "truecost-coq-check";
  expect "1";
  expect "objective";
  let alpha =
    match next () with
    | "truecost" -> Option.None
    | "discounted" -> Option.Some (fraction ())
    | t -> fail "unknown objective %S" t
  in
  expect "states";
  let n = small (next ()) in
  let model = ref [] and values = ref [] and policy = ref [] and ranks = ref [] in
  for _ = 1 to n do
    expect "state";
    let flag =
      match next () with "0" -> false | "1" -> true | t -> fail "flag %S is not 0 or 1" t
    in
    let value =
      match toks.(!pos) with
      | "inf" ->
          incr pos;
          None
      | _ -> Some (fraction ())
      | exception Invalid_argument _ -> fail "the input ends early"
    in
    let pi = match next () with "-" -> None | t -> Some (nat_of (small t)) in
    let rank = nat_of (small (next ())) in
    let k = small (next ()) in
    let actions =
      List.init k (fun _ ->
          expect "action";
          let c = fraction () in
          let j = small (next ()) in
          let outcomes =
            List.init j (fun _ ->
                let y = nat_of (small (next ())) in
                Pair (y, fraction ()))
          in
          Pair (c, list_of outcomes))
    in
    model := Pair (flag, list_of actions) :: !model;
    values := value :: !values;
    policy := pi :: !policy;
    ranks := rank :: !ranks
  done;
  expect "end";
  if !pos <> Array.length toks then fail "%S after the end" toks.(!pos);
  let m = list_of (List.rev !model)
  and v = list_of (List.rev !values)
  and p = list_of (List.rev !policy)
  and r = list_of (List.rev !ranks) in
  match alpha with
  | Option.None -> check m v p r
  | Option.Some a -> check_discounted m a v p

let () =
  match Sys.argv with
  | [| _; path |] -> (
      match run path with
      | true ->
          print_endline "accepted";
          exit 0
      | false ->
          print_endline "rejected";
          exit 1
      | exception Malformed why ->
          prerr_endline ("malformed input: " ^ String.escaped why);
          exit 2)
  | _ ->
      prerr_endline "usage: truecost-coq-check FILE";
      exit 2
