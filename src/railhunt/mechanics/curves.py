"""Creep-force curves: the laws side by side on one patch, one creepage swept.

:func:`creep_curves` evaluates :func:`railhunt.mechanics.laws.creep_forces` for every law
asked for over a sweep of ``xi``, ``eta`` or ``phi`` with the other two fixed, and keeps
the patch's data (semi-axes, load, friction, material, Kalker's coefficients) with the
result, so that a table, a JSON object or a figure (:func:`railhunt.plots.creep_figure`)
can say what was computed.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from railhunt.mechanics.coefficients import kalker_coefficients
from railhunt.mechanics.laws import LAWS, creep_forces
from railhunt.results import Columns, ResultDisplay, Row

__all__ = ["SWEEPS", "CreepCurves", "creep_curves"]

#: Creepages that can be swept, and their units.
SWEEPS = {"xi": "", "eta": "", "phi": "1/m"}


@dataclass(frozen=True, repr=False)
class CreepCurves(ResultDisplay):
    """Creep forces of several laws over a sweep of one creepage on one patch.

    Attributes
    ----------
    sweep : str
        ``"xi"``, ``"eta"`` or ``"phi"``.
    values : ndarray
        The swept creepage (``phi`` in 1/m).
    fixed : dict
        The other two creepages.
    a, b, normal_force, mu, shear_modulus, poisson : float
        The patch (m, m, N, -, Pa, -).
    fx, fy, mz : dict of str to ndarray
        Per law, the forces (N) and the spin moment (N*m) along the sweep.
    """

    sweep: str
    values: np.ndarray
    fixed: dict[str, float]
    a: float
    b: float
    normal_force: float
    mu: float
    shear_modulus: float
    poisson: float
    fx: dict[str, np.ndarray] = field(default_factory=dict)
    fy: dict[str, np.ndarray] = field(default_factory=dict)
    mz: dict[str, np.ndarray] = field(default_factory=dict)

    @property
    def laws(self) -> tuple[str, ...]:
        return tuple(self.fx)

    @property
    def c(self) -> float:
        """``sqrt(a b)`` (m)."""
        return float(np.sqrt(self.a * self.b))

    @property
    def coefficients(self) -> tuple[float, float, float, float]:
        """Kalker's ``C11, C22, C23, C33`` of the patch."""
        return kalker_coefficients(self.a / self.b, self.poisson)

    def _summary(self) -> list[Row]:
        c11, c22, c23, c33 = self.coefficients
        return [("patch a x b", f"{self.a * 1e3:.4g} x {self.b * 1e3:.4g}", "mm"),
                ("normal force", self.normal_force, "N"), ("mu", self.mu, ""),
                ("Kalker C11, C22, C23, C33", f"{c11:.4g}, {c22:.4g}, {c23:.4g}, {c33:.4g}",
                 ""),
                ("swept", f"{self.sweep} from {self.values[0]:.4g} to {self.values[-1]:.4g}",
                 SWEEPS[self.sweep]),
                ("fixed", ", ".join(f"{k} = {v:.4g}" for k, v in self.fixed.items()), ""),
                ("laws", ", ".join(self.laws), "")]  # fmt: skip

    def _columns(self) -> Columns:
        cols: Columns = {self.sweep: (self.values, SWEEPS[self.sweep])}
        for law in self.laws:
            cols[f"fx_{law}"] = (self.fx[law], "N")
            cols[f"fy_{law}"] = (self.fy[law], "N")
            cols[f"mz_{law}"] = (self.mz[law], "N*m")
        return cols


def creep_curves(sweep: str, values, *, a: float, b: float, mu: float, normal_force: float,
                 laws=LAWS, xi: float = 0.0, eta: float = 0.0, phi: float = 0.0,
                 shear_modulus: float = 8.2e10, poisson: float = 0.28,
                 grid=None) -> CreepCurves:
    """Creep forces of ``laws`` on one patch over ``values`` of the creepage ``sweep``.

    Parameters
    ----------
    sweep : {"xi", "eta", "phi"}
        The creepage swept.
    values : array_like
        Its values (``phi`` in 1/m).
    a, b, mu, normal_force, shear_modulus, poisson, grid
        As :func:`railhunt.creep_forces`.
    laws : sequence of str
        Laws to evaluate (default: all).
    xi, eta, phi : float
        The fixed creepages (the swept one's is ignored).

    Returns
    -------
    CreepCurves
    """
    if sweep not in SWEEPS:
        raise ValueError(f"sweep = {sweep!r} is invalid: must be 'xi', 'eta' or 'phi'")
    values = np.atleast_1d(np.asarray(values, dtype=float))
    fixed = {k: float(v) for k, v in (("xi", xi), ("eta", eta), ("phi", phi)) if k != sweep}
    args = {**fixed, sweep: values}
    out = CreepCurves(sweep, values, fixed, float(a), float(b), float(normal_force),
                      float(mu), float(shear_modulus), float(poisson))
    for law in laws:
        grid_law = grid if law in ("exact", "fastsim", "fastsim-modified") else None
        r = creep_forces(args["xi"], args["eta"], args["phi"], a=a, b=b, mu=mu,
                         normal_force=normal_force, law=law, shear_modulus=shear_modulus,
                         poisson=poisson, grid=grid_law)
        out.fx[law] = np.broadcast_to(r.fx, values.shape).copy()
        out.fy[law] = np.broadcast_to(r.fy, values.shape).copy()
        out.mz[law] = np.broadcast_to(r.mz, values.shape).copy()
    return out
