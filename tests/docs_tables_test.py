"""Tables of the docs that a ``qcpp estimate`` command prints are what it prints today.

A Markdown table right after a line that is one backquoted ``qcpp estimate ... --format md`` command (the estimate
guide's resource and scaling tables, the scaling table of the resource-estimates page) must equal that command's
output, run in process (commands of :data:`SLOW` in the heavy run). The headline table of README.md and
docs/index.md (ours against the paper) must hold the qubits and CX of the Quick start command's rows.
"""

from __future__ import annotations

import functools
import re
import shlex
from pathlib import Path

import pytest
from typer.testing import CliRunner

from qcpp.cli.app import app

ROOT = Path(__file__).resolve().parents[1]
PASTED = [ROOT / "docs" / "guide" / "estimate.md", ROOT / "docs" / "resource-estimates.md"]
SLOW = ("--physical", "--depth exact")
"""A command with any of these runs for many seconds (the QDK estimator, exact depths of 40x40): its table is
checked in the heavy run."""
HEADLINE = [ROOT / "README.md", ROOT / "docs" / "index.md"]
QUICK_START = "qcpp estimate --grid 3x3,4x4,5x5,6x6 --robots 1..3 --compare paper --format md"
_COMMAND = re.compile(r"^`(qcpp estimate [^`]*--format md[^`]*)`$")


@functools.cache
def run(command: str) -> str:
    """What ``command`` (a ``qcpp ...`` line) prints on standard output (once per command and process)."""
    res = CliRunner().invoke(app, shlex.split(command)[1:], env={"COLUMNS": "250"})
    assert res.exit_code == 0, res.output
    return res.stdout


def pasted_tables(text: str) -> list[tuple[int, str, str]]:
    """(line, command, table) for every table right after a lone backquoted ``qcpp estimate ... --format md``."""
    lines = text.splitlines()
    out = []
    for i, line in enumerate(lines):
        m = _COMMAND.match(line.strip())
        if not m:
            continue
        j = next((k for k in range(i + 1, len(lines)) if lines[k].strip()), len(lines))
        if j == len(lines) or not lines[j].startswith("|"):
            continue  # the command is named in prose, not above its table
        end = next((k for k in range(j, len(lines)) if not lines[k].startswith("|")), len(lines))
        out.append((i + 1, m.group(1), "\n".join(lines[j:end])))
    return out


def markdown_rows(table: str) -> list[dict[str, str]]:
    """The rows of a Markdown table as header -> cell."""
    lines = [line.strip().strip("|").split("|") for line in table.strip().splitlines()]
    head = [c.strip() for c in lines[0]]
    return [dict(zip(head, (c.strip() for c in cells))) for cells in lines[2:]]


def test_the_parser_finds_a_pasted_table() -> None:
    text = "x\n\n`qcpp estimate --grid 2x2 --format md`\n\n| a |\n|---|\n| 1 |\n\nmore\n"
    assert pasted_tables(text) == [(3, "qcpp estimate --grid 2x2 --format md", "| a |\n|---|\n| 1 |")]
    assert pasted_tables("`qcpp estimate --grid 2x2 --format md`\n(prose)\n\n| a |\n") == []
    assert markdown_rows("| a | b |\n|---|---|\n| 1 | 2 |") == [{"a": "1", "b": "2"}]


def _pasted_cases() -> list[object]:
    """One case per page and pasted table (a page without one: a case that fails), the slow ones heavy."""
    cases: list[object] = []
    for page in PASTED:
        name = str(page.relative_to(ROOT))
        tables = pasted_tables(page.read_text(encoding="utf-8")) or [(0, "", "")]
        for line, command, table in tables:
            marks = [pytest.mark.heavy] if any(flag in command for flag in SLOW) else []
            cases.append(pytest.param(page, line, command, table, marks=marks, id=f"{name}:{line}"))
    return cases


@pytest.mark.parametrize(("page", "line", "command", "table"), _pasted_cases())
def test_a_pasted_table_is_what_its_command_prints(page: Path, line: int, command: str, table: str) -> None:
    assert command, f"{page.relative_to(ROOT)} names no qcpp estimate command above a table"
    lines = page.read_text(encoding="utf-8").splitlines()
    printed = run(command).strip().splitlines()
    rows = "\n".join(x for x in printed if x.startswith("|"))
    assert table == rows, f"{page.relative_to(ROOT)}:{line}: the table differs from `{command}`"
    after = lines[line + table.count("\n") + 2 : line + table.count("\n") + 8]  # the lines under the table
    for note in (x for x in printed if x.strip() and not x.startswith("|")):  # a footnote: the page has it too
        assert note in after, f"{page.relative_to(ROOT)}:{line}: `{command}` ends with {note!r}; paste it too"


@pytest.mark.parametrize("page", HEADLINE, ids=lambda p: str(p.relative_to(ROOT)))
def test_the_headline_table_holds_the_quick_start_s_numbers(page: Path) -> None:
    text = page.read_text(encoding="utf-8")
    assert QUICK_START in text.replace("\n", " ").replace("` `", " "), "the page names no source of its table"
    start = text.index("| grid / robots |")
    headline = markdown_rows(text[start : text.index("\n\n", start)])
    printed = {f"{r['rows']}x{r['cols']} / {r['robots']}": r for r in markdown_rows(run(QUICK_START))}
    columns = {"qubits (ours)": "qubits", "qubits (paper)": "paper_qubits", "CX (ours)": "cx", "CX (paper)": "paper_cx"}
    assert headline
    for row in headline:
        for ours, theirs in columns.items():
            assert row[ours].replace(",", "") == printed[row["grid / robots"]][theirs], (page.name, row, ours)
