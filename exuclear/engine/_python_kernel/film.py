"""The oil film of a lubricated joint (:class:`Film`, docs/physics.md section 10): one more kind
of contact, without history, whose law is :mod:`exuclear.film`.  The compiled kernel's
``film.hpp``."""
from __future__ import annotations

from dataclasses import replace
from typing import NamedTuple

from ...film import FilmLaw, FilmLoad
from ...history import ContactState
from .kinematics import V3, SliceKinematics


class FilmInput(NamedTuple):
    """What the film law takes (:meth:`exuclear.film.FilmLaw.blended_load`): the eccentricity
    ``e`` [m] in the bearing's joint frame, ``de/dt`` [m/s] as the connector hands it over
    (``A0^T (v1 - v0)``: the inertial derivative in the bearing frame's components, without
    the frame-rotation term), and the spins [rad/s] of journal and bearing about the axis.
    With that velocity the absolute spins are the consistent pair: ``dphi/dt`` is then the
    inertial angle rate of ``e``, and ``omega_eff = omega_J + omega_B - 2 dphi/dt`` equals
    ``omega_J - omega_B - 2 dphi_rel/dt`` of the bearing's rotating frame (docs/physics.md
    section 10.8, eq. (56))."""

    ex: float
    ey: float
    vx: float
    vy: float
    omega_journal: float
    omega_bearing: float


class Film:
    """The oil film of a lubricated joint (docs/physics.md section 10): one more kind of
    contact, without history, acting at every eccentricity (at the blended one of eq. (70)
    near the wall), added to the dry contact's loads (the compiled kernel's ``FILM``)."""

    def __init__(self, film: FilmLaw, share: float = 1.0) -> None:
        self.law, self.share = film, share

    def load(self, kin: FilmInput) -> FilmLoad:
        """Film force on the journal and viscous moments, eqs. (68)-(70)."""
        return self.law.blended_load(kin.ex, kin.ey, kin.vx, kin.vy, kin.omega_journal, kin.omega_bearing)

    def add_loads(self, loads: list[float], r: FilmLoad) -> None:
        """``F = -F_film`` on the bearing, ``T = -M_J``, and the bearing's moment beyond
        ``T``, ``M_B + M_J`` (as the planar slice's, eqs. (24)-(26))."""
        loads[0] += -r.fx
        loads[1] += -r.fy
        loads[5] += -r.torque_journal
        loads[8] += r.torque_bearing + r.torque_journal

    def add_slice_loads(self, loads: list[float], u: V3, kin: SliceKinematics, r: FilmLoad) -> None:
        """A spatial slice's share ``w / L`` of the film (docs/physics.md section 10.8): ``-F``
        on the bearing at the slice's axis point, ``F`` on the journal at ``c = p + s u``, the
        viscous moments about the bearing axis: ``T = s u x (-F) - M_J z``, and the bearing's
        moment beyond ``T`` (before ``p x F``), ``e x F + (M_B + M_J) z``."""
        w = self.share
        fx, fy, m_j, m_b = w * r.fx, w * r.fy, w * r.torque_journal, w * r.torque_bearing
        sx, sy, sz = kin.s * u[0], kin.s * u[1], kin.s * u[2]
        loads[0] += -fx
        loads[1] += -fy
        loads[3] += sz * fy                     # (s u) x (-F), F in the plane
        loads[4] += -sz * fx
        loads[5] += -(sx * fy - sy * fx) - m_j
        loads[8] += (kin.ex * fy - kin.ey * fx) + (m_b + m_j)

    def with_outputs(self, state: ContactState, kin: FilmInput) -> ContactState:
        """``state`` with the film's outputs at ``kin`` (the data node's film columns): a
        slice's share of the force and of the journal's moment."""
        r = self.load(kin)
        w = self.share
        return replace(state, film_fx=w * r.fx, film_fy=w * r.fy, film_torque=w * r.torque_journal)



def slice_film_input(kin: SliceKinematics, p: V3, u: V3, dv: V3, dw: V3, w_j: V3) -> FilmInput:
    """A spatial slice's film input (docs/physics.md section 10.8): the eccentricity of its
    axis point ``c = p + s u`` and its rate in the bearing's rotating frame, ``dv - w_j x p +
    dw x s u`` (the ``w`` of eq. (38)), with the journal's spin relative to the bearing
    ``dw . u`` and the bearing's 0: the rotating frame's pair (the planar joint takes the
    inertial one; both give the same ``omega_eff``)."""
    su = (kin.s * u[0], kin.s * u[1], kin.s * u[2])
    wx = dv[0] - (w_j[1] * p[2] - w_j[2] * p[1]) + (dw[1] * su[2] - dw[2] * su[1])
    wy = dv[1] - (w_j[2] * p[0] - w_j[0] * p[2]) + (dw[2] * su[0] - dw[0] * su[2])
    return FilmInput(kin.ex, kin.ey, wx, wy, dw[0] * u[0] + dw[1] * u[1] + dw[2] * u[2], 0.0)
