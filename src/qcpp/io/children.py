"""Child processes that end with their parent.

A child doing work for its parent (QCEC's equivalence check, a heavy-hex window routed ahead) must not outlive it:
a parent killed outright (``kill -9``) cannot stop it, and it would run on alone, for seconds or minutes.
:func:`die_with_parent`, called first thing in the child, asks the kernel to kill it when the parent dies (Linux
``PR_SET_PDEATHSIG``; elsewhere it does nothing, and the parent's own stop is the only one).

Example:
    >>> import os
    >>> die_with_parent(os.getppid()) is None  # here: this process, with its real parent
    True
"""

from __future__ import annotations

import os

__all__ = ["die_with_parent"]


def die_with_parent(parent: int) -> None:
    """Ask the kernel to SIGKILL this process when its parent (process id ``parent``) dies (Linux); exit at once if
    it already has."""
    import ctypes
    import signal

    try:
        libc = ctypes.CDLL(None, use_errno=True)
        libc.prctl(1, int(signal.SIGKILL))  # 1 = PR_SET_PDEATHSIG
    except (OSError, AttributeError):  # pragma: no cover - not Linux
        return
    if os.getppid() != parent:  # the parent died before the request
        os._exit(1)
