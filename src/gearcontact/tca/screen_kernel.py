"""Compiled (numba) edge screen of :mod:`.edge_screen`.

:func:`~.edge_screen.edge_gaps` bounds, at one surface contact, the turn gap of every
edge of both flanks from below: each edge sampled evenly, each sample's turn gap
solved by Newton's method on ``S(a, b) = R_z(turn delta) q``, the intervals between
samples bounded by their curvature and halved where the bound is not positive
(docs/machine_settings.md sec. 5, "The edge check while the surface contact is
inside"). :func:`screen` runs the same procedure in compiled code when both flanks have
a kernel form (:func:`~gearcontact.tca.gap_kernel.kernel_surface`), step for step:

* the edge point ``(u, v)`` of :func:`~.edge_contact.edge_parameters` (a ridge's
  ``u_k(s)`` from :func:`~gearcontact.geometry.kinked.kink_u`, clipped into the box),
  the flank points from :func:`~gearcontact.tca.gap_kernel.flank_vector`;
* the same Newton iteration (start, update, stopping rule, the points given up), the
  3 x 3 systems by :func:`~gearcontact.tca.gap_kernel.solve3` where the numpy path
  calls LAPACK;
* the same interval bounds (:func:`~.edge_screen.interval_bounds`, the same arithmetic)
  and the same halvings, each interval's halvings depth first (the lowest bound of an
  edge is a minimum, the same whatever the order).

Flank evaluation and the 3 x 3 solves agree with the numpy path to rounding, not bit
for bit: a bound may differ by ~1e-15 rad (tests/tca/test_edge_screen.py).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from .edge_kernel import edge_point
from .gap_kernel import flank_vector, solve3

__all__ = ["point_turn", "sample_bounds", "screen"]


@njit(cache=True)
def point_turn(okd, opa, otx, oty, opc, okx, okc, okn,
               tkd, tpa, ttx, tty, tpc, tkx, tkc, tkn,
               code, kink, own_box, oth_box, s, rot_own, c_own, rot_oth, c_oth, turn,
               a0, b0, delta0, tol_mm, max_iter, out):
    """The extra gear turn ``delta`` that brings the point ``s`` of an edge of the own
    flank (kernel form ``o*``) onto the other flank (``t*``): ``out = (delta, a, b)``,
    delta NaN where Newton does not converge (module docstring).

    ``code``, ``kink``: the edge (:data:`~.edge_kernel.EDGE_CODES`, a kink line's index);
    ``own_box``, ``oth_box``: ``(u0, u1, v0, v1)``; ``rot_*``, ``c_*``: the poses, the
    centres already less the gear's; ``turn``: the axis sign of the edge point's turn;
    ``(a0, b0, delta0)``: the start.
    """
    u, v = edge_point(code, kink, okx, okc, okn, own_box, s)
    d = np.zeros(6)
    vec = np.empty((7, 3))
    flank_vector(okd, opa, otx, oty, opc, okx, okc, okn, u, v, d, vec)
    q = np.empty(3)
    for i in range(3):
        q[i] = (rot_own[i, 0] * vec[0, 0] + rot_own[i, 1] * vec[0, 1]
                + rot_own[i, 2] * vec[0, 2]) + c_own[i]
    u0, u1, v0, v1 = oth_box[0], oth_box[1], oth_box[2], oth_box[3]
    size = max(u1 - u0, v1 - v0)
    a, b, delta = a0, b0, delta0
    jac = np.empty((3, 3))
    rhs = np.empty(3)
    step = np.empty(3)
    res = np.empty(3)
    out[0] = np.nan
    out[1] = a
    out[2] = b
    for _ in range(max_iter):
        flank_vector(tkd, tpa, ttx, tty, tpc, tkx, tkc, tkn, a, b, d, vec)
        c = np.cos(turn * delta)
        sn = np.sin(turn * delta)
        p0 = c * q[0] - sn * q[1]
        p1 = sn * q[0] + c * q[1]
        p2 = q[2]
        for i in range(3):
            res[i] = (rot_oth[i, 0] * vec[0, 0] + rot_oth[i, 1] * vec[0, 1]
                      + rot_oth[i, 2] * vec[0, 2]) + c_oth[i] - (p0 if i == 0 else
                                                                  p1 if i == 1 else p2)
        if abs(res[0]) < tol_mm and abs(res[1]) < tol_mm and abs(res[2]) < tol_mm:
            out[0] = delta
            out[1] = a
            out[2] = b
            return
        for i in range(3):
            jac[i, 0] = (rot_oth[i, 0] * vec[1, 0] + rot_oth[i, 1] * vec[1, 1]
                         + rot_oth[i, 2] * vec[1, 2])
            jac[i, 1] = (rot_oth[i, 0] * vec[2, 0] + rot_oth[i, 1] * vec[2, 1]
                         + rot_oth[i, 2] * vec[2, 2])
            rhs[i] = -res[i]
        # -dp/ddelta: dp = turn (-p1, p0, 0)
        jac[0, 2] = -(turn * -p1)
        jac[1, 2] = -(turn * p0)
        jac[2, 2] = -(turn * 0.0)
        det = (jac[0, 0] * (jac[1, 1] * jac[2, 2] - jac[1, 2] * jac[2, 1])
               - jac[0, 1] * (jac[1, 0] * jac[2, 2] - jac[1, 2] * jac[2, 0])
               + jac[0, 2] * (jac[1, 0] * jac[2, 1] - jac[1, 1] * jac[2, 0]))
        if det == 0.0:          # singular: given up (LAPACK's refusal on the numpy path)
            return
        solve3(jac, rhs, step)
        a += step[0]
        b += step[1]
        delta += step[2]
        out[1] = a
        out[2] = b
        if not (np.isfinite(step[0]) and np.isfinite(step[1]) and np.isfinite(step[2])):
            return
        if (abs(delta) > 1.0 or a < u0 - size or a > u1 + size or b < v0 - size
                or b > v1 + size):
            return


@njit(cache=True)
def sample_bounds(d, m, factor, bounds, cd, cm):
    """:func:`~.edge_screen.interval_bounds` of evenly sampled ``(g, margin)`` with the
    default curvatures (the same arithmetic), and those curvatures ``M h^2`` per
    interval into ``cd``, ``cm``."""
    n = d.shape[0]
    for k in range(n - 1):
        # _local_d2: the larger |second difference| at the interval's two ends
        gd = np.nan
        gm = np.nan
        for j in (k, k + 1):
            if 0 < j < n - 1:
                xd = abs((d[j + 1] - d[j]) - (d[j] - d[j - 1]))
                xm = abs((m[j + 1] - m[j]) - (m[j] - m[j - 1]))
                gd = xd if np.isnan(gd) else (gd if np.isnan(xd) else max(gd, xd))
                gm = xm if np.isnan(gm) else (gm if np.isnan(xm) else max(gm, xm))
        cd[k] = factor * gd
        cm[k] = factor * gm
    for k in range(n - 1):
        bounds[k] = _pair_bound(d[k], d[k + 1], m[k], m[k + 1], cd[k], cm[k])
        sa, sb = np.isfinite(d[k]), np.isfinite(d[k + 1])
        if sa != sb:
            if sa:
                ia, ia2 = k, k - 1
            else:
                ia, ia2 = k + 1, k + 2
            if not (0 <= ia2 < n and np.isfinite(d[ia2])):
                bounds[k] = -np.inf
                continue
            j = ia2
            c_g = np.nan
            c_m = np.nan
            if 0 < j < n - 1:
                if np.isfinite(d[j - 1]) and np.isfinite(d[j]) and np.isfinite(d[j + 1]):
                    c_g = factor * abs(d[j - 1] - 2 * d[j] + d[j + 1])
                if np.isfinite(m[j - 1]) and np.isfinite(m[j]) and np.isfinite(m[j + 1]):
                    c_m = factor * abs(m[j - 1] - 2 * m[j] + m[j + 1])
            if not (np.isfinite(c_g) and np.isfinite(c_m)):
                bounds[k] = -np.inf
            elif max(m[ia], 2 * m[ia] - m[ia2] + c_m) < 0.0:
                bounds[k] = np.inf
            else:
                bounds[k] = min(d[ia], 2 * d[ia] - d[ia2] - c_g)


@njit(cache=True, inline="always")
def _pair_bound(d0, d1, m0, m1, cd, cm):
    """The bound of one interval between two samples (both solved: the curvature bound;
    neither: +inf; one: -inf, as :func:`~.edge_screen.interval_bounds` gives it for an
    interval whose solved end has no other neighbour)."""
    s0, s1 = np.isfinite(d0), np.isfinite(d1)
    if not (s0 and s1):
        return -np.inf if s0 or s1 else np.inf
    lower = (d0 if d0 < d1 else d1) - cd / 8.0
    if np.isnan(m0):
        reach = m1
    elif np.isnan(m1):
        reach = m0
    else:
        reach = max(m0, m1)
    reach = reach + cm / 8.0
    out = np.inf if reach < 0.0 else lower
    return -np.inf if np.isnan(out) else out


@njit(cache=True)
def _sample(pin, gear, member, code, kink, boxes, rots, cs, turns, at, s, a0, b0, g0,
            forward, tol_mm, max_iter, got):
    """One sample's ``got = (g, margin, a, b)`` (:func:`screen`), Newton started from
    ``(a0, b0)`` and the turn gap ``g0`` where all are finite, else from the contact."""
    if not (np.isfinite(a0) and np.isfinite(b0) and np.isfinite(g0)):
        a0, b0, g0 = at[member, 0], at[member, 1], 0.0
    out = np.empty(3)
    o, t = member, 1 - member
    delta0 = -g0 if forward else g0
    if member == 0:
        point_turn(pin[0], pin[1], pin[2], pin[3], pin[4], pin[5], pin[6], pin[7],
                   gear[0], gear[1], gear[2], gear[3], gear[4], gear[5], gear[6], gear[7],
                   code, kink, boxes[o], boxes[t], s, rots[o], cs[o], rots[t], cs[t],
                   turns[o], a0, b0, delta0, tol_mm, max_iter, out)
    else:
        point_turn(gear[0], gear[1], gear[2], gear[3], gear[4], gear[5], gear[6], gear[7],
                   pin[0], pin[1], pin[2], pin[3], pin[4], pin[5], pin[6], pin[7],
                   code, kink, boxes[o], boxes[t], s, rots[o], cs[o], rots[t], cs[t],
                   turns[o], a0, b0, delta0, tol_mm, max_iter, out)
    delta, a, b = out[0], out[1], out[2]
    got[0] = -delta if forward else delta
    if np.isfinite(delta):
        box = boxes[t]
        got[1] = min(min(min(a - box[0], box[1] - a), b - box[2]), box[3] - b)
    else:
        got[1] = np.nan
    got[2] = a
    got[3] = b


@njit(cache=True)
def screen(pin, gear, boxes, rots, cs, turns, at, members, codes, kinks, spans,
           start_ab, start_g, forward, tol_mm, max_iter, factor, levels,
           gap_out, margin_out, ab_out, lower_out):
    """The screen of every edge (module docstring; :func:`~.edge_screen.edge_gaps`).

    Parameters
    ----------
    pin, gear : tuple
        Kernel forms of the two flanks.
    boxes, rots, cs, turns : ndarray (2, 4), (2, 3, 3), (2, 3), (2,)
        Per member (pinion, gear): ``(u0, u1, v0, v1)``; its pose at the contact, its
        centre less the gear's, mm; the axis sign of its edge points' turn.
    at : ndarray (2, 2)
        Per member the other flank's contact parameters (the default start), mm.
    members, codes, kinks : ndarray (E,) int
        Per edge its member (0 pinion, 1 gear), edge code and kink index.
    spans : ndarray (E, N)
        The samples of each edge's free parameter, mm.
    start_ab, start_g : ndarray (E, N, 2), (E, N)
        Newton starts per sample (NaN: from the contact).
    forward : bool
        The gear is pushed towards +phi2.
    tol_mm, max_iter, factor, levels
        Newton's tolerance (mm) and iteration limit, the curvature factor, the halvings.
    gap_out, margin_out, ab_out, lower_out
        Per sample ``g`` (rad), margin (mm), ``(a, b)`` (mm); per edge its lower bound.
    """
    n_edge, n = spans.shape
    got = np.empty(4)
    bounds = np.empty(n - 1)
    cd = np.empty(n - 1)
    cm = np.empty(n - 1)
    cap = n + 2 * levels + 4
    # stack rows: (s, g, m, a, b) of both ends, M_g h^2, M_m h^2, depth
    stack = np.empty((cap, 13))
    for e in range(n_edge):
        mem, code, kink = members[e], codes[e], kinks[e]
        for k in range(n):
            _sample(pin, gear, mem, code, kink, boxes, rots, cs, turns, at, spans[e, k],
                    start_ab[e, k, 0], start_ab[e, k, 1], start_g[e, k], forward, tol_mm,
                    max_iter, got)
            gap_out[e, k] = got[0]
            margin_out[e, k] = got[1]
            ab_out[e, k, 0] = got[2]
            ab_out[e, k, 1] = got[3]
        sample_bounds(gap_out[e], margin_out[e], factor, bounds, cd, cm)
        lowest = np.inf
        top = 0
        for k in range(n - 1):
            if np.isfinite(bounds[k]) and bounds[k] <= 0.0 and levels > 0:
                row = stack[top]
                row[0], row[1], row[2] = spans[e, k], gap_out[e, k], margin_out[e, k]
                row[3], row[4] = ab_out[e, k, 0], ab_out[e, k, 1]
                row[5], row[6], row[7] = spans[e, k + 1], gap_out[e, k + 1], margin_out[e, k + 1]
                row[8], row[9] = ab_out[e, k + 1, 0], ab_out[e, k + 1, 1]
                row[10], row[11], row[12] = cd[k], cm[k], 0.0
                top += 1
            else:
                lowest = min(lowest, bounds[k])
        while top > 0:
            top -= 1
            lo = stack[top, 0:5].copy()
            hi = stack[top, 5:10].copy()
            qd, qm, depth = stack[top, 10] / 4.0, stack[top, 11] / 4.0, stack[top, 12]
            s_mid = 0.5 * (lo[0] + hi[0])
            _sample(pin, gear, mem, code, kink, boxes, rots, cs, turns, at, s_mid,
                    0.5 * (lo[3] + hi[3]), 0.5 * (lo[4] + hi[4]), 0.5 * (lo[1] + hi[1]),
                    forward, tol_mm, max_iter, got)
            for half in range(2):
                if half == 0:
                    d0, m0, d1, m1 = lo[1], lo[2], got[0], got[1]
                else:
                    d0, m0, d1, m1 = got[0], got[1], hi[1], hi[2]
                bound = _pair_bound(d0, d1, m0, m1, qd, qm)
                if np.isfinite(bound) and bound <= 0.0 and depth + 1 < levels:
                    row = stack[top]
                    if half == 0:
                        row[0:5] = lo
                        row[5], row[6], row[7], row[8], row[9] = (s_mid, got[0], got[1],
                                                                  got[2], got[3])
                    else:
                        row[0], row[1], row[2], row[3], row[4] = (s_mid, got[0], got[1],
                                                                  got[2], got[3])
                        row[5:10] = hi
                    row[10], row[11], row[12] = qd, qm, depth + 1
                    top += 1
                else:
                    lowest = min(lowest, bound)
        lower_out[e] = lowest
