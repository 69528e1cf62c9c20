"""The importer on hand-written toy-text tables (no Gymnasium needed for most tests)."""

import itertools
import json
import os
import subprocess
import sys
import tempfile
import unittest
from fractions import Fraction

from truecost_gym import ImportRefused, import_table, to_json
from truecost_gym.importer import BAD_TABLE, UNSUPPORTED
from cli_binary import truecost_binary

HERE = os.path.dirname(os.path.abspath(__file__))
PYTHON_DIR = os.path.dirname(HERE)

# A toy-text table written by hand (Gymnasium's convention P[s][a] = [(p, s', r, terminated)]):
# state 0 the start, 1 a corridor, 2 the goal (+10 on entry), 3 a pit (-5 on entry).
#   state 0, action 0 (walk): to the corridor, reward -1 (listed twice, 0.5 each, as Gymnasium
#            lists outcomes of different slips that land on the same cell);
#   state 0, action 1 (jump): the goal with probability 2/3, the pit with 1/3;
#   state 1, action 0 (push): reward -2 and stay with probability 1/3, the goal with 2/3;
#   state 1, action 1 (back): to the start, reward -1.
# Initial distribution: 3/4 on the start, 1/4 in the corridor.
TWO_THIRDS, ONE_THIRD = 2 / 3, 1 / 3
TINY_P = {
    0: {0: [(0.5, 1, -1.0, False), (0.5, 1, -1.0, False)],
        1: [(TWO_THIRDS, 2, 10.0, True), (ONE_THIRD, 3, -5.0, True)]},
    1: {0: [(ONE_THIRD, 1, -2.0, False), (TWO_THIRDS, 2, 10.0, True)],
        1: [(1.0, 0, -1.0, False)]},
    2: {0: [(1.0, 2, 0.0, True)], 1: [(1.0, 2, 0.0, True)]},
    3: {0: [(1.0, 3, 0.0, True)], 1: [(1.0, 3, 0.0, True)]},
}
TINY_ISD = [0.75, 0.25, 0.0, 0.0]


def initial_distribution(problem):
    """The file's initial distribution as ``[(state, Fraction)]``: a state number is that state
    with probability 1, a list its entries."""
    initial = problem["initial"]
    if isinstance(initial, int):
        return [(initial, Fraction(1))]
    return [(e["state"], Fraction(e["p"])) for e in initial]


def optimum_by_enumeration(problem):
    """The least expected cost at the initial distribution over the stationary deterministic
    policies that reach a goal with probability 1 from every initial state (exact Gaussian
    elimination per policy): an oracle independent of the importer and of truecost's
    solvers."""
    n = problem["states"]
    goals = set(problem["goals"])
    acts = problem["actions"]
    choices = [range(len(acts[x])) if x not in goals else [None] for x in range(n)]
    best = None
    for policy in itertools.product(*choices):
        succ = {x: [(o["to"], Fraction(o["p"])) for o in acts[x][policy[x]]["outcomes"]]
                for x in range(n) if x not in goals}
        # Proper from the initial states: every state it reaches can reach a goal.
        start = initial_distribution(problem)
        reach = {x for x, _ in start}
        stack = list(reach)
        while stack:
            x = stack.pop()
            for y, _ in succ.get(x, []):
                if y not in reach:
                    reach.add(y)
                    stack.append(y)
        can = set(goals)
        changed = True
        while changed:
            changed = False
            for x, out in succ.items():
                if x not in can and any(y in can for y, _ in out):
                    can.add(x)
                    changed = True
        if not reach <= can:
            continue
        # Solve (I - P) G = c on the reached non-goal states.
        xs = sorted(reach - goals)
        idx = {x: i for i, x in enumerate(xs)}
        m = len(xs)
        a = [[Fraction(int(i == j)) for j in range(m)] + [Fraction(acts[x][policy[x]]["cost"])]
             for i, x in enumerate(xs)]
        for i, x in enumerate(xs):
            for y, p in succ[x]:
                if y in idx:
                    a[i][idx[y]] -= p
        g = expectation(solved(a), idx, start)
        if best is None or g < best:
            best = g
    return best


def solved(a):
    """The unknowns of the augmented system ``a`` (``m`` rows of ``m + 1`` Fractions), by exact
    Gauss-Jordan elimination."""
    m = len(a)
    for c in range(m):
        r = next(r for r in range(c, m) if a[r][c] != 0)
        a[c], a[r] = a[r], a[c]
        for r in range(m):
            if r != c and a[r][c] != 0:
                f = a[r][c] / a[c][c]
                a[r] = [u - f * v for u, v in zip(a[r], a[c])]
    return [a[i][m] / a[i][i] for i in range(m)]


def expectation(values, idx, distribution):
    """The expectation over ``distribution`` ((state, probability) pairs) of ``values`` (by the
    positions ``idx``; 0 at a state without one)."""
    return sum((p * values[idx[x]] if x in idx else Fraction(0) for x, p in distribution),
               Fraction(0))


def optimum_by_enumeration_moves(problem):
    """``optimum_by_enumeration`` on a file whose moves ``{to, cost}`` are read as one outcome."""
    as_outcomes = dict(problem)
    as_outcomes["actions"] = [
        [a if "outcomes" in a else {"cost": a["cost"], "outcomes": [{"to": a["to"], "p": "1"}]}
         for a in row]
        for row in problem["actions"]
    ]
    return optimum_by_enumeration(as_outcomes)


def discounted_by_enumeration(problem, alpha):
    """The greatest discounted value of the file's rewards at the initial distribution over the
    stationary deterministic policies (exact Gaussian elimination of V = r + alpha P V per
    policy; goals and ``terminal`` states have value 0): an oracle independent of truecost."""
    n = problem["states"]
    ended = set(problem["goals"]) | set(problem.get("terminal", []))
    acts = problem["actions"]
    choices = [range(len(acts[x])) if x not in ended else [None] for x in range(n)]
    xs = [x for x in range(n) if x not in ended]
    idx = {x: i for i, x in enumerate(xs)}
    best = None
    for policy in itertools.product(*choices):
        m = len(xs)
        a = [[Fraction(int(i == j)) for j in range(m)] + [Fraction(acts[x][policy[x]]["reward"])]
             for i, x in enumerate(xs)]
        for i, x in enumerate(xs):
            act = acts[x][policy[x]]
            outcomes = act["outcomes"] if "outcomes" in act else [{"to": act["to"], "p": "1"}]
            for o in outcomes:
                if o["to"] in idx:
                    a[i][idx[o["to"]]] -= alpha * Fraction(o["p"])
        v = expectation(solved(a), idx, initial_distribution(problem))
        if best is None or v > best:
            best = v
    return best


class TinyTable(unittest.TestCase):
    def setUp(self):
        self.problem, self.report = import_table(TINY_P, 4, 2, TINY_ISD, env_name="tiny")

    def test_file_contents_by_hand(self):
        p = self.problem
        # The initial distribution, 3/4 on the start and 1/4 in the corridor, as a list.
        self.assertEqual((p["format"], p["states"], p["goals"]), ("truecost-stochastic/1", 4, [2]))
        self.assertEqual(p["initial"], [{"state": 0, "p": "3/4"}, {"state": 1, "p": "1/4"}])
        self.assertEqual(self.report["initial_distribution"], {"support": 2})
        self.assertEqual(self.report["traps"], [3])
        acts = p["actions"]
        # Walk: the two entries to the corridor merged; reward -1 costs 1.
        self.assertEqual(acts[0][0], {"cost": "1", "reward": "-1",
                                      "outcomes": [{"to": 1, "p": "1"}]})
        # Jump: 2/3 * 1 (a positive reward costs one step) + 1/3 * 5 = 7/3; its expected
        # reward 2/3 * 10 + 1/3 * (-5) = 5.
        self.assertEqual(acts[0][1], {"cost": "7/3", "reward": "5",
                                      "outcomes": [{"to": 2, "p": "2/3"}, {"to": 3, "p": "1/3"}]})
        # Push: 1/3 * 2 + 2/3 * 1 = 4/3; reward 1/3 * (-2) + 2/3 * 10 = 6.
        self.assertEqual((acts[1][0]["cost"], acts[1][0]["reward"]), ("4/3", "6"))
        self.assertEqual(acts[1][1]["reward"], "-1")
        self.assertEqual(acts[2], [], "the goal terminates")
        self.assertEqual(acts[3], [{"cost": "0", "reward": "0",
                                    "outcomes": [{"to": 3, "p": "1"}]}], "a trap")
        self.assertEqual(p["terminal"], [3], "the trap ends the episode")
        self.assertEqual(len(acts), 4, "no state beyond the table's")
        self.assertEqual(list(p), ["format", "name", "states", "initial", "goals", "terminal",
                                   "actions"], "the key order of truecost export")
        self.assertEqual(self.report["merged_outcomes"], 1)
        self.assertEqual(self.report["rewards"], "gymnasium")

    def test_rewards_costs_writes_no_reward(self):
        p, report = import_table(TINY_P, 4, 2, TINY_ISD, env_name="tiny", rewards="costs")
        self.assertFalse(any("reward" in a for row in p["actions"] for a in row))
        # Everything else is the default's file without its rewards.
        stripped = [[{k: v for k, v in a.items() if k != "reward"} for a in row]
                    for row in self.problem["actions"]]
        self.assertEqual(p["actions"], stripped)
        self.assertEqual(p["terminal"], [3])
        self.assertEqual(p["name"], "tiny (truecost stage costs)")
        self.assertEqual(self.problem["name"], "tiny (truecost stage costs, Gymnasium's rewards)")
        self.assertEqual(report["rewards"], "costs")
        with self.assertRaises(ValueError):
            import_table(TINY_P, 4, 2, TINY_ISD, rewards="negated")

    def test_discounted_value_known_by_hand(self):
        # At alpha = 1/2, with the expected rewards above (the goal and the trap end the
        # episode: value 0). Corridor: push gives V(1) = 6 + (1/2)(1/3) V(1), so V(1) = 36/5
        # (back: -1 + V(0)/2 is less). Start: jump 5, walk -1 + V(1)/2 = 13/5: V(0) = 5. At the
        # initial distribution (3/4 on the start, 1/4 in the corridor): 3/4 * 5 + 1/4 * 36/5 =
        # 111/20.
        alpha = Fraction(1, 2)
        self.assertEqual(discounted_by_enumeration(self.problem, alpha), Fraction(111, 20))
        v = json.loads(self.solve_with_binary("--objective", "discounted", "--alpha", "1/2",
                                              "--format", "json").stdout)
        self.assertEqual(v["discounted_value_initial"], "111/20")
        self.assertEqual(v["values"], ["5", "36/5", "0", "0"])
        self.assertEqual(v["rewards"], "the file's rewards")

    def test_optimum_known_by_hand(self):
        # Corridor: G(1) = 4/3 + G(1)/3, so G(1) = 2; start: walk 1 + G(1) = 3 (the jump may
        # fall into the pit: not proper). From the initial distribution 3/4 * 3 + 1/4 * 2.
        self.assertEqual(optimum_by_enumeration(self.problem), Fraction(11, 4))
        out = self.solve_with_binary("--objective", "truecost", "--format", "json")
        self.assertEqual(json.loads(out.stdout)["cost_to_go_initial"], "11/4")
        # The solvers of one initial state x1 refuse the distribution, in one line.
        out = self.solve_with_binary(check=False)
        self.assertEqual(out.returncode, 1)
        self.assertEqual(out.stderr.count("\n"), 1, out.stderr)
        self.assertIn("draws its initial state from 2 states", out.stderr)

    def solve_with_binary(self, *args, check=True):
        """`truecost solve --file F --algorithm exact ARGS` on the tiny problem written to a
        temporary file (the test is skipped without a built binary)."""
        binary = truecost_binary()
        if binary is None:
            self.skipTest("no truecost binary built")
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "tiny.json")
            with open(path, "w") as f:
                f.write(to_json(self.problem))
            return subprocess.run([binary, "solve", "--file", path, "--algorithm", "exact",
                                   *args], capture_output=True, text=True, check=check)

    def test_initial_state_chosen_or_single(self):
        # initial=STATE writes that state, and so does a distribution of one state.
        for initial in (1, [0.0, 1.0, 0.0, 0.0]):
            with self.subTest(initial=initial):
                p, report = import_table(TINY_P, 4, 2, initial)
                self.assertEqual((p["states"], p["initial"]), (4, 1))
                self.assertIsNone(report["initial_distribution"])
        # From the corridor alone: G(1) = 2 (by hand above).
        self.assertEqual(optimum_by_enumeration(p), Fraction(2))
        # The states of probability 0 are left out, the others listed in increasing order (a
        # goal may be one of them).
        p, _ = import_table(TINY_P, 4, 2, [0.0, 0.5, 0.0, 0.5], goals=[2, 3])
        self.assertEqual(p["initial"], [{"state": 1, "p": "1/2"}, {"state": 3, "p": "1/2"}])

    def test_every_recovered_value_is_reported(self):
        by_float = {(v["kind"], v["float"]): v for v in self.report["values"]}
        self.assertEqual(by_float[("probability", repr(TWO_THIRDS))]["value"], "2/3")
        self.assertEqual(by_float[("probability", repr(ONE_THIRD))]["value"], "1/3")
        self.assertEqual(by_float[("initial probability", "0.75")]["how"], "exact")
        self.assertEqual(by_float[("reward", "-5.0")]["value"], "-5")

    def test_compact_and_pretty_texts_hold_the_same_problem(self):

        self.assertEqual(json.loads(to_json(self.problem, compact=True)), self.problem)
        self.assertEqual(json.loads(to_json(self.problem)), self.problem)

    def test_single_outcomes_as_moves(self):
        p, report = import_table(TINY_P, 4, 2, TINY_ISD, deterministic_moves=True)
        acts = p["actions"]
        self.assertEqual(acts[0][0], {"to": 1, "cost": "1", "reward": "-1"},
                         "merged to one outcome: a move")
        self.assertIn("outcomes", acts[0][1], "the jump stays stochastic")
        self.assertEqual(acts[1][1], {"to": 0, "cost": "1", "reward": "-1"})
        self.assertEqual(acts[3], [{"to": 3, "cost": "0", "reward": "0"}], "the trap's self-loop")
        costs, _ = import_table(TINY_P, 4, 2, TINY_ISD, deterministic_moves=True, rewards="costs")
        self.assertEqual(costs["actions"][3], [{"to": 3, "cost": "0"}])
        self.assertTrue(report["deterministic_moves"])
        self.assertEqual(optimum_by_enumeration_moves(p), Fraction(11, 4))

    def test_goals_may_be_named(self):
        p, report = import_table(TINY_P, 4, 2, TINY_ISD, goals=[2, 3])
        self.assertEqual((p["goals"], report["traps"]), ([2, 3], []))


class Refusals(unittest.TestCase):
    def test_row_summing_to_one_minus_1e9_refused(self):
        P = {s: dict(r) for s, r in TINY_P.items()}
        P[1][0] = [(0.5, 1, -2.0, False), (0.5 - 1e-9, 2, 10.0, True)]
        with self.assertRaises(ImportRefused) as c:
            import_table(P, 4, 2, TINY_ISD, env_name="tiny")
        msg = str(c.exception)
        self.assertIn("state 1, action 0", msg)
        self.assertIn("not exactly 1", msg)
        self.assertIn("1 - 1e-09", msg)
        self.assertEqual(c.exception.status, BAD_TABLE)
        self.assertNotIn("\n", msg)

    def test_exact_binary_refuses_gymnasiums_thirds(self):
        P = {s: dict(r) for s, r in TINY_P.items()}
        third = (1 - 1 / 3) / 2  # FrozenLake's 0.33333333333333337
        P[1][0] = [(third, 1, -2.0, False), (1 / 3, 0, -2.0, False), (third, 2, 10.0, True)]
        p, _ = import_table(P, 4, 2, TINY_ISD)
        self.assertEqual([o["p"] for o in p["actions"][1][0]["outcomes"]], ["1/3"] * 3)
        with self.assertRaises(ImportRefused) as c:
            import_table(P, 4, 2, TINY_ISD, exact_binary=True)
        # The floats 2/3 and 1/3 of the jump already sum to 1 - 2^-54 in exact binary.
        self.assertIn("state 0, action 1", str(c.exception))
        self.assertIn("(1 - 5.55e-17) in exact binary", str(c.exception))
        P[0][1] = [(0.5, 2, 10.0, True), (0.5, 3, -5.0, True)]
        with self.assertRaises(ImportRefused) as c:
            import_table(P, 4, 2, TINY_ISD, exact_binary=True)
        self.assertIn("state 1, action 0", str(c.exception))
        self.assertIn("(1 + 5.55e-17) in exact binary", str(c.exception))

    def test_state_entered_with_and_without_termination_refused(self):
        P = {s: dict(r) for s, r in TINY_P.items()}
        P[1][1] = [(1.0, 3, -1.0, False)]  # walks into the pit without ending the episode
        with self.assertRaises(ImportRefused) as c:
            import_table(P, 4, 2, TINY_ISD)
        self.assertIn("state 3 is entered with terminated=True", str(c.exception))

    def test_no_goal_refused(self):
        P = {s: {a: [(1.0, s, -1.0, False)] for a in (0, 1)} for s in range(2)}
        with self.assertRaises(ImportRefused) as c:
            import_table(P, 2, 2, [1.0, 0.0])
        self.assertIn("--goals", str(c.exception))

    def test_initial_distribution_required_and_checked(self):
        with self.assertRaises(ImportRefused):
            import_table(TINY_P, 4, 2, None)
        with self.assertRaises(ImportRefused) as c:
            import_table(TINY_P, 4, 2, [0.5, 0.25, 0.0, 0.0])
        self.assertIn("initial distribution sums to 3/4", str(c.exception))
        p, _ = import_table(TINY_P, 4, 2, 1)
        self.assertEqual((p["states"], p["initial"]), (4, 1))

    def test_bad_entries_refused(self):
        for entries, needle in [([(1.0, 7, -1.0, False)], "next state 7"),
                                ([(1.5, 0, -1.0, False)], "not in [0, 1]"),
                                ([(1.0, 0, float("nan"), False)], "not a finite number"),
                                ([(1.0, 0)], "not (probability, next_state, reward, terminated)"),
                                ([], "state 0, action 0: no outcome of positive probability"),
                                ([(0.0, 1, -1.0, False)], "no outcome of positive probability")]:
            P = {s: dict(r) for s, r in TINY_P.items()}
            P[0][0] = entries
            with self.subTest(needle=needle), self.assertRaises(ImportRefused) as c:
                import_table(P, 4, 2, TINY_ISD)
            self.assertIn(needle, str(c.exception))


class Doctests(unittest.TestCase):
    def test_importer_doctests(self):
        import doctest

        from truecost_gym import importer

        failures, tried = doctest.testmod(importer)
        self.assertEqual(failures, 0)
        self.assertGreater(tried, 0)

    def test_echo_doctests(self):
        import doctest

        from truecost_gym import echo

        failures, tried = doctest.testmod(echo)
        self.assertEqual(failures, 0)
        self.assertGreater(tried, 0)


try:
    import gymnasium  # noqa: F401

    HAVE_GYM = True
except ImportError:
    HAVE_GYM = False


def run_cli(*args, cwd=None, stdout=subprocess.PIPE):
    """``python -m truecost_gym ARGS`` with this checkout's module, its output as text."""
    env = dict(os.environ, PYTHONPATH=PYTHON_DIR + os.pathsep + os.environ.get("PYTHONPATH", ""))
    return subprocess.run([sys.executable, "-m", "truecost_gym", *args], stdout=stdout,
                          stderr=subprocess.PIPE, text=True, cwd=cwd, env=env)


def assert_one_line_error(case, out, status):
    """``out`` (a finished run) failed with ``status`` and one escaped ``error:`` line, no
    traceback and no raw escape character; returns that line."""
    case.assertEqual(out.returncode, status, out.stderr)
    case.assertEqual(out.stderr.count("\n"), 1, out.stderr)
    case.assertTrue(out.stderr.startswith("error: "), out.stderr)
    case.assertNotIn("Traceback", out.stderr)
    case.assertNotIn("\x1b", out.stderr)
    case.assertNotIn("\x07", out.stderr)
    return out.stderr


class InTemporaryDirectory(unittest.TestCase):
    """A test case with a fresh temporary directory ``self.d``."""

    def setUp(self):
        self.dir = tempfile.TemporaryDirectory()
        self.d = self.dir.name

    def tearDown(self):
        self.dir.cleanup()


BOX_MODULE = '''
import gymnasium as gym
import numpy as np
from gymnasium import spaces


class Continuous(gym.Env):
    def __init__(self):
        self.observation_space = spaces.Box(low=0.0, high=1.0, shape=(2,), dtype=np.float64)
        self.action_space = spaces.Discrete(2)
        self.P = {}


gym.register("BoxWorld-v0", entry_point=Continuous)
'''


@unittest.skipUnless(HAVE_GYM, "gymnasium is not installed")
class WithGymnasium(unittest.TestCase):
    def test_box_space_refused_in_one_line_exit_2(self):
        with tempfile.TemporaryDirectory() as d:
            with open(os.path.join(d, "boxworld.py"), "w") as f:
                f.write(BOX_MODULE)
            out = run_cli("export", "BoxWorld-v0", "--module", "boxworld", "--out",
                          os.path.join(d, "x.json"), cwd=d)
            self.assertEqual(out.returncode, UNSUPPORTED, out.stderr)
            self.assertEqual(len(out.stderr.strip().splitlines()), 1, out.stderr)
            self.assertTrue(out.stderr.startswith("error: BoxWorld-v0: the observation space is Box"))
            self.assertIn("not Discrete", out.stderr)
            self.assertFalse(os.path.exists(os.path.join(d, "x.json")))

    def test_environment_object_without_registration(self):
        import gymnasium as gym
        from gymnasium import spaces

        from truecost_gym import from_env

        class Tiny(gym.Env):
            observation_space = spaces.Discrete(4)
            action_space = spaces.Discrete(2)
            P = TINY_P
            isd = TINY_ISD

        p, _ = from_env(Tiny(), "tiny")
        self.assertEqual(p["actions"][0][1]["cost"], "7/3")
        self.assertEqual(optimum_by_enumeration(p), Fraction(11, 4))

    def test_usage_errors_are_one_line_exit_2(self):
        for args in (["export", "FrozenLake-v1"], ["export", "NoSuchEnv-v0", "--out", "-"],
                     ["export", "FrozenLake-v1", "--kwargs", "[1]", "--out", "-"],
                     ["export", "FrozenLake-v1", "--max-denominator", "0", "--out", "-"],
                     ["export", "FrozenLake-v1", "--rewards", "negated", "--out", "-"]):
            with self.subTest(args=args):
                out = run_cli(*args)
                self.assertEqual(out.returncode, 2, out.stderr)
                self.assertEqual(len(out.stderr.strip().splitlines()), 1, out.stderr)
                self.assertTrue(out.stderr.startswith("error: "), out.stderr)
                self.assertEqual(out.stdout, "")

    def test_rewards_option(self):
        default = run_cli("export", "FrozenLake-v1", "--quiet", "--out", "-")
        costs = run_cli("export", "FrozenLake-v1", "--quiet", "--rewards", "costs", "--out", "-")
        for out in (default, costs):
            self.assertEqual(out.returncode, 0, out.stderr)
        g, c = json.loads(default.stdout), json.loads(costs.stdout)
        # FrozenLake: +1 on entering the goal only. From state 14, RIGHT slips to 10 (up),
        # 15 (right) or 14 (down), a third each: expected reward 1/3. The holes end the episode.
        self.assertEqual(g["actions"][14][2]["reward"], "1/3")
        self.assertEqual(g["actions"][0][0]["reward"], "0")
        self.assertEqual((g["terminal"], c["terminal"]), ([5, 7, 11, 12], [5, 7, 11, 12]))
        self.assertIn("Gymnasium's rewards", g["name"])
        self.assertNotIn("reward", costs.stdout)
        self.assertEqual(
            c["actions"],
            [[{k: v for k, v in a.items() if k != "reward"} for a in row] for row in g["actions"]])

    def test_exact_binary_refuses_slippery_frozenlake_naming_the_row(self):
        out = run_cli("export", "FrozenLake-v1", "--exact-binary", "--out", "-")
        self.assertEqual(out.returncode, BAD_TABLE)
        self.assertIn("state 0, action 0: the probabilities sum to", out.stderr)
        self.assertIn("(1 + 5.55e-17) in exact binary", out.stderr)


if __name__ == "__main__":
    unittest.main()
