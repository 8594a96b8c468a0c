"""The commands of ``railhunt``, one module each (``critical-speed --method stochastic``
reports from ``stochastic.py``); COMMANDS lists them in the order ``railhunt --help`` shows.
"""

from __future__ import annotations

from railhunt.cli.commands.bifurcation import bifurcation_command
from railhunt.cli.commands.conicity import conicity_command
from railhunt.cli.commands.contact import contact_command
from railhunt.cli.commands.creep import creep_command
from railhunt.cli.commands.critical_speed import critical_speed_command
from railhunt.cli.commands.curve import curve_command
from railhunt.cli.commands.eigen import eigen_command
from railhunt.cli.commands.frequency import frequency_command
from railhunt.cli.commands.optimize import optimize_command
from railhunt.cli.commands.parameters import parameters_command
from railhunt.cli.commands.plot import plot_command
from railhunt.cli.commands.reproduce import reproduce_command
from railhunt.cli.commands.sections import sections_command
from railhunt.cli.commands.sensitivity import sensitivity_command
from railhunt.cli.commands.simulate import simulate_command
from railhunt.cli.commands.spectrogram import spectrogram_command
from railhunt.cli.commands.stability_map import stability_map_command
from railhunt.cli.commands.sweep import sweep_command
from railhunt.cli.commands.vehicles import vehicle_command, vehicles_command

__all__ = ["COMMANDS"]

#: Every command, in the order of ``railhunt --help``: one speed (on straight track, in a
#: curve), then speed scans, then the contact geometry and creep forces, measured signals,
#: parameter studies (of the vehicle, of the curve radius) and the paper's report.
COMMANDS = (
    simulate_command,
    curve_command,
    eigen_command,
    critical_speed_command,
    parameters_command,
    vehicles_command,
    vehicle_command,
    bifurcation_command,
    frequency_command,
    contact_command,
    conicity_command,
    creep_command,
    spectrogram_command,
    sweep_command,
    stability_map_command,
    sensitivity_command,
    optimize_command,
    sections_command,
    plot_command,
    reproduce_command,
)
