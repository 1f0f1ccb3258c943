"""Session-13 study tool: the DE power balance of landed drops (issue 15, eta and the mu_rad switch).

usage: python docs/studies/eta_power.py OUT/TAG [OUT/TAG ...] [--t0 0.8]

For every drop directory OUT/TAG/dK (written by ``docs/studies/ensemble.py --keep-h5``: since
session 14 the ensemble tool deletes each drop's results.h5 unless asked to keep it) prints, averaged over
t >= t0: the DE race / rotor speed ratio at the end, the DE contact load (mean, mean while in
contact), the DE ribbon deflection |x_o| (race centre off the housing centre), the journal's orbit
radius, and the powers: the contact force's work on the DE journal's lateral motion (the whirl
drive, F_c . v_j), the DE ribbon's cross-coupled (eta) and viscous (c_rib) losses (F . v_o of each
term, recomputed from eq 28-29 on the stored race motion), and the system totals the model books.
"""
from __future__ import annotations

import json
import sys
from pathlib import Path

import h5py
import numpy as np


def drop(d: Path, t0: float) -> dict:
    s = json.loads((d / "summary.json").read_text())
    if not (d / "results.h5").exists():
        sys.exit(f"{d / 'results.h5'}: missing; run docs/studies/ensemble.py with --keep-h5")
    sc = None
    with h5py.File(d / "results.h5") as f:
        t = f["time_s"][:]
        g = f["series"]
        a = {k: g[k][:] for k in g.keys()}
        sc = json.loads(f["scenario_json"][()])
    m = t >= t0
    end = t >= t[-1] - 0.1
    b = sc["bearings"]["DE"]
    krib, crib, eta = b["k_rib"], b["c_rib"], b["eta"]
    jy, jz = a["DE_y_m"], a["DE_z_m"]
    vjy, vjz = np.gradient(jy, t), np.gradient(jz, t)
    oy, oz = a["DE_race_y_m"], a["DE_race_z_m"]
    voy, voz = np.gradient(oy, t), np.gradient(oz, t)
    fcy, fcz = a["DE_contact_force_y_n"], a["DE_contact_force_z_n"]
    p_drive = fcy * vjy + fcz * vjz
    # eq 28-29 terms (ribbon.py): cross term k eta S_v (z, -y) with S_v ~ sign(y vz - z vy)
    h = oy * voz - oz * voy
    sv = np.sign(h)
    p_cc = krib * eta * sv * (oz * voy - oy * voz)
    p_c = -crib * (voy ** 2 + voz ** 2)
    # the sleeve contact's net power into the lateral (whirl) motion at each bearing: the contact force on
    # the journal (DE_contact_force_*, on the journal) times the journal's velocity relative to the inner
    # race, F . (v_j - v_i) = mu_eff N w g on a circular whirl (the rest of the sliding loss is the spin's)
    drive = {}
    for B in ("DE", "NDE"):
        ry, rz = a[f"{B}_race_y_m"], a[f"{B}_race_z_m"]
        dvy = np.gradient(a[f"{B}_y_m"] - ry, t)
        dvz = np.gradient(a[f"{B}_z_m"] - rz, t)
        drive[B] = a[f"{B}_contact_force_y_n"] * dvy + a[f"{B}_contact_force_z_n"] * dvz
    N = a["DE_normal_force_n"]
    xo = np.hypot(oy, oz)
    rj = np.hypot(jy, jz)
    # whirl sense of the journal: + forward (same sense as spin, assumed about +x: y->z)
    hj = jy * vjz - jz * vjy
    ratio = np.mean(a["DE_race_speed_rpm"][end]) / np.mean(a["rotor_speed_rpm"][end])
    inc = m & (N > 1.0)
    return {
        "drop": d.name, "class": s["whirl"]["direction"],
        "de": (s["whirl"].get("per_bearing") or {}).get("DE", {}).get("direction"),
        "race_ratio_end": ratio,
        "N_mean": float(np.mean(N[m])), "N_contact": float(np.mean(N[inc])) if inc.any() else 0.0,
        "contact_share": float(np.mean(inc[m])),
        "xo_um": float(np.mean(xo[m]) * 1e6), "rj_um": float(np.mean(rj[m]) * 1e6),
        "whirl_sense": float(np.mean(np.sign(hj[m]))),
        "P_drive": float(np.mean(p_drive[m])),
        "P_drive_rel_DE": float(np.mean(drive["DE"][m])), "P_drive_rel_NDE": float(np.mean(drive["NDE"][m])),
        "N_NDE": float(np.mean(a["NDE_normal_force_n"][m])),
        "P_balldamp_sys": float(np.mean(a["power_ball_damping_w"][m])),
        "P_contactdamp_sys": float(np.mean(a["power_contact_damping_w"][m])),
        "P_racedamp_sys": float(np.mean(a["power_race_damping_w"][m])),
        "P_outer_coul_sys": float(np.mean(a["power_outer_race_coulomb_w"][m])), "P_eta": float(np.mean(p_cc[m])), "P_crib": float(np.mean(p_c[m])),
        "P_radfric_sys": float(np.mean(a["power_radial_friction_w"][m])),
        "P_eta_sys": float(np.mean(a["power_ribbon_cross_coupling_w"][m])),
        "P_crib_sys": float(np.mean(a["power_ribbon_damping_w"][m])),
        "P_worn_sys": float(np.mean(a["power_worn_bearing_drag_w"][m])),
        "P_rotor_sys": float(np.mean(a["power_rotor_damping_w"][m])),
    }


def main(argv=None) -> int:
    argv = list(sys.argv[1:] if argv is None else argv)
    t0 = 0.8
    if "--t0" in argv:
        i = argv.index("--t0"); t0 = float(argv[i + 1]); del argv[i:i + 2]
    for tagdir in argv:
        print(f"== {tagdir} (t >= {t0} s)")
        print("  drop class    DE       race/rot  N_mean N_cont share  xo_um  rj_um sense  P_drive  P_eta  P_crib | sys: radfric  eta  crib worn rotor [W]")
        for d in sorted(Path(tagdir).glob("d*"), key=lambda p: int(p.name[1:])):
            r = drop(d, t0)
            print(f"  {r['drop']:4s} {r['class']:8s} {str(r['de']):8s} {r['race_ratio_end']:6.3f} {r['N_mean']:7.0f} {r['N_contact']:6.0f} {r['contact_share']:5.2f}"
                  f" {r['xo_um']:6.1f} {r['rj_um']:6.1f} {r['whirl_sense']:+5.2f} {r['P_drive']:8.1f} {r['P_eta']:6.1f} {r['P_crib']:7.1f}"
                  f" | {r['P_radfric_sys']:8.0f} {r['P_eta_sys']:5.0f} {r['P_crib_sys']:5.0f} {r['P_worn_sys']:5.0f} {r['P_rotor_sys']:5.0f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())


def ensemble_balance(tagdir: str, t0: float = 0.8, mu_w: float | None = None) -> dict:
    """Medians over the whirling drops of an ensemble, and the steady-whirl prediction of the DE load
    from the power balance of one bearing (drive = ribbon losses, light races, circular whirl):

        mu_eff N w g  =  eta N w R_out + c_rib w^2 R_out^2,  R_out = N / K_rib (the outer race's orbit)
        =>   N = mu_eff g K_rib / (eta + c_rib w / K_rib)

    with g = R_j - R_i the journal to inner-race gap (clearance + approach; "xo_um" is the inner race's
    orbit radius, the outer race's plus the ball set's deflection), mu_eff the tangential / normal force
    ratio at the sleeve: mu_rad on a stalled race, the worn drag's 1.43 mu_w on a carried one (session 10),
    whichever is smaller. The two bearings exchange power through the rotor, so this holds per bearing
    only roughly; the sum over both (P_drive_rel_* against the system's ribbon losses) is the check.
    """
    rj = json.loads(Path(tagdir + ".json").read_text())
    rows = []
    for k, m in enumerate(rj["members"]):
        if m["direction"] == "none" or m["frequency_hz"] is None:
            continue
        r = drop(Path(tagdir) / f"d{k}", t0)
        r["f"] = m["frequency_hz"]
        rows.append(r)
    if not rows:
        return {}
    with h5py.File(Path(tagdir) / "d0" / "results.h5") as f:
        sc = json.loads(f["scenario_json"][()])
    b, mu = sc["bearings"]["DE"], sc["contact"]["mu_rad"]
    med = lambda key: float(np.median([r[key] for r in rows]))
    ratio = med("race_ratio_end")
    mw = b.get("worn_drag_friction", 0.0) if mu_w is None else mu_w
    mu_eff = min(mu, 1.43 * mw) if (ratio > 0.5 and mw > 0) else mu
    w = 2 * np.pi * med("f")
    g = (med("rj_um") - med("xo_um")) * 1e-6
    pred = mu_eff * g * b["k_rib"] / (b["eta"] + b["c_rib"] * w / b["k_rib"])
    return {"n_whirl": len(rows), "race_ratio": ratio, "mu_eff": mu_eff, "f": med("f"), "N": med("N_mean"),
            "xo_um": med("xo_um"), "gap_um": g * 1e6, "N_pred": pred}
