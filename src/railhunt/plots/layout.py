"""Pictures of a vehicle layout: plan and side view of its bodies, elements and wheelsets.

:func:`layout_figure` draws any layout from its file's description (bodies where they sit,
each force element as a symbol at its attachment point, the wheelsets on their rails);
:func:`plot_layout` saves it (``railhunt vehicle NAME|FILE --png FILE``). Body outlines
are drawn around the points that attach to them (a layout file gives no body dimensions):
they show where things are, not how big a body is. Distances in m.
"""

from __future__ import annotations

import os
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from matplotlib.patches import Circle, Rectangle

from railhunt.plots.figure import new_figure, save_figure

__all__ = ["ELEMENT_STYLE", "hunting_mode_figure", "hunting_mode_shape", "layout_figure",
           "plot_hunting_mode", "plot_layout"]

#: Marker, colour and label of each element kind (an element to the track: its own style).
ELEMENT_STYLE: dict[str, tuple[str, str, str]] = {
    "spring": ("s", "tab:blue", "spring"),
    "damper": ("D", "tab:orange", "damper"),
    "maxwell": ("X", "tab:red", "Maxwell (yaw damper)"),
    "stop": ("|", "tab:purple", "stop"),
    "torsion-spring": ("o", "tab:green", "torsion spring"),
    "torsion-damper": ("o", "tab:olive", "torsion damper"),
    "track": ("v", "black", "to the track (flange)"),
}
_BODY_COLOUR = {"car": "tab:blue", "frame": "tab:green", "wheelset": "0.3", "fixed": "0.6"}


def _value(expr: Any, values: Mapping[str, float]) -> float:
    return float(expr(values)) if callable(expr) else float(expr)


def _geometry(vehicle: Any) -> tuple[list[dict[str, Any]], list[dict[str, Any]], float, float]:
    """Bodies (name, kind, x, height, outline) and elements (kind, points) in m."""
    spec = vehicle.layout
    values = vehicle.as_dict()
    elements = []
    points: dict[str, list[tuple[float, float, float]]] = {b.name: [] for b in spec.bodies}
    for el in spec.elements:
        pa = tuple(_value(c, values) for c in el.at)
        pb = tuple(_value(c, values) for c in el.at_b)
        kind = "track" if el.body_b == "track" else el.kind
        elements.append({"kind": kind, "points": (pa, pb), "bodies": (el.body_a, el.body_b)})
        points[el.body_a].append(pa)
        if el.body_b in points:
            points[el.body_b].append(pb)
    wheel_rail = dict(spec.wheel_rail)
    a = _value(wheel_rail["half_gauge"], values) if "half_gauge" in wheel_rail else 0.75
    r0 = _value(wheel_rail["radius"], values) if "radius" in wheel_rail else 0.45
    bodies = []
    for b in spec.bodies:
        x, h = _value(b.x, values), _value(b.height, values)
        pts = points[b.name] or [(x, 0.0, h)]
        if b.kind == "wheelset":
            outline = (x - r0, x + r0, -a - 0.07, a + 0.07, h - r0, h + r0)
        else:
            xs = [p[0] for p in pts] + [x]
            ys = [abs(p[1]) for p in pts]
            zs = [p[2] for p in pts] + [h]
            margin = 0.35 if b.kind == "frame" else 0.8
            half_width = max(max(ys, default=0.0) + 0.15, a + 0.1 if b.kind == "frame" else 1.45)
            bottom, top = min(zs) - 0.05, max(max(zs) + 0.05, 2 * h - min(zs))
            outline = (min(xs) - margin, max(xs) + margin, -half_width, half_width, bottom, top)
        bodies.append({"name": b.name, "kind": b.kind, "x": x, "height": h, "outline": outline})
    return bodies, elements, a, r0


def layout_figure(vehicle: Any) -> Any:
    """Plan view (x, y) and side view (x, z) of a vehicle layout.

    Parameters
    ----------
    vehicle : railhunt.Vehicle
        A vehicle read from a layout file (every shipped vehicle is one).

    Returns
    -------
    matplotlib.figure.Figure
        Bodies as outlines at their positions (car bodies blue, frames green, fixed bodies
        grey and dashed), wheelsets with their wheels on the rails, each element as a
        symbol at its attachment point (:data:`ELEMENT_STYLE`), the centres of gravity as
        crosses.
    """
    bodies, elements, a, r0 = _geometry(vehicle)
    x_lo = min(b["outline"][0] for b in bodies) - 0.5
    x_hi = max(b["outline"][1] for b in bodies) + 0.5
    width = min(18.0, max(8.0, 0.5 * (x_hi - x_lo) + 3.0))
    fig = new_figure(width, 6.5)
    plan, side = fig.subplots(2, 1)
    for ax, y_rail in ((plan, (-a, a)), (side, (0.0,))):
        for yr in y_rail:
            ax.axhline(yr, color="0.75", lw=3, zorder=0)
    for b in sorted(bodies, key=lambda b: {"car": 0, "fixed": 0, "frame": 1}.get(b["kind"], 2)):
        x0, x1, y0, y1, z0, z1 = b["outline"]
        colour = _BODY_COLOUR[b["kind"]]
        dashed = "--" if b["kind"] == "fixed" else "-"
        if b["kind"] == "wheelset":
            plan.plot([b["x"], b["x"]], [-a, a], color=colour, lw=2.5)
            for s in (-1.0, 1.0):
                plan.add_patch(Rectangle((b["x"] - r0, s * a - 0.07), 2 * r0, 0.14,
                                         color=colour, alpha=0.7))  # fmt: skip
            side.add_patch(Circle((b["x"], b["height"]), r0, fill=False, color=colour, lw=2))
        else:
            plan.add_patch(Rectangle((x0, y0), x1 - x0, y1 - y0, fill=False, ec=colour,
                                     ls=dashed, lw=1.5))  # fmt: skip
            side.add_patch(Rectangle((x0, z0), x1 - x0, z1 - z0, fill=False, ec=colour,
                                     ls=dashed, lw=1.5))  # fmt: skip
        for ax, yy in ((plan, 0.0), (side, b["height"])):
            ax.plot(b["x"], yy, "+", color=colour, ms=9, mew=1.5)
        plan.annotate(b["name"], (b["x"], y1 if b["kind"] != "wheelset" else a + 0.1),
                      ha="center", va="bottom", fontsize=7, color=colour)  # fmt: skip
    seen: set[str] = set()
    for el in elements:
        marker, colour, label = ELEMENT_STYLE[el["kind"]]
        for p in {el["points"][0], el["points"][1]}:
            kwargs = {"label": label} if el["kind"] not in seen else {}
            seen.add(el["kind"])
            plan.plot(p[0], p[1], marker, color=colour, ms=6, ls="none", **kwargs)
            side.plot(p[0], p[2], marker, color=colour, ms=6, ls="none")
    half = max(b["outline"][3] for b in bodies) + 0.4
    for ax, (lo, hi) in ((plan, (-half, half)),
                         (side, (-0.2, max(b["outline"][5] for b in bodies) + 0.4))):
        ax.set_xlim(x_lo, x_hi)
        ax.set_ylim(lo, hi)
        ax.set_aspect("equal", adjustable="box")
    plan.set_ylabel("y (m), + left")
    side.set_ylabel("z above rail (m)")
    side.set_xlabel("x (m), + forward")
    plan.set_title(f"{vehicle.name}: plan view")
    side.set_title("side view")
    plan.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=8, frameon=False)
    return fig


def plot_layout(vehicle: Any, path: str | os.PathLike[str]) -> Path:
    """Save :func:`layout_figure` of ``vehicle`` to ``path`` (format from the suffix)."""
    return save_figure(layout_figure(vehicle), path)


def hunting_mode_shape(vehicle: Any, speed_kmh: float | None = None,
                       ) -> tuple[Any, float, complex, Any]:  # fmt: skip
    """The least-damped oscillating mode at ``speed_kmh`` (default: the Hopf point).

    Returns
    -------
    tuple
        ``(model, speed_kmh, eigenvalue, shape)``: the Model, the speed (km/h), the
        eigenvalue (1/s, Im > 0) and the mode's coordinates (complex, over
        ``model.layout.dof_names``), scaled so that the largest lateral amplitude of a body
        or wheelset is 1 at phase 0.
    """
    import numpy as np

    from railhunt.analysis.linear import linear_critical_speed
    from railhunt.analysis.modes import sorted_eig
    from railhunt.model import Model

    model = Model(vehicle)
    if speed_kmh is None:
        speed_kmh = float(linear_critical_speed(vehicle).speed_kmh)
        if not np.isfinite(speed_kmh):
            raise ValueError(f"vehicle {vehicle.name!r} has no Hopf point between 20 and "
                             "1000 km/h: give the speed of the mode to draw")  # fmt: skip
    w, vecs = sorted_eig(model.jacobian(speed_kmh / 3.6))
    k = next(i for i in range(w.size) if w[i].imag > 1e-6)
    q = vecs[: model.layout.n_dof, k]
    lateral = np.concatenate([model.layout.body_y, model.layout.wheelset_y]).astype(int)
    ref = q[lateral[int(np.argmax(np.abs(q[lateral])))]]
    return model, speed_kmh, complex(w[k]), q / ref


def hunting_mode_figure(vehicle: Any, speed_kmh: float | None = None,
                        scale: float = 0.4) -> Any:  # fmt: skip
    """Plan view of the hunting mode's shape: each body's lateral and yaw motion.

    Parameters
    ----------
    vehicle : railhunt.Vehicle
        Any layout.
    speed_kmh : float, optional
        Speed of the linearisation (km/h); default: the Hopf point (the linear critical
        speed).
    scale : float
        Drawn size of the largest lateral amplitude (m): the mode has no amplitude of its
        own.

    Returns
    -------
    matplotlib.figure.Figure
        For four phases of the oscillation (0, 90, 180, 270 degrees, shades of one
        colour) every moving body's centre line displaced by ``y + psi (x - x_b)``; fixed
        bodies dashed. The title gives the eigenvalue; the side table each body's
        amplitude (lateral in units of the largest, yaw times the half gauge) and phase.
    """
    import numpy as np

    model, speed_kmh, lam, q = hunting_mode_shape(vehicle, speed_kmh)
    bodies, _, a, _ = _geometry(vehicle)
    x_lo = min(b["outline"][0] for b in bodies) - 0.5
    x_hi = max(b["outline"][1] for b in bodies) + 0.5
    fig = new_figure(min(18.0, max(8.0, 0.5 * (x_hi - x_lo) + 3.0)), 4.2)
    ax = fig.subplots()
    index = {b.name: model.layout.body_dofs(b.name) for b in model.layout.bodies}
    lines = []
    for b in bodies:
        x0, x1 = b["outline"][0], b["outline"][1]
        colour = _BODY_COLOUR[b["kind"]]
        if b["name"] not in index:
            ax.plot([x0, x1], [0.0, 0.0], ls="--", color=colour, lw=1.5)
            continue
        iy, ip, _ = index[b["name"]]
        y = q[iy] if iy >= 0 else 0.0
        psi = q[ip] if ip >= 0 else 0.0
        xs = np.linspace(x0, x1, 2)
        for j, phase in enumerate((0.0, 0.5 * np.pi, np.pi, 1.5 * np.pi)):
            rot = np.exp(1j * phase)
            shape = (y * rot).real + (psi * rot).real * (xs - b["x"])
            ax.plot(xs, scale * shape, color=colour, lw=2.0 if j == 0 else 1.0,
                    alpha=1.0 - 0.2 * j)  # fmt: skip
        lines.append(f"{b['name']}: y {abs(y):.2f} at {np.degrees(np.angle(y)):+.0f} deg, "
                     f"a psi {a * abs(psi):.2f} at {np.degrees(np.angle(psi)):+.0f} deg")
    ax.axhline(0.0, color="0.8", lw=0.8, zorder=0)
    ax.set_xlim(x_lo, x_hi)
    ax.set_xlabel("x (m), + forward")
    ax.set_ylabel(f"lateral shape (largest = {scale:g})")
    ax.set_title(f"{vehicle.name}: hunting mode at {speed_kmh:.1f} km/h, "
                 f"{abs(lam.imag) / (2 * np.pi):.2f} Hz, Re = {lam.real:.2e} 1/s\n"
                 "(phases 0, 90, 180, 270 deg: darkest first)", fontsize=10)  # fmt: skip
    ax.text(1.01, 1.0, "\n".join(lines), transform=ax.transAxes, va="top", fontsize=7,
            family="monospace")  # fmt: skip
    return fig


def plot_hunting_mode(vehicle: Any, path: str | os.PathLike[str],
                      speed_kmh: float | None = None) -> Path:  # fmt: skip
    """Save :func:`hunting_mode_figure` to ``path``."""
    return save_figure(hunting_mode_figure(vehicle, speed_kmh), path)
