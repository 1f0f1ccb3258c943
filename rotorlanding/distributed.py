"""Optional Dask path for sweeps (``--scheduler tcp://host:8786``); needs ``dask[distributed]``.

Cases are submitted one task each, longest first (the order of ``jobs``), and gathered one by
one: a case whose task raises (for instance its worker died and Dask gave up on it) becomes a
failed row through ``on_error``, the same as a case that raises inside ``run_case``.
"""

from __future__ import annotations

from .errors import InputError

CONNECT_TIMEOUT_S = 10


def map_on_dask(fn, jobs, scheduler: str, *, warm_up=None, on_error=None, timeout: float | None = None):
    try:
        from dask.distributed import Client, as_completed
    except ImportError:
        raise InputError("--scheduler", scheduler,
                         "needs dask.distributed: pip install 'rotorlanding[dask]' (or dask[distributed])") from None
    try:
        client = Client(scheduler, timeout=timeout or CONNECT_TIMEOUT_S)
    except (OSError, TimeoutError, ValueError) as err:
        why = str(err).splitlines()[0] if str(err) else type(err).__name__
        raise InputError("--scheduler", scheduler, f"cannot connect to a Dask scheduler there ({why})") from None
    with client:
        if warm_up is not None:
            client.run(warm_up)  # every worker: model code imported, kernels loaded, BLAS single-threaded
        n = len(jobs)
        futures = {client.submit(fn, job, pure=False, priority=n - k): job for k, job in enumerate(jobs)}
        results = []
        for fut in as_completed(futures):
            job = futures[fut]
            try:
                results.append(fut.result())
            except Exception as err:
                if on_error is None:
                    raise
                results.append(on_error(job, f"{type(err).__name__}: {err}"))
        return results
