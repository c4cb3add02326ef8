"""``qcpp.simulate_qaoa(..., method="tensor", client=...)``: the tensor backend gets the dask client (which runs the
slices of wide contractions; ``tests/simulate/tensor_test.py`` checks sliced contractions on a cluster) and the
figures equal the exact subspace simulator's; a client with another method is refused in one line."""

from __future__ import annotations

from typing import Any

import pytest

import qcpp
from tests.api.bad_input_test import error_of

pytestmark = pytest.mark.xdist_group("quimb")  # one worker compiles quimb's kernels (tests/conftest.py)

S = qcpp.grid_scenario(2, 3, robots=1)
ANGLES = [0.37, 0.81]


def test_the_client_reaches_the_tensor_backend_and_the_figures_are_the_subspace_simulator_s(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    from dask.distributed import Client, LocalCluster

    import qcpp.simulate.tensor as tensor

    seen: list[Any] = []

    class Recording(tensor.TensorCircuit):
        def __init__(self, *args: Any, **kwargs: Any) -> None:
            seen.append(kwargs.get("client"))
            super().__init__(*args, **kwargs)

    monkeypatch.setattr(tensor, "TensorCircuit", Recording)
    exact = qcpp.simulate_qaoa(S, 1, angles=ANGLES)
    with Client(LocalCluster(n_workers=1, threads_per_worker=1, processes=False, dashboard_address=None)) as client:
        run = qcpp.simulate_qaoa(S, 1, angles=ANGLES, method="tensor", client=client)
        assert seen == [client]
    assert run.method == "tensor"
    assert run.p_optimum == pytest.approx(exact.p_optimum, abs=1e-9)
    assert run.expectation == pytest.approx(exact.expectation, abs=1e-9)


def test_a_client_needs_the_tensor_method() -> None:
    message = error_of(lambda: qcpp.simulate_qaoa(S, 1, client=object()), qcpp.OptionError)
    assert message.startswith("client:") and "tensor" in message
