"""The slider-crank for the nonlinear tools (:mod:`exuclear.nonlinear`): :func:`driven`
makes the minimal formulation at a parameter set a :class:`~exuclear.nonlinear.Driven`,
whose period is the crank's, ``2 pi / |omega|``."""
from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from exuclear.nonlinear import Driven

from ._params import crank_speed_from_rpm
from ._slider_crank_build import _build_minimal
from ._slider_crank_params import SliderCrankParams
from ._slider_crank_run import default_settings

#: Fields :func:`driven` sets itself: the nonlinear tools need the minimal formulation
#: (no constraints: the exponent perturbs every coordinate) with its one joint at B, and
#: the run's length follows from the periods.
DRIVEN_FIXED = ("formulation", "clearance_joints", "ideal", "revolutions")


#: The scene's DOPRI5 tolerances (:func:`default_settings`) are divided by this for the
#: nonlinear runs.  In sustained contact the explicit method runs at its stability limit
#: in the contact's stiff mode and holds that mode at the level of its tolerance, in each
#: copy on its own: at the scene's rtol 1e-7 the two copies of the exponent stay about
#: 2.5e-6 apart (coordinates and rates, SI) whatever their distance d0 after the
#: renormalisation, a floor above d0 = 1e-6 that reads as a positive exponent for a
#: periodic response; at a tenth of the tolerances the distance contracts, in proportion
#: to d0 from 1e-7 to 1e-5 (``python -m validation.nonlinear verdicts`` prints both).
TOLERANCE_FACTOR = 10.0

#: The crank angle among the minimal formulation's coordinates (crank angle, rod angle
#: relative to the crank, slider x): the drive, held at its speed by the flywheel.
CRANK_ANGLE = 0


@dataclass(frozen=True)
class _Copy:
    """One copy of the minimal slider-crank: joint B named ``B`` (copy 0) or ``B1`` (copy 1:
    Exudyn refuses a name twice); returns the joints by name."""

    params: SliderCrankParams

    def __call__(self, mbs: Any, copy: int = 0) -> dict:
        return _build_minimal(self.params, mbs, name="B" if copy == 0 else f"B{copy}")[0]


@dataclass(frozen=True)
class _Carry:
    """The state a sweep carries to a new parameter set: the coordinates as they are, the
    velocities scaled by the ratio of the crank speeds (the mechanism's motion at another
    speed, with the flywheel's rate set to the new speed)."""

    crank_speed: float
    clearance: float

    def __call__(self, q: np.ndarray, v: np.ndarray, previous: Driven) -> tuple[np.ndarray, np.ndarray]:
        before = previous.params
        if before.get("clearance", self.clearance) != self.clearance:
            raise ValueError("a sweep cannot carry the journal's position to another clearance (it would sit in or "
                             "off the wall): sweep the clearance with independent runs (sweep=False)")
        return q, v * (self.crank_speed / before["crank_speed"])


def driven(values: dict) -> Driven:
    """The slider-crank at ``values`` (fields of :class:`SliderCrankParams` over the paper's,
    ``crank_speed`` in rad/s or ``rpm``, and ``mu``, a Coulomb coefficient for a sweep over
    friction: 0 is none) as a :class:`~exuclear.nonlinear.Driven`: the
    minimal formulation; its default settings (:func:`default_settings`) at a tenth of
    their tolerances (:data:`TOLERANCE_FACTOR`), with one output per crank period (the
    tools record the sections, not the sensors); the crank angle as the drive
    (:attr:`~exuclear.nonlinear.Driven.drive`); the default observables, the eccentricity
    ratios of joint B and their rates (``B.ex``, ``B.ey``, ``B.vx``, ``B.vy``)."""
    v = dict(values)
    if "rpm" in v:
        if "crank_speed" in v:
            raise ValueError("give the crank speed once: `crank_speed` [rad/s] or `rpm`")
        v["crank_speed"] = crank_speed_from_rpm("rpm", v.pop("rpm"))
    if "mu" in v:  # a number to sweep: smoothed Coulomb friction with this coefficient
        if "friction" in v:
            raise ValueError("give the friction once: `friction` (a law's name) or `mu` (a Coulomb coefficient)")
        mu = v.pop("mu")
        v["friction"] = "none" if mu == 0 else f"coulomb:{mu}"
    fixed = sorted(set(v) & set(DRIVEN_FIXED))
    if fixed:
        raise ValueError(f"the slider-crank's nonlinear runs set {', '.join(fixed)} themselves (minimal formulation, "
                         "joint B, length from the periods)")
    try:
        params = SliderCrankParams.paper(**v, formulation="minimal")
    except TypeError as err:  # an unknown field
        raise ValueError(f"unknown slider-crank parameter: {err}; known: the fields of SliderCrankParams or rpm") from None
    period = 2.0 * math.pi / abs(params.crank_speed)
    scene = default_settings(params)
    settings = replace(scene, output_step=period, rtol=scene.rtol / TOLERANCE_FACTOR,
                       atol=scene.atol / TOLERANCE_FACTOR)
    return Driven(_Copy(params), settings, period,
                  params={"crank_speed": params.crank_speed, "clearance": params.clearance, **v},
                  carry=_Carry(params.crank_speed, params.clearance), drive=(CRANK_ANGLE,))
