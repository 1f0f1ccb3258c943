"""Any number of catcher bearings with user names (issue 17, point 4): a rotor with a third
catcher bearing at mid-span lands on all three, and the energy balance still closes."""

import json
from pathlib import Path

import pytest

from rotorlanding.cli import main
from rotorlanding.errors import InputError
from rotorlanding.landing import build_spec
from rotorlanding.scenario import load_scenario

ROOT = Path(__file__).resolve().parents[1]
BASE = (ROOT / "scenarios" / "paper" / "no_whirl_landing.toml").as_posix()
MID = """
[rotor.reduction]
boundary_stations = ["NDE_sleeve", "speed_sensor", "DE_sleeve"]
[bearings.MID]
station = "speed_sensor"
clearance = 2.0e-4                 # as the DE and NDE bearings: the session-15 rotor's mid-span drops 0.27 mm in 0.05 s (0.4 mm was never reached)
sleeve_radius = 0.0298
inner_race_mass = 0.28
inner_race_inertia = 3.2e-4
inner_race_damping = 0.0
outer_race_mass = 0.8
outer_race_damping = 0.0
k_b1 = 1.5e8
k_b2 = 3.0e12
c_b = 200.0
contact_angle_deg = 40.0
static_load_rating = 4.5e4
pitch_diameter = 0.085
hp_z = 0.001
hp_y = 0.33
k_rib = 6.3e7
c_rib = 2.0e3
eta = 0.1
mu_d = 0.1
axial_face = false
"""


@pytest.fixture
def three(tmp_path):
    f = tmp_path / "three.toml"
    f.write_text(f'include = ["{BASE}"]\n{MID}')
    return f


def test_three_catcher_bearings_land_and_the_energy_balance_closes(three, tmp_path, capsys):
    spec = build_spec(load_scenario(three))
    assert spec.bearing_names == ["DE", "NDE", "MID"]
    assert [n for n in spec.names if n.startswith("MID.")] == [f"MID.{c}" for c in
                                                               ("race_y", "race_z", "race_phi", "outer_y", "outer_z")]
    out = tmp_path / "out"
    assert main(["run", str(three), "--out", str(out), "--t-end", "0.05"]) == 0
    s = json.loads((out / "summary.json").read_text())
    assert set(s["bearings"]) == {"DE", "NDE", "MID"}
    assert set(s["whirl"]["per_bearing"]) == {"DE", "NDE", "MID"}
    # the rotor falls onto all three: a contact force at the mid-span bearing too
    assert all(s["bearings"][b]["max_contact_force_n"] > 100.0 for b in ("DE", "NDE", "MID"))
    assert abs(s["energy"]["balance_error_relative"]) < 1e-3


@pytest.mark.parametrize("text, field", [
    ("[bearings.MID]\nstation = \"DE_sleeve\"", "bearings.MID"),          # not a full table: names the bearing
    ("[bearings.\"MID_1\"]\nstation = \"speed_sensor\"", "bearings.MID_1"),  # "_" would split the series names
    ("[operating]\norientation = \"vertical\"", "operating.orientation"),
])
def test_bad_bearing_tables_and_a_vertical_machine_are_refused(tmp_path, text, field):
    f = tmp_path / "s.toml"
    f.write_text(f'include = ["{BASE}"]\n{text}\n')
    with pytest.raises(InputError) as err:
        load_scenario(f)
    assert field in str(err.value)


def test_two_bearings_on_one_station_are_refused(three, tmp_path):
    f = tmp_path / "dup.toml"
    f.write_text(three.read_text().replace('station = "speed_sensor"', 'station = "DE_sleeve"'))
    with pytest.raises(InputError, match="bearings.MID.station.*one catcher bearing per station"):
        load_scenario(f)
