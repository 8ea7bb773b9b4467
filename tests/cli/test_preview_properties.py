"""Property test over the preview command line (hypothesis).

Truth (issue 12): whatever the user types — any float (NaN, inf, negative, huge, tiny)
as curvature, load, modulus or Poisson ratio, any gap stencil, either fp64 or fixed-point
backend — ``gearcontact preview`` answers with a result (exit 0: finite, positive a, b,
k, p_max), a named error (exit 2: one stderr line ``error: <field> = ...``) or a datapath
flag (exit 3: each flag on stderr), never a traceback, an internal error or a NaN.
"""

import contextlib
import io
import json
import math
import tempfile
from pathlib import Path

from hypothesis import example, given, settings
from hypothesis import strategies as st

from gearcontact.cli import main
from gearcontact.contract.stencil import stencil_coordinates, write_stencil_csv

numbers = st.one_of(st.floats(allow_nan=True, allow_infinity=True, width=64),
                    st.floats(1e-5, 1e6), st.sampled_from([0.0, -0.0, 1.0, 1755.0]))
backends = st.sampled_from(["reference", "golden"])


def _run(argv):
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        try:
            code = main(argv)
        except SystemExit as exc:          # argparse: unparsable text
            code = exc.code
    return code, out.getvalue(), err.getvalue()


def _check(code, out, err):
    assert "Traceback" not in err and "internal error" not in err, err
    assert code in (0, 2, 3), (code, err)
    if code == 0:
        d = json.loads(out)
        for key in ("a_mm", "b_mm", "k", "p_max_mpa"):
            assert math.isfinite(d[key]) and d[key] > 0, d
        assert d["flags"] == []
    elif code == 2:
        assert "error:" in err and "nan" not in err.split("error:")[0]
    else:
        d = json.loads(out)
        assert d["flags"] and err == (f"gearcontact preview: datapath flag: "
                                      f"{', '.join(d['flags'])} (outputs invalid)\n")


@settings(max_examples=150, deadline=None)
@given(a=numbers, b=numbers, w=numbers, backend=backends,
       material=st.one_of(st.just(None), st.tuples(numbers, numbers)))
# found by this test: a 2147 GPa modulus overflowed the golden E' register (exit 1)
@example(a=0.1, b=0.01, w=100.0, backend="golden", material=(2147484.0, 0.0))
def test_curvature_inputs(a, b, w, backend, material):
    argv = ["preview", "--curvatures", repr(a), repr(b), "--load", repr(w),
            "--backend", backend, "--json"]
    if material is not None:
        argv += ["--modulus", repr(material[0]), "--poisson", repr(material[1])]
    _check(*_run(argv))


@settings(max_examples=40, deadline=None)
@given(coef=st.tuples(st.floats(-1.0, 1.0), st.floats(-1.0, 1.0), st.floats(-0.2, 0.2),
                      st.floats(-0.01, 0.01)),
       noise=st.lists(st.floats(-1e-3, 1e-3), min_size=49, max_size=49),
       w=numbers, backend=backends)
def test_stencil_inputs(coef, noise, w, backend):
    """Quadrics of every sign (ellipses, saddles, planes, tilted) plus noise."""
    s, t = stencil_coordinates()
    a, b, c, d = coef
    gaps = a * s ** 2 + b * t ** 2 + c * s * t + d * s + noise
    with tempfile.TemporaryDirectory() as tmp:
        path = write_stencil_csv(Path(tmp) / "st.csv", gaps)
        _check(*_run(["preview", "--stencil", str(path), "--load", repr(w),
                      "--backend", backend, "--json"]))
