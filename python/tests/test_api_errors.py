"""Refusals raise truecost.Error (a ValueError) with the command line's one-line message;
exactness of the inputs (floats refused); the GIL is released during an analysis and Ctrl-C
interrupts it; the package's other parts (truecost.gym, the truecost-gym command, the
version)."""

import json
import os
import re
import shutil
import signal
import subprocess
import sys
import sysconfig
import tempfile
import textwrap
import threading
import time
import unittest
from fractions import Fraction

from test_api_support import API_MISSING, REPO, cli_error, gymnasium, truecost


def setUpModule():
    if API_MISSING:
        raise unittest.SkipTest(API_MISSING)


class CommandLineMessages(unittest.TestCase):
    """The same input refused by the API and by the CLI: the same message."""

    def assert_same(self, call, *cli_args):
        with self.assertRaises(truecost.Error) as raised:
            call()
        self.assertIsInstance(raised.exception, ValueError)
        self.assertEqual(str(raised.exception), cli_error(*cli_args))

    def test_unknown_env_spec(self):
        self.assert_same(lambda: truecost.solve("frozenlake:map=9x9"),
                         "solve", "--env", "frozenlake:map=9x9", "--algorithm", "exact")

    def test_missing_file(self):
        path = os.path.join(tempfile.gettempdir(), "truecost-no-such-file.json")
        self.assert_same(lambda: truecost.solve(path), "solve", "--file", path,
                         "--algorithm", "exact", "--objective", "truecost")
        self.assert_same(lambda: truecost.discount(path), "discount", "--file", path)

    def test_objectives_and_alphas(self):
        solve = ["solve", "--env", "frozenlake", "--algorithm", "exact"]
        self.assert_same(lambda: truecost.solve("frozenlake", "discounted"),
                         *solve, "--objective", "discounted")
        self.assert_same(lambda: truecost.solve("frozenlake", "discounted", alpha=1),
                         *solve, "--objective", "discounted", "--alpha", "1")
        self.assert_same(lambda: truecost.solve("frozenlake", "reach", alpha="0.9"),
                         *solve, "--objective", "reach", "--alpha", "0.9")
        self.assert_same(lambda: truecost.solve("frozenlake", with_cost=True),
                         *solve, "--objective", "truecost", "--with-cost")
        self.assert_same(lambda: truecost.solve("frozenlake", "discounted", "0.9", with_cost=True),
                         *solve, "--objective", "discounted", "--alpha", "0.9", "--with-cost")
        self.assert_same(lambda: truecost.compare("frozenlake", alphas=["0.9", "1/0"]),
                         "compare", "--env", "frozenlake", "--alphas", "0.9,1/0")

    def test_malformed_file(self):
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "bad.json")
            with open(path, "w") as f:
                json.dump({"initial": 0, "goals": [7], "actions": [[]]}, f)
            self.assert_same(lambda: truecost.solve(path), "solve", "--file", path,
                             "--algorithm", "exact", "--objective", "truecost")


class Inputs(unittest.TestCase):
    def test_float_alpha_refused(self):
        with self.assertRaises(truecost.Error) as raised:
            truecost.solve("frozenlake", "discounted", alpha=0.9)
        self.assertIn("float", str(raised.exception))
        self.assertIn(str(Fraction(0.9)), str(raised.exception))

    def test_exact_alpha_forms_agree(self):
        values = {truecost.solve("frozenlake", "discounted", alpha=a).value
                  for a in ("0.9", "9/10", Fraction(9, 10))}
        self.assertEqual(len(values), 1)

    def test_keyword_arguments_need_a_gymnasium_id(self):
        with self.assertRaisesRegex(truecost.Error, "Gymnasium id"):
            truecost.solve("frozenlake", map_name="8x8")

    def test_not_an_environment(self):
        with self.assertRaisesRegex(truecost.Error, "got int"):
            truecost.solve(42)

    @unittest.skipUnless(gymnasium, "gymnasium is not installed")
    def test_gymnasium_refusals(self):
        with self.assertRaisesRegex(truecost.Error, "^cannot make NoSuchEnv-v0: "):
            truecost.solve("NoSuchEnv-v0")
        # Not toy-text: no transition table (the importer's refusal).
        with self.assertRaisesRegex(truecost.Error, "CartPole-v1"):
            truecost.solve("CartPole-v1")

    def test_non_finite_numbers_name_the_parameter(self):
        from decimal import Decimal

        for bad in (float("nan"), float("inf"), float("-inf"), Decimal("NaN"),
                    Decimal("Infinity"), Decimal("sNaN")):
            with self.assertRaises(truecost.Error) as raised:
                truecost.solve("frozenlake", "discounted", alpha=bad)
            self.assertRegex(str(raised.exception), r"^alpha = .* is not a finite number$")
            with self.assertRaisesRegex(truecost.Error, "^alpha = .* is not a finite number$"):
                truecost.compare("frozenlake", alphas=["0.9", bad])

    def test_a_tiny_float_is_shown_short(self):
        with self.assertRaises(truecost.Error) as raised:
            truecost.solve("frozenlake", "discounted", alpha=1e-320)
        message = str(raised.exception)
        self.assertTrue(message.startswith("alpha = 1e-320 is a float"), message)
        self.assertLess(len(message), 200, message)
        # The exact value shortened, its length said: 1e-320 is n / 2^1074 with 327 characters.
        self.assertIn(f"({len(str(Fraction(1e-320)))} characters)", message)

    def test_a_huge_decimal_exponent_reaches_the_engine_unexpanded(self):
        from decimal import Decimal

        start = time.monotonic()
        with self.assertRaisesRegex(truecost.Error, "exponent outside the supported range"):
            truecost.solve("frozenlake", "discounted", alpha=Decimal("1e-999999999"))
        self.assertLess(time.monotonic() - start, 5)

    def test_importer_options_are_a_dict(self):
        for bad in ([1], "goals", 3):
            with self.assertRaisesRegex(truecost.Error, "^importer must be a dict of "):
                truecost.solve("frozenlake", importer=bad)

    def test_compare_alphas_are_distinct_and_few(self):
        for alphas, first, second in ((["0.9", "9/10"], 1, 2),
                                      (["0.5", Fraction(99, 100), "990e-3"], 2, 3)):
            with self.assertRaisesRegex(
                truecost.Error,
                rf"^alpha .* is listed twice \(as discount factor {first} and {second}\)$",
            ):
                truecost.compare("frozenlake", alphas=alphas)
        # The same refusal as the command line for the same list.
        with self.assertRaises(truecost.Error) as raised:
            truecost.compare("frozenlake", alphas=["0.9", "0.95", "9/10"])
        self.assertEqual(str(raised.exception),
                         cli_error("compare", "--env", "frozenlake", "--alphas", "0.9,0.95,9/10"))
        many = [Fraction(i, 100) for i in range(1, 66)]
        with self.assertRaisesRegex(truecost.Error, "^alphas lists 65 discount factors, more "
                                    "than the 64 compare takes$"):
            truecost.compare("frozenlake", alphas=many)
        # Out of range twice: the engine's range refusal, as on the command line.
        with self.assertRaisesRegex(truecost.Error, "alpha"):
            truecost.compare("frozenlake", alphas=["2", "2"])


class Threads(unittest.TestCase):
    def test_gil_released_during_an_analysis(self):
        ticks = []
        done = threading.Event()

        def analyse():
            try:
                truecost.discount("frozenlake:map=8x8")
            finally:
                done.set()

        worker = threading.Thread(target=analyse)
        start = time.monotonic()
        worker.start()
        while not done.is_set():
            ticks.append(time.monotonic())
            time.sleep(0.01)
        worker.join()
        elapsed = time.monotonic() - start
        # Python ran throughout: about one tick per 10 ms of the analysis.
        self.assertGreater(elapsed, 0.2, "the analysis was too quick to observe")
        self.assertGreater(len(ticks), elapsed / 0.01 / 4)

    @unittest.skipIf(sys.platform == "win32", "SIGINT to a child process")
    def test_ctrl_c_interrupts(self):
        script = textwrap.dedent("""
            import sys, time, truecost
            print("start", flush=True)
            t = time.monotonic()
            try:
                truecost.discount("frozenlake:map=8x8")
                print("finished", time.monotonic() - t, flush=True)
            except KeyboardInterrupt:
                print("interrupted", time.monotonic() - t, flush=True)
        """)
        # SIGINT restored to its default in the child, so that Python turns it into
        # KeyboardInterrupt even where the test runs with SIGINT ignored (a background job).
        child = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE,
                                 text=True, cwd=tempfile.gettempdir(),
                                 preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
        self.assertEqual(child.stdout.readline().strip(), "start")
        time.sleep(0.3)
        sent = time.monotonic()
        child.send_signal(signal.SIGINT)
        out, _ = child.communicate(timeout=120)
        answered = time.monotonic() - sent
        self.assertTrue(out.startswith("interrupted"), out)
        # The interrupt is seen within a poll (50 ms), plus the child's start-up and exit.
        self.assertLess(answered, 2.0)


class Package(unittest.TestCase):
    def test_gym_reexports_the_importer(self):
        import truecost.gym
        import truecost_gym

        self.assertIs(truecost.gym.from_env, truecost_gym.from_env)
        self.assertIs(truecost.gym.to_json, truecost_gym.to_json)
        self.assertEqual(set(truecost.gym.__all__), set(truecost_gym.__all__))

    def test_console_command(self):
        command = shutil.which("truecost-gym", path=sysconfig.get_path("scripts"))
        self.assertIsNotNone(command, "truecost-gym is not installed")
        r = subprocess.run([command, "export", "--help"], capture_output=True, text=True)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("--out", r.stdout)

    def test_version_is_the_crates(self):
        with open(os.path.join(REPO, "Cargo.toml"), encoding="utf-8") as f:
            version = re.search(r'^\[package\][^\[]*?^version = "([^"]+)"', f.read(), re.M | re.S)
        self.assertEqual(truecost.__version__, version.group(1))


if __name__ == "__main__":
    unittest.main()
