"""Model-gap diagnosis: which missing effect, or which wrong parameter, explains where simulation
and measurement disagree (docs/measured_data.md).

The machinery behind ``rotorlanding diagnose`` and the Python API's ``rotorlanding.diagnose(...)``
(:mod:`rotorlanding.api_studies`, which returns a ``Diagnosis``); the module is named ``diagnose_run`` so
that the package attribute ``rotorlanding.diagnose`` is the function.

``diagnose(measured, scenario_path, ...)``:
  a. simulate the model as it is at every operating point (one point for a record; one per
     ``[points.NAME]`` table of a feature table, each with its scenario overrides), extract the
     same features as from the measurement, gap_before = one weighted RMS over the rows of every
     point (:func:`rotorlanding.features.gap_points`; a feature one side cannot produce is charged
     ``features.ABSENT_FEATURE_DISTANCE``); repeated landings of one point (several records,
     :class:`Repeated`) are compared as the means of their features against the model's ensemble
     of as many drops;
  b. the noise gate from the data (:func:`_noise_gate`): the model dropped from a 5 um disc with
     the record's own sensor noise (:func:`sensor_noise`), sampled at its rate and made of its
     channels (so a member's gap has the record's rows), the 95 % prediction bound of one more
     member's gap (with repeated landings the members are ensembles of as many drops as there
     are records, so the gate has the statistics of the data's means); a user-given drop instant is checked against the detected one;
  c. candidates: each effect the model lacks (switched on, its parameter calibrated within bounds
     on the gap over all points jointly; threads sharing one process pool) and each uncertain
     parameter of the scenario (its ``[bounds]``; screened either side of its value, the closest calibrated);
  d. rank by a BIC-like score n ln(gap^2) + k ln n (n feature rows, k fitted numbers) and name the
     best only if the gap is above the noise gate, its score beats the unchanged model by more
     than 2, and either it shrinks the gap by at least ``min_improvement`` (30 %), or it makes the
     whirl direction right at some operating point without making it wrong at another, or what it
     leaves is inside its own noise gate (the candidate model's drops: a chaotic true model);
  e. ``--max-effects N`` repeats from the improved model, re-fitting everything named so far
     jointly with each new candidate before they are ranked (:func:`_joint_refit`); at the end the gate of the final model judges
     what stays unexplained (``explanation`` = "unexplained", with the largest remaining features).
"""

from __future__ import annotations

import copy
import functools
import json
import math
import time
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field, replace

import numpy as np
from scipy.optimize import minimize_scalar

from .effects import CATALOGUE
from .errors import InputError
from .features import ABSENT_FEATURE_DISTANCE, JOURNALS, RACE_LAG_WINDOW_S, extract_features, gap_points
from .identifiability import alike_with, assess, signature
from .measured import Measurement
from .mechanisms import housing_force, rotor_force
from .runner import Pool, reduction_cache
from .safeio import atomic_write_text, save_figure

#: the noise gate is estimated (:func:`_noise_gate`); this is its floor: on clean data (the
#: model against its own resampled, noisy output) the gap is 0.03-0.1
NOISE_GAP_MIN = 0.1
#: drops of the model that estimate the gate (drops from random points of a 5 um disc)
NOISE_MEMBERS = 4
#: reads of each model drop through the records' sensor model (_Simulator.as_recorded): the
#: noise left in the model's mean features is that of 1/8 of a record's (a read, logger sampling,
#: noise and feature extraction, costs about 5 ms against a 0.2-0.8 s landing; docs/performance.md)
MODEL_REALISATIONS = 8
#: the seed of the model's reads (drop k of point j: [MODEL_READ_SEED + 1000 j + k, read]), apart
#: from the members' (seeds 0 ... members x records - 1)
MODEL_READ_SEED = 10000
#: a named effect must remove at least this share of the remaining gap; with two missing effects
#: the first one found can only remove its own part (e.g. 48 % for windage + ribbon cross-coupling)
MIN_STEP_IMPROVEMENT = 0.3
#: calibration of a parameter: a grid over its bounds (one parallel batch), then a bounded search
#: between the neighbours of the best grid value
GRID_POINTS = 5


#: post-processing mechanisms whose series no feature reads (rotorlanding.mechanisms.evaluate's skip)
POST_NOT_NEEDED = frozenset({"catcher_thermal"})


@dataclass
class Repeated:
    """Repeated landings of one operating point: the features of each record (name -> (value,
    scale)), e.g. a test campaign's drops at one speed. A rattling landing is chaotic, so one
    record is one draw; diagnose compares the records' mean features (``features.ensemble_features``)
    with the model's ensemble of as many drops, and the noise gate with member ensembles of that
    size (issue 20, points 1 and 6). ``spread``: per feature, the standard deviation over the
    records (the data's own scatter, reported)."""

    features: list

    def __post_init__(self):
        if len(self.features) < 2:
            raise ValueError(f"Repeated needs at least 2 records, got {len(self.features)}")

    @property
    def spread(self) -> dict:
        out = {}
        for name in sorted({k for f in self.features for k in f}):
            vals = [f[name][0] for f in self.features if name in f and isinstance(f[name][0], (int, float))
                    and not isinstance(f[name][0], bool)]
            if len(vals) >= 2:
                out[name] = float(np.std(vals, ddof=1))
        return out


@dataclass
class Point:
    """An operating point: its name, the scenario overrides that define it and the measured
    features there (name -> (value, scale))."""

    name: str
    overrides: list[str] = field(default_factory=list)
    features: dict = field(default_factory=dict)


def _simulate_features(scenario_path, overrides, clearance, *, with_series=False, noise=None, seed=0,
                       realisations: int = 0):
    """Features of one simulation; ``noise`` (channel -> standard deviation, the measured record's
    own sensor noise, :func:`sensor_noise`) is added to the model's series first (seeded).
    ``realisations`` > 0: the list of the features of that many records of this one landing, each
    with its own noise and logger phase (seeds ``[seed, m]``), the landing simulated once."""
    from .postprocess import evaluate
    from .run import simulate
    from .scenario import load_scenario

    sc = load_scenario(scenario_path, overrides)
    spec, t, q, v, info = simulate(sc, progress=False, reduction=reduction_cache())
    # the catcher temperatures are no feature and their post-processing (the thermal network
    # integrated over every sample) took a third of a 0.3 s landing's 0.75 s; the solve does not read
    # it (thermal feedback acts inside the solve), so the features are the same without it
    series = evaluate(spec, t, q, v, skip=POST_NOT_NEEDED)
    chans = {}
    for b in spec.bearings:
        force, housing = rotor_force(series, b.name), housing_force(series, b.name)
        for ax, f, h in zip(("y", "z"), force, housing):
            chans[f"{b.name}_{ax}_m"] = (t, series[f"{b.name}_{ax}_m"])
            chans[f"{b.name}_force_{ax}_n"] = (t, f)
            chans[f"{b.name}_housing_force_{ax}_n"] = (t, h)
        chans[f"{b.name}_inner_race_speed_rpm"] = (t, series[f"{b.name}_race_speed_rpm"])
    chans["rotor_speed_rpm"] = (t, series["rotor_speed_rpm"])
    chans["axial_m"] = (t, series["axial_position_m"])
    if noise and realisations > 0:
        return [extract_features(_as_recorded(chans, noise, np.random.default_rng([seed, m])), clearance=clearance,
                                 t_drop=sc.amb.t_drop) for m in range(realisations)]
    measured = _as_recorded(chans, noise, np.random.default_rng(seed)) if noise else Measurement(chans)
    feats = extract_features(measured, clearance=clearance, t_drop=sc.amb.t_drop)
    return (feats, measured) if with_series else feats


def _as_recorded(chans: dict, noise: dict, rng) -> Measurement:
    """The model's channels (name -> (t, v)) as the record's logger gives them: its channels only,
    sampled at its rate with a random phase, its sensor noise added (``noise``: :func:`sensor_noise`
    with :data:`RATE_KEY` and :data:`CHANNELS_KEY`); ``rng`` draws the phase, then the noise."""
    noise = dict(noise)
    fs = noise.pop(RATE_KEY, None)
    channels = noise.pop(CHANNELS_KEY, None)
    if channels:
        # a drop taken as a record (a noise gate's member) has the record's channels only: until
        # session 44 it had every channel the model gives, so its gap counted
        # rows the record's gap cannot have (the contact force, which no sensor reads; an NDE
        # channel the record lacks). Against an unchanged gap that inflated the gate: 0.510
        # against 0.206 on the bench's strong contact damping, 4 records (the undamped model's
        # contact-force peak scatters 0.32 of its scale between drops, 0.07 with the damping)
        chans = {k: v for k, v in chans.items() if k in channels}
    if fs:
        # sampled as a record is: at the logger's rate, with a random phase against the drop and
        # one sample before it, so the features interpolate the noisy samples onto their grid from
        # the drop as they do a record's (partly averaging the noise). With the noise on that grid
        # itself, every extreme kept its full noise: three clean records' first rebounds read
        # 0.227-0.251 mm (noise-free 0.218), the gate's members 0.242-0.254 on the grid and
        # 0.234-0.243 sampled like this (session 20)
        chans = logger_samples(chans, fs, rng.uniform(0.0, 1.0))
    for name, sigma in sorted(noise.items()):
        if name in chans and sigma > 0:
            tt, vv = chans[name]
            chans[name] = (tt, vv + rng.normal(0.0, sigma, np.shape(vv)))
    return Measurement(chans)


def logger_samples(chans: dict, fs: float, phase: float) -> dict:
    """The channels (name -> (t, v), t from the drop) as a logger at ``fs`` Hz samples them: at
    ``phase`` (0-1) of a sample period after each grid instant, from one sample before the first
    (held at the first value), linearly interpolated."""
    out = {}
    for name, (tt, vv) in chans.items():
        tn = np.arange(tt[0] + (phase - 1.0) / fs, tt[-1], 1.0 / fs)
        out[name] = (tn, np.interp(tn, tt, vv))
    return out


def _sim_job(args):
    """One simulation in a worker: features, or the failure (a solver that does not converge at a
    trial parameter value is a bad trial, not a crash of the diagnosis)."""
    scenario_path, overrides, clearance, noise, seed, *more = args
    try:
        return _simulate_features(scenario_path, overrides, clearance, noise=noise, seed=seed,
                                  realisations=more[0] if more else 0)
    except Exception as exc:  # noqa: BLE001 - reported as a failed trial
        return {"__error__": f"{type(exc).__name__}: {exc}"}


class _Simulator:
    """Runs the simulations of every operating point of one model variant in a shared process
    pool. Overrides per simulation: the model's ``--set`` values, then the point's own values
    (its speed ...), then the candidate effect and its parameter."""

    def __init__(self, scenario_path, points: list[Point], clearance: float, workers: int, base: list[str],
                 ensemble: int = 1, ensemble_radius_m: float | None = None, records: int = 1,
                 as_recorded: dict | None = None, realisations: int = MODEL_REALISATIONS, scatter: bool = False):
        self.scenario_path, self.points, self.clearance, self.base = scenario_path, points, clearance, list(base)
        # the records' sensor model (sensor_noise with RATE_KEY, CHANNELS_KEY): the model's own drops
        # are compared as the records are, each landing read ``realisations`` times through it (its
        # noise, logger rate, random phase; seeds common to every variant) and its features the
        # mean of those reads. A noisy signal's extremes (a displacement's min / max, the first
        # rebound) lie beyond the noise-free signal's, so a noise-free model is biased against
        # every noisy record: the bench's clean 6 um control, four records, had a gap of 0.682
        # against the noise-free model and 0.122 (gate 0.925 -> 0.363) read like this (session 46,
        # docs/measured_data.md). With repeated records the model's drops also spread over the
        # disc the records fall from (ensemble.disc_drop_offsets), not on its rim
        self.as_recorded = as_recorded or None
        self.realisations = max(1, int(realisations))
        self.pool = Pool(workers, blas_threads=None)  # BLAS as before (runner.worker_setup says why)
        self.count = 0
        # > 1: every model variant is an ensemble of drops (from a 5 um circle; over its disc when
        # read as repeated records are) and its features are
        # the ensemble's statistics (features.ensemble_features), so the gap does not hinge on one
        # chaotic trajectory (issue 20, point 1)
        self.ensemble = ensemble
        self.radius = ensemble_radius_m
        # the number of measured records whose mean features are compared (:class:`Repeated`); the
        # noise gate's members are means of as many drops
        self.records = records
        # True: each feature of a variant also carries the scatter of its drops (and reads), added
        # to the feature's scale (features.ensemble_features' scatter_factor 1/records + 1/drops):
        # the gap then counts a difference in units of what this model's own chaos lets it scatter
        self.scatter = bool(scatter)
        # variants already landed, noise-free or read with fixed seeds (overrides -> features per
        # point): the solver is deterministic, so a variant asked for twice (the identifiability probes, then the same
        # values on a calibration's grid or a parameter's screening) is landed once
        self.memo: dict = {}

    def overrides(self, p: Point, extra: list[str]) -> list[str]:
        return self.base + list(p.overrides) + list(extra)

    def read_description(self) -> str:
        """What the model's features are, in words (the report's line)."""
        from .ensemble import DROP_RADIUS_M

        radius = 1e6 * (self.radius or DROP_RADIUS_M)
        drops = ("the centred drop" if self.ensemble <= 1 else
                 f"{self.ensemble} drops spread over the {radius:g} um disc" if self.as_recorded and self.records > 1
                 else f"{self.ensemble} drops from the {radius:g} um circle")
        if self.scatter:
            drops += " (each feature's scale widened by the drops' scatter)"
        if not self.as_recorded:
            return drops + ", noise-free"
        rate = self.as_recorded.get(RATE_KEY)
        return (f"{drops}, each read {self.realisations} times through the records' sensor model (their noise"
                + (f", their {rate:.0f} Hz logger with a random phase" if rate else "")
                + (", their channels" if self.as_recorded.get(CHANNELS_KEY) else "") + "), the mean of the reads")

    def features(self, extras: list[list[str]], noise=None, single: bool = False) -> list[list[dict]]:
        """Simulated features at every point for each model variant (all submitted at once);
        ``noise``: sensor noise added to the series (variant i seeded with i); ``single``: one drop
        per variant even in ensemble mode (the noise gate's members). Model variants (``noise``
        None: noise-free, or read with fixed seeds) landed before in this diagnosis come from
        :attr:`memo`."""
        if noise:
            return self._land(extras, noise, single)
        keys = [(tuple(e), single) for e in extras]
        todo = list(dict.fromkeys(k for k in keys if k not in self.memo))
        if todo:
            for k, sims in zip(todo, self._land([list(k[0]) for k in todo], None, single)):
                self.memo[k] = sims
        return [list(self.memo[k]) for k in keys]

    def _land(self, extras: list[list[str]], noise, single: bool) -> list[list[dict]]:
        from .ensemble import disc_drop_offsets, drop_offsets
        from .features import ensemble_features

        if not extras:
            return []
        radius = [self.radius] if self.radius else []
        members = [[]] if single or self.ensemble <= 1 else \
            disc_drop_offsets(self.ensemble, *radius) if self.as_recorded and self.records > 1 else \
            drop_offsets(self.ensemble, *radius)
        reads = noise is None and not single and bool(self.as_recorded)
        if reads:
            # the model's own drops, read as the records are; drop k at point j has the same seeds in
            # every variant, so a parameter's change is not mixed with a change of noise draws (and
            # the points' reads are drawn apart from each other)
            jobs = [(self.scenario_path, self.overrides(p, extra + off), self.clearance, self.as_recorded,
                     MODEL_READ_SEED + 1000 * j + k, self.realisations)
                    for extra in extras for j, p in enumerate(self.points) for k, off in enumerate(members)]
        else:
            jobs = [(self.scenario_path, self.overrides(p, extra + off), self.clearance, noise, i)
                    for i, extra in enumerate(extras) for p in self.points for off in members]
        self.count += len(jobs)
        out = self.pool.map(_sim_job, jobs, failures="raise")  # _sim_job turns a failed trial into its row
        k = len(members)
        if k > 1 or reads:  # the reads of one drop come as a list (a failed landing: its error row)
            grouped = [out[j * k:(j + 1) * k] for j in range(len(out) // k)]
            # a drop read several times contributes each read (as many per drop): the features are
            # the mean over drops and reads, the whirl shares over reads
            factor = 1.0 / max(1, self.records) + 1.0 / k if self.scatter else None
            out = [next((m for m in g if isinstance(m, dict) and "__error__" in m), None)
                   or ensemble_features([r for m in g for r in (m if isinstance(m, list) else [m])], factor)
                   for g in grouped]
        n = len(self.points)
        return [out[i * n:(i + 1) * n] for i in range(len(extras))]

    def gaps(self, extras: list[list[str]]):
        res = []
        for sims in self.features(extras):
            failed = [s["__error__"] for s in sims if "__error__" in s]
            if failed:
                res.append((float("inf"), [], sims, failed[0]))
                continue
            g, rows = gap_points([p.features for p in self.points], sims, [p.name for p in self.points])
            res.append((g, rows, sims, None))
        return res

    def gap(self, extra: list[str]):
        return self.gaps([extra])[0]

    def close(self):
        self.pool.close()


#: a user-given drop instant further than this from the detected one gets a warning (automatic
#: detection was good to about 0.3 ms on the issue-20 bench; a landing's features move within ms)
OFFSET_TOLERANCE_S = 2e-3


#: the key of a noise dict that carries the record's sampling rate (Hz), not a channel
RATE_KEY = "_sampling_rate_hz"
#: the record's channel names, beside its noise: a member drop is made of those channels only
CHANNELS_KEY = "_channels"


def records_sensor_model(noise: dict | None, rate: float | None = None, channels=None) -> dict | None:
    """The records' sensor model as the gate's members and the model's reads take it
    (:func:`_as_recorded`): the per-channel noise, with the logger's rate under :data:`RATE_KEY`
    (the members are sampled as the record was) and the record's channels under
    :data:`CHANNELS_KEY` (a member has the rows the record's gap has), each where known; a key
    already there is kept. No noise: None (the model is compared noise-free)."""
    if not noise:
        return None
    out = dict(noise)
    if rate and RATE_KEY not in out:
        out[RATE_KEY] = float(rate)
    if channels and CHANNELS_KEY not in out:
        out[CHANNELS_KEY] = tuple(channels)
    return out


def record_rate(m: Measurement) -> float | None:
    """The record's sampling rate (Hz): the median step of its DE vertical channel (else its first)."""
    if not m.channels:
        return None
    t, _ = m.channels.get("DE_z_m", next(iter(m.channels.values())))
    if len(t) < 3:
        return None
    dt = float(np.median(np.diff(np.asarray(t, float))))
    return 1.0 / dt if dt > 0 else None


def sensor_noise(m: Measurement) -> dict:
    """Per-channel sensor noise of a record, from the data: the robust spread of its second
    differences, MAD / 0.6745 / sqrt(6) (white noise of standard deviation s gives second
    differences of standard deviation sqrt(6) s; a smooth signal sampled fast gives almost none,
    and the median ignores the impacts)."""
    out = {}
    for name, (_, v) in m.channels.items():
        if len(v) >= 5:
            d2 = np.diff(np.asarray(v, float), 2)
            out[name] = float(np.median(np.abs(d2 - np.median(d2))) / 0.6745 / math.sqrt(6.0))
    return out


def measured_for_diagnosis(scenario_path, measured_path, sets: list[str], time_offset_s: float | None = None):
    """What ``rotorlanding diagnose`` compares the model with: (clearance of the scenario's DE
    bearing (else its first), the measurement, its features: one ``Point`` per operating point of a
    points file, a feature table, or features extracted from a record after its detected drop,
    info: the record's sensor noise (:func:`sensor_noise`) and, with a user-given time offset, the
    drop detected in the shifted record and the features with the detected drop instead).
    Every bad input is one InputError naming the file."""
    from .features import features_from_table
    from .measured import detect_drop, load_measurement
    from .scenario import load_scenario

    sc = load_scenario(scenario_path, sets)
    clearance = sc.bearings["DE"].clearance if "DE" in sc.bearings else next(iter(sc.bearings.values())).clearance
    m = load_measurement(measured_path, time_offset_s=time_offset_s or 0.0)
    info: dict = {}
    if m.points:
        meas = []
        for p in m.points:
            try:
                load_scenario(scenario_path, sets + p.overrides)
            except InputError as err:
                raise InputError(f"points.{p.name}.set", " ".join(p.overrides),
                                 f"not valid for {scenario_path}: {err.field} = {err.value!r}: {err.allowed}",
                                 file=measured_path) from None
            meas.append(Point(p.name, p.overrides, features_from_table(p.features, clearance,
                                                                        where=f"points.{p.name}.features",
                                                                        file=measured_path)))
    elif m.features:
        meas = features_from_table(m.features, clearance, file=measured_path)
    else:
        for name, (_, v) in m.channels.items():
            if name.endswith("_m") and name != "axial_m" and np.nanmax(np.abs(v)) > 5 * clearance:
                raise InputError(name, f"{np.nanmax(np.abs(v)):.3g} m", f"journal displacements beyond 5x the model's "
                                 f"clearance ({clearance:g} m): data from a different rotor, or not in metres?",
                                 file=measured_path)
        detected = detect_drop(m, clearance)
        t_drop = detected if time_offset_s is None else 0.0
        info["sensor_noise"] = sensor_noise(m)
        info["sampling_rate_hz"] = record_rate(m)
        info["channels"] = sorted(m.channels)
        if time_offset_s is not None and detected is not None:
            # the drop the data show, in the file's clock, against the one the user gave
            info["time_offset"] = {"given_s": time_offset_s, "detected_s": time_offset_s + detected,
                                   "difference_s": -detected}
            alt = m.shifted(detected)
            info["features_detected_offset"] = extract_features(alt, clearance=clearance, t_drop=0.0)
        m = m.shifted(t_drop or 0.0)
        span = max(float(t[-1]) for t, _ in m.channels.values())
        if span < 0.1:
            raise InputError("time_s", f"{span:.3g} s after the drop", "record too short: need >= 0.1 s after the drop",
                             file=measured_path)
        meas = extract_features(m, clearance=clearance, t_drop=0.0)
    return clearance, m, meas, info


def records_for_diagnosis(scenario_path, paths, sets: list[str], option: str = "--measured"):
    """Several records of repeated landings of one operating point, each read and its drop
    detected on its own (:func:`measured_for_diagnosis`): (clearance, the first record, a
    :class:`Repeated` of their features, info: the sensor noise per channel averaged over the
    records that have it). A feature table among them is one InputError naming it."""
    from pathlib import Path

    feats, noises, rates, channels, first = [], [], [], set(), None
    seen = set()
    for path in paths:
        key = Path(path).resolve()
        if key in seen:
            raise InputError(option, str(path), "given twice: repeated landings are different records", file=str(path))
        seen.add(key)
        clearance, m, meas, info = measured_for_diagnosis(scenario_path, path, sets, None)
        if not m.channels:
            raise InputError(option, str(path), "repeated landings must be records (time series); a feature table "
                             "or points file is a measurement on its own", file=str(path))
        first = first or m
        feats.append(meas)
        noises.append(info.get("sensor_noise", {}))
        rates.append(info.get("sampling_rate_hz"))
        channels |= set(info.get("channels", ()))
    noise = {k: float(np.mean([n[k] for n in noises if k in n])) for k in sorted(set().union(*noises))}
    rates = [r for r in rates if r]
    return clearance, first, Repeated(feats), {"sensor_noise": noise, "channels": sorted(channels),
                                               "sampling_rate_hz": float(np.median(rates)) if rates else None}


def _records_ensemble(records: int, ensemble: int, option: str = "ensemble") -> int:
    """The model's drops per variant with ``records`` repeated landings: as many as records
    (``ensemble`` 1), or more. More drops bring the model's features nearer its expectation, at
    that many times the landings: on the four-record bench a model of 4 drops is one draw of a
    chaotic landing, and with 16 the verdict of diagnose's rule on the true model changed in 4 of
    34 cases (docs/measured_data.md, session 47). Fewer drops than records would make the model
    noisier than the data it is compared with. (Until session 47 exactly as many were required:
    the gate's members then fell on the model's circle between its points; they are random
    points of the disc since session 21.)"""
    if ensemble != 1 and ensemble < records:
        raise InputError(option, ensemble, f"1 (as many drops as the {records} records) or at least {records}: "
                         "the model runs at least as many drops per variant as there are records")
    return records if ensemble == 1 else int(ensemble)


#: the journals whose per-journal features diagnose compares by default (``--journals``): the DE
#: only. The NDE's rows (features.OTHER_JOURNAL_ROWS) measured on the bench (docs/measured_data.md,
#: session 13) are opt-in
DEFAULT_JOURNALS = ("DE",)


def _journal_rows(features: dict, journals) -> dict:
    """The features without the per-journal rows of journals not in ``journals``."""
    others = [j + "_" for j in JOURNALS if j not in journals]
    return {k: v for k, v in features.items() if not any(k.startswith(o) for o in others)}


def _param_overrides(param, x):
    return [f"{k}={x!r}" for k in param.keys]


@dataclass
class Term:
    """One change of the model: an effect switched on with its fitted parameter values, or one of
    the scenario's uncertain parameters (a ``[bounds]`` key) moved within its bound."""

    kind: str                 # "effect" or "parameter"
    name: str                 # effect name or the bounds key
    params: tuple = ()        # effects.Parameter objects fitted
    values: dict = field(default_factory=dict)   # parameter name -> value

    def overrides(self) -> list[str]:
        out = [f"effects.{self.name}=true"] if self.kind == "effect" else []
        for p in self.params:
            if p.name in self.values:
                out += _param_overrides(p, self.values[p.name])
        return out


def _terms_overrides(terms, skip=None) -> list[str]:
    out = []
    for t in terms:
        if t is skip:
            out += [f"effects.{t.name}=true"] if t.kind == "effect" else []
        else:
            out += t.overrides()
    return out


def _fit_1d(sim: _Simulator, fixed: list[str], p, maxiter: int, cache: dict | None = None,
            grid_points: int = GRID_POINTS) -> dict:
    """Fit one parameter on the joint gap with everything in ``fixed`` held: a grid of
    ``GRID_POINTS`` over its bounds (one parallel batch; points already in ``cache`` are reused),
    then a bounded search between the neighbours of the best grid value."""
    to_x = (lambda u: 10 ** u) if p.log else (lambda u: u)
    lo, hi = (math.log10(p.lower), math.log10(p.upper)) if p.log else (p.lower, p.upper)
    cache = dict(cache or {})

    def objective(u):
        x = float(to_x(u))
        g, rows, sims, err = sim.gap(fixed + _param_overrides(p, x))
        cache[float(u)] = (g, rows, x, sims)
        return g if math.isfinite(g) else 1e9

    grid = [float(u) for u in np.linspace(lo, hi, grid_points)]
    todo = [u for u in grid if u not in cache]
    for u, (g, rows, sims, err) in zip(todo, sim.gaps([fixed + _param_overrides(p, float(to_x(u))) for u in todo])):
        cache[u] = (g, rows, float(to_x(u)), sims)
    k = int(np.argmin([cache[u][0] for u in grid]))
    a, b = grid[max(k - 1, 0)], grid[min(k + 1, grid_points - 1)]
    if maxiter > 0:
        minimize_scalar(objective, bounds=(a, b), method="bounded", options={"maxiter": maxiter, "xatol": 1e-3})
    u_best = min(cache, key=lambda u: cache[u][0])
    g, rows, x, sims = cache[u_best]
    return {"gap": g, "rows": rows, "x": x, "sims": sims, "evaluations": len(cache), "cache": cache}


def fit_span(cache: dict, member_gaps: list[float], z: float | None = None) -> dict | None:
    """The fit's own uncertainty, as far as its evaluated values show it (issue 20, point 1: "a
    calibration that reports its own uncertainty"): the values whose gap lies within ``z``
    standard deviations of the noise members' gaps above the best gap. Those the data cannot rank
    against the best, as a record's noise and drop point alone move a gap by about that much
    (like calibrate's ``within_noise`` and with its NOISE_Z = 2, but with the members' scatter as
    the gap's noise where calibrate has each score's standard error). ``cache``: a
    :func:`_fit_1d` cache (search variable -> (gap, rows, value, sims)). The values within are
    grouped into ranges of neighbours among the evaluated values, sorted: more than one range
    means separate dips, so the value is not one basin's minimum and the data do not fix it
    (the four-record bench's mu_rad 0.3: dips at 0.19, 0.25 and 0.30, docs/measured_data.md,
    session 47). None without two finite member gaps or two finite evaluated gaps. Values are the
    parameter's own (not the search variable of a log parameter)."""
    if z is None:
        from .calibrate_run import NOISE_Z as z
    members = [g for g in member_gaps if math.isfinite(g)]
    pts = sorted((float(x), float(g)) for g, _, x, _ in cache.values() if math.isfinite(g))
    if len(members) < 2 or len(pts) < 2:
        return None
    margin = z * float(np.std(members, ddof=1))
    best_x, best = min(pts, key=lambda t: t[1])
    runs, start = [], None   # index ranges of neighbours within
    for i, (_, g) in enumerate(pts):
        if g <= best + margin:
            start = i if start is None else start
        elif start is not None:
            runs.append((start, i - 1))
            start = None
    if start is not None:
        runs.append((start, len(pts) - 1))
    ranges = [[pts[a][0], pts[b][0]] for a, b in runs]
    # the values evaluated show the span only to their spacing: between a range's end and the
    # nearest value that fits worse the data are silent, so the truth may lie up to that value
    # (its bracket; a grid of 5 over a friction coefficient's 0.04-0.8 is 0.19 apart)
    brackets = [[pts[max(a - 1, 0)][0], pts[min(b + 1, len(pts) - 1)][0]] for a, b in runs]
    return {"best": best_x, "gap": best, "margin": margin, "z": z, "ranges": ranges, "brackets": brackets,
            "within": sum(g <= best + margin for _, g in pts), "evaluated": len(pts),
            # a range that reaches the lowest or highest value evaluated (a grid's: the bound) is
            # open on that side: the data would allow values beyond it
            "open_low": ranges[0][0] == pts[0][0], "open_high": ranges[-1][1] == pts[-1][0]}


def _calibrate(sim: _Simulator, name: str, terms: list[Term], maxiter: int) -> dict:
    """Switch one effect on (with everything named so far) and fit its parameters on the gap over
    all points (one after the other, each bounded). An effect the scenario cannot take (e.g.
    unbalance without an [unbalance] table) comes back with gap = inf and the reason."""
    eff = CATALOGUE[name]
    current = _terms_overrides(terms)
    on = current + [f"effects.{name}=true"]
    reason = _not_applicable(sim, on, eff)
    if reason:
        return {"effect": name, "kind": "effect", "gap": float("inf"), "parameters": {}, "rows": [], "k": 0,
                "not_applicable": reason}
    if not eff.parameters:
        g, rows, sims, err = sim.gap(on)
        return {"effect": name, "kind": "effect", "gap": g, "parameters": {}, "rows": rows, "k": 0, "sims": sims,
                "directions": _directions(sims), "term": Term("effect", name), **({"failed": err} if err else {})}
    # every parameter of the effect, jointly (issue 20, point 4): the first over its bounds with the
    # others at their scenario values, then one round of coordinate descent over the others with the
    # first held, each bounded; k counts them all, so a second freedom must pay for itself
    p = eff.parameters[0]
    fit = _fit_1d(sim, on, p, maxiter)
    null_fit = {"fixed": on, "param": p, "cache": fit["cache"], "grid_points": GRID_POINTS, "gap": fit["gap"]}
    term = Term("effect", name, tuple(eff.parameters), {p.name: fit["x"]})
    best, evaluations = fit, fit["evaluations"]
    for q in eff.parameters[1:]:
        fq = _fit_1d(sim, on + term.overrides()[1:], q, maxiter)
        evaluations += fq["evaluations"]
        if fq["gap"] < best["gap"]:
            term.values[q.name] = fq["x"]
            best = fq
    return {"effect": name, "kind": "effect", "gap": best["gap"], "parameters": dict(term.values), "rows": best["rows"],
            "k": len(eff.parameters), "directions": _directions(best["sims"]), "evaluations": evaluations,
            "sims": best["sims"], "term": term, "null_fit": null_fit}


#: the scenario's uncertain parameters diagnose tries by default (when the scenario has a
#: ``[bounds]`` entry for them), with why each can mimic a missing effect; ``--parameters`` gives
#: others (any [bounds] key)
DEFAULT_PARAMETERS = {
    "bearings.DE.clearance": "sets the landing depth, the orbit radius and the impact speed at the DE",
    "bearings.NDE.clearance": "as bearings.DE.clearance, at the NDE",
    "rotor.disks.3.mass": "the overhung coupling hub: bearing loads, forces and the rotor's modes",
    "bearings.DE.k_rib": "ribbon stiffness: rebound, force peaks and whirl frequency at the DE",
    "bearings.DE.inner_race_mass": "inertia of the race the journal hits: rebound and spin-up",
    "contact.mu_rad": "radial friction: race spin-up, sideways kick, whirl onset",
}
#: parameters calibrated in full after screening (every parameter either side of its value, one
#: batch): all six defaults. With 2, a clearance of 2.6e-4 for 2e-4 was screened out (its features
#: move by 5 scales per 1e-4 step, so both screening points looked no better than the model)
PARAMETER_FITS = 6
#: grid of a parameter's calibration: finer than an effect's (5): a displacement-setting parameter
#: moves features by many scales across its bound (the DE clearance's gap is a V 0.3e-4 wide over a
#: 1e-4-5e-4 bound: 1.84 at 2e-4, 0.09 at the true 2.6e-4, 1.86 at 3e-4)
PARAMETER_GRID_POINTS = 9


def _parameter(key: str, bound):
    from .effects import Parameter

    return Parameter(key, (key,), bound.min, bound.max, bound.log)


SCREEN_STEP = 0.25


def _screen_points(p, value) -> list[float]:
    """Where a parameter is screened: a quarter of its bound's span either side of its value (on a
    log axis for a log parameter), clipped to the bound; the bounds themselves when the value is
    unknown. Not at the bounds: a landing's features are far from linear in a parameter, and a
    clearance of 2.6e-4 for 2e-4 looked worse at both 1e-4 and 5e-4 than the model as it is."""
    lo, hi = (math.log10(p.lower), math.log10(p.upper)) if p.log else (p.lower, p.upper)
    if value is None or not (p.lower <= value <= p.upper) or (p.log and value <= 0):
        return [p.lower, p.upper]
    u = math.log10(value) if p.log else value
    pts = [min(max(u + s * SCREEN_STEP * (hi - lo), lo), hi) for s in (-1.0, 1.0)]
    return [float(10 ** x) if p.log else float(x) for x in pts]


def _parameter_candidates(sim: _Simulator, base, keys, terms: list[Term], maxiter: int, current: dict) -> list[dict]:
    """Screen the uncertain parameters (each a quarter of its span either side of its value, one
    parallel batch: :func:`_screen_points`), then calibrate the ``PARAMETER_FITS`` that came
    closest over their whole bound; the others are reported with their screening gap."""
    fixed = _terms_overrides(terms)
    params = [_parameter(k, base.bounds[k]) for k in keys]
    if not params:
        return []
    extras, where = [], []
    for p in params:
        for x in _screen_points(p, current.get(p.name)):
            extras.append(fixed + _param_overrides(p, x))
            where.append((p, x))
    screened = {p.name: {} for p in params}
    for (p, x), (g, rows, sims, err) in zip(where, sim.gaps(extras)):
        u = float(math.log10(x) if p.log else x)  # the search variable of _fit_1d
        screened[p.name][u] = (g, rows, x, sims)
    order = sorted(params, key=lambda p: min(v[0] for v in screened[p.name].values()))
    out = []
    for i, p in enumerate(order):
        null_fit = None
        if i < PARAMETER_FITS:
            fit = _fit_1d(sim, fixed, p, maxiter, cache=screened[p.name], grid_points=PARAMETER_GRID_POINTS)
            null_fit = {"fixed": fixed, "param": p, "cache": fit["cache"], "grid_points": PARAMETER_GRID_POINTS,
                        "gap": fit["gap"]}
        else:
            u, (g, rows, x, sims) = min(screened[p.name].items(), key=lambda kv: kv[1][0])
            fit = {"gap": g, "rows": rows, "x": x, "sims": sims, "evaluations": 2}
        out.append({"effect": p.name, "kind": "parameter", "gap": fit["gap"], "parameters": {p.name: fit["x"]},
                    "from": current.get(p.name), "bound": [p.lower, p.upper], "rows": fit["rows"], "k": 1,
                    "directions": _directions(fit["sims"]), "evaluations": fit["evaluations"], "sims": fit["sims"],
                    "screened_only": i >= PARAMETER_FITS, "term": Term("parameter", p.name, (p,), {p.name: fit["x"]}),
                    "null_fit": null_fit})
    return out


def _lacking(base, named: list[str], candidates) -> list[str]:
    """The effects a step may add: switched off in the model, in the catalogue, not named yet, and
    among ``candidates`` when given; faults (a worn bearing) only on request, as a healthy rig's gap
    is not a fault."""
    return [n for n, on in base.effects.items() if not on and n in CATALOGUE and n not in named
            and (n in candidates if candidates else not CATALOGUE[n].fault)]


def _identifiability(sim: _Simulator, sims0: list[dict], base, effects: list[str], keys: list[str],
                     current: dict, gate: float, gap_before: float) -> dict:
    """Which candidates the channels given can tell apart, before calibrating
    (:mod:`rotorlanding.identifiability`). Each effect is landed at the top of its first
    parameter's range (the strongest the catalogue allows: an effect not seen there is not seen
    at all), each parameter at both its screening points (the larger change counts): the values
    step one's calibration grid and screening land, so with the simulator's memo the probes cost
    no landing of their own."""
    probes, extras, owner = [], [], []
    for name in effects:
        eff = CATALOGUE[name]
        on = [f"effects.{name}=true"]
        reason = _not_applicable(sim, on, eff)
        if reason:
            probes.append({"name": name, "kind": "effect", "at": {}, "failed": f"not applicable: {reason}"})
            continue
        extra, at = on, {}
        if eff.parameters:
            p = eff.parameters[0]
            lo, hi = (math.log10(p.lower), math.log10(p.upper)) if p.log else (p.lower, p.upper)
            u = [float(u) for u in np.linspace(lo, hi, GRID_POINTS)][-1]  # _fit_1d's grid, its top
            x = float(10 ** u) if p.log else u
            extra, at = on + _param_overrides(p, x), {p.name: x}
        probes.append({"name": name, "kind": "effect", "at": at})
        extras.append(extra)
        owner.append((len(probes) - 1, at))
    for k in keys:
        p = _parameter(k, base.bounds[k])
        probes.append({"name": k, "kind": "parameter", "at": {}, "from": current.get(k)})
        for x in _screen_points(p, current.get(k)):
            extras.append(_param_overrides(p, x))
            owner.append((len(probes) - 1, {k: x}))
    names = [pt.name for pt in sim.points]
    measured = [pt.features for pt in sim.points]
    for (i, at), sims in zip(owner, sim.features(extras)):
        probe = probes[i]
        failed = [x["__error__"] for x in sims if "__error__" in x]
        if failed:
            probe.setdefault("failed", failed[0])
            continue
        change, sig = signature(sims0, sims, measured, names)
        if change > probe.get("change", -1.0):
            probe.update(change=change, signature=sig, at=at)
    for probe in probes:
        if "change" in probe:  # one screening point landed: the probe stands on it
            probe.pop("failed", None)
    return assess(probes, gate, gap_before)


def _not_applicable(sim: _Simulator, on: list[str], eff) -> str | None:
    """Why the scenario cannot take the effect switched on (e.g. unbalance without an [unbalance]
    table), or None. An effect whose only missing input is the parameter its fit supplies (the
    worn drag torque) is applicable: probed again with it."""
    from .scenario import load_scenario

    probes = [on] + ([on + _param_overrides(eff.parameters[0], eff.parameters[0].lower)] if eff.parameters else [])
    first_error = None
    for probe in probes:
        try:
            for p in sim.points:
                load_scenario(sim.scenario_path, sim.overrides(p, probe))
            return None
        except InputError as err:
            first_error = first_error or err
    return str(first_error)


def _refit(sim: _Simulator, terms: list[Term], maxiter: int, start: dict) -> dict:
    """Re-fit every parameter of the named terms jointly: one round of coordinate descent (each
    parameter in turn with the others held at their latest values), starting from ``start``
    (gap, rows, sims of the terms as they are). Returns the best state and the values."""
    best = dict(start)
    for t in terms:
        for p in t.params:
            # a parameter without a value kept its scenario value (its fit did not lower the gap)
            fixed = _terms_overrides(terms, skip=t) + [o for q in t.params if q is not p and q.name in t.values
                                                      for o in _param_overrides(q, t.values[q.name])]
            fit = _fit_1d(sim, fixed, p, maxiter)
            if fit["gap"] < best["gap"]:
                t.values[p.name] = fit["x"]
                best = {"gap": fit["gap"], "rows": fit["rows"], "sims": fit["sims"]}
    return best


def _joint_refit(sim: _Simulator, terms: list[Term], r: dict, maxiter: int) -> None:
    """Re-fit the terms named so far jointly with candidate ``r`` (:func:`_refit`, starting from
    its greedy fit); ``r`` takes the joint state when it is better, and ``r["refit"]`` records both gaps."""
    trial = [Term(t.kind, t.name, t.params, dict(t.values)) for t in terms] + [r["term"]]
    before = r["gap"]
    state = _refit(sim, trial, maxiter, {"gap": r["gap"], "rows": r["rows"], "sims": r["sims"]})
    r["refit"] = {"gap_before_refit": before, "gap_after_refit": state["gap"],
                  "values": {t.name: dict(t.values) for t in trial}}
    if state["gap"] < before:
        r["gap"], r["rows"] = state["gap"], state["rows"]
        r["directions"], r["sims"] = _directions(state["sims"]), state["sims"]
        r["refit_terms"] = trial
        r["parameters"] = dict(r["term"].values)


#: the directed test's level: the data's shrink must lie below the one-sided 95 % lower
#: prediction bound of the noise members' shrinks (as the gate's upper bound, :func:`gate_bound`)
DIRECTED_LEVEL = 0.95
# the seed of the noise gate's drop points (random within the disc, as records are)
MEMBER_SEED = 21


def directed_bound(shrinks: list[float], candidates: int = 1) -> float:
    """The lower prediction bound of one more member's shrink (fitted gap / gap before),
    mean - t(level, k-1) sqrt(1 + 1/k) s (:func:`_prediction_half_width`), at most their smallest;
    0 (nothing passes) with fewer than 2. ``level`` is ``DIRECTED_LEVEL`` Bonferroni-corrected for
    the ``candidates`` the tested one was chosen from, 1 - (1 - DIRECTED_LEVEL) / candidates: the
    data's candidate is the best of the step's, while each member fits that one only, so without the
    correction some candidate of noise data passes far more often than 5 % of the time
    (tests/test_diagnose_directed.py measures both rates)."""
    if len(shrinks) < 2:
        return 0.0
    level = 1.0 - (1.0 - DIRECTED_LEVEL) / max(1, int(candidates))
    return min(float(np.mean(shrinks)) - _prediction_half_width(shrinks, level), min(shrinks))


def _directed_test(sim: _Simulator, cand: dict, members: list, current_gap: float, maxiter: int,
                   candidates: int = 1) -> dict:
    """Is the candidate's shrink of the gap more than fitting it to noise gives? The gate asks
    whether the model as it is fits the data within noise (an omnibus question); this asks whether
    one named direction of change fits them better than it fits noise (a directed one, with more
    power where the gap is inside the gate). Each noise member (the current model dropped off
    centre with the record's noise, the gate's ``member_sims``, against which its gap ``g0`` was
    taken) plays the data: the candidate's first parameter is fitted to it exactly as to the data
    (the same grid, its landings reused, then the bounded search), and its shrink is the fitted gap
    over g0. The data's shrink is that same 1-D fit's gap over the current gap (before any joint
    re-fit, so data and members get the same freedom). Passed when the data's shrink lies below
    :func:`directed_bound` of the members' shrinks, corrected for the ``candidates`` it was the best
    of."""
    nf = cand.get("null_fit")
    if not nf or not members or not current_gap > 0:
        return {"passed": False, "why": "no 1-D fit or no members"}
    names = [p.name for p in sim.points]
    shrinks = []
    for feats, g0 in members:
        if not (math.isfinite(g0) and g0 > 0):
            continue
        # the member as the measurement, with the features the data have (no more)
        feats = [{k: v for k, v in f.items() if k in p.features} for f, p in zip(feats, sim.points)]
        msim = copy.copy(sim)
        msim.points = [replace(p, features=f) for p, f in zip(sim.points, feats)]
        cache = {}
        for u, (g, rows, x, sims) in nf["cache"].items():
            if any("__error__" in s_ for s_ in sims):
                cache[u] = (float("inf"), [], x, sims)
            else:
                gm, rm = gap_points(feats, sims, names)
                cache[u] = (gm, rm, x, sims)
        fit = _fit_1d(msim, nf["fixed"], nf["param"], maxiter, cache=cache, grid_points=nf["grid_points"])
        sim.count = msim.count  # the copy counted on from the shared total
        if math.isfinite(fit["gap"]):
            shrinks.append(fit["gap"] / g0)
    data = nf["gap"] / current_gap
    bound = directed_bound(shrinks, candidates)
    return {"passed": bool(data < bound), "shrink": data, "member_shrinks": shrinks, "bound": bound,
            "candidates": candidates, "parameter": nf["param"].name}


def above_gate(current_gap: float, gate: float, produced: list, score: float, base_score: float) -> bool:
    """A step's best candidate is considered at all when the gap it starts from is above the noise
    gate (or it produces a feature the data show and noise cannot) and its score beats the model
    as it is by more than 2 units (the score charges each added freedom log n)."""
    return (current_gap > gate or bool(produced)) and score < base_score - 2.0


def named_by(above: bool, relative: bool, direction_fixed: bool, best_gap: float, own_gate: float | None,
             current_gap: float, gate: float, directed: bool = False) -> str | None:
    """Why a step's best candidate is named, or None. Beyond :func:`above_gate`, one of: the gap
    falls by ``MIN_STEP_IMPROVEMENT`` or more; the candidate makes a whirl direction right and
    breaks none; or (repeated records only: ``own_gate`` is None otherwise) what it leaves is
    inside its own noise gate, and that gate is below the gap it started from, so a candidate that
    makes the landing wilder cannot explain a gap by its own scatter."""
    if not above:
        return None
    within_own = own_gate is not None and best_gap <= own_gate < current_gap
    if relative:
        why = "relative improvement"
    elif direction_fixed:
        why = "whirl direction"
    elif within_own:
        why = "the remainder inside the candidate's own noise gate"
    else:
        return None
    return why + ("" if current_gap > gate else ", more than fitting it to noise gives" if directed
                  else ", a feature noise cannot produce")


def whirl_direction_fixed(points, measured, before, after, noise_directions) -> tuple[list[str], list[str]]:
    """Points where a candidate makes the whirl direction right (measured, not before, after), and
    those of them where some off-centre drop of the noise gate (``noise_directions``: per member,
    the direction per point) already whirls as measured. Only the first count for the naming rule:
    at the others the direction is the chaos of the landing, not a regime the candidate brings.
    Measured on the paper's Table 2 (issue 20): the rig's 3000 rpm DE whirl is forward in 3 of the
    4 gate drops and none in the centred one; a 1 kg coupling hub (the bound's minimum) turned the
    centred drop forward and was named at 27 % shrink, though on 8 drops it breaks the DE forward
    whirl at 7000 rpm (8 -> 5 of 8) and 10000 rpm (8 -> 1 of 8)."""
    fixed, by_noise = [], []
    for i, (p, m, b, a) in enumerate(zip(points, measured, before, after)):
        if m is None or b == m or a != m:
            continue
        if any(i < len(d) and d[i] == m for d in noise_directions):
            by_noise.append(p.name or "record")
        else:
            fixed.append(p.name or "record")
    return fixed, by_noise


def _directions(sims: list[dict]) -> list:
    return [s.get("whirl_direction", (None,))[0] for s in sims]


def _row_key(r) -> str:
    return f"{r['point']}:{r['feature']}" if r.get("point") else r["feature"]


def decisive_features(rows_before: list[dict], rows_after: list[dict], n: int = 3) -> list[dict]:
    """The features that carry the decision (issue 20, point 7): the rows whose weighted squared
    distance fell the most between the model as it is and the diagnosed model, each with its share
    of the whole fall of sum w d^2 (the gap is the RMS of these rows, so the shares say which
    channels the named change was chosen on). Empty when nothing fell."""
    after = {_row_key(r): r for r in rows_after}
    falls = []
    for r in rows_before:
        a = after.get(_row_key(r))
        if a is None:
            continue
        fall = r["weight"] * r["distance"] ** 2 - a["weight"] * a["distance"] ** 2
        falls.append((fall, r, a))
    total = sum(f for f, _, _ in falls if f > 0)
    if total <= 0:
        return []
    top = sorted((x for x in falls if x[0] > 0), key=lambda x: -x[0])[:n]
    return [{"point": r.get("point"), "feature": r["feature"], "distance_before": r["distance"],
             "distance_after": a["distance"], "share": f / total} for f, r, a in top]


def _absent_in_model(rows) -> list[str]:
    return [_row_key(r) for r in rows if r.get("absent_in") == "model"]


def _current_values(base, keys) -> dict:
    from .scenario import get_dotted

    out = {}
    for k in keys:
        try:
            out[k] = float(get_dotted(base.raw, k))
        except Exception:  # noqa: BLE001 - a key the scenario resolves elsewhere: no "from" value
            out[k] = None
    return out


#: the model's drops per variant against one time record when ``ensemble`` is left out (session 51).
#: On the bench's one-record cases 4 drops gave 23 / 34 right with the 7 clean controls quiet, one drop
#: 20 / 34 with a false alarm (clean 2 um); a one-point, one-effect case takes 106-161 s on one core
#: (docs/measured_data.md, sessions 50-51)
RECORD_DROPS = 4


def ensemble_default(ensemble: int | None, measured, info: dict | None = None) -> int:
    """``diagnose``'s ``ensemble`` as given, or for None: :data:`RECORD_DROPS` against one time
    record (a :class:`Measurement`, or the features :func:`measured_for_diagnosis` extracted from one,
    known by its ``info``'s channels), 1 otherwise: repeated records then get as many drops as records
    (:func:`_records_ensemble`), and a feature table's numbers, one landing's each, one drop per point,
    as the paper's tables were validated."""
    if ensemble is not None:
        return ensemble
    one_record = isinstance(measured, Measurement) or isinstance(measured, dict) and bool((info or {}).get("channels"))
    return RECORD_DROPS if one_record else 1


def scatter_default(scatter_scales: bool | None, ensemble: int) -> bool:
    """``diagnose``'s ``scatter_scales`` as given, or for None: on when each model variant runs more
    than one drop (``ensemble``, already raised to the records' number for repeated records)."""
    if scatter_scales is not None:
        return bool(scatter_scales)
    # the model's own chaos is measured only where it drops more than once (one drop's only scatter is
    # the reads' noise); on the bench (docs/measured_data.md, sessions 48-49) it gave 21 / 34 against 19
    # with one record and 4 drops, 22 against 21 with four records, the clean controls 7 / 7 quiet in both
    return ensemble > 1


def diagnose(measured, scenario_path, *, clearance: float, candidates=None, max_effects: int = 1,
             min_improvement: float = MIN_STEP_IMPROVEMENT, noise_gap: float | None = None, workers: int = 2,
             maxiter: int = 10, t_drop: float = 0.0, base_overrides: list[str] | None = None,
             parameters: list[str] | None = None, noise_members: int = NOISE_MEMBERS,
             sensor_noise_sigma: dict | None = None, refit: bool = True, info: dict | None = None,
             ensemble: int | None = None, ensemble_radius_m: float | None = None, journals=DEFAULT_JOURNALS,
             directed: bool = False, as_recorded: bool = True, scatter_scales: bool | None = None) -> dict:
    """``measured``: a Measurement (channels), a feature dict (one point: the scenario as it is),
    :class:`Repeated` (the features of several records of one point: compared as their means, the
    model then an ensemble of as many drops unless ``ensemble`` > 1 says otherwise) or a list of
    :class:`Point` (one per operating point, each with its scenario overrides).
    ``base_overrides``: ``--set`` changes of the model (e.g. ``effects.axial_rub=false``).
    ``parameters``: [bounds] keys tried as "wrong parameter" candidates (None: the defaults of
    :data:`DEFAULT_PARAMETERS` the scenario bounds; [] none). ``noise_gap``: None estimates the
    gate from ``noise_members`` drops of the model (:func:`_noise_gate`); a number is used as is.
    ``info``: from :func:`measured_for_diagnosis` (sensor noise, time-offset check).
    ``journals``: whose per-journal features are compared (the whirl rows are the DE's); a
    measured feature of another journal is left out, in the gap and in the noise gate alike.
    ``directed``: where the gap is inside the gate, a candidate that shrinks it may still be named
    when it shrinks it more than fitting it to the gate's noise members does (:func:`_directed_test`).
    ``as_recorded``: the model's drops are read through the records' sensor model (their noise,
    logger rate and channels, where known) as the records were (:class:`_Simulator`); False: the
    noise-free model (diagnose until session 46). ``scatter_scales``: every feature is charged in
    units of its scale and the model variant's own scatter over its drops and reads together
    (:data:`features.SCATTER`, session 48); None (the default, session 50): on whenever the model
    runs more than one drop per variant (``ensemble`` > 1 or repeated records), where the drops'
    scatter is measured; off for one drop, whose only scatter would be the reads' noise.
    ``ensemble``: drops per model variant; None (the default, session 51): :func:`ensemble_default`,
    4 against one time record, as many as the records of repeated landings, 1 per point of a
    feature table."""
    from .scenario import load_scenario

    t_start = time.perf_counter()
    info = dict(info or {})
    ensemble = ensemble_default(ensemble, measured, info)
    base_overrides = list(base_overrides or [])
    records = 1
    if isinstance(measured, Repeated):
        from .features import ensemble_features

        records = len(measured.features)
        points = [Point("", [], ensemble_features(measured.features))]
        ensemble = _records_ensemble(records, ensemble)
    elif isinstance(measured, list):
        points = measured
    else:
        if isinstance(measured, Measurement) and sensor_noise_sigma is None:
            sensor_noise_sigma = sensor_noise(measured)
        meas = measured if isinstance(measured, dict) else extract_features(measured, clearance=clearance,
                                                                              t_drop=t_drop)
        points = [Point("", [], meas)]
    points = [replace(p, features=_journal_rows(p.features, journals)) for p in points]
    scatter_scales = scatter_default(scatter_scales, ensemble)
    if sensor_noise_sigma is None:
        sensor_noise_sigma = info.get("sensor_noise")
    rate = info.get("sampling_rate_hz") or (record_rate(measured) if isinstance(measured, Measurement) else None)
    channels = info.get("channels") or (sorted(measured.channels) if isinstance(measured, Measurement) else None)
    sensor_noise_sigma = records_sensor_model(sensor_noise_sigma, rate, channels)
    base = load_scenario(scenario_path, base_overrides)
    warnings_early = []
    lag_rows = sorted({k for p in points for k in p.features if k.endswith("_race_lag_s")})
    if lag_rows and base.t_end < base.amb.t_drop + RACE_LAG_WINDOW_S:
        # a model run that ends inside the lag's window has no lag to compare (features.race_lag):
        # left out of the data too, or it would be charged as a feature the model cannot produce
        points = [replace(p, features={k: v for k, v in p.features.items() if k not in lag_rows}) for p in points]
        warnings_early.append(f"{', '.join(lag_rows)} left out: the model's run ends at {base.t_end:g} s, "
                              f"within the lag's window of {RACE_LAG_WINDOW_S:g} s after the drop")
    if parameters is None:
        parameters = [k for k in DEFAULT_PARAMETERS if k in base.bounds]
    for k in parameters:
        if k not in base.bounds:
            raise InputError("--parameters", k, "not an uncertain parameter of the scenario; allowed: its [bounds] "
                             "keys: " + ", ".join(base.bounds), file=str(scenario_path))
    current_values = _current_values(base, parameters)
    sim = _Simulator(scenario_path, points, clearance, workers, base_overrides, ensemble=ensemble,
                     ensemble_radius_m=ensemble_radius_m, records=records,
                     as_recorded=sensor_noise_sigma if as_recorded else None, scatter=scatter_scales)
    terms: list[Term] = []
    named, steps, warnings = [], [], list(warnings_early)
    try:
        gap_before, rows_before, sims0, err = sim.gap([])
        if err:
            raise RuntimeError(f"the model as it is fails to simulate: {err}")
        directions_before = _directions(sims0)
        noise = _noise_gate(sim, sims0, noise_members, sensor_noise_sigma, journals=journals) if noise_gap is None else \
            {"gate": noise_gap, "source": "given", "member_gaps": []}
        gate = noise["gate"]
        noise_history = [gate]
        offset = info.get("time_offset")
        if offset is not None and "features_detected_offset" in info:
            g_det, _ = gap_points([info["features_detected_offset"]], [sims0[0]], [points[0].name])
            offset["gap_given"], offset["gap_detected"] = gap_before, g_det
            worse = gap_before > g_det
            far = abs(offset["difference_s"]) > OFFSET_TOLERANCE_S
            if worse or far:
                warnings.append(f"the given --time-offset-s {offset['given_s']:g} s is "
                                f"{1e3 * offset['difference_s']:+.1f} ms from the drop detected in the data "
                                f"({offset['detected_s']:.6g} s); the model as it is fits the given offset with gap "
                                f"{gap_before:.3f}, the detected one with {g_det:.3f}"
                                + (": the given offset fits worse" if worse else ""))
        # which candidates the channels can tell apart, said before any calibration (issue 20, point 8)
        ident = _identifiability(sim, sims0, base, _lacking(base, [], candidates), list(parameters), current_values,
                                 gate, gap_before)
        warnings += ident["warnings"]
        current_gap, current_rows, current_dirs = gap_before, rows_before, directions_before
        adjusted: list[str] = []
        step_gate, gate_now = gate, None   # gate_now: (overrides, _noise_gate) of the model named so far
        step_noise = noise                 # the noise gate the step is judged against (its members)
        step_se = noise.get("gate_se")      # ... and its standard error
        own = None                         # (overrides, _noise_gate) of the last step's best candidate
        for k_step in range(max_effects):
            lacking = _lacking(base, named, candidates)
            params_left = [k for k in parameters if k not in adjusted]
            if not lacking and not params_left:
                break
            if sim.pool is not None and len(lacking) > 1:
                with ThreadPoolExecutor(len(lacking)) as ex:
                    results = list(ex.map(lambda n: _calibrate(sim, n, terms, maxiter), lacking))
            else:
                results = [_calibrate(sim, n, terms, maxiter) for n in lacking]
            results += _parameter_candidates(sim, base, params_left, terms, maxiter, current_values)
            n = max(1, len(current_rows))

            def score(r):
                return (n * math.log(r["gap"] ** 2 + 1e-12) + r["k"] * math.log(n)) if math.isfinite(r["gap"]) \
                    else float("inf")

            if refit and terms:
                # the greedy fits held what was named before; every candidate is re-fitted jointly
                # with it before the ranking (forward stepwise selection: each candidate model with
                # all its numbers estimated). Re-fitting the best alone missed the bench's axial rub +
                # outer-race friction pair: mu_ax, fitted alone at step one, had taken up part of the
                # friction, so the friction on top of it made the gap worse (0.39 -> 0.44) and a
                # radial-friction coefficient won the step
                todo = [r for r in results if math.isfinite(r["gap"]) and r.get("term") is not None
                        and not r.get("screened_only")]
                if sim.pool is not None and len(todo) > 1:
                    with ThreadPoolExecutor(len(todo)) as ex:
                        list(ex.map(lambda r: _joint_refit(sim, terms, r, maxiter), todo))
                else:
                    for r in todo:
                        _joint_refit(sim, terms, r, maxiter)
            for r in results:
                r["score"] = score(r)
            results.sort(key=lambda r: r["score"])
            best = results[0]
            refit_info = best.get("refit")
            base_score = n * math.log(current_gap ** 2 + 1e-12)
            relative = best["gap"] <= (1 - min_improvement) * current_gap
            # a whirl direction made right at some point and broken at none is a qualitative gain
            # (the whirl regime), not something sensor noise or a parameter fit of noise produces
            meas_dirs = [p.features.get("whirl_direction", (None,))[0] for p in points]
            new_dirs = best.get("directions", [None] * len(points))
            fixed, by_noise = whirl_direction_fixed(points, meas_dirs, current_dirs, new_dirs,
                                                    noise.get("member_directions", []))
            broken = [p.name or "record" for p, m, b, a in zip(points, meas_dirs, current_dirs, new_dirs)
                      if m is not None and b == m and a != m]
            # a feature the data show that neither the model nor any of the gate's noisy off-centre
            # drops produces, and the candidate does produce, is not noise whatever the gap's size:
            # a model without radial friction is so chaotic (gate 2.1) that the race it never spins
            # up (charged 3) and the rotor it never brakes stayed below the gate (issue 20 bench)
            noise_cannot = set(_absent_in_model(current_rows)) - set(noise.get("member_features", []))
            produced = sorted(noise_cannot - set(_absent_in_model(best.get("rows", []))))
            if not math.isfinite(best["gap"]) or not noise["member_gaps"]:
                produced = []  # a given gate (no members to tell what noise produces) is the only gate
            above = above_gate(current_gap, step_gate, produced, best["score"], base_score)
            directed_info = None
            if directed and not above and noise_gap is None and relative and best["score"] < base_score - 2.0:
                # inside the gate: the directed test, against the members of the gate of the model
                # the step starts from
                members_now = (gate_now[1] if gate_now is not None else noise).get("member_sims", [])
                directed_info = _directed_test(sim, best, members_now, current_gap, maxiter,
                                               candidates=sum(math.isfinite(r["score"]) for r in results))
                above = directed_info["passed"]
            own = None
            if above and records > 1 and not relative and not (fixed and not broken) and noise_gap is None \
                    and best.get("term") is not None and math.isfinite(best["gap"]):
                # the candidate's own noise: where the true model's landing is itself chaotic (mu_rad
                # 0.3 for 0.15 on the bench, with repeated records: the fit found 0.303, the gap only
                # fell 24 % as the data's four drops and the model's four differ by chaos), what is
                # left may be no more than that model's scatter. Named when the remainder is inside
                # the candidate's own gate; its gate is estimated, like the others, from its drops
                trial = best.get("refit_terms") or terms + [best["term"]]
                own_fixed = _terms_overrides(trial)
                own = (own_fixed, _noise_gate(sim, best["sims"], noise_members, sensor_noise_sigma, own_fixed,
                                              journals=journals))
                noise_history.append(own[1]["gate"])
            significant_by = named_by(above, relative, bool(fixed) and not broken, best["gap"],
                                      own[1]["gate"] if own else None, current_gap, step_gate,
                                      directed=bool(directed_info and directed_info["passed"]))
            significant = significant_by is not None
            # the best of the other kind within 2 score units: the data do not tell them apart
            rival = next((r for r in results[1:] if r["kind"] != best["kind"] and math.isfinite(r["score"])), None)
            # what the best candidate's (first) parameter's 1-D fit cannot tell from its best value
            nf = best.get("null_fit")
            span = fit_span(nf["cache"], step_noise.get("member_gaps", [])) if nf and math.isfinite(best["gap"]) \
                else None
            if span:
                span["parameter"], span["keys"] = nf["param"].name, list(nf["param"].keys)
            keys = ("effect", "kind", "gap", "parameters", "from", "bound", "score", "directions", "evaluations",
                    "screened_only", "not_applicable", "failed", "rows", "refit")
            steps.append({"gap_before": current_gap, "base_score": base_score,
                          "candidates": [{k: r[k] for k in keys if k in r} for r in results],
                          "named_effect": best["effect"] if significant and best["kind"] == "effect" else None,
                          "named": best["effect"] if significant else None, "kind": best["kind"],
                          "relative_improvement": 1 - best["gap"] / current_gap
                          if math.isfinite(best["gap"]) and current_gap > 0 else 0.0,
                          "whirl_direction_fixed_at": fixed, "whirl_direction_broken_at": broken,
                          "whirl_direction_also_in_noise_at": by_noise,
                          "produces_absent_feature": produced,
                          "refit": refit_info,
                          "indistinguishable_from": rival["effect"] if rival and significant
                          and rival["score"] < best["score"] + 2.0 else None,
                          "gate": step_gate, "gate_margin": gate_margin(current_gap, step_gate, step_se),
                          "own_gate": own[1]["gate"] if own else None, "directed": directed_info,
                          "fit_span": span,
                          "significant_by": significant_by})
            if not significant:
                break
            if "refit_terms" in best:
                terms = best["refit_terms"]
            else:
                terms = terms + [best["term"]]
            if best["kind"] == "effect":
                named.append(best["effect"])
            else:
                adjusted.append(best["effect"])
            current_gap, current_rows, current_dirs, current_sims = best["gap"], best["rows"], best["directions"], \
                best["sims"]
            if noise_gap is None and k_step + 1 < max_effects:
                # the next step is judged against the smaller of the two gates: the model as given, and
                # the model with what is named so far. A model without radial friction is so chaotic
                # (gate 2.1) that the second effect of a pair stayed below its gate once radial friction
                # had tamed the landing (bench: windage + radial friction); the model as given keeps
                # its say where a first fit off the truth makes the landing wilder (mu_ax 0.42 for 0.3:
                # gate 1.12, which hid a second effect that took the gap 1.11 -> 0.33)
                fixed_now = _terms_overrides(terms)
                if own is not None and own[0] == fixed_now:
                    gate_now = own
                else:
                    gate_now = (fixed_now, _noise_gate(sim, current_sims, noise_members, sensor_noise_sigma, fixed_now,
                                                       journals=journals))
                    noise_history.append(gate_now[1]["gate"])
                step_gate = min(gate, gate_now[1]["gate"])
                step_noise = noise if step_gate == gate else gate_now[1]
                step_se = step_noise.get("gate_se")
        if terms and noise_gap is None:
            # what stays unexplained is judged against the gate of the final model: a landing with the
            # named changes can be more (or less) chaotic than without them. When the last step named
            # nothing, that model's gate is the one the step was judged against: not simulated again
            fixed_now = _terms_overrides(terms)
            if gate_now is not None and gate_now[0] == fixed_now:
                noise_final = gate_now[1]
            elif own is not None and own[0] == fixed_now:
                noise_final = own[1]
            else:
                noise_final = _noise_gate(sim, current_sims, noise_members, sensor_noise_sigma, fixed_now,
                                          journals=journals)
                noise_history.append(noise_final["gate"])
            final_gate = noise_final["gate"]
        else:
            noise_final, final_gate = None, gate
    finally:
        sim.close()
    effects_named = [t.name for t in terms if t.kind == "effect"]
    param_terms = [t for t in terms if t.kind == "parameter"]
    unexplained = bool(math.isfinite(current_gap) and current_gap > final_gate)
    largest = sorted(current_rows, key=lambda r: -r["distance"])[:3]
    decisive = decisive_features(rows_before, current_rows)
    if not terms:
        verdict = "none" if not unexplained else "unexplained"
    elif unexplained:
        verdict = "unexplained"
    else:
        verdict = "effect" if effects_named and not param_terms else "parameter" if param_terms and not effects_named \
            else "effect and parameter"
    return {"named_effect": effects_named[0] if effects_named else None, "named_effects": effects_named,
            "named_parameters": [{"key": t.name, "from": current_values.get(t.name), "to": t.values[t.name],
                                  "bound": [t.params[0].lower, t.params[0].upper],
                                  "source": base.bounds[t.name].source} for t in param_terms],
            "explanation": verdict, "unexplained": unexplained,
            "largest_remaining": [{"point": r.get("point"), "feature": r["feature"], "distance": r["distance"]}
                                  for r in largest],
            "decisive_features": decisive, "journals": list(journals),
            "records": records,
            "record_spread": _journal_rows(measured.spread, journals) if isinstance(measured, Repeated) else {},
            "noise": _public(noise), "noise_gate": gate, "noise_final": _public(noise_final),
            "noise_gate_final": final_gate,
            "gate_margins": {"before": gate_margin(gap_before, gate, noise.get("gate_se")),
                             "after": gate_margin(current_gap, final_gate,
                                                  (noise_final or noise).get("gate_se"))},
            "noise_gates": noise_history, "warnings": warnings, "time_offset": info.get("time_offset"),
            "identifiability": ident,
            # a name chosen among candidates the channels could not tell apart is a weaker statement
            "named_alike": {n: a for n in effects_named + [t.name for t in param_terms] if (a := alike_with(ident, n))},
            "absent_in_model_before": _absent_in_model(rows_before),
            "absent_in_model_after": _absent_in_model(current_rows),
            "gap_before": gap_before,
            "gap_after": current_gap, "features_before": rows_before, "features_after": current_rows,
            "calibrated_overrides": _terms_overrides(terms), "steps": steps,
            "fitted": {t.name: dict(t.values) for t in terms},
            "signatures": {n: CATALOGUE[n].signature for n in effects_named},
            "model_overrides": base_overrides,
            "points": [{"name": p.name, "overrides": p.overrides,
                        "whirl_measured": p.features.get("whirl_direction", (None,))[0],
                        "whirl_before": d0, "whirl_after": d1}
                       for p, d0, d1 in zip(points, directions_before, current_dirs)],
            "ensemble": ensemble, "scatter_scales": bool(scatter_scales), "model_read": sim.read_description(), "simulations": sim.count, "wall_s": round(time.perf_counter() - t_start, 1), "workers": workers}


def _public(noise: dict | None) -> dict | None:
    """A noise gate's record without the members' feature tables (kept for the directed test)."""
    return None if noise is None else {k: v for k, v in noise.items() if k != "member_sims"}


def gate_bound(gaps: list[float], floor: float = NOISE_GAP_MIN) -> float:
    """The noise gate from the gaps of the members (noise alone): the one-sided 95 % prediction
    bound of one more member gap, mean + t(0.95, k-1) sqrt(1 + 1/k) s (members taken as normal),
    at least their largest and ``floor``. Why a bound and not the largest: a chaotic landing spreads
    widely (without radial friction 0.16-1.44 over 6 drops of one model), and the largest of 4
    members (1.16 there) sits below a third of the noise gaps."""
    gate = max([floor] + list(gaps))
    if len(gaps) >= 2:
        gate = max(gate, float(np.mean(gaps)) + _prediction_half_width(gaps, 0.95))
    return gate


def gate_standard_error(gaps: list[float], floor: float = NOISE_GAP_MIN) -> float | None:
    """The standard error of the gate :func:`gate_bound` as an estimate, where it is the prediction
    bound G = m + c s (m, s the mean and standard deviation of k member gaps taken as normal,
    c = t(0.95, k-1) sqrt(1 + 1/k)): m and s are independent, Var m = sigma^2 / k and
    Var s = sigma^2 (1 - c4^2), so SE(G) = sigma sqrt(1/k + c^2 (1 - c4^2)), sigma estimated by s / c4
    (c4(k) = sqrt(2 / (k-1)) Gamma(k/2) / Gamma((k-1)/2), the bias of s). With 4 members it is
    1.14 sigma: the gate is itself a noisy number (session 21: it moved by -40 % to +62 % with the
    members' draw), so a gap within about one SE of it is a verdict that hangs on the draw. None
    where the gate is not the bound (fewer than 2 members, or set by the largest member or the floor)."""
    k = len(gaps)
    if k < 2:
        return None
    s = float(np.std(gaps, ddof=1))
    if s <= 1e-12 * max(1e-300, float(np.max(np.abs(gaps)))):
        return None
    bound = float(np.mean(gaps)) + _prediction_half_width(gaps, 0.95)
    if bound < max([floor] + list(gaps)):
        return None
    return prediction_bound_se(k, s)


def prediction_bound_se(k: int, s: float, level: float = 0.95) -> float:
    """The standard error of m + c s over k normal values of sample standard deviation ``s``
    (c = t(level, k-1) sqrt(1 + 1/k)), :func:`gate_standard_error`'s formula."""
    c = _prediction_factor(k, level)
    c4 = math.sqrt(2.0 / (k - 1)) * math.exp(math.lgamma(k / 2) - math.lgamma((k - 1) / 2))
    return float(s / c4 * math.sqrt(1.0 / k + c * c * (1.0 - c4 * c4)))


def gate_margin(gap: float, gate: float, se: float | None) -> dict:
    """A gap against its noise gate: the margin (gap - gate), the gate's standard error
    (:func:`gate_standard_error`; None for a given gate or one set by a member or the floor) and
    whether the margin is within one standard error, where the verdict (above or inside the
    gate) would flip with another draw of the members."""
    margin = gap - gate if math.isfinite(gap) else float("nan")
    return {"gap": gap, "gate": gate, "margin": margin, "gate_se": se,
            "within_one_se": bool(se is not None and math.isfinite(margin) and abs(margin) < se)}


def _prediction_half_width(values: list[float], level: float) -> float:
    """t(level, k-1) sqrt(1 + 1/k) s over k >= 2 values taken as normal: how far one more value may
    lie from their mean, one-sided (the noise gate's upper bound, the directed test's lower one)."""
    k = len(values)
    return float(_prediction_factor(k, level) * np.std(values, ddof=1))


@functools.lru_cache(maxsize=64)
def _prediction_factor(k: int, level: float) -> float:
    """t(level, k-1) sqrt(1 + 1/k) (cached: scipy's t quantile costs ~0.3 ms a call, and the gate's
    Monte Carlo test calls it tens of thousands of times)."""
    from scipy.stats import t as student_t

    return float(student_t.ppf(level, k - 1)) * math.sqrt(1 + 1 / k)


def _noise_gate(sim: _Simulator, sims0: list[dict], members: int, sigma: dict | None,
                fixed: list[str] | None = None, journals=DEFAULT_JOURNALS) -> dict:
    """The gap noise alone produces, estimated, not assumed: the model as it is dropped from
    ``members`` random points of the 5 um disc (``ensemble.random_drop_offset``, seeded: a real
    rotor is never dropped exactly centred, and a rattling landing is chaotic), with the measured
    record's own sensor noise added to its series; each member, taken as the measurement, against
    the model as the gap compares it (``sims0``: the centred drop or the ensemble, read through the
    records' sensor model since session 46). Against an ensemble model (``sim.ensemble`` > 1) a single record's members
    fall between the ensemble's drop points on the circle.
    The gate is the one-sided 95 % prediction bound of one more member gap, mean + t(0.95, k-1)
    sqrt(1 + 1/k) s over the k member gaps (at least their largest), never below ``NOISE_GAP_MIN``
    (the resolution of the features). With repeated landings (``sim.records`` > 1) each member
    is the mean of as many drops as there are records, each from a random point of the disc as a
    record is, so the gate has the data's statistics."""
    from .ensemble import DROP_RADIUS_M, drop_offsets, random_drop_offset
    from .features import ensemble_features

    if members < 1:
        return {"gate": NOISE_GAP_MIN, "source": "minimum (no members)", "member_gaps": [], "member_features": [],
                "member_directions": []}

    gaps, produced, directions, kept = [], set(), [], []
    size = max(1, sim.records)
    radius = sim.radius or DROP_RADIUS_M
    on_circle = size == 1 and sim.ensemble > 1
    if on_circle:
        # one record against an ensemble model: single drops between the ensemble's own drop points
        # (half a step round the circle)
        groups = [[o] for o in drop_offsets(members, radius, 0.5)]
    else:
        # each member is as many drops as there are records (the data are their mean), each from a
        # random point of the disc of the AMB's position error, as a record falls
        # (ensemble.random_drop_offset; seeded, so a diagnosis repeats). Until session 21 (repeated
        # records) and 22 (one record) they fell from its rim: 5 um off centre against the records'
        # 3.3 um on average, so the members landed wilder than the records (bench clean 1 um, 4
        # records: data gap 0.154 below all four members' 0.21-0.66, gate 1.07)
        rng = np.random.default_rng(MEMBER_SEED + 1000 * members + size)
        groups = [[random_drop_offset(rng, radius) for _ in range(size)] for _ in range(members)]
    flat = sim.features([list(fixed or []) + o for grp in groups for o in grp], noise=sigma or None, single=True)
    member_sims = []
    for g in range(len(groups)):
        drops = flat[g * size:(g + 1) * size]
        if any("__error__" in s for d in drops for s in d):
            continue
        member_sims.append(drops[0] if size == 1 else
                           [ensemble_features([d[i] for d in drops]) for i in range(len(sim.points))])
    for sims in member_sims:
        directions.append(_directions(sims))
        # the member is the "measurement": its own scales, and the journals compared (the gap's);
        # its channels are the record's (_simulate_features), so it has the rows the record's gap has
        sims = [_journal_rows(s, journals) for s in sims]
        g, rows = gap_points(sims, sims0, [p.name for p in sim.points])
        if math.isfinite(g):
            gaps.append(g)
            kept.append((sims, g))
        # features a noisy off-centre drop produces and the centred one does not: their absence
        # in the model is no sign of a missing effect (the qualitative rule in diagnose)
        produced |= {_row_key(r) for r in rows if r.get("absent_in") == "model"}
    gate = gate_bound(gaps)
    what = f"{len(gaps)} drops" if size == 1 else f"{len(gaps)} means of {size} drops (as many as the records)"
    rate = (sigma or {}).get(RATE_KEY)
    points = f"a {1e6 * radius:g} um circle" if on_circle else f"random points of a {1e6 * radius:g} um disc"
    return {"gate": gate, "gate_se": gate_standard_error(gaps),
            "source": f"{what} from {points}" + (" with the record's sensor noise" if sigma else "")
            + (f", sampled at its {rate:.0f} Hz with a random phase" if rate else "")
            + (f", of its {len(chans)} channels" if (chans := (sigma or {}).get(CHANNELS_KEY)) else ""),
            "member_gaps": gaps, "sensor_noise": sigma or {}, "member_features": sorted(produced),
            "member_directions": directions, "member_sims": kept}


_DIR_Y = {"backward": -1, "none": 0, "forward": 1}


def _feature_figure(res: dict, path) -> None:
    """Per-point features: measured vs model before vs after, one panel per feature."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    names = [p["name"] or "-" for p in res["points"]]
    feats = sorted({r["feature"] for r in res["features_before"]} | {r["feature"] for r in res["features_after"]},
                   key=lambda f: (f != "whirl_direction", f != "whirl_frequency_hz", f))
    fig, axes = plt.subplots(len(feats), 1, figsize=(7, 2.2 * len(feats) + 0.5), squeeze=False)
    for ax, feat in zip(axes[:, 0], feats):
        for label, rows, style in (("measured", res["features_before"], dict(color="k", marker="o", ms=9, ls="")),
                                   ("model before", res["features_before"], dict(color="tab:blue", marker="x", ms=8,
                                                                                  ls="")),
                                   ("model after", res["features_after"], dict(color="tab:green", marker="s", ms=6,
                                                                                ls="", mfc="none"))):
            xs, ys = [], []
            for r in rows:
                if r["feature"] != feat:
                    continue
                v = r["measured"] if label == "measured" else r["simulated"]
                if v is None:
                    continue
                xs.append(names.index(r.get("point") or "-"))
                ys.append(_DIR_Y.get(v, 0) if feat == "whirl_direction" else v)
            ax.plot(xs, ys, label=label, **style)
        if feat == "whirl_direction":
            ax.set_yticks([-1, 0, 1], ["backward", "none", "forward"])
            ax.set_ylim(-1.5, 1.5)
        ax.set_ylabel(feat, fontsize=8)
        ax.set_xticks(range(len(names)), names)
        ax.set_xlim(-0.5, len(names) - 0.5)
        ax.grid(alpha=0.3)
    axes[0, 0].legend(fontsize=8)
    axes[0, 0].set_title(f"gap {res['gap_before']:.3f} -> {res['gap_after']:.3f}; named: {res['named_effect']}",
                         fontsize=9)
    fig.tight_layout()
    save_figure(fig, path, dpi=100)
    plt.close(fig)


def _overlay_figure(res: dict, path, measured: Measurement, scenario_path, clearance: float) -> None:
    """measured vs model before vs after (one record): DE vertical, rotor speed, full spectrum."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from .whirl import full_spectrum

    _, before = _simulate_features(scenario_path, res["model_overrides"], clearance, with_series=True)
    _, after = _simulate_features(scenario_path, res["model_overrides"] + res["calibrated_overrides"], clearance,
                                  with_series=True)
    fig, axes = plt.subplots(3, 1, figsize=(9, 10))
    sets = [("measured", measured, "0.55"), ("model before", before, "tab:blue"), ("model after", after, "tab:green")]
    for label, m, c in sets:
        lw = 2.5 if label == "measured" else 0.8
        if m.has("DE_z_m"):
            t, z = m.series("DE_z_m")
            axes[0].plot(t, z * 1e3, color=c, lw=lw, label=label)
        if m.has("rotor_speed_rpm"):
            t, sp = m.series("rotor_speed_rpm")
            axes[1].plot(t, sp, color=c, lw=lw, label=label)
        if m.has("DE_y_m") and m.has("DE_z_m"):
            t, y = m.series("DE_y_m")
            dt = float(np.median(np.diff(t)))
            tu = np.arange(t[0], t[-1], dt)
            f, a = full_spectrum(tu, np.interp(tu, t, y), np.interp(tu, *m.series("DE_z_m")))
            axes[2].plot(f, a * 1e6, color=c, lw=lw, label=label)
    axes[0].set_ylabel("DE vertical [mm]")
    axes[0].set_xlabel("time after the drop [s]")
    axes[1].set_ylabel("rotor speed [rpm]")
    axes[2].set_ylabel("full spectrum DE [um]")
    axes[2].set_xlabel("frequency [Hz] (negative: backward)")
    axes[2].set_xlim(-300, 300)
    for ax in axes:
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    fig.tight_layout()
    save_figure(fig, path, dpi=110)
    plt.close(fig)


def _fmt(v) -> str:
    if v is None:
        return "-"
    if isinstance(v, str):
        return v
    return f"{v:.4g}"


def _margin_text(label: str, m: dict) -> str | None:
    """One gap against its gate in words (:func:`gate_margin`), or None without a standard error."""
    if m.get("gate_se") is None or not math.isfinite(m["margin"]):
        return None
    side = "above" if m["margin"] > 0 else "inside"
    text = (f"gap {label} {m['gap']:.3f} is {abs(m['margin']):.3f} {side} the gate {m['gate']:.3f} "
            f"(standard error {m['gate_se']:.3f}, {abs(m['margin']) / m['gate_se']:.2f} of them)")
    if m["within_one_se"]:
        text += (": **within one standard error**, so whether it is above the noise hangs on the gate's draw; "
                 "repeated records of the operating point settle it")
    return text


def _span_text(sp: dict) -> str:
    """A fit's uncertainty (:func:`fit_span`) in words."""
    def rng(r):
        return f"{r[0]:.4g}" if r[0] == r[1] else f"{r[0]:.4g}-{r[1]:.4g}"

    text = (f"{', '.join(sp.get('keys') or [sp['parameter']])}, fitted on its own: the values within {sp['z']:g} x {sp['margin'] / sp['z']:.3f} of "
            f"the best gap {sp['gap']:.3f} (that many standard deviations of the noise members' gaps: the data "
            f"cannot rank them) are {', '.join(rng(r) for r in sp['ranges'])} ({sp['within']} of the "
            f"{sp['evaluated']} values evaluated); not ruled out, up to the nearest values that fit worse: "
            f"{', '.join(rng(r) for r in sp['brackets'])}")
    if len(sp["ranges"]) > 1:
        text += (f": **{len(sp['ranges'])} separate dips**, so these data do not fix the value (the gap is not one "
                 "basin here; more records narrow it)")
    ends = [e for e, o in (("lowest", sp["open_low"]), ("highest", sp["open_high"])) if o]
    if ends:
        text += f"; open at the {' and '.join(ends)} value evaluated (the bound)"
    return text


def _step_lines(steps: list[dict]) -> list[str]:
    """The report's lines on each step's joint re-fit and rival. A step's re-fit is of the terms
    named before it together with the step's best candidate: when that candidate is not named (the
    paper's Table 1 with ``--max-effects 2``: the DE clearance at step 2, score 6.34 against 5.21),
    the line says so instead of listing it among what was named."""
    lines = []
    for i, stp in enumerate(steps, 1):
        if stp.get("refit"):
            r = stp["refit"]
            best = stp["candidates"][0]["effect"] if stp.get("candidates") else None
            fit = f"gap {r['gap_before_refit']:.3f} -> {r['gap_after_refit']:.3f} ({r['values']})"
            if stp.get("named"):
                lines.append(f"Step {i}: joint re-fit of everything named so far with {stp['named']}: {fit}.")
            else:
                lines.append(f"Step {i}: the best candidate, {best}, re-fitted jointly with everything named before it: "
                             f"{fit}; not named (it does not pay for itself or stays within the noise).")
        if stp.get("named") and stp.get("fit_span"):
            lines.append(f"Step {i}: " + _span_text(stp["fit_span"]) + ".")
        said = _margin_text("it started from", stp["gate_margin"]) if i > 1 and stp.get("gate_margin") else None
        if said:
            lines.append(f"Step {i}: the {said}.")
        if stp.get("indistinguishable_from"):
            lines.append(f"Step {i}: {stp['named']} and {stp['indistinguishable_from']} explain the gap about equally "
                         "(scores within 2): the data given do not tell them apart.")
    return lines


def _identifiability_lines(ident: dict | None, pairs_shown: int = 8) -> list[str]:
    """The report's section on what the channels can tell apart (before calibrating)."""
    if not ident:
        return []
    lines = ["", "## What the channels given can tell apart (before calibrating)", "",
             ("Each candidate landed at the operating point(s) as step one's calibration lands it first: an effect "
              "at the top of its first parameter's range (the strongest the catalogue allows), a parameter a quarter "
              "of its bound's span either side of its value (the larger change shown). Change: the gap it opens "
              "against the model as it is, over the features the data have; seen when above the noise gate "
              f"({ident['gate']:.3g}). Carried by: the feature rows that change most (signed distance, in scales)."),
             "",
             "| candidate | kind | at | change | seen | carried by |", "|---|---|---|---|---|---|"]
    for c in ident["candidates"]:
        at = ", ".join(f"{k} = {v:.4g}" for k, v in c["at"].items()) or "on"
        if c.get("failed"):
            lines.append(f"| {c['name']} | {c['kind']} | {at} | - | not landed: {c['failed']} | - |")
            continue
        carried = "; ".join(f"{f['feature']} {f['distance']:+.2f}" for f in c.get("features", [])) or "-"
        lines.append(f"| {c['name']} | {c['kind']} | {at} | {c['change']:.3g} | {'yes' if c['detectable'] else 'no'} "
                     f"| {carried} |")
    if ident.get("note"):
        lines += ["", ident["note"][0].upper() + ident["note"][1:] + "."]
    elif ident["pairs"]:
        lines += ["", ("Pairs of seen candidates, most alike first: c is the correlation of their signatures; if one "
                       f"explained the data's gap ({ident['gap_before']:.3g}) the other, fitted to it, would leave "
                       "gap sqrt(1 - c^2) (c by magnitude where a parameter is involved: it may be too high or too "
                       "low); inside the gate the data cannot choose between them, which happens here above |c| = "
                       f"{ident['correlation_limit']:.2f}."), "",
                  "| pair | c | remainder | told apart |", "|---|---|---|---|"]
        for q in ident["pairs"][:pairs_shown]:
            lines.append(f"| {q['a']} / {q['b']} | {q['correlation']:+.2f} | {q['remainder']:.3g} | "
                         f"{'yes' if q['told_apart'] else '**no**'} |")
        if len(ident["pairs"]) > pairs_shown:
            lines.append(f"| ({len(ident['pairs']) - pairs_shown} more in report.json) | | | |")
    return lines


def write_report(res: dict, out_dir, measured: Measurement | None, scenario_path, clearance: float) -> list[str]:
    """report.md and a figure: overlay.png (a record: measured vs model before vs after, spectrum)
    or features.png (a feature table: per-point features measured vs before vs after)."""
    from pathlib import Path

    out = Path(out_dir)
    if measured is not None and measured.channels:
        fig_name = "overlay.png"
        _overlay_figure(res, out / fig_name, measured, scenario_path, clearance)
    else:
        fig_name = "features.png"
        _feature_figure(res, out / fig_name)
    multi = len(res["points"]) > 1 or any(p["overrides"] for p in res["points"])
    model = f"`{scenario_path}`" + (f" with `{' '.join(res['model_overrides'])}`" if res["model_overrides"] else "")
    shrink = (f" ({100 * (1 - res['gap_after'] / res['gap_before']):.0f} % smaller)"
              if res["gap_before"] and math.isfinite(res["gap_before"]) else "")
    lines = ["# Model-gap diagnosis", "",
             f"Model: {model}. Gap before: **{res['gap_before']:.3f}**, after: **{res['gap_after']:.3f}**{shrink}. "
             f"Noise gate: **{res['noise_gate']:.3f}** ({res['noise']['source']}; gaps of the members: "
             f"{', '.join(f'{g:.3f}' for g in res['noise']['member_gaps']) or '-'})"
             + (f"; of the final model: **{res['noise_gate_final']:.3f}**" if res.get("noise_final") else "") + ".", ""]
    if res.get("model_read"):
        lines += [f"The model compared: {res['model_read']}.", ""]
    margins = res.get("gate_margins") or {}
    said = [t for t in (_margin_text(k, margins[k]) for k in ("before", "after") if margins.get(k)) if t]
    if said:
        lines += ["Margins against the gate's own standard error (the gate is estimated from a few drops, so it "
                  "moves with their draw): " + "; ".join(said) + ".", ""]
    if res.get("records", 1) > 1:
        spread = sorted(res.get("record_spread", {}).items())
        lines += [f"Measured: **{res['records']} records** of repeated landings, compared as their mean features with "
                  f"the model's mean over {res['ensemble']} drops; the records' own scatter (standard deviation): "
                  + (", ".join(f"{k} {_fmt(v)}" for k, v in spread) or "-") + ".", ""]
    for w in res.get("warnings", []):
        lines += [f"**Warning**: {w}.", ""]
    if res.get("absent_in_model_before"):
        lines += ["First hint: features in the data the model as it is cannot produce (each charged "
                  f"{ABSENT_FEATURE_DISTANCE:g}, the largest distance): **{', '.join(res['absent_in_model_before'])}**"
                  + (f"; after: {', '.join(res['absent_in_model_after'])}" if res.get("absent_in_model_after")
                     else "; after: none") + ".", ""]
    for q in res.get("named_parameters", []):
        lines.append(f"Wrong parameter: **{q['key']}** {_fmt(q['from'])} -> {q['to']:.4g} (bound {q['bound'][0]:g}-"
                     f"{q['bound'][1]:g}: {q['source']}).")
    if res.get("named_parameters"):
        lines.append("")
    if res.get("unexplained"):
        lines += [f"**Unexplained**: the gap {res['gap_after']:.3f} stays above the noise gate of the final model "
                  f"{res['noise_gate_final']:.3f}; "
                  "it is largest in " + ", ".join(f"{r['feature']}" + (f" ({r['point']})" if r["point"] else "")
                                                 + f" {r['distance']:.2f}" for r in res["largest_remaining"]) + ".", ""]
    if multi:
        lines.append(f"Operating points: {', '.join(p['name'] + ' (' + ' '.join(p['overrides']) + ')' for p in res['points'])}; "
                     f"{res['simulations']} simulations, {res['wall_s']:.0f} s wall on {res['workers']} workers.")
        lines.append("")
    if res["named_effect"]:
        for n in res["named_effects"]:
            lines.append(f"Named effect: **{n}**. Signature: {res['signatures'][n]}.")
        lines.append(f"Calibrated: `{' '.join(res['calibrated_overrides'])}`.")
        if any(p["whirl_measured"] for p in res["points"]):
            fixed = [p["name"] or "the record" for p in res["points"]
                     if p["whirl_measured"] and p["whirl_before"] != p["whirl_measured"] == p["whirl_after"]]
            still = [p["name"] or "the record" for p in res["points"]
                     if p["whirl_measured"] and p["whirl_after"] != p["whirl_measured"]]
            lines.append("")
            lines.append("In the data: whirl direction measured / before / after per point: "
                         + "; ".join(f"{p['name'] or 'record'}: {p['whirl_measured']} / {p['whirl_before']} / "
                                     f"{p['whirl_after']}" for p in res["points"]) + "."
                         + (f" The named effect makes the model whirl as measured at {', '.join(fixed)}." if fixed
                            else "")
                         + (f" Still different at {', '.join(still)}." if still else ""))
    elif not res.get("named_parameters"):
        lines.append("No candidate effect or parameter explains the disagreement significantly (null answer).")
    for n, others in (res.get("named_alike") or {}).items():
        lines += ["", f"Read **{n}** with care: before calibrating, the channels could not tell it from "
                  + ", ".join(f"{o['other']} (c {o['correlation']:+.2f})" for o in others)
                  + " (section below); the ranking chose it on the calibrated gaps."]
    if res.get("decisive_features") and (res["named_effect"] or res.get("named_parameters")):
        lines += ["", "The decision rests on (share of the fall of the squared gap): " + "; ".join(
            f"{d['feature']}" + (f" ({d['point']})" if d["point"] else "")
            + f" {d['distance_before']:.2f} -> {d['distance_after']:.2f} ({100 * d['share']:.0f} %)"
            for d in res["decisive_features"]) + "."]
    lines += _step_lines(res["steps"])
    lines += _identifiability_lines(res.get("identifiability"))
    lines += ["", "## Candidates (effects the model lacks, and its uncertain parameters within their bounds)", "",
              "Score n ln(gap^2) + k ln n (n feature rows, k fitted numbers: an effect's parameters, 1 for a parameter "
              "moved within its bound): each added freedom must pay for itself.", "",
              "| step | kind | candidate | gap | parameters | score | whirl per point |",
              "|---|---|---|---|---|---|---|"]
    for i, stp in enumerate(res["steps"], 1):
        for c in stp["candidates"]:
            note = c.get("not_applicable") or c.get("failed") or " / ".join(map(str, c.get("directions", [])))
            if c.get("screened_only"):
                note += " (screened only)"
            lines.append(f"| {i} | {c.get('kind', 'effect')} | {c['effect']} | {c['gap']:.3g} | {c['parameters']} | "
                         f"{c['score']:.3g} | {note} |")
    lines += ["", "## Features (distance = |measured - model| / scale, at most 3)", "",
              "| point | feature | measured | before | after | scale | distance before | distance after |",
              "|---|---|---|---|---|---|---|---|"]
    after_rows = {(r.get("point"), r["feature"]): r for r in res["features_after"]}
    for r in res["features_before"]:
        a = after_rows.get((r.get("point"), r["feature"]), {})
        mark = " (absent in the model)" if r.get("absent_in") == "model" else \
            " (absent in the data)" if r.get("absent_in") == "measurement" else ""
        lines.append(f"| {r.get('point') or '-'} | {r['feature']}{mark} | {_fmt(r['measured'])} | {_fmt(r['simulated'])} | "
                     f"{_fmt(a.get('simulated'))} | {_fmt(r['scale'])} | {r['distance']:.3g} | "
                     f"{a.get('distance', float('nan')):.3g} |")
    lines += ["", f"![{fig_name[:-4]}]({fig_name})", ""]
    atomic_write_text(out / "report.md", "\n".join(lines))
    return ["report.md", fig_name]


def run_diagnose(scenario_path, measured_path, out_dir, *, sets=(), t_end: float | None = None, candidates=None,
                 max_effects: int = 1, workers: int = 2, maxiter: int = 10, time_offset_s: float | None = None,
                 parameters=None, noise_gap: float | None = None, ensemble: int | None = None,
                 ensemble_radius_m: float | None = None, journals=DEFAULT_JOURNALS,
                 cli_names: bool = True, scatter_scales: bool | None = None) -> tuple[dict, list[str]]:
    """``rotorlanding diagnose`` without its printing: validate the options, read the measurement,
    run :func:`diagnose`, write ``out_dir``/report.json, report.md and the figure; returns (the
    report, the names of the files written besides report.json). The command line and the API's
    ``rotorlanding.diagnose`` both call it, so their reports are the same.

    ``measured_path``: one measurement file, or several records of repeated landings of one
    operating point (a list: compared as their means, :class:`Repeated`).
    ``sets``: ``KEY=VALUE`` items (``--set``); ``t_end`` [s] overrides ``operating.t_end``;
    ``candidates``: effect names or None (every effect the model lacks, faults only on request);
    ``time_offset_s`` [s]: the drop instant in the data's clock (None: detected); ``parameters``: the
    scenario keys tried as wrong parameters beside the effects (None: the default list, [] none);
    ``noise_gap``: the gate (None: estimated from the model's drops with the record's noise);
    ``ensemble``: drops per feature evaluation (1: one drop; None: :func:`ensemble_default`, 4
    against one record), from a circle of ``ensemble_radius_m`` [m] (None: the default); ``journals``: whose per-journal features are compared (``("DE",)``
    or ``("DE", "NDE")``; the whirl rows are the DE's). ``cli_names``:
    errors name the options as the command line spells them (``--max-effects``), else as the API's
    keywords (``max_effects``). ``scatter_scales``: each feature's scale widened by the model's own
    drop scatter (None: on when the model runs more than one drop, :func:`diagnose`).
    Every bad input is one InputError before any simulation."""
    from pathlib import Path

    from .safeio import atomic_write_text, check_out_dir
    from .scenario import EFFECTS

    def opt(name: str) -> str:
        return "--" + name.replace("_", "-") if cli_names else name

    for name, v in (("workers", workers), ("maxiter", maxiter), ("max_effects", max_effects),
                    ("ensemble", 1 if ensemble is None else ensemble)):
        if isinstance(v, bool) or not isinstance(v, int) or v < 1:
            raise InputError(opt(name), v, "must be an integer >= 1")
    if scatter_scales is not None and not isinstance(scatter_scales, bool):
        raise InputError(opt("scatter_scales"), scatter_scales, "True, False, or None (on when the model runs more "
                         "than one drop: --ensemble > 1 or repeated records)")
    sets = list(sets or [])
    for item in sets:
        key = item.split("=", 1)[0].strip()
        if key.startswith("effects.") and key[8:] not in EFFECTS:
            raise InputError(f"{opt('set')} {key}", item.split("=", 1)[-1], f"unknown effect; allowed: {', '.join(EFFECTS)}")
    if t_end is not None:
        sets.append(f"operating.t_end={t_end!r}")
    paths = [measured_path] if isinstance(measured_path, (str, Path)) else list(measured_path)
    if not paths:
        raise InputError(opt("measured"), "none", "a measurement file, or several records of repeated landings")
    if time_offset_s is not None and not math.isfinite(time_offset_s):
        raise InputError(opt("time_offset_s"), time_offset_s, "must be a finite time in seconds (the drop instant "
                         "in the data's clock), or left out to detect the drop")
    if len(paths) > 1 and time_offset_s is not None:
        raise InputError(opt("time_offset_s"), time_offset_s, f"only with one record ({len(paths)} given): the drop "
                         "of each of several records is detected in its own data")
    try:
        if len(paths) > 1:
            clearance, m, meas, info = records_for_diagnosis(scenario_path, paths, sets, option=opt("measured"))
        else:
            clearance, m, meas, info = measured_for_diagnosis(scenario_path, paths[0], sets, time_offset_s)
    except InputError as err:  # the readers name the file option as the command line spells it
        if cli_names or not err.field.startswith("--"):
            raise
        raise InputError(err.field[2:].replace("-", "_"), err.value, err.allowed, file=err.file) from None
    if isinstance(meas, Repeated):
        _records_ensemble(len(meas.features), ensemble or 1, opt("ensemble"))  # before any simulation
    journals = tuple(journals)
    if not journals or journals[0] != "DE" or any(j not in JOURNALS for j in journals) or len(set(journals)) < len(journals):
        raise InputError(opt("journals"), ",".join(journals), "DE, or DE,NDE (the whirl rows are the DE journal's)")
    cands = list(candidates) if candidates else None
    for c in cands or []:
        if c not in CATALOGUE:
            raise InputError(opt("candidates"), c, f"unknown effect; allowed: {', '.join(CATALOGUE)}")
    if ensemble_radius_m is not None and not 0 < ensemble_radius_m < clearance:
        raise InputError(opt("ensemble_radius_m"), ensemble_radius_m,
                         f"must be > 0 and below the DE clearance ({clearance:g} m)")
    if noise_gap is not None and not noise_gap > 0:
        raise InputError(opt("noise_gap"), noise_gap, "must be > 0 (omit it to estimate the gate from the model's drops)")
    params = None if parameters is None else [str(k).strip() for k in parameters if str(k).strip()]
    out = check_out_dir(out_dir, opt("out") if cli_names else "out_dir")
    res = diagnose(meas, scenario_path, clearance=clearance, candidates=cands, max_effects=max_effects,
                   workers=workers, maxiter=maxiter, base_overrides=sets, parameters=params,
                   noise_gap=noise_gap, info=info, ensemble=ensemble, ensemble_radius_m=ensemble_radius_m,
                   journals=journals, scatter_scales=scatter_scales)
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    atomic_write_text(out / "report.json", json.dumps(res, indent=2, default=float))
    files = write_report(res, out, m if m.channels else None, scenario_path, clearance)
    return res, files


__all__ = ["Point", "Repeated", "diagnose", "run_diagnose", "write_report"]
