"""Long commands predict their cost, then refuse in one line or show progress on stderr (``qcpp.cli.progress``).

No test here depends on timing: progress is asked for with ``QCPP_PROGRESS=lines`` and
``QCPP_PROGRESS_INTERVAL=0`` (a line at every step and stage, from the start, no clock), and the one test of the
heartbeat thread waits for the line it expects (with a generous upper bound for a hung thread).
"""

from __future__ import annotations

import io
import json
import re
import threading
from pathlib import Path

import pytest
from typer.testing import CliRunner

import qcpp.cli.commands.compile as compile_cmd
from qcpp.cli.app import app
from qcpp.cli.progress import Progress
from qcpp.io.progress import FIRST_LINE_AFTER, progress_mode
from qcpp.problem.paths import count_paths, enumerate_paths
from qcpp.problem.presets import default_scenario
from qcpp.problem.scenario_io import load_scenario
from qcpp.problem.solvers import exhaustive
from qcpp.problem.solvers.exhaustive import DfsTooLargeError, dfs, dfs_paths

from .clirun import assert_one_line_error

REPO = Path(__file__).resolve().parents[2]
EXAMPLES = REPO / "examples"
LINES = {"QCPP_PROGRESS": "lines", "QCPP_PROGRESS_INTERVAL": "0"}


def invoke(*args: str, env: dict[str, str] | None = None):  # type: ignore[no-untyped-def]
    return CliRunner().invoke(app, list(args), env=env)


def write_scenario(path: Path, rows: int, cols: int, robots: list[tuple[tuple[int, int], tuple[int, int]]]) -> str:
    text = f"[grid]\nrows = {rows}\ncols = {cols}\n"
    for start, goal in robots:
        text += f"[[robots]]\nstart = [{start[0]}, {start[1]}]\ngoal = [{goal[0]}, {goal[1]}]\n"
    path.write_text(text)
    return str(path)


# ----------------------------------------------------------------------------- the helper


def test_lines_count_steps_name_stages_and_end_with_a_summary() -> None:
    out = io.StringIO()
    with Progress("job", total=3, unit="rows", stream=out, mode="lines", interval=0) as bar:
        bar.stage("warming up")
        for _ in bar.iterate(range(3)):
            pass
    lines = out.getvalue().splitlines()
    assert lines[0].startswith("job: 0 / 3 rows (0.0%)")
    assert lines[1].startswith("job: 0 / 3 rows (0.0%), warming up, ")
    assert [line.split(",")[0] for line in lines[2:5]] == [f"job: {k} / 3 rows ({100 * k / 3:.1f}%)" for k in (1, 2, 3)]
    assert lines[-1].startswith("job: 3 rows done in ")
    assert all(line.startswith("job: ") for line in lines)


def test_one_step_is_singular() -> None:
    """``1 row done``, ``1 improving solution``: not ``1 rows``."""
    out = io.StringIO()
    with Progress("job", total=1, unit="rows", stream=out, mode="lines", interval=0) as bar:
        bar.advance()
    assert out.getvalue().splitlines()[-1].startswith("job: 1 row done in ")
    out = io.StringIO()
    with Progress("cpsat", unit="improving solutions", stream=out, mode="lines", interval=0) as bar:
        bar.update(1)
    lines = out.getvalue().splitlines()
    assert lines[-2].startswith("cpsat: 1 improving solution, ") and "1 improving solution done in" in lines[-1]


def test_off_prints_nothing_and_an_error_skips_the_summary() -> None:
    out = io.StringIO()
    with Progress("job", total=2, stream=out, mode="off") as bar:
        bar.advance()
    assert out.getvalue() == ""
    out = io.StringIO()
    with pytest.raises(RuntimeError), Progress("job", stream=out, mode="lines", interval=0):
        raise RuntimeError("boom")
    assert "done" not in out.getvalue()


def test_a_long_single_step_still_gets_lines_from_the_heartbeat() -> None:
    """No advance at all (one long native call): the heartbeat thread writes the stage line by itself."""
    seen = threading.Event()

    class Stream(io.StringIO):
        def write(self, text: str) -> int:
            if "contracting" in text:
                seen.set()
            return super().write(text)

    out = Stream()
    with Progress("validate", stream=out, mode="lines", interval=0.01, first_after=0.0) as bar:
        bar.stage("contracting")
        assert seen.wait(120), "no heartbeat line"  # an upper bound for a hung thread, not an expectation
    assert "validate: contracting, " in out.getvalue()


def test_terminal_gets_a_bar_a_pipe_gets_lines_and_the_variable_decides(monkeypatch: pytest.MonkeyPatch) -> None:
    class Tty(io.StringIO):
        def isatty(self) -> bool:
            return True

    monkeypatch.setenv("QCPP_PROGRESS", "auto")
    assert progress_mode(Tty()) == "bar" and progress_mode(io.StringIO()) == "lines"
    monkeypatch.setenv("QCPP_PROGRESS", "off")
    assert progress_mode(Tty()) == "off"
    monkeypatch.setenv("QCPP_PROGRESS", "loud")
    with pytest.raises(ValueError, match="QCPP_PROGRESS"):
        progress_mode(Tty())
    assert FIRST_LINE_AFTER <= 1.0  # the first line on a pipe comes well within the 2 s a user waits


def test_the_bar_on_a_terminal_writes_to_its_stream_only() -> None:
    class Tty(io.StringIO):
        def isatty(self) -> bool:
            return True

    out = Tty()
    with Progress("job", total=4, stream=out, mode="bar") as bar:
        for _ in bar.iterate(range(4)):
            pass
    assert out.getvalue()  # something was drawn (and erased: transient)


def test_the_bar_keeps_its_counts_and_time_on_an_80_column_terminal(monkeypatch: pytest.MonkeyPatch) -> None:
    """A long task and stage are cut with an ellipsis; the count and the elapsed time stay on the line."""

    class Tty(io.StringIO):
        def isatty(self) -> bool:
            return True

    monkeypatch.setenv("COLUMNS", "80")
    out = Tty()
    with Progress("compile 3x3, 2 robot(s), p=1, --device ibm_fez", total=4, stream=out, mode="bar") as bar:
        bar.stage("routing the whole circuit on ibm_fez from 96 SabreLayout starts")
        bar.advance()
        bar._bar.refresh()  # type: ignore[union-attr]  # draw now, not at rich's next refresh
    frames = [re.sub(r"\x1b\[[0-9;?]*[a-zA-Z]", "", f) for f in out.getvalue().split("\r") if "compile" in f]
    assert frames and all("…" in f and "/4 0:00:0" in f for f in frames), frames
    assert "1/4 0:00:0" in frames[-1], frames


LONG_TASK = "compile 3x4, 1 robot(s), p=1, --device ibm_fez --layout medial --lowered"
LONG_STAGE = "3x3 r1 p1 on heavy-hex:7: choosing partial-mixer plans for the routing on heavy-hex:9 (3 / 6)"


@pytest.mark.parametrize("width", [60, 80])
def test_lines_fit_the_width_cutting_the_task_and_stage_never_the_numbers(
    width: int, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setattr(Progress, "_elapsed", lambda self: 5.0)  # the time left shows too
    out = io.StringIO()
    with Progress(LONG_TASK, total=90, unit="rows", stream=out, mode="lines", interval=0, width=width) as bar:
        bar.stage(LONG_STAGE)
        bar.update(1)
        bar.update(80)
    lines = out.getvalue().splitlines()
    assert len(lines) == 5
    assert all(len(line) <= width for line in lines), [(len(line), line) for line in lines]
    assert all(line.startswith("compile") and line != LONG_TASK for line in lines)
    assert ": 1 / 90 rows (1.1%), " in lines[2] and lines[2].endswith(", 5 s elapsed, about 7 min left")
    assert ": 80 / 90 rows (88.9%), " in lines[3] and lines[3].endswith(", 5 s elapsed, about 1 s left")
    assert lines[1].endswith(" (3 / 6), 5 s elapsed") and " … " in lines[1]  # the stage's own counts stay
    assert lines[-1].endswith(": 80 rows done in 5 s")


def test_where_only_the_numbers_fit_the_line_keeps_them_and_the_first_word(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(Progress, "_elapsed", lambda self: 30.0)
    out = io.StringIO()
    with Progress(LONG_TASK, total=1_200, unit="rows", stream=out, mode="lines", interval=0, width=30) as bar:
        bar.stage(LONG_STAGE)
        bar.update(12)
    assert out.getvalue().splitlines()[2:] == [
        "compile…: 12 / 1,200 rows (1.0%), 30 s elapsed, about 50 min left",
        "compile…: 12 rows done in 30 s",
    ]


def test_a_deadline_caps_the_time_left(monkeypatch: pytest.MonkeyPatch) -> None:
    """A solver stopping at its time limit (``qcpp solve --time-limit``): the time left is at most what remains of
    it, whatever the share of steps done promises; without one, the extrapolation."""
    monkeypatch.setattr(Progress, "_elapsed", lambda self: 30.0)

    def last(deadline: float | None) -> str:
        out = io.StringIO()
        with Progress("anneal", total=1_200, unit="steps", stream=out, mode="lines", interval=0, width=200,
                      deadline=deadline) as bar:  # fmt: skip
            bar.update(12)
        return out.getvalue().splitlines()[1]

    assert last(None).endswith("30 s elapsed, about 50 min left")
    assert last(90.0).endswith("30 s elapsed, about 60 s left")
    assert last(20.0).endswith("30 s elapsed, about 0 s left")


def test_the_bar_s_time_left_is_capped_by_the_deadline_too() -> None:
    from types import SimpleNamespace

    from rich.progress import TimeRemainingColumn

    from qcpp.io.progress import _capped_remaining

    task = SimpleNamespace(total=100, elapsed=30.0, time_remaining=3000.0)
    assert _capped_remaining(TimeRemainingColumn, 90.0).render(task).plain == "0:01:00"
    assert _capped_remaining(TimeRemainingColumn, None).render(task).plain == "0:50:00"


def test_lines_are_whole_where_they_fit_and_the_width_defaults_to_columns(monkeypatch: pytest.MonkeyPatch) -> None:
    out = io.StringIO()
    with Progress(LONG_TASK, stream=out, mode="lines", interval=0, width=200) as bar:
        bar.stage(LONG_STAGE)
    assert out.getvalue().splitlines()[1].startswith(f"{LONG_TASK}: {LONG_STAGE}, ")
    monkeypatch.setenv("COLUMNS", "50")
    out = io.StringIO()
    with Progress(LONG_TASK, stream=out, mode="lines", interval=0) as bar:
        bar.stage(LONG_STAGE)
    assert max(len(line) for line in out.getvalue().splitlines()) <= 50


def test_a_device_compile_on_a_pipe_fits_columns(tmp_path: Path) -> None:
    scen = write_scenario(tmp_path / "s.toml", 2, 3, [((0, 0), (1, 2))])
    res = invoke("compile", scen, "--device", "heavy-hex", "--layout", "medial", "--lowered", "--json",
                 env={**LINES, "COLUMNS": "60"})  # fmt: skip
    assert res.exit_code == 0, res.stderr
    lines = res.stderr.splitlines()
    assert len(lines) > 3 and all(len(line) <= 60 for line in lines), lines


# ----------------------------------------------------------------------------- estimate


def test_an_estimate_table_shows_progress_before_the_table() -> None:
    args = ("estimate", "--grid", "2x2..3x4", "--robots", "1..2", "--depth", "none")
    quiet = invoke(*args)
    res = invoke(*args, env=LINES)
    assert res.exit_code == 0 and quiet.exit_code == 0, res.stderr
    assert res.stdout == quiet.stdout  # progress never touches stdout
    lines = res.stderr.splitlines()
    total = int(lines[0].split(" / ")[1].split()[0])
    assert lines[0].startswith(f"estimate: 0 / {total} rows") and total == 12  # first: before any row is computed
    assert any(line.startswith(f"estimate: {total} / {total} rows") for line in lines)
    assert any(line.startswith(f"estimate: {total} / {total} rows (100.0%), rendering the table") for line in lines)
    assert lines[-1].startswith(f"estimate: {total} rows done in ")


def test_a_long_sweep_prints_its_first_line_at_once(monkeypatch: pytest.MonkeyPatch) -> None:
    """No clock: the first line of a long sweep is written when the work starts (before any row), not after 1 s."""
    import qcpp.cli.commands.estimate as estimate_cmd

    written: list[str] = []
    real = Progress.__enter__

    def enter(self: Progress) -> Progress:
        out = real(self)
        written.append(f"first_after={self._first_after}")
        return out

    monkeypatch.setattr(Progress, "__enter__", enter)
    monkeypatch.setattr(estimate_cmd, "LONG_SWEEP_ROWS", 2)
    assert invoke("estimate", "--grid", "2x2..2x3", "--depth", "none").exit_code == 0
    monkeypatch.setattr(estimate_cmd, "LONG_SWEEP_ROWS", 3)
    assert invoke("estimate", "--grid", "2x2..2x3", "--depth", "none").exit_code == 0
    assert written == ["first_after=0.0", f"first_after={FIRST_LINE_AFTER}"]


def test_streamed_rows_to_a_pipe_get_progress_too() -> None:
    res = invoke("estimate", "--grid", "2x2..2x3", "--format", "csv", "--depth", "none", env=LINES)
    assert res.exit_code == 0 and len(res.stdout.splitlines()) == 3
    assert res.stderr.splitlines()[0].startswith("estimate: 0 / 2 rows")


def test_cpsat_counts_its_improving_solutions_without_a_total() -> None:
    """CP-SAT cannot know how many improving solutions it will find: the lines count them, never ``n / 0``."""
    res = invoke("solve", "--grid", "4x4", "--robots", "2", "--method", "cpsat", env=LINES)
    assert res.exit_code == 0
    counted = [line for line in res.stderr.splitlines() if "improving solutions" in line]
    assert counted and all("/" not in line for line in res.stderr.splitlines())
    assert counted[-1].startswith("cpsat on ") and " improving solutions done in " in counted[-1]


# ----------------------------------------------------------------------------- compile


@pytest.mark.parametrize("lowered", [False, True])
def test_a_big_compile_is_built_in_sections_with_progress_and_the_same_summary(
    monkeypatch: pytest.MonkeyPatch, lowered: bool
) -> None:
    args = ["compile", str(EXAMPLES / "two_robots_4x4.toml"), "--json", "-p", "2", *(["--lowered"] if lowered else [])]
    whole = json.loads(invoke(*args).stdout)
    monkeypatch.setattr(compile_cmd, "STREAM_ABOVE_GATES", 0)  # as if it were a 40x40 / 8 robot circuit
    res = invoke(*args, env=LINES)
    assert res.exit_code == 0, res.stderr
    streamed = json.loads(res.stdout)
    whole.pop("seconds"), streamed.pop("seconds")
    assert streamed == whole
    lines = res.stderr.splitlines()
    assert lines[0].startswith("compile 4x4, 2 robot(s), p=2: 0")  # at once: a circuit this big is known to be long
    assert any("planning the circuit" in line for line in lines)
    assert lines[-1].startswith(f"compile 4x4, 2 robot(s), p=2: {whole['total_gates']:,} gates done")
    if lowered:  # the prediction is exact for the lowered circuit
        assert f" / {whole['total_gates']:,} gates" in lines[1]


def test_writing_qasm_shows_both_passes(tmp_path: Path) -> None:
    out = str(tmp_path / "c.qasm")
    res = invoke("compile", str(EXAMPLES / "paper_3x3.toml"), "--lowered", "--qasm", out, env=LINES)
    assert res.exit_code == 0, res.stderr
    assert "collecting symbols" in res.stderr and "writing OpenQASM" in res.stderr


@pytest.mark.parametrize("lowered", [False, True])
def test_writing_qasm_counts_each_gate_once_per_pass(tmp_path: Path, lowered: bool) -> None:
    """The OpenQASM writer walks the sections twice (header, then text): each pass counts from 0 to the circuit's
    gate count, so the total shown and the last count equal the summary's ``total_gates`` (lowered: predicted
    exactly; high level: the first pass's count), never twice it."""
    args = ["compile", str(EXAMPLES / "two_robots_4x4.toml"), "-p", "2", "--json", "--qasm", str(tmp_path / "c.qasm")]
    res = invoke(*args, *(["--lowered"] if lowered else []), env={**LINES, "COLUMNS": "200"})
    assert res.exit_code == 0, res.stderr
    gates = json.loads(res.stdout)["total_gates"]
    lines = res.stderr.splitlines()
    counts = [(int(m[1].replace(",", "")), m[2]) for m in (re.search(r": ([\d,]+)(?: / ([\d,]+))? gates", line)
                                                           for line in lines) if m]  # fmt: skip
    assert counts and max(done for done, _ in counts) == gates
    totals = {total for _, total in counts if total is not None}
    assert totals == {f"{gates:,}"}
    writing = [line for line in lines if "pass 2 / 2: writing OpenQASM" in line]
    assert writing[0].split(": ")[1].startswith(f"0 / {gates:,} gates")
    assert writing[-1].split(": ")[1].startswith(f"{gates:,} / {gates:,} gates (100.0%)")
    assert lines[-1].startswith(f"compile 4x4, 2 robot(s), p=2: {gates:,} gates done")


@pytest.mark.parametrize("qasm", [False, True])
def test_writing_qasm_claims_no_time_left(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, qasm: bool) -> None:
    """Writing costs per gate vary (the mixer sections write slower than the phase sections, both slower than
    collecting symbols): with ``--qasm`` the lines count gates and time but promise no time left; a streamed count
    without ``--qasm`` (uniform work) still does. The clock is fixed at 100 s, so every line could show it."""
    monkeypatch.setattr(Progress, "_elapsed", lambda self: 100.0)
    monkeypatch.setattr(compile_cmd, "STREAM_ABOVE_GATES", 0)  # streamed with or without --qasm
    args = ["--qasm", str(tmp_path / "c.qasm")] if qasm else []
    res = invoke("compile", str(EXAMPLES / "paper_3x3.toml"), "--lowered", *args, env=LINES)
    assert res.exit_code == 0, res.stderr
    counted = [line for line in res.stderr.splitlines() if " gates (" in line and "(0.0%)" not in line]
    assert counted and all("100 s elapsed" in line for line in counted)
    assert all(("left" in line) != qasm for line in counted if "(100.0%)" not in line)


def test_a_device_compile_names_its_stages(tmp_path: Path) -> None:
    """``compile --device heavy-hex`` (the cells' plan choice can take a while): stages on stderr, stdout unchanged."""
    scen = write_scenario(tmp_path / "s.toml", 2, 3, [((0, 0), (1, 2))])
    args = ["compile", scen, "--device", "heavy-hex", "--layout", "medial", "--lowered", "--json"]
    res = invoke(*args, env={**LINES, "COLUMNS": "200"})  # wide enough that no task or stage is cut
    assert res.exit_code == 0, res.stderr
    quiet = invoke(*args, env={"QCPP_PROGRESS": "off"})
    assert res.stderr and not quiet.stderr
    first, second = json.loads(res.stdout), json.loads(quiet.stdout)
    first.pop("seconds"), second.pop("seconds")
    assert first == second
    lines = res.stderr.splitlines()
    assert all(line.startswith("compile 2x3, 1 robot(s), p=1, --device heavy-hex: ") for line in lines)
    stages = ["compiling the circuit", "choosing partial-mixer plans on the cells (0 / 2)",
              "choosing partial-mixer plans on the cells (1 / 2)", "allocating ancillas on heavy-hex:7",
              "relaying far phases", "routing "]  # fmt: skip
    found = [next(i for i, line in enumerate(lines) if stage in line) for stage in stages]
    assert found == sorted(found)
    assert lines[-1].startswith("compile 2x3, 1 robot(s), p=1, --device heavy-hex: done in ")


# ----------------------------------------------------------------------------- solve -m dfs


def test_dfs_paths_equal_the_enumeration_and_give_the_same_optimum() -> None:
    s = load_scenario(EXAMPLES / "two_robots_4x4.toml")
    lists = dfs_paths(s)
    assert lists == [enumerate_paths(s, r) for r in range(s.num_robots)]
    given, own = dfs(s, paths=lists), dfs(s)
    assert given.paths == own.paths and given.cost == own.cost and given.evaluated == own.evaluated
    assert count_paths(s, 0) == len(lists[0]) and count_paths(s, 0, cap=5) == 5


@pytest.mark.parametrize(
    ("rows", "cols", "robots"),
    [(6, 6, 3), (5, 5, 3), (7, 7, 3), (6, 6, 4)],
)
def test_hopeless_dfs_is_refused_at_once_naming_the_size_and_the_override(
    tmp_path: Path, rows: int, cols: int, robots: int
) -> None:
    s = default_scenario(rows, cols, robots)
    path = write_scenario(tmp_path / "s.toml", rows, cols, [(r.start, r.goal) for r in s.robots])
    res = invoke("solve", path, "-m", "dfs")
    assert_one_line_error(res, "paths per robot", "assignments", "GB", "over the run-time limit of 60 min",
                          "--allow-large")  # fmt: skip


def test_dfs_refuses_what_does_not_fit_in_the_memory_available_and_allow_large_lifts_it(tmp_path: Path) -> None:
    path = write_scenario(tmp_path / "s.toml", 4, 4, [((0, 0), (3, 3))])  # 184 paths
    small = {"QCPP_MEMORY_AVAILABLE": "1M"}
    assert_one_line_error(invoke("solve", path, "-m", "dfs", env=small), "GB of memory available", "--allow-large")
    res = invoke("solve", path, "-m", "dfs", "--allow-large", "--json", env=small)
    assert res.exit_code == 0 and json.loads(res.stdout)["evaluated"] == 184
    res = invoke("solve", path, "-m", "dfs", "--json")  # the machine's memory: a small search runs
    assert res.exit_code == 0 and json.loads(res.stdout)["evaluated"] == 184


def test_dfs_of_two_robots_on_5x5_is_not_refused() -> None:
    """73.8 million assignments: about 0.4 GB and half a minute, so it runs without an override (the fixed
    limits it replaced refused 2 million paths or a billion assignments, whatever the machine)."""
    s = load_scenario(EXAMPLES / "two_robots_5x5.toml")
    counts = [count_paths(s, r) for r in range(s.num_robots)]
    size = exhaustive.DfsSize(tuple(counts), (True, True), s.edges_per_robot, s.grid.num_nodes)
    assert size.bytes < 10**9 and size.seconds < 600
    lists = dfs_paths(s, max_assignments=None, max_paths=None, max_bytes=24 * 10**9, max_seconds=3600.0)
    assert [len(pl) for pl in lists] == counts


def test_dfs_size_is_a_lower_bound_until_counted() -> None:
    with pytest.raises(DfsTooLargeError) as err:
        dfs_paths(default_scenario(6, 6, 2), max_assignments=10**6)
    size = err.value.size
    assert not size.exact and size.assignments > 10**6
    assert "at least" in str(err.value) and "\n" not in str(err.value)


# ----------------------------------------------------------------------------- validate


def test_validate_picks_a_backend_that_fits() -> None:
    small = invoke("validate", str(EXAMPLES / "paper_3x3.toml"), "--json")
    assert small.exit_code == 0, small.stderr
    assert json.loads(small.stdout)["backend"] == "statevector"
    big = invoke("validate", str(EXAMPLES / "two_robots_4x4.toml"), env=LINES)
    assert big.exit_code == 0, big.stderr
    assert "backend=sparse" in big.stdout and "PASSED" in big.stdout
    stages = [line for line in big.stderr.splitlines() if line.startswith("validate two_robots_4x4.toml: ")]
    for stage in ("predicting the size", "simulating the feasible subspace", "compiling the lowered circuit",
                  "simulating the circuit (sparse)"):  # fmt: skip
        assert any(stage in line for line in stages), stage
    assert "backend=sparse (auto), 80 qubits" in " ".join(big.stdout.split())  # the choice is in the title


def test_validate_refuses_a_reference_state_that_does_not_fit() -> None:
    res = invoke("validate", str(EXAMPLES / "two_robots_5x5.toml"), env={"QCPP_MEMORY_AVAILABLE": "24G"})
    assert_one_line_error(res, "two_robots_5x5.toml", "73,788,100 feasible assignments", "predicted peak",
                          "over the 24.0 GB available", "--allow-large")  # fmt: skip
    res = invoke("validate", str(EXAMPLES / "two_robots_5x5.toml"), env={"QCPP_MEMORY_AVAILABLE": "1000"})
    assert_one_line_error(res, "two_robots_5x5.toml", "validating at least 1,048,576 feasible assignments",
                          "paths counted: 1,024 x 1,024", "over the 0.0 GB available", "--allow-large")  # fmt: skip


def test_simulate_refuses_only_what_does_not_fit_or_runs_for_hours() -> None:
    five = str(EXAMPLES / "two_robots_5x5.toml")
    res = invoke("simulate", five, env={"QCPP_MEMORY_AVAILABLE": "2G"})  # it peaks at about 3.1 GB
    assert_one_line_error(res, "two_robots_5x5.toml", "73,788,100 feasible assignments", "predicted peak 3.1 GB",
                          "over the 2.0 GB available", "--allow-large")  # fmt: skip
    res = invoke("simulate", five, "-p", "500", env={"QCPP_MEMORY_AVAILABLE": "24G"})
    assert_one_line_error(res, "two_robots_5x5.toml", "predicted to run for about", "h (peak 3.1 GB",
                          "over the limit of 1 h", "--allow-large")  # fmt: skip
    assert invoke("simulate", str(EXAMPLES / "two_robots_4x4.toml"), "--json").exit_code == 0


def test_the_two_robot_5x5_simulation_fits_a_24_gb_machine() -> None:
    """It peaks at 3.1 GB in under a minute: the guard lets it run (the check itself, without simulating)."""
    from qcpp.problem.limits import check_need
    from qcpp.simulate.footprint import simulate_need

    need = simulate_need(load_scenario(EXAMPLES / "two_robots_5x5.toml"), 1)
    assert 2.5e9 < need.bytes < 4e9 and need.seconds is not None and need.seconds < 600
    check_need(need, available=24 * 10**9)


def test_a_new_stage_is_written_at_once_on_a_pipe_past_the_first_line_delay(monkeypatch: pytest.MonkeyPatch) -> None:
    """A native call that holds the GIL (QCEC) starves the heartbeat thread: its stage is announced on entry."""
    monkeypatch.setattr(Progress, "_heartbeat", lambda self: None)  # only the stage's own line, no race with it
    out = io.StringIO()
    with Progress("validate x", stream=out, mode="lines", interval=600.0, first_after=0.0) as bar:
        bar.stage("proving equivalence")
        bar.stage("proving equivalence")  # the same stage again: no second line
        written = out.getvalue()
        quiet = io.StringIO()
        with Progress("quick", stream=quiet, mode="lines", interval=600.0, first_after=600.0) as fast:
            fast.stage("compiling")  # before the first-line delay: quick commands stay silent
        assert quiet.getvalue() == ""
    assert written.count("\n") == 1 and written.startswith("validate x: proving equivalence, ")


def test_stages_that_change_quickly_write_at_most_one_line_per_interval(monkeypatch: pytest.MonkeyPatch) -> None:
    """A device estimate changes its stage many times a second: a log gets one line for them, not one each."""
    monkeypatch.setattr(Progress, "_heartbeat", lambda self: None)
    out = io.StringIO()
    with Progress("estimate", stream=out, mode="lines", interval=600.0, first_after=0.0) as bar:
        for k in range(50):
            bar.stage(f"routing window {k} / 50")
        written = out.getvalue()
    assert written.count("\n") == 1 and written.startswith("estimate: routing window 0 / 50, ")


def test_a_late_heartbeat_writes_nothing_after_the_work_ended(monkeypatch: pytest.MonkeyPatch) -> None:
    """The heartbeat passed its check, then the machine did not run it before ``__exit__`` gave up waiting
    (seen once under load: a progress line after ``interrupted``): its line is dropped, not printed last."""
    from qcpp.io import progress as progress_module

    monkeypatch.setattr(progress_module, "HEARTBEAT_JOIN_SECONDS", 0.01)
    stream = io.StringIO()
    bar = progress_module.Progress("work", mode="lines", interval=0.01, first_after=0.0, stream=stream)
    entered, release = threading.Event(), threading.Event()
    status = bar.status

    def held_status() -> str:
        entered.set()
        release.wait(30)
        return status()

    monkeypatch.setattr(bar, "status", held_status)
    bar.__enter__()
    assert entered.wait(30)
    bar.__exit__(KeyboardInterrupt, KeyboardInterrupt(), None)
    stream.write("interrupted\n")
    release.set()
    assert bar._thread is not None
    bar._thread.join(30)
    assert stream.getvalue().splitlines()[-1] == "interrupted", stream.getvalue()


def test_the_stage_says_when_numba_compiles() -> None:
    """The first run after installing spends up to a minute compiling numba kernels; the progress says so while
    it does (numba's ``numba:compile`` events, which fire only for a kernel not in numba's cache)."""
    import numba

    from qcpp.io.progress import COMPILING

    out = io.StringIO()
    with Progress("validate", stream=out, mode="lines", interval=0) as bar:
        bar.stage("simulating the circuit (tensor)")
        assert numba.njit(lambda x: x + 1)(1) == 2  # a new function: compiled now, never cached
        bar.stage("checking")
    lines = out.getvalue().splitlines()
    compiling = [i for i, line in enumerate(lines) if COMPILING in line]
    assert compiling, lines
    assert "simulating the circuit (tensor)" in lines[compiling[0] - 1]
    assert COMPILING not in lines[-2] and "checking" in lines[-2]
    from numba.core import event

    assert not any(type(listener).__name__ == "_Compiles" for listener in event._registered["numba:compile"])


def test_a_stage_announced_between_heartbeats_is_not_written_again_by_the_next_one(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """The last row's stage (``rendering the table``) is announced at once; the heartbeat, due a moment later on
    its own schedule, must wait an interval from that line, not write it again. Run on a scripted clock: the
    heartbeat's waits advance it, so no timing is involved."""
    from qcpp.io import progress as progress_module

    now = [1000.0]
    monkeypatch.setattr(progress_module, "time", type("Clock", (), {"monotonic": staticmethod(lambda: now[0])}))
    out = io.StringIO()
    bar = progress_module.Progress("estimate", total=12, unit="rows", stream=out, mode="lines", interval=5.0,
                                   first_after=1.0)  # fmt: skip
    bar._start = now[0]
    waits: list[float] = []

    class Stop:
        """The heartbeat's stop event: each wait moves the clock; during the second, the last row ends."""

        def wait(self, timeout: float) -> bool:
            waits.append(timeout)
            if len(waits) == 2:
                now[0] += timeout
                bar.update(12)
                bar.stage("rendering the table")  # announced: no line for an interval
                now[0] += 0.1  # the heartbeat wakes a moment later
                return False
            now[0] += timeout
            return len(waits) >= 3  # the work ends during the third wait

        def is_set(self) -> bool:
            return len(waits) >= 3

    bar._stop = Stop()  # type: ignore[assignment]
    bar._heartbeat()
    lines = out.getvalue().splitlines()
    assert sum("rendering the table" in line for line in lines) == 1, lines
    assert len(lines) == 2 and lines[0].startswith("estimate: 0 / 12 rows"), lines
