"""Scenario files: load a :class:`~qcpp.problem.scenario.Scenario` from TOML or JSON, save one back.

The loader guards the read (size, encoding, nesting depth, keys given twice) before parsing, builds the value with
:func:`~qcpp.problem.scenario.scenario_from_dict` (which validates every field), and on request refuses weights the
solvers or the QAOA phases cannot represent exactly (:mod:`qcpp.problem.cost_range`). Saving writes the file
atomically; ``load_scenario(path)`` after ``save_scenario(s, path)`` gives ``s`` back.

Example:
    >>> import tempfile, pathlib
    >>> from qcpp.problem.presets import default_scenario
    >>> s = default_scenario(3, 3, 1)
    >>> with tempfile.TemporaryDirectory() as d:
    ...     path = pathlib.Path(d) / "s.toml"
    ...     save_scenario(s, path)
    ...     load_scenario(path, check_range=True) == s
    True
"""

from __future__ import annotations

import json
import os
import re
import sys
from pathlib import Path
from typing import Any

import numpy as np

from qcpp.errors import OptionError
from qcpp.io.atomic import STDOUT_NAMES, write_text_atomic
from qcpp.io.inputs import InputError, read_bounded
from qcpp.problem.cost_range import check_cost_range, check_phase_range
from qcpp.problem.errors import ScenarioError
from qcpp.problem.scenario import Scenario, scenario_from_dict, scenario_to_dict

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

MAX_SCENARIO_BYTES = 16 << 20
"""Largest scenario file :func:`load_scenario` reads (16 MiB)."""


STDIN = "-"
"""The file name :func:`load_scenario` reads as standard input (``qcpp scenario ... | qcpp solve -``)."""

STDIN_LABEL = "standard input"
"""How messages name standard input (the name ``-`` says nothing in an error line)."""

_STREAM_DIRS = ("/dev/", "/proc/")
"""Names under these folders (``/dev/stdin``, ``/dev/fd/N`` of ``<(...)``) are streams whatever they point at."""


def load_scenario(
    path: str | os.PathLike[str], *, check_range: bool = False, phases: bool = False
) -> Scenario:
    """Load a scenario from a ``.toml`` or ``.json`` file, or from standard input (``path="-"``).

    The format is the suffix's. Standard input (``-``) and files without one of the two suffixes that are not
    regular files (a pipe such as ``/dev/stdin`` or the ``/dev/fd/N`` of a shell's ``<(...)``, a FIFO, a device)
    are read first and their format told from the content (:func:`sniff_format`: JSON starts with ``{``, anything
    else is read as TOML); a regular file with another suffix is refused before it is opened. The file is UTF-8,
    with or without a byte order mark, at most :data:`MAX_SCENARIO_BYTES`, nested at most :data:`MAX_NESTING`
    levels deep, and no object/table may give a key twice (JSON parsers would silently keep the last value). FIFOs
    and devices are read with a time limit, a pipe the process was handed (standard input, ``/dev/fd/N``) for as
    long as its writer takes (:func:`qcpp.io.inputs.read_bounded`).

    Args:
        path: The file, or ``-`` for standard input (refused when it is a terminal: nothing was piped in).
        check_range: Also refuse weights the solvers cannot represent exactly
            (:func:`qcpp.problem.cost_range.check_cost_range`; the command line does).
        phases: With ``check_range``: the narrower range in which the QAOA circuit's phases are exact to the
            simulators' tolerance (:data:`qcpp.problem.cost_range.PHASE_COST_LIMIT`; ``solve -m qaoa``,
            ``simulate``, ``validate``).

    Raises:
        ScenarioError: if the file is missing, unreadable, empty, not valid TOML/JSON, or describes a bad scenario
            (the field is prefixed by the file name, ``standard input`` for ``-``; a grid over
            :data:`qcpp.problem.limits.MAX_GRID_NODES` nodes is refused unless
            :func:`qcpp.problem.limits.allow_large` is in effect).

    Example:
        >>> import os, tempfile
        >>> read, write = os.pipe()
        >>> _ = os.write(write, b'{"grid": {"rows": 2, "cols": 2}, "robots": [{"start": [0, 0], "goal": [1, 1]}]}')
        >>> os.close(write)
        >>> load_scenario(f"/dev/fd/{read}").grid.rows  # a pipe without a suffix: JSON by its first character
        2
        >>> os.close(read)
    """
    p = Path(path)
    stdin = os.fspath(path) == STDIN
    label = STDIN_LABEL if stdin else str(p)
    kind = "" if stdin else p.suffix.lower()
    try:
        if stdin:
            if os.isatty(0):
                raise ScenarioError(label, "is a terminal: pipe a scenario in (qcpp scenario ... | qcpp solve -)")
            if os.path.exists("/dev/stdin"):  # read as any pipe is: bounded in size and in waiting
                raw = read_bounded("/dev/stdin", MAX_SCENARIO_BYTES)
            else:  # pragma: no cover - systems without /dev/stdin
                raw = sys.stdin.buffer.read(MAX_SCENARIO_BYTES + 1)
        else:
            if not p.is_dir() and kind not in (".json", ".toml") and not _is_stream(p):  # before opening: a FIFO
                raise ScenarioError(str(p), "unknown file type (expected .toml or .json)")  # is never waited on
            raw = read_bounded(p, MAX_SCENARIO_BYTES)  # bounded: /dev/zero or a huge file must not fill the memory
        if len(raw) > MAX_SCENARIO_BYTES:
            raise ScenarioError(label, f"the file is larger than {MAX_SCENARIO_BYTES >> 20} MiB; not a scenario")
        text = raw.decode("utf-8-sig")  # a leading UTF-8 byte order mark is not content
    except InputError as exc:
        raise ScenarioError(label, f"cannot read the file: {exc.reason}") from None
    except OSError as exc:
        raise ScenarioError(label, f"cannot read the file ({exc.strerror or exc})") from None
    except UnicodeDecodeError as exc:
        raise ScenarioError(label, f"not valid UTF-8 text ({exc.reason} at byte {exc.start})") from None
    if kind in (".json", ".toml"):
        fmt = kind[1:].upper()
    else:
        if not text.strip():
            raise ScenarioError(label, "empty: expected a scenario in TOML or JSON")
        fmt = sniff_format(text)
    depth = nesting_depth(text, fmt)
    if depth > MAX_NESTING:
        raise ScenarioError(
            label, f"not a scenario: brackets nested {depth:,} levels deep (at most {MAX_NESTING}; a scenario needs 5)"
        )
    try:
        data = json.loads(text, object_pairs_hook=_unique_keys) if fmt == "JSON" else tomllib.loads(text)
    except _DuplicateKeyError as exc:
        raise ScenarioError(label, f"not valid JSON: {exc}") from None
    except json.JSONDecodeError as exc:
        raise ScenarioError(label, f"not valid JSON: {exc}") from None
    except tomllib.TOMLDecodeError as exc:
        raise ScenarioError(label, f"not valid TOML: {_toml_reason(text, exc)}") from None
    try:
        s = scenario_from_dict(data)
        if check_range:
            check_phase_range(s) if phases else check_cost_range(s)
        return s
    except ScenarioError as exc:
        raise ScenarioError(f"{STDIN_LABEL if stdin else p.name}: {exc.field}", exc.reason) from None


def sniff_format(text: str) -> str:
    """``JSON`` or ``TOML``: the format of scenario ``text`` that came without a suffix.

    A JSON scenario is an object, so it starts with ``{``; a TOML document cannot (it starts with a key, a table
    header ``[...]`` or a comment), so anything else is read as TOML, and a parse error then names TOML.

    Example:
        >>> sniff_format('  {"grid": {}}'), sniff_format("[grid]"), sniff_format("# a field")
        ('JSON', 'TOML', 'TOML')
    """
    return "JSON" if text.lstrip().startswith("{") else "TOML"


def _is_device(p: Path) -> bool:
    """Whether ``p`` exists and is not a regular file or a folder (a device, a FIFO): written straight to."""
    import stat

    try:
        mode = os.stat(p).st_mode
    except OSError:
        return False
    return not (stat.S_ISREG(mode) or stat.S_ISDIR(mode))


def _is_stream(p: Path) -> bool:
    """Whether ``p`` is read as a stream whose format the content tells: not a regular file (a pipe, FIFO, device;
    a missing file raises ``FileNotFoundError``, which the caller reports as unreadable), or a name under
    ``/dev/`` or ``/proc/`` (``/dev/stdin`` redirected from a file points at the file, which has any name)."""
    import stat

    if str(p).startswith(_STREAM_DIRS):
        return True
    return not stat.S_ISREG(os.stat(p).st_mode)


MAX_NESTING = 64
"""Deepest bracket nesting :func:`load_scenario` parses (a scenario needs 5; Python's parsers recurse per level,
so deeper input would end in a ``RecursionError``)."""

_STRINGS = {
    "JSON": re.compile(r'"(?:[^"\\]|\\.)*"'),
    "TOML": re.compile(r'"""[\s\S]*?"""|\'\'\'[\s\S]*?\'\'\'|"(?:[^"\\\n]|\\.)*"|\'[^\'\n]*\'|#[^\n]*'),
}


def nesting_depth(text: str, fmt: str) -> int:
    """The deepest nesting of ``[``/``{`` brackets in JSON or TOML ``text``, outside strings and comments.

    Example:
        >>> nesting_depth('{"a": [[1, 2], "]]]"]}', "JSON"), nesting_depth("a = [[1]] # [[[", "TOML")
        (3, 2)
    """
    bare = _STRINGS[fmt].sub("", text).encode("utf-8", "surrogatepass")
    codes = np.frombuffer(bare, dtype=np.uint8)
    steps = np.isin(codes, (ord("["), ord("{"))).astype(np.int64) - np.isin(codes, (ord("]"), ord("}")))
    return int(np.cumsum(steps).max(initial=0))


class _DuplicateKeyError(ValueError):
    pass


def _unique_keys(pairs: list[tuple[str, Any]]) -> dict[str, Any]:
    """``json.loads``'s object hook: a dict, refusing a key given twice in one object."""
    out: dict[str, Any] = {}
    for key, value in pairs:
        if key in out:
            keys = ", ".join(json.dumps(k) for k in dict(pairs))
            raise _DuplicateKeyError(
                f"the key {json.dumps(key)} appears twice in one object (keys {keys}); give each key once"
            )
        out[key] = value
    return out


_TOML_AT = re.compile(r"\(at line (\d+), column \d+\)|\(at end of document\)")


def _toml_reason(text: str, exc: Exception) -> str:
    """tomllib's message, with the key named when it is a key given twice (tomllib only gives a position)."""
    message = str(exc)
    declared = re.match(r"Cannot declare \(((?:'[^']*',? ?)+)\) twice \(at line (\d+)", message)
    if declared:
        table = ".".join(re.findall(r"'([^']*)'", declared.group(1)))
        return f"the table [{table}] is declared twice (line {declared.group(2)}); declare each table once"
    if not message.startswith("Cannot overwrite a value"):
        return message
    where = _TOML_AT.search(message)
    lines = text.splitlines()
    if where is None or not lines:
        return message
    if where.group(1):
        index = int(where.group(1)) - 1
    else:  # at the end: the last line with content
        index = max((i for i, line in enumerate(lines) if line.strip()), default=0)
    index = min(index, len(lines) - 1)
    key = lines[index].split("=", 1)[0].strip()
    table = next((line.strip() for line in reversed(lines[:index]) if line.strip().startswith("[")), "")
    inside = f" in {table}" if table else ""
    return f"the key {key}{inside} is given twice (line {index + 1}); give each key once"


def _toml_value(v: Any) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, (int, float)):
        return repr(v)
    if isinstance(v, str):
        return _toml_string(v)
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_toml_value(x) for x in v) + "]"
    raise TypeError(f"cannot write {v!r} as TOML")


def _toml_string(v: str) -> str:
    """A TOML basic string. Not ``json.dumps``: JSON escapes characters beyond U+FFFF as surrogate pairs,
    which TOML rejects. Quote, backslash and control characters are escaped, everything else is literal."""
    out = ['"']
    for ch in v:
        o = ord(ch)
        if ch in '"\\':
            out.append("\\" + ch)
        elif o < 0x20 or o == 0x7F:
            out.append(f"\\u{o:04X}")
        elif 0xD800 <= o <= 0xDFFF:
            raise ScenarioError("name", f"contains the lone surrogate U+{o:04X}, which TOML cannot hold (save as JSON)")
        else:
            out.append(ch)
    out.append('"')
    return "".join(out)


def scenario_to_toml(s: Scenario) -> str:
    """TOML text of ``s`` in the documented file format."""
    d = scenario_to_dict(s)
    lines = []
    if "name" in d:
        lines.append(f"name = {_toml_value(d['name'])}\n")
    lines.append("[grid]")
    lines += [f"{k} = {_toml_value(v)}" for k, v in d["grid"].items()]
    for rb in d["robots"]:
        lines += ["", "[[robots]]", f"start = {_toml_value(rb['start'])}", f"goal = {_toml_value(rb['goal'])}"]
    lines += ["", "[objective]"]
    lines += [f"{k} = {_toml_value(v)}" for k, v in d["objective"].items()]
    return "\n".join(lines) + "\n"


def save_scenario(s: Scenario, path: str | os.PathLike[str]) -> None:
    """Save ``s`` as ``.toml`` or ``.json`` (by the suffix), atomically: the file is whole or absent.

    An existing device or FIFO (``/dev/null``, ``mkfifo``) and standard output (``/dev/stdout``, whatever it is
    redirected to) are written straight to (:func:`qcpp.io.atomic.write_text_atomic`), in TOML unless the name
    ends in ``.json``.

    Raises:
        qcpp.errors.OptionError: ``s`` is not a :class:`Scenario`.
        ScenarioError: the suffix is neither ``.toml`` nor ``.json`` (and the destination is no device or FIFO).
        OutputError: the destination cannot be written (an :class:`OSError`: the environment, not the input).
    """
    if not isinstance(s, Scenario):
        raise OptionError("scenario", f"expected a Scenario (qcpp.grid_scenario or qcpp.load_scenario), got "
                                      f"{type(s).__name__}")  # fmt: skip
    p = Path(path)
    if p.suffix.lower() == ".json":
        text = json.dumps(scenario_to_dict(s), indent=2) + "\n"
    elif p.suffix.lower() == ".toml" or _is_device(p) or str(p) in STDOUT_NAMES:
        text = scenario_to_toml(s)
    else:
        raise ScenarioError(str(p), "unknown file type (expected .toml or .json)")
    write_text_atomic(p, text)
