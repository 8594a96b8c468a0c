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
# # Your own vehicle, and what changes its critical speed
#
# A vehicle file is TOML. It starts from a shipped vehicle (`base = "paper2019"`) and
# lists only the parameters that differ, in SI units. `data/my.toml` is such a file: the
# paper's vehicle with a heavier car body, stiffer primary longitudinal springs and softer
# yaw dampers.

# %%
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd

import railhunt

print(Path("data/my.toml").read_text())

# %% [markdown]
# `load_vehicle` reads it, checks every value against its rule (a negative mass, a
# misspelt name or a wrong unit is a one-line error naming the parameter) and returns a
# `Vehicle`. The parameters that differ from the paper's vehicle, with their units:

# %%
paper = railhunt.Vehicle.paper2019()
mine = railhunt.load_vehicle("data/my.toml")

changed = pd.DataFrame(
    [(name, getattr(paper, name), value, unit, meaning)
     for name, value, unit, meaning in mine.parameter_table()
     if value != getattr(paper, name)],
    columns=["parameter", "paper2019", "my_vehicle", "unit", "meaning"],
)
changed

# %% [markdown]
# ## Its critical speeds
#
# The **nonlinear critical speed** is the paper's: at each trial speed the vehicle runs
# over one 8 mm lateral track defect, and the highest speed at which the motion dies out
# is the result (bisection to 1 km/h). The **linear critical speed** is where the centred
# running itself becomes unstable (the Hopf point). Each result shows a summary; in a
# notebook it is an HTML table, and `to_dataframe()` gives its data (here: one row per
# trial speed).

# %%
nonlinear = railhunt.critical_speed(mine)
nonlinear

# %%
nonlinear.to_dataframe()

# %%
linear = railhunt.linear_critical_speed(mine)
linear

# %% [markdown]
# My vehicle hunts from 294 km/h after the defect (the paper's vehicle: 302 km/h; its
# critical speed is 301 km/h), and its centred running becomes unstable at 341 km/h
# instead of 441 km/h.

# %%
assert nonlinear.speed_kmh == 293.0, nonlinear.speed_kmh
assert abs(linear.speed_kmh - 341.4) < 0.5, linear.speed_kmh
assert railhunt.critical_speed(paper).speed_kmh == 301.0

# %% [markdown]
# ## Which change does it?
#
# Put each change alone on the paper's vehicle, then all together. `Vehicle.replace`
# makes a changed copy (validated like a file).

# %%
rows = []
for name in changed["parameter"]:
    variant = paper.replace(**{name: getattr(mine, name)})
    rows.append((f"only {name}", railhunt.critical_speed(variant).speed_kmh,
                 railhunt.linear_critical_speed(variant).speed_kmh))
rows.insert(0, ("paper2019", 301.0, railhunt.linear_critical_speed(paper).speed_kmh))
rows.append(("my_vehicle (all four)", nonlinear.speed_kmh, linear.speed_kmh))
attribution = pd.DataFrame(rows, columns=["vehicle", "nonlinear_kmh", "linear_kmh"])
attribution.round(1)

# %% [markdown]
# The softer yaw dampers (`C_d1`) move the Hopf point most (441 → 348 km/h) and, with
# the stiffer primary springs (`K_px`), lower the nonlinear critical speed by 6 km/h
# each. The heavier car body hardly matters; its larger yaw inertia (`J_cz`) even raises
# both speeds a little. Here the single effects roughly add up: 0 + 2 − 6 − 6 = −10 km/h
# against −8 km/h for all four together. They need not in general, since the model is
# nonlinear; run the combination rather than adding.

# %%
by_name = attribution.set_index("vehicle")
assert by_name.loc["only C_d1", "linear_kmh"] < 350 < by_name.loc["only M_c", "linear_kmh"]
assert by_name.loc["only C_d1", "nonlinear_kmh"] == 295.0
assert by_name.loc["only K_px", "nonlinear_kmh"] == 295.0

# %% [markdown]
# ## One parameter over a range
#
# The yaw damper's first-stage damping `C_d1` over a range, for my vehicle. The linear
# critical speed takes a fraction of a second per point; the nonlinear one a second or
# so. (For many points, or many parameters, use `railhunt.sweep`: see the parameter-study
# example.)

# %%
c_d1 = np.array([100e3, 200e3, 300e3, 450e3, 600e3])  # N*s/m
scan = pd.DataFrame({
    "C_d1": c_d1,
    "nonlinear_kmh": [railhunt.critical_speed(mine.replace(C_d1=c)).speed_kmh for c in c_d1],
    "linear_kmh": [railhunt.linear_critical_speed(mine.replace(C_d1=c)).speed_kmh
                   for c in c_d1],
})
fig, ax = plt.subplots(figsize=(6, 3.5))
ax.plot(scan["C_d1"] / 1e3, scan["nonlinear_kmh"], "o-", label="nonlinear (8 mm defect)")
ax.plot(scan["C_d1"] / 1e3, scan["linear_kmh"], "s--", label="linear (Hopf point)")
ax.set_xlabel("yaw damper first-stage damping C_d1 (kN·s/m)")
ax.set_ylabel("critical speed (km/h)")
ax.legend()
scan.round(1)

# %% [markdown]
# Both rise with `C_d1`: the yaw dampers resist the bogie's yaw, which is what the
# hunting motion needs. Here the nonlinear critical speed levels off above about
# 300 kN·s/m. Its fold is set mainly by the dampers' blow-off force `F_u`, which caps the
# force whatever the damping. The linear one keeps climbing.

# %%
assert np.all(np.diff(scan["linear_kmh"]) > 0)
assert scan["nonlinear_kmh"].iloc[0] < scan["nonlinear_kmh"].iloc[-1]

# %% [markdown]
# ## Save a vehicle, and the command line
#
# A changed vehicle is saved as a complete file (every parameter with its unit and
# meaning) and loads back identical:

# %%
import tempfile

folder = Path(tempfile.mkdtemp())
saved = mine.replace(C_d1=450e3).to_toml(folder / "my_450.toml")
assert railhunt.load_vehicle(saved) == mine.replace(C_d1=450e3)
print(saved.read_text()[:400])

# %% [markdown]
# The same from the command line (from the repository's root):
#
# ```bash
# railhunt critical-speed --vehicle examples/data/my.toml
# railhunt critical-speed --vehicle examples/data/my.toml --set C_d1=200e3 --json
# railhunt parameters --vehicle examples/data/my.toml     # every value, unit and meaning
# ```
