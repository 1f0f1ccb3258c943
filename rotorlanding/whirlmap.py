"""Whirl-risk map: ``rotorlanding whirl-map MAP.toml``: the probability of each whirl class over two
scenario keys, from several drop directions per cell.

Why: a landing near a whirl threshold is chaotic (``ensemble``): one drop per grid point, as in
``sweep``, gives one class per cell that the next drop may contradict. The designer's question is
"at which speeds and frictions does this machine whirl, and how often?": every cell here is an
ensemble of ``drops`` landings from points of a small circle (``ensemble.drop_offsets``), and the
map gives per cell the share of drops in each class (none / forward / backward / failed), the
median whirl frequency of each whirling class and the median peak contact force.

A map file::

    scenario = "../paper/forward_whirl_landing.toml"   # relative to the map file
    drops = 8                                          # drop directions per cell (default 8)
    drop_radius_m = 5e-6                               # circle radius (default 5 um)
    [fixed]                                            # applied to every drop
    "operating.t_end" = 0.3
    [axes]                                             # exactly two keys, each a list of values
    "operating.speed_rpm" = [3000.0, 5000.0, 7000.0, 10000.0]
    "contact.mu_rad" = [0.1, 0.15, 0.2, 0.3]

Output (``--out``, written atomically): ``whirl_map.json`` (the file's settings, per cell its
counts, probabilities, medians, and the members), ``whirl_map.csv`` (one row per cell) and
``whirl_map.png`` (one panel per class: its probability over the two keys, the forward and
backward panels annotated with the median frequency). Drops run on the runner's worker pool
(``--workers``), the model code and kernels loaded once in the parent before the workers fork,
the rotor reduction cached per worker; a drop writes no results.h5 (a 1000-drop map would be
gigabytes): the members' whirl, peak force and solver statistics are kept in whirl_map.json. A
drop that fails is a ``failed`` member of its cell.
"""

from __future__ import annotations

import csv
import functools
import io
import json
import time
from pathlib import Path
from statistics import median

from .config import override_table, study_file, value_list
from .ensemble import DROP_RADIUS_M, drop_offsets
from .errors import InputError
from .runner import Failure, reduction_cache, run_all, warm_model
from .safeio import atomic_write_text, check_out_dir, save_figure

CLASSES = ("none", "forward", "backward", "failed")


def load_map(path) -> dict:
    with study_file(path) as (path, t):
        base = path.parent / t.string("scenario")
        if not base.is_file():
            raise InputError("scenario", str(base), "file not found")
        drops = t.integer("drops", 8)
        radius = t.number("drop_radius_m", DROP_RADIUS_M, positive=True)
        fixed = override_table(t.raw("fixed", {}), "fixed")
        axes = t.raw("axes")
        if not isinstance(axes, dict) or len(axes) != 2:
            raise InputError("axes", axes, 'must be a table of exactly two scenario keys = [values], e.g. '
                             '"operating.speed_rpm" = [3000, 7000] and "contact.mu_rad" = [0.1, 0.3]')
        for k, vals in axes.items():
            value_list(vals, f"axes.{k}")
        t.finish()
        keys = list(axes)
        _check(base, fixed, keys, axes, drops, radius)
    return {"base": base, "drops": drops, "drop_radius_m": radius, "fixed": fixed, "keys": keys,
            "values": [list(axes[k]) for k in keys]}


def _sets(fixed: dict, cell: dict, offset: list[str]) -> list[str]:
    return [f"{k}={json.dumps(v)}" for k, v in {**fixed, **cell}.items()] + offset


def _check(base: Path, fixed: dict, keys: list[str], axes: dict, drops: int, radius: float = DROP_RADIUS_M) -> None:
    """The fixed overrides, every axis value (alone on top of them) and the first cell are valid
    scenario input: bad input is one line naming the field before any drop runs."""
    from .scenario import load_scenario

    if drops > 1000:
        raise InputError("drops", drops, "must be <= 1000 per cell")
    try:
        load_scenario(base, _sets(fixed, {}, []))
    except InputError as err:
        raise InputError("fixed", fixed, f"invalid for the scenario: {err}") from None
    for k in keys:
        for v in axes[k]:
            try:
                load_scenario(base, _sets(fixed, {k: v}, []))
            except InputError as err:
                raise InputError(f"axes.{k}", v, f"invalid for the scenario: {err}") from None
    first = {k: axes[k][0] for k in keys}
    try:
        load_scenario(base, _sets(fixed, first, []))
    except InputError as err:
        raise InputError("axes", first, f"the first cell is invalid for the scenario: {err}") from None
    try:
        # the first cell's drop from the circle: a radius beyond the clearance failed every drop
        load_scenario(base, _sets(fixed, first, drop_offsets(1, radius)[0]))
    except InputError as err:
        raise InputError("drop_radius_m", radius, f"the drops start outside the first cell's clearance: {err}") from None


def run_drop(job) -> dict:
    """One drop of one cell: its whirl (the landing's, ensemble.member_result), peak contact force,
    steps and solve time; no files."""
    from .ensemble import member_result
    from .run import build_summary, simulate
    from .scenario import load_scenario

    cell, k, base, sets = job
    sc = load_scenario(base, sets)
    spec, t, q, v, stats = simulate(sc, progress=False, reduction=reduction_cache())
    if len(t) < 2:
        raise RuntimeError(f"solver stopped at once: {stats['message']}")
    _, summary = build_summary(sc, spec, t, q, v, stats)
    m = member_result(summary)
    out = {"cell": cell, "drop": k, "direction": m["direction"] if summary["complete"] else "failed",
           "bearing": m["bearing"], "frequency_hz": m["frequency_hz"], "onset_s": m["onset_s"],
           "peak_force_n": max(b["max_contact_force_n"] for b in summary["bearings"].values()),
           "steps": stats["steps"], "solve_s": stats["wall_s"]}
    if not summary["complete"]:
        out["error"] = stats["message"]
    return out


def cell_stats(members: list[dict]) -> dict:
    n = len(members)
    counts = {c: sum(m["direction"] == c for m in members) for c in CLASSES}
    out = {"n": n, "counts": counts, "probability": {c: counts[c] / n for c in CLASSES}}
    for c in ("forward", "backward"):
        f = [m["frequency_hz"] for m in members if m["direction"] == c and m.get("frequency_hz")]
        out[f"{c}_frequency_hz"] = median(f) if f else None
    pk = [m["peak_force_n"] for m in members if m.get("peak_force_n") is not None]
    out["peak_force_n"] = median(pk) if pk else None
    return out


def run_map(path, out_dir, *, workers: int = 2) -> dict:
    mp = load_map(path)
    out = check_out_dir(Path(out_dir))
    offsets = drop_offsets(mp["drops"], mp["drop_radius_m"])
    (kx, ky), (vx, vy) = mp["keys"], mp["values"]
    cells = [(i, j) for i in range(len(vx)) for j in range(len(vy))]
    jobs = [((i, j), k, str(mp["base"]), _sets(mp["fixed"], {kx: vx[i], ky: vy[j]}, off))
            for (i, j) in cells for k, off in enumerate(offsets)]
    wall0 = time.perf_counter()
    warm = functools.partial(warm_model, mp["base"], _sets(mp["fixed"], {kx: vx[0], ky: vy[0]}, []))
    results = run_all(run_drop, jobs, workers, warm=warm)
    wall = time.perf_counter() - wall0
    members: dict = {c: [] for c in cells}
    for job, r in zip(jobs, results):
        if isinstance(r, Failure):
            r = {"cell": job[0], "drop": job[1], "direction": "failed", "error": r.error, "peak_force_n": None}
        members[tuple(r["cell"])].append(r)
    table = []
    for (i, j) in cells:
        st = cell_stats(members[(i, j)])
        table.append({kx: vx[i], ky: vy[j], **st, "members": members[(i, j)]})
    report = {"map_file": str(path), "scenario": str(mp["base"]), "keys": mp["keys"], "values": mp["values"],
              "fixed": mp["fixed"], "drops_per_cell": mp["drops"], "drop_radius_m": mp["drop_radius_m"],
              "drops": len(jobs), "workers": workers, "wall_s": round(wall, 2),
              "drops_per_minute": round(60.0 * len(jobs) / wall, 1), "cells": table}
    atomic_write_text(out / "whirl_map.json", json.dumps(report, indent=2))
    atomic_write_text(out / "whirl_map.csv", _csv(table, kx, ky))
    plot_map(report, out / "whirl_map.png")
    return report


def _csv(table: list[dict], kx: str, ky: str) -> str:
    buf = io.StringIO()
    fields = [kx, ky, "n"] + [f"p_{c}" for c in CLASSES] + ["forward_frequency_hz", "backward_frequency_hz",
                                                             "peak_force_n"]
    w = csv.DictWriter(buf, fieldnames=fields, lineterminator="\n")
    w.writeheader()
    for c in table:
        w.writerow({kx: c[kx], ky: c[ky], "n": c["n"], **{f"p_{k}": c["probability"][k] for k in CLASSES},
                    "forward_frequency_hz": c["forward_frequency_hz"], "backward_frequency_hz": c["backward_frequency_hz"],
                    "peak_force_n": c["peak_force_n"]})
    return buf.getvalue()


def plot_map(report: dict, path) -> None:
    """One panel per class (failed only when a drop failed): its probability per cell over the two
    keys (cells in index order, labelled with the values); forward/backward cells annotated with
    the median whirl frequency. Written atomically (:func:`rotorlanding.safeio.save_figure`)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    kx, ky = report["keys"]
    vx, vy = report["values"]
    classes = [c for c in CLASSES if c != "failed" or any(cl["counts"]["failed"] for cl in report["cells"])]
    # one panel per class, stacked; the width grows with the number of columns so labels stay legible
    w = max(6.0, 0.8 * len(vx) + 2.5)
    fig, axes = plt.subplots(len(classes), 1, figsize=(w, (0.45 * len(vy) + 1.3) * len(classes)), squeeze=False,
                             sharex=True)
    labels = [[f"{v:g}" if isinstance(v, (int, float)) else str(v) for v in vals] for vals in (vx, vy)]
    for ax, c in zip(axes[:, 0], classes):
        P = np.zeros((len(vy), len(vx)))
        for cell in report["cells"]:
            P[vy.index(cell[ky]), vx.index(cell[kx])] = cell["probability"][c]
        im = ax.imshow(P, origin="lower", vmin=0.0, vmax=1.0, cmap="viridis", aspect="auto")
        for cell in report["cells"]:
            p = cell["probability"][c]
            if p == 0.0:
                continue  # empty cells stay dark and unlabelled
            txt = f"{p:.2f}"
            f = cell.get(f"{c}_frequency_hz")
            if f:
                txt += f"\n{f:.0f} Hz"
            ax.text(vx.index(cell[kx]), vy.index(cell[ky]), txt, ha="center", va="center", fontsize=6.5,
                    color="w" if p < 0.6 else "k")
        ax.set_xticks(range(len(vx)), labels[0], fontsize=7)
        ax.set_yticks(range(len(vy)), labels[1], fontsize=7)
        ax.set_ylabel(ky, fontsize=8)
        ax.set_title(f"P({c})", fontsize=9)
    axes[-1, 0].set_xlabel(kx, fontsize=8)
    fig.colorbar(im, ax=axes[:, 0].tolist(), shrink=0.9, label="probability over drop directions")
    fig.suptitle(f"whirl class per cell, {report['drops_per_cell']} drops each "
                 f"({report['drop_radius_m'] * 1e6:g} um circle); frequency: median of that class", fontsize=9)
    path = Path(path)
    try:
        save_figure(fig, path, dpi=110)
    finally:
        plt.close(fig)
