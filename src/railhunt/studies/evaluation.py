"""How the points of a global study are evaluated: the task, its items and the description.

:func:`railhunt.sensitivity` and :func:`railhunt.optimize` evaluate their points exactly as
:func:`railhunt.sweep` does (its task, :func:`railhunt.studies.sweep.evaluate_point`), or
call a model function; :class:`Evaluation` holds what both need for
:func:`railhunt.studies.runner.run_study`.
"""

from __future__ import annotations

import functools
from collections.abc import Callable, Mapping, Sequence
from typing import Any

from railhunt.studies.design import Point, frequency_speed
from railhunt.studies.factors import function_name, function_task, vehicle_outputs
from railhunt.studies.outputs import OutputOptions
from railhunt.studies.store import columns_for
from railhunt.vehicle import Vehicle


def _warm_up() -> None:
    from railhunt.studies.sweep import warm_up

    warm_up()


class Evaluation:
    """The evaluation of a study's points on a model (a vehicle or a function).

    Parameters
    ----------
    model : Vehicle or callable
        The model.
    names : sequence of str
        The factors.
    param_columns : sequence of str
        The parameter columns of a point (factors and tied parameters).
    columns : sequence of str
        The outputs asked for (results columns, or the function's keys).
    options : OutputOptions
        Settings of the fold, damping and curving outputs.
    excitation, creep_law, frequency_speed_kmh : optional
        As in :func:`railhunt.sweep` (vehicles only).
    """

    def __init__(self, model: Vehicle | Callable[..., Mapping[str, Any]], names: Sequence[str],
                 param_columns: Sequence[str], columns: Sequence[str], options: OutputOptions,
                 excitation: object = None, creep_law: str | None = None,
                 frequency_speed_kmh: float | None = None) -> None:  # fmt: skip
        self.model = model
        self.names = list(names)
        self.frequency_speed_kmh = frequency_speed_kmh
        self.meta: dict[str, Any] = {}
        if isinstance(model, Vehicle):
            from railhunt.provenance import provenance, vehicle_block
            from railhunt.studies.sweep import point_task
            from railhunt.track import SingleDefect

            groups = vehicle_outputs(columns)
            options.check_for(groups)
            excitation = SingleDefect() if excitation is None else excitation
            self.meta.update(vehicle=vehicle_block(model), provenance=provenance(model),
                             sweep_outputs=list(groups), creep_law=creep_law,
                             columns=columns_for(list(param_columns), groups),
                             **options.describe(groups))  # fmt: skip
            if "critical_speed" in groups or "hunting_frequency" in groups:
                self.meta["excitation"] = repr(excitation)
            if "hunting_frequency" in groups:
                self.meta["frequency_speed_kmh"] = frequency_speed(Point(0, "", {}), self.names,
                                                                   frequency_speed_kmh)  # fmt: skip
            self.task: Callable[[Any], dict[str, Any]] = functools.partial(
                point_task, vehicle=model, outputs=groups, excitation=excitation,
                creep_law=creep_law, amplitude=None, output_options=options)  # fmt: skip
            self.warm_up: Callable[[], None] | None = _warm_up
        else:
            self.meta.update(function=function_name(model),
                             columns=["point", "line", *param_columns, *columns, "status",
                                      "message"])  # fmt: skip
            self.task = functools.partial(function_task, function=model, outputs=tuple(columns))
            self.warm_up = None

    @property
    def is_vehicle(self) -> bool:
        """Whether the model is a vehicle."""
        return isinstance(self.model, Vehicle)

    def check(self, points: Sequence[Point]) -> None:
        """Every point must make a valid vehicle (before any work starts)."""
        if not self.is_vehicle:
            return
        for p in points:
            try:
                self.model.replace(**p.values)  # type: ignore[union-attr]
            except ValueError as exc:
                raise ValueError(f"point {p.index} is not a valid vehicle ({exc}); narrow the "
                                 "factors' ranges or distributions") from None  # fmt: skip

    def items(self, points: Sequence[Point]) -> list[tuple[int, Any]]:
        """The ``(index, item)`` pairs :func:`run_study` takes."""
        if not self.is_vehicle:
            return [(p.index, (p.index, p.values)) for p in points]
        return [(p.index, (p, frequency_speed(p, self.names, self.frequency_speed_kmh)))
                for p in points]  # fmt: skip
