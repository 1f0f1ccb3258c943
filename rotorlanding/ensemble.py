"""Landing ensembles: the same landing dropped from a few points of a small circle.

Why: a rattling landing near a whirl threshold is chaotic. A rotor dropped from exactly the
bearing centre has a mirror-symmetric start, and whether and when it whirls then hangs on
round-off (class and onset changed with the time step). A real rotor is never dropped exactly
centred: the AMBs hold it within a few micrometres. Dropping it from ``n`` points of a circle of
radius ``radius_m`` (default 5 um, a typical AMB position error) and reporting the statistics of
the members turns the landing into a result that does not hang on one trajectory.
"""

from __future__ import annotations

import math
from collections import Counter
from statistics import median, stdev

from .whirl import landing_whirl

DROP_RADIUS_M = 5e-6  # m: typical AMB position-control error of a levitated rotor


def drop_offsets(n: int, radius_m: float = DROP_RADIUS_M, phase: float = 0.0) -> list[list[str]]:
    """``--set`` overrides of the ``n`` members: drops from equally spaced points of the circle,
    the first at ``phase`` (a fraction of the spacing) from the +y axis."""
    if n < 1:
        raise ValueError(f"ensemble size must be >= 1, got {n}")
    return [_offset(radius_m, 2.0 * math.pi * (k + phase) / n) for k in range(n)]


def random_drop_offset(rng, radius_m: float = DROP_RADIUS_M) -> list[str]:
    """The ``--set`` override of one drop from a random point of the disc of radius ``radius_m``
    (uniform over its area; ``rng`` a numpy Generator, two draws: radius, then angle): a rig's
    drop point within the AMB's position error, as repeated landings have them."""
    return _offset(radius_m * math.sqrt(rng.uniform()), rng.uniform(0.0, 2.0 * math.pi))


def disc_drop_offsets(n: int, radius_m: float = DROP_RADIUS_M) -> list[list[str]]:
    """``--set`` overrides of ``n`` drops spread evenly over the disc of radius ``radius_m`` (a
    sunflower layout: drop k at radius sqrt((k + 1/2) / n) of the disc's, golden-angle steps), the
    deterministic counterpart of :func:`random_drop_offset`: a model's drops that stand for records
    falling from random points of the disc (their mean radius 2/3 of the disc's), where
    :func:`drop_offsets` puts every drop on its rim."""
    if n < 1:
        raise ValueError(f"ensemble size must be >= 1, got {n}")
    golden = math.pi * (3.0 - math.sqrt(5.0))
    return [_offset(radius_m * math.sqrt((k + 0.5) / n), k * golden) for k in range(n)]


def _offset(r: float, a: float) -> list[str]:
    r, a = float(r), float(a)
    return [f"amb.drop_offset_m=[{r * math.cos(a)!r}, {r * math.sin(a)!r}]"]


def member_result(summary: dict) -> dict:
    """The numbers of one landing (a run summary) that ensemble statistics and calibration use:
    the landing's whirl (``whirl.landing_whirl_bearing``: the DE's, or another bearing's when
    only that one whirls), where it was found, its shape (``whirl_form``), the DE vertical
    displacement and force ranges, and the DE inner race's speed over the rotor's at the end
    (``race_to_rotor``)."""
    w = landing_whirl(summary["whirl"])
    name = "DE" if "DE" in summary["bearings"] else next(iter(summary["bearings"]))  # else the first bearing
    de = summary["bearings"][name]
    de_w = (summary["whirl"].get("per_bearing") or {}).get(name) or {}
    rotor_rpm = summary["speeds"]["final_rotor_rpm"]
    return {"direction": w["direction"], "bearing": w["bearing"],
            "frequency_hz": w["frequency_hz"], "onset_s": w["onset_s"],
            "end_s": w.get("end_s"), "persistence": w.get("persistence"),
            # its shape: both journals going round together or against each other (whirl.whirl_shape)
            "whirl_form": (w.get("shape") or {}).get("form"),
            # the DE journal's own whirl: the paper measured its frequencies there
            "de_direction": de_w.get("direction", "none"), "de_frequency_hz": de_w.get("frequency_hz"),
            "v_disp_range_m": de["vertical_displacement_range_m"], "v_force_range_n": de["vertical_force_range_n"],
            # undefined once the rotor has (nearly) stopped
            "race_to_rotor": de["final_race_speed_rpm"] / rotor_rpm if rotor_rpm > 1.0 else None,
            # the whole span's excursion (run summaries only; a calibration's summaries leave it out)
            "span_peak_m": (summary.get("rotor_deflection") or {}).get("station_peak_m"),
            "span_max_m": (summary.get("rotor_deflection") or {}).get("peak_m")}


def ensemble_stats(members: list[dict]) -> dict:
    """Statistics of member results, each a dict with ``direction``, ``frequency_hz``, ``onset_s``
    and optionally ``end_s``, ``persistence``, ``v_disp_range_m`` / ``v_force_range_n`` ([min, max]).

    ``direction``: the most frequent class (ties go to the whirl class, so a half-whirling
    ensemble is not called calm); ``fraction``: share of members in that class; frequency and
    onset, end, persistence: medians over the members of that class; ranges: medians of the
    members' min and max; ``race_to_rotor``: median over all members; ``bearings``: how many
    members of the whirl class whirled at which bearing (members without ``bearing`` count as DE);
    ``de_whirls``: members of any class whose DE journal whirls.  ``frequency_se_hz``: standard
    error of the median frequency, 1.2533 s / sqrt(k) (s the sample standard deviation of the k >= 2 frequencies; the large-sample
    rule for a median), the sampling noise against which a step-size change is judged;
    ``onset_se_s`` the same for the onsets, and ``onset_range_s`` their [min, max] (a developing
    worn drag makes the onset a random variable of the drop: docs/calibration.md, session 7).
    ``v_disp_range_se_m`` / ``v_force_range_se_n``: standard errors of the median peaks;
    ``race_to_rotor_se`` that of the median speed ratio; ``end_se_s`` and ``persistence_se`` those of
    the whirl's median end and persistence.
    ``forms``: the whirl shapes (``whirl_form`` of the members of the whirl class: cylindrical,
    conical, mixed), each with its number of drops, their median frequency and its standard error;
    ``de["forms"]`` the same for the DE journal's whirl.
    ``de``: the DE journal's own whirl over all members (members with ``de_direction``): its class
    counts, majority class and median frequency with its standard error; the paper measured its
    whirl frequencies there, while the landing's whirl may be another bearing's.
    """
    if not members:
        raise ValueError("empty ensemble")
    counts = Counter(m["direction"] for m in members)
    direction = _majority(counts)
    same = [m for m in members if m["direction"] == direction]
    freqs = [m["frequency_hz"] for m in same if m.get("frequency_hz") is not None]
    onsets = [m["onset_s"] for m in same if m.get("onset_s") is not None]
    whirl = direction in ("forward", "backward")
    out = {"n": len(members), "direction": direction, "fraction": len(same) / len(members),
           "counts": dict(counts),
           "frequency_hz": median(freqs) if freqs and whirl else None,
           "onset_s": median(onsets) if onsets and whirl else None}
    if whirl:
        out["bearings"] = dict(Counter(m.get("bearing", "DE") for m in same))
        out["frequency_locks"] = frequency_locks(freqs)
        if len(freqs) >= 2:
            out["frequency_se_hz"] = _frequency_se(freqs, out["frequency_locks"])
        forms = _forms(same, "frequency_hz")
        if forms:
            out["forms"] = forms
        if onsets:
            out["onset_range_s"] = [min(onsets), max(onsets)]
        if len(onsets) >= 2:
            out["onset_se_s"] = _median_se(onsets)
    # members (of any class) in which the DE journal itself whirls: the landing's whirl is the DE's
    # whenever the DE whirls (whirl.landing_whirl_bearing)
    out["de_whirls"] = sum(m["direction"] in ("forward", "backward") and m.get("bearing", "DE") == "DE"
                           for m in members)
    for key in ("end_s", "persistence"):
        vals = [m[key] for m in same if m.get(key) is not None]
        if vals and whirl:
            out[key] = median(vals)
            if len(vals) >= 2:
                out[key.removesuffix("_s") + "_se" + ("_s" if key.endswith("_s") else "")] = _median_se(vals)
    ratios = [m["race_to_rotor"] for m in members if m.get("race_to_rotor") is not None]
    if ratios:
        out["race_to_rotor"] = median(ratios)
        if len(ratios) >= 2:
            out["race_to_rotor_se"] = _median_se(ratios)
    for key, unit in (("v_disp_range_m", "_m"), ("v_force_range_n", "_n")):
        vals = [m[key] for m in members if m.get(key) is not None]
        if vals:
            out[key] = [median(v[0] for v in vals), median(v[1] for v in vals)]
            if len(vals) >= 2:
                out[key.removesuffix(unit) + "_se" + unit] = [_median_se([v[i] for v in vals]) for i in (0, 1)]
    # the DE journal's own whirl over all members (the paper's measuring node): its class counts and
    # the median frequency of the members whose DE journal whirls in the DE majority class
    de = [m for m in members if "de_direction" in m]
    if de:
        de_counts = Counter(m["de_direction"] for m in de)
        de_dir = _majority(de_counts)
        f_de = [m["de_frequency_hz"] for m in de if m["de_direction"] == de_dir and m.get("de_frequency_hz")]
        locks = frequency_locks(f_de) if de_dir != "none" else []
        out["de"] = {"counts": dict(de_counts), "direction": de_dir,
                     "frequency_hz": median(f_de) if f_de and de_dir != "none" else None,
                     "frequency_se_hz": _frequency_se(f_de, locks) if len(f_de) >= 2 and de_dir != "none" else None,
                     "frequency_locks": locks}
        # the shape is the landing whirl's, which is the DE's whenever the DE journal whirls
        de_forms = _forms([m for m in de if m["de_direction"] == de_dir != "none" and m.get("bearing", "DE") == "DE"],
                          "de_frequency_hz")
        if de_forms:
            out["de"]["forms"] = de_forms
    return out


def _forms(members: list[dict], key: str) -> dict:
    """The whirl shapes of ``members`` (their ``whirl_form``), most drops first, each with its drops,
    the median of their ``key`` frequency and its standard error (two drops or more)."""
    groups: dict[str, list[float]] = {}
    for m in members:
        if m.get("whirl_form") and m.get(key) is not None:
            groups.setdefault(m["whirl_form"], []).append(m[key])
    return {k: {"n": len(v), "frequency_hz": median(v), **({"frequency_se_hz": _median_se(v)} if len(v) >= 2 else {})}
            for k, v in sorted(groups.items(), key=lambda kv: -len(kv[1]))}


def _majority(counts: Counter) -> str:
    """The most frequent class; ties go to a whirl class, so a half-whirling ensemble is not
    called calm."""
    top = max(counts.values())
    classes = [c for c, k in counts.items() if k == top]
    return next((c for c in ("backward", "forward") if c in classes), classes[0])


#: two whirl frequencies of an ensemble belong to different locks (rotor modes the whirl locked
#: to) when no chain of drops closer than this joins them: drops of one lock agree within ~0.5 Hz
#: (the rig's 7000 rpm whirl: 63.7-63.8 Hz), different modes lie several Hz apart (10000 rpm:
#: 72.7-73.2 and 78.9-79.4 Hz in session 24's validate)
LOCK_GAP_HZ = 2.0


def frequency_locks(freqs, gap_hz: float = LOCK_GAP_HZ) -> list[tuple[float, int]]:
    """The whirl frequencies of an ensemble's drops grouped into locks: sorted, split wherever two
    neighbours differ by more than ``gap_hz``; each lock as (its median [Hz], its number of drops),
    most drops first. One lock: the ensemble's median describes it; several: the median of the
    drops follows the split between them, and the standard error of a median understates a jump."""
    fs = sorted(float(f) for f in freqs if f is not None)
    groups: list[list[float]] = []
    for f in fs:
        if groups and f - groups[-1][-1] <= gap_hz:
            groups[-1].append(f)
        else:
            groups.append([f])
    return sorted(((median(g), len(g)) for g in groups), key=lambda m: (-m[1], m[0]))


def _frequency_se(freqs, locks: list) -> float:
    """The standard error of the median whirl frequency: the large-sample rule, or, where the drops
    split between locked modes (``locks``, :func:`frequency_locks` of ``freqs``), the larger of it and
    the bootstrap's: the median then jumps with the split, which the rule (a smooth, single-peaked
    spread) understates."""
    se = _median_se(freqs)
    return max(se, bootstrap_median_se(freqs)) if len(locks) > 1 else se


def bootstrap_median_se(vals, resamples: int = 4000, seed: int = 0) -> float:
    """Standard error of the median of ``vals`` by the bootstrap (seeded, so a report repeats): the
    standard deviation of the medians of ``resamples`` resamples with replacement. For drops split
    between two whirl locks (5 at 72.7-73.2 Hz, 3 at 78.9-79.4 Hz) it gives 2.2 Hz, where the
    large-sample rule gives 1.5 and the median of 8 drops from such a population scatters by 2.2
    (tests/test_ensemble.py)."""
    import numpy as np

    x = np.asarray(list(vals), dtype=float)
    rng = np.random.default_rng(seed)
    meds = np.median(rng.choice(x, size=(resamples, len(x)), replace=True), axis=1)
    return float(np.std(meds, ddof=1))


def share_se(k: int, n: int) -> float:
    """Standard error of a share k / n of drops: binomial, sqrt(p (1 - p) / n), with p kept half a
    drop away from 0 and 1 (an ensemble of 8 / 8 is not certain: the same rule as validate's class
    checks, there in drops)."""
    p = min(max(k / n, 0.5 / n), 1 - 0.5 / n)
    return math.sqrt(p * (1 - p) / n)


def _median_se(vals) -> float:
    """Standard error of the median of ``vals``: 1.2533 s / sqrt(k), the large-sample rule."""
    return 1.2533 * stdev(vals) / math.sqrt(len(vals))
