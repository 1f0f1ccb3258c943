"""Figures of a landing run (PNG): displacements, forces, orbits with the clearance circle,
speeds, full spectrum, energy, and the rotor's excursion along its span with the catcher clearances
and the close clearances (AMB stators, sensors, seals) drawn."""

from __future__ import annotations

import textwrap
from pathlib import Path

import numpy as np

from .mechanisms import rotor_force
from .safeio import save_figure
from .postprocess import uniform
from .whirl import full_spectrum


def _wrap(text: str, width: int = 90) -> str:
    """A figure title on as many lines as it needs: a 9-inch figure shows about 90 characters
    of the default title font, and a scenario's name plus the plot's own title ran past its edge."""
    return textwrap.fill(text, width)


def _plt():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


FIGURES = ("displacements", "forces", "orbits", "speeds", "spectrum", "energy", "span")


def plot_all(out_dir, t, series: dict, summary: dict, bearings: dict, t_drop: float = 0.0,
             which=None) -> list[Path]:
    """Write every figure (or those named in ``which``, a subset of :data:`FIGURES`) as
    ``NAME.png``; ``bearings`` maps name -> clearance [m]. Returns the files written."""
    def want(name: str) -> bool:
        return which is None or name in which

    plt = _plt()
    out = Path(out_dir)
    files = []
    names = list(bearings)
    title = summary.get("scenario", "")

    def save(fig, fname):
        fig.tight_layout()
        files.append(out / fname)
        save_figure(fig, files[-1], dpi=110)
        plt.close(fig)

    def time_histories(curves, ylabel, suptitle, fname, band=None):
        """One panel per bearing: curves(b) -> [(values, label)], optional +/- band (dotted)."""
        fig, axes = plt.subplots(len(names), 1, figsize=(9, 3.2 * len(names)), sharex=True, squeeze=False)
        for ax, b in zip(axes[:, 0], names):
            for k, (vals, label) in enumerate(curves(b)):
                ax.plot(t, vals, label=label, alpha=1.0 if k == 0 else 0.8)
            if band is not None:
                for sgn in (-1, 1):
                    ax.axhline(sgn * band(b), color="k", ls=":", lw=0.8)
            ax.set_ylabel(ylabel.format(b=b))
            ax.legend(loc="upper right", fontsize=8)
            ax.grid(alpha=0.3)
        axes[-1, 0].set_xlabel("time [s]")
        fig.suptitle(_wrap(f"{title}: {suptitle}"))
        save(fig, fname)

    if want("displacements"):
        time_histories(lambda b: [(series[f"{b}_z_m"] * 1e3, "vertical z"), (series[f"{b}_y_m"] * 1e3, "horizontal y")],
                       "{b} journal [mm]", "journal displacement (dotted: +/- radial clearance)", "displacements.png",
                       band=lambda b: bearings[b] * 1e3)
    if want("forces"):
        # the force the race exerts on the rotor, positive up: the sign of the paper's Figs. 12, 22, 30
        # and Tables 1-2 (a rotor resting on its catcher bearing is pushed up)
        time_histories(lambda b: [(rotor_force(series, b)[1] * 1e-3, "vertical z (on the rotor)"),
                                  (rotor_force(series, b)[0] * 1e-3, "horizontal y (on the rotor)")],
                       "{b} force on the rotor [kN]", "force on the rotor (race contact + face rub)",
                       "forces.png")

    if want("orbits"):
        # top: the journal relative to the inner race, which the clearance bounds (up to the Hertz
        # penetration); bottom: the absolute journal orbit, which also carries the race's excursion
        # on the ball set and ribbon, so it runs past the clearance under load
        fig, axes = plt.subplots(2, len(names), figsize=(5 * len(names), 10), squeeze=False)
        th = np.linspace(0, 2 * np.pi, 200)
        for col, b in enumerate(names):
            c = bearings[b] * 1e3
            w = summary["whirl"]["per_bearing"].get(b, {})
            txt = w.get("direction", "none") + (f" whirl {w['frequency_hz']:.1f} Hz" if w.get("frequency_hz") else "")
            rel = f"{b}_race_y_m" in series
            views = [("relative to the inner race", series[f"{b}_y_m"] - series[f"{b}_race_y_m"],
                      series[f"{b}_z_m"] - series[f"{b}_race_z_m"])] if rel else []
            views.append(("absolute (housing frame;\nincludes race, ball-set and ribbon deflection)",
                          series[f"{b}_y_m"], series[f"{b}_z_m"]))
            for row in range(2):
                ax = axes[row, col]
                if row >= len(views):
                    ax.set_visible(False)
                    continue
                label, yy, zz = views[row]
                ax.plot(c * np.cos(th), c * np.sin(th), "b-", lw=1.2, label=f"radial clearance {c:.3g} mm")
                ax.plot(yy * 1e3, zz * 1e3, "k-", lw=0.5, label="journal orbit")
                ax.set_aspect("equal")
                ax.set_xlabel("y (horizontal) [mm]")
                ax.set_ylabel("z (vertical) [mm]")
                ax.set_title(f"{b} journal {label}:\n{txt}", fontsize=9)
                ax.grid(alpha=0.3)
                ax.legend(loc="upper right", fontsize=8)
        save(fig, "orbits.png")

    if want("speeds"):
        fig, ax = plt.subplots(figsize=(9, 4))
        ax.plot(t, series["rotor_speed_rpm"], "k", label="rotor")
        for b in names:
            ax.plot(t, series[f"{b}_race_speed_rpm"], label=f"{b} inner race")
        ax.set_xlabel("time [s]")
        ax.set_ylabel("speed [rpm]")
        ax.legend(fontsize=8)
        ax.grid(alpha=0.3)
        ax.set_title(_wrap(f"{title}: rotor and inner-race speeds"))
        save(fig, "speeds.png")

    if want("spectrum"):
        fig, axes = plt.subplots(len(names), 1, figsize=(9, 3.2 * len(names)), squeeze=False)
        sel = t >= t_drop
        for ax, b in zip(axes[:, 0], names):
            if sel.sum() >= 16:
                f, a = full_spectrum(*uniform(t[sel], series[f"{b}_y_m"][sel], series[f"{b}_z_m"][sel]))
                ax.plot(f, a * 1e6, "k-", lw=0.8)
                spin = series["rotor_speed_rpm"][-1] / 60.0
                ax.axvline(spin, color="r", ls="--", lw=0.8, label="+1x (end of run)")
                ax.axvline(-spin, color="r", ls=":", lw=0.8, label="-1x")
                ax.set_xlim(-3 * spin, 3 * spin)
            ax.set_ylabel(f"{b} [um]")
            ax.grid(alpha=0.3)
            ax.legend(fontsize=8)
        axes[-1, 0].set_xlabel("full-spectrum frequency [Hz] (negative = backward whirl)")
        fig.suptitle(_wrap(f"{title}: full spectrum of y + i z after the drop"))
        save(fig, "spectrum.png")

    if want("energy"):
        fig, ax = plt.subplots(figsize=(9, 4))
        for k, v in series.items():
            if k.startswith("dissipated_") and v[-1] > 1e-3 * max(1e-12, summary["energy"]["dissipated_total_j"]):
                ax.plot(t, v, label=k[len("dissipated_"):-2].replace("_", " "))
        ax.set_xlabel("time [s]")
        ax.set_ylabel("energy dissipated [J]")
        ax.set_yscale("symlog", linthresh=1e-2)
        ax.legend(fontsize=8)
        ax.grid(alpha=0.3)
        ax.set_title(_wrap(f"{title}: energy lost per mechanism"))
        save(fig, "energy.png")

    span = summary.get("rotor_deflection") or {}
    if want("span") and span.get("node_peak_m"):
        fig, ax = plt.subplots(figsize=(9, 4.6))
        x = np.asarray(span["x_m"])
        ax.plot(x, 1e3 * np.asarray(span["node_peak_m"]), "-", color="C0", lw=1.5,
                label="largest excursion over the run")
        peaks, where = span["station_peak_m"], span["station_x_m"]
        catchers = {bs["station"]: (name, bs["clearance_m"]) for name, bs in (summary.get("bearings") or {}).items()
                    if bs.get("station") in where}
        for k, (st, (name, c)) in enumerate(catchers.items()):
            ax.plot([where[st]], [1e3 * c], "v", color="k", ms=8, label=None if k else "catcher bearing radial clearance")
            ax.annotate(name, (where[st], 1e3 * c), textcoords="offset points", xytext=(0, 8), ha="center", fontsize=8)
        gaps = {st: g for st, g in (span.get("close_clearances_m") or {}).items() if st in where}
        for k, (st, gap) in enumerate(gaps.items()):
            ax.plot([where[st]], [1e3 * gap], "v", color="C3", ms=8,
                    label=None if k else "close clearance ([limits] close_clearances_m)")
            ax.annotate(st + (" PAST" if peaks.get(st, 0.0) > gap else ""), (where[st], 1e3 * gap),
                        textcoords="offset points", xytext=(0, 8), ha="center", fontsize=8, color="C3")
        ax.set_xlabel("position along the rotor x [m] (from the NDE end)")
        ax.set_ylabel("radial displacement off the bearings' axis [mm]")
        ax.set_ylim(bottom=0.0)
        ax.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.16), ncol=3)  # below: the curve fills the axes
        ax.grid(alpha=0.3)
        ax.set_title(_wrap(f"{title}: how far the rotor runs off the bearings' axis along its span "
                           "(levitated axis; gravity sag and support deflection included)"))
        save(fig, "span.png")
    return files
