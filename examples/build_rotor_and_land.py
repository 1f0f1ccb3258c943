"""Build a rotor in Python, look at its Campbell diagram, and drop it onto the rig's catcher bearings.

    python examples/build_rotor_and_land.py [--short] [--out DIR]

Units: SI (m, kg, Pa, kg m^2, N, s); speeds in rpm as named.
"""

import rotorlanding as rl
from _common import SCENARIOS, arguments


def main(argv=None):
    """Build, print the modes, land, save the figures and results; returns the landing (for a
    notebook or another script: importing this file runs nothing; ``argv`` as on the command line,
    None for the process's own)."""
    args = arguments(__doc__, "build_rotor_and_land", argv)

    steel = {"youngs_modulus": 2.1e11, "poisson_ratio": 0.3, "density": 7850.0}
    # left (NDE) to right (DE): actuator stub, NDE landing sleeve, AMB, slender main shaft, AMB,
    # DE landing sleeve, shaft to the thrust disk; the sleeves (59.6 mm) sit in 60 mm catcher bearings
    rotor = rl.Rotor(
        "a Python-built AMB rotor",
        materials={"steel": steel},
        sections=[
            {"length": 0.115, "outer_diameter": 0.07, "material": "steel", "elements": 4},
            {"length": 0.04, "outer_diameter": 0.0596, "material": "steel", "elements": 2},
            {"length": 0.10, "outer_diameter": 0.07, "material": "steel", "elements": 3},
            {"length": 0.70, "outer_diameter": 0.04, "material": "steel", "elements": 14},
            {"length": 0.10, "outer_diameter": 0.07, "material": "steel", "elements": 3},
            {"length": 0.04, "outer_diameter": 0.0596, "material": "steel", "elements": 2},
            {"length": 0.20, "outer_diameter": 0.05, "material": "steel", "elements": 4},
        ],
        disks=[
            {"name": "actuator", "position": 0.0, "outer_diameter": 0.40, "inner_diameter": 0.07, "thickness": 0.02,
             "material": "steel"},
            {"name": "thrust", "position": 1.295, "outer_diameter": 0.20, "inner_diameter": 0.05, "thickness": 0.025,
             "material": "steel"},
        ],
        stations={"NDE_sleeve": 0.135, "DE_sleeve": 1.075},
        # AMBs as linear supports for the Campbell diagram (the landing drops them)
        supports=[{"station": "NDE_sleeve", "kyy": 3.6e7, "kzz": 3.6e7},
                  {"station": "DE_sleeve", "kyy": 3.6e7, "kzz": 3.6e7}],
        reduction={"boundary_stations": ["NDE_sleeve", "DE_sleeve"], "modes": 14},
        max_speed_rpm=10000.0,
    )
    print(rotor)
    rotor.to_toml(args.out / "rotor.toml")  # `rotorlanding modes` reads it too

    modes = rotor.modes([0.0, 7000.0], n_modes=4)
    for speed, f, w in zip(modes.speeds_rpm, modes.frequencies_hz, modes.whirl):
        print(f"{speed:6.0f} rpm: " + ", ".join(f"{x:.1f} Hz {s}" for x, s in zip(f, w)))
    modes.campbell(args.out / "campbell.png", points=5 if args.short else 41)

    # land it on the rig's catcher bearings (scenarios/landing_7000rpm.toml): 7000 rpm radial drop
    scenario = rl.Scenario.load(SCENARIOS / "landing_7000rpm.toml").with_rotor(rotor)
    landing = rl.simulate(scenario, t_end=0.05 if args.short else 0.5)
    print(landing)
    for b, s in landing.summary["bearings"].items():
        print(f"{b}: peak force on the rotor {s['max_contact_force_n']:.0f} N, "
              f"vertical range {s['vertical_displacement_range_m'][0] * 1e3:+.3f} mm")
    force = landing["DE_normal_force_n"]
    print(f"DE normal force at the end: {force.values[-1]:.0f} {force.unit}")
    landing.plot_orbits(args.out / "orbits.png")
    landing.plot_displacements(args.out / "displacements.png")
    landing.save(args.out / "results.h5")
    print(f"figures and results.h5 in {args.out}")
    return landing


if __name__ == "__main__":
    main()
