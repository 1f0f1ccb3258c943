"""Step-size convergence of the landing model (run on demand, not in CI).

For a scenario and a list of steps, runs the landing and prints/stores peak contact force and
whirl frequency per step, and the change when the step is halved. The acceptance rule of the
landing model: halving the step changes the peak contact force by < 5 % and the whirl frequency
by < 1 %.

usage: python benchmarks/step_convergence.py SCENARIO.toml --t-end 0.5 --steps 5e-5,2.5e-5,1.25e-5
       [--set key=value ...] [--json out.json]
"""

from __future__ import annotations

import argparse
import json
import sys
import time

from rotorlanding.postprocess import evaluate, summarize
from rotorlanding.run import simulate
from rotorlanding.scenario import load_scenario


def main(argv=None):
    ap = argparse.ArgumentParser()
    ap.add_argument("scenario")
    ap.add_argument("--t-end", type=float, default=0.5)
    ap.add_argument("--steps", default="5e-5,2.5e-5,1.25e-5")
    ap.add_argument("--set", action="append", default=[])
    ap.add_argument("--json")
    a = ap.parse_args(argv)
    rows = []
    for h in [float(s) for s in a.steps.split(",")]:
        sc = load_scenario(a.scenario, a.set + [f"operating.t_end={a.t_end}", f"solver.step={h}",
                                                f"solver.output_period={max(h, 2e-5)}"])
        w0 = time.perf_counter()
        spec, t, q, v, info = simulate(sc, progress=False)
        s = summarize(spec, t, evaluate(spec, t, q, v))
        rows.append({"step_s": h, "complete": info["complete"], "wall_s": time.perf_counter() - w0,
                     "solver_wall_per_sim_s": info["wall_s"] / a.t_end,
                     "peak_force_n": max(b["max_contact_force_n"] for b in s["bearings"].values()),
                     "whirl": s["whirl"]["direction"], "whirl_hz": s["whirl"]["frequency_hz"],
                     "energy_error": s["energy"]["balance_error_relative"]})
        r = rows[-1]
        print(f"h={h:.3g} s: {r['solver_wall_per_sim_s']:.2f} s/s, peak {r['peak_force_n']:.0f} N, whirl "
              f"{r['whirl']} {r['whirl_hz']}, energy error {100 * r['energy_error']:.3f} %", flush=True)
    for coarse, fine in zip(rows[:-1], rows[1:]):
        df = abs(coarse["peak_force_n"] - fine["peak_force_n"]) / fine["peak_force_n"]
        dw = (abs(coarse["whirl_hz"] - fine["whirl_hz"]) / fine["whirl_hz"]
              if coarse["whirl_hz"] and fine["whirl_hz"] else None)
        coarse["peak_force_change_on_halving"] = df
        coarse["whirl_change_on_halving"] = dw
        print(f"h={coarse['step_s']:.3g} -> {fine['step_s']:.3g}: peak force change {100 * df:.2f} %, whirl "
              f"frequency change {'n/a' if dw is None else f'{100 * dw:.2f} %'}")
    if a.json:
        with open(a.json, "w") as fh:
            json.dump(rows, fh, indent=2)
    return 0


if __name__ == "__main__":
    sys.exit(main())
