"""Session-15 study: which catcher bearing is worn decides the Table 1 switch (issue 15).

usage (from the repository root):
    python docs/studies/worn_location.py [--n 32] [--where both,DE,NDE] [--mu 0.15,0.3]
                                         [--torques 3.41] [--out study_out/worn_location] [key=value ...]

The backward-whirl landing (`scenarios/paper/backward_whirl_landing.toml`, the worn bearing's drag
T_w and growth angle as that file has them unless --torques is given) with the worn drag on both
bearings, on the DE alone or on the NDE alone, each at mu_rad 0.15 and 0.3, N drops from the 5 um
circle. For each case it prints the class counts of the drops (any bearing), the DE journal's class
counts and the median frequency of the DE's whirling drops.

It also prints the static argument (docs/calibration.md, "Session 15"): a worn race at rest is
carried by the sleeve when the friction torque the bearing's static load W can pass exceeds the
worn drag, mu_rad r_i W > T_w, i.e. above mu* = T_w / (r_i W). With mu* between 0.15 and 0.3 or
above both, the race stalls at rest at 0.15; below 0.15 it is carried at rest at both frictions and
nothing distinguishes them.
Writes OUT/<where>_T<T>_mu<mu>.json per ensemble (resumable: an existing file is read, not re-run).
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
SCENARIO = ROOT / "scenarios/paper/backward_whirl_landing.toml"


def _sibling(name: str):
    spec = importlib.util.spec_from_file_location(f"{name}_study", Path(__file__).with_name(f"{name}.py"))
    mod = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = mod  # the forked workers unpickle its functions by this name
    spec.loader.exec_module(mod)
    return mod


def worn_drag(sc_raw: dict) -> tuple[float, float]:
    """The scenario's worn torque [N m] and growth angle [rad], from whichever bearing carries them."""
    b = sc_raw["bearings"]
    src = b["DE"] if b["DE"].get("worn_drag_torque", 0.0) > 0 else b["NDE"]
    return src["worn_drag_torque"], src["worn_drag_growth_angle"]


def worn_sets(where: str, torque: float | None, sc_raw: dict) -> list[str]:
    """Overrides that put the worn drag on ``where`` (both / DE / NDE), with the scenario's (or the
    given) torque and growth angle on the worn bearing(s) and no worn drag on the other."""
    t, g = worn_drag(sc_raw)
    t = t if torque is None else torque
    sets = []
    for name in ("DE", "NDE"):
        on = where in ("both", name)
        sets += [f"bearings.{name}.worn_drag_torque={t if on else 0.0}",
                 f"bearings.{name}.worn_drag_growth_angle={g}"]
    return sets


def row(members: list) -> str:
    c = Counter(m["direction"] for m in members)
    de = Counter(m["de_direction"] for m in members)
    f = [m["frequency_hz"] for m in members if m["de_direction"] != "none" and m["frequency_hz"]]
    fs = f"{statistics.median(f):.1f} Hz" if f else "-"
    return (f"calm {c.get('none', 0)}/{len(members)}, backward {c.get('backward', 0)}, forward "
            f"{c.get('forward', 0)}; DE backward {de.get('backward', 0)}, DE whirl {fs}")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("sets", nargs="*", help="further --set overrides key=value")
    ap.add_argument("--n", type=int, default=32)
    ap.add_argument("--where", default="both,DE,NDE")
    ap.add_argument("--mu", default="0.15,0.3")
    ap.add_argument("--torques", default=None, help="comma list of T_w [N m]; default: the scenario's")
    ap.add_argument("--out", default="study_out/worn_location")
    ap.add_argument("--workers", type=int, default=2)
    a = ap.parse_args(argv)
    from rotorlanding.scenario import load_scenario

    ens = _sibling("ensemble")
    loads = _sibling("coupling_landings").static_loads(0.0)
    raw = load_scenario(SCENARIO).raw
    r_i = {n: raw["bearings"][n]["sleeve_radius"] + raw["bearings"][n]["clearance"] for n in ("DE", "NDE")}
    torques = [None] if a.torques is None else [float(x) for x in a.torques.split(",")]
    out = Path(a.out)
    for t in torques:
        t_w = worn_drag(raw)[0] if t is None else t
        print(f"T_w = {t_w:.3g} N m; static loads DE {loads['DE']:.0f} N, NDE {loads['NDE']:.0f} N; "
              + ", ".join(f"mu* {n} = T_w / (r_i W) = {t_w / (r_i[n] * loads[n]):.3f}" for n in ("DE", "NDE")))
        for where in a.where.split(","):
            for mu in a.mu.split(","):
                tag = f"{where}_T{t_w:.3g}_mu{mu}"
                f = out / f"{tag}.json"
                if f.is_file():
                    members = json.loads(f.read_text())["members"]
                else:
                    sets = worn_sets(where, t, raw) + [f"contact.mu_rad={mu}"] + list(a.sets)
                    members = ens.ensemble(SCENARIO, a.n, sets, workers=a.workers, out=str(out), tag=tag)["members"]
                print(f"  worn {where:4s} mu_rad {mu}: {row(members)}", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
