"""Figures of the hard cases (matplotlib, imported when drawn)."""
from __future__ import annotations

import os

import numpy as np

import exuclear


def plot_resting(data: dict[str, object], directory: str) -> str:
    """Penetration against time of the resting journal at every floor (and the dropped
    journal at the default floor), with the analytic static penetration as a line."""
    import matplotlib

    matplotlib.use("Agg")  # files only
    import matplotlib.pyplot as plt

    resting = data["resting"]
    fig, axes = plt.subplots(2, 1, figsize=(7.0, 6.5))
    ax = axes[0]
    for v_min, run in resting:
        ax.plot(run.out["time"] * 1e3, run.out["penetration"] * 1e9, lw=0.9, label=f"v_min = {v_min:g} m/s")
    d_s = resting[0][1].delta_s
    ax.axhline(d_s * 1e9, color="k", ls="--", lw=1.0, label=f"static penetration (analytic) {d_s * 1e9:.2f} nm")
    ax.set_xlabel("time [ms]")
    ax.set_ylabel("penetration [nm]")
    ax.set_title("journal set down on its bearing under gravity (Wang-Liu, cr 0.9)", fontsize=10)
    ax.set_xlim(0, 8)
    ax.legend(fontsize=8)
    ax.grid(True, alpha=0.3)
    ax = axes[1]
    dropped = data.get("dropped")
    if dropped is not None:
        ax.plot(dropped.out["time"] * 1e3, dropped.out["penetration"] * 1e9, lw=0.7, label="dropped from the centre")
        ax.axhline(dropped.delta_s * 1e9, color="k", ls="--", lw=1.0, label="static penetration (analytic)")
        ax.set_ylim(-5 * dropped.delta_s * 1e9, 50 * dropped.delta_s * 1e9)
        ax.set_title(f"journal dropped from the bearing centre (v_min = {exuclear.contact.V_MIN_DEFAULT:g} m/s); free flight "
                     "below the axis", fontsize=10)
        ax.legend(fontsize=8)
    ax.set_xlabel("time [ms]")
    ax.set_ylabel("penetration [nm]")
    ax.grid(True, alpha=0.3)
    fig.tight_layout()
    path = os.path.join(directory, "resting_journal.png")
    fig.savefig(path, dpi=130)
    plt.close(fig)
    return path


def plot_stick_slip(data: dict[str, object], directory: str) -> str:
    """Slip velocity and |F_T| / F_N against crank angle, with the law's v_s and v_d."""
    import matplotlib

    matplotlib.use("Agg")  # files only
    import matplotlib.pyplot as plt

    params, out, law = data["stick_slip"]
    contact = out["in_contact"] > 0.0
    angle = np.degrees(out["time"] * params.crank_speed)
    v = np.where(contact, out["slip_velocity"], np.nan)
    fig, axes = plt.subplots(2, 1, figsize=(7.5, 6.0), sharex=True)
    ax = axes[0]
    ax.plot(angle, v, lw=0.7, label="slip velocity v_T (in contact)")
    for level, style, name in ((law.v_s, ":", "v_s"), (law.v_d, "--", "v_d")):
        ax.axhline(level, color="k", ls=style, lw=0.8, label=f"±{name} = {level:g} m/s")
        ax.axhline(-level, color="k", ls=style, lw=0.8)
    ax.set_yscale("symlog", linthresh=law.v_s / 10)
    ax.set_ylabel("v_T [m/s]")
    ax.set_title("stick-slip at the clearance joint B (modified Coulomb law, mu_s 0.3, mu_d 0.25)", fontsize=10)
    ax.legend(fontsize=8, loc="upper right")
    ax.grid(True, alpha=0.3)
    ax = axes[1]
    f_n = out["normal_force"]
    mu = np.divide(out["tangential_force"], f_n, out=np.full_like(f_n, np.nan), where=contact & (f_n > 0.0))
    ax.plot(angle, mu, lw=0.7)
    for level in (law.mu_s, law.mu_d):
        ax.axhline(level, color="k", ls=":", lw=0.8)
        ax.axhline(-level, color="k", ls=":", lw=0.8)
    ax.set_ylabel("F_T / F_N")
    ax.set_xlabel("crank angle [deg]")
    # the rod turns back relative to the slider where the crank is at 90 and 270 degrees
    for turn in np.arange(90.0, angle[-1], 180.0):
        for a in axes:
            a.axvline(turn, color="0.6", lw=0.8, ls="-.")
    ax.grid(True, alpha=0.3)
    fig.tight_layout()
    path = os.path.join(directory, "stick_slip.png")
    fig.savefig(path, dpi=130)
    plt.close(fig)
    return path
