"""The cylindrical (involute) tooth as a shell body (gearcontact.structure.cylindrical_tooth)
against independent truths.

Truths:
- the plate thickness at the reference circle is the tooth's chordal thickness of
  ISO 21771: transverse arc s_t = m_t (pi/2 + 2 x tan alpha_n), chord d sin(s_t / d),
  times cos(beta) along the mid-surface normal of a helical tooth (exact for spur:
  1e-9 relative; helical 1e-3: the normal section of a helicoid is not a straight
  chord, measured 5e-4);
- shell vs the 3D FE of the same tooth with the same rim (scikit-fem, P2), under
  distributed loads (segment and line loads at a 3 x 3 flank lattice, deflection of the
  back-flank points; as for bevel members, docs/bending.md sec. 3 and 9): within 15 %
  on the default mesh 12 x 6 x 3 + 4 (measured with the calibrated rim factor 1.4:
  spur 20/40 pinion 0.94..1.07, gear 0.98..1.08; helical 23/67 pinion 1.00..1.04, gear
  0.97..1.04) and 25 % on the calibration mesh 20 x 8 x 4 + 6 (slow suite; measured
  spur 0.93..1.16, helical 0.96..1.10), the tolerances of the bevel members;
- bad input names the field.
"""

import math
from pathlib import Path

import numpy as np
import pytest

from gearcontact.geometry.pair import load_pair
from gearcontact.structure.compliance import FeMesh, shell_compliance
from gearcontact.structure.cylindrical_tooth import (cylindrical_tooth, cylindrical_tooth_shell,
                                                     loaded_side)
from gearcontact.validation import InputRangeError

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
TOLERANCE, TOLERANCE_FINE = 0.15, 0.25


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


def _ratios(name, member, mesh):
    pytest.importorskip("skfem")
    shell = cylindrical_tooth_shell(_pair(name), member)
    return shell_compliance(shell, fe=True, fe_mesh=mesh).ratios()


@pytest.mark.parametrize("member", ["pinion", "gear"])
def test_shell_against_fe_spur(member):
    r = _ratios("spur_20x40_m3", member, FeMesh())
    assert np.all(np.abs(r - 1.0) < TOLERANCE), r


@pytest.mark.slow
@pytest.mark.parametrize("name", ["spur_20x40_m3", "ev_reducer_helical_23x67"])
@pytest.mark.parametrize("member", ["pinion", "gear"])
def test_shell_against_fe_calibration_mesh(name, member):
    r = _ratios(name, member, FeMesh(20, 8, 4, 6))
    assert np.all(np.abs(r - 1.0) < TOLERANCE_FINE), r


@pytest.mark.slow
@pytest.mark.parametrize("member", ["pinion", "gear"])
def test_shell_against_fe_helical(member):
    r = _ratios("ev_reducer_helical_23x67", member, FeMesh())
    assert np.all(np.abs(r - 1.0) < TOLERANCE), r
