"""Settings shared by every test: no test depends on how fast the machine is.

* Hypothesis's default per-example deadline (200 ms) and its "too slow" health check measure wall time, so they
  fail on a loaded machine (CI runs two workers on two cores, often beside other jobs): both are off for every
  ``@given`` test (the ``timeless`` profile, loaded here).
* Progress lines (:mod:`qcpp.cli.progress`) appear after a second of work on a pipe, so whether a command printed one
  depends on the machine's load: they are off (``QCPP_PROGRESS=off``, inherited by subprocesses); the tests of
  progress itself turn them on with ``QCPP_PROGRESS_INTERVAL=0`` (a line at every step, no clock involved).
* At the session's end pytest collects garbage five times over (to report exceptions raised in finalizers); with
  the session's caches of compiled circuits alive that re-scanned millions of objects five times. One collection
  here finds today's garbage; :func:`gc.freeze` then moves what survived it (live objects) out of the collector's
  sight, so pytest's collections scan only what finalizers left behind; the freeze ends at exit, so that the
  interpreter frees the survivors as usual (:mod:`tests.shutdown`: else nanobind extensions report them as leaks).
"""

from __future__ import annotations

import os

import pytest
from hypothesis import HealthCheck, settings

from tests.shutdown import freeze_survivors

settings.register_profile("timeless", deadline=None, suppress_health_check=[HealthCheck.too_slow])
settings.load_profile("timeless")

os.environ["QCPP_PROGRESS"] = "off"


def pytest_sessionfinish(session: pytest.Session, exitstatus: int) -> None:
    """Collect once, then freeze the survivors until exit (see the module docstring)."""
    freeze_survivors()
