"""What collecting the tests imported: recorded by ``tests/conftest.py`` when collection ends, read by a test.

The tests that run quimb form one pytest-xdist group (``tests/conftest.py``): on a fresh install numba compiles
quimb's kernels when a process first imports quimb, so a test module that imported it at collection would make
every worker pay that cost again.
"""

from __future__ import annotations

import pytest

QUIMB_AT_COLLECTION = pytest.StashKey[bool]()
"""Whether ``quimb.tensor`` was imported when collection ended."""
