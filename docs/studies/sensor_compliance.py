"""Session-18 study (issue 15, point 1: "what the rig has that the model lacks: ... the force
sensor's compliance"). A force sensor under each catcher-bearing housing sits in series with the
ribbon, the ball set and the Hertz contact. On the fit's landed support (the chain of
`scenarios/calibration/rotor_modes.toml`, 3.6e7 N/m) this computes the landed forward mode the
forward whirl locks to (`modefit.matched_modes`, as `validate.ribbon_modal_shift` does for the
ribbon) with a sensor of stiffness k_s added to the chain, at the three Fig. 39 speeds. No landing.

The sensor range is ours, not a catalogue's: 1e8 N/m (a soft strain-gauge ring) to 3e9 N/m (a
quartz load washer); the library held no datasheet with stiffness figures.

usage (from the repository root): python docs/studies/sensor_compliance.py [k_s ...]"""
import sys

from rotorlanding.modefit import load_space, matched_modes, rotor_with
from rotorlanding.validate import project_root


def main(sensors=(1e8, 3e8, 1e9, 3e9)) -> None:
    space = load_space(project_root() / "scenarios" / "calibration" / "rotor_modes.toml")
    k_sup = space["support_stiffness"]
    for j, rpm in enumerate(space["speeds_rpm"]):
        target = space["frequencies_hz"][j] / space["lock_ratio"]
        f0 = float(matched_modes(rotor_with(space["rotor_data"], {}, k_sup), [rpm], [target])[0])
        print(f"{rpm:.0f} rpm: chain {k_sup:.3g} N/m, landed forward mode {f0:.2f} Hz")
        for ks in sensors:
            k = 1.0 / (1.0 / k_sup + 1.0 / ks)
            data = rotor_with(space["rotor_data"], {}, k)
            # the same mode followed (nearest the unperturbed one), and the mode nearest Fig. 39's
            # target, which with a very soft sensor can be the next one down
            f = float(matched_modes(data, [rpm], [f0])[0])
            ft = float(matched_modes(data, [rpm], [target])[0])
            print(f"  sensor {ks:.0e} N/m: chain {k:.3g} N/m ({k / k_sup - 1:+.1%}), mode {f:.2f} Hz ({f / f0 - 1:+.2%})"
                  + ("" if ft == f else f"; nearest the target: another forward mode, {ft:.2f} Hz"))


if __name__ == "__main__":
    main([float(a) for a in sys.argv[1:]] or (1e8, 3e8, 1e9, 3e9))
