"""Left-hand pairs: the mirror image of the right-hand pair's flanks.

A left-hand pinion (with its right-hand gear) is the mirror image of the right-hand pair
under ``M = diag(1, -1, 1)`` (the plane y = 0 of the meshing frame, which holds both
axes' directions; the pinion axis moves from y = -E to y = +E). The flanks are built for
the right-hand twin and reflected, parameter for parameter:

- gear (:class:`~.formate.FormateFlank`): the blade cone with the reflected cutter frame
  ``(M C, M a, M e1, M e2)``; the closed-form position, derivatives and normal
  (``sigma cos(alpha) e_rho - sin(alpha) a``) are then exactly ``M r``, ``M r_u``, ...,
  ``M n``;
- pinion (:class:`~.sheet.RadialSheet`): ``r = (v, R cos psi, R sin psi)`` reflects to
  the same sheet with ``psi -> pi - psi``; as ``(M a) x (M b) = -M (a x b)``, the normal
  sign flips so that the normal is ``M n``.

Since the second fundamental form ``r_ij . n`` is invariant (``M`` is orthogonal), the
principal curvatures of every flank equal those of the right-hand twin at the same
(u, v); the kinematics mirror with :class:`~.kinematics.MeshKinematics` ``hand="left"``.
:func:`~.flank.build_flanks` assembles the left-hand flank set from these.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from .cutter import CutterPlacement

__all__ = ["MIRROR", "mirror_gear_flank", "mirror_placement", "mirror_sheet",
           "mirror_solution"]

#: The reflection y -> -y of the meshing frame (and of both body frames).
MIRROR = np.diag([1.0, -1.0, 1.0])


def mirror_placement(pl: CutterPlacement) -> CutterPlacement:
    """The reflected cutter frame (``heel_sign`` kept: same blade-angle parameter)."""
    return CutterPlacement(centre_mm=MIRROR @ pl.centre_mm, axis=MIRROR @ pl.axis,
                           e1=MIRROR @ pl.e1, e2=MIRROR @ pl.e2, heel_sign=pl.heel_sign)


def mirror_gear_flank(gear, placement: CutterPlacement):
    """The mirror image of a :class:`~.formate.FormateFlank` (``placement``: the reflected
    cutter frame, :func:`mirror_placement`)."""
    return dataclasses.replace(gear, blade=dataclasses.replace(gear.blade, placement=placement))


def mirror_solution(sol):
    """The mirror image of a :class:`~.conjugate.MeshingSolution`: the parameters
    (h, theta, phi2) are those of the right-hand twin, psi -> pi - psi and every vector
    reflected."""
    return dataclasses.replace(sol, psi_rad=np.pi - sol.psi_rad, x1_mm=sol.x1_mm @ MIRROR,
                               n1=sol.n1 @ MIRROR, x_f_mm=sol.x_f_mm @ MIRROR,
                               n_f=sol.n_f @ MIRROR)


def mirror_sheet(sheet):
    """The mirror image of a pinion :class:`~.sheet.RadialSheet` (or a subclass):
    ``psi -> pi - psi``, normal sign flipped.

    A :class:`~.conjugate.ConjugateFlank` keeps its right-hand twin's solver; its node
    solutions are reflected (:func:`mirror_solution`) and so are those of its
    ``exact`` method (flag ``mirrored``).
    """
    extra = {}
    if hasattr(sheet, "mirrored"):
        extra = {"nodes": mirror_solution(sheet.nodes), "mirrored": not sheet.mirrored}
    return dataclasses.replace(sheet, psi_nodes=np.pi - sheet.psi_nodes,
                               normal_sign=-sheet.normal_sign, **extra)
