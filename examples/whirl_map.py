"""A speed x friction whirl map: which landings whirl forward, backward or not at all.

    python examples/whirl_map.py [--short] [--out DIR]

Varies the drop speed [rpm] and the radial friction coefficient contact.mu_rad [-] of the paper's
combined landing (4 kN thrust) with Scenario.replace, one simulate() each. Units: SI; rpm and Hz
as named.
"""

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import rotorlanding as rl
from _common import SCENARIOS, arguments

args = arguments(__doc__, "whirl_map")
base = rl.Scenario.load(SCENARIOS / "paper" / "forward_whirl_landing.toml")
speeds_rpm = [3000.0, 10000.0] if args.short else [3000.0, 5000.0, 7000.0, 10000.0]
frictions = [0.05, 0.3] if args.short else [0.05, 0.1, 0.15, 0.3, 0.5]
t_end = 0.3 if args.short else 0.6

rows = []
for speed in speeds_rpm:
    for mu in frictions:
        landing = rl.simulate(base.replace(operating__speed_rpm=speed, contact__mu_rad=mu), t_end=t_end)
        w = landing.whirl
        rows.append((speed, mu, w["direction"], w.get("frequency_hz"), landing.complete))
        print(f"{speed:7.0f} rpm, mu_rad {mu:4.2f}: {w['direction']:8s} "
              f"{(w.get('frequency_hz') or float('nan')):6.1f} Hz" + ("" if landing.complete else "  (incomplete)"))

style = {"forward": ("tab:red", "^"), "backward": ("tab:blue", "v"), "none": ("0.5", "o")}
fig, ax = plt.subplots(figsize=(7.5, 5))
for d, (c, mk) in style.items():
    pts = [(s, m) for s, m, dd, _, _ in rows if dd == d]
    if pts:
        ax.scatter(*np.array(pts).T, c=c, marker=mk, s=140, label=f"{d} whirl", edgecolors="k")
for s, m, d, f, ok in rows:
    if f:
        ax.annotate(f"{f:.0f} Hz", (s, m), textcoords="offset points", xytext=(9, -3), fontsize=8)
ax.set_xlabel("rotor speed at the drop [rpm]")
ax.set_ylabel("radial friction coefficient mu_rad [-]")
ax.set_title(f"whirl map of the combined landing (4 kN thrust), {t_end:g} s after the drop", fontsize=10)
ax.margins(0.15)
ax.grid(alpha=0.3)
ax.legend(fontsize=8, loc="best")
fig.tight_layout()
fig.savefig(args.out / "whirl_map.png", dpi=120)
print(f"figure in {args.out / 'whirl_map.png'}")
