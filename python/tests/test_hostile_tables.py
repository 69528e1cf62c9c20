"""Hostile tables: wrong types, numbers near 0, environments whose own code raises, escapes in
every echoed text, files larger than truecost's readers accept."""

import contextlib
import io
import json
import os
import re
import signal
import subprocess
import sys
import tempfile
import time
import unittest
from fractions import Fraction
from unittest import mock

from truecost_gym import ImportRefused, import_table
from truecost_gym.importer import MAX_FILE_BYTES, UNSUPPORTED
from truecost_gym.rational import BINARY, recover

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from test_importer import InTemporaryDirectory, assert_one_line_error, run_cli  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
PYTHON_DIR = os.path.dirname(HERE)
REPO = os.path.dirname(PYTHON_DIR)

try:
    import gymnasium  # noqa: F401

    HAVE_GYM = True
except ImportError:
    HAVE_GYM = False


def corridor(entry):
    """Two states: from 0 both actions lead to the goal 1 through ``entry`` (a 4-tuple
    ``(p, next, reward, terminated)`` for action 0); action 1 is a plain step into the goal."""
    return {0: {0: [entry], 1: [(1.0, 1, -1.0, True)]},
            1: {0: [(1.0, 1, 0.0, True)], 1: [(1.0, 1, 0.0, True)]}}


def refusal(entry, **options):
    with unittest.TestCase().assertRaises(ImportRefused) as c:
        import_table(corridor(entry), 2, 2, 0, env_name="t", **options)
    return str(c.exception)


class Types(unittest.TestCase):
    def test_terminated_must_be_a_bool(self):
        for done in ("False", "True", 0, 1, None, 1.0):
            with self.subTest(done=done):
                msg = refusal((1.0, 1, -1.0, done))
                self.assertIn(f"P[0][0][0]: terminated {done!r} is a {type(done).__name__}, "
                              "not a bool", msg)
        p, _ = import_table(corridor((1.0, 1, -1.0, True)), 2, 2, 0)
        self.assertEqual(p["goals"], [1])

    def test_numpy_booleans_and_integers_accepted(self):
        try:
            import numpy
        except ImportError:
            self.skipTest("numpy is not installed")
        P = corridor((numpy.float64(1.0), numpy.int64(1), numpy.float32(-1.0), numpy.bool_(True)))
        p, _ = import_table(P, 2, 2, 0)
        self.assertEqual(p["actions"][0][0]["outcomes"], [{"to": 1, "p": "1"}])
        self.assertEqual(p["actions"][0][0]["reward"], "-1")
        msg = refusal((1.0, numpy.bool_(True), -1.0, True))
        self.assertIn("next state", msg)

    def test_next_state_must_be_an_int_in_range(self):
        for nxt, needle in ((1.0, "next state 1.0 is a float, not an int"),
                            (True, "next state True is a bool, not an int"),
                            ("1", "next state '1' is a str, not an int"),
                            (2, "next state 2 is not a state 0..1"),
                            (-1, "next state -1 is not a state 0..1")):
            with self.subTest(nxt=nxt):
                self.assertIn(needle, refusal((1.0, nxt, -1.0, True)))

    def test_probabilities_and_rewards_must_be_numbers(self):
        for entry, needle in (((True, 1, -1.0, True), "probability True is a bool"),
                              (("1.0", 1, -1.0, True), "probability '1.0' is a str"),
                              ((1.0, 1, "-1", True), "reward '-1' is a str"),
                              ((1.0, 1, None, True), "reward None is a NoneType"),
                              ((1.0, 1, False, True), "reward False is a bool")):
            with self.subTest(entry=entry):
                self.assertIn(needle, refusal(entry))
        # A zero-probability entry's reward is checked too.
        P = corridor((1.0, 1, -1.0, True))
        P[0][0] = [(1.0, 1, -1.0, True), (0.0, 0, "x", False)]
        with self.assertRaises(ImportRefused) as c:
            import_table(P, 2, 2, 0)
        self.assertIn("P[0][0][1]: reward 'x' is a str", str(c.exception))

    def test_named_goals_checked(self):
        P = corridor((1.0, 1, -1.0, True))
        for goals, needle in (([1, 1], "goal 1 is named twice"), ([2], "goal 2 is not a state"),
                              ([True], "goal True is not a state")):
            with self.subTest(goals=goals), self.assertRaises(ImportRefused) as c:
                import_table(P, 2, 2, 0, goals=goals)
            self.assertIn(needle, str(c.exception))
            self.assertEqual(c.exception.status, UNSUPPORTED)


class NearZero(unittest.TestCase):
    def test_a_non_zero_float_is_never_recovered_as_zero(self):
        # The smallest floats: the simplest fraction within 4 ulps is 0, which is passed over;
        # the float's exact binary value (±2^-1074) is kept.
        for x in (5e-324, -5e-324, 1e-323, -2e-323):
            with self.subTest(x=x):
                r = recover(x)
                self.assertEqual(r.value, Fraction(x))
                self.assertNotEqual(r.value, 0)
                self.assertEqual(r.how, BINARY)
        self.assertEqual(recover(-5e-324).value, -Fraction(1, 2**1074))
        self.assertEqual(recover(0.0).value, 0)
        self.assertEqual(recover(-0.0).value, 0)

    def test_the_reward_of_minus_5e_324_reaches_the_file(self):
        p, report = import_table(corridor((1.0, 1, -5e-324, True)), 2, 2, 0)
        act = p["actions"][0][0]
        # r < 0 costs -r = 2^-1074; the expected reward is the reward itself.
        self.assertEqual(Fraction(act["reward"]), -Fraction(1, 2**1074))
        self.assertEqual(Fraction(act["cost"]), Fraction(1, 2**1074))
        kept = [v for v in report["values"] if v["float"] == "-5e-324"]
        self.assertEqual([v["how"] for v in kept], [BINARY])


class Boom(Exception):
    pass


class RaisingRow:
    """A row object whose iteration raises an exception type of its own."""

    def __iter__(self):
        raise Boom("row \x1b[2J exploded")


class RaisingTable(dict):
    def __getitem__(self, s):
        raise ZeroDivisionError("table \x1b]0;title\x07 says no")


class EnvironmentCode(unittest.TestCase):
    def test_the_tables_own_exceptions_are_one_refusal(self):
        P = corridor((1.0, 1, -1.0, True))
        P[0][1] = RaisingRow()
        with self.assertRaises(ImportRefused) as c:
            import_table(P, 2, 2, 0, env_name="t")
        self.assertIn("reading P[0][1] raised Boom: row", str(c.exception))
        with self.assertRaises(ImportRefused) as c:
            import_table(RaisingTable(), 2, 2, 0, env_name="t")
        self.assertIn("reading P[0][0] raised ZeroDivisionError", str(c.exception))

    def test_a_number_type_whose_float_raises(self):
        class Odd(float):
            def __float__(self):
                raise Boom("no float")

            def __repr__(self):
                raise Boom("no repr either")

        msg = refusal((1.0, 1, Odd(-1.0), True))
        self.assertIn("reward <Odd>", msg)
        self.assertIn("Boom", msg)

    @unittest.skipUnless(HAVE_GYM, "gymnasium is not installed")
    def test_from_env_wraps_every_exception(self):
        import gymnasium as gym
        from gymnasium import spaces

        from truecost_gym import from_env

        class Raising(gym.Env):
            observation_space = spaces.Discrete(2)
            action_space = spaces.Discrete(2)

            @property
            def P(self):
                raise Boom("the P property")

        with self.assertRaises(ImportRefused) as c:
            from_env(Raising(), "raising")
        self.assertEqual(str(c.exception),
                         "raising: the environment raised Boom: the P property")


RAISING_MODULE = '''
import os
import time

import gymnasium as gym
from gymnasium import spaces


class Oops(Exception):
    pass


class Small(gym.Env):
    observation_space = spaces.Discrete(2)
    action_space = spaces.Discrete(2)
    isd = [1.0, 0.0]


class Raising(Small):
    @property
    def P(self):
        raise Oops("line one\\nline two \\x1b[31mred\\x1b[0m")


class Typed(Small):
    P = {0: {0: [(1.0, 1, -1.0, "False")], 1: [(1.0, 1, -1.0, True)]},
         1: {0: [(1.0, 1, 0.0, True)], 1: [(1.0, 1, 0.0, True)]}}


class Slow(Small):
    @property
    def P(self):
        open(os.environ["SLOW_MARKER"], "w").close()
        time.sleep(60)


gym.register("Raising-v0", entry_point=Raising)
gym.register("Typed-v0", entry_point=Typed)
gym.register("Slow-v0", entry_point=Slow)
'''


@unittest.skipUnless(HAVE_GYM, "gymnasium is not installed")
class CommandLine(InTemporaryDirectory):
    def setUp(self):
        super().setUp()
        with open(os.path.join(self.d, "raising.py"), "w") as f:
            f.write(RAISING_MODULE)

    def one_line_error(self, out, status):
        self.assertEqual(out.stdout, "")
        return assert_one_line_error(self, out, status)

    def test_a_raising_P_property_is_one_escaped_line_naming_the_exception(self):
        err = self.one_line_error(
            run_cli("export", "Raising-v0", "--module", "raising", "--out", "-", cwd=self.d), 1)
        self.assertEqual(err, "error: Raising-v0: the environment raised Oops: line one\\nline "
                         "two \\x1b[31mred\\x1b[0m\n")

    def test_a_string_terminated_is_refused(self):
        err = self.one_line_error(
            run_cli("export", "Typed-v0", "--module", "raising", "--out", "-", cwd=self.d), 1)
        self.assertIn("P[0][0][0]: terminated 'False' is a str, not a bool", err)

    def test_escapes_in_the_env_id_and_module_never_reach_the_terminal(self):
        for args in (["export", "Frozen\x1b]0;title\x07Lake-v1", "--out", "-"],
                     ["export", "FrozenLake-v1", "--module", "evil\x1b[2J\n", "--out", "-"],
                     ["export", "FrozenLake-v1", "--goals", "1,\x1b[2J", "--out", "-"]):
            with self.subTest(args=args):
                err = self.one_line_error(run_cli(*args, cwd=self.d), 2)
                self.assertIn("\\x1b", err)

    def test_a_module_that_exits_is_one_line(self):
        with open(os.path.join(self.d, "quitter.py"), "w") as f:
            f.write("import sys\nsys.exit('bye\\nnow')\n")
        err = self.one_line_error(run_cli("export", "FrozenLake-v1", "--module", "quitter",
                                          "--out", "-", cwd=self.d), 2)
        self.assertIn("--module quitter: SystemExit: bye\\nnow", err)

    def test_interrupted_is_one_line_exit_130(self):
        marker = os.path.join(self.d, "inside")
        env = dict(os.environ, PYTHONPATH=PYTHON_DIR, SLOW_MARKER=marker)
        # SIGINT restored to its default in the child (a background job starts with it
        # ignored, and Python then never raises KeyboardInterrupt).
        proc = subprocess.Popen([sys.executable, "-m", "truecost_gym", "export", "Slow-v0",
                                 "--module", "raising", "--out", "-"], cwd=self.d, env=env,
                                stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                                preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
        try:
            for _ in range(600):
                if os.path.exists(marker) or proc.poll() is not None:
                    break
                time.sleep(0.05)
            self.assertTrue(os.path.exists(marker), "the environment's P was never read")
            proc.send_signal(signal.SIGINT)
            out, err = proc.communicate(timeout=30)
        finally:
            if proc.poll() is None:
                proc.kill()
                proc.wait()
        self.assertEqual((proc.returncode, err, out), (130, "error: interrupted\n", ""))

    def test_a_closed_standard_output_is_no_traceback(self):
        # A 20x20 map: about 400 KB of text, more than a pipe holds, so the writer meets the
        # closed pipe.
        desc = ["S" + "F" * 19] + ["F" * 20] * 18 + ["F" * 19 + "G"]
        env = dict(os.environ, PYTHONPATH=PYTHON_DIR)
        proc = subprocess.Popen([sys.executable, "-m", "truecost_gym", "export", "FrozenLake-v1",
                                 "--kwargs", json.dumps({"desc": desc}), "--quiet", "--out", "-"],
                                env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
        self.assertEqual(proc.stdout.read(1), b"{")
        proc.stdout.close()
        err = proc.stderr.read().decode()
        proc.stderr.close()
        proc.wait(60)
        self.assertEqual((proc.returncode, err), (0, ""))

    def test_duplicate_goals_refused(self):
        err = self.one_line_error(run_cli("export", "FrozenLake-v1", "--goals", "15,15",
                                          "--out", "-"), 2)
        self.assertIn("state 15 listed twice", err)


class Echo(unittest.TestCase):
    def test_every_hidden_character_is_escaped(self):
        from truecost_gym.echo import one_line, printable

        for raw, shown in (("\x1b[2J", "\\x1b[2J"), ("\x9b31m", "\\x9b31m"),
                           ("\x7f", "\\x7f"), ("a\u202eb", "a\\u{202e}b"),
                           ("\u2066", "\\u{2066}"), ("\ufeff", "\\u{feff}"),
                           ("\udcff", "\\u{dcff}"), ("\r\n\t", "\\r\\n\\t"),
                           ("é ü", "é ü")):
            with self.subTest(raw=raw):
                self.assertEqual(printable(raw), shown)
        # Shortened without cutting an escape.
        line = one_line("x" * 297 + "\x1b")
        self.assertEqual(line, "x" * 297 + "…")
        self.assertEqual(one_line("x" * 296 + "\x1b"), "x" * 296 + "\\x1b")


class Size(unittest.TestCase):
    def test_the_limit_is_the_rust_readers(self):
        # MAX_FILE_BYTES mirrors the reader's constant in src/model/file.rs: read it there.
        with open(os.path.join(REPO, "src", "model", "file.rs"), encoding="utf-8") as f:
            text = f.read()
        m = re.search(r"pub const MAX_FILE_BYTES: u64 = (\d+) << (\d+);", text)
        self.assertIsNotNone(m, "MAX_FILE_BYTES not found in src/model/file.rs")
        self.assertEqual(MAX_FILE_BYTES, int(m.group(1)) << int(m.group(2)))

    @unittest.skipUnless(HAVE_GYM, "gymnasium is not installed")
    def test_a_file_over_the_limit_is_refused_unless_allowed(self):
        # FrozenLake 4x4 in the default layout: 14,005 bytes, of which the bound from the
        # table's shape sees 13,150 (its four holes are traps, counted as goals' "[]").
        from truecost_gym import __main__ as cli

        def run(limit, *options):
            err = io.StringIO()
            with mock.patch.object(cli, "MAX_FILE_BYTES", limit), \
                    contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
                try:
                    code = cli.main(["export", "FrozenLake-v1", "--quiet", "--out", out,
                                     *options])
                except SystemExit as e:
                    code = e.code
            return code, err.getvalue()

        with tempfile.TemporaryDirectory() as d:
            out = os.path.join(d, "fl.json")
            self.assertEqual(run(10 ** 9), (0, ""))
            size = os.path.getsize(out)
            os.unlink(out)
            # Under the bound: refused before the values are read, naming the bound.
            code, err = run(10_000)
            self.assertEqual(code, 1)
            m = re.search(r"^error: FrozenLake-v1: the file would take at least (\d+) bytes "
                          r"\(a lower bound from the table's shape\), more than the 10000 "
                          r"bytes truecost's readers accept: nothing written", err)
            self.assertIsNotNone(m, err)
            least = int(m.group(1))
            self.assertLess(least, size)
            self.assertEqual(os.listdir(d), [])
            # Between the bound and the size: refused once the text is laid out.
            code, err = run(least + 1)
            self.assertEqual(code, 1)
            self.assertIn(f"would take {size} bytes, more than the {least + 1} bytes", err)
            self.assertEqual(os.listdir(d), [])
            # --allow-large: one warning each time, the file written.
            for limit, said in ((10_000, f"at least {least} bytes"), (least + 1, f"{size} bytes")):
                code, err = run(limit, "--allow-large")
                self.assertEqual(code, 0, err)
                self.assertEqual(err.count("\n"), 1, err)
                self.assertTrue(err.startswith("warning: "), err)
                self.assertIn(said, err)
                self.assertEqual(os.path.getsize(out), size)
                os.unlink(out)


if __name__ == "__main__":
    unittest.main()
