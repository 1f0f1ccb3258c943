"""Rotors from ROSS: files written by ROSS 2.3's ``Rotor.save`` (tests/fixtures/ross/, made by
make_fixtures.py in a venv with ROSS) converted without ROSS give ROSS's own natural frequencies
(ross_frequencies.json, computed by ROSS); what cannot be converted stops with one line."""

import copy
import json
import math
import subprocess
import sys
import tomllib
from pathlib import Path

import numpy as np
import pytest

import rotorlanding as rl
from rotorlanding.cli import main
from rotorlanding.from_ross import is_ross_layout, rotor_table

FIX = Path(__file__).resolve().parent / "fixtures" / "ross"
REF = json.loads((FIX / "ross_frequencies.json").read_text())
#: measured (the last make_fixtures.py run): 1.9e-12 (rotor_example), 4.3e-13 (compressor_like,
#: conical and hollow elements), 1.6e-12 (disks_bearings), 3.8e-12 (frequency-dependent bearings at
#: each speed), 1.0e-11 (ROSS's compressor_example, coaxial layers with E = 6.9 kPa beside steel),
#: 2.8e-11 (the AMB rotor's elastic modes): the formulations agree, so the bound is rounding (ROSS's
#: own eigenvalues move by ~3e-12 between runs)
RTOL = 1e-9


def _data(name):
    return tomllib.loads((FIX / name).read_text())


@pytest.mark.parametrize("name", sorted(REF["rotors"]))
def test_converted_rotor_has_ross_frequencies(name):
    ref = REF["rotors"][name]
    rotor = rl.Rotor.from_ross(FIX / ref["file"])
    theirs = np.array(ref["frequencies_hz"])
    ours = rotor.modes(REF["speeds_rpm"], n_modes=theirs.shape[1]).frequencies_hz
    rel = np.abs(ours - theirs) / theirs
    print(f"{name}: largest relative difference to ROSS {rel.max():.2e}")
    assert rel.max() < RTOL, rel


def test_compressor_fixture_covers_conical_and_hollow_sections():
    sections = rl.Rotor.from_ross(FIX / "compressor_like.toml").model.sections
    tapered = [s for s in sections if s.tapered]
    assert len(tapered) == 3
    assert any(s.inner_diameter > 0 and s.inner_diameter_right == 0.0 for s in tapered)  # hollow to solid
    assert sum(s.inner_diameter > 0 and not s.tapered for s in sections) == 4


def test_tapered_section_mass_is_the_frustum_and_equal_ends_are_uniform():
    # independent closed forms: frustum volume pi L / 12 (D^2 + D d + d^2) per diameter, and a
    # "tapered" section whose ends are equal is the uniform section
    steel = {"youngs_modulus": 2.1e11, "poisson_ratio": 0.3, "density": 7850.0}
    cone = rl.Rotor(materials={"s": steel}, sections=[{"length": 0.4, "outer_diameter": 0.1, "outer_diameter_right": 0.06,
                                                        "inner_diameter": 0.02, "inner_diameter_right": 0.03,
                                                        "material": "s", "elements": 5}])
    vol = math.pi * 0.4 / 12 * ((0.1**2 + 0.1 * 0.06 + 0.06**2) - (0.02**2 + 0.02 * 0.03 + 0.03**2))
    assert cone.mass == pytest.approx(7850.0 * vol, rel=1e-14)
    assert cone.fe().mass == pytest.approx(7850.0 * vol, rel=1e-14)
    assert np.trace(cone.fe().M[0::4, 0::4]) > 0
    flat = dict(length=0.4, outer_diameter=0.08, inner_diameter=0.02, material="s", elements=4)
    uni = rl.Rotor(materials={"s": steel}, sections=[flat]).fe()
    same = rl.Rotor(materials={"s": steel}, sections=[dict(flat, outer_diameter_right=0.08)]).fe()
    for a, b in ((uni.M, same.M), (uni.K, same.K), (uni.G, same.G)):
        np.testing.assert_allclose(b, a, rtol=1e-12, atol=1e-12 * np.abs(a).max())


def test_to_toml_round_trip_keeps_the_conical_sections(tmp_path):
    rotor = rl.Rotor.from_ross(FIX / "compressor_like.toml", catcher_nodes={"NDE_catcher": 0, "DE_catcher": 10})
    back = rl.Rotor.from_toml(rotor.to_toml(tmp_path / "rotor.toml"))
    a, b = rotor.fe(), back.fe()
    assert np.array_equal(a.M, b.M) and np.array_equal(a.K, b.K) and np.array_equal(a.G, b.G)
    assert back.model.reduction.boundary_stations == ("NDE_catcher", "DE_catcher")
    assert back.model.stations["DE_catcher"] == pytest.approx(sum(s.length for s in rotor.model.sections[:10]))


def test_catcher_positions_between_nodes_split_an_element():
    base = rl.Rotor.from_ross(FIX / "rotor_example.toml")
    rotor = rl.Rotor.from_ross(FIX / "rotor_example.toml", catchers={"NDE": 0.1, "DE": 1.4}, reduction_modes=6)
    assert len(rotor.fe().nodes) == len(base.fe().nodes) + 2
    assert rotor.model.reduction.modes == 6
    # a finer mesh of the same rotor: the first mode moves by the discretisation error only
    assert rotor.modes([0.0], n_modes=1).frequencies_hz[0, 0] == pytest.approx(
        base.modes([0.0], n_modes=1).frequencies_hz[0, 0], rel=1e-5)


def test_cli_modes_reads_a_ross_file(capsys):
    ref = REF["rotors"]["disks_bearings"]
    assert main(["modes", str(FIX / ref["file"]), "--speeds-rpm", "5000", "--json", "--n-modes", "6"]) == 0
    out = json.loads(capsys.readouterr().out)
    f = np.array([m["frequency_hz"] for m in out["modes"][0]])
    np.testing.assert_allclose(f, ref["frequencies_hz"][1][:6], rtol=RTOL)


def test_unsupported_elements_give_one_line():
    with pytest.raises(rl.InputError) as err:
        rl.Rotor.from_ross(FIX / "unsupported.toml")
    text = str(err.value)
    assert "\n" not in text and "unsupported.toml" in text
    assert "SealElement" in text and "fluid film" in text
    proc = subprocess.run([sys.executable, "-m", "rotorlanding.cli", "modes", str(FIX / "unsupported.toml")],
                          capture_output=True, text=True)
    assert proc.returncode == 2 and "Traceback" not in proc.stderr
    assert len(proc.stderr.strip().splitlines()) == 1 and "seal" in proc.stderr


def test_frequency_dependent_bearing_is_named():
    data = _data("unsupported.toml")
    with pytest.raises(rl.InputError, match=r"fluid film\.kxx.*frequency-dependent"):
        rotor_table(data, ignore=["SealElement"])


def test_ignore_leaves_elements_out_on_purpose():
    rotor = rl.Rotor.from_ross(FIX / "unsupported.toml", ignore=["SealElement", "fluid film"])
    assert [s.station for s in rotor.model.supports] == ["Bearing_0"]


def _edit(fn):
    data = _data("rotor_example.toml")
    fn(data)
    return data


def _first(data, cls):
    return next(v for k, v in data.items() if k.startswith(cls + "_"))


CASES = {
    "no shear": (lambda d: _first(d, "ShaftElement").update(shear_effects=False), "shear_effects"),
    "axial force": (lambda d: _first(d, "ShaftElement").update(axial_force=1e4), "axial_force"),
    "hutchinson": (lambda d: _first(d, "ShaftElement").update(shear_method_calc="hutchinson"), "cowper"),
    "coaxial layer of another length": (
        lambda d: d.update({"ShaftElement_sleeve": dict(copy.deepcopy(_first(d, "ShaftElement")), L=0.2, idl=0.05,
                                                        odl=0.08, idr=0.05, odr=0.08, tag="sleeve")}),
        "coaxial layer"),
    "gap": (lambda d: _first(d, "ShaftElement").update(n=9), "gap"),
    "linked bearing": (lambda d: _first(d, "BearingElement").update(n_link=7), "linked"),
    "bearing mass": (lambda d: _first(d, "BearingElement").update(mxx=[3.0]), "mass coefficients"),
    "magnetic bearing": (lambda d: d.update({"MagneticBearingElement_AMB": {"n": 3, "g0": 1e-3, "tag": "AMB"}}),
                         "active magnetic bearing"),
    "gear": (lambda d: d.update({"GearElement_g": {"n": 2, "tag": "g"}}), "gear"),
    "unknown": (lambda d: d.update({"FancyElement_x": {"n": 2}}), "FancyElement"),
    "point mass mx != my": (lambda d: d.update({"PointMass_p": {"n": 2, "mx": 1.0, "my": 2.0}}), "mx != my"),
    "material by name": (lambda d: _first(d, "ShaftElement").update(material="Steel"), "available_materials"),
    "damping differs": (lambda d: _first(d, "ShaftElement").update(alpha=1.0), "Rayleigh"),
    "not on the shaft": (lambda d: _first(d, "DiskElement").update(n=40), "shaft node"),
}


@pytest.mark.parametrize("case", sorted(CASES))
def test_what_cannot_be_converted_is_named(case):
    edit, words = CASES[case]
    with pytest.raises(rl.InputError) as err:
        rotor_table(_edit(edit), source="rotor.toml")
    assert words in str(err.value) and "\n" not in str(err.value) and str(err.value).startswith("rotor.toml: ")


def test_point_mass_on_the_shaft_is_a_disk_without_inertia():
    data = _edit(lambda d: d.update({"PointMass_p": {"n": 3, "mx": 2.5, "my": 2.5, "tag": "p"}}))
    base, rotor = rl.Rotor.from_ross(FIX / "rotor_example.toml"), rl.Rotor.from_table(rotor_table(data))
    assert rotor.mass == pytest.approx(base.mass + 2.5, rel=1e-14)


def test_json_and_ross_1x_layouts_read_alike(tmp_path):
    data = _data("rotor_example.toml")
    js = tmp_path / "rotor.json"
    js.write_text(json.dumps(data))
    ref = rl.Rotor.from_ross(FIX / "rotor_example.toml").fe()
    assert np.array_equal(rl.Rotor.from_ross(js).fe().K, ref.K)
    # ROSS 1.x: no ross_version, 6-DoF class names, scalar coefficients, max_w [rad/s] in [parameters]
    old = {"parameters": {"max_w": 500.0}}
    for key, el in data.items():
        if not isinstance(el, dict) or key == "parameters":
            continue
        cls, tag = key.split("_", 1)
        el = {k: (v[0] if isinstance(v, list) else v) for k, v in el.items() if k not in ("alpha", "beta", "kzz", "czz")}
        old[f"{cls}6DoF_{tag}" if cls == "ShaftElement" else key] = el
    assert is_ross_layout(old)
    table = rotor_table(old)
    assert table["max_speed_rpm"] == pytest.approx(500.0 * 30 / math.pi)
    fe = rl.Rotor.from_table(table).fe()
    assert np.array_equal(fe.M, ref.M) and np.array_equal(fe.K, ref.K)


def test_live_ross_rotor_converts():
    rs = pytest.importorskip("ross")
    rotor = rs.rotor_example()
    ours = rl.Rotor.from_ross(rotor, catcher_nodes={"NDE": 0, "DE": 6}).modes([3000.0], n_modes=8).frequencies_hz[0]
    modal = rotor.run_modal(3000.0 * math.pi / 30, num_modes=4 * rotor.ndof, sparse=False)
    nd = rotor.number_dof
    lateral = []
    for i, wd in enumerate(modal.wd):
        v = np.abs(modal.evectors[:rotor.ndof, i]) ** 2
        if wd > 0 and sum(v[j::nd].sum() for j in (0, 1, 3, 4)) > 0.99 * v.sum():
            lateral.append(wd / (2 * math.pi))
    np.testing.assert_allclose(ours, sorted(lateral)[:8], rtol=RTOL)


def test_from_toml_reads_a_ross_file_and_names_a_file_that_is_neither(tmp_path):
    a = rl.Rotor.from_toml(FIX / "rotor_example.toml").fe()
    assert np.array_equal(a.K, rl.Rotor.from_ross(FIX / "rotor_example.toml").fe().K)
    other = tmp_path / "other.toml"
    other.write_text("[parameters]\nx = 1\n")
    with pytest.raises(rl.InputError, match=r"other\.toml: rotor = None: missing required table \[rotor\] \(nor"):
        rl.Rotor.from_toml(other)


@pytest.mark.parametrize("name", ["frequency_dependent", "compressor_example"])
def test_frequency_dependent_bearings_frozen_at_each_speed_match_ross(name):
    # ROSS's run_modal takes frequency-dependent coefficients at the spin frequency (a smoothing
    # spline over 5 or 8 points, linear over 2): converted at each speed, the frequencies agree there.
    # compressor_example is ROSS's own (its seals left out when the fixture was made): 55 elements,
    # coaxial layers on 36 (impeller hubs as a massive, nearly stiffness-free material), 7 disks
    ref = REF[name]
    worst = 0.0
    for speed, theirs in zip(REF["speeds_rpm"], ref["frequencies_hz"]):
        rotor = rl.Rotor.from_ross(FIX / ref["file"], bearings_at_rpm=speed)
        ours = rotor.modes([speed], n_modes=len(theirs)).frequencies_hz[0]
        worst = max(worst, float(np.max(np.abs(ours - theirs) / np.array(theirs))))
    print(f"{name}: largest relative difference to ROSS {worst:.2e}")
    assert worst < RTOL
    assert (sum(bool(s.layers) for s in rotor.model.sections) == 36) == (name == "compressor_example")
    with pytest.raises(rl.InputError, match="bearings_at_rpm=SPEED"):
        rl.Rotor.from_ross(FIX / ref["file"])


def test_coaxial_layers_add_their_mass_and_survive_to_toml(tmp_path):
    steel = {"youngs_modulus": 2.1e11, "poisson_ratio": 0.3, "density": 7850.0}
    soft = {"youngs_modulus": 1e4, "shear_modulus": 1e4, "density": 7800.0}
    sec = {"length": 0.5, "outer_diameter": 0.05, "material": "steel", "elements": 3,
           "layers": [{"outer_diameter": 0.12, "inner_diameter": 0.05, "material": "hub"}]}
    rotor = rl.Rotor(materials={"steel": steel, "hub": soft}, sections=[sec])
    plain = rl.Rotor(materials={"steel": steel}, sections=[{k: v for k, v in sec.items() if k != "layers"}])
    hub_mass = 7800.0 * math.pi / 4 * (0.12**2 - 0.05**2) * 0.5
    assert rotor.mass == pytest.approx(plain.mass + hub_mass, rel=1e-14)
    assert rotor.fe().mass == pytest.approx(plain.mass + hub_mass, rel=1e-14)
    # the hub's mass lowers the free-free bending frequencies; its 1e4 Pa adds no stiffness to speak of
    assert np.abs(rotor.fe().K - plain.fe().K).max() < 1e-6 * np.abs(plain.fe().K).max()
    back = rl.Rotor.from_toml(rotor.to_toml(tmp_path / "r.toml"))
    assert np.array_equal(back.fe().M, rotor.fe().M) and back.model.sections[0].layers
    bad = dict(sec, layers=[{"outer_diameter": 0.12, "inner_diameter": 0.05, "material": "brass"}])
    with pytest.raises(rl.InputError, match=r"rotor\.sections\[0\]\.layers\[0\]\.material = 'brass'"):
        rl.Rotor(materials={"steel": steel}, sections=[bad])


def test_cli_modes_takes_ross_bearings_at_each_speed(capsys, tmp_path):
    ref = REF["frequency_dependent"]
    png = tmp_path / "campbell.png"
    args = ["modes", str(FIX / ref["file"]), "--speeds-rpm", "0,5000,10000", "--json", "--n-modes", "10", "--plot", str(png)]
    assert main(args) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["model"].endswith("ROSS bearing coefficients at each speed")
    ours = np.array([[m["frequency_hz"] for m in per_speed] for per_speed in out["modes"]])
    np.testing.assert_allclose(ours, ref["frequencies_hz"], rtol=RTOL)
    assert png.stat().st_size > 10_000


@pytest.mark.parametrize("kw, words", [
    ({"catchers": {"DE": 2.0}}, "catchers.DE = 2.0: must be a position on the rotor, 0 <= x <= 1.5 m"),
    ({"catcher_nodes": {"DE": 9}}, "catcher_nodes.DE.node = 9: must be a shaft node, 0..6"),
    ({"catcher_nodes": {"DE": 0.5}}, "must be a ROSS node number (int)"),
    ({"catchers": {"Bearing_0": 0.2}}, "station name already used by a ROSS bearing"),
    ({"bearings_at_rpm": float("nan")}, "must be a spin speed >= 0 rpm"),
])
def test_bad_catcher_stations_are_named(kw, words):
    with pytest.raises(rl.InputError) as err:
        rl.Rotor.from_ross(FIX / "rotor_example.toml", **kw)
    assert words in str(err.value) and str(err.value).startswith(str(FIX / "rotor_example.toml"))


@pytest.mark.parametrize("name", ["compressor_like", "compressor_example"])
def test_matrices_equal_ross_lateral_blocks(name):
    # ROSS's own assembled matrices (free rotor: its bearings' K taken out), lateral DOFs x, y,
    # alpha, beta of each node, against ours (y, z, alpha, beta: the same conventions, no sign flip)
    rs = pytest.importorskip("ross")
    path = FIX / f"{name}.toml"
    theirs = rs.Rotor.load(path)
    ours = rl.Rotor.from_ross(path, bearings_at_rpm=0.0).fe()
    idx = np.array([[6 * k + j for j in (0, 1, 3, 4)] for k in range(len(ours.nodes))]).ravel()
    k_free = theirs.K(0)
    for b in theirs.bearing_elements:
        dofs = list(b.dof_global_index.values())
        k_free[np.ix_(dofs, dofs)] -= b.K(0)
    for a, b in ((theirs.M(0), ours.M), (k_free, ours.K), (theirs.G(), ours.G)):
        assert np.abs(a[np.ix_(idx, idx)] - b).max() < 1e-13 * np.abs(b).max()


def test_ross_amb_rotor_matches_ross_with_shaft_only_damping():
    # ROSS's AMB rig rotor: magnetic bearings (PID coefficients over 50 frequencies), 19 disks and
    # Rayleigh damping alpha = 2.5 1/s on the shaft elements only (damping.shaft_only). The
    # elastic modes agree to rounding; the four AMB rigid-body modes (1-8 Hz, damping ratio 0.16-0.56)
    # are ill-conditioned eigenvalues: 1e-15 of noise on K moves them by ~1e-7 (checked below), so
    # they are compared at 1e-5
    from rotorlanding.timoshenko import support_matrices

    ref = REF["amb_example"]
    for speed, f_ross, z_ross in zip(ref["speeds_rpm"], ref["frequencies_hz"], ref["damping_ratios"]):
        rotor = rl.Rotor.from_ross(FIX / ref["file"], bearings_at_rpm=speed)
        assert rotor.model.damping_shaft_only and rotor.model.mass_proportional_damping == 2.5
        modes = rotor.modes([speed], n_modes=len(f_ross))
        f, z = modes.frequencies_hz[0], modes.damping_ratios[0]
        rigid = np.array(f_ross) < 50.0  # the elastic modes start above 100 Hz
        assert rigid.sum() == 4
        rel_f, rel_z = np.abs(f - f_ross) / f_ross, np.abs(z - z_ross) / np.array(z_ross)
        print(f"AMB rotor at {speed:.0f} rpm: elastic modes {rel_f[~rigid].max():.1e} (damping ratios "
              f"{rel_z[~rigid].max():.1e}), AMB rigid-body modes {rel_f[rigid].max():.1e}")
        assert rel_f[~rigid].max() < RTOL and rel_z[~rigid].max() < 1e-7
        assert rel_f[rigid].max() < 1e-5 and rel_z[rigid].max() < 1e-5
    # the conditioning of the rigid-body modes, on our own matrices at the last speed
    fe = rotor.fe()
    ks, cs = support_matrices(fe)
    n, omega = fe.ndof, speed * math.pi / 30.0

    def lowest(k):
        a = np.block([[np.zeros((n, n)), np.eye(n)],
                      [-np.linalg.solve(fe.M, k), -np.linalg.solve(fe.M, fe.C + cs + omega * fe.G)]])
        lam = np.linalg.eigvals(a)
        return np.sort(lam.imag[lam.imag > 1e-9])[:4]

    noise = np.random.default_rng(1).standard_normal((n, n))
    k = fe.K + ks
    moved = np.abs(lowest(k * (1 + 1e-15 * (noise + noise.T))) - lowest(k)) / lowest(k)
    assert moved.max() > 1e-9


def test_shaft_only_damping_leaves_the_disks_out():
    steel = {"youngs_modulus": 2.1e11, "poisson_ratio": 0.3, "density": 7850.0}
    kw = dict(materials={"s": steel}, sections=[{"length": 1.0, "outer_diameter": 0.05, "material": "s", "elements": 4}],
              stations={"a": 0.3, "b": 0.6})
    disks = [{"name": "d", "position": 0.3, "mass": 20.0, "polar_inertia": 0.2, "transverse_inertia": 0.1}]
    damping = {"mass_proportional": 3.0, "stiffness_proportional": 1e-5}
    with_disks = rl.Rotor(disks=disks, damping=dict(damping, shaft_only=True), **kw).fe()
    whole = rl.Rotor(disks=disks, damping=damping, **kw).fe()
    bare = rl.Rotor(**kw).fe()  # the same mesh (the disk sits on station a)
    np.testing.assert_allclose(with_disks.C, 3.0 * bare.M + 1e-5 * bare.K, rtol=1e-14, atol=1e-14 * np.abs(bare.K).max())
    np.testing.assert_allclose(whole.C - with_disks.C, 3.0 * (whole.M - bare.M), atol=1e-12)
