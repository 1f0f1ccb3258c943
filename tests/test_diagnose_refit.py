"""Issue 20, point 5: two missing effects of similar size, found by forward selection with a joint
re-fit of everything named so far. Data from our own sensor model (tests/sensor_model.py)."""

import math
import sys
from pathlib import Path

import pytest

from rotorlanding.diagnose_run import _simulate_features, diagnose, measured_for_diagnosis
from rotorlanding.features import gap

sys.path.insert(0, str(Path(__file__).parent))
from sensor_model import C, THRUST, known_rig_model, write_record  # noqa: E402

TRUTH = ["effects.axial_rub=true", "contact.mu_ax=0.3", "effects.outer_race_coulomb=true", "bearings.NDE.mu_d=0.3"]


def test_axial_rub_and_outer_race_coulomb_both_named_after_a_joint_refit(tmp_path):
    """The issue's failed pair: greedy, mu_ax froze after step one and the second effect changed
    nothing (1.035 -> 1.041). Measured here (0.3 s, thrust 4 kN): step one fits mu_ax = 0.42 alone
    (gap 2.82 -> 1.11); outer-race friction on top with mu_ax held gives 0.72, the joint re-fit
    0.33 (mu_ax 0.275, mu_d 0.39; truth 0.3 / 0.3). Since session 50 (the race's lag a feature) the
    model is 4 drops per variant, as recommended for one record: with one drop step one fitted mu_ax
    0.254 (gap 0.51) and the one round of coordinate descent stayed in a local minimum (mu_d 0.074,
    gap 0.455) where the truth gives 0.057, a one-drop needle landscape (docs/measured_data.md,
    session 50). With 4 drops: 2.83 -> 0.53 -> 0.26 (mu_d 0.39)."""
    model = known_rig_model(tmp_path / "model.toml", ["axial_rub", "outer_race_coulomb"], extra=THRUST)
    csv = tmp_path / "rig.csv"
    write_record(model, TRUTH, csv, clearance=C, seed=7)
    _, m, meas, info = measured_for_diagnosis(model, csv, [], None)
    res = diagnose(meas, model, clearance=C, candidates=["axial_rub", "outer_race_coulomb"], parameters=[],
                   workers=2, maxiter=5, info=info, max_effects=2, ensemble=4)
    assert set(res["named_effects"]) == {"axial_rub", "outer_race_coulomb"}, res["steps"]
    assert res["gap_after"] <= 0.5 * res["gap_before"]
    refit = res["steps"][1]["refit"]
    # the re-fit moved the first effect's value and took the gap well below the greedy step's
    assert refit["gap_after_refit"] <= 0.7 * refit["gap_before_refit"]
    assert refit["values"]["axial_rub"]["mu_ax"] != res["steps"][0]["candidates"][0]["parameters"]["mu_ax"]
    # independent yardstick: the model with the true values against the same data
    reachable, _ = gap(meas, _simulate_features(model, TRUTH, C))
    assert res["gap_after"] <= max(reachable, res["noise_gate_final"])
    assert res["explanation"] == "effect" and not res["unexplained"]


def test_every_parameter_of_an_effect_is_calibrated_jointly():
    """Issue 20, point 4: an effect with two parameters (the worn-bearing drag: its torque and the
    rotation over which it develops) gets both fitted within their bounds, and the score charges
    both. A smooth, separable gap stands in for the landings, so the search itself is what is
    tested: the minimum of sqrt(ln(T/1.7)^2 + ln(phi/90)^2) lies inside both bounds."""
    import math
    from pathlib import Path

    from rotorlanding.diagnose_run import Point, _calibrate

    root = Path(__file__).resolve().parents[1]

    class FakeSim:
        scenario_path = str(root / "scenarios" / "paper" / "backward_whirl_landing.toml")
        points = [Point("p", [])]

        def overrides(self, p, extra):
            return list(extra)

        def gap(self, extra):
            vals = {}
            for o in extra:
                k, _, v = o.partition("=")
                if k.endswith("worn_drag_torque"):
                    vals["T"] = float(v)
                elif k.endswith("worn_drag_growth_angle"):
                    vals["phi"] = float(v)
            g = math.hypot(math.log(vals.get("T", 3.41) / 1.7), math.log(vals.get("phi", 144.7) / 90.0))
            return g, [{"feature": "f", "distance": g, "weight": 1.0}], [{"whirl_direction": ("backward", None)}], None

        def gaps(self, extras):
            return [self.gap(e) for e in extras]

    r = _calibrate(FakeSim(), "worn_bearing_drag", [], maxiter=20)
    assert r["k"] == 2
    assert r["parameters"]["worn_drag_torque"] == pytest.approx(1.7, rel=0.02)
    assert r["parameters"]["worn_drag_growth_angle"] == pytest.approx(90.0, rel=0.03)
    assert r["gap"] < 0.03
    assert sorted(o.split("=")[0] for o in r["term"].overrides()) == sorted([
        "effects.worn_bearing_drag", "bearings.DE.worn_drag_torque", "bearings.NDE.worn_drag_torque",
        "bearings.DE.worn_drag_growth_angle", "bearings.NDE.worn_drag_growth_angle"])


def test_each_candidate_is_refitted_with_what_was_named_before_it_is_ranked():
    """Forward stepwise selection fits every candidate model with all its numbers. The bench's
    axial rub + outer-race friction pair (4 records) showed why the best alone is not enough:
    mu_ax, fitted alone at step one, had taken up part of the friction, so outer-race friction on
    top of the held mu_ax made the gap worse and a parameter won the step. A smooth stand-in for
    the landings with that structure: rows a + b - 0.4 (what both frictions do) and a - 0.2 (the
    face rub alone); truth a = b = 0.2. a alone fits 0.3 (gap 0.141), b beside the held a fits 0.1
    (gap 0.1); one round of the joint re-fit (a given b, then b given a) gives 0.25 / 0.15, gap 0.05."""
    from rotorlanding.diagnose_run import Point, _calibrate, _joint_refit
    from rotorlanding.effects import CATALOGUE

    root = Path(__file__).resolve().parents[1]
    calls = []

    class FakeSim:
        scenario_path = str(root / "scenarios" / "paper" / "forward_whirl_landing.toml")
        points = [Point("p", [])]
        pool = None

        def overrides(self, p, extra):
            return list(extra)

        def gap(self, extra):
            calls.append(extra)
            vals = {k: float(v) for k, _, v in (o.partition("=") for o in extra) if not k.startswith("effects.")}
            a = vals.get("contact.mu_ax", 0.3) if "effects.axial_rub=true" in extra else 0.0
            b = vals.get("bearings.NDE.mu_d", 0.3) if "effects.outer_race_coulomb=true" in extra else 0.0
            g = math.hypot(a + b - 0.4, a - 0.2)
            return g, [{"feature": "f", "distance": g, "weight": 1.0}], [{"whirl_direction": ("forward", None)}], None

        def gaps(self, extras):
            return [self.gap(e) for e in extras]

    sim = FakeSim()
    first = _calibrate(sim, "axial_rub", [], maxiter=20)
    assert first["parameters"]["mu_ax"] == pytest.approx(0.3, abs=0.005)   # takes up the missing friction
    named = [first["term"]]
    greedy = _calibrate(sim, "outer_race_coulomb", named, maxiter=20)
    assert greedy["parameters"]["mu_d"] == pytest.approx(0.1, abs=0.005)
    assert greedy["gap"] == pytest.approx(0.1, abs=0.005)
    _joint_refit(sim, named, greedy, maxiter=20)
    assert greedy["refit"]["gap_before_refit"] == pytest.approx(0.1, abs=0.005)
    assert greedy["gap"] == greedy["refit"]["gap_after_refit"] == pytest.approx(0.05, abs=0.005)
    assert greedy["refit_terms"][0].values["mu_ax"] == pytest.approx(0.25, abs=0.005)
    assert greedy["parameters"]["mu_d"] == pytest.approx(0.15, abs=0.005)
    # what was named stays as it was: the candidate works on copies
    assert named[0].values["mu_ax"] == first["parameters"]["mu_ax"]
    assert CATALOGUE["outer_race_coulomb"].parameters[0].name in greedy["parameters"]
