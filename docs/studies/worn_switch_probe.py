"""Does any worn DE bearing inside its bound give Table 1's switch on the rig rotor? (issue 15, point 2;
session 30).

On the session-30 rotor the adopted worn fit (scenarios/calibration/worn_bearing.toml, scored on the
mu_rad 0.3 landing only) whirls backward in 32 of 32 drops at mu_rad 0.3, but also in 10 of 32 at 0.15:
the switch's calm side fails. This probe lands the backward scenario at both frictions over a grid of
the worn drag's two unknowns (torque across its search range 2.0-5.1 N m, growth angle across 40-300
rad), everything else as adopted, and counts the drops of each class; the switch holds where the 0.15
side is calm and the 0.3 side backward in >= 7 of 8 (validate's share) of the drops.

    python docs/studies/worn_switch_probe.py [--out docs/studies/worn_switch_probe] [--drops 16] [--workers 2]
        [--torques 2.2,3.0,3.6,4.4,5.0] [--angles 60,220] [--bearing DE|NDE]

Writes OUT/worn_switch_probe.json and .md (atomically). About 5 min on 2 cores with 16 drops and the
default grid. Session 30's runs: the default grid (stored in docs/studies/worn_switch_probe/), and
``--torques 2.6,2.9 --angles 230 --drops 32 --out docs/studies/worn_switch_probe/near_fit`` (about 2 min), and the
NDE bearing worn instead (the DE healthy; the NDE carries 705 N of this rotor, the DE 248 N):
``--bearing NDE --torques 3,6,9 --angles 220 --out docs/studies/worn_switch_probe/nde`` and, with 32 drops,
``--bearing NDE --torques 8,10,12 --angles 220 --drops 32 --out docs/studies/worn_switch_probe/nde_32``.
"""

from __future__ import annotations

import argparse
import json
import sys
from collections import Counter
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))

TORQUES_NM = (2.2, 3.0, 3.6, 4.4, 5.0)
ANGLES_RAD = (60.0, 220.0)
FRICTIONS = (0.15, 0.3)
SCENARIO = ROOT / "scenarios" / "paper" / "backward_whirl_landing.toml"


def land(job):
    from rotorlanding.postprocess import evaluate, summarize
    from rotorlanding.run import simulate
    from rotorlanding.scenario import load_scenario

    key, sets = job
    sc = load_scenario(SCENARIO, sets)
    spec, t, q, v, info = simulate(sc, progress=False)
    w = summarize(spec, t, evaluate(spec, t, q, v))["whirl"]
    return key, w["direction"], w.get("onset_s")


def main(argv=None) -> int:
    from rotorlanding.ensemble import drop_offsets
    from rotorlanding.safeio import atomic_write_text
    from rotorlanding.validate import class_need

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default=str(ROOT / "docs" / "studies" / "worn_switch_probe"))
    ap.add_argument("--drops", type=int, default=16)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--torques", default=",".join(f"{x:g}" for x in TORQUES_NM), help="worn drag torques [N m]")
    ap.add_argument("--angles", default=",".join(f"{x:g}" for x in ANGLES_RAD), help="growth angles [rad]")
    ap.add_argument("--bearing", choices=("DE", "NDE"), default="DE",
                    help="the worn bearing (the other healthy: worn_drag_torque 0)")
    a = ap.parse_args(argv)
    torques = [float(x) for x in a.torques.split(",")]
    angles = [float(x) for x in a.angles.split(",")]
    jobs = []
    for tw in torques:
        for ang in angles:
            for mu in FRICTIONS:
                other = "NDE" if a.bearing == "DE" else "DE"
                base = [f"bearings.{a.bearing}.worn_drag_torque={tw}", f"bearings.{a.bearing}.worn_drag_growth_angle={ang}",
                        f"bearings.{other}.worn_drag_torque=0.0", f"contact.mu_rad={mu}"]
                jobs += [((tw, ang, mu), base + d) for d in drop_offsets(a.drops)]
    res: dict = {}
    with ProcessPoolExecutor(a.workers) as ex:
        for key, direction, onset in ex.map(land, jobs):
            res.setdefault(key, []).append({"direction": direction, "onset_s": onset})
    need = class_need(a.drops)
    rows = []
    for tw in torques:
        for ang in angles:
            calm = Counter(m["direction"] for m in res[(tw, ang, 0.15)])
            worn = Counter(m["direction"] for m in res[(tw, ang, 0.3)])
            rows.append({"torque_nm": tw, "growth_angle_rad": ang, "mu_0.15": dict(calm), "mu_0.3": dict(worn),
                         "switch": calm.get("none", 0) >= need and worn.get("backward", 0) >= need})
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    atomic_write_text(out / "worn_switch_probe.json", json.dumps({"bearing": a.bearing, "drops": a.drops, "rows": rows},
                                                                 indent=2))
    lines = [f"# Worn {a.bearing} bearing against Table 1's switch ({a.drops} drops per cell; switch: calm at mu_rad 0.15 "
             f"and backward at 0.3 in >= {need} of {a.drops})", "",
             "| T_w [N m] | growth angle [rad] | mu_rad 0.15 | mu_rad 0.3 | switch |", "|---|---|---|---|---|"]
    for r in rows:
        def fmt(c):
            return ", ".join(f"{k} {v}" for k, v in sorted(c.items(), key=lambda kv: -kv[1]))
        lines.append(f"| {r['torque_nm']:g} | {r['growth_angle_rad']:g} | {fmt(r['mu_0.15'])} | {fmt(r['mu_0.3'])} | "
                     f"{'yes' if r['switch'] else 'no'} |")
    atomic_write_text(out / "worn_switch_probe.md", "\n".join(lines) + "\n")
    print("\n".join(lines))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
