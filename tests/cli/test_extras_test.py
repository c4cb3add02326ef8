"""Test-only libraries stay out of production: no module of ``src/qcpp`` but the optional :mod:`qcpp.testing`
imports ``hypothesis`` or :mod:`qcpp.testing` (an installation without the ``test`` extra must import every one)."""

from __future__ import annotations

import ast
import subprocess
import sys
from pathlib import Path

import qcpp

SRC = Path(qcpp.__file__).resolve().parent
TEST_ONLY = ("hypothesis", "qcpp.testing")


def _imported(tree: ast.AST) -> set[str]:
    names: set[str] = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            names |= {a.name for a in node.names}
        elif isinstance(node, ast.ImportFrom) and node.module:
            names.add(node.module)
            names |= {f"{node.module}.{a.name}" for a in node.names}
    return names


def _offenders(root: Path) -> list[str]:
    out = []
    for path in sorted(root.rglob("*.py")):
        if path == root / "testing.py":
            continue
        names = _imported(ast.parse(path.read_text(encoding="utf-8")))
        if any(n == t or n.startswith(t + ".") for n in names for t in TEST_ONLY):
            out.append(path.relative_to(root).as_posix())
    return out


def test_no_production_module_imports_a_test_only_library() -> None:
    assert _offenders(SRC) == []


def test_the_check_sees_a_test_only_import(tmp_path: Path) -> None:
    (tmp_path / "a.py").write_text("def f():\n    from qcpp import testing\n", encoding="utf-8")
    (tmp_path / "b.py").write_text("from hypothesis import strategies\n", encoding="utf-8")
    (tmp_path / "c.py").write_text("import qcpp.testing_free\n", encoding="utf-8")
    assert _offenders(tmp_path) == ["a.py", "b.py"]


def test_the_crosscheck_imports_without_hypothesis() -> None:
    code = "import sys; import qcpp.estimators.crosscheck; print('hypothesis' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"
