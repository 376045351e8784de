"""Analytic values (static and step-load penetration) and the energy audits of the hard cases."""
from __future__ import annotations

import math
from collections.abc import Sequence
from typing import NamedTuple

import exudyn as exu
import numpy as np
from exudyn.itemInterface import SensorNode
from scipy.integrate import quad
from scipy.optimize import brentq

import exuclear
from exuclear.models import slider_crank as sc_model
from exuclear.models.journal_bearing import JournalBearingParams
from exuclear.models.scene import Scene
from exuclear.models.slider_crank import FLYWHEEL_INERTIA
from validation.hard_cases.common import AUDIT_LIMIT

# =======================================================================================
# analytic values
# =======================================================================================


def static_penetration(law: exuclear.ContactLaw, load: float) -> float:
    """``delta_s`` [m] with ``F_el(delta_s) = load`` [N], by Brent's method on ``(0, c]``.

    ``F_el(delta) = K_eff(delta) delta^n`` rises monotonically from 0 for every law of
    :mod:`exuclear.contact`; a load beyond ``F_el(c)`` raises ``ValueError``.
    """
    c = law.geometry.clearance
    if not 0.0 < load < law.elastic_force(c):
        raise ValueError(f"`load` must lie in (0, F_el(c) = {law.elastic_force(c):.3g} N), got {load}")
    return brentq(lambda d: law.elastic_force(d) - load, 0.0, c, xtol=1e-15 * c, rtol=1e-14)


def elastic_energy(law: exuclear.ContactLaw, delta: float) -> float:
    """``E_el(delta) = int_0^delta F_el`` [J]: the energy stored elastically (0 for delta <= 0)."""
    if delta <= 0.0:
        return 0.0
    return quad(law.elastic_force, 0.0, delta, epsabs=0.0, epsrel=1e-12)[0]


def step_load_penetration(law: exuclear.ContactLaw, load: float) -> float:
    """Largest penetration of an elastic contact set down at rest under ``load`` [N]:
    the root of ``load delta = E_el(delta)`` beyond ``delta_s`` [m]."""
    d_s = static_penetration(law, load)
    hi = 2.0 * d_s
    while load * hi > elastic_energy(law, hi):
        hi *= 2.0
    return brentq(lambda d: load * d - elastic_energy(law, d), d_s, hi, xtol=1e-15 * hi, rtol=1e-14)


# =======================================================================================
# energy audits
# =======================================================================================


class Audit(NamedTuple):
    """Energy balance of a run [J]: ``work = change + stored + dissipated + residual``.

    ``gross`` is the work the contact forces did in and out, ``int |F_N delta_dot +
    F_T v_T| dt``; ``scale`` the energy the residual is judged against: ``gross`` for the
    slider-crank, the work of gravity for the journal under gravity.  ``floor`` [J] is
    what the measurement of ``work`` cannot resolve (the flywheel's round-off,
    :func:`audit_minimal`; 0 elsewhere).
    """

    work: float
    change: float
    stored: float
    dissipated: float
    gross: float
    residual: float
    scale: float
    floor: float = 0.0

    @property
    def absorbed(self) -> float:
        return self.stored + self.dissipated

    @property
    def relative(self) -> float:
        return self.residual / self.scale

    @property
    def passed(self) -> bool:
        return abs(self.residual) <= AUDIT_LIMIT * abs(self.scale) + self.floor


def _contact_energy(handle: exuclear.ClearanceJointHandle, in_penetration: bool = False) -> tuple[float, float, float]:
    """Elastic energy stored at the end, the rest of the energy one joint absorbed, and the
    gross work of its forces [J].

    ``in_penetration`` False: the dissipated power ``(F_N - F_el) delta_dot + F_T v_T`` by
    the trapezoid rule in time (the elastic part is a function of the state, exact).
    True: the normal work ``sum (F_N,k + F_N,k+1) / 2 (delta_k+1 - delta_k)``, which is the
    work the trapezoidal family (generalized-alpha at spectral radius 1) does in its own
    discrete energy balance (``dT = F_avg . dq``), and the friction in time.
    """
    out = handle.outputs()
    law = handle.joint.law
    delta, f_n, t = out["penetration"], out["normal_force"], out["time"]
    stored = elastic_energy(law, float(delta[-1])) - elastic_energy(law, float(delta[0]))
    friction_power = out["tangential_force"] * out["slip_velocity"]
    gross = float(np.trapezoid(np.abs(f_n * out["penetration_rate"] + friction_power), t))
    friction = float(np.trapezoid(friction_power, t))
    if in_penetration:
        normal = float(np.sum(0.5 * (f_n[1:] + f_n[:-1]) * np.diff(delta)))
        return stored, normal - stored + friction, gross
    elastic = np.array([law.elastic_force(d) for d in delta])
    return stored, float(np.trapezoid((f_n - elastic) * out["penetration_rate"], t)) + friction, gross


def _audit(work: float, change: float, joints: Sequence[exuclear.ClearanceJointHandle], *, scale: float | None = None,
           floor: float = 0.0, in_penetration: bool = False) -> Audit:
    terms = [_contact_energy(h, in_penetration) for h in joints]
    stored, dissipated, gross = (sum(t[k] for t in terms) for k in range(3))
    residual = work - change - stored - dissipated
    return Audit(work, change, stored, dissipated, gross, residual, gross if scale is None else scale, floor)


def flywheel_roundoff(omega: float, steps: int) -> float:
    """What the flywheel's energy cannot resolve over ``steps`` steps [J].

    The crank speed changes by ~1e-12 of itself per step, so every step rounds the
    increment to the spacing ``ulp(omega)`` of doubles; ``steps`` roundings of up to half a
    spacing add up like a random walk, ``ulp / 2 sqrt(steps)``, and ``J_fly omega`` turns a
    speed error into an energy error.  The bound is 4 of those standard deviations (the
    walk is not quite random: the audit rows of ``python -m validation.hard_cases`` show
    residuals of 1-2 of them).
    """
    return 4.0 * FLYWHEEL_INERTIA * abs(omega) * float(np.spacing(abs(omega))) / 2.0 * math.sqrt(steps)


def audit_minimal(model: Scene, steps: int) -> Audit:
    """Energy audit of a minimal-coordinate slider-crank run (outputs at every step).

    Kinetic and potential energy of crank (its own inertia), rod and slider from
    :func:`exuclear.models.slider_crank.mechanical_energy`.  The drive work is what the flywheel gave up,
    ``-J_fly (omega_end^2 - omega_0^2) / 2``:
    exact, but only to the round-off of :func:`flywheel_roundoff` (some 1e-5 J at 500
    rpm).  (The trapezoid rule on the recorded crank moment misses by 4 to 30 %: the
    moment varies by its own size within one step at an impact.)
    """
    p = model.params
    _, energy, thd = sc_model.mechanical_energy(model)
    work = -0.5 * FLYWHEEL_INERTIA * (thd[-1] - thd[0]) * (thd[-1] + thd[0])
    return _audit(work, float(energy[-1] - energy[0]), list(model.joints.values()),
                  floor=flywheel_roundoff(p.crank_speed, steps))


def _add_body_sensors(model: Scene) -> dict[str, tuple[int, int]]:
    """Position and velocity sensors (x, y, phi) of crank, rod and slider of a redundant model.

    Crank and slider nodes are those of the model's own sensors; the rod's node is the
    journal node of joint B, or the bearing node of joint A.
    """
    mbs = model.mbs
    crank = int(mbs.GetSensor(model.sensors["crank"])["nodeNumber"])
    slider = int(mbs.GetSensor(model.sensors["slider_x"])["nodeNumber"])
    rods = {n for h in model.joints.values() for n in h.nodes} - {crank, slider}
    if len(rods) != 1:
        raise ValueError("the rod's node is found through a clearance joint at A or B")
    store = dict(storeInternal=True, writeToFile=False)
    sensors = {}
    for name, node in (("crank", crank), ("rod", rods.pop()), ("slider", slider)):
        sensors[name] = tuple(int(mbs.AddSensor(SensorNode(nodeNumber=node, outputVariableType=kind, **store)))
                              for kind in (exu.OutputVariableType.Coordinates, exu.OutputVariableType.Coordinates_t))
    mbs.Assemble()
    return sensors


def audit_redundant(model: Scene, sensors: dict[str, tuple[int, int]]) -> Audit:
    """Energy audit of a redundant-coordinate slider-crank run (outputs at every step).

    Bodies' energies from their node sensors (:func:`_add_body_sensors`): the nodes sit
    at the centres of mass.  Drive work ``int M omega dt`` by the trapezoid rule, with
    the moment from the drive constraint's multiplier and omega held exactly; contact
    work in the generalized-alpha method's own terms (see :func:`_contact_energy`).
    """
    p, mbs = model.params, model.mbs
    masses = {"crank": (p.crank_mass, p.crank_inertia), "rod": (p.rod_mass, p.rod_inertia),
              "slider": (p.slider_mass, 0.0)}  # the slider does not rotate
    energy = 0.0
    for name, (pos, vel) in sensors.items():
        m, inertia = masses[name]
        q, v = np.asarray(mbs.GetSensorStoredData(pos)), np.asarray(mbs.GetSensorStoredData(vel))
        y0 = mbs.GetNodeParameter(int(mbs.GetSensor(pos)["nodeNumber"]), "referenceCoordinates")[1]
        energy = energy + 0.5 * m * (v[:, 1] ** 2 + v[:, 2] ** 2) + 0.5 * inertia * v[:, 3] ** 2 \
            + m * p.gravity * (y0 + q[:, 2])
    drive = np.asarray(mbs.GetSensorStoredData(model.sensors["moment"]))
    # the multiplier is the constraint's reaction on the crank: the drive is its negative
    work = float(np.trapezoid(-drive[:, 1] * p.crank_speed, drive[:, 0]))
    return _audit(work, float(energy[-1] - energy[0]), list(model.joints.values()), in_penetration=True)


def audit_journal(params: JournalBearingParams, handle: exuclear.ClearanceJointHandle) -> Audit:
    """Energy audit of the journal under gravity: gravity's work ``m g (x_end - x_0)`` =
    kinetic energy + absorbed; the journal moves along X only, ``e = (x, 0)``, so its
    speed is ``delta_dot`` (sign of ``x`` aside).  Relative to the work of gravity."""
    out = handle.outputs()
    x, rate = out["ecc_x"], out["penetration_rate"]
    v = np.where(x < 0.0, -rate, rate)
    work = params.mass * params.gravity * float(x[-1] - x[0])
    change = 0.5 * params.mass * float(v[-1] ** 2 - v[0] ** 2)
    return _audit(work, change, [handle], scale=work)


def _audit_text(a: Audit, label: str = "audit") -> str:
    bound = f"1 % + flywheel round-off {a.floor / a.scale:.2%}" if a.floor else "1 %"
    return (f"{label} residual {a.relative:+.2%} of the {a.gross * 1e3:.4g} mJ the contact exchanged (bound {bound}; "
            f"{a.residual / a.absorbed:+.2%} of the {a.absorbed * 1e3:.4g} mJ absorbed)")


def _finite(*tables: dict[str, np.ndarray]) -> bool:
    return all(bool(np.all(np.isfinite(v))) for t in tables for v in t.values())
