"""Rational recovery of floating-point numbers (standard library only).

Gymnasium stores probabilities and rewards as binary floats: FrozenLake's "1/3" is the float
0.33333333333333337, which is *not* the float nearest to 1/3 (that one is 0.3333333333333333):
it is the result of computing ``(1 - 1/3) / 2`` in floating point. truecost's exact solvers need
the fractions the author meant, so every float is recovered as follows, all bounds being exact
``fractions.Fraction`` values (never a float):

1. ``exact``: the float is an integer, or the simplest fraction whose correctly rounded float is
   the float itself is the float's own binary value (0.5, 0.25, -100.0).
2. ``rounding interval``: the simplest fraction (smallest denominator; Stern–Brocot search by
   continued fractions) among those whose correctly rounded float is this float, if its
   denominator is at most ``max_denominator`` (0.1 -> 1/10, 1/3's float -> 1/3).
3. ``within K ulps``: otherwise, the simplest fraction with denominator at most
   ``max_denominator`` within ``ulps`` units in the last place of the float (a value computed
   with a rounding error or two, such as FrozenLake's 0.33333333333333337 -> 1/3, 0.67 ulp
   away). A non-zero float is never recovered as 0 (nor with the other sign): near 0 the
   interval contains 0, which is then passed over.
4. ``exact binary``: otherwise the float's exact binary value is kept (and said so); a
   probability row containing one almost never sums to 1, and is then refused by the caller.
"""

import math
import numbers
from decimal import Decimal
from fractions import Fraction

DEFAULT_MAX_DENOMINATOR = 10**6
DEFAULT_ULPS = 4

EXACT = "exact"
ROUNDING = "rounding interval"
BINARY = "exact binary"


def simplest_between(lo, hi, max_denominator=None):
    """The fraction with the smallest denominator in the closed interval ``[lo, hi]``.

    Among the fractions of smallest denominator it is unique (it is the first node of the
    Stern–Brocot tree inside the interval), and it is computed from the continued-fraction
    expansions of the exact bounds. Returns ``None`` if that denominator exceeds
    ``max_denominator`` (then no fraction in the interval has a denominator within the bound).

    >>> simplest_between(Fraction(3, 10), Fraction(7, 20))
    Fraction(1, 3)
    >>> simplest_between(Fraction(-1, 2), Fraction(1, 3))
    Fraction(0, 1)
    >>> simplest_between(Fraction(1, 1000001), Fraction(1, 1000000), 999999) is None
    True
    """
    lo, hi = Fraction(lo), Fraction(hi)
    if lo > hi:
        raise ValueError("empty interval")
    if lo <= 0 <= hi:
        return Fraction(0)
    if hi < 0:
        found = simplest_between(-hi, -lo, max_denominator)
        return None if found is None else -found
    # 0 < lo <= hi. The answer is (p1 * t + p0) / (q1 * t + q0) for the simplest t in the
    # current interval, t >= 1 after the first step; denominators grow with t, so the least
    # integer in the interval is the simplest choice when there is one.
    p0, q0, p1, q1 = 0, 1, 1, 0
    while True:
        least = math.ceil(lo)
        if least <= hi:
            num, den = least * p1 + p0, least * q1 + q0
            if max_denominator is not None and den > max_denominator:
                return None
            return Fraction(num, den)
        whole = math.floor(lo)
        p0, q0, p1, q1 = p1, q1, whole * p1 + p0, whole * q1 + q0
        if max_denominator is not None and q1 > max_denominator:
            return None
        lo, hi = 1 / (hi - whole), 1 / (lo - whole)


def _neighbours(x):
    """The floats just below and just above ``x`` in x's own binary format."""
    if hasattr(x, "dtype") and getattr(x.dtype, "itemsize", 8) != 8:
        import numpy

        kind = x.dtype.type
        return (
            numpy.nextafter(x, kind(-numpy.inf)),
            numpy.nextafter(x, kind(numpy.inf)),
        )
    f = float(x)
    return math.nextafter(f, -math.inf), math.nextafter(f, math.inf)


def _rounds_to(fraction, x):
    """Whether ``fraction`` rounds (to nearest) to the float ``x`` of x's own format."""
    if hasattr(x, "dtype") and getattr(x.dtype, "itemsize", 8) != 8:
        # Narrow formats: nearest by exact comparison with the neighbours.
        below, above = (Fraction(float(v)) for v in _neighbours(x))
        exact = Fraction(float(x))
        d = abs(fraction - exact)
        return d <= abs(fraction - below) and d <= abs(fraction - above)
    return float(fraction) == float(x)


class Recovery:
    """One recovered number: the float as given, the exact value used, and how it was found."""

    __slots__ = ("text", "value", "how", "ulps_away")

    def __init__(self, text, value, how, ulps_away):
        self.text = text
        self.value = value
        self.how = how
        self.ulps_away = ulps_away

    def __repr__(self):
        return f"Recovery({self.text} -> {self.value}, {self.how})"


def float_text(x):
    """The shortest text that reads back as the same float (Python's repr), or the exact text."""
    if isinstance(x, bool):
        return str(int(x))
    if isinstance(x, numbers.Integral):
        return str(int(x))
    if isinstance(x, numbers.Rational):
        return str(Fraction(x))
    if isinstance(x, Decimal):
        return str(x)
    if hasattr(x, "dtype") and getattr(x.dtype, "itemsize", 8) != 8:
        return f"{x!r}"
    return repr(float(x))


def recover(x, max_denominator=DEFAULT_MAX_DENOMINATOR, ulps=DEFAULT_ULPS, exact_binary=False):
    """The exact value of ``x`` (module docs: exact, rounding interval, within K ulps, binary).

    Integers and exact numbers (``int``, ``Fraction``, ``Decimal``, NumPy integers) are taken
    as they are. Raises ``ValueError`` for NaN and infinities, ``TypeError`` for text.

    >>> recover(0.1).value, recover(1 / 3).value, recover(2 / 3).value
    (Fraction(1, 10), Fraction(1, 3), Fraction(2, 3))
    >>> r = recover(0.33333333333333337)
    >>> (r.value, r.how)
    (Fraction(1, 3), 'within 1 ulp')
    >>> recover(0.1, exact_binary=True).value == Fraction(0.1)
    True
    """
    if isinstance(x, (str, bytes)):
        raise TypeError(f"{x!r} is text, not a number")
    text = float_text(x)
    if isinstance(x, Decimal):
        if not x.is_finite():
            raise ValueError(f"{text} is not a finite number")
        return Recovery(text, Fraction(x), EXACT, 0)
    if isinstance(x, (bool, numbers.Rational)):
        return Recovery(text, Fraction(int(x)) if isinstance(x, bool) else Fraction(x), EXACT, 0)
    f = float(x)
    if math.isnan(f) or math.isinf(f):
        raise ValueError(f"{text} is not a finite number")
    own = Fraction(f)
    if exact_binary or own.denominator == 1:
        return Recovery(text, own, EXACT if own.denominator <= max_denominator else BINARY, 0)
    below, above = (Fraction(float(v)) for v in _neighbours(x))
    # Step 2: every real in [mid(below, x), mid(x, above)] rounds to x, except possibly an
    # endpoint (ties go to the even neighbour): the candidate is checked by rounding it.
    lo, hi = (below + own) / 2, (own + above) / 2
    found = simplest_between(lo, hi, max_denominator)
    if found is not None and _rounds_to(found, x):
        return Recovery(text, found, EXACT if found == own else ROUNDING, 0)
    # Step 3: within `ulps` units in the last place (the larger gap to a neighbour).
    if ulps > 0:
        unit = max(own - below, above - own)
        found = simplest_between(own - ulps * unit, own + ulps * unit, max_denominator)
        # A float near 0 (-5e-324) is never recovered as 0, nor with the other sign: the
        # simplest fraction of an interval around 0 is 0, and the float's binary value is kept.
        if found is not None and found != 0:
            away = math.ceil(abs(found - own) / unit)
            return Recovery(text, found, f"within {away} ulp{'' if away == 1 else 's'}", away)
    return Recovery(text, own, BINARY, 0)
