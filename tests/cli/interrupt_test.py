"""Ctrl-C and SIGTERM on a real ``qcpp`` process: ``interrupted``, exit 130, and only whole rows printed.

``qcpp estimate`` streams rows as it computes them (no process pool, no cache: estimates come from the gadgets'
costs): the signal arrives after some rows are out and more are being computed; the process must stop at once,
leave every printed row whole and say ``interrupted``.

No test here depends on timing: a signal is sent only once the process said it is under way (rows on stdout,
or the ``ready: ...`` line that ``QCPP_READY=1`` turns on, printed once the signal handling is installed and the
work has started), never after a sleep. Time limits are generous upper bounds for a hung process, not
expectations; the outputs are parsed without assuming they hold anything.
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
from collections.abc import Callable
from pathlib import Path

import pytest

from qcpp.cli import interrupt

REPO = Path(__file__).resolve().parents[2]
SWEEP = ["estimate", "--grid", "2x2..40x40", "--robots", "1..8", "-p", "1..5", "--depth", "none"]
HUNG = 120.0
"""Seconds after which a process that should have stopped counts as hung (an upper bound, never a wait)."""


def start(args: list[str], env: dict[str, str] | None = None) -> subprocess.Popen[str]:
    return subprocess.Popen(
        [sys.executable, "-m", "qcpp", *args],
        cwd=REPO,
        env={**os.environ, "PYTHONPATH": str(REPO / "src"), interrupt.READY_ENV: "1", **(env or {})},
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )


def run_script(script: str) -> subprocess.CompletedProcess[str]:
    """Run ``python -c script`` against this checkout's ``src`` and wait for it (at most :data:`HUNG` seconds)."""
    return subprocess.run(
        [sys.executable, "-c", script],
        cwd=REPO,
        env={**os.environ, "PYTHONPATH": str(REPO / "src")},
        capture_output=True,
        text=True,
        timeout=HUNG,
        check=False,
    )


def read_until(stream: object, enough: Callable[[str], bool]) -> str:
    """Read a pipe's descriptor directly until ``enough(text so far)`` or its end; return all the text read.

    Not through the pipe's file object: its buffer would keep what it read past the point asked for, and
    ``communicate`` (which :func:`stop` uses) reads the descriptor, so those bytes would be lost to both.
    """
    fd = stream.fileno()  # type: ignore[attr-defined]
    data = b""
    while not enough(data.decode(errors="replace")):
        chunk = os.read(fd, 65536)
        if not chunk:
            break
        data += chunk
    return data.decode()


def wait_until_ready(proc: subprocess.Popen[str]) -> list[str]:
    """Read stderr until the CLI's ``ready: ...`` line (its work has started); return the lines read."""
    assert proc.stderr is not None
    seen = read_until(proc.stderr, lambda text: any(line.startswith("ready: ") for line in text.splitlines()))
    if any(line.startswith("ready: ") for line in seen.splitlines()):
        return seen.splitlines(keepends=True)
    proc.wait()
    pytest.fail(f"the process ended (exit {proc.returncode}) without saying it was ready: {seen!r}")


def stop(proc: subprocess.Popen[str], sig: signal.Signals, err_before: str = "") -> str:
    """Send ``sig``; the process must stop with exit 130, a last stderr line ``interrupted`` and no traceback.

    Returns:
        What it printed on stdout after the signal.
    """
    proc.send_signal(sig)
    try:
        out, err = proc.communicate(timeout=HUNG)
    except subprocess.TimeoutExpired:
        proc.kill()
        proc.communicate()
        pytest.fail("the process did not stop after the signal")
    err = err_before + err
    assert proc.returncode == 130, err
    lines = err.strip().splitlines()
    assert lines and lines[-1] == "interrupted", err
    assert "Traceback" not in err and err.count("interrupted") == 1, err
    return out


@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM])
def test_signal_stops_a_streaming_sweep_with_whole_rows(sig: signal.Signals) -> None:
    proc = start([*SWEEP, "--format", "jsonl"])
    assert proc.stdout is not None
    read = read_until(proc.stdout, lambda text: text.count("\n") >= 20)  # rows are out: the sweep is under way
    first = read.splitlines(keepends=True)[:20]
    assert len(first) == 20 and all(line.endswith("\n") for line in first), f"the sweep ended early: {first}"
    out = stop(proc, sig)
    lines = [line for line in (read + out).splitlines() if line]
    rows = [json.loads(line) for line in lines]  # every printed row is whole
    assert 20 <= len(rows) < 60_000


@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM])
def test_interrupting_a_single_process_command(sig: signal.Signals) -> None:
    """The main thread is interrupted mid-computation (a table waits for every row, so stdout stays empty)."""
    proc = start(SWEEP)
    before = "".join(wait_until_ready(proc))
    out = stop(proc, sig, before)
    assert out == ""


@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM])
def test_a_signal_during_start_up_is_the_same_one_line(sig: signal.Signals) -> None:
    """``QCPP_HOLD_START`` holds the start-up right after the first handlers, before the CLI's imports: the signal
    lands there (not by timing luck) and gives ``interrupted``, exit 130, as during the work."""
    from qcpp.__main__ import HOLD_ENV

    proc = start(["estimate", "--grid", "2x2", "--depth", "none"], env={HOLD_ENV: "1"})
    assert proc.stderr is not None
    seen = read_until(proc.stderr, lambda text: "ready: start-up\n" in text)
    assert seen == "ready: start-up\n", seen
    maps = Path(f"/proc/{proc.pid}/maps")
    if maps.exists():  # held before the heavy imports: numpy's C extension is not loaded yet
        assert "_multiarray_umath" not in maps.read_text()
    out = stop(proc, sig, seen)
    assert out == ""


def test_the_start_up_hold_is_off_by_default() -> None:
    """Without the hook nothing waits: the same command runs to its end (exit 0, its table on stdout)."""
    from qcpp.__main__ import HOLD_ENV

    env = {k: v for k, v in {**os.environ, "PYTHONPATH": str(REPO / "src")}.items() if k != HOLD_ENV}
    proc = subprocess.run([sys.executable, "-m", "qcpp", "estimate", "--grid", "2x2", "--depth", "none", "--json"],
                          cwd=REPO, env=env, capture_output=True, text=True, timeout=HUNG)  # fmt: skip
    assert proc.returncode == 0 and "ready" not in proc.stderr and json.loads(proc.stdout), proc.stderr


def test_the_ready_line_is_off_by_default() -> None:
    proc = subprocess.run(
        [sys.executable, "-m", "qcpp", "estimate", "--grid", "2x2", "--depth", "none"],
        cwd=REPO,
        env={k: v for k, v in {**os.environ, "PYTHONPATH": str(REPO / "src")}.items() if k != interrupt.READY_ENV},
        capture_output=True,
        text=True,
        timeout=HUNG,
    )
    assert proc.returncode == 0 and "ready" not in proc.stderr, proc.stderr


def test_an_exception_the_signal_caused_is_reported_as_interrupted(monkeypatch: pytest.MonkeyPatch) -> None:
    """A signal inside a C extension's import surfaces as ``ImportError``: still ``interrupted``, exit 130."""
    import threading

    from typer.testing import CliRunner

    from qcpp.cli.app import QcppTyper

    app = QcppTyper()

    @app.command("broken")
    def broken() -> None:
        raise ImportError("initialization failed")

    @app.command("other")
    def other() -> None:
        """A second command, so that typer keeps the command names."""

    res = CliRunner().invoke(app, ["broken"], env={"QCPP_DEBUG": ""})
    assert res.exit_code == 1 and res.stderr.startswith("error: internal error: ImportError: ")  # no signal: a bug
    monkeypatch.setattr(interrupt, "_requested", [signal.SIGINT])
    monkeypatch.setattr(interrupt, "_reported", threading.Event())
    res = CliRunner().invoke(app, ["broken"])
    assert res.exit_code == 130 and res.stderr == "interrupted\n" and res.stdout == ""


def test_an_interrupt_while_typer_builds_the_context_is_reported(monkeypatch: pytest.MonkeyPatch) -> None:
    """typer turns a ``KeyboardInterrupt`` outside the command (its lazy imports while it parses the options) into
    a silent exit code 130; the group says ``interrupted`` then too (the trial's signal probe found exits 130 with
    no line)."""
    import threading

    import typer
    from typer.testing import CliRunner

    from qcpp.cli.app import QcppTyper

    def boom(value: bool) -> None:
        if value:
            interrupt._requested.append(signal.SIGINT)  # what the handler records before it raises
            raise KeyboardInterrupt

    app = QcppTyper()

    @app.callback()
    def top(flag: bool = typer.Option(False, "--boom", callback=boom)) -> None:
        """A group option whose parsing is interrupted."""

    @app.command("run")
    def run_() -> None:
        """A command."""

    monkeypatch.setattr(interrupt, "_requested", [])
    monkeypatch.setattr(interrupt, "_reported", threading.Event())
    res = CliRunner().invoke(app, ["--boom", "run"])
    assert res.exit_code == 130 and res.stderr == "interrupted\n" and res.stdout == ""


def test_a_deferred_stop_takes_the_first_signal_as_a_request_and_the_second_as_an_interrupt(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """Inside :func:`interrupt.deferred_stop` (as ``qcpp solve`` runs its stoppable solvers) the first signal only
    sets the block's event; a second raises as outside it, and the block puts the handlers back."""
    monkeypatch.setattr(interrupt, "_installed", True)  # as after install(), without its process-wide watchdog
    monkeypatch.setattr(interrupt, "_requested", [])
    previous = signal.getsignal(signal.SIGINT)
    with pytest.raises(KeyboardInterrupt), interrupt.deferred_stop() as stopped:
        signal.raise_signal(signal.SIGINT)
        assert stopped.is_set() and interrupt.stop_requested()
        signal.raise_signal(signal.SIGINT)
        pytest.fail("the second signal did not raise")
    assert signal.getsignal(signal.SIGINT) is previous


@pytest.mark.heavy
@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM])
@pytest.mark.parametrize("method", ["anneal", "genetic"])
def test_a_signal_during_a_long_solve_prints_the_best_so_far(method: str, sig: signal.Signals) -> None:
    """A search of far more steps than the test could wait for: the signal lands in it (or in its set-up, which then
    stops before its first step), and the answer so far comes out whole, marked, before ``interrupted``."""
    steps = ["--iterations", "1000000000"] if method == "anneal" else ["--generations", "1000000000"]
    proc = start(["solve", "--grid", "4x4", "--robots", "2", "-m", method, *steps, "--json"])
    before = "".join(wait_until_ready(proc))
    out = json.loads(stop(proc, sig, before))
    assert out["method"] == method and out["stopped"] == "interrupted"
    assert any(n.startswith("interrupted after ") for n in out["notes"]) and len(out["paths"]) == 2


@pytest.mark.heavy
def test_a_signal_during_cpsat_search_prints_its_best_so_far() -> None:
    """The signal goes once CP-SAT reported its first improving solution (a progress line at every step), so it
    lands inside the native search, which a helper thread then stops; 3 robots on 8x8 are far from proven then."""
    env = {"QCPP_PROGRESS": "lines", "QCPP_PROGRESS_INTERVAL": "0"}
    proc = start(["solve", "--grid", "8x8", "--robots", "3", "-m", "cpsat", "--json"], env)
    assert proc.stderr is not None
    seen = read_until(proc.stderr, lambda text: "improving solution" in text)
    if "improving solution" not in seen:
        proc.wait()
        pytest.fail(f"the process ended (exit {proc.returncode}) before CP-SAT found a solution: {seen!r}")
    out = json.loads(stop(proc, signal.SIGINT, seen))
    assert out["stopped"] == "interrupted" and out["status"] == "FEASIBLE" and out["proven_optimal"] is False
    assert out["relative_gap"] == pytest.approx(out["gap"] / max(1.0, abs(out["cost"])))


@pytest.mark.heavy
@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM])
def test_a_signal_stops_a_running_qcec_check(sig: signal.Signals) -> None:
    """QCEC's native check holds the interpreter lock for minutes on two_robots_4x4; it runs in a child process,
    so the signal is handled at once. The signal goes once the validation names the QCEC stage, which it does
    when the child has received the circuits (an observable readiness signal; a heartbeat line could come while
    the child was still being started, and a signal there once left a child printing a traceback)."""
    pytest.importorskip("mqt.qcec")
    import queue
    import threading

    from qcpp.simulate.validate import QCEC_STAGE

    env = {"QCPP_PROGRESS": "lines", "QCPP_PROGRESS_INTERVAL": "0"}  # a line at every stage
    proc = start(["validate", "examples/two_robots_4x4.toml", "--backend", "qcec"], env)
    assert proc.stderr is not None
    lines: queue.Queue[str] = queue.Queue()
    reader = threading.Thread(target=lambda: [lines.put(line) for line in iter(proc.stderr.readline, "")],
                              daemon=True)  # fmt: skip
    reader.start()
    seen: list[str] = []
    while not any(QCEC_STAGE in line for line in seen):
        try:
            seen.append(lines.get(timeout=HUNG))
        except queue.Empty:
            proc.kill()
            pytest.fail(f"the QCEC stage did not start within {HUNG:g} s: {''.join(seen)!r}")
    proc.send_signal(sig)
    try:
        proc.wait(timeout=HUNG)
    except subprocess.TimeoutExpired:
        proc.kill()
        pytest.fail("the process did not stop after the signal")
    reader.join(HUNG)
    while not lines.empty():
        seen.append(lines.get())
    err = "".join(seen)
    assert proc.returncode == 130, err
    assert err.strip().splitlines()[-1] == "interrupted" and "Traceback" not in err, err


@pytest.mark.heavy
@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM])
def test_a_signal_while_the_qcec_child_starts_leaves_no_traceback(sig: signal.Signals) -> None:
    """The signal lands in the parent at the worst moment: the QCEC child's interpreter is launched and its
    arguments are not yet written (the signal is sent from inside the launch, so where it lands is certain, not
    timing). The start finishes, then the signal is handled, and the child is terminated without a word."""
    pytest.importorskip("mqt.qcec")
    script = (
        "import multiprocessing, multiprocessing.util, os, signal, sys\n"
        "from qcpp.ir.circuit import Circuit, Section\n"
        "from qcpp.ir.gates import mcx\n"
        "from qcpp.lowering.passes import lower\n"
        "from qcpp.simulate.equivalence import check_sections_interruptibly\n"
        "signal.signal(signal.SIGTERM, signal.default_int_handler)\n"
        "signal.signal(signal.SIGINT, signal.default_int_handler)\n"  # as the CLI: a background job gets SIG_IGN
        "launch = multiprocessing.util.spawnv_passfds\n"
        "def spawn(*args):\n"
        "    pid = launch(*args)\n"
        "    if 'spawn_main' in repr(args[1]):\n"  # the QCEC child (not the resource tracker)
        f"        os.kill(os.getpid(), {int(sig)})\n"
        "    return pid\n"
        "multiprocessing.util.spawnv_passfds = spawn\n"
        "high = Circuit([('data', 5)], [Section('s', [mcx([0, 1, 2, 3], 4, '1011')])])\n"
        "try:\n"
        "    check_sections_interruptibly(high, lower(high), 5)\n"
        "    print('not stopped')\n"
        "except KeyboardInterrupt:\n"
        "    print('children left:', len(multiprocessing.active_children()))\n"
    )
    proc = run_script(script)
    assert proc.stdout == "children left: 0\n", proc.stdout + proc.stderr
    assert proc.stderr == "", proc.stderr


def test_a_signal_that_lands_in_a_finaliser_still_stops_without_a_traceback() -> None:
    """Python prints a ``KeyboardInterrupt`` raised inside ``__del__`` as "Exception ignored ... Traceback" and goes
    on; the process must still end with ``interrupted`` and exit 130 (the signal is sent from inside ``__del__``,
    so where it lands is certain, not timing)."""
    script = (
        "import os, signal, time\n"
        "from qcpp.cli import interrupt\n"
        "interrupt.install()\n"
        "class Finalised:\n"
        "    def __del__(self):\n"
        "        os.kill(os.getpid(), signal.SIGTERM)\n"
        "        sum(range(100_000))\n"
        "try:\n"
        "    Finalised()\n"
        "    end = time.monotonic() + 60\n"
        "    while time.monotonic() < end:\n"
        "        time.sleep(0.001)\n"
        "    print('not stopped')\n"
        "except KeyboardInterrupt:\n"
        "    interrupt.report_interrupted()\n"
        "    os._exit(interrupt.EXIT_CODE)\n"
    )
    proc = run_script(script)
    assert proc.returncode == 130 and proc.stdout == "", proc
    assert proc.stderr == "interrupted\n", proc.stderr
