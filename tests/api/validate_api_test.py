"""``qcpp.validate``: the report of ``qcpp validate --json`` for the same scenario and options (timings aside: the
verdict, ``passed`` and ``tolerance`` included), a circuit that breaks fails it, a skipped check never passes, and
bad options raise the command's one-line reasons."""

from __future__ import annotations

from typing import Any

import pytest

import qcpp
from tests.api.bad_input_test import error_of
from tests.api.cli_equality_test import cli_json

S = qcpp.grid_scenario(2, 3, robots=1)


def _untimed(d: dict[str, Any]) -> dict[str, Any]:
    out = {k: v for k, v in d.items() if k != "seconds"}
    out["checks"] = [{k: v for k, v in c.items() if k != "seconds"} for c in d["checks"]]
    return out


@pytest.mark.parametrize("backend", ["statevector", "sparse"])
def test_the_report_is_the_cli_s(backend: str) -> None:
    cli = cli_json("validate", "--grid", "2x3", "--robots", "1", "-p", "2", "--angles", "0.3,0.8,0.5,1.1",
                   "--backend", backend, "--json")  # fmt: skip
    report = qcpp.validate(S, p=2, angles=[0.3, 0.8, 0.5, 1.1], backend=backend)
    assert report.passed and cli["verdict"] == "passed"
    assert _untimed(report.to_dict()) == _untimed(cli)  # type: ignore[arg-type]
    assert report.checks and all(c.status == "pass" for c in report.checks)


@pytest.mark.parametrize("backend", ["statevector", "qcec"])
def test_seeded_report_equals_the_cli_json(backend: str) -> None:
    """Seeded angles (the command's default seed 0), a file scenario: ``to_dict()`` is the ``--json`` object."""
    if backend == "qcec":
        pytest.importorskip("mqt.qcec")
        pytest.importorskip("qiskit")
    cli = cli_json("validate", "examples/paper_3x3.toml", "-p", "1", "--backend", backend, "--json")
    report = qcpp.validate(qcpp.load_scenario("examples/paper_3x3.toml"), 1, backend=backend, seed=0)
    d = report.to_dict()
    assert _untimed(d) == _untimed(cli)  # type: ignore[arg-type]
    assert d["verdict"] == "passed" and d["passed"] is True
    assert (d["tolerance"] is None) == (backend == "qcec")


def test_a_skipped_check_is_incomplete_not_passed() -> None:
    """A check that did not run: the report is ``incomplete`` and ``passed`` is false (the command exits 1)."""
    import dataclasses

    import qcpp.simulate.validate as sv

    report = qcpp.validate(S, p=1, angles=[0.3, 0.8], backend="statevector")
    skipped = sv.Check("amplitudes", "tensor contraction", float("nan"), float("nan"), 0, "skipped", 0.0, "wide")
    partial = dataclasses.replace(report, checks=(*report.checks, skipped))
    assert report.verdict == "passed" and partial.verdict == "incomplete" and not partial.passed
    assert partial.to_dict()["passed"] is False and partial.to_dict()["verdict"] == "incomplete"
    assert "<caption>validation INCOMPLETE: " in partial._repr_html_()
    assert dataclasses.replace(report, checks=()).verdict == "incomplete"


def test_a_circuit_that_breaks_fails_the_check(monkeypatch: pytest.MonkeyPatch) -> None:
    """Drop the first cx of every partial mixer's mirror: the amplitudes no longer match the subspace simulator."""
    import qcpp.gadgets.partial_mixer as pm

    parts = pm.ParityPartialMixer.parts

    def broken(self: Any) -> Any:
        compute, rotation, mirror = parts(self)
        k = next(i for i, g in enumerate(mirror) if g[0] == "cx")
        return compute, rotation, mirror[:k] + mirror[k + 1 :]

    monkeypatch.setattr(pm.ParityPartialMixer, "parts", broken)
    report = qcpp.validate(S, p=1, angles=[0.3, 0.8], backend="statevector")
    assert not report.passed
    assert any(c.status == "fail" for c in report.checks)
    html = report._repr_html_()  # in a notebook the failure shows in the caption and in its row
    assert "<caption>validation FAILED: " in html and "<td>fail</td>" in html
    assert html.count("<tr>") == 1 + len(report.checks)


def test_notebooks_show_the_reports_as_tables() -> None:
    report = qcpp.validate(S, p=1, angles=[0.3, 0.8])
    html = report._repr_html_()
    assert html.startswith("<table><caption>validation passed: ") and html.count("<tr>") == 1 + len(report.checks)
    assert all(f"<td>{c.name}</td><td>{c.method}</td>" in html for c in report.checks)
    verified = qcpp.verify(S)
    html = verified._repr_html_()
    assert html.startswith("<table><caption>feasibility preservation holds: ")
    assert html.count("<tr>") == 1 + len(verified.checks) and "FAILS" not in html and "<pre>" not in html


def test_bad_options_name_what_is_wrong() -> None:
    assert error_of(lambda: qcpp.validate(S, angles=[0.1]), qcpp.OptionError).startswith("angles: p = 1 needs 2")
    assert error_of(lambda: qcpp.validate(S, max_amplitudes=0), qcpp.OptionError).startswith("max_amplitudes:")
    message = error_of(lambda: qcpp.validate(S, backend="sparse", dask="local"), qcpp.OptionError)
    assert message == "dask: only the tensor backend uses a dask cluster, got backend='sparse'"
    message = error_of(lambda: qcpp.validate(S, dask="tcp://h"), qcpp.OptionError)
    assert message.startswith("dask: ") and "missing port number" in message
    assert error_of(lambda: qcpp.validate("s.toml"), qcpp.OptionError).startswith("scenario:")  # type: ignore[arg-type]


ONE_ROBOT_3x3 = qcpp.grid_scenario(3, 3, robots=1)  # its local-search path is not its initial path


@pytest.mark.parametrize(
    "options",
    [{"target": "ft"}, {"initial": "local_search"}, {"first_phase": False},
     {"target": "ft", "initial": "local_search", "first_phase": False, "phase": "whole-space"}],
    ids=lambda o: ",".join(f"{k}={v}" for k, v in o.items()),
)  # fmt: skip
def test_plan_options_are_validated_against_the_subspace_simulator(options: dict[str, Any]) -> None:
    """The circuit built with the options (its qubits and gates are the compiled ones) matches a reference that
    follows them: the initial state's, the phase constant's, no first phase separator."""
    report = qcpp.validate(ONE_ROBOT_3x3, p=2, angles=[0.3, 0.8, 0.5, 1.1], backend="statevector", **options)
    compiled = qcpp.compile(ONE_ROBOT_3x3, p=2, lowered=True, **options)
    assert report.passed and report.plan == options
    assert (report.qubits, report.gates) == (compiled.qubits, sum(compiled.counts().values()))


def test_validate_s_plan_options_are_the_cli_s_plan_flags() -> None:
    cli = cli_json("validate", "--grid", "3x3", "--robots", "1", "-p", "2", "--angles", "0.3,0.8,0.5,1.1",
                   "--target", "ft", "--initial", "local_search", "--skip-first-phase", "--json")  # fmt: skip
    report = qcpp.validate(ONE_ROBOT_3x3, p=2, angles=[0.3, 0.8, 0.5, 1.1], target="ft", initial="local_search",
                           first_phase=False)  # fmt: skip
    assert cli["plan"] == {"initial": "local_search", "target": "ft", "first_phase": False}
    assert _untimed(report.to_dict()) == _untimed(cli)  # type: ignore[arg-type]


def test_plan_options_validate_cannot_check_are_refused_in_one_line() -> None:
    from qcpp.estimators.crosscheck import interior_endpoints
    from qcpp.simulate.validate import check_validatable
    from tests.cli.clirun import assert_one_line_error, run

    message = error_of(lambda: qcpp.validate(S, colour="red"), qcpp.OptionError)
    assert message.startswith("colour: unknown plan option")
    split = interior_endpoints(4, 3, "hard")  # representatives start in a superposition here
    message = error_of(lambda: qcpp.validate(split, initial="representatives", first_phase=False), qcpp.OptionError)
    assert message.startswith("first_phase: ") and "representatives prepares a superposition" in message
    with pytest.raises(qcpp.OptionError, match=r"^angles: the subspace simulator has one beta per layer, not multi$"):
        check_validatable(qcpp.PlanOptions(angles="multi"))
    assert_one_line_error(run("validate", "--grid", "2x3", "--robots", "1", "--mixer-angles", "multi"),
                          "--mixer-angles")  # fmt: skip


def test_the_cli_s_table_names_the_plan_options_that_are_not_the_default() -> None:
    from tests.cli.clirun import run

    res = run("validate", "--grid", "2x3", "--robots", "1", "--target", "ft", "--skip-first-phase")
    assert res.exit_code == 0, res.output
    assert "p=1, target=ft, first_phase=False, backend=" in " ".join(res.stdout.split())
    assert "target=" not in run("validate", "--grid", "2x3", "--robots", "1").stdout
