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
    minimum at 0.3, not at the noise level: the measured landing is not a typical member).
    Session 25 (numpy 2.4.6, constraints.txt): one drop 1.92 1.69 1.74 1.36 0.06 1.23 1.51 2.15 2.20;
    ensemble 1.98 1.87 1.70 1.35 1.37 1.22 0.93 1.92 2.32, +/- 0.06-0.20 (jackknife over the 8
    drops). Its raw count is 2 minima: 1.35 beside 1.37 is a 0.02 ripple against errors of 0.08
    and 0.05. So a minimum counts for the ensemble only when its well is deeper, on both sides,
    than 2 standard errors of the difference (``significant_minima``): none here, one basin."""
    from diagnose_gap_scan import scan

    res = scan([0.05, 0.1, 0.15, 0.2, 0.22, 0.25, 0.3, 0.4, 0.5], 8, 3e-5, 2)
    assert res["single_local_minima"] >= 2 and not res["single_one_basin"]
    assert res["ensemble_significant_minima"] <= 1 and res["ensemble_one_basin"]
    # the deepest well (its shallower side) of the ensemble scan is far shallower than the needle

    def deepest_well(g):
        return max(min(g[i - 1] - g[i], g[i + 1] - g[i]) for i in range(1, len(g) - 1))

    assert deepest_well(res["ensemble"]) < 0.5 * deepest_well(res["single"])


def test_a_minimum_counts_only_beyond_the_noise_of_its_well():
    """significant_minima against hand-made scans; the jackknife error against numpy's for a mean
    (for the mean the jackknife gives exactly the standard error s / sqrt(n))."""
    import numpy as np

    from diagnose_gap_scan import jackknife_se, local_minima, one_basin, significant_minima

    g = [1.98, 1.87, 1.70, 1.35, 1.37, 1.22, 0.93, 1.92, 2.32]
    se = [0.06, 0.08, 0.09, 0.08, 0.05, 0.13, 0.15, 0.20, 0.02]
    assert local_minima(g) == 2 and significant_minima(g, se) == 0
    assert significant_minima(g, [0.01] * 9) == 1          # with small errors the 0.29-deep well at 0.3 counts
    needle = [2.0, 1.9, 1.8, 0.1, 1.7, 1.6, 0.2, 1.8, 2.0]
    assert significant_minima(needle, [0.1] * 9) == 2
    assert one_basin(g, se) and not one_basin(g, [0.0] * 9) and not one_basin(needle, [0.1] * 9)
    x = np.random.default_rng(5).normal(size=12)
    loo = [float(np.mean(np.delete(x, k))) for k in range(12)]
    assert jackknife_se(loo) == pytest.approx(float(x.std(ddof=1) / np.sqrt(12)))
