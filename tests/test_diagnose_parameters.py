"""Issue 20, point 3: "is my model missing something, or did I get a number wrong?" The scenario's
uncertain parameters ([bounds] of the rig files) are candidates as well as the missing effects.
Data from our own sensor model (tests/sensor_model.py)."""

import sys
from pathlib import Path

import pytest

from rotorlanding.diagnose_run import diagnose, measured_for_diagnosis

sys.path.insert(0, str(Path(__file__).parent))
from sensor_model import C, known_rig_model, write_record  # noqa: E402



@pytest.fixture(scope="module")
def heavy_hub(tmp_path_factory):
    """The rig's coupling hub is 7 kg where the model has 4 kg (inside its sourced bound 1-8 kg);
    nothing else differs. The model also lacks windage and ribbon cross-coupling (candidates)."""
    d = tmp_path_factory.mktemp("hub")
    model = known_rig_model(d / "model.toml", ["windage", "ribbon_cross_coupling"])
    write_record(model, ["rotor.disks.3.mass=7.0"], d / "rig.csv", clearance=C, seed=11)
    _, m, meas, info = measured_for_diagnosis(model, d / "rig.csv", [], None)
    return model, meas, info, d


def test_a_wrong_mass_is_reported_as_a_wrong_parameter_not_a_missing_effect(heavy_hub, tmp_path):
    """Measured: gap 1.15 -> 0.07 with the hub at 7.06 kg; the best effect (ribbon cross-coupling,
    the issue's wrong answer for a heavier hub) only reaches 1.03. The report gives the fit's own
    uncertainty: the masses evaluated that fit within the noise members' scatter of the best."""
    from rotorlanding.diagnose_run import write_report

    model, meas, info, d = heavy_hub
    res = diagnose(meas, model, clearance=C, candidates=["windage", "ribbon_cross_coupling"], workers=2,
                   maxiter=5, info=info, ensemble=1)
    assert res["named_effect"] is None and res["explanation"] == "parameter", res["steps"]
    (q,) = res["named_parameters"]
    assert q["key"] == "rotor.disks.3.mass" and q["from"] == 4.0 and q["to"] == pytest.approx(7.0, rel=0.15)
    assert q["bound"] == [1.0, 8.0] and "coupling" in q["source"]
    assert res["gap_after"] <= 0.5 * res["gap_before"] and not res["unexplained"]
    effects = [c for c in res["steps"][0]["candidates"] if c["kind"] == "effect"]
    assert min(c["gap"] for c in effects) > 2 * res["gap_after"]
    span = res["steps"][0]["fit_span"]
    assert span["keys"] == ["rotor.disks.3.mass"] and span["best"] == q["to"]
    assert any(lo <= q["to"] <= hi for lo, hi in span["ranges"]) and span["evaluated"] >= 9
    assert span["margin"] > 0 and span["within"] < span["evaluated"]   # the data do rule masses out
    write_report(res, tmp_path, None, model, C)
    assert "rotor.disks.3.mass, fitted on its own: the values within 2 x" in (tmp_path / "report.md").read_text()


def test_without_the_right_candidate_the_report_says_unexplained(heavy_hub, tmp_path):
    """The same data with no parameter candidates: no effect explains it, and the report says the
    gap stays unexplained and where it is largest, instead of naming the nearest effect."""
    from rotorlanding.diagnose_run import write_report

    model, meas, info, d = heavy_hub
    res = diagnose(meas, model, clearance=C, candidates=["windage", "ribbon_cross_coupling"], parameters=[],
                   workers=2, maxiter=5, info=info, ensemble=1)
    assert res["named_effect"] is None and res["named_parameters"] == []
    assert res["unexplained"] and res["explanation"] == "unexplained"
    assert res["gap_after"] == res["gap_before"] > res["noise_gate_final"]
    assert len(res["largest_remaining"]) == 3
    write_report(res, tmp_path, None, model, C)
    md = (tmp_path / "report.md").read_text()
    assert "**Unexplained**" in md and res["largest_remaining"][0]["feature"] in md


def test_a_larger_clearance_is_found_as_the_wrong_parameter(tmp_path):
    """DE clearance 2.6e-4 m on the rig, 2e-4 in the model (the issue: 'rightly not named, but
    nothing told the user what does explain' it). Measured: named bearings.DE.clearance 2e-4 ->
    2.5e-4 m, gap 1.84 -> 0.56; screened only at its bounds or on a 5-point grid it was missed
    (its gap is a V 0.3e-4 wide: 1.84 at 2e-4, 0.09 at 2.6e-4, 1.86 at 3e-4)."""
    model = known_rig_model(tmp_path / "model.toml", ["windage", "ribbon_cross_coupling"])
    write_record(model, ["bearings.DE.clearance=2.6e-4"], tmp_path / "rig.csv", clearance=C, seed=11)
    _, m, meas, info = measured_for_diagnosis(model, tmp_path / "rig.csv", [], None)
    res = diagnose(meas, model, clearance=C, candidates=["windage", "ribbon_cross_coupling"], workers=2,
                   maxiter=5, info=info, ensemble=1)
    assert res["named_effect"] is None and res["explanation"] == "parameter", res["steps"]
    (q,) = res["named_parameters"]
    assert q["key"] == "bearings.DE.clearance" and q["to"] == pytest.approx(2.6e-4, rel=0.1)
    assert res["gap_after"] <= 0.5 * res["gap_before"]
