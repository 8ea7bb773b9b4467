"""The curvature of a setting fit's residual along the target's contact path, and the
Hertz bound of the contact pressure change it implies.

A fitted flank that lies within ``eps`` of its target moves every initial gap by at most
``eps`` (a bound on the transmission error), but the contact pressure follows the
relative curvature of the flanks, which the residual ``d(u, v)`` (normal deviation, um,
:func:`~.setting_fit.flank_deviation_um`) changes by its second derivatives. At a point
of the target's contact path with half relative curvature tensor ``K`` (1/mm, gap
``g = x^T K x`` in an orthonormal basis of the common tangent plane, eigenvalues ``A``
and ``B``: :mod:`gearcontact.analytic.hertz`), the cut pair's tensor is, to first order
in ``d``,

    K' = K + dK,    dK = +-(1/2) H_d  (+ the offset term ``|d| kappa^2 / 2``),

``H_d`` the Hessian of ``d`` in tangent-plane arc lengths (chain rule through the
target sheet, :func:`tangent_hessian`). With the relative curvature error

    E = K^(-1/2) dK K^(-1/2),    e = ||E||_2 + |d| kappa_max^2 / (2 lambda_min(K)),

``(1 - e) K <= K' <= (1 + e) K`` in the Loewner order, so each principal value moves by
at most a factor ``1 +- e`` (Courant-Fischer), and since the Hertz peak pressure is
increasing in each of ``A`` and ``B`` and homogeneous of degree 2/3 in them (the
elliptic solution; degree 1/2 in ``B_max`` for an ellipse truncated by the flank, the
line contact), the peak pressure of the cut pair at the same load satisfies

    |p' / p - 1| <= 1 - (1 - e)^(2/3)     (e < 1),

the bound of :func:`pressure_bound` (docs/machine_settings.md sec. 6, "The residual's
curvature and the pressure it bounds").

The fit can be asked to keep ``E`` small at the path points (:class:`CurvedFitProblem`):
rows ``paint_um * (E_11, sqrt(2) E_12, E_22)`` join the gap rows of the least squares,
``paint_um`` = 6.35 um, the paint thickness the TCA's contact ellipse is drawn at: a
row is the gap change the residual's curvature makes at the end of the paint ellipse's
axis (``x^T dK x`` at ``x^T K x = paint``), in the gap rows' unit.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.interpolate import RectBivariateSpline

from ..validation import InputRangeError
from .setting_fit import FitProblem

__all__ = ["CURVATURE_PARAMETERS", "CurvedFitProblem", "PAINT_UM", "PathCurvature",
           "PathResidual", "curvature_rows", "path_residual", "pressure_bound",
           "spline_derivatives", "tangent_hessian"]

#: Added to the fitted subset of a side fitted with curvature rows: the helical motion
#: V_1, the lengthwise freedom the rows need (the choice measured in
#: docs/machine_settings.md sec. 6, "The residual's curvature and the pressure it
#: bounds").
CURVATURE_PARAMETERS = ("helical_motion_mm_per_rad",)
#: The paint thickness of the TCA's contact ellipse (tca.curvature.PAINT_THICKNESS_MM),
#: um: the scale of the curvature rows (module docstring).
PAINT_UM = 6.35


@dataclass(frozen=True)
class PathCurvature:
    """The target pair's contact path on one pinion flank.

    Attributes
    ----------
    u_mm, v_mm : ndarray (n,)
        The path's surface contacts on the pinion sheet (height above the root cone,
        axial position), mm; the first is the reference point P0 (the TCA's mean
        contact, where the loaded commands solve the single pair).
    basis : ndarray (n, 3, 2)
        An orthonormal basis of the tangent plane at each point, pinion body frame.
    tensor_per_mm : ndarray (n, 2, 2)
        The half relative curvature tensor ``K`` in ``basis`` (eigenvalues ``A``, ``B``
        of :mod:`gearcontact.analytic.hertz`), 1/mm, positive definite.
    """

    u_mm: np.ndarray
    v_mm: np.ndarray
    basis: np.ndarray
    tensor_per_mm: np.ndarray

    def __post_init__(self):
        lam = np.linalg.eigvalsh(self.tensor_per_mm)
        if not (np.all(np.isfinite(lam)) and np.all(lam > 0.0)):
            raise InputRangeError("tensor_per_mm (path curvature)", float(np.min(lam)),
                                  "positive definite half relative curvatures (point "
                                  "contact: no line contact, no edge contact)")


@dataclass(frozen=True)
class PathResidual:
    """The residual's curvature at the target's contact path (module docstring).

    Attributes
    ----------
    error : ndarray (n,)
        ``e`` at each path point: the relative curvature error, dimensionless.
    hessian_per_mm : ndarray (n, 2, 2)
        ``H_d`` in the path's tangent basis, 1/mm.
    deviation_um : ndarray (n,)
        The residual ``d`` at the path points, um.
    """

    error: np.ndarray
    hessian_per_mm: np.ndarray
    deviation_um: np.ndarray

    @property
    def max_error(self) -> float:
        """The largest ``e`` over the path."""
        return float(np.max(self.error))

    @property
    def reference_error(self) -> float:
        """``e`` at the reference point P0 (the path's first point)."""
        return float(self.error[0])

    @property
    def pressure_bound(self) -> float:
        """:func:`pressure_bound` of :attr:`max_error`: the relative peak pressure
        change the residual's curvature allows anywhere on the path."""
        return pressure_bound(self.max_error)


def pressure_bound(error: float) -> float:
    """The bound ``1 - (1 - e)^(2/3)`` of the relative Hertz peak pressure change for a
    relative curvature error ``e`` (module docstring); ``inf`` for ``e >= 1`` (the
    perturbed tensor may not be positive definite: no bound)."""
    e = float(error)
    if not e >= 0.0:
        raise InputRangeError("error", e, "a relative curvature error >= 0")
    return math.inf if e >= 1.0 else 1.0 - (1.0 - e) ** (2.0 / 3.0)


def spline_derivatives(us, vs, values, u, v) -> np.ndarray:
    """``(d_u, d_v, d_uu, d_uv, d_vv)`` at the points ``(u, v)`` of the bicubic spline
    interpolating ``values`` (``(len(us), len(vs))``, any unit) on the grid ``us x vs``:
    (5, n), the unit of ``values`` per mm, per mm^2."""
    spl = RectBivariateSpline(us, vs, values, kx=3, ky=3, s=0.0)
    return np.array([spl.ev(u, v, dx=i, dy=j)
                     for i, j in ((1, 0), (0, 1), (2, 0), (1, 1), (0, 2))])


def tangent_hessian(target, path: PathCurvature, derivs: np.ndarray) -> np.ndarray:
    """The Hessian (n, 2, 2) in ``path.basis`` (arc lengths) of a function on the
    target sheet with sheet derivatives ``derivs`` = ``(d_u, d_v, d_uu, d_uv, d_vv)``
    (5, n, ...) at the path points: ``H = M^-T (D2 - g_a S_a) M^-1`` with
    ``M = basis^T [r_u r_v]``, ``g = M^-T (d_u, d_v)`` and ``S_a`` the second
    derivatives of ``r`` along basis vector ``a`` (the chain rule of the tangent-plane
    coordinates ``sigma = basis^T (r - r_0)``). Extra trailing axes of ``derivs``
    are carried (the columns of a linear map)."""
    s = target.evaluate(path.u_mm, path.v_mm, second=True)
    b = path.basis
    m = np.stack([np.einsum("nka,nk->na", b, s.r_u), np.einsum("nka,nk->na", b, s.r_v)],
                 axis=-1)                                        # (n, a, i)
    mi = np.linalg.inv(m)                                        # (n, i, a)
    sec = np.stack([np.einsum("nka,nk->na", b, r) for r in (s.r_uu, s.r_uv, s.r_vv)],
                   axis=-1)                                      # (n, a, 3)
    d = np.asarray(derivs, dtype=float)
    extra = d.shape[2:]
    d = d.reshape(5, d.shape[1], -1)                             # (5, n, c)
    g = np.einsum("nia,inc->nac", mi, d[:2])                     # sigma gradient
    flat = d[2:] - np.einsum("nac,naj->jnc", g, sec)             # (uu, uv, vv) - g.S
    d2 = np.stack([np.stack([flat[0], flat[1]], axis=1),
                   np.stack([flat[1], flat[2]], axis=1)], axis=1)    # (n, i, j, c)
    h = np.einsum("nia,nijc,njb->nabc", mi, d2, mi)
    return h.reshape(h.shape[:3] + extra)


def _inverse_root(tensor: np.ndarray) -> np.ndarray:
    lam, vec = np.linalg.eigh(tensor)
    return np.einsum("nij,nj,nkj->nik", vec, 1.0 / np.sqrt(lam), vec)


def curvature_rows(target, path: PathCurvature, us, vs) -> np.ndarray:
    """The linear map (3 n, len(us) len(vs)) from the deviation (um) on the fit grid
    ``us x vs`` to the rows ``paint_um * (E_11, sqrt(2) E_12, E_22)`` at the ``n`` path
    points (module docstring; ``E`` of the bicubic spline through the grid values, sum
    of squares = ``paint_um^2 ||E||_F^2``)."""
    nu, nv = len(us), len(vs)
    eye = np.eye(nu * nv).reshape(nu, nv, nu * nv)
    derivs = np.stack([spline_derivatives(us, vs, eye[:, :, c], path.u_mm, path.v_mm)
                       for c in range(nu * nv)], axis=-1)        # (5, n, c)
    h = tangent_hessian(target, path, derivs)                    # (n, 2, 2, c), um/mm^2
    w = _inverse_root(path.tensor_per_mm)
    e = np.einsum("nia,nabc,nbj->nijc", w, 0.5e-3 * h, w)
    rows = np.stack([e[:, 0, 0], math.sqrt(2.0) * e[:, 0, 1], e[:, 1, 1]], axis=1)
    return PAINT_UM * rows.reshape(-1, nu * nv)


def path_residual(target, path: PathCurvature, u_mm, v_mm, residual_um) -> PathResidual:
    """The residual's curvature at the path points: ``e``, ``H_d`` and ``d`` (module
    docstring), from the bicubic spline through the residual map ``residual_um`` on the
    grid ``u_mm x v_mm`` (meshgrid arrays, ``ij`` indexing: the map of
    :func:`~.setting_fit.flank_deviation_um`)."""
    us, vs = np.asarray(u_mm)[:, 0], np.asarray(v_mm)[0, :]
    derivs = spline_derivatives(us, vs, residual_um, path.u_mm, path.v_mm)
    dev = RectBivariateSpline(us, vs, residual_um, kx=3, ky=3, s=0.0).ev(path.u_mm,
                                                                        path.v_mm)
    h = 1e-3 * tangent_hessian(target, path, derivs)             # 1/mm
    w = _inverse_root(path.tensor_per_mm)
    e = np.einsum("nia,nab,nbj->nij", w, 0.5 * h, w)
    lam = np.linalg.eigvalsh(path.tensor_per_mm)
    offset = 0.5e-3 * np.abs(dev) * _kappa_max(target, path) ** 2 / lam[:, 0]
    return PathResidual(error=np.abs(np.linalg.eigvalsh(e)).max(axis=1) + offset,
                        hessian_per_mm=h, deviation_um=dev)


def _kappa_max(target, path: PathCurvature) -> np.ndarray:
    """The target's largest |principal curvature| at the path points, 1/mm."""
    s = target.evaluate(path.u_mm, path.v_mm, second=True)
    out = []
    for k in range(len(path.u_mm)):
        first = np.array([[s.r_u[k] @ s.r_u[k], s.r_u[k] @ s.r_v[k]],
                          [s.r_u[k] @ s.r_v[k], s.r_v[k] @ s.r_v[k]]])
        second = np.array([[s.r_uu[k] @ s.n[k], s.r_uv[k] @ s.n[k]],
                           [s.r_uv[k] @ s.n[k], s.r_vv[k] @ s.n[k]]])
        out.append(np.abs(np.linalg.eigvals(np.linalg.solve(first, second))).max())
    return np.array(out)


class CurvedFitProblem(FitProblem):
    """A :class:`~.setting_fit.FitProblem` whose residual vector is the deviation at
    the grid nodes followed by the curvature rows at the target's contact path
    (:func:`curvature_rows`): the fit keeps the residual's curvature small where the
    pair touches (module docstring). ``gap_rows`` is the number of grid nodes."""

    def __init__(self, seed, blank, target, names, us, vs, path: PathCurvature):
        super().__init__(seed, blank, target, names, us, vs)
        self.rows = curvature_rows(target, path, us, vs)
        self.gap_rows = self.U.size

    def deviation_um(self, x, *, keep: bool = False) -> np.ndarray:
        dev = super().deviation_um(x, keep=keep)
        return np.concatenate([dev, self.rows @ dev])
