"""The active box of a flank cut from machine settings (:mod:`.generated`): where the
generated flank ends towards the root, and the node margin below it.

- :func:`active_box`: the nominal box (root to tip, face width) with its root raised to
  the line the top of the blade's edge round generates (below it the round cuts the
  root fillet, :mod:`.fillet`) or, where the envelope folds first (a limit line), to
  the last regular height plus the node margin (Litvin & Fuentes 2004, sec. 6.3-6.4).
- The node grid behind the flank's spline extends :data:`~.conjugate.NODE_MARGIN_MM`
  beyond the box; those nodes are solved on the envelope of the blade's straight (or
  curved) profile continued past the edge round's top towards the tip plane. Near an
  undercut (the toe of a hypoid pinion's convex flank, a low pinion tooth count) that
  envelope can fold *within the margin* below the edge line: the box's root is then
  raised so that the nodes keep their margin inside the regular envelope
  (:func:`margin_root`), as :func:`~.conjugate.pinion_active_box` does for the
  conjugate pinion. Traced on the node grid's own lengthwise extent (its toe and heel
  columns lie a margin beyond the face). The tip is the blank's and is not lowered: an
  envelope folding within the margin above it is refused before the node grid
  (:func:`check_tip_margin`).

References
----------
F. L. Litvin, A. Fuentes, *Gear Geometry and Applied Theory*, 2nd ed., 2004, sec. 6.3-6.4
(limit lines of an envelope).
"""

from __future__ import annotations

import dataclasses

import numpy as np

from .conjugate import NODE_MARGIN_MM, UndercutError
from .formate import FlankBoundary
from .machine import MachineSetup, edge_round
from .print_words import INCH_MM

__all__ = ["LIMIT_FRACTION", "active_box", "check_tip_margin", "edge_length_mm", "edge_radius_bound_mm", "inch_hint",
           "margin_root"]

#: Lengthwise sections and profile steps that trace the line the blade's edge top
#: generates (the lower end of the active flank).
_SECTIONS, _MARCH_STEPS = 9, 24
#: The active profile ends where |det J| falls below this fraction of the mean node's
#: (towards a limit line the curvature grows without bound; as :mod:`.conjugate`).
_CUSP_FRACTION = 0.1
#: |det J| below this fraction of the mean node's: the node grid refuses a singular
#: envelope there (:mod:`.generated`), so :func:`check_tip_margin` refuses it first.
LIMIT_FRACTION = 1e-3
#: Profile steps of the margin check (:func:`margin_root`) and bisection steps that
#: locate a fold within one step (to ``step / 2**_BISECTIONS``, ~1e-8 mm).
_FOLD_STEPS, _BISECTIONS = 32, 22


def edge_length_mm(setup: MachineSetup) -> float:
    """Blade arc length from the tip to the top of the edge round (the round's tangent
    point, :func:`~.machine.edge_round`; 0 for a sharp tip), mm."""
    if setup.blade.edge_radius_mm == 0.0:
        return 0.0
    return edge_round(setup.blade).top_length_mm


def edge_radius_bound_mm(setup: MachineSetup, l_node_mm: float) -> float:
    """The largest edge radius of ``setup``'s blade whose round ends below the blade arc
    length ``l_node_mm`` (:func:`edge_length_mm` grows with the radius): bisection on
    ``[0, the typed radius]`` to 1e-4 mm, the lower end returned (a radius that clears
    the node), mm; 0 for ``l_node_mm <= 0``."""
    if l_node_mm <= 0.0:
        return 0.0

    def top(r_mm: float) -> float:
        return edge_length_mm(dataclasses.replace(
            setup, blade=dataclasses.replace(setup.blade, edge_radius_mm=r_mm)))

    lo, hi = 0.0, setup.blade.edge_radius_mm
    while hi - lo > 1e-4:
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if top(mid) < l_node_mm else (lo, mid)
    return lo


def inch_hint(blade, bound_mm: float) -> str:
    """``" (25.4 times too large? r/25.4 mm keeps it)"`` where the blade's edge radius
    read as inches converted twice (:data:`~.print_words.INCH_MM`) is within
    ``bound_mm``, else ``""``."""
    r = blade.edge_radius_mm / INCH_MM
    return f" (25.4 times too large? {r:.4g} mm keeps it)" if r <= bound_mm else ""


def _section_q(solver, vs: np.ndarray, u_m: float, v_m: float, q_mean: np.ndarray) -> np.ndarray:
    """Node solutions ``(l, theta, psi)`` at height ``u_m`` on the sections ``vs``, by
    continuation along the face from the mean node (four steps per section)."""
    q = np.empty((len(vs), 3))
    for order in (np.flatnonzero(vs >= v_m), np.flatnonzero(vs < v_m)[::-1]):
        prev, v_prev = q_mean, v_m
        for k in order:
            for v in np.linspace(v_prev, vs[k], 5)[1:]:
                prev = solver.solve(u_m, v, prev).q
            q[k], v_prev = prev, vs[k]
    return q


def _regular(s, det_min: float) -> np.ndarray:
    """Converged nodes whose node Jacobian is at least ``det_min`` (away from a fold)."""
    return s.converged & (np.abs(s.jacobian_det) >= det_min)


def active_box(solver, nominal: FlankBoundary, u_m: float, v_m: float, mean,
               l_edge: float) -> FlankBoundary:
    """The nominal box with its root raised to the line generated by the top of the blade
    edge round (below it the edge cuts the root fillet) or, where the envelope folds
    first (limit line: no solution, or ``|det J|`` below ``_CUSP_FRACTION`` of the mean
    node's), to the last regular height plus the node margin. Traced on ``_SECTIONS``
    lengthwise sections from the mean height downwards; the box's root is the highest
    such height over the sections (Litvin & Fuentes 2004, sec. 6.3-6.4), raised further
    where the envelope folds within the node margin below it (:func:`margin_root`). The
    tip is the blank's: an envelope folding within the node margin above it is refused
    (:func:`check_tip_margin`).

    ``solver`` is the flank's :class:`~.generated.EnvelopeSolver`, ``mean`` its mean
    node's solution at ``(u_m, v_m)``, ``l_edge`` the blade arc length of the edge
    round's top (:func:`edge_length_mm`).

    Raises
    ------
    UndercutError
        An active profile under 10 % of the nominal one; a fold within the node margin
        above the tip (:func:`check_tip_margin`).
    """
    vs = np.linspace(nominal.v_toe, nominal.v_heel, _SECTIONS)
    q = _section_q(solver, vs, u_m, v_m, mean.q)
    det_min = _CUSP_FRACTION * abs(float(mean.jacobian_det))
    ends = np.full(len(vs), nominal.u_root)
    alive = np.ones(len(vs), dtype=bool)
    u_prev, l_prev = np.full(len(vs), u_m), q[:, 0].copy()
    for u in np.linspace(u_m, nominal.u_root - NODE_MARGIN_MM[0], _MARCH_STEPS + 1)[1:]:
        s = solver.solve(np.full(len(vs), u), vs, q, strict=False)
        lost = alive & ~_regular(s, det_min)
        ends = np.where(lost, u_prev + NODE_MARGIN_MM[0], ends)
        crossed = alive & ~lost & ((s.l_mm - l_edge) * (l_prev - l_edge) <= 0.0)
        frac = (l_edge - l_prev) / np.where(s.l_mm == l_prev, 1.0, s.l_mm - l_prev)
        ends = np.where(crossed, np.maximum(u_prev + frac * (u - u_prev), nominal.u_root), ends)
        alive &= ~(lost | crossed)
        if not alive.any():
            break
        q = np.where(alive[:, None], s.q, q)
        u_prev, l_prev = np.where(alive, u, u_prev), np.where(alive, s.l_mm, l_prev)
    u_root = margin_root(solver, nominal, float(np.max(ends)), u_m=u_m, v_m=v_m, mean=mean,
                         det_min=det_min)
    check_tip_margin(solver, nominal, u_m=u_m, v_m=v_m, mean=mean,
                     det_min=LIMIT_FRACTION * abs(float(mean.jacobian_det)))
    if not nominal.u_tip - u_root > 0.1 * (nominal.u_tip - nominal.u_root):
        raise UndercutError(f"{solver.setup.member} {solver.setup.side} flank active profile",
                            (u_root, nominal.u_tip),
                            "a generated profile of at least 10 % of the working depth (the "
                            "blade edge line / limit line leave less: check the settings)")
    return FlankBoundary(u_root=u_root, u_tip=nominal.u_tip, v_toe=nominal.v_toe,
                         v_heel=nominal.v_heel)


def margin_root(solver, nominal: FlankBoundary, u_root: float, *, u_m: float, v_m: float,
                mean, det_min: float) -> float:
    """The root height of the active box that keeps the node grid's bottom row
    (``u_root - NODE_MARGIN_MM[0]``, over the node grid's lengthwise extent
    ``[v_toe, v_heel]`` widened by ``NODE_MARGIN_MM[1]``) on the regular envelope.

    Each of ``_SECTIONS`` lengthwise sections is marched down from the mean height to
    that row; where the envelope is lost first (no solution, or ``|det J| < det_min``),
    the last regular height is located by bisection, and the root is raised to the
    highest such height plus the margin. ``u_root`` itself (mm) where nothing folds
    (the flank of a pair without a fold in its margin is unchanged, bit for bit).
    """
    vs = _margin_sections(nominal)
    fold = _fold_heights(solver, vs, _section_q(solver, vs, u_m, v_m, mean.q), u_m,
                         u_root - NODE_MARGIN_MM[0], det_min)
    return max(u_root, float(np.max(np.where(np.isnan(fold), -np.inf, fold)))
               + NODE_MARGIN_MM[0])


def check_tip_margin(solver, box: FlankBoundary, *, u_m: float, v_m: float, mean,
                     det_min: float) -> None:
    """Refuse a flank whose envelope folds below the node grid's top row
    (``u_tip + NODE_MARGIN_MM[0]``, over the node grid's lengthwise extent): the box's tip
    is the blank's, so it is not lowered (as :func:`margin_root` raises the root), and the
    node grid could not be solved there.

    Each of ``_SECTIONS`` lengthwise sections is marched up from the mean height to that
    row (``_FOLD_STEPS`` steps, the fold located by bisection as in
    :func:`margin_root`); ``det_min`` is the node grid's own bound
    (:data:`LIMIT_FRACTION` of the mean node's ``|det J|``), so that only a flank whose
    node grid would fail is refused, before the grid is solved. A fold there is a flank whose normal turns into the member's
    axial plane (``|det J|`` of the node equations vanishes while the generated surface
    stays regular): the flank turns over towards the tip (docs/machine_settings.md sec. 5,
    "A fold at the tip", measures one whose tooth is pointed there).

    Raises
    ------
    UndercutError
        Naming the flank's settings, the fold's height against the box's tip and its
        lengthwise position against the box.
    """
    vs = _margin_sections(box)
    u_top = box.u_tip + NODE_MARGIN_MM[0]
    fold = _fold_heights(solver, vs, _section_q(solver, vs, u_m, v_m, mean.q), u_m, u_top,
                         det_min)
    if np.all(np.isnan(fold)):
        return
    k = int(np.nanargmin(fold))
    setup = solver.setup
    where = ("toe" if vs[k] < box.v_toe else "heel" if vs[k] > box.v_heel else "face")
    raise UndercutError(
        f"[machine.{setup.member}.{setup.side}] / [blade.{setup.member}.{setup.side}] "
        f"(blade point radius {setup.blade.point_radius_mm:.4g} mm)",
        f"a fold of the generated {setup.member} {setup.side} flank at u = {fold[k]:.4f} mm "
        f"(tip {fold[k] - box.u_tip:+.4f} mm), v = {vs[k]:.4f} mm ({where}: the box is "
        f"v = [{box.v_toe:.4f}, {box.v_heel:.4f}] mm)",
        f"an envelope regular to the node grid's top row u = {u_top:.4f} mm (tip + "
        f"{NODE_MARGIN_MM[0]:g} mm) over v = [{vs[0]:.4f}, {vs[-1]:.4f}] mm (the node equations "
        "turn singular where the flank's normal turns into the axial plane: the flank turns "
        "over towards the tip)"
        + (_STANDARD_HINT if setup.member == "pinion" else "")
        + '; docs/machine_settings.md sec. 5, "A fold at the tip"')


#: What removes a tip fold of a pinion cut with standard settings (measured,
#: docs/machine_settings.md sec. 5, "A fold at the tip").
_STANDARD_HINT = (
    ". Standard settings (`design --machine-settings`) of a narrow face "
    "(design.gear_face_width_mm) get such a pinion cutter radius from the standard "
    "lengthwise crowning, and the fold moves into the flank as the spiral angle "
    "(design.pinion_spiral_angle_deg) grows: a wider face or less crowning "
    "(--lengthwise-crowning-um) removes it")


def _margin_sections(box: FlankBoundary) -> np.ndarray:
    """The ``_SECTIONS`` lengthwise sections over the node grid's extent (``box``'s
    widened by ``NODE_MARGIN_MM[1]``), mm."""
    return np.linspace(box.v_toe - NODE_MARGIN_MM[1], box.v_heel + NODE_MARGIN_MM[1],
                       _SECTIONS)


def _fold_heights(solver, vs: np.ndarray, q: np.ndarray, u_m: float, u_end: float,
                  det_min: float) -> np.ndarray:
    """Per section ``vs`` (solutions ``q`` at the mean height ``u_m``): marched in
    ``_FOLD_STEPS`` steps towards ``u_end``, the last regular height before the envelope
    is lost (bisection, :func:`_last_regular`), or NaN where it stays regular, mm."""
    fold = np.full(len(vs), np.nan)
    alive = np.ones(len(vs), dtype=bool)
    u_prev = np.full(len(vs), u_m)
    for u in np.linspace(u_m, u_end, _FOLD_STEPS + 1)[1:]:
        s = solver.solve(np.full(len(vs), u), vs, q, strict=False)
        lost = alive & ~_regular(s, det_min)
        for k in np.flatnonzero(lost):
            fold[k] = _last_regular(solver, vs[k], u_prev[k], u, q[k], det_min)
        alive &= ~lost
        if not alive.any():
            break
        q = np.where(alive[:, None], s.q, q)
        u_prev = np.where(alive, u, u_prev)
    return fold


def _last_regular(solver, v: float, u_ok: float, u_lost: float, q_ok: np.ndarray,
                  det_min: float) -> float:
    """The lowest height between the regular ``u_ok`` (solution ``q_ok``) and ``u_lost``
    on section ``v`` where the envelope is still regular, by bisection, mm."""
    for _ in range(_BISECTIONS):
        u = 0.5 * (u_ok + u_lost)
        s = solver.solve(u, v, q_ok, strict=False)
        if bool(_regular(s, det_min)):
            u_ok, q_ok = u, s.q
        else:
            u_lost = u
    return u_ok
