"""The validation report rendered again from a stored run (``rotorlanding validate --report-from RUN``): the stored
result gives the floats JSON turned into strings back, and a run is refused when it cannot stand for the rig as
the scenarios now give it (no landing is run here)."""

import json

import pytest

from rotorlanding import validate as V
from rotorlanding.cli import main
from rotorlanding.errors import InputError


def _result(**extra):
    # the parts of a result that load_result and report_from_run read before rendering
    return {"evaluation": {"checks": []}, "rig_overlay": None,
            "ribbon_modal": {"modes_hz": {0.5: 64.7, 1.0: 67.5, 1.5: 68.2}, "shift": {0.5: -0.041, 1.5: 0.01},
                             "support_n_m": {0.5: 2.2e7, 1.0: 3.6e7, 1.5: 4.6e7},
                             "forward_modes_hz": {0.5: [64.7], 1.0: [67.5], 1.5: [68.2]},
                             "ribbon_energy_share": {0.5: 0.12, 1.5: 0.05}, "k_rib_n_m": 6.3e7},
            **extra}


def _store(folder, result):
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "validation.json").write_text(json.dumps(result, default=float))
    return folder


def test_the_ribbon_factors_come_back_as_floats(tmp_path):
    r = _result()
    back = V.load_result(_store(tmp_path / "run", r))
    # JSON wrote 0.5 / 1.0 / 1.5 as "0.5" ...: the report indexes them as floats (a KeyError before session 42)
    assert back["ribbon_modal"] == r["ribbon_modal"]
    assert list(back["ribbon_modal"]["modes_hz"]) == [0.5, 1.0, 1.5]


def test_a_missing_or_torn_result_is_one_line(tmp_path):
    with pytest.raises(InputError, match="must hold the validation.json"):
        V.load_result(tmp_path)
    (tmp_path / "validation.json").write_text('{"evaluation": {"checks": [')
    with pytest.raises(InputError, match="unreadable"):
        V.load_result(tmp_path)
    (tmp_path / "validation.json").write_text('{"cases": {}}')
    with pytest.raises(InputError, match="no evaluation"):
        V.load_result(tmp_path)


def test_a_run_older_than_the_fingerprints_is_refused(tmp_path):
    run = _store(tmp_path / "run", _result(rerenderable=True))
    with pytest.raises(InputError, match="scenario_fingerprints.*predates"):
        V.report_from_run(run)


def test_a_run_whose_scenarios_changed_is_refused(tmp_path):
    prints = V.scenario_fingerprints()
    # one case landed on other values than its scenario now gives (e.g. a re-fitted worn bearing)
    stale = {**prints, "backward_whirl": "0" * 16}
    run = _store(tmp_path / "run", _result(scenario_fingerprints=stale, rerenderable=True))
    with pytest.raises(InputError, match="backward_whirl.*other values"):
        V.report_from_run(run)
    # a case the run did not land (a study added since) is a change too
    fewer = {k: v for k, v in prints.items() if k != "heldout_3000"}
    run = _store(tmp_path / "run2", _result(scenario_fingerprints=fewer, rerenderable=True))
    with pytest.raises(InputError, match="heldout_3000"):
        V.report_from_run(run)


def test_a_result_that_did_not_give_its_report_back_is_refused(tmp_path):
    run = _store(tmp_path / "run", _result(scenario_fingerprints=V.scenario_fingerprints(), rerenderable=False))
    with pytest.raises(InputError, match="rerenderable"):
        V.report_from_run(run)


def test_the_fingerprints_cover_every_case_validate_lands():
    prints = V.scenario_fingerprints()
    assert set(prints) == set(V.CASES) | set(V.studies())
    # the same scenario with other overrides is another landing: the ribbon variants differ from the base case
    assert prints["forward_7000"] != prints["ribbon_k_rib_x1.5"] != prints["forward_7000_no_axial_rub"]


@pytest.mark.parametrize("extra", [["--quick"], ["--set", "contact.mu_rad=0.2"], ["--out", "elsewhere"]])
def test_options_that_would_change_the_landings_are_refused(tmp_path, capsys, extra):
    run = _store(tmp_path / "run", _result())
    assert main(["validate", "--report-from", str(run)] + extra) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "--report-from" in err[0]


def _design(k, hz, fraction=1.0, direction="backward", onset=0.0, dmax=2.8e-4, dmin=-3.05e-4):
    return {"design": k, "bw_direction": direction, "bw_fraction": fraction, "bw_hz": hz, "bw_onset_s": onset,
            "bw_v_disp_max_m": dmax, "bw_v_disp_min_m": dmin, "bearings.DE.worn_drag_torque": 2.0 + k,
            "bearings.DE.worn_drag_growth_angle": 100.0 * (k + 1)}


def test_a_frequency_only_fit_keeps_what_the_frequency_cannot_reject():
    # Table 1: 49 Hz, band 4.9 Hz; onset 0.4 s (band 0.04), displacement max 0.2 mm (0.05), min -0.4 mm (0.12)
    designs = [_design(0, 48.0, onset=0.38, dmax=2.2e-4),          # admissible, nearest 49 Hz
               _design(1, 52.0, onset=0.0),                         # admissible
               _design(2, 49.1, fraction=0.8),                      # whirls in too few drops
               _design(3, 49.0, direction="none"),                  # calm
               _design(4, 60.0, onset=0.4)]                         # outside the band
    fo = V.frequency_only_backward(designs)
    assert fo["designs"] == 5 and fo["admissible"] == 2 and fo["fit"]["design"] == 0
    on = fo["rows"]["t1_onset"]
    assert (on["fit"], on["min"], on["max"], on["in_band"], on["fit_in_band"]) == (0.38, 0.0, 0.38, 1, True)
    assert fo["rows"]["t1_disp_max"]["in_band"] == 1 and fo["rows"]["t1_disp_min"]["in_band"] == 2
    text = "\n".join(V.frequency_only_lines(fo))
    # the fit's stored numbers are read against the band, not judged: they carry no standard error
    assert "keeps 2 of them" in text and "design 0" in text and "onset 0.38 s (in band" in text
    assert "PASS" not in text and "FAIL" not in text
    assert V.frequency_only_backward([_design(0, 70.0)]) is None and V.frequency_only_lines(None) == []
    # the pick, landed again (validate's case): its --set values, and its rows judged with margins and errors
    assert V.frequency_only_sets(fo) == ["bearings.DE.worn_drag_torque=2.0", "bearings.DE.worn_drag_growth_angle=100.0"]
    assert V.frequency_only_sets(None) == []
    w = {"counts": {"backward": 30, "none": 2}, "direction": "backward", "frequency_hz": 48.5, "frequency_se_hz": 1.0,
         "onset_s": 0.0, "onset_se_s": 0.03, "v_disp_range_m": [-3.0e-4, 2.8e-4], "v_disp_range_se_m": [4e-6, 8e-6]}
    landed = V.frequency_only_landed(w)
    assert (landed["n"], landed["backward"], landed["frequency_in_band"]) == (32, 30, True)
    rows = landed["rows"]
    assert rows["t1_onset"]["margin"] == pytest.approx(0.04 - 0.4) and not rows["t1_onset"]["pass"]
    assert rows["t1_disp_max"]["margin"] == pytest.approx(0.05e-3 - 0.08e-3) and not rows["t1_disp_max"]["pass"]
    assert rows["t1_disp_min"]["margin"] == pytest.approx(0.12e-3 - 0.1e-3) and rows["t1_disp_min"]["pass"]
    assert rows["t1_disp_min"]["se"] == 4e-6
    text = "\n".join(V.frequency_only_lines({**fo, "landed": landed}))
    assert "backward in 30 of 32, 48.5 Hz" in text
    assert "onset 0 +/- 0.03 s, margin -0.36 (0.03) FAIL" in text
    assert "displacement min -0.3 +/- 0.004 mm, margin 0.02 (0.004) PASS" in text
    assert V.frequency_only_landed(None) is None


def test_the_switch_reading_says_what_holds_the_calm_race():
    ens = {"backward_whirl": {"race_to_rotor": 0.98, "members": [{"race_to_rotor": 0.97}, {"race_to_rotor": 0.99}]},
           "backward_mu_0.15": {"race_to_rotor": 1e-4, "members": [{"race_to_rotor": 0.0}, {"race_to_rotor": 0.02}]},
           "no_whirl": {"race_to_rotor": 0.993}}
    sw = V.switch_sides(ens)
    # the worn bearing's torque and the landing's speed come from the backward scenario itself
    from rotorlanding.scenario import load_scenario
    sc = load_scenario(V.paper_dir() / V.CASES["backward_whirl"][0])
    assert sw["worn_drag_torque_n_m"] == sc.bearings["DE"].worn_drag_torque and sw["omega_rad_s"] == sc.omega0
    assert sw["race_to_rotor_max"] == {"mu_0.3": 0.99, "mu_0.15": 0.02}
    text = V.switch_lines(sw)[1]
    power_kw = sc.bearings["DE"].worn_drag_torque * 0.98 * sc.omega0 / 1e3
    assert f"about {power_kw:.2g} kW" in text and "race at rest" in text and "0.993" in text
    assert V.switch_sides({"backward_whirl": ens["backward_whirl"]}) is None


def test_steady_extremes_leave_the_first_swings_out(tmp_path, monkeypatch):
    import numpy as np

    import rotorlanding.mechanisms as mech
    import rotorlanding.results as res

    t = np.linspace(0.0, 1.0, 1001)
    # a whirl from 0.2 s whose force swings +/-4 kN until 0.5 s and +/-1 kN after; displacement alike
    amp = np.where(t < 0.5, 4000.0, 1000.0)
    runs = {}
    for k in range(3):
        f = tmp_path / f"drop{k}.h5"
        f.write_text("")
        runs[str(f)] = {"time_s": t, "series": {"DE_z_m": amp * 1e-7 * np.sin(400 * t + k), "fz": amp * np.sin(400 * t + k)}}
    monkeypatch.setattr(V, "member_results", lambda out, key, k: tmp_path / f"drop{k}.h5")
    monkeypatch.setattr(res, "read_results", lambda p: runs[str(p)])
    monkeypatch.setattr(mech, "rotor_force", lambda series, b: (None, series["fz"]))
    members = [{"direction": "forward", "onset_s": 0.2}, {"direction": "forward", "onset_s": 0.2},
               {"direction": "none", "onset_s": None}]
    st = V.steady_extremes({"ensembles": {"forward_7000": {"members": members}}}, tmp_path)
    # the second half of the whirl starts at (0.2 + 1.0) / 2 = 0.6 s, after the large swings; the calm drop is out
    assert st["drops"] == 2 and st["of"] == 3 and st["from_s"] == pytest.approx(0.6)
    assert st["force_n"][0] == pytest.approx(-1000.0, rel=1e-3) and st["force_n"][1] == pytest.approx(1000.0, rel=1e-3)
    assert st["disp_m"][1] == pytest.approx(1e-4, rel=1e-3)
    assert V.steady_extremes({"ensembles": {}}, tmp_path) is None


def test_a_rig_margin_has_the_fits_spread_beside_it():
    from rotorlanding.scenario import Bound

    bound, search = Bound(0.0, 1.0, "src"), Bound(0.2, 0.95, "fit")
    # 0.9 is nearer the search range's top (6.7 % of its width) than the bound's (10 %): the spread is read there
    assert V.clear_spread(0.9, bound, search, [0.85, 0.93]) == pytest.approx(0.04 / 0.75)
    # on a log bound the spread is a share of the log width
    log = Bound(1.0, 1e4, "src", True)
    assert V.clear_spread(100.0, log, None, [10.0, 1000.0]) == pytest.approx(0.25)
    assert V.clear_spread(0.5, bound, search, None) is None and V.clear_spread(0.5, None, search, [0.4, 0.6]) is None


def test_the_failing_checks_table_lists_only_what_fails():
    checks = [{"check": "Table 1: backward whirl onset", "pass": False, "provenance": "fitted (x)"},
              {"check": "Table 2: DE vertical displacement max (7000 rpm)", "pass": True},
              {"check": "a check without a note", "pass": False}]
    lines = V.failure_lines(checks)
    rows = [x for x in lines if x.startswith("| Table")]
    assert len(rows) == 1 and rows[0].startswith("| Table 1: backward whirl onset | fitted (x) | sessions 5, 7, 32-34, 42")
    assert V.failure_lines([{**c, "pass": True} for c in checks]) == []
    # every note names a search, a mechanism, a script and a kind
    assert all(len(v) == 4 and all(v) for v in V.FAILURE_NOTES.values())


def test_a_run_on_other_landing_code_is_refused(tmp_path):
    run = _store(tmp_path / "run", _result(scenario_fingerprints=V.scenario_fingerprints(), rerenderable=True,
                                           code_fingerprint="0" * 16, landed_at="abc123"))
    with pytest.raises(InputError, match="code_fingerprint.*landed at abc123"):
        V.report_from_run(run)


def test_the_code_fingerprint_leaves_out_the_report_code_only(monkeypatch):
    fp = V.code_fingerprint()
    assert fp == V.code_fingerprint() and len(fp) == 16
    # the report's own sources are what a re-render may change; counting them changes the fingerprint
    monkeypatch.setattr(V, "RENDER_SOURCES", ())
    assert V.code_fingerprint() != fp


def test_every_failure_note_names_a_check_validate_makes():
    import inspect

    names = {r[1] for r in V.TABLE_ROWS}
    src = inspect.getsource(V)
    for key in V.FAILURE_NOTES:
        # a table row's name, or a check name written in evaluate_cases / clearance_check besides the note itself
        assert any(n.startswith(key) for n in names) or src.count(f'"{key}') >= 2, key
