"""Settings shared by every test: no test depends on how fast the machine is.

Hypothesis's default per-example deadline (200 ms) and its "too slow" health check measure wall time, so they
fail on a loaded machine (CI runs two workers on two cores, often beside other jobs): both are off for every
``@given`` test (the ``timeless`` profile, loaded here).
"""

from __future__ import annotations

from hypothesis import HealthCheck, settings

settings.register_profile("timeless", deadline=None, suppress_health_check=[HealthCheck.too_slow])
settings.load_profile("timeless")
