"""A flank cut by a relieved (Toprem / Flankrem) blade: smooth pieces meeting along kinks.

A relieved blade is the union of the smooth blades of its segments
(:func:`~.blade.blade_segments`), each continued past its kinks: locally at a kink the
tool is the union of the two continued blades (the relief turns the profile into the
cut tooth, a concave corner of the tool). The work a union of tools leaves is the
intersection of what each leaves, so the flank is, point by point, the deeper (into
the tooth) of the flanks the continued segment blades generate, and a kink of the blade
maps to the line where two of these smooth flanks intersect: a curve of tangent-plane
discontinuity on the flank (docs/machine_settings.md sec. 1, "Toprem and Flankrem").
For a formate cut the flanks are the blade surfaces and the kink is the blade's
circle at its depth; in generation the two pieces' generating points on the kink
circle differ (their normals differ), so the kink line is not the trace of one blade
circle.

:class:`KinkedFlank` keeps each piece a :class:`~.surface.Surface` with its own
closed-form (or C2 spline) derivatives and selects the piece by the kink lines
``u = u_k(v)`` (``u`` root -> tip): curvature is one-sided at a kink, never across it.
The ridge itself is an edge for TCA (:mod:`gearcontact.tca.edge_contact`).

References
----------
F. L. Litvin, A. Fuentes, *Gear Geometry and Applied Theory*, 2nd ed., 2004, sec. 6.1
(the envelope of a family of surfaces), ch. 20-21 (head-cutter blades).
H. J. Stadtfeld, *Handbook of Bevel and Hypoid Gears*, 1993 (Toprem and Flankrem).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np
from numba import njit
from scipy.interpolate import CubicSpline, PPoly

from .blade import blade_segments
from .flank_reuse import reused
from .formate import FlankBoundary
from .generated import (formate_gear_flank, gear_flank_of, generated_gear_box,
                        generated_gear_flank, generated_pinion_box, generated_pinion_flank)
from .sampling import SurfaceArrays, point_from_arrays
from .surface import SurfacePoint

__all__ = ["KINK_NODES", "KinkLine", "KinkedFlank", "kinked_flank", "machine_flank",
           "kink_u", "kink_piece", "kink_pieces"]

#: Lengthwise nodes on which each kink line is solved (interpolated between them by a
#: cubic spline; tests/geometry/test_kinked.py measures the interpolation error).
KINK_NODES = 41
_BISECTIONS = 64


@njit(cache=True, inline="always")
def kink_u(x, c, n, v):
    """``u_k(v)`` of a kink line from its piecewise cubic (the first ``n`` breaks ``x``,
    coefficients ``c`` (n - 1, 4): :attr:`KinkLine.pp_table`): the piece
    ``x[i] <= v < x[i+1]`` (the first / last continued), summed in ascending powers of
    ``v - x[i]`` as scipy's ``PPoly`` does."""
    a = min(max(np.searchsorted(x[:n], v, side="right") - 1, 0), n - 2)
    s = v - x[a]
    res = 0.0
    z = 1.0
    for p in range(4):
        res = res + c[a, p] * z
        z *= s
    return res


@njit(cache=True, inline="always")
def kink_piece(kink_x, kink_c, kink_n, u, v):
    """Index of the piece that holds ``(u, v)``: the number of kink lines below
    (tables: :attr:`KinkedFlank.kink_tables`)."""
    k = 0
    for j in range(kink_x.shape[0]):
        if u > kink_u(kink_x[j], kink_c[j], kink_n[j], v):
            k += 1
    return k


@njit(cache=True)
def kink_pieces(kink_x, kink_c, kink_n, u, v):
    """:func:`kink_piece` at the points ``(u[i], v[i])`` (1-D arrays)."""
    out = np.empty(u.shape[0], dtype=np.int64)
    for i in range(u.shape[0]):
        out[i] = kink_piece(kink_x, kink_c, kink_n, u[i], v[i])
    return out


@dataclass(frozen=True, eq=False)
class KinkLine:
    """The kink between pieces ``lower`` and ``lower + 1`` of a :class:`KinkedFlank`:
    ``u = u_k(v)`` solved at ``v_nodes`` (``u_nodes``; -inf / +inf where the kink lies
    below / above the flank's box; where it crosses the box's root or tip line between
    two nodes, the crossing is a node of its own, :func:`kinked_flank`)."""

    name: str
    lower: int
    v_nodes: np.ndarray
    u_nodes: np.ndarray

    def u(self, v):
        """``u_k(v)``, mm: the piecewise cubic :attr:`pp_table` (a cubic spline through
        the nodes; where the kink lies outside the box, the huge value -1e300 / 1e300
        standing for its side)."""
        v = np.asarray(v, dtype=float)
        fit = self.__dict__.get("_fit")
        if fit is None:
            x, c = self.pp_table
            fit = PPoly(np.ascontiguousarray(c.T[::-1]), x)
            object.__setattr__(self, "_fit", fit)
        return fit(v)

    @property
    def pp_table(self) -> tuple[np.ndarray, np.ndarray]:
        """``(breaks, coef)``: :meth:`u` as a piecewise cubic, also for compiled code
        (:func:`kink_u`): on ``breaks[i] <= v < breaks[i+1]`` (the first / last piece
        continued beyond the ends) ``u_k = sum_p coef[i, p] s^p`` with
        ``s = v - breaks[i]``, summed in ascending powers as scipy's ``PPoly`` does.
        Each run of finite nodes is scipy's not-a-knot ``CubicSpline`` (all of them
        for a kink inside the box over the whole face width); an interval with an
        infinite end is the constant -1e300 / 1e300 of that end's sign (the kink
        leaves the box at the finite end: a crossing node on the root or tip line)."""
        got = self.__dict__.get("_pp")
        if got is None:
            x = np.ascontiguousarray(self.v_nodes, dtype=float)
            y = np.asarray(self.u_nodes, dtype=float)
            coef = np.zeros((x.size - 1, 4))
            finite = np.isfinite(y)
            i = 0
            while i < x.size - 1:
                if finite[i] and finite[i + 1]:
                    j = i + 1
                    while j + 1 < x.size and finite[j + 1]:
                        j += 1
                    fit = CubicSpline(x[i:j + 1], y[i:j + 1])
                    coef[i:j] = fit.c[::-1].T
                    i = j
                else:
                    end = y[i + 1] if not finite[i + 1] else y[i]
                    coef[i, 0] = np.sign(end) * 1e300
                    i += 1
            got = (x, np.ascontiguousarray(coef))
            object.__setattr__(self, "_pp", got)
        return got


@dataclass(frozen=True, eq=False)
class KinkedFlank:
    """A flank of smooth pieces (each a :class:`~.surface.Surface` over the same
    ``(u, v)``, ordered root -> tip) separated by :class:`KinkLine` s.

    Attributes
    ----------
    pieces : tuple
        Piece surfaces; piece ``k`` is evaluated at ``(u, v_scales[k] v)`` (formate
        pieces: the blade angle per unit ``v`` differs from cone to cone).
    names : tuple of str
        ``"toprem"``, ``"main"``, ``"flankrem"`` (:class:`~.blade.BladeSegment`).
    kinks : tuple of KinkLine
    v_scales : tuple of float
    """

    pieces: tuple
    names: tuple
    kinks: tuple
    v_scales: tuple

    @property
    def main(self):
        """The main piece (the blade's own profile)."""
        return self.pieces[self.names.index("main")]

    @property
    def _main_scale(self) -> float:
        return self.v_scales[self.names.index("main")]

    @property
    def boundary(self):
        """The main piece's box in this flank's ``v`` (its own over its ``v_scale``)."""
        b, s = self.main.boundary, self._main_scale
        return b if s == 1.0 else dataclasses.replace(b, v_toe=b.v_toe / s,
                                                      v_heel=b.v_heel / s)

    @property
    def u_range(self) -> tuple[float, float]:
        return self.main.u_range       # u is every piece's own

    @property
    def v_range(self) -> tuple[float, float]:
        lo, hi = self.main.v_range
        return (lo / self._main_scale, hi / self._main_scale)

    @property
    def side(self) -> str:
        return self.main.side

    def __getattr__(self, name):
        # the main piece's own attributes (cone, blade, dedendum_mm, ...) for the code
        # that reads them; never its evaluation (point / evaluate are this class's)
        if name.startswith("_") or name in ("pieces", "names", "kinks", "v_scales"):
            raise AttributeError(name)
        return getattr(self.main, name)

    @property
    def kink_tables(self):
        """``(kink_x, kink_c, kink_n)``: the kinks' :attr:`KinkLine.pp_table` stacked
        (K, n), (K, n - 1, 4) (a kink with fewer breaks padded at the end) and their
        break counts (K,), for :func:`kink_piece` (compiled code: this class,
        :mod:`gearcontact.tca.gap_kernel`)."""
        got = self.__dict__.get("_kink_tables")
        if got is None:
            tables = [kink.pp_table for kink in self.kinks]
            n = max((t[0].size for t in tables), default=2)
            kx, kc = np.zeros((len(tables), n)), np.zeros((len(tables), n - 1, 4))
            for j, (x, c) in enumerate(tables):
                kx[j, :x.size], kc[j, :x.size - 1] = x, c
            got = (kx, kc, np.array([t[0].size for t in tables], dtype=np.int64))
            object.__setattr__(self, "_kink_tables", got)
        return got

    def piece_index(self, u, v) -> np.ndarray:
        """Index of the piece that holds ``(u, v)`` (arrays): the number of kinks below
        (:func:`kink_pieces` on :attr:`kink_tables`, the compiled TCA kernel's choice)."""
        u, v = np.broadcast_arrays(np.asarray(u, dtype=float), np.asarray(v, dtype=float))
        return kink_pieces(*self.kink_tables, np.ascontiguousarray(u.ravel()),
                           np.ascontiguousarray(v.ravel())).reshape(u.shape)

    def kink_name(self, u0, u1, v) -> str | None:
        """The kink crossed between ``(u0, v)`` and ``(u1, v)``, or None."""
        a, b = (int(x) for x in self.piece_index([u0, u1], [v, v]))
        if a == b:
            return None
        return self.kinks[min(a, b)].name

    def map_pieces(self, fn) -> KinkedFlank:
        """The flank with ``fn`` applied to every piece (a turn about the member axis, a
        reflection): the kinks' ``(u, v)`` stay."""
        return dataclasses.replace(self, pieces=tuple(fn(p) for p in self.pieces))

    def piece_bounds(self, i: int, v) -> tuple[np.ndarray, np.ndarray]:
        """``(u_a(v), u_b(v))``: the ``u`` interval of piece ``i`` at ``v`` (its kinks
        below and above, else the box's ends; clipped to the box, so an empty interval
        where the piece does not reach the flank)."""
        v = np.asarray(v, dtype=float)
        lo, hi = self.u_range
        a = self.kinks[i - 1].u(v) if i > 0 else np.full(v.shape, lo)
        b = self.kinks[i].u(v) if i < len(self.kinks) else np.full(v.shape, hi)
        return np.clip(a, lo, hi), np.clip(b, lo, hi)

    def evaluate_piece(self, i: int, u, v, *, second: bool = True) -> SurfaceArrays:
        """Piece ``i`` (continued past its kinks) at ``(u, v)`` of this flank."""
        u, v = np.broadcast_arrays(np.asarray(u, dtype=float), np.asarray(v, dtype=float))
        s = self.v_scales[i]
        got = self.pieces[i].evaluate(u, s * v, second=second)
        names = ("r", "r_u", "r_v", "r_uu", "r_uv", "r_vv", "n")
        return SurfaceArrays(u=u, v=v, **{f: scale * getattr(got, f) for f, scale in
                                          zip(names, (1.0, 1.0, s, 1.0, s, s * s, 1.0))})

    def evaluate(self, u, v, *, second: bool = True) -> SurfaceArrays:
        """Vectorized evaluation, each point on its piece (one-sided at a kink)."""
        u, v = np.broadcast_arrays(np.asarray(u, dtype=float), np.asarray(v, dtype=float))
        k = self.piece_index(u, v)
        names = ("r", "r_u", "r_v", "r_uu", "r_uv", "r_vv", "n")
        out = {f: np.empty(u.shape + (3,)) for f in names}
        for i in range(len(self.pieces)):
            m = k == i
            if not m.any():
                continue
            got = self.evaluate_piece(i, u[m], v[m], second=second)
            for f in names:
                out[f][m] = getattr(got, f)
        return SurfaceArrays(u=u, v=v, **out)

    def point(self, u: float, v: float) -> SurfacePoint:
        """:class:`~.surface.SurfacePoint` of the piece that holds ``(u, v)``."""
        i = kink_piece(*self.kink_tables, float(u), float(v))
        s = self.v_scales[i]
        p = self.pieces[i].point(u, s * v)
        if s == 1.0:
            return p
        return point_from_arrays(SurfaceArrays(u=u, v=v, r=p.r, r_u=p.r_u, r_v=s * p.r_v,
                                               r_uu=p.r_uu, r_uv=s * p.r_uv, r_vv=s * s * p.r_vv,
                                               n=p.n))


def _depth_gap(lower, s_lower, upper, s_upper, u, v):
    """``(r_lower - r_upper) . n_upper`` at (u, v): > 0 where the upper piece is the
    deeper (the lower one lies towards the slot)."""
    a = lower.evaluate(u, s_lower * v, second=False)
    b = upper.evaluate(u, s_upper * v, second=False)
    return np.einsum("...i,...i->...", a.r - b.r, b.n)


def _with_crossings(args, vs, u_k, u_box):
    """The kink's nodes with, between two nodes on different sides of the box's root
    (tip) line (``u_k`` finite on one, -inf (+inf) on the other), the point where the
    kink crosses that line: ``v`` by bisection of :func:`_depth_gap` along it (to
    rounding, 64 halvings), ``u`` the line's."""
    v_out, u_out = [vs[:1]], [u_k[:1]]
    for j in range(len(vs) - 1):
        crossings = []
        for u_line, out in zip(u_box, (-np.inf, np.inf)):
            if (u_k[j] == out) != (u_k[j + 1] == out):
                a, b = np.array([vs[j]]), np.array([vs[j + 1]])
                g_a = _depth_gap(*args, np.array([u_line]), a)
                for _ in range(_BISECTIONS):
                    mid = 0.5 * (a + b)
                    same = (_depth_gap(*args, np.array([u_line]), mid) < 0.0) == (g_a < 0.0)
                    a, b = np.where(same, mid, a), np.where(same, b, mid)
                crossings.append((float(0.5 * (a + b)[0]), u_line))
        for v, u in sorted(crossings):
            v_out.append(np.array([v]))
            u_out.append(np.array([u]))
        v_out.append(vs[j + 1:j + 2])
        u_out.append(u_k[j + 1:j + 2])
    return np.concatenate(v_out), np.concatenate(u_out)


def kinked_flank(pieces, names, *, v_scales=None, n_nodes: int = KINK_NODES) -> KinkedFlank:
    """The :class:`KinkedFlank` of ``pieces`` (root -> tip, one box): each kink solved by
    bisection of :func:`_depth_gap` over the box's ``u`` at ``n_nodes`` lengthwise nodes
    (to rounding, 64 halvings). A kink with no sign change over the box lies outside it
    (``u_k = -inf``: the upper piece is the deeper everywhere; ``+inf``: the lower);
    where it crosses the root or tip line between two nodes the crossing is added as a
    node (:func:`_with_crossings`)."""
    v_scales = tuple(1.0 for _ in pieces) if v_scales is None else tuple(v_scales)
    main, s_main = pieces[names.index("main")], v_scales[names.index("main")]
    (u_lo, u_hi), (v_lo, v_hi) = main.u_range, main.v_range
    vs = np.linspace(v_lo, v_hi, n_nodes) / s_main
    kinks = []
    for i in range(len(pieces) - 1):
        args = (pieces[i], v_scales[i], pieces[i + 1], v_scales[i + 1])
        lo, hi = np.full_like(vs, u_lo), np.full_like(vs, u_hi)
        g_lo, g_hi = _depth_gap(*args, lo, vs), _depth_gap(*args, hi, vs)
        for _ in range(_BISECTIONS):
            mid = 0.5 * (lo + hi)
            below = _depth_gap(*args, mid, vs) < 0.0
            lo, hi = np.where(below, mid, lo), np.where(below, hi, mid)
        u_k = np.where(g_lo >= 0.0, -np.inf, np.where(g_hi <= 0.0, np.inf, 0.5 * (lo + hi)))
        v_k, u_k = _with_crossings(args, vs, u_k, (u_lo, u_hi))
        kinks.append(KinkLine(name=names[i + 1] if names[i] == "main" else names[i],
                              lower=i, v_nodes=v_k, u_nodes=u_k))
    return KinkedFlank(pieces=tuple(pieces), names=tuple(names), kinks=tuple(kinks),
                       v_scales=v_scales)


@reused
def machine_flank(setup, blank, *, face_width_mm: float, n_u: int = 120, n_v: int = 150,
                  pinion_box: FlankBoundary | None = None):
    """The flank ``setup`` cuts on its member: :func:`~.generated.gear_flank_of` /
    :func:`~.generated.generated_pinion_flank` for a smooth blade (unchanged), a
    :class:`KinkedFlank` for a relieved one (module docstring): one piece per blade
    segment, all on the active box the tip segment traces (formate gear: the blade
    cones, the kink at the relief depth). ``pinion_box``: a pinion flank's active box
    when the caller holds it (:func:`~.generated.generated_pinion_box` of ``setup``,
    which checks it), not traced again; the same flank, bit for bit. Within
    :func:`~.flank_reuse.reusing_flanks` a call with the same inputs is served the flank
    cut before (:func:`~.flank_reuse.reused`)."""
    segs = blade_segments(setup.blade)
    gear = setup.member == "gear"
    if len(segs) == 1:
        if gear:
            return gear_flank_of(setup, blank, gear_face_width_mm=face_width_mm, n_u=n_u, n_v=n_v)
        return generated_pinion_flank(setup, blank, pinion_face_width_mm=face_width_mm,
                                      n_u=n_u, n_v=n_v, box=pinion_box)[0]
    setups = [dataclasses.replace(setup, blade=seg.blade) for seg in segs]
    names = [seg.name for seg in segs]
    if gear and setup.settings.formate:
        cones = [formate_gear_flank(s, blank, gear_face_width_mm=face_width_mm) for s in setups]
        main = cones[names.index("main")]
        # v is the tip cone's (its fillet's, geometry.fillet); piece k is evaluated at
        # v_scales[k] v: the same blade angle at the same v
        kv = [c.blade.placement.heel_sign / c.blade.radius_pitch_mm for c in cones]
        scales = [kv[0] / k for k in kv]
        s_main = scales[names.index("main")]
        box = FlankBoundary(cones[0].boundary.u_root, main.boundary.u_tip,
                            main.boundary.v_toe / s_main, main.boundary.v_heel / s_main)
        pieces = [dataclasses.replace(c, boundary=dataclasses.replace(
            box, v_toe=box.v_toe * s, v_heel=box.v_heel * s)) for c, s in zip(cones, scales)]
        return kinked_flank(pieces, names, v_scales=scales)
    if gear:
        box = generated_gear_box(setup, blank, gear_face_width_mm=face_width_mm)[1]
        pieces = [generated_gear_flank(s, blank, gear_face_width_mm=face_width_mm, n_u=n_u,
                                       n_v=n_v, box=box)[0] for s in setups]
    else:
        box = pinion_box or generated_pinion_box(setup, blank,
                                                 pinion_face_width_mm=face_width_mm)[1]
        pieces = [generated_pinion_flank(s, blank, pinion_face_width_mm=face_width_mm, n_u=n_u,
                                         n_v=n_v, box=box)[0] for s in setups]
    return kinked_flank(pieces, names)
