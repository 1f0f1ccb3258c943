"""Do the diagnose bench's records carry the effects it fails to name? (issue 20, session 19)

For each bench case given, the records are rebuilt as ``benchmarks/diagnose_bench.py --repeats R``
builds them (same seeds), and two models are scored against their mean features on the drop points
``diagnose`` uses: the model as the case gives it (the effect missing) and the true model (the
case's own overrides; for a pair also the true model without each of its two effects). Each model: R drops from the 5 um circle and 4 gate members of R drops with
the records' sensor noise. Two metrics: diagnose's fixed-scale gap, and a whitened one (every
feature's scale replaced by its own scatter over the model's 5R single drops times sqrt(2/R), the
noise of a difference of two means of R; never below FLOOR times the fixed scale). Printed: gap,
gate (mean + t(0.95) sqrt(1 + 1/k) s of the member gaps, at least their largest), their ratio and
the four largest whitened feature distances; one JSON per case in docs/studies/diagnose_information/

usage: RECORDS=4 [FORCES=N] python docs/studies/diagnose_information.py CASE[,CASE...]|all [FLOOR] > out.txt
FORCES=N (session 42) adds the four bearing force channels to every record, as the paper's rig had them
(force sensors at the bearings: its Fig. 33-34 plot DE and NDE forces), with white noise of N newtons
times the case's per-channel factor (0.5-2); the JSONs then end in _F.json. With FORCE_KIND=housing (session 43)
the four channels are the housing's (a load cell's reading, mechanisms.housing_force) and the JSONs end in _H.json.
With GATE=diagnose (session 44) the 4 gate members are drawn as diagnose draws them (_noise_gate): each the
mean of R drops from random points of the 5 um disc (the same seed), sampled at the records' logger rate with a
random phase; the model's own R drops stay on the circle. The JSONs then end in _D.json;
with ROWS=data as well (the members count only the records' features) in _Dr.json.
RECORDS=1 (session 45): the one record the bench writes with --repeats 1 (its seed, drop instant and detection as
diagnose_bench.run_case), against the centred drop, as diagnose compares one record.
OWN=read (session 46): the model as diagnose compares it since session 46 (each drop read through the records'
sensor model; needs GATE=diagnose); JSONs end in _read.json.
OWN_DROPS=M (session 47, with OWN=read and RECORDS > 1): the model's own features from M drops over the disc, not R,
so the as-is and true models' gaps are their expected values, not one draw of R chaotic drops (the gate's members
stay means of R drops, as the records are); JSONs end in _read_ownM.json.
SCATTER=1 (session 51, with OWN=read): each feature's scale widened by the model's own scatter over its drops, as
diagnose does by default whenever the model drops more than once (session 50); JSONs end in _scatter.json.
GAP=diagnose (session 51, with OWN=read): gap and gate computed by diagnose's own functions (``_Simulator.gap``,
``_noise_gate``), so the probe is diagnose's comparison by construction; with RECORDS=1 and OWN_DROPS=4 it is the
default one-record diagnosis (4 drops on the 5 um circle, the gate's members single drops between them); JSONs end
in _dg.json.
JOURNALS=DE,NDE (session 51): both journals' features compared, as diagnose --journals DE,NDE; JSONs end in _nde.json.
Output of session 19: docs/studies/diagnose_information/ (4 and 8 records); session 42: *_F.json.
"""
import sys, json, math, tempfile
from pathlib import Path
import numpy as np
ROOT = Path(__file__).resolve().parents[2]; sys.path.insert(0, str(ROOT / 'tests')); sys.path.insert(0, str(ROOT / 'benchmarks'))
import diagnose_bench as B
from sensor_model import C, THRUST, known_rig_model
from rotorlanding.diagnose_run import records_for_diagnosis, _Simulator, Point, _journal_rows, gate_bound
from rotorlanding.ensemble import random_drop_offset, drop_offsets, DROP_RADIUS_M
from rotorlanding.features import ensemble_features, gap_points, scale_of, WHIRL_SHARES
R = int(__import__("os").environ.get("RECORDS", "4"))
FORCE_NOISE_N = float(__import__("os").environ.get("FORCES", "0"))  # 0: no force channels (session 19's records)
# FORCE_KIND=housing (session 43): the channels a load cell between bearing and housing gives
# (mechanisms.housing_force) instead of the contact force on the rotor, which no rig sensor reads
HOUSING = __import__("os").environ.get("FORCE_KIND", "contact") == "housing"
FORCE_CHANNELS = (("DE_housing_force_y_n", "DE_housing_force_z_n", "NDE_housing_force_y_n", "NDE_housing_force_z_n")
                  if HOUSING else ("DE_force_y_n", "DE_force_z_n", "NDE_force_y_n", "NDE_force_z_n"))
# GATE=diagnose (session 44): diagnose's own members (random points of the disc, the logger's rate), not circles
DIAGNOSE_GATE = __import__("os").environ.get("GATE", "circle") == "diagnose"
# ROWS=data (session 44): a gate member counts only the features the records have (diagnose's members counted
# every feature the model has, the contact-force rows included, which no record carries)
DATA_ROWS = __import__("os").environ.get("ROWS", "model") == "data"
FLOOR = 0.1  # whitened scale never below this share of the fixed scale (main: the second argument)
OUT = ROOT / 'docs' / 'studies' / 'diagnose_information'


# OWN=disc (session 45): the model's own R drops spread over the disc the records fall from
# (ensemble.disc_drop_offsets, the layout diagnose's reads use since session 46), not on its rim
OWN_DISC = __import__("os").environ.get("OWN", "circle") == "disc"
# OWN_NOISE=1 (session 45): the model's own drops get the records' sensor noise and logger rate too, so a noisy
# extreme (a displacement's min / max, the first rebound) is biased alike in the records and the model
OWN_NOISE = __import__("os").environ.get("OWN_NOISE", "0") == "1"
# OWN=read (session 46): the model as diagnose now compares it (_Simulator's as_recorded: R drops over the disc,
# or the centred one for one record, each read 8 times through the records' sensor model and channels)
OWN_READ = __import__("os").environ.get("OWN", "circle") == "read"
if OWN_READ and not DIAGNOSE_GATE:
    raise SystemExit("diagnose_information.py: OWN=read needs GATE=diagnose (the records' logger rate for the reads)")
# OWN_DROPS=M (session 47): the model's own drops per variant (default R, as diagnose)
OWN_DROPS = int(__import__("os").environ.get("OWN_DROPS", "0")) or None
# JOURNALS=DE,NDE (session 51): the journals compared (diagnose's --journals; default DE, diagnose's default)
JOURNALS = tuple(__import__("os").environ.get("JOURNALS", "DE").split(","))
# GAP=diagnose (session 51): diagnose's own gap and gate functions
GAP_DIAGNOSE = __import__("os").environ.get("GAP", "probe") == "diagnose"
if GAP_DIAGNOSE and not OWN_READ:
    raise SystemExit("diagnose_information.py: GAP=diagnose needs OWN=read (diagnose's reads of the model)")
if OWN_DROPS and not (OWN_READ and (R > 1 or GAP_DIAGNOSE)):
    raise SystemExit("diagnose_information.py: OWN_DROPS needs OWN=read and RECORDS > 1 (drops over the records' disc), "
                     "or GAP=diagnose (with RECORDS=1: drops on the 5 um circle, as diagnose's one-record ensemble)")


# SCATTER=1 (session 51): the scales widened by the model's drop scatter (diagnose's default with R > 1)
SCATTER = __import__("os").environ.get("SCATTER", "0") == "1"
if SCATTER and not OWN_READ:
    raise SystemExit("diagnose_information.py: SCATTER=1 needs OWN=read (the scatter is the simulator's, as diagnose's)")


def own_offsets(n):
    from rotorlanding.ensemble import disc_drop_offsets
    return disc_drop_offsets(n) if OWN_DISC else drop_offsets(n)


def gate_of(gaps):
    # diagnose's own gate (gate_bound) without its 0.1 floor, which is in fixed-scale units
    return gate_bound(gaps, floor=0.0)

def whiten(feats, sig):
    out = {}
    for k, v in feats.items():
        if k in sig and isinstance(v, tuple) and v[1]:
            out[k] = (v[0], max(sig[k], FLOOR * v[1]))
        else:
            out[k] = v
    return out

def analyse_diagnose(sim, extra, noise):
    # diagnose's comparison itself: the gap of the model with ``extra`` and its noise gate (NOISE_MEMBERS members)
    from rotorlanding.diagnose_run import NOISE_MEMBERS, _noise_gate
    g, rows, sims, err = sim.gap(extra)
    if err:
        raise RuntimeError(err)
    ng = _noise_gate(sim, sims, NOISE_MEMBERS, noise, list(extra), journals=JOURNALS)
    top = sorted(((r['feature'], round(r['distance'], 2)) for r in rows), key=lambda x: -x[1])[:4]
    out = {'gap': g, 'gate': ng['gate'], 'members': ng['member_gaps'], 'top': top}
    return {'phys': out, 'white': out}


def analyse(sim, meas_mean, extra, noise):
    if GAP_DIAGNOSE:
        return analyse_diagnose(sim, extra, noise)
    # the model diagnose compares: R drops on the circle for R records, the centred drop for one record
    offs = own_offsets(R) if R > 1 else [[]]
    if OWN_READ:
        own, model_feats = [], sim.features([extra])[0][0]
    elif OWN_NOISE:
        # the model's own drops with the records' noise and logger as well (seeds 10000 + k: not a member's)
        from rotorlanding.diagnose_run import _sim_job
        p0 = sim.points[0]
        own = sim.pool.map(_sim_job, [(sim.scenario_path, sim.overrides(p0, extra + o), sim.clearance, noise,
                                       10000 + k) for k, o in enumerate(offs)], failures="raise")
    else:
        own = [o[0] for o in sim.features([extra + o for o in offs], single=True)]
    if DIAGNOSE_GATE:
        from rotorlanding.diagnose_run import MEMBER_SEED
        mrng = np.random.default_rng(MEMBER_SEED + 1000 * 4 + R)
        groups = [[random_drop_offset(mrng, DROP_RADIUS_M) for _ in range(R)] for _ in range(4)]
    else:
        groups = [drop_offsets(R, DROP_RADIUS_M, (g + 1) / (R + 1)) for g in range(4)]
    flat = sim.features([extra + o for grp in groups for o in grp], noise=noise, single=True)
    flat = [f[0] for f in flat]
    model = _journal_rows(model_feats if OWN_READ else ensemble_features(own), JOURNALS)
    members = [_journal_rows(ensemble_features(flat[g * R:(g + 1) * R]), JOURNALS) for g in range(4)]
    if DATA_ROWS:
        members = [{k: v for k, v in m.items() if k in meas_mean} for m in members]
    singles = [_journal_rows(f, JOURNALS) for f in own + flat]
    sig = {}
    for k in model:
        if k in ('whirl_direction', WHIRL_SHARES):
            continue
        vals = [s[k][0] for s in singles if k in s and isinstance(s[k][0], (int, float)) and s[k][0] is not None]
        if len(vals) >= 4:
            sig[k] = float(np.std(vals, ddof=1)) * math.sqrt(2.0 / R)
    out = {}
    for label, tf in (('phys', lambda f: f), ('white', lambda f: whiten(f, sig))):
        g, rows = gap_points([tf(meas_mean)], [tf(model)])
        mg = [gap_points([tf(m)], [tf(model)])[0] for m in members]
        out[label] = {'gap': g, 'gate': gate_of(mg), 'members': mg,
                      'top': sorted(((r['feature'], round(r['distance'], 2)) for r in rows), key=lambda x: -x[1])[:4]}
    out['sigma'] = {k: (v, scale_of(k, model[k][0] if model[k][0] is not None else 1.0, C) if k in model else None) for k, v in sig.items()}
    return out

def main(argv):
    global FLOOR
    allc = B.cases()
    known = [c['case'] for c in allc]
    if not argv:
        raise SystemExit("usage: RECORDS=4 python docs/studies/diagnose_information.py CASE[,CASE...]|all [FLOOR]")
    names = known if argv[0] == 'all' else argv[0].split(',')
    bad = [n for n in names if n not in known]
    if bad:
        raise SystemExit(f"diagnose_information.py: unknown case {bad[0]!r}; the bench's cases: {', '.join(known)}")
    if len(argv) > 1:
        FLOOR = float(argv[1])
    for name in names:
        i = [c['case'] for c in allc].index(name); case = allc[i]
        tmp = Path(tempfile.mkdtemp())
        model = known_rig_model(tmp / f"{case['case']}.toml", case['off'], extra=THRUST if case['thrust'] else '')
        sen = B.sensor(i, case)
        if FORCE_NOISE_N > 0:
            frng = np.random.default_rng(9000 + i)
            sen['channels'] = list(sen['channels']) + list(FORCE_CHANNELS)
            sen['noise_by_channel'] = {**sen['noise_by_channel'],
                                       **{ch: FORCE_NOISE_N * float(frng.uniform(0.5, 2.0)) for ch in FORCE_CHANNELS}}
        # the bench's own records (diagnose_bench.write_records: the same seeds), read as diagnose reads them
        recs = B.write_records(i, case, model, tmp, sen, R)
        if R == 1:
            from rotorlanding.diagnose_run import measured_for_diagnosis
            clearance, _, meas1, info = measured_for_diagnosis(model, recs[0], [], None)
        else:
            clearance, _, meas, info = records_for_diagnosis(model, recs, [])
        from rotorlanding.diagnose_run import records_sensor_model
        if DIAGNOSE_GATE:
            info['sensor_noise'] = records_sensor_model(info['sensor_noise'], info.get('sampling_rate_hz'))
        mm = _journal_rows(ensemble_features(meas.features) if R > 1 else meas1, JOURNALS)
        if OWN_READ:
            info['sensor_noise'] = records_sensor_model(info['sensor_noise'], None, info['channels'])
        sim = _Simulator(model, [Point('', [], mm)], clearance, 2, [], ensemble=OWN_DROPS or R, records=R,
                         as_recorded=info['sensor_noise'] if OWN_READ else None, scatter=SCATTER)
        try:
            res = {'case': name, 'as_is': analyse(sim, mm, [], info['sensor_noise'])}
            if case['kind'] != 'clean':
                res['truth'] = analyse(sim, mm, list(case['sets']), info['sensor_noise'])
            if case['kind'] == 'pair':
                # each effect's own share: the true model without it (what the second step must see)
                for eff in case['truth']:
                    res[f'truth_without_{eff}'] = analyse(sim, mm, [x for x in case['sets'] if x != f'effects.{eff}=true'],
                                                          info['sensor_noise'])
        finally:
            sim.close()
        for k in [k for k in res if k != 'case']:
            if k in res:
                a = res[k]
                print(name, k, 'phys gap %.3f gate %.3f ratio %.2f | white gap %.3f gate %.3f ratio %.2f' % (
                    a['phys']['gap'], a['phys']['gate'], a['phys']['gap'] / a['phys']['gate'],
                    a['white']['gap'], a['white']['gate'], a['white']['gap'] / a['white']['gate']), a['white']['top'], flush=True)
        OUT.mkdir(parents=True, exist_ok=True)
        (OUT / f'{name}_R{R}{("_H" if HOUSING else "_F") if FORCE_NOISE_N > 0 else ""}{"_D" if DIAGNOSE_GATE else ""}{"r" if DATA_ROWS else ""}{"_disc" if OWN_DISC else ""}{"_noisy" if OWN_NOISE else ""}{"_read" if OWN_READ else ""}{f"_own{OWN_DROPS}" if OWN_DROPS else ""}{"_scatter" if SCATTER else ""}{"_dg" if GAP_DIAGNOSE else ""}{"_nde" if "NDE" in JOURNALS else ""}.json').write_text(json.dumps(res, default=str, indent=1))

if __name__ == "__main__":
    main(sys.argv[1:])
