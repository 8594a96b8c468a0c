"""Analyses built on the model: linear stability, critical speeds, limit cycles, frequency.

Also the speed ramp, continuation of limit cycles, the stochastic criterion and spectrograms.
"""
