"""Five-term pinion ease-off and the modified (eased) pinion flank.

The ease-off is a relief of the pinion flank along its outward unit normal N1
(docs/geometry.md sec. 3; Litvin & Fuentes 2004, sec. 21.8 "local synthesis" uses the same
polynomial topology):

    r1*(u, v) = r1(u, v) - E(xi, eta) N1(u, v)
    E = c_PA eta + c_SA xi + c_PC eta^2 + c_LC xi^2 + c_TW xi eta

with xi = v - v_m (lengthwise, along the pinion axis, mm) and eta = u - u_m (profile,
radial height, mm) measured from the pinion mean point (pitch radius, mean section),
E > 0 removing material. Coefficients (pair file, um per mm^k):

- c_PA  profile angle (pressure-angle change): tilts the bearing across the profile;
- c_SA  spiral angle: tilts it along the face (moves the bearing toe/heel under load);
- c_PC  profile crowning: limits the bearing height, sets the contact-ellipse length
        across the contact lines (a = sqrt(2 delta_paint / kappa_E), kappa_E ~ 2 c);
- c_LC  lengthwise crowning: localizes the bearing along the face and sets the
        parabolic unloaded TE0 (TE ~ -dE_path / h2, h2 ~ 35 mm lever);
- c_TW  bias (twist): turns the contact path (bias in / bias out).

The eased flank is again a :class:`~.sheet.RadialSheet`: for every node (u, v) the
base-flank point (u0, v0) whose relieved image ``r1 - E N1`` has the node's axial
position and radius is found (Newton iteration on the sheet derivatives and the
relief gradient, 2-3 steps to 1 pm),
and the image's angular coordinate becomes the new sample. The modified normal and
curvatures are recomputed from the new sheet's derivatives, never from N1.

References
----------
F. L. Litvin, A. Fuentes, *Gear Geometry and Applied Theory*, 2nd ed., 2004, ch. 21.
ISO 23509:2016 (mean point, face width).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

import csv
import io
import math

from scipy.interpolate import NdBSpline, RectBivariateSpline

from ..errors import CheckFailed
from ..validation import InputRangeError, read_text_file
from .sheet import RadialSheet

__all__ = ["EaseOff", "GridEaseOff", "apply_easeoff", "easeoff_limit_um", "max_relief_um",
           "mean_normal_thickness_mm", "read_easeoff_grid", "GRID_COLUMNS",
           "MAX_EASEOFF_THICKNESS_FRACTION"]

#: Largest |E| accepted over the flank as a fraction of the pinion mean normal tooth
#: thickness s_mn. Why a fraction of the thickness: the relief removes material along
#: the normal, so E is a local loss of tooth thickness. Ease-off is a micro-geometry
#: (machine-setting) modification within the finishing stock of the flank; at 5 % of
#: s_mn it already changes the local bending stiffness (~ t^3) by ~15 % and the backlash
#: by E, beyond which the "ease-off" is a different tooth form and should be designed
#: as one (pressure angle, addendum, thickness), not as a relief. For s0003 (s_mn ~ 1.7
#: mm) the limit is ~85 um; it scales with the tooth size instead of being a fixed value.
MAX_EASEOFF_THICKNESS_FRACTION = 0.05
_NODE_SHRINK_MM = 0.04   # eased nodes stay at least this far inside the base node box
_ITER = 30


@dataclass(frozen=True)
class EaseOff:
    """The ease-off polynomial with its mean point (coefficients in um/mm^k, mean in mm)."""

    profile_angle_um_per_mm: float
    spiral_angle_um_per_mm: float
    profile_crowning_um_per_mm2: float
    lengthwise_crowning_um_per_mm2: float
    bias_um_per_mm2: float
    u_mean_mm: float
    v_mean_mm: float

    @classmethod
    def from_coefficients(cls, coeffs, *, u_mean_mm: float, v_mean_mm: float) -> "EaseOff":
        """From :class:`~.pair.EaseOffCoefficients` and the pinion mean point."""
        return cls(u_mean_mm=float(u_mean_mm), v_mean_mm=float(v_mean_mm),
                   **{k: getattr(coeffs, k) for k in coeffs.__dataclass_fields__})

    @property
    def is_zero(self) -> bool:
        """True if all five coefficients are zero."""
        return not any((self.profile_angle_um_per_mm, self.spiral_angle_um_per_mm,
                        self.profile_crowning_um_per_mm2, self.lengthwise_crowning_um_per_mm2,
                        self.bias_um_per_mm2))

    def relief_mm(self, u, v) -> np.ndarray:
        """E at pinion parameters (u, v), mm (positive = material removed)."""
        eta = np.asarray(u, dtype=float) - self.u_mean_mm
        xi = np.asarray(v, dtype=float) - self.v_mean_mm
        um = (self.profile_angle_um_per_mm * eta + self.spiral_angle_um_per_mm * xi
              + self.profile_crowning_um_per_mm2 * eta ** 2
              + self.lengthwise_crowning_um_per_mm2 * xi ** 2 + self.bias_um_per_mm2 * xi * eta)
        return 1e-3 * um


@dataclass(frozen=True, eq=False)
class GridEaseOff:
    """An ease-off sampled on a rectangular (u, v) grid of the pinion sheet (a measured
    deviation grid), interpolated by the bicubic spline through the samples (exact for
    polynomials up to degree 3 in each direction: the five-term :class:`EaseOff`
    sampled on a grid is reproduced to rounding) and continued beyond the grid by its
    edge polynomials (the node margin of :func:`apply_easeoff`).

    Parameters
    ----------
    u_mm, v_mm : ndarray
        Increasing grid lines: height above the root cone and axial position, mm
        (:mod:`.sheet`), at least 4 each.
    relief_um : ndarray (len(u_mm), len(v_mm))
        E at the nodes, um (positive = material removed, as :class:`EaseOff`).
    """

    u_mm: np.ndarray
    v_mm: np.ndarray
    relief_um: np.ndarray

    def __post_init__(self):
        fit = RectBivariateSpline(self.u_mm, self.v_mm, self.relief_um, kx=3, ky=3, s=0)
        tx, ty, c = fit.tck
        object.__setattr__(self, "_spline", NdBSpline(
            (tx, ty), np.asarray(c).reshape(len(tx) - 4, len(ty) - 4), 3, extrapolate=True))

    @property
    def is_zero(self) -> bool:
        """True if every sample is zero."""
        return not np.any(self.relief_um)

    def relief_mm(self, u, v) -> np.ndarray:
        """E at pinion parameters (u, v), mm (positive = material removed)."""
        u, v = np.broadcast_arrays(np.asarray(u, dtype=float), np.asarray(v, dtype=float))
        pts = np.stack([u.ravel(), v.ravel()], axis=-1)
        return 1e-3 * self._spline(pts).reshape(u.shape)

    def check_covers(self, boundary, *, where: str) -> None:
        """Refuse a grid that does not cover the flank box ``boundary`` (1 um slack)."""
        b, tol = boundary, 1e-3
        if (self.u_mm[0] > b.u_root + tol or self.u_mm[-1] < b.u_tip - tol
                or self.v_mm[0] > b.v_toe + tol or self.v_mm[-1] < b.v_heel - tol):
            raise InputRangeError(
                f"{where} grid (u {self.u_mm[0]:.3f}..{self.u_mm[-1]:.3f}, v "
                f"{self.v_mm[0]:.3f}..{self.v_mm[-1]:.3f} mm)", "a grid short of the flank",
                f"a grid covering the active flank u {b.u_root:.3f}..{b.u_tip:.3f}, "
                f"v {b.v_toe:.3f}..{b.v_heel:.3f} mm")


#: Columns of a deviation grid CSV (:func:`read_easeoff_grid`).
GRID_COLUMNS = ("side", "v_mm", "u_mm", "easeoff_um")


def read_easeoff_grid(path) -> dict:
    """A measured ease-off grid from a CSV file: ``{side: GridEaseOff}``.

    Columns ``side,v_mm,u_mm,easeoff_um`` (header row; ``side`` drive | coast; ``v``
    axial position in the pinion body frame, ``u`` height above the root cone, mm,
    :mod:`.sheet`; ``easeoff_um`` the deviation from the conjugate pinion along its
    outward normal, positive = material removed, the sign of :class:`EaseOff`). Each
    side listed is a complete rectangular grid of at least 4 x 4 distinct (u, v),
    every node once.

    Raises
    ------
    InputRangeError
        A missing column, a non-numeric or non-finite value, an unknown side, or an
        incomplete / repeated / too small grid (the message names the row or side).
    """
    text = read_text_file(path, field="target flank", what="a CSV deviation grid")
    rows = list(csv.reader(io.StringIO(text)))
    head = [h.strip() for h in rows[0]] if rows else []
    if head != list(GRID_COLUMNS):
        raise InputRangeError(f"{path}: header", ",".join(head), ",".join(GRID_COLUMNS))
    nodes: dict = {}
    for k, row in enumerate(rows[1:], start=2):
        if not row or not "".join(row).strip():
            continue
        if len(row) != 4 or row[0].strip() not in ("drive", "coast"):
            raise InputRangeError(f"{path}: row {k}", ",".join(row),
                                  "side (drive | coast), v_mm, u_mm, easeoff_um")
        try:
            v, u, e = (float(x) for x in row[1:])
        except ValueError:
            raise InputRangeError(f"{path}: row {k}", ",".join(row), "numbers") from None
        if not all(math.isfinite(x) for x in (v, u, e)):
            raise InputRangeError(f"{path}: row {k}", ",".join(row), "finite numbers")
        side = nodes.setdefault(row[0].strip(), {})
        if (u, v) in side:
            raise InputRangeError(f"{path}: row {k}", ",".join(row), "each (u, v) once per side")
        side[u, v] = e
    if not nodes:
        raise InputRangeError(f"{path}", "no rows", "at least one side's grid")
    out = {}
    for name, side in nodes.items():
        us, vs = sorted({u for u, _ in side}), sorted({v for _, v in side})
        if len(us) < 4 or len(vs) < 4 or len(side) != len(us) * len(vs):
            raise InputRangeError(f"{path}: {name} grid", f"{len(side)} nodes on {len(us)} u x "
                                  f"{len(vs)} v lines", "a complete grid of at least 4 x 4")
        out[name] = GridEaseOff(u_mm=np.array(us), v_mm=np.array(vs), relief_um=np.array(
            [[side[u, v] for v in vs] for u in us]))
    return out


def mean_normal_thickness_mm(drive: RadialSheet, coast: RadialSheet, *, u_mm: float,
                             v_mm: float, spiral_angle_deg: float) -> float:
    """Pinion mean normal tooth thickness s_mn from its two flanks, mm.

    The transverse arc thickness at the mean point (radius R, axial position v) is
    ``R |psi_coast - psi_drive|`` (angular positions of the two flanks of one tooth,
    both centred on the mean point at phi1 = 0); ``s_mn = s_mt cos(beta_m1)``
    (ISO 23509 clause 7, mean normal circular thickness).
    """
    pts = [sheet.evaluate(np.array([u_mm]), np.array([v_mm]), second=False).r[0]
           for sheet in (drive, coast)]
    ang = [np.arctan2(p[2], p[1]) for p in pts]
    d = abs((ang[1] - ang[0] + np.pi) % (2.0 * np.pi) - np.pi)
    radius = float(np.hypot(pts[0][1], pts[0][2]))
    return float(radius * d * np.cos(np.radians(spiral_angle_deg)))


def easeoff_limit_um(thickness_mm: float) -> float:
    """Largest accepted |E| over a flank, um: :data:`MAX_EASEOFF_THICKNESS_FRACTION`
    of the pinion mean normal tooth thickness ``thickness_mm``."""
    return 1e3 * MAX_EASEOFF_THICKNESS_FRACTION * float(thickness_mm)


def max_relief_um(easeoff: EaseOff, boundary) -> tuple[float, float, float]:
    """Largest |E| over a flank box (41 x 41 samples, corners included), um, and its
    (u, v) in mm. E is quadratic, so its extremes lie at corners or on edges."""
    b = boundary
    U, V = np.meshgrid(np.linspace(b.u_root, b.u_tip, 41), np.linspace(b.v_toe, b.v_heel, 41),
                       indexing="ij")
    E = 1e3 * np.abs(easeoff.relief_mm(U, V))
    k = np.unravel_index(int(np.argmax(E)), E.shape)
    return float(E[k]), float(U[k]), float(V[k])


def _corner_name(base: RadialSheet, u: float, v: float) -> str:
    """'toe/root'-style name of the flank region of (u, v)."""
    b = base.boundary
    prof = "root" if u < 0.5 * (b.u_root + b.u_tip) else "tip"
    face = "toe" if v < 0.5 * (b.v_toe + b.v_heel) else "heel"
    return f"{face}/{prof}"


def apply_easeoff(base: RadialSheet, easeoff: "EaseOff | GridEaseOff", *, limit_um: float
                  ) -> RadialSheet:
    """The eased flank ``r - E N`` of ``base`` as a new :class:`RadialSheet`.

    Parameters
    ----------
    base : RadialSheet
        The conjugate (un-eased) pinion flank.
    easeoff : EaseOff or GridEaseOff
    limit_um : float
        Largest |E| accepted over the flank, um (:func:`easeoff_limit_um`).

    Raises
    ------
    InputRangeError
        If |E| exceeds ``limit_um`` anywhere on the flank (the message names the
        largest relief, where it occurs and the limit).
    ArithmeticError
        If the node mapping does not converge.
    InputRangeError
        If ``base`` is a flank of a relieved blade
        (:class:`~gearcontact.geometry.kinked.KinkedFlank`), before any work.
    """
    if hasattr(base, "kinks"):
        # a KinkedFlank (relieved blade, geometry.kinked): the eased sheet is resampled
        # on one node grid across the kink, which would round it off
        raise InputRangeError(f"easeoff ({base.side}) base flank", f"{type(base).__name__} "
                              f"(pieces {', '.join(base.names)})", "a smooth pinion flank "
                              "(RadialSheet): an ease-off laid on a flank cut by a relieved "
                              "blade would smooth its kink")
    b = base.boundary
    e_max, u_k, v_k = max_relief_um(easeoff, b)
    if e_max > limit_um:
        raise InputRangeError(
            f"easeoff ({base.side}) relief at the {_corner_name(base, u_k, v_k)} corner "
            f"(u = {u_k:.2f}, v = {v_k:.2f} mm)", f"|E| = {e_max:.1f} um",
            f"<= {limit_um:.1f} um ({100 * MAX_EASEOFF_THICKNESS_FRACTION:g} % of the pinion "
            "mean normal tooth thickness; reduce the crowning or move the relief centre)")
    # eased nodes must map back into the base node box: the node moves by at most |E|
    # (times the in-plane part of the unit normal), so shrink by the largest relief
    # beyond the box, within the base grid's margin around the box
    margin = min(b.u_root - base.u_nodes[0], base.u_nodes[-1] - b.u_tip,
                 b.v_toe - base.v_nodes[0], base.v_nodes[-1] - b.v_heel)
    ends = np.meshgrid(base.u_nodes[[0, -1]], base.v_nodes[[0, -1]], indexing="ij")
    e_nodes = 1e-3 * max(e_max, 1e3 * float(np.abs(easeoff.relief_mm(*ends)).max()))
    shrink = max(_NODE_SHRINK_MM, min(1.2 * e_nodes + 0.005, 0.9 * margin))
    us = np.linspace(base.u_nodes[0] + shrink, base.u_nodes[-1] - shrink, len(base.u_nodes))
    vs = np.linspace(base.v_nodes[0] + shrink, base.v_nodes[-1] - shrink, len(base.v_nodes))
    U, V = np.meshgrid(us, vs, indexing="ij")
    if easeoff.is_zero:
        return RadialSheet(side=base.side, cone=base.cone, u_nodes=base.u_nodes,
                           v_nodes=base.v_nodes, psi_nodes=base.psi_nodes,
                           normal_sign=base.normal_sign, boundary=base.boundary)
    cone = base.cone
    R_target = cone.radius_mm(U, V)
    u0, v0 = U.copy(), V.copy()
    eps = 1e-6  # mm, finite-difference step of the (polynomial) relief gradient
    for _ in range(_ITER):
        s = base.evaluate(u0, v0, second=False)
        E = easeoff.relief_mm(u0, v0)
        p = s.r - E[..., None] * s.n
        dx = p[..., 0] - V
        Rp = np.hypot(p[..., 1], p[..., 2])
        dR = Rp - R_target
        if max(np.abs(dx).max(), np.abs(dR).max()) < 1e-12:  # 1 pm
            break
        # Newton step on (x(p), R(p)) = (v, R) with dp/du0 ~ r_u - E_u n (n' E term dropped)
        E_u = (easeoff.relief_mm(u0 + eps, v0) - E) / eps
        E_v = (easeoff.relief_mm(u0, v0 + eps) - E) / eps
        cols = []
        for d in (s.r_u - E_u[..., None] * s.n, s.r_v - E_v[..., None] * s.n):
            cols.append((d[..., 0], (p[..., 1] * d[..., 1] + p[..., 2] * d[..., 2]) / Rp))
        (a, c), (b, d) = cols
        det = a * d - b * c
        u0 = u0 - (d * dx - b * dR) / det
        v0 = v0 - (-c * dx + a * dR) / det
    else:
        raise CheckFailed(f"ease-off node mapping of the {base.side} flank did not converge "
                          f"(residual {max(np.abs(dx).max(), np.abs(dR).max()):.2e} mm)")
    # p (from the converged last iterate) has the node's x and R; its angle, unwrapped
    # against the base nodes (at most 0.04 mm away, << pi), is the new sample
    ang = np.arctan2(p[..., 2], p[..., 1])
    psi = ang + 2.0 * np.pi * np.round((base.psi_nodes - ang) / (2.0 * np.pi))
    return RadialSheet(side=base.side, cone=cone, u_nodes=us, v_nodes=vs, psi_nodes=psi,
                       normal_sign=base.normal_sign, boundary=base.boundary)
