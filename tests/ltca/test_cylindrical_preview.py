"""The preview (C -> line core) on the contact of cylindrical pairs
(ltca.cylindrical_preview) against independent truths:

* Johnson 1985 eq. 4.45, the Hertz line contact p0 = sqrt(W E* / (pi R L)) of the spur
  pair at its pitch point (R = r1 r2 / (r1 + r2), r_i = r_bi tan a_wt, L = b, W = F_n:
  single contact there), unmodified and with a 2 um lead crowning (a full-face line);
* the LCP of ltca.cylindrical_lte (rigid, same torque and cycle): at mid-face the LCP's
  peak is the Hertz line contact of its own local line load (the half-space of a finite
  line carries more at the face ends, the preview's uniform line the mean);
* golden == RTL (ChainLineCore in the Amaranth simulator) bit for bit on the stencils of
  the spur and EV helical pairs, 811 cycles each.
"""

import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from gearcontact.geometry.cylindrical.pair import ToothModifications
from gearcontact.geometry.pair import load_pair
from gearcontact.halfspace.lcp import resolve_e_star
from gearcontact.ltca.cylindrical_lte import cylindrical_loaded_te
from gearcontact.ltca.cylindrical_preview import cylindrical_preview
from gearcontact.preview.fit.golden import encode_gaps
from gearcontact.preview.fit.pinv import coefficient_error_bound
from gearcontact.tca.cylindrical_cycle import cylindrical_mesh_cycle
from gearcontact.validation import InputRangeError

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
LSB_P = 2.0 ** -8          # PMAX Q(32,8), MPa
TORQUE_NM = 200.0


def _spur(crowning_um):
    p = load_pair(EXAMPLES / "spur_20x40_m3.toml", kinds=("cylindrical",))
    return replace(p, modifications_pinion=ToothModifications(lead_crowning_um=crowning_um))


def _johnson_p0(pair, load_n, length_mm=None):
    """Johnson 1985 eq. 4.45 at the pitch point on ``length_mm`` (default the face)."""
    g = pair.geometry
    length_mm = g.face_width_mm if length_mm is None else length_mm
    a = math.radians(g.working_pressure_angle_deg)
    r1 = 0.5 * g.base_diameter_pinion_mm * math.tan(a)
    r2 = 0.5 * g.base_diameter_gear_mm * math.tan(a)
    e_star = resolve_e_star((pair.pinion_material, pair.gear_material))
    return math.sqrt(load_n * e_star / (math.pi * (r1 * r2 / (r1 + r2)) * length_mm))


@pytest.fixture(scope="module", params=[0.0, 2.0], ids=["unmodified", "crowned_2um"])
def spur_pitch(request):
    """Spur pair, three phases (pitch point in the middle), its LTE and preview. The LTE
    has rigid teeth: the preview is the half-space Hertz law, and its truth the
    half-space LCP (tooth bending moves load along the line and with it the end effect
    the last test states)."""
    p = _spur(request.param)
    cyc = cylindrical_mesh_cycle(p, phases=3)
    lte = cylindrical_loaded_te(p, TORQUE_NM, cycle=cyc, bending=False)
    pv = cylindrical_preview(p, TORQUE_NM, cycle=cyc, loaded_te=lte)
    return request.param, p, cyc, lte, pv, cyc.pair_offsets.index(0)


def test_pitch_point_p0_is_johnson_eq_4_45(spur_pitch):
    """Johnson eq. 4.45 on the line chain's L: unmodified the slice law's line is flat
    (L_eq = L_c = L = b, 1e-9: the ease-off's rounding), so p0 is the full face's;
    crowned (2 um), the chain runs on the equivalent length of the slice law's peak line
    load, L_eq = W / w_peak < L, and p0 is Johnson's on L_eq (the crowning's peak, not
    the mean: the next test's truth is the LCP)."""
    crowning, p, cyc, lte, pv, j = spur_pitch
    k = 1
    assert pv.loaded[:, k].sum() == 1 and pv.load_n[j, k] == pytest.approx(pv.normal_load_n,
                                                                           rel=1e-12)
    fl = pv.face_load
    l_eq = float(fl.equivalent_length_mm[j, k])
    if crowning == 0.0:
        assert l_eq == pytest.approx(p.geometry.face_width_mm, rel=1e-9)
    else:
        assert 0.8 * p.geometry.face_width_mm < l_eq < 0.95 * p.geometry.face_width_mm
    assert not fl.end_loaded[j, k]
    truth = _johnson_p0(p, pv.normal_load_n, l_eq)
    ref = pv.results["reference"][j][k]
    gold = pv.results["golden"][j][k]
    assert ref.mode == gold.mode == "line" and gold.flags == ()
    # fp64: unmodified, the window leaves the face and is the osculating quadric: exact
    # to the rounding (1e-9); crowned, the true gap on the flank: stage C's bias on A-
    # (4e-7, tests/tca/test_cylindrical_stencil.py; the former quadratic fit's +0.6 %)
    # at half weight in p0 ~ sqrt(A-): measured 2.0e-7
    tol = 1e-9 if crowning == 0.0 else 1e-5
    assert ref.p_max_mpa == pytest.approx(truth, rel=tol)
    assert fl.hertz_pressure_mpa[j, k] == pytest.approx(ref.p_max_mpa, rel=1e-12)
    # golden against the fp64 chain: the fit's rigorous coefficient bound at half weight
    # plus one output LSB (as tests/preview/test_chain_line.py)
    c = coefficient_error_bound(pv.stencils.gaps_mm[j, k])
    bound = 0.5 * (c[3] + c[5] + c[4] / 2) / ref.A_minus_per_mm * ref.p_max_mpa + LSB_P
    assert abs(gold.p_max_mpa - ref.p_max_mpa) <= bound
    # the line's half-width b = 2 W / (pi L_eq p0) (Johnson eq. 4.44 with 4.45)
    assert ref.b_mm == pytest.approx(2 * pv.normal_load_n / (
        math.pi * l_eq * ref.p_max_mpa), rel=1e-12)


def test_pitch_point_p0_against_the_lcp(spur_pitch):
    """The LCP's peak across the line at mid-face (where the crowned line's gap is least
    and its slice-law line load peaks) against the preview scaled from its line load
    ``w_peak`` (the slice law's peak, W / L_eq) to the LCP's local line load there,
    p0 sqrt(w_mid / w_peak): within 1 % (the strip's 24 cells over +-2 Hertz half-widths
    sample the peak at b/12 from the centre, -0.35 %, plus the constant-pressure cells'
    discretization). The unscaled ratio is the end effect of the finite line (stated,
    not a tolerance: unmodified -4.2 %, crowned -1.5 % (w_peak 198 N/mm, 1.12 x the
    mean, against the LCP's 194 mid-face): the half-space loads the sharp face ends,
    the slice law's foundation does not; against the uniform line over L the crowned
    line's LCP was +4.1 %)."""
    crowning, p, cyc, lte, pv, j = spur_pitch
    k, mid = 1, lte.z_mm.size // 2
    assert lte.converged and not lte.edge_touch
    assert lte.load_share[j, k] == pytest.approx(1.0, abs=1e-12)
    p_lcp = lte.line_pressure_mpa[j, k, mid - 1: mid + 1].max()
    w_mid = lte.line_load_n_per_mm[j, k, mid - 1: mid + 1].mean()
    w_peak = float(pv.face_load.peak_line_load_n_per_mm[j, k])
    p_ref = pv.results["reference"][j][k].p_max_mpa
    assert p_lcp == pytest.approx(p_ref * math.sqrt(w_mid / w_peak), rel=1e-2)
    ratio = p_lcp / p_ref
    assert (0.94 < ratio < 0.97) if crowning == 0.0 else (0.97 < ratio < 1.0)


@pytest.mark.parametrize("incl_um", [100.0, 300.0])
def test_end_loaded_line_of_a_misaligned_spur(incl_um):
    """The uncrowned spur with its gear axis inclined by f_Sigma_delta over the face (the
    user's try of issue 26): at the pitch point (single contact, W = F_n) the line is
    end-loaded. Truth: analytic.face_load.end_loaded_line on the gap slope that the tilt
    projects onto the plane of action, s = f_Sigma_delta sin(alpha_wt) / b (ISO 6336-1's
    component of the inclination) and the line's exact A-. The preview's slice law
    (16 slices of w = L / 16) differs from it by its discretisation and by the gap's
    own slope at the closed end:

    * the end half-slice is held at s w / 2 (module ltca.slice_law): the interference
      lacks s w^2 / 8, and with F(L) = s L^2 / 2 - lambda' W g(L) convex (g = 1.5 ln L
      + const), 0 <= L_c - L_c0 <= w^2 / (8 L_c0 (1 - 3 / (4 g0)));
    * the TCA's gap opens a little slower at the closed end than its mean slope (the
      tilt's second-order term: measured -0.55 / -1.6 % at 100 / 300 um, bound 2 %),
      L_c ~ s^(-1/2): +1 % more;
    * the peak line load, w_peak = s L_c / (lambda' g(L_c)) on the slice law against
      2 W / L_c0 = s L_c0 / (lambda' g0) on the closed form, within [-1 %, +1 % +
      the length's bound relative] (the slope's half weight; the length's ratio
      over g's).

    Measured: L_c 5.822 / 3.033 mm against 5.770 / 2.931 (bounds 0.097 / 0.107 mm),
    peak 397.2 / 783.9 against 396.5 / 780.6 N/mm."""
    from gearcontact.analytic.face_load import end_loaded_line
    from gearcontact.analytic.hertz import line_contact_terms
    from gearcontact.geometry.cylindrical.pair import MeshAlignment

    p = replace(_spur(0.0), assembly=MeshAlignment(axis_inclination_um=incl_um))
    cyc = cylindrical_mesh_cycle(p, phases=3)
    pv = cylindrical_preview(p, 64.5, cycle=cyc, backends=("reference",))
    k = 1
    j = int(np.argmax(pv.load_n[:, k]))
    assert pv.load_n[j, k] == pytest.approx(pv.normal_load_n, rel=1e-12)
    g = p.geometry
    e_prime = 2.0 * resolve_e_star((p.pinion_material, p.gear_material))
    length = float(pv.stencils.line_length_mm[j, k])
    b_max = float(pv.stencils.A_minus_per_mm[j, k])
    truth = end_loaded_line(
        load_n=pv.normal_load_n, slope=incl_um * 1e-3 * math.sin(math.radians(
            g.working_pressure_angle_deg)) / g.face_width_mm,
        length_mm=length, b_max_per_mm=b_max, e_prime_mpa=e_prime)
    fl = pv.face_load
    assert fl.end_loaded[j, k] and truth.end_loaded
    l_c0, w = truth.loaded_length_mm, length / 16
    _, b = line_contact_terms(b_max, pv.normal_load_n, l_c0, e_prime)
    g0 = math.log(4.0 * l_c0 / b) - 0.75
    bound = w * w / (8.0 * l_c0 * (1.0 - 0.75 / g0)) + 0.01 * l_c0
    assert 0.0 <= fl.loaded_length_mm[j, k] - l_c0 <= bound
    assert 0.99 <= fl.peak_line_load_n_per_mm[j, k] / truth.peak_line_load_n_per_mm \
        <= 1.01 + bound / l_c0
    assert fl.face_load_factor[j, k] == pytest.approx(
        fl.peak_line_load_n_per_mm[j, k] * length / pv.load_n[j, k], rel=1e-12)
    # the chain's p_max is the Hertz pressure of the peak line load
    assert pv.results["reference"][j][k].p_max_mpa == pytest.approx(
        fl.hertz_pressure_mpa[j, k], rel=1e-12)


@pytest.mark.parametrize("incl_um", [100.0, 300.0])
def test_crowned_misaligned_spur_against_the_lcp(incl_um):
    """Spur 20/40, 30 um lead crowning, gear axis inclined by 100 / 300 um, 64.5 N·m,
    the pitch point (single contact): the preview's slice law on the line's real gap
    (crowning + tilt) against the rigid LCP (128 rows; the same load).

    * 100 um: the crowning centres the load (the least gap 2.9 mm off mid-face): not
      end-loaded in either. Loaded length LCP / law 0.907 (0.917 at 256 rows), peak
      line load LCP / law 1.087 -- the LCP carries the same load over a length shorter
      by the half-space's spread beside the load (its surface lifts beyond the loaded
      end: last session's 0.83-0.89 on uncrowned wedges), so its peak is the law's
      times L_law / L_LCP (1.10 here, within 1.5 %); p_max LCP / preview 1.042, its
      square root. Bounds: length 0.85-0.95, line load 1.0-1.15 and to 3 % of the
      length ratio's inverse, p_max 1.0-1.07.
    * 300 um: end-loaded in both, at the face end where the crowning slows but does
      not stop the wedge. Loaded length LCP / law 0.930 (0.902 / 0.916 at 64 / 256
      rows), bound 0.85-0.95; the peak at the sharp end is singular on the half-space
      (the LCP's end row grows with the rows), so the LCP's line load is taken as its
      mean over the first slice (w = L / 16) from the loaded end, which converges
      (356 / 359 / 365 N/mm at 64 / 128 / 256 rows): 1.22 x the law's peak (294 N/mm),
      bound 1.1-1.35 (the shorter length's 1.08 and the end's concentration). The
      closed form on the mean slope (analytic.face_load.end_loaded_line, which the
      preview took before) gave 2.84 mm and 806 N/mm: conservative by half."""
    from gearcontact.geometry.cylindrical.pair import MeshAlignment

    p = replace(_spur(30.0), assembly=MeshAlignment(axis_inclination_um=incl_um))
    cyc = cylindrical_mesh_cycle(p, phases=3)
    lte = cylindrical_loaded_te(p, 64.5, cycle=cyc, cells_along=128, bending=False)
    pv = cylindrical_preview(p, 64.5, cycle=cyc, loaded_te=lte, backends=("reference",))
    k = 1
    j = int(np.argmax(pv.load_n[:, k]))
    assert pv.load_n[j, k] == pytest.approx(pv.normal_load_n, rel=1e-9)
    assert lte.converged and not lte.edge_touch
    fl = pv.face_load
    end = incl_um == 300.0
    assert bool(fl.end_loaded[j, k]) == bool(lte.line_end_loaded[j, k]) == end
    ratio_l = lte.loaded_length_mm[j, k] / fl.loaded_length_mm[j, k]
    assert 0.85 < ratio_l < 0.95
    wl = lte.line_load_n_per_mm[j, k]
    w_peak = fl.peak_line_load_n_per_mm[j, k]
    if end:
        dz = lte.z_mm[1] - lte.z_mm[0]
        first = int(np.flatnonzero(wl > 0.0)[0])
        n = int(round(pv.stencils.line_length_mm[j, k] / 16 / dz))
        assert 1.1 < wl[first:first + n].mean() / w_peak < 1.35
    else:
        ratio_w = wl.max() / w_peak
        assert 1.0 < ratio_w < 1.15
        assert ratio_w == pytest.approx(1.0 / ratio_l, rel=0.03)
        ratio_p = lte.line_pressure_mpa[j, k].max() / pv.results["reference"][j][k].p_max_mpa
        assert 1.0 < ratio_p < 1.07


@pytest.fixture(scope="module")
def ev_lte():
    """EV helical pair (tip relief, crowning), 5 phases, 300 N·m: its cycle and loaded
    TE with tooth bending."""
    p = load_pair(EXAMPLES / "ev_reducer_helical_23x67.toml", kinds=("cylindrical",))
    cyc = cylindrical_mesh_cycle(p, phases=5)
    return p, cyc, cylindrical_loaded_te(p, 300.0, cycle=cyc)


@pytest.fixture(scope="module")
def ev_preview(ev_lte):
    """The preview on the loaded TE's shares with the slice law on the half-space
    foundation alone (``bending=False``: the twin's law)."""
    p, cyc, lte = ev_lte
    return p, cyc, cylindrical_preview(p, 300.0, cycle=cyc, loaded_te=lte, min_share=0.0,
                                       bending=False)


def test_helical_preview_with_ltca_shares(ev_preview):
    """EV helical pair: every loaded pair previewed, golden within the fit's bound of
    fp64, the loads summing to F_n at every phase. A pair entering the zone with ~1 % of
    F_n on a 1.9 mm line has an equivalent length below the line core's 1 mm
    (LINE_ENVELOPE): the host's lift (preview.hertz.line.length_lift, on 2^s W and 2^s
    L_eq) answers it in line mode, fp64 and golden alike, nothing refused or flagged."""
    from gearcontact.preview.hertz.reference import LINE_ENVELOPE

    p, cyc, pv = ev_preview
    np.testing.assert_allclose(pv.load_n.sum(axis=0), pv.normal_load_n, rtol=1e-9)
    assert pv.loaded.sum() >= 2 * 5
    short = pv.loaded & (pv.face_load.equivalent_length_mm
                         < LINE_ENVELOPE["line_length_mm"][0])
    assert short.any() and not pv.errors
    assert (pv.load_n[short] < 0.02 * pv.normal_load_n).all()
    ref, gold = pv.values("reference", "p_max_mpa"), pv.values("golden", "p_max_mpa")
    for j, k in zip(*np.nonzero(pv.loaded)):
        c = coefficient_error_bound(pv.stencils.gaps_mm[j, k])
        r = pv.results["reference"][j][k]
        assert abs(gold[j, k] - ref[j, k]) <= 0.5 * (c[3] + c[5] + c[4] / 2) / \
            r.A_minus_per_mm * ref[j, k] + LSB_P
    assert set(pv.modes("golden")[pv.loaded]) == {"line"}
    assert set(pv.modes("reference")[pv.loaded]) == {"line"}


def test_helical_preview_on_the_loaded_length(ev_preview):
    """The EV pair's crowned, relieved lines carry load mid-line: the line chain runs on
    the equivalent length L_eq = W / w_peak of the twin's slice law's peak line load
    (ltca.slice_law), not on the whole line L. Truths: (1) the fp64 line core's p_max
    is Johnson 1985 eq. 4.45 on L_eq, p0 = sqrt(W E* / (pi R L_eq)) with 1/(2R) the
    fitted B_max (to 1e-9, the rounding), and L_c / 2 <= L_eq <= L_c (the Winkler load
    of a convex ease-off lies between a triangle and a rectangle);
    (2) L_c is a part of the line (0 < L_c <= L) and shorter than it here (the crowning
    and the relief leave the line ends open at 300 N·m: measured 0.85-0.95 L on every
    pair carrying a twentieth of F_n; bound < 0.96 L); (3) the twin's law at the same rows: the slice
    law on the twin's own mesh-table inputs (twin.cylindrical.cylindrical_mesh_table:
    ease-off, line length, stage C's fp64 fit, as twin.line_law reads them) at the same
    load gives the same L_c and L_eq bit for bit."""
    from gearcontact.ltca.slice_law import equivalent_length, loaded_length_mm
    from gearcontact.preview.fit.reference import principal_curvatures
    from gearcontact.twin.cylindrical import cylindrical_mesh_table
    from gearcontact.preview.fit.reference import fitted_coefficients

    p, cyc, pv = ev_preview
    e_star = resolve_e_star((p.pinion_material, p.gear_material))
    mesh = cylindrical_mesh_table(p, cyc, pv.stencils)
    coeff = fitted_coefficients(mesh.stencil_gaps_mm)
    long_pairs = 0
    for j, k in zip(*np.nonzero(pv.loaded)):
        r = pv.results["reference"][j][k]
        w, l_c = float(pv.load_n[j, k]), float(pv.loaded_length_mm[j, k])
        length = float(pv.stencils.line_length_mm[j, k])
        assert r.mode == "line"
        b_max = max(r.A_minus_per_mm, r.B_minus_per_mm)      # 1 / (2 R)
        l_eq = float(pv.face_load.equivalent_length_mm[j, k])
        assert r.p_max_mpa == pytest.approx(math.sqrt(w * e_star * 2.0 * b_max
                                                      / (math.pi * l_eq)), rel=1e-9)
        assert 0.5 * l_c <= l_eq <= l_c
        assert 0.0 < l_c <= length * (1.0 + 1e-12)
        if w >= 0.05 * pv.normal_load_n:
            assert l_c < 0.96 * length
            long_pairs += 1
        kk = int(np.flatnonzero(mesh.phi1_rad == cyc.phi1_rad[k])[0])
        assert mesh.contact_mode[j, kk] == 0 and mesh.line_length_mm[j, kk] == length
        twin_b = max(principal_curvatures(*map(float, coeff[j, kk]))[:2])
        d_c, twin_l_c, area = loaded_length_mm(mesh.line_gap_mm[j, kk], length, w, twin_b,
                                               mesh.e_prime_mpa)
        assert twin_l_c == l_c and equivalent_length(d_c, area, length) == l_eq
    assert long_pairs >= 5


def _coupled_rows(ev_lte, ev_preview):
    """Per phase, the heaviest line's ``(j, k, coupled / LCP, uncoupled / LCP peak line
    load, coupled L_c, uncoupled L_c, the LCP's L_c)`` and the coupled preview."""
    p, cyc, lte = ev_lte
    half = ev_preview[2]
    pv = cylindrical_preview(p, 300.0, cycle=cyc, loaded_te=lte, min_share=0.0,
                             backends=("reference",))
    cb = math.cos(math.radians(p.geometry.base_helix_angle_deg))
    rows = []
    for k in range(pv.load_n.shape[1]):
        j = int(np.argmax(pv.load_n[:, k]))
        lcp_peak = float(lte.line_load_n_per_mm[j, k].max()) * cb
        rows.append((j, k, float(pv.face_load.peak_line_load_n_per_mm[j, k]) / lcp_peak,
                     float(half.face_load.peak_line_load_n_per_mm[j, k]) / lcp_peak,
                     float(pv.face_load.loaded_length_mm[j, k]),
                     float(half.face_load.loaded_length_mm[j, k]),
                     float(lte.loaded_length_mm[j, k])))
    return pv, rows


def test_coupled_slice_law_in_the_preview(ev_lte, ev_preview):
    """With the loaded TE's tooth bending (the default of ``analyze``), the preview runs
    the coupled slice law (ltca.coupled_slice_law: the half-space foundation plus the
    shells' compliance G at the line's slices, the loaded TE's shells). On every loaded
    pair: the coupled law's slice forces sum to the pair's LCP load (1e-12, rounding of
    the shares; one lever per line, so the torque balance is the same sum) and are >= 0;
    its L_eq is at least the uncoupled law's (G positive semi-definite: bending spreads,
    never concentrates, on these convex ease-offs; 1e-12 for the rounding where a line's
    G f is nearly uniform); the line chain's p_max is Johnson eq. 4.45 on the coupled
    L_eq (1e-9, the rounding)."""
    from gearcontact.ltca.coupled_slice_law import coupled_line, line_bending_compliance
    from gearcontact.ltca.cylindrical_bending import cylindrical_bending
    from gearcontact.ltca.slice_law import line_easeoff_mm
    from gearcontact.materials import effective_modulus_mpa
    from gearcontact.preview.fit.reference import fitted_coefficients, principal_curvatures

    p, cyc, lte = ev_lte
    half = ev_preview[2]
    pv, _ = _coupled_rows(ev_lte, ev_preview)
    assert lte.bending
    e_star = resolve_e_star((p.pinion_material, p.gear_material))
    ease, slices = line_easeoff_mm(p, cyc, pv.stencils.valid)
    teeth = cylindrical_bending(p, facing=cyc.facing)
    coeff = fitted_coefficients(pv.stencils.gaps_mm)
    for j, k in zip(*np.nonzero(pv.loaded)):
        w, length = float(pv.load_n[j, k]), float(pv.stencils.line_length_mm[j, k])
        b_max = max(principal_curvatures(*map(float, coeff[j, k]))[:2])
        line = coupled_line(ease[j, k], length, w, b_max,
                            effective_modulus_mpa(p.pinion_material, p.gear_material),
                            line_bending_compliance(teeth, slices, j, k))
        assert line.slice_load_n.sum() == pytest.approx(w, rel=1e-12)
        assert (line.slice_load_n >= 0.0).all()
        assert line.loaded_length_mm == pv.face_load.loaded_length_mm[j, k]
        l_eq = float(pv.face_load.equivalent_length_mm[j, k])
        assert l_eq >= float(half.face_load.equivalent_length_mm[j, k]) * (1.0 - 1e-12)
        r = pv.results["reference"][j][k]
        if r is not None:
            assert r.p_max_mpa == pytest.approx(math.sqrt(
                w * e_star * 2.0 * max(r.A_minus_per_mm, r.B_minus_per_mm)
                / (math.pi * l_eq)), rel=1e-9)


@pytest.mark.xfail(strict=True, reason=(
    "differs, measured: the coupled law at the least gap is 0.993-1.0025 of the LCP's "
    "line load at 300 N·m (0.990-1.015 at 64.5 N·m, 61 phases), above the declared "
    "0.937-1.002 (the rigid foundation bias 0.952-0.987 +- 0.015): with bending the "
    "foundation's own bias is not kept, the coupled law lands on the LCP within "
    "+-1.5 %; docs/cylindrical.md sec. 8"))
def test_coupled_line_load_at_the_least_gap_against_the_lcp(ev_lte, ev_preview):
    """Where the preview's peak line load is defined -- the line's least gap -- the
    coupled law's w_peak against the LCP with bending's line load at the same point
    (interpolated between its rows; per unit face width times cos(beta_b)), on the
    heaviest line of each phase. Tolerance declared from the cause before this
    comparison: the slice law's own foundation bias there on rigid teeth (uncoupled law
    / rigid LCP at the least gap, EV example: 0.973-0.987 at 300 N·m, 0.952-0.973 at
    64.5 N·m), with 0.015 either side for the shells' G at the 16 slices' points:
    0.937-1.002. The uncoupled law against the same LCP stays > 1.10 (measured
    1.188-1.251 at 64.5 N·m: bending's spreading, which it lacks). (The LCP's largest
    line load sits elsewhere at some phases, at the tip relief's start, an ease-off
    kink the Winkler foundation does not sharpen: test below.)"""
    from gearcontact.ltca.slice_law import line_easeoff_mm

    p, cyc, lte = ev_lte
    half = ev_preview[2]
    pv, _ = _coupled_rows(ev_lte, ev_preview)
    ease, slices = line_easeoff_mm(p, cyc, pv.stencils.valid)
    cb = math.cos(math.radians(p.geometry.base_helix_angle_deg))
    for k in range(pv.load_n.shape[1]):
        j = int(np.argmax(pv.load_n[:, k]))
        z0 = slices.z_mm[j, k][int(np.argmin(ease[j, k]))]
        lcp = float(np.interp(z0, lte.z_mm, lte.line_load_n_per_mm[j, k])) * cb
        assert half.face_load.peak_line_load_n_per_mm[j, k] / lcp > 1.10
        assert 0.937 <= pv.face_load.peak_line_load_n_per_mm[j, k] / lcp <= 1.002


@pytest.mark.xfail(strict=True, reason=(
    "differs, measured: at 300 N·m the coupled law loads the whole line (L_c 21.1-22.7 mm) "
    "where the LCP with bending leaves 19.6-20.2 mm loaded (the uncoupled law 18.9-19.4), "
    "and at the two-pair phase (0 = 4) its peak line load is 0.863 of the LCP's, the "
    "uncoupled law's 1.003 (phases 1-3: 0.958-1.002 against 1.108-1.159); "
    "docs/cylindrical.md sec. 8"))
def test_coupled_slice_law_against_the_lcp_with_bending(ev_lte, ev_preview):
    """The truth of the coupled law is the loaded TE's LCP with the same shells. On the
    heaviest line of each phase (the one that sets the phase's peak; lines entering or
    leaving at a tip carry a sharp end the 16 slices do not resolve), declared before
    this comparison from the 64.5 N·m, 61-phase measurement (docs/cylindrical.md sec.
    8): the uncoupled law overshoots the LCP's peak line load by > 5 % (measured
    1.098-1.215 there); the coupled law's peak line load lies in 0.88-1.02 of the LCP's
    (measured 0.899-0.994 there, against the slice law's own foundation bias of
    0.951-0.965 on rigid teeth, with 0.02 either side); it is nearer the LCP than the
    uncoupled law's in the peak line load and in the loaded length (the LCP's loaded
    rows along the line). The LCP's line load is per unit face width: times
    cos(beta_b) per unit length of the line."""
    _, rows = _coupled_rows(ev_lte, ev_preview)
    for j, k, coupled, uncoupled, l_c, l_u, l_lcp in rows:
        assert uncoupled > 1.05
        assert 0.88 <= coupled <= 1.02
        assert abs(coupled - 1.0) < abs(uncoupled - 1.0)
        assert abs(l_c - l_lcp) < abs(l_u - l_lcp)


def test_torque_mismatch_refused():
    p = _spur(0.0)
    cyc = cylindrical_mesh_cycle(p, phases=3)
    lte = cylindrical_loaded_te(p, 100.0, cycle=cyc, cells_along=8, cells_across=8)
    with pytest.raises(InputRangeError, match="loaded_te.torque_nm"):
        cylindrical_preview(p, 200.0, cycle=cyc, loaded_te=lte)
    with pytest.raises(InputRangeError, match="bending"):
        cylindrical_preview(p, 100.0, cycle=cyc, loaded_te=lte, bending="yes")


def test_rtl_equals_golden_on_cylindrical_stencils(spur_pitch):
    """ChainLineCore (Amaranth simulator) == golden bit for bit, 811 cycles, on the
    stencils of the pitch phase and both neighbours (about 2 s per stencil)."""
    from gearcontact.preview.chain import CHAIN_LINE_CYCLES, chain_line_golden
    from gearcontact.preview.chain_line_rtl import simulate_chain_line_core
    crowning, p, cyc, lte, pv, j = spur_pitch
    idx = list(zip(*np.nonzero(pv.loaded)))[:3]
    codes = [pv.results["golden"][j][k].codes for j, k in idx]
    gaps = np.array([encode_gaps(pv.stencils.gaps_mm[j, k]) for j, k in idx])
    w = [c["W"] for c in codes]
    length = [c["L"] for c in codes]
    ep = codes[0]["e_prime"]
    outs, cycles = simulate_chain_line_core(gaps, w, length, e_prime_code=ep)
    assert cycles == [CHAIN_LINE_CYCLES] * len(idx)
    want = [chain_line_golden([int(x) for x in g], wi, li, e_prime_code=ep)
            for g, wi, li in zip(gaps, w, length)]
    assert outs == want
    # and the engine's golden results are those codes (what the analysis reports)
    for o, (j, k) in zip(outs, idx):
        assert o.hertz.p_max_code * LSB_P == pv.results["golden"][j][k].p_max_mpa


def test_verilator_chain_line_on_cylindrical_vectors():
    """The Verilator harness (hw.harness_cores, core ``chain_line``) on every loaded
    pair's stencil of the spur pair (21 phases) and the EV helical pair (21 phases, LCP
    shares at 64.5 N·m): RTL == golden on every output port, 811 cycles each (the
    harness build is cached after its first run, ~1-3 min on a fresh machine)."""
    from gearcontact.hw import harness_cores as hc
    from gearcontact.hw.verilator import VerilatorNotFound
    from gearcontact.preview.stimulus import Stimulus

    fields = {"gaps": [], "W": [], "L": [], "e_prime": []}
    for name, phases, torque in (("spur_20x40_m3.toml", 21, 200.0),
                                 ("ev_reducer_helical_23x67.toml", 21, 64.5)):
        p = load_pair(EXAMPLES / name, kinds=("cylindrical",))
        cyc = cylindrical_mesh_cycle(p, phases=phases)
        lte = cylindrical_loaded_te(p, torque, cycle=cyc, cells_along=40)
        pv = cylindrical_preview(p, torque, cycle=cyc, loaded_te=lte, backends=("golden",))
        for j, k in zip(*np.nonzero(pv.loaded)):
            c = pv.results["golden"][j][k].codes
            fields["gaps"].append(encode_gaps(pv.stencils.gaps_mm[j, k]))
            for key in ("W", "L", "e_prime"):
                fields[key].append(c[key])
    st = Stimulus("chain_line", {k: np.asarray(v, dtype=np.int64) for k, v in fields.items()},
                  tuple(["cylindrical"] * len(fields["W"])), 0)
    try:
        rep = hc.run_equivalence("chain_line", 0, stim=st)
    except (VerilatorNotFound, hc.CoreUnavailable) as exc:
        pytest.skip(str(exc))
    assert rep.vectors == len(st) >= 60
    assert rep.mismatches == 0, rep.mismatch_examples
    assert rep.cycle_counts == {811: len(st)}
