"""Where a number comes from: the railhunt version, the vehicle and a fingerprint of it.

Every JSON object and every CSV file the command line writes carries these keys (a CSV in
its sidecar ``<file>.meta.json``, a study's results file in its ``<file>.sweep.json``), so
that a number in a report can be traced to the code and the vehicle that produced it.

The fingerprint covers what changes the numbers and nothing else: every parameter's SI
value and the contact description, not the vehicle's name (``vehicle.replace(name=...)``
keeps it); it is the same as the study sidecar's ``vehicle`` block would give.
"""

from __future__ import annotations

import hashlib
import json
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from railhunt.vehicle import Vehicle

__all__ = ["provenance", "vehicle_block", "vehicle_fingerprint"]


def vehicle_block(vehicle: Vehicle) -> dict[str, Any]:
    """What describes a vehicle's numbers: ``{"parameters": {name: SI value}, "contact":
    repr of its contact description}`` (a study sidecar's ``vehicle`` entry), and for a
    layout other than the paper's vehicle ``"layout"``: the SHA-256 of its bodies,
    elements and wheel/rail data."""
    block: dict[str, Any] = {"parameters": vehicle.as_dict(), "contact": repr(vehicle.contact)}
    from railhunt.vehicle.files import paper_layout

    layout = vehicle.layout
    if layout != paper_layout():
        text = repr((layout.bodies, layout.elements, layout.wheel_rail, layout.gravity))
        block["layout"] = "sha256:" + hashlib.sha256(text.encode()).hexdigest()[:16]
    return block


def vehicle_fingerprint(vehicle: Vehicle) -> str:
    """``"sha256:"`` and the first 16 hex digits of the SHA-256 of :func:`vehicle_block`
    (canonical JSON, sorted keys): equal for vehicles with equal parameters and contact."""
    text = json.dumps(vehicle_block(vehicle), sort_keys=True, separators=(",", ":"))
    return "sha256:" + hashlib.sha256(text.encode()).hexdigest()[:16]


def provenance(vehicle: Vehicle | None = None) -> dict[str, Any]:
    """The keys that trace an output: ``railhunt_version`` and, with a vehicle,
    ``vehicle`` (its name) and ``vehicle_fingerprint`` (:func:`vehicle_fingerprint`)."""
    from railhunt._version import __version__

    out: dict[str, Any] = {"railhunt_version": __version__}
    if vehicle is not None:
        out["vehicle"] = vehicle.name
        out["vehicle_fingerprint"] = vehicle_fingerprint(vehicle)
    return out
