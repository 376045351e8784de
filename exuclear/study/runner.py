"""The runner: :func:`run_study` completes and checks every parameter set, resumes a table,
sends batches sized to about :data:`TASK_SECONDS` of work to an executor, records each row
as it comes back, reruns alone the runs of a task that died, and stops cleanly on Ctrl-C."""
from __future__ import annotations

import concurrent.futures as cf
import contextlib
import math
import os
from collections import deque
from collections.abc import Callable, Iterable, Mapping, Sequence
from concurrent.futures.process import BrokenProcessPool
from numbers import Integral
from pathlib import Path
from typing import Any

from .batch import _error_text, _run_batch, _shippable
from .executors import _check_workers, _CtrlC, _Pool, _pool, _SerialExecutor
from .spec import Params, Study, _as_study, identity, run_id
from .table import _Table, _write_parquet

#: Target duration of one task [s]: a batch holds about this much work, so that the
#: per-task cost (some milliseconds with Dask, less with local processes) stays below
#: 1 % of it, while a finished batch still reaches the table within a second or so.
TASK_SECONDS = 1.0
#: Tasks kept in flight per worker: one running, one waiting, so no worker idles while
#: the next batch travels to it.
IN_FLIGHT_PER_WORKER = 2
#: At least this many tasks per worker over what is left of a study, so that the last
#: batches finish together instead of one worker carrying a long tail.
TASKS_PER_WORKER = 4


def prepare(study: Study | Callable, runs: Iterable[Mapping[str, Any]]) -> list[tuple[str, Params]]:
    """Complete and check every parameter set before any run: ``ValueError`` naming the
    first bad set.  Returns ``(run_id, params)`` pairs, duplicates dropped."""
    study = _as_study(study)
    prepared, seen = [], set()
    for index, params in enumerate(runs):
        full = study.complete(params)
        if study.check is not None:
            try:
                study.check(dict(full))
            except ValueError as err:
                raise ValueError(f"run {index} {params}: {err}") from None
        key = run_id(full)
        if key not in seen:
            seen.add(key)
            prepared.append((key, full))
    if not prepared:
        raise ValueError("the study has no runs")
    return prepared


def run_study(study: Study | Callable[[Params], Mapping[str, Any]], runs: Iterable[Mapping[str, Any]],
              out: str | os.PathLike | None = None, *, workers: int | None = None, scheduler: str | None = None,
              executor: cf.Executor | None = None, batch_size: int | None = None, retry_failed: bool = False,
              progress: bool = True, keep_arrays: bool = False):
    """Run ``study`` over ``runs``; returns the table (a DataFrame, rows in the order of
    ``runs``).

    Parameters
    ----------
    study : Study or callable
        The study (a bare function: no parameter names or checks).
    runs : iterable of dict
        Parameter sets (:func:`grid`, :func:`sample`, or a list); all are completed and
        checked before the first run.
    out : path, optional
        The study's CSV, appended row by row; an existing table of the same study is
        resumed (its runs are skipped).  Parquet is written next to it at the end when
        pyarrow is present, and the study's identity (its function and that function's
        code, its parameters, its columns) in ``<out>.study.json``: a table written by
        another study (or by this one before its function changed) is refused, with how
        to start afresh or keep both.
    workers : int, optional
        Local worker processes (default: all cores; 1: in this process), or the workers
        of a local Dask cluster.
    scheduler : str, optional
        A Dask scheduler address, or ``"local"`` for a ``LocalCluster``.
    executor : concurrent.futures.Executor, optional
        Run through this executor instead (not shut down here).
    batch_size : int, optional
        Runs per task; default: adaptive, about :data:`TASK_SECONDS` of work per task.
    retry_failed : bool
        Also redo the runs that failed in the existing table.
    progress : bool
        Show a tqdm progress bar (done, failed, rate, ETA) on stderr.
    keep_arrays : bool
        Only with ``out=None``: array metrics come back as the numpy arrays the runs
        returned, not through the table's text as lists; for time series a table on
        disk would not carry.

    Returns
    -------
    DataFrame
        One row per parameter set of ``runs``.  ``table.attrs["ran"]``: the runs made
        by this call; ``table.attrs["resumed"]``: the rows taken from the table at ``out``
        (a resumed study).  A row's ``message`` carries the run's own message and its
        warnings of :data:`CARRIED_WARNINGS` (``UnitWarning: ...``; :func:`warned`).

    Raises
    ------
    ValueError
        Before any run: unknown parameter names, values the study refuses, no runs,
        a table at ``out`` that belongs to another study (its sidecar names another
        function, code, parameters or columns).
    KeyboardInterrupt
        On Ctrl-C or a ``KeyboardInterrupt`` from a run, after the finished rows are on
        disk.
    """
    study = _as_study(study)
    _check_workers(workers)
    if batch_size is not None and (isinstance(batch_size, bool) or not isinstance(batch_size, Integral)
                                   or batch_size < 1):
        raise ValueError(f"`batch_size` must be a positive integer, got {batch_size!r}")
    prepared = prepare(study, runs)
    path = None if out is None else Path(out)
    if keep_arrays and path is not None:
        raise ValueError("`keep_arrays` keeps arrays in memory: give it with `out=None`")
    if path is not None and path.suffix.lower() != ".csv":
        raise ValueError(f"`out` must name a .csv file (Parquet is written next to it), got {str(out)!r}")
    if path is not None and not path.parent.exists():
        path.parent.mkdir(parents=True)
    names = list(study.parameters) if study.parameters is not None else list(dict.fromkeys(
        k for _, p in prepared for k in p))
    table = _Table.open(path, names, keep_arrays, identity(study))
    done = {k for k, row in table.rows.items() if not (retry_failed and row.get("success") == "False")}
    todo = deque((k, p) for k, p in prepared if k not in done)
    order = [k for k, _ in prepared]
    ran = len(todo)
    if todo:
        _execute(study, todo, table, len(prepared), workers, scheduler, executor, batch_size, progress)
    df = table.frame(order)
    if path is not None:
        _write_parquet(df, path)
    df.attrs.update(ran=ran, resumed=len(prepared) - ran)  # after the Parquet file, which would keep them
    return df


class _Progress:
    """tqdm bar of done runs, with the failed ones in its postfix; or nothing."""

    def __init__(self, total: int, initial: int, label: str, show: bool) -> None:
        self.failed = 0
        self.bar = None
        if show:
            from tqdm.auto import tqdm

            self.bar = tqdm(total=total, initial=initial, desc=label or "study", unit="run", dynamic_ncols=True,
                            smoothing=0.1)
            self.bar.set_postfix(failed=0)

    def update(self, rows: Sequence[Mapping[str, Any]]) -> None:
        self.failed += sum(not r["success"] for r in rows)
        if self.bar is not None:
            self.bar.update(len(rows))
            self.bar.set_postfix(failed=self.failed)

    def close(self) -> None:
        if self.bar is not None:
            self.bar.close()


def _execute(study: Study, todo: deque, table: _Table, total: int, workers: int | None, scheduler: str | None,
             executor: cf.Executor | None, batch_size: int | None, show: bool) -> None:
    pool = _pool(workers, scheduler, executor)
    serial = isinstance(pool.executor, _SerialExecutor)
    function = study.function if serial else _shippable(study.function)
    bar = _Progress(total, total - len(todo), study.name, show)
    in_flight: dict[cf.Future, list] = {}
    window = 1 if serial else pool.workers * IN_FLIGHT_PER_WORKER
    ctrl_c = _CtrlC() if serial else contextlib.nullcontext(None)
    interrupted = False
    try:
        with ctrl_c as pressed:
            _loop(pool, function, todo, table, bar, batch_size, window, in_flight, pressed)
    except KeyboardInterrupt:
        interrupted = True
        for future in list(in_flight):  # tasks finished meanwhile are kept too
            if future.done() and not future.cancelled() and future.exception() is None:
                for row in future.result():
                    table.add(row)
                del in_flight[future]
    finally:
        bar.close()
        for future in in_flight:
            future.cancel()
        pool.close(cancel=interrupted or bool(in_flight))
    if interrupted:
        where = f"; {len(table.rows)} rows kept in {table.path}, run again to resume" if table.path else ""
        raise KeyboardInterrupt(f"study interrupted{where}")


def _loop(pool: _Pool, function: Any, todo: deque, table: _Table, bar: _Progress, batch_size: int | None,
          window: int, in_flight: dict, ctrl_c: _CtrlC | None) -> None:
    """Submit batches, keep ``window`` tasks in flight, record the rows as tasks finish."""
    # runs of a task that died as a whole (its worker crashed or was lost): each is rerun
    # alone, so that a second death names the run that causes it
    suspects: deque = deque()
    alone: set[cf.Future] = set()
    timing = [0.0, 0]  # wall time and number of finished runs, for the batch size

    def restart() -> None:
        """A broken local pool loses every task in it: they become suspects."""
        for other in list(in_flight):
            suspects.extend(in_flight.pop(other))
        alone.clear()
        pool.executor.shutdown(wait=True, cancel_futures=True)
        pool.executor = pool.restart()

    def submit(batch: list) -> cf.Future:
        try:
            future = pool.executor.submit(_run_batch, function, batch)
        except BrokenProcessPool:  # a worker died before its task came back: noticed here first
            if pool.restart is None:
                raise
            restart()
            future = pool.executor.submit(_run_batch, function, batch)
        in_flight[future] = batch
        return future

    while todo or suspects or in_flight:
        while (todo or suspects) and len(in_flight) < window:
            if suspects:
                if in_flight:
                    break  # a suspect waits until it can run alone
                future = submit([suspects.popleft()])
                if len(in_flight) == 1:
                    alone.add(future)
                break
            size = batch_size or _batch_size(timing, len(todo), pool.workers)
            submit([todo.popleft() for _ in range(min(size, len(todo)))])
        finished, _ = cf.wait(in_flight, return_when=cf.FIRST_COMPLETED)
        for future in [f for f in in_flight if f in finished]:  # in the order of submission
            batch = in_flight.pop(future, None)
            if batch is None:
                continue  # lost with its broken pool (below) and queued again
            try:
                rows = future.result()
            except (KeyboardInterrupt, cf.CancelledError):
                raise KeyboardInterrupt from None
            except Exception as err:  # the task died as a whole: worker killed or lost, unpicklable result
                rows = [_crashed_row(batch[0], err)] if future in alone else []
                if not rows:
                    suspects.extend(batch)
                if isinstance(err, BrokenProcessPool) and pool.restart is not None:
                    restart()
            alone.discard(future)
            if ctrl_c is not None and ctrl_c.pressed > 1:
                rows = [row for row in rows if row["success"]]  # a failure may be the second Ctrl-C
            for row in rows:
                table.add(row)
                timing[0] += row["wall_time"] if math.isfinite(row["wall_time"]) else 0.0
                timing[1] += 1
            bar.update(rows)
        if ctrl_c is not None and ctrl_c.pressed:
            raise KeyboardInterrupt


def _crashed_row(item: tuple[str, Params], err: BaseException) -> dict[str, Any]:
    key, params = item
    return {**params, "success": False, "message": f"the run killed its worker ({_error_text(err)})",
            "wall_time": math.nan, "run_id": key}


def _batch_size(timing: list, left: int, workers: int) -> int:
    """Runs per task: about :data:`TASK_SECONDS` of work at the mean run time so far
    (one run until a first one has finished), and no more than leaves
    :data:`TASKS_PER_WORKER` tasks per worker over the runs left."""
    seconds, count = timing
    if count == 0:
        return 1
    mean = max(seconds / count, 1e-6)
    balanced = max(1, left // (workers * TASKS_PER_WORKER))
    return max(1, min(int(TASK_SECONDS / mean), balanced))
