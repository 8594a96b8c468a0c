"""Contact mechanics of one wheel/rail patch: the Hertz normal problem, Kalker's creep
coefficients, and the tangential laws that turn creepages into creep forces and the spin
moment (:func:`creep_forces`: FASTSIM, modified FASTSIM, Kalker's exact steady-rolling
theory, Polach, the paper's heuristic law, Vermeulen-Johnson, Kalker's linear law).
"""
