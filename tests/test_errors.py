"""The error hierarchy (:mod:`gearcontact.errors`): every error the library raises on
purpose derives from the base of its kind, which fixes its exit code
(:data:`gearcontact.cli.EXIT_CODES`), and still from the builtin class callers caught
before (``except ValueError`` / ``ArithmeticError`` / ``RuntimeError`` keep working)."""

import pytest

from gearcontact.cli import exit_code_of
from gearcontact.cli.outdir import OutputDirectoryError
from gearcontact.halfspace.lcp import LcpConvergenceError
from gearcontact.errors import BadInput, CheckFailed, DatapathFlagged, RtlMismatch, ToolUnavailable
from gearcontact.geometry.conjugate import MeshingError, UndercutError
from gearcontact.hw.harness_cores import CoreUnavailable
from gearcontact.hw.synth import YosysNotFound
from gearcontact.hw.verilator import VerilatorBuildError, VerilatorNotFound
from gearcontact.contract.qformat import FixedPointOverflow
from gearcontact.tca.edges import PatternOffFlank
from gearcontact.tca.types import TcaConvergenceError
from gearcontact.validation import InputRangeError, UnusableInput


@pytest.mark.parametrize("cls, base, builtin, code", [
    (InputRangeError, BadInput, ValueError, 2),
    (UnusableInput, BadInput, ValueError, 2),
    (PatternOffFlank, BadInput, ValueError, 2),
    (UndercutError, BadInput, ValueError, 2),
    (OutputDirectoryError, BadInput, ValueError, 2),
    (VerilatorNotFound, ToolUnavailable, RuntimeError, 2),
    (VerilatorBuildError, ToolUnavailable, RuntimeError, 2),
    (CoreUnavailable, ToolUnavailable, RuntimeError, 2),
    (YosysNotFound, ToolUnavailable, RuntimeError, 2),
    (FixedPointOverflow, DatapathFlagged, ArithmeticError, 3),
    (LcpConvergenceError, CheckFailed, RuntimeError, 4),
    (TcaConvergenceError, CheckFailed, ArithmeticError, 4),
    (MeshingError, CheckFailed, ArithmeticError, 4),
    (RtlMismatch, CheckFailed, ArithmeticError, 4),
])
def test_library_errors_derive_from_their_kind(cls, base, builtin, code):
    assert issubclass(cls, base) and issubclass(cls, builtin)
    assert exit_code_of(cls) == code
