"""Session 32: the sleeve's slip speed on the DE race by phase of one landing (docs/studies/onset_probe/README.md).

    rotorlanding run scenarios/paper/backward_whirl_landing.toml --out bw   # the centred drop, about 5 s
    python docs/studies/onset_probe/slip_phases.py bw/results.h5

Prints, per time window, the share of samples in contact (DE normal force > 1 N), the median and 90th
percentile of |slip| over those samples and the mean DE race / rotor speed.
"""

import sys

import h5py
import numpy as np

WINDOWS_S = ((0.0, 0.01), (0.01, 0.03), (0.03, 0.06), (0.06, 0.1), (0.1, 0.2), (0.2, 0.35), (0.35, 0.6), (0.6, 1.2))


def main(argv=None) -> int:
    path = (argv or sys.argv[1:])[0]
    with h5py.File(path, "r") as f:
        s, t = f["series"], f["time_s"][:]
        vs, fn = s["DE_slip_velocity_m_s"][:], s["DE_normal_force_n"][:]
        ratio = s["DE_race_speed_rpm"][:] / s["rotor_speed_rpm"][:]
    print("window [s] | in contact | |slip| median / 90th percentile [m/s] | race / rotor speed")
    for a, b in WINDOWS_S:
        w = (t >= a) & (t < b)
        c = w & (fn > 1.0)
        med, p90 = (np.median(abs(vs[c])), np.percentile(abs(vs[c]), 90)) if c.any() else (0.0, 0.0)
        print(f"{a:.2f}-{b:.2f} | {c.sum() / w.sum():.2f} | {med:.2f} / {p90:.2f} | {ratio[w].mean():.3f}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
