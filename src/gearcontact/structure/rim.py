"""The root fillet and rim segment below a tooth's root line, one geometry for the
shell (:mod:`.shell`) and the 3D finite elements (:mod:`.fe`).

A tooth (:mod:`.tooth`) ends at its root line ``eta = -1``, the lowest height both
flanks cover. Below it the solid continues (``docs/bending.md`` sec. 3):

- a root fillet approximation over the height ``fillet_mm``: the sides widen on a
  quarter ellipse from the tooth's chord ``P_d - P_c`` at the root line to the slot
  middles, so that the segment spans one pitch (half a slot on each side);
- the rim block below it, down to the depth ``depth_mm`` below the root line, whose
  bottom is clamped (its sides and the toe / heel ends are free).

Section at depth ``s`` (mm) below the root point of the face position ``xi``: centre
``C(xi) + s d(xi)`` with ``C = (P_c + P_d) / 2`` at the root line and ``d`` the unit
direction down the mid-surface there (``-X_eta / |X_eta|``); the points across it are
``C + s d + (zeta - 1/2) f(s) (P_d - P_c)`` for ``zeta`` in [0, 1], with
``f = 1 + (w - 1) sqrt(1 - (1 - q)^2)``, ``q = min(s / fillet_mm, 1)`` and ``w`` the
widening that makes the section span one pitch angle about the member axis.

Defaults (both models): the depth is the tooth height (mid-surface length over eta at
the face centre), the fillet height the larger of the flank's start above the root
cone (``u_lo``) and 15 % of the tooth height.

A segment may instead carry a tabulated widening (:class:`SectionProfile`): ``f(s)``
over the fillet from a real root's section widths (a cylindrical tooth's trochoid,
:func:`gearcontact.structure.cylindrical_tooth.cylindrical_rim`), then the root row's
width below it (the shell's only; the FE meshes the real root itself).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..validation import InputRangeError, check_positive
from .tooth import MidSurfaceArrays

__all__ = ["RimSegment", "SectionProfile", "rim_segment", "rim_points", "rim_mid_surface",
           "rim_modulus_factor", "root_line_section", "tooth_height_mm"]

#: Step in xi of the central differences of the section's direction along the face.
_DXI = 1e-4


@dataclass(frozen=True)
class SectionProfile:
    """A tabulated widening of the fillet (module docstring), one for every face position.

    Attributes
    ----------
    depth_mm : tuple of float
        Depths below the root line, ascending from 0 to the segment's ``fillet_mm``, mm.
    widening : tuple of float
        ``f`` at those depths: the section's width over the root line's (1 at depth 0),
        linear between them.
    rim_widening : float
        ``f`` from ``fillet_mm`` down (the rim block's width over the root line's).
    """

    depth_mm: tuple
    widening: tuple
    rim_widening: float

    def __post_init__(self):
        s, f = np.asarray(self.depth_mm, float), np.asarray(self.widening, float)
        if s.ndim != 1 or s.shape != f.shape or len(s) < 2 or s[0] != 0.0 or np.any(
                np.diff(s) <= 0.0):
            raise InputRangeError("section profile depth_mm", f"{len(s)} values",
                                  "ascending from 0, as many as the widening values (>= 2)")
        if not (np.all(f > 0.0) and np.all(np.isfinite(f))):
            raise InputRangeError("section profile widening", float(np.min(f)), "> 0")
        check_positive("section profile rim_widening", self.rim_widening)


@dataclass(frozen=True)
class RimSegment:
    """The fillet and rim block below a tooth's root line.

    Attributes
    ----------
    depth_mm : float
        Depth of the rim's (clamped) bottom below the root line, mm.
    fillet_mm : float
        Height of the fillet widening below the root line, mm (<= ``depth_mm``).
    stiffening : float
        Factor on the modulus of the rim block in the shell model, reached over the
        fillet (:func:`rim_modulus_factor`; the 3D FE uses the material as it is), > 0;
        see :data:`gearcontact.structure.shell.RIM_STIFFENING`.
    profile : SectionProfile or None
        The shell's tabulated widening (its last depth is ``fillet_mm``); None: the
        quarter ellipse to one pitch (module docstring).
    """

    depth_mm: float
    fillet_mm: float
    stiffening: float = 1.0
    profile: SectionProfile | None = None

    def __post_init__(self):
        check_positive("rim depth_mm", self.depth_mm)
        check_positive("rim fillet_mm", self.fillet_mm)
        check_positive("rim stiffening", self.stiffening)
        if self.fillet_mm > self.depth_mm:
            raise InputRangeError("rim fillet_mm", self.fillet_mm,
                                  f"<= depth_mm = {self.depth_mm:g}")
        if self.profile is not None and self.profile.depth_mm[-1] != self.fillet_mm:
            raise InputRangeError("rim profile's last depth_mm", self.profile.depth_mm[-1],
                                  f"the fillet_mm {self.fillet_mm:g}")


def tooth_height_mm(body) -> float:
    """Length of the mid-surface over the height at the face centre, mm."""
    mid = body.mid_surface(0.0, np.linspace(-1.0, 1.0, 9))
    return float(np.sum(np.linalg.norm(np.diff(mid.position_mm, axis=0), axis=1)))


def rim_segment(body, *, depth_mm: float | None = None, fillet_mm: float | None = None,
                stiffening: float = 1.0, profile: SectionProfile | None = None
                ) -> RimSegment:
    """The rim segment of a tooth with the defaults of the module docstring (with a
    ``profile``, the fillet height is its last depth)."""
    if profile is not None and fillet_mm is not None:
        raise InputRangeError("fillet_mm", fillet_mm, "None with a profile (its last "
                              "depth is the fillet height)")
    if not hasattr(body, "teeth"):
        raise InputRangeError("rim", type(body).__name__, "a tooth with a member axis")
    height = tooth_height_mm(body)
    depth = height if depth_mm is None else check_positive("rim_depth_mm", depth_mm)
    if profile is not None:
        fil = profile.depth_mm[-1]
        if fil > depth:
            raise InputRangeError("rim profile's last depth_mm", fil,
                                  f"<= the rim depth {depth:g} mm")
    else:
        fil = (max(body.u_span_mm[0], 0.15 * height) if fillet_mm is None
               else check_positive("fillet_mm", fillet_mm))
    return RimSegment(depth_mm=float(depth), fillet_mm=float(min(fil, depth)),
                      stiffening=float(stiffening), profile=profile)


def root_line_section(body, xi):
    """(centre, unit down direction, chord P_d - P_c, widening to one pitch) at the root
    line ``eta = -1`` of the face positions ``xi``, each (n, ...)."""
    pc0, pd0 = body.side_points(xi, -np.ones_like(xi))
    mid = body.mid_surface(xi, -np.ones_like(xi))
    down = -mid.x_eta / np.linalg.norm(mid.x_eta, axis=-1, keepdims=True)
    axis = body.axis
    rc = pc0 - np.outer(pc0 @ axis, axis)
    rd = pd0 - np.outer(pd0 @ axis, axis)
    cosang = np.einsum("ni,ni->n", rc, rd) / (np.linalg.norm(rc, axis=1)
                                               * np.linalg.norm(rd, axis=1))
    widen = (2.0 * np.pi / body.teeth) / np.arccos(np.clip(cosang, -1.0, 1.0))
    return 0.5 * (pc0 + pd0), down, pd0 - pc0, widen


def _widening(rim: RimSegment, s_mm, widen):
    """``f`` at depth ``s_mm`` (module docstring): the tabulated profile, or the quarter
    ellipse from 1 at the root line to the pitch widening ``widen`` at its end."""
    if rim.profile is not None:
        p = rim.profile
        s = np.asarray(s_mm, float)
        return np.where(s < rim.fillet_mm, np.interp(s, p.depth_mm, p.widening),
                        p.rim_widening)
    q = np.clip(np.asarray(s_mm, float) / rim.fillet_mm, 0.0, 1.0)
    return 1.0 + (widen - 1.0) * np.sqrt(1.0 - (1.0 - q) ** 2)


def rim_modulus_factor(rim: RimSegment, s_mm) -> np.ndarray:
    """Factor on the modulus of the shell's fillet and rim at depth ``s_mm``: 1 at the
    root line, rising over the fillet to ``rim.stiffening`` at its end (a cubic
    smoothstep, flat at both ends: the plate's strains stay smooth and the Ritz
    polynomials converge as on the tooth, not as across a jump)."""
    q = np.clip(np.asarray(s_mm, float) / rim.fillet_mm, 0.0, 1.0)
    return 1.0 + (rim.stiffening - 1.0) * q * q * (3.0 - 2.0 * q)


def rim_points(body, rim: RimSegment, xi, s_mm, zeta) -> np.ndarray:
    """Points (n, 3) of the fillet / rim segment at face position ``xi``, depth ``s_mm``
    below the root line and ``zeta`` in [0, 1] across (coast -> drive side), mm."""
    xi, s_mm, zeta = (np.asarray(a, float) for a in np.broadcast_arrays(xi, s_mm, zeta))
    centre, down, chord, widen = root_line_section(body, xi)
    f = _widening(rim, s_mm, widen)
    return centre + s_mm[:, None] * down + ((zeta - 0.5) * f)[:, None] * chord


def rim_mid_surface(body, rim: RimSegment, xi, s_mm) -> MidSurfaceArrays:
    """Mid-surface of the fillet / rim segment at (``xi``, depth ``s_mm``).

    ``x_eta`` is the derivative per unit depth *upwards* (``-d``, towards the tooth, as
    the tooth's own ``x_eta``), ``x_xi`` per unit xi (the direction ``d`` varies along
    the face: central differences of step :data:`_DXI`); the thickness is the widened
    chord's component along the normal.
    """
    xi, s_mm = (np.asarray(a, float) for a in np.broadcast_arrays(xi, s_mm))
    centre, down, chord, widen = root_line_section(body, xi)
    lo, hi = np.maximum(xi - _DXI, -1.0), np.minimum(xi + _DXI, 1.0)
    c_lo, d_lo, _, _ = root_line_section(body, lo)
    c_hi, d_hi, _, _ = root_line_section(body, hi)
    span = (hi - lo)[:, None]
    x_xi = (c_hi - c_lo) / span + s_mm[:, None] * (d_hi - d_lo) / span
    x_eta = -down
    normal = np.cross(x_xi, x_eta)
    normal /= np.linalg.norm(normal, axis=-1, keepdims=True)
    normal *= np.sign(np.einsum("ni,ni->n", chord, normal))[:, None]  # coast -> drive
    f = _widening(rim, s_mm, widen)
    thickness = f * np.einsum("ni,ni->n", chord, normal)
    return MidSurfaceArrays(position_mm=centre + s_mm[:, None] * down, x_xi=x_xi,
                            x_eta=x_eta, normal=normal, thickness_mm=thickness)
