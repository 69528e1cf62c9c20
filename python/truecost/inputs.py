"""What a call's first argument names, as the native module's input ``(kind, text, name)``.

* a Gymnasium environment object, or a registered id such as ``"FrozenLake-v1"`` (with
  ``gymnasium.make`` keyword arguments): exported in memory by the importer
  (:mod:`truecost_gym`), as ``truecost-gym export`` writes it, then read as a problem file;
* a path (``os.PathLike``, an existing file, or a name ending in ``.json``): a problem file,
  as ``--file``;
* any other string: an ``--env`` spec of the command line (``"frozenlake:map=8x8"``,
  ``"cliffwalking:slippery=true"``, ``"taxi"``), built by truecost itself.
"""

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


def exact_text(number, what="alpha"):
    """An exact number's text for the engine: a ``Fraction``, ``int``, ``Decimal`` or a string
    (``"0.99"``, ``"99/100"``). A float is refused: ``0.9`` is not ``9/10``."""
    if isinstance(number, str):
        return number
    if isinstance(number, bool):
        raise Error(f"{what} must be a number, got {number!r}")
    if isinstance(number, (int, Fraction, Decimal)):
        return str(Fraction(number))
    if isinstance(number, float):
        raise Error(
            f"{what} = {number!r} is a float, whose exact value is {Fraction(number)}: give a "
            f"Fraction, an int or a string such as '{number!r}'"
        )
    raise Error(f"{what} must be a Fraction, an int or a string, got {type(number).__name__}")
