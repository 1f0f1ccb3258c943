"""Issue 18, step 4: [limits] and `rotorlanding verdict` (rotorlanding/verdict.py).

Checked against: the Stribeck/NSK load of the most loaded ball and a hand Hertz pressure, the
line-contact closed form for the sleeve, ISO 281's rating life (damage per revolution (F_r/C)^3
1e-6 at zero clearance) for the damage wiring, and on a real short landing the temperature
criterion against the stored series; bad limits are one line (exit 2), the files are written."""

import json
import math
from pathlib import Path

import numpy as np
import pytest

from rotorlanding import verdict as vd
from rotorlanding.cli import main
from rotorlanding.landing import build_spec
from rotorlanding.limits import Limits, limits_from_dict
from rotorlanding.errors import InputError
from rotorlanding.scenario import apply_overrides, load_scenario

ROOT = Path(__file__).resolve().parents[1]
LANDING = ROOT / "scenarios" / "landing_7000rpm.toml"


@pytest.fixture(scope="module")
def spec():
    # the synthetic records below carry no temperatures: the thermal networks are off here
    return build_spec(load_scenario(LANDING, ["effects.catcher_thermal=false"]))


def test_ball_race_pressure_against_the_hand_calculation(spec):
    """F_r = 2 kN, zero clearance: Q_max = 4.37 F_r / (Z cos a) = 760.6 N (Stribeck, NSK), hand
    Brewe-Hamrock p0 = 1.442 GPa on the inner race (docs/designer_models.md); the exact elliptic
    integrals give 0.6 % less."""
    laws = spec.bearings[0].laws
    p_in, p_out, geom, _ = vd.ball_pressures(np.array([2000.0]), np.array([0.0]), np.array([0.0]), laws)
    q_max = 4.37 * 2000.0 / (15 * math.cos(math.radians(40.0)))
    assert q_max == pytest.approx(760.6, abs=0.1)
    assert p_in[0] == pytest.approx(1.442e9, rel=0.01)
    assert p_out[0] < p_in[0]


def _record(spec, f_r, t, rpm=1000.0, fn=None):
    n = len(t)
    s = {"axial_force_n": np.zeros(n), "rotor_speed_rpm": np.full(n, 7000.0)}
    for b in spec.bearing_names:
        s.update({f"{b}_ball_force_y_n": np.zeros(n), f"{b}_ball_force_z_n": np.asarray(f_r, float),
                  f"{b}_normal_force_n": np.zeros(n) if fn is None else fn, f"{b}_race_speed_rpm": np.full(n, rpm)})
    return s


@pytest.mark.parametrize("ratio", [1.0, 0.5])
def test_damage_per_drop_is_iso_281_at_constant_load(spec, monkeypatch, ratio):
    """Constant F_r over n revolutions at zero clearance: the overrolling damage is ISO 281's
    n (F_r/C)^3 / 1e6 (Q_max ~ F_r exactly at zero clearance, p ~ Q^(1/3), N ~ p^-9), and the
    rainflow count of a constant history has no cycle."""
    monkeypatch.setattr(vd, "DEFAULT_INTERNAL_CLEARANCE_M", 0.0)
    lim = Limits()
    t = np.linspace(0.0, 1.0, 11)
    rpm = 600.0  # 10 revolutions
    f_r = np.full(11, ratio * lim.dynamic_load_rating_n)
    crit, dmg = vd.bearing_criteria(spec, spec.bearings[0], t, _record(spec, f_r, t, rpm), lim, {})
    per_rev = ratio**3 * 1e-6
    d = next(c for c in crit if c["criterion"].startswith("allowable"))["dominant"]
    assert d["overrolling_damage"] == pytest.approx(10.0 * per_rev, rel=1e-3)
    assert d["rainflow_damage"] == 0.0  # a constant envelope has no cycles (a landing's starts from 0)
    assert dmg["allowable_drops"] == pytest.approx(1.0 / (10.0 * per_rev), rel=1e-3)


def test_sleeve_pressure_is_the_line_contact_and_exceedance_is_counted(spec):
    """p0 = sqrt(F E* / (pi L R*)) (Johnson 4.3) with R* = r_s r_b / (r_b - r_s); a force ramp that
    passes the limit once is one crossing with the interpolated time above."""
    laws = spec.bearings[0].laws
    e_star = 208e9 / (2 * (1 - 0.3**2))
    r_star = laws.sleeve_radius * laws.race_radius / laws.clearance
    length = 0.022
    p_limit = 30e6
    f_at_limit = p_limit**2 * math.pi * length * r_star / e_star   # N: where p0 = 30 MPa
    t = np.linspace(0.0, 1.0, 1001)
    fn = 2.0 * f_at_limit * t                                        # p0 ~ sqrt(t): above from t = 0.5
    lim = Limits(sleeve_contact_pressure_pa=p_limit)
    crit, _ = vd.bearing_criteria(spec, spec.bearings[0], t, _record(spec, np.full(1001, 100.0), t, fn=fn), lim, {})
    c = next(c for c in crit if c["criterion"].startswith("sleeve"))
    assert c["value"] == pytest.approx(math.sqrt(2.0) * p_limit, rel=1e-9)
    assert not c["pass"] and c["dominant"]["crossings"] == 1
    assert c["dominant"]["time_above_s"] == pytest.approx(0.5, abs=1e-3)


def test_limits_table_defaults_and_bad_values():
    assert limits_from_dict(None) == Limits()
    assert Limits().temperature_k == pytest.approx(393.15)
    for bad, field in (({"temperature_degc": -300.0}, "temperature_degc"), ({"drops_required": 0}, "drops_required"),
                       ({"ball_contact_pressure_pa": -1.0}, "ball_contact_pressure_pa"), ({"speed": 1.0}, "speed")):
        with pytest.raises(InputError, match=f"limits.{field}"):
            limits_from_dict(bad)
    with pytest.raises(InputError, match="limits.ball_contact_pressure_pa"):  # at load, before any run
        load_scenario(LANDING, ["limits.ball_contact_pressure_pa=0"])


def test_verdict_command_on_a_short_landing(tmp_path, capsys):
    out = tmp_path / "v"
    assert main(["verdict", str(LANDING), "--t-end", "0.02", "--out", str(out), "--quiet"]) == 0
    v = json.loads((out / "verdict.json").read_text())
    assert (out / "verdict.md").read_text().startswith("# Verdict")
    assert (out / "temperatures.png").is_file()
    import h5py

    with h5py.File(out / "results.h5", "r") as h5:
        t_max = max(float(np.max(h5["series"][k][()])) for k in h5["series"] if "_temperature_" in k)
    temps = [c for c in v["criteria"] if c["criterion"] == "temperature"]
    assert max(c["value"] for c in temps) == pytest.approx(t_max - 273.15, abs=1e-9)
    assert v["verdict"] == ("pass" if all(c["pass"] for c in v["criteria"]) else "fail")
    # the same run judged against a tighter temperature limit: the temperature fails, named
    capsys.readouterr()
    assert main(["verdict", str(out / "results.h5"), "--no-plots", "--set",
                 f"limits.temperature_degc={t_max - 273.15 - 0.01}"]) == 0
    v2 = json.loads((out / "verdict.json").read_text())
    assert v2["verdict"] == "fail" and any(f.startswith("temperature") for f in v2["failed"])
    # a bad limit is one line, exit 2
    capsys.readouterr()
    assert main(["verdict", str(out / "results.h5"), "--set", "limits.drops_required=0"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "limits.drops_required" in err[0]


def test_no_load_is_unlimited_drops_and_valid_json(spec):
    t = np.linspace(0.0, 0.01, 11)
    lim = Limits()
    crit, dmg = vd.bearing_criteria(spec, spec.bearings[0], t, _record(spec, np.zeros(11), t), lim, {})
    c = next(c for c in crit if c["criterion"].startswith("allowable"))
    assert dmg["allowable_drops"] is None and c["pass"] and c["margin"] is None
    json.loads(json.dumps(c, allow_nan=False))  # strict JSON: no Infinity


def test_whirl_criterion_speed_and_severity():
    """A forward whirl from t = 0.1 s, when the rotor turns 6000 rpm: fails with the default limit
    (no whirl acceptable), passes when whirl is acceptable below 6500 rpm; severity by hand."""
    t = np.linspace(0.0, 1.0, 101)
    s = {"rotor_speed_rpm": 7000.0 - 10000.0 * t}
    summary = {"whirl": {"direction": "forward", "onset_s": 0.1, "end_s": 0.5, "persistence": 0.5,
                         "frequency_hz": 60.0, "amplitude_m": 1.5e-4, "bearing": "DE"}}
    c = vd.whirl_criterion(t, s, summary, Limits(), {"DE": 2e-4})
    assert not c["pass"] and c["dominant"]["rotor_speed_at_onset_rpm"] == pytest.approx(6000.0)
    assert c["dominant"]["time_whirling_s"] == pytest.approx(0.2)
    assert c["dominant"]["amplitude_over_clearance"] == pytest.approx(0.75)
    assert vd.whirl_criterion(t, s, summary, Limits(whirl_acceptable_below_rpm=6500.0))["pass"]


def test_an_unfinished_run_says_what_it_could_not_judge(spec):
    """The placeholder summary of a running coast-down has no whirl record: the whirl is listed as
    not evaluated (not passed), and the run as incomplete."""
    t = np.linspace(0.0, 0.01, 11)
    v = vd.evaluate(spec, t, _record(spec, np.full(11, 1000.0), t), {"complete": False}, Limits())
    assert not any(c["criterion"] == "whirl" for c in v["criteria"])
    assert any(x.startswith("whirl") for x in v["not_evaluated"]) and not v["complete"]
    assert "INCOMPLETE" in vd.markdown(v) and "Not evaluated: whirl" in vd.markdown(v)


def test_whirl_severity_and_peak_force_are_reported_and_judged_when_limited(spec):
    """Whirl severity (time whirling, orbit amplitude / clearance) and the peak contact force are
    rows of every verdict: 'reported' while their limit is 0, judged (and failed, named) once a
    limit is set; values by hand: 0.5 x (0.5 - 0.1) s = 0.2 s, 1.5e-4 / 2e-4 = 0.75."""
    t = np.linspace(0.0, 1.0, 11)
    summary = {"whirl": {"direction": "forward", "onset_s": 0.1, "end_s": 0.5, "persistence": 0.5,
                         "frequency_hz": 60.0, "amplitude_m": 1.5e-4, "bearing": "DE"},
               "bearings": {"DE": {"max_contact_force_n": 1500.0}, "NDE": {"max_contact_force_n": 900.0}}}
    s = _record(spec, np.full(11, 500.0), t)
    v = vd.evaluate(spec, t, s, summary, Limits(whirl_acceptable_below_rpm=1e4))
    rows = {(c["criterion"], c["bearing"]): c for c in v["criteria"]}
    tw = rows[("whirl severity: time whirling", "DE")]
    orbit = rows[("whirl severity: orbit amplitude / clearance", "DE")]
    force = rows[("peak contact force", "DE")]
    assert tw["value"] == pytest.approx(0.2) and orbit["value"] == pytest.approx(0.75)
    assert force["value"] == 1500.0 and rows[("peak contact force", "NDE")]["value"] == 900.0
    assert not any(c["judged"] for c in (tw, orbit, force)) and v["verdict"] == "pass"
    assert "| reported |" in vd.markdown(v)
    assert "shape" not in rows[("whirl", "DE")]["dominant"]  # a summary without the whirl's shape
    shaped = {**summary, "whirl": {**summary["whirl"], "shape": {"against": "NDE", "phase_deg": 170.0,
                                                                "amplitude_ratio": 1.1, "form": "conical"}}}
    v_sh = vd.evaluate(spec, t, s, shaped, Limits(whirl_acceptable_below_rpm=1e4))
    assert next(c for c in v_sh["criteria"] if c["criterion"] == "whirl")["dominant"]["shape"] == "conical"
    assert "shape conical" in vd.markdown(v_sh)
    strict = Limits(whirl_acceptable_below_rpm=1e4, whirl_time_s=0.1, whirl_orbit_over_clearance=0.8,
                    contact_force_n=1000.0)
    v2 = vd.evaluate(spec, t, s, summary, strict)
    assert v2["verdict"] == "fail"
    assert set(v2["failed"]) == {"whirl severity: time whirling (DE)", "peak contact force (DE)"}
    orbit2 = next(c for c in v2["criteria"] if c["criterion"].startswith("whirl severity: orbit"))
    assert orbit2["pass"] and orbit2["margin"] == pytest.approx((0.8 - 0.75) / 0.8)


def test_the_report_says_the_allowable_drops_are_fatigue_only(spec):
    t = np.linspace(0.0, 0.01, 11)
    v = vd.evaluate(spec, t, _record(spec, np.full(11, 1000.0), t), {"whirl": {"direction": "none"}}, Limits())
    md = vd.markdown(v)
    line = next(x for x in md.splitlines() if x.startswith("Allowable drops"))
    assert "rolling-contact fatigue only" in line and "wear" in line and "cage" in line and "heat" in line
    assert "rolling-contact fatigue only" in vd.format_lines(v)[1 + len(v["not_evaluated"])]


def test_coastdown_whirl_names_the_bearing_that_whirled_longest():
    """Coast-down: each chunk stores the bearing of its whirl (index, -1 none); the phases carry
    the whirl time per bearing and the verdict names the bearing with the longest whirl time over
    the run (here NDE: 0.3 s against DE's 0.1 s), not None. Synthetic chunk records."""
    from rotorlanding.coastdown_run import whirl_phases

    t0 = np.arange(7) * 0.1
    t1 = t0 + 0.1
    direction = np.array([0, 1, 1, 1, 0, -1, -1])
    bearing = np.array([-1, 0, 1, 1, -1, 1, 0])  # DE 0.2 s, NDE 0.3 s (forward DE first, NDE more)
    freq = np.array([np.nan, 60.0, 61.0, 62.0, np.nan, 40.0, 41.0])
    speed = 7000.0 - 1000.0 * t1
    phases = whirl_phases(t0, t1, direction, freq, speed, bearing, ("DE", "NDE"))
    assert [p["direction"] for p in phases] == ["none", "forward", "none", "backward"]
    assert phases[1]["bearing"] == "NDE" and phases[1]["bearing_time_s"] == pytest.approx({"DE": 0.1, "NDE": 0.2})
    assert phases[3]["bearing_time_s"] == pytest.approx({"NDE": 0.1, "DE": 0.1})
    assert phases[3]["bearing"] == "NDE"  # a tie: the first to whirl in the phase
    assert "bearing" not in phases[0]
    summary = json.loads(json.dumps({"whirl_phases": phases}))  # as stored in summary_json
    t = np.linspace(0.0, 0.7, 71)
    c = vd.whirl_criterion(t, {"rotor_speed_rpm": 7000.0 - 1000.0 * t}, summary, Limits())
    assert c["bearing"] == "NDE" and not c["pass"] and c["value"].startswith("forward")
    assert vd.whirl_bearing(summary) == "NDE"
    # DE whirls longest once its chunks dominate; the verdict follows the stored times
    phases_de = whirl_phases(t0, t1, direction, freq, speed, np.array([-1, 0, 0, 1, -1, 0, 0]), ("DE", "NDE"))
    assert vd.whirl_bearing({"whirl_phases": phases_de}) == "DE"
    # a file from before the per-chunk bearing (no column): phases name none, the verdict says so
    old = whirl_phases(t0, t1, direction, freq, speed)
    assert old[1]["bearing"] is None and vd.whirl_bearing({"whirl_phases": old}) is None
    # no whirl at all: no bearing
    calm = whirl_phases(t0, t1, np.zeros(7), freq, speed, np.full(7, -1), ("DE", "NDE"))
    assert vd.whirl_criterion(t, {"rotor_speed_rpm": 7000.0 - 1000.0 * t}, {"whirl_phases": calm},
                              Limits())["bearing"] is None


def test_coastdown_chunk_classification_stores_the_whirling_bearing(spec):
    """A chunk whose NDE journal circles its clearance forward at 50 Hz (DE at rest) is classified
    forward, ~50 Hz, bearing index of NDE: what the chunk row stores (synthetic states)."""
    from rotorlanding.coastdown_run import _classify_whirl

    t = np.arange(0.0, 0.4 + 1e-12, 1e-4)
    q = np.zeros((len(t), spec.n))
    v = np.zeros((len(t), spec.n))
    v[:, spec.i_theta] = 7000.0 * math.pi / 30.0
    nde = spec.bearing_names.index("NDE")
    b = spec.bearings[nde]
    r = b.params.clearance
    q[:, b.i_station] = r * np.cos(2 * math.pi * 50.0 * t)
    q[:, b.i_station + 1] = r * np.sin(2 * math.pi * 50.0 * t)
    d, f, k = _classify_whirl(spec, t, q, v, 0.4)
    assert (d, k) == (1, nde) and f == pytest.approx(50.0, rel=0.02)
    q[:] = 0.0
    assert _classify_whirl(spec, t, q, v, 0.4)[::2] == (0, -1)


def test_close_clearance_limits_are_checked_at_load():
    """``close_clearances_m``: a gap per rotor station, > 0 and < 0.05 m; a station the rotor lacks is
    named at load, before any run."""
    assert limits_from_dict({"close_clearances_m": {"DE_AMB": 4e-4}}).close_clearances_m == {"DE_AMB": 4e-4}
    for bad in (0.0, -1e-4, 0.1, "wide", float("nan")):
        with pytest.raises(InputError, match="limits.close_clearances_m.DE_AMB"):
            limits_from_dict({"close_clearances_m": {"DE_AMB": bad}})
    with pytest.raises(InputError, match="limits.close_clearances_m.nowhere.*unknown rotor station"):
        load_scenario(LANDING, ["limits.close_clearances_m.nowhere=4e-4"])
    sc = load_scenario(LANDING, ["limits.close_clearances_m.DE_AMB=3.5e-4"])
    assert limits_from_dict(sc.raw["limits"]).close_clearances_m["DE_AMB"] == 3.5e-4
    data = {"limits": {}}  # --set creates the sub-table where the scenario has none
    apply_overrides(data, ["limits.close_clearances_m.DE_AMB=3.5e-4"])
    assert data == {"limits": {"close_clearances_m": {"DE_AMB": 3.5e-4}}}


def test_close_clearance_criterion_judges_the_station_peak():
    """value = the summary's peak at the station, margin (gap - peak) / gap, pass iff peak <= gap; no
    limit: no criterion; a summary without the span deflection: not evaluated, said."""
    summary = {"rotor_deflection": {"station_peak_m": {"DE_AMB": 4.7e-4, "NDE_AMB": 3.0e-4}}}
    crit, missing = vd.close_clearance_criteria(summary, Limits(close_clearances_m={"DE_AMB": 4e-4, "NDE_AMB": 4e-4}))
    assert missing == [] and [c["bearing"] for c in crit] == ["DE_AMB", "NDE_AMB"]
    de, nde = crit
    assert de["value"] == 4.7e-4 and not de["pass"] and de["margin"] == pytest.approx((4e-4 - 4.7e-4) / 4e-4)
    assert nde["pass"] and nde["margin"] == pytest.approx(0.25)
    assert vd.close_clearance_criteria(summary, Limits()) == ([], [])
    crit, missing = vd.close_clearance_criteria({}, Limits(close_clearances_m={"DE_AMB": 4e-4}))
    assert crit == [] and "no rotor deflection" in missing[0]


def test_close_clearance_on_a_short_landing(tmp_path, capsys):
    """The verdict of a real landing reads the run's own span deflection: a gap above the station's peak
    passes, one just below it fails and is named."""
    out = tmp_path / "v"
    assert main(["verdict", str(LANDING), "--t-end", "0.02", "--out", str(out), "--quiet", "--no-plots",
                 "--set", "limits.close_clearances_m.DE_AMB=1e-3"]) == 0
    peak = json.loads((out / "summary.json").read_text())["rotor_deflection"]["station_peak_m"]["DE_AMB"]
    assert peak > 0
    v = json.loads((out / "verdict.json").read_text())
    c = next(c for c in v["criteria"] if c["criterion"] == "close clearance" and c["bearing"] == "DE_AMB")
    assert c["bearing"] == "DE_AMB" and c["value"] == pytest.approx(peak, rel=1e-12) and c["pass"]
    assert main(["verdict", str(out / "results.h5"), "--no-plots", "--set",
                 f"limits.close_clearances_m.DE_AMB={0.99 * peak}"]) == 0
    v2 = json.loads((out / "verdict.json").read_text())
    assert v2["verdict"] == "fail" and "close clearance (DE_AMB)" in v2["failed"]
    assert "close clearance [DE_AMB]" in capsys.readouterr().out
