"""Measures of the slider-crank runs against the ideal mechanism: the ideal joint force
in closed form, the metrics of one run, and the contact history at every accepted step."""
from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, fields, replace

import numpy as np

from exuclear.models.slider_crank import SliderCrankParams, SliderCrankResult, ideal_joint_force
from exuclear.spectrum import amplitude_spectrum
from validation.slider_crank.cases import (
    BAND,
    DEAD_WINDOW,
    LAG_WINDOW,
    MODE_SEARCH,
    ROD_TURNING,
    SETTLE_TIME,
    SPECTRUM_STEP,
    STARTUP,
    STICTION_SPEED,
    History,
)

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
    f, a = amplitude_spectrum(t, cols["slider_a"], SPECTRUM_STEP)
    a_ideal = cols["slider_a"] - da
    _, a_late = amplitude_spectrum(t, np.where(late, cols["slider_a"], a_ideal), SPECTRUM_STEP)
    _, a_startup = amplitude_spectrum(t, np.where(late, a_ideal, cols["slider_a"]), SPECTRUM_STEP)
    fi, ai = amplitude_spectrum(ideal["time"], ideal["slider_a"], SPECTRUM_STEP)
    fd, ad = amplitude_spectrum(t[late], da[late], SPECTRUM_STEP, window="hann")
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
