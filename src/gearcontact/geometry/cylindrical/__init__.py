"""Cylindrical (spur and helical) involute pairs: the ``kind = "cylindrical"`` pair
format, the ISO 21771 geometry, the involute-helicoid flanks with micro-geometry and
the trochoidal root fillet (docs/cylindrical.md).

Data flow: :func:`~.pair.parse_cylindrical_pair` -> :class:`~.pair.CylindricalPair`
-> ``.geometry`` (:func:`~.iso21771.involute_geometry`) -> :func:`~.flank.involute_flank`
(a :class:`~gearcontact.geometry.surface.Surface`) and :func:`~.fillet.root_fillet`;
:class:`~.kinematics.ParallelKinematics` poses the pair for the TCA solvers.
"""

from .iso21771 import InvoluteGeometry, inv, inv_inverse, involute_geometry
from .pair import CylindricalPair, MeshAlignment, ToothModifications, parse_cylindrical_pair

__all__ = ["CylindricalPair", "InvoluteGeometry", "MeshAlignment", "ToothModifications",
           "inv", "inv_inverse", "involute_geometry", "parse_cylindrical_pair"]
