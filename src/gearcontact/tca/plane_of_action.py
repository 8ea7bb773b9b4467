"""The posed flank pair of one facing of a cylindrical pair and its plane of action:
the batched point solves of the mesh-cycle TCA (:mod:`.cylindrical_cycle`, module
docstring there) and of the tip-edge contact (:mod:`.cylindrical_tip`).

A pinion flank point lies in the plane of action at a roll length ``u1`` affine in the
phase and in ``z`` (exact for unmodified flanks, the start of a Newton solve
otherwise); from it the gear flank is met along the transverse line of action ``d``
(a 3 x 3 Newton ray solve on the posed gear flank, tilted by the ``[assembly]`` errors),
the *gap* ``g`` is that distance (> 0 apart) and ``rate`` its change per gear turn.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from ..geometry.cylindrical.flank import ProfileLeadModification, involute_flank
from ..geometry.cylindrical.pair import CylindricalPair
from .parallel_axes import parallel_kinematics, pitch_point_guess
from .types import TcaConvergenceError

__all__ = ["PlaneOfAction"]

#: Newton iterations of the pinion and gear point solves (both converge quadratically
#: from the affine start; 1e-11 mm is reached in 2-3); more raise TcaConvergenceError.
_NEWTON = 8
#: Residual (mm) at which the point solves stop: a few hundred ulps of the coordinates.
_RESIDUAL_MM = 1e-11


def _turns(angle_rad):
    """Batched rotations about +z by ``angle_rad`` (N,) -> (N, 3, 3)."""
    c, s = np.cos(angle_rad), np.sin(angle_rad)
    zero, one = np.zeros_like(c), np.ones_like(c)
    return np.stack([np.stack([c, -s, zero], -1), np.stack([s, c, zero], -1),
                     np.stack([zero, zero, one], -1)], -2)



class PlaneOfAction:
    """Pose, flanks and the plane of action of one facing of a cylindrical pair
    (vectorized point solves; module docstring)."""

    def __init__(self, pair: CylindricalPair, facing: str):
        self.kin = parallel_kinematics(pair)
        self.pinion = involute_flank(pair, "pinion", facing)
        self.gear = involute_flank(pair, "gear", facing)
        g = pair.geometry
        start = pitch_point_guess(pair, facing)
        self.phi1_p = start.phi1_rad
        self.phi2_offset = start.phi2_rad - start.phi1_rad / pair.ratio
        self.ratio = pair.ratio
        self.rot2_0 = self.kin.gear_pose(0.0)[0]
        self.rot1_0, self.t1 = self.kin.pinion_pose(0.0)
        # the plane of action: through the pitch point along the transverse part of the
        # unmodified pinion normal there (the gear lies along +d)
        ideal = replace(self.pinion, modification=ProfileLeadModification())
        rot1, _ = self.kin.pinion_pose(self.phi1_p)
        n = rot1 @ ideal.evaluate(start.u1, 0.0, second=False).n
        self.d = np.array([n[0], n[1], 0.0]) / math.hypot(n[0], n[1])
        self.m = np.cross([0.0, 0.0, 1.0], self.d)
        self.p0 = np.array([-0.5 * g.working_pitch_diameter_gear_mm, 0.0, 0.0])
        self.roll_sum = g.centre_distance_mm * math.sin(
            math.radians(g.working_pressure_angle_deg))
        # u1 on the plane of action is affine in (phi1, z): fit it from three solves
        u = self._pinion_u(self.phi1_p + np.array([0.0, 1e-3, 0.0]),
                           np.array([0.0, 0.0, 1.0]), np.full(3, start.u1))
        self._u_fit = (u[0], (u[1] - u[0]) / 1e-3, u[2] - u[0])

    def pinion_poses(self, phi1):
        """Batched pinion poses: pinion_pose(phi1) = pinion_pose(0) rot_z(-phi1)."""
        return np.einsum("ij,njk->nik", self.rot1_0, _turns(-phi1)), self.t1

    def gear_rotations(self, phi2):
        """Batched gear rotations: gear_pose(phi2) = gear_pose(0) rot_z(phi2) (the gear
        turns about its own axis; no translation)."""
        return np.einsum("ij,njk->nik", self.rot2_0, _turns(phi2))

    def _pinion_u(self, phi1, z, u):
        rot1, t1 = self.pinion_poses(phi1)
        for _ in range(_NEWTON):
            a = self.pinion.evaluate(u, z, second=False)
            h = (np.einsum("nij,nj->ni", rot1, a.r) + t1 - self.p0) @ self.m
            if np.max(np.abs(h), initial=0.0) < _RESIDUAL_MM:
                return u
            u = u - h / (np.einsum("nij,nj->ni", rot1, a.r_u) @ self.m)
        k = int(np.argmax(np.abs(h)))
        raise TcaConvergenceError(float(phi1[k]), float(abs(h[k])), _NEWTON)

    def pinion_u_affine(self, phi1, z):
        """The affine start of :meth:`pinion_u` (exact for unmodified flanks)."""
        u0, a_phi, a_z = self._u_fit
        return u0 + a_phi * (np.asarray(phi1, float) - self.phi1_p) + a_z * np.asarray(z, float)

    def pinion_u(self, phi1, z):
        """Roll length of the pinion point on the plane of action (NaN where z is)."""
        phi1, z = np.broadcast_arrays(np.asarray(phi1, float), np.asarray(z, float))
        ok = np.isfinite(z)
        zz = np.where(ok, z, 0.0).ravel()
        u = self._pinion_u(phi1.ravel(), zz, self.pinion_u_affine(phi1.ravel(), zz))
        return np.where(ok, u.reshape(z.shape), np.nan)

    def section(self, phi1, z):
        """Per element: pinion point P on the plane of action at axial z, the gear point
        G along d, the gap g, gear (u2, v2), gear normal and the rate dg/dphi2."""
        phi1, z = np.broadcast_arrays(np.asarray(phi1, float), np.asarray(z, float))
        shape = phi1.shape
        phi1, z = phi1.ravel(), z.ravel()
        u1 = self.pinion_u(phi1, z)
        a = self.pinion.evaluate(u1, z, second=False)
        rot1, t1 = self.pinion_poses(phi1)
        P = np.einsum("nij,nj->ni", rot1, a.r) + t1
        phi2 = phi1 / self.ratio + self.phi2_offset
        rot2 = self.gear_rotations(phi2)
        u2, v2, g = self.roll_sum - u1, z.copy(), np.zeros_like(z)
        for _ in range(_NEWTON):
            b = self.gear.evaluate(u2, v2, second=False)
            G = np.einsum("nij,nj->ni", rot2, b.r)
            res = G - P - g[:, None] * self.d
            if np.max(np.abs(res), initial=0.0) < _RESIDUAL_MM:
                break
            jac = np.stack([np.einsum("nij,nj->ni", rot2, b.r_u),
                            np.einsum("nij,nj->ni", rot2, b.r_v),
                            np.broadcast_to(-self.d, G.shape)], axis=-1)
            step = np.linalg.solve(jac, -res[..., None])[..., 0]
            u2, v2, g = u2 + step[:, 0], v2 + step[:, 1], g + step[:, 2]
        else:
            k = int(np.argmax(np.abs(res).max(axis=1)))
            raise TcaConvergenceError(float(phi1[k]), float(np.linalg.norm(res[k])), _NEWTON)
        b = self.gear.evaluate(u2, v2, second=False)
        G = np.einsum("nij,nj->ni", rot2, b.r)
        n2 = np.einsum("nij,nj->ni", rot2, b.n)
        rate = np.cross(self.kin.gear_axis, G) @ self.d
        out = dict(u1=u1, P=P, u2=u2, v2=v2, g=g, G=G, n2=n2, rate=rate, phi2=phi2)
        return {k: (v.reshape(shape + v.shape[1:])) for k, v in out.items()}

    def gap(self, phi1, z):
        return self.section(phi1, z)["g"]
