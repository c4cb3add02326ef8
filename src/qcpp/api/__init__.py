"""The implementation of qcpp's public Python API; import the names from :mod:`qcpp` itself.

One module per concept: :mod:`~qcpp.api.scenarios` (building, loading and saving scenarios),
:mod:`~qcpp.api.estimates` (``qcpp.estimate``), :mod:`~qcpp.api.compiling` (``qcpp.compile``),
:mod:`~qcpp.api.solving` (``qcpp.solve``, ``qcpp.train_qaoa``, ``qcpp.simulate_qaoa``), :mod:`~qcpp.api.devices`
and :mod:`~qcpp.api.checks` (the argument checks they share with the command line).
"""
