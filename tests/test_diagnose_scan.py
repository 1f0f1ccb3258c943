"""Issue 20, point 1: the gap over one parameter, one drop per value vs an ensemble per value
(benchmarks/diagnose_gap_scan.py). Long (81 landings): marked slow."""

import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))


@pytest.mark.slow
def test_ensemble_gap_is_one_basin_where_one_drop_is_a_needle():
    """Measured (2026-11, mu_rad 0.05-0.5, truth 0.22): one drop 2.09 1.84 1.89 1.49 0.04 1.35 1.45
    2.30 2.37 (a needle at the truth: the data are the model's own centred drop; 2 local minima);
    8 drops from a 30 um circle 2.16 2.04 1.86 1.47 1.42 1.33 1.01 2.14 2.52 (one basin, its
    minimum at 0.3, not at the noise level: the measured landing is not a typical member)."""
    from diagnose_gap_scan import scan

    res = scan([0.05, 0.1, 0.15, 0.2, 0.22, 0.25, 0.3, 0.4, 0.5], 8, 3e-5, 2)
    assert res["single_local_minima"] >= 2
    assert res["ensemble_local_minima"] == 1
    # the deepest well (its shallower side) of the ensemble scan is far shallower than the needle

    def deepest_well(g):
        return max(min(g[i - 1] - g[i], g[i + 1] - g[i]) for i in range(1, len(g) - 1))

    assert deepest_well(res["ensemble"]) < 0.5 * deepest_well(res["single"])
