"""The landing model in Exudyn: build the ``mbs`` from a LandingSpec, solve, collect states.

Objects (Exudyn 1.13.6, see shared notes):
- reduced rotor: one ``ObjectGenericODE2`` over [station NodePoint2D..., modal NodeGenericODE2,
  spin/axial NodeGenericODE2 (theta, x_ax)] with the Craig-Bampton M, K, C, the spin inertia and
  rotor mass, the reduced gravity load, and a user force (gyroscopics, AMB hold, unbalance,
  windage, drive, axial model) — :func:`rotorlanding.forces.rotor_forces`;
- inner race: ``NodeRigidBody2D`` + ``ObjectRigidBody2D`` (y, z, spin angle);
- outer race: ``NodePoint2D`` + ``ObjectMassPoint2D``;
- one zero-mass ``ObjectGenericODE2`` connector over [bearing stations, spin/axial node, races] whose
  user force applies the paper's laws of all bearings (contact, axial rub, balls, drag, ribbon,
  Coulomb) and the spin/axial rotor loads, compiled with numba, with an analytic
  ``jacobianUserFunction`` — :mod:`rotorlanding.bearing_kernel` (one Python call per residual and
  one per Jacobian; the rotor loads move to their own connector when they need the lateral
  coordinates: AMB before the drop, unbalance). ``build_exudyn(..., analytic_jacobian=False)``
  gives the former layout for comparison: one plain-Python connector per bearing
  (:func:`rotorlanding.forces.bearing_forces`) with Exudyn's numerical Jacobians.

Speed (paper forward-whirl landing, 1 s, 2 cores; ``benchmarks/landing_speed.py``): Exudyn spends
its time per Newton iteration (~8 us: residual of all objects, one Python call) and per Jacobian
(~25 us: 28 x 28 system); the step is the main lever. See SolverSettings for the Newton strategy.

Exudyn's planar (X, Y) is our (y, z). Nodes are added in the LandingSpec coordinate order, so the
system's ODE2 vector is the spec's q.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from . import step_kernel
from .bearing_kernel import bearing_functions, direct, landing_functions, update_tilts
from .forces import (BEARING_LOCAL, bearing_forces, mechanism_functions, registry_forces, rotor_forces,
                     rotor_loads_jacobian, rotor_loads_need_lateral)
from .landing import LandingSpec


@dataclass
class SolverSettings:
    """All solver settings in one place (from the scenario's [solver] table)."""

    step: float
    spectral_radius: float
    modified_newton: bool
    output_period: float
    newton_relative_tolerance: float = 1e-6
    newton_absolute_tolerance: float = 1e-8
    # Newton strategy (measured on the paper's forward-whirl landing, benchmarks/landing_speed.py):
    # with analytic Jacobians a Jacobian costs about 3 residual evaluations, so it pays to
    # refresh it at the start of every step and whenever one modified-Newton iteration reduces
    # the residual by less than 5x (Exudyn's default 2x let it crawl at a contraction of ~0.4 for
    # 8-10 iterations per step); a step whose Newton fails after 12 iterations is retried at half
    # the step (adaptive step), and the step grows back after 10 steps with < 12 iterations
    jacobian_per_step: bool = True
    newton_contractivity: float = 0.2
    newton_max_iterations: int = 12
    adaptive_recovery_iterations: int = 12
    # Eigen's dense LU factorises the 28 x 28 system Jacobian faster than Exudyn's own dense solver
    # (same iterations, ~20 % less CPU per simulated second on the forward-whirl landing)
    linear_solver: str = "EigenDense"
    # error-controlled step (scenario solver.step_control = "auto"; StepController): step starts at
    # ``step`` and moves in [min_step, max_step] with a local position error <= step_tolerance
    step_control: str = "fixed"
    step_tolerance: float = 1e-7
    max_step: float = 4e-4
    min_step: float = 1e-7

    @classmethod
    def from_spec(cls, spec: LandingSpec) -> "SolverSettings":
        s = spec.scenario.solver
        return cls(s.step, s.spectral_radius, s.modified_newton, s.output_period, s.newton_relative_tolerance,
                   s.newton_absolute_tolerance, step_control=s.step_control, step_tolerance=s.step_tolerance,
                   max_step=s.max_step, min_step=s.min_step)

    def apply(self, exu, t_start: float, t_end: float):
        ss = exu.SimulationSettings()
        ti = ss.timeIntegration
        ti.startTime = t_start
        ti.endTime = t_end
        ti.numberOfSteps = max(1, int(round((t_end - t_start) / self.step)))
        ti.generalizedAlpha.spectralRadius = self.spectral_radius
        ti.newton.useModifiedNewton = self.modified_newton
        ti.newton.relativeTolerance = self.newton_relative_tolerance
        ti.newton.absoluteTolerance = self.newton_absolute_tolerance
        ti.newton.modifiedNewtonJacUpdatePerStep = self.jacobian_per_step
        ti.newton.modifiedNewtonContractivity = self.newton_contractivity
        ti.newton.maxIterations = self.newton_max_iterations
        ti.adaptiveStep = True
        ti.adaptiveStepRecoveryIterations = self.adaptive_recovery_iterations
        ss.linearSolver.solverType = getattr(exu.LinearSolverType, self.linear_solver)
        ti.verboseMode = 0
        ss.solution.file.write = False
        ss.solution.sensors.writePeriod = self.output_period
        ss.show.computationTime = False
        ss.show.statistics = False
        if self.step_control == "auto":
            StepController.configure(ss, self, t_start, t_end)
        return ss


class StepController:
    """Error-controlled step for Exudyn 1.13.6's generalized-alpha solver (``solver.step_control =
    "auto"``), all inside one ``SolveDynamic`` (no re-initialisation).

    Error estimate (after each converged step, Exudyn's PostNewton hook): the local error of the
    positions of the Newmark family, ``e_i = |beta - 1/6| h^2 |a_i(end) - a_i(start)|`` (Zienkiewicz and
    Xie 1991; beta of the generalized-alpha scheme at the scenario's spectral radius), over the
    physical positions (rotor stations, axial position, inner and outer races; spin angles and
    modal amplitudes excluded), scaled by ``step_tolerance`` [m]: ``err = max_i e_i / tol``.

    Controller: ``err > REJECT`` (2) rejects the step: the hook returns ``[err, h_new]`` with
    ``discontinuous.iterationTolerance = 1`` and ``maxIterations = 2``, which makes Exudyn restore
    the start of the step and repeat it at ``min(0.75 h, h_new)``; ``h_new = h max(0.2, SAFETY
    err^(-1/3))`` (e ~ h^3). An accepted step sets the next step itself (``it.currentStepSize``,
    read at the next step's start): ``h max(0.5, min(GROW, SAFETY err^(-1/3)))`` in [min_step,
    max_step], not grown after a step whose Newton needed more than ``newton_grow_limit`` (6)
    iterations (large steps where Newton crawls cost more than they save: 3 / 4 / 6 / 8 gave
    21741 / 20600 / 19982 / 23006 Newton iterations on the forward landing's first 0.3 s). Exudyn's
    own step growth is switched off (recovery steps 1e9); its halving after a failed Newton stays.
    GROW 1.5, SAFETY 0.8 and REJECT 2 (instead of 2, 0.9, 1): 77 instead of 1037 rejections there.

    Contact look-ahead: when the next step would exceed ``solver.step``, it is ended at the
    predicted time a free journal reaches its clearance (radial speed held), not below
    ``solver.step``: an impact inside a large step is where Newton fails after 12 iterations.

    Note (issue 21, session 12): returning a recommended step with ``maxIterations = 1`` (the
    probe of session 11) is ignored by Exudyn, which repeats a step only when the PostNewton
    error exceeds ``iterationTolerance`` and another discontinuous iteration is allowed.
    """

    GROW = 1.5
    SAFETY = 0.8
    REJECT = 2.0
    RACES = True

    def __init__(self, spec: LandingSpec, settings: "SolverSettings"):
        import exudyn as exu

        idx = list(range(2 * len(spec.stations))) + [spec.i_axial]
        if self.RACES:
            for b in spec.bearings:
                idx += [b.i_race, b.i_race + 1, b.i_race + 3, b.i_race + 4]
        self.idx = np.array(sorted(idx), dtype=np.int64)
        rho = settings.spectral_radius
        am, af = (2 * rho - 1) / (rho + 1), rho / (rho + 1)
        beta = 0.25 * (0.5 + af - am + 0.5) ** 2
        self.c = abs(beta - 1.0 / 6.0) / settings.step_tolerance
        self.hmax, self.hmin = settings.max_step, settings.min_step
        self.newton_grow_limit = max(2, settings.newton_max_iterations // 2)
        # contact awareness: station y index, race y index, clearance per bearing
        self.iy = np.array([b.i_station for b in spec.bearings], dtype=np.int64)
        self.ir = np.array([b.i_race for b in spec.bearings], dtype=np.int64)
        self.cl = np.array([b.params.clearance for b in spec.bearings], dtype=float)
        self.h_impact = settings.step
        self.SOS = exu.ConfigurationType.StartOfStep
        z = np.zeros(spec.n)
        self.max_jump = direct(step_kernel.max_jump, z, z, self.idx)
        self.time_to_contact = direct(step_kernel.time_to_contact, z, z, self.iy, self.ir, self.cl)
        self.sd = None
        self.solver = None
        self.accepted = 0
        self.rejected = 0
        self.a_start = None  # accelerations at the start of the present step (end of the last accepted)
        self.pre_step = None  # PreStep run here after each accepted step instead of before each attempt

    @staticmethod
    def configure(ss, settings: "SolverSettings", t_start: float, t_end: float):
        ti = ss.timeIntegration
        # Exudyn's largest step is (t_end - t_start) / numberOfSteps and its first step that one
        ti.numberOfSteps = max(1, int(np.ceil((t_end - t_start) / settings.max_step - 1e-9)))
        ti.minimumStepSize = settings.min_step
        ti.adaptiveStep = True
        ti.adaptiveStepRecoverySteps = 10 ** 9   # growth is the controller's
        d = ti.discontinuous
        d.useRecommendedStepSize = True
        d.iterationTolerance = 1.0
        d.maxIterations = 2
        d.ignoreMaxIterations = True
        # every accepted step is stored; collect() resamples them onto the output grid
        ss.solution.sensors.writePeriod = 0.0

    def __call__(self, mbs, t):
        if self.solver is None:
            self.solver = mbs.sys["dynamicSolver"]
            self.sd = mbs.systemData
        it = self.solver.it
        h = it.currentStepSize
        sd = self.sd
        a1 = sd.GetODE2Coordinates_tt()
        if self.a_start is None:
            self.a_start = sd.GetODE2Coordinates_tt(self.SOS)
        err = self.c * h * h * self.max_jump(a1, self.a_start, self.idx)
        if err > self.REJECT and h > self.hmin * (1 + 1e-9):
            self.rejected += 1
            return [err, max(self.hmin, h * max(0.2, self.SAFETY * err ** (-1.0 / 3.0)))]
        self.accepted += 1
        # the next step starts from this one's end: its start accelerations without another copy
        # out of Exudyn (~1 us)
        self.a_start = a1
        if self.pre_step is not None:
            self.pre_step(mbs, t)
        fac = self.GROW if err <= 0.0 else min(self.GROW, self.SAFETY * err ** (-1.0 / 3.0))
        if it.newtonSteps > self.newton_grow_limit:
            fac = min(fac, 1.0)
        h_next = min(self.hmax, h * max(0.5, fac))
        if h_next > self.h_impact:
            # a contact that closes within the next step: end that step at the predicted closing
            # time, so the impact starts with a small step (the error estimate alone sees an impact
            # only after a large step ran into it, where Newton often fails after 12 iterations)
            tau = self.time_to_contact(sd.GetODE2Coordinates(), sd.GetODE2Coordinates_t(), self.iy, self.ir, self.cl)
            if tau < h_next:
                h_next = max(self.h_impact, tau)
        it.currentStepSize = max(self.hmin, h_next)
        return [0.0, -1.0]


@dataclass
class ExudynModel:
    SC: object
    mbs: object
    spec: LandingSpec
    node_slices: list  # (node number, slice into q)
    sensors: list  # (sensor pos, sensor vel, slice)
    pre_step: object = None  # PreStep (gyroscopic update + optional progress callback)
    accel_sensors: list = None  # (sensor acc, slice): the auto step's Hermite resampling needs them
    controller: object = None   # StepController of the last auto-step solve (its counts)
    resample: tuple = None      # (t_start, output period) set by solve() with the auto step
    pre_step_detached: bool = False  # the auto step runs the pre-step's work itself
    post_newton_set: bool = False    # the auto step's controller is Exudyn's PostNewton hook


GYRO_UPDATE_TOL = 1e-4  # relative change of Omega that triggers a new C + Omega G


class PreStep:
    """Exudyn pre-step user function: sets the rotor damping matrix to C + Omega G when Omega has
    changed by more than GYRO_UPDATE_TOL since the last update (Omega decays slowly during a landing,
    so this runs a few times per run instead of a G q' product in every residual evaluation), and
    calls an optional progress callback."""

    def __init__(self, rotor_object, spin_node, C_full, G_full, enabled: bool):
        import exudyn as exu

        self.obj, self.node = rotor_object, spin_node
        self.C, self.G = C_full, G_full
        self.enabled = enabled
        self.omega = None
        self.progress = None
        self.var = exu.OutputVariableType.Coordinates_t
        self.updates = 0
        self.tilts = []  # (list [alpha, beta] read by a bearing closure, row alpha, row beta, n_lat)
        # merged connector: (compiled update, arguments after q) doing what the loop over
        # self.tilts does, in one call (the same bits, bearing_kernel.update_tilts)
        self.tilt_update = None
        self.sd = None

    def __call__(self, mbs, t) -> bool:
        if self.tilt_update is not None:
            f, args = self.tilt_update
            f(self.sd.GetODE2Coordinates(), *args)
        elif self.tilts:
            q = mbs.systemData.GetODE2Coordinates()
            for holder, ra, rb, n in self.tilts:
                holder[0] = float(ra @ q[:n])
                holder[1] = float(rb @ q[:n])
        if self.enabled:
            omega = mbs.GetNodeOutput(self.node, self.var)[0]
            if self.omega is None or abs(omega - self.omega) > GYRO_UPDATE_TOL * max(abs(self.omega), 1.0):
                mbs.SetObjectParameter(self.obj, "dampingMatrix", self.C + omega * self.G)
                self.omega = omega
                self.updates += 1
        if self.progress is not None:
            return self.progress(mbs, t)
        return True


def _timed(f, acc: dict, key: str):
    """f wrapped to accumulate its wall time and call count in acc[key] (benchmark only)."""
    from time import perf_counter

    acc.setdefault(key, [0.0, 0])

    def g(*args):
        t0 = perf_counter()
        r = f(*args)
        a = acc[key]
        a[0] += perf_counter() - t0
        a[1] += 1
        return r

    return g


def build_exudyn(spec: LandingSpec, q0=None, v0=None, *, analytic_jacobian: bool = True,
                 merge_connectors: bool = True, instrument: dict | None = None,
                 accelerations: bool | None = None) -> ExudynModel:
    """The Exudyn system of the landing. ``analytic_jacobian``: compiled bearing connectors with
    analytic Jacobians (:mod:`rotorlanding.bearing_kernel`) and the analytic Jacobian of the rotor
    loads; False gives the plain-Python laws with Exudyn's numerical differentiation (slower, for
    comparison); ``merge_connectors`` (with analytic_jacobian): all bearings and the spin/axial rotor
    loads in one connector (one Python call per residual instead of three). ``instrument``: a dict
    that receives {"force" | "jacobian" | "prestep": [seconds, calls]} of all Python user functions
    (benchmarks; the timers add ~0.2 us per call). ``accelerations``: also store the accelerations
    (needed by the auto step's resampling; default: when the scenario's solver.step_control is
    "auto")."""
    import exudyn as exu
    from exudyn.itemInterface import (NodeGenericODE2, NodePoint2D, NodeRigidBody2D, ObjectGenericODE2,
                                      ObjectMassPoint2D, ObjectRigidBody2D, SensorNode)

    if q0 is None or v0 is None:
        q0, v0 = spec.initial_state()
    q0 = np.asarray(q0, float)
    v0 = np.asarray(v0, float)
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    if instrument is not None:
        mbs_real = mbs

        class _Timed:
            def AddObject(self, item):
                if isinstance(item, ObjectGenericODE2):
                    if item.forceUserFunction != 0:
                        item.forceUserFunction = _timed(item.forceUserFunction, instrument, "force")
                    if item.jacobianUserFunction != 0:
                        item.jacobianUserFunction = _timed(item.jacobianUserFunction, instrument, "jacobian")
                return mbs_real.AddObject(item)

            def SetPreStepUserFunction(self, f):
                return mbs_real.SetPreStepUserFunction(_timed(f, instrument, "prestep"))

            def __getattr__(self, name):
                return getattr(mbs_real, name)

        mbs = _Timed()
    nodes = []  # (node number, slice)

    def point(i):
        nd = mbs.AddNode(NodePoint2D(referenceCoordinates=[0.0, 0.0], initialCoordinates=q0[i:i + 2].tolist(),
                                     initialVelocities=v0[i:i + 2].tolist()))
        nodes.append((nd, slice(i, i + 2)))
        return nd

    def generic(i, n):
        nd = mbs.AddNode(NodeGenericODE2(numberOfODE2Coordinates=n, referenceCoordinates=[0.0] * n,
                                         initialCoordinates=q0[i:i + n].tolist(),
                                         initialCoordinates_t=v0[i:i + n].tolist()))
        nodes.append((nd, slice(i, i + n)))
        return nd

    station_nodes = [point(2 * k) for k in range(len(spec.stations))]
    nb2 = 2 * len(spec.stations)
    n_modes = spec.n_lat - nb2
    modal_node = generic(nb2, n_modes) if n_modes > 0 else None
    spin_node = generic(spec.i_theta, 2)
    lateral_nodes = station_nodes + ([modal_node] if modal_node is not None else [])

    n_rot = spec.n_lat + 2
    M = np.zeros((n_rot, n_rot))
    K = np.zeros((n_rot, n_rot))
    C = np.zeros((n_rot, n_rot))
    M[: spec.n_lat, : spec.n_lat] = spec.M
    K[: spec.n_lat, : spec.n_lat] = spec.K
    C[: spec.n_lat, : spec.n_lat] = spec.C
    M[spec.i_theta, spec.i_theta] = spec.rotor_polar_inertia
    M[spec.i_axial, spec.i_axial] = spec.rotor_mass
    fvec = np.zeros(n_rot)
    fvec[: spec.n_lat] = spec.f_gravity
    frot = rotor_forces(spec, gyroscopic_in_user_function=False)
    G = np.zeros((n_rot, n_rot))
    G[: spec.n_lat, : spec.n_lat] = spec.G
    gyro = spec.rotor_laws.gyroscopic
    if gyro:
        C = C + spec.scenario.omega0 * G

    def rotor_uf(mbs_, t, item, q, q_t):
        return frot(t, q, q_t)

    # the rotor itself is linear (Exudyn differentiates it exactly); its state-dependent loads
    # (axial model, windage, drive, AMB, unbalance) sit in a zero-mass connector over the few
    # coordinates they use, so numerical Jacobians stay cheap
    rotor_extra = {}
    if analytic_jacobian:
        # with a jacobianUserFunction Exudyn adds K and D to the Jacobian directly; without one it
        # costs ~30 us per Jacobian for the 24 x 24 rotor (measured, tests/test_bearing_jacobian.py
        # checks both give the same system Jacobian)
        zeros_rot = np.zeros((n_rot, n_rot))

        def rotor_jac0(mbs_, t, item, q, q_t, fq, fv):
            return zeros_rot

        rotor_extra["jacobianUserFunction"] = rotor_jac0
    rotor_obj = mbs.AddObject(ObjectGenericODE2(nodeNumbers=lateral_nodes + [spin_node], massMatrix=M,
                                                stiffnessMatrix=K, dampingMatrix=C, forceVector=fvec.tolist(),
                                                **rotor_extra))
    need_lateral = rotor_loads_need_lateral(spec, False)
    merged = analytic_jacobian and merge_connectors
    if not merged or need_lateral:
        load_nodes = (lateral_nodes if need_lateral else []) + [spin_node]
        nl = (spec.n_lat if need_lateral else 0) + 2
        extra = {}
        if analytic_jacobian:
            jrot = rotor_loads_jacobian(spec, gyroscopic_in_user_function=False)

            def rotor_jac(mbs_, t, item, q, q_t, fq, fv):
                return jrot(t, q, q_t, fq, fv)

            extra["jacobianUserFunction"] = rotor_jac
        mbs.AddObject(ObjectGenericODE2(nodeNumbers=load_nodes, massMatrix=np.zeros((nl, nl)),
                                        stiffnessMatrix=np.zeros((nl, nl)), dampingMatrix=np.zeros((nl, nl)),
                                        forceVector=[0.0] * nl, forceUserFunction=rotor_uf, **extra))
    pre = PreStep(rotor_obj, spin_node, C - (spec.scenario.omega0 * G if gyro else 0.0), G, gyro)
    mbs.SetPreStepUserFunction(pre)

    race_outer = []
    for b in spec.bearings:
        p = b.params
        i = b.i_race
        race = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[0.0, 0.0, 0.0],
                                           initialCoordinates=q0[i:i + 3].tolist(),
                                           initialVelocities=v0[i:i + 3].tolist()))
        nodes.append((race, slice(i, i + 3)))
        mbs.AddObject(ObjectRigidBody2D(mass=p.inner_race_mass, inertia=p.inner_race_inertia,
                                        nodeNumber=race))
        outer = point(i + 3)
        mbs.AddObject(ObjectMassPoint2D(mass=p.outer_race_mass, nodeNumber=outer))
        race_outer.append((race, outer))

    def rub_tilt(b):
        return b.laws.axial_rub

    if merged:
        # one connector for all bearings (and the spin/axial rotor loads): one Python call per
        # residual, one analytic Jacobian call per Jacobian
        st_nodes = []
        for b in spec.bearings:
            nd = station_nodes[spec.stations.index(b.station)]
            if nd not in st_nodes:
                st_nodes.append(nd)
        ns = 2 * len(st_nodes)
        tilts = np.zeros((len(spec.bearings), 2))
        local = []
        for k, b in enumerate(spec.bearings):
            s0 = 2 * st_nodes.index(station_nodes[spec.stations.index(b.station)])
            r0 = ns + 2 + 5 * k
            local.append([s0, s0 + 1, ns, ns + 1, r0, r0 + 1, r0 + 2, r0 + 3, r0 + 4])
            if rub_tilt(b):
                tilts[k] = [float(b.tilt_alpha @ q0[: spec.n_lat]), float(b.tilt_beta @ q0[: spec.n_lat])]
                pre.tilts.append((tilts[k], b.tilt_alpha, b.tilt_beta, spec.n_lat))
        fl, jl = landing_functions(spec, local, tilts, include_rotor_loads=not need_lateral)
        if pre.tilts:
            rows = np.array([k for k, b in enumerate(spec.bearings) if rub_tilt(b)], dtype=np.int64)
            TA = np.array([np.ascontiguousarray(b.tilt_alpha, float) for b in spec.bearings if rub_tilt(b)])
            TB = np.array([np.ascontiguousarray(b.tilt_beta, float) for b in spec.bearings if rub_tilt(b)])
            args = (TA, TB, rows, spec.n_lat, tilts)
            pre.tilt_update = (direct(update_tilts, q0, *args), args)
        conn = st_nodes + [spin_node] + [nd for ro in race_outer for nd in ro]
        n = ns + 2 + 5 * len(spec.bearings)
        mbs.AddObject(ObjectGenericODE2(nodeNumbers=conn, massMatrix=np.zeros((n, n)),
                                        stiffnessMatrix=np.zeros((n, n)), dampingMatrix=np.zeros((n, n)),
                                        forceVector=[0.0] * n, forceUserFunction=fl, jacobianUserFunction=jl))
    else:
        for b, (race, outer) in zip(spec.bearings, race_outer):
            tilt = None
            if rub_tilt(b):
                tilt = [float(b.tilt_alpha @ q0[: spec.n_lat]), float(b.tilt_beta @ q0[: spec.n_lat])]
                pre.tilts.append((tilt, b.tilt_alpha, b.tilt_beta, spec.n_lat))
            lat = [station_nodes[spec.stations.index(b.station)]]
            extra = {}
            if analytic_jacobian:
                bearing_uf, extra["jacobianUserFunction"], _ = bearing_functions(spec, b, tilt)
            else:
                fb = bearing_forces(spec, b, tilt)

                def bearing_uf(mbs_, t, item, q, q_t, fb=fb):
                    return fb(t, q, q_t)

            n = len(BEARING_LOCAL)
            mbs.AddObject(ObjectGenericODE2(nodeNumbers=lat + [spin_node, race, outer], massMatrix=np.zeros((n, n)),
                                            stiffnessMatrix=np.zeros((n, n)), dampingMatrix=np.zeros((n, n)),
                                            forceVector=[0.0] * n, forceUserFunction=bearing_uf, **extra))

    # mechanisms of the registry outside the compiled kernel: one connector each per bearing where
    # active (an inactive one adds nothing, so the default model is unchanged); the plain-Python
    # bearing connectors (analytic_jacobian=False) already include them (forces.bearing_forces)
    for b, (race, outer) in zip(spec.bearings, race_outer):
        for m in (registry_forces(spec, b.laws) if analytic_jacobian else ()):
            fm, jm = mechanism_functions(m, b.laws)
            n = len(BEARING_LOCAL)
            extra = {"jacobianUserFunction": jm} if jm is not None else {}
            mbs.AddObject(ObjectGenericODE2(nodeNumbers=[station_nodes[spec.stations.index(b.station)], spin_node,
                                                         race, outer], massMatrix=np.zeros((n, n)),
                                            stiffnessMatrix=np.zeros((n, n)), dampingMatrix=np.zeros((n, n)),
                                            forceVector=[0.0] * n, forceUserFunction=fm, **extra))

    import exudyn as exu  # noqa: F811 (output types)

    sensors = []
    if accelerations is None:
        accelerations = spec.scenario.solver.step_control == "auto"
    accel_sensors = [] if accelerations else None
    for nd, sl in nodes:
        sp = mbs.AddSensor(SensorNode(nodeNumber=nd, storeInternal=True,
                                      outputVariableType=exu.OutputVariableType.Coordinates))
        sv = mbs.AddSensor(SensorNode(nodeNumber=nd, storeInternal=True,
                                      outputVariableType=exu.OutputVariableType.Coordinates_t))
        sensors.append((sp, sv, sl))
        if accelerations:
            accel_sensors.append((mbs.AddSensor(SensorNode(nodeNumber=nd, storeInternal=True,
                                                           outputVariableType=exu.OutputVariableType.Coordinates_tt)), sl))
    mbs.Assemble()
    if instrument is not None:
        mbs = mbs_real
    pre.sd = mbs.systemData
    return ExudynModel(SC, mbs, spec, nodes, sensors, pre, accel_sensors=accel_sensors)


def collect(model: ExudynModel) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Stored sensor data as (t, q[t, n], v[t, n]) in spec coordinate order. After an auto-step
    solve (every accepted step stored) the states are resampled onto the output grid of the fixed
    step, t_start + k * output_period (and the last step's time), by cubic Hermite interpolation:
    q from (q, v), v from (v, a) at the ends of each step (:func:`hermite_resample`), so the
    post-processing sees the same uniform samples either way."""
    mbs = model.mbs
    t = None
    q = v = a = None
    for sp, sv, sl in model.sensors:
        dp = mbs.GetSensorStoredData(sp)
        dv = mbs.GetSensorStoredData(sv)
        if t is None:
            t = dp[:, 0]
            q = np.zeros((len(t), model.spec.n))
            v = np.zeros((len(t), model.spec.n))
        k = sl.stop - sl.start
        q[:, sl] = dp[: len(t), 1: 1 + k]
        v[:, sl] = dv[: len(t), 1: 1 + k]
    if model.resample is None or t is None or len(t) < 2:
        return t, q, v
    a = np.zeros_like(q)
    for sa, sl in model.accel_sensors:
        da = mbs.GetSensorStoredData(sa)
        a[:, sl] = da[: len(t), 1: 1 + (sl.stop - sl.start)]
    t0, period = model.resample
    return hermite_resample(t, q, v, a, t0, period)


def hermite_resample(t, q, v, a, t0: float, period: float):
    """(t_out, q_out, v_out) on t0 + k period (k = 0, 1, ... up to t[-1]) plus t[-1] when it is off
    that grid, from states (q, v, a) at increasing times t: per interval, the cubic Hermite
    polynomial of q through (q, v) at both ends and that of v through (v, a) (errors O(h^4) of the
    step h, below the integrator's O(h^3) local error)."""
    keep = np.concatenate([[True], np.diff(t) > 0])  # a repeated time (the end sample) once
    t, q, v, a = t[keep], q[keep], v[keep], a[keep]
    n = int(np.floor((t[-1] - t0) / period + 1e-9))
    tg = t0 + period * np.arange(n + 1)
    if t[-1] - tg[-1] > 1e-9 * period:
        tg = np.append(tg, t[-1])
    tg = np.clip(tg, t[0], t[-1])
    j = np.clip(np.searchsorted(t, tg, side="right") - 1, 0, len(t) - 2)
    h = (t[j + 1] - t[j])[:, None]
    s = (tg[:, None] - t[j][:, None]) / h
    h00, h10 = 2 * s ** 3 - 3 * s ** 2 + 1, s ** 3 - 2 * s ** 2 + s
    h01, h11 = -2 * s ** 3 + 3 * s ** 2, s ** 3 - s ** 2
    qo = h00 * q[j] + h10 * h * v[j] + h01 * q[j + 1] + h11 * h * v[j + 1]
    vo = h00 * v[j] + h10 * h * a[j] + h01 * v[j + 1] + h11 * h * a[j + 1]
    return tg, qo, vo


def solve(model: ExudynModel, t_start: float, t_end: float, settings: SolverSettings):
    """Run the implicit solver; return (ok, message, stats)."""
    import exudyn as exu

    ss = settings.apply(exu, t_start, t_end)
    model.controller = model.resample = None
    pre = model.pre_step
    if settings.step_control == "auto":
        if model.accel_sensors is None:
            raise ValueError("auto step: build the model with accelerations=True (collect resamples with them)")
        model.controller = StepController(model.spec, settings)
        if pre is not None and pre.progress is None:
            # the pre-step's work (axial-face tilt, gyroscopic update) needs the start-of-step state,
            # which is the end of the last accepted step: done by the controller on acceptance, one
            # Python crossing per step less (same bits: forward-landing hash unchanged)
            pre(model.mbs, t_start)
            model.controller.pre_step = pre
            model.mbs.SetPreStepUserFunction(0)
            model.pre_step_detached = True
        model.mbs.SetPostNewtonUserFunction(model.controller)
        model.post_newton_set = True
        model.resample = (t_start, settings.output_period)
    else:  # a fixed-step solve after an auto-step one: the hooks as built
        if model.post_newton_set:
            model.mbs.SetPostNewtonUserFunction(0)
            model.post_newton_set = False
        if model.pre_step_detached:
            model.mbs.SetPreStepUserFunction(pre)
            model.pre_step_detached = False
    # Exudyn warns on stdout about per-step allocations of Python user functions (expected here);
    # our own progress and summary are the user-facing output
    exu.config.suppressWarnings = True
    console = exu.config.printToConsole
    exu.config.printToConsole = False
    wall0 = time.perf_counter()
    ok, msg = True, ""
    try:
        res = exu.SolveDynamic(model.mbs, ss)
        if res is False:
            ok, msg = False, "Exudyn solver did not converge"
    except Exception as exc:  # Exudyn raises RuntimeError/ValueError on divergence
        ok, msg = False, f"{type(exc).__name__}: {str(exc).strip().splitlines()[-1] if str(exc).strip() else ''}"
    finally:
        exu.config.printToConsole = console
    wall = time.perf_counter() - wall0
    it = model.mbs.sys["dynamicSolver"].it
    stats = {"wall_s": wall, "steps": int(it.currentStepIndex), "newton_iterations": int(it.newtonStepsCount),
             "jacobians": int(it.newtonJacobiCount), "t_reached": float(it.currentTime),
             "step_at_stop_s": float(it.currentStepSize)}
    if model.controller is not None:
        stats["rejected_steps"] = model.controller.rejected
        stats["accepted_steps"] = model.controller.accepted
    return ok, msg, stats
