"""The rotor's deflection along its span (postprocess.span_deflection), rebuilt from the
Craig-Bampton coordinates, against closed forms."""

from pathlib import Path

import numpy as np
import pytest

from rotorlanding.landing import build_spec
from rotorlanding.postprocess import span_deflection
from rotorlanding.scenario import load_scenario

ROOT = Path(__file__).resolve().parents[1]


FREE = ["rotor.supports.2.kyy=0.0", "rotor.supports.2.kzz=0.0"]  # the motor coupling laterally free


@pytest.fixture(scope="module")
def spec():
    """The rig's landing model with the motor coupling laterally free (the rig until session 40): no
    support in K, so the constraint modes hold the rotor's rigid-body motions."""
    return build_spec(load_scenario(ROOT / "scenarios" / "paper" / "forward_whirl_landing.toml", FREE))


@pytest.fixture(scope="module")
def landed_spec():
    """The rig's landing model as it is: the 1e5 N/m motor coupling in K (since session 40)."""
    return build_spec(load_scenario(ROOT / "scenarios" / "paper" / "forward_whirl_landing.toml"))


def _rigid(spec, a, b, c, d):
    """Reduced coordinates of a rigid-body motion y = a + b x, z = c + d x (fixed-interface modes 0)."""
    q = np.zeros(spec.n_lat)
    for s in spec.stations:
        x = spec.fe.nodes[spec.fe.station_nodes[s]]
        q[spec.cb.index(s, "y")], q[spec.cb.index(s, "z")] = a + b * x, c + d * x
    return q


def test_a_rigid_body_motion_is_rebuilt_exactly_at_every_node(spec):
    """The constraint modes of a free rotor hold its rigid-body motions (the landing model with no
    support in K: the coupling laterally free; with the rig's coupling see the next test): boundary values of a
    translation plus a tilt give that straight line at every node, including the stations off the
    reduction's boundary (AMBs, sensors, disks) and the largest one at the rotor's far end."""
    a, b, c, d = 1e-4, 3e-4, -2e-4, 1e-4
    r = span_deflection(spec, _rigid(spec, a, b, c, d))
    x = spec.fe.nodes
    for st, n in spec.fe.station_nodes.items():
        assert r["station_peak_m"][st] == pytest.approx(np.hypot(a + b * x[n], c + d * x[n]), rel=1e-9, abs=1e-15), st
    line = np.hypot(a + b * x, c + d * x)
    assert r["peak_m"] == pytest.approx(line.max(), rel=1e-9)
    assert r["peak_x_m"] == pytest.approx(x[int(np.argmax(line))])


def test_with_the_coupling_in_k_a_boundary_motion_rebuilds_its_static_shape(landed_spec, spec):
    """With the motor coupling in K (the rig since session 40) a constraint mode is the static shape
    of its boundary values, not a straight line: the rebuilt displacement loads no interior DOF
    (K u = 0 there, checked on the landing model's own full K), and the coupling's spring bends the
    overhang off the line that the free rotor keeps."""
    s = landed_spec
    a, b, c, d = 1e-4, 3e-4, -2e-4, 1e-4
    q = _rigid(s, a, b, c, d)
    u = s.cb.T @ q[:s.n_lat]
    boundary = {s.fe.dof(st, dof) for st in s.stations for dof in ("y", "z")}
    interior = [i for i in range(s.fe.ndof) if i not in boundary]
    f = s.fe.K @ u
    assert np.abs(f[interior]).max() < 1e-9 * np.abs(f[sorted(boundary)]).max()
    n = s.fe.station_nodes["coupling"]
    x = s.fe.nodes[n]
    line = np.hypot(a + b * x, c + d * x)
    bent = span_deflection(s, q)["station_peak_m"]["coupling"]
    free = span_deflection(spec, _rigid(spec, a, b, c, d))["station_peak_m"]["coupling"]
    assert free == pytest.approx(line, rel=1e-9)
    assert abs(bent - line) > 0.02 * line  # 3.7 % on the rig


def test_the_peak_is_over_time_and_a_bending_mode_moves_the_span_not_the_sleeves(spec):
    """Over several samples each station keeps its largest displacement; a fixed-interface mode
    (sleeves held) moves the span and leaves the boundary stations at exactly zero."""
    q0 = _rigid(spec, 1e-4, 0.0, 0.0, 0.0)
    q1 = _rigid(spec, 0.0, 0.0, -3e-4, 0.0)
    r = span_deflection(spec, np.vstack([q0, q1]))
    assert all(v == pytest.approx(3e-4, rel=1e-9) for v in r["station_peak_m"].values())
    qm = np.zeros(spec.n_lat)
    qm[len(spec.stations) * 2] = 1e-3  # the first fixed-interface mode
    rm = span_deflection(spec, qm)
    assert all(rm["station_peak_m"][s] == 0.0 for s in spec.stations)
    assert rm["peak_m"] > 0.0 and rm["peak_x_m"] not in [spec.fe.nodes[spec.fe.station_nodes[s]] for s in spec.stations]


def test_the_report_gives_each_case_s_median_excursion_per_station():
    """validate's span section: per case the median over the drops that carry ``rotor_deflection``
    (a calibration's members carry none and are left out), in mm, with the catcher clearance; a
    verdict only with the close-clearance check (tests/test_validate_clearance.py), shown when given."""
    from rotorlanding.validate import span_lines

    def member(de_amb, mid):
        return {"span_peak_m": {"DE_sleeve": 2.5e-4, "DE_AMB": de_amb, "speed_sensor": mid}, "span_max_m": mid}

    ens = {"forward_7000": {"members": [member(4e-4, 2.0e-3), member(5e-4, 2.4e-3), member(9e-4, 2.2e-3)]},
           "backward_whirl": {"members": [{"span_peak_m": None, "span_max_m": None}]}}
    centred = {"forward_7000": {"bearings": {"DE": {"clearance_m": 2e-4}, "NDE": {"clearance_m": 2e-4}}}}
    text = "\n".join(span_lines(ens, centred))
    assert "radial clearance 0.2 mm" in text
    assert "| forward_7000 | 3 | 0.25 | 0.5 | 2.2 | 2.2 |" in text
    assert "backward_whirl" not in text and "PASS" not in text and "FAIL" not in text
    assert span_lines({"x": {"members": [{"span_peak_m": None}]}}, {}) == []
    check = {"check": "the landed rotor stays inside the rig's close clearances", "rule": "r", "ours": "o",
             "margin": -1e-4, "se": 2e-5, "pass": False, "within_noise": False, "source": "s"}
    text = "\n".join(span_lines(ens, centred, check))
    assert "| the landed rotor stays inside the rig's close clearances | r | o | -0.1 (0.02) | FAIL | s |" in text
