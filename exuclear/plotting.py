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
