"""The creep table shipped with railhunt (Kalker's exact theory, tabulated) and the script
that builds it (``python -m railhunt.data.creep.build_creep_table``)."""
