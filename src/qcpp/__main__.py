"""``python -m qcpp`` and the ``qcpp`` console script: signal handling first, then the CLI.

Ctrl-C/SIGTERM handling (:mod:`qcpp.cli.interrupt`) is installed before the heavy imports (numpy, sympy, typer, ...),
so even an interrupt during start-up is one line ``interrupted`` and exit code 130, never a traceback.
"""

from __future__ import annotations

import os


def main() -> None:
    """Install the signal handling, import the CLI and run it."""
    from qcpp.cli.interrupt import EXIT_CODE, install, report_interrupted
    from qcpp.cli.streams import guard_closed_streams

    guard_closed_streams()  # before any file is opened: none may land on a closed descriptor 0-2
    install()
    try:
        from qcpp.cli.app import main as cli_main
    except KeyboardInterrupt:
        report_interrupted()
        os._exit(EXIT_CODE)
    cli_main()


if __name__ == "__main__":
    main()
