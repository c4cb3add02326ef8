"""Size of ``src/``: lines and code lines per package, of this tree and optionally of a revision.

Run: ``python benchmarks/src_size.py [--against REV] [--counting] [--merges M ...]``.

* lines: every line of every ``.py`` file under ``src/``;
* code lines: lines that hold code, i.e. not blank, not only a comment and not part of a docstring (the string
  that opens a module, class or function body). A statement spanning several lines counts each of its lines.

With ``--against REV`` a second column pair gives the same counts of ``REV``'s ``src/`` (read with ``git show``,
nothing checked out) and the ratio. ``--counting`` adds a table of the counting code only: the modules along the
seven count paths issue #17 names (at ``d41c381``) and their successors (:data:`COUNTING`), the set whose code
lines issue #17's "src/ shrinks" was judged on. ``--merges M ...`` prints what each merge commit's branch did to
``src/`` on its own: lines and code lines at the branch's fork point (``git merge-base M^1 M^2``) and at its tip
(``M^2``), and the sums (:data:`ISSUE_17_MERGES` lists issue #17's branches, ``--merges 17`` names them).

Example::

    python benchmarks/src_size.py --against d41c381 --counting --merges 17
"""

from __future__ import annotations

import argparse
import ast
import io
import subprocess
import sys
import tokenize
from collections.abc import Callable, Iterable
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

#: The counting code: the seven count paths of issue #17 (the compiled circuit's counter, the plan's sums, the
#: mixer / phase class counters, the estimate's shortcuts, the formulas, the plan-section rebuild and the cross-check)
#: as they were at d41c381, and the modules that replaced them since. A module missing from a tree counts zero.
COUNTING = (
    "qcpp/plan/qaoa.py",
    "qcpp/plan/call_graph.py",
    "qcpp/plan/mixer_classes.py",
    "qcpp/plan/phase_classes.py",
    "qcpp/plan/phase_choice.py",
    "qcpp/estimators/counts.py",
    "qcpp/estimators/crosscheck.py",
    "qcpp/estimators/depth.py",
    "qcpp/estimators/estimate.py",
    "qcpp/estimators/formulas.py",
    "estimators/mixer_count.py",
    "estimators/phase_count.py",
)

#: The merges of issue #17's branches into main, oldest first: plan (PlanOptions, the call graph), its follow-ups,
#: plan2, shrink, shrink9, then simshrink, clishrink and count17.
ISSUE_17_MERGES = ("e2f2116", "c429989", "a237704", "cc01521", "ead7f70", "4746b0d", "cf51b55", "df9392a", "e3e8b11")


def docstring_lines(tree: ast.Module) -> set[int]:
    """Line numbers (1-based) covered by the docstrings of a module and its classes and functions.

    Args:
        tree: the parsed module.

    Returns:
        Every line of every docstring.

    Example:
        >>> sorted(docstring_lines(ast.parse("def f():\\n    '''Doc.\\n\\n    More.'''\\n    return 1\\n")))
        [2, 3, 4]
    """
    lines: set[int] = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Module | ast.ClassDef | ast.FunctionDef | ast.AsyncFunctionDef) and node.body:
            first = node.body[0]
            if isinstance(first, ast.Expr) and isinstance(getattr(first.value, "value", None), str):
                lines.update(range(first.lineno, (first.end_lineno or first.lineno) + 1))
    return lines


def count(text: str) -> tuple[int, int]:
    """Lines and code lines of one Python source.

    Args:
        text: the file's text.

    Returns:
        ``(lines, code lines)``: code lines hold a token other than a comment, outside every docstring.

    Example:
        >>> count("'''Doc.'''\\n\\n# why\\nx = (1,\\n     2)  # two\\n")
        (5, 2)
    """
    skip = docstring_lines(ast.parse(text))
    code: set[int] = set()
    ignored = {tokenize.COMMENT, tokenize.NL, tokenize.NEWLINE, tokenize.INDENT, tokenize.DEDENT, tokenize.ENDMARKER}
    for token in tokenize.generate_tokens(io.StringIO(text).readline):
        if token.type not in ignored:
            code.update(line for line in range(token.start[0], token.end[0] + 1) if line not in skip)
    return len(text.splitlines()), len(code)


def tree_files(rev: str | None) -> tuple[list[str], Callable[[str], str]]:
    """The ``.py`` paths under ``src/`` (relative to it) of this tree or of ``rev``, and a reader of their text.

    Args:
        rev: a git revision, or ``None`` for the working tree.

    Returns:
        ``(paths, read)``.
    """
    if rev is None:
        paths = sorted(str(p.relative_to(ROOT / "src")) for p in (ROOT / "src").rglob("*.py"))
        return paths, lambda path: (ROOT / "src" / path).read_text()
    listing = subprocess.run(
        ["git", "ls-tree", "-r", "--name-only", rev, "src"], cwd=ROOT, check=True, capture_output=True, text=True
    ).stdout.split()
    paths = sorted(p.removeprefix("src/") for p in listing if p.endswith(".py"))

    def read(path: str) -> str:
        return subprocess.run(
            ["git", "show", f"{rev}:src/{path}"], cwd=ROOT, check=True, capture_output=True, text=True
        ).stdout

    return paths, read


def sizes(rev: str | None) -> dict[str, tuple[int, int]]:
    """Lines and code lines per file of ``src/`` (this tree, or ``rev``).

    Args:
        rev: a git revision, or ``None`` for the working tree.

    Returns:
        ``{path relative to src: (lines, code lines)}``.
    """
    paths, read = tree_files(rev)
    return {path: count(read(path)) for path in paths}


def totals(per_file: dict[str, tuple[int, int]], keys: Iterable[str]) -> tuple[int, int]:
    """Summed lines and code lines of the files ``keys`` (missing ones count zero)."""
    found = [per_file.get(key, (0, 0)) for key in keys]
    return sum(f[0] for f in found), sum(f[1] for f in found)


def _ratio(a: int, b: int) -> str:
    return f"{a / b:.3f}" if b else "-"


def table(rows: list[tuple[str, tuple[int, int], tuple[int, int] | None]], against: str | None) -> str:
    """One text table: name, lines, code lines (and the other tree's, with ratios, if given)."""
    head = f"{'':32} {'lines':>7} {'code':>7}"
    if against:
        head += f" {'lines@' + against[:9]:>16} {'code@' + against[:9]:>15} {'lines x':>8} {'code x':>7}"
    out = [head]
    for name, (lines, code), other in rows:
        line = f"{name:32} {lines:7,} {code:7,}"
        if other is not None:
            line += f" {other[0]:16,} {other[1]:15,} {_ratio(lines, other[0]):>8} {_ratio(code, other[1]):>7}"
        out.append(line)
    return "\n".join(out)


def _git(*args: str) -> str:
    return subprocess.run(["git", *args], cwd=ROOT, check=True, capture_output=True, text=True).stdout.strip()


def merge_table(merges: list[str]) -> str:
    """What each merge's branch did to ``src/``: (lines, code lines) at its fork point and its tip, and the sums.

    Args:
        merges: merge commits (their second parent is the branch's tip).

    Returns:
        A text table, one row per merge and a total row.
    """
    head = f"{'merge':10} {'branch':42} {'lines':>15} {'code':>15} {'d lines':>8} {'d code':>7}"
    out, total = [head], [0, 0]
    for merge in merges:
        tip = _git("rev-parse", f"{merge}^2")
        base = _git("merge-base", f"{merge}^1", tip)
        before = totals(sizes(base), sizes(base))
        after = totals(sizes(tip), sizes(tip))
        delta = (after[0] - before[0], after[1] - before[1])
        total = [total[0] + delta[0], total[1] + delta[1]]
        subject = _git("log", "-1", "--format=%s", merge).removeprefix("Merge ")[:42]
        lines, code = f"{before[0]:,}->{after[0]:,}", f"{before[1]:,}->{after[1]:,}"
        out.append(f"{merge[:10]:10} {subject:42} {lines:>15} {code:>15} {delta[0]:+8,} {delta[1]:+7,}")
    out.append(f"{'all':10} {'':42} {'':>15} {'':>15} {total[0]:+8,} {total[1]:+7,}")
    return "\n".join(out)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--against", metavar="REV", help="also count REV's src/ (git show) and print ratios")
    parser.add_argument("--counting", action="store_true", help="also the counting modules of issue #17")
    parser.add_argument("--merges", nargs="+", metavar="M", help="each merge branch's own effect (17: issue #17's)")
    args = parser.parse_args(argv)
    here = sizes(None)
    there = sizes(args.against) if args.against else None
    packages = sorted({path.split("/")[0] for path in [*here, *(there or {})]})

    def row(name: str, keys: Callable[[dict[str, tuple[int, int]]], Iterable[str]]):
        return name, totals(here, keys(here)), totals(there, keys(there)) if there is not None else None

    rows = [row(package + "/", lambda f, p=package: [k for k in f if k.split("/")[0] == p]) for package in packages]
    rows.append(row("src/ (all)", lambda f: list(f)))
    print(table(rows, args.against))
    if args.counting:
        print()
        rows = [row(path, lambda f, p=path: [p]) for path in COUNTING]
        rows.append(row("counting modules (all)", lambda f: COUNTING))
        print(table(rows, args.against))
    if args.merges:
        print()
        print(merge_table(list(ISSUE_17_MERGES) if args.merges == ["17"] else args.merges))
    return 0


if __name__ == "__main__":
    sys.exit(main())
