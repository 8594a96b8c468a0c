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
viscous damper, Eqs. 35-37 of the paper); its force is an ODE state. Its rows are
assembled here (:func:`yaw_damper_rows`); its law is compiled in
:mod:`railhunt.kernel.damper` (:func:`damper_velocity`, re-exported here).

The state layout (which coordinate sits where) is :mod:`railhunt.kernel.layout`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from railhunt.kernel.damper import damper_force_steady, damper_velocity
from railhunt.kernel.layout import BODY_DOFS, DAMPER_NAMES, DOF_NAMES, LAYOUT, N_DAMPER, N_DOF
from railhunt.vehicle import Vehicle

__all__ = [
    "BODY_DOFS", "DAMPER_NAMES", "DOF_NAMES", "N_DAMPER", "N_DOF", "Element", "assemble",
    "bump_stop_rows",
    "damper_force_steady", "damper_velocity", "gravity_stiffness", "mass_matrix_diagonal",
    "point_row", "suspension_elements", "yaw_damper_rows",
]  # fmt: skip

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
    """Displacement of a body-fixed point along ``axis`` as a row over the coordinates q.

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
        Row of length ``N_DOF`` (m per m or m per rad).
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
    K : numpy.ndarray, shape (N_DOF, N_DOF)
        Stiffness matrix (N/m, N*m/rad, ...), symmetric.
    C : numpy.ndarray, shape (N_DOF, N_DOF)
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
    car = LAYOUT.dof("phi_c")
    G[car, car] = -vehicle.M_c * vehicle.g * vehicle.h1
    for iphi in (LAYOUT.dof("phi_t1"), LAYOUT.dof("phi_t2")):
        G[iphi, iphi] = -vehicle.M_t * vehicle.g * vehicle.h4
    return G


def mass_matrix_diagonal(vehicle: Vehicle) -> np.ndarray:
    """Diagonal of the mass matrix (kg and kg*m^2) in state order."""
    v = vehicle
    inertia = {
        "car": {"y": v.M_c, "psi": v.J_cz, "phi": v.J_cx},
        "bogie": {"y": v.M_t, "psi": v.J_tz, "phi": v.J_tx},
        "wheelset": {"y": v.M_w, "psi": v.J_wz},
    }
    return np.array(
        [inertia[b.name.rstrip("0123456789")][c] for b in LAYOUT.bodies for c in b.coordinates]
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


def bump_stop_rows(vehicle: Vehicle) -> np.ndarray:
    """Deformation rows of the secondary lateral bump stops, one per bogie (m).

    Each stop acts laterally between the car body (at x = +-l) and its bogie frame at the
    level of the secondary suspension (car ``-h1``, bogie ``+h3`` from the centres of
    gravity): deformation = bogie point minus car point, ``B_s @ q``. Its law (free play
    ``y_bs``, then ``K_bs u + K_bs3 u^3``) is :mod:`railhunt.kernel.bumpstop`.
    """
    rows = []
    for i in range(2):
        xc = vehicle.l if i == 0 else -vehicle.l
        rows.append(point_row(f"bogie{i + 1}", (0.0, 0.0, vehicle.h3), "y")
                    - point_row("car", (xc, 0.0, -vehicle.h1), "y"))  # fmt: skip
    return np.array(rows)
