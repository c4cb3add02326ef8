"""``dir(qcpp)`` is the public API (``__all__``) and dunders, without loading it; every exported error is a
:class:`qcpp.QcppError` listed in docs/api.md."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import qcpp

DOCS = Path(__file__).resolve().parents[2] / "docs" / "api.md"


def test_dir_lists_the_public_api_and_dunders_only() -> None:
    names = dir(qcpp)
    public = [n for n in names if not n.startswith("_")]
    assert public == sorted(n for n in qcpp.__all__ if not n.startswith("_"))
    assert set(qcpp.__all__) <= set(names)
    assert all(n.startswith("__") and n.endswith("__") for n in names if n.startswith("_"))
    assert not {"Any", "TYPE_CHECKING", "importlib", "annotations", "PackageNotFoundError", "version"} & set(names)


def test_dir_does_not_load_the_api() -> None:
    code = (
        "import sys, qcpp; names = dir(qcpp); "
        "assert 'compile' in names and 'qcpp.api.compiling' not in sys.modules, sorted(sys.modules); "
        "assert qcpp.compile.__module__ == 'qcpp.api.compiling'"
    )
    src = str(Path(qcpp.__file__).resolve().parents[1])
    subprocess.run([sys.executable, "-c", code], check=True, env={"PYTHONPATH": src, "PATH": ""})


def test_every_exported_error_is_a_qcpp_error_listed_in_the_api_docs() -> None:
    errors = [n for n in qcpp.__all__ if n.endswith("Error")]
    assert "QasmProfileError" in errors
    from qcpp.lowering.qasm_profiles import QasmProfileError

    assert qcpp.QasmProfileError is QasmProfileError
    text = DOCS.read_text(encoding="utf-8")
    for name in errors:
        assert issubclass(getattr(qcpp, name), (qcpp.QcppError, OSError)), name
        assert f"`{name}`" in text, name


def test_plan_options_and_solution_are_public_and_are_what_the_api_takes_and_returns() -> None:
    from qcpp.plan.options import PlanOptions
    from qcpp.problem.solvers import Solution

    assert qcpp.PlanOptions is PlanOptions and qcpp.Solution is Solution
    assert {"PlanOptions", "Solution"} <= set(qcpp.__all__) & set(dir(qcpp))
    s = qcpp.grid_scenario(2, 3, robots=1)
    assert isinstance(qcpp.solve(s), qcpp.Solution)
    assert qcpp.verify(s, options=qcpp.PlanOptions(target="ft")).holds
    text = DOCS.read_text(encoding="utf-8")
    assert "`PlanOptions`" in text and "`Solution`" in text
