"""Which of the bench's cases can diagnose's rule name from the records at all? (issue 20, session 45)

Reads the information probe's JSONs (``docs/studies/diagnose_information.py`` run with ``GATE=diagnose
ROWS=data``: the gate's members drawn as diagnose draws them, on the records' own rows) and a bench result
(``benchmarks/diagnose_bench.py`` csv of the same record count), and sets for every case what the records allow
beside what the tool did. No fitting here: the models compared are the model as the case gives it (the effect
missing or the parameter at its nominal value) and the true model (the case's own overrides), so the verdict does
not depend on how well diagnose's search finds the truth.

The rule applied is diagnose's naming rule in its two main parts (``diagnose_run.above_gate``, ``named_by``):
the gap the step starts from above that model's noise gate, and the true model's gap at least
``MIN_STEP_IMPROVEMENT`` (30 %) below it. For a pair, step one is the pair's larger share (the true model without
the other effect), step two the other effect on top of it, against the smaller of the two gates (as diagnose
judges its second step). Not modelled: diagnose's other routes past the gate (a feature noise cannot produce, a
whirl direction made right, a remainder inside the candidate's own gate), so a case it names by one of them is
reported as "named by another route". The gates are one draw of 4 members each (standard error about 1.1 times
the members' spread), so a ratio within 0.9-1.1 of its gate is a coin toss; such cases are flagged.

usage: python docs/studies/diagnose_ceiling.py [RECORDS] [BENCH_CSV or -] [_H or ""] [_read, _read_ownM, _read_scatter or _read_own4_scatter_dg] > docs/studies/diagnose_ceiling_R4.md
(outputs of session 45: diagnose_ceiling_R1.md, _R4.md against the bench's one-record and four-record runs of
session 44, _R8_H.md without a tool run; session 51: _R4_read_scatter.md and _R1_read_own4_scatter_dg.md, the probe as
diagnose compares by default, with a second verdict by the bench's own judge: 50 % down for an effect, what is left
inside the true model's gate for a parameter error)
"""
import csv
import json
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "benchmarks"))
import diagnose_bench as B  # noqa: E402
from rotorlanding.diagnose_run import MIN_STEP_IMPROVEMENT  # noqa: E402

PROBE = ROOT / "docs" / "studies" / "diagnose_information"
EDGE = 0.1  # |gap / gate - 1| below this: within about one standard error of a 4-member gate


def phys(d, key):
    return d[key]["phys"]["gap"], d[key]["phys"]["gate"]


def step(gap_from, gate, gap_to):
    """(passes, why) for one step of the rule: above the gate and the truth 30 % nearer."""
    ratio, shrink = gap_from / gate, 1.0 - gap_to / gap_from
    if ratio <= 1.0:
        why = f"inside its gate ({ratio:.2f})"
    elif shrink < 0:
        why = f"truth farther ({gap_to:.3f})"
    elif shrink < MIN_STEP_IMPROVEMENT:
        why = f"truth only {100 * shrink:.0f} % nearer"
    else:
        return True, f"above its gate ({ratio:.2f}), truth {100 * shrink:.0f} % nearer"
    edge = abs(ratio - 1.0) < EDGE
    return False, why + (" (at the gate's edge)" if edge else "")


def verdict(case, d):
    """(reachable, text) for one case from its probe JSON."""
    g0, gate0 = phys(d, "as_is")
    if case["kind"] == "clean":
        ok = g0 <= gate0
        return ok, f"gap {g0:.3f}, gate {gate0:.3f} ({g0 / gate0:.2f}): " + ("quiet" if ok else "a false alarm")
    gt, _ = phys(d, "truth")
    if case["kind"] != "pair":
        ok, why = step(g0, gate0, gt)
        return ok, f"as given {g0:.3f} / gate {gate0:.3f}, truth {gt:.3f}: {why}"
    a, b = case["truth"]
    ga, gate_a = phys(d, f"truth_without_{b}")  # only a present
    gb, gate_b = phys(d, f"truth_without_{a}")
    # step one takes the larger share: the one-effect model nearer the records
    first, (g1, gate1) = (a, (ga, gate_a)) if ga <= gb else (b, (gb, gate_b))
    second = b if first == a else a
    ok1, why1 = step(g0, gate0, g1)
    ok2, why2 = step(g1, min(gate0, gate1), gt)
    return ok1 and ok2, (f"step 1 {first}: {g0:.3f} -> {g1:.3f}, {why1}; step 2 {second}: {g1:.3f} -> {gt:.3f} "
                         f"against {min(gate0, gate1):.3f}, {why2}")


def judge_allows(case, d, ok):
    """(allowed, why not) by the bench's own judge (``diagnose_bench.judge``) as well as the rule, were the truth
    named with its exact values: an effect's case also needs the gap down 50 % (the truth's gap at most half the
    model's as given); a parameter error needs what is left inside the true model's own gate, or the report says
    "unexplained" rather than "parameter" (session 51: the naming rule alone counted neither)."""
    if not ok or case["kind"] == "clean":
        return ok, ""
    g0, _ = phys(d, "as_is")
    gt, gate_t = phys(d, "truth")
    if case["kind"] == "param":
        return (True, "") if gt <= gate_t else (False, f"truth's own gap {gt:.3f} above its gate {gate_t:.3f}")
    return (True, "") if gt <= 0.5 * g0 else (False, f"truth only {100 * (1 - gt / g0):.0f} % down, the judge asks 50")


def main(argv):
    records = int(argv[0]) if argv else 4
    bench = argv[1] if len(argv) > 1 else str(ROOT / "benchmarks" / "results" / "diagnose_bench_s44_rep4.csv")
    suffix = argv[2] if len(argv) > 2 else ""  # "_H": the probe's records with load cells (FORCE_KIND=housing)
    tail = argv[3] if len(argv) > 3 else ""  # "_read": the probe's OWN=read (the model as diagnose reads it, s46);
    # "_read_own16": with OWN_DROPS=16 as well (session 47); "_read_scatter": SCATTER=1 (session 51);
    # "_read_own4_scatter_dg": RECORDS=1 OWN_DROPS=4 SCATTER=1 GAP=diagnose, the default one-record diagnosis
    rows = {} if bench == "-" else {r["case"]: r for r in csv.DictReader(Path(bench).open())}
    cells = " with load cells (FORCES=20 FORCE_KIND=housing)" if suffix == "_H" else ""
    print(f"# What the bench's records allow diagnose's rule, {records} record{'s' if records > 1 else ''}{cells}"
          f" (`{Path(__file__).name}`)\n")
    print(f"Probe: `diagnose_information.py` with RECORDS={records}{cells} GATE=diagnose ROWS=data{' OWN=read (the model read as the records are, diagnose since session 46)' if tail.startswith('_read') else ''}{(' OWN_DROPS=' + tail.split('_own')[1].split('_')[0] + ' (the model from that many drops over the disc, not one draw of ' + str(records) + ')') if '_own' in tail else ''}{' SCATTER=1 (the scales widened by the drops scatter, diagnose since session 50)' if '_scatter' in tail else ''}{' GAP=diagnose (gap and gate by diagnose_run._Simulator.gap and _noise_gate themselves)' if '_dg' in tail else ''}{' JOURNALS=DE,NDE (both journals compared)' if tail.endswith('_nde') else ''}; tool: "
          + ("not run" if bench == "-" else f"`{Path(bench).name}`") + ".\n")
    print("| case | kind | records allow the rule | and the bench's judge | tool | what the records give |")
    print("|---|---|---|---|---|---|")
    counts = {"reachable": 0, "judged": 0, "tool right": 0, "tool right, not reachable": 0, "wrong fits better": 0,
              "missing": 0}
    by_kind = {}
    for case in B.cases():
        name = case["case"]
        path = PROBE / f"{name}_R{records}{suffix}_Dr{tail}.json"
        tool = rows.get(name)
        right = tool is not None and tool["right"] == "True"
        if not path.exists():
            counts["missing"] += 1
            print(f"| {name} | {case['kind']} | (no probe) | | {'-' if tool is None else ('yes' if right else 'NO')} | |")
            continue
        probe = json.loads(path.read_text())
        ok, text = verdict(case, probe)
        judged, why_not = judge_allows(case, probe, ok)
        counts["reachable"] += ok
        counts["judged"] += judged
        if why_not:
            text += f"; {why_not}"
        counts["tool right"] += right
        if right and not ok:
            counts["tool right, not reachable"] += 1
            text += " (named by another route)"
        truth_gap = probe.get("truth", {}).get("phys", {}).get("gap")
        if tool is not None and not right and tool["named"] not in ("", "-") and truth_gap is not None \
                and float(tool["gap_after"]) < truth_gap:
            # what diagnose named fits the records better than the truth does: no fit-based rule finds the truth
            counts["wrong fits better"] += 1
            text += f"; what the tool named fits better than the truth ({float(tool['gap_after']):.3f} < {truth_gap:.3f})"
        k = by_kind.setdefault(case["kind"], [0, 0, 0, 0])
        k[0] += ok
        k[1] += right
        k[2] += 1
        k[3] += judged
        said = "-" if tool is None else ("yes" if right else "NO") + " (" + (tool["named"] or "-") + ")"
        print(f"| {name} | {case['kind']} | {'yes' if ok else 'no'} | {'yes' if judged else 'no'} | {said} | {text} |")
    n = sum(v[2] for v in by_kind.values())
    tool_said = "" if not rows else (
        f"; the tool is right in {counts['tool right']} ({counts['tool right, not reachable']} of them by a route this"
        f" rule does not model); in {counts['wrong fits better']} of its misses what it named fits the records better"
        f" than the truth")
    print(f"\n- the records allow the rule {counts['reachable']} of {n}, the rule and the bench's judge together "
          f"{counts['judged']} of {n}{tool_said}")
    for kind, (ok, right, total, judged) in by_kind.items():
        print(f"- {kind}: records allow {ok}/{total} (with the judge {judged}/{total})"
              + (f", tool {right}/{total}" if rows else ""))
    if counts["missing"]:
        print(f"- {counts['missing']} cases without a probe JSON")


if __name__ == "__main__":
    main(sys.argv[1:])
