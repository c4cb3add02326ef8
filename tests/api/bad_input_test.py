"""Bad calls to the public API raise the documented :class:`qcpp.QcppError` subclass, with a one-line message that
gives the reason the command line gives for the same mistake; no public function leaves a partial file behind."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest

import qcpp
from tests.cli.clirun import run

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
S = qcpp.grid_scenario(3, 3, robots=1)


def error_of(call: Callable[[], Any], kind: type[Exception]) -> str:
    """The message of the error ``call`` raises, checked: ``kind`` (a QcppError, so a ValueError), one line."""
    with pytest.raises(kind) as info:
        call()
    assert isinstance(info.value, qcpp.QcppError) and isinstance(info.value, ValueError)
    message = str(info.value)
    assert message and "\n" not in message
    return message


def cli_error(*args: str) -> str:
    """The CLI's one error line for ``args``, without ``error: `` and the ``(see ...)`` hint."""
    res = run(*args)
    assert res.exit_code == 2, res.output
    line = res.stderr.strip()
    assert line.startswith("error: ") and "\n" not in line
    return line.removeprefix("error: ").split(" (see '")[0]


@pytest.mark.parametrize(
    ("kwargs", "flag_args", "name"),
    [
        ({"p": 0}, ("-p", "0"), "p"),
        ({"rule": "fast"}, ("--rule", "fast"), "rule"),
        ({"ancilla_budget": -1}, ("--ancilla-budget", "-1"), "ancilla_budget"),
        ({"p": 1001}, ("-p", "1001"), "p"),
    ],
)
def test_compile_and_estimate_options_give_the_cli_s_reason(
    kwargs: dict[str, Any], flag_args: tuple[str, ...], name: str
) -> None:
    cli = cli_error("compile", str(EXAMPLES / "paper_3x3.toml"), *flag_args)
    _, _, reason = cli.partition(": ")
    p = kwargs.get("p", 1)
    rest = {k: v for k, v in kwargs.items() if k != "p"}
    for fn in (qcpp.compile, qcpp.estimate):
        message = error_of(lambda fn=fn: fn(S, p, **rest), qcpp.QcppError)
        assert message == f"{name}: {reason}".replace("pass --allow-large", "call it in a qcpp.allow_large() block")


@pytest.mark.parametrize("p", ["1", 1.0, True, None])
def test_a_p_that_is_not_an_integer_names_p(p: Any) -> None:
    assert error_of(lambda: qcpp.estimate(S, p), qcpp.OptionError) == f"p: expected an integer, got {p!r}"


def test_an_unknown_plan_option_is_named() -> None:
    message = error_of(lambda: qcpp.compile(S, colour="red"), qcpp.OptionError)
    assert message.startswith("colour: unknown plan option (known: rule, initial,")


@pytest.mark.parametrize("device", [None, "grid"])
def test_an_unknown_symbol_in_bind_names_the_argument(device: str | None) -> None:
    """``bind: unknown symbol(s) ...`` from the API, ``--bind: ...`` from the command line, routed or not."""
    where = [] if device is None else ["--device", device]
    cli = cli_error("compile", str(EXAMPLES / "paper_3x3.toml"), "--bind", "delta_0=1", *where)
    s = qcpp.load_scenario(EXAMPLES / "paper_3x3.toml")
    message = error_of(lambda: qcpp.compile(s, bind={"delta_0": 1.0}, device=device), qcpp.OptionError)
    assert message.startswith("bind: unknown symbol(s) delta_0 (this circuit has: gamma_0, beta_0")
    assert cli == "--" + message


def test_a_binding_that_is_not_a_finite_number_is_named() -> None:
    cli = cli_error("compile", str(EXAMPLES / "paper_3x3.toml"), "--bind", "gamma_0=inf")
    message = error_of(lambda: qcpp.compile(S, bind={"gamma_0": float("inf")}), qcpp.OptionError)
    assert message == "bind" + cli.removeprefix("--bind")


def test_an_unknown_device_has_the_cli_s_message() -> None:
    """The command line names its flag before the same reason (``--device: unknown device ...``)."""
    cli = cli_error("compile", str(EXAMPLES / "paper_3x3.toml"), "--device", "ibm_nowhere")
    assert cli.startswith("--device: unknown device 'ibm_nowhere' (known: ")
    reason = cli.removeprefix("--device: ")
    assert error_of(lambda: qcpp.compile(S, device="ibm_nowhere"), qcpp.DeviceError) == reason
    assert error_of(lambda: qcpp.estimate(S, device="ibm_nowhere"), qcpp.DeviceError) == reason
    assert error_of(lambda: qcpp.device("ibm_nowhere"), qcpp.DeviceError) == reason


def test_a_robot_off_the_grid_names_the_robot_and_the_grid(tmp_path: Path) -> None:
    path = tmp_path / "off.toml"
    path.write_text('[grid]\nrows = 3\ncols = 3\n\n[[robots]]\nstart = [0, 0]\ngoal = [3, 0]\n')
    cli = cli_error("compile", str(path))
    message = error_of(lambda: qcpp.grid_scenario(3, 3, robots=[((0, 0), (3, 0))]), qcpp.ScenarioError)
    assert message == "robots[0].goal: (3, 0) is outside the 3x3 grid"
    assert cli == f"off.toml: {message}"


def test_an_obstacle_off_the_grid_or_on_a_robot_is_named() -> None:
    message = error_of(lambda: qcpp.grid_scenario(3, 3, robots=1, obstacles=[(5, 5)]), qcpp.ScenarioError)
    assert message == "obstacles[0]: (5, 5) is outside the 3x3 grid"
    message = error_of(lambda: qcpp.grid_scenario(3, 3, robots=1, obstacles=[(0, 0)]), qcpp.ScenarioError)
    assert message == "robots[0].start: (0, 0) is an obstacle"
    message = error_of(lambda: qcpp.grid_scenario(2, 2, robots=5), qcpp.ScenarioError)
    assert message.startswith("robots: the default placement fits 1 to 4 robots on a 2x2 grid")


def test_openqasm_2_of_an_unbound_circuit_names_the_symbols(tmp_path: Path) -> None:
    cli = cli_error("compile", str(EXAMPLES / "paper_3x3.toml"), "--qasm-version", "2", "--qasm", str(tmp_path / "x"))
    c = qcpp.compile(qcpp.load_scenario(EXAMPLES / "paper_3x3.toml"))
    message = error_of(lambda: c.to_qasm(version=2), qcpp.UnboundParameterError)
    assert message.removesuffix("bind them first") == cli.removesuffix("give them with --bind NAME=VALUE")
    assert cli.endswith("gamma_0, beta_0; give them with --bind NAME=VALUE")  # the command names its flag
    assert error_of(lambda: c.to_qasm(version=4), qcpp.OptionError) == "version: expected 3 or 2, got 4"


def test_estimate_settings_give_the_cli_s_reason() -> None:
    cli = cli_error("estimate", "--epsilon", "2")
    assert error_of(lambda: qcpp.estimate(S, epsilon=2.0), qcpp.OptionError) == cli.removeprefix("--")
    assert error_of(lambda: qcpp.estimate(S, depth="deep"), qcpp.OptionError).startswith("depth: expected auto or")


def test_a_qec_scheme_the_qubit_model_lacks_is_refused_before_the_qdk() -> None:
    """floquet_code on a gate-based model: one line naming both and the compatible models, in the CLI and the API
    alike (the QDK's own error was ``InvalidFaultToleranceProtocol``)."""
    cli = cli_error("estimate", "--grid", "3x3", "--physical", "--qec-scheme", "floquet_code")
    assert cli == ("--qec-scheme: floquet_code needs a Majorana qubit model (--qubit-model qubit_maj_ns_e4 or "
                   "qubit_maj_ns_e6), got qubit_gate_ns_e3")  # fmt: skip
    api = error_of(lambda: qcpp.estimate(S, physical=True, qec_scheme="floquet_code"), qcpp.OptionError)
    assert api == cli.replace("--qubit-model", "qubit_model").replace("--qec-scheme", "qec_scheme")
    est = qcpp.estimate(S, physical=True, qubit_model="qubit_maj_ns_e4", qec_scheme="floquet_code")
    assert est.physical_qubits > 0 and "floquet_code" in est.physical_model


@pytest.mark.parametrize(
    ("call", "start"),
    [
        (lambda: qcpp.estimate("examples/paper_3x3.toml"), "scenario: expected a Scenario"),
        (lambda: qcpp.compile(S, layout="greedy"), "layout: 'greedy' applies with a device only"),
        (lambda: qcpp.compile(S, optimize_for="esp"), "optimize_for: applies with a device only"),
        (lambda: qcpp.compile(S, device="ibm_fez", optimize_for="fidelity"), "optimize_for: expected esp or twoq"),
        (lambda: qcpp.compile(S, effort="quick"), "effort: 'quick' applies with a device only"),
        (lambda: qcpp.compile(S, device="ibm_fez", effort="fast"), "effort: expected full or quick"),
        (lambda: qcpp.estimate(S, effort="quick"), "effort: 'quick' applies with a device only"),
        (lambda: qcpp.estimate(S, device="ibm_fez", effort="fast"), "effort: expected full or quick"),
        (lambda: qcpp.compile(S, zero_start=True), "zero_start: applies with a named device only"),
        (lambda: qcpp.compile(S, device="grid", zero_start=True), "zero_start: applies with a named device with coup"),
        (lambda: qcpp.compile(S, device="quantinuum_helios", zero_start=True), "zero_start: applies with a named"),
        (lambda: qcpp.compile(S, device="ibm_fez", lowered=True, zero_start=True), "zero_start: applies to the nat"),
        (lambda: qcpp.compile(S, device="ibm_fez", zero_start=1), "zero_start: expected True or False"),
        (lambda: qcpp.solve(S, "magic"), "method: expected dfs or cpsat"),
        (lambda: qcpp.solve(S, "dfs", p=2), "p: applies to method='qaoa' only"),
        (lambda: qcpp.solve(S, "dfs", time_limit=5), "time_limit: applies to method='cpsat', 'anneal' or 'genetic'"),
        (lambda: qcpp.solve(S, "anneal", time_limit=0), "time_limit: expected a positive number of seconds"),
        (lambda: qcpp.solve(S, "dfs", stop=lambda: True), "stop: applies to method='cpsat', 'anneal' or 'genetic'"),
        (lambda: qcpp.solve(S, "genetic", stop=True), "stop: expected a function stop() -> bool, got bool"),
        (lambda: qcpp.solve(S, "anneal", workers=2), "workers: applies to method='cpsat' only"),
        (lambda: qcpp.solve(S, "genetic", generations=0), "generations: must be at least 1, got 0"),
        (lambda: qcpp.solve(S, "anneal", sampler="sa"), "sampler: applies to method='qubo' only"),
        (lambda: qcpp.solve(S, "qubo", sampler="anneal"), "sampler: expected tabu or sa"),
        (lambda: qcpp.train_qaoa(S, 1, optimizer="adam"), "optimizer: expected layerwise or"),
        (lambda: qcpp.train_qaoa(S, 1, gibbs_scale=0), "gibbs_scale: expected a positive finite number, got 0"),
        (lambda: qcpp.train_qaoa(S, 1, gibbs_scale="40"), "gibbs_scale: expected a positive finite number"),
        (lambda: qcpp.train_qaoa(S, 1, objective="cvar", gibbs_scale=5), "gibbs_scale: applies to objective='gibbs'"),
        (lambda: qcpp.train_qaoa(S, 1, restart_every_level="yes"), "restart_every_level: expected True, False or None"),
        (lambda: qcpp.train_qaoa(S, 1, optimizer="cobyla", restart_every_level=True),
         "restart_every_level: applies to optimizer='layerwise' only"),
        (lambda: qcpp.solve(S, "dfs", gibbs_scale=5), "gibbs_scale: applies to method='qaoa' only"),
        (lambda: qcpp.simulate_qaoa(S, 2, angles=[0.1, 0.2]), "angles: p = 2 needs 4 angles"),
        (lambda: qcpp.simulate_qaoa(S, 1, angles=[0.1, float("nan")]), "angles: nan is not a finite number"),
        (lambda: qcpp.compile(S, max_gates=10), "refusing to build"),
        (lambda: qcpp.verify(S, 0), "p: must be at least 1, got 0"),
        (lambda: qcpp.verify(S, 1.0), "p: expected an integer, got 1.0"),
        (lambda: qcpp.verify(S, rule="fast"), "rule: expected exact or paper, got 'fast'"),
        (lambda: qcpp.verify(S, 1001),
         "p: 1,001 layers is over the limit of 1,000; call it in a qcpp.allow_large() block to run it anyway"),
        (lambda: qcpp.grid_scenario("3", 3), "rows: expected an integer, got '3'"),
        (lambda: qcpp.grid_scenario(3, 3, obstacles=[(1, 1), (1, 1)]), "obstacles[1]: (1, 1) is listed twice"),
        (lambda: qcpp.grid_scenario(3, 3, obstacles=5), "obstacles: expected (row, col) nodes, got 5"),
        (lambda: qcpp.verify("examples/paper_3x3.toml"), "scenario: expected a Scenario"),
        (lambda: qcpp.verify(S, options={"rule": "paper"}), "options: expected a PlanOptions, got dict"),
        (lambda: qcpp.verify(S, colour="red"), "colour: unknown plan option"),
        (lambda: qcpp.is_feasible("x", 0, 0), "scenario: expected a Scenario"),
        (lambda: qcpp.is_feasible(S, S.num_robots, 0), f"robot: the scenario has robots 0 .. {S.num_robots - 1}"),
        (lambda: qcpp.is_feasible(S, -1, 0), "robot: must be at least 0, got -1"),
        (lambda: qcpp.is_feasible(S, 0, "x"), "mask: expected an integer, got 'x'"),
        (lambda: qcpp.save_scenario("x", "unwritten.toml"), "scenario: expected a Scenario"),
    ],
)
def test_other_bad_calls_raise_one_line_errors(call: Callable[[], Any], start: str) -> None:
    assert error_of(call, qcpp.QcppError).startswith(start)


def test_no_partial_file_after_an_error(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    c = qcpp.compile(S)
    target = tmp_path / "out.qasm"
    error_of(lambda: c.write_qasm(target, version=2), qcpp.UnboundParameterError)
    assert list(tmp_path.iterdir()) == []
    target.write_text("kept\n")

    import qcpp.lowering.qasm as qasm_module

    def interrupted(*args: Any, **kwargs: Any) -> Any:
        yield "OPENQASM 3.0;\n"
        raise KeyboardInterrupt

    monkeypatch.setattr(qasm_module, "iter_qasm", interrupted)
    with pytest.raises(KeyboardInterrupt):
        c.write_qasm(target)
    assert target.read_text() == "kept\n" and list(tmp_path.iterdir()) == [target]
    named = qcpp.grid_scenario(3, 3, robots=1)
    bad = type(named)(named.grid, named.robots, name="\ud800")  # a lone surrogate: TOML cannot hold it
    error_of(lambda: qcpp.save_scenario(bad, tmp_path / "s.toml"), qcpp.ScenarioError)
    assert list(tmp_path.iterdir()) == [target]


def test_the_simulators_keep_the_cli_s_size_guards(monkeypatch: pytest.MonkeyPatch) -> None:
    from qcpp.problem.limits import MEMORY_ENV

    s = qcpp.grid_scenario(3, 3, robots=2)
    monkeypatch.setenv(MEMORY_ENV, "1M")  # 1 MB available: no process fits
    message = error_of(lambda: qcpp.train_qaoa(s, 1, maxiter=1), qcpp.SizeError)
    assert message.startswith("scenario: training QAOA on") and "qcpp.allow_large()" in message
    message = error_of(lambda: qcpp.simulate_qaoa(s, 1), qcpp.SizeError)
    assert message.startswith("scenario: simulating") and "GB available" in message
    assert "of memory available" in error_of(lambda: qcpp.solve(s, "dfs"), qcpp.QcppError)
    message = error_of(lambda: qcpp.compile(s, 1), qcpp.SizeError)
    assert message.startswith("compiling") and "qcpp.allow_large()" in message
    with qcpp.allow_large():  # the override lifts every guard
        assert qcpp.simulate_qaoa(s, 1, angles=[0.1, 0.2]).p == 1
        assert qcpp.solve(s, "dfs").cost.total == pytest.approx(qcpp.solve(s, "cpsat").cost.total)


def test_an_estimate_point_cannot_mislabel_its_scenario() -> None:
    from qcpp.estimators.estimate import Point

    s = qcpp.grid_scenario(10, 10, robots=3)
    good = Point.from_scenario(s, 1)
    assert (good.rows, good.cols, good.robots) == (10, 10, 3)
    message = error_of(lambda: Point(4, 4, 1, 1, good.scenario_json), qcpp.OptionError)
    assert message.startswith("scenario_json: the scenario is 10x10 with 3 robot(s), but the point says 4x4 with 1")
