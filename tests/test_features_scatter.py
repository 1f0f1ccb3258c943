"""Features charged in units of the model's own scatter (``ensemble_features(..., scatter_factor)``,
session 48): a chaotic feature's difference of means counts against sqrt(scale^2 + f s^2), s the
drops' standard deviation, f = 1/R + 1/E for R records against the mean of E model drops. Checked
against the closed form, computed here independently; off (None) nothing changes."""
import math
import statistics

from rotorlanding.features import SCATTER, ensemble_features, gap, soft_cap

SCALE = 1e-5  # a first rebound's scale: 0.05 c of a 0.2 mm clearance


def _drop(rebound, direction="forward", freq=60.0):
    return {"whirl_direction": (direction, None), "DE_first_rebound_m": (rebound, SCALE),
            "whirl_frequency_hz": (freq, 2.0)}


def _row(rows, name):
    return next(r for r in rows if r["feature"] == name)


MODEL = [_drop(v, freq=f) for v, f in ((2.25e-4, 58.0), (2.02e-4, 61.0), (2.80e-4, 60.0), (2.93e-4, 63.0))]
RECORD = _drop(2.23e-4, freq=66.0)


def test_off_the_gap_is_the_fixed_scales_alone():
    model = ensemble_features(MODEL)
    assert SCATTER not in model
    _, rows = gap(RECORD, model)
    mean = statistics.mean(v["DE_first_rebound_m"][0] for v in MODEL)
    d = abs(2.23e-4 - mean) / SCALE
    assert math.isclose(_row(rows, "DE_first_rebound_m")["distance"], soft_cap(d))
    assert "scatter" not in _row(rows, "DE_first_rebound_m")


def test_one_record_against_four_drops_is_charged_in_the_drops_scatter():
    """R = 1, E = 4: f = 1.25; the rebound's drops scatter 42 um, so a 27 um difference of means
    (2.7 scales) is 0.56 of sqrt(scale^2 + 1.25 s^2)."""
    f = 1.0 + 1.0 / len(MODEL)
    model = ensemble_features(MODEL, scatter_factor=f)
    vals = [m["DE_first_rebound_m"][0] for m in MODEL]
    s = statistics.stdev(vals)
    assert math.isclose(model[SCATTER]["DE_first_rebound_m"], math.sqrt(f) * s)
    _, rows = gap(RECORD, model)
    row = _row(rows, "DE_first_rebound_m")
    expected = abs(2.23e-4 - statistics.mean(vals)) / math.sqrt(SCALE ** 2 + f * s * s)
    assert math.isclose(row["distance"], soft_cap(expected))
    assert expected < 0.7 < abs(2.23e-4 - statistics.mean(vals)) / SCALE / 3  # the scatter matters here
    # the whirl frequency of the members whirling the measured way: its scatter too
    fs = statistics.stdev(m["whirl_frequency_hz"][0] for m in MODEL)
    freq = _row(rows, "whirl_frequency_hz")
    expected_f = abs(66.0 - statistics.mean(m["whirl_frequency_hz"][0] for m in MODEL)) / math.hypot(2.0, math.sqrt(f) * fs)
    assert math.isclose(freq["distance"], soft_cap(expected_f))


def test_a_model_without_scatter_is_charged_as_before():
    """Identical drops: no scatter to add, the fixed scale alone (a calm landing keeps its power)."""
    same = [_drop(2.6e-4)] * 4
    on = gap(RECORD, ensemble_features(same, scatter_factor=1.25))
    off = gap(RECORD, ensemble_features(same))
    assert math.isclose(on[0], off[0])
    assert math.isclose(_row(on[1], "DE_first_rebound_m")["distance"], soft_cap(3.7))


def test_within_a_regime_the_regime_drops_scatter_counts():
    """Records calm, model 2 calm drops of 1 and 3 um and 2 whirling ones of 200 um: the calm
    regime's extremes are compared with the calm drops' mean and scatter (not the pooled one)."""
    calm = [{"whirl_direction": ("none", None), "DE_vertical_max_m": (v, 2e-5)} for v in (1e-6, 3e-6)]
    wild = [{"whirl_direction": ("forward", None), "DE_vertical_max_m": (2e-4, 2e-5)}] * 2
    records = ensemble_features([{"whirl_direction": ("none", None), "DE_vertical_max_m": (5e-5, 2e-5)}] * 4)
    f = 0.25 + 0.25
    model = ensemble_features(calm + wild, scatter_factor=f)
    _, rows = gap(records, model)
    s = statistics.stdev([1e-6, 3e-6])
    expected = abs(5e-5 - 2e-6) / math.sqrt(2e-5 ** 2 + f * s * s)
    assert math.isclose(_row(rows, "DE_vertical_max_m")["distance"], soft_cap(expected))


class _FakePool:
    """The pool of a :class:`_Simulator`: each job's 'landing' a linear function of its drop point."""

    def map(self, fn, jobs, failures="raise"):
        out = []
        for job in jobs:
            off = next(o for o in job[1] if o.startswith("amb.drop_offset_m"))
            y, z = (float(v) for v in off.split("=", 1)[1].strip("[]").split(","))
            out.append({"DE_vertical_min_m": (-2e-4 + 4.0 * z, 2e-5), "DE_horizontal_max_m": (1e-4 + 4.0 * y, 2e-5)})
        return out


def _fake_sim(records, ensemble, scatter):
    from rotorlanding.diagnose_run import Point, _Simulator

    sim = _Simulator.__new__(_Simulator)
    sim.scenario_path, sim.points, sim.clearance, sim.base = "model.toml", [Point("", [], {})], 2e-4, []
    sim.as_recorded, sim.realisations, sim.pool, sim.count, sim.memo = None, 1, _FakePool(), 0, {}
    sim.ensemble, sim.radius, sim.records, sim.scatter = ensemble, None, records, scatter
    return sim


def test_the_simulator_widens_by_one_over_records_plus_one_over_drops():
    """diagnose's model: E drops per variant against R records, f = 1/R + 1/E (one record, four
    drops: 1.25), computed here from the drops' own points; off, no scatter is attached."""
    from rotorlanding.ensemble import drop_offsets

    zs = [float(o[0].split("=", 1)[1].strip("[]").split(",")[1]) for o in drop_offsets(4)]
    s = statistics.stdev(-2e-4 + 4.0 * z for z in zs)
    for records, f in ((1, 1.25), (4, 0.5)):
        feats = _fake_sim(records, 4, True).features([[]])[0][0]
        assert math.isclose(feats[SCATTER]["DE_vertical_min_m"], math.sqrt(f) * s)
    assert SCATTER not in _fake_sim(1, 4, False).features([[]])[0][0]


def test_the_default_is_on_where_the_model_drops_more_than_once():
    """Session 50: ``scatter_scales`` None resolves by the drops per model variant (repeated records
    raise ``ensemble`` to their number first); an explicit choice is kept; the command line's
    default is None and ``--no-scatter-scales`` turns it off; a non-bool is one line."""
    import pytest

    from rotorlanding.cli import build_parser
    from rotorlanding.diagnose_run import _records_ensemble, run_diagnose, scatter_default
    from rotorlanding.errors import InputError

    assert scatter_default(None, 1) is False                        # one record, one drop
    assert scatter_default(None, 4) is True                         # --ensemble 4
    assert scatter_default(None, _records_ensemble(3, 1)) is True   # three records, ensemble left at 1
    assert scatter_default(False, 8) is False and scatter_default(True, 1) is True
    p = build_parser()
    base = ["diagnose", "--scenario", "m.toml", "--measured", "r.csv", "--out", "o"]
    assert p.parse_args(base).scatter_scales is None
    assert p.parse_args(base + ["--scatter-scales"]).scatter_scales is True
    assert p.parse_args(base + ["--no-scatter-scales"]).scatter_scales is False
    with pytest.raises(InputError) as e:
        run_diagnose("m.toml", "r.csv", "o", scatter_scales="yes", cli_names=False)
    assert e.value.field == "scatter_scales" and e.value.value == "yes"


def test_the_model_drops_four_times_against_one_record_by_default(tmp_path):
    """Session 51: ``ensemble`` None resolves by what was measured: 4 drops (``RECORD_DROPS``)
    against one time record, whether given as channels or as the features
    ``measured_for_diagnosis`` extracted from a CSV; 1 for a feature table (one landing's numbers
    per point, as the paper's tables were validated) and for repeated records, which
    ``_records_ensemble`` then raises to their number; an explicit number is kept; the command
    line's default is None."""
    import numpy as np

    from sensor_model import C, known_rig_model

    from rotorlanding.cli import build_parser
    from rotorlanding.diagnose_run import (RECORD_DROPS, Repeated, _records_ensemble, ensemble_default,
                                           measured_for_diagnosis)
    from rotorlanding.measured import Measurement

    t = np.arange(0.0, 0.6, 1e-4)
    z = -0.8 * C * np.clip((t - 0.1) / 0.01, 0.0, 1.0)   # falls onto the bearing 0.1 s into the record
    csv = tmp_path / "rig.csv"
    np.savetxt(csv, np.column_stack([t, 0.0 * t, z]), delimiter=",", header="time_s,DE_y_m,DE_z_m", comments="")
    model = known_rig_model(tmp_path / "model.toml")
    _, m, feats, info = measured_for_diagnosis(model, csv, [], None)
    assert RECORD_DROPS == 4
    assert ensemble_default(None, m) == 4 and ensemble_default(None, feats, info) == 4
    assert ensemble_default(None, feats, {}) == 1                  # the same numbers as a feature table
    assert ensemble_default(None, [feats]) == 1                     # operating points
    rep = Repeated([feats, feats, feats])
    assert ensemble_default(None, rep, info) == 1 and _records_ensemble(3, ensemble_default(None, rep, info)) == 3
    assert ensemble_default(1, m) == 1 and ensemble_default(8, feats, info) == 8
    assert isinstance(m, Measurement) and m.channels
    p = build_parser()
    assert p.parse_args(["diagnose", "--scenario", "m.toml", "--measured", "r.csv", "--out", "o"]).ensemble is None
