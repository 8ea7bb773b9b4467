"""The cylindrical (involute) tooth as a shell body (gearcontact.structure.cylindrical_tooth)
against independent truths.

Truths:
- the plate thickness at the reference circle is the tooth's chordal thickness of
  ISO 21771: transverse arc s_t = m_t (pi/2 + 2 x tan alpha_n), chord d sin(s_t / d),
  times cos(beta) along the mid-surface normal of a helical tooth (exact for spur:
  1e-9 relative; helical 1e-3: the normal section of a helicoid is not a straight
  chord, measured 5e-4);
- shell vs the 3D FE of the same tooth on its real root (the trochoids its generating
  rack cuts, structure.cylindrical_tooth.cylindrical_fillet_root; scikit-fem, P2), under
  distributed loads (segment and line loads at a 3 x 3 flank lattice, deflection of the
  back-flank points; as for bevel members, docs/bending.md sec. 3, 9 and 10), default
  mesh 12 x 6 x 3 + 4 with 3 fillet layers and 2 slot cells, the shell's fillet
  following the real root's section (structure.cylindrical_tooth.section_profile) and
  the calibrated rim factor 1.31: the spur 20/40 pinion within 10 % in the default
  suite (measured 0.940..1.036), all six teeth of the three examples within 15 % (slow;
  measured 0.895..1.112, the FZG C pinion lowest, the spur gear highest; the margins
  cover the FE's mesh convergence, 0.9 %, and a factor moved by a few hundredths;
  docs/bending.md sec. 9);
- the FE tooth compliance converges under mesh refinement (slow): the line load at
  mid-height on the spur pinion moves by < 3 % from the default mesh to 16 x 8 x 4 + 5
  with 4 fillet layers and 3 slot cells (measured +0.9 %), as the bevel real-root
  check (test_root_fillet.py: 10 %);
- bad input names the field.
"""

import math
from pathlib import Path

import numpy as np
import pytest

from gearcontact.geometry.pair import load_pair
from gearcontact.structure.compliance import FeMesh
from gearcontact.structure.cylindrical_compliance import cylindrical_flank_compliance
from gearcontact.structure.cylindrical_tooth import cylindrical_tooth, loaded_side
from gearcontact.validation import InputRangeError

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
TOLERANCE, TOLERANCE_ALL = 0.10, 0.15


def _pair(name):
    return load_pair(EXAMPLES / f"{name}.toml", kinds=("cylindrical",))


@pytest.mark.parametrize("name, rel", [("spur_20x40_m3", 1e-9),
                                       ("ev_reducer_helical_23x67", 1e-3)])
@pytest.mark.parametrize("member", ["pinion", "gear"])
def test_thickness_at_the_reference_circle(name, rel, member):
    p = _pair(name)
    g = p.geometry
    tooth = cylindrical_tooth(p, member)
    d = getattr(g, f"reference_diameter_{member}_mm")
    db = getattr(g, f"base_diameter_{member}_mm")
    lo, hi = tooth.u_span_mm
    eta = 2.0 * (0.5 * math.sqrt(d * d - db * db) - lo) / (hi - lo) - 1.0
    x = getattr(g, f"profile_shift_{member}")
    s_t = g.transverse_module_mm * (0.5 * math.pi
                                    + 2.0 * x * math.tan(math.radians(g.normal_pressure_angle_deg)))
    chord = d * math.sin(s_t / d) * math.cos(math.radians(g.helix_angle_deg))
    assert float(tooth.mid_surface(0.0, eta).thickness_mm) == pytest.approx(chord, rel=rel)


def test_loaded_side_and_bad_input():
    assert loaded_side("ccw") == "drive" and loaded_side("cw") == "coast"
    with pytest.raises(InputRangeError, match="facing"):
        loaded_side("up")
    with pytest.raises(InputRangeError, match="member"):
        cylindrical_tooth(_pair("spur_20x40_m3"), "rack")


def _ratios(name, member, mesh=FeMesh()):
    pytest.importorskip("skfem")
    return cylindrical_flank_compliance(_pair(name), member, fe=True, fe_mesh=mesh)


def test_shell_against_fe_on_the_real_root_spur_pinion():
    res = _ratios("spur_20x40_m3", "pinion")
    assert res.fe_root == "cutter" and res.fe_root_note is None
    r = res.ratios()
    assert np.all(np.abs(r - 1.0) < TOLERANCE), r


@pytest.mark.slow
@pytest.mark.parametrize("name", ["spur_20x40_m3", "ev_reducer_helical_23x67", "fzg_c_type"])
@pytest.mark.parametrize("member", ["pinion", "gear"])
def test_shell_against_fe_on_the_real_root(name, member):
    r = _ratios(name, member).ratios()
    assert np.all(np.abs(r - 1.0) < TOLERANCE_ALL), r


@pytest.mark.slow
def test_fe_on_the_real_root_converges():
    line = [float(_ratios("spur_20x40_m3", "pinion", mesh).line_fe_mm_per_n[1])
            for mesh in (FeMesh(12, 6, 3, 4, 3, 2), FeMesh(16, 8, 4, 5, 4, 3))]
    assert line[1] == pytest.approx(line[0], rel=0.03), line
