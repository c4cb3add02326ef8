"""Robustness classes that must stay held (docs/cli.md, "Robustness"): each through a real ``qcpp`` process.

Already covered elsewhere and not repeated here: a full disk for ``--qasm``, ``--plot`` and standard output
(``bad_input_test.py``), a closed or broken standard output (``closed_stdout_test.py``), FIFOs, symlinks and
oversized or deeply nested files (``bad_input_test.py``, ``input_limits_test.py``), an unusable cache folder named
by ``XDG_CACHE_HOME`` (``help_and_noise_test.py``). Here: output under ``/proc`` and in a read-only folder, four
concurrent writers of one output file, no ``HOME`` with an unusable cache folder, the C locale with non-ASCII
paths, ``NO_COLOR`` with ``TERM=dumb``, an address-space limit below a simulation's need, and hostile scenario
files (duplicated obstacles, 5,000 robots on a 3x3 grid, a 1x40 strip, a file over the size limit).

Every failure case expects the CLI's contract: one line ``error: ...`` on stderr, exit code 2, no traceback, and
no file left behind. No test depends on timing.
"""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from tests.cli.clirun import run

REPO = Path(__file__).resolve().parents[2]
EXAMPLES = REPO / "examples"
PAPER = EXAMPLES / "paper_3x3.toml"
ANSI = re.compile(r"\x1b\[")


def qcpp(*args: str | Path, env: dict[str, str] | None = None, unset: tuple[str, ...] = (), cwd: Path = REPO,
         preexec_fn=None) -> subprocess.CompletedProcess[str]:  # type: ignore[no-untyped-def]  # fmt: skip
    """Run ``python -m qcpp ARGS`` with this checkout's sources (``env`` added, ``unset`` removed)."""
    base = {k: v for k, v in os.environ.items() if k not in unset}
    full = {**base, "PYTHONPATH": str(REPO / "src"), "MPLBACKEND": "Agg", **(env or {})}
    return subprocess.run([sys.executable, "-m", "qcpp", *map(str, args)], cwd=cwd, env=full, capture_output=True,
                          text=True, timeout=600, preexec_fn=preexec_fn, check=False)  # fmt: skip


def assert_one_line_error(res: subprocess.CompletedProcess[str], *fragments: str) -> str:
    """Exit 2, one line ``error: ...`` naming ``fragments`` (progress lines aside), no traceback; the line."""
    assert res.returncode == 2, (res.returncode, res.stderr)
    assert "Traceback" not in res.stderr, res.stderr
    lines = [line for line in res.stderr.splitlines() if line.startswith("error: ")]
    assert len(lines) == 1, res.stderr
    for fragment in fragments:
        assert fragment in lines[0], (fragment, lines[0])
    return lines[0]


# ----------------------------------------------------------------------------- unwritable places


@pytest.mark.parametrize("target", ["/proc/qcpp-out.qasm", "/proc/self/qcpp/out.qasm"])
def test_output_under_proc_is_one_line_before_any_work(target: str) -> None:
    res = qcpp("compile", PAPER, "--qasm", target)
    assert_one_line_error(res, target)
    assert res.stdout == ""


@pytest.mark.skipif(os.name != "posix" or os.geteuid() == 0, reason="root writes into read-only folders")
def test_output_in_a_read_only_folder_is_one_line(tmp_path: Path) -> None:
    folder = tmp_path / "ro"
    folder.mkdir()
    folder.chmod(0o555)
    try:
        res = qcpp("compile", PAPER, "--qasm", folder / "out.qasm")
        assert_one_line_error(res, "out.qasm")
        assert list(folder.iterdir()) == []
    finally:
        folder.chmod(0o755)


def test_output_in_a_read_only_mount_is_one_line(tmp_path: Path) -> None:
    """As root a read-only folder is still writable; a read-only file system is not (``/proc/sys`` is one)."""
    res = qcpp("compile", PAPER, "--qasm", "/proc/sys/qcpp.qasm")
    assert_one_line_error(res, "/proc/sys/qcpp.qasm")


# ----------------------------------------------------------------------------- concurrent writers


@pytest.mark.slow
def test_four_concurrent_writers_of_one_file_leave_one_whole_output(tmp_path: Path) -> None:
    """Each writer writes a temporary file and renames it over the destination (qcpp.io.atomic): whichever
    rename comes last wins, and the file is always one writer's whole output, never a mix or a fragment."""
    out = tmp_path / "out.qasm"
    env = {**os.environ, "PYTHONPATH": str(REPO / "src"), "QCPP_PROGRESS": "off"}
    layers = ["1", "2", "3", "4"]  # four different outputs, so a mix would show
    procs = [subprocess.Popen([sys.executable, "-m", "qcpp", "compile", str(PAPER), "-p", p, "--qasm", str(out)],
                              env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
             for p in layers]  # fmt: skip
    errors = [proc.communicate(timeout=600)[1] for proc in procs]
    assert [proc.returncode for proc in procs] == [0, 0, 0, 0], errors
    text = out.read_text(encoding="utf-8")
    singles = []
    for p in layers:
        single = tmp_path / f"single{p}.qasm"  # the reference outputs in-process (no interpreter start each)
        assert run("compile", str(PAPER), "-p", p, "--qasm", str(single)).exit_code == 0
        singles.append(single.read_text(encoding="utf-8"))
    assert text in singles
    assert sorted(f.name for f in tmp_path.iterdir()) == sorted(["out.qasm", *(f"single{p}.qasm" for p in layers)])


# ----------------------------------------------------------------------------- odd environments


def test_no_home_and_an_unusable_cache_folder(tmp_path: Path) -> None:
    """Without ``HOME`` and with ``XDG_CACHE_HOME`` under /proc: commands run; the tensor backend says in one
    ``note:`` line that it runs without its on-disk cache."""
    env = {"XDG_CACHE_HOME": "/proc/qcpp-cache", "QCPP_PROGRESS": "off"}
    res = qcpp("solve", PAPER, "-m", "dfs", "--json", env=env, unset=("HOME", "QCPP_CACHE_DIR"))
    assert res.returncode == 0 and res.stderr == "", res.stderr
    res = qcpp("simulate", PAPER, "--json", env=env, unset=("HOME", "QCPP_CACHE_DIR"))
    assert res.returncode == 0 and "Traceback" not in res.stderr, res.stderr


@pytest.mark.heavy
def test_no_home_and_an_unusable_cache_folder_for_the_tensor_backend() -> None:
    env = {"XDG_CACHE_HOME": "/proc/qcpp-cache", "QCPP_PROGRESS": "off"}
    res = qcpp("validate", PAPER, "--backend", "tensor", env=env, unset=("HOME", "QCPP_CACHE_DIR"))
    assert res.returncode == 0, res.stderr
    notes = res.stderr.splitlines()
    assert len(notes) == 1 and notes[0].startswith("note: ") and "/proc/qcpp-cache" in notes[0], res.stderr


def test_the_c_locale_with_non_ascii_paths(tmp_path: Path) -> None:
    scenario = tmp_path / "scénario_ü.toml"
    shutil.copy(PAPER, scenario)
    out = tmp_path / "výstup_ü.qasm"
    c_locale = {"LC_ALL": "C"}
    unset = ("LANG", "LC_CTYPE", "PYTHONUTF8", "PYTHONIOENCODING")
    res = qcpp("compile", scenario, "--qasm", out, env=c_locale, unset=unset, cwd=tmp_path)
    assert res.returncode == 0, res.stderr
    assert out.read_text(encoding="utf-8").startswith("OPENQASM")
    res = qcpp("solve", tmp_path / "missing_ü.toml", env=c_locale, unset=unset, cwd=tmp_path)
    assert_one_line_error(res, "missing_ü.toml", "cannot read the file")


def test_no_color_and_a_dumb_terminal_print_no_escape_codes() -> None:
    env = {"NO_COLOR": "1", "TERM": "dumb", "QCPP_PROGRESS": "auto"}
    for args in (("solve", PAPER, "-m", "dfs"), ("validate", PAPER), ("estimate", "--grid", "3x3")):
        res = qcpp(*args, env=env)
        assert res.returncode == 0, res.stderr
        assert not ANSI.search(res.stdout) and not ANSI.search(res.stderr), args


SGR = re.compile(r"\x1b\[([0-9;]*)m")


def _colour_codes(text: str) -> list[str]:
    """The SGR sequences in ``text`` that set a colour (30-49, 90-107: foreground and background)."""
    found = []
    for match in SGR.finditer(text):
        params = [int(p) for p in match.group(1).split(";") if p]
        if any(30 <= p <= 49 or 90 <= p <= 107 for p in params):
            found.append(match.group(0))
    return found


def test_no_color_on_a_terminal_prints_no_colour() -> None:
    """``NO_COLOR=1`` asks for no colour (no-color.org): none on a terminal, where bold text and the progress bar
    (cursor movements) stay; ``TERM=dumb`` is what turns every escape code off (the test above)."""
    import pty

    leader, follower = pty.openpty()
    env = {**os.environ, "PYTHONPATH": str(REPO / "src"), "NO_COLOR": "1", "TERM": "xterm-256color",
           "QCPP_PROGRESS": "auto", "MPLBACKEND": "Agg"}  # fmt: skip
    proc = subprocess.Popen([sys.executable, "-m", "qcpp", "solve", str(PAPER), "-m", "dfs"], cwd=REPO, env=env,
                            stdin=subprocess.DEVNULL, stdout=follower, stderr=follower)  # fmt: skip
    os.close(follower)
    chunks = []
    try:
        while True:
            try:
                chunk = os.read(leader, 65536)
            except OSError:  # EIO: every writer closed the terminal
                break
            if not chunk:
                break
            chunks.append(chunk)
    finally:
        os.close(leader)
        proc.wait(timeout=600)
    text = b"".join(chunks).decode("utf-8", errors="replace")
    assert proc.returncode == 0, text
    assert "assignments scored" in text
    assert _colour_codes(text) == [], text


# ----------------------------------------------------------------------------- memory limits


def _address_space(limit: int):  # type: ignore[no-untyped-def]
    def apply() -> None:
        import resource

        resource.setrlimit(resource.RLIMIT_AS, (limit, limit))

    return apply


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="RLIMIT_AS and /proc/self/statm: Linux")
def test_an_address_space_limit_below_the_need_is_refused_before_the_work() -> None:
    """Under ``ulimit -v`` of 2.5 GB the two-robot 5x5 simulation (3.1 GB) does not fit: the guard sees the
    limit and refuses in one line naming the prediction, before anything is built."""
    res = qcpp("simulate", EXAMPLES / "two_robots_5x5.toml", preexec_fn=_address_space(2_500_000_000))
    assert_one_line_error(res, "two_robots_5x5.toml", "predicted peak 3.1 GB", "GB available", "--allow-large")


@pytest.mark.heavy
@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="RLIMIT_AS: Linux")
def test_running_out_of_address_space_anyway_is_one_line() -> None:
    """With ``--allow-large`` the guard is lifted and the simulation runs into the limit: ``MemoryError``
    becomes one line and exit 2."""
    res = qcpp("simulate", EXAMPLES / "two_robots_5x5.toml", "--allow-large", env={"QCPP_PROGRESS": "off"},
               preexec_fn=_address_space(2_500_000_000))  # fmt: skip
    assert_one_line_error(res, "out of memory")


# ----------------------------------------------------------------------------- hostile files


def _obstacles_file(path: Path, copies: int) -> Path:
    obstacles = ", ".join(["[1, 1]"] * copies)
    path.write_text(f"[grid]\nrows = 3\ncols = 3\nobstacles = [{obstacles}]\n[[robots]]\nstart = [0, 0]\n"
                    "goal = [2, 2]\n", encoding="utf-8")  # fmt: skip
    return path


def test_duplicated_obstacles_are_refused_by_name(tmp_path: Path) -> None:
    path = _obstacles_file(tmp_path / "dup.toml", 20_000)
    assert_one_line_error(qcpp("solve", path, "-m", "dfs"), "grid.obstacles[1]: (1, 1) is listed twice")


@pytest.mark.heavy
def test_a_large_file_of_duplicated_obstacles_is_refused_by_name(tmp_path: Path) -> None:
    path = _obstacles_file(tmp_path / "dup.toml", 600_000)  # 4.8 MB: under the size limit, so it is parsed
    assert_one_line_error(qcpp("solve", path, "-m", "dfs"), "grid.obstacles[1]: (1, 1) is listed twice")


def test_a_scenario_file_over_the_size_limit_is_refused_unread(tmp_path: Path) -> None:
    path = _obstacles_file(tmp_path / "big.toml", 2_600_000)  # about 21 MB
    assert_one_line_error(qcpp("simulate", path), "big.toml")


ONE_LOADER = ["solve", *(pytest.param(c, marks=pytest.mark.heavy) for c in ("simulate", "compile"))]
"""Every command reads a scenario through one loader: the default run asks one of them, the heavy step the others."""


@pytest.mark.parametrize("command", ONE_LOADER)
def test_five_thousand_robots_on_a_3x3_grid(tmp_path: Path, command: str) -> None:
    path = tmp_path / "crowd.toml"
    path.write_text("[grid]\nrows = 3\ncols = 3\n" + "[[robots]]\nstart = [0, 0]\ngoal = [2, 2]\n" * 5000,
                    encoding="utf-8")  # fmt: skip
    assert_one_line_error(qcpp(command, path), "5000 robots do not fit on the 9 free nodes")


@pytest.mark.parametrize("command", ONE_LOADER)
def test_a_1x40_strip(tmp_path: Path, command: str) -> None:
    path = tmp_path / "strip.toml"
    path.write_text("[grid]\nrows = 1\ncols = 40\n[[robots]]\nstart = [0, 0]\ngoal = [0, 39]\n", encoding="utf-8")
    assert_one_line_error(qcpp(command, path), "grid.rows", "at least 2x2, got 1x40")
