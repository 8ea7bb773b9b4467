"""The cylindrical twin's line law (twin.line_law, the slice law on the loaded length)
on end-loaded lines against the half-space LCP: the uncrowned spur 20/40 with its gear
axis inclined over the face (issue 26's careless try), whose lines close from one face
end as a wedge (docs/cylindrical.md sec. 7, "End-loaded lines")."""

from dataclasses import replace
from pathlib import Path

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
