"""A pytest plugin: the tests that cost the most CPU, which the machine's load moves far less than wall clock.

``--durations`` reports wall clock, which on the shared 2-core machine doubles or triples with the other jobs'
load; this plugin times each test (setup, call and teardown) by the CPU seconds of the pytest process and of the
subprocesses it waited for (:func:`os.times`), and prints the slowest and the total at the end of a serial run:

    PYTHONPATH=src:benchmarks python -m pytest -p cpu_durations -m "not heavy" -p no:randomly -q

Under pytest-xdist each worker times its own tests and sends them to the controller, which prints the same
summary for the whole run, so CI's own steps can be measured as CI runs them:

    PYTHONPATH=src:benchmarks python -m pytest -p cpu_durations -m heavy -n 2 --maxschedchunk 1 -q

The summary lists the slowest tests, then the test files by their tests' total (where a step's CPU goes when it
is spread over many small tests), then the total. ``CPU_DURATIONS_TOP`` (default 30) sets how many tests and files
are listed; ``CPU_DURATIONS_OUT=path`` also writes every test's seconds to ``path`` (one ``seconds node-id`` line
each, slowest first), to compare two trees.
"""

from __future__ import annotations

import os
from collections.abc import Iterator
from typing import Any

import pytest

_SECONDS: list[tuple[float, str]] = []


def _cpu() -> float:
    t = os.times()
    return t.user + t.system + t.children_user + t.children_system


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_protocol(item: pytest.Item, nextitem: pytest.Item | None) -> Iterator[None]:
    start = _cpu()
    yield
    _SECONDS.append((_cpu() - start, item.nodeid))


def pytest_sessionfinish(session: pytest.Session) -> None:
    workeroutput = getattr(session.config, "workeroutput", None)
    if workeroutput is not None:  # an xdist worker: the controller reports (pytest_testnodedown)
        workeroutput["cpu_durations"] = [list(row) for row in _SECONDS]
        return
    out = os.environ.get("CPU_DURATIONS_OUT")
    if out and _SECONDS:
        with open(out, "w", encoding="utf-8") as f:
            f.writelines(f"{seconds:.3f} {node}\n" for seconds, node in sorted(_SECONDS, reverse=True))


@pytest.hookimpl(optionalhook=True)
def pytest_testnodedown(node: Any, error: object) -> None:
    """xdist's controller: a worker finished; keep the seconds it sent."""
    _SECONDS.extend((float(seconds), str(nodeid)) for seconds, nodeid in node.workeroutput.get("cpu_durations", ()))


def pytest_terminal_summary(terminalreporter: pytest.TerminalReporter) -> None:
    if not _SECONDS:
        return
    rows = sorted(_SECONDS, reverse=True)
    top = int(os.environ.get("CPU_DURATIONS_TOP", "30"))
    terminalreporter.write_sep("=", f"slowest {min(top, len(rows))} tests by CPU seconds")
    for seconds, node in rows[:top]:
        terminalreporter.write_line(f"{seconds:7.2f} s  {node}")
    files: dict[str, list[float]] = {}
    for seconds, node in rows:
        files.setdefault(node.split("::")[0], []).append(seconds)
    by_file = sorted(files.items(), key=lambda kv: -sum(kv[1]))
    terminalreporter.write_sep("=", f"{min(top, len(by_file))} test files of the most CPU seconds")
    for path, seconds_each in by_file[:top]:
        terminalreporter.write_line(f"{sum(seconds_each):7.1f} s  {len(seconds_each):4d} tests  {path}")
    terminalreporter.write_line(f"total: {sum(s for s, _ in rows):.1f} CPU seconds over {len(rows)} tests")
