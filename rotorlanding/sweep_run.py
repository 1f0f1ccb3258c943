"""Parameter sweeps of landing scenarios: ``rotorlanding sweep SWEEP.toml``.

The machinery behind ``rotorlanding sweep`` and the Python API's ``rotorlanding.sweep(...)``
(:mod:`rotorlanding.api_studies`, which returns a ``Sweep``); the module is named ``sweep_run`` so
that the package attribute ``rotorlanding.sweep`` is the function.

A sweep file names a base scenario and the keys to vary::

    scenario = "paper/forward_whirl_landing.toml"   # relative to the sweep file
    mode = "grid"                                    # "grid" (all combinations) or "monte_carlo"
    samples = 32                                     # monte_carlo only
    seed = 1                                         # monte_carlo only
    plots = false                                    # per-case figures (default false)
    [fixed]                                          # applied to every case
    "operating.t_end" = 0.5
    [grid]                                           # grid: lists of values
    "operating.speed_rpm" = [3000, 7000, 10000]
    "contact.mu_ax" = [0.1, 0.3]
    [ranges]                                         # monte_carlo: uniform ranges
    "contact.mu_rad" = {min = 0.1, max = 0.3}

Each case runs in its own folder ``OUT/cases/case_NNNN`` (results.h5, summary.json); the table
``OUT/sweep.csv`` collects the summary figures (one row per case, failed cases with their error),
and ``OUT/whirl_map.png`` shows whirl class and frequency over the first two swept keys.
Cases run in worker processes (``--workers``, or a Dask cluster with ``--scheduler``); a case
that raises, or whose worker process dies, is recorded as failed with its error and the others
go on; re-running skips cases whose summary.json is complete.

Speed and reproducibility (see ``benchmarks/sweep_speedup.py``):

* every case runs in a worker process, also with ``--workers 1``; local workers are forked from
  the parent after it has imported the model code and built the first case's model once (numba
  kernels loaded), so no worker pays imports or JIT loading again;
* every worker runs BLAS/LAPACK single-threaded (as Dask's nanny does), so N workers do not
  oversubscribe the cores and a case's summary is bit-identical whatever the number of workers
  or the scheduler (multi-threaded BLAS changes float summation order);
* the Craig-Bampton reduction is cached per worker process, keyed by the exact bytes of the FE
  matrices and the reduction settings (a cache hit returns the same numbers as a recomputation);
* cases are submitted longest first (t_end / step), one at a time, so the last case does not
  leave a worker idle; the parent imports matplotlib for the whirl map as soon as a worker has
  run out of cases, not after the last case.
"""

from __future__ import annotations

import csv
import functools
import io
import itertools
import json
import os
import time
import traceback
from pathlib import Path

import numpy as np

from .config import override_table, range_spec, sample_ranges, study_file, value_list
from .errors import InputError
from .runner import ReductionCache, executor, reduction_cache, worker_setup
from .safeio import atomic_write_text, save_figure
from .whirl import landing_whirl

CSV_FIELDS = ["case", "status", "error", "whirl_direction", "whirl_frequency_hz", "whirl_onset_s",
              "whirl_end_s", "whirl_persistence", "whirl_bearing", "whirl_shape",
              # per bearing of the sweep's scenario, in its order (BEARING_FIELDS), then:
              "final_rotor_rpm", "energy_dissipated_j", "wall_s"]
#: summary value of each bearing -> CSV column suffix (the column is <bearing>_<suffix>)
BEARING_FIELDS = {"max_contact_force_n": lambda sb: sb.get("max_contact_force_n"),
                  "vertical_min_m": lambda sb: sb.get("vertical_displacement_range_m", [None, None])[0],
                  "vertical_max_m": lambda sb: sb.get("vertical_displacement_range_m", [None, None])[1]}


def csv_fields(bearing_names) -> list[str]:
    per = [f"{b}_{k}" for b in bearing_names for k in BEARING_FIELDS]
    i = CSV_FIELDS.index("whirl_shape") + 1
    return CSV_FIELDS[:i] + per + CSV_FIELDS[i:]


def load_sweep(path) -> dict:
    with study_file(path) as (path, t):
        base = path.parent / t.string("scenario")
        if not base.is_file():
            raise InputError("scenario", str(base), "file not found")
        mode = t.string("mode", "grid")
        if mode not in ("grid", "monte_carlo"):
            raise InputError("mode", mode, "must be 'grid' or 'monte_carlo'")
        fixed = override_table(t.raw("fixed", {}), "fixed")
        plots = t.boolean("plots", False)
        cases = []
        if mode == "grid":
            grid = t.raw("grid")
            if not isinstance(grid, dict) or not grid:
                raise InputError("grid", grid, "give at least one key = [values]")
            for k, vals in grid.items():
                value_list(vals, f"grid.{k}")
            keys = list(grid)
            for combo in itertools.product(*(grid[k] for k in keys)):
                cases.append(dict(zip(keys, combo)))
            t.raw("samples", None)
            t.raw("seed", None)
        else:
            ranges = t.raw("ranges")
            if not isinstance(ranges, dict) or not ranges:
                raise InputError("ranges", ranges, "give at least one key = {min, max}")
            n = t.integer("samples", 16)
            seed = t.integer("seed", 1, minimum=0)
            keys = list(ranges)
            for k in keys:
                range_spec(ranges[k], f"ranges.{k}")
            cases = sample_ranges(ranges, n, seed)
        t.raw("grid" if mode == "monte_carlo" else "ranges", None)
        t.finish()
        _check_cases(base, fixed, cases)
    return {"base": base, "mode": mode, "keys": keys, "fixed": fixed, "cases": cases, "plots": plots}


def _check_cases(base: Path, fixed: dict, cases: list[dict]) -> None:
    """Validate cases (scenario schema and plausibility limits) until one passes. One invalid case
    among valid ones runs as a failed case (a sweep maps where the model breaks); a sweep whose
    every case is invalid is bad input, reported before any worker starts. Stopping at the first
    valid case keeps this cheap (usually one scenario load)."""
    from .scenario import load_scenario

    first = None
    for case in cases:
        try:
            load_scenario(base, _overrides(fixed, case))
            return
        except InputError as err:
            first = first or err
    if first is not None:
        raise InputError(first.field, first.value, f"{first.allowed} (every one of the {len(cases)} cases is "
                         f"invalid{'' if first.file is None else ' for ' + str(first.file)})")


def _overrides(fixed: dict, case: dict) -> list[str]:
    out = []
    for k, v in list(fixed.items()) + list(case.items()):
        out.append(f"{k}={json.dumps(v) if isinstance(v, str) else repr(v)}")
    return out


# ---------------------------------------------------------------------------------------------
# Worker process set-up (single-threaded BLAS, reduction cache): rotorlanding.runner, shared with
# the other studies; the names stay importable from here
_CraigBamptonCache = ReductionCache


def warm_up(job) -> None:
    """Set this process up as a worker and build (not solve) the model of ``job``: model code
    imported, numba kernels loaded, reduction cached."""
    worker_setup()
    from .exudyn_model import build_exudyn
    from .landing import build_spec
    from .scenario import load_scenario

    try:
        build_exudyn(build_spec(load_scenario(job[1], job[2]), reduction=reduction_cache()))
    except Exception:  # a bad case fails later, in run_case, where it is recorded
        pass


def _marker(job) -> Path:
    return Path(job[3]) / "cases" / f"case_{job[0]:04d}" / ".running"


def run_case(job) -> dict:
    """Run one case (in a worker); never raises: failures come back as a row."""
    worker_setup()
    from .run import run_scenario
    from .scenario import load_scenario

    idx, base, overrides, out_dir, plots = job
    row = {"case": idx, "status": "ok", "error": ""}
    folder = Path(out_dir) / "cases" / f"case_{idx:04d}"
    folder.mkdir(parents=True, exist_ok=True)
    marker = _marker(job)
    marker.write_text(str(os.getpid()))
    # the inputs are stored once the case has finished with them (_finished compares them): a case
    # that fails leaves none, so an older summary in its folder is never taken for its result
    (folder / "case.json").unlink(missing_ok=True)
    w0 = time.perf_counter()
    try:
        sc = load_scenario(base, overrides)
        s = run_scenario(sc, folder, progress=False, plots=plots, reduction=reduction_cache())
        row.update(summary_row(s))
        if not s.get("complete", True):
            row["status"], row["error"] = "incomplete", s.get("message", "")
        else:
            atomic_write_text(folder / "case.json", json.dumps(_case_inputs(base, overrides), indent=2))
    except Exception as exc:  # a failing case is recorded, the sweep goes on
        row.update(_failed_row(idx, f"{type(exc).__name__}: {exc}", out_dir, traceback.format_exc()))
    row["wall_s"] = round(time.perf_counter() - w0, 3)
    marker.unlink(missing_ok=True)
    return row


def _failed_row(idx: int, error: str, out_dir, details: str | None = None) -> dict:
    """The row of a failed case; its error (or ``details``) also goes to the case's error.txt."""
    folder = Path(out_dir) / "cases" / f"case_{idx:04d}"
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "error.txt").write_text(details or error + "\n")
    return {"case": idx, "status": "failed", "error": error.replace("\n", " ")}


def summary_row(s: dict) -> dict:
    b = s.get("bearings", {})
    w = landing_whirl(s["whirl"])  # also re-derives summaries of finished cases written before
    return {"_bearings": list(b), "whirl_direction": w["direction"], "whirl_frequency_hz": w["frequency_hz"],
            "whirl_onset_s": w["onset_s"], "whirl_end_s": w.get("end_s"), "whirl_persistence": w.get("persistence"),
            "whirl_bearing": w["bearing"] if w["direction"] != "none" else None,
            # cylindrical / conical (whirl.whirl_shape); empty for a case summarised before session 27
            "whirl_shape": (w.get("shape") or {}).get("form") if w["direction"] != "none" else None,
            **{f"{name}_{k}": get(sb) for name, sb in b.items() for k, get in BEARING_FIELDS.items()},
            "final_rotor_rpm": s["speeds"]["final_rotor_rpm"],
            "energy_dissipated_j": s["energy"]["dissipated_total_j"]}


def _case_inputs(base, overrides) -> dict:
    """What made a case: the base scenario and the case's overrides (stored beside its results)."""
    return {"base": str(base), "overrides": [str(o) for o in overrides]}


def _finished(out_dir: Path, idx: int, inputs: dict | None = None):
    """The summary of case ``idx`` if it finished with these ``inputs``. A case folder of the same
    number from a sweep file since edited (other values for that case) is not reused: it was,
    by index alone, and reported another case's results under the new values."""
    folder = out_dir / "cases" / f"case_{idx:04d}"
    f = folder / "summary.json"
    if f.is_file():
        if inputs is not None:
            try:
                if json.loads((folder / "case.json").read_text()) != inputs:
                    return None
            except (OSError, ValueError):
                return None
        s = json.loads(f.read_text())
        if s.get("complete") and "whirl" in s:
            return s
    return None


def _cost(fixed: dict, case: dict, base_t_end: float, base_step: float) -> float:
    """Relative cost of a case for longest-first ordering: number of time steps."""
    def get(key, default):
        v = case.get(key, fixed.get(key, default))
        return float(v) if isinstance(v, (int, float)) else default

    return get("operating.t_end", base_t_end) / max(get("solver.step", base_step), 1e-12)


def _run_local(jobs: list, workers: int, idle=None) -> list[dict]:
    """Run jobs (in the given order) in the runner's worker processes; a case whose worker dies is
    retried alone and recorded as failed if it kills its worker again (the case's marker file
    says which were running). ``idle()`` is called once as soon as a worker has nothing left to
    do (the parent uses that core for its own work)."""
    from concurrent.futures import as_completed
    from concurrent.futures.process import BrokenProcessPool

    results, pending, alone = [], list(jobs), []
    while pending or alone:
        batch, n = (pending, min(workers, len(pending))) if not alone else (alone[:1], 1)
        for j in batch:
            _marker(j).unlink(missing_ok=True)
        broken = []
        with executor(n) as ex:
            futs = {ex.submit(run_case, j): j for j in batch}
            inflight = len(futs)
            for f in as_completed(futs):
                inflight -= 1
                if idle is not None and inflight < n:
                    idle()
                    idle = None
                try:
                    results.append(f.result())
                except BrokenProcessPool:
                    broken.append(futs[f])
        if alone:
            alone = alone[1:]
            if broken:
                j = broken[0]
                _marker(j).unlink(missing_ok=True)
                results.append(_failed_row(j[0], "worker process died while running this case (a crash in "
                                                 "the solver?); the other cases were not affected", j[3]))
            continue
        # the cases that were running when a worker died are retried one at a time
        running = [j for j in broken if _marker(j).is_file()]
        alone = running
        pending = [j for j in broken if j not in running]
    return results


def run_sweep(path, out_dir, *, workers: int = 1, scheduler: str | None = None) -> list[dict]:
    sw = load_sweep(path)
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    atomic_write_text(out / "sweep.json", json.dumps({"sweep_file": str(path), "base": str(sw["base"]), "mode": sw["mode"],
                                                      "keys": sw["keys"], "fixed": sw["fixed"], "cases": sw["cases"]},
                                                     indent=2))
    rows: dict[int, dict] = {}
    jobs = []
    for idx, case in enumerate(sw["cases"]):
        done = _finished(out, idx, _case_inputs(sw["base"], _overrides(sw["fixed"], case)))
        if done is not None:
            rows[idx] = dict(case=idx, status="ok", error="", wall_s=done.get("performance", {}).get("wall_s"),
                             **summary_row(done))
            rows[idx]["skipped"] = True
        else:
            jobs.append((idx, str(sw["base"]), _overrides(sw["fixed"], case), str(out), sw["plots"]))
    if jobs:
        from .scenario import load_scenario

        try:
            base = load_scenario(sw["base"], _overrides(sw["fixed"], {}))
            t_end, step = base.t_end, base.solver.step
        except InputError:  # the cases' own values may complete it: they fail (or not) one by one
            t_end, step = 1.0, 1.0
        cost = {j[0]: _cost(sw["fixed"], sw["cases"][j[0]], t_end, step) for j in jobs}
        jobs.sort(key=lambda j: (-cost[j[0]], j[0]))  # longest first
        if scheduler:
            from .distributed import map_on_dask

            results = map_on_dask(run_case, jobs, scheduler, warm_up=functools.partial(warm_up, jobs[0]),
                                  on_error=lambda job, err: _failed_row(job[0], err, job[3]))
        else:
            # the parent is a worker while it forks workers, so they start warm (imports, numba
            # kernels, reduction cache); afterwards its BLAS threads and functions are restored
            undo = worker_setup()
            try:
                warm_up(jobs[0])
                results = _run_local(jobs, workers, idle=_import_plotting)
            finally:
                undo()
        for r in results:
            rows[r["case"]] = r
    table = [rows[i] for i in sorted(rows)]
    for r in table:
        r.update({k: sw["cases"][r["case"]][k] for k in sw["keys"]})
    # the whole table is written under a temporary name and renamed: a kill leaves the old or the new one
    fh = io.StringIO(newline="")
    bearings = next((r["_bearings"] for r in table if r.get("_bearings")), ["DE", "NDE"])
    w = csv.DictWriter(fh, fieldnames=["case"] + sw["keys"] + csv_fields(bearings)[1:], extrasaction="ignore")
    w.writeheader()
    for r in table:
        w.writerow(r)
    atomic_write_text(out / "sweep.csv", fh.getvalue())
    plot_whirl_map(table, sw["keys"], out / "whirl_map.png")
    return table


def _import_plotting():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot  # noqa: F401


#: the unit of a swept key, from its name (SI otherwise unnamed: the scenario file's fields are SI)
_KEY_UNITS = (("_rpm", "rpm"), ("_hz", "Hz"), ("_s", "s"), ("_m", "m"), ("_n", "N"), ("_j", "J"), ("_w", "W"),
              ("diameter", "m"), ("radius", "m"), ("clearance", "m"), ("length", "m"), ("thickness", "m"),
              ("t_end", "s"), ("t_drop", "s"), ("mass", "kg"))
_KEY_NAMES = {"operating.speed_rpm": "rotor speed at the drop", "contact.mu_rad": "radial friction coefficient mu_rad",
              "contact.mu_ax": "axial friction coefficient mu_ax", "axial.f_thrust": "axial thrust"}
_KEY_EXTRA = {"axial.f_thrust": "N", "contact.k_hertz": "N/m^e", "contact.mu_rad": "-", "contact.mu_ax": "-"}
WHIRL_STYLE = {"forward": ("tab:red", "^"), "backward": ("tab:blue", "v"), "none": ("0.75", "o"),
               "failed": ("k", "x")}


def key_label(key: str) -> str:
    """An axis label for a swept key with its unit: ``operating.speed_rpm`` -> "rotor speed at
    the drop [rpm] (operating.speed_rpm)"."""
    unit = _KEY_EXTRA.get(key) or next((u for suf, u in _KEY_UNITS if key.endswith(suf)), None)
    name = _KEY_NAMES.get(key)
    core = f"{name} [{unit}]" if name and unit else (name or (f"{key} [{unit}]" if unit else key))
    return f"{core}\n({key})" if name else core


def _cls(r: dict) -> str:
    return (r.get("whirl_direction") or "failed") if r.get("status") == "ok" else "failed"


def plot_whirl_map(rows: list[dict], keys: list[str], path) -> None:
    """The whirl map of a sweep (PNG). Two swept keys on a full grid: left, one cell per case
    coloured by whirl class with the whirl frequency [Hz] (and its ratio to the spin frequency
    when ``operating.speed_rpm`` is swept) written in it; right, the whirl frequency [Hz] against
    the first key, one line per value of the second (the 1x spin-frequency line when the first
    key is the speed). Otherwise a scatter of the cases over the first two keys."""
    _import_plotting()
    import matplotlib.pyplot as plt
    from matplotlib.colors import ListedColormap
    from matplotlib.patches import Patch

    kx = keys[0]
    ky = keys[1] if len(keys) > 1 else None
    xs = sorted({r[kx] for r in rows})
    ys = sorted({r[ky] for r in rows}) if ky else [0.0]
    speed_key = next((k for k in (kx, ky) if k == "operating.speed_rpm"), None)
    cell = {}
    for r in rows:
        cell.setdefault((r[kx], r[ky] if ky else 0.0), r)
    full_grid = len(keys) <= 2 and len(cell) == len(xs) * len(ys) == len(rows)
    title = "whirl class and frequency (DE journal, else the bearing that whirls)"
    if not full_grid:
        fig, ax = plt.subplots(figsize=(7, 5))
        seen = set()
        for r in rows:
            cls = _cls(r)
            c, m = WHIRL_STYLE.get(cls, ("k", "x"))
            x, y = r[kx], (r[ky] if ky else 0.0)
            ax.plot(x, y, m, color=c, ms=10, mec="k", label=None if cls in seen else cls)
            seen.add(cls)
            if r.get("whirl_frequency_hz"):
                ax.annotate(f"{r['whirl_frequency_hz']:.0f} Hz", (x, y), textcoords="offset points", xytext=(6, 6),
                            fontsize=8)
        ax.set_xlabel(key_label(kx))
        ax.set_ylabel(key_label(ky) if ky else "")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
        ax.set_title(title, fontsize=10)
        fig.tight_layout()
        save_figure(fig, path, dpi=110)
        plt.close(fig)
        return
    classes = list(WHIRL_STYLE)
    codes = np.array([[classes.index(_cls(cell[(x, y)])) for x in xs] for y in ys])
    cmap = ListedColormap(["#e8867d", "#7fa7d9", "#d9d9d9", "#404040"])
    fig, (ax, ax2) = plt.subplots(1, 2, figsize=(13, 5.2), gridspec_kw={"width_ratios": [1.15, 1]})
    ax.imshow(codes, cmap=cmap, vmin=-0.5, vmax=len(classes) - 0.5, origin="lower", aspect="auto")
    for j, y in enumerate(ys):
        for i, x in enumerate(xs):
            r = cell[(x, y)]
            f = r.get("whirl_frequency_hz")
            txt = {"none": "no whirl"}.get(_cls(r), _cls(r))
            if f and _cls(r) in ("forward", "backward"):
                txt = f"{f:.0f} Hz"
                if speed_key:
                    spin = (x if speed_key == kx else y) / 60.0
                    txt += f"\n{f / spin:.2f} x spin"
            ax.text(i, j, txt, ha="center", va="center", fontsize=9,
                    color="w" if _cls(r) == "failed" else "k")
    for i in range(1, len(xs)):  # white rules between the cells of neighbouring cases of one class
        ax.axvline(i - 0.5, color="w", lw=2)
    for j in range(1, len(ys)):
        ax.axhline(j - 0.5, color="w", lw=2)
    ax.set_xticks(range(len(xs)), [f"{x:g}" for x in xs])
    ax.set_yticks(range(len(ys)), [f"{y:g}" for y in ys] if ky else [""])
    ax.set_xlabel(key_label(kx))
    ax.set_ylabel(key_label(ky) if ky else "")
    present = sorted({int(c) for c in codes.ravel()})
    ax.legend(handles=[Patch(color=cmap(k), label={"none": "no whirl", "failed": "failed"}.get(classes[k], f"{classes[k]} whirl")) for k in present],
              fontsize=8, loc="upper left", bbox_to_anchor=(0.0, -0.16), ncol=len(present), frameon=False)
    ax.set_title(title, fontsize=10)
    # the whirl frequency against the first key, one line per value of the second
    for y, color in zip(ys, plt.cm.viridis(np.linspace(0.0, 0.85, len(ys)))):
        fx = [(x, cell[(x, y)].get("whirl_frequency_hz")) for x in xs]
        fx = [(x, f if f and _cls(cell[(x, y)]) in ("forward", "backward") else np.nan) for x, f in fx]
        fx = [(x, -f if _cls(cell[(x, y)]) == "backward" else f) for x, f in fx]
        ax2.plot([a for a, _ in fx], [b for _, b in fx], "o-", color=color,
                 label=f"{ky} = {y:g}" if ky else None)
    if kx == "operating.speed_rpm":
        sx = np.linspace(0.0, max(xs) * 1.05, 50)
        ax2.plot(sx, sx / 60.0, "k--", lw=0.8, label="1x spin frequency")
        ax2.plot(sx, -sx / 60.0, "k:", lw=0.8, label="-1x")
    ax2.axhline(0.0, color="0.5", lw=0.6)
    ax2.set_xlabel(key_label(kx))
    ax2.set_ylabel("whirl frequency [Hz] (negative: backward)")
    ax2.grid(alpha=0.3)
    if ky or kx == "operating.speed_rpm":
        ax2.legend(fontsize=8)
    ax2.set_title("whirl frequency (a missing point: no whirl there)", fontsize=10)
    fig.tight_layout()
    save_figure(fig, path, dpi=120)
    plt.close(fig)
