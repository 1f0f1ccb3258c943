"""Re-runnable fit of rotor geometry to whirl frequencies measured at several speeds
(``rotorlanding fit-modes SPACE.toml``).

Why this exists: in our landing model a sustained whirl does not run at a kinematic rolling
frequency but locks onto a natural mode of the landed rotor (sleeves on the series stiffness of
Hertz contact, balls and ribbon), a few per cent below it (``docs/calibration.md``). Fitting that
mode is the cheap first step of reproducing measured whirl frequencies: a linear modal fit takes
minutes, a landing search hours.

A space file::

    rotor = "../rig_rotor.toml"        # rotor (or scenario) file whose keys are fitted
    support_stiffness = 3.6e7          # N/m at every [[rotor.supports]] (the landed state)
    lock_ratio = 0.975                 # landing whirl frequency / mode frequency (measured)
    seed = 4
    popsize = 8                        # scipy differential evolution settings
    maxiter = 25
    [targets]
    speeds_rpm = [3000.0, 7000.0, 10000.0]
    frequencies_hz = [48.0, 65.0, 77.0]   # measured whirl (here: paper Fig. 39, experimental)
    direction = "forward"
    max_mode_to_spin = 0.99            # optional: matched mode <= 0.99 x spin at every speed
    [ranges]
    "rotor.sections.3.outer_diameter" = {min = 0.035, max = 0.07}

At each speed the mode of the given whirl direction nearest to ``frequency / lock_ratio`` is
matched; the objective is the sum of squared relative errors. ``max_mode_to_spin`` (optional)
adds a steep penalty where the matched mode exceeds that multiple of the spin frequency: a
forward whirl driven by friction on the axial face can only lock to a mode below the spin (the
face must slip forward over the whirling contact), so at a low speed the mode has to stay below
the spin even where the measured whirl, divided by ``lock_ratio``, would put it above.
The search (differential evolution, fixed seed, serial, single-threaded BLAS) is deterministic, and the result is rounded to 4 significant
digits, so re-running the space file reproduces the values written into the rotor file.
"""

from __future__ import annotations

import copy
import json
import math
from pathlib import Path

import numpy as np

from .config import load_toml, range_spec, set_dotted, study_file
from .errors import InputError


def _finite(x) -> bool:
    return isinstance(x, (int, float)) and not isinstance(x, bool) and math.isfinite(x)


def load_space(path) -> dict:
    with study_file(path) as (path, t):
        rotor_file = (path.parent / t.string("rotor")).resolve()
        if not rotor_file.is_file():
            raise InputError("rotor", t.raw("rotor"), f"must name an existing rotor file ({rotor_file} not found)")
        space = {
            "rotor": rotor_file,
            "support_stiffness": t.number("support_stiffness", positive=True),
            "lock_ratio": t.number("lock_ratio", 1.0, positive=True, upper=2.0),
            "seed": t.integer("seed", 1, minimum=0),
            "popsize": t.integer("popsize", 8, minimum=2),
            "maxiter": t.integer("maxiter", 25, minimum=1),
        }
        tg = t.table("targets")
        speeds = tg.raw("speeds_rpm")
        freqs = tg.raw("frequencies_hz")
        if not (isinstance(speeds, list) and speeds and all(_finite(s) and s >= 0 for s in speeds)):
            raise InputError("targets.speeds_rpm", speeds, "must be a non-empty list of speeds >= 0 rpm")
        if not (isinstance(freqs, list) and len(freqs) == len(speeds)
                and all(_finite(f) and f > 0 for f in freqs)):
            raise InputError("targets.frequencies_hz", freqs, f"must be a list of {len(speeds)} frequencies > 0 Hz")
        direction = tg.string("direction", "forward")
        max_ratio = tg.number("max_mode_to_spin", positive=True) if tg.has("max_mode_to_spin") else math.inf
        held = tg.raw("predict_speeds_rpm") if tg.has("predict_speeds_rpm") else []
        if not (isinstance(held, list) and all(_finite(s) and s >= 0 and s not in speeds
                                               for s in held)):
            raise InputError("targets.predict_speeds_rpm", held,
                             "must be a list of speeds >= 0 rpm that are not among speeds_rpm")
        if direction not in ("forward", "backward"):
            raise InputError("targets.direction", direction, "must be 'forward' or 'backward'")
        tg.finish()
        ranges = t.raw("ranges")
        if not isinstance(ranges, dict) or not ranges:
            raise InputError("ranges", ranges, "give at least one key = {min, max}")
        for k, r in ranges.items():
            range_spec(r, f"ranges.{k}")
        t.finish()
    rotor_data = load_toml(rotor_file)
    if not isinstance(rotor_data.get("rotor"), dict):
        raise InputError("rotor", str(rotor_file), "must name a rotor file or a scenario with a [rotor] table",
                         file=str(path))
    for k in ranges:
        try:
            set_dotted(copy.deepcopy(rotor_data), k, 1.0, must_exist=True)
        except InputError as err:
            raise InputError(f"ranges.{k}", ranges[k], f"key not in {rotor_file.name}: {err.allowed}").with_file(
                str(path)) from None
    space.update(speeds_rpm=[float(s) for s in speeds], frequencies_hz=[float(f) for f in freqs],
                 predict_speeds_rpm=[float(s) for s in held],
                 direction=direction, max_mode_to_spin=max_ratio, ranges={k: (float(r["min"]), float(r["max"])) for k, r in ranges.items()})
    space["rotor_data"] = rotor_data
    return space


def rotor_with(rotor_data: dict, values: dict, support_stiffness: float | None = None) -> dict:
    """A copy of the rotor file data with ``values`` set (and every support that stands in for a
    landed catcher bearing at the stiffness; an ``in_landing`` support, e.g. the motor coupling,
    keeps its own)."""
    data = copy.deepcopy(rotor_data)
    for k, v in values.items():
        set_dotted(data, k, float(v), must_exist=True)
    if support_stiffness is not None:
        for s in data["rotor"].get("supports", []):
            if not s.get("in_landing", False):
                s["kyy"] = s["kzz"] = float(support_stiffness)
    return data


def whirl_modes(rotor_data: dict, speeds_rpm, direction: str = "forward") -> list[list[float]]:
    """At each speed, the frequencies [Hz] of the rotor's modes of ``direction`` (and those without a
    whirl sense, as at standstill), ascending; the rotor assembled once."""
    from .modal import modal_analysis
    from .reduction import full_model
    from .rotor import rotor_from_dict
    from .timoshenko import assemble

    system = full_model(assemble(rotor_from_dict(rotor_data))).with_supports()
    return [sorted(m.frequency_hz for m in modal_analysis(system, sp).modes if m.whirl in (direction, "none"))
            for sp in speeds_rpm]


def static_support_loads(rotor_data: dict) -> dict[str, float]:
    """Support station -> the vertical load [N] it carries with the rotor at rest on its supports:
    the reaction -k u of each support under the FE model's own consistent gravity load (the rotor
    file's supports all in place: the catcher stand-ins at the sleeves and any ``in_landing`` one,
    e.g. a motor coupling with lateral stiffness, which then takes its share). For a steady whirl
    it is also the time-mean contact force of a journal on two catcher bearings (the rotor's mean
    acceleration is zero), which validate reads Table 2's force rows against."""
    from .reduction import full_model
    from .rotor import rotor_from_dict
    from .timoshenko import assemble, landing_support_preload

    fe = assemble(rotor_from_dict(rotor_data))
    system = full_model(fe).with_supports()
    # an in_landing support relaxed off the levitated axis (offset_z) pulls with -k (u - u0)
    u = np.linalg.solve(system.K, system.gravity_load() + landing_support_preload(fe))
    return {s.station: float(-s.kzz * (u[fe.dof(s.station, "z")] - s.offset_z)
                             - s.kzy * (u[fe.dof(s.station, "y")] - s.offset_y)) for s in fe.rotor.supports}


def nearest(freqs_hz, target_hz: float) -> float:
    """The frequency of ``freqs_hz`` nearest to the target (nan when there is none)."""
    return min(freqs_hz, key=lambda f: abs(f - target_hz)) if freqs_hz else float("nan")


def matched_modes(rotor_data: dict, speeds_rpm, targets_hz, direction: str = "forward") -> list[float]:
    """At each speed, the frequency [Hz] of the mode of ``direction`` nearest to the target (at
    standstill, where modes have no whirl sense, the nearest mode)."""
    return [nearest(fs, ft) for fs, ft in zip(whirl_modes(rotor_data, speeds_rpm, direction), targets_hz)]


def round_sig(x: float, digits: int = 4) -> float:
    if x == 0 or not math.isfinite(x):
        return x
    return float(f"{x:.{digits - 1}e}")


def fit_modes(space_path, out_dir=None, *, stream=None) -> dict:
    """Run the fit of a space file; returns (and writes to OUT/modefit.json) the result."""
    from scipy.optimize import differential_evolution

    sp = load_space(space_path)
    keys = list(sp["ranges"])
    n_fit = len(sp["speeds_rpm"])
    speeds = sp["speeds_rpm"] + sp["predict_speeds_rpm"]
    targets = np.array(sp["frequencies_hz"]) / sp["lock_ratio"]
    # a held-out speed has no measured frequency: the mode is followed there from the fitted ones
    # (nearest to the linear trend of the targets over speed), only to pick the branch
    targets = np.concatenate([targets, _trend(sp["speeds_rpm"], targets, sp["predict_speeds_rpm"])])
    spin_hz = np.maximum(np.array(speeds) / 60.0, 1e-9)

    def modes_of(x):
        data = rotor_with(sp["rotor_data"], dict(zip(keys, x)), sp["support_stiffness"])
        return np.array(matched_modes(data, speeds, targets, sp["direction"]))

    def objective(x):
        try:
            f = modes_of(x)
        except (InputError, ValueError, np.linalg.LinAlgError):
            return 1e3  # a geometry the rotor model rejects
        if not np.all(np.isfinite(f)):
            return 1e3
        # the spin constraint is physics (face friction drives a forward whirl only below the spin),
        # not a measured number: it holds at the held-out speeds too
        excess = np.where(spin_hz > 1e-6, np.maximum(f / (spin_hz * sp["max_mode_to_spin"]) - 1.0, 0.0), 0.0)
        fit = (f[:n_fit] - targets[:n_fit]) / targets[:n_fit]
        return float(np.sum(fit ** 2) + 100.0 * np.sum(excess))

    from .runner import limit_blas_threads

    # single-threaded BLAS: faster for these small eigenproblems, and the float results (hence
    # the search path) do not depend on the machine's thread count
    restore = limit_blas_threads(1)
    try:
        res = differential_evolution(objective, [sp["ranges"][k] for k in keys], seed=sp["seed"],
                                     popsize=sp["popsize"], maxiter=sp["maxiter"], polish=False, tol=1e-10)
        best = {k: round_sig(float(v)) for k, v in zip(keys, res.x)}
        f = modes_of([best[k] for k in keys])
        final_objective = objective([best[k] for k in keys])
    finally:
        restore()
    result = {
        "space": str(space_path), "rotor": str(sp["rotor"]), "values": best,
        "support_stiffness_n_m": sp["support_stiffness"], "lock_ratio": sp["lock_ratio"],
        "speeds_rpm": sp["speeds_rpm"], "target_whirl_hz": sp["frequencies_hz"],
        "mode_hz": [float(x) for x in f[:n_fit]], "predicted_whirl_hz": [float(x * sp["lock_ratio"]) for x in f[:n_fit]],
        "max_mode_to_spin": sp["max_mode_to_spin"] if math.isfinite(sp["max_mode_to_spin"]) else None,
        "mode_to_spin": [float(x / s) for x, s in zip(f[:n_fit], spin_hz)],
        "relative_error": [float(x * sp["lock_ratio"] / t - 1) for x, t in zip(f[:n_fit], sp["frequencies_hz"])],
        "held_out": [{"speed_rpm": s, "mode_hz": float(x), "predicted_whirl_hz": float(x * sp["lock_ratio"]),
                      "mode_to_spin": float(x / h)}
                     for s, x, h in zip(sp["predict_speeds_rpm"], f[n_fit:], spin_hz[n_fit:])],
        "objective": final_objective, "evaluations": int(res.nfev),
    }
    if out_dir is not None:
        out = Path(out_dir)
        out.mkdir(parents=True, exist_ok=True)
        (out / "modefit.json").write_text(json.dumps(result, indent=2))
    if stream is not None:
        stream.write(format_result(result))
    return result


def format_result(r: dict) -> str:
    lines = [f"fit of {r['rotor']} ({r['evaluations']} evaluations, objective {r['objective']:.3g})",
             "values (4 significant digits; paste into the rotor file):"]
    lines += [f"  {k} = {v!r}" for k, v in r["values"].items()]
    lines.append(" speed_rpm  mode_hz  predicted_whirl_hz  target_hz  error")
    for s, m, p, t, e in zip(r["speeds_rpm"], r["mode_hz"], r["predicted_whirl_hz"], r["target_whirl_hz"],
                             r["relative_error"]):
        lines.append(f" {s:9.0f} {m:8.2f} {p:19.2f} {t:10.2f} {e:+6.1%}")
    for h in r.get("held_out", []):
        lines.append(f" {h['speed_rpm']:9.0f} {h['mode_hz']:8.2f} {h['predicted_whirl_hz']:19.2f}  (held out: a prediction)")
    return "\n".join(lines) + "\n"


def _trend(speeds, values, at) -> np.ndarray:
    """Linear trend of ``values`` over ``speeds`` evaluated ``at`` (the value itself for one speed)."""
    if not at:
        return np.zeros(0)
    if len(speeds) == 1:
        return np.full(len(at), float(values[0]))
    slope, icpt = np.polyfit(speeds, values, 1)
    return slope * np.asarray(at) + icpt


__all__ = ["load_space", "fit_modes", "matched_modes", "rotor_with", "round_sig", "format_result"]
