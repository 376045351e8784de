"""Figures of the scenes: the journal-bearing's impact curves and the slider-crank's
plots against crank angle, its orbit and spectra (matplotlib, imported only on use).

They live with the scenes, not in the library, because each knows a scene's outputs by
name (``slider_x``, ``crank_moment``, ...).  The figures are written to files and never shown: each is a
:class:`matplotlib.figure.Figure` made outside pyplot, which ``savefig`` renders with
matplotlib's Agg canvas, so no backend is chosen or switched and a user's pyplot session
is left alone.
"""
from __future__ import annotations

import os
import textwrap
from collections.abc import Sequence

import numpy as np

from exuclear.spectrum import amplitude_spectrum

#: Titles longer than this many characters are wrapped so that they fit the figure.
_TITLE_WIDTH = 55


def _subplots(nrows: int = 1, ncols: int = 1, *, figsize: tuple[float, float], **kwargs):
    """``(figure, axes)`` as ``pyplot.subplots`` returns them, for a figure outside pyplot."""
    from matplotlib.figure import Figure

    fig = Figure(figsize=figsize)
    return fig, fig.subplots(nrows, ncols, **kwargs)


def impact_curves(results: Sequence[tuple[str, dict[str, np.ndarray]]], directory: str, stem: str,
                  title: str = "") -> list[str]:
    """Force-penetration and rate-penetration curves of impacts (the paper's Figs. 4-7).

    ``results`` holds ``(label, outputs)`` pairs with the joint outputs of
    :meth:`exuclear.ClearanceJointHandle.outputs`.  Penetration in micrometres, force in
    newtons, rate in m/s.  Returns the written file paths.
    """
    os.makedirs(directory, exist_ok=True)
    paths = []
    for key, ylabel, scale, name in (("normal_force", "contact force [N]", 1.0, "force"),
                                     ("penetration_rate", "penetration rate [m/s]", 1.0, "rate")):
        fig, ax = _subplots(figsize=(5.5, 4.0))
        for label, out in results:
            mask = out["penetration"] > 0.0
            ax.plot(out["penetration"][mask] * 1e6, out[key][mask] * scale, label=label)
        ax.set_xlabel("penetration [µm]")
        ax.set_ylabel(ylabel)
        if title:
            ax.set_title(textwrap.fill(title, _TITLE_WIDTH), fontsize=10)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8)
        fig.tight_layout()
        path = os.path.join(directory, f"{stem}_{name}.png")
        fig.savefig(path, dpi=130)
        paths.append(path)
    return paths


#: Slider-crank quantities plotted against crank angle: (column, axis label, scale).
_CRANK_ANGLE_PLOTS = (
    ("slider_x", "slider position [m]", 1.0),
    ("slider_v", "slider velocity [m/s]", 1.0),
    ("slider_a", "slider acceleration [m/s²]", 1.0),
    ("contact_force", "contact force at B [N]", 1.0),
    ("crank_moment", "crank driving moment [N m]", 1.0),
)


def _log_frequency_axis(ax, spectra: Sequence[np.ndarray]) -> None:
    """Frequency on a log axis, from half the lowest drawn (non-zero) frequency.

    The slider-crank's spectrum spans the crank frequency (8.3 Hz at 500 rpm) and the
    impact band near 150-350 Hz: a linear 0-1000 Hz axis squeezes the crank line
    against its left edge.  ``spectra``: the frequency arrays drawn [Hz].
    """
    positive = [float(f[f > 0.0].min()) for f in spectra if np.any(f > 0.0)]
    highest = [float(f.max()) for f in spectra if len(f)]
    ax.set_xscale("log")
    if positive and highest:
        ax.set_xlim(0.5 * min(positive), max(highest))


def slider_crank_figures(cases: Sequence[tuple[str, dict[str, np.ndarray]]], baseline: dict[str, np.ndarray] | None,
                         clearance: float, directory: str, stem: str, title: str = "",
                         spectrum_step: float = 1e-5, max_frequency: float = 1000.0) -> list[str]:
    """The slider-crank plots of the paper's Figs. 10-20.

    Slider position, velocity, acceleration, contact force and crank moment against
    crank angle (degrees), the ideal mechanism ``baseline`` dashed on each; the journal
    centre's orbit inside the clearance circle (micrometres; not drawn without
    ``cases``, as for the ideal mechanism alone); the amplitude spectrum of the slider
    acceleration up to ``max_frequency`` on a log frequency axis.  Returns the written
    paths.
    """
    os.makedirs(directory, exist_ok=True)
    paths = []

    def save(fig, name):
        if title:
            fig.suptitle(textwrap.fill(title, _TITLE_WIDTH), fontsize=10)
        fig.tight_layout()
        path = os.path.join(directory, f"{stem}_{name}.png")
        fig.savefig(path, dpi=130)
        paths.append(path)

    for key, label, scale in _CRANK_ANGLE_PLOTS:
        fig, ax = _subplots(figsize=(7.0, 3.6))
        for name, cols in cases:
            ax.plot(cols["crank_angle"], cols[key] * scale, lw=0.8, label=name)
        if baseline is not None:
            ax.plot(baseline["crank_angle"], baseline[key] * scale, "k--", lw=1.0, label="ideal joint")
        ax.set_xlabel("crank angle [°]")
        ax.set_ylabel(label)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7, ncol=3)
        save(fig, key)

    if cases:  # an ideal joint has no orbit: the figure would hold the circle alone
        fig, ax = _subplots(figsize=(4.8, 4.8))
        circle = np.linspace(0.0, 2.0 * np.pi, 361)
        ax.plot(clearance * 1e6 * np.cos(circle), clearance * 1e6 * np.sin(circle), "k-", lw=1.0,
                label="clearance circle")
        for name, cols in cases:
            ax.plot(cols["ecc_x"] * 1e6, cols["ecc_y"] * 1e6, lw=0.6, label=name)
        ax.set_aspect("equal")
        ax.set_xlabel("journal centre x - bearing centre x [µm]")
        ax.set_ylabel("y [µm]")
        ax.legend(fontsize=7, loc="upper right")
        save(fig, "orbit")

    fig, ax = _subplots(figsize=(7.0, 3.6))
    drawn = []
    for name, cols in cases:
        f, a = amplitude_spectrum(cols["time"], cols["slider_a"], spectrum_step)
        keep = (f > 0.0) & (f <= max_frequency)  # the mean (0 Hz) is removed
        ax.plot(f[keep], a[keep], lw=0.8, label=name)
        drawn.append(f[keep])
    if baseline is not None:
        f, a = amplitude_spectrum(baseline["time"], baseline["slider_a"], spectrum_step)
        keep = (f > 0.0) & (f <= max_frequency)
        ax.plot(f[keep], a[keep], "k--", lw=1.0, label="ideal joint")
        drawn.append(f[keep])
    _log_frequency_axis(ax, drawn)
    ax.set_xlabel("frequency [Hz]")
    ax.set_ylabel("slider acceleration amplitude [m/s²]")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7)
    save(fig, "spectrum")
    return paths


#: Sweep figures: quantities drawn as one panel per case, (column, axis label).
_STACKED_PLOTS = (
    ("slider_a", "slider acceleration [m/s²]"),
    ("contact_force", "contact force at B [N]"),
    ("crank_moment", "crank moment [N m]"),
)
#: Sweep figures: quantities overlaid, with their deviation from the baseline below,
#: (column, axis label, deviation label, deviation scale).
_OVERLAY_PLOTS = (
    ("slider_x", "slider position [m]", "position − ideal [µm]", 1e6),
    ("slider_v", "slider velocity [m/s]", "velocity − ideal [m/s]", 1.0),
)
#: Height of one case panel in the stacked sweep figures [inch].
_PANEL_HEIGHT = 1.45
#: Spectra are drawn on a log scale down to this fraction of their largest amplitude
#: (the ideal mechanism's round-off floor, ~1e-11 of its peak, would flatten the rest).
_SPECTRUM_RANGE = 1e-5


def _mark_angles(ax, angles: Sequence[float]) -> None:
    for angle in angles:
        ax.axvline(angle, color="0.55", lw=0.6, ls=":")


def _zoom_limits(cases, baseline, key: str, after: float) -> tuple[float, float] | None:
    """y-limits that show every curve beyond crank angle ``after`` (10 % margin)."""
    parts = [cols[key][cols["crank_angle"] >= after] for _, cols in cases]
    if baseline is not None:
        parts.append(baseline[key])
    values = np.concatenate(parts)
    if values.size == 0:
        return None
    low, high = float(values.min()), float(values.max())
    margin = 0.1 * max(high - low, 1e-12)
    return low - margin, high + margin


def _on_baseline(cols: dict[str, np.ndarray], baseline: dict[str, np.ndarray], key: str) -> np.ndarray:
    """``cols[key]`` minus the baseline interpolated at the case's times."""
    return cols[key] - np.interp(cols["time"], baseline["time"], baseline[key])


def _stacked_figure(cases, baseline, key: str, label: str, dead_points: Sequence[float],
                    zoom_after: float | None):
    n = len(cases)
    fig, axes = _subplots(n, 1, figsize=(7.5, _PANEL_HEIGHT * n + 0.9), sharex=True, sharey=True, squeeze=False)
    limits = _zoom_limits(cases, baseline, key, zoom_after) if zoom_after is not None else None
    for k, (ax, (name, cols)) in enumerate(zip(axes[:, 0], cases, strict=True)):
        ax.plot(cols["crank_angle"], cols[key], lw=0.6, color=f"C{k}", label=name)
        if baseline is not None:
            ax.plot(baseline["crank_angle"], baseline[key], "k--", lw=0.8, label="ideal joint")
        _mark_angles(ax, dead_points)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7, loc="upper right", ncol=2)
        if limits is not None:
            peak = float(np.abs(cols[key]).max())
            if peak > max(abs(limits[0]), abs(limits[1])):
                ax.text(0.01, 0.93, f"off scale before {zoom_after:g}°: |peak| {peak:.3g}", transform=ax.transAxes,
                        fontsize=7, color="0.2", va="top", bbox={"facecolor": "white", "edgecolor": "none", "alpha": 0.8})
    if limits is not None:
        axes[0, 0].set_ylim(*limits)
    axes[-1, 0].set_xlabel("crank angle [°]")
    fig.supylabel(label, fontsize=10)
    return fig


def _overlay_figure(cases, baseline, key: str, label: str, dev_label: str, dev_scale: float,
                    dead_points: Sequence[float]):
    fig, (top, bottom) = _subplots(2, 1, figsize=(7.5, 5.2), sharex=True, gridspec_kw={"height_ratios": [2, 1.3]})
    for k, (name, cols) in enumerate(cases):
        top.plot(cols["crank_angle"], cols[key], lw=0.8, color=f"C{k}", label=name)
        if baseline is not None:
            bottom.plot(cols["crank_angle"], _on_baseline(cols, baseline, key) * dev_scale, lw=0.6, color=f"C{k}")
    if baseline is not None:
        top.plot(baseline["crank_angle"], baseline[key], "k--", lw=1.0, label="ideal joint")
    for ax in (top, bottom):
        _mark_angles(ax, dead_points)
        ax.grid(True, alpha=0.3)
    top.set_ylabel(label)
    top.legend(fontsize=7, ncol=3)
    bottom.set_ylabel(dev_label)
    bottom.set_xlabel("crank angle [°]")
    return fig


def _orbit_figure(cases, clearance: float):
    n = len(cases)
    fig, axes = _subplots(1, n, figsize=(2.9 * n, 3.4), sharex=True, sharey=True, squeeze=False)
    circle = np.linspace(0.0, 2.0 * np.pi, 361)
    c_um = clearance * 1e6
    for k, (ax, (name, cols)) in enumerate(zip(axes[0], cases, strict=True)):
        ax.plot(c_um * np.cos(circle), c_um * np.sin(circle), color="0.6", ls="--", lw=0.8)
        ax.plot(cols["ecc_x"] * 1e6, cols["ecc_y"] * 1e6, lw=0.6, color=f"C{k}")
        ax.set_aspect("equal")
        ax.set_title(name, fontsize=8)
        ax.set_xlabel("e_x [µm]")
    axes[0, 0].set_ylabel("e_y [µm]")
    return fig


def _spectrum_figure(spectra, baseline_spectrum, band: tuple[float, float] | None, ylabel: str, log: bool):
    n = len(spectra)
    fig, axes = _subplots(n, 1, figsize=(7.5, _PANEL_HEIGHT * n + 0.9), sharex=True, sharey=True, squeeze=False)
    top = max(float(a.max()) for _, _, a in spectra)
    for k, (ax, (name, f, a)) in enumerate(zip(axes[:, 0], spectra, strict=True)):
        ax.plot(f, a, lw=0.7, color=f"C{k}", label=name)
        if baseline_spectrum is not None:
            ax.plot(*baseline_spectrum, "k--", lw=0.8, label="ideal joint")
        if band is not None:
            ax.axvspan(*band, color="0.85", zorder=0)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7, loc="upper right", ncol=2)
    if log:
        axes[0, 0].set_yscale("log")
        axes[0, 0].set_ylim(top * _SPECTRUM_RANGE, top * 2.0)
    _log_frequency_axis(axes[0, 0], [f for _, f, _ in spectra])  # shared by every panel
    axes[-1, 0].set_xlabel("frequency [Hz]")
    fig.supylabel(ylabel, fontsize=10)
    return fig


def slider_crank_sweep_figures(cases: Sequence[tuple[str, dict[str, np.ndarray]]], baseline: dict[str, np.ndarray] | None,
                               clearance: float, directory: str, stem: str, *, title: str = "",
                               dead_points: Sequence[float] = (), zoom_after: float | None = None,
                               band: tuple[float, float] | None = None, spectrum_step: float = 1e-5,
                               max_frequency: float = 1000.0, deviation_after: float | None = None,
                               quantities: Sequence[str] | None = None) -> list[str]:
    """The slider-crank plots of the paper's Figs. 10-20 for a sweep of several cases.

    Readable with four or more cases: slider position and velocity are overlaid, with
    their deviations from the ideal ``baseline`` in a panel below; acceleration,
    contact force, crank moment and the acceleration spectrum get one panel per case
    (shared axes, the baseline dashed in each); the journal orbits sit side by side.

    Parameters
    ----------
    cases : sequence of (str, dict)
        ``(label, columns)`` with the columns of :data:`exuclear.models.slider_crank.COLUMNS`
        (angles in degrees, SI units).
    baseline : dict or None
        Columns of the ideal mechanism.
    clearance : float
        Radial clearance [m], drawn as the circle of the orbit plots.
    directory, stem : str
        Files are ``directory/stem_<quantity>.png``.
    title : str
        Figure title.
    dead_points : sequence of float
        Crank angles [deg] marked by dotted lines.
    zoom_after : float, optional
        Fit the y-range of the per-case panels to the curves beyond this crank angle
        [deg] (start-up impacts would otherwise flatten the rest); off-scale peaks are
        written in the panel.
    band : (float, float), optional
        Frequency band [Hz] shaded in the spectra.
    spectrum_step, max_frequency : float
        Resampling step [s] and upper plotted frequency [Hz] of the spectra.
    deviation_after : float, optional
        If given, also plot the Hann-windowed spectrum of the acceleration deviation
        from the baseline beyond this crank angle [deg] (``stem_deviation_spectrum.png``).
    quantities : sequence of str, optional
        Draw only these figures (names as in the file names: ``slider_x``, ``slider_v``,
        ``slider_a``, ``contact_force``, ``crank_moment``, ``orbit``, ``spectrum``,
        ``deviation_spectrum``); default all.

    Returns
    -------
    list of str
        The written paths.
    """
    os.makedirs(directory, exist_ok=True)
    paths = []

    def save(fig, name):
        if title:
            fig.suptitle(textwrap.fill(title, 2 * _TITLE_WIDTH), fontsize=10)
        fig.tight_layout()
        path = os.path.join(directory, f"{stem}_{name}.png")
        fig.savefig(path, dpi=130)
        paths.append(path)

    def wanted(name):
        return quantities is None or name in quantities

    for key, label, dev_label, dev_scale in _OVERLAY_PLOTS:
        if wanted(key):
            save(_overlay_figure(cases, baseline, key, label, dev_label, dev_scale, dead_points), key)
    for key, label in _STACKED_PLOTS:
        if wanted(key):
            save(_stacked_figure(cases, baseline, key, label, dead_points, zoom_after), key)
    if wanted("orbit"):
        save(_orbit_figure(cases, clearance), "orbit")

    def clipped(f, a):
        keep = (f > 0.0) & (f <= max_frequency)
        return f[keep], a[keep]

    if wanted("spectrum"):
        spectra = [(name, *clipped(*amplitude_spectrum(cols["time"], cols["slider_a"], spectrum_step)))
                   for name, cols in cases]
        ideal = None if baseline is None else clipped(*amplitude_spectrum(baseline["time"], baseline["slider_a"],
                                                                        spectrum_step))
        save(_spectrum_figure(spectra, ideal, band, "slider acceleration amplitude [m/s²]", log=True), "spectrum")
    if deviation_after is not None and baseline is not None and wanted("deviation_spectrum"):
        spectra = []
        for name, cols in cases:
            keep = cols["crank_angle"] >= deviation_after
            spectra.append((name, *clipped(*amplitude_spectrum(cols["time"][keep], _on_baseline(cols, baseline, "slider_a")[keep],
                                                               spectrum_step, window="hann"))))
        save(_spectrum_figure(spectra, None, band, f"amplitude of (acceleration − ideal) after {deviation_after:g}° "
                              "[m/s²]", log=False), "deviation_spectrum")
    return paths


def crank_angle_panels(panels: Sequence[tuple[str, Sequence[tuple[str, np.ndarray, np.ndarray, str]]]], path: str, *,
                       xlabel: str = "crank angle [°]", title: str = "", marks: Sequence[float] = (),
                       log_panels: Sequence[int] = ()) -> str:
    """Stacked panels of curves sharing the x-axis (diagnostic plots).

    Parameters
    ----------
    panels : sequence of (str, sequence of (str, array, array, str))
        Per panel its y-axis label and curves ``(label, x, y, matplotlib format)``.
    path : str
        Output file (PNG).
    xlabel, title : str
        x-axis label and figure title.
    marks : sequence of float
        x positions marked by dotted lines (e.g. the dead points).
    log_panels : sequence of int
        Indices of the panels drawn with a logarithmic y-axis.

    Returns
    -------
    str
        ``path``.
    """
    os.makedirs(os.path.dirname(path) or ".", exist_ok=True)
    fig, axes = _subplots(len(panels), 1, figsize=(7.5, 2.1 * len(panels) + 0.8), sharex=True, squeeze=False)
    for k, (ax, (ylabel, curves)) in enumerate(zip(axes[:, 0], panels, strict=True)):
        for label, x, y, fmt in curves:
            ax.plot(x, y, fmt, lw=0.7, label=label)
        if k in log_panels:
            ax.set_yscale("log")
        _mark_angles(ax, marks)
        ax.set_ylabel(ylabel, fontsize=9)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7, loc="upper right", ncol=3)
    axes[-1, 0].set_xlabel(xlabel)
    if title:
        fig.suptitle(textwrap.fill(title, 2 * _TITLE_WIDTH), fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=130)
    return path
