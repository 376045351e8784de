"""The restitution relation: the effective coefficient of restitution of one impact under
``F_e(delta) (1 + D delta_dot / v0)`` and its inverse (see :class:`~exuclear.contact.damping.CarvalhoMartinsDamping`).

Exact for a free mass and any elastic force ``F_e``: ``e`` is a function of ``D`` alone.
"""
from __future__ import annotations

import math
import sys

from ..checks import check_open_closed, check_real

#: Relative tolerance of the restitution relation's roots (:func:`restitution_of_damping`,
#: :func:`damping_for_restitution`): the smallest :func:`scipy.optimize.brentq` accepts,
#: 4 machine epsilons, i.e. round-off.
RESTITUTION_RTOL = 4.0 * sys.float_info.epsilon
#: Absolute tolerance of those roots: none beyond the relative one (brentq needs one > 0).
_ROOT_XTOL = 1e-300
#: Iteration limit of those roots: at worst brentq bisects, and from the bracket's end
#: ``1/cr`` down to ``D = 1.5e-16`` (cr = 1 - 1e-16) to round-off takes ~110 halvings.
_ROOT_MAX_ITER = 200

#: Below this ``|x|``, :func:`_x_minus_log1p` sums its series: ``x - ln(1 + x)`` ~ ``x^2 / 2``
#: is then far smaller than ``x``, and the direct difference would keep only the
#: round-off of ``x``; at 0.1 the series needs 15 terms for round-off.
_SERIES_BELOW = 0.1


def _x_minus_log1p(x: float) -> float:
    """``x - ln(1 + x)`` (>= 0) for ``x > -1``, to round-off also where it is tiny against ``x``.

    The two sides of the restitution relation (:func:`restitution_of_damping`) agree to
    first order in ``D``; written with this function their difference keeps its digits.
    """
    if abs(x) >= _SERIES_BELOW:
        return x - math.log1p(x)
    total, term, k = 0.0, -x, 1  # sum over k >= 2 of (-x)^k / k
    while True:
        k += 1
        term *= -x
        step = term / k
        if total + step == total:
            return total
        total += step


def restitution_of_damping(D: float) -> float:
    """Effective restitution ``e`` of one impact under ``F_e(delta) (1 + D delta_dot / v0)``.

    Exact for a free mass and any elastic force ``F_e``: the root ``0 < e <= 1`` of
    ``D (1 + e) = ln(1 + D) - ln(1 - D e)`` (see :class:`CarvalhoMartinsDamping`), found by
    Brent's method (:func:`scipy.optimize.brentq`) to round-off (:data:`RESTITUTION_RTOL`).
    ``D = 0`` gives 1.  Both sides agree to first order in ``D`` (the relation's slope in
    ``e`` is about ``-D^2``); their difference is written with :func:`_x_minus_log1p`, so
    that it keeps its digits and the root is exact to round-off for small ``D`` too (the
    difference taken directly left an error of about ``2e-16 / D``).
    """
    from scipy.optimize import brentq

    D = check_real("D", D)
    if D < 0.0:
        raise ValueError(f"`D` must be non-negative, got {D}")
    if D == 0.0:
        return 1.0

    def r(e: float) -> float:  # D (1 + e) - ln(1 + D) + ln(1 - D e); decreases in e, r(0) > 0
        return _x_minus_log1p(D) - _x_minus_log1p(-D * e)

    # r(1) < 0, and r -> -inf at e = 1/D (the log's pole): end the bracket just before it
    hi = min(1.0, math.nextafter(1.0 / D, 0.0))
    if not r(hi) < 0.0:  # no sign change that floating point can see
        if D < 1.0:  # r(1) ~ -2 D^3 / 3 underflows (D below ~1e-100): e = 1 - 2 D / 3 to round-off
            return 1.0 - 2.0 * D / 3.0
        return hi  # large D: 1 - D e = (1 + D) exp(-D (1 + e)) is below round-off, e is 1/D to an ulp
    return brentq(r, 0.0, hi, xtol=_ROOT_XTOL, rtol=RESTITUTION_RTOL, maxiter=_ROOT_MAX_ITER)


def damping_for_restitution(cr: float) -> float:
    """The ``D > 0`` whose exact effective restitution is ``cr`` (inverse of :func:`restitution_of_damping`).

    The root of ``h(D) = ln(1 + D) - ln(1 - cr D) - D (1 + cr)`` by Brent's method
    (:func:`scipy.optimize.brentq`) to round-off (:data:`RESTITUTION_RTOL`).  ``h`` is
    negative on ``(0, root)``, positive beyond, and tends to ``+inf`` at ``D = 1/cr``;
    ``D = 0`` is a trivial root, which the bracket leaves out by starting at
    ``3 (1 - cr) / 4``, half of the root's limit ``3 (1 - cr) / 2`` as ``cr -> 1`` (below
    the root on a grid of 1000 values of cr in (0, 1); a bracket without the root would
    raise ``ValueError``, never return a wrong one).  ``h`` is written
    with :func:`_x_minus_log1p`, so that ``h ~ -(1 - cr^2) D^2 / 2`` keeps its digits up
    to ``cr = 1 - 1e-16``.  For small cr (below about 0.03) the root lies within an ulp of
    ``1/cr``, where ``h`` cannot be told from 0 in floating point; that neighbour of
    ``1/cr`` is returned.
    """
    from scipy.optimize import brentq

    cr = check_open_closed("cr", cr, 0.0, 1.0)
    if cr == 1.0:
        return 0.0

    def h(d: float) -> float:  # ln(1 + d) - ln(1 - cr d) - d (1 + cr)
        return _x_minus_log1p(-cr * d) - _x_minus_log1p(d)

    lo = 0.75 * (1.0 - cr)  # half of Hunt and Crossley's factor, the root's limit as cr -> 1
    hi = math.nextafter(1.0 / cr, 0.0)  # h(hi) is finite
    if not h(hi) > 0.0:
        return hi  # small cr: 1 - cr D = (1 + D) exp(-D (1 + cr)) is below round-off, D is 1/cr to an ulp
    return brentq(h, lo, hi, xtol=_ROOT_XTOL, rtol=RESTITUTION_RTOL, maxiter=_ROOT_MAX_ITER)

