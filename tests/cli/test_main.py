"""The command line's contract (:func:`gearcontact.cli.main`): one exit-code convention,
all validation before the first expensive stage, named errors for bad files.

Truths: every bad option or file exits 2 with one stderr line naming the field (and the
limit where there is one) and *before any work*: the expensive stage is replaced by a
function that fails the test, and ``--out`` is never created; a bug (any other
exception) exits 1 with "internal error, please report" and shows the traceback only
with ``--debug``; a datapath flag exits 3 with the flag on stderr.
"""

import pytest

import gearcontact.cli.analyze as cli_analyze
import gearcontact.cli.ltca as cli_ltca
import gearcontact.cli.lte as cli_lte
import gearcontact.cli.preview as cli_preview
import gearcontact.cli.tca as cli_tca
from gearcontact.cli import EXIT_BAD_INPUT, EXIT_FLAGGED, EXIT_INTERNAL, main
from gearcontact.contract.stencil import stencil_coordinates, write_stencil_csv

S0003 = (__import__("importlib.resources").resources.files("gearcontact")
         / "data/pairs/s0003.toml").read_text()


@pytest.fixture
def no_work(monkeypatch):
    """The expensive first stage of every pair command fails the test if reached."""
    def fail(*a, **k):
        raise AssertionError("the expensive stage started before validation")

    for mod in (cli_tca, cli_ltca, cli_lte):
        monkeypatch.setattr(mod, "analyze_pair", fail)
    monkeypatch.setattr(cli_analyze, "run_analysis", fail)


def _err(capsys, argv):
    code = main(argv)
    err = capsys.readouterr().err
    return code, err


@pytest.mark.parametrize("argv, needles", [
    (["analyze", "--lte-torque", "0"], ["--lte-torque", "> 0"]),
    (["analyze", "--torques", "64.5", "1e9"], ["--torques", "1000000000.0", "131072] N"]),
    (["analyze", "--lte-phases", "2"], ["--lte-phases", "or 0 to skip"]),
    # more LTE than TCA phases ran with the TCA's 3 phases, exit 0
    (["analyze", "--phases", "3", "--lte-phases", "1001"], ["--lte-phases = 1001", "[3, 3]"]),
    (["tca", "--table-records", "0"], ["--table-records", "65535"]),
    (["tca", "--pairs", "99"], ["--pairs", "[0, 6]"]),
    (["tca", "--phases", "100000"], ["--phases", "1001"]),
    (["ltca", "--torque", "1e9"], ["--torque", "1000000000.0", "131072] N"]),
    (["ltca", "--cells", "5000"], ["--cells", "320"]),
    (["lte", "--torque", "0"], ["--torque"]),
])
def test_bad_options_rejected_before_any_work(tmp_path, capsys, no_work, argv, needles):
    out = tmp_path / "out"
    code, err = _err(capsys, argv[:1] + ["--out", str(out), "--quiet"] + argv[1:])
    assert code == EXIT_BAD_INPUT, err
    assert len(err.strip().splitlines()) == 1 and "Traceback" not in err
    for needle in needles:
        assert needle in err
    assert not out.exists()


def test_torque_named_not_load(tmp_path, capsys, no_work):
    code, err = _err(capsys, ["ltca", "--out", str(tmp_path / "o"), "--torque", "1e9"])
    assert code == 2 and "--torque" in err and "load_n" not in err


def test_torque_beyond_the_lever_limit_named_after_tca(tmp_path, capsys):
    """5500 N·m passes the outer-radius bound (6080 N·m for s0003-centred) but the
    TCA's lever (36.7 mm) makes W = 150 kN > 131072 N: still reported as --torque, with
    the limit of this pair (131072 N x 36.7 mm = 4.8 kN·m), before the LCP and any
    file."""
    out = tmp_path / "o"
    code, err = _err(capsys, ["ltca", "--pair", "s0003-centred", "--out", str(out),
                              "--torque", "5500", "--phases", "5", "--cells", "24"])
    assert code == EXIT_BAD_INPUT and "--torque (N·m) = 5500" in err and "(0, 48" in err
    assert "Traceback" not in err and not out.exists()   # created by the run, removed


@pytest.mark.parametrize("argv, needles", [
    (["vectors", "--count", "2000000"], ["--count", "[0, 100000]"]),
    (["rtl", "sim", "--core", "hertz", "--vectors", "0", "--no-corners"],
     ["--vectors", "at least 1 with --no-corners"]),
    (["rtl", "sim", "--core", "hertz", "--vectors", "20000000"], ["--vectors", "10000000"]),
    (["rtl", "sim", "--core", "hertz", "--jobs", "0"], ["--jobs"]),
])
def test_count_limits_in_the_message(tmp_path, capsys, argv, needles):
    if argv[0] == "vectors":
        argv = argv + ["--out", str(tmp_path / "v")]
    code, err = _err(capsys, argv)
    assert code == EXIT_BAD_INPUT
    for needle in needles:
        assert needle in err
    assert not (tmp_path / "v").exists()


def _pair_file(tmp_path, text: str | bytes):
    p = tmp_path / "pair.toml"
    (p.write_bytes if isinstance(text, bytes) else p.write_text)(text)
    return p


@pytest.mark.parametrize("content, needles", [
    (S0003.encode() + b"\n# \xff\xfe latin-1 bytes\n", ["pair.toml", "UTF-8"]),
    (S0003.replace("gear_mean_cone_distance_mm = 40.68", "gear_mean_cone_distance_mm = 1e5"),
     ["pair.toml", "gear_mean_cone_distance_mm", "5000"]),
    ("[teeth\n", ["pair.toml", "TOML"]),
])
def test_bad_pair_files_named(tmp_path, capsys, no_work, content, needles):
    path = _pair_file(tmp_path, content)
    for argv in (["design", "--pair", str(path)],
                 ["tca", "--pair", str(path), "--out", str(tmp_path / "o")]):
        code, err = _err(capsys, argv)
        assert code == EXIT_BAD_INPUT and "Traceback" not in err
        for needle in needles:
            assert needle in err, err
    assert not (tmp_path / "o").exists()


def test_stencil_file_errors_named(tmp_path, capsys):
    code, err = _err(capsys, ["preview", "--stencil", str(tmp_path), "--load", "10"])
    assert code == 2 and "stencil file" in err and "regular file" in err
    bad = tmp_path / "s.csv"
    bad.write_bytes(b"s_mm,t_mm,gap_mm\n\xff,0,0\n")
    code, err = _err(capsys, ["preview", "--stencil", str(bad), "--load", "10"])
    assert code == 2 and "s.csv" in err and "UTF-8" in err


@pytest.mark.parametrize("backend", ["reference", "golden", "rtl"])
@pytest.mark.parametrize("a, b, w, field", [
    ("16.0000001", "0.01", "100", "A_minus"),          # above the 16 1/mm register
    ("0.0004882", "0.0004882", "1", "A_minus"),        # below 2^-11 1/mm, rounds onto it
    ("0.1", "0.01", "200000", "load_n"),              # above 131072 N
])
def test_golden_and_reference_share_one_domain(capsys, backend, a, b, w, field):
    code, err = _err(capsys, ["preview", "--curvatures", a, b, "--load", w,
                              "--backend", backend])
    assert code == EXIT_BAD_INPUT and field in err


def test_datapath_flag_exit_code_and_stderr(tmp_path, capsys):
    s, t = stencil_coordinates()
    path = write_stencil_csv(tmp_path / "saddle.csv", 0.2 * s ** 2 - 0.01 * t ** 2)
    code = main(["preview", "--stencil", str(path), "--load", "10", "--backend", "golden",
                 "--json"])
    cap = capsys.readouterr()
    assert code == EXIT_FLAGGED
    assert "datapath flag: fit_not_elliptic" in cap.err


def test_a_library_warning_is_one_stderr_line_and_the_run_succeeds(capsys, monkeypatch):
    """Issue 28 probe: `analyze` exited 0 with fixed-point preview results missing and
    nothing on stderr. The library says so by a PreviewDomainWarning (its text naming
    which result is missing: tests/report/test_analyze.py); a command prints a library
    warning as one stderr line naming the command and the class, its exit code
    unchanged (the route of :func:`gearcontact.cli.main`, here through `preview`)."""
    import warnings

    from gearcontact.report.analyze import PreviewDomainWarning

    real = cli_preview.get_engine

    def warning_engine(*a, **k):
        warnings.warn("fixed-point preview outside the datapath's domain: golden D (line "
                      "core) p_max missing\n for 2 of 3 torques", PreviewDomainWarning)
        return real(*a, **k)

    monkeypatch.setattr(cli_preview, "get_engine", warning_engine)
    code = main(["preview", "--curvatures", "0.1", "0.01", "--load", "100"])
    cap = capsys.readouterr()
    assert code == 0 and "p_max" in cap.out
    assert cap.err == ("gearcontact preview: warning: fixed-point preview outside the "
                       "datapath's domain: golden D (line core) p_max missing for 2 of 3 "
                       "torques (PreviewDomainWarning)\n")


@pytest.mark.parametrize("exc", [ValueError("a bug"), ZeroDivisionError("a bug"),
                                 KeyError("a bug")])
def test_internal_error_exit_1_traceback_only_with_debug(capsys, monkeypatch, exc):
    def broken(*a, **k):
        raise exc

    monkeypatch.setattr(cli_preview, "get_engine", broken)
    argv = ["preview", "--curvatures", "0.1", "0.01", "--load", "100"]
    assert main(argv) == EXIT_INTERNAL
    err = capsys.readouterr().err
    assert "internal error, please report" in err and "Traceback" not in err
    assert len(err.strip().splitlines()) == 1
    assert main(argv + ["--debug"]) == EXIT_INTERNAL
    assert "Traceback" in capsys.readouterr().err


def test_disk_full_is_said_as_such(tmp_path, capsys, monkeypatch):
    import errno

    import gearcontact.cli.vectors as cli_vectors

    def full(*a, **k):
        raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr(cli_vectors, "export_vectors", full)
    assert main(["vectors", "--out", str(tmp_path / "v"), "--count", "1"]) == EXIT_INTERNAL
    err = capsys.readouterr().err
    assert "system refused a write" in err and "please report" not in err


def test_ctrl_c_while_the_commands_load(monkeypatch, capsys):
    """Ctrl-C during ``build_parser`` (it imports the command's module: seconds on a
    cold start) printed a KeyboardInterrupt traceback; now one line and exit 130."""
    import gearcontact.cli as cli

    def interrupted(argv=None):
        raise KeyboardInterrupt

    monkeypatch.setattr(cli, "build_parser", interrupted)
    assert cli.main(["tca", "--out", "unused"]) == 130
    err = capsys.readouterr().err
    assert err == "gearcontact: interrupted\n"


@pytest.mark.parametrize("delay_s", [0.0, 0.05, 0.3, 1.0])
def test_ctrl_c_early_in_a_real_process(tmp_path, delay_s):
    """Ctrl-C in the first fraction of a second of a command (numpy and the command
    modules still importing) gives the one line and exit 130, never a traceback:
    ``import gearcontact.cli`` is light (no numpy), so the handler in ``main`` is in place
    after a few milliseconds. The child says "ready" once ``gearcontact.cli`` is imported
    and then runs :func:`gearcontact.cli.console_main` exactly as the console script
    does; the delays count from there, not from the process start, because the
    interpreter's own start (where Python itself owns SIGINT) takes from 30 ms to
    seconds on a loaded machine. Exit 130, not -2: see
    :func:`gearcontact.cli.console_main`."""
    import signal
    import subprocess
    import sys
    import time

    # Python's own handler, as a command started from a terminal has it: a process
    # started in the background by a non-interactive shell (`cmd &`, as a test run may
    # be) inherits SIGINT ignored, and Python then installs no handler of its own
    child = ("import signal, sys; signal.signal(signal.SIGINT, signal.default_int_handler); "
             "from gearcontact.cli import console_main; "
             f"sys.argv = ['gearcontact', 'tca', '--pair', 's0003', '--out', {str(tmp_path / 'out')!r}]; "
             "print('ready', file=sys.stderr, flush=True); console_main()")
    proc = subprocess.Popen([sys.executable, "-c", child],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    assert proc.stderr.readline().strip() == "ready"
    time.sleep(delay_s)
    proc.send_signal(signal.SIGINT)
    _, err = proc.communicate(timeout=120)
    assert "Traceback" not in err, err
    assert proc.returncode == 130, (proc.returncode, err)
    assert err.strip().endswith("interrupted"), err
    assert not (tmp_path / "out").exists()


def test_ctrl_c_swallowed_by_an_import_still_interrupts(tmp_path, monkeypatch, capsys):
    """An interrupt that lands inside code which catches and drops it (an extension
    module clearing the pending error of an import probe: seen once in CI, where the
    command then ran to exit 0) still ends the command with 130, keeping no output: the
    latch in :func:`gearcontact.cli.main` records the signal itself."""
    import os
    import signal

    from gearcontact import cli

    real_build = cli.build_parser

    def swallowing_build(argv=None):
        try:
            os.kill(os.getpid(), signal.SIGINT)         # the handler runs on return
        except KeyboardInterrupt:
            pass                                         # what the extension did
        return real_build(argv)

    monkeypatch.setattr(cli, "build_parser", swallowing_build)
    # Python's own handler, as a command started from a terminal has it (a test run
    # started in the background by a non-interactive shell inherits SIGINT ignored)
    before = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        out = tmp_path / "out"
        assert cli.main(["tca", "--pair", "s0003", "--out", str(out)]) == 130
        assert capsys.readouterr().err.strip().endswith("interrupted")
        assert not out.exists()
        # the latch is gone after main: Python's own handler is back
        assert signal.getsignal(signal.SIGINT) is signal.default_int_handler
    finally:
        signal.signal(signal.SIGINT, before)


def test_package_import_is_light():
    """``import gearcontact.cli`` loads no numpy (the console script's Ctrl-C handler
    must be reachable at once); the public names still resolve lazily."""
    import subprocess
    import sys

    code = ("import sys, gearcontact.cli; assert 'numpy' not in sys.modules; "
            "import gearcontact; assert gearcontact.STEEL.youngs_modulus_mpa == 209000.0")
    subprocess.run([sys.executable, "-c", code], check=True)


def test_a_command_imports_only_its_own_module():
    """``gearcontact design`` imports its command module and none of the other 12 nor
    matplotlib (docs/performance.md, "Test suite budget": importing every command module
    and the plotting code cost 1.4 s of CPU in every process); ``gearcontact --help``
    still lists every command."""
    import subprocess
    import sys

    from gearcontact.cli import COMMANDS

    code = """if True:
        import contextlib, io, sys
        from gearcontact.cli import main
        with contextlib.redirect_stdout(io.StringIO()):
            assert main(["design", "--pair", "s0003", "--json"]) == 0
        print(*sorted(m for m in sys.modules if m.startswith("gearcontact.cli.")
                      or m.split(".")[0] == "matplotlib"))"""
    child = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                           check=True, timeout=300)
    loaded = child.stdout.split()
    # warm_up: its first-run note (``note_cold_cache``, no numpy), before every command
    assert loaded == ["gearcontact.cli.design", "gearcontact.cli.design_modes",
                      "gearcontact.cli.design_options", "gearcontact.cli.outdir",
                      "gearcontact.cli.warm_up"], loaded
    usage = subprocess.run([sys.executable, "-m", "gearcontact", "--help"], capture_output=True,
                           text=True, check=True, timeout=300).stdout
    assert all(f"    {name} " in usage or f"    {name}\n" in usage for name in COMMANDS), usage
