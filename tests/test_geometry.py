"""Contact kinematics, section-4 loads and the contact history (pure physics)."""
from __future__ import annotations

import math

import pytest

from exuclear.geometry import contact_kinematics, joint_loads


def test_kinematics_of_a_journal_pressed_along_x(geometry):
    kin = contact_kinematics(geometry, 1.2e-4, 0.0, 0.5, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
    assert (kin.nx, kin.ny) == (1.0, 0.0)
    assert kin.delta == pytest.approx(2e-5, rel=1e-9)
    assert kin.delta_dot == 0.5
    assert kin.v_t == 0.0


def test_slip_of_a_spinning_journal(geometry):
    # n = +x, t = (0, -1); a journal spinning with omega moves its contact point by
    # omega x (R_J n) = (0, omega R_J), i.e. -omega R_J along t
    kin = contact_kinematics(geometry, 1.0e-4, 0.0, 0.0, 0.0, 2.0, 0.0, 0.0, 0.0, 0.0, 0.0)
    assert kin.v_t == pytest.approx(-2.0 * 9.9e-3)


def test_power_of_the_loads_is_the_contact_dissipation(geometry):
    # sum of F.v + M.omega over both bodies = -(F_N delta_dot + F_T v_T) for any state
    state = (1.05e-4 * math.cos(0.7), 1.05e-4 * math.sin(0.7), 0.3, -0.2, 4.0, 0.0, 0.0, 0.05, 0.1, -3.0)
    kin = contact_kinematics(geometry, *state)
    f_n, f_t = 500.0, 40.0
    loads = joint_loads(geometry, kin, f_n, f_t)
    vxj, vyj, wi, vxb, vyb, wj = state[2], state[3], state[4], state[7], state[8], state[9]
    power = loads.fx * (vxj - vxb) + loads.fy * (vyj - vyb) + loads.m_i * wi + loads.m_j * wj
    assert power == pytest.approx(-(f_n * kin.delta_dot + f_t * kin.v_t), rel=1e-12)


def test_loads_conserve_momentum_and_turn_by_the_friction_couple(geometry):
    # docs/physics.md eqs. (28)-(29): the forces on the two bodies cancel; their moments
    # about any fixed point add up to delta F_T (the friction forces act at Q_J and Q_B,
    # delta apart along n), here with both centres away from the origin
    xb, yb = 0.31, -0.02
    angle, ecc = 2.3, 1.07e-4  # delta = 7e-6 m
    xj, yj = xb + ecc * math.cos(angle), yb + ecc * math.sin(angle)
    kin = contact_kinematics(geometry, xj, yj, 0.4, 0.1, 3.0, xb, yb, -0.2, 0.05, -1.0)
    f_n, f_t = 800.0, -60.0
    loads = joint_loads(geometry, kin, f_n, f_t)
    fx_j, fy_j = -loads.fx, -loads.fy  # the bearing's force, eq. (26)
    torque = (xj * loads.fy - yj * loads.fx + loads.m_i) + (xb * fy_j - yb * fx_j + loads.m_j)
    # round-off: lever arms of 0.3 m times forces of 800 N, relative 1e-16, against 4e-4 N m
    assert torque == pytest.approx(kin.delta * f_t, rel=1e-9, abs=1e-12)
    assert kin.delta == pytest.approx(7e-6, rel=1e-9)
