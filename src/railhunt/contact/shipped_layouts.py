"""Text of the shipped per-point vehicle ``s1002_uic60_per_point.toml``.

The paper's layout (``paper2019.toml``, bodies and elements unchanged) with the parameter
values of the shipped ``s1002_uic60_table.toml`` (S1002 on UIC60 1:40, from
:func:`railhunt.contact.fit.s1002_uic60_parameters`: the same numbers, so that the two
vehicles differ in their contact mechanics only), its ``[contact]`` section, and the
wheel/rail keys of per-point contact mechanics: ``contact = "profiles"``,
``contact_mechanics = "per-point"``, ``shear_modulus``, ``poisson`` (the creep law stays the
paper's heuristic). A test checks that the shipped file is what this writes.
"""

from __future__ import annotations

import re

__all__ = ["s1002_uic60_per_point_toml", "s1002_uic60_two_point_toml"]

_HEADER = """\
# railhunt vehicle file: the paper's vehicle (paper2019 layout) with S1002 wheels on UIC60
# rails inclined 1:40 (gauge 1435 mm, back-to-back 1360 mm, wheel radius 0.43 m at the
# tape circle) and contact mechanics at each contact point: every wheel's Hertz ellipse
# from the profiles' curvatures where it touches its rail, its own Kalker coefficients,
# and its normal force from its equilibrium with the contact angle; the paper's
# heuristic creep law, as in s1002_uic60_table, so that the two differ in their contact
# mechanics alone.
# Written by railhunt.contact.shipped_layouts.s1002_uic60_per_point_toml(); the tests
# check that it is what the code computes. The parameters are those of
# s1002_uic60_table (f11 ... f33 at the centred contact are kept for reference: the
# per-point model computes its own). SI units throughout.
"""

_WHEEL_RAIL = """\
[wheel_rail]
contact = "profiles"
contact_mechanics = "per-point"
creep_law = "heuristic"
shear_modulus = "E_steel / (2 * (1 + nu_steel))"
poisson = "nu_steel"
lambda1 = "lambda1"
lambda2 = "lambda2"
lambda3 = "lambda3"
lambda4 = "lambda4"
lambda5 = "lambda5"
d0 = "d0"
d1 = "d1"
d4 = "d4"
d5 = "d5"
delta_max = "delta_max"
half_gauge = "a"
radius = "r0"
f11 = "f11"
f22 = "f22"
f23 = "f23"
f33 = "f33"
mu = "mu"
load = "W * g / 2"
axle_load = "W"
"""

_MATERIAL = """
[parameters.E_steel]
value = 210000000000.0
unit = "Pa"
meaning = "Young's modulus of wheel and rail steel (Hertz ellipses, Kalker coefficients)"
source = "the value of the centred coefficients of s1002_uic60 (docs/contact.md)"
rule = "positive"

[parameters.nu_steel]
value = 0.3
unit = "1"
meaning = "Poisson's ratio of wheel and rail steel"
source = "the value of the centred coefficients of s1002_uic60 (docs/contact.md)"
rule = "positive"
"""


def s1002_uic60_per_point_toml() -> str:
    """Text of the shipped ``s1002_uic60_per_point.toml`` (module docstring)."""
    import tomllib
    from importlib import resources

    from railhunt.vehicle import ContactSpec

    folder = resources.files("railhunt") / "data" / "vehicles"
    text = (folder / "paper2019.toml").read_text(encoding="utf-8")
    table = tomllib.loads((folder / "s1002_uic60_table.toml").read_text(encoding="utf-8"))
    params = {name: entry["value"] for name, entry in table["parameters"].items()
              if entry["source"] == "railhunt.contact.fit.s1002_uic60_parameters"}
    body = text[text.index("[vehicle]"):]
    body = body.replace('name = "paper2019"', 'name = "s1002_uic60_per_point"', 1)
    body = re.sub(r'description = "[^"]*"',
                  'description = "paper2019 layout, S1002 on UIC60 1:40, contact mechanics '
                  'at each contact point"', body, count=1)
    for name, value in params.items():
        pattern = rf"(\[parameters\.{name}\]\nvalue = )[^\n]*"
        body, n = re.subn(pattern, lambda m, v=value: m.group(1) + repr(float(v)), body)
        if n != 1:
            raise RuntimeError(f"paper2019.toml has no single [parameters.{name}]")
        src = rf"(\[parameters\.{name}\]\n(?:[^\n]*\n){{3}}source = )[^\n]*"
        body = re.sub(src, lambda m: m.group(1) + '"railhunt.contact.fit.'
                      's1002_uic60_parameters"', body, count=1)
    start = body.index("[wheel_rail]")
    end = body.index("\n\n", start)
    body = body[:start] + _WHEEL_RAIL.rstrip("\n") + body[end:]
    marker = "# ---------------------------------------------------------------- wheel/rail"
    body = body.replace(marker, _MATERIAL.strip("\n") + "\n\n" + marker, 1)
    contact = ContactSpec(wheel="S1002", rail="UIC60", rail_inclination=1.0 / 40.0,
                          gauge=1.435, back_to_back=1.36, wheel_radius=0.43).toml_lines()
    return _HEADER + "\n" + body.rstrip("\n") + "\n" + "\n".join(contact) + "\n"


_TWO_POINT_HEADER = """\
# railhunt vehicle file: the paper's vehicle (paper2019 layout) with S1002 wheels on UIC60
# rails inclined 1:40 (gauge 1435 mm, back-to-back 1360 mm, wheel radius 0.43 m at the
# tape circle) and two-point contact: up to two contact patches per wheel, found on the
# yawed wheelset's contact locus and sharing the wheel load by their elastic approach,
# each with its own Hertz ellipse, Kalker coefficients, normal force and creepages at its
# own point, tabulated over the lateral displacement and the yaw; the paper's heuristic
# creep law, as in s1002_uic60_per_point, so that the two differ in their contact
# geometry alone.
# Written by railhunt.contact.shipped_layouts.s1002_uic60_two_point_toml(); the tests
# check that it is what the code computes. The parameters are those of
# s1002_uic60_table. SI units throughout.
"""


def s1002_uic60_two_point_toml() -> str:
    """Text of the shipped ``s1002_uic60_two_point.toml``: ``s1002_uic60_per_point.toml``
    with ``contact_mechanics = "two-point"``."""
    text = s1002_uic60_per_point_toml()
    body = text[text.index("[vehicle]"):]
    body = body.replace('name = "s1002_uic60_per_point"', 'name = "s1002_uic60_two_point"', 1)
    body = body.replace("contact mechanics at each contact point", "two-point contact", 1)
    body = body.replace('contact_mechanics = "per-point"', 'contact_mechanics = "two-point"', 1)
    return _TWO_POINT_HEADER + "\n" + body
