"""Parameter studies: sweep designs, parallel execution, result files, Table 1 sections."""
