"""Calibration against the paper: scoring rule and a tiny end-to-end run."""

import csv
import json
import re
from pathlib import Path

import pytest

from rotorlanding.calibrate_run import score
from rotorlanding.cli import main


def _calibrate_faked(monkeypatch, tmp_path, fake_run_all, space_text: str) -> list[dict]:
    """``calibrate`` on a space file written from ``space_text``, its landings replaced by
    ``fake_run_all`` (jobs, workers) -> {design: {case: result}}: the table logic alone."""
    from rotorlanding import calibrate_run as cal

    monkeypatch.setattr(cal, "_run_all", fake_run_all)
    space = tmp_path / "space.toml"
    space.write_text(space_text)
    return cal.calibrate(space, tmp_path / "c", workers=1)

def test_score_is_zero_at_the_experimental_values_and_penalises_wrong_classes():
    exact = {"fw3000": {"direction": "forward", "frequency_hz": 48.0},
             "fw7000": {"direction": "forward", "frequency_hz": 65.0, "force_max_n": 4500.0},
             "fw10000": {"direction": "forward", "frequency_hz": 77.0},
             "bw": {"direction": "backward", "frequency_hz": 49.0, "onset_s": 0.4}}
    assert score(exact)[0] == pytest.approx(0.0)
    off = dict(exact, fw3000={"direction": "none", "frequency_hz": None})
    assert score(off)[0] == pytest.approx(1.0)
    slow = dict(exact, fw7000={"direction": "forward", "frequency_hz": 71.5, "force_max_n": 4500.0})
    assert score(slow)[0] == pytest.approx(0.1)


def test_tiny_calibration_run(tmp_path, capsys):
    space = tmp_path / "space.toml"
    space.write_text('samples = 1\nseed = 2\nt_end = 0.15\n[ranges]\n"bearings.DE.c_rib" = {min = 1e3, max = 3e4, log = true}\n')
    assert main(["calibrate", str(space), "--out", str(tmp_path / "c"), "--workers", "2"]) == 0
    rows = list(csv.DictReader(open(tmp_path / "c" / "calibration.csv")))
    assert len(rows) == 1 and 1e3 <= float(rows[0]["bearings.DE.c_rib"]) <= 3e4
    assert float(rows[0]["score"]) > 0
    assert "--set bearings.DE.c_rib=" in capsys.readouterr().out
    bad = tmp_path / "bad.toml"
    bad.write_text('[ranges]\n"x.y" = {min = 2, max = 1}\n')
    assert main(["calibrate", str(bad)]) == 2


def test_tied_keys_expand_and_step_convergence_rule():
    from rotorlanding.calibrate_run import converged, design_overrides

    sets = design_overrides({"bearings.DE.eta,bearings.NDE.eta": 0.2}, {"solver.step": 1e-4})
    assert sets == ["solver.step=0.0001", "bearings.DE.eta=0.2", "bearings.NDE.eta=0.2"]
    a = {"fw3000": {"direction": "forward", "frequency_hz": 48.0},
         "fw7000": {"direction": "forward", "frequency_hz": 65.0, "force_max_n": 4500.0},
         "fw10000": {"direction": "forward", "frequency_hz": 77.0},
         "bw": {"direction": "backward", "frequency_hz": 49.0}}
    assert converged(a, a)
    assert not converged(a, dict(a, bw={"direction": "none", "frequency_hz": None}))
    assert not converged(a, dict(a, fw10000={"direction": "forward", "frequency_hz": 80.0}))
    assert not converged(a, dict(a, fw7000={"direction": "forward", "frequency_hz": 65.0, "force_max_n": 5000.0}))
    # score_force = false (the rotor fitted by landing): Table 2's force maximum is left out
    b = dict(a, fw7000={"direction": "forward", "frequency_hz": 65.0, "force_max_n": 9000.0})
    assert score(b, ["fw7000"])[1]["force"] == pytest.approx(0.5)
    assert "force" not in score(b, ["fw7000"], force=False)[1] and score(b, ["fw7000"], force=False)[0] == 0.0


def test_scored_cases_and_backward_ensemble(tmp_path, capsys):
    """``cases`` restricts the score to the listed landings; ``ensemble`` runs the backward landing
    as drops from a 5 um circle and scores the members' statistics."""
    bw = {"bw": {"direction": "backward", "frequency_hz": 53.9, "onset_s": 0.4, "persistence": 0.75}}
    total, parts = score(bw, ["bw"])
    assert set(parts) == {"bw_freq", "bw_onset", "bw_persist"}
    assert parts["bw_persist"] == pytest.approx(0.25) and total == pytest.approx(0.35)
    assert score({"bw": {"direction": "none"}}, ["bw"])[0] == pytest.approx(3.0)
    # an ensemble is also charged the share of its drops that do not whirl backward (validate's switch
    # asks 7 of 8): a majority of 19 of 32 is not the paper's backward landing
    ens = {"bw": dict(bw["bw"], n=32, counts={"backward": 19, "none": 13})}
    total, parts = score(ens, ["bw"])
    assert parts["bw_share"] == pytest.approx(13 / 32) and total == pytest.approx(0.35 + 13 / 32)
    assert score({"bw": {"direction": "none", "n": 8, "counts": {"none": 5, "backward": 3}}}, ["bw"])[1]["bw_share"] == 0.625
    assert "bw_share" not in score({"bw": dict(bw["bw"], counts={"backward": 1})}, ["bw"])[1]  # one landing: no share
    space = tmp_path / "space.toml"
    space.write_text('samples = 1\nseed = 1\nt_end = 0.3\ncases = ["bw"]\nensemble = 2\n[ranges]\n'
                     '"bearings.DE.worn_drag_torque,bearings.NDE.worn_drag_torque" = {min = 2.0, max = 2.5}\n')
    assert main(["calibrate", str(space), "--out", str(tmp_path / "c"), "--workers", "2"]) == 0
    row = next(csv.DictReader(open(tmp_path / "c" / "calibration.csv")))
    assert "fw7000_direction" not in row and 0.0 <= float(row["bw_fraction"]) <= 1.0
    assert row["bw_direction"] in ("none", "backward", "forward")
    # what the score leaves out is recorded (docs/studies/backward_frequency_only.py): the drops'
    # median DE vertical range, the journal below the centre after the drop and within 2 mm
    lo, hi = float(row["bw_v_disp_min_m"]), float(row["bw_v_disp_max_m"])
    assert -2e-3 < lo < -1e-4 and lo < hi < 2e-3
    bad = tmp_path / "bad.toml"
    bad.write_text('cases = ["fw9000"]\n[ranges]\n"contact.mu_rad" = {min = 0.1, max = 0.2}\n')
    assert main(["calibrate", str(bad)]) == 2
    assert "fw9000" in capsys.readouterr().err
    # a [choices] entry judged on a case that does not exist: one line naming the field
    bad.write_text('[choices]\n"the worn bearing" = {options = "DE / NDE", chosen = "DE", judged_on = ["bw3"], '
                   'record = "x"}\n[ranges]\n"contact.mu_rad" = {min = 0.1, max = 0.2}\n')
    assert main(["calibrate", str(bad)]) == 2
    err = capsys.readouterr().err
    assert "choices.the worn bearing" in err and len(err.strip().splitlines()) == 1
    bad.write_text('score_force = "no"\n[ranges]\n"contact.mu_rad" = {min = 0.1, max = 0.2}\n')
    assert main(["calibrate", str(bad)]) == 2
    err = capsys.readouterr().err
    assert "score_force" in err and len(err.strip().splitlines()) == 1


def test_verification_continues_until_a_design_converges(tmp_path, monkeypatch):
    """When none of the ``verify_top`` best designs converges at half the step, the next batch is
    verified; converged designs rank first, unchecked next, unconverged last."""

    def fake_run_all(jobs, workers):
        out = {}
        for i, case, _d, _t, _f, step_factor, _x in jobs:
            f = 49.0 + 0.5 * i  # design i scores i * 0.5 / 49 on frequency alone
            if step_factor != 1.0 and i != 4:
                f *= 1.1  # only design 4 keeps its frequency at half the step
            out[i] = {case: {"direction": "backward", "frequency_hz": f, "onset_s": 0.4, "persistence": 1.0}}
        return out

    rows = _calibrate_faked(monkeypatch, tmp_path, fake_run_all,
                            'samples = 7\nseed = 1\ncases = ["bw"]\nverify_top = 2\n'
                            '[ranges]\n"bearings.DE.worn_drag_torque" = {min = 1.0, max = 3.0}\n')
    # batches (0, 1) and (2, 3) fail, (4, 5) holds the converged 4; 6 is never checked
    assert [r["design"] for r in rows] == [4, 6, 0, 1, 2, 3, 5]
    assert [r["converged"] for r in rows] == [True, None, False, False, False, False, False]


def test_ensemble_option_applies_to_every_case(monkeypatch, tmp_path):
    """``ensemble = n`` runs each scored case as n drops; the members fold into the case's
    statistics, and the forward force score reads their median peak force."""
    from rotorlanding import calibrate_run as cal

    sp = {"cases": ["fw7000", "bw"], "ensemble": 3, "t_end": 0.1, "fixed": {}}
    jobs = cal._jobs({0: {"x": 1.0}}, sp, 1.0)
    assert sorted(j[1] for j in jobs) == ["bw#0", "bw#1", "bw#2", "fw7000#0", "fw7000#1", "fw7000#2"]
    assert all(len(j[6]) == 1 and j[6][0].startswith("amb.drop_offset_m=") for j in jobs)

    def fake_run(job):
        i, case, *_ = job
        k = int(case.split("#")[1])
        if case.startswith("fw"):
            return i, case, {"direction": "forward", "frequency_hz": 64.0 + k, "onset_s": 0.1,
                             "v_force_range_n": [-1e3, 4000.0 + 500.0 * k]}
        return i, case, {"direction": "backward" if k else "none", "frequency_hz": 50.0 if k else None,
                         "onset_s": 0.1 if k else None, "persistence": 1.0, "v_force_range_n": [0.0, 1.0]}

    monkeypatch.setattr(cal, "_run", fake_run)
    res = cal._run_all(jobs, workers=1)[0]
    assert res["fw7000"]["direction"] == "forward" and res["fw7000"]["frequency_hz"] == 65.0
    assert res["fw7000"]["force_max_n"] == 4500.0 and res["fw7000"]["fraction"] == 1.0
    assert res["bw"]["direction"] == "backward" and res["bw"]["fraction"] == pytest.approx(2 / 3)
    total, parts = cal.score(res, ["fw7000", "bw"])
    assert parts["force"] == pytest.approx(0.0) and parts["fw7000"] == pytest.approx(0.0)


def test_worn_bearing_calibration_scores_the_drops_validate_judges():
    """The report says the backward onset was calibrated on its own ensemble's drops: the space
    file's ensemble must be validate's backward ensemble (same size, hence the same drop points)."""
    from rotorlanding.calibrate_run import load_space
    from rotorlanding.validate import ENSEMBLE

    space = load_space(Path(__file__).resolve().parents[1] / "scenarios" / "calibration" / "worn_bearing.toml")
    assert space["ensemble"] == ENSEMBLE["backward_whirl"]
    assert space["cases"] == ["bw", "bw015"]


def test_switch_case_scores_the_share_of_whirling_drops_at_normal_friction():
    """bw015 (the backward landing's bearing at mu_rad 0.15, Table 1's switch) must land calm:
    its score part is the share of its drops that whirl, in either direction."""
    from rotorlanding.calibrate_run import CASES, score

    assert CASES["bw015"] == ("backward_whirl_landing.toml", ["contact.mu_rad=0.15"])
    total, parts = score({"bw015": {"counts": {"none": 6, "backward": 1, "forward": 1}}}, ["bw015"])
    assert parts == {"bw015_whirls": 0.25} and total == 0.25
    assert score({"bw015": {"direction": "none"}}, ["bw015"])[1]["bw015_whirls"] == 0.0
    assert score({"bw015": {"direction": "backward"}}, ["bw015"])[1]["bw015_whirls"] == 1.0
    assert "bw015_whirls" not in score({})[1]  # opt-in: not among the default cases


def test_forward_ensembles_are_judged_at_the_de_journal():
    """An ensemble forward case scores the DE journal's median frequency and the share of drops
    whose DE journal does not whirl forward (the paper measured the DE), not the landing majority."""
    ens = {"direction": "forward", "frequency_hz": 46.0,
           "de": {"counts": {"forward": 6, "none": 2}, "direction": "forward", "frequency_hz": 43.2}}
    total, parts = score({"fw3000": ens}, ["fw3000"])
    assert parts == {"fw3000": pytest.approx(0.1), "fw3000_de": pytest.approx(0.25)}
    calm_de = dict(ens, de={"counts": {"none": 5, "forward": 3}, "direction": "none", "frequency_hz": None})
    assert score({"fw3000": calm_de}, ["fw3000"])[1] == {"fw3000": 1.0, "fw3000_de": pytest.approx(0.625)}


def test_score_error_adds_the_parts_errors_and_a_share_has_the_binomial_error():
    """score_se: the frequency median's error over the experiment and the share's binomial error,
    in quadrature; the binomial rule checked against a Monte Carlo draw of 8-drop ensembles."""
    import numpy as np

    from rotorlanding.calibrate_run import score_parts, score_se
    from rotorlanding.ensemble import share_se

    ens = {"n": 8, "direction": "forward", "frequency_hz": 46.0,
           "de": {"counts": {"forward": 6, "none": 2}, "direction": "forward", "frequency_hz": 43.2,
                  "frequency_se_hz": 0.96}}
    parts = score_parts({"fw3000": ens}, ["fw3000"])
    assert parts["fw3000"] == (pytest.approx(0.1), pytest.approx(0.96 / 48.0))
    assert parts["fw3000_de"] == (pytest.approx(0.25), pytest.approx((0.25 * 0.75 / 8) ** 0.5))
    assert score_se({"fw3000": ens}, ["fw3000"]) == pytest.approx(((0.02) ** 2 + 0.25 * 0.75 / 8) ** 0.5)
    k = np.random.default_rng(3).binomial(8, 0.25, size=200_000)
    assert np.std(k / 8) == pytest.approx(share_se(2, 8), rel=0.01)
    # 8 of 8 is not certain: p kept half a drop from 1 (validate's class-check rule)
    assert share_se(8, 8) == pytest.approx((0.0625 * 0.9375 / 8) ** 0.5)
    # a single landing is one draw: no error to give, and no design can be judged within noise
    assert score_se({"fw3000": {"direction": "forward", "frequency_hz": 47.0}}, ["fw3000"]) is None


def test_designs_within_noise_of_the_best_and_their_span():
    """A design is indistinguishable from the best when its score is above the best's by no more
    than NOISE_Z standard errors of the difference; failed or error-less designs are never in."""
    from rotorlanding.calibrate_run import NOISE_Z, noise_span, within_noise

    rows = [{"design": 8, "score": 0.067, "score_se": 0.15, "failed_landings": 0, "x": 0.0407},
            {"design": 18, "score": 0.231, "score_se": 0.17, "failed_landings": 0, "x": 0.0398},
            {"design": 3, "score": 0.067 + NOISE_Z * 0.25 + 0.01, "score_se": 0.2, "failed_landings": 0, "x": 0.045},
            {"design": 5, "score": 0.1, "score_se": 0.1, "failed_landings": 1, "x": 0.038},
            {"design": 6, "score": 0.1, "score_se": None, "failed_landings": 0, "x": 0.038}]
    near = within_noise(rows)
    assert [r["design"] for r in near] == [8, 18]  # 3: 0.01 beyond 2 x hypot(0.15, 0.2) = 0.5
    for r in rows:
        r["within_noise_of_best"] = r in near
    assert noise_span(rows, ["x"]) == {"x": [0.0398, 0.0407]}
    assert within_noise([dict(rows[0], score_se=None)] + rows[1:]) == []
    # checked at half the step: the worse of the two scores counts, an unconverged design never
    half = [dict(rows[0], converged=True), dict(rows[1], converged=None),
            dict(rows[1], design=19, converged=False), dict(rows[1], design=20, score_half_step=0.9)]
    assert [r["design"] for r in within_noise(half)] == [8, 18]


def test_ensemble_gives_the_persistence_error():
    from rotorlanding.ensemble import _median_se, ensemble_stats

    members = [{"direction": "backward", "frequency_hz": 48.0 + k, "onset_s": 0.1 * k, "persistence": p}
               for k, p in enumerate([0.9, 0.95, 1.0, 0.85])]
    st = ensemble_stats(members)
    assert st["persistence"] == pytest.approx(0.925)
    assert st["persistence_se"] == pytest.approx(_median_se([0.9, 0.95, 1.0, 0.85]))


@pytest.mark.slow
def test_rig_landing_fit_reruns_and_keeps_the_rotor_file_within_its_noise(tmp_path):
    """The rig rotor's main shaft and actuator disk are design 0 of
    scenarios/calibration/rotor_landings.toml (session 30). Re-run (2304 landings since session 35's
    32 drops per speed, ~21 min on 2 cores), that design is among those the fit cannot tell from its best. Which of them ranks first
    moves with the install's arithmetic (session 24: design 8, 40.73 / 420.9 mm, on numpy 2.4.6), so
    the fit's claim, and this test's, is the set and its span (docs/calibration.md, session 25)."""
    from rotorlanding.calibrate_run import calibrate
    from rotorlanding.config import load_toml

    root = Path(__file__).resolve().parents[1]
    rows = calibrate(root / "scenarios" / "calibration" / "rotor_landings.toml", tmp_path, workers=2)
    rotor = load_toml(root / "scenarios" / "rig_rotor.toml")["rotor"]
    adopted = (rotor["sections"][3]["outer_diameter"], rotor["disks"][4]["outer_diameter"])
    near = [(r["rotor.sections.3.outer_diameter"], r["rotor.disks.4.outer_diameter"])
            for r in rows if r["within_noise_of_best"]]
    assert adopted in near
    assert len(near) < len(rows)  # the fit does tell designs apart: not every design is "within noise"


@pytest.mark.slow
def test_worn_bearing_fit_reruns_and_keeps_the_backward_scenario_within_its_noise(tmp_path):
    """The worn DE bearing's drag and growth angle in scenarios/paper/backward_whirl_landing.toml are
    the first design of scenarios/calibration/worn_bearing.toml on the pinned install (session 26;
    1024 landings and 96 at half the step, ~15 min on 2 cores). Re-run, the adopted values are among
    the designs the fit cannot tell from its best, and the fit tells some designs apart; the
    stored run (docs/studies/worn_fit/) gives the same span on the same install."""
    import json

    from rotorlanding.calibrate_run import calibrate
    from rotorlanding.config import load_toml

    root = Path(__file__).resolve().parents[1]
    rows = calibrate(root / "scenarios" / "calibration" / "worn_bearing.toml", tmp_path, workers=2)
    de = load_toml(root / "scenarios" / "paper" / "backward_whirl_landing.toml")["bearings"]["DE"]
    adopted = (de["worn_drag_torque"], de["worn_drag_growth_angle"])
    keys = ("bearings.DE.worn_drag_torque", "bearings.DE.worn_drag_growth_angle")
    near = [tuple(r[k] for k in keys) for r in rows if r["within_noise_of_best"]]
    assert adopted in near
    assert len(near) < len(rows)
    stored = json.loads((root / "docs" / "studies" / "worn_fit" / "calibration.json").read_text())
    assert [r["design"] for r in rows if r["within_noise_of_best"]] == \
        [r["design"] for r in stored["designs"] if r["within_noise_of_best"]]


def test_heldout_span_scores_the_two_fitted_speeds_and_judges_each_design_in_the_noise():
    """docs/studies/heldout_span.py: the fit without one speed is the full fit's parts of the other
    two (same designs), its noise set is judged by validate's held-out rule at the third."""
    import importlib.util

    path = Path(__file__).resolve().parents[1] / "docs" / "studies" / "heldout_span.py"
    spec = importlib.util.spec_from_file_location("heldout_span", path)
    hs = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(hs)

    def row(i, e3, e7, e10, hz3, fwd3):
        r = {"design": i, hs.KEYS[0]: 0.04, hs.KEYS[1]: 0.42, "fw3000_de_hz": hz3, "fw3000_de_forward": fwd3,
             "fw3000_de_direction": "forward"}
        for c, e in (("fw3000", e3), ("fw7000", e7), ("fw10000", e10)):
            r.update({f"err_{c}": e, f"err_{c}_se": 0.01, f"err_{c}_de": 0.0, f"err_{c}_de_se": 0.03})
        return r

    rows = [row(0, 0.5, 0.01, 0.01, 40.0, 8),   # best without 3000 rpm, predicts 40 Hz (-16.7 %): fails
            row(1, 0.0, 0.02, 0.02, 47.0, 8),   # within noise of it (0.02 apart), predicts 47 Hz: passes
            row(2, 0.0, 0.02, 0.02, 47.0, 6),   # same, but its DE whirls forward in 6 of 8: fails
            row(3, 0.0, 0.5, 0.5, 48.0, 8)]     # far off on the fitted speeds: not in the set
    assert hs.sub_score(rows[0], ["fw7000", "fw10000"]) == (pytest.approx(0.02), pytest.approx(0.002 ** 0.5))
    h = hs.heldout(rows, 3000, 8)
    assert h["first"] == 0 and [p["design"] for p in h["within_noise"]] == [0, 1, 2]
    assert [p["pass"] for p in h["within_noise"]] == [False, True, False] and h["passing"] == 1
    assert h["within_noise"][0]["error"] == pytest.approx(40.0 / 48.0 - 1)
    # validate's pick rule includes the fit's search range: design 1 at 1 % of the shaft's range from
    # its lower end fails as 'on its bound' though it predicts 47 Hz (session 30)
    from rotorlanding.scenario import Bound

    ranges = {hs.KEYS[0]: Bound(0.0399, 0.0449, "s"), hs.KEYS[1]: Bound(0.38, 0.48, "s")}
    rows[1][hs.KEYS[0]] = 0.0399 + 0.01 * 0.005
    h = hs.heldout(rows, 3000, 8, ranges)
    assert [p["on_bound"] for p in h["within_noise"]] == [False, True, False] and h["passing"] == 0


def test_heldout_fits_search_the_ranges_and_designs_of_the_study_and_rotor_fits():
    """The held-out fits are parts of the three-speed study fit (holdout/all_speeds_landings.toml:
    same seed, designs and ranges; docs/studies/heldout_span.py reads them as such), and since session
    30 the adopted rotor fit searches the same ranges."""
    from rotorlanding.config import load_toml

    cal = Path(__file__).resolve().parents[1] / "scenarios" / "calibration"
    ref = load_toml(cal / "holdout" / "all_speeds_landings.toml")
    for f in [cal / "rotor_landings.toml"] + sorted((cal / "holdout").glob("without_*rpm_landings.toml")):
        t = load_toml(f)
        assert t["ranges"] == ref["ranges"], f.name
        assert (t["samples"], t["seed"], t["ensemble"], t["t_end"]) == (ref["samples"], ref["seed"], ref["ensemble"],
                                                                       ref["t_end"]), f.name


def test_heldout_span_reads_the_drops_of_the_run_it_is_given(tmp_path):
    """The study judges 'DE forward in >= 7 of 8' on the fit's own ensemble size: a run with 16 drops
    per speed (calibration.json's ``ensemble``, or the space file it names) is judged on 14 of 16,
    not on the repository's space file's size (8 until session 34, 32 since session 35)."""
    import importlib.util

    path = Path(__file__).resolve().parents[1] / "docs" / "studies" / "heldout_span.py"
    spec = importlib.util.spec_from_file_location("heldout_span", path)
    hs = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(hs)
    default = Path(__file__).resolve().parents[1] / "scenarios" / "calibration" / "rotor_landings.toml"
    j = tmp_path / "calibration.json"
    j.write_text(json.dumps({"space": "x.toml", "ensemble": 16, "designs": []}))
    assert hs.run_drops(j, default) == 16
    space16 = tmp_path / "s16.toml"
    from rotorlanding.calibrate_run import load_space

    shipped = int(load_space(default)["ensemble"])  # the space file's own, whatever it ships
    assert shipped != 16
    space16.write_text(re.sub(r"(?m)^ensemble = \d+", "ensemble = 16", default.read_text()))
    j.write_text(json.dumps({"space": str(space16), "designs": []}))
    assert hs.run_drops(j, default) == 16
    j.write_text(json.dumps({"space": str(tmp_path / "gone.toml"), "designs": []}))
    assert hs.run_drops(j, default) == shipped
    row = {"design": 0, hs.KEYS[0]: 0.04, hs.KEYS[1]: 0.42, "fw3000_de_hz": 47.0, "fw3000_de_forward": 13,
           "fw3000_de_direction": "forward"}
    for c in ("fw3000", "fw7000", "fw10000"):
        row.update({f"err_{c}": 0.01, f"err_{c}_se": 0.01, f"err_{c}_de": 0.0, f"err_{c}_de_se": 0.03})
    assert not hs.heldout([row], 3000, 16)["within_noise"][0]["pass"]  # 13 of 16 < 14
    assert hs.heldout([row], 3000, 8)["within_noise"][0]["pass"]


def test_a_fit_records_the_de_whirl_shapes_per_case(tmp_path, monkeypatch):
    """Each design's row says on which shapes its drops whirled at the DE (cylindrical, conical), with
    their drops and median frequency: the 10000 rpm median follows that split (docs/calibration.md,
    session 27)."""

    forms = {"cylindrical": {"n": 5, "frequency_hz": 72.7}, "conical": {"n": 3, "frequency_hz": 79.3}}

    def fake_run_all(jobs, workers):
        return {i: {case.split("#")[0]: {"direction": "forward", "frequency_hz": 73.0, "fraction": 1.0,
                                         "de": {"counts": {"forward": 8}, "direction": "forward",
                                                "frequency_hz": 73.0, "forms": forms}}
                    for i, case, *_ in jobs} for i, *_ in jobs}

    _calibrate_faked(monkeypatch, tmp_path, fake_run_all,
                     'samples = 1\nseed = 1\ncases = ["fw10000"]\nensemble = 8\n'
                     '[ranges]\n"rotor.disks.4.outer_diameter" = {min = 0.40, max = 0.49}\n')
    row = next(csv.DictReader(open(tmp_path / "c" / "calibration.csv")))
    assert row["fw10000_de_shapes"] == "cylindrical 5 72.70; conical 3 79.30"


def test_a_fit_records_table2s_de_numbers_per_case_unscored(tmp_path, monkeypatch):
    """Each row carries the case's median DE displacement and force peaks (Table 2's numbers, forces
    on the rotor), and the score does not read them (score_force = false keeps them predictions)."""

    def fake_run_all(jobs, workers):
        base = {"direction": "forward", "frequency_hz": 65.0, "fraction": 1.0,
                "de": {"counts": {"forward": 8}, "direction": "forward", "frequency_hz": 65.0}}
        out = {}
        for i, case, *_ in jobs:
            k = 1.0 + i  # a design's numbers differ, so a mix-up between rows would show
            out.setdefault(i, {})[case.split("#")[0]] = {
                **base, "v_disp_range_m": [-3e-4 * k, 1.5e-4 * k], "v_force_range_n": [-500.0 * k, 4500.0 * k]}
        return out

    rows = _calibrate_faked(monkeypatch, tmp_path, fake_run_all,
                            'samples = 2\nseed = 1\ncases = ["fw7000"]\nensemble = 8\nscore_force = false\n'
                            '[ranges]\n"rotor.disks.4.outer_diameter" = {min = 0.40, max = 0.49}\n')
    for r in rows:
        k = 1.0 + r["design"]
        assert r["fw7000_v_disp_min_m"] == pytest.approx(-3e-4 * k)
        assert r["fw7000_v_disp_max_m"] == pytest.approx(1.5e-4 * k)
        assert r["fw7000_v_force_min_n"] == pytest.approx(-500.0 * k)
        assert r["fw7000_v_force_max_n"] == pytest.approx(4500.0 * k)
        assert "err_force" not in r
    # same frequency and share on both designs: equal scores although their forces differ
    assert rows[0]["score"] == rows[1]["score"]


def test_a_fit_read_off_a_stored_run_is_the_fit_the_space_would_run(tmp_path, monkeypatch):
    """``calibrate --from-run``: a space that scores two of the three Fig. 39 speeds of a stored
    three-speed run's designs gets, without landing, the table its own run gives (the held-out fits,
    session 40): the same order, scores, errors and noise set; mismatched spaces are refused."""
    from rotorlanding import calibrate_run as cal
    from rotorlanding.errors import InputError

    def fake_run_all(jobs, workers):
        out = {}
        for i, case, *_ in jobs:
            c = case.split("#")[0]
            f = {"fw3000": 40.0 + 3 * i, "fw7000": 70.0 - 2 * i, "fw10000": 77.0 + ((i * 7) % 5)}[c]
            fwd = 8 - (i + len(c)) % 3
            out.setdefault(i, {})[c] = {"direction": "forward", "frequency_hz": f, "fraction": 1.0,
                                        "de": {"counts": {"forward": fwd, "none": 8 - fwd}, "direction": "forward",
                                               "frequency_hz": f, "frequency_se_hz": 0.5 + 0.1 * i}}
        return out

    monkeypatch.setattr(cal, "_run_all", fake_run_all)
    head = 'samples = 6\nseed = 3\nensemble = 8\nscore_force = false\n'
    rng = '[ranges]\n"rotor.disks.4.outer_diameter" = {min = 0.40, max = 0.49}\n'
    (tmp_path / "all.toml").write_text(head + 'cases = ["fw3000", "fw7000", "fw10000"]\n' + rng)
    (tmp_path / "two.toml").write_text(head + 'cases = ["fw7000", "fw10000"]\n' + rng)
    cal.calibrate(tmp_path / "all.toml", tmp_path / "all", workers=1)
    ran = cal.calibrate(tmp_path / "two.toml", tmp_path / "two", workers=1)
    read = cal.calibrate_from_run(tmp_path / "two.toml", tmp_path / "all" / "calibration.json", tmp_path / "read")
    keys = ("design", "score", "score_se", "within_noise_of_best", "err_fw7000", "err_fw10000_de")
    assert [tuple(r[k] for k in keys) for r in read] == [tuple(r[k] for k in keys) for r in ran]
    assert not any(k.startswith("err_fw3000") for k in read[0])       # not part of this fit's score
    assert read[0]["fw3000_de_hz"] is not None                         # the held-out speed's landing, as data
    assert json.loads((tmp_path / "read" / "calibration.json").read_text())["cases"] == ["fw7000", "fw10000"]
    # another draw of designs, or a case the run did not land, is refused in one line
    (tmp_path / "seed.toml").write_text(head.replace("seed = 3", "seed = 4") + 'cases = ["fw7000"]\n' + rng)
    with pytest.raises(InputError, match="designs"):
        cal.calibrate_from_run(tmp_path / "seed.toml", tmp_path / "all" / "calibration.json", tmp_path / "x")
    (tmp_path / "bw.toml").write_text(head + 'cases = ["bw"]\n' + rng)
    with pytest.raises(InputError, match="every case"):
        cal.calibrate_from_run(tmp_path / "bw.toml", tmp_path / "all" / "calibration.json", tmp_path / "x")
    assert main(["calibrate", str(tmp_path / "bw.toml"), "--from-run", str(tmp_path / "all" / "calibration.json"),
                 "--out", str(tmp_path / "y")]) == 2


@pytest.mark.parametrize("rpm", [3000, 7000, 10000])
def test_the_stored_heldout_fits_are_the_stored_rotor_fit_read_on_two_speeds(tmp_path, rpm):
    """The held-out fits validate lands (scenarios/calibration/holdout/without_<rpm>rpm/) are the rotor
    fit's stored run (docs/studies/heldout_span/fit/) scored on the other two speeds: read off it with
    ``calibrate_from_run``, the same designs in the same order with the same scores (session 40: the
    three held-out runs, 4608 landings, agreed to the bit with the three-speed run's parts)."""
    from rotorlanding.calibrate_run import calibrate_from_run

    root = Path(__file__).resolve().parents[1]
    read = calibrate_from_run(root / "scenarios" / "calibration" / "holdout" / f"without_{rpm}rpm_landings.toml",
                              root / "docs" / "studies" / "heldout_span" / "fit" / "calibration.json", tmp_path)
    stored = json.loads((root / "scenarios" / "calibration" / "holdout" / f"without_{rpm}rpm" /
                         "calibration.json").read_text())["designs"]
    assert [(r["design"], r["score"], r["within_noise_of_best"]) for r in read] == \
        [(r["design"], r["score"], r["within_noise_of_best"]) for r in stored]
