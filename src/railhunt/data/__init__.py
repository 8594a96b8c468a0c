"""Data shipped with railhunt (read at run time through importlib.resources).

Vehicles (TOML), wheel and rail profiles, and the paper's tables.
"""
