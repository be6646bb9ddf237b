"""Draw the theory pages' diagrams of the three models (SVG, committed beside this script):
the rigid block on a slope, the flexible sliding mass, the rocking block, each with its
forces and sign conventions. Run from anywhere: ``python docs/theory/figures/make_diagrams.py``."""

import math
import pathlib

import matplotlib
import numpy as np

matplotlib.use("Agg")
matplotlib.rcParams.update({"svg.hashsalt": "blockdae", "font.size": 10})
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.patches import FancyArrowPatch, Polygon, Rectangle  # noqa: E402

HERE = pathlib.Path(__file__).parent
FORCE, MOTION, GEOMETRY = "C3", "C0", "0.35"


def arrow(ax, start, end, color, text=None, at=None, **kw):
    """An arrow from ``start`` to ``end`` with ``text`` at ``at`` (default: past the end)."""
    ax.add_patch(FancyArrowPatch(start, end, arrowstyle="-|>", mutation_scale=12, lw=1.6, color=color))
    if text:
        x, y = at if at is not None else end
        ax.text(x, y, text, color=color, **({"ha": "center", "va": "center"} | kw))


def rotated(points, angle, about=(0.0, 0.0)):
    c, s = math.cos(angle), math.sin(angle)
    return [(about[0] + c * (x - about[0]) - s * (y - about[1]), about[1] + s * (x - about[0]) + c * (y - about[1]))
            for x, y in points]


def sliding_block():
    """The rigid block on a slope of angle beta; x along the slope, positive upslope."""
    beta = math.radians(20)
    fig, ax = plt.subplots(figsize=(6.4, 3.6))
    ground = rotated([(-0.5, 0), (5.2, 0), (5.2, -0.35), (-0.5, -0.35)], beta)
    ax.add_patch(Polygon(ground, closed=True, fc="0.85", ec="0.3", hatch="///", lw=1))
    block = rotated([(1.9, 0), (3.3, 0), (3.3, 0.9), (1.9, 0.9)], beta)
    ax.add_patch(Polygon(block, closed=True, fc="#dbe8f5", ec="k", lw=1.4))
    centre = rotated([(2.6, 0.45)], beta)[0]
    along = (math.cos(beta), math.sin(beta))
    normal = (-math.sin(beta), math.cos(beta))
    arrow(ax, centre, (centre[0], centre[1] - 1.1), FORCE, "W = m g", at=(centre[0] + 0.05, centre[1] - 1.25))
    base = rotated([(2.6, 0.0)], beta)[0]
    arrow(ax, (base[0] + 0.1 * normal[0], base[1] + 0.1 * normal[1]),
          (base[0] + 1.0 * normal[0], base[1] + 1.0 * normal[1]), FORCE, "N", at=(base[0] - 0.65, base[1] + 0.85))
    foot = rotated([(3.3, 0.02)], beta)[0]
    arrow(ax, foot, (foot[0] + 0.9 * along[0], foot[1] + 0.9 * along[1]), FORCE,
          "friction ≤ μ N\n(against the slip)", at=(foot[0] + 0.9, foot[1] + 0.75), fontsize=9)
    start = rotated([(0.2, -0.6)], beta)[0]
    arrow(ax, start, (start[0] + 1.2 * along[0], start[1] + 1.2 * along[1]), MOTION,
          "base: a(t) [m/s²]\nalong +x", at=(start[0] + 1.05, start[1] - 0.25), fontsize=9)
    x0 = rotated([(3.6, 1.25)], beta)[0]
    arrow(ax, x0, (x0[0] + 0.9 * along[0], x0[1] + 0.9 * along[1]), GEOMETRY, "+x (upslope)",
          at=(x0[0] + 0.75, x0[1] + 0.55), fontsize=9)
    d0 = rotated([(1.7, 1.25)], beta)[0]
    arrow(ax, d0, (d0[0] - 0.9 * along[0], d0[1] - 0.9 * along[1]), MOTION,
          "D = −u ≥ 0\n(downslope)", at=(d0[0] - 1.2, d0[1] + 0.05), fontsize=9)
    corner = rotated([(-0.5, 0.0)], beta)[0]
    ax.plot([corner[0], corner[0] + 1.6], [corner[1], corner[1]], color=GEOMETRY, lw=0.8, ls="--")
    ax.text(corner[0] + 1.2, corner[1] + 0.12, "β", fontsize=11, color=GEOMETRY)
    ax.text(-0.6, -1.45, "u = x_block − x_base [m];  the block slides when the demand\n"
                         "passes ky g (Newmark: μ = ky, direction=\"negative\")", fontsize=9, va="top")
    ax.set(xlim=(-0.8, 5.8), ylim=(-2.1, 2.8), aspect="equal")
    ax.axis("off")
    return fig


def flexible_mass():
    """The shear column of height H on the slip surface, its first mode, the ground motion."""
    fig, ax = plt.subplots(figsize=(6.4, 3.8))
    ax.add_patch(Rectangle((-0.6, -0.45), 5.0, 0.45, fc="0.85", ec="0.3", hatch="///"))
    ax.add_patch(Rectangle((0.6, 0.0), 1.2, 2.6, fc="#e8f0e0", ec="k", lw=1.4))
    z = np.linspace(0, 1, 40)
    shape = np.sin(np.pi * z / 2)  # the first mode of a shear column fixed at its base
    ax.plot(1.2 + 0.5 * shape, 2.6 * z, color=MOTION, lw=1.6)
    ax.plot([1.2, 1.2], [0, 2.6], color=GEOMETRY, lw=0.8, ls=":")
    ax.text(1.95, 2.2, "first mode\nsin(π z / 2H)", color=MOTION, fontsize=9)
    arrow(ax, (3.4, 0.0), (3.4, 2.6), GEOMETRY)
    arrow(ax, (3.4, 2.6), (3.4, 0.0), GEOMETRY)
    ax.text(3.52, 1.3, "H [m]\nvs [m/s], ξ", fontsize=9, va="center")
    ax.plot([-0.6, 4.4], [0, 0], color="k", lw=2.2)
    ax.text(3.3, 0.08, "slip surface", fontsize=9)
    arrow(ax, (0.2, -0.75), (1.4, -0.75), MOTION, "ground: a(t) [m/s²]", at=(2.6, -0.75), fontsize=9)
    arrow(ax, (0.6, 0.3), (-0.3, 0.3), FORCE, "ky g\n(yield)", at=(-0.45, 0.75), fontsize=9)
    arrow(ax, (0.9, 3.0), (1.9, 3.0), MOTION, "u: modal displacement\ns: sliding displacement [m]",
          at=(3.3, 3.05), fontsize=9)
    ax.text(-0.6, -1.15, "it slides when HEA = a + (2/π) ü reaches ky g;  D = s ≥ 0 downslope",
            fontsize=9)
    ax.set(xlim=(-0.8, 5.0), ylim=(-1.3, 3.5), aspect="equal")
    ax.axis("off")
    return fig


def rocking_block():
    """The block of 2b x 2h rocking about its corner at +b (theta > 0), its forces."""
    b, h, theta = 0.5, 1.5, math.radians(12)
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    ax.add_patch(Rectangle((-2.0, -0.3), 4.8, 0.3, fc="0.85", ec="0.3", hatch="///"))
    pivot = (b, 0.0)
    ax.add_patch(Polygon([(-b, 0), (b, 0), (b, 2 * h), (-b, 2 * h)], closed=True, fc="none", ec="0.6", ls="--"))
    corners = rotated([(-b, 0), (b, 0), (b, 2 * h), (-b, 2 * h)], -theta, about=pivot)
    ax.add_patch(Polygon(corners, closed=True, fc="#f5e6d3", ec="k", lw=1.4))
    centre = rotated([(0.0, h)], -theta, about=pivot)[0]
    ax.plot(*centre, "ko", ms=4)
    ax.plot([pivot[0], centre[0]], [pivot[1], centre[1]], color=GEOMETRY, lw=1)
    ax.text((pivot[0] + centre[0]) / 2 + 0.12, (pivot[1] + centre[1]) / 2 + 0.1, "R", color=GEOMETRY)
    ax.plot([pivot[0], pivot[0]], [0, 2.2], color=GEOMETRY, lw=0.8, ls=":")
    ax.text(pivot[0] + 0.75, 2.6, "θ > 0: about the\ncorner at +b", fontsize=9)
    ax.text(-0.3, 0.6, "α", color=GEOMETRY)
    ax.plot([0, b], [h, 0], color="0.6", lw=0.8, ls="--")
    arrow(ax, centre, (centre[0], centre[1] - 1.0), FORCE, "m g_e", at=(centre[0] + 0.3, centre[1] - 1.1))
    arrow(ax, centre, (centre[0] + 0.9, centre[1]), FORCE, "−m a_x", at=(centre[0] + 1.25, centre[1] + 0.15))
    arrow(ax, (pivot[0], -0.05 - 0.9), (pivot[0], -0.05), FORCE, "N", at=(pivot[0] + 0.2, -1.05))
    arrow(ax, (pivot[0] + 0.9, 0.05), (pivot[0] + 0.05, 0.05), FORCE, "F", at=(pivot[0] + 0.95, 0.22))
    arrow(ax, (-2.0, -0.5), (-1.3, -0.5), MOTION, "base: a_x(t) (+x), a_z(t) (up) [m/s²]",
          at=(-2.0, -0.8), fontsize=9, ha="left")
    arrow(ax, (-1.7, 0.6), (-1.7, 1.5), GEOMETRY, "+z", at=(-1.7, 1.65), fontsize=9)
    arrow(ax, (-1.7, 0.6), (-0.9, 0.6), GEOMETRY, "+x", at=(-0.75, 0.6), fontsize=9, ha="left")
    ax.text(-2.0, 3.75, "2b × 2h;  α = atan(b/h);  p = √(3g / 4R);  g_e = g + a_z\n"
                        "it rocks about +b when a_x < −g_e tan α; an impact at θ = 0 gives θ' → r θ'",
            fontsize=9, va="top")
    ax.set(xlim=(-2.1, 3.0), ylim=(-1.2, 3.8), aspect="equal")
    ax.axis("off")
    return fig


if __name__ == "__main__":
    for name, draw in (("sliding-block", sliding_block), ("flexible-mass", flexible_mass),
                       ("rocking-block", rocking_block)):
        figure = draw()
        figure.savefig(HERE / f"{name}.svg", bbox_inches="tight", metadata={"Date": None})
        plt.close(figure)
