"""The application layer: scene files (:mod:`~cusp.app.scene`), the runner
(:mod:`~cusp.app.run`), figures (:mod:`~cusp.app.figures`) and the ``cusp`` command
(:mod:`~cusp.app.cli`, with the ``run``, ``demo`` and ``verify`` subcommands).

Each module imports only what its job needs: ``cusp run --no-plots`` never loads matplotlib,
and no command but ``cusp verify`` loads sympy.
"""
