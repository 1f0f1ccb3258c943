"""The windage bounds of scenarios/rig/rig.toml (``spin.c_w1``, ``spin.c_w2``) from the rig rotor's
geometry (issue 15, point 1: "disk windage at its rim speed"; session 30).

Sessions 9 and 29 derived these bounds by hand for the rotor of the day; each rotor change left them
describing the old disk (session 29 found c_w2 1.5x the top of its re-derived range). This script is the
derivation, and tests/test_rig_bounds.py checks the rig file's bounds against it, so a new rotor
cannot keep stale windage silently.

Spin-drag torque T = c_w1 w + c_w2 w^2 (the spin model, eq 6 and rotorlanding.mechanisms).

c_w2, turbulent windage of the overhung actuator disk (radius R, width b; air rho 1.2 kg/m^3,
nu 1.5e-5 m^2/s, Re = w R^2 / nu):
- faces: T = C_m 0.5 rho w^2 R^5 with C_m = 0.146 Re^-0.2 for a free disk (von Karman's 1/7 law,
  T = 0.073 rho w^2 R^5 Re^-0.2; Bird, Stewart & Lightfoot, Transport Phenomena, problem on the
  rotating disk), or 0.0622 Re^-0.2 as the both-face total of an enclosed disk (the lower reading);
- rim: a rotating cylinder, skin friction from Theodorsen & Regier (NACA Report 793, 1944),
  1/sqrt(C_f) = -0.6 + 4.07 log10(Re sqrt(C_f)), T = C_f 0.5 rho (w R)^2 (2 pi R b) R.
c_w2 = T / w^2 ranges from the enclosed faces alone at 10000 rpm (lowest) to the free disk plus rim
at 3000 rpm (highest).

c_w1, laminar (Couette) drag of the narrow gaps (mu 1.8e-5 Pa s, radial or axial gap h 0.3-1 mm):
each radial AMB stack 2 pi mu R^3 L / h, the thrust disk in its AMB 2 faces x pi mu R^4 / (2 h).
The thrust gap's Couette Reynolds number at 7000 rpm is transitional, so the laminar law is a lower
estimate there (as the rig file says).

    python docs/studies/windage_bounds.py [--rotor scenarios/rig_rotor.toml]

Prints both ranges, the torques at the three test speeds and the geometric middles.
"""

from __future__ import annotations

import argparse
import math
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))

RHO_AIR = 1.2  # kg/m^3
NU_AIR = 1.5e-5  # m^2/s
MU_AIR = 1.8e-5  # Pa s
GAPS_M = (0.3e-3, 1.0e-3)  # AMB and thrust-bearing air gaps
SPEEDS_RPM = (3000.0, 7000.0, 10000.0)


def rim_cf(re: float) -> float:
    """Theodorsen & Regier's rotating-cylinder skin friction, solved by fixed point."""
    cf = 0.003
    for _ in range(60):
        cf = (-0.6 + 4.07 * math.log10(re * math.sqrt(cf))) ** -2
    return cf


def disk_torques(radius: float, width: float, rpm: float) -> dict:
    """Windage torques [N m] of a disk at ``rpm``: free faces, enclosed faces, rim."""
    w = rpm * math.pi / 30
    re = w * radius * radius / NU_AIR
    face = 0.5 * RHO_AIR * w * w * radius ** 5 * re ** -0.2
    rim = rim_cf(re) * 0.5 * RHO_AIR * (w * radius) ** 2 * 2 * math.pi * radius * width * radius
    return {"free_faces": 0.146 * face, "enclosed_faces": 0.0622 * face, "rim": rim, "w": w}


def c_w2_range(radius: float, width: float) -> tuple[float, float]:
    """(lowest, highest) c_w2 [N m s^2]: enclosed faces at the top test speed, free faces plus rim at
    the lowest (C_m falls with Re, so c_w2 does with speed)."""
    lo = disk_torques(radius, width, max(SPEEDS_RPM))
    hi = disk_torques(radius, width, min(SPEEDS_RPM))
    return lo["enclosed_faces"] / lo["w"] ** 2, (hi["free_faces"] + hi["rim"]) / hi["w"] ** 2


def c_w1_range(stacks: list[tuple[float, float]], thrust_radius: float) -> tuple[float, float]:
    """(lowest, highest) c_w1 [N m s]: Couette drag of the AMB stacks (radius, length) and the thrust
    disk's two faces, over the gaps ``GAPS_M`` (the widest gap gives the lowest drag)."""
    def at(h):
        return (sum(2 * math.pi * MU_AIR * r ** 3 * length / h for r, length in stacks)
                + 2 * math.pi * MU_AIR * thrust_radius ** 4 / (2 * h))
    return at(max(GAPS_M)), at(min(GAPS_M))


def rig_geometry(rotor_path: Path, record_path: Path) -> dict:
    """The windage geometry of the rig rotor: the actuator disk and the DE stack from the rotor file,
    the NDE stack and the thrust disk (held there as mass and inertias) from the screen's record."""
    from rotorlanding.config import load_toml

    disks = {d["name"]: d for d in load_toml(rotor_path)["rotor"]["disks"]}
    geo = {k: g["value"] for k, g in load_toml(record_path)["geometry"].items()}
    act, de = disks["actuator_disk"], disks["DE_AMB_laminations"]
    return {"disk": (act["outer_diameter"] / 2, act["thickness"]),
            "stacks": [(geo["NDE_AMB_laminations.outer_diameter"] / 2, geo["NDE_AMB_laminations.length"]),
                       (de["outer_diameter"] / 2, de["thickness"])],
            "thrust_radius": geo["thrust_disk.outer_diameter"] / 2}


def derived(rotor_path: Path | None = None, record_path: Path | None = None) -> dict:
    """Both derived ranges for the rig rotor: {"spin.c_w1": (lo, hi), "spin.c_w2": (lo, hi)}."""
    g = rig_geometry(rotor_path or ROOT / "scenarios" / "rig_rotor.toml",
                     record_path or ROOT / "scenarios" / "calibration" / "rotor_rise_screen.toml")
    return {"spin.c_w1": c_w1_range(g["stacks"], g["thrust_radius"]), "spin.c_w2": c_w2_range(*g["disk"]),
            "geometry": g}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rotor", default=str(ROOT / "scenarios" / "rig_rotor.toml"))
    a = ap.parse_args(argv)
    d = derived(Path(a.rotor))
    r, b = d["geometry"]["disk"]
    print(f"actuator disk {2e3 * r:.1f} x {1e3 * b:.2f} mm; stacks "
          + ", ".join(f"{2e3 * s[0]:.1f} x {1e3 * s[1]:.2f} mm" for s in d["geometry"]["stacks"])
          + f"; thrust disk {2e3 * d['geometry']['thrust_radius']:.1f} mm")
    for rpm in SPEEDS_RPM:
        t = disk_torques(r, b, rpm)
        print(f"{rpm:6.0f} rpm: faces free {t['free_faces']:.3f} / enclosed {t['enclosed_faces']:.3f} N m, "
              f"rim {t['rim']:.3f} N m (rim speed {t['w'] * r:.0f} m/s)")
    for key in ("spin.c_w2", "spin.c_w1"):
        lo, hi = d[key]
        print(f"{key}: {lo:.3g} .. {hi:.3g} (geometric middle {math.sqrt(lo * hi):.2g})")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
