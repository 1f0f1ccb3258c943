"""Physical bounds of rig parameters (`[bounds]` in rig, rotor and scenario files): parsed with
one-line errors, every bound of the rig files names a real parameter, and validate's rig check
flags a calibrated value that sits on its bound or its search range's end."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from rotorlanding.config import get_dotted, load_toml
from rotorlanding.errors import InputError
from rotorlanding.scenario import Bound, load_scenario

ROOT = Path(__file__).resolve().parents[1]
PAPER = ROOT / "scenarios" / "paper"


def test_bound_position_linear_and_log():
    assert Bound(0.0, 2.0, "s").position(0.5) == pytest.approx(0.25)
    assert Bound(1.0, 100.0, "s", log=True).position(10.0) == pytest.approx(0.5)


# a key the rig files give no bound: a bound there would be merged into the table written here
@pytest.mark.parametrize("text, field", [
    ('"solver.spectral_radius" = {min = 0.5, max = 0.1, source = "x"}', "bounds.solver.spectral_radius"),
    ('"solver.spectral_radius" = {min = 0.0, max = 1.0}', "bounds.solver.spectral_radius"),
    ('"solver.spectral_radius" = {min = 0.0, max = 1.0, source = " "}', "bounds.solver.spectral_radius.source"),
    ('"solver.spectral_radius" = {min = 0.0, max = 1.0, source = "x", log = true}', "bounds.solver.spectral_radius"),
    ('"bearings.DE" = {min = 0.0, max = 1.0, source = "x"}', "bounds.bearings.DE"),
])
def test_bad_bound_names_the_field(tmp_path, text, field):
    f = tmp_path / "s.toml"
    f.write_text(f'include = ["{(PAPER / "forward_whirl_landing.toml").as_posix()}"]\n[bounds]\n{text}\n')
    with pytest.raises(InputError) as err:
        load_scenario(f)
    assert field in str(err.value) and str(f) in str(err.value)


def test_every_bound_of_the_rig_files_names_a_parameter_of_the_paper_scenarios():
    # a bound whose key the scenario lacks bounds nothing (an overlaid rotor may have fewer disks):
    # so a misspelt key would go unseen without this check
    for fname in ("forward_whirl_landing.toml", "backward_whirl_landing.toml"):
        sc = load_scenario(PAPER / fname)
        declared = load_toml(PAPER / fname).get("bounds", {})
        assert set(declared) <= set(sc.bounds), fname
        for key, b in sc.bounds.items():
            assert b.source and math.isfinite(get_dotted(sc.raw, key)), key


def test_calibration_search_ranges_lie_inside_the_physical_bounds():
    from rotorlanding.validate import calibrated_keys

    bw = load_scenario(PAPER / "backward_whirl_landing.toml")
    keys = calibrated_keys()
    assert keys and all(k in bw.bounds for k in keys), [k for k in keys if k not in bw.bounds]
    for key, (_, rng) in keys.items():
        b = bw.bounds[key]
        assert b.min <= rng["min"] < rng["max"] <= b.max, key


def test_rig_check_flags_a_value_on_its_search_range_end(monkeypatch):
    import rotorlanding.validate as v

    # a search range around the calibrated value, whatever the calibration made of it
    sc = load_scenario(PAPER / "backward_whirl_landing.toml")
    value = sc.bearings["DE"].worn_drag_torque
    top = sc.bounds["bearings.DE.worn_drag_torque"].max  # inside the physical bound, however near it the fit sits
    rng = {"min": 0.2, "max": value + 0.5 * (top - value)}
    monkeypatch.setattr(v, "calibrated_keys", lambda: {"bearings.DE.worn_drag_torque": ("space.toml", rng)})
    ok = v.rig_checks()[0]
    assert ok["pass"] and ok["source"].startswith("min: healthy")
    rng["max"] = value * 1.001  # the calibrated value now presses on the search range's end
    on = v.rig_checks()[0]
    assert not on["pass"] and on["margin"] < 0
    rng.update(min=0.01, max=1.5 * value)  # the search range reaches outside the physical bound
    out = v.rig_checks()[0]
    assert not out["pass"] and "outside the bound" in out["ours"]


def test_rig_check_hangs_on_the_pick_when_a_design_within_the_fits_noise_is_on_a_bound(monkeypatch):
    """A fitted value off its bounds passes, but the row says it hangs on the fit's pick when a design
    the stored fit cannot tell from its best sits on the bound or on the search range's end (as the
    held-out rows do); a design outside the fit's noise does not count."""
    import rotorlanding.validate as v

    sc = load_scenario(PAPER / "backward_whirl_landing.toml")
    value = sc.bearings["DE"].worn_drag_torque
    rng = {"min": 0.5 * value, "max": 1.5 * value}
    monkeypatch.setattr(v, "calibrated_keys", lambda: {"bearings.DE.worn_drag_torque": ("space.toml", rng)})
    designs = [{"within_noise_of_best": True, "bearings.DE.worn_drag_torque": x} for x in (value, 1.1 * value)]
    designs.append({"within_noise_of_best": False, "bearings.DE.worn_drag_torque": 0.5 * value})  # on the end
    run = {"within_noise_span": {"bearings.DE.worn_drag_torque": [value, 1.1 * value]}, "designs": designs}
    monkeypatch.setattr(v, "stored_run", lambda cal: run)
    monkeypatch.setattr(v, "STORED_FITS", {"space.toml": "a stored run"})
    row = v.rig_checks()[0]
    assert row["pass"] and row["robust"] == {"passing": 2, "n": 2, "holds": True} and v._verdict(row) == "PASS"
    designs[-1]["within_noise_of_best"] = True  # the design on the search range's end is within the noise
    row = v.rig_checks()[0]
    assert row["pass"] and row["robust"] == {"passing": 2, "n": 3, "holds": False}
    assert v._verdict(row) == "PASS (hangs on the fit's pick: 2 of 3 designs within its noise pass)"
    # the report's count line says how many fitted rows hold over their fit's noise
    ev = {"checks": [row], "groups": {"rig": {"passed": 1, "total": 1}}, "passed": 1, "total": 1}
    assert "**1 of 1** (0 of the 1 fitted by landing holding over every design within their fit's noise)" in \
        v.counts_line(ev)


def test_rig_value_check_flags_an_uncalibrated_value_outside_its_bound(tmp_path):
    import rotorlanding.validate as v

    overlay = tmp_path / "rig.toml"
    overlay.write_text("[contact]\nmu_ax = 0.95\n")  # steel on steel: the bound ends at 0.8
    bad = v.rig_value_check(str(overlay))
    assert not bad["pass"] and "contact.mu_ax = 0.95 outside [0.04, 0.8]" in bad["ours"]
    overlay.write_text("[contact]\nmu_ax = 0.5\n")
    ok = v.rig_value_check(str(overlay))
    assert "contact.mu_ax" not in ok["ours"]
    n_in, n = (int(w) for w in ok["ours"].split(" bounded")[0].split(" of "))
    assert n > 20 and n_in == n - len({o.split(" =")[0] for o in ok["ours"].split(": ", 1)[1].split("; ")}) \
        if n_in < n else ok["pass"]


def test_every_thermal_input_of_the_rig_has_a_sourced_bound():
    """Issue 18: every parameter of the thermal network (catcher_thermal) and of the thermal
    feedback is an assumed input of the rig; each must be bounded, with its source, for both
    bearings, and the rig's value must lie inside."""
    from rotorlanding.mechanisms import REGISTRY

    sc = load_scenario(PAPER / "forward_whirl_landing.toml")
    keys = [p.key for m in REGISTRY if m.name in ("catcher_thermal", "thermal_feedback") for p in m.params]
    assert len(keys) == 9
    for b in ("DE", "NDE"):
        for k in keys:
            bound = sc.bounds.get(f"bearings.{b}.{k}")
            assert bound is not None and bound.source, f"bearings.{b}.{k}"
            assert bound.min <= get_dotted(sc.raw, f"bearings.{b}.{k}") <= bound.max, f"bearings.{b}.{k}"


def test_screen_record_matches_the_rotor_file_and_its_check_finds_values_on_their_bounds(monkeypatch, tmp_path):
    """The screen chose the rotor's design values on the paper's whirl rise, so validate judges them
    as fitted values (validate.screen_check). The record's annuli are the rotor file's lumped masses
    and inertias (m = rho pi/4 (D^2 - d^2) L, Ip = m/8 (D^2 + d^2), It = Ip/2 + m L^2/12); the NDE
    stack is the DE's design (one radial AMB, session 30). The adopted choice (session 30, every drawn
    value >= 5 % inside its range) passes; a record with a value on its bound fails and names it."""
    import rotorlanding.validate as v

    root = v.project_root()
    rec = load_toml(root / "scenarios" / "calibration" / "rotor_rise_screen.toml")
    disks = {d["name"]: d for d in load_toml(root / "scenarios" / "rig_rotor.toml")["rotor"]["disks"]}
    g = {k: e["value"] for k, e in rec["geometry"].items()}
    assert (g["NDE_AMB_laminations.outer_diameter"], g["NDE_AMB_laminations.length"]) == (
        disks["DE_AMB_laminations"]["outer_diameter"], disks["DE_AMB_laminations"]["thickness"])
    rho = 7850.0
    for name, (outer, inner, length) in {
            "NDE_AMB_laminations": (g["NDE_AMB_laminations.outer_diameter"], 0.07, g["NDE_AMB_laminations.length"]),
            "thrust_disk": (g["thrust_disk.outer_diameter"], 0.05, g["thrust_disk.thickness"]),
            "coupling_hub": (g["coupling_hub.outer_diameter"], g["coupling_hub.bore"], g["coupling_hub.length"])}.items():
        m = rho * math.pi / 4 * (outer ** 2 - inner ** 2) * length
        ip = m / 8 * (outer ** 2 + inner ** 2)
        d = disks[name]
        assert (d["mass"], d["polar_inertia"], d["transverse_inertia"]) == pytest.approx(
            (m, ip, ip / 2 + m * length ** 2 / 12), rel=2e-3), name
    c = v.screen_check("rotor_rise_screen.toml")
    assert c["pass"] and c["margin"] >= 0.05 - v.ON_BOUND - 1e-3
    assert "ON ITS BOUND" not in c["ours"]
    # the record read from elsewhere, with the NDE stack 99.6 mm long (session 28's, 99.3 % of its
    # 40-100 mm bound): the row fails and names it; the screen's keys are not "every other value"
    text = (root / "scenarios" / "calibration" / "rotor_rise_screen.toml").read_text()
    assert text.count("value = 0.08603") == 1
    text = text.replace("value = 0.08603", "value = 0.09956")
    cal = tmp_path / "scenarios" / "calibration"
    cal.mkdir(parents=True)
    (cal / "rotor_rise_screen.toml").write_text(text)
    monkeypatch.setattr(v, "project_root", lambda: tmp_path)
    monkeypatch.setattr(v, "paper_dir", lambda: root / "scenarios" / "paper")
    c2 = v.screen_check("rotor_rise_screen.toml")
    assert not c2["pass"] and c2["margin"] < 0
    assert "ON ITS BOUND: `NDE_AMB_laminations.length` 0.09956 at 99.3% of its bound" in c2["ours"]
    assert "rotor.disks.1.outer_diameter" in v.screened_keys()


def test_heldout_pick_on_its_bound_is_flagged(monkeypatch):
    """A held-out fit's first design is judged as the adopted fit's: a value within ON_BOUND of its
    sourced bound's end, or of its search range's, is on it (validate.heldout_pick_positions)."""
    import rotorlanding.validate as v

    key = "rotor.sections.3.outer_diameter"
    rng = load_toml(v.holdout_dir() / "without_3000rpm_landings.toml")["ranges"]
    other = next(k for k in rng if k != key)
    mid = {k: 0.5 * (r["min"] + r["max"]) for k, r in rng.items()}
    monkeypatch.setattr(v, "_holdout_best", lambda rpm: dict(mid, design=1))
    assert not any(q["on_bound"] for q in v.heldout_pick_positions(3000))
    b = load_scenario(PAPER / "forward_whirl_landing.toml").bounds[key]
    near = b.min + 0.01 * (b.max - b.min)  # 1 % of the physical bound from its lower end
    monkeypatch.setattr(v, "_holdout_best", lambda rpm: dict(mid, **{key: near}, design=1))
    q = {p["key"]: p for p in v.heldout_pick_positions(3000)}
    assert q[key]["on_bound"] and q[key]["bound_position"] == pytest.approx(0.01) and not q[other]["on_bound"]


def test_rows_over_fit_spans_the_designs_within_the_fits_noise(monkeypatch, tmp_path):
    """validate.rows_over_fit: a predicted Table 2 number over the designs a stored rotor fit cannot
    tell from its best (designs outside its noise do not count), and how many of them fall in the
    row's band (Table 2 force minimum: -0.5 kN +/- 1.0 kN)."""
    import json

    import rotorlanding.validate as v

    rows = [{"within_noise_of_best": True, "fw7000_v_force_min_n": -1200.0},
            {"within_noise_of_best": True, "fw7000_v_force_min_n": -6000.0},
            {"within_noise_of_best": True, "fw7000_v_force_min_n": None},
            {"within_noise_of_best": False, "fw7000_v_force_min_n": -300.0}]
    f = tmp_path / v.STORED_FITS["scenarios/calibration/rotor_landings.toml"]
    f.parent.mkdir(parents=True)
    f.write_text(json.dumps({"space": "scenarios/calibration/rotor_landings.toml", "designs": rows}))
    paper = v.paper_dir()
    monkeypatch.setattr(v, "project_root", lambda: tmp_path)
    monkeypatch.setattr(v, "paper_dir", lambda: paper)
    o = v.rows_over_fit()
    assert set(o) == {"t2_force_min"}
    assert (o["t2_force_min"]["min"], o["t2_force_min"]["max"], o["t2_force_min"]["n"]) == (-6000.0, -1200.0, 2)
    assert o["t2_force_min"]["in_band"] == 1
    f.unlink()
    assert v.rows_over_fit() == {}


def test_rows_over_fit_counts_a_design_without_the_number_as_outside(monkeypatch, tmp_path):
    """validate.rows_over_fit on the worn fit's run: Table 1's onset over its designs within noise; a
    design whose backward landing gave no onset (no backward whirl) cannot pass the row, so it counts in
    n_designs and not in in_band; and the verdict's robust entry (validate._over_fit) holds for a fail
    only when no design passes, for a pass only when every design does (Table 1 onset band 0.4 +/- 0.04 s)."""
    import json

    import rotorlanding.validate as v

    rows = [{"within_noise_of_best": True, "bw_onset_s": 0.41},
            {"within_noise_of_best": True, "bw_onset_s": 0.03},
            {"within_noise_of_best": True, "bw_onset_s": None},
            {"within_noise_of_best": False, "bw_onset_s": 0.40}]
    f = tmp_path / v.STORED_FITS[v.WORN_FIT]
    f.parent.mkdir(parents=True)
    f.write_text(json.dumps({"space": v.WORN_FIT, "ensemble": 32, "designs": rows}))
    paper = v.paper_dir()
    monkeypatch.setattr(v, "project_root", lambda: tmp_path)
    monkeypatch.setattr(v, "paper_dir", lambda: paper)
    o = v.rows_over_fit()["t1_onset"]
    assert (o["n"], o["n_designs"], o["in_band"], o["min"], o["max"]) == (2, 3, 1, 0.03, 0.41)
    assert v._over_fit(o, ok=False) == {"passing": 1, "n": 3, "holds": False, "fit": v.WORN_FIT}
    assert v._over_fit(o, ok=True)["holds"] is False
    assert v._over_fit(dict(o, in_band=0), ok=False)["holds"] is True
    assert v._over_fit(dict(o, in_band=3), ok=True)["holds"] is True
    assert v._over_fit(None, ok=True) is None


def test_causes_over_fit_judges_each_design_by_the_checks_rule(monkeypatch, tmp_path):
    """validate.causes_over_fit: the mu_rad switch's backward side over the worn fit's designs within
    noise (backward in >= 7/8 of its 32 drops: 0.875 passes, 0.8125 does not, a calm majority does not),
    and the DE-forward check at 3000 rpm over the rotor fit's (>= 7 of its 8 drops forward at the DE)."""
    import json

    import rotorlanding.validate as v

    worn = [{"within_noise_of_best": True, "bw_direction": "backward", "bw_fraction": 0.875},
            {"within_noise_of_best": True, "bw_direction": "backward", "bw_fraction": 0.8125},
            {"within_noise_of_best": True, "bw_direction": "none", "bw_fraction": 1.0},
            {"within_noise_of_best": False, "bw_direction": "backward", "bw_fraction": 1.0}]
    rotor = [{"within_noise_of_best": True, "fw3000_de_forward": 7},
             {"within_noise_of_best": True, "fw3000_de_forward": 6},
             {"within_noise_of_best": True, "fw3000_de_forward": None}]
    for cal, rows, n in ((v.WORN_FIT, worn, 32), (v.ROTOR_FIT, rotor, 8)):
        f = tmp_path / v.STORED_FITS[cal]
        f.parent.mkdir(parents=True)
        f.write_text(json.dumps({"space": cal, "ensemble": n, "designs": rows}))
    monkeypatch.setattr(v, "project_root", lambda: tmp_path)
    c = v.causes_over_fit()
    assert c["mu_rad switch: mu_rad 0.3 whirls backward"] == {"passing": 1, "n_designs": 3, "fit": v.WORN_FIT}
    assert c["mu_rad switch: the same bearing at mu_rad 0.15 is calm"]["passing"] == 0
    assert c["combined landing 3000 rpm whirls forward at the DE"] == {"passing": 1, "n_designs": 3, "fit": v.ROTOR_FIT}


@pytest.mark.parametrize("edit,field", [
    (("script = ", "scriptx = "), "script"),
    (("max = 0.18}", "max = 0.05}"), "ranges.rotor.disks.1.outer_diameter"),
    (("value = 0.1398", "value = \"wide\""), "geometry.NDE_AMB_laminations.outer_diameter"),
    (("speeds_rpm = [7000, 10000]", "speeds_rpm = [7000, -1]"), "speeds_rpm"),
    (("speeds_rpm = [7000, 10000]", "speeds_rpm = [7000, 7500]"), "speeds_rpm"),  # not a Fig. 39 speed
])
def test_a_bad_screen_record_is_one_line(tmp_path, edit, field):
    """validate.load_screen: a broken screen record names its file and field (the brief's bad-input rule)."""
    import rotorlanding.validate as v

    text = (v.project_root() / "scenarios" / "calibration" / "rotor_rise_screen.toml").read_text()
    assert edit[0] in text
    f = tmp_path / "screen.toml"
    f.write_text(text.replace(edit[0], edit[1], 1))
    with pytest.raises(InputError) as err:
        v.load_screen(f)
    assert str(f) in str(err.value) and field in str(err.value) and "\n" not in str(err.value)


def test_heldout_search_range_outside_the_physical_bound_is_flagged(monkeypatch, tmp_path):
    """A held-out fit whose search range reaches outside the sourced bound fits no physical value,
    wherever its pick lands (validate.heldout_pick_positions)."""
    import rotorlanding.validate as v

    (tmp_path / "without_3000rpm_landings.toml").write_text(
        '[ranges]\n"rotor.sections.3.outer_diameter" = {min = 0.030, max = 0.045}\n')
    monkeypatch.setattr(v, "holdout_dir", lambda: tmp_path)
    monkeypatch.setattr(v, "_holdout_best", lambda rpm: {"rotor.sections.3.outer_diameter": 0.0375, "design": 1})
    (q,) = v.heldout_pick_positions(3000)
    assert not q["search_inside"] and q["on_bound"] and 0.05 < q["bound_position"] < 0.95


def test_rise_label_credits_the_screen_only_for_the_rig_rotor():
    """The rig rotor was screened on the whirl's rise; another rotor given with --rig was not."""
    import rotorlanding.validate as v

    assert "screened for the rise" in v.provenance()["rise"]
    assert "screened" not in v.provenance("other_rotor.toml")["rise"]
    # the Fig. 39 rows the screen read (its speeds_rpm, 7000 and 10000 rpm) say so; 3000 rpm was not read
    screened = "screened on it (scenarios/calibration/rotor_rise_screen.toml)"
    prov = v.provenance()
    assert screened in prov["fig39_7000"] and screened in prov["fig39_10000"] and screened not in prov["fig39_3000"]
    assert prov["fig39_7000"].startswith("fitted (scenarios/calibration/rotor_landings.toml")
    assert screened not in v.provenance("other_rotor.toml")["fig39_7000"]


def _windage_study():
    import importlib.util

    path = ROOT / "docs" / "studies" / "windage_bounds.py"
    spec = importlib.util.spec_from_file_location("windage_bounds", path)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def test_windage_laws_reproduce_the_textbook_numbers():
    """docs/studies/windage_bounds.py against hand values: von Karman's free disk, T = 0.073 rho w^2
    R^5 Re^-0.2 per both faces (C_m = 0.146 Re^-0.2 with 0.5 rho w^2 R^5), and Theodorsen & Regier's
    rim law, which at Re = 1.65e6 gives C_f = 0.00264 (solved by hand: 1/sqrt(0.00264) = 19.46 =
    -0.6 + 4.07 log10(1.65e6 x 0.0514))."""
    wb = _windage_study()
    r, rpm = 0.1836, 7000.0
    w = rpm * math.pi / 30
    re = w * r * r / wb.NU_AIR
    t = wb.disk_torques(r, 0.0319, rpm)
    assert t["free_faces"] == pytest.approx(0.073 * wb.RHO_AIR * w * w * r ** 5 * re ** -0.2, rel=1e-12)
    assert t["enclosed_faces"] / t["free_faces"] == pytest.approx(0.0622 / 0.146)
    cf = wb.rim_cf(re)
    assert 1 / math.sqrt(cf) == pytest.approx(-0.6 + 4.07 * math.log10(re * math.sqrt(cf)), rel=1e-9)
    assert cf == pytest.approx(0.00264, rel=0.01)
    # session 29's hand arithmetic (docs/calibration.md, "Session 29"; rig.toml's source text then): the
    # 367.2 x 31.9 mm disk's rim 0.19 N m at 7000 rpm; the Couette drag of a 149.6 x 99.6 mm stack, 4.7e-6
    # N m s at a 1 mm gap, of a 249.1 mm thrust disk's two faces, 1.4e-5
    assert t["rim"] == pytest.approx(0.19, rel=0.03)
    assert wb.c_w1_range([(0.0748, 0.0996)], 0.0)[0] == pytest.approx(4.7e-6, rel=0.02)
    assert wb.c_w1_range([], 0.12455)[0] == pytest.approx(1.36e-5, rel=0.02)
    assert wb.c_w1_range([], 0.12455)[1] == pytest.approx(1.36e-5 / 0.3, rel=0.02)  # the 0.3 mm gap


def test_rig_windage_bounds_describe_the_rig_rotor():
    """The rig file's windage bounds are those derived from the rig rotor's geometry (rounded outward
    to two digits, so within 10 % outside the derived range), and the values lie inside: a new rotor
    cannot keep the old disk's windage (session 30; session 29 found c_w2 1.5x the top of its range)."""
    wb = _windage_study()
    d = wb.derived()
    sc = load_scenario(PAPER / "forward_whirl_landing.toml")
    for key in ("spin.c_w1", "spin.c_w2"):
        lo, hi = d[key]
        b = sc.bounds[key]
        assert 0.9 * lo <= b.min <= lo and hi <= b.max <= 1.1 * hi, (key, (b.min, b.max), (lo, hi))
        assert lo < get_dotted(sc.raw, key) < hi, key


def test_a_tied_unknown_is_one_rig_row_that_fails_when_the_rig_breaks_the_tie(tmp_path):
    """The worn fit sets C_rib at both bearings as one unknown (a tied range): the rig table gives it
    one row, and a rig whose two values differ fails it, naming the tie."""
    import rotorlanding.validate as v

    assert v.tied_followers() == {"bearings.NDE.c_rib": "bearings.DE.c_rib"}
    overlay = tmp_path / "rig.toml"
    overlay.write_text("[bearings.NDE]\nc_rib = 3000.0\n")
    (row,) = [c for c in v.rig_checks(rig=overlay) if "c_rib" in c["check"]]
    assert not row["pass"] and "bearings.NDE.c_rib NOT the same value, though tied in the fit" in row["ours"], row


def test_screen_sleeve_loads_are_the_statics_of_two_supports():
    """docs/studies/rotor_rise_screen.py's static sleeve loads (session 32: Table 1's onset follows the
    DE's) against the lever rule by hand: a uniform 1 m shaft on sleeves at 0.2 and 0.8 m with a 10 kg
    disk overhung at 1.0 m; and the rig rotor's support loads add up to its weight: the sleeves' and
    the motor coupling's, a landed support since session 40 (1e5 N/m), which takes its share."""
    import importlib.util

    spec = importlib.util.spec_from_file_location("rotor_rise_screen", ROOT / "docs" / "studies" / "rotor_rise_screen.py")
    rs = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(rs)
    d = {"rotor": {"name": "t", "materials": {"steel": {"youngs_modulus": 2.1e11, "density": 7850.0, "poisson_ratio": 0.3}},
                   "sections": [{"length": 1.0, "outer_diameter": 0.05, "material": "steel", "elements": 4}],
                   "disks": [{"name": "d", "position": 1.0, "mass": 10.0, "polar_inertia": 0.05, "transverse_inertia": 0.03}],
                   "stations": {"NDE_sleeve": 0.2, "DE_sleeve": 0.8},
                   "supports": [{"station": "NDE_sleeve", "kyy": 3.6e7, "kzz": 3.6e7},
                                {"station": "DE_sleeve", "kyy": 3.6e7, "kzz": 3.6e7}]}}
    from rotorlanding.timoshenko import GRAVITY as g
    shaft = 7850.0 * math.pi / 4 * 0.05 ** 2 * 1.0
    de = (shaft * g * (0.5 - 0.2) + 10.0 * g * (1.0 - 0.2)) / 0.6
    nde, de_s = rs.sleeve_loads(d)
    assert de_s == pytest.approx(de, rel=1e-12)
    assert nde == pytest.approx((shaft + 10.0) * g - de, rel=1e-12)
    rig = load_toml(ROOT / "scenarios" / "rig_rotor.toml")
    from rotorlanding.modefit import static_support_loads
    from rotorlanding.rotor import rotor_from_dict
    loads = static_support_loads(rig)
    assert set(loads) == {"NDE_sleeve", "DE_sleeve", "coupling"}
    assert rs.sleeve_loads(rig) == (loads["NDE_sleeve"], loads["DE_sleeve"])
    assert sum(loads.values()) == pytest.approx(rotor_from_dict(rig).mass * g, rel=1e-12)
    assert 0.0 < loads["coupling"] < 0.05 * rotor_from_dict(rig).mass * g  # a soft coupling: a small share
