"""Land the rotors of ``ribbon_rise_screen.py`` whose linear mode rises enough and moves with the ribbon
(issue 15, session 37; docs/calibration.md "Session 37").

For every rotor of the stored screen with a rise 10000 / 3000 rpm of at least the least Fig. 39's bands
allow and a ribbon move of at least 10 % at 7000 rpm (the modal screen's ``rise_ok`` and ``ribbon``), the
combined landing (``docs/studies/ensemble.py``, N drops from the 5 um circle) at 7000 rpm, at 7000 rpm with
K_rib x0.5 and x1.5, and at 10000 and 3000 rpm. A rotor is counted for each check it would pass in
``validate`` (DE forward in >= 0.875 of the drops within 10 % of Fig. 39; the ribbon: the 7000 rpm DE
whirl moved >= 10 % by either variant that still whirls forward at the DE).

    python docs/studies/ribbon_landing_screen.py [--n 8] [--workers 2] [--out DIR] [--limit K]
    python docs/studies/ribbon_landing_screen.py --backward [--out DIR]   (after the above)

``--funnel --screen-json J``: the same worn-bearing landing on every rotor of J (e.g. the weaker-ribbon rotors of
``ribbon_rise_screen.py --weak``), into DIR/funnel.jsonl, before any forward landing.

``--funnel-pass --screen-json J``: the five landings above and the no-whirl landing (``calm``: no whirl in >= 7 of 8)
on the rotors of DIR/funnel.jsonl whose backward whirl is in Table 1's band; DIR/funnel_landed.jsonl (with the no-whirl
landing's median DE race / rotor speed and DE force range: whether the DE lands at all, session 39).

``--backward``: for every landed rotor that passes the ribbon check, the worn-bearing landing of Table 1
(``scenarios/paper/backward_whirl_landing.toml``, mu_rad 0.3) with the worn torque scaled to the rotor's static
DE load, so that T_w / (r_i W) stays the rig's (2.79 N m at 248 N, 0.38), N drops; DIR/backward.jsonl. About 10 s
a rotor.

``--set KEY=VALUE`` (repeatable) adds an override to every landing (e.g. the ribbon's damping for both bearings);
``--rotors S:N,...`` lands only those. Use another DIR for each set of overrides.

Resumable: each rotor's result is appended to DIR/landed.jsonl once all its landings are done (a killed run
loses at most the rotor it was on). Prints one line per rotor and the counts. About 30 s a rotor on 2 cores (80 rotors: 39 min).
"""

from __future__ import annotations

import argparse
import json
import os
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "docs" / "studies"))

SCENARIO = ROOT / "scenarios" / "paper" / "forward_whirl_landing.toml"
NO_WHIRL = ROOT / "scenarios" / "paper" / "no_whirl_landing.toml"
CASES = {
    "7000": [],
    "7000_k05": ["bearings.DE.k_rib=3.15e7", "bearings.NDE.k_rib=3.15e7"],
    "7000_k15": ["bearings.DE.k_rib=9.45e7", "bearings.NDE.k_rib=9.45e7"],
    "10000": ["operating.speed_rpm=10000"],
    "3000": ["operating.speed_rpm=3000"],
}
TARGET_HZ = {"3000": 48.0, "7000": 65.0, "10000": 77.0}
SHARE = 0.875


def de_result(d: dict) -> tuple[int, float | None]:
    """(drops whose DE journal whirls forward, their median DE frequency [Hz])."""
    import statistics

    f = [m["de_frequency_hz"] for m in d["members"] if m.get("de_direction") == "forward" and m.get("de_frequency_hz")]
    return len(f), (statistics.median(f) if f else None)


def verdicts(res: dict, n: int) -> dict:
    out = {"calm": res["nowhirl"][0] >= SHARE * n} if "nowhirl" in res else {}
    for sp, t in TARGET_HZ.items():
        k, f = res[sp]
        out[f"fig39_{sp}"] = k >= SHARE * n and f is not None and abs(f / t - 1) <= 0.10
    k0, f0 = res["7000"]
    moves = [abs(res[v][1] / f0 - 1) for v in ("7000_k05", "7000_k15")
             if f0 and res[v][1] and res[v][0] >= SHARE * n]
    out["ribbon"] = bool(moves) and max(moves) >= 0.10 and k0 >= SHARE * n
    out["ribbon_move"] = max(moves) if moves else None
    return out


def in_table1_band(b: dict) -> bool:
    """A worn-bearing ensemble record (``funnel.jsonl``) whirls backward in Table 1's band: 49 Hz +/- 10 % in
    >= SHARE of its drops."""
    n = sum(b["counts"].values())
    return bool(b["frequency_hz"]) and abs(b["frequency_hz"] / 49.0 - 1) <= 0.10 and b["counts"].get("backward", 0) >= SHARE * n


def _records(log: Path) -> list[dict]:
    """The finished rotors of ``log``; a line torn by a kill is skipped (that rotor is landed again)."""
    recs = []
    for line in (log.read_text().splitlines() if log.exists() else []):
        try:
            recs.append(json.loads(line))
        except json.JSONDecodeError:
            continue
    return recs


RIG_WORN_TORQUE_N_M = 2.790095721727786  # scenarios/paper/backward_whirl_landing.toml
RIG_DE_LOAD_N = 248.0  # the rig rotor's static DE sleeve load (modefit.static_support_loads)


def backward(out: Path, screen_json: Path, n: int, workers: int, funnel: bool = False, extra=(), only=()) -> int:
    """The worn-bearing landing on every rotor of ``out``/landed.jsonl that passes the ribbon check, or
    (``funnel``) on every rotor of ``screen_json``, into ``out``/funnel.jsonl: Table 1's landing first, as a
    cheap filter before the forward cases."""
    from ensemble import ensemble
    from ribbon_regimes import screened_sets
    import rotor_rise_screen as rrs
    from rotorlanding.config import load_toml
    from rotorlanding.modefit import static_support_loads

    base = load_toml(ROOT / "scenarios" / "rig_rotor.toml")
    rows = json.loads(screen_json.read_text())["rows"]
    log = out / ("funnel.jsonl" if funnel else "backward.jsonl")
    done = {x["rotor"] for x in _records(log)}
    todo = ([{"rotor": f"{r['seed']}:{r['sample']}", "ribbon": True} for r in rows] if funnel
            else _records(out / "landed.jsonl"))
    for rec in todo:
        if not rec["ribbon"] or rec["rotor"] in done or (only and rec["rotor"] not in only):
            continue
        seed, sample = (int(x) for x in rec["rotor"].split(":"))
        r = next(r for r in rows if r["seed"] == seed and r["sample"] == sample)
        w = static_support_loads(rrs.rotor_data(base, r["vals"]))["DE_sleeve"]
        tw = RIG_WORN_TORQUE_N_M * w / RIG_DE_LOAD_N
        tag = f"{seed}_{sample}_bw"
        ensemble(str(ROOT / "scenarios" / "paper" / "backward_whirl_landing.toml"), n,
                 [*screened_sets(screen_json, rec["rotor"]), f"bearings.DE.worn_drag_torque={tw:.4g}", *extra],
                 workers=workers, out=str(out / "runs"), tag=tag)
        st = json.loads((out / "runs" / f"{tag}.json").read_text())["stats"]
        b = {"rotor": rec["rotor"], "de_load_n": w, "worn_drag_torque": tw, "counts": st["counts"],
             "frequency_hz": st.get("frequency_hz"), "onset_s": st.get("onset_s"),
             "all_four": all(rec.get(k) for k in ("fig39_3000", "fig39_7000", "fig39_10000", "ribbon"))}
        with open(log, "a") as fh:
            fh.write(json.dumps(b) + "\n")
            fh.flush()
            os.fsync(fh.fileno())
        print(json.dumps(b), flush=True)
    recs = _records(log)
    f = sorted(x["frequency_hz"] for x in recs if x["frequency_hz"])
    if f:
        print(f"{len(recs)} rotors; backward whirl in {len(f)} at {f[0]:.1f}-{f[-1]:.1f} Hz, median {f[len(f) // 2]:.1f} Hz "
              "(Table 1: 49 Hz)")
    return 0


def main(argv=None) -> int:
    from ensemble import ensemble
    from ribbon_regimes import screened_sets
    import ribbon_rise_screen as rrs

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=8)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--out", default="study_out/ribbon_landing_screen")
    ap.add_argument("--limit", type=int, default=0, help="land only the first K candidates (0: all)")
    ap.add_argument("--backward", action="store_true", help="the worn-bearing landing on the ribbon-passing rotors")
    ap.add_argument("--funnel", action="store_true", help="the worn-bearing landing alone on every rotor of --screen-json")
    ap.add_argument("--funnel-pass", action="store_true",
                    help="land the forward cases and the calm landing on the rotors of DIR/funnel.jsonl whose "
                         "backward whirl lies in Table 1's band (49 Hz +/- 10 %%, >= 7 of 8 drops), into DIR/funnel_landed.jsonl")
    ap.add_argument("--screen-json", default=str(ROOT / "docs" / "studies" / "ribbon_rise_screen" / "candidates.json"))
    ap.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                    help="an override added to every landing (e.g. bearings.DE.c_rib=1500), after the rotor's own")
    ap.add_argument("--keep-all", action="store_true",
                    help="--funnel-pass on every rotor of DIR/funnel.jsonl, in Table 1's band or not")
    ap.add_argument("--rotors", default="", help="comma-separated seed:sample; only these (default: all)")
    a = ap.parse_args(argv)
    sj = Path(a.screen_json)
    only = {x for x in a.rotors.split(",") if x}
    if a.backward or a.funnel:
        return backward(Path(a.out), sj, a.n, a.workers, funnel=a.funnel, extra=a.set, only=only)
    rows = [r for r in json.loads(sj.read_text())["rows"]
            if "modes_hz" in r and all(r["modes_hz"]) and all(r["rib_7000_hz"].values())]
    out = Path(a.out)
    cases = dict(CASES)
    if a.funnel_pass:
        # Table 1's backward whirl first (the funnel), then everything else on its survivors
        keep = {b["rotor"] for b in _records(out / "funnel.jsonl") if a.keep_all or in_table1_band(b)}
        cands = [r for r in rows if f"{r['seed']}:{r['sample']}" in keep]
        cases["nowhirl"] = None
    else:
        cands = [r for r in rows if (lambda j: j["rise_ok"] and j["ribbon"])(rrs.judge(r))]
    if only:
        cands = [r for r in cands if f"{r['seed']}:{r['sample']}" in only]
    cands.sort(key=lambda r: sum(abs(rrs.LOCK * f / t - 1) for f, t in zip(r["modes_hz"], rrs.TARGET_HZ)))
    if a.limit:
        cands = cands[:a.limit]
    out.mkdir(parents=True, exist_ok=True)
    log = out / ("funnel_landed.jsonl" if a.funnel_pass else "landed.jsonl")
    done = {x["rotor"] for x in _records(log)}
    print(f"{len(cands)} candidates (modal rise and ribbon move), {len(done)} already landed", flush=True)
    for r in cands:
        pick = f"{r['seed']}:{r['sample']}"
        if pick in done:
            continue
        sets = [*screened_sets(sj, pick), *a.set]
        res, landed_de = {}, {}
        for case, csets in cases.items():
            tag = f"{r['seed']}_{r['sample']}_{case}"
            if csets is None:  # the no-whirl landing (mu_rad 0.15, healthy bearings): calm drops counted
                ensemble(str(NO_WHIRL), a.n, sets, workers=a.workers, out=str(out / "runs"), tag=tag)
                st = json.loads((out / "runs" / f"{tag}.json").read_text())["stats"]
                res[case] = (st["counts"].get("none", 0), None)
                # whether the DE lands at all (validate's race spin-up check, >= 0.97): a DE held up by the
                # coupling stays calm without touching its race (session 39)
                landed_de = {"nowhirl_de_race_to_rotor": st.get("race_to_rotor"),
                             "nowhirl_de_force_range_n": st.get("v_force_range_n")}
                continue
            ensemble(str(SCENARIO), a.n, [*sets, *csets], workers=a.workers, out=str(out / "runs"), tag=tag)
            res[case] = de_result(json.loads((out / "runs" / f"{tag}.json").read_text()))
        rec = {"rotor": pick, "modes_hz": r["modes_hz"], "results": res, **verdicts(res, a.n), **landed_de}
        with open(log, "a") as fh:  # one line per finished rotor: a kill leaves whole lines before it
            fh.write(json.dumps(rec) + "\n")
            fh.flush()
            os.fsync(fh.fileno())
        print(pick, " ".join(f"{c}: {k}/{a.n} {f or float('nan'):.1f}" for c, (k, f) in res.items()),
              {k: v for k, v in rec.items() if k.startswith(("fig39", "ribbon", "calm"))}, flush=True)
    recs = _records(log)
    keys = ["fig39_3000", "fig39_7000", "fig39_10000", "ribbon"]
    print(f"{len(recs)} rotors landed; passing: " + ", ".join(f"{k} {sum(x[k] for x in recs)}" for k in keys)
          + f"; all four {sum(all(x[k] for k in keys) for x in recs)}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
