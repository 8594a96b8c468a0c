"""Studies built on the analyses: parameter sweeps, sections and the paper's reproduction."""
