"""Gap field of an edge contact: a tangent-plane grid fitted to the touching edge.

At an edge contact (:mod:`.edge_contact`: a flank boundary of one member touching the
other member's surface at ``P0``) the contact region is bounded by the edge: no
pressure acts beyond it (no material). A field in the surface-contact frame
(:func:`.stencil.gap_field`, principal axes of a Hertzian ellipse, centred on ``P0``)
puts half its cells beyond the edge and, with the axes of the edge's equivalent
curvature (:func:`.curvature.relative_curvature`) but the extents of a surface
ellipse, can miss the touch altogether (docs/twin.md, "Edge contact").

This field is built on the edge instead, in the tangent plane of the touched flank
(normal ``n`` = the mating point's normal, out of the gear tooth):

* ``e_s`` along the edge (its tangent projected on the plane), ``e_t = n x e_s``
  pointing into the edge's own flank (``e_s`` turned round if needed, so the frame
  stays right-handed);
* ``s`` nodes ``s_k = (k - side // 2) h_s``, ``h_s = 2 L_s / side``: one node on the
  line through ``P0`` across the edge;
* ``t`` nodes ``t_j = (j + 1/2) h_t`` from the edge into the flank, ``h_t = D / side``
  (``D`` the depth): the edge is the border ``t = 0`` of the first row of cells, so
  the grid holds only flank and its least gap is the separation half a cell inside
  the edge at ``P0``, ``~ m h_t / 2 + (1/2) B_tt (h_t / 2)^2`` (``m`` the inward slope
  of :func:`.edge_contact.inward_slope`, ``B`` the smooth flanks' relative curvature),
  against 0 at ``P0`` itself;
* rows behind the edge: one, so that the edge is a border between flank and off-flank
  cells inside the grid (a contact reaching the edge is seen as an edge contact, not as
  one reaching its field's border), and more where the edge curves behind ``t = 0``
  within ``|s| <= L_s`` (a curved root or tip line), so the flank there is still
  covered (at most ``side // 2``); cells beyond the edge are marked off the flank as
  everywhere;
* a *corner contact* (``frame_name = "edge corner"``): where ``P0`` is also on a second
  boundary -- an end of its own edge, or the other flank's boundary crossing the edge
  there (s0003 coast: the pinion tip edge on the gear's heel boundary) -- the node half a
  cell inside on the line through ``P0`` is off the flank (the second boundary runs
  through it) and the least gap lay one whole cell along the edge, ``~ m_s h_s`` (``m_s``
  the separation's slope along the edge, not 0 at a constrained extreme). The ``s``
  nodes are then shifted by half a cell towards the flank side, ``s_k = (k - side // 2
  +- 1/2) h_s``, so that ``P0`` is a cell corner and the least gap is at most the
  separation at ``(+-h_s / 2, h_t / 2)``, ``~ (m_s h_s + m h_t) / 2``. Where neither
  diagonal node is on both flanks (a corner wedge narrower than a cell's diagonal) the
  grid is left unshifted (still ``"edge corner"``).

References
----------
F. L. Litvin, A. Fuentes, *Gear Geometry and Applied Theory*, 2nd ed., 2004, sec. 15.7.
K. L. Johnson, *Contact Mechanics*, 1985, sec. 5.2 (contact bounded by an edge).
"""

from __future__ import annotations

import numpy as np

from ..geometry.kinematics import MeshKinematics
from ..geometry.surface import Surface
from ..validation import InputRangeError, check_positive
from .edge_contact import edge_directions, edge_parameters, edge_span, is_kink
from .stencil import GapField, gap_at
from .types import MatingPoint

__all__ = ["EDGE_CURVE_SAMPLES", "corner_shift", "edge_frame", "edge_gap_field"]

#: Points along the edge that find how far it curves behind ``t = 0``.
EDGE_CURVE_SAMPLES = 257


def edge_frame(pinion: Surface, gear: Surface, kin: MeshKinematics,
               mp: MatingPoint) -> np.ndarray:
    """Columns ``(e_s, e_t, n)`` of the edge frame at an edge contact (module
    docstring)."""
    if not mp.edge_contact:
        raise InputRangeError("mp.edge_contact", mp.edge_contact, "an edge label "
                              "(an edge contact of tca.edge_contact)")
    along, inward, _ = edge_directions(pinion, gear, kin, mp)
    n = np.asarray(mp.normal, float) / np.linalg.norm(mp.normal)
    e_s = along - (along @ n) * n
    e_s /= np.linalg.norm(e_s)
    e_t = np.cross(n, e_s)
    if e_t @ inward < 0.0:
        e_s, e_t = -e_s, -e_t
    return np.column_stack([e_s, e_t, n])


def _rows_behind(pinion, gear, kin, mp, axes, half_length: float, h_t: float,
                 side: int) -> int:
    """Rows behind ``t = 0``: one, and those covering the flank where the edge
    curves back; half the grid at a kink line (a ridge: the flank on both sides)."""
    member, _, name = mp.edge_contact.partition(" ")
    own = pinion if member == "pinion" else gear
    if is_kink(own, name):
        return side // 2
    rot, c = kin.pinion_pose(mp.phi1_rad) if member == "pinion" else kin.gear_pose(mp.phi2_rad)
    lo, hi = edge_span(own, name)
    pts = np.array([rot @ own.point(*edge_parameters(own, name, s)).r + c
                    for s in np.linspace(lo, hi, EDGE_CURVE_SAMPLES)])
    st = (pts - np.asarray(mp.point_mm, float)) @ axes[:, :2]
    inside = np.abs(st[:, 0]) <= half_length
    t_lo = float(st[inside, 1].min()) if inside.any() else 0.0
    return int(min(max(np.ceil(-t_lo / h_t), 1), side // 2))


def edge_gap_field(pinion: Surface, gear: Surface, kin: MeshKinematics, mp: MatingPoint,
                   *, half_length_mm: float, depth_mm: float, side: int = 40,
                   allow_outside: bool = False) -> GapField:
    """Gap on a grid fitted to an edge contact (module docstring).

    Parameters
    ----------
    pinion, gear : Surface
        The flanks.
    kin : MeshKinematics
        Kinematics (poses at ``mp.phi1_rad``, ``mp.phi2_rad``).
    mp : MatingPoint
        An edge contact (``mp.edge_contact`` names the edge).
    half_length_mm : float
        Half extent ``L_s`` along the edge, mm (> 0).
    depth_mm : float
        Extent ``D`` from the edge into its flank, mm (> 0).
    side : int
        Nodes along the edge and rows from the edge into the flank (>= 4).
    allow_outside : bool
        As :func:`.stencil.gap_at` (``on_flank`` records the flank either way).

    Returns
    -------
    GapField
        ``frame_name = "edge"`` (``"edge corner"`` at a corner contact, module
        docstring); rows (``t``) from the edge (or from behind it where it curves back)
        into the flank, columns along the edge.
    """
    ls = check_positive("half_length_mm", half_length_mm)
    depth = check_positive("depth_mm", depth_mm)
    if int(side) != side or side < 4:
        raise InputRangeError("side", side, "an integer >= 4")
    side = int(side)
    axes = edge_frame(pinion, gear, kin, mp)
    h_s, h_t = 2.0 * ls / side, depth / side
    back = _rows_behind(pinion, gear, kin, mp, axes, ls, h_t, side)
    shift = corner_shift(pinion, gear, kin, mp, axes, h_s, h_t)
    s_axis = (np.arange(side) - side // 2 + (shift or 0.0)) * h_s
    t_axis = (np.arange(side + back) - back + 0.5) * h_t
    s, t = np.meshgrid(s_axis, t_axis)
    return gap_at(pinion, gear, kin, mp, s, t, frame="edge" if shift is None else "edge corner",
                  axes=axes, allow_outside=allow_outside)


def corner_shift(pinion: Surface, gear: Surface, kin: MeshKinematics, mp: MatingPoint,
                 axes: np.ndarray, h_s: float, h_t: float) -> float | None:
    """Shift of the ``s`` nodes in cells at an edge contact (module docstring): None
    if the node half a cell inside on the line through ``P0`` is on both flanks (no
    corner); else ``+1/2`` or ``-1/2`` towards the diagonal node on both flanks, 0 if
    neither is (a wedge narrower than a cell's diagonal)."""
    probe = gap_at(pinion, gear, kin, mp, np.array([0.0, 0.5 * h_s, -0.5 * h_s]),
                   np.full(3, 0.5 * h_t), frame="edge", axes=axes, allow_outside=True)
    on = probe.on_flank
    if on[0]:
        return None
    return 0.5 if on[1] else -0.5 if on[2] else 0.0
