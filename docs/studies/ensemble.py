"""Session-10 study tool: one landing as N drops from the 5 um circle, with --set overrides.

usage (from the repository root): OVL=scenarios/rig_rotor_candidate.toml (optional rig overlay)
    python docs/studies/ensemble.py SCENARIO N [--t-end T] [--tag TAG] [--workers 2] key=value ...
Prints every drop (class, bearing, DE and NDE class, frequency, onset, DE displacement and force
ranges) and the ensemble statistics (rotorlanding.ensemble); writes study_out/TAG.json.
Used for docs/calibration.md session 10 and docs/rotor_study_session10.md."""
import sys, json, time, os
os.environ.setdefault("OMP_NUM_THREADS", "1"); os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

def run(args):
    scen, sets, out = args
    from rotorlanding.run import run_scenario
    from rotorlanding.scenario import load_scenario
    from rotorlanding.ensemble import member_result
    sc = load_scenario(scen, sets, overlays=[os.environ["OVL"]] if os.environ.get("OVL") else ())
    s = run_scenario(sc, Path(out), progress=False, plots=False)
    m = member_result(s)
    m["wall"] = s.get("performance", {}).get("wall_s")
    m["nde_dir"] = (s["whirl"].get("per_bearing") or {}).get("NDE", {}).get("direction")
    return m

if __name__ == "__main__":
    a = sys.argv[1:]
    scen, n = a[0], int(a[1]); a = a[2:]
    t_end = None; tag = "x"; workers = 2
    if "--t-end" in a:
        i = a.index("--t-end"); t_end = a[i+1]; del a[i:i+2]
    if "--tag" in a:
        i = a.index("--tag"); tag = a[i+1]; del a[i:i+2]
    if "--workers" in a:
        i = a.index("--workers"); workers = int(a[i+1]); del a[i:i+2]
    from rotorlanding.ensemble import drop_offsets, ensemble_stats
    sets = list(a) + ([f"operating.t_end={t_end}"] if t_end else [])
    jobs = [(scen, sets + extra, f"study_out/{tag}/d{k}") for k, extra in enumerate(drop_offsets(n))]
    t0 = time.time()
    with ProcessPoolExecutor(workers) as ex:
        ms = list(ex.map(run, jobs))
    st = ensemble_stats(ms)
    print(f"== {tag}: {scen} {a} n={n} wall {time.time()-t0:.0f}s")
    for k, m in enumerate(ms):
        fr = m['frequency_hz']; dr = m['v_disp_range_m']; fo = m['v_force_range_n']
        print(f"  d{k}: {m['direction']:8s} at {m['bearing']}  DE {m['de_direction']:8s} NDE {m['nde_dir']}  f={fr if fr is None else round(fr,1)}  onset={m['onset_s']}  disp=[{dr[0]*1e3:.3f},{dr[1]*1e3:.3f}]mm  F=[{fo[0]/1e3:.2f},{fo[1]/1e3:.2f}]kN  wall={m['wall']:.1f}")
    print("  counts", st["counts"], "DE", st.get("de"), "f", st["frequency_hz"],
          "disp", [round(x*1e3,3) for x in st.get("v_disp_range_m",[0,0])], "F", [round(x/1e3,2) for x in st.get("v_force_range_n",[0,0])])
    Path(f"study_out/{tag}.json").write_text(json.dumps({"members": ms, "stats": st}, default=float, indent=1))
