"""The Python API of the studies: coast-down, sweep, model-gap diagnosis and calibration.

``rotorlanding.coastdown(...)``, ``rotorlanding.sweep(...)`` and ``rotorlanding.diagnose(...)``
run the code of the commands ``rotorlanding coastdown|sweep|diagnose`` (the machinery lives in
:mod:`rotorlanding.coastdown_run`, :mod:`rotorlanding.sweep_run`, :mod:`rotorlanding.diagnose_run`),
write the same files into an output folder and return a results object (:class:`Coastdown`,
:class:`Sweep`, :class:`Diagnosis`) that reads itself back from that folder (``load``) and draws
its figures. Kept out of :mod:`rotorlanding.api` (the rotor, scenario and landing) because
these three are folder-based studies that wrap a command; they share its :class:`Series`,
:class:`Scenario` and the one ``--set`` parser.

Units are SI (m, s, N, J, W); names say the unit where not (``speed_rpm``, ``frequency_hz``).
Bad input raises the one-line :class:`~rotorlanding.errors.InputError` before anything runs.
Reference: ``docs/python_api.md``.
"""

from __future__ import annotations

import copy
import csv
import json
import tempfile
from collections.abc import Mapping
from pathlib import Path

import numpy as np

from .api import Scenario, _override_items, _SeriesResults, _toml_dump
from .errors import InputError
from .safeio import atomic_write_text, save_figure

__all__ = ["Coastdown", "coastdown", "Sweep", "sweep", "Diagnosis", "diagnose", "Calibration", "calibrate"]


def _png(path, default: str) -> Path:
    return Path(path) if path is not None else Path(default)


def _seconds(name: str, value) -> float | None:
    """A time [s] given by the caller (None stays None): a finite number > 0, else InputError."""
    if value is None:
        return None
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)) \
            or not np.isfinite(value) or value <= 0:
        raise InputError(name, value, "must be a number of seconds > 0")
    return float(value)


# ---------------------------------------------------------------------------------------------
# Coast-down (rotorlanding.coastdown_run.run_coastdown, the code path of `rotorlanding coastdown`)

def _coastdown_file(path: Path) -> dict:
    """time, series with units, stored summary, chunk table and the stored scenario tables of a
    coast-down results.h5 (opened read-only; a landing's file or a damaged one: InputError)."""
    import h5py

    if not path.is_file():
        raise InputError("results file", str(path), "no such file")
    try:
        with h5py.File(path, "r") as h5:
            if h5.attrs.get("kind") != "coastdown":
                raise InputError("results file", str(path), f"is not a coastdown result (kind "
                                 f"{h5.attrs.get('kind', 'landing')!r}); a landing is read by Landing.load")
            return {"t": h5["time_s"][()],
                    "units": {k: str(h5["series"][k].attrs["unit"]) for k in h5["series"]},
                    "summary": json.loads(h5["summary_json"][()]) if "summary_json" in h5 else {},
                    "chunks": {k: h5["coastdown/chunks"][k][()] for k in h5["coastdown/chunks"]}
                    if "coastdown/chunks" in h5 else {},
                    "scenario": json.loads(h5["scenario_json"][()]) if "scenario_json" in h5 else None,
                    "scenario_name": str(h5.attrs.get("scenario_name", ""))}
    except (OSError, KeyError, ValueError) as exc:
        raise InputError("results file", str(path), f"not a rotorlanding results.h5 ({exc})") from None


class _FileSeries(Mapping):
    """The series of a coast-down results.h5, each read from the file when asked for: a run to
    rest stores millions of samples of ~70 series (about 1 GB for the rig's hour), which a
    results object must not hold at once (the coast-down itself keeps memory bounded)."""

    def __init__(self, path: Path, names):
        self.path, self.names = path, list(names)

    def __getitem__(self, name: str) -> np.ndarray:
        import h5py

        if name not in self.names:
            raise KeyError(name)
        with h5py.File(self.path, "r") as h5:
            return h5["series"][name][()]

    def __iter__(self):
        return iter(self.names)

    def __len__(self) -> int:
        return len(self.names)


def _folder_summary(path: Path, stored: dict) -> dict:
    """summary.json beside results.h5 when it belongs to the stored run (it adds the file size and
    figures), else the summary stored in the file."""
    f = path.parent / "summary.json"
    if f.is_file():
        try:
            s = json.loads(f.read_text())
        except ValueError:
            s = {}
        if s.get("kind") == "coastdown" and s.get("t_reached_s") == stored.get("t_reached_s") and "performance" in s:
            return s
    return stored


class Coastdown(_SeriesResults):
    """Results of a coast-down (:func:`coastdown` or :meth:`load`): the ``results.h5`` and
    ``summary.json`` that ``rotorlanding coastdown`` writes into its folder.

    Attributes:
        summary: the summary.json content (dict): ``stop_reason``, ``time_to_stop_s`` [s],
            ``speeds`` [rpm], ``energy`` [J], per bearing ``max_contact_force_n`` [N],
            ``whirl_phases``, ``performance``
        t: stored sample times [s] (decimated where the motion is smooth, so irregular)
        series_names, units: the stored series and their units ({name: unit})
        chunks: the per-chunk table (dict of arrays): ``t_start_s``, ``t_end_s`` [s],
            ``rotor_speed_rpm``, ``whirl_direction`` (-1, 0, +1), ``whirl_frequency_hz``,
            ``whirl_bearing`` (index into the bearing names, -1 none; absent in files begun before
            it was stored), ``<bearing>_max_contact_force_n`` [N], solver counts
        scenario: the :class:`~rotorlanding.api.Scenario` that was run (from the file)
        clearances: {bearing: radial clearance [m]}
        path: the results.h5; complete: False when interrupted (``resume=True`` continues) or
            the solver failed
    Series by name: ``cd["rotor_speed_rpm"]`` or ``cd.series(name)`` (a :class:`Series`), read
    from results.h5 when asked for (a run to rest holds too many samples to load them all).
    """

    def __init__(self, path, summary: dict | None = None):
        from .scenario import scenario_from_dict

        self.path = Path(path)
        data = _coastdown_file(self.path)
        self.t = data["t"]
        self.units = data["units"]
        self._series = _FileSeries(self.path, self.units)
        self.chunks = data["chunks"]
        self.summary = summary if summary is not None else _folder_summary(self.path, data["summary"])
        raw = data["scenario"]
        self.scenario = Scenario(scenario_from_dict(raw, name=data["scenario_name"] or None)) if raw else None
        self.clearances = ({b: bb.clearance for b, bb in self.scenario.model.bearings.items()}
                           if self.scenario else {})

    @classmethod
    def load(cls, dir_or_file) -> "Coastdown":
        """Read a coast-down: its output folder (``results.h5`` inside) or the results.h5 itself."""
        p = Path(dir_or_file)
        return cls(p / "results.h5" if p.is_dir() else p)

    def plot_speeds(self, path=None) -> Path:
        """Rotor and inner-race speeds [rpm] against time [s], the chunks that whirl forward /
        backward shaded, the stop speed dashed (PNG at ``path``, default ``speeds.png``)."""
        from .plots import _plt

        plt = _plt()
        path = _png(path, "speeds.png")
        fig, ax = plt.subplots(figsize=(9, 4.5))
        ax.plot(self.t, self._series["rotor_speed_rpm"], "k", lw=1.5, label="rotor")
        for k in self._series:
            if k.endswith("_race_speed_rpm"):
                ax.plot(self.t, self._series[k], lw=1.0, alpha=0.85, label=f"{k[:-len('_race_speed_rpm')]} inner race")
        t0, t1 = self.chunks.get("t_start_s", np.array([])), self.chunks.get("t_end_s", np.array([]))
        wd = self.chunks.get("whirl_direction", np.array([]))
        for d, col, name in ((1, "tab:red", "forward whirl"), (-1, "tab:blue", "backward whirl")):
            first = True
            for a, b in zip(t0[wd == d], t1[wd == d]):
                ax.axvspan(a, b, color=col, alpha=0.15, lw=0, label=name if first else None)
                first = False
        stop = self.summary.get("coastdown", {}).get("stop_speed_rpm")
        if stop:
            ax.axhline(stop, color="0.4", ls="--", lw=0.8, label=f"stop speed {stop:g} rpm")
        ax.set_xlabel("time after the start [s]")
        ax.set_ylabel("speed [rpm]")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8, loc="upper right")
        ax.set_title(f"{self.summary.get('scenario', '')}: coast-down speeds "
                     f"({self.summary.get('stop_reason', '')})", fontsize=10)
        fig.tight_layout()
        save_figure(fig, path, dpi=120)
        plt.close(fig)
        return path

    def _plot(self, which: str, path) -> Path:
        from .plots import plot_all

        t_drop = self.scenario.model.amb.t_drop if self.scenario else 0.0
        with tempfile.TemporaryDirectory() as tmp:
            files = plot_all(tmp, self.t, self._series, self.summary, self.clearances, t_drop, which={which})
            path = _png(path, f"{which}.png")
            path.write_bytes(files[0].read_bytes())
        return path

    def plot_displacements(self, path=None) -> Path:
        """Journal displacements y, z [mm] against time [s] at each catcher bearing, the +/- radial
        clearance dotted (the landing's figure on the stored samples; PNG)."""
        return self._plot("displacements", path)

    def plot_forces(self, path=None) -> Path:
        """Force of each catcher bearing on the rotor [kN] against time [s] (PNG)."""
        return self._plot("forces", path)

    def __repr__(self) -> str:
        return (f"Coastdown({self.summary.get('scenario', '')!r}: {self.t[-1] if len(self.t) else 0.0:.4g} s, "
                f"{self.summary.get('stop_reason', '')})")


def coastdown(scenario, out_dir, *, resume: bool = False, overwrite: bool = False, t_end: float | None = None,
              progress: bool = False, set: dict | None = None) -> Coastdown:
    """Run (or resume) a coast-down to rest: the crash-safe chunked run of ``rotorlanding
    coastdown`` (same code, same files: ``out_dir``/results.h5, summary.json, coastdown.png).

    Parameters:
        scenario: a coast-down scenario file (TOML with an optional ``[coastdown]`` table, or a
            coast-down results.h5) or a :class:`Scenario` (its ``[coastdown]`` table takes the
            defaults, or values through ``set``).
        out_dir: output folder (created).
        resume: continue the unfinished run in ``out_dir`` (``--resume``).
        overwrite: start over even if ``out_dir`` holds an unfinished run (``--overwrite``).
        t_end: cap on the simulated time [s] (``--t-end``); the run normally ends when the rotor
            speed falls to ``coastdown.stop_speed_rpm`` [rpm].
        progress: progress lines on stderr.
        set: {dotted key: value} overrides, ``coastdown.*`` included (``--set``), e.g.
            ``{"coastdown.stop_speed_rpm": 500.0}``.

    Returns a :class:`Coastdown`: ``.summary`` (the summary.json, equal to the command's except
    the wall-clock and memory figures: ``time_to_stop_s`` [s], final speeds [rpm], energy per
    mechanism [J], peak contact force per bearing [N]), ``.t`` [s], series by name with units
    (displacements [m], forces [N], speeds [rpm], energies [J]), ``.plot_speeds()`` and the other
    figures.
    Bad input raises :class:`InputError` before anything is written.
    """
    from .coastdown_run import FIELDS, coastdown_from_dict, load_coastdown, run_coastdown
    from .scenario import apply_overrides, scenario_from_dict

    items = _override_items(set or {})
    if _seconds("t_end", t_end) is not None:
        items.append(f"operating.t_end={float(t_end)!r}")  # the command's --t-end item
    if resume and overwrite:
        raise InputError("resume", True, "cannot be combined with overwrite=True")
    if isinstance(scenario, Scenario):
        data = copy.deepcopy(scenario.model.raw)
        apply_overrides(data, items, tables={"coastdown": FIELDS})
        cd_raw = data.pop("coastdown", None)
        model = scenario_from_dict(data, source=scenario.model.source, name=scenario.model.name)
        cd = coastdown_from_dict(cd_raw, model)
    elif isinstance(scenario, (str, Path)):
        model, cd = load_coastdown(str(scenario), items)
    else:
        raise InputError("scenario", type(scenario).__name__,
                         "must be a coast-down scenario file (path) or a rotorlanding.Scenario")
    summary = run_coastdown(model, cd, out_dir, resume=bool(resume), overwrite=bool(overwrite),
                            progress=bool(progress))
    return Coastdown(Path(out_dir) / "results.h5", summary)


# ---------------------------------------------------------------------------------------------
# Sweep (rotorlanding.sweep_run.run_sweep, the code path of `rotorlanding sweep`)

def _csv_value(text: str):
    """A cell of sweep.csv back as the number it was written from (repr round-trips floats)."""
    if text == "":
        return None
    for conv in (int, float):
        try:
            return conv(text)
        except ValueError:
            pass
    return text


class Sweep:
    """Results of a parameter sweep (:func:`sweep` or :meth:`load`): the output folder of
    ``rotorlanding sweep``.

    Attributes:
        table: the rows of ``sweep.csv`` as a list of dicts, one per case: ``case``, the swept
            keys, ``status`` ("ok" / "failed"), ``error``, ``whirl_direction``,
            ``whirl_frequency_hz`` [Hz], ``whirl_onset_s``, ``whirl_end_s`` [s],
            ``whirl_persistence`` [-], ``whirl_bearing``, ``whirl_shape`` (cylindrical / conical /
            mixed, empty when calm), per bearing
            ``<b>_max_contact_force_n`` [N], ``<b>_vertical_min_m``, ``<b>_vertical_max_m`` [m],
            ``final_rotor_rpm`` [rpm], ``energy_dissipated_j`` [J], ``wall_s`` [s]; numbers as
            int / float (the CSV's text read back exactly), empty cells None
        keys: the swept keys (dotted), in the sweep file's order
        out_dir: the output folder (``cases/case_NNNN/`` holds each case's results.h5)
    """

    def __init__(self, out_dir):
        self.out_dir = Path(out_dir)
        csv_path, meta = self.out_dir / "sweep.csv", self.out_dir / "sweep.json"
        if not csv_path.is_file() or not meta.is_file():
            raise InputError("sweep folder", str(self.out_dir), "holds no sweep.csv and sweep.json (not a sweep's output)")
        with open(csv_path, newline="") as fh:
            self.table = [{k: _csv_value(v) for k, v in row.items()} for row in csv.DictReader(fh)]
        self.keys = list(json.loads(meta.read_text())["keys"])

    @classmethod
    def load(cls, out_dir) -> "Sweep":
        """Read the output folder of a sweep (``sweep.csv``, ``sweep.json``)."""
        return cls(out_dir)

    def column(self, name: str) -> np.ndarray:
        """One column of the table as an array (None -> NaN for numbers); unknown: InputError."""
        if not self.table or name not in self.table[0]:
            raise InputError("column", name, f"unknown; available: {', '.join(self.table[0]) if self.table else '-'}")
        vals = [r[name] for r in self.table]
        if all(v is None or isinstance(v, (int, float)) for v in vals):
            return np.array([np.nan if v is None else v for v in vals], dtype=float)
        return np.array(vals, dtype=object)

    def case_landing(self, case: int):
        """The :class:`~rotorlanding.api.Landing` of one case (its ``cases/case_NNNN/results.h5``)."""
        from .api import Landing

        return Landing.load(self.out_dir / "cases" / f"case_{int(case):04d}" / "results.h5")

    def whirl_map(self, path=None) -> Path:
        """The whirl map (the command's ``whirl_map.png``): on a grid of two swept keys one cell
        per case coloured by whirl class (forward / backward / none / failed) with its whirl
        frequency [Hz] and its ratio to the spin frequency where the speed is swept, beside the
        whirl frequency [Hz] against the first key; other sweeps as a scatter. PNG at ``path``
        (default ``whirl_map.png``); returns the path."""
        from .sweep_run import plot_whirl_map

        path = _png(path, "whirl_map.png")
        plot_whirl_map(self.table, self.keys, path)
        return path

    def __repr__(self) -> str:
        ok = sum(1 for r in self.table if r.get("status") == "ok")
        return f"Sweep({len(self.table)} cases, {ok} ok, keys {self.keys})"


def _sweep_file_from_python(base, out: Path, grid, ranges, fixed, samples, seed) -> Path:
    """Write the sweep file (and, for a :class:`Scenario`, its base scenario) that ``grid`` /
    ``ranges`` describe into ``out``, so the run is the command's and can be repeated from the
    command line (``rotorlanding sweep OUT/sweep_input.toml``)."""
    if grid is not None and ranges is not None:
        raise InputError("ranges", ranges, "give grid (all combinations) or ranges (Monte Carlo), not both")
    table = grid if grid is not None else ranges
    if not isinstance(table, dict) or not table:
        raise InputError("grid" if grid is not None else "ranges", table,
                         "must be a non-empty dict of dotted keys, e.g. {'contact.mu_rad': [0.1, 0.3]}")
    if grid is not None and (samples is not None or seed is not None):
        raise InputError("samples" if samples is not None else "seed", samples if samples is not None else seed,
                         "goes with ranges= (Monte Carlo); a grid runs every combination")
    texts = {}  # file name -> text, written only after the check below
    if isinstance(base, Scenario):
        base_path = out / "base_scenario.toml"
        with tempfile.TemporaryDirectory() as tmp:
            texts[base_path.name] = base.to_toml(Path(tmp) / base_path.name).read_text()
    elif isinstance(base, (str, Path)):
        base_path = Path(base).resolve()
        if not base_path.is_file():
            raise InputError("scenario", str(base), "file not found")
    else:
        raise InputError("scenario", type(base).__name__, "must be a scenario file (path) or a rotorlanding.Scenario")
    doc = {"scenario": str(base_path.resolve()), "mode": "grid" if grid is not None else "monte_carlo"}
    if ranges is not None:
        if samples is not None:
            doc["samples"] = samples
        if seed is not None:
            doc["seed"] = seed
    if fixed:
        doc["fixed"] = dict(fixed)
    if grid is not None:
        doc["grid"] = {k: list(v) if isinstance(v, (list, tuple, np.ndarray)) else v for k, v in grid.items()}
    else:
        doc["ranges"] = dict(ranges)
    f = out / "sweep_input.toml"
    texts[f.name] = "# sweep written by rotorlanding.sweep (run again: rotorlanding sweep THIS_FILE)\n" + _toml_dump(doc)
    # finished cases in out_dir are not run again (the command's resume): they must be cases of
    # this sweep, or a notebook that changed its scenario would read the old results back
    for name, text in texts.items():
        old = out / name
        if old.is_file() and old.read_text() != text:
            raise InputError("out_dir", str(out), f"holds a sweep of another scenario or grid ({name} differs); "
                             "use a new folder, or delete this one to run again")
    for name, text in texts.items():
        atomic_write_text(out / name, text)
    return f


def sweep(sweep_or_scenario, out_dir, *, grid: dict | None = None, ranges: dict | None = None,
          fixed: dict | None = None, samples: int | None = None, seed: int | None = None, workers: int = 1,
          scheduler: str | None = None) -> Sweep:
    """Run a grid or Monte Carlo sweep of scenario values: ``rotorlanding sweep`` (the same
    runner and files: ``out_dir``/sweep.csv, sweep.json, whirl_map.png, cases/case_NNNN/).

    Two forms:
        ``sweep("scenarios/sweeps/forward_whirl_speed_mu.toml", "out")``: a sweep file (base
        scenario, ``[fixed]``, ``[grid]`` or ``mode = "monte_carlo"`` with ``[ranges]``);
        ``sweep(scenario, "out", grid={"operating.speed_rpm": [3000.0, 7000.0],
        "contact.mu_rad": [0.1, 0.3]}, fixed={"operating.t_end": 0.3})``: a :class:`Scenario`
        or scenario file and the keys in Python; ``ranges={"contact.mu_rad": {"min": 0.1,
        "max": 0.3}}`` with ``samples`` and ``seed`` for Monte Carlo. The sweep file is written to
        ``out_dir``/sweep_input.toml (a Scenario object to ``out_dir``/base_scenario.toml).

    Parameters:
        out_dir: output folder; cases already finished there are not run again.
        workers: local worker processes (>= 1); scheduler: a Dask scheduler address instead.
        Values in their keys' units (SI; ``operating.speed_rpm`` in rpm).

    Returns a :class:`Sweep`: ``.table``, the rows of sweep.csv (per case the swept values, whirl
    class and ``whirl_frequency_hz`` [Hz], onset [s], per-bearing peak force [N] and vertical range
    [m], final speed [rpm], energy dissipated [J]); ``.whirl_map()``. A failing case is a row with
    ``status`` "failed" and its error; bad input raises :class:`InputError`.
    """
    from .safeio import check_out_dir
    from .sweep_run import run_sweep

    if isinstance(workers, bool) or not isinstance(workers, int) or workers < 1:
        raise InputError("workers", workers, "must be an integer >= 1")
    if grid is None and ranges is None:
        if fixed is not None or samples is not None or seed is not None:
            raise InputError("fixed", fixed, "fixed / samples / seed go with grid= or ranges=; a sweep file has its own")
        if not isinstance(sweep_or_scenario, (str, Path)):
            raise InputError("sweep_or_scenario", type(sweep_or_scenario).__name__,
                             "must be a sweep file (path), or a scenario with grid= or ranges=")
        sweep_file = Path(sweep_or_scenario)
        if not sweep_file.is_file():
            raise InputError("sweep file", str(sweep_file), "file not found")
        out = check_out_dir(out_dir, "out_dir")
    else:
        out = check_out_dir(out_dir, "out_dir")
        sweep_file = _sweep_file_from_python(sweep_or_scenario, out, grid, ranges, fixed, samples, seed)
    run_sweep(str(sweep_file), out, workers=workers, scheduler=scheduler)
    return Sweep(out)


# ---------------------------------------------------------------------------------------------
# Diagnose (rotorlanding.diagnose_run.run_diagnose, the code path of `rotorlanding diagnose`)

class Diagnosis:
    """Results of a model-gap diagnosis (:func:`diagnose` or :meth:`load`): the output folder of
    ``rotorlanding diagnose`` (report.json, report.md, overlay.png or features.png).

    Attributes:
        report: the report.json content (dict)
        named_effect: the effect that significantly shrinks the gap, or None (no candidate does)
        named_effects: every named effect in order (``max_effects`` > 1)
        gap_before, gap_after: the weighted RMS feature distance [-] of the model as it is and
            with the named effects calibrated
        calibrated: {dotted key: value} of the named effects (switch and fitted parameter, in
            the key's units), ready for ``Scenario.with_overrides``
        points: per operating point: name, overrides, whirl measured / before / after
        features_before, features_after: the feature rows (``feature``, ``measured``,
            ``simulated``, ``scale``, ``distance``, ``point``; SI units as the feature names say)
        identifiability: what the channels given can tell apart, said before calibrating:
            ``candidates`` (each with the gap it opens, ``change``, whether the noise gate lets it
            be seen, and the feature rows that carry it), ``pairs`` (correlation of two seen
            candidates' signatures, the remainder the other leaves, ``told_apart``) and
            ``warnings`` (rotorlanding/identifiability.py)
        out_dir, report_md, figure: the folder, report.md and the figure written by the run
    """

    def __init__(self, out_dir):
        self.out_dir = Path(out_dir)
        f = self.out_dir / "report.json"
        if not f.is_file():
            raise InputError("diagnosis folder", str(self.out_dir), "holds no report.json (not a diagnosis' output)")
        try:
            self.report = json.loads(f.read_text())
        except ValueError as exc:
            raise InputError("report file", str(f), f"not JSON ({exc})") from None
        self.report_md = self.out_dir / "report.md"
        figs = [self.out_dir / n for n in ("overlay.png", "features.png") if (self.out_dir / n).is_file()]
        self.figure = figs[0] if figs else None

    @classmethod
    def load(cls, out_dir) -> "Diagnosis":
        """Read the output folder of a diagnosis (``report.json`` inside)."""
        return cls(out_dir)

    named_effect = property(lambda self: self.report["named_effect"])
    named_effects = property(lambda self: list(self.report["named_effects"]))
    gap_before = property(lambda self: self.report["gap_before"])
    gap_after = property(lambda self: self.report["gap_after"])
    points = property(lambda self: self.report["points"])
    features_before = property(lambda self: self.report["features_before"])
    features_after = property(lambda self: self.report["features_after"])
    # a report written before session 24 has none
    identifiability = property(lambda self: self.report.get("identifiability"))

    @property
    def calibrated(self) -> dict:
        from .config import parse_value

        out = {}
        for item in self.report["calibrated_overrides"]:
            k, v = item.split("=", 1)
            out[k] = parse_value(v)
        return out

    def plot_features(self, path=None) -> Path:
        """Per operating point and feature: measured, model before and after (one panel per
        feature, whirl direction as backward / none / forward; PNG, default ``features.png``)."""
        from .diagnose_run import _feature_figure

        path = _png(path, "features.png")
        _feature_figure(self.report, path)
        return path

    def __repr__(self) -> str:
        return (f"Diagnosis(named {self.named_effect!r}, gap {self.gap_before:.3g} -> {self.gap_after:.3g}, "
                f"{len(self.points)} point(s))")


def diagnose(measured, scenario, out_dir, *, set: dict | None = None, t_end: float | None = None,
             candidates=None, max_effects: int = 1, workers: int = 2, maxiter: int = 10,
             time_offset_s: float | None = None, parameters=None, noise_gap: float | None = None,
             ensemble: int | None = None, journals=("DE",), scatter_scales: bool | None = None) -> Diagnosis:
    """Model-gap diagnosis: which effect the model lacks explains where it and a measurement
    disagree (``rotorlanding diagnose``: the same code and files, ``out_dir``/report.json,
    report.md, overlay.png or features.png).

    Parameters:
        measured: the measurement file: a record (CSV, .mat, a results.h5) or a feature table
            with one or several operating points (.toml/.json; ``docs/measured_data.md``), e.g.
            ``scenarios/measured/paper_table2_fig39.toml``; or a list of records of repeated
            landings of one operating point (compared as their means with the model's ensemble
            of as many drops).
        scenario: the model as it is: a scenario file or a :class:`Scenario` (written to
            ``out_dir``/model.toml, which the workers read).
        out_dir: output folder (created).
        set: {dotted key: value} changes of the model (``--set``), e.g.
            ``{"effects.axial_rub": False}``.
        t_end: simulated time of every model run [s] (``--t-end``).
        candidates: effect names to try (default: every effect the model lacks except faults).
        max_effects: how many effects to name in turn (>= 1).
        workers: worker processes (>= 1); maxiter: search iterations per parameter (>= 1).
        time_offset_s: the drop instant in the record's clock [s] (default: detected).
        parameters: scenario keys tried as wrong parameters beside the effects (``--parameters``;
            None: the default list, []: none).
        noise_gap: the gap below which a disagreement is noise (``--noise-gap``; None: estimated
            from the model's drops with the record's noise).
        ensemble: drops per feature evaluation (``--ensemble``; 1: one drop; None: 4 against one
            record, as many as the records of repeated landings, 1 per point of a feature table).
        journals: whose per-journal features are compared (``--journals``): ``("DE",)`` or
            ``("DE", "NDE")`` (the NDE's landing depth, mean orbit, impact force, race spin-up).
        scatter_scales: each feature charged in units of its scale and the model's own scatter
            over its drops (``--scatter-scales``; None: on with ``ensemble`` >= 2 or repeated records,
            where that scatter is measured, off for one drop).

    Returns a :class:`Diagnosis` (``.named_effect``, ``.gap_before`` / ``.gap_after``,
    ``.calibrated``, ``.plot_features()``); its report equals the command's on the same input
    except the measured ``wall_s``. Bad input raises :class:`InputError` before any simulation.
    """
    from .diagnose_run import run_diagnose

    if isinstance(candidates, str):
        candidates = [c.strip() for c in candidates.split(",")]
    many = isinstance(measured, (list, tuple))
    if not (isinstance(measured, (str, Path)) or many and measured and all(isinstance(p, (str, Path)) for p in measured)):
        raise InputError("measured", type(measured).__name__, "must be a measurement file (path): CSV, .mat, "
                         "results.h5 or a feature table (.toml/.json), or a list of records of repeated landings")
    if isinstance(scenario, Scenario):
        from .safeio import check_out_dir

        out = check_out_dir(out_dir, "out_dir")
        scenario_path = out / "model.toml"
        scenario.to_toml(scenario_path)
    elif isinstance(scenario, (str, Path)):
        scenario_path = Path(scenario)
    else:
        raise InputError("scenario", type(scenario).__name__, "must be a scenario file (path) or a rotorlanding.Scenario")
    run_diagnose(str(scenario_path), [str(p) for p in measured] if many else str(measured), out_dir, sets=_override_items(set or {}),
                 t_end=_seconds("t_end", t_end),
                 candidates=candidates, max_effects=max_effects, workers=workers, maxiter=maxiter,
                 time_offset_s=time_offset_s, parameters=parameters, noise_gap=noise_gap, ensemble=ensemble,
                 journals=journals.split(",") if isinstance(journals, str) else journals, cli_names=False,
                 scatter_scales=scatter_scales)
    return Diagnosis(out_dir)


class Calibration:
    """Results of a calibration (:func:`calibrate` or :meth:`load`): the output folder of
    ``rotorlanding calibrate`` (calibration.csv, calibration.json).

    Attributes:
        designs: every design as a dict, best first (the command's ranking: designs checked at
            half the step and converged first): ``design`` (its number in the Monte Carlo draw),
            ``score`` [-] (sum of relative errors against the paper's experiments, 1 per wrong
            whirl class) and ``score_se`` [-] (its standard error on ensembles, else None),
            ``within_noise_of_best``, ``converged``, the searched keys (in their units, SI),
            ``err_<part>`` and ``err_<part>_se`` [-], per case ``<case>_direction``, ``<case>_hz``
            [Hz] and on ensembles the DE journal's ``<case>_de_direction``, ``<case>_de_hz`` [Hz],
            ``<case>_de_forward`` (drops)
        keys: the searched keys (dotted; a tied key "a,b" sets both to one value)
        best: the first design
        within_noise: the designs the search cannot tell from the best (a score within
            ``noise_z`` standard errors of the difference); [] without score errors (single landings)
        span: {key: [min, max]} over ``within_noise``: what the fit determines ({} without errors)
        noise_z: standard errors of a difference that tell two designs apart (2)
        space: the space file the run read
        ensemble: drops per case of each design (1: single centred landings); None for a run
            written before session 26
        cases: the landings scored (e.g. ``["fw3000", "fw7000", "fw10000"]``); None likewise
        out_dir: the output folder
    """

    def __init__(self, out_dir):
        self.out_dir = Path(out_dir)
        f = self.out_dir / "calibration.json"
        if not f.is_file():
            raise InputError("calibration folder", str(self.out_dir),
                             "holds no calibration.json (not a calibration's output)")
        try:
            data = json.loads(f.read_text())
        except ValueError as exc:
            raise InputError("calibration file", str(f), f"not JSON ({exc})") from None
        self.designs = list(data["designs"])
        self.space = data.get("space")
        self.noise_z = data.get("noise_z")
        self.ensemble = data.get("ensemble")
        self.cases = data.get("cases")
        self.span = dict(data.get("within_noise_span") or {})
        self.keys = [k for k in self.designs[0] if "." in k and not k.endswith("_half_step")] if self.designs else []

    @classmethod
    def load(cls, out_dir) -> "Calibration":
        """Read the output folder of a calibration (``calibration.json`` inside)."""
        return cls(out_dir)

    best = property(lambda self: self.designs[0])
    within_noise = property(lambda self: [d for d in self.designs if d.get("within_noise_of_best")])

    @property
    def overrides(self) -> dict:
        """The best design as ``{dotted key: value}`` (tied keys split), for ``Scenario.with_overrides``."""
        from .config import tied_keys

        return {k: self.best[tied] for tied in self.keys for k in tied_keys(tied)}

    def plot(self, path=None) -> Path:
        """Per searched key: every design's score [-] against the key's value, with its standard
        error where known, the designs within the noise of the best filled and the best starred;
        the span they cover shaded. PNG (default ``calibration.png``); returns the path."""
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        path = _png(path, "calibration.png")
        n = max(1, len(self.keys))
        fig, axes = plt.subplots(1, n, figsize=(5.0 * n, 3.8), squeeze=False)
        for ax, key in zip(axes[0], self.keys):
            x = np.array([d[key] for d in self.designs], dtype=float)
            y = np.array([d["score"] for d in self.designs], dtype=float)
            e = np.array([d.get("score_se") or 0.0 for d in self.designs], dtype=float)
            near = np.array([bool(d.get("within_noise_of_best")) for d in self.designs])
            if key in self.span:
                ax.axvspan(*self.span[key], color="tab:green", alpha=0.12,
                           label=f"within the noise of the best ({self.noise_z:g} s.e.)")
            ax.errorbar(x[~near], y[~near], yerr=e[~near], fmt="o", mfc="white", color="0.45", ms=5, lw=0.8,
                        label="other designs")
            if near.any():
                ax.errorbar(x[near], y[near], yerr=e[near], fmt="o", color="tab:green", ms=5, lw=0.8,
                            label="designs within the noise")
            ax.plot([x[0]], [y[0]], "*", color="tab:red", ms=14, label=f"best (design {self.best['design']})")
            lengths = ("diameter", "clearance", "length", "thickness", "_m")
            ax.set_xlabel(f"{key} [m]" if key.endswith(lengths) else f"{key} (SI units)")
            ax.set_ylabel("score [-] (+/- standard error)")
            ax.grid(alpha=0.3)
            ax.legend(fontsize=7)
        fig.suptitle(f"calibration: {self.space}", fontsize=10)
        fig.tight_layout()
        save_figure(fig, path)
        plt.close(fig)
        return path

    def __repr__(self) -> str:
        se = self.best.get("score_se") if self.designs else None
        return (f"Calibration({len(self.designs)} designs, best {self.best['design']} score {self.best['score']:.3g}"
                + ("" if se is None else f" +/- {se:.2g}") + f", {len(self.within_noise)} within its noise)")


def calibrate(space, out_dir, *, workers: int = 2) -> Calibration:
    """Monte Carlo calibration of rig unknowns against the paper's validation data
    (``rotorlanding calibrate``: the same code and files, ``out_dir``/calibration.csv and
    calibration.json).

    Parameters:
        space: the space file (TOML): the unknowns' ranges, samples, seed, t_end [s], the cases
            scored and the drops per case (``ensemble``); the shipped ones are in
            ``scenarios/calibration/`` (``rotor_landings.toml``: the rig rotor fitted by landing,
            2304 landings, ~21 min on 2 cores).
        out_dir: output folder (created).
        workers: worker processes (>= 1).

    Returns a :class:`Calibration` (``.best``, ``.overrides``, ``.within_noise``, ``.span``,
    ``.plot()``). Bad input raises :class:`InputError` before any landing.
    """
    from .calibrate_run import calibrate as run_calibration
    from .safeio import check_out_dir

    if isinstance(workers, bool) or not isinstance(workers, int) or workers < 1:
        raise InputError("workers", workers, "an integer >= 1")
    if not isinstance(space, (str, Path)):
        raise InputError("space", type(space).__name__, "must be a calibration space file (path, TOML)")
    check_out_dir(out_dir, "out_dir")
    run_calibration(space, out_dir, workers=workers)
    return Calibration(out_dir)
