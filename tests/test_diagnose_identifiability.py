"""Issue 20, point 8: before calibrating, diagnose says which candidates the channels given can
tell apart (rotorlanding/identifiability.py), and its probes cost no landing of their own."""

import math
import sys
from pathlib import Path

import numpy as np
import pytest

from rotorlanding.diagnose_run import _Simulator, diagnose
from rotorlanding.identifiability import assess, correlation, signature

sys.path.insert(0, str(Path(__file__).parent))
from sensor_model import known_rig_model  # noqa: E402

C = 2e-4
# two features with their scales: a rebound [m] and a deceleration [rpm/s]
BASE = {"DE_first_rebound_m": (1.0e-4, 1.0e-5), "rotor_deceleration_rpm_s": (-100.0, 10.0)}


def _moved(rebound_scales=0.0, decel_scales=0.0):
    return {"DE_first_rebound_m": (1.0e-4 + rebound_scales * 1.0e-5, 1.0e-5),
            "rotor_deceleration_rpm_s": (-100.0 + decel_scales * 10.0, 10.0)}


def _probe(name, kind, cand):
    change, sig = signature([BASE], [cand], [BASE])
    return {"name": name, "kind": kind, "at": {}, "change": change, "signature": sig}


def test_signature_is_the_gap_with_signs():
    change, sig = signature([BASE], [_moved(0.5, -0.3)], [BASE])
    # distances of 0.5 and 0.3 scales (soft cap ~1 below 1 scale), signed by the direction of the change
    assert sig["DE_first_rebound_m"] == pytest.approx(0.5, rel=1e-3)
    assert sig["rotor_deceleration_rpm_s"] == pytest.approx(-0.3, rel=1e-3)
    assert change == pytest.approx(math.sqrt((0.5 ** 2 + 0.3 ** 2) / 2), rel=1e-3)
    # only the features the measurement has
    _, sig = signature([BASE], [_moved(0.5, -0.3)], [{"DE_first_rebound_m": BASE["DE_first_rebound_m"]}])
    assert set(sig) == {"DE_first_rebound_m"}


def test_parallel_signatures_flagged_orthogonal_told_apart_weak_unseen():
    probes = [_probe("a", "effect", _moved(rebound_scales=2.0)),
              _probe("b", "effect", _moved(rebound_scales=0.8)),    # a's direction, weaker
              _probe("c", "effect", _moved(decel_scales=2.0)),      # another feature
              _probe("d", "effect", _moved(decel_scales=0.05))]     # below the gate
    r = assess(probes, gate=0.3, gap_before=1.5)
    seen = {c["name"]: c["detectable"] for c in r["candidates"]}
    assert seen == {"a": True, "b": True, "c": True, "d": False}
    pairs = {(q["a"], q["b"]): q for q in r["pairs"]}
    assert set(pairs) == {("a", "b"), ("a", "c"), ("b", "c")}   # d is not judged
    assert pairs[("a", "b")]["correlation"] == pytest.approx(1.0)
    assert not pairs[("a", "b")]["told_apart"] and pairs[("a", "c")]["told_apart"]
    assert len(r["warnings"]) == 1 and "a and b cannot be told apart" in r["warnings"][0]
    # the gap inside the gate: nothing to tell apart, no pairs, said so
    quiet = assess(probes, gate=0.3, gap_before=0.2)
    assert quiet["pairs"] == [] and quiet["warnings"] == [] and "inside the noise gate" in quiet["note"]


def test_the_remainder_is_what_a_least_squares_fit_of_the_other_leaves():
    """Independent computation: the data = a signature scaled to the gap's size; the other
    candidate's strength fitted to it by least squares (numpy) leaves the remainder assess states."""
    a = _probe("a", "effect", _moved(0.9, 0.2))
    b = _probe("b", "effect", _moved(0.4, 0.6))
    gap_before, gate = 1.2, 0.01
    keys = sorted(a["signature"])
    va = np.array([a["signature"][k] for k in keys])
    vb = np.array([b["signature"][k] for k in keys])
    data = va / np.sqrt(np.mean(va ** 2)) * gap_before          # RMS = the gap
    t, *_ = np.linalg.lstsq(vb[:, None], data, rcond=None)
    left = float(np.sqrt(np.mean((data - t[0] * vb) ** 2)))
    (pair,) = assess([a, b], gate=gate, gap_before=gap_before)["pairs"]
    assert pair["remainder"] == pytest.approx(left, rel=1e-9)
    assert pair["correlation"] == pytest.approx(correlation(a["signature"], b["signature"]))


def test_opposite_effects_told_apart_by_sign_a_parameter_either_way():
    up, down = _moved(rebound_scales=2.0), _moved(rebound_scales=-2.0)
    effects = assess([_probe("e1", "effect", up), _probe("e2", "effect", down)], gate=0.3, gap_before=1.5)
    assert effects["pairs"][0]["correlation"] == pytest.approx(-1.0) and effects["pairs"][0]["told_apart"]
    # a wrong parameter may be too high or too low: the same two signatures are then one direction
    mixed = assess([_probe("e1", "effect", up), _probe("p", "parameter", down)], gate=0.3, gap_before=1.5)
    assert not mixed["pairs"][0]["told_apart"]


def test_simulator_memo_lands_each_noise_free_variant_once():
    sim = object.__new__(_Simulator)
    sim.memo, landed = {}, []

    def land(extras, noise, single):
        landed.append([list(e) for e in extras])
        return [[{"v": (len(e), None)}] for e in extras]

    sim._land = land
    out = sim.features([["x=1"], ["y=2"], ["x=1"]])
    assert landed == [[["x=1"], ["y=2"]]] and out[0] == out[2]
    sim.features([["y=2"]])
    assert len(landed) == 1                                      # nothing new to land
    sim.features([["y=2"]], noise={"DE_z_m": 1e-6})              # noisy members are drawn anew
    assert len(landed) == 2


def test_windage_and_ball_drag_told_apart_before_calibrating(tmp_path):
    """The issue's new-user round: windage and ball drag were never confused. The report says so
    before the calibration, its probes add no landing (the same count with and without them:
    every probe is a landing step one's grid or screening makes), and names which rows carry each."""
    from rotorlanding.benchdata import make_hidden_effect_data
    from rotorlanding.features import extract_features
    from rotorlanding.measured import detect_drop, load_measurement

    model = known_rig_model(tmp_path / "model.toml", ["windage", "ball_drag"])
    make_hidden_effect_data(model, "windage", tmp_path / "rig.csv", seed=3, value=1.2e-6, drop_channel="NDE_y_m")
    m = load_measurement(tmp_path / "rig.csv")
    feats = extract_features(m.shifted(detect_drop(m, C)), clearance=C)
    res = diagnose(feats, model, clearance=C, candidates=["windage", "ball_drag"], parameters=[], workers=2, maxiter=2)
    ident = res["identifiability"]
    by = {c["name"]: c for c in ident["candidates"]}
    assert by["windage"]["detectable"] and by["ball_drag"]["detectable"]
    assert by["windage"]["features"][0]["feature"] == "rotor_deceleration_rpm_s"
    (pair,) = ident["pairs"]
    assert pair["told_apart"] and not ident["warnings"]
    assert res["named_effect"] == "windage"

    import rotorlanding.diagnose_run as dr

    real = dr._identifiability
    try:
        dr._identifiability = lambda *a, **k: {"warnings": []}
        bare = diagnose(feats, model, clearance=C, candidates=["windage", "ball_drag"], parameters=[], workers=2,
                        maxiter=2)
    finally:
        dr._identifiability = real
    assert bare["simulations"] == res["simulations"] and bare["gap_after"] == res["gap_after"]


def test_many_alike_pairs_are_one_warning():
    """A gap just above the gate leaves almost nothing to tell apart: one warning that says why,
    with the correlation limit sqrt(1 - (gate / gap)^2), not one line per pair."""
    probes = [_probe(f"p{i}", "parameter", _moved(1.0 + 0.3 * i, 0.2 * i)) for i in range(5)]
    r = assess(probes, gate=0.3, gap_before=0.31)
    assert r["correlation_limit"] == pytest.approx(math.sqrt(1 - (0.3 / 0.31) ** 2))
    flagged = [q for q in r["pairs"] if not q["told_apart"]]
    assert len(flagged) > 3 and len(r["warnings"]) == 1 and f"{len(flagged)} of 10 pairs" in r["warnings"][0]
    assert all(abs(q["correlation"]) > r["correlation_limit"] for q in flagged)


def test_alike_with_lists_the_pairs_not_told_apart():
    from rotorlanding.identifiability import alike_with

    probes = [_probe("a", "effect", _moved(rebound_scales=2.0)), _probe("b", "effect", _moved(rebound_scales=0.8)),
              _probe("c", "effect", _moved(decel_scales=2.0))]
    r = assess(probes, gate=0.3, gap_before=1.5)
    assert [o["other"] for o in alike_with(r, "a")] == ["b"] and alike_with(r, "c") == []
    assert alike_with(None, "a") == []


def test_a_parameter_probe_stands_on_the_screening_point_that_landed():
    """One screening point fails to land (a solver failure at that value), the other lands: the
    candidate is judged on the one that landed, not reported as failed."""
    from types import SimpleNamespace

    from rotorlanding.diagnose_run import Point, _identifiability

    key = "contact.mu_rad"

    class FakeSim:
        points = [Point("", [], BASE)]

        def features(self, extras):
            # screening points 0.15 -/+ a quarter of the span 0.05-0.5, lower first: the upper fails
            return [[{"__error__": "SolverError"}] if float(e[0].split("=")[1]) > 0.15 else [_moved(2.0, 0.0)]
                    for e in extras]

    base = SimpleNamespace(bounds={key: SimpleNamespace(min=0.05, max=0.5, log=False)})
    r = _identifiability(FakeSim(), [BASE], base, [], [key], {key: 0.15}, gate=0.3, gap_before=1.5)
    (c,) = r["candidates"]
    assert "failed" not in c and c["detectable"] and c["at"][key] < 0.15
