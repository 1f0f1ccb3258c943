"""Issue 20, point 1: a calibration that reports its own uncertainty. diagnose_run.fit_span: the
values a 1-D fit evaluated whose gap is within z standard deviations of the noise members' gaps
above the best one, in ranges of neighbours; several ranges are separate dips (a needle landscape)."""

import math

import numpy as np
import pytest

from rotorlanding import diagnose_run as d


def _cache(xs, gaps, log=False):
    return {(math.log10(x) if log else x): (g, [], x, []) for x, g in zip(xs, gaps)}


MEMBERS = [0.20, 0.25, 0.30, 0.35]   # standard deviation 0.0645: margin 2 x 0.0645 = 0.129


def test_a_v_shaped_gap_gives_one_range_around_its_minimum():
    xs = np.arange(1.0, 10.0)
    sp = d.fit_span(_cache(xs, 0.2 + 0.1 * abs(xs - 5.0)), MEMBERS)
    assert sp["margin"] == pytest.approx(2.0 * np.std(MEMBERS, ddof=1))
    assert sp["best"] == 5.0 and sp["gap"] == pytest.approx(0.2)
    assert sp["ranges"] == [[4.0, 6.0]] and (sp["within"], sp["evaluated"]) == (3, 9)
    assert sp["brackets"] == [[3.0, 7.0]]    # up to the nearest values that fit worse
    assert not sp["open_low"] and not sp["open_high"]
    # twice the members' scatter: twice as wide
    wide = d.fit_span(_cache(xs, 0.2 + 0.1 * abs(xs - 5.0)), [2 * g for g in MEMBERS])
    assert wide["ranges"] == [[3.0, 7.0]]


def test_separate_dips_are_separate_ranges_and_said_so():
    """The four-record bench's mu_rad 0.3 (docs/studies/diagnose_param_scan/): dips at 0.19, 0.25
    and 0.31 with the gap 1.4-1.6 between them."""
    xs = [0.17, 0.19, 0.21, 0.23, 0.25, 0.27, 0.29, 0.31, 0.33]
    gaps = [1.54, 1.16, 1.52, 1.54, 1.21, 1.51, 1.41, 1.16, 1.54]
    sp = d.fit_span(_cache(xs, gaps), [0.10, 0.15, 0.20, 0.25])
    assert sp["ranges"] == [[0.19, 0.19], [0.25, 0.25], [0.31, 0.31]]
    assert sp["brackets"] == [[0.17, 0.21], [0.23, 0.27], [0.29, 0.33]]
    sp["parameter"], sp["keys"] = "mu_rad", ["contact.mu_rad"]
    text = d._span_text(sp)
    assert text.startswith("contact.mu_rad, fitted on its own")
    assert "3 separate dips" in text and "0.19, 0.25, 0.31" in text and "do not fix the value" in text


def test_ranges_are_in_the_parameters_values_and_open_at_a_bound():
    """A log parameter's cache is keyed by log10 of the value; the ranges are values. A minimum at
    the lowest value evaluated is open there: the data would allow less."""
    xs = [1e11, 1e12, 1e13, 1e14]
    sp = d.fit_span(_cache(xs, [0.30, 0.35, 0.9, 1.2], log=True), MEMBERS)
    assert sp["ranges"] == [[1e11, 1e12]] and sp["open_low"] and not sp["open_high"]
    assert sp["brackets"] == [[1e11, 1e13]]  # the bound itself at the open end
    assert "open at the lowest value evaluated" in d._span_text({**sp, "parameter": "contact.k_visc"})


def test_no_span_without_members_or_values_and_failed_landings_left_out():
    xs = [1.0, 2.0, 3.0]
    assert d.fit_span(_cache(xs, [0.5, 0.2, 0.6]), [0.3]) is None              # one member: no scatter
    assert d.fit_span(_cache(xs, [0.5, math.inf, math.inf]), MEMBERS) is None  # one finite gap
    sp = d.fit_span(_cache(xs, [0.25, math.inf, 0.3]), MEMBERS)
    assert sp["evaluated"] == 2 and sp["ranges"] == [[1.0, 3.0]]              # the failed one is no break


def test_the_bench_checks_whether_the_span_holds_the_true_value():
    """benchmarks/diagnose_bench.span_covers: per named step whose parameter the case set, whether
    the truth lies in the fit's span (the coverage of the reported uncertainty, judged on the bench)."""
    import sys
    from pathlib import Path

    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))
    import diagnose_bench as bench

    case = {"sets": ["effects.windage=true", "spin.c_w2=1.5e-06"]}
    step = {"named": "windage", "fit_span": {"parameter": "c_w2", "keys": ["spin.c_w2"], "best": 1.4e-6,
                                             "ranges": [[1.2e-6, 1.6e-6]]}}
    assert bench.span_covers(case, {"steps": [step, {"named": None}]}) == "yes"
    step["fit_span"]["ranges"] = [[1e-7, 1.2e-6], [1.7e-6, 2e-6]]
    assert bench.span_covers(case, {"steps": [step]}) == "no"
    step["fit_span"]["brackets"] = [[5e-8, 1.3e-6], [1.6e-6, 2.1e-6]]
    assert bench.span_covers(case, {"steps": [step]}) == "no"
    step["fit_span"]["brackets"] = [[5e-8, 1.55e-6], [1.6e-6, 2.1e-6]]
    assert bench.span_covers(case, {"steps": [step]}) == "bracket"       # not ruled out
    assert bench.span_covers({"sets": ["effects.windage=false"]}, {"steps": [step]}) == "-"
    assert bench.span_covers(case, {"steps": [{**step, "named": None}]}) == "-"   # not named: not judged
