"""What :func:`qcpp.verification.verify` reports: the checks it ran and, when feasibility fails, a counterexample.

A report is plain data (frozen dataclasses of numbers, strings and tuples) with :meth:`VerifyReport.to_dict` for
``qcpp verify --json`` and :meth:`VerifyReport.summary` for text (wrapped to a width, as ``qcpp verify`` prints it
on a terminal). Its :attr:`VerifyReport.outcome` is one of three verdicts:

``holds``
    Every check held (:attr:`VerifyReport.holds` is true).
``fails``
    A :attr:`VerifyReport.counterexample`: an input of the circuit, or a local input contained in a feasible path,
    where feasibility is lost.
``not_certified``
    No counterexample, but the gadget method met local inputs it could neither show harmless nor show on a
    feasible path (the first is :attr:`VerifyReport.unresolved`): it can neither certify nor refute, and the
    state method, which runs the circuit on its real inputs, decides.

Example:
    >>> c = Check("mixer_0", "state", "exhaustive", 12, True)
    >>> VerifyReport("2x2", 1, "exact", "state", True, (c,), None, 0.0, 0).to_dict()["checks"][0]["inputs"]
    12
"""

from __future__ import annotations

import re
import textwrap
from dataclasses import asdict, dataclass
from html import escape
from typing import Any, Literal

from qcpp.io.html import html_table

__all__ = ["OUTCOMES", "Check", "Counterexample", "Method", "Outcome", "VerifyReport"]

Method = Literal["state", "gadgets", "auto"]
METHODS: tuple[Method, ...] = ("state", "gadgets", "auto")

Outcome = Literal["holds", "fails", "not_certified"]
OUTCOMES: tuple[Outcome, ...] = ("holds", "fails", "not_certified")
"""The verdicts of :attr:`VerifyReport.outcome` (``qcpp verify`` exits 0, 1 and 3 on them)."""

Edge = tuple[tuple[int, int], tuple[int, int]]

_NBSP = "\u00a0"  # joins the words of one unit (an edge ``(0, 1)-(1, 1)``) so that wrapping never splits it

NOT_CERTIFIED = (
    "Not certified: no counterexample either. The gadget method checks local inputs, and no feasible path was shown "
    "to contain this one; --method state runs the circuit on every feasible input and decides (up to 62 qubits, "
    "every input while there are at most --samples of them)."
)
"""What the text report says after an unresolved input: why there is no verdict and what decides."""

CORNER_LETTERS = "E the robot's start or goal, B two outer edges, N fewer"
"""What a corner's letter in a local picture means (:attr:`qcpp.problem.sbf.LocalPicture.label`)."""

PICTURES = (
    f"pictures (four corner letters, as NNEN): a plaquette's corners a, b, c, d in order, {CORNER_LETTERS}; a "
    "final D: start and goal on diagonal corners"
)
"""The line the text report adds under checks whose subjects name local pictures."""

_PICTURE = re.compile(r"\b[EBN]{4}D?\b")
"""A local picture's label in a subject or gadget name (four corner letters, then ``D`` if diagonal)."""

MIN_WIDTH = 40
"""The narrowest width :meth:`VerifyReport.summary` wraps to (a smaller one is taken as this)."""


def _wrap(text: str, width: int | None, first: str = "", rest: str = "") -> list[str]:
    """``first + text`` as lines of at most ``width`` characters, continued after ``rest``; ``None``: one line.

    Breaks only at plain spaces (:data:`_NBSP` holds a unit together and prints as a space), so nothing is cut:
    only a single unit longer than the line can make a line longer."""
    if width is None:
        return [(first + text).replace(_NBSP, " ")]
    lines = textwrap.wrap(text, max(width, MIN_WIDTH), initial_indent=first, subsequent_indent=rest,
                          break_long_words=False, break_on_hyphens=False) or [first.rstrip()]  # fmt: skip
    return [line.replace(_NBSP, " ") for line in lines]


def _edges(p: tuple[Edge, ...]) -> str:
    """An edge set as text: edges ``a-b``, each one unit for :func:`_wrap`; ``(none)`` when empty."""
    return " ".join(f"{a}-{b}".replace(" ", _NBSP) for a, b in p) or "(none)"


def _picture_line(kind: str, plaquette: tuple[tuple[int, int], ...] | None) -> str | None:
    """The corner codes in ``kind`` in words: the one picture spelled out on ``plaquette``'s corners, else the
    letters' meaning (a junction names two pictures); ``None`` when ``kind`` names none."""
    codes = sorted(set(_PICTURE.findall(kind)))
    if not codes:
        return None
    if len(codes) > 1 or plaquette is None or len(plaquette) != 4:
        return PICTURES
    code = codes[0]
    corners = ", ".join(f"{c} {letter}".replace(" ", _NBSP) for c, letter in zip(plaquette, code, strict=False))
    diagonal = "; D: start and goal on diagonal corners" if code.endswith("D") else ""
    return f"{code} = corners {corners}{diagonal} ({CORNER_LETTERS})"


@dataclass(frozen=True)
class Check:
    """One check that ran.

    Attributes:
        subject: What was checked: a circuit part (``initial_state``, ``phase_0``, ``mixer_0``, ``circuit``) for
            the state method; a gadget kind (``MixerJunction ...``) or ``rule <picture>`` for the gadget method.
        part: ``initial_state``, ``phase`` or ``mixer`` (gadgets), or ``state`` (the state method).
        how: ``exhaustive`` (every input), ``sampled`` (a seeded sample), ``structural`` (a proof from the gate
            list's form) or ``covered`` (checked as part of another kind, named in ``detail``).
        inputs: Inputs it ran on (feasible assignments, or local inputs of a gadget; 0 for structural checks).
        held: Whether it held.
        multiplicity: How often the kind occurs in one layer (gadget method; 1 otherwise).
        detail: A short note (what the structural proof used, which kind covers this one).
        undecided: The check did not hold, but only on local inputs that no feasible path was shown to contain
            (gadget method): neither a proof nor a counterexample. Always false when ``held``.
    """

    subject: str
    part: str
    how: str
    inputs: int
    held: bool
    multiplicity: int = 1
    detail: str = ""
    undecided: bool = False

    @property
    def mark(self) -> str:
        """``ok``, ``FAIL`` or ``open`` (undecided), as the text report prints it."""
        return "ok" if self.held else "open" if self.undecided else "FAIL"


@dataclass(frozen=True)
class Counterexample:
    """Where feasibility preservation fails.

    Attributes:
        method: ``state`` (a real input of the compiled circuit) or ``gadgets`` (a local input of one gadget kind).
        check: The :attr:`Check.subject` that failed.
        kind: The gadget (class and kind) found responsible, if known.
        robot: The robot whose path leaves the feasible set (or whose partial mixer is at fault), if known.
        plaquette: The plaquette's corners ``(a, b, c, d)``, if known.
        input_paths: The input: per robot its path as edges (state method), or the set edges of the gadget's
            local input for ``robot`` (gadget method).
        output_paths: The offending output, in the same form.
        dirty_ancillas: Ancilla qubits left in ``|1>`` in the offending output (state method: qubits of the circuit;
            gadget method: positions among the gadget's local qubits, data first).
        amplitude: Modulus of the offending output amplitude.
        reason: What went wrong: which flip or gadget, and why the output is not allowed.
        reachable: Whether a feasible path of ``robot`` contains the input (the gadget method's inputs are local
            configurations; ``None`` where that was not decided). ``True`` for the state method's layer parts,
            whose inputs are feasible assignments; ``None`` for its ``initial_state`` and ``circuit`` (input
            ``|0...0>``).
    """

    method: str
    check: str
    kind: str | None
    robot: int | None
    plaquette: tuple[tuple[int, int], ...] | None
    input_paths: tuple[tuple[Edge, ...], ...]
    output_paths: tuple[tuple[Edge, ...], ...]
    dirty_ancillas: tuple[int, ...]
    amplitude: float
    reason: str
    reachable: bool | None = None

    def path_robots(self, paths: tuple[tuple[Edge, ...], ...]) -> tuple[int | None, ...]:
        """Whose edges each entry of ``paths`` (:attr:`input_paths` or :attr:`output_paths`) is: with several
        entries, or by the state method, entry ``r`` is robot ``r``'s; the gadget method's one entry is
        :attr:`robot`'s (``None``: no robot's, as for a phase gadget's input).

        Example:
            >>> cx = Counterexample("gadgets", "rule paper NENED", None, 1, None, ((),), ((),), (), 1.0, "")
            >>> cx.path_robots(cx.input_paths)
            (1,)
        """
        if self.method == "state" or len(paths) > 1:
            return tuple(range(len(paths)))
        return (self.robot,) * len(paths)

    def _labelled(self, paths: tuple[tuple[Edge, ...], ...], first: str, width: int | None,
                  tail: str = "") -> list[str]:  # fmt: skip
        """``paths`` as lines, each robot's edges after ``robot k:`` on a line of its own, ``tail`` after the last."""
        out: list[str] = []
        robots = self.path_robots(paths)
        for i, (r, p) in enumerate(zip(robots, paths, strict=True)):
            label = "" if r is None else f"robot{_NBSP}{r}: "
            end = tail if i == len(paths) - 1 else ""
            out += _wrap(f"{label}{_edges(p)}{end}", width, first if i == 0 else " " * len(first),
                         " " * (len(first) + len(label)))  # fmt: skip
        return out or _wrap(tail.strip(), width, first)

    def describe(self, width: int | None = None, heading: str = "counterexample") -> str:
        """A few human-readable lines: the reason, the gadget (and its local picture's corners in words), the input
        and the output, each robot's edges on lines of their own after ``robot k:``.

        Args:
            width: Characters per line (at least :data:`MIN_WIDTH`): long lines wrap at spaces, never inside an
                edge, continued indented. ``None``: one line per item, however long.
            heading: The first word (``unresolved input`` for :attr:`VerifyReport.unresolved`).
        """
        out = _wrap(f"{heading} ({self.method}, {self.check}): {self.reason}", width, "", "  ")
        if self.kind:
            where = f" robot {self.robot}" if self.robot is not None else ""
            corners = ", ".join(str(c).replace(" ", _NBSP) for c in self.plaquette or ())
            where += f" plaquette ({corners})" if self.plaquette else ""
            out += _wrap(f"{self.kind}{where}", width, "  gadget: ", " " * 10)
            picture = _picture_line(self.kind, self.plaquette)
            if picture is not None:
                out += _wrap(picture, width, "  picture: ", " " * 11)
        out += self._labelled(self.input_paths, "  input:  ", width)
        out += self._labelled(self.output_paths, "  output: ", width, f"  (|amplitude| {self.amplitude:.3g})")
        if self.dirty_ancillas:
            out += _wrap(str(list(self.dirty_ancillas)), width, "  dirty ancillas: ", " " * 10)
        return "\n".join(out)


@dataclass(frozen=True)
class VerifyReport:
    """The outcome of :func:`qcpp.verification.verify`.

    Attributes:
        scenario: The scenario's name (or ``RxC``).
        p: QAOA layers.
        rule: The SBF rule the circuit was compiled with.
        method: The method that ran (``state`` or ``gadgets``; ``auto`` resolved).
        holds: Every check held: the compiled circuit keeps every feasible assignment in the span of feasible
            assignments with clean ancillas (for the inputs checked; for every input when every check is
            ``exhaustive``, ``structural`` or ``covered``). False for both other outcomes (:attr:`outcome`).
        checks: The checks, in the order they ran.
        counterexample: The first failure found, or ``None``.
        seconds: Wall time.
        seed: Seed of the angles (and of the sample, if inputs were sampled).
        target: The cost model the circuit's constructions were chosen for (``nisq`` or ``ft``).
        unresolved: Without a counterexample, the first local input the gadget method could neither show
            harmless nor show on a feasible path (``reachable`` says what was found), else ``None``.
    """

    scenario: str
    p: int
    rule: str
    method: str
    holds: bool
    checks: tuple[Check, ...]
    counterexample: Counterexample | None
    seconds: float
    seed: int
    target: str = "nisq"
    unresolved: Counterexample | None = None

    @property
    def outcome(self) -> Outcome:
        """``holds``, ``fails`` (a :attr:`counterexample`) or ``not_certified`` (only :attr:`unresolved` inputs:
        neither a proof nor a counterexample; ``--method state`` decides where the field fits it)."""
        if self.holds:
            return "holds"
        return "fails" if self.counterexample is not None or self.unresolved is None else "not_certified"

    @property
    def exhaustive(self) -> bool:
        """No check was sampled: the verdict covers every feasible input."""
        return all(c.how != "sampled" for c in self.checks)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready form (what ``qcpp verify --json`` prints): the fields, ``outcome`` and ``exhaustive``."""
        out = asdict(self)
        out["outcome"] = self.outcome
        out["exhaustive"] = self.exhaustive
        return out

    @property
    def verdict(self) -> str:
        """One line: holds, FAILS or NOT CERTIFIED, on what, by which method over which inputs, and the time taken."""
        return self._verdict(" ")

    def _verdict(self, space: str) -> str:
        """:attr:`verdict`, with ``space`` between each number and its unit."""
        verdict = {"holds": "holds", "fails": "FAILS", "not_certified": "NOT CERTIFIED"}[self.outcome]
        if not self.exhaustive:
            scope = "the sampled inputs"
        elif self.method == "gadgets":  # each kind on all its local inputs: a verdict on every feasible input
            scope = "every gadget kind on each of its local inputs"
        else:
            scope = "every feasible input"
        return (
            f"feasibility preservation {verdict}: {self.scenario}, p = {self.p}, rule {self.rule}, "
            + (f"target {self.target}, " if self.target != "nisq" else "")
            + f"method {self.method} ({scope}; {self.seconds:.1f}{space}s)"
        )

    def summary(self, width: int | None = None) -> str:
        """Human-readable text: the :attr:`verdict`, one row per check, the counterexample or, when not certified,
        the first unresolved input and what decides it.

        Args:
            width: Characters per line (at least :data:`MIN_WIDTH`; ``qcpp verify`` passes the terminal's).
                A row that does not fit wraps at spaces, continued under its subject; no subject, edge or number
                is cut (only a single word longer than the line could make one longer). ``None``: one line per
                check, subjects in one aligned column.

        Returns:
            The text, without a final newline.
        """
        subject_w = max((len(c.subject) for c in self.checks), default=0)
        lines = _wrap(self._verdict(_NBSP), width, "", "  ")
        for c in self.checks:
            head = f"  {c.mark:<4} {c.part:<13} "
            times = f" x{c.multiplicity}" if c.multiplicity != 1 else ""
            count = f" {c.inputs}{_NBSP}inputs" if c.inputs else ""
            note = f"  ({c.detail})" if c.detail else ""
            tail = f"{times} {c.how}{count}{note}"
            one = f"{head}{c.subject:<{subject_w}}{tail}".replace(_NBSP, " ")
            if width is None or len(one) <= width:
                lines.append(one)
                continue
            indent = " " * (len(head) if width - len(head) >= 30 else 6)
            lines += _wrap(f"{c.subject}{tail}", width, head, indent)
        if any(_PICTURE.search(c.subject) for c in self.checks):
            lines += _wrap(PICTURES, width, "  ", "  ")
        if self.counterexample is not None:
            lines.append(self.counterexample.describe(width))
        elif self.unresolved is not None:
            lines.append(self.unresolved.describe(width, "unresolved input"))
            lines += _wrap(NOT_CERTIFIED, width)
        return "\n".join(lines)

    def _repr_html_(self) -> str:
        """In a notebook: the verdict as the caption, one table row per check, the counterexample below."""
        result = {"ok": "held", "FAIL": "FAILS", "open": "undecided"}
        rows = [(c.part, c.subject, c.how, str(c.inputs), str(c.multiplicity), result[c.mark], c.detail)
                for c in self.checks]  # fmt: skip
        headers = ("part", "subject", "how", "inputs", "times", "result", "")
        table = html_table(self.verdict, headers, rows, align=(None, None, None, "right", "right"))
        if self.counterexample is not None:
            table += f"<pre>{escape(self.counterexample.describe())}</pre>"
        elif self.unresolved is not None:
            table += f"<pre>{escape(self.unresolved.describe(heading='unresolved input'))}\n{NOT_CERTIFIED}</pre>"
        return table
