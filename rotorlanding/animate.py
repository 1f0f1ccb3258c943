"""Offline Exudyn visualisation of a finished landing run (``rotorlanding animate``).

The stored states of ``results.h5`` are replayed in a visualisation-only Exudyn system and each
frame is rendered with Exudyn's software raytracer (works without a display; never call
``SC.renderer.Start()`` headless). Frames are assembled into a GIF with Pillow (a matplotlib
dependency).

Views: ``DE`` / ``NDE`` — the bearing seen along the rotor axis: outer race (blue), inner race
(grey, with a spin marker), rotor sleeve (red, with a spin marker) and the journal's orbit trace
so far; displacements are magnified so that the radial clearance is drawn as 20 % of the bore
radius (the factor is written on every frame). ``rotor`` — side view of the rotor's deflected axis
(vertical plane, magnified) with the two landing sleeves and their clearance band.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from .errors import InputError


def _frames(t: np.ndarray, fps: float, max_frames: int | None) -> np.ndarray:
    n = max(2, int(round((t[-1] - t[0]) * fps)) + 1)
    if max_frames:
        n = min(n, max_frames)
    targets = np.linspace(t[0], t[-1], n)
    return np.unique(np.searchsorted(t, targets).clip(0, len(t) - 1))


def animate(results_path, out_path, *, fps: float = 20.0, view: str = "DE", max_frames: int | None = None,
            size: tuple[int, int] = (480, 480)) -> dict:
    results_path = Path(results_path)
    if not results_path.is_file():
        raise InputError("results", str(results_path), "file not found (give a results.h5 written by rotorlanding run)")
    if not isinstance(view, str) or not view:
        raise InputError("--view", view, "must be rotor or the name of a catcher bearing of the run (e.g. DE)")
    if not fps > 0:
        raise InputError("--fps", fps, "must be > 0")
    if max_frames is not None and max_frames < 2:
        raise InputError("--max-frames", max_frames, "must be >= 2")

    import exudyn as exu
    import exudyn.graphics as gr
    from exudyn.itemInterface import NodeRigidBody2D, ObjectGround, ObjectRigidBody2D, VObjectGround, VObjectRigidBody2D
    from PIL import Image, ImageDraw

    from .landing import build_spec
    from .readers import read_results_guarded
    from .scenario import scenario_from_dict

    res = read_results_guarded(results_path, ("scenario", "time_s", "q"))
    spec = build_spec(scenario_from_dict(res["scenario"], source=str(results_path)))
    if view != "rotor" and view not in spec.bearing_names:
        raise InputError("--view", view, f"must be rotor or one of this run's bearings: {', '.join(spec.bearing_names)}")
    t, q = res["time_s"], res["q"]
    if len(t) < 2 or q.shape[1] != len(spec.names):
        # a results file whose states do not belong to its stored scenario cannot be replayed
        raise InputError("states/q", f"shape {q.shape}", f"must hold >= 2 samples of the scenario's "
                         f"{len(spec.names)} coordinates", file=str(results_path))
    idx = _frames(t, fps, max_frames)

    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    vs = SC.visualizationSettings
    vs.window.renderWindowSize = list(size)
    vs.general.drawCoordinateSystem = False
    vs.general.drawWorldBasis = False
    vs.general.showSolverInformation = False
    vs.general.showComputationInfo = False
    vs.general.showSolutionInformation = False
    state = {"k": 0}
    nodes = []

    if view != "rotor":
        b = next(bb for bb in spec.bearings if bb.name == view)
        p = b.params
        R = p.race_radius
        mag = 0.2 * R / p.clearance
        r_sleeve = R - mag * p.clearance
        z0 = 0.0

        def body(radius, color, height, marker):
            nd = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[0.0, 0.0, 0.0]))
            g = [gr.Cylinder(pAxis=[0, 0, z0 + height], vAxis=[0, 0, 0.002], radius=radius, color=color, nTiles=64)]
            if marker:
                g.append(gr.Brick(centerPoint=[0.5 * radius, 0, z0 + height + 0.0025], size=[radius, 0.08 * R, 0.001],
                                  color=gr.color.black))
            mbs.AddObject(ObjectRigidBody2D(nodeNumber=nd, mass=1.0, inertia=1.0,
                                            visualization=VObjectRigidBody2D(graphicsData=g)))
            nodes.append(nd)

        body(1.45 * R, [0.55, 0.7, 0.95, 1.0], 0.000, False)   # outer race
        body(1.2 * R, [0.75, 0.75, 0.75, 1.0], 0.003, True)    # inner race, bore = R
        mbs.AddObject(ObjectGround(visualization=VObjectGround(graphicsData=[
            gr.Cylinder(pAxis=[0, 0, 0.006], vAxis=[0, 0, 0.001], radius=R, color=[1, 1, 1, 1], nTiles=64)])))
        body(r_sleeve, [0.9, 0.2, 0.2, 1.0], 0.008, True)      # rotor sleeve
        s, r, o = b.i_station, b.i_race, b.i_race + 3
        ys, zs = q[:, s] * mag, q[:, s + 1] * mag

        def trace(mbs_, item):
            k = state["k"]
            pts = [[ys[j], zs[j], 0.0125] for j in range(0, k + 1, max(1, k // 400))]
            if len(pts) < 2:
                pts = [[ys[0], zs[0], 0.0125], [ys[0] + 1e-9, zs[0], 0.0125]]
            return [gr.Lines(pts, color=gr.color.black)]

        mbs.AddObject(ObjectGround(visualization=VObjectGround(graphicsDataUserFunction=trace)))

        def coords(k):
            qk = q[k]
            return [mag * qk[o], mag * qk[o + 1], 0.0,
                    mag * qk[r], mag * qk[r + 1], qk[r + 2],
                    mag * qk[s], mag * qk[s + 1], qk[spec.i_theta]]

        label = f"{view} bearing, displacements x{mag:.0f}"
        span = 1.5 * R
    else:
        x = spec.fe.nodes
        nl = spec.n_lat
        T = spec.cb.T
        clear = max(bb.params.clearance for bb in spec.bearings)
        L = float(x[-1] - x[0])
        zmax = max(clear, float(np.max(np.abs((q[idx, :nl] @ T.T)[:, 1::4]))))
        mag = 0.15 * L / zmax
        stations = [(spec.fe.nodes[spec.fe.station_nodes[bb.station]], bb.params.clearance) for bb in spec.bearings]

        def shape(mbs_, item):
            k = state["k"]
            full = T @ q[k, :nl]
            z = full[1::4] * mag
            g = [gr.Lines([[float(xi), float(zi), 0.0] for xi, zi in zip(x, z)], color=gr.color.red)]
            for xs, c in stations:
                for sgn in (-1, 1):
                    g.append(gr.Lines([[xs - 0.03 * L, sgn * c * mag, 0.0], [xs + 0.03 * L, sgn * c * mag, 0.0]],
                                      color=gr.color.blue))
            g.append(gr.Lines([[float(x[0]), 0.0, -0.001], [float(x[-1]), 0.0, -0.001]], color=[0.6, 0.6, 0.6, 1]))
            return g

        mbs.AddObject(ObjectGround(visualization=VObjectGround(graphicsDataUserFunction=shape)))

        def coords(k):
            return []

        label = f"rotor side view (vertical plane), deflection x{mag:.0f}"
        span = 0.6 * L

    mbs.Assemble()
    center = [0.0, 0.0, 0.0] if view != "rotor" else [float(spec.fe.nodes[-1]) / 2, 0.0, 0.0]
    SC.renderer.SetState({"centerPoint": center, "maxSceneSize": 2 * span, "zoom": span})
    images = []
    for k in idx:
        state["k"] = int(k)
        c = coords(k)
        if c:
            mbs.systemData.SetODE2Coordinates(c, configuration=exu.ConfigurationType.Current)
        img = SC.renderer.RedrawAndGetImage(useRaytracer=True)
        im = Image.fromarray(np.asarray(img, dtype=np.uint8)).convert("RGB")
        if im.size != tuple(size):
            im = im.resize(tuple(size))
        ImageDraw.Draw(im).text((8, 8), f"t = {t[k]:.4f} s   {label}", fill=(0, 0, 0))
        images.append(im.convert("P", palette=Image.ADAPTIVE))
    out_path = Path(out_path)
    images[0].save(out_path, save_all=True, append_images=images[1:], duration=int(1000 / fps), loop=0)
    return {"frames": len(images), "file": str(out_path), "magnification": mag}

