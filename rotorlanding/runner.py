"""One study runner: the process pool, BLAS thread limits, failures as rows and the reduction cache
that ``sweep``, ``calibrate``, ``validate`` and ``diagnose`` share (``fit-modes`` runs serially and
shares the BLAS limit).

Learned from Exudyn's ``processing.ParameterVariation`` / ``GeneticOptimization``: every study is a
job function ``fn(job) -> result`` and a list of jobs; one driver runs them. Here:

- :class:`Pool` runs ``fn`` over jobs in forked worker processes (serially in this process when
  ``workers <= 1``), results in job order; a job that raises comes back as a :class:`Failure` row
  (``failures="row"``) or stops the study (``failures="raise"``), never as a dead pool;
- :func:`worker_setup` runs once per worker: BLAS/LAPACK single-threaded (so N workers do not
  oversubscribe the cores, and a result does not depend on the machine's thread count), model code
  imported, this process's :class:`ReductionCache` created. ``blas_threads=None`` leaves BLAS as
  the parent's: the thread count changes the last bits of a landing (tested: a 0.3 s backward
  landing's summary differs at 1e-13..1e-7 between 1 and 2 OpenBLAS threads, its race speed at
  2.6e-9), so ``validate``, ``calibrate`` and ``diagnose`` keep the setting their published
  numbers were made with; moving them to 1 thread is a change of their results, not a refactor;
- :func:`reduction_cache` is that cache, passed explicitly to ``landing.build_spec`` (through
  ``run.simulate``/``run.run_scenario``): nothing is monkeypatched.
"""

from __future__ import annotations

import hashlib
import traceback
from dataclasses import dataclass, replace

import numpy as np

from .blas import BLAS_ENV, limit_blas_threads  # noqa: F401  (re-exported: workers, modefit)


class ReductionCache:
    """``reduction.craig_bampton`` memoised on the exact FE matrices and reduction settings (cases of
    a study that change no rotor value share one reduction)."""

    def __init__(self, fn=None, size: int = 8):
        if fn is None:
            from .reduction import craig_bampton as fn
        self.fn, self.size, self.store, self.hits = fn, size, {}, 0

    def key(self, fe, stations, n_modes, rotations):
        h = hashlib.sha256()
        for a in (fe.M, fe.K, fe.C, fe.G):
            a = np.ascontiguousarray(a)
            h.update(repr((a.shape, a.dtype.str)).encode())
            h.update(a.tobytes())
        nodes = tuple(fe.station_nodes.get(s) for s in stations)
        return h.hexdigest(), tuple(stations), nodes, int(n_modes), bool(rotations)

    def __call__(self, fe, stations, n_modes, rotations=False):
        k = self.key(fe, stations, n_modes, rotations)
        cb = self.store.get(k)
        if cb is None:
            cb = self.fn(fe, stations, n_modes, rotations)
            if len(self.store) >= self.size:
                self.store.pop(next(iter(self.store)))
            self.store[k] = cb
        else:
            self.hits += 1
        # fresh arrays and this case's FE model: callers may not alias the cached copy
        return replace(cb, M=cb.M.copy(), K=cb.K.copy(), C=cb.C.copy(), G=cb.G.copy(), T=cb.T.copy(),
                       names=list(cb.names), fe=fe, boundary=list(cb.boundary))


_WORKER: dict = {}   # this process as a worker: {"cache": ReductionCache, "undo": callable}


def worker_setup(blas_threads: int | None = 1):
    """Once per worker process: BLAS limited to ``blas_threads`` (None: as it is), model code
    imported, the reduction cache. Returns a function that undoes it (for a parent process that
    forks workers)."""
    if _WORKER:
        return lambda: None
    restore_blas = limit_blas_threads(blas_threads) if blas_threads else (lambda: None)
    from . import run  # noqa: F401  (exudyn, numba kernels, h5py)

    _WORKER["cache"] = ReductionCache()

    def undo():
        restore_blas()
        _WORKER.clear()

    return undo


def reduction_cache() -> ReductionCache | None:
    """This process's reduction cache when it is set up as a worker (else None: no caching)."""
    return _WORKER.get("cache")


def warm_model(scenario, sets=()) -> None:
    """In a parent process about to fork workers: import the model code and load every compiled
    kernel of a landing from numba's cache by building (not solving) ``scenario``'s model and
    post-processing its initial state, so that no worker pays the imports (~0.8 s) and the kernel
    loading (~0.4 s) again; nothing of the worker setup (BLAS limits, reduction cache) is done here.
    A scenario that fails to build is left to fail in its job."""
    import numpy as np

    from .exudyn_model import build_exudyn
    from .landing import build_spec
    from .postprocess import evaluate
    from .scenario import load_scenario

    try:
        spec = build_spec(load_scenario(scenario, list(sets)))
        build_exudyn(spec)
        q0, v0 = spec.initial_state()
        evaluate(spec, np.array([0.0, 1e-4]), np.array([q0, q0]), np.array([v0, v0]))
    except Exception:  # noqa: BLE001 - recorded where the job runs
        pass


@dataclass(frozen=True)
class Failure:
    """A job that raised: its row in the study's results."""

    job: object
    error: str        # "Type: message", one line
    details: str      # the traceback


def _guarded(fn, job):
    try:
        return fn(job)
    except Exception as exc:  # noqa: BLE001 - a failed job is a row, the study goes on
        return Failure(job, f"{type(exc).__name__}: {exc}".replace("\n", " "), traceback.format_exc())


def _call(args):
    fn, job = args
    return _guarded(fn, job)


def executor(workers: int, blas_threads: int | None = 1):
    """A process pool of forked workers (inheriting the parent's imports and caches) set up by
    :func:`worker_setup`."""
    import functools
    import multiprocessing as mp
    from concurrent.futures import ProcessPoolExecutor

    ctx = mp.get_context("fork") if "fork" in mp.get_all_start_methods() else None
    return ProcessPoolExecutor(workers, mp_context=ctx, initializer=functools.partial(worker_setup, blas_threads))


class Pool:
    """Run job functions over jobs, in ``workers`` processes (kept for the pool's lifetime, so a
    study that maps many batches pays the start once) or serially here with ``workers <= 1``."""

    def __init__(self, workers: int = 1, *, blas_threads: int | None = 1, warm=None):
        """``warm``: called here once before the workers fork (e.g. ``functools.partial(warm_model,
        scenario)``), so they inherit what it loaded."""
        self.workers = workers
        if warm is not None and workers > 1:
            warm()
        self._ex = executor(workers, blas_threads) if workers > 1 else None

    def map(self, fn, jobs, *, failures: str = "row") -> list:
        """``fn(job)`` for every job, results in job order; a job that raises gives a
        :class:`Failure` (``failures="row"``) or raises RuntimeError naming it (``"raise"``)."""
        jobs = list(jobs)
        if self._ex is None:
            out = [_guarded(fn, j) for j in jobs]
        else:
            out = list(self._ex.map(_call, [(fn, j) for j in jobs]))
        if failures == "raise":
            for r in out:
                if isinstance(r, Failure):
                    raise RuntimeError(f"{r.error}\n{r.details}")
        return out

    def close(self):
        if self._ex is not None:
            self._ex.shutdown()
            self._ex = None

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()


def run_all(fn, jobs, workers: int = 1, *, failures: str = "row", blas_threads: int | None = 1, warm=None) -> list:
    """One study batch: ``Pool(workers, blas_threads=..., warm=...).map(fn, jobs)`` and the pool closed."""
    with Pool(workers, blas_threads=blas_threads, warm=warm) as pool:
        return pool.map(fn, jobs, failures=failures)
