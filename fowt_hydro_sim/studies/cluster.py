"""Many model runs on a Dask cluster: a LocalCluster on this machine (loopback only) by
default, or an existing cluster by its scheduler address, with no code change; a progress
bar on stderr (the results in order, or each as soon as it is ready).

A local cluster's worker processes ignore SIGINT (``dask_setup``, run in each as it starts):
Ctrl-C (which the terminal sends to the whole process group) is handled by this process
alone, which shuts the cluster down (the client, then each worker, given ``WORKER_EXIT_S``
to exit, then the cluster) with Dask's own shutdown messages kept off the terminal. The
worker processes log only what is critical: a run's exception reaches the user through its
result, a worker that dies through this process's nanny (a worker interrupted mid-run would
otherwise print the tracebacks of its broken connections). Runs the cluster loses
(cancelled, forgotten, or their worker killed too often) end the work with a
``ClusterError``: one line, not Dask's traceback."""
from __future__ import annotations

import asyncio
import logging
import os
import signal
import threading
from collections.abc import Callable, Iterator, Sequence
from contextlib import contextmanager

from fowt_hydro_sim.errors import ClusterError, InputError

WORKER_EXIT_S = 30.0  # a worker process asked to close is killed only after 0.8 x this
INTERRUPTED_EXIT_S = 5.0  # the same after Ctrl-C: a worker busy with a run is not waited for


@contextmanager
def _sigint_ignored() -> Iterator[None]:
    """SIGINT ignored meanwhile (when called from the main thread): a second Ctrl-C does not
    break a shutdown under way (bounded by its timeouts)."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    previous = signal.signal(signal.SIGINT, signal.SIG_IGN)
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, previous)


@contextmanager
def _sigint_held() -> Iterator[None]:
    """SIGINT blocked meanwhile in the main thread: the threads it starts inherit it blocked
    (Ctrl-C reaches the main thread, not the cluster's event loop), and a Ctrl-C meanwhile is
    not lost but raised (KeyboardInterrupt) on leaving."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    previous = signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT})
    try:
        yield
    finally:
        signal.pthread_sigmask(signal.SIG_SETMASK, previous)


def dask_setup(worker) -> None:
    """Run by each local worker process as it starts (Dask's ``preload``): SIGINT ignored
    there, so that Ctrl-C reaches only the command, which shuts the cluster down. (A worker
    process resets the signal mask it is spawned with, and its event loop turns a SIGINT into
    a KeyboardInterrupt with the traceback of every coroutine it cancels.)"""
    signal.signal(signal.SIGINT, signal.SIG_IGN)


@contextmanager
def quiet_dask(level: int) -> Iterator[None]:
    """Distributed's loggers (in this process) at ``level`` or above meanwhile: a shutdown's
    routine warnings (workers killed after a timeout, connections closed, tasks cancelled)
    are no failure of the user's."""
    loggers = [logging.getLogger(name) for name in ("distributed", *sorted(logging.root.manager.loggerDict))
               if name == "distributed" or name.startswith("distributed.")]
    previous = [logger.level for logger in loggers]
    for logger in loggers:
        if logger.name == "distributed" or logger.level != logging.NOTSET:
            logger.setLevel(max(level, logger.getEffectiveLevel()))
    try:
        yield
    finally:
        for logger, old in zip(loggers, previous):
            logger.setLevel(old)


def _close_local(client, cluster, interrupted: bool) -> None:
    """Close the client, then every worker (given time to exit), then the cluster."""
    timeout = INTERRUPTED_EXIT_S if interrupted else WORKER_EXIT_S

    async def close_workers() -> None:
        await asyncio.gather(*(worker.close(timeout=timeout) for worker in list(cluster.workers.values())),
                             return_exceptions=True)

    with _sigint_ignored(), quiet_dask(logging.CRITICAL if interrupted else logging.ERROR):
        if client is not None:
            client.close(timeout=timeout)
        cluster.sync(close_workers)
        cluster.close(timeout=timeout)


@contextmanager
def _lost_runs_as_cluster_error() -> Iterator[None]:
    """Dask's errors for runs it lost (a cancelled or forgotten future, a worker killed too
    often) raised as one ``ClusterError`` naming the reason."""
    from concurrent.futures import CancelledError

    from distributed.scheduler import KilledWorker
    try:
        yield
    except (CancelledError, KilledWorker) as exc:
        reason = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
        raise ClusterError(f"the Dask cluster lost runs under way ({reason}); a sweep or diagnose-benchmark "
                           "resumes when run again into the same folder") from None


@contextmanager
def dask_client(scheduler: str | None = None, workers: int | None = None) -> Iterator:
    """A ``dask.distributed.Client``: of the cluster at ``scheduler``, else of a local cluster
    of ``workers`` single-threaded processes (default: one per core) on 127.0.0.1, shut down
    cleanly and quietly on leaving (also on Ctrl-C, which only this process receives).
    InputError if Dask (the ``cluster`` extra) is not installed; ClusterError if the cluster
    loses runs."""
    try:
        from dask.distributed import Client, LocalCluster
    except ImportError:
        raise InputError("this command runs on a Dask cluster, and Dask is not installed: "
                         "pip install 'fowt_hydro_sim[cluster]'") from None
    logging.getLogger("distributed").setLevel(logging.WARNING)  # not every worker's start and stop
    interrupted = False
    if scheduler:
        client = Client(scheduler)
        try:
            with _lost_runs_as_cluster_error():
                yield client
        except KeyboardInterrupt:
            interrupted = True
            raise
        finally:
            with _sigint_ignored(), quiet_dask(logging.CRITICAL if interrupted else logging.ERROR):
                client.close()
        return
    cluster = client = None
    try:
        with _sigint_held():  # the cluster's thread starts with SIGINT blocked, its workers ignore it
            cluster = LocalCluster(n_workers=workers or os.cpu_count() or 1, threads_per_worker=1, processes=True,
                                   host="127.0.0.1", silence_logs=logging.CRITICAL, preload=[__name__],
                                   scheduler_kwargs={"dashboard": False, "dashboard_address": "127.0.0.1:0"})
            # (the scheduler's HTTP server on loopback, no dashboard)
            client = Client(cluster)
        with _lost_runs_as_cluster_error():
            yield client
    except KeyboardInterrupt:
        interrupted = True
        raise
    finally:
        if cluster is not None:
            _close_local(client, cluster, interrupted)


def map_with_progress(client, function: Callable, items: Sequence, description: str, position: int = 0,
                      **shared) -> list:
    """``function(item, **shared)`` for every item on the cluster, in order, with a progress
    bar (at line ``position``: several maps may run at once); ``shared`` values (e.g. a
    measured record) are sent to the workers with each map, unless already scattered
    (``scatter``)."""
    from dask.distributed import Future, as_completed
    from tqdm import tqdm
    shared = {k: v if isinstance(v, Future) else scatter(client, v) for k, v in shared.items()}
    futures = client.map(function, list(items), pure=False, **shared)
    with tqdm(total=len(futures), desc=description, unit="run", leave=False, position=position) as bar:
        for _ in as_completed(futures):
            bar.update()
    return client.gather(futures)


def scatter(client, value):
    """``value`` on every worker, once, as one object (a future to pass to
    ``map_with_progress``; scattering a dict or list itself would scatter its items)."""
    return client.scatter([value], broadcast=True, hash=False)[0]


def results_as_completed(client, function: Callable, items: Sequence, description: str, done: int = 0,
                         **shared) -> Iterator:
    """``function(item, **shared)`` for every item on the cluster, each result yielded as
    soon as it is ready (in finishing order), with a progress bar and its ETA counting
    ``done`` items finished before (a resumed study)."""
    from dask.distributed import as_completed
    from tqdm import tqdm
    futures = client.map(function, list(items), pure=False, **shared)
    with tqdm(total=done + len(futures), initial=done, desc=description, unit="run", smoothing=0.1) as bar:
        for future in as_completed(futures):
            result = future.result()
            bar.update()
            yield result
