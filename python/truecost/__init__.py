"""truecost: exact answers for planning problems and Gymnasium environments.

    >>> import truecost, gymnasium
    >>> truecost.solve(gymnasium.make("FrozenLake-v1")).value        # doctest: +SKIP
    >>> truecost.discount("frozenlake").breakpoints                   # doctest: +SKIP

Native bindings of the truecost library (its Rust engine, :mod:`truecost._native`): the same
library functions as ``truecost solve --algorithm exact --objective O``, ``truecost compare``
and ``truecost discount``, whose answers these are, number for number. Every value is a
:class:`fractions.Fraction` (``math.inf`` where infinite). Refusals raise :class:`Error` (a
``ValueError``) with the command line's one-line message. The engine runs with the GIL
released; Ctrl-C raises ``KeyboardInterrupt`` within 50 ms (a discount analysis stops at its
next probe, an exact solve finishes on its own thread).

The first argument of every call is a Gymnasium environment, a Gymnasium id with
``gymnasium.make`` keyword arguments (``truecost.solve("FrozenLake-v1", map_name="8x8")``),
an ``--env`` spec (``"frozenlake:map=8x8"``) or a problem file path. See
``docs/guide/python.md``.
"""

from . import _native
from ._native import Error
from .inputs import alpha_texts, exact_text, resolve
from .results import (
    Breakpoint,
    Comparison,
    Discount,
    End,
    Interval,
    Piece,
    Point,
    Range,
    Solution,
)

__version__ = _native.__version__

#: The discount factors of :func:`compare` when none are given (those of ``truecost compare``).
DEFAULT_ALPHAS = ("0.9", "0.95", "0.99", "0.999")


def solve(env, /, objective="truecost", alpha=None, *, with_cost=False, importer=None, **kwargs):
    """The exact optimum of one objective (``truecost solve --algorithm exact --objective``).

    ``objective`` is ``"truecost"`` (the paper's: least expected cost among the policies
    reaching a goal with probability 1), ``"reach"`` (the greatest probability of reaching a
    goal) or ``"discounted"`` (the rewards discounted by ``alpha``, maximised; ``alpha`` in
    ``(0, 1)``, exact: a ``Fraction``, an ``int`` or a string such as ``"0.99"``).
    ``with_cost`` (the reach objective only, as ``--with-cost``): also compute the reported
    policy's expected truecost and steps when they are finite; without it they are ``None``
    then (and ``math.inf`` where the policy misses the goal with positive probability, which
    costs nothing to find).
    ``kwargs`` go to ``gymnasium.make`` when ``env`` is a Gymnasium id; ``importer`` are
    options of :func:`truecost_gym.from_env` (``goals``, ``initial``, ...).
    Returns a :class:`Solution`.
    """
    if not isinstance(objective, str):
        raise Error(f"objective must be a string (truecost, reach, discounted), got {objective!r}")
    if not isinstance(with_cost, bool):
        raise Error(f"with_cost must be True or False, got {with_cost!r}")
    alpha = None if alpha is None else exact_text(alpha)
    kind, text, name = resolve(env, kwargs, importer)
    return Solution._of(_native.solve(kind, text, name, objective, alpha, with_cost))


def compare(env, /, alphas=DEFAULT_ALPHAS, *, importer=None, **kwargs):
    """Every objective side by side (``truecost compare --alphas``): truecost, reach and the
    discounted objective at each ``α`` of ``alphas``. Returns a :class:`Comparison`."""
    alphas = alpha_texts(alphas)
    kind, text, name = resolve(env, kwargs, importer)
    d = _native.compare(kind, text, name, alphas)
    return Comparison(d["source"], d["rewards"], tuple(Solution._of(r) for r in d["rows"]))


def discount(env, /, *, importer=None, **kwargs):
    """The exact discount breakpoints (``truecost discount``): every ``α`` in ``(0, 1)`` where
    the discount-optimal policies change, exactly, with what the optimal policies achieve on
    each side, and the set of ``α`` where a discount-optimal policy fails to reach a goal.
    Returns a :class:`Discount`."""
    kind, text, name = resolve(env, kwargs, importer)
    return Discount._of(_native.discount(kind, text, name))


__all__ = [
    "Breakpoint",
    "Comparison",
    "DEFAULT_ALPHAS",
    "Discount",
    "End",
    "Error",
    "Interval",
    "Piece",
    "Point",
    "Range",
    "Solution",
    "compare",
    "discount",
    "solve",
]
