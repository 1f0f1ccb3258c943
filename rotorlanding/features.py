"""Discrepancy features of a landing and one gap number (model-gap workflow, issue 5).

Each feature has a value and a *scale* (what counts as a meaningful difference), so differences
of different quantities are comparable: distance = |measured - simulated| / scale. The whirl
direction is categorical (distance 0 or ``DIRECTION_MISMATCH``); when directions differ, whirl
frequency and onset are not compared. The gap is sqrt(sum w d^2 / sum w) over the features
present in both, with the per-feature table.
"""

from __future__ import annotations

import math

import numpy as np

from .measured import Measurement
from .whirl import whirl_analysis

DIRECTION_MISMATCH = 3.0


def _uniform(t, v, dt=None):
    dt = dt or float(np.median(np.diff(t)))
    tu = np.arange(t[0], t[-1] + 0.5 * dt, dt)
    return tu, np.interp(tu, t, v)


def extract_features(m: Measurement, *, clearance: float, bearing: str = "DE", t_drop: float = 0.0) -> dict:
    """Features (value, scale) from whichever channels the measurement has."""
    f: dict[str, tuple] = {}
    c = clearance
    yk, zk = f"{bearing}_y_m", f"{bearing}_z_m"
    if m.has(yk) and m.has(zk):
        ty, y = m.series(yk)
        tz, z = m.series(zk)
        t0, t1 = max(ty[0], tz[0], t_drop), min(ty[-1], tz[-1])
        dt = max(float(np.median(np.diff(ty))), float(np.median(np.diff(tz))))
        tu = np.arange(t0, t1, dt)
        yu, zu = np.interp(tu, ty, y), np.interp(tu, tz, z)
        spin = None
        if m.has("rotor_speed_rpm"):
            ts, s = m.series("rotor_speed_rpm")
            spin = np.interp(tu, ts, s) / 60.0
        try:
            w = whirl_analysis(tu, yu, zu, clearance=c, spin_hz=spin, t_start=t0)
            f["whirl_direction"] = (w.direction, None)
            if w.direction != "none":
                f["whirl_frequency_hz"] = (w.frequency_hz, max(2.0, 0.03 * w.frequency_hz))
                f["whirl_onset_s"] = (w.onset_s - t_drop, 0.05)
        except ValueError:
            pass
        late = tu > t0 + 0.1
        if late.any():
            f[f"{bearing}_orbit_radius_mean_m"] = (float(np.mean(np.hypot(yu[late], zu[late]))), 0.1 * c)
        # first bounce: after the first contact (z below -c), the highest point before it falls back
        hit = np.nonzero(zu < -c)[0]
        if hit.size:
            k0 = hit[0]
            k1 = k0 + int(np.argmin(zu[k0:k0 + max(2, int(0.005 / dt))]))  # deepest point of the first impact
            after = zu[k1:k1 + max(2, int(0.03 / dt))]
            f[f"{bearing}_first_rebound_m"] = (float(after.max() - zu[k1]), 0.05 * c)
        f[f"{bearing}_vertical_min_m"] = (float(zu.min()), 0.1 * c)
        f[f"{bearing}_vertical_max_m"] = (float(zu.max()), 0.1 * c)
        f[f"{bearing}_horizontal_min_m"] = (float(yu.min()), 0.1 * c)
        f[f"{bearing}_horizontal_max_m"] = (float(yu.max()), 0.1 * c)
    fy, fz = f"{bearing}_force_y_n", f"{bearing}_force_z_n"
    if m.has(fy) and m.has(fz):
        t, a = m.series(fy)
        _, b = m.series(fz)
        peak = float(np.max(np.hypot(a, np.interp(t, *m.series(fz)))))
        f[f"{bearing}_force_peak_n"] = (peak, max(200.0, 0.15 * peak))
    if m.has("rotor_speed_rpm"):
        t, s = m.series("rotor_speed_rpm")
        sel = t >= t_drop
        if sel.sum() > 2:
            slope = float(np.polyfit(t[sel], s[sel], 1)[0])
            f["rotor_deceleration_rpm_s"] = (-slope, max(5.0, 0.1 * abs(slope)))
        rk = f"{bearing}_inner_race_speed_rpm"
        if m.has(rk):
            tr, r = m.series(rk)
            rotor = np.interp(tr, t, s)
            up = np.nonzero((tr >= t_drop) & (r >= 0.9 * rotor))[0]
            if up.size:
                f[f"{bearing}_race_spinup_s"] = (float(tr[up[0]] - t_drop), 0.02)
    if m.has("axial_m"):
        t, x = m.series("axial_m")
        sel = t >= t_drop + 0.1
        if sel.sum() > 2:
            f["axial_mean_m"] = (float(np.mean(x[sel])), 2e-5)
            f["axial_oscillation_m"] = (float(np.std(x[sel])), 1e-5)
    return f


def features_from_table(table: dict) -> dict:
    """Measured features given as a table {name: value} (scales from the same rules)."""
    out = {}
    for k, v in table.items():
        out[k] = (v, None)
    return out


def gap(measured: dict, simulated: dict, weights: dict | None = None) -> tuple[float, list[dict]]:
    """Weighted normalised distance between two feature sets, and the per-feature table."""
    weights = weights or {}
    rows = []
    dm = measured.get("whirl_direction", (None,))[0]
    ds = simulated.get("whirl_direction", (None,))[0]
    same_direction = dm == ds
    for name in sorted(set(measured) & set(simulated)):
        vm, sm = measured[name]
        vs, ss = simulated[name]
        if name == "whirl_direction":
            d = 0.0 if same_direction else DIRECTION_MISMATCH
        else:
            if name in ("whirl_frequency_hz", "whirl_onset_s") and not same_direction:
                continue
            scale = sm or ss
            if vm is None or vs is None or not scale:
                continue
            d = abs(vm - vs) / scale
        rows.append({"feature": name, "measured": vm, "simulated": vs, "scale": sm or ss, "distance": d,
                     "weight": weights.get(name, 1.0)})
    if not rows:
        return float("nan"), rows
    w = np.array([r["weight"] for r in rows])
    d = np.array([r["distance"] for r in rows])
    return float(math.sqrt(np.sum(w * d * d) / np.sum(w))), rows
