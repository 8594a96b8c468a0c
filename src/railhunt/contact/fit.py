"""The paper's polynomial contact geometry (Eqs. 32-33) fitted to a profile-based table.

The compiled model evaluates, per wheel displaced ``u`` toward its flange,
``r(u) = r0 + lambda1 u + ... + lambda5 u^5`` and
``delta(u) = d0 - d1 u + d4 u^4 - d5 u^5`` (see :mod:`railhunt.contact.polynomial`).
For the left wheel ``u = y``, so both polynomials are least-squares fits of the left
wheel's ``r_L(y)`` and ``delta_L(y)`` of a symmetric wheel pair over ``|y| <= y_fit``.
``r0`` becomes the centred rolling radius ``r_L(0)`` (so a centred wheelset runs without
longitudinal creepage) and ``a`` half the centred distance between the contact points.
The fit errors are reported; a quintic cannot follow the jump to flange contact, so the
fitting range should stop near it (the default 6 mm for S1002 on UIC60 1:40 at 1435 mm).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from railhunt.contact.geometry import ContactGeometry
from railhunt.contact.hertz import creep_coefficients

__all__ = ["PolynomialFit", "fit_polynomials", "profile_vehicle_parameters"]


@dataclass(frozen=True)
class PolynomialFit:
    """Coefficients of Eqs. 32-33 fitted to a contact table, with the fit errors.

    Attributes
    ----------
    coefficients : dict
        ``r0`` (m), ``lambda1..lambda5`` (1, 1/m, ...), ``d0`` (rad), ``d1`` (rad/m),
        ``d4`` (rad/m^4), ``d5`` (rad/m^5), ``a`` (m).
    y_fit : float
        Half-width of the fitting range (m).
    radius_rms, radius_max : float
        RMS and largest error of ``r_L(y)`` (m) over the range.
    delta_r_max : float
        Largest error of ``Delta r(y) = r(y) - r(-y)`` (m) over the range.
    angle_rms, angle_max : float
        RMS and largest error of ``delta_L(y)`` (rad) over the range.
    """

    coefficients: dict
    y_fit: float
    radius_rms: float
    radius_max: float
    delta_r_max: float
    angle_rms: float
    angle_max: float


def fit_polynomials(geometry: ContactGeometry, y_fit: float = 0.006) -> PolynomialFit:
    """Least-squares fit of Eqs. 32-33 to ``geometry`` over ``|y| <= y_fit``.

    Parameters
    ----------
    geometry : ContactGeometry
        Table from :func:`railhunt.contact.geometry.contact_geometry`.
    y_fit : float
        Half-width of the fitting range (m), within the table.

    Returns
    -------
    PolynomialFit
    """
    y_all = geometry.y
    if not (math.isfinite(y_fit) and 0.0 < y_fit <= float(np.max(np.abs(y_all))) + 1e-12):
        raise ValueError(f"y_fit = {y_fit!r} m is invalid: must be in (0, "
                         f"{float(np.max(np.abs(y_all))):g}] (the table's range)")
    m = np.abs(y_all) <= y_fit + 1e-12
    u = y_all[m]
    i0 = int(np.argmin(np.abs(y_all)))
    r0 = float(geometry.r_left[i0])
    r = geometry.r_left[m] - r0
    basis = np.column_stack([u**k for k in range(1, 6)])
    lam, *_ = np.linalg.lstsq(basis, r, rcond=None)
    r_fit = basis @ lam
    d_basis = np.column_stack([np.ones_like(u), -u, u**4, -(u**5)])
    dcoef, *_ = np.linalg.lstsq(d_basis, geometry.delta_left[m], rcond=None)
    d_fit = d_basis @ dcoef
    dr_fit = r_fit - (basis * np.array([(-1.0) ** k for k in range(1, 6)])) @ lam
    dr_err = dr_fit - geometry.delta_r[m]
    a = 0.5 * float(geometry.contact_distance[i0])
    coefficients = {
        "r0": r0, "a": a,
        "lambda1": float(lam[0]), "lambda2": float(lam[1]), "lambda3": float(lam[2]),
        "lambda4": float(lam[3]), "lambda5": float(lam[4]),
        "d0": float(dcoef[0]), "d1": float(dcoef[1]), "d4": float(dcoef[2]),
        "d5": float(dcoef[3]),
    }
    return PolynomialFit(
        coefficients=coefficients, y_fit=y_fit,
        radius_rms=float(np.sqrt(np.mean((r_fit - r) ** 2))),
        radius_max=float(np.max(np.abs(r_fit - r))),
        delta_r_max=float(np.max(np.abs(dr_err))),
        angle_rms=float(np.sqrt(np.mean((d_fit - geometry.delta_left[m]) ** 2))),
        angle_max=float(np.max(np.abs(d_fit - geometry.delta_left[m]))),
    )


def profile_vehicle_parameters(
    geometry: ContactGeometry,
    wheel_curvature: float,
    rail_curvature: float,
    normal_load: float,
    y_fit: float = 0.006,
    young: float = 2.1e11,
    nu: float = 0.3,
) -> tuple[dict, PolynomialFit]:
    """Vehicle parameters from a contact table: Eqs. 32-33 and Kalker's coefficients.

    Parameters
    ----------
    geometry : ContactGeometry
        Contact table of the wheel pair.
    wheel_curvature, rail_curvature : float
        Transverse curvatures (1/m) of wheel and rail profile at the centred contact
        point (convex positive).
    normal_load : float
        Wheel normal load (N).
    y_fit : float
        Fitting half-range (m).
    young, nu : float
        Steel's Young's modulus (Pa) and Poisson's ratio.

    Returns
    -------
    tuple
        ``(parameters, fit)``: a dict of vehicle parameters (``r0, a, lambda1..5, d0, d1,
        d4, d5, f11, f22, f23, f33``) and the :class:`PolynomialFit`.
    """
    fit = fit_polynomials(geometry, y_fit)
    params = dict(fit.coefficients)
    i0 = int(np.argmin(np.abs(geometry.y)))
    cc = creep_coefficients(
        normal_load, float(geometry.r_left[i0]),
        wheel_transverse_radius=1.0 / wheel_curvature if wheel_curvature else math.inf,
        rail_transverse_radius=1.0 / rail_curvature if rail_curvature else math.inf,
        young=young, nu=nu,
    )
    params.update(f11=float(cc.f11), f22=float(cc.f22), f23=float(cc.f23), f33=float(cc.f33))
    return params, fit


def transverse_curvature(profile_y: np.ndarray, profile_z: np.ndarray, y: float,
                         half_width: float = 2e-3) -> float:
    """Second derivative ``d2z/dy2`` (1/m) of a profile at ``y`` (quadratic fit over +-2 mm).

    For a rail (``z`` = depth) a convex crown gives a positive value; for a wheel
    (``z`` = radius increase) a *concave* (hollow) tread gives a positive value.
    """
    m = np.abs(profile_y - y) <= half_width
    if np.count_nonzero(m) < 5:
        raise ValueError(f"profile has fewer than 5 points within {half_width * 1e3:g} mm "
                         f"of y = {y * 1e3:.3f} mm")
    return float(2.0 * np.polyfit(profile_y[m] - y, profile_z[m], 2)[0])


def s1002_uic60_parameters(normal_load: float = 10900.0 * 9.8 / 2.0,
                           y_fit: float = 0.006) -> tuple[dict, PolynomialFit, ContactGeometry]:
    """Parameters of the shipped ``s1002_uic60`` vehicle (S1002 on UIC60 1:40, 1435 mm).

    Analytic S1002 and UIC60 profiles, rail inclination 1:40, gauge 1435 mm, back-to-back
    1360 mm, tape-circle radius 0.43 m; Eqs. 32-33 fitted over ``|y| <= y_fit``; Kalker's
    coefficients at the centred contact point for ``normal_load`` (default: the paper's
    ``W g / 2``), E = 210 GPa, nu = 0.3.

    Returns
    -------
    tuple
        ``(parameters, fit, geometry)``.
    """
    from railhunt.contact.geometry import contact_geometry
    from railhunt.contact.profiles import s1002, uic60

    wheel, rail = s1002(step=1e-5), uic60(0.0, step=1e-5)
    geometry = contact_geometry(wheel, rail, rail_inclination=1.0 / 40.0, y_max=0.012,
                                y_step=1e-4)
    i0 = int(np.argmin(np.abs(geometry.y)))
    rail_c = rail.inclined(1.0 / 40.0)
    k_wheel = -transverse_curvature(wheel.y, wheel.z, float(geometry.wheel_left[i0]))
    k_rail = transverse_curvature(rail_c.y, rail_c.z, float(geometry.rail_left[i0]))
    params, fit = profile_vehicle_parameters(geometry, k_wheel, k_rail, normal_load, y_fit)
    return params, fit, geometry


def s1002_uic60_toml(table: bool = False) -> str:
    """Text of the shipped ``s1002_uic60.toml``: paper2019 with profile-based contact.

    Every parameter of the paper's vehicle, with ``r0, a, lambda1..5, d0, d1, d4, d5,
    f11, f22, f23, f33`` replaced by :func:`s1002_uic60_parameters`. With ``table=True``,
    the text of ``s1002_uic60_table.toml``: the same parameters plus a ``[contact]``
    section, so that the model interpolates the contact geometry of the profiles instead
    of the fitted polynomials.
    """
    import tomllib
    from importlib import resources

    from railhunt.contact.conicity import equivalent_conicity

    base = tomllib.loads((resources.files("railhunt") / "data" / "vehicles" /
                          "paper2019.toml").read_text(encoding="utf-8"))
    params, fit, geometry = s1002_uic60_parameters()
    eq = equivalent_conicity(geometry.y, geometry.delta_r, 0.003)
    rng = f"|y| <= {fit.y_fit * 1e3:g} mm"
    meaning = {
        "r0": "Nominal rolling radius: centred rolling radius r_L(0) of S1002 on UIC60 1:40 "
              "(wheel radius 0.43 m at the tape circle)",
        "a": "Half of the centred lateral distance between the contact points",
    }
    for k in ("lambda1", "lambda2", "lambda3", "lambda4", "lambda5"):
        meaning[k] = f"Rolling-radius polynomial (Eq. 32), least-squares fit over {rng}"
    for k in ("d0", "d1", "d4", "d5"):
        meaning[k] = f"Contact-angle polynomial (Eq. 33, paper's sign of y), fit over {rng}"
    for k, what in (("f11", "Longitudinal"), ("f22", "Lateral"), ("f23", "Lateral/spin"),
                    ("f33", "Spin")):
        meaning[k] = f"{what} creep coefficient: Hertz + Kalker at the centred contact point"
    lines = [
        "# railhunt vehicle file: the paper's vehicle (paper2019) with S1002 wheels on UIC60",
        "# rails inclined 1:40, gauge 1435 mm, back-to-back 1360 mm, wheel radius 0.43 m at",
        "# the tape circle. Written by railhunt.contact.fit.s1002_uic60_toml(); the tests check",
        "# that it is what the code computes. Contact geometry: rigid contact search on the",
        "# analytic EN 13715 S1002 and EN 13674-1 60E1 profiles; Eqs. 32-33 fitted by least",
        f"# squares over {rng}: rolling radius RMS error {fit.radius_rms * 1e3:.3f} mm "
        f"(max {fit.radius_max * 1e3:.3f} mm),",
        f"# Delta r max error {fit.delta_r_max * 1e3:.3f} mm, contact angle RMS error "
        f"{fit.angle_rms:.4f} rad (max {fit.angle_max:.4f} rad).",
        f"# Equivalent conicity (EN 15302 Annex B) at 3 mm amplitude: {eq:.4f}.",
        "# Kalker coefficients: Hertz ellipse for N = W*g/2, E = 210 GPa, nu = 0.3 and the",
        "# wheel and rail transverse curvatures at the centred contact point.",
        "# SI units throughout. Each parameter: value (SI), unit, meaning, source.",
        "",
        "[vehicle]",
        'name = "s1002_uic60_table"' if table else 'name = "s1002_uic60"',
        'description = "paper2019 vehicle, S1002 wheels on UIC60 rails 1:40 '
        + ('(contact geometry tabulated from the profiles)"' if table else
           '(profile-based contact geometry)"'),
    ]
    for name, entry in base["parameters"].items():
        value = params.get(name, entry["value"])
        mean = meaning.get(name, entry["meaning"])
        src = "railhunt.contact.fit.s1002_uic60_parameters" if name in params else entry[
            "source"]
        lines += ["", f"[parameters.{name}]", f"value = {float(value)!r}",
                  f'unit = "{entry["unit"]}"', "meaning = " + _quote(mean),
                  "source = " + _quote(src)]
    if table:
        from railhunt.vehicle import ContactSpec

        lines += ["", "# The model interpolates this contact geometry (the lambda and d",
                  "# polynomials above are then not used)."]
        lines += ContactSpec(wheel="S1002", rail="UIC60", rail_inclination=1.0 / 40.0,
                             gauge=1.435, back_to_back=1.36, wheel_radius=0.43)\
            .toml_lines()[1:]
    return "\n".join(lines) + "\n"


def _quote(text: str) -> str:
    return '"' + text.replace("\\", "\\\\").replace('"', '\\"') + '"'
