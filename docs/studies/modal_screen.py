"""Session-10 study tool: screen a rig rotor. Mass, static support reactions, and the forward (f) and
backward (b) modes at 3000 / 7000 / 10000 rpm with the DE and NDE sleeve participation (share of the
largest nodal amplitude), at the paper's K_rib and +/- 50 % (in series with balls and Hertz contact).

usage (from the repository root): python docs/studies/modal_screen.py ROTOR.toml [key=value ...]"""
import sys, numpy as np
from rotorlanding.config import load_toml, set_dotted
from rotorlanding.rotor import rotor_from_dict
from rotorlanding.timoshenko import assemble
from rotorlanding.modefit import rotor_with
from rotorlanding.reduction import full_model
from rotorlanding.modal import modal_analysis

def series(*ks): return 1.0 / sum(1.0 / k for k in ks)
K_BALL, K_HZ = 1.5e8, 6e8
def ksup(krib): return series(krib, K_BALL, K_HZ)

def evaluate(data, krib=6.3e7, speeds=(3000, 7000, 10000), fmax=160):
    """Mass, static sleeve reactions and the modes up to ``fmax`` at ``speeds`` (returned, not printed)."""
    # every support that stands in for a landed catcher bearing at k_sup; an in_landing one (the
    # motor coupling) keeps its own stiffness (the same rule as fit-modes)
    data = rotor_with(data, {}, ksup(krib))
    fe = assemble(rotor_from_dict(data))
    sysm = full_model(fe).with_supports()
    # static deflection and reactions
    g = sysm.gravity_load()
    u = np.linalg.solve(sysm.K, g)
    reac = {}
    for s in fe.rotor.supports:
        iz = fe.dof(s.station, "z")
        reac[s.station] = -s.kzz * u[iz]
    out = {"mass": fe.mass, "reactions": reac, "modes": {}}
    for sp in speeds:
        out["modes"][sp] = [(w, round(f, 1), round(a, 2), round(b, 2)) for w, f, a, b in mode_rows(sysm, fe, sp, fmax)]
    out["polar_inertia"], out["k_sup"] = fe.polar_inertia, ksup(krib)
    return out


def report(out) -> str:
    lines = [f"mass {out['mass']:.1f} kg, Ip total {out['polar_inertia']:.2f}; reactions "
             + ", ".join(f"{k} {v:.0f} N" for k, v in out["reactions"].items()) + f" k_sup {out['k_sup']:.3g}"]
    lines += [f"  {sp:5d} rpm: " + "  ".join(f"{w}{f}(DE{a},NDE{b})" for w, f, a, b in fw)
              for sp, fw in out["modes"].items()]
    return "\n".join(lines)

def mode_rows(sysm, fe, speed_rpm, fmax=160):
    """(whirl sense, frequency [Hz], DE and NDE sleeve share of the largest nodal amplitude) of every
    mode up to ``fmax`` at ``speed_rpm``."""
    de, nde = fe.dof("DE_sleeve", "y"), fe.dof("NDE_sleeve", "y")
    rows = []
    for m in modal_analysis(sysm, speed_rpm).modes:
        if m.frequency_hz > fmax: break
        sh = m.shape
        amax = max(abs(sh[i]) + abs(sh[i + 1]) for i in range(0, len(sh), 4))
        rows.append((m.whirl[0], m.frequency_hz, (abs(sh[de]) + abs(sh[de + 1])) / amax,
                     (abs(sh[nde]) + abs(sh[nde + 1])) / amax))
    return rows

def load(path, sets=()):
    data = load_toml(path)
    for kv in sets:
        k, v = kv.split("=", 1)
        set_dotted(data, k, float(v), must_exist=True)
    return data

def main(argv: list[str]) -> int:
    from rotorlanding.errors import InputError

    if not argv:
        print("usage: python docs/studies/modal_screen.py ROTOR.toml [key=value ...]", file=sys.stderr)
        return 2
    try:
        for kv in argv[1:]:
            if "=" not in kv:
                raise InputError(kv, kv, "key=value with a number")
            try:
                float(kv.split("=", 1)[1])
            except ValueError:
                raise InputError(kv.split("=", 1)[0], kv.split("=", 1)[1], "a number") from None
        d = load(argv[0], argv[1:])
        results = [(kr, evaluate(d, kr)) for kr in (6.3e7, 3.15e7, 9.45e7)]
    except (InputError, KeyError, TypeError, ValueError) as exc:  # a rotor file this screen cannot read
        print(f"{argv[0]}: {exc}", file=sys.stderr)
        return 2
    for kr, out in results:
        print("k_rib", kr)
        print(report(out))
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
