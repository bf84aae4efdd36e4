"""High-precision reference arithmetic for the tests: ``decimal`` with 60 significant digits.

The standard ``decimal`` module has ``sqrt`` but no trigonometry; the few functions the tests
need are written here from their Taylor series (with the usual argument reductions), so a
reference value can be computed from a model's published formula far more precisely than
float64.  Inputs are converted exactly (``Decimal(float)`` is exact), so a reference value is
the formula's value at exactly the float64 inputs the kernel sees.
"""

from __future__ import annotations

from decimal import Decimal, localcontext

PREC = 60


def precise():
    """Context manager: Decimal arithmetic at :data:`PREC` digits inside ``with precise():``."""
    return localcontext(prec=PREC)


def D(x) -> Decimal:
    """Exact conversion of a float (or int, or Decimal) to Decimal."""
    return x if isinstance(x, Decimal) else Decimal(x)


def _atan_small(x: Decimal) -> Decimal:
    """atan(x) for small |x| (≤ 0.2 here) by its series Σ (−1)ᵏ x^(2k+1)/(2k+1)."""
    x2, term, k, total = x * x, x, 0, Decimal(0)
    eps = Decimal(10) ** -(PREC + 5)
    while abs(term) > eps:
        total += term / (2 * k + 1)
        term = -term * x2
        k += 1
    return total


def atan(x) -> Decimal:
    with localcontext() as ctx:
        ctx.prec = PREC + 10
        x = D(x)
        if x < 0:
            return -atan(-x)
        if x > 1:
            return pi() / 2 - atan(1 / x)
        halvings = 0
        while x > Decimal("0.1"):  # atan x = 2 atan(x / (1 + √(1 + x²)))
            x = x / (1 + (1 + x * x).sqrt())
            halvings += 1
        return _atan_small(x) * (2**halvings)


def pi() -> Decimal:
    """Machin's formula π = 16 atan(1/5) − 4 atan(1/239) (the series converges for |x| < 1)."""
    with localcontext() as ctx:
        ctx.prec = PREC + 10
        return 16 * _atan_small(Decimal(1) / 5) - 4 * _atan_small(Decimal(1) / 239)


def atan2(y, x) -> Decimal:
    """Angle of (x, y) for y ≥ 0 (a polar angle: y = sin θ ≥ 0)."""
    y, x = D(y), D(x)
    if x > 0:
        return atan(y / x)
    if x == 0:
        return pi() / 2
    return pi() - atan(y / -x)


def sin(x) -> Decimal:
    with localcontext() as ctx:
        ctx.prec = PREC + 10
        x = D(x)
        term, k, total = x, 1, Decimal(0)
        eps = Decimal(10) ** -(PREC + 5)
        while abs(term) > eps:
            total += term
            term = -term * x * x / ((k + 1) * (k + 2))
            k += 2
        return total


def cos(x) -> Decimal:
    with localcontext() as ctx:
        ctx.prec = PREC + 10
        x = D(x)
        term, k, total = Decimal(1), 0, Decimal(0)
        eps = Decimal(10) ** -(PREC + 5)
        while abs(term) > eps:
            total += term
            term = -term * x * x / ((k + 1) * (k + 2))
            k += 2
        return total


def tan(x) -> Decimal:
    return sin(x) / cos(x)


def sqrt(x) -> Decimal:
    with localcontext() as ctx:
        ctx.prec = PREC + 10
        return D(x).sqrt()
