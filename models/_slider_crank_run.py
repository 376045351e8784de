"""Running the slider-crank: its solver settings by formulation, a run's output columns
(:data:`COLUMNS`), the ideal mechanism's joint force and the convergence check."""
from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

import numpy as np

import exuclear
from exuclear import SolverSettings
from exuclear import convergence as _convergence
from exuclear.engine import AccuracyWarning
from exuclear.timescales import reduced_mass
from exuclear.wear import WearProfile

from . import _defaults
from ._cli import write_csv as _write_columns
from ._lubricant import joint_force
from ._slider_crank_build import build
from ._slider_crank_params import COLUMNS, FILM_COLUMNS, FLYWHEEL_INERTIA, SliderCrankParams
from .scene import Scene

MINIMAL_DEFAULTS = {"method": "dopri5", "step": 1e-4, "rtol": 1e-7, "atol": 1e-10}
#: Redundant: generalized-alpha with impact-aware steps (2e-5 s, 1e-6 s from each contact
#: onset, grown in free flight by the joint), and a Jacobian wherever a modified-Newton
#: iteration reduces the residual by less than 100x (``newton_contractivity``): the crank
#: turns the Jacobian fast and the matrix is small, so fresh Jacobians pay.  The measurements
#: behind both, and the steps tried instead, are in docs/validation/speed.md
#: (python -m validation.cost benchmark, python -m validation.scaled_defaults).
REDUNDANT_DEFAULTS = {"method": "generalized-alpha", "step": 2e-5, "impact_step": 1e-6, "newton_contractivity": 0.01}
#: Spatial: the redundant formulation's steps, with which the two agree to ~2e-7 c; their
#: error against the converged minimal formulation is in tests/test_spatial.py (CONVERGED).
SPATIAL_DEFAULTS = REDUNDANT_DEFAULTS
_DEFAULTS = {"minimal": MINIMAL_DEFAULTS, "redundant": REDUNDANT_DEFAULTS, "spatial": SPATIAL_DEFAULTS}


def default_settings(params: SliderCrankParams) -> SolverSettings:
    """Solver settings of a formulation (:data:`MINIMAL_DEFAULTS`,
    :data:`REDUNDANT_DEFAULTS`, :data:`SPATIAL_DEFAULTS`, measured at 500 rpm and
    c = 0.1 mm) carried to the model's crank speed and clearance by
    :func:`exuclear.models._defaults.scaled`; outputs every 1e-5 s."""
    return SolverSettings(end_time=params.end_time, **_scaled_defaults(params, _DEFAULTS[params.formulation]))


def _scaled_defaults(params: SliderCrankParams, base: dict) -> dict:
    theta = np.linspace(0.0, 2.0 * math.pi, 361)
    force = float(np.max(np.hypot(*ideal_joint_force(params, theta))))  # the load at B of the ideal mechanism
    mass = reduced_mass(params.rod_mass, params.slider_mass)
    return _defaults.scaled(base, params.crank_speed, params.clearance, params.joint, mass, force)


def accuracy_notes(params: SliderCrankParams, settings: SolverSettings) -> list[str]:
    """Why a run of ``params`` at its default settings may not be converged."""
    if params.ideal:
        return []
    return _defaults.accuracy_notes(params.crank_speed, params.clearance, len(params.clearance_joints),
                                    not settings.explicit)


@dataclass
class SliderCrankResult:
    """Outputs of a run: :data:`COLUMNS` as arrays, and the run's summary."""

    columns: dict[str, np.ndarray]
    success: bool
    message: str
    wall_time: float
    build_time: float
    steps: int
    rejected: int
    onset_times: np.ndarray  # contact onsets [s], found at accepted steps (none is missed by output sampling)
    #: Why the path may not be converged: the defaults' limits (:func:`accuracy_notes`) and
    #: the run's own findings (:attr:`exuclear.SimulationResult.notes`).
    notes: tuple[str, ...] = ()
    #: The worn profiles of the joint at B after the run (a run with a ``wear_coefficient``).
    wear: WearProfile | None = None

    @property
    def impacts(self) -> int:
        return len(self.onset_times)

    @property
    def peak_force(self) -> float:
        return float(self.columns["contact_force"].max())


def ideal_joint_force(params: SliderCrankParams, theta: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Force of the rod on the slider at B in the ideal mechanism [N], as ``(fx, fy)``.

    Closed form at constant crank speed ``w`` (signed: clockwise cranks too): rod angle ``phi`` from
    ``r sin(theta) + l sin(phi) = 0``; the frictionless guide gives
    ``fx = m_slider * a_slider``; ``fy`` follows from the rod's moment balance about A,
    ``(B - A) x (-F) + (G - A) x m_rod g = I_G phi'' + (G - A) x m_rod a_G``.  This is
    the direction ``n`` the journal is pressed towards (force on the bearing ``F_N n``).
    Its magnitude is the ``contact_force`` column of an ideal run, the force the ideal
    joint at B carries (``docs/physics.md`` eqs. (30)-(32)).

    Parameters
    ----------
    params : SliderCrankParams
        Mechanism (the clearance fields are not used).
    theta : ndarray, shape (n,)
        Crank angles [rad].
    """
    r, l, w, g = params.crank_length, params.rod_length, params.crank_speed, params.gravity
    m, inertia = params.rod_mass, params.rod_inertia
    s, c = np.sin(theta), np.cos(theta)
    phi = np.arcsin(-r * s / l)
    sp, cp = np.sin(phi), np.cos(phi)
    phi_t = -r * w * c / (l * cp)
    phi_tt = (r * w**2 * s + l * sp * phi_t**2) / (l * cp)
    a_slider = -r * w**2 * c - l * cp * phi_t**2 - l * sp * phi_tt
    ag_x = -r * w**2 * c + 0.5 * l * (-sp * phi_tt - cp * phi_t**2)
    ag_y = -r * w**2 * s + 0.5 * l * (cp * phi_tt - sp * phi_t**2)
    fx = params.slider_mass * a_slider
    rhs = inertia * phi_tt + 0.5 * l * m * (cp * ag_y - sp * ag_x)
    fy = (l * sp * fx - 0.5 * l * cp * m * g - rhs) / (l * cp)
    return fx, fy


def columns(model: Scene) -> dict[str, np.ndarray]:
    """The recorded :data:`COLUMNS` of a finished run (SI units, angles in degrees)."""
    p, mbs, s = model.params, model.mbs, model.sensors

    def data(key: str) -> np.ndarray:
        return np.asarray(mbs.GetSensorStoredData(s[key]))

    if p.formulation == "minimal":
        q, q_t, q_tt = data("q"), data("q_t"), data("q_tt")
        t = q[:, 0]
        cols = {"time": t, "crank_angle": np.degrees(q[:, 1]), "slider_x": q[:, 3] + p.crank_length + p.rod_length,
                "slider_v": q_t[:, 3], "slider_a": q_tt[:, 3], "crank_moment": -FLYWHEEL_INERTIA * q_tt[:, 1]}
    else:
        crank = data("crank")
        t = crank[:, 0]
        # the crank angle is the node's last coordinate: phi of a 2D node, rz of an Rxyz node
        cols = {"time": t, "crank_angle": np.degrees(crank[:, -1]), "slider_x": data("slider_x")[:, 1],
                "slider_v": data("slider_v")[:, 1], "slider_a": data("slider_a")[:, 1],
                # the multiplier is the constraint's reaction on the crank: the drive is its negative
                "crank_moment": -data("moment")[:, 1]}
    if model.joint is None:
        zeros = np.zeros_like(t)
        # the ideal joint at B carries the reaction force; in the ideal mechanism it has a
        # closed form; with clearance at O or A only, B's force is not measured (NaN)
        force = np.hypot(*ideal_joint_force(p, np.radians(cols["crank_angle"]))) if p.ideal else np.full_like(t, np.nan)
        cols.update(contact_force=force, ecc_x=zeros, ecc_y=zeros, penetration=np.full_like(t, -p.clearance),
                    in_contact=zeros)
    else:
        out = model.joint.outputs()
        # the eccentricity in the global x, y (the spatial formulation's joint frame is that of
        # mbs.CreateRevoluteJoint, turned in the plane)
        ecc_x, ecc_y = model.joint.frame[:2, :2] @ np.array([out["ecc_x"], out["ecc_y"]])
        cols.update(contact_force=np.hypot(out["normal_force"], out["tangential_force"]), ecc_x=ecc_x,
                    ecc_y=ecc_y, penetration=out["penetration"], in_contact=out["in_contact"])
        if model.joint.joint.film is not None:
            cols.update({k: out[k] for k in FILM_COLUMNS[:-1]}, joint_force=joint_force(out))
            return {k: cols[k] for k in COLUMNS + FILM_COLUMNS}
    return {k: cols[k] for k in COLUMNS}


def run(params: SliderCrankParams, settings: SolverSettings | None = None) -> SliderCrankResult:
    """Build and simulate; returns the recorded :data:`COLUMNS` and the run's summary.

    With the default settings, where those are not shown to hold 1 % of c
    (:func:`accuracy_notes`), the run warns (:class:`exuclear.AccuracyWarning`) and the
    result's ``notes`` say why and what to do.
    """
    model = build(params)
    notes: tuple[str, ...] = ()
    if settings is None:
        settings = default_settings(params)
        notes = tuple(accuracy_notes(params, settings))
        for note in notes:
            warnings.warn(note, AccuracyWarning, stacklevel=2)
    sim = exuclear.simulate(model.mbs, settings)
    onsets = np.array(model.joint.history.onset_times if model.joint is not None else [])  # joint B
    worn = model.joint is not None and model.joint.joint.wear is not None
    return SliderCrankResult(columns(model), sim.success, sim.message, sim.wall_time, model.build_time,
                             sim.steps, sim.rejected, onsets, notes + sim.notes,
                             model.joint.wear_profile() if worn else None)


def write_csv(path: str, columns: dict[str, np.ndarray], incomplete: str = "", notes: tuple[str, ...] = ()) -> None:
    """Write :data:`COLUMNS` (and :data:`FILM_COLUMNS` where ``columns`` holds them: a
    lubricated joint) with a header line (SI units, angles in degrees).

    ``incomplete``: why the run stopped early; it then goes first, as a comment line
    ``# INCOMPLETE: ...`` before the header; ``notes`` follow as ``# NOTE: ...`` lines.
    """
    _write_columns(path, columns, csv_columns(columns), incomplete, notes)


def csv_columns(columns: dict[str, np.ndarray]) -> tuple[str, ...]:
    """The columns a run's CSV has: :data:`COLUMNS`, and :data:`FILM_COLUMNS` where ``columns``
    holds them (a lubricated joint)."""
    return COLUMNS + FILM_COLUMNS if "film_force" in columns else COLUMNS


#: The columns :func:`record` hands to :func:`exuclear.check_convergence` as named
#: signals (the time histories a user of the scene reads: slider motion and the driving moment).
SIGNALS = ("slider_x", "slider_v", "crank_moment")


def record(params: SliderCrankParams, settings: SolverSettings) -> _convergence.RunRecord:
    """Build and run the slider-crank and return what :func:`exuclear.check_convergence`
    compares: every clearance joint by its name (O, A, B) and :data:`SIGNALS`."""
    model = build(params)
    sim = exuclear.simulate(model.mbs, settings)
    cols = columns(model)
    return _convergence.RunRecord.from_handles(sim, model.joints, {k: (cols["time"], cols[k]) for k in SIGNALS})


def check_convergence(params: SliderCrankParams, settings: SolverSettings | None = None,
                      **options: object) -> _convergence.ConvergenceResult:
    """:func:`exuclear.check_convergence` of this scene at ``settings`` (default
    :func:`default_settings`); ``options`` go to it (``factor``, ``bound``, ...)."""
    return _convergence.check_convergence(lambda s: record(params, s), settings or default_settings(params), **options)

