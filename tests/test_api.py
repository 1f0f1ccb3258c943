"""The Python API (rotorlanding.api): rotors built in Python round-trip through TOML, simulate()
gives the CLI's summary bit for bit, results save and load, bad input is one InputError line."""

import json
import pydoc
from pathlib import Path

import numpy as np
import pytest

import rotorlanding as rl
from rotorlanding.cli import main
from rotorlanding.results import read_results

ROOT = Path(__file__).resolve().parents[1]
SCEN = ROOT / "scenarios" / "landing_7000rpm.toml"
T_END = 0.05

STEEL = {"youngs_modulus": 2.1e11, "poisson_ratio": 0.3, "density": 7850.0}


def python_rotor(**changes):
    kw = dict(
        name="two-disk test rotor",
        materials={"steel": STEEL, "alu": {"youngs_modulus": 7.0e10, "shear_modulus": 2.6e10, "density": 2700.0}},
        sections=[{"length": 0.1, "outer_diameter": 0.06, "material": "steel", "elements": 2},
                  {"length": 0.6, "outer_diameter": 0.04, "inner_diameter": 0.01, "material": "steel", "elements": 9},
                  {"length": 0.1, "outer_diameter": 0.06, "material": "alu", "elements": 2}],
        disks=[{"name": "impeller", "position": 0.3, "mass": 4.3, "polar_inertia": 0.0213,
                "transverse_inertia": 0.0113},
               {"name": "thrust", "position": 0.55, "outer_diameter": 0.16, "thickness": 0.02, "material": "steel"}],
        stations={"NDE": 0.05, "DE": 0.75},
        supports=[{"station": "NDE", "kyy": 1e7, "kzz": 1.2e7, "cyy": 300.0}, {"station": "DE", "kyy": 1e7, "kzz": 1e7}],
        reduction={"boundary_stations": ["NDE", "DE"], "modes": 6},
        damping={"mass_proportional": 0.5, "stiffness_proportional": 1e-5},
        max_speed_rpm=12000.0)
    kw.update(changes)
    return rl.Rotor(**kw)


@pytest.mark.parametrize("source", ["python", "rig"])
def test_rotor_toml_round_trip_gives_identical_fe_matrices(tmp_path, source):
    rotor = python_rotor() if source == "python" else rl.Rotor.from_toml(ROOT / "scenarios" / "rig_rotor.toml")
    back = rl.Rotor.from_toml(rotor.to_toml(tmp_path / "rotor.toml"))
    a, b = rotor.fe(), back.fe()
    for name in ("nodes", "M", "K", "G", "C"):
        assert np.array_equal(getattr(a, name), getattr(b, name)), name
    assert a.station_nodes == b.station_nodes and a.disk_nodes == b.disk_nodes
    assert back.model == rotor.model  # every validated field (dataclass equality)
    assert rotor.mass > 1.0


def test_numpy_values_round_trip(tmp_path):
    """A rotor built from numpy numbers (a script's usual values) writes plain TOML and reads back."""
    lengths = np.linspace(0.2, 0.4, 3)
    rotor = python_rotor(sections=[{"length": L, "outer_diameter": np.float64(0.05), "material": "steel",
                                    "elements": np.int64(3)} for L in lengths],
                         stations={"NDE": np.float64(0.05), "DE": 0.75})
    back = rl.Rotor.from_toml(rotor.to_toml(tmp_path / "r.toml"))
    assert "np." not in (tmp_path / "r.toml").read_text()
    assert np.array_equal(back.fe().K, rotor.fe().K) and back.model == rotor.model


def test_rotor_modes_match_the_cli_on_the_written_file(tmp_path, capsys):
    rotor = python_rotor()
    path = rotor.to_toml(tmp_path / "rotor.toml")
    modes = rotor.modes([0.0, 6000.0], n_modes=4)
    assert main(["modes", str(path), "--speeds-rpm", "0,6000", "--n-modes", "4", "--json"]) == 0
    cli = json.loads(capsys.readouterr().out)
    assert cli["modes"] == modes.to_dict()["modes"]
    assert modes.frequencies_hz.shape == (2, 4) and np.all(modes.frequencies_hz > 1.0)
    assert set(modes.whirl[1]) <= {"forward", "backward"}  # at speed every mode has a sense
    png = modes.campbell(tmp_path / "campbell.png", points=9)
    assert png.stat().st_size > 10000


@pytest.fixture(scope="module")
def cli_and_api(tmp_path_factory):
    out = tmp_path_factory.mktemp("cli")
    assert main(["run", str(SCEN), "--out", str(out), "--t-end", str(T_END), "--quiet", "--no-plots"]) == 0
    landing = rl.simulate(rl.Scenario.load(SCEN), t_end=T_END)
    return out, landing


WALL = ("wall_s", "wall_s_per_simulated_s")


def _without_wall(summary: dict) -> dict:
    s = json.loads(json.dumps(summary))
    for k in WALL:
        s["performance"].pop(k)
    return s


def test_simulate_gives_the_cli_summary_bit_for_bit(cli_and_api):
    out, landing = cli_and_api
    cli = json.loads((out / "summary.json").read_text())
    assert landing.complete and cli["complete"]
    assert json.dumps(_without_wall(landing.summary), sort_keys=True) == json.dumps(_without_wall(cli), sort_keys=True)
    # and the time series of the CLI's results.h5, array for array
    res = read_results(out / "results.h5")
    assert np.array_equal(res["time_s"], landing.t) and np.array_equal(res["q"], landing.q)
    assert sorted(res["series"]) == sorted(landing.series_names)
    for k, v in res["series"].items():
        assert np.array_equal(v, landing[k].values), k
    assert landing.t[-1] == pytest.approx(T_END)


def test_series_carry_the_registry_units(cli_and_api):
    _, landing = cli_and_api
    assert landing["DE_normal_force_n"].unit == "N"
    assert landing.series("rotor_speed_rpm").unit == "rpm"
    assert landing["NDE_y_m"].unit == "m"
    assert all(landing.units[k] for k in landing.series_names)
    assert np.asarray(landing["DE_normal_force_n"]).shape == landing.t.shape
    # the summary's peak force is |force on the rotor| (race contact + face rub), at least the
    # normal force of the race contact alone
    peak = landing.summary["bearings"]["DE"]["max_contact_force_n"]
    assert np.max(np.abs(landing["DE_normal_force_n"].values)) <= peak * (1 + 1e-12)
    assert peak > 1000.0  # landed
    assert landing.whirl["direction"] in ("none", "forward", "backward")
    with pytest.raises(rl.InputError, match="unknown series"):
        landing["DE_force"]


def test_save_load_round_trip(cli_and_api, tmp_path):
    _, landing = cli_and_api
    path = landing.save(tmp_path / "results.h5")
    back = rl.Landing.load(path)
    assert back.summary == landing.summary
    assert np.array_equal(back.t, landing.t) and np.array_equal(back.q, landing.q) and np.array_equal(back.v, landing.v)
    assert back.units == landing.units and back.series_names == landing.series_names
    for k in landing.series_names:
        assert np.array_equal(back[k].values, landing[k].values), k
    assert back.scenario.model.raw == landing.scenario.model.raw
    assert back.whirl == landing.whirl


def test_plots_write_labelled_figures(cli_and_api, tmp_path):
    _, landing = cli_and_api
    for fn in (landing.plot_orbits, landing.plot_displacements, landing.plot_spectrum, landing.plot_span):
        p = fn(tmp_path / f"{fn.__name__}.png")
        assert p.stat().st_size > 10000


def test_scenario_overrides_and_replace():
    sc = rl.Scenario.load(SCEN, set={"contact.mu_rad": 0.2, "operating.t_end": 0.01})
    assert sc.model.contact.mu_rad == 0.2 and sc.t_end == 0.01
    sc2 = sc.replace(operating__speed_rpm=9000.0)
    assert sc2.speed_rpm == 9000.0 and sc.speed_rpm == 7000.0  # the original is unchanged
    sc3 = sc.with_overrides({"effects.race_windage": False})
    assert sc3.model.effects["race_windage"] is False


def test_scenario_to_toml_round_trip(tmp_path):
    sc = rl.Scenario.load(SCEN)
    back = rl.Scenario.load(sc.to_toml(tmp_path / "sc.toml"))
    assert back.model.raw == sc.model.raw and back.name == sc.name


@pytest.mark.parametrize("build, field", [
    (lambda: python_rotor(sections=[{"length": -0.1, "outer_diameter": 0.05, "material": "steel"}]),
     "rotor.sections[0].length"),
    (lambda: python_rotor(stations={"NDE": 0.05, "DE": 2.0}), "rotor.stations.DE"),
    (lambda: python_rotor(disks=[{"name": "d", "position": 0.3, "mass": 1.0, "polar_inertia": 0.01,
                                  "transverse_inertia": 0.005, "colour": "red"}]), "rotor.disks[0].colour"),
    (lambda: rl.Scenario.load(SCEN, set={"contact.mu_radial": 0.2}), "contact.mu_radial"),
    (lambda: rl.Scenario.load(SCEN).replace(operating__t_end=-1.0), "operating.t_end"),
    (lambda: python_rotor().modes([-5.0]), "speeds_rpm"),
    (lambda: python_rotor().modes([1e6]), "speeds_rpm"),  # above the burst speed
    (lambda: python_rotor(sections=[0.1, 0.05]), "rotor.sections[0]"),
    (lambda: python_rotor(materials=["steel"]), "rotor.materials"),
])
def test_bad_input_is_one_line_input_error(build, field):
    with pytest.raises(rl.InputError) as exc:
        build()
    assert exc.value.field == field
    assert "\n" not in str(exc.value) and field in str(exc.value)


def test_bad_input_matches_the_toml_path(tmp_path):
    """The same bad value gives the same message in Python and from a file."""
    good = python_rotor()
    table = good.table
    table["sections"][1]["inner_diameter"] = 0.05  # >= outer diameter
    path = tmp_path / "bad.toml"
    path.write_text(rl.api._toml_dump({"rotor": table}))
    with pytest.raises(rl.InputError) as from_file:
        rl.Rotor.from_toml(path)
    with pytest.raises(rl.InputError) as from_python:
        rl.Rotor.from_table(table)
    assert from_file.value.field == from_python.value.field == "rotor.sections[1].inner_diameter"
    assert from_file.value.allowed == from_python.value.allowed
    assert str(from_file.value).startswith(str(path))


def test_help_of_simulate_states_units():
    text = pydoc.render_doc(rl.simulate, renderer=pydoc.plaintext)
    for unit in ("[s]", "[m]", "[N]", "[rpm]", "[J]"):
        assert unit in text
    assert set(rl.__all__) >= {"Rotor", "Scenario", "simulate", "Landing", "InputError"}


def test_python_api_doc_covers_every_public_name_and_member():
    text = (ROOT / "docs" / "python_api.md").read_text()
    base = set(dir(ValueError))
    missing = []
    for name in rl.__all__:
        if f"`{name}" not in text and name not in text:
            missing.append(name)
        obj = getattr(rl, name)
        if isinstance(obj, type):
            members = [m for m in vars(obj) if not m.startswith("_")] if obj is not rl.InputError else \
                [m for m in vars(obj) if not m.startswith("_") and m not in base]
            missing += [f"{name}.{m}" for m in members if m not in text]
    assert not missing


def test_readme_python_section_runs(tmp_path, monkeypatch):
    """The README's Python snippet, with a shorter t_end, runs as written."""
    readme = (ROOT / "README.md").read_text()
    code = readme.split("## Python", 1)[1].split("```python", 1)[1].split("```", 1)[0]
    code = code.replace('"operating.t_end": 0.3', '"operating.t_end": 0.02')
    monkeypatch.chdir(ROOT)
    code = code.replace('"orbits.png"', repr(str(tmp_path / "o.png"))).replace(
        '"results.h5"', repr(str(tmp_path / "r.h5"))).replace(
        '.campbell("campbell.png")', f'.campbell({str(tmp_path / "c.png")!r}, points=3)')
    exec(compile(code, "README.md", "exec"), {})
    assert (tmp_path / "r.h5").is_file() and (tmp_path / "c.png").is_file()


def test_with_rotor_keeps_the_close_clearances_at_the_stations_it_has():
    """The rig's AMB gaps are at stations of the rig rotor: a new rotor with those stations keeps them,
    one without them leaves them out (its own are given with with_overrides, and a station it lacks is
    refused, one line)."""
    sc = rl.Scenario.load(SCEN)
    gaps = sc.model.raw["limits"]["close_clearances_m"]
    assert set(gaps) == {"NDE_AMB", "DE_AMB"}  # the rig gives its AMB gaps
    table = sc.model.raw["rotor"]
    assert sc.with_rotor(rl.Rotor.from_table(table)).model.raw["limits"]["close_clearances_m"] == gaps
    keep = ("NDE_sleeve", "DE_sleeve", "coupling")  # a rotor without the AMB stations
    mine = rl.Rotor.from_table({**table, "stations": {k: table["stations"][k] for k in keep}})
    sc2 = sc.with_rotor(mine)
    assert sc2.model.raw["limits"]["close_clearances_m"] == {}
    assert sc2.with_overrides({"limits.close_clearances_m.DE_sleeve": 3e-4}).model.raw["limits"][
        "close_clearances_m"] == {"DE_sleeve": 3e-4}
    with pytest.raises(rl.InputError, match="limits.close_clearances_m.DE_AMB"):
        sc2.with_overrides({"limits.close_clearances_m.DE_AMB": 4e-4})
