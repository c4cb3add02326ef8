"""Help text, shell completion, third-party noise and the cache folder: choice options list their choices,
``solve --help`` lists every method, completion is installable, QCEC/Dask/warnings never leak their own lines,
an unusable cache folder is named (once) as the cache folder, and no process (a test run, the CLI) ends with
nanobind's leak report."""

from __future__ import annotations

import json
import os
import re
import shlex
import subprocess
import sys
import warnings
from pathlib import Path

import pytest
import typer.main
from typer.testing import CliRunner

from qcpp.cli.app import CHOICES, CHOICES_IN_METAVAR, app, choices_of, one_line_warnings
from qcpp.cli.commands.solve import SOLVE_METHODS

REPO = Path(__file__).resolve().parents[2]
EXAMPLE = str(REPO / "examples" / "paper_3x3.toml")
COMMANDS = ["solve", "simulate", "compile", "estimate", "validate", "verify"]


def _help(*args: str) -> str:
    res = CliRunner().invoke(app, [*args, "--help"], env={"COLUMNS": "400"})
    assert res.exit_code == 0, res.output
    return res.stdout


def _params(command: str) -> dict[str, object]:
    group = typer.main.get_command(app)
    return {p.name: p for p in group.commands[command].params}  # type: ignore[attr-defined]


def test_every_choice_key_names_a_real_option() -> None:
    """CHOICES cannot drift from the commands: every ``command.param`` key exists, every bare key somewhere."""
    for key in CHOICES:
        if "." in key:
            command, param = key.split(".")
            assert param in _params(command), key
        else:
            assert any(key in _params(c) for c in COMMANDS), key


@pytest.mark.parametrize("command", COMMANDS)
def test_choice_options_list_their_choices(command: str) -> None:
    text = _help(command)
    for name, param in _params(command).items():
        values = choices_of(command, name)
        if values is None:
            continue
        flag = max(param.opts, key=len)  # type: ignore[attr-defined]
        line = next(line for line in text.splitlines() if line.lstrip("│ ").startswith(flag + " "))
        if len("[" + "|".join(values) + "]") <= CHOICES_IN_METAVAR:
            assert "[" + "|".join(values) + "]" in line, line
            assert "<str>" not in line and "<int>" not in line
        else:  # a long list: in the help text, where it wraps
            assert all(re.search(rf"(?<![\w-]){re.escape(v)}(?![\w-])", line.split(flag, 1)[1]) for v in values), line


def _all_commands() -> list[str]:
    return sorted(typer.main.get_command(app).commands)  # type: ignore[attr-defined]


@pytest.mark.parametrize("command", ["", *_all_commands()])
def test_no_option_name_is_cut_at_80_columns(command: str) -> None:
    """Every option name (``--x`` and its ``--no-x``) appears whole in ``--help`` at ``COLUMNS=80``, nothing is cut
    with an ellipsis, and no line is wider than 80 characters."""
    args = [command] if command else []
    res = CliRunner().invoke(app, [*args, "--help"], env={"COLUMNS": "80"})
    assert res.exit_code == 0, res.output
    text = res.stdout
    assert "…" not in text, text
    assert max(len(line) for line in text.splitlines()) <= 80
    group = typer.main.get_command(app)
    params = group.commands[command].params if command else group.params  # type: ignore[attr-defined]
    cells = {cell for line in text.splitlines() for cell in re.split(r"[\s│,]+", line) if cell}
    for param in params:
        if getattr(param, "hidden", False):
            continue
        for name in [*param.opts, *getattr(param, "secondary_opts", [])]:
            if name.startswith("--"):
                assert name in cells, (command, name)


def test_a_negative_flag_has_its_own_help_row_and_the_option_keeps_both_names() -> None:
    text = CliRunner().invoke(app, ["solve", "--help"], env={"COLUMNS": "80"}).stdout
    row = next(line for line in text.splitlines() if "--no-restart-every-level" in line)
    assert "The opposite of" in row and "--restart-every-level " not in row.split("--no-restart-every-level")[0]
    assert _params("solve")["restart_every_level"].secondary_opts == ["--no-restart-every-level"]  # type: ignore[attr-defined]


def test_solve_help_lists_every_method() -> None:
    top, own = (" ".join(text.split()) for text in (_help(), _help("solve")))  # however the help is wrapped
    for method in SOLVE_METHODS:
        assert f"{method} = " in own  # described in solve's help
        assert method in top.split("solve ", 2)[2].split(" simulate ")[0]  # named in the command list
    assert "cpsat" in own


def test_estimate_help_says_where_its_columns_are_defined_and_that_page_defines_every_field() -> None:
    """``routed_twoq``, ``esp``, ``routed_kind``: the help names the pages, and the column table there lists every
    field a row can hold (counts, fault-tolerant, paper and routed ones)."""
    from qcpp.estimators import routed
    from qcpp.estimators.estimate import Point, estimate_point
    from qcpp.estimators.tables import make_row

    text = " ".join(_help("estimate").split())
    assert "docs/resource-estimates.md" in text and "docs/guide/hardware.md" in text and "routed_kind" in text
    page = (REPO / "docs" / "resource-estimates.md").read_text(encoding="utf-8")
    start = page.index("### Columns")
    table = [line.split("|")[1] for line in page[start : page.index("\n## ", start)].splitlines()
             if line.startswith("| `")]  # fmt: skip
    named = {name for cell in table for name in re.findall(r"`([a-z0-9_]+)`", cell)}
    fields = set(make_row(estimate_point(Point(2, 2, 1, 1)), compare_paper=True)) - {"sections"}
    fields |= {"device", "fits", *routed._NONE}
    assert not fields - named, f"docs/resource-estimates.md's Columns table lacks {sorted(fields - named)}"


def test_shell_completion_is_installable_and_completes_choices() -> None:
    assert "--install-completion" in _help() and "--show-completion" in _help()
    runner = CliRunner()
    env = {"_QCPP_COMPLETE": "complete_bash", "COMP_WORDS": "qcpp solve x.toml --method ", "COMP_CWORD": "4"}
    res = runner.invoke(app, [], env=env, prog_name="qcpp")
    assert res.stdout.split() == list(SOLVE_METHODS)
    env = {"_QCPP_COMPLETE": "complete_bash", "COMP_WORDS": "qcpp est", "COMP_CWORD": "1"}
    assert runner.invoke(app, [], env=env, prog_name="qcpp").stdout.split() == ["estimate"]
    docs = (REPO / "docs" / "cli.md").read_text()
    assert "--install-completion" in docs and "--show-completion" in docs


def test_warnings_become_one_note_line_once(capsys: pytest.CaptureFixture[str]) -> None:
    with one_line_warnings():
        for _ in range(3):
            warnings.warn("the cache folder /x cannot be used\nsecond line", UserWarning, stacklevel=1)
    err = capsys.readouterr().err
    assert err == "note: the cache folder /x cannot be used second line\n"


@pytest.mark.parametrize("env", [
    {"XDG_CACHE_HOME": "/proc/x"},
    pytest.param({"QCPP_CACHE_DIR": "/dev/null"}, marks=pytest.mark.heavy),
])
def test_an_unusable_cache_folder_is_named_once_and_the_run_proceeds(env: dict[str, str]) -> None:
    env = {"QCPP_CACHE_DIR": "", **env}
    res = CliRunner().invoke(app, ["validate", EXAMPLE, "--backend", "tensor"], env=env)
    assert res.exit_code == 0, res.output
    notes = [line for line in res.stderr.splitlines() if "cache folder" in line]
    assert len(notes) == 1 and notes[0].startswith("note: the contraction-path cache folder ")
    assert next(iter(env.values())) in notes[0] or "/proc/x" in notes[0]
    assert "Traceback" not in res.output


def test_qcec_prints_nothing_of_its_own_and_claims_no_tolerance(capfd: pytest.CaptureFixture[str]) -> None:
    pytest.importorskip("mqt.qcec")
    res = CliRunner().invoke(app, ["validate", EXAMPLE, "--backend", "qcec"])
    native = capfd.readouterr()
    assert res.exit_code == 0, res.output
    assert "[QCEC]" not in native.out + native.err + res.output
    words = " ".join(res.stdout.split())
    assert "tolerance" not in words and "decided exactly by QCEC" in words
    assert "construction checker" in words  # QCEC's fallback warning, in our words
    as_json = CliRunner().invoke(app, ["validate", EXAMPLE, "--backend", "qcec", "--json"])
    out = json.loads(as_json.stdout)
    assert out["tolerance"] is None and out["passed"] is True
    assert "[QCEC]" not in capfd.readouterr().err


@pytest.mark.heavy
def test_dask_says_it_ran(capfd: pytest.CaptureFixture[str]) -> None:
    pytest.importorskip("dask.distributed")
    import socket

    # another cluster's dashboard on dask's default port: ours must neither complain nor take it
    with socket.socket() as busy:
        try:
            busy.bind(("127.0.0.1", 8787))
            busy.listen()
        except OSError:
            pass  # already held by some other process: the same condition
        res = CliRunner().invoke(app, ["validate", EXAMPLE, "--dask", "local"])
    assert res.exit_code == 0, res.output
    assert "Dask (" in res.stdout
    native = capfd.readouterr()
    assert "8787" not in native.err + res.stderr and "distributed." not in native.err + res.stderr


_LIVE_CYCLE = """
import gc, sys
from mqt.core.ir import QuantumComputation
cache = {"circuit": QuantumComputation(2)}
cache["self"] = cache  # a live cycle holding a nanobind object, as the session's caches hold circuits
if sys.argv[1] == "survivors":
    from tests.shutdown import freeze_survivors
    freeze_survivors()
else:
    gc.collect()
    gc.freeze()
"""


@pytest.mark.parametrize(("how", "leaks"), [("survivors", False), ("plain freeze", True)])
def test_a_test_run_ends_without_nanobind_leak_reports(how: str, leaks: bool) -> None:
    """The test session's end (:func:`tests.shutdown.freeze_survivors`) leaves nanobind nothing to report; a plain
    :func:`gc.freeze` (the control) makes it print its report, so the check can see one."""
    pytest.importorskip("mqt.core")
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(REPO), *sys.path])}
    res = subprocess.run([sys.executable, "-c", _LIVE_CYCLE, how], capture_output=True, text=True, env=env,
                         cwd=REPO, check=True)  # fmt: skip
    assert ("nanobind" in res.stderr) is leaks, res.stderr[:500]


@pytest.mark.heavy
def test_the_cli_ends_without_nanobind_leak_reports() -> None:
    pytest.importorskip("mqt.qcec")
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(sys.path)}
    res = subprocess.run([sys.executable, "-m", "qcpp", "validate", EXAMPLE, "--backend", "qcec"],
                         capture_output=True, text=True, env=env, check=False)  # fmt: skip
    assert res.returncode == 0, res.stderr
    assert "nanobind" not in res.stderr + res.stdout


# --- usage examples in every command's help: on its first screen, and they run ------------------------------------

HELP_COMMANDS = ["", "estimate", "compile", "export", "simulate", "solve", "validate", "verify", "decode", "scenario"]
FIRST_SCREEN = 25  # lines of help at 80 columns

SLOW_EXAMPLES = frozenset({
    "qcpp solve field.toml --method cpsat",
    "qcpp estimate --grid 2x2..6x6 --robots 1..3 --compare paper --plot cx.png",
    "qcpp estimate examples/two_robots_4x4.toml --physical --json",
    "qcpp compile examples/paper_3x3.toml --device heavy-hex --qasm routed.qasm",
    "qcpp simulate examples/paper_3x3.toml -p 1 --angles 0.3,1.2",
    "qcpp solve examples/two_robots_4x4.toml -m anneal --seed 3 --plot paths.png",
    "qcpp solve examples/two_robots_5x5.toml --method cpsat --json",
    "qcpp solve examples/paper_3x3.toml --method qaoa -p 2 --plot-trace trace.png",
    "qcpp validate examples/paper_3x3.toml -p 2 --backend tensor",
    "qcpp validate examples/paper_3x3.toml --backend qcec",
    "qcpp verify examples/two_robots_5x5.toml -p 3 --method gadgets",
})
"""Examples that take more than a second or so: run by the heavy test only."""


def _screen(command: str) -> list[str]:
    res = CliRunner().invoke(app, [*([command] if command else []), "--help"], env={"COLUMNS": "80"})
    assert res.exit_code == 0, res.output
    return res.stdout.splitlines()


def _examples(command: str) -> list[str]:
    """The example command lines of ``qcpp COMMAND --help`` at 80 columns, in order."""
    return [line.strip() for line in _screen(command) if line.strip().startswith("qcpp ")]


@pytest.mark.parametrize("command", HELP_COMMANDS)
def test_help_shows_two_to_four_examples_on_its_first_screen(command: str) -> None:
    lines = _screen(command)
    at = [i for i, line in enumerate(lines) if line.strip().startswith("qcpp ")]
    assert 2 <= len(at) <= 4 and max(at) < FIRST_SCREEN, lines[:FIRST_SCREEN]
    for i in at:  # whole on its line: the next line is another example or blank, not a wrapped tail
        assert lines[i + 1].strip() == "" or lines[i + 1].strip().startswith("qcpp "), lines[i : i + 2]
    assert all(ex.startswith(f"qcpp {command}".rstrip() + " ") for ex in _examples(command))
    if command:  # every option in a named panel (qcpp.cli.app.PANELS), none left in typer's catch-all
        panels = [line.split()[1] for line in lines if line.startswith("╭─ ")]
        assert "Options" not in panels and {"Output", "Advanced"} <= set(panels), panels


def test_slow_examples_are_examples() -> None:
    assert {ex for c in HELP_COMMANDS for ex in _examples(c)} >= SLOW_EXAMPLES


def _run_examples(command: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch, slow: bool) -> None:
    """Run the examples of ``command``'s help in order, in a fresh folder that holds the repository's examples."""
    (tmp_path / "examples").symlink_to(REPO / "examples")
    monkeypatch.chdir(tmp_path)
    for example in _examples(command):
        if example in SLOW_EXAMPLES and not slow:
            continue
        res = CliRunner().invoke(app, shlex.split(example)[1:], env={"COLUMNS": "80"})
        assert res.exit_code == 0, f"{example}: {res.output}"


@pytest.mark.parametrize("command", HELP_COMMANDS)
def test_help_examples_run(command: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    _run_examples(command, tmp_path, monkeypatch, slow=False)


@pytest.mark.heavy
@pytest.mark.parametrize("command", HELP_COMMANDS)
def test_every_help_example_runs(command: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    _run_examples(command, tmp_path, monkeypatch, slow=True)
