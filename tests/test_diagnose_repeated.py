"""Repeated landings in diagnose (issue 20, points 1 and 6): several records of one operating
point compared as their mean features with the model's ensemble of as many drops, and a noise
gate whose members are means of as many drops."""

import math
import sys
from pathlib import Path

import numpy as np
import pytest

from rotorlanding.cli import main
from rotorlanding.diagnose_run import MEMBER_SEED, Point, Repeated, _noise_gate, records_for_diagnosis, run_diagnose
from rotorlanding.ensemble import drop_offsets, random_drop_offset
from rotorlanding.errors import InputError
from rotorlanding.features import ensemble_features, gap

sys.path.insert(0, str(Path(__file__).parent))
from sensor_model import C, known_rig_model, write_record  # noqa: E402


def _offset(o: list[str]) -> tuple[float, float]:
    y, z = o[0].split("=", 1)[1].strip("[]").split(",")
    return float(y), float(z)


def test_drop_offsets_phase_turns_the_circle():
    base = [_offset(o) for o in drop_offsets(4, 5e-6)]
    half = [_offset(o) for o in drop_offsets(4, 5e-6, 0.5)]
    assert base[1] == pytest.approx((0.0, 5e-6), abs=1e-20)
    # half a spacing: 45, 135, ... degrees, on the same circle, none on the unturned points
    assert half[0] == pytest.approx((5e-6 / math.sqrt(2), 5e-6 / math.sqrt(2)), rel=1e-12)
    assert all(math.hypot(*p) == pytest.approx(5e-6, rel=1e-12) for p in half)
    assert min(math.dist(p, q) for p in half for q in base) > 3e-6


def test_repeated_needs_two_records_and_reports_their_spread():
    with pytest.raises(ValueError):
        Repeated([{"DE_vertical_min_m": (-2e-4, 2e-5)}])
    r = Repeated([{"DE_vertical_min_m": (-2e-4, 2e-5), "whirl_direction": ("none", None)},
                  {"DE_vertical_min_m": (-3e-4, 2e-5), "whirl_direction": ("none", None)},
                  {"DE_vertical_min_m": (-4e-4, 2e-5)}])
    assert r.spread["DE_vertical_min_m"] == pytest.approx(1e-4)   # sample standard deviation of -2, -3, -4
    assert "whirl_direction" not in r.spread


class _FakeSim:
    """A simulator whose drops are features that depend on the drop point only: records the
    offsets asked for, so the gate's member structure can be checked without a landing."""

    def __init__(self, records, ensemble):
        self.records, self.ensemble, self.radius = records, ensemble, None
        self.points = [Point("", [], {})]
        self.asked = []

    def features(self, extras, noise=None, single=False):
        assert single   # the gate's members are built from single drops
        out = []
        for extra in extras:
            y, z = _offset([e for e in extra if e.startswith("amb.drop_offset_m")])
            self.asked.append((y, z))
            out.append([{"DE_vertical_min_m": (-2e-4 + 4.0 * z, 2e-5), "DE_horizontal_max_m": (1e-4 + 4.0 * y, 2e-5)}])
        return out


def test_gate_members_are_means_of_as_many_drops_as_records():
    sim = _FakeSim(records=3, ensemble=3)
    model = [ensemble_features([{"DE_vertical_min_m": (-2e-4 + 4.0 * z, 2e-5), "DE_horizontal_max_m": (1e-4 + 4.0 * y, 2e-5)}
                                for y, z in map(_offset, drop_offsets(3))])]
    noise = _noise_gate(sim, model, 4, None)
    assert len(sim.asked) == 4 * 3 and "means of 3 drops" in noise["source"]
    # each drop from a random point of the 5 um disc, as a record is (not of its rim: the records'
    # points lie 3.3 um off centre on average, and the members dropped from the rim landed wilder)
    radii = [math.hypot(*p) for p in sim.asked]
    assert max(radii) <= 5e-6 * (1 + 1e-9) and min(radii) < 0.9 * 5e-6 and len(set(sim.asked)) == len(sim.asked)
    # the points are those the records' own draw gives with the gate's seed (a diagnosis repeats)
    rng = np.random.default_rng(MEMBER_SEED + 1000 * 4 + 3)
    assert sim.asked == [_offset(random_drop_offset(rng)) for _ in range(4 * 3)]
    # each member gap is the gap of the mean of its 3 drops (computed here independently)
    expect = []
    for g in range(4):
        drops = sim.asked[3 * g:3 * g + 3]
        mean = {"DE_vertical_min_m": (float(np.mean([-2e-4 + 4.0 * z for _, z in drops])), 2e-5),
                "DE_horizontal_max_m": (float(np.mean([1e-4 + 4.0 * y for y, _ in drops])), 2e-5)}
        expect.append(gap(mean, model[0])[0])
    assert noise["member_gaps"] == pytest.approx(expect, rel=1e-12)
    # one record against one drop: single drops, from random points of the disc too (a record
    # falls from some point of it), seeded as with repeated records
    sim1 = _FakeSim(records=1, ensemble=1)
    assert "4 drops from random points of a 5 um disc" in _noise_gate(sim1, model, 4, None)["source"]
    rng = np.random.default_rng(MEMBER_SEED + 1000 * 4 + 1)
    assert sim1.asked == [_offset(random_drop_offset(rng)) for _ in range(4)]
    assert min(math.hypot(*p) for p in sim1.asked) < 0.9 * 5e-6
    # one record against an ensemble model: single drops between its drop points on the circle
    sim2 = _FakeSim(records=1, ensemble=4)
    assert "4 drops from a 5 um circle" in _noise_gate(sim2, model, 4, None)["source"]
    assert all(math.hypot(*p) == pytest.approx(5e-6) for p in sim2.asked)


@pytest.fixture
def rig_without_windage(tmp_path):
    return known_rig_model(tmp_path / "model.toml", ["windage", "ball_drag"])


def _records(model, sets, tmp_path, n, seed):
    """``n`` records of the rig with ``sets``, each dropped from its own random point within 5 um."""
    rng = np.random.default_rng(seed)
    paths = []
    for k in range(n):
        paths.append(tmp_path / f"drop{k}.csv")
        write_record(model, list(sets) + random_drop_offset(rng), paths[-1],
                     clearance=C, seed=seed + k, fs_hz=5000.0, drop_at_s=float(rng.uniform(1.0, 5.0)))
    return paths


def test_repeated_records_name_a_weak_effect(rig_without_windage, tmp_path):
    """Weak windage (c_w2 3e-7, the bench's weak case): four repeated landings of the rig, each
    from its own point of the AMB's position error, against the model without windage. The gate
    of four-drop means is about half a single drop's, and windage is named with its value."""
    paths = _records(rig_without_windage, ["effects.windage=true", "spin.c_w2=3e-7"], tmp_path, 4, 11)
    clearance, first, meas, info = records_for_diagnosis(rig_without_windage, paths, [])
    assert isinstance(meas, Repeated) and len(meas.features) == 4 and first.channels
    assert set(info["sensor_noise"]) >= {"DE_y_m", "DE_z_m"} and 0.5e-6 < info["sensor_noise"]["DE_z_m"] < 2e-6
    res, files = run_diagnose(str(rig_without_windage), [str(p) for p in paths], tmp_path / "dg", maxiter=4,
                              parameters=[], candidates=["windage", "ball_drag"], workers=2, cli_names=False)
    assert res["records"] == 4 and res["ensemble"] == 4 and "means of 4 drops" in res["noise"]["source"]
    assert res["scatter_scales"] is True  # the default with repeated records (session 50)
    assert res["named_effects"] == ["windage"], (res["gap_before"], res["noise_gate"], res["steps"][0]["candidates"])
    assert res["gap_after"] <= 0.5 * res["gap_before"]
    c_w2 = float(res["calibrated_overrides"][-1].split("=")[1])
    assert 1.5e-7 < c_w2 < 6e-7
    assert "4 records" in (tmp_path / "dg" / "report.md").read_text()


def test_repeated_records_bad_input_one_line(rig_without_windage, tmp_path, capsys):
    paths = _records(rig_without_windage, [], tmp_path, 2, 3)
    table = tmp_path / "table.toml"
    table.write_text("[features]\nwhirl_direction = \"forward\"\nwhirl_frequency_hz = 65.0\n")
    with pytest.raises(InputError) as err:
        records_for_diagnosis(rig_without_windage, [paths[0], table], [])
    assert "table.toml" in str(err.value) and "repeated landings must be records" in str(err.value)
    code = main(["diagnose", "--scenario", str(rig_without_windage), "--measured", str(paths[0]), str(paths[1]),
                 "--time-offset-s", "0.2", "--out", str(tmp_path / "o")])
    line = capsys.readouterr().err.strip()
    assert code != 0 and "--time-offset-s" in line and "only with one record" in line and "\n" not in line
    # the same record twice would pass for two draws with no scatter (a gate too narrow)
    with pytest.raises(InputError) as err:
        records_for_diagnosis(rig_without_windage, [paths[0], paths[1], paths[0]], [])
    assert "given twice" in str(err.value) and "drop0.csv" in str(err.value)
    # a model of no drops is refused in one line (fewer drops than records: _records_ensemble, below)
    code = main(["diagnose", "--scenario", str(rig_without_windage), "--measured", str(paths[0]), str(paths[1]),
                 "--ensemble", "0", "--out", str(tmp_path / "o2")])
    line = capsys.readouterr().err.strip()
    assert code != 0 and "--ensemble" in line and "integer >= 1" in line and "\n" not in line


def test_naming_rule_own_gate_and_its_guards():
    """The step's naming rule on its own (diagnose_run.named_by / above_gate): the own-gate reason
    names a candidate only when what it leaves is inside its own gate and that gate is below the gap
    it started from; one record (no own gate) keeps the old rule."""
    from rotorlanding.diagnose_run import above_gate, named_by

    # considered at all: above the gate and 2 score units better; or a feature noise cannot produce
    assert above_gate(0.5, 0.3, [], -10.0, -7.9) and not above_gate(0.5, 0.3, [], -10.0, -8.1)
    assert not above_gate(0.2, 0.3, [], -10.0, -5.0)
    assert above_gate(0.2, 0.3, ["DE_race_spinup_s"], -10.0, -5.0)
    # the reasons, in order; nothing named when not above the gate whatever the improvement
    assert named_by(True, True, False, 0.3, None, 1.0, 0.2) == "relative improvement"
    assert named_by(True, False, True, 0.9, None, 1.0, 0.2) == "whirl direction"
    assert named_by(False, True, True, 0.1, 0.5, 1.0, 0.2) is None
    # bench case param_mu_rad_0.3 with 4 records: gap 1.59 -> 1.21 (24 %, not relative), its own gate 1.43
    assert named_by(True, False, False, 1.21, 1.43, 1.59, 0.16) == \
        "the remainder inside the candidate's own noise gate"
    # a wilder candidate: its own gate is not below the gap it started from, so its scatter
    # cannot be what explains that gap
    assert named_by(True, False, False, 1.21, 1.59, 1.59, 0.16) is None
    assert named_by(True, False, False, 1.21, 2.0, 1.59, 0.16) is None
    # what is left is outside the candidate's own noise
    assert named_by(True, False, False, 1.5, 1.43, 1.59, 0.16) is None
    # one record: no own gate, the old rule (relative or direction only)
    assert named_by(True, False, False, 1.21, None, 1.59, 0.16) is None
    # named below the gate only through a feature noise cannot produce, and the reason says so
    assert named_by(True, True, False, 0.05, None, 0.25, 0.3) == \
        "relative improvement, a feature noise cannot produce"


def test_repeated_records_take_a_model_of_as_many_drops_or_more():
    """With R records the model lands R drops per variant by default, or more when asked (its
    features nearer their expectation); fewer would be noisier than the data and are refused with
    the option, the value and what is allowed."""
    from rotorlanding.diagnose_run import _records_ensemble
    from rotorlanding.errors import InputError

    assert _records_ensemble(4, 1) == 4
    assert _records_ensemble(4, 4) == 4 and _records_ensemble(4, 16) == 16
    with pytest.raises(InputError) as e:
        _records_ensemble(4, 2, "--ensemble")
    assert e.value.field == "--ensemble" and e.value.value == 2 and "at least 4" in e.value.allowed
