"""The ``cusp`` console command.

Each subcommand lives in its own module and is imported only when it runs, so
``cusp verify`` never pays for plotting and ``cusp run`` never pays for sympy.
A subcommand module provides ``add_arguments(parser)`` and ``main(args) -> int``.
"""

from __future__ import annotations

import argparse
import importlib
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


def _parser() -> tuple[argparse.ArgumentParser, dict[str, argparse.ArgumentParser]]:
    parser = argparse.ArgumentParser(
        prog="cusp",
        description="Continuation and bifurcation analysis of the stick-slip cusp catastrophe.",
    )
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    subparsers = {}
    for name, (_, help_text) in COMMANDS.items():
        subparsers[name] = sub.add_parser(name, help=help_text, description=help_text)
    return parser, subparsers


def main(argv: list[str] | None = None) -> int:
    argv = list(sys.argv[1:] if argv is None else argv)
    parser, subparsers = _parser()
    if not argv or argv[0] not in COMMANDS and argv[0] not in ("-h", "--help"):
        argv.insert(0, DEFAULT_COMMAND)
    name = argv[0]
    if name in COMMANDS:
        module = importlib.import_module(COMMANDS[name][0])
        module.add_arguments(subparsers[name])
    args = parser.parse_args(argv)
    module = importlib.import_module(COMMANDS[args.command][0])
    return int(module.main(args) or 0)


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
