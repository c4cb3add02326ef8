"""``qcpp.qubo_model`` and ``qcpp.write_qubo``: the file ``qcpp export`` writes for the same scenario and options,
byte for byte; the dimod model and the Ising form keep the energies; bad options raise one line."""

from __future__ import annotations

import importlib.util
import itertools
from pathlib import Path

import numpy as np
import pytest

import qcpp
from tests.api.bad_input_test import error_of
from tests.cli.clirun import run

S = qcpp.grid_scenario(3, 3, robots=1, obstacles=[(1, 1)])


@pytest.mark.parametrize(
    ("form", "penalty", "fmt"),
    [("per-robot", None, "qubo"), ("per-robot", 2.5, "ising"), ("paper", None, "lp"), ("per-robot", None, "mps")],
)
def test_the_file_is_the_one_export_writes(tmp_path: Path, form: str, penalty: float | None, fmt: str) -> None:
    flags = ["--form", form] + ([] if penalty is None else ["--penalty", str(penalty)])
    res = run("export", "--grid", "3x3", "--robots", "1", "--obstacle", "1,1", "--format", fmt,
              "--out", str(tmp_path / "cli.out"), *flags)  # fmt: skip
    assert res.exit_code == 0, res.output
    model = qcpp.qubo_model(S, form=form, penalty=penalty)
    qcpp.write_qubo(model, tmp_path / "api.out", fmt)
    assert (tmp_path / "api.out").read_bytes() == (tmp_path / "cli.out").read_bytes()


def test_ising_and_dimod_forms_keep_the_energies() -> None:
    model = qcpp.qubo_model(S, form="paper")
    h, J, offset = model.to_ising()
    rows = np.array(list(itertools.product((0, 1), repeat=model.num_variables)))
    z = 1 - 2 * rows  # x = (1 - Z) / 2
    index = {lab: i for i, lab in enumerate(model.labels)}
    ising = offset + z @ np.array([h[lab] for lab in model.labels])
    for (a, b), v in J.items():
        ising = ising + v * z[:, index[a]] * z[:, index[b]]
    assert np.allclose(ising, model.energy(rows))
    if importlib.util.find_spec("dimod") is not None:
        bqm = model.to_dimod()
        sample = dict(zip(model.labels, rows[5].tolist(), strict=True))
        assert bqm.energy(sample) == pytest.approx(model.energy(rows[5]))


def test_bad_options_name_what_is_wrong(tmp_path: Path) -> None:
    assert error_of(lambda: qcpp.qubo_model(S, form="ising"), qcpp.OptionError).startswith("form:")
    assert error_of(lambda: qcpp.qubo_model(S, penalty=-1.0), qcpp.OptionError).startswith("penalty: expected")
    assert error_of(lambda: qcpp.qubo_model(S, form="paper", penalty=2.0), qcpp.OptionError).startswith("penalty:")
    model = qcpp.qubo_model(S)
    assert error_of(lambda: qcpp.write_qubo(model, tmp_path / "m", "csv"), qcpp.OptionError).startswith("format:")
    assert error_of(lambda: qcpp.write_qubo(S, tmp_path / "m", "qubo"), qcpp.OptionError).startswith("model:")  # type: ignore[arg-type]
    with pytest.raises(qcpp.OutputError):
        qcpp.write_qubo(model, tmp_path / "no such folder" / "m.json", "qubo")
    assert not list(tmp_path.iterdir())


def test_solve_passes_the_sampler_and_its_answer_is_feasible() -> None:
    pytest.importorskip("dwave.samplers")
    from qcpp.problem.paths import is_feasible

    s = qcpp.load_scenario("examples/two_robots_4x4.toml")
    sol = qcpp.solve(s, "qubo", sampler="sa")
    assert sol.notes[0].endswith(", sa")
    assert all(is_feasible(s, r, m) for r, m in enumerate(sol.paths))
    assert qcpp.solve(s, "qubo").notes[0].endswith(", tabu")
