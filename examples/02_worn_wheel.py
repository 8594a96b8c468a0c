# ---
# jupyter:
#   jupytext:
#     formats: py:percent
#   kernelspec:
#     display_name: Python 3
#     language: python
#     name: python3
# ---

# %% [markdown]
# # A worn wheel: profile → conicity → critical speed
#
# Wheels wear. The most common pattern is **hollow wear**: the running band around the
# tape circle wears down, the tread becomes concave and a "false flange" rises on the
# field side. The rolling-radius difference then grows faster with the lateral
# displacement: the equivalent conicity rises, and a vehicle that was stable becomes
# prone to hunting.
#
# railhunt ships a hollow-worn S1002 (`worn_s1002.prw`, SIMPACK format). It is
# **generated, not measured**: the analytic S1002 with 2 mm of hollow wear by the
# model of `railhunt.contact.wear` (source and licence in
# `src/railhunt/data/profiles/README.md`). A measured profile file (SIMPACK `.prw`, or
# two columns `y z` in mm) is read the same way with `railhunt.read_profile`.

# %%
import matplotlib.pyplot as plt
import numpy as np
import pandas as pd

import railhunt
from railhunt.contact.profiles import shipped_profile
from railhunt.contact.wear import hollow_wear_depth, hollow_worn

new = railhunt.s1002(step=1e-5)
worn = shipped_profile("S1002_worn")   # the same file as examples/data/worn_s1002.prw
worn.name, worn.kind, worn.y.size

# %% [markdown]
# The wear model removes `d(y) = h cos²(π (y − c)/w)` inside a band of width `w` = 60 mm
# centred `c` = 5 mm toward the field side of the tape circle, with the hollow depth
# `h` = 2 mm, and refers the profile again to its tape circle (`z` = 0 at `y` = 0).

# %%
fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(6.5, 5), sharex=True)
ax1.plot(new.y * 1e3, new.z * 1e3, label="S1002 new")
ax1.plot(worn.y * 1e3, worn.z * 1e3, label="S1002 hollow-worn")
ax1.set_ylabel("radius over the tape circle (mm)")
ax1.set_ylim(32, -5)  # drawn as usual: flange down
ax1.legend()
ax2.plot(new.y * 1e3, hollow_wear_depth(new.y, 2e-3, 5e-3, 60e-3) * 1e3)
ax2.set_xlabel("y (mm, + toward the field side)")
ax2.set_ylabel("material removed (mm)")
fig.tight_layout()

# %% [markdown]
# ## Contact geometry and equivalent conicity
#
# The rigid contact search gives the rolling radii and contact angles of both wheels
# against the lateral displacement of the wheelset. Here on UIC60 rails inclined 1:40,
# gauge 1435 mm. The summary reports the equivalent conicity at 3 mm amplitude (EN 15302,
# Annex B), the flange contact and the contact-point jumps.

# %%
rail = railhunt.uic60()
geo_new = railhunt.contact_geometry(new, rail, rail_inclination=1 / 40)
geo_worn = railhunt.contact_geometry(worn, rail, rail_inclination=1 / 40)
geo_worn

# %%
amplitudes = np.array([1.0, 2.0, 3.0, 4.0, 5.0]) * 1e-3  # m
conicity = pd.DataFrame({
    "amplitude_mm": amplitudes * 1e3,
    "new": [railhunt.equivalent_conicity(geo_new.y, geo_new.delta_r, a) for a in amplitudes],
    "worn": [railhunt.equivalent_conicity(geo_worn.y, geo_worn.delta_r, a) for a in amplitudes],
})
ax = conicity.plot(x="amplitude_mm", marker="o", figsize=(5.5, 3.2))
ax.set_ylabel("equivalent conicity")
conicity.round(3)

# %% [markdown]
# At 3 mm the conicity rises from 0.18 to 0.44. Values above about 0.4 are what the
# limits for high-speed vehicles are set against. The curves of `Δr(y)` show why: beyond
# about 2 mm of displacement the worn wheel runs up the side of its hollow, and its
# radius difference grows much faster than the new wheel's.

# %%
ax = geo_new.to_dataframe().plot(x="y", y="delta_r", label="new", figsize=(5.5, 3.2))
geo_worn.to_dataframe().plot(x="y", y="delta_r", label="worn", ax=ax)
ax.set_xlabel("y (m)")
ax.set_ylabel("r_L - r_R (m)")
assert abs(conicity.loc[2, "new"] - 0.1834) < 1e-3
assert abs(conicity.loc[2, "worn"] - 0.438) < 2e-3

# %% [markdown]
# ## Critical speed on worn wheels
#
# A vehicle runs on tabulated geometry from profiles through a `[contact]` section in
# its file. `data/worn.toml` puts the paper's vehicle on the worn wheels. Its `r0` must
# equal the profiles' centred rolling radius, which `railhunt contact` prints. The same
# vehicle on new S1002 wheels is the shipped `s1002_uic60_table`.

# %%
print(open("data/worn.toml").read())
on_worn = railhunt.load_vehicle("data/worn.toml")
on_new = railhunt.Vehicle.shipped("s1002_uic60_table")

speeds = pd.DataFrame(
    [(label, railhunt.critical_speed(v).speed_kmh, railhunt.linear_critical_speed(v))
     for label, v in (("new S1002", on_new), ("hollow-worn S1002", on_worn))],
    columns=["wheels", "nonlinear_kmh", "linear"],
)
speeds["linear_kmh"] = [r.speed_kmh for r in speeds.pop("linear")]
speeds.round(1)

# %% [markdown]
# The worn wheels lower the nonlinear critical speed from 213 to 167 km/h and the Hopf
# point from 327 to 227 km/h. (The creep coefficients stay those of the new profiles. A
# study of real worn wheels would also take the Hertz ellipse at the worn contact point:
# `railhunt.creep_coefficients` with the worn curvatures.)

# %%
assert list(speeds["nonlinear_kmh"]) == [213.0, 167.0]
assert abs(speeds["linear_kmh"].iloc[1] - 227.4) < 0.5

# %% [markdown]
# ## How much wear?
#
# The same model at other depths: the conicity and the critical speeds against the
# hollow depth. `Vehicle.replace(r0=...)` keeps `r0` equal to each profile's centred
# rolling radius, and `contact=` passes the geometry directly.

# %%
base = railhunt.Vehicle.shipped("s1002_uic60")
rows = []
for depth in (0.0, 0.5e-3, 1.0e-3, 1.5e-3, 2.0e-3):
    geo = railhunt.contact_geometry(hollow_worn(new, depth=depth), rail, rail_inclination=1 / 40)
    v = base.replace(r0=float(np.interp(0.0, geo.y, geo.r_left)))
    rows.append((depth * 1e3, railhunt.equivalent_conicity(geo.y, geo.delta_r, 3e-3),
                 railhunt.critical_speed(v, contact=geo).speed_kmh,
                 railhunt.linear_critical_speed(v, contact=geo).speed_kmh))
wear = pd.DataFrame(rows, columns=["hollow_depth_mm", "conicity_3mm", "nonlinear_kmh",
                                   "linear_kmh"])
fig, ax = plt.subplots(figsize=(5.5, 3.2))
ax.plot(wear["hollow_depth_mm"], wear["nonlinear_kmh"], "o-", label="nonlinear")
ax.plot(wear["hollow_depth_mm"], wear["linear_kmh"], "s--", label="linear")
ax.set_xlabel("hollow depth (mm)")
ax.set_ylabel("critical speed (km/h)")
ax.legend()
wear.round(3)

# %% [markdown]
# Half a millimetre of hollow raises the conicity by 60 %, one millimetre doubles it
# (0.18 → 0.38), and the critical speeds fall as the conicity rises.

# %%
assert wear["conicity_3mm"].is_monotonic_increasing
assert wear["linear_kmh"].is_monotonic_decreasing

# %% [markdown]
# From the command line:
#
# ```bash
# railhunt contact --wheel examples/data/worn_s1002.prw --rail examples/data/my_rail.txt
# railhunt critical-speed --vehicle examples/data/worn.toml
# ```
