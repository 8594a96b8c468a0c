"""How the vehicle package writes values: in error messages and as TOML strings."""

import math

DIMENSIONLESS = "1"


def fmt_value(value: object) -> str:
    """Format a value for an error message: integral floats without ``.0``, others by repr.

    Parameters
    ----------
    value : object
        Usually a float in SI units; bools, ints and other objects are accepted too.

    Returns
    -------
    str
        ``"28000"`` for 28000.0, ``"0.7465"`` for 0.7465, ``"nan"`` for nan.
    """
    if isinstance(value, bool):
        return str(value)
    if isinstance(value, float):
        if math.isfinite(value) and value.is_integer() and abs(value) < 1e15:
            return str(int(value))
        return repr(value)
    if isinstance(value, int):
        return str(value)
    return repr(value)


def with_unit(value: object, unit: str | None) -> str:
    """``"-5 N*s/m"``; dimensionless (unit ``"1"``) and unit-less values print bare.

    Parameters
    ----------
    value : object
        The value, formatted by :func:`fmt_value`.
    unit : str or None
        SI unit text.

    Returns
    -------
    str
    """
    text = fmt_value(value)
    if unit and unit != DIMENSIONLESS:
        return f"{text} {unit}"
    return text


_TOML_ESCAPES = {
    '"': '\\"',
    "\\": "\\\\",
    "\b": "\\b",
    "\t": "\\t",
    "\n": "\\n",
    "\f": "\\f",
    "\r": "\\r",
}


def toml_string(text: str) -> str:
    """Quote ``text`` as a TOML basic string.

    Parameters
    ----------
    text : str
        Any text, control characters included.

    Returns
    -------
    str
        The text between double quotes, with TOML escapes.
    """
    out = []
    for ch in text:
        if ch in _TOML_ESCAPES:
            out.append(_TOML_ESCAPES[ch])
        elif ord(ch) < 0x20 or ord(ch) == 0x7F:
            out.append(f"\\u{ord(ch):04X}")
        else:
            out.append(ch)
    return '"' + "".join(out) + '"'
