"""Compiled (numba) line-surface intersections behind the gap fields of :mod:`.stencil`.

:func:`gearcontact.tca.stencil.gap_at` intersects, for every tangent-plane sample, the
normal line ``q + lambda n`` with both posed flanks by Newton's method on
``R r(u, v) + c - q - lambda n = 0``. For the flanks of :mod:`gearcontact.geometry`
this module runs exactly that iteration (same start, update, clamping and stopping
rule) per line in compiled code, with the surfaces evaluated exactly as their
``evaluate`` methods do:

* :class:`~gearcontact.geometry.sheet.RadialSheet` (pinion): the quintic
  tensor-product B-spline of ``psi(u, v)`` and its first derivatives from the spline's
  own knots and coefficients (Cox-de Boor recursion; arguments clamped to the knot
  box as FITPACK does), then ``r = (v, R cos psi, R sin psi)``, ``r_u``, ``r_v``;
* :class:`~gearcontact.geometry.flank.FormateFlank` (gear): the blade cone in closed
  form.

Other surfaces (e.g. analytic test surfaces) have no compiled form
(:func:`kernel_surface` returns None) and use the vectorized numpy path of
:mod:`.stencil`. Results agree with that path to rounding (~1e-13 mm).

A surface is passed to the kernel as ``(kind, par, tx, ty, coef)``: ``kind`` 0 (sheet)
or 1 (cone), a float parameter vector and the spline arrays (empty for a cone).
"""

from __future__ import annotations

import weakref

import numpy as np
from numba import njit

__all__ = ["KIND_SHEET", "KIND_CONE", "kernel_surface", "intersect_lines"]

#: Surface kinds of the kernel.
KIND_SHEET = 0
KIND_CONE = 1
_EMPTY = np.zeros(0)
_CACHE: "weakref.WeakKeyDictionary" = weakref.WeakKeyDictionary()


def kernel_surface(surface):
    """The kernel form ``(kind, par, tx, ty, coef)`` of a flank, or None.

    Sheet ``par``: ``(kx, ky, apex_x, tan_delta, root_offset)``; cone ``par``:
    ``(centre[3], axis[3], e1[3], e2[3], rho_0, k = sigma tan(alpha), dedendum,
    k_v = heel_sign / rho_0)``.
    """
    from ..geometry.flank import FormateFlank
    from ..geometry.sheet import RadialSheet

    try:
        return _CACHE[surface]
    except (KeyError, TypeError):
        pass
    if type(surface) is RadialSheet:
        spline = surface._spline
        tx, ty, c = (np.ascontiguousarray(a, dtype=float) for a in spline.tck[:3])
        kx, ky = spline.degrees
        cone = surface.cone
        par = np.array([kx, ky, cone.apex_x_mm, cone.tan_delta, cone.root_offset_mm], float)
        out = (KIND_SHEET, par, tx, ty, c)
    elif type(surface) is FormateFlank:
        blade = surface.blade
        pl = blade.placement
        k = blade.sigma * np.tan(np.radians(blade.pressure_angle_deg))
        par = np.concatenate([pl.centre_mm, pl.axis, pl.e1, pl.e2,
                              [blade.radius_pitch_mm, k, surface.dedendum_mm, surface._kv]])
        out = (KIND_CONE, np.asarray(par, float), _EMPTY, _EMPTY, _EMPTY)
    else:
        return None
    _CACHE[surface] = out
    return out


@njit(cache=True)
def _basis(t, k, x, nb, dnb, left, right):
    """Non-zero B-spline basis values ``nb[0..k]`` and first derivatives ``dnb`` of
    degree ``k`` at ``x`` (clamped to the knot box; ``left``, ``right``: work arrays
    of k + 1); returns the knot span ``l`` (``nb[j]`` belongs to coefficient
    ``l - k + j``)."""
    n = t.shape[0]
    lo, hi = t[k], t[n - k - 1]
    clamped = x < lo or x > hi
    x = min(max(x, lo), hi)
    # span: t[l] <= x < t[l + 1], k <= l <= n - k - 2 (bisection)
    a = k
    b = n - k - 2
    while a < b:
        mid = (a + b + 1) // 2
        if x >= t[mid]:
            a = mid
        else:
            b = mid - 1
    l = a
    nb[0] = 1.0
    for j in range(1, k + 1):
        left[j] = x - t[l + 1 - j]
        right[j] = t[l + j] - x
        saved = 0.0
        for r in range(j):
            tmp = nb[r] / (right[r + 1] + left[j - r])
            nb[r] = saved + right[r + 1] * tmp
            saved = left[j - r] * tmp
        nb[j] = saved
        if j == k - 1:  # degree k-1 values give the derivatives of degree k
            for s in range(k + 1):
                d = 0.0
                if s >= 1:
                    i = l - k + s
                    d += nb[s - 1] / (t[i + k] - t[i])
                if s <= k - 1:
                    i = l - k + s + 1
                    d -= nb[s] / (t[i + k] - t[i])
                dnb[s] = 0.0 if clamped else k * d
    return l


@njit(cache=True)
def _eval_sheet(par, tx, ty, coef, u, v, out, work):
    """r, r_u, r_v of a radial sheet into ``out[0:3], out[3:6], out[6:9]``
    (``work``: (6, max(kx, ky) + 1) scratch)."""
    kx = int(par[0])
    ky = int(par[1])
    nu, dnu, nv, dnv = work[0], work[1], work[2], work[3]
    lu = _basis(tx, kx, u, nu, dnu, work[4], work[5])
    lv = _basis(ty, ky, v, nv, dnv, work[4], work[5])
    ncy = ty.shape[0] - ky - 1
    p = 0.0
    pu = 0.0
    pv = 0.0
    for a in range(kx + 1):
        row = (lu - kx + a) * ncy + lv - ky
        s0 = 0.0
        s1 = 0.0
        for b in range(ky + 1):
            cc = coef[row + b]
            s0 += nv[b] * cc
            s1 += dnv[b] * cc
        p += nu[a] * s0
        pu += dnu[a] * s0
        pv += nu[a] * s1
    tan = par[3]
    rad = (v - par[2]) * tan - par[4] + u
    cp = np.cos(p)
    sp = np.sin(p)
    out[0] = v
    out[1] = rad * cp
    out[2] = rad * sp
    # r_u = e_R + R pu e_psi, r_v = x + t e_R + R pv e_psi; e_R = (0, c, s), e_psi = (0, -s, c)
    out[3] = 0.0
    out[4] = cp - rad * pu * sp
    out[5] = sp + rad * pu * cp
    out[6] = 1.0
    out[7] = tan * cp - rad * pv * sp
    out[8] = tan * sp + rad * pv * cp


@njit(cache=True)
def _eval_cone(par, u, v, out):
    """r, r_u, r_v of a formate blade cone (h = dedendum - u, theta = k_v v)."""
    h = par[14] - u
    kv = par[15]
    th = kv * v
    c = np.cos(th)
    s = np.sin(th)
    rho = par[12] + par[13] * h
    for i in range(3):
        e_rho = c * par[6 + i] + s * par[9 + i]
        e_th = -s * par[6 + i] + c * par[9 + i]
        out[i] = par[i] + rho * e_rho + h * par[3 + i]
        out[3 + i] = -(par[13] * e_rho + par[3 + i])
        out[6 + i] = kv * rho * e_th


@njit(cache=True)
def _solve3(a, b, x):
    """x = a^-1 b for a 3 x 3 system (Gaussian elimination, partial pivoting).
    Overwrites ``a`` and ``b``."""
    for col in range(3):
        piv = col
        for r in range(col + 1, 3):
            if abs(a[r, col]) > abs(a[piv, col]):
                piv = r
        if piv != col:
            for j in range(3):
                tmp = a[col, j]
                a[col, j] = a[piv, j]
                a[piv, j] = tmp
            tmp = b[col]
            b[col] = b[piv]
            b[piv] = tmp
        for r in range(col + 1, 3):
            f = a[r, col] / a[col, col]
            for j in range(col, 3):
                a[r, j] -= f * a[col, j]
            b[r] -= f * b[col]
    for r in range(2, -1, -1):
        acc = b[r]
        for j in range(r + 1, 3):
            acc -= a[r, j] * x[j]
        x[r] = acc / a[r, r]


@njit(cache=True)
def intersect_lines(kind, par, tx, ty, coef, rot, trans, q, n, uv0, lo, hi, clamp,
                    tol_mm, max_iter, order, prev):
    """Newton intersections of the lines ``q_i + lambda n`` with a posed surface.

    Parameters
    ----------
    kind, par, tx, ty, coef
        Kernel form of the surface (:func:`kernel_surface`).
    rot, trans : ndarray (3, 3), (3,)
        Pose ``x -> rot x + trans`` of the surface.
    q : ndarray (N, 3)
        Points of the lines; ``n`` (3,) their common direction.
    uv0 : ndarray (N, 2)
        Starting parameters (with ``lambda = 0``).
    lo, hi : ndarray (2,)
        Parameter box; with ``clamp`` every iterate is clipped into it.
    tol_mm : float
        Residual tolerance; an iteration also has to move the parameters < 1e-12.
    max_iter : int
        Iteration limit.
    order, prev : ndarray (N,) of int
        Lines are solved in the sequence ``order``; line ``i`` starts instead from the
        tangent-plane prediction at the solution of line ``prev[i]`` (solved earlier)
        if that converged (inside the box, with ``clamp``); ``-1``: no predecessor.

    Returns
    -------
    lam : ndarray (N,)
        Line parameter of the intersection (NaN where Newton did not converge or, with
        ``clamp``, where it lies outside the box).
    inside : ndarray (N,) of bool
        Converged strictly inside the box.

    Notes
    -----
    Beyond the knot box a sheet's psi is FITPACK's constant extension; its derivative
    there is taken as zero (consistent), so such continuation points converge
    quadratically too.
    """
    m = q.shape[0]
    lam_out = np.empty(m)
    inside = np.zeros(m, dtype=np.bool_)
    ok = np.zeros(m, dtype=np.bool_)
    sol = np.empty((m, 3))        # converged (u, v, lambda)
    tang = np.empty((m, 6))       # posed r_u, r_v there
    ev = np.empty(9)
    work = np.empty((6, int(par[0:2].max()) + 1 if kind == 0 else 1))
    jac = np.empty((3, 3))
    rhs = np.empty(3)
    step = np.empty(3)
    x = np.empty(3)
    for i in order:
        u = uv0[i, 0]
        v = uv0[i, 1]
        lam = 0.0
        p = prev[i]
        if p >= 0 and ok[p]:
            for a in range(3):
                jac[a, 0] = tang[p, a]
                jac[a, 1] = tang[p, 3 + a]
                jac[a, 2] = -n[a]
                rhs[a] = q[i, a] - q[p, a]
            _solve3(jac, rhs, step)
            u = sol[p, 0] + step[0]
            v = sol[p, 1] + step[1]
            lam = sol[p, 2] + step[2]
            if clamp:
                u = min(max(u, lo[0]), hi[0])
                v = min(max(v, lo[1]), hi[1])
        converged = False
        for _ in range(max_iter):
            if kind == 0:
                _eval_sheet(par, tx, ty, coef, u, v, ev, work)
            else:
                _eval_cone(par, u, v, ev)
            res_max = 0.0
            for a in range(3):
                x[a] = 0.0
                ju = 0.0
                jv = 0.0
                for b in range(3):
                    x[a] += rot[a, b] * ev[b]
                    ju += rot[a, b] * ev[3 + b]
                    jv += rot[a, b] * ev[6 + b]
                res = x[a] + trans[a] - q[i, a] - lam * n[a]
                res_max = max(res_max, abs(res))
                rhs[a] = -res
                jac[a, 0] = ju
                jac[a, 1] = jv
                jac[a, 2] = -n[a]
                tang[i, a] = ju
                tang[i, 3 + a] = jv
            _solve3(jac, rhs, step)
            nu_ = u + step[0]
            nv_ = v + step[1]
            if clamp:
                nu_ = min(max(nu_, lo[0]), hi[0])
                nv_ = min(max(nv_, lo[1]), hi[1])
            moved = max(abs(nu_ - u), abs(nv_ - v))
            u = nu_
            v = nv_
            lam += step[2]
            if res_max < tol_mm and moved < 1e-12:
                converged = True
                break
        ins = converged and lo[0] < u < hi[0] and lo[1] < v < hi[1]
        inside[i] = ins
        ok[i] = converged and (ins or not clamp)
        sol[i, 0] = u
        sol[i, 1] = v
        sol[i, 2] = lam
        lam_out[i] = lam if ok[i] else np.nan
    return lam_out, inside
