"""Certificates of models nobody here wrote: PRISM benchmark models from the PRISM and QVBS case
studies (the copies stormpy ships in ``stormpy/examples/files/mdp``), built by Storm with exact
rational numbers and written by Storm in its explicit DRN format. On each file:

* ``truecost solve --file F.drn --algorithm exact --certificate C`` (the truecost objective and,
  with ``--objective discounted --alpha 99/100``, the discounted one), then ``truecost check``
  and ``truecost check --coq`` accept, and the certificate's values equal Storm's exact
  ``Rmin=? [F goal]`` at every state;
* every kind of tampering is rejected by ``check`` and by ``check --coq``, each naming the state
  and condition this test derives on its own (from the model as Storm reads the file), and by
  the verified checker itself, run directly on the model as Storm reads it: ``check --coq`` runs
  the Rust checker first, and a certificate that checker rejects never reaches the Coq one.

The models name their goals and costs as their authors did (``"done"``, ``"coinflips"``):
truecost reads them with ``--goal-label`` and ``--cost-reward`` (docs/guide/formats.md); the
files are used as Storm writes them.

Needs stormpy (``pip install stormpy``) and a built ``truecost`` binary (``$TRUECOST_BIN``, else
the newer of target/release and target/debug), and for ``--coq`` Coq, OCaml, ocamlfind and
zarith. Without stormpy the tests are skipped, or fail naming it when ``TRUECOST_REQUIRE_API=1``
(CI).
"""

import hashlib
import json
import os
import subprocess
import tempfile
import unittest
from collections import deque
from fractions import Fraction
from typing import NamedTuple, Optional

from cli_binary import truecost_binary

try:
    import stormpy
except ImportError:  # pragma: no cover - reported by every test
    stormpy = None

MISSING_STORMPY = ("stormpy is not installed: the certificates of Storm-written models need "
                   "Storm's Python bindings (pip install stormpy, in a virtual environment)")

ALPHA = Fraction(99, 100)
TINY = Fraction(1, 10**30)


class Foreign(NamedTuple):
    """A PRISM model of stormpy's examples and what truecost needs to read its DRN export."""
    name: str                 # the file's stem in stormpy/examples/files/mdp
    constants: Optional[str]  # values of the model's undefined constants
    goal: str                 # the label of the target
    reward: Optional[str]     # the reward structure of the costs (None: the model's only one)
    options: tuple            # truecost's options naming them
    discounted: bool          # also certify the discounted objective (skipped where slow)


MODELS = (
    Foreign("two_dice", None, "done", "coinflips", ("--goal-label", "done"), True),
    Foreign("coin2-2", None, "finished", "steps", ("--goal-label", "finished"), True),
    Foreign("csma2_2", None, "all_delivered", "time", ("--goal-label", "all_delivered"), True),
    # 4,093 states; its discounted optimum takes 10 s in the debug build.
    Foreign("firewire", "delay=3,fast=0.5", "elected", "time",
            ("--goal-label", "elected", "--cost-reward", "time"), False),
    Foreign("maze_2", None, "goal", None, (), True),
    # Two ones, a goal most runs miss: most states' least expected cost is infinite (inf where
    # no policy reaches the goal with probability 1), and the other sums loop at no cost.
    Foreign("two_dice", None, "two", "coinflips", ("--goal-label", "two"), False),
)


def value(text):
    """A certificate value: a Fraction, or None for ``inf``."""
    return None if text == "inf" else Fraction(text)


class StormModel:
    """The model as Storm reads the DRN file: per state its goal flag and actions, each a cost
    (the reward structure's state reward plus its action reward) and its outcomes."""

    def __init__(self, path, spec):
        m = stormpy.build_model_from_drn[stormpy.Rational](path)
        self.storm = m
        name = spec.reward if spec.reward is not None else next(iter(m.reward_models))
        rewards = m.reward_models[name]
        assert not rewards.has_transition_rewards, "transition rewards are not read here"
        goals = m.labeling.get_states(spec.goal)
        tm = m.transition_matrix
        self.n = m.nr_states
        self.goal = [goals.get(x) for x in range(self.n)]
        self.actions = []
        # (Each read of these properties copies the whole vector.)
        state_rewards = rewards.state_rewards if rewards.has_state_rewards else None
        action_rewards = rewards.state_action_rewards if rewards.has_state_action_rewards else None
        for x in range(self.n):
            state_reward = Fraction(str(state_rewards[x])) if state_rewards else 0
            acts = []
            for row in range(tm.get_row_group_start(x), tm.get_row_group_end(x)):
                cost = state_reward
                if action_rewards:
                    cost += Fraction(str(action_rewards[row]))
                outcomes = [(e.column, Fraction(str(e.value))) for e in tm.get_row(row)]
                acts.append((cost, outcomes))
            self.actions.append(acts)

    def q(self, x, a, v, alpha=None):
        """``c + Σ p V`` (truecost), or ``-c + α Σ p V`` (discounted, the negated costs)."""
        cost, outcomes = self.actions[x][a]
        total = sum(p * v[y] for y, p in outcomes)
        return cost + total if alpha is None else -cost + alpha * total

    def predecessors(self, policy, values):
        """Per state, the finite non-goal states whose policy action may lead to it."""
        into = [[] for _ in range(self.n)]
        for y in range(self.n):
            a = policy[y]
            if (values[y] is not None and not self.goal[y] and a is not None
                    and a < len(self.actions[y])):
                for x, _ in self.actions[y][a][1]:
                    if not into[x] or into[x][-1] != y:
                        into[x].append(y)
        return into

    def hints(self, policy, values):
        """The Coq checker's hints (proofs/coq/extract/driver.ml): per finite state its distance
        to a goal along the policy's outcomes, per ``inf`` state the round of the ``W*``
        iteration that removes it; 0 where there is none (which the checker rejects)."""
        rank = [0] * self.n
        into = self.predecessors(policy, values)
        seen = list(self.goal)
        queue = deque(x for x in range(self.n) if self.goal[x])
        while queue:
            y = queue.popleft()
            for x in into[y]:
                if not seen[x]:
                    seen[x] = True
                    rank[x] = rank[y] + 1
                    queue.append(x)
        w = [True] * self.n
        round_ = 1
        while True:
            r = list(self.goal)
            changed = True
            while changed:
                changed = False
                for x in range(self.n):
                    if w[x] and not r[x] and any(
                            all(w[y] for y, _ in outs) and any(r[y] for y, _ in outs)
                            for _, outs in self.actions[x]):
                        r[x] = changed = True
            if r == w:
                return rank
            for x in range(self.n):
                if w[x] and not r[x] and values[x] is None:
                    rank[x] = round_
            w, round_ = r, round_ + 1

    def coq_input(self, cert):
        """The verified checker's input (format: proofs/coq/extract/driver.ml's header) for
        ``cert`` on this model, as Storm reads it."""
        values = [value(v) for v in cert["values"]]
        policy = cert["policy"]
        alpha = Fraction(cert["alpha"]) if cert["objective"] == "discounted" else None
        frac = lambda q: f"{q.numerator} {q.denominator}"  # noqa: E731
        lines = ["truecost-coq-check 1",
                 "objective truecost" if alpha is None else f"objective discounted {frac(alpha)}",
                 f"states {self.n}"]
        ranks = self.hints(policy, values) if alpha is None else [0] * self.n
        for x in range(self.n):
            v = "inf" if values[x] is None else frac(values[x])
            pi = "-" if policy[x] is None else str(min(policy[x], len(self.actions[x])))
            lines.append(f"state {int(self.goal[x])} {v} {pi} {ranks[x]} {len(self.actions[x])}")
            for cost, outcomes in self.actions[x]:
                number = cost if alpha is None else -cost
                lines.append(" ".join([f"action {frac(number)} {len(outcomes)}",
                                       *(f"{y} {frac(p)}" for y, p in outcomes)]))
        lines.append("end")
        return "\n".join(lines) + "\n"


_SHARED = {}


def shared():
    """Every model built by Storm and written as a DRN file, once per run (the certificates are
    kept beside them): the directory and ``{spec: (DRN path, StormModel)}``."""
    if not _SHARED:
        tmp = tempfile.TemporaryDirectory()
        built = {}
        for spec in MODELS:
            program = stormpy.parse_prism_program(
                os.path.join(os.path.dirname(stormpy.__file__), "examples", "files", "mdp",
                             spec.name + ".nm"))
            if spec.constants:
                program = stormpy.instantiate_constants(program, spec.constants)[0]
            drn = os.path.join(tmp.name, spec.name + ".drn")
            if not os.path.exists(drn):
                stormpy.io.export_to_drn(stormpy.build_model[stormpy.Rational](program), drn)
            built[spec] = (drn, StormModel(drn, spec))
        _SHARED.update(tmp=tmp, built=built)
    return _SHARED["tmp"], _SHARED["built"]


def tearDownModule():
    if _SHARED:
        _SHARED["tmp"].cleanup()


class ForeignCase(unittest.TestCase):
    """Runs truecost on the models' DRN files."""

    def setUp(self):
        if stormpy is None:
            if os.environ.get("TRUECOST_REQUIRE_API") == "1":
                self.fail(MISSING_STORMPY)
            self.skipTest(MISSING_STORMPY)
        self.binary = truecost_binary()
        if self.binary is None:
            self.fail("no truecost binary: build it with cargo build (target/debug/truecost)")
        self.tmp, self.built = shared()

    def truecost(self, *args):
        return subprocess.run([self.binary, *args], capture_output=True, text=True, timeout=300)

    def certify(self, spec, *objective):
        """The certificate ``solve`` writes (``objective``: extra options), as JSON."""
        drn, _ = self.built[spec]
        path = os.path.join(self.tmp.name, f"{spec.name}-{spec.goal}-{len(objective)}.cert.json")
        if not os.path.exists(path):
            out = self.truecost("solve", "--file", drn, *spec.options, "--algorithm", "exact",
                                *objective, "--certificate", path)
            self.assertEqual(out.returncode, 0, out.stderr)
        with open(path) as f:
            return json.load(f)

    def check(self, spec, cert, coq):
        """``check`` (with ``--coq``) of ``cert`` on the model's file: the process."""
        drn, _ = self.built[spec]
        path = os.path.join(self.tmp.name, "candidate.json")
        with open(path, "w") as f:
            json.dump(cert, f)
        return self.truecost("check", *(("--coq",) if coq else ()), "--file", drn,
                             *spec.options, path, "--format", "json")

    def accepted(self, spec, cert):
        for coq in (False, True):
            out = self.check(spec, cert, coq)
            self.assertEqual(out.returncode, 0, f"{spec.name} coq={coq}: {out.stderr}")
            report = json.loads(out.stdout)
            self.assertTrue(report["accepted"])
            self.assertEqual(report["coq_checked"], coq)
            self.assertEqual(report["coq_checker"] is not None, coq)
            self.assertEqual(report["states"], self.built[spec][1].n)

    def rejected(self, spec, cert, state, condition):
        """Both ``check`` and ``check --coq`` reject ``cert`` in one line naming ``state``
        (None: no state) and ``condition``; the verified checker, run on the model as Storm
        reads it, rejects it too (except a wrong SHA-256, which is not its business)."""
        where = "" if state is None else f"state {state}: "
        for coq in (False, True):
            out = self.check(spec, cert, coq)
            self.assertEqual(out.returncode, 1, f"{spec.name} coq={coq}: {out.stderr}")
            lines = out.stderr.strip().split("\n")
            self.assertEqual(len(lines), 1, out.stderr)
            self.assertTrue(
                lines[0].startswith(f"error: certificate rejected: {where}condition {condition}: "),
                f"{spec.name} coq={coq}: expected state {state}, condition {condition}: {lines[0]}")
            report = json.loads(out.stdout)
            self.assertEqual((report["accepted"], report["state"], report["condition"]),
                             (False, state, condition))
        if condition != "problem":
            self.assertEqual(self.coq_verdict(spec, cert), "rejected",
                             (spec.name, state, condition))

    def coq_checker(self, spec):
        """The extracted checker program ``check --coq`` runs (its ``coq_checker`` in the JSON
        report), asked once per run on the model's own certificate."""
        if "checker" not in _SHARED:
            out = self.check(spec, self.certify(spec), True)
            self.assertEqual(out.returncode, 0, out.stderr)
            _SHARED["checker"] = json.loads(out.stdout)["coq_checker"]
        return _SHARED["checker"]

    def coq_verdict(self, spec, cert):
        checker = self.coq_checker(spec)
        self.assertTrue(os.access(checker, os.X_OK),
                        f"the extracted checker {checker} is not built (check --coq builds it)")
        path = os.path.join(self.tmp.name, "coq-input.txt")
        with open(path, "w") as f:
            f.write(self.built[spec][1].coq_input(cert))
        out = subprocess.run([checker, path], capture_output=True, text=True, timeout=300)
        self.assertIn(out.returncode, (0, 1), out.stderr)
        return out.stdout.strip()


class Accepted(ForeignCase):
    def test_truecost_certificates_are_accepted_and_are_storms_optimum(self):
        for spec in MODELS:
            with self.subTest(model=spec.name):
                model = self.built[spec][1]
                cert = self.certify(spec)
                self.assertEqual(cert["objective"], "truecost")
                with open(self.built[spec][0], "rb") as f:
                    self.assertEqual(cert["problem"]["sha256"],
                                     hashlib.sha256(f.read()).hexdigest())
                self.accepted(spec, cert)
                self.assertEqual(self.coq_verdict(spec, cert), "accepted")
                # Storm's exact engine on the same file: the least expected cost of reaching
                # the goal, at every state.
                reward = f'{{"{spec.reward}"}}' if spec.reward else ""
                prop = stormpy.parse_properties(f'R{reward}min=? [F "{spec.goal}"]')[0]
                result = stormpy.model_checking(model.storm, prop,
                                                environment=stormpy.environments.exact())
                storm = [str(result.get_value(x)) for x in range(model.n)]
                storm = [None if t == "inf" else Fraction(t) for t in storm]
                self.assertEqual([value(v) for v in cert["values"]], storm)
                self.assertEqual(None in storm, spec.goal == "two")

    def test_discounted_certificates_are_accepted_and_solve_bellmans_equation(self):
        for spec in MODELS:
            if not spec.discounted:
                continue
            with self.subTest(model=spec.name):
                model = self.built[spec][1]
                cert = self.certify(spec, "--objective", "discounted", "--alpha", "99/100")
                self.assertEqual((cert["objective"], Fraction(cert["alpha"])),
                                 ("discounted", ALPHA))
                self.accepted(spec, cert)
                self.assertEqual(self.coq_verdict(spec, cert), "accepted")
                # Derived here from Storm's reading: 0 at the goals, elsewhere the greatest
                # -cost + α Σ p V over the actions, attained by the certificate's action.
                v = [value(t) for t in cert["values"]]
                for x in range(model.n):
                    if model.goal[x]:
                        self.assertEqual((v[x], cert["policy"][x]), (0, None))
                        continue
                    qs = [model.q(x, a, v, ALPHA) for a in range(len(model.actions[x]))]
                    self.assertEqual(v[x], max(qs), (spec.name, x))
                    self.assertEqual(qs[cert["policy"][x]], v[x], (spec.name, x))


def changed(cert, changes):
    """A copy of ``cert`` with ``changes``: ``{state: (value text, policy entry)}``."""
    c = json.loads(json.dumps(cert))
    for x, (val, act) in changes.items():
        c["values"][x], c["policy"][x] = val, act
    return c


class Tampered(ForeignCase):
    """Each kind of tampering, where the model has a state it applies to; the expected state
    and condition are derived from the checker's documented order (docs/guide/certificates.md:
    conditions in order, each over the states in order)."""

    def pick(self, model, cert, test):
        """The states (from the middle of the model on, then from the start) where ``test``
        holds: tamperings land away from the initial state."""
        order = list(range(model.n // 2, model.n)) + list(range(model.n // 2))
        return [x for x in order if test(x)]

    def truecost_tamperings(self, spec):
        """(kind, tampered certificate, expected state, expected condition)."""
        model = self.built[spec][1]
        cert = self.certify(spec)
        v = [value(t) for t in cert["values"]]
        pi = cert["policy"]
        inner = lambda x: not model.goal[x] and v[x] is not None  # noqa: E731
        preds = model.predecessors(pi, v)
        out = []
        tampered = lambda changes: changed(cert, changes)  # noqa: E731
        for x in self.pick(model, cert, inner)[:1]:
            out.append(("a value off by 10^-30", tampered({x: (str(v[x] + TINY), pi[x])}),
                        min([x, *preds[x]]), "evaluation"))
        for x in self.pick(model, cert, inner):
            other = [a for a in range(len(model.actions[x])) if model.q(x, a, v) != v[x]]
            if other:
                out.append(("another action", tampered({x: (cert["values"][x], other[0])}), x,
                            "evaluation"))
                break
        # A worse action with the value it gives, at a state no policy action leads to: every
        # equation holds, the state's value is not the least.
        for x in self.pick(model, cert, lambda x: inner(x) and not preds[x]):
            worse = [a for a, (_, outs) in enumerate(model.actions[x])
                     if model.q(x, a, v) > v[x] and all(y != x for y, _ in outs)]
            if worse:
                c = tampered({x: (str(model.q(x, worse[0], v)), worse[0])})
                out.append(("a worse action with its own value", c, x, "optimality"))
                break
        # A policy that never reaches the goal: a self-loop at a finite state. It costs
        # something there (asserted), so its equation V(x) = c + V(x) fails before `proper`.
        for x in self.pick(model, cert, inner):
            loops = [a for a, (_, outs) in enumerate(model.actions[x])
                     if all(y == x for y, _ in outs)]
            if loops:
                self.assertGreater(model.actions[x][loops[0]][0], 0)
                out.append(("an improper policy (a self-loop)",
                            tampered({x: (cert["values"][x], loops[0])}), x, "evaluation"))
                break
        # A free self-loop at an `inf` state, claimed to cost 0 there: every equation holds,
        # but the policy never reaches the goal (where no finite state has an action into it).
        into = {y for x in range(model.n) if inner(x)
                for _, outs in model.actions[x] for y, _ in outs}
        for x in self.pick(model, cert, lambda x: v[x] is None and x not in into):
            loops = [a for a, (cost, outs) in enumerate(model.actions[x])
                     if cost == 0 and all(y == x for y, _ in outs)]
            if loops:
                out.append(("an improper policy (a free self-loop)", tampered({x: ("0", loops[0])}),
                            x, "proper"))
                break
        for x in self.pick(model, cert, inner)[:1]:
            out.append(("an index out of range",
                        tampered({x: (cert["values"][x], len(model.actions[x]))}), x, "policy"))
            # A finite state claimed inf: where the policy leads there, that state's action
            # leaves the finite states; where nothing leads there, the state is in W*.
            out.append(("a finite state claimed inf", tampered({x: ("inf", None)}),
                        min(preds[x]) if preds[x] else x, "closed" if preds[x] else "infinite"))
        for x in self.pick(model, cert, lambda x: inner(x) and not preds[x])[:1]:
            out.append(("a finite state without predecessors claimed inf",
                        tampered({x: ("inf", None)}), x, "infinite"))
        goal = self.pick(model, cert, lambda x: model.goal[x])[0]
        out.append(("a goal's value changed", tampered({goal: ("1", None)}), goal, "goal"))
        wrong = json.loads(json.dumps(cert))
        wrong["problem"]["sha256"] = "0" * 64
        out.append(("a wrong SHA-256", wrong, None, "problem"))
        return out

    def test_truecost_tamperings_are_rejected_by_both_checkers(self):
        kinds = set()
        for spec in MODELS:
            for kind, cert, state, condition in self.truecost_tamperings(spec):
                kinds.add(kind)
                with self.subTest(model=spec.name, kind=kind):
                    self.rejected(spec, cert, state, condition)
        self.assertTrue({"a value off by 10^-30", "another action",
                         "a worse action with its own value", "an improper policy (a self-loop)",
                         "an improper policy (a free self-loop)",
                         "an index out of range",
                         "a finite state claimed inf",
                         "a finite state without predecessors claimed inf",
                         "a goal's value changed", "a wrong SHA-256"} <= kinds, kinds)

    def test_discounted_tamperings_are_rejected_by_both_checkers(self):
        kinds = set()
        for spec in MODELS:
            if not spec.discounted:
                continue
            model = self.built[spec][1]
            cert = self.certify(spec, "--objective", "discounted", "--alpha", "99/100")
            v = [value(t) for t in cert["values"]]
            pi = cert["policy"]
            inner = lambda x: not model.goal[x]  # noqa: E731
            preds = model.predecessors(pi, v)
            x = self.pick(model, cert, inner)[0]
            cases = [("a value off by 10^-30", changed(cert, {x: (str(v[x] - TINY), pi[x])}),
                      min([x, *preds[x]]), "evaluation"),
                     ("an index out of range",
                      changed(cert, {x: (cert["values"][x], len(model.actions[x]))}), x, "policy")]
            for y in self.pick(model, cert, inner):
                other = [a for a in range(len(model.actions[y]))
                         if model.q(y, a, v, ALPHA) != v[y]]
                if other:
                    cases.append(("another action",
                                  changed(cert, {y: (cert["values"][y], other[0])}), y,
                                  "evaluation"))
                    break
            goal = self.pick(model, cert, lambda x: model.goal[x])[0]
            cases.append(("a terminal state's value changed", changed(cert, {goal: ("-1", None)}),
                          goal, "goal"))
            wrong = json.loads(json.dumps(cert))
            wrong["problem"]["sha256"] = "f" * 64
            cases.append(("a wrong SHA-256", wrong, None, "problem"))
            for kind, c, state, condition in cases:
                kinds.add(kind)
                with self.subTest(model=spec.name, kind=kind):
                    self.rejected(spec, c, state, condition)
        self.assertEqual(len(kinds), 5, kinds)


class Options(ForeignCase):
    def test_names_the_file_lacks_are_refused_in_one_line(self):
        drn, _ = self.built[MODELS[3]]
        for options, expect in ((("--goal-label", "finished", "--cost-reward", "time"),
                                 "no state is labelled 'finished'"),
                                (("--goal-label", "elected"), "no reward model named 'cost'"),
                                (("--goal-label", "elected", "--cost-reward", "steps"),
                                 "no reward model named 'steps' (--cost-reward)")):
            with self.subTest(options=options):
                out = self.truecost("solve", "--file", drn, *options, "--algorithm", "exact")
                self.assertEqual((out.returncode, out.stdout), (1, ""))
                self.assertEqual(len(out.stderr.strip().split("\n")), 1, out.stderr)
                self.assertIn(expect, out.stderr)
        out = self.truecost("solve", "--problem", "3", "--goal-label", "done",
                            "--algorithm", "exact")
        self.assertEqual(out.returncode, 1)
        self.assertIn("--goal-label and --cost-reward apply to --file", out.stderr)


if __name__ == "__main__":
    unittest.main()
