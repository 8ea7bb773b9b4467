"""One exit code per kind of failure (:data:`gearcontact.cli.EXIT_CODES`), each seen
from outside: a real process, its return code and its stderr.

Truths: bad input exits 2 before any work, the fixed-point datapath's flag exits 3, a
computation that fails its own check exits 4, a bug exits 1 (issue 28, item 3). Exits
2 and 3 run the installed console script ``gearcontact``; exits 4 and 1 need a failure
that no valid input of a correct program produces, so their process runs
:func:`gearcontact.cli.console_main` (the console script's entry point, the same
code) after replacing one function: for 4 the golden model the RTL is compared with
(the comparison itself is real: the RTL runs in the Amaranth simulator), for 1 the
preview engine (it raises ZeroDivisionError, as a bug would).
"""

import subprocess
import sys
import textwrap

import pytest

from gearcontact.errors import BadInput, CheckFailed, DatapathFlagged, ToolUnavailable
from gearcontact.cli import EXIT_CODES, exit_code_of
from gearcontact.contract.stencil import stencil_coordinates, write_stencil_csv
from console_script import ENV, run_console


def _entry_point(setup: str, *argv):
    """Run ``console_main`` in a fresh interpreter after ``setup``."""
    code = textwrap.dedent(setup) + textwrap.dedent(f"""
        import sys
        sys.argv = ["gearcontact", *{list(argv)!r}]
        from gearcontact.cli import console_main
        console_main()
        """)
    p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                       env=ENV, timeout=300)
    return p.returncode, p.stdout, p.stderr


def test_bad_input_exit_2(tmp_path):
    """A stencil gap beyond STENCIL_GAP Q(32,21) with the golden datapath was a
    FixedPointOverflow reported as an internal error (exit 1); it is the file's value:
    exit 2 naming the file, the row and the column, before any engine is built."""
    s, t = stencil_coordinates()
    gaps = 0.01 * (s ** 2 + t ** 2)
    gaps[7] = 2000.0                               # mm; Q(32,21) ends at 1024 mm
    path = write_stencil_csv(tmp_path / "far.csv", gaps)
    code, out, err = run_console("preview", "--stencil", str(path), "--load", "10",
                             "--backend", "golden")
    assert code == 2, err
    assert out == ""
    assert err.startswith("gearcontact preview: error: ") and len(err.splitlines()) == 1
    assert f"{path}: row 8 (sample 7), column gap_mm = 2000.0" in err
    assert "[-1024, 1023.9999995231628] mm" in err      # 2^10 - 2^-21: the format's ends


def test_datapath_flag_exit_3(tmp_path):
    """A saddle stencil (A- > 0 > B-): the golden datapath flags fit_not_elliptic."""
    s, t = stencil_coordinates()
    path = write_stencil_csv(tmp_path / "saddle.csv", 0.2 * s ** 2 - 0.01 * t ** 2)
    code, out, err = run_console("preview", "--stencil", str(path), "--load", "10",
                             "--backend", "golden")
    assert code == 3, err
    assert "fit_not_elliptic" in out and "datapath flag: fit_not_elliptic" in err


def test_failed_check_exit_4():
    """RTL != golden: the golden model's flags of vector 1 are inverted, so the real RTL
    (Amaranth simulation) disagrees on exactly that vector."""
    setup = """
        import dataclasses
        import numpy as np
        import gearcontact.hw.harness_cores as hc
        bench = hc.get_bench("fit")
        def wrong(st):
            cols = bench.golden(st)
            cols["flags"] = cols["flags"] ^ (np.arange(len(st)) == 1)
            return cols
        hc.BENCHES["fit"] = dataclasses.replace(bench, golden=wrong)
        """
    code, out, err = _entry_point(setup, "rtl", "sim", "--core", "fit", "--vectors", "2",
                                  "--no-corners", "--simulator", "amaranth")
    assert code == 4, err
    assert "mismatches   1" in out
    assert err.strip().splitlines()[-1].startswith(
        "gearcontact rtl sim: check failed: RTL != golden on core fit: 1 of 2 vectors")


def test_bug_exit_1():
    """One line asking for a report, no traceback (``--debug`` shows it: test_main)."""
    setup = """
        import gearcontact.cli.preview as cli_preview
        def broken(*a, **k):
            return 1 / 0
        cli_preview.get_engine = broken
        """
    argv = ("preview", "--curvatures", "0.1", "0.01", "--load", "100")
    code, _, err = _entry_point(setup, *argv)
    assert code == 1
    assert err == ("gearcontact preview: internal error, please report (ZeroDivisionError: "
                   "division by zero); rerun with --debug for the traceback\n")


@pytest.mark.parametrize("exc, code", [
    (BadInput("x"), 2), (ToolUnavailable("x"), 2), (DatapathFlagged("x"), 3),
    (CheckFailed("x"), 4), (KeyboardInterrupt(), 130), (ValueError("x"), 1),
    (ArithmeticError("x"), 1), (RuntimeError("x"), 1)])
def test_one_map_from_class_to_code(exc, code):
    """The map is by class: the package's bases, and anything else a bug (a plain
    ValueError or ArithmeticError is not input or a check: it is 1)."""
    assert exit_code_of(exc) == exit_code_of(type(exc)) == code
    assert [c for _, c, _ in EXIT_CODES] == [2, 3, 4, 130]


# ------------------------------------------------------------------ twin: exits 3 and 4
def _module(*argv):
    """Run ``python -m gearcontact`` in a fresh interpreter; (return code, stdout, stderr)."""
    p = subprocess.run([sys.executable, "-m", "gearcontact", *argv], capture_output=True,
                       text=True, env=ENV, timeout=600)
    return p.returncode, p.stdout, p.stderr


def _s0003_with(tmp_path, name, **moduli_mpa):
    """s0003 as a pair TOML with other Young's moduli (``pinion=``, ``gear=``, MPa)."""
    from dataclasses import replace

    from gearcontact.geometry.pair import load_pair, pair_to_toml
    pair = load_pair("s0003")
    mats = {f"{member}_material": replace(getattr(pair, f"{member}_material"),
                                          youngs_modulus_mpa=e)
            for member, e in moduli_mpa.items()}
    path = tmp_path / f"{name}.toml"
    path.write_text(pair_to_toml(replace(pair, name=name, **mats)))
    return path


def test_twin_datapath_flag_exit_3(tmp_path):
    """The twin evaluates a preview outside the datapath's domain by the fp64 law (a
    result, issue 28 item 2), so what makes its golden datapath refuse is an input the
    datapath cannot hold at all: E' is a Q(32,0) register (MPa), and moduli of 5e9 MPa
    give E' = 5.49e9 > 2^31 - 1. Found by a real run, no patch: exit 3 naming the signal
    and the format (the E' the material check accepts: any positive modulus)."""
    path = _s0003_with(tmp_path, "stiff", pinion=5e9, gear=5e9)
    code, out, err = _module("twin", "--pair", str(path), "--backend", "golden",
                             "--phases", "11", "--duration-ms", "0.05", "--no-figures",
                             "--quiet", "--out", str(tmp_path / "x"))
    assert code == 3, err
    assert err.startswith("gearcontact twin: datapath flag: e_prime_mpa = 549450549")
    assert "does not fit Q(32,0)" in err


@pytest.mark.slow
def test_twin_failed_check_exit_4(tmp_path, served_tri_core):
    """A board built for another pair: `gearcontact rtl serve` bakes steel-on-steel E'
    into its SoC (as a board build would), the twin runs s0003 with a bronze gear
    (E = 110 GPa) through it. The golden loop's previews replayed on that board differ
    (its E' register is another pair's): RTL != golden, a failed check, exit 4, with the
    hint that names the E' code. Real processes, no patch (~1 min: the SoC is simulated
    behind litex_server's protocol)."""
    path = _s0003_with(tmp_path, "bronze_gear", gear=110e3)
    host, port = served_tri_core
    code, out, err = _module("twin", "--pair", str(path), "--backend", "soc", "--board",
                             f"{host}:{port}", "--phases", "11", "--duration-ms", "0.03",
                             "--step-us", "10", "--no-figures", "--quiet",
                             "--out", str(tmp_path / "x"))
    assert code == 4, err
    last = err.strip().splitlines()[-1]
    assert last.startswith("gearcontact twin: check failed: soc != golden in ")
    assert "was the board built with E' code" in last
