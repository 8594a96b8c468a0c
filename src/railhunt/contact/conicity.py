"""Equivalent conicity of a wheelset on its track, EN 15302.

Annex B (the reference method): the wheelset's kinematic (Klingel) motion on the
tabulated rolling-radius difference,

    d^2 y / dx^2 = -Delta_r(y) / (2 e r0),

is integrated over distance ``x`` for a given oscillation amplitude ``y_hat`` (half the
peak-to-peak lateral excursion); its wavelength ``lambda`` gives the equivalent
conicity through Klingel's formula ``lambda = 2 pi sqrt(e r0 / tan(gamma_e))``, i.e.
``tan(gamma_e) = e r0 (2 pi / lambda)^2``. ``e`` and ``r0`` cancel: the result depends on
``Delta_r(y)`` only. ``Delta_r`` is taken as tabulated, with *linear* interpolation between
the table's points (the standard's data have steps at flange contact; a spline would ring).
For pairs with ``Delta_r(0) != 0`` (different wheel diameters, case E5) the motion is
centred on the equilibrium ``Delta_r(y_c) = 0``. A worn or cylindrical tread can have
``Delta_r = 0`` over a band around the centre: the centre is then the band's middle, and
for amplitudes whose oscillation stays inside the band the wheelset does not oscillate
kinematically, so ``tan(gamma_e) = 0`` (EN 15302); beyond it the motion crosses the band
freely between the restoring flanks, and the integration gives its wavelength.

Annex C: the slope of the least-squares straight line through ``Delta_r(y)`` over
``[y_c - y_hat, y_c + y_hat]``, halved: ``tan(gamma_e) = slope / 2``.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

__all__ = ["ConicityError", "equivalent_conicity", "equivalent_conicity_regression"]


class ConicityError(ValueError):
    """Invalid input to an equivalent conicity computation."""


def _table(y: np.ndarray, delta_r: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    y = np.asarray(y, dtype=np.float64)
    d = np.asarray(delta_r, dtype=np.float64)
    if y.ndim != 1 or y.shape != d.shape or y.size < 3:
        raise ConicityError(f"y and delta_r must be 1-D arrays of equal length >= 3, got "
                            f"shapes {y.shape} and {d.shape}")
    if not (np.all(np.isfinite(y)) and np.all(np.isfinite(d))):
        raise ConicityError("y and delta_r must be finite")
    if not np.all(np.diff(y) > 0):
        raise ConicityError("y must be strictly increasing")
    return y, d


def _flat_bands(y: np.ndarray, d: np.ndarray) -> list[tuple[float, float]]:
    """The intervals ``[a, b]`` over which the interpolated ``Delta_r`` is exactly zero
    (runs of two or more consecutive zero points)."""
    bands = []
    i = 0
    while i < d.size:
        if d[i] == 0.0:
            j = i
            while j + 1 < d.size and d[j + 1] == 0.0:
                j += 1
            if j > i:
                bands.append((float(y[i]), float(y[j])))
            i = j + 1
        else:
            i += 1
    return bands


def _centre(y: np.ndarray, d: np.ndarray) -> float:
    """Equilibrium ``y_c`` where the interpolated ``Delta_r`` changes sign (nearest 0); the
    middle of a band where it is zero."""
    bands = _flat_bands(y, d)
    s = np.sign(d)
    idx = np.nonzero(s[:-1] * s[1:] <= 0)[0]
    if idx.size == 0:
        raise ConicityError("delta_r does not change sign within the table: no centred "
                            "running position (is the table large enough?)")
    cands = [0.5 * (a + b) for a, b in bands]
    for i in idx:
        if any(a <= y[i] and y[i + 1] <= b for a, b in bands):
            continue  # inside a flat band: its middle stands for it
        if d[i] == d[i + 1]:
            cands.append(0.5 * (y[i] + y[i + 1]))
        else:
            cands.append(y[i] - d[i] * (y[i + 1] - y[i]) / (d[i + 1] - d[i]))
    cands = np.array(cands)
    return float(cands[np.argmin(np.abs(cands))])


def _inside_flat_band(y: np.ndarray, d: np.ndarray, yc: float, amplitude: float) -> bool:
    """True when ``[yc - amplitude, yc + amplitude]`` lies in a band of ``Delta_r = 0``."""
    tol = 1e-12 * max(1.0, abs(yc))
    return any(a - tol <= yc - amplitude and yc + amplitude <= b + tol
               for a, b in _flat_bands(y, d))  # fmt: skip


def _potential(y: np.ndarray, d: np.ndarray, yc: float):
    """Exact integral of the piecewise-linear ``Delta_r`` from ``yc`` (m^2)."""
    cum = np.concatenate([[0.0], np.cumsum(0.5 * (d[1:] + d[:-1]) * np.diff(y))])

    def integral(x: float) -> float:
        i = int(np.clip(np.searchsorted(y, x) - 1, 0, y.size - 2))
        dx = x - y[i]
        slope = (d[i + 1] - d[i]) / (y[i + 1] - y[i])
        return cum[i] + d[i] * dx + 0.5 * slope * dx * dx

    base = integral(yc)
    return lambda x: integral(x) - base


def _turning_points(y: np.ndarray, d: np.ndarray, amplitude: float,
                    limit_only: bool = False) -> tuple[float, float, float]:  # fmt: skip
    """Centre and the two turning points whose half-distance is ``amplitude``.

    With ``limit_only``, return ``(limit, nan, nan)`` instead: the largest half-distance
    (amplitude, m) whose oscillation stays inside the table.
    """
    yc = _centre(y, d)
    pot = _potential(y, d, yc)
    lo, hi = y[0], y[-1]

    def partner(y_plus: float) -> float:
        """Turning point below ``yc`` with the same potential as ``y_plus``."""
        v = pot(y_plus)
        if v <= 0.0:
            return yc
        if pot(lo) < v:
            return math.nan
        if pot(yc) - v >= 0.0:
            return yc
        return brentq(lambda x: pot(x) - v, lo, yc, xtol=1e-15, rtol=1e-13)

    def excess(y_plus: float) -> float:
        ym = partner(y_plus)
        return math.inf if math.isnan(ym) else 0.5 * (y_plus - ym) - amplitude

    # The largest y_plus whose partner lies inside the table.
    top = hi
    if math.isinf(excess(top)):
        a, b = yc, hi
        for _ in range(80):
            m = 0.5 * (a + b)
            a, b = (m, b) if not math.isinf(excess(m)) else (a, m)
        top = a
    if limit_only:
        return excess(top) + amplitude, math.nan, math.nan
    if excess(top) < -1e-9 * amplitude:
        raise ConicityError(
            f"amplitude = {amplitude * 1e3:.4g} mm is invalid: the delta_r table "
            f"(y in [{lo * 1e3:.4g}, {hi * 1e3:.4g}] mm, centre {yc * 1e3:.4g} mm) supports "
            f"at most {(excess(top) + amplitude) * 1e3:.4g} mm"
        )
    if excess(top) <= 0.0:  # amplitude at the table's limit (within rounding)
        return yc, top, partner(top)
    y_plus = brentq(excess, yc + 1e-12, top, xtol=1e-15, rtol=1e-13)
    return yc, y_plus, partner(y_plus)


def max_amplitude(y: np.ndarray, delta_r: np.ndarray) -> float:
    """Largest amplitude (m) whose whole oscillation stays inside the table."""
    y, d = _table(y, delta_r)
    limit, _, _ = _turning_points(y, d, 1e3, limit_only=True)
    return float(limit) * (1.0 - 1e-12)  # rounded down: always accepted


def equivalent_conicity(
    y: np.ndarray,
    delta_r: np.ndarray,
    amplitude: float,
    method: str = "integration",
    *,
    rtol: float = 1e-8,
) -> float:
    """Equivalent conicity ``tan(gamma_e)`` of a ``Delta_r(y)`` table (EN 15302).

    Parameters
    ----------
    y : numpy.ndarray
        Lateral wheelset displacement (m), strictly increasing.
    delta_r : numpy.ndarray
        Rolling-radius difference ``r_L - r_R`` (m) at ``y``.
    amplitude : float
        Oscillation amplitude ``y_hat`` (m), half the peak-to-peak excursion, > 0.
    method : {"integration", "regression"}
        ``"integration"``: Annex B (kinematic motion, wavelength, Klingel);
        ``"regression"``: Annex C (least-squares line through ``Delta_r``).
    rtol : float
        Relative tolerance of the ODE integration.

    Returns
    -------
    float
        ``tan(gamma_e)`` (dimensionless); 0 when the oscillation stays inside a band of
        ``Delta_r = 0`` around the centre (no kinematic oscillation, EN 15302).

    Raises
    ------
    ConicityError
        Bad arrays, an amplitude outside what the table supports, an unknown method.
    """
    if method not in ("integration", "regression"):
        raise ConicityError(f"method = {method!r} is invalid: must be 'integration' or "
                            "'regression'")
    if not (isinstance(amplitude, int | float) and math.isfinite(amplitude) and amplitude > 0):
        raise ConicityError(f"amplitude = {amplitude!r} m is invalid: must be finite and > 0")
    y, d = _table(y, delta_r)
    if method == "regression":
        return equivalent_conicity_regression(y, d, amplitude)
    if _inside_flat_band(y, d, _centre(y, d), amplitude):
        return 0.0
    yc, y_plus, y_minus = _turning_points(y, d, amplitude)

    def rhs(_x: float, s: np.ndarray) -> np.ndarray:
        return np.array([s[1], -0.5 * np.interp(s[0], y, d)])

    # Units with e*r0 = 1: y'' = -Delta_r(y)/2 and tan(gamma_e) = (2 pi / period)^2.
    # Phase 1: from the upper turning point down to y_minus and back up through y_c;
    # phase 2: on to the upper turning point again (y' = 0). Period = sum of both.
    slope_max = float(np.max(np.abs(np.diff(d) / np.diff(y))))
    step = 0.05 * 2.0 * math.pi / math.sqrt(max(slope_max, 1e-12) / 2.0)

    def through_centre(_x: float, s: np.ndarray) -> float:
        return s[0] - yc

    through_centre.direction = 1.0
    through_centre.terminal = True

    def at_top(_x: float, s: np.ndarray) -> float:
        return s[1]

    at_top.direction = -1.0
    at_top.terminal = True

    atol = 1e-12 * max(amplitude, 1e-6)
    horizon = 1e5 * step
    s0 = np.array([y_plus, 0.0])
    period = 0.0
    for event in (through_centre, at_top):
        sol = solve_ivp(rhs, (0.0, horizon), s0, method="DOP853", rtol=rtol,
                        atol=[atol, atol], events=event, max_step=step)
        if sol.status != 1 or sol.t_events[0].size == 0:
            raise ConicityError("the kinematic motion did not complete a period (delta_r "
                                "must restore the wheelset toward its centre)")
        period += float(sol.t_events[0][0])
        s0 = sol.y_events[0][0].copy()
        if event is through_centre:
            s0[1] = max(s0[1], 1e-300)
    return (2.0 * math.pi / period) ** 2


def equivalent_conicity_regression(y: np.ndarray, delta_r: np.ndarray, amplitude: float) -> float:
    """Annex C value: half the slope of the least-squares line through ``Delta_r``.

    The line is fitted to the table's points in ``[y_c - y_hat, y_c + y_hat]`` (``y_c``
    the equilibrium, ``Delta_r(y_c) = 0``), with the interval's ends interpolated.
    """
    y, d = _table(y, delta_r)
    yc = _centre(y, d)
    a, b = yc - amplitude, yc + amplitude
    if a < y[0] - 1e-12 or b > y[-1] + 1e-12:
        raise ConicityError(
            f"amplitude = {amplitude * 1e3:.4g} mm is invalid: [{a * 1e3:.4g}, {b * 1e3:.4g}] mm "
            f"leaves the delta_r table [{y[0] * 1e3:.4g}, {y[-1] * 1e3:.4g}] mm"
        )
    inside = (y > a) & (y < b)
    yy = np.concatenate([[a], y[inside], [b]])
    dd = np.interp(yy, y, d)
    slope = np.polyfit(yy, dd, 1)[0]
    return float(0.5 * slope)
