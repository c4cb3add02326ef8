"""QAOA as a solver, on the simulators of :mod:`qcpp.simulate`: angles evaluated and trained, the trained state read.

* :mod:`~qcpp.training.evaluate`: given angles, one simulator's expectation, P(optimum) and feasible weight
  (``qcpp simulate``);
* :mod:`~qcpp.training.training` (one optimiser run at a fixed depth), :mod:`~qcpp.training.layerwise` (depth by
  depth, warm-started: the default), :mod:`~qcpp.training.objectives` (expectation, CVaR, Gibbs) and
  :mod:`~qcpp.training.mixer_only` (the every-gamma-0 warm start and multi-angle training);
* :mod:`~qcpp.training.angle_search` and :mod:`~qcpp.training.angle_fit`: yardsticks for the training (the best
  P(optimum) an expensive search finds; angles fitted across instances);
* :mod:`~qcpp.training.qaoa_solver`: train, then answer with the most probable assignment (``qcpp solve -m qaoa``).

Every module here runs a simulator of :mod:`qcpp.simulate`; none of those imports this package.
"""
