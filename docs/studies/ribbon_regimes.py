"""The ribbon's hold on the forward whirl on a bending and on a nearly rigid rotor (issue 15, session 37;
docs/calibration.md "Session 37").

The paper: "in the event of a full circular whirl mode, the ribbon characteristics greatly influence the
frequency of the whirl motion". On the rig rotor (its landed whirl a bending mode) K_rib x1.5 moves the
7000 rpm whirl by 2 % (validate's ribbon check). Here the same combined landing (8 drops from the 5 um
circle, ``docs/studies/ensemble.py``) on three rotors, each with K_rib x0.5 / x1 / x1.5 at 7000 rpm and at
3000 and 10000 rpm:

- ``rig``: scenarios/rig_rotor.toml as it is;
- ``rigid``: the same rotor nearly rigid: main shaft 70 mm (its bound's top) and the modulus 1.2e12 Pa
  (the tool's limit; not a steel: a probe of the regime, not a design);
- ``heavy``: ``rigid`` with the density x1.6 (12560 kg/m^3), 1.6 times the mass and inertia;
- ``S:N`` (``--screened S:N ...``): rotor N of seed S of ``ribbon_rise_screen.py``'s stored run, its drawn
  values and the stations they put (as that screen assembles it).

    python docs/studies/ribbon_regimes.py [--n 8] [--workers 2] [--out DIR] [--rotors rig,rigid,heavy]
                                          [--screened S:N ...] [--screen-json PATH]

About 4 min on 2 cores for the three built-in rotors. Prints one table (medians over the drops) and writes DIR/TAG.json
per ensemble.
"""

from __future__ import annotations

import argparse
import json
import statistics
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "docs" / "studies"))

SCENARIO = ROOT / "scenarios" / "paper" / "forward_whirl_landing.toml"
ROTORS = {
    "rig": [],
    "rigid": ["rotor.materials.steel.youngs_modulus=1.2e12", "rotor.sections.3.outer_diameter=0.07"],
    "heavy": ["rotor.materials.steel.youngs_modulus=1.2e12", "rotor.sections.3.outer_diameter=0.07",
              "rotor.materials.steel.density=12560"],
}
#: the table's rows: ribbon_landing_screen.py's cases (one definition of their overrides), labelled
LABELS = {"7000": "7000 rpm", "7000_k05": "7000 rpm, K_rib x0.5", "7000_k15": "7000 rpm, K_rib x1.5",
          "3000": "3000 rpm", "10000": "10000 rpm"}


def screened_sets(screen_json: Path, pick: str) -> list[str]:
    """``key=value`` overrides that land rotor ``pick`` ("seed:sample") of the ribbon screen's run."""
    import rotor_rise_screen as rrs

    seed, sample = (int(x) for x in pick.split(":"))
    rows = json.loads(screen_json.read_text())["rows"]
    v = next(r["vals"] for r in rows if r["seed"] == seed and r["sample"] == sample)
    st = rrs.stations(v["rotor.sections.0.length"], v["rotor.sections.3.length"], v["rotor.sections.6.length"])
    sets = [f"{k}={x:.6g}" for k, x in v.items()]
    sets += [f"rotor.stations.{k}={x:.6g}" for k, x in st.items()]
    sets += [f"rotor.disks.{j}.position={st[name]:.6g}"
             for j, name in enumerate(("NDE_AMB", "DE_AMB", "thrust_disk", "coupling"))]
    return sets


def row(rotor: str, case: str, d: dict) -> str:
    ms = d["members"]
    de = {}
    for m in ms:
        de[m.get("de_direction") or "none"] = de.get(m.get("de_direction") or "none", 0) + 1
    f_de = [m["de_frequency_hz"] for m in ms if m.get("de_direction") == "forward" and m.get("de_frequency_hz")]
    f_any = [m["frequency_hz"] for m in ms if m.get("direction") == "forward" and m.get("frequency_hz")]
    med = lambda xs: statistics.median(xs) if xs else float("nan")  # noqa: E731
    disp = [med([m["v_disp_range_m"][i] for m in ms]) * 1e3 for i in (0, 1)]
    force = [med([m["v_force_range_n"][i] for m in ms]) / 1e3 for i in (0, 1)]
    amb = [med([m["span_peak_m"][s] for m in ms]) * 1e3 for s in ("NDE_AMB", "DE_AMB")]
    classes = ", ".join(f"{k} {v}" for k, v in sorted(de.items()))
    return (f"| {rotor} | {case} | {classes} | {med(f_de):.1f} | {med(f_any):.1f} | {disp[0]:.3f} / {disp[1]:+.3f} | "
            f"{force[0]:.2f} / {force[1]:+.2f} | {amb[0]:.3f} / {amb[1]:.3f} |")


def main(argv=None) -> int:
    from ensemble import ensemble
    from ribbon_landing_screen import CASES

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=8)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--out", default="study_out/ribbon_regimes")
    ap.add_argument("--rotors", default="rig,rigid,heavy", help="of the built-in rotors, comma separated ('' none)")
    ap.add_argument("--screened", nargs="*", default=[], help="seed:sample of ribbon_rise_screen.py's run")
    ap.add_argument("--screen-json", default=str(ROOT / "docs" / "studies" / "ribbon_rise_screen" / "candidates.json"))
    a = ap.parse_args(argv)
    rotors = {k: ROTORS[k] for k in a.rotors.split(",") if k}
    rotors.update({p: screened_sets(Path(a.screen_json), p) for p in a.screened})
    lines = ["| rotor | landing | DE journal (drops) | DE forward f [Hz] | forward whirl f, either journal [Hz] | "
             "DE vertical displacement min / max [mm] | DE vertical force on the rotor min / max [kN] | "
             "peak excursion at NDE_AMB / DE_AMB [mm] |", "|---|---|---|---|---|---|---|---|"]
    for rotor, rsets in rotors.items():
        for key, case in LABELS.items():
            tag = f"{rotor.replace(':', '_')}_{case.replace(' ', '').replace(',', '_').replace('.', '')}"
            ensemble(str(SCENARIO), a.n, [*rsets, *CASES[key]], workers=a.workers, out=a.out, tag=tag)
            d = json.loads((Path(a.out) / f"{tag}.json").read_text())
            lines.append(row(rotor, case, d))
            print(lines[-1], flush=True)
    print("\n".join(lines))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
