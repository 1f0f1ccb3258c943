"""Command line: ``rotorlanding run|coastdown|modes|reduce ...``.

Bad input never shows a traceback: an :class:`InputError` prints one line naming the file, field,
value and what is allowed, and the exit code is 2. A result file that cannot be written (disk
full, file too large, I/O error: :class:`rotorlanding.safeio.WriteError`) prints one line naming
the file and the error, exit code 3. A run that stops incomplete exits 1.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

import numpy as np

from . import __version__
from .errors import InputError
from .safeio import WriteError, check_out_dir, hard_exit, poisoned

EXIT_INPUT = 2
EXIT_IO = 3  # a result could not be written (disk full, I/O error); the input was fine


def _speeds(text: str) -> list[float]:
    out = []
    for part in text.split(","):
        part = part.strip()
        try:
            v = float(part)
        except ValueError:
            raise InputError("--speeds-rpm", text, "must be a comma-separated list of numbers, e.g. 0,3000,7000") from None
        if not np.isfinite(v) or v < 0:
            raise InputError("--speeds-rpm", part, "speeds must be finite and >= 0 rpm")
        out.append(v)
    return out


def _below_burst(rotor, speeds) -> None:
    """Spin speeds a rotor can reach: below its burst speed (docs/scenario_file.md, plausibility limits)."""
    burst, part = rotor.burst_speed_rpm()
    if speeds and max(speeds) > burst:
        raise InputError("--speeds-rpm", max(speeds), f"must be <= {burst:.4g} rpm: above it {part} bursts even if "
                         "made of the strongest steel", file=rotor.source)


def _check_figure_path(path, option: str) -> None:
    """A figure file matplotlib can write, in a folder that exists and is writable (checked before
    the work: a bad name used to end a finished computation with a traceback)."""
    from matplotlib.figure import Figure

    from .safeio import check_out_file

    kinds = Figure().canvas.get_supported_filetypes()
    suffix = Path(path).suffix.lower().lstrip(".")
    if suffix not in kinds:
        raise InputError(option, str(path), "must end in an image type matplotlib writes: "
                         + ", ".join("." + k for k in sorted(kinds)))
    check_out_file(path, option)


def _linear_model(path: str, model: str, free: bool, speeds=(), bearings_at_rpm=None):
    from .reduction import full_model, reduce_rotor
    from .rotor import load_rotor
    from .timoshenko import assemble

    rotor = load_rotor(path, bearings_at_rpm=bearings_at_rpm)
    _below_burst(rotor, speeds)
    fe = assemble(rotor)
    if model == "reduced":
        try:
            system = reduce_rotor(fe)
        except InputError as err:
            raise err.with_file(path) from None
        label = f"Craig-Bampton ({len(system.boundary)} boundary DOFs + {system.n_modes} modes)"
    else:
        system = full_model(fe)
        label = f"full FE ({len(fe.nodes)} nodes, {fe.ndof} DOFs)"
    if not free:
        system = system.with_supports()
        label += f", {len(rotor.supports)} linear supports"
    else:
        label += ", free (supports ignored)"
    return rotor, system, label


def cmd_modes(args) -> int:
    from .modal import campbell, plot_campbell

    speeds = _speeds(args.speeds_rpm)
    if args.n_modes < 1:
        raise InputError("--n-modes", args.n_modes, "must be >= 1")
    if args.plot:
        _check_figure_path(args.plot, "--plot")
    # a ROSS rotor's frequency-dependent bearings are taken at each spin speed, as ROSS's run_modal
    from .from_ross import has_speed_dependent_bearings

    per_speed = has_speed_dependent_bearings(args.file)
    rotor, system, label = _linear_model(args.file, args.model, args.free, speeds,
                                         bearings_at_rpm=speeds[0] if per_speed else None)
    if per_speed:
        label += ", ROSS bearing coefficients at each speed"

    def modes_at(at_speeds):
        if not per_speed:
            return campbell(system, at_speeds, args.n_modes)
        return [campbell(_linear_model(args.file, args.model, args.free, [s], bearings_at_rpm=s)[1], [s],
                         args.n_modes)[0] for s in at_speeds]

    results = modes_at(speeds)
    if args.plot:
        top = max(max(speeds), rotor.max_speed_rpm)
        dense = np.linspace(0.0, top, 41)
        plot_campbell(modes_at(dense), args.plot, title=f"Campbell diagram: {rotor.name}\n{label}")
    if args.json:
        out = {"speeds_rpm": speeds, "model": label,
               "modes": [[m.to_dict() for m in r.modes] for r in results]}
        print(json.dumps(out))
    else:
        print(f"rotor: {rotor.name} ({args.file}); model: {label}")
        print(f"{'speed_rpm':>10} {'mode':>4} {'frequency_hz':>13} {'damping_ratio':>13}  whirl")
        for r in results:
            for k, m in enumerate(r.modes, 1):
                print(f"{r.speed_rpm:10.0f} {k:4d} {m.frequency_hz:13.3f} {m.damping_ratio:13.5f}  {m.whirl}")
        if args.plot:
            print(f"Campbell diagram written to {args.plot}")
    return 0


def cmd_reduce(args) -> int:
    from .modal import reduction_report
    from .reduction import full_model, reduce_rotor
    from .rotor import load_rotor
    from .timoshenko import assemble, with_landing_supports

    speeds = _speeds(args.speeds_rpm)
    rotor = load_rotor(args.file)
    _below_burst(rotor, speeds)
    # the rotor the landing reduces: with the supports that act in the landing (e.g. the motor
    # coupling) in K before the reduction; --free: the free rotor
    fe = assemble(rotor) if args.free else with_landing_supports(assemble(rotor))
    try:
        red = reduce_rotor(fe)
    except InputError as err:
        raise err.with_file(args.file) from None
    full, red = full_model(fe), red
    if not args.free:
        full, red = full.with_supports(), red.with_supports()
    f_limit = 2.0 * rotor.max_speed_rpm / 60.0 if args.f_limit_hz is None else args.f_limit_hz
    rows = reduction_report(full, red, speeds, f_limit)
    if args.json:
        print(json.dumps({"f_limit_hz": f_limit, "full_dofs": fe.ndof, "reduced_dofs": red.n, "rows": rows}))
        return 0
    print(f"Craig-Bampton check: {fe.ndof} -> {red.n} coordinates "
          f"({len(red.boundary)} boundary + {red.n_modes} modes), modes below {f_limit:.1f} Hz")
    print(f"{'speed_rpm':>10} {'mode':>4} {'full_hz':>10} {'reduced_hz':>10} {'error_%':>8}  whirl")
    for r in rows:
        print(f"{r['speed_rpm']:10.0f} {r['mode']:4d} {r['full_hz']:10.3f} {r['reduced_hz']:10.3f} "
              f"{100 * r['relative_error']:8.4f}  {r['whirl']}")
    worst = max((abs(r["relative_error"]) for r in rows), default=0.0)
    print(f"largest relative error: {100 * worst:.4f} %")
    return 0


def _load_case(path: str, overrides):
    """A scenario TOML file, or a results.h5 whose stored scenario is re-run."""
    from .scenario import apply_overrides, load_scenario, scenario_from_dict

    if path.endswith(".h5"):
        from .readers import read_results_guarded

        data = read_results_guarded(path, ("scenario",), field="scenario")["scenario"]
        return scenario_from_dict(apply_overrides(data, overrides), source=path)
    return load_scenario(path, overrides)


def cmd_run(args) -> int:
    from .run import format_summary, run_scenario

    overrides = list(args.set or [])
    if args.t_end is not None:
        overrides.append(f"operating.t_end={args.t_end}")
    if args.scenario.endswith(".toml"):
        from .config import load_toml

        if "coastdown" in load_toml(args.scenario):
            raise InputError("coastdown", "[coastdown]", "this is a coast-down scenario: run it with "
                             f"`rotorlanding coastdown {args.scenario} --out DIR`", file=args.scenario)
    scenario = _load_case(args.scenario, overrides)  # validates everything before writing anything
    summary = run_scenario(scenario, args.out, progress=None if not args.quiet else False, plots=not args.no_plots)
    print(format_summary(summary))
    print(f"results written to {args.out}/ (results.h5, summary.json" + ("" if args.no_plots else ", figures") + ")")
    if not summary.get("complete", True):
        print(f"rotorlanding: run incomplete: {summary.get('message', '')}", file=sys.stderr)
        return 1
    return 0


def cmd_coastdown(args) -> int:
    from .coastdown_run import format_summary, load_coastdown, run_coastdown

    overrides = list(args.set or [])
    if args.t_end is not None:
        overrides.append(f"operating.t_end={args.t_end}")
    scenario, cd = load_coastdown(args.scenario, overrides)  # validates everything before writing anything
    if args.resume and args.overwrite:
        raise InputError("--resume", True, "cannot be combined with --overwrite")
    summary = run_coastdown(scenario, cd, args.out, resume=args.resume, overwrite=args.overwrite,
                            progress=not args.quiet, plots=not args.no_plots)
    print(format_summary(summary))
    print(f"results written to {args.out}/ (results.h5, summary.json" + ("" if args.no_plots else ", coastdown.png")
          + ")")
    if not summary.get("complete", True):
        print(f"rotorlanding: coast-down incomplete: {summary.get('message', summary.get('stop_reason'))}",
              file=sys.stderr)
        return 1
    return 0


def cmd_verdict(args) -> int:
    """Run the scenario (a landing, or a coast-down when it has a [coastdown] table) into --out, or
    take a finished run's results.h5, and write the verdict (verdict.json, verdict.md)."""
    from .verdict import format_lines, verdict_from_results

    overrides = list(args.set or [])
    if args.scenario.endswith(".h5"):
        if args.t_end is not None:
            raise InputError("--t-end", args.t_end, "applies to a new run, not to a finished results.h5")
        results, out = Path(args.scenario), Path(args.out) if args.out else Path(args.scenario).parent
    else:
        from .config import load_toml

        if args.t_end is not None:
            overrides.append(f"operating.t_end={args.t_end}")
        out = Path(args.out or "verdict")
        if "coastdown" in load_toml(args.scenario):
            from .coastdown_run import format_summary, load_coastdown, run_coastdown

            scenario, cd = load_coastdown(args.scenario, overrides)
            summary = run_coastdown(scenario, cd, out, resume=args.resume, overwrite=not args.resume,
                                    progress=not args.quiet, plots=not args.no_plots)
        else:
            from .run import format_summary, run_scenario

            scenario = _load_case(args.scenario, overrides)
            summary = run_scenario(scenario, out, progress=None if not args.quiet else False, plots=not args.no_plots)
        print(format_summary(summary))
        results = out / "results.h5"
        overrides = []  # already in the stored scenario

    check_out_dir(out)
    v = verdict_from_results(results, out, overrides=overrides, plots=not args.no_plots)
    print("\n".join(format_lines(v)))
    print(f"verdict written to {out}/ (verdict.json, verdict.md" + (", temperatures.png" if v.get("figures") else "")
          + ")")
    return 0


def cmd_validate(args) -> int:
    from .validate import check_cases, check_line, counts_line, report_from_run, validate

    rerender = args.report_from is not None
    if rerender:
        # the run's own landings are rendered: options that would change them have no meaning here
        for flag, given in (("--quick", args.quick), ("--rig", args.rig is not None), ("--set", bool(args.sets)),
                            ("--out", args.out != "validation")):
            if given:
                raise InputError(flag, "given with --report-from", "not allowed: the report is rendered from RUN's "
                                 "own landings, into RUN (and --publish)")
        if not Path(args.report_from).is_dir():
            raise InputError("--report-from", args.report_from, "must be the folder of a rotorlanding validate run")
    else:
        if args.workers < 1:
            raise InputError("--workers", args.workers, "must be >= 1")
        if args.rig is not None and not Path(args.rig).is_file():
            raise InputError("--rig", args.rig, "must be an existing rotor or rig TOML file")
        check_cases(args.sets or (), args.rig)
    if args.publish is not None and not Path(args.publish).is_dir():
        raise InputError("--publish", args.publish, "must be an existing folder (e.g. docs)")
    # every folder checked before some 400 landings are run into it (or a run rendered): a bad one is one line, now
    out, option = (args.report_from, "--report-from") if rerender else (args.out, "--out")
    check_out_dir(out, option)
    if args.publish is not None:
        check_out_dir(args.publish, "--publish")
    res = (report_from_run(out, publish=args.publish) if rerender else
           validate(out, quick=args.quick, workers=args.workers, rig=args.rig, publish=args.publish, sets=args.sets))
    ev = res["evaluation"]
    for c in ev["checks"]:
        print(check_line(c))
    print(counts_line(ev).replace("**", "") + f" Report: {out}/validation.md"
          + (" (rendered from the stored run, no landing)" if rerender else ""))
    return 0


def _size(text: str) -> tuple[int, int]:
    try:
        w, h = (int(v) for v in text.lower().split("x"))
    except ValueError:
        raise InputError("--size", text, "must be WIDTHxHEIGHT in pixels, e.g. 1280x720") from None
    return w, h


def cmd_animate(args) -> int:
    from .animate import animate

    size = _size(args.size)
    info = animate(args.results, args.out, fps=args.fps, view=args.view, max_frames=args.max_frames,
                   play_fps=args.play_fps, size=size, at=args.at)
    print(f"{info['frames']} frame(s) written to {info['file']} (lateral displacements x{info['magnification']:.0f})")
    return 0


def cmd_sweep(args) -> int:
    from .sweep_run import run_sweep

    if args.workers < 1:
        raise InputError("--workers", args.workers, "must be >= 1")
    rows = run_sweep(args.sweep, args.out, workers=args.workers, scheduler=args.scheduler)
    failed = [r for r in rows if r["status"] != "ok"]
    skipped = sum(1 for r in rows if r.get("skipped"))
    print(f"{len(rows)} cases ({skipped} already done), {len(failed)} failed; table: {args.out}/sweep.csv, "
          f"map: {args.out}/whirl_map.png")
    for r in failed:
        print(f"  case {r['case']}: {r['status']}: {r['error']}")
    if rows and len(failed) == len(rows):
        print(f"rotorlanding: every one of the {len(rows)} cases failed", file=sys.stderr)
        return 1
    if failed:  # the others are results; the count goes to stderr as well, where scripts look
        print(f"rotorlanding: warning: {len(failed)} of {len(rows)} cases failed", file=sys.stderr)
    return 0


def cmd_whirl_map(args) -> int:
    from .whirlmap import run_map

    if args.workers < 1:
        raise InputError("--workers", args.workers, "must be >= 1")
    r = run_map(args.map, args.out, workers=args.workers)
    failed = sum(c["counts"]["failed"] for c in r["cells"])
    print(f"{len(r['cells'])} cells x {r['drops_per_cell']} drops = {r['drops']} drops in {r['wall_s']:.1f} s "
          f"({r['drops_per_minute']:.0f} drops/min), {failed} failed; {args.out}/whirl_map.json, whirl_map.csv, "
          f"whirl_map.png")
    if failed == r["drops"]:
        print(f"rotorlanding: every one of the {r['drops']} drops failed", file=sys.stderr)
        return 1
    return 0


def cmd_diagnose(args) -> int:
    from .diagnose_run import run_diagnose

    cands = [c.strip() for c in args.candidates.split(",")] if args.candidates else None
    params = None if args.parameters is None else \
        [] if args.parameters.strip() == "none" else [k.strip() for k in args.parameters.split(",") if k.strip()]
    res, files = run_diagnose(args.scenario, args.measured, args.out, sets=args.set or [], t_end=args.t_end,
                              candidates=cands, max_effects=args.max_effects, workers=args.workers,
                              maxiter=args.maxiter, time_offset_s=args.time_offset_s, parameters=params,
                              noise_gap=args.noise_gap, ensemble=args.ensemble,
                              ensemble_radius_m=args.ensemble_radius_m, scatter_scales=args.scatter_scales,
                              journals=[j.strip() for j in args.journals.split(",") if j.strip()])
    out = args.out
    for w in res["warnings"]:
        print(f"rotorlanding: warning: {w}", file=sys.stderr)
    print(f"gap before {res['gap_before']:.3f}, after {res['gap_after']:.3f} (noise gate {res['noise_gate']:.3f}, "
          f"{res['noise']['source']}); explanation: {res['explanation']}; named effect: {res['named_effect']} "
          f"({res['simulations']} simulations, {res['wall_s']:.0f} s)")
    for label, m in (res.get("gate_margins") or {}).items():
        if m.get("within_one_se"):
            print(f"  note: the gap {label} ({m['gap']:.3f}) is within one standard error ({m['gate_se']:.3f}) of its "
                  f"noise gate ({m['gate']:.3f}): the verdict hangs on the gate's estimate; repeated records settle it")
    if res["absent_in_model_before"]:
        print("  the model cannot produce: " + ", ".join(res["absent_in_model_before"]))
    for n in res["named_effects"]:
        print(f"  {n}: {res['signatures'][n]}")
    for q in res["named_parameters"]:
        print(f"  parameter {q['key']}: {q['from']} -> {q['to']:.4g} (bound {q['bound'][0]:g}-{q['bound'][1]:g})")
    for n, others in (res.get("named_alike") or {}).items():
        print(f"  {n} could not be told from " + ", ".join(o["other"] for o in others)
              + " with these channels (before calibrating): read the choice with care")
    if res.get("decisive_features") and (res["named_effects"] or res["named_parameters"]):
        print("  decided on: " + ", ".join(f"{d['feature']}" + (f" ({d['point']})" if d["point"] else "")
                                          + f" {100 * d['share']:.0f} %" for d in res["decisive_features"]))
    if res["unexplained"]:
        print(f"  unexplained: the gap {res['gap_after']:.3f} stays above the noise gate; largest in "
              + ", ".join(r["feature"] + (f" ({r['point']})" if r["point"] else "") for r in res["largest_remaining"]))
    if len(res["points"]) > 1:
        print("  whirl measured / before / after: " + "; ".join(
            f"{p['name']}: {p['whirl_measured']} / {p['whirl_before']} / {p['whirl_after']}" for p in res["points"]))
    print(f"report: {out}/report.json, " + ", ".join(f"{out}/{f}" for f in files))
    return 0


def cmd_calibrate(args) -> int:
    from .calibrate_run import calibrate

    if args.workers < 1:
        raise InputError("--workers", args.workers, "must be >= 1")
    check_out_dir(args.out, "--out")  # before the designs are landed, not after
    if args.from_run:
        from .calibrate_run import calibrate_from_run

        rows = calibrate_from_run(args.space, args.from_run, args.out)
    else:
        rows = calibrate(args.space, args.out, workers=args.workers)
    failed = sum(1 for r in rows if r.get("failed_landings"))
    if failed == len(rows):
        print(f"rotorlanding: every one of the {len(rows)} designs had a landing that failed "
              f"(errors: {args.out}/calibration.json); no best design", file=sys.stderr)
        return 1
    if failed:
        print(f"rotorlanding: warning: {failed} of {len(rows)} designs had a landing that failed "
              f"(failed_landings in {args.out}/calibration.csv)", file=sys.stderr)
    best = rows[0]
    from .calibrate_run import design_overrides

    keys = [k for k in best if "." in k and not k.endswith("_half_step")]
    conv = {True: "converged at h/2", False: "NOT converged at h/2", None: "step convergence not checked"}
    print(f"{len(rows)} designs; best score {best['score']:.3f} (design {best['design']}, "
          f"{conv[best['converged']]}); table: {args.out}/calibration.csv")
    print("best as --set: " + " ".join(f"--set {s}" for s in design_overrides({k: best[k] for k in keys})))
    near = [r for r in rows if r.get("within_noise_of_best")]
    if near:  # what the fit determines: the designs it cannot rank against the best, and their span
        from .calibrate_run import NOISE_Z, noise_span

        print(f"{len(near)} design(s) within the noise of the best (score within {NOISE_Z:g} standard errors "
              f"of the difference; best {best['score']:.3f} +/- {best['score_se']:.3f}): "
              + ", ".join(str(r["design"]) for r in near))
        for k, (lo, hi) in noise_span(rows, keys).items():
            print(f"  {k}: {lo:.6g} .. {hi:.6g} over them")
    elif best.get("score_se") is None:
        print("no score error (single landings per case): the ranking's noise is unknown; use ensemble > 1")
    return 0


def cmd_fit_modes(args) -> int:
    from .modefit import fit_modes

    check_out_dir(args.out, "--out")  # before the fit: a bad --out used to end it with a traceback
    fit_modes(args.space, args.out, stream=sys.stdout)
    print(f"written: {args.out}/modefit.json")
    return 0


def _run_options(p, t_end_help: str, set_help: str, plots_help: str, quiet_help: str) -> None:
    """The options `run` and `coastdown` share: --t-end, --set, --no-plots, --quiet."""
    p.add_argument("--t-end", type=float, default=None, help=t_end_help)
    p.add_argument("--set", action="append", metavar="KEY=VALUE", help=set_help + " (repeatable)")
    p.add_argument("--no-plots", action="store_true", help=plots_help)
    p.add_argument("--quiet", action="store_true", help=quiet_help)


def build_parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="rotorlanding", description=__doc__.splitlines()[0])
    p.add_argument("--version", action="version", version=f"rotorlanding {__version__}")
    sub = p.add_subparsers(dest="command", required=True)

    m = sub.add_parser("modes", help="damped natural frequencies, whirl labels and Campbell diagram")
    m.add_argument("file", help="rotor TOML file, or a scenario file containing [rotor]")
    m.add_argument("--speeds-rpm", default="0", help="comma-separated spin speeds in rpm (default 0)")
    m.add_argument("--json", action="store_true", help="print one JSON object instead of a table")
    m.add_argument("--plot", metavar="PNG", help="write a Campbell diagram (0 .. max speed) to this PNG")
    m.add_argument("--n-modes", type=int, default=8, help="number of elastic modes to report (default 8)")
    m.add_argument("--model", choices=["full", "reduced"], default="full",
                   help="full FE model (default) or the Craig-Bampton model of [rotor.reduction]")
    m.add_argument("--free", action="store_true", help="ignore [[rotor.supports]] (free-free rotor)")
    m.set_defaults(func=cmd_modes)

    u = sub.add_parser("run", help="simulate a landing scenario: results.h5, summary.json, figures")
    u.add_argument("scenario", help="scenario TOML file (or a results.h5 to re-run its stored scenario)")
    u.add_argument("--out", default="out", help="output folder (default ./out)")
    _run_options(u, "override operating.t_end [s]", "override a scenario value, e.g. --set contact.mu_rad=0.3",
                 "skip the figures", "no progress bar")
    u.set_defaults(func=cmd_run)

    cd = sub.add_parser("coastdown", help="coast-down to rest: chunked, streamed to results.h5, resumable")
    cd.add_argument("scenario", help="scenario TOML with an optional [coastdown] table (or a coast-down results.h5)")
    cd.add_argument("--out", default="coastdown", help="output folder (default ./coastdown)")
    cd.add_argument("--resume", action="store_true", help="continue the run in --out from its last written chunk")
    cd.add_argument("--overwrite", action="store_true", help="start over even if --out holds an unfinished run")
    _run_options(cd, "override operating.t_end (cap on simulated time) [s]",
                 "override a value, e.g. --set coastdown.stop_speed_rpm=500", "skip coastdown.png", "no progress lines")
    cd.set_defaults(func=cmd_coastdown)

    vd = sub.add_parser("verdict", help="the designer's verdict: contact pressures (ISO 76), temperatures, runaway, "
                                        "damage per drop and allowable drops, whirl, against [limits]")
    vd.add_argument("scenario", help="scenario TOML (a coast-down if it has [coastdown]), or a finished results.h5")
    vd.add_argument("--out", default=None, help="output folder (default ./verdict; for a results.h5 its folder)")
    vd.add_argument("--resume", action="store_true", help="coast-down: continue the unfinished run in --out")
    _run_options(vd, "override operating.t_end [s]", "override a value, e.g. --set limits.temperature_degc=100",
                 "skip the figures", "no progress output")
    vd.set_defaults(func=cmd_verdict)

    va = sub.add_parser("validate", help="run the paper's landings and write the validation report")
    va.add_argument("--out", default="validation", help="output folder (default ./validation)")
    va.add_argument("--quick", action="store_true", help="0.5 s runs")
    va.add_argument("--publish", default=None, metavar="DIR",
                    help="also write the report to DIR/validation.md (DIR/validation_<rig stem>.md with --rig), "
                         "e.g. --publish docs to regenerate the checkout's docs/validation.md")
    va.add_argument("--workers", type=int, default=2, help="parallel runs (default 2)")
    va.add_argument("--rig", default=None, help="rotor/rig TOML merged on top of every paper scenario "
                                                "(e.g. scenarios/rig_rotor_first.toml)")
    va.add_argument("--set", dest="sets", action="append", default=[], metavar="KEY=VALUE",
                    help="override a value in every landing, e.g. --set solver.step_control='auto' (stated in the report)")
    va.add_argument("--report-from", default=None, metavar="RUN",
                    help="no landing: render the report and figures again from the stored run in RUN (a validate "
                         "--out folder), e.g. after a change of the report's wording; refused when a scenario "
                         "gives other values than RUN was landed on. With --publish DIR the report goes there too")
    va.set_defaults(func=cmd_validate)

    an = sub.add_parser("animate", help="render a results.h5 offline (Exudyn's raytracer: the rotor in 3D, and "
                        "the orbits) into an MP4, a GIF or a PNG still")
    an.add_argument("results", help="results.h5 of a rotorlanding run")
    an.add_argument("--out", default="landing.gif", help="landing.gif, landing.mp4 (needs pip install "
                    "'rotorlanding[video]') or still.png (one frame at --at); default landing.gif")
    an.add_argument("--fps", type=float, default=20.0, help="frames per simulated second (default 20): "
                    "floor(duration x fps) + 1 frames")
    an.add_argument("--play-fps", type=float, default=20.0, help="frames per second of the movie (default 20)")
    an.add_argument("--view", default="all", help="all (3D rotor and every bearing's orbit; default), a catcher "
                    "bearing of the run, e.g. DE (3D and its orbit), or rotor (3D only)")
    an.add_argument("--max-frames", type=int, default=None, help="cap on the number of frames")
    an.add_argument("--size", default="1280x720", help="frame size WIDTHxHEIGHT in pixels (default 1280x720)")
    an.add_argument("--at", type=float, default=None, help="time [s] of the still for a .png (default: the last sample)")
    an.set_defaults(func=cmd_animate)

    sw = sub.add_parser("sweep", help="run a grid / Monte Carlo sweep of scenario values in parallel")
    sw.add_argument("sweep", help="sweep TOML file")
    sw.add_argument("--out", default="sweep", help="output folder (default ./sweep)")
    sw.add_argument("--workers", type=int, default=2, help="local worker processes (default 2)")
    sw.add_argument("--scheduler", default=None, help="Dask scheduler address (tcp://host:8786)")
    sw.set_defaults(func=cmd_sweep)

    wm = sub.add_parser("whirl-map", help="probability of each whirl class over two scenario keys, several drop "
                                          "directions per cell, with its figure")
    wm.add_argument("map", help="whirl-map TOML file (scenario, drops, [fixed], [axes] with two keys)")
    wm.add_argument("--out", default="whirl_map", help="output folder (default ./whirl_map)")
    wm.add_argument("--workers", type=int, default=2, help="local worker processes (default 2)")
    wm.set_defaults(func=cmd_whirl_map)

    dg = sub.add_parser("diagnose", help="find the missing effect that explains a model-measurement gap")
    dg.add_argument("--measured", required=True, nargs="+",
                    help="CSV, .mat, results.h5 or a feature table (.toml/.json); several records of repeated "
                         "landings of one operating point are compared as their means")
    dg.add_argument("--scenario", required=True, help="the model as it is (scenario TOML)")
    dg.add_argument("--out", default="diagnosis")
    dg.add_argument("--candidates", default=None, help="comma-separated effect names (default: every effect off except faults such as worn_bearing_drag)")
    dg.add_argument("--max-effects", type=int, default=1)
    dg.add_argument("--workers", type=int, default=2)
    dg.add_argument("--time-offset-s", type=float, default=None,
                    help="drop instant in the data's clock (default: detected from the vertical displacement)")
    dg.add_argument("--set", action="append", metavar="KEY=VALUE",
                    help="change the model, e.g. --set effects.axial_rub=false (repeatable)")
    dg.add_argument("--t-end", type=float, default=None, help="override operating.t_end of the model [s]")
    dg.add_argument("--maxiter", type=int, default=10, help="search iterations per candidate parameter (default 10)")
    dg.add_argument("--parameters", default=None,
                    help="comma-separated [bounds] keys tried as wrong-parameter candidates, or none "
                         "(default: rotorlanding.diagnose_run.DEFAULT_PARAMETERS the scenario bounds)")
    dg.add_argument("--ensemble", type=int, default=None,
                    help="drops per model variant (from a 5 um circle; over its disc with repeated records); "
                         "features become the ensemble's statistics, a gap smooth in the parameters (default: 4 "
                         "against one record, as many as the records of repeated landings, 1 per point of a "
                         "feature table; with records at least as many; 1: one drop)")
    dg.add_argument("--scatter-scales", action=argparse.BooleanOptionalAction, default=None,
                    help="charge each feature in units of its scale and the model's own scatter over its drops "
                         "(default: on with --ensemble >= 2 or repeated records, where that scatter is measured, "
                         "off for one drop; docs/measured_data.md sessions 48-50)")
    dg.add_argument("--ensemble-radius-m", type=float, default=None,
                    help="radius of the drop circle of --ensemble [m] (default 5e-6, an AMB's position error)")
    dg.add_argument("--journals", default="DE",
                    help="journals whose features are compared: DE (default) or DE,NDE (the NDE's landing depth, "
                         "mean orbit, impact force and race spin-up; the whirl rows are the DE's)")
    dg.add_argument("--noise-gap", type=float, default=None,
                    help="noise gate (default: estimated from the model's drops and the record's noise)")
    dg.set_defaults(func=cmd_diagnose)

    ca = sub.add_parser("calibrate", help="Monte Carlo search of rig unknowns against the paper's validation data")
    ca.add_argument("space", help="space TOML: samples, seed, t_end, [ranges]")
    ca.add_argument("--out", default="calibration")
    ca.add_argument("--workers", type=int, default=2)
    ca.add_argument("--from-run", default=None, metavar="RUN.json",
                    help="read the fit off a stored run (calibration.json) that landed the same designs on "
                         "more cases, without landing (e.g. a held-out fit from the three-speed fit)")
    ca.set_defaults(func=cmd_calibrate)

    fm = sub.add_parser("fit-modes", help="fit rotor geometry so that a landed mode matches measured whirl "
                                          "frequencies at several speeds (deterministic, re-runnable)")
    fm.add_argument("space", help="space TOML: rotor, support_stiffness, lock_ratio, [targets], [ranges]")
    fm.add_argument("--out", default="modefit")
    fm.set_defaults(func=cmd_fit_modes)

    r = sub.add_parser("reduce", help="Craig-Bampton reduction error: full vs reduced frequencies")
    r.add_argument("file")
    r.add_argument("--speeds-rpm", default="0,10000")
    r.add_argument("--f-limit-hz", type=float, default=None,
                   help="compare modes below this frequency (default 2 x max_speed_rpm / 60)")
    r.add_argument("--free", action="store_true", help="ignore supports")
    r.add_argument("--json", action="store_true")
    r.set_defaults(func=cmd_reduce)
    return p


def main(argv=None) -> int:
    args = build_parser().parse_args(argv)
    try:
        for opt in ("out", "publish", "plot"):
            # '' is the current folder to Path: a run wrote there (clearing a results.h5 first)
            if isinstance(getattr(args, opt, None), str) and not getattr(args, opt).strip():
                raise InputError(f"--{opt}", "''", "must name a folder or file, not an empty string")
        return args.func(args)
    except InputError as err:
        print(f"rotorlanding: error: {err}", file=sys.stderr)
        return EXIT_INPUT
    except WriteError as err:
        print(f"rotorlanding: error: {err}", file=sys.stderr)
        if poisoned():  # an HDF5 file whose write failed: the library's shutdown would crash
            hard_exit(EXIT_IO)
        return EXIT_IO


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
