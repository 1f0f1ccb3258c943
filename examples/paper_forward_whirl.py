"""The paper's forward-whirl landing (section 3.3, Table 2, Fig. 39) from the Python API.

    python examples/paper_forward_whirl.py [--short] [--out DIR]

Combined axial-radial landing at 7000 rpm with 4 kN thrust onto the NDE face; the paper measured a
forward whirl at about 65 Hz. Units: SI; speeds in rpm, frequencies in Hz as named.
"""

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import rotorlanding as rl
from _common import SCENARIOS, arguments

PAPER_WHIRL_HZ = 65.0  # Fig. 39 at 7000 rpm


def main(argv=None):
    """The example's work: land the paper's 7000 rpm combined drop, print its whirl, draw the
    figure into --out; returns the landing."""
    args = arguments(__doc__, "paper_forward_whirl", argv)
    scenario = rl.Scenario.load(SCENARIOS / "paper" / "forward_whirl_landing.toml")
    landing = rl.simulate(scenario, t_end=0.3 if args.short else scenario.t_end)
    w = landing.whirl
    print(landing)
    print(f"whirl at the {w['bearing']} bearing: {w['direction']}, {w.get('frequency_hz') or float('nan'):.1f} Hz "
          f"(paper: forward, {PAPER_WHIRL_HZ:.0f} Hz), from t = {w.get('onset_s') or float('nan'):.3f} s")

    # one figure a colleague reads: DE orbit in the clearance, vertical displacement and force in time
    t = landing.t
    clear_mm = landing.summary["bearings"]["DE"]["clearance_m"] * 1e3
    y, z = landing["DE_y_m"].values * 1e3, landing["DE_z_m"].values * 1e3  # absolute (housing frame)
    # the journal relative to the inner race: the clearance bounds it (up to the Hertz penetration)
    ry = y - landing["DE_race_y_m"].values * 1e3
    rz = z - landing["DE_race_z_m"].values * 1e3
    fig = plt.figure(figsize=(12, 5.2))
    ax = fig.add_subplot(1, 2, 1)
    th = np.linspace(0, 2 * np.pi, 300)
    ax.plot(clear_mm * np.cos(th), clear_mm * np.sin(th), "b-", lw=1.2, label=f"radial clearance {clear_mm:.2f} mm")
    sc = ax.scatter(ry, rz, c=t, s=1.5, cmap="viridis")
    fig.colorbar(sc, ax=ax, label="time [s]")
    ax.set_aspect("equal")
    ax.set_xlabel("DE journal y relative to the inner race (horizontal) [mm]")
    ax.set_ylabel("DE journal z relative to the inner race (vertical) [mm]")
    ax.set_title(f"DE journal orbit: {w['direction']} whirl {w.get('frequency_hz') or 0:.1f} Hz "
                 f"(paper {PAPER_WHIRL_HZ:.0f} Hz)", fontsize=10)
    ax.legend(loc="upper right", fontsize=8)
    ax.grid(alpha=0.3)
    ax1 = fig.add_subplot(2, 2, 2)
    ax1.plot(t, z, "k-", lw=0.6, label="vertical z")
    ax1.plot(t, y, "tab:orange", lw=0.6, label="horizontal y")
    ax1.set_ylabel("DE journal (housing frame) [mm]")
    ax1.legend(fontsize=8, loc="upper right")
    ax1.grid(alpha=0.3)
    ax2 = fig.add_subplot(2, 2, 4, sharex=ax1)
    force = landing["DE_normal_force_n"]
    ax2.plot(t, force.values * 1e-3, "tab:red", lw=0.6)
    ax2.set_ylabel("DE race contact normal force [kN]")
    ax2.set_xlabel("time [s]")
    ax2.grid(alpha=0.3)
    fig.suptitle(f"{scenario.name}: {scenario.speed_rpm:.0f} rpm drop", fontsize=11)
    fig.tight_layout()
    fig.savefig(args.out / "forward_whirl.png", dpi=120)
    plt.close(fig)  # main may be called again in one session (a script, a notebook)
    landing.plot_spectrum(args.out / "spectrum.png")
    landing.save(args.out / "results.h5")
    print(f"figures and results.h5 in {args.out}")
    return landing


if __name__ == "__main__":
    main()
