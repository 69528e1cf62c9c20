"""Rational recovery of floats (truecost_gym.rational): standard library only."""

import doctest
import math
import unittest
from fractions import Fraction

from truecost_gym import rational
from truecost_gym.rational import BINARY, EXACT, ROUNDING, recover, simplest_between


def brute_simplest(lo, hi, max_denominator):
    """The fraction of smallest denominator in [lo, hi], by trying every denominator."""
    for q in range(1, max_denominator + 1):
        p = math.ceil(lo * q)
        if Fraction(p, q) <= hi:
            return Fraction(p, q)
    return None


class SimplestBetween(unittest.TestCase):
    def test_agrees_with_trying_every_denominator(self):
        cases = [
            (Fraction(3, 10), Fraction(7, 20)),
            (Fraction(1, 7), Fraction(1, 7)),
            (Fraction(355, 113), Fraction(22, 7)),
            (Fraction(5, 3), Fraction(17, 10)),
            (Fraction(1001, 1000), Fraction(1002, 1000)),
            (Fraction(0.1), Fraction(0.1) + Fraction(1, 10**9)),
            (Fraction(2, 3) - Fraction(1, 10**6), Fraction(2, 3)),
            (Fraction(7), Fraction(15, 2)),
        ]
        for lo, hi in cases:
            with self.subTest(lo=lo, hi=hi):
                self.assertEqual(simplest_between(lo, hi, 2000), brute_simplest(lo, hi, 2000))

    def test_sign_and_zero(self):
        self.assertEqual(simplest_between(Fraction(-1, 2), Fraction(1, 3)), 0)
        self.assertEqual(simplest_between(Fraction(-7, 20), Fraction(-3, 10)), Fraction(-1, 3))

    def test_bound_on_the_denominator(self):
        lo = hi = Fraction(1, 1009)
        self.assertEqual(simplest_between(lo, hi, 1009), Fraction(1, 1009))
        self.assertIsNone(simplest_between(lo, hi, 1008))


class Recover(unittest.TestCase):
    def test_common_fractions_come_back(self):
        for f in [Fraction(1, 3), Fraction(2, 3), Fraction(1, 10), Fraction(1, 300),
                  Fraction(4, 5), Fraction(-7, 3), Fraction(999999, 1000000)]:
            with self.subTest(f=f):
                r = recover(float(f))
                self.assertEqual(r.value, f)
                self.assertEqual(r.how, ROUNDING)

    def test_dyadic_and_integer_floats_are_exact(self):
        for x, f in [(0.5, Fraction(1, 2)), (-100.0, Fraction(-100)), (0.0, Fraction(0)),
                     (0.375, Fraction(3, 8)), (20, Fraction(20)), (Fraction(2, 7), Fraction(2, 7))]:
            with self.subTest(x=x):
                r = recover(x)
                self.assertEqual((r.value, r.how), (f, EXACT))

    def test_frozenlakes_third_is_recovered_within_one_ulp(self):
        # Gymnasium computes (1 - 1/3) / 2 = 0.33333333333333337, the float above 1/3's float.
        x = (1 - 1 / 3) / 2
        self.assertEqual(repr(x), "0.33333333333333337")
        self.assertNotEqual(float(Fraction(1, 3)), x)
        r = recover(x)
        self.assertEqual((r.value, r.how), (Fraction(1, 3), "within 1 ulp"))
        # With no tolerance beyond the rounding interval the float's own value is kept.
        self.assertEqual(recover(x, ulps=0).how, BINARY)
        self.assertEqual(recover(x, ulps=0).value, Fraction(x))

    def test_arithmetic_results_within_a_few_ulps(self):
        r = recover(0.1 + 0.2)  # 0.30000000000000004
        self.assertEqual(r.value, Fraction(3, 10))
        self.assertTrue(r.how.startswith("within"))

    def test_denominator_bound(self):
        x = 1 / 1000003
        self.assertEqual(recover(x, max_denominator=10**7).value, Fraction(1, 1000003))
        r = recover(x)  # default bound 10^6: no such fraction near enough
        self.assertEqual((r.value, r.how), (Fraction(x), BINARY))
        # 0.499999999 needs the denominator 10^9.
        self.assertEqual(recover(0.499999999).how, BINARY)

    def test_exact_binary_keeps_the_float(self):
        self.assertEqual(recover(0.1, exact_binary=True).value, Fraction(0.1))
        self.assertEqual(recover(0.1, exact_binary=True).how, BINARY)
        self.assertEqual(recover(0.25, exact_binary=True).how, EXACT)

    def test_recovered_value_rounds_to_the_float(self):
        for q in range(1, 60):
            for p in range(0, q + 1):
                x = p / q
                r = recover(x)
                self.assertEqual(float(r.value), x, (p, q))
                self.assertLessEqual(r.value.denominator, q)

    def test_non_finite_refused(self):
        for x in [math.inf, -math.inf, math.nan]:
            with self.assertRaises(ValueError):
                recover(x)

    def test_doctests(self):
        failures, _ = doctest.testmod(rational)
        self.assertEqual(failures, 0)


if __name__ == "__main__":
    unittest.main()
