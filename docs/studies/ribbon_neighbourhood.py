"""The neighbourhoods of the two rotors nearest to passing every check at once (issue 15, session 38;
docs/calibration.md "Session 38").

Session 37's funnel (``ribbon_landing_screen.py --funnel`` / ``--funnel-pass``) found no rotor that passes Fig. 39 at
all three speeds, the ribbon check, the calm landing and Table 1's backward frequency together. Two came within
one check: 11:771 (all but the ribbon) and 12:1018 (all but Fig. 39 at 10000 rpm). The backward whirl's landed
frequency follows no linear mode (correlation 0.29), so a wider random draw reaches Table 1's band by luck; near a
rotor that already has it, the chance should be better. This script draws children around each parent:

- every drawn value of ``rotor_rise_screen.DRAWN`` (main shaft over 35-70 mm, as ``ribbon_rise_screen.py``) and
  the thrust disk's and hub's annuli moved by a normal step of ``--sigma`` times its bound's width, clipped to the
  bound (the NDE AMB stack stays the DE's, as in the screens);
- the same modal screen as ``ribbon_rise_screen.py`` (the first forward landed mode at the three speeds and with
  K_rib x0.5 / x1.5 in the chain);
- kept: rise >= 1.31, Fig. 39 by the mode (x 0.95 within 10 %) and a modal ribbon move >= 7.4 %, ranked by the modal distance to Fig. 39; the best
  ``--keep`` of each parent written as DIR/children.json (``ribbon_rise_screen`` rows, seed = parent's seed and
  sample run together, e.g. 11771), which ``ribbon_landing_screen.py --funnel`` / ``--funnel-pass`` land:

    python docs/studies/ribbon_neighbourhood.py [--children 600] [--sigma 0.06] [--keep 60] [--out DIR]
    python docs/studies/ribbon_landing_screen.py --funnel --screen-json DIR/children.json --out DIR
    python docs/studies/ribbon_landing_screen.py --funnel-pass --screen-json DIR/children.json --out DIR
    python docs/studies/ribbon_neighbourhood.py --report --out DIR   (the six checks and the table rows, per child)

The ribbon's damping on the five-check children (session 38; stored in docs/studies/ribbon_neighbourhood/c_rib/C/):

    python docs/studies/ribbon_landing_screen.py --funnel --screen-json DIR/children.json --out DIR_C \
        --rotors 11771:12,11771:335,11771:260,11771:255,11771:270,11771:186 \
        --set bearings.DE.c_rib=C --set bearings.NDE.c_rib=C      (then --funnel-pass with the same options;
    --n 32 --keep-all --rotors 11771:12 for the 32-drop check of the one that passes on 8)

Seeded (``--seed``): the same command draws the same children. The modal part takes about 4 min on 2 cores.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "docs" / "studies"))

import ribbon_rise_screen as rib  # noqa: E402
import rotor_rise_screen as rrs  # noqa: E402

WEAK = ROOT / "docs" / "studies" / "ribbon_rise_screen" / "weak.json"
PARENTS = ("11:771", "12:1018")
#: the bounds the children stay in: the screens' (main shaft 35-70 mm as ribbon_rise_screen draws it)
BOUNDS = {**rrs.DRAWN, "rotor.sections.3.outer_diameter": (0.035, 0.07),
          "thrust_od": rrs.DRAWN_GEOM["thrust", 0], "thrust_t": rrs.DRAWN_GEOM["thrust", 2],
          "hub_od": rrs.DRAWN_GEOM["hub", 0], "hub_id": rrs.DRAWN_GEOM["hub", 1], "hub_l": rrs.DRAWN_GEOM["hub", 2]}
RIB_MIN = 0.074  # modal ribbon move kept: the check's 10 % over the landed / modal ratio 1.36 (session 37)
THRUST_ID = 0.05  # m: the sampler's fixed bore of the thrust disk


def annuli_of(v: dict) -> dict:
    """The thrust disk's and hub's annulus dimensions [m] behind a row's masses and inertias (the inverse of
    ``rotor_rise_screen.annulus``): outer^2 + inner^2 = 8 Ip / m, L^2 = 12 (It - Ip / 2) / m."""
    m, ip = v["rotor.disks.2.mass"], v["rotor.disks.2.polar_inertia"]
    od = math.sqrt(8 * ip / m - THRUST_ID ** 2)
    t = m / (rrs.RHO * math.pi / 4 * (od * od - THRUST_ID ** 2))
    m3, ip3, it3 = (v[f"rotor.disks.3.{k}"] for k in ("mass", "polar_inertia", "transverse_inertia"))
    s = 8 * ip3 / m3
    length = math.sqrt(12 * (it3 - ip3 / 2) / m3)
    d = m3 / (rrs.RHO * math.pi / 4 * length)  # outer^2 - inner^2
    return {"thrust_od": od, "thrust_t": t, "hub_od": math.sqrt((s + d) / 2), "hub_id": math.sqrt((s - d) / 2),
            "hub_l": length}


def values(x: dict) -> dict:
    """A row's ``vals`` from the drawn values and annuli of ``x`` (the sampler's masses and inertias)."""
    v = {k: x[k] for k in rrs.DRAWN}
    geom = {0: (v["rotor.disks.1.outer_diameter"], 0.07, v["rotor.disks.1.thickness"]),
            2: (x["thrust_od"], THRUST_ID, x["thrust_t"]), 3: (x["hub_od"], x["hub_id"], x["hub_l"])}
    for j, g in geom.items():
        v[f"rotor.disks.{j}.mass"], v[f"rotor.disks.{j}.polar_inertia"], v[f"rotor.disks.{j}.transverse_inertia"] = rrs.annulus(*g)
    return v


def children(parent: dict, n: int, sigma: float, seed: int) -> list[dict]:
    x0 = {**{k: parent["vals"][k] for k in rrs.DRAWN}, **annuli_of(parent["vals"])}
    rng = np.random.default_rng(seed)
    out = []
    for _ in range(n):
        x = {k: float(np.clip(x0[k] + sigma * (b - a) * rng.standard_normal(), a, b)) for k, (a, b) in BOUNDS.items()}
        out.append(values(x))
    return out


def analyse_batch(args) -> list[dict]:
    from rotorlanding.config import load_toml

    tag, batch = args
    base = load_toml(ROOT / "scenarios" / "rig_rotor.toml")
    out = []
    for i, v in batch:
        try:
            out.append({"seed": tag, "sample": i, "vals": v, **rib.analyse(base, v)})
        except Exception as exc:  # a rotor the model refuses is listed, not counted
            out.append({"seed": tag, "sample": i, "vals": v, "error": str(exc)})
    return out


def fig39_distance(r: dict) -> float:
    return sum(abs(rib.LOCK * f / t - 1) for f, t in zip(r["modes_hz"], rib.TARGET_HZ))


#: the table rows a landing reads beside the six checks: (label, ensemble, stats key, index, experiment, band, scale)
#: (validate.TABLE_ROWS with the bands of its report: the larger of 10 % and the paper's own error)
TABLE = [("T1 disp max [mm]", "bw", "v_disp_range_m", 1, 0.2, 0.05, 1e3),
         ("T1 disp min [mm]", "bw", "v_disp_range_m", 0, -0.4, 0.12, 1e3),
         ("T1 onset [s]", "bw", "onset_s", None, 0.4, 0.04, 1.0),
         ("T2 disp max [mm]", "7000", "v_disp_range_m", 1, 0.15, 0.05, 1e3),
         ("T2 disp min [mm]", "7000", "v_disp_range_m", 0, -0.3, 0.03, 1e3),
         ("T2 force max [kN]", "7000", "v_force_range_n", 1, 4.5, 0.45, 1e-3),
         ("T2 force min [kN]", "7000", "v_force_range_n", 0, -0.5, 1.0, 1e-3)]
AMB = ("NDE_AMB", "DE_AMB")
AMB_GAP_M = 0.4e-3  # scenarios/rig/rig.toml [limits] close_clearances_m


def report(out: Path) -> int:
    """The landed children (``ribbon_landing_screen.py --funnel-pass``): the six checks, the table rows above from
    the stored ensembles, and the largest AMB excursion (median over the drops, largest over the landings)."""
    import statistics

    sys.path.insert(0, str(ROOT / "docs" / "studies"))
    from ribbon_landing_screen import _records, in_table1_band
    from rotorlanding.validate import JOINT_CHECKS as checks  # Fig. 39 x3, the ribbon, the calm landing

    funnel = {b["rotor"]: b for b in _records(out / "funnel.jsonl")}
    recs = _records(out / "funnel_landed.jsonl")
    rows = []
    for rec in recs:
        seed, sample = rec["rotor"].split(":")
        runs = {case: json.loads((out / "runs" / f"{seed}_{sample}_{case}.json").read_text())
                for case in ("bw", "7000", "7000_k05", "7000_k15", "10000", "3000", "nowhirl")}
        vals = []
        for _, case, key, i, ref, band, scale in TABLE:
            x = runs[case]["stats"].get(key)
            x = None if x is None else (x[i] if i is not None else x) * scale
            vals.append((x, x is not None and abs(x - ref) <= band))
        amb = max(statistics.median(m["span_peak_m"][st] for m in r["members"]) for r in runs.values() for st in AMB)
        b = funnel[rec["rotor"]]
        ok = [bool(rec[k]) for k in checks] + [in_table1_band(b)]  # the funnel's filter, unless --keep-all
        rows.append((sum(ok), rec, vals, amb, b))
    rows.sort(key=lambda t: (-t[0], -sum(v[1] for v in t[2]), t[3]))
    lines = ["| rotor | DE load [N] | f 3000 / 7000 / 10000 [Hz] | ribbon | calm | T1 f [Hz] | checks | "
             + " | ".join(t[0] for t in TABLE) + " | largest AMB excursion [mm] |", "|" + "---|" * (8 + len(TABLE))]
    for n_ok, rec, vals, amb, b in rows:
        f = " / ".join(("{:.1f}".format(rec["results"][sp][1]) if rec["results"][sp][1] else "-")
                       + ("" if rec[f"fig39_{sp}"] else "x") for sp in ("3000", "7000", "10000"))
        rib = "-" if rec["ribbon_move"] is None else f"{rec['ribbon_move']:.1%}" + ("" if rec["ribbon"] else "x")
        cells = " | ".join("-" if x is None else f"{x:.3g}" + ("" if ok else "x") for x, ok in vals)
        lines.append(f"| {rec['rotor']} | {b['de_load_n']:.0f} | {f} | {rib} | {rec['results']['nowhirl'][0]}/{sum(b['counts'].values())}"
                     f"{'' if rec['calm'] else 'x'} | {b['frequency_hz']:.1f}{'' if abs(b['frequency_hz'] / 49.0 - 1) <= 0.10 else 'x'} | {n_ok} of 6 | {cells} | {amb * 1e3:.2f} |")
    lines.append(f"\n{len(rows)} landed; all six: {sum(t[0] == 6 for t in rows)}. x marks a fail (the table rows: "
                 f"validate's bands; the AMB gap is {AMB_GAP_M * 1e3:.1f} mm). Medians over each rotor's drops; 'checks' counts "
                 "Fig. 39 x3, the ribbon, the calm landing and Table 1's band (the funnel's filter).")
    text = "\n".join(lines) + "\n"
    print(text, end="")
    tmp = out / "report.md.tmp"
    tmp.write_text(text)
    tmp.replace(out / "report.md")
    return 0


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default="study_out/ribbon_neighbourhood")
    ap.add_argument("--children", type=int, default=600, help="children per parent")
    ap.add_argument("--sigma", type=float, default=0.06, help="step as a share of each bound's width")
    ap.add_argument("--keep", type=int, default=60, help="children per parent written for the landings")
    ap.add_argument("--seed", type=int, default=38)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--report", action="store_true", help="tabulate DIR's landed children (after --funnel-pass)")
    a = ap.parse_args(argv)
    if a.report:
        return report(Path(a.out))
    weak = json.loads(WEAK.read_text())["rows"]
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    jobs = []
    for p in PARENTS:
        s, n = (int(t) for t in p.split(":"))
        parent = next(r for r in weak if r["seed"] == s and r["sample"] == n)
        back = values({**{k: parent["vals"][k] for k in rrs.DRAWN}, **annuli_of(parent["vals"])})
        err = max(abs(back[k] / parent["vals"][k] - 1) for k in parent["vals"])
        assert err < 1e-9, f"annulus inversion of {p} off by {err:.2e}"  # the children start at the parent itself
        kids = children(parent, a.children, a.sigma, a.seed + n)
        tag = int(f"{s}{n}")
        idx = list(enumerate(kids))
        jobs += [(tag, idx[k::a.workers]) for k in range(a.workers)]
    with ProcessPoolExecutor(a.workers) as ex:
        rows = sorted((r for part in ex.map(analyse_batch, jobs) for r in part), key=lambda r: (r["seed"], r["sample"]))
    keep = []
    for p in PARENTS:
        tag = int(p.replace(":", ""))
        mine = [r for r in rows if r["seed"] == tag]
        ok = [r for r in mine if "modes_hz" in r and all(r["modes_hz"]) and all(r["rib_7000_hz"].values())]
        j = [(r, rib.judge(r)) for r in ok]
        # the landed ribbon move runs about 1.36 x the modal one (session 37), so 7.4 % modal reaches the check's 10 %
        good = sorted((r for r, x in j if x["rise_ok"] and x["fig39"] and x["rib"] >= RIB_MIN), key=fig39_distance)
        keep += good[:a.keep]
        print(f"{p}: {len(mine)} children, {len(ok)} analysed; rise_ok {sum(x['rise_ok'] for _, x in j)}, "
              f"modal ribbon >= 6 % {sum(x['rib'] >= 0.06 for _, x in j)}, >= 10 % {sum(x['ribbon'] for _, x in j)}, "
              f"modal Fig. 39 {sum(x['fig39'] for _, x in j)}; rise_ok, modal Fig. 39 and ribbon >= {RIB_MIN:.1%}: {len(good)}, kept {len(good[:a.keep])}")
    rib.write_candidates(keep, out / "children.json")
    tmp = out / "all_children.json.tmp"
    tmp.write_text(json.dumps({"parents": PARENTS, "sigma": a.sigma, "seed": a.seed, "rows": rows}))
    tmp.replace(out / "all_children.json")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
