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
# # A bifurcation diagram and what its branches mean
#
# Above some speed, a lateral disturbance of a railway vehicle does not die out: the
# wheelsets settle on a **limit cycle**, a periodic side-to-side motion of a few
# millimetres and a few hertz. The bifurcation diagram draws every limit cycle of the
# vehicle on ideal track against the speed. It shows which speed is "critical" for which
# disturbance.
#
# `railhunt.bifurcation_diagram` finds the cycles directly: shooting with Newton's method
# (the yaw dampers' blow-off switchings located), stability from the Floquet multipliers,
# and pseudo-arclength continuation in speed from the Hopf point, through the folds. It
# takes about 20 s for the paper's vehicle (the run time is in the summary below).

# %%
import time

import matplotlib.pyplot as plt

import railhunt

vehicle = railhunt.Vehicle.paper2019()
start = time.perf_counter()
diagram = railhunt.bifurcation_diagram(vehicle, speed_range_kmh=(250.0, 460.0))
print(f"computed in {time.perf_counter() - start:.0f} s")
diagram

# %% [markdown]
# `to_dataframe()` gives one row per limit cycle: the branch it lies on, its speed, the
# amplitude of the leading wheelset's lateral displacement, period, frequency, stability
# and largest Floquet multiplier.

# %%
orbits = diagram.to_dataframe()
orbits.head()

# %%
fig, ax = plt.subplots(figsize=(7, 4.2))
colours = {0: "tab:blue", 1: "tab:red"}
for (branch, stable), part in orbits.groupby(["branch", "stable"]):
    ax.plot(part["speed_kmh"], part["amplitude"] * 1e3, ".", ms=3, color=colours[branch],
            alpha=1.0 if stable else 0.35,
            label=f"branch {branch} ({'stable' if stable else 'unstable'})")
ax.axhline(0, color="k", lw=1)
ax.plot([diagram.hopf_speed_kmh], [0], "ko")
ax.annotate("Hopf point", (diagram.hopf_speed_kmh, 0), (400, 1.5),
            arrowprops={"arrowstyle": "->"})
ax.set_xlabel("speed (km/h)")
ax.set_ylabel("amplitude of y_w1 (mm)")
ax.legend(fontsize=8)
fig.tight_layout()

# %% [markdown]
# ## Reading it
#
# * **The equilibrium** (amplitude 0) is stable up to the **Hopf point**, 441.3 km/h: the
#   linear critical speed, where the hunting eigenvalue crosses into the right half plane.
#   Below it, *small* disturbances die out.
# * **Branch 0** is born at the Hopf point and runs *backwards*, unstable, to lower speeds:
#   the bifurcation is **subcritical**. An unstable cycle is a threshold: a disturbance
#   smaller than it dies out, a larger one grows. The branch folds at 302 km/h and returns
#   stable with a *small* leading-wheelset amplitude. On this part the rear bogie hunts
#   (wheelsets 3 and 4 at 6 to 11 mm) while the front bogie hardly moves.
# * **Branch 1** was found by simulating a large disturbance at the top speed: both bogies
#   hunt at 5 to 11 mm. Its stable part reaches down to its fold at **292.8 km/h**, the
#   lowest speed at which the vehicle can hunt at all: the **nonlinear critical speed**.
#
# Between 292.8 and 441.3 km/h the stable equilibrium and stable limit cycles coexist:
# whether the vehicle hunts depends on how hard it is disturbed. Engineers take the lower
# speed, because track defects in service are large.
#
# The paper's point P (where a 3 mm disturbance meets an unstable branch, 375 km/h in
# the paper) has no counterpart here: the unstable parts of the branches lie below 1.4 mm
# or above 4.3 mm, so the summary shows `nan`.

# %%
assert abs(diagram.hopf_speed_kmh - 441.32) < 0.05
assert diagram.hopf_type == "subcritical"
assert abs(diagram.fold_speed_kmh - 292.8) < 0.5
assert any(abs(f.speed_kmh - 302.0) < 0.5 for f in diagram.branches[0].folds)

# %% [markdown]
# The wheelset amplitudes tell the two families apart. On the stable part of branch 0
# the rear wheelsets (3, 4) swing far more than the leading one:

# %%
rear = diagram.branches[0]
stable_rows = [k for k in range(rear.speed_kmh.size) if rear.stable[k]
               and 350.0 < rear.speed_kmh[k] < 450.0]
k = stable_rows[len(stable_rows) // 2]
print(f"branch 0 at {rear.speed_kmh[k]:.0f} km/h: wheelset amplitudes (mm)",
      (rear.wheelset_amplitudes[k] * 1e3).round(2))
assert rear.wheelset_amplitudes[k][2] > 5 * rear.wheelset_amplitudes[k][0]

# %% [markdown]
# ## Three ways to the nonlinear critical speed
#
# The paper lists three ways to find the nonlinear critical speed by simulation. railhunt
# has two of them beside the diagram:
#
# * **(b) a single track defect** (`critical_speed`, the paper's method): the highest
#   speed at which the motion after an 8 mm defect dies out. It finds **301 km/h**, just
#   below the fold of branch 0. The large cycle of branch 1 has a small basin near its
#   fold, and no single defect reaches it there.
# * **(a) a slow speed ramp** (`critical_speed_ramp`): start on the large cycle and lower
#   the speed until it dies. It finds **292 km/h**, the fold of branch 1.

# %%
bisection = railhunt.critical_speed(vehicle)
ramp = railhunt.critical_speed_ramp(vehicle)
print(f"single defect: {bisection.speed_kmh:.0f} km/h, ramp: {ramp.speed_kmh:.1f} km/h")
ramp

# %%
assert bisection.speed_kmh == 301.0
assert abs(ramp.speed_kmh - 292.0) < 0.5

# %% [markdown]
# A stiffer blow-off (a larger `F_u`) lifts the folds and turns the bifurcation from
# subcritical to supercritical (`railhunt bifurcation --fu-family 1,2,3,5,8,inf`, the
# paper's Fig. 13); see *Bifurcation and frequency* in the user guide. From the command
# line:
#
# ```bash
# railhunt bifurcation --png fig7a.png --json > diagram.json
# ```
