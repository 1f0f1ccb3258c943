"""Session 32: one rotor of the rise screen as scenario overrides (key=value ...) against the rig rotor file,
for docs/studies/ensemble.py; prints its static sleeve loads to stderr.

    python docs/studies/onset_probe/screen_candidate_sets.py SCREEN_JSON SEED SAMPLE > candidate.sets

SCREEN_JSON: the output of ``python docs/studies/rotor_rise_screen.py --same-amb --margin 0.05 --out DIR``
(DIR/rotor_rise_screen.json). screen_2_796.sets was made so from seed 2, sample 796.
"""

import json
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[3]
sys.path[:0] = [str(ROOT), str(ROOT / "docs" / "studies")]

import rotor_rise_screen as rs  # noqa: E402

from rotorlanding.config import load_toml  # noqa: E402


def flat(o, p=""):
    if isinstance(o, dict):
        for k, v in o.items():
            yield from flat(v, f"{p}{k}.")
    elif isinstance(o, list):
        for i, v in enumerate(o):
            yield from flat(v, f"{p}{i}.")
    else:
        yield p[:-1], o


def main(argv=None) -> int:
    path, seed, sample = (argv or sys.argv[1:])[:3]
    base = load_toml(ROOT / "scenarios" / "rig_rotor.toml")
    rows = json.loads(Path(path).read_text())["rows"]
    r = next(x for x in rows if x["seed"] == int(seed) and x["sample"] == int(sample))
    d = rs.rotor_data(base, r["vals"])
    b, n = dict(flat(base["rotor"], "rotor.")), dict(flat(d["rotor"], "rotor."))
    print(" ".join(f"{k}={v:.6g}" for k, v in n.items() if isinstance(v, float) and k in b and b[k] != v))
    nde, de = rs.sleeve_loads(d)
    print(f"static loads: NDE {nde:.0f} N, DE {de:.0f} N", file=sys.stderr)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
