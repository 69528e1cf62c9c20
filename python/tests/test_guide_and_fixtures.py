"""The guide's example and the committed fixtures, regenerated with Gymnasium (skipped without).

tests/data/gym_import/ holds the importer's files that tests/gym_import.rs reads without
Python; these tests write them again from Gymnasium's tables and compare byte for byte, so a
change of the importer or of Gymnasium that alters them is seen here.
"""

import os
import re
import subprocess
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
PYTHON_DIR = os.path.dirname(HERE)
REPO = os.path.dirname(PYTHON_DIR)
FIXTURES = os.path.join(REPO, "tests", "data", "gym_import")
GUIDE = os.path.join(REPO, "docs", "guide", "gymnasium.md")

try:
    import gymnasium

    GYM_VERSION = gymnasium.__version__
except ImportError:
    GYM_VERSION = None

# (fixture, Gymnasium id, keyword arguments, other options)
FIXTURE_ENVS = [
    ("frozenlake_4x4_slippery.json", "FrozenLake-v1", None),
    ("frozenlake_4x4.json", "FrozenLake-v1", '{"is_slippery": false}'),
    ("frozenlake_4x4_moves.json", "FrozenLake-v1", '{"is_slippery": false}',
     "--deterministic-moves"),
    ("cliffwalking.json", "CliffWalking-v1", None),
    ("cliffwalking_slippery.json", "CliffWalkingSlippery-v1", None),
    ("taxi.json", "Taxi-v4", None),
]


def export(env_id, out, *extra, cwd=None):
    env = dict(os.environ, PYTHONPATH=PYTHON_DIR + os.pathsep + os.environ.get("PYTHONPATH", ""))
    cmd = [sys.executable, "-m", "truecost_gym", "export", env_id, "--compact", "--quiet",
           "--out", out, *extra]
    return subprocess.run(cmd, capture_output=True, text=True, cwd=cwd, env=env)


def read(path):
    with open(path, encoding="utf-8") as f:
        return f.read()


def guide_module():
    """The Python code block that follows the guide's `<!-- mud_corridor.py` marker."""
    text = read(GUIDE)
    m = re.search(r"<!-- mud_corridor\.py.*?-->\s*```python\n(.*?)```", text, re.S)
    if m is None:
        raise AssertionError("the guide has no mud_corridor.py block")
    return m.group(1)


@unittest.skipIf(GYM_VERSION is None, "gymnasium is not installed")
class Regenerated(unittest.TestCase):
    def setUp(self):
        if GYM_VERSION != "1.4.0":
            self.skipTest(f"the fixtures come from Gymnasium 1.4.0, this is {GYM_VERSION}")

    def test_fixtures_are_what_the_importer_writes(self):
        with tempfile.TemporaryDirectory() as d:
            for name, env_id, kwargs, *options in FIXTURE_ENVS:
                with self.subTest(name=name):
                    out = os.path.join(d, name)
                    extra = (["--kwargs", kwargs] if kwargs else []) + options
                    done = export(env_id, out, *extra)
                    self.assertEqual(done.returncode, 0, done.stderr)
                    self.assertEqual(read(out), read(os.path.join(FIXTURES, name)))

    def test_the_guides_module_exports_the_committed_file(self):
        with tempfile.TemporaryDirectory() as d:
            with open(os.path.join(d, "mud_corridor.py"), "w") as f:
                f.write(guide_module())
            out = os.path.join(d, "mud.json")
            done = export("MudCorridor-v0", out, "--module", "mud_corridor", cwd=d)
            self.assertEqual(done.returncode, 0, done.stderr)
            self.assertEqual(read(out), read(os.path.join(FIXTURES, "mud_corridor.json")))
            # Gymnasium's own module:Id syntax imports the module too.
            out2 = os.path.join(d, "mud2.json")
            done = export("mud_corridor:MudCorridor-v0", out2, cwd=d)
            self.assertEqual(done.returncode, 0, done.stderr)
            self.assertEqual(read(out2).split("\n")[1:], read(out).split("\n")[1:])
            # --entry-point registers a class under any id.
            out3 = os.path.join(d, "mud3.json")
            done = export("Corridor-v7", out3, "--entry-point", "mud_corridor:MudCorridorEnv",
                          "--kwargs", '{"slip": 0.25, "length": 4}', cwd=d)
            self.assertEqual(done.returncode, 0, done.stderr)
            text = read(out3)
            self.assertIn('"name":"Corridor-v7 {\\"slip\\":0.25,\\"length\\":4}', text)
            self.assertIn('{"to":1,"p":"3/4"},{"to":0,"p":"1/4"}', text)

    def test_the_guides_environment_runs_episodes(self):
        # The table is what the importer reads; step() must follow it (the guide says so).
        namespace = {}
        exec(compile(guide_module(), "mud_corridor.py", "exec"), namespace)
        env = namespace["MudCorridorEnv"]()
        state, _ = env.reset(seed=0)
        self.assertEqual(state, 0)
        for _ in range(200):
            state, reward, terminated, truncated, _ = env.step(1)
            self.assertIn(reward, (-1.0, -3.0))
            if terminated:
                break
        self.assertTrue(terminated)
        self.assertEqual(state, 4)


if __name__ == "__main__":
    unittest.main()
