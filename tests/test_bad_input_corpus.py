"""Bad-input corpus (issue 16, point 7): generated mutations of the real scenarios, rotor files,
measured data, space files and results files, for every command.

Each case must give exit code 2 and exactly one stderr line, ``rotorlanding: error: ...``, that
names the mutated field; no traceback, and never exit 0 for a physically impossible value. Every
case fails at validation: the solve entry points are replaced by a function that raises, so an
accepted bad input fails here at once instead of running a landing. The CLI runs in-process
(``cli.main``); only damaged HDF5 files are read in a subprocess, because a crash in the HDF5
library there would kill pytest. ``python tests/test_bad_input_corpus.py`` prints the count per
command.
"""

from __future__ import annotations

import collections
import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from rotorlanding.cli import main
from rotorlanding.config import load_toml

ROOT = Path(__file__).resolve().parents[1]
PAPER = ROOT / "scenarios" / "paper" / "forward_whirl_landing.toml"
COAST = ROOT / "scenarios" / "coastdown_7000rpm.toml"
ROTOR = ROOT / "scenarios" / "rig_rotor.toml"
SWEEP = ROOT / "scenarios" / "sweeps" / "forward_whirl_speed_mu.toml"
CAL_SPACE = ROOT / "scenarios" / "calibration" / "rig_space.toml"
FIT_SPACE = ROOT / "scenarios" / "calibration" / "rotor_modes.toml"
CLEARANCE = 2.0e-4  # m, the rig's (scenarios/rig/rig.toml)


# ---------------------------------------------------------------------------------------------
# Case generation (pure, at import: the lists are also what the per-command count reports)

def _numeric_keys(node, prefix=""):
    """Dotted keys of every number in the resolved scenario tables (arrays of tables by index;
    plain arrays such as drop_offset_m are not --set targets)."""
    if isinstance(node, dict):
        for k, v in node.items():
            yield from _numeric_keys(v, f"{prefix}.{k}" if prefix else k)
    elif isinstance(node, list) and node and all(isinstance(v, dict) for v in node):
        for i, v in enumerate(node):
            yield from _numeric_keys(v, f"{prefix}.{i}")
    elif isinstance(node, (int, float)) and not isinstance(node, bool):
        yield prefix


def _field_pattern(key: str) -> list[str]:
    """How an error may spell a --set key: as given, or with array indices in brackets
    (rotor.sections.3.outer_diameter -> rotor.sections[3].outer_diameter)."""
    parts = key.split(".")
    bracket = parts[0]
    for p in parts[1:]:
        bracket += f"[{p}]" if p.isdigit() else f".{p}"
    return [key, bracket]


SCENARIO_KEYS = [k for k in _numeric_keys(load_toml(PAPER)) if not k.startswith("bounds")]

#: --set mutations of the paper scenario: every number at +/-1e300 (impossible for any field),
#: then named impossible values from issue 16 and a few schema breakers
RUN_SET_CASES = [([f"{k}={v}"], _field_pattern(k)) for k in SCENARIO_KEYS for v in ("1e300", "-1e300")]
RUN_SET_CASES += [
    (["bearings.DE.thermal_ambient_k=0"], ["bearings.DE.thermal_ambient_k"]),   # 0 K: the DE summary vanished
    (["bearings.DE.clearance=abc"], ["bearings.DE.clearance = 'abc'"]),   # the value named, not its [bounds] entry
    (["bearings.DE.thermal_runaway_limit_k=100"], ["bearings.DE.thermal_runaway_limit_k"]),  # below the ambient
    (["bearings.DE.clearance=1e-2"], ["bearings.DE.clearance"]),          # 34 % of the sleeve radius
    (["amb.stiffness=1e300"], ["amb.stiffness"]),
    (["contact.mu_ax=50"], ["contact.mu_ax"]),
    (["contact.mu_rad=1e6"], ["contact.mu_rad"]),
    (["operating.speed_rpm=1e12"], ["operating.speed_rpm"]),
    (["operating.speed_rpm=70000"], ["operating.speed_rpm"]),            # above the rig rotor's burst speed (63 600 rpm)
    (["bearings.NDE.inner_race_mass=1e30"], ["bearings.NDE.inner_race_mass"]),
    (["bearings.DE.outer_race_mass=1e30"], ["bearings.DE.outer_race_mass"]),
    (["rotor.materials.steel.density=1e30"], ["rotor.materials.steel.density"]),
    (["rotor.disks.2.mass=1e30"], ["rotor.disks[2].mass"]),
    (["contact.k_hertz=1e300"], ["contact.k_hertz"]),
    (["operating.t_end=1e300"], ["operating.t_end"]),
    (["bearings.DE.eta=3"], ["bearings.DE.eta"]),
    (["bearings.DE.pitch_diameter=0.05"], ["bearings.DE.pitch_diameter"]),  # inside the bore
    (["solver.step_control='adaptive'"], ["solver.step_control"]),
    (["solver.step_control='auto'", "solver.max_step=1e-6"], ["solver.step"]),
    (["solver.step_control='auto'", "solver.max_step=1e300"], ["solver.max_step"]),
    (["solver.step_tolerance=1e300"], ["solver.step_tolerance"]),
    (["contact.mu_rad=nan"], ["contact.mu_rad"]),
    (["contact.mu_rad=inf"], ["contact.mu_rad"]),
    (["contact.mu_rad=\"high\""], ["contact.mu_rad"]),
    (["contact.mu_rad=true"], ["contact.mu_rad"]),
    (["contact.mu_rad=[0.1, 0.2]"], ["contact.mu_rad"]),
    (["contact.exponent=0.5"], ["contact.exponent"]),
    (["=5"], ["--set"]),
    ([".mu=5"], ["--set"]),
    (["contact..mu_rad=5"], ["--set"]),
    (["contact.mu_rad"], ["--set"]),
    (["contact.no_such=1"], ["contact.no_such"]),
    (["nosuch.table=1"], ["nosuch.table"]),
    (["effects.no_effect=true"], ["effects.no_effect"]),
    (["effects.windage=3"], ["effects.windage"]),
    # issue 18: the verdict's whirl-severity limits and a thermal capacity that cannot be zero
    (["limits.whirl_time_s=-1"], ["limits.whirl_time_s"]),
    (["limits.whirl_orbit_over_clearance=nan"], ["limits.whirl_orbit_over_clearance"]),
    (["bearings.NDE.thermal_housing_capacity_j_k=0"], ["bearings.NDE.thermal_housing_capacity_j_k"]),
    (["bearings.DE.thermal_width_m=0"], ["bearings.DE.thermal_width_m"]),
]

#: whole-file mutations of a scenario: (name, bytes or a function of the original text, field)
_TEXT = PAPER.read_text()


def _file_cases():
    inc_target = "include_target.toml"
    return [
        ("empty", b"", "(file)"),
        ("blank", b"\n  \n", "(file)"),
        ("binary", bytes(range(256)) * 4, "(file)"),
        ("utf16", _TEXT.encode("utf-16"), "(file)"),
        ("utf16be_no_bom", _TEXT.encode("utf-16-be"), "(file)"),
        ("latin1", ("# Überdrehzahl\n" + _TEXT).encode("latin-1"), "(file)"),
        ("syntax", b"[contact\nmu_rad = 0.3\n", "(syntax)"),
        ("array_top", b"x = [1, 2\n", "(syntax)"),
        ("include_number", b"include = 5\n", "include"),
        ("include_missing", b'include = ["does_not_exist.toml"]\n', "include"),
        ("include_binary", f'include = ["{inc_target}"]\n'.encode(), "(file)"),
        ("include_self", b'include = ["include_self.toml"]\n', "include"),
        ("no_rotor", b'name = "x"\n', "rotor"),
        ("rotor_text", b'rotor = "../rig_rotor.toml"\n', "rotor"),
    ]


FILE_CASES = _file_cases()

#: rotor-file mutations for `modes` and `reduce`: (old text, new text, field in the message)
ROTOR_TEXT = ROTOR.read_text()
ROTOR_CASES = [
    ("density = 7850.0", "density = 1e30", "density"),
    ("density = 7850.0", "density = -1.0", "density"),
    ("youngs_modulus = 2.1e11", "youngs_modulus = 1e300", "youngs_modulus"),
    ("poisson_ratio = 0.3", "poisson_ratio = 0.7", "poisson_ratio"),
    ("max_speed_rpm = 10000.0", "max_speed_rpm = 1e12", "max_speed_rpm"),
]
ROTOR_CMDS = [("modes", []), ("reduce", [])]
ROTOR_ARG_CASES = [
    (["modes", "--speeds-rpm", "abc"], "--speeds-rpm"),
    (["modes", "--speeds-rpm", "-5"], "--speeds-rpm"),
    (["modes", "--speeds-rpm", "nan"], "--speeds-rpm"),
    (["modes", "--n-modes", "0"], "--n-modes"),
    (["modes", "--speeds-rpm", "0,1e12"], "--speeds-rpm"),        # beyond the rotor's burst speed
    (["reduce", "--speeds-rpm", "1e300"], "--speeds-rpm"),
    (["reduce", "--speeds-rpm", "1,x"], "--speeds-rpm"),
    (["modes", "--plot", "no_such_folder/c.png"], "--plot"),          # checked before the modes are computed
    (["modes", "--plot", "campbell.txt"], "--plot"),                  # a type matplotlib cannot write
    (["modes", "--plot", ""], "--plot"),
]

COAST_CASES = [
    (["coastdown.stop_speed_rpm=-1"], "coastdown.stop_speed_rpm"),
    (["coastdown.chunk_s=0"], "coastdown.chunk_s"),
    (["coastdown.decimate_every=0"], "coastdown.decimate_every"),
    (["solver.step_control='auto'"], "solver.step_control"),   # verified for landings only
    (["coastdown.nosuch=1"], "coastdown.nosuch"),
    (["contact.mu_ax=50"], "contact.mu_ax"),
    (["operating.speed_rpm=1e12"], "operating.speed_rpm"),
    (["bearings.DE.clearance=1e300"], "bearings.DE.clearance"),
    (["=5"], "--set"),
]

# measured data for `diagnose`: a synthetic landing record, valid, then broken one way per case
_N = 3000
_T = np.arange(_N) * 2e-4                      # 0.6 s at 5 kHz
_Z = np.where(_T < 0.1, 0.0, -np.minimum(0.5 * 9.81 * (_T - 0.1) ** 2, CLEARANCE))
_COLS = {"time_s": _T, "DE_y_m": 1e-6 * np.sin(300 * _T), "DE_z_m": _Z, "rotor_speed_rpm": 7000.0 - 100.0 * _T}


def _csv(cols: dict) -> str:
    names = list(cols)
    rows = [",".join(names)] + [",".join(repr(float(cols[n][i])) if not isinstance(cols[n][i], str) else cols[n][i]
                                         for n in names) for i in range(len(cols[names[0]]))]
    return "\n".join(rows) + "\n"


def _mutated(**changes) -> dict:
    cols = {k: np.array(v, dtype=object) for k, v in _COLS.items()}
    for k, v in changes.items():
        if v is None:
            cols.pop(k)
        else:
            cols[k] = v
    return cols


def _restart():
    t = _T.copy()
    t[_N // 2:] -= 0.3   # the logger's clock restarts part-way
    return t


def _text_cells():
    v = np.array(_COLS["DE_y_m"], dtype=object)
    v[100:110] = "n/a"
    return v


CSV_CASES = [
    ("clock_restarts", _csv(_mutated(time_s=_restart())), "time_s"),
    ("clock_repeats", _csv(_mutated(time_s=np.where(np.arange(_N) == 50, _T[49], _T))), "time_s"),
    ("text_cells", _csv(_mutated(DE_y_m=_text_cells())), "DE_y_m"),
    ("text_column", _csv(_mutated(DE_y_m=np.array(["up"] * _N, dtype=object))), "DE_y_m"),
    ("speed_1e300", _csv(_mutated(rotor_speed_rpm=np.full(_N, 1e300))), "rotor_speed_rpm"),
    ("speed_inf", _csv(_mutated(rotor_speed_rpm=np.full(_N, np.inf))), "rotor_speed_rpm"),
    ("displacement_mm", _csv(_mutated(DE_z_m=_Z * 1000.0)), "DE_z_m"),
    ("displacement_1e300", _csv(_mutated(DE_y_m=np.full(_N, 1e300))), "DE_y_m"),
    ("force_1e300", _csv(_mutated(DE_force_z_n=np.full(_N, 1e300))), "DE_force_z_n"),
    ("unknown_channel", _csv(_mutated(DE_q_m=np.zeros(_N))), "DE_q_m"),
    ("no_time", _csv(_mutated(time_s=None)), "time_s"),
    ("time_text", _csv(_mutated(time_s=np.array(["t"] * _N, dtype=object))), "time_s"),
    ("time_nan", _csv(_mutated(time_s=np.full(_N, np.nan))), "time_s"),
    ("duplicate_header", "time_s,DE_y_m,DE_y_m\n0,0,0\n1,0,0\n", "(csv header)"),
    ("ragged_row", "time_s,DE_y_m\n0,0\n1,0,5\n", "(csv)"),
    ("header_only", "time_s,DE_y_m,DE_z_m\n", "(csv)"),
    ("one_row", "time_s,DE_z_m\n0,0\n", "time_s"),
    ("empty", "", "(file)"),
    ("binary", bytes(range(256)) * 8, "(file)"),
    ("utf16", _csv(_COLS).encode("utf-16")[: 20000], "(file)"),
    ("latin1", ("time_s,DE_y_m\n0,0\n# \xb5m\n").encode("latin-1"), "(file)"),
    ("far_beyond_clearance", _csv(_mutated(DE_z_m=_Z * 20.0)), "DE_z_m"),  # 4 mm: not this rotor
    ("too_short", _csv({k: v[:200] for k, v in _COLS.items()}), "time_s"),  # 0.04 s record
]

MAT_CASES = [
    ("clock_restarts", {**_COLS, "time_s": _restart()}, "time_s"),
    ("string_variable", {**_COLS, "DE_y_m": "abc"}, "DE_y_m"),
    ("matrix", {**_COLS, "DE_y_m": np.ones((_N, 3))}, "DE_y_m"),
    ("speed_1e300", {**_COLS, "rotor_speed_rpm": np.full(_N, 1e300)}, "rotor_speed_rpm"),
    ("truncated", None, "(file)"),
    ("text", b"time_s,DE_z_m\n0,0\n", "(file)"),
    ("empty", b"", "(file)"),
]

FEATURE_CASES = [
    ("negative_whirl", "[features]\nwhirl_direction = 'forward'\nwhirl_frequency_hz = -48.0\n", "whirl_frequency_hz"),
    ("zero_whirl", "[features]\nwhirl_direction = 'forward'\nwhirl_frequency_hz = 0.0\n", "whirl_frequency_hz"),
    ("nan_whirl", "[features]\nwhirl_direction = 'forward'\nwhirl_frequency_hz = nan\n", "whirl_frequency_hz"),
    ("negative_onset", "[features]\nwhirl_direction = 'forward'\nwhirl_onset_s = -0.2\n", "whirl_onset_s"),
    ("negative_force", "[features]\nDE_force_peak_n = -4500.0\n", "DE_force_peak_n"),
    ("negative_radius", "[features]\nDE_orbit_radius_mean_m = -1e-4\n", "DE_orbit_radius_mean_m"),
    ("mm_displacement", "[features]\nDE_vertical_min_m = -0.2\n", "DE_vertical_min_m"),
    ("unknown_feature", "[features]\nwhirl_speed = 3.0\n", "whirl_speed"),
    ("bad_direction", "[features]\nwhirl_direction = 'sideways'\n", "whirl_direction"),
    ("text_value", "[features]\nwhirl_frequency_hz = 'fast'\n", "whirl_frequency_hz"),
    ("features_not_table", "features = 5\n", "features"),
    ("no_set", "[points.a.features]\nwhirl_frequency_hz = 48.0\n", "points.a.set"),
    ("point_bad_key", "[points.a.set]\ncontact.mu_rad = 0.3\n[points.a.features]\nwhirl_frequency_hz = -1.0\n",
     "points.a.features.whirl_frequency_hz"),
    ("point_impossible_set", "[points.a.set]\ncontact.mu_ax = 50.0\n[points.a.features]\nwhirl_frequency_hz = 48.0\n",
     "points.a.set"),
    ("frequency_without_direction", "[features]\nwhirl_frequency_hz = 48.0\n", "whirl_frequency_hz"),
    ("axial_mean_metres", "[features]\naxial_mean_m = 5.0\n", "axial_mean_m"),
    ("force_1e12", "[features]\nDE_force_peak_n = 1e12\n", "DE_force_peak_n"),
    ("deceleration_1e9", "[features]\nrotor_deceleration_rpm_s = -1e9\n", "rotor_deceleration_rpm_s"),
    ("min_above_max", "[features]\nDE_vertical_min_m = 2e-4\nDE_vertical_max_m = -2e-4\n", "DE_vertical_min_m"),
    ("empty_toml", "", "(file)"),
    ("utf16_toml", "[features]\nwhirl_frequency_hz = 48.0\n".encode("utf-16"), "(file)"),
]
JSON_CASES = [
    ("list_top", "[1, 2]", "(file)"),
    ("negative_whirl", '{"features": {"whirl_direction": "forward", "whirl_frequency_hz": -48}}', "whirl_frequency_hz"),
    ("broken", '{"features": {', "(file)"),
    ("binary", bytes(range(256)), "(file)"),
]

DIAGNOSE_ARG_CASES = [
    (["--time-offset-s", "nan"], "--time-offset-s"),
    (["--time-offset-s", "inf"], "--time-offset-s"),
    (["--workers", "0"], "--workers"),
    (["--maxiter", "0"], "--maxiter"),
    (["--candidates", "no_such_effect"], "--candidates"),
    (["--journals", "NDE"], "--journals"),
    (["--journals", "DE,XDE"], "--journals"),
    (["--set", "effects.nothing=true"], "effects.nothing"),
    (["--set", "contact.mu_ax=50"], "contact.mu_ax"),
]

SWEEP_CASES = [
    ("fixed_number", 'fixed = 5\n', "fixed"),
    ("fixed_array", '[fixed]\n"operating.t_end" = [0.1, 0.2]\n', "fixed.operating.t_end"),
    ("fixed_nan", '[fixed]\n"operating.t_end" = nan\n', "fixed.operating.t_end"),
    ("grid_number", 'grid = 5\n', "grid"),
    ("grid_empty_list", '[grid]\n"contact.mu_ax" = []\n', "grid.contact.mu_ax"),
    ("grid_tables", '[grid]\n"contact.mu_ax" = [{a = 1}]\n', "grid.contact.mu_ax"),
    ("grid_all_impossible", '[grid]\n"contact.mu_ax" = [50.0, 60.0]\n', "contact.mu_ax"),
    ("grid_unknown_key", '[grid]\n"contact.nosuch" = [1.0]\n', "contact.nosuch"),
    ("grid_key_with_space", '[grid]\n"contact.mu_ax " = [0.1]\n', "grid.contact.mu_ax"),
    ("mode_bad", 'mode = "random"\n[grid]\n"contact.mu_ax" = [0.1]\n', "mode"),
    ("ranges_text", 'mode = "monte_carlo"\n[ranges]\n"contact.mu_ax" = {min = "a", max = 0.3}\n', "ranges.contact.mu_ax.min"),
    ("ranges_inverted", 'mode = "monte_carlo"\n[ranges]\n"contact.mu_ax" = {min = 0.3, max = 0.1}\n', "ranges.contact.mu_ax"),
    ("ranges_number", 'mode = "monte_carlo"\nranges = 3\n', "ranges"),
    ("ranges_impossible", 'mode = "monte_carlo"\n[ranges]\n"contact.mu_ax" = {min = 40.0, max = 50.0}\n', "contact.mu_ax"),
    ("samples_zero", 'mode = "monte_carlo"\nsamples = 0\n[ranges]\n"contact.mu_ax" = {min = 0.1, max = 0.3}\n', "samples"),
    ("unknown_top", 'colour = "red"\n[grid]\n"contact.mu_ax" = [0.1]\n', "colour"),
    ("scenario_missing", None, "scenario"),
]

CAL_CASES = [
    ("choices_number", 'choices = 5\n[ranges]\n"contact.mu_rad" = {min = 0.1, max = 0.3}\n', "choices"),
    ("t_end_beyond_a_day", 't_end = 1e9\n[ranges]\n"contact.mu_rad" = {min = 0.1, max = 0.3}\n', "t_end"),
    ("fixed_number", "fixed = 5\n", "fixed"),
    ("ranges_text", '[ranges]\n"contact.mu_rad" = {min = "a", max = 0.3}\n', "ranges.contact.mu_rad.min"),
    ("ranges_log_negative", '[ranges]\n"contact.mu_rad" = {min = -0.1, max = 0.3, log = true}\n', "ranges.contact.mu_rad.min"),
    ("ranges_impossible", '[ranges]\n"contact.mu_rad" = {min = 0.1, max = 50.0}\n', "contact.mu_rad"),
    ("ranges_unknown_key", '[ranges]\n"contact.nosuch" = {min = 0.1, max = 0.3}\n', "contact.nosuch"),
    ("ranges_missing", 'samples = 3\n', "ranges"),
    ("cases_unknown", 'cases = ["fw1"]\n[ranges]\n"contact.mu_rad" = {min = 0.1, max = 0.3}\n', "cases"),
    ("t_end_negative", 't_end = -1.0\n[ranges]\n"contact.mu_rad" = {min = 0.1, max = 0.3}\n', "t_end"),
    ("samples_zero", 'samples = 0\n[ranges]\n"contact.mu_rad" = {min = 0.1, max = 0.3}\n', "samples"),
    ("binary", bytes(range(256)), "(file)"),
]

_FIT_HEAD = 'rotor = "{rotor}"\nsupport_stiffness = 3.6e7\n'
_FIT_TARGETS = '[targets]\nspeeds_rpm = [3000.0, 7000.0]\nfrequencies_hz = [48.0, 65.0]\n'
_FIT_RANGES = '[ranges]\n"rotor.sections.3.outer_diameter" = {min = 0.035, max = 0.07}\n'
FIT_CASES = [
    ("rotor_without_rotor_table", _FIT_HEAD.replace("{rotor}", str(ROOT / "scenarios" / "paper" / "reference.toml"))
     + _FIT_TARGETS + '[ranges]\n"table1.simulated.onset_s" = {min = 0.035, max = 0.07}\n', "rotor"),
    ("ranges_text", _FIT_HEAD + _FIT_TARGETS + '[ranges]\n"rotor.sections.3.outer_diameter" = {min = "x", max = 0.07}\n',
     "ranges.rotor.sections.3.outer_diameter.min"),
    ("ranges_unknown_key", _FIT_HEAD + _FIT_TARGETS + '[ranges]\n"rotor.nosuch" = {min = 0.1, max = 0.2}\n', "ranges.rotor.nosuch"),
    ("speed_negative", _FIT_HEAD + '[targets]\nspeeds_rpm = [-3000.0]\nfrequencies_hz = [48.0]\n' + _FIT_RANGES,
     "targets.speeds_rpm"),
    ("speed_inf", _FIT_HEAD + '[targets]\nspeeds_rpm = [inf]\nfrequencies_hz = [48.0]\n' + _FIT_RANGES, "targets.speeds_rpm"),
    ("frequency_negative", _FIT_HEAD + '[targets]\nspeeds_rpm = [3000.0]\nfrequencies_hz = [-48.0]\n' + _FIT_RANGES,
     "targets.frequencies_hz"),
    ("direction_bad", _FIT_HEAD + _FIT_TARGETS + 'direction = "up"\n' + _FIT_RANGES, "targets.direction"),
    ("stiffness_text", 'rotor = "{rotor}"\nsupport_stiffness = "stiff"\n' + _FIT_TARGETS + _FIT_RANGES, "support_stiffness"),
    ("rotor_missing", 'rotor = "nowhere.toml"\nsupport_stiffness = 3.6e7\n' + _FIT_TARGETS + _FIT_RANGES, "rotor"),
    ("empty", "", "(file)"),
    ("utf16", (_FIT_HEAD + _FIT_TARGETS + _FIT_RANGES).encode("utf-16"), "(file)"),
]

VALIDATE_CASES = [(["--workers", "0"], "--workers"), (["--rig", "no_such_rig.toml"], "--rig"),
                  (["--set", "contact.mu_rad=-1"], "contact.mu_rad"), (["--set", "foo.bar=1"], "foo"),
                  (["--quick", "--set", "operating.t_end=-1"], "operating.t_end")]
ANIMATE_ARG_CASES = [(["--view", "top"], "--view"), (["--fps", "0"], "--fps"), (["--max-frames", "1"], "--max-frames")]

#: damaged results.h5 for run / animate / diagnose: name -> {command: field in the message}. A
#: command is left out where the damage is in a part it does not read (run re-runs the stored
#: scenario only; diagnose reads the time series only)
_ALL = ("run", "animate", "diagnose")
H5_CASES = {
    "empty": dict.fromkeys(_ALL, "(file)"), "text": dict.fromkeys(_ALL, "(file)"),
    "truncated_head": dict.fromkeys(_ALL, "(file)"), "zeroed_head": dict.fromkeys(_ALL, "(file)"),
    "truncated_half": dict.fromkeys(_ALL, "(file)"), "overwritten_metadata": dict.fromkeys(_ALL, "(file)"),
    "foreign_hdf5": dict.fromkeys(_ALL, "package"),
    "no_scenario": {"run": "scenario_json", "animate": "scenario_json"},
    "scenario_not_json": {"run": "scenario_json", "animate": "scenario_json"},
    "impossible_scenario": {"run": "contact.mu_ax", "animate": "contact.mu_ax"},
    "no_time": {"animate": "time_s", "diagnose": "time_s", "verdict": "time_s"},
    "no_states": {"animate": "states/q"},
    "q_wrong_rows": {"animate": "states/q"},
    "no_series": {"diagnose": "series", "verdict": "series"},
    "clock_restarts": {"diagnose": "time_s"},
    "speed_1e300": {"diagnose": "rotor_speed_rpm"},
}
H5_JOBS = [(cmd, name, field) for name, per in H5_CASES.items() for cmd, field in per.items()]
H5_COMMANDS = _ALL


def case_counts() -> dict[str, int]:
    c = collections.Counter()
    c["run"] += len(RUN_SET_CASES) + len(FILE_CASES)
    c["coastdown"] += len(COAST_CASES) + len(FILE_CASES)
    c["modes"] += len(ROTOR_CASES) + sum(1 for a, _ in ROTOR_ARG_CASES if a[0] == "modes")
    c["reduce"] += len(ROTOR_CASES) + sum(1 for a, _ in ROTOR_ARG_CASES if a[0] == "reduce")
    c["diagnose"] += len(CSV_CASES) + len(MAT_CASES) + len(FEATURE_CASES) + len(JSON_CASES) + len(DIAGNOSE_ARG_CASES)
    c["sweep"] += len(SWEEP_CASES)
    c["calibrate"] += len(CAL_CASES)
    c["fit-modes"] += len(FIT_CASES)
    c["validate"] += len(VALIDATE_CASES)
    c["animate"] += len(ANIMATE_ARG_CASES)
    for cmd, _, _ in H5_JOBS:
        c[cmd] += 1
    return dict(c)


# ---------------------------------------------------------------------------------------------
# Harness

def _refuse(*args, **kwargs):
    raise AssertionError("a solve was reached: the bad input passed validation")


@pytest.fixture(autouse=True)
def _no_solves(monkeypatch):
    """Replace every solve entry point: the corpus must fail before any of them."""
    import scipy.optimize

    import rotorlanding.calibrate_run
    import rotorlanding.coastdown_run
    import rotorlanding.diagnose_run
    import rotorlanding.run
    import rotorlanding.sweep_run
    import rotorlanding.validate

    monkeypatch.setattr(rotorlanding.run, "run_scenario", _refuse)
    monkeypatch.setattr(rotorlanding.coastdown_run, "run_coastdown", _refuse)
    monkeypatch.setattr(rotorlanding.diagnose_run, "diagnose", _refuse)
    monkeypatch.setattr(rotorlanding.sweep_run, "warm_up", _refuse)
    monkeypatch.setattr(rotorlanding.sweep_run, "_run_local", _refuse)
    monkeypatch.setattr(rotorlanding.calibrate_run, "_run_all", _refuse)
    monkeypatch.setattr(rotorlanding.validate, "validate", _refuse)
    monkeypatch.setattr(scipy.optimize, "differential_evolution", _refuse)


def _expect_one_line_error(rc: int, err: str, fields) -> None:
    fields = [fields] if isinstance(fields, str) else list(fields)
    assert "Traceback" not in err, err
    assert rc == 2, f"exit {rc}, stderr: {err!r}"
    lines = [ln for ln in err.splitlines() if ln.strip()]
    assert len(lines) == 1 and lines[0].startswith("rotorlanding: error: "), err
    assert any(f in lines[0] for f in fields), f"none of {fields} named in: {lines[0]}"


def _cli(argv, capsys, fields) -> None:
    rc = main([str(a) for a in argv])
    _expect_one_line_error(rc, capsys.readouterr().err, fields)


def _write(path: Path, content) -> Path:
    path.write_bytes(content if isinstance(content, bytes) else content.encode())
    return path


# ---------------------------------------------------------------------------------------------
# run / coastdown: scenario values and scenario files

@pytest.mark.parametrize("sets,fields", RUN_SET_CASES, ids=[" ".join(s) for s, _ in RUN_SET_CASES])
def test_run_set(sets, fields, tmp_path, capsys):
    argv = ["run", PAPER, "--out", tmp_path / "o"]
    for s in sets:
        argv += ["--set", s]
    _cli(argv, capsys, fields)


def _scenario_file(tmp_path: Path, name: str, content) -> Path:
    # beside the paper scenarios' includes: a copy in tmp_path with the rig include made absolute
    _write(tmp_path / "include_target.toml", bytes(range(256)))
    _write(tmp_path / "include_self.toml", b'include = ["include_self.toml"]\n')
    return _write(tmp_path / f"{name}.toml", content)


@pytest.mark.parametrize("name,content,field", FILE_CASES, ids=[c[0] for c in FILE_CASES])
@pytest.mark.parametrize("cmd", ["run", "coastdown"])
def test_scenario_file(cmd, name, content, field, tmp_path, capsys):
    f = _scenario_file(tmp_path, name, content)
    _cli([cmd, f, "--out", tmp_path / "o"], capsys, field)


@pytest.mark.parametrize("sets,field", COAST_CASES, ids=[c[1] for c in COAST_CASES])
def test_coastdown_set(sets, field, tmp_path, capsys):
    _cli(["coastdown", COAST, "--out", tmp_path / "o", "--set", *sets], capsys, field)


# ---------------------------------------------------------------------------------------------
# modes / reduce: rotor files and options

@pytest.mark.parametrize("old,new,field", ROTOR_CASES, ids=[c[1] for c in ROTOR_CASES])
@pytest.mark.parametrize("cmd", ["modes", "reduce"])
def test_rotor_file(cmd, old, new, field, tmp_path, capsys):
    assert old in ROTOR_TEXT  # the mutation must hit the real file
    f = _write(tmp_path / "rotor.toml", ROTOR_TEXT.replace(old, new, 1))
    _cli([cmd, f], capsys, field)


@pytest.mark.parametrize("args,field", ROTOR_ARG_CASES, ids=[" ".join(a) for a, _ in ROTOR_ARG_CASES])
def test_rotor_options(args, field, capsys):
    _cli([args[0], ROTOR, *args[1:]], capsys, field)


# ---------------------------------------------------------------------------------------------
# diagnose: measured CSV, .mat, feature tables, options

def _diagnose(measured: Path, tmp_path: Path, capsys, field, extra=()):
    _cli(["diagnose", "--measured", measured, "--scenario", PAPER, "--out", tmp_path / "d", *extra], capsys, field)


def test_valid_csv_reaches_the_search(tmp_path):
    # the unmutated record passes every check (the corpus's failures are the mutations')
    f = _write(tmp_path / "ok.csv", _csv(_COLS))
    with pytest.raises(AssertionError, match="a solve was reached"):
        main(["diagnose", "--measured", str(f), "--scenario", str(PAPER), "--out", str(tmp_path / "d")])


@pytest.mark.parametrize("name,content,field", CSV_CASES, ids=[c[0] for c in CSV_CASES])
def test_diagnose_csv(name, content, field, tmp_path, capsys):
    _diagnose(_write(tmp_path / f"{name}.csv", content), tmp_path, capsys, field)


@pytest.mark.parametrize("name,cols,field", MAT_CASES, ids=[c[0] for c in MAT_CASES])
def test_diagnose_mat(name, cols, field, tmp_path, capsys):
    from scipy.io import savemat

    f = tmp_path / f"{name}.mat"
    if isinstance(cols, dict):
        savemat(f, cols)
    elif cols is None:  # truncated: a valid file cut to a third
        savemat(f, _COLS)
        f.write_bytes(f.read_bytes()[: f.stat().st_size // 3])
    else:
        f.write_bytes(cols)
    _diagnose(f, tmp_path, capsys, field)


@pytest.mark.parametrize("name,content,field", FEATURE_CASES, ids=[c[0] for c in FEATURE_CASES])
def test_diagnose_feature_table(name, content, field, tmp_path, capsys):
    _diagnose(_write(tmp_path / f"{name}.toml", content), tmp_path, capsys, field)


@pytest.mark.parametrize("name,content,field", JSON_CASES, ids=[c[0] for c in JSON_CASES])
def test_diagnose_json(name, content, field, tmp_path, capsys):
    _diagnose(_write(tmp_path / f"{name}.json", content), tmp_path, capsys, field)


@pytest.mark.parametrize("args,field", DIAGNOSE_ARG_CASES, ids=[" ".join(a) for a, _ in DIAGNOSE_ARG_CASES])
def test_diagnose_options(args, field, tmp_path, capsys):
    _diagnose(_write(tmp_path / "ok.csv", _csv(_COLS)), tmp_path, capsys, field, args)


# ---------------------------------------------------------------------------------------------
# sweep / calibrate / fit-modes space files, validate and animate options

@pytest.mark.parametrize("name,body,field", SWEEP_CASES, ids=[c[0] for c in SWEEP_CASES])
def test_sweep_file(name, body, field, tmp_path, capsys):
    if body is None:
        text = 'scenario = "no_such_scenario.toml"\n[grid]\n"contact.mu_ax" = [0.1]\n'
    else:
        text = f'scenario = "{PAPER}"\n' + body
    _cli(["sweep", _write(tmp_path / "s.toml", text), "--out", tmp_path / "o"], capsys, field)


@pytest.mark.parametrize("name,body,field", CAL_CASES, ids=[c[0] for c in CAL_CASES])
def test_calibrate_space(name, body, field, tmp_path, capsys):
    _cli(["calibrate", _write(tmp_path / "space.toml", body), "--out", tmp_path / "o"], capsys, field)


@pytest.mark.parametrize("name,body,field", FIT_CASES, ids=[c[0] for c in FIT_CASES])
def test_fit_modes_space(name, body, field, tmp_path, capsys):
    content = body.replace("{rotor}", str(ROTOR)) if isinstance(body, str) else body
    _cli(["fit-modes", _write(tmp_path / "space.toml", content), "--out", tmp_path / "o"], capsys, field)


@pytest.mark.parametrize("args,field", VALIDATE_CASES, ids=[a[0] for a, _ in VALIDATE_CASES])
def test_validate_options(args, field, tmp_path, capsys):
    _cli(["validate", "--out", tmp_path / "v", *args], capsys, field)


# ---------------------------------------------------------------------------------------------
# results.h5 given to run / animate / diagnose: read in one subprocess (an HDF5 crash must not
# take pytest down), every case through cli.main there

def _write_results(path: Path, scenario_raw, n: int = 11, ncoord: int = 3, **drop) -> None:
    """A results.h5 in the layout of rotorlanding.results (written here with h5py, so the test
    does not depend on the write side)."""
    import h5py

    t = np.linspace(0.0, 0.01, n)
    with h5py.File(path, "w") as h5:
        h5.attrs["package"] = "rotorlanding"
        h5.attrs["complete"] = True
        if "scenario" not in drop:
            h5["scenario_json"] = scenario_raw if isinstance(scenario_raw, str) else json.dumps(scenario_raw)
        if "time" not in drop:
            h5["time_s"] = t
        if "states" not in drop:
            q = np.zeros((n + (1 if "q_rows" in drop else 0), ncoord))
            h5["states/q"] = q
            h5["states/v"] = q
            h5["states/q"].attrs["names"] = json.dumps([f"c{i}" for i in range(ncoord)])
        if "time" not in drop and "restart" in drop:
            del h5["time_s"]
            h5["time_s"] = np.where(np.arange(n) < n // 2, t, t - 0.005)
        if "series" not in drop:
            for name in ("DE_y_m", "DE_z_m", "rotor_speed_rpm"):
                h5[f"series/{name}"] = np.full(n, 1e300) if (name == "rotor_speed_rpm" and "speed" in drop) \
                    else np.zeros(n)
        h5["summary_json"] = json.dumps({"complete": True})


def _h5_corpus(folder: Path) -> dict[str, Path]:
    from rotorlanding.scenario import load_scenario

    raw = load_scenario(PAPER).raw
    good = folder / "good.h5"
    _write_results(good, raw, n=400)
    data = good.read_bytes()
    files = {}

    def put(name, content):
        files[name] = _write(folder / f"{name}.h5", content)

    put("empty", b"")
    put("text", b"time_s,DE_z_m\n0,0\n")
    put("truncated_head", data[:6])
    put("zeroed_head", b"\0" * 512 + data[512:])
    put("truncated_half", data[: len(data) // 2])
    # the object headers and B-tree nodes that follow the superblock, overwritten with noise
    head = bytearray(data)
    head[96:2048] = np.random.default_rng(16).integers(0, 256, 2048 - 96, dtype=np.uint8).tobytes()
    put("overwritten_metadata", bytes(head))
    import h5py

    with h5py.File(folder / "foreign_hdf5.h5", "w") as h5:
        h5["temperature"] = np.arange(10.0)
    files["foreign_hdf5"] = folder / "foreign_hdf5.h5"
    for name, kw in (("no_scenario", {"scenario": 1}), ("no_time", {"time": 1}), ("no_states", {"states": 1}),
                     ("q_wrong_rows", {"q_rows": 1}), ("no_series", {"series": 1}),
                     ("clock_restarts", {"restart": 1}), ("speed_1e300", {"speed": 1})):
        files[name] = folder / f"{name}.h5"
        _write_results(files[name], raw, **kw)
    files["scenario_not_json"] = folder / "scenario_not_json.h5"
    _write_results(files["scenario_not_json"], "{not json")
    bad = json.loads(json.dumps(raw))
    bad["contact"]["mu_ax"] = 50.0
    files["impossible_scenario"] = folder / "impossible_scenario.h5"
    _write_results(files["impossible_scenario"], bad)
    return files


_H5_RUNNER = r"""
import contextlib, io, json, sys, traceback
import rotorlanding.run, rotorlanding.diagnose_run
from rotorlanding.cli import main

def refuse(*a, **k):
    raise AssertionError("a solve was reached: the bad input passed validation")

rotorlanding.run.run_scenario = refuse
rotorlanding.diagnose_run.diagnose = refuse
out = []
for argv in json.loads(sys.stdin.read()):
    err = io.StringIO()
    with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
        try:
            rc = main(argv)
        except BaseException:
            traceback.print_exc()
            rc = "exception"
    out.append({"rc": rc, "err": err.getvalue()})
print(json.dumps(out))
"""


def _h5_argv(cmd: str, f: Path, out: Path) -> list[str]:
    if cmd == "run":
        return ["run", str(f), "--out", str(out / "r"), "--no-plots", "--quiet"]
    if cmd == "animate":
        return ["animate", str(f), "--out", str(out / "a.gif")]
    if cmd == "verdict":
        return ["verdict", str(f), "--out", str(out / "v"), "--no-plots"]
    return ["diagnose", "--measured", str(f), "--scenario", str(PAPER), "--out", str(out / "d")]


@pytest.fixture(scope="module")
def h5_results(tmp_path_factory):
    folder = tmp_path_factory.mktemp("h5corpus")
    files = _h5_corpus(folder)
    jobs = [(cmd, name) for cmd, name, _ in H5_JOBS]
    argv = [_h5_argv(cmd, files[name], folder) for cmd, name in jobs]
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")])}
    proc = subprocess.run([sys.executable, "-c", _H5_RUNNER], input=json.dumps(argv), capture_output=True,
                          text=True, timeout=300, env=env)
    assert proc.returncode == 0, f"the HDF5 corpus process died (exit {proc.returncode}): {proc.stderr[-2000:]}"
    return dict(zip(jobs, json.loads(proc.stdout.strip().splitlines()[-1])))


@pytest.mark.parametrize("cmd,name,field", H5_JOBS, ids=[f"{c}-{n}" for c, n, _ in H5_JOBS])
def test_damaged_results_file(cmd, name, field, h5_results):
    r = h5_results[(cmd, name)]
    _expect_one_line_error(r["rc"] if isinstance(r["rc"], int) else -1, r["err"], field)


@pytest.mark.parametrize("args,field", ANIMATE_ARG_CASES, ids=[a[0] for a, _ in ANIMATE_ARG_CASES])
def test_animate_options(args, field, tmp_path, capsys):
    f = tmp_path / "r.h5"
    from rotorlanding.scenario import load_scenario

    _write_results(f, load_scenario(PAPER).raw)
    _cli(["animate", f, "--out", tmp_path / "a.gif", *args], capsys, field)


# ---------------------------------------------------------------------------------------------
# issue 16 point 6: a sweep or calibration whose every case fails exits non-zero; a partial
# failure says how many failed

def test_sweep_all_failed_exits_1_and_partial_counts(monkeypatch, tmp_path, capsys):
    import rotorlanding.sweep_run

    rows = [{"case": 0, "status": "failed", "error": "x"}, {"case": 1, "status": "failed", "error": "y"}]
    monkeypatch.setattr(rotorlanding.sweep_run, "run_sweep", lambda *a, **k: rows)
    assert main(["sweep", str(SWEEP), "--out", str(tmp_path)]) == 1
    assert "every one of the 2 cases failed" in capsys.readouterr().err
    rows[1] = {"case": 1, "status": "ok", "error": ""}
    assert main(["sweep", str(SWEEP), "--out", str(tmp_path)]) == 0
    assert "1 of 2 cases failed" in capsys.readouterr().err


def test_calibrate_all_failed_exits_1_and_partial_counts(monkeypatch, tmp_path, capsys):
    import rotorlanding.calibrate_run

    rows = [{"design": 0, "score": 9.0, "converged": None, "failed_landings": 4},
            {"design": 1, "score": 9.0, "converged": None, "failed_landings": 1}]
    monkeypatch.setattr(rotorlanding.calibrate_run, "calibrate", lambda *a, **k: rows)
    assert main(["calibrate", str(CAL_SPACE), "--out", str(tmp_path)]) == 1
    assert "every one of the 2 designs had a landing that failed" in capsys.readouterr().err
    rows[1]["failed_landings"] = 0
    assert main(["calibrate", str(CAL_SPACE), "--out", str(tmp_path)]) == 0
    assert "1 of 2 designs had a landing that failed" in capsys.readouterr().err


def test_every_shipped_input_still_loads():
    """The plausibility limits sit where physics ends: every scenario, rotor, sweep case,
    calibration space (load_space checks both ends of its ranges) and fit-mode range end shipped
    in scenarios/, and both ends of every parameter range diagnose searches, must load."""
    from rotorlanding import calibrate_run, modefit, sweep_run, whirlmap
    from rotorlanding.coastdown_run import load_coastdown
    from rotorlanding.effects import CATALOGUE
    from rotorlanding.rotor import load_rotor, rotor_from_dict
    from rotorlanding.scenario import load_scenario

    kinds = collections.Counter()
    for f in sorted((ROOT / "scenarios").rglob("*.toml")):
        data = load_toml(f)
        if "coastdown" in data:
            load_coastdown(f)
            kinds["coastdown"] += 1
        elif "bearings" in data and "station" not in data["bearings"].get("DE", {}):
            # a rig overlay (rotor + bearing values, `validate --rig`): loads merged over a paper scenario
            load_scenario(ROOT / "scenarios" / "paper" / "forward_whirl_landing.toml", overlays=[f])
            kinds["rig overlay"] += 1
        elif "bearings" in data:
            load_scenario(f)
            kinds["scenario"] += 1
        elif isinstance(data.get("rotor"), dict):
            load_rotor(f)
            kinds["rotor"] += 1
        elif isinstance(data.get("rotor"), str):
            sp = modefit.load_space(f)
            for end in (0, 1):
                rotor_from_dict(modefit.rotor_with(sp["rotor_data"], {k: v[end] for k, v in sp["ranges"].items()}))
            kinds["fit-modes space"] += 1
        elif "grid" in data or "mode" in data:
            sw = sweep_run.load_sweep(f)
            for case in sw["cases"]:
                load_scenario(sw["base"], sweep_run._overrides(sw["fixed"], case))
            kinds["sweep"] += 1
        elif "script" in data and "geometry" in data:  # a screen's record, judged by validate as a fit
            from rotorlanding.validate import SCREENS, load_screen

            assert f.name in SCREENS and load_screen(f)["ranges"]
            kinds["screen record"] += 1
        elif "ranges" in data:
            calibrate_run.load_space(f)
            kinds["calibration space"] += 1
        elif "axes" in data:  # a whirl-risk map: every cell loads
            wm = whirlmap.load_map(f)
            (kx, ky), (vx, vy) = wm["keys"], wm["values"]
            for x in vx:
                for y in vy:
                    load_scenario(wm["base"], whirlmap._sets(wm["fixed"], {kx: x, ky: y}, []))
            kinds["whirl map"] += 1
        elif f.name == "reference.toml":  # the paper's numbers (validate.paper reads them)
            assert set(data) == {"table1", "table2", "fig39"}
            kinds["paper numbers"] += 1
        elif f.parent.name == "measured":  # a measured feature table (diagnose --measured): it reads
            from rotorlanding.measured import load_measurement

            m = load_measurement(f)
            assert m.points or m.features
            kinds["measured feature table"] += 1
        else:
            kinds["other"] += 1
    assert kinds == {"scenario": 7, "coastdown": 2, "rotor": 4, "fit-modes space": 4, "sweep": 1,
                     "calibration space": 10, "paper numbers": 1, "measured feature table": 2, "rig overlay": 1,
                     "whirl map": 1, "screen record": 1}
    for f in ("forward_whirl_landing.toml", "backward_whirl_landing.toml", "forward_whirl_3000rpm.toml"):
        for effect in CATALOGUE.values():
            for p in effect.parameters:
                if p.keys[0].startswith("unbalance."):
                    continue  # the paper scenarios have no [unbalance] table
                for v in (p.lower, p.upper):
                    load_scenario(ROOT / "scenarios" / "paper" / f, [f"{k}={v!r}" for k in p.keys])


@pytest.mark.parametrize("argv,field", [
    (["calibrate", "scenarios/calibration/worn_bearing.toml", "--out", "{file}"], "--out"),
    (["calibrate", "scenarios/calibration/worn_bearing.toml", "--workers", "0", "--out", "{tmp}/c"], "--workers"),
    (["fit-modes", "scenarios/calibration/rotor_modes.toml", "--out", "{file}"], "--out"),
    (["run", "scenarios/landing_7000rpm.toml", "--out", ""], "--out"),
    (["sweep", "scenarios/sweeps/forward_whirl_speed_mu.toml", "--out", ""], "--out"),
], ids=["calibrate-out-file", "calibrate-workers-0", "fit-modes-out-file", "run-out-empty", "sweep-out-empty"])
def test_output_checked_before_the_work(argv, field, tmp_path, capsys, monkeypatch):
    """An --out that is a file or an empty string (the current folder to Path: a run wrote there,
    clearing a results.h5 first) is refused before any design is landed or any mode fitted."""
    monkeypatch.chdir(ROOT)
    f = tmp_path / "a_file"
    f.write_text("x")
    _cli([a.replace("{file}", str(f)).replace("{tmp}", str(tmp_path)) for a in argv], capsys, field)


def test_whirl_map_drop_circle_beyond_the_clearance(tmp_path, capsys):
    """A drop circle wider than the clearance failed every drop (exit 1, no reason); now one line."""
    body = (f'scenario = "{PAPER}"\ndrops = 2\ndrop_radius_m = 1.0\n[fixed]\n"operating.t_end" = 0.01\n[axes]\n'
            '"operating.speed_rpm" = [3000.0]\n"contact.mu_rad" = [0.1]\n')
    _cli(["whirl-map", _write(tmp_path / "m.toml", body), "--out", tmp_path / "o"], capsys, "drop_radius_m")


def test_corpus_size():
    counts = case_counts()
    assert sum(counts.values()) >= 150
    assert set(counts) >= {"run", "coastdown", "modes", "reduce", "diagnose", "sweep", "calibrate", "fit-modes",
                           "validate", "animate"}


if __name__ == "__main__":  # pragma: no cover
    c = case_counts()
    for k, v in sorted(c.items()):
        print(f"{k:10s} {v}")
    print(f"{'total':10s} {sum(c.values())}")
