"""Opt-in plotting helpers (matplotlib is imported here only, and only on use)."""
from __future__ import annotations

import os
import textwrap
from collections.abc import Sequence

import numpy as np

#: Titles longer than this many characters are wrapped so that they fit the figure.
_TITLE_WIDTH = 55


def _pyplot():
    import matplotlib

    matplotlib.use("Agg")  # files only; there may be no display
    import matplotlib.pyplot as plt

    return plt


def impact_curves(results: Sequence[tuple[str, dict[str, np.ndarray]]], directory: str, stem: str,
                  title: str = "") -> list[str]:
    """Force-penetration and rate-penetration curves of impacts (the paper's Figs. 4-7).

    ``results`` holds ``(label, outputs)`` pairs with the joint outputs of
    :meth:`exuclear.ClearanceJointHandle.outputs`.  Penetration in micrometres, force in
    newtons, rate in m/s.  Returns the written file paths.
    """
    plt = _pyplot()
    os.makedirs(directory, exist_ok=True)
    paths = []
    for key, ylabel, scale, name in (("normal_force", "contact force [N]", 1.0, "force"),
                                     ("penetration_rate", "penetration rate [m/s]", 1.0, "rate")):
        fig, ax = plt.subplots(figsize=(5.5, 4.0))
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
        plt.close(fig)
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


def uniform_spectrum(t: np.ndarray, y: np.ndarray, dt: float) -> tuple[np.ndarray, np.ndarray]:
    """One-sided amplitude spectrum of ``y(t)`` resampled on a uniform grid of step ``dt``.

    Returns frequencies [Hz] and amplitudes (units of ``y``); the mean is removed.
    """
    grid = np.arange(t[0], t[-1], dt)
    samples = np.interp(grid, t, y)
    samples = samples - samples.mean()
    amplitude = 2.0 * np.abs(np.fft.rfft(samples)) / len(samples)
    return np.fft.rfftfreq(len(samples), dt), amplitude


def slider_crank_figures(cases: Sequence[tuple[str, dict[str, np.ndarray]]], baseline: dict[str, np.ndarray] | None,
                         clearance: float, directory: str, stem: str, title: str = "",
                         spectrum_step: float = 1e-5, max_frequency: float = 1000.0) -> list[str]:
    """The slider-crank plots of the paper's Figs. 10-20.

    Slider position, velocity, acceleration, contact force and crank moment against
    crank angle (degrees), the ideal mechanism ``baseline`` dashed on each; the journal
    centre's orbit inside the clearance circle (micrometres); the amplitude spectrum of
    the slider acceleration up to ``max_frequency``.  Returns the written paths.
    """
    plt = _pyplot()
    os.makedirs(directory, exist_ok=True)
    paths = []

    def save(fig, name):
        if title:
            fig.suptitle(textwrap.fill(title, _TITLE_WIDTH), fontsize=10)
        fig.tight_layout()
        path = os.path.join(directory, f"{stem}_{name}.png")
        fig.savefig(path, dpi=130)
        plt.close(fig)
        paths.append(path)

    for key, label, scale in _CRANK_ANGLE_PLOTS:
        fig, ax = plt.subplots(figsize=(7.0, 3.6))
        for name, cols in cases:
            ax.plot(cols["crank_angle"], cols[key] * scale, lw=0.8, label=name)
        if baseline is not None:
            ax.plot(baseline["crank_angle"], baseline[key] * scale, "k--", lw=1.0, label="ideal joint")
        ax.set_xlabel("crank angle [°]")
        ax.set_ylabel(label)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7, ncol=3)
        save(fig, key)

    fig, ax = plt.subplots(figsize=(4.8, 4.8))
    circle = np.linspace(0.0, 2.0 * np.pi, 361)
    ax.plot(clearance * 1e6 * np.cos(circle), clearance * 1e6 * np.sin(circle), "k-", lw=1.0, label="clearance circle")
    for name, cols in cases:
        ax.plot(cols["ecc_x"] * 1e6, cols["ecc_y"] * 1e6, lw=0.6, label=name)
    ax.set_aspect("equal")
    ax.set_xlabel("journal centre x - bearing centre x [µm]")
    ax.set_ylabel("y [µm]")
    ax.legend(fontsize=7, loc="upper right")
    save(fig, "orbit")

    fig, ax = plt.subplots(figsize=(7.0, 3.6))
    for name, cols in cases:
        f, a = uniform_spectrum(cols["time"], cols["slider_a"], spectrum_step)
        keep = f <= max_frequency
        ax.plot(f[keep], a[keep], lw=0.8, label=name)
    if baseline is not None:
        f, a = uniform_spectrum(baseline["time"], baseline["slider_a"], spectrum_step)
        keep = f <= max_frequency
        ax.plot(f[keep], a[keep], "k--", lw=1.0, label="ideal joint")
    ax.set_xlabel("frequency [Hz]")
    ax.set_ylabel("slider acceleration amplitude [m/s²]")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7)
    save(fig, "spectrum")
    return paths
