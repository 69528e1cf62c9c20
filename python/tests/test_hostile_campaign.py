"""Regressions of a hostile campaign against the importer: an environment whose code raises
``SystemExit`` or a ``BaseException`` of its own (not an ``Exception``) is one refusal naming
it, never a traceback, never the environment's exit status and text; a warning of Gymnasium or
of the environment (Gymnasium colours its own with raw escape sequences) is one escaped line."""

import os
import sys
import unittest

from truecost_gym import ImportRefused, import_table

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from test_importer import InTemporaryDirectory, assert_one_line_error, run_cli  # noqa: E402

try:
    import gymnasium  # noqa: F401

    HAVE_GYM = True
except ImportError:
    HAVE_GYM = False


class Abort(BaseException):
    pass


class Table:
    """A table whose every row raises ``error``."""

    def __init__(self, error):
        self.error = error

    def __getitem__(self, s):
        raise self.error


class NotAnException(unittest.TestCase):
    def test_import_table_refuses_what_the_table_raises(self):
        for error, name in ((SystemExit("x\ny"), "SystemExit"), (Abort("gone"), "Abort"),
                            (GeneratorExit(), "GeneratorExit")):
            with self.subTest(name=name):
                with self.assertRaises(ImportRefused) as c:
                    import_table(Table(error), 2, 2, 0, env_name="t")
                self.assertIn(f"reading P[0][0] raised {name}", str(c.exception))
                # The size check reads the table first: the same refusal.
                with self.assertRaises(ImportRefused) as c:
                    import_table(Table(error), 2, 2, 0, env_name="t", max_file_bytes=1 << 20)
                self.assertIn(f"reading P[0][0] raised {name}", str(c.exception))

    def test_an_interruption_still_interrupts(self):
        with self.assertRaises(KeyboardInterrupt):
            import_table(Table(KeyboardInterrupt()), 2, 2, 0, env_name="t")


EXITING_MODULE = '''
import gymnasium as gym
from gymnasium import spaces


class Abort(BaseException):
    pass


class Small(gym.Env):
    observation_space = spaces.Discrete(2)
    action_space = spaces.Discrete(2)
    isd = [1.0, 0.0]


class ExitingTable(Small):
    @property
    def P(self):
        raise SystemExit("bye\\n\\x1b[31mred")


class AbortingTable(Small):
    @property
    def P(self):
        raise Abort("gone")


class ExitingConstructor(Small):
    def __init__(self):
        raise SystemExit(7)


class Warning(Small):
    P = {0: {0: [(1.0, 1, -1.0, True)], 1: [(1.0, 1, -1.0, True)]},
         1: {0: [(1.0, 1, 0.0, True)], 1: [(1.0, 1, 0.0, True)]}}

    def __init__(self):
        import warnings
        warnings.warn("two\\nlines \\x1b[31mred\\x1b[0m")


gym.register("Warning-v0", entry_point=Warning)
gym.register("ExitingTable-v0", entry_point=ExitingTable)
gym.register("AbortingTable-v0", entry_point=AbortingTable)
gym.register("ExitingConstructor-v0", entry_point=ExitingConstructor)
'''


@unittest.skipUnless(HAVE_GYM, "gymnasium is not installed")
class CommandLine(InTemporaryDirectory):
    def test_one_line_naming_the_exception(self):
        with open(os.path.join(self.d, "exiting.py"), "w") as f:
            f.write(EXITING_MODULE)
        for env_id, status, expected in (
                ("ExitingTable-v0", 1,
                 "error: ExitingTable-v0: the environment raised SystemExit: bye\\n\\x1b[31mred\n"),
                ("AbortingTable-v0", 1,
                 "error: AbortingTable-v0: the environment raised Abort: gone\n"),
                ("ExitingConstructor-v0", 2,
                 "error: cannot make ExitingConstructor-v0: SystemExit: 7\n")):
            with self.subTest(env_id=env_id):
                out = run_cli("export", env_id, "--module", "exiting", "--out", "o.json",
                              cwd=self.d)
                self.assertEqual(assert_one_line_error(self, out, status), expected)
                self.assertFalse(os.path.exists(os.path.join(self.d, "o.json")))

    def test_warnings_are_one_escaped_line_each(self):
        with open(os.path.join(self.d, "exiting.py"), "w") as f:
            f.write(EXITING_MODULE)
        out = run_cli("export", "Warning-v0", "--module", "exiting", "--out", "o.json",
                      cwd=self.d)
        self.assertEqual(out.returncode, 0, out.stderr)
        self.assertIn("warning: UserWarning: two\\nlines \\x1b[31mred\\x1b[0m\n", out.stderr)
        self.assertNotIn("\x1b", out.stderr)
        for line in out.stderr.splitlines():
            self.assertTrue(line.startswith(("warning: ", "recovered ")), line)
        # Gymnasium's own, coloured with raw escapes: an id it deprecates.
        out = run_cli("export", "Taxi-v3", "--out", "t.json", cwd=self.d)
        self.assertNotIn("\x1b", out.stderr)
        self.assertTrue(all(line.startswith(("warning: ", "error: "))
                            for line in out.stderr.splitlines()), out.stderr)


if __name__ == "__main__":
    unittest.main()
