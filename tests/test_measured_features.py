"""Measured data in (CSV, .mat, results.h5, feature tables) and discrepancy features / gap."""

import json
from pathlib import Path

import numpy as np
import pytest

from rotorlanding.errors import InputError
from rotorlanding.features import extract_features, gap
from rotorlanding.measured import Measurement, detect_drop, load_measurement

C = 2e-4


def _synthetic(f_whirl=65.0, onset=0.4, t_end=1.2, fs=5000.0, drop_at=0.0, sense=1.0):
    t = np.arange(0, t_end, 1 / fs)
    y = np.zeros_like(t)
    # levitated, then free fall onto the race (z = -g t^2 / 2 until the clearance is used up)
    z = np.maximum(-0.5 * 9.80665 * np.clip(t - drop_at, 0, None) ** 2, -C)
    on = t >= drop_at + onset
    ph = sense * 2 * np.pi * f_whirl * (t[on] - drop_at - onset)
    y[on], z[on] = C * np.cos(ph - np.pi / 2), C * np.sin(ph - np.pi / 2)
    rotor = 7000 - 100 * np.clip(t - drop_at, 0, None)
    race = np.minimum(rotor, 30000 * np.clip(t - drop_at, 0, None))
    return t, y, z, rotor, race


def test_csv_with_offset_different_sampling_noise_and_missing_channel(tmp_path):
    t, y, z, rotor, race = _synthetic(drop_at=0.3)
    rng = np.random.default_rng(0)
    z_noisy = z + rng.normal(0, 0.03 * C, z.size)
    speed = np.full_like(t, np.nan)
    speed[::10] = rotor[::10]  # slower speed channel
    f = tmp_path / "rig.csv"
    np.savetxt(f, np.column_stack([t + 12.0, y, z_noisy, speed]), delimiter=",",
               header="time_s,DE_y_m,DE_z_m,rotor_speed_rpm", comments="")
    m = load_measurement(f, time_offset_s=12.0)
    assert set(m.channels) == {"DE_y_m", "DE_z_m", "rotor_speed_rpm"}
    assert len(m.series("rotor_speed_rpm")[0]) == pytest.approx(len(t) / 10, abs=1)
    assert detect_drop(m, C) == pytest.approx(0.3, abs=2e-3)
    feats = extract_features(m, clearance=C, t_drop=0.3)
    assert feats["whirl_direction"][0] == "forward"
    assert feats["whirl_frequency_hz"][0] == pytest.approx(65.0, abs=0.5)
    assert feats["whirl_onset_s"][0] == pytest.approx(0.4, abs=0.03)
    assert feats["rotor_deceleration_rpm_s"][0] == pytest.approx(100.0, rel=0.05)


def test_gap_is_zero_for_itself_and_grows_with_the_difference():
    t, y, z, rotor, race = _synthetic()
    base = Measurement({"DE_y_m": (t, y), "DE_z_m": (t, z), "rotor_speed_rpm": (t, rotor),
                        "DE_inner_race_speed_rpm": (t, race)})
    fa = extract_features(base, clearance=C)
    g0, rows = gap(fa, fa)
    assert g0 == 0.0 and len(rows) >= 8
    gaps = []
    for f_w in (60.0, 50.0):
        t2, y2, z2, *_ = _synthetic(f_whirl=f_w)
        other = Measurement({"DE_y_m": (t2, y2), "DE_z_m": (t2, z2), "rotor_speed_rpm": (t, rotor),
                             "DE_inner_race_speed_rpm": (t, race)})
        gaps.append(gap(fa, extract_features(other, clearance=C))[0])
    assert 0 < gaps[0] < gaps[1]
    # a backward whirl: the measured (forward) whirl is not reproduced, so direction, frequency and
    # onset each count the mismatch distance 3, the largest any feature can reach
    t3, y3, z3, *_ = _synthetic(sense=-1.0)
    back = Measurement({"DE_y_m": (t3, y3), "DE_z_m": (t3, z3), "rotor_speed_rpm": (t, rotor)})
    fb = extract_features(back, clearance=C)
    assert fb["whirl_direction"][0] == "backward"
    g, rows = gap(fa, fb)
    d = {r["feature"]: r["distance"] for r in rows}
    assert d["whirl_direction"] == d["whirl_frequency_hz"] == d["whirl_onset_s"] == 3.0
    assert max(d.values()) == 3.0 and g >= 3.0 * np.sqrt(3 / len(rows))


def test_mat_and_feature_table_and_bad_files(tmp_path):
    from scipy.io import savemat

    t, y, z, rotor, race = _synthetic()
    savemat(tmp_path / "d.mat", {"time_s": t, "DE_y_m": y, "DE_z_m": z})
    m = load_measurement(tmp_path / "d.mat")
    assert m.has("DE_z_m") and not m.has("rotor_speed_rpm")
    (tmp_path / "f.json").write_text(json.dumps({"features": {"whirl_frequency_hz": 65.0}}))
    assert load_measurement(tmp_path / "f.json").features["whirl_frequency_hz"] == 65.0
    (tmp_path / "bad.csv").write_text("time_s,DE_q_m\n0,1\n1,2\n")
    with pytest.raises(InputError, match="DE_q_m"):
        load_measurement(tmp_path / "bad.csv")
    with pytest.raises(InputError, match="file not found"):
        load_measurement(tmp_path / "none.csv")


def test_results_file_is_measured_data(tmp_path):
    from rotorlanding.cli import main

    root = Path(__file__).resolve().parents[1]
    out = tmp_path / "r"
    assert main(["run", str(root / "scenarios" / "landing_7000rpm.toml"), "--out", str(out), "--t-end", "0.05",
                 "--quiet", "--no-plots"]) == 0
    m = load_measurement(out / "results.h5")
    assert {"DE_y_m", "DE_z_m", "rotor_speed_rpm", "DE_force_z_n", "axial_m", "DE_housing_force_z_n",
            "NDE_housing_force_y_n"} <= set(m.channels)
    assert detect_drop(m, C) == pytest.approx(0.0, abs=1e-3)
    f = extract_features(m, clearance=C)
    assert f["DE_vertical_min_m"][0] < -0.9 * C and f["DE_force_peak_n"][0] > 500
    # the load cell's reading: the impact passes the race and the ribbon, so it is near the contact peak
    assert f["DE_housing_force_peak_n"][0] == pytest.approx(f["DE_force_peak_n"][0], rel=0.25)


def test_distances_are_bounded_by_the_direction_mismatch():
    from rotorlanding.features import MAX_DISTANCE, soft_cap

    assert soft_cap(1.0) == pytest.approx(1.0, rel=0.005) and soft_cap(2.0) == pytest.approx(1.91, abs=0.01)
    assert soft_cap(6.0) < soft_cap(60.0) < MAX_DISTANCE == 3.0
    m = {"whirl_direction": ("forward", None), "whirl_frequency_hz": (65.0, 2.0)}
    # the right direction at a wrong frequency is closer than no whirl at all
    g_far, _ = gap(m, {"whirl_direction": ("forward", None), "whirl_frequency_hz": (90.0, 2.7)})
    g_none, rows = gap(m, {"whirl_direction": ("none", None)})
    assert g_far < g_none == 3.0 and [r["feature"] for r in rows] == ["whirl_direction", "whirl_frequency_hz"]


def test_table_scales_follow_the_extraction_rules():
    from rotorlanding.features import FEATURE_UNITS, OTHER_JOURNAL_ROWS, scale_of

    t, y, z, rotor, race = _synthetic()
    fz = np.where(z <= -C, 3000.0, 0.0)
    chans = {"rotor_speed_rpm": (t, rotor), "axial_m": (t, 1e-5 * np.sin(t))}
    for b in ("DE", "NDE"):
        chans.update({f"{b}_y_m": (t, y), f"{b}_z_m": (t, z), f"{b}_inner_race_speed_rpm": (t, race),
                      f"{b}_force_y_n": (t, 0 * t), f"{b}_force_z_n": (t, fz),
                      f"{b}_housing_force_y_n": (t, 0 * t), f"{b}_housing_force_z_n": (t, 0.9 * fz)})
    f = extract_features(Measurement(chans), clearance=C)
    assert set(f) == set(FEATURE_UNITS) - {"DE_first_rebound_m"}
    # every channel gives its features (issue 20, point 7): the NDE rows equal the DE rows of the same
    # signals, and a record without NDE channels gives no NDE rows (not a charge)
    nde = {k for k in f if k.startswith("NDE_")}
    assert nde == {"NDE_" + k for k in OTHER_JOURNAL_ROWS}
    assert all(f[k] == f["DE" + k[3:]] for k in nde)
    de_only = extract_features(Measurement({k: v for k, v in chans.items() if not k.startswith("NDE")}), clearance=C)
    assert de_only == {k: v for k, v in f.items() if not k.startswith("NDE")}
    peak, housing_peak = f["DE_force_peak_n"][0], f["DE_housing_force_peak_n"][0]
    assert housing_peak == pytest.approx(0.9 * peak)   # each force channel has its own features and scales
    for name, (v, s) in f.items():
        ref = (housing_peak if "housing" in name else peak) if name.endswith("_n") else None
        assert scale_of(name, v, C, ref) == pytest.approx(s) if s else s is None


def test_paper_table_agrees_with_validate_paper(tmp_path):
    from rotorlanding.features import features_from_table
    from rotorlanding.validate import paper

    root = Path(__file__).resolve().parents[1]
    m = load_measurement(root / "scenarios" / "measured" / "paper_table2_fig39.toml")
    fig, t2 = paper()["fig39"], paper()["table2"]["experimental"]
    assert [p.overrides for p in m.points] == [[f"operating.speed_rpm={float(r)!r}"] for r in fig["speed_rpm"]]
    assert [p.features["whirl_frequency_hz"] for p in m.points] == fig["experimental_hz"]
    assert all(p.features["whirl_direction"] == "forward" for p in m.points)
    p7 = m.points[fig["speed_rpm"].index(7000)].features
    assert (p7["DE_vertical_max_m"], p7["DE_vertical_min_m"], p7["DE_force_z_max_n"], p7["DE_force_z_min_n"]) == \
        (t2["v_disp_max_m"], t2["v_disp_min_m"], t2["v_force_max_n"], t2["v_force_min_n"])
    f = features_from_table(p7, C)
    assert f["DE_force_z_min_n"][1] == f["DE_force_z_max_n"][1] == pytest.approx(0.15 * 4500.0)
    assert f["DE_vertical_max_m"][1] == pytest.approx(0.1 * C) and f["whirl_frequency_hz"][1] == pytest.approx(2.0)


def test_paper_table1_agrees_with_validate_paper():
    from rotorlanding.features import features_from_table
    from rotorlanding.validate import paper

    root = Path(__file__).resolve().parents[1]
    m = load_measurement(root / "scenarios" / "measured" / "paper_table1.toml")
    t1 = paper()["table1"]["experimental"]
    assert not m.points and m.features == {
        "whirl_direction": "backward", "whirl_frequency_hz": t1["frequency_hz"], "whirl_onset_s": t1["onset_s"],
        "DE_vertical_max_m": t1["v_disp_max_m"], "DE_vertical_min_m": t1["v_disp_min_m"]}
    f = features_from_table(m.features, C)
    assert f["DE_vertical_min_m"][1] == pytest.approx(0.1 * C) and f["whirl_onset_s"][1] == pytest.approx(0.05)
    # what diagnose compares its model with (no simulation): one point, the scenario as it is
    from rotorlanding.diagnose_run import measured_for_diagnosis

    clearance, _, meas, _ = measured_for_diagnosis(root / "scenarios" / "paper" / "backward_whirl_landing.toml",
                                                   root / "scenarios" / "measured" / "paper_table1.toml", [])
    assert clearance == C and meas["whirl_direction"] == ("backward", None) and len(meas) == 5


@pytest.mark.parametrize("text, words", [
    ('[points.a]\nset.operating.speed_rpm = 3000.0\nfeatures.whirl_frequency_mhz = 48.0\n',
     ["points.a.features.whirl_frequency_mhz", "wrong unit", "whirl_frequency_hz"]),
    ('[points.a]\nset.operating.speed_rpm = 3000.0\nfeatures.whirl_speed_hz = 48.0\n',
     ["points.a.features.whirl_speed_hz", "unknown feature", "allowed"]),
    ('[points.a]\nset.operating.speed_rpm = 3000.0\nfeatures.DE_vertical_max_m = 0.15\n',
     ["DE_vertical_max_m", "mm?"]),
    ('[points.a]\nset.operating.speed_rpm = 3000.0\nfeatures.whirl_direction = "sideways"\n',
     ["whirl_direction", "none, forward, backward"]),
    ('[points.a]\nfeatures.whirl_frequency_hz = 48.0\n', ["points.a.set", "missing operating-point overrides"]),
    ('[points.a]\nset.operating.speed_rpm = 3000.0\n', ["points.a.features", "missing measured features"]),
    ('[points.a]\nset.operating.sped_rpm = 3000.0\nfeatures.whirl_frequency_hz = 48.0\n',
     ["points.a.set", "sped_rpm", "not valid for"]),
    ('[point.a]\nset.operating.speed_rpm = 3000.0\n', ["point", "unknown key"]),
])
def test_bad_feature_tables_one_line_errors(tmp_path, capsys, text, words):
    from rotorlanding.cli import main

    root = Path(__file__).resolve().parents[1]
    f = tmp_path / "table.toml"
    f.write_text(text)
    assert main(["diagnose", "--measured", str(f), "--scenario", str(root / "scenarios" / "paper" /
                                                                      "forward_whirl_landing.toml"),
                 "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "Traceback" not in err and str(f) in err, err
    for w in words:
        assert w in err, err


@pytest.mark.parametrize("extra, words", [
    (["--set", "effects.axial_rubb=false"], ["effects.axial_rubb", "unknown effect", "axial_rub"]),
    (["--candidates", "axial,windage"], ["--candidates", "'axial'", "unknown effect"]),
    (["--workers", "0"], ["--workers", ">= 1"]),
])
def test_bad_diagnose_options_one_line_errors(tmp_path, capsys, extra, words):
    from rotorlanding.cli import main

    root = Path(__file__).resolve().parents[1]
    assert main(["diagnose", "--measured", str(root / "scenarios" / "measured" / "paper_table2_fig39.toml"),
                 "--scenario", str(root / "scenarios" / "paper" / "forward_whirl_landing.toml"),
                 "--out", str(tmp_path / "o")] + extra) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and all(w in err for w in words), err


def test_diagnose_summary_line_says_a_parameter_explains(monkeypatch, capsys, tmp_path):
    """The paper's Table 2 (issue 20): the report named the coupling hub's mass while the command's
    summary line said only 'named effect: None'; it now gives the explanation as well."""
    import rotorlanding.diagnose_run as dr
    from rotorlanding.cli import main

    res = {"warnings": [], "gap_before": 2.076, "gap_after": 1.511, "noise_gate": 1.396,
           "noise": {"source": "4 drops from a 5 um circle"}, "named_effect": None, "named_effects": [],
           "explanation": "parameter", "signatures": {}, "unexplained": False, "absent_in_model_before": [],
           "named_parameters": [{"key": "rotor.disks.3.mass", "from": 4.0, "to": 1.0, "bound": [1.0, 8.0]}],
           "points": [{"name": "a"}], "simulations": 321, "wall_s": 368.0}
    monkeypatch.setattr(dr, "run_diagnose", lambda *a, **k: (res, ["report.md"]))
    assert main(["diagnose", "--measured", "m.toml", "--scenario", "s.toml", "--out", str(tmp_path / "o")]) == 0
    out = capsys.readouterr().out
    assert "explanation: parameter; named effect: None" in out and "parameter rotor.disks.3.mass: 4.0 -> 1" in out


def test_report_step_line_does_not_call_an_unnamed_candidate_named():
    """The paper's Table 1 with --max-effects 2 (issue 20): step 2's best candidate (the DE
    clearance) was re-fitted with the named k_rib and not named, and the report listed it under
    'joint re-fit of everything named so far'."""
    from rotorlanding.diagnose_run import _step_lines

    refit = {"gap_before_refit": 1.605, "gap_after_refit": 1.605,
             "values": {"bearings.DE.k_rib": {"bearings.DE.k_rib": 4.18e7},
                        "bearings.DE.clearance": {"bearings.DE.clearance": 1.88e-4}}}
    steps = [{"named": "bearings.DE.k_rib", "refit": None, "candidates": [{"effect": "bearings.DE.k_rib"}]},
             {"named": None, "refit": refit, "candidates": [{"effect": "bearings.DE.clearance"}]}]
    (line,) = _step_lines(steps)
    assert line.startswith("Step 2: the best candidate, bearings.DE.clearance, re-fitted") and "not named" in line
    steps[1]["named"] = "bearings.DE.clearance"
    assert "joint re-fit of everything named so far with bearings.DE.clearance" in _step_lines(steps)[0]


def test_whirl_direction_rule_ignores_a_direction_the_noise_drops_already_have():
    """The paper's Table 2 (issue 20): at 3000 rpm the centred drop of the rig does not whirl at the
    DE, 3 of the 4 off-centre drops of the noise gate whirl forward; a candidate that turns the
    centred drop forward there has not brought a whirl regime, and the naming rule must not count it."""
    from rotorlanding.diagnose_run import Point, whirl_direction_fixed

    pts = [Point("rpm_3000"), Point("rpm_7000"), Point("rpm_10000")]
    measured = ["forward"] * 3
    before, after = ["none", "none", "forward"], ["forward", "forward", "forward"]
    noise = [["forward", "none", "forward"], ["none", "none", "forward"], ["forward", "none", "forward"],
             ["forward", "none", "forward"]]
    assert whirl_direction_fixed(pts, measured, before, after, noise) == (["rpm_7000"], ["rpm_3000"])
    # without members (a given gate) every fixed point counts, as before
    assert whirl_direction_fixed(pts, measured, before, after, []) == (["rpm_3000", "rpm_7000"], [])
    # a member whirling the other way is no evidence either way
    assert whirl_direction_fixed(pts, measured, before, after, [["backward", "backward", "forward"]])[0] == \
        ["rpm_3000", "rpm_7000"]
