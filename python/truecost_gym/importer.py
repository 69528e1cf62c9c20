"""A discrete Gymnasium environment's transition table as a truecost stochastic problem file.

The input is the toy-text convention: ``env.unwrapped.P[s][a]`` is a list of
``(probability, next_state, reward, terminated)`` for every state ``s`` of a ``Discrete``
observation space and every action ``a`` of a ``Discrete`` action space, and
``env.unwrapped.initial_state_distrib`` (or ``isd``) the initial distribution. The output is the
``truecost-stochastic/1`` JSON that ``truecost solve|compare|discount --file`` read, built the
way ``truecost export --env`` builds the built-in environments:

* **terminal states** are the states entered by a transition with ``terminated=True`` from a
  state where the episode runs (reachable from the initial distribution without ending the
  episode); a state entered both with and without termination is refused. States no episode
  reaches keep Gymnasium's actions (Taxi's 96 states "passenger delivered, taxi elsewhere").
  The **goals** are the states entered with the greatest reward of any terminated transition
  of the table (FrozenLake's goal +1 against the holes' 0, CliffWalking's single terminal
  state, Taxi's deliveries +20), reachable or not; the other terminal states are **traps**
  (the episode ends in failure). An unreachable goal is kept and reported, and a table that
  cannot tell success from failure is refused (:mod:`truecost_gym.goals`). ``goals=``
  overrides the choice. A goal has no action (termination, cost 0); a trap a single zero-cost
  self-loop, so that no policy entering it reaches a goal.
* **stage costs** (the paper's truecost, docs/spec.md §1 and §3): an outcome with reward ``r < 0``
  costs ``-r`` (the environment's own penalty: CliffWalking's -1 per step and -100 per fall,
  Taxi's -10 for an illegal action); an outcome with ``r >= 0`` costs 1, one step (FrozenLake's
  0 and +1, Taxi's +20 delivery, whose reward is a terminal bonus, not a cost). An action costs
  the expectation over its outcomes: the file's cost is paid whatever the outcome, and equal
  expectations give equal expected totals.
* **rewards** (``rewards="gymnasium"``, the default): every action's ``reward`` is its
  expected Gymnasium reward ``Σ p·r`` over its outcomes, exactly (the reward the discounted
  objective maximises, as ``truecost discount|compare --env`` use it); a trap's self-loop has
  reward 0. The file's ``terminal`` lists the traps, so that the episode ends there as in
  Gymnasium. ``rewards="costs"`` writes no reward: the discounted objective then rewards the
  negated stage costs.
* **outcomes**: zero-probability entries are dropped, entries to the same next state merged
  (probabilities added, first appearance order), as ``truecost export --env`` does.
* **initial state**: a single state of probability 1 is the file's ``initial`` (a state
  number); a distribution over two or more states is the file's ``initial`` list
  ``[{"state": x, "p": "q"}, ...]`` of the states of positive probability, in increasing order
  (Taxi's 300 states, 1/300 each), over which ``truecost solve --objective``, ``compare`` and
  ``discount --file`` take expectations, as ``--env`` does. ``initial=STATE`` chooses one
  state instead.

Every float is recovered as an exact fraction by :mod:`truecost_gym.rational`; a probability row
that does not sum to exactly 1 after recovery is refused, naming the state and action. Entries
are type-checked: probabilities and rewards real numbers (not bools, not text), next states
``int`` in range, ``terminated`` a ``bool``; any exception the table's own code raises is one
refusal naming the exception's type.
"""

import json
import numbers
import re
from decimal import Decimal
from fractions import Fraction

from .goals import choose_goals, terminal_states
from .rational import (
    BINARY,
    DEFAULT_MAX_DENOMINATOR,
    DEFAULT_ULPS,
    float_text,
    recover,
)
from .refusal import BAD_TABLE, UNSUPPORTED, ImportRefused  # noqa: F401 (re-exported)
from .size import Layout, least_file_bytes, refuse_or_warn

FORMAT = "truecost-stochastic/1"

#: The values of ``rewards``: Gymnasium's expected rewards, or none (negated stage costs).
REWARDS = ("gymnasium", "costs")

#: The largest problem file truecost's readers accept, in bytes (32 MiB, the Rust constant
#: ``truecost::model::file::MAX_FILE_BYTES``): a larger file is refused by every command.
MAX_FILE_BYTES = 32 << 20


def _space_size(space, what, env_name):
    name = type(space).__name__
    n = getattr(space, "n", None)
    if name != "Discrete" or n is None:
        raise ImportRefused(
            f"{env_name}: the {what} space is {space!r}, not Discrete: truecost imports finite "
            "environments with a transition table (env.unwrapped.P) only",
            UNSUPPORTED,
        )
    start = int(getattr(space, "start", 0))
    if start != 0:
        raise ImportRefused(
            f"{env_name}: the {what} space {space!r} starts at {start}; the transition table "
            "convention numbers states and actions from 0",
            UNSUPPORTED,
        )
    return int(n)


class _Values:
    """Recovers floats and records each distinct one (kind, text) once for the report."""

    def __init__(self, env_name, max_denominator, ulps, exact_binary):
        self.env_name = env_name
        self.max_denominator = max_denominator
        self.ulps = ulps
        self.exact_binary = exact_binary
        self.seen = {}

    def get(self, kind, x, where):
        if not _is_number(x):
            raise _not_a_number(self.env_name, where, kind, x)
        try:
            key = (kind, type(x).__name__ if isinstance(x, Decimal) else "", float_text(x))
        except Exception as e:  # a number type of the environment's own
            raise ImportRefused(f"{self.env_name}: {where}: {kind} {_shown(x)}: "
                                f"{type(e).__name__}: {e}") from None
        entry = self.seen.get(key)
        if entry is None:
            try:
                r = recover(x, self.max_denominator, self.ulps, self.exact_binary)
            except Exception as e:
                raise ImportRefused(f"{self.env_name}: {where}: {kind} {_shown(x)}: "
                                    f"{e}") from None
            entry = {"kind": kind, "float": r.text, "value": str(r.value), "how": r.how,
                     "entries": 0, "first": where, "_exact": r.value}
            self.seen[key] = entry
        entry["entries"] += 1
        return entry["_exact"]

    def report(self):
        return [{k: v for k, v in e.items() if not k.startswith("_")}
                for e in self.seen.values()]


def _shown(x, limit=60):
    """``repr(x)``, shortened, or the type's name if the environment's ``__repr__`` fails."""
    try:
        text = repr(x)
    except Exception:
        return f"<{type(x).__name__}>"
    return text if len(text) <= limit else text[: limit - 1] + "…"


def _not_a_number(env_name, where, kind, x):
    return ImportRefused(f"{env_name}: {where}: {kind} {_shown(x)} is a {type(x).__name__}, "
                         "not a number")


def _is_number(x):
    """A real number that is not a bool: ``int``, ``float``, ``Fraction``, ``Decimal``, NumPy's
    integers and floats."""
    if isinstance(x, bool) or getattr(getattr(x, "dtype", None), "kind", "") == "b":
        return False
    return isinstance(x, (numbers.Real, Decimal))


def _is_bool(x):
    """``True``/``False`` or a NumPy boolean (not the strings "True"/"False", nor 0 and 1)."""
    return isinstance(x, bool) or (getattr(getattr(x, "dtype", None), "kind", "") == "b"
                                   and getattr(x, "shape", None) == ())


def _entries(P, s, a, env_name):
    """``P[s][a]`` as a list of 4-tuples; any exception the environment's table raises is one
    refusal naming its type."""
    try:
        row = list(P[s][a])
    except (KeyError, IndexError):
        raise ImportRefused(f"{env_name}: P[{s}][{a}] is missing from the transition table") from None
    except KeyboardInterrupt:
        raise
    except BaseException as e:  # the environment's own code: one line, naming the exception
        raise ImportRefused(f"{env_name}: reading P[{s}][{a}] raised {type(e).__name__}: {e}") from None
    out = []
    for i, t in enumerate(row):
        if not isinstance(t, (tuple, list)) or len(t) != 4:
            raise ImportRefused(
                f"{env_name}: P[{s}][{a}][{i}] is {_shown(t)}, not (probability, next_state, "
                "reward, terminated)"
            )
        out.append(tuple(t))
    return out


def _move(nxt, done, n_states, env_name, where):
    """An entry's next state and ``terminated`` flag, type-checked: ``(int, bool)``."""
    if not isinstance(nxt, numbers.Integral) or isinstance(nxt, bool):
        raise ImportRefused(f"{env_name}: {where}: next state {_shown(nxt)} is a "
                            f"{type(nxt).__name__}, not an int")
    if not 0 <= nxt < n_states:
        raise ImportRefused(
            f"{env_name}: {where}: next state {int(nxt)} is not a state 0..{n_states - 1}"
        )
    if not _is_bool(done):
        raise ImportRefused(f"{env_name}: {where}: terminated {_shown(done)} is a "
                            f"{type(done).__name__}, not a bool")
    return int(nxt), bool(done)


def _shape(P, n_states, n_actions, env_name):
    """Every action's ``(s, [(probability, next_state, terminated)])``, type-checked as pass 1
    of :func:`import_table` checks them, for :func:`~truecost_gym.size.least_file_bytes`."""
    for s in range(n_states):
        for a in range(n_actions):
            entries = []
            for i, (p, nxt, _, done) in enumerate(_entries(P, s, a, env_name)):
                if type(p) is not float and not _is_number(p):
                    raise _not_a_number(env_name, f"P[{s}][{a}][{i}]", "probability", p)
                if type(nxt) is not int or type(done) is not bool or not 0 <= nxt < n_states:
                    nxt, done = _move(nxt, done, n_states, env_name, f"P[{s}][{a}][{i}]")
                entries.append((p, nxt, done))
            yield s, entries


def _off_one(total):
    """``total`` exactly, and how far from 1 (a float's repr would print 1.0 for 1 + 2^-54)."""
    diff = total - 1
    sign = "+" if diff > 0 else "-"
    text = str(total)
    if len(text) > 60:
        text = text[:28] + "…" + text[-28:]
    return f"{text} (1 {sign} {float(abs(diff)):.3g})"


def truecost_cost(reward):
    """The paper's stage cost of one outcome (module docs): ``-r`` for ``r < 0``, else 1.

    >>> truecost_cost(Fraction(-100)), truecost_cost(Fraction(20)), truecost_cost(Fraction(0))
    (Fraction(100, 1), Fraction(1, 1), Fraction(1, 1))
    """
    return -reward if reward < 0 else Fraction(1)


def import_table(P, n_states, n_actions, initial, *, env_name="environment",
                 max_denominator=DEFAULT_MAX_DENOMINATOR, ulps=DEFAULT_ULPS,
                 exact_binary=False, goals=None, deterministic_moves=False,
                 rewards="gymnasium", max_file_bytes=None, compact=False, large=None):
    """Builds the problem from a transition table (module docs).

    ``P[s][a]``: lists of ``(p, s', r, terminated)``; ``initial``: a sequence of ``n_states``
    probabilities (written as the file's initial distribution when two or more are positive),
    or one state (an ``int``); ``goals``: the goal states, overriding the rule of the module
    docs. Returns ``(problem, report)``: ``problem`` is a dict in the file's key
    order with exact strings, ``report`` a dict describing every recovered value and every
    choice made. ``deterministic_moves`` writes an action with a single outcome as a move
    ``{"to": y, "cost": c}``: a table without randomness then makes a deterministic problem
    file, which the commands on deterministic problems also read (``verify --claim C4``,
    ``learn``, ``solve --algorithm dijkstra``). ``rewards``: ``"gymnasium"`` writes every
    action's expected reward, ``"costs"`` none (module docs). ``max_file_bytes``: refuse,
    before any value is recovered, a table whose file in the layout of ``to_json(...,
    compact)`` takes more bytes (a lower bound from the state count, then from one quick pass
    over the table's shape, :mod:`truecost_gym.size`); ``large``, a function, is passed that
    refusal's text instead, and the import goes on. ``report["warnings"]`` lists what the
    caller should print (an unreachable goal).
    Raises :class:`ImportRefused` (one line, naming the state and action) for a malformed or
    ambiguous table, including any exception the table's own code raises.
    """
    if rewards not in REWARDS:
        raise ValueError(f"rewards must be one of {REWARDS}, got {rewards!r}")
    with_rewards = rewards == "gymnasium"
    values = _Values(env_name, max_denominator, ulps, exact_binary)
    after = "in exact binary" if exact_binary else "after recovery"
    named = set()
    for g in goals or ():
        if not isinstance(g, numbers.Integral) or isinstance(g, bool) or not 0 <= g < n_states:
            raise ImportRefused(f"{env_name}: goal {_shown(g)} is not a state 0..{n_states - 1}",
                                UNSUPPORTED)
        if g in named:
            raise ImportRefused(f"{env_name}: goal {g} is named twice", UNSUPPORTED)
        named.add(int(g))
    if max_file_bytes is not None:
        layout = Layout(to_json, compact, deterministic_moves, with_rewards)
        least = layout.empty + (n_states - 1) * layout.goal
        if least > max_file_bytes:
            raise ImportRefused(
                f"{env_name}: {n_states} states take at least {least} bytes, more than the "
                f"{max_file_bytes} bytes truecost's readers accept",
                UNSUPPORTED,
            )
        least = least_file_bytes(_shape(P, n_states, n_actions, env_name), n_states, layout,
                                 named)
        refuse_or_warn(least, max_file_bytes, env_name, large)
    # Pass 1: read and recover every entry with positive probability.
    table = []
    for s in range(n_states):
        row = []
        for a in range(n_actions):
            outcomes = []
            for i, (p, nxt, r, done) in enumerate(_entries(P, s, a, env_name)):
                where = f"P[{s}][{a}][{i}]"
                prob = values.get("probability", p, where)
                if prob < 0 or prob > 1:
                    raise ImportRefused(f"{env_name}: {where}: probability {float_text(p)} is not in [0, 1]")
                nxt, done = _move(nxt, done, n_states, env_name, where)
                if prob == 0:
                    if not _is_number(r):
                        values.get("reward", r, where)  # refuses it
                    continue
                reward = values.get("reward", r, where)
                outcomes.append((prob, nxt, reward, done, (s, a, i)))
            row.append(outcomes)
        table.append(row)

    # Initial distribution.
    if initial is None:
        raise ImportRefused(
            f"{env_name}: no initial state distribution (env.unwrapped.initial_state_distrib or "
            "isd): give --initial STATE"
        )
    if isinstance(initial, int):
        if not 0 <= initial < n_states:
            raise ImportRefused(f"{env_name}: initial state {initial} is not a state 0..{n_states - 1}",
                                UNSUPPORTED)
        initial = [1 if s == initial else 0 for s in range(n_states)]
    if len(initial) != n_states:
        raise ImportRefused(
            f"{env_name}: the initial distribution has {len(initial)} entries for {n_states} states"
        )
    start = []
    for s, q in enumerate(initial):
        prob = values.get("initial probability", q, f"initial_state_distrib[{s}]")
        if prob < 0 or prob > 1:
            raise ImportRefused(f"{env_name}: initial_state_distrib[{s}] = {float_text(q)} is not in [0, 1]")
        if prob > 0:
            start.append((s, prob))
    total = sum((p for _, p in start), Fraction(0))
    if total != 1:
        raise ImportRefused(
            f"{env_name}: the initial distribution sums to {_off_one(total)} {after}, not "
            "exactly 1"
        )

    # Terminal states and goals (module truecost_gym.goals).
    entered_running, entered_terminated = terminal_states(table, start, named, env_name)
    terminal = set(entered_terminated) | named
    warnings = []
    if goals is None:
        goal_set, goal_rule, warnings = choose_goals(table, entered_running, entered_terminated,
                                                     named, env_name)
    else:
        goal_set = named
        goal_rule = "named with --goals"
    traps = sorted(terminal - goal_set)
    running = len(entered_running)

    def action(cost, by_next, reward):
        """One action of the file, in the key order of ``truecost export``."""
        out = {"to": next(iter(by_next))} if deterministic_moves and len(by_next) == 1 else {}
        out["cost"] = str(cost)
        if with_rewards:
            out["reward"] = str(reward)
        if "to" not in out:
            out["outcomes"] = [{"to": x, "p": str(p)} for x, p in by_next.items()]
        return out

    # Pass 2: actions with merged outcomes, expected costs and expected rewards.
    actions = []
    merged = 0
    for s in range(n_states):
        if s in goal_set:
            actions.append([])
            continue
        if s in terminal:
            actions.append([action(Fraction(0), {s: Fraction(1)}, Fraction(0))])
            continue
        row = []
        for a in range(n_actions):
            entries = table[s][a]
            if not entries:
                raise ImportRefused(
                    f"{env_name}: state {s}, action {a}: no outcome of positive probability"
                )
            total = sum((p for p, *_ in entries), Fraction(0))
            if total != 1:
                    raise ImportRefused(
                    f"{env_name}: state {s}, action {a}: the probabilities sum to "
                    f"{_off_one(total)} {after}, not exactly 1"
                )
            cost = sum((p * truecost_cost(r) for p, _, r, _, _ in entries), Fraction(0))
            reward = sum((p * r for p, _, r, _, _ in entries), Fraction(0))
            by_next = {}
            for p, nxt, *_ in entries:
                if nxt in by_next:
                    merged += 1
                by_next[nxt] = by_next.get(nxt, Fraction(0)) + p
            row.append(action(cost, by_next, reward))
        actions.append(row)

    if len(start) == 1:
        x1 = start[0][0]
    else:
        x1 = [{"state": x, "p": str(p)} for x, p in start]

    problem = {
        "format": FORMAT,
        "name": f"{env_name} ({name_note(rewards)})",
        "states": n_states,
        "initial": x1,
        "goals": sorted(goal_set),
    }
    if traps:
        problem["terminal"] = traps
    problem["actions"] = actions
    recovered = values.report()
    report = {
        "environment": env_name,
        "states": n_states,
        "actions": sum(len(r) for r in actions),
        "initial": x1,
        "initial_distribution": None if len(start) == 1 else {"support": len(start)},
        "running_states": running,
        "goals": sorted(goal_set),
        "goal_rule": goal_rule,
        "warnings": warnings,
        "traps": traps,
        "cost_rule": "an outcome with reward r < 0 costs -r, with r >= 0 costs 1 (one step); "
                     "an action costs the expectation over its outcomes",
        "rewards": rewards,
        "reward_rule": "an action's reward is the expectation of Gymnasium's rewards over its "
                       "outcomes (traps: 0)" if with_rewards else
                       "no reward written: the discounted objective rewards the negated stage "
                       "costs",
        "merged_outcomes": merged,
        "max_denominator": max_denominator,
        "ulps": ulps,
        "exact_binary": exact_binary,
        "deterministic_moves": deterministic_moves,
        "values": recovered,
        "binary": [v for v in recovered if v["how"] == BINARY],
    }
    return problem, report


def name_note(rewards):
    """What the file's name says about its costs and rewards.

    >>> name_note("gymnasium"), name_note("costs")
    ("truecost stage costs, Gymnasium's rewards", 'truecost stage costs')
    """
    return "truecost stage costs, Gymnasium's rewards" if rewards == "gymnasium" else \
        "truecost stage costs"


#: Characters JSON allows raw in a string that must not reach a terminal that shows the file:
#: DEL, the C1 controls, the line and paragraph separators, direction and zero-width marks.
_RAW_HIDDEN = re.compile("[\x7f-\x9f\u200b-\u200f\u2028-\u202e\u2066-\u2069\ufeff]")


def _escape_hidden(text):
    """``text`` (JSON) with :data:`_RAW_HIDDEN` written as ``\\uXXXX`` escapes (they occur in
    strings only, where the escape means the same character)."""
    return _RAW_HIDDEN.sub(lambda m: f"\\u{ord(m.group()):04x}", text)


def to_json(problem, compact=False):
    """The file's text: ``compact`` puts one state's action list per line; otherwise the same
    layout as ``truecost export`` (two-space indentation). Control and direction characters
    of the name are escaped (``\\u009b``), never written raw."""
    if not compact:
        return _escape_hidden(json.dumps(problem, indent=2, ensure_ascii=False)) + "\n"
    head = {k: v for k, v in problem.items() if k != "actions"}
    sep = (",", ":")
    lines = [json.dumps(head, separators=sep, ensure_ascii=False)[:-1] + ',"actions":[']
    rows = [json.dumps(r, separators=sep) for r in problem["actions"]]
    lines.append(",\n".join(rows))
    lines.append("]}")
    return _escape_hidden("\n".join(lines)) + "\n"
