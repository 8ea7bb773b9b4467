"""Tangent-plane gap field around a mating point and the 7 x 7 hardware stencil.

At the mating point ``P0`` with common normal ``n`` (the gear's, out of the gear tooth)
a grid point ``q = P0 + s e_s + t e_t`` of the tangent plane defines the line
``q + lambda n``. Each posed flank is intersected with that line exactly (Newton on
``R r(u, v) + c - q - lambda n = 0``, three equations in ``(u, v, lambda)``, analytic
Jacobian ``[R r_u, R r_v, -n]``), and the gap is the separation of the two
intersections along ``n``:

    gap(s, t) = lambda_pinion - lambda_gear      (mm, > 0 open, 0 at P0).

To second order ``gap = (1/2) q^T B q`` with the relative curvature tensor ``B`` of
:mod:`.curvature`, which is what stage C of the preview recovers from the stencil.

Frames (both right-handed with ``n``):

* ``"principal"``: ``e_s`` = major axis of the contact ellipse (direction of
  ``kappa_min``), ``e_t = n x e_s``;
* ``"flank"``: ``e_s = l`` (gear lengthwise, toe -> heel), ``e_t = n x l`` (the
  profile direction; root -> tip on one flank side, tip -> root on the other).

Grids:

* the host field (:func:`gap_field_80`): 80 x 80 cell-centred nodes in the principal
  frame, ``s_k = (k + 1/2 - 40) h_s``, ``h_s = 2 L_s / 80`` (likewise t), with half
  extents ``L_s = 2 a_paint`` and ``L_t = 2 b_paint`` (twice the paint-ellipse
  semi-axes at 6.35 um), so the grid covers the unloaded pattern with margin and
  resolves the narrow direction; for s0003 this is about +-3.6 mm x +-0.5 mm and also
  contains the loaded Hertz ellipse up to 258 N m;
* the hardware stencil (:func:`hardware_stencil`): the baked 7 x 7 grid of
  :mod:`gearcontact.contract.stencil` (spacing ``STENCIL_SPACING_MM``, row-major,
  s fastest) in the **flank** frame; stage C recovers A-, B- independently of the
  rotation of the frame. Written by :func:`write_stencil_csv` as ``gap_stencil.csv``
  (header ``s_mm,t_mm,gap_mm``). A window reaching beyond the flank is filled as chosen
  by ``off_flank`` (:func:`hardware_stencil`).

Points whose line leaves either flank's parameter box are not extrapolated: their gap
is NaN and ``on_flank`` is False, unless ``allow_outside=True`` is given, in which case
the surfaces' analytic continuation is used and ``on_flank`` still records the fact.

Speed: for the flanks of :mod:`gearcontact.geometry` the intersections run compiled
(:mod:`.gap_kernel`), grids swept outwards from P0 with every line started at its
solved neighbour (:func:`_sweep`); other surfaces use the vectorized numpy iteration.
Both give the same gaps to rounding (~1e-13 mm).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache
from inspect import signature
from pathlib import Path

import numpy as np

from ..geometry.kinematics import MeshKinematics
from ..geometry.surface import Surface
from ..contract.stencil import STENCIL_SIDE, STENCIL_SPACING_MM, stencil_coordinates
from ..contract.stencil import write_stencil_csv as write_stencil_file
from ..validation import check_positive
from .curvature import PAINT_THICKNESS_MM, contact_ellipse, relative_curvature
from .gap_kernel import intersect_lines, kernel_surface
from .types import MatingPoint

__all__ = ["GapField", "GAP_GRID_SIDE", "evaluate_many", "gap_at", "gap_field", "gap_field_80",
           "hardware_stencil", "write_stencil_csv", "tangent_frame", "tangent_parameters"]

#: Nodes per side of the host gap field (docs/spec.md sec. 3).
GAP_GRID_SIDE = 80


@dataclass(frozen=True)
class GapField:
    """Gap between the flanks over tangent-plane points around ``P0``.

    Attributes
    ----------
    s_mm, t_mm : ndarray
        Tangent-plane coordinates of the samples, mm (same shape as ``gap_mm``).
    gap_mm : ndarray
        Separation along the common normal, mm (NaN off the flank).
    on_flank : ndarray of bool
        True where both intersections lie inside their parameter boxes.
    origin_mm : ndarray (3,)
        ``P0`` in the meshing frame, mm.
    frame : ndarray (3, 3)
        Columns ``e_s, e_t, n`` in the meshing frame.
    frame_name : str
        ``"principal"`` or ``"flank"``.
    kinks : tuple of str
        The blade-relief kinks (:class:`~gearcontact.geometry.kinked.KinkedFlank`) the
        samples straddle, as ``"<member> <kink>"`` (e.g. ``"pinion toprem"``): across a
        kink the gap's slope jumps and no quadric fits it (empty: none).
    """

    s_mm: np.ndarray
    t_mm: np.ndarray
    gap_mm: np.ndarray
    on_flank: np.ndarray
    origin_mm: np.ndarray
    frame: np.ndarray
    frame_name: str
    kinks: tuple = ()


def tangent_frame(pinion: Surface, gear: Surface, kin: MeshKinematics,
                  mp: MatingPoint, frame: str) -> np.ndarray:
    """Columns ``(e_s, e_t, n)`` of the ``"principal"`` or ``"flank"`` frame at ``mp``."""
    rc = relative_curvature(pinion, gear, kin, mp)
    if frame == "flank":
        e_s = rc.lengthwise
    elif frame == "principal":
        e_s = rc.dir_min
    else:
        raise ValueError(f"frame = {frame!r} is not one of 'principal', 'flank'")
    n = rc.normal
    return np.column_stack([e_s, np.cross(n, e_s), n])


def evaluate_many(surface: Surface, u: np.ndarray, v: np.ndarray):
    """Evaluate a surface at many parameter pairs: ``(r, r_u, r_v)`` as (N, 3) arrays.

    Uses the surface's optional vectorized ``evaluate(u, v)`` (the flanks of
    :mod:`gearcontact.geometry` return arrays with (N, 3) fields; with
    ``second=False`` where supported, as no second derivatives are needed) when it
    has one, else loops over ``point``.
    """
    if hasattr(surface, "evaluate"):
        kw = {"second": False} if _takes_second(type(surface)) else {}
        sp = surface.evaluate(u, v, **kw)
        return np.asarray(sp.r), np.asarray(sp.r_u), np.asarray(sp.r_v)
    pts = [surface.point(float(a), float(b)) for a, b in zip(u, v)]
    return (np.array([p.r for p in pts]), np.array([p.r_u for p in pts]),
            np.array([p.r_v for p in pts]))


@lru_cache(maxsize=64)
def _takes_second(kind: type) -> bool:
    """Whether the ``evaluate`` of a surface type takes ``second`` (looked up once per
    type: a signature costs ~0.1 ms)."""
    return "second" in signature(kind.evaluate).parameters


def _sweep(st: np.ndarray, shape: tuple[int, ...]) -> tuple[np.ndarray, np.ndarray]:
    """Solve order and predecessors of the samples (flattened ``st``, (N, 2)) for the
    compiled intersections: every sample starts from the tangent-plane prediction at an
    already solved neighbour nearer to P0 than itself.

    A 2-D ``shape`` (a grid, row j along t, column k along s) is swept from its centre
    node along the centre row, then out along the columns; other point sets take the
    nearest already solved sample (up to 1024 samples; beyond that none).
    """
    m = st.shape[0]
    if len(shape) == 2 and min(shape) > 1:
        return _grid_sweep(tuple(int(n) for n in shape))
    scale = np.ptp(st, axis=0) if m else np.ones(2)
    scale[scale == 0.0] = 1.0
    x = st / scale
    order = np.argsort(np.einsum("ij,ij->i", x, x), kind="stable")
    prev = np.full(m, -1)
    if 1 < m <= 1024:
        xs = x[order]
        d2 = ((xs[:, None, :] - xs[None, :, :]) ** 2).sum(axis=2)
        d2[np.triu_indices(m)] = np.inf           # only samples solved before
        near = np.argmin(d2, axis=1)
        closer = d2[np.arange(m), near] < np.einsum("ij,ij->i", xs, xs)
        prev[order[closer]] = order[near[closer]]
    return order, prev


@lru_cache(maxsize=16)
def _grid_sweep(shape: tuple[int, int]) -> tuple[np.ndarray, np.ndarray]:
    """:func:`_sweep` of a grid: it depends on the shape alone (one per field size of a
    loaded TE, not one per field)."""
    rows, cols = shape
    jc, kc = rows // 2, cols // 2
    j, k = (a.ravel() for a in np.indices(shape))
    prev = np.where(j != jc, (j - np.sign(j - jc)) * cols + k,
                    np.where(k != kc, j * cols + k - np.sign(k - kc), -1))
    order = np.lexsort((np.abs(k - kc), np.abs(j - jc))).astype(np.int64)
    prev = prev.astype(np.int64)
    for a in (order, prev):
        a.setflags(write=False)
    return order, prev


def _intersect_many(surface: Surface, pose, q: np.ndarray, n: np.ndarray,
                    uv0: np.ndarray, *, clamp: bool, tol_mm: float, max_iter: int = 25,
                    sweep=None, uv_out: np.ndarray | None = None):
    """Intersections of the lines ``q_i + lambda n`` with a posed surface (Newton,
    vectorized over the lines).

    Returns ``(lambda, inside)``: ``lambda`` (N,) is NaN where Newton did not converge
    or, with ``clamp``, where the intersection lies outside the parameter box. The
    flanks of :mod:`gearcontact.geometry` run the same iteration compiled
    (:mod:`.gap_kernel`), started along ``sweep`` (:func:`_sweep`; default: every
    line from ``uv0``); other surfaces run it vectorized in numpy from ``uv0``. Both
    leave the converged intersections' ``(u, v)`` in ``uv_out`` when given (NaN
    elsewhere).
    """
    rot, c = pose
    lo = np.array([surface.u_range[0], surface.v_range[0]], float)
    hi = np.array([surface.u_range[1], surface.v_range[1]], float)
    compiled = kernel_surface(surface)
    if compiled is not None:
        order, prev = sweep if sweep is not None else (np.arange(len(q)), np.full(len(q), -1))
        uv = np.empty((len(q), 2))
        got = intersect_lines(*compiled, np.ascontiguousarray(rot, dtype=float),
                              np.asarray(c, dtype=float), np.ascontiguousarray(q, dtype=float),
                              np.ascontiguousarray(n, dtype=float),
                              np.ascontiguousarray(uv0, dtype=float), lo, hi, bool(clamp),
                              float(tol_mm), int(max_iter), order.astype(np.int64),
                              prev.astype(np.int64), uv)
        if uv_out is not None:
            uv_out[...] = uv
        return got
    uv = uv0.copy()
    lam = np.zeros(len(q))
    active = np.ones(len(q), dtype=bool)
    converged = np.zeros(len(q), dtype=bool)
    for _ in range(max_iter):
        idx = np.flatnonzero(active)
        if idx.size == 0:
            break
        r, r_u, r_v = evaluate_many(surface, uv[idx, 0], uv[idx, 1])
        res = r @ rot.T + c - q[idx] - lam[idx, None] * n
        jac = np.stack([r_u @ rot.T, r_v @ rot.T, np.broadcast_to(-n, r.shape)], axis=2)
        step = np.linalg.solve(jac, -res[..., None])[..., 0]
        new_uv = uv[idx] + step[:, :2]
        if clamp:
            new_uv = np.clip(new_uv, lo, hi)
        moved = np.abs(new_uv - uv[idx]).max(axis=1)
        uv[idx] = new_uv
        lam[idx] += step[:, 2]
        done = (np.abs(res).max(axis=1) < tol_mm) & (moved < 1e-12)
        converged[idx[done]] = True
        active[idx[done]] = False
    inside = converged & np.all((uv > lo) & (uv < hi), axis=1)
    lam = np.where(converged & (inside | ~clamp), lam, np.nan)
    if uv_out is not None:
        uv_out[...] = np.where(converged[:, None], uv, np.nan)
    return lam, inside


def tangent_parameters(surface: Surface, pose, axes: np.ndarray, uv_p0, st: np.ndarray
                       ) -> np.ndarray:
    """Flank parameters (n, 2) of tangent-plane offsets ``st`` (n, 2) (mm, along the
    columns 0, 1 of ``axes``) about the flank point ``uv_p0``, to first order:
    ``(u, v) = uv_p0 + J^-1 st`` with J the tangent-plane components of the posed
    ``r_u``, ``r_v`` (``pose = (R, c)``)."""
    sp = surface.point(*uv_p0)
    jac = axes[:, :2].T @ (pose[0] @ np.column_stack([sp.r_u, sp.r_v]))
    return np.asarray(uv_p0, float) + np.asarray(st, float) @ np.linalg.inv(jac).T


def gap_at(pinion: Surface, gear: Surface, kin: MeshKinematics, mp: MatingPoint,
           s_mm, t_mm, *, frame: str = "principal", allow_outside: bool = False,
           tol_mm: float = 1e-11, axes: np.ndarray | None = None) -> GapField:
    """Gap field at arbitrary tangent-plane points ``(s_mm, t_mm)`` around ``mp``.

    Parameters
    ----------
    pinion, gear : Surface
        The flanks (body frames, normals out of the tooth).
    kin : MeshKinematics
        Kinematics (poses at ``mp.phi1_rad``, ``mp.phi2_rad``).
    mp : MatingPoint
        Interior mating point ``P0``.
    s_mm, t_mm : array_like
        Sample coordinates in the chosen frame, mm (any equal shapes).
    frame : str
        ``"principal"`` or ``"flank"`` (module docstring).
    allow_outside : bool
        Evaluate the flanks' continuation beyond their parameter boxes.
    tol_mm : float
        Newton tolerance of each line-surface intersection, mm.
    axes : ndarray (3, 3), optional
        Columns ``(e_s, e_t, n)`` of an explicit frame (e.g. :func:`edge_gap_field`'s);
        ``frame`` then only names it.
    """
    check_positive("tol_mm", tol_mm)
    s = np.asarray(s_mm, dtype=float)
    t = np.asarray(t_mm, dtype=float)
    if s.shape != t.shape:
        raise ValueError(f"s_mm and t_mm must have equal shapes, got {s.shape} and {t.shape}")
    axes = tangent_frame(pinion, gear, kin, mp, frame) if axes is None else np.asarray(axes, float)
    n = axes[:, 2]
    st = np.column_stack([s.ravel(), t.ravel()])
    q = mp.point_mm + st @ axes[:, :2].T
    lams, insides, kinks = [], [], []
    sweep = _sweep(st, s.shape)
    for member, surf, pose, uv_p0 in (
            ("pinion", pinion, kin.pinion_pose(mp.phi1_rad), (mp.u1, mp.v1)),
            ("gear", gear, kin.gear_pose(mp.phi2_rad), (mp.u2, mp.v2))):
        # Newton starts from the first-order map (s, t) -> (u, v) of the tangent plane
        uv0 = tangent_parameters(surf, pose, axes, uv_p0, st)
        uv = np.full_like(uv0, np.nan)
        lam, inside = _intersect_many(surf, pose, q, n, uv0, clamp=not allow_outside,
                                      tol_mm=tol_mm, sweep=sweep, uv_out=uv)
        lams.append(lam)
        insides.append(inside)
        kinks += [f"{member} {name}" for name in _kinks_crossed(surf, uv)]
    gap = (lams[0] - lams[1]).reshape(s.shape)
    on_flank = (insides[0] & insides[1]).reshape(s.shape)
    return GapField(s, t, gap, on_flank, np.array(mp.point_mm, float), axes, frame,
                    tuple(kinks))


def _kinks_crossed(surface: Surface, uv: np.ndarray) -> list[str]:
    """Names of the kinks of a :class:`~gearcontact.geometry.kinked.KinkedFlank` with
    intersections ``uv`` (n, 2) on both sides; none for a smooth flank."""
    if not hasattr(surface, "kinks"):
        return []
    ok = np.all(np.isfinite(uv), axis=1)
    k = surface.piece_index(uv[ok, 0], uv[ok, 1])
    return [kink.name for kink in surface.kinks
            if np.any(k <= kink.lower) and np.any(k > kink.lower)]


def gap_field(pinion: Surface, gear: Surface, kin: MeshKinematics, mp: MatingPoint,
              *, half_extent_mm: tuple[float, float], side: int = GAP_GRID_SIDE,
              frame: str = "principal", allow_outside: bool = False) -> GapField:
    """Gap on a ``side x side`` cell-centred grid with the given half extents (mm).

    Node ``(j, k)`` (row j along t, column k along s) sits at
    ``s_k = (k + 1/2 - side/2) h_s``, ``t_j = (j + 1/2 - side/2) h_t`` with
    ``h = 2 L / side``.
    """
    ls = check_positive("half_extent_mm[0]", half_extent_mm[0])
    lt = check_positive("half_extent_mm[1]", half_extent_mm[1])
    idx = np.arange(side) + 0.5 - side / 2.0
    s_axis = idx * (2.0 * ls / side)
    t_axis = idx * (2.0 * lt / side)
    s, t = np.meshgrid(s_axis, t_axis)
    return gap_at(pinion, gear, kin, mp, s, t, frame=frame, allow_outside=allow_outside)


def gap_field_80(pinion: Surface, gear: Surface, kin: MeshKinematics, mp: MatingPoint,
                 *, paint_mm: float = PAINT_THICKNESS_MM,
                 allow_outside: bool = False) -> GapField:
    """The documented 80 x 80 host field: principal frame, half extents twice the
    paint-ellipse semi-axes (module docstring)."""
    ell = contact_ellipse(relative_curvature(pinion, gear, kin, mp), paint_mm=paint_mm)
    if not np.isfinite(ell.semi_major_mm):
        raise ValueError("line contact at the mating point: the gap field needs a finite "
                         "contact ellipse (apply an ease-off)")
    return gap_field(pinion, gear, kin, mp,
                     half_extent_mm=(2.0 * ell.semi_major_mm, 2.0 * ell.semi_minor_mm),
                     frame="principal", allow_outside=allow_outside)


def hardware_stencil(pinion: Surface, gear: Surface, kin: MeshKinematics,
                     mp: MatingPoint, *, spacing_mm: float = STENCIL_SPACING_MM,
                     frame: str = "flank", off_flank: str = "nan") -> GapField:
    """The 49 gap samples of the 7 x 7 stage-C stencil, in the baked order (flat arrays).

    Parameters
    ----------
    off_flank : str
        What a sample whose normal line misses a flank gets (``on_flank`` is False
        there in every case):

        * ``"nan"`` - NaN (not writable as a hardware stencil);
        * ``"continuation"`` - the surfaces' own continuation beyond their parameter
          boxes (exact for analytic flanks; unreliable for interpolated ones);
        * ``"quadric"`` - where the window leaves the flank, the osculating quadric
          of the gap at P0, ``Q(q) = (1/2) q^T B q`` with the relative curvature
          tensor B of :mod:`.curvature`, at **every** sample of the window, so that
          stage C reads exactly the P0 curvatures there. A window over a flank edge
          (path ends, edge pairs of the loaded TE, small teeth, bearings at the tip)
          has no gap to sample beyond the edge, and a mixture of the true gap with
          any fill biases the fit: the point-symmetric stencil cancels the gap's cubic
          terms only in pairs ``(q, -q)`` wholly on the flank and spreads its quartic
          terms by the pairs it has. With ``Q`` beside the true samples the ISO
          23509 F3 pair's path ends read B- = 4.9e-7 1/mm for the TCA's 2.45e-4 (the
          twin refused the pair), and completing each pair to ``Q`` still left
          s0003-centred's coast path ends 58 % low (docs/twin.md). A window on the
          flank carries the true gap (stage C's own quartic bias: +5 % on s0003's
          B-, ``tests/tca/test_s0003.py``).
    """
    if off_flank not in ("nan", "continuation", "quadric"):
        raise ValueError(f"off_flank = {off_flank!r} is not 'nan', 'continuation' or 'quadric'")
    s, t = stencil_coordinates(spacing_mm)
    field = gap_at(pinion, gear, kin, mp, s, t, frame=frame,
                   allow_outside=off_flank == "continuation")
    if off_flank != "quadric" or field.on_flank.all():
        return field
    rc = relative_curvature(pinion, gear, kin, mp)
    # B in the stencil frame: rotate the flank-frame tensor (l, p) onto (e_s, e_t)
    rot = np.column_stack([rc.lengthwise, rc.profile]).T @ field.frame[:, :2]
    tensor = rot.T @ rc.tensor_per_mm @ rot
    q = np.column_stack([s, t])
    quad = 0.5 * np.einsum("ni,ij,nj->n", q, tensor, q)
    return GapField(field.s_mm, field.t_mm, quad, field.on_flank, field.origin_mm,
                    field.frame, field.frame_name, field.kinks)


def write_stencil_csv(field: GapField, path) -> Path:
    """Write a 49-sample stencil as ``gap_stencil.csv`` through the format owner,
    :func:`gearcontact.contract.stencil.write_stencil_csv` (read it back with
    :func:`~gearcontact.contract.stencil.read_stencil_csv`). Raises ``ValueError``
    if a sample lies off the flank without a fill (NaN)."""
    if field.gap_mm.size != STENCIL_SIDE * STENCIL_SIDE:
        raise ValueError(f"a hardware stencil has {STENCIL_SIDE ** 2} samples, "
                         f"got {field.gap_mm.size}")
    gaps = field.gap_mm.ravel()
    if not np.all(np.isfinite(gaps)):
        bad = int(np.argmin(np.isfinite(gaps)))
        raise ValueError(f"stencil sample {bad} lies off the flank (gap is NaN); "
                         "choose an off_flank fill in hardware_stencil")
    spacing = float(field.s_mm.ravel()[1] - field.s_mm.ravel()[0])
    return write_stencil_file(path, gaps, spacing_mm=spacing)
