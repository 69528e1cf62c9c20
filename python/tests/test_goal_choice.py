"""The importer's choice of goals: the table's greatest terminal reward, an unreachable goal
said so, and refusals where the table cannot tell success from failure."""

import json
import os
import subprocess
import sys
import unittest
from fractions import Fraction

from truecost_gym import ImportRefused, import_table

HERE = os.path.dirname(os.path.abspath(__file__))
PYTHON_DIR = os.path.dirname(HERE)
REPO = os.path.dirname(PYTHON_DIR)

sys.path.insert(0, HERE)
from test_importer import InTemporaryDirectory, run_cli, truecost_binary  # noqa: E402

try:
    import gymnasium  # noqa: F401

    HAVE_GYM = True
except ImportError:
    HAVE_GYM = False

# A walled-off goal, FrozenLake-style (rewards: +1 entering the goal, 0 otherwise):
#   0 start; 1 a hole; 2 a cell behind the hole; 3 the goal.
# From 0 both actions end in the hole or stay; only 2 (which no episode reaches) enters 3.
WALLED = {
    0: {0: [(0.5, 0, 0, False), (0.5, 1, 0, True)], 1: [(1.0, 1, 0, True)]},
    1: {0: [(1.0, 1, 0, True)], 1: [(1.0, 1, 0, True)]},
    2: {0: [(1.0, 3, 1, True)], 1: [(1.0, 1, 0, True)]},
    3: {0: [(1.0, 3, 0, True)], 1: [(1.0, 3, 0, True)]},
}


def reachable(problem):
    """The states a policy can reach from the file's initial state (every outcome of every
    action followed; goals and the file's terminal states end the walk)."""
    ended = set(problem["goals"]) | set(problem.get("terminal", []))
    start = problem["initial"]
    seen = {start} if isinstance(start, int) else {e["state"] for e in start}
    stack = list(seen)
    while stack:
        x = stack.pop()
        if x in ended:
            continue
        for act in problem["actions"][x]:
            for o in act.get("outcomes", [{"to": act.get("to")}]):
                if o["to"] not in seen:
                    seen.add(o["to"])
                    stack.append(o["to"])
    return seen


class Rule(unittest.TestCase):
    def test_an_unreachable_goal_is_kept_and_said(self):
        p, report = import_table(WALLED, 4, 2, 0, env_name="walled")
        self.assertEqual((p["goals"], p["terminal"]), ([3], [1]))
        # No policy reaches the goal: success probability 0 for every policy.
        self.assertNotIn(3, reachable(p))
        self.assertEqual(len(report["warnings"]), 1)
        w = report["warnings"][0]
        self.assertTrue(w.startswith("walled: no goal is reachable: the greatest terminal "
                                     "reward, 1, is entered only from states no episode "
                                     "reaches (first P[2][0][0]); goals [3]"), w)
        self.assertIn("[1], are traps", w)
        self.assertIn("no goal is reachable", report["goal_rule"])
        # The state behind the hole keeps its actions (no episode goes there).
        self.assertEqual(len(p["actions"][2]), 2)

    def test_a_reachable_goal_gives_no_warning(self):
        P = dict(WALLED)
        P[0] = {0: [(0.5, 2, 0, False), (0.5, 1, 0, True)], 1: [(1.0, 1, 0, True)]}
        p, report = import_table(P, 4, 2, 0)
        self.assertEqual((p["goals"], p["terminal"], report["warnings"]), ([3], [1], []))
        self.assertIn(3, reachable(p))

    def test_endings_that_cannot_be_told_apart_refused(self):
        # Two holes, no goal: every ending has reward 0, as every step does.
        P = {0: {0: [(0.5, 1, 0, True), (0.5, 2, 0, True)], 1: [(1.0, 0, 0, False)]},
             1: {0: [(1.0, 1, 0, True)], 1: [(1.0, 1, 0, True)]},
             2: {0: [(1.0, 2, 0, True)], 1: [(1.0, 2, 0, True)]}}
        with self.assertRaises(ImportRefused) as c:
            import_table(P, 3, 2, 0, env_name="holes")
        self.assertEqual(str(c.exception),
                         "holes: every ending ([1, 2]) has the same reward 0, no more than a "
                         "step's (0 at P[0][1][0]): which endings are goals and which are "
                         "failures cannot be told; name the goal states with --goals")
        # Named goals settle it.
        p, _ = import_table(P, 3, 2, 0, goals=[2])
        self.assertEqual((p["goals"], p["terminal"]), ([2], [1]))

    def test_the_step_reward_compared_is_a_running_step(self):
        # Here step 0 -> 0 pays 0 and stays; the two endings pay 5 each: a bonus, two goals.
        P = {0: {0: [(1.0, 0, 0, False)], 1: [(0.5, 1, 5, True), (0.5, 2, 5, True)]},
             1: {0: [(1.0, 1, 0, True)], 1: [(1.0, 1, 0, True)]},
             2: {0: [(1.0, 2, 0, True)], 1: [(1.0, 2, 0, True)]}}
        p, report = import_table(P, 3, 2, 0)
        self.assertEqual((p["goals"], report["traps"], report["warnings"]), ([1, 2], [], []))

    def test_a_single_ending_is_the_goal_whatever_it_pays(self):
        # CliffWalking's shape: every step -1, the one terminal state entered with -1 too.
        P = {0: {0: [(1.0, 0, -1, False)], 1: [(1.0, 1, -1, True)]},
             1: {0: [(1.0, 1, 0, True)], 1: [(1.0, 1, 0, True)]}}
        p, report = import_table(P, 2, 2, 0)
        self.assertEqual((p["goals"], report["traps"]), ([1], []))

    def test_a_goal_entered_with_different_tolls_is_a_goal(self):
        # The goal 2 is entered from the grass (-1) and from the mud (-3); the pit 3 with -10.
        P = {0: {0: [(1.0, 1, -1, False)], 1: [(1.0, 2, -1, True)]},
             1: {0: [(1.0, 2, -3, True)], 1: [(1.0, 3, -10, True)]},
             2: {0: [(1.0, 2, 0, True)], 1: [(1.0, 2, 0, True)]},
             3: {0: [(1.0, 3, 0, True)], 1: [(1.0, 3, 0, True)]}}
        p, report = import_table(P, 4, 2, 0)
        self.assertEqual((p["goals"], report["traps"], report["warnings"]), ([2], [3], []))

    def test_a_goal_the_episodes_walk_through_refused(self):
        # State 1 is entered by the episodes without termination; a state they never reach
        # (2) enters it with terminated=True and the greatest reward.
        P = {0: {0: [(1.0, 1, 0, False)]}, 1: {0: [(1.0, 3, 0, True)]},
             2: {0: [(1.0, 1, 9, True)]}, 3: {0: [(1.0, 3, 0, True)]}}
        with self.assertRaises(ImportRefused) as c:
            import_table(P, 4, 1, 0, env_name="t")
        msg = str(c.exception)
        self.assertIn("state 1 is entered with terminated=True and the greatest terminal reward "
                      "9 (P[2][0][0], from a state no episode reaches)", msg)
        self.assertIn("--goals", msg)


@unittest.skipUnless(HAVE_GYM, "gymnasium is not installed")
class FrozenLakeMaps(InTemporaryDirectory):

    def export(self, desc, *extra):
        out = os.path.join(self.d, "map.json")
        done = run_cli("export", "FrozenLake-v1", "--kwargs", json.dumps({"desc": desc}),
                       "--quiet", "--out", out, *extra)
        return done, out

    def test_walled_off_goal_as_gymnasium_says(self):
        # SHF / HFG: the start's neighbours are holes (1 and 3), the goal 5 is behind them.
        done, out = self.export(["SHF", "HFG"])
        self.assertEqual(done.returncode, 0, done.stderr)
        self.assertEqual(done.stderr.count("\n"), 1, done.stderr)
        self.assertTrue(done.stderr.startswith("warning: FrozenLake-v1: no goal is reachable"),
                        done.stderr)
        with open(out) as f:
            p = json.load(f)
        self.assertEqual((p["goals"], p["terminal"]), ([5], [1, 3]))
        self.assertNotIn(5, reachable(p))
        self.assertIn("goals [5], traps [1, 3]", done.stdout)
        binary = truecost_binary()
        if binary is None:
            return  # the file's contents are checked above; the comparison needs truecost
        with open(os.path.join(self.d, "map.txt"), "w") as f:
            f.write("SHF\nHFG\n")
        by_file = subprocess.run([binary, "compare", "--file", out, "--format", "json"],
                                 capture_output=True, text=True)
        by_env = subprocess.run([binary, "compare", "--env", "frozenlake:map=map.txt",
                                 "--format", "json"], capture_output=True, text=True, cwd=self.d)
        self.assertEqual(by_file.returncode, 0, by_file.stderr)
        self.assertEqual(by_env.returncode, 0, by_env.stderr)
        rows_file = json.loads(by_file.stdout)["rows"]
        rows_env = json.loads(by_env.stdout)["rows"]
        self.assertEqual(rows_file, rows_env)
        for row in rows_file:
            self.assertEqual(Fraction(row["success_probability"]), 0, row)

    def test_random_maps_answer_as_gymnasiums_own_semantics(self):
        # Maps with many holes, the goal often walled off: the file's goals are the map's G,
        # its traps the holes episodes reach, and `compare --file` prints `compare --env`'s
        # rows (when truecost is built).
        import random

        import gymnasium as gym

        from truecost_gym import from_env, to_json

        rng = random.Random(49)
        binary = truecost_binary()
        walled = 0
        for k in range(12):
            n = rng.choice((3, 4))
            cells = ["H" if rng.random() < 0.4 else "F" for _ in range(n * n)]
            cells[0] = "S"
            goal = rng.randrange(1, n * n)
            cells[goal] = "G"
            desc = ["".join(cells[r * n:(r + 1) * n]) for r in range(n)]
            with self.subTest(desc=desc):
                p, report = from_env(gym.make("FrozenLake-v1", desc=desc), "map")
                self.assertEqual(p["goals"], [goal])
                holes = {i for i, c in enumerate(cells) if c == "H"}
                self.assertLessEqual(set(p.get("terminal", [])), holes)
                if goal not in reachable(p):
                    walled += 1
                    self.assertEqual(len(report["warnings"]), 1)
                if binary is None:
                    continue
                path = os.path.join(self.d, f"map{k}.json")
                with open(path, "w") as f:
                    f.write(to_json(p))
                with open(os.path.join(self.d, f"map{k}.txt"), "w") as f:
                    f.write("\n".join(desc) + "\n")
                rows = []
                for source in (["--file", path], ["--env", f"frozenlake:map=map{k}.txt"]):
                    done = subprocess.run([binary, "compare", *source, "--format", "json"],
                                          capture_output=True, text=True, cwd=self.d)
                    self.assertEqual(done.returncode, 0, done.stderr)
                    rows.append(json.loads(done.stdout)["rows"])
                self.assertEqual(rows[0], rows[1])
        self.assertGreater(walled, 0, "no map walled its goal off: the seed tests nothing new")

    def test_map_without_goal_refused_and_named_goals_accepted(self):
        done, out = self.export(["SHF", "HFH"])
        self.assertEqual(done.returncode, 1, done.stderr)
        self.assertEqual(done.stderr.count("\n"), 1, done.stderr)
        self.assertIn("which endings are goals and which are failures cannot be told",
                      done.stderr)
        self.assertFalse(os.path.exists(out))
        done, out = self.export(["SHF", "HFH"], "--goals", "5")
        self.assertEqual(done.returncode, 0, done.stderr)
        with open(out) as f:
            p = json.load(f)
        self.assertEqual((p["goals"], p["terminal"]), ([5], [1, 3]))


if __name__ == "__main__":
    unittest.main()
