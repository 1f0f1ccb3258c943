"""Held-out predictions over the fit's own uncertainty (issue 15, point 4; session 25).

    python docs/studies/heldout_span.py [--out docs/studies/heldout_span] [--from FIT/calibration.json | --rerun]

`rotorlanding validate` lands each held-out Fig. 39 speed on the *first* design of the fit made
without it (scenarios/calibration/holdout/). But a fit on ensembles of drops (8 per speed until session 34, 32 since session 35) cannot rank the designs
near its best (calibrate's ``within_noise_of_best``), and which comes first moves with the install.
A held-out prediction is then a band: every design the two-speed fit cannot tell from its best
predicts the third speed. This study asks whether each of them does.

No extra landings: the held-out fits (`without_<rpm>rpm_landings.toml`) sample the same 24 designs
(seed 15) as the three-speed fit on their ranges (`holdout/all_speeds_landings.toml`; since session 30
its ranges, samples, seed, drops and t_end are rotor_landings.toml's, which a test checks) and score two of
its three speeds, so one run of it holds every held-out fit (scored on the parts of the two speeds, with
their errors) and every design's landing at the held-out speed (the fit's drops per speed; validate lands
32). It reads the rotor fit's stored run (docs/studies/heldout_span/fit/calibration.json, the same
landings) unless ``--from`` names another calibration.json or ``--rerun`` runs the three-speed fit into
OUT/heldout_fit (2304 landings, ~21 min on 2 cores); the run must have the parts' errors ``err_<part>_se``
and the DE columns ``<case>_de_*`` (written by calibrate since session 25).

Writes OUT/heldout_span.md and OUT/heldout_span.json (atomically).
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))

from rotorlanding.calibrate_run import NOISE_Z, calibrate, stored_score, within_noise  # noqa: E402
from rotorlanding.safeio import atomic_write_text  # noqa: E402
from rotorlanding.validate import (  # noqa: E402
    HELDOUT_BAND,
    HELDOUT_DROPS,
    ON_BOUND,
    class_need,
    paper,
    paper_dir,
    placement,
    search_bounds,
)

SPEEDS = {3000: "fw3000", 7000: "fw7000", 10000: "fw10000"}
KEYS = ("rotor.sections.3.outer_diameter", "rotor.disks.4.outer_diameter")


def sub_score(row: dict, cases: list[str]) -> tuple[float, float | None]:
    """The score of a fit on ``cases`` only, from the full fit's parts, and its standard error
    (``calibrate_run.stored_score``, which ``rotorlanding calibrate --from-run`` ranks by)."""
    return stored_score(row, cases)


def on_bound(r: dict, bounds: dict, ranges: dict | None = None) -> bool:
    """Whether a design's fitted value sits within ON_BOUND of its sourced bound's end or of its fit's
    search range's end (validate's rule for a held-out fit's pick, ``validate.placement`` as
    ``validate.heldout_pick_positions`` applies it: such a design fails the held-out check whatever it
    predicts). ``bounds``: the rig's sourced bounds; ``ranges``: key -> search range (Bound)."""
    ranges = ranges or {}
    return any(placement(r[k], bounds.get(k), ranges.get(k))["on_bound"] for k in KEYS)


def heldout(rows: list[dict], rpm: int, drops: int, ranges: dict | None = None) -> dict:
    """The fit without ``rpm``: its designs in order, the set within its noise, and what each of
    them predicts at ``rpm`` (DE direction, forward drops, frequency against the experiment). A
    design on its bound fails, as validate fails a held-out pick on its bound."""
    from rotorlanding.scenario import load_scenario

    bounds = load_scenario(paper_dir() / "forward_whirl_landing.toml").bounds
    fit = [c for r, c in SPEEDS.items() if r != rpm]
    case = SPEEDS[rpm]
    f_exp = dict(zip(paper()["fig39"]["speed_rpm"], paper()["fig39"]["experimental_hz"]))[rpm]
    scored = []
    for r in rows:
        total, se = sub_score(r, fit)
        # a landing that failed at the held-out speed is no reason to leave the design out of the
        # fit made without that speed (per-case counts since session 25; the total before)
        failed = (sum(int(r[f"{c}_failed"]) for c in fit) if all(f"{c}_failed" in r for c in fit)
                  else r.get("failed_landings"))
        scored.append({**r, "score": total, "score_se": se, "failed_landings": failed})
    scored.sort(key=lambda r: r["score"])
    near = within_noise(scored)
    preds = []
    for r in near:
        hz = r.get(f"{case}_de_hz")
        fwd = int(r.get(f"{case}_de_forward") or 0)
        err = (hz - f_exp) / f_exp if hz and r.get(f"{case}_de_direction") == "forward" else None
        edge = on_bound(r, bounds, ranges)
        preds.append({"design": r["design"], **{k: r[k] for k in KEYS}, "score": r["score"], "score_se": r["score_se"],
                      "de_forward": fwd, "de_hz": hz, "error": err,
                      # the DE whirl's shapes at the held-out speed (calibrate's rows since session 27)
                      "de_shapes": r.get(f"{case}_de_shapes"), "on_bound": edge,
                      # validate's held-out rule: the share of drops of its class checks, the band, and
                      # the pick not on its bound
                      "pass": bool(err is not None and abs(err) <= HELDOUT_BAND and fwd >= class_need(drops)
                                   and not edge)})
    return {"rpm": rpm, "fitted_on": fit, "experiment_hz": f_exp, "first": scored[0]["design"],
            "within_noise": preds, "passing": sum(p["pass"] for p in preds)}


def report(res: list[dict], drops: int, source: str, n: int) -> str:
    lines = ["# Held-out predictions over the fit's uncertainty (generated by docs/studies/heldout_span.py)", "",
             f"Three-speed fit on the held-out fits' ranges and designs: `{source}` ({n} designs, {drops} drops "
             "per speed). For each held-out speed: the designs the "
             f"fit on the other two speeds cannot tell from its best (score within {NOISE_Z:g} standard errors of "
             "the difference), and what each predicts at the held-out speed from the same fit's landings there "
             f"({drops} drops; validate lands {HELDOUT_DROPS} on the first design). Pass: DE forward in >= "
             f"{class_need(drops)} of {drops} and within "
             f"{100 * HELDOUT_BAND:g} % of the experiment, its shaft and disk not within {ON_BOUND:.0%} of their "
             "sourced bounds' ends or of the fit's search ranges' (validate's rule for a fit's pick; marked 'on its bound'). Shapes: the DE whirl's at the held-out speed, cylindrical "
             "(both journals going round together) or conical (against each other), with drops and median frequency "
             "(`whirl.whirl_shape`; recorded by calibrate since session 27).", ""]
    for h in res:
        p = h["within_noise"]
        lines += [f"## Held out {h['rpm']} rpm (experiment {h['experiment_hz']:g} Hz): "
                  f"{h['passing']} of {len(p)} designs within the fit's noise pass", "",
                  f"Fitted on {' + '.join(h['fitted_on'])}; first design {h['first']}.", "",
                  "| design | shaft [mm] | disk [mm] | fit score +/- s.e. | DE forward | DE whirl [Hz] | error | "
                  "shapes: drops, median Hz | verdict |",
                  "|---|---|---|---|---|---|---|---|---|"]
        for q in p:
            hz = "-" if q["de_hz"] is None else f"{q['de_hz']:.1f}"
            err = "-" if q["error"] is None else f"{100 * q['error']:+.1f} %"
            lines.append(f"| {q['design']} | {1e3 * q[KEYS[0]]:.2f} | {1e3 * q[KEYS[1]]:.1f} | "
                         f"{q['score']:.3f} +/- {q['score_se']:.3f} | {q['de_forward']} of {drops} | {hz} | {err} | "
                         f"{q.get('de_shapes') or '-'} | {'PASS' if q['pass'] else 'FAIL'}{' (on its bound)' if q.get('on_bound') else ''} |")
        errs = [q["error"] for q in p if q["error"] is not None]
        if errs:
            lines += ["", f"Prediction band over these designs: {100 * min(errs):+.1f} % to {100 * max(errs):+.1f} %."]
        lines.append("")
    return "\n".join(lines)


def run_drops(src: Path, space: Path) -> int:
    """Drops per speed of the fit in ``src``: its calibration.json's ``ensemble`` (written since
    session 26), else that of the space file it names, else that of ``space``."""
    from rotorlanding.calibrate_run import load_space

    d = json.loads(src.read_text())
    if "ensemble" in d:
        return int(d["ensemble"])
    named = Path(d.get("space", ""))
    return int(load_space(named if named.is_file() else space)["ensemble"])


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default=str(ROOT / "docs" / "studies" / "heldout_span"))
    ap.add_argument("--from", dest="source", default=str(ROOT / "docs" / "studies" / "heldout_span" / "fit"
                                                         / "calibration.json"),
                    help="calibration.json of a run of scenarios/calibration/holdout/all_speeds_landings.toml "
                         "(or of rotor_landings.toml, the same settings); default: the rotor fit's stored run")
    ap.add_argument("--rerun", action="store_true",
                    help="run the three-speed fit into OUT/heldout_fit instead of reading --from")
    ap.add_argument("--workers", type=int, default=2)
    a = ap.parse_args(argv)
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    space = ROOT / "scenarios" / "calibration" / "holdout" / "all_speeds_landings.toml"
    if not a.rerun:
        src = Path(a.source)
        rows = json.loads(src.read_text())["designs"]
    else:
        rows = calibrate(space, out / "heldout_fit", workers=a.workers)
        src = out / "heldout_fit" / "calibration.json"
    if not rows or "err_fw3000_se" not in rows[0]:
        print(f"{src}: no per-part errors (err_<part>_se); re-run calibrate (session 25 or later)", file=sys.stderr)
        return 2
    drops = run_drops(src, space)
    # the held-out fits search the three-speed fit's ranges (same file contents, checked by a test)
    ranges = search_bounds(space)
    res = [heldout(rows, rpm, drops, ranges) for rpm in SPEEDS]
    shown = src.resolve().relative_to(ROOT) if src.resolve().is_relative_to(ROOT) else src
    atomic_write_text(out / "heldout_span.json", json.dumps({"source": str(shown), "drops": drops, "heldout": res},
                                                            indent=2, default=float))
    text = report(res, drops, shown, len(rows))
    atomic_write_text(out / "heldout_span.md", text)
    print(text)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
