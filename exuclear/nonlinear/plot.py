"""Figures of the nonlinear tools (opt-in: imports matplotlib; ``import exuclear`` and
:mod:`exuclear.nonlinear` never do).

:func:`phase_portrait` (the journal centre in its clearance circle, ``e_x / c`` against
``e_y / c``), :func:`poincare_map`, :func:`bifurcation` (an orbit diagram's samples over
its parameter) and :func:`exponent_plot` (the largest Lyapunov exponent over it).  Each
draws into ``ax`` if given, else into a new figure: saved to ``path`` and closed (a
figure outside pyplot), or returned as Axes in the caller's backend.
"""
from __future__ import annotations

import os
from typing import Any

import numpy as np

from ..study.plot import _finish, _new_axes

#: Marker colour of each verdict in a bifurcation diagram (:func:`~exuclear.nonlinear.classify`).
KIND_COLOURS = {"period": "tab:blue", "quasi-periodic": "tab:green", "chaotic": "tab:red", "aperiodic": "tab:grey"}


def phase_portrait(ex: object, ey: object, *, sections: tuple[object, object] | None = None, ax: Any = None,
                   path: str | os.PathLike | None = None, title: str = "journal centre in the clearance circle"):
    """The journal centre's path in its clearance circle: ``ex``, ``ey`` are ``e_x / c`` and
    ``e_y / c`` over time (a joint's outputs over its clearance); the unit circle is the
    bearing wall.  ``sections``: the Poincare points ``(ex_k, ey_k)``, drawn on top."""
    if ax is None:
        ax = _new_axes(figsize=(5.0, 5.0), for_pyplot=path is None)
    angle = np.linspace(0.0, 2.0 * np.pi, 361)
    ax.plot(np.cos(angle), np.sin(angle), color="k", linewidth=1.0, label="wall |e| = c")
    ax.plot(np.asarray(ex, dtype=float), np.asarray(ey, dtype=float), linewidth=0.6, color="tab:blue", label="path")
    if sections is not None:
        ax.plot(*(np.asarray(s, dtype=float) for s in sections), linestyle="none", marker="o", markersize=3,
                color="tab:red", label="once per period")
    ax.set_aspect("equal")
    ax.set_xlabel("e_x / c")
    ax.set_ylabel("e_y / c")
    ax.set_title(title)
    ax.legend(loc="upper right", fontsize="small")
    return _finish(ax, path)


def poincare_map(x: object, y: object, *, xlabel: str = "x", ylabel: str = "y", ax: Any = None,
                 path: str | os.PathLike | None = None, title: str = "Poincare map"):
    """The section's points ``(x_k, y_k)``: a period-N response shows N points, a
    quasi-periodic one a closed curve, a chaotic one a fractal cloud."""
    if ax is None:
        ax = _new_axes(figsize=(5.0, 4.5), for_pyplot=path is None)
    ax.plot(np.asarray(x, dtype=float), np.asarray(y, dtype=float), linestyle="none", marker=".", markersize=3)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(title)
    ax.grid(True, alpha=0.3)
    return _finish(ax, path)


def _kind_colour(kind: str) -> str:
    return KIND_COLOURS["period"] if kind.startswith("period") else KIND_COLOURS.get(kind, "k")


def bifurcation(table: Any, parameter: str, observable: str, *, ax: Any = None, path: str | os.PathLike | None = None,
                title: str | None = None):
    """An orbit diagram (:func:`~exuclear.nonlinear.orbit_diagram`): every sample of
    ``observable`` at its parameter value, coloured by the value's verdict; a sweep's
    down-run is drawn with open markers beside the up-run's dots."""
    for name in (parameter, observable):
        if name not in table.columns:
            raise ValueError(f"the table has no column {name!r}; columns: {', '.join(map(str, table.columns))}")
    rows = table[table["success"].astype(bool)]
    if rows.empty:
        raise ValueError("no successful run to plot")
    if ax is None:
        ax = _new_axes(figsize=(7.0, 4.5), for_pyplot=path is None)
    seen = set()
    for _, row in rows.iterrows():
        samples = np.asarray(row[observable], dtype=float)
        kind = str(row.get("kind", "") or "")
        label = kind.split("-")[0] if kind.startswith("period") else kind
        down = row.get("direction", "up") == "down"
        ax.plot(np.full(samples.size, float(row[parameter])), samples, linestyle="none", marker="o" if down else ".",
                markersize=4 if down else 2, color=_kind_colour(kind), markerfacecolor="none" if down else None,
                label=None if label in seen else (label or None))
        seen.add(label)
    ax.set_xlabel(parameter)
    ax.set_ylabel(observable)
    ax.set_title(title if title is not None else f"orbit diagram: {observable} once per period")
    ax.legend(fontsize="small")
    ax.grid(True, alpha=0.3)
    return _finish(ax, path)


def exponent_plot(table: Any, parameter: str, *, ax: Any = None, path: str | os.PathLike | None = None,
                  title: str = "largest Lyapunov exponent"):
    """The largest Lyapunov exponent [1/s] of each value of an orbit diagram run with
    ``exponent=True``; zero drawn: above it chaos."""
    if "exponent" not in table.columns or not np.isfinite(table["exponent"].astype(float)).any():
        raise ValueError("the table has no exponents: run the orbit diagram with exponent=True")
    rows = table[table["success"].astype(bool)].sort_values(parameter)
    if ax is None:
        ax = _new_axes(figsize=(7.0, 3.5), for_pyplot=path is None)
    ax.axhline(0.0, color="k", linewidth=0.8)
    ax.plot(rows[parameter].to_numpy(float), rows["exponent"].to_numpy(float), marker="o", markersize=3)
    ax.set_xlabel(parameter)
    ax.set_ylabel("largest exponent [1/s]")
    ax.set_title(title)
    ax.grid(True, alpha=0.3)
    return _finish(ax, path)


__all__ = ["phase_portrait", "poincare_map", "bifurcation", "exponent_plot", "KIND_COLOURS"]
