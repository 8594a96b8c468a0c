"""Shipped vehicle files (TOML, SI units): the paper's vehicle and its profile variants.

Usable by name (``Vehicle.shipped(name)``, ``--vehicle NAME``, ``[vehicle] base = NAME``).
"""
