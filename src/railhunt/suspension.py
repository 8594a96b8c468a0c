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
from railhunt.kernel.layout import (
    BODY_DOFS,
    DAMPER_NAMES,
    DOF_NAMES,
    LAYOUT,
    N_DAMPER,
    N_DOF,
    StateLayout,
)
from railhunt.layout.assembly import point_row as assembly_point_row
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

    def deformation_row(self, layout: StateLayout = LAYOUT) -> np.ndarray:
        """Row ``B`` with ``deformation = B @ q`` (point b minus point a along the axis)."""
        return point_row(self.body_b, self.point_b, self.axis, layout) - point_row(
            self.body_a, self.point_a, self.axis, layout
        )


def point_row(body: str, point: tuple[float, float, float], axis: str,
              layout: StateLayout = LAYOUT) -> np.ndarray:  # fmt: skip
    """Displacement of a body-fixed point along ``axis`` as a row over the coordinates q.

    Parameters
    ----------
    body : str
        Key of :data:`BODY_DOFS`.
    point : tuple of float
        ``(px, py, pz)`` in m relative to the body's centre of gravity.
    axis : {"x", "y", "z"}
        Displacement component.
    layout : StateLayout
        The state layout (default: the paper's vehicle).

    Returns
    -------
    numpy.ndarray
        Row of length ``n_dof`` (m per m or m per rad).
    """
    if axis not in ("x", "y", "z"):
        raise ValueError(f"axis must be 'x', 'y' or 'z', got {axis!r}")
    return assembly_point_row(layout.body_dofs(body), point, axis, layout.n_dof)


def suspension_elements(vehicle: Vehicle) -> list[Element]:
    """The linear springs and dampers of the vehicle's layout, with numeric arms.

    The layout's ``spring`` and ``damper`` elements along x, y, z between two moving bodies
    of the paper's coordinate names, in the layout's order (torsion elements, elements to
    the track or to a fixed body, Maxwell elements and stops are not included: the model
    reads all of them from :attr:`Vehicle.assembly`). Kept for scripts and tests that
    inspect the paper's suspension element by element; :func:`assemble` of these gives
    the assembly's matrices.
    """
    from railhunt.layout.assembly import arm

    layout = vehicle.layout
    values = vehicle.values
    out: list[Element] = []
    for el in layout.elements:
        if el.kind not in ("spring", "damper") or el.axis not in ("x", "y", "z"):
            continue
        if el.body_b == "track":
            continue
        a, b = layout.body(el.body_a), layout.body(el.body_b)
        if not (a.coordinates and b.coordinates):
            continue
        key = "stiffness" if el.kind == "spring" else "damping"
        out.append(Element(el.name, el.kind, el.axis, a.name, arm(el.at, a, values), b.name,
                           arm(el.at_b, b, values), el.value(key)(values)))  # fmt: skip
    return out


def assemble(elements: list[Element],
             layout: StateLayout = LAYOUT) -> tuple[np.ndarray, np.ndarray]:  # fmt: skip
    """Stiffness and damping matrices of a set of elements (coordinates of ``layout``,
    default the paper's vehicle).

    Returns
    -------
    K : numpy.ndarray, shape (N_DOF, N_DOF)
        Stiffness matrix (N/m, N*m/rad, ...), symmetric.
    C : numpy.ndarray, shape (N_DOF, N_DOF)
        Damping matrix (N*s/m, ...), symmetric.
    """
    n = layout.n_dof
    K = np.zeros((n, n))
    C = np.zeros((n, n))
    for el in elements:
        b = el.deformation_row(layout)
        target = K if el.kind == "spring" else C
        target += el.coefficient * np.outer(b, b)
    return K, C


def gravity_stiffness(vehicle: Vehicle) -> np.ndarray:
    """Gravitational roll stiffness of the layout's bodies (Eqs. 12 and 22 for the paper's).

    A body whose weight is carried on springs a height ``h`` below its centre of gravity
    has a destabilising roll stiffness ``-m g h``: car body on the secondary suspension
    (``h1``), bogie frames on the primary suspension at wheelset-centre height (``h4``).
    The rule for any layout: docs/model.md, "Vehicle layouts".
    """
    return vehicle.assembly.gravity.copy()


def mass_matrix_diagonal(vehicle: Vehicle) -> np.ndarray:
    """Diagonal of the mass matrix (kg and kg*m^2) in state order."""
    return vehicle.assembly.mass.copy()


def yaw_damper_rows(vehicle: Vehicle) -> np.ndarray:
    """Elongation rows of the layout's Maxwell elements, ``elongation = B_d @ q`` (m).

    For the paper's vehicle: the four yaw dampers, each longitudinal between the car body
    (at x = +-l) and a bogie frame, at lateral arm ``b4``; order front left, front right,
    rear left, rear right.
    """
    return vehicle.assembly.damper_rows.copy()


def bump_stop_rows(vehicle: Vehicle) -> np.ndarray:
    """Deformation rows of the layout's stops (m).

    For the paper's vehicle: the secondary lateral bump stops, one per bogie, between the
    car body (at x = +-l) and its bogie frame at the level of the secondary suspension
    (car ``-h1``, bogie ``+h3`` from the centres of gravity): deformation = bogie point
    minus car point, ``B_s @ q``. Its law (free play ``y_bs``, then
    ``K_bs u + K_bs3 u^3``) is :mod:`railhunt.kernel.bumpstop`.
    """
    return vehicle.assembly.stop_rows.copy()
