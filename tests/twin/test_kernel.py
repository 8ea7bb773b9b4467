"""The previews inside the compiled loop are the preview engine's previews.

Truth: :class:`gearcontact.preview.engine.ReferenceEngine` (fp64) and
:class:`~gearcontact.preview.engine.GoldenEngine` (bit-exact codes, its own input
quantization) on the same curvatures and loads; the approach coefficient against the
exact relation delta = 3 W F/(pi a E') of Hamrock–Brewe (the reference's own approach).
"""

import math

import numpy as np
import pytest

from gearcontact.analytic.hertz import hamrock_brewe_hertz
from gearcontact.materials import STEEL, effective_modulus_mpa
from gearcontact.preview.engine import get_engine
from gearcontact.preview.hertz.golden import encode_e_prime
from gearcontact.preview.hertz.golden_vec import golden_constants
from gearcontact.twin import kernel as K

E_PRIME = effective_modulus_mpa(STEEL)
rng = np.random.default_rng(7)
#: s0003's range of half curvatures (A- ~0.087, B- ~0.0016-0.0021 1/mm) and beyond
POINTS = [(0.0869, 0.00186, 1755.0), (0.088, 0.0016, 12.3), (0.05, 0.03, 40000.0)] + [
    (float(a), float(b), float(w)) for a, b, w in zip(rng.uniform(0.002, 1.0, 20),
                                                      rng.uniform(0.002, 1.0, 20),
                                                      rng.uniform(1.0, 50000.0, 20))
    if max(a, b) / min(a, b) < 120]


def _prm():
    prm = np.zeros(K.N_PRM)
    prm[K.P_EP] = E_PRIME
    prm[K.P_ECODE] = encode_e_prime(E_PRIME)
    return prm


@pytest.mark.parametrize("A, B, W", POINTS)
def test_reference_preview_is_the_engine(A, B, W):
    out = np.zeros(3)
    kap = K._kappa_reference(A, B, W, _prm(), out)
    res = get_engine("reference").hertz(A, B, W)
    assert (out[0], out[1], out[2]) == (res.a_mm, res.b_mm, res.p_max_mpa)
    # kappa W^(2/3) is the Hamrock–Brewe approach (its own closed form)
    hb = hamrock_brewe_hertz(A, B, W, e_prime_mpa=E_PRIME)
    assert kap * W ** (2.0 / 3.0) == pytest.approx(hb.approach_mm, rel=1e-13)


@pytest.mark.parametrize("A, B, W", POINTS)
def test_golden_preview_is_the_engine_bit_for_bit(A, B, W):
    out = np.zeros(3)
    trace = np.zeros((1, 9), np.int64)
    tcount = np.zeros(4, np.int64)
    kap = K._kappa_golden(A, B, W, _prm(), *golden_constants(), trace, tcount, out)
    res = get_engine("golden").hertz(A, B, W)
    c = res.codes
    # the same input quantization and the same output codes
    assert (trace[0, 1], trace[0, 2], trace[0, 3]) == (min(c["A_in"], c["B_in"]),
                                                       max(c["A_in"], c["B_in"]), c["W"])
    assert tuple(trace[0, 4:9]) == (c["flags"], c["a"], c["b"], c["p_max"], c["k"])
    assert (out[0], out[1], out[2]) == (res.a_mm, res.b_mm, res.p_max_mpa)
    # kappa from the golden a and k: within the golden error of the fp64 one (a 3.6e-4,
    # k 6.8e-4 end to end; F(k) is log-flat: 1.5e-3 covers both)
    ref = K._kappa_reference(A, B, W, _prm(), np.zeros(3))
    assert kap == pytest.approx(ref, rel=1.5e-3)
    assert math.isfinite(kap)
