"""The ``rtl`` preview backend equals the ``golden`` backend exactly (codes, flags,
decoded values and cycles), under Verilator and under the Amaranth simulator."""

import dataclasses
import subprocess
import sys

import numpy as np
import pytest

from gearcontact.hw import backends as hardware_backends
from gearcontact.hw import verilator as vl
from gearcontact.preview.engine import BACKENDS, get_engine
from gearcontact.contract.stencil import stencil_coordinates
from gearcontact.preview.hertz.schedule import CHAIN_CYCLES, HERTZ_CYCLES

needs_verilator = pytest.mark.skipif(
    not vl.verilator_available(), reason=f"Verilator toolchain not installed: {vl.INSTALL_HINT}")

HERTZ_INPUTS = [(0.05, 0.01, 1000.0),       # elliptic, alpha 5
                (0.2, 0.2, 1.0),            # A = B, minimum load
                (2.0 ** -7, 1.0, 500.0)]    # alpha = 128, the envelope's edge
#: Outside the operating envelope: every backend rejects them alike before any datapath
#: runs (the flag behaviour of the cores on such codes is covered by the bulk corner
#: vectors of tests/hw, RTL == golden on the raw codes).
OUTSIDE_ENVELOPE = [(2.0 ** -11, 0.25, 500.0),  # alpha 512 > 128
                    (0.01, 0.03, 2.0e5)]        # load above the envelope


def _stencil(A, B, theta=0.3, c0=0.0):
    s, t = stencil_coordinates()
    c, si = np.cos(theta), np.sin(theta)
    u, v = c * s + si * t, -si * s + c * t
    return c0 + A * u ** 2 + B * v ** 2


STENCILS = [(_stencil(0.05, 0.01), 1200.0), (_stencil(0.3, -0.1), 800.0),
            (_stencil(0.02, 0.02, c0=-0.01), 50.0)]


def _same(rtl, gold, cycles):
    assert rtl.backend == "rtl"
    assert rtl.cycles == cycles
    assert dataclasses.replace(rtl, backend="golden") == gold


def test_registration_is_inverted_and_does_not_load_amaranth():
    """preview.engine knows only reference and golden; importing gearcontact.hw.backends
    registers the hardware ones, still without importing Amaranth."""
    code = ("import sys, gearcontact.preview.engine as e; "
            "assert set(e.BACKENDS) == {'reference', 'golden'}, e.BACKENDS; "
            "assert 'gearcontact.hw' not in sys.modules, 'preview imports hw'; "
            "import gearcontact.hw.backends; "
            "assert {'rtl', 'rtl-soc'} <= set(e.BACKENDS); "
            "assert 'amaranth' not in sys.modules")
    subprocess.run([sys.executable, "-c", code], check=True)
    assert set(hardware_backends.HARDWARE_BACKENDS) <= set(BACKENDS)


@needs_verilator
@pytest.mark.parametrize("A,B,W", HERTZ_INPUTS)
def test_hertz_rtl_equals_golden(A, B, W):
    _same(get_engine("rtl").hertz(A, B, W), get_engine("golden").hertz(A, B, W),
          HERTZ_CYCLES)


@pytest.mark.parametrize("A,B,W", OUTSIDE_ENVELOPE)
def test_rtl_rejects_what_golden_rejects(A, B, W):
    from gearcontact.validation import InputRangeError

    for name in ("golden", "rtl", "reference"):
        with pytest.raises(InputRangeError):
            get_engine(name).hertz(A, B, W)


@needs_verilator
@pytest.mark.parametrize("k", range(len(STENCILS)))
def test_stencil_rtl_equals_golden(k):
    gaps, w = STENCILS[k]
    _same(get_engine("rtl").stencil(gaps, w), get_engine("golden").stencil(gaps, w),
          CHAIN_CYCLES)


@needs_verilator
def test_hertz_batch_rtl_equals_golden():
    A = np.array([[0.05, 0.2], [0.01, 1.0]])
    B = np.array([[0.01, 0.2], [0.5, 2.0 ** -11]])
    W = np.array([1000.0, 10.0])
    r, g = get_engine("rtl").hertz_batch(A, B, W), get_engine("golden").hertz_batch(A, B, W)
    assert r.backend == "rtl" and r.a_mm.shape == (2, 2)
    for f in ("a_mm", "b_mm", "k", "p_max_mpa", "flags"):
        np.testing.assert_array_equal(getattr(r, f), getattr(g, f))


def test_amaranth_simulator_path_equals_golden():
    eng = get_engine("rtl")
    amaranth = type(eng)(simulator="amaranth") if eng.simulator != "amaranth" else eng
    A, B, W = HERTZ_INPUTS[0]
    _same(amaranth.hertz(A, B, W), get_engine("golden").hertz(A, B, W), HERTZ_CYCLES)
    gaps, w = STENCILS[0]
    _same(amaranth.stencil(gaps, w), get_engine("golden").stencil(gaps, w), CHAIN_CYCLES)


def test_bad_inputs_are_rejected_like_golden():
    from gearcontact.validation import InputRangeError
    eng = get_engine("rtl")
    with pytest.raises(InputRangeError, match="load_n"):
        eng.hertz(0.1, 0.1, -5.0)
    with pytest.raises(InputRangeError, match="stencil length"):
        eng.stencil(np.zeros(48), 100.0)


def test_verilator_requested_but_missing(monkeypatch):
    from gearcontact.hw.rtl_engine import RtlEngine
    monkeypatch.setattr(vl.shutil, "which", lambda name: None)
    with pytest.raises(vl.VerilatorNotFound, match="apt-get install"):
        RtlEngine(simulator="verilator")
    monkeypatch.setenv("GEARCONTACT_RTL_SIMULATOR", "amaranth")
    assert RtlEngine().simulator == "amaranth"


@pytest.mark.parametrize("simulator", ["amaranth", "verilator"])
def test_exact_form_rtl_equals_golden(simulator):
    """get_engine("rtl", hertz_form="exact") runs the hertz_exact / chain_exact cores:
    same codes, flags, cycles and hertz_form as the exact golden backend (the stencil
    under Amaranth only: chain_exact's Verilator build, 18 s, is left to the slow suite)."""
    if simulator == "verilator" and not vl.verilator_available():
        pytest.skip(f"Verilator toolchain not installed: {vl.INSTALL_HINT}")
    rtl = get_engine("rtl", hertz_form="exact")
    rtl = type(rtl)(simulator=simulator, hertz_form="exact")
    gold = get_engine("golden", hertz_form="exact")
    A, B, W = HERTZ_INPUTS[0]
    r = rtl.hertz(A, B, W)
    _same(r, gold.hertz(A, B, W), HERTZ_CYCLES)
    assert r.hertz_form == "exact" and r.k != get_engine("golden").hertz(A, B, W).k
    if simulator == "amaranth":
        gaps, w = STENCILS[0]
        _same(rtl.stencil(gaps, w), gold.stencil(gaps, w), CHAIN_CYCLES)
