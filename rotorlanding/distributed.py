"""Optional Dask path for sweeps (``--scheduler tcp://host:8786``); needs ``dask[distributed]``."""

from __future__ import annotations

from .errors import InputError


def map_on_dask(fn, jobs, scheduler: str):
    try:
        from dask.distributed import Client
    except ImportError:
        raise InputError("--scheduler", scheduler,
                         "needs dask.distributed: pip install 'rotorlanding[dask]' (or dask[distributed])") from None
    with Client(scheduler) as client:
        futures = client.map(fn, jobs, pure=False)
        return client.gather(futures)
