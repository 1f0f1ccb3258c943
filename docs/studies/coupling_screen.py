"""Session-12 study tool (issue 15, point 1: "what the rig has that the model lacks"): the motor
coupling's lateral stiffness at the DE end. The rotor is joined to the (grounded) motor shaft by a
flexible coupling; after the drop the coupling holds its hub near the levitated axis, so it acts as
a lateral spring k_c from the `coupling` station to ground. Screened here on the landed modal
model (sleeves on k_sup = K_rib in series with balls and Hertz contact, as modal_screen.py):
static sleeve reactions and the forward (f) / backward (b) modes with DE / NDE sleeve participation.

usage (from the repository root): python docs/studies/coupling_screen.py [ROTOR.toml] [k_c ...]"""
import importlib.util
import sys
from pathlib import Path

from rotorlanding.modefit import static_support_loads

# the sibling study tool, by its path: importable from any working directory and any caller
_spec = importlib.util.spec_from_file_location("modal_screen", Path(__file__).with_name("modal_screen.py"))
ms = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(ms)


def screen(data, k_c, krib=6.3e7, speeds=(3000, 7000, 10000), fmax=160.0):
    data = ms.rotor_with(data, {}, ms.ksup(krib))  # the coupling entry of the rig rotor (in_landing) stays at its 0
    if k_c > 0:
        data["rotor"]["supports"].append({"station": "coupling", "kyy": k_c, "kzz": k_c, "cyy": 0.0, "czz": 0.0})
    fe = ms.assemble(ms.rotor_from_dict(data))
    sysm = ms.full_model(fe).with_supports()
    return static_support_loads(data), {sp: ms.mode_rows(sysm, fe, sp, fmax) for sp in speeds}


def main(argv) -> int:
    """Print the screen for each k_c; bad arguments are one line on stderr (exit 2), not a traceback."""
    from rotorlanding.errors import InputError

    args = list(argv)
    # the rig rotor of this checkout by default, from any working directory
    path = args.pop(0) if args and args[0].endswith(".toml") else str(Path(__file__).resolve().parents[2] /
                                                                        "scenarios" / "rig_rotor.toml")
    try:
        ks = [float(a) for a in args] or [0.0, 3e5, 1e6, 3e6, 1e7, 3e7]
    except ValueError as exc:
        print(f"coupling_screen.py: k_c must be numbers in N/m ({exc})", file=sys.stderr)
        return 2
    try:
        d = ms.load(path)
    except InputError as exc:
        print(f"coupling_screen.py: {exc}", file=sys.stderr)
        return 2
    for k_c in ks:
        reac, modes = screen(d, k_c)
        print(f"k_c {k_c:.3g} N/m: reactions " + ", ".join(f"{k} {v:.0f} N" for k, v in reac.items()))
        for sp, row in modes.items():
            print(f"  {sp:5d} rpm: " + "  ".join(f"{w}{f:.1f}(DE{a:.2f},NDE{b:.2f})" for w, f, a, b in row))
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
