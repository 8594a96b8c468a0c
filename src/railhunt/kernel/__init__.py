"""The compiled, unit-free core: state layout, right-hand side, element laws, integrators.

Everything numba compiles lives here; it imports nothing from the object layer above it.
"""
