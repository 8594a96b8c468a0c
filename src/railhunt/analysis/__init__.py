"""Analyses built on the model: linear stability, critical speed."""
