"""Independent finite-difference solver of Reynolds' equation for a journal bearing of finite width.

The reference of the film laws (docs/physics.md section 10); it shares nothing with
:mod:`exuclear.film` (no import of it, none of its closed forms).  It works in the
bearing's fixed frame with the absolute angle ``alpha`` and the axial coordinate ``z``:

    film      h(alpha, t) = c - e_x cos(alpha) - e_y sin(alpha)
    Reynolds  (1/R^2) d/dalpha (h^3 dp/dalpha) + d/dz (h^3 dp/dz)
                  = 6 eta (omega_J + omega_B) dh/dalpha + 12 eta dh/dt,
              dh/dt = -(de_x/dt cos(alpha) + de_y/dt sin(alpha))

(O. Reynolds, Phil. Trans. R. Soc. 177 (1886) 157; e.g. Hamrock, Schmid, Jacobson,
Fundamentals of Fluid Film Lubrication, 2nd ed., 2004, with both surfaces
moving tangentially).  The whirl of the line of centres is not put in by hand: it enters
through ``dh/dt`` of the fixed frame.  ``p = 0`` at the bearing's ends ``z = +-B/2``,
periodic in ``alpha``; the film is symmetric in ``z`` and only ``0 <= z <= B/2`` is solved
(mirror condition at ``z = 0``).

Discretisation: vertex-centred finite differences in conservative (flux) form,
second order: ``h^3`` at the half-points ``alpha_{i+1/2}`` and the wedge term as
``(h_{i+1/2} - h_{i-1/2}) / dalpha``; one sparse matrix ``A`` (an M-matrix) with
``A p = b`` for the full film.

Cavitation, two conditions:

``"gumbel"``
    Half-Sommerfeld: the full-film solution of ``A p = b`` (negative pressures allowed),
    then its negative part set to zero before the forces are integrated.
``"reynolds"``
    Reynolds' (Swift-Stieber) condition in its complementarity form: ``p >= 0``,
    ``A p - b >= 0``, ``p (A p - b) = 0`` node by node, which is the fixed point of
    Gauss-Seidel with the projection ``p = max(p, 0)`` (Christopherson 1941).  Solved by a
    primal-dual active-set iteration (a semismooth Newton method; Hintermueller, Ito,
    Kunisch, SIAM J. Optim. 13 (2003) 865): solve on the nodes where ``p > 0`` with
    ``p = 0`` on the others, move nodes with negative pressure or negative ``A p - b``
    across, repeat until the sets stay: the exact discrete solution, in a few sparse solves.

Forces on the journal: ``F = -R integral integral p (cos(alpha), sin(alpha)) dalpha dz``
(the trapezoidal rule in both directions, spectral in the periodic ``alpha`` for a smooth
``p``).  Viscous moments from the shear stress of the film's velocity profile (Couette plus
Poiseuille; the Couette part over the whole circumference, cavitated or not):

    tau_J = eta R (omega_B - omega_J) / h - (h / (2 R)) dp/dalpha     on the journal,
    tau_B = -eta R (omega_B - omega_J) / h - (h / (2 R)) dp/dalpha    on the bearing,
    M = R^2 integral integral tau dalpha dz

with ``dp/dalpha`` by central differences of the pressure after the cavitation condition.
:func:`converged` refines the mesh by halving both steps and extrapolates (Richardson, order 2).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

CAVITATION = ("gumbel", "reynolds")
#: Active-set iterations before the Reynolds-condition solve gives up (it needs ~5-20).
MAX_ACTIVE_SET_ITERATIONS = 200


@dataclass(frozen=True)
class Bearing:
    """Journal bearing: journal radius ``R`` [m], radial clearance ``c`` [m], width ``B`` [m],
    viscosity ``eta`` [Pa s]."""

    radius: float
    clearance: float
    width: float
    viscosity: float


@dataclass(frozen=True)
class Solution:
    """Pressure field and the forces it puts on the journal.

    ``alpha`` (n_alpha,) [rad], ``z`` (n_z + 1,) [m] from 0 to ``B/2``, ``pressure``
    (n_alpha, n_z + 1) [Pa] after the cavitation condition; ``fx``, ``fy`` [N] on the
    journal; ``iterations`` of the active-set loop (0 for Guembel); ``torque_journal``,
    ``torque_bearing`` [N m] about ``+z``.
    """

    alpha: np.ndarray
    z: np.ndarray
    pressure: np.ndarray
    fx: float
    fy: float
    iterations: int
    torque_journal: float = math.nan
    torque_bearing: float = math.nan


def solve(bearing: Bearing, ex: float, ey: float, vx: float = 0.0, vy: float = 0.0, omega_journal: float = 0.0,
          omega_bearing: float = 0.0, n_alpha: int = 256, n_z: int = 32, cavitation: str = "gumbel",
          groove: float | None = None) -> Solution:
    """Pressure field for the journal at ``e = (ex, ey)`` moving at ``(vx, vy)`` [m, m/s].

    ``n_alpha`` nodes around, ``n_z`` steps from the mid-plane to the end.  ``groove``: the
    angle [rad] of an axial supply groove at ambient pressure, ``p = 0`` along the nodes
    nearest to it (Butenschoen's film starts at the largest gap: ``groove = angle of -e``);
    ``None`` for a bearing without one.
    """
    if cavitation not in CAVITATION:
        raise ValueError(f"unknown `cavitation` {cavitation!r}; known: {', '.join(CAVITATION)}")
    if math.hypot(ex, ey) >= bearing.clearance:
        raise ValueError("the journal must be off the wall, |e| < c")
    R, c, eta = bearing.radius, bearing.clearance, bearing.viscosity
    da = 2.0 * math.pi / n_alpha
    dz = 0.5 * bearing.width / n_z
    alpha = np.arange(n_alpha) * da
    z = np.arange(n_z + 1) * dz

    def gap(a):
        return c - ex * np.cos(a) - ey * np.sin(a)

    h3_half = gap(alpha + 0.5 * da) ** 3          # h^3 at alpha_{i+1/2}
    h3 = gap(alpha) ** 3
    dh_dalpha = (gap(alpha + 0.5 * da) - gap(alpha - 0.5 * da)) / da
    dh_dt = -(vx * np.cos(alpha) + vy * np.sin(alpha))
    rhs = 6.0 * eta * (omega_journal + omega_bearing) * dh_dalpha + 12.0 * eta * dh_dt   # (n_alpha,)

    # unknowns p[i, j], j = 0 .. n_z - 1 (p = 0 at j = n_z), index k = i n_z + j;
    # A = -(discrete operator), so that A is an M-matrix and A p = b with b = -rhs
    n = n_alpha * n_z
    idx = np.arange(n).reshape(n_alpha, n_z)
    i = np.repeat(np.arange(n_alpha), n_z)
    j = np.tile(np.arange(n_z), n_alpha)
    east = h3_half[i] / (R * R * da * da)             # to alpha_{i+1}
    west = h3_half[(i - 1) % n_alpha] / (R * R * da * da)
    axial = h3[i] / (dz * dz)
    up = np.where(j == 0, 2.0 * axial, axial)         # mirror at z = 0: p_{-1} = p_1
    rows = np.concatenate([idx[i, j], idx[i, j], idx[i, j], idx[i, j]])
    cols = np.concatenate([idx[i, j], idx[(i + 1) % n_alpha, j], idx[(i - 1) % n_alpha, j],
                           idx[i, np.minimum(j + 1, n_z - 1)]])
    vals = np.concatenate([east + west + 2.0 * axial, -east, -west, np.where(j + 1 < n_z, -up, 0.0)])
    down_mask = j > 0
    rows = np.concatenate([rows, idx[i, j][down_mask]])
    cols = np.concatenate([cols, idx[i, j - 1][down_mask]])
    vals = np.concatenate([vals, -axial[down_mask]])
    b = -rhs[i]
    if groove is not None:  # p = 0 on the groove's nodes: identity rows, no coupling into them
        g = int(round((groove % (2.0 * math.pi)) / da)) % n_alpha
        held = np.isin(rows, idx[g]) | np.isin(cols, idx[g])
        rows, cols, vals = rows[~held], cols[~held], vals[~held]
        rows, cols, vals = (np.concatenate([rows, idx[g]]), np.concatenate([cols, idx[g]]),
                            np.concatenate([vals, np.ones(n_z)]))
        b[idx[g]] = 0.0
    A = sp.csr_matrix((vals, (rows, cols)), shape=(n, n))

    p = spla.spsolve(A.tocsc(), b)
    iterations = 0
    if cavitation == "gumbel":
        p = np.maximum(p, 0.0)
    else:
        p, iterations = _complementarity(A, b, p)

    field = np.zeros((n_alpha, n_z + 1))
    field[:, :n_z] = p.reshape(n_alpha, n_z)
    # trapezoid in z over [0, B/2] (p = 0 at the end), doubled for the mirror half
    wz = np.full(n_z + 1, dz)
    wz[0] = wz[-1] = 0.5 * dz
    line = 2.0 * field @ wz                           # integral over z of p, (n_alpha,)
    fx = -R * da * float(np.sum(line * np.cos(alpha)))
    fy = -R * da * float(np.sum(line * np.sin(alpha)))
    h = gap(alpha)
    dp_dalpha = (np.roll(line, -1) - np.roll(line, 1)) / (2.0 * da)        # of the z-integrated pressure
    couette = eta * R * (omega_bearing - omega_journal) / h * bearing.width   # z-integrated
    poiseuille = -(h / (2.0 * R)) * dp_dalpha
    torque_journal = R * R * da * float(np.sum(couette + poiseuille))
    torque_bearing = R * R * da * float(np.sum(-couette + poiseuille))
    return Solution(alpha, z, field, fx, fy, iterations, torque_journal, torque_bearing)


def _complementarity(A: sp.csr_matrix, b: np.ndarray, p_full: np.ndarray) -> tuple[np.ndarray, int]:
    """``p >= 0, w = A p - b >= 0, p w = 0`` by a primal-dual active-set iteration."""
    diag = A.diagonal()
    active = p_full <= 0.0                            # nodes held at p = 0
    p = np.zeros_like(b)
    for iteration in range(1, MAX_ACTIVE_SET_ITERATIONS + 1):
        free = ~active
        p = np.zeros_like(b)
        p[free] = spla.spsolve(A[free][:, free].tocsc(), b[free])
        w = A @ p - b
        new_active = (p - w / diag) < 0.0             # p < 0 on free nodes, w > 0 on held ones
        if np.array_equal(new_active, active):
            return np.maximum(p, 0.0), iteration
        active = new_active
    raise RuntimeError("the active-set iteration for Reynolds' condition did not settle; refine the mesh")


def sommerfeld(bearing: Bearing, solution: Solution, omega: float, ex: float, ey: float) -> tuple[float, float]:
    """``(So, beta)`` of a solution for rotation at ``omega``: ``So = F psi^2 / (B D eta omega)``,
    ``psi = c / R``, ``beta`` [deg] between the load ``-F`` and ``e``."""
    f = math.hypot(solution.fx, solution.fy)
    psi = bearing.clearance / bearing.radius
    so = f * psi ** 2 / (bearing.width * 2.0 * bearing.radius * bearing.viscosity * abs(omega))
    beta = math.degrees(math.atan2(abs(ex * solution.fy - ey * solution.fx), -(ex * solution.fx + ey * solution.fy)))
    return so, beta


@dataclass(frozen=True)
class Converged:
    """Forces on the finest of ``levels`` meshes, their Richardson extrapolation, and the
    relative change of the force magnitude between the two finest meshes."""

    fx: float
    fy: float
    fx_fine: float
    fy_fine: float
    change: float
    extrapolation_change: float


def converged(bearing: Bearing, ex: float, ey: float, vx: float = 0.0, vy: float = 0.0, omega_journal: float = 0.0,
              omega_bearing: float = 0.0, n_alpha: int = 128, n_z: int = 16, levels: int = 3,
              cavitation: str = "gumbel", groove: float | None = None) -> Converged:
    """Solve on ``levels`` meshes, each halving both steps, and extrapolate the forces
    (Richardson, order 2, from the two finest).  ``change`` is ``|F_fine - F_coarser| /
    |F_fine|``; ``extrapolation_change`` the same for the extrapolations of the last two
    pairs (``nan`` with fewer than three levels): both estimate the error."""
    forces = []
    for level in range(levels):
        s = solve(bearing, ex, ey, vx, vy, omega_journal, omega_bearing, n_alpha * 2 ** level, n_z * 2 ** level,
                  cavitation, groove)
        forces.append(np.array([s.fx, s.fy]))
    extrapolated = [f + (f - g) / 3.0 for g, f in zip(forces[:-1], forces[1:])]
    fine = forces[-1]
    size = np.linalg.norm(fine)
    change = float(np.linalg.norm(fine - forces[-2]) / size)
    ext_change = (float(np.linalg.norm(extrapolated[-1] - extrapolated[-2]) / np.linalg.norm(extrapolated[-1]))
                  if len(extrapolated) > 1 else float("nan"))
    return Converged(float(extrapolated[-1][0]), float(extrapolated[-1][1]), float(fine[0]), float(fine[1]), change,
                     ext_change)
