"""Tensor-network validation of compiled, lowered QAOA circuits at 15-50 qubits (quimb + cotengra), slicing on dask.

The tests that run quimb are in one xdist group (tests/conftest.py): one worker compiles its numba kernels.
Each case compiles the lowered circuit, runs it from |0...0> at seeded random angles and checks, with two
independent tensor methods (an MPS of the whole circuit, and exact contraction with a reused cotengra path),
that the ancillas end in |0> (probability 1 to 1e-8) and that feasible assignments' amplitudes equal the exact
feasible-subspace simulator's (1e-8).

The 18-40 qubit checks and the dask LocalCluster check are ``heavy`` (CI runs them in a second step); the CLI
check stays in the default run.
"""

from __future__ import annotations

import ast
import json
from pathlib import Path
from typing import Any

import pytest
from typer.testing import CliRunner

from qcpp.cli.app import app
from qcpp.plan.options import PlanOptions
from qcpp.problem.presets import default_scenario
from qcpp.problem.scenario_io import load_scenario
from qcpp.simulate.validate import validate
from tests.collection_imports import QUIMB_AT_COLLECTION

EXAMPLE = Path(__file__).parents[2] / "examples" / "paper_3x3.toml"

pytestmark = pytest.mark.xdist_group("quimb")  # one worker compiles quimb's kernels (tests/conftest.py)


def test_no_test_module_imports_quimb_at_collection(pytestconfig: pytest.Config) -> None:
    """No test module imports quimb at collection, where every worker would compile its kernels (tests/conftest.py)."""
    assert pytestconfig.stash[QUIMB_AT_COLLECTION] is False


@pytest.mark.heavy  # 30 s to 2 min each on 2 cores: CI's second step
@pytest.mark.parametrize(
    ("rows", "cols", "robots", "p", "max_amplitudes"),
    [
        (3, 3, 1, 1, None),  # 18 qubits: every feasible amplitude
        (3, 3, 2, 1, 16),  # 30 qubits
        pytest.param(3, 4, 2, 1, None, marks=pytest.mark.heavy),  # 50 qubits: all 1,444 amplitudes, both methods
    ],
)
def test_compiled_circuit_matches_subspace_simulator(
    rows: int, cols: int, robots: int, p: int, max_amplitudes: int | None
) -> None:
    report = validate(default_scenario(rows, cols, robots), p, backend="tensor", seed=7, max_amplitudes=max_amplitudes)
    assert report.passed, report.to_dict()
    assert abs(report.ancilla_probability - 1) < 1e-8
    assert report.max_amplitude_error < 1e-8
    mps = [c for c in report.checks if c.method == "tensor MPS"]
    assert mps and all(c.status == "pass" for c in mps)
    assert report.amplitudes_checked == report.feasible_assignments


@pytest.mark.heavy
def test_tensor_agrees_with_dense_statevector_on_the_paper_example() -> None:
    s = load_scenario(EXAMPLE)
    dense = validate(s, 2, backend="statevector", seed=3)
    tensor = validate(s, 2, backend="tensor", seed=3)
    assert dense.passed and tensor.passed
    assert dense.angles == tensor.angles


def test_validate_cli_json_and_exit_codes() -> None:
    res = CliRunner().invoke(app, ["validate", str(EXAMPLE), "-p", "1", "--backend", "tensor", "--json"])
    assert res.exit_code == 0, res.stderr
    d = json.loads(res.stdout)
    assert d["passed"] is True and d["backend"] == "tensor" and d["amplitudes_checked"] == d["feasible_assignments"]
    bad = CliRunner().invoke(app, ["validate", str(EXAMPLE), "-p", "1", "--angles", "0.1"])
    assert bad.exit_code == 2 and "--angles" in bad.stderr and len(bad.stderr.strip().splitlines()) == 1


# --- slicing and dask ------------------------------------------------------------------------------------------
@pytest.mark.heavy  # a dask LocalCluster and sliced path searches: 307 s of the default run beside other jobs
def test_sliced_contraction_on_a_local_dask_cluster_equals_the_unsliced_one(tmp_path: Path) -> None:
    import numpy as np
    from dask.distributed import Client, LocalCluster

    from qcpp.plan.compile import compile_scenario
    from qcpp.simulate.statevector import simulate_statevector
    from qcpp.simulate.tensor import TensorCircuit, contract_sliced

    angles = {"gamma_0": 0.4, "beta_0": 0.9, "gamma_1": 0.3, "beta_1": 1.2}
    c = compile_scenario(default_scenario(3, 3, 1), 2, lowered=True, bindings=angles).circuit
    dense = simulate_statevector(c)
    state = int(np.argmax(np.abs(dense)))
    tc = TensorCircuit(c, cache_dir=tmp_path)
    unsliced = tc.amplitude(state)
    assert abs(unsliced - dense[state]) < 1e-10
    tn = tc._amplitude_network(state)
    tree, info = tc._tree(tn)
    assert info.width >= 8  # wide enough that slicing has something to cut
    assert abs(contract_sliced(tn, tree, target_slices=8) - unsliced) < 1e-10  # in-process slices
    with Client(LocalCluster(n_workers=1, threads_per_worker=2, processes=False, dashboard_address=":0")) as client:
        assert abs(contract_sliced(tn, tree, target_slices=8, client=client) - unsliced) < 1e-10
        # TensorCircuit slices a contraction wider than max_width and runs the slices on the cluster
        narrow = TensorCircuit(c, cache_dir=tmp_path, client=client, max_width=info.width - 3)
        assert abs(narrow.amplitude(state) - unsliced) < 1e-10


def test_validate_cli_rejects_dask_without_the_tensor_backend() -> None:
    res = CliRunner().invoke(app, ["validate", str(EXAMPLE), "--backend", "sparse", "--dask", "local"])
    assert res.exit_code == 2 and "--dask" in res.stderr and len(res.stderr.strip().splitlines()) == 1


# --- ancilla blocks collapsed, open-qubit batches ----------------------------------------------------------------
def test_collapsed_ancilla_blocks_and_open_qubits_give_the_dense_amplitudes(tmp_path: Path) -> None:
    import numpy as np

    from qcpp.plan.compile import compile_scenario
    from qcpp.simulate.statevector import simulate_statevector
    from qcpp.simulate.tensor import TensorCircuit, collapse_ancilla_blocks

    s = default_scenario(2, 3, 2)
    angles = {"gamma_0": 0.4, "beta_0": 0.9, "gamma_1": 0.3, "beta_1": 1.2}
    # unfused partial mixers: each is a block with clean ancillas at both ends (what the tensor backend compiles)
    c = compile_scenario(s, 2, PlanOptions(fuse=False), lowered=True, bindings=angles).circuit
    n = s.num_variables
    ancillas = list(range(n, c.num_qubits))
    ops = collapse_ancilla_blocks(c, ancillas)
    assert ops is not None and any(isinstance(op, np.ndarray) for _, op in ops)
    dense = simulate_statevector(c)
    states = [int(k) for k in np.argsort(-np.abs(dense))[:40]] + [1 << n]  # the last one has an ancilla set
    tc = TensorCircuit(c, cache_dir=tmp_path, ancillas=ancillas)
    np.testing.assert_allclose(tc.amplitudes(states), dense[states], atol=1e-10)
    opened = list(range(n - s.edges_per_robot, n))
    np.testing.assert_allclose(tc.amplitudes(states, open_qubits=opened), dense[states], atol=1e-10)


def test_a_wide_diagonal_block_is_kept_as_its_phases_and_a_wide_permutation_is_not(tmp_path: Path) -> None:
    import numpy as np

    import qcpp.simulate.tensor as tensor
    from qcpp.ir.circuit import Circuit, Section
    from qcpp.ir.gates import ccx, cx, h, rz
    from qcpp.simulate.statevector import simulate_statevector

    regs = [("d", 3), ("a", 1)]
    mix = Section("h", [h(0), h(1), h(2)])
    # compute x0 AND x1 into the ancilla, phase it, uncompute: diagonal on the data, ancilla clean
    phase = Section("p", [ccx(0, 1, 3), rz(0.7, 3), cx(3, 2), rz(0.3, 2), cx(3, 2), ccx(0, 1, 3), rz(0.2, 0)])
    c = Circuit(regs, [mix, phase, mix, phase, Section("t", [h(1), rz(0.4, 2)])])
    narrow = tensor.collapse_ancilla_blocks(c, [3], max_block_data_qubits=1)  # every block "too wide" for a matrix
    wide = tensor.collapse_ancilla_blocks(c, [3])
    diagonals = [(qs, op) for qs, op in narrow if isinstance(op, np.ndarray)]
    matrices = [(qs, op) for qs, op in wide if isinstance(op, np.ndarray)]
    assert len(diagonals) == 2 and all(op.shape == (8,) for _, op in diagonals)
    assert [qs for qs, _ in diagonals] == [qs for qs, _ in matrices]
    for (_, d), (_, m) in zip(diagonals, matrices):  # the phases are the verified operator's diagonal
        np.testing.assert_allclose(m, np.diag(d), atol=1e-12)
    dense = simulate_statevector(c)
    for width in (1, tensor.MAX_BLOCK_DATA_QUBITS):  # the blocks as their phases, then as matrices
        tc = tensor.TensorCircuit(c, cache_dir=tmp_path, ancillas=[3], max_block_data_qubits=width)
        np.testing.assert_allclose(tc.amplitudes(range(16)), dense, atol=1e-12)
        assert tc.block_leak is not None and tc.block_leak < 1e-12
    # a clean-ancilla Toffoli on the data is unitary but not diagonal: too wide for a matrix, so not collapsed
    toffoli = Circuit(regs, [mix, Section("t", [ccx(0, 1, 3), cx(3, 2), ccx(0, 1, 3)])])
    assert tensor.collapse_ancilla_blocks(toffoli, [3], max_block_data_qubits=1) is None
    [_, _, _, (qubits, op)] = tensor.collapse_ancilla_blocks(toffoli, [3])
    assert qubits == (0, 1, 2) and op.shape == (8, 8)


def test_a_block_that_leaves_an_ancilla_dirty_is_not_collapsed() -> None:
    from qcpp.ir.circuit import Circuit, Section
    from qcpp.ir.gates import ccx, h
    from qcpp.simulate.tensor import collapse_ancilla_blocks

    leaky = Circuit([("d", 2), ("a", 1)], [Section("s", [h(0), ccx(0, 1, 2)])])  # no uncompute
    assert collapse_ancilla_blocks(leaky, [2]) is None
    # a later section that uncomputes makes the pair one clean block
    fixed = Circuit([("d", 2), ("a", 1)], [Section("s", [h(0), ccx(0, 1, 2)]), Section("t", [ccx(0, 1, 2)])])
    [(qubits, op)] = collapse_ancilla_blocks(fixed, [2])
    assert qubits == (0, 1) and op.shape == (4, 4)


@pytest.mark.filterwarnings("ignore:Couldn't import `kahypar`")  # cotengra's note, once per process
def test_a_cached_path_serves_only_networks_of_its_shape(tmp_path: Path) -> None:
    """Networks that differ only in their tensors without indices (scalars, which simplification leaves in varying
    numbers) get their own paths, in memory and from the disk cache in a later process (cotengra's own key has
    them all share one, and the second contraction fails on an index out of range)."""
    import numpy as np
    import quimb.tensor as qtn

    from qcpp.simulate.contraction_paths import PATH_OPTIMIZERS, path_optimizer

    def network(scalars: int, vectors: bool) -> qtn.TensorNetwork:
        """``scalars`` tensors 2.0, after (with ``vectors``) the vectors (1, 2) and (3, 5) joined by one index."""
        pair = [qtn.Tensor(np.array([1.0, 2.0]), inds=("i",)), qtn.Tensor(np.array([3.0, 5.0]), inds=("i",))]
        return qtn.TensorNetwork((pair if vectors else []) + [qtn.Tensor(np.array(2.0)) for _ in range(scalars)])

    shapes = [(13, False), (6, False), (5, True), (2, True)]
    want = [2.0**scalars * (13.0 if vectors else 1.0) for scalars, vectors in shapes]
    for _process in range(2):  # the second reads the first's paths from disk
        PATH_OPTIMIZERS.clear()
        opt = path_optimizer(tmp_path)
        assert [float(network(*shape).contract(optimize=opt)) for shape in shapes] == want
    assert len(list(tmp_path.glob("*/*"))) == len(shapes)
    PATH_OPTIMIZERS.clear()


def _two_vectors_and_a_scalar() -> Any:
    """Two vectors (1, 1) joined by one index, and the scalar 2: the network contracts to 4."""
    import numpy as np
    import quimb.tensor as qtn

    one = qtn.Tensor(np.ones(2), inds=("i",))
    return qtn.TensorNetwork([one, one.copy(), qtn.Tensor(np.array(2.0))])


@pytest.mark.filterwarnings("ignore:Couldn't import `kahypar`")  # cotengra's note, once per process
def test_a_path_file_cut_short_is_searched_again_and_replaced(tmp_path: Path) -> None:
    """A path file cut short (a full disk or a kill in the middle of a write) counts as absent: the path is
    searched again and the file rewritten whole (cotengra alone fails on every later contraction of that shape)."""
    from qcpp.simulate.contraction_paths import PATH_OPTIMIZERS, path_optimizer

    PATH_OPTIMIZERS.clear()
    assert float(_two_vectors_and_a_scalar().contract(optimize=path_optimizer(tmp_path))) == 4.0
    [saved] = tmp_path.glob("*/*")
    whole = saved.read_bytes()
    saved.write_bytes(whole[:20])
    PATH_OPTIMIZERS.clear()  # a later process
    assert float(_two_vectors_and_a_scalar().contract(optimize=path_optimizer(tmp_path))) == 4.0
    assert saved.read_bytes() == whole and [saved] == list(tmp_path.glob("*/*"))
    PATH_OPTIMIZERS.clear()


FULL_DISK = """
import resource, signal, sys, warnings
import numpy as np
import quimb.tensor as qtn
signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
resource.setrlimit(resource.RLIMIT_FSIZE, (0, 0))  # every write to a file fails, as on a full disk
from qcpp.simulate.contraction_paths import CacheFolderWarning, path_optimizer
with warnings.catch_warnings(record=True) as caught:
    warnings.simplefilter("always", CacheFolderWarning)
    opt = path_optimizer(sys.argv[1])
    one = qtn.Tensor(np.ones(2), inds=("i",))  # the network of _two_vectors_and_a_scalar
    network = qtn.TensorNetwork([one, one.copy(), qtn.Tensor(np.array(2.0))])
    print([float(network.copy().contract(optimize=opt)) for _ in range(2)])
print([str(w.message) for w in caught if w.category is CacheFolderWarning])
"""


def test_a_path_folder_that_cannot_be_written_keeps_paths_in_memory(tmp_path: Path) -> None:
    """Where no path file can be written (a full disk), the contraction still answers, says why the new path is not
    saved (once: the second contraction finds it in memory), and leaves no file behind."""
    import subprocess
    import sys

    repo = Path(__file__).resolve().parents[2]
    env = {"PYTHONPATH": str(repo / "src"), "PATH": "/usr/bin:/bin", "HOME": str(tmp_path)}
    res = subprocess.run([sys.executable, "-W", "ignore::UserWarning", "-c", FULL_DISK, str(tmp_path / "paths")],
                         capture_output=True, text=True, env=env, timeout=300)  # fmt: skip
    assert res.returncode == 0, res.stderr
    results, messages = res.stdout.splitlines()
    assert results == "[4.0, 4.0]"
    [message] = ast.literal_eval(messages)
    assert message.startswith(f"new contraction paths stay in memory: cannot write {tmp_path / 'paths'}")
    assert message.endswith(": File too large")
    assert not [p for p in (tmp_path / "paths").rglob("*") if p.is_file()]


def test_path_optimizers_are_shared_per_directory_until_the_cache_is_cleared(tmp_path: Path) -> None:
    """path_optimizer hands out one optimizer per directory and settings (its paths are reused by every contraction
    of the process) until PATH_OPTIMIZERS.clear(), after which a new one is built."""
    from qcpp.simulate.contraction_paths import PATH_OPTIMIZERS, path_optimizer

    first = path_optimizer(tmp_path / "a")
    assert path_optimizer(tmp_path / "a") is first
    assert path_optimizer(tmp_path / "b") is not first
    assert path_optimizer(tmp_path / "a", max_repeats=4) is not first
    PATH_OPTIMIZERS.clear()
    assert len(PATH_OPTIMIZERS) == 0
    assert path_optimizer(tmp_path / "a") is not first
