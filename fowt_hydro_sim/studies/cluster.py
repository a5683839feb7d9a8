"""Many model runs on a Dask cluster: a LocalCluster on this machine (loopback only) by
default, or an existing cluster by its scheduler address, with no code change; a progress
bar on stderr (the results in order, or each as soon as it is ready)."""
from __future__ import annotations

import logging
import os
from contextlib import contextmanager
from typing import Callable, Iterator, Sequence


@contextmanager
def dask_client(scheduler: str | None = None, workers: int | None = None) -> Iterator:
    """A ``dask.distributed.Client``: of the cluster at ``scheduler``, else of a local cluster
    of ``workers`` single-threaded processes (default: one per core) on 127.0.0.1."""
    from dask.distributed import Client, LocalCluster
    logging.getLogger("distributed").setLevel(logging.WARNING)  # not every worker's start and stop
    if scheduler:
        with Client(scheduler) as client:
            yield client
        return
    with LocalCluster(n_workers=workers or os.cpu_count() or 1, threads_per_worker=1, processes=True,
                      host="127.0.0.1", scheduler_kwargs={"dashboard": False, "dashboard_address": "127.0.0.1:0"},
                      ) as cluster, Client(cluster) as client:  # (its HTTP server on loopback, no dashboard)
        yield client


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
