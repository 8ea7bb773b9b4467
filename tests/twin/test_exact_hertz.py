"""The twin's exact Hertz form (:mod:`gearcontact.twin.exact_hertz`, ``hertz_form="exact"``).

Truth: exact elliptic Hertz written with scipy's Carlson integrals and a Brent solve of
the eccentricity equation (:func:`gearcontact.analytic.hertz.exact_elliptic_hertz`, 4 eps)
at the same curvatures and load, at random points off the table's grid over curvature
ratios 1 .. 1.4e5 (axis ratios 1 .. ~1000) and loads 1 .. 1e5 N.

Tolerance: :data:`~gearcontact.twin.exact_hertz.REL_BOUND` = 1e-8 relative on a, b,
p_max, the approach and the stiffness, declared in the module before this test was run:
the 4-point Lagrange cubic at h = 0.02 errs by at most ``h^4 |f''''| 3/128`` in each log
(a few 1e-10 for these smooth functions of ln alpha), the cube root 5 ulp and the exp's
and products' roundings a few ulp; 1e-8 leaves a factor ~30 over the interpolation.
"""

import math

import numpy as np
import pytest

from gearcontact.analytic.hertz import exact_elliptic_hertz
from gearcontact.twin import kernel as K
from gearcontact.twin.exact_hertz import (RATIO_MAX, REL_BOUND, ROWS, STEP,
                                          exact_hertz_table, exact_hertz_terms)

E_PRIME = 226373.6      # steel on steel, MPa (E' = E/(1 - nu^2), E 206 GPa, nu 0.3)


def _points(n: int, seed: int):
    """``(A-, B-, W)``: A- log-uniform in 1e-4 .. 0.1 1/mm, ratio log-uniform in
    1 .. 1.4e5, W log-uniform in 1 .. 1e5 N; plus ratios on the table's first interval
    (one-sided stencil), at grid midpoints and at 1.4e5, all off the grid nodes."""
    rng = np.random.default_rng(seed)
    u = np.concatenate([rng.uniform(0.0, math.log(1.4e5), n),
                        rng.uniform(0.0, 2.0 * STEP, 8),
                        (np.arange(8) * 97 + 0.5) * STEP, [math.log(1.4e5)]])
    lo = 10.0 ** rng.uniform(-4.0, -1.0, u.size)
    w = 10.0 ** rng.uniform(0.0, 5.0, u.size)
    return lo, lo * np.exp(u), w


def _prm_exact() -> np.ndarray:
    prm = np.concatenate([np.zeros(K.N_PRM), exact_hertz_table()])
    prm[K.P_HFORM] = K.HERTZ_FORM_CODES["exact"]
    prm[K.P_EP] = E_PRIME
    return prm


def test_table_covers_the_declared_range():
    tab = exact_hertz_table()
    assert tab.size == ROWS * 3 and (ROWS - 1) * STEP >= math.log(RATIO_MAX)
    # row 0 is the circle: R_D(0,1,1) = 3 pi/4 (Carlson R_D(0,y,y) = 3 pi/(4 y^1.5)), so c_a = (3/4)^(1/3)
    # (a^3 = 3 W/(4 A E'), circular Hertz with 1/R = 4 A), b = a, K = pi/2; 1e-15: ulps
    assert tab[:3] == pytest.approx([math.log(0.75) / 3.0, 0.0, math.log(math.pi / 2)],
                                    abs=1e-15)


def test_compiled_terms_against_exact_hertz():
    """(a) the compiled interpolated law at random curvature pairs and loads."""
    prm = _prm_exact()
    err = []
    for lo, hi, w in zip(*_points(300, 7)):
        ex = exact_elliptic_hertz(lo, hi, w, e_prime_mpa=E_PRIME)
        a, b, p, d = exact_hertz_terms(lo, hi, w, E_PRIME, prm, K.N_PRM)
        err.append([a / ex.a_mm, b / ex.b_mm, p / ex.p_max_mpa, d / ex.approach_mm])
    err = np.abs(np.array(err) - 1.0)
    assert err.max() < REL_BOUND, err.max(axis=0)


def test_twin_law_kappa_and_stiffness():
    """(a) the twin's fp64 law as the kernel calls it (:func:`~gearcontact.twin.
    contact_law._kappa_reference`, A-, B- in either order): kappa W^(2/3) is the exact
    approach at W, the stiffness dW/d(delta) = 3 W^(1/3)/(2 kappa) the exact one
    (3 W/(2 delta), delta ~ W^(2/3)), and a, b, p_max at the unit load."""
    prm = _prm_exact()
    out = np.zeros(K.N_PREVIEW)
    err = []
    for lo, hi, w in zip(*_points(200, 11)):
        kap = K._kappa_reference(hi, lo, prm, out)
        ex = exact_elliptic_hertz(lo, hi, w, e_prime_mpa=E_PRIME)
        unit = exact_elliptic_hertz(lo, hi, 1.0, e_prime_mpa=E_PRIME)
        stiff = 1.5 * w ** (1.0 / 3.0) / kap
        err.append([kap * w ** (2.0 / 3.0) / ex.approach_mm,
                    stiff / (1.5 * w / ex.approach_mm), out[0] / unit.a_mm,
                    out[1] / unit.b_mm, out[2] / unit.p_max_mpa])
        assert out[K.PV_LOAD] == 1.0
    err = np.abs(np.array(err) - 1.0)
    assert err.max() < REL_BOUND, err.max(axis=0)


def test_beyond_the_table_has_no_contact_law():
    """A preview beyond RATIO_MAX is counted without a contact law (kernel's tcount[5]),
    never extrapolated."""
    from gearcontact.twin.contact_law import _fp64_law

    prm = _prm_exact()
    tcount = np.zeros(K.N_COUNT, np.int64)
    out = np.zeros(K.N_PREVIEW)
    assert _fp64_law(1e-6, 1e-6 * RATIO_MAX * 1.01, prm, tcount, out, False) == -1.0
    assert tcount[5] == 1
    assert _fp64_law(1e-6, 1e-6 * RATIO_MAX * 0.99, prm, tcount, out, False) > 0.0
    assert tcount[5] == 1


def test_exact_form_refusals(s0003_twin):
    """Bad input is refused before the run, naming the field and what is allowed."""
    from dataclasses import replace

    from gearcontact.twin.params import default_drivetrain
    from gearcontact.twin.simulate import build_model
    from gearcontact.validation import InputRangeError

    pair, _, _, mesh = s0003_twin
    dt = default_drivetrain(pair)
    with pytest.raises(InputRangeError, match="hertz_form.*reference backend"):
        build_model(mesh, dt, 64.5, backend="golden", hertz_form="exact")
    with pytest.raises(InputRangeError, match="hertz_form.*one of"):
        build_model(mesh, dt, 64.5, hertz_form="hertz")
    # a row beyond the table's ratios: A- shrunk so that B-/A- exceeds RATIO_MAX
    far = replace(mesh, A_minus_per_mm=np.where(mesh.valid, 1e-9, mesh.A_minus_per_mm),
                  B_minus_per_mm=np.where(mesh.valid, 0.5, mesh.B_minus_per_mm))
    with pytest.raises(InputRangeError, match="beyond 1e\\+08"):
        build_model(far, dt, 64.5, hertz_form="exact")
    model = build_model(mesh, dt, 64.5, hertz_form="exact")
    assert model.hertz_form == "exact"


def test_cli_refuses_exact_form_off_the_reference_backend(tmp_path, capsys):
    from gearcontact.cli import main

    out = tmp_path / "o"
    assert main(["twin", "--out", str(out), "--backend", "golden", "--hertz-form", "exact",
                 "--quiet"]) == 2
    err = capsys.readouterr().err
    assert "--hertz-form" in err and "--backend reference" in err
    assert not out.exists()


def test_edge_rows_keep_their_lcp_approach(s0003_coast_twin):
    """The exact form on a mesh with LCP-calibrated edge rows (s0003 coast, its tip-edge
    bearing; tests/twin/test_edge_law.py checks those rows' approach against a fresh
    LCP): an edge row's scale is the LCP's approach over Hamrock-Brewe's, so its kappa
    under the exact form is the default form's (the same LCP approach) within
    REL_BOUND; every other row's kappa changes by exact Hertz over Hamrock-Brewe at its
    curvatures (analytic.hertz, scipy's integrals), within REL_BOUND."""
    from gearcontact.analytic.hertz import exact_elliptic_hertz, hamrock_brewe_hertz
    from gearcontact.twin.model import _prm
    from gearcontact.twin.params import default_drivetrain
    from gearcontact.twin.simulate import build_model

    pair, _, _, mesh = s0003_coast_twin
    dt = default_drivetrain(pair)
    hb = build_model(mesh, dt, 64.5, curvatures="exact")
    ex = build_model(mesh, dt, 64.5, curvatures="exact", hertz_form="exact")
    p_hb, p_ex = _prm(hb, 0.0), _prm(ex, 0.0)
    out = np.zeros(K.N_PREVIEW)
    calibrated = (mesh.contact_mode != 0) & (mesh.edge_exponent != 0.0)
    n_edge = 0
    for i, k in zip(*np.nonzero(mesh.valid)):
        a, b = mesh.A_minus_per_mm[i, k], mesh.B_minus_per_mm[i, k]
        k_hb = K._kappa_reference(a, b, p_hb, out)
        k_ex = K._kappa_reference(ex.mesh.A_minus_per_mm[i, k], ex.mesh.B_minus_per_mm[i, k],
                                  p_ex, out)
        if calibrated[i, k]:
            want = 1.0
            n_edge += 1
        else:
            assert ex.mesh.A_minus_per_mm[i, k] == a and ex.mesh.B_minus_per_mm[i, k] == b
            want = (exact_elliptic_hertz(a, b, 1.0, e_prime_mpa=mesh.e_prime_mpa).approach_mm
                    / hamrock_brewe_hertz(a, b, 1.0, e_prime_mpa=mesh.e_prime_mpa).approach_mm)
        assert k_ex / k_hb == pytest.approx(want, rel=REL_BOUND), (i, k)
    assert n_edge >= 2


@pytest.mark.slow       # ~25 s (the pair's edge-contact TCA of both sides, 11 phases)
def test_cli_exact_form_on_the_f2_machine_pair(tmp_path, capsys):
    """``gearcontact twin --hertz-form exact`` on the ISO 23509 F.2 machine pair (whose
    rows reach curvature ratio ~640, beyond Hamrock-Brewe's range on 129 of 191 rows,
    docs/hertz.md sec. 7): the option reaches the law (twin.json names the form, the
    previews outside the datapath are evaluated by exact Hertz) and the law status is
    ok on every row, none without a contact law."""
    import json

    from gearcontact.cli import main

    from .conftest import F2_MACHINE

    out = tmp_path / "o"
    assert main(["twin", "--pair", str(F2_MACHINE), "--out", str(out), "--duration-ms", "2",
                 "--phases", "11", "--hertz-form", "exact", "--no-figures", "--quiet"]) == 0
    s = json.loads((out / "twin.json").read_text())
    assert s["hertz_form"] == "exact" and s["hertz_law_status"] == "ok"
    assert s["hertz_law_rows_beyond_range"] == 0 and s["hertz_law_ratio_max"] > 122.0
    assert s["outside_datapath_evaluated_by"].startswith("fp64 exact Hertz")
    assert s["previews_without_contact_law"] == 0
    assert "fp64 Hertz law: exact" in capsys.readouterr().out
