"""The cylindrical twin's line law (twin.line_law, the slice law on the loaded length)
on end-loaded lines against the half-space LCP and the closed form of the finite line:
the spur 20/40 with its gear axis inclined over the face (issue 26's careless try),
whose lines close from one face end as a wedge (docs/cylindrical.md sec. 7,
"End-loaded lines"), uncrowned and with lead crowning."""

import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from gearcontact.geometry.cylindrical.pair import MeshAlignment
from gearcontact.geometry.pair import load_pair
from gearcontact.ltca.cylindrical_lte import cylindrical_loaded_te
from gearcontact.tca.cylindrical_cycle import cylindrical_mesh_cycle
from gearcontact.tca.types import ARCSEC_PER_RAD
from gearcontact.twin.cylindrical import cylindrical_mesh_table
from gearcontact.twin.params import default_drivetrain
from gearcontact.twin.simulate import build_model

from .test_line_law import _pitch_point_rotation

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
TORQUE_NM = 64.5


@pytest.mark.parametrize("incl_um", [100.0, 300.0])
def test_end_loaded_pitch_point_rotation_against_the_lcp(incl_um):
    """Single contact at the pitch point (the 3-phase cycle's middle row), rigid teeth:
    the rotation at which the fp64 twin's law carries T2 = 64.5 N·m (bisection on its
    elastic torque) against the rigid loaded TE's |TE - TE0| (the LCP on the strip that
    the end-loaded line needs, 64 rows). The law's loaded length is the closed form's
    (11-17 % above the LCP's) and its 16 slices hold the end half-slice flat, yet its
    approach is the finite line's energy mean, which the LCP's approach follows within
    1.4 % (tests/ltca/test_cylindrical_lte.py): bound LCP / twin within 4 % (measured
    0.988 / 0.979 at 100 / 300 um; the aligned line's 1.033 is the finite cylinder's
    sharp ends, tests/twin/test_line_law.py)."""
    pair = load_pair(EXAMPLES / "spur_20x40_m3.toml", kinds=("cylindrical",))
    pair = replace(pair, assembly=MeshAlignment(axis_inclination_um=incl_um))
    cycle = cylindrical_mesh_cycle(pair, phases=3)
    model = build_model(cylindrical_mesh_table(pair, cycle), default_drivetrain(pair),
                        TORQUE_NM, backend="reference", curvatures="line")
    hi = _pitch_point_rotation(model, TORQUE_NM)
    lte = cylindrical_loaded_te(pair, TORQUE_NM, cycle=cycle, cells_along=64, bending=False)
    assert lte.line_end_loaded[:, 1].any() and not lte.edge_touch
    want = abs(lte.te0_arcsec[1] - lte.lte_arcsec[1]) / ARCSEC_PER_RAD
    assert want / hi == pytest.approx(1.0, abs=0.04)


@pytest.mark.parametrize("crowning_um, incl_um", [(0.0, 300.0), (30.0, 100.0)])
def test_pitch_point_peak_pressure(crowning_um, incl_um):
    """The twin's p_max (the line chain on L_eq = W / w_peak, twin.line_law) at the
    pitch point's static rotation (single contact, rigid teeth, 64.5 N·m), fp64 and
    golden:

    * uncrowned, 300 um: against the closed form's Hertz pressure of its peak line load
      2 W / L_c (analytic.face_load.end_loaded_line on the projected slope, exact A-),
      within the square root of the 16-slice bound on the peak of
      tests/ltca/test_cylindrical_preview.py (-1 % .. +1 % + the length's bound);
      the twin's a is L_c / 2 within that test's length bound (measured: p_max 2053.0
      MPa against 2048.7, L_c 3.033 against 2.931 mm); before, the twin reported the
      uniform load over L_c, 1424 MPa, 0.70 of it;
    * 30 um crowning, 100 um (the load centred): against the rigid LCP's p_max (128
      rows), 1.0-1.07 (measured 1081.6 against 1037.8 MPa, 1.042 as in the preview: the
      half-space's shorter loaded length, tests/ltca/test_cylindrical_preview.py;
      before, 843 MPa, 0.78);
    * golden against fp64 within the fit's coefficient bound at half weight plus one
      PMAX LSB (as tests/ltca/test_cylindrical_preview.py).
    """
    from gearcontact.analytic.face_load import end_loaded_line
    from gearcontact.analytic.hertz import line_contact_terms
    from gearcontact.geometry.cylindrical.pair import ToothModifications
    from gearcontact.halfspace.lcp import resolve_e_star
    from gearcontact.preview.fit.pinv import coefficient_error_bound
    from gearcontact.twin.layout import N_CACHE
    from gearcontact.twin.model import _prm
    from gearcontact.twin.statics import _elastic

    pair = load_pair(EXAMPLES / "spur_20x40_m3.toml", kinds=("cylindrical",))
    pair = replace(pair, assembly=MeshAlignment(axis_inclination_um=incl_um),
                   modifications_pinion=ToothModifications(lead_crowning_um=crowning_um))
    cycle = cylindrical_mesh_cycle(pair, phases=3)
    mesh = cylindrical_mesh_table(pair, cycle)
    p_max, a_mm = {}, {}
    for backend in ("reference", "golden"):
        model = build_model(mesh, default_drivetrain(pair), TORQUE_NM, backend=backend,
                            curvatures="line")
        theta = _pitch_point_rotation(model, TORQUE_NM)
        cache = np.full((2, mesh.valid.shape[0], N_CACHE), -1.0)
        w_fn = 1e3 * TORQUE_NM / mesh.reference_lever_mm
        _, w = _elastic(model, _prm(model, 0.0), theta, mesh.psi_rad[1],
                        w_eval=np.full(3, w_fn), cache=cache)
        j = int(np.argmax(w))
        assert w[j] == pytest.approx(w_fn, rel=1e-6)
        p_max[backend], a_mm[backend] = cache[0, j, 4], cache[0, j, 2]
    c = coefficient_error_bound(mesh.stencil_gaps_mm[j, 1])
    assert abs(p_max["golden"] - p_max["reference"]) <= 0.5 * (c[3] + c[5] + c[4] / 2) / \
        mesh.A_minus_per_mm[j, 1] * p_max["reference"] + 2.0 ** -8
    g = pair.geometry
    if crowning_um == 0.0:
        e_prime = 2.0 * resolve_e_star((pair.pinion_material, pair.gear_material))
        length, b_max = float(mesh.line_length_mm[j, 1]), float(mesh.A_minus_per_mm[j, 1])
        truth = end_loaded_line(
            load_n=w_fn, slope=incl_um * 1e-3 * math.sin(math.radians(
                g.working_pressure_angle_deg)) / g.face_width_mm,
            length_mm=length, b_max_per_mm=b_max, e_prime_mpa=e_prime)
        l_c0 = truth.loaded_length_mm
        _, b = line_contact_terms(b_max, w_fn, l_c0, e_prime)
        g0 = math.log(4.0 * l_c0 / b) - 0.75
        bound = (length / 16) ** 2 / (8.0 * l_c0 * (1.0 - 0.75 / g0)) + 0.01 * l_c0
        ratio = p_max["reference"] / truth.hertz_pressure_mpa
        assert math.sqrt(0.99) - 1e-6 <= ratio <= math.sqrt(1.01 + bound / l_c0) + 1e-6
        assert 0.0 <= 2.0 * a_mm["reference"] - l_c0 <= bound
    else:
        lte = cylindrical_loaded_te(pair, TORQUE_NM, cycle=cycle, cells_along=128,
                                    bending=False)
        assert not lte.line_end_loaded[j, 1] and not lte.edge_touch
        assert 1.0 < lte.line_pressure_mpa[j, 1].max() / p_max["reference"] < 1.07
