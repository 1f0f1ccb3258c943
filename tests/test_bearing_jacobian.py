"""Compiled bearing connector and analytic Jacobians (rotorlanding.bearing_kernel,
forces.rotor_loads_jacobian) against the plain-Python laws and finite differences, and the
Exudyn system Jacobian with the analytic user Jacobians against Exudyn's numerical one."""

from pathlib import Path

import numpy as np
import pytest

from rotorlanding.bearing_kernel import bearing_functions
from rotorlanding.forces import bearing_forces, rotor_forces, rotor_loads_jacobian
from rotorlanding.landing import build_spec
from rotorlanding.scenario import load_scenario

ROOT = Path(__file__).resolve().parents[1]
PAPER = ROOT / "scenarios" / "paper" / "forward_whirl_landing.toml"


@pytest.fixture(scope="module")
def spec():
    # the worn-bearing drag (off in the paper's forward case) is switched on so its derivatives are
    # checked too, still developing (growth angles of the order of the states' race angles, so the
    # derivative w.r.t. the race angle is large)
    return build_spec(load_scenario(PAPER, ["contact.k_visc=2e4", "bearings.NDE.eta=0.1",
                                            "effects.worn_bearing_drag=true", "bearings.DE.worn_drag_torque=2.0",
                                            "bearings.NDE.worn_drag_torque=1.5",
                                            "bearings.DE.worn_drag_growth_angle=0.5",
                                            "bearings.NDE.worn_drag_growth_angle=0.2",
                                            # its load-proportional part (ball contacts sliding)
                                            "bearings.DE.worn_drag_friction=0.2",
                                            "bearings.NDE.worn_drag_friction=0.1"]))


def _states(spec, b):
    """(name, q, v, tilt): free flight, radial contact with slip, face contact (full and partial
    pressure, both faces), rolling/whirling races, outer race at rest."""
    c = b.params.clearance
    cl = spec.scenario.axial.cl_ax
    dm = spec.scenario.axial.delta_m
    v_roll = [0.02, -0.03, 733.0, 0.004, 0.003, -0.002, 650.0, 0.005, -0.004]
    return [
        ("free", [1e-5, 2e-5, 0.3, 0.0, 1e-7, -2e-7, 0.1, 1e-7, -3e-7], [0.01, 0.0, 733.0, 0.0, 0, 0, 0.0, 0, 0],
         [0.0, 0.0]),
        ("radial contact", [3e-5, -1.05 * c, 1.0, 0.0, 1e-6, -2e-6, 0.3, 1e-6, -3e-6], v_roll, [0.0, 0.0]),
        ("face full", [3e-5, -1.04 * c, 1.0, cl + 3e-6, 1e-6, -2e-6, 0.3, 1e-6, -3e-6], v_roll, [2e-5, -3e-5]),
        ("face partial", [-4e-5, 1.02 * c, 1.0, cl + 2e-6, 1e-6, -2e-6, 0.3, 2e-6, 1e-6], v_roll, [4e-4, -6e-4]),
        ("face bottomed, -x", [c * 0.7, c * 0.75, 1.0, -(cl + dm + 2e-5), 0.0, 0.0, 0.3, 0.0, 0.0],
         [0.05, -0.01, 700.0, -0.002, 0.0, 0.0, 10.0, 0.0, 0.0], [-1e-4, 2e-4]),
        ("rolling contact, small slip", [3e-5, -1.05 * c, 1.0, cl + 3e-6, 1e-6, -2e-6, 0.3, 1e-6, -3e-6],
         [0.002, -0.003, 733.0, 0.004, 0.0003, -0.0002, 733.0 * b.params.sleeve_radius / b.params.race_radius + 0.01,
          0.0005, -0.0004], [2e-5, -3e-5]),
        ("outer race at rest", [3e-5, -1.05 * c, 1.0, cl + 3e-6, 1e-6, -2e-6, 0.3, 1e-6, -3e-6],
         [0.02, -0.03, 733.0, 0.004, 0.003, -0.002, 650.0, 0.0, 0.0], [2e-5, -3e-5]),
    ]


def _fd(f, q, v, hq, hv):
    n = len(q)
    Nq = np.zeros((n, n))
    Nv = np.zeros((n, n))
    for j in range(n):
        a, b = list(q), list(q)
        a[j] += hq[j]
        b[j] -= hq[j]
        Nq[:, j] = (np.array(f(a, v)) - np.array(f(b, v))) / (2 * hq[j])
        a, b = list(v), list(v)
        a[j] += hv[j]
        b[j] -= hv[j]
        Nv[:, j] = (np.array(f(q, a)) - np.array(f(q, b))) / (2 * hv[j])
    return Nq, Nv


def _close(J, N, rtol, noise=0.0):
    """Entry-wise agreement relative to the row scale of the reference (each row is one force),
    plus the round-off of the central differences (``noise``, per column)."""
    scale = np.abs(N).max(axis=1, keepdims=True)
    return np.abs(J - N) <= rtol * scale + noise + 1e-300


@pytest.mark.parametrize("bname", ["DE", "NDE"])
def test_bearing_kernel_forces_and_jacobian(spec, bname):
    b = next(x for x in spec.bearings if x.name == bname)
    checked_rub = False
    for name, q, v, tilt in _states(spec, b):
        holder = list(tilt)
        fpy = bearing_forces(spec, b, holder)
        force, jac, _ = bearing_functions(spec, b, holder)
        r_py = np.array(fpy(0.0, q, v))
        r_nb = np.array(force(None, 0.0, 0, q, v))
        np.testing.assert_allclose(r_nb, r_py, rtol=1e-12, atol=1e-9, err_msg=name)
        Jq = -np.array(jac(None, 0.0, 0, q, v, 1.0, 0.0))
        Jv = -np.array(jac(None, 0.0, 0, q, v, 0.0, 1.0))
        # combined factors are the linear combination
        np.testing.assert_allclose(-np.array(jac(None, 0.0, 0, q, v, 2.0, 3e-3)), 2.0 * Jq + 3e-3 * Jv,
                                   rtol=1e-12, atol=1e-6)
        hq = np.full(9, 2e-10)
        hq[3] = 5e-11
        hv = np.full(9, 1e-8)
        hv[2] = hv[6] = 1e-5
        Nq, Nv = _fd(lambda a, c: fpy(0.0, a, c), q, v, hq, hv)
        fmax = np.abs(r_py).max()
        okq, okv = _close(Jq, Nq, 2e-5, 1e-13 * fmax / hq), _close(Jv, Nv, 2e-5, 1e-13 * fmax / hv)
        assert okq.all(), f"{name}: dF/dq differs at {np.argwhere(~okq).tolist()}\n{Jq}\n{Nq}"
        assert okv.all(), f"{name}: dF/dv differs at {np.argwhere(~okv).tolist()}\n{Jv}\n{Nv}"
        # the race angle enters only through the developing worn drag (row 6), whose derivative is
        # small against the row's contact terms: checked on its own scale
        a, c = list(q), list(q)
        a[6] += 1e-6
        c[6] -= 1e-6
        n6 = (np.array(fpy(0.0, a, v)) - np.array(fpy(0.0, c, v))) / 2e-6
        assert abs(n6[6]) > 0.1 or v[6] == 0.0, name  # a race at rest feels no drag
        np.testing.assert_allclose(Jq[:, 6], n6, rtol=1e-5, atol=1e-4, err_msg=name)
        if name.startswith("face") and b.params.axial_face:
            # the axial rub and Coulomb friction make the race forces depend on x_ax
            assert np.abs(Nq[[0, 1, 2, 6], 3]).max() > 0 and np.abs(Nv[[7, 8], 3]).max() >= 0
            checked_rub = True
    assert checked_rub == b.params.axial_face


def test_rotor_loads_jacobian():
    from rotorlanding.config import load_toml
    from rotorlanding.scenario import scenario_from_dict

    path = ROOT / "scenarios" / "landing_7000rpm.toml"
    data = load_toml(path)
    data["unbalance"] = {"station": "DE_sleeve", "magnitude": 2e-4, "phase_deg": 30.0}
    data.setdefault("effects", {})["unbalance"] = True
    data["amb"].update(t_drop=0.01, drop_axial=True)
    data["axial"]["f_thrust"] = 4000.0
    data["spin"].update(drive="constant", drive_gain=0.3)
    sc = scenario_from_dict(data, source=str(path))
    spec = build_spec(sc)
    for gyro in (False, True):
        f = rotor_forces(spec, gyroscopic_in_user_function=gyro)
        jac = rotor_loads_jacobian(spec, gyroscopic_in_user_function=gyro)
        rng = np.random.default_rng(3)
        n = spec.n_lat + 2
        for t, x in [(0.0, 0.0), (0.02, sc.axial.cl_ax + 1e-5), (0.02, -(sc.axial.cl_ax + sc.axial.delta_m + 1e-5))]:
            q = list(rng.normal(0, 1e-5, n))
            v = list(rng.normal(0, 1e-3, n))
            q[-2], v[-2] = 1.3, 733.0
            q[-1], v[-1] = x, 0.002
            Jq = -jac(t, q, v, 1.0, 0.0)
            Jv = -jac(t, q, v, 0.0, 1.0)
            Nq, Nv = _fd(lambda a, c: f(t, a, c), q, v, [1e-9] * (n - 2) + [1e-6, 1e-11], [1e-7] * (n - 2) + [1e-4, 1e-8])
            assert _close(Jq, Nq, 1e-5).all(), (t, x)
            assert _close(Jv, Nv, 1e-5).all(), (t, x)


@pytest.mark.parametrize("sets", [[], ["amb.t_drop=0.01", "amb.drop_axial=true"],
                                  ["effects.worn_bearing_drag=true", "bearings.DE.worn_drag_torque=2.0"],
                                  ["effects.worn_bearing_drag=true", "bearings.DE.worn_drag_torque=2.0",
                                   "bearings.DE.worn_drag_growth_angle=0.3"],
                                  ["effects.worn_bearing_drag=true", "bearings.DE.worn_drag_friction=0.2",
                                   "bearings.NDE.worn_drag_friction=0.2", "bearings.NDE.worn_drag_growth_angle=0.3"]])
def test_exudyn_system_jacobian_analytic_equals_numerical(sets):
    """Same model with and without jacobianUserFunction: Exudyn's ODE2 RHS Jacobians agree at a
    state with radial contact and face contact (checks the sign and scaling convention); with the
    AMB still on, the rotor loads sit in their own connector."""
    import exudyn as exu

    from rotorlanding.exudyn_model import SolverSettings, build_exudyn

    spec = build_spec(load_scenario(PAPER, sets))
    q0, v0 = spec.initial_state()
    q, v = q0.copy(), v0.copy()
    for b in spec.bearings:
        q[b.i_station + 1] = -1.04 * b.params.clearance
        q[b.i_station] = 2e-5
        v[b.i_station: b.i_station + 2] = [0.02, -0.01]
        v[b.i_race + 2] = 500.0
        v[b.i_race: b.i_race + 2] = [0.003, -0.002]
        v[b.i_outer: b.i_outer + 2] = [0.001, 0.004]
        q[b.i_outer: b.i_outer + 2] = [2e-6, -5e-6]  # (the ribbon's cross term is singular at the centre)
    q[spec.i_axial] = spec.scenario.axial.cl_ax + 5e-6
    v[spec.i_axial] = 0.003
    mats = {}
    for analytic in (False, True):
        model = build_exudyn(spec, q, v, analytic_jacobian=analytic)
        for holder, ra, rb, n in model.pre_step.tilts:
            holder[0], holder[1] = 1e-5, -2e-5
        ss = SolverSettings.from_spec(spec).apply(exu, 0.0, 0.01)
        solver = exu.MainSolverImplicitSecondOrder()
        solver.InitializeSolver(model.mbs, ss)
        out = []
        for fq, fv in ((1.0, 0.0), (0.0, 1.0)):
            solver.ComputeJacobianODE2RHS(model.mbs, scalarFactor_ODE2=fq, scalarFactor_ODE2_t=fv)
            out.append(np.array(solver.GetSystemJacobian())[: spec.n, : spec.n].copy())
        mats[analytic] = out
    for (Jn, Ja) in zip(mats[False], mats[True]):
        assert np.abs(Jn).max() > 1e4
        ok = _close(Ja, Jn, 1e-4)
        assert ok.all(), np.argwhere(~ok).tolist()


@pytest.mark.parametrize("sets", [[], ["amb.t_drop=0.01"],
                                  ["effects.worn_bearing_drag=true", "bearings.DE.worn_drag_friction=0.2",
                                   "bearings.NDE.worn_drag_friction=0.1", "bearings.NDE.worn_drag_growth_angle=0.3"]])
def test_system_forces_equal_reference(sets):
    """The lean whole-system RHS (compiled kernel, used for the LSODA benchmark) equals the
    independent reference assembly, and its Jacobian matches finite differences."""
    from rotorlanding.bearing_kernel import system_forces
    from rotorlanding.reference import generalized_forces

    spec = build_spec(load_scenario(PAPER, sets))
    f, jac = system_forces(spec)
    rng = np.random.default_rng(5)
    q0, v0 = spec.initial_state()
    for t in (0.0, 0.02):
        q = q0 + rng.normal(0, 2e-6, spec.n)
        v = v0 + rng.normal(0, 1e-3, spec.n)
        for b in spec.bearings:
            q[b.i_station + 1] = -1.03 * b.params.clearance
            v[b.i_race + 2] = 400.0
        q[spec.i_axial] = spec.scenario.axial.cl_ax + 4e-6
        ref = generalized_forces(spec, t, q, v)
        np.testing.assert_allclose(f(t, q, v), ref, rtol=1e-9, atol=1e-6 * np.abs(ref).max())
        Jq, Jv = jac(t, q, v)
        hq = np.full(spec.n, 1e-10)
        hv = np.full(spec.n, 1e-7)
        hv[spec.i_theta] = 1e-4
        for j in range(spec.n):
            e = np.zeros(spec.n)
            e[j] = hq[j]
            nq = (f(t, q + e, v) - f(t, q - e, v)) / (2 * hq[j])
            e[j] = hv[j]
            nv = (f(t, q, v + e) - f(t, q, v - e)) / (2 * hv[j])
            assert np.abs(Jv[:, j] - nv).max() <= 1e-4 * np.abs(Jv).max() + 1e-13 * np.abs(ref).max() / hv[j], j
            # the axial-rub forces depend on the lateral coordinates through the face tilt, which the
            # Jacobian leaves out: skip those rows in the lateral columns
            rows = list(range(spec.n))
            if j < spec.n_lat:
                for b in spec.bearings:
                    if b.params.axial_face:
                        rows = [i for i in rows if i not in (b.i_station, b.i_station + 1, spec.i_theta, b.i_race,
                                                             b.i_race + 1, b.i_race + 2)]
            assert np.abs(Jq[rows, j] - nq[rows]).max() <= 1e-5 * np.abs(Jq).max() + 1e-13 * np.abs(ref).max() / hq[j], j
