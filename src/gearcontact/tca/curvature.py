"""Relative curvatures and the instantaneous contact ellipse at a mating point.

Each flank's shape operator is projected onto one orthonormal basis ``E = [e1 e2]`` of
the common tangent plane. With ``J = [r_u r_v]`` (posed) and ``M = E^T J`` the curvature
tensor of a surface w.r.t. its own unit normal ``n`` is (do Carmo 1976, sec. 3-3)

.. math::  K = M^{-T}\\, II\\, M^{-1}, \\qquad II_{ij} = \\mathbf r_{ij} \\cdot \\mathbf n,

so that near the point the surface is ``X = P + q + (1/2) q^T K q n``. Both flank
normals point out of their own tooth (``n1 = -n2`` at contact), and the separation of
the flanks along the gear normal ``n2`` is, to second order,

.. math::  g(q) = \\tfrac12\\, q^T B q, \\qquad B = -(K_1 + K_2),

the relative curvature tensor (Litvin & Fuentes 2004, sec. 9.5 "relations between
principal curvatures"; positive definite for point contact). Its eigenvalues
``kappa_max >= kappa_min`` are the principal relative curvatures (1/mm). The Hertz
stage takes half of them, with the naming of docs/spec.md sec. 6 stage C:
``A- = (h + r)/2 = kappa_max/2`` and ``B- = (h - r)/2 = kappa_min/2``.

The instantaneous contact ellipse at the paint (marking compound) thickness
``delta = 6.35 um`` is the set ``g(q) <= delta``: semi-axes ``sqrt(2 delta / kappa)``,
i.e. ``sqrt(delta / A-)`` (minor) and ``sqrt(delta / B-)`` (major, along the
direction of ``kappa_min``).

Orientation convention: the flank frame at the mating point has ``l`` = the gear's
lengthwise direction (unit tangent component of the posed ``r_v``, toe -> heel) and
``p`` = its profile direction (the tangent component of the posed ``r_u`` orthogonal
to ``l``, root -> tip). The ellipse angle is the angle from ``l`` to the major axis,
positive towards ``p`` (i.e. towards the gear tip when going heelwards), folded into
(-90, 90] deg. ``(l, p, n2)`` is right-handed on one flank side and left-handed on the
other.

The principal directions are lines; their signs (which the eigen-solver leaves
arbitrary, and which flip with rounding where the tensor is diagonal in ``(l, p)``)
are fixed so that every consumer of a direction (the ``"principal"`` frame of the gap
fields, :func:`gearcontact.tca.stencil.tangent_frame`, hence the LTCA grids) sees the
same one:

* ``dir_min`` (the major axis) points towards the toe, ``dir_min . l < 0``; a major
  axis within :data:`ORIENTATION_TOL` of the profile direction
  (``|dir_min . l| <= ORIENTATION_TOL``: the ellipse at +-90 deg, e.g. at a contact on
  a gear kink ridge or root / tip edge, whose tensor is diagonal in ``(l, p)`` by
  construction) points towards the root, ``dir_min . p < 0``, and its angle is reported
  as 90 deg exactly;
* ``dir_max`` (the minor axis) is ``dir_min`` turned by -90 deg in the ``(l, p)``
  plane (components ``(d_p, -d_l)`` of ``dir_min = (d_l, d_p)``): towards the tip for
  a major axis near ``-l``.

These are the signs the eigen-solver returned for every principal frame of s0003's,
the ISO 23509 F.2 pairs' and the Toprem pair's ``analyze`` runs (measured; so their
results stay bit for bit), now a rule instead of a rounding accident.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..geometry.kinematics import MeshKinematics
from ..geometry.surface import Surface, SurfacePoint
from ..validation import check_positive
from .types import MatingPoint

__all__ = ["PAINT_THICKNESS_MM", "ORIENTATION_TOL", "RelativeCurvature", "ContactEllipse",
           "curvature_tensor", "relative_curvature", "contact_ellipse", "flank_frame"]

#: Thickness of the marking compound that defines the unloaded contact pattern, mm.
PAINT_THICKNESS_MM = 6.35e-3
#: A unit major axis whose lengthwise component is at most this (the cosine of its
#: angle from ``l``; 1e-9 rad = 5.7e-8 deg from +-90 deg) is taken as at 90 deg (module
#: docstring). Rounding moves a principal direction by ~1e-16 to 1e-13 (a ridge
#: contact's tensor is diagonal to ~1e-19 of its 4e-3 1/mm), far inside; an ellipse
#: within 5.7e-8 deg of 90 deg is reported at 90 deg.
ORIENTATION_TOL = 1e-9


@dataclass(frozen=True)
class RelativeCurvature:
    """Relative curvature at a mating point (all vectors in the meshing frame).

    Attributes
    ----------
    kappa_max_per_mm, kappa_min_per_mm : float
        Principal relative curvatures, 1/mm (``kappa_max >= kappa_min``).
    dir_max, dir_min : ndarray (3,)
        Unit principal directions of ``kappa_max`` and ``kappa_min``.
    A_minus_per_mm, B_minus_per_mm : float
        Hertz-stage curvatures ``kappa_max/2`` and ``kappa_min/2``, 1/mm.
    tensor_per_mm : ndarray (2, 2)
        ``B`` in the flank frame ``(l, p)``, 1/mm.
    lengthwise, profile, normal : ndarray (3,)
        The flank frame ``(l, p, n2)`` (toe -> heel, root -> tip, gear normal).
    """

    kappa_max_per_mm: float
    kappa_min_per_mm: float
    dir_max: np.ndarray
    dir_min: np.ndarray
    A_minus_per_mm: float
    B_minus_per_mm: float
    tensor_per_mm: np.ndarray
    lengthwise: np.ndarray
    profile: np.ndarray
    normal: np.ndarray


@dataclass(frozen=True)
class ContactEllipse:
    """Instantaneous contact ellipse ``g <= delta`` at a mating point.

    Attributes
    ----------
    semi_major_mm, semi_minor_mm : float
        Semi-axes, mm (infinite major axis for line contact).
    major_axis : ndarray (3,)
        Unit direction of the major axis in the meshing frame.
    angle_deg : float
        Angle from the lengthwise direction to the major axis, deg (see module doc).
    paint_mm : float
        The separation ``delta`` that defines it, mm.
    """

    semi_major_mm: float
    semi_minor_mm: float
    major_axis: np.ndarray
    angle_deg: float
    paint_mm: float

    @property
    def ratio(self) -> float:
        """Length-to-width ratio ``a / b``."""
        return self.semi_major_mm / self.semi_minor_mm


def curvature_tensor(sp: SurfacePoint, rot: np.ndarray, basis: np.ndarray) -> np.ndarray:
    """Curvature tensor ``K = M^-T II M^-1`` (1/mm) of a posed surface point in ``basis``.

    Parameters
    ----------
    sp : SurfacePoint
        Body-frame evaluation (II is taken w.r.t. ``sp.n``).
    rot : ndarray (3, 3)
        Pose rotation body -> meshing frame.
    basis : ndarray (3, 2)
        Orthonormal basis of the tangent plane in the meshing frame.
    """
    _, second = sp.fundamental_forms()
    m = basis.T @ (rot @ np.column_stack([sp.r_u, sp.r_v]))
    m_inv = np.linalg.inv(m)
    return m_inv.T @ second @ m_inv


def flank_frame(sp_gear: SurfacePoint, rot_gear: np.ndarray) -> np.ndarray:
    """Columns ``(l, p, n2)``: gear lengthwise (toe -> heel), profile (root -> tip) and
    normal directions, posed; ``l`` and ``p`` orthonormal in the tangent plane."""
    n = rot_gear @ sp_gear.n
    rv = rot_gear @ sp_gear.r_v
    lw = rv - (rv @ n) * n
    lw /= np.linalg.norm(lw)
    ru = rot_gear @ sp_gear.r_u
    pr = ru - (ru @ n) * n - (ru @ lw) * lw
    pr /= np.linalg.norm(pr)
    return np.column_stack([lw, pr, n])


def relative_curvature(pinion: Surface, gear: Surface, kin: MeshKinematics,
                       mp: MatingPoint) -> RelativeCurvature:
    """Principal relative curvatures and directions at the mating point ``mp``.

    At an edge contact (``mp.edge_contact``) the equivalent curvatures of the edge's
    paint strip (:func:`_edge_tensor`).

    Raises
    ------
    ValueError
        For an edge phase (no interior mating point).
    """
    if mp.edge:
        raise ValueError(f"no relative curvature at an edge-contact phase "
                         f"(phi1 = {np.degrees(mp.phi1_rad):.6f} deg, {mp.edge_where})")
    rot1 = kin.pinion_pose(mp.phi1_rad)[0]
    rot2 = kin.gear_pose(mp.phi2_rad)[0]
    sp1 = pinion.point(mp.u1, mp.v1)
    sp2 = gear.point(mp.u2, mp.v2)
    frame = flank_frame(sp2, rot2)
    basis = frame[:, :2]
    if mp.edge_contact:
        tensor = _edge_tensor(sp1, rot1, sp2, rot2, basis, mp.edge_contact)
    else:
        tensor = -(curvature_tensor(sp1, rot1, basis) + curvature_tensor(sp2, rot2, basis))
    tensor = 0.5 * (tensor + tensor.T)
    evals, evecs = np.linalg.eigh(tensor)
    d_min, d_max = _oriented(basis, frame[:, 0], evecs)
    return RelativeCurvature(float(evals[1]), float(evals[0]), d_max, d_min,
                             0.5 * float(evals[1]), 0.5 * float(evals[0]), tensor,
                             frame[:, 0], frame[:, 1], frame[:, 2])


def _oriented(basis: np.ndarray, lengthwise: np.ndarray,
              evecs: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The principal directions ``(dir_min, dir_max)`` (meshing frame) of the eigenvector
    columns ``evecs`` (in ``basis``, whose first column is ``lengthwise``) with the
    signs of the module docstring's convention: only signs change (exact negations)."""
    e_min, e_max = evecs[:, 0], evecs[:, 1]
    d_min = basis @ e_min
    c_l = float(d_min @ lengthwise)
    # towards the toe; within the tolerance of +-90 deg towards the root
    if c_l > ORIENTATION_TOL or (abs(c_l) <= ORIENTATION_TOL and e_min[1] > 0.0):
        e_min, d_min = -e_min, -d_min
    # dir_max = dir_min turned by -90 deg in (l, p): components (e_p, -e_l)
    if e_max[0] * e_min[1] - e_max[1] * e_min[0] < 0.0:
        e_max = -e_max
    return d_min, basis @ e_max


def _edge_tensor(sp1: SurfacePoint, rot1: np.ndarray, sp2: SurfacePoint, rot2: np.ndarray,
                 basis: np.ndarray, edge: str, *, paint_mm: float = PAINT_THICKNESS_MM
                 ) -> np.ndarray:
    """Equivalent relative curvature tensor of an edge contact in ``basis`` (1/mm).

    An edge touching a surface is a singular contact: along the edge ``e`` the
    separation grows as ``1/2 kappa_e s^2`` (``kappa_e = e^T B e`` with ``B`` the
    relative curvature of the smooth flanks; ``kappa_e >= 0`` at a first touch inside
    the edge), across it, on the flank side, linearly with the slope ``tan theta``
    of the angle between the flank normals. The paint strip across the edge is then
    ``w = delta / tan theta`` wide; the equivalent curvature with the same width at the
    paint thickness ``delta`` is ``kappa_f = 2 tan^2 theta / delta``. At a corner
    (``kappa_e <= 0``: the extreme is an end of the edge) the separation grows
    linearly both ways and ``kappa_f`` is used along the edge too.
    """
    member, _, name = edge.partition(" ")
    smooth = -(curvature_tensor(sp1, rot1, basis) + curvature_tensor(sp2, rot2, basis))
    own, rot = (sp1, rot1) if member == "pinion" else (sp2, rot2)
    tangent = basis.T @ (rot @ (own.r_u if name in ("toe", "heel") else own.r_v))
    e = tangent / np.linalg.norm(tangent)
    f = np.array([-e[1], e[0]])
    cos_theta = float(np.clip(-(rot1 @ sp1.n) @ (rot2 @ sp2.n), -1.0, 1.0))
    tan2 = (1.0 - cos_theta ** 2) / max(cos_theta ** 2, 1e-12)
    kappa_f = 2.0 * tan2 / paint_mm
    kappa_e = float(e @ smooth @ e)
    if kappa_e <= 0.0:
        kappa_e = kappa_f
    return kappa_e * np.outer(e, e) + kappa_f * np.outer(f, f)


def contact_ellipse(rc: RelativeCurvature, *,
                    paint_mm: float = PAINT_THICKNESS_MM) -> ContactEllipse:
    """Contact ellipse at separation ``paint_mm`` (default the 6.35 um paint).

    Semi-axes ``sqrt(2 delta / kappa)`` (Litvin & Fuentes 2004, sec. 9.6). A
    non-positive ``kappa_min`` (line contact or separating flanks) gives an infinite
    major axis.
    """
    check_positive("paint_mm", paint_mm)
    if rc.kappa_max_per_mm <= 0.0:
        raise ValueError(f"relative curvature kappa_max = {rc.kappa_max_per_mm:g} 1/mm "
                         "<= 0: the flanks do not form a contact ellipse")
    minor = float(np.sqrt(2.0 * paint_mm / rc.kappa_max_per_mm))
    major = (float(np.sqrt(2.0 * paint_mm / rc.kappa_min_per_mm))
             if rc.kappa_min_per_mm > 0.0 else float("inf"))
    axis = rc.dir_min
    if abs(axis @ rc.lengthwise) <= ORIENTATION_TOL:
        angle = 90.0            # at +-90 deg within the tolerance (module docstring)
    else:
        angle = np.degrees(np.arctan2(axis @ rc.profile, axis @ rc.lengthwise))
        if angle > 90.0:
            angle -= 180.0
        elif angle <= -90.0:
            angle += 180.0
    return ContactEllipse(major, minor, axis, float(angle), float(paint_mm))
