"""Unit conversions at the edges: railhunt is SI inside (m/s), people speak km/h.

Every conversion of a speed between km/h and m/s goes through these two functions, so
that the factor (and the exact floating-point operation: ``/ 3.6`` one way, ``* 3.6``
the other) is written once.
"""

from __future__ import annotations

#: km/h per m/s.
KMH_PER_MS = 3.6


def kmh_to_ms(speed_kmh: float):
    """Speed in m/s from km/h (``speed_kmh / 3.6``); works on floats and NumPy arrays."""
    return speed_kmh / KMH_PER_MS


def ms_to_kmh(speed: float):
    """Speed in km/h from m/s (``speed * 3.6``); works on floats and NumPy arrays."""
    return speed * KMH_PER_MS
