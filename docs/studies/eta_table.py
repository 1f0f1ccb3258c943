"""Session-13 study tool: one markdown row per ensemble JSON written by docs/studies/ensemble.py.

usage: python docs/studies/eta_table.py OUT/*.json
Columns: overrides, drops per class (all bearings and the DE journal), median frequency and onset of
the whirling drops, median DE force range,
and the median over the drops of the largest DE force magnitude |F|.
"""
import json
import statistics as st
import sys
from pathlib import Path


def row(p: Path) -> str:
    r = json.loads(p.read_text())
    ms = r["members"]
    cnt, de = {}, {}
    for m in ms:
        cnt[m["direction"]] = cnt.get(m["direction"], 0) + 1
        de[m["de_direction"]] = de.get(m["de_direction"], 0) + 1
    f = [m["frequency_hz"] for m in ms if m["frequency_hz"] is not None and m["direction"] != "none"]
    on = [m["onset_s"] for m in ms if m["onset_s"] is not None and m["direction"] != "none"]
    fmin = [m["v_force_range_n"][0] / 1e3 for m in ms]
    fmax = [m["v_force_range_n"][1] / 1e3 for m in ms]
    fabs = st.median([max(-a, b) for a, b in zip(fmin, fmax)])
    c = ", ".join(f"{k} {v}" for k, v in sorted(cnt.items()))
    d = ", ".join(f"{k} {v}" for k, v in sorted(de.items()))
    fs = f"{st.median(f):.1f} ({min(f):.0f}-{max(f):.0f})" if f else "-"
    os_ = f"{st.median(on):.2f}" if on else "-"
    return f"| {p.stem} | {c} | {d} | {fs} | {os_} | {st.median(fmin):.1f} / {st.median(fmax):.1f} | {fabs:.1f} |"


def main(argv: list[str]) -> int:
    if not argv:
        print("usage: python docs/studies/eta_table.py OUT/*.json (ensemble JSONs of docs/studies/ensemble.py)",
              file=sys.stderr)
        return 2
    rows = []
    for a in argv:
        try:
            rows.append(row(Path(a)))
        except (OSError, ValueError, KeyError, TypeError, IndexError) as exc:
            print(f"{a}: not an ensemble JSON of docs/studies/ensemble.py ({type(exc).__name__}: {exc})",
                  file=sys.stderr)
            return 2
    print("| tag | drops (all) | DE journal | f [Hz] median (range) | onset [s] | DE force min / max [kN] | \\|F\\| [kN] |")
    print("|---|---|---|---|---|---|---|")
    print("\n".join(rows))
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
