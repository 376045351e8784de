"""The worn-in journal's law: a rigid journal of radius ``r = R - c`` turning under a constant
load ``F`` in a fixed bearing that wears (docs/physics.md section 11.6), the check of the
worn joint.

Once the imprint is deeper than the elastic approach, the bearing takes the journal's arc
over the half-angle ``phi_c`` where the journal's circle, moved by ``e = c + d0`` along the
load, leaves the bearing's unworn circle (eq. (82)); beyond 90 degrees the imprint's walls
face away from the load and carry nothing.  The imprint keeps the journal's shape only if
every point of the arc wears at the rate that keeps it on the journal's circle,
``k_D p ds = dd0 cos(phi)``: the pressure is ``p = P0 cos(phi)``.  Equilibrium along the load,
``F = P0 r L (phi_c + sin phi_c cos phi_c)``, then gives the depth's growth with the slip
``s`` (eq. (83)):

    dd0/ds = k_D F / (r L (phi_c + sin phi_c cos phi_c))

Early (``d0 << c``, ``phi_c^2 = 2 d0 / c``) this is ``d0 = [3 k_D F s sqrt(c) / (4 sqrt(2) r L)]^(2/3)``;
late (``phi_c = 90`` degrees) ``dd0/ds = 2 k_D F / (pi r L)``, ``4 k_D F / L`` per revolution.

With Coulomb friction ``mu`` the traction ``mu p`` turns the resultant of the contact by
``atan(mu)`` from the pressure's axis: the deepest point lies ``atan(mu)`` from the load, on
the side the journal's surface slides towards, and the normal resultant is ``F / sqrt(1 +
mu^2)``, which slows the growth by that factor (eq. (84)).
"""
from __future__ import annotations

import math

import numpy as np


def contact_half_angle(depth: float, r: float, c: float) -> float:
    """``phi_c`` [rad] of the imprint ``depth`` [m] (eq. (82)): where the journal's circle,
    its centre at ``e = c + depth`` from the bearing's, meets the bearing's ``R = r + c``;
    at most 90 degrees."""
    e = c + depth
    # 1 - cos(phi_c) = ((r + c)^2 - r^2 - e^2) / (2 e r) rearranged, exact to round-off at d0 -> 0
    one_minus_cos = depth * (2.0 * r + e + c) / (2.0 * e * r)
    if one_minus_cos >= 1.0:
        return 0.5 * math.pi
    return 2.0 * math.asin(math.sqrt(0.5 * one_minus_cos))


def depth_rate(depth: float, force: float, coefficient: float, r: float, c: float, length: float,
               mu: float = 0.0) -> float:
    """``dd0/ds`` [m/m] at the imprint ``depth`` (eqs. (83), (84))."""
    phi = contact_half_angle(depth, r, c)
    normal = force / math.sqrt(1.0 + mu * mu)
    return coefficient * normal / (r * length * (phi + math.sin(phi) * math.cos(phi)))


def slip_to_depth(depth: float, force: float, coefficient: float, r: float, c: float, length: float,
                  mu: float = 0.0, steps: int = 4000) -> float:
    """The slip [m] that wears the imprint to ``depth`` [m]: ``int dd0 / (dd0/ds)`` from 0,
    on a grid fine near 0 where the integrand goes as ``sqrt(d0)``."""
    d = depth * np.linspace(0.0, 1.0, steps + 1) ** 2
    inv = np.array([0.0] + [1.0 / depth_rate(x, force, coefficient, r, c, length, mu) for x in d[1:]])
    return float(np.sum(0.5 * (inv[1:] + inv[:-1]) * np.diff(d)))


def depth_after_slip(slip: float, force: float, coefficient: float, r: float, c: float, length: float,
                     mu: float = 0.0) -> float:
    """The imprint's depth ``d0`` [m] after the slip ``slip`` [m]: eq. (83) integrated, inverted
    by bisection between 0 and the late law's bound."""
    late = 2.0 * coefficient * force / (math.pi * r * length)
    early = (3.0 * coefficient * force * slip * math.sqrt(c) / (4.0 * math.sqrt(2.0) * r * length)) ** (2.0 / 3.0)
    lo, hi = 0.0, max(early, late * slip) * 2.0
    for _ in range(80):
        mid = 0.5 * (lo + hi)
        if slip_to_depth(mid, force, coefficient, r, c, length, mu, 400) < slip:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def early_depth(slip: float, force: float, coefficient: float, r: float, c: float, length: float) -> float:
    """The early law ``d0 = [3 k_D F s sqrt(c) / (4 sqrt(2) r L)]^(2/3)`` (``d0 << c``) [m]."""
    return (3.0 * coefficient * force * slip * math.sqrt(c) / (4.0 * math.sqrt(2.0) * r * length)) ** (2.0 / 3.0)
