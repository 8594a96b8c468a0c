"""Hertz ellipse and Kalker's coefficients: kept importable here, they live in
:mod:`railhunt.mechanics.hertz` and :mod:`railhunt.mechanics.coefficients` (contact
mechanics) since railhunt has a package for it."""

from railhunt.mechanics.hertz import (
    CreepCoefficients,
    HertzContact,
    creep_coefficients,
    hertz_contact,
    kalker_coefficients,
)

__all__ = [
    "CreepCoefficients",
    "HertzContact",
    "creep_coefficients",
    "hertz_contact",
    "kalker_coefficients",
]
