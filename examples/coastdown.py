"""A coast-down: the AMBs fail at 7000 rpm, the rotor lands and runs down on its catcher bearings.

    python examples/coastdown.py [--short] [--out DIR]

rl.coastdown runs the crash-safe, chunked coast-down of `rotorlanding coastdown` (results.h5 and
summary.json in --out; a killed run continues with resume=True, bit for bit). The full version
runs 20 s of the rig's coast-down (about 20 s of wall time after the first compile); the whole run
to rest (~1 h of machine time) is the same call with t_end=None. --short: 0.4 s (two chunks).
Units: SI (m, N, s, J); speeds in rpm as named; the figure shows mm and kN as labelled.
"""

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

import rotorlanding as rl
from _common import SCENARIOS, arguments


def main(argv=None):
    """The example's work: run the coast-down into --out, print its summary, draw the figures;
    returns the coast-down."""
    args = arguments(__doc__, "coastdown", argv)
    t_end = 0.4 if args.short else 20.0  # s of simulated time (a cap; the run ends at the stop speed)
    # overwrite: an example is re-run into the same folder; a real run would resume instead
    cd = rl.coastdown(SCENARIOS / "coastdown_7000rpm.toml", args.out, t_end=t_end, overwrite=True)
    print(cd)
    s = cd.summary
    print(f"stopped by: {s['stop_reason']}; rotor {s['speeds']['initial_rotor_rpm']:.0f} -> "
          f"{s['speeds']['final_rotor_rpm']:.0f} rpm in {s['t_reached_s']:.2f} s")
    e = s["energy"]
    print(f"energy dissipated {e['dissipated_total_j']:.4g} J: " + ", ".join(
        f"{k} {v:.3g}" for k, v in sorted(e["dissipated_j"].items(), key=lambda kv: -kv[1]) if v > 0)
          + f" (energy balance error {100 * e['balance_error_relative']:.3f} %)")
    for b, v in s["bearings"].items():
        print(f"{b}: peak contact force {v['max_contact_force_n'] / 1e3:.2f} kN")
    for ph in s["whirl_phases"]:
        print(f"{ph['t_start_s']:7.2f} - {ph['t_end_s']:7.2f} s: whirl {ph['direction']}"
              + (f" at {ph['frequency_hz_median']:.1f} Hz" if ph.get("frequency_hz_median") else "")
              + f", {ph['rotor_speed_rpm_at_end']:.0f} rpm at its end")

    # one figure: speeds (whirling chunks shaded), the DE journal within its clearance, the force of
    # each catcher bearing on the rotor, and where the energy went
    t = cd.t
    fig, axes = plt.subplots(2, 2, figsize=(13, 8.5))
    ax = axes[0, 0]
    ax.plot(t, cd["rotor_speed_rpm"].values, "k", lw=1.5, label="rotor")
    for b in cd.clearances:
        ax.plot(t, cd[f"{b}_race_speed_rpm"].values, lw=1.0, label=f"{b} inner race")
    for d, col, name in ((1, "tab:red", "forward whirl"), (-1, "tab:blue", "backward whirl")):
        sel = cd.chunks["whirl_direction"] == d
        for k, (a, e) in enumerate(zip(cd.chunks["t_start_s"][sel], cd.chunks["t_end_s"][sel])):
            ax.axvspan(a, e, color=col, alpha=0.15, lw=0, label=name if k == 0 else None)
    ax.set_ylabel("speed [rpm]")
    ax.set_title("rotor and inner-race speeds (shaded: chunks that whirl)", fontsize=10)
    ax.legend(fontsize=8)

    ax = axes[0, 1]
    clear_mm = cd.clearances["DE"] * 1e3
    # relative to the inner race: what the radial clearance bounds (up to the Hertz penetration)
    rel_z = (cd["DE_z_m"].values - cd["DE_race_z_m"].values) * 1e3
    rel_y = (cd["DE_y_m"].values - cd["DE_race_y_m"].values) * 1e3
    ax.plot(t, rel_z, "k", lw=0.6, label="vertical z")
    ax.plot(t, rel_y, "tab:orange", lw=0.6, label="horizontal y")
    for sgn in (-1, 1):
        ax.axhline(sgn * clear_mm, color="b", ls=":", lw=1.0, label=f"+/- radial clearance {clear_mm:.2f} mm" if sgn > 0 else None)
    ax.set_ylabel("DE journal relative to the inner race [mm]")
    ax.set_ylim(-1.6 * clear_mm, 1.6 * clear_mm)
    ax.set_title("DE journal in its catcher bearing", fontsize=10)
    ax.legend(fontsize=8, loc="upper center", ncol=3)

    ax = axes[1, 0]
    for b in cd.clearances:
        ax.plot(t, cd[f"{b}_normal_force_n"].values * 1e-3, lw=0.6, label=f"{b} race contact")
    # the peak of each chunk comes from its full-rate samples (the stored ones are decimated)
    ax.hlines(cd.chunks["DE_max_contact_force_n"] * 1e-3, cd.chunks["t_start_s"], cd.chunks["t_end_s"], colors="k",
              lw=1.5, label="DE peak within each chunk")
    ax.set_ylabel("contact normal force [kN]")
    ax.set_title("catcher-bearing contact forces", fontsize=10)
    ax.legend(fontsize=8)

    ax = axes[1, 1]
    lost = [cd[k] for k in cd.series_names if k.startswith("dissipated_")]
    for v in lost:  # the mechanisms that take more than 0.1 % of the energy lost
        if len(v) and v.values[-1] > 1e-3 * e["dissipated_total_j"]:
            ax.plot(t, v.values, label=v.name[len("dissipated_"):-2].replace("_", " "))
    ax.set_ylabel(f"energy dissipated [{lost[0].unit}]")
    ax.set_title("where the kinetic energy went", fontsize=10)
    ax.legend(fontsize=8)
    for ax in axes.ravel():
        if t[-1] > 5.0:  # a long run: linear over the landing's first second, logarithmic after
            ax.set_xscale("symlog", linthresh=1.0, linscale=1.0)
        ax.set_xlim(0.0, t[-1])
        ax.set_xlabel("time after the drop [s]")
        ax.grid(alpha=0.3)
    fig.suptitle(f"{s['scenario']}: {s['t_reached_s']:.2f} s simulated, {s['stop_reason']}", fontsize=11)
    fig.tight_layout()
    fig.savefig(args.out / "coastdown_overview.png", dpi=120)
    cd.plot_speeds(args.out / "speeds.png")
    print(f"figures in {args.out}: coastdown_overview.png, speeds.png, coastdown.png (the command's)")
    return cd


if __name__ == "__main__":
    main()
