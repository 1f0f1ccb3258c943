"""Import a rotor from ROSS and drop it onto catcher bearings.

    python examples/ross_landing.py [--short] [--out DIR]

The rotor is a compressor-like ROSS rotor (hollow impeller section, conical transitions, three
impellers, an overhung coupling hub, two bearings with cross-coupled coefficients) saved by ROSS
2.3's ``rotor.save("compressor_ross.toml")`` (tests/fixtures/ross/make_fixtures.py). It is read
without ROSS; with ROSS installed (``pip install '.[ross]'``) a live rotor converts the same way:
``rl.Rotor.from_ross(ross_rotor, catcher_nodes=...)``. The ROSS bearings (the AMBs) become linear
supports for the Campbell diagram; the landing drops the rotor from them onto the rig's catcher
bearings (scenarios/landing_7000rpm.toml), placed at the shaft ends (ROSS nodes 0 and 10). The
command line reads the same file: ``rotorlanding modes examples/data/compressor_ross.toml``.

Units: SI (m, kg, N, s); speeds in rpm, frequencies in Hz as named.
"""

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.patches import Polygon, Rectangle  # noqa: E402

import rotorlanding as rl  # noqa: E402
from _common import SCENARIOS, arguments  # noqa: E402
from pathlib import Path  # noqa: E402

ROSS_FILE = Path(__file__).resolve().parent / "data" / "compressor_ross.toml"


def draw_rotor(rotor, path):
    """Side view of the converted rotor [mm]: sections (conical ones as cones, bores white),
    disks (diameter of a solid disk of the same m and Ip), ROSS bearings and the catcher sleeves."""
    m = rotor.model
    fig, ax = plt.subplots(figsize=(9, 3.6))
    x0 = 0.0
    for s in m.sections:
        (do_l, di_l), (do_r, di_r) = s.diameters(0.0), s.diameters(1.0)
        x1 = x0 + s.length
        for sign in (1, -1):
            ax.add_patch(Polygon([(x0 * 1e3, sign * di_l / 2e-3), (x1 * 1e3, sign * di_r / 2e-3),
                                  (x1 * 1e3, sign * do_r / 2e-3), (x0 * 1e3, sign * do_l / 2e-3)],
                                 closed=True, fc="0.65", ec="0.3", lw=0.8))
        x0 = x1
    for d in m.disks:
        dia = (8.0 * d.polar_inertia / d.mass) ** 0.5 if d.mass > 0 else 0.0
        ax.add_patch(Rectangle((d.position * 1e3 - 6, -dia / 2e-3), 12, dia / 1e-3, fc="firebrick", ec="0.2",
                               alpha=0.85))
    shaft_top = max(s.max_outer_diameter for s in m.sections) / 2e-3
    top = max([shaft_top] + [(8.0 * d.polar_inertia / d.mass) ** 0.5 / 2e-3 for d in m.disks if d.mass > 0])
    for sup in m.supports:
        x = m.stations[sup.station] * 1e3
        ax.plot([x], [-shaft_top - 12], marker="^", ms=13, color="#355d7a")
        ax.annotate(f"ROSS bearing {sup.station}\nk_yy {sup.kyy / 1e6:.0f}, k_zz {sup.kzz / 1e6:.0f} MN/m", (x, -shaft_top - 24),
                    ha="center", va="top", fontsize=8, color="#355d7a")
    for st in m.reduction.boundary_stations:
        x = m.stations[st] * 1e3
        ax.axvline(x, color="tab:orange", lw=1.5, ls="--")
        left = x < m.length * 1e3 / 2
        ax.annotate(f" catcher bearing {st} " if left else f"catcher bearing {st} ", (x, top + 8),
                    ha="left" if left else "right", fontsize=9, color="tab:orange")
    ax.set_xlim(-40, m.length * 1e3 + 40)
    ax.set_ylim(-top - 20, top + 35)
    ax.set_aspect("equal")
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("radius [mm]")
    ax.set_title(f"{rotor.name}: {rotor.mass:.1f} kg, {len(m.sections)} sections "
                 f"({sum(s.tapered for s in m.sections)} conical), {len(m.disks)} disks (red: solid disk of the same "
                 "m and Ip)", fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=130)
    plt.close(fig)


def main(argv=None):
    """The example's work: convert the ROSS rotor, draw it, print its modes and land it from 7000 rpm
    into --out; returns the landing."""
    args = arguments(__doc__, "ross_landing", argv)

    # the catcher-bearing sleeves at ROSS nodes 0 and 10; their names are the scenario's bearing stations
    rotor = rl.Rotor.from_ross(ROSS_FILE, catcher_nodes={"NDE_sleeve": 0, "DE_sleeve": 10}, reduction_modes=12,
                               name="compressor rotor from ROSS")
    print(rotor)
    rotor.to_toml(args.out / "rotor.toml")  # the converted rotor as a rotorlanding rotor file
    draw_rotor(rotor, args.out / "rotor.png")

    # natural frequencies on the ROSS bearings (the supports), the same as ROSS's own (docs/ross.md)
    modes = rotor.modes([0.0, 7000.0], n_modes=4)
    table = modes.to_dict()
    for speed, per_speed in zip(table["speeds_rpm"], table["modes"]):
        print(f"{speed:6.0f} rpm:", "  ".join(f"{m['frequency_hz']:.1f} Hz ({m['whirl']}, zeta {m['damping_ratio']:.3f})"
                                             for m in per_speed))
    modes.campbell(args.out / "campbell.png", points=5 if args.short else 41)

    # drop it from 7000 rpm onto the rig's catcher bearings (the AMBs switch off at t = 0)
    scenario = rl.Scenario.load(SCENARIOS / "landing_7000rpm.toml").with_rotor(rotor)
    landing = rl.simulate(scenario, t_end=0.05 if args.short else 0.5)
    print(landing)
    peaks = {b: s["max_contact_force_n"] for b, s in landing.summary["bearings"].items()}
    print("peak contact force on the rotor:", ", ".join(f"{b} {f / 1e3:.2f} kN" for b, f in peaks.items()),
          f"(rotor weight {rotor.mass * 9.80665 / 1e3:.2f} kN)")
    w = landing.whirl
    print(f"whirl: {w['direction']}" + (f" at {w['frequency_hz']:.1f} Hz from {w['onset_s']:.3f} s" if w["frequency_hz"] else ""))
    landing.plot_orbits(args.out / "orbits.png")
    landing.plot_displacements(args.out / "displacements.png")
    landing.plot_forces(args.out / "forces.png")
    landing.save(args.out / "results.h5")
    print(f"figures and results.h5 in {args.out}")
    return landing


if __name__ == "__main__":
    main()
