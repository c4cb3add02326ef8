"""The files a user of the package expects agree with each other: one version, the licence pyproject declares, the
wheel as built (one import package, the type-hint marker, the device files and the licence in it), the OpenQASM 3
importer of ``to_qiskit`` in the core install, the paper cited."""

from __future__ import annotations

import re
import sys
import zipfile
from pathlib import Path

import pytest

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
    assert PROJECT["license"] == "MIT" and PROJECT["license-files"] == ["LICENSE"] and text.startswith("MIT License")
    assert "Copyright (c) 2026 The qcpp developers" in text


def test_the_citation_names_the_paper() -> None:
    text = (ROOT / "CITATION.cff").read_text()
    assert "arXiv:2407.08767" in text
    assert "A Quantum Computing Approach for Multi-robot Coverage Path Planning" in text


def test_the_wheel_holds_one_import_package_its_data_and_the_licence(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """The wheel pip builds (by the backend pyproject names, in-process): ``qcpp`` and its metadata alone at the top,
    every module and data file of ``src/qcpp`` (the type-hint marker, the device files) and no byte-code."""
    from flit_core import buildapi

    backend = tomllib.loads((ROOT / "pyproject.toml").read_text())["build-system"]["build-backend"]
    assert backend == "flit_core.buildapi"
    monkeypatch.chdir(ROOT)
    with zipfile.ZipFile(tmp_path / buildapi.build_wheel(str(tmp_path))) as wheel:
        names = set(wheel.namelist())
    dist_info = f"qcpp-{PROJECT['version']}.dist-info"
    assert {n.split("/")[0] for n in names} == {"qcpp", dist_info}
    sources = {str(f.relative_to(ROOT / "src")) for f in (ROOT / "src" / "qcpp").rglob("*")
               if f.is_file() and "__pycache__" not in f.parts}  # fmt: skip
    assert {n for n in names if n.startswith("qcpp/")} == sources
    assert {"qcpp/py.typed", "qcpp/hardware/data/ibm_fez.json", f"{dist_info}/licenses/LICENSE"} <= names


def test_qiskit_loads_openqasm_3_with_the_core_install() -> None:
    assert any(dep.startswith("qiskit-qasm3-import") for dep in PROJECT["dependencies"])
