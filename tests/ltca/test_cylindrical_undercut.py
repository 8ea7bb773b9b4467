"""The loaded TE with tooth bending on an undercut pinion (12/40 spur m 3, x = 0 < x_min
= 0.298: its involute starts at the trochoid's crossing, its path at d_Ff) against
ISO 6336-1 Method B.

Truth: the same test as the standard 20/40 pair's (tests/ltca/test_cylindrical_lte.py,
test_mesh_stiffness_with_bending_against_iso_6336: T2 = 400 N·m, 333 N/mm at d2, 21
phases): the single-contact stiffness and the mean within 1.0-1.3 x c' and c_gamma_alpha
(Method B, C_M = 0.8; the band the standard pair is held to, not chosen for this one;
measured 1.21 and 1.24 against the 20/40 pair's 1.11 and 1.15: the undercut tooth is
stiffer than Method B's, whose q' polynomial knows nothing of the undercut). Slow: the
cycle and the bending LCP take ~9 s.
"""

import numpy as np
import pytest

from gearcontact.analytic.iso6336 import cylindrical_pair_stiffness
from gearcontact.geometry.cylindrical.pair import CylindricalPair
from gearcontact.ltca.cylindrical_lte import cylindrical_loaded_te
from gearcontact.tca.cylindrical_cycle import cylindrical_mesh_cycle


@pytest.mark.slow
def test_mesh_stiffness_of_the_undercut_pair_against_iso_6336():
    pair = CylindricalPair(name="undercut_12x40", pinion_teeth=12, gear_teeth=40,
                           normal_module_mm=3.0, pinion_face_width_mm=20.0,
                           gear_face_width_mm=20.0)
    g = pair.geometry
    assert g.undercut_pinion
    r = cylindrical_loaded_te(pair, 400.0, cycle=cylindrical_mesh_cycle(pair, phases=21))
    assert r.bending and r.converged and not r.edge_touch
    iso = cylindrical_pair_stiffness(pinion_teeth=12, gear_teeth=40, helix_angle_deg=0.0,
                                     base_helix_angle_deg=0.0,
                                     transverse_contact_ratio=g.transverse_contact_ratio)
    single = r.stiffness_n_per_mm_um[np.count_nonzero(r.load_share, axis=0) == 1]
    assert single.size > 0
    assert 1.0 < single.mean() / iso.c_n_per_mm_um < 1.3
    assert 1.0 < r.mean_stiffness_n_per_mm_um / iso.c_gamma_alpha_n_per_mm_um < 1.3
