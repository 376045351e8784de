"""Where a study's batches run: in this process, in local worker processes or on a Dask
cluster, behind one :class:`concurrent.futures.Executor`; and what Ctrl-C does to each."""
from __future__ import annotations

import concurrent.futures as cf
import multiprocessing
import os
from collections.abc import Callable
from dataclasses import dataclass, field
from numbers import Integral
from typing import Any


def _ignore_sigint() -> None:
    """Worker initializer: Ctrl-C goes to the main process, which stops the study."""
    import signal

    signal.signal(signal.SIGINT, signal.SIG_IGN)


class _CtrlC:
    """Ctrl-C during a study run in this process (``workers=1``).

    A ``KeyboardInterrupt`` raised inside a solver's Python callback would come back from
    Exudyn as a failed run, and the study would carry on.  So the first Ctrl-C only sets
    :attr:`pressed`: the current run finishes, its row is kept, and the runner then
    stops.  A second Ctrl-C raises at once (a row that then comes back failed is not
    recorded).  Installed only in the main thread, over Python's default handler.
    """

    def __init__(self) -> None:
        self.pressed = 0
        self.previous: Any = None

    def _handle(self, signum: int, frame: Any) -> None:  # noqa: ARG002 - signal handler signature
        self.pressed += 1
        if self.pressed > 1:
            raise KeyboardInterrupt

    def __enter__(self) -> _CtrlC:
        import signal
        import threading

        if threading.current_thread() is threading.main_thread() and \
                signal.getsignal(signal.SIGINT) is signal.default_int_handler:
            self.previous = signal.signal(signal.SIGINT, self._handle)
        return self

    def __exit__(self, *exc: object) -> None:
        if self.previous is not None:
            import signal

            signal.signal(signal.SIGINT, self.previous)


class _SerialExecutor(cf.Executor):
    """Runs each task at submission, in this process (``workers=1``).  A
    ``KeyboardInterrupt`` propagates from :meth:`submit` at once."""

    def submit(self, fn, /, *args, **kwargs):  # noqa: D102 - Executor's interface
        future: cf.Future = cf.Future()
        try:
            future.set_result(fn(*args, **kwargs))
        except Exception as err:
            future.set_exception(err)
        return future



@dataclass
class _Pool:
    """The executor of a study, with what it takes to close (and to restart) it."""

    executor: cf.Executor
    workers: int
    owned: bool
    restart: Callable[[], cf.Executor] | None = None
    closers: list[Callable[[], None]] = field(default_factory=list)

    def close(self, cancel: bool = False) -> None:
        if self.owned:
            self.executor.shutdown(wait=not cancel, cancel_futures=True)
        for close in self.closers:
            close()


def _local_processes(workers: int) -> cf.Executor:
    # spawn: the workers start clean (no copy of this process's threads: progress bar,
    # Dask client), as Dask's workers do
    return cf.ProcessPoolExecutor(max_workers=workers, mp_context=multiprocessing.get_context("spawn"),
                                  initializer=_ignore_sigint)


def _dask_pool(scheduler: str, workers: int | None) -> _Pool:
    try:
        from dask.distributed import Client, LocalCluster
    except ImportError:
        raise ValueError("`scheduler` needs Dask: pip install 'exuclear[cluster]'") from None
    closers = []
    if scheduler == "local":
        cluster = LocalCluster(n_workers=workers or os.cpu_count() or 1, threads_per_worker=1, processes=True,
                               dashboard_address=None)
        client = Client(cluster)
        closers = [client.close, cluster.close]
    else:
        try:
            client = Client(scheduler, timeout="20s")
        except OSError as err:
            raise ValueError(f"cannot reach the Dask scheduler at {scheduler!r}: {err}") from None
        closers = [client.close]
    threads = sum(w.get("nthreads", 1) for w in client.scheduler_info().get("workers", {}).values()) or 1
    # pure=False: a batch resubmitted after a worker was lost is run again, not served
    # from the result of its first submission
    executor = client.get_executor(pure=False)
    return _Pool(executor, threads, owned=False, closers=closers)


def _pool(workers: int | None, scheduler: str | None, executor: cf.Executor | None) -> _Pool:
    if executor is not None:
        if scheduler is not None:
            raise ValueError("give either `executor` or `scheduler`, not both")
        count = workers or getattr(executor, "_max_workers", None) or os.cpu_count() or 1
        return _Pool(executor, count, owned=False)
    if scheduler is not None:
        if not isinstance(scheduler, str) or not scheduler:
            raise ValueError(f"`scheduler` must be an address such as 'tcp://host:8786' or 'local', got {scheduler!r}")
        return _dask_pool(scheduler, workers)
    count = workers if workers is not None else (os.cpu_count() or 1)
    if count == 1:
        return _Pool(_SerialExecutor(), 1, owned=False)
    return _Pool(_local_processes(count), count, owned=True, restart=lambda: _local_processes(count))


def _check_workers(workers: int | None) -> None:
    if workers is not None and (isinstance(workers, bool) or not isinstance(workers, Integral) or workers < 1):
        raise ValueError(f"`workers` must be a positive integer, got {workers!r}")

