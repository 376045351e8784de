"""Default solver settings that scale with the model (issues 15 and 16).

A model's ``*_DEFAULTS`` hold the settings measured on the paper's case (500 rpm,
c = 0.1 mm, docs/physics.md section 6.2).  :func:`scaled` carries them to another crank
speed and clearance by the model's own time scales:

- the crank period ``T``: the largest step shrinks with it (ratio ``s = T_paper / T``,
  never above 1: a slower crank keeps the paper's steps);
- the tolerances: DOPRI5's ``rtol`` falls as ``s**3`` and ``atol`` is 1e-6 of the
  clearance.  Measured (``validation/cost/work_precision.py``, case ``speed-clearance``): at
  5000 rpm rtol 1e-7 errs by 0.07 c and 1e-8 / 1e-9 by 4e-3 / 1.8e-2 c (the motion is
  sensitive: the error grows tenfold over two revolutions), 1e-10 holds 3.2e-3 c;
- the impact step of the implicit methods: no more than a twentieth of the largest step
  and shorter in proportion for clearances above the paper's (faster impacts: 0.5 mm
  errs by 2.4e-2 c at 1e-6 s and 9.1e-3 c at 2e-7 s);
- the contact period ``T_c`` (:func:`exuclear.timescales.contact_period`): the largest
  implicit step stays below ``T_c / 10``, where contact openings are resolved.

:func:`accuracy_notes` says where the defaults are not shown to hold 1 % of c.
"""
from __future__ import annotations

import math

from exuclear.joint import ClearanceJoint
from exuclear.settings import METHODS
from exuclear.timescales import STEPS_PER_CONTACT_PERIOD, contact_period

#: The paper's case (Wang et al. 2017, example 2), where the ``*_DEFAULTS`` were measured:
#: crank speed [rpm] and [rad/s], clearance [m].  The scenes take them from here.
PAPER_RPM = 500.0
PAPER_CRANK_SPEED = PAPER_RPM * math.pi / 30.0
PAPER_CLEARANCE = 1e-4
#: Exponent of the speed ratio in DOPRI5's relative tolerance (module docstring).
RTOL_SPEED_EXPONENT = 3
#: Absolute tolerance of DOPRI5 per metre of clearance: 1e-10 m at the paper's 0.1 mm.
ATOL_PER_CLEARANCE = 1e-6
#: Impact steps per largest step at least (module docstring).
IMPACT_STEPS_PER_STEP = 20
#: Crank speeds [rad/s] and clearances [m] the scaled defaults were checked on.
CHECKED_SPEEDS = (PAPER_CRANK_SPEED, 5000.0 * math.pi / 30.0)
CHECKED_CLEARANCES = (5e-5, 5e-4)
#: Above this crank speed [rad/s] the implicit defaults reach only ~1 % of c (1.07e-2 c
#: measured at 5000 rpm; 2.3e-3 c at 2000 rpm).
IMPLICIT_CHECKED_SPEED = 2000.0 * math.pi / 30.0


def scaled(base: dict, crank_speed: float, clearance: float, joint: ClearanceJoint | None = None,
           mass: float = math.nan, force: float = math.nan) -> dict:
    """The settings ``base`` (measured on the paper's case) for another crank speed
    [rad/s] and clearance [m]; with ``joint``, ``mass`` [kg] and ``force`` [N] the
    contact period caps the implicit largest step (module docstring)."""
    s = max(1.0, abs(crank_speed) / PAPER_CRANK_SPEED)
    out = dict(base, step=base["step"] / s)
    if METHODS[base["method"]][1]:  # explicit, adaptive
        out["rtol"] = base["rtol"] / s**RTOL_SPEED_EXPONENT
        out["atol"] = ATOL_PER_CLEARANCE * clearance
        return out
    if joint is not None and mass > 0.0 and force > 0.0:
        out["step"] = min(out["step"], contact_period(joint.law, mass, force) / STEPS_PER_CONTACT_PERIOD)
    if base.get("impact_step") is not None:
        out["impact_step"] = min(base["impact_step"] * min(1.0, PAPER_CLEARANCE / clearance),
                                 out["step"] / IMPACT_STEPS_PER_STEP if s > 1.0 else out["step"])
    return out


def accuracy_notes(crank_speed: float, clearance: float, clearance_joints: int, implicit: bool) -> list[str]:
    """Why a default run may not be converged (empty where the defaults were shown to
    hold 1 % of c)."""
    notes = []
    if clearance_joints > 1:
        notes.append(
            f"{clearance_joints} clearance joints: their impacts couple and the path is sensitive to microseconds "
            "of onset time. With clearance at O, A and B at 500 rpm the default path agrees with a run at a quarter "
            "of the steps to 1 % of c only until 8 ms (3 % of two revolutions); beyond, impact counts and the "
            "distributions of peak force and onset velocity agree statistically, while the spectrum of |e| at B and "
            "the crank moment do not (exuclear.models.slider_crank --clearance-joints OAB --check-convergence). Check "
            "convergence (exuclear.check_convergence, or --check-convergence) before trusting the path")
    w = abs(crank_speed)
    if not CHECKED_SPEEDS[0] * 0.999 <= w <= CHECKED_SPEEDS[1] * 1.001 and w > CHECKED_SPEEDS[0]:
        notes.append(f"crank speed {w * 30 / math.pi:.0f} rpm is beyond the 5000 rpm the scaled defaults were checked "
                     "on; the path may not be converged: rerun with half the step and a tenth of the tolerances")
    elif implicit and w > IMPLICIT_CHECKED_SPEED * 1.001:
        notes.append(f"at {w * 30 / math.pi:.0f} rpm the implicit defaults hold the path only to about 1 % of c "
                     "(1.07e-2 c measured at 5000 rpm): use the minimal formulation (DOPRI5) or check convergence")
    if not CHECKED_CLEARANCES[0] * 0.999 <= clearance <= CHECKED_CLEARANCES[1] * 1.001:
        notes.append(f"clearance {clearance * 1e3:g} mm is outside the 0.05-0.5 mm the defaults were checked on; "
                     "the path may not be converged: check convergence")
    return notes
