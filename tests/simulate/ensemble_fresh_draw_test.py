"""benchmarks/ensemble_fresh_draw.py: the agreement check between the committed ensemble medians and a fresh draw."""

from __future__ import annotations

import json
import math
from pathlib import Path
from types import ModuleType

import pytest

from .script_module import load_script

SCRIPT = Path(__file__).resolve().parents[2] / "benchmarks" / "ensemble_fresh_draw.py"


def _script() -> ModuleType:
    return load_script(SCRIPT, "ensemble_fresh_draw")


def _results(path: Path, p_opts: list[float], dfs_s: float, seed: int) -> Path:
    rows = [{"cell": "3x3/1", "method": "qaoa", "p": 1, "p_opt": v, "best_p_opt": 2 * v, "tts_99": math.inf}
            for v in p_opts]
    rows += [{"cell": "3x3/1", "method": "dfs", "tts_99": dfs_s}]
    path.write_text(json.dumps({"config": {"seed": seed}, "rows": rows}), encoding="utf-8")
    return path


@pytest.mark.parametrize(("fresh", "code", "verdicts"), [
    ([0.15, 0.3, 0.45], 0, ["yes", "yes", "yes", "yes"]),  # medians 0.3 against 0.2: within 2x; both QAOA times inf
    ([0.5, 0.7, 0.9], 1, ["NO", "NO", "yes", "yes"]),  # medians 0.7 against 0.2: 3.5x
])
def test_the_fresh_draw_check_flags_medians_beyond_2x(
        tmp_path: Path, capsys: pytest.CaptureFixture[str], fresh: list[float], code: int, verdicts: list[str]) -> None:
    committed = _results(tmp_path / "committed.json", [0.1, 0.2, 0.3], 0.001, seed=0)
    other = _results(tmp_path / "fresh.json", fresh, 0.0015, seed=1)
    assert _script().main([str(committed), str(other)]) == code
    rows = [line.split("|") for line in capsys.readouterr().out.splitlines() if line.startswith("| 3x3/1")]
    assert sorted(r[-2].strip() for r in rows) == sorted(verdicts)
