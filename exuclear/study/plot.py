"""Plots of study tables (opt-in: imports matplotlib; the library itself never does).

No backend is chosen or switched here: a figure only saved to a file is a
:class:`matplotlib.figure.Figure` outside pyplot (rendered by ``savefig`` with the Agg
canvas); a figure returned to draw on further is made by pyplot, in the caller's backend.

:func:`plot_metric` draws a metric of a :func:`exuclear.study.run_study` table over one
parameter (lines, or points for a bifurcation-style diagram; one set per value of
``by``) or over two (a heat map).  Failed runs are left out and counted in the title.
Axes are labelled with what a column holds and its unit, from the study's
:class:`~exuclear.columns.Column` table (a scene's ``STUDY_COLUMNS``), and with the bare
column name where it has none.
"""
from __future__ import annotations

import os
from collections.abc import Mapping
from typing import Any

import numpy as np


def _select(table, metric: str, names: list[str], where: Mapping[str, Any]):
    """The successful rows matching ``where``; ``ValueError`` for unknown columns or
    parameters that vary but are neither plotted nor fixed."""
    for name in [metric, *names, *where]:
        if name not in table.columns:
            raise ValueError(f"the table has no column {name!r}; columns: {', '.join(map(str, table.columns))}")
    rows = table
    for name, value in where.items():
        rows = rows[rows[name] == value]
        if rows.empty:
            raise ValueError(f"no row has {name} = {value!r}")
    failed = int((~rows["success"].astype(bool)).sum())
    rows = rows[rows["success"].astype(bool)]
    return rows, failed


def axis_label(name: str, columns: Mapping[str, Any] | None = None) -> str:
    """``"label [unit]"`` of column ``name`` from ``columns`` (name ->
    :class:`~exuclear.columns.Column`) or the status columns' table; else ``name`` itself."""
    from .table import STATUS_LABELS

    column = (columns or {}).get(name) or STATUS_LABELS.get(name)
    return column.axis_label if column is not None else name


def plot_metric(table, metric: str, x: str, *, y: str | None = None, by: str | None = None,
                where: Mapping[str, Any] | None = None, points: bool = False, logx: bool = False,
                logy: bool = False, ax: Any = None, path: str | os.PathLike | None = None, title: str | None = None,
                columns: Mapping[str, Any] | None = None):
    """Plot ``metric`` over parameter ``x``.

    Parameters
    ----------
    table : DataFrame
        A study table (:func:`exuclear.study.run_study`, :func:`exuclear.study.load_table`).
    metric, x : str
        Column names.
    y : str, optional
        Second parameter: a heat map of ``metric`` over ``(x, y)`` (mean where several
        rows share a cell).
    by : str, optional
        One line (or point set) per value of this parameter.
    where : mapping, optional
        Keep only the rows with these parameter values.
    points : bool
        Markers only, no lines (bifurcation-style: several values of the metric at one x,
        as from a metric that is an array per run).
    ax : matplotlib Axes, optional
        Draw into it; otherwise a new figure (outside pyplot when ``path`` is given, else
        a pyplot figure in the caller's backend).
    path : path, optional
        Save the figure there and close it (if pyplot holds it); returns the path.
        Without it, returns the Axes.
    columns : mapping, optional
        What the columns hold, name -> :class:`~exuclear.columns.Column` (the study's
        ``Study.columns``, e.g. ``scene("slider-crank").columns``): the axis labels with
        units (:func:`axis_label`).
    """
    if y is not None and by is not None:
        raise ValueError("give `y` (a heat map) or `by` (one line per value), not both")
    names = [n for n in (x, y, by) if n is not None]
    rows, failed = _select(table, metric, names, where or {})
    if len(rows) and isinstance(rows[metric].iloc[0], list):  # an array per run: one point per element
        rows = rows.explode(metric).astype({metric: float})
    if rows.empty:
        raise ValueError(f"no successful run to plot ({failed} failed)")
    if ax is None:
        ax = _new_axes(figsize=(7.0, 4.5), for_pyplot=path is None)
    if y is not None:
        cells = rows.pivot_table(index=y, columns=x, values=metric, aggfunc="mean")
        xs, ys = cells.columns.to_numpy(float), cells.index.to_numpy(float)
        mesh = ax.pcolormesh(_edges(xs, logx), _edges(ys, logy), cells.to_numpy(float), shading="flat")
        ax.figure.colorbar(mesh, ax=ax, label=axis_label(metric, columns))
        ax.set_ylabel(axis_label(y, columns))
    else:
        groups = [(None, rows)] if by is None else list(rows.groupby(by, sort=True))
        for value, group in groups:
            group = group.sort_values(x)
            label = None if by is None else f"{value}"
            style = dict(linestyle="none", marker=".", markersize=4) if points else dict(marker="o", markersize=3)
            ax.plot(group[x].to_numpy(float), group[metric].to_numpy(float), label=label, **style)
        if by is not None:
            ax.legend(title=axis_label(by, columns))
        ax.set_ylabel(axis_label(metric, columns))
        if logy:
            ax.set_yscale("log")
    if logx:
        ax.set_xscale("log")
    ax.set_xlabel(axis_label(x, columns))
    fixed = ", ".join(f"{k} = {v}" for k, v in (where or {}).items())
    note = f"{failed} failed run(s) left out" if failed else ""
    what = f"{metric} over {x}" + (f" and {y}" if y else "")
    ax.set_title(title if title is not None else "; ".join(s for s in (what, fixed, note) if s))
    ax.grid(True, alpha=0.3)
    return _finish(ax, path)


def _finish(ax: Any, path: str | os.PathLike | None) -> Any:
    """``ax`` where no ``path`` is given; else its figure saved there and closed, and ``path``."""
    if path is None:
        return ax
    ax.figure.tight_layout()
    ax.figure.savefig(path, dpi=150)
    _close(ax.figure)
    return path


def _new_axes(figsize: tuple[float, float], for_pyplot: bool):
    """Axes of a new figure: a pyplot one to be shown or drawn on further, or one outside
    pyplot (no backend chosen) to be saved only."""
    if for_pyplot:
        import matplotlib.pyplot as plt

        return plt.subplots(figsize=figsize)[1]
    from matplotlib.figure import Figure

    return Figure(figsize=figsize).subplots()


def _close(figure) -> None:
    """Close ``figure`` if pyplot holds it (a figure outside pyplot needs no closing)."""
    import sys

    plt = sys.modules.get("matplotlib.pyplot")  # not imported: it holds no figure
    if plt is not None:
        plt.close(figure)  # a no-op for a figure outside pyplot


def _edges(centres: np.ndarray, log: bool) -> np.ndarray:
    """Cell edges around sorted cell centres (midpoints; in log space for a log axis)."""
    c = np.log(centres) if log else centres
    if len(c) == 1:
        half = 0.5 * (abs(c[0]) if c[0] != 0.0 else 1.0)
        e = np.array([c[0] - half, c[0] + half])
    else:
        mid = 0.5 * (c[1:] + c[:-1])
        e = np.concatenate([[2 * c[0] - mid[0]], mid, [2 * c[-1] - mid[-1]]])
    return np.exp(e) if log else e


__all__ = ["plot_metric", "axis_label"]
