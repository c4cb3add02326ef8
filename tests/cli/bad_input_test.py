"""Bad and unusual input to every command: one line on stderr, exit 2, no traceback, nothing left behind.

Each case runs in a scratch folder holding the usual suspects (a FIFO, a symlink, a folder named like a file,
files with a byte order mark, binary junk, a 10000x10000 grid); afterwards the folder must hold exactly what it
held before, with the special files still special and the symlink's target untouched.
"""

from __future__ import annotations

import json
import os
import shutil
import stat
import subprocess
import sys
import threading
from pathlib import Path

import pytest
from typer.testing import CliRunner

import qcpp.io.atomic
from qcpp.cli.app import app
from qcpp.lowering.qasm import to_qasm3
from qcpp.plan.qaoa import qaoa_circuit
from qcpp.problem.scenario_io import load_scenario

from .clirun import run

REPO = Path(__file__).resolve().parents[2]
EXAMPLE = REPO / "examples" / "paper_3x3.toml"
LINK_TARGET_TEXT = "previous content\n"


@pytest.fixture
def scratch(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    """A folder of odd files, made the working directory; FIFO writers give up after 0.2 s."""
    monkeypatch.chdir(tmp_path)
    monkeypatch.setattr(qcpp.io.atomic, "FIFO_WAIT", 0.2)
    monkeypatch.setenv("QCPP_CACHE_DIR", str(tmp_path / "cache"))
    shutil.copy(EXAMPLE, tmp_path / "ex.toml")
    (tmp_path / "bom.toml").write_bytes(b"\xef\xbb\xbf" + EXAMPLE.read_bytes())
    (tmp_path / "bom.json").write_bytes(
        b"\xef\xbb\xbf" + json.dumps({"grid": {"rows": 2, "cols": 3}, "robots": [{"start": [0, 0], "goal": [1, 2]}]})
        .encode()
    )
    (tmp_path / "empty.toml").write_text("")
    (tmp_path / "binary.toml").write_bytes(b"\x00\xff\xfe\x80 rows = 3")
    (tmp_path / "broken.json").write_text('{"grid": {"rows": 3,')
    (tmp_path / "notes.txt").write_text("[grid]\nrows = 3\ncols = 3\n")
    huge = "[grid]\nrows = 10000\ncols = 10000\n[[robots]]\nstart = [0, 0]\ngoal = [1, 1]\n"
    (tmp_path / "huge.toml").write_text(huge)
    (tmp_path / "folder.toml").mkdir()
    os.mkfifo(tmp_path / "fifo")
    (tmp_path / "target.qasm").write_text(LINK_TARGET_TEXT)
    (tmp_path / "link.qasm").symlink_to("target.qasm")
    (tmp_path / "dangling.qasm").symlink_to("missing/x.qasm")
    (tmp_path / "loop").symlink_to("loop")
    return tmp_path


def snapshot(folder: Path) -> dict[str, str]:
    """Every entry (recursively) with its kind and, for regular files, its content."""
    out = {}
    for p in sorted(folder.rglob("*")):
        rel = str(p.relative_to(folder))
        if rel.startswith("cache"):
            continue
        mode = p.lstat().st_mode
        if stat.S_ISLNK(mode):
            out[rel] = "link->" + os.readlink(p)
        elif stat.S_ISFIFO(mode):
            out[rel] = "fifo"
        elif stat.S_ISDIR(mode):
            out[rel] = "dir"
        else:
            out[rel] = p.read_bytes().decode("latin-1")
    return out


EX = "ex.toml"
BAD = [
    # unknown or malformed options and commands
    ("compile", EX, "--bogus"),
    ("estimate", "--nope"),
    ("solve", EX, "-z"),
    ("simulate", EX, "--method"),
    ("validate",),
    ("frobnicate",),
    ("solve", EX, "--json=yes"),
    # numbers
    ("compile", EX, "-p", "x"),
    ("compile", EX, "-p", "0"),
    ("compile", EX, "-p", "-1"),
    ("compile", EX, "-p", "2.5"),
    ("compile", EX, "-p", "100000"),
    ("compile", EX, "--qasm-version", "4"),
    ("compile", EX, "--bind", "gamma_0=nan", "beta_0=1"),
    ("simulate", EX, "-p", "0"),
    ("simulate", EX, "--seed", "-1"),
    ("simulate", EX, "--angles", "nan,1"),
    ("simulate", EX, "--angles", "1,x"),
    ("solve", EX, "-m", "qaoa", "--maxiter", "0"),
    ("solve", EX, "-m", "qaoa", "-p", "0"),
    ("solve", EX, "-m", "dfs", "-p", "0"),
    ("solve", EX, "--seed", "-5"),
    ("validate", EX, "-p", "0"),
    ("validate", EX, "--max-amplitudes", "0"),
    ("validate", EX, "--max-amplitudes", "-3"),
    ("validate", EX, "--angles", "inf,1"),
    ("validate", EX, "--seed", "-1"),
    ("estimate", "-p", "0"),
    ("estimate", "--epsilon", "nan"),
    ("estimate", "--epsilon", "0"),
    ("estimate", "--grid", "0x0"),
    ("estimate", "--grid", "10000x10000"),
    ("estimate", "--robots", "0"),
    ("estimate", "--grid", "2x2", "--columns", "rows,nonsense"),
    ("estimate", "--grid", "2x2", "--columns", ","),
    ("estimate", "--grid", "2x2", "--columns", "rows,cx", "--json"),
    ("estimate", "--grid", "2x2", "--columns", "rows,nonsense", "--format", "csv"),
    ("estimate", "--grid", "2x2", "--json", "--format", "csv"),  # two formats asked for: refused, not JSON
    ("estimate", "--grid", "2x2", "--json", "--format", "table"),  # table is the default, but this one was asked for
    ("estimate", "--grid", "2x2", "--format", "md", "--json"),
    ("estimate", "--grid", "2x2", "--format", "json", "--json"),
    # scenario files
    ("solve", "missing.toml"),
    ("solve", "folder.toml"),
    ("solve", "empty.toml"),
    ("solve", "binary.toml"),
    ("compile", "broken.json"),
    ("simulate", "notes.txt"),
    ("solve", "huge.toml"),
    ("compile", "huge.toml"),
    ("estimate", "--scenario", "huge.toml"),
    ("solve", "/dev/zero"),
    # output destinations
    ("compile", EX, "--qasm", "/dev/full"),
    ("compile", EX, "--qasm", "fifo"),
    ("compile", EX, "--qasm", "missing/x.qasm"),
    ("compile", EX, "--qasm", "folder.toml"),
    ("compile", EX, "--qasm", "dangling.qasm"),
    ("compile", EX, "--qasm", "-", "--json"),
    ("compile", EX, "--qasm", ""),
    ("compile", EX, "--qasm", "loop"),
    ("solve", EX, "-m", "dfs", "--plot", "missing/p.png"),
    ("solve", EX, "-m", "anneal", "--plot-trace", "missing/t.png"),
    ("estimate", "--grid", "2x2", "--plot", "missing/e.png"),
    # a full disk or a FIFO without a reader under --plot: output_checks_test.py (the printed result stays)
]


@pytest.mark.parametrize("args", BAD, ids=[" ".join(a) for a in BAD])
def test_bad_input_is_one_line_exit_2_and_leaves_everything_as_it_was(scratch: Path, args: tuple[str, ...]) -> None:
    before = snapshot(scratch)
    res = run(*args)
    assert res.exit_code == 2, (res.stdout, res.stderr)
    assert res.stdout == ""
    lines = res.stderr.splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: "), res.stderr
    assert "Traceback" not in res.stderr and "╭" not in res.stderr
    assert ".tmp" not in lines[0]  # errors name the user's path, never our temporary file
    assert snapshot(scratch) == before  # no leftover file, no special file replaced, the link's target untouched
    assert stat.S_ISCHR(os.stat("/dev/full").st_mode)


@pytest.mark.parametrize(
    ("args", "fragment"),
    [
        (("compile", EX, "--bogus"), "No such option: --bogus"),  # click may add "(Possible options: ...)"
        (("compile", EX, "-p", "0"), "-p/--layers: must be at least 1, got 0"),
        (("validate", EX, "--max-amplitudes", "0"), "--max-amplitudes: must be at least 1, got 0"),
        (("solve", EX, "-m", "qaoa", "--maxiter", "0"), "--maxiter: must be at least 1, got 0"),
        (("compile", EX, "-p", "100000"), "--allow-large"),
        (("solve", "huge.toml"), "10000x10000 grid has 100,000,000 nodes"),
        (("compile", EX, "--qasm", "/dev/full"), "cannot write /dev/full: No space left on device"),
        (("compile", EX, "--qasm", "missing/x.qasm"), "cannot write missing/x.qasm: the folder missing does not exist"),
        (("compile", EX, "--qasm", "fifo"), "cannot write fifo: no process opened the FIFO"),
        (("solve", EX, "-m", "dfs", "--plot", "missing/p.png"), "the folder missing does not exist"),
        (("estimate", "--grid", "2x2", "--plot", "missing/e.png"), "the folder missing does not exist"),
        (("validate",), "give a scenario file, or the scenario inline with --grid"),
    ],
)
def test_error_lines_say_what_is_wrong(scratch: Path, args: tuple[str, ...], fragment: str) -> None:
    res = run(*args)
    assert res.exit_code == 2 and fragment in res.stderr, res.stderr


def test_same_layer_rule_in_every_command(scratch: Path) -> None:
    """``-p 0`` is refused the same way everywhere (it used to pass compile and estimate)."""
    for args in (("compile", EX), ("simulate", EX), ("validate", EX), ("solve", EX, "-m", "qaoa")):
        res = run(*args, "-p", "0")
        assert res.exit_code == 2 and "-p/--layers: must be at least 1, got 0" in res.stderr, args
    assert run("estimate", "-p", "0").exit_code == 2


def _reason(res) -> str:  # type: ignore[no-untyped-def]
    """The error line without the ``error:`` prefix and the per-command ``(see 'qcpp X --help')`` hint."""
    assert res.exit_code == 2, res.output
    (line,) = res.stderr.strip().splitlines()
    return line.removeprefix("error: ").split(" (see 'qcpp ")[0]


@pytest.mark.parametrize(
    ("estimate_args", "other_args", "expected"),
    [
        (("-p", "0"), ("compile", EX, "-p", "0"), "-p/--layers: must be at least 1, got 0"),
        (("-p", "5000"), ("compile", EX, "-p", "5000"), "-p/--layers: 5,000 layers is over the limit of 1,000"),
        (("--grid", "0x6"), ("verify", "--grid", "0x6"), "--grid: the grid must be at least 2x2, got 0x6"),
        (("--grid", "0x6"), ("compile", "--grid", "0x6"), "--grid: the grid must be at least 2x2, got 0x6"),
        (("--grid", "3"), ("compile", "--grid", "3"), "--grid: expected ROWSxCOLS such as 3x4, got '3'"),
        (("--grid", "60x60"), ("solve", "--grid", "60x60"), "--grid: a 60x60 grid has 3,600 nodes"),
        (("--device", "ibm_foo"), ("compile", EX, "--device", "ibm_foo"), "--device: unknown device 'ibm_foo' ("),
    ],
)
def test_one_wording_per_check_in_every_command(
    scratch: Path, estimate_args: tuple[str, ...], other_args: tuple[str, ...], expected: str
) -> None:
    """``qcpp estimate`` (ranges) and the single-scenario commands refuse the same value with the same line: the
    option first, then what is wrong and what was given."""
    mine, theirs = _reason(run("estimate", *estimate_args)), _reason(run(*other_args))
    assert mine == theirs and mine.startswith(expected), (mine, theirs)


@pytest.mark.parametrize(
    ("args", "expected"),
    [
        (("--robots", "0"), "--robots: must be at least 1, got 0"),
        (("-p", "1..0"), "-p/--layers: the range is empty (its end is below its start), got '1..0'"),
        (("-p", "x"), "-p/--layers: expected N, A..B or a comma list of them, got 'x'"),
        (("--grid", "4x4..3x3"), "--grid: the range is empty"),
    ],
)
def test_estimate_range_errors_name_the_option_first(scratch: Path, args: tuple[str, ...], expected: str) -> None:
    assert _reason(run("estimate", *args)).startswith(expected)


def test_byte_order_mark_is_not_content(scratch: Path) -> None:
    plain = run("solve", EX, "-m", "dfs", "--json")
    bom = run("solve", "bom.toml", "-m", "dfs", "--json")
    assert plain.exit_code == 0 and bom.exit_code == 0, bom.stderr
    assert json.loads(bom.stdout)["paths"] == json.loads(plain.stdout)["paths"]
    assert load_scenario("bom.json").grid.cols == 3


def test_symlink_is_followed_and_stays_a_link(scratch: Path) -> None:
    res = run("compile", EX, "--qasm", "link.qasm")
    assert res.exit_code == 0, res.stderr
    assert os.path.islink("link.qasm") and os.readlink("link.qasm") == "target.qasm"
    assert Path("target.qasm").read_text() == to_qasm3(qaoa_circuit(load_scenario(EX), 1))
    assert sorted(p.name for p in scratch.iterdir() if p.name.startswith(".")) == []


def test_devices_and_fifos_are_written_straight_to(scratch: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    # the reader thread may be slow to open the FIFO on a loaded machine: wait for it as long as it takes
    monkeypatch.setattr(qcpp.io.atomic, "FIFO_WAIT", 600.0)
    assert run("compile", EX, "--qasm", "/dev/null").exit_code == 0
    assert stat.S_ISCHR(os.stat("/dev/null").st_mode)
    received: list[bytes] = []
    reader = threading.Thread(target=lambda: received.append(Path("fifo").read_bytes()))
    reader.start()
    res = run("compile", EX, "--qasm", "fifo", "--qasm-version", "3")
    reader.join(timeout=600)  # an upper bound for a failed writer (the reader then never gets EOF)
    assert res.exit_code == 0, res.stderr
    assert received == [to_qasm3(qaoa_circuit(load_scenario(EX), 1)).encode()]
    assert stat.S_ISFIFO(os.lstat("fifo").st_mode)


def test_qasm_dash_is_standard_output(scratch: Path) -> None:
    res = run("compile", EX, "--qasm", "-")
    assert res.exit_code == 0, res.stderr
    assert res.stdout == to_qasm3(qaoa_circuit(load_scenario(EX), 1))
    assert "wrote standard output" in res.stderr


def test_help_shows_flags_as_flags() -> None:
    for cmd in ("solve", "simulate", "compile", "estimate", "validate"):
        res = CliRunner().invoke(app, [cmd, "--help"], env={"COLUMNS": "200"})
        assert res.exit_code == 0
        assert "<bool>" not in res.stdout and "--json" in res.stdout and "--allow-large" in res.stdout, cmd


def test_standard_output_on_a_full_disk_is_one_line(tmp_path: Path) -> None:
    with open("/dev/full", "w") as full:
        proc = subprocess.run(
            [sys.executable, "-m", "qcpp", "solve", str(EXAMPLE), "-m", "dfs"],
            stdout=full,
            stderr=subprocess.PIPE,
            text=True,
            env={**os.environ, "PYTHONPATH": str(REPO / "src")},
            check=False,
        )
    assert proc.returncode == 2
    assert proc.stderr.splitlines() == ["error: cannot write standard output: No space left on device"]


def test_a_check_that_did_not_run_never_reports_passed(scratch: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    import qcpp.simulate.validate as sv

    real = sv.validate

    def with_a_skipped_check(*args, **kwargs):  # type: ignore[no-untyped-def]
        report = real(*args, **kwargs)
        skipped = sv.Check("amplitudes", "tensor contraction", float("nan"), float("nan"), 0, "skipped", 0.0, "wide")
        return sv.ValidationReport(**{**report.__dict__, "checks": (*report.checks, skipped)})

    monkeypatch.setattr(sv, "validate", with_a_skipped_check)
    text = run("validate", "bom.json", "--backend", "statevector")  # a 2x3 grid: quick
    assert text.exit_code == 1 and "PASSED" not in text.stdout and "INCOMPLETE" in text.stdout
    js = run("validate", "bom.json", "--backend", "statevector", "--json")
    d = json.loads(js.stdout)
    assert js.exit_code == 1 and d["passed"] is False and d["verdict"] == "incomplete"
