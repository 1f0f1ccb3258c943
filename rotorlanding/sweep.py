"""Parameter sweeps of landing scenarios: ``rotorlanding sweep SWEEP.toml``.

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
Cases run in a local process pool (``--workers``); a case that raises is recorded as failed
and the others go on; re-running skips cases whose summary.json is complete.
"""

from __future__ import annotations

import csv
import itertools
import json
import time
import traceback
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

import numpy as np

from .config import Table, load_toml
from .errors import InputError

CSV_FIELDS = ["case", "status", "error", "whirl_direction", "whirl_frequency_hz", "whirl_onset_s",
              "DE_max_contact_force_n", "NDE_max_contact_force_n", "DE_vertical_min_m", "DE_vertical_max_m",
              "final_rotor_rpm", "energy_dissipated_j", "wall_s"]


def load_sweep(path) -> dict:
    path = Path(path)
    data = load_toml(path)
    try:
        t = Table(data, "")
        base = path.parent / t.string("scenario")
        if not base.is_file():
            raise InputError("scenario", str(base), "file not found")
        mode = t.string("mode", "grid")
        if mode not in ("grid", "monte_carlo"):
            raise InputError("mode", mode, "must be 'grid' or 'monte_carlo'")
        fixed = dict(t.raw("fixed", {}))
        plots = t.boolean("plots", False)
        cases = []
        if mode == "grid":
            grid = t.raw("grid")
            if not isinstance(grid, dict) or not grid:
                raise InputError("grid", grid, "give at least one key = [values]")
            for k, vals in grid.items():
                if not isinstance(vals, list) or not vals:
                    raise InputError(f"grid.{k}", vals, "must be a non-empty list of values")
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
            rng = np.random.default_rng(t.integer("seed", 1, minimum=0))
            keys = list(ranges)
            for k in keys:
                r = ranges[k]
                if not (isinstance(r, dict) and set(r) == {"min", "max"} and r["min"] < r["max"]):
                    raise InputError(f"ranges.{k}", r, "must be {min = a, max = b} with a < b")
            for _ in range(n):
                cases.append({k: float(rng.uniform(ranges[k]["min"], ranges[k]["max"])) for k in keys})
        t.raw("grid" if mode == "monte_carlo" else "ranges", None)
        t.finish()
    except InputError as err:
        raise err.with_file(str(path)) from None
    return {"base": base, "mode": mode, "keys": keys, "fixed": fixed, "cases": cases, "plots": plots}


def _overrides(fixed: dict, case: dict) -> list[str]:
    out = []
    for k, v in list(fixed.items()) + list(case.items()):
        out.append(f"{k}={json.dumps(v) if isinstance(v, str) else repr(v)}")
    return out


def run_case(job) -> dict:
    """Run one case (in a worker); never raises: failures come back as a row."""
    from .run import run_scenario
    from .scenario import load_scenario

    idx, base, overrides, out_dir, plots = job
    row = {"case": idx, "status": "ok", "error": ""}
    folder = Path(out_dir) / "cases" / f"case_{idx:04d}"
    w0 = time.perf_counter()
    try:
        sc = load_scenario(base, overrides)
        s = run_scenario(sc, folder, progress=False, plots=plots)
        row.update(summary_row(s))
        if not s.get("complete", True):
            row["status"], row["error"] = "incomplete", s.get("message", "")
    except Exception as exc:  # a failing case is recorded, the sweep goes on
        row["status"] = "failed"
        row["error"] = f"{type(exc).__name__}: {exc}".replace("\n", " ")
        folder.mkdir(parents=True, exist_ok=True)
        (folder / "error.txt").write_text(traceback.format_exc())
    row["wall_s"] = round(time.perf_counter() - w0, 3)
    return row


def summary_row(s: dict) -> dict:
    b = s.get("bearings", {})
    return {"whirl_direction": s["whirl"]["direction"], "whirl_frequency_hz": s["whirl"]["frequency_hz"],
            "whirl_onset_s": s["whirl"]["onset_s"],
            "DE_max_contact_force_n": b.get("DE", {}).get("max_contact_force_n"),
            "NDE_max_contact_force_n": b.get("NDE", {}).get("max_contact_force_n"),
            "DE_vertical_min_m": b.get("DE", {}).get("vertical_displacement_range_m", [None, None])[0],
            "DE_vertical_max_m": b.get("DE", {}).get("vertical_displacement_range_m", [None, None])[1],
            "final_rotor_rpm": s["speeds"]["final_rotor_rpm"],
            "energy_dissipated_j": s["energy"]["dissipated_total_j"]}


def _finished(out_dir: Path, idx: int):
    f = out_dir / "cases" / f"case_{idx:04d}" / "summary.json"
    if f.is_file():
        s = json.loads(f.read_text())
        if s.get("complete") and "whirl" in s:
            return s
    return None


def run_sweep(path, out_dir, *, workers: int = 1, scheduler: str | None = None) -> list[dict]:
    sw = load_sweep(path)
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    (out / "sweep.json").write_text(json.dumps({"sweep_file": str(path), "base": str(sw["base"]), "mode": sw["mode"],
                                                "keys": sw["keys"], "fixed": sw["fixed"], "cases": sw["cases"]},
                                               indent=2))
    rows: dict[int, dict] = {}
    jobs = []
    for idx, case in enumerate(sw["cases"]):
        done = _finished(out, idx)
        if done is not None:
            rows[idx] = dict(case=idx, status="ok", error="", wall_s=done.get("performance", {}).get("wall_s"),
                             **summary_row(done))
            rows[idx]["skipped"] = True
        else:
            jobs.append((idx, str(sw["base"]), _overrides(sw["fixed"], case), str(out), sw["plots"]))
    if jobs:
        if scheduler:
            from .distributed import map_on_dask

            results = map_on_dask(run_case, jobs, scheduler)
        elif workers > 1:
            with ProcessPoolExecutor(workers) as ex:
                results = list(ex.map(run_case, jobs))
        else:
            results = [run_case(j) for j in jobs]
        for r in results:
            rows[r["case"]] = r
    table = [rows[i] for i in sorted(rows)]
    for r in table:
        r.update({k: sw["cases"][r["case"]][k] for k in sw["keys"]})
    with open(out / "sweep.csv", "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=["case"] + sw["keys"] + CSV_FIELDS[1:], extrasaction="ignore")
        w.writeheader()
        for r in table:
            w.writerow(r)
    plot_whirl_map(table, sw["keys"], out / "whirl_map.png")
    return table


def plot_whirl_map(rows: list[dict], keys: list[str], path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7, 5))
    kx = keys[0]
    ky = keys[1] if len(keys) > 1 else None
    style = {"forward": ("tab:red", "^"), "backward": ("tab:blue", "v"), "none": ("0.5", "o"),
             "failed": ("k", "x")}
    seen = set()
    for r in rows:
        cls = r.get("whirl_direction") if r["status"] == "ok" else "failed"
        cls = cls or "failed"
        c, m = style.get(cls, ("k", "x"))
        x = r[kx]
        y = r[ky] if ky else 0.0
        ax.plot(x, y, m, color=c, ms=10, label=None if cls in seen else cls)
        seen.add(cls)
        if r.get("whirl_frequency_hz"):
            ax.annotate(f"{r['whirl_frequency_hz']:.0f} Hz", (x, y), textcoords="offset points", xytext=(6, 6),
                        fontsize=8)
    ax.set_xlabel(kx)
    ax.set_ylabel(ky or "")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    ax.set_title("whirl class and frequency (DE)")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
