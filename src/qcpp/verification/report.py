"""What :func:`qcpp.verification.verify` reports: the checks it ran and, when feasibility fails, a counterexample.

A report is plain data (frozen dataclasses of numbers, strings and tuples) with :meth:`VerifyReport.to_dict` for
``qcpp verify --json``. :attr:`VerifyReport.holds` is true when every check held; then
:attr:`VerifyReport.counterexample` is ``None``.

Example:
    >>> c = Check("mixer_0", "state", "exhaustive", 12, True)
    >>> VerifyReport("2x2", 1, "exact", "state", True, (c,), None, 0.0, 0).to_dict()["checks"][0]["inputs"]
    12
"""

from __future__ import annotations

from dataclasses import asdict, dataclass
from html import escape
from typing import Any, Literal

from qcpp.io.html import html_table

__all__ = ["Check", "Counterexample", "Method", "VerifyReport"]

Method = Literal["state", "gadgets", "auto"]
METHODS: tuple[Method, ...] = ("state", "gadgets", "auto")

Edge = tuple[tuple[int, int], tuple[int, int]]


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
    """

    subject: str
    part: str
    how: str
    inputs: int
    held: bool
    multiplicity: int = 1
    detail: str = ""


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
        reason: One sentence on what went wrong.
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

    def describe(self) -> str:
        """A few human-readable lines."""

        def paths(ps: tuple[tuple[Edge, ...], ...]) -> str:
            return "; ".join(" ".join(f"{a}-{b}" for a, b in p) or "(none)" for p in ps)

        lines = [f"counterexample ({self.method}, {self.check}): {self.reason}"]
        if self.kind:
            where = f" robot {self.robot}" if self.robot is not None else ""
            where += f" plaquette {self.plaquette}" if self.plaquette else ""
            lines.append(f"  gadget: {self.kind}{where}")
        lines.append(f"  input:  {paths(self.input_paths)}")
        lines.append(f"  output: {paths(self.output_paths)}  (|amplitude| {self.amplitude:.3g})")
        if self.dirty_ancillas:
            lines.append(f"  dirty ancillas: {list(self.dirty_ancillas)}")
        return "\n".join(lines)


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
            ``exhaustive``, ``structural`` or ``covered``).
        checks: The checks, in the order they ran.
        counterexample: The first failure found, or ``None``.
        seconds: Wall time.
        seed: Seed of the angles (and of the sample, if inputs were sampled).
        target: The cost model the circuit's constructions were chosen for (``nisq`` or ``ft``).
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

    @property
    def exhaustive(self) -> bool:
        """No check was sampled: the verdict covers every feasible input."""
        return all(c.how != "sampled" for c in self.checks)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready form (what ``qcpp verify --json`` prints)."""
        out = asdict(self)
        out["exhaustive"] = self.exhaustive
        return out

    def summary(self) -> str:
        """Human-readable text: verdict, checks, counterexample."""
        verdict = "holds" if self.holds else "FAILS"
        if not self.exhaustive:
            scope = "the sampled inputs"
        elif self.method == "gadgets":  # each kind on all its local inputs: a verdict on every feasible input
            scope = "every gadget kind on each of its local inputs"
        else:
            scope = "every feasible input"
        lines = [
            f"feasibility preservation {verdict}: {self.scenario}, p = {self.p}, rule {self.rule}, "
            + (f"target {self.target}, " if self.target != "nisq" else "")
            + f"method {self.method} ({scope}; {self.seconds:.1f} s)"
        ]
        for c in self.checks:
            mark = "ok  " if c.held else "FAIL"
            count = f"{c.inputs} inputs" if c.inputs else ""
            times = f" x{c.multiplicity}" if c.multiplicity != 1 else ""
            note = f"  ({c.detail})" if c.detail else ""
            lines.append(f"  {mark} {c.part:<13} {c.subject[:60]:<60}{times} {c.how} {count}{note}".rstrip())
        if self.counterexample is not None:
            lines.append(self.counterexample.describe())
        return "\n".join(lines)

    def _repr_html_(self) -> str:
        """In a notebook: the verdict as the caption, one table row per check, the counterexample below."""
        rows = [(c.part, c.subject, c.how, str(c.inputs), str(c.multiplicity), "held" if c.held else "FAILS", c.detail)
                for c in self.checks]  # fmt: skip
        headers = ("part", "subject", "how", "inputs", "times", "result", "")
        table = html_table(self.summary().splitlines()[0], headers, rows, align=(None, None, None, "right", "right"))
        if self.counterexample is not None:
            table += f"<pre>{escape(self.counterexample.describe())}</pre>"
        return table
