"""Every Python example of README.md and the docs pages runs as printed, and prints the numbers its comments claim.

A page's ``python`` blocks run in order in one namespace (a later block may use an earlier one's names), in a fresh
directory that holds the repository's ``examples/`` (so ``load_scenario("examples/...")`` works and written files
land outside the checkout). A ``print(...)`` whose line ends in a comment starting with numbers (``# 144 2786``,
``# -20.0``, ``# 2786: the estimate is exact``) must print exactly those numbers; other comments are prose. A block
right after a line ``<!-- not run: REASON -->`` is shown, not run (it needs a cluster, say).
"""

from __future__ import annotations

import ast
import contextlib
import io
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PAGES = sorted([ROOT / "README.md", *(ROOT / "docs").glob("*.md"), *(ROOT / "docs" / "guide").glob("*.md")])
NOT_RUN = "<!-- not run:"
_CLAIM = re.compile(r"-?\d[\d.,]*(?: -?\d[\d.,]*)*")


def python_blocks(text: str) -> list[tuple[int, str]]:
    """The ``python`` blocks of a Markdown page that are run: (first line number, source)."""
    blocks: list[tuple[int, str]] = []
    lines = text.splitlines()
    i = 0
    while i < len(lines):
        if lines[i].strip() == "```python":
            before = next((line.strip() for line in reversed(lines[:i]) if line.strip()), "")
            end = next(j for j in range(i + 1, len(lines)) if lines[j].strip() == "```")
            if not before.startswith(NOT_RUN):
                blocks.append((i + 2, "\n".join(lines[i + 1 : end])))
            i = end
        i += 1
    return blocks


def claimed_output(source: str, node: ast.stmt) -> str | None:
    """The numbers the comment on a ``print(...)`` statement's last line says it prints, if it says so."""
    if not (isinstance(node, ast.Expr) and isinstance(node.value, ast.Call)):
        return None
    if not (isinstance(node.value.func, ast.Name) and node.value.func.id == "print"):
        return None
    line = source.splitlines()[(node.end_lineno or node.lineno) - 1]
    if "#" not in line:
        return None
    comment = line.split("#", 1)[1].split(":", 1)[0].strip()
    return comment if _CLAIM.fullmatch(comment) else None


PAGES_WITH_CODE = [p for p in PAGES if python_blocks(p.read_text(encoding="utf-8"))]


def test_the_parser_finds_the_readme_example_and_its_claims() -> None:
    blocks = python_blocks((ROOT / "README.md").read_text(encoding="utf-8"))
    assert blocks, "README.md has no python block"
    source = blocks[0][1]
    claims = [c for node in ast.parse(source).body if (c := claimed_output(source, node))]
    assert claims and all(_CLAIM.fullmatch(c) for c in claims)
    assert claimed_output("print(x)  # 1 2: the counts", ast.parse("print(x)  # 1 2: the counts").body[0]) == "1 2"
    assert claimed_output("print(x)  # a dict", ast.parse("print(x)  # a dict").body[0]) is None
    text = "<!-- not run: needs a cluster -->\n```python\nraise SystemExit\n```\n\n```python\nx = 1\n```\n"
    assert python_blocks(text) == [(7, "x = 1")]


@pytest.mark.parametrize("page", PAGES_WITH_CODE, ids=lambda p: str(p.relative_to(ROOT)))
def test_the_page_s_python_examples_run_and_print_what_they_claim(
    page: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    (tmp_path / "examples").symlink_to(ROOT / "examples")
    monkeypatch.chdir(tmp_path)
    namespace: dict[str, object] = {"__name__": "__docs_example__"}
    for first_line, source in python_blocks(page.read_text(encoding="utf-8")):
        for node in ast.parse(source).body:
            where = f"{page.relative_to(ROOT)}:{first_line + node.lineno - 1}"
            code = compile(ast.Module(body=[node], type_ignores=[]), where, "exec")
            out = io.StringIO()
            with contextlib.redirect_stdout(out):
                exec(code, namespace)
            claim = claimed_output(source, node)
            if claim is not None:
                assert out.getvalue().strip() == claim, f"{where} prints {out.getvalue().strip()!r}, claims {claim!r}"
