"""Craig-Bampton reduction: frequencies, rigid-body modes, static response at the boundary."""

import dataclasses
from pathlib import Path

import numpy as np
import pytest

from rotorlanding.errors import InputError
from rotorlanding.modal import modal_analysis, reduction_report, rigid_body_basis
from rotorlanding.reduction import craig_bampton, full_model, reduce_rotor
from rotorlanding.rotor import load_rotor
from rotorlanding.timoshenko import assemble, with_landing_supports

RIG = Path(__file__).resolve().parents[1] / "scenarios" / "rig_rotor.toml"


@pytest.fixture(scope="module")
def rig_fe():
    return assemble(load_rotor(RIG))


def test_rig_reduction_frequencies_within_half_percent(rig_fe):
    """Modes below 2 x the max spin frequency (333 Hz) within 0.5 % with the rig's 15 modes."""
    assert rig_fe.rotor.reduction.modes == 15
    red = reduce_rotor(rig_fe)
    f_limit = 2 * 10000 / 60
    for supported in (True, False):
        full, r = full_model(rig_fe), red
        if supported:
            full, r = full.with_supports(), r.with_supports()
        rows = reduction_report(full, r, [0.0, 10000.0], f_limit)
        assert len(rows) >= 4 * (1 if not supported else 1)
        assert {row["speed_rpm"] for row in rows} == {0.0, 10000.0}
        worst = max(abs(row["relative_error"]) for row in rows)
        assert worst < 5e-3, rows
        # CB is a Rayleigh-Ritz projection: reduced frequencies are never below the full ones at 0 rpm
        assert all(row["reduced_hz"] >= row["full_hz"] * (1 - 1e-9) for row in rows if row["speed_rpm"] == 0.0)


def test_error_falls_with_more_modes(rig_fe):
    full = full_model(rig_fe).with_supports()
    worst = []
    for n in (4, 8, 12):
        red = craig_bampton(rig_fe, ["NDE_sleeve", "DE_sleeve"], n).with_supports()
        rows = reduction_report(full, red, [10000.0], 333.0)
        worst.append(max(abs(r["relative_error"]) for r in rows))
    assert worst[0] > worst[1] > worst[2]


def test_free_rotor_keeps_four_rigid_body_modes(rig_fe):
    full = full_model(rig_fe)
    red = reduce_rotor(rig_fe)
    assert rigid_body_basis(full).shape[1] == 4
    assert rigid_body_basis(red).shape[1] == 4
    # rigid-body modes are excluded from the reported modes; at speed the free rigid rotor's
    # nutation (forward, ~ Ip/Id Omega) shows up among the rigid modes, not the elastic ones
    res = modal_analysis(red, 7000.0)
    nut = [m for m in res.rigid_modes if m.frequency_hz > 0.01]
    # exactly one nutation, forward; the other rigid eigenvalues sit at zero frequency, and whether
    # round-off lifts one of them above the report's zero threshold depends on the geometry (the
    # count of all rigid modes was 3 with the session-3 rotor and 1 with the session-8 refit)
    assert len(nut) == 1 and nut[0].whirl == "forward" and not any(m.rigid for m in res.modes)
    # the lowest elastic mode lies well above the nutation (~6 Hz): nothing rigid leaks into it
    assert all(m.frequency_hz > 2 * nut[0].frequency_hz for m in res.modes)
    assert len(nut) == 1 and nut[0].whirl == "forward"
    # the reduced model keeps the full model's nutation (same rigid-body subspace)
    nut_full = [m for m in modal_analysis(full, 7000.0).rigid_modes if m.frequency_hz > 0.01]
    assert nut[0].frequency_hz == pytest.approx(nut_full[0].frequency_hz, rel=1e-3)
    # rigid-rotor closed form, nutation frequency = Ip Omega / Id (Id about the centre of mass), on
    # the rig rotor made 1000x stiffer: the elastic part of the mode then vanishes (on the rig
    # itself the 60 kg actuator disk on its 40 mm shaft lowers it by ~20 %)
    stiff = dataclasses.replace(rig_fe.rotor, sections=tuple(
        dataclasses.replace(sec, material=dataclasses.replace(
            sec.material, youngs_modulus=sec.material.youngs_modulus * 1e3,
            shear_modulus=sec.material.shear_modulus * 1e3)) for sec in rig_fe.rotor.sections))
    fe = assemble(stiff)
    nut_stiff = [m for m in modal_analysis(reduce_rotor(fe), 7000.0).rigid_modes if m.frequency_hz > 0.01]
    x = fe.nodes
    u, t = np.zeros(fe.ndof), np.zeros(fe.ndof)
    u[0::4] = 1.0
    t[0::4], t[3::4] = x, 1.0
    xc = (u @ fe.M @ t) / (u @ fe.M @ u)
    t[0::4] = x - xc  # rigid tilt about the centre of mass in the x-y plane
    id_cg = t @ fe.M @ t
    expected = fe.polar_inertia * 7000 / 60 / id_cg
    assert nut_stiff[0].frequency_hz == pytest.approx(expected, rel=2e-3)


def test_static_gravity_deflection_matches_at_boundary(rig_fe):
    """Craig-Bampton is exact in statics at its boundary whatever the number of modes, when every
    spring on an interior DOF is in K before reducing: the landing model's rotor
    (``with_landing_supports``: the motor coupling, 1e5 N/m since session 40, in K; the catcher
    stand-ins at the boundary added after). A coupling added to the reduced model instead acts
    through the reduction's shapes only, and the statics are then not exact (why build_spec
    reduces the landed rotor)."""
    landed = with_landing_supports(rig_fe)
    assert landed is not rig_fe  # the rig has a landed support off the boundary
    full = full_model(landed).with_supports()
    late = craig_bampton(rig_fe, ["NDE_sleeve", "DE_sleeve"], 0).with_supports()
    u_late = np.linalg.solve(late.K, late.gravity_load())
    u_ref = np.linalg.solve(full.K, full.gravity_load())
    assert abs(u_late[late.index("DE_sleeve", "z")] / u_ref[rig_fe.dof("DE_sleeve", "z")] - 1) > 1e-4
    for n_modes in (0, 3, 12):
        red = craig_bampton(landed, ["NDE_sleeve", "DE_sleeve"], n_modes).with_supports()
        u_full = np.linalg.solve(full.K, full.gravity_load())
        u_red = np.linalg.solve(red.K, red.gravity_load())
        for st in ("NDE_sleeve", "DE_sleeve"):
            for d in ("y", "z"):
                uf = u_full[rig_fe.dof(st, d)]
                ur = u_red[red.index(st, d)]
                assert ur == pytest.approx(uf, rel=1e-9, abs=1e-15)
        # sanity: the rotor sags (gravity -z) by weight / support stiffness order of magnitude
        sag = u_full[rig_fe.dof("DE_sleeve", "z")]
        assert -1e-4 < sag < -1e-7


def test_reduced_total_mass_and_physical_boundary(rig_fe):
    red = reduce_rotor(rig_fe)
    # a rigid translation in y expressed in reduced coordinates: boundary y = 1, modes 0
    q = np.zeros(red.n)
    q[red.index("NDE_sleeve", "y")] = 1.0
    q[red.index("DE_sleeve", "y")] = 1.0
    np.testing.assert_allclose((red.T @ q)[0::4], 1.0, atol=1e-9)
    assert q @ red.M @ q == pytest.approx(rig_fe.mass, rel=1e-9)
    np.testing.assert_allclose(red.G, -red.G.T, atol=1e-12)


def test_unrestrained_boundary_is_a_clear_error(rig_fe):
    with pytest.raises(InputError, match="rigid-body"):
        craig_bampton(rig_fe, ["DE_sleeve"], 4)
    # one station with its rotations restrains the rigid motion
    red = craig_bampton(rig_fe, ["DE_sleeve"], 12, rotations=True)
    assert red.n == 16
