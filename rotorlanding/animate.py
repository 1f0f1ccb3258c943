"""Offline picture of a finished landing run (``rotorlanding animate``, ``Landing.animate``).

Each frame has two parts, composed into one 1280 x 720 image (``size``):

* left, the machine in 3D, rendered by Exudyn's own software raytracer (headless: no display, no
  GPU, no OpenGL; ``SC.renderer.Start()`` would kill the process without a display, so it is never
  called): every shaft element of the rotor file as a cylinder on the deflected axis, the disks
  (lamination stacks, named ``*lamin*``, as a stack of sheets), the landing sleeves coloured by
  their contact force, and at each catcher bearing the inner race, the balls on their cage and the
  outer race (cut open at the top so the sleeve inside shows), with a red arrow pushing on the
  sleeve along the contact normal, its length proportional to the contact force. Lateral
  displacements and the radial clearance are magnified (factor on the frame); axial sizes are true.
* right (matplotlib), per catcher bearing the orbit of the journal relative to its inner race
  [um] with the clearance circle, the trace up to the frame's time coloured by contact force, the
  current position and the contact-force arrow; time, rotor speed and contact forces as text.

Writers by the output's suffix: ``.gif`` (Pillow), ``.mp4`` (H.264 through the ffmpeg binary of
``imageio-ffmpeg``: ``pip install '.[video]'``), ``.png`` (one still at ``at`` seconds). Every file
is written under a temporary name beside the target and renamed into place.

Frames: one every 1/fps simulated seconds from the first sample, the last at or before the last
sample: ``floor(duration * fps) + 1`` frames (capped at ``max_frames``, then evenly spread);
``play_fps`` is the movie's frame rate (slow motion = play_fps / fps).
"""

from __future__ import annotations

import math
import os
from pathlib import Path

import numpy as np

from .errors import InputError
from .safeio import check_out_file

SUFFIXES = (".gif", ".mp4", ".png")
#: s: the recent part of the orbit trace, drawn thick and coloured by contact force
RECENT_S = 0.04
#: left (3D) part's width as a share of the frame
_LEFT = 0.6


def frame_indices(t: np.ndarray, fps: float, max_frames: int | None = None) -> np.ndarray:
    """Sample indices of the frames: one per 1/fps simulated seconds (see module doc)."""
    dur = float(t[-1] - t[0])
    n = int(math.floor(dur * fps * (1 + 1e-12))) + 1
    n = max(n, 2)
    if max_frames:
        n = min(n, max_frames)
    if n == int(math.floor(dur * fps * (1 + 1e-12))) + 1:
        targets = t[0] + np.arange(n) / fps
    else:
        targets = np.linspace(t[0], t[-1], n)
    return np.searchsorted(t, targets - 1e-12).clip(0, len(t) - 1)


def _disk_geometry(raw: dict, disk) -> tuple[float, float, float]:
    """(outer radius, inner radius, thickness) [m] of a disk: as written in the rotor file, or the
    solid disk of the same mass and inertias (r = sqrt(2 Ip / m), t from It = m (3 r^2 + t^2) / 12)."""
    if raw.get("outer_diameter") and raw.get("thickness"):
        return 0.5 * float(raw["outer_diameter"]), 0.5 * float(raw.get("inner_diameter", 0.0)), float(raw["thickness"])
    if disk.mass <= 0 or disk.polar_inertia <= 0:
        return 0.0, 0.0, 0.0
    r = math.sqrt(2.0 * disk.polar_inertia / disk.mass)
    t2 = 12.0 * disk.transverse_inertia / disk.mass - 3.0 * r * r
    return r, 0.0, math.sqrt(t2) if t2 > (0.05 * r) ** 2 else 0.1 * r


def _check(results_path, out_path, fps, view, max_frames, play_fps, size, at):
    results_path = Path(results_path)
    if not results_path.is_file():
        raise InputError("results", str(results_path), "file not found (give a results.h5 written by rotorlanding run)")
    out_path = Path(out_path)
    if out_path.suffix.lower() not in SUFFIXES:
        raise InputError("--out", str(out_path), "must end in .gif, .mp4 or .png (one still frame)")
    if out_path.is_dir() or not out_path.parent.is_dir():
        raise InputError("--out", str(out_path), "must be a file in an existing folder")
    check_out_file(out_path, "--out")
    if not isinstance(view, str) or not view:
        raise InputError("--view", view, "must be all, rotor or the name of a catcher bearing of the run (e.g. DE)")
    if not (isinstance(fps, (int, float)) and fps > 0 and math.isfinite(fps)):
        raise InputError("--fps", fps, "must be > 0 (frames per simulated second)")
    if not (isinstance(play_fps, (int, float)) and 0 < play_fps <= 120):
        raise InputError("--play-fps", play_fps, "must be > 0 and <= 120 (frames per second of the movie)")
    if max_frames is not None and max_frames < 2:
        raise InputError("--max-frames", max_frames, "must be >= 2")
    w, h = size
    if not (320 <= w <= 3840 and 240 <= h <= 2160) or w % 2 or h % 2:
        raise InputError("--size", f"{w}x{h}", "must be even numbers within 320x240 .. 3840x2160")
    if at is not None and not math.isfinite(at):
        raise InputError("--at", at, "must be a time in seconds")
    if out_path.suffix.lower() == ".mp4":
        try:
            import imageio_ffmpeg  # noqa: F401
        except ImportError:
            raise InputError("--out", str(out_path), "MP4 needs imageio-ffmpeg: pip install 'rotorlanding[video]' "
                             "(or write .gif)") from None
    return results_path, out_path


class _Scene:
    """The 3D part: a visualisation-only Exudyn system whose one ground object draws the frame."""

    def __init__(self, spec, raw_rotor: dict, series: dict, q: np.ndarray, size: tuple[int, int], f_max: float):
        import exudyn as exu
        import exudyn.graphics as gr
        from exudyn.itemInterface import ObjectGround, VObjectGround
        from matplotlib import colormaps
        from matplotlib.colors import ListedColormap

        self.gr, self.spec, self.q = gr, spec, q
        # YlOrRd without its palest eighth, so that a sleeve without contact is still visibly coloured;
        # one map for the sleeves, the orbit traces and the colour bar
        self.cmap = ListedColormap(colormaps["YlOrRd"](np.linspace(0.15, 1.0, 256)))
        self.f_max = f_max
        fe, rotor = spec.fe, spec.fe.rotor
        self.x = fe.nodes
        self.nl = spec.n_lat
        self.T = spec.cb.T
        L = float(self.x[-1] - self.x[0])
        clear = max(b.params.clearance for b in spec.bearings)
        # the clearance drawn as 1.2 % of the rotor length (~16 mm on the rig's 1.3 m rotor)
        self.mag = 0.012 * L / clear
        # per element: radius and its section; sleeves = the sections holding a bearing's station
        starts = np.concatenate([[0.0], np.cumsum([s.length for s in rotor.sections])])
        mids = 0.5 * (self.x[1:] + self.x[:-1])
        self.owner = np.clip(np.searchsorted(starts, mids) - 1, 0, len(rotor.sections) - 1)
        self.radius = []
        for e, si in enumerate(self.owner):
            sec = rotor.sections[si]
            xi = (mids[e] - starts[si]) / sec.length
            self.radius.append(0.5 * max(p.diameters(xi)[0] for p in sec.parts))
        self.sleeve_of = {}
        for b in spec.bearings:
            xs = rotor.stations[b.station]
            si = int(np.clip(np.searchsorted(starts, xs, side="right") - 1, 0, len(rotor.sections) - 1))
            self.sleeve_of[si] = b.name
        raw_disks = list(raw_rotor.get("disks", []) or [])
        self.disks = []
        for j, d in enumerate(rotor.disks):
            ro, ri, th = _disk_geometry(raw_disks[j] if j < len(raw_disks) else {}, d)
            if ro > 0:
                self.disks.append((fe.disk_nodes[d.name], ro, ri, th, "lamin" in d.name.lower()))
        self.normal = {b.name: series.get(f"{b.name}_normal_force_n") for b in spec.bearings}
        self.k = 0

        SC = exu.SystemContainer()
        mbs = SC.AddSystem()
        vs = SC.visualizationSettings
        vs.window.renderWindowSize = [int(size[0]), int(size[1])]
        for key in ("drawCoordinateSystem", "drawWorldBasis", "showSolverInformation", "showComputationInfo",
                    "showSolutionInformation"):
            setattr(vs.general, key, False)
        vs.general.renderWindowString = ""
        vs.raytracer.advanced.showText = False
        vs.general.backgroundColor = [1.0, 1.0, 1.0, 1.0]
        mbs.AddObject(ObjectGround(visualization=VObjectGround(graphicsDataUserFunction=lambda m, i: self.graphics())))
        mbs.Assemble()
        # camera: from the front (-y), 25 deg above, the axis turned 28 deg
        a, b = math.radians(-65.0), math.radians(-28.0)
        rx = np.array([[1, 0, 0], [0, math.cos(a), -math.sin(a)], [0, math.sin(a), math.cos(a)]])
        rz = np.array([[math.cos(b), -math.sin(b), 0], [math.sin(b), math.cos(b), 0], [0, 0, 1]])
        centre = [float(self.x[0]) + 0.44 * L, 0.0, 0.0]
        SC.renderer.SetState({"centerPoint": centre, "maxSceneSize": 1.2 * L, "zoom": 0.55 * L,
                              "modelRotation": (rx @ rz).T})
        self.SC, self.mbs = SC, mbs  # keep mbs alive: its graphics user function dies with it

    def deflection(self, k: int):
        full = self.T @ self.q[k, :self.nl]
        return full[0::4] * self.mag, full[1::4] * self.mag

    def force_colour(self, f: float) -> list:
        c = self.cmap(min(1.0, max(0.0, f / self.f_max)))
        return [float(c[0]), float(c[1]), float(c[2]), 1.0]

    def graphics(self) -> list:
        gr, spec, k = self.gr, self.spec, self.k
        qk = self.q[k]
        y, z = self.deflection(k)
        x = self.x
        steel = [0.62, 0.64, 0.68, 1.0]
        g = []
        fk = {n: (float(s[k]) if s is not None else 0.0) for n, s in self.normal.items()}
        for e, si in enumerate(self.owner):
            p0 = [float(x[e]), float(y[e]), float(z[e])]
            v = [float(x[e + 1] - x[e]), float(y[e + 1] - y[e]), float(z[e + 1] - z[e])]
            name = self.sleeve_of.get(int(si))
            col = self.force_colour(fk[name]) if name else steel
            g.append(gr.Cylinder(pAxis=p0, vAxis=v, radius=self.radius[e], color=col, nTiles=24))
        for node, ro, ri, th, lam in self.disks:
            i0, i1 = max(node - 1, 0), min(node + 1, len(x) - 1)
            ax = np.array([x[i1] - x[i0], y[i1] - y[i0], z[i1] - z[i0]])
            ax /= np.linalg.norm(ax)
            c = np.array([x[node], y[node], z[node]])
            if lam:  # a lamination stack: thin sheets, alternately dark and light
                n = 10
                for j in range(n):
                    p = c + ax * th * (j / n - 0.5)
                    g.append(gr.Cylinder(pAxis=list(p), vAxis=list(ax * th / n), radius=ro,
                                         color=[0.25, 0.27, 0.32, 1.0] if j % 2 else [0.45, 0.47, 0.52, 1.0], nTiles=32))
            else:
                g.append(gr.Cylinder(pAxis=list(c - 0.5 * th * ax), vAxis=list(th * ax), radius=ro,
                                     color=[0.45, 0.55, 0.7, 1.0], nTiles=48))
        for b in spec.bearings:
            g += self.bearing(b, qk, fk[b.name])
        return g

    def bearing(self, b, qk, force: float) -> list:
        gr, m = self.gr, self.mag
        p = b.params
        xs = float(self.spec.fe.nodes[self.spec.fe.station_nodes[b.station]])
        gap = m * p.clearance
        R = p.sleeve_radius + gap                     # drawn bore of the inner race
        rp = 0.5 * p.pitch_diameter + gap             # drawn pitch radius
        rb = 0.45 * (0.5 * p.pitch_diameter - p.sleeve_radius - p.clearance)   # ball radius
        w = 2.2 * rb                                  # race width
        ri = np.array([m * qk[b.i_race], m * qk[b.i_race + 1]])
        ro = np.array([m * qk[b.i_outer], m * qk[b.i_outer + 1]])
        cut = [0.5 * math.pi, 2.5 * math.pi - 0.9]    # cut open at the top, towards the viewer
        out = [gr.Cylinder(pAxis=[xs - w / 2, ri[0], ri[1]], vAxis=[w, 0, 0], radius=rp - 0.8 * rb, radiusInner=R,
                           color=[0.8, 0.8, 0.82, 1.0], nTiles=64, angleRange=cut),
               gr.Cylinder(pAxis=[xs - w / 2, ro[0], ro[1]], vAxis=[w, 0, 0], radius=rp + 2.2 * rb,
                           radiusInner=rp + 0.8 * rb, color=[0.35, 0.5, 0.8, 1.0], nTiles=64, angleRange=cut)]
        # balls: on the cage, which turns at (1 - d/D)/2 of the inner race's angle
        cage = 0.5 * (1.0 - 2.0 * rb / p.pitch_diameter) * qk[b.i_race + 2]
        nb = max(6, int(math.pi * p.pitch_diameter / (2.6 * rb)))
        cb = 0.5 * (ri + ro)
        for j in range(nb):
            a = cage + 2 * math.pi * j / nb
            out.append(gr.Sphere(point=[xs, cb[0] + rp * math.cos(a), cb[1] + rp * math.sin(a)], radius=rb,
                                 color=[0.15, 0.15, 0.18, 1.0], nTiles=12))
        # contact force on the sleeve: an arrow from outside the bearing onto the contact point
        s = self.spec.fe.station_nodes[b.station]
        e = np.array([m * qk[b.i_station], m * qk[b.i_station + 1]]) - ri
        if force > 0 and np.linalg.norm(e) > 0:
            n = e / np.linalg.norm(e)
            tip = ri + n * (rp + 2.3 * rb)
            length = 0.25 * (self.x[-1] - self.x[0]) * force / self.f_max
            tail = tip + n * length
            out.append(gr.Arrow(pAxis=[xs, tail[0], tail[1]], vAxis=[0, tip[0] - tail[0], tip[1] - tail[1]],
                                radius=0.009, color=[1.0, 0.1, 0.05, 1.0]))
        del s
        return out

    def render(self, k: int) -> np.ndarray:
        self.k = int(k)
        return np.asarray(self.SC.renderer.RedrawAndGetImage(useRaytracer=True), dtype=np.uint8)


class _Frame:
    """Matplotlib figure holding the 3D image and the orbit panels; updated in place per frame."""

    def __init__(self, spec, series, t, size, view, scene, title):
        from matplotlib.figure import Figure
        from matplotlib.backends.backend_agg import FigureCanvasAgg
        from matplotlib.collections import LineCollection
        from matplotlib.colors import Normalize
        from matplotlib.cm import ScalarMappable

        w, h = size
        # laid out at 12.8 in wide: the text keeps its share of the frame at any --size
        self.size = (int(w), int(h))
        self.fig = Figure(figsize=(12.8, 12.8 * h / w), dpi=w / 12.8, facecolor="white")
        self.canvas = FigureCanvasAgg(self.fig)
        self.t, self.series, self.scene = t, series, scene
        bearings = spec.bearings if view in ("all", "rotor") else [b for b in spec.bearings if b.name == view]
        if view == "rotor":
            bearings = []
        left = _LEFT if bearings else 1.0
        self.ax3d = self.fig.add_axes([0, 0, left, 1])
        self.ax3d.set_axis_off()
        self.img = self.ax3d.imshow(np.ones((int(h), int(w * left), 3), dtype=np.uint8) * 255, interpolation="none")
        self.title = self.fig.text(0.01, 0.975, title, fontsize=12, weight="bold", va="top")
        self.clock = self.fig.text(0.01, 0.93, "", fontsize=12, va="top", family="monospace")
        self.fig.text(0.01, 0.015, f"lateral displacements and radial clearance x{scene.mag:.0f}; axial sizes true. "
                      "Sleeve colour and red arrows: contact force", fontsize=8.5, color="0.3")
        norm = Normalize(0.0, scene.f_max / 1e3)
        self.cnorm = Normalize(0.0, scene.f_max)
        self.cmap = scene.cmap
        cax = self.fig.add_axes([0.015, 0.09, 0.16, 0.018])
        cb = self.fig.colorbar(ScalarMappable(norm=norm, cmap=scene.cmap), cax=cax, orientation="horizontal")
        cb.set_label("contact force [kN]", fontsize=8.5)
        cb.ax.tick_params(labelsize=8)
        self.panels = []
        n = len(bearings)
        xb = {bb.name: spec.fe.rotor.stations[bb.station] for bb in spec.bearings}
        side = {k: ("left" if v == min(xb.values()) else "right" if v == max(xb.values()) else "middle")
                for k, v in xb.items()} if len(xb) > 1 else {}
        for j, b in enumerate(bearings):
            hgt = 0.88 / max(n, 1) - 0.115
            ax = self.fig.add_axes([left + 0.07, 0.07 + (n - 1 - j) * (hgt + 0.115), 0.92 - left - 0.06, hgt])
            c = b.params.clearance * 1e6
            ey = (series[f"{b.name}_y_m"] - series[f"{b.name}_race_y_m"]) * 1e6
            ez = (series[f"{b.name}_z_m"] - series[f"{b.name}_race_z_m"]) * 1e6
            f = series.get(f"{b.name}_normal_force_n", np.zeros_like(ey))
            th = np.linspace(0, 2 * np.pi, 361)
            ax.plot(c * np.cos(th), c * np.sin(th), color="0.15", lw=1.4, ls="--")
            ax.annotate(f"clearance\n{c:.0f} um", (c * math.cos(0.8), c * math.sin(0.8)),
                        xytext=(0.80, 0.97), textcoords="axes fraction", fontsize=8.5, va="top",
                        arrowprops=dict(arrowstyle="-", color="0.4", lw=0.8))
            ax.axhline(0, color="0.85", lw=0.6, zorder=0)
            ax.axvline(0, color="0.85", lw=0.6, zorder=0)
            lim = 1.3 * max(c, float(np.max(np.hypot(ey, ez))))
            ax.set_xlim(-lim, lim)
            ax.set_ylim(-lim, lim)
            ax.set_aspect("equal")
            ax.tick_params(labelsize=8)
            ax.set_xlabel("y [um] (horizontal)", fontsize=9)
            ax.set_ylabel("z [um] (up)", fontsize=9)
            where = f" ({side[b.name]} in 3D)" if b.name in side else ""
            ax.set_title(f"{b.name}{where}: journal relative to its inner race\n(last {RECENT_S * 1e3:.0f} ms in colour)",
                         fontsize=9.5)
            old, = ax.plot([], [], color="0.72", lw=0.6)
            lc = LineCollection([], cmap=scene.cmap, norm=self.cnorm, linewidths=2.0)
            ax.add_collection(lc)
            dot, = ax.plot([], [], "o", ms=7, mfc="tab:blue", mec="k", zorder=5)
            arrow = ax.annotate("", xy=(0, 0), xytext=(0, 0),
                                arrowprops=dict(arrowstyle="-|>", color=(0.85, 0.05, 0.05), lw=2.2), zorder=6)
            label = ax.text(0.02, 0.03, "", transform=ax.transAxes, fontsize=9, family="monospace")
            self.panels.append(dict(name=b.name, c=c, ax=ax, ey=ey, ez=ez, f=f, lc=lc, old=old, dot=dot, arrow=arrow, label=label, lim=lim))
        self.speed = series.get("rotor_speed_rpm")

    def circles(self) -> dict:
        """Per bearing the clearance circle in the frame's pixels: [column, row, radius]."""
        h = self.fig.bbox.height
        out = {}
        for p in self.panels:
            (x0, y0), (x1, _) = p["ax"].transData.transform([(0.0, 0.0), (p["c"], 0.0)])
            out[p["name"]] = [float(x0), float(h - y0), float(x1 - x0)]
        return out

    def draw(self, k: int, image: np.ndarray) -> np.ndarray:
        self.img.set_data(image)
        sp = f"   rotor {self.speed[k]:7.0f} rpm" if self.speed is not None else ""
        self.clock.set_text(f"t = {self.t[k]:.4f} s{sp}")
        for p in self.panels:
            ey, ez, f = p["ey"][:k + 1], p["ez"][:k + 1], p["f"][:k + 1]
            step = max(1, len(ey) // 4000)
            p["old"].set_data(ey[::step], ez[::step])
            # the last RECENT_S seconds in colour (contact force), thick; the earlier path thin grey
            j0 = int(np.searchsorted(self.t, self.t[k] - RECENT_S))
            pts = np.column_stack([ey[j0:], ez[j0:]])
            if len(pts) > 1:
                p["lc"].set_segments(np.stack([pts[:-1], pts[1:]], axis=1))
                p["lc"].set_array(np.maximum(f[j0 + 1:], 0.0))
            p["dot"].set_data([ey[-1]], [ez[-1]])
            fk = float(f[-1])
            r = math.hypot(ey[-1], ez[-1])
            if fk > 0 and r > 0:  # force on the journal: from the contact point towards the centre
                n = np.array([ey[-1], ez[-1]]) / r
                ln = p["lim"] * (0.15 + 0.5 * fk / self.cnorm.vmax)
                p["arrow"].xy = tuple(np.array([ey[-1], ez[-1]]) - n * ln)
                p["arrow"].set_position((ey[-1], ez[-1]))
                p["arrow"].set_visible(True)
            else:
                p["arrow"].set_visible(False)
            p["label"].set_text(f"contact {fk / 1e3:5.2f} kN")
        self.canvas.draw()
        rgb = np.asarray(self.canvas.buffer_rgba())[:, :, :3]
        if rgb.shape[:2] != (self.size[1], self.size[0]):  # a pixel lost to rounding of the dpi
            from PIL import Image

            rgb = np.asarray(Image.fromarray(rgb).resize(self.size))
        return rgb.copy()


class _Writer:
    """GIF / MP4 / PNG under a temporary name, renamed into place by ``close``."""

    def __init__(self, path: Path, size, play_fps: float):
        from .safeio import tmp_name

        self.path, self.kind, self.fps = path, path.suffix.lower(), play_fps
        self.tmp = tmp_name(path, "part" + self.kind)  # keeps the suffix for ffmpeg
        self.frames, self.n = [], 0
        if self.kind == ".mp4":
            import imageio_ffmpeg

            self.gen = imageio_ffmpeg.write_frames(str(self.tmp), tuple(size), fps=play_fps, codec="libx264",
                                                   pix_fmt_out="yuv420p", quality=8, macro_block_size=2,
                                                   output_params=["-f", "mp4"])
            self.gen.send(None)

    def add(self, rgb: np.ndarray) -> None:
        self.n += 1
        if self.kind == ".mp4":
            self.gen.send(np.ascontiguousarray(rgb))
        else:
            from PIL import Image

            im = Image.fromarray(rgb)
            self.frames.append(im if self.kind == ".png" else im.quantize(colors=255, method=Image.Quantize.MEDIANCUT))

    def abort(self) -> None:
        """Drop the partial file (an error or Ctrl-C while rendering)."""
        try:
            if self.kind == ".mp4":
                self.gen.close()
        except Exception:
            pass
        try:
            self.tmp.unlink()
        except OSError:
            pass

    def close(self) -> None:
        from .safeio import fsync_dir, fsync_path

        try:
            if self.kind == ".mp4":
                self.gen.close()
            elif self.kind == ".png":
                self.frames[0].save(self.tmp, format="PNG")
            else:
                self.frames[0].save(self.tmp, format="GIF", save_all=True, append_images=self.frames[1:],
                                    duration=int(round(1000 / self.fps)), loop=0)
            fsync_path(self.tmp)
            os.replace(self.tmp, self.path)
        except BaseException:
            try:
                self.tmp.unlink()
            except OSError:
                pass
            raise
        fsync_dir(self.path.parent)


def animate(results_path, out_path, *, fps: float = 20.0, view: str = "all", max_frames: int | None = None,
            play_fps: float = 20.0, size: tuple[int, int] = (1280, 720), at: float | None = None) -> dict:
    """Render a run's ``results.h5`` into ``out_path`` (.gif, .mp4 or .png; see the module doc).

    fps: frames per simulated second; play_fps: frames per second of the movie; view: ``all``
    (3D and every bearing's orbit), a bearing name (3D and its orbit) or ``rotor`` (3D only);
    size: (width, height) in pixels; at: time [s] of the still for a .png (default the last sample).
    Returns {"frames", "file", "magnification", "times_s", "clearance_circles_px" ({bearing:
    [column, row, radius]} of each clearance circle in the frame), "left_width_px" (the 3D part)}."""
    if view == "DE_NDE":
        view = "all"
    results_path, out_path = _check(results_path, out_path, fps, view, max_frames, play_fps, size, at)

    from .landing import build_spec
    from .readers import read_results_guarded
    from .scenario import scenario_from_dict

    res = read_results_guarded(results_path, ("scenario", "time_s", "q", "series"))
    scenario = scenario_from_dict(res["scenario"], source=str(results_path))
    spec = build_spec(scenario)
    if view not in ("all", "rotor") and view not in spec.bearing_names:
        raise InputError("--view", view, f"must be all, rotor or one of this run's bearings: {', '.join(spec.bearing_names)}")
    t, q, series = res["time_s"], res["q"], res["series"]
    if len(t) < 2 or q.shape[1] != len(spec.names) or q.shape[0] != len(t):
        # a results file whose states do not belong to its stored scenario cannot be replayed
        raise InputError("states/q", f"shape {q.shape}", f"must hold >= 2 samples of the scenario's "
                         f"{len(spec.names)} coordinates", file=str(results_path))
    for b in spec.bearings:
        for key in (f"{b.name}_y_m", f"{b.name}_z_m", f"{b.name}_race_y_m", f"{b.name}_race_z_m"):
            if key not in series or len(series[key]) != len(t):
                raise InputError(f"series/{key}", "missing" if key not in series else f"length {len(series[key])}",
                                 f"must be a series of {len(t)} samples", file=str(results_path))
    if out_path.suffix.lower() == ".png":
        ta = float(t[-1]) if at is None else at
        if not t[0] <= ta <= t[-1]:
            raise InputError("--at", at, f"must lie within the run, {t[0]:g} .. {t[-1]:g} s")
        idx = np.array([min(int(np.searchsorted(t, ta - 1e-12)), len(t) - 1)])
    else:
        idx = frame_indices(t, fps, max_frames)

    forces = [series[f"{b.name}_normal_force_n"] for b in spec.bearings if f"{b.name}_normal_force_n" in series]
    f_max = max([float(np.max(f)) for f in forces] + [1.0])
    w, h = int(size[0]), int(size[1])
    has_panels = view != "rotor"
    wl = w if not has_panels else int(round(w * _LEFT))
    scene = _Scene(spec, res["scenario"].get("rotor", {}), series, q, (wl, h), f_max)
    name = res.get("attrs", {}).get("scenario_name") or res["scenario"].get("name") or results_path.parent.name
    frame = _Frame(spec, series, t, (w, h), view, scene, str(name))
    writer = _Writer(out_path, (w, h), play_fps)
    try:
        for k in idx:
            img = scene.render(k)
            if img.shape[:2] != (h, wl):
                from PIL import Image

                img = np.asarray(Image.fromarray(img).resize((wl, h)))
            writer.add(frame.draw(int(k), img))
    except BaseException:
        writer.abort()
        raise
    writer.close()
    return {"frames": writer.n, "file": str(out_path), "magnification": scene.mag,
            "times_s": [float(t[k]) for k in idx], "clearance_circles_px": frame.circles(),
            "left_width_px": wl}
