"""Parameter studies: sweeps over vehicle parameters and their analysis (issue 5)."""
