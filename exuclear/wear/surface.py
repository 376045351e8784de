"""The worn surfaces in contact: penetration over the arc, the contact's normal, the pressure
and one step's wear (docs/physics.md sections 11.1-11.4).

The bearing's depth ``h_B(theta)`` [m] is kept on ``N`` nodes ``theta_k = 2 pi k / N`` of the
joint frame, measured radially from the bearing's centre; the journal's ``h_J(phi)`` on
``N`` nodes of its own frame, measured along its radius.  The journal's centre sits at
``e = (ex, ey)`` from the bearing's centre, turned by ``psi`` about the axis.  Plain NumPy on
the profiles; the compiled kernel (``exuclear/_kernel/wear.hpp``) states the same sums node
by node.  Pure physics: no exudyn, no state.
"""
from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np


class Grid(NamedTuple):
    """The profile nodes: ``theta`` [rad], its cosine and sine, and the spacing ``dtheta``."""

    theta: np.ndarray
    cos: np.ndarray
    sin: np.ndarray
    dtheta: float


def grid(nodes: int) -> Grid:
    theta = 2.0 * math.pi * np.arange(nodes) / nodes
    return Grid(theta, np.cos(theta), np.sin(theta), 2.0 * math.pi / nodes)


def periodic_value(values: np.ndarray, angle: np.ndarray | float, dtheta: float) -> np.ndarray:
    """``values`` on the nodes ``k dtheta`` interpolated linearly at ``angle`` [rad] (any range)."""
    n = len(values)
    x = np.mod(np.asarray(angle) / dtheta, n)
    k = np.floor(x).astype(int) % n
    f = x - np.floor(x)
    return (1.0 - f) * values[k] + f * values[(k + 1) % n]


#: Nodes added on each side of the arc where the surfaces can overlap (:func:`window`).
WINDOW_MARGIN = 3


def window(g: Grid, ex: float, ey: float, clearance: float) -> np.ndarray:
    """The nodes where the worn surfaces can overlap, and :data:`WINDOW_MARGIN` more on each
    side: wear only deepens the bearing and thins the journal, so an overlap needs that of
    the unworn circles, ``|e| cos(theta - alpha) > c`` about the eccentricity's angle
    ``alpha`` (eq. (72)).  Without one, the nodes about ``alpha``."""
    ecc = math.sqrt(ex * ex + ey * ey)
    centre = int(round(math.atan2(ey, ex) / g.dtheta))
    half = math.acos(min(clearance / ecc, 1.0)) if ecc > 0.0 else 0.0
    m = min(int(half / g.dtheta) + 1 + WINDOW_MARGIN, len(g.theta) // 2)
    return (centre + np.arange(-m, m + 1)) % len(g.theta)


class SurfaceField(NamedTuple):
    """The two surfaces along the rays of the bearing's nodes ``nodes`` (eqs. (72)-(74)).

    ``w`` the penetration [m] at each node along the journal's normal (> 0: the surfaces
    overlap there); ``nx``, ``ny`` that normal (outward from the journal's centre);
    ``cos_gamma`` the cosine of its angle to the ray; ``area`` the bearing's surface
    element [m^2] of each node.
    """

    w: np.ndarray
    nx: np.ndarray
    ny: np.ndarray
    cos_gamma: np.ndarray
    area: np.ndarray
    nodes: np.ndarray


def surface_field(g: Grid, r_j: float, r_b: float, length: float, ex: float, ey: float, psi: float,
                  bearing: np.ndarray, journal: np.ndarray | None) -> SurfaceField:
    """The penetration of the worn journal into the worn bearing along the rays of the nodes
    of :func:`window`.

    Along the ray ``n_k`` from the bearing's centre, the unworn journal's surface is at
    ``rho = e . n_k + sqrt(R_J^2 - (e x n_k)^2)`` (eq. (72)); its normal there makes the angle
    ``gamma`` with the ray, ``cos gamma = sqrt(R_J^2 - (e x n_k)^2) / R_J``.  The radial
    overlap ``rho - R_B - h_B`` times ``cos gamma`` is the overlap along the normal; the
    journal's depth, along its own normal, comes off it (eq. (73)).
    """
    nodes = window(g, ex, ey, r_b - r_j)
    cos_t, sin_t, depth = g.cos[nodes], g.sin[nodes], bearing[nodes]
    a = ex * cos_t + ey * sin_t
    b = np.sqrt(np.maximum(r_j * r_j - (ex * ex + ey * ey) + a * a, 0.0))
    rho = a + b
    nx, ny = (rho * cos_t - ex) / r_j, (rho * sin_t - ey) / r_j
    cos_gamma = b / r_j
    w = (rho - r_b - depth) * cos_gamma
    if journal is not None:  # the journal's depth at the point's own angle in its frame
        w = w - periodic_value(journal, np.arctan2(ny, nx) - psi, g.dtheta)
    area = length * (r_b + depth) * g.dtheta / np.maximum(cos_gamma, 1e-12)                     # eq. (74)
    return SurfaceField(w, nx, ny, cos_gamma, area, nodes)


class WornContact(NamedTuple):
    """The contact of the worn surfaces: the penetration ``delta`` [m] the contact law
    takes, and the unit normal ``(nx, ny)`` from the bearing towards the journal."""

    delta: float
    nx: float
    ny: float


def overlap_at(g: Grid, r_j: float, r_b: float, ex: float, ey: float, psi: float, angle: float,
               bearing: np.ndarray, journal: np.ndarray | None) -> float:
    """The overlap along the journal's normal (eq. (73)) on the ray at ``angle`` [rad], the
    profiles interpolated linearly between their nodes."""
    cos_t, sin_t = math.cos(angle), math.sin(angle)
    a = ex * cos_t + ey * sin_t
    b = math.sqrt(max(r_j * r_j - (ex * ex + ey * ey) + a * a, 0.0))
    rho = a + b
    w = (rho - r_b - float(periodic_value(bearing, angle, g.dtheta))) * b / r_j
    if journal is not None:
        phi = math.atan2(rho * sin_t - ey, rho * cos_t - ex) - psi
        w -= float(periodic_value(journal, phi, g.dtheta))
    return w


def worn_contact(f: SurfaceField, g: Grid, r_j: float, r_b: float, ex: float, ey: float, psi: float,
                 bearing: np.ndarray, journal: np.ndarray | None) -> WornContact:
    """The normal is that of the resultant ``sum w_k+ n_k A_k`` of the overlaps (eq. (75)),
    the eccentricity's direction where the surfaces do not overlap; the penetration is the
    overlap on the ray along that normal (eq. (76)).  Both move continuously with the
    journal, as Newton's iterations on the contact force need."""
    q = np.maximum(f.w, 0.0) * f.area
    rx, ry = float(np.dot(q, f.nx)), float(np.dot(q, f.ny))
    r = math.sqrt(rx * rx + ry * ry)
    if r > 0.0:
        nx, ny = rx / r, ry / r
    else:
        ecc = math.sqrt(ex * ex + ey * ey)
        nx, ny = (ex / ecc, ey / ecc) if ecc > 0.0 else (1.0, 0.0)
    delta = overlap_at(g, r_j, r_b, ex, ey, psi, math.atan2(ny, nx), bearing, journal)
    return WornContact(delta, nx, ny)


def hertz_half_width(f_n: float, r_j: float, r_b: float, length: float, e_star: float) -> float:
    """The half-width ``a`` [m] of the Hertz strip of a journal in a bearing (eq. (78)):
    ``a = sqrt(4 F_N R* / (pi L E*))`` with ``R* = R_J R_B / (R_B - R_J)``."""
    r_star = r_j * r_b / (r_b - r_j)
    return math.sqrt(4.0 * f_n * r_star / (math.pi * length * e_star))


def pressure_shape(f: SurfaceField, g: Grid, pressure: str, normal: tuple[float, float], half_width: float,
                   r_b: float) -> np.ndarray:
    """The pressure's shape over the window's nodes, up to its scale: the overlap ``w+`` (``"winkler"``,
    eq. (77)) or ``sqrt(1 - (s / a)^2)`` at the arc length ``s`` from the normal's node
    (``"hertz"``, eq. (78)); at least the deepest node carries load."""
    if pressure == "winkler":
        q = np.maximum(f.w, 0.0)
    else:
        angle = np.arctan2(normal[1], normal[0])
        s = r_b * (np.mod(g.theta[f.nodes] - angle + math.pi, 2.0 * math.pi) - math.pi)
        q = np.sqrt(np.maximum(1.0 - (s / half_width) ** 2, 0.0))
    if not np.any(q > 0.0):
        q = np.zeros_like(f.w)
        q[int(np.argmax(f.w))] = 1.0
    return q


class WearStep(NamedTuple):
    """One accepted step's wear: the depth added to the bearing's and the journal's nodes
    [m] (all nodes), the bearing's nodes in contact, and the step's stability number
    ``k_D K ds`` (eq. (81); 0 for the Hertz strip, whose pressure ignores the profiles)."""

    bearing: np.ndarray
    journal: np.ndarray
    loaded: np.ndarray
    stability: float


def wear_step(f: SurfaceField, g: Grid, q: np.ndarray, f_n: float, slip: float, coefficient: float,
              wears_bearing: bool, wears_journal: bool, psi: float, ex: float, ey: float, r_j: float,
              modulus_factor: float) -> WearStep:
    """The wear of one accepted step (eqs. (77), (79), (80)).

    The pressure ``p_k = F_N q_k / |sum q_j n_j A_j|`` has the contact law's ``F_N`` as its
    resultant; each surface loses ``k_D p ds`` along its normal, ``ds`` = ``slip`` the
    relative slip of the step [m].  The bearing's radial depth grows by that over
    ``cos gamma``; the journal's node at ``phi`` takes the pressure at its own point.
    ``modulus_factor``: the law's exponent ``d ln F / d ln delta`` for the Winkler modulus
    ``K`` of eq. (81) (0: no bound, the Hertz strip).
    """
    rx, ry = float(np.dot(q * f.area, f.nx)), float(np.dot(q * f.area, f.ny))
    scale = f_n / math.sqrt(rx * rx + ry * ry)
    n = len(g.theta)
    p = np.zeros(n)
    p[f.nodes] = scale * q
    bearing, journal = np.zeros(n), np.zeros(n)
    if wears_bearing:
        bearing[f.nodes] = coefficient * slip * p[f.nodes] / f.cos_gamma
    if wears_journal:
        phi = g.theta + psi  # the journal's nodes, in the joint frame
        qx, qy = ex + r_j * np.cos(phi), ey + r_j * np.sin(phi)
        journal = coefficient * slip * periodic_value(p, np.arctan2(qy, qx), g.dtheta)
    stability = coefficient * modulus_factor * scale * slip
    return WearStep(bearing, journal, p > 0.0, stability)
