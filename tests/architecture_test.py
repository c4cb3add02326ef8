"""The import structure of ``src/qcpp``: no import cycles between modules, and the subpackages stacked one way.

Every module is parsed (nothing is imported): each ``import`` and ``from ... import`` anywhere in it, at module
level, inside functions or under ``TYPE_CHECKING``, is an edge to the module it names (``from a import b`` is an
edge to ``a.b`` when that is a module, else to ``a``; relative imports are resolved against the package).

Layers, lowest first (a subpackage may import only the ones listed in :data:`ALLOWED` for it)::

    io < problem < qubo                                     the problem model and its file guards
    ir < lowering < gadgets < plan < hardware < routing < layout < pipeline < testing
       < estimators | simulate | verification < training < api < cli

``errors``, ``io`` and ``problem`` may be imported by anything above them (the compiler builds circuits *of* a
problem); ``qubo`` only by ``api`` and ``cli``. ``estimators``, ``simulate`` and ``verification`` are siblings:
they count resources, run states and check feasibility, and none imports another (what they need lives below
them), which keeps the graph acyclic by construction. ``training`` (QAOA angles trained and evaluated) runs the
simulators, so it sits above ``simulate``. ``testing`` (the hypothesis strategies) imports only the IR
and the problem; nothing in the library imports it. The package's ``__init__`` is the public facade: it re-exports
lazily from any layer, and any layer may read its version; ``qcpp/__main__.py`` is on top.

An edge that breaks the order and cannot be fixed yet goes into :data:`ALLOWED_EXCEPTIONS` (a cycle into
:data:`KNOWN_CYCLES`) with a one-line reason, so that the test still fails on any new violation.
"""

from __future__ import annotations

import ast
from collections.abc import Iterator, Mapping
from functools import cache
from pathlib import Path

import networkx as nx
import pytest

SRC = Path(__file__).resolve().parents[1] / "src"
PACKAGE = "qcpp"

_BASE = frozenset({"__init__", "errors", "io", "problem"})
_COMPILER = ("ir", "lowering", "gadgets", "plan", "hardware", "routing", "layout", "pipeline", "testing")
_USES = ("estimators", "simulate", "verification")


def _allowed() -> dict[str, frozenset[str]]:
    table: dict[str, frozenset[str]] = {
        "errors": frozenset(),  # qcpp/errors.py: the error hierarchy every layer raises
        "io": frozenset({"__init__", "errors"}),
        "problem": frozenset({"__init__", "errors", "io"}),
        "qubo": _BASE,
    }
    for i, name in enumerate(_COMPILER):
        table[name] = _BASE | set(_COMPILER[:i])
    for name in _USES:
        table[name] = _BASE | set(_COMPILER)
    table["training"] = _BASE | set(_COMPILER) | {"simulate"}
    table["api"] = _BASE | set(_COMPILER) | {"qubo", *_USES, "training"}
    table["cli"] = table["api"] | {"api"}
    table["__main__"] = table["cli"] | {"cli"}
    # qcpp/__init__.py is the public facade: it re-exports (lazily) from any layer, and every layer may read its
    # version; package __init__ files are left out of the cycle check, so this makes no circle.
    table["__init__"] = frozenset(table["__main__"] | {"api", "cli"}) - {"__init__"}
    return table


ALLOWED: dict[str, frozenset[str]] = _allowed()
"""Subpackage -> the subpackages its modules may import (its own is always allowed)."""

ALLOWED_EXCEPTIONS: dict[tuple[str, str], str] = {}
"""``(importing module, imported module)`` -> why this edge against the order is tolerated for now."""

KNOWN_CYCLES: dict[tuple[str, ...], str] = {}
"""Sorted modules of an import cycle -> why it is tolerated for now (the test fails on any other cycle)."""


class Source:
    """One module's file: its text and whether it is a package ``__init__``."""

    def __init__(self, text: str, is_package: bool) -> None:
        self.text, self.is_package = text, is_package


def _modules(root: Path = SRC) -> dict[str, Source]:
    """Dotted module name -> source, for every ``.py`` under ``root/qcpp`` (a package by its ``__init__``)."""
    out = {}
    for path in sorted((root / PACKAGE).rglob("*.py")):
        parts = list(path.relative_to(root).with_suffix("").parts)
        if parts[-1] == "__init__":
            parts.pop()
        out[".".join(parts)] = Source(path.read_text(encoding="utf-8"), path.name == "__init__.py")
    return out


def _resolve(name: str, modules: Mapping[str, Source]) -> str | None:
    """The longest prefix of ``name`` that is a module of the package, or ``None`` (not ours)."""
    while name and name not in modules:
        name = name.rpartition(".")[0]
    return name or None


@cache
def _named(module: str, text: str, is_package: bool) -> tuple[tuple[str, tuple[str, ...]], ...]:
    """Every import of one file as ``(module named, names taken from it)`` (``import a.b``: ``("a.b", ())``),
    relative imports resolved against the package; parsed once per text."""
    package = module if is_package else module.rpartition(".")[0]
    out: list[tuple[str, tuple[str, ...]]] = []
    for node in ast.walk(ast.parse(text, module)):
        if isinstance(node, ast.Import):
            out += [(alias.name, ()) for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")[: len(package.split(".")) - node.level + 1]
                full = ".".join([*base, node.module] if node.module else base)
            else:
                full = node.module or ""
            out.append((full, tuple(alias.name for alias in node.names)))
    return tuple(out)


def _imports(module: str, source: Source, modules: Mapping[str, Source]) -> Iterator[str]:
    """The package's modules that ``module`` imports anywhere in its file (``from a import b``: ``a.b`` when that
    is a module, else ``a``)."""
    for full, names in _named(module, source.text, source.is_package):
        if not names:
            targets = [_resolve(full, modules)]
        else:
            targets = [f"{full}.{n}" if f"{full}.{n}" in modules else _resolve(full, modules) for n in names]
        yield from (t for t in targets if t)


def import_graph(modules: Mapping[str, Source]) -> nx.DiGraph:
    """The module import graph (self-imports dropped)."""
    graph = nx.DiGraph()
    graph.add_nodes_from(modules)
    for module, source in modules.items():
        for target in _imports(module, source, modules):
            if target != module:
                graph.add_edge(module, target)
    return graph


def subpackage(module: str) -> str:
    """``qcpp.plan.qaoa`` -> ``plan``; ``qcpp.testing`` -> ``testing``; ``qcpp`` -> ``__init__``."""
    parts = module.split(".")
    return parts[1] if len(parts) > 1 else "__init__"


def import_cycles(graph: nx.DiGraph, modules: Mapping[str, Source]) -> list[tuple[str, ...]]:
    """Strongly connected components of more than one module, package ``__init__`` files left out (importing a
    package's ``__init__`` to reach a sibling is how Python works, not a design circle)."""
    plain = graph.subgraph(m for m in graph if not modules[m].is_package)
    return sorted(tuple(sorted(c)) for c in nx.strongly_connected_components(plain) if len(c) > 1)


def layer_violations(graph: nx.DiGraph) -> list[tuple[str, str]]:
    """Edges from a subpackage to one it may not import (:data:`ALLOWED`)."""
    out = []
    for a, b in graph.edges:
        sa, sb = subpackage(a), subpackage(b)
        if sa != sb and sb not in ALLOWED[sa]:
            out.append((a, b))
    return sorted(out)


@cache
def all_modules() -> dict[str, Source]:
    """Every module of the package (read once per test process, when a test first needs it: not at collection)."""
    return _modules()


@cache
def package_graph() -> nx.DiGraph:
    """The import graph of :func:`all_modules`."""
    return import_graph(all_modules())


def test_the_parser_sees_module_and_function_level_imports() -> None:
    # routing imports the device's geometry inside a function; the plan imports gadgets at module level
    assert package_graph().has_edge("qcpp.routing.sabre", "qcpp.hardware.device")
    assert package_graph().has_edge("qcpp.plan.call_graph", "qcpp.gadgets")
    assert package_graph().number_of_edges() > 300


def test_every_subpackage_has_a_layer() -> None:
    assert {subpackage(m) for m in all_modules()} <= set(ALLOWED)


MAX_MODULES_PER_FOLDER = 20
"""A folder of more modules holds more than one concept: split it by concept (its ``__init__`` not counted)."""
MAX_MODULE_LINES = 1_000
"""A module of more lines does more than one thing."""


def folder_sizes(root: Path = SRC) -> dict[str, int]:
    """Modules (``.py`` files but ``__init__.py``) per folder of the package, by path relative to ``root``."""
    sizes: dict[str, int] = {}
    for path in (root / PACKAGE).rglob("*.py"):
        if path.name != "__init__.py":
            folder = path.parent.relative_to(root).as_posix()
            sizes[folder] = sizes.get(folder, 0) + 1
    return sizes


def test_no_folder_holds_more_than_twenty_modules() -> None:
    sizes = folder_sizes()
    assert sizes["qcpp/simulate"] > 1 and sum(sizes.values()) > 100  # the count sees the package
    assert {f: n for f, n in sizes.items() if n > MAX_MODULES_PER_FOLDER} == {}


def test_no_module_exceeds_a_thousand_lines() -> None:
    lines = {name: src.text.count("\n") + (not src.text.endswith("\n")) for name, src in all_modules().items()}
    assert max(lines.values()) > 500  # the count sees the modules
    assert {m: n for m, n in lines.items() if n > MAX_MODULE_LINES} == {}


def test_the_folder_count_would_see_a_crowded_folder(tmp_path: Path) -> None:
    crowded = tmp_path / PACKAGE / "crowded"
    crowded.mkdir(parents=True)
    for i in range(MAX_MODULES_PER_FOLDER + 1):
        (crowded / f"m{i}.py").write_text("")
    (crowded / "__init__.py").write_text("")
    assert folder_sizes(tmp_path) == {f"{PACKAGE}/crowded": MAX_MODULES_PER_FOLDER + 1}


def test_no_import_cycles() -> None:
    cycles = [c for c in import_cycles(package_graph(), all_modules()) if c not in KNOWN_CYCLES]
    assert cycles == []


def test_subpackages_import_only_lower_layers() -> None:
    violations = [e for e in layer_violations(package_graph()) if e not in ALLOWED_EXCEPTIONS]
    assert violations == [], "imports against the layer order:\n" + "\n".join(f"{a} -> {b}" for a, b in violations)


def test_every_tolerated_exception_still_occurs() -> None:
    stale = [e for e in ALLOWED_EXCEPTIONS if e not in set(layer_violations(package_graph()))]
    stale += [c for c in KNOWN_CYCLES if c not in import_cycles(package_graph(), all_modules())]
    assert stale == [], f"these no longer occur; remove them: {stale}"


@pytest.mark.parametrize(
    ("added", "violation"),
    [
        (
            {"qcpp.plan.bad": "def f():\n    from qcpp.pipeline.device_compile import compile_for_device\n"},
            ("qcpp.plan.bad", "qcpp.pipeline.device_compile"),
        ),
        ({"qcpp.ir.bad": "from qcpp.cli import app\n"}, ("qcpp.ir.bad", "qcpp.cli.app")),
        ({"qcpp.problem.bad": "import qcpp.gadgets.blocks as b\n"}, ("qcpp.problem.bad", "qcpp.gadgets.blocks")),
    ],
)
def test_the_layer_check_fails_on_a_bad_import(added: dict[str, str], violation: tuple[str, str]) -> None:
    """The package with one module added that imports upwards (inside a function too): the check reports it."""
    modules = {**all_modules(), **{name: Source(text, False) for name, text in added.items()}}
    assert violation in layer_violations(import_graph(modules))
    assert violation not in layer_violations(package_graph())


def test_the_cycle_check_fails_on_a_circle() -> None:
    """Two modules importing each other (one relatively, one inside a function): the check reports the circle;
    through a package ``__init__`` it does not."""
    added = {
        "qcpp.gadgets.bad": Source("from qcpp.gadgets import loop\n", False),
        "qcpp.gadgets.loop": Source("def f():\n    from . import bad\n", False),
    }
    graph = import_graph({**all_modules(), **added})
    assert ("qcpp.gadgets.bad", "qcpp.gadgets.loop") in import_cycles(graph, {**all_modules(), **added})
    through_init = {"qcpp.gadgets.bad": Source("import qcpp.gadgets\n", False)}
    modules = {**all_modules(), **through_init}
    assert not any("qcpp.gadgets.bad" in c for c in import_cycles(import_graph(modules), modules))


ARCHITECTURE = Path(__file__).resolve().parents[1] / "docs" / "architecture.md"


def pictured_layers(text: str) -> tuple[list[str], set[str], set[str]]:
    """The subpackages of the first picture in ``docs/architecture.md``, top first; the siblings (``├─┬``,
    ``│ ├``, ``│ └`` lines); and those beside the stack."""
    block = text.split("```\n", 2)[1]
    names, siblings, beside = [], set(), set()
    for line in block.splitlines()[1:]:
        parts = line.replace("│", " ").split()
        if not parts or parts[0] not in ("├─", "└─", "├─┬", "├", "└"):
            continue
        names.append(parts[1])
        if parts[0] in ("├─┬", "├", "└"):
            siblings.add(parts[1])
        if parts[2:4] == ["beside", "the"]:
            beside.add(parts[1])
    return names, siblings, beside


def picture_mismatches(text: str) -> list[str]:
    """Where the picture and :data:`ALLOWED` differ: a subpackage may import exactly those the picture lists below
    it, but for siblings (none imports another) and what is beside the stack (imported by api and cli only);
    ``training`` runs ``simulate`` alone of the siblings."""
    names, siblings, beside = pictured_layers(text)
    out = []
    if sorted(names) != sorted(set(ALLOWED) - {"__init__", "__main__", "testing"}):
        out.append(f"pictured subpackages {names}")
    if siblings != set(_USES) or beside != {"qubo"}:
        out.append(f"siblings {sorted(siblings)}, beside the stack {sorted(beside)}")
    for i, name in enumerate(names):
        below = set(names[i + 1 :])
        if name in siblings:
            below -= siblings
        if name == "training":
            below -= siblings - {"simulate"}
        if name not in ("api", "cli"):
            below -= beside
        if name in ALLOWED and ALLOWED[name] - {"__init__", "testing"} != below:
            out.append(f"{name}: pictured above {sorted(below)}, allowed {sorted(ALLOWED[name])}")
    return out


def test_the_architecture_picture_is_the_layers_of_this_test() -> None:
    assert picture_mismatches(ARCHITECTURE.read_text(encoding="utf-8")) == []


def test_the_picture_check_sees_a_sibling_drawn_as_a_layer() -> None:
    text = ARCHITECTURE.read_text(encoding="utf-8")
    assert picture_mismatches(text.replace(" │ ├ simulate", " ├─ simulate", 1))
    assert picture_mismatches(text.replace(" ├─ qubo             beside the stack:", " ├─ qubo ", 1))
