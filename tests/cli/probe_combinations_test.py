"""Option combinations a new user tries that do not make sense together: one ``error:`` line naming the flag.

Found by an adversarial pass over the CLI (docs/cli.md, "Probed combinations"); each used to be ignored without a
word or to be refused without naming the flag.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from .clirun import assert_one_line_error, run

PAPER = str(Path(__file__).resolve().parents[2] / "examples" / "paper_3x3.toml")

REFUSED = [
    (("compile", PAPER, "--layout", "medial"), ("--layout medial", "--device")),
    (("compile", PAPER, "--layout", "greedy", "--json"), ("--layout greedy", "--device")),
    (("compile", PAPER, "--local-ancillas"), ("--local-ancillas", "--device")),
    (("solve", PAPER, "-m", "qaoa", "--objective", "cvar:2"), ("--objective", "cvar:2", "gibbs")),
    (("solve", PAPER, "-m", "qaoa", "--optimizer", "multi-angle", "--objective", "bogus"), ("--objective", "bogus")),
    (("simulate", PAPER, "--angles", "0.1,0.2,0.3"), ("--angles", "needs 2 angles", "got 3")),
    (("validate", PAPER, "--dask", "bogus"), ("--dask", "missing port number", "tcp://host:8786")),
    (("validate", PAPER, "--dask", "tcp://h"), ("--dask", "missing port number")),
]


@pytest.mark.parametrize(("args", "fragments"), REFUSED, ids=[" ".join((a[0], *a[2:])) for a, _ in REFUSED])
def test_combination_is_one_line_naming_the_flag(args: tuple[str, ...], fragments: tuple[str, ...]) -> None:
    assert_one_line_error(run(*args), *fragments)


def test_layout_auto_without_device_is_the_default_and_accepted() -> None:
    res = run("compile", PAPER, "--layout", "auto", "--json")
    assert res.exit_code == 0, res.output


def test_qaoa_training_too_big_for_memory_is_refused_before_enumerating(tmp_path: Path) -> None:
    """3 robots on 5x5: over 10^11 feasible assignments, so one state alone is terabytes; the size is named (the
    robots' paths counted together, 8,512 each), and the override."""
    path = tmp_path / "three_5x5.toml"
    robots = "".join(f"[[robots]]\nstart = {a}\ngoal = {b}\n" for a, b in (([0, 0], [4, 4]), ([0, 4], [4, 0]),
                                                                         ([4, 0], [0, 4])))
    path.write_text(f"[grid]\nrows = 5\ncols = 5\n{robots}")
    for optimizer in ("layerwise", "multi-angle"):
        res = run("solve", str(path), "-m", "qaoa", "--optimizer", optimizer)
        assert_one_line_error(res, "three_5x5.toml: training QAOA on 8,512 x 8,512 x 8,512 paths",
                              "616,729,673,728 feasible assignments", "GB available", "--allow-large")
