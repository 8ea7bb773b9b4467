"""One tooth of a cylindrical (spur or helical) gear as a plate body, and its shell model
(docs/bending.md sec. 9).

The tooth between the two involute-helicoid flanks of a member
(:func:`~gearcontact.geometry.cylindrical.flank.involute_flank`, body frame: axis z,
the tooth centred on +x at z = 0) is a :class:`~.tooth.ToothGeometry` like a bevel
member's: its "drive" side is the flank facing counter-clockwise, its "coast" side the
one facing clockwise (both bound the same tooth, so no turn; this order makes the
plate frame (axial, normal, towards the tip) right-handed), so a mesh on ``facing``
loads the side :func:`loaded_side` names. ``eta`` is affine in the
roll length ``u`` from the form circle (``eta = -1``) to the tip, ``xi`` in the axial
position over the member's face. At equal (u, z) the two flank points lie at the same
radius, so the mid-surface is the helicoid of the tooth's centre line and the thickness
along its normal the normal chordal tooth thickness.

Below the form circle the shell continues through the fillet and rim segment of
:mod:`.rim`, the rim depth the tooth height (as for bevel members). Its fillet follows
the real root (:func:`cylindrical_fillet_root`: the sides down the trochoidal fillets
the basic rack's tip rounding generates, :mod:`gearcontact.geometry.cylindrical.fillet`,
the slot bottoms on the root circle, the rim block below to the same depth;
:mod:`.root_fillet`), the same geometry the 3D FE meshes (:mod:`.fe`):
:func:`section_profile` tabulates the section's width down the two side curves (along
the thickness direction ``m``, at depths along the down direction ``d``) to the fillet
bottoms, and the root row's width (one pitch of the root circle) below. The shell's
modulus of the fillet and rim is raised by :data:`CYLINDRICAL_RIM_STIFFENING` per
member, calibrated against the 3D FE of the same tooth on its real root.

References
----------
ISO 21771:2007, clauses 4.3-4.4 (involute helicoid), 5 (form circle).
M. Kolivand, A. Kahraman, *Mechanism and Machine Theory* 44(10), 2009, 1848-1865 (the
tooth as a shell over the mid-surface between its flanks).
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np

from ..geometry.cylindrical.fillet import root_fillet
from ..geometry.cylindrical.flank import FACINGS, involute_flank
from ..geometry.cylindrical.pair import CylindricalPair
from ..threads import one_blas_thread
from ..validation import InputRangeError
from .rim import RimSegment, SectionProfile, rim_segment, root_line_section
from .root_fillet import FilletRoot, fillet_root
from .shell import ORDER, ORDER_FACE, ShellModel, build_shell
from .tooth import ToothGeometry

__all__ = ["CYLINDRICAL_RIM_STIFFENING", "cylindrical_tooth", "cylindrical_rim",
           "cylindrical_fillet_root", "cylindrical_tooth_shell", "loaded_side",
           "rack_fillets", "section_profile"]

#: Arc-length samples of each side curve of :func:`section_profile` (the table's rows:
#: dense where the trochoid turns into the root circle and the width grows fastest).
_PROFILE_SAMPLES = 129
#: Cells across each slot bottom of the root row whose width :func:`section_profile`
#: takes below the fillet (its end points alone matter: the slot middles).
_ROW_SLOT = 2

#: Factor on the modulus of the shell's fillet and rim of a cylindrical tooth
#: (:func:`~.rim.rim_modulus_factor`; the fillet following the real root,
#: :func:`section_profile`), calibrated against the 3D FE of the same teeth on their real
#: roots (:func:`cylindrical_fillet_root`; P2, 12 x 6 x 3 + 4 cells, 3 fillet layers, 2
#: slot cells; spur 20/40 m 3, helical 23/67 m 2, FZG C 16/24, both members; segment
#: and line loads at three heights): the one factor minimizing the largest
#: |log(shell / FE)| over the six teeth, shell / FE 0.895 .. 1.112 (docs/bending.md
#: sec. 9; 1.1 with the quarter-ellipse fillet, 0.85 .. 1.17).
CYLINDRICAL_RIM_STIFFENING = {"pinion": 1.31, "gear": 1.31}


def loaded_side(facing: str) -> str:
    """The side of :func:`cylindrical_tooth` a mesh on ``facing`` ("cw" | "ccw",
    :func:`~gearcontact.tca.cylindrical_cycle.cylindrical_mesh_cycle`) loads."""
    if facing not in FACINGS:
        raise InputRangeError("facing", facing, f"one of {FACINGS}")
    return "drive" if facing == "ccw" else "coast"


def cylindrical_tooth(pair: CylindricalPair, member: str) -> ToothGeometry:
    """One tooth of ``member`` ("pinion" | "gear") between its two flanks (module
    docstring: "drive" faces counter-clockwise, "coast" clockwise)."""
    if member not in ("pinion", "gear"):
        raise InputRangeError("member", member, "'pinion' or 'gear'")
    drive = involute_flank(pair, member, "ccw")
    coast = involute_flank(pair, member, "cw")
    span = (max(drive.u_range[0], coast.u_range[0]), min(drive.u_range[1], coast.u_range[1]))
    return ToothGeometry(member=member, drive=drive, coast=coast, coast_turn=np.eye(3),
                         u_span_mm=span, axis=np.array([0.0, 0.0, 1.0]),
                         teeth=int(getattr(pair, f"{member}_teeth")),
                         material=getattr(pair, f"{member}_material"))


def cylindrical_rim(pair: CylindricalPair, tooth: ToothGeometry, *,
                    stiffening: float | None = None) -> RimSegment:
    """The fillet and rim segment below the form circle (module docstring): the widening
    of :func:`section_profile` on the real root, the fillet height its depth;
    ``stiffening`` defaults to the member's :data:`CYLINDRICAL_RIM_STIFFENING` (1: the
    FE's)."""
    g = pair.geometry
    m = tooth.member
    if not getattr(g, f"form_diameter_{m}_mm") > getattr(g, f"root_diameter_{m}_mm"):
        raise InputRangeError(f"{m} form diameter (mm)", getattr(g, f"form_diameter_{m}_mm"),
                              "above the root diameter (a root fillet)")
    k = CYLINDRICAL_RIM_STIFFENING[m] if stiffening is None else stiffening
    return rim_segment(tooth, stiffening=k,
                       profile=section_profile(cylindrical_fillet_root(pair, tooth)))


def section_profile(root: FilletRoot) -> SectionProfile:
    """The shell's widening (:class:`~.rim.SectionProfile`) of the real root ``root``: at
    the face centre, the width along the thickness direction ``m``
    (:meth:`~.root_fillet.FilletRoot.section_plane`) between the two side curves at each
    depth along ``d`` below the root line's centre, over the root line's width, down to
    the fillet bottoms (:meth:`~.root_fillet.FilletRoot.cone_depth_mm`: the fillet
    height), then the root row's width (slot middle to slot middle) below. A cylindrical
    tooth's sections are one screw motion apart along the face, so one table serves
    every face position."""
    xi = np.zeros(1)
    centre, _, chord, _ = root_line_section(root.tooth, xi)
    across, down = (a[0] for a in root.section_plane(xi))
    q = np.linspace(0.0, 1.0, _PROFILE_SAMPLES)
    depth, lateral = {}, {}
    for side in ("coast", "drive"):
        rel = root.side_points(side, np.zeros_like(q), q) - centre[0]
        depth[side], lateral[side] = rel @ down, rel @ across
        if np.any(np.diff(depth[side]) <= 0.0):
            raise InputRangeError(f"{root.tooth.member} {side} root side curve's depth",
                                  "not increasing", "a side curve descending to the root "
                                  "circle (no fillet rising again)")
    bottom = float(root.cone_depth_mm(xi)[0])
    s = np.unique(np.concatenate([depth["coast"], depth["drive"]]))
    s = s[(s > 0.0) & (s < bottom)]
    s = np.concatenate([[0.0], s, [bottom]])
    width = (np.interp(s, depth["drive"], lateral["drive"])
             - np.interp(s, depth["coast"], lateral["coast"]))
    root_width = float(chord[0] @ across)
    row = root.root_row(xi, _ROW_SLOT)[0]
    return SectionProfile(depth_mm=tuple(s.tolist()),
                          widening=tuple((width / root_width).tolist()),
                          rim_widening=float((row[-1] - row[0]) @ across / root_width))


@lru_cache(maxsize=8)
def cylindrical_tooth_shell(pair: CylindricalPair, member: str, *, order: int = ORDER,
                            order_face: int = ORDER_FACE, stiffening: float | None = None
                            ) -> ShellModel:
    """The shell model (:func:`~.shell.build_shell`) of one tooth of ``member`` with its
    calibrated fillet and rim, cached per pair, member and options (the pair is a frozen
    dataclass: hashed by value; both flanks share the model)."""
    tooth = cylindrical_tooth(pair, member)
    rim = cylindrical_rim(pair, tooth, stiffening=stiffening)
    with one_blas_thread():       # threaded BLAS of these sizes spins on a busy machine
        return build_shell(tooth, order=order, order_face=order_face, rim=rim)


def cylindrical_fillet_root(pair: CylindricalPair, tooth: ToothGeometry, *,
                            depth_mm: float | None = None) -> FilletRoot:
    """The real root of ``tooth`` (:func:`cylindrical_tooth`): its sides run from the form
    circle down the trochoidal fillets of its two flanks
    (:func:`~gearcontact.geometry.cylindrical.fillet.root_fillet`: "drive" the
    counter-clockwise facing one, "coast" the clockwise) to the root circle, the slot
    bottoms beside them on the root circle span one pitch, the rim block below reaches
    ``depth_mm`` below the root line (default the tooth height, the shell's rim depth).
    A modified flank (relief, crowning) stands micrometres off the unmodified fillet at
    the form circle: :class:`~.root_fillet.FilletRoot` bridges the gap."""
    return fillet_root(tooth, rack_fillets(pair, tooth.member), depth_mm=depth_mm)


def rack_fillets(pair: CylindricalPair, member: str) -> dict:
    """``side -> RootFillet`` of the tooth of ``member`` (the sides of
    :func:`cylindrical_tooth`)."""
    return {side: root_fillet(pair, member, facing)
            for side, facing in (("drive", "ccw"), ("coast", "cw"))}
