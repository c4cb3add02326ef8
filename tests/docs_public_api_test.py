"""The tutorials and the user pages use only the public API: ``import qcpp`` and its names (``qcpp.testing``, the
documented testing extra, aside), as docs/architecture.md promises. Internal module paths belong on the developer
pages (architecture, resource estimates, paper notes, benchmarks, experiments, validation)."""

from __future__ import annotations

import ast
import json
import re
from pathlib import Path

import pytest

import qcpp

ROOT = Path(__file__).resolve().parent.parent
NOTEBOOKS = sorted((ROOT / "docs" / "tutorials").glob("*.ipynb"))
USER_PAGES = [ROOT / "README.md", ROOT / "docs" / "index.md", ROOT / "docs" / "getting-started.md",
              ROOT / "docs" / "api.md", *sorted((ROOT / "docs" / "guide").glob("*.md"))]  # fmt: skip
ALLOWED_MODULES = {"qcpp", "qcpp.testing"}
_BLOCK = re.compile(r"^```python\n(.*?)^```", re.S | re.M)


def private_uses(source: str) -> list[str]:
    """Every import of a ``qcpp`` submodule and every ``qcpp.NAME`` that is not a public name, in ``source``."""
    found = []
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.Import):
            found += [a.name for a in node.names if a.name.startswith("qcpp.") and a.name not in ALLOWED_MODULES]
        elif isinstance(node, ast.ImportFrom) and (node.module or "").startswith("qcpp"):
            if node.module not in ALLOWED_MODULES:
                found.append(f"from {node.module} import ...")
            elif node.module == "qcpp":
                found += [f"from qcpp import {a.name}" for a in node.names if a.name not in qcpp.__all__]
        elif isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name) and node.value.id == "qcpp":
            found += [f"qcpp.{node.attr}"] if node.attr not in qcpp.__all__ and node.attr != "testing" else []
    return found


def test_the_checker_finds_a_private_use() -> None:
    assert private_uses("import qcpp\nqcpp.compile(s)\nfrom qcpp import estimate") == []
    assert private_uses("from qcpp.training.layerwise import X") == ["from qcpp.training.layerwise import ..."]
    assert private_uses("import qcpp.plan.qaoa") == ["qcpp.plan.qaoa"]
    assert private_uses("import qcpp\nqcpp.plan.qaoa_plan(s)") == ["qcpp.plan"]
    assert private_uses("from qcpp import qaoa_plan") == ["from qcpp import qaoa_plan"]


@pytest.mark.parametrize("notebook", NOTEBOOKS, ids=lambda p: p.name)
def test_a_tutorial_uses_only_public_names(notebook: Path) -> None:
    cells = json.loads(notebook.read_text(encoding="utf-8"))["cells"]
    code = "\n".join("".join(c["source"]) for c in cells if c["cell_type"] == "code")
    source = "\n".join(line for line in code.splitlines() if not line.lstrip().startswith(("%", "!")))  # magics
    assert private_uses(source) == [], notebook.name


@pytest.mark.parametrize("page", USER_PAGES, ids=lambda p: str(p.relative_to(ROOT)))
def test_a_user_page_s_python_uses_only_public_names(page: Path) -> None:
    for block in _BLOCK.findall(page.read_text(encoding="utf-8")):
        try:
            uses = private_uses(block)
        except SyntaxError:  # a fragment (an excerpt with '...'): nothing to check
            continue
        assert uses == [], f"{page.relative_to(ROOT)}: {uses}"
