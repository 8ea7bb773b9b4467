"""What the preview engines accept (:mod:`gearcontact.preview.engine`).

Truths: the reference and golden backends accept exactly one domain — the operating
envelope of :data:`~gearcontact.preview.hertz.reference.ENVELOPE` — so an input is
rejected by both or by neither (checked at the envelope's edges, where the golden
model's rounding used to let values in, and by a property test over arbitrary floats);
numpy scalars and 0-d arrays are the same number as the Python float (identical
results); a bool is not a load; a material may be given by preset name; a non-numeric
stencil is a named error.
"""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from gearcontact.materials import STEEL
from gearcontact.preview.engine import get_engine
from gearcontact.preview.hertz.reference import ENVELOPE
from gearcontact.validation import InputRangeError

ENGINES = {name: get_engine(name) for name in ("reference", "golden")}
C_LO, C_HI = ENVELOPE["curvature_per_mm"]
W_LO, W_HI = ENVELOPE["load_n"]


def _outcome(engine, a, b, w):
    try:
        return engine.hertz(a, b, w)
    except InputRangeError as exc:
        return exc


@pytest.mark.parametrize("a, b, w", [
    (math.nextafter(C_HI, math.inf), 0.01, 100.0),   # 16.0000001 rounded into the register
    (16.0000001, 0.01, 100.0),
    (0.0004882, 0.0004882, 1.0),                     # rounds onto 2^-11 in Q(32,20)
    (0.1, 0.01, math.nextafter(W_HI, math.inf)),
    (0.1, 0.01, 0.999),
    (1.0, 1.0 / 200.0, 100.0),                       # alpha = 200 > 128
])
def test_outside_the_envelope_rejected_by_every_backend(a, b, w):
    for engine in ENGINES.values():
        with pytest.raises(InputRangeError):
            engine.hertz(a, b, w)


@pytest.mark.parametrize("a, b, w", [(C_HI, C_HI / 128, W_HI), (C_LO, C_LO, W_LO),
                                     (0.0869, 0.00186, 1755.0)])
def test_envelope_edges_accepted_by_every_backend(a, b, w):
    for engine in ENGINES.values():
        res = engine.hertz(a, b, w)
        assert res.valid and res.p_max_mpa > 0


@settings(max_examples=300, deadline=None)
@given(st.floats(allow_nan=True, allow_infinity=True, width=64),
       st.floats(allow_nan=True, allow_infinity=True, width=64),
       st.floats(allow_nan=True, allow_infinity=True, width=64))
def test_one_domain_for_reference_and_golden(a, b, w):
    ref, gold = (_outcome(e, a, b, w) for e in ENGINES.values())
    assert isinstance(ref, InputRangeError) == isinstance(gold, InputRangeError)
    if not isinstance(ref, InputRangeError):
        # inside the domain: a finite answer, and the golden one carries no flag
        assert gold.valid and gold.flags == ()
        for res in (ref, gold):
            assert all(math.isfinite(v) and v > 0 for v in
                       (res.a_mm, res.b_mm, res.k, res.p_max_mpa))


@pytest.mark.parametrize("wrap", [np.float64, np.float32, np.array, lambda x: np.array(x)[()],
                                  np.int64])
def test_numpy_scalars_and_0d_arrays_are_numbers(wrap):
    for engine in ENGINES.values():
        ref = engine.hertz(0.0869, 0.00186, 1755)
        got = engine.hertz(wrap(0.0869) if wrap is not np.int64 else 0.0869,
                           wrap(0.00186) if wrap is not np.int64 else 0.00186, wrap(1755))
        tol = 1e-6 if wrap is np.float32 else 0.0   # float32 rounds the curvatures
        assert got.p_max_mpa == pytest.approx(ref.p_max_mpa, rel=tol)


@pytest.mark.parametrize("load", [True, np.bool_(True), np.array([1755.0, 1.0]), "1755"])
def test_bool_and_arrays_are_not_loads(load):
    for engine in ENGINES.values():
        with pytest.raises(InputRangeError) as err:
            engine.hertz(0.0869, 0.00186, load)
        assert "load_n" in str(err.value)


def test_material_by_name_and_bad_material():
    by_name = get_engine("golden", material="steel").hertz(0.0869, 0.00186, 1755.0)
    assert by_name == get_engine("golden", material=STEEL).hertz(0.0869, 0.00186, 1755.0)
    with pytest.raises(InputRangeError) as err:
        get_engine("golden", material="wood")
    assert "material" in str(err.value) and "steel" in str(err.value)


@pytest.mark.parametrize("gaps", ["abc", [[1, 2], [3]], object(), np.zeros(48)])
def test_stencil_not_numbers_is_a_named_error(gaps):
    for engine in ENGINES.values():
        with pytest.raises(InputRangeError) as err:
            engine.stencil(gaps, 100.0)
        assert "gaps" in str(err.value) or "stencil" in str(err.value)
