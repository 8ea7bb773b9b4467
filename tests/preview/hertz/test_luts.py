"""POW / CBRT ROM contents and interpolation accuracy (truth: x**(2/pi), x**(1/3))."""

import math

import numpy as np
import pytest

from gearcontact.preview.hertz.luts import (CBRT_SPEC, LUT_SIZE, POW_SPEC, cbrt_lut,
                                            lut_interpolate, pow_lut, unpack_word)


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
