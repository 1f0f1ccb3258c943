"""Session-10 study tool: one landing as N drops from the 5 um circle, with --set overrides.

usage (from the repository root):
    python docs/studies/ensemble.py SCENARIO N [--t-end S] [--tag TAG] [--workers 2] [--rig OVERLAY.toml]
                                    [--out study_out] [--keep-h5] [key=value ...]

Prints every drop (class, bearing, DE and NDE class, frequency, onset, DE displacement and force
ranges) and the ensemble statistics of ``rotorlanding.ensemble``; writes OUT/TAG.json. The drops
run on the project's study runner (``rotorlanding.runner``), as validate's ensembles do.
Used for docs/calibration.md (session 10) and docs/rotor_study_session10.md.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path


def run_drop(job: tuple) -> dict:
    """One drop: ``(scenario, overrides, rig overlay or None, out_dir)`` -> the member result."""
    from rotorlanding.ensemble import member_result
    from rotorlanding.run import run_scenario
    from rotorlanding.scenario import load_scenario

    scenario, sets, rig, out, keep_h5 = (*job, False)[:5]
    sc = load_scenario(scenario, sets, overlays=[rig] if rig else ())
    # ~8 MB of results.h5 per 1.2 s drop: a 1000-drop study would fill a disk (session 14 did)
    s = run_scenario(sc, Path(out), progress=False, plots=False, results=keep_h5)
    return {**member_result(s), "wall_s": s.get("performance", {}).get("wall_s"),
            "nde_direction": (s["whirl"].get("per_bearing") or {}).get("NDE", {}).get("direction")}


def ensemble(scenario, n: int, sets=(), *, rig=None, t_end=None, workers: int = 2, out="study_out",
             tag: str = "x", keep_h5: bool = False) -> dict:
    """The members and statistics of ``n`` drops; also written to ``out/tag.json``."""
    from rotorlanding.ensemble import drop_offsets, ensemble_stats
    from rotorlanding.runner import run_all
    from rotorlanding.safeio import atomic_write_text

    sets = list(sets) + ([f"operating.t_end={t_end}"] if t_end else [])
    jobs = [(str(scenario), sets + extra, rig, str(Path(out) / tag / f"d{k}"), keep_h5)
            for k, extra in enumerate(drop_offsets(n))]
    members = run_all(run_drop, jobs, workers, failures="raise", blas_threads=None)
    result = {"scenario": str(scenario), "overrides": sets, "rig": rig, "members": members,
              "stats": ensemble_stats(members)}
    Path(out).mkdir(parents=True, exist_ok=True)
    atomic_write_text(Path(out) / f"{tag}.json", json.dumps(result, default=float, indent=1))
    return result


def _line(k: int, m: dict) -> str:
    f, d, F = m["frequency_hz"], m["v_disp_range_m"], m["v_force_range_n"]
    return (f"  d{k}: {m['direction']:8s} at {m['bearing']}  DE {m['de_direction']:8s} NDE {m['nde_direction']}  "
            f"f={'-' if f is None else f'{f:.1f}'} Hz  onset={m['onset_s']}  "
            f"disp=[{d[0] * 1e3:.3f}, {d[1] * 1e3:.3f}] mm  F=[{F[0] / 1e3:.2f}, {F[1] / 1e3:.2f}] kN")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("scenario")
    ap.add_argument("n", type=int)
    ap.add_argument("sets", nargs="*", help="--set overrides key=value")
    ap.add_argument("--t-end", type=float, default=None)
    ap.add_argument("--tag", default="x")
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--rig", default=None, help="a rig overlay merged over the scenario (as validate --rig)")
    ap.add_argument("--out", default="study_out")
    ap.add_argument("--keep-h5", action="store_true", help="keep each drop's results.h5 (~8 MB per 1.2 s drop)")
    a = ap.parse_args(argv)
    r = ensemble(a.scenario, a.n, a.sets, rig=a.rig, t_end=a.t_end, workers=a.workers, out=a.out, tag=a.tag,
                 keep_h5=a.keep_h5)
    st = r["stats"]
    print(f"== {a.tag}: {a.scenario} {a.sets} n={a.n}")
    for k, m in enumerate(r["members"]):
        print(_line(k, m))
    print(f"  counts {st['counts']}  DE {st.get('de')}  f {st['frequency_hz']}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
