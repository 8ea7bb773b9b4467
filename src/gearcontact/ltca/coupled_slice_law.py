"""The coupled slice law: the slice law (:mod:`.slice_law`) on a line whose teeth also
bend (docs/cylindrical.md sec. 8, 10).

The slice law distributes a line's load ``W`` along its ``n`` slices on the half-space
foundation alone: the line load ``w = K (d - h)^+`` with the Winkler modulus ``K`` of the
finite Hertz line (:func:`.slice_law.loaded_line`). The loaded TE's LCP also bends both
teeth (:mod:`.cylindrical_bending`), which closes the gap where the neighbours carry
load and so spreads the load along the line. The coupled law adds that deflection to
the ease-off::

    w = K (d - h - G f)^+,     f_j = w_j dy (the slice forces, N),  sum f = W

with ``G`` (n, n), mm/N, the bending compliance of the pinion and the gear tooth at the
slices' line points (:func:`line_bending_compliance`: the shell operators the loaded TE
uses, restricted to the line's slice positions of both members), so that ``G f`` is the
normal deflection at each slice's centre. It is the slice law on the *effective
ease-off* ``x = h + G f(x)`` (over its least), with ``f(x)`` the slice law's forces on
``x`` (each slice's part of the interference, :func:`.slice_law.interference`'s
shares, times ``W / I``: they sum to ``W``). The fixed point is solved by Newton on
``R(x) = x - h - G f(x)`` with the Jacobian ``1 - G df/dx`` (``df/dx`` by forward
differences, ``n + 1`` slice-law solves per step; ``-df/dx`` has ones in its null
space, so ``(1 - G df/dx) 1 = 1``, and with ``G`` positive semi-definite the step was
regular in every case met, 2-4 steps on the examples) and a halving line search on
``max |R|``. The tip edge's slices beyond the line's ends (``edge_slices``, as the
twin's law takes them) join the same fixed point with their rows and columns of ``G``. ``w >= 0`` holds by the foundation's ``(.)^+``: the
active set is the slice law's own loaded length. The peak line load, the loaded and the
equivalent length are then the slice law's on ``x`` (``w_peak = W d_c / I``,
``L_eq = I / d_c``). ``G = 0`` returns the uncoupled slice law itself (the same call, bit
for bit), and so does ``G = c 1 1^T`` (bending in series: every slice deflects alike).

References
----------
K. L. Johnson, *Contact Mechanics*, 1985, sec. 4.3 (the line's foundation).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import CheckFailed
from ..tca.cylindrical_cycle import LineGaps
from ..validation import InputRangeError
from .cylindrical_bending import line_bending_factor
from .slice_law import interference, loaded_line
from .tooth_bending import ToothBending

__all__ = ["CoupledLine", "coupled_line", "line_bending_compliance"]

#: Convergence of the effective ease-off: ``max |R| <= TOL_REL * max |G f| + TOL_ABS``
#: (mm): 1e-10 of the bending deflection is far below the slice law's own resolution
#: (its Newton stops at 1e-14 of ``d``; the forward differences err by ~1e-7 relative,
#: which slows Newton but does not move the fixed point).
TOL_REL = 1e-10
TOL_ABS = 1e-15
#: Forward-difference step of ``df/dx``, mm (the ease-offs are 1e-4-1e-1 mm; the slice
#: law's approach is solved to ~1e-17 mm, so the quotient errs by ~1e-8 relative).
FD_STEP_MM = 1e-9
MAX_STEPS = 60


@dataclass(frozen=True)
class CoupledLine:
    """The coupled slice law of one line (module docstring).

    Attributes
    ----------
    approach_mm : float
        ``d_c`` on the effective ease-off (over its least), mm.
    loaded_length_mm : float
        ``L_c``, mm.
    interference_mm2 : float
        ``I``, mm^2.
    effective_ease_mm : ndarray (n,)
        ``x = h + G f`` over its least, mm.
    slice_load_n : ndarray (n,)
        The slice forces ``f`` (N), summing to ``W``.
    steps : int
        Newton steps taken (0: ``G = 0`` or no load).
    """

    approach_mm: float
    loaded_length_mm: float
    interference_mm2: float
    effective_ease_mm: np.ndarray
    slice_load_n: np.ndarray
    steps: int


def line_bending_compliance(teeth: ToothBending, slices: LineGaps, j: int, k: int
                            ) -> np.ndarray:
    """``G`` (n, n), mm/N, of pair ``j``'s line at phase ``k``: the bending compliance of
    the pinion plus the gear tooth between the line points of its slices
    (:func:`.cylindrical_bending.line_bending_factor` at the slices' axial positions and
    roll lengths, one cell across: the loaded TE's rows, ``G = F F^T``).

    Raises
    ------
    CheckFailed
        A slice's line point is missing (NaN roll length): the line's slices left it.
    """
    z = np.broadcast_to(slices.z_mm, slices.gap_mm.shape)[j, k]
    u1, u2 = slices.pinion_roll_mm[j, k], slices.gear_roll_mm[j, k]
    if not (np.isfinite(u1).all() and np.isfinite(u2).all()):
        raise CheckFailed(f"pair {j} phase {k}: a slice of the line has no line point "
                          "(docs/cylindrical.md sec. 10)")
    f = np.asarray(line_bending_factor(teeth, z, u1, u2, 1)[:, 0, :], np.float64)
    return f @ f.T


def _forces(x, n, length, we, b_max, e_prime, nb, wb):
    """``(d_c, L_c, I, f)`` of the slice law on the ease-off ``x`` (m = n + 2 nb: the
    line's slices, then the edge's beyond its ends), its slice forces ``f = W shares /
    I`` (N, m)."""
    m = x.size
    h = np.zeros(2 * m)
    h[:m] = x
    d_c, l_c, area = loaded_line(h, 0, n, length, we, b_max, e_prime, nb, wb)
    interference(h, 0, n, length / n, d_c, True, nb, wb)
    return d_c, l_c, area, we * h[m:] / area


def coupled_line(ease_mm, length_mm: float, load_n: float, b_max_per_mm: float,
                 e_prime_mpa: float, compliance_mm_per_n=None, *, edge_slices: int = 0,
                 edge_width_mm: float = 0.0) -> CoupledLine:
    """The coupled slice law (module docstring) of one line: the ease-off ``ease_mm``
    (m = n + 2 ``edge_slices`` slices, mm: the line's n, then the tip edge's beyond
    either end, as :func:`.slice_law.interference` takes them on ``edge_width_mm``,
    the edge slices' width times their foundation's relative stiffness) of a line of
    ``length_mm``, loaded by ``load_n`` (N) across the curvature ``b_max_per_mm``
    (1/mm) with the modulus ``e_prime_mpa``, its teeth's bending compliance
    ``compliance_mm_per_n`` ((m, m) mm/N, symmetric; None or all 0: the uncoupled slice
    law, bit for bit).

    Raises
    ------
    InputRangeError
        ``compliance_mm_per_n`` not (n, n), not finite or not symmetric.
    CheckFailed
        Newton did not reach the tolerance in ``MAX_STEPS`` steps.
    """
    h = np.asarray(ease_mm, np.float64)
    nb, wb = int(edge_slices), float(edge_width_mm)
    n = h.size - 2 * nb
    if n < 2 or nb < 0:
        raise InputRangeError("edge_slices", edge_slices,
                              f"0 .. {(h.size - 2) // 2} (ease_mm has {h.size} slices)")
    length, we = float(length_mm), float(load_n)
    b_max, e_prime = float(b_max_per_mm), float(e_prime_mpa)
    g = None if compliance_mm_per_n is None else np.asarray(compliance_mm_per_n, np.float64)
    if g is not None:
        if g.shape != (h.size, h.size) or not np.isfinite(g).all() \
                or np.abs(g - g.T).max() > 1e-9 * max(np.abs(g).max(), 1e-300):
            raise InputRangeError("compliance_mm_per_n", f"shape {g.shape}",
                                  f"a finite symmetric ({h.size}, {h.size}) matrix, mm/N")
        if not g.any():
            g = None
    d_c, l_c, area, f = _forces(h, n, length, we, b_max, e_prime, nb, wb)
    if g is None or we <= 0.0:
        return CoupledLine(d_c, l_c, area, h.copy(), f, 0)

    def residual(x):
        d_c, l_c, area, f = _forces(x, n, length, we, b_max, e_prime, nb, wb)
        c = g @ f
        r = x - h - c
        return r - r.min(), (d_c, l_c, area, f), c

    x = h.copy()
    r, sol, c = residual(x)
    for step in range(1, MAX_STEPS + 1):
        tol = TOL_REL * np.abs(c).max() + TOL_ABS
        if np.abs(r).max() <= tol:
            return CoupledLine(*sol[:3], x - x.min(), sol[3], step - 1)
        jac = np.eye(h.size)
        for i in range(h.size):
            xp = x.copy()
            xp[i] += FD_STEP_MM
            jac[:, i] -= g @ ((_forces(xp, n, length, we, b_max, e_prime, nb, wb)[3] - sol[3])
                              / FD_STEP_MM)
        delta = np.linalg.solve(jac, -r)
        t, best = 1.0, np.abs(r).max()
        while True:
            xt = x + t * delta
            xt -= xt.min()
            rt, solt, ct = residual(xt)
            if np.abs(rt).max() < best or t < 2.0 ** -20:
                break
            t *= 0.5
        x, r, sol, c = xt, rt, solt, ct
    raise CheckFailed(f"coupled slice law: no convergence in {MAX_STEPS} Newton steps "
                      f"(max |R| {np.abs(r).max():.3e} mm; docs/cylindrical.md sec. 8)")
