"""railhunt: hunting stability of railway vehicles.

How fast a vehicle can run before it starts hunting, at what frequency it hunts, and
which suspension parameters move those numbers. The model is the 17-DOF lateral model of
a high-speed vehicle described in ``docs/model.md``.

Main entry points (imported lazily, so ``import railhunt`` stays fast)::

    Vehicle, load_vehicle            vehicle description (SI units, validated)
    simulate                         time integration with named channels
    linear_critical_speed            Hopf point of the centred equilibrium
    critical_speed                   nonlinear critical speed by bisection (the paper's)
    critical_speed_ramp              nonlinear critical speed by a slow speed ramp (type a)
    Curve, curving                   a curve of the track; steady curving and its stability
    stability_map                    critical speeds against the curve radius
    bifurcation_diagram              limit-cycle branches by path following, Hopf type
    periodic_orbit                   one limit cycle by shooting, Floquet multipliers
    hunting_frequency                hunting frequency (eigenvalue or limit cycle)
    eigen_analysis                   eigenvalues and hunting mode versus speed
    SingleDefect, InitialDisplacement  excitations
    track_irregularity, load_irregularity  random (published PSD) or measured track
    stochastic_critical_speed        lowest speed breaking the EN 14363-style criterion
    read_profile, s1002, uic60       wheel/rail profiles (SIMPACK, text; EN 13715, 60E1)
    contact_geometry                 rigid contact: r_L, r_R, contact angles, roll vs y
    contact_patches                  a yawed wheelset's contact patches (two-point, lead)
    equivalent_conicity              EN 15302 equivalent conicity of a Delta r table
    creep_coefficients               Hertz ellipse + Kalker's f11, f22, f23, f33
    creep_forces                     creep forces and spin moment of a patch (FASTSIM, exact, ...)
    sweep, read_results              parameter studies on all cores or a Dask cluster
    table1_study, section_changes    the paper's Table 1 study and its Fig. 12 sections
    reproduce                        the paper's Figs. 6-13 and an HTML report
    sensitivity                      Sobol / Morris indices of outputs to varied factors
    optimize                         Pareto front of objectives by NSGA-II
    StudyOptions                     how a study runs (file, resume, workers, cluster, progress)
"""

# ruff: noqa: I001  (the TYPE_CHECKING block keeps one `from` line per module with `X as X`)
from __future__ import annotations

from importlib import import_module
from typing import TYPE_CHECKING, Any

from railhunt._version import __version__ as __version__  # noqa: E402

# Before any numba function is defined: a cache folder per version of the sources (see
# railhunt/_cache.py; numba alone would reuse code compiled from older equations).
from railhunt import _cache  # noqa: E402

NUMBA_CACHE = _cache.configure()

_EXPORTS = {
    "Vehicle": "railhunt.vehicle",
    "load_vehicle": "railhunt.vehicle",
    "ParameterError": "railhunt.vehicle",
    "Model": "railhunt.model",
    "simulate": "railhunt.simulation",
    "SimulationResult": "railhunt.simulation",
    "SingleDefect": "railhunt.track",
    "InitialDisplacement": "railhunt.track",
    "SampledTrack": "railhunt.track",
    "linear_critical_speed": "railhunt.analysis.linear",
    "eigen_analysis": "railhunt.analysis.linear",
    "critical_speed": "railhunt.analysis.critical",
    "critical_speed_ramp": "railhunt.analysis.ramp",
    "Curve": "railhunt.curve",
    "curving": "railhunt.analysis.curving",
    "CurvingResult": "railhunt.analysis.curving",
    "stability_map": "railhunt.studies.stability_map",
    "bifurcation_diagram": "railhunt.analysis.continuation",
    "periodic_orbit": "railhunt.analysis.periodic",
    "hunting_frequency": "railhunt.analysis.frequency",
    "track_irregularity": "railhunt.irregularity",
    "load_irregularity": "railhunt.irregularity",
    "track_spectrum": "railhunt.irregularity",
    "TrackIrregularity": "railhunt.irregularity",
    "stochastic_critical_speed": "railhunt.analysis.stochastic",
    "assess_stability": "railhunt.analysis.stochastic",
    "equivalent_conicity": "railhunt.contact.conicity",
    "equivalent_conicity_regression": "railhunt.contact.conicity",
    "contact_geometry": "railhunt.contact.geometry",
    "ContactGeometry": "railhunt.contact.geometry",
    "contact_patches": "railhunt.contact.patches",
    "ContactPatch": "railhunt.contact.patches",
    "WheelsetContact": "railhunt.contact.patches",
    "Profile": "railhunt.contact.profiles",
    "read_profile": "railhunt.contact.profiles",
    "s1002": "railhunt.contact.profiles",
    "uic60": "railhunt.contact.profiles",
    "hertz_contact": "railhunt.mechanics.hertz",
    "kalker_coefficients": "railhunt.mechanics.coefficients",
    "creep_coefficients": "railhunt.mechanics.hertz",
    "creep_forces": "railhunt.mechanics.laws",
    "CreepForces": "railhunt.mechanics.laws",
    "fit_polynomials": "railhunt.contact.fit",
    "sweep": "railhunt.studies.sweep",
    "read_results": "railhunt.studies.store",
    "SweepResults": "railhunt.studies.store",
    "load_table1": "railhunt.paper2019",
    "table1_study": "railhunt.studies.sections",
    "section_changes": "railhunt.studies.sections",
    "reproduce": "railhunt.studies.reproduce",
    "sensitivity": "railhunt.studies.sensitivity",
    "SensitivityResult": "railhunt.studies.sensitivity",
    "optimize": "railhunt.studies.optimize",
    "ParetoResult": "railhunt.studies.optimize",
    "StudyOptions": "railhunt.studies.options",
}

__all__ = sorted(_EXPORTS)

# The names above, for type checkers and IDEs (explicit `X as X` re-exports; at run time they
# are imported lazily by __getattr__ below).
if TYPE_CHECKING:
    from railhunt.analysis.continuation import bifurcation_diagram as bifurcation_diagram
    from railhunt.analysis.curving import CurvingResult as CurvingResult, curving as curving
    from railhunt.analysis.critical import critical_speed as critical_speed
    from railhunt.analysis.frequency import hunting_frequency as hunting_frequency
    from railhunt.analysis.linear import (
        eigen_analysis as eigen_analysis,
        linear_critical_speed as linear_critical_speed,
    )
    from railhunt.analysis.periodic import periodic_orbit as periodic_orbit
    from railhunt.analysis.ramp import critical_speed_ramp as critical_speed_ramp
    from railhunt.analysis.stochastic import (
        assess_stability as assess_stability,
        stochastic_critical_speed as stochastic_critical_speed,
    )
    from railhunt.contact.conicity import (
        equivalent_conicity as equivalent_conicity,
        equivalent_conicity_regression as equivalent_conicity_regression,
    )
    from railhunt.contact.fit import fit_polynomials as fit_polynomials
    from railhunt.contact.geometry import (
        ContactGeometry as ContactGeometry,
        contact_geometry as contact_geometry,
    )
    from railhunt.contact.patches import (
        ContactPatch as ContactPatch,
        WheelsetContact as WheelsetContact,
        contact_patches as contact_patches,
    )
    from railhunt.mechanics.coefficients import kalker_coefficients as kalker_coefficients
    from railhunt.mechanics.hertz import (
        creep_coefficients as creep_coefficients,
        hertz_contact as hertz_contact,
    )
    from railhunt.mechanics.laws import CreepForces as CreepForces, creep_forces as creep_forces
    from railhunt.curve import Curve as Curve
    from railhunt.contact.profiles import (
        Profile as Profile,
        read_profile as read_profile,
        s1002 as s1002,
        uic60 as uic60,
    )
    from railhunt.irregularity import (
        TrackIrregularity as TrackIrregularity,
        load_irregularity as load_irregularity,
        track_irregularity as track_irregularity,
        track_spectrum as track_spectrum,
    )
    from railhunt.model import Model as Model
    from railhunt.paper2019 import load_table1 as load_table1
    from railhunt.simulation import SimulationResult as SimulationResult, simulate as simulate
    from railhunt.studies.optimize import ParetoResult as ParetoResult, optimize as optimize
    from railhunt.studies.options import StudyOptions as StudyOptions
    from railhunt.studies.reproduce import reproduce as reproduce
    from railhunt.studies.sections import (
        section_changes as section_changes,
        table1_study as table1_study,
    )
    from railhunt.studies.sensitivity import (
        SensitivityResult as SensitivityResult,
        sensitivity as sensitivity,
    )
    from railhunt.studies.stability_map import stability_map as stability_map
    from railhunt.studies.store import SweepResults as SweepResults, read_results as read_results
    from railhunt.studies.sweep import sweep as sweep
    from railhunt.track import (
        InitialDisplacement as InitialDisplacement,
        SampledTrack as SampledTrack,
        SingleDefect as SingleDefect,
    )
    from railhunt.vehicle import (
        ParameterError as ParameterError,
        Vehicle as Vehicle,
        load_vehicle as load_vehicle,
    )


def __getattr__(name: str) -> Any:
    if name in _EXPORTS:
        return getattr(import_module(_EXPORTS[name]), name)
    raise AttributeError(f"module 'railhunt' has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(list(globals()) + __all__)
