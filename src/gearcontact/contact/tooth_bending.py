"""Tooth bending blocks of the multi-pair LCP: the shell compliance at a pair's cells.

A tooth pair's field (:mod:`.lte_pairs`) is a grid of tangent-plane cells around the
pair's mating point. Each cell lies on the pinion flank and on the gear flank at
parameters given, to first order, by the tangent-plane map of the mating point
(:func:`gearcontact.tca.stencil.tangent_parameters`; the compliance is smooth over the
flank, so the first-order position is ample). The bending compliance of the pair at its
cells is that of the pinion tooth plus that of the gear tooth,
``G = G_pinion + G_gear`` (both deflect away from the contact along the common normal),
each the low-rank shell operator of :mod:`gearcontact.structure.shell`. It is handed to
:func:`.mesh_lcp.solve_mesh_lcp` as one factor ``F`` with ``G = F F^T``, compressed to
the singular directions with singular values above ``1e-6`` of the largest (the dropped
part is below 1e-12 of the largest compliance, far under the LCP tolerance).

Cells outside a flank's parameter box (off-flank cells, which never carry load) take
the compliance of the nearest box point.

References
----------
M. Kolivand, A. Kahraman, "A load distribution model for hypoid gears using ease-off
topography and shell theory", *Mechanism and Machine Theory* 44(10), 2009, 1848-1865
(block-diagonal bending compliance per tooth, added to the half-space compliance).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..structure.shell import ShellModel, tooth_shell
from ..validation import check_range

__all__ = ["ToothBending", "tooth_bending"]

#: Relative singular-value cut of the compressed bending factor.
_SVD_CUT = 1e-6


@dataclass(frozen=True, eq=False)
class ToothBending:
    """Shell models of one pinion and one gear tooth for the contacts of one side.

    Attributes
    ----------
    pinion, gear : ShellModel
    side : str
        "drive" or "coast".
    scale : float
        Factor on the bending compliance (1: the model; 0: rigid teeth, the
        zero-compliance limit; > 1: softer teeth, e.g. a lower Young's modulus E/scale).
    """

    pinion: ShellModel
    gear: ShellModel
    side: str
    scale: float = 1.0

    def factor(self, uv_pinion: np.ndarray, uv_gear: np.ndarray, shape) -> np.ndarray:
        """Bending factor ``F`` (ny, nx, r) at cells with pinion / gear flank parameters
        ``uv_*`` (ny * nx, 2), mm: ``G = F F^T`` (mm/N)."""
        parts = []
        for shell, uv in ((self.pinion, uv_pinion), (self.gear, uv_gear)):
            tooth = shell.body
            flank = getattr(tooth, self.side)
            u = np.clip(uv[:, 0], *flank.u_range)
            v = np.clip(uv[:, 1], *flank.v_range)
            parts.append(shell.compliance(tooth.flank_points(self.side, u, v)).factor)
        if self.scale == 0.0:
            return np.zeros(tuple(shape) + (1,))
        f = np.concatenate(parts, axis=1) * np.sqrt(self.scale)
        # compress: F^T F = V S^2 V^T, so F F^T = (F V)(F V)^T; keep the columns of
        # F V with singular values s > cut * s_max (the small Gram matrix is much
        # cheaper than an SVD of F)
        s2, vecs = np.linalg.eigh(f.T @ f)
        keep = s2 > (_SVD_CUT ** 2) * s2[-1]
        return (f @ vecs[:, keep]).reshape(tuple(shape) + (int(keep.sum()),))


def tooth_bending(flanks, pair, *, side: str, order: int = 6, scale: float = 1.0
                  ) -> ToothBending:
    """The :class:`ToothBending` of a pair (shell models cached per flank set)."""
    check_range("bending scale", scale, 0.0, 1e6)
    return ToothBending(
        pinion=tooth_shell(flanks, "pinion", material=pair.pinion_material, order=order),
        gear=tooth_shell(flanks, "gear", material=pair.gear_material, order=order),
        side=side, scale=float(scale))
