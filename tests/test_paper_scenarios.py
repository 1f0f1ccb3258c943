"""Paper scenarios. Default run: short versions asserting the whirl class where our rig already
reproduces the paper. `pytest -m paper`: the full validation (every acceptance check of the
paper-reproduction issue); it fails until the rig is calibrated (see docs/validation.md)."""

from pathlib import Path

import numpy as np
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
    # 0.6 s: since session 31's fitted ribbon damping (c_rib 3907 N s/m) the DE orbit is still growing at
    # 0.4 s (NDE / DE 2.37 there, 1.78 at 0.6 s, 1.65 over validate's full 1.0 s)
    s = _whirl("forward_whirl_landing.toml", 0.6)
    assert s["whirl"]["direction"] == "forward"
    # both journals go round together at 7000 rpm (every drop of every rotor design of the fit:
    # docs/calibration.md, session 27), with the NDE's orbit the larger (the face rub drives it)
    assert all(w["direction"] == "forward" for w in s["whirl"]["per_bearing"].values()), s["whirl"]
    sh = s["whirl"]["shape"]
    assert sh["against"] == "NDE" and sh["form"] == "cylindrical", sh
    assert 1.0 < sh["amplitude_ratio"] < 2.0, sh
    off = _whirl("forward_whirl_landing.toml", 0.4, ["effects.axial_rub=false"])
    assert off["whirl"]["direction"] != "forward"
    assert "shape" not in off["whirl"] or off["whirl"]["direction"] != "none"


def test_combined_landing_at_3000rpm_whirls_forward_at_the_thrust_face_bearing_short():
    """At 3000 rpm the thrust-face friction drives the rotor round its clearances: the landing whirls
    forward near Fig. 39's 48 Hz, at the DE journal where the paper measured (since the session-28 rotor;
    on the session-15 rotor the centred drop whirled at the NDE only); without axial rub it does not.
    The scenario's full 1.0 s, four drops from the 5 um circle as validate lands them (the centred drop
    is mirror-symmetric and hangs on round-off: with the 1e5 N/m coupling of session 40 it locks at
    60 Hz while validate's 128 drops whirl at 45.0 Hz, conical in most)."""
    from rotorlanding.ensemble import drop_offsets, ensemble_stats

    def de_whirls(extra=()):
        out = []
        for sets in drop_offsets(4):
            s = _whirl("forward_whirl_3000rpm.toml", 1.0, sets + list(extra))
            de = s["whirl"]["per_bearing"]["DE"]
            out.append({"direction": de["direction"], "frequency_hz": de["frequency_hz"], "onset_s": de["onset_s"],
                        "any_forward": any(w["direction"] == "forward" for w in s["whirl"]["per_bearing"].values())})
        return out

    on = de_whirls()
    stats = ensemble_stats(on)
    assert stats["counts"].get("forward", 0) == 4 and 44.0 < stats["frequency_hz"] < 52.0, stats
    off = de_whirls(["effects.axial_rub=false"])
    assert not any(m["any_forward"] for m in off), off


def test_worn_bearing_landing_whirls_backward_and_the_worn_drag_raises_its_share_short():
    """Short backward-whirl landing, judged as the validation judges it: drops from a 5 um circle
    (the centred drop is mirror-symmetric and its whirl hangs on round-off). Without the worn
    bearing's drag the same mu_rad = 0.3 landing whirls backward in fewer drops. (Until session 29 the
    claim was "in none"; on the session-30 rotor 2 of these 4 do, also at session 31's fitted ribbon
    damping: a weaker claim, the strict xfail below keeps the old one.)
    The full 1.2 s record, validate's: the calibrated drag develops over the race's first turns
    (session 31's fit, 2.79 N m over 98 rad with c_rib 3907 N s/m: 32 of 32 backward from a median 0.025 s;
    session 29's 5.94 N m whirled from 0.41 s; since session 41, with the 1e5 N/m motor coupling, 2.93 N m over
    200 rad with c_rib 2363 N s/m)."""
    from rotorlanding.ensemble import drop_offsets, ensemble_stats

    def members(extra):
        out = []
        for sets in drop_offsets(4):
            w = _whirl("backward_whirl_landing.toml", 1.2, sets + extra)["whirl"]
            out.append({"direction": w["direction"], "frequency_hz": w["frequency_hz"], "onset_s": w["onset_s"]})
        return ensemble_stats(out)

    worn = members([])
    assert worn["direction"] == "backward" and worn["fraction"] >= 0.75, worn
    assert 40.0 < worn["frequency_hz"] < 60.0, worn
    new = members(["effects.worn_bearing_drag=false"])
    # the worn drag raises the backward share (session 30 rig, session 31's c_rib: 4 of 4 with it, 2 of 4 without)
    assert new["counts"].get("backward", 0) < worn["counts"]["backward"], new


@pytest.mark.xfail(strict=True, reason="session 30 rig (and session 31's fitted ribbon damping): without the worn drag "
                   "the mu_rad 0.3 landing whirls backward in 2 of these 4 drops (0 of 4 on the session-28 rotor); "
                   "docs/calibration.md, Sessions 30 and 31")
def test_without_the_worn_drag_the_backward_landing_does_not_whirl_backward():
    """The causal claim of the backward calibration as it stood until session 29: without the worn
    bearing's drag the same mu_rad = 0.3 landing does not whirl backward. On the session-30 rotor
    radial friction alone whirls some drops backward (the paper's own switch, partly)."""
    from rotorlanding.ensemble import drop_offsets

    counts = [_whirl("backward_whirl_landing.toml", 1.2, sets + ["effects.worn_bearing_drag=false"])["whirl"]["direction"]
              for sets in drop_offsets(4)]
    assert counts.count("backward") == 0, counts


def _switch_classes(mu, n=8):
    from collections import Counter

    from rotorlanding.ensemble import drop_offsets

    return Counter(_whirl("backward_whirl_landing.toml", 1.2, sets + [f"contact.mu_rad={mu}"])["whirl"]["direction"]
                   for sets in drop_offsets(n))


def test_worn_de_bearing_whirls_backward_at_high_radial_friction():
    """Table 1's switch, its backward side: the worn DE bearing whirls backward at mu_rad 0.3 in >= 7 of 8
    drops (the worn fit of session 31: 32 of 32). The calm side is the test below."""
    worn = _switch_classes(0.3)
    assert worn.get("backward", 0) >= 7, worn


def test_worn_de_bearing_radial_friction_decides_the_backward_whirl():
    """Table 1's switch (issue 15): the same worn DE bearing lands calm at mu_rad 0.15 and whirls
    backward at 0.3, everything else equal; 8 drops each from the 5 um circle, the full 1.2 s
    record (a whirl at 0.15 may start late). The rule here is the validation's, 7 of 8, on each side
    (the backward side is the test above).
    It held on the session-28 rotor at the then assumed ribbon damping c_rib 2000 N s/m; on the session-30
    rotor at that c_rib a quarter of the drops whirled at 0.15 (a strict xfail until session 31). Since
    session 31 C_rib is fitted with the worn drag on both sides of the switch (scenarios/calibration/
    worn_bearing.toml: 3907 N s/m, 2.79 N m, 98 rad; 32 of 32 calm and 32 of 32 backward in the fit; since
    session 41, with the motor coupling at 1e5 N/m, 2363 N s/m, 2.93 N m, 200 rad):
    the ribbon's damping sets the friction at which a sliding contact feeds the backward whirl
    (docs/calibration.md, "Session 31"), so this side is now fitted, not predicted."""
    calm = _switch_classes(0.15)
    assert calm.get("none", 0) >= 7, calm


@pytest.mark.paper
def test_full_paper_validation(tmp_path):
    from rotorlanding.validate import validate

    res = validate(tmp_path)
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


def _member(direction, f=None, onset=None, de=None, disp=(-3e-4, 2.5e-4), force=(-1e3, 4.5e3), race=0.99):
    """An ensemble member as ``ensemble.member_result`` makes it; ``de``: the DE journal's own class."""
    de = direction if de is None else de
    return {"direction": direction, "bearing": "DE" if de == direction else "NDE", "frequency_hz": f,
            "onset_s": onset, "end_s": None, "persistence": 1.0 if f else None, "de_direction": de,
            "de_frequency_hz": f if de != "none" else None, "v_disp_range_m": list(disp),
            "v_force_range_n": list(force), "race_to_rotor": race}


def _paper_ensembles(**changes):
    from rotorlanding.ensemble import ensemble_stats

    ens = {"no_whirl": [_member("none")] * 8,
           "backward_whirl": [_member("backward", 49.0 + 0.1 * k, 0.4, disp=(-4e-4, 2e-4)) for k in range(16)],
           "forward_3000": [_member("forward", 48.0, 0.1, disp=(-3e-4, 1.5e-4))] * 8,
           "forward_7000": [_member("forward", 65.0 + 0.1 * k, 0.1, disp=(-3e-4, 1.5e-4), force=(-0.5e3, 4.5e3))
                            for k in range(8)],
           "forward_10000": [_member("forward", 77.0, 0.1)] * 8,
           "forward_7000_no_axial_rub": [_member("none")] * 8}
    ens.update(changes)
    return {k: ensemble_stats(m) for k, m in ens.items()}


def test_validation_judges_the_ensemble_and_the_paper_measuring_node():
    """Checks read the ensemble (class shares, member medians), and Fig. 39 reads the DE journal
    as the paper measured it: a 3000 rpm landing that whirls at the NDE while the DE journal stays
    down fails its row and direction check, however the landing as a whole is classed."""
    from rotorlanding.validate import CASES, evaluate_cases

    s = {k: None for k in CASES}
    ok = {c["check"]: c for c in evaluate_cases(s, _paper_ensembles())["checks"]}
    assert all(c["pass"] for c in ok.values()), [k for k, c in ok.items() if not c["pass"]]
    assert len([c for c in ok.values() if c["group"] == "table"]) == 11  # every number of Tables 1-2 and Fig. 39
    nde_only = [_member("forward", 46.0, 0.0, de="none")] * 7 + [_member("forward", 45.0, 0.1)]
    slow_race = [_member("none", race=0.9)] * 8
    bad = {c["check"]: c for c in evaluate_cases(s, _paper_ensembles(forward_3000=nde_only, no_whirl=slow_race))["checks"]}
    assert not bad["combined landing 3000 rpm whirls forward at the DE"]["pass"]
    assert bad["combined landing 3000 rpm whirls forward at the DE"]["ours"] == "1 of 8"
    assert not bad["Fig. 39: forward whirl frequency at the DE, 3000 rpm"]["pass"]
    assert not bad["forward whirl frequency rises with speed (DE)"]["pass"]
    assert not bad["no-whirl: inner race reaches rotor speed"]["pass"] and bad["no-whirl: inner race reaches rotor speed"]["ours"] == 0.9
    assert bad["combined landing 7000 rpm whirls forward at the DE"]["pass"]
    # every statistical verdict carries its margin and the margin's standard error
    rise = ok["forward whirl frequency rises with speed (DE)"]
    assert rise["margin"] == pytest.approx(77.0 - 65.35) and rise["se"] > 0  # the smaller step; 7000 rpm: median of 65.0..65.7
    assert not rise["within_noise"]
    race = ok["no-whirl: inner race reaches rotor speed"]
    assert race["margin"] is not None and race["se"] is not None
    # spread members: the race ratio's median error is the median rule's, and a step of the rising
    # frequencies inside its noise flags the verdict though the other step is clear of it
    spread = {"no_whirl": [_member("none", race=0.972 + 0.01 * (k - 3.5)) for k in range(8)],
              "forward_7000": [_member("forward", 75.5 + 2.0 * (k - 3.5), 0.1) for k in range(8)]}
    c = {c["check"]: c for c in evaluate_cases(s, _paper_ensembles(**spread))["checks"]}
    race = c["no-whirl: inner race reaches rotor speed"]
    assert race["se"] == pytest.approx(1.2533 * np.std([0.01 * (k - 3.5) for k in range(8)], ddof=1) / 8 ** 0.5,
                                       rel=1e-3)
    assert race["pass"] and race["margin"] == pytest.approx(0.002) and race["within_noise"]
    rise = c["forward whirl frequency rises with speed (DE)"]
    assert rise["pass"] and rise["margin"] == pytest.approx(1.5)  # 77 - 75.5, the smaller step
    assert rise["within_noise"] and rise["se"] > 1.5  # the 7000 rpm median's error; 75.5 - 48 is clear of it


def test_onset_spread_counts_drops_in_the_paper_band():
    """The onset note counts the backward drops that start inside Table 1's band (0.4 +/- 0.04 s, the
    band rule) and from 0.2 s on; calm drops and drops without an onset are not counted."""
    from rotorlanding.validate import onset_spread

    ms = [{"direction": "backward", "onset_s": t} for t in (0.0, 0.025, 0.19, 0.2, 0.361, 0.439, 0.45)]
    ms += [{"direction": "none", "onset_s": None}, {"direction": "backward", "onset_s": None},
           {"direction": "forward", "onset_s": 0.4}]
    assert onset_spread(ms) == ("Of the 7 backward drops, 2 start inside the paper's band (0.36-0.44 s) "
                                "and 4 from 0.2 s on.")
    assert onset_spread([{"direction": "none", "onset_s": None}]) == ""


def test_a_verdict_over_its_fits_designs_says_where_it_hangs_on_the_pick():
    """evaluate_cases with ``over_fit``: a passing table row that only some designs within its fit's
    noise pass, and a class check that every one passes, get ``robust``; the report's verdict names the
    first as hanging on the fit's pick and leaves the second plain; a row without a record has none."""
    from rotorlanding.validate import CASES, _verdict, evaluate_cases

    s = {k: None for k in CASES}
    ens = _paper_ensembles(forward_7000=[_member("forward", 65.0, 0.1, disp=(-3e-4, 1.5e-4), force=(-0.5e3, 4.5e3))] * 8)
    over = {"rows": {"t2_force_max": {"in_band": 7, "n_designs": 14, "fit": "f"}},
            "causes": {"combined landing 7000 rpm whirls forward at the DE": {"passing": 14, "n_designs": 14, "fit": "f"}}}
    c = {c["check"]: c for c in evaluate_cases(s, ens, over_fit=over)["checks"]}
    row = c["Table 2: DE vertical force on the rotor max"]
    assert row["pass"] and row["robust"] == {"passing": 7, "n": 14, "holds": False, "fit": "f"}
    assert _verdict(row) == "PASS (hangs on the fit's pick: 7 of 14 designs within its noise pass)"
    de = c["combined landing 7000 rpm whirls forward at the DE"]
    assert de["pass"] and de["robust"]["holds"] and _verdict(de) == "PASS"
    assert c["Table 2: DE vertical force on the rotor min"]["robust"] is None

def test_band_rule_margins_and_provenance():
    """Band = max(10 % of the experiment, the paper's own simulation error); a value just outside
    fails, just inside passes; the margin's standard error flags a verdict that hangs on noise;
    the Fig. 39 rows are labelled fitted because rotor_modes.toml targets them."""
    from rotorlanding.validate import CASES, band, evaluate_cases, provenance

    assert band(-1.5e3, -0.5e3) == pytest.approx(1.0e3)  # the example: Table 2 force minimum
    assert band(4.5e3, 4.5e3) == pytest.approx(450.0)
    assert band(51.0, 49.0) == pytest.approx(4.9)
    s = {k: None for k in CASES}
    inside = _paper_ensembles(forward_7000=[_member("forward", 65.0, 0.1, disp=(-3e-4, 1.5e-4), force=(-1.45e3, 4.5e3))] * 8)
    outside = _paper_ensembles(forward_7000=[_member("forward", 65.0, 0.1, disp=(-3e-4, 1.5e-4), force=(-1.55e3, 4.5e3))] * 8)
    row = "Table 2: DE vertical force on the rotor min"
    assert {c["check"]: c for c in evaluate_cases(s, inside)["checks"]}[row]["pass"]
    out = {c["check"]: c for c in evaluate_cases(s, outside)["checks"]}[row]
    assert not out["pass"] and out["margin"] == pytest.approx(-50.0) and out["closer_than_paper"] is False
    # scattered members: the median's standard error exceeds the 4 % margin of a 1.5 % frequency error
    noisy = [_member("forward", f, 0.1, disp=(-3e-4, 1.5e-4), force=(-0.5e3, 4.5e3)) for f in (50, 58, 66, 66, 66, 74, 82, 90)]
    c = {c["check"]: c for c in evaluate_cases(s, _paper_ensembles(forward_7000=noisy))["checks"]}[
        "Fig. 39: forward whirl frequency at the DE, 7000 rpm"]
    assert c["pass"] and c["se"] > c["margin"] > 0 and c["within_noise"]
    # closer than the paper's simulation (67 Hz, 2 Hz off) by 1 Hz, inside that standard error: said so
    assert c["closer_than_paper"] and c["closer_margin"] == pytest.approx(1.0) and c["closer_within_noise"]
    assert not out["closer_within_noise"]  # identical members: no scatter, the comparison stands
    prov = provenance()
    assert prov["fig39_7000"].startswith("fitted") and prov["t1_disp_max"] == "predicted"
    assert prov["t2_force_min"] == "predicted"
    # the rotor is fitted by landing on ensembles of drops (32 per speed since session 35): the DE's forward share at each speed is in
    # its score, so the three "whirls forward at the DE" checks are fitted too; its force is not scored
    assert all(prov[f"fw_de_{r}"].startswith("fitted (scenarios/calibration/rotor_landings.toml") for r in (3000, 7000, 10000))
    assert prov["t2_force_max"] == "predicted"


def test_orbit_reading_splits_the_displacement_rows_into_centre_and_half_range():
    """Each table's displacement max and min read as the orbit's centre and half-range, for the
    experiment (Table 1: +0.2 / -0.4 mm, centre -0.1, half-range 0.3), the paper's simulation
    (+0.25 / -0.28) and ours (the ensemble's medians), checked against the hand computation."""
    from rotorlanding.validate import CASES, evaluate_cases, orbit_readings

    s = {k: None for k in CASES}
    ens = _paper_ensembles(backward_whirl=[_member("backward", 49.0, 0.4, disp=(-3.4e-4, 3.1e-4))] * 16,
                           forward_7000=[_member("forward", 65.0, 0.1, disp=(-4.2e-4, 4.0e-4), force=(-9e3, 10e3))] * 8)
    ev = evaluate_cases(s, ens)
    t1, t2, _ = orbit_readings(ev["checks"])
    assert t1["table"] == "Table 1" and t2["table"] == "Table 2"
    assert t1["experimental"]["centre"] == pytest.approx(-1e-4) and t1["experimental"]["half_range"] == pytest.approx(3e-4)
    assert t1["paper_simulated"]["centre"] == pytest.approx(-1.5e-5)
    assert t1["paper_simulated"]["half_range"] == pytest.approx(2.65e-4)
    assert t1["ours"]["centre"] == pytest.approx(-1.5e-5) and t1["ours"]["half_range"] == pytest.approx(3.25e-4)
    assert t1["half_range_error"] == pytest.approx(0.25e-4 / 3e-4)
    # Table 2: experiment +0.15 / -0.3 mm
    assert t2["experimental"]["centre"] == pytest.approx(-7.5e-5) and t2["ours"]["half_range"] == pytest.approx(4.1e-4)
    assert t2["half_range_error"] == pytest.approx((4.1e-4 - 2.25e-4) / 2.25e-4)
    # a table whose displacement rows are missing gives no reading
    f2 = orbit_readings(ev["checks"])[2]
    assert orbit_readings([c for c in ev["checks"] if not c["check"].startswith("Table 1")]) == [t2, f2]
    # Table 2's force rows the same way: experiment +4.5 / -0.5 kN, centre 2 kN; ours (-9 / +10 kN) 0.5 kN
    assert f2["table"] == "Table 2, force" and f2["experimental"]["centre"] == pytest.approx(2.0e3)
    assert f2["paper_simulated"]["centre"] == pytest.approx(1.5e3) and f2["ours"]["centre"] == pytest.approx(0.5e3)


def test_force_centre_reading_states_the_static_load_both_force_rows_need():
    """Table 2's force rows in band need (max + min) / 2 >= the two bands' low ends averaged:
    (4.5 - 0.45 + (-0.5 - 1.0)) / 2 = 1.275 kN, given against ours (members -3 / +4 kN: 0.5 kN) with the
    rotor's static DE load and, when measured, the DE's time-mean force; nothing without the load."""
    from rotorlanding.validate import (
        CASES,
        evaluate_cases,
        force_centre_lines,
        orbit_readings,
    )

    ev = evaluate_cases({k: None for k in CASES}, _paper_ensembles(
        forward_7000=[_member("forward", 65.0, 0.1, force=(-3.0e3, 4.0e3))] * 8))
    orbits = orbit_readings(ev["checks"])
    (text,) = [x for x in force_centre_lines(orbits, {"DE_sleeve": 250.0}) if x]
    assert "(4.05 + (-1.5)) / 2 = 1.27 kN of any signal, 2.5 times ours" in text  # 1275 / 500
    assert "ours is 0.5 kN" in text and "carries 0.25 kN with the rotor on the levitated axis" in text and "time-mean force over" not in text
    mean = {"drop": 3, "from_s": 0.1, "mean_n": 240.0}
    (text,) = [x for x in force_centre_lines(orbits, {"DE_sleeve": 250.0}, mean=mean) if x]
    assert "whirl (drop 3, from 0.1 s) is 0.24 kN" in text
    assert force_centre_lines(orbits, None) == [] and force_centre_lines(orbits, {"NDE_sleeve": 700.0}) == []
    assert force_centre_lines(orbits, {"DE_sleeve": 0.0}) == []
    # with the support's stiffness, the displacement centres as loads: W = -centre K_s (Table 2: experiment
    # -0.075 mm, the members' -0.025 mm, at 4e7 N/m: 3 kN and 1 kN)
    (text,) = [x for x in force_centre_lines(orbits, {"DE_sleeve": 250.0}, support_n_m=4e7) if x]
    assert "Table 2: the experiment's -0.075 mm is 3 kN, ours -0.025 mm is 1 kN" in text
    assert "Table 1: the experiment's -0.1 mm is 4 kN" in text  # Table 1: +0.2 / -0.4 mm


def test_static_support_loads_of_the_rig_rotor_carry_its_weight():
    """modefit.static_support_loads: the rig rotor's support reactions sum to its weight, the
    DE sleeve's being validate's reading of Table 2's force centre."""
    from rotorlanding.config import load_toml
    from rotorlanding.modefit import static_support_loads
    from rotorlanding.rotor import rotor_from_dict
    from rotorlanding.timoshenko import GRAVITY
    from rotorlanding.validate import project_root, static_loads

    loads = static_loads()
    assert set(loads) >= {"DE_sleeve", "NDE_sleeve"} and 0 < loads["DE_sleeve"] < loads["NDE_sleeve"]
    rig = load_toml(project_root() / "scenarios" / "rig_rotor.toml")
    assert sum(static_support_loads(rig).values()) == pytest.approx(rotor_from_dict(rig).mass * GRAVITY, rel=1e-12)


def test_heldout_verdict_is_flagged_when_its_share_of_drops_hangs_on_noise(monkeypatch):
    """A held-out speed has two margins, the frequency's and the share of drops': 7 of 8 forward at
    the right frequency passes with no margin in drops (s.e. 0.94), so it is flagged within noise;
    16 of 16 is not; 6 of 8 fails. (The stored fit's pick is set aside: its own rule is tested below.)"""
    import rotorlanding.validate as v
    from rotorlanding.validate import CASES, evaluate_cases

    monkeypatch.setattr(v, "heldout_pick_positions", lambda rpm: [])

    s = {k: None for k in CASES}

    def held(members):
        ev = evaluate_cases(s, _paper_ensembles(heldout_10000=members))
        return next(c for c in ev["checks"] if c["group"] == "held-out")

    c = held([_member("forward", 77.0, 0.1)] * 7 + [_member("backward", 60.0, 0.1)])
    assert c["pass"] and c["class_margin"] == 0 and c["within_noise"] and c["margin"] > c["se"]
    c = held([_member("forward", 77.0 + 0.1 * k, 0.1) for k in range(16)])
    assert c["pass"] and c["class_margin"] == 2 and not c["within_noise"]
    c = held([_member("forward", 77.0, 0.1)] * 6 + [_member("backward", 60.0, 0.1)] * 2)
    assert not c["pass"] and c["class_margin"] == -1


def test_heldout_row_fails_when_the_fits_pick_sits_on_its_bound(monkeypatch):
    """A held-out prediction whose fit stopped on a bound is not a prediction: the same 16 drops at the
    right frequency pass with the pick inside its bounds and fail, naming the value, with it on one
    (validate.heldout_pick_positions; the rig table's rule for the adopted fit)."""
    import rotorlanding.validate as v

    s = {k: None for k in v.CASES}
    members = [_member("forward", 77.0 + 0.1 * k, 0.1) for k in range(16)]
    inside = [{"key": "rotor.sections.3.outer_diameter", "value": 0.0366, "bound_position": 0.046,
               "search_position": 0.26, "on_bound": False}]
    monkeypatch.setattr(v, "heldout_pick_positions", lambda rpm: inside)
    c = next(c for c in v.evaluate_cases(s, _paper_ensembles(heldout_10000=members))["checks"] if c["group"] == "held-out")
    assert c["pass"] and "ON ITS BOUND" not in c["ours"]
    on = [dict(inside[0], value=0.03563, bound_position=0.018, on_bound=True),
          {"key": "rotor.disks.4.outer_diameter", "value": 0.4, "bound_position": None, "search_position": 0.5,
           "on_bound": True}]
    monkeypatch.setattr(v, "heldout_pick_positions", lambda rpm: on)
    c = next(c for c in v.evaluate_cases(s, _paper_ensembles(heldout_10000=members))["checks"] if c["group"] == "held-out")
    assert not c["pass"] and "ON ITS BOUND: `rotor.sections.3.outer_diameter` 0.03563 at 1.8% of its bound" in c["ours"]
    assert "`rotor.disks.4.outer_diameter` 0.4 at no sourced bound" in c["ours"]


def test_heldout_verdict_says_when_it_hangs_on_the_fits_pick(tmp_path, monkeypatch):
    """A held-out prediction judged over every design its fit cannot tell from its best
    (docs/studies/heldout_span): a pass that some of those designs reverse is marked as hanging on
    the fit's pick, a pass they all share is not; the count line says how many hold."""
    import json

    import rotorlanding.validate as v

    (tmp_path / "docs" / "studies" / "heldout_span").mkdir(parents=True)
    span = {"heldout": [{"rpm": 10000, "first": 8, "passing": 8, "within_noise": [
        {"error": -0.04, "pass": True}] * 8 + [{"error": None, "pass": False}] * 9}]}
    (tmp_path / "docs" / "studies" / "heldout_span" / "heldout_span.json").write_text(json.dumps(span))
    paper = v.paper_dir()  # the paper's numbers and scenarios stay the checkout's
    monkeypatch.setattr(v, "project_root", lambda: tmp_path)
    monkeypatch.setattr(v, "paper_dir", lambda: paper)
    monkeypatch.setattr(v, "_heldout_first", lambda rpm: 8)
    s = {k: None for k in v.CASES}
    ev = v.evaluate_cases(s, _paper_ensembles(heldout_10000=[_member("forward", 77.0 + 0.1 * k, 0.1) for k in range(16)]))
    c = next(c for c in ev["checks"] if c["group"] == "held-out")
    assert c["pass"] and c["robust"]["passing"] == 8 and c["robust"]["n"] == 17 and not c["robust"]["holds"]
    assert "hangs on the fit's pick: 8 of 17" in v._verdict(c)
    assert "(0 of them holding over every design" in v.counts_line(ev)
    span["heldout"][0]["within_noise"] = [{"error": -0.04, "pass": True}] * 8
    (tmp_path / "docs" / "studies" / "heldout_span" / "heldout_span.json").write_text(json.dumps(span))
    ev = v.evaluate_cases(s, _paper_ensembles(heldout_10000=[_member("forward", 77.0 + 0.1 * k, 0.1) for k in range(16)]))
    c = next(c for c in ev["checks"] if c["group"] == "held-out")
    assert c["robust"]["holds"] and v._verdict(c) == "PASS"
    assert "(1 of them holding over every design" in v.counts_line(ev)


def test_shipped_heldout_study_matches_the_shipped_heldout_fits():
    """docs/studies/heldout_span was made from the same install's full fit as the stored held-out
    fits: each held-out fit's first design is the study's (else validate's span column would
    describe another fit), and each study has designs within its fit's noise to judge."""
    import rotorlanding.validate as v

    span = v.heldout_span()
    assert sorted(span) == [3000, 7000, 10000]
    for rpm, sp in span.items():
        assert sp["first"] == v._heldout_first(rpm), rpm
        assert sp["n"] >= 1 and 0 <= sp["passing"] <= sp["n"]


def test_class_verdict_counts_drops_with_a_binomial_error():
    from rotorlanding.validate import _class_verdict

    v = _class_verdict({"backward": 7, "none": 1}, 8, "backward")
    assert v["pass"] and v["margin"] == 0 and v["ours"] == "7 of 8"
    assert v["se"] == pytest.approx((8 * 7 / 8 * 1 / 8) ** 0.5)
    v = _class_verdict({"backward": 5, "none": 3}, 8, "none")
    assert not v["pass"] and v["margin"] == -4
    v = _class_verdict({"none": 16}, 16, {"none", "backward"})
    assert v["pass"] and v["margin"] == 2 and v["se"] > 0  # 16 of 16 is not certainty: p held half a drop off 1


def test_representative_drop_is_nearest_the_median_onset():
    from rotorlanding.ensemble import ensemble_stats
    from rotorlanding.validate import representative_drop

    members = [_member("backward", 50.0, t) for t in (0.025, 0.025, 0.3, 0.33, 0.6)] + [_member("none")]
    ens = {**ensemble_stats(members), "members": members}
    assert ens["onset_s"] == pytest.approx(0.3) and representative_drop(ens) == 2
    calm = [_member("none", disp=(-3e-4, d)) for d in (1e-4, 2e-4, 3e-4)]
    assert representative_drop({**ensemble_stats(calm), "members": calm}) == 1


def test_report_orbits_and_forces_are_the_representative_drop(tmp_path):
    """The report's orbit and force figures (validate.GALLERY) are drawn from each ensemble's
    representative drop, not from the centred one: a short landing stands in for drop 2 of a
    backward ensemble whose median onset is drop 2's; a case without its drop's results gets none."""
    from rotorlanding.ensemble import ensemble_stats
    from rotorlanding.results import read_results
    from rotorlanding.run import run_scenario
    from rotorlanding.scenario import load_scenario
    from rotorlanding.validate import (
        FIGURE_CASES,
        GALLERY,
        REPRESENTATIVE_FIGURES,
        _representative_figures,
        paper_dir,
        representative_force_mean,
    )

    members = [_member("backward", 50.0, t) for t in (0.025, 0.025, 0.3, 0.33, 0.6)]
    drop = tmp_path / "ensembles" / "backward_whirl_drop2"
    run_scenario(load_scenario(paper_dir() / "backward_whirl_landing.toml", ["operating.t_end=0.03"]), drop,
                 progress=False, plots=False, results=True)
    assert read_results(drop / "results.h5")["time_s"][-1] == pytest.approx(0.03, abs=1e-3)
    result = {"ensembles": {"backward_whirl": {**ensemble_stats(members), "members": members},
                            "forward_7000": {**ensemble_stats(members), "members": members}}}
    files = _representative_figures(result, tmp_path)
    assert files == ["backward_whirl_representative/orbits.png"]  # the backward case's forces are not shown
    assert all((tmp_path / f).stat().st_size > 10_000 for f in files)
    assert representative_force_mean(result, tmp_path) is None  # the 7000 rpm drop's results are missing here
    # the DE's time-mean force from the representative drop's onset: here drop 2 (onset 0.3 s) is 0.03 s long,
    # so none; with the onset inside the record, the trapezoid mean of the force on the rotor from it
    assert representative_force_mean(result, tmp_path, key="backward_whirl") is None
    early = [_member("backward", 50.0, t) for t in (0.5, 0.6, 0.01, 0.01, 0.01)]  # median 0.01 s: drop 2
    m = representative_force_mean({"ensembles": {"backward_whirl": {**ensemble_stats(early), "members": early}}},
                                  tmp_path, key="backward_whirl")
    from rotorlanding.mechanisms import rotor_force

    r = read_results(drop / "results.h5")
    t, fz = r["time_s"], rotor_force(r["series"], "DE")[1]
    sel = t >= t[0] + 0.01
    assert m["drop"] == 2 and m["from_s"] >= 0.01
    assert m["mean_n"] == pytest.approx(np.trapezoid(fz[sel], t[sel]) / (t[sel][-1] - t[sel][0]))
    # every orbit and force figure the report shows is one of these, and its drop's results.h5 is kept
    shown = [g[0] for g in GALLERY if "orbits" in g[0] or "forces" in g[0]]
    assert shown and all(g.split("_representative/")[0] in REPRESENTATIVE_FIGURES for g in shown)
    assert all(Path(g).stem in REPRESENTATIVE_FIGURES[g.split("_representative/")[0]] for g in shown)
    assert set(REPRESENTATIVE_FIGURES) <= set(FIGURE_CASES)


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


def test_provenance_follows_the_adopted_calibrations(monkeypatch, tmp_path):
    """A calibration that scores the mu_rad 0.15 landing (case bw015) makes the calm half of the
    switch a fitted result, not a prediction; a calibration not adopted labels nothing."""
    import rotorlanding.validate as v

    # since session 31 the adopted worn-bearing calibration scores bw015 too (the ribbon's damping is
    # fitted on the switch): the calm half is fitted, with its three unknowns
    assert v.provenance()["switch_calm"] == "fitted (scenarios/calibration/worn_bearing.toml: 3 unknowns)"
    # a calibration scoring only bw whose worn bearing's location was chosen on the switch ([choices]
    # judged_on bw015): the label must say so
    only_bw = tmp_path / "worn_only_bw.toml"
    only_bw.write_text('cases = ["bw"]\n[choices]\n"the worn bearing" = {options = "both / DE / NDE", chosen = "DE", '
                       'judged_on = ["bw015"], record = "a record"}\n[ranges]\n'
                       '"bearings.DE.worn_drag_torque" = {min = 2.0, max = 5.0}\n'
                       '"bearings.DE.worn_drag_growth_angle" = {min = 40.0, max = 300.0}\n')
    monkeypatch.setattr(v, "ADOPTED", (str(only_bw),))
    calm = v.provenance()["switch_calm"]
    assert calm.startswith("predicted for the 2 fitted unknowns") and "chosen on this check: DE" in calm
    monkeypatch.setattr(v, "ADOPTED", ("rotor_modes.toml", "worn_bearing_switch.toml"))
    prov = v.provenance()
    assert prov["switch_calm"].startswith("fitted (scenarios/calibration/worn_bearing_switch.toml")
    assert prov["t1_onset"] == prov["switch_calm"] and prov["t2_force_min"] == "predicted"
    assert prov["rise"].startswith("fitted: its frequencies are fitted (scenarios/calibration/rotor_modes.toml")
    monkeypatch.setattr(v, "ADOPTED", ())
    # the rise of the whirl with speed stays fitted while a screen chose the rotor on it
    assert v.provenance()["rise"] == ("fitted: the rotor's design values were screened for the rise "
                                      "(scenarios/calibration/rotor_rise_screen.toml)")
    monkeypatch.setattr(v, "SCREENS", ())
    assert set(v.provenance().values()) == {"predicted"}


def test_ribbon_modal_shift_is_the_ribbon_share_of_the_mode_strain_energy():
    """The report's explanation of the ribbon check (validate.ribbon_modal_shift): the landed mode
    moves with K_rib by about half the ribbon's share of the mode's strain energy. Checked where
    Rayleigh's rule is exact (standstill, no gyroscopic terms) against the strain energies of the
    mode shape itself: d ln f / d ln K_rib = 1/2 (E_support / E_total) (k_sup / K_rib) for the
    ribbon in series with the rest of the support chain. Then the report's numbers at 7000 rpm."""
    import math

    import numpy as np

    from rotorlanding.modal import modal_analysis
    from rotorlanding.modefit import load_space, rotor_with
    from rotorlanding.reduction import full_model
    from rotorlanding.rotor import rotor_from_dict
    from rotorlanding.timoshenko import assemble
    from rotorlanding.validate import project_root, ribbon_modal_shift

    rm = ribbon_modal_shift()
    k_rib, k_rest = rm["k_rib"], rm["k_rest"]
    space = load_space(project_root() / "scenarios" / "calibration" / "rotor_modes.toml")

    def mode(factor):
        ks = 1.0 / (1.0 / (factor * k_rib) + 1.0 / k_rest)
        fe = assemble(rotor_from_dict(rotor_with(space["rotor_data"], {}, ks)))
        sysm = full_model(fe).with_supports()
        m = min(modal_analysis(sysm, 0.0).modes, key=lambda m: abs(m.frequency_hz - 49.0))
        return m, sysm, fe, ks

    m0, sysm, fe, ks = mode(1.0)
    phi = np.real(m0.shape) if np.linalg.norm(np.real(m0.shape)) > np.linalg.norm(np.imag(m0.shape)) else np.imag(m0.shape)
    q = np.linalg.lstsq(sysm.T, phi, rcond=None)[0]
    e_total = float(q @ sysm.K @ q)
    # the chains the ribbon is in series with: the catcher stand-ins, not the motor coupling (an
    # in_landing support, 1e5 N/m since session 40, which K_rib does not scale)
    e_support = sum(s.kyy * phi[fe.dof(s.station, "y")] ** 2 + s.kzz * phi[fe.dof(s.station, "z")] ** 2
                    for s in fe.rotor.supports if not s.in_landing)
    assert any(s.in_landing and s.kyy > 0 for s in fe.rotor.supports)
    predicted = 0.5 * e_support / e_total * ks / k_rib
    eps = 0.01
    fd = math.log(mode(1 + eps)[0].frequency_hz / mode(1 - eps)[0].frequency_hz) / math.log((1 + eps) / (1 - eps))
    assert fd == pytest.approx(predicted, rel=0.03)
    # the report's numbers: the 7000 rpm mode moves little and the same way as the ribbon
    assert rm["modes_hz"][0.5] < rm["modes_hz"][1.0] < rm["modes_hz"][1.5]
    assert rm["support_n_m"][1.0] == pytest.approx(space["support_stiffness"])
    share = rm["ribbon_energy_share"]
    assert set(share) == {0.5, 1.5} and all(0.0 < v < 0.3 for v in share.values()) and share[0.5] > share[1.5]
    assert share[1.5] == pytest.approx(2 * math.log(rm["modes_hz"][1.5] / rm["modes_hz"][1.0]) / math.log(1.5))
    assert abs(rm["shift"][1.5]) < 0.10 and abs(rm["shift"][0.5]) < 0.10
    # the forward modes listed per factor hold the matched one, ascending, and a next one above it
    for f, modes in rm["forward_modes_hz"].items():
        assert modes == sorted(modes) and rm["modes_hz"][f] in modes and modes[-1] > rm["modes_hz"][f]


def test_ribbon_mode_changes_names_a_whirl_that_left_the_matched_mode():
    """A ribbon variant's landed whirl nearer another landed forward mode than the matched one is a
    mode change (the report says so); one near the matched mode, or a variant without a whirl, is not."""
    from rotorlanding.validate import ribbon_mode_changes

    rm = {"modes_hz": {0.5: 64.0, 1.5: 66.0}, "forward_modes_hz": {0.5: [40.0, 64.0, 95.0], 1.5: [41.0, 66.0, 97.0]}}
    assert ribbon_mode_changes(rm, {0.5: 62.5, 1.5: 96.5}) == {1.5: (96.5, 97.0, 66.0)}
    assert ribbon_mode_changes(rm, {0.5: 62.5, 1.5: 64.0}) == {}
    assert ribbon_mode_changes(rm, {0.5: None, 1.5: 70.0}) == {}
    assert ribbon_mode_changes({"modes_hz": {1.5: 66.0}}, {1.5: 96.5}) == {}  # no mode list: nothing claimed


def test_holdout_sets_read_the_landing_fit_before_the_modal_fit(tmp_path, monkeypatch):
    """validate lands a held-out speed on the best design of the calibration fitted without it
    (calibration.json of holdout/without_<rpm>rpm_landings.toml, tied keys split); a modal fit's
    modefit.json is the fallback; nothing when neither ran. Also: the shipped held-out fits are
    landing fits whose best design is the first row."""
    import json

    import rotorlanding.validate as v

    monkeypatch.setattr(v, "holdout_dir", lambda: tmp_path)
    assert v._holdout_sets(3000) is None
    (tmp_path / "without_3000rpm").mkdir()
    (tmp_path / "without_3000rpm" / "modefit.json").write_text(json.dumps({"values": {"rotor.disks.4.thickness": 0.05}}))
    assert v._holdout_sets(3000) == ["rotor.disks.4.thickness=0.05"]
    (tmp_path / "without_3000rpm_landings.toml").write_text(
        '[ranges]\n"a.b,c.d" = {min = 1.0, max = 2.0}\n"e" = {min = 1.0, max = 2.0}\n')
    (tmp_path / "without_3000rpm" / "calibration.json").write_text(json.dumps(
        {"designs": [{"a.b,c.d": 1.5, "e": 1.25, "score": 0.1}, {"a.b,c.d": 1.9, "e": 1.0, "score": 0.2}]}))
    assert v._holdout_sets(3000) == ["a.b=1.5", "c.d=1.5", "e=1.25"]
    monkeypatch.undo()
    for rpm in (3000, 7000, 10000):
        sets = v._holdout_sets(rpm)
        assert sets and all(s.startswith(("rotor.sections.3.outer_diameter=", "rotor.disks.4.outer_diameter=")) for s in sets)


def test_report_figures_are_copied_beside_the_report_and_shown(tmp_path):
    # the published report shows its figures from a folder beside it (issue 15, point 5), not file
    # names of a run folder the reader does not have; a figure the run did not make is left out
    import matplotlib

    from rotorlanding.validate import GALLERY, copy_gallery, figure_lines, gallery_dir

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from PIL import Image

    out = tmp_path / "run"
    made = GALLERY[:-1]  # the backward orbits "failed"
    for k, (src, _, _) in enumerate(made):
        (out / src).parent.mkdir(parents=True, exist_ok=True)
        f, ax = plt.subplots(figsize=(3, 2))
        ax.plot([0, 1], [0, k + 1], label=src)
        ax.legend()
        f.savefig(out / src, dpi=60)
        plt.close(f)
    folder = gallery_dir("validation.md")
    assert folder == "validation_figures" and gallery_dir("validation_rig_rotor_first.md") == \
        "validation_rig_rotor_first_figures"
    (tmp_path / "docs" / folder).mkdir(parents=True)
    (tmp_path / "docs" / folder / GALLERY[0][1]).write_bytes(b"old")
    shown = copy_gallery(out, tmp_path / "docs" / folder)
    assert [n for n, _ in shown] == [g[1] for g in made]
    for src, name, _ in made:
        with Image.open(out / src) as a, Image.open(tmp_path / "docs" / folder / name) as b:
            assert a.size == b.size
            # the palette copy keeps the picture: mean colour difference well under one grey level
            diff = np.abs(np.asarray(a.convert("RGB"), float) - np.asarray(b.convert("RGB"), float))
            assert diff.mean() < 1.0, (name, diff.mean())
    assert not (tmp_path / "docs" / folder / GALLERY[-1][1]).exists()
    assert not [p for p in (tmp_path / "docs" / folder).iterdir() if p.name.startswith(".")]  # no temporaries

    section = "\n".join(figure_lines({"figures": [g[0] for g in GALLERY[:2]] + ["extra.png"], "gallery": shown,
                                       "gallery_dir": folder}))
    for name, caption in shown:
        assert f"]({folder}/{name})" in section and f"*{caption}*" in section
    assert "- `extra.png`" in section and "- `forward_whirl_vs_speed.png`" not in section


def test_validate_write_failures_are_one_line(monkeypatch, tmp_path, capsys):
    # an --out that is a file is refused before any landing; a full disk while the report is
    # written is one line naming the file and the reason (exit 3), not a traceback
    import errno

    import rotorlanding.validate as V

    def no_landings(*a, **k):
        raise AssertionError("no landing may run")

    monkeypatch.setattr(V, "run_all", no_landings)
    (tmp_path / "v").write_text("a file")
    assert main(["validate", "--out", str(tmp_path / "v")]) == 2
    err = capsys.readouterr().err.strip()
    assert "--out" in err and "not a folder" in err and "\n" not in err

    monkeypatch.setattr(V, "run_all", lambda *a, **k: [])
    monkeypatch.setattr(V, "ribbon_modal_shift", lambda rig: None)
    monkeypatch.setattr(V, "evaluate_cases", lambda *a, **k: {"checks": []})
    monkeypatch.setattr(V, "counts_line", lambda ev: "")

    def full_disk(result, out):
        raise OSError(errno.ENOSPC, "No space left on device", str(out / "forward_whirl_vs_speed.png"))

    monkeypatch.setattr(V, "plot_validation", full_disk)
    assert main(["validate", "--out", str(tmp_path / "w")]) == 3
    err = capsys.readouterr().err.strip()
    assert "forward_whirl_vs_speed.png" in err and "No space left on device" in err and "\n" not in err


def test_rig_table_shows_what_the_rotor_fit_determines_and_the_adopted_rotor_lies_in_it():
    """The rig table gives each landing-fitted rotor size, and the worn bearing's unknowns (the ribbon's
    damping among them, fitted tied at both bearings), the
    span of the designs the stored fit cannot tell from its best; the adopted values lie inside it.
    A calibration without a stored run has no span."""
    from rotorlanding.config import get_dotted, load_toml
    from rotorlanding.validate import fit_span, paper_dir, project_root, rig_checks

    rotor = {"rotor": load_toml(project_root() / "scenarios" / "rig_rotor.toml")["rotor"]}
    worn = load_toml(paper_dir() / "backward_whirl_landing.toml")
    rig = load_toml(project_root() / "scenarios" / "rig" / "rig.toml")  # the ribbon's damping, fitted tied (DE, NDE)
    checks = rig_checks()
    for cal, data, key in [("rotor_landings.toml", rotor, k) for k in ("rotor.sections.3.outer_diameter",
                                                                         "rotor.disks.4.outer_diameter")] + \
            [("worn_bearing.toml", worn, k) for k in ("bearings.DE.worn_drag_torque",
                                                      "bearings.DE.worn_drag_growth_angle")] + \
            [("worn_bearing.toml", rig, "bearings.DE.c_rib")]:
        lo, hi = fit_span(f"scenarios/calibration/{cal}", key)
        assert lo < hi and lo <= get_dotted(data, key) <= hi
        c = next(c for c in checks if c["check"].startswith(key))
        assert f"the fit determines [{lo:.4g}, {hi:.4g}]" in c["ours"]
    assert fit_span("scenarios/calibration/worn_bearing_switch.toml", "bearings.DE.worn_drag_torque") is None
    # the tied unknown is one row (its first key's), which says the tie holds in the rig
    assert fit_span("scenarios/calibration/worn_bearing.toml", "bearings.NDE.c_rib") == \
        fit_span("scenarios/calibration/worn_bearing.toml", "bearings.DE.c_rib")
    (row,) = [c for c in checks if "c_rib" in c["check"]]
    assert row["check"].startswith("bearings.DE.c_rib (tied: bearings.NDE.c_rib)") and row["pass"], row
    assert "the same value (tied in the fit)" in row["ours"]


def test_ribbon_screen_summary_reads_the_stored_screens(tmp_path):
    """The report's sentence on other rotors (validate.ribbon_screen_summary) counts what the stored
    session-37 screens hold: candidates, landed rotors passing all four checks, and the backward whirl's
    frequency only of those, only where their ensemble whirled backward; absent or torn files give None."""
    import json

    from rotorlanding.validate import ribbon_screen_summary

    (tmp_path / "candidates.json").write_text(json.dumps({"rows": [{}, {}, {}]}))
    ok = {"fig39_3000": True, "fig39_7000": True, "fig39_10000": True, "ribbon": True}
    landed = [{"rotor": "1:1", **ok}, {"rotor": "1:2", **ok, "fig39_10000": False}, {"rotor": "1:3", **ok}]
    (tmp_path / "landed.jsonl").write_text("\n".join(json.dumps(x) for x in landed) + "\n")
    back = [{"rotor": "1:1", "frequency_hz": 80.0}, {"rotor": "1:2", "frequency_hz": 50.0},
            {"rotor": "1:3", "frequency_hz": None}]
    (tmp_path / "backward.jsonl").write_text("\n".join(json.dumps(x) for x in back) + "\n")
    s = ribbon_screen_summary(tmp_path)
    assert s == {"candidates": 3, "landed": 3, "all_four": ["1:1", "1:3"], "backward_hz": [80.0]}
    (tmp_path / "backward.jsonl").write_text('{"rotor": "1:1", "freq')  # torn by a kill
    assert ribbon_screen_summary(tmp_path) is None
    (tmp_path / "backward.jsonl").unlink()
    assert ribbon_screen_summary(tmp_path) is None


def test_joint_screen_summary_counts_the_funnels(tmp_path):
    """validate.joint_screen_summary over several funnel files: a rotor passing the five checks is listed, one
    missing exactly one is counted (and whether that one is the ribbon check), a torn or absent file gives None."""
    import json

    from rotorlanding.validate import JOINT_CHECKS, joint_screen_summary

    ok = dict.fromkeys(JOINT_CHECKS, True)
    a = [{"rotor": "1:1", **ok}, {"rotor": "1:2", **ok, "ribbon": False},
         {"rotor": "1:3", **ok, "ribbon": False, "calm": False}]
    b = [{"rotor": "7:1", **ok, "fig39_10000": False}]
    fa, fb = tmp_path / "a.jsonl", tmp_path / "b.jsonl"
    fa.write_text("\n".join(json.dumps(x) for x in a) + "\n")
    fb.write_text("\n".join(json.dumps(x) for x in b) + "\n")
    assert joint_screen_summary([fa, fb]) == {"landed": 4, "all": ["1:1"], "one_short": 2, "one_short_ribbon": 1}
    fb.write_text('{"rotor": "7:1", "fig39')  # torn by a kill
    assert joint_screen_summary([fa, fb]) is None
    assert joint_screen_summary([fa, tmp_path / "absent.jsonl"]) is None


def test_alignment_summary_judges_the_switch_per_offset_and_drops_a_stale_study(tmp_path):
    """validate.alignment_summary: per motor offset, Table 1's switch by the switch checks' own rule (14 of 16 drops
    backward at mu_rad 0.3 and calm at 0.15, the landing's class: a drop whose NDE whirls is not calm), offsets
    descending; the report's range is the unbroken run of passes around the rig's offset, and a frequency outside
    Table 1's band is said so; a record whose scenario no longer gives the values it was landed on, or a torn file,
    gives None."""
    import json
    import shutil

    from rotorlanding.validate import (
        alignment_lines,
        alignment_summary,
        scenario_fingerprint,
    )

    paper = tmp_path / "paper"
    paper.mkdir()
    for c in ("backward_whirl_landing", "forward_whirl_landing"):
        (paper / f"{c}.toml").write_text(f'name = "{c}"\n[operating]\nspeed_rpm = 7000.0\n')
    fp = {c: scenario_fingerprint(paper / f"{c}.toml") for c in ("backward_whirl_landing", "forward_whirl_landing")}

    def rec(case, oz, mu, counts, f=None, n=16, de=None):
        return {"case": case, "coupling_n_per_m": 1.0e5, "offset_z_m": oz, "mu_rad": mu, "drops": n, "counts": counts,
                "rig_fingerprint": fp[case], "de_counts": de or counts, "de_frequency_hz": f}

    bw = "backward_whirl_landing"
    recs = [rec(bw, 0.0, 0.3, {"backward": 14, "none": 2}, 49.5), rec(bw, 0.0, 0.15, {"none": 16}),
            rec(bw, -1e-4, 0.3, {"backward": 16}, 49.0), rec(bw, -1e-4, 0.15, {"none": 13, "forward": 3},
                                                                   de={"none": 16}),  # the NDE whirls: not calm
            rec(bw, -2e-4, 0.3, {"backward": 15, "none": 1}, 50.0), rec(bw, -2e-4, 0.15, {"none": 16}),
            rec(bw, 5e-5, 0.3, {"backward": 16}, 60.0), rec(bw, 5e-5, 0.15, {"none": 14, "backward": 2}),
            rec("forward_whirl_landing", -2e-4, None, {"forward": 8}, 65.0, n=8, de={"forward": 7, "none": 1})]
    scan = tmp_path / "scan.jsonl"
    scan.write_text("".join(json.dumps(r) + "\n" for r in recs))
    al = alignment_summary(scan, paper)
    assert [s["offset_z_m"] for s in al["switch"]] == [5e-5, 0.0, -1e-4, -2e-4]
    assert [s["pass"] for s in al["switch"]] == [True, True, False, True]
    assert [(s["backward"], s["calm"]) for s in al["switch"]] == [(16, 14), (14, 16), (16, 13), (15, 16)]
    assert al["other"] == [{"case": "forward_whirl_landing", "offset_z_m": -2e-4, "n": 8, "ok": 7, "frequency_hz": 65.0}]
    text = alignment_lines(al)[1]
    assert "+0.05 mm 16 / 14 of 16 (60.0 Hz, outside Table 1's band) PASS" in text
    assert "+0 mm 14 / 16 of 16 (49.5 Hz) PASS" in text and "-0.1 mm 16 / 13 of 16 (49.0 Hz) FAIL" in text
    # each verdict with its margin, the weaker side's in drops, and that side's binomial standard error
    assert "PASS (+0 drops (1.3), within noise)" in text and "FAIL (-1 drops (1.6), within noise)" in text
    assert [(s["margin"], round(s["se"], 2)) for s in al["switch"]][:2] == [(0, 1.32), (0, 1.32)]
    assert "holds from +0 to +0.05 mm" in text  # the pass at -0.2 mm lies beyond a fail: not in the range
    assert "forward in 7 of 8 drops" in text
    assert "fails at the offset nearest" in alignment_lines(al, rig_offset_z=-1e-4)[1]
    shutil.copy(paper / f"{bw}.toml", tmp_path / "kept.toml")
    (paper / f"{bw}.toml").write_text('# a comment changes nothing\nname = "backward_whirl_landing"\n'
                                      '[operating]\nspeed_rpm = 7000.0\n')
    assert alignment_summary(scan, paper) == al
    (paper / f"{bw}.toml").write_text('name = "backward_whirl_landing"\n[operating]\nspeed_rpm = 7001.0\n')
    assert alignment_summary(scan, paper) is None and alignment_lines(None) == []  # the rig moved on: stale
    shutil.copy(tmp_path / "kept.toml", paper / f"{bw}.toml")
    scan.write_text(scan.read_text()[:-40])  # torn by a kill
    assert alignment_summary(scan, paper) is None


def test_alignment_summary_of_the_checkout():
    """The checkout's stored alignment study (docs/studies/coupling_alignment/) is of the rig as it is and reads as
    docs/calibration.md's session 41 states it: the switch holds on the bearings' straight axis and the levitated
    hub, and fails with the motor aligned on the resting hub."""
    from rotorlanding.validate import alignment_summary

    al = alignment_summary()
    assert al is not None and al["k"] == 1.0e5
    passes = {round(s["offset_z_m"] * 1e6): s["pass"] for s in al["switch"]}
    assert passes[0] and passes[-74] and not passes[-270]


def test_joint_screen_summary_of_the_checkout():
    """The checkout's stored funnels read as docs/calibration.md's sessions 37-38 state them: 20 + 21 rotors in
    Table 1's band landed, none passing the five checks, 8 missing one (7 of them the ribbon check)."""
    from rotorlanding.validate import joint_screen_summary

    assert joint_screen_summary() == {"landed": 41, "all": [], "one_short": 8, "one_short_ribbon": 7}


def test_ribbon_screen_summary_of_the_checkout():
    """The checkout's stored screens (docs/studies/ribbon_rise_screen) read as docs/calibration.md's
    session 37 states them: 80 candidates landed, five passing all four checks."""
    from rotorlanding.validate import ribbon_screen_summary

    s = ribbon_screen_summary()
    assert s is not None and s["candidates"] == s["landed"] == 80
    assert sorted(s["all_four"]) == ["11:983", "12:416", "12:437", "12:623", "12:690"]
    assert len(s["backward_hz"]) == 4 and min(s["backward_hz"]) > 49.0 * 1.1  # all outside Table 1's band
