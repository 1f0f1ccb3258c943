"""Hidden-effect test bench for the model-gap workflow: synthetic "measured" data from the full
model with one effect switched on at a random parameter inside its catalogue bounds, with sensor
noise, resampling, a shifted drop instant and a dropped channel. Which effect it was is returned
separately (the truth) and is not in the data file.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from .effects import CATALOGUE


def make_hidden_effect_data(scenario_path, effect: str, out_csv, *, seed: int = 0, noise_rel: float = 0.02,
                            fs_hz: float = 5000.0, drop_at_s: float = 2.5, drop_channel: str | None = None,
                            value: float | None = None, extra: list[str] | None = None) -> dict:
    from .results import read_results
    from .run import run_scenario
    from .scenario import load_scenario

    rng = np.random.default_rng(seed)
    p = CATALOGUE[effect].parameters[0]
    if value is None:
        u = rng.uniform(math.log10(p.lower), math.log10(p.upper)) if p.log else rng.uniform(p.lower, p.upper)
        value = float(10 ** u) if p.log else float(u)
    overrides = (extra or []) + [f"effects.{effect}=true"] + [f"{k}={value!r}" for k in p.keys]
    sc = load_scenario(scenario_path, overrides)
    work = Path(out_csv).with_suffix("")
    run_scenario(sc, work, progress=False, plots=False)
    r = read_results(work / "results.h5")
    t = r["time_s"]
    s = r["series"]
    cols = {"DE_y_m": s["DE_y_m"], "DE_z_m": s["DE_z_m"], "NDE_y_m": s["NDE_y_m"], "NDE_z_m": s["NDE_z_m"],
            "rotor_speed_rpm": s["rotor_speed_rpm"], "DE_inner_race_speed_rpm": s["DE_race_speed_rpm"]}
    if drop_channel:
        cols.pop(drop_channel, None)
    tu = np.arange(t[0], t[-1], 1.0 / fs_hz)
    data = [tu + drop_at_s]
    for name, v in cols.items():
        vu = np.interp(tu, t, v)
        scale = np.std(vu) if name.endswith("_m") else np.mean(np.abs(vu)) * 0.01
        data.append(vu + rng.normal(0.0, noise_rel * max(scale, 1e-12), vu.size))
    np.savetxt(out_csv, np.column_stack(data), delimiter=",", header=",".join(["time_s"] + list(cols)),
               comments="")
    return {"effect": effect, "parameter": p.name, "value": value, "drop_at_s": drop_at_s, "file": str(out_csv)}
