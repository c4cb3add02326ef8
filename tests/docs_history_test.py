"""The README, the docs pages and the source describe the software as it is: no session or issue numbers, no commit
hashes, no story of how a figure changed (that belongs in CHANGELOG.md and the commit messages).

A light regex over README.md, docs/*.md, docs/guide/*.md and src/**/*.py; :data:`ALLOWED` lists the few lines where a
pattern means something else (a hash column a script prints, a sentence about another package's versions).
"""

from __future__ import annotations

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

HISTORY = re.compile(
    r"\bsessions?\b"  # work sessions
    r"|\b(?:issues?|PR|pull request|fix(?:es|ed)?|closes?|finding)\s*#\d+"  # issue and PR references
    r"|\(#\d+\)"
    r"|(?<![.\w])(?!0[bx])(?=[0-9a-f]*[a-f])(?=[0-9a-f]*\d)[0-9a-f]{7,40}\b(?![-+]\d)"  # commit hashes
    r"|\bpreviously\b|\bformerly\b|\bused to be\b|\bno longer\b|\bthe old way\b|\bas before\b|\bonce failed\b"
    r"|\bwas [^.;:]{1,40}, now\b|\bdefaults? (?:is|are) now\b|\b(?:is|are) now the default\b|\bnow defaults?\b",
    re.IGNORECASE,
)

ALLOWED = (
    re.compile(r"\| [0-9a-f]{12,16}(?: \|)?$"),  # a hash column a benchmark prints (sections_speed.py, ...)
    re.compile(r"qdk no longer has \(qdk 1\.33 has it\)"),  # another package's versions
    re.compile(r"localized ancillas are no longer the plan's sections"),  # a circuit's state, not history
    re.compile(r"it can no longer end the process"),  # what a held lock prevents
)


def files() -> list[Path]:
    """The files checked: user docs and the library's source."""
    docs = [ROOT / "README.md", ROOT / "CONTRIBUTING.md", *(ROOT / "docs").glob("*.md"),
            *(ROOT / "docs" / "guide").glob("*.md")]  # fmt: skip
    return sorted([*docs, *(ROOT / "src").rglob("*.py")])


def history_lines(text: str) -> list[tuple[int, str]]:
    """The lines of ``text`` (number, line) that tell history, :data:`ALLOWED` lines aside."""
    out = []
    for n, line in enumerate(text.splitlines(), 1):
        if HISTORY.search(line) and not any(a.search(line) for a in ALLOWED):
            out.append((n, line.strip()))
    return out


def test_the_pattern_finds_history_and_passes_plain_descriptions() -> None:
    told = [
        "Fixed in session 31 (issue #12).",
        "the sweep took 288 s before d736226",
        "the router previously wrote one SWAP per gate",
        "the depth was 5,212, now 4,980",
        "`compile p=5` is the old way",
        "the default is now exact",
        "see (#31)",
        "the default is now the exact rule",
    ]
    plain = [
        "qcpp #2 + our placement",  # a candidate's name
        "3x3/1 | grid | 1.0 | 1343533c8cc126a5",  # a hash column
        "the stage the work is in now",
        "# Degrees are now 1 at the ends",  # a step of an algorithm
        "<= 2.220446049250313e-16",
        "decode_edges(s, m, bits) == (0b1000101,)",
        "| 4x4/2 | heavy-hex:9 | 5,038 | 11bbccc930ce |",
        "robots 0-3 start in the corners",
        "a test proves them equal on over 500 scenarios",
    ]
    assert [s for s in told if not history_lines(s)] == []
    assert [s for s in plain if history_lines(s)] == []


def test_docs_and_source_tell_no_history() -> None:
    found = [f"{p.relative_to(ROOT)}:{n}: {line}" for p in files() for n, line in history_lines(p.read_text("utf-8"))]
    assert found == [], "\n".join(found)
