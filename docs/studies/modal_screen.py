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

def evaluate(data, krib=6.3e7, speeds=(3000, 7000, 10000), show=True, fmax=160):
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
    if show:
        print(f"mass {fe.mass:.1f} kg, Ip total {fe.polar_inertia:.2f}; reactions " + ", ".join(f"{k} {v:.0f} N" for k, v in reac.items()), f"k_sup {ksup(krib):.3g}")
        for sp, fw in out["modes"].items():
            print(f"  {sp:5d} rpm: " + "  ".join(f"{w}{f}(DE{a},NDE{b})" for w, f, a, b in fw))
    return out

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

if __name__ == "__main__":
    d = load(sys.argv[1], sys.argv[2:])
    for kr in (6.3e7, 3.15e7, 9.45e7):
        print("k_rib", kr); evaluate(d, kr)
