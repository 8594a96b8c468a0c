"""Timing report for railhunt: simulation, critical speeds, a SciPy baseline, cold start.

Run from the repository root::

    python benchmarks/run.py            # 5 repeats per case
    python benchmarks/run.py --quick    # fewer repeats
    python benchmarks/run.py --repeat 9
    python benchmarks/run.py --only creep   # the contact mechanics' rows alone
    python benchmarks/run.py --only machinery   # the study machinery's rows alone

Times are medians over the repeats, measured warm (after a first call has compiled or
loaded the numba functions). The exit code is 0 whatever the outcome: this is a report,
not a test. The last line lists the cases that missed their target.
"""

from __future__ import annotations

import argparse
import math
import subprocess
import sys
import time
from collections.abc import Callable
from pathlib import Path

import numpy as np
from scipy.integrate import solve_ivp

import railhunt
from railhunt.kernel import damper as rh_damper
from railhunt.kernel import track as rh_track
from railhunt.kernel import wheelset as rh_wheelset
from railhunt.kernel.layout import (
    FORCE0,
    N_DOF,
    N_STATE,
    RATE0,
    WHEELSET_PSI,
    WHEELSET_Y,
    WR,
    Y_W1,
)
from railhunt.model import Model
from railhunt.simulation import auto_step, default_atol
from railhunt.units import kmh_to_ms

# The table of rows (Row, timing, printing) has its own module, which the global
# studies' rows use too; its names are importable from here as before.
from table import Row, fmt_time, median_time, print_table  # noqa: E402, F401

SPEED_KMH = 350.0
DURATION = 10.0
Y_AGREEMENT = 1e-6  # m: baseline vs railhunt DOPRI5, final y_w1
SWEEP_SPEEDUP = 1.7  # sweep throughput of 2 workers over 1 (issue 5)
#: Issue 19: one nonlinear critical-speed search at most this share of the baseline's time,
#: and sweep points per second per worker (every output) at least twice the 3 of before.
SEARCH_SHARE = 0.06
SWEEP_RATE_TARGET = 6.0

COLD_SNIPPET = (
    "import time; t=time.time(); import railhunt; v=railhunt.Vehicle.paper2019(); "
    "railhunt.simulate(v, 300, duration=1.0); print(time.time()-t)"
)


# --------------------------------------------------------------------------------------
# Baseline: the same physics as a pure-NumPy right-hand side for scipy's solve_ivp.
# It reuses the model's assembled arrays and calls the pure-Python versions (.py_func) of
# the compiled scalar helpers, so there is one set of equations (railhunt.kernel.rhs).
# --------------------------------------------------------------------------------------


def numpy_rhs(model: Model, speed: float, excitation: object) -> Callable:
    """dx/dt(t, x) written with NumPy, as a typical solve_ivp user would (speed in m/s)."""
    s = model.system(excitation)
    lin, bd, dd, dpar, wr = s.linear, s.damper_rows, s.damper_acc, s.damper, s.wheel_rail
    trk, trs, offsets = s.track, s.track_samples, s.wheelset_delay
    inv_mass = 1.0 / model.mass
    iy, ip = WHEELSET_Y, WHEELSET_PSI  # wheelsets' lateral displacements and yaw angles
    # The Python body of the wheel/rail forces (its small helpers stay compiled, as before).
    wheelset_contact = rh_wheelset.wheelset_contact.py_func
    damper_velocity = rh_damper.damper_velocity.py_func
    alignment = rh_track.alignment.py_func
    nq = N_DOF

    def rhs(t: float, x: np.ndarray) -> np.ndarray:
        dq = x[RATE0 : RATE0 + nq]
        forces = x[FORCE0:]
        acc = lin @ x[:FORCE0] + dd @ forces
        v_visc = np.array([damper_velocity(f, *dpar[d, 1:]) for d, f in enumerate(forces)])
        dforces = dpar[:, 0] * (bd @ dq - v_visc)
        for j in range(len(iy)):
            yr, slope = alignment(speed * t - offsets[j], trk, trs)
            fy, mz, _, _ = wheelset_contact(
                x[iy[j]] - yr, dq[iy[j]], x[ip[j]], x[ip[j]] - slope, dq[ip[j]], dq[ip[j]],
                speed, wr[j], wr[j, WR.N], wr[j, WR.N],
            )
            acc[iy[j]] += fy * inv_mass[iy[j]]
            acc[ip[j]] += mz * inv_mass[ip[j]]
        return np.concatenate([dq, acc, dforces])

    return rhs


def baseline_run(vehicle: railhunt.Vehicle, excitation: object):
    model = Model(vehicle)
    f = numpy_rhs(model, kmh_to_ms(SPEED_KMH), excitation)
    return solve_ivp(
        f, (0.0, DURATION), np.zeros(N_STATE), method="RK45", rtol=1e-6, atol=default_atol()
    )


def check_baseline_rhs(vehicle: railhunt.Vehicle, excitation: object) -> float:
    """Largest relative difference between the NumPy and the compiled right-hand sides."""
    model = Model(vehicle)
    speed = kmh_to_ms(SPEED_KMH)
    f = numpy_rhs(model, speed, excitation)
    rng = np.random.default_rng(1)
    worst = 0.0
    for t in (0.0, 0.1, 0.25):
        x = np.concatenate([rng.normal(0, 2e-3, FORCE0), rng.normal(0, 2e3, N_STATE - FORCE0)])
        a = f(t, x)
        b = model.derivative(x, speed, t=t, excitation=excitation)
        worst = max(worst, float(np.max(np.abs(a - b) / (np.abs(b) + 1e-12))))
    return worst


def cold_start() -> float:
    """Seconds for import + first simulate in a fresh process (second of two runs)."""
    out = math.nan
    for _ in range(2):  # the first run warms numba's cache
        proc = subprocess.run(
            [sys.executable, "-c", COLD_SNIPPET], capture_output=True, text=True, check=False
        )
        if proc.returncode != 0:
            print(proc.stderr, file=sys.stderr)
            return math.nan
        out = float(proc.stdout.strip().splitlines()[-1])
    return out


# --------------------------------------------------------------------------------------


def sweep_rate(vehicle: railhunt.Vehicle, workers: int, repeat: int) -> tuple[float, int]:
    """Median seconds and points of a 24-point study (C_d1 and K_px lines, every output) on
    a local Dask cluster of ``workers`` processes, every worker's numba code loaded first."""

    from railhunt.studies.execute import local_client
    from railhunt.studies.sweep import warm_up

    warm_up()
    study = {"C_d1": np.linspace(50e3, 600e3, 12), "K_px": np.linspace(10e6, 80e6, 12)}
    with local_client(workers) as client:
        client.run(warm_up)  # each worker loads the compiled code from numba's cache
        seconds, result = median_time(lambda: railhunt.sweep(vehicle, study, client=client),
                                      max(repeat, 2))  # fmt: skip
        return seconds, len(result.rows)


def warm_up_curves() -> None:
    """Load the compiled code, the curve analyses' included, in this process (a worker)."""
    from railhunt.studies.sweep import warm_up

    warm_up()
    railhunt.curving(railhunt.Vehicle.paper2019(), 200.0, railhunt.Curve(2000.0, 0.1))


def curve_rows(vehicle: railhunt.Vehicle, repeat: int) -> tuple[list[Row], str]:
    """Curved track (issue 14): steady curving, both critical speeds in a curve (150 mm cant;
    R = 3000 m, and 8000 m for the nonlinear one), and a stability map of 5 radii with both
    critical speeds on a local Dask cluster of 2 workers (the workers' compiled code loaded,
    cluster start-up not timed)."""
    from railhunt.studies.execute import local_client
    from railhunt.studies.sweep import warm_up

    curve = railhunt.Curve(3000.0, cant=0.15)
    rows = []
    t_curv, state = median_time(lambda: railhunt.curving(vehicle, 300.0, curve), repeat)
    rows.append(Row("steady curving (R 3000 m, 150 mm cant, 300 km/h)", t_curv, 0.020))
    t_lin, lin = median_time(lambda: railhunt.linear_critical_speed(vehicle, curve=curve),
                             repeat)  # fmt: skip
    rows.append(Row("linear critical speed in a curve (R 3000 m)", t_lin, 0.100))
    # Two curves: at 8000 m the nonlinear critical speed lies far below the Hopf point, as on
    # straight track; at 3000 m it lies at the Hopf point, where trial runs decay slowly and
    # the search simulates longer.
    wide = railhunt.Curve(8000.0, cant=0.15)
    t_nlw, nlw = median_time(lambda: railhunt.critical_speed(vehicle, curve=wide), repeat)
    rows.append(Row("nonlinear critical speed in a curve (R 8000 m)", t_nlw, 0.5))
    t_nl, nl = median_time(lambda: railhunt.critical_speed(vehicle, curve=curve), repeat)
    rows.append(Row("nonlinear critical speed in a curve (R 3000 m, at the Hopf point)", t_nl,
                    0.5))  # fmt: skip
    radii = [1000.0, 2000.0, 4000.0, 8000.0, math.inf]
    with local_client(2) as client:
        client.run(warm_up)  # each worker loads the compiled code, the curves' included
        client.run(railhunt.curving, vehicle, 200.0, railhunt.Curve(2000.0, 0.1))
        t0 = time.perf_counter()
        result = railhunt.stability_map(vehicle, radii, 0.15, client=client)
        t_map = time.perf_counter() - t0
    rows.append(Row("stability map, 5 radii, both critical speeds (2 Dask workers)", t_map,
                    20.0))  # fmt: skip
    found = ", ".join(
        f"{'straight' if r['radius_m'] == math.inf else format(r['radius_m'], 'g')}: "
        f"{r['critical_speed_kmh']:.0f}/{r['linear_critical_speed_kmh']:.1f}"
        for r in result.rows)  # fmt: skip
    summary = (f"curves: at 300 km/h in R 3000 m (150 mm cant) y_w1 "
               f"{state.wheelset_y[0] * 1e3:.3f} mm, {'stable' if state.stable else 'unstable'}"
               f"; critical speeds there {nl.speed_kmh:.0f} km/h (nonlinear, "
               f"{len(nl.trials)} trials), {lin.speed_kmh:.1f} km/h (linear); in R 8000 m "
               f"{nlw.speed_kmh:.0f} km/h ({len(nlw.trials)} trials); stability map "
               f"(nonlinear/linear km/h) {found}")  # fmt: skip
    return rows, summary


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5, help="repeats per case (default 5)")
    parser.add_argument("--quick", action="store_true", help="fewer repeats (2, baseline 1)")
    parser.add_argument("--only", choices=["creep", "machinery"], help="run only these rows")
    args = parser.parse_args(argv)
    repeat = 2 if args.quick else max(1, args.repeat)
    if args.only == "machinery":
        import study_machinery

        return study_machinery.main()
    if args.only == "creep":
        from contact_mechanics import creep_rows

        rows = creep_rows(repeat, Row)
        print(f"railhunt {railhunt.__version__}, Python {sys.version.split()[0]}, "
              f"{repeat} repeats\n")
        print_table(rows)
        misses = [r.case for r in rows if r.verdict == "FAIL"]
        print(f"SUMMARY: {len(misses)} missed: " + "; ".join(misses) if misses
              else "SUMMARY: all targets met")
        return 0
    repeat_baseline = 1 if args.quick else min(repeat, 3)  # the baseline takes seconds

    vehicle = railhunt.Vehicle.paper2019()
    exc = railhunt.SingleDefect()
    dt_ms = auto_step(Model(vehicle), kmh_to_ms(SPEED_KMH)) * 1e3
    rows: list[Row] = []
    print(
        f"railhunt {railhunt.__version__}, Python {sys.version.split()[0]}, "
        f"{repeat} repeats (baseline {repeat_baseline}), median of warm runs\n"
    )

    # A sweep point builds its vehicle (the layout's assembly) and its Model: from the
    # parsed layout, no file read; reading a layout file is once per study.
    t_point, _ = median_time(lambda: Model(vehicle.replace(C_d1=vehicle.C_d1 * 1.01)),
                             max(repeat, 20))  # fmt: skip
    rows.append(Row("build a Model for one sweep point (paper2019 layout)", t_point, 0.010))
    from railhunt.vehicle.files import shipped_path

    path = str(shipped_path("paper2019"))
    t_file, _ = median_time(lambda: Model(railhunt.load_vehicle(path)), max(repeat, 5))
    rows.append(Row("read the paper2019 layout file and build its Model", t_file, 0.100))

    t_rk4, _ = median_time(
        lambda: railhunt.simulate(vehicle, SPEED_KMH, duration=DURATION, excitation=exc), repeat
    )
    rows.append(Row(f"simulate 10 s (RK4, dt={dt_ms:.1f} ms auto)", t_rk4))

    t_dp, res_dp = median_time(
        lambda: railhunt.simulate(
            vehicle, SPEED_KMH, duration=DURATION, excitation=exc, method="dopri5"
        ),
        repeat,
    )
    rows.append(Row("simulate 10 s (DOPRI5)", t_dp))

    t_lin, lin = median_time(lambda: railhunt.linear_critical_speed(vehicle), repeat)
    rows.append(Row("linear critical speed", t_lin, 0.020))

    t_nl, nl = median_time(lambda: railhunt.critical_speed(vehicle), repeat)
    rows.append(Row("nonlinear critical speed search", t_nl, 0.3))

    warm_up_curves()
    curves, curve_summary = curve_rows(vehicle, repeat)
    rows += curves

    # Per-point contact mechanics against the centred model on the same vehicle (S1002/UIC60).
    from per_point import contact_mechanics_rows

    rows += contact_mechanics_rows(repeat, Row)

    # Two-point contact (up to two patches per wheel, over y and yaw) against per-point.
    from two_point import two_point_rows

    rows += two_point_rows(repeat, Row)

    # Periodic orbits and continuation (issue 4). The orbit case warms the compiled code;
    # the whole diagram is timed once (it takes seconds).
    from railhunt.analysis.continuation import bifurcation_diagram
    from railhunt.analysis.periodic import phase_origin

    settle = railhunt.simulate(vehicle, SPEED_KMH, duration=20.0,
                               excitation=railhunt.InitialDisplacement(0.008))  # fmt: skip
    k = phase_origin(settle.t, settle.x[:, Y_W1])
    t_orb, orbit = median_time(
        lambda: railhunt.periodic_orbit(vehicle, SPEED_KMH, settle.x[k], 0.21), repeat
    )
    rows.append(Row(f"limit cycle by shooting at {SPEED_KMH:g} km/h (+ Floquet)", t_orb))
    t0 = time.perf_counter()
    diagram = bifurcation_diagram(vehicle, (200.0, 500.0))
    t_bif = time.perf_counter() - t0
    n_orbits = sum(b.speed_kmh.size for b in diagram.branches)
    rows.append(Row(f"bifurcation diagram 200-500 km/h ({n_orbits} orbits)", t_bif, 30.0))
    t_hf, _ = median_time(lambda: railhunt.hunting_frequency(vehicle, 400.0), repeat)
    rows.append(Row("hunting frequency at 400 km/h (limit cycle)", t_hf))
    # A sweep point's hunting frequency (issue 19): the run over the defect, past the saddle
    # cycle it lingers at, then shooting for the stable cycle (with its Floquet multipliers).
    t_hf_defect, _ = median_time(lambda: railhunt.hunting_frequency(
        vehicle, 350.0, excitation=railhunt.SingleDefect()), repeat)  # fmt: skip
    rows.append(Row("hunting frequency at 350 km/h over the defect (stable cycle)",
                    t_hf_defect))  # fmt: skip
    t_ramp, ramp = median_time(lambda: railhunt.critical_speed_ramp(vehicle), 1)
    rows.append(Row("critical speed by speed ramp (type a)", t_ramp))

    rhs_err = check_baseline_rhs(vehicle, exc)
    t_base, sol = median_time(lambda: baseline_run(vehicle, exc), repeat_baseline)
    rows.append(Row("baseline: solve_ivp + NumPy RHS, 10 s", t_base))
    rows.append(Row(f"nonlinear critical speed search against the baseline "
                    f"({t_nl / t_base:.3f}x; target {SEARCH_SHARE:g}x)", t_nl,
                    SEARCH_SHARE * t_base))  # fmt: skip

    # One-command reproduction of the paper's figures (issue 5): quick in this process; the
    # full run on a local Dask cluster of 2 workers when Dask is installed (timed once each).
    import tempfile

    from railhunt.studies.reproduce import reproduce

    with tempfile.TemporaryDirectory() as tmp:
        t_rq = reproduce(Path(tmp) / "quick", quick=True).seconds
        rows.append(Row("railhunt reproduce --quick (1 process)", t_rq, 60.0))
        if not args.quick:
            from railhunt.studies.execute import local_client

            with local_client(2) as client:
                t_rf = reproduce(Path(tmp) / "full", client=client).seconds
            rows.append(Row("railhunt reproduce, full (2 Dask workers)", t_rf, 300.0))

    t_cold = cold_start()
    rows.append(Row("import + first call (cold process, numba cache warm)", t_cold, 5.0))

    # Contact mechanics: the exact theory's and FASTSIM's cost per case.
    from contact_mechanics import creep_rows

    rows += creep_rows(repeat, Row)

    # The global studies (issue 19): a fold speed, a Sobol study on 2 workers.
    from global_studies import global_study_rows

    rows += global_study_rows(repeat, args.quick, Row)

    # Sweep throughput (issue 5): the same study on a local Dask cluster of 1 and 2
    # workers (cluster start-up not timed).
    rates = {n: sweep_rate(vehicle, n, repeat) for n in (1, 2)}
    for n, (seconds, n_points) in rates.items():
        rows.append(Row(f"sweep of {n_points} points, {n} worker{'s' if n > 1 else ''} "
                        f"({n_points / seconds:.2f} points/s; target "
                        f"{SWEEP_RATE_TARGET * n:g})", seconds,
                        n_points / (SWEEP_RATE_TARGET * n)))  # fmt: skip
    speedup = rates[1][0] / rates[2][0]

    print_table(rows)

    y_rh = float(res_dp.x[-1, Y_W1])
    y_base = float(sol.y[Y_W1, -1])
    diff = abs(y_rh - y_base)
    ok = diff <= Y_AGREEMENT and sol.status == 0 and res_dp.ok
    print()
    print(
        f"results: linear critical speed {lin.speed_kmh:.1f} km/h "
        f"({lin.frequency_hz:.2f} Hz); nonlinear {nl.speed_kmh:.0f} km/h "
        f"({len(nl.trials)} trial speeds)"
    )
    print(
        f"limit cycle at {SPEED_KMH:g} km/h: {orbit.amplitude * 1e3:.3f} mm, "
        f"{orbit.frequency_hz:.3f} Hz; diagram: {diagram.hopf_type}, Hopf "
        f"{diagram.hopf_speed_kmh:.1f} km/h, lowest fold {diagram.fold_speed_kmh:.1f} km/h; "
        f"ramp: cycle dies at {ramp.speed_kmh:.1f} km/h"
    )
    print(
        f"baseline check: NumPy RHS vs compiled RHS max rel. difference {rhs_err:.1e}; "
        f"final y_w1 at t = {DURATION:g} s: railhunt DOPRI5 {y_rh * 1e3:+.6f} mm, "
        f"solve_ivp {y_base * 1e3:+.6f} mm, |difference| = {diff:.2e} m "
        f"({'agrees' if ok else 'DISAGREES'} to {Y_AGREEMENT:g} m)"
    )
    print(
        f"baseline: {sol.nfev} RHS calls vs {res_dp.stats['rhs_calls']} for railhunt DOPRI5; "
        f"speed-up of railhunt DOPRI5 over the baseline: {t_base / t_dp:.0f}x "
        f"(RK4: {t_base / t_rk4:.0f}x)"
    )

    print(curve_summary)
    print(
        f"sweep throughput: 1 worker {rates[1][1] / rates[1][0]:.2f} points/s, 2 workers "
        f"{rates[2][1] / rates[2][0]:.2f} points/s: {speedup:.2f}x (target >= "
        f"{SWEEP_SPEEDUP:g}x)"
    )

    misses = [r.case for r in rows if r.verdict == "FAIL"]
    if speedup < SWEEP_SPEEDUP:
        misses.append(f"sweep speed-up with 2 workers ({speedup:.2f}x)")
    if not ok:
        misses.append("baseline agreement check")
    if misses:
        print(f"SUMMARY: {len(misses)} missed: " + "; ".join(misses))
    else:
        print("SUMMARY: all targets met")
    return 0


if __name__ == "__main__":
    sys.exit(main())
