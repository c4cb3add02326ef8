"""Where float costs stop being exact: the cost bound and the simulated phases' amplitude error per edge length.

Two robots on 3x3 (one obstacle), growing ``edge_length``: the scenario's cost bound
(:func:`qcpp.problem.cost_range.cost_bound`), whether the general range (2^53) and the phase range (2^26) take it,
and the largest amplitude error of ``validate --backend sparse`` (the compiled circuit against the
feasible-subspace simulator, seed 0) run through the library, past the CLI's refusal. The phase range is chosen
from this table: below it the error stays far under the 1e-8 tolerance.

Run:  PYTHONPATH=src python benchmarks/cost_range.py
"""

from __future__ import annotations

import argparse

from qcpp.problem.cost_range import COST_LIMIT, PHASE_COST_LIMIT, cost_bound
from qcpp.problem.scenario import scenario_from_dict
from qcpp.simulate.validate import validate

BASE = {
    "grid": {"rows": 3, "cols": 3, "obstacles": [[1, 1]]},
    "robots": [{"start": [0, 0], "goal": [2, 2]}, {"start": [0, 2], "goal": [2, 0]}],
}


def main() -> None:
    argparse.ArgumentParser(description=__doc__.splitlines()[0]).parse_args()  # --help, and no other argument
    print(f"{'edge_length':>11} {'cost bound':>11} {'<= 2^53':>8} {'<= 2^26':>8} {'max amplitude error':>20} verdict")
    for length in (1.0, 1e1, 1e2, 1e3, 1e4, 1e5):
        s = scenario_from_dict({**BASE, "objective": {"edge_length": length}})
        bound = cost_bound(s)
        report = validate(s, 1, "sparse", seed=0)
        verdict = "passed" if report.passed else "FAILED"
        print(f"{length:>11g} {bound:>11.3g} {bound <= COST_LIMIT!s:>8} {bound <= PHASE_COST_LIMIT!s:>8} "
              f"{report.max_amplitude_error:>20.2e} {verdict}")


if __name__ == "__main__":
    main()
