"""Errors of the vehicle package: invalid, unknown, missing or derived parameters; bad files.

Every parameter error is a :class:`ParameterError` (a ``ValueError``) that carries the
parameter's name, the rejected value, the broken rule and the unit, and pickles with all of
them (so it crosses process boundaries, e.g. from a Dask worker).
"""

from railhunt.quantities.formatting import with_unit

__all__ = [
    "DerivedOverrideWarning",
    "DerivedParameterError",
    "MissingParametersError",
    "ParameterError",
    "UnknownParameterError",
    "VehicleFileError",
]


def _rebuild_error(cls: type, args: tuple, state: dict) -> Exception:
    err = cls.__new__(cls)
    Exception.__init__(err, *args)
    err.__dict__.update(state)
    return err


class ParameterError(ValueError):
    """An invalid vehicle parameter value.

    Parameters
    ----------
    parameter : str or None
        Name of the offending parameter (``None`` when the error is about a set of names).
    value : object
        The rejected value, as given.
    rule : str
        The rule that was broken, e.g. ``"finite and > 0"``.
    unit : str or None
        Expected SI unit of the parameter.
    meaning : str, optional
        Physical meaning, appended to the default message.
    message : str, optional
        Full message, replacing the default
        ``"<name> = <value> <unit> is invalid: must be <rule> (<meaning>)"``.

    Attributes
    ----------
    parameter, value, rule, unit : see Parameters
    path : str or None
        Vehicle file the value came from, if any (prefixed to the message by ``str()``).
    """

    def __init__(
        self,
        parameter: str | None,
        value: object,
        rule: str,
        unit: str | None,
        *,
        meaning: str | None = None,
        message: str | None = None,
    ) -> None:
        if message is None:
            message = f"{parameter} = {with_unit(value, unit)} is invalid: must be {rule}"
            if meaning:
                message += f" ({meaning})"
        super().__init__(message)
        self.parameter = parameter
        self.value = value
        self.rule = rule
        self.unit = unit
        self.message = message
        self.path: str | None = None

    def __str__(self) -> str:
        return f"{self.path}: {self.message}" if self.path else self.message

    def __reduce__(self) -> tuple:
        return (_rebuild_error, (type(self), self.args, dict(self.__dict__)))


class UnknownParameterError(ParameterError):
    """A parameter name that the model does not know.

    Attributes
    ----------
    suggestions : tuple of str
        Close known names (``difflib``), best first; may be empty.
    """

    def __init__(self, parameter: str, value: object = None,
                 known: tuple[str, ...] | None = None) -> None:  # fmt: skip
        from railhunt.vehicle.table import DERIVED, PARAMETERS, suggest

        suggestions = suggest(parameter, known)
        if parameter in DERIVED:  # a derived quantity is known, just not settable
            spec = DERIVED[parameter]
            super().__init__(parameter, value, "a parameter, not a derived quantity", None,
                             message=f"{parameter} is derived, not a parameter: {parameter} "
                             f"= {spec.formula} ({spec.meaning}, {spec.unit}); vary "
                             f"{spec.change_instead} instead")  # fmt: skip
            self.suggestions = suggestions
            return
        if suggestions:
            quoted = [repr(s) for s in suggestions]
            options = quoted[0] if len(quoted) == 1 else f"{', '.join(quoted[:-1])} or {quoted[-1]}"
            hint = f"did you mean {options}?"
        elif known is None or set(known) == set(PARAMETERS):
            hint = f"see railhunt.vehicle.PARAMETERS for the {len(PARAMETERS)} known names"
        else:
            hint = f"the vehicle's {len(known)} parameters are: {', '.join(known)}"
        super().__init__(
            parameter,
            value,
            "a known parameter name",
            None,
            message=f"unknown vehicle parameter {parameter!r}; {hint}",
        )
        self.suggestions = suggestions


class MissingParametersError(ParameterError):
    """Parameters absent from a complete parameter set.

    Attributes
    ----------
    missing : tuple of str
        The missing names, in :data:`~railhunt.vehicle.PARAMETERS` order.
    """

    def __init__(self, missing: tuple[str, ...], *, hint: str = "") -> None:
        message = f"{len(missing)} vehicle parameter(s) missing: {', '.join(missing)}"
        if hint:
            message += f" ({hint})"
        super().__init__(None, None, "every parameter must be given", None, message=message)
        self.missing = missing


class DerivedParameterError(ParameterError):
    """An attempt to set a derived quantity (``v_u`` or ``N``) directly."""

    def __init__(self, parameter: str, value: object = None) -> None:
        from railhunt.vehicle.table import DERIVED

        spec = DERIVED[parameter]
        message = (
            f"{parameter} is derived, not a parameter: {parameter} = {spec.formula} "
            f"({spec.meaning}, {spec.unit}); change {spec.change_instead} instead"
        )
        super().__init__(
            parameter, value, f"not set (derived: {spec.formula})", spec.unit, message=message
        )


class VehicleFileError(ValueError):
    """A vehicle file that is not valid TOML or has the wrong structure."""


class DerivedOverrideWarning(UserWarning):
    """A derived parameter (an expression of others in its layout file) was given a value
    of its own: it no longer follows the parameters it was computed from."""
