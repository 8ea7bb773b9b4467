"""The cylindrical twin's law with tooth bending is the coupled slice law
(ltca.coupled_slice_law: w = K (d - h - G f), G the line's bending Gram matrix from the
loaded TE's own shells; docs/cylindrical.md sec. 10) against independent truths:

* the preview's coupled law (ltca.coupled_slice_law.coupled_line, the law at a load,
  which ``analyze``'s cylindrical preview runs) at the twin's own static pair load: the
  twin solves the same fixed point at its approach (coupled_solve at an approach), so
  its contact approach, loaded length and interference are the preview's within the
  Newton's stop (bound 1e-8 relative: both stop at max |R| <= 1e-10 max |G f| in the
  effective ease-off, ~1e-13 mm on a 1e-3 mm deflection; through the loaded length's
  slope (slice width over the ease-off's step across a slice, ~1e4) at most ~1e-9 of
  L_c; two orders above, the cases' rounding);
* the loaded TE with bending (ltca.cylindrical_lte: the half-space LCP with the same
  shells, an independent solver): its loaded TE p-p and the tip edge's share of F_n
  beyond the lines (slow).

The tolerances of the LCP comparison were declared before the coupled twin's numbers
were measured (session 20): the quasi-static test's 0.35 arcsec on the p-p
(tests/twin/test_cylindrical_edges.py, not widened), and the edge share's mean over the
phases within 1.0 percentage point of F_n of the LCP's (the twin in series was 1.3-3.6
points below it, 3.33-4.86 % against 5.29-7.00 % at 13 phases; the coupled law on the
twin's mesh-table inputs at the LCP's loads, offline, 5.3-6.5 % against 5.3-6.1 % at 7
phases), with the coupled share nearer the LCP's than the uncoupled law's at every
phase.
"""

import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from gearcontact.geometry.pair import load_pair
from gearcontact.ltca.coupled_slice_law import coupled_line
from gearcontact.preview.fit.reference import fitted_coefficients, principal_curvatures
from gearcontact.tca.cylindrical_cycle import cylindrical_mesh_cycle
from gearcontact.twin import cylindrical as twin_cyl
from gearcontact.twin import kernel as K
from gearcontact.twin import statics
from gearcontact.twin.model import _prm
from gearcontact.twin.params import default_drivetrain
from gearcontact.twin.simulate import build_model

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def _law_inputs(mesh, j, k):
    """The line's ease-off with the edge slices, its Gram matrix, B_max (the fp64 stage
    C of the row's stencil), the edge slices' count and width (the twin's inputs)."""
    coeff = fitted_coefficients(mesh.stencil_gaps_mm[j, k])
    b_max = max(principal_curvatures(*map(float, coeff))[:2])
    if mesh.beyond_gap_mm is None:
        return mesh.line_gap_mm[j, k], mesh.line_bending_gram_mm_per_n[j, k], b_max, 0, 0.0
    h = np.concatenate([mesh.line_gap_mm[j, k], mesh.beyond_gap_mm[j, k].ravel()])
    return (h, mesh.line_bending_gram_mm_per_n[j, k], b_max, mesh.beyond_gap_mm.shape[-1],
            mesh.beyond_width_mm * mesh.beyond_stiffness)


def _static_previews(model, k, torque_nm):
    """Static rotation at row ``k`` (bisection on the law's torque, as
    statics.static_rotation) and the previews the law took there (the kernel's cache)."""
    m = model.mesh
    prm = _prm(model, 0.0)
    n_p = model.arrays["lever"].shape[1]
    lo, hi = 0.0, 1e-3
    w_eval = np.full(n_p, 1e3)
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        t, w = statics._elastic(model, prm, mid, m.psi_rad[k], w_eval=w_eval)
        w_eval = np.where(w > 0, w, w_eval)
        lo, hi = (mid, hi) if t < torque_nm else (lo, mid)
        if hi - lo <= 1e-15 * hi:
            break
    cache = np.full((2, n_p, K.N_CACHE), -1.0)
    _, w = statics._elastic(model, prm, hi, m.psi_rad[k], w_eval=w_eval, cache=cache)
    return hi, w, cache[0]


def _check_law_is_the_preview(model, k, torque_nm):
    """At row ``k``'s static state: per loaded line pair, the twin's preview (its load
    W_e, the law's a = L_c / 2, offset h_bar = d_c - I / L_c and secant compliance c_b =
    (d - d_c) / W_e) against coupled_line at W_e on the same inputs."""
    m = model.mesh
    theta, w, cache = _static_previews(model, k, torque_nm)
    checked = 0
    for j in np.flatnonzero(w > 0.0):
        if m.contact_mode[j, k] != 0:
            continue
        h, g, b_max, nb, wb = _law_inputs(m, j, k)
        we = cache[j, 5]
        line = coupled_line(h, float(m.line_length_mm[j, k]), we, b_max, m.e_prime_mpa, g,
                            edge_slices=nb, edge_width_mm=wb)
        assert line.steps > 0
        d = m.lever_mm[j, k] * theta - m.opening_mm[j, k]
        assert cache[j, 7] == K.MODE_LINE
        assert 2.0 * cache[j, 2] == pytest.approx(line.loaded_length_mm, rel=1e-8)
        d_c = d - cache[j, 10] * we
        assert d_c == pytest.approx(line.approach_mm, rel=1e-8)
        h_bar = line.approach_mm - line.interference_mm2 / line.loaded_length_mm
        assert cache[j, 9] == pytest.approx(h_bar, abs=1e-8 * line.approach_mm)
        checked += 1
    return checked


def test_spur_law_is_the_preview_coupled_law():
    """The unmodified spur 20/40 with bending, 200 N·m, its pitch-point row (one pair
    on the whole line: the coupled law loads its ends more) and the first row (two
    pairs): module docstring, bound 1e-8."""
    from gearcontact.ltca.cylindrical_bending import cylindrical_bending

    pair = load_pair(EXAMPLES / "spur_20x40_m3.toml", kinds=("cylindrical",))
    cycle = cylindrical_mesh_cycle(pair, phases=3)
    mesh = twin_cyl.cylindrical_mesh_table(
        pair, cycle, bending=cylindrical_bending(pair, facing=cycle.facing))
    model = build_model(mesh, default_drivetrain(pair), 200.0, backend="reference",
                        curvatures="line")
    assert sum(_check_law_is_the_preview(model, k, 200.0) for k in (0, 1)) >= 3


@pytest.fixture(scope="module")
def unrelieved():
    ev = load_pair(EXAMPLES / "ev_reducer_helical_23x67.toml", kinds=("cylindrical",))
    return replace(ev, modifications_pinion=replace(ev.modifications_pinion, tip_relief_um=0.0),
                   modifications_gear=replace(ev.modifications_gear, tip_relief_um=0.0))


@pytest.mark.slow
def test_static_twin_with_bending_against_the_loaded_te(unrelieved):
    """EV example without tip relief, 400 N·m, 13 phases, bending: the static twin (the
    coupled law at every row but the last) against the loaded TE with bending (LCP, 80
    rows along the face): loaded TE p-p within 0.35 arcsec; the edge slices' share of
    F_n (the coupled law at each line pair's static load, which is the twin's law
    there: test_spur_law_is_the_preview_coupled_law, checked here too at the first
    row) against the LCP's edge rows beyond the lines: mean over the rows within 1.0
    point, and at every row nearer than the uncoupled law's at the same load (module
    docstring: declared before measuring)."""
    from gearcontact.ltca import cylindrical_lte as lte_module

    torque, phases = 400.0, 13
    cyc = cylindrical_mesh_cycle(unrelieved, phases=phases)
    model = twin_cyl.cylindrical_model(unrelieved, torque_nm=torque, phases=phases,
                                       bending=True)
    m = model.mesh
    assert _check_law_is_the_preview(model, 0, torque) >= 1
    lte = lte_module.cylindrical_loaded_te(unrelieved, torque, cycle=cyc, cells_along=80,
                                           bending=True)
    order = twin_cyl._order(m.motion_sign, len(m.psi_rad))
    arcsec = 3600 * 180 / math.pi
    n = m.line_gap_mm.shape[-1]
    te, share, share0, want = [], [], [], []
    for k in range(len(m.psi_rad) - 1):
        theta, w, _ = _static_previews(model, k, torque)
        te.append(m.te0_arcsec[k] - m.motion_sign * theta * arcsec)
        s = {False: 0.0, True: 0.0}
        for j in np.flatnonzero(w > 0.0):
            if m.contact_mode[j, k] != 0:
                continue
            h, g, b_max, nb, wb = _law_inputs(m, j, k)
            for bent in (False, True):
                line = coupled_line(h, float(m.line_length_mm[j, k]), float(w[j]), b_max,
                                    m.e_prime_mpa, g if bent else None, edge_slices=nb,
                                    edge_width_mm=wb)
                s[bent] += line.slice_load_n[n:].sum() / lte.normal_load_n
        share.append(s[True])
        share0.append(s[False])
        want.append(lte.beyond_load_share[:, order[k]].sum())
    share, share0, want = map(np.array, (share, share0, want))
    pp_twin, pp_lcp = float(np.ptp(te)), float(np.ptp(lte.lte_arcsec[order][:-1]))
    assert abs(pp_twin - pp_lcp) < 0.35, (pp_twin, pp_lcp)
    assert abs(share.mean() - want.mean()) < 0.010, (share, want)
    assert np.all(np.abs(share - want) < np.abs(share0 - want)), (share, share0, want)
