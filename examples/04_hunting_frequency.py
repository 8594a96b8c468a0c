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
# # Hunting frequency and the blow-off jump
#
# How fast does the vehicle swing from side to side? The paper's definition (Sec. 3.3):
# release the vehicle from a lateral displacement. If the motion **decays**, the hunting
# frequency is that of the least-damped eigenvalue of the linearised model. If it settles
# on a **limit cycle**, it is the frequency of the cycle. `railhunt.hunting_frequency` does
# exactly that at one speed: a 3 mm displacement of all wheelsets by default, a run
# judged like the critical-speed search, then the eigenvalue, or the cycle's spectral
# peak refined by shooting.

# %%
import matplotlib.pyplot as plt
import numpy as np
import pandas as pd

import railhunt
from railhunt.analysis.frequency import frequency_jump
from railhunt.paper2019 import NO_BLOWOFF

vehicle = railhunt.Vehicle.paper2019()
railhunt.hunting_frequency(vehicle, 400.0)

# %% [markdown]
# ## Frequency against speed
#
# One call per speed; the `to_dataframe()` rows of all speeds concatenate into one table.

# %%
speeds = np.arange(320.0, 461.0, 10.0)  # km/h
table = pd.concat([railhunt.hunting_frequency(vehicle, s).to_dataframe() for s in speeds],
                  ignore_index=True)
table[["speed_kmh", "frequency_hz", "source", "amplitude", "eigen_frequency_hz"]].round(3)

# %% [markdown]
# Up to 360 km/h the 3 mm release decays and the frequency is the eigenvalue's: it rises
# slowly with speed, as a kinematic (Klingel) oscillation does. At 370 km/h the release
# no longer decays. The vehicle lands on the large limit cycle and the frequency **jumps**
# from 3.56 to 5.08 Hz. The paper's Fig. 7b has the same jump at 375 km/h, from 4 to
# 5.3 Hz.

# %%
jump = frequency_jump(table["speed_kmh"].to_numpy(), table["frequency_hz"].to_numpy(),
                      list(table["source"]))
print("jump at {:.0f} km/h: {:.2f} -> {:.2f} Hz".format(*jump))
assert jump[0] == 365.0 and abs(jump[1] - 3.56) < 0.02 and abs(jump[2] - 5.08) < 0.02

# %% [markdown]
# ## Why it jumps: the yaw dampers blow off
#
# Each yaw damper has two stages: a steep first stage (`C_d1` = 300 kN·s/m) up to the
# blow-off force `F_u` = 3 kN, then a shallow second stage (`C_d2` = 20 kN·s/m). On
# the large limit cycle the damper's piston moves faster than the blow-off velocity
# `v_u = F_u / C_d1` = 10 mm/s for much of each period. The damper then stops holding the
# bogie's yaw. The bogie turns more freely, and the cycle runs at a higher frequency than
# the linear (unsaturated) hunting mode. The run's damper velocities show it (the paper's
# Fig. 8):

# %%
cycle = railhunt.hunting_frequency(vehicle, 400.0)
fig, ax = plt.subplots(figsize=(7, 3.2))
window = cycle.t > cycle.t[-1] - 1.0
ax.plot(cycle.t[window], cycle.damper_velocity[window, 0] * 1e3, label="yaw damper 1")
for sign in (1, -1):
    ax.axhline(sign * cycle.blowoff_velocity * 1e3, color="k", ls="--", lw=1)
ax.set_xlabel("time (s)")
ax.set_ylabel("damper velocity (mm/s)")
ax.legend()
above = np.mean(np.abs(cycle.damper_velocity[window, 0]) > cycle.blowoff_velocity)
print(f"blow-off velocity {cycle.blowoff_velocity * 1e3:.0f} mm/s; damper 1 is blown off "
      f"{above:.0%} of the time on the cycle at 400 km/h")
assert above > 0.3

# %% [markdown]
# Without blow-off (`F_u` → ∞: the damper stays on its first stage) there is no jump.
# The release decays up to the Hopf point (441 km/h), and the small cycles above it stay
# near the linear hunting mode's frequency: 3.3 to 3.9 Hz at every speed.

# %%
stiff = vehicle.replace(F_u=NO_BLOWOFF)
no_blowoff = pd.concat([railhunt.hunting_frequency(stiff, s).to_dataframe() for s in speeds],
                       ignore_index=True)
fig, ax = plt.subplots(figsize=(6, 3.5))
for label, frame, marker in (("F_u = 3 kN", table, "o"), ("no blow-off", no_blowoff, "s")):
    ax.plot(frame["speed_kmh"], frame["frequency_hz"], marker + "-", label=label)
ax.set_xlabel("speed (km/h)")
ax.set_ylabel("hunting frequency (Hz)")
ax.legend()
no_blowoff[["speed_kmh", "frequency_hz", "source"]].round(2).T

# %%
steps = np.abs(np.diff(no_blowoff["frequency_hz"]))
assert steps.max() < 0.4, steps  # no jump: neighbouring speeds within 0.4 Hz
assert (no_blowoff["source"] == "eigenvalue").sum() > (table["source"] == "eigenvalue").sum()

# %% [markdown]
# From the command line (the paper's Figs. 7b and 8):
#
# ```bash
# railhunt frequency --from 300 --to 450 --png fig7b.png --damper-png fig8.png
# ```
