"""The assembled vehicle model: a :class:`Vehicle` turned into the compiled kernel's arrays.

:class:`Model` assembles the mass, stiffness and damping matrices from the suspension
elements (:mod:`railhunt.suspension`), the yaw damper rows and parameters, and the
wheel/rail parameter vector, and hands them to the kernel as one bundle
(:class:`railhunt.kernel.layout.SystemArrays`, from :meth:`Model.system`). The equations
themselves are written once, in :func:`railhunt.kernel.rhs.rhs`; the state layout is
:mod:`railhunt.kernel.layout`.

State vector (38 entries, SI units)::

    x[0:17]   generalised coordinates q (see railhunt.kernel.layout.DOF_NAMES), m and rad
    x[17:34]  their rates dq/dt, m/s and rad/s
    x[34:38]  yaw damper forces F_d1..F_d4 (front left, front right, rear left, rear right), N
"""

from __future__ import annotations

import math

import numpy as np

from railhunt import track as _track
from railhunt.kernel.creep import CREEP_LAWS
from railhunt.kernel.damper import damper_velocity_array
from railhunt.kernel.layout import (
    N_ROUTE,
    N_STATE,
    N_WR,
    NO_CONTACT_WORK,
    NO_CREEP_TABLE,
    STATE_NAMES,
    WHEELSET_Y,
    WR,
    Y_W1,
    StateLayout,
    SystemArrays,
)
from railhunt.kernel.point_contact import N_STAGE_SLOTS
from railhunt.kernel.rhs import jacobian, rhs, wheelset_forces
from railhunt.vehicle import Vehicle

# Kept importable from here (older scripts and the docs use railhunt.model.<name>).
__all__ = [
    "N_STATE", "STATE_NAMES", "WHEELSET_Y", "Y_W1", "Model", "jacobian", "rhs",
    "wheelset_forces",
]  # fmt: skip


class Model:
    """The vehicle's equations of motion in the arrays the compiled code needs.

    Parameters
    ----------
    vehicle : Vehicle
        Validated vehicle description (SI).
    creep_law : {"heuristic", "heuristic-per-wheel", "linear", "polach", "vermeulen-johnson"}
        ``"heuristic"``: the paper's Eq. 28 with one factor per wheelset from the mean of
        both wheels' ``beta``; ``"heuristic-per-wheel"``: one factor per wheel;
        ``"linear"``: Kalker's linear law without saturation; ``"polach"``: Polach's
        saturation per wheel; ``"vermeulen-johnson"``: Eq. 28's cubic per wheel on the
        creepage forces without spin (see :mod:`railhunt.kernel.creep`).
    contact : railhunt.contact.geometry.ContactGeometry, optional
        Tabulated contact geometry (uniform ``y`` grid) used instead of the vehicle's
        polynomials (Eqs. 32-33): ``r_L, r_R, delta_L, delta_R`` interpolated linearly in
        the compiled right-hand side, held constant beyond the table. The vehicle's ``r0``
        (creepage reference) and ``a`` are still used. Default: the geometry of the
        vehicle's :class:`railhunt.vehicle.ContactSpec` (its ``[contact]`` section) if it
        has one, else the polynomials.
    contact_mechanics : {"centred", "per-point", "two-point"}, optional
        For every wheelset instead of its layout's ``contact_mechanics``:
        ``"centred"``, the vehicle's coefficients ``f11 ... f33`` and the static wheel
        load; ``"per-point"``, each contact point's own Hertz ellipse, Kalker
        coefficients and normal force from the wheel's equilibrium
        (:mod:`railhunt.kernel.point_contact`; needs a profile contact table);
        ``"two-point"``, up to two patches per wheel, each with its own normal force,
        ellipse and creep forces at its own point, over the lateral displacement and the
        yaw (:mod:`railhunt.kernel.two_point`; needs the vehicle's ``[contact]``
        profiles). The creep law ``"exact-table"`` (Kalker's exact theory, tabulated)
        needs ``"per-point"`` or ``"two-point"``.

    Attributes
    ----------
    mass : numpy.ndarray
        Mass matrix diagonal (kg, kg*m^2).
    K, C : numpy.ndarray
        Suspension stiffness (incl. gravitational roll terms) and damping matrices.
    lin, bd, dd, dpar, wr : numpy.ndarray
        The kernel's arrays (:class:`~railhunt.kernel.layout.SystemArrays` fields
        ``linear``, ``damper_rows``, ``damper_acc``, ``damper``, ``wheel_rail``).
    """

    def __init__(
        self, vehicle: Vehicle, creep_law: str | None = None, contact: object = None,
        contact_mechanics: str | None = None,
    ) -> None:
        from railhunt.arguments import check_vehicle
        from railhunt.layout.parse import CONTACT_MECHANICS

        check_vehicle(vehicle)
        if creep_law is not None and creep_law not in CREEP_LAWS:
            raise ValueError(
                f"creep_law = {creep_law!r} is invalid: must be one of {sorted(CREEP_LAWS)}"
            )
        if contact_mechanics is not None and contact_mechanics not in CONTACT_MECHANICS:
            raise ValueError(f"contact_mechanics = {contact_mechanics!r} is invalid: must be "
                             f"one of {', '.join(CONTACT_MECHANICS)}")  # fmt: skip
        asm = vehicle.assembly
        self.vehicle = vehicle
        #: The state vector's slots (bodies, coordinates, dampers) of this vehicle.
        self.layout: StateLayout = asm.layout
        self.creep_law = creep_law if creep_law is not None else asm.creep_laws[0]
        given = contact
        if contact is None and vehicle.contact is not None:
            contact = vehicle.contact.geometry()
        wr = asm.wheel_rail.copy()
        if creep_law is not None:
            wr[:, WR.CREEP_LAW] = CREEP_LAWS[creep_law]
        n_ws = wr.shape[0]
        mechanics = (tuple(asm.contact_mechanics) or ("centred",) * n_ws
                     if contact_mechanics is None else (contact_mechanics,) * n_ws)  # fmt: skip
        #: Each wheelset's contact mechanics, ``"centred"``, ``"per-point"`` or
        #: ``"two-point"``.
        self.contact_mechanics: tuple[str, ...] = mechanics
        exact = [int(code) == CREEP_LAWS["exact-table"] for code in wr[:, WR.CREEP_LAW]]
        for j in range(n_ws):
            if exact[j] and mechanics[j] not in ("per-point", "two-point"):
                raise ValueError("creep_law = 'exact-table' is invalid with contact_mechanics "
                                 f"= {mechanics[j]!r}: it needs 'per-point' or 'two-point' "
                                 "(each contact's own ellipse)")  # fmt: skip
        if "per-point" in mechanics and contact is None:
            raise ValueError("contact_mechanics = 'per-point' is invalid for this vehicle: it "
                             "needs profile contact (a [contact] section, or contact=)")
        if "two-point" in mechanics and vehicle.contact is None:
            raise ValueError("contact_mechanics = 'two-point' is invalid for this vehicle: it "
                             "needs its profiles (a [contact] section)")
        if ("two-point" in mechanics and given is not None
                and not _same_geometry(given, vehicle.contact.geometry())):
            raise ValueError("contact= is invalid with contact_mechanics = 'two-point': its "
                             "patches are tabulated from the vehicle's own [contact] profiles; "
                             "give the profiles there (railhunt.studies.fleet.with_wheel, a "
                             "vehicle file) or use contact_mechanics = 'per-point'")  # fmt: skip
        creep_table = NO_CREEP_TABLE
        if any(exact):
            from railhunt.contact.creep_table import shipped_creep_table

            creep_table = shipped_creep_table().kernel_array
        if contact is not None:
            # The creepages are measured from r0: a centred wheelset on a table whose
            # radius differs from r0 would carry a steady longitudinal creepage that eats
            # into the saturation of every creep force.
            r_centre = float(np.interp(0.0, contact.y, contact.r_left))
            r0 = float(wr[0, WR.R0])
            if abs(r_centre - r0) > 1e-6:
                raise ValueError(
                    f"r0 = {r0!r} m is invalid with this contact geometry: must "
                    f"equal its centred rolling radius {r_centre:.9f} m within 1 um "
                    f"(set r0 = {r_centre!r})"
                )
            table = _contact_table(contact)
            rows = []
            for j, row in enumerate(wr):
                tail = np.zeros(0)
                if mechanics[j] == "per-point":
                    tail = _point_tail(contact, asm.materials[j] if asm.materials else None,
                                       float(row[WR.N]), exact[j])  # fmt: skip
                elif mechanics[j] == "two-point":
                    from railhunt.contact.patch_table import vehicle_two_point_block

                    tail = vehicle_two_point_block(
                        vehicle.contact, asm.materials[j] if asm.materials else None,
                        float(row[WR.N]), exact[j])  # fmt: skip
                rows.append(np.concatenate([row[:WR.TABLE], table, tail]))
            wr = wheel_rail_rows(rows)
        self.contact = contact
        self.mass = asm.mass
        k_susp, self.C = asm.K_suspension, asm.C
        self.K = k_susp + asm.gravity
        inv_m = 1.0 / self.mass
        bd, rows = asm.damper_rows, asm.stop_rows
        trk, trs = _track.encode(None)
        self._eigen_cache: dict[float, np.ndarray] = {}  # centred_eigenvalues, by speed
        self._system = SystemArrays(
            linear=np.asfortranarray(-inv_m[:, None] * np.hstack([self.K, self.C])),
            damper_rows=np.ascontiguousarray(bd),
            damper_acc=np.ascontiguousarray(-inv_m[:, None] * bd.T),
            damper=np.ascontiguousarray(asm.damper),
            wheel_rail=np.ascontiguousarray(wr),
            wheelsets=asm.wheelsets.copy(),
            wheelset_delay=asm.wheelset_delay.copy(),
            track=trk,
            track_samples=trs,
            stop_rows=np.ascontiguousarray(rows),
            stop_acc=np.ascontiguousarray(-inv_m[:, None] * rows.T),
            stop=np.ascontiguousarray(asm.stop),
            route=np.zeros((0, N_ROUTE)),
            bodies=asm.bodies.copy(),
            body_delay=asm.body_delay.copy(),
            suspension=np.ascontiguousarray(-inv_m[:, None] * np.hstack([k_susp, self.C])),
            scratch=np.zeros(3 * len(self.mass)),
            stop_wheelset=asm.stop_track.copy(),
            creep_table=creep_table,
            contact_work=(np.zeros((N_STAGE_SLOTS, 2 * len(wr))) if any(exact)
                          else NO_CONTACT_WORK),
        )

    @property
    def half_gauge(self) -> float:
        """Half the distance between the leading wheelset's contact points (m)."""
        return float(self._system.wheel_rail[0, WR.A])

    @property
    def gravity(self) -> float:
        """Acceleration of gravity of the model (m/s^2)."""
        return float(self._system.wheel_rail[0, WR.G])

    @property
    def n_state(self) -> int:
        """Length of this model's state vector."""
        return self.layout.n_state

    # The kernel's arrays under their short historical names.
    lin = property(lambda self: self._system.linear)
    bd = property(lambda self: self._system.damper_rows)
    dd = property(lambda self: self._system.damper_acc)
    dpar = property(lambda self: self._system.damper)
    #: The first wheelset's wheel/rail row (every wheelset of this vehicle has the same).
    wr = property(lambda self: self._system.wheel_rail[0])

    def wheel_rail_vector(self) -> np.ndarray:
        """The leading wheelset's wheel/rail parameters (slots :class:`WR`)."""
        return self._system.wheel_rail[0].copy()

    def wheelset_offsets(self) -> np.ndarray:
        """Distance of each wheelset behind the leading one (m), from the bodies' ``x``
        (0, 2*l1, 2*l, 2*l + 2*l1 for the paper's vehicle)."""
        return self._system.wheelset_delay.copy()

    def body_offsets(self) -> np.ndarray:
        """Distance of each moving body's centre behind the leading wheelset (m), in layout
        order (car body ``l + l1``, bogies ``l1`` and ``2 l + l1``, then the wheelsets for
        the paper's vehicle)."""
        return self._system.body_delay.copy()

    def mass_height(self) -> float:
        """Sum of mass times height above the rail carried by the leading wheelset (kg*m).

        Each body's share of the weight that rests on the wheelset, times its height
        (docs/model.md, "Vehicle layouts"): for the paper's vehicle a quarter of the car
        body at ``r0 + h4 + h3 + h1``, half a bogie frame at ``r0 + h4`` and the wheelset
        at ``r0``. Sets the load transfer between the wheels in a curve.
        """
        return float(self._system.wheel_rail[0, WR.MH])

    def system(self, excitation: object = None, route: np.ndarray | None = None) -> SystemArrays:
        """The kernel's bundle of arrays, with a track input and a route.

        Parameters
        ----------
        excitation : object, optional
            Track input (:class:`railhunt.track.SingleDefect`, ``SampledTrack``); ideal
            track otherwise.
        route : numpy.ndarray, optional
            Track geometry (:meth:`railhunt.curve.Curve.route` or ``steady_route``);
            straight track otherwise.
        """
        system = self._system
        if excitation is not None:
            trk, trs = _track.encode(excitation)
            system = system._replace(track=trk, track_samples=trs)
        if route is not None:
            route = np.ascontiguousarray(route, dtype=np.float64)
            if route.ndim != 2 or route.shape[1] != N_ROUTE:
                raise ValueError(f"route has shape {route.shape}: must be (n, {N_ROUTE})")
            system = system._replace(route=route)
        return system

    def args(self, speed: float, excitation: object = None,
             route: np.ndarray | None = None) -> tuple[float, SystemArrays]:  # fmt: skip
        """Arguments that follow ``(t, x)`` in every call of the kernel's ``rhs``.

        Parameters
        ----------
        speed : float
            Forward speed (m/s), > 0.
        excitation : object, optional
            Track input; ideal track otherwise.
        route : numpy.ndarray, optional
            Track geometry; straight track otherwise.

        Returns
        -------
        tuple
            ``(speed, system)``: ``rhs(t, x, *model.args(speed), out)``.
        """
        if not (math.isfinite(speed) and speed > 0.0):
            raise ValueError(f"speed = {speed!r} m/s is invalid: must be finite and > 0")
        return float(speed), self.system(excitation, route)

    def derivative(
        self, x: np.ndarray, speed: float, t: float = 0.0, excitation: object = None,
        route: np.ndarray | None = None,
    ) -> np.ndarray:  # fmt: skip
        """dx/dt at state ``x`` (convenience wrapper of the kernel's ``rhs``)."""
        out = np.empty(self.layout.n_state)
        rhs(t, np.ascontiguousarray(x, dtype=np.float64), *self.args(speed, excitation, route),
            out)  # fmt: skip
        return out

    def jacobian(self, speed: float, x: np.ndarray | None = None,
                 route: np.ndarray | None = None, t: float = 0.0) -> np.ndarray:  # fmt: skip
        """Jacobian of the system without track input at ``x`` (default: centred), at
        time ``t`` on ``route`` (default: straight track)."""
        n = self.layout.n_state
        x0 = np.zeros(n) if x is None else np.ascontiguousarray(x, dtype=np.float64)
        return jacobian(x0, *self.args(speed, route=route), t)

    def centred_eigenvalues(self, speed: float) -> np.ndarray:
        """Eigenvalues (1/s) of :meth:`jacobian` at the centred state on straight track at
        ``speed`` (m/s), kept for the last few speeds: a trial's step
        (:func:`railhunt.simulation.auto_step`) and its linear decay rates
        (:func:`railhunt.analysis.modes.least_damped_rate`) read the same ones."""
        key = float(speed)
        cache = self._eigen_cache
        if key not in cache:
            if len(cache) >= 8:
                cache.pop(next(iter(cache)))
            cache[key] = np.linalg.eigvals(self.jacobian(key))
        return cache[key].copy()

    def damper_velocities(self, damper_forces: np.ndarray) -> np.ndarray:
        """Velocities of the viscous parts of the yaw dampers (m/s) for given forces (N).

        ``damper_forces`` has the dampers in its last axis; a whole state history
        (``x[:, railhunt.kernel.layout.FORCES]``) works.
        """
        f = np.asarray(damper_forces, dtype=np.float64)
        out = np.empty_like(f)
        n_damper = self.layout.n_damper
        if n_damper == 0:
            return out
        flat_f, flat_o = f.reshape(-1, n_damper), out.reshape(-1, n_damper)
        for d in range(n_damper):
            _, c1, c2, fu = self.dpar[d]
            flat_o[:, d] = damper_velocity_array(flat_f[:, d], c1, c2, fu)
        return out


def wheel_rail_rows(rows: list[np.ndarray]) -> np.ndarray:
    """One wheel/rail row per wheelset, padded with zeros to the longest (``SystemArrays.
    wheel_rail``, shape ``(n_wheelsets, width)``); each row's ``WR.TABLE`` slot says how
    much of its contact table is used."""
    width = max((len(r) for r in rows), default=N_WR)
    out = np.zeros((len(rows), width))
    for j, r in enumerate(rows):
        out[j, : len(r)] = r
    return out


def _same_geometry(a: object, b: object) -> bool:
    """Whether two contact tables are the same (one object, or equal rows)."""
    if a is b:
        return True
    names = ("y", "r_left", "r_right", "delta_left", "delta_right", "roll")
    try:
        return all(np.array_equal(getattr(a, k), getattr(b, k)) for k in names)
    except AttributeError:
        return False


def _point_tail(contact: object, material: tuple[float, float] | None, static_load: float,
                exact: bool) -> np.ndarray:  # fmt: skip
    """The per-point block of a wheel/rail row (:meth:`PointContact.kernel_tail`)."""
    from railhunt.contact.point_contact import POISSON, SHEAR_MODULUS, point_contact

    shear, nu = material if material is not None else (SHEAR_MODULUS, POISSON)
    grid = None
    if exact:
        from railhunt.contact.creep_table import shipped_creep_table

        grid = shipped_creep_table().ab_grid
    # A sweep builds a Model per point on the one (cached) contact table: its ellipses
    # once, not per point (the Hertz solutions take about 0.1 s).
    key = (id(contact), float(shear), float(nu))
    hit = _POINT_CACHE.get(key)
    if hit is None or hit[0] is not contact:
        if len(_POINT_CACHE) >= 16:
            _POINT_CACHE.pop(next(iter(_POINT_CACHE)))
        hit = (contact, point_contact(contact, shear, nu))
        _POINT_CACHE[key] = hit
    return hit[1].kernel_tail(static_load, grid)


#: Per-point ellipses by (contact table, shear modulus, Poisson's ratio); the table is kept
#: with its entry, so that its id cannot be reused while the entry lives.
_POINT_CACHE: dict[tuple[int, float, float], tuple[object, object]] = {}


def _contact_table(contact: object) -> np.ndarray:
    """Pack a contact table (``y`` uniform) into the ``wr`` tail (from slot ``WR.TABLE``)."""
    y = np.asarray(contact.y, dtype=np.float64)
    step = np.diff(y)
    if y.ndim != 1 or y.size < 2 or not np.all(step > 0):
        raise ValueError("contact.y must be strictly increasing with at least 2 points")
    if np.max(np.abs(step - step[0])) > 1e-9 * max(abs(step[0]), 1e-12) + 1e-15:
        raise ValueError("contact.y must be uniformly spaced (tabulated geometry)")
    cols = [np.asarray(getattr(contact, name), dtype=np.float64)
            for name in ("r_left", "r_right", "delta_left", "delta_right")]
    for name, col in zip(("r_left", "r_right", "delta_left", "delta_right"), cols,
                         strict=True):
        if col.shape != y.shape or not np.all(np.isfinite(col)):
            raise ValueError(f"contact.{name} must be finite with the shape of contact.y")
    return np.concatenate([[float(y.size), y[0], step[0]], *cols])
