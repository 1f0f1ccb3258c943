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
