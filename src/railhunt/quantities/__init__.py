"""Values with units and the rules they obey: the vocabulary below vehicles and layouts.
Rooms: formatting (values in messages and TOML), rules (ranges, parameter specs), units
(unit texts of files, converted to SI or refused), meanings (the rule a value gets from what
it is in a layout: a mass, a stiffness, a wheel radius).

Both :mod:`railhunt.vehicle` and :mod:`railhunt.layout` import from here; this package
imports neither.
"""
