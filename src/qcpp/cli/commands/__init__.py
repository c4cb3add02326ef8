"""Subcommands of the ``qcpp`` CLI, one module per command, each with ``register(app)``."""
