"""The two-point contact table of the kernel: every wheel's patches over ``(y, psi)``.

For each node of a uniform grid of lateral displacement and yaw, the wheelset is placed
on its rails as :func:`railhunt.contact_patches` places it, under its static wheel load:
each wheel's patches (up to two), their shares of the load from their elastic approach,
positions, rolling radii, contact angles and Hertz/Kalker columns
(:class:`~railhunt.kernel.layout.PatchColumn`), read by
:mod:`railhunt.kernel.two_point`.

**Slots.** Each wheel has two slots. Along ``y`` (from the centre outward, at each yaw) a
slot follows its patch: a patch goes to the slot whose patch of the previous node lay
within 2 mm of it on the wheel, else to the slot that carried less. A slot without a
patch keeps following its valley of the gap function with ``W = 0`` (or takes the lowest
valley not in contact; with none, the other slot's geometry), so that its columns stay
continuous where its load sets in; where a contact jumps, one slot's load falls as the
other's rises, and the kernel's interpolation blends the two contacts' forces (each on its
own geometry).

The shares are those of the static load (a curve's load transfer scales a wheel's
patches together). Only ``psi >= 0`` is searched: ``psi < 0`` is the mirror (the left
wheel at ``(y, psi)`` is the right one at ``(-y, -psi)``).
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np

from railhunt.contact.curvature import surface_curvature
from railhunt.contact.locus import (
    PatchSearch,
    distinct,
    ellipse_constants,
    patch_search,
    raw_patches,
    share_load,
)
from railhunt.contact.profiles import Profile
from railhunt.kernel.layout import N_PATCH_COLUMNS, TWO_POINT, PatchColumn, TwoPointHeader

__all__ = ["TwoPointTable", "two_point_table", "vehicle_two_point_block"]

#: A patch follows a slot whose previous patch lay this close along the wheel (m).
_FOLLOW = 2e-3


@dataclass(frozen=True)
class TwoPointTable:
    """The patches' columns over the grid (SI units).

    Attributes
    ----------
    y, psi : numpy.ndarray
        The grid's lateral displacements (m) and yaw angles (rad), uniform.
    columns : numpy.ndarray, shape (n_psi, n_y, 2, 2, N_PATCH_COLUMNS)
        For each node, wheel (left, right) and slot, the :class:`PatchColumn` values.
    static_load : float
        The wheel load (N) the shares are computed at.
    """

    y: np.ndarray
    psi: np.ndarray
    columns: np.ndarray
    static_load: float

    def kernel_block(self) -> np.ndarray:
        """The block after the contact table in the wheel/rail vector
        (:class:`~railhunt.kernel.layout.TwoPointHeader`)."""
        head = np.zeros(TwoPointHeader.DATA)
        head[TwoPointHeader.CODE] = TWO_POINT
        head[TwoPointHeader.QTH] = np.cbrt(self.static_load)
        head[TwoPointHeader.N_Y] = self.y.size
        head[TwoPointHeader.Y0] = self.y[0]
        head[TwoPointHeader.DY] = self.y[1] - self.y[0]
        head[TwoPointHeader.N_PSI] = self.psi.size
        head[TwoPointHeader.PSI0] = self.psi[0]
        head[TwoPointHeader.DPSI] = self.psi[1] - self.psi[0]
        return np.concatenate([head, self.columns.ravel()])

    @property
    def shares(self) -> np.ndarray:
        """Each slot's share of its wheel's load, shape ``(n_psi, n_y, 2, 2)``."""
        return self.columns[..., PatchColumn.W]


def _curvature_lookup(profile: Profile, window: float) -> tuple[np.ndarray, np.ndarray]:
    """The surface curvature on a 0.1-mm grid of the profile (interpolated later)."""
    grid = np.arange(profile.y[0], profile.y[-1], 1e-4)
    return grid, surface_curvature(profile, grid, window)


@functools.lru_cache(maxsize=64)
def _mechanics(delta: float, radius: float, kw: float, kr: float, young: float,
               poisson: float) -> tuple[float, float, float, tuple[float, ...]]:  # fmt: skip
    from railhunt.contact.point_contact import contact_coefficients

    a1, b1, d1 = ellipse_constants(delta, radius, kw, kr, young, poisson)
    return a1, b1, d1, contact_coefficients(a1 / b1, poisson)


def _wheel_patches(search: PatchSearch, side: int, y: float, phi: float, psi: float,
                   load: float, curv: tuple, young: float, poisson: float,
                   separation: float) -> list[dict]:  # fmt: skip
    """A wheel's valleys at one node, each with its share ``w`` of ``load`` (0: unloaded)
    and its ellipse under 1 N (``a1, b1``) and Kalker's coefficients ``c``."""
    locus = search.left if side == 0 else search.right
    _, raw, gap = raw_patches(locus, y, phi, psi, 1e-3, separation)
    (gw, kw), (gr, kr) = curv
    for p in raw:
        key = (round(p["delta"], 9), round(p["r"], 9),
               round(float(np.interp(p["u"], gw, kw)), 3),
               round(float(np.interp(p["t"], gr, kr)), 3))  # fmt: skip
        p["a1"], p["b1"], p["d1"], p["c"] = _mechanics(*key, young, poisson)
        p["w"] = 0.0
    keep = list(range(len(raw)))
    for _ in range(len(raw) + 1):
        sel = [raw[i] for i in keep]
        cosd = np.cos([p["delta"] for p in sel])
        stiff = np.array([p["d1"] ** -1.5 for p in sel])
        forces, approach = share_load(np.array([p["gap"] for p in sel]), cosd, stiff, load)
        new = distinct(gap, raw, approach)
        if new == keep:
            break
        keep = new
    for i, f, c in zip(keep, forces, cosd, strict=True):
        raw[i]["w"] = float(f * c / load)
    s = 1.0 if side == 0 else -1.0
    for p in raw:
        p["s"] = s * (search.params["back_to_back"] / 2 + search.params["flange_back"] + p["u"])
    return raw


def _columns(p: dict, shear: float, ab_grid: tuple[float, float] | None) -> np.ndarray:
    """One slot's :class:`PatchColumn` values from a patch (``p["w"]`` its share)."""
    out = np.zeros(N_PATCH_COLUMNS)
    w, cd = p["w"], math.cos(p["delta"])
    out[PatchColumn.W] = w
    out[PatchColumn.R] = p["r"]
    out[PatchColumn.D] = p["delta"]
    out[PatchColumn.X] = p["x"]
    out[PatchColumn.S] = p["s"]
    ab1 = p["a1"] * p["b1"]
    c11, c22, c23, c33 = p["c"]
    scale = w / cd
    out[PatchColumn.C1] = math.sqrt(ab1) * scale ** (1 / 3)
    out[PatchColumn.K11] = shear * ab1 * c11 * scale ** (2 / 3)
    out[PatchColumn.K22] = shear * ab1 * c22 * scale ** (2 / 3)
    out[PatchColumn.K23] = shear * ab1**1.5 * c23 * scale
    out[PatchColumn.K33] = shear * ab1**2 * c33 * scale ** (4 / 3)
    if ab_grid is not None:
        out[PatchColumn.AB] = round((math.log(p["a1"] / p["b1"]) - ab_grid[0]) / ab_grid[1])
    return out


def _assign(prev: list[dict | None], patches: list[dict]) -> list[dict | None]:
    """The two slots' patches at this node (module docstring), from the previous node's."""
    loaded = sorted((p for p in patches if p["w"] > 0.0), key=lambda p: p["gap"])[:2]
    slots: list[dict | None] = [None, None]
    rest = []
    for p in loaded:
        near = [k for k in (0, 1) if prev[k] is not None and slots[k] is None
                and abs(prev[k]["u"] - p["u"]) < _FOLLOW]  # fmt: skip
        if near:
            slots[min(near, key=lambda k: abs(prev[k]["u"] - p["u"]))] = p
        else:
            rest.append(p)
    for p in rest:
        free = [k for k in (0, 1) if slots[k] is None]
        slots[min(free, key=lambda k: prev[k]["w"] if prev[k] is not None else -1.0)] = p
    for k in (0, 1):
        if slots[k] is not None:
            continue
        taken = [id(q) for q in slots if q is not None]
        free = sorted((q for q in patches if id(q) not in taken), key=lambda q: q["gap"])
        near = [q for q in free if prev[k] is not None
                and abs(q["u"] - prev[k]["u"]) < _FOLLOW]  # fmt: skip
        if near:  # the valley it followed
            slots[k] = dict(min(near, key=lambda q: abs(q["u"] - prev[k]["u"])), w=0.0)
        elif free:  # the lowest valley not in contact: where a second patch would set in
            slots[k] = dict(free[0], w=0.0)
    return slots


def two_point_table(
    wheel: Profile, rail: Profile, *, rail_inclination: float, gauge: float,
    back_to_back: float, r0: float, static_load: float, y_max: float = 0.012,
    y_step: float = 2e-4, yaw_max: float = 0.012, yaw_step: float = 0.003,
    shear_modulus: float = 2.1e11 / 2.6, poisson: float = 0.3,
    ab_grid: tuple[float, float] | None = None, separation: float = 1e-3,
    sample_step: float = 2e-5, curvature_window: float = 2e-3,
) -> TwoPointTable:  # fmt: skip
    """Tabulate a wheelset's patches over ``|y| <= y_max``, ``|psi| <= yaw_max``.

    Parameters
    ----------
    wheel, rail : Profile
        Wheel and *upright* rail profile.
    rail_inclination, gauge, back_to_back, r0 : float
        As :func:`railhunt.contact_geometry` (``r0`` the radius at the tape circle, m).
    static_load : float
        Vertical wheel load (N) the patches share.
    y_max, y_step, yaw_max, yaw_step : float
        The grid (m, rad); ``y_max / y_step`` and ``yaw_max / yaw_step`` whole numbers.
    shear_modulus, poisson : float
        Material (Pa, -).
    ab_grid : tuple of float, optional
        ``(ln(a/b) of the first slice, step)`` of the creep table; None: no table.
    separation, sample_step, curvature_window : float
        As :func:`railhunt.contact_patches` (m).

    Returns
    -------
    TwoPointTable
    """
    for name, value, lo, hi in (("y_max", y_max, 1e-3, 0.03), ("y_step", y_step, 1e-5, 1e-3),
                                ("yaw_max", yaw_max, 1e-3, 0.05),
                                ("yaw_step", yaw_step, 1e-4, 0.01),
                                ("static_load", static_load, 1.0, 1e7)):  # fmt: skip
        if not (math.isfinite(value) and lo <= value <= hi):
            raise ValueError(f"{name} = {value!r} is invalid: must be in [{lo:g}, {hi:g}]")
    n_y = int(round(y_max / y_step))
    n_p = int(round(yaw_max / yaw_step))
    ys = y_step * np.arange(-n_y, n_y + 1)
    psis = yaw_step * np.arange(-n_p, n_p + 1)
    search = patch_search(wheel, rail, rail_inclination=rail_inclination, gauge=gauge,
                          back_to_back=back_to_back, r0=r0, sample_step=sample_step)
    curv = (_curvature_lookup(wheel, curvature_window),
            _curvature_lookup(search.rail, curvature_window))
    young = 2.0 * shear_modulus * (1.0 + poisson)
    cols = np.zeros((psis.size, ys.size, 2, 2, N_PATCH_COLUMNS))
    for jp in range(n_p, psis.size):  # psi >= 0; the rest by mirror
        psi = float(psis[jp])
        nodes: dict[int, list[list[dict]]] = {}
        for order in (range(n_y, ys.size), range(n_y, -1, -1)):
            guess: list[float] = []
            for iy in order:
                if iy in nodes and iy != n_y:
                    continue
                y = float(ys[iy])
                g = (2 * guess[-1] - guess[-2] if len(guess) > 1 else
                     guess[-1] if guess else None)  # fmt: skip
                phi = search.roll(y, psi, g)
                guess.append(phi)
                nodes[iy] = [_wheel_patches(search, side, y, phi, psi, static_load, curv,
                                            young, poisson, separation)
                             for side in (0, 1)]  # fmt: skip
        for side in (0, 1):
            for order in (range(n_y, ys.size), range(n_y, -1, -1)):
                prev: list[dict | None] = [None, None]
                for iy in order:
                    slots = _assign(prev, nodes[iy][side])
                    for k in (0, 1):
                        p = slots[k] if slots[k] is not None else dict(slots[1 - k], w=0.0)
                        cols[jp, iy, side, k] = _columns(p, shear_modulus, ab_grid)
                    prev = slots
    for jp in range(n_p):  # mirror: left(y, psi) = right(-y, -psi), s negated
        for side in (0, 1):
            src = cols[psis.size - 1 - jp, ::-1, 1 - side]
            cols[jp, :, side] = src
            cols[jp, :, side, :, PatchColumn.S] = -src[:, :, PatchColumn.S]
    return TwoPointTable(y=ys, psi=psis, columns=cols, static_load=float(static_load))


#: The yaw grid of a vehicle's two-point table: +-12 mrad in steps of 4 mrad (a hunting
#: wheelset yaws by a few mrad; beyond the grid the table is held at its edge).
VEHICLE_YAW_MAX = 0.012
VEHICLE_YAW_STEP = 0.004
#: The lateral step of a vehicle's two-point table (m): the per-point table's, so that the
#: small cycles near the Hopf point (0.05-0.2 mm) see S1002/UIC60's tread between the
#: centre and its contact jump at 0.25 mm as the per-point model does.
VEHICLE_Y_STEP = 1e-4


@functools.lru_cache(maxsize=16)
def _vehicle_table(spec: object, load: float, shear: float, nu: float,
                   exact: bool) -> TwoPointTable:  # fmt: skip
    from railhunt.contact.profiles import read_profile, s1002, uic60

    wheel = s1002() if spec.wheel.upper() == "S1002" else read_profile(spec.wheel, "wheel")
    rail = uic60() if spec.rail.upper() in ("UIC60", "60E1") else read_profile(spec.rail, "rail")
    grid = None
    if exact:
        from railhunt.contact.creep_table import shipped_creep_table

        grid = shipped_creep_table().ab_grid
    step = VEHICLE_Y_STEP
    y_max = step * math.floor(spec.y_max / step + 1e-9)
    return two_point_table(wheel, rail, rail_inclination=spec.rail_inclination,
                           gauge=spec.gauge, back_to_back=spec.back_to_back,
                           r0=spec.wheel_radius, static_load=load, y_max=y_max, y_step=step,
                           yaw_max=VEHICLE_YAW_MAX, yaw_step=VEHICLE_YAW_STEP,
                           shear_modulus=shear, poisson=nu, ab_grid=grid)  # fmt: skip


def vehicle_two_point_block(spec: object, material: tuple[float, float] | None,
                            static_load: float, exact: bool) -> np.ndarray:  # fmt: skip
    """The two-point block of a wheelset's wheel/rail row: the table of its vehicle's
    ``[contact]`` profiles (:class:`railhunt.vehicle.ContactSpec`) under its static wheel
    load (N), computed once per profiles, load and material (a few seconds)."""
    from railhunt.contact.point_contact import POISSON, SHEAR_MODULUS

    shear, nu = material if material is not None else (SHEAR_MODULUS, POISSON)
    return _vehicle_table(spec, float(static_load), float(shear), float(nu),
                          bool(exact)).kernel_block()  # fmt: skip
