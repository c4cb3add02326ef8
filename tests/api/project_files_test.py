"""The files a user of the package expects agree with each other: one version, the licence pyproject declares, the
type-hint marker shipped, the OpenQASM 3 importer of ``to_qiskit`` in the core install, the paper cited."""

from __future__ import annotations

import re
import sys
from pathlib import Path

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

ROOT = Path(__file__).resolve().parents[2]
PROJECT = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]


def test_one_version_in_pyproject_changelog_and_citation() -> None:
    version = PROJECT["version"]
    first = re.search(r"^## \[(\d+\.\d+\.\d+)\]", (ROOT / "CHANGELOG.md").read_text(), re.M)
    assert first is not None and first.group(1) == version
    assert re.search(rf"^version: {re.escape(version)}$", (ROOT / "CITATION.cff").read_text(), re.M)


def test_the_licence_file_is_the_one_pyproject_declares() -> None:
    text = (ROOT / "LICENSE").read_text()
    assert PROJECT["license"]["text"] == "MIT" and text.startswith("MIT License")
    assert "Copyright (c) 2026 The qcpp developers" in text


def test_the_citation_names_the_paper() -> None:
    text = (ROOT / "CITATION.cff").read_text()
    assert "arXiv:2407.08767" in text
    assert "A Quantum Computing Approach for Multi-robot Coverage Path Planning" in text


def test_type_hints_ship_and_qiskit_loads_openqasm_3_with_the_core_install() -> None:
    assert (ROOT / "src" / "qcpp" / "py.typed").is_file()
    setuptools = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]
    assert "py.typed" in setuptools["package-data"]["qcpp"]
    assert any(dep.startswith("qiskit-qasm3-import") for dep in PROJECT["dependencies"])
