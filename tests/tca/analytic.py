"""Analytic flank stand-ins with closed-form contact, for testing the TCA machinery.

A sphere (radius ``Rs``) on the pinion meshes with a torus (core radius ``Rt``, tube
radius ``r``) on the gear under :class:`MeshKinematics`. Independent truth:

* contact at pinion phase phi1 <=> distance(sphere centre, posed core circle) = r + Rs;
  phi2 follows from a scalar root (scipy ``brentq``), the contact point lies on the
  segment from the nearest core-circle point to the sphere centre;
* relative curvatures (torus: meridian 1/r, parallel cos(u)/(Rt + r cos u); sphere 1/Rs
  in every direction, all convex):
  kappa_max = 1/r + 1/Rs (meridian), kappa_min = cos u/(Rt + r cos u) + 1/Rs (parallel).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq

from gearcontact.geometry.kinematics import MeshKinematics
from gearcontact.geometry.surface import SurfacePoint


@dataclass(frozen=True)
class Sphere:
    """r = c + R (sin u cos v e1 + sin u sin v e2 + cos u e3); outward normal."""

    center: np.ndarray
    frame: np.ndarray          # columns e1, e2, e3
    radius: float
    u_range: tuple = (0.4, np.pi - 0.4)
    v_range: tuple = (-1.2, 1.2)

    def point(self, u, v):
        e1, e2, e3 = self.frame.T
        su, cu, sv, cv = np.sin(u), np.cos(u), np.sin(v), np.cos(v)
        d = su * cv * e1 + su * sv * e2 + cu * e3
        d_u = cu * cv * e1 + cu * sv * e2 - su * e3
        d_v = -su * sv * e1 + su * cv * e2
        d_uu = -d
        d_uv = -cu * sv * e1 + cu * cv * e2
        d_vv = -su * cv * e1 - su * sv * e2
        R = self.radius
        return SurfacePoint(u, v, self.center + R * d, R * d_u, R * d_v, R * d_uu,
                            R * d_uv, R * d_vv, d)


@dataclass(frozen=True)
class Torus:
    """r = c + (Rt + r cos u)(cos v e1 + sin v e2) + r sin u e3; outward normal."""

    center: np.ndarray
    frame: np.ndarray
    core_radius: float
    tube_radius: float
    u_range: tuple = (-1.0, 1.0)
    v_range: tuple = (-0.6, 0.6)

    def point(self, u, v):
        e1, e2, e3 = self.frame.T
        Rt, r = self.core_radius, self.tube_radius
        rho = np.cos(v) * e1 + np.sin(v) * e2
        rho_v = -np.sin(v) * e1 + np.cos(v) * e2
        w = Rt + r * np.cos(u)
        n = np.cos(u) * rho + np.sin(u) * e3
        x = self.center + w * rho + r * np.sin(u) * e3
        x_u = -r * np.sin(u) * rho + r * np.cos(u) * e3
        x_v = w * rho_v
        x_uu = -r * np.cos(u) * rho - r * np.sin(u) * e3
        x_uv = -r * np.sin(u) * rho_v
        x_vv = -w * rho
        return SurfacePoint(u, v, x, x_u, x_v, x_uu, x_uv, x_vv, n)


def _unit(a):
    a = np.asarray(a, float)
    return a / np.linalg.norm(a)


@dataclass(frozen=True)
class SphereTorusCase:
    kin: MeshKinematics
    pinion: Sphere
    gear: Torus
    tube_angle: float   # u of the torus at the phi = 0 contact

    def sphere_centre(self, phi1):
        rot, t = self.kin.pinion_pose(phi1)
        return rot @ self.pinion.center + t

    def _circle_distance(self, s, phi2):
        rot, t = self.kin.gear_pose(phi2)
        c = rot @ self.gear.center + t
        e1, e2, e3 = (rot @ self.gear.frame).T
        d = s - c
        h = d @ e3
        radial = d - h * e3
        rho = np.linalg.norm(radial)
        q = c + self.gear.core_radius * radial / rho
        return np.linalg.norm(s - q), q

    def truth(self, phi1, bracket=0.05):
        """phi2, contact point and both relative curvatures at pinion phase phi1."""
        s = self.sphere_centre(phi1)
        target = self.gear.tube_radius + self.pinion.radius
        guess = phi1 / self.kin.ratio
        phi2 = brentq(lambda p: self._circle_distance(s, p)[0] - target,
                      guess - bracket, guess + bracket, xtol=1e-15, rtol=1e-15)
        _, q = self._circle_distance(s, phi2)
        normal = _unit(s - q)
        point = q + self.gear.tube_radius * normal
        rot, t = self.kin.gear_pose(phi2)
        e3 = rot @ self.gear.frame[:, 2]
        u = np.arcsin(np.clip(normal @ e3, -1, 1))
        Rt, r, Rs = self.gear.core_radius, self.gear.tube_radius, self.pinion.radius
        k_max = 1 / r + 1 / Rs
        k_min = np.cos(u) / (Rt + r * np.cos(u)) + 1 / Rs
        return phi2, point, normal, k_max, k_min


def sphere_torus_case(*, tube_angle=0.3, core_radius=30.0, tube_radius=8.0,
                      sphere_radius=15.0, errors=None) -> SphereTorusCase:
    """Sphere on the pinion touching a torus on the gear at P0 = (35.8, -18.7, 5.7) mm
    (the s0003 pitch point) at phi1 = phi2 = 0 in the nominal assembly."""
    kw = {} if errors is None else {"errors": errors}
    kin = MeshKinematics(offset_mm=19.0, ratio=10.0, **kw)
    nominal = MeshKinematics(offset_mm=19.0, ratio=10.0)
    p0 = np.array([35.8, -18.7, 5.7])
    # gear normal out of the gear tooth: mostly along the gear's rotation velocity
    n2 = _unit(np.cross([0, 0, 1.0], p0) + np.array([0.0, 0.0, 0.3]))
    w = _unit(np.cross(n2, [0.2, 0.5, 1.0]))
    u = tube_angle
    rho_hat = np.cos(u) * n2 - np.sin(u) * w
    axis = np.sin(u) * n2 + np.cos(u) * w
    q = p0 - tube_radius * n2
    centre = q - core_radius * rho_hat
    frame_t = np.column_stack([rho_hat, np.cross(axis, rho_hat), axis])
    gear = Torus(centre, frame_t, core_radius, tube_radius,
                 u_range=(u - 1.0, u + 1.0))
    # sphere: outward normal -n2 at P0, pole axis perpendicular to n2
    rot1, t1 = nominal.pinion_pose(0.0)
    s_centre = p0 + sphere_radius * n2
    e1 = rot1.T @ (-n2)
    e3 = rot1.T @ w
    frame_s = np.column_stack([e1, np.cross(e3, e1), e3])
    pinion = Sphere(rot1.T @ (s_centre - t1), frame_s, sphere_radius)
    return SphereTorusCase(kin, pinion, gear, u)
