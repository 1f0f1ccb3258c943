"""Re-runnable calibration of the rig's unknown parameters against the paper's validation data
(``rotorlanding calibrate SPACE.toml``).

A space file lists the unknowns and their ranges (any scenario keys, arrays of tables by index)::

    samples = 40          # Monte Carlo designs
    seed = 1
    t_end = 0.8           # s per landing
    verify_top = 3        # re-run the best designs at half the step (step-convergence check)
    cases = ["bw"]        # optional: the landings scored (default fw3000, fw7000, fw10000, bw; bw015,
                          # the backward landing at mu_rad 0.15 that must stay calm, on request)
    ensemble = 8          # optional: every case as 8 drops from a 5 um circle, scored on the
                          # members' majority class and medians (rotorlanding.ensemble)
    [fixed]               # optional: applied to every design (e.g. a solver step for the search)
    "solver.step" = 1e-4
    [ranges]
    "rotor.sections.3.outer_diameter" = {min = 0.035, max = 0.06}
    "bearings.DE.c_rib,bearings.NDE.c_rib" = {min = 1e3, max = 3e4, log = true}   # tied keys

Each design runs the paper's forward-whirl landings at 3000/7000/10000 rpm and the
backward-whirl landing (scenarios/paper), and is scored by the sum of relative errors against
the experimental values (Fig. 39 frequencies, Table 1 frequency and onset, Table 2 force), with
a penalty of 1 for each wrong whirl class. A key list separated by commas sets all its keys to
one sampled value (the same unknown at both bearings).

Landings near a whirl threshold can change class with the time step; a design that does so is
not a result. The ``verify_top`` best designs are therefore run again at half the step and
scored again, and the next ``verify_top`` after them while none of a batch has converged;
``converged`` is true when every whirl class is the same and every whirl frequency agrees within
2 % (and the forward-case DE force within 5 %). An ensemble's median frequency is a statistic of
chaotic drops with a standard error of a few per cent; for it the frequency tolerance is twice
the standard error of the difference when that exceeds 2 %. Converged designs rank first, then unchecked
ones, then unconverged ones.

On ensembles every score has a standard error (``score_se``: the medians' and shares' errors in
quadrature), and ``within_noise_of_best`` marks the designs whose score lies within ``NOISE_Z``
standard errors of the difference from the best's: the search cannot rank them, so their span
(``within_noise_span`` in calibration.json, printed) is the fit's uncertainty in each unknown, and
which of them comes first is a draw (on another install the first may be another of them).
``OUT/calibration.csv`` lists designs by score; the
best design's overrides are printed as ``--set`` arguments and TOML lines to paste into
``scenarios/rig/rig.toml`` (with the reasoning), after which ``rotorlanding validate`` reports.
"""

from __future__ import annotations

import csv
import functools
import io
import json
import math
from pathlib import Path

from .config import override_table, range_spec, sample_ranges, study_file, tied_keys
from .ensemble import drop_offsets, ensemble_stats, member_result, share_se
from .errors import InputError
from .runner import reduction_cache, run_all, warm_model
from .safeio import atomic_write_text
from .validate import paper, paper_dir

#: s, the onset change between steps h and h/2 that an ensemble may show without its noise
ONSET_TOL_S = 0.05

#: case -> (paper scenario, extra --set): bw015 is the backward landing's bearing at the paper's
#: normal friction, mu_rad 0.15, which must land calm (Table 1's switch; scored by its whirling share)
CASES = {"fw3000": ("forward_whirl_3000rpm.toml", []), "fw7000": ("forward_whirl_landing.toml", []),
         "fw10000": ("forward_whirl_10000rpm.toml", []), "bw": ("backward_whirl_landing.toml", []),
         "bw015": ("backward_whirl_landing.toml", ["contact.mu_rad=0.15"])}
#: the cases scored when a space file names none (the switch is opt-in)
DEFAULT_CASES = ["fw3000", "fw7000", "fw10000", "bw"]


def load_space(path) -> dict:
    with study_file(path) as (path, t):
        n = t.integer("samples", 20)
        seed = t.integer("seed", 1, minimum=0)
        t_end = t.number("t_end", 0.8, positive=True)
        from .scenario import MAX_T_END

        if t_end > MAX_T_END:  # checked here: every design's landing failed on it, exit 1
            raise InputError("t_end", t_end, f"must be <= {MAX_T_END:g} s (as a scenario's operating.t_end)")
        verify_top = t.integer("verify_top", 0, minimum=0)
        cases = t.raw("cases", list(DEFAULT_CASES))
        if not (isinstance(cases, list) and cases and all(c in CASES for c in cases)):
            raise InputError("cases", cases, f"must be a non-empty list of {', '.join(CASES)}")
        ensemble = t.integer("ensemble", 1)
        score_force = t.raw("score_force", True)
        if not isinstance(score_force, bool):
            raise InputError("score_force", score_force, "true or false (score Table 2's force maximum)")
        fixed = override_table(t.raw("fixed", {}), "fixed")
        ranges = t.raw("ranges")
        if not isinstance(ranges, dict) or not ranges:
            raise InputError("ranges", ranges, "give at least one key = {min, max[, log]}")
        for k, r in ranges.items():
            range_spec(r, f"ranges.{k}", log=True)
        # discrete choices made outside the search (read by validate's provenance labels)
        choices = t.raw("choices", {})
        if not isinstance(choices, dict):
            raise InputError("choices", choices, "a table of tables {options, chosen, judged_on = [case, ...], record}")
        for what, c in choices.items():
            if not (isinstance(c, dict) and set(c) == {"options", "chosen", "judged_on", "record"}
                    and isinstance(c["judged_on"], list) and all(j in CASES for j in c["judged_on"])):
                raise InputError(f"choices.{what}", c, "a table {options, chosen, judged_on = [case, ...], record}")
        t.finish()
        _check_ranges(fixed, ranges, cases)
    return {"designs": sample_ranges(ranges, n, seed), "t_end": t_end, "verify_top": verify_top,
            "fixed": dict(fixed), "cases": cases, "ensemble": ensemble, "score_force": score_force}


def _check_ranges(fixed: dict, ranges: dict, cases: list[str]) -> None:
    """Every scored paper case must load (schema and plausibility limits) at both ends of the
    ranges, so a key that does not exist or a range outside the physical limits is reported
    before hours of landings rather than as every design failing."""
    from .scenario import load_scenario

    for end in ("min", "max"):
        design = {k: float(r[end]) for k, r in ranges.items()}
        for case in cases:
            fname, case_sets = CASES[case]
            try:
                load_scenario(paper_dir() / fname, case_sets + design_overrides(design, fixed))
            except InputError as err:
                raise InputError(f"ranges ({end} ends), case {case}: {err.field}", err.value, err.allowed) from None


def design_overrides(design: dict, fixed: dict | None = None) -> list[str]:
    """--set strings of a design (tied keys expanded) after the fixed ones."""
    out = [f"{k}={v!r}" for k, v in (fixed or {}).items()]
    for k, v in design.items():
        out += [f"{kk}={v!r}" for kk in tied_keys(k)]
    return out


def _run(job):
    from .postprocess import evaluate, summarize
    from .run import simulate
    from .scenario import load_scenario

    i, case, design, t_end, fixed, step_factor, extra = job
    fname, case_sets = CASES[case.split("#")[0]]  # "bw#3": member 3 of the backward landing's ensemble
    sets = case_sets + design_overrides(design, fixed) + [f"operating.t_end={t_end}"] + list(extra)
    try:
        sc = load_scenario(paper_dir() / fname, sets)
        if step_factor != 1.0:
            sc = load_scenario(paper_dir() / fname, sets + [f"solver.step={sc.solver.step * step_factor!r}"])
        spec, t, q, v, info = simulate(sc, progress=False, reduction=reduction_cache())
        s = summarize(spec, t, evaluate(spec, t, q, v))
        r = member_result(s)
        return i, case, {**r, "force_max_n": r["v_force_range_n"][1], "ok": info["complete"]}
    except Exception as exc:  # a design that breaks the model scores badly, the search goes on
        return i, case, {"direction": "failed", "error": str(exc), "ok": False}


def score(res: dict, cases=tuple(DEFAULT_CASES), *, force: bool = True) -> tuple[float, dict]:
    """Sum of relative errors vs the experiments over ``cases``; 1 per wrong whirl class.

    A forward case run as an ensemble is judged at the DE journal, as ``validate`` judges it (the
    paper measured its whirl frequencies there): the DE's median frequency, plus ``CASE_de``, the
    share of drops whose DE journal does not whirl forward.

    The backward case also scores persistence: the paper's whirl (Figs. 20-24) lasts from its onset
    to the end of the record, so ``1 - persistence`` (share of the time after onset not whirling)
    is added as ``bw_persist``; an ensemble adds ``bw_share``, the share of its drops that do not whirl
    backward (validate's switch asks for 7 of 8; since session 31). ``bw015`` (Table 1's switch: the same bearing at mu_rad 0.15) scores
    the share of its drops that whirl, as ``bw015_whirls``. ``force = False`` leaves Table 2's force
    maximum out of the score (``score_force`` in the space file), so that it stays a prediction."""
    parts = score_parts(res, cases, force=force)
    return _total(parts), {k: v for k, (v, _) in parts.items()}


def _total(parts: dict) -> float:
    return float(sum(v for v, _ in parts.values()))


def _quadrature(parts: dict) -> float | None:
    ses = [se for _, se in parts.values()]
    return None if any(se is None for se in ses) else math.sqrt(sum(se * se for se in ses))


def score_se(res: dict, cases=tuple(DEFAULT_CASES), *, force: bool = True) -> float | None:
    """Standard error of ``score``: the parts' errors added in quadrature (the drops of each case are
    their own draws). ``None`` when a part has no error to give: a single landing per case is one
    draw of a chaotic landing, with no spread to measure."""
    return _quadrature(score_parts(res, cases, force=force))


def score_parts(res: dict, cases=tuple(DEFAULT_CASES), *, force: bool = True) -> dict:
    """``score``'s parts, each as (value, standard error). A fixed penalty (a class missed, a part
    clipped at 1) has error 0; a median's error is the ensemble's (``frequency_se_hz``, ``onset_se_s``,
    ``v_force_range_se_n``) over the experiment it is divided by; a share of drops has the binomial
    error of ``ensemble.share_se``. ``None``: no error known (a single landing)."""
    parts = {}
    for case, rpm, f_exp in zip(("fw3000", "fw7000", "fw10000"), *[paper()["fig39"][k] for k in
                                                                    ("speed_rpm", "experimental_hz")]):
        if case not in cases:
            continue
        r = res.get(case, {})
        de = r.get("de")
        if de:  # an ensemble: judged at the DE journal, where the paper measured (as validate does)
            f_de = de.get("frequency_hz") if de.get("direction") == "forward" else None
            parts[case] = ((abs(f_de - f_exp) / f_exp, (de.get("frequency_se_hz") or 0.0) / f_exp) if f_de
                           else (1.0, 0.0))
            n, k = sum(de["counts"].values()), de["counts"].get("forward", 0)
            parts[case + "_de"] = (1.0 - k / n, share_se(k, n))
        else:
            parts[case] = ((abs(r["frequency_hz"] - f_exp) / f_exp, None) if r.get("direction") == "forward"
                           else (1.0, None))
    ens = "n" in res.get("fw7000", {})  # ensemble_stats' results carry their size
    r = res.get("fw7000", {})
    if force and "fw7000" in cases and r.get("force_max_n"):
        f_exp = paper()["table2"]["experimental"]["v_force_max_n"]
        v = abs(r["force_max_n"] / f_exp - 1) / 2
        se = (r.get("v_force_range_se_n") or [0.0, 0.0])[1] / f_exp / 2 if ens else None
        parts["force"] = (1.0, 0.0) if v >= 1.0 else (v, se)
    b = res.get("bw", {})
    t1 = paper()["table1"]["experimental"]
    ens = "n" in b
    if "bw" in cases and b.get("direction") == "backward":
        parts["bw_freq"] = (abs(b["frequency_hz"] - t1["frequency_hz"]) / t1["frequency_hz"],
                            (b.get("frequency_se_hz") or 0.0) / t1["frequency_hz"] if ens else None)
        v = abs(b["onset_s"] - t1["onset_s"]) / t1["onset_s"]
        parts["bw_onset"] = (1.0, 0.0) if v >= 1.0 else (v, (b.get("onset_se_s") or 0.0) / t1["onset_s"]
                                                         if ens else None)
        parts["bw_persist"] = (1.0 - min(1.0, max(0.0, b.get("persistence", 1.0))),
                               b.get("persistence_se", 0.0) if ens else None)
    elif "bw" in cases:
        parts["bw_freq"] = parts["bw_onset"] = parts["bw_persist"] = (1.0, 0.0)
    if "bw" in cases and ens and b.get("counts"):  # an ensemble: the share of drops not whirling backward,
        # as validate's switch judges the mu_rad 0.3 side (a majority alone passed designs with 19 of 32);
        # a majority that is not backward pays it on top of the three parts above, on purpose: it is
        # further from the paper's landing than a backward majority of too few drops
        n, k = sum(b["counts"].values()), b["counts"].get("backward", 0)
        parts["bw_share"] = (1.0 - k / n, share_se(k, n))
    if "bw015" in cases:  # the same bearing at mu_rad 0.15 must land calm: score its whirling share
        r = res.get("bw015", {})
        counts = r.get("counts") or {r.get("direction", "failed"): 1}
        n, k = sum(counts.values()), counts.get("none", 0)
        parts["bw015_whirls"] = (1.0 - k / n, share_se(k, n) if "n" in r else None)
    return parts


def noise_span(rows: list[dict], keys: list[str]) -> dict:
    """Per searched key, [min, max] over the designs ``within_noise_of_best``: the fit's own
    uncertainty in that unknown, as far as the sampled designs show it ({} when no design has an
    error to judge by)."""
    near = [r for r in rows if r.get("within_noise_of_best")]
    return {k: [min(r[k] for r in near), max(r[k] for r in near)] for k in keys} if near else {}


#: how many standard errors of a score difference make two designs distinguishable: 2, about 95 %
#: two-sided for a normal difference (the conventional significance of a single comparison)
NOISE_Z = 2.0


def within_noise(rows: list[dict], z: float = NOISE_Z) -> list[dict]:
    """The designs that the search cannot tell from the best (``rows[0]``): a score above the best's
    by less than ``z`` standard errors of the difference, hypot(se, se_best). Designs with a failed
    landing or without an error (single landings) are left out; so is every design when the best has
    no error. This set, not its first member, is what a Monte Carlo fit on ensembles of chaotic
    drops determines: which of its members ranks first moves with the last bits of the arithmetic
    (docs/calibration.md, session 24). A design checked at half the step counts with the worse of
    its two scores (as ``calibrate`` ranks it); one that did not converge there is left out."""
    def ranked(r):
        return max(r["score"], r.get("score_half_step") or r["score"])

    best = rows[0]
    if best.get("score_se") is None or best.get("failed_landings") or best.get("converged") is False:
        return []
    lim = ranked(best)
    return [r for r in rows if r.get("score_se") is not None and not r.get("failed_landings")
            and r.get("converged") is not False
            and ranked(r) - lim <= z * math.hypot(r["score_se"], best["score_se"])]


def _jobs(designs: dict, sp: dict, step_factor: float) -> list[tuple]:
    """One job per design and case; each case as ``sp['ensemble']`` drops when > 1."""
    jobs = []
    for i, d in designs.items():
        for c in sp["cases"]:
            if sp["ensemble"] > 1:
                jobs += [(i, f"{c}#{k}", d, sp["t_end"], sp["fixed"], step_factor, extra)
                         for k, extra in enumerate(drop_offsets(sp["ensemble"]))]
            else:
                jobs.append((i, c, d, sp["t_end"], sp["fixed"], step_factor, []))
    return jobs


def _run_all(jobs, workers):
    results: dict[int, dict] = {}
    # _run turns a failing design into its row; BLAS as before (runner.worker_setup says why)
    warm = functools.partial(warm_model, paper_dir() / "forward_whirl_landing.toml")  # see validate
    it = run_all(_run, jobs, workers, failures="raise", blas_threads=None, warm=warm)
    members: dict[tuple, list] = {}
    for i, case, r in it:
        if "#" in case:  # "CASE#k": member k of CASE's ensemble
            members.setdefault((i, case.split("#")[0]), []).append(r)
        else:
            results.setdefault(i, {})[case] = {**r, "failed": int(r.get("direction") == "failed")}
    for (i, case), m in members.items():
        st = ensemble_stats(m)
        st["failed"] = sum(x.get("direction") == "failed" for x in m)  # landings that raised
        if "v_force_range_n" in st:  # the force score reads the members' median peak
            st["force_max_n"] = st["v_force_range_n"][1]
        results.setdefault(i, {})[case] = st
    return results


def converged(a: dict, b: dict) -> bool:
    """Same whirl classes, frequencies within 2 % (or, for ensemble medians, within twice the
    standard error of their difference when that is larger), ensemble median onsets within
    ``ONSET_TOL_S`` (or twice their standard error of the difference), forward-case force within
    5 % (step h vs h/2)."""
    for c in CASES:
        if c not in a and c not in b:
            continue
        ra, rb = a.get(c, {}), b.get(c, {})
        if ra.get("direction") != rb.get("direction") or ra.get("direction") == "failed":
            return False
        fa, fb = ra.get("frequency_hz"), rb.get("frequency_hz")
        # an ensemble median carries sampling noise (frequency_se_hz): a step change within twice
        # the noise of the difference cannot be told from a different draw of chaotic drops
        noise = 2.0 * math.hypot(ra.get("frequency_se_hz") or 0.0, rb.get("frequency_se_hz") or 0.0)
        if fa and fb and abs(fa - fb) > max(0.02 * abs(fb), noise):
            return False
        # the onset of an ensemble (a random variable of the drop once the worn drag develops):
        # judged like the frequency, against 0.05 s (one whirl-detector window) or twice its noise
        oa, ob = ra.get("onset_s"), rb.get("onset_s")
        if ra.get("onset_se_s") is not None or rb.get("onset_se_s") is not None:
            noise = 2.0 * math.hypot(ra.get("onset_se_s") or 0.0, rb.get("onset_se_s") or 0.0)
            if oa is not None and ob is not None and abs(oa - ob) > max(ONSET_TOL_S, noise):
                return False
    fa, fb = a.get("fw7000", {}).get("force_max_n"), b.get("fw7000", {}).get("force_max_n")
    return not (fa and fb and abs(fa - fb) > 0.05 * abs(fb))


def calibrate(space_path, out_dir, *, workers: int = 2) -> list[dict]:
    sp = load_space(space_path)
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    cases = sp["cases"]
    results = _run_all(_jobs(dict(enumerate(sp["designs"])), sp, 1.0), workers)
    rows = []
    for i, d in enumerate(sp["designs"]):
        both = score_parts(results[i], cases, force=sp["score_force"])  # (value, error) per part, once
        parts, part_se = {k: v for k, (v, _) in both.items()}, {k: se for k, (_, se) in both.items()}
        de = {c: results[i][c].get("de") or {} for c in cases}
        rows.append({"design": i, "score": _total(both), "score_se": _quadrature(both),
                     "within_noise_of_best": None, "converged": None, "score_half_step": None,
                     "failed_landings": sum(results[i][c].get("failed", 0) for c in cases), **d,
                     **{f"err_{k}": v for k, v in parts.items()},
                     # each part's error, so that a study can score a subset of the cases with its noise
                     # (the held-out fits score two of the three speeds of the same designs)
                     **{f"err_{k}_se": v for k, v in part_se.items()},
                     # the DE journal's own whirl per case (what validate and the score judge)
                     **{f"{c}_de_{key}": de[c].get(name) for c in cases if de[c]
                        for key, name in (("direction", "direction"), ("hz", "frequency_hz"))},
                     **{f"{c}_de_forward": de[c]["counts"].get("forward", 0) for c in cases if de[c]},
                     # its shapes (ensemble.ensemble_stats' de["forms"]): "cylindrical 5 72.70; conical 3
                     # 79.30", one text per case so the table stays flat
                     **{f"{c}_de_shapes": "; ".join(f"{k} {v['n']} {v['frequency_hz']:.2f}" for k, v in de[c]["forms"].items())
                        for c in cases if de[c].get("forms")},
                     **{f"{c}_failed": results[i][c].get("failed", 0) for c in cases},
                     **{f"{c}_direction": results[i][c].get("direction") for c in cases},
                     **{f"{c}_hz": results[i][c].get("frequency_hz") for c in cases},
                     **({"bw_onset_s": results[i]["bw"].get("onset_s"),
                         "bw_persistence": results[i]["bw"].get("persistence")} if "bw" in cases else {}),
                     # what the score leaves out, recorded so a study can ask what a fit to some of
                     # Table 1 predicts of the rest (docs/studies/backward_frequency_only.py)
                     **({"bw_se_hz": results[i]["bw"].get("frequency_se_hz"),
                         "bw_onset_se_s": results[i]["bw"].get("onset_se_s"),
                         "bw_v_disp_min_m": (results[i]["bw"].get("v_disp_range_m") or [None, None])[0],
                         "bw_v_disp_max_m": (results[i]["bw"].get("v_disp_range_m") or [None, None])[1]}
                        if "bw" in cases and sp["ensemble"] > 1 else {}),
                     **({f"{c}_fraction": results[i][c].get("fraction") for c in cases} if sp["ensemble"] > 1
                        else {}),
                     # Table 2's DE numbers (median peaks over the drops, forces on the rotor, positive up),
                     # recorded unscored so that a study can ask what they say of the designs
                     **{f"{c}_v_{q}_{end}_{u}": results[i][c][f"v_{q}_range_{u}"][j]
                        for c in cases for q, u in (("disp", "m"), ("force", "n"))
                        if results[i][c].get(f"v_{q}_range_{u}") for j, end in ((0, "min"), (1, "max"))}})
    rows.sort(key=lambda r: r["score"])
    # verify the best designs at half the step, batch after batch, until one has converged
    n = sp["verify_top"]
    for b0 in range(0, len(rows) if n else 0, max(n, 1)):
        top = rows[b0:b0 + n]
        half = _run_all(_jobs({r["design"]: sp["designs"][r["design"]] for r in top}, sp, 0.5), workers)
        for r in top:
            r["converged"] = converged(results[r["design"]], half[r["design"]])
            r["score_half_step"] = score(half[r["design"]], cases, force=sp["score_force"])[0]
            r.update({f"{c}_hz_half_step": half[r["design"]][c].get("frequency_hz") for c in cases})
            if "bw" in cases:
                r["bw_onset_s_half_step"] = half[r["design"]]["bw"].get("onset_s")
        if any(r["converged"] for r in top):
            break
    return _rank_and_write(rows, space_path, sp, out)


def _rank_and_write(rows: list[dict], space_path, sp: dict, out: Path) -> list[dict]:
    """Rank the designs (converged first, then unchecked, then unconverged; a checked design's score
    is the worse of the two steps), mark those within the noise of the best, and write the table."""
    rank = {True: 0, None: 1, False: 2}
    rows.sort(key=lambda r: (rank[r["converged"]], max(r["score"], r["score_half_step"] or 0.0)))
    noise = within_noise(rows)
    for r in rows:
        r["within_noise_of_best"] = (r in noise) if noise else None
    keys = []
    for r in rows:
        keys += [k for k in r if k not in keys]
    rows = [{k: r.get(k) for k in keys} for r in rows]
    # written whole under a temporary name and renamed: a kill leaves the previous table or this one
    buf = io.StringIO(newline="")
    w = csv.DictWriter(buf, fieldnames=list(rows[0]))
    w.writeheader()
    w.writerows(rows)
    atomic_write_text(out / "calibration.csv", buf.getvalue())
    atomic_write_text(out / "calibration.json", json.dumps(
        {"space": str(space_path), "ensemble": sp["ensemble"], "cases": list(sp["cases"]), "noise_z": NOISE_Z,
         "within_noise_span": noise_span(rows, list(sp["designs"][0])),
         "designs": rows}, indent=2, default=float))
    return rows


def calibrate_from_run(space_path, run_path, out_dir) -> list[dict]:
    """The fit of ``space_path`` read off a stored run (``run_path``: a ``calibration.json``) whose space
    landed the same designs on more cases, without a landing: each design's score is the sum of its
    stored parts over this space's cases, its error their quadrature, then ranked and written as
    ``calibrate`` would. A case's landings do not depend on which other cases a fit scores (each is its
    own run of the same scenario, design and drops), so this is the fit the space would run, to the
    bit on the same install. It is how the held-out fits (two of the three Fig. 39 speeds) follow
    from the three-speed fit. Refused in one line unless the two spaces draw the same designs with
    the same fixed values, drops, t_end and score rule, this space's cases are among the run's, and
    neither checks the step (verify_top = 0: a half-step check lands again)."""
    sp = load_space(space_path)
    run_path = Path(run_path)
    try:
        run = json.loads(run_path.read_text())
        src = Path(run["space"])
        if not src.is_absolute():  # as calibrate was given it: from where it ran, else the checkout's root
            from .validate import project_root

            src = next((b / src for b in (Path.cwd(), project_root()) if (b / src).is_file()), src)
        rsp = load_space(src)
    except (OSError, ValueError, KeyError, InputError) as e:
        raise InputError("--from-run", str(run_path), f"a calibration.json whose space file can be read ({e})")
    if not set(sp["cases"]) <= set(run["cases"]):
        raise InputError("--from-run", str(run_path), f"a run that scored every case of {Path(space_path).name} "
                         f"({', '.join(sp['cases'])}); it scored {', '.join(run['cases'])}")
    for key in ("designs", "fixed", "ensemble", "t_end", "score_force", "verify_top"):
        if sp[key] != rsp[key]:
            raise InputError("--from-run", str(run_path), f"a run of the same {key} as {Path(space_path).name} "
                             f"(its space {src.name} differs)")
    if sp["verify_top"]:
        raise InputError("verify_top", sp["verify_top"], "0 for a fit read off a stored run (a step check lands again)")
    fitted = set(sp["cases"])
    rows = []
    for r in run["designs"]:
        parts = stored_parts(r, fitted)
        # the other cases' parts are no part of this score; their landings' columns stay, as data
        row = {k: v for k, v in r.items() if not k.startswith("err_") or _part_case(k[4:].removesuffix("_se")) in fitted}
        failed = [r[f"{c}_failed"] for c in sp["cases"] if f"{c}_failed" in r]
        row.update({"score": _total(parts), "score_se": _quadrature(parts), "within_noise_of_best": None,
                    "failed_landings": sum(failed) if len(failed) == len(sp["cases"]) else r.get("failed_landings")})
        rows.append(row)
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    rows.sort(key=lambda r: r["design"])
    return _rank_and_write(rows, space_path, sp, out)


def stored_parts(row: dict, cases) -> dict:
    """A stored design row's score parts that belong to ``cases``, each as (value, standard error): a
    case's own part and, for an ensemble, its DE share (the ``err_<part>`` and ``err_<part>_se``
    columns ``calibrate`` writes). ``_total`` and ``_quadrature`` of them are that fit's score and error."""
    cases = set(cases)
    return {k[4:]: (v, row.get(f"{k}_se")) for k, v in row.items()
            if k.startswith("err_") and not k.endswith("_se") and _part_case(k[4:]) in cases}


def stored_score(row: dict, cases) -> tuple[float, float | None]:
    """The score of a fit on ``cases`` only, from a stored row's parts, and its standard error."""
    parts = stored_parts(row, cases)
    return _total(parts), _quadrature(parts)


def _part_case(part: str) -> str:
    """The case a score part belongs to (``score_parts``' names): fw7000 and fw7000_de -> fw7000, force
    -> fw7000 (Table 2's force is the 7000 rpm landing's), bw_freq / bw_share -> bw, bw015_whirls -> bw015."""
    if part == "force":
        return "fw7000"
    for c in sorted(CASES, key=len, reverse=True):
        if part == c or part.startswith(c + "_"):
            return c
    return part
