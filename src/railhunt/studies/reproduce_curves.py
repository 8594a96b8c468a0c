"""Reproduction step beyond the paper: the stability map of its vehicle in curves.

The paper computes on straight track only and leaves curves to future work (its Sec. 5).
This step is railhunt's own result, not a comparison: the linear and nonlinear critical
speed of the paper's vehicle in curves of :attr:`Settings.map_radii
<railhunt.studies.records.Settings.map_radii>` with the cant of
:attr:`~railhunt.studies.records.Settings.map_cant`, and on straight track, computed by
:func:`railhunt.stability_map` (as Dask tasks when a client is given) into
``stability_map.csv``, drawn by :func:`railhunt.plots.plot_stability_map` and listed in the
step's table. It adds no headline row: the paper has no number to compare with.
"""

from __future__ import annotations

import math
from typing import Any

from railhunt.studies.records import Context, Step

__all__ = ["curves"]


def _radius_text(radius: float) -> str:
    return "straight track" if radius == math.inf else f"R = {radius:g} m"


def _num(value: float, spec: str) -> str:
    """A number as the step shows it, or "none" when there is none (NaN)."""
    return format(value, spec) if math.isfinite(value) else "none"


def _kmh(value: float, spec: str) -> str:
    """A speed in words: "350.6 km/h", or "none found"."""
    return f"{value:{spec}} km/h" if math.isfinite(value) else "none found"


def map_table(results: Any, nonlinear: bool) -> list[dict[str, Any]]:
    """The step's table: one row per radius (radius in m, speeds in km/h, frequency in Hz,
    the cant deficiency at the nonlinear critical speed in mm), as text."""
    from railhunt.curve import Curve
    from railhunt.units import kmh_to_ms

    table = []
    for row in results.rows:
        radius = row["radius_m"]
        entry: dict[str, Any] = {
            "radius (m)": "straight" if radius == math.inf else f"{radius:g}",
            "cant (mm)": f"{row['cant_m'] * 1e3:g}",
            "linear critical speed (km/h)": _num(row["linear_critical_speed_kmh"], ".1f"),
            "hunting frequency there (Hz)": _num(row["linear_frequency_hz"], ".2f"),
        }
        if nonlinear:
            v = row["critical_speed_kmh"]
            entry["nonlinear critical speed (km/h)"] = _num(v, ".0f")
            deficiency = math.nan
            if math.isfinite(v) and radius != math.inf:
                deficiency = Curve(radius, row["cant_m"]).cant_deficiency(kmh_to_ms(v)) * 1e3
            entry["cant deficiency there (mm)"] = _num(deficiency, ".0f")
        entry["note"] = row["message"]
        table.append(entry)
    return table


def curves(ctx: Context) -> Step:
    """Beyond the paper: the stability map of its vehicle in curves with a fixed cant."""
    from railhunt.plots import plot_stability_map
    from railhunt.studies.stability_map import MAP_OUTPUTS, stability_map

    s = ctx.settings
    cant_mm = s.map_cant * 1e3
    step = Step("curves", "Beyond the paper: hunting stability in curves", "")
    outputs = MAP_OUTPUTS if s.map_nonlinear else ("linear_critical_speed",)
    results = stability_map(ctx.vehicle, s.map_radii, s.map_cant, outputs=outputs,
                            out=ctx.out_dir / "stability_map.csv", overwrite=True,
                            client=ctx.client,
                            workers=1 if ctx.client is None else None)  # fmt: skip
    step.figures.append(plot_stability_map(results, ctx.out_dir / "stability_map.png"))
    step.table = map_table(results, s.map_nonlinear)
    parts = []
    for row in results.rows:
        text = (f"{_radius_text(row['radius_m'])}: linear "
                f"{_kmh(row['linear_critical_speed_kmh'], '.1f')}")
        if s.map_nonlinear:
            text += f", nonlinear {_kmh(row['critical_speed_kmh'], '.0f')}"
        parts.append(text)
    step.shows = (
        "railhunt's own results, not the paper's: the paper computes on straight track only "
        "and leaves curves to future work (Sec. 5). Critical speeds of the paper's vehicle "
        f"in curves with {cant_mm:g} mm cant: " + "; ".join(parts) + ". With a fixed cant the "
        "cant deficiency grows with v²/R: in tighter curves the vehicle runs against larger "
        "steady creep forces (and its flanges and bump stops), which changes its stability; "
        "the dashed line marks 150 mm of cant deficiency, about the most a curve admits in "
        "service, so a critical speed above it lies beyond the speeds that curve is run at."
    )
    nonlinear = ("both critical speeds" if s.map_nonlinear else
                 "the linear critical speed only (--quick leaves out the nonlinear search)")
    step.how = (f"railhunt.stability_map over {len(s.map_radii)} radii with {cant_mm:g} mm "
                f"cant, {nonlinear}: linear, the Hopf point of the steady-curving equilibrium "
                "followed along the speed; nonlinear, the bisection over an 8 mm x 20 m defect "
                "inside the constant curve, each trial judged by the leading wheelset's "
                "distance from the curving equilibrium; results in stability_map.csv.")
    return step
