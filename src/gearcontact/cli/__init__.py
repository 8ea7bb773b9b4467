"""The ``gearcontact`` command line: a thin layer that parses, calls the library and
writes files. Each subcommand lives in its own module ``gearcontact.cli.<name>`` that
defines ``register(subparsers)``; its handler is stored as ``func`` on the parser, an
optional cheap ``check(args)`` (all option and input-file validation) as ``check``.

:func:`main` runs, in this order: the command's ``check``, the output-directory policy
of :mod:`.outdir` (commands with ``--out``), the handler. One exit-code convention
holds for every command, mapped in one place (:data:`EXIT_CODES`, by the class of what
the command raised; :mod:`gearcontact.errors` holds the bases):

====  ==================================================================================
code  meaning
====  ==================================================================================
0     success
1     internal error (a bug: any exception outside :mod:`gearcontact.errors`' classes):
      one line "internal error, please report"; the traceback is printed only with
      ``--debug``. Also a write the system refused (disk full, read-only file system),
      said as such
2     bad input (:class:`~gearcontact.errors.BadInput`): an option, an input file or the
      output directory, reported in one line naming the field, the value, the allowed
      range and the file where one is involved, before any work; also a missing
      optional tool
3     the fixed-point datapath flagged this input
      (:class:`~gearcontact.errors.DatapathFlagged`; golden / rtl preview, twin): the
      flags are printed on stderr; the outputs are invalid
4     the computation did not pass its own check
      (:class:`~gearcontact.errors.CheckFailed`): an LCP did not converge, a Newton
      iteration failed inside a run, or the RTL disagrees with the golden model
====  ==================================================================================

A command whose computation ends with 3 or 4 keeps the files it wrote (``run.json``
records the exit code); after 1, 2 or an interrupt the output directory keeps its
previous run.
"""

from __future__ import annotations

import argparse
import errno
import importlib
import os
import signal
import sys
import threading
import traceback
import warnings

from ..errors import BadInput, CheckFailed, DatapathFlagged, GearcontactError

__all__ = ["main", "console_main", "build_parser", "exit_code_of", "EXIT_OK", "EXIT_INTERNAL",
           "EXIT_BAD_INPUT", "EXIT_FLAGGED", "EXIT_CHECK_FAILED", "EXIT_CODES",
           "EXIT_INTERRUPTED"]

#: Subcommand -> its module ``gearcontact.cli.<module>``, in the order ``gearcontact
#: --help`` lists them.
COMMANDS = {"analyze": "analyze", "reproduce": "reproduce", "preview": "preview",
            "design": "design", "tca": "tca", "rtl": "rtl", "vectors": "vectors",
            "ltca": "ltca", "lte": "lte", "bending": "bending", "twin": "twin",
            "sweep": "sweep", "export": "export", "warm-up": "warm_up"}

EXIT_OK = 0
#: A bug: "internal error, please report" (traceback with --debug).
EXIT_INTERNAL = 1
#: Bad input (option, input file, output directory) or a missing optional tool.
EXIT_BAD_INPUT = 2
#: The fixed-point datapath flagged this input (flags on stderr).
EXIT_FLAGGED = 3
#: The computation failed its own check (LCP not converged, RTL != golden).
EXIT_CHECK_FAILED = 4
#: Ctrl-C (128 + SIGINT, as a shell reports it).
EXIT_INTERRUPTED = 130

#: The one map from what a command raised to the exit code (first match; anything
#: else is a bug, :data:`EXIT_INTERNAL`), with the word stderr shows before the message.
EXIT_CODES = ((BadInput, EXIT_BAD_INPUT, "error"),
              (DatapathFlagged, EXIT_FLAGGED, "datapath flag"),
              (CheckFailed, EXIT_CHECK_FAILED, "check failed"),
              (KeyboardInterrupt, EXIT_INTERRUPTED, "interrupted"))


def exit_code_of(exc: BaseException | type) -> int:
    """The exit code of a command that raised ``exc`` (an exception or its class)."""
    cls = exc if isinstance(exc, type) else type(exc)
    return next((code for base, code, _ in EXIT_CODES if issubclass(cls, base)),
                EXIT_INTERNAL)


def _leaf_parsers(parser: argparse.ArgumentParser):
    """Every parser that runs a handler (subcommands and ``rtl`` actions)."""
    subs = [a for a in parser._actions if isinstance(a, argparse._SubParsersAction)]
    if not subs:
        yield parser
        return
    for action in subs:
        for child in dict.fromkeys(action.choices.values()):
            yield from _leaf_parsers(child)


def build_parser(argv: list[str] | None = None) -> argparse.ArgumentParser:
    """The parser of the command line.

    Parameters
    ----------
    argv : list of str, optional
        The arguments it will parse. When the first one names a command, only that
        command's module is imported and registered: the command modules import numpy,
        scipy, numba and the plotting code, about 2 s of CPU for all of them against a
        fraction for one. Otherwise (none given, ``--help``, ``--version``, a misspelt
        command) every command is registered, so that help and errors list them all.
    """
    from .. import __version__

    parser = argparse.ArgumentParser(
        prog="gearcontact",
        description="Gear tooth-contact computation: hypoid flanks, TCA, LTCA and the "
                    "physics-direct Hertz preview (fp64 / fixed point / RTL).",
        epilog="exit codes: 0 success, 1 internal error (traceback with --debug), 2 bad "
               "input, 3 fixed-point datapath flagged the input, 4 a computation failed "
               "its own check (LCP not converged, RTL != golden)")
    parser.add_argument("--version", action="version", version=f"gearcontact {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", required=True)
    chosen = [argv[0]] if argv and argv[0] in COMMANDS else COMMANDS
    for name in chosen:
        importlib.import_module(f"{__name__}.{COMMANDS[name]}").register(sub)
    for leaf in _leaf_parsers(parser):
        leaf.add_argument("--debug", action="store_true",
                          help="print the traceback of an internal error")
    return parser


class _SigintLatch:
    """Remember every Ctrl-C while a command runs, even one an extension swallowed.

    Python raises ``KeyboardInterrupt`` at the next bytecode boundary after SIGINT; when
    that boundary lies inside an import that an extension module drives through the C
    API and then clears the pending error (optional-submodule probes do), the interrupt
    is lost and the command would run on to exit 0. The latch records the signal itself,
    so :func:`main` can still end the run as interrupted. Installed only in the main
    thread (``signal.signal`` refuses elsewhere); a no-op otherwise.
    """

    def __init__(self):
        self.hit = False
        self._previous = None

    def _handler(self, signum, frame):
        self.hit = True
        signal.default_int_handler(signum, frame)

    def __enter__(self):
        if threading.current_thread() is threading.main_thread():
            self._previous = signal.signal(signal.SIGINT, self._handler)
        return self

    def __exit__(self, *exc):
        if self._previous is not None:
            signal.signal(signal.SIGINT, self._previous)
        return False

    def check(self) -> None:
        """Raise ``KeyboardInterrupt`` if a Ctrl-C arrived and was swallowed."""
        if self.hit:
            raise KeyboardInterrupt


def _run(args, argv: list[str], name: str) -> int:
    def one_line(message, category, *_args, **_kwargs):
        # warnings users must see: one line each on stderr, no source excerpt
        text = " ".join(str(message).split())
        print(f"gearcontact {name}: warning: {text} ({category.__name__})", file=sys.stderr)

    with warnings.catch_warnings():           # the filters stay Python's defaults
        warnings.showwarning = one_line
        return _run_command(args, argv, name)


def _work(args, name: str, fn=None) -> int:
    """The command's work (``fn``, default ``args.func``: its checks too); an input
    error it finds in typed machine settings the check before it warned about is named
    by that check's likely slip (:mod:`.settings_slip`)."""
    try:
        return int((fn or args.func)(args) or 0)
    except BadInput as exc:
        from .settings_slip import work_slip_renamed

        renamed = work_slip_renamed(exc, args, name)
        if renamed is exc:
            raise
        raise renamed from exc


def _run_command(args, argv: list[str], name: str) -> int:
    latch = args.sigint_latch
    check = getattr(args, "check", None)
    if check is not None:
        _work(args, name, check)    # cheap validation before any work or output
    from .warm_up import note_cold_cache
    note_cold_cache(args.command, getattr(getattr(args, "gear_pair", None), "kind", None))
    latch.check()
    if not getattr(args, "writes_files", False):
        code = _work(args, name)
        latch.check()
        return code
    from .outdir import RunDirectory

    with RunDirectory(args.out, argv, force=args.force,
                      staged=getattr(args, "staged_output", True),
                      resume=getattr(args, "resume_entries", ()), command=name) as run:
        args.run, args.out = run, run.work
        run.input_checks.update(getattr(args, "input_checks", {}))
        run.timings_s.update(getattr(args, "input_timings_s", {}))
        run.exit_code = _work(args, name)
        latch.check()           # a swallowed Ctrl-C still discards the run
        if run.exit_code in (EXIT_INTERNAL, EXIT_BAD_INPUT):
            run.discard()       # a refused run keeps nothing; the previous run stays
    return run.exit_code


def main(argv: list[str] | None = None) -> int:
    """Entry point of the console script; returns the process exit code."""
    argv = list(sys.argv[1:] if argv is None else argv)
    with _SigintLatch() as latch:
        return _main(argv, latch)


def _main(argv: list[str], latch: _SigintLatch) -> int:
    try:
        # everything heavy (numpy, the command's module: seconds when cold) is imported
        # here, inside the Ctrl-C handler; ``import gearcontact.cli`` itself is light
        parser = build_parser(argv)
        args = parser.parse_args(argv)
        latch.check()
    except BaseException as exc:
        # an interrupt inside an extension's import can surface as the ImportError it
        # caused (numpy: "PyCapsule_Import could not import module 'datetime'")
        if not (latch.hit or isinstance(exc, KeyboardInterrupt)):
            raise
        print("gearcontact: interrupted", file=sys.stderr)
        return EXIT_INTERRUPTED
    args.sigint_latch = latch
    name = " ".join(filter(None, (args.command, getattr(args, "rtl_command", None),
                                  getattr(args, "export_command", None))))
    try:
        return _run(args, argv, name)
    except Exception as exc:
        if not latch.hit:
            return _failed(exc, name, args)
        print(f"gearcontact {name}: interrupted", file=sys.stderr)
        return EXIT_INTERRUPTED
    except KeyboardInterrupt as exc:
        return _failed(exc, name, args)


def _failed(exc: BaseException, name: str, args) -> int:
    """Say in one line on stderr how a command that raised ``exc`` ended; its exit code."""
    if isinstance(exc, (GearcontactError, KeyboardInterrupt)):
        # one line: bad input names the field, the value and the allowed range (or why
        # the pair cannot be analysed as given); a flag or a failed check says what
        code = exit_code_of(exc)
        word = next(w for base, c, w in EXIT_CODES if c == code)
        print(f"gearcontact {name}: {word}" + (f": {exc}" if str(exc) else ""),
              file=sys.stderr)
        return code
    if isinstance(exc, BrokenPipeError):
        # the reader of stdout went away (``| head``): not an error of ours
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 141
    if isinstance(exc, OSError) and exc.errno in _SYSTEM_REFUSED:
        print(f"gearcontact {name}: error: the system refused a write ({exc}); the "
              "output directory keeps its previous run", file=sys.stderr)
        return EXIT_INTERNAL
    return _internal(name, exc, args)   # the last line of defence: report a bug


def console_main() -> None:
    """The console script and ``python -m gearcontact``: :func:`main`, then exit.

    After a Ctrl-C the process ends with ``os._exit(130)`` once stdout and stderr are
    flushed: an interrupt that landed in code an extension module ran through
    ``PyRun_String`` (numpy and numba initialise that way) leaves CPython's
    "unhandled KeyboardInterrupt" mark set even though :func:`main` handled it, and the
    interpreter would then kill itself with SIGINT (exit -2) instead of exiting 130.
    Nothing is left to clean up at that point: the output directory was restored by
    its context manager before the handler ran.
    """
    try:
        code = main()
    except KeyboardInterrupt:       # in the instant before main's own handler was set
        print("gearcontact: interrupted", file=sys.stderr)
        code = EXIT_INTERRUPTED
    if code == 130:
        sys.stdout.flush()
        sys.stderr.flush()
        os._exit(130)
    sys.exit(code)


#: errno values of an OSError that are the system's refusal, not a bug (disk full,
#: quota, I/O error, read-only file system).
_SYSTEM_REFUSED = {errno.ENOSPC, errno.EDQUOT, errno.EIO, errno.EROFS}


def _internal(name: str, exc: BaseException, args) -> int:
    """A bug: one line asking for a report; the traceback only with ``--debug``."""
    if getattr(args, "debug", False):
        traceback.print_exception(exc)
    print(f"gearcontact {name}: internal error, please report "
          f"({type(exc).__name__}: {exc}); rerun with --debug for the traceback",
          file=sys.stderr)
    return EXIT_INTERNAL


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
