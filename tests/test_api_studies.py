"""rl.coastdown, rl.sweep and rl.diagnose (rotorlanding.api_studies): each is the command's run
from Python, so its result is compared with what the command writes on the same input (an
independent path through argparse and the files), apart from measured wall-clock figures."""

import csv
import importlib.util
import inspect
import json
import pydoc
from pathlib import Path

import numpy as np
import pytest

import rotorlanding as rl
from rotorlanding.cli import main

ROOT = Path(__file__).resolve().parents[1]
CD_SCEN = ROOT / "scenarios" / "coastdown_7000rpm.toml"
LANDING = ROOT / "scenarios" / "landing_7000rpm.toml"
PAPER_MODEL = ROOT / "scenarios" / "paper" / "forward_whirl_landing.toml"
PAPER_TABLE = ROOT / "scenarios" / "measured" / "paper_table2_fig39.toml"
# two chunks of 0.02 s: the chunked, committed path without a long solve
CD_T_END = 0.04
CD_SET = {"coastdown.chunk_s": 0.02, "coastdown.decimate_every": 10}
# wall-clock and process-memory figures differ from run to run, and so does the size of results.h5
# by a few bytes (its stored summary holds those figures as text: 0.513908 vs 0.513917 MB over four
# identical runs, measured on i19-api2); everything else must not
CD_WALL = ("wall_s", "solver_wall_s", "wall_s_per_simulated_s", "peak_memory_mb", "results_h5_mb")


def _without_wall(summary: dict) -> dict:
    s = json.loads(json.dumps(summary))
    for k in CD_WALL:
        s["performance"].pop(k)
    return s


def _cli_set(d: dict) -> list[str]:
    return [a for k, v in d.items() for a in ("--set", f"{k}={v!r}")]


# ---------------------------------------------------------------------------------------------
# the package attributes are the functions, the machinery has its own modules

def test_api_names_are_plain_functions_and_the_machinery_modules_are_separate():
    import rotorlanding.api_studies as studies

    for name in ("coastdown", "sweep", "diagnose"):
        f = getattr(rl, name)
        assert inspect.isfunction(f) and f is getattr(studies, name), name
        assert importlib.util.find_spec(f"rotorlanding.{name}") is None, f"a module rotorlanding.{name} is back"
        assert importlib.util.find_spec(f"rotorlanding.{name}_run") is not None
    from rotorlanding.coastdown_run import run_coastdown
    from rotorlanding.diagnose_run import run_diagnose
    from rotorlanding.sweep_run import run_sweep

    assert callable(run_coastdown) and callable(run_sweep) and callable(run_diagnose)
    # importing the machinery does not shadow the functions (a submodule import sets a package attribute)
    assert inspect.isfunction(rl.coastdown) and inspect.isfunction(rl.sweep) and inspect.isfunction(rl.diagnose)


@pytest.mark.parametrize("name, words", [("coastdown", ["t_end", "[s]", "[rpm]"]), ("sweep", ["workers", "grid", "rpm"]),
                                         ("diagnose", ["t_end", "[s]", "candidates", "time_offset_s"])])
def test_help_states_parameters_and_units(name, words):
    text = pydoc.render_doc(getattr(rl, name), renderer=pydoc.plaintext)
    for w in words:
        assert w in text, (name, w)


# ---------------------------------------------------------------------------------------------
# coastdown

@pytest.fixture(scope="module")
def coastdowns(tmp_path_factory):
    cli = tmp_path_factory.mktemp("cd_cli")
    assert main(["coastdown", str(CD_SCEN), "--out", str(cli), "--t-end", str(CD_T_END), "--quiet",
                 *_cli_set(CD_SET)]) == 0
    api_out = tmp_path_factory.mktemp("cd_api")
    return cli, rl.coastdown(CD_SCEN, api_out, t_end=CD_T_END, set=CD_SET)


def test_coastdown_gives_the_cli_summary_bit_for_bit(coastdowns):
    cli, cd = coastdowns
    cli_summary = json.loads((cli / "summary.json").read_text())
    assert cd.complete and cli_summary["complete"] and cd.summary["stop_reason"].startswith("t_end")
    assert cd.summary["performance"]["simulated_s"] == pytest.approx(CD_T_END)
    assert cd.summary["performance"]["chunks"] == 2
    assert json.dumps(_without_wall(cd.summary), sort_keys=True) == json.dumps(_without_wall(cli_summary),
                                                                             sort_keys=True)
    # the summary returned is the summary.json written in the API's folder
    assert cd.summary == json.loads((cd.path.parent / "summary.json").read_text())
    back = rl.Coastdown.load(cli)
    assert back.summary == cli_summary
    assert np.array_equal(back.t, cd.t) and back.series_names == cd.series_names
    for k in cd.series_names:
        assert np.array_equal(back[k].values, cd[k].values), k


def test_coastdown_series_units_scenario_and_figures(coastdowns, tmp_path):
    _, cd = coastdowns
    assert cd["rotor_speed_rpm"].unit == "rpm" and cd["DE_normal_force_n"].unit == "N" and cd["DE_y_m"].unit == "m"
    assert cd.t[-1] == pytest.approx(CD_T_END) and len(cd["DE_y_m"]) == len(cd.t)
    assert len(cd.chunks["t_end_s"]) == cd.summary["performance"]["chunks"]
    # the stored scenario is the file's (clearances read back from it, not from the summary)
    from rotorlanding.coastdown_run import load_coastdown

    model, _ = load_coastdown(str(CD_SCEN))
    assert cd.clearances == {b: bb.clearance for b, bb in model.bearings.items()} and len(cd.clearances) == 2
    with pytest.raises(rl.InputError, match="unknown series"):
        cd["DE_force"]
    assert rl.Coastdown.load(cd.path).summary == cd.summary
    for plot in (cd.plot_speeds, cd.plot_displacements, cd.plot_forces):
        assert plot(tmp_path / f"{plot.__name__}.png").stat().st_size > 10000


def test_coastdown_of_a_scenario_object_is_the_coastdown_of_its_file(coastdowns, tmp_path):
    """A Scenario (no [coastdown] table: the defaults, plus `set`) runs as its file does."""
    kw = dict(t_end=CD_T_END, set=CD_SET)
    from_file = rl.coastdown(LANDING, tmp_path / "file", **kw)
    from_object = rl.coastdown(rl.Scenario.load(LANDING), tmp_path / "object", **kw)
    assert from_object.summary["performance"]["chunks"] == 2 and from_object.summary["coastdown"]["chunk_s"] == 0.02
    assert _without_wall(from_object.summary) == _without_wall(from_file.summary)
    assert np.array_equal(from_object["DE_y_m"].values, from_file["DE_y_m"].values)


def test_coastdown_refuses_bad_input_and_wrong_files(tmp_path):
    with pytest.raises(rl.InputError) as exc:  # a Scenario with a [coastdown] value set: validated
        rl.coastdown(rl.Scenario.load(LANDING), tmp_path / "x", set={"coastdown.stop_speed_rpm": 8000.0})
    assert exc.value.field == "coastdown.stop_speed_rpm"
    assert not (tmp_path / "x").exists()
    with pytest.raises(rl.InputError, match="coastdown.chunk_s"):
        rl.coastdown(CD_SCEN, tmp_path / "y", set={"coastdown.chunk_s": -1.0})
    assert not (tmp_path / "y" / "results.h5").exists()
    for bad in ("0.1", -1.0, float("nan")):
        with pytest.raises(rl.InputError) as exc:
            rl.coastdown(CD_SCEN, tmp_path / "z", t_end=bad)
        assert exc.value.field == "t_end"
    with pytest.raises(rl.InputError, match="overwrite"):
        rl.coastdown(CD_SCEN, tmp_path / "z", resume=True, overwrite=True)
    landing = rl.simulate(rl.Scenario.load(LANDING), t_end=0.005)
    with pytest.raises(rl.InputError, match="not a coastdown"):
        rl.Coastdown.load(landing.save(tmp_path / "landing.h5"))


# ---------------------------------------------------------------------------------------------
# sweep

GRID = {"operating.speed_rpm": [3000.0, 7000.0]}
FIXED = {"operating.t_end": 0.02}


def _sweep_file(tmp_path) -> Path:
    f = tmp_path / "tiny_sweep.toml"
    f.write_text(f'scenario = "{LANDING}"\nmode = "grid"\n'
                 '[fixed]\n"operating.t_end" = 0.02\n[grid]\n"operating.speed_rpm" = [3000.0, 7000.0]\n')
    return f


def _csv_rows(path: Path) -> list[dict]:
    with open(path, newline="") as fh:
        return list(csv.DictReader(fh))


def _same_rows(a_csv: Path, b_csv: Path) -> None:
    a_rows, b_rows = _csv_rows(a_csv), _csv_rows(b_csv)
    assert len(a_rows) == len(b_rows) == 2 and list(a_rows[0]) == list(b_rows[0])  # same columns, same order
    for a, b in zip(a_rows, b_rows):
        assert a.pop("wall_s") and b.pop("wall_s")  # wall time: measured, differs
        assert a == b  # every other cell, as text


def test_sweep_gives_the_cli_sweep_csv(tmp_path):
    f = _sweep_file(tmp_path)
    assert main(["sweep", str(f), "--out", str(tmp_path / "cli"), "--workers", "1"]) == 0
    sw = rl.sweep(f, tmp_path / "api", workers=1)
    _same_rows(tmp_path / "cli" / "sweep.csv", tmp_path / "api" / "sweep.csv")
    # .table is sweep.csv with numbers as numbers, read back exactly
    api_rows = _csv_rows(tmp_path / "api" / "sweep.csv")
    assert [r["case"] for r in sw.table] == [0, 1] and sw.keys == ["operating.speed_rpm"]
    assert [r["operating.speed_rpm"] for r in sw.table] == [3000.0, 7000.0]
    assert all(r["status"] == "ok" and r["DE_max_contact_force_n"] > 0 for r in sw.table)
    assert repr(sw.table[1]["final_rotor_rpm"]) == api_rows[1]["final_rotor_rpm"]
    assert np.array_equal(sw.column("DE_max_contact_force_n"), [float(r["DE_max_contact_force_n"]) for r in api_rows])
    assert rl.Sweep.load(tmp_path / "api").table == sw.table
    # a case's landing is its results.h5: its summary is the row's source
    case = sw.case_landing(1)
    assert case.summary["bearings"]["DE"]["max_contact_force_n"] == sw.table[1]["DE_max_contact_force_n"]
    assert sw.whirl_map(tmp_path / "map.png").stat().st_size > 10000


def test_sweep_from_python_equals_the_sweep_file(tmp_path):
    """grid= / fixed= on a Scenario object write a sweep file that runs as the hand-written one."""
    f = _sweep_file(tmp_path)
    assert main(["sweep", str(f), "--out", str(tmp_path / "cli"), "--workers", "1"]) == 0
    sw = rl.sweep(rl.Scenario.load(LANDING), tmp_path / "py", grid=GRID, fixed=FIXED, workers=1)
    _same_rows(tmp_path / "cli" / "sweep.csv", tmp_path / "py" / "sweep.csv")
    # the written sweep file runs again from the command line (cases found finished: skipped)
    assert main(["sweep", str(tmp_path / "py" / "sweep_input.toml"), "--out", str(tmp_path / "py")]) == 0
    assert sw.keys == list(GRID)
    # the same sweep again: the finished cases are read back from their summaries, not run
    # (wall_s then comes from the summary's performance, not the worker's clock)
    again = rl.sweep(rl.Scenario.load(LANDING), tmp_path / "py", grid=GRID, fixed=FIXED, workers=1)
    assert [{k: v for k, v in r.items() if k != "wall_s"} for r in again.table] == \
        [{k: v for k, v in r.items() if k != "wall_s"} for r in sw.table]
    # another scenario into the same folder would read the old cases back as its own: refused
    with pytest.raises(rl.InputError) as exc:
        rl.sweep(rl.Scenario.load(LANDING, set={"contact.mu_rad": 0.2}), tmp_path / "py", grid=GRID, fixed=FIXED)
    assert exc.value.field == "out_dir" and "base_scenario.toml differs" in str(exc.value)
    with pytest.raises(rl.InputError) as exc:
        rl.sweep(LANDING, tmp_path / "py", grid=GRID, fixed=FIXED, seed=3)
    assert exc.value.field == "seed"


def test_sweep_refuses_bad_input(tmp_path):
    f = _sweep_file(tmp_path)
    for kw, field in ((dict(workers=0), "workers"), (dict(workers=True), "workers"),
                      (dict(fixed={"operating.t_end": 0.1}), "fixed"),
                      (dict(grid={}), "grid"), (dict(grid=GRID, ranges={"contact.mu_rad": {"min": 0.1, "max": 0.2}}),
                                                "ranges")):
        with pytest.raises(rl.InputError) as exc:
            rl.sweep(f if "grid" not in kw else LANDING, tmp_path / "o", **kw)
        assert exc.value.field == field, kw
    with pytest.raises(rl.InputError) as exc:  # an unknown key: the sweep file's own validation
        rl.sweep(LANDING, tmp_path / "k", grid={"contact.mu_radial": [0.1]})
    assert "contact.mu_radial" in str(exc.value)
    (tmp_path / "a_file").write_text("")
    with pytest.raises(rl.InputError) as exc:  # an output folder that is a file: named, nothing run
        rl.sweep(f, tmp_path / "a_file")
    assert exc.value.field == "out_dir"
    with pytest.raises(rl.InputError, match="not a sweep"):
        rl.Sweep.load(tmp_path)


# ---------------------------------------------------------------------------------------------
# diagnose: the paper's measured features at 7000 rpm against the model without axial rub, a
# few short runs (the method itself is tested in tests/test_diagnose.py)

DIAG_KW = dict(t_end=0.05, candidates=["axial_rub"], maxiter=1, workers=1)


@pytest.fixture(scope="module")
def one_point_table(tmp_path_factory):
    import tomllib

    data = tomllib.loads(PAPER_TABLE.read_text())
    data["points"] = {"rpm_7000": data["points"]["rpm_7000"]}
    f = tmp_path_factory.mktemp("table") / "paper_7000.json"
    f.write_text(json.dumps(data))
    return f


def test_diagnose_gives_the_cli_report(one_point_table, tmp_path):
    assert main(["diagnose", "--measured", str(one_point_table), "--scenario", str(PAPER_MODEL),
                 "--set", "effects.axial_rub=false", "--candidates", "axial_rub", "--t-end", "0.05",
                 "--maxiter", "1", "--workers", "1", "--out", str(tmp_path / "cli")]) == 0
    dg = rl.diagnose(one_point_table, str(PAPER_MODEL), tmp_path / "api", set={"effects.axial_rub": False}, **DIAG_KW)
    cli = json.loads((tmp_path / "cli" / "report.json").read_text())
    assert cli.pop("wall_s") >= 0 and dg.report.pop("wall_s") >= 0
    assert json.dumps(dg.report, sort_keys=True) == json.dumps(cli, sort_keys=True)
    assert (tmp_path / "api" / "report.md").read_text().split("\n")[2] == \
        (tmp_path / "cli" / "report.md").read_text().split("\n")[2]  # the model and gap line
    assert dg.figure.name == "features.png" and dg.figure.stat().st_size > 10000
    assert dg.gap_before == cli["gap_before"] and dg.named_effect == cli["named_effect"]
    assert [p["name"] for p in dg.points] == ["rpm_7000"]
    # calibrated: the report's KEY=VALUE items as values, the ones Scenario.with_overrides takes
    assert [f"{k}={v!r}".replace("=True", "=true") for k, v in dg.calibrated.items()] == cli["calibrated_overrides"]
    back = rl.Diagnosis.load(tmp_path / "api")
    assert back.gap_after == dg.gap_after and back.plot_features(tmp_path / "f.png").stat().st_size > 10000


def test_diagnose_of_a_scenario_object_is_the_diagnosis_of_its_file(one_point_table, tmp_path):
    a = rl.diagnose(one_point_table, PAPER_MODEL, tmp_path / "file", set={"effects.axial_rub": False}, **DIAG_KW)
    sc = rl.Scenario.load(PAPER_MODEL, set={"effects.axial_rub": False})
    b = rl.diagnose(one_point_table, sc, tmp_path / "object", **DIAG_KW)
    assert (tmp_path / "object" / "model.toml").is_file()
    for k in ("gap_before", "gap_after", "features_before", "features_after", "calibrated_overrides", "points"):
        assert a.report[k] == b.report[k], k


def test_diagnose_refuses_bad_input_before_simulating(one_point_table, tmp_path, monkeypatch):
    import rotorlanding.diagnose_run

    def refuse(*a, **k):
        raise AssertionError("a simulation was reached")

    monkeypatch.setattr(rotorlanding.diagnose_run, "diagnose", refuse)
    cases = [(dict(candidates=["no_such_effect"]), "candidates"), (dict(workers=0), "workers"),
             (dict(max_effects=0), "max_effects"), (dict(maxiter=1.5), "maxiter"), (dict(t_end=-1.0), "t_end"),
             (dict(set={"effects.no_such": True}), "set effects.no_such")]
    for kw, field in cases:
        with pytest.raises(rl.InputError) as exc:
            rl.diagnose(one_point_table, PAPER_MODEL, tmp_path / "o", **kw)
        assert exc.value.field == field, kw
    with pytest.raises(rl.InputError) as exc:
        rl.diagnose(tmp_path / "missing.csv", PAPER_MODEL, tmp_path / "o")
    assert exc.value.field == "measured" and "missing.csv" in str(exc.value)  # the keyword, not --measured
    with pytest.raises(rl.InputError, match="not a diagnosis"):
        rl.Diagnosis.load(tmp_path)


def test_calibrated_reads_the_report_items_as_values(tmp_path):
    """Diagnosis.calibrated parses the report's KEY=VALUE items as --set does (TOML values)."""
    rep = {"named_effect": "axial_rub", "named_effects": ["axial_rub"], "gap_before": 2.7, "gap_after": 1.8,
           "calibrated_overrides": ["effects.axial_rub=true", "contact.mu_ax=0.05000000000000001"],
           "points": [], "features_before": [], "features_after": []}
    (tmp_path / "report.json").write_text(json.dumps(rep))
    dg = rl.Diagnosis.load(tmp_path)
    assert dg.calibrated == {"effects.axial_rub": True, "contact.mu_ax": 0.05000000000000001}
    sc = rl.Scenario.load(PAPER_MODEL, set={"effects.axial_rub": False}).with_overrides(dg.calibrated)
    assert sc.model.effects["axial_rub"] is True and sc.table["contact"]["mu_ax"] == 0.05000000000000001
    assert dg.figure is None and "axial_rub" in repr(dg)


def test_readme_studies_snippet_runs(tmp_path, monkeypatch):
    """The README's second Python block (coastdown, sweep, diagnose) runs as written, shortened:
    folders and figures in tmp_path, 0.4 s of coast-down, 0.02 s sweep cases, a one-candidate
    diagnosis on 0.05 s runs (tests/test_api.py runs the first block the same way)."""
    readme = (ROOT / "README.md").read_text()
    blocks = readme.split("## Python", 1)[1].split("\n## ", 1)[0].split("```python")
    code = "import rotorlanding as rl\n" + blocks[2].split("```", 1)[0]
    monkeypatch.chdir(ROOT)
    for old, new in (('"cd_out", t_end=2.0', f'{str(tmp_path / "cd")!r}, t_end=0.4'),
                     ('"operating.t_end": 0.3', '"operating.t_end": 0.02'), ('workers=2', 'workers=1'),
                     ('"sweep_out"', repr(str(tmp_path / "sw"))),
                     ('"diag_out", set={"effects.axial_rub": False})',
                      f'{str(tmp_path / "dg")!r}, set={{"effects.axial_rub": False}}, t_end=0.05, '
                      'candidates=["axial_rub"], maxiter=1, workers=1)'),
                     ('"speeds.png"', repr(str(tmp_path / "s.png"))), ('"whirl_map.png"', repr(str(tmp_path / "w.png")))):
        assert old in code, old  # the snippet still reads as the test expects
        code = code.replace(old, new)
    scope = {}
    exec(compile(code, "README.md", "exec"), scope)
    assert scope["cd"].summary["performance"]["simulated_s"] == pytest.approx(0.4)
    assert len(scope["sw"].table) == 4 and (tmp_path / "w.png").is_file() and (tmp_path / "s.png").is_file()
    assert (tmp_path / "dg" / "report.json").is_file() and not (ROOT / "diag_out").exists()


def test_calibrate_from_python_returns_the_designs_with_their_noise(tmp_path):
    """rl.calibrate runs the command's calibration (tiny: 2 designs, 2 drops of 0.1 s at 7000 rpm)
    and returns a Calibration that reads calibration.json back: designs best first, the score's
    error on ensembles, the designs within the best's noise (the best among them) and their span,
    the best as overrides, a figure; bad input is an InputError before any landing."""
    import rotorlanding as rl

    space = tmp_path / "space.toml"
    space.write_text('samples = 2\nseed = 3\nt_end = 0.1\ncases = ["fw7000"]\nensemble = 2\n'
                     '[ranges]\n"bearings.DE.c_rib,bearings.NDE.c_rib" = {min = 1e3, max = 3e4, log = true}\n')
    cal = rl.calibrate(space, tmp_path / "c", workers=2)
    assert isinstance(cal, rl.Calibration) and len(cal.designs) == 2
    assert cal.designs[0]["score"] <= cal.designs[1]["score"] and cal.best is cal.designs[0]
    assert cal.best["score_se"] > 0 and cal.noise_z == 2.0 and cal.ensemble == 2 and cal.cases == ["fw7000"]
    assert cal.best in cal.within_noise
    lo, hi = cal.span["bearings.DE.c_rib,bearings.NDE.c_rib"]
    assert 1e3 <= lo <= cal.best["bearings.DE.c_rib,bearings.NDE.c_rib"] <= hi <= 3e4
    v = cal.best["bearings.DE.c_rib,bearings.NDE.c_rib"]
    assert cal.overrides == {"bearings.DE.c_rib": v, "bearings.NDE.c_rib": v}
    assert rl.Calibration.load(tmp_path / "c").designs == cal.designs
    assert cal.plot(tmp_path / "cal.png").stat().st_size > 5000
    assert "2 designs" in repr(cal)
    for kwargs in ({"workers": 0}, {"workers": 1.5}):
        with pytest.raises(rl.InputError):
            rl.calibrate(space, tmp_path / "d", **kwargs)
    with pytest.raises(rl.InputError):
        rl.calibrate({"ranges": {}}, tmp_path / "d")
    with pytest.raises(rl.InputError):
        rl.Calibration.load(tmp_path)
