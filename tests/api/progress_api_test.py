"""``progress=`` on the long API calls (:mod:`qcpp.api.progress`): one mechanism everywhere. A function
``progress(done, total)`` sees the work advance on a small case of every call; ``True`` writes the command line's
progress lines on stderr; anything else is one ``OptionError`` naming ``progress``; the result does not depend on
whether progress was asked for.

``QCPP_PROGRESS_INTERVAL=0`` makes the ``True`` form write a line at every step, synchronously, so nothing here
depends on timing.
"""

from __future__ import annotations

import importlib.util
from collections.abc import Callable
from typing import Any

import pytest

import qcpp
from tests.api.bad_input_test import error_of

S = qcpp.grid_scenario(2, 3, robots=1)
TWO = qcpp.grid_scenario(3, 3, robots=2)


class Seen:
    """A ``progress(done, total)`` that records its calls."""

    def __init__(self) -> None:
        self.calls: list[tuple[int, int | None]] = []

    def __call__(self, done: int, total: int | None) -> None:
        self.calls.append((done, total))

    @property
    def done(self) -> list[int]:
        return [d for d, _ in self.calls]


def test_compile_counts_the_gates_built_of_the_predicted_total() -> None:
    seen = Seen()
    c = qcpp.compile(TWO, 2, lowered=True, progress=seen)
    gates = sum(c.counts().values())
    assert len(seen.calls) > 1 and seen.done == sorted(seen.done)
    assert seen.calls[-1] == (gates, gates)  # the prediction is the lowered count
    assert c.circuit == qcpp.compile(TWO, 2, lowered=True).circuit  # built section by section: the same circuit


def test_compile_of_the_high_level_circuit_has_no_total() -> None:
    seen = Seen()
    c = qcpp.compile(TWO, 1, progress=seen)
    assert seen.calls and {t for _, t in seen.calls} == {None}
    assert seen.done[-1] == sum(c.counts().values())
    assert c.circuit == qcpp.compile(TWO, 1).circuit


def test_a_device_compile_counts_its_stages() -> None:
    seen = Seen()
    c = qcpp.compile(S, device="grid", progress=seen)
    assert seen.done == list(range(1, len(seen.calls) + 1)) and len(seen.calls) >= 2
    assert {t for _, t in seen.calls} == {None}
    assert c.counts() == qcpp.compile(S, device="grid").counts()


@pytest.mark.parametrize(
    ("method", "total"),
    [("dfs", "known"), ("cpsat", None), ("anneal", "known"), ("genetic", "known"), ("qaoa", "known")],
)
def test_solve_reports_the_method_s_steps(method: str, total: str | None) -> None:
    seen = Seen()
    sol = qcpp.solve(TWO, method, progress=seen)
    assert seen.calls, method
    done, last_total = seen.calls[-1]
    if total == "known":
        assert last_total is not None and done == last_total
    else:
        assert last_total is None and done >= 1
    assert sol.cost.total == qcpp.solve(TWO, method).cost.total


@pytest.mark.skipif(importlib.util.find_spec("dimod") is None, reason="dimod (extra 'annealing')")
def test_solve_qubo_reports_its_three_steps() -> None:
    seen = Seen()
    qcpp.solve(S, "qubo", progress=seen)
    assert seen.calls == [(1, 3), (2, 3), (3, 3)]


def test_train_qaoa_counts_the_levels() -> None:
    seen = Seen()
    qcpp.train_qaoa(S, 2, maxiter=5, progress=seen)
    assert seen.calls == [(0, 2), (1, 2), (2, 2)]


@pytest.mark.parametrize("backend", ["statevector", "sparse"])
def test_validate_counts_its_stages(backend: str) -> None:
    seen = Seen()
    report = qcpp.validate(S, backend=backend, progress=seen)
    assert report.passed and len(seen.calls) >= 2
    assert seen.calls == [(k, None) for k in range(1, len(seen.calls) + 1)]


def test_estimate_on_a_device_counts_the_routing_stages() -> None:
    seen = Seen()
    est = qcpp.estimate(S, device="grid", progress=seen)
    assert seen.calls and seen.calls == [(k, None) for k in range(1, len(seen.calls) + 1)]
    assert est.to_dict() == qcpp.estimate(S, device="grid").to_dict()


def test_verify_counts_its_checks() -> None:
    seen = Seen()
    assert qcpp.verify(S, progress=seen).holds
    assert seen.calls and seen.calls[-1][0] == seen.calls[-1][1]


CALLS: list[tuple[str, Callable[[Any], Any]]] = [
    ("compile", lambda progress: qcpp.compile(S, lowered=True, progress=progress)),
    ("solve", lambda progress: qcpp.solve(S, "anneal", progress=progress)),
    ("train_qaoa", lambda progress: qcpp.train_qaoa(S, maxiter=5, progress=progress)),
    ("validate", lambda progress: qcpp.validate(S, progress=progress)),
    ("estimate", lambda progress: qcpp.estimate(S, device="grid", progress=progress)),
    ("verify", lambda progress: qcpp.verify(S, progress=progress)),
]


@pytest.mark.parametrize(("name", "call"), CALLS, ids=[name for name, _ in CALLS])
def test_true_writes_progress_lines_on_stderr(
    name: str, call: Callable[[Any], Any], capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv("QCPP_PROGRESS_INTERVAL", "0")  # a line at every step, at once
    call(True)
    out, err = capsys.readouterr()
    lines = err.splitlines()
    assert out == "" and len(lines) >= 2, err
    assert all(line.startswith(name) for line in lines), err  # the task starts every line
    assert "done in" in lines[-1], err


@pytest.mark.parametrize(("name", "call"), CALLS, ids=[name for name, _ in CALLS])
def test_false_and_none_are_silent(
    name: str, call: Callable[[Any], Any], capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv("QCPP_PROGRESS_INTERVAL", "0")
    call(False)
    call(None)
    assert capsys.readouterr() == ("", "")


@pytest.mark.parametrize(("name", "call"), CALLS, ids=[name for name, _ in CALLS])
@pytest.mark.parametrize("bad", ["yes", 1, [print]])
def test_anything_else_is_one_line_naming_progress(name: str, call: Callable[[Any], Any], bad: object) -> None:
    message = error_of(lambda: call(bad), qcpp.OptionError)
    assert message.startswith("progress: expected True, False, None or a function progress(done, total)")


def test_what_the_function_raises_ends_the_call() -> None:
    class Stop(Exception):
        pass

    def stop(done: int, total: int | None) -> None:
        raise Stop

    with pytest.raises(Stop):
        qcpp.solve(TWO, "anneal", progress=stop)
