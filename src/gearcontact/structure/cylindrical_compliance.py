"""Flank compliance of a cylindrical tooth: its shell beside the 3D FE on its real root
(``gearcontact bending`` on a cylindrical pair; docs/bending.md sec. 9).

The shell is :func:`~.cylindrical_tooth.cylindrical_tooth_shell`; the FE
(:mod:`.fe`) meshes the tooth on the root the generating rack cuts
(:func:`~.cylindrical_tooth.cylindrical_fillet_root`) or, on request, on the
quarter-ellipse root of :mod:`.rim`; loads and compared deflections are those of
:mod:`.compliance` (one path with the bevel members: :func:`~.compliance.compare_on_root`).
"""

from __future__ import annotations

from ..geometry.cylindrical.pair import CylindricalPair
from .compliance import FeMesh, FlankCompliance, check_member_and_root, compare_on_root
from .cylindrical_tooth import cylindrical_tooth_shell, rack_fillets
from .shell import ORDER, ORDER_FACE

__all__ = ["cylindrical_flank_compliance"]


def cylindrical_flank_compliance(pair: CylindricalPair, member: str, *, side: str = "drive",
                                 xi=(-0.5, 0.0, 0.5), eta=(-1 / 3, 0.0, 1 / 3),
                                 order: int = ORDER, order_face: int = ORDER_FACE,
                                 stiffening: float | None = None, fe: bool = False,
                                 fe_mesh: FeMesh = FeMesh(), fe_root: str = "cutter"
                                 ) -> FlankCompliance:
    """:func:`~.compliance.flank_compliance` of one cylindrical tooth of ``member``: the
    shell of :func:`~.cylindrical_tooth.cylindrical_tooth_shell` (``stiffening`` as
    there) at the lattice ``xi x eta`` of its flank ``side`` ("drive": the
    counter-clockwise facing one, :func:`~.cylindrical_tooth.loaded_side`), with the 3D
    FE (``fe``) on the real root (``fe_root="cutter"``, the default:
    :func:`~.cylindrical_tooth.cylindrical_fillet_root`) or on the quarter-ellipse root
    of :mod:`.rim` (``"ellipse"``); the result's ``fe_root`` names the root meshed
    (docs/bending.md sec. 9)."""
    check_member_and_root(member, fe_root)
    shell = cylindrical_tooth_shell(pair, member, order=order, order_face=order_face,
                                    stiffening=stiffening)
    return compare_on_root(shell, lambda: (rack_fillets(pair, member), None), name=pair.name,
                           side=side, xi=xi, eta=eta, fe=fe, fe_mesh=fe_mesh, fe_root=fe_root)
