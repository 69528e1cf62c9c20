"""Command line: ``python3 -m truecost_gym export ENV_ID [options] --out FILE.json``.

Every refusal is one line on stderr (``error: ...``, escaped by :mod:`truecost_gym.echo`):
exit status 2 for usage errors, outputs that cannot be written (:mod:`truecost_gym.output`)
and environments truecost cannot import (non-Discrete spaces, no transition table), 1 for a
table that is malformed, inconsistent after recovery (a probability row not summing to 1, a
state entered both with and without termination) or ambiguous about its goals, for an
environment whose own code raises, and for a file larger than truecost's readers accept
(unless ``--allow-large``); 130 when interrupted. Python's warnings (Gymnasium's, the
environment's) are one escaped ``warning:`` line each.
"""

import argparse
import importlib
import json
import os
import sys
import warnings

from . import output
from .echo import one_line, printable
from .importer import (
    BAD_TABLE,
    MAX_FILE_BYTES,
    REWARDS,
    UNSUPPORTED,
    ImportRefused,
    name_note,
    to_json,
)
from .rational import BINARY, DEFAULT_MAX_DENOMINATOR, DEFAULT_ULPS, EXACT

SHOWN = 20  # recovered values listed on stderr (all of them are in --report)


def fail(message, status):
    """Exits with ``status`` after one escaped line ``error: message`` on stderr."""
    print(f"error: {one_line(message)}", file=sys.stderr)
    sys.exit(status)


def warn(message):
    """One escaped line ``warning: message`` on stderr."""
    print(f"warning: {one_line(message, 1000)}", file=sys.stderr)


def _show_warning(message, category, filename, lineno, file=None, line=None):
    """A Python warning (Gymnasium's, the environment's) as one escaped ``warning:`` line."""
    warn(f"{category.__name__}: {message}")


class Parser(argparse.ArgumentParser):
    def error(self, message):
        fail(f"{message} (try --help)", 2)


def _states(text):
    try:
        out = [int(t) for t in text.split(",") if t.strip()]
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected comma-separated states, got {text!r}")
    if not out:
        raise argparse.ArgumentTypeError("expected at least one state")
    twice = sorted({x for x in out if out.count(x) > 1})
    if twice:
        raise argparse.ArgumentTypeError(
            f"state{'s' if len(twice) > 1 else ''} {', '.join(map(str, twice))} listed twice")
    return out


def _positive(text):
    try:
        v = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a positive integer, got {text!r}")
    if v < 1:
        raise argparse.ArgumentTypeError(f"expected a positive integer, got {text!r}")
    return v


def _non_negative(text):
    try:
        v = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected an integer >= 0, got {text!r}")
    if v < 0:
        raise argparse.ArgumentTypeError(f"expected an integer >= 0, got {text!r}")
    return v


def parser():
    p = Parser(prog="python3 -m truecost_gym",
               description="A discrete Gymnasium environment as a truecost problem file.")
    sub = p.add_subparsers(dest="command", required=True, parser_class=Parser)
    e = sub.add_parser(
        "export",
        help="write ENV_ID's transition table as a truecost-stochastic/1 file",
        description="Write the environment's transition table env.unwrapped.P as a "
        "truecost-stochastic/1 problem file with exact probabilities, truecost stage costs "
        "(reward r < 0 costs -r, r >= 0 costs 1) and Gymnasium's expected rewards, for truecost "
        "solve|compare|discount --file.",
    )
    e.add_argument("env_id", metavar="ENV_ID",
                   help="a registered id (FrozenLake-v1), or module:Id (Gymnasium imports the module)")
    e.add_argument("--kwargs", metavar="JSON", default="{}",
                   help="keyword arguments of gymnasium.make, as a JSON object")
    e.add_argument("--module", metavar="MODULE", action="append", default=[],
                   help="import MODULE first (it registers the environment); repeatable")
    e.add_argument("--entry-point", metavar="MODULE:CLASS",
                   help="register ENV_ID with this entry point first (a class that is not "
                   "registered anywhere)")
    e.add_argument("--out", metavar="FILE.json", required=True,
                   help="the problem file to write ('-': standard output; a pipe or a terminal "
                   "is written directly, a regular file replaced whole, anything else refused)")
    e.add_argument("--report", metavar="FILE.json",
                   help="also write every recovered value and every choice made, as JSON")
    e.add_argument("--max-denominator", metavar="N", type=_positive,
                   default=DEFAULT_MAX_DENOMINATOR,
                   help=f"largest denominator of a recovered fraction (default {DEFAULT_MAX_DENOMINATOR})")
    e.add_argument("--ulps", metavar="K", type=_non_negative, default=DEFAULT_ULPS,
                   help="when no fraction rounds to the float, accept the simplest one within K "
                   f"units in the last place (default {DEFAULT_ULPS}; 0: rounding interval only)")
    e.add_argument("--exact-binary", action="store_true",
                   help="keep every float's exact binary value (no recovery)")
    e.add_argument("--goals", metavar="S,S,...", type=_states,
                   help="the goal states (default: the terminal states entered with the greatest "
                   "terminal reward)")
    e.add_argument("--initial", metavar="STATE", type=_non_negative,
                   help="the initial state (default: the environment's initial_state_distrib "
                   "or isd, written as the file's initial distribution when it has two or more "
                   "states)")
    e.add_argument("--deterministic-moves", action="store_true",
                   help="write an action with a single outcome as a move {to, cost}: a table "
                   "without randomness becomes a deterministic problem file (for verify --claim "
                   "C4, learn, solve --algorithm dijkstra)")
    e.add_argument("--rewards", choices=REWARDS, default="gymnasium",
                   help="gymnasium (default): write every action's expected Gymnasium reward, "
                   "which truecost's discounted objective maximises (discount|compare --file "
                   "then answer as --env); costs: write no reward (the discounted objective "
                   "rewards the negated stage costs)")
    e.add_argument("--compact", action="store_true",
                   help="one state's actions per line (default: the layout of truecost export)")
    e.add_argument("--allow-large", action="store_true",
                   help=f"write a file larger than {MAX_FILE_BYTES} bytes (32 MiB), the most "
                   "truecost's readers accept (default: refused before writing)")
    e.add_argument("--quiet", action="store_true",
                   help="do not list the recovered values on stderr")
    return p


def _import_module(name):
    try:
        importlib.import_module(name)
    except KeyboardInterrupt:
        raise
    except BaseException as e:  # the user's module, sys.exit included: one line
        fail(f"--module {name}: {type(e).__name__}: {e}", 2)


def export(args):
    try:
        kwargs = json.loads(args.kwargs)
    except json.JSONDecodeError as e:
        fail(f"--kwargs: not JSON: {e}", 2)
    if not isinstance(kwargs, dict):
        fail("--kwargs: expected a JSON object", 2)
    try:
        targets = output.check_all([("--out", args.out), ("--report", args.report)])
    except output.OutputRefused as e:
        fail(str(e), e.status)
    if "" not in sys.path and os.getcwd() not in sys.path:
        sys.path.insert(0, os.getcwd())
    for name in args.module:
        _import_module(name)
    try:
        import gymnasium
    except ImportError:
        fail("gymnasium is not installed (pip install gymnasium)", 2)
    if args.entry_point:
        if ":" not in args.entry_point:
            fail(f"--entry-point {args.entry_point}: expected MODULE:CLASS", 2)
        try:
            gymnasium.register(id=args.env_id, entry_point=args.entry_point)
        except KeyboardInterrupt:
            raise
        except BaseException as e:
            fail(f"--entry-point {args.entry_point}: {type(e).__name__}: {e}", 2)
    try:
        env = gymnasium.make(args.env_id, **kwargs)
    except KeyboardInterrupt:
        raise
    except BaseException as e:  # unknown ids, bad keyword arguments, the user's constructor
        fail(f"cannot make {args.env_id}: {type(e).__name__}: {e}", 2)
    from .environment import from_env

    warned = []

    def large(message):
        warned.append(message)
        warn(message)

    try:
        problem, report = from_env(env, args.env_id, initial=args.initial,
                                   max_denominator=args.max_denominator, ulps=args.ulps,
                                   exact_binary=args.exact_binary, goals=args.goals,
                                   deterministic_moves=args.deterministic_moves,
                                   rewards=args.rewards, max_file_bytes=MAX_FILE_BYTES,
                                   compact=args.compact,
                                   large=large if args.allow_large else None)
    except ImportRefused as e:
        fail(str(e), e.status)
    options = "" if not kwargs else " " + json.dumps(kwargs, separators=(",", ":"))
    name = f"{args.env_id}{options} (Gymnasium {gymnasium.__version__}; " \
        f"{name_note(args.rewards)})"
    problem["name"] = name
    report["gymnasium_version"] = gymnasium.__version__
    report["env_id"] = args.env_id
    report["kwargs"] = kwargs
    text = to_json(problem, compact=args.compact)
    size = len(text.encode("utf-8"))
    if size > MAX_FILE_BYTES:
        message = (f"{printable(args.out)} would take {size} bytes, more than the "
                   f"{MAX_FILE_BYTES} bytes (32 MiB) truecost's readers accept")
        if not args.allow_large:
            fail(f"{message}: nothing written ({report['states']} states, "
                 f"{report['actions']} actions; --compact, if not given, makes it smaller; "
                 "--allow-large writes it anyway)", 1)
        if not warned:
            warn(f"{message}; written as --allow-large asks")
    texts = [text]
    if args.report:
        texts.append(json.dumps(report, indent=2) + "\n")
    for line in report["warnings"]:
        warn(line)
    summary = output.all_beside_stdout(targets)  # before the files are replaced
    try:
        output.write_all(list(zip(targets, texts)))
    except output.OutputRefused as e:
        fail(str(e), e.status)
    if not args.quiet:
        listed = [v for v in report["values"] if v["how"] != EXACT]
        for v in listed[:SHOWN]:
            what = "kept" if v["how"] == BINARY else "recovered"
            print(one_line(f"{what} {v['kind']} {v['float']} = {v['value']} ({v['how']}; "
                           f"{v['entries']} entries, first {v['first']})", 1000),
                  file=sys.stderr)
        if len(listed) > SHOWN:
            print(f"... and {len(listed) - SHOWN} more recovered values (--report lists them)",
                  file=sys.stderr)
    binary = len(report["binary"])
    note = f"; {binary} values kept in exact binary" if binary and not args.exact_binary else ""
    if args.out != "-":
        # On stdout unless an output goes there (a pipe, /dev/stdout) or to a terminal.
        print(one_line(f"wrote {args.out} ({report['states']} states, {report['actions']} "
                       f"actions; goals {_short(report['goals'])}, traps "
                       f"{_short(report['traps'])}{note})", 1000),
              file=sys.stdout if summary else sys.stderr)
    return 0


def _short(states, limit=8):
    if len(states) <= limit:
        return "[" + ", ".join(map(str, states)) + "]"
    return "[" + ", ".join(map(str, states[:limit])) + f", ... {len(states)} in all]"


def main(argv=None):
    """The command line (module docs); returns the exit status. An interruption (Ctrl-C) is one
    line too, exit status 130."""
    try:
        with warnings.catch_warnings():
            warnings.showwarning = _show_warning
            args = parser().parse_args(argv)
            if args.command == "export":
                return export(args)
            return BAD_TABLE
    except KeyboardInterrupt:
        fail("interrupted", 130)
    except BrokenPipeError:
        # Standard output's reader left (``| head``): what it read is what it wanted.
        output.silence_stdout()
        return 0


if __name__ == "__main__":
    sys.exit(main())


__all__ = ["main", "parser", "UNSUPPORTED"]
