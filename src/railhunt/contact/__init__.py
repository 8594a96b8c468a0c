"""Wheel/rail contact geometry: profiles, the rigid contact search, equivalent conicity.

Also Hertz/Kalker creep coefficients and the fit of the paper's polynomials to profiles.
"""

from railhunt.contact.polynomial import contact_angle, rolling_radius

__all__ = ["contact_angle", "rolling_radius"]
