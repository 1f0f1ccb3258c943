"""Session-18 study (issue 15, point 4): what a backward calibration on the frequency alone predicts
of the rest of Table 1 (onset, DE vertical displacement max and min).

It reads the output of the worn-bearing calibration (`rotorlanding calibrate
scenarios/calibration/worn_bearing.toml --out DIR`: 32 designs of the worn DE drag torque and its
growth angle, each landed as the backward scenario's 32-drop ensemble). A calibration on the
frequency alone cannot reject any design whose ensemble whirls backward in >= 7 of 8 drops with
its median frequency inside Table 1's band (49 Hz +/- 4.9 Hz, validate's band rule). Those
designs are the frequency-only calibration's admissible set: what they do with the onset and the
displacements is what the frequency predicts of them. The design nearest 49 Hz is the point a
frequency-only fit would report.

usage (from the repository root):
    python docs/studies/backward_frequency_only.py DIR [--json OUT.json]"""
import argparse
import csv
import json
import statistics
import sys
from pathlib import Path

from rotorlanding.safeio import atomic_write_text
from rotorlanding.validate import CLASS_SHARE, _paper_values, band

ROWS = (("onset_s", "bw_onset_s", "onset", "s", 1.0),
        ("v_disp_max_m", "bw_v_disp_max_m", "DE vertical displacement max", "mm", 1e3),
        ("v_disp_min_m", "bw_v_disp_min_m", "DE vertical displacement min", "mm", 1e3))


def _f(x):
    return float(x) if x not in (None, "", "None") else None


def admissible(rows: list[dict]) -> tuple[list[dict], float, float]:
    """The designs a calibration on Table 1's frequency alone cannot reject: backward in at least
    CLASS_SHARE of the drops, median frequency inside the band. Returns them, the target, the band."""
    sim, exp = _paper_values("table1", "frequency_hz")
    b = band(sim, exp)
    keep = [r for r in rows if r.get("bw_direction") == "backward" and (_f(r.get("bw_fraction")) or 0.0) >= CLASS_SHARE
            and _f(r.get("bw_hz")) is not None and abs(_f(r["bw_hz"]) - exp) <= b]
    return keep, exp, b


def study(out_dir) -> dict:
    path = Path(out_dir) / "calibration.csv"
    if not path.is_file():
        raise SystemExit(f"{path}: not found: give the --out folder of `rotorlanding calibrate "
                         "scenarios/calibration/worn_bearing.toml`")
    with open(path, encoding="utf-8") as fh:
        rows = list(csv.DictReader(fh))
    missing = [c for _, c, *_ in ROWS if rows and c not in rows[0]]
    if missing:
        print(f"{path}: no column {', '.join(missing)} (a calibration from before session 18): those rows are left out",
              file=sys.stderr)
    keep, f_exp, f_band = admissible(rows)
    if not keep:
        raise SystemExit(f"{out_dir}/calibration.csv: no design whirls backward inside {f_exp} +/- {f_band} Hz")
    best = min(keep, key=lambda r: abs(_f(r["bw_hz"]) - f_exp))
    res = {"designs": len(rows), "admissible": len(keep), "frequency_target_hz": f_exp, "frequency_band_hz": f_band,
           "frequency_only_fit": {"worn_drag_torque_n_m": _f(best["bearings.DE.worn_drag_torque"]),
                                  "worn_drag_growth_angle_rad": _f(best["bearings.DE.worn_drag_growth_angle"]),
                                  "frequency_hz": _f(best["bw_hz"])},
           "rows": {}}
    for key, col, label, unit, scale in ROWS:
        sim, exp = _paper_values("table1", key)
        b = band(sim, exp)
        vals = [_f(r.get(col)) for r in keep if _f(r.get(col)) is not None]
        if not vals:
            continue
        inside = sum(abs(v - exp) <= b for v in vals)
        res["rows"][key] = {"label": label, "unit": unit, "experimental": exp * scale, "band": b * scale,
                            "min": min(vals) * scale, "median": statistics.median(vals) * scale,
                            "max": max(vals) * scale, "inside_band": inside, "of": len(vals),
                            "frequency_only_fit": _f(best.get(col)) * scale if _f(best.get(col)) is not None else None}
    return res


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("dir")
    ap.add_argument("--json", default=None)
    a = ap.parse_args(argv)
    res = study(a.dir)
    fit = res["frequency_only_fit"]
    print(f"{res['admissible']} of {res['designs']} designs whirl backward inside {res['frequency_target_hz']:g} "
          f"+/- {res['frequency_band_hz']:.2g} Hz (a frequency-only calibration cannot reject them); the one nearest "
          f"the target: T_w {fit['worn_drag_torque_n_m']:.3g} N m, growth {fit['worn_drag_growth_angle_rad']:.3g} rad, "
          f"{fit['frequency_hz']:.1f} Hz")
    print("| Table 1 | experiment | band | frequency-only fit | admissible designs: min / median / max | inside the band |")
    print("|---|---|---|---|---|---|")
    for r in res["rows"].values():
        fo = "-" if r["frequency_only_fit"] is None else f"{r['frequency_only_fit']:.3g}"
        print(f"| {r['label']} [{r['unit']}] | {r['experimental']:.3g} | {r['band']:.2g} | {fo} | "
              f"{r['min']:.3g} / {r['median']:.3g} / {r['max']:.3g} | {r['inside_band']} of {r['of']} |")
    if a.json:
        atomic_write_text(Path(a.json), json.dumps(res, indent=2))
    return 0


if __name__ == "__main__":
    sys.exit(main())
