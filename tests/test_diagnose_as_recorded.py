"""Issue 20, session 46: diagnose compares the model as the records are. Each model drop is read
through the records' sensor model (their noise, logger rate with a random phase, their channels)
several times, and with repeated records the model's drops spread over the disc the records fall
from, not on its rim. Data from our own sensor model (tests/sensor_model.py)."""

import math
import re
import sys
from pathlib import Path

import numpy as np
import pytest

from rotorlanding import diagnose_run as d
from rotorlanding.ensemble import DROP_RADIUS_M, disc_drop_offsets

sys.path.insert(0, str(Path(__file__).parent))
from sensor_model import C, known_rig_model  # noqa: E402


def _radii_angles(offsets):
    out = []
    for (o,) in offsets:
        y, z = (float(v) for v in re.findall(r"[-+0-9.e]+", o.split("=", 1)[1]))
        out.append((math.hypot(y, z), math.atan2(z, y)))
    return out


def test_disc_drops_cover_the_disc_as_uniform_random_points_do():
    """A uniform point of a disc of radius a has E[r^2] = a^2 / 2 and E[r] = 2a/3. The sunflower
    layout's r_k^2 = a^2 (k + 1/2) / n has that mean exactly, and its mean radius tends to 2a/3;
    every drop is inside the disc, no two at one point."""
    n = 16
    ra = _radii_angles(disc_drop_offsets(n))
    r = np.array([x for x, _ in ra])
    assert np.all(r < DROP_RADIUS_M)
    assert np.mean(r ** 2) == pytest.approx(0.5 * DROP_RADIUS_M ** 2, rel=1e-12)
    assert np.mean(r) == pytest.approx(2.0 / 3.0 * DROP_RADIUS_M, rel=0.01)
    pts = {(round(x, 12), round(a, 9)) for x, a in ra}
    assert len(pts) == n
    with pytest.raises(ValueError):
        disc_drop_offsets(0)


def test_reads_through_a_perfect_sensor_are_the_model_and_noisy_extremes_lie_beyond(tmp_path):
    """Read through a sensor without noise at the model's own samples, every read is the noise-free
    model, feature for feature. With noise, E[max(x + n)] >= max(x + E[n]) = max(x) (Jensen, max
    being convex) and likewise for the minimum: the mean of the reads' displacement extremes lies
    beyond the noise-free ones, the bias a noise-free model has against noisy records."""
    model = known_rig_model(tmp_path / "model.toml", ["windage"])
    clean = d._simulate_features(model, [], C)
    perfect = d._simulate_features(model, [], C, noise={"DE_y_m": 0.0}, seed=3, realisations=2)
    assert len(perfect) == 2 and all(p == clean for p in perfect)
    sigma = 5e-6
    noise = {"DE_y_m": sigma, "DE_z_m": sigma, d.RATE_KEY: 5000.0}
    reads = d._simulate_features(model, [], C, noise=noise, seed=3, realisations=8)
    assert len(reads) == 8 and len({repr(sorted(r.items())) for r in reads}) == 8   # own draws per read
    again = d._simulate_features(model, [], C, noise=noise, seed=3, realisations=8)
    assert again == reads                                                            # seeded: a diagnosis repeats
    keys = [k for k in clean if k.startswith("DE_") and k.endswith(("_max_m", "_min_m"))]
    assert keys, sorted(clean)
    for k in keys:
        mean_read = float(np.mean([r[k][0] for r in reads]))
        if k.endswith("_max_m"):
            assert mean_read > clean[k][0], k
        else:
            assert mean_read < clean[k][0], k


class _Recorder:
    """A pool that records its jobs and answers each with features that say which job it was."""

    def __init__(self):
        self.jobs = []

    def map(self, fn, jobs, failures="row"):
        jobs = list(jobs)
        self.jobs += jobs
        out = []
        for j in jobs:
            reads = j[5] if len(j) > 5 else 0
            # the variant's own value (its last "a=" override) in a feature of its own
            a = next((float(o.split("=")[1]) for o in reversed(j[1]) if o.startswith("a=")), 0.0)
            one = {"x_m": (float(j[4]), 1.0), "a_m": (a, 1.0)}
            out.append([{"x_m": (float(j[4]) + m, 1.0), "a_m": (a, 1.0)} for m in range(reads)] if reads else one)
        return out

    def close(self):
        pass


def test_the_models_drops_are_read_with_seeds_common_to_every_variant(tmp_path):
    """With the records' sensor model, the model's drop k is read with seed MODEL_READ_SEED + k in
    every variant (a parameter's change is not mixed with new noise draws), from the disc layout
    with repeated records, and its features are the mean over drops and reads. The noise gate's
    members (noise given, one drop each) keep their own seeds; without a sensor model the drops
    stay noise-free on the rim."""
    sensor = {"DE_y_m": 1e-6, d.RATE_KEY: 5000.0}
    sim = d._Simulator("m.toml", [d.Point("")], C, 1, [], ensemble=4, records=4, as_recorded=sensor, realisations=3)
    sim.pool = _Recorder()
    out = sim.features([["a=1"], ["a=2"]])
    model_jobs = sim.pool.jobs
    assert len(model_jobs) == 8
    for v in range(2):
        variant = model_jobs[4 * v:4 * v + 4]
        assert [j[4] for j in variant] == [d.MODEL_READ_SEED + k for k in range(4)]
        assert all(j[3] == sensor and j[5] == 3 for j in variant)
        assert [j[1][-1] for j in variant] == [o[0] for o in disc_drop_offsets(4)]
    # the mean of 4 drops x 3 reads: seeds 10000-10003 plus reads 0-2
    want = np.mean([d.MODEL_READ_SEED + k + m for k in range(4) for m in range(3)])
    assert out[0][0]["x_m"][0] == pytest.approx(want) and out[1][0]["x_m"][0] == pytest.approx(want)
    assert (out[0][0]["a_m"][0], out[1][0]["a_m"][0]) == (1.0, 2.0)    # each variant its own group
    # a variant asked for again (another batch, another position) is not landed again
    sim.pool.jobs = []
    again = sim.features([["a=2"]])
    assert sim.pool.jobs == [] and again[0] == out[1]
    sim.pool.jobs = []
    sim.features([["a=1"], ["a=1"]], noise=sensor, single=True)
    assert [(j[4], len(j)) for j in sim.pool.jobs] == [(0, 5), (1, 5)]
    plain = d._Simulator("m.toml", [d.Point("")], C, 1, [], ensemble=4, records=4)
    plain.pool = _Recorder()
    plain.features([["a=1"]])
    assert all(j[3] is None and len(j) == 5 for j in plain.pool.jobs)
    assert [j[1][-1] for j in plain.pool.jobs] != [o[0] for o in disc_drop_offsets(4)]


def test_the_report_says_how_the_model_was_read():
    sensor = {"DE_y_m": 1e-6, d.RATE_KEY: 5000.0, d.CHANNELS_KEY: ("DE_y_m",)}
    sim = d._Simulator("m.toml", [d.Point("")], C, 1, [], ensemble=4, records=4, as_recorded=sensor, realisations=8)
    assert sim.read_description() == ("4 drops spread over the 5 um disc, each read 8 times through the records' "
                                      "sensor model (their noise, their 5000 Hz logger with a random phase, their "
                                      "channels), the mean of the reads")
    assert d._Simulator("m.toml", [d.Point("")], C, 1, []).read_description() == "the centred drop, noise-free"


def test_a_failed_drop_stays_a_failed_variant_when_the_model_is_read():
    """One drop per variant (one record), read 3 times: the first variant's landing fails (its job gives the
    error row, not a list of reads), the second lands. The first stays a failed trial, the second is the mean of
    its reads."""
    class Failing(_Recorder):
        def map(self, fn, jobs, failures="row"):
            out = super().map(fn, jobs, failures)
            out[0] = {"__error__": "RuntimeError: no convergence"}
            return out

    sim = d._Simulator("m.toml", [d.Point("")], C, 1, [], as_recorded={"DE_y_m": 1e-6}, realisations=3)
    sim.pool = Failing()
    bad, good = sim.features([["a=1"], ["a=2"]])
    assert "__error__" in bad[0]
    assert good[0]["x_m"][0] == pytest.approx(d.MODEL_READ_SEED + 1.0)   # reads 0, 1, 2 of drop 0


def test_two_points_draw_their_reads_apart():
    """Two operating points, one drop each, read twice: the points' reads have seeds of their own (drop k of point
    j: MODEL_READ_SEED + 1000 j + k), so the noise left in the model's features is not alike at both."""
    sim = d._Simulator("m.toml", [d.Point("p0", ["s=1"]), d.Point("p1", ["s=2"])], C, 1, [],
                       as_recorded={"DE_y_m": 1e-6}, realisations=2)
    sim.pool = _Recorder()
    (p0, p1), = sim.features([["a=3"]])
    assert [j[4] for j in sim.pool.jobs] == [d.MODEL_READ_SEED, d.MODEL_READ_SEED + 1000]
    assert p0["a_m"][0] == p1["a_m"][0] == 3.0 and p1["x_m"][0] - p0["x_m"][0] == pytest.approx(1000.0)


def test_the_records_sensor_model_is_put_together_in_one_place():
    """diagnose, the gap scan and the studies build the records' sensor model with one function:
    the noise, the logger rate and the channels where known, a key already there kept, and no
    sensor model at all without noise (the model then compared noise-free)."""
    noise = {"DE_y_m": 1e-6, "rotor_speed_rpm": 2.0}
    full = d.records_sensor_model(noise, 4000, ["DE_y_m", "rotor_speed_rpm"])
    assert full == {**noise, d.RATE_KEY: 4000.0, d.CHANNELS_KEY: ("DE_y_m", "rotor_speed_rpm")}
    assert noise == {"DE_y_m": 1e-6, "rotor_speed_rpm": 2.0}                  # the input is not changed
    assert d.records_sensor_model(noise) == noise                             # rate and channels unknown
    assert d.records_sensor_model(full, 10000, ["DE_y_m"]) == full            # keys already there are kept
    assert d.records_sensor_model({}, 4000, ["DE_y_m"]) is None
    assert d.records_sensor_model(None, 4000) is None
