"""The ``gearcontact`` command line: a thin layer that parses, calls the library and
writes files. Each subcommand lives in its own module ``gearcontact.cli.<name>`` that
defines ``register(subparsers)``; its handler is stored as ``func`` on the parser.
"""

from __future__ import annotations

import argparse
import importlib
import sys

from ..validation import InputRangeError

__all__ = ["main", "build_parser"]

#: Subcommand modules, in the order ``gearcontact --help`` lists them.
COMMANDS = ("analyze", "reproduce", "preview", "design", "tca", "rtl", "vectors", "ltca",
            "lte")


def build_parser() -> argparse.ArgumentParser:
    from .. import __version__

    parser = argparse.ArgumentParser(
        prog="gearcontact",
        description="Gear tooth-contact computation: hypoid flanks, TCA, LTCA and the "
                    "physics-direct Hertz preview (fp64 / fixed point / RTL).")
    parser.add_argument("--version", action="version", version=f"gearcontact {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", required=True)
    for name in COMMANDS:
        importlib.import_module(f"{__name__}.{name}").register(sub)
    return parser


def main(argv: list[str] | None = None) -> int:
    """Entry point of the console script; returns the process exit code."""
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        return int(args.func(args) or 0)
    except (InputRangeError, ArithmeticError, FileNotFoundError, ValueError) as exc:
        # Bad input is reported as one clear line, not a traceback.
        print(f"gearcontact {args.command}: error: {exc}", file=sys.stderr)
        return 2


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
