"""Tip edges beyond a helical pair's contact line in the loaded TE (ltca.cylindrical_edges,
ltca.cylindrical_lte; docs/cylindrical.md sec. 7, "Tip-edge contact (edge rows)") against
independent truths: the LCP's monotonicity (more contacts under the same torque turn the
gear less), its complementarity (an edge carries exactly where its closing turn is below
the solved rotation), the torque balance with each block's own lever, the involute
helicoid's normal moment r_b2 cos(beta_b), mirror symmetry of the hands, and a spur pair
with no sections beyond its line.

Rigid teeth on a coarse grid (16 rows, 12 cells across, 7 phases) keep each solve to
~0.05 s: the truths are properties of the LCP, exact on any grid."""

from dataclasses import replace
from pathlib import Path
import math

import numpy as np
import pytest

from gearcontact.geometry.cylindrical.pair import ToothModifications
from gearcontact.geometry.pair import load_pair
from gearcontact.ltca import cylindrical_lte as lte_module
from gearcontact.tca.cylindrical_cycle import cylindrical_mesh_cycle
from gearcontact.tca.cylindrical_tip import beyond_line_edge_gaps
from gearcontact.tca.plane_of_action import PlaneOfAction

from lte_edges_off import without_lte_edges

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
ARCSEC = 206264.80624709636
GRID = dict(bending=False, cells_along=16, cells_across=12)


def _unmodified(p):
    return replace(p, modifications_pinion=ToothModifications(member="pinion"),
                   modifications_gear=ToothModifications(member="gear"))


@pytest.fixture(scope="module")
def ev():
    return load_pair(EXAMPLES / "ev_reducer_helical_23x67.toml", kinds=("cylindrical",))


@pytest.fixture(scope="module")
def unrelieved(ev):
    """The EV pair without micro-geometry (a left-hand pinion), its 7-phase cycle and
    loaded TE at T2 = 400 N·m."""
    p = _unmodified(ev)
    c = cylindrical_mesh_cycle(p, phases=7)
    return p, c, lte_module.cylindrical_loaded_te(p, 400.0, cycle=c, **GRID)


def _theta(r):
    return np.abs(r.lte_arcsec - r.te0_arcsec) / ARCSEC


def test_edges_beyond_the_lines_of_an_unrelieved_helical_pair(unrelieved, monkeypatch):
    """The EV pair without micro-geometry at T2 = 400 N·m: the tip edges just beyond the
    lines' tip ends (separation growing from 0 at the end) carry, as rows of their line's
    block. Truths: (a) the torque balance (1e-9: the LCP's constraint); (b) a loaded edge
    row is rigidly closed at the solved rotation (its closing turn, its first cell into
    the flank at x = dx/2 included, below the rotation: elastic displacements only open a
    contact), and every row whose closing turn is below the rotation is in the LCP (the
    entry rule), margins above 1e-9 rad; (c) the pinion tip touches the gear's involute
    helicoid, whose normal has the moment r_b2 cos(beta_b) about its axis (1e-9), the
    line's lever; (d) the edge rows lie beyond the line's ends, at pair-phases where the
    unloaded cycle's tip solve finds the edge touching within reach (TE0's extended
    contact); (e) monotonicity: with the edges the gear turns less at every phase than
    without them (1e-9 relative: the LCP's tolerance), strictly where one carries, and
    the loaded TE p-p drops."""
    p, c, r = unrelieved
    g = p.geometry
    lever = 0.5 * g.base_diameter_gear_mm * math.cos(math.radians(g.base_helix_angle_deg))
    moment = (r.load_share * r.lever_mm).sum(axis=0) \
        + (r.beyond_load_share * r.beyond_lever_mm).sum(axis=(0, 2))
    np.testing.assert_allclose(moment, lever, rtol=1e-9)
    carry = r.beyond_load_share > 0.0
    assert carry[..., 0].any() and carry[..., 1].any()        # both tip edges
    theta = _theta(r)
    bg = beyond_line_edge_gaps(PlaneOfAction(p, c.facing), c, r.z_mm)
    np.testing.assert_allclose(bg[0].lever_mm[np.isfinite(bg[0].lever_mm)], lever, rtol=1e-9)
    dz = r.z_mm[1] - r.z_mm[0]
    x = 0.5 * r.grid_dx_mm
    for e in range(2):
        gap = bg[e].gap_mm
        turn = (gap - c.closing_gap_mm[None, :, None]) / np.abs(bg[e].rate_mm_per_rad)[..., None]
        cell = (bg[e].slope * x + 0.5 * bg[e].inv_radius_per_mm * x * x) / bg[e].lever_mm
        loaded = (r.beyond_rows == e) & (r.line_load_n_per_mm > 0.0)
        closed = turn + cell[..., None] < theta[None, :, None]
        assert np.all(closed[loaded])
        margin = np.abs(turn + cell[..., None] - theta[None, :, None])
        assert np.all(margin[loaded] > 1e-9)
        np.testing.assert_array_equal((turn < theta[None, :, None]) & np.isfinite(gap)
                                      & ~(r.beyond_rows == e), False)
        np.testing.assert_allclose((r.line_load_n_per_mm * (r.beyond_rows == e)).sum(-1) * dz,
                                   r.beyond_load_share[..., e] * r.normal_load_n, rtol=1e-12,
                                   atol=1e-12)
    lo, hi = c.line_ends_zu_mm[..., 0, 0], c.line_ends_zu_mm[..., 1, 0]
    z = np.broadcast_to(r.z_mm, r.beyond_rows.shape)
    edge = r.beyond_rows >= 0
    assert np.all(((z < lo[..., None]) | (z > hi[..., None]))[edge])
    assert np.all(np.isfinite(c.tip.gap_mm)[carry.any(axis=-1)])
    without_lte_edges(monkeypatch)
    r0 = lte_module.cylindrical_loaded_te(p, 400.0, cycle=c, **GRID)
    theta0 = _theta(r0)
    assert np.all(theta <= theta0 * (1.0 + 1e-9))
    assert np.all(theta[carry.any(axis=(0, 2))] < theta0[carry.any(axis=(0, 2))] * (1.0 - 1e-6))
    assert r.lte_pp_arcsec < r0.lte_pp_arcsec


def test_relieved_helical_pair_at_light_load_is_unchanged(ev, monkeypatch):
    """The EV example (8 um tip relief on both members) at T2 = 20 N·m: its relief opens
    the edges beyond the lines by 12-15 um, far above the ~1 um approach: none carries
    (those of the first phase enter the LCP, whose previous rotation is unknown, and stand
    open), and the loaded TE and line loads are those without them to the LCP's
    tolerance (1e-8 of the load: 1e-9 relative on the TE), bit for bit after phase 0."""
    c = cylindrical_mesh_cycle(ev, phases=7)
    r = lte_module.cylindrical_loaded_te(ev, 20.0, cycle=c, **GRID)
    assert not r.beyond_load_share.any() and (r.beyond_rows[:, 1:] == -1).all()
    without_lte_edges(monkeypatch)
    r0 = lte_module.cylindrical_loaded_te(ev, 20.0, cycle=c, **GRID)
    np.testing.assert_allclose(r.lte_arcsec, r0.lte_arcsec, rtol=1e-9)
    np.testing.assert_allclose(r.line_load_n_per_mm, r0.line_load_n_per_mm, rtol=1e-6,
                               atol=1e-8 * r.normal_load_n)
    np.testing.assert_array_equal(r.lte_arcsec[1:], r0.lte_arcsec[1:])


def test_mirror_hands_give_the_mirrored_edges(ev, unrelieved):
    """Left- and right-hand pinions (the EV pair without micro-geometry, 400 N·m) are
    mirror images through the mid-face plane: the same loaded TE (1e-9 relative: the
    LCP's tolerance on mirrored, otherwise identical, fields), the same edge loads and
    levers, on the mirrored rows."""
    assert ev.pinion_hand == "left"
    a = unrelieved[2]
    p = _unmodified(replace(ev, pinion_hand="right"))
    b = lte_module.cylindrical_loaded_te(p, 400.0, cycle=cylindrical_mesh_cycle(p, phases=7),
                                         **GRID)
    np.testing.assert_allclose(a.lte_arcsec, b.lte_arcsec, rtol=1e-9)
    np.testing.assert_allclose(a.beyond_load_share, b.beyond_load_share, rtol=1e-6, atol=1e-9)
    np.testing.assert_allclose(a.beyond_lever_mm, b.beyond_lever_mm, rtol=1e-9)
    np.testing.assert_array_equal(a.beyond_rows, b.beyond_rows[..., ::-1])
    assert a.beyond_load_share.any()


def test_spur_pair_has_no_sections_beyond_its_line():
    """A spur pair's line spans the face in one transverse state: no section lies beyond
    the path end while others are in the zone, so there is no edge row beyond a line."""
    p = load_pair(EXAMPLES / "spur_20x40_m3.toml", kinds=("cylindrical",))
    c = cylindrical_mesh_cycle(p, phases=7)
    z = np.linspace(*c.pinion_v_range_mm, 16)
    for bg in beyond_line_edge_gaps(PlaneOfAction(p, c.facing), c, z):
        assert np.isnan(bg.gap_mm).all()
