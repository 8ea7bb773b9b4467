"""The coupled slice law (gearcontact.ltca.coupled_slice_law): the slice law on the
ease-off plus the teeth's bending deflection of the slice loads, w = K (d - h - G f).
Truths: the uncoupled law itself where bending cannot change the distribution (G = 0,
and G = c 1 1^T: bending in series, every slice shifted alike), the linear algebra of
the fully loaded line (where the law is linear: an independent solve), conservation of
the line's load, and the loaded TE's LCP with the shells (tests/ltca/
test_cylindrical_preview.py)."""

import math

import numpy as np
import pytest

from gearcontact.ltca.coupled_slice_law import coupled_line
from gearcontact.ltca.slice_law import equivalent_length, loaded_length_mm
from gearcontact.validation import InputRangeError

E_PRIME, B_ACROSS = 229_670.0, 0.05
N, LENGTH = 16, 20.0
Y = (np.arange(N) + 0.5) / N * LENGTH - 0.5 * LENGTH


def _kernel(scale_mm_per_n=2e-5, decay_mm=5.0):
    """A smooth symmetric positive definite compliance along the line (mm/N): the
    shells' shape (largest on the diagonal, decaying over a few mm along the face)."""
    return scale_mm_per_n * np.exp(-np.abs(Y[:, None] - Y[None, :]) / decay_mm)


@pytest.mark.parametrize("crown_mm", [0.0, 2e-3, 2e-2])
def test_without_bending_spread_it_is_the_slice_law_bit_for_bit(crown_mm):
    """G = 0 (None or zeros) and G = c 1 1^T (the twin's bending in series: every slice
    deflects by c W) leave the distribution the uncoupled slice law's: (d_c, L_c, I)
    bit for bit (the law only sees the ease-off's differences)."""
    h = crown_mm * (Y / (0.5 * LENGTH)) ** 2
    ref = loaded_length_mm(h, LENGTH, 400.0, B_ACROSS, E_PRIME)
    for g in (None, np.zeros((N, N)), np.full((N, N), 3e-5)):
        c = coupled_line(h, LENGTH, 400.0, B_ACROSS, E_PRIME, g)
        assert (c.approach_mm, c.loaded_length_mm, c.interference_mm2) == ref
        assert c.steps == 0


def test_fully_loaded_line_is_the_linear_solve():
    """A line loaded over its whole length (a 0.2 um crowning at 600 N): the law is then
    linear, its slice forces f = k dy (d 1 - M x) with M the slices' averaging (1/4,
    1/2, 1/4 inside; 3/4, 1/4 at the ends: the ease-off linear between the centres,
    constant over the end half-slices) and the modulus k = 1 / (lambda' g(L)),
    lambda' = 4 / (pi E'), g = ln(4 L / b) - 3/4 (the finite line, Johnson 1985 sec.
    4.3), fixed while L_c = L. With x = h + G f, (1 + k dy M G) f = k dy (d 1 - M h),
    sum f = W: two linear solves, independent of the Newton iteration. Tolerance 1e-8
    relative: the iteration stops at 1e-10 of max |G f| in x (the slice law's approach
    to 1e-14), amplified into f by the
    foundation's k dy (~1e5 N/mm) over W: at most 1e-8."""
    w = 600.0
    h = 2e-4 * (Y / (0.5 * LENGTH)) ** 2
    g = _kernel()
    c = coupled_line(h, LENGTH, w, B_ACROSS, E_PRIME, g)
    assert c.loaded_length_mm == pytest.approx(LENGTH, rel=1e-15) and c.steps > 0
    dy = LENGTH / N
    b = math.sqrt(4.0 * w / (math.pi * LENGTH * E_PRIME * B_ACROSS))
    k = 1.0 / (4.0 / (math.pi * E_PRIME) * (math.log(4.0 * LENGTH / b) - 0.75))
    m = np.diag(np.full(N, 0.5)) + np.diag(np.full(N - 1, 0.25), 1) \
        + np.diag(np.full(N - 1, 0.25), -1)
    m[0, 0] = m[-1, -1] = 0.75
    a = np.eye(N) + k * dy * m @ g
    f1 = np.linalg.solve(a, k * dy * np.ones(N))       # per unit d
    f0 = np.linalg.solve(a, -k * dy * m @ h)
    d = (w - f0.sum()) / f1.sum()
    f = f0 + d * f1
    np.testing.assert_allclose(c.slice_load_n, f, rtol=1e-8)
    assert c.slice_load_n.sum() == pytest.approx(w, rel=1e-12)


@pytest.mark.parametrize("crown_mm, load_n", [(2e-3, 300.0), (2e-2, 900.0), (5e-2, 50.0)])
def test_partly_loaded_line_conserves_and_spreads(crown_mm, load_n):
    """A crowned line loaded over part of its length: the slice forces sum to W (1e-12:
    the shares sum to I, rounding), are >= 0, the effective ease-off is h + G f up to
    a constant (1e-9 of max |G f|: the stop at 1e-10, then the solve's rounding), and
    bending lengthens the loaded length and lowers the peak line load (the neighbours'
    deflection closes the gap beside the peak: G positive definite, decaying)."""
    h = crown_mm * (Y / (0.5 * LENGTH)) ** 2
    g = _kernel()
    c = coupled_line(h, LENGTH, load_n, B_ACROSS, E_PRIME, g)
    assert c.slice_load_n.sum() == pytest.approx(load_n, rel=1e-12)
    assert (c.slice_load_n >= 0.0).all()
    gf = g @ c.slice_load_n
    r = c.effective_ease_mm - h - gf
    assert np.ptp(r) <= 1e-9 * np.abs(gf).max()
    d_u, l_u, a_u = loaded_length_mm(h, LENGTH, load_n, B_ACROSS, E_PRIME)
    assert l_u < LENGTH and c.loaded_length_mm > l_u
    assert load_n / equivalent_length(c.approach_mm, c.interference_mm2, LENGTH) < \
        load_n / equivalent_length(d_u, a_u, LENGTH)


def test_bad_compliance_refused():
    h = np.zeros(N)
    for g in (np.zeros((N, N - 1)), np.triu(_kernel()), np.full((N, N), np.nan)):
        with pytest.raises(InputRangeError, match="compliance_mm_per_n"):
            coupled_line(h, LENGTH, 100.0, B_ACROSS, E_PRIME, g)


def test_edge_slices_beyond_the_line():
    """The tip edge beyond either end (``edge_slices`` runs of ``edge_width_mm``, as the
    twin's law takes them, ltca.slice_law.interference): G = 0 is ltca.slice_law.
    loaded_line with the same edge slices bit for bit; with G the forces of the line's
    and the edge's slices sum to W (1e-12) and x = h + G f holds on all of them (1e-9 of
    max |G f|, as above)."""
    from gearcontact.ltca.slice_law import loaded_line

    nb, wb, w = 4, 0.4, 500.0
    edge = 1e-3 + 2e-3 * np.arange(1, nb + 1) ** 2 / nb ** 2    # opening outwards, mm
    h = np.concatenate([2e-3 * (Y / (0.5 * LENGTH)) ** 2, edge, edge])
    pv = np.zeros(2 * h.size)
    pv[:h.size] = h
    ref = loaded_line(pv, 0, N, LENGTH, w, B_ACROSS, E_PRIME, nb, wb)
    c0 = coupled_line(h, LENGTH, w, B_ACROSS, E_PRIME, None, edge_slices=nb,
                      edge_width_mm=wb)
    assert (c0.approach_mm, c0.loaded_length_mm, c0.interference_mm2) == ref
    y_edge = 0.5 * LENGTH + wb * (np.arange(nb) + 0.5)
    y_all = np.concatenate([Y, -y_edge, y_edge])
    g = 2e-5 * np.exp(-np.abs(y_all[:, None] - y_all[None, :]) / 5.0)
    c = coupled_line(h, LENGTH, w, B_ACROSS, E_PRIME, g, edge_slices=nb, edge_width_mm=wb)
    assert c.slice_load_n.sum() == pytest.approx(w, rel=1e-12)
    gf = g @ c.slice_load_n
    assert np.ptp(c.effective_ease_mm - h - gf) <= 1e-9 * np.abs(gf).max()
    with pytest.raises(InputRangeError, match="edge_slices"):
        coupled_line(h, LENGTH, w, B_ACROSS, E_PRIME, None, edge_slices=h.size)


@pytest.mark.slow
def test_edge_share_against_the_loaded_te_with_bending():
    """The twin's open question (docs/cylindrical.md sec. 10): with bending in series its
    edge slices carry 3.3-4.9 % of F_n against the loaded TE's 5.3-7.0 %. The coupled
    law on the twin's own mesh-table inputs (line and edge slices, their foundation, the
    shells' Gram at both, twin.cylindrical.cylindrical_mesh_table) at the loaded TE's
    pair loads (line plus its edge rows) against the loaded TE with bending at 80 rows
    (ltca.cylindrical_lte, the half-space LCP with the shells: independent), EV example
    without tip relief at 400 N·m, 7 phases (~40 s): the edge's share of F_n lies nearer
    the loaded TE's than the uncoupled law's at every phase (an ordering, no band;
    measured 5.3-6.5 % against the loaded TE's 5.3-6.1 % and the uncoupled 3.3-4.5 %)."""
    from dataclasses import replace
    from pathlib import Path

    from gearcontact.geometry.pair import load_pair
    from gearcontact.ltca.cylindrical_bending import cylindrical_bending
    from gearcontact.ltca.cylindrical_lte import cylindrical_loaded_te
    from gearcontact.preview.fit.reference import fitted_coefficients, principal_curvatures
    from gearcontact.tca.cylindrical_cycle import cylindrical_mesh_cycle
    from gearcontact.tca.cylindrical_stencil import cylindrical_stencils
    from gearcontact.twin.cylindrical import cylindrical_mesh_table

    ev = load_pair(Path(__file__).resolve().parents[2] / "examples"
                   / "ev_reducer_helical_23x67.toml", kinds=("cylindrical",))
    p = replace(ev, modifications_pinion=replace(ev.modifications_pinion, tip_relief_um=0.0),
                modifications_gear=replace(ev.modifications_gear, tip_relief_um=0.0))
    cyc = cylindrical_mesh_cycle(p, phases=7)
    lte = cylindrical_loaded_te(p, 400.0, cycle=cyc, cells_along=80, bending=True)
    st = cylindrical_stencils(p, cyc)
    mesh = cylindrical_mesh_table(p, cyc, st, bending=cylindrical_bending(p, facing=cyc.facing),
                                  torque_nm=400.0)
    coeff = fitted_coefficients(mesh.stencil_gaps_mm)
    nb = mesh.beyond_gap_mm.shape[-1]
    wb = mesh.beyond_width_mm * mesh.beyond_stiffness
    n = mesh.line_gap_mm.shape[-1]
    f_n = lte.normal_load_n
    for k in range(len(cyc.phi1_rad)):
        kk = int(np.flatnonzero(mesh.phi1_rad == cyc.phi1_rad[k])[0])
        share = {False: 0.0, True: 0.0}
        for j in range(lte.load_share.shape[0]):
            if not st.valid[j, k] or mesh.contact_mode[j, kk] != 0:
                continue
            w = (lte.load_share[j, k] + lte.beyond_load_share[j, k].sum()) * f_n
            if w <= 1e-3 * f_n:
                continue
            h = np.concatenate([mesh.line_gap_mm[j, kk], mesh.beyond_gap_mm[j, kk].ravel()])
            b_max = max(principal_curvatures(*map(float, coeff[j, kk]))[:2])
            for bent in (False, True):
                line = coupled_line(h, mesh.line_length_mm[j, kk], w, b_max, mesh.e_prime_mpa,
                                    mesh.line_bending_gram_mm_per_n[j, kk] if bent else None,
                                    edge_slices=nb, edge_width_mm=wb)
                share[bent] += line.slice_load_n[n:].sum() / f_n
        want = lte.beyond_load_share[:, k].sum()
        assert want > 0.0
        assert abs(share[True] - want) < abs(share[False] - want)


@pytest.mark.parametrize("at_approach", [False, True])
def test_exact_jacobian_against_central_differences(at_approach):
    """The Newton's Jacobian (slice_law.interference_derivatives and the law's equation
    differentiated implicitly, coupled_slice_law._evaluate) against central differences
    of the slice forces f(x) (step 1e-9 mm), at a load (d_c implicit) and at an approach
    (W implicit), on a crowned line (20 um) with edge slices, partly loaded (kinks of L_c away
    from the step). Bound 1e-7 of max |df/dx|: the slice law's solve to 1e-14 of d_c
    and the forces' rounding (~1e-14 of 30 N) over the 2e-9 mm difference give ~1e-8
    (measured 1.6e-8 at a load, 1.6e-9 at an approach; L_c 9.6 of 20 mm)."""
    from gearcontact.ltca import coupled_slice_law as core

    nb, wb = 4, 0.4
    edge = 1e-3 + 2e-3 * np.arange(1, nb + 1) ** 2 / nb ** 2
    h = np.concatenate([2e-2 * (Y / (0.5 * LENGTH)) ** 2, edge, edge])
    y_edge = 0.5 * LENGTH + wb * (np.arange(nb) + 0.5)
    y_all = np.concatenate([Y, -y_edge, y_edge])
    g = 2e-5 * np.exp(-np.abs(y_all[:, None] - y_all[None, :]) / 5.0)
    m = h.size
    ox, of = core._at(0, m, core._X), core._at(0, m, core._F)

    def forces(x, value, at):
        buf = np.zeros(core.core_scratch(m))
        buf[:m], buf[m:m + m * m], buf[ox:ox + m] = h, g.ravel(), x
        res = core._evaluate(buf, 0, m, N, LENGTH, B_ACROSS, E_PRIME, nb, wb, value, at,
                             300.0)
        return buf[of:of + m].copy(), buf, res

    x = h + g @ np.r_[np.full(N, 500.0 / N), np.zeros(2 * nb)] \
        + 1e-5 * np.random.default_rng(1).standard_normal(m)
    value = 500.0
    if at_approach:     # the approach at which x carries 500 N
        value = forces(x - x.min(), 500.0, False)[2][0] + x.min()
    _, buf, res = forces(x, value, at_approach)
    assert 0.0 < res[1] < LENGTH - 2.0 and res[3] == pytest.approx(500.0, rel=1e-9)
    od = core._at(0, m, core._DER)
    sd, sub, diag, sup = (buf[od + k * m:od + (k + 1) * m] for k in range(4))
    v = buf[core._at(0, m, core._V):][:m]
    u = buf[core._at(0, m, core._U):][:m]
    s = buf[ox + m:ox + 2 * m]
    jac = res[6] * (np.diag(diag) + np.diag(sup[:-1], 1) + np.diag(sub[1:], -1)) \
        + res[7] * np.outer(sd, v) + np.outer(s, u)
    fd = np.zeros((m, m))
    for j in range(m):
        step = np.zeros(m)
        step[j] = 1e-9
        fd[:, j] = (forces(x + step, value, at_approach)[0]
                    - forces(x - step, value, at_approach)[0]) / 2e-9
    assert np.abs(jac - fd).max() < 1e-7 * np.abs(jac).max()


def _edge_problem():
    """A crowned line (20 um) with 4 edge slices beyond either end and a smooth kernel
    over all of them (test_exact_jacobian_against_central_differences's problem)."""
    nb, wb = 4, 0.4
    edge = 1e-3 + 2e-3 * np.arange(1, nb + 1) ** 2 / nb ** 2
    h = np.concatenate([2e-2 * (Y / (0.5 * LENGTH)) ** 2, edge, edge])
    y_edge = 0.5 * LENGTH + wb * (np.arange(nb) + 0.5)
    y_all = np.concatenate([Y, -y_edge, y_edge])
    return h, 2e-5 * np.exp(-np.abs(y_all[:, None] - y_all[None, :]) / 5.0), nb, wb


def _solve_at_approach(h, g, nb, wb, d, x0, w_start, max_steps=None):
    """coupled_solve at the approach d (mm) from x0: (d_c, L_c, I, W, steps), x, f.
    ``max_steps`` None is the default cap, passed as an argument as coupled_line
    passes it: one compiled specialization for both (docs/performance.md, "Session
    26")."""
    from gearcontact.ltca import coupled_slice_law as core

    m = h.size
    buf = np.zeros(core.core_scratch(m))
    ox = core.start_offset(0, m)
    buf[:m], buf[m:m + m * m], buf[ox:ox + m] = h, g.ravel(), x0
    args = (buf, 0, m, m - 2 * nb, LENGTH, B_ACROSS, E_PRIME, nb, wb, d, True, w_start)
    res = core.coupled_solve(*args, core.MAX_STEPS if max_steps is None else max_steps)
    of = core._at(0, m, core._F)
    return res, buf[ox:ox + m].copy(), buf[of:of + m].copy()


@pytest.mark.parametrize("load_n", [150.0, 500.0, 3000.0])
def test_chord_iteration_solves_the_fixed_point_at_an_approach(load_n):
    """At an approach coupled_solve follows a Newton step from a small residual with
    chord steps on its factors (docs/twin.md, "Speed of the bent cylindrical twin").
    Truths:
    the fixed point's residual R = x - h - G f recomputed here in numpy (f from the
    returned forces) within the stated tolerance (TOL_REL max |G f| + TOL_ABS), the
    forces summing to the returned W, and the same line solved at that load
    (coupled_line: Newton alone, from h) giving the same effective ease-off and forces.
    Started from a twin-like warm start (the solution at a 2 % lower load: the load moves
    ~1 % a step) and from the series state's cold one (x = h + G f with the uncoupled
    slice law's forces). Bound on the two solutions: 1e-8 of max |G f| on x, 1e-8 of W
    on f (each is solved to 1e-10 of max |G f| in its own datum, and the load's own
    Newton to 1e-14: 1e-8 leaves the conditioning of the line's ends a factor 100)."""
    from gearcontact.ltca import coupled_slice_law as core

    h, g, nb, wb = _edge_problem()
    ref = coupled_line(h, LENGTH, load_n, B_ACROSS, E_PRIME, g, edge_slices=nb,
                       edge_width_mm=wb)
    x_ref = ref.effective_ease_mm
    d = ref.approach_mm + (h + g @ ref.slice_load_n).min()     # x absolute: h + G f
    near = coupled_line(h, LENGTH, 0.98 * load_n, B_ACROSS, E_PRIME, g, edge_slices=nb,
                        edge_width_mm=wb)
    cold = coupled_line(h, LENGTH, load_n, B_ACROSS, E_PRIME, None, edge_slices=nb,
                        edge_width_mm=wb)
    for x0 in (h + g @ near.slice_load_n, h + g @ cold.slice_load_n):
        (d_c, l_c, area, w, steps), x, f = _solve_at_approach(h, g, nb, wb, d, x0, load_n)
        assert steps >= 1
        gf = g @ f
        r = x - h - gf
        assert np.abs(r).max() <= core.TOL_REL * np.abs(gf).max() + core.TOL_ABS
        assert f.sum() == pytest.approx(w, rel=1e-12)
        assert w == pytest.approx(load_n, rel=1e-8)
        assert np.abs((x - x.min()) - x_ref).max() <= 1e-8 * np.abs(gf).max()
        assert np.abs(f - ref.slice_load_n).max() <= 1e-8 * load_n


def test_iteration_cap_reports_no_convergence():
    """The solve's failure path (steps -1), reached through the iteration cap that only
    tests lower (the FMU's render-time cap: tests/export/test_fmu_cylindrical.py): with
    no step allowed the cold start is not converged; with the default cap the same call
    converges."""
    h, g, nb, wb = _edge_problem()
    cold = coupled_line(h, LENGTH, 500.0, B_ACROSS, E_PRIME, None, edge_slices=nb,
                        edge_width_mm=wb)
    x0 = h + g @ cold.slice_load_n
    d = 0.05
    assert _solve_at_approach(h, g, nb, wb, d, x0, 500.0, max_steps=0)[0][4] == -1
    assert _solve_at_approach(h, g, nb, wb, d, x0, 500.0)[0][4] >= 1
