"""Measured landing data in: CSV, HDF5 (our own results.h5 counts as data), MATLAB .mat, and a
feature-level table (TOML/JSON) as rig reports and papers give. First piece of the model-gap
workflow (issue 5).

Channel names carry their unit (SI unless named): ``time_s`` and any subset of::

    DE_y_m, DE_z_m, NDE_y_m, NDE_z_m               journal displacement (y horizontal, z up)
    rotor_speed_rpm, DE_inner_race_speed_rpm, NDE_inner_race_speed_rpm
    axial_m                                        rotor axial position
    DE_force_y_n, DE_force_z_n, NDE_force_y_n, NDE_force_z_n   contact force on the rotor
    DE_housing_force_y_n, DE_housing_force_z_n, NDE_housing_force_y_n, NDE_housing_force_z_n
                                                   force of the housing on the bearing (what a load
                                                   cell between them reads), positive up as the above

Channels may have different sampling (NaN where a channel has no sample), missing channels are
fine, and the drop instant is aligned by ``time_offset_s`` (the time of the drop in the file's
clock, subtracted) or detected from the vertical displacement (:func:`detect_drop`).

Feature tables (``.toml``/``.json``, format in ``docs/measured_data.md``): either one
``[features]`` table (one operating point: the scenario as it is), or one table per operating
point ``[points.NAME]`` with ``set`` (the scenario overrides that define the point, e.g.
``set.operating.speed_rpm = 3000.0``) and ``features`` (the measured features there). Example:
``scenarios/measured/paper_table2_fig39.toml``.
"""

from __future__ import annotations

import json
import tomllib
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from .errors import InputError
from .mechanisms import housing_force, rotor_force
from .readers import read_columns, read_results_guarded, read_text

CHANNELS = ("DE_y_m", "DE_z_m", "NDE_y_m", "NDE_z_m", "rotor_speed_rpm", "DE_inner_race_speed_rpm",
            "NDE_inner_race_speed_rpm", "axial_m", "DE_force_y_n", "DE_force_z_n", "NDE_force_y_n", "NDE_force_z_n",
            "DE_housing_force_y_n", "DE_housing_force_z_n", "NDE_housing_force_y_n", "NDE_housing_force_z_n")

#: results.h5 series -> measurement channel (forces: contact + axial-rub force on the rotor)
_FROM_RESULTS = {"DE_y_m": "DE_y_m", "DE_z_m": "DE_z_m", "NDE_y_m": "NDE_y_m", "NDE_z_m": "NDE_z_m",
                 "rotor_speed_rpm": "rotor_speed_rpm", "DE_race_speed_rpm": "DE_inner_race_speed_rpm",
                 "NDE_race_speed_rpm": "NDE_inner_race_speed_rpm", "axial_position_m": "axial_m"}


@dataclass
class OperatingPoint:
    """One operating point of a feature table: scenario overrides and the measured features there
    (raw table values; checked and scaled by :func:`rotorlanding.features.features_from_table`)."""

    name: str
    overrides: list[str]
    features: dict


@dataclass
class Measurement:
    """Time series per channel, each with its own valid samples: channel -> (t [s], values)."""

    channels: dict[str, tuple[np.ndarray, np.ndarray]] = field(default_factory=dict)
    features: dict = field(default_factory=dict)  # feature-level data (measured features)
    source: str = ""
    points: list[OperatingPoint] = field(default_factory=list)  # multi-point feature table

    def has(self, name: str) -> bool:
        return name in self.channels

    def series(self, name: str):
        return self.channels[name]

    def shifted(self, dt: float) -> "Measurement":
        return Measurement({k: (t - dt, v) for k, (t, v) in self.channels.items()}, dict(self.features), self.source,
                           list(self.points))


#: largest magnitude a measured channel can plausibly hold, by unit, and why (beyond it the data
#: are in another unit, corrupted, or a sensor's overflow code)
CHANNEL_LIMITS = {
    "_rpm": (1.0e6, "rpm: the fastest rotors built (micro gas turbines) stay below 1e6 rpm"),
    "_m": (0.1, "m: a journal or axial displacement of a landing is a fraction of a millimetre; 0.1 m is "
                "beyond any catcher bearing (data in mm or um?)"),
    "_n": (1.0e7, "N: 1e7 N (1000 t) is beyond the static load rating of any rolling bearing"),
}


def _check_clock(t: np.ndarray, source: str) -> None:
    """time_s: finite where given, strictly increasing. A clock that restarts or repeats (two
    records joined, a logger reset) would otherwise be sorted into one interleaved record."""
    ok = np.isfinite(t)
    if ok.sum() < 2:
        raise InputError("time_s", f"{int(ok.sum())} valid samples", "needs at least 2 finite times", file=source)
    tt = t[ok]
    back = np.nonzero(np.diff(tt) <= 0)[0]
    if back.size:
        k = int(back[0])
        raise InputError("time_s", f"{tt[k + 1]:.9g} after {tt[k]:.9g} (sample {int(np.nonzero(ok)[0][k + 1]) + 1})",
                         "must increase strictly: a clock that restarts or repeats means joined records; "
                         "give one record", file=source)


def _check_channel(name: str, v: np.ndarray, source: str) -> None:
    """A channel holds numbers (NaN only where it has no sample) within a physical range."""
    finite = np.isfinite(v)
    if np.any(np.isinf(v)):
        raise InputError(name, "inf", "must be finite numbers (NaN where the channel has no sample)", file=source)
    if finite.sum() < 2:
        raise InputError(name, f"{int(finite.sum())} numeric samples", "a channel needs at least 2 numbers "
                         "(a text or empty column?)", file=source)
    for suffix, (limit, why) in CHANNEL_LIMITS.items():
        if name.endswith(suffix) and not name.endswith("_m_s"):
            big = float(np.max(np.abs(v[finite])))
            if big > limit:
                raise InputError(name, f"{big:.6g}", f"|value| must be <= {limit:g} {why}", file=source)
            break


def _from_columns(cols: dict[str, np.ndarray], source: str) -> Measurement:
    if "time_s" not in cols:
        raise InputError("time_s", None, "missing time column (channel names carry units, e.g. time_s, DE_y_m)",
                         file=source)
    t = np.asarray(cols["time_s"], float).ravel()
    _check_clock(t, source)
    m = Measurement(source=source)
    for name, val in cols.items():
        if name == "time_s":
            continue
        if name not in CHANNELS:
            raise InputError(name, "column", f"unknown channel; allowed: time_s, {', '.join(CHANNELS)}", file=source)
        v = np.asarray(val, float).ravel()
        if v.shape != t.shape:
            raise InputError(name, f"{v.size} samples", f"must have as many samples as time_s ({t.size})", file=source)
        _check_channel(name, v, source)
        ok = np.isfinite(v) & np.isfinite(t)
        if ok.sum() >= 2:
            order = np.argsort(t[ok])
            m.channels[name] = (t[ok][order], v[ok][order])
    if not m.channels:
        raise InputError("channels", "none", "the file holds no channel with at least 2 valid samples", file=source)
    return m


def load_measurement(path, *, time_offset_s: float = 0.0) -> Measurement:
    """Read measured data; ``time_offset_s`` (the drop instant in the file's clock) is subtracted."""
    path = Path(path)
    if not path.is_file():
        raise InputError("--measured", str(path), "file not found")
    suffix = path.suffix.lower()
    if suffix in (".csv", ".mat"):
        m = _from_columns(read_columns(path), str(path))
    elif suffix in (".h5", ".hdf5"):
        res = read_results_guarded(path, ("time_s", "series"), field="--measured")
        cols = {"time_s": res["time_s"]}
        for src, dst in _FROM_RESULTS.items():
            if src in res["series"]:
                cols[dst] = res["series"][src]
        for b in ("DE", "NDE"):
            if f"{b}_contact_force_y_n" in res["series"]:
                cols[f"{b}_force_y_n"], cols[f"{b}_force_z_n"] = rotor_force(res["series"], b)
            if f"{b}_ribbon_force_y_n" in res["series"]:
                cols[f"{b}_housing_force_y_n"], cols[f"{b}_housing_force_z_n"] = housing_force(res["series"], b)
        m = _from_columns(cols, str(path))
    elif suffix in (".toml", ".json"):
        return _feature_table(path, suffix)
    else:
        raise InputError("--measured", str(path), "must be .csv, .mat, .h5 or a .toml/.json feature table")
    return m.shifted(time_offset_s) if time_offset_s else m


def _override_text(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, str):
        return json.dumps(v)
    return repr(v)


def _flatten(prefix: str, node, out: list[tuple[str, object]]):
    if isinstance(node, dict):
        for k, v in node.items():
            _flatten(f"{prefix}.{k}" if prefix else k, v, out)
    else:
        out.append((prefix, node))


def _feature_table(path: Path, suffix: str) -> Measurement:
    try:
        text = read_text(path, kind=suffix[1:].upper(), field="--measured")
        data = tomllib.loads(text) if suffix == ".toml" else json.loads(text)
    except (tomllib.TOMLDecodeError, json.JSONDecodeError) as exc:
        raise InputError("(file)", str(exc).splitlines()[0], f"valid {suffix[1:].upper()}", file=str(path)) from None
    if not isinstance(data, dict):
        raise InputError("(file)", type(data).__name__, "a feature table is a table/object at the top level",
                         file=str(path))
    allowed_top = {"title", "source", "notes", "features", "points"}
    for k in data:
        if k not in allowed_top:
            raise InputError(k, data[k] if not isinstance(data[k], dict) else "(table)",
                             "unknown key; a feature table has [features] (one point) or [points.NAME] tables "
                             "(and optional title, source, notes)", file=str(path))
    if ("features" in data) == ("points" in data):
        raise InputError("features/points", None, "a feature table needs either one [features] table or "
                         "[points.NAME] tables (one per operating point)", file=str(path))
    if "features" in data:
        if not isinstance(data["features"], dict) or not data["features"]:
            raise InputError("features", data["features"], "must be a non-empty table of measured features",
                             file=str(path))
        return Measurement(features=data["features"], source=str(path))
    pts = data["points"]
    if not isinstance(pts, dict) or not pts:
        raise InputError("points", pts, "must hold one table per operating point, e.g. [points.rpm_3000]",
                         file=str(path))
    points = []
    for name, p in pts.items():
        where = f"points.{name}"
        if not isinstance(p, dict):
            raise InputError(where, p, "must be a table with set and features", file=str(path))
        for k in p:
            if k not in ("set", "features", "notes"):
                raise InputError(f"{where}.{k}", p[k] if not isinstance(p[k], dict) else "(table)",
                                 "unknown key; allowed: set, features, notes", file=str(path))
        if not isinstance(p.get("set"), dict) or not p["set"]:
            raise InputError(f"{where}.set", p.get("set"), "missing operating-point overrides: give the scenario "
                             "values that define the point, e.g. set.operating.speed_rpm = 3000.0", file=str(path))
        if not isinstance(p.get("features"), dict) or not p["features"]:
            raise InputError(f"{where}.features", p.get("features"), "missing measured features at this point, e.g. "
                             "features.whirl_frequency_hz = 48.0", file=str(path))
        flat: list[tuple[str, object]] = []
        _flatten("", p["set"], flat)
        for key, v in flat:
            if isinstance(v, list):
                raise InputError(f"{where}.set.{key}", v, "a scenario value (number, true/false or string)",
                                 file=str(path))
        points.append(OperatingPoint(name, [f"{k}={_override_text(v)}" for k, v in flat], p["features"]))
    sets = [tuple(sorted(p.overrides)) for p in points]
    if len(set(sets)) < len(sets):
        raise InputError("points", [p.name for p in points], "two operating points have the same overrides",
                         file=str(path))
    return Measurement(source=str(path), points=points)


def detect_drop(m: Measurement, clearance: float, bearing: str = "DE") -> float | None:
    """Drop instant from the free fall of the journal: while it falls from 5 % to 50 % of the
    clearance below its levitated level, z = z0 - g (t - t_drop)^2 / 2, so each such sample gives
    t_drop = t - sqrt(2 (z0 - z) / g); the median is robust to sensor noise."""
    from .timoshenko import GRAVITY

    name = f"{bearing}_z_m"
    if not m.has(name):
        return None
    t, z = m.series(name)
    z0 = float(np.median(z[: max(3, len(z) // 50)]))
    below = np.nonzero(z < z0 - 0.5 * clearance)[0]
    if not below.size:
        return None
    k = below[0]
    fall = np.arange(k + 1)
    fall = fall[(z0 - z[fall] >= 0.05 * clearance)]
    # keep the contiguous fall just before the first crossing of 50 %
    if fall.size == 0:
        return float(t[k])
    brk = np.nonzero(np.diff(fall) > 1)[0]
    fall = fall[brk[-1] + 1:] if brk.size else fall
    est = t[fall] - np.sqrt(2.0 * (z0 - z[fall]) / GRAVITY)
    return float(np.median(est))
