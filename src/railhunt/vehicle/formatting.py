"""How values are written in messages and TOML: kept importable from here
(:mod:`railhunt.quantities.formatting` is their home, below the vehicle and layout packages)."""

from railhunt.quantities.formatting import DIMENSIONLESS, fmt_value, toml_string, with_unit

__all__ = ["DIMENSIONLESS", "fmt_value", "toml_string", "with_unit"]
