"""Validation and robustness suites: the contacts, gear designs and reference analyses that the command lines of
scripts/ run and tabulate and that tests/ check (the envelope suite, random face gear designs, the thermal inlet
analysis and the published thermal validation)."""
