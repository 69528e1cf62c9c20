"""What a call's first argument names, as the native module's input ``(kind, text, name)``.

* a Gymnasium environment object, or a registered id such as ``"FrozenLake-v1"`` (with
  ``gymnasium.make`` keyword arguments): exported in memory by the importer
  (:mod:`truecost_gym`), as ``truecost-gym export`` writes it, then read as a problem file;
* a path (``os.PathLike``, an existing file, or a name ending in ``.json``): a problem file,
  as ``--file``;
* any other string: an ``--env`` spec of the command line (``"frozenlake:map=8x8"``,
  ``"cliffwalking:slippery=true"``, ``"taxi"``), built by truecost itself.
"""

import math
import os
import re
from decimal import Decimal
from fractions import Fraction

from ._native import Error

#: A Gymnasium id: ``[namespace/]Name-vN``.
GYMNASIUM_ID = re.compile(r"^(?:[\w.-]+/)?[\w.:-]+-v\d+$")


def _one_line(text):
    return " ".join(str(text).split())


def _gymnasium():
    try:
        import gymnasium
    except ImportError:
        raise Error("gymnasium is not installed (pip install gymnasium)") from None
    return gymnasium


def _export(env, env_id, kwargs, importer):
    """The importer's problem file of ``env``, in memory."""
    from truecost_gym import ImportRefused, from_env, to_json
    from truecost_gym.importer import name_note

    gymnasium = _gymnasium()
    # Options are checked against the importer's own keywords before the environment's code
    # runs (from_env passes the others to import_table; a TypeError raised inside the
    # environment is the environment's refusal, not an unknown option).
    import inspect

    from truecost_gym import import_table

    known = set(inspect.signature(import_table).parameters) | {"initial"}
    known -= {"P", "n_states", "n_actions", "env_name"}
    unknown = sorted(set(importer) - known)
    if unknown:
        raise Error(
            f"importer options: unknown {', '.join(map(repr, unknown))} "
            f"(known: {', '.join(sorted(known))})"
        )
    try:
        problem, _ = from_env(env, env_id, **importer)
    except ImportRefused as e:
        raise Error(_one_line(e)) from None
    except TypeError as e:  # an importer option that does not exist
        raise Error(f"importer options: {_one_line(e)}") from None
    if env_id is None:
        spec = getattr(env, "spec", None)
        env_id = spec.id if spec is not None else type(getattr(env, "unwrapped", env)).__name__
    options = "" if not kwargs else " " + ",".join(f"{k}={v!r}" for k, v in kwargs.items())
    name = f"{env_id}{options} (Gymnasium {gymnasium.__version__}; {name_note('gymnasium')})"
    problem["name"] = name
    return "json", to_json(problem, compact=True), name


def resolve(env, kwargs, importer):
    """``(kind, text, name)`` of the native module for ``env`` and the ``gymnasium.make``
    keyword arguments ``kwargs``; ``importer`` are options of :func:`truecost_gym.from_env`
    (``goals``, ``initial``, ``max_denominator``, ...)."""
    if importer is not None and not isinstance(importer, dict):
        raise Error(
            "importer must be a dict of truecost_gym.from_env options "
            f"(goals, initial, ...), got {type(importer).__name__}"
        )
    importer = dict(importer or {})
    if isinstance(env, str) and GYMNASIUM_ID.match(env):
        gymnasium = _gymnasium()
        try:
            made = gymnasium.make(env, **kwargs)
        except Exception as e:  # unknown ids, bad keyword arguments, the user's constructor
            raise Error(f"cannot make {env}: {type(e).__name__}: {_one_line(e)}") from None
        try:
            return _export(made, env, kwargs, importer)
        finally:
            made.close()
    if kwargs:
        raise Error(
            f"keyword arguments ({', '.join(kwargs)}) apply to a Gymnasium id such as "
            "'FrozenLake-v1'; an --env spec takes its options after ':' "
            "('frozenlake:map=8x8'), an environment object is already made"
        )
    if isinstance(env, (str, os.PathLike)):
        if importer:
            raise Error("importer options apply to Gymnasium environments and ids")
        path = os.fspath(env)
        if isinstance(env, os.PathLike) or os.path.exists(path) or path.endswith(".json"):
            return "file", path, None
        return "env", path, None
    if hasattr(env, "unwrapped"):
        return _export(env, None, {}, importer)
    raise Error(
        "expected a Gymnasium environment, a Gymnasium id ('FrozenLake-v1'), an --env spec "
        f"('frozenlake:map=8x8') or a problem file path, got {type(env).__name__}"
    )


def _short(text, limit=60):
    """``text`` shortened to about ``limit`` characters, its length said when shortened."""
    text = str(text)
    if len(text) <= limit:
        return text
    half = (limit - 20) // 2
    return f"{text[:half]}…{text[-half:]} ({len(text)} characters)"


def exact_text(number, what="alpha"):
    """An exact number's text for the engine: a ``Fraction``, ``int``, finite ``Decimal`` or a
    string (``"0.99"``, ``"99/100"``). A float is refused: ``0.9`` is not ``9/10``."""
    if isinstance(number, str):
        return number
    if isinstance(number, bool):
        raise Error(f"{what} must be a number, got {number!r}")
    if isinstance(number, Decimal):
        if not number.is_finite():
            raise Error(f"{what} = {_short(repr(number))} is not a finite number")
        # The engine reads the exponent notation exactly (and bounds the exponent).
        return str(number)
    if isinstance(number, (int, Fraction)):
        return str(Fraction(number))
    if isinstance(number, float):
        if not math.isfinite(number):
            raise Error(f"{what} = {number!r} is not a finite number")
        raise Error(
            f"{what} = {number!r} is a float, whose exact value is {_short(Fraction(number))}: "
            f"give a Fraction, an int or a string such as '{number!r}'"
        )
    raise Error(f"{what} must be a Fraction, an int or a string, got {type(number).__name__}")

#: The most discount factors :func:`truecost.compare` takes (as ``truecost compare --alphas``).
MAX_ALPHAS = 64

#: An exact number's text as the engine reads it: ``[+-]digits[.digits][e[+-]digits]``.
_DECIMAL = re.compile(r"^\s*[+-]?(\d+\.?\d*|\.\d+)(?:[eE]([+-]?\d+))?\s*$")


def _exact_value(text):
    """The exact value of an engine number text, or ``None`` where the engine itself refuses
    it (bad syntax, an exponent beyond its +-10000, a zero denominator): then its message is
    the one raised."""
    sides = text.split("/")
    if len(sides) > 2 or len(text) > 4096:
        return None
    value = Fraction(1)
    for i, side in enumerate(sides):
        m = _DECIMAL.match(side)
        if m is None or (m.group(2) is not None and abs(int(m.group(2))) > 10000):
            return None
        v = Fraction(Decimal(side.strip()))
        if i == 0:
            value = v
        elif v == 0:
            return None
        else:
            value /= v
    return value


def alpha_texts(alphas):
    """The texts of ``compare``'s discount factors: a list of at most :data:`MAX_ALPHAS`
    exact numbers (:func:`exact_text`), none listed twice however written."""
    if isinstance(alphas, (str, bytes)):
        raise Error("alphas must be a list of exact numbers, e.g. ['0.9', Fraction(99, 100)]")
    try:
        alphas = list(alphas)
    except TypeError:
        raise Error(f"alphas must be a list of exact numbers, got {type(alphas).__name__}") from None
    if len(alphas) > MAX_ALPHAS:
        raise Error(
            f"alphas lists {len(alphas)} discount factors, more than the {MAX_ALPHAS} compare takes"
        )
    texts = [exact_text(a) for a in alphas]
    seen = {}
    for i, text in enumerate(texts):
        value = _exact_value(text)
        if value is None or not 0 < value < 1:
            continue  # the engine's own refusal names it
        if value in seen:
            raise Error(
                f"alpha {_short(text)} is listed twice "
                f"(as discount factor {seen[value] + 1} and {i + 1})"
            )
        seen[value] = i
    return texts
