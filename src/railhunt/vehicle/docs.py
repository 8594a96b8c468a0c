"""The parameter table as documentation: Markdown rendered from the table itself."""

from railhunt.vehicle.core import Vehicle
from railhunt.vehicle.formatting import fmt_value
from railhunt.vehicle.parameters import DERIVED, PARAMETERS

__all__ = ["parameter_markdown"]


def _cell(text: str) -> str:
    return text.replace("|", "\\|")


def parameter_markdown(vehicle: Vehicle | None = None) -> str:
    """The parameter table in Markdown: name, unit, meaning, rule and a vehicle's values.

    One row per parameter of :data:`~railhunt.vehicle.PARAMETERS`, in order, then one per
    derived quantity. ``docs/parameters.md`` holds this table for the paper's vehicle (a
    test keeps it up to date).

    Parameters
    ----------
    vehicle : Vehicle, optional
        Whose values fill the last column (headed by its name); default
        :meth:`Vehicle.paper2019`.

    Returns
    -------
    str
        The table, one line per row, ending with a newline.
    """
    if vehicle is None:
        vehicle = Vehicle.paper2019()
    lines = [
        f"| name | unit | meaning | rule | {_cell(vehicle.name)} |",
        "| --- | --- | --- | --- | ---: |",
    ]
    for spec in PARAMETERS.values():
        rule = str(spec.rule)
        if spec.default is not None:
            rule += f"; {fmt_value(spec.default)} when a vehicle file omits it"
        value = fmt_value(getattr(vehicle, spec.name))
        lines.append(f"| `{spec.name}` | {_cell(spec.unit)} | {_cell(spec.meaning)} "
                     f"| {_cell(rule)} | {value} |")  # fmt: skip
    for spec in DERIVED.values():
        value = fmt_value(getattr(vehicle, spec.name))
        lines.append(f"| `{spec.name}` | {_cell(spec.unit)} | {_cell(spec.meaning)} "
                     f"| derived: {spec.formula} (not set) | {value} |")  # fmt: skip
    return "\n".join(lines) + "\n"
