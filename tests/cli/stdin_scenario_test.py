"""A scenario from standard input (``-``) or from a pipe without a suffix (``/dev/stdin``, the ``/dev/fd/N`` of a
shell's ``<(...)``): read by the one loader the CLI and ``qcpp.load_scenario`` share, TOML or JSON told from the
content, and the same one-line errors as a file.

Each case runs ``qcpp`` (or Python) in a fresh process with the input piped in, as a shell pipeline does.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import time
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
EXAMPLE = REPO / "examples" / "paper_3x3.toml"
HUNG = 120.0
"""Seconds after which a process counts as hung (an upper bound, never a wait)."""


def qcpp(*args: str, stdin: bytes | None = None, **kwargs: object) -> subprocess.CompletedProcess[bytes]:
    return subprocess.run(
        [sys.executable, "-m", "qcpp", *args],
        input=stdin,
        cwd=REPO,
        env={**os.environ, "PYTHONPATH": str(REPO / "src")},
        capture_output=True,
        timeout=HUNG,
        check=False,
        **kwargs,  # type: ignore[arg-type]
    )


def solved_cost(res: subprocess.CompletedProcess[bytes]) -> float:
    assert res.returncode == 0, res.stderr.decode()
    return float(json.loads(res.stdout)["cost"])


def one_line_error(res: subprocess.CompletedProcess[bytes], *fragments: str) -> None:
    err = res.stderr.decode()
    assert res.returncode == 2 and res.stdout == b"", err
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: "), err
    for f in fragments:
        assert f in lines[0], err


@pytest.fixture(scope="module")
def expected() -> float:
    return solved_cost(qcpp("solve", str(EXAMPLE), "-m", "dfs", "--json"))


@pytest.mark.parametrize("name", ["-", "/dev/stdin"])
@pytest.mark.parametrize("form", ["toml", "json"])
def test_a_piped_scenario_is_read_in_either_format(name: str, form: str, expected: float) -> None:
    from qcpp.problem.scenario import scenario_to_dict
    from qcpp.problem.scenario_io import load_scenario

    text = EXAMPLE.read_bytes() if form == "toml" else json.dumps(scenario_to_dict(load_scenario(EXAMPLE))).encode()
    assert solved_cost(qcpp("solve", name, "-m", "dfs", "--json", stdin=text)) == expected


def test_a_pipeline_of_two_commands() -> None:
    """``qcpp scenario ... | qcpp solve -``: the inline scenario's optimum, through the pipe."""
    made = qcpp("scenario", "--grid", "3x3", "--robots", "2")
    assert made.returncode == 0
    direct = solved_cost(qcpp("solve", "--grid", "3x3", "--robots", "2", "-m", "dfs", "--json"))
    assert solved_cost(qcpp("solve", "-", "-m", "dfs", "--json", stdin=made.stdout)) == direct


def test_process_substitution_is_a_pipe_without_a_suffix(expected: float) -> None:
    """``qcpp solve <(cat field.toml)``: a ``/dev/fd/N`` pipe, passed to the child as the shell passes it."""
    read, write = os.pipe()
    os.write(write, EXAMPLE.read_bytes())
    os.close(write)
    try:
        res = qcpp("solve", f"/dev/fd/{read}", "-m", "dfs", "--json", pass_fds=(read,))
    finally:
        os.close(read)
    assert solved_cost(res) == expected


@pytest.mark.parametrize(
    ("stdin", "fragments"),
    [
        (b"", ("standard input", "empty")),
        (b"  \n", ("standard input", "empty")),
        (b"[grid]\nrows = \n", ("standard input", "not valid TOML")),
        (b'{"grid": {"rows": 3', ("standard input", "not valid JSON")),
        (b'{"grid": {"rows": 3, "cols": 3}, "robots": []}', ("standard input", "robots")),
        (b"\xff\xfe[grid]", ("standard input", "not valid UTF-8")),
    ],
)
def test_bad_standard_input_is_one_line(stdin: bytes, fragments: tuple[str, ...]) -> None:
    one_line_error(qcpp("solve", "-", "-m", "dfs", stdin=stdin), *fragments)


def test_a_terminal_is_refused_at_once() -> None:
    """Nothing piped in (standard input a terminal): one line saying so, not a wait for typed input."""
    import pty

    leader, follower = pty.openpty()
    try:
        res = subprocess.run([sys.executable, "-m", "qcpp", "solve", "-", "-m", "dfs"], stdin=follower, cwd=REPO,
                             env={**os.environ, "PYTHONPATH": str(REPO / "src")}, capture_output=True, timeout=HUNG,
                             check=False)  # fmt: skip
    finally:
        os.close(follower)
        os.close(leader)
    one_line_error(res, "standard input", "terminal")


def test_the_api_reads_standard_input_too(expected: float) -> None:
    code = "import qcpp; s = qcpp.load_scenario('-'); print(qcpp.solve(s, 'dfs').cost.total)"
    res = subprocess.run([sys.executable, "-c", code], input=EXAMPLE.read_bytes(), capture_output=True,
                         env={**os.environ, "PYTHONPATH": str(REPO / "src")}, timeout=HUNG, check=False)  # fmt: skip
    assert res.returncode == 0, res.stderr.decode()
    assert float(res.stdout) == expected


_SLOW_READER = """
import sys
import qcpp.io.inputs
qcpp.io.inputs.INPUT_WAIT = 0.05  # a named FIFO nobody writes to is given up on after this
import qcpp
print("reading", file=sys.stderr, flush=True)
print(qcpp.load_scenario(sys.argv[1]).grid.rows)
"""


@pytest.mark.parametrize("name", ["-", "/dev/stdin", "fd"])
def test_a_slow_writer_in_a_pipeline_is_waited_for(name: str) -> None:
    """``slow-producer | qcpp solve -`` (or ``/dev/stdin``, or a ``<(...)`` descriptor): the pipe's writer exists
    from the start, so its data is waited for as long as it takes, as ``cat`` waits; the time limit is for a named
    FIFO nobody may ever open. The writer here starts writing well after the reader's limit."""
    read, write = os.pipe()
    if name == "fd":
        args, stdin, fds, name = [f"/dev/fd/{read}"], subprocess.DEVNULL, (read,), f"/dev/fd/{read}"
    else:
        args, stdin, fds = [name], read, ()
    proc = subprocess.Popen([sys.executable, "-c", _SLOW_READER, *args], stdin=stdin, pass_fds=fds,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, cwd=REPO,
                            env={**os.environ, "PYTHONPATH": str(REPO / "src")})  # fmt: skip
    os.close(read)
    try:
        assert proc.stderr is not None and proc.stderr.readline() == b"reading\n"
        time.sleep(0.5)  # ten times the reader's limit: the writer is slow, not gone
        os.write(write, EXAMPLE.read_bytes())
        os.close(write)
        write = -1
        out, err = proc.communicate(timeout=HUNG)
    finally:
        if write >= 0:
            os.close(write)
        proc.kill()
        proc.wait()
    assert proc.returncode == 0 and out == b"3\n", err.decode()
