"""A bit-level fingerprint of the paper's vehicle: the kernel's arrays, the right-hand side
and its Jacobian at random states and speeds, and the linear critical speed.

Run ``python benchmarks/fingerprint.py`` before and after a restructuring: every line must
stay the same (the hashes are of the raw float64 bytes).

The linear critical speed's last digits depend on which kernels OpenBLAS runs the
eigenvalue problem with: the stored value, 441.31801778747035 km/h, is that of the CPU's own
kernels; ``OPENBLAS_CORETYPE=Haswell`` gives 441.3180177874659 km/h and ``Sandybridge``
441.31801778745836 km/h on the same arrays, right-hand side and Jacobian (whose hashes do
not change). Compare on one machine with one setting.
"""

from __future__ import annotations

import hashlib

import numpy as np

from railhunt.model import Model
from railhunt.vehicle import Vehicle


def digest(array: np.ndarray) -> str:
    """SHA-256 (first 16 hex digits) of an array's float64/int64 bytes."""
    return hashlib.sha256(np.ascontiguousarray(array).tobytes()).hexdigest()[:16]


def fingerprint() -> dict[str, str]:
    """Hashes of the paper's model: system arrays, rhs and Jacobian at random points."""
    model = Model(Vehicle.paper2019())
    system = model.system()
    out = {}
    for name in system._fields:
        value = getattr(system, name)
        if name in ("scratch", "contact_work") or (name in ("stop_wheelset", "creep_table")
                                                   and value.size == 0):
            continue
        if name == "wheel_rail" and value.ndim == 2:  # one row per wheelset (since issue 18)
            for j, row in enumerate(value):
                out[f"system.wheel_rail[{j}]"] = digest(row)
            continue
        out[f"system.{name}"] = digest(value)
    rng = np.random.default_rng(2019)
    n = system.linear.shape[0] * 2 + system.damper.shape[0]
    for k in range(3):
        x = rng.normal(scale=1e-3, size=n)
        x[2 * system.linear.shape[0]:] *= 1e6
        speed = float(rng.uniform(20.0, 120.0))
        out[f"rhs[{k}]"] = digest(model.derivative(x, speed, t=0.3 * k))
        out[f"jacobian[{k}]"] = digest(model.jacobian(speed, x))
    from railhunt.analysis.linear import linear_critical_speed

    lcs = linear_critical_speed(model.vehicle)
    out["linear_critical_speed"] = f"{lcs.speed_kmh!r} km/h, {lcs.frequency_hz!r} Hz"
    return out


if __name__ == "__main__":
    for key, value in fingerprint().items():
        print(f"{key}: {value}")
