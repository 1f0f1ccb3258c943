"""`rotorlanding modes` / `reduce` on the rig rotor, and clear one-line errors for bad input."""

import json
import subprocess
import sys
from pathlib import Path

import pytest

from rotorlanding.cli import main

ROOT = Path(__file__).resolve().parents[1]
RIG = ROOT / "scenarios" / "rig_rotor.toml"


def test_modes_json_on_rig_rotor(capsys, tmp_path):
    png = tmp_path / "campbell.png"
    assert main(["modes", str(RIG), "--speeds-rpm", "0,3000,7000,10000", "--json", "--plot", str(png)]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["speeds_rpm"] == [0, 3000, 7000, 10000]
    assert len(out["modes"]) == 4
    for per_speed in out["modes"]:
        f = [m["frequency_hz"] for m in per_speed]
        assert f == sorted(f) and f[0] > 1.0  # sorted, no rigid-body (zero) modes
        assert all(set(m) == {"frequency_hz", "damping_ratio", "whirl"} for m in per_speed)
        assert all(m["whirl"] in ("forward", "backward", "none") for m in per_speed)
    assert {m["whirl"] for m in out["modes"][0]} == {"none"}
    assert {m["whirl"] for m in out["modes"][2]} == {"forward", "backward"}
    # the lowest pair splits: its backward branch softens, its forward branch stiffens with speed
    f0 = out["modes"][0][0]["frequency_hz"]
    bwd = [min(m["frequency_hz"] for m in s if m["whirl"] == "backward") for s in out["modes"][1:]]
    fwd = [min(m["frequency_hz"] for m in s if m["whirl"] == "forward") for s in out["modes"][1:]]
    assert bwd[2] < bwd[1] < bwd[0] < f0 < fwd[0] < fwd[1] < fwd[2]
    assert png.stat().st_size > 10_000 and png.read_bytes()[:4] == b"\x89PNG"


def test_modes_free_excludes_rigid_modes(capsys):
    assert main(["modes", str(RIG), "--speeds-rpm", "7000", "--json", "--free", "--model", "reduced"]) == 0
    out = json.loads(capsys.readouterr().out)
    # rigid translation and tilt (0 Hz) and the free rotor's gyroscopic nutation (~6 Hz at 7000 rpm)
    # are excluded; the lowest elastic mode (the actuator disk on the shaft) is at ~20 Hz
    assert min(m["frequency_hz"] for m in out["modes"][0]) > 12.0


def test_reduce_table(capsys):
    assert main(["reduce", str(RIG), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["reduced_dofs"] == 19 and max(abs(r["relative_error"]) for r in out["rows"]) < 5e-3


def _write(tmp_path, text, name="bad.toml"):
    p = tmp_path / name
    p.write_text(text)
    return p


RIG_TEXT = RIG.read_text()


@pytest.mark.parametrize("mutate, field, value", [
    (lambda s: s.replace("density = 7850.0", ""), "rotor.materials.steel.density", "None"),
    (lambda s: s.replace("length = 0.1328 ", "length = -0.1328 ", 1), "rotor.sections[0].length", "-0.1328"),
    (lambda s: s.replace("outer_diameter = 0.0596", "outer_diameter = -0.0596", 1), "rotor.sections[1].outer_diameter", "-0.0596"),
    (lambda s: s.replace("density = 7850.0", "density = -7850.0"), "rotor.materials.steel.density", "-7850.0"),
    (lambda s: s.replace('material = "steel"\nelements = 4', 'inner_diameter = 0.095\nmaterial = "steel"\nelements = 4', 1),
     "rotor.sections[0].inner_diameter", "0.095"),
    (lambda s: s.replace('station = "DE_sleeve"', 'station = "DE_sleve"'), "rotor.supports[1].station", "DE_sleve"),
    (lambda s: s.replace('"NDE_sleeve", "DE_sleeve"]', '"NDE_sleeve", "XX"]'), "rotor.reduction.boundary_stations[1]", "XX"),
    (lambda s: s.replace("elements = 2\n", "elemnts = 2\n", 1), "rotor.sections[1].elemnts", "2"),
    (lambda s: s.replace("[rotor.stations]", "[rotor.stations\n"), "(syntax)", ""),
])
def test_bad_input_one_line_error_exit_2(tmp_path, capsys, mutate, field, value):
    bad = _write(tmp_path, mutate(RIG_TEXT))
    assert main(["modes", str(bad), "--model", "reduced"]) == 2
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and "Traceback" not in err
    assert str(bad) in err and field in err and value in err


def test_bad_speeds_and_missing_file(tmp_path, capsys):
    assert main(["modes", str(RIG), "--speeds-rpm", "0,abc"]) == 2
    assert "--speeds-rpm" in capsys.readouterr().err
    assert main(["modes", str(RIG), "--speeds-rpm", "-5"]) == 2
    assert main(["modes", str(tmp_path / "nope.toml")]) == 2
    assert "file not found" in capsys.readouterr().err


def test_scenario_file_with_include_is_accepted(tmp_path, capsys):
    (tmp_path / "rig").mkdir()
    (tmp_path / "rig" / "rotor.toml").write_text(RIG_TEXT)
    scen = _write(tmp_path, 'include = ["rig/rotor.toml"]\n[operating]\nspeed_rpm = 7000\n', "scenario.toml")
    assert main(["modes", str(scen), "--speeds-rpm", "7000", "--json"]) == 0
    assert len(json.loads(capsys.readouterr().out)["modes"][0]) == 8


def test_console_entry_point_exit_code_without_traceback(tmp_path):
    bad = _write(tmp_path, "[rotor\n")
    proc = subprocess.run([sys.executable, "-m", "rotorlanding", "modes", str(bad)], capture_output=True, text=True)
    assert proc.returncode == 2
    assert "Traceback" not in proc.stderr and proc.stderr.count("\n") == 1 and str(bad) in proc.stderr
