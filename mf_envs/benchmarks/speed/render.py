"""Frame cost of the renderer: PIL ImageDraw + own projection vs matplotlib Agg (mplot3d).

Both candidates draw the SAME meshes (`mf_envs.render.meshes`, same colours and Lambert shading)
at the same 360x480 output with a HUD line; matplotlib gets its most favourable use (one figure
reused, only the Poly3DCollection replaced, `canvas.draw()` + `buffer_rgba()` per frame).
The ratio is PIL frames/s over matplotlib frames/s, timed alternately frame by frame.
"""

from __future__ import annotations

import time
from collections.abc import Callable

import numpy as np

from mf_envs.frames import exp_so3, rot_x
from mf_envs.render import draw_gowec, draw_inchworm, draw_rigid_body, draw_ship, meshes
from mf_envs.render.projection import Mesh, _normals, shade
from mf_envs.render.scenes3d import ship_meshes

SIZE = (360, 480)
REFERENCE = "matplotlib Agg mplot3d (reused figure)"


class MplCandidate:
    """matplotlib's way to draw the same scene: Poly3DCollection on a reused Agg figure."""

    def __init__(self, extent: float, elev: float, azim: float) -> None:
        from matplotlib.backends.backend_agg import FigureCanvasAgg
        from matplotlib.figure import Figure

        self.fig = Figure(figsize=(SIZE[1] / 100, SIZE[0] / 100), dpi=100)
        FigureCanvasAgg(self.fig)
        self.ax = self.fig.add_axes((0, 0, 1, 1), projection="3d")
        self.ax.view_init(elev=elev, azim=azim)
        for lim in (self.ax.set_xlim, self.ax.set_ylim, self.ax.set_zlim):
            lim(-extent, extent)
        self.ax.set_box_aspect((1, 1, 1))
        self.ax.set_axis_off()
        self.hud = self.fig.text(0.01, 0.97, "", va="top", fontsize=9)
        self.coll = None

    def frame(self, mesh: Mesh, text: str) -> np.ndarray:
        from mpl_toolkits.mplot3d.art3d import Poly3DCollection

        normals = _normals(mesh.polys)
        colors = [np.array(shade(c, n)) / 255 for c, n in zip(mesh.colors, normals)]
        if self.coll is not None:
            self.coll.remove()
        self.coll = Poly3DCollection(
            mesh.polys, facecolors=colors, edgecolors="0.25", linewidths=0.5
        )
        self.ax.add_collection3d(self.coll)
        self.hud.set_text(text)
        self.fig.canvas.draw()
        return np.asarray(self.fig.canvas.buffer_rgba())[..., :3].copy()


def _rate(fn: Callable[[int], object], n: int) -> float:
    fn(0)  # warm up (imports, font and gradient caches)
    t0 = time.perf_counter()
    for i in range(n):
        fn(i)
    return n / (time.perf_counter() - t0)


def _side_by_side(a: Callable[[int], object], b: Callable[[int], object], n: int):
    """Frames/s of `a` and `b`, timed alternately frame by frame (load drift cancels)."""
    a(0), b(0)
    ta = tb = 0.0
    for i in range(n):
        t0 = time.perf_counter()
        a(i)
        t1 = time.perf_counter()
        b(i)
        ta, tb = ta + t1 - t0, tb + time.perf_counter() - t1
    return n / ta, n / tb


def _attitude(i: int) -> np.ndarray:
    return exp_so3(np.array([0.4, -0.3, 0.8]) + 0.05 * i)


def _box_case(n: int) -> tuple[float, float]:
    a = np.array([0.3, 0.15, 0.05])
    mpl = MplCandidate(0.3, 24, -35)

    def pil(i):
        return draw_rigid_body(R=_attitude(i), half_extents=a, text=f"frame {i}")

    def ref(i):
        return mpl.frame(meshes.box(a, meshes.AXIS_COLORS).transformed(_attitude(i), 0), f"{i}")

    return _side_by_side(pil, ref, n)


def _ship_case(n: int) -> tuple[float, float]:
    mpl = MplCandidate(5.5, 20, -40)

    def angles(i):
        return np.array([0.3, -0.3]) * np.cos(0.1 * i), np.array([1.0, -1.0]) * i

    def pil(i):
        phi, psi = angles(i)
        return draw_ship(
            ship_R=rot_x(0.1 * np.sin(0.1 * i)),
            gimbal_angles=phi,
            rotor_angles=psi,
            text=f"frame {i}",
        )

    def ref(i):
        phi, psi = angles(i)
        hull, items = ship_meshes(phi, psi)
        hull.extend(items)
        return mpl.frame(hull.transformed(rot_x(0.1 * np.sin(0.1 * i)), 0), f"{i}")

    return _side_by_side(pil, ref, n)


def _flat_cases(n: int) -> list[tuple[str, float]]:
    """Frame rates of the other two scenes (PIL only; no matplotlib twin is kept)."""
    s = np.linspace(-30, 30, 121)
    S = np.linspace(0, 0.2, 41)
    c = np.column_stack([np.cumsum(np.cos(1.3 - 13 * S)), np.cumsum(np.sin(1.3 - 13 * S))])
    gowec = _rate(
        lambda i: draw_gowec(
            buoy_R=rot_x(0.1), gimbal_angle=0.02 * i, wave_x=s, wave_z=np.cos(0.25 * s - 0.1 * i)
        ),
        n,
    )
    worm = _rate(lambda i: draw_inchworm(centerline=c * 0.005, x_head=0.2, x_tail=0.0), n)
    return [("draw_gowec", gowec), ("draw_inchworm", worm)]


def rows(quick: bool) -> list[dict]:
    n = 20 if quick else 100
    out = []
    for case, fn in (("rigid body box 360x480", _box_case), ("ship, 2 gyros 360x480", _ship_case)):
        pil, ref = fn(n)
        out.append(
            dict(
                case=case,
                variant="PIL ImageDraw, 2x supersampled",
                steps_per_s=pil,
                reference=REFERENCE,
                reference_steps_per_s=ref,
                ratio=pil / ref,
                unit="frames/s",
            )
        )
    for case, rate in _flat_cases(n):
        out.append(
            dict(
                case=f"{case} 360x480",
                variant="PIL ImageDraw, 2x supersampled",
                steps_per_s=rate,
                reference="(no matplotlib twin)",
                reference_steps_per_s=float("nan"),
                ratio=float("nan"),
                unit="frames/s",
            )
        )
    return out


if __name__ == "__main__":  # pragma: no cover
    for r in rows(quick=True):
        print(r)
