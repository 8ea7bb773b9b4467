"""The bent cylindrical twin's first mesh resonance against ISO 6336-1's resonance speed
n_E1 of the same pair (issue 26, "Independent truths": the dynamic factor's reference).

Truth: ISO 6336-1:2006 clause 6.5.3, n_E1 = 30 000/(pi z1) sqrt(c_gamma_alpha / m_red)
with Method B's mesh stiffness c_gamma_alpha and the reduced mass of the pair
(:func:`gearcontact.analytic.iso6336.resonance_speed_rpm`, checked against the standard's
formulas in tests/analytic/test_iso6336.py). Tolerance: the standard's own, its main
resonance range N_S < N <= 1.15 (N = n1 / n_E1; N_S = 0.85 for K_A F_t / b >= 100 N/mm;
ISO 6336-1 clause 6.5: the real resonance may lie above or below n_E1 by what the
formula leaves out -- shafts, bearings, housing, damping), not fitted to the result. The twin compared is the one whose mesh is the
standard's kind of tooth: contact with the shell bending of both teeth (``--bending``);
the rigid-tooth twin's mode lies about sqrt(2) higher (tests/twin/test_cylindrical.py).
The EV example at T2 = 300 N·m (F_t / b = 134 N/mm, inside Method B's >= 100 N/mm),
the table backend on 7 phases (the twin's linearised chain; measured session 19:
17,704 rpm against n_E1 = 18,651 rpm, N = 0.949; rigid teeth 25,644 rpm, N = 1.375).
"""

from pathlib import Path

from gearcontact.analytic.iso6336 import resonance_speed_rpm
from gearcontact.geometry.pair import load_pair
from gearcontact.report.cylindrical_lte import iso_method_b, iso_reduced_mass_kg_per_mm
from gearcontact.twin.cylindrical import cylindrical_model
from gearcontact.twin.statics import linearized_modes

EV = Path(__file__).resolve().parents[2] / "examples" / "ev_reducer_helical_23x67.toml"
TORQUE_NM = 300.0


def test_bent_twin_mesh_mode_in_the_iso_resonance_range():
    pair = load_pair(EV, kinds=("cylindrical",))
    iso = iso_method_b(pair)
    m_red = iso_reduced_mass_kg_per_mm(pair)
    n_e1 = resonance_speed_rpm(pinion_teeth=pair.pinion_teeth,
                               c_gamma_n_per_mm_um=iso.c_gamma_alpha_n_per_mm_um,
                               reduced_mass_kg_per_mm=m_red)
    model = cylindrical_model(pair, torque_nm=TORQUE_NM, phases=7, backend="table",
                              bending=True)
    n_twin = 60.0 * linearized_modes(model)[-1] / pair.pinion_teeth  # the mesh mode
    assert 0.85 < n_twin / n_e1 <= 1.15
