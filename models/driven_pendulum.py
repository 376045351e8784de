"""The driven damped pendulum of Baker and Gollub: a model whose periodic, period-doubled
and chaotic windows are textbook, for checking the nonlinear tools (:mod:`exuclear.nonlinear`).

::

        o  pivot
         \\
          \\  theta           theta'' + theta' / q + sin(theta) = g cos(omega_D t)
           \\
            O  bob            q = 2, omega_D = 2/3; forcing amplitude g

Dimensionless: time in units of the inverse small-oscillation frequency, the torque in
units of ``m g L``.  G. L. Baker and J. P. Gollub, *Chaotic Dynamics: an Introduction*,
2nd ed., Cambridge University Press (1996), chapter 3: with ``q = 2`` and
``omega_D = 2/3``, ``g = 0.9`` is periodic with the drive's period, ``g = 1.07`` period
two, ``g = 1.15`` and ``g = 1.5`` chaotic (their bifurcation diagram over ``g``).

Built in Exudyn as one ODE2 coordinate (``NodeGenericODE2``) with unit mass, damping
``1 / q`` and the forcing and gravity torque as a Python force user function
(``ObjectGenericODE2``), so it runs with the explicit solvers and without constraints.
"""
from __future__ import annotations

import math
from functools import partial

import exudyn as exu
import numpy as np
from exudyn.itemInterface import NodeGenericODE2, ObjectGenericODE2

from exuclear import SolverSettings
from exuclear.nonlinear import Driven

#: Baker and Gollub's damping quality factor and drive frequency.
Q = 2.0
DRIVE_FREQUENCY = 2.0 / 3.0
#: Parameters of :func:`driven` and their defaults: the forcing amplitude ``g``, ``q``,
#: ``omega_D`` and the initial angle and rate.
PARAMETERS = {"forcing": 1.07, "q": Q, "drive_frequency": DRIVE_FREQUENCY, "theta0": 0.0, "omega0": 0.0}
#: Solver settings: DOPRI5 at rtol 1e-9; the section samples then agree with a SciPy
#: DOP853 integration at rtol 1e-12 to 1e-6 over 100 periods of a periodic response
#: (tests/test_nonlinear_pendulum.py), far below the distances between the points of a
#: period-2 orbit (0.07 in theta').  Largest step 0.05, a hundredth of the natural period.
SETTINGS = SolverSettings(end_time=1.0, method="dopri5", step=0.05, rtol=1e-9, atol=1e-11)


def build(mbs: exu.MainSystem, copy: int = 0, *, forcing: float = PARAMETERS["forcing"], q: float = Q,
          drive_frequency: float = DRIVE_FREQUENCY, theta0: float = 0.0, omega0: float = 0.0) -> int:
    """Add one pendulum to ``mbs``; returns its node (one coordinate, the angle [rad]).
    ``copy`` is not used: the pendulum names no item."""
    node = mbs.AddNode(NodeGenericODE2(referenceCoordinates=[0.0], initialCoordinates=[theta0],
                                       initialCoordinates_t=[omega0], numberOfODE2Coordinates=1))

    def torque(mbs: exu.MainSystem, t: float, item: int, coordinates: list, rates: list) -> list:
        return [forcing * math.cos(drive_frequency * t) - math.sin(coordinates[0])]

    mbs.AddObject(ObjectGenericODE2(nodeNumbers=[node], massMatrix=np.eye(1), dampingMatrix=np.eye(1) / q,
                                    forceUserFunction=torque))
    return node


def observe(mbs: exu.MainSystem, node: int) -> dict[str, float]:
    """The section's quantities: the angular rate ``omega`` (Baker and Gollub's bifurcation
    diagram), and ``cos`` and ``sin`` of the angle (a turning pendulum's angle grows
    without bound, its cosine and sine do not)."""
    theta = float(mbs.GetNodeOutput(node, exu.OutputVariableType.Coordinates))
    rate = float(mbs.GetNodeOutput(node, exu.OutputVariableType.Coordinates_t))
    return {"omega": rate, "cos": math.cos(theta), "sin": math.sin(theta)}


def driven(values: dict) -> Driven:
    """The pendulum at the parameters ``values`` (names of :data:`PARAMETERS`) for
    :mod:`exuclear.nonlinear`: period ``2 pi / omega_D``, :data:`SETTINGS`."""
    unknown = sorted(set(values) - set(PARAMETERS))
    if unknown:
        raise ValueError(f"unknown parameters {unknown} of the driven pendulum; known: {', '.join(PARAMETERS)}")
    p = {**PARAMETERS, **values}
    for name in ("q", "drive_frequency"):
        if not p[name] > 0.0:
            raise ValueError(f"`{name}` must be positive, got {p[name]}")
    return Driven(partial(build, **p), SETTINGS, 2.0 * math.pi / p["drive_frequency"], observe=observe, params=p)
