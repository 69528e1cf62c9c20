"""Shared by the test_api*.py files: the installed package, the truecost binary, and the
command line's answers as exact numbers.

The package must be the installed one (``pip install ./python``): run the tests from outside
``python/``, where the source directory ``python/truecost`` (without its native module) would
be imported instead. Without the native module the API tests are skipped, unless
``TRUECOST_REQUIRE_API=1`` (CI) makes that an error.
"""

import json
import math
import os
import subprocess
import sys
from fractions import Fraction
from cli_binary import truecost_binary

HERE = os.path.dirname(os.path.abspath(__file__))
PYTHON_DIR = os.path.dirname(HERE)
REPO = os.path.dirname(PYTHON_DIR)

try:
    import truecost
    from truecost import _native  # noqa: F401

    API_MISSING = None
except ImportError as e:
    truecost = None
    API_MISSING = f"the truecost package is not installed (pip install ./python): {e}"
    if os.environ.get("TRUECOST_REQUIRE_API") == "1":
        raise

try:
    import gymnasium
except ImportError:
    gymnasium = None


def run_cli(*args):
    binary = truecost_binary()
    if binary is None:
        raise AssertionError("no truecost binary: cargo build, or set TRUECOST_BIN")
    return subprocess.run([binary, *args], capture_output=True, text=True, timeout=600)


def cli_json(*args):
    """The command line's JSON answer (``--format json`` appended)."""
    r = run_cli(*args, "--format", "json")
    if r.returncode != 0:
        raise AssertionError(f"truecost {' '.join(args)} failed: {r.stderr}")
    return json.loads(r.stdout)


def cli_error(*args):
    """The command line's one-line error, without its ``error: `` prefix."""
    r = run_cli(*args)
    if r.returncode == 0:
        raise AssertionError(f"truecost {' '.join(args)} succeeded")
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: "), r.stderr
    return lines[0][len("error: "):]


def exact(text):
    """An exact string of the command line: ``inf`` or a rational ``p/q``."""
    return math.inf if text == "inf" else Fraction(text)


def success(value):
    """The command line's success probability: one exact string, or ``{min, max}``."""
    if isinstance(value, dict):
        return (exact(value["min"]), exact(value["max"]))
    return (exact(value), exact(value))


def polynomial_text(coefficients):
    """Integer coefficients (constant first) written as the command line writes a polynomial:
    ``4x^3 - 36x + 27``."""
    terms = []
    for power in range(len(coefficients) - 1, -1, -1):
        c = coefficients[power]
        if c == 0:
            continue
        magnitude = "" if abs(c) == 1 and power > 0 else str(abs(c))
        var = "" if power == 0 else "x" if power == 1 else f"x^{power}"
        sign = ("-" if c < 0 else "") if not terms else (" - " if c < 0 else " + ")
        terms.append(f"{sign}{magnitude}{var}")
    return "".join(terms) or "0"


def export_with_importer(env_id, kwargs, out, *options):
    """The importer's command line (``python -m truecost_gym export``) writing ``out``."""
    cmd = [sys.executable, "-m", "truecost_gym", "export", env_id, "--quiet", "--out", out,
           "--kwargs", json.dumps(kwargs), *options]
    r = subprocess.run(cmd, capture_output=True, text=True, timeout=600)
    if r.returncode != 0:
        raise AssertionError(f"export failed: {r.stderr}")
