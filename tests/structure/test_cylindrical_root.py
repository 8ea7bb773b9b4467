"""The real root of a cylindrical tooth (structure.cylindrical_tooth.cylindrical_fillet_root,
structure.root_fillet, structure.fe) against independent truths.

Truths:
- the envelope of the generating rack (ISO 53 basic rack, tip radius 0.38 m_n): every
  point of the fillet zone, and every vertex of the FE mesh there, lies outside every
  position of the rack's tip rounding (in the transverse section an ellipse of semi-axes
  rho_fP / cos(beta) and rho_fP) and touches one, min over the rack shift of the
  rounding's implicit function = 0; computed here from the rolling of the generating
  pitch circle on the rack's pitch line alone (not from the fillet's closed form, which
  uses Willis' normal condition). Tolerance 1e-9 mm (measured 2e-14 mm: rounding of
  ~25-75 mm coordinates); the slot-bottom vertices on the root circle d_f / 2 (1e-9 mm);
- ISO 6336-3:2019 sec. 6.2 (Method B, generating rack without protuberance): the 30 deg
  tangent section s_Fn and the fillet radius there rho_F from the standard's closed
  form (the theta iteration). For spur gears the closed form is exact for the rack's
  trochoid: s_Fn within 1e-6 mm (measured 1.3e-9 mm), rho_F within 2e-4 relative (a
  circle through three side-curve points 20 um apart, O(h^2): measured 0.9e-5 to
  4.2e-5); on the mesh itself (48 fillet layers, the 30 deg crossing interpolated along
  the vertex polyline) s_Fn within 2e-4 (the chord error of the polyline's tangent;
  measured 7e-5). Helical: ISO replaces the tooth's normal section by the virtual spur
  gear z_n = z / (cos^2 beta_b cos beta), an approximation (measured on the 23/67
  stage: s_Fn 0.28 % / 0.17 % and rho_F 1.8 % / 0.35 % above it, pinion / gear):
  tolerances 1 % and 5 %;
- the shell's fillet (structure.cylindrical_tooth.section_profile) follows the same
  real root: on spur teeth its width at the depth of the 30 deg section is ISO's s_Fn
  within 5e-5 relative (linear interpolation between 129 arc-length samples of each
  side curve: measured 5e-6 to 1.2e-5), its width below the fillet the root row's,
  the chord of one pitch on the root circle d_f sin(pi / z) (1e-12 relative, measured
  2e-16), 1 at the root line, and the shell's fillet ends at the fillet bottoms;
- convergence: the FE tooth compliance on the real root under mesh refinement
  (slow; docs/bending.md sec. 9).
"""

import math
from pathlib import Path

import numpy as np
import pytest

from gearcontact.geometry.pair import load_pair
from gearcontact.structure.cylindrical_compliance import cylindrical_flank_compliance
from gearcontact.structure.cylindrical_tooth import (cylindrical_fillet_root, cylindrical_rim,
                                                     cylindrical_tooth, section_profile)
from gearcontact.structure.rim import root_line_section
from gearcontact.validation import InputRangeError
from rack_envelope import envelope_gap_mm, iso_critical_section, radius_at
from rack_envelope import rack as rack_of

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def _pair(name):
    return load_pair(EXAMPLES / f"{name}.toml", kinds=("cylindrical",))


# FZG C pinion: spur with profile shift 0.1817; the helical stage's gear: beta 25 deg,
# x 0.1, unmodified flanks (its pinion's relief leaves the form point micrometres off the
# fillet, bridged: tested below)
CASES = [("fzg_c_type", "pinion"), ("ev_reducer_helical_23x67", "gear")]


@pytest.mark.parametrize("name, member", CASES)
def test_fe_mesh_on_the_rack_generated_trochoid(name, member):
    # a small FE mesh on the real root (P2, 6 x 2 x 1 cells, 1 block layer, 2 fillet
    # layers, 1 slot cell; ~1 s): no inverted cells (build_fe checks), every side vertex
    # of the fillet zone on the rack's envelope, every root-row vertex on the root circle
    pytest.importorskip("skfem")
    from gearcontact.structure.fe import build_fe

    pair = _pair(name)
    tooth = cylindrical_tooth(pair, member)
    root = cylindrical_fillet_root(pair, tooth)
    rack = rack_of(pair, member)
    n_block, n_fillet, n_slot, n_zeta = 1, 2, 1, 1
    fe = build_fe(tooth, n_xi=6, n_eta=2, n_zeta=n_zeta, n_rim=n_block, root=root,
                  n_fillet=n_fillet, n_slot=n_slot)
    for side, k in (("coast", n_slot), ("drive", n_slot + n_zeta)):
        verts = fe._vertex[:, n_block:n_block + n_fillet + 1, k].ravel()
        gaps = [envelope_gap_mm(rack, side, p) for p in fe.vertex_positions_mm(verts)]
        assert np.max(np.abs(gaps)) < 1e-9, gaps
    r_f = 0.5 * getattr(pair.geometry, f"root_diameter_{member}_mm")
    for i in range(len(fe.xi_levels)):
        row = fe.vertex_positions_mm(fe._vertex[i, n_block, :])
        assert np.abs(np.hypot(row[:, 0], row[:, 1]) - r_f).max() < 1e-9


def test_modified_flank_is_bridged_to_the_fillet():
    # the helical pinion's flank is relieved and crowned: at its form point it stands
    # 2.4 um (face centre) to 7.4 um (face ends) off the unmodified fillet, which the
    # bridge closes; every fillet point below stays on the envelope (1e-9 mm)
    pair = _pair("ev_reducer_helical_23x67")
    root = cylindrical_fillet_root(pair, cylindrical_tooth(pair, "pinion"))
    rack = rack_of(pair, "pinion")
    xi = np.array([-1.0, 0.0, 1.0])
    assert root.bridge_mm("drive", xi) == pytest.approx([7.4e-3, 2.4e-3, 7.4e-3], abs=5e-5)
    for q in (0.2, 0.6, 1.0):
        for p in root.side_points("drive", xi, np.full(3, q)):
            assert abs(envelope_gap_mm(rack, "drive", p)) < 1e-9


@pytest.mark.parametrize("name, member, tol_s, tol_rho", [
    ("spur_20x40_m3", "pinion", 1e-6, 2e-4), ("spur_20x40_m3", "gear", 1e-6, 2e-4),
    ("fzg_c_type", "pinion", 1e-6, 2e-4), ("fzg_c_type", "gear", 1e-6, 2e-4),
    ("ev_reducer_helical_23x67", "pinion", 0.01, 0.05),
    ("ev_reducer_helical_23x67", "gear", 0.01, 0.05)])
def test_iso_6336_3_critical_section(name, member, tol_s, tol_rho):
    pair = _pair(name)
    root = cylindrical_fillet_root(pair, cylindrical_tooth(pair, member))
    s_fn, rho_f = iso_critical_section(pair, member)
    cs = root.critical_section(np.array([0.0]))
    across, down = (a[0] for a in root.section_plane(np.array([0.0])))
    if tol_s < 1e-3:        # spur: exact
        assert cs.thickness_mm[0] == pytest.approx(s_fn, abs=tol_s)
    else:
        assert cs.thickness_mm[0] == pytest.approx(s_fn, rel=tol_s)
    for side in ("coast", "drive"):
        rho = radius_at(root, side, getattr(cs, f"{side}_mm")[0], across, down)
        assert rho == pytest.approx(rho_f, rel=tol_rho)


@pytest.mark.parametrize("name, member", [("spur_20x40_m3", "pinion"), ("fzg_c_type", "gear")])
def test_iso_section_on_the_mesh_vertices(name, member):
    # the side vertices of a fillet zone of 48 layers (structure.root_fillet.mesh_points,
    # the positions build_fe meshes): the 30 deg crossing of the polyline's segment
    # angles, interpolated linearly between segment midpoints
    pair = _pair(name)
    root = cylindrical_fillet_root(pair, cylindrical_tooth(pair, member))
    n = 48
    q = 1.0 - np.arange(n) / n
    nodes = root.mesh_points(np.array([0.0]), q, np.array([1.0, 0.0]), np.array([0.0, 1.0]),
                             1)[0, 1:, 1:3]          # fillet zone, bottom (q = 1) up
    across, down = (a[0] for a in root.section_plane(np.array([0.0])))
    ends = []
    for col in (0, 1):
        p = nodes[:, col]
        t = np.diff(p, axis=0)
        ang = np.degrees(np.arctan2(np.abs(t @ across), -(t @ down)))  # upwards: 90 -> 0
        mid = 0.5 * (p[1:] + p[:-1])
        k = int(np.argmax(ang < 30.0))
        w = (ang[k - 1] - 30.0) / (ang[k - 1] - ang[k])
        ends.append(mid[k - 1] + w * (mid[k] - mid[k - 1]))
    s_fn = abs((ends[1] - ends[0]) @ across)
    assert s_fn == pytest.approx(iso_critical_section(pair, member)[0], rel=2e-4)


@pytest.mark.parametrize("name, member", [("spur_20x40_m3", "pinion"), ("fzg_c_type", "gear")])
def test_shell_fillet_follows_the_real_root(name, member):
    pair = _pair(name)
    tooth = cylindrical_tooth(pair, member)
    root = cylindrical_fillet_root(pair, tooth)
    prof = section_profile(root)
    xi = np.zeros(1)
    across = root.section_plane(xi)[0][0]
    width = float(root_line_section(tooth, xi)[2][0] @ across)
    depth = float(root.critical_section(xi).depth_mm[0])
    got = float(np.interp(depth, prof.depth_mm, prof.widening)) * width
    assert got == pytest.approx(iso_critical_section(pair, member)[0], rel=5e-5)
    d_f, z = getattr(pair.geometry, f"root_diameter_{member}_mm"), getattr(pair, f"{member}_teeth")
    assert prof.rim_widening * width == pytest.approx(d_f * math.sin(math.pi / z), rel=1e-12)
    assert prof.widening[0] == 1.0
    rim = cylindrical_rim(pair, tooth)
    assert rim.profile == prof
    assert rim.fillet_mm == prof.depth_mm[-1] == pytest.approx(float(root.cone_depth_mm(xi)[0]),
                                                               rel=1e-12)


def test_bad_fe_root_is_named_first():
    with pytest.raises(InputRangeError, match="fe_root"):
        cylindrical_flank_compliance(_pair("spur_20x40_m3"), "gear", fe=True, fe_root="real")
    with pytest.raises(InputRangeError, match="member"):
        cylindrical_flank_compliance(_pair("spur_20x40_m3"), "rack")
