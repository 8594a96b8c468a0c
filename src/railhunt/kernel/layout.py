"""Where every state and parameter slot sits: names, never literal offsets.

The state vector of a vehicle with ``n_dof`` generalised coordinates and ``n_damper``
Maxwell yaw dampers is, in this order::

    x[0 : n_dof]                     generalised coordinates q (m, rad)
    x[n_dof : 2 n_dof]               their rates dq/dt (m/s, rad/s)
    x[2 n_dof : 2 n_dof + n_damper]  yaw damper forces F_d (N, positive in tension)

:class:`StateLayout` names the coordinates body by body; :data:`VEHICLE_17DOF` is the
paper's vehicle (car body, two bogie frames, four wheelsets) and the module constants
below (``DOF_NAMES``, ``STATE_NAMES``, ``Y_W1``, ``WHEELSET_Y``, ``RATE0``, ``FORCE0``,
...) are its slots. The compiled kernel reads the sizes from the arrays it is given
(:class:`SystemArrays`), so another body layout needs a new :class:`StateLayout` and the
object layer's assembly, not a new right-hand side.

The parameter vectors the kernel reads are laid out by :class:`WR` (wheel/rail
parameters, followed by an optional contact table; one row per wheelset) and
:class:`DamperParam` (one row per yaw damper).
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import IntEnum
from functools import cached_property
from typing import NamedTuple

import numpy as np

#: numba options for kernel functions that allocate nothing and run millions of times (the
#: right-hand side, one integrator step, the state check): compiled without reference
#: counting of arrays, which otherwise costs an atomic increment and decrement for every
#: array taken out of the :class:`SystemArrays` bundle at every call (a third of the
#: right-hand side's time). Such a function must not allocate or return an array.
NO_REFCOUNT = {"_nrt": False}


@dataclass(frozen=True)
class Body:
    """A rigid body of the vehicle and the coordinates it has.

    Parameters
    ----------
    name : str
        Body name, e.g. ``"car"``, ``"bogie1"``, ``"wheelset3"``.
    tag : str
        Suffix of its coordinate names, e.g. ``"c"``, ``"t1"``, ``"w3"``.
    coordinates : tuple of str
        Its coordinates in state order, from ``"y"`` (lateral, m), ``"psi"`` (yaw, rad)
        and ``"phi"`` (roll, rad).
    kind : str
        ``"car"``, ``"frame"``, ``"wheelset"``; empty: from the name (``wheelset*``).
    """

    name: str
    tag: str
    coordinates: tuple[str, ...]
    kind: str = ""

    @property
    def is_wheelset(self) -> bool:
        """Whether the body is a wheelset (runs on the rails)."""
        return self.kind == "wheelset" or (not self.kind and self.name.startswith("wheelset"))


@dataclass(frozen=True)
class StateLayout:
    """The state vector of a vehicle: bodies, their coordinates, rates and damper forces.

    Parameters
    ----------
    bodies : tuple of Body
        Bodies in state order.
    dampers : tuple of str
        Names of the Maxwell yaw dampers whose forces are states, in state order.
    """

    bodies: tuple[Body, ...]
    dampers: tuple[str, ...]

    @cached_property
    def dof_names(self) -> tuple[str, ...]:
        """Names of the generalised coordinates, e.g. ``("y_c", "psi_c", ...)`` (computed
        once: every index lookup of the layout reads them)."""
        return tuple(f"{c}_{b.tag}" for b in self.bodies for c in b.coordinates)

    @property
    def n_dof(self) -> int:
        """Number of generalised coordinates."""
        return len(self.dof_names)

    @property
    def n_damper(self) -> int:
        """Number of yaw dampers (force states)."""
        return len(self.dampers)

    @property
    def n_state(self) -> int:
        """Length of the state vector: coordinates, rates, damper forces."""
        return 2 * self.n_dof + self.n_damper

    @property
    def rate0(self) -> int:
        """Index of the first rate: ``x[rate0 + i]`` is the rate of coordinate ``i``."""
        return self.n_dof

    @property
    def force0(self) -> int:
        """Index of the first damper force: ``x[force0 + d]`` is damper ``d``'s force."""
        return 2 * self.n_dof

    @property
    def state_names(self) -> tuple[str, ...]:
        """Names of all states: coordinates, ``d`` + coordinate, ``F_`` + damper."""
        names = self.dof_names
        return names + tuple("d" + n for n in names) + tuple("F_" + d for d in self.dampers)

    def dof(self, name: str) -> int:
        """Index of coordinate ``name`` (e.g. ``"psi_t2"``) in ``q`` and in the state."""
        return self.dof_names.index(name)

    def rate(self, name: str) -> int:
        """State index of the rate of coordinate ``name``."""
        return self.rate0 + self.dof(name)

    def force(self, damper: str) -> int:
        """State index of the force of yaw damper ``damper`` (e.g. ``"d3"``)."""
        return self.force0 + self.dampers.index(damper)

    def body_dofs(self, body: str) -> tuple[int, int, int]:
        """Indices of ``(y, psi, phi)`` of ``body`` in ``q``; -1 where it has none."""
        for b in self.bodies:
            if b.name == body:
                return tuple(  # type: ignore[return-value]
                    self.dof(f"{c}_{b.tag}") if c in b.coordinates else -1
                    for c in ("y", "psi", "phi")
                )
        raise KeyError(f"no body {body!r}; bodies are: {', '.join(self.body_names)}")

    @property
    def body_names(self) -> tuple[str, ...]:
        """Names of the bodies in state order."""
        return tuple(b.name for b in self.bodies)

    @property
    def wheelsets(self) -> tuple[str, ...]:
        """Names of the wheelsets (bodies named ``wheelset*``), leading first."""
        return tuple(b.name for b in self.bodies if b.is_wheelset)

    def body_index(self) -> np.ndarray:
        """Indices of ``(y, psi, phi)`` of every body in ``q`` (-1: none), shape (n, 3)."""
        return np.array([self.body_dofs(b) for b in self.body_names], dtype=np.int64)

    def wheelset_index(self) -> np.ndarray:
        """Indices of ``(y, psi)`` of every wheelset in ``q``, shape ``(n_wheelsets, 2)``."""
        return np.array(
            [self.body_dofs(w)[:2] for w in self.wheelsets], dtype=np.int64
        ).reshape(-1, 2)

    @property
    def wheelset_y(self) -> np.ndarray:
        """Indices of the wheelsets' lateral displacements in ``q`` (and the state)."""
        return self.wheelset_index()[:, 0].copy()

    @property
    def wheelset_psi(self) -> np.ndarray:
        """Indices of the wheelsets' yaw angles in ``q``."""
        return self.wheelset_index()[:, 1].copy()

    @property
    def y_w1(self) -> int:
        """Index of the leading (first) wheelset's lateral displacement."""
        return int(self.wheelset_index()[0, 0])

    @property
    def body_y(self) -> np.ndarray:
        """Indices of the lateral displacements of the bodies that are not wheelsets."""
        return np.array([self.body_dofs(b.name)[0] for b in self.bodies
                         if not b.is_wheelset and "y" in b.coordinates],
                        dtype=np.int64)  # fmt: skip

    @property
    def forces(self) -> slice:
        """Slice of the damper forces in the state vector."""
        return slice(self.force0, self.force0 + self.n_damper)


_LATERAL_YAW_ROLL = ("y", "psi", "phi")
_LATERAL_YAW = ("y", "psi")

#: The paper's 17-DOF vehicle: car body and two bogie frames (lateral, yaw, roll), four
#: wheelsets (lateral, yaw); four yaw dampers (front left, front right, rear left, rear
#: right).
VEHICLE_17DOF = StateLayout(
    bodies=(
        Body("car", "c", _LATERAL_YAW_ROLL),
        Body("bogie1", "t1", _LATERAL_YAW_ROLL),
        Body("bogie2", "t2", _LATERAL_YAW_ROLL),
        Body("wheelset1", "w1", _LATERAL_YAW),
        Body("wheelset2", "w2", _LATERAL_YAW),
        Body("wheelset3", "w3", _LATERAL_YAW),
        Body("wheelset4", "w4", _LATERAL_YAW),
    ),
    dampers=("d1", "d2", "d3", "d4"),
)

# ---- the 17-DOF vehicle's slots ------------------------------------------------------
LAYOUT = VEHICLE_17DOF
#: Names of the 17 generalised coordinates, in state order.
DOF_NAMES: tuple[str, ...] = LAYOUT.dof_names
#: Names of the yaw dampers.
DAMPER_NAMES: tuple[str, ...] = LAYOUT.dampers
N_DOF = LAYOUT.n_dof
N_DAMPER = LAYOUT.n_damper
#: Length of the state vector (38).
N_STATE = LAYOUT.n_state
#: Index of the first rate (``x[RATE0 + i]`` is the rate of coordinate ``i``).
RATE0 = LAYOUT.rate0
#: Index of the first yaw damper force.
FORCE0 = LAYOUT.force0
#: Names of the 38 states.
STATE_NAMES: tuple[str, ...] = LAYOUT.state_names
#: Body name -> indices of (y, psi, phi) in q; -1 where the body has no such coordinate.
BODY_DOFS: dict[str, tuple[int, int, int]] = {b: LAYOUT.body_dofs(b) for b in LAYOUT.body_names}
#: Lateral displacements of the car body and the bogie frames in q.
BODY_Y = np.array([LAYOUT.dof(n) for n in ("y_c", "y_t1", "y_t2")])
#: Roll angles of the bogie frames in q.
BOGIE_PHI = np.array([LAYOUT.dof(n) for n in ("phi_t1", "phi_t2")])
#: Indices of (y, psi, phi) of each body in q (-1: none), shape (7, 3).
BODY_INDEX = LAYOUT.body_index()
#: Indices of (y, psi) of each wheelset in q, shape (4, 2).
WHEELSET_INDEX = LAYOUT.wheelset_index()
#: Indices of the wheelsets' lateral displacements (and in the state vector).
WHEELSET_Y = WHEELSET_INDEX[:, 0].copy()
#: Indices of the wheelsets' yaw angles.
WHEELSET_PSI = WHEELSET_INDEX[:, 1].copy()
#: Index of the leading wheelset's lateral displacement.
Y_W1 = LAYOUT.dof("y_w1")
#: Slice of the yaw damper forces in the state vector.
FORCES = slice(FORCE0, FORCE0 + N_DAMPER)


class WR(IntEnum):
    """Slots of the wheel/rail parameter vector (SI units).

    After ``TABLE`` comes either nothing (``TABLE`` holds 0: the polynomial geometry of
    Eqs. 32-33) or a contact table on a uniform grid of the wheelset's lateral
    displacement: ``[n, y0, dy, r_L[n], r_R[n], delta_L[n], delta_R[n]]`` starting at
    ``TABLE`` (see :func:`railhunt.kernel.contact.wheel_geometry`). A table may be
    followed by the per-point contact mechanics (:class:`PointColumn`): at
    ``p = TABLE + 3 + 4 n`` the code :data:`PER_POINT` (0 or absent: the vehicle's
    centred coefficients, as before), at ``p + 1`` the cube root of the static load
    ``N^(1/3)``, then for each grid point the columns of the left wheel and those of the
    right wheel (``2 N_POINT_COLUMNS`` values per point, contiguous:
    :func:`railhunt.kernel.point_contact.point_columns` reads two blocks).
    """

    F11 = 0  # longitudinal creep coefficient (N)
    F22 = 1  # lateral creep coefficient (N)
    F23 = 2  # lateral/spin creep coefficient (N*m)
    F33 = 3  # spin creep coefficient (N*m^2)
    MU = 4  # friction coefficient
    N = 5  # normal load per wheel (N)
    A = 6  # half the contact-point distance (m)
    R0 = 7  # centred rolling radius (m)
    LAMBDA1 = 8  # rolling-radius polynomial coefficients (1, 1/m, ... 1/m^4)
    LAMBDA2 = 9
    LAMBDA3 = 10
    LAMBDA4 = 11
    LAMBDA5 = 12
    D0 = 13  # contact-angle polynomial coefficients (rad, rad/m, rad/m^4, rad/m^5)
    D1 = 14
    D4 = 15
    D5 = 16
    DELTA_MAX = 17  # flange angle: the contact angle's limit (rad)
    CREEP_LAW = 18  # railhunt.kernel.creep.CreepLaw code
    INV_MW = 19  # 1 / wheelset mass (1/kg)
    INV_JW = 20  # 1 / wheelset yaw inertia (1/(kg*m^2))
    W = 21  # axle load: the mass carried by one wheelset (kg)
    G = 22  # acceleration of gravity (m/s^2)
    MH = 23  # sum of mass times height above rail carried by one wheelset (kg*m): load transfer
    TABLE = 24  # number of contact-table points (0: polynomials), then the table


#: Length of the wheel/rail vector without a contact table (the 0 in ``TABLE`` included).
N_WR = WR.TABLE + 1

#: Code after a contact table: the contact mechanics are computed at each contact point.
PER_POINT = 1


class PointColumn(IntEnum):
    """Per-point contact mechanics: the columns tabulated for each wheel along ``y``.

    With ``Q`` the wheel's vertical load and ``N0 = Q / cos(delta)`` its normal force
    without creep forces, the Hertz ellipse's ``c = sqrt(a b) = C1 Q^(1/3)`` and Kalker's
    coefficients ``f11 = K11 Q^(2/3)``, ``f22 = K22 Q^(2/3)``, ``f23 = K23 Q``,
    ``f33 = K33 Q^(4/3)`` (the powers of ``1/cos(delta)`` of ``N0`` are in the columns).
    ``AB`` is the index of the creep table's slice nearest the ellipse's ``a/b``
    (:mod:`railhunt.kernel.creep_table`; interpolated in ``y``, fractional between points
    of different slices).
    """

    C1 = 0  # sqrt(a b) per Q^(1/3) (m / N^(1/3))
    K11 = 1  # f11 per Q^(2/3) (N^(1/3))
    K22 = 2  # f22 per Q^(2/3) (N^(1/3))
    K23 = 3  # f23 per Q (m)
    K33 = 4  # f33 per Q^(4/3) (m^2 / N^(1/3))
    AB = 5  # the creep table's slice of this a/b (index)


#: Number of per-point columns of one wheel.
N_POINT_COLUMNS = len(PointColumn)

#: Code after a contact table: up to two contact patches per wheel, tabulated over the
#: lateral displacement and the yaw (:mod:`railhunt.kernel.two_point`).
TWO_POINT = 2


class TwoPointHeader(IntEnum):
    """Slots of the two-point block, from ``p = TABLE + 3 + 4 n`` (after the contact
    table); the patches' columns follow at ``DATA``: for each yaw node, for each lateral
    node, the left wheel's two slots then the right wheel's (``4 N_PATCH_COLUMNS``
    values per node)."""

    CODE = 0  # TWO_POINT
    QTH = 1  # cube root of the static wheel load (N^(1/3))
    N_Y = 2  # lateral nodes
    Y0 = 3  # first lateral node (m)
    DY = 4  # lateral step (m)
    N_PSI = 5  # yaw nodes
    PSI0 = 6  # first yaw node (rad)
    DPSI = 7  # yaw step (rad)
    DATA = 8


class PatchColumn(IntEnum):
    """The columns of one contact patch (a slot) of a wheel in the two-point table.

    With ``Q`` the wheel's vertical load and ``W`` the patch's share of it, the patch's
    normal force without creep forces is ``N0 = W Q / cos(delta)``; the coefficients hold
    the powers of ``W / cos(delta)``, as :class:`PointColumn` holds those of
    ``1 / cos(delta)``: ``c = C1 Q^(1/3)``, ``f11 = K11 Q^(2/3)``, ``f22 = K22 Q^(2/3)``,
    ``f23 = K23 Q``, ``f33 = K33 Q^(4/3)``. A slot without a patch has ``W = 0``.
    """

    W = 0  # share of the wheel's vertical load (-)
    R = 1  # rolling radius (m)
    D = 2  # contact angle (rad)
    X = 3  # lead ahead of the axle, along the track (m)
    S = 4  # axle coordinate of the contact's section (m, + left)
    C1 = 5  # sqrt(a b) per Q^(1/3) (m / N^(1/3))
    K11 = 6  # f11 per Q^(2/3)
    K22 = 7  # f22 per Q^(2/3)
    K23 = 8  # f23 per Q (m)
    K33 = 9  # f33 per Q^(4/3)
    AB = 10  # the creep table's slice of this a/b (index)


#: Number of columns of one patch.
N_PATCH_COLUMNS = len(PatchColumn)


class DamperParam(IntEnum):
    """Columns of the yaw damper parameter array (one row per damper)."""

    K_D = 0  # series stiffness (N/m)
    C_D1 = 1  # first-stage damping (N*s/m)
    C_D2 = 2  # second-stage damping (N*s/m)
    F_U = 3  # blow-off force (N)


class StopParam(IntEnum):
    """Columns of the bump stop parameter array (one row per bump stop)."""

    GAP = 0  # free play (m)
    K1 = 1  # linear stiffness once in contact (N/m)
    K3 = 2  # cubic (progressive) stiffness (N/m^3)


class RouteColumn(IntEnum):
    """Columns of the route array: one row per segment of track geometry.

    Within a segment starting at ``S0``, at ``u = s - S0``: curvature
    ``kappa = KAPPA0 + DKAPPA u`` (1/m, + for a curve to the left), heading
    ``theta = THETA0 + KAPPA0 u + DKAPPA u^2 / 2`` (rad), its integral
    ``Phi = PHI0 + THETA0 u + KAPPA0 u^2 / 2 + DKAPPA u^3 / 6`` (m) and cant angle
    ``CANT0 + DCANT u`` (rad, + when a point above the track moves toward +y). Before
    the first row the track is straight and aligned with heading 0.
    """

    S0 = 0  # start of the segment (m)
    S1 = 1  # end of the segment (m)
    KAPPA0 = 2
    DKAPPA = 3
    THETA0 = 4
    PHI0 = 5
    CANT0 = 6
    DCANT = 7


#: Number of route columns.
N_ROUTE = len(RouteColumn)


#: No bump stop acts against the track (default of ``SystemArrays.stop_wheelset``).
NO_TRACK_STOPS = np.zeros(0, dtype=np.int64)
#: No creep table (default of ``SystemArrays.creep_table``).
NO_CREEP_TABLE = np.zeros(0)
#: The empty work array of :class:`SystemArrays` (no staged per-point contact).
NO_CONTACT_WORK = np.zeros((0, 0))


class SystemArrays(NamedTuple):
    """Everything the compiled right-hand side needs besides ``(t, x, v)``.

    Built by :meth:`railhunt.model.Model.system`; passed as one argument to every kernel
    function (``rhs(t, x, v, system, out)``).

    Attributes
    ----------
    linear : numpy.ndarray, shape (n_dof, 2 n_dof)
        ``-M^-1 [K + G, C]``: accelerations from the linear suspension (Fortran order:
        :func:`railhunt.kernel.rhs.rhs` runs down its columns).
    damper_rows : numpy.ndarray, shape (n_damper, n_dof)
        Yaw damper elongation rows ``B_d`` (elongation = ``B_d @ q``).
    damper_acc : numpy.ndarray, shape (n_dof, n_damper)
        ``-M^-1 B_d^T``: accelerations per unit damper force.
    damper : numpy.ndarray, shape (n_damper, 4)
        Damper parameters, columns :class:`DamperParam`.
    wheel_rail : numpy.ndarray, shape (n_wheelsets, width)
        Wheel/rail parameters, one row per wheelset (slots :class:`WR`), so wheelsets may
        differ in mass, load, radius, contact geometry and creep law. Rows are padded
        with zeros to the longest contact table; each row's ``TABLE`` slot says how much
        of it is used. Slot ``G`` (gravity) is read from the first row.
    wheelsets : numpy.ndarray of int64, shape (n_wheelsets, 2)
        Indices of each wheelset's ``(y, psi)`` in ``q``.
    wheelset_delay : numpy.ndarray, shape (n_wheelsets,)
        Distance of each wheelset behind the leading one (m): it meets the track input at
        track position ``v t - delay``.
    track : numpy.ndarray, shape (4,)
        Track input ``[code, p1, p2, p3]`` (:mod:`railhunt.kernel.track`).
    track_samples : numpy.ndarray
        Alignment samples of a sampled track (m), else one dummy entry.
    stop_rows : numpy.ndarray, shape (n_stop, n_dof)
        Deformation rows of the bump stops (deformation = ``stop_rows @ q``).
    stop_acc : numpy.ndarray, shape (n_dof, n_stop)
        ``-M^-1 B_s^T``: accelerations per unit bump-stop force.
    stop : numpy.ndarray, shape (n_stop, 3)
        Bump stop parameters, columns :class:`StopParam`.
    route : numpy.ndarray, shape (n_segments, N_ROUTE)
        Track geometry (:class:`RouteColumn`); no rows: straight track.
    bodies : numpy.ndarray of int64, shape (n_bodies, 3)
        Indices of each body's ``(y, psi, phi)`` in ``q`` (-1: none); the first body is
        the reference of the curve's geometric offsets.
    body_delay : numpy.ndarray, shape (n_bodies,)
        Distance of each body behind the leading wheelset (m).
    suspension : numpy.ndarray, shape (n_dof, 2 n_dof)
        ``-M^-1 [K, C]`` of the suspension alone (no gravitational terms): accelerations
        from the geometric offsets a curve imposes.
    scratch : numpy.ndarray, shape (3 n_dof,)
        Work space of the curve terms (overwritten at every call; the kernel is used by
        one thread at a time per bundle).
    stop_wheelset : numpy.ndarray of int64, shape (n_stop,) or (0,)
        For each bump stop, the wheelset whose rails are its second body (a flange: its
        deformation is ``stop_rows @ q`` minus the rails' lateral alignment at that
        wheelset, the track input with the wheelset's delay), -1 for a stop between two
        bodies of the vehicle. Shorter than ``stop`` (default: empty): the missing stops
        are between bodies.
    creep_table : numpy.ndarray
        The tabulated creep law of per-point contact mechanics
        (:mod:`railhunt.kernel.creep_table`), empty when no wheelset uses it.
    contact_work : numpy.ndarray, shape (N_STAGE_SLOTS, 2 n_wheelsets) or (0, 0)
        Work space of the wheelsets whose per-point contact uses the tabulated law: the
        right-hand side evaluates their creep forces together
        (:func:`railhunt.kernel.point_contact.stage_point_contact`); overwritten at every
        call, one thread at a time per bundle like ``scratch``. Empty: each wheelset on
        its own.
    """

    linear: np.ndarray
    damper_rows: np.ndarray
    damper_acc: np.ndarray
    damper: np.ndarray
    wheel_rail: np.ndarray
    wheelsets: np.ndarray
    wheelset_delay: np.ndarray
    track: np.ndarray
    track_samples: np.ndarray
    stop_rows: np.ndarray
    stop_acc: np.ndarray
    stop: np.ndarray
    route: np.ndarray
    bodies: np.ndarray
    body_delay: np.ndarray
    suspension: np.ndarray
    scratch: np.ndarray
    stop_wheelset: np.ndarray = NO_TRACK_STOPS
    creep_table: np.ndarray = NO_CREEP_TABLE
    contact_work: np.ndarray = NO_CONTACT_WORK
