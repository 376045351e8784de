"""The reference's outputs: the columns and energies sampled on the output grid from
each phase's dense output (:class:`Result`)."""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from validation.reference._contact import Laws
from validation.reference.slider_crank.mechanism import _make_dynamics, _Mechanism
from validation.reference.slider_crank.phases import _Phase

#: The exact column names of :attr:`Result.columns` (SI units, angles in degrees).
COLUMNS = ("time", "crank_angle", "slider_x", "slider_v", "slider_a", "contact_force", "crank_moment",
           "ecc_x", "ecc_y", "penetration", "in_contact")
#: Columns of :attr:`Result.energy` [J], cumulative from t = 0.
ENERGY_COLUMNS = ("time", "kinetic", "potential", "crank_work", "contact_work")

#: Relative slack when the output grid is laid on [0, t_end]: keeps a grid point that
#: lands on t_end up to round-off.
GRID_SLACK = 1e-9

@dataclass
class Result:
    """Output of :func:`simulate`.

    Attributes
    ----------
    columns : dict of str to ndarray, shape (n,)
        Exactly the keys of :data:`COLUMNS`: ``time`` [s], ``crank_angle`` [deg],
        ``slider_x`` [m], ``slider_v`` [m/s], ``slider_a`` [m/s^2], ``contact_force``
        ``sqrt(F_N^2 + F_T^2)`` [N], ``crank_moment`` [N m], ``ecc_x``, ``ecc_y`` (journal
        centre minus bearing centre) [m], ``penetration`` ``|e| - c`` [m], ``in_contact``
        (1 inside a contact phase, from onset to release event, else 0).
    onsets : ndarray
        Times of the contact onsets [s].
    n_impacts : int
        Number of contact onsets.
    wall_time : float
        Integration time [s] (output evaluation excluded).
    n_rhs : int
        Right-hand-side evaluations, finite-difference Jacobians of implicit methods included.
    success : bool
    message : str
    energy : dict of str to ndarray, shape (n,)
        Keys of :data:`ENERGY_COLUMNS` on the output grid: kinetic and potential energy,
        the crank work ``int M omega dt`` and the contact work
        ``int (F_N delta_dot + F_T v_T) dt`` (absorbed by the contact; stored elastic
        energy included).  Energy balance: ``crank_work = Delta(kinetic + potential) +
        contact_work``.  Empty for the ideal mechanism.
    """

    columns: dict[str, np.ndarray]
    onsets: np.ndarray
    n_impacts: int
    wall_time: float
    n_rhs: int
    success: bool
    message: str
    energy: dict[str, np.ndarray] = field(default_factory=dict)

def _output_times(t_end: float, output_step: float) -> np.ndarray:
    n = int(math.floor(t_end / output_step * (1.0 + GRID_SLACK)))
    return np.minimum(np.arange(n + 1) * output_step, t_end)


def _energies(m: _Mechanism, t: float, y) -> tuple[float, float]:
    """Kinetic and potential energy of the three bodies [J]."""
    theta, phi, phi_t, x_t = m.omega * t, y[0], y[2], y[3]
    v_g2 = (m.r * m.omega) ** 2 + (m.l * phi_t / 2.0) ** 2 + m.r * m.l * m.omega * phi_t * math.cos(theta - phi)
    kinetic = 0.5 * (m.j_o * m.omega**2 + m.m_r * v_g2 + m.i_r * phi_t**2 + m.m_s * x_t**2)
    g_y = m.r * math.sin(theta) + m.l / 2.0 * math.sin(phi)
    potential = m.g * (m.m_c * m.r / 2.0 * math.sin(theta) + m.m_r * g_y)
    return kinetic, potential


def _sample(m: _Mechanism, laws: Laws, phases: list[_Phase], times: np.ndarray) -> tuple[dict, dict]:
    """Columns and energies on ``times``, each point from the dense output of its own phase."""
    starts = np.array([ph.t_start for ph in phases])
    owner = np.clip(np.searchsorted(starts, times, side="right") - 1, 0, len(phases) - 1)
    rows, energy_rows = [], []
    for k, phase in enumerate(phases):
        ts = times[owner == k]
        if len(ts) == 0:
            continue
        dyn = _make_dynamics(m, laws, phase.v0)
        ys = phase.sol(ts)
        for j, t in enumerate(ts):
            y = ys[:, j]
            phi_tt, x_tt, moment, f_n, f_t, _, ex, ey, delta = dyn(float(t), y)
            rows.append((t, y[1], y[3], x_tt, math.hypot(f_n, f_t), moment, ex, ey, delta,
                         0.0 if phase.v0 is None else 1.0))
            energy_rows.append((t, *_energies(m, float(t), y), y[4], y[5]))
    table = np.array(rows).reshape(-1, 10)
    columns = {"time": table[:, 0], "crank_angle": np.degrees(m.omega * table[:, 0])}
    columns.update(zip(COLUMNS[2:], table[:, 1:].T))
    energy = dict(zip(ENERGY_COLUMNS, np.array(energy_rows).reshape(-1, 5).T))
    return columns, energy
