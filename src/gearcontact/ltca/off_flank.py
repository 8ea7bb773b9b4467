"""The law of a contact whose field lies wholly off the flank: the edge contact at its
searched touch (the twin's mesh-table rows, :mod:`gearcontact.twin.mesh`, and the loaded
TE's preview ``TE_pre``, :mod:`.edge_rows`).

A pair far past its path's end has its field posed around its nearest interior state;
where no node of that field lies on both flanks (s0003 coast's pair +1 at 3-4 of 31-61
phases, within the mesh's reach since session 24) its opening is the touch of the posed
flanks over the whole flank (:func:`gearcontact.ltca.patch_field.touch_search`), which
lies on a boundary of one member's flank: an edge (a tip edge, a flank end) touching the
other member's flank. That is not the elliptic Hertz contact of the pair's nearest
surface contact, whose curvatures the row carries: the edge bounds the contact region
(no pressure beyond it) and the surfaces recede from it with their inward slope. The
row's law is therefore the one the mesh table gives the TCA's edge rows
(:func:`gearcontact.ltca.edge_law.edge_compliance`: the half-space LCP of the posed
flanks at ``T/16, T/4, T`` over the row's lever, on fields fitted to its patch, from
the row's opening, the searched touch (:func:`gearcontact.ltca.edge_law.edge_datum_mm`),
against the Hamrock–Brewe approach of the row's curvatures), on
a field placed at the touch instead of the row's own: :class:`TouchField`, a square of
the row's frame (origin, axes and posed point of its field, so the gap is the same
function of the same plane point: its least value is the touch) centred on the flank
region's border sample nearest to contact (:func:`touch_point`), ``cells`` cells per
side, half-side :data:`TOUCH_FIELD_HALF` times the larger Hertzian semi-axis of the row's
curvatures under the whole torque, then fitted to the box of its flank cells widened by
a cell (the flank region near such a touch is a sliver: s0003 coast's 36-51 of the
square's 1,600 cells, where the LCP found 1-2 contact cells); the patch fitting of
:func:`gearcontact.ltca.patch_field.patch_approach` then shrinks or widens it to the
patch.

Bending: the work-conjugate compliance (:func:`gearcontact.ltca.tooth_bending.
conjugate_compliance`, the structure layer's factor at the field's cells, as every row
takes it) of the LCP's own pressure under the whole torque on the touch field
(:func:`touch_bending_compliance`) instead of the Hertzian ellipse centred on the row's
field, which has no flank cell.

Where the LCP of the calibration fails at a load on that field (the patch on a single
cell: s0003 coast's phase 3 at ``T/16``), the calibration runs again on the same square
with :data:`TOUCH_REFINE` times the cells per side (the fields fitted to the patch keep
the table's cells) and takes that law if it converges at more loads. Below the least
calibration load the law follows a corner's approach ``delta ~ W^(1/2)``
(:data:`CORNER_EXPONENT`, :attr:`~gearcontact.ltca.edge_law.EdgeCompliance.
low_exponent`) where the LCP's local exponent between its two least loads is nearer
1/2 than 2/3 (:func:`corner_law`): the flank region's corner, where the gap rises
linearly in every direction of its wedge (a gap of degree ``d`` gives ``delta ~
W^(d/(d+1))``; Johnson 1985 sec. 5.2).

What the law keeps from the row: its lever and the normal of its field's plane (the
nearest interior state's), as every posed-field row (docs/twin.md "Rows wholly off the
flank: the edge law at the touch").
"""

from __future__ import annotations

from dataclasses import replace
from types import SimpleNamespace

import numpy as np

from ..analytic.hertz import hamrock_brewe_hertz
from ..halfspace.lcp import solve_lcp
from .edge_law import EDGE_LOAD_FRACTIONS, EdgeCompliance, edge_compliance
from .flank_touch import edge_samples, flank_gaps_mm
from .pair_ltca import OFF_FLANK_GAP_MM
from .patch_field import patch_grid
from .tooth_bending import conjugate_compliance

__all__ = ["CORNER_EXPONENT", "TOUCH_FIELD_HALF", "TOUCH_REFINE", "TouchField",
           "corner_law", "is_wholly_off", "touch_point", "touch_field", "touch_law",
           "touch_bending_compliance"]

#: Half-side of a touch field in multiples of the larger Hertzian semi-axis of the row's
#: curvatures under the whole torque (the extent of the loaded TE's fields is 1.6-2 of
#: them; the patch fitting widens a field whose patch reaches its on-flank border).
TOUCH_FIELD_HALF = 2.0
#: Cells per side of the touch field, in multiples of the table's, where the LCP of a
#: calibration load failed on it (a patch on one cell; module docstring).
TOUCH_REFINE = 2
#: The approach's power of the load at a corner as the patch shrinks: a gap rising
#: linearly in every direction of a wedge (degree ``d = 1``), ``d / (d + 1)``.
CORNER_EXPONENT = 0.5


def is_wholly_off(fields, pc) -> bool:
    """The row's field (:class:`~gearcontact.ltca.lte_pairs.PairFields`) has no flank
    cell."""
    return bool(fields.get(pc)[2].all())


def touch_point(fields, pc) -> tuple[float, float, float]:
    """``(s, t, gap)`` (mm, the row's frame): the least-gap sample of the flank region's
    border (:func:`gearcontact.ltca.flank_touch.edge_samples`, the 8 edges of the two
    members' parameter boxes, 64 points each). A row whose field lies wholly off the
    flank touches on that border (its pair is past its path's end: no interior
    minimum), so this is the touch to a sample spacing (measured: docs/twin.md)."""
    _, _, pts = edge_samples(fields, pc)
    flat = np.concatenate(pts)
    g = flank_gaps_mm(fields, pc, flat[:, 0], flat[:, 1])
    i = int(np.argmin(g))
    if not np.isfinite(g[i]):
        raise ArithmeticError(f"off_flank: no border sample of the row at path index "
                              f"{pc.path_index} lies on both flanks")
    return float(flat[i, 0]), float(flat[i, 1]), float(g[i])


class TouchField:
    """The field source of one wholly-off row (module docstring): the attributes of
    :class:`~gearcontact.ltca.lte_pairs.PairFields` that :func:`~gearcontact.ltca.
    edge_law.edge_compliance` and :func:`~gearcontact.ltca.patch_field.patch_approach`
    read (``args``, ``cells``, ``e_prime``, ``frames``, ``points``, ``get``), its field
    a square of the row's frame centred on the touch.

    Parameters
    ----------
    fields : PairFields
        The mesh table's fields (the row's frame and posed point).
    pc : PairContact
        The row, resolved (its opening the searched touch).
    torque_nmm : float
        The table's torque, N·mm (sizes the square).
    refine : int
        Cells per side of the square and its fitted field in multiples of the table's
        ``fields.cells`` (the fields fitted to a patch keep ``fields.cells``).
    """

    def __init__(self, fields, pc, *, torque_nmm: float, refine: int = 1):
        self.args, self.cells, self.e_prime = fields.args, fields.cells, fields.e_prime
        self.frames, self.points, self.bending = fields.frames, fields.points, fields.bending
        self._fields = fields
        lever = fields.get(pc)[3]
        s0, t0, _ = touch_point(fields, pc)
        hz = hamrock_brewe_hertz(pc.A_minus_per_mm, pc.B_minus_per_mm, torque_nmm / lever,
                                 e_prime_mpa=fields.e_prime)
        half = TOUCH_FIELD_HALF * max(hz.a_mm, hz.b_mm)
        box = (s0 - half, s0 + half, t0 - half, t0 + half)
        for _ in range(2):      # the square, then its flank cells' box
            s_axis, t_axis, grid = patch_grid(box, refine * fields.cells)
            s, t = np.meshgrid(s_axis, t_axis)
            gap = flank_gaps_mm(fields, pc, s, t)
            off = ~np.isfinite(gap)
            if off.all():
                raise ArithmeticError(f"off_flank: the touch field of the row at path "
                                      f"index {pc.path_index} has no flank cell")
            h_s, h_t = float(grid.dx_mm[0]), float(grid.dy_mm[0])
            box = (s[~off].min() - 1.5 * h_s, s[~off].max() + 1.5 * h_s,
                   t[~off].min() - 1.5 * h_t, t[~off].max() + 1.5 * h_t)
        self.s_mm, self.t_mm = s, t
        self.field = (np.where(off, OFF_FLANK_GAP_MM, gap), grid, off, lever)

    def get(self, pc):
        """(gap, grid, off-flank mask, lever) of the touch field."""
        return self.field

    def factor(self, pc) -> np.ndarray | None:
        """The bending factor of the teeth at the touch field's cells (None without
        bending): :class:`~gearcontact.ltca.lte_pairs.PairFields`' own map of a field's
        cells onto both flanks."""
        if self.bending is None:
            return None
        f = SimpleNamespace(s_mm=self.s_mm, t_mm=self.t_mm, gap_mm=self.field[0],
                            frame=self.frames[pc.field_key][1])
        return self._fields._bending_factor(f, self.points[pc.field_key])


def touch_field(fields, pc, *, torque_nmm: float) -> TouchField | None:
    """The row's :class:`TouchField`, or None where it has none (no border sample on
    both flanks, no flank cell in the square)."""
    try:
        return TouchField(fields, pc, torque_nmm=torque_nmm)
    except ArithmeticError:
        return None


_UNSET = object()


def touch_law(fields, pc, *, materials, torque_nmm: float,
              touch=_UNSET) -> EdgeCompliance | None:
    """:func:`~gearcontact.ltca.edge_law.edge_compliance` of a wholly-off row on its
    :class:`TouchField` (module docstring; ``touch``: :func:`touch_field`'s, when the
    caller holds it), again on the field :data:`TOUCH_REFINE` times finer where a load
    failed, with :func:`corner_law`'s law below the least calibration load; None where
    it fails (no touch field, an LCP not converged at two loads, a field that does not
    close): the row keeps the Hertzian law, counted uncalibrated as before."""
    tf = touch_field(fields, pc, torque_nmm=torque_nmm) if touch is _UNSET else touch
    if tf is None:
        return None
    law = _calibration(tf, pc, materials, torque_nmm)
    if law is None or law.loads_n.size < len(EDGE_LOAD_FRACTIONS):
        finer = _calibration(TouchField(fields, pc, torque_nmm=torque_nmm,
                                        refine=TOUCH_REFINE), pc, materials, torque_nmm)
        if finer is not None and (law is None or finer.loads_n.size > law.loads_n.size):
            law = finer
    return None if law is None else corner_law(law)


def _calibration(tf, pc, materials, torque_nmm) -> EdgeCompliance | None:
    try:
        return edge_compliance(tf, pc, materials=materials, torque_nmm=torque_nmm)
    except ArithmeticError:
        return None


def corner_law(law: EdgeCompliance) -> EdgeCompliance:
    """``law`` with the corner's asymptote below its least calibration load
    (``low_exponent`` = :data:`CORNER_EXPONENT`) where the LCP's local exponent between
    its two least loads is nearer 1/2 than 2/3 (module docstring), else ``law``."""
    corner = abs(law.low_local_exponent - CORNER_EXPONENT) < abs(law.low_local_exponent
                                                                 - 2.0 / 3.0)
    return replace(law, low_exponent=CORNER_EXPONENT) if corner else law


def touch_bending_compliance(fields, pc, *, materials, torque_nmm: float,
                             touch=_UNSET) -> float:
    """Bending compliance (mm/N) of a wholly-off row's teeth: the work-conjugate
    compliance of the LCP's pressure of the pair carrying ``torque_nmm`` alone on its
    :class:`TouchField` (module docstring; ``touch`` as in :func:`touch_law`); where
    that LCP does not converge, the pressure of the largest calibration load
    (:data:`~gearcontact.ltca.edge_law.EDGE_LOAD_FRACTIONS`) whose LCP does; 0 where
    none does (no founded pressure shape; the row is then uncalibrated as well)."""
    tf = touch_field(fields, pc, torque_nmm=torque_nmm) if touch is _UNSET else touch
    if tf is None:
        return 0.0
    gap, grid, _, lever = tf.field
    for fraction in sorted(EDGE_LOAD_FRACTIONS, reverse=True):
        res = solve_lcp(gap, grid, fraction * torque_nmm / lever, materials=materials,
                        warn_coarse=False)
        if res.converged:
            return conjugate_compliance(tf.factor(pc), res.loads_n)
    return 0.0
