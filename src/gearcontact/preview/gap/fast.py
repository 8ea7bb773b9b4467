"""Vectorized gap golden model: many posed points against many samples, bit-exact.

:func:`gap_golden_batch` runs one core pass per point (M points, each with its own or a
shared pose) against the same N samples and returns exactly what
:func:`.golden.gap_golden_codes` returns for each point -- same integer formulas, same
lane striping and tie rules (see :mod:`.golden`). The per-sample terms run in float64
when the format's structural bounds keep every intermediate an integer (or an integer
times 2^-rf) below 2^53 in magnitude -- true for the contract formats (docs/spec.md
sec. 6) and the whole cf sweep at rf = 19 -- with the normals stored pre-scaled by 2^-rf:
products and sums of such values, power-of-two scalings and ``floor`` are then exact
(Goldberg 1991, sec. 1.2), and this is ~1.4x faster than int64 on AVX-512 (which has no
full-rate 64-bit multiply). Otherwise they run in int64 (all intermediates < 2^60). Both
paths share one source (:func:`_nshift` is ``>> rf`` on integers, ``floor`` on floats)
and are tested bit-identical to the scalar model.

The empty-lane residual is held as 2^63 - 1 instead of the core's 2^64 - 1; both
exceed every real rho (< 2^56) and every gate (<= 2^63 - 1), so the outcome is
identical. It is compiled with numba (``parallel=True, cache=True``) when
numba is importable and otherwise runs the same code as plain Python (slow).

Per point, the (gamma, rho) terms of all samples are computed in one straight loop
(which LLVM vectorizes) and the lanes' running
minima are then taken beat by beat over that buffer (``i = k L + l``).

References
----------
D. Goldberg, "What every computer scientist should know about floating-point
arithmetic", ACM Computing Surveys 23(1), 1991.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...validation import InputRangeError, check_array_finite
from .golden import DEFAULT_FORMAT, IDX_SENTINEL, GapFormat, check_codes, quantize_pass
from .reference import MAX_SAMPLES, check_lanes
from .variants import residual_limit

try:  # numba is optional: the kernel is also valid Python
    from numba import get_num_threads, njit, prange
    HAVE_NUMBA = True
except ImportError:  # pragma: no cover - exercised only without numba
    HAVE_NUMBA = False
    prange = range

    def get_num_threads() -> int:
        return 1

    def njit(*args, **kwargs):
        return (lambda f: f) if not args or not callable(args[0]) else args[0]

__all__ = ["GapBatchCodes", "GapBatchResult", "gap_golden_batch", "gap_golden_points",
           "HAVE_NUMBA"]


def _fshift(x, n, scale):
    """``floor(x / 2^n)``: ``x >> n`` on integers, ``floor(x * 2^-n)`` on floats.

    For a float64 holding an integer of magnitude < 2^53 the product with the power
    of two ``scale = 2^-n`` and the floor are exact, so both branches agree.
    """
    if isinstance(x, (int, np.integer)):
        return x >> n
    return np.floor(x * scale)


def _nshift(x, n):
    """Normal-scale floor shift: ``x >> n`` on integers; ``floor(x)`` on floats, whose
    normals are stored pre-scaled by ``2^-n`` (exact), so x already carries it."""
    if isinstance(x, (int, np.integer)):
        return x >> n
    return np.floor(x)


if HAVE_NUMBA:
    from numba import types
    from numba.extending import overload

    @overload(_fshift, inline="always")
    def _fshift_overload(x, n, scale):
        if isinstance(x, types.Integer):
            return lambda x, n, scale: x >> n
        return lambda x, n, scale: np.floor(x * scale)

    @overload(_nshift, inline="always")
    def _nshift_overload(x, n):
        if isinstance(x, types.Integer):
            return lambda x, n: x >> n
        return lambda x, n: np.floor(x)


@dataclass(frozen=True)
class GapBatchCodes:
    """Per-point outputs of :func:`gap_golden_batch` (fields as in ``GapCodes``).

    Attributes
    ----------
    min_gap_code : numpy.ndarray
        int64 (M,), Q(gap_bits, cf) codes, mm; ``gap_sentinel`` where not valid.
    min_idx : numpy.ndarray
        int64 (M,), winning sample index; ``IDX_SENTINEL`` where not valid.
    valid : numpy.ndarray
        bool (M,).
    overflow : numpy.ndarray
        bool (M,), p' left the coordinate format.
    """

    min_gap_code: np.ndarray
    min_idx: np.ndarray
    valid: np.ndarray
    overflow: np.ndarray


@njit(cache=True, boundscheck=False, inline="always")
def _sample_terms(px, py, pz, gx, gy, gz, nx, ny, nz, rf, half, e_shift, e_lim, rho_inf,
                  rho, gam):
    """gamma and rho codes of every sample for the posed point (px, py, pz).

    ``e_lim > 0`` (lean variant, :mod:`.variants`): rho = ``rho_inf`` where an e_k
    leaves ``[-e_lim, e_lim - 1]``.

    Integer mode: ``g*``, ``n*`` int64 codes and ``half = 2^(rf-1)``. Float mode:
    float64 ``g*`` codes, normals pre-scaled to ``n 2^-rf`` and ``half = 0.5``; every
    value is then an integer (or an integer times 2^-rf) below 2^53 in magnitude, so
    all operations are exact and both modes give identical codes.
    """
    e_half = (np.int64(1) << (e_shift - 1)) if e_shift > 0 else np.int64(0)
    e_scale = 1.0 / (np.int64(1) << e_shift)
    for i in range(gx.shape[0]):
        dx = px - gx[i]
        dy = py - gy[i]
        dz = pz - gz[i]
        gm = _nshift(half - (nx[i] * dx + ny[i] * dy + nz[i] * dz), rf)
        ex = dx + _nshift(gm * nx[i] + half, rf)
        ey = dy + _nshift(gm * ny[i] + half, rf)
        ez = dz + _nshift(gm * nz[i] + half, rf)
        if e_shift > 0:                       # loop-invariant: LLVM unswitches it
            ex = _fshift(ex + e_half, e_shift, e_scale)
            ey = _fshift(ey + e_half, e_shift, e_scale)
            ez = _fshift(ez + e_half, e_shift, e_scale)
        # e^2 < 2^52, so a sum of two is exact in float64; the third add is int64
        rho[i] = np.int64(ex * ex + ey * ey) + np.int64(ez * ez)
        if e_lim > 0:                         # loop-invariant as well
            if (ex < -e_lim or ex >= e_lim or ey < -e_lim or ey >= e_lim
                    or ez < -e_lim or ez >= e_lim):
                rho[i] = rho_inf
        gam[i] = np.int64(gm)


@njit(parallel=True, cache=True, boundscheck=False)
def _batch_kernel(r, t, p, gx, gy, gz, nx, ny, nz, n_half, tau2, lanes, rf, cmin, cmax,
                  e_shift, e_lim, key_inf, gap_sent, idx_sent, rho_inf, n_chunks,
                  out_gap, out_idx, out_valid, out_ovf):
    m_pts = p.shape[0]
    n_smp = gx.shape[0]
    half = np.int64(1) << (rf - 1)
    beats = (n_smp + lanes - 1) // lanes
    n_pad = beats * lanes
    per = (m_pts + n_chunks - 1) // n_chunks
    per_r = 1 if r.shape[0] == m_pts else 0     # shared (1) or per-point (M) poses
    per_t = 1 if t.shape[0] == m_pts else 0
    for c in prange(n_chunks):
        rho = np.empty(n_pad, np.int64)      # per-thread buffers, samples padded
        gam = np.zeros(n_pad, np.int64)      # to whole beats with empty slots
        rho[n_smp:] = rho_inf
        l_rho = np.empty(lanes, np.int64)
        l_k = np.empty(lanes, np.int64)
        for m in range(c * per, min(m_pts, (c + 1) * per)):
            a, b = per_r * m, per_t * m
            px = ((t[b, 0] << rf) + r[a, 0, 0] * p[m, 0] + r[a, 0, 1] * p[m, 1]
                  + r[a, 0, 2] * p[m, 2] + half) >> rf
            py = ((t[b, 1] << rf) + r[a, 1, 0] * p[m, 0] + r[a, 1, 1] * p[m, 1]
                  + r[a, 1, 2] * p[m, 2] + half) >> rf
            pz = ((t[b, 2] << rf) + r[a, 2, 0] * p[m, 0] + r[a, 2, 1] * p[m, 1]
                  + r[a, 2, 2] * p[m, 2] + half) >> rf
            ovf = ((px < cmin) | (px > cmax) | (py < cmin) | (py > cmax)
                   | (pz < cmin) | (pz > cmax))
            out_ovf[m] = ovf
            out_gap[m] = gap_sent
            out_idx[m] = idx_sent
            out_valid[m] = False
            if ovf:
                continue
            _sample_terms(px, py, pz, gx, gy, gz, nx, ny, nz, rf, n_half, e_shift, e_lim,
                          rho_inf, rho, gam)
            for lane in range(lanes):        # beat 0, then strict-< updates:
                l_rho[lane] = rho[lane]      # the earliest sample wins a lane tie
                l_k[lane] = 0
            for k in range(1, beats):
                b = k * lanes
                for lane in range(lanes):
                    v = rho[b + lane]
                    upd = v < l_rho[lane]
                    l_rho[lane] = v if upd else l_rho[lane]
                    l_k[lane] = k if upd else l_k[lane]
            best = key_inf
            win = 0
            for lane in range(lanes):        # lowest lane of the minimal key (tree rule)
                key = abs(gam[l_k[lane] * lanes + lane]) if l_rho[lane] < tau2 else key_inf
                if key < best:
                    best = key
                    win = lane
            if best != key_inf:
                i = l_k[win] * lanes + win
                out_gap[m] = gam[i]
                out_idx[m] = i
                out_valid[m] = True


def _codes(field: str, a, shape_tail: tuple[int, ...]) -> np.ndarray:
    arr = np.asarray(a)
    if not np.issubdtype(arr.dtype, np.integer) or arr.shape[-len(shape_tail):] != shape_tail:
        raise InputRangeError(f"{field}", f"dtype {arr.dtype}, shape {arr.shape}",
                              f"integer codes of shape (..., {', '.join(map(str, shape_tail))})")
    return np.ascontiguousarray(arr, dtype=np.int64)


def gap_golden_batch(r_code, t_code, p_code, g_code, n_code, tau2_code: int, *,
                     lanes: int = 16, fmt: GapFormat = DEFAULT_FORMAT,
                     variant: str = "published") -> GapBatchCodes:
    """One gap pass per point, bit-identical to :func:`.golden.gap_golden_codes`.

    Parameters
    ----------
    r_code : array_like of int, shape (3, 3) or (M, 3, 3)
        Rotation codes Q(rf+2, rf), ``|c| <= 2^rf`` (shared or per point).
    t_code : array_like of int, shape (3,) or (M, 3)
        Translation codes, coordinate format (mm).
    p_code : array_like of int, shape (M, 3)
        Body points, coordinate codes (mm).
    g_code, n_code : array_like of int, shape (N, 3)
        Gear samples (coordinate codes, mm) and normals (normal codes).
    tau2_code : int
        Gate, UQ(64, rho_frac) code (mm^2).
    lanes, fmt, variant : keyword-only
        As in :func:`.golden.gap_golden_codes`.

    Returns
    -------
    GapBatchCodes
    """
    lanes = check_lanes(lanes)
    e_lim = residual_limit(variant)
    p = _codes("p_code", p_code, (3,))
    if p.ndim != 2:
        raise InputRangeError("p_code.shape", p.shape, "(M, 3)")
    m = p.shape[0]
    r = _codes("r_code", r_code, (3, 3)).reshape(-1, 3, 3)
    t = _codes("t_code", t_code, (3,)).reshape(-1, 3)
    for name, a in (("r_code", r), ("t_code", t)):
        if a.shape[0] not in (1, m):
            raise InputRangeError(f"{name}.shape", a.shape, f"one pose or M = {m} poses")
    g = _codes("g_code", g_code, (3,))
    n = _codes("n_code", n_code, (3,))
    if not 1 <= g.shape[0] <= MAX_SAMPLES or g.ndim != 2 or n.shape != g.shape:
        raise InputRangeError("g_code/n_code shape", (g.shape, n.shape),
                              f"equal shapes (N, 3), 1 <= N <= {MAX_SAMPLES}")
    check_codes(fmt=fmt, r=r, t=t, p=p, g=g, n=n, tau2=tau2_code)
    cmin, cmax = fmt.coord.min_code, fmt.coord.max_code
    out_gap = np.empty(m, np.int64)
    out_idx = np.empty(m, np.int64)
    out_valid = np.empty(m, np.bool_)
    out_ovf = np.empty(m, np.bool_)
    # float64 is exact iff |n.d|, |gamma n| < 2^53 and e^2 < 2^52 (see golden formats)
    exact_f64 = fmt.dot_bits <= 54 and fmt.e_bits <= 27
    dtype = np.float64 if exact_f64 else np.int64
    gt, nt = np.ascontiguousarray(g.T, dtype=dtype), np.ascontiguousarray(n.T, dtype=dtype)
    if exact_f64:
        nt *= 2.0 ** -fmt.normal_frac            # exact: power-of-two scaling
        n_half = np.float64(0.5)
    else:
        n_half = np.int64(1 << (fmt.normal_frac - 1))
    _batch_kernel(r, t, p, gt[0], gt[1], gt[2], nt[0], nt[1], nt[2], n_half,
                  np.int64(tau2_code), np.int64(lanes), np.int64(fmt.normal_frac),
                  np.int64(cmin), np.int64(cmax), np.int64(fmt.e_shift),
                  np.int64(e_lim), np.int64(fmt.key_inf), np.int64(fmt.gap_sentinel),
                  np.int64(IDX_SENTINEL), np.int64((1 << 63) - 1),
                  np.int64(max(1, min(m, 8 * get_num_threads()))),
                  out_gap, out_idx, out_valid, out_ovf)
    return GapBatchCodes(min_gap_code=out_gap, min_idx=out_idx, valid=out_valid,
                         overflow=out_ovf)


@dataclass(frozen=True)
class GapBatchResult:
    """Per-point golden results in physical units (see :class:`GapBatchCodes`).

    Attributes
    ----------
    min_gap_mm : numpy.ndarray
        float64 (M,), winning signed gap, mm; ``nan`` where not valid.
    min_gap_code : numpy.ndarray
        int64 (M,), its Q(gap_bits, cf) code.
    min_idx : numpy.ndarray
        int64 (M,), winning sample index; ``IDX_SENTINEL`` where not valid.
    valid : numpy.ndarray
        bool (M,).
    overflow : numpy.ndarray
        bool (M,), p' = R p + t left the coordinate range (then not valid).
    """

    min_gap_mm: np.ndarray
    min_gap_code: np.ndarray
    min_idx: np.ndarray
    valid: np.ndarray
    overflow: np.ndarray


def gap_golden_points(R, t, points_mm, samples_xyz, normals, *, tau_mm: float,
                      lanes: int = 16, fmt: GapFormat = DEFAULT_FORMAT) -> GapBatchResult:
    """Quantize real inputs and run one golden pass per point (shared pose).

    Parameters
    ----------
    R : array_like, shape (3, 3)
        Rotation (dimensionless), see :func:`.reference.validate_gap_inputs`.
    t : array_like, shape (3,)
        Translation, mm.
    points_mm : array_like, shape (M, 3)
        Body points, mm.
    samples_xyz, normals : array_like, shape (N, 3)
        Gear samples (mm) and unit normals.
    tau_mm : float, keyword-only
        Gate radius, mm.
    lanes, fmt : keyword-only
        As in :func:`.golden.gap_golden_codes`.

    Returns
    -------
    GapBatchResult
        Overflowing points are flagged per point (``overflow``), not raised.
    """
    pts = check_array_finite("points_mm", points_mm)
    if pts.ndim != 2 or pts.shape[1] != 3 or pts.shape[0] < 1:
        raise InputRangeError("points_mm.shape", pts.shape, "(M, 3) with M >= 1")
    vec = quantize_pass(R, t, pts[0], samples_xyz, normals, tau_mm=tau_mm, fmt=fmt)
    codes = gap_golden_batch(vec.r_code, vec.t_code,
                             fmt.coord.quantize_array(pts, field="points_mm"),
                             vec.g_code, vec.n_code, vec.tau2_code, lanes=lanes, fmt=fmt)
    gap_mm = np.where(codes.valid, fmt.gap.to_float(codes.min_gap_code), np.nan)
    return GapBatchResult(min_gap_mm=gap_mm, min_gap_code=codes.min_gap_code,
                          min_idx=codes.min_idx, valid=codes.valid, overflow=codes.overflow)
