"""Suspension elements between attachment points, and the yaw damper.

Every spring and damper of the vehicle joins a point on one body to a point on another
and acts along one axis (x longitudinal, y lateral, z vertical). Its deformation is a
linear function of the generalised coordinates (small angles), ``delta = B @ q``, so a
spring of stiffness ``k`` contributes ``k * B.T @ B`` to the stiffness matrix and a
damper ``c * B.T @ B`` to the damping matrix. Action equals reaction by construction,
and both matrices are symmetric.

Sign conventions (see ``docs/model.md``): x forward, y to the left, z up; yaw ``psi``
positive when the nose turns toward +y; roll ``phi`` positive when a point above the
centre of gravity moves toward +y. For a point at body-fixed position ``(px, py, pz)``
relative to the centre of gravity::

    u_x = -psi * py
    u_y = y + psi * px + phi * pz
    u_z = -phi * py

The yaw damper is a Maxwell element (linear spring ``K_d`` in series with a two-stage
viscous damper, Eqs. 35-37 of the paper); its force is an ODE state (see
:func:`damper_velocity`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numba import njit

from railhunt.vehicle import Vehicle

#: Names of the 17 generalised coordinates, in state order.
DOF_NAMES: tuple[str, ...] = (
    "y_c", "psi_c", "phi_c",
    "y_t1", "psi_t1", "phi_t1",
    "y_t2", "psi_t2", "phi_t2",
    "y_w1", "psi_w1", "y_w2", "psi_w2", "y_w3", "psi_w3", "y_w4", "psi_w4",
)  # fmt: skip
N_DOF = len(DOF_NAMES)
#: Yaw dampers: front bogie left/right, rear bogie left/right.
DAMPER_NAMES: tuple[str, ...] = ("d1", "d2", "d3", "d4")
N_DAMPER = len(DAMPER_NAMES)

# Body name -> indices of (y, psi, phi) in q; -1 where the body has no such coordinate.
BODY_DOFS: dict[str, tuple[int, int, int]] = {
    "car": (0, 1, 2),
    "bogie1": (3, 4, 5),
    "bogie2": (6, 7, 8),
    "wheelset1": (9, 10, -1),
    "wheelset2": (11, 12, -1),
    "wheelset3": (13, 14, -1),
    "wheelset4": (15, 16, -1),
}


@dataclass(frozen=True)
class Element:
    """A linear spring or damper between two attachment points.

    Parameters
    ----------
    name : str
        Label, e.g. ``"primary lateral spring, wheelset 1 left"``.
    kind : {"spring", "damper"}
        Spring (coefficient in N/m) or viscous damper (N*s/m).
    axis : {"x", "y", "z"}
        Direction in which the element acts.
    body_a, body_b : str
        Bodies joined (keys of :data:`BODY_DOFS`).
    point_a, point_b : tuple of float
        Attachment points ``(px, py, pz)`` in m, relative to each body's centre of gravity.
    coefficient : float
        Stiffness (N/m) or damping (N*s/m).
    """

    name: str
    kind: str
    axis: str
    body_a: str
    point_a: tuple[float, float, float]
    body_b: str
    point_b: tuple[float, float, float]
    coefficient: float

    def deformation_row(self) -> np.ndarray:
        """Row ``B`` with ``deformation = B @ q`` (point b minus point a along the axis)."""
        return point_row(self.body_b, self.point_b, self.axis) - point_row(
            self.body_a, self.point_a, self.axis
        )


def point_row(body: str, point: tuple[float, float, float], axis: str) -> np.ndarray:
    """Displacement of a body-fixed point along ``axis`` as a row over the 17 coordinates.

    Parameters
    ----------
    body : str
        Key of :data:`BODY_DOFS`.
    point : tuple of float
        ``(px, py, pz)`` in m relative to the body's centre of gravity.
    axis : {"x", "y", "z"}
        Displacement component.

    Returns
    -------
    numpy.ndarray
        Row of length 17 (m per m or m per rad).
    """
    iy, ipsi, iphi = BODY_DOFS[body]
    px, py, pz = point
    row = np.zeros(N_DOF)
    if axis == "x":
        row[ipsi] = -py
    elif axis == "y":
        row[iy] = 1.0
        row[ipsi] = px
        if iphi >= 0:
            row[iphi] = pz
    elif axis == "z":
        if iphi >= 0:
            row[iphi] = -py
    else:
        raise ValueError(f"axis must be 'x', 'y' or 'z', got {axis!r}")
    return row


def suspension_elements(vehicle: Vehicle) -> list[Element]:
    """All linear springs and dampers of the vehicle (primary and secondary suspension).

    The yaw dampers are not included: they are Maxwell elements with their own state
    (see :func:`yaw_damper_rows`).
    """
    v = vehicle
    els: list[Element] = []
    sides = ((1.0, "left"), (-1.0, "right"))
    # Primary suspension: per axle box (two per wheelset).
    for j in range(4):
        bogie = f"bogie{j // 2 + 1}"
        ws = f"wheelset{j + 1}"
        xr = v.l1 if j % 2 == 0 else -v.l1
        for s, side in sides:
            tag = f"wheelset {j + 1} {side}"
            pb = (xr, s * v.b1, -v.h4)
            pw = (0.0, s * v.b1, 0.0)
            els += [
                Element(f"primary longitudinal spring, {tag}", "spring", "x", bogie, pb, ws, pw,
                        v.K_px),
                Element(f"primary longitudinal damper, {tag}", "damper", "x", bogie, pb, ws, pw,
                        v.C_px),
                Element(f"primary lateral spring, {tag}", "spring", "y", bogie, pb, ws, pw, v.K_py),
                Element(f"primary lateral damper, {tag}", "damper", "y", bogie, pb, ws, pw, v.C_py),
                Element(f"primary vertical spring, {tag}", "spring", "z", bogie, pb, ws, pw,
                        v.K_pz),
                Element(f"primary vertical damper, {tag}", "damper", "z", bogie, pb, ws, pw,
                        v.C_pz),
            ]  # fmt: skip
    # Secondary suspension: two air springs, two lateral and two vertical dampers per bogie.
    for i in range(2):
        bogie = f"bogie{i + 1}"
        xc = v.l if i == 0 else -v.l
        for s, side in sides:
            tag = f"bogie {i + 1} {side}"
            spring_c, spring_t = (xc, s * v.b2, -v.h1), (0.0, s * v.b2, v.h3)
            lat_c, lat_t = (xc, s * v.b2, -v.h2), (0.0, s * v.b2, v.h5)
            vd_c, vd_t = (xc, s * v.b3, -v.h1), (0.0, s * v.b3, v.h3)
            els += [
                Element(f"secondary longitudinal spring, {tag}", "spring", "x", "car", spring_c,
                        bogie, spring_t, v.K_sx),
                Element(f"secondary lateral spring, {tag}", "spring", "y", "car", spring_c, bogie,
                        spring_t, v.K_sy),
                Element(f"secondary vertical spring, {tag}", "spring", "z", "car", spring_c, bogie,
                        spring_t, v.K_sz),
                Element(f"secondary lateral damper, {tag}", "damper", "y", "car", lat_c, bogie,
                        lat_t, v.C_sy),
                Element(f"secondary vertical damper, {tag}", "damper", "z", "car", vd_c, bogie,
                        vd_t, v.C_sz),
            ]  # fmt: skip
    return els


def assemble(elements: list[Element]) -> tuple[np.ndarray, np.ndarray]:
    """Stiffness and damping matrices of a set of elements.

    Returns
    -------
    K : numpy.ndarray, shape (17, 17)
        Stiffness matrix (N/m, N*m/rad, ...), symmetric.
    C : numpy.ndarray, shape (17, 17)
        Damping matrix (N*s/m, ...), symmetric.
    """
    K = np.zeros((N_DOF, N_DOF))
    C = np.zeros((N_DOF, N_DOF))
    for el in elements:
        b = el.deformation_row()
        target = K if el.kind == "spring" else C
        target += el.coefficient * np.outer(b, b)
    return K, C


def gravity_stiffness(vehicle: Vehicle) -> np.ndarray:
    """Gravitational roll stiffness of car body and bogie frames (Eqs. 12 and 22).

    A body whose weight is carried on springs a height ``h`` below its centre of gravity
    has a destabilising roll stiffness ``-m g h``: car body on the secondary suspension
    (``h1``), bogie frames on the primary suspension at wheelset-centre height (``h4``).
    """
    G = np.zeros((N_DOF, N_DOF))
    G[2, 2] = -vehicle.M_c * vehicle.g * vehicle.h1
    for iphi in (5, 8):
        G[iphi, iphi] = -vehicle.M_t * vehicle.g * vehicle.h4
    return G


def mass_matrix_diagonal(vehicle: Vehicle) -> np.ndarray:
    """Diagonal of the mass matrix (kg and kg*m^2) in state order."""
    v = vehicle
    return np.array(
        [v.M_c, v.J_cz, v.J_cx]
        + [v.M_t, v.J_tz, v.J_tx] * 2
        + [v.M_w, v.J_wz] * 4
    )


def yaw_damper_rows(vehicle: Vehicle) -> np.ndarray:
    """Elongation rows of the four yaw dampers, ``elongation = B_d @ q`` (m).

    Each damper runs longitudinally between the car body (at x = +-l) and a bogie frame,
    at lateral arm ``b4``. Order: front left, front right, rear left, rear right.
    """
    rows = []
    for i in range(2):
        xc = vehicle.l if i == 0 else -vehicle.l
        for s in (1.0, -1.0):
            rows.append(
                point_row(f"bogie{i + 1}", (0.0, s * vehicle.b4, 0.0), "x")
                - point_row("car", (xc, s * vehicle.b4, 0.0), "x")
            )
    return np.array(rows)


@njit(cache=True)
def damper_velocity(force: float, c1: float, c2: float, f_u: float) -> float:
    """Velocity of the two-stage viscous damper carrying ``force`` (inverse of Fig. 4b).

    Parameters
    ----------
    force : float
        Damper force (N), positive in tension.
    c1, c2 : float
        First- and second-stage damping (N*s/m).
    f_u : float
        Blow-off force (N); the blow-off velocity is ``f_u / c1``.

    Returns
    -------
    float
        Elongation rate of the viscous part (m/s): ``force / c1`` below blow-off,
        ``sign(force) * (f_u / c1 + (|force| - f_u) / c2)`` above. Odd in ``force``.
    """
    af = abs(force)
    if af <= f_u:
        return force / c1
    vel = f_u / c1 + (af - f_u) / c2
    return vel if force > 0.0 else -vel


@njit(cache=True)
def damper_force_steady(velocity: float, c1: float, c2: float, f_u: float) -> float:
    """Steady two-stage damper force at a constant velocity (Fig. 4b), N.

    ``c1 * v`` for ``|v| <= v_u = f_u / c1``, then ``sign(v) * (f_u + c2 * (|v| - v_u))``.
    """
    v_u = f_u / c1
    av = abs(velocity)
    if av <= v_u:
        return c1 * velocity
    f = f_u + c2 * (av - v_u)
    return f if velocity > 0.0 else -f
