"""Scenarios: loading TOML/JSON, the lossless round trip, validation errors naming the field, derived data."""

from __future__ import annotations

import copy
import json
import math
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from qcpp.io.atomic import write_text_atomic
from qcpp.problem.errors import ScenarioError
from qcpp.problem.grid import Grid
from qcpp.problem.scenario import Objective, Robot, Scenario, scenario_from_dict, scenario_to_dict
from qcpp.problem.scenario_io import load_scenario, save_scenario, scenario_to_toml

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"

BASE: dict[str, Any] = {
    "name": "base",
    "grid": {"rows": 3, "cols": 3, "obstacles": [[1, 1]]},
    "robots": [{"start": [0, 0], "goal": [2, 2]}],
    "objective": {"alpha": [1.0, 2.0, 3.0], "obstacles": "soft"},
}

TOML_TEXT = """
name = "from toml"
[grid]
rows = 3
cols = 4
obstacles = [[1, 1], [0, 2]]

[[robots]]
start = [0, 0]
goal = [2, 3]

[[robots]]
start = [2, 0]
goal = [0, 3]

[objective]
alpha = [1, 0.5, 2]
obstacle_weight = 4
edge_lengths = [[[0, 1], [0, 0], 2.5]]
balance = "all-pairs"
degree_target = "paper"
"""


def _check_toml_scenario(s: Scenario) -> None:
    assert s.name == "from toml"
    assert s.grid == Grid(3, 4)
    assert s.obstacles == ((0, 2), (1, 1))  # sorted row-major on the way in
    assert s.robots == (Robot((0, 0), (2, 3)), Robot((2, 0), (0, 3)))
    ob = s.objective
    assert ob.alpha == (1.0, 0.5, 2.0)
    assert ob.obstacle_weight == 4.0
    assert ob.free_weight == Objective().free_weight  # default
    assert ob.edge_length == 1.0
    assert ob.edge_lengths == ((((0, 0), (0, 1)), 2.5),)  # (u, v) normalised
    assert (ob.obstacles, ob.balance, ob.degree_target) == ("soft", "all-pairs", "paper")


def test_load_toml_and_json(tmp_path: Path) -> None:
    p = tmp_path / "s.toml"
    p.write_text(TOML_TEXT, encoding="utf-8")
    s = load_scenario(p)
    _check_toml_scenario(s)
    j = tmp_path / "s.json"
    j.write_text(json.dumps(scenario_to_dict(s)), encoding="utf-8")
    assert load_scenario(j) == s
    # a hand-written minimal JSON file takes every default
    m = tmp_path / "m.json"
    m.write_text('{"grid": {"rows": 2, "cols": 3}, "robots": [{"start": [0, 0], "goal": [1, 2]}]}', encoding="utf-8")
    s2 = load_scenario(m)
    assert s2.objective == Objective() and s2.obstacles == () and s2.name == ""


def test_file_suffix_is_case_insensitive(tmp_path: Path) -> None:
    p = tmp_path / "S.TOML"
    p.write_text(TOML_TEXT, encoding="utf-8")
    _check_toml_scenario(load_scenario(p))


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(data=st.data())
def test_round_trip(data: st.DataObject, scenario_dict_strategy: Any, tmp_path_factory: pytest.TempPathFactory) -> None:
    _assert_round_trip(data, scenario_dict_strategy, tmp_path_factory)


@pytest.mark.heavy
@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(data=st.data())
def test_round_trip_on_more_scenarios(
    data: st.DataObject, scenario_dict_strategy: Any, tmp_path_factory: pytest.TempPathFactory
) -> None:
    """The default run's property on 150 scenarios (it writes two files each)."""
    _assert_round_trip(data, scenario_dict_strategy, tmp_path_factory)


def _assert_round_trip(
    data: st.DataObject, scenario_dict_strategy: Any, tmp_path_factory: pytest.TempPathFactory
) -> None:
    d = data.draw(scenario_dict_strategy(tame_numbers=False, names=True))
    s = scenario_from_dict(d)
    assert scenario_from_dict(scenario_to_dict(s)) == s
    folder = tmp_path_factory.mktemp("rt")
    for suffix in (".toml", ".json"):
        path = folder / f"s{suffix}"
        save_scenario(s, path)
        assert load_scenario(path) == s
    # the written dict is complete: every objective key present
    assert set(scenario_to_dict(s)["objective"]) == set(d["objective"])


@pytest.mark.parametrize(
    "name", ["plain", "emoji \U0001f600 here", 'quote " and back\\slash', "tab\tnl\n\x7f\x00", "\u2028"]
)
def test_names_survive_toml(tmp_path: Path, name: str) -> None:
    s = scenario_from_dict({**BASE, "name": name})
    path = tmp_path / "n.toml"
    save_scenario(s, path)
    assert load_scenario(path) == s


def test_lone_surrogate_name_cannot_be_toml(tmp_path: Path) -> None:
    s = scenario_from_dict({**BASE, "name": "bad \ud800"})
    with pytest.raises(ScenarioError) as exc:
        scenario_to_toml(s)
    assert exc.value.field == "name"
    save_scenario(s, tmp_path / "ok.json")  # JSON escapes it
    assert load_scenario(tmp_path / "ok.json") == s


def _with(path: str, value: Any) -> dict[str, Any]:
    """BASE with the value at a dotted path (``robots.0.start``) set; ``...`` deletes the key."""
    d = copy.deepcopy(BASE)
    keys = path.split(".")
    node: Any = d
    for k in keys[:-1]:
        node = node[int(k)] if isinstance(node, list) else node[k]
    last = keys[-1]
    if isinstance(node, list):
        node[int(last)] = value
    elif value is ...:
        del node[last]
    else:
        node[last] = value
    return d


BAD_INPUTS = [
    # nodes outside the grid
    (_with("grid.obstacles", [[3, 0]]), "grid.obstacles[0]", "outside"),
    (_with("robots.0.start", [0, 5]), "robots[0].start", "outside"),
    (_with("robots.0.goal", [-1, 0]), "robots[0].goal", "outside"),
    (_with("objective.edge_lengths", [[[0, 2], [0, 3], 2.0]]), "objective.edge_lengths[0]", "outside"),
    (_with("objective.edge_lengths", [[[0, 0], [1, 1], 2.0]]), "objective.edge_lengths[0]", "not grid neighbours"),
    # endpoints on obstacles, equal endpoints
    (_with("robots.0.start", [1, 1]), "robots[0].start", "obstacle"),
    (_with("robots.0.goal", [1, 1]), "robots[0].goal", "obstacle"),
    (_with("robots.0.goal", [0, 0]), "robots[0].goal", "equals the start"),
    # grid sizes
    (_with("grid.rows", 1), "grid.rows", "at least 2x2"),
    (_with("grid.cols", 1), "grid.cols", "at least 2x2"),
    (_with("grid.rows", 0), "grid.rows", "at least 2x2"),
    (_with("grid.rows", -3), "grid.rows", "at least 2x2"),
    (_with("grid.cols", 2.5), "grid.cols", "integer"),
    (_with("grid.rows", 3.0), "grid.rows", "integer"),
    (_with("grid.rows", "3"), "grid.rows", "integer"),
    (_with("grid.rows", True), "grid.rows", "integer"),
    (_with("grid.cols", None), "grid.cols", "integer"),
    # unknown keys at every level (the message names the key)
    ({**BASE, "robot": []}, "robot", "unknown key"),
    (_with("grid.size", 3), "grid.size", "unknown key"),
    (_with("robots.0.speed", 1.0), "robots[0].speed", "unknown key"),
    (_with("objective.beta", 1.0), "objective.beta", "unknown key"),
    # missing required keys
    (_with("grid", ...), "grid", "missing"),
    (_with("grid.rows", ...), "grid.rows", "missing"),
    (_with("robots", ...), "robots", "missing"),
    (_with("robots.0.goal", ...), "robots[0].goal", "missing"),
    (_with("robots", []), "robots", "at least one robot"),
    # wrong types
    (_with("grid", [3, 3]), "grid", "table"),
    (_with("robots", {"start": [0, 0]}), "robots", "list"),
    (_with("robots", "r"), "robots", "list"),
    (_with("robots.0", [[0, 0], [2, 2]]), "robots[0]", "table"),
    (_with("objective", 3), "objective", "table"),
    (_with("name", 5), "name", "string"),
    (_with("robots.0.start", "0,0"), "robots[0].start", "two integers"),
    (_with("robots.0.start", [0]), "robots[0].start", "two integers"),
    (_with("robots.0.start", [0, 0, 0]), "robots[0].start", "two integers"),
    (_with("robots.0.start", [True, 0]), "robots[0].start", "two integers"),
    (_with("robots.0.goal", [2.0, 2]), "robots[0].goal", "two integers"),
    (_with("grid.obstacles", "1,1"), "grid.obstacles", "list"),
    (_with("grid.obstacles", [[1]]), "grid.obstacles[0]", "two integers"),
    (_with("objective.alpha", 1), "objective.alpha", "list"),
    (_with("objective.alpha", [1, 2]), "objective.alpha", "3 numbers"),
    (_with("objective.alpha", [1, "a", 3]), "objective.alpha[1]", "number"),
    (_with("objective.alpha", [1, True, 3]), "objective.alpha[1]", "number"),
    (_with("objective.alpha", [1, 1, math.inf]), "objective.alpha[2]", "finite"),
    (_with("objective.obstacle_weight", "x"), "objective.obstacle_weight", "number"),
    (_with("objective.obstacle_weight", 10**400), "objective.obstacle_weight", "finite"),
    (_with("objective.free_weight", None), "objective.free_weight", "number"),
    (_with("objective.free_weight", math.nan), "objective.free_weight", "finite"),
    (_with("objective.edge_length", 0), "objective.edge_length", "positive"),
    (_with("objective.edge_length", -1.5), "objective.edge_length", "positive"),
    (_with("objective.edge_lengths", [[[0, 0], [0, 1]]]), "objective.edge_lengths[0]", "length"),
    (_with("objective.edge_lengths", [[[0, 0], [0, 1], 0.0]]), "objective.edge_lengths[0]", "positive"),
    (_with("objective.edge_lengths", [[[0, 0], [0, 1], "2"]]), "objective.edge_lengths[0]", "number"),
    (
        _with("objective.edge_lengths", [[[0, 0], [0, 1], 2.0], [[0, 1], [0, 0], 3.0]]),
        "objective.edge_lengths[1]",
        "listed twice",
    ),
    (_with("objective.obstacles", "none"), "objective.obstacles", "expected one of"),
    (_with("objective.balance", "pairs"), "objective.balance", "expected one of"),
    (_with("objective.degree_target", 2), "objective.degree_target", "string"),
    (_with("objective.degree_target", "Exact"), "objective.degree_target", "expected one of"),
    # infeasible scenarios
    (
        {
            "grid": {"rows": 3, "cols": 3, "obstacles": [[0, 1], [1, 1], [2, 1]]},
            "robots": [{"start": [0, 0], "goal": [0, 2]}],
            "objective": {"obstacles": "hard"},
        },
        "robots[0].goal",
        "cannot be reached",
    ),
    (
        {
            "grid": {"rows": 2, "cols": 2, "obstacles": [[0, 0], [0, 1], [1, 0]]},
            "robots": [{"start": [1, 1], "goal": [0, 0]}, {"start": [1, 1], "goal": [0, 1]}],
        },
        "robots",
        "do not fit",
    ),
    (
        {
            "grid": {"rows": 2, "cols": 2},
            "robots": [{"start": [0, 0], "goal": [1, 1]}, {"start": [0, 0], "goal": [0, 1]}],
        },
        "robots[1].start",
        "already robot 0's start",
    ),
    (_with("grid.obstacles", [[1, 1], [2, 0], [1, 1]]), "grid.obstacles[2]", "listed twice"),
]


@pytest.mark.parametrize(("data", "field", "reason"), BAD_INPUTS, ids=[f"{b[1]}-{i}" for i, b in enumerate(BAD_INPUTS)])
def test_bad_input_names_the_field(data: Any, field: str, reason: str) -> None:
    with pytest.raises(ScenarioError) as exc:
        scenario_from_dict(data)
    assert exc.value.field == field
    assert reason in exc.value.reason
    assert str(exc.value).startswith(f"{field}: ")


def test_unknown_key_message_names_the_key() -> None:
    for data, key in [
        ({**BASE, "robot": []}, "robot"),
        (_with("grid.size", 3), "size"),
        (_with("robots.0.speed", 1), "speed"),
        (_with("objective.beta", 1), "beta"),
    ]:
        with pytest.raises(ScenarioError, match=rf"\b{key}\b.*unknown key"):
            scenario_from_dict(data)


def test_the_hard_mode_wall_is_fine_in_soft_mode() -> None:
    d = {
        "grid": {"rows": 3, "cols": 3, "obstacles": [[0, 1], [1, 1], [2, 1]]},
        "robots": [{"start": [0, 0], "goal": [0, 2]}],
    }
    assert scenario_from_dict(d).objective.obstacles == "soft"


def test_not_a_mapping_at_all() -> None:
    with pytest.raises(ScenarioError) as exc:
        scenario_from_dict([1, 2])  # type: ignore[arg-type]
    assert exc.value.field == "scenario"


@pytest.mark.parametrize(
    ("name", "content", "reason"),
    [
        ("bad.toml", b"[grid\nrows = 3\n", "not valid TOML"),
        ("bad.json", b'{"grid": {"rows": 3,', "not valid JSON"),
        ("bad.toml", b"\xff\xfe[grid]\n", "UTF-8"),
        ("bad.yaml", b"grid: {}\n", "unknown file type"),
    ],
)
def test_bad_files(tmp_path: Path, name: str, content: bytes, reason: str) -> None:
    p = tmp_path / name
    p.write_bytes(content)
    with pytest.raises(ScenarioError) as exc:
        load_scenario(p)
    assert exc.value.field == str(p)
    assert reason in exc.value.reason


def test_missing_file_and_folder(tmp_path: Path) -> None:
    for p in (tmp_path / "nope.toml", tmp_path):
        with pytest.raises(ScenarioError, match="cannot read the file") as exc:
            load_scenario(p)
        assert exc.value.field == str(p)


def test_file_errors_are_prefixed_with_the_file_name(tmp_path: Path) -> None:
    p = tmp_path / "wrong.toml"
    p.write_text("[grid]\nrows = 1\ncols = 3\n[[robots]]\nstart = [0, 0]\ngoal = [0, 2]\n", encoding="utf-8")
    with pytest.raises(ScenarioError) as exc:
        load_scenario(p)
    assert exc.value.field == "wrong.toml: grid.rows"


def test_save_rejects_unknown_suffix_and_leaves_nothing(tmp_path: Path) -> None:
    s = scenario_from_dict(BASE)
    with pytest.raises(ScenarioError, match="unknown file type"):
        save_scenario(s, tmp_path / "s.yaml")
    assert list(tmp_path.iterdir()) == []


def test_save_writes_a_device_or_fifo_straight_to_in_toml(tmp_path: Path) -> None:
    """``/dev/null`` and a FIFO have no suffix: they are written to (TOML), not refused as an unknown type."""
    import os
    import threading

    s = scenario_from_dict(BASE)
    save_scenario(s, "/dev/null")
    fifo = tmp_path / "out"
    os.mkfifo(fifo)
    got: list[str] = []
    reader = threading.Thread(target=lambda: got.append(fifo.read_text()))
    reader.start()
    save_scenario(s, fifo)
    reader.join(10)
    assert got == [scenario_to_toml(s)]
    with pytest.raises(ScenarioError, match="unknown file type"):
        save_scenario(s, tmp_path / "plain")  # a regular file (new) still needs a suffix


def test_write_text_atomic_replaces_whole_file(tmp_path: Path) -> None:
    p = tmp_path / "f.txt"
    p.write_text("old content that is longer", encoding="utf-8")
    write_text_atomic(p, "new")
    assert p.read_text(encoding="utf-8") == "new"
    assert [q.name for q in tmp_path.iterdir()] == ["f.txt"]  # no temp file left behind


def test_direct_construction_validates() -> None:
    r = (Robot((0, 0), (1, 1)),)
    for kwargs, field in [
        ({"grid": Grid(1, 3)}, "grid.rows"),
        ({"grid": Grid(True, 3)}, "grid.rows"),  # type: ignore[arg-type]
        ({"grid": Grid(2, 2), "obstacles": ((1, 0), (0, 1))}, "grid.obstacles"),
        ({"grid": Grid(2, 2), "robots": ()}, "robots"),
        ({"grid": Grid(2, 2), "objective": Objective(alpha=(1.0, 2.0))}, "objective.alpha"),  # type: ignore[arg-type]
        ({"grid": Grid(2, 2), "objective": Objective(obstacles="firm")}, "objective.obstacles"),  # type: ignore[arg-type]
        # edge lengths must be stored as the file loader stores them, or the round trip would change them
        (
            {"grid": Grid(2, 2), "objective": Objective(edge_lengths=((((0, 1), (0, 0)), 2.0),))},
            "objective.edge_lengths[0]",
        ),
        (
            {
                "grid": Grid(2, 2),
                "objective": Objective(edge_lengths=((((0, 1), (1, 1)), 2.0), (((0, 0), (0, 1)), 2.0))),
            },
            "objective.edge_lengths",
        ),
    ]:
        kwargs.setdefault("robots", r)
        with pytest.raises(ScenarioError) as exc:
            Scenario(**kwargs)
        assert exc.value.field == field


def test_variables_and_derived_data(build: Any) -> None:
    obstacles = [(1, 1), (0, 2)]
    for mode in ("soft", "hard"):
        s = build(3, 3, [((0, 0), (2, 2)), ((2, 0), (0, 1))], obstacles, mode=mode, obstacle_weight=5.0,
                  free_weight=-2.0, edge_length=1.5, edge_lengths=[[[0, 0], [0, 1], 4.0]])
        g = s.grid
        touching = {e for e, (u, v) in enumerate(g.edges) if u in obstacles or v in obstacles}
        assert s.obstacle_edges == touching
        expected_vars = [e for e in range(g.num_edges) if mode == "soft" or e not in touching]
        assert list(s.variable_edges) == expected_vars
        assert s.variable_mask == sum(1 << e for e in expected_vars)
        assert s.edges_per_robot == len(expected_vars) and s.num_variables == 2 * len(expected_vars)
        seen = set()
        for r in range(2):
            for k, e in enumerate(expected_vars):
                i = s.variable_index(r, e)
                assert i == r * len(expected_vars) + k
                assert s.variable_of(i) == (r, e)
                seen.add(i)
        assert seen == set(range(s.num_variables))
        if mode == "hard":
            with pytest.raises(KeyError, match="not a decision variable"):
                s.variable_index(0, min(touching))
        w = [5.0 if e in touching else -2.0 for e in range(g.num_edges)]
        assert np.array_equal(s.edge_weights, w)
        d = [4.0 if g.edges[e] == ((0, 0), (0, 1)) else 1.5 for e in range(g.num_edges)]
        assert np.array_equal(s.edge_lengths, d)


def test_bundled_examples_load() -> None:
    files = sorted(EXAMPLES.glob("*.toml")) + sorted(EXAMPLES.glob("*.json"))
    names = {p.name for p in files}
    for want in ("paper_3x3.toml", "paper_3x3.json", "two_robots_4x4.toml", "two_robots_5x5.toml",
                 "obstacles_hard_4x4.toml"):
        assert want in names
    loaded = {p.name: load_scenario(p) for p in files}
    assert loaded["paper_3x3.json"] == loaded["paper_3x3.toml"]
    for name, s in loaded.items():
        assert s.name, f"{name} has no name"
        assert load_scenario(EXAMPLES / name) == scenario_from_dict(scenario_to_dict(s))
    assert loaded["obstacles_hard_4x4.toml"].objective.obstacles == "hard"
    assert loaded["paper_3x3.toml"].objective.obstacles == "soft"
    assert loaded["paper_3x3.toml"].num_robots == 1 and loaded["paper_3x3.toml"].num_variables == 12


@pytest.mark.parametrize(
    ("data", "field"),
    [
        (_with("grid.obstacles", [[5, 0], [0, 0]]), "grid.obstacles[0]"),
        (_with("grid.obstacles", [[2, 2], [0, 1], [2, 2]]), "grid.obstacles[2]"),
        (_with("objective.edge_lengths", [[[0, 1], [0, 2], 2.0], [[0, 0], [0, 5], 1.0]]), "objective.edge_lengths[1]"),
        (_with("objective.edge_lengths", [[[1, 1], [1, 2], 2.0], [[0, 0], [0, 1], -1.0]]), "objective.edge_lengths[1]"),
    ],
)
def test_list_errors_use_the_index_as_written(data: Any, field: str) -> None:
    """Lists are sorted on the way in; an error must still point at the entry as the user wrote it."""
    with pytest.raises(ScenarioError) as exc:
        scenario_from_dict(data)
    assert exc.value.field == field
