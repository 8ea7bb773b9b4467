"""Stage A/B geometric contact gap, fp64 reference (docs/spec.md sec. 6, Algorithm 1).

One posed point ``p' = R p + t`` is compared with ``N`` gear samples ``(g_i, n_i)``
(positions in mm, outward unit normals, all in the meshing frame)::

    d_i     = p' - g_i                       (mm)
    gamma_i = -(n_i . d_i)                   signed gap, mm (docs/spec.md sec. 4 sign)
    rho_i   = || d_i + gamma_i n_i ||^2      perpendicular residual, mm^2

With ``n`` pointing out of the gear material towards the pinion, ``gamma < 0`` means
``p'`` lies outside the gear (open) and ``gamma > 0`` that it has penetrated.
``rho_i`` is the squared distance of ``g_i`` from the normal line through ``p'``
(Litvin & Fuentes 2004, sec. 6.1: the gap of two surfaces is measured along their
common normal); a sample takes part only when that line passes within the gate radius
``tau``: ``rho_i < tau^2``.

Two selection rules are provided:

``lanes=None`` (ideal)
    the sample with the smallest ``|gamma_i|`` among those with ``rho_i < tau^2`` wins;
    ties go to the lowest index.
``lanes=L`` (the datapath's rule, see :mod:`.golden`)
    samples are striped round-robin over L lanes (``i = l + k L``); each lane keeps the
    sample of smallest ``rho`` (strict ``<``: the earliest sample wins a tie); then the
    lane key is ``|gamma|`` if that sample passes the gate, else infinity, and the
    lowest lane holding the smallest key wins.  For ``N <= L`` (one sample per lane)
    both rules coincide.

No sample passing the gate gives ``valid = False`` with ``min_gap_mm = nan`` and
``min_idx = -1`` (documented sentinels of the fp64 model; the fixed-point sentinels are
in :mod:`.golden`).

References
----------
F. L. Litvin, A. Fuentes, *Gear Geometry and Applied Theory*, 2nd ed., Cambridge
University Press, 2004.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...validation import InputRangeError, check_array_finite, check_positive

__all__ = ["GapResult", "GapSampleTerms", "gap_reference", "gap_sample_terms",
           "validate_gap_inputs", "check_lanes", "UNIT_NORMAL_TOL", "ROTATION_TOL", "MAX_SAMPLES"]

#: Allowed deviation of ``||n_i||`` from 1 (dimensionless). Normals from the flank
#: generator are unit to ~1e-15; 1e-6 admits single-precision sources while rejecting
#: unnormalized gradients.
UNIT_NORMAL_TOL = 1e-6
#: Allowed max-abs deviation of ``R^T R`` from the identity (dimensionless).
ROTATION_TOL = 1e-6
#: Largest sample count; the datapath's 16-bit index reserves 0xFFFF as its sentinel.
MAX_SAMPLES = 0xFFFF


@dataclass(frozen=True)
class GapResult:
    """Result of one gap pass (fp64 reference).

    Attributes
    ----------
    min_gap_mm : float
        Signed gap of the winning sample, mm; ``nan`` if not valid.
    min_idx : int
        Index of the winning sample; ``-1`` if not valid.
    valid : bool
        False when no sample passes the gate ``rho < tau^2``.
    """

    min_gap_mm: float
    min_idx: int
    valid: bool


@dataclass(frozen=True)
class GapSampleTerms:
    """Per-sample terms of Algorithm 1 (fp64).

    Attributes
    ----------
    posed_point_mm : numpy.ndarray
        ``p' = R p + t``, shape (3,), mm.
    gamma_mm : numpy.ndarray
        Signed gaps ``-(n_i . (p' - g_i))``, shape (N,), mm.
    rho_mm2 : numpy.ndarray
        Perpendicular residuals ``||d_i + gamma_i n_i||^2``, shape (N,), mm^2.
    """

    posed_point_mm: np.ndarray
    gamma_mm: np.ndarray
    rho_mm2: np.ndarray


def _vector(field: str, value, shape: tuple[int, ...]) -> np.ndarray:
    arr = check_array_finite(field, value)
    if arr.shape != shape:
        raise InputRangeError(f"{field}.shape", arr.shape, f"shape {shape}")
    return arr


def validate_gap_inputs(R, t, p, samples_xyz, normals):
    """Check and convert the inputs of one gap pass.

    Parameters
    ----------
    R : array_like, shape (3, 3)
        Rotation matrix (dimensionless), orthonormal with det +1 to ``ROTATION_TOL``.
    t : array_like, shape (3,)
        Translation, mm.
    p : array_like, shape (3,)
        Point in its body frame, mm.
    samples_xyz : array_like, shape (N, 3)
        Gear sample positions, mm; ``1 <= N <= MAX_SAMPLES``.
    normals : array_like, shape (N, 3)
        Gear unit normals (dimensionless), ``| ||n|| - 1 | <= UNIT_NORMAL_TOL``.

    Returns
    -------
    tuple of numpy.ndarray
        ``(R, t, p, samples_xyz, normals)`` as float64 arrays.

    Raises
    ------
    InputRangeError
        Naming the field, value and allowed range of the first bad input.
    """
    R = _vector("R", R, (3, 3))
    t = _vector("t_mm", t, (3,))
    p = _vector("p_mm", p, (3,))
    g = check_array_finite("samples_xyz_mm", samples_xyz)
    n = check_array_finite("normals", normals)
    if g.ndim != 2 or g.shape[1] != 3 or not 1 <= g.shape[0] <= MAX_SAMPLES:
        raise InputRangeError("samples_xyz_mm.shape", g.shape,
                              f"(N, 3) with 1 <= N <= {MAX_SAMPLES}")
    if n.shape != g.shape:
        raise InputRangeError("normals.shape", n.shape, f"{g.shape} (same as samples_xyz_mm)")
    dev = np.abs(R.T @ R - np.eye(3)).max()
    if dev > ROTATION_TOL or np.linalg.det(R) < 0.0:
        raise InputRangeError("R", R.tolist(),
                              f"a rotation: max|R^T R - I| <= {ROTATION_TOL:g} and det R = +1")
    norms = np.linalg.norm(n, axis=1)
    bad = np.abs(norms - 1.0) > UNIT_NORMAL_TOL
    if bad.any():
        i = int(np.argmax(bad))
        raise InputRangeError(f"normals[{i}]", n[i].tolist(),
                              f"a unit vector: | ||n|| - 1 | <= {UNIT_NORMAL_TOL:g}")
    return R, t, p, g, n


def check_lanes(lanes, *, allow_none: bool = False) -> int | None:
    """Return the lane count L (power of two in [8, 64]); ``None`` only if allowed."""
    if lanes is None and allow_none:
        return None
    if lanes is None or isinstance(lanes, bool) or not isinstance(lanes, (int, np.integer)) \
            or not 8 <= lanes <= 64 or lanes & (lanes - 1):
        raise InputRangeError("lanes", lanes, ("None or " if allow_none else "")
                              + "a power of two in [8, 64]")
    return int(lanes)


def gap_sample_terms(R, t, p, samples_xyz, normals) -> GapSampleTerms:
    """Per-sample signed gap and perpendicular residual of Algorithm 1 in fp64.

    Parameters are those of :func:`validate_gap_inputs`.

    Returns
    -------
    GapSampleTerms
    """
    R, t, p, g, n = validate_gap_inputs(R, t, p, samples_xyz, normals)
    pp = R @ p + t
    d = pp[None, :] - g
    gamma = -np.einsum("ij,ij->i", n, d)
    e = d + gamma[:, None] * n
    rho = np.einsum("ij,ij->i", e, e)
    return GapSampleTerms(posed_point_mm=pp, gamma_mm=gamma, rho_mm2=rho)


def gap_reference(R, t, p, samples_xyz, normals, *, tau_mm: float,
                  lanes: int | None = None) -> GapResult:
    """Gated minimum signed gap of one posed point against gear samples (fp64).

    Parameters
    ----------
    R, t, p, samples_xyz, normals
        See :func:`validate_gap_inputs` (R dimensionless; t, p, samples in mm).
    tau_mm : float
        Gate radius, mm (> 0): a sample counts only if ``rho < tau_mm**2``.
    lanes : int or None, keyword-only
        ``None`` for the ideal rule, or the datapath's lane count L (power of two in
        [8, 64]) for its lane rule; see the module docstring.

    Returns
    -------
    GapResult
    """
    tau = check_positive("tau_mm", tau_mm)
    lanes = check_lanes(lanes, allow_none=True)
    terms = gap_sample_terms(R, t, p, samples_xyz, normals)
    gamma, rho = terms.gamma_mm, terms.rho_mm2
    tau2 = tau * tau
    n_samples = gamma.shape[0]
    if lanes is None:
        cand = np.flatnonzero(rho < tau2)
        if cand.size == 0:
            return GapResult(min_gap_mm=float("nan"), min_idx=-1, valid=False)
        win = int(cand[np.argmin(np.abs(gamma[cand]))])   # argmin: first of ties
        return GapResult(min_gap_mm=float(gamma[win]), min_idx=win, valid=True)
    keys = np.full(lanes, np.inf)
    best = np.full(lanes, -1)
    for lane in range(min(lanes, n_samples)):
        idx = np.arange(lane, n_samples, lanes)
        j = int(idx[np.argmin(rho[idx])])                 # earliest of equal rho
        best[lane] = j
        if rho[j] < tau2:
            keys[lane] = abs(gamma[j])
    if not np.isfinite(keys).any():
        return GapResult(min_gap_mm=float("nan"), min_idx=-1, valid=False)
    win = int(best[int(np.argmin(keys))])                  # lowest lane of ties
    return GapResult(min_gap_mm=float(gamma[win]), min_idx=win, valid=True)
