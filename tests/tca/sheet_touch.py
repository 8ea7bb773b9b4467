"""Brute-force first touch of a pinion sheet and a gear sheet at one pinion phase: the
independent truth of the TCA's edge-contact search (plain numpy, no Newton, no Brent).

Both flanks are angle sheets (:class:`~gearcontact.geometry.sheet.RadialSheet` about the
pinion axis, :class:`~gearcontact.geometry.sheet.GearSheet` about the gear axis), so:

- a pinion point, posed at the pinion phase, keeps its radius and height about the gear
  axis while the gear turns; the gear sheet's ``(u, v)`` at that radius and height is
  the cone's exact inverse (``GearCone.parameters``), and the gear turn that brings the
  gear flank onto the point is ``side (theta - psi_gear(u, v))`` (``theta`` its azimuth
  about the gear axis): no iteration;
- a gear point's touch with the pinion sheet is the zero of its angular offset from the
  sheet about the pinion axis as the gear turns, found by bisection (60 halvings of a
  +-3e-4 rad window about a given turn).

The first touch of the pair (the gear pushed towards -phi2 rests on the smallest turn,
towards +phi2 on the largest: :mod:`gearcontact.tca.mesh`) is the extreme over dense
samples of the pinion's whole box (interior and its four boundary curves) and of the
gear's four boundary curves (a gear interior point touching the pinion interior is the
same contact as the pinion point it touches), each sample set zoomed eight times about
its best sample (41 samples over +-3 spacings; a 2-D window is moved without
shrinking while its best sample lies on its outer ring). A point beyond the other
sheet's box touches nothing.
"""

from __future__ import annotations

import numpy as np

#: Samples of the pinion box (profile x lengthwise) and of each boundary curve.
GRID = (150, 200)
EDGE_POINTS = 2000
#: Zoom levels about the best sample, the moves of a window a level and the
#: well-separated interior seeds zoomed.
ZOOMS = 8
MOVES = 50
SEEDS = 4
#: Bisection window about the given gear turn (rad) and its halvings.
WINDOW_RAD = 3e-4
HALVINGS = 60


def _wrap(a):
    return (a + np.pi) % (2.0 * np.pi) - np.pi


def _box(sheet) -> tuple[float, float, float, float]:
    return (*sheet.u_range, *sheet.v_range)


def _inside(box, u, v):
    return (u >= box[0]) & (u <= box[1]) & (v >= box[2]) & (v <= box[3])


class SheetTouch:
    """The gear turn at which each sampled point of a pinion or gear sheet touches the
    other sheet, the pinion held at ``phi1_rad`` (``kin``: the pair's kinematics)."""

    def __init__(self, pinion, gear, kin, phi1_rad: float):
        self.pinion, self.gear = pinion, gear
        self.side = float(kin.gear_axis[2])
        self.rot1, self.c1 = kin.pinion_pose(phi1_rad)
        self.t2 = kin.gear_pose(0.0)[1]

    def pinion_point(self, u, v, near_rad: float):
        """Gear turn (rad, within pi of ``near_rad``) touching pinion point (u, v); NaN
        where its radius and height about the gear axis are off the gear's box."""
        cone = self.pinion.cone
        rad, psi = cone.radius_mm(u, v), self.pinion.psi(u, v)
        r = np.stack([v + 0.0 * u, rad * np.cos(psi), rad * np.sin(psi)], -1)
        x = r @ self.rot1.T + self.c1 - self.t2
        u2, v2 = self.gear.cone.parameters(x[..., 2], np.hypot(x[..., 0], x[..., 1]))
        ok = _inside(_box(self.gear), u2, v2)
        psi2 = self.gear.psi(np.where(ok, u2, self.gear.u_range[0]),
                             np.where(ok, v2, self.gear.v_range[0]))
        turn = self.side * (np.arctan2(x[..., 1], x[..., 0]) - psi2)
        return np.where(ok, near_rad + _wrap(turn - near_rad), np.nan)

    def _offset(self, r2, turn):
        """Angle of the posed gear point about the pinion axis off the pinion sheet, and
        its pinion ``(u, v)``."""
        c, s = np.cos(self.side * turn), np.sin(self.side * turn)
        x = np.stack([c * r2[..., 0] - s * r2[..., 1], s * r2[..., 0] + c * r2[..., 1],
                      r2[..., 2]], -1) + self.t2
        q = (x - self.c1) @ self.rot1
        u1, v1 = self.pinion.cone.parameters(q[..., 0], np.hypot(q[..., 1], q[..., 2]))
        return _wrap(np.arctan2(q[..., 2], q[..., 1]) - self.pinion.psi(u1, v1)), u1, v1

    def gear_point(self, u, v, near_rad: float):
        """Gear turn (rad) touching gear point (u, v) with the pinion sheet, by bisection
        in ``near_rad +- WINDOW_RAD``; NaN without a sign change there or off the
        pinion's box."""
        cone, psi = self.gear.cone, self.gear.psi(u, v)
        rad = cone.radius_mm(u, v)
        r2 = np.stack([rad * np.cos(psi), rad * np.sin(psi), cone.height_mm(u, v)], -1)
        a, b = np.full(u.shape, near_rad - WINDOW_RAD), np.full(u.shape, near_rad + WINDOW_RAD)
        fa, fb = self._offset(r2, a)[0], self._offset(r2, b)[0]
        ok = np.sign(fa) != np.sign(fb)
        for _ in range(HALVINGS):
            m = 0.5 * (a + b)
            fm = self._offset(r2, m)[0]
            left = np.sign(fm) == np.sign(fa)
            a, fa, b = np.where(left, m, a), np.where(left, fm, fa), np.where(left, b, m)
        m = 0.5 * (a + b)
        _, u1, v1 = self._offset(r2, m)
        return np.where(ok & _inside(_box(self.pinion), u1, v1), m, np.nan)


def _grid(box, n_u, n_v):
    return np.meshgrid(np.linspace(box[0], box[1], n_u), np.linspace(box[2], box[3], n_v),
                       indexing="ij")


def _zoom(f, box, u, v, best, sign):
    """Zoom a 2-D sample about ``best`` (u, v, turn) ``ZOOMS`` times: a window of +-3
    spacings, 41 x 41 samples, moved without shrinking while its best sample lies on its
    outer ring inside the box (a long flat valley, nearly a contact line), at most
    ``MOVES`` times a level."""
    h = ((box[1] - box[0]) / (u - 1), (box[3] - box[2]) / (v - 1))
    uc, vc, turn = best
    for _ in range(ZOOMS):
        for _ in range(MOVES):
            sub = (max(box[0], uc - 3 * h[0]), min(box[1], uc + 3 * h[0]),
                   max(box[2], vc - 3 * h[1]), min(box[3], vc + 3 * h[1]))
            uu, vv = _grid(sub, 41, 41)
            t = f(uu, vv)
            if not np.isfinite(t).any() or np.nanmax(sign * t) < sign * turn:
                return uc, vc, turn
            j = np.unravel_index(np.nanargmax(sign * t), uu.shape)
            uc, vc, turn = float(uu[j]), float(vv[j]), float(t[j])
            ring = (j[0] in (0, 40) and uc not in box[:2]) or (j[1] in (0, 40)
                                                               and vc not in box[2:])
            if not ring:
                break
        h = ((sub[1] - sub[0]) / 40, (sub[3] - sub[2]) / 40)
    return uc, vc, turn


def _edge_curves(box):
    """``(name, (u, v) of s)`` of the box's four boundary curves and their spans."""
    return (("root", lambda s: (np.full_like(s, box[0]), s), box[2], box[3]),
            ("tip", lambda s: (np.full_like(s, box[1]), s), box[2], box[3]),
            ("toe", lambda s: (s, np.full_like(s, box[2])), box[0], box[1]),
            ("heel", lambda s: (s, np.full_like(s, box[3])), box[0], box[1]))


def first_touch(pinion, gear, kin, phi1_rad: float, *, near_rad: float,
                forward: bool) -> list[dict]:
    """Every sample set's first touch at pinion phase ``phi1_rad``, best first: dicts
    ``where`` (``"pinion"`` interior grid, ``"pinion heel"``, ``"gear toe"``, ...), ``u``,
    ``v`` (that member's parameters, mm) and ``phi2_rad`` (the gear turn). ``forward``:
    the gear pushed towards +phi2 (the first touch the largest turn)."""
    touch = SheetTouch(pinion, gear, kin, phi1_rad)
    sign = 1.0 if forward else -1.0
    found = []
    box1 = _box(pinion)
    u0, v0 = _grid(box1, *GRID)

    def on_pinion(u, v):
        return touch.pinion_point(u, v, near_rad)

    t0 = on_pinion(u0, v0)
    seeds: list = []
    for i in np.argsort(np.where(np.isfinite(t0), -sign * t0, np.inf), axis=None):
        if not np.isfinite(t0.flat[i]) or len(seeds) == SEEDS:
            break
        iu, iv = np.unravel_index(i, u0.shape)
        if all(abs(iu - a) > 5 or abs(iv - b) > 5 for a, b in seeds):
            seeds.append((iu, iv))
    for iu, iv in seeds:
        uc, vc, turn = _zoom(on_pinion, box1, GRID[0], GRID[1],
                             (float(u0[iu, iv]), float(v0[iu, iv]), float(t0[iu, iv])), sign)
        found.append(dict(where="pinion", u=uc, v=vc, phi2_rad=turn))
    for member, sheet, f in (("pinion", pinion, touch.pinion_point),
                             ("gear", gear, touch.gear_point)):
        for name, curve, lo, hi in _edge_curves(_box(sheet)):
            s, best = np.linspace(lo, hi, EDGE_POINTS), None
            level = moves = 0
            while level < ZOOMS:
                u, v = curve(s)
                t = f(u, v, near_rad)
                if not np.isfinite(t).any():
                    break
                i = int(np.nanargmax(sign * t))
                if best is None or sign * t[i] >= sign * best["phi2_rad"]:
                    best = dict(where=f"{member} {name}", u=float(u[i]), v=float(v[i]),
                                phi2_rad=float(t[i]))
                ds = s[1] - s[0]
                # a best sample at the window's end inside the curve: moved, not shrunk
                if s.size == 41 and i in (0, 40) and s[i] not in (lo, hi) and moves < MOVES:
                    moves, half = moves + 1, 20 * ds
                else:
                    level, moves, half = level + 1, 0, 3 * ds
                s = np.linspace(max(lo, s[i] - half), min(hi, s[i] + half), 41)
            if best is not None:
                found.append(best)
    return sorted(found, key=lambda r: -sign * r["phi2_rad"])
