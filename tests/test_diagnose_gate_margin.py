"""The noise gate's own standard error (issue 20, point 6; the standards' "no verdict whose margin
is smaller than its standard error passes or fails silently"): the formula against a Monte Carlo
of the gate over normal member gaps, and the margin's words in the report."""

import math

import numpy as np
import pytest

from rotorlanding.diagnose_run import _margin_text, gate_bound, gate_margin, gate_standard_error, prediction_bound_se


@pytest.mark.parametrize("k", [3, 4])
def test_the_gate_standard_error_matches_a_monte_carlo_of_the_gate(k):
    """With the default 4 members (and 3) the gate is the prediction bound in nearly every draw."""
    rng = np.random.default_rng(7 + k)
    mu, sigma, n = 1.0, 0.1, 6000
    draws = rng.normal(mu, sigma, (n, k))
    gates = np.array([gate_bound(list(d)) for d in draws])
    ses = [gate_standard_error(list(d)) for d in draws]
    assert sum(s is None for s in ses) < 0.01 * n
    se_true = float(np.std(gates, ddof=1))
    # the estimate is unbiased for the spread of the gate (s / c4 is unbiased for sigma; m and s are
    # independent for normal members); Monte Carlo error of a standard deviation over 6000 draws ~0.9 %
    assert np.mean([s for s in ses if s is not None]) == pytest.approx(se_true, rel=0.03)
    # and it is what makes a 4-member gate a noisy number: more than one sigma of the members
    assert se_true > sigma


@pytest.mark.parametrize("k", [8, 16])
def test_the_bound_standard_error_with_more_members(k):
    """The bound m + c s alone, computed here with scipy's t, against the formula (with 8 or 16
    members the largest member often sets the gate instead, 1 - 0.95^k of the time)."""
    from scipy.stats import t as student_t

    rng = np.random.default_rng(70 + k)
    draws = rng.normal(1.0, 0.1, (6000, k))
    c = student_t.ppf(0.95, k - 1) * math.sqrt(1 + 1 / k)
    bounds = draws.mean(axis=1) + c * draws.std(axis=1, ddof=1)
    est = [prediction_bound_se(k, float(np.std(d, ddof=1))) for d in draws]
    assert np.mean(est) == pytest.approx(float(np.std(bounds, ddof=1)), rel=0.03)


def test_no_standard_error_where_the_gate_is_not_the_bound():
    assert gate_standard_error([0.3]) is None                       # one member: the gate is it
    assert gate_standard_error([0.2, 0.2, 0.2]) is None             # no spread
    assert gate_standard_error([0.01, 0.012, 0.011, 0.013]) is None  # the floor (0.1) sets the gate


def test_the_margin_and_its_words():
    m = gate_margin(0.502, 0.406, 0.1)
    assert m["margin"] == pytest.approx(0.096) and m["within_one_se"]
    assert "within one standard error" in _margin_text("before", m) and "above" in _margin_text("before", m)
    far = gate_margin(0.961, 0.236, 0.05)
    assert not far["within_one_se"] and "within" not in _margin_text("before", far)
    assert "14.50 of them" in _margin_text("before", far)
    inside = gate_margin(0.3, 0.45, 0.2)
    assert inside["within_one_se"] and "inside" in _margin_text("after", inside)
    given = gate_margin(0.5, 0.3, None)     # a gate the user gave: no standard error, no words
    assert not given["within_one_se"] and _margin_text("before", given) is None
    assert not gate_margin(float("inf"), 0.3, 0.1)["within_one_se"]
    assert math.isnan(gate_margin(float("nan"), 0.3, 0.1)["margin"])


def test_a_later_step_states_its_margin():
    from rotorlanding.diagnose_run import _step_lines

    steps = [{"gate_margin": gate_margin(0.9, 0.3, 0.05), "named": "windage"},
             {"gate_margin": gate_margin(0.266, 0.244, 0.05), "named": None},
             {"gate_margin": gate_margin(0.266, 0.244, None), "named": None}]
    lines = _step_lines(steps)
    # the first step's margin is the report's "gap before" line; the second's is within one SE;
    # the third's gate has no standard error (a given gate): nothing said
    assert len(lines) == 1 and lines[0].startswith("Step 2: the gap it started from 0.266 is 0.022 above the gate 0.244")
    assert "within one standard error" in lines[0]
