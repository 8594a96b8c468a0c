"""Wheel/rail contact geometry."""

from railhunt.contact.polynomial import contact_angle, rolling_radius

__all__ = ["contact_angle", "rolling_radius"]
