"""Which diagnose candidates the given channels can tell apart (issue 20, point 8), said before
anything is calibrated.

Each candidate (an effect the model lacks, switched on at the top of its first parameter's
range, the strongest the catalogue allows; an uncertain parameter moved a quarter of its bound's
span either side of its value, the larger change kept) is landed at the operating point(s), and
its *signature* is the change it makes to the features the measurement has, against the model
as it is, in the gap's own units: per feature row the signed distance (model with the candidate
minus the model as it is, over the feature's scale, soft-capped as in
:func:`rotorlanding.features.gap_points`). Its size, the gap the candidate opens (the same RMS
as the gap), says whether the channels see it at all: below the noise gate, even that strength
is indistinguishable from noise.

Two candidates the data cannot tell apart are two whose signatures point the same way, as far
as the data's gap can show: a calibration scales each candidate's strength to fit the data, so
only the direction counts. If candidate A explained a gap of size G exactly, fitting B to the
same data would leave G sqrt(1 - c^2), with c the correlation of the two signatures (the cosine
of the angle between them, each feature row weighted as in the gap). When that remainder is
inside the noise gate, the data cannot choose between them. The correlation is signed for two
effects (an effect's strength is >= 0, so opposite signatures are told apart by their sign) and
taken by magnitude when a parameter is involved (a wrong value may be too high or too low).

These are statements about the model at one strength per candidate: a landing is far from linear
in its parameters (docs/measured_data.md), so a pair flagged here is a warning to read the
calibration's ranking with, not a verdict; the ranking itself is the calibration's.
"""

from __future__ import annotations

import math

from .features import WHIRL_SHARES, gap_points


#: pairs warned about one by one; more are summed up in one warning
MAX_PAIR_WARNINGS = 3


def _row_key(r: dict) -> str:
    key = (f"{r['point']}: " if r.get("point") else "") + r["feature"]
    if r["feature"] == "whirl_direction":
        return f"{key} -> {r.get('simulated')}"  # each new regime its own axis
    if r.get("absent_in"):
        return f"{key} (absent in {r['absent_in']})"
    return key


def signature(base: list[dict], candidate: list[dict], measured: list[dict],
              names: list[str] | None = None) -> tuple[float, dict]:
    """(gap the candidate opens against the model as it is, {feature row: signed distance x
    sqrt(weight)}) over the features the measurement has (``measured``: per point, the measured
    feature dicts; only their names are read)."""
    restricted = []
    for b, m in zip(base, measured):
        keep = {k: v for k, v in b.items() if k in m}
        if WHIRL_SHARES in b:
            keep[WHIRL_SHARES] = b[WHIRL_SHARES]
        restricted.append(keep)
    g, rows = gap_points(restricted, candidate, names or [""] * len(restricted))
    vec = {}
    for r in rows:
        vm, vs = r.get("measured"), r.get("simulated")
        sign = 1.0
        if r["feature"] != "whirl_direction" and not r.get("absent_in") and _number(vm) and _number(vs):
            sign = 1.0 if vs >= vm else -1.0
        vec[_row_key(r)] = sign * r["distance"] * math.sqrt(r.get("weight", 1.0))
    return g, vec


def _number(v) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)


def correlation(a: dict, b: dict) -> float:
    """Cosine of the angle between two signatures (0 when either is zero)."""
    na = math.sqrt(sum(v * v for v in a.values()))
    nb = math.sqrt(sum(v * v for v in b.values()))
    if na == 0.0 or nb == 0.0:
        return 0.0
    return sum(v * b.get(k, 0.0) for k, v in a.items()) / (na * nb)


def top_rows(vec: dict, n: int = 3) -> list[dict]:
    """The feature rows that carry a signature, largest first."""
    return [{"feature": k, "distance": round(v, 4)} for k, v in sorted(vec.items(), key=lambda kv: -abs(kv[1]))[:n]
            if v != 0.0]


def assess(probes: list[dict], gate: float, gap_before: float) -> dict:
    """The identifiability report from landed probes.

    ``probes``: dicts with ``name``, ``kind`` ("effect" or "parameter"), ``at`` (the values it was
    landed at), and either ``change`` (its gap against the model as it is) and ``signature`` (from
    :func:`signature`) or ``failed`` (why it could not be landed). ``gate``: the noise gate;
    ``gap_before``: the data's gap to the model as it is.

    Returns ``candidates`` (each with ``detectable``: change > gate) and ``pairs`` of detectable
    candidates, each with its correlation, the remainder ``gap_before sqrt(1 - c^2)`` and
    ``told_apart`` (remainder > gate), and ``warnings`` for the pairs that are not; with the gap
    inside the gate nothing needs telling apart, and ``pairs`` is empty (``note`` says so)."""
    cands = []
    for p in probes:
        c = {"name": p["name"], "kind": p["kind"], "at": p.get("at", {})}
        if p.get("failed"):
            c.update(detectable=None, failed=p["failed"])
        else:
            c.update(change=p["change"], detectable=bool(p["change"] > gate), features=top_rows(p["signature"]))
        cands.append(c)
    out = {"gate": gate, "gap_before": gap_before, "candidates": cands, "pairs": [], "warnings": []}
    if not math.isfinite(gap_before):
        out["note"] = "the data and the model share no feature to compare: nothing can be told apart"
        return out
    if not gap_before > gate:
        out["note"] = (f"the data's gap {gap_before:.3g} is inside the noise gate {gate:.3g}: there is nothing "
                       "for the candidates to explain, so none needs telling apart")
        return out
    # a pair is told apart when sqrt(1 - c^2) > gate / gap_before: the nearer the gap to the gate,
    # the less alike two signatures may be
    out["correlation_limit"] = math.sqrt(1.0 - (gate / gap_before) ** 2)
    seen = [p for p in probes if not p.get("failed") and p["change"] > gate]
    for i, a in enumerate(seen):
        for b in seen[i + 1:]:
            c = correlation(a["signature"], b["signature"])
            c_eff = abs(c) if "parameter" in (a["kind"], b["kind"]) else max(c, 0.0)
            remainder = gap_before * math.sqrt(max(0.0, 1.0 - c_eff * c_eff))
            out["pairs"].append({"a": a["name"], "b": b["name"], "correlation": c, "remainder": remainder,
                                 "told_apart": bool(remainder > gate)})
    out["pairs"].sort(key=lambda r: -abs(r["correlation"]))
    alike = [q for q in out["pairs"] if not q["told_apart"]]
    if len(alike) <= MAX_PAIR_WARNINGS:
        out["warnings"] = [
            f"{q['a']} and {q['b']} cannot be told apart with the channels given: their signatures correlate "
            f"{q['correlation']:+.2f}, so either fitted to the data leaves at most {q['remainder']:.3g} of the gap "
            f"{gap_before:.3g} for the other to explain, inside the noise gate {gate:.3g}" for q in alike]
    else:
        # one line, not a flood: with the gap just above the gate almost every pair is alike
        out["warnings"] = [
            f"{len(alike)} of {len(out['pairs'])} pairs of candidates cannot be told apart with the channels given: "
            f"the data's gap {gap_before:.3g} is only {gap_before / gate:.2f} x the noise gate {gate:.3g}, so only "
            f"signatures correlating below {out['correlation_limit']:.2f} can be; most alike: "
            + ", ".join(f"{q['a']} / {q['b']} ({q['correlation']:+.2f})" for q in alike[:MAX_PAIR_WARNINGS])]
    return out


def alike_with(ident: dict | None, name: str) -> list[dict]:
    """The candidates found alike ``name`` before calibrating (pairs not told apart), most alike first."""
    out = []
    for q in (ident or {}).get("pairs", []):
        if not q["told_apart"] and name in (q["a"], q["b"]):
            out.append({"other": q["b"] if q["a"] == name else q["a"], "correlation": q["correlation"]})
    return out
