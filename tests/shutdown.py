"""The test run's end: live objects frozen out of the collector's sight, handed back before the interpreter exits.

:func:`freeze_survivors` is what ``tests/conftest.py`` does when the session finishes: one collection finds today's
garbage, :func:`gc.freeze` moves the survivors (the session's caches of compiled circuits) to the permanent
generation, so pytest's five closing collections scan only what finalizers leave behind. Frozen objects are never
collected, also not by the interpreter's last collection at exit; objects of a nanobind extension (``mqt.core``,
``mqt.qcec``) kept alive in a reference cycle would then still exist when nanobind checks for leaks, and it prints
``nanobind: leaked N instances!`` with some 60 lines of detail. So the freeze ends at exit (:func:`gc.unfreeze` in
an :mod:`atexit` handler, which runs before the modules are torn down): the interpreter frees those cycles as it
would without the freeze, and a real leak in a binding is still reported.
"""

from __future__ import annotations

import atexit
import gc

__all__ = ["freeze_survivors"]


def freeze_survivors() -> None:
    """Collect once, freeze what survived, and unfreeze it when the interpreter exits (see the module docstring)."""
    gc.collect()
    gc.freeze()
    atexit.register(gc.unfreeze)
