"""Odd numbers and odd files on every command: weights out of the solvers' exact range, deeply nested JSON/TOML,
duplicate keys and bindings, FIFOs as scenarios -- each one line ``error: ...`` naming the culprit, exit 2."""

from __future__ import annotations

import json
import os
import threading
from pathlib import Path

import pytest

import qcpp.io.inputs
from qcpp.problem.scenario_io import MAX_NESTING

from .clirun import assert_one_line_error, run

REPO = Path(__file__).resolve().parents[2]
EXAMPLE = REPO / "examples" / "paper_3x3.toml"
TWO_ROBOTS = """[grid]
rows = 3
cols = 3
obstacles = [[1, 1]]
[[robots]]
start = [0, 0]
goal = [2, 2]
[[robots]]
start = [0, 2]
goal = [2, 0]
[objective]
"""

# every command that reads a scenario, with the options that make it quick
COMMANDS = [
    ["solve", "-m", "dfs"],
    ["solve", "-m", "cpsat"],
    ["solve", "-m", "anneal"],
    ["solve", "-m", "genetic"],
    ["solve", "-m", "qaoa", "--maxiter", "2"],
    ["simulate"],
    ["compile"],
    ["estimate", "--scenario"],
    ["validate"],
]

# (objective line, field named) -- every numeric field, too large or too small
ODD_NUMBERS = [
    ("edge_length = 1e9", "objective.edge_length"),
    ("edge_length = 1e200", "objective.edge_length"),
    ("edge_length = 1e-200", "objective.edge_length"),
    ("alpha = [1e308, 1.0, 1.0]", "objective.alpha[0]"),
    ("alpha = [1.0, -1e300, 1.0]", "objective.alpha[1]"),
    ("alpha = [1.0, 1.0, 1e17]", "objective.alpha[2]"),
    ("obstacle_weight = 1e200", "objective.obstacle_weight"),
    ("free_weight = -1e17", "objective.free_weight"),
    ("free_weight = 1e-9", "objective.free_weight"),
    ("edge_lengths = [[[0, 0], [0, 1], 1e154]]", "objective.edge_lengths[0]"),
]


def _args(command: list[str], path: Path) -> list[str]:
    if command[0] == "estimate":
        return [*command, str(path)]
    return [command[0], str(path), *command[1:]]


@pytest.mark.parametrize("line, field", ODD_NUMBERS)
def test_weights_outside_the_exact_range_are_one_line_everywhere(tmp_path: Path, line: str, field: str) -> None:
    path = tmp_path / "odd.toml"
    path.write_text(TWO_ROBOTS + line + "\n")
    for command in COMMANDS:
        res = run(*_args(command, path))
        assert_one_line_error(res, f"odd.toml: {field}:")
        assert "Warning" not in res.stderr
        assert ("<=" in res.stderr) or ("at least" in res.stderr)


def test_the_same_field_in_json(tmp_path: Path) -> None:
    path = tmp_path / "odd.json"
    path.write_text(json.dumps({
        "grid": {"rows": 3, "cols": 3},
        "robots": [{"start": [0, 0], "goal": [2, 2]}, {"start": [0, 2], "goal": [2, 0]}],
        "objective": {"edge_length": 1e9},
    }))
    assert_one_line_error(run("solve", str(path), "-m", "cpsat"), "objective.edge_length", "1.18e+07")


@pytest.mark.parametrize("text, suffix", [
    ("[" * 100_000 + "]" * 100_000, ".json"),
    ('{"a": ' * 5000 + "1" + "}" * 5000, ".json"),
    ("a = " + "[" * 100_000 + "]" * 100_000, ".toml"),
    ("a = " + "{b = " * 3000 + "1" + "}" * 3000, ".toml"),
    ("[" * (MAX_NESTING + 1) + "]" * (MAX_NESTING + 1), ".json"),
])
def test_deep_nesting_is_one_line(tmp_path: Path, text: str, suffix: str) -> None:
    path = tmp_path / f"deep{suffix}"
    path.write_text(text)
    assert_one_line_error(run("solve", str(path)), "deep", "nested", str(MAX_NESTING))


def test_brackets_inside_strings_do_not_count(tmp_path: Path) -> None:
    path = tmp_path / "s.json"
    path.write_text(json.dumps({"name": "[" * 1000 + '"{', "grid": {"rows": 2, "cols": 2},
                                "robots": [{"start": [0, 0], "goal": [1, 1]}]}))
    assert run("solve", str(path), "-m", "dfs").exit_code == 0
    toml = tmp_path / "s.toml"
    toml.write_text('name = "' + "[" * 1000 + "\" # [[[[\n[grid]\nrows = 2\ncols = 2\n[[robots]]\n"
                    "start = [0, 0]\ngoal = [1, 1]\n")
    assert run("solve", str(toml), "-m", "dfs").exit_code == 0


@pytest.mark.parametrize("text, key", [
    ('{"grid": {"rows": 3, "rows": 4, "cols": 3}, "robots": [{"start": [0, 0], "goal": [2, 2]}]}', '"rows"'),
    ('{"grid": {"rows": 3, "cols": 3}, "robots": [{"start": [0, 0], "goal": [2, 2], "goal": [1, 1]}]}', '"goal"'),
    ('{"grid": {"rows": 3, "cols": 3}, "grid": {"rows": 2, "cols": 2}, "robots": []}', '"grid"'),
])
def test_duplicate_json_keys_are_refused_by_name(tmp_path: Path, text: str, key: str) -> None:
    path = tmp_path / "dup.json"
    path.write_text(text)
    assert_one_line_error(run("solve", str(path)), "dup.json", key, "twice")


@pytest.mark.parametrize("text, fragment", [
    ("[grid]\nrows = 3\ncols = 3\nrows = 4\n", "rows in [grid]"),
    ("[grid]\nrows = 3\n[grid]\ncols = 3\n", "[grid]"),
    ("[grid]\nrows = 3\ncols = 3\n[[robots]]\nstart = [0, 0]\nstart = [1, 1]\n", "start in [[robots]]"),
    ("[objective]\nalpha = [1, 1, 1]\n  alpha = [2, 2, 2]", "alpha in [objective]"),
    ('[grid]\nrows = 3\n"rows" = 4', "twice"),
])
def test_duplicate_toml_keys_are_refused_by_name(tmp_path: Path, text: str, fragment: str) -> None:
    path = tmp_path / "dup.toml"
    path.write_text(text)
    assert_one_line_error(run("solve", str(path)), "dup.toml", fragment)


@pytest.mark.parametrize("binds", [
    ["--bind", "gamma_0=0.1", "gamma_0=0.2"],
    ["--bind", "gamma_0=0.1", "--bind", "gamma_0=0.1"],
    ["--bind", "beta_0=0.1,gamma_0=1, beta_0 = 2"],
])
def test_duplicate_bindings_are_refused_by_name(binds: list[str]) -> None:
    name = "beta_0" if "beta_0 = 2" in binds[-1] else "gamma_0"
    assert_one_line_error(run("compile", str(EXAMPLE), *binds), "--bind", name, "twice")


@pytest.fixture
def quick_input_wait(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(qcpp.io.inputs, "INPUT_WAIT", 0.2)


@pytest.mark.parametrize("command", [["solve"], ["compile"], ["estimate", "--scenario"], ["simulate"]])
def test_a_fifo_nobody_writes_is_refused_in_time(tmp_path: Path, quick_input_wait: None, command: list[str]) -> None:
    fifo = tmp_path / "s.toml"
    os.mkfifo(fifo)
    assert_one_line_error(run(*_args(command, fifo)), "s.toml", "FIFO")


def test_a_fifo_with_a_writer_is_read(tmp_path: Path) -> None:
    fifo = tmp_path / "s.toml"
    os.mkfifo(fifo)

    def write() -> None:
        with open(fifo, "w") as f:  # blocks until the command opens the FIFO for reading
            f.write(EXAMPLE.read_text())

    writer = threading.Thread(target=write, daemon=True)
    writer.start()
    res = run("solve", str(fifo), "-m", "dfs", "--json")
    writer.join(5)
    assert res.exit_code == 0, res.output
    direct = run("solve", str(EXAMPLE), "-m", "dfs", "--json")
    assert json.loads(res.stdout)["cost"] == json.loads(direct.stdout)["cost"]


def test_a_writer_that_stalls_is_refused(tmp_path: Path, quick_input_wait: None) -> None:
    fifo = tmp_path / "s.toml"
    os.mkfifo(fifo)
    done = threading.Event()

    def write() -> None:
        with open(fifo, "w") as f:
            f.write("[grid]\n")
            f.flush()
            done.wait(10)  # keeps the FIFO open without writing more

    writer = threading.Thread(target=write, daemon=True)
    writer.start()
    try:
        assert_one_line_error(run("solve", str(fifo)), "s.toml", "no more data")
    finally:
        done.set()
        writer.join(5)


def test_special_files_without_a_scenario_suffix_are_read_boundedly(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """A FIFO or device without a suffix is read (its format told from the content), never waited on for ever nor
    read without end: a FIFO nobody writes to gives up after the input wait, /dev/zero at 16 MiB."""
    monkeypatch.setattr(qcpp.io.inputs, "INPUT_WAIT", 0.2)
    fifo = tmp_path / "fifo"
    os.mkfifo(fifo)
    assert_one_line_error(run("solve", str(fifo)), "fifo", "no process wrote to the FIFO")
    assert_one_line_error(run("solve", "/dev/zero"), "/dev/zero", "16 MiB")
    (tmp_path / "plain").write_text("[grid]\nrows = 2\ncols = 2\n")  # a regular file: the suffix decides
    assert_one_line_error(run("solve", str(tmp_path / "plain")), "plain", "unknown file type")


def test_other_special_files_as_scenarios(tmp_path: Path) -> None:
    """A socket cannot be opened, a folder is no file, /dev/zero behind a .json name is refused at 16 MiB; each
    one line naming the file."""
    import socket

    sock_path = tmp_path / "s.toml"
    server = socket.socket(socket.AF_UNIX)
    try:
        server.bind(str(sock_path))
        assert_one_line_error(run("solve", str(sock_path)), "s.toml", "socket")
    finally:
        server.close()
    (tmp_path / "zero.json").symlink_to("/dev/zero")
    assert_one_line_error(run("solve", str(tmp_path / "zero.json")), "zero.json", "16 MiB")
    (tmp_path / "dir.toml").mkdir()
    assert_one_line_error(run("estimate", "--scenario", str(tmp_path / "dir.toml")), "dir.toml", "cannot read")


def test_simulating_commands_take_the_narrower_phase_range(tmp_path: Path) -> None:
    """edge_length 1e4 (cost bound 6.4e9): the classical solvers and estimate take it; QAOA, simulate and validate
    refuse it (their phases would carry 4e-8 of float error: benchmarks/cost_range.py, validate fails); at the
    largest value the refusal allows, validate passes."""
    from qcpp.problem.cost_range import PHASE_COST_LIMIT, largest_allowed
    from qcpp.problem.scenario_io import load_scenario

    path = tmp_path / "long.toml"
    path.write_text(TWO_ROBOTS + "edge_length = 1e4\n")
    assert run("solve", str(path), "-m", "dfs").exit_code == 0
    assert run("estimate", "--scenario", str(path)).exit_code == 0
    for args in (["solve", str(path), "-m", "qaoa"], ["simulate", str(path)], ["validate", str(path)]):
        assert_one_line_error(run(*args), "objective.edge_length", "phases", "1.02e+03")
    most = largest_allowed(load_scenario(path), "objective.edge_length", PHASE_COST_LIMIT)
    edge = tmp_path / "edge.toml"
    edge.write_text(TWO_ROBOTS + f"edge_length = {float(f'{most:.2e}'):.2e}\n")
    res = run("validate", str(edge), "--backend", "sparse", "--json")
    assert res.exit_code == 0, res.output
    assert json.loads(res.stdout)["passed"] is True
