"""Paper scenarios. Default run: short versions asserting the whirl class where our rig already
reproduces the paper. `pytest -m paper`: the full validation (every acceptance check of the
paper-reproduction issue); it fails until the rig is calibrated (see docs/validation.md)."""

from pathlib import Path

import pytest

from rotorlanding.cli import main
from rotorlanding.postprocess import evaluate, summarize
from rotorlanding.run import simulate
from rotorlanding.scenario import load_scenario

PAPER = Path(__file__).resolve().parents[1] / "scenarios" / "paper"


def _whirl(fname, t_end, sets=()):
    sc = load_scenario(PAPER / fname, list(sets) + [f"operating.t_end={t_end}"])
    spec, t, q, v, info = simulate(sc, progress=False)
    assert info["complete"]
    return summarize(spec, t, evaluate(spec, t, q, v))


def test_no_whirl_landing_short():
    s = _whirl("no_whirl_landing.toml", 0.5)
    assert s["whirl"]["direction"] == "none"
    assert s["bearings"]["DE"]["final_race_speed_rpm"] > 0.95 * s["speeds"]["final_rotor_rpm"]


def test_combined_landing_whirls_forward_and_axial_rub_is_the_cause_short():
    s = _whirl("forward_whirl_landing.toml", 0.4)
    assert s["whirl"]["direction"] == "forward"
    off = _whirl("forward_whirl_landing.toml", 0.4, ["effects.axial_rub=false"])
    assert off["whirl"]["direction"] != "forward"


def test_combined_landing_at_3000rpm_whirls_forward_at_the_thrust_face_bearing_short():
    """At 3000 rpm the thrust-face friction drives the NDE journal round its clearance at about
    0.93 x spin while the loaded DE journal stays down: the landing whirls forward (Fig. 39's
    48 Hz), found at the NDE; without axial rub it does not."""
    s = _whirl("forward_whirl_3000rpm.toml", 0.4)
    nde = s["whirl"]["per_bearing"]["NDE"]
    assert nde["direction"] == "forward" and 40.0 < nde["frequency_hz"] < 50.0, nde
    assert s["whirl"]["direction"] == "forward", s["whirl"]
    off = _whirl("forward_whirl_3000rpm.toml", 0.4, ["effects.axial_rub=false"])
    assert all(w["direction"] != "forward" for w in off["whirl"]["per_bearing"].values()), off["whirl"]


def test_worn_bearing_landing_whirls_backward_and_the_worn_drag_is_the_cause_short():
    """Short backward-whirl landing, judged as the validation judges it: drops from a 5 um circle
    (the centred drop is mirror-symmetric and its whirl hangs on round-off). Without the worn
    bearing's drag the same mu_rad = 0.3 landing does not whirl backward (our causal claim)."""
    from rotorlanding.ensemble import drop_offsets, ensemble_stats

    def members(extra):
        out = []
        for sets in drop_offsets(4):
            w = _whirl("backward_whirl_landing.toml", 0.5, sets + extra)["whirl"]
            out.append({"direction": w["direction"], "frequency_hz": w["frequency_hz"], "onset_s": w["onset_s"]})
        return ensemble_stats(out)

    worn = members([])
    assert worn["direction"] == "backward" and worn["fraction"] >= 0.75, worn
    assert 40.0 < worn["frequency_hz"] < 60.0, worn
    new = members(["effects.worn_bearing_drag=false"])
    assert new["counts"].get("backward", 0) == 0, new


@pytest.mark.paper
def test_full_paper_validation(tmp_path):
    from rotorlanding.validate import validate

    res = validate(tmp_path, docs=False)
    failed = [c["check"] for c in res["evaluation"]["checks"] if not c["pass"]]
    assert not failed, failed


def test_paper_scenarios_found_from_the_checkout_after_a_regular_install(tmp_path, monkeypatch):
    # a non-editable install puts the package in site-packages, without scenarios/: validate then
    # uses the checkout it is run from, and elsewhere says so in one line instead of a dead worker
    import rotorlanding.validate as v
    from rotorlanding.errors import InputError

    root = Path(__file__).resolve().parents[1]
    monkeypatch.setattr(v, "__file__", str(tmp_path / "site-packages" / "rotorlanding" / "validate.py"))
    monkeypatch.chdir(root)
    assert v.project_root() == root and v.paper_dir().is_dir()
    monkeypatch.chdir(tmp_path)
    with pytest.raises(InputError, match="scenarios/paper"):
        v.project_root()
    assert main(["validate", "--out", str(tmp_path / "v"), "--quick"]) == 2


def test_validation_judges_a_case_on_its_ensemble_not_its_centred_drop():
    """A centred drop that whirls while most drops of its ensemble do not fails the check: the
    ensemble's majority class is what a check judges (numbers: member medians)."""
    from rotorlanding.validate import CASES, evaluate_cases

    def case(direction, f=None, onset=None):
        return {"whirl": {"direction": direction, "frequency_hz": f, "onset_s": onset},
                "bearings": {"DE": {"vertical_displacement_range_m": [-3e-4, 2.5e-4],
                                    "vertical_force_range_n": [-1e3, 5e3], "final_race_speed_rpm": 6990.0}},
                "speeds": {"final_rotor_rpm": 7000.0}}

    s = {"no_whirl": case("none"), "backward_whirl": case("backward", 50.0, 0.4),
         "forward_3000": case("forward", 46.0, 0.1), "forward_7000": case("forward", 66.0, 0.1),
         "forward_10000": case("forward", 75.0, 0.1), "forward_7000_no_axial_rub": case("none")}
    assert set(s) == set(CASES)
    centred = evaluate_cases(s)
    assert centred["passed"] == centred["total"] == 15

    def ens(direction, counts, f=None):
        return {"n": 8, "direction": direction, "fraction": max(counts.values()) / 8, "counts": counts,
                "frequency_hz": f, "onset_s": 0.1 if f else None, "v_disp_range_m": [-3e-4, 2.5e-4],
                "v_force_range_n": [-1e3, 5e3], "race_to_rotor": 0.9}

    ensembles = {"no_whirl": ens("none", {"none": 8}),
                 "forward_3000": ens("none", {"none": 7, "forward": 1}),
                 "forward_7000": ens("forward", {"forward": 8}, 66.0)}
    judged = {c["check"]: c for c in evaluate_cases(s, ensembles)["checks"]}
    assert not judged["forward 3000 rpm: direction"]["pass"]
    assert judged["forward 3000 rpm: direction"]["ours"] == "none (88 % of 8)"
    assert not judged["forward 3000 rpm: frequency"]["pass"] and not judged["forward: frequency rises with speed"]["pass"]
    assert judged["forward 7000 rpm: direction"]["pass"] and judged["forward 10000 rpm: frequency"]["pass"]
    # the race check reads the members' median too (centred drop: 6990 / 7000 passes)
    assert judged["no-whirl: no sustained whirl"]["pass"]
    assert not judged["no-whirl: inner race reaches rotor speed"]["pass"]
    assert judged["no-whirl: inner race reaches rotor speed"]["ours"] == 0.9


def test_backward_onset_note_reads_the_calibrated_growth_angle():
    """The report says the onset row is a calibrated reproduction exactly when the paper's backward
    scenario has a developing worn drag, with the angle from that file."""
    import rotorlanding.validate as v
    from rotorlanding.scenario import load_scenario

    sc = load_scenario(v.paper_dir() / v.CASES["backward_whirl"][0])
    grow = sc.bearings["DE"].worn_drag_growth_angle
    note = v._onset_note()
    if grow > 0:
        assert f"growth angle {grow:.3g} rad" in note and "calibrated" in note
    else:
        assert note == ""
