"""truecost.solve, compare and discount give the command line's answers, number for number,
on the same inputs: an --env spec, a problem file, a Gymnasium environment object and id
(exported by the importer's command line for the CLI), a random FrozenLake map from
Gymnasium's own generator; and values derived by hand on a two-state problem."""

import json
import math
import os
import tempfile
import unittest
from fractions import Fraction

from test_api_support import (
    API_MISSING,
    cli_json,
    exact,
    export_with_importer,
    gymnasium,
    polynomial_text,
    success,
    truecost,
)

# A deterministic problem file: state 0 may loop (cost 1) or go to the goal 1 (cost 10).
# By hand: truecost 10 (the loop never reaches the goal); discounted (rewards -1 and -10):
# looping forever is worth -1/(1 - a), going -10, so looping is optimal exactly for
# a <= 9/10 (a tie at 9/10): the failure set is (0, 9/10], one breakpoint at 9/10.
LOOP_OR_GO = {
    "initial": 0,
    "goals": [1],
    "actions": [[{"to": 0, "cost": "1"}, {"to": 1, "cost": "10"}], []],
}


def setUpModule():
    if API_MISSING:
        raise unittest.SkipTest(API_MISSING)


class Agreement:
    """Assertions that an API answer is the CLI's JSON answer."""

    def assert_solve(self, call, cli_args, objective):
        """``call(with_cost)`` (a ``truecost.solve``) against ``truecost solve`` with
        ``cli_args``: without ``with_cost`` and, for the reach objective, with it and
        ``--with-cost``."""
        for asked in (False, True) if objective == "reach" else (False,):
            with self.subTest(with_cost=asked):
                cli = cli_json(*cli_args, *(["--with-cost"] if asked else []))
                self.assert_solution(call(asked), cli)

    def assert_solution(self, api, cli):
        self.assertEqual(api.objective, cli["objective"])
        self.assertEqual(api.values, tuple(exact(v) for v in cli["values"]))
        self.assertEqual(list(api.policy), cli["policy"])
        self.assertEqual(tuple(api.success_range), success(cli["success_probability"]))
        self.assertEqual(api.policy_success_probability, exact(cli["policy_success_probability"]))
        # Absent from the CLI's answer where not computed (reach without --with-cost).
        for key in ("expected_truecost", "expected_steps"):
            self.assertEqual(getattr(api, key), exact(cli[key]) if key in cli else None, key)
        self.assertEqual(api.initial_states, cli["initial_states"])
        key = {"truecost": "cost_to_go_initial", "reach": "reach_probability_initial",
               "discounted": "discounted_value_initial"}[api.objective]
        self.assertEqual(api.value, exact(cli[key]))
        for v in api.values + (api.value,):
            self.assertTrue(isinstance(v, Fraction) or v == math.inf, v)

    def assert_row(self, api, cli):
        self.assertEqual(api.objective, cli["objective"])
        self.assertEqual(api.alpha, None if cli["alpha"] is None else Fraction(cli["alpha"]))
        self.assertEqual(api.value, exact(cli["value_initial"]))
        self.assertEqual(tuple(api.success_range), success(cli["success_probability"]))
        self.assertEqual(api.expected_truecost, exact(cli["expected_truecost"]))
        self.assertEqual(api.expected_steps, exact(cli["expected_steps"]))

    def assert_discount(self, api, cli):
        self.assertEqual(len(api.breakpoints), len(cli["breakpoints"]))
        self.assertGreater(len(api.breakpoints), 0)
        for b, c in zip(api.breakpoints, cli["breakpoints"]):
            self.assertEqual(b.decimal, c["alpha_decimal"])
            self.assertEqual(b.exact, None if c["exact"] is None else Fraction(c["exact"]))
            self.assertEqual(b.interval, tuple(Fraction(x) for x in c["bracket"]))
            lo, hi = b.interval
            self.assertTrue(lo <= hi and hi - lo <= Fraction(1, 2**100))
            if c["polynomial"] is not None:
                self.assertEqual(polynomial_text(b.polynomial), c["polynomial"])
                self.assertEqual(len(b.polynomial) - 1, c["polynomial_degree"])
                self.assertEqual(b.minimal, c["polynomial_minimal"])
            self.assertEqual(b.touch, c["touch"])
            self.assertEqual(b.ties, {t["state"]: tuple(t["optimal_actions"]) for t in c["ties"]})
            self.assertEqual(tuple(b.success_range), success(c["success_probability"]))
            self.assertEqual(tuple(b.truecost_range), success(c["truecost"]))
            # The polynomial vanishes between the interval's ends: a sign change, or an end.
            value = [sum(k * x**i for i, k in enumerate(b.polynomial)) for x in b.interval]
            self.assertTrue(value[0] * value[1] <= 0, value)
        self.assertEqual(len(api.intervals), len(cli["intervals"]))
        for k, (i, c) in enumerate(zip(api.intervals, cli["intervals"])):
            self.assertEqual(i.sample, Fraction(c["sample_alpha"]))
            self.assertEqual(list(i.policy), c["policy"])
            self.assertEqual([list(a) for a in i.optimal], c["optimal_actions"])
            self.assertEqual(tuple(i.success_range), success(c["success_probability"]))
            self.assertEqual(tuple(i.truecost_range), success(c["truecost"]))
            self.assertLess(Fraction(0), i.sample)
            self.assertLess(i.sample, Fraction(1))
            if k > 0:
                self.assertIs(i.lo, api.breakpoints[k - 1])
                self.assertEqual(api.breakpoints[k - 1].optimal_right, i.optimal)
                self.assertLess(i.lo.interval[1], i.sample)
            if k < len(api.breakpoints):
                self.assertIs(i.hi, api.breakpoints[k])
                self.assertEqual(api.breakpoints[k].optimal_left, i.optimal)
                self.assertLess(i.sample, i.hi.interval[0])
        self.assertEqual(api.method, cli["method"])


class EnvSpec(Agreement, unittest.TestCase):
    """An --env spec, which truecost builds itself."""

    def test_solve_every_objective(self):
        for objective, alpha in (("truecost", None), ("reach", None), ("discounted", "0.9")):
            with self.subTest(objective=objective):
                args = ["solve", "--env", "frozenlake", "--algorithm", "exact",
                        "--objective", objective, *(["--alpha", alpha] if alpha else [])]
                self.assert_solve(
                    lambda asked: truecost.solve("frozenlake", objective, alpha, with_cost=asked),
                    args, objective)
        # Slippery FrozenLake: no policy reaches the goal with probability 1.
        self.assertEqual(truecost.solve("frozenlake").value, math.inf)

    def test_compare(self):
        api = truecost.compare("cliffwalking", alphas=["0.9", Fraction(99, 100)])
        cli = cli_json("compare", "--env", "cliffwalking", "--alphas", "0.9,99/100")
        self.assertEqual(len(api.rows), len(cli["rows"]))
        self.assertEqual(len(api.rows), 4)
        for a, c in zip(api.rows, cli["rows"]):
            self.assert_row(a, c)
        self.assertEqual(set(api.discounted), {Fraction(9, 10), Fraction(99, 100)})

    def test_discount(self):
        api = truecost.discount("frozenlake")
        self.assert_discount(api, cli_json("discount", "--env", "frozenlake"))
        # Slippery FrozenLake: every policy fails with positive probability, for every alpha.
        self.assertEqual(api.failure_set_text, "(0, 1)")
        self.assertEqual([(p.lo.exact, p.hi.exact) for p in api.failure_set], [(0, 1)])


class ProblemFile(Agreement, unittest.TestCase):
    """A problem file: the same file through the API and --file."""

    def setUp(self):
        self.dir = tempfile.TemporaryDirectory()
        self.path = os.path.join(self.dir.name, "loop_or_go.json")
        with open(self.path, "w") as f:
            json.dump(LOOP_OR_GO, f)

    def tearDown(self):
        self.dir.cleanup()

    def test_values_by_hand(self):
        t = truecost.solve(self.path)
        self.assertEqual((t.value, t.policy, t.expected_steps), (10, (1, None), 1))
        self.assertEqual(t.success_probability, 1)
        d = truecost.solve(self.path, "discounted", alpha=Fraction(1, 2))
        self.assertEqual((d.value, d.policy), (-2, (0, None)))  # looping: -1/(1 - 1/2)
        self.assertEqual(d.success_probability, 0)
        self.assertEqual(d.expected_truecost, math.inf)
        d = truecost.solve(self.path, "discounted", alpha="0.95")
        self.assertEqual((d.value, d.policy), (-10, (1, None)))

    def test_solve_and_compare_as_the_cli(self):
        for objective, alpha in (("truecost", None), ("reach", None), ("discounted", "1/2")):
            with self.subTest(objective=objective):
                args = ["solve", "--file", self.path, "--algorithm", "exact",
                        "--objective", objective, *(["--alpha", alpha] if alpha else [])]
                self.assert_solve(
                    lambda asked: truecost.solve(self.path, objective, alpha, with_cost=asked),
                    args, objective)
        api = truecost.compare(self.path, alphas=["1/2", "0.95"])
        cli = cli_json("compare", "--file", self.path, "--alphas", "1/2,0.95")
        for a, c in zip(api.rows, cli["rows"]):
            self.assert_row(a, c)

    def test_failure_set_by_hand_and_as_the_cli(self):
        api = truecost.discount(self.path)
        self.assertTrue(api.deterministic)
        [b] = api.breakpoints
        nine_tenths = Fraction(9, 10)
        self.assertEqual((b.exact, b.interval, b.polynomial),
                         (nine_tenths, (nine_tenths, nine_tenths), (-9, 10)))
        self.assertEqual(b.decimal, "0.9" + "0" * 29)
        [piece] = api.failure_set
        self.assertEqual((piece.lo.exact, piece.lo_closed, piece.hi.exact, piece.hi_closed),
                         (0, False, Fraction(9, 10), True))
        self.assertEqual(api.failure_set_text, "(0, 9/10]")
        cli = cli_json("discount", "--file", self.path)
        self.assertEqual(api.failure_set_text, cli["set"])
        self.assertEqual(
            [(p.lo.text, p.lo_closed, p.hi.text, p.hi_closed) for p in api.failure_set],
            [(p["lo"], p["lo_closed"], p["hi"], p["hi_closed"]) for p in cli["pieces"]])

    def test_reach_cost_only_when_asked(self):
        # By hand: going reaches the goal surely; its cost is 10 in 1 step, the reach policy's.
        plain = truecost.solve(self.path, "reach")
        asked = truecost.solve(self.path, "reach", with_cost=True)
        self.assertEqual((plain.value, plain.policy), (1, (1, None)))
        self.assertEqual((plain.expected_truecost, plain.expected_steps), (None, None))
        self.assertEqual((asked.value, asked.policy), (1, (1, None)))
        self.assertEqual((asked.expected_truecost, asked.expected_steps), (10, 1))
        args = ["solve", "--file", self.path, "--algorithm", "exact", "--objective", "reach"]
        self.assertNotIn("expected_truecost", cli_json(*args))
        self.assertEqual(cli_json(*args, "--with-cost")["expected_truecost"], "10")
        # Where the reach policy misses the goal (slippery FrozenLake: 14/17 at best), its
        # cost is infinite without being asked for, as on the command line.
        lake = truecost.solve("frozenlake", "reach")
        self.assertEqual((lake.expected_truecost, lake.expected_steps), (math.inf, math.inf))
        cli = cli_json("solve", "--env", "frozenlake", "--algorithm", "exact",
                       "--objective", "reach")
        self.assertEqual((cli["expected_truecost"], cli["expected_steps"]), ("inf", "inf"))
        # The other objectives always compute the reported policy's cost.
        self.assertEqual(truecost.solve(self.path).expected_truecost, 10)

    def test_pathlike(self):
        import pathlib

        self.assertEqual(truecost.solve(pathlib.Path(self.path)).value, 10)


@unittest.skipUnless(gymnasium, "gymnasium is not installed")
class Gymnasium(Agreement, unittest.TestCase):
    """Gymnasium environments: the API exports them in memory; the CLI reads the importer's
    file of the same environment."""

    def setUp(self):
        self.dir = tempfile.TemporaryDirectory()

    def tearDown(self):
        self.dir.cleanup()

    def exported(self, env_id, kwargs, *options):
        path = os.path.join(self.dir.name, "env.json")
        export_with_importer(env_id, kwargs, path, *options)
        return path

    def test_random_frozenlake_map(self):
        from gymnasium.envs.toy_text.frozen_lake import generate_random_map

        desc = generate_random_map(size=5, p=0.8, seed=2026)
        path = self.exported("FrozenLake-v1", {"desc": desc})
        env = gymnasium.make("FrozenLake-v1", desc=desc)
        for objective, alpha in (("truecost", None), ("reach", None), ("discounted", "0.95")):
            with self.subTest(objective=objective):
                args = ["solve", "--file", path, "--algorithm", "exact", "--objective", objective,
                        *(["--alpha", alpha] if alpha else [])]
                self.assert_solve(
                    lambda asked: truecost.solve(env, objective, alpha, with_cost=asked),
                    args, objective)
                self.assert_solve(
                    lambda asked: truecost.solve("FrozenLake-v1", objective, alpha, desc=desc,
                                                 with_cost=asked),
                    args, objective)
        api = truecost.compare(env, alphas=["0.9", "0.99"])
        cli = cli_json("compare", "--file", path, "--alphas", "0.9,0.99")
        for a, c in zip(api.rows, cli["rows"]):
            self.assert_row(a, c)
        self.assert_discount(truecost.discount(env), cli_json("discount", "--file", path))

    def test_id_with_keyword_arguments(self):
        path = self.exported("FrozenLake-v1", {"is_slippery": False})
        api = truecost.solve("FrozenLake-v1", is_slippery=False)
        cli = cli_json("solve", "--file", path, "--algorithm", "exact", "--objective", "truecost")
        self.assert_solution(api, cli)
        # Six moves from the start to the goal on the plain 4x4 map.
        self.assertEqual((api.value, api.success_probability), (6, 1))

    def test_importer_options(self):
        # Moves with one outcome as a deterministic problem file: discount reads it as
        # `discount --file` does (the failure set of a deterministic problem).
        kwargs = {"map_name": "8x8", "is_slippery": False}
        path = self.exported("FrozenLake-v1", kwargs, "--deterministic-moves")
        api = truecost.discount("FrozenLake-v1", importer={"deterministic_moves": True}, **kwargs)
        self.assertTrue(api.deterministic)
        self.assertEqual(api.failure_set_text, cli_json("discount", "--file", path)["set"])
        args = ["solve", "--file", path, "--algorithm", "exact", "--objective", "truecost"]
        solved = truecost.solve("FrozenLake-v1", importer={"deterministic_moves": True}, **kwargs)
        self.assert_solution(solved, cli_json(*args))
        # Fourteen moves from one corner of the 8x8 map to the other.
        self.assertEqual(solved.value, 14)
        with self.assertRaisesRegex(truecost.Error, "^importer options: "):
            truecost.solve("FrozenLake-v1", importer={"no_such_option": 1})

    def test_made_environment_as_in_the_guide(self):
        # docs/guide/python.md's install check: the default FrozenLake-v1 (slippery 4x4) has
        # truecost +inf at the start (the engine's own --env model says the same).
        value = truecost.solve(gymnasium.make("FrozenLake-v1")).value
        self.assertEqual(value, math.inf)
        self.assertEqual(value, truecost.solve("frozenlake").value)
        self.assertEqual(truecost.solve(gymnasium.make("FrozenLake-v1"), "reach").value,
                         truecost.solve("frozenlake", "reach").value)


if __name__ == "__main__":
    unittest.main()
