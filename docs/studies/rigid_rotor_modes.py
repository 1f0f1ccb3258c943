"""Session 36's modal argument, kept as a script (session 42; it was a /work-only computation): on the paper's
support chain, can a rotor of the rig's mass whirl forward at Fig. 39's 48 / 65 / 77 Hz without bending?

The rig rotor of the 7000 rpm combined landing (both sleeves on the landed support chain, the motor coupling in
place; modal analysis, no landing): the first forward landed mode at 3000 / 7000 / 10000 rpm, with the steel as it is,
with its Young's modulus x5 (the input check stops at 1.2e12 Pa), and as a rigid body: the rotor's own mass,
inertias and gyroscopics projected on its four rigid-body motions (the free rotor's zero modes), on the same
supports. That is the limit of a stiffer and stiffer shaft (session 36 reached it with the modulus x20 / x100 /
x1000: 98 / 105 / 106 Hz at 3000 rpm); its frequency and its rise with speed are what a rotor that does not bend could
give.

usage (from the repository root): python docs/studies/rigid_rotor_modes.py   (about 10 s)
Output of session 42: docs/studies/rigid_rotor_modes.txt"""
import copy
import sys
from dataclasses import replace
from pathlib import Path

from rotorlanding.modal import modal_analysis, rigid_body_basis
from rotorlanding.modefit import static_support_loads, whirl_modes
from rotorlanding.reduction import full_model
from rotorlanding.rotor import rotor_from_dict
from rotorlanding.scenario import load_scenario
from rotorlanding.timoshenko import assemble
from rotorlanding.validate import paper, paper_dir


def rigid_first_forward(rotor_data: dict, speeds) -> list[float]:
    free = full_model(assemble(rotor_from_dict(rotor_data)))
    rb = rigid_body_basis(free)  # M-orthonormal: y, z and the two tilts
    sup = free.with_supports()
    rigid = replace(sup, M=rb.T @ sup.M @ rb, K=rb.T @ sup.K @ rb, C=rb.T @ sup.C @ rb, G=rb.T @ sup.G @ rb,
                    T=sup.T @ rb, names=[f"rigid{k}" for k in range(rb.shape[1])], boundary=[])
    return [min(m.frequency_hz for m in modal_analysis(rigid, sp).modes if m.whirl == "forward") for sp in speeds]

ROOT = Path(__file__).resolve().parents[2]


def main() -> int:
    sc = load_scenario(paper_dir() / "forward_whirl_landing.toml")
    speeds = [float(s) for s in paper()["fig39"]["speed_rpm"]]
    exp = paper()["fig39"]["experimental_hz"]
    loads = static_support_loads({"rotor": sc.raw["rotor"]})
    print(f"rig rotor, static loads at rest [N]: " + ", ".join(f"{k} {v:.1f}" for k, v in loads.items()))
    print("| Young's modulus x | " + " | ".join(f"{s:.0f} rpm [Hz]" for s in speeds) + " | rise 3000 -> 10000 rpm |")
    print("|---|" + "---|" * len(speeds) + "---|")
    for factor in (1.0, 5.0):
        rotor = copy.deepcopy(sc.raw["rotor"])
        for m in rotor["materials"].values():
            m["youngs_modulus"] = m["youngs_modulus"] * factor
        first = [modes[0] for modes in whirl_modes({"rotor": rotor}, speeds, "forward")]
        print(f"| {factor:g} | " + " | ".join(f"{f:.1f}" for f in first) + f" | {first[-1] / first[0] - 1:+.0%} |")
    first = rigid_first_forward({"rotor": sc.raw["rotor"]}, speeds)
    print("| rigid | " + " | ".join(f"{f:.1f}" for f in first) + f" | {first[-1] / first[0] - 1:+.0%} |")
    print("| Fig. 39 (experiment) | " + " | ".join(f"{f:g}" for f in exp) + f" | {exp[-1] / exp[0] - 1:+.0%} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
