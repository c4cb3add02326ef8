"""File input and output for every package: output files whole or not at all (:mod:`qcppio.atomic`).

The lowest layer: it imports none of the project's packages, so the problem model (``gridcover``), the compiler
(``circuitgen``), the estimators, the simulators and the CLI all write files the same way.
"""
