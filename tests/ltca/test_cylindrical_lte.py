"""Loaded TE of cylindrical pairs (ltca.cylindrical_lte, rigid teeth and with tooth
bending) against independent truths: Johnson's line-contact Hertz pressure, the load
balance of the torque, ISO 6336-1 Method B stiffness, and the direction the load turns
the gear."""

import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from gearcontact.analytic.iso6336 import cylindrical_pair_stiffness, theoretical_single_stiffness
from gearcontact.geometry.pair import load_pair
from gearcontact.halfspace.lcp import resolve_e_star
from gearcontact.ltca.cylindrical_lte import cylindrical_loaded_te, harris_map, normal_load_n
from gearcontact.tca.cylindrical_cycle import cylindrical_mesh_cycle
from gearcontact.validation import InputRangeError

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def _load(name):
    return load_pair(EXAMPLES / name, kinds=("cylindrical",))


@pytest.fixture(scope="module")
def spur():
    """The standard 20/40 m 3 spur pair with 1 um lead crowning on the pinion (a full-face
    line at T2 = 400 N·m) and its 21-phase cycle."""
    p = _load("spur_20x40_m3.toml")
    p = replace(p, modifications_pinion=replace(p.modifications_pinion, lead_crowning_um=1.0))
    return p, cylindrical_mesh_cycle(p, phases=21)


@pytest.fixture(scope="module")
def helical():
    p = _load("ev_reducer_helical_23x67.toml")
    return p, cylindrical_mesh_cycle(p, phases=13)


def test_line_contact_hertz_at_the_pitch_point(spur):
    """Mid-face of the single pair at the pitch point (phase 10 of 21: single contact of
    eps_alpha 1.635): the peak pressure across the line against Johnson 1985 eq. 4.45,
    p0 = sqrt(w E* / (pi R)), with w the LCP's own load per unit length there (the
    half-space raises the load at the face ends; 2D Hertz holds where it varies slowly)
    and 1/R = 1/(r_b1 tan a_wt) + 1/(r_b2 tan a_wt). Tolerance: the cell centres nearest
    the peak lie dx/2 off it, p0 (1 - (dx/2b)^2/2), plus 0.5 % for the piecewise-constant
    pressure (measured -0.08 % at 48 cells across, -0.32 % at 24)."""
    p, c = spur
    r = cylindrical_loaded_te(p, 400.0, cycle=c, cells_across=48, cells_along=40,
                              bending=False)
    k = 10
    assert np.count_nonzero(r.load_share[:, k]) == 1
    j = int(np.argmax(r.load_share[:, k]))
    g = p.geometry
    tan_a = math.tan(math.radians(g.working_pressure_angle_deg))
    R = 1.0 / (2.0 / (g.base_diameter_pinion_mm * tan_a) + 2.0 / (g.base_diameter_gear_mm * tan_a))
    e_star = resolve_e_star((p.pinion_material, p.gear_material))
    mid = 20
    w = 0.5 * (r.line_load_n_per_mm[j, k, mid - 1] + r.line_load_n_per_mm[j, k, mid])
    p_lcp = 0.5 * (r.line_pressure_mpa[j, k, mid - 1] + r.line_pressure_mpa[j, k, mid])
    p0 = math.sqrt(w * e_star / (math.pi * R))
    half_width = math.sqrt(4.0 * w * R / (math.pi * e_star))
    tol = 0.5 * (r.grid_dx_mm / (2.0 * half_width)) ** 2 + 5e-3
    assert abs(p_lcp / p0 - 1.0) < tol
    assert not r.edge_touch and r.converged


def test_load_balance_of_the_torque(helical):
    """The torque balance of every phase, ``sum (share lever) = r_b2 cos beta_b`` over the
    lines and the tip edges beyond them, each block with its own lever (the LCP's torque
    constraint: 1e-9 relative), F_n = T2 / (r_b2 cos beta_b), and the line loads integrate
    to the blocks' normal loads; with tooth bending (the default)."""
    p, c = helical
    r = cylindrical_loaded_te(p, 400.0, cycle=c)
    g = p.geometry
    cb = math.cos(math.radians(g.base_helix_angle_deg))
    lever = 0.5 * g.base_diameter_gear_mm * cb
    fn = 400e3 / lever
    # the pinion's torque balance of the same load (ISO 6336-1: T1 / (r_b1 cos beta_b))
    assert fn == pytest.approx(400e3 / p.ratio / (0.5 * g.base_diameter_pinion_mm * cb), rel=1e-12)
    assert r.normal_load_n == pytest.approx(fn, rel=1e-12)
    moment = (r.load_share * r.lever_mm).sum(axis=0) \
        + (r.beyond_load_share * r.beyond_lever_mm).sum(axis=(0, 2))
    np.testing.assert_allclose(moment, lever, rtol=1e-9)
    dz = r.z_mm[1] - r.z_mm[0]
    total = r.load_share.sum(axis=0) + r.beyond_load_share.sum(axis=(0, 2))
    np.testing.assert_allclose(r.line_load_n_per_mm.sum(axis=(0, 2)) * dz, fn * total,
                               rtol=1e-9)
    # more than one pair shares the load (eps_gamma 3.4) and the solves converged
    assert (np.count_nonzero(r.load_share > 1e-3, axis=0) >= 2).all() and r.converged


@pytest.mark.parametrize("facing", ["cw", "ccw"])
def test_load_turns_the_gear_further_the_way_it_lags(helical, facing):
    """The unloaded gear lags by the backlash half (TE0 < 0 cw, > 0 ccw, docs sec. 6); the
    load adds the contact's approach the same way, more at a higher torque."""
    p, _ = helical
    c = cylindrical_mesh_cycle(p, facing=facing, phases=7)
    lo, hi = (cylindrical_loaded_te(p, t, cycle=c, bending=False) for t in (150.0, 600.0))
    s = np.sign(c.envelope_arcsec)
    assert (s == s[0]).all()
    assert (s * (lo.lte_arcsec - lo.te0_arcsec) > 0).all()
    assert (s * (hi.lte_arcsec - lo.lte_arcsec) > 0).all()


def test_mesh_stiffness_against_iso_6336_method_b(spur):
    """ISO 6336-1 Method B for the standard 20/40 spur pair: c' = c'_th C_M C_R C_B
    (0.8, 1, 0.975: h_fP 1.25 m) = 12.7 and c_gamma_alpha = c' (0.75 eps_alpha + 0.25)
    = 18.7 N/(mm·µm). Rigid teeth: the half-space holds only the contact flattening, so
    it must be stiffer than the standard's contact + bending + foundation; asserted with
    the order of magnitude (ratio < 10). Measured at T2 = 400 N·m (333 N/mm at d2):
    single-contact stiffness 30.9 (ratio 2.4 to c'), mean 48.2 (2.6 to c_gamma_alpha).
    With bending see :func:`test_mesh_stiffness_with_bending_against_iso_6336`."""
    p, c = spur
    r = cylindrical_loaded_te(p, 400.0, cycle=c, bending=False)
    iso = cylindrical_pair_stiffness(pinion_teeth=20, gear_teeth=40, helix_angle_deg=0.0,
                                     base_helix_angle_deg=0.0,
                                     transverse_contact_ratio=p.geometry.transverse_contact_ratio)
    c_single, c_gamma = iso.c_n_per_mm_um, iso.c_gamma_alpha_n_per_mm_um
    # the same from the flexibility polynomial by hand (C_M 0.8, C_R 1, C_B 0.975)
    c_th = theoretical_single_stiffness(z_n1=20.0, z_n2=40.0)
    assert c_single == pytest.approx(c_th * 0.8 * (1.0 + 0.5 * (1.2 - 1.25)), rel=1e-12)
    single = r.stiffness_n_per_mm_um[np.count_nonzero(r.load_share, axis=0) == 1]
    assert single.size > 0
    assert 1.0 < single.mean() / c_single < 10.0
    assert 1.0 < r.mean_stiffness_n_per_mm_um / c_gamma < 10.0


def test_harris_map_matches_the_direct_solves(helical):
    """Each cell of the map is the loaded TE p-p of the pair with that C_a on both members
    (bit for bit the direct call), and a bad torque is refused naming the field."""
    p, _ = helical
    m = harris_map(p, [150.0, 600.0], [0.0, 8.0], phases=7, bending=False)
    assert m.lte_pp_arcsec.shape == (2, 2) and m.converged
    c = cylindrical_mesh_cycle(p, phases=7)      # the example has C_a = 8 um
    direct = cylindrical_loaded_te(p, 600.0, cycle=c, bending=False)
    assert m.lte_pp_arcsec[1, 1] == direct.lte_pp_arcsec
    assert m.te0_pp_arcsec[1] == c.te0_pp_arcsec
    with pytest.raises(InputRangeError, match="torques_nm"):
        harris_map(p, [0.0], [1.0])
    with pytest.raises(InputRangeError, match="torque_nm"):
        normal_load_n(p, -1.0)


def test_harris_map_of_a_spur_pair():
    """The classic Harris map (S. L. Harris, Proc. Instn Mech. Engrs 172 (1958) 87-112):
    unrelieved spur teeth have a loaded TE p-p that grows with the load (the single /
    double contact stiffness step); a tip relief (both members, from just above the
    highest point of single contact) gives a p-p minimum at the load whose deflection it
    matches, at a larger load for a larger relief, far below the unrelieved p-p there.
    Measured (15 phases; d_Ca 61.68 / 122.17 mm): minima at F_t / b = 50, 200, 300 N/mm
    for C_a = 5, 20, 30 um, p-p 0.70, 2.67, 4.27 against 3.43, 12.19, 17.62 arcsec
    unrelieved. Rigid teeth (the matching loads fall with bending: docs/cylindrical.md
    sec. 7)."""
    p = _load("spur_20x40_m3.toml")
    g = p.geometry

    def start(member, roll):      # d_Ca at a roll length, mm
        return 2.0 * math.hypot(roll, 0.5 * getattr(g, f"base_diameter_{member}_mm"))

    q = replace(p, modifications_pinion=replace(
        p.modifications_pinion, tip_relief_start_diameter_mm=start("pinion", 12.5)),
        modifications_gear=replace(p.modifications_gear,
                                   tip_relief_start_diameter_mm=start("gear", 23.5)))
    from gearcontact.ltca.cylindrical_lte import harris_torques_nm

    m = harris_map(q, harris_torques_nm(q, (25, 50, 100, 200, 300, 400)), [0.0, 5.0, 20.0, 30.0],
                   phases=15, bending=False)
    pp = m.lte_pp_arcsec
    assert m.converged and not m.edge_touch
    assert (np.diff(pp[0]) > 0).all()                      # unrelieved: grows with load
    best = pp[1:].argmin(axis=1)
    assert (np.diff(best) > 0).all() and best[0] > 0 and best[-1] < pp.shape[1] - 1
    for r, k in enumerate(best, start=1):                   # far below the unrelieved p-p
        assert pp[r, k] < 0.5 * pp[0, k]


@pytest.fixture(scope="module")
def spur_iso_stiffness(spur):
    # (measured single-contact stiffness, ISO c'), (measured mean, ISO c_gamma_alpha)
    p, c = spur
    r = cylindrical_loaded_te(p, 400.0, cycle=c)
    assert r.bending and r.converged and not r.edge_touch
    g = p.geometry
    iso = cylindrical_pair_stiffness(pinion_teeth=20, gear_teeth=40, helix_angle_deg=0.0,
                                     base_helix_angle_deg=0.0,
                                     transverse_contact_ratio=g.transverse_contact_ratio)
    single = r.stiffness_n_per_mm_um[np.count_nonzero(r.load_share, axis=0) == 1]
    assert single.size > 0
    return ((single.mean(), iso.c_n_per_mm_um),
            (r.mean_stiffness_n_per_mm_um, iso.c_gamma_alpha_n_per_mm_um))


def test_mesh_stiffness_with_bending_against_iso_6336(spur_iso_stiffness):
    """With the shell bending of both teeth (the fillet following the real root, the rim
    factor calibrated against the 3D FE on the teeth's real roots, docs/bending.md sec.
    9) the 20/40 spur pair at T2 = 400 N·m (333 N/mm at d2, inside Method B's >= 100
    N/mm): measured single-contact stiffness 14.15 and mean 21.57 N/(mm·µm), i.e. 1.11
    and 1.15 times c' = 12.7 and c_gamma_alpha = 18.7 (ISO 6336-1 Method B with its
    measured correction C_M = 0.8).
    Asserted against c' and c_gamma_alpha within the 30 % the background allows an
    empirical fit (tens of percent). The rigid teeth gave 2.5-2.7 times c'."""
    for value, iso_value in spur_iso_stiffness:
        assert 1.0 < value / iso_value < 1.3


@pytest.mark.xfail(strict=True, reason=(
    "differs: single-contact stiffness 0.89 x ISO 6336-1's theoretical c'_th C_B = 15.9 "
    "N/(mm·µm) (mean 0.92 x c_gamma_alpha / C_M = 23.4, at the band's edge), below the "
    "q' polynomial's -8 % band; the 3D FE on the teeth's real trochoidal roots, which "
    "the shell (its fillet following that root, rim factor 1.31) is calibrated on "
    "within 0.94..1.04 (pinion) and 1.00..1.11 (gear), finds these teeth softer than "
    "the theory (the ellipse-root FE's factor 1.4 gave 0.97 / 1.01); "
    "docs/cylindrical.md sec. 7, docs/bending.md sec. 9"))
def test_mesh_stiffness_with_bending_against_iso_6336_theory(spur_iso_stiffness):
    """ISO 6336-1's C_M = 0.8 is the mean ratio of measured to theoretical single
    stiffness of solid disc gears; the model is a theory of the elastic teeth and body of
    the same kind as the theoretical c'_th (no mounting, no shaft or housing compliance),
    so it is compared with the theoretical values (c' / C_M, c_gamma_alpha / C_M) within
    the -8 % / +5 % band the standard gives for the q' polynomial's fit to its theory."""
    for value, iso_value in spur_iso_stiffness:
        assert 0.92 < value / (iso_value / 0.8) < 1.05


def test_bending_factor_is_the_shell_compliance(helical):
    """The factor rows of a pair's field (the flank-rows spline of ltca.tooth_bending and
    its pivoted-Cholesky cut 1e-6) against the shell compliance of the pinion and gear
    tooth evaluated directly at the line points of every row (the operators of
    structure.shell, G_pinion + G_gear): within 2e-3 of the largest entry (the bound of
    ltca.tooth_bending; measured 1e-4 to 2e-4); every cell across a row shares its row,
    rows off the line carry none."""
    from gearcontact.ltca.cylindrical_bending import cylindrical_bending, line_bending_factor
    from gearcontact.tca.cylindrical_cycle import contact_line_gaps

    p, c = helical
    bend = cylindrical_bending(p, facing=c.facing)
    z = np.linspace(*c.pinion_v_range_mm, 64)
    lg = contact_line_gaps(p, c, z)
    k = len(c.phi1_rad) // 2
    j = int(np.argmax(np.isfinite(lg.pinion_roll_mm[:, k]).sum(axis=1)))
    on = np.isfinite(lg.pinion_roll_mm[j, k])
    assert on.sum() >= 10
    f = line_bending_factor(bend, z, lg.pinion_roll_mm[j, k], lg.gear_roll_mm[j, k], 5)
    assert f.shape[:2] == (64, 5)
    np.testing.assert_array_equal(f[:, 0], f[:, 4])
    G = np.einsum("ir,jr->ij", f[on, 0], f[on, 0])
    exact = 0.0
    for shell, roll in ((bend.pinion, lg.pinion_roll_mm), (bend.gear, lg.gear_roll_mm)):
        pts = shell.body.flank_points(bend.side, roll[j, k][on], z[on])
        exact = exact + shell.compliance(pts).matrix()
    assert np.abs(G - exact).max() < 2e-3 * exact.max()
    assert not f[~on].any()


def test_bending_softens_the_mesh_at_every_phase(helical):
    """Added compliance can only turn the gear further: the loaded TE with bending lies
    beyond the rigid one (in the direction the gear lags) at every phase, and the mesh
    stiffness is lower at every phase."""
    p, c = helical
    rigid = cylindrical_loaded_te(p, 400.0, cycle=c, bending=False)
    bent = cylindrical_loaded_te(p, 400.0, cycle=c)
    s = np.sign(c.envelope_arcsec[0])
    assert (s * (bent.lte_arcsec - rigid.lte_arcsec) > 0).all()
    assert (bent.stiffness_n_per_mm_um < rigid.stiffness_n_per_mm_um).all()
    assert bent.bending and not rigid.bending


def test_harris_map_minimum_moves_to_lower_loads_with_bending():
    """A tip relief is matched by the static deflection at one load, delta = F / c: with
    the teeth bending the mesh stiffness about halves (49.8 -> 21.6 N/(mm·µm), above), so
    the load a relief matches falls. 20/40 spur pair, C_a = 20 um on both members from
    just above the highest point of single contact (as the rigid map above), 15 phases:
    measured minimum at F_t / b = 100 N/mm with bending against 200 N/mm rigid (p-p 2.99
    against 2.67 arcsec); unrelieved, the loaded TE p-p is larger with bending at every
    load (the single / double contact stiffness step grows with the compliance)."""
    from gearcontact.ltca.cylindrical_lte import harris_torques_nm

    p = _load("spur_20x40_m3.toml")
    g = p.geometry

    def start(member, roll):
        return 2.0 * math.hypot(roll, 0.5 * getattr(g, f"base_diameter_{member}_mm"))

    q = replace(p, modifications_pinion=replace(
        p.modifications_pinion, tip_relief_start_diameter_mm=start("pinion", 12.5)),
        modifications_gear=replace(p.modifications_gear,
                                   tip_relief_start_diameter_mm=start("gear", 23.5)))
    loads = (50, 100, 200, 300)
    maps = [harris_map(q, harris_torques_nm(q, loads), [0.0, 20.0], phases=15, bending=b)
            for b in (False, True)]
    assert all(m.converged and not m.edge_touch for m in maps)
    rigid, bent = (m.lte_pp_arcsec for m in maps)
    assert loads[int(bent[1].argmin())] == 100 and loads[int(rigid[1].argmin())] == 200
    assert (bent[0] > rigid[0]).all()


def test_extended_contact_of_deflected_unrelieved_teeth():
    """The classical extended contact of an unrelieved spur pair under load: the teeth in
    contact deflect, the gear lags the unloaded mesh by the LCP's rotation theta, and a
    pair beyond its path of contact touches at its tip edge (tca.cylindrical_tip, tested
    against the closed-form tip circle on the involute) wherever its closing turn behind
    the unloaded mesh, m (TE0_env - TE0_j), is less: the entering pair's gear tip before
    its line enters (premature), the leaving pair's pinion tip after its line has left
    (prolonged). Checked on the 20/40 m 3 at T2 = 400 N·m, rigid teeth, 21 phases: a tip
    block carries load exactly where that turn is below theta (complementarity of the
    LCP, margins above 1e-9 rad), both kinds occur, the pinion tip's lever is r_b2 (it
    touches the gear's involute, whose normal is tangent to the base circle; 1e-9) and a
    gear tip's is less; the torque balance holds with each block's own lever (1e-9)."""
    p = _load("spur_20x40_m3.toml")
    c = cylindrical_mesh_cycle(p, phases=21)
    r = cylindrical_loaded_te(p, 400.0, cycle=c, cells_along=8, cells_across=16,
                              bending=False)
    g = p.geometry
    rb2 = 0.5 * g.base_diameter_gear_mm
    theta = np.abs(r.lte_arcsec - r.te0_arcsec) / 206264.80624709636
    closing = (c.envelope_arcsec[None, :] - c.te0_pairs_arcsec) / 206264.80624709636
    tip = r.edge_label != ""
    loaded = r.load_share > 0.0
    margin = np.abs(closing - theta[None, :])
    assert np.all(margin[tip] > 1e-9)
    np.testing.assert_array_equal(loaded[tip], (closing < theta[None, :])[tip])
    kinds = set(r.edge_label[tip & loaded])
    assert kinds == {"gear tip", "pinion tip"}
    np.testing.assert_allclose(r.lever_mm[(r.edge_label == "pinion tip") & loaded], rb2,
                               rtol=1e-9)
    assert np.all(r.lever_mm[(r.edge_label == "gear tip") & loaded] < rb2)
    moment = (r.load_share * r.lever_mm).sum(axis=0)
    np.testing.assert_allclose(moment, rb2, rtol=1e-9)


@pytest.fixture(scope="module")
def misaligned_spur():
    """The uncrowned spur 20/40 with the gear axis inclined by 100 and 300 um over the
    face: end-loaded lines at T2 = 64.5 N·m (the user's try of issue 26), their 3-phase
    cycles (phase 1: single contact at the pitch point)."""
    from gearcontact.geometry.cylindrical.pair import MeshAlignment

    p = _load("spur_20x40_m3.toml")
    out = {}
    for incl in (100.0, 300.0):
        q = replace(p, assembly=MeshAlignment(axis_inclination_um=incl))
        out[incl] = q, cylindrical_mesh_cycle(q, phases=3)
    return out


@pytest.mark.parametrize("incl", [100.0, 300.0])
def test_end_loaded_line_against_the_closed_form(misaligned_spur, incl):
    """Rigid teeth, the single pair at the pitch point: the strip is widened until no
    loaded cell lies on its border (the default 24 cells across, before 0.012 mm and
    truncated); the load reaches the line's end (the gear's face end, shifted by the
    tilt) and the phase's peak pressure sits in that end row. Against the finite line's
    closed form on the TCA's gap slope (analytic.face_load.end_loaded_line): the
    approach at the closed end (the gear's rotation times r_b2: the pair closes first)
    within 3 % (measured -0.9 / -1.3 % at 256 rows, -2.4 / -0.2 % at 64: the law is the
    finite line's energy mean on its loaded length); the loaded length below it by at
    most 25 % (measured 0.87 / 0.83 at 100 / 300 um: the closed form's foundation
    deflects only where it is loaded, the half-space also beside the load, which lifts
    the surface at the contact's end). Under refinement (64 -> 256 rows) the loaded
    length moves by less than a coarse row and the approach by < 3 %, and the line load
    sums to the pair's load (1e-9), while the end row's pressure grows (the sharp end's
    singularity: x1.65 / x1.75 measured, bound > 1.2)."""
    from gearcontact.analytic.face_load import end_loaded_line
    from gearcontact.tca.cylindrical_cycle import contact_line_gaps

    p, c = misaligned_spur[incl]
    runs = [cylindrical_loaded_te(p, 64.5, cycle=c, cells_along=n, bending=False)
            for n in (64, 256)]
    k = 1
    j = int(np.argmax(runs[1].load_share[:, k]))
    assert np.count_nonzero(runs[1].load_share[:, k]) == 1
    g = p.geometry
    lever = 0.5 * g.base_diameter_gear_mm
    approach = [abs(r.te0_arcsec[k] - r.lte_arcsec[k]) / 206264.806 * lever for r in runs]
    for r in runs:
        assert not r.edge_touch and r.converged
        assert r.line_end_loaded[j, k] and r.peak_at_edge[k]
        dz = r.z_mm[1] - r.z_mm[0]
        assert r.line_load_n_per_mm[j, k].sum() * dz == pytest.approx(r.normal_load_n, rel=1e-9)
    coarse = runs[0].z_mm[1] - runs[0].z_mm[0]
    assert abs(runs[1].loaded_length_mm[j, k] - runs[0].loaded_length_mm[j, k]) <= coarse
    assert approach[1] == pytest.approx(approach[0], rel=0.03)
    assert runs[1].max_pressure_mpa[k] > 1.2 * runs[0].max_pressure_mpa[k]
    lines = contact_line_gaps(p, c, runs[1].z_mm)
    on = np.isfinite(lines.gap_mm[j, k])
    z = runs[1].z_mm[on]
    slope = abs(np.polyfit(z, lines.gap_mm[j, k][on], 1)[0])
    ends = c.line_ends_zu_mm[j, k, :, 0]
    tan_a = math.tan(math.radians(g.working_pressure_angle_deg))
    b_max = 1.0 / (g.base_diameter_pinion_mm * tan_a) + 1.0 / (g.base_diameter_gear_mm * tan_a)
    e_star = resolve_e_star((p.pinion_material, p.gear_material))
    closed = end_loaded_line(load_n=runs[1].normal_load_n, slope=slope,
                             length_mm=float(abs(ends[1] - ends[0])), b_max_per_mm=b_max,
                             e_prime_mpa=2.0 * e_star)
    assert closed.end_loaded
    assert 0.75 < runs[1].loaded_length_mm[j, k] / closed.loaded_length_mm < 1.0
    assert approach[1] == pytest.approx(closed.approach_mm, rel=0.03)
