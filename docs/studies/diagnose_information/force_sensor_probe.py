"""Session 42: does contact damping reach a housing force sensor? The known rig of the diagnose bench (tests/sensor_model.py,
7000 rpm, 0.3 s, contact damping and ribbon cross-coupling off), 4 drops from the 5 um circle, noise-free: the peak
of the DE contact force on the rotor (the `DE_force_*_n` channels of a record, docs/measured_data.md) against the
peak of the ribbon force on the outer race (what a load cell under the bearing housing carries), with contact
damping off, k_visc 5e11 (the bench weak case) and 5e12 (strong). usage: python docs/studies/diagnose_information/force_sensor_probe.py
Output: force_sensor_probe.txt beside it."""
import sys, numpy as np, tempfile
from pathlib import Path
ROOT = Path(__file__).resolve().parents[3]; sys.path.insert(0, str(ROOT / 'tests'))
from sensor_model import known_rig_model
from rotorlanding.scenario import load_scenario
from rotorlanding.run import simulate
from rotorlanding.postprocess import evaluate
from rotorlanding.ensemble import drop_offsets
from rotorlanding.diagnose_run import reduction_cache, POST_NOT_NEEDED


def main() -> int:
    with tempfile.TemporaryDirectory() as d:
        return probe(known_rig_model(Path(d) / 'm.toml', ['contact_damping', 'ribbon_cross_coupling']))


def probe(model) -> int:
    for label, sets in (('off',[]),('kv5e11',['effects.contact_damping=true','contact.k_visc=5e11']),('kv5e12',['effects.contact_damping=true','contact.k_visc=5e12'])):
        for off in drop_offsets(4):
            sc=load_scenario(model, sets+list(off))
            spec,t,q,v,info=simulate(sc,progress=False,reduction=reduction_cache())
            s=evaluate(spec,t,q,v,skip=POST_NOT_NEEDED)
            fc=np.hypot(s['DE_contact_force_y_n'],s['DE_contact_force_z_n'])
            fr=np.hypot(s['DE_ribbon_force_y_n'],s['DE_ribbon_force_z_n'])
            fb=np.hypot(s['DE_ball_force_y_n'],s['DE_ball_force_z_n'])
            print(label, off, 'contact peak %.0f  ball peak %.0f  ribbon peak %.0f  ribbon zmin %.0f zmax %.0f  dt %.2e'%(fc.max(), fb.max(), fr.max(), s['DE_ribbon_force_z_n'].min(), s['DE_ribbon_force_z_n'].max(), np.median(np.diff(t))), flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
