"""Session-14 study: the motor coupling's lateral stiffness k_c in the landings (issue 15).

usage (from the repository root):
    python docs/studies/coupling_landings.py [--n 32] [--k 0,5e5,1e6,2e6,2.5e6,4e6] [--out study_out/coupling]
                                             [--cases fwd3000,...] [--tag T --set key=value ...]

For each k_c (`rotor.supports.2.kyy/kzz`, the rig rotor's `coupling` support, in_landing) it
  1. lets the non-rotating rotor settle on its catcher bearings and prints the static loads
     (DE / NDE contact, coupling spring) and the coupling hub's drop;
  2. lands the paper's five cases as validate does (N drops from the 5 um circle each): the
     forward whirl at 3000 / 7000 / 10000 rpm, the no-whirl landing, the worn bearing at
     mu_rad 0.3 and at 0.15 (the Table 1 switch), and prints the DE journal's class counts, the
     median frequency of the whirling drops and the median DE displacement / force ranges.
Writes OUT/k<k>_<case>.json per ensemble (resumable: an existing file is read, not re-run).
Results: docs/calibration.md, "Session 14".
"""

from __future__ import annotations

import argparse
import importlib.util
import json
import statistics
import sys
from collections import Counter
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
CASES = {  # name: (scenario, extra overrides)
    "fwd3000": ("scenarios/paper/forward_whirl_3000rpm.toml", []),
    "fwd7000": ("scenarios/paper/forward_whirl_landing.toml", []),
    "fwd10000": ("scenarios/paper/forward_whirl_10000rpm.toml", []),
    "nowhirl": ("scenarios/paper/no_whirl_landing.toml", []),
    "worn_mu0.3": ("scenarios/paper/backward_whirl_landing.toml", []),
    "worn_mu0.15": ("scenarios/paper/backward_whirl_landing.toml", ["contact.mu_rad=0.15"]),
}


def _ensemble_module():
    spec = importlib.util.spec_from_file_location("ensemble_study", Path(__file__).with_name("ensemble.py"))
    mod = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = mod  # the forked workers unpickle its run_drop by this name
    spec.loader.exec_module(mod)
    return mod


def coupling_sets(k: float) -> list[str]:
    return [f"rotor.supports.2.kyy={k}", f"rotor.supports.2.kzz={k}"]


def static_loads(k: float, sets=()) -> dict:
    """Rest on the catcher bearings without spin (0.6 s, rotor damped): contact loads and the
    coupling spring's share of the weight."""
    from rotorlanding.postprocess import evaluate
    from rotorlanding.run import simulate
    from rotorlanding.scenario import load_scenario
    from rotorlanding.timoshenko import GRAVITY

    from dataclasses import replace

    sc = load_scenario(ROOT / "scenarios/landing_7000rpm.toml",
                       coupling_sets(k) + list(sets) + ["operating.speed_rpm=0", "operating.t_end=0.6", "effects.windage=false"])
    # damped (as tests/test_landing_supports.py) so that the rotor comes to rest instead of rocking
    sc = replace(sc, rotor=replace(sc.rotor, mass_proportional_damping=40.0))
    spec, t, q, v, info = simulate(sc, progress=False)
    series = evaluate(spec, t, q, v)
    node = spec.fe.station_nodes["coupling"]
    last = t > 0.5  # means over the last 0.1 s
    z_c = float((q[last, :spec.n_lat] @ spec.cb.T[4 * node + 1]).mean())
    out = {b.name: float(series[f"{b.name}_contact_force_z_n"][last].mean()) for b in spec.bearings}
    out.update(coupling_n=-k * z_c, hub_drop_mm=-z_c * 1e3, weight_n=spec.rotor_mass * GRAVITY)
    return out


def row(members: list) -> str:
    med = lambda xs: statistics.median(xs) if xs else None  # noqa: E731
    c = Counter(m["de_direction"] for m in members)
    f = med([m["frequency_hz"] for m in members if m["de_direction"] != "none" and m["frequency_hz"]])
    d = [med([m["v_disp_range_m"][i] for m in members]) for i in (0, 1)]
    F = [med([m["v_force_range_n"][i] for m in members]) for i in (0, 1)]
    counts = ", ".join(f"{k} {v}" for k, v in sorted(c.items()))
    return (f"{counts}; {'-' if f is None else f'{f:.1f} Hz'}; {d[0] * 1e3:.3f} / {d[1] * 1e3:.3f} mm; "
            f"{F[0] / 1e3:.2f} / {F[1] / 1e3:.2f} kN")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=32)
    ap.add_argument("--k", default="0,5e5,1e6,2e6,2.5e6,4e6", help="coupling stiffnesses [N/m], comma separated")
    ap.add_argument("--cases", default=",".join(CASES))
    ap.add_argument("--out", default="study_out/coupling")
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--tag", default="", help="prefix of the ensemble files (for runs with --set overrides)")
    ap.add_argument("--set", dest="sets", action="append", default=[], help="override for every case (key=value)")
    a = ap.parse_args(argv)
    ens = _ensemble_module()
    out = Path(a.out)
    for ks in a.k.split(","):
        k = float(ks)
        s = static_loads(k, a.sets)
        print(f"k_c = {k:.3g} N/m: at rest DE {s['DE']:.0f} N, NDE {s['NDE']:.0f} N, coupling {s['coupling_n']:.0f} N "
              f"(weight {s['weight_n']:.0f} N), hub {s['hub_drop_mm']:.3f} mm below the levitated axis", flush=True)
        for name in a.cases.split(","):
            scenario, extra = CASES[name]
            tag = f"{a.tag}k{ks}_{name}"
            path = out / f"{tag}.json"
            if path.exists():
                members = json.loads(path.read_text())["members"]
            else:
                members = ens.ensemble(ROOT / scenario, a.n, coupling_sets(k) + a.sets + extra, workers=a.workers,
                                       out=str(out), tag=tag)["members"]
            print(f"  {name:12s} DE: {row(members)}", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
