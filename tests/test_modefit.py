"""fit-modes: recovers a known geometry from its own mode frequencies; bad input names the field;
the committed rig rotor is the fit's result."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from rotorlanding.cli import main
from rotorlanding.config import load_toml
from rotorlanding.errors import InputError
from rotorlanding.modefit import fit_modes, load_space, matched_modes, rotor_with

ROOT = Path(__file__).resolve().parents[1]
RIG_SPACE = ROOT / "scenarios" / "calibration" / "rotor_modes.toml"

ROTOR = """
[rotor]
name = "overhung disk test rotor"
[rotor.materials.steel]
youngs_modulus = 2.1e11
poisson_ratio = 0.3
density = 7850.0
[[rotor.sections]]
length = 0.2
outer_diameter = 0.04
material = "steel"
elements = 4
[[rotor.sections]]
length = 0.5
outer_diameter = 0.04
material = "steel"
elements = 8
[rotor.stations]
A = 0.2
B = 0.7
[[rotor.disks]]
name = "disk"
position = 0.0
outer_diameter = 0.2
thickness = 0.03
material = "steel"
[[rotor.supports]]
station = "A"
kyy = 1e8
kzz = 1e8
[[rotor.supports]]
station = "B"
kyy = 1e8
kzz = 1e8
"""


def _space(tmp_path, targets, extra="", ranges='"rotor.disks.0.outer_diameter" = {min = 0.1, max = 0.3}'):
    (tmp_path / "rotor.toml").write_text(ROTOR)
    p = tmp_path / "space.toml"
    p.write_text(f"""rotor = "rotor.toml"
support_stiffness = 1e8
lock_ratio = 0.95
seed = 1
popsize = 6
maxiter = 12
{extra}
[targets]
speeds_rpm = [0.0, 6000.0]
frequencies_hz = {targets}
[ranges]
{ranges}
""")
    return p


def test_fit_recovers_the_geometry_that_made_the_targets(tmp_path):
    data = load_toml(_space(tmp_path, "[1.0, 1.0]").parent / "rotor.toml")
    # the overhung disk's forward mode at 0 and 6000 rpm, with D = 0.23 m, seen through lock_ratio
    guess = [50.0, 60.0]
    modes = matched_modes(rotor_with(data, {"rotor.disks.0.outer_diameter": 0.23}, 1e8), [0.0, 6000.0], guess)
    assert modes[1] > modes[0]  # gyroscopic stiffening of the forward mode
    targets = [round(float(0.95 * f), 6) for f in modes]
    res = fit_modes(_space(tmp_path, str(targets)), tmp_path / "out")
    assert res["values"]["rotor.disks.0.outer_diameter"] == pytest.approx(0.23, rel=2e-3)
    assert max(abs(e) for e in res["relative_error"]) < 2e-3
    written = json.loads((tmp_path / "out" / "modefit.json").read_text())
    assert written["values"] == res["values"]
    # deterministic: a re-run gives the same values
    assert fit_modes(_space(tmp_path, str(targets)))["values"] == res["values"]


def test_mode_is_kept_below_the_allowed_fraction_of_spin(tmp_path):
    # targets made with D = 0.2 m (mode 93.5 Hz at 6000 rpm = 0.93 x spin); allowing at most
    # 0.85 x spin forces a bigger disk whose mode sits at the limit
    data = load_toml(_space(tmp_path, "[1.0, 1.0]").parent / "rotor.toml")
    modes = matched_modes(rotor_with(data, {"rotor.disks.0.outer_diameter": 0.2}, 1e8), [0.0, 6000.0], [80.0, 90.0])
    targets = [round(float(0.95 * f), 6) for f in modes]
    p = _space(tmp_path, str(targets)).read_text().replace("[targets]", "[targets]\nmax_mode_to_spin = 0.85")
    (tmp_path / "space.toml").write_text(p)
    res = fit_modes(tmp_path / "space.toml")
    assert 0.83 < res["mode_to_spin"][1] <= 0.8505
    assert res["values"]["rotor.disks.0.outer_diameter"] > 0.21


def test_held_out_speed_is_predicted_and_keeps_the_spin_constraint(tmp_path):
    """Fitted on 0 and 6000 rpm only, the rotor predicts the 3000 rpm mode the true geometry has
    (an independent modal computation); a held-out speed carries no target, but the spin
    constraint (physics, not data) holds there."""
    data = load_toml(_space(tmp_path, "[1.0, 1.0]").parent / "rotor.toml")
    true = rotor_with(data, {"rotor.disks.0.outer_diameter": 0.23}, 1e8)
    modes = matched_modes(true, [0.0, 3000.0, 6000.0], [50.0, 55.0, 60.0])
    targets = [round(float(0.95 * f), 6) for f in (modes[0], modes[2])]
    p = _space(tmp_path, str(targets)).read_text().replace("[targets]", "[targets]\npredict_speeds_rpm = [3000.0]")
    (tmp_path / "space.toml").write_text(p)
    res = fit_modes(tmp_path / "space.toml")
    (held,) = res["held_out"]
    assert held["speed_rpm"] == 3000.0 and held["mode_hz"] == pytest.approx(modes[1], rel=3e-3)
    assert len(res["mode_hz"]) == len(res["relative_error"]) == 2  # the held-out speed is not in the fit
    # only 0 rpm fitted, 6000 rpm held out with at most 0.85 x spin: the fit must respect it there
    low = _space(tmp_path, f"[{targets[0]}]").read_text().replace("speeds_rpm = [0.0, 6000.0]", "speeds_rpm = [0.0]")
    (tmp_path / "space.toml").write_text(low.replace("[targets]", "[targets]\npredict_speeds_rpm = [6000.0]\n"
                                                                  "max_mode_to_spin = 0.85"))
    res = fit_modes(tmp_path / "space.toml")
    assert res["held_out"][0]["mode_to_spin"] <= 0.8505


def test_held_out_speed_must_not_be_a_fitted_one(tmp_path):
    p = _space(tmp_path, "[40.0, 50.0]")
    p.write_text(p.read_text().replace("[targets]", "[targets]\npredict_speeds_rpm = [6000.0]"))
    with pytest.raises(InputError, match="targets.predict_speeds_rpm"):
        load_space(p)


@pytest.mark.parametrize("extra, ranges, field", [
    ("", '"rotor.disks.0.outer_diametr" = {min = 0.1, max = 0.3}', "ranges.rotor.disks.0.outer_diametr"),
    ("", '"rotor.disks.0.outer_diameter" = {min = 0.3, max = 0.1}', "ranges.rotor.disks.0.outer_diameter"),
    ("bogus = 1", '"rotor.disks.0.outer_diameter" = {min = 0.1, max = 0.3}', "bogus"),
])
def test_bad_space_names_the_field(tmp_path, extra, ranges, field):
    p = _space(tmp_path, "[40.0, 50.0]", extra, ranges)
    with pytest.raises(InputError) as err:
        load_space(p)
    assert field in str(err.value) and str(p) in str(err.value)
    assert main(["fit-modes", str(p), "--out", str(tmp_path / "o")]) == 2


def test_rig_rotor_modes_predict_fig39_within_10_percent():
    # the committed rig rotor carries the fit's values: its forward mode, times the lock ratio
    # measured on landings, lies within 10 % of the paper's experimental whirl frequencies
    sp = load_space(RIG_SPACE)
    data = rotor_with(sp["rotor_data"], {}, sp["support_stiffness"])
    targets = [f / sp["lock_ratio"] for f in sp["frequencies_hz"]]
    modes = matched_modes(data, sp["speeds_rpm"], targets)
    for m, f in zip(modes, sp["frequencies_hz"]):
        assert m * sp["lock_ratio"] == pytest.approx(f, rel=0.10)
    assert modes[0] < modes[1] < modes[2]


def test_rig_overlay_replaces_the_rotor_of_a_paper_scenario(tmp_path, capsys):
    from rotorlanding.scenario import load_scenario

    paper = ROOT / "scenarios" / "paper" / "forward_whirl_landing.toml"
    first = ROOT / "scenarios" / "rig_rotor_first.toml"
    base = load_scenario(paper)
    sc = load_scenario(paper, overlays=[first])
    assert "actuator_disk" in [d.name for d in base.rotor.disks]
    assert "actuator_disk" not in [d.name for d in sc.rotor.disks]
    assert sc.rotor.sections[3].outer_diameter == pytest.approx(0.05)
    # everything else of the scenario stays: thrust, friction, speed
    assert (sc.axial.f_thrust, sc.contact.mu_ax, sc.speed_rpm) == (base.axial.f_thrust, base.contact.mu_ax, base.speed_rpm)
    assert main(["validate", "--out", str(tmp_path / "v"), "--rig", str(tmp_path / "missing.toml")]) == 2
    assert "--rig" in capsys.readouterr().err
