"""The real root of a cut tooth: its sides down the cutter's root fillets, the slot bottoms
beside it and the rim block below, for the 3D finite elements (:mod:`.fe`).

Where a member's cutter is known (:func:`gearcontact.geometry.fillet.pair_fillets`:
machine settings, the formate gear of a ``[cutter]``), the solid below a tooth's root
line (:mod:`.tooth`: ``eta = -1``, the lowest height both flanks cover) is bounded by
surfaces the cutter made, not by the quarter-ellipse approximation of :mod:`.rim`
(``docs/bending.md`` sec. 3 and 10):

- each **side curve** runs, at the face position ``xi`` (the flank's own lengthwise
  parameter ``v``, which the fillet shares), from the tooth's root point down the flank
  to the flank box's lower edge ``u_range[0]``, then to the fillet's top row (the round's
  tangent line; on the generated pinion the flank box of the sheet stops 0.1-0.7 mm
  above it: that strip of the generated flank is bridged by the cubic Hermite curve of
  the two end points and tangents; on the formate gear the two coincide to 1e-14 mm
  and there is no bridge), and down the fillet ``RootFillet.evaluate(u, v)`` from its
  top ``u = u_range[1]`` to its bottom ``u = u_range[0]`` on the root cone (a cutter's
  round: ``(0, s_top)`` mm; the rack-generated trochoid of a cylindrical gear,
  :mod:`gearcontact.geometry.cylindrical.fillet`: ``(-pi/2, -alpha_n)`` rad, its
  bottom on the root cylinder);
- the **slot bottoms**: from the two fillet bottoms ``B_c``, ``B_d`` along the root
  cone (turned about the member axis, which keeps them on the cone) to the slot
  middles, half a slot on each side, so that the root row spans one pitch. Where a
  slot's two fillets (this tooth's and the neighbour's, cut by the two blades) cross
  above the root cone (:meth:`FilletRoot.crossing`: the 7-tooth s0003 pinion at the
  toe) the slot closes in a V: each fillet ends at the crossing, found per axial
  section by a bracketed 1-D solve, the two crossings lie one pitch apart and the
  slot bottom between them has no width (its strip on the root cone goes to zero
  where the V starts; the FE merges its points, :func:`.fe.build_fe`);
- the **rim block**: the root row moved along the tooth's down direction ``d`` at the
  root line (:func:`.rim.root_line_section`) to the clamped bottom, whose centre lies
  ``depth_mm`` below the root line's centre (the depth of :mod:`.rim`'s segment).

The ISO 6336-3 critical section of each face position is where the side curves'
tangent, in the plane of ``d`` and the root chord, makes 30 deg with ``d``
(:meth:`FilletRoot.critical_section`).

References
----------
ISO 6336-3:2019, *Calculation of load capacity of spur and helical gears - Part 3:
Calculation of tooth bending strength*, sec. 6.2 (critical section at the 30 deg
tangent, s_Fn, rho_F).
F. L. Litvin, A. Fuentes, *Gear Geometry and Applied Theory*, 2nd ed., 2004, ch. 20-21
(the fillet of face-milled gears).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import brentq

from ..errors import CheckFailed
from ..validation import InputRangeError
from .rim import root_line_section, tooth_height_mm
from .tooth import ToothGeometry, axis_rotation

__all__ = ["CriticalSection", "FilletRoot", "fillet_root", "ISO_TANGENT_DEG"]

#: Angle between the fillet tangent and the tooth centre line at the critical section
#: (ISO 6336-3 sec. 6.2, external gears), deg.
ISO_TANGENT_DEG = 30.0
#: Samples per piece of a side curve for its arc-length table.
_SAMPLES = 33
#: Step of the fillet parameter of the tangent at the fillet's top row (mm on a cutter's
#: round, rad on a rack-generated trochoid: 1e-5 rad is ~1e-5 mm there).
_DU_MM = 1e-5
#: Bridges shorter than this are not searched for the 30 deg tangent, mm: a modified
#: cylindrical flank (relief, crowning) stands micrometres off the unmodified fillet
#: at its form point (2-7 um on the helical example), and the cubic bridging such a gap
#: turns its tangent through any angle over its few micrometres; the ISO section is the
#: fillet's. The bevel bridges are 0 (formate) or 0.15-0.71 mm (generated pinions).
_BRIDGE_SEARCH_MM = 0.01
#: Tolerance of the crossing of a slot's two fillets: the gap between them at equal
#: radius in the axial section, mm (the fillet points themselves are exact to 1e-10).
_CROSSING_TOL_MM = 1e-12


@dataclass(frozen=True)
class CriticalSection:
    """The 30 deg tangent section of a tooth at face positions ``xi`` (arrays (n,)).

    Attributes
    ----------
    xi : ndarray
    thickness_mm : ndarray
        ``s_Fn``: the chord between the two tangent points, its component along the
        thickness direction ``m`` (:meth:`FilletRoot.section_plane`), mm.
    depth_mm : ndarray
        Depth of the chord's middle below the root line's centre along ``d``, mm.
    coast_mm, drive_mm : ndarray (n, 3)
        The tangent points, body frame, mm.
    """

    xi: np.ndarray
    thickness_mm: np.ndarray
    depth_mm: np.ndarray
    coast_mm: np.ndarray
    drive_mm: np.ndarray


@dataclass(frozen=True, eq=False)
class FilletRoot:
    """The root of ``tooth`` bounded by its cutter's fillets (module docstring).

    Attributes
    ----------
    tooth : ToothGeometry
    fillets : dict
        ``side -> RootFillet`` (:mod:`gearcontact.geometry.fillet`), in the flanks'
        frames (the coast fillet is turned into the tooth as its flank is).
    depth_mm : float
        Depth of the rim's clamped bottom below the root line's centre, mm.
    """

    tooth: ToothGeometry
    fillets: dict
    depth_mm: float
    _ends: dict = field(default_factory=dict, repr=False)   # (side, xi bytes) -> p_end

    # ---------------------------------------------------------------- side curves
    def _pieces(self, side: str, xi: np.ndarray, p: np.ndarray) -> np.ndarray:
        """Side curve points (n, 3) at the piece coordinate ``p`` in [0, 3] (n,): flank
        (0..1), bridge (1..2), fillet (2..3), body frame (coast turned)."""
        tooth, fil = self.tooth, self.fillets[side]
        flank = getattr(tooth, side)
        _, v = tooth.flank_parameters(side, xi, -np.ones_like(xi))
        u_root, u_lo = tooth.u_span_mm[0], flank.u_range[0]
        s_bottom, s_top = fil.u_range
        out = np.empty(xi.shape + (3,))
        a = p <= 1.0
        if np.any(a):
            u = u_root + np.clip(p[a], 0.0, 1.0) * (u_lo - u_root)
            out[a] = flank.evaluate(u, v[a], second=False).r
        c = p >= 2.0
        if np.any(c):
            f = 3.0 - np.clip(p[c], 2.0, 3.0)        # 1 at the fillet's top, 0 at its bottom
            out[c] = fil.evaluate(s_bottom + (s_top - s_bottom) * f, v[c]).r
        b = ~(a | c)
        if np.any(b):
            t = (p[b] - 1.0)[:, None]
            A, TA, B, TB = self._bridge_ends(side, v[b])
            L = np.linalg.norm(B - A, axis=-1, keepdims=True)
            out[b] = ((2 * t ** 3 - 3 * t ** 2 + 1) * A + (t ** 3 - 2 * t ** 2 + t) * L * TA
                      + (-2 * t ** 3 + 3 * t ** 2) * B + (t ** 3 - t ** 2) * L * TB)
        return out @ tooth.coast_turn.T if side == "coast" else out

    def _bridge_ends(self, side: str, v):
        """Ends and unit tangents (down the tooth) of the bridge at ``v``: the flank box's
        lower edge and the fillet's top row, in the flank's frame."""
        flank, fil = getattr(self.tooth, side), self.fillets[side]
        s = flank.evaluate(np.full_like(v, flank.u_range[0]), v, second=False)
        ta = -s.r_u / np.linalg.norm(s.r_u, axis=-1, keepdims=True)
        s_top = fil.u_range[1]
        top = fil.evaluate(np.full_like(v, s_top), v).r
        below = fil.evaluate(np.full_like(v, s_top - _DU_MM), v).r
        tb = (below - top) / np.linalg.norm(below - top, axis=-1, keepdims=True)
        return s.r, ta, top, tb

    def bridge_mm(self, side: str, xi) -> np.ndarray:
        """Length of the chord bridged between the flank box and the fillet (n,), mm."""
        xi = np.atleast_1d(np.asarray(xi, float))
        v = self.tooth.flank_parameters(side, xi, -np.ones_like(xi))[1]
        A, _, B, _ = self._bridge_ends(side, v)
        return np.linalg.norm(B - A, axis=-1)

    def side_points(self, side: str, xi, q) -> np.ndarray:
        """Points (n, 3) of the side curve of ``side`` at face positions ``xi`` (n,) and
        arc-length fractions ``q`` (n,) in [0, 1] (0: the tooth's root point, 1: the
        curve's end: the fillet's bottom on the root cone, or where the slot closes in a
        V, the crossing with the neighbouring tooth's fillet, :meth:`crossing`): exactly
        on the flank, bridge and fillet (the fraction is mapped to the piece coordinate
        through an arc-length table of :data:`_SAMPLES` points per piece)."""
        xi, q = (np.asarray(a, float) for a in np.broadcast_arrays(xi, q))
        return self._pieces(side, xi, self._piece_coordinate(side, xi, q))

    def _arc_table(self, side, cols):
        """Piece-coordinate grids and arc lengths (n, 3 _SAMPLES - 2) of the side curves
        at the face positions ``cols`` (n,), from the root point to each curve's end."""
        grid = np.concatenate([np.linspace(0.0, 1.0, _SAMPLES),
                               np.linspace(1.0, 2.0, _SAMPLES)[1:],
                               np.linspace(2.0, 3.0, _SAMPLES)[1:]])
        end = self._side_end(side, cols)
        if np.all(end == 3.0):
            grids = np.broadcast_to(grid, (len(cols), len(grid)))
            pts = self._pieces(side, np.repeat(cols, len(grid)), np.tile(grid, len(cols)))
        else:           # the fillet pieces end at the V's crossing
            grids = np.array([np.concatenate([grid[:2 * _SAMPLES - 1],
                                              np.linspace(2.0, e, _SAMPLES)[1:]]) for e in end])
            pts = self._pieces(side, np.repeat(cols, len(grid)), grids.ravel())
        seg = np.linalg.norm(np.diff(pts.reshape(len(cols), len(grid), 3), axis=1), axis=-1)
        arc = np.concatenate([np.zeros((len(cols), 1)), np.cumsum(seg, axis=1)], axis=1)
        return grids, arc

    def _piece_coordinate(self, side, xi, q):
        cols, inv = np.unique(xi, return_inverse=True)
        grids, arc = self._arc_table(side, cols)
        out = np.empty_like(q)
        for k in range(len(cols)):
            at = inv.ravel() == k
            out.ravel()[at] = np.interp(q.ravel()[at] * arc[k, -1], arc[k], grids[k])
        return out

    # ---------------------------------------------------------------- V slots
    def _side_end(self, side: str, xi) -> np.ndarray:
        """Piece coordinate of the side curves' ends at ``xi`` (n,): 3 (the fillet's
        bottom) where the slot is open down to the root cone, the crossing's where it
        closes in a V (:meth:`crossing`); cached per ``xi``."""
        xi = np.asarray(xi, float)
        key = (side, xi.tobytes())
        if key not in self._ends:
            self._ends[key] = self._find_ends(side, xi)
        return self._ends[key]

    def _bottoms_turn(self, xi):
        """Fillet bottoms ``(B_c, B_d)`` (n, 3) at ``xi`` and the half slot angle about the
        axis beside them (n,), rad (<= 0: the slot closes above the root cone), with the
        sense (n,) of the turn coast -> drive (+-1)."""
        bc, bd = (self._pieces(s, xi, np.full_like(xi, 3.0)) for s in ("coast", "drive"))
        return (bc, bd) + self._half_slot(bc, bd)

    def _half_slot(self, bc, bd):
        """Half the slot angle about the axis beside the points ``bc``, ``bd`` (n, 3) of
        the coast and drive sides, rad (n,), and the sense coast -> drive (+-1)."""
        ax = self.tooth.axis
        rc, rd = bc - np.outer(bc @ ax, ax), bd - np.outer(bd @ ax, ax)
        delta = np.arctan2(np.cross(rc, rd) @ ax, np.einsum("ni,ni->n", rc, rd))
        return 0.5 * (2.0 * math.pi / self.tooth.teeth - np.abs(delta)), np.sign(delta)

    def _find_ends(self, side, xi):
        end = np.full(xi.shape, 3.0)
        if xi.size == 0:
            return end
        _, _, half, _ = self._bottoms_turn(xi)
        closed = half <= 0.0
        if np.any(closed):
            lo, hi = self.fillets[side].u_range
            end[closed] = 3.0 - (self._crossing(side, xi[closed])[0] - lo) / (hi - lo)
        return end

    def crossing(self, side: str, xi) -> tuple[np.ndarray, np.ndarray]:
        """Where the slot beside ``side`` closes in a V at face positions ``xi`` (n,):
        ``(u, points)``, the fillet parameter (mm on the edge round) of this tooth's
        ``side`` fillet at the crossing with the neighbouring tooth's other fillet (the
        coast fillet of the next tooth beside the drive side, the drive fillet of the
        previous one beside the coast side) and the crossing points (n, 3), body frame;
        NaN where the slot is open down to the root cone.

        Found per axial section (the side curves of one ``xi`` share it: the pinion's
        lengthwise parameter is the axial position) by a bracketed 1-D solve (Illinois
        regula falsi) on the fillet parameter of the gap to the neighbour at equal
        radius, that radius found on the neighbour's side curve by the same solve:
        both points exact on their fillets, the gap below :data:`_CROSSING_TOL_MM`.

        Raises
        ------
        InputRangeError
            Where the two side curves of the section do not share an axial plane, or
            the slot closes above the fillets (the crossing on a flank or bridge).
        """
        xi = np.atleast_1d(np.asarray(xi, float))
        u = np.full(xi.shape, np.nan)
        pts = np.full(xi.shape + (3,), np.nan)
        closed = self._bottoms_turn(xi)[2] <= 0.0
        if np.any(closed):
            u[closed], pts[closed] = self._crossing(side, xi[closed])
        return u, pts

    def _crossing(self, side, xi):
        """:meth:`crossing` at face positions ``xi`` where the slot closes (n,)."""
        tooth, fil = self.tooth, self.fillets[side]
        ax = tooth.axis
        other = "coast" if side == "drive" else "drive"
        bc, bd, _, sense = self._bottoms_turn(xi)
        spread = np.abs((bd - bc) @ ax)
        if np.any(spread > 1e-9):
            k = int(np.argmax(spread))
            raise InputRangeError(f"{tooth.member} side curves at xi = {xi[k]:.3f}: axial "
                                  "distance of the fillet bottoms (mm)", float(spread[k]),
                                  "0 (a slot closing in a V is meshed in axial sections)")
        # the neighbour beside ``side``: one pitch on in the sense coast -> drive
        turn = (sense if side == "drive" else -sense) * 2.0 * math.pi / tooth.teeth
        v = tooth.flank_parameters(side, xi, -np.ones_like(xi))[1]
        s_bottom, s_top = fil.u_range

        def point(s):
            r = fil.evaluate(s, v).r
            return r @ tooth.coast_turn.T if side == "coast" else r

        def radius(r):
            return np.linalg.norm(r - np.outer(r @ ax, ax), axis=-1)

        def neighbour(rho):
            """The neighbour's side-curve point at radius ``rho`` and its piece coordinate
            (its radius falls from the root point, p = 0, to the root cone, p = 3)."""
            def f(p):
                return radius(self._pieces(other, xi, p)) - rho
            p = _illinois(f, np.zeros_like(rho), np.full_like(rho, 3.0), tol=1e-13)
            r = self._pieces(other, xi, p)
            rot = np.array([axis_rotation(ax, t) for t in turn])
            return np.einsum("nij,nj->ni", rot, r), p

        def gap(s):
            """Arc (mm, at the point's radius) from the point of the fillet at ``s`` to the
            neighbour's side curve, > 0 into the open slot."""
            r = point(s)
            n, _ = neighbour(radius(r))
            a = np.arctan2(np.cross(r, n) @ ax, np.einsum("ni,ni->n", r, n) - (r @ ax) * (n @ ax))
            return np.sign(turn) * a * radius(r)

        top = gap(np.full_like(xi, s_top))
        if np.any(top <= 0.0):
            k = int(np.argmin(top))
            raise InputRangeError(f"{tooth.member} slot beside the {side} side at "
                                  f"xi = {xi[k]:.3f}: gap at the fillet's top (mm)",
                                  float(top[k]), "> 0 (a slot closing below its fillets' "
                                  "tops; here the flanks cross)")
        s = _illinois(gap, np.full_like(xi, s_bottom), np.full_like(xi, s_top),
                      tol=_CROSSING_TOL_MM)
        r = point(s)
        p_other = neighbour(radius(r))[1]
        if np.any(p_other < 2.0):
            k = int(np.argmin(p_other))
            raise InputRangeError(f"{tooth.member} slot beside the {side} side at "
                                  f"xi = {xi[k]:.3f}: the crossing's piece coordinate on "
                                  f"the {other} side curve", float(p_other[k]),
                                  ">= 2 (on its fillet, not its flank or bridge)")
        return s, r

    # ---------------------------------------------------------------- slot and rim
    def root_row(self, xi, n_slot: int) -> np.ndarray:
        """The root row at face positions ``xi`` (n,): (n, 2 n_slot + 2, 3) points,
        coast slot middle -> the coast side curve's end (index n_slot) -> the drive
        side curve's end (n_slot + 1) -> drive slot middle, mm: from the two fillet
        bottoms ``B_c``, ``B_d`` along the root cone (turned about the axis), half a slot
        on each side. Where the slot closes in a V above the root cone (:meth:`crossing`;
        the 7-tooth s0003 pinion at the toe) the side curves end at the crossings, one
        pitch apart, and the slot bottom has no width: its points all lie at the
        crossing (:func:`.fe.build_fe` merges them); towards the V the strip's width
        goes to zero with the half slot angle beside the bottoms."""
        xi = np.atleast_1d(np.asarray(xi, float))
        one = np.ones_like(xi)
        bc, bd = self.side_points("coast", xi, one), self.side_points("drive", xi, one)
        ax = self.tooth.axis
        half, sign = self._half_slot(bc, bd)
        closed = self.closed(xi)
        if np.any(closed):
            # the crossings lie one pitch apart (to the solve's tolerance): no strip
            half = np.where(closed, 0.0, half)
        frac = np.linspace(0.0, 1.0, n_slot + 1)
        row = np.empty((len(xi), 2 * n_slot + 2, 3))
        for i in range(len(xi)):
            for k, f in enumerate(frac):
                row[i, n_slot - k] = axis_rotation(ax, -sign[i] * half[i] * f) @ bc[i]
                row[i, n_slot + 1 + k] = axis_rotation(ax, sign[i] * half[i] * f) @ bd[i]
        return row

    def closed(self, xi) -> np.ndarray:
        """Where the slots beside the tooth close in a V above the root cone (n,) bool
        (:meth:`crossing`)."""
        xi = np.atleast_1d(np.asarray(xi, float))
        return (self._side_end("coast", xi) < 3.0) | (self._side_end("drive", xi) < 3.0)

    def cone_depth_mm(self, xi) -> np.ndarray:
        """Depth of the fillet bottoms' middle below the root line's centre along ``d``
        (n,), mm: the height of the real fillet zone below the tooth's root line."""
        xi = np.atleast_1d(np.asarray(xi, float))
        one = np.ones_like(xi)
        centre, down, _, _ = root_line_section(self.tooth, xi)
        mid = 0.5 * (self.side_points("coast", xi, one) + self.side_points("drive", xi, one))
        return np.einsum("ni,ni->n", mid - centre, down)

    def _block_mm(self, xi) -> np.ndarray:
        """Height of the rim block below the fillet zone at ``xi`` (n,), mm; raises
        InputRangeError where the rim is not deeper than the fillet zone."""
        block = self.depth_mm - self.cone_depth_mm(xi)
        if np.any(block <= 0.0):
            raise InputRangeError(f"{self.tooth.member} rim depth_mm", self.depth_mm,
                                  "> the fillet zone's depth "
                                  f"{float(np.max(self.depth_mm - block)):.3f} mm")
        return block

    def check_meshable(self, xi_levels, n_slot: int) -> None:
        """Raise InputRangeError, as :meth:`mesh_points` would, where the FE cannot mesh
        this root at the face positions ``xi_levels``: a slot closing above its fillets
        or out of an axial section (:meth:`crossing`) or a rim not deeper than the
        fillet zone."""
        xi = np.asarray(xi_levels, float)
        self.root_row(xi, n_slot)
        self._block_mm(xi)

    def mesh_points(self, xi_levels, q_levels, s_fractions, zeta_levels, n_slot: int
                    ) -> np.ndarray:
        """Node positions below the root line for :func:`.fe.build_fe`:
        ``(n_xi, len(s_fractions) + len(q_levels) - 1, n_zeta + 2 n_slot + 1, 3)`` with
        levels from the clamped bottom (0) up: the rim block at the depth fractions
        ``s_fractions`` (descending, 1 at the bottom .. 0 at the root row), then the
        fillet zone at the side-curve fractions ``q_levels[1:]`` (descending;
        ``q_levels[0] = 1`` is the root row itself, the root line ``q = 0`` is the
        tooth's and excluded); columns across: the coast slot bottom, the tooth (``zeta_levels``,
        straight from the coast to the drive side point), the drive slot bottom. Nodes of
        the fillet zone outside the tooth's columns are unused (NaN)."""
        xi = np.asarray(xi_levels, float)
        zeta = np.asarray(zeta_levels, float)
        nz = len(zeta) - 1
        row = self.root_row(xi, n_slot)                            # (n_xi, 2 n_slot + 2, 3)
        # the root row with the tooth's columns between the two fillet bottoms
        tooth_cols = row[:, n_slot:n_slot + 1] + zeta[None, :, None] * (
            row[:, n_slot + 1:n_slot + 2] - row[:, n_slot:n_slot + 1])
        full = np.concatenate([row[:, :n_slot], tooth_cols, row[:, n_slot + 2:]], axis=1)
        closed = self.closed(xi)
        if np.any(closed):      # a closed slot's points at the tooth's end, exactly
            full[closed, :n_slot] = full[closed, n_slot:n_slot + 1]
            full[closed, n_slot + nz + 1:] = full[closed, n_slot + nz:n_slot + nz + 1]
        _, down, _, _ = root_line_section(self.tooth, xi)
        block = self._block_mm(xi)
        s = np.asarray(s_fractions, float)
        levels = [full + (s[j] * block)[:, None, None] * down[:, None, :]
                  for j in range(len(s))]
        q = np.asarray(q_levels, float)
        for qj in q[1:]:
            lvl = np.full_like(full, np.nan)
            pc = self.side_points("coast", xi, np.full_like(xi, qj))
            pd = self.side_points("drive", xi, np.full_like(xi, qj))
            lvl[:, n_slot:n_slot + nz + 1] = pc[:, None] + zeta[None, :, None] * (pd - pc)[:, None]
            levels.append(lvl)
        return np.stack(levels, axis=1)

    # ---------------------------------------------------------------- ISO section
    def section_plane(self, xi) -> tuple[np.ndarray, np.ndarray]:
        """``(m, d)`` (n, 3) at the root line: the tooth's thickness direction (the
        mid-surface normal, coast -> drive, made normal to ``d``) and the unit down
        direction. A section at ``xi`` is measured in their plane: the chord of two
        side points at one ``xi`` runs obliquely through a spiral tooth, its normal
        thickness is its component along ``m``."""
        xi = np.atleast_1d(np.asarray(xi, float))
        _, down, _, _ = root_line_section(self.tooth, xi)
        m = self.tooth.mid_surface(xi, -np.ones_like(xi)).normal
        m = m - np.einsum("ni,ni->n", m, down)[:, None] * down
        return m / np.linalg.norm(m, axis=-1, keepdims=True), down

    def critical_section(self, xi, *, tangent_deg: float = ISO_TANGENT_DEG
                         ) -> CriticalSection:
        """The section where each side curve's tangent (projected into the plane of the
        down direction ``d`` and the thickness direction ``m``) makes ``tangent_deg`` with
        ``d``
        (ISO 6336-3 sec. 6.2), found by Brent's method on the piece coordinate over the
        bridge and the fillet."""
        xi = np.atleast_1d(np.asarray(xi, float))
        across, down = self.section_plane(xi)
        target = math.radians(tangent_deg)
        pts, centre = {}, root_line_section(self.tooth, xi)[0]
        for side in ("coast", "drive"):
            got = np.empty((len(xi), 3))
            for i, x in enumerate(xi):
                def angle(p, side=side, i=i, x=x):
                    h = 1e-6
                    a, b = (self._pieces(side, np.array([x]), np.array([p + e]))[0]
                            for e in (-h, h))
                    t = b - a
                    return math.atan2(abs(t @ across[i]), t @ down[i]) - target
                # the first crossing down the curve (a bridge of micrometres skipped)
                bridged = self.bridge_mm(side, x)[0] > _BRIDGE_SEARCH_MM
                end = self._side_end(side, np.array([x]))[0]     # 3, or a V's crossing
                grid = [p for p in np.linspace(1e-5, end - 1e-5, 61)
                        if bridged or not 1.0 < p < 2.0]
                f = np.array([angle(p) for p in grid])
                k = int(np.argmax(f > 0.0))
                if k == 0:
                    raise InputRangeError(f"{self.tooth.member} {side} root side tangent",
                                          f"{math.degrees(f[0] + target):.1f} deg",
                                          f"a tangent through {tangent_deg} deg")
                p30 = brentq(angle, grid[k - 1], grid[k], xtol=1e-12)
                got[i] = self._pieces(side, np.array([x]), np.array([p30]))[0]
            pts[side] = got
        w = pts["drive"] - pts["coast"]
        mid = 0.5 * (pts["drive"] + pts["coast"])
        return CriticalSection(xi=xi, thickness_mm=np.abs(np.einsum("ni,ni->n", w, across)),
                               depth_mm=np.einsum("ni,ni->n", mid - centre, down),
                               coast_mm=pts["coast"], drive_mm=pts["drive"])


def _illinois(f, a, b, *, tol: float, steps: int = 100) -> np.ndarray:
    """Roots (n,) of the vectorized ``f`` bracketed by ``[a, b]`` (n,) (Illinois
    regula falsi, Dowell & Jarratt 1971): to ``|f| <= tol`` or a bracket of 1e-15
    relative; where ``f(a)``, ``f(b)`` have the same sign the end of smaller ``|f|``
    (a target outside the bracket: the curve's end)."""
    a, b = np.array(a, float), np.array(b, float)
    fa, fb = f(a), f(b)
    out = np.where(np.abs(fa) <= np.abs(fb), a, b)
    active = np.sign(fa) * np.sign(fb) < 0.0
    last = np.zeros(a.shape, int)
    for _ in range(steps):
        if not np.any(active):
            break
        c = np.where(active, (a * fb - b * fa) / np.where(active, fb - fa, 1.0), out)
        fc = f(c)
        out = np.where(active, c, out)
        done = (np.abs(fc) <= tol) | (np.abs(b - a) <= 1e-15 * (1.0 + np.abs(c)))
        keep_b = np.sign(fc) == np.sign(fa)             # c replaces a
        a, fa = np.where(keep_b, c, a), np.where(keep_b, fc, fa)
        b, fb = np.where(keep_b, b, c), np.where(keep_b, fb, fc)
        # an end kept twice: halve its value (the Illinois step)
        fb = np.where(keep_b & (last == 1), 0.5 * fb, fb)
        fa = np.where(~keep_b & (last == -1), 0.5 * fa, fa)
        last = np.where(keep_b, 1, -1)
        active &= ~done
    if np.any(active):
        raise CheckFailed(f"regula falsi did not converge in {steps} steps "   # pragma: no cover
                          "(the fillets' crossing)")
    return out


def fillet_root(tooth: ToothGeometry, fillets: dict, *, depth_mm: float | None = None
                ) -> FilletRoot:
    """The :class:`FilletRoot` of ``tooth`` from ``fillets`` (``{(member, side):
    RootFillet}`` of :func:`~gearcontact.geometry.fillet.pair_fillets`, or ``{side:
    RootFillet}``); ``depth_mm`` defaults to the tooth height (:mod:`.rim`'s depth).

    Raises
    ------
    InputRangeError
        A side without a fillet (its member's cutter unknown: the conjugate pinion).
    """
    got = {}
    for side in ("drive", "coast"):
        f = fillets.get((tooth.member, side), fillets.get(side))
        if f is None:
            raise InputRangeError(f"{tooth.member} {side} root fillet", "none",
                                  "a fillet of the member's cutter (geometry.fillet)")
        got[side] = f
    depth = tooth_height_mm(tooth) if depth_mm is None else float(depth_mm)
    if not depth > 0.0:
        raise InputRangeError("rim depth_mm", depth, "> 0")
    return FilletRoot(tooth=tooth, fillets=got, depth_mm=depth)
