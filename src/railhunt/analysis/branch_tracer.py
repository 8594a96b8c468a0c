"""Pseudo-arclength continuation of one direction of a branch of limit cycles.

:class:`BranchTracer` follows a branch from an orbit along its tangent (predictor along
the null vector of the shooting Jacobian, corrector by Newton on the residual plus the
arclength condition, step adapted to Newton's effort and limited in speed and amplitude
by :class:`BranchLimits`). :mod:`railhunt.analysis.continuation` (the bifurcation
diagram), :mod:`railhunt.analysis.hopf_start` (the branch's first orbits) and
:mod:`railhunt.analysis.fold` (the fold speed) trace with it.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from railhunt.analysis.periodic import PeriodicOrbit, Shooting, newton
from railhunt.units import ms_to_kmh

__all__ = ["BranchLimits", "BranchTracer"]


@dataclass
class BranchLimits:
    """Where and how finely a branch is traced: its speed range (km/h), largest amplitude
    (m) and number of orbits, the largest steps in speed (km/h) and amplitude (m)."""

    lo: float
    hi: float
    max_amplitude: float
    max_points: int
    max_step_kmh: float
    max_step_amplitude: float
    min_amplitude: float = 0.0  # m: a branch whose amplitude falls below this has ended
    max_ds: float = 50.0  # largest arclength step (scaled unknowns)
    newton_tol: float = 1e-9  # corrector's tolerance (scaled residual)


class BranchTracer:
    """Pseudo-arclength continuation of one direction of a branch."""

    def __init__(self, shoot: Shooting, limits: BranchLimits,
                 on_point: Callable[[PeriodicOrbit], None] | None) -> None:  # fmt: skip
        self.shoot = shoot
        self.limits = limits
        self.on_point = on_point
        keep = np.ones(shoot.n_state, dtype=bool)
        keep[shoot.phase_index] = False
        #: The displacement that measures the branch (the shooting's phase coordinate).
        self.measure = shoot.phase_coordinate
        self.iy = int(np.flatnonzero(keep).tolist().index(self.measure))
        #: The wheelset whose amplitude ends the branch at a second Hopf point.
        self.wheel = [int(i) for i in shoot.model.layout.wheelset_y].index(self.measure)

    def solve(self, u: np.ndarray, norm: float, it: int) -> tuple[PeriodicOrbit, tuple]:
        lin = self.shoot.linearise(u)
        orbit = self.shoot.orbit(u, norm, it, lin)
        if self.on_point is not None:
            self.on_point(orbit)
        return orbit, lin

    def null_vector(self, jac: np.ndarray, guess: np.ndarray) -> np.ndarray:
        aug = np.vstack([jac, guess])
        e = np.zeros(guess.size)
        e[-1] = 1.0
        t = np.linalg.solve(aug, e)
        return t / np.linalg.norm(t)

    def trace(self, u0: np.ndarray, lin0: tuple, tangent: np.ndarray, ds: float,
              budget: int, limits: BranchLimits | None = None,
              stop: Callable[[list[PeriodicOrbit]], str] | None = None,
              ) -> tuple[list[PeriodicOrbit], str, bool, bool]:  # fmt: skip
        """Follow the branch from ``u0`` along ``tangent``.

        Returns the new orbits, why it stopped, whether it stopped normally (False: Newton
        failed at the smallest step or the point budget ran out) and whether it left the
        speed range downward (the branch goes on below the range). ``stop(orbits)``,
        called after each new orbit, ends the trace (normally) when it returns a reason.
        """
        lim, shoot, iy = limits or self.limits, self.shoot, self.iy
        orbits: list[PeriodicOrbit] = []
        u_prev, lin = u0, lin0
        ds_min, ds_max = 1e-3, lim.max_ds
        for _ in range(budget):
            jac = shoot.jacobian(u_prev, lin=lin)
            tangent = self.null_vector(jac, tangent)
            ok = False
            while ds >= ds_min:
                dv_kmh = ms_to_kmh(abs(tangent[-1]) * Shooting.V_SCALE)
                da = abs(tangent[iy]) * self.shoot.scale[self.measure]
                ds = min(ds, ds_max, lim.max_step_kmh / max(dv_kmh, 1e-12),
                         lim.max_step_amplitude / max(da, 1e-12))  # fmt: skip
                u_pred = u_prev + ds * tangent
                t_row = tangent.copy()

                def fun(w, u_pred=u_pred, t_row=t_row):
                    return np.append(shoot.residual(w), t_row @ (w - u_pred))

                def jac_fun(w, r, t_row=t_row):
                    return np.vstack([shoot.jacobian(w, r[:-1]), t_row])

                u_new, norm, it, ok, _ = newton(fun, jac_fun, u_pred, tol=lim.newton_tol,
                                                max_iter=8, jac=np.vstack([jac, t_row]))
                # Reject a corrector that strayed far from the predictor (it may have jumped
                # to another branch) or fell onto the equilibrium, which solves the shooting
                # equations for any period.
                if ok and (np.linalg.norm(u_new - u_pred) > ds
                           or shoot.near_equilibrium(u_new)):  # fmt: skip
                    ok = False
                if ok:
                    break
                ds *= 0.5
            if not ok:
                return orbits, "Newton failed at the smallest step", False, False
            orbit, lin = self.solve(u_new, norm, it)
            orbits.append(orbit)
            u_prev = u_new
            ds *= 1.4 if it <= 4 else 0.7 if it > 6 else 1.0
            going_down = tangent[-1] < 0
            v_kmh = orbit.speed_kmh
            if v_kmh < lim.lo and going_down:
                return orbits, "left the speed range downward", True, True
            if v_kmh > lim.hi and not going_down:
                return orbits, "left the speed range upward", True, False
            if orbit.amplitude > lim.max_amplitude:
                return orbits, f"amplitude above {lim.max_amplitude * 1e3:g} mm", True, False
            if orbit.wheelset_amplitudes[self.wheel] < lim.min_amplitude:
                return orbits, (f"came back to the equilibrium near {v_kmh:.1f} km/h (a second "
                                "Hopf point)"), True, False  # fmt: skip
            reason = stop(orbits) if stop is not None else ""
            if reason:
                return orbits, reason, True, False
        return orbits, f"used all its {budget} points (incomplete)", False, False
