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
# # Other vehicles: the Cooperrider bogie and a two-axle wagon
#
# railhunt describes a vehicle as bodies joined by force elements, in one layout file
# (docs: *Your own vehicle layout*). The paper's car is one such file; this example runs
# two others that ship with railhunt through the same analyses:
#
# * `cooperrider_bogie`, the classic benchmark of nonlinear railway dynamics: one bogie
#   frame and two wheelsets under a car body that is held still (a *fixed* body), conical
#   wheels on knife-edge rails, Vermeulen-Johnson creep saturation, dead-band flange
#   springs to the rails, no yaw damper (7 coordinates);
# * `two_axle_wagon`, a laden freight wagon: a car body on two wheelsets with a primary
#   suspension only (representative values, 7 coordinates).
#
# No code describes either: their files do.

# %%
import matplotlib.pyplot as plt

import railhunt
from railhunt.plots.layout import hunting_mode_figure, layout_figure

bogie = railhunt.Vehicle.shipped("cooperrider_bogie")
wagon = railhunt.Vehicle.shipped("two_axle_wagon")
for v in (bogie, wagon):
    print(f"{v.name}: {v.description}")

# %% [markdown]
# ## The layout
#
# `layout_figure` (the command line's `railhunt vehicle cooperrider_bogie --png FILE`)
# draws where the bodies sit and where each element attaches: the primary springs at the
# axle boxes, the secondary springs and dampers between the frame and the fixed body
# (dashed), the frame's yaw spring, and a flange spring from each wheelset to the track.

# %%
layout_figure(bogie)

# %% [markdown]
# ## Its Hopf point, against the literature
#
# The linear critical speed is where the least damped eigenvalue of the linearised
# model crosses into the right half plane. For this bogie the literature gives
# v0 = 68.66 m/s with a hard (subcritical) loss of stability.

# %%
linear = railhunt.linear_critical_speed(bogie)
print(f"Hopf point: {linear.speed_kmh:.1f} km/h = {linear.speed_kmh / 3.6:.2f} m/s, "
      f"{linear.frequency_hz:.2f} Hz")
linear

# %%
assert abs(linear.speed_kmh / 3.6 - 68.64) < 0.01
assert abs(linear.frequency_hz - 4.00) < 0.01

# %% [markdown]
# The mode that crosses is the bogie's hunting: frame and wheelsets move laterally nearly
# together (wheelsets 0.9 of the frame's amplitude), the wheelsets' yaw about a quarter
# period ahead of their lateral motion (`railhunt eigen --vehicle cooperrider_bogie
# --mode-png FILE`):

# %%
hunting_mode_figure(bogie)

# %% [markdown]
# ## The bifurcation diagram
#
# The cycles born at the Hopf point are unstable and run back to lower speeds
# (subcritical), to a fold at 238.9 km/h where the leading wheelset swings 9.35 mm: just
# beyond the flange clearance of 9.1 mm. There the flange springs catch them, and the
# branch turns into stable cycles that run on the flanges. The fold is the nonlinear
# critical speed: from 238.9 to 247.1 km/h the centred running and a flange-bound cycle
# are both stable.

# %%
diagram = railhunt.bifurcation_diagram(bogie, speed_range_kmh=(200.0, 300.0))
fold = min(diagram.folds, key=lambda f: f.speed_kmh)
print(f"{diagram.hopf_type}; fold at {fold.speed_kmh:.1f} km/h, "
      f"amplitude {fold.amplitude * 1e3:.2f} mm")
diagram

# %%
assert diagram.hopf_type == "subcritical"
assert abs(fold.speed_kmh - 238.9) < 0.5
assert abs(fold.amplitude * 1e3 - 9.35) < 0.1

# %%
orbits = diagram.to_dataframe()
fig, ax = plt.subplots(figsize=(7, 4.2))
for stable, part in orbits.groupby("stable"):
    ax.plot(part["speed_kmh"], part["amplitude"] * 1e3, ".", ms=3,
            label="stable cycles" if stable else "unstable cycles")
ax.axhline(bogie.delta * 1e3, color="0.5", ls=":", label="flange clearance")
ax.plot([diagram.hopf_speed_kmh], [0.0], "ko", label="Hopf point")
ax.set_xlabel("speed (km/h)")
ax.set_ylabel("amplitude of y_w1 (mm)")
ax.legend(fontsize=8)
fig.tight_layout()

# %% [markdown]
# ## The two-axle wagon
#
# The same calls on the wagon. Its bifurcation is supercritical: the cycles born at the
# Hopf point are stable and grow with speed, so the single-defect bisection of the
# paper's method finds (to its 1 km/h) the Hopf point itself.

# %%
wagon_linear = railhunt.linear_critical_speed(wagon)
wagon_nonlinear = railhunt.critical_speed(wagon)
print(f"linear {wagon_linear.speed_kmh:.1f} km/h at {wagon_linear.frequency_hz:.2f} Hz, "
      f"nonlinear {wagon_nonlinear.speed_kmh:.0f} km/h")

# %%
assert abs(wagon_linear.speed_kmh - 287.7) < 0.1
assert abs(wagon_linear.frequency_hz - 8.94) < 0.01
assert wagon_nonlinear.speed_kmh == 287.0

# %% [markdown]
# These numbers describe the file, not a real wagon: its link suspension is linearised
# without the friction that limits real two-axle wagons to far lower speeds. Changing a
# parameter works as for the paper's car, by the names of the wagon's own file. Halving
# the longitudinal axle-box stiffness `K_px` (the wheelsets' yaw stiffness to the body)
# lets another mode cross first: at 1.45 Hz, the car body yawing and rolling with the
# wheelsets, already at 44.9 km/h, the low-speed car body instability of two-axle
# vehicles whose wheelsets are held too softly in yaw.

# %%
softer = railhunt.linear_critical_speed(wagon.replace(K_px=1.0e6))
print(f"K_px = 1 MN/m: {softer.speed_kmh:.1f} km/h at {softer.frequency_hz:.2f} Hz")

# %%
assert abs(softer.speed_kmh - 44.9) < 0.1
assert abs(softer.frequency_hz - 1.45) < 0.01
