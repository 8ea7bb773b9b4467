"""The package's error hierarchy: four kinds of failure, each one exit code of the CLI.

Every error the library raises on purpose derives from one of these bases, so that a
caller (and :func:`gearcontact.cli.main`, which maps them to exit codes in one table,
:data:`gearcontact.cli.EXIT_CODES`) tells them apart by class:

- :class:`BadInput` (exit 2): the user's input (an option, an input file, the output
  directory, a missing optional tool); raised before work.
- :class:`DatapathFlagged` (exit 3): the fixed-point datapath flagged what it was given;
  its outputs are invalid.
- :class:`CheckFailed` (exit 4): a computation did not pass its own check (an LCP did not
  converge, a Newton iteration inside a run failed, the RTL disagrees with the golden
  model).
- anything else (exit 1): a bug.

The bases also derive from the builtin class their subclasses had before
(:class:`ValueError`, :class:`ArithmeticError`), so ``except ValueError`` around an
input check keeps working. This module imports nothing: every other module may use it.
"""

from __future__ import annotations

__all__ = ["GearcontactError", "BadInput", "ToolUnavailable", "DatapathFlagged", "CheckFailed",
           "RtlMismatch"]


class GearcontactError(Exception):
    """Base of every error the package raises on purpose (not a bug).

    Pickled with its attributes and message as they are, whatever its ``__init__``
    takes: it crosses a process pool intact (the default, ``cls(*args)``, fails in the
    parent for an ``__init__`` of other arguments, which then reports a
    ``BrokenProcessPool`` instead of this error).
    """

    def __reduce__(self):
        return (_restore, (type(self), self.args, self.__dict__))


class BadInput(GearcontactError, ValueError):
    """The user's input cannot be used as given (exit 2). Raised before expensive work;
    the message names the field, the value and the allowed range (or the reason)."""


class ToolUnavailable(BadInput):
    """An optional tool (Verilator, Yosys, LiteX, an RTL core's Amaranth) is missing or
    unusable here (exit 2): the message says what to install."""


class DatapathFlagged(GearcontactError, ArithmeticError):
    """The fixed-point datapath flagged its input; its outputs are invalid (exit 3)."""


class CheckFailed(GearcontactError, ArithmeticError):
    """A computation did not pass its own check (exit 4): an LCP that did not converge,
    a Newton iteration that failed inside a run, RTL != golden."""


class RtlMismatch(CheckFailed):
    """The RTL disagrees with the bit-exact golden model (bits or cycle counts)."""


def _restore(cls, args, state):
    """Unpickle a :class:`GearcontactError` without calling its ``__init__``."""
    exc = cls.__new__(cls, *args)
    exc.args = args
    exc.__dict__.update(state)
    return exc
