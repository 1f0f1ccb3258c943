"""The ribbon's share of the landed chain, and the motor coupling's pull on the DE (issue 15, session 39;
docs/calibration.md "Session 39").

Two levers session 38 left untried for the ribbon check (K_rib x0.5 / x1.5 should move the 7000 rpm forward
whirl by >= 10 %, the paper's "greatly influences"):

1. **The rest of the landed chain.** A landed sleeve reaches ground through the sleeve/race Hertz contact
   (eq. 15, F = k_hertz d^1.5), the ball set (eq. 22, F = k_b1 r + k_b2 r^2) and the ribbon (K_rib), in
   series. The ribbon's share of the chain's compliance sets how far K_rib x0.5 moves the chain. Here: the
   tangent stiffnesses at 1 / 2 / 4.5 kN with the rig's values and with the rest of the chain at the stiff
   and the soft ends of its bounds (``scenarios/rig/rig.toml`` [bounds]), then the rig rotor's first forward
   landed mode at 7000 rpm on those chains (``ribbon_rise_screen.first_forward``).
2. **The motor coupling** (``rotor.supports.2``, bound 0-2.5e6 N/m, 0 in the rig): a spring to the
   levitated axis at the DE shaft end. Landed, the hub sits about one clearance below that axis, so the
   coupling lifts the rotor there; by statics (moments about the NDE sleeve) the DE sleeve loses
   ``(x_coupling - x_NDE) / (x_DE - x_NDE)`` times that lift. Printed against the rig's static DE load
   (``modefit.static_support_loads``). The landings are ``ribbon_landing_screen.py --funnel`` with
   ``--set rotor.supports.2.kyy=K --set rotor.supports.2.kzz=K``; results in
   ``docs/studies/ribbon_neighbourhood/coupling/``.

3. **What the coupling does to the backward landed mode** that Table 1's worn landing follows (its backward whirl
   runs at about 0.7 of the first backward landed mode at 7000 rpm; session 37).

    python docs/studies/chain_share.py        (a few seconds; prints the three tables)
"""

from __future__ import annotations

import sys
from pathlib import Path

from scipy.optimize import brentq

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "docs" / "studies"))

K_RIB = 6.3e7  # N/m: the paper's ribbon
# (k_b1 [N/m], k_b2 [N/m^2], k_hertz [N/m^1.5]): the rig and the ends of their bounds in scenarios/rig/rig.toml
REST = {"rig": (1.5e8, 2.4e12, 2.0e11), "stiffest rest (bounds' tops)": (3.1e8, 3.5e12, 8.0e11),
        "softest rest (bounds' bottoms)": (4.0e7, 0.0, 1.0e11)}


def chain(force_n: float, k_b1: float, k_b2: float, k_hertz: float, k_rib: float) -> tuple[float, float]:
    """(tangent stiffness [N/m] of contact + ball set + ribbon in series at ``force_n``, the ribbon's share of
    its compliance)."""
    r = brentq(lambda r: k_b1 * r + k_b2 * r * r - force_n, 0.0, 1e-2)
    k_ball = k_b1 + 2.0 * k_b2 * r
    d = (force_n / k_hertz) ** (2.0 / 3.0)
    k_contact = 1.5 * k_hertz * d ** 0.5
    compliance = 1.0 / k_rib + 1.0 / k_ball + 1.0 / k_contact
    return 1.0 / compliance, (1.0 / k_rib) / compliance


def main() -> int:
    import ribbon_rise_screen as rib
    from rotorlanding.config import load_toml
    from rotorlanding.modefit import rotor_with, static_support_loads

    print("1. The landed chain: tangent stiffness, the ribbon's share of its compliance, and K_rib x0.5 / x1.5")
    rows = {}
    for f in (1000.0, 2000.0, 4500.0):
        for name, (kb1, kb2, kh) in REST.items():
            k, share = chain(f, kb1, kb2, kh, K_RIB)
            lo, hi = (chain(f, kb1, kb2, kh, fac * K_RIB)[0] for fac in (0.5, 1.5))
            rows[f, name] = (k, lo, hi)
            print(f"  {f / 1e3:.1f} kN, {name:31s} chain {k:.3g} N/m, ribbon's share {share:.2f}; "
                  f"chain moved {lo / k - 1:+.1%} / {hi / k - 1:+.1%}")
    base = load_toml(ROOT / "scenarios" / "rig_rotor.toml")
    print("   the rig rotor's first forward landed mode at 7000 rpm on these chains (2 kN) and on fit-modes' 3.6e7:")
    chains = {"fit-modes' chain": (rib.K_CHAIN, rib.chain(0.5), rib.chain(1.5))}
    chains.update({name: rows[2000.0, name] for name in REST})
    for name, (k, lo, hi) in chains.items():
        f0, f_lo, f_hi = (rib.first_forward(rotor_with(base, {}, x), [7000.0])[0] for x in (k, lo, hi))
        print(f"  {name:31s} {k:.3g} N/m: {f0:.2f} Hz; K_rib x0.5 {f_lo / f0 - 1:+.2%}, x1.5 {f_hi / f0 - 1:+.2%}")

    print("2. The coupling's lift on the landed DE sleeve (hub one 0.2 mm clearance below the levitated axis)")
    st = base["rotor"]["stations"]
    lever = (st["coupling"] - st["NDE_sleeve"]) / (st["DE_sleeve"] - st["NDE_sleeve"])
    w_de = static_support_loads(base)["DE_sleeve"]
    for k in (2.5e5, 5e5, 1e6, 2.5e6):
        lift = k * 2.0e-4
        print(f"  {k:.2g} N/m: coupling lift {lift:.0f} N, DE sleeve unloaded by {lever * lift:.0f} N "
              f"(lever {lever:.3f}) of its {w_de:.0f} N static load")

    print("3. The coupling's stiffness and the landed modes Table 1 and Fig. 39 follow (7000 rpm, chain 3.6e7 N/m): the")
    print("   first backward landed mode above 30 Hz (Table 1's worn landing whirls backward at about 0.7 of it) and the")
    print("   first forward one, on two five-check children of 11:771 (docs/studies/ribbon_neighbourhood/children.json)")
    import json

    import rotor_rise_screen as rrs
    from rotorlanding.modefit import whirl_modes

    children = {f"{r['seed']}:{r['sample']}": r for r in
                json.loads((ROOT / "docs" / "studies" / "ribbon_neighbourhood" / "children.json").read_text())["rows"]}
    for name in ("11771:186", "11771:12"):
        d = rrs.rotor_data(base, children[name]["vals"])
        for k in (0.0, 5e5, 1e6, 1.5e6, 2.5e6):
            dk = rotor_with(d, {"rotor.supports.2.kyy": k, "rotor.supports.2.kzz": k}, rib.K_CHAIN)
            b = [f for f in whirl_modes(dk, [7000.0], "backward")[0] if f > 30.0]
            f = [f for f in whirl_modes(dk, [7000.0], "forward")[0] if f > 15.0]
            print(f"  {name} coupling {k:.2g} N/m: backward {b[0]:.1f} Hz, forward {f[0]:.1f} Hz")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
