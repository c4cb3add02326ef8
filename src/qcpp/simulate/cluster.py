"""Dask clusters for the tensor backend: the check of a scheduler address and the client that connects to one.

The tensor simulator (:mod:`qcpp.simulate.tensor`) slices contractions wider than one process can hold and runs
the slices on a ``dask.distributed`` cluster when it is given a client; ``qcpp validate --dask``,
``qcpp.validate(dask=...)`` and the experiment scripts make that client here. Importing this module loads neither
dask nor the tensor libraries.

Example:
    >>> check_dask_address("local")
    >>> check_dask_address("tcp://10.0.0.5:8786")
"""

from __future__ import annotations

import logging
import os
from typing import Any

from qcpp.errors import OptionError

__all__ = ["check_dask_address", "dask_client"]


def check_dask_address(text: object, name: str = "dask") -> None:
    """Refuse a value that is neither ``local`` nor a dask scheduler address, before any work (dask's own message,
    after the simulation, would name no option).

    Args:
        text: The value given.
        name: The option, as the caller spells it (``--dask`` on the command line).

    Raises:
        qcpp.errors.OptionError: naming ``name``.

    Example:
        >>> check_dask_address("tcp://127.0.0.1:8786")
        >>> check_dask_address("", "--dask")
        Traceback (most recent call last):
        ...
        qcpp.errors.OptionError: --dask: expected a scheduler address such as tcp://host:8786, or 'local'
    """
    expected = "expected a scheduler address such as tcp://host:8786, or 'local'"
    if not isinstance(text, str) or not text.strip():
        raise OptionError(name, expected)
    if text.strip() == "local":
        return
    try:
        from distributed.comm import parse_address
        from distributed.comm.addressing import parse_host_port
    except ImportError:
        return  # the tensor backend says that dask is missing
    try:
        scheme, location = parse_address(text.strip())
        if scheme in ("tcp", "tls"):
            parse_host_port(location)
    except ValueError as exc:
        raise OptionError(name, f"{exc} ({expected})") from None


def dask_client(address: str, workers: int | None = None) -> Any:
    """A ``dask.distributed.Client``: ``'local'`` starts a ``LocalCluster`` of its own (``workers`` processes, one
    thread each; closing the client stops it), anything else is a scheduler address such as ``tcp://10.0.0.5:8786``.
    Close it when done (``with dask_client(...) as client:``).

    Args:
        address: ``'local'`` or a scheduler address.
        workers: Worker processes of a local cluster (default: one per core).

    Raises:
        OSError: the scheduler cannot be reached within 10 s.
    """
    from dask.distributed import Client

    # distributed logs through `logging` to stderr (a busy dashboard port, a slow worker): the CLI reports what
    # matters itself (how many contractions ran on the cluster), so only errors get through
    logging.getLogger("distributed").setLevel(logging.ERROR)
    if address == "local":
        # ":0": the dashboard takes a free port; the default (also with None) asks for 8787 and warns when another
        # cluster holds it. silence_logs reaches the worker processes, whose logging is their own: at teardown a
        # worker's heartbeat can meet the closed scheduler and log an ERROR with a traceback; a task's failure
        # still reaches the caller as its exception
        return Client(
            n_workers=workers or os.cpu_count() or 1, threads_per_worker=1, dashboard_address=":0",
            silence_logs=logging.CRITICAL,
        )
    try:
        return Client(address, timeout="10s")
    except OSError as exc:
        raise OSError(f"dask scheduler {address!r} unreachable: {exc}") from exc
