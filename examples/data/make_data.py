"""Regenerate the input files in this folder (run from anywhere: python make_data.py).

Every file is made by railhunt itself, so its source and licence are railhunt's (MIT):

- ``worn_s1002.prw``: S1002 with 2 mm of hollow tread wear, the same file as
  ``src/railhunt/data/profiles/worn_s1002.prw`` (``railhunt.contact.wear.worn_s1002``).
- ``my_rail.txt``: an upright UIC60 (60E1) rail head as two columns ``y z`` in mm, every
  0.5 mm, from ``railhunt.uic60()``: the format of a measured rail profile.
- ``track_alignment.csv``: 1500 m of lateral track alignment every 0.5 m, in the format of
  a track recording car's output (``distance [m],alignment [mm]``). The values are drawn
  from the German high-speed spectrum for low disturbance (seed 7): no measured alignment
  is available here under a licence that allows shipping it.

``my.toml``, ``worn.toml`` and ``articulated_pair.toml`` are written by hand.
"""

from __future__ import annotations

from pathlib import Path

import railhunt
from railhunt.contact.profiles import write_profile
from railhunt.contact.wear import worn_s1002

HERE = Path(__file__).resolve().parent


def make_rail(path: Path) -> None:
    """``my_rail.txt``: the upright UIC60 head every 0.5 mm."""
    comment = "UIC60 (60E1) rail head, upright, from railhunt.uic60(step=0.5 mm)"
    write_profile(railhunt.uic60(step=5e-4), path, comment)


def make_alignment(path: Path) -> None:
    """``track_alignment.csv``: 1500 m of German low-disturbance alignment, seed 7."""
    track = railhunt.track_irregularity("german-low", length=1500.0, dx=0.5, seed=7)
    lines = ["distance [m],alignment [mm]"]
    lines += [f"{s:.1f},{a * 1e3:.4f}" for s, a in zip(track.distance, track.alignment,
                                                       strict=True)]
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")


def main() -> None:
    """Write every generated file of this folder."""
    worn_s1002(HERE / "worn_s1002.prw")
    make_rail(HERE / "my_rail.txt")
    make_alignment(HERE / "track_alignment.csv")


if __name__ == "__main__":
    main()
