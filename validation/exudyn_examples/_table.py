"""The zoo's table and report: every model's row (:func:`._runs.run_model`), the
printed table, ``zoo.csv`` and ``report.md`` (the template ``_report.md`` filled in).
"""
from __future__ import annotations

import time
from pathlib import Path
from typing import Any

import exudyn as exu

import exuclear

from ._common import DEFAULT_GROUP, IMPORT_ERRORS, REGISTRY, group_import_errors, group_names, load_models
from ._runs import CONVERGED_PENETRATION, PENETRATION_WRONG, QUICK_TIME_LIMIT, REFERENCE_FACTOR, TIME_LIMIT, run_model

#: Columns of the printed table (all columns go to zoo.csv).
TABLE_COLUMNS = ["model", "ideal_wall", "ideal_steps", "own_reached", "own_time", "own_wall", "own_steps", "own_impacts",
                 "own_pen_c", "own_force", "probe_diff", "own_ratio", "sim_reached", "sim_wall", "sim_steps", "sim_impacts",
                 "sim_pen_c", "sim_ratio", "verdict", "sim_verdict", "own_convergence", "convergence", "own_newton"]


def run_zoo(names: list[str] | None = None, quick: bool = False, convergence: bool = True,
            end_time: float | None = None, out: Path | None = None, progress: bool = True,
            group: str = DEFAULT_GROUP) -> Any:
    """Run the models (``names``; none given: every model of ``group``, by default the zoo's
    table); returns the table (pandas DataFrame) and writes ``zoo.csv`` and ``report.md``
    into ``out`` if given."""
    import pandas as pd

    names_given = bool(names)
    errors: dict = {}  # a group's models that failed to import and are not among its names
    if names_given:
        load_models(None)
    else:
        names = group_names(group)
        errors = group_import_errors(group)
    unknown = [n for n in names if n not in REGISTRY and n not in IMPORT_ERRORS]
    if unknown:
        raise ValueError(f"unknown zoo model(s) {unknown}; registered: {sorted(REGISTRY)}")
    rows = []
    for name in names:
        if name in IMPORT_ERRORS:
            rows.append({"model": name, "verdict": "import error", "error": IMPORT_ERRORS[name]})
            continue
        if progress:
            print(f"[zoo] {name} ...", flush=True)
        t0 = time.perf_counter()
        rows.append(run_model(name, quick, convergence, end_time))
        if progress:
            print(f"[zoo] {name}: {rows[-1].get('verdict')} ({time.perf_counter() - t0:.0f} s)", flush=True)
    for name, error in errors.items():
        if name not in names:
            rows.append({"model": name, "verdict": "import error", "error": error})
    table = pd.DataFrame(rows)
    if out is not None:
        out.mkdir(parents=True, exist_ok=True)
        table.to_csv(out / "zoo.csv", index=False)
        (out / "report.md").write_text(report(table, quick, end_time, None if names_given else group))
    return table


def show(table: Any) -> str:
    """The printed table: :data:`TABLE_COLUMNS` that exist, numbers rounded."""
    cols = [c for c in TABLE_COLUMNS if c in table.columns]
    return table[cols].to_string(index=False, float_format=lambda x: f"{x:.3g}")


def report(table: Any, quick: bool, end_time: float | None, group: str | None = DEFAULT_GROUP) -> str:
    """The Markdown report: _report.md filled with the tables and the run's notes; ``group``:
    the group run (None: models named one by one)."""
    template = (Path(__file__).with_name("_report.md")).read_text()
    cols = [c for c in TABLE_COLUMNS if c in table.columns]
    messages = []
    for _, r in table.iterrows():
        for key in ("ideal_message", "own_message", "own_warnings", "sim_message", "sim_warnings", "error"):
            value = r.get(key)
            if isinstance(value, str) and value:
                messages.append(f"- `{r['model']}` {key}: {value}")
    entries = [REGISTRY[n] for n in table["model"] if n in REGISTRY]
    models = "\n".join(f"- `{e.name}`: {e.example} ({e.bodies}); replaced: {e.replaced}"
                       + (f"; with {', '.join(f'{k}={v!r}' for k, v in e.fixed.items())}" if e.fixed else "")
                       for e in entries)
    return template.format(
        mode="quick (one run per timing, no convergence check)" if quick else "full (median of 3 timings)",
        group="the models named" if group is None else f"the group {group!r}",
        end_time="the examples' own" if end_time is None else f"{end_time:g} s for every model",
        exudyn=exu.__version__, exuclear=getattr(exuclear, "__version__", "?"),
        models=models, table=table[cols].to_markdown(index=False, floatfmt=".3g") if _has_tabulate()
        else "```\n" + show(table) + "\n```",
        messages="\n".join(messages) or "(none)", pen_wrong=PENETRATION_WRONG, ref_factor=REFERENCE_FACTOR,
        converged=CONVERGED_PENETRATION,
        time_limit=QUICK_TIME_LIMIT if quick else TIME_LIMIT)


def _has_tabulate() -> bool:
    try:
        import tabulate  # noqa: F401
    except ImportError:
        return False
    return True
