"""Diagnose a measured landing: which effect the model lacks explains where it and the rig disagree.

    python examples/diagnose_measured.py [--short] [--out DIR]

The measurement is the paper's forward-whirl combined landing (scenarios/measured/
paper_table2_fig39.toml: Fig. 39's whirl at 48 / 65 / 77 Hz at 3000 / 7000 / 10000 rpm and Table
2's DE displacement and force range at 7000 rpm, the format of docs/measured_data.md). The model
is scenarios/paper/forward_whirl_landing.toml with axial rub switched off, as if we did not know
about it: rl.diagnose calibrates each effect the model lacks on the joint gap and names the one
that significantly shrinks it. Then the model before and after is landed again and drawn against
the measured numbers. --short: the 7000 and 10000 rpm points, 0.5 s runs, axial rub the one
candidate, a coarse search (about 20 s on 2 cores). Units: SI; speeds in rpm, frequencies in Hz, the figure in mm and kN as
labelled.

On the present rig rotor (session 15) the answer is honest but not the paper's: axial rub is the best
candidate and brings back the forward whirl at both speeds, yet nothing is named, because with it the
model's DE force and displacement stay at about twice Table 2's range (the open model gap of
docs/calibration.md), so the gap shrinks only 2.62 -> 2.16 and does not pay for the fitted mu_ax.
"""

import json
import tomllib

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

import rotorlanding as rl
from rotorlanding.mechanisms import rotor_force  # force of a bearing on the rotor (race contact + face rub)
from rotorlanding.postprocess import uniform
from rotorlanding.whirl import full_spectrum
from _common import SCENARIOS, arguments


def main(argv=None):
    """Diagnose the paper's measured features against the model without axial rub, land the model
    before and after at 7000 rpm and draw both against the measured numbers; returns the Diagnosis."""
    args = arguments(__doc__, "diagnose_measured", argv)
    table = SCENARIOS / "measured" / "paper_table2_fig39.toml"
    model = rl.Scenario.load(SCENARIOS / "paper" / "forward_whirl_landing.toml", set={"effects.axial_rub": False})
    measured = tomllib.loads(table.read_text())["points"]
    if args.short:  # two operating points of the table (a feature table may hold any subset)
        measured = {k: measured[k] for k in ("rpm_7000", "rpm_10000")}
        table = args.out / "paper_7000_10000rpm.json"
        table.write_text(json.dumps({"title": "paper Table 2 and Fig. 39 at 7000 and 10000 rpm", "points": measured}))
        # a single point would not do: its six features cannot pay the fitted parameter's penalty
        # in the score (n ln gap^2 + k ln n), so the search needs the two speeds to name an effect
        options = dict(t_end=0.5, candidates=["axial_rub"], maxiter=2)
    else:
        options = dict(t_end=1.0)  # every effect the model lacks is a candidate (faults only when named)

    dg = rl.diagnose(table, model, args.out, workers=2, **options)
    print(dg)
    print(f"gap before {dg.gap_before:.3f}, after {dg.gap_after:.3f}; named effect: {dg.named_effect}")
    print(f"calibrated: {dg.calibrated}")
    for p in dg.points:
        print(f"  {p['name']}: whirl measured {p['whirl_measured']}, model before {p['whirl_before']}, "
              f"after {p['whirl_after']}")
    print(f"report: {dg.report_md}, figure: {dg.figure}")

    # the model before and after, landed again at 7000 rpm and drawn against the paper's numbers
    point = measured["rpm_7000"]["features"]
    runs = {"model before (no axial rub)": model.replace(operating__speed_rpm=7000.0)}
    runs["model after (" + (dg.named_effect or "nothing named") + ")"] = runs["model before (no axial rub)"].with_overrides(
        dg.calibrated)
    landings = {k: rl.simulate(sc, t_end=options["t_end"]) for k, sc in runs.items()}
    clear_mm = model.model.bearings["DE"].clearance * 1e3
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.8))
    for (label, ld), c in zip(landings.items(), ("tab:blue", "tab:green")):
        t = ld.t
        axes[0].plot(t, ld["DE_z_m"].values * 1e3, color=c, lw=0.7, label=label)
        axes[1].plot(t, rotor_force({k: ld[k].values for k in ld.series_names}, "DE")[1] * 1e-3, color=c, lw=0.7,
                     label=label)
        w = ld.whirl
        sel = t >= 0.05  # after the drop's first impacts
        f, a = full_spectrum(*uniform(t[sel], ld["DE_y_m"].values[sel], ld["DE_z_m"].values[sel]))
        axes[2].plot(f, a * 1e6, color=c, lw=0.8,
                     label=f"{label}: {w['direction']}" + (f" {w['frequency_hz']:.0f} Hz" if w.get("frequency_hz") else ""))
    for sgn in (-1, 1):
        axes[0].axhline(sgn * clear_mm, color="b", ls=":", lw=1.0, label="+/- radial clearance (bounds the journal\nrelative to its race, not this absolute z)" if sgn > 0 else None)
    for key, ax, scale, name in (("DE_vertical_max_m", axes[0], 1e3, "measured range"),
                                 ("DE_vertical_min_m", axes[0], 1e3, None),
                                 ("DE_force_z_max_n", axes[1], 1e-3, "measured range"),
                                 ("DE_force_z_min_n", axes[1], 1e-3, None)):
        if key in point:
            ax.axhline(point[key] * scale, color="k", ls="--", lw=1.2, label=name)
    axes[2].axvline(point["whirl_frequency_hz"], color="k", ls="--", lw=1.2,
                    label=f"measured: {point['whirl_direction']} {point['whirl_frequency_hz']:.0f} Hz")
    axes[2].axvline(7000.0 / 60.0, color="r", ls=":", lw=0.8, label="1x spin")
    axes[0].set_ylabel("DE journal vertical z (housing frame) [mm]")
    axes[1].set_ylabel("DE vertical force on the rotor [kN]")
    axes[2].set_ylabel("full spectrum of y + i z at DE [um]")
    axes[2].set_xlabel("frequency [Hz] (negative: backward whirl)")
    axes[2].set_xlim(-250, 250)
    for ax in axes[:2]:
        ax.set_xlabel("time after the drop [s]")
    for ax in axes:
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7, loc="best", framealpha=0.9)
    fig.suptitle(f"paper forward-whirl landing at 7000 rpm, measured vs model: gap {dg.gap_before:.2f} -> "
                 f"{dg.gap_after:.2f}, named: {dg.named_effect}", fontsize=11)
    fig.tight_layout()
    fig.savefig(args.out / "measured_vs_model.png", dpi=120)
    plt.close(fig)
    print(f"figure: {args.out / 'measured_vs_model.png'}")
    return dg


if __name__ == "__main__":
    main()
