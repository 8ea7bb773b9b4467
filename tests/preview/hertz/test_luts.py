"""Stage-D ROM contents and interpolation accuracy (truths: x**(2/pi), x**(1/3), and
the exact Hertz k(alpha), E(alpha) of :func:`analytic.hertz.exact_ellipticity`)."""

import math

import numpy as np
import pytest

from gearcontact.analytic.hertz import exact_ellipticity
from gearcontact.preview.hertz.luts import (CBRT_SPEC, EE_EXACT_SPEC, LUT_SIZE,
                                            POW_EXACT_SPEC, POW_SPEC, LutSpec, cbrt_lut,
                                            lut_interpolate, pow_lut, rom_words,
                                            same_geometry, unpack_word)


@pytest.mark.parametrize("spec,lut", [(POW_SPEC, pow_lut), (CBRT_SPEC, cbrt_lut)])
def test_rom_shape_and_nodes(spec, lut):
    words = lut()
    assert len(words) == LUT_SIZE == 256
    assert all(0 <= w < (1 << 32) for w in words)            # 32-bit words
    for i in (0, 1, 17, 100, 255):
        v, q = unpack_word(words[i], spec)
        x = spec.x0 + i * 2.0 ** spec.step_log2
        assert v == math.floor(x ** spec.exponent * 2 ** spec.vfrac + 0.5)   # round half up
        assert q >= 0                                          # concave function
    # interpolation at a node (r = 0) returns the node value exactly
    for i in (0, 5, 200):
        code = spec.x0_code + (i << spec.tbits)
        assert lut_interpolate(code, spec) == unpack_word(words[i], spec)[0] << spec.tbits


def _max_rel_err(spec, xs):
    errs = []
    for x in xs:
        code = int(x * 2 ** spec.arg_frac)
        y = lut_interpolate(code, spec) / 2 ** spec.out_frac
        errs.append(abs(y / (code / 2 ** spec.arg_frac) ** spec.exponent - 1.0))
    return max(errs)


def test_pow_interpolation_error():
    # Measured: 1.9e-4 (cubic remainder of the midpoint-matched quadratic, alpha ~ 1.1),
    # 2.5e-6 beyond alpha = 5. Bounds add ~5 % margin for the sampling density.
    near = np.linspace(1.0, 2.0, 4001)
    far = np.linspace(5.0, 128.0, 20001)
    assert _max_rel_err(POW_SPEC, near) < 2.0e-4
    assert _max_rel_err(POW_SPEC, far) < 3.0e-6


def test_cbrt_interpolation_error():
    # Measured 1.8e-7 (node rounding 2^-23 plus interpolation); 2.5e-7 bound.
    xs = np.concatenate([np.linspace(1.0, 1.1, 3001), np.linspace(1.0, 8.0, 7001)[:-1]])
    assert _max_rel_err(CBRT_SPEC, xs) < 2.5e-7


def test_segment_range_checked():
    with pytest.raises(ValueError, match="segment"):
        lut_interpolate(POW_SPEC.x0_code + (255 << POW_SPEC.tbits), POW_SPEC)


# ---------------------------------------------------------------------------------
# exact-Hertz tables (hertz_form="exact"); truth: analytic.hertz.exact_ellipticity
# ---------------------------------------------------------------------------------
def _k_exact(x):
    return exact_ellipticity(x)[0]


def _n_exact(x):
    return 6.0 / math.pi * x * (exact_ellipticity(x)[1] - 1.0)


@pytest.mark.parametrize("spec,f", [(POW_EXACT_SPEC, _k_exact), (EE_EXACT_SPEC, _n_exact)])
def test_exact_tables_nodes_and_geometry(spec, f):
    words = rom_words(spec)
    assert len(words) == LUT_SIZE and all(0 <= w < (1 << 32) for w in words)
    assert same_geometry(spec, POW_SPEC)          # read by the POW interpolator
    for i in (0, 1, 17, 100, 255):
        v, q = unpack_word(words[i], spec)
        assert v == math.floor(f(1.0 + 0.5 * i) * 2 ** spec.vfrac + 0.5)
        assert q >= 0
    # alpha = 1 (circular): k = 1, E = pi/2, i.e. N = 3 - 6/pi = N5 (published = exact)
    assert unpack_word(words[0], spec)[0] == (1 << 17 if f is _k_exact
                                              else round((3 - 6 / math.pi) * 2 ** 17))


@pytest.mark.parametrize("spec,f,near_bound,far_bound", [
    # measured (4001 / 20001 points): POWX 1.74e-4 near alpha = 1 (cubic remainder as
    # for POW), 2.5e-6 beyond alpha = 5; EEX 2.08e-4 and 4.3e-6 (bounds ~15 % above)
    (POW_EXACT_SPEC, _k_exact, 2.0e-4, 3.0e-6),
    (EE_EXACT_SPEC, _n_exact, 2.4e-4, 5.0e-6)])
def test_exact_tables_interpolation_error(spec, f, near_bound, far_bound):
    def worst(xs):
        errs = []
        for x in xs:
            code = int(x * 2 ** spec.arg_frac)
            y = lut_interpolate(code, spec) / 2 ** spec.out_frac
            errs.append(abs(y / f(code / 2 ** spec.arg_frac) - 1.0))
        return max(errs)
    assert worst(np.linspace(1.0, 2.0, 801)) < near_bound
    assert worst(np.linspace(5.0, 128.0, 2001)) < far_bound


def test_rom_words_rejects_foreign_specs():
    with pytest.raises(ValueError, match="not a stage-D table"):
        rom_words(LutSpec("pow", 1.0, -1, 24, 22, 17, 10, 15, 0.5))
