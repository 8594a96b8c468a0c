"""From a layout and its parameter values to the kernel's matrices and rows: one assembly
for every vehicle.

Every element joins a point on one body to a point on another (or to the rails) and acts
along one axis; its deformation is a linear function of the coordinates, ``B @ q`` (point
on the second body minus point on the first, small angles, sign conventions of
:mod:`railhunt.suspension`). A spring adds ``k B^T B`` to the stiffness matrix, a damper
``c B^T B`` to the damping matrix, a torsion element the same with ``B`` the difference of
the two bodies' yaw or roll angles; a Maxwell element gives a damper row and its force is a
state; a stop gives a stop row. The rules that follow from the heights and positions
(gravitational roll stiffness, wheel loads, load transfer, track delays) are stated in
``docs/model.md`` ("Vehicle layouts") and applied here.
"""

from __future__ import annotations

import warnings
from collections.abc import Mapping
from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from railhunt.kernel.contact import conical_slots
from railhunt.kernel.creep import CREEP_LAWS
from railhunt.kernel.layout import N_WR, WR, Body, DamperParam, StateLayout, StopParam
from railhunt.layout.expressions import Expression, ExpressionError, difference
from railhunt.layout.spec import TRACK, BodySpec, ElementSpec, LayoutError, LayoutSpec

__all__ = ["Assembly", "FreeWheelsetWarning", "assemble_layout", "state_layout"]

_SPRINGS = ("spring", "torsion-spring")
_DAMPERS = ("damper", "torsion-damper")
_INERTIA = {"y": "mass", "psi": "yaw_inertia", "phi": "roll_inertia"}


class FreeWheelsetWarning(UserWarning):
    """A wheelset that no element joins to another body (only the rails hold it)."""


@lru_cache(maxsize=64)
def _body_dofs(spec: LayoutSpec) -> dict[str, tuple[int, int, int]]:
    layout = state_layout(spec)
    return {b.name: layout.body_dofs(b.name) for b in layout.bodies}


@dataclass(frozen=True)
class Assembly:
    """A layout's numbers for one set of parameter values (SI).

    Attributes
    ----------
    layout : StateLayout
        The state vector's slots.
    mass : numpy.ndarray
        Mass matrix diagonal (kg, kg*m^2).
    K_suspension, gravity, C : numpy.ndarray
        Suspension stiffness, gravitational roll stiffness (diagonal) and damping matrices.
    damper_rows, damper : numpy.ndarray
        Maxwell elements' elongation rows and parameters (:class:`DamperParam` columns).
    stop_rows, stop : numpy.ndarray
        Stops' deformation rows and parameters (:class:`StopParam` columns).
    stop_track : numpy.ndarray of int64
        For each stop, the wheelset index whose rail it meets (-1: between two bodies).
    wheel_rail : numpy.ndarray, shape (n_wheelsets, N_WR)
        Each wheelset's wheel/rail vector (:class:`WR` slots, no contact table).
    creep_laws : tuple of str
        Each wheelset's creep law.
    wheelsets, bodies : numpy.ndarray of int64
        Indices of ``(y, psi)`` of each wheelset and ``(y, psi, phi)`` of each moving
        body in ``q`` (-1: none).
    wheelset_delay, body_delay : numpy.ndarray
        Distance behind the leading wheelset (m).
    carried : numpy.ndarray
        Mass resting on each wheelset, its own included (kg).
    contact_mechanics : tuple of str
        Each wheelset's contact mechanics, ``"centred"`` or ``"per-point"``.
    materials : tuple of (float, float)
        Each wheelset's shear modulus (Pa) and Poisson's ratio (the per-point ellipses).
    """

    layout: StateLayout
    mass: np.ndarray
    K_suspension: np.ndarray
    gravity: np.ndarray
    C: np.ndarray
    damper_rows: np.ndarray
    damper: np.ndarray
    stop_rows: np.ndarray
    stop: np.ndarray
    stop_track: np.ndarray
    wheel_rail: np.ndarray
    creep_laws: tuple[str, ...]
    wheelsets: np.ndarray
    bodies: np.ndarray
    wheelset_delay: np.ndarray
    body_delay: np.ndarray
    carried: np.ndarray
    contact_mechanics: tuple[str, ...] = ()
    materials: tuple[tuple[float, float], ...] = ()


@lru_cache(maxsize=64)
def state_layout(spec: LayoutSpec) -> StateLayout:
    """The state vector's slots of a layout: its moving bodies and its Maxwell elements."""
    bodies = tuple(Body(b.name, b.tag, b.coordinates, b.kind) for b in spec.bodies
                   if b.coordinates)  # fmt: skip
    n_d = sum(1 for el in spec.elements if el.kind == "maxwell")
    return StateLayout(bodies=bodies, dampers=tuple(f"d{k + 1}" for k in range(n_d)))


def _value(expr: Expression, values: Mapping[str, float], where: str) -> float:
    try:
        return expr(values)
    except ExpressionError as exc:
        raise LayoutError(f"{where}: {exc}") from None


def assemble_layout(spec: LayoutSpec, values: Mapping[str, float],
                    creep_law: str | None = None) -> Assembly:  # fmt: skip
    """The layout's matrices, rows and wheel/rail vectors for these parameter values.

    Parameters
    ----------
    spec : LayoutSpec
        The layout.
    values : Mapping[str, float]
        Every parameter the layout names (SI).
    creep_law : str, optional
        A creep law for every wheelset instead of the layout's.

    Raises
    ------
    LayoutError
        A non-positive mass or inertia, an unknown parameter, a coordinate that no element
        restrains (a free mode).
    """
    where = spec.source or "layout"
    layout = state_layout(spec)
    n = layout.n_dof
    index = _body_dofs(spec)
    g = _value(spec.gravity, values, f"{where}: [vehicle] gravity")

    # Bodies: masses, inertias (checked), positions and heights.
    mass = np.empty(n)
    props: dict[str, dict[str, float]] = {}
    for b in spec.bodies:
        p = {"x": _value(b.x, values, f"{where}: body {b.name!r} x"),
             "height": _value(b.height, values, f"{where}: body {b.name!r} height")}  # fmt: skip
        for key in ("mass", "yaw_inertia", "roll_inertia"):
            expr = getattr(b, key)
            if expr is None:
                continue
            p[key] = _value(expr, values, f"{where}: body {b.name!r} {key}")
            if not p[key] > 0.0:
                raise LayoutError(f"{where}: body {b.name!r}: {key} = {p[key]!r} is invalid: "
                                  "must be > 0 (kg, kg*m^2)")  # fmt: skip
        props[b.name] = p
        if b.coordinates:
            for c, i in zip(("y", "psi", "phi"), index[b.name], strict=True):
                if i >= 0:
                    mass[i] = p[_INERTIA[c]]

    # Elements: rows, then K, C (in the file's order), Maxwell and stop rows.
    K = np.zeros((n, n))
    C = np.zeros((n, n))
    d_rows, d_par, s_rows, s_par, s_track = [], [], [], [], []
    bodies_by_name = {b.name: b for b in spec.bodies}
    ws_names = [b.name for b in spec.wheelsets]
    touched = np.zeros(n, dtype=bool)
    joined: set[str] = set()
    law_values: list[dict[str, float]] = []
    for el in spec.elements:
        law = {k: _value(e, values, f"{where}: element {el.name!r} {k}") for k, e in el.law}
        law_values.append(law)
        row = _element_row(el, bodies_by_name, index, values, n, where)
        joined.update((el.body_a, el.body_b))
        if el.kind in _SPRINGS:
            K += law["stiffness"] * np.outer(row, row)
        elif el.kind in _DAMPERS:
            C += law["damping"] * np.outer(row, row)
        elif el.kind == "maxwell":
            d_rows.append(row)
            par = np.zeros(len(DamperParam))
            par[DamperParam.K_D], par[DamperParam.C_D1] = law["stiffness"], law["damping"]
            par[DamperParam.C_D2], par[DamperParam.F_U] = law["damping2"], law["blowoff_force"]
            d_par.append(par)
        else:
            s_rows.append(row)
            par = np.zeros(len(StopParam))
            par[StopParam.GAP], par[StopParam.K1] = law["gap"], law["stiffness"]
            par[StopParam.K3] = law["stiffness3"]
            s_par.append(par)
            s_track.append(ws_names.index(el.body_a) if el.body_b == TRACK
                           and el.body_a in ws_names else -1)  # fmt: skip
        touched |= row != 0.0

    gravity = _gravity_stiffness(spec, props, law_values, index, bodies_by_name, values, g, n,
                                 where)  # fmt: skip
    _check_free_modes(spec, layout, touched, joined, where)

    # Loads: each body's weight shared among the bodies below it that carry it through
    # vertical springs, in proportion to their stiffness; then per wheelset.
    share = _load_shares(spec, props, law_values)
    carried = np.array([sum(share[b.name].get(w, 0.0) * props[b.name].get("mass", 0.0)
                            for b in spec.bodies) for w in ws_names])  # fmt: skip
    lead = max(spec.wheelsets, key=lambda b: props[b.name]["x"])
    wheelset_delay = np.array([difference(lead.x, w.x, values) for w in spec.wheelsets])
    moving = [b for b in spec.bodies if b.coordinates]
    body_delay = np.array([difference(lead.x, b.x, values) for b in moving])

    wr = np.zeros((len(ws_names), N_WR))
    laws: list[str] = []
    mechanics: list[str] = []
    materials: list[tuple[float, float]] = []
    for j, w in enumerate(spec.wheelsets):
        mh = 0.0
        for b in spec.bodies:
            s = share[b.name].get(w.name, 0.0)
            if s:
                mh = mh + s * props[b.name].get("mass", 0.0) * props[b.name]["height"]
        law = _wheel_rail_row(spec, w, props[w.name], values, g, carried[j], mh, wr[j],
                              creep_law, where)  # fmt: skip
        laws.append(law)
        mech, material = _contact_mechanics(spec, w, values, where)
        mechanics.append(mech)
        materials.append(material)
    return Assembly(
        layout=layout, mass=mass, K_suspension=K, gravity=gravity, C=C,
        damper_rows=np.array(d_rows).reshape(-1, n),
        damper=np.array(d_par).reshape(-1, len(DamperParam)),
        stop_rows=np.array(s_rows).reshape(-1, n),
        stop=np.array(s_par).reshape(-1, len(StopParam)),
        stop_track=np.array(s_track, dtype=np.int64),
        wheel_rail=wr, creep_laws=tuple(laws),
        wheelsets=layout.wheelset_index(), bodies=layout.body_index(),
        wheelset_delay=wheelset_delay, body_delay=body_delay, carried=carried,
        contact_mechanics=tuple(mechanics), materials=tuple(materials),
    )  # fmt: skip


def arm(point: tuple[Expression, Expression, Expression], body: BodySpec,
        values: Mapping[str, float]) -> tuple[float, float, float]:  # fmt: skip
    """A point's position relative to the body's centre of gravity ``(x, 0, height)`` (m),
    with shared terms cancelled (:func:`~railhunt.layout.expressions.difference`)."""
    return (difference(point[0], body.x, values), point[1](values),
            difference(point[2], body.height, values))  # fmt: skip


def point_row(dofs: tuple[int, int, int], p: tuple[float, float, float], axis: str,
              n: int) -> np.ndarray:  # fmt: skip
    """Displacement of a body-fixed point along ``axis`` as a row over the ``n`` coordinates.

    ``dofs`` are the body's ``(y, psi, phi)`` indices (-1: none; a fixed body or the track
    has none), ``p`` the point relative to its centre of gravity (m); ``axis`` is
    ``"x"``, ``"y"``, ``"z"`` (small angles: ``u_x = -psi py``, ``u_y = y + psi px + phi pz``,
    ``u_z = -phi py``), or ``"yaw"``/``"roll"`` for a torsion element.
    """
    iy, ipsi, iphi = dofs
    px, py, pz = p
    row = np.zeros(n)
    if axis == "x":
        if ipsi >= 0:
            row[ipsi] = -py
    elif axis == "y":
        if iy >= 0:
            row[iy] = 1.0
        if ipsi >= 0:
            row[ipsi] = px
        if iphi >= 0:
            row[iphi] = pz
    elif axis == "z":
        if iphi >= 0:
            row[iphi] = -py
    elif axis in ("yaw", "roll"):
        i = ipsi if axis == "yaw" else iphi
        if i >= 0:
            row[i] = 1.0
    return row


def _element_row(el: ElementSpec, bodies: dict[str, BodySpec],
                 index: dict[str, tuple[int, int, int]], values: Mapping[str, float], n: int,
                 where: str) -> np.ndarray:  # fmt: skip
    """Deformation row: point on body b minus point on body a along the axis (against the
    track: point on body a minus the rails, as the kernel's flange stops read it)."""
    try:
        a = bodies[el.body_a]
        row_a = point_row(index.get(a.name, (-1, -1, -1)), arm(el.at, a, values), el.axis, n)
        if el.body_b == TRACK:
            return row_a  # against the rails: the body's displacement minus the rails'
        b = bodies[el.body_b]
        row_b = point_row(index.get(b.name, (-1, -1, -1)), arm(el.at_b, b, values), el.axis,
                           n)  # fmt: skip
    except ExpressionError as exc:
        raise LayoutError(f"{where}: element {el.name!r}: {exc}") from None
    return row_b - row_a


_Supports = dict[str, list[tuple[ElementSpec, str, float]]]


def _supports(spec: LayoutSpec, props: dict[str, dict[str, float]],
              law_values: list[dict[str, float]]) -> _Supports:  # fmt: skip
    """For each body, the vertical springs that carry it: (element, body below, k)."""
    out: dict[str, list[tuple[ElementSpec, str, float]]] = {b.name: [] for b in spec.bodies}
    for el, law in zip(spec.elements, law_values, strict=True):
        if el.kind != "spring" or el.axis != "z" or el.body_b == TRACK:
            continue
        ha, hb = props[el.body_a]["height"], props[el.body_b]["height"]
        if ha > hb:
            out[el.body_a].append((el, el.body_b, law["stiffness"]))
        elif hb > ha:
            out[el.body_b].append((el, el.body_a, law["stiffness"]))
    return out


def _load_shares(spec: LayoutSpec, props: dict[str, dict[str, float]],
                 law_values: list[dict[str, float]]) -> dict[str, dict[str, float]]:
    """Fraction of each body's weight that rests on each wheelset (1 for itself)."""
    supports = _supports(spec, props, law_values)
    share: dict[str, dict[str, float]] = {}
    for b in sorted(spec.bodies, key=lambda b: props[b.name]["height"]):
        if b.kind == "wheelset":
            share[b.name] = {b.name: 1.0}
            continue
        total = 0.0
        per: dict[str, float] = {}
        for _, below, k in supports[b.name]:
            total += k
            per[below] = per.get(below, 0.0) + k
        mine: dict[str, float] = {}
        for below, k in per.items():
            f = k / total
            for w, s in share.get(below, {}).items():
                mine[w] = mine.get(w, 0.0) + f * s
        share[b.name] = mine
    return share


def _gravity_stiffness(spec: LayoutSpec, props: dict[str, dict[str, float]],
                       law_values: list[dict[str, float]], index: dict[str, tuple[int, int, int]],
                       bodies: dict[str, BodySpec], values: Mapping[str, float], g: float,
                       n: int, where: str) -> np.ndarray:  # fmt: skip
    """``-m g h`` on the roll of each body resting on vertical springs ``h`` below its
    centre of gravity (``h``: their mean height below it, stiffness-weighted)."""
    G = np.zeros((n, n))
    supports = _supports(spec, props, law_values)
    for b in spec.bodies:
        iphi = index.get(b.name, (-1, -1, -1))[2]
        if iphi < 0 or not supports[b.name]:
            continue
        depths, weights = [], []
        for el, _, k in supports[b.name]:
            point = el.at if el.body_a == b.name else el.at_b
            depths.append(-difference(point[2], b.height, values))
            weights.append(k)
        if all(d == depths[0] for d in depths):
            h = depths[0]
        else:
            h = float(np.dot(depths, weights) / np.sum(weights))
        G[iphi, iphi] = -props[b.name]["mass"] * g * h
    return G


def _check_free_modes(spec: LayoutSpec, layout: StateLayout, touched: np.ndarray,
                      joined: set[str], where: str) -> None:  # fmt: skip
    for b in layout.bodies:
        kind = spec.body(b.name).kind
        if kind == "wheelset":
            if b.name not in joined:
                warnings.warn(f"{where}: wheelset {b.name!r} is joined to no body: only the "
                              "rails hold it (a free wheelset)", FreeWheelsetWarning,
                              stacklevel=3)  # fmt: skip
            continue
        for c in b.coordinates:
            i = layout.dof(f"{c}_{b.tag}")
            if not touched[i]:
                raise LayoutError(
                    f"{where}: coordinate {c}_{b.tag} of body {b.name!r} is restrained by no "
                    f"element (a free mode): add an element acting on it, or leave {c!r} "
                    "out of the body's coordinates"
                )


def _wheel_rail_row(spec: LayoutSpec, w: BodySpec, p: dict[str, float],
                    values: Mapping[str, float], g: float, carried: float, mh: float,
                    wr: np.ndarray, creep_law: str | None, where: str) -> str:  # fmt: skip
    data = spec.wheel_rail_of(w)
    label = f"{where}: wheelset {w.name!r}"

    def num(key: str, default: float | None = None) -> float:
        if key not in data:
            if default is None:
                raise LayoutError(f"{label}: no wheel/rail value {key!r}")
            return default
        return _value(data[key], values, f"{label}: {key}")  # type: ignore[arg-type]

    law = creep_law or str(data.get("creep_law", "heuristic"))
    if law not in CREEP_LAWS:
        raise LayoutError(f"{label}: creep_law = {law!r} is unknown; use one of "
                          f"{', '.join(sorted(CREEP_LAWS))}")  # fmt: skip
    wr[WR.F11], wr[WR.F22], wr[WR.F23], wr[WR.F33] = (num("f11"), num("f22"), num("f23"),
                                                       num("f33"))  # fmt: skip
    axle = num("axle_load", carried)
    load = num("load") if "load" in data else carried * g / 2.0
    wr[WR.MU], wr[WR.N], wr[WR.A], wr[WR.R0] = num("mu"), load, num("half_gauge"), num("radius")
    contact = data.get("contact", "polynomial")
    if contact == "conical":
        for slot, value in conical_slots(num("conicity"), num("contact_angle", 0.0)).items():
            wr[slot] = value
    else:
        for slot, key in ((WR.LAMBDA1, "lambda1"), (WR.LAMBDA2, "lambda2"),
                          (WR.LAMBDA3, "lambda3"), (WR.LAMBDA4, "lambda4"),
                          (WR.LAMBDA5, "lambda5"), (WR.D0, "d0"), (WR.D1, "d1"),
                          (WR.D4, "d4"), (WR.D5, "d5")):  # fmt: skip
            wr[slot] = num(key, 0.0)
        wr[WR.DELTA_MAX] = num("delta_max", 1.2217)
    wr[WR.CREEP_LAW] = CREEP_LAWS[law]
    wr[WR.INV_MW], wr[WR.INV_JW] = 1.0 / p["mass"], 1.0 / p["yaw_inertia"]
    wr[WR.W], wr[WR.G], wr[WR.MH] = axle, g, mh
    return law


#: Default shear modulus (Pa) and Poisson's ratio: E = 210 GPa, nu = 0.3 (steel).
_SHEAR_MODULUS = 2.1e11 / 2.6
_POISSON = 0.3


def _contact_mechanics(spec: LayoutSpec, w: BodySpec, values: Mapping[str, float],
                       where: str) -> tuple[str, tuple[float, float]]:  # fmt: skip
    """A wheelset's contact mechanics and material (shear modulus, Poisson's ratio)."""
    data = spec.wheel_rail_of(w)
    label = f"{where}: wheelset {w.name!r}"
    mech = str(data.get("contact_mechanics", "centred"))
    shear = (_value(data["shear_modulus"], values, f"{label}: shear_modulus")  # type: ignore[arg-type]
             if "shear_modulus" in data else _SHEAR_MODULUS)  # fmt: skip
    nu = (_value(data["poisson"], values, f"{label}: poisson")  # type: ignore[arg-type]
          if "poisson" in data else _POISSON)  # fmt: skip
    if not 1e10 <= shear <= 1e12:
        raise LayoutError(f"{label}: shear_modulus = {shear!r} Pa is invalid: must be in "
                          "[1e+10, 1e+12] Pa")  # fmt: skip
    if not 0.0 <= nu < 0.5:
        raise LayoutError(f"{label}: poisson = {nu!r} is invalid: must be in [0, 0.5)")
    return mech, (float(shear), float(nu))
