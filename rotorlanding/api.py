"""The Python API: build or load a rotor and a landing scenario, simulate, read and plot results.

Units are SI throughout (m, kg, s, N, Pa, J, W, rad); a name says its unit where it is not SI
(``speed_rpm``, ``frequency_hz``). Every bad input raises the one-line
:class:`~rotorlanding.errors.InputError` of the TOML path: the API validates through the same
readers as the command line, so a rotor built here is the rotor its TOML file would give.

    >>> import rotorlanding as rl
    >>> sc = rl.Scenario.load("scenarios/landing_7000rpm.toml", set={"operating.t_end": 0.05})
    >>> landing = rl.simulate(sc)
    >>> landing.whirl["direction"], landing["DE_normal_force_n"].unit
    ('none', 'N')

Reference: ``docs/python_api.md``.
"""

from __future__ import annotations

import copy
import json
import math
import tempfile
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .errors import InputError
from .safeio import atomic_write_text
from .rotor import rotor_from_dict
from .scenario import apply_overrides, scenario_from_dict

__all__ = ["Rotor", "Modes", "Scenario", "Landing", "Series", "simulate", "InputError"]


# ---------------------------------------------------------------------------------------------
# TOML writing (the subset the rotor and scenario tables use: tables, arrays of tables, scalars,
# lists of scalars). Floats are written with repr(), so a value reads back bit for bit.

def _toml_value(v) -> str:
    if isinstance(v, np.generic):  # numpy scalars: their repr is not TOML (np.float64(0.1))
        v = v.item()
    if isinstance(v, np.ndarray):
        v = v.tolist()
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        if math.isnan(v):
            return "nan"
        if math.isinf(v):
            return "inf" if v > 0 else "-inf"
        return repr(v)
    if isinstance(v, str):
        return json.dumps(v)
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_toml_value(x) for x in v) + "]"
    if isinstance(v, dict):
        return "{" + ", ".join(f"{_key(k)} = {_toml_value(x)}" for k, x in v.items()) + "}"
    raise InputError("value", v, "cannot be written to TOML (numbers, strings, booleans, lists, tables)")


def _key(k: str) -> str:
    return k if k.replace("_", "").replace("-", "").isalnum() else json.dumps(k)


def _is_table_array(v) -> bool:
    return isinstance(v, list) and bool(v) and all(isinstance(x, dict) for x in v)


def _toml_dump(data: dict, prefix: str = "") -> str:
    lines = [f"{_key(k)} = {_toml_value(v)}" for k, v in data.items()
             if not isinstance(v, dict) and not _is_table_array(v)]
    out = "\n".join(lines) + ("\n" if lines else "")
    for k, v in data.items():
        name = f"{prefix}.{_key(k)}" if prefix else _key(k)
        if isinstance(v, dict):
            out += f"\n[{name}]\n" + _toml_dump(v, name)
        elif _is_table_array(v):
            for item in v:
                out += f"\n[[{name}]]\n" + _toml_dump(item, name)
    return out


def _plain(v):
    """numpy scalars and arrays as the Python numbers and lists a TOML file gives."""
    if isinstance(v, dict):
        return {k: _plain(x) for k, x in v.items()}
    if isinstance(v, (list, tuple)):
        return [_plain(x) for x in v]
    if isinstance(v, np.ndarray):
        return _plain(v.tolist())
    if isinstance(v, np.generic):
        return v.item()
    return v


def _table(v, field: str) -> dict:
    if not isinstance(v, dict):
        raise InputError(field, v, "must be a table (a dict)")
    return copy.deepcopy(v)


def _tables(v, field: str) -> list:
    if isinstance(v, (str, bytes, dict)) or not hasattr(v, "__iter__"):
        raise InputError(field, v, "must be a list of tables (dicts)")
    return [_table(x, f"{field}[{i}]") for i, x in enumerate(v)]


# ---------------------------------------------------------------------------------------------
# Rotor

class Rotor:
    """A rotor: shaft sections, disks, stations, materials (and, for landings, its Craig-Bampton
    reduction). Built in Python with the fields of the ``[rotor]`` table (``docs/rotor_file.md``)
    or read with :meth:`from_toml`; either way validated by the TOML reader, so bad input raises
    the same one-line :class:`InputError` naming the dotted field (``rotor.sections[1].length``).

    Parameters (SI):
        name: str
        materials: {name: {"youngs_modulus" [Pa], "density" [kg/m^3], "poisson_ratio" [-] or
            "shear_modulus" [Pa]}}
        sections: list of {"length" [m], "outer_diameter" [m], "inner_diameter" [m] (default 0),
            "material", "elements" (default 1)}, left to right from x = 0
        disks: list of {"name", "position" [m], "mass" [kg], "polar_inertia" [kg m^2],
            "transverse_inertia" [kg m^2]} or {"name", "position", "outer_diameter" [m],
            "inner_diameter" [m], "thickness" [m], "material"}
        stations: {name: x [m]}, named axial positions (bearings, sensors)
        supports: list of {"station", "kyy", "kzz", "kyz", "kzy" [N/m], "cyy", "czz", "cyz",
            "czy" [N s/m]}: linear supports used by :meth:`modes`
        reduction: {"boundary_stations": [...], "modes": int, "boundary_rotations": bool}
        damping: {"mass_proportional" [1/s], "stiffness_proportional" [s]}
        max_speed_rpm: highest operating speed [rpm]

    Attributes: ``table`` (the ``[rotor]`` table, a dict), ``model`` (the validated
    :class:`rotorlanding.rotor.Rotor` dataclass), ``mass`` [kg], ``length`` [m],
    ``polar_inertia`` [kg m^2]; :meth:`fe` gives the finite-element matrices.
    """

    def __init__(self, name: str = "rotor", *, materials: dict, sections: list, disks=(), stations=None,
                 supports=(), reduction: dict | None = None, damping: dict | None = None,
                 max_speed_rpm: float = 10000.0, _source: str | None = None):
        table = {"name": name, "max_speed_rpm": max_speed_rpm, "materials": _table(materials, "rotor.materials"),
                 "sections": _tables(sections, "rotor.sections")}
        if stations:
            table["stations"] = _table(stations, "rotor.stations")
        if disks:
            table["disks"] = _tables(disks, "rotor.disks")
        if supports:
            table["supports"] = _tables(supports, "rotor.supports")
        if reduction is not None:
            table["reduction"] = _table(reduction, "rotor.reduction")
        if damping is not None:
            table["damping"] = _table(damping, "rotor.damping")
        self._init(_plain(table), _source)

    def _init(self, table: dict, source: str | None) -> None:
        self.table = copy.deepcopy(table)
        self.model = rotor_from_dict({"rotor": copy.deepcopy(table)}, source=source)

    @classmethod
    def from_table(cls, table: dict, *, source: str | None = None) -> "Rotor":
        """A rotor from an already-parsed ``[rotor]`` table (a dict)."""
        self = cls.__new__(cls)
        self._init(table, source)
        return self

    @classmethod
    def from_toml(cls, path) -> "Rotor":
        """Read the ``[rotor]`` table of a rotor file or of a scenario file (``include`` resolved),
        or a rotor saved by ROSS (as :meth:`from_ross` without catcher stations)."""
        from .rotor import read_rotor_table

        return cls.from_table(read_rotor_table(path), source=str(Path(path)))

    @classmethod
    def from_ross(cls, source, *, catchers: dict | None = None, catcher_nodes: dict | None = None,
                  reduction_modes: int = 8, name: str | None = None, max_speed_rpm: float | None = None,
                  ignore=(), bearings_at_rpm: float | None = None) -> "Rotor":
        """A rotor from ROSS: a file written by ``ross.Rotor.save`` (.toml or .json, read without
        ROSS) or a live ``ross.Rotor`` (``pip install '.[ross]'``). Shaft elements (uniform,
        hollow, conical), disks, point masses and constant-coefficient bearings (as ``supports``
        for :meth:`modes`) convert; anything else raises a one-line :class:`InputError` naming
        the element and why (``ignore=[tag or class]`` leaves elements out on purpose).

        ``catchers``: {station name: x [m]} or ``catcher_nodes``: {station name: ROSS node}: the
        catcher-bearing sleeves, which become stations and the Craig-Bampton boundary
        (``reduction_modes`` fixed-interface modes) so that the rotor can land
        (:meth:`Scenario.with_rotor`). ``max_speed_rpm`` [rpm] (default: the file's, else 10000).
        ``bearings_at_rpm`` [rpm]: freeze frequency-dependent bearing coefficients at this spin
        speed (as ROSS's ``run_modal`` at that speed). Mapping and limits: ``docs/ross.md``."""
        from .from_ross import table_from_ross

        table, src = table_from_ross(source, catchers=catchers, catcher_nodes=catcher_nodes,
                                     reduction_modes=reduction_modes, name=name, max_speed_rpm=max_speed_rpm,
                                     ignore=ignore, bearings_at_rpm=bearings_at_rpm)
        return cls.from_table(table, source=src)

    def to_toml(self, path) -> Path:
        """Write the rotor as a rotor file (``[rotor]`` table) that :meth:`from_toml` and the
        command line (``rotorlanding modes PATH``) read back to the same model, bit for bit."""
        path = Path(path)
        atomic_write_text(path, "# rotor written by rotorlanding.Rotor.to_toml; units SI (m, kg, Pa, kg m^2)\n"
                          + _toml_dump({"rotor": self.table}))
        return path

    # properties of the validated model
    @property
    def name(self) -> str:
        return self.model.name

    @property
    def mass(self) -> float:
        """Total mass [kg] (shaft sections and disks)."""
        return self.model.mass

    @property
    def length(self) -> float:
        """Length [m]."""
        return self.model.length

    @property
    def polar_inertia(self) -> float:
        """Polar moment of inertia about the spin axis [kg m^2]."""
        return self.model.polar_inertia

    def fe(self):
        """The free rotor's Timoshenko finite-element model (:class:`rotorlanding.timoshenko.RotorFE`):
        ``M`` [kg, kg m^2], ``K`` [N/m, N m/rad], ``G`` (gyroscopic, per rad/s of spin), ``C``
        (Rayleigh damping), node positions ``nodes`` [m]; DOFs per node y, z [m], alpha, beta [rad]."""
        from .timoshenko import assemble

        return assemble(self.model)

    def modes(self, speeds_rpm, *, n_modes: int | None = None, free: bool = False,
              model: str = "full") -> "Modes":
        """Damped natural frequencies [Hz], damping ratios and whirl labels at each spin speed
        in ``speeds_rpm`` [rpm]. ``free``: ignore the linear supports; ``model``: "full" (FE) or
        "reduced" (the rotor's Craig-Bampton reduction). Returns :class:`Modes`."""
        from .modal import campbell
        from .reduction import full_model, reduce_rotor

        speeds = [float(s) for s in np.atleast_1d(speeds_rpm)]
        for s in speeds:
            if not math.isfinite(s) or s < 0:
                raise InputError("speeds_rpm", s, "must be finite and >= 0 rpm")
        burst, part = self.model.burst_speed_rpm()
        if speeds and max(speeds) > burst:
            raise InputError("speeds_rpm", max(speeds), f"must be <= {burst:.4g} rpm: above it {part} bursts even if "
                             "made of the strongest steel")
        if model not in ("full", "reduced"):
            raise InputError("model", model, "must be 'full' or 'reduced'")
        if n_modes is not None and (isinstance(n_modes, bool) or not isinstance(n_modes, int) or n_modes < 1):
            raise InputError("n_modes", n_modes, "must be an integer >= 1")
        fe = self.fe()
        system = reduce_rotor(fe) if model == "reduced" else full_model(fe)
        if not free:
            system = system.with_supports()
        return Modes(self, system, campbell(system, speeds, n_modes), n_modes)

    def __repr__(self) -> str:
        return (f"Rotor({self.name!r}: {len(self.model.sections)} sections, {len(self.model.disks)} disks, "
                f"stations {list(self.model.stations)}, {self.mass:.4g} kg, {self.length:.4g} m)")


class Modes:
    """Modal results of :meth:`Rotor.modes`, one entry per speed.

    Attributes: ``speeds_rpm`` (array [rpm]), ``results`` (list of
    :class:`rotorlanding.modal.ModalResult`), ``frequencies_hz`` (speeds x modes array [Hz], NaN
    where a speed has fewer modes), ``damping_ratios`` (same shape, [-]), ``whirl`` (list of lists
    of "forward" / "backward" / "none")."""

    def __init__(self, rotor: Rotor, system, results, n_modes):
        self.rotor, self._system, self.results, self._n_modes = rotor, system, results, n_modes
        self.speeds_rpm = np.array([r.speed_rpm for r in results])
        n = max((len(r.modes) for r in results), default=0)
        self.frequencies_hz = np.full((len(results), n), np.nan)
        self.damping_ratios = np.full((len(results), n), np.nan)
        for i, r in enumerate(results):
            for k, m in enumerate(r.modes):
                self.frequencies_hz[i, k] = m.frequency_hz
                self.damping_ratios[i, k] = m.damping_ratio
        self.whirl = [[m.whirl for m in r.modes] for r in results]

    def to_dict(self) -> dict:
        """The ``rotorlanding modes --json`` content: speeds [rpm] and per speed the modes'
        frequency [Hz], damping ratio and whirl."""
        return {"speeds_rpm": self.speeds_rpm.tolist(),
                "modes": [[m.to_dict() for m in r.modes] for r in self.results]}

    def campbell(self, path, *, points: int = 41, max_speed_rpm: float | None = None,
                 max_frequency_hz: float | None = None) -> Path:
        """Write the Campbell diagram (PNG): damped frequency [Hz] against spin speed [rpm] on
        ``points`` speeds from 0 to ``max_speed_rpm`` (default: the larger of the rotor's
        max_speed_rpm and the highest speed asked), markers coloured by whirl, the 1x line."""
        from .modal import campbell, plot_campbell

        top = max_speed_rpm or max(float(self.speeds_rpm.max(initial=0.0)), self.rotor.model.max_speed_rpm)
        dense = campbell(self._system, np.linspace(0.0, top, points), self._n_modes)
        return Path(plot_campbell(dense, path, title=f"Campbell diagram: {self.rotor.name}",
                                  max_frequency_hz=max_frequency_hz))

    def __repr__(self) -> str:
        return f"Modes({len(self.results)} speeds, up to {self.frequencies_hz.shape[1]} modes)"


# ---------------------------------------------------------------------------------------------
# Scenario

def _override_items(overrides: dict) -> list[str]:
    """Dotted overrides as the command line's ``KEY=VALUE`` items (the one ``--set`` parser)."""
    if not isinstance(overrides, dict):
        raise InputError("set", overrides, "must be a dict of dotted keys -> values, e.g. {'contact.mu_rad': 0.2}")
    return [f"{k}={_toml_value(v)}" for k, v in overrides.items()]


class Scenario:
    """A landing scenario: rotor, catcher bearings, contact, AMB drop, spin, solver (the tables of
    ``docs/scenario_file.md``). Load one with :meth:`load`; derive variants for studies with
    :meth:`replace` / :meth:`with_overrides` (dotted keys, as ``--set`` on the command line).

    Attributes: ``name``, ``speed_rpm`` [rpm], ``t_end`` [s], ``rotor`` (:class:`Rotor`),
    ``bearings`` (names), ``table`` (the fully resolved input tables, a dict), ``model`` (the
    validated :class:`rotorlanding.scenario.Scenario`)."""

    def __init__(self, model):
        self.model = model

    @classmethod
    def load(cls, path, set: dict | None = None, overlays=()) -> "Scenario":
        """Read a scenario file (``include`` resolved), merge ``overlays`` (files), apply ``set``
        ({dotted key: value}, exactly like ``rotorlanding run --set KEY=VALUE``), validate."""
        from .scenario import load_scenario

        return cls(load_scenario(path, _override_items(set or {}), overlays))

    @classmethod
    def from_dict(cls, tables: dict, *, name: str | None = None) -> "Scenario":
        """A scenario from its tables (a dict as a parsed scenario file, includes already merged)."""
        return cls(scenario_from_dict(tables, name=name))

    def with_overrides(self, overrides: dict) -> "Scenario":
        """A new scenario with ``{dotted key: value}`` applied (``{"contact.mu_rad": 0.2,
        "operating.speed_rpm": 9000.0}``); this one is unchanged."""
        data = copy.deepcopy(self.model.raw)
        apply_overrides(data, _override_items(overrides))
        return Scenario(scenario_from_dict(data, source=self.model.source, name=self.model.name))

    def with_rotor(self, rotor: Rotor) -> "Scenario":
        """A new scenario landing ``rotor`` (a :class:`Rotor`) on this scenario's catcher
        bearings: its stations must include the bearings' stations and it needs a
        ``reduction`` (the Craig-Bampton boundary at the sleeves). The scenario's
        ``[limits] close_clearances_m`` are kept at the stations the new rotor defines (the same
        stators at the same names) and left out at the others, which it does not have; give or
        change the new rotor's with :meth:`with_overrides`
        (``{"limits.close_clearances_m.DE_AMB": 4e-4}``)."""
        if not isinstance(rotor, Rotor):
            raise InputError("rotor", type(rotor).__name__, "must be a rotorlanding.Rotor")
        data = copy.deepcopy(self.model.raw)
        data["rotor"] = copy.deepcopy(rotor.table)
        gaps = (data.get("limits") or {}).get("close_clearances_m")
        if isinstance(gaps, dict):
            stations = (rotor.table.get("stations") or {})
            data["limits"]["close_clearances_m"] = {k: x for k, x in gaps.items() if k in stations}
        return Scenario(scenario_from_dict(data, name=self.model.name))

    def replace(self, **dotted) -> "Scenario":
        """Keyword form of :meth:`with_overrides`: a double underscore stands for the dot
        (``sc.replace(contact__mu_rad=0.2, operating__t_end=0.05)``)."""
        return self.with_overrides({k.replace("__", "."): v for k, v in dotted.items()})

    def to_toml(self, path) -> Path:
        """Write the fully resolved scenario as one TOML file (no includes) that
        :meth:`load` and ``rotorlanding run`` read back to the same scenario."""
        path = Path(path)
        atomic_write_text(path, "# scenario written by rotorlanding.Scenario.to_toml (includes resolved); units SI\n"
                          + _toml_dump(self.model.raw))
        return path

    @property
    def name(self) -> str:
        return self.model.name

    @property
    def speed_rpm(self) -> float:
        """Rotor speed at the drop [rpm]."""
        return self.model.speed_rpm

    @property
    def t_end(self) -> float:
        """Simulated time [s]."""
        return self.model.t_end

    @property
    def bearings(self) -> list[str]:
        """Catcher-bearing names (prefix of their output series, ``DE_normal_force_n``)."""
        return list(self.model.bearings)

    @property
    def rotor(self) -> Rotor:
        return Rotor.from_table(self.model.raw["rotor"])

    @property
    def table(self) -> dict:
        return copy.deepcopy(self.model.raw)

    def __repr__(self) -> str:
        return (f"Scenario({self.name!r}: {self.speed_rpm:g} rpm, t_end {self.t_end:g} s, bearings "
                f"{self.bearings})")


# ---------------------------------------------------------------------------------------------
# Landing results

@dataclass(frozen=True)
class Series:
    """One time series of a landing: ``values`` (numpy array, one per sample of ``Landing.t``)
    and its ``unit`` (as declared in the mechanism registry, ``rotorlanding.mechanisms``)."""

    name: str
    values: np.ndarray
    unit: str

    def __array__(self, dtype=None, copy=None):
        return np.asarray(self.values, dtype=dtype)

    def __len__(self) -> int:
        return len(self.values)


class _SeriesResults:
    """Series by name, shared by the results objects: they hold ``_series`` ({name: values}, may
    read lazily), ``units`` ({name: unit}) and ``summary`` (dict with ``complete``)."""

    @property
    def series_names(self) -> list[str]:
        return list(self._series)

    @property
    def complete(self) -> bool:
        return bool(self.summary.get("complete", False))

    def series(self, name: str) -> Series:
        """The time series ``name`` with its unit; an unknown name is an InputError listing the
        available ones."""
        if name not in self._series:
            raise InputError("series", name, f"unknown series; available: {', '.join(self._series)}")
        return Series(name, np.asarray(self._series[name]), self.units[name])

    def __getitem__(self, name: str) -> Series:
        return self.series(name)

    def __contains__(self, name) -> bool:
        return name in self._series


class Landing(_SeriesResults):
    """Results of a landing (:func:`simulate` or :meth:`load`), the content of ``results.h5``.

    Attributes:
        summary: the summary.json content (dict; SI units, speeds in rpm as named)
        whirl: the landing's whirl (dict: ``direction`` "forward"/"backward"/"none",
            ``frequency_hz``, ``onset_s``, ``bearing``, ``per_bearing``, and on two bearings
            ``shape``: the other journal's phase, amplitude ratio and the form, cylindrical or conical)
        t: sample times [s]
        series_names, units: the series and their units ({name: unit})
        q, v, coordinates: generalised coordinates and velocities (samples x coordinates) and
            their names
        scenario: the :class:`Scenario` that was run
        complete: False when the solver stopped early (``summary["message"]`` says why)
    Series by name: ``landing.series("DE_normal_force_n")`` or ``landing["DE_normal_force_n"]``
    (a :class:`Series`, ``.values`` and ``.unit``).
    """

    def __init__(self, scenario: Scenario, t, q, v, coordinates, series: dict, units: dict, summary: dict):
        self.scenario = scenario
        self.t = np.asarray(t)
        self.q, self.v, self.coordinates = np.asarray(q), np.asarray(v), list(coordinates)
        self._series = series
        self.units = dict(units)
        self.summary = summary

    @property
    def whirl(self) -> dict:
        from .whirl import landing_whirl

        return landing_whirl(self.summary["whirl"]) if self.summary.get("whirl") else {}

    # ----- persistence
    def save(self, path) -> Path:
        """Write results.h5 (the layout of ``rotorlanding run``, :mod:`rotorlanding.results`)."""
        from .results import write_results

        path = Path(path)
        return write_results(path, scenario_raw=self.scenario.model.raw, scenario_name=self.scenario.name,
                             names=self.coordinates, t=self.t, q=self.q, v=self.v, series=self._series,
                             units=self.units, summary=self.summary, complete=self.complete,
                             t_reached=float(self.summary.get("t_reached_s", self.t[-1])),
                             message=self.summary.get("message", ""))

    @classmethod
    def load(cls, path) -> "Landing":
        """Read a results.h5 written by :meth:`save` or ``rotorlanding run``."""
        from .results import read_results

        path = Path(path)
        if not path.is_file():
            raise InputError("results file", str(path), "no such file")
        try:
            res = read_results(path)
            units = res["units"]
        except (OSError, KeyError) as exc:
            raise InputError("results file", str(path), f"not a rotorlanding results.h5 ({exc})") from None
        if res["attrs"].get("kind") == "coastdown":
            raise InputError("results file", str(path), "is a coast-down result; Landing.load reads landings")
        scenario = Scenario(scenario_from_dict(res["scenario"], name=res["attrs"].get("scenario_name")))
        from .mechanisms import series_units

        # the registry's output order (the file stores series alphabetically)
        schema = list(series_units(scenario.bearings))
        order = [k for k in schema if k in res["series"]] + sorted(set(res["series"]) - set(schema))
        return cls(scenario, res["time_s"], res["q"], res["v"], res["names"], {k: res["series"][k] for k in order},
                   {k: str(units[k]) for k in order}, res["summary"])

    # ----- figures (rotorlanding.plots, the CLI's figures)
    def _plot(self, which: str, path) -> Path:
        from .plots import plot_all

        clear = {b: self.summary["bearings"][b]["clearance_m"] for b in self.scenario.bearings}
        with tempfile.TemporaryDirectory() as tmp:
            files = plot_all(tmp, self.t, self._series, self.summary, clear, self.scenario.model.amb.t_drop,
                             which={which})
            path = Path(path) if path is not None else Path(f"{which}.png")
            path.write_bytes(files[0].read_bytes())
        return path

    def plot_orbits(self, path=None) -> Path:
        """Journal orbits [mm] at each catcher bearing with the radial-clearance circle (PNG at
        ``path``, default ``orbits.png``); returns the path."""
        return self._plot("orbits", path)

    def plot_displacements(self, path=None) -> Path:
        """Journal displacements y, z [mm] against time [s] with the +/- clearance band (PNG)."""
        return self._plot("displacements", path)

    def plot_spectrum(self, path=None) -> Path:
        """Full spectrum of y + i z after the drop (amplitude [um] against frequency [Hz],
        negative = backward whirl), the +-1x lines (PNG)."""
        return self._plot("spectrum", path)

    def plot_span(self, path=None) -> Path:
        """The rotor's largest radial displacement off the bearings' axis [mm] at every point of its
        span [m] over the run, with the catcher clearances and the scenario's close clearances
        (``[limits] close_clearances_m``) drawn (PNG)."""
        return self._plot("span", path)

    def plot_forces(self, path=None) -> Path:
        """Force of each catcher bearing on the rotor [kN] against time [s] (PNG)."""
        return self._plot("forces", path)

    def plot_speeds(self, path=None) -> Path:
        """Rotor and inner-race speeds [rpm] against time [s] (PNG)."""
        return self._plot("speeds", path)

    def animate(self, path, *, fps: float = 20.0, play_fps: float = 20.0, view: str = "all",
                max_frames: int | None = None, size: tuple[int, int] = (1280, 720), at: float | None = None) -> dict:
        """Render the landing (``rotorlanding animate``): ``path`` ending in .mp4 (needs
        ``pip install 'rotorlanding[video]'``), .gif, or .png (one still at ``at`` [s], default
        the end). The rotor in 3D (Exudyn's raytracer, no display needed) beside each journal's
        orbit relative to its inner race with the clearance circle; time [s], speed [rpm] and
        contact forces [kN] on the frame. ``fps``: frames per simulated second
        (floor(duration x fps) + 1 frames); ``play_fps``: the movie's frame rate; ``view``:
        "all", a bearing name or "rotor"; ``size``: (width, height) [px]. Returns
        {"frames", "file", "magnification", "times_s"}."""
        from .animate import animate

        with tempfile.TemporaryDirectory() as tmp:
            res = self.save(Path(tmp) / "results.h5")
            return animate(res, path, fps=fps, play_fps=play_fps, view=view, max_frames=max_frames,
                           size=size, at=at)

    def __repr__(self) -> str:
        w = self.whirl
        return (f"Landing({self.scenario.name!r}: {self.t[-1]:.4g} s, {len(self.t)} samples, whirl "
                f"{w.get('direction', '?')}{'' if self.complete else ', INCOMPLETE'})")


def simulate(scenario: Scenario, progress: bool = False, *, t_end: float | None = None) -> Landing:
    """Simulate a landing: the rotor dropped by its AMBs onto the catcher bearings.

    Parameters:
        scenario: a :class:`Scenario` (``Scenario.load(path)``).
        progress: show a text progress bar on stderr.
        t_end: simulated time [s]; default the scenario's ``operating.t_end`` [s]. Same as
            ``rotorlanding run --t-end``.

    Returns a :class:`Landing`: ``.summary`` (the summary.json of ``rotorlanding run``, bit for
    bit except the wall-clock times), ``.whirl``, ``.t`` [s], series by name with their SI units
    (displacements [m], forces [N], speeds [rpm], energies [J], powers [W]), plots, ``.save()``.
    A solver that stops early does not raise: ``landing.complete`` is False and
    ``landing.summary["message"]`` says where and why. Bad input raises :class:`InputError`.
    """
    from . import run
    from .mechanisms import series_units

    if not isinstance(scenario, Scenario):
        raise InputError("scenario", type(scenario).__name__, "must be a rotorlanding.Scenario (Scenario.load(path))")
    if t_end is not None:
        scenario = scenario.with_overrides({"operating.t_end": float(t_end)})
    spec, t, q, v, stats = run.simulate(scenario.model, progress=bool(progress))
    if len(t) < 2:
        raise InputError("scenario", scenario.name, f"the solver stopped before the first output: {stats['message']}")
    series, summary = run.build_summary(scenario.model, spec, t, q, v, stats)
    units = series_units(spec.bearing_names)
    return Landing(scenario, t, q, v, spec.names, series, {k: units[k] for k in series}, summary)
