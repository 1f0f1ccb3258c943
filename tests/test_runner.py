"""The one study runner (rotorlanding.runner): results in job order, a failing job as its row (or
the study stopped), the reduction cache passed in explicitly with the same numbers."""

from pathlib import Path

import numpy as np
import pytest

from rotorlanding import landing, reduction
from rotorlanding.runner import Failure, ReductionCache, run_all
from rotorlanding.scenario import load_scenario

ROOT = Path(__file__).resolve().parents[1]


def _square_or_fail(x):
    if x % 3 == 2:
        raise ValueError(f"no {x}")
    return x * x


@pytest.mark.parametrize("workers", [1, 2])
def test_results_in_job_order_and_failures_as_rows(workers):
    out = run_all(_square_or_fail, range(7), workers)
    for x, r in zip(range(7), out):
        if x % 3 == 2:
            assert isinstance(r, Failure) and r.job == x and r.error == f"ValueError: no {x}"
            assert "Traceback" in r.details
        else:
            assert r == x * x


@pytest.mark.parametrize("workers", [1, 2])
def test_failures_raise_stops_the_study(workers):
    with pytest.raises(RuntimeError, match="ValueError: no 2"):
        run_all(_square_or_fail, range(4), workers, failures="raise")


def test_reduction_cache_is_passed_in_and_gives_the_same_numbers():
    sc = load_scenario(ROOT / "scenarios" / "paper" / "no_whirl_landing.toml")
    cache = ReductionCache()
    plain = landing.build_spec(sc)
    first = landing.build_spec(sc, reduction=cache)
    again = landing.build_spec(sc, reduction=cache)
    assert cache.hits == 1 and len(cache.store) == 1
    for s in (first, again):
        for name in ("M", "K", "C", "G", "f_gravity"):
            assert np.array_equal(getattr(s, name), getattr(plain, name)), name
    assert again.M is not first.M                       # a hit hands out fresh arrays
    assert landing.craig_bampton is reduction.craig_bampton   # nothing was patched


_WARMED = []


def _warmed(_):
    return len(_WARMED)


@pytest.mark.parametrize("workers,expected", [(1, 0), (2, 1)])
def test_warm_runs_once_in_the_parent_before_the_workers_fork(workers, expected):
    """``warm`` (e.g. runner.warm_model: imports and compiled kernels loaded once) runs in the
    parent only when workers fork, and the workers inherit what it did."""
    _WARMED.clear()
    out = run_all(_warmed, range(3), workers, warm=lambda: _WARMED.append(1))
    assert len(_WARMED) == expected and out == [expected] * 3


def test_warm_model_loads_the_kernels_and_swallows_a_bad_scenario():
    from rotorlanding.bearing_kernel import landing_rhs, rub_series
    from rotorlanding.runner import warm_model

    warm_model(ROOT / "scenarios" / "paper" / "forward_whirl_landing.toml")
    assert landing_rhs.signatures and rub_series.signatures
    warm_model(ROOT / "no such scenario.toml")  # left to fail in its job
