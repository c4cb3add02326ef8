"""``python -m qcpp``: the same as the ``qcpp`` command."""

from qcpp.cli import main

if __name__ == "__main__":
    main()
