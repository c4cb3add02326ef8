"""A progress line cut to the terminal's width (:func:`qcpp.io.progress._fit_line`) splits no word where a word
boundary is near: what it keeps of the task and the stage are whole words, with ``…`` for what went; only a word
with no boundary within :data:`~qcpp.io.progress.WORD_REACH` characters before the cut (a long path, or the
first word of the text) is cut inside, and then the ``…`` follows it at once. Checked at every width 20..120.
"""

from __future__ import annotations

import re

import pytest

from qcpp.io.progress import WORD_REACH, _cut_end, _cut_middle, _fit_line

TASKS = (
    "estimate",
    "compile 3x4, 1 robot(s), p=1",
    "validate two_robots_4x4.toml",
    "compile examples/a_really_long_scenario_file_name_without_spaces.toml, device ibm_fez",
    "cpsat on 4x4, 2 robots",
)
STAGES = (
    "",
    "routing the whole circuit",
    "simulating the feasible subspace",
    "compiling numba kernels (first run only)",
    "3x3 r1 p1 on heavy-hex:7: choosing partial-mixer plans on the cells (13 / 18)",
    "proving equivalence with QCEC (mqt.qcec), this may take a while",
    "routing_the_whole_circuit_with_sabre_windows_and_relays",
)
NUMBERS = (["1,234 / 60,807 rows (2.0%)", "6 s elapsed", "about 4 min left"], ["31 s elapsed"])


def words(text: str) -> list[str]:
    return re.split(r"[\s,:]+", text.strip(" ,:"))


def split_words(task: str, stage: str, numbers: list[str], line: str) -> list[str]:
    """The pieces of ``line`` that are not whole words of the input nor an allowed cut of a long or first word."""
    whole = set(words(task)) | set(words(stage)) | set(words(" ".join(numbers))) | {"…", ""}
    bad = []
    for piece in words(line):
        if piece in whole:
            continue
        stem = piece.removesuffix("…")
        first_word = task.startswith(stem) or stage.startswith(stem)  # nothing before it to cut back to
        long_word = len(stem) >= WORD_REACH and any(w.startswith(stem) for w in whole)
        if piece.endswith("…") and (stem in whole or first_word or long_word):
            continue
        bad.append(piece)
    return bad


@pytest.mark.parametrize("task", TASKS)
def test_no_word_is_split_where_a_boundary_is_near_at_every_width(task: str) -> None:
    cut = 0
    for stage in STAGES:
        for numbers in NUMBERS:
            full = _fit_line(task, stage, numbers, 1_000)
            for width in range(20, 121):
                line = _fit_line(task, stage, numbers, width)
                assert split_words(task, stage, numbers, line) == [], (width, line)
                floor = len(f"{task.split()[0]}…: {', '.join(numbers)}")
                assert len(line) <= max(width, floor), (width, line)  # longer only where the numbers need it
                cut += line != full
    assert cut > 100  # the widths do cut these lines


def test_the_check_sees_a_split_word() -> None:
    """The lines the cutter used to write: the end of ``circuit`` after the ``…``, and ``simulati…``."""
    task, stage, numbers = "compile 3x4, 1 robot(s), p=1", "routing the whole circuit", ["31 s elapsed"]
    assert split_words(task, stage, numbers, "compile…: … rcuit, 31 s elapsed") == ["rcuit"]
    assert split_words(task, "simulating the feasible subspace", numbers, "compile…: the feasi… subspace") == [
        "feasi…"
    ]


def test_cuts_fall_between_words() -> None:
    assert _fit_line("compile 3x4, 1 robot(s), p=1", "routing the whole circuit", ["31 s elapsed"], 37) == (
        "compile…: routing the…, 31 s elapsed"
    )
    assert _cut_middle("simulating the feasible subspace", 20) == "… subspace"
    assert _cut_middle("routing the whole circuit", 12) == "routing the…"
    assert _cut_end("compile 3x4, 1 robot(s), p=1", 16) == "compile 3x4, 1…"


def test_a_long_word_is_cut_inside_with_the_ellipsis_at_once() -> None:
    """No boundary within reach: the word is cut where the room ends (dropping back to ``compile`` would hide the
    file the task names)."""
    task = "compile examples/a_really_long_scenario_file_name_without_spaces.toml, device ibm_fez"
    assert _cut_end(task, 40) == "compile examples/a_really_long_scenario…"
    assert _cut_end(task, 80) == "compile examples/a_really_long_scenario_file_name_without_spaces.toml, device…"
