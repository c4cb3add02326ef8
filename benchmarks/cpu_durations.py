"""A pytest plugin: the tests that cost the most CPU, which the machine's load moves far less than wall clock.

``--durations`` reports wall clock, which on the shared 2-core machine doubles or triples with the other jobs'
load; this plugin times each test (setup, call and teardown) by the CPU seconds of the pytest process and of the
subprocesses it waited for (:func:`os.times`), and prints the slowest and the total at the end of a serial run:

    PYTHONPATH=src:benchmarks python -m pytest -p cpu_durations -m "not heavy" -p no:randomly -q

``CPU_DURATIONS_TOP`` (default 30) sets how many tests are listed; ``CPU_DURATIONS_OUT=path`` also writes every
test's seconds to ``path`` (one ``seconds node-id`` line each, slowest first), to compare two trees. Under
pytest-xdist each worker times its own tests, prints nothing and writes ``path.<worker>`` (``path.gw0``, ...):

    CPU_DURATIONS_OUT=/tmp/heavy PYTHONPATH=src:benchmarks python -m pytest -p cpu_durations -m heavy -n 2 -q
    cat /tmp/heavy.gw* | sort -rn | head -40
"""

from __future__ import annotations

import os
from collections.abc import Iterator

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
    out = os.environ.get("CPU_DURATIONS_OUT")
    worker = os.environ.get("PYTEST_XDIST_WORKER")
    if out and _SECONDS:
        with open(f"{out}.{worker}" if worker else out, "w", encoding="utf-8") as f:
            f.writelines(f"{seconds:.3f} {node}\n" for seconds, node in sorted(_SECONDS, reverse=True))


def pytest_terminal_summary(terminalreporter: pytest.TerminalReporter) -> None:
    if not _SECONDS:
        return
    rows = sorted(_SECONDS, reverse=True)
    top = int(os.environ.get("CPU_DURATIONS_TOP", "30"))
    terminalreporter.write_sep("=", f"slowest {min(top, len(rows))} tests by CPU seconds")
    for seconds, node in rows[:top]:
        terminalreporter.write_line(f"{seconds:7.2f} s  {node}")
    terminalreporter.write_line(f"total: {sum(s for s, _ in rows):.1f} CPU seconds over {len(rows)} tests")
