"""The slider-crank as a parameter study (:mod:`exuclear.study`): its parameters, metrics
and columns, and the energy audit a run's summary carries."""
from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

import exuclear
from exuclear.columns import Column

from ._defaults import PAPER_RPM
from ._lubricant import FILM_MODEL_DEFAULT
from ._params import (
    crank_speed_from_rpm,
    nonnegative,
    positive,
    study_columns,
)
from ._slider_crank_build import build
from ._slider_crank_params import FLYWHEEL_INERTIA, SliderCrankParams
from ._slider_crank_run import columns, default_settings
from .scene import Scene

# =======================================================================================
# the slider-crank as a parameter study (exuclear.study)
# =======================================================================================

#: Parameters of :func:`study` and their defaults: the paper's case (:meth:`SliderCrankParams.paper`)
#: with the crank speed in rpm, ``startup`` revolutions left out of the steady metrics and
#: ``revolutions`` measured after them.  Every name but ``rpm`` and ``startup`` is a
#: :class:`SliderCrankParams` field.  ``viscosity`` None (or ``"none"`` on a command line:
#: ``--viscosity none,0.01,0.1`` sweeps dry and two oils) is a dry joint, whatever the
#: ``film_model`` of its row.
def _study_defaults() -> dict:
    paper = SliderCrankParams.paper()
    fields = ("law", "journal_material", "bearing_material", "friction", "bearing_length", "gravity", "v_min",
              "formulation", "backend", "viscosity", "film_model", "wear_coefficient")
    return {"cr": paper.cr, "clearance": paper.clearance, "rpm": PAPER_RPM, "startup": 1.0,
            "revolutions": paper.revolutions, **{name: getattr(paper, name) for name in fields}}


STUDY_PARAMETERS = _study_defaults()

#: The metrics of :func:`study`: what each is, its unit (axis labels of study plots).
#: "Steady": after the ``startup`` revolutions.
STUDY_METRICS = {
    "peak_force": Column("peak contact force, whole run", "N"),
    "peak_force_steady": Column("peak contact force, steady", "N"),
    "peak_force_by_rev": Column("peak contact force per steady revolution", "N"),
    "impacts": Column("contact onsets, whole run"),
    "impacts_per_rev": Column("contact onsets per steady revolution"),
    "impacts_by_rev": Column("contact onsets in each steady revolution"),
    "max_ecc_over_c": Column("largest |e| / c, steady"),
    # the force the joint carries, oil film and metal contact together (joint_force): the
    # peak contact force of a dry joint
    "peak_joint_force": Column("peak joint force (film and contact), whole run", "N"),
    # c - |e| at its smallest, steady: negative where the journal penetrates the wall
    "min_film_thickness": Column("smallest film thickness c - |e|, steady", "m"),
    "metal_contact_fraction": Column("fraction of the steady time in metal contact"),
    # RMS over the steady revolutions of the slider acceleration minus the ideal
    # mechanism's (ideal_slider_acceleration), and that over the ideal RMS
    "slider_acc_rms_dev": Column("RMS deviation of the slider acceleration from the ideal", "m/s^2"),
    "slider_acc_rms_dev_rel": Column("RMS deviation of the slider acceleration / ideal RMS"),
    # the energy audit (_energy_audit; minimal formulation and a dry joint, NaN otherwise)
    "drive_work": Column("drive work", "J"),
    "contact_dissipated": Column("energy dissipated by the contact", "J"),
    "energy_residual": Column("energy residual", "J"),
    "energy_residual_rel": Column("energy residual / gross contact work"),
    # the wear of the bearing at B over the whole run (a run with a wear_coefficient; NaN otherwise)
    "max_wear_depth": Column("largest wear depth of the bearing at B", "m"),
    "max_wear_angle": Column("angle of the largest wear depth, joint frame", "deg"),
    "wear_volume": Column("worn volume of the bearing at B", "m^3"),
    "steps": Column("solver steps"),
    "sim_wall_time": Column("solver wall time", "s"),
}

#: Parameters (from the :class:`SliderCrankParams` fields: help, unit, the command line's
#: other spellings such as ``--length``) and metrics of the study, for
#: ``python -m exuclear.study`` and its plots.
STUDY_COLUMNS = {
    **study_columns(SliderCrankParams, STUDY_PARAMETERS, {
        "formulation": "formulation",
        "revolutions": "crank revolutions after the start-up"}),
    "rpm": Column("crank speed", "rpm"),
    "startup": Column("start-up revolutions, left out of the steady metrics"),
    **STUDY_METRICS,
}

#: Output interval of a study run [s]: below any step, so that every accepted step is
#: recorded and the energy audit's trapezoid rule and the peak force see each impact.
STUDY_EVERY_STEP = 1e-12


def study_params(values: dict) -> SliderCrankParams:
    """The :class:`SliderCrankParams` of a study's parameter set (defaults
    :data:`STUDY_PARAMETERS`); ``ValueError`` for a value the model refuses."""
    v = {**STUDY_PARAMETERS, **values}
    if isinstance(v["viscosity"], str) and v["viscosity"].lower() == "none":
        v["viscosity"] = None  # a dry joint, as the command line spells it
    if isinstance(v["wear_coefficient"], str) and v["wear_coefficient"].lower() == "none":
        v["wear_coefficient"] = None  # no wear, as the command line spells it
    if v["viscosity"] is None:
        # the dry runs of a sweep over viscosity and film model (--viscosity none,0.01
        # --film-model finite): a dry joint has no film, so the film model does not apply
        v["film_model"] = FILM_MODEL_DEFAULT
    unknown = sorted(set(v) - set(STUDY_PARAMETERS))
    if unknown:
        raise ValueError(f"unknown study parameters {unknown}; known: {', '.join(STUDY_PARAMETERS)}")
    crank_speed = crank_speed_from_rpm("rpm", v["rpm"])
    nonnegative("startup", v["startup"])
    positive("revolutions", v["revolutions"])
    fields = {k: v[k] for k in STUDY_PARAMETERS if k not in ("rpm", "startup", "revolutions")}
    return SliderCrankParams.paper(**fields, crank_speed=crank_speed,
                                   revolutions=v["startup"] + v["revolutions"])


def check_study(values: dict) -> None:
    """Raise ``ValueError`` for a study parameter set the model refuses (before any run)."""
    study_params(values)


def ideal_slider_acceleration(theta: np.ndarray, omega: float, r: float, l: float) -> np.ndarray:
    """Slider acceleration of the ideal mechanism at constant crank speed [m/s^2].

    ``x = r cos(theta) + D``, ``D = sqrt(l^2 - r^2 sin^2 theta)``, differentiated twice
    at ``theta' = omega``::

        x'' = -r w^2 cos(theta) - r^2 w^2 [cos(2 theta) / D + r^2 sin^2 cos^2 / D^3]
    """
    s, c = np.sin(theta), np.cos(theta)
    d = np.sqrt(l**2 - (r * s) ** 2)
    return -r * omega**2 * c - r**2 * omega**2 * ((c**2 - s**2) / d + r**2 * s**2 * c**2 / d**3)


def _elastic_energy(law: exuclear.ContactLaw, delta: float) -> float:
    """``int_0^delta F_el`` [J], the energy a contact stores at penetration ``delta``."""
    from scipy.integrate import quad

    return 0.0 if delta <= 0.0 else quad(law.elastic_force, 0.0, delta, epsabs=0.0, epsrel=1e-12)[0]


def mechanical_energy(model: Scene) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Kinetic plus potential energy of crank (its own inertia, not the flywheel's), rod
    and slider of a minimal-formulation run [J], from the recorded tree coordinates (crank
    angle, rod angle relative to the crank, slider x); returns ``(time, energy, crank
    speed)`` at the recorded instants."""
    if model.params.formulation != "minimal":
        raise ValueError(f"the energy is written for the minimal formulation, got {model.params.formulation!r}")
    p, mbs = model.params, model.mbs
    r, l = p.crank_length, p.rod_length
    q = np.asarray(mbs.GetSensorStoredData(model.sensors["q"]))
    q_t = np.asarray(mbs.GetSensorStoredData(model.sensors["q_t"]))
    th, thd = q[:, 1], q_t[:, 1]
    phi, phid, xd = th + q[:, 2], thd + q_t[:, 2], q_t[:, 3]
    gx = -r * np.sin(th) * thd - l / 2 * np.sin(phi) * phid
    gy = r * np.cos(th) * thd + l / 2 * np.cos(phi) * phid
    kinetic = (0.5 * (p.crank_inertia + p.crank_mass * r**2 / 4) * thd**2 + 0.5 * p.rod_mass * (gx**2 + gy**2)
               + 0.5 * p.rod_inertia * phid**2 + 0.5 * p.slider_mass * xd**2)
    potential = p.gravity * (p.crank_mass * r / 2 * np.sin(th) + p.rod_mass * (r * np.sin(th) + l / 2 * np.sin(phi)))
    return q[:, 0], kinetic + potential, thd


def _energy_audit(model: Scene) -> dict[str, float]:
    """Energy balance of a minimal-formulation run with outputs at every step [J].

    Drive work (what the flywheel gave up, ``-J_fly (w_end^2 - w_0^2) / 2``) = change of
    the links' kinetic and potential energy + energy the contact absorbed (elastic energy
    stored at the end, plus ``int (F_N - F_el) delta' + F_T v_T dt`` dissipated, trapezoid
    rule) + residual.  ``energy_residual_rel`` is the residual over the gross contact
    work ``int |F_N delta' + F_T v_T| dt``; it includes the round-off of the flywheel's
    energy (``validation/hard_cases/common.py`` bounds it, AUDIT_LIMIT).
    """
    t, energy, omega = mechanical_energy(model)
    change = float(energy[-1] - energy[0])
    work = float(-0.5 * FLYWHEEL_INERTIA * (omega[-1] - omega[0]) * (omega[-1] + omega[0]))
    out, law = model.joint.outputs(), model.joint.joint.law
    t, delta, f_n, rate = out["time"], out["penetration"], out["normal_force"], out["penetration_rate"]
    friction = out["tangential_force"] * out["slip_velocity"]
    elastic = np.array([law.elastic_force(d) if d > 0.0 else 0.0 for d in delta])
    stored = _elastic_energy(law, float(delta[-1])) - _elastic_energy(law, float(delta[0]))
    dissipated = float(np.trapezoid((f_n - elastic) * rate + friction, t))
    gross = float(np.trapezoid(np.abs(f_n * rate + friction), t))
    residual = work - change - stored - dissipated
    return {"drive_work": work, "contact_dissipated": dissipated, "energy_residual": residual,
            "energy_residual_rel": residual / gross if gross > 0.0 else math.nan}


def study(values: dict) -> dict:
    """One run of a slider-crank study (:mod:`exuclear.study`); parameters
    :data:`STUDY_PARAMETERS`.  The run covers ``startup + revolutions`` crank
    revolutions; "steady" metrics use the last ``revolutions`` only.

    Returns
    -------
    dict
        The metrics of :data:`STUDY_METRICS` (meaning and unit there); ``success`` and
        ``message`` of the run.
    """
    p = study_params(values)
    model = build(p)
    settings = replace(default_settings(p), output_step=STUDY_EVERY_STEP)
    sim = exuclear.simulate(model.mbs, settings)
    cols = columns(model)
    t = cols["time"]
    startup = float({**STUDY_PARAMETERS, **values}["startup"])
    t_start = 2.0 * math.pi * startup / abs(p.crank_speed)
    steady = t >= t_start
    onsets = np.asarray(model.joint.history.onset_times)
    ecc = np.hypot(cols["ecc_x"], cols["ecc_y"]) / p.clearance
    ideal = ideal_slider_acceleration(np.radians(cols["crank_angle"]), p.crank_speed, p.crank_length, p.rod_length)

    def rms(x: np.ndarray) -> float:
        ts = t[steady]
        return math.sqrt(float(np.trapezoid(x[steady] ** 2, ts)) / (ts[-1] - ts[0])) if steady.sum() > 1 else math.nan

    dev = rms(cols["slider_a"] - ideal)
    in_contact = (cols["penetration"] > 0.0).astype(float)
    # the audit counts what the metal contact dissipates, not the oil film's viscous work:
    # with a film its residual would be that work, so a lubricated run has none
    audit = (_energy_audit(model) if p.formulation == "minimal" and p.viscosity is None else
             dict.fromkeys(("drive_work", "contact_dissipated", "energy_residual", "energy_residual_rel"), math.nan))
    steady_force = cols["contact_force"][steady]
    # each steady revolution on its own (the last one may be partial): the points of a
    # bifurcation diagram
    period = 2.0 * math.pi / abs(p.crank_speed)
    revolution = np.floor((t - t_start) / period * (1.0 + 1e-12)).astype(int)
    count = math.ceil(p.revolutions - startup - 1e-9)
    by_rev = [cols["contact_force"][revolution == k] for k in range(count)]
    wear = model.joint.wear_profile() if p.wear_coefficient is not None else None
    depth, angle = wear.deepest() if wear is not None else (math.nan, math.nan)
    return {
        "peak_force": float(cols["contact_force"].max()),
        "peak_force_steady": float(steady_force.max()) if steady_force.size else math.nan,
        "peak_force_by_rev": [float(f.max()) if f.size else math.nan for f in by_rev],
        "impacts": len(onsets),
        "impacts_per_rev": float(np.sum(onsets >= t_start)) / (p.revolutions - startup),
        "impacts_by_rev": np.bincount(np.floor((onsets[onsets >= t_start] - t_start) / period).astype(int),
                                      minlength=count)[:count].tolist(),
        "max_ecc_over_c": float(ecc[steady].max()) if steady.any() else math.nan,
        "peak_joint_force": float(cols.get("joint_force", cols["contact_force"]).max()),
        "min_film_thickness": p.clearance * (1.0 - float(ecc[steady].max())) if steady.any() else math.nan,
        "metal_contact_fraction": rms(in_contact) ** 2,  # the time average of a 0/1 signal
        "slider_acc_rms_dev": dev, "slider_acc_rms_dev_rel": dev / rms(ideal),
        **audit,
        "max_wear_depth": depth, "max_wear_angle": math.degrees(angle),
        "wear_volume": wear.volume["bearing"] if wear is not None else math.nan,
        "steps": sim.steps, "sim_wall_time": sim.wall_time,
        "success": sim.success, "message": sim.message,
    }

