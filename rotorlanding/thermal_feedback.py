"""Thermal feedback of a catcher bearing on its laws (issue 18, step 3): the registry's
``thermal_feedback`` mechanism (off by default; ``[effects] thermal_feedback = true``).

From the node temperatures of the bearing's thermal network (``catcher_thermal``, the carried
series) and the mounting temperature T_m (``thermal_ambient_k``), with the growth laws of
:mod:`user_forces.thermal_growth` (linear expansion alpha = 11.9e-6 /K of 52100, checked; see
docs/designer_models.md):

- journal (catcher) clearance: c = c_0 + alpha (r_bore dT_inner - r_sleeve dT_sleeve); the sleeve
  radius grows by alpha r_sleeve dT_sleeve, the bore follows as sleeve radius + c;
- internal (diametral) clearance of the ball set: P_d = P_d0 + alpha (d_o dT_outer - d_i dT_inner
  - 2 D dT_balls), groove bottoms d_i,o = d_m -+ D (Harris & Kotzalas ch. 2, quoted);
- once P_d < 0, the preload of the ball set: ``thermal_preload_fast`` (groove-centre geometry,
  Q = K_n delta_n^1.5 per ball, the rings held axially by a mounting of stiffness
  ``thermal_axial_mount_stiffness_n_m``): per-ball compression delta_n, contact angle a, and the
  axial resultant F_a = Z Q sin a;
- the preload feeds (1) the ball set's radial stiffness: k_b1 + 3/4 Z K_n delta_n^(1/2) cos^2 a
  (d/d delta_r of sum_j K_n (delta_n + delta_r cos psi_j cos a)^1.5 cos a cos psi_j at delta_r = 0,
  sum_j cos^2 psi_j = Z/2 for Z >= 3 equally spaced balls; rigid rings, the axial coupling of a
  spring-mounted pair neglected), and (2) the axial load of the drag laws: Harris-Palmgren's
  F_beta and F_s (and the worn bearing's load-proportional drag) see F_a,ext + F_a,preload
  (``BearingLaws.drag_axial_preload``; superposition of the axial loads, assumed as in
  user_forces/thermal_growth.py). A hot bearing therefore drags more, which heats it more.

Operator split: the solver reads these retuned laws, frozen over one coast-down chunk, from the
temperatures at the chunk's start (the carried state the chunk starts from: a resume reads the same
values). The feedback lags the temperatures by one chunk: chunk_s (1 s in the rig's coast-down)
against the network's fastest time constant (~22 s on the rig's defaults), a ratio ~0.05; a landing run (one
solve from the mounting temperature) sees the cold laws, which is what a fraction of a second of
heating gives (< 1 K). The retuned laws change the elastic energies between chunks (k_b1, the
clearance): a jump of ~1e-3 J against kJ dissipated, visible in the balance residual.

Runaway: the post hook evaluates clearance and preload on every sample from the temperatures
(diagnostic series; the solver used the chunk-start values); :func:`summary` reports when the
internal clearance is consumed, the peak preload, and the runaway time: the first instant a node
passes ``thermal_runaway_limit_k`` (default 473.15 K = 200 degC: AISI 52100 is tempered and
dimensionally stabilised at 150-200 degC, user_forces/thermal_growth.py) with the ball set
preloaded, or the journal clearance is consumed (the sleeve seizes in the bore). The threshold
itself (loop gain dP_out/dP = 1) is explained in docs/designer_models.md section 2.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from user_forces.contact_stress import BEARING_7212BE_ASSUMED, ball_stiffness_kn
from user_forces.thermal import BALLS, INNER, OUTER, SLEEVE, STEEL_52100
from user_forces.thermal_growth import internal_clearance_change, journal_clearance_change, thermal_preload_fast

MIN_JOURNAL_CLEARANCE = 1.0e-6   # m: the radial contact law needs c > 0; below it the sleeve has seized
ALPHA = STEEL_52100.expansion


def geometry(laws):
    """The ball set's internal geometry: the 7212 BE (assumed, docs/designer_models.md) with the
    bearing's own pitch diameter and contact angle."""
    return replace(BEARING_7212BE_ASSUMED, pitch_diameter=laws.pitch_diameter,
                   contact_angle_deg=laws.contact_angle_deg)


def state(laws, temps) -> dict:
    """Clearances, preload and the stiffness increment of the ball set at node temperatures
    ``temps`` [K] (sleeve, inner, balls, outer, housing); laws = the bearing's cold laws."""
    x = laws.extra
    tm = x["thermal_ambient_k"]
    g = geometry(laws)
    dts, dti, dtb, dto = (temps[i] - tm for i in (SLEEVE, INNER, BALLS, OUTER))
    c = laws.clearance + journal_clearance_change(laws.race_radius, laws.sleeve_radius, dti, dts, ALPHA)
    pd = x["thermal_internal_clearance_m"] + internal_clearance_change(g.pitch_diameter, g.ball_diameter, dti, dto,
                                                                       dtb, ALPHA)
    k_n = ball_stiffness_kn(g)
    q = fa = delta = 0.0
    angle = math.radians(g.contact_angle_deg)
    if pd < 0.0:
        q, fa, angle, delta, _ = thermal_preload_fast(pd, g.n_balls, math.radians(g.contact_angle_deg),
                                                      (g.f_inner + g.f_outer - 1.0) * g.ball_diameter, k_n,
                                                      x["thermal_axial_mount_stiffness_n_m"])
    dk = 0.75 * g.n_balls * k_n * math.sqrt(delta) * math.cos(angle) ** 2
    return {"journal_clearance": c, "internal_clearance": pd, "ball_preload": q, "axial_preload": fa,
            "delta_n": delta, "contact_angle_rad": angle, "dk_b1": dk,
            "sleeve_radius": laws.sleeve_radius * (1.0 + ALPHA * dts)}


def retune(laws, temps):
    """The bearing's laws at node temperatures ``temps`` [K] (module docstring)."""
    s = state(laws, temps)
    c = max(s["journal_clearance"], MIN_JOURNAL_CLEARANCE)
    return replace(laws, clearance=c, sleeve_radius=s["sleeve_radius"], race_radius=s["sleeve_radius"] + c,
                   k_b1=laws.k_b1 + s["dk_b1"], drag_axial_preload=s["axial_preload"])


def active(spec, laws) -> bool:
    return laws.extra["thermal_axial_mount_stiffness_n_m"] > 0 and laws.extra["thermal_ambient_k"] > 0


def retune_bearing(laws, name: str, carry: dict):
    """The registry's ``retune`` hook: the laws at the carried temperatures of bearing ``name``
    (the laws themselves when ``carry`` holds none)."""
    from .thermal_states import NODE_SERIES

    if name + "_" + NODE_SERIES[0] not in carry:
        return laws
    return retune(laws, [carry[name + "_" + s] for s in NODE_SERIES])


def post_feedback(ev, laws) -> None:
    """Per-sample clearances and preload from the temperature series (diagnostic; the solver used the
    values at the chunk's start). ``laws`` are the laws the solver used: the cold ones are needed, so
    the clearance is recomputed from the scenario's value (``ev.bearing.params``)."""
    from .thermal_states import NODE_SERIES

    pre = ev.bearing.name + "_"
    cold = replace(laws, clearance=ev.bearing.params.clearance, sleeve_radius=ev.bearing.params.sleeve_radius,
                   race_radius=ev.bearing.params.race_radius)
    temps = np.column_stack([ev.series[pre + s] for s in NODE_SERIES])
    rows = [state(cold, tk) for tk in temps]
    ev.out("journal_clearance_m", np.array([r["journal_clearance"] for r in rows]))
    ev.out("internal_clearance_m", np.array([r["internal_clearance"] for r in rows]))
    ev.out("thermal_preload_n", np.array([r["axial_preload"] for r in rows]))


def first_runaway(spec, t, series: dict):
    """The earliest runaway over the samples ``t`` of the bearings with an active feedback:
    (bearing name, time [s], reason) or None. A coast-down stops there (beyond it the growth,
    preload and drag laws are outside their range: 52100 softens, the preload geometry breaks)."""
    from .mechanisms import thermal_feedback_active

    found = []
    for b in spec.bearings:
        if thermal_feedback_active(spec, b.laws):
            s = summary(t, series, b.name, b.laws)
            if s["runaway"]:
                found.append((s["t_runaway_s"], b.name, s["runaway_reason"]))
    if not found:
        return None
    t_r, name, why = min(found)
    return name, t_r, why


def summary(t, series: dict, name: str, laws) -> dict:
    """Runaway detection of one bearing over the stored samples (module docstring)."""
    from .thermal_states import NODE_SERIES

    pre = name + "_"
    limit = laws.extra["thermal_runaway_limit_k"]
    pd = series[pre + "internal_clearance_m"]
    fa = series[pre + "thermal_preload_n"]
    c = series[pre + "journal_clearance_m"]
    tmax = np.max(np.column_stack([series[pre + s] for s in NODE_SERIES]), axis=1)
    consumed = np.flatnonzero(pd < 0.0)
    hot = np.flatnonzero((tmax > limit) & (fa > 0.0))
    seized = np.flatnonzero(c <= MIN_JOURNAL_CLEARANCE)
    cand = [(float(t[i[0]]), why) for i, why in ((hot, "a node passed the limit with the ball set preloaded"),
                                                 (seized, "journal clearance consumed")) if len(i)]
    first = min(cand) if cand else None
    return {"min_internal_clearance_m": float(np.min(pd)), "min_journal_clearance_m": float(np.min(c)),
            "max_thermal_preload_n": float(np.max(fa)),
            "t_internal_clearance_consumed_s": float(t[consumed[0]]) if len(consumed) else None,
            "runaway": first is not None, "t_runaway_s": first[0] if first else None,
            "runaway_reason": first[1] if first else None, "runaway_limit_degc": limit - 273.15}
