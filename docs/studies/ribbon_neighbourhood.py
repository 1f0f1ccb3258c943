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


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default="study_out/ribbon_neighbourhood")
    ap.add_argument("--children", type=int, default=600, help="children per parent")
    ap.add_argument("--sigma", type=float, default=0.06, help="step as a share of each bound's width")
    ap.add_argument("--keep", type=int, default=60, help="children per parent written for the landings")
    ap.add_argument("--seed", type=int, default=38)
    ap.add_argument("--workers", type=int, default=2)
    a = ap.parse_args(argv)
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
