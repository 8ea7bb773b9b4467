"""The previews inside the compiled loop are the preview engine's previews.

Truth: :class:`gearcontact.preview.engine.ReferenceEngine` (fp64) and
:class:`~gearcontact.preview.engine.GoldenEngine` (bit-exact codes, its own input
quantization) on the same curvatures and loads; the approach coefficient against the
exact relation delta = 3 W F/(pi a E') of Hamrock–Brewe (the reference's own approach).
With stage C per step (curvatures="stencil"): the package's C -> D chain,
:func:`gearcontact.preview.chain.chain_reference` (fp64, 1e-12) and
:func:`~gearcontact.preview.chain.chain_golden` (bit for bit, every code and the chain
flags word) on the stencil the loop interpolates between two rows.
"""

import math

import numpy as np
import pytest

from gearcontact.analytic.hertz import hamrock_brewe_hertz
from gearcontact.materials import STEEL, effective_modulus_mpa
from gearcontact.preview.engine import get_engine
from gearcontact.preview.chain import FIT_FLAG_SHIFT, chain_golden, chain_reference
from gearcontact.preview.fit.golden import element_constants, encode_gaps
from gearcontact.preview.fit.pinv import N_COEFFS, N_TAPS, baked_pinv
from gearcontact.contract.stencil import stencil_coordinates
from gearcontact.preview.hertz.golden import encode_e_prime
from gearcontact.preview.hertz.golden_vec import golden_constants
from gearcontact.twin import kernel as K
from gearcontact.twin.contact_law import _kappa_golden

E_PRIME = effective_modulus_mpa(STEEL)
rng = np.random.default_rng(7)
#: s0003's range of half curvatures (A- ~0.087, B- ~0.0016-0.0021 1/mm) and beyond
POINTS = [(0.0869, 0.00186, 1755.0), (0.088, 0.0016, 12.3), (0.05, 0.03, 40000.0)] + [
    (float(a), float(b), float(w)) for a, b, w in zip(rng.uniform(0.002, 1.0, 20),
                                                      rng.uniform(0.002, 1.0, 20),
                                                      rng.uniform(1.0, 50000.0, 20))
    if max(a, b) / min(a, b) < 120]


def _prm(source="exact"):
    prm = np.zeros(K.N_PRM)
    prm[K.P_EP] = E_PRIME
    prm[K.P_ECODE] = encode_e_prime(E_PRIME)
    prm[K.P_STAGEC] = K.CURVATURE_SOURCES[source]
    return prm


def _fit(trace_rows=1):
    w, cst = element_constants()
    return (w, cst, np.zeros((1, N_TAPS), np.int64), np.zeros((1, N_COEFFS), np.int64),
            np.zeros((trace_rows, N_TAPS), np.int64))


def _kappa(cv, f, W, backend, source, trace, fit):
    """The loop's preview of pair 0 between rows 0 and 1 of ``cv`` (2, C) at fraction f."""
    out = np.zeros(K.N_PREVIEW)
    tcount = np.zeros(K.N_COUNT, np.int64)
    kap = K._kappa(0, 0, 0, f, W, _prm(source), np.asarray(cv, float)[None, None],
                   backend, *golden_constants(), trace, tcount, fit, out)
    return kap, out


@pytest.mark.parametrize("A, B, W", POINTS)
def test_reference_preview_is_the_engine(A, B, W):
    """The fp64 law's preview at the unit load it reports (the engine's, 2e-15 relative),
    and its kappa and a, b, p_max against Hamrock-Brewe at W: ``kappa W^(2/3)`` is the
    approach, ``a, b, p_max ~ W^(1/3)`` (Hertz similarity); 1e-13 relative, a few
    roundings of the power and the cube root beside the closed form's own. Not bit for
    bit at 1 N: the compiled law's cube root is the exported C's
    (:func:`gearcontact.analytic.cube_root.cbrt_positive`, within 5 ulp of the root),
    the engine's libm's (within 1): a and kappa ~ 1/a within 6 ulp (6.7e-16), b = a/k
    half an ulp more, p_max ~ 1/(a b) twice that, 2e-15 covers all four."""
    out = np.zeros(K.N_PREVIEW)
    kap = K._kappa_reference(A, B, _prm(), out)
    assert out[K.PV_LOAD] == 1.0
    res = get_engine("reference").hertz(A, B, 1.0)
    assert (out[0], out[1], out[2]) == pytest.approx((res.a_mm, res.b_mm, res.p_max_mpa),
                                                     rel=2e-15, abs=0.0)
    assert kap == pytest.approx(hamrock_brewe_hertz(A, B, 1.0, e_prime_mpa=E_PRIME)
                                .approach_mm, rel=2e-15, abs=0.0)
    hb = hamrock_brewe_hertz(A, B, W, e_prime_mpa=E_PRIME)
    assert kap * W ** (2.0 / 3.0) == pytest.approx(hb.approach_mm, rel=1e-13)
    scale = W ** (1.0 / 3.0)
    assert (out[0] * scale, out[1] * scale, out[2] * scale) == pytest.approx(
        (hb.a_mm, hb.b_mm, hb.p_max_mpa), rel=1e-13)


@pytest.mark.parametrize("A, B, W", POINTS)
def test_golden_preview_is_the_engine_bit_for_bit(A, B, W):
    trace = np.zeros((1, 9), np.int64)
    kap, out = _kappa([[A, B], [A, B]], 0.0, W, 1, "exact", trace, _fit(0))
    res = get_engine("golden").hertz(A, B, W)
    c = res.codes
    # the same input quantization and the same output codes
    assert (trace[0, 1], trace[0, 2], trace[0, 3]) == (min(c["A_in"], c["B_in"]),
                                                       max(c["A_in"], c["B_in"]), c["W"])
    assert tuple(trace[0, 4:9]) == (c["flags"], c["a"], c["b"], c["p_max"], c["k"])
    assert (out[0], out[1], out[2]) == (res.a_mm, res.b_mm, res.p_max_mpa)
    # kappa from the golden a and k: within the golden error of the fp64 one (a 3.6e-4,
    # k 6.8e-4 end to end; F(k) is log-flat: 1.5e-3 covers both)
    ref = K._kappa_reference(A, B, _prm(), np.zeros(K.N_PREVIEW))
    assert kap == pytest.approx(ref, rel=1.5e-3)
    assert math.isfinite(kap)


def test_golden_kappa_within_11_ulp_of_the_formula():
    """The golden law's kappa, ``3 F W^(1/3) / (pi a E')`` on stage D's a and k codes at
    the quantized load (:func:`gearcontact.twin.contact_law.hertz_kappa`: the library's
    cube root, not ``pow(W, 2/3)``), against the same formula in mpmath at 100 bits on
    the same doubles (exact pi): within 11 ulp (2^-52 relative each; the docstring's
    count: cube root 5, ln k 1, F 2, products and division 3); measured 2.7. 2,000
    operands of the datapath's domain: curvature codes log-uniform over its range,
    loads over the twin's evaluation envelope (1 .. 2^17 N), E' codes over theirs."""
    mpmath = pytest.importorskip("mpmath")
    pow_lut, cbrt_lut, cst = golden_constants()
    r = np.random.default_rng(17)
    mp = mpmath.mp.clone()
    mp.prec = 100
    worst, n = 0.0, 0
    while n < 2000:
        a, b = np.sort(np.exp(r.uniform(math.log(cst[0]), math.log(cst[1]), 2))).astype(int)
        w = float(np.exp(r.uniform(0.0, math.log(2.0 ** 17))))
        prm = _prm()
        prm[K.P_ECODE] = int(r.integers(cst[4], cst[5] + 1))
        trace, out = np.zeros((1, 9), np.int64), np.zeros(K.N_PREVIEW)
        kap = _kappa_golden(int(a), int(b), 0, w, prm, pow_lut, cbrt_lut, cst, trace,
                              np.zeros(K.N_COUNT, np.int64), _fit(0), out)
        if kap <= 0.0:          # flagged (beyond alpha_max)
            continue
        a_mm, k, w_q = mp.mpf(out[0]), mp.mpf(int(trace[0, 8])) / 2 ** 20, mp.mpf(int(trace[0, 3])) / 256
        f = mp.pi / 2 + (mp.pi / 2 - 1) * (mp.pi / 2) * mp.log(k)
        exact = 3 * f * mp.cbrt(w_q) / (mp.pi * a_mm * prm[K.P_ECODE])
        worst = max(worst, float(abs(kap / exact - 1)) / 2.0 ** -52)
        n += 1
    assert worst <= 11, worst


def _stencils(A, B):
    """Two rows of stencils (mm): quadrics with principal half curvatures near (A, B),
    turned, with a tilt and cubic terms (stage C fits them with a bias, as on real
    flanks), the second row a little different from the first."""
    s, t = stencil_coordinates()
    rows = []
    for turn, cubic in ((0.3, 0.002), (0.45, -0.003)):
        c, d = math.cos(turn), math.sin(turn)
        u, v = c * s + d * t, -d * s + c * t
        rows.append(A * u * u + B * v * v + 1e-3 * s + cubic * u ** 3 + 0.01 * s * t * t)
    return np.array(rows)


STENCIL_POINTS = [(a, b, w) for a, b, w in POINTS if max(a, b) / min(a, b) < 60][:12]


@pytest.mark.parametrize("f", [0.0, 0.37])
@pytest.mark.parametrize("A, B, W", STENCIL_POINTS)
def test_stencil_reference_preview_is_the_chain(A, B, W, f):
    g = _stencils(A, B)
    # fp64: the rows' fitted coefficients, interpolated (stage C is linear)
    cv = g @ baked_pinv().weights[3:6].T
    kap, out = _kappa(cv, f, W, 0, "stencil", np.zeros((0, 9), np.int64), _fit(0))
    ref = chain_reference(g[0] + f * (g[1] - g[0]), W, e_prime_mpa=E_PRIME)
    hz = ref.hertz
    # the fp64 law's a, b, p_max hold at 1 N (Hertz similarity: ~ W^(1/3) beyond)
    assert out[K.PV_LOAD] == 1.0
    np.testing.assert_allclose(out[:3] * W ** (1.0 / 3.0), [hz.a_mm, hz.b_mm, hz.p_max_mpa],
                               rtol=1e-12)
    hb = hamrock_brewe_hertz(ref.fit.A_minus_per_mm, ref.fit.B_minus_per_mm, W,
                             e_prime_mpa=E_PRIME)
    assert kap * W ** (2.0 / 3.0) == pytest.approx(hb.approach_mm, rel=1e-12)


@pytest.mark.parametrize("f", [0.0, 0.37])
@pytest.mark.parametrize("A, B, W", STENCIL_POINTS)
def test_stencil_golden_preview_is_the_chain_bit_for_bit(A, B, W, f):
    g = _stencils(A, B)
    trace = np.zeros((1, 9), np.int64)
    fit = _fit(1)
    kap, out = _kappa(g, f, W, 1, "stencil", trace, fit)
    codes = encode_gaps(g[0] + f * (g[1] - g[0]))
    assert np.array_equal(fit[4][0], codes)            # the traced stencil
    w_code = int(trace[0, 3])
    assert w_code == math.floor(W * 256.0 + 0.5)
    ch = chain_golden(codes, w_code, e_prime_code=encode_e_prime(E_PRIME))
    assert (trace[0, 1], trace[0, 2]) == (ch.fit.b_minus_code, ch.fit.a_minus_code)
    hz = ch.hertz
    assert tuple(trace[0, 4:9]) == (ch.flags, hz.a_code, hz.b_code, hz.p_max_code,
                                    hz.k_code)
    assert ch.flags >> FIT_FLAG_SHIFT == 0 and ch.flags == 0
    ref, _ = _kappa(g @ baked_pinv().weights[3:6].T, f, W, 0, "stencil",
                    np.zeros((0, 9), np.int64), _fit(0))
    assert kap == pytest.approx(ref, rel=2e-3)         # the golden error of the chain


def test_stencil_not_elliptic_is_flagged_not_loaded():
    # a saddle: stage C's B- < 0; fp64 gives no law (-1), golden the chain's flags
    s, t = stencil_coordinates()
    g = np.array([0.05 * s * s - 0.01 * t * t] * 2)
    kap, _ = _kappa(g @ baked_pinv().weights[3:6].T, 0.0, 100.0, 0, "stencil",
                    np.zeros((0, 9), np.int64), _fit(0))
    assert kap == -1.0
    trace = np.zeros((1, 9), np.int64)
    kap, _ = _kappa(g, 0.0, 100.0, 1, "stencil", trace, _fit(1))
    assert kap == -1.0 and trace[0, 4] != 0
    ch = chain_golden(encode_gaps(g[0]), 25600, e_prime_code=encode_e_prime(E_PRIME))
    assert trace[0, 4] == ch.flags and "fit_not_elliptic" in ch.flag_names


def test_one_preview_per_loaded_pair_and_step(s0003_twin):
    """The kernel previews a loaded pair once per step and holds it into the next row
    interval (docs/twin.md, "One preview per pair and step"): 600 golden steps of 10 us
    at 6000 rpm on s0003 (31 phases: a row interval every ~5 steps, so ~120 steps
    whose later stages enter the next interval), the golden trace's previews per step
    against the pairs loaded at the step's start (the record). Truth by counting: a
    step forms exactly its loaded pairs' previews, more only where a pair first closes
    in a later stage (the loaded pairs grow by the next step's start) or the pitch wraps
    (the pairs relabelled: previewed again), never fewer. The rule before (a preview
    again in the next interval) added every loaded pair's at each such step."""
    from gearcontact.twin.params import default_drivetrain
    from gearcontact.twin.simulate import (_fit_args, _prm, build_model,
                                           speed_controller_gains, static_rotation)

    pair, _, _, mesh = s0003_twin
    m = build_model(mesh, default_drivetrain(pair), 64.5, backend="golden")
    a, dt = m.arrays, m.drivetrain
    prm = _prm(m, 0.0)
    omega = 6000.0 * 2.0 * math.pi / 60.0
    prm[K.P_OMEGA] = omega
    prm[K.P_KP], prm[K.P_KI] = speed_controller_gains(m)
    theta0, w0 = static_rotation(m)
    y = np.zeros(K.N_STATE)
    y[0] = m.torque_nm / mesh.ratio / dt.input_stiffness_nm_per_rad
    y[2] = mesh.eps_rad[0] - theta0
    y[3] = y[2] - m.torque_nm / dt.output_stiffness_nm_per_rad
    y[4:8] = omega, omega, omega / mesh.ratio, omega / mesh.ratio
    n, n_p = 600, a["lever"].shape[1]
    w_eval = np.full((2, n_p), K.W_EVAL_MIN_N)
    w_eval[0] = np.where(w0 > 0, w0, K.W_EVAL_MIN_N)
    trace = np.zeros((n * (n_p + 2), K.N_TRACE), np.int64)
    tcount = np.zeros(K.N_COUNT, np.int64)
    rec = np.zeros((n, K.N_REC))
    K.run_steps(y, 0.0, n, 1e-5, prm, a["eps"], a["lever"], a["opening"], a["cv"],
                a["valid"], a["cb"], 1, w_eval, a["pow_lut"], a["cbrt_lut"], a["cst"], trace,
                tcount, _fit_args(a, 0), a["tab_theta"], a["tab_t23"], a["tab_w23"], rec, 0, 1)
    assert tcount[5] == 0       # every preview has a law: each loaded pair one preview
    previews = np.bincount(trace[:tcount[0], 0], minlength=n)
    pairs = rec[:, K.R_NPAIRS].astype(int)
    x = np.mod(rec[:, K.R_PSI], prm[K.P_PITCH]) / prm[K.P_DPSI]
    row = np.minimum(x.astype(int), int(prm[K.P_NROW]) - 2)
    inside = np.diff(row) == 1          # a later stage of the step in the next interval
    wrap = np.diff(row) < 0
    grows = np.diff(pairs) > 0
    extra = (previews - pairs)[:-1]
    assert inside.sum() > 100 and wrap.sum() >= 3
    assert np.all(extra >= 0)
    assert np.all(extra[~(wrap | grows)] == 0)
    assert np.all(extra[inside & ~grows] == 0)
