"""The vectorized line core (:mod:`gearcontact.preview.hertz.line_vec`) is bit-identical to
the scalar golden model :func:`~gearcontact.preview.hertz.line.line_golden`.

Truth: the scalar model, every output register, the mode, the scale and the flags, on
the corner cases and seeded random vectors of
:func:`gearcontact.preview.stimulus.line_stimulus` (every SCALE exponent, both modes,
about 25 % flagged). The scalar model costs about 1.5 ms per vector on a loaded 2-core
machine, so the default suite compares 2,000 vectors (plus 400 in the exact form); the
slow suite 20,000 in each form (measured identical: 20,000 + 17 corners, both forms).
"""

import numpy as np
import pytest

from gearcontact.preview.hertz import formats as F
from gearcontact.preview.hertz.line import FLAG_LENGTH_RANGE, line_golden
from gearcontact.preview.hertz.line_vec import line_golden_array
from gearcontact.preview.stimulus import line_stimulus

FIELDS = ("a_code", "b_code", "p_max_code", "k_code", "A_min_code", "B_max_code", "mode",
          "scale", "flags")


def _compare(n, seed, hertz_form="hamrock-brewe"):
    f = line_stimulus(n, seed=seed).fields
    vec = line_golden_array(f["A"], f["B"], f["W"], f["L"], e_prime_code=f["e_prime"],
                            hertz_form=hertz_form)
    got = np.stack([getattr(vec, k) for k in FIELDS])
    want = np.array([[getattr(line_golden(int(a), int(b), int(w), int(length),
                                          e_prime_code=int(e), hertz_form=hertz_form), k)
                      for k in FIELDS]
                     for a, b, w, length, e in zip(f["A"], f["B"], f["W"], f["L"],
                                                   f["e_prime"])], dtype=np.int64).T
    assert np.array_equal(got, want)
    return vec


def test_bit_identical_random_and_corners():
    vec = _compare(2_000, seed=31)
    names = vec.mode_names
    # every path is exercised: both modes, every SCALE exponent, the envelope flags
    assert (names == "elliptic").sum() > 300 and (names == "line").sum() > 500
    assert set(vec.scale[vec.valid].tolist()) == {0, 1, 2, 3}
    assert (vec.flags & FLAG_LENGTH_RANGE).any() and (vec.flags & F.FLAG_LOAD_RANGE).any()


def test_exact_form_bit_identical():
    vec = _compare(400, seed=32, hertz_form="exact")
    assert (vec.mode_names == "elliptic").sum() > 50


def test_shapes_and_broadcast():
    A = np.full((3, 4), 1 << 14)
    v = line_golden_array(A, 1 << 16, 1 << 18, 20 << 20, e_prime_code=229_670)
    assert v.a_code.shape == (3, 4) and v.valid.all()
    s = line_golden(1 << 14, 1 << 16, 1 << 18, 20 << 20, e_prime_code=229_670)
    assert (int(v.p_max_code[2, 3]), int(v.mode[0, 0])) == (s.p_max_code, s.mode)


@pytest.mark.slow
@pytest.mark.parametrize("hertz_form", ["hamrock-brewe", "exact"])
def test_bit_identical_long_sweep(hertz_form):
    """20,000 seeded vectors per form (about 30 s of scalar model each)."""
    _compare(20_000, seed=5, hertz_form=hertz_form)


def test_lifted_batch_is_the_scalar_host_path():
    """``lifted_line_golden_array`` (numba: lift_lengths, the batch core, unlift_line_array)
    against the scalar host path, ``length_lift`` + ``line_golden`` on ``(W << s, L << s)``
    + ``unlift_line_codes``, on 600 short lines (every lift 1..8 reached, and the lift's
    corners) and the line stimulus's 200 + corners (lift 0 mostly): every register, the
    mode, the flags and the lift."""
    from gearcontact.preview.hertz.line import length_lift, unlift_line_codes
    from gearcontact.preview.hertz.line_vec import lifted_line_golden_array
    from gearcontact.preview.stimulus_lift import short_line_stimulus

    for st in (short_line_stimulus(600, 3), line_stimulus(200, seed=5)):
        f = st.fields
        vec, lift = lifted_line_golden_array(f["A"], f["B"], f["W"], f["L"],
                                             e_prime_code=f["e_prime"])
        for i in range(len(st)):
            a, b, w, length, e = (int(f[k][i]) for k in ("A", "B", "W", "L", "e_prime"))
            s = int(length_lift(w, length))
            want = unlift_line_codes(line_golden(a, b, w << s, length << s, e_prime_code=e), s)
            assert lift[i] == s and [int(getattr(vec, k)[i]) for k in FIELDS] == \
                [getattr(want, k) for k in FIELDS], (i, st.labels[i])
    assert set(lift.tolist()) >= {0}
