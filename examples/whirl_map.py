"""A speed x radial-friction whirl map: which landings whirl forward, backward or not at all.

    python examples/whirl_map.py [--short] [--out DIR]

Varies the drop speed operating.speed_rpm [rpm] and the radial friction coefficient
contact.mu_rad [-] of the paper's combined landing (4 kN thrust onto the NDE face) with rl.sweep:
the grid is given in Python, the cases run in parallel worker processes (`rotorlanding sweep`'s
runner; out/sweep_input.toml repeats it from the command line), and the Sweep draws the map. The
orbits of the case with the strongest whirl show it inside the clearance. --short: a 2 x 2 grid of
0.3 s landings; full: 4 x 5 landings of 0.6 s. Units: SI; speeds in rpm, frequencies in Hz.
"""

import rotorlanding as rl
from _common import SCENARIOS, arguments


def main(argv=None):
    """The example's work: run the grid (worker processes: the __main__ guard keeps them from
    re-running it on import), print and draw the map and the strongest whirl's orbits; returns the Sweep."""
    args = arguments(__doc__, "whirl_map", argv)
    base = rl.Scenario.load(SCENARIOS / "paper" / "forward_whirl_landing.toml")
    grid = {"operating.speed_rpm": [3000.0, 10000.0] if args.short else [3000.0, 5000.0, 7000.0, 10000.0],
            "contact.mu_rad": [0.05, 0.3] if args.short else [0.05, 0.1, 0.15, 0.3, 0.5]}
    t_end = 0.3 if args.short else 0.6  # s after the start; the drop is at amb.t_drop
    sw = rl.sweep(base, args.out, grid=grid, fixed={"operating.t_end": t_end}, workers=2)
    print(sw)
    for r in sw.table:
        f = r["whirl_frequency_hz"]
        print(f"{r['operating.speed_rpm']:7.0f} rpm, mu_rad {r['contact.mu_rad']:4.2f}: {r['status']:6s} "
              f"{r['whirl_direction'] or '-':8s} {'' if f is None else f'{f:6.1f} Hz'}"
              f"  DE peak {r['DE_max_contact_force_n'] / 1e3 if r['DE_max_contact_force_n'] else float('nan'):.2f} kN")
    sw.whirl_map(args.out / "whirl_map.png")

    # the case whose whirl is strongest (largest whirl amplitude), its orbits in the clearance circle
    whirling = [r for r in sw.table if r["status"] == "ok" and r["whirl_direction"] in ("forward", "backward")]
    if whirling:
        amp = {r["case"]: (sw.case_landing(r["case"]).whirl.get("amplitude_m") or 0.0) for r in whirling}
        case = max(amp, key=amp.get)
    else:
        case = sw.table[0]["case"]
    landing = sw.case_landing(case)
    row = sw.table[case]
    print(f"orbits of case {case} ({row['operating.speed_rpm']:.0f} rpm, mu_rad {row['contact.mu_rad']:g}): "
          f"whirl {landing.whirl['direction']}, amplitude {1e3 * (landing.whirl.get('amplitude_m') or 0):.3f} mm")
    landing.plot_orbits(args.out / "orbits.png")
    print(f"figures in {args.out}: whirl_map.png, orbits.png; table: {args.out / 'sweep.csv'}")
    return sw


if __name__ == "__main__":
    main()
