"""A sensor model of our own for the diagnose tests (issue 20): not the project's benchdata
generator. A simulated landing is sampled by a data logger at its own rate with a random phase,
after a pre-trigger stretch (the rotor levitated at its centre, speeds constant), with white noise
per channel (displacement, speed), the drop at a known instant of the logger's clock; channels
can be left out. Written as a CSV the diagnose command reads."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from rotorlanding.diagnose_run import _simulate_features

ROOT = Path(__file__).resolve().parents[1]
#: the rig the diagnose tests were sized on: the first rig rotor with the bearings of
#: tests/known_rig_bearings.toml, so a change of the shipped rig does not move their gaps
KNOWN_RIG = (f'include = ["{ROOT / "scenarios" / "landing_7000rpm.toml"}", '
             f'"{ROOT / "scenarios" / "rig_rotor_first.toml"}", '
             f'"{ROOT / "tests" / "known_rig_bearings.toml"}"]')
#: its radial clearance [m]
C = 2e-4
#: the axial landing of the combined (forward-whirl) cases: the paper's 4 kN thrust, axial AMB off
THRUST = "[axial]\nf_thrust = 4000.0\n[amb]\ndrop_axial = true\n"


def known_rig_model(path, off=(), *, t_end: float = 0.3, extra: str = "") -> Path:
    """Write the model file the diagnose tests and benches land: the known rig at 7000 rpm for
    ``t_end`` s, the effects in ``off`` switched off, ``extra`` TOML appended (e.g. :data:`THRUST`)."""
    path = Path(path)
    effects = "[effects]\n" + "".join(f"{e} = false\n" for e in off) if off else ""
    path.write_text(f"{KNOWN_RIG}\n{effects}[operating]\nspeed_rpm = 7000.0\nt_end = {t_end!r}\n{extra}")
    return path

CHANNELS = ("DE_y_m", "DE_z_m", "NDE_y_m", "NDE_z_m", "rotor_speed_rpm", "DE_inner_race_speed_rpm")


def write_record(scenario, overrides, csv, *, clearance, seed=0, fs_hz=4000.0, noise_m=1.0e-6, noise_rpm=2.0,
                 pre_trigger_s=0.2, drop_at_s=3.0, channels=CHANNELS, noise_by_channel=None):
    """Simulate ``scenario`` with ``overrides`` and write what the logger saw; returns the drop
    instant in the logger's clock (the truth). ``noise_by_channel`` (name -> standard deviation)
    replaces ``noise_m`` / ``noise_rpm`` for the channels it names (a rig's sensors differ)."""
    rng = np.random.default_rng(seed)
    _, m = _simulate_features(scenario, list(overrides), clearance, with_series=True)
    t_sim = m.series("DE_z_m")[0]
    phase = rng.uniform(0.0, 1.0 / fs_hz)
    t = np.arange(-pre_trigger_s + phase, t_sim[-1], 1.0 / fs_hz)
    cols = [t + drop_at_s]
    for name in channels:
        ts, v = m.series(name)
        before = 0.0 if name.endswith("_m") else float(v[0])  # levitated at the centre, speeds as at the drop
        vu = np.where(t < ts[0], before, np.interp(t, ts, v))
        sigma = (noise_by_channel or {}).get(name, noise_m if name.endswith("_m") else noise_rpm)
        cols.append(vu + rng.normal(0.0, sigma, t.size))
    np.savetxt(csv, np.column_stack(cols), delimiter=",", header=",".join(("time_s",) + tuple(channels)),
               comments="")
    return drop_at_s
