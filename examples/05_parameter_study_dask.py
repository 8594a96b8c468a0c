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
# # A parameter study on a Dask cluster
#
# `railhunt.sweep` computes, for every point of a study, the nonlinear critical speed,
# the linear one and the hunting frequency. The points are independent, so they run in
# parallel on a [Dask](https://docs.dask.org) cluster: by default a local one with one
# worker per core, or any cluster you point it at. Each point is written to the results
# file as soon as it finishes, and an interrupted study resumes from that file.
#
# Here: a local cluster of two worker processes, made explicitly so that you can see it
# (and its dashboard address).

# %%
import tempfile
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
from dask.distributed import Client, LocalCluster

import railhunt

cluster = LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                       dashboard_address=":0")
client = Client(cluster)
print(client)

# %% [markdown]
# ## One parameter, one line
#
# The yaw damper's first-stage damping `C_d1` at six values (SI units: N·s/m), the
# results written to `cd1.csv` in a scratch folder:

# %%
vehicle = railhunt.Vehicle.paper2019()
folder = Path(tempfile.mkdtemp())
results = railhunt.sweep(vehicle, {"C_d1": np.linspace(100e3, 600e3, 6)},
                         client=client, out=folder / "cd1.csv")
results

# %% [markdown]
# `to_dataframe()` gives the results file as a table (units in `attrs["units"]`):

# %%
frame = results.to_dataframe()
print(frame.attrs["units"])
frame[["C_d1", "critical_speed_kmh", "linear_critical_speed_kmh", "hunting_frequency_hz",
       "frequency_source"]].round(2)

# %%
fig, ax1 = plt.subplots(figsize=(6, 3.5))
ax1.plot(frame["C_d1"] / 1e3, frame["critical_speed_kmh"], "o-", label="nonlinear")
ax1.plot(frame["C_d1"] / 1e3, frame["linear_critical_speed_kmh"], "s--", label="linear")
ax1.set_xlabel("C_d1 (kN·s/m)")
ax1.set_ylabel("critical speed (km/h)")
ax1.legend(loc="upper left")
ax2 = ax1.twinx()
ax2.plot(frame["C_d1"] / 1e3, frame["hunting_frequency_hz"], "^:", color="tab:green")
ax2.set_ylabel("hunting frequency (Hz)", color="tab:green")
fig.tight_layout()

# %% [markdown]
# As in the paper's Fig. 10a, the critical speed rises with `C_d1`. Each point's
# frequency comes from a run at 300 km/h (`frequency_speed_kmh`) over the same defect
# as its critical-speed search. It is the eigenvalue's when the motion decays and the
# limit cycle's when it hunts (`frequency_source`). So it jumps where the critical speed
# crosses 300 km/h.

# %%
assert np.all(np.diff(frame["linear_critical_speed_kmh"]) > 0)
assert frame["critical_speed_kmh"].iloc[-1] > frame["critical_speed_kmh"].iloc[0]
assert (frame["status"] == "ok").all()

# %% [markdown]
# ## Resume instead of recompute
#
# Run the same study again with `resume=True`: every point is already in the file, so
# nothing is computed. After a crash or Ctrl-C, only the missing points would be.

# %%
again = railhunt.sweep(vehicle, {"C_d1": np.linspace(100e3, 600e3, 6)},
                       client=client, out=folder / "cd1.csv", resume=True)
print(f"computed {again.computed}, found in the file {again.resumed}")
assert (again.computed, again.resumed) == (0, 6)
assert again.rows == results.rows

# %% [markdown]
# ## Two parameters: a Latin hypercube
#
# Designs: `lines` (one parameter at a time, the default), `grid`, `random` and `lhs`.
# Eight points of a Latin hypercube over `C_d1` and the blow-off force `F_u`, only the
# linear and nonlinear critical speeds:

# %%
lhs = railhunt.sweep(vehicle, {"C_d1": (150e3, 500e3), "F_u": (2e3, 6e3)}, design="lhs",
                     samples=8, seed=1, outputs=("critical_speed", "linear_critical_speed"),
                     client=client)
lhs.to_dataframe()[["C_d1", "F_u", "critical_speed_kmh", "linear_critical_speed_kmh"]].round(1)

# %% [markdown]
# The linear critical speed depends on `C_d1` only (the linearised damper never blows
# off); the nonlinear one also rises with `F_u`.

# %%
client.close()
cluster.close()

# %% [markdown]
# ## Pointing it at a real cluster
#
# Nothing in the study changes; only where it runs. Start a scheduler and workers on
# the machines, each with the same railhunt installed:
#
# ```bash
# dask scheduler                                  # on the head node: tcp://10.0.0.5:8786
# dask worker tcp://10.0.0.5:8786 --nthreads 1    # on each compute node, one per core
# ```
#
# then give the address to the study, in Python or on the command line:
#
# ```python
# results = railhunt.sweep(vehicle, {"C_d1": np.linspace(20e3, 1000e3, 21)},
#                          scheduler="tcp://10.0.0.5:8786", out="cd1.csv")
# # or with a Client you made yourself (dask-jobqueue, Kubernetes, Coiled, ...):
# results = railhunt.sweep(vehicle, {...}, client=Client("tcp://10.0.0.5:8786"))
# ```
#
# ```bash
# railhunt sweep C_d1 --from 20e3 --to 1000e3 --num 21 --scheduler tcp://10.0.0.5:8786 \
#     --out cd1.csv
# ```
#
# Use one thread per worker process: each point runs compiled code that holds the GIL.
# The results file is written by the process that called `sweep`, so it needs no
# shared file system. In a script (not a notebook), guard the call with
# `if __name__ == "__main__":`, because Dask starts local workers with *spawn*.
# More in *Sweeps and clusters* in the user guide.
