"""The ``cusp`` console command.

Each subcommand lives in its own module and is imported only when it runs, so
``cusp verify`` never pays for plotting and ``cusp run`` never pays for sympy.
A subcommand module provides ``add_arguments(parser)`` and ``main(args) -> int``.

Options of every command: ``-v`` (the ``cusp`` loggers' INFO records on standard error;
``-vv``: DEBUG; :mod:`cusp.app.progress` names the loggers), given before or after the
subcommand; ``cusp --version``. Output into a pipe that closes early (``cusp run | head -1``)
ends the command quietly, with exit status 141 (128 + SIGPIPE, as the shell reports a
command the signal ended).
"""

from __future__ import annotations

import argparse
import importlib
import os
import sys

#: subcommand name -> (module path, one-line help)
COMMANDS: dict[str, tuple[str, str]] = {
    "run": (
        "cusp.app.run",
        "trace the contact-loss path of a scene (TOML); default: the paper's Fig 6 scene",
    ),
    "sweep": (
        "cusp.app.sweep",
        "run every case of a scene's [sweep] section into a Parquet dataset (resumable)",
    ),
    "demo": ("cusp.app.demo", "trace the cusp normal form x^3 - a x - b = 0 and print its folds"),
    "verify": (
        "cusp.app.verify",
        "derive the paper's closed forms with sympy; compare printed, derived and implemented",
    ),
}

#: what ``cusp`` with no subcommand runs
DEFAULT_COMMAND = "run"

#: the exit status after standard output was closed by its reader (128 + SIGPIPE)
BROKEN_PIPE_STATUS = 141

_VERBOSE = {"-v": 1, "--verbose": 1, "-vv": 2, "-vvv": 3}


def _parser() -> tuple[argparse.ArgumentParser, dict[str, argparse.ArgumentParser]]:
    parser = argparse.ArgumentParser(
        prog="cusp",
        description="Continuation and bifurcation analysis of the stick-slip cusp catastrophe.",
    )
    parser.add_argument("--version", action="store_true", help="print cusp's version and exit")
    verbose = "show the cusp loggers' records on stderr (-v INFO, -vv DEBUG)"
    parser.add_argument("-v", "--verbose", action="count", default=0, dest="verbose_", help=verbose)
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    subparsers = {}
    for name, (_, help_text) in COMMANDS.items():
        subparsers[name] = sub.add_parser(name, help=help_text, description=help_text)
        subparsers[name].add_argument("-v", "--verbose", action="count", default=0, help=verbose)
    return parser, subparsers


def main(argv: list[str] | None = None) -> int:
    argv = list(sys.argv[1:] if argv is None else argv)
    try:
        return _main(argv)
    except BrokenPipeError:
        # the reader of stdout went away (cusp run | head -1): no traceback, and no second
        # error when Python flushes stdout at exit
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        return BROKEN_PIPE_STATUS


def _main(argv: list[str]) -> int:
    verbose = 0
    while argv and (argv[0] in _VERBOSE or argv[0] == "--version"):
        flag = argv.pop(0)
        if flag == "--version":
            from importlib.metadata import PackageNotFoundError, version

            try:
                number = version("cusp")
            except PackageNotFoundError:  # a source tree never installed
                number = "unknown (not installed)"
            print(f"cusp {number}")
            return 0
        verbose += _VERBOSE[flag]
    parser, subparsers = _parser()
    if not argv or argv[0] not in COMMANDS and argv[0] not in ("-h", "--help"):
        argv.insert(0, DEFAULT_COMMAND)
    name = argv[0]
    if name in COMMANDS:
        module = importlib.import_module(COMMANDS[name][0])
        module.add_arguments(subparsers[name])
    args = parser.parse_args(argv)
    from .progress import configure_logging

    configure_logging(verbose + args.verbose)
    module = importlib.import_module(COMMANDS[args.command][0])
    return int(module.main(args) or 0)


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
