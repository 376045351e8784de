"""The slider-crank's mechanism and equations of motion (docs/physics.md section 6.2), and
the closed form of the ideal mechanism.

::

        Y
        ^          A = r (cos theta, sin theta)
        |         o.
        |  crank /   '.  rod (length l, absolute angle phi)
        |    r  /      '.
        |      / theta   '.   B_J = A + l (cos phi, sin phi): journal centre
        O-----o-----------'(o)__    bearing centre (x, 0) in the slider
      ground pivot          [slider]=====> X   (frictionless guide, y = 0)

Minimal coordinates: the crank angle is prescribed, ``theta = omega t``; the free
coordinates are the rod's absolute angle ``phi`` and the slider position ``x``.  The
clearance joint B (journal on the rod, bearing in the slider) decouples rod and slider,
so the mass matrix of ``(phi, x)`` is diagonal:

``T = J_O omega^2 / 2 + m_r |v_G|^2 / 2 + I_r phi_t^2 / 2 + m_s x_t^2 / 2`` with the crank
inertia about O ``J_O = I_c + m_c r^2 / 4``, the rod centre of mass
``G = A + (l/2)(cos phi, sin phi)`` and
``|v_G|^2 = r^2 omega^2 + (l^2/4) phi_t^2 + r l omega phi_t cos(theta - phi)``;
``V = m_c g (r/2) sin theta + m_r g G_y``.  Lagrange's equations (``theta_tt = 0``):

``J_A phi_tt - m_r (l/2) r omega^2 sin(theta - phi) = -m_r g (l/2) cos phi + Q_phi``,
``J_A = I_r + m_r l^2 / 4`` (the rod about A);

``m_s x_tt = Q_x``.

Contact (docs/physics.md sections 1-4, :mod:`validation.reference._contact`): eccentricity
``e = B_J - (x, 0)``, journal body the rod (angular velocity ``phi_t``), bearing body
the slider (no rotation).  The force ``F_i`` on the journal and the moment ``M_i`` on the
rod give, by virtual work with ``dB_J/dphi = l (-sin phi, cos phi)`` and
``dP_B/dx = (1, 0)``,

``Q_phi = F_i . l (-sin phi, cos phi) + M_i``,   ``Q_x = -F_i,x``.

The slider's moment ``M_j`` is taken by its guide and does no work.  The contact power
on the bodies is then ``-(F_N delta_dot + F_T v_T)``, the energy absorbed by the contact.

Two quadrature states ride along with the four mechanical ones: the crank work
``int M omega dt`` and the contact work ``int (F_N delta_dot + F_T v_T) dt`` (for the
energy audit of :attr:`.outputs.Result.energy`); the integration is piecewise
(:mod:`.phases`).
"""
from __future__ import annotations

import math
from collections.abc import Callable
from typing import NamedTuple

import numpy as np

from exuclear.models.slider_crank import SliderCrankParams
from validation.reference._contact import Laws, build_laws, contact_kinematics, journal_loads

#: Methods that need a Jacobian; they get the one of :func:`_make_jacobian`.
IMPLICIT_METHODS = ("Radau", "BDF", "LSODA")
#: Relative finite-difference step of that Jacobian: sqrt(machine epsilon), the usual
#: balance of truncation and round-off for forward differences.
FD_STEP = float(np.sqrt(np.finfo(float).eps))

# state vector: phi, x, phi_t, x_t, crank work, contact work; the first four are the
# mechanical states, the last two quadratures that the right-hand side never reads
_N_MECHANICAL, _N_STATE = 4, 6


class _Mechanism(NamedTuple):
    """Constants of the mechanism (SI), read once from the params."""

    r: float
    l: float
    omega: float
    m_c: float
    m_r: float
    m_s: float
    i_r: float
    j_a: float      # rod inertia about A, I_r + m_r l^2 / 4
    j_o: float      # crank inertia about O, I_c + m_c r^2 / 4
    g: float
    r_j: float
    r_b: float
    c: float


def _mechanism(p: SliderCrankParams) -> _Mechanism:
    r, l = p.crank_length, p.rod_length
    return _Mechanism(r=r, l=l, omega=p.crank_speed, m_c=p.crank_mass, m_r=p.rod_mass, m_s=p.slider_mass,
                      i_r=p.rod_inertia, j_a=p.rod_inertia + p.rod_mass * l * l / 4.0,
                      j_o=p.crank_inertia + p.crank_mass * r * r / 4.0, g=p.gravity,
                      r_j=p.bearing_radius - p.clearance, r_b=p.bearing_radius, c=p.clearance)


def _laws(p: SliderCrankParams) -> Laws:
    if p.viscosity is not None:  # the reference has the dry joint's laws only: never treat oil as dry
        raise ValueError(f"the SciPy reference models the dry joint; got `viscosity` {p.viscosity} (an oil film)")
    return build_laws(journal_radius=p.bearing_radius - p.clearance, bearing_radius=p.bearing_radius,
                      length=p.bearing_length, law=p.law, cr=p.cr, journal_material=p.journal_material,
                      bearing_material=p.bearing_material, friction=p.friction, v_min=p.v_min)

def _eccentricity(m: _Mechanism, t: float, y) -> tuple[float, float, float, float]:
    """``e = B_J - (x, 0)`` and ``e_t`` from the state ``y = (phi, x, phi_t, x_t, ...)``."""
    theta = m.omega * t
    ct, st = math.cos(theta), math.sin(theta)
    cp, sp = math.cos(y[0]), math.sin(y[0])
    return (m.r * ct + m.l * cp - y[1], m.r * st + m.l * sp,
            -m.r * m.omega * st - m.l * y[2] * sp - y[3], m.r * m.omega * ct + m.l * y[2] * cp)


def _crank_moment(m: _Mechanism, theta: float, phi: float, phi_t: float, phi_tt: float,
                 fx_i: float, fy_i: float) -> float:
    """Crank driving moment that keeps ``theta_tt = 0`` [N m].

    Lagrange's equation of the crank angle, with the whole kinetic energy ``T`` of the
    module docstring (``theta`` now free, ``M`` its generalized force):

    ``d/dt dT/dtheta_t - dT/dtheta + dV/dtheta = M + Q_theta``, where
    ``dT/dtheta_t = (J_O + m_r r^2) theta_t + m_r (r l / 2) phi_t cos(theta - phi)``,
    ``dT/dtheta = -m_r (r l / 2) theta_t phi_t sin(theta - phi)`` and
    ``dV/dtheta = (m_c / 2 + m_r) g r cos theta``.  With ``theta_tt = 0``:

    ``M = m_r (r l / 2) (phi_tt cos(theta - phi) + phi_t^2 sin(theta - phi))
    + (m_c / 2 + m_r) g r cos theta - Q_theta``,

    ``Q_theta = F_i . dB_J/dtheta = r (-F_i,x sin theta + F_i,y cos theta)``: the joint
    force on the rod end, which moves with A.  The rod's coupling enters through
    ``phi_tt``, ``phi_t`` and ``F_i``.

    Parameters
    ----------
    m : _Mechanism
    theta, phi, phi_t, phi_tt : float
        Crank angle [rad], rod angle [rad], its rate [rad/s] and acceleration [rad/s^2].
    fx_i, fy_i : float
        Force on the rod end B_J (the journal) [N].
    """
    s, c = math.sin(theta - phi), math.cos(theta - phi)
    coupling = m.m_r * m.r * m.l / 2.0 * (phi_tt * c + phi_t * phi_t * s)
    gravity = (m.m_c / 2.0 + m.m_r) * m.g * m.r * math.cos(theta)
    q_theta = m.r * (-fx_i * math.sin(theta) + fy_i * math.cos(theta))
    return coupling + gravity - q_theta


def _make_dynamics(m: _Mechanism, laws: Laws, v0: float | None) -> Callable:
    """``dyn(t, y) -> (phi_tt, x_tt, M, f_n, f_t, power, e_x, e_y, delta)`` of one phase.

    ``v0 is None``: free flight, no contact force.  Otherwise contact with onset rate v0;
    ``power = F_N delta_dot + F_T v_T`` is the power absorbed by the contact.
    """
    r, l, w, m_r, m_s, j_a, g = m.r, m.l, m.omega, m.m_r, m.m_s, m.j_a, m.g
    r_j, r_b, c = m.r_j, m.r_b, m.c
    normal_force, mu, frictional = laws.normal_force, laws.friction_coefficient, laws.frictional
    in_contact = v0 is not None

    def dyn(t: float, y) -> tuple:
        theta = w * t
        ct, st = math.cos(theta), math.sin(theta)
        phi, phi_t = y[0], y[2]
        cp, sp = math.cos(phi), math.sin(phi)
        ex, ey = r * ct + l * cp - y[1], r * st + l * sp
        f_n = f_t = power = fx = fy = m_i = 0.0
        delta = math.hypot(ex, ey) - c
        if in_contact and delta > 0.0:
            vex, vey = -r * w * st - l * phi_t * sp - y[3], r * w * ct + l * phi_t * cp
            delta, delta_dot, v_t, nx, ny = contact_kinematics(ex, ey, vex, vey, phi_t, 0.0, r_j, r_b, c)
            f_n = normal_force(delta, delta_dot, v0)
            f_t = mu(v_t) * f_n if frictional else 0.0
            fx, fy, m_i, _ = journal_loads(nx, ny, f_n, f_t, r_j, r_b)  # M_j goes to the guide
            power = f_n * delta_dot + f_t * v_t
        q_phi = -m_r * g * l / 2.0 * cp + l * (-sp * fx + cp * fy) + m_i
        phi_tt = (q_phi + m_r * l / 2.0 * r * w * w * math.sin(theta - phi)) / j_a
        x_tt = -fx / m_s
        moment = _crank_moment(m, theta, phi, phi_t, phi_tt, fx, fy)
        return phi_tt, x_tt, moment, f_n, f_t, power, ex, ey, delta

    return dyn


class _Counter:
    """Counts right-hand-side calls of all phases."""

    def __init__(self) -> None:
        self.calls = 0


def _make_rhs(m: _Mechanism, dyn: Callable, counter: _Counter) -> Callable:
    w = m.omega

    def rhs(t: float, y) -> list[float]:
        counter.calls += 1
        phi_tt, x_tt, moment, _, _, power, _, _, _ = dyn(t, y)
        return [y[2], y[3], phi_tt, x_tt, moment * w, power]

    return rhs


def _make_jacobian(m: _Mechanism, rhs: Callable) -> Callable:
    """Forward-difference Jacobian for the implicit methods.

    Only the four mechanical columns are differenced, with steps ``FD_STEP *
    max(|y_j|, scale_j)`` on the scales (1 rad, l, omega, r omega); the quadrature
    columns are exactly zero.  (SciPy's own ``num_jac`` keeps enlarging its step on
    those columns, whose differences stay zero, until it overflows.)
    """
    scales = (1.0, m.l, m.omega, m.r * m.omega)

    def jac(t: float, y) -> np.ndarray:
        f0 = np.asarray(rhs(t, y))
        out = np.zeros((_N_STATE, _N_STATE))
        for j in range(_N_MECHANICAL):
            h = FD_STEP * max(abs(y[j]), scales[j])
            yh = np.array(y, dtype=float)
            yh[j] += h
            out[:, j] = (np.asarray(rhs(t, yh)) - f0) / h
        return out

    return jac

# --------------------------------------------------------------------------------------
# ideal mechanism
# --------------------------------------------------------------------------------------
def ideal_kinematics(params: SliderCrankParams, t) -> dict[str, np.ndarray]:
    """Closed-form ideal slider-crank (ideal revolute joint at B, clearance 0).

    ``sin phi = -(r/l) sin theta``, ``x = r cos theta + l cos phi =
    r cos theta + sqrt(l^2 - r^2 sin^2 theta)``; differentiating
    ``l sin phi = -r sin theta`` twice (``theta_t = omega``, ``theta_tt = 0``):
    ``phi_t = -r omega cos theta / (l cos phi)``,
    ``phi_tt = (r omega^2 sin theta + l phi_t^2 sin phi) / (l cos phi)``,
    ``x_t = -r omega sin theta - l phi_t sin phi``,
    ``x_tt = -r omega^2 cos theta - l (phi_tt sin phi + phi_t^2 cos phi)``.

    Crank moment by the energy balance ``M omega = d(T + V)/dt`` with
    ``dT/dt = m_r v_G . a_G + I_r phi_t phi_tt + m_s x_t x_tt`` (the crank's own kinetic
    energy is constant) and ``dV/dt = m_r g v_G,y + m_c g (r/2) omega cos theta``.

    ``contact_force`` is the magnitude of the ideal joint's force ``R`` on the rod end:
    ``R_x = -m_s x_tt`` (the slider's equation) and ``R_y`` from the rod's moment balance
    about A, ``l (cos phi R_y - sin phi R_x) = I_r phi_tt + m_r (G - A) x a_G +
    m_r g (G - A)_x``.  ``ecc_x``, ``ecc_y`` and ``penetration`` are 0; ``in_contact`` is
    1 (the ideal joint always carries its force).

    Parameters
    ----------
    params : SliderCrankParams
    t : array_like, shape (n,)
        Times [s].

    Returns
    -------
    dict of str to ndarray, shape (n,)
        The columns of :data:`COLUMNS`.
    """
    m = _mechanism(params)
    t = np.asarray(t, dtype=float)
    theta = m.omega * t
    st, ct = np.sin(theta), np.cos(theta)
    sp = -m.r / m.l * st
    cp = np.sqrt(1.0 - sp * sp)
    phi_t = -m.r * m.omega * ct / (m.l * cp)
    phi_tt = (m.r * m.omega**2 * st + m.l * phi_t**2 * sp) / (m.l * cp)
    x = m.r * ct + m.l * cp
    x_t = -m.r * m.omega * st - m.l * phi_t * sp
    x_tt = -m.r * m.omega**2 * ct - m.l * (phi_tt * sp + phi_t**2 * cp)
    # rod centre of mass: G - A = (l/2)(cos phi, sin phi)
    h = m.l / 2.0
    vg_x, vg_y = -m.r * m.omega * st - h * phi_t * sp, m.r * m.omega * ct + h * phi_t * cp
    ag_x = -m.r * m.omega**2 * ct - h * (phi_tt * sp + phi_t**2 * cp)
    ag_y = -m.r * m.omega**2 * st + h * (phi_tt * cp - phi_t**2 * sp)
    power = (m.m_r * (vg_x * ag_x + vg_y * ag_y) + m.i_r * phi_t * phi_tt + m.m_s * x_t * x_tt
             + m.g * (m.m_r * vg_y + m.m_c * m.r / 2.0 * m.omega * ct))
    r_x = -m.m_s * x_tt
    moment_a = m.i_r * phi_tt + m.m_r * h * (cp * ag_y - sp * ag_x) + m.m_r * m.g * h * cp
    r_y = (moment_a / m.l + sp * r_x) / cp
    zeros = np.zeros_like(t)
    return {"time": t, "crank_angle": np.degrees(theta), "slider_x": x, "slider_v": x_t, "slider_a": x_tt,
            "contact_force": np.hypot(r_x, r_y), "crank_moment": power / m.omega, "ecc_x": zeros,
            "ecc_y": zeros.copy(), "penetration": zeros.copy(), "in_contact": np.ones_like(t)}
