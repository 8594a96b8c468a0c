"""Parameter studies: sweeps, result files, Table 1 sections, the paper's reproduction."""
