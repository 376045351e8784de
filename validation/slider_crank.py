"""Slider-crank with a revolute clearance joint: the paper's Figs. 10-20 and its claims.

Source problem: example 2 of X. Wang, G. Liu, S. Ma, R. Tong, "Effects of restitution
coefficient and material characteristics on dynamic response of planar multi-body
systems with revolute clearance joint", J. Mech. Sci. Technol. 31(2) (2017) 587-597,
restated in ``docs/physics.md`` section 6.2: a crank turning at 500 rpm drives a
slider through a connecting rod; the rod-slider joint has a radial clearance of 0.1 mm.

Every run goes through :mod:`models.slider_crank`; this script chooses the cases,
measures them against the ideal mechanism, draws the figures and writes the report:

- restitution sweep: cr = 0.3, 0.5, 0.7, 0.9, steel journal and bearing (Wang-Liu law);
- material sweep at cr = 0.3: steel bearing, journal of steel, ductile iron, copper,
  aluminium;
- each sweep without friction and with the paper's friction law (eq. 11, Table 1);
- the ideal mechanism (redundant formulation, ideal revolute joint) as the baseline.

The report takes the paper's qualitative claims one by one and explains every
disagreement with diagnostic runs, without changing the library's model: a solver
tolerance ladder, the contact history at every accepted step (``v0``, impact
durations, what outputs every 1e-5 s can show), the ideal joint force at B in closed
form, and a run with ``v0`` floored at the first impact's speed.

Run from the repository root::

    python -m validation.slider_crank [--out DIR] [--revolutions N]

Exit status 0 if every run succeeded, 1 otherwise (the failed runs are named), 2 on
bad options.
"""
from __future__ import annotations

import argparse
import math
import os
import sys
import time
from collections.abc import Sequence
from dataclasses import dataclass, field, fields, replace

import numpy as np

import exuclear
from exuclear.plotting import crank_angle_panels, hann_spectrum, slider_crank_sweep_figures, uniform_spectrum
from models.slider_crank import SliderCrankParams, SliderCrankResult, build, default_settings, ideal_joint_force, run
from validation._tables import markdown_table, write_csv

DEFAULT_OUT = os.path.join("results", "slider_crank")

#: Restitution coefficients of the paper's restitution sweep.
CR_SWEEP = (0.3, 0.5, 0.7, 0.9)
#: Journal materials of the paper's material sweep (the bearing stays steel).
JOURNAL_MATERIALS = ("steel", "ductile-iron", "copper", "aluminium")
#: Restitution coefficient of the material sweep.
MATERIAL_CR = 0.3
#: Friction laws every sweep runs with (docs/physics.md section 3: the paper leaves it open).
FRICTIONS = ("none", "paper")

#: DOPRI5 tolerances of the clearance runs.  The paper's rtol 1e-6 changes the number
#: of impacts of the friction runs (see the tolerance ladder in the report) and misses
#: the energy audit of tests/test_slider_crank.py by 4 %; rtol 1e-8 holds it to 0.1 %.
#: atol 1e-12 m is 1e-8 of the clearance.
RTOL, ATOL = 1e-8, 1e-12
#: The paper's largest step [s] (docs/physics.md section 6.2), used for the figures that reproduce it.
PAPER_MAX_STEP = 1e-5
#: (rtol, atol) of the tolerance ladder.
TOLERANCE_LADDER = ((1e-6, 1e-9), (RTOL, ATOL), (1e-10, 1e-14))
#: Output step that records every accepted step (the solver's steps are >= 1e-12 s).
EVERY_STEP = 1e-12

#: Time [s] after which the ideal run's algorithmic accelerations have settled (tests/test_slider_crank.py).
SETTLE_TIME = 1e-3
#: Frequency band [Hz] where the paper sees acceleration content growing with cr.
BAND = (150.0, 350.0)
#: Half-width [deg] of the windows around the dead points.
DEAD_WINDOW = 20.0
#: Crank angle [deg] that ends the start-up: the journal starts centred in the bearing
#: and its first contacts form a bouncing sequence; the "after start-up" numbers start
#: here (the report counts the contact onsets after it, so a late bounce is not hidden).
STARTUP = 90.0
#: Fewest revolutions that hold the first dead point's whole window.
MIN_REVOLUTIONS = (180.0 + DEAD_WINDOW) / 360.0
#: Resampling step of the spectra [s]: the paper's output step.
SPECTRUM_STEP = 1e-5
#: Frequency range [Hz] searched for the peak of the acceleration-deviation spectrum.
MODE_SEARCH = (50.0, 1000.0)
#: Largest time lag [s] searched by the cross-correlation of the material sweep.
LAG_WINDOW = 1e-3
#: "Barely changes": a deviation below this fraction of the ideal curve's range is
#: hard to see on a plot of the whole curve.
BARELY = 0.05
#: "Oscillates strongly near the dead points": RMS deviation in the dead-point windows
#: at least this many times the RMS elsewhere (after the start-up).
CONCENTRATED = 1.5
#: Figures drawn for the frozen-v0 diagnostic (names as in slider_crank_sweep_figures).
FROZEN_FIGURES = ("slider_a", "contact_force", "orbit", "deviation_spectrum")
#: Crank angles [deg] where the rod's angular velocity -r w cos(theta) / (l cos(phi)) vanishes.
ROD_TURNING = (90.0, 270.0)
#: Slip speed [m/s] below which the paper's friction law is in its stiction branch (v_s).
STICTION_SPEED = exuclear.ModifiedCoulomb.paper().v_s


# -- cases ----------------------------------------------------------------------------

@dataclass(frozen=True)
class Variant:
    """One run of a sweep: the shown parameter value, a legend label, the changes
    to :meth:`SliderCrankParams.paper`."""

    value: str
    label: str
    changes: dict[str, object] = field(hash=False)


@dataclass(frozen=True)
class Sweep:
    """One figure set of the paper: clearance runs that differ in one parameter.

    Parameters
    ----------
    stem : str
        File-name stem of the figures and the CSV table.
    title : str
        Figure and table title.
    kind : str
        ``"cr"`` or ``"material"``.
    column : str
        Header of the parameter column.
    friction : str
        Friction law of every run (``"none"`` or ``"paper"``).
    variants : tuple of Variant
        The runs, in legend order.
    """

    stem: str
    title: str
    kind: str
    column: str
    friction: str
    variants: tuple[Variant, ...]


def paper_sweeps(revolutions: float) -> tuple[Sweep, ...]:
    """The restitution and material sweeps of docs/physics.md section 6.2, each with both friction laws."""
    sweeps = []
    for friction in FRICTIONS:
        base = {"friction": friction, "revolutions": revolutions}
        cr_variants = tuple(Variant(f"{cr:g}", f"cr = {cr:g}", {**base, "cr": cr}) for cr in CR_SWEEP)
        material_variants = tuple(Variant(m, f"{m} journal", {**base, "cr": MATERIAL_CR, "journal_material": m})
                                  for m in JOURNAL_MATERIALS)
        sweeps.append(Sweep(f"restitution_friction-{friction}",
                            f"restitution sweep, steel/steel, Wang-Liu law, friction {friction}", "cr", "cr",
                            friction, cr_variants))
        sweeps.append(Sweep(f"material_friction-{friction}",
                            f"material sweep, steel bearing, cr = {MATERIAL_CR:g}, friction {friction}", "material",
                            "journal", friction, material_variants))
    return tuple(sweeps)


def clearance_settings(params: SliderCrankParams, rtol: float = RTOL, atol: float = ATOL,
                       output_step: float | None = None) -> exuclear.SolverSettings:
    """The model's default DOPRI5 with the paper's largest step (1e-5 s) and the given tolerances."""
    base = default_settings(params)
    return replace(base, step=PAPER_MAX_STEP, rtol=rtol, atol=atol, output_step=output_step or base.output_step)


def ideal_settings(params: SliderCrankParams) -> exuclear.SolverSettings:
    """The baseline's settings: generalized-alpha at the paper's fixed 1e-5 s step."""
    return replace(default_settings(params), step=PAPER_MAX_STEP, impact_step=None)


def describe(params: SliderCrankParams) -> str:
    """One-line description of a run's parameters."""
    if params.ideal:
        return f"ideal mechanism ({params.formulation})"
    text = (f"cr = {params.cr:g}, {params.journal_material} journal / {params.bearing_material} bearing, "
            f"friction {params.friction}")
    if params.v_min != exuclear.V_MIN_DEFAULT:
        text += f", v_min = {params.v_min:.4g} m/s"
    return text


# -- runs -----------------------------------------------------------------------------

@dataclass
class History:
    """The clearance joint's outputs at every accepted step of a run.

    ``theta`` is the crank angle [deg] from the crank speed (the flywheel of the
    minimal formulation holds it to 1e-6); ``out`` holds
    :data:`exuclear.OUTPUT_COLUMNS` and ``time``.
    """

    theta: np.ndarray
    out: dict[str, np.ndarray]
    onsets: int
    success: bool
    message: str
    wall_time: float


class Runner:
    """Runs the slider-crank and keeps every run, so that shared cases run once.

    :meth:`result` goes through :func:`models.slider_crank.run`; :meth:`history`
    builds the model itself to read the joint's own outputs (``v0``, slip, forces),
    which :class:`SliderCrankResult` does not carry.
    """

    def __init__(self) -> None:
        self.results: dict[tuple, SliderCrankResult] = {}
        self.histories: dict[tuple, History] = {}

    def result(self, params: SliderCrankParams, settings: exuclear.SolverSettings | None = None) -> SliderCrankResult:
        settings = settings or (ideal_settings(params) if params.ideal else clearance_settings(params))
        key = (params, settings)
        if key not in self.results:
            res = run(params, settings)
            status = "" if res.success else f"  FAILED: {res.message}"
            extra = "" if params.ideal else f", {res.impacts} impacts, peak force {res.peak_force:.0f} N"
            print(f"    ran {describe(params)} [{settings.method}, rtol {settings.rtol:g}]: "
                  f"{res.wall_time:.1f} s{extra}{status}", flush=True)
            self.results[key] = res
        return self.results[key]

    def history(self, params: SliderCrankParams) -> History:
        settings = clearance_settings(params, output_step=EVERY_STEP)
        key = (params, settings)
        if key not in self.histories:
            model = build(params)
            sim = exuclear.simulate(model.mbs, settings)
            out = model.joint.outputs()
            hist = History(np.degrees(params.crank_speed * out["time"]), out, model.joint.history.onsets,
                           sim.success, sim.message, sim.wall_time)
            status = "" if sim.success else f"  FAILED: {sim.message}"
            print(f"    ran {describe(params)} [every accepted step]: {sim.wall_time:.1f} s, {hist.onsets} impacts"
                  f"{status}", flush=True)
            self.histories[key] = hist
        return self.histories[key]

    def failures(self) -> list[tuple[str, str]]:
        """``(description, message)`` of every run that did not succeed."""
        failed = [(f"{describe(p)} [rtol {s.rtol:g}]", r.message) for (p, s), r in self.results.items() if not r.success]
        failed += [(f"{describe(p)} [every step]", h.message) for (p, _), h in self.histories.items() if not h.success]
        return failed


# -- the ideal mechanism in closed form ----------------------------------------------

@dataclass(frozen=True)
class IdealForce:
    """Where the ideal joint force at B is small, large and turning (after the start-up)."""

    min_force: float          # N
    min_angle: float          # deg, in [0, 360)
    max_force: float          # N
    dead_min: float           # smallest |F| within the dead-point windows [N]
    dead_max: float
    fx_zeros: tuple[float, ...]  # crank angles [deg, 0..360) where the horizontal component changes sign
    max_turn_rate: float      # largest |d(direction)/d(theta)| [deg/deg]
    max_turn_angle: float     # deg
    turns_per_revolution: float


def ideal_force_stats(params: SliderCrankParams) -> IdealForce:
    """Closed-form numbers of :func:`ideal_joint_force` over one revolution."""
    deg = np.linspace(0.0, 360.0, 36001)
    fx, fy = ideal_joint_force(params, np.radians(deg))
    mag = np.hypot(fx, fy)
    direction = np.degrees(np.unwrap(np.arctan2(fy, fx)))
    rate = np.gradient(direction, deg)
    near = _near_dead_points(deg, dead_points(360.0 + DEAD_WINDOW))
    sign_change = np.flatnonzero(np.diff(np.sign(fx)) != 0)
    k_min, k_turn = int(np.argmin(mag)), int(np.argmax(np.abs(rate)))
    return IdealForce(float(mag.min()), float(deg[k_min]), float(mag.max()), float(mag[near].min()),
                      float(mag[near].max()), tuple(float(deg[k]) for k in sign_change),
                      float(np.abs(rate).max()), float(deg[k_turn]), float((direction[-1] - direction[0]) / 360.0))


def closed_form_error(params: SliderCrankParams, ideal: dict[str, np.ndarray]) -> float:
    """Largest difference [m/s^2] between the closed form's slider acceleration (``fx / m_slider``)
    and the ideal Exudyn run's, after the first millisecond (the generalized-alpha
    accelerations settle within a few steps, see tests/test_slider_crank.py)."""
    fx, _ = ideal_joint_force(params, np.radians(ideal["crank_angle"]))
    settled = ideal["time"] > SETTLE_TIME
    return float(np.abs(fx / params.slider_mass - ideal["slider_a"])[settled].max())


def tangential_mode_range(params: SliderCrankParams, force: IdealForce) -> tuple[float, float]:
    """Frequency range [Hz] of the journal sliding to and fro along the bearing wall.

    The journal pressed against the wall by a force ``F`` is a pendulum on a circular
    track of radius ``c``: ``f = sqrt(F / (m c)) / (2 pi)``.  The mass ``m`` lies between
    the slider's (tangent along X) and the rod end's, ``I_A / l^2`` (tangent along Y,
    rod turning about A); ``F`` between the ideal force's extremes.
    """
    c, l = params.clearance, params.rod_length
    rod_end = (params.rod_inertia + params.rod_mass * l**2 / 4.0) / l**2
    light, heavy = min(params.slider_mass, rod_end), max(params.slider_mass, rod_end)
    return (math.sqrt(force.min_force / (heavy * c)) / (2.0 * math.pi),
            math.sqrt(force.max_force / (light * c)) / (2.0 * math.pi))


# -- measures of one run --------------------------------------------------------------

def dead_points(end_angle: float) -> tuple[float, ...]:
    """The dead points (crank at multiples of 180 degrees) strictly inside ``(0, end_angle)``."""
    return tuple(180.0 * k for k in range(1, int(math.ceil(end_angle / 180.0))) if 180.0 * k < end_angle)


def _near_dead_points(theta: np.ndarray, points: Sequence[float]) -> np.ndarray:
    near = np.zeros(theta.shape, dtype=bool)
    for point in points:
        near |= np.abs(theta - point) <= DEAD_WINDOW
    return near


def _rms(x: np.ndarray) -> float:
    return float(np.sqrt(np.mean(x**2))) if x.size else float("nan")


def _band_rms(f: np.ndarray, a: np.ndarray) -> float:
    """RMS of a one-sided amplitude spectrum over :data:`BAND`."""
    return _rms(a[(f >= BAND[0]) & (f <= BAND[1])])


def _onsets(in_contact: np.ndarray) -> np.ndarray:
    """Indices of the samples where a contact begins (0 -> 1)."""
    return np.flatnonzero(np.diff(in_contact.astype(int)) > 0) + 1


@dataclass(frozen=True)
class CaseMetrics:
    """Numbers of one clearance run against the ideal mechanism.

    Outputs every 1e-5 s (the paper's step); "late" means after :data:`STARTUP`;
    deviations are differences from the ideal mechanism at the same instant; the
    dead-point ratios compare the RMS deviation within :data:`DEAD_WINDOW` of the
    interior dead points with the RMS elsewhere, both after the start-up.
    """

    peak_force: float        # N
    peak_da: float           # max |a - a_ideal| [m/s^2]
    rms_da: float            # RMS of a - a_ideal over the run [m/s^2]
    impacts: int             # contact onsets at accepted steps (SliderCrankResult.impacts)
    sampled_onsets: int      # contact onsets seen in the sampled outputs
    late_onsets: int         # of which after the start-up
    last_onset: float        # crank angle of the last sampled onset [deg]
    contact_fraction: float
    late_contact_fraction: float
    band: float              # RMS amplitude of the slider acceleration spectrum in BAND [m/s^2]
    band_ideal: float        # the same for the ideal mechanism
    band_late: float         # the same with the start-up replaced by the ideal acceleration
    band_startup: float      # the same with everything after the start-up replaced by it
    band_dev: float          # the same for (a - a_ideal) after the start-up, Hann-windowed
    mode_frequency: float    # peak of that deviation spectrum within MODE_SEARCH [Hz]
    spectrum_peak: float     # frequency of the largest amplitude of the slider acceleration [Hz]
    max_dx: float            # m
    max_dv: float            # m/s
    late_max_dv: float       # m/s
    dead_rms: float          # acceleration deviation near the dead points [m/s^2]
    other_rms: float         # elsewhere
    force_ratio: float       # dead-point ratio of contact force - |ideal joint force|
    moment_ratio: float      # dead-point ratio of crank moment - ideal moment
    dead_each: tuple[tuple[float, float], ...] = ()  # (dead point [deg], ratio of its window alone), acceleration

    @property
    def flight_fraction(self) -> float:
        return 1.0 - self.contact_fraction

    @property
    def dead_ratio(self) -> float:
        return self.dead_rms / self.other_rms


def _dead_ratio(dev: np.ndarray, dead: np.ndarray, other: np.ndarray) -> float:
    return _rms(dev[dead]) / _rms(dev[other])


def case_metrics(params: SliderCrankParams, cols: dict[str, np.ndarray], ideal: dict[str, np.ndarray]) -> CaseMetrics:
    """Measure a clearance run (``cols``) against the ideal mechanism (``ideal``)."""
    t, theta = cols["time"], cols["crank_angle"]

    def deviation(key: str) -> np.ndarray:
        return cols[key] - np.interp(t, ideal["time"], ideal[key])

    da, dm = deviation("slider_a"), deviation("crank_moment")
    df = cols["contact_force"] - np.hypot(*ideal_joint_force(params, np.radians(theta)))
    late = theta >= STARTUP
    points = dead_points(float(theta[-1]))
    near = _near_dead_points(theta, points)
    dead, other = near & late, ~near & late
    f, a = uniform_spectrum(t, cols["slider_a"], SPECTRUM_STEP)
    a_ideal = cols["slider_a"] - da
    _, a_late = uniform_spectrum(t, np.where(late, cols["slider_a"], a_ideal), SPECTRUM_STEP)
    _, a_startup = uniform_spectrum(t, np.where(late, a_ideal, cols["slider_a"]), SPECTRUM_STEP)
    fi, ai = uniform_spectrum(ideal["time"], ideal["slider_a"], SPECTRUM_STEP)
    fd, ad = hann_spectrum(t[late], da[late], SPECTRUM_STEP)
    search = (fd >= MODE_SEARCH[0]) & (fd <= MODE_SEARCH[1])
    in_contact = cols["in_contact"] > 0.5
    onsets = _onsets(in_contact)
    return CaseMetrics(
        peak_force=float(cols["contact_force"].max()), peak_da=float(np.abs(da).max()), rms_da=_rms(da),
        impacts=0, sampled_onsets=len(onsets) + int(in_contact[0]),
        late_onsets=int(np.count_nonzero(theta[onsets] >= STARTUP)),
        last_onset=float(theta[onsets[-1]]) if onsets.size else float("nan"),
        contact_fraction=float(in_contact.mean()), late_contact_fraction=float(in_contact[late].mean()),
        band=_band_rms(f, a), band_ideal=_band_rms(fi, ai), band_late=_band_rms(f, a_late),
        band_startup=_band_rms(f, a_startup), band_dev=_band_rms(fd, ad),
        mode_frequency=float(fd[search][np.argmax(ad[search])]), spectrum_peak=float(f[1:][np.argmax(a[1:])]),
        max_dx=float(np.abs(deviation("slider_x")).max()), max_dv=float(np.abs(deviation("slider_v")).max()),
        late_max_dv=float(np.abs(deviation("slider_v")[late]).max()), dead_rms=_rms(da[dead]), other_rms=_rms(da[other]),
        force_ratio=_dead_ratio(df, dead, other), moment_ratio=_dead_ratio(dm, dead, other),
        dead_each=tuple((p, _dead_ratio(da, _near_dead_points(theta, (p,)) & late, other)) for p in points))


def metrics_of(params: SliderCrankParams, result: SliderCrankResult, ideal: dict[str, np.ndarray]) -> CaseMetrics:
    """:func:`case_metrics` with the impact count of the run; NaN (counts 0) for a failed run."""
    if not result.success:
        values = {f.name: 0 if f.type == "int" else float("nan") for f in fields(CaseMetrics) if f.name != "dead_each"}
        return CaseMetrics(**{**values, "impacts": result.impacts})
    return replace(case_metrics(params, result.columns, ideal), impacts=result.impacts)


def response_lag(cols: dict[str, np.ndarray], reference: dict[str, np.ndarray], ideal: dict[str, np.ndarray]) -> float:
    """Time lag [s] of a run's acceleration deviation behind a reference run's, after the start-up.

    The lag maximises the cross-correlation of the two deviations (resampled every
    :data:`SPECTRUM_STEP`) within :data:`LAG_WINDOW`; positive: ``cols`` responds later.
    """
    def deviation(c: dict[str, np.ndarray], grid: np.ndarray) -> np.ndarray:
        dev = np.interp(grid, c["time"], c["slider_a"]) - np.interp(grid, ideal["time"], ideal["slider_a"])
        return dev - dev.mean()

    start = float(cols["time"][np.argmax(cols["crank_angle"] >= STARTUP)])
    grid = np.arange(start, min(cols["time"][-1], reference["time"][-1]), SPECTRUM_STEP)
    x, y = deviation(cols, grid), deviation(reference, grid)
    shifts = np.arange(-int(LAG_WINDOW / SPECTRUM_STEP), int(LAG_WINDOW / SPECTRUM_STEP) + 1)
    n = len(grid)
    corr = [np.dot(x[max(k, 0):n + min(k, 0)], y[max(-k, 0):n - max(k, 0)]) for k in shifts]
    return float(shifts[int(np.argmax(corr))] * SPECTRUM_STEP)


# -- measures of the contact history -------------------------------------------------

@dataclass(frozen=True)
class HistoryStats:
    """The joint's contact history at every accepted step of one run (see :class:`History`)."""

    onsets: int
    v0_first: float              # onset speed of the first impact [m/s]
    v0_last: float               # onset speed of the last contact, kept for the rest of it [m/s]
    last_onset: float            # deg
    damping_gain: float          # D/v0_eff of the last contact over that of the first impact
    zeta: tuple[float, float]    # damping ratio of the normal contact vibration in the last contact
    normal_frequency: tuple[float, float]  # its frequency [Hz]
    true_peak: float             # largest contact force at any accepted step [N]
    true_peak_angle: float       # deg
    first_duration: float        # first impact [s]
    shortest: float              # shortest closed contact [s]
    late_min_force: float        # smallest normal force after the start-up [N]
    late_min_angle: float        # deg
    dead_min_force: float        # smallest normal force in the dead-point windows [N]
    dead_contact: float          # contact fraction (of steps) in the dead-point windows after the start-up
    stick_fraction: float        # fraction of steps after the start-up with |v_T| < v_s
    stick_near_turning: float    # share of those steps within DEAD_WINDOW of the rod's turning points
    force_mismatch: float        # RMS(F_N - |F_ideal|) / mean |F_ideal| after the start-up
    angle_offset: float          # mean angle from the ideal force direction to the eccentricity [deg]
    max_angle_offset: float      # largest absolute angle between them [deg]


def _intervals(mask: np.ndarray) -> list[tuple[int, int]]:
    """``(first, last)`` index of each run of True in ``mask``."""
    edges = np.diff(np.concatenate(([0], mask.astype(int), [0])))
    return list(zip(np.flatnonzero(edges > 0), np.flatnonzero(edges < 0) - 1, strict=True))


def _contact_vibration(params: SliderCrankParams, force: float, penetration: float,
                       v0_eff: float) -> tuple[tuple[float, float], tuple[float, float]]:
    """Damping ratio and frequency [Hz] of the normal contact vibration about a mean load.

    Linearised law: stiffness ``k = n F / delta`` (Wang-Liu's ``K_eff`` barely changes
    with ``delta << c``), damping ``D F / v0_eff``; the moving mass lies between the
    slider's and the rod end's (see :func:`tangential_mode_range`).
    """
    joint = params.joint
    k = joint.law.exponent * force / penetration
    damping = joint.law.damping_factor * force / v0_eff
    rod_end = (params.rod_inertia + params.rod_mass * params.rod_length**2 / 4.0) / params.rod_length**2
    masses = sorted((params.slider_mass, rod_end))
    zeta = tuple(damping / (2.0 * math.sqrt(k * m)) for m in reversed(masses))
    freq = tuple(math.sqrt(k / m) / (2.0 * math.pi) for m in reversed(masses))
    return zeta, freq


def history_stats(params: SliderCrankParams, hist: History) -> HistoryStats:
    """Measure the contact history of one run."""
    out, theta, t = hist.out, hist.theta, hist.out["time"]
    contact = out["in_contact"] > 0.5
    onsets = _onsets(contact)
    starts = np.concatenate(([0], onsets)) if contact[0] else onsets  # a run may start in contact
    closed = [(a, b) for a, b in _intervals(contact) if b + 1 < len(t)]
    durations = [t[b + 1] - t[a] for a, b in closed]
    late = theta >= STARTUP
    near = _near_dead_points(theta, dead_points(float(theta[-1]))) & late
    v_min = params.joint.law.v_min
    v0_first, v0_last = float(out["v0"][starts[0]]), float(out["v0"][starts[-1]])
    last = late & contact
    zeta, freq = _contact_vibration(params, float(out["normal_force"][last].mean()),
                                    float(out["penetration"][last].mean()), max(v0_last, v_min))
    fx, fy = ideal_joint_force(params, np.radians(theta))
    ideal_mag = np.hypot(fx, fy)
    offset = np.degrees(np.angle(np.exp(1j * (np.arctan2(out["ecc_y"], out["ecc_x"]) - np.arctan2(fy, fx)))))
    stick = late & contact & (np.abs(out["slip_velocity"]) < STICTION_SPEED)
    k_peak, k_min = int(np.argmax(out["normal_force"])), int(np.argmin(np.where(late, out["normal_force"], np.inf)))
    return HistoryStats(
        onsets=hist.onsets, v0_first=v0_first, v0_last=v0_last, last_onset=float(theta[starts[-1]]),
        damping_gain=max(v0_first, v_min) / max(v0_last, v_min), zeta=zeta, normal_frequency=freq,
        true_peak=float(np.hypot(out["normal_force"], out["tangential_force"]).max()),
        true_peak_angle=float(theta[k_peak]), first_duration=float(durations[0]) if durations else float("nan"),
        shortest=float(min(durations)) if durations else float("nan"),
        late_min_force=float(out["normal_force"][k_min]), late_min_angle=float(theta[k_min]),
        dead_min_force=float(out["normal_force"][near].min()) if near.any() else float("nan"),
        dead_contact=float(contact[near].mean()) if near.any() else float("nan"),
        stick_fraction=float(stick.sum() / late.sum()),
        stick_near_turning=float(np.mean(_near_dead_points(theta[stick] % 360.0, ROD_TURNING)))
        if stick.any() else float("nan"),
        force_mismatch=_rms((out["normal_force"] - ideal_mag)[last]) / float(ideal_mag[last].mean()),
        angle_offset=float(np.mean(offset[last])), max_angle_offset=float(np.abs(offset[last]).max()))


# -- running the study ----------------------------------------------------------------

#: A finished sweep: each variant with its parameters, result and metrics.
SweepRows = list[tuple[Variant, SliderCrankParams, SliderCrankResult, CaseMetrics]]


def run_sweep(runner: Runner, sweep: Sweep, ideal: dict[str, np.ndarray], index: int, total: int) -> SweepRows:
    """Run every variant of ``sweep``, printing one progress line per run."""
    print(f"sweep {index}/{total}: {sweep.title}", flush=True)
    rows = []
    for variant in sweep.variants:
        params = SliderCrankParams.paper(**variant.changes)
        result = runner.result(params)
        rows.append((variant, params, result, metrics_of(params, result, ideal)))
    return rows


def sweep_lags(rows: SweepRows, ideal: dict[str, np.ndarray]) -> list[float]:
    """Lag of each variant's response behind the first variant's (see :func:`response_lag`)."""
    reference = rows[0][2]
    return [response_lag(result.columns, reference.columns, ideal) if result.success and reference.success
            else float("nan") for _, _, result, _ in rows]


@dataclass
class Diagnostics:
    """The diagnostic runs of the report."""

    tolerance: list[tuple[str, float, SliderCrankResult, CaseMetrics]]
    histories: dict[tuple[str, str], HistoryStats]     # (sweep stem, variant value) -> stats
    frozen_v_min: float
    frozen: dict[str, SweepRows]                       # friction -> cr sweep with v0 floored
    ideal_force: IdealForce
    mode_range: tuple[float, float]
    closed_form_error: float                           # max |fx / m_slider - a_slider of the ideal run| [m/s^2]


def tolerance_ladder(runner: Runner, ideal: dict[str, np.ndarray],
                     revolutions: float) -> list[tuple[str, float, SliderCrankResult, CaseMetrics]]:
    """The extreme cases (cr 0.3 with friction, cr 0.9 without) at each tolerance of the ladder."""
    print("diagnostics: solver tolerance ladder", flush=True)
    rows = []
    for cr, friction in ((0.3, "paper"), (0.9, "none")):
        params = SliderCrankParams.paper(cr=cr, friction=friction, revolutions=revolutions)
        for rtol, atol in TOLERANCE_LADDER:
            result = runner.result(params, clearance_settings(params, rtol, atol))
            rows.append((describe(params), rtol, result, metrics_of(params, result, ideal)))
    return rows


def contact_histories(runner: Runner, sweeps: Sequence[Sweep]) -> dict[tuple[str, str], HistoryStats]:
    """:func:`history_stats` of every clearance case, from runs recording every step."""
    print("diagnostics: contact histories at every accepted step", flush=True)
    stats = {}
    for sweep in sweeps:
        for variant in sweep.variants:
            params = SliderCrankParams.paper(**variant.changes)
            hist = runner.history(params)
            if hist.success:
                stats[(sweep.stem, variant.value)] = history_stats(params, hist)
    return stats


def frozen_v0_sweeps(runner: Runner, sweeps: Sequence[Sweep], v_min: float,
                     ideal: dict[str, np.ndarray]) -> dict[str, SweepRows]:
    """The restitution sweeps again with ``v_min`` raised to ``v_min`` (a parameter of the law)."""
    print(f"diagnostics: restitution sweeps with v0 floored at the first impact's {v_min:.4g} m/s", flush=True)
    frozen = {}
    for sweep in sweeps:
        if sweep.kind != "cr":
            continue
        rows = []
        for variant in sweep.variants:
            params = SliderCrankParams.paper(**variant.changes, v_min=v_min)
            result = runner.result(params)
            rows.append((variant, params, result, metrics_of(params, result, ideal)))
        frozen[sweep.friction] = rows
    return frozen


def run_diagnostics(runner: Runner, sweeps: Sequence[Sweep], ideal: dict[str, np.ndarray],
                    revolutions: float) -> Diagnostics:
    """All diagnostic runs (see the module docstring)."""
    tolerance = tolerance_ladder(runner, ideal, revolutions)
    histories = contact_histories(runner, sweeps)
    firsts = [h.v0_first for h in histories.values()]
    v_min = max(firsts) if firsts else exuclear.V_MIN_DEFAULT
    frozen = frozen_v0_sweeps(runner, sweeps, v_min, ideal)
    paper = SliderCrankParams.paper(revolutions=revolutions)
    force = ideal_force_stats(paper)
    return Diagnostics(tolerance, histories, v_min, frozen, force, tangential_mode_range(paper, force),
                       closed_form_error(paper, ideal))


# -- tables -------------------------------------------------------------------------



def _fmt(x: float, spec: str) -> str:
    return "-" if x is None or (isinstance(x, float) and math.isnan(x)) else format(x, spec)


def _case_record(column: str, value: str, m: CaseMetrics, failed: bool) -> dict[str, object]:
    """One table row of a sweep (SI units, micrometres for the position), in CSV order."""
    return {
        column: f"{value} (FAILED)" if failed else value,
        "peak contact force [N]": m.peak_force,
        "peak |a - ideal| [m/s2]": m.peak_da,
        "RMS a - ideal [m/s2]": m.rms_da,
        "impacts": m.impacts,
        "free flight": m.flight_fraction,
        "contact": m.contact_fraction,
        "band 150-350 Hz [m/s2]": m.band,
        "max |x - ideal| [um]": m.max_dx * 1e6,
        "max |v - ideal| [m/s]": m.max_dv,
        "RMS a - ideal, dead points [m/s2]": m.dead_rms,
        "RMS a - ideal, elsewhere [m/s2]": m.other_rms,
        "onsets after start-up": m.late_onsets,
        "last onset [deg]": m.last_onset,
        "contact after start-up": m.late_contact_fraction,
        "band, start-up replaced by ideal [m/s2]": m.band_late,
        "band, start-up only [m/s2]": m.band_startup,
        "band of a - ideal after start-up [m/s2]": m.band_dev,
        "peak of a - ideal spectrum [Hz]": m.mode_frequency,
        "max |v - ideal| after start-up [m/s]": m.late_max_dv,
        "dead-point ratio a": m.dead_ratio,
        "dead-point ratio force": m.force_ratio,
        "dead-point ratio moment": m.moment_ratio,
        "ratio a per dead point": " / ".join(f"{p:g}: {x:.2f}" for p, x in m.dead_each),
    }


#: Markdown formats of the sweep-table columns after the parameter column, and where
#: the first table (the key numbers) ends and the second (after the start-up) begins.
_CASE_FORMATS = (".0f", ".0f", ".1f", "d", ".3f", ".3f", ".2f", ".1f", ".3f", ".1f", ".1f",
                 "d", ".1f", ".3f", ".2f", ".2f", ".2f", ".0f", ".4f", ".2f", ".2f", ".2f", "s")
_FIRST_TABLE = 11


def _records(sweep: Sweep, rows: SweepRows) -> list[dict[str, object]]:
    return [_case_record(sweep.column, v.value, m, not r.success) for v, _, r, m in rows]


def sweep_table_md(sweep: Sweep, rows: SweepRows) -> str:
    """Markdown tables of one sweep's metrics: the key numbers, then those after the start-up."""
    records = _records(sweep, rows)
    header = list(records[0])
    cells = []
    for rec in records:
        values = list(rec.values())
        cells.append([values[0]] + [_fmt(x, f) for x, f in zip(values[1:], _CASE_FORMATS, strict=True)])
    cut = _FIRST_TABLE + 1
    first = markdown_table(header[:cut], [row[:cut] for row in cells])
    second = markdown_table(header[:1] + header[cut:], [row[:1] + row[cut:] for row in cells])
    return f"{first}\n\nAfter the start-up ({STARTUP:g}°) and dead-point ratios:\n\n{second}"




def _history_record(stem: str, value: str, h: HistoryStats) -> dict[str, object]:
    return {
        "sweep": stem, "case": value, "impacts": h.onsets, "v0 first [m/s]": h.v0_first,
        "v0 of the last contact [m/s]": h.v0_last, "last onset [deg]": h.last_onset,
        "D/v0 last over first": h.damping_gain, "zeta last contact (min)": h.zeta[0],
        "zeta last contact (max)": h.zeta[1], "normal vibration [Hz] (min)": h.normal_frequency[0],
        "normal vibration [Hz] (max)": h.normal_frequency[1], "true peak force [N]": h.true_peak,
        "true peak at [deg]": h.true_peak_angle, "first impact [us]": h.first_duration * 1e6,
        "shortest contact [us]": h.shortest * 1e6, "min F_N after start-up [N]": h.late_min_force,
        "at [deg]": h.late_min_angle, "min F_N near dead points [N]": h.dead_min_force,
        "contact near dead points": h.dead_contact, "stick fraction": h.stick_fraction,
        "stick near rod turning": h.stick_near_turning,
        "F_N vs ideal |F| (RMS rel.)": h.force_mismatch, "ecc - ideal F direction [deg]": h.angle_offset,
        "max abs(ecc - ideal F direction) [deg]": h.max_angle_offset,
    }


def _history_rows(diag: Diagnostics, sweeps: Sequence[Sweep]) -> list[tuple[str, str, HistoryStats]]:
    """``(case, friction, stats)`` of every recorded history, each parameter set once."""
    rows, seen = [], set()
    for sweep in sweeps:
        for variant in sweep.variants:
            h = diag.histories.get((sweep.stem, variant.value))
            params = SliderCrankParams.paper(**variant.changes)
            if h is None or params in seen:
                continue
            seen.add(params)
            name = variant.label if sweep.kind == "cr" else f"{variant.label}, cr = {MATERIAL_CR:g}"
            rows.append((name, sweep.friction, h))
    return rows


def history_table_md(diag: Diagnostics, sweeps: Sequence[Sweep]) -> str:
    """Markdown tables of the contact histories: onset speed and damping, then forces."""
    rows = _history_rows(diag, sweeps)
    damping = markdown_table(
        ["case", "friction", "impacts", "v0 first [m/s]", "v0 last contact [m/s]", "last onset [deg]",
         "D/v0: last / first", "zeta of last contact", "normal vibration [Hz]"],
        [[name, fr, h.onsets, f"{h.v0_first:.4f}", f"{h.v0_last:.2e}", f"{h.last_onset:.1f}", f"{h.damping_gain:.0f}",
          f"{h.zeta[0]:.2f}-{h.zeta[1]:.2f}", f"{h.normal_frequency[0]:.0f}-{h.normal_frequency[1]:.0f}"]
         for name, fr, h in rows])
    forces = markdown_table(
        ["case", "friction", "true peak force [N] at [deg]", "first impact [us]", "shortest contact [us]",
         "min F_N after start-up [N] at [deg]", "min F_N near dead points [N]", "contact near dead points",
         "stick fraction", "F_N vs ideal abs(F), RMS rel.", "ecc vs ideal F direction, mean / max [deg]"],
        [[name, fr, f"{h.true_peak:.0f} at {h.true_peak_angle:.3f}", f"{h.first_duration * 1e6:.0f}",
          f"{h.shortest * 1e6:.0f}", f"{h.late_min_force:.1f} at {h.late_min_angle:.0f}", f"{h.dead_min_force:.1f}",
          f"{h.dead_contact:.3f}", f"{h.stick_fraction:.3f}", f"{h.force_mismatch:.3f}",
          f"{h.angle_offset:+.1f} / {h.max_angle_offset:.1f}"] for name, fr, h in rows])
    return f"{damping}\n\n{forces}"


def _short_rows_md(rows: SweepRows, label: str) -> list[list[object]]:
    return [[label, v.label, m.impacts, m.late_onsets, f"{m.late_contact_fraction:.3f}", f"{m.peak_force:.0f}",
             f"{m.dead_rms:.1f}", f"{m.other_rms:.1f}", f"{m.dead_ratio:.2f}", f"{m.band:.2f}", f"{m.band_dev:.2f}",
             f"{m.mode_frequency:.0f}"] for v, _, _, m in rows]


_SHORT_HEADER = ["treatment", "case", "impacts", "onsets after start-up", "contact after start-up", "peak force [N]",
                 "RMS a - ideal, dead points", "elsewhere", "ratio", "band [m/s2]", "band of a - ideal", "peak [Hz]"]


# -- the claims -----------------------------------------------------------------------

def _increasing(values: Sequence[float]) -> bool:
    return all(b > a for a, b in zip(values, values[1:], strict=False))


def _span(values: Sequence[float], spec: str) -> str:
    lo, hi = min(values), max(values)
    return format(lo, spec) if format(lo, spec) == format(hi, spec) else f"{format(lo, spec)} to {format(hi, spec)}"


def _verdict(ok: bool, partly: bool = False) -> str:
    return "**agree**" if ok else ("**partly agree**" if partly else "**disagree**")


def _by_kind(done: Sequence[tuple[Sweep, SweepRows]], kind: str) -> list[tuple[Sweep, SweepRows]]:
    return [(s, r) for s, r in done if s.kind == kind]


def _case_spread(rows: SweepRows, key: str, after: float = 0.0) -> float:
    """Largest difference of ``key`` between the cases of a sweep at the same instant (beyond ``after`` deg)."""
    cols = [r.columns for _, _, r, _ in rows if r.success]
    t = cols[0]["time"][cols[0]["crank_angle"] >= after]
    values = np.array([np.interp(t, c["time"], c[key]) for c in cols])
    return float((values.max(axis=0) - values.min(axis=0)).max())


def claim_motion_md(done: Sequence[tuple[Sweep, SweepRows]], ideal: dict[str, np.ndarray]) -> tuple[str, str]:
    """Claim 1: cr and material barely change slider position and velocity."""
    metrics = [m for _, rows in done for _, _, _, m in rows]
    stroke = float(np.ptp(ideal["slider_x"]))
    v_range = float(np.ptp(ideal["slider_v"]))
    dx, dv, dv_late = (max(getattr(m, k) for m in metrics) for k in ("max_dx", "max_dv", "late_max_dv"))
    spread_x = max(_case_spread(rows, "slider_x") for _, rows in done)
    spread_v = max(_case_spread(rows, "slider_v") for _, rows in done)
    spread_v_late = max(_case_spread(rows, "slider_v", STARTUP) for _, rows in done)
    ok = max(dx, spread_x) / stroke < BARELY and max(dv, spread_v) / v_range < BARELY
    text = (f"Largest deviations from the ideal mechanism over all {len(metrics)} clearance runs: slider position "
            f"{dx * 1e6:.1f} µm ({100 * dx / stroke:.2f} % of the {stroke * 1e3:.0f} mm stroke; the radial clearance is "
            f"{SliderCrankParams.paper().clearance * 1e6:.0f} µm, so the journal simply sits against the bearing wall), "
            f"slider velocity {dv:.3f} m/s ({100 * dv / v_range:.1f} % of the ideal velocity's range "
            f"{v_range:.2f} m/s), reached during the start-up impacts; after the start-up at most {dv_late:.4f} m/s. "
            f"Largest difference between two cases of one sweep at the same instant: position {spread_x * 1e6:.1f} µm, "
            f"velocity {spread_v:.3f} m/s ({spread_v_late:.4f} m/s after the start-up). Verdict "
            f"({100 * BARELY:.0f} % of the curve's range as \"barely\"): {_verdict(ok)}.")
    return _verdict(ok), text


def _dead_point_strength(ratios: Sequence[float]) -> str:
    """How the oscillation near the dead points compares with elsewhere, in one sentence."""
    if max(ratios) < 1.0:
        return "It is weaker at the dead points than elsewhere."
    return (f"Over all dead-point windows together it is at most {max(ratios):.2f} times as strong (RMS) as "
            "elsewhere; per dead point see above.")


def _per_dead_point(done: Sequence[tuple[Sweep, SweepRows]]) -> tuple[str, list[str]]:
    """Acceleration ratio of each dead point's window, per friction law: the text, and the
    ``friction, point`` pairs where every run has a ratio of at least :data:`CONCENTRATED`."""
    texts, concentrated = [], []
    for friction in FRICTIONS:
        metrics = [m for s, rows in done if s.friction == friction for *_, m in rows if m.dead_each]
        if not metrics:
            continue
        cells = []
        for k, (point, _) in enumerate(metrics[0].dead_each):
            values = [m.dead_each[k][1] for m in metrics]
            cells.append(f"{point:g}°: {_span(values, '.2f')}")
            if min(values) >= CONCENTRATED:
                concentrated.append(f"θ = {point:g}° with friction {friction}")
        texts.append(f"friction {friction}: " + ", ".join(cells))
    return "; ".join(texts), concentrated


def claim_dead_points_md(done: Sequence[tuple[Sweep, SweepRows]], diag: Diagnostics) -> tuple[str, str]:
    """Claim 2: acceleration, force and moment oscillate strongly near the dead points, more so for higher cr."""
    cr_rows = _by_kind(done, "cr")
    ratios = [m.dead_ratio for _, rows in done for *_, m in rows]
    f_ratios = [m.force_ratio for _, rows in done for *_, m in rows]
    m_ratios = [m.moment_ratio for _, rows in done for *_, m in rows]
    concentrated = min(ratios) >= CONCENTRATED
    grows = all(_increasing([m.dead_rms for *_, m in rows]) for _, rows in cr_rows)
    each, at_one = _per_dead_point(done)
    verdict = _verdict(concentrated and grows, partly=grows or bool(at_one))
    late = [m.late_onsets for _, rows in done for *_, m in rows]
    late_contact = [m.late_contact_fraction for _, rows in done for *_, m in rows]
    hist = list(diag.histories.values())
    f = diag.ideal_force
    parts = [
        f"Dead-point ratio (RMS of the deviation within ±{DEAD_WINDOW:g}° of the interior dead points over the RMS "
        f"elsewhere, both after {STARTUP:g}°): slider acceleration {_span(ratios, '.2f')}, contact force "
        f"{_span(f_ratios, '.2f')}, crank moment {_span(m_ratios, '.2f')} over all runs. Acceleration RMS near the "
        "dead points against cr: " + "; ".join(
            f"friction {s.friction}: " + ", ".join(f"{m.dead_rms:.1f}" for *_, m in rows) + " m/s²"
            for s, rows in cr_rows) + f" (cr = {', '.join(f'{cr:g}' for cr in CR_SWEEP)}). "
        + ("The deviations are smaller near the dead points than elsewhere in every run. " if max(ratios) < 1.0
           else "")
        + f"Each dead point's window alone against elsewhere: {each}. "
        + (f"Concentrated (ratio ≥ {CONCENTRATED:g} in every run) at: {'; '.join(at_one)}. " if at_one else "")
        + f"Verdict (ratio ≥ {CONCENTRATED:g} and growing with cr): {verdict}.",
        "",
        ("Why: **the journal never leaves the bearing after the start-up.** " if max(late) == 0 else "Why: ")
        + f"Contact onsets after {STARTUP:g}° in the sampled outputs: {_span(late, 'd')} per run; contact fraction "
        f"after {STARTUP:g}°: {_span(late_contact, '.3f')}. The last contact of a run begins at "
        f"{_span([h.last_onset for h in hist], '.1f')}°"
        + (" and lasts to the end of the run." if min(late_contact) == 1.0 else "."),
        "",
        "- *The joint force does not reverse at the dead points.* The ideal joint force at B (closed form, "
        f"`ideal_joint_force`; its slider acceleration matches the ideal Exudyn run to {diag.closed_form_error:.2g} "
        "m/s²) has its horizontal component, slider mass × slider acceleration, change sign at "
        f"θ = {', '.join(f'{a:.1f}°' for a in f.fx_zeros)} (mid-stroke, where the slider acceleration vanishes), "
        f"not at the dead points. Its magnitude never falls below {f.min_force:.1f} N (at θ = {f.min_angle:.1f}°), "
        "because the rod's weight and rotary inertia keep a vertical component, and it is largest near the dead "
        f"points ({f.dead_min:.1f} to {f.dead_max:.1f} N within the windows; overall maximum {f.max_force:.1f} N). "
        f"Its direction turns {f.turns_per_revolution:+.2f} times round per revolution, at most "
        f"{f.max_turn_rate:.2f}° per crank degree (at θ = {f.max_turn_angle:.0f}°): the journal slides round the "
        "wall after it instead of crossing the clearance. The simulated normal force follows the ideal magnitude "
        f"(RMS difference {_span([h.force_mismatch for h in hist], '.3f')} of its mean after the start-up) and the "
        "eccentricity follows the ideal force direction: mean angle between them "
        f"{_span([h.angle_offset for h in hist], '+.1f')}° (with friction the resultant of normal and tangential "
        "force follows it, so the normal may turn by up to "
        f"atan(μ_d) = {math.degrees(math.atan(exuclear.ModifiedCoulomb.paper().mu_d)):.0f}°); the swings about it, "
        f"up to {max(h.max_angle_offset for h in hist):.0f}°, are the sliding oscillation described below.",
        f"- *Contact is not lost at the dead points:* the normal force within the dead-point windows stays above "
        f"{min(h.dead_min_force for h in hist):.1f} N (the smallest after the start-up, "
        f"{_span([h.late_min_force for h in hist], '.1f')} N, comes at θ ≈ "
        f"{_span([h.late_min_angle % 360.0 for h in hist], '.0f')}° mod 360, next to the sign change of the "
        f"horizontal force); contact fraction within the windows {_span([h.dead_contact for h in hist], '.3f')}.",
        "- *cr hardly matters once the contact is permanent, because v0 is frozen at a tiny value.* docs/physics.md "
        "section 2.3 keeps v0, the penetration rate at the onset of the current contact, until the contact ends. "
        "The start-up bounces lose speed one after another; the first impact has v0 = "
        f"{_span([h.v0_first for h in hist], '.4f')} m/s, the last (permanent) contact "
        f"{_span([h.v0_last for h in hist], '.2e')} m/s. The hysteresis term D·δ̇/v0 of the permanent contact is "
        f"therefore {_span([h.damping_gain for h in hist], '.0f')} times that of the first impact per unit "
        "penetration rate; the normal contact vibration about the mean load (linearised law, moving mass between "
        f"slider and rod end; {_span([x for h in hist for x in h.normal_frequency], '.0f')} Hz) has a damping ratio "
        f"of {_span([x for h in hist for x in h.zeta], '.2f')}, so it dies out within a few of its sub-millisecond "
        "periods. cr enters only through D and the v0 of that "
        "last contact, which is itself set by where the bounce sequence happens to end.",
        "- *What oscillates is the journal sliding to and fro along the wall* (the wiggles of the eccentricity "
        "direction, see the orbit and deviation-spectrum figures), a pendulum on a circular track of radius c "
        "whose restoring force is the contact force: f = √(F/(m c))/2π = "
        f"{diag.mode_range[0]:.0f}-{diag.mode_range[1]:.0f} Hz for the ideal force range and m between slider and "
        "rod end. It starts where the force direction swings round (near the sign changes of its horizontal "
        f"component, fastest at θ = {f.max_turn_angle:.0f}° mod 360) and is barely damped without friction, since "
        "the normal hysteresis does not act along the wall. " + _dead_point_strength(ratios)
        + (f" Where one dead point stands out ({'; '.join(at_one)}), it is this oscillation, excited by the "
           f"swing of the force direction before it (fastest at θ = {f.max_turn_angle:.0f}° mod 360), still "
           "ringing as the crank passes the dead point; it does not grow with cr." if at_one else ""),
    ]
    return verdict, "\n".join(parts)


def _band_source(metrics: Sequence[CaseMetrics]) -> str:
    """Which part of the run the 150-350 Hz band content comes from, in one sentence."""
    late = sum(m.band_late > m.band_startup for m in metrics)
    if late == len(metrics):
        return "in every run the band comes mostly from after the start-up, not from the start-up impacts."
    if late == 0:
        return "in every run the band comes mostly from the start-up impacts."
    return f"the band comes mostly from after the start-up in {late} of {len(metrics)} runs, else from the start-up."


def claim_spectrum_md(done: Sequence[tuple[Sweep, SweepRows]], crank_frequency: float,
                      resolution: float) -> tuple[str, str]:
    """Claim 3: main spectrum near the crank frequency; a 150-350 Hz band that grows with cr."""
    metrics = [m for _, rows in done for *_, m in rows]
    main_ok = all(abs(m.spectrum_peak - crank_frequency) <= resolution for m in metrics)
    cr_rows = _by_kind(done, "cr")
    band_grows = all(_increasing([m.band for *_, m in rows]) for _, rows in cr_rows)
    dev_grows = all(_increasing([m.band_dev for *_, m in rows]) for _, rows in cr_rows)
    in_band = [m.mode_frequency for m in metrics]
    band_present = min(m.band_dev for m in metrics) > 10.0 * max(m.band_ideal for m in metrics)
    lines = [
        f"Largest amplitude of the slider-acceleration spectrum (record of {1.0 / resolution:.3g} s, resolution "
        f"{resolution:.2f} Hz): "
        f"{_span([m.spectrum_peak for m in metrics], '.2f')} Hz in every run, the crank frequency "
        f"{crank_frequency:.2f} Hz: {_verdict(main_ok)}.",
        "",
        f"Band {BAND[0]:g}-{BAND[1]:g} Hz, RMS of the one-sided amplitude spectrum over the whole run against cr: "
        + "; ".join(f"friction {s.friction}: " + ", ".join(f"{m.band:.2f}" for *_, m in rows) for s, rows in cr_rows)
        + f" m/s² (ideal mechanism: {max(m.band_ideal for m in metrics):.1e} m/s²). The same for the acceleration "
        "deviation after the start-up (Hann window, no start-up impacts): "
        + "; ".join(f"friction {s.friction}: " + ", ".join(f"{m.band_dev:.2f}" for *_, m in rows)
                    for s, rows in cr_rows)
        + f" m/s²; its spectrum peaks at {_span(in_band, '.0f')} Hz. A band is there "
        f"({'present' if band_present else 'absent'}: far above the ideal mechanism's), but it "
        f"{'grows' if band_grows and dev_grows else 'does not grow'} with cr: "
        f"{_verdict(band_present and band_grows and dev_grows, partly=band_present)}.",
        "",
        f"Why: {_band_source(metrics)} With the start-up replaced "
        f"by the ideal acceleration the band RMS is {_span([m.band_late for m in metrics], '.2f')} m/s², with "
        f"everything after it replaced {_span([m.band_startup for m in metrics], '.2f')} m/s² (whole run "
        f"{_span([m.band for m in metrics], '.2f')} m/s²; a short impact adds about the same amplitude to every "
        "frequency, the more so the shorter the record). After the start-up the band holds the journal's sliding "
        "oscillation along the wall (claim 2), whose frequency is set by the contact force, the masses and the "
        "clearance and whose damping comes from friction; cr acts only on the normal vibration, which is heavily "
        "damped in the permanent contact and lies at kilohertz. The frozen-v0 diagnostic shows what a different "
        "v0 treatment changes.",
    ]
    return _verdict(main_ok and band_present and band_grows and dev_grows, partly=main_ok), "\n".join(lines)


def claim_materials_md(done: Sequence[tuple[Sweep, SweepRows]], diag: Diagnostics,
                       lags: dict[str, list[float]]) -> tuple[str, str]:
    """Claim 4: softer journal materials delay the response."""
    lines, verdicts = [], []
    for sweep, rows in _by_kind(done, "material"):
        order = sorted(range(len(rows)), key=lambda k: -exuclear.composite_modulus(rows[k][1].journal_material,
                                                                                     rows[k][1].bearing_material))
        hist = [diag.histories.get((sweep.stem, rows[k][0].value)) for k in order]
        if any(h is None for h in hist):
            continue
        peaks = [h.true_peak_angle for h in hist]
        durations = [h.first_duration for h in hist]
        lag = [lags[sweep.stem][k] for k in order]
        ok = _increasing(peaks) and _increasing(durations) and all(b >= a for a, b in zip(lag, lag[1:], strict=False))
        verdicts.append(ok)
        names = ", ".join(rows[k][0].value for k in order)
        lines.append(
            f"- friction {sweep.friction} ({names}, stiffest first): first-impact force peak at θ = "
            + ", ".join(f"{p:.4f}" for p in peaks) + "°; first impact lasts "
            + ", ".join(f"{d * 1e6:.0f}" for d in durations) + " µs; lag of the acceleration deviation after the "
            "start-up behind the steel journal's: " + ", ".join(f"{x * 1e6:.0f}" for x in lag) + " µs (resolution "
            f"{SPECTRUM_STEP * 1e6:.0f} µs); peak contact force "
            + ", ".join(f"{rows[k][3].peak_force:.0f}" for k in order) + " N (sampled).")
    ok = bool(verdicts) and all(verdicts)
    text = ("\n".join(lines) + "\n\nSofter journals make every contact longer and later (Hertzian contact time grows "
            "as E*^(-2/5)) and the permanent contact deeper, which shifts the later oscillation by tens of "
            f"microseconds, a fraction of a crank degree. Verdict: {_verdict(ok)}, but the delays are small.")
    return _verdict(ok), text


def friction_md(done: Sequence[tuple[Sweep, SweepRows]], diag: Diagnostics) -> str:
    """What the paper's friction law changes."""
    pairs = {}
    for sweep, rows in done:
        for variant, _, _, m in rows:
            pairs.setdefault((sweep.kind, variant.value), {})[sweep.friction] = m
    both = [p for p in pairs.values() if set(FRICTIONS) <= set(p)]
    stick = [h for (stem, _), h in diag.histories.items() if stem.endswith("paper")]
    slip_free = [h for (stem, _), h in diag.histories.items() if stem.endswith("none")]
    return (
        "With the paper's eq. 11 (μ_s = 0.3, μ_d = 0.25) the journal sticks to the bearing when the slip of the "
        "surfaces falls below v_s; stick fraction (of steps) after the "
        f"start-up {_span([h.stick_fraction for h in stick], '.3f')}, of which "
        f"{_span([h.stick_near_turning for h in stick], '.2f')} within ±{DEAD_WINDOW:g}° of θ = "
        f"{', '.join(f'{a:g}°' for a in ROD_TURNING)} (mod 360), where the rod's angular velocity vanishes. "
        "Sliding friction turns the contact point away from the "
        f"ideal force direction (mean {_span([h.angle_offset for h in stick], '+.1f')}° against "
        f"{_span([h.angle_offset for h in slip_free], '+.1f')}° without friction). It changes the sliding "
        "oscillation: deviation-spectrum peak "
        f"{_span([p['none'].mode_frequency for p in both], '.0f')} Hz without friction against "
        f"{_span([p['paper'].mode_frequency for p in both], '.0f')} Hz with it; dead-point ratio "
        f"{_span([p['none'].dead_ratio for p in both], '.2f')} against {_span([p['paper'].dead_ratio for p in both], '.2f')}; "
        f"start-up impacts {_span([p['none'].impacts for p in both], 'd')} against "
        f"{_span([p['paper'].impacts for p in both], 'd')}. It does not bring back free flight: contact after the "
        f"start-up {_span([p['paper'].late_contact_fraction for p in both], '.3f')}.")


def tolerance_md(diag: Diagnostics) -> str:
    """The tolerance ladder as Markdown, with the changes from the chosen tolerance to the tightest."""
    header = ["case", "rtol", "steps", "wall [s]", "impacts", "peak force [N]", "contact", "RMS a - ideal",
              "dead-point ratio", "band [m/s2]", "max abs(x - ideal) [um]"]
    rows = [[name, f"{rtol:g}", r.steps, f"{r.wall_time:.1f}", m.impacts, f"{m.peak_force:.0f}",
             f"{m.contact_fraction:.4f}", f"{m.rms_da:.1f}", f"{m.dead_ratio:.3f}", f"{m.band:.3f}",
             f"{m.max_dx * 1e6:.3f}"] for name, rtol, r, m in diag.tolerance]
    notes = []
    by_case: dict[str, dict[float, CaseMetrics]] = {}
    for name, rtol, _, m in diag.tolerance:
        by_case.setdefault(name, {})[rtol] = m
    loose, chosen, tight = (rtol for rtol, _ in TOLERANCE_LADDER)
    for name, ladder in by_case.items():
        if not {loose, chosen, tight} <= set(ladder):
            continue
        a, b, c = ladder[loose], ladder[chosen], ladder[tight]
        notes.append(
            f"- {name}: impacts {a.impacts} / {b.impacts} / {c.impacts} at rtol {loose:g} / {chosen:g} / {tight:g}; "
            f"from rtol {chosen:g} to {tight:g} the RMS acceleration deviation changes by "
            f"{100 * abs(c.rms_da / b.rms_da - 1):.1f} %, the dead-point ratio by "
            f"{100 * abs(c.dead_ratio / b.dead_ratio - 1):.1f} %, the band by {100 * abs(c.band / b.band - 1):.1f} %, "
            f"the sampled peak force by {100 * abs(c.peak_force / b.peak_force - 1):.1f} % (the sampled peak depends on "
            "where the samples fall, see the contact history).")
    return markdown_table(header, rows) + "\n\n" + "\n".join(notes)


def sampling_md(done: Sequence[tuple[Sweep, SweepRows]], diag: Diagnostics) -> str:
    """What outputs every 1e-5 s show of the impacts."""
    pairs = [(m, diag.histories[(s.stem, v.value)]) for s, rows in done for v, _, _, m in rows
             if (s.stem, v.value) in diag.histories]
    if not pairs:
        return "No contact history was recorded."
    under = [1.0 - m.peak_force / h.true_peak for m, h in pairs]
    same = all(m.impacts == h.onsets for m, h in pairs)
    seen = sum(m.sampled_onsets for m, _ in pairs)
    total = sum(h.onsets for _, h in pairs)
    return (
        "The runs recording every accepted step take the same steps as the main runs (impact counts "
        f"{'equal' if same else 'DIFFERENT'}). The shortest contact lasts "
        f"{_span([h.shortest * 1e6 for m, h in pairs], '.0f')} µs, the first impact "
        f"{_span([h.first_duration * 1e6 for m, h in pairs], '.0f')} µs: each impact spans several samples at "
        f"{SPECTRUM_STEP:g} s, and the sampled outputs show {seen} of the {total} contact onsets of all runs. They "
        f"understate the peak force by {_span([100 * u for u in under], '.1f')} % (true peak "
        f"{_span([h.true_peak for m, h in pairs], '.0f')} N against sampled "
        f"{_span([m.peak_force for m, h in pairs], '.0f')} N). The sliding oscillation (hundreds of Hz) and the "
        f"normal contact vibration (kHz) lie far below the {0.5 / SPECTRUM_STEP / 1e3:.0f} kHz Nyquist frequency: "
        "the sampling neither hides oscillations at the dead points nor explains the disagreement.")


def _frozen_summary(friction: str, frozen: SweepRows, default: SweepRows) -> str:
    """How the raised v_min changes one restitution sweep, in one sentence."""
    bouncing = [f"{v.label} (last onset at {m.last_onset:.0f}°)" for v, *_, m in frozen if m.late_onsets > 0]
    changes = ", ".join(
        f"{v.label}: {d.late_onsets} → {m.late_onsets} onsets after start-up, dead-point RMS {d.dead_rms:.1f} → "
        f"{m.dead_rms:.1f} m/s², ratio {d.dead_ratio:.2f} → {m.dead_ratio:.2f}"
        for (v, *_, m), (*_, d) in zip(frozen, default, strict=True))
    keeps = (f"the journal keeps bouncing after the start-up for {', '.join(bouncing)} only" if bouncing
             else "the journal still settles during the start-up in every case")
    growth = frozen[-1][3].dead_rms / frozen[0][3].dead_rms
    ratio = max(m.dead_ratio for *_, m in frozen)
    verdict = (f"Dead-point RMS at the highest cr {growth:.1f} times that at the lowest, "
               f"{'more so for higher cr as the paper says' if growth > 1.0 else 'not growing with cr'}; "
               f"dead-point ratio at most {ratio:.2f}, "
               f"{'concentrated at the dead points' if ratio >= CONCENTRATED else 'not concentrated at the dead points'}.")
    return f"- friction {friction}: {keeps} (default → raised v_min: {changes}). {verdict}"


def frozen_md(diag: Diagnostics, done: Sequence[tuple[Sweep, SweepRows]]) -> str:
    """The frozen-v0 demonstration as Markdown."""
    rows = []
    for friction, frozen_rows in diag.frozen.items():
        rows += _short_rows_md(frozen_rows, f"v_min = {diag.frozen_v_min:.4f}, friction {friction}")
    default = {s.friction: r for s, r in _by_kind(done, "cr")}
    summaries = [_frozen_summary(fr, r, default[fr]) for fr, r in diag.frozen.items() if fr in default]
    return (
        "A modelling difference that could explain the paper's picture: a v0 that is not lowered by the settling "
        "bounces, as if every contact were damped like the first impact (or v0 were a fixed reference speed). "
        "Demonstrated without touching the model through the law's parameter `v_min`, raised from "
        f"{exuclear.V_MIN_DEFAULT:g} m/s to the first impact's onset speed {diag.frozen_v_min:.4f} m/s "
        "(v0_eff = max(v0, v_min)); restitution sweeps (cr = "
        f"{', '.join(f'{cr:g}' for cr in CR_SWEEP)}):\n\n" + markdown_table(_SHORT_HEADER, rows) + "\n\n"
        + "\n".join(summaries) + "\n\nThe paper does not say how it handles v0 in a long contact; docs/physics.md fixes "
        "it (section 2.3: the onset rate of the current contact, floored at 1e-3 m/s) and the library keeps it.")


# -- report ----------------------------------------------------------------------------

def _intro_md(revolutions: float) -> str:
    p = SliderCrankParams.paper()
    return (
        "# Slider-crank with a revolute clearance joint: the paper's Figs. 10-20\n\n"
        "Source problem: example 2 of Wang, Liu, Ma, Tong, J. Mech. Sci. Technol. 31(2) (2017) 587-597 "
        f"(docs/physics.md section 6.2). Crank {p.crank_length:g} m at {p.crank_speed * 30 / math.pi:.0f} rpm, rod "
        f"{p.rod_length:g} m, slider {p.slider_mass:g} kg; clearance joint between rod and slider, R_B = "
        f"{p.bearing_radius * 1e3:g} mm, c = {p.clearance * 1e3:g} mm, L = {p.bearing_length * 1e3:g} mm, Wang-Liu "
        f"law; the journal starts centred. {revolutions:g} revolutions.\n\n"
        "Runs: minimal formulation (kinematic tree), DOPRI5 with steps ≤ 1e-5 s (the paper's maximum) and "
        f"rtol = {RTOL:g}, atol = {ATOL:g} m instead of the paper's rtol 1e-6 (the tolerance ladder below shows "
        "why); outputs every 1e-5 s. Baseline: the ideal mechanism (redundant formulation, generalized-alpha, "
        "step 1e-5 s), dashed in every figure; for the contact force it is the force the ideal joint transmits, "
        "from the closed form `ideal_joint_force` (the `contact_force` column of the ideal run). Friction \"none\" or "
        "\"paper\" (eq. 11, Table 1: μ_s = 0.3, μ_d = 0.25, v_s = 0.1 mm/s, v_d = 10 mm/s).\n\n"
        "Definitions: *deviation* = value minus the ideal mechanism's at the same instant; *start-up* = crank "
        f"angle below {STARTUP:g}° (the journal's first bounces); *dead-point windows* = ±{DEAD_WINDOW:g}° around "
        "the interior dead points (crank at 180°, 360°, ...), compared with the rest after the start-up; *band* "
        f"= RMS of the one-sided amplitude spectrum between {BAND[0]:g} and {BAND[1]:g} Hz (whole run as the "
        "paper's FFT, and for the acceleration deviation after the start-up with a Hann window); *impacts* = "
        "contact onsets at accepted steps. Figures: position and velocity overlaid with their deviation below; "
        "acceleration, contact force, crank moment and spectra one panel per case, y-range fitted to the curves "
        "after the start-up (off-scale start-up peaks are written in the panel); dotted lines mark the dead "
        "points.\n")


def _claims_summary_md(claims: Sequence[tuple[str, str, str]]) -> str:
    return "## The paper's claims\n\n" + markdown_table(["claim (docs/physics.md section 6.2)", "verdict"],
                                                    [[name, verdict] for name, verdict, _ in claims]) + "\n"


def _sweep_section_md(sweep: Sweep, rows: SweepRows, lags: list[float] | None) -> str:
    quantities = ("slider_x", "slider_v", "slider_a", "contact_force", "crank_moment", "orbit", "spectrum",
                  "deviation_spectrum")
    figures = "\n".join(f"![{sweep.title}: {q}]({sweep.stem}_{q}.png)" for q in quantities)
    lag_text = ""
    if lags is not None:
        lag_text = ("\n\nLag of the acceleration deviation after the start-up behind the first case: "
                    + ", ".join(f"{v.value} {x * 1e6:.0f} µs" for (v, *_), x in zip(rows, lags, strict=True)) + ".")
    return (f"### {sweep.title}\n\nCSV: `{sweep.stem}.csv`.\n\n{sweep_table_md(sweep, rows)}{lag_text}\n\n"
            f"{figures}\n")


def _failures_md(failures: list[tuple[str, str]]) -> str:
    if not failures:
        return ""
    return "## Failed runs\n\n" + "\n".join(f"- {name}: {message}" for name, message in failures) + "\n"


def write_report(path: str, revolutions: float, done: Sequence[tuple[Sweep, SweepRows]], diag: Diagnostics,
                 lags: dict[str, list[float]], ideal: dict[str, np.ndarray], runner: Runner, wall: float) -> str:
    """Write the Markdown report; returns ``path``."""
    p = SliderCrankParams.paper()
    crank_frequency = p.crank_speed / (2.0 * math.pi)
    resolution = 1.0 / (ideal["time"][-1] - ideal["time"][0])
    claims = [
        ("cr and material barely change slider position and velocity", *claim_motion_md(done, ideal)),
        ("slider acceleration, contact force and crank moment oscillate strongly near the dead points, more so for "
         "higher cr", *claim_dead_points_md(done, diag)),
        ("main acceleration spectrum near the crank frequency, band near 150-350 Hz growing with cr",
         *claim_spectrum_md(done, crank_frequency, resolution)),
        ("softer journal materials delay the response", *claim_materials_md(done, diag, lags)),
    ]
    parts = [_intro_md(revolutions), _claims_summary_md(claims)]
    parts += [f"### Claim {k}: {name}\n\n{text}\n" for k, (name, _, text) in enumerate(claims, start=1)]
    parts.append("### What the friction law changes\n\n" + friction_md(done, diag) + "\n")
    parts.append("## Sweeps\n")
    parts += [_sweep_section_md(s, rows, lags.get(s.stem) if s.kind == "material" else None) for s, rows in done]
    parts.append("## Diagnostics\n\n### Solver tolerance\n\nThe two extreme cases at three DOPRI5 tolerances "
                 "(outputs every 1e-5 s). CSV: `diagnostics_tolerance.csv`.\n\n" + tolerance_md(diag) + "\n")
    parts.append("### Contact history at every accepted step\n\nThe same runs recording every accepted step "
                 "(`v0` is the joint's onset speed, see docs/physics.md section 2.3). CSV: `diagnostics_history.csv`. "
                 "![contact history](diagnostic_contact_history.png)\n\n" + history_table_md(diag, [s for s, _ in done])
                 + "\n\n" + sampling_md(done, diag) + "\n")
    parts.append("### v0 floored at the first impact's speed\n\nCSV: `diagnostics_frozen_v0.csv`. "
                 "![frozen v0](diagnostic_frozen_v0_slider_a.png)\n\n" + frozen_md(diag, done) + "\n")
    parts.append(f"Total: {len(runner.results) + len(runner.histories)} runs, wall time {wall:.0f} s.\n")
    parts.append(_failures_md(runner.failures()))
    with open(path, "w", encoding="utf-8") as f:
        f.write("\n".join(part for part in parts if part))
    return path


# -- files ----------------------------------------------------------------------------

def write_sweep_files(sweep: Sweep, rows: SweepRows, ideal: dict[str, np.ndarray], directory: str,
                      revolutions: float) -> list[str]:
    """The figures and the CSV table of one sweep; returns the paths."""
    cases = [(v.label, r.columns) for v, _, r, _ in rows if r.success]
    paths = []
    if cases:
        paths += slider_crank_sweep_figures(
            cases, ideal, rows[0][1].clearance, directory, sweep.stem, title=sweep.title,
            dead_points=dead_points(360.0 * revolutions), zoom_after=STARTUP, band=BAND, spectrum_step=SPECTRUM_STEP,
            deviation_after=STARTUP)
    paths.append(write_csv(os.path.join(directory, f"{sweep.stem}.csv"), _records(sweep, rows)))
    return paths


def write_diagnostic_files(runner: Runner, done: Sequence[tuple[Sweep, SweepRows]], diag: Diagnostics,
                           ideal: dict[str, np.ndarray], directory: str, revolutions: float) -> list[str]:
    """CSV tables and figures of the diagnostics; returns the paths."""
    paths = [write_csv(os.path.join(directory, "diagnostics_tolerance.csv"),
                       [{"case": name, "rtol": rtol, "steps": r.steps, "wall [s]": r.wall_time,
                         **_case_record("value", "", m, not r.success)} for name, rtol, r, m in diag.tolerance])]
    if diag.histories:
        paths.append(write_csv(os.path.join(directory, "diagnostics_history.csv"),
                               [_history_record(stem, value, h) for (stem, value), h in diag.histories.items()]))
    frozen = [{"friction": fr, **_case_record("cr", v.value, m, not r.success)}
              for fr, rows in diag.frozen.items() for v, _, r, m in rows]
    if frozen:
        paths.append(write_csv(os.path.join(directory, "diagnostics_frozen_v0.csv"), frozen))
    marks = dead_points(360.0 * revolutions)
    paths.append(_history_figure(runner, done, directory, revolutions))
    for friction, rows in diag.frozen.items():
        cases = [(f"{v.label}, v_min {diag.frozen_v_min:.3f} m/s", r.columns) for v, _, r, _ in rows if r.success]
        if cases:
            paths += slider_crank_sweep_figures(
                cases, ideal, rows[0][1].clearance, directory, f"diagnostic_frozen_v0_friction-{friction}",
                title=f"restitution sweep with v0 floored at the first impact's speed, friction {friction}",
                dead_points=marks, zoom_after=STARTUP, band=BAND, spectrum_step=SPECTRUM_STEP, deviation_after=STARTUP,
                quantities=FROZEN_FIGURES)
    if "none" in diag.frozen:
        paths.append(_frozen_overview(diag, done, ideal, directory, marks))
    return paths


def _history_figure(runner: Runner, done: Sequence[tuple[Sweep, SweepRows]], directory: str,
                    revolutions: float) -> str:
    """Normal force against the ideal force, eccentricity direction and v0 of the restitution sweeps."""
    force_curves, angle_curves, v0_curves = [], [], []
    for sweep, rows in done:
        if sweep.kind != "cr":
            continue
        for variant, params, _, _ in {id(row): row for row in (rows[0], rows[-1])}.values():
            hist = runner.histories.get((params, clearance_settings(params, output_step=EVERY_STEP)))
            if hist is None or not hist.success:
                continue
            label = f"{variant.label}, friction {sweep.friction}"
            out, theta = hist.out, hist.theta
            force_curves.append((label, theta, out["normal_force"], "-"))
            angle_curves.append((label, theta, np.degrees(np.unwrap(np.arctan2(out["ecc_y"], out["ecc_x"]))), "-"))
            v0_curves.append((label, theta, out["v0"], "-"))
    theta = np.linspace(0.0, 360.0 * revolutions, 20001)
    fx, fy = ideal_joint_force(SliderCrankParams.paper(), np.radians(theta))
    force_curves.append(("ideal joint force (closed form)", theta, np.hypot(fx, fy), "k--"))
    angle_curves.append(("ideal F direction", theta, np.degrees(np.unwrap(np.arctan2(fy, fx))), "k--"))
    path = os.path.join(directory, "diagnostic_contact_history.png")
    return crank_angle_panels([("normal force [N]", force_curves), ("eccentricity direction [°]", angle_curves),
                               ("v0 of the current contact [m/s]", v0_curves)], path, log_panels=(0, 2),
                              marks=dead_points(360.0 * revolutions),
                              title="contact history at every accepted step (restitution sweeps, lowest and highest cr)")


def _frozen_overview(diag: Diagnostics, done: Sequence[tuple[Sweep, SweepRows]], ideal: dict[str, np.ndarray],
                     directory: str, marks: Sequence[float]) -> str:
    """Acceleration deviation at cr 0.3 and 0.9 (no friction), default v_min against the raised one."""
    default = {v.value: r.columns for s, rows in done if s.kind == "cr" and s.friction == "none"
               for v, _, r, _ in rows}
    frozen = {v.value: r.columns for v, _, r, _ in diag.frozen["none"]}
    panels = []
    for value in (f"{CR_SWEEP[0]:g}", f"{CR_SWEEP[-1]:g}"):
        curves = []
        for name, cols in ((f"v_min {exuclear.V_MIN_DEFAULT:g} m/s", default.get(value)),
                           (f"v_min {diag.frozen_v_min:.3f} m/s", frozen.get(value))):
            if cols is not None:
                dev = cols["slider_a"] - np.interp(cols["time"], ideal["time"], ideal["slider_a"])
                curves.append((name, cols["crank_angle"], np.clip(dev, -500.0, 500.0), "-"))
        panels.append((f"a - ideal [m/s²], cr = {value}", curves))
    path = os.path.join(directory, "diagnostic_frozen_v0_slider_a.png")
    return crank_angle_panels(panels, path, marks=marks,
                              title="slider acceleration deviation, no friction: default v0 treatment against v0 "
                                    "floored at the first impact's speed (clipped at ±500 m/s²)")


# -- command line ---------------------------------------------------------------------

def _parser() -> argparse.ArgumentParser:
    ap = argparse.ArgumentParser(prog="python -m validation.slider_crank", description=__doc__.split("\n")[0])
    ap.add_argument("--out", metavar="DIR", default=DEFAULT_OUT,
                    help="directory of the figures, tables and report (default %(default)s)")
    ap.add_argument("--revolutions", type=float, default=SliderCrankParams.paper().revolutions,
                    help=f"crank revolutions per run, at least {MIN_REVOLUTIONS:.4g} (default %(default)s)")
    return ap


def main(argv: list[str] | None = None) -> int:
    """Run the sweeps and diagnostics, write figures, CSV tables and the report; 1 if any run failed."""
    ap = _parser()
    args = ap.parse_args(argv)
    if not args.revolutions >= MIN_REVOLUTIONS:
        ap.error(f"--revolutions must be at least {MIN_REVOLUTIONS:.4g} (the first dead point and its window), "
                 f"got {args.revolutions}")
    start = time.perf_counter()
    os.makedirs(args.out, exist_ok=True)
    runner = Runner()
    print("baseline: ideal mechanism", flush=True)
    ideal_result = runner.result(SliderCrankParams.paper(ideal=True, formulation="redundant",
                                                         revolutions=args.revolutions))
    ideal = ideal_result.columns
    sweeps = paper_sweeps(args.revolutions)
    done, paths = [], []
    for k, sweep in enumerate(sweeps, start=1):
        rows = run_sweep(runner, sweep, ideal, k, len(sweeps))
        paths += write_sweep_files(sweep, rows, ideal, args.out, args.revolutions)
        done.append((sweep, rows))
    lags = {s.stem: sweep_lags(rows, ideal) for s, rows in done if s.kind == "material"}
    diag = run_diagnostics(runner, sweeps, ideal, args.revolutions)
    paths += write_diagnostic_files(runner, done, diag, ideal, args.out, args.revolutions)
    wall = time.perf_counter() - start
    paths.append(write_report(os.path.join(args.out, "slider_crank.md"), args.revolutions, done, diag, lags, ideal,
                              runner, wall))
    for path in paths:
        print(f"wrote {path}")
    print(f"{len(runner.results) + len(runner.histories)} runs, wall time {wall:.1f} s")
    failures = runner.failures()
    for name, message in failures:
        print(f"error: run failed: {name}: {message}", file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
