"""The answers of :func:`truecost.solve`, :func:`truecost.compare` and :func:`truecost.discount`.

Every number is exact: a :class:`fractions.Fraction` built from the engine's integers, or
``math.inf`` for an infinite value (truecost where no policy reaches a goal with probability 1,
the expected steps of an improper policy). Floats appear nowhere else.
"""

from dataclasses import dataclass
from fractions import Fraction
from typing import Dict, NamedTuple, Optional, Tuple, Union

#: An exact value of the extended reals: a ``Fraction``, or ``math.inf``.
Value = Union[Fraction, float]


class Range(NamedTuple):
    """A quantity's least and greatest value over all the policies optimal for an objective
    (they differ when tied optimal actions differ in what they achieve)."""

    min: Value
    max: Value


def _single(r):
    return r.min if r.min == r.max else r


@dataclass(frozen=True)
class Solution:
    """One objective, solved exactly (``truecost solve --algorithm exact --objective O``).

    ``value`` is the optimal value at the initial state (the expectation over the initial
    distribution when there is one, as for Taxi); ``values`` one per state; ``policy`` the
    reported optimal policy, an action number per state (Gymnasium's action for an
    environment), ``None`` where the episode is over or where every action is optimal
    (truecost where the value is infinite). ``expected_truecost`` and ``expected_steps`` are
    the reported policy's; ``None`` for the reach objective solved without ``with_cost`` where
    they are finite (not computed, as ``solve --objective reach`` without ``--with-cost``
    leaves them out).
    """

    source: str
    objective: str
    alpha: Optional[Fraction]
    rewards: str
    states: int
    initial_states: int
    value: Value
    values: Tuple[Value, ...]
    policy: Tuple[Optional[int], ...]
    success_range: Range
    policy_success_probability: Fraction
    expected_truecost: Optional[Value]
    expected_steps: Optional[Value]
    terminal_bonus: Optional[Fraction]

    @property
    def success_probability(self):
        """The probability of reaching a goal under the optimal policies: a ``Fraction`` when
        they all agree, else their :class:`Range`."""
        return _single(self.success_range)

    @classmethod
    def _of(cls, d):
        return cls(
            source=d["source"],
            objective=d["objective"],
            alpha=d["alpha"],
            rewards=d["rewards"],
            states=d["states"],
            initial_states=d["initial_states"],
            value=d["value"],
            values=tuple(d["values"]),
            policy=tuple(d["policy"]),
            success_range=Range(*d["success"]),
            policy_success_probability=d["policy_success"],
            expected_truecost=d["expected_truecost"],
            expected_steps=d["expected_steps"],
            terminal_bonus=d["terminal_bonus"],
        )


@dataclass(frozen=True)
class Comparison:
    """Every objective side by side (``truecost compare``): ``rows`` is truecost, reach, then
    discounted for each ``α`` in the order given."""

    source: str
    rewards: str
    rows: Tuple[Solution, ...]

    @property
    def truecost(self) -> Solution:
        return self.rows[0]

    @property
    def reach(self) -> Solution:
        return self.rows[1]

    @property
    def discounted(self) -> Dict[Fraction, Solution]:
        """The discounted rows by ``α``."""
        return {r.alpha: r for r in self.rows[2:]}


@dataclass(frozen=True)
class Point:
    """A real algebraic number in ``[0, 1]``, exactly.

    ``exact`` is the number when it is rational (else ``None``); ``interval`` two ``Fraction``
    bounds isolating it (both equal to it when it is rational, else ``lo < x < hi`` with
    ``hi - lo <= 2**-100``); ``polynomial`` the integer coefficients of a polynomial vanishing
    at it, constant term first (its minimal polynomial when ``minimal``, else square-free
    without rational roots); ``decimal`` its value correctly rounded to 30 digits after the
    point. ``float(point)`` is a float near it (for plotting only).
    """

    exact: Optional[Fraction]
    interval: Tuple[Fraction, Fraction]
    polynomial: Tuple[int, ...]
    minimal: bool
    decimal: str

    def __float__(self):
        return float(self.decimal)

    @staticmethod
    def _fields(d):
        return dict(
            exact=d["exact"],
            interval=tuple(d["interval"]),
            polynomial=tuple(d["polynomial"]),
            minimal=d["minimal"],
            decimal=d["decimal"],
        )


@dataclass(frozen=True)
class End(Point):
    """An end of a piece of :attr:`Discount.failure_set`, with the command line's text of it."""

    text: str


@dataclass(frozen=True)
class Piece:
    """A maximal interval of the failure set (a single point when ``lo == hi``)."""

    lo: End
    lo_closed: bool
    hi: End
    hi_closed: bool


@dataclass(frozen=True)
class Breakpoint(Point):
    """A discount factor ``α`` where the set of discount-optimal policies changes.

    ``optimal_left`` and ``optimal_right`` are the optimal actions per state on the open
    intervals on either side; ``ties`` the states whose optimal actions at the point itself
    differ from a neighbour's, with those actions; ``touch`` whether both sides have the same
    optimal actions (a tie at the point only). ``success_range`` and ``truecost_range`` are
    what the policies optimal at the point achieve.
    """

    touch: bool
    ties: Dict[int, Tuple[int, ...]]
    success_range: Range
    truecost_range: Range
    optimal_left: Tuple[Tuple[int, ...], ...]
    optimal_right: Tuple[Tuple[int, ...], ...]

    @property
    def success_probability(self):
        return _single(self.success_range)


@dataclass(frozen=True)
class Interval:
    """An open interval of ``α`` between consecutive breakpoints (``lo``/``hi`` a
    :class:`Breakpoint`, or ``Fraction(0)``/``Fraction(1)`` at the ends), with a rational
    ``sample`` inside, an optimal ``policy``, the ``optimal`` actions per state, and what the
    optimal policies achieve there."""

    lo: Union[Breakpoint, Fraction]
    hi: Union[Breakpoint, Fraction]
    sample: Fraction
    policy: Tuple[Optional[int], ...]
    optimal: Tuple[Tuple[int, ...], ...]
    success_range: Range
    truecost_range: Range

    @property
    def success_probability(self):
        return _single(self.success_range)


@dataclass(frozen=True)
class Discount:
    """The exact discount analysis (``truecost discount``).

    ``failure_set`` is the set of ``α`` in ``(0, 1)`` where a discount-optimal policy reaches a
    goal with probability below 1 (from some initial state), as maximal :class:`Piece` s;
    ``failure_set_text`` is the command line's text of it.
    """

    source: str
    rewards: str
    method: str
    deterministic: bool
    breakpoints: Tuple[Breakpoint, ...]
    intervals: Tuple[Interval, ...]
    failure_set: Tuple[Piece, ...]
    failure_set_text: str

    @classmethod
    def _of(cls, d):
        raw = d["intervals"]
        optimal = [tuple(tuple(a) for a in i["optimal"]) for i in raw]
        breakpoints = tuple(
            Breakpoint(
                **Point._fields(b),
                touch=b["touch"],
                ties={x: tuple(a) for x, a in b["ties"]},
                success_range=Range(*b["success"]),
                truecost_range=Range(*b["truecost"]),
                optimal_left=optimal[k],
                optimal_right=optimal[k + 1],
            )
            for k, b in enumerate(d["breakpoints"])
        )

        def end(index, default):
            return default if index is None else breakpoints[index]

        intervals = tuple(
            Interval(
                lo=end(i["lo"], Fraction(0)),
                hi=end(i["hi"], Fraction(1)),
                sample=i["sample"],
                policy=tuple(i["policy"]),
                optimal=optimal[k],
                success_range=Range(*i["success"]),
                truecost_range=Range(*i["truecost"]),
            )
            for k, i in enumerate(raw)
        )
        pieces = tuple(
            Piece(
                lo=End(**Point._fields(p["lo"]), text=p["lo"]["text"]),
                lo_closed=p["lo_closed"],
                hi=End(**Point._fields(p["hi"]), text=p["hi"]["text"]),
                hi_closed=p["hi_closed"],
            )
            for p in d["failure_set"]
        )
        return cls(
            source=d["source"],
            rewards=d["rewards"],
            method=d["method"],
            deterministic=d["deterministic"],
            breakpoints=breakpoints,
            intervals=intervals,
            failure_set=pieces,
            failure_set_text=d["failure_set_text"],
        )


__all__ = [
    "Breakpoint",
    "Comparison",
    "Discount",
    "End",
    "Interval",
    "Piece",
    "Point",
    "Range",
    "Solution",
    "Value",
]
