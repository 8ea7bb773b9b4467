"""A gear flank cut from machine settings against a reference gear sheet at the
reference's exact envelope nodes on the face, shared by the ``--machine-settings`` tests
of generated gears (tests/geometry/test_gear_generation.py, test_basic_settings.py)."""

import numpy as np


def face_node_arc_mm(cut, ref) -> np.ndarray:
    """``cut``'s angular departure from the ``ref`` sheet's nodes inside its boundary
    (the face and active profile), as arc length at the node radius, mm."""
    b = ref.boundary
    iu = (ref.u_nodes >= b.u_root) & (ref.u_nodes <= b.u_tip)
    iv = (ref.v_nodes >= b.v_toe) & (ref.v_nodes <= b.v_heel)
    U, V = np.meshgrid(ref.u_nodes[iu], ref.v_nodes[iv], indexing="ij")
    return (cut.psi(U, V) - ref.psi_nodes[np.ix_(iu, iv)]) * cut.cone.radius_mm(U, V)
