"""The importer's size check before the table's values are read (truecost_gym.size): a lower
bound of the file's bytes, never above the file written, close to it on toy-text tables, and a
large table refused by it at once, in little memory, without a value recovered."""

import os
import random
import sys
import time
import tracemalloc
import unittest
from unittest import mock

from truecost_gym import ImportRefused, import_table, to_json
from truecost_gym.importer import _shape
from truecost_gym.size import Layout, least_file_bytes

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from test_importer import InTemporaryDirectory, assert_one_line_error, run_cli  # noqa: E402

try:
    import gymnasium

    HAVE_GYM = True
except ImportError:
    HAVE_GYM = False

ROWS = ([1.0], [0.5, 0.5], [1 / 3] * 3, [0.25, 0.75], [0.1, 0.9], [0.0, 1.0], [0.2] * 5)
REWARDS = (-100.0, -1.0, -3.5, 0.0, 1.0, 20.0, 0.1, -1e-7)


def random_table(rng):
    n = rng.randint(1, 9)
    n_actions = rng.randint(1, 3)
    P = {}
    for s in range(n):
        P[s] = {}
        for a in range(n_actions):
            probs = rng.choice(ROWS)
            P[s][a] = [(p, rng.randrange(n), rng.choice(REWARDS), rng.random() < 0.3)
                       for p in probs]
    return P, n, n_actions


def least(P, n, n_actions, compact, moves, rewards, goals=()):
    layout = Layout(to_json, compact, moves, rewards == "gymnasium")
    return least_file_bytes(_shape(P, n, n_actions, "t"), n, layout, goals)


class Bound(unittest.TestCase):
    def test_never_above_the_file_written(self):
        rng = random.Random(49)
        checked = 0
        for _ in range(1500):
            P, n, n_actions = random_table(rng)
            options = dict(compact=rng.random() < 0.5, deterministic_moves=rng.random() < 0.5,
                           rewards=rng.choice(("gymnasium", "costs")))
            goals = sorted(rng.sample(range(n), rng.randint(1, n))) if rng.random() < 0.3 \
                else None
            start = rng.randrange(n)
            compact = options.pop("compact")
            try:
                problem, _ = import_table(P, n, n_actions, start, goals=goals, **options)
            except ImportRefused:
                continue
            size = len(to_json(problem, compact=compact).encode("utf-8"))
            bound = least(P, n, n_actions, compact, options["deterministic_moves"],
                          options["rewards"], goals or ())
            self.assertLessEqual(bound, size, (P, options, compact, goals))
            # The check itself: the file's own size passes, one byte less than the bound
            # is refused before the values are read.
            import_table(P, n, n_actions, start, goals=goals, max_file_bytes=size,
                         compact=compact, **options)
            with self.assertRaises(ImportRefused) as c:
                import_table(P, n, n_actions, start, goals=goals, max_file_bytes=bound - 1,
                             compact=compact, **options)
            self.assertIn(f"take at least {bound} bytes", str(c.exception))
            checked += 1
        self.assertGreater(checked, 250)

    def test_exact_but_for_the_head_on_the_least_values(self):
        # A corridor of 200 states, every cost "1", every reward "0" but the goal's entry
        # ("1"), every probability 1: the bound misses only the head's keys beyond "format"
        # (name, states, initial, goals; under 250 bytes), in every layout.
        n = 200
        P = {s: {0: [(1.0, s + 1, float(s + 1 == n - 1), s + 1 == n - 1)],
                 1: [(1.0, s, 0.0, False)]} for s in range(n - 1)}
        P[n - 1] = {0: [(1.0, n - 1, 0.0, True)], 1: [(1.0, n - 1, 0.0, True)]}
        for compact in (False, True):
            for moves in (False, True):
                for rewards in ("gymnasium", "costs"):
                    problem, _ = import_table(P, n, 2, 0, deterministic_moves=moves,
                                              rewards=rewards)
                    size = len(to_json(problem, compact=compact).encode("utf-8"))
                    bound = least(P, n, 2, compact, moves, rewards)
                    self.assertLessEqual(bound, size)
                    self.assertLess(size - bound, 250, (compact, moves, rewards))

    @unittest.skipUnless(HAVE_GYM, "gymnasium is not installed")
    def test_close_to_the_file_on_frozen_lake(self):
        # Within 7% on FrozenLake 8x8 (its traps, one action each, are counted as goals).
        for compact in (False, True):
            env = gymnasium.make("FrozenLake-v1", map_name="8x8").unwrapped
            problem, _ = import_table(env.P, 64, 4, list(env.initial_state_distrib))
            size = len(to_json(problem, compact=compact).encode("utf-8"))
            bound = least(env.P, 64, 4, compact, False, "gymnasium")
            self.assertLessEqual(bound, size)
            self.assertGreater(bound, 0.93 * size, (bound, size, compact))


def slippery_grid(side):
    """A FrozenLake-like table without holes: ``side * side`` states, 4 actions of 3
    outcomes (1/3 each), the last state the goal."""
    n = side * side
    goal = n - 1

    def moved(s, d):
        r, c = divmod(s, side)
        r, c = ((r, max(c - 1, 0)), (min(r + 1, side - 1), c), (r, min(c + 1, side - 1)),
                (max(r - 1, 0), c))[d]
        return r * side + c

    P = {}
    for s in range(n):
        P[s] = {}
        for a in range(4):
            if s == goal:
                P[s][a] = [(1.0, s, 0.0, True)]
                continue
            P[s][a] = [(1 / 3, t, float(t == goal), t == goal)
                       for t in (moved(s, (a - 1) % 4), moved(s, a), moved(s, (a + 1) % 4))]
    return P, n


class LargeTable(unittest.TestCase):
    def test_refused_before_a_value_is_recovered(self):
        P, n = slippery_grid(190)  # 36,100 states: about 41 MB in the default layout
        with mock.patch("truecost_gym.importer.recover",
                        side_effect=AssertionError("a value was recovered")):
            start = time.process_time()
            with self.assertRaises(ImportRefused) as c:
                import_table(P, n, 4, 0, max_file_bytes=32 << 20)
            spent = time.process_time() - start
        self.assertRegex(str(c.exception), r"the file would take at least \d+ bytes .*more "
                         r"than the 33554432 bytes truecost's readers accept: nothing written")
        least_bytes = int(str(c.exception).split("at least ")[1].split()[0])
        self.assertGreater(least_bytes, 38_000_000)
        self.assertLess(spent, 10, spent)  # 0.35 s measured (a minute to recover and lay out)

    def test_in_one_number_and_one_byte_per_state(self):
        P, n = slippery_grid(100)  # 10,000 states, 11 MB laid out
        tracemalloc.start()
        with self.assertRaises(ImportRefused) as c:
            import_table(P, n, 4, 0, max_file_bytes=5_000_000)
        _, peak = tracemalloc.get_traced_memory()
        tracemalloc.stop()
        self.assertIn("would take at least", str(c.exception))
        self.assertLess(peak, 9 * n + 200_000, peak)  # 0.19 MB measured, for an 11 MB file

    def test_compact_counted_in_its_own_layout(self):
        # 120x120 (14,400 states): about 16 MB laid out, 6 MB with --compact.
        P, n = slippery_grid(120)
        with self.assertRaises(ImportRefused):
            import_table(P, n, 4, 0, max_file_bytes=10_000_000)
        with mock.patch("truecost_gym.importer.recover",
                        side_effect=AssertionError("a value was recovered")):
            with self.assertRaises(ImportRefused) as c:  # the compact bound passes
                import_table(P, n, 4, 0, max_file_bytes=10_000_000, compact=True)
        self.assertIn("a value was recovered", str(c.exception))

    def test_too_many_states_for_the_layout(self):
        class Untouchable:
            def __getitem__(self, s):
                raise AssertionError("the table was read")

        # A goal is "[]" and its separator ",\n" (8 bytes laid out, 4 compact) and the least
        # head ('{\n  "format": "truecost-stochastic/1",\n  "actions": [\n    []\n  ]\n}\n',
        # 67 bytes; '{"format":"truecost-stochastic/1","actions":[\n[]\n]}\n', 52 bytes,
        # counted by hand): the most states the check lets
        # through have their table read, one more is refused before.
        limit = 32 << 20
        for compact, per_state, head in ((False, 8, 67), (True, 4, 52)):
            most = (limit - head) // per_state + 1
            with self.assertRaises(ImportRefused) as c:
                import_table(Untouchable(), most + 1, 4, 0, max_file_bytes=limit,
                             compact=compact)
            self.assertIn(f"{most + 1} states take at least {head + most * per_state} bytes",
                          str(c.exception))
            with self.assertRaises(ImportRefused) as c:
                import_table(Untouchable(), most, 4, 0, max_file_bytes=limit, compact=compact)
            self.assertIn("raised AssertionError: the table was read", str(c.exception))
            p, _ = import_table({s: {0: [(1.0, s, 0.0, True)]} for s in range(50)}, 50, 1, 0,
                                goals=list(range(50)))
            self.assertEqual(len(to_json(dict(p, name="", goals=[]), compact=compact)),
                             len(to_json({"format": p["format"], "name": "", "states": 50,
                                          "initial": 0, "goals": [], "actions": [[]]},
                                         compact=compact)) + 49 * per_state)


BIG_MODULE = '''
import gymnasium as gym
from gymnasium import spaces


class Big(gym.Env):
    def __init__(self, n=36100):
        self.observation_space = spaces.Discrete(n)
        self.action_space = spaces.Discrete(4)
        self.P = {s: {a: [(0.25, (s + k) % n, -1.0, False) for k in range(1, 5)]
                      for a in range(4)} for s in range(n)}
        self.initial_state_distrib = [1.0] + [0.0] * (n - 1)


gym.register("Big-v0", entry_point=Big)
'''


@unittest.skipUnless(HAVE_GYM, "gymnasium is not installed")
class CommandLine(InTemporaryDirectory):
    def test_a_large_table_refused_at_once(self):
        with open(os.path.join(self.d, "big_env.py"), "w") as f:
            f.write(BIG_MODULE)
        start = time.monotonic()
        out = run_cli("export", "Big-v0", "--module", "big_env", "--out", "big.json",
                      cwd=self.d)
        spent = time.monotonic() - start
        line = assert_one_line_error(self, out, 1)
        self.assertRegex(line, r"^error: Big-v0: the file would take at least \d+ bytes \(a "
                         r"lower bound from the table's shape\), more than the 33554432 bytes")
        self.assertEqual([x for x in os.listdir(self.d) if x not in ("big_env.py", "__pycache__")],
                         [])
        # Recovering and laying out 577,600 entries takes a minute; the bound, a second
        # (plus the interpreter, Gymnasium and the table's construction).
        self.assertLess(spent, 30, spent)


if __name__ == "__main__":
    unittest.main()
