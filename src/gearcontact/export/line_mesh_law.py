"""The mesh FMU's contact law of a cylindrical pair in Python: the twin's line law at one
instant, no state (docs/export.md, "Cylindrical pairs"; docs/cylindrical.md sec. 10).

:class:`LineMeshTable` holds what ``gearcontact export fmu --kind mesh`` bakes into the
FMU of a cylindrical pair: the loaded flank's :class:`~gearcontact.twin.mesh.MeshTable`
rows (levers, openings, the unloaded TE) and per pair and row the line chain's inputs
(:func:`line_rows`: the 7 x 7 gap stencil, stage C's fp64 fit, the contact line's
length and the ease-off at its slices, the edge slices beyond a helical line's ends);
:func:`line_mesh_outputs` evaluates the FMU's outputs at given inputs with the twin's
own compiled law (:func:`gearcontact.twin.line_law._line_law`), the reference the C
code is tested against.

The law, at the inputs of :mod:`.mesh_law` (the same kinematics, torque and TE): per pair
valid at both rows with ``d_j = l_j theta - g_j > 0`` one preview of the line chain at
the approach ``d_j`` (the slice law finds the load there; its Newton starts at
:data:`~gearcontact.twin.contact_law.W_EVAL_MIN_N`, the FMU having no previous step),
then the pair's load: Hertz ``W = (d / kappa)^(3/2)`` where the chain answers an
ellipse, the line law ``d - h_bar = lambda W (beta - ln(W)/2)`` by
:func:`~gearcontact.twin.line_law.line_pair_load` from the load the preview was sampled
at. ``a``, ``b``, ``p_max`` of the most loaded pair scale from that load as the twin's
record does (Hertz ``W^(1/3)``; line ``b``, ``p_max ~ W^(1/2)``, ``a = L_c / 2``).
The domain counts: every closed pair's preview counted as the twin's line law counts
previews (:func:`gearcontact.twin.line_law._line_fp64`: ``tcount[3]``, outside the
datapath's domain -- the golden chain flagged, or in fp64 ``B_max`` outside the line
core's envelope, ``L_eq`` without the host's lift, a lifted line that keeps its ellipse
--, the fp64 line chain evaluating it; ``tcount[5]``, without a contact law, a saddle:
the pair then carries nothing).
With tooth bending (the table's ``bending_mm_per_n`` and the slices' Gram in its rows,
``gearcontact export fmu --bending``) the preview solves the twin's coupled slice law at
the approach from the series state with the uniform load's compliance (a fresh preview,
as the twin's static point), and the pair's load solves the law with its secant
compliance ``c_b = (d - d_c) / W`` in series.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..twin import layout as L
from ..twin.contact_law import W_EVAL_MIN_N, _pair_load
from ..ltca.slice_law import line_pair_load
from ..twin.line_law import MODE_LINE, _line_law, line_law_constants
from .mesh_law import (BACKENDS, MeshLawTable, MeshOutputs, _kinematics, _Law, _outputs,
                       closed_pairs, law_of, mesh_law_table)

__all__ = ["LineMeshTable", "line_mesh_table", "line_mesh_outputs", "line_rows"]


@dataclass(frozen=True, eq=False)
class LineMeshTable(MeshLawTable):
    """The loaded flank's mesh rows and line-chain inputs baked into the FMU of a
    cylindrical pair (module docstring; :class:`~.mesh_law.MeshLawTable`'s attributes,
    ``bending_mm_per_n`` the uniform-load bending compliance, None for rigid teeth).

    Attributes
    ----------
    line_rows : ndarray (P, K, 49 + 4 + m [+ m^2])
        Per pair and row: the 49 gap samples (mm), stage C's c3, c4, c5 (1/mm), the
        contact line's length (mm), the ease-off at its ``m = slices + 2 beyond``
        slices (mm), with bending their Gram matrix (mm/N; :func:`line_rows`).
    slices, beyond : int
        Slices along the line, edge slices beyond either end (0: none).
    beyond_width_mm : float
        The edge slices' width times the edge section's stiffness relative to the
        line's, mm (``prm[P_BEYOND_W]``).
    """

    line_rows: np.ndarray = None
    slices: int = 0
    beyond: int = 0
    beyond_width_mm: float = 0.0

    @classmethod
    def from_npz(cls, path) -> "LineMeshTable":
        """Read a table written by :meth:`to_npz`."""
        tab = super().from_npz(path)
        kw = dict(tab.__dict__, slices=int(tab.slices), beyond=int(tab.beyond),
                  beyond_width_mm=float(tab.beyond_width_mm))
        return cls(**kw)


def line_rows(mesh) -> np.ndarray:
    """(P, K, 49 + 4 + m [+ m^2]) line-chain inputs of a cylindrical pair's mesh table
    (the golden twin's rows, :func:`gearcontact.twin.model._curvature_rows` with the
    line source; the slices' bending Gram with tooth bending, none for rigid teeth)."""
    from ..twin.model import _curvature_rows

    rows = _curvature_rows(mesh, L.LINE_SOURCE, golden=True)
    if mesh.line_bending_gram_mm_per_n is not None:
        return np.ascontiguousarray(rows)
    m = _slice_count(mesh)
    return np.ascontiguousarray(rows[..., :rows.shape[-1] - m * m])


def _slice_count(mesh) -> int:
    n = mesh.line_gap_mm.shape[-1]
    return n if mesh.beyond_gap_mm is None else n + 2 * mesh.beyond_gap_mm.shape[-1]


def line_mesh_table(mesh) -> LineMeshTable:
    """The FMU's table of a cylindrical pair's :class:`~gearcontact.twin.mesh.MeshTable`:
    :func:`~.mesh_law.mesh_law_table`'s rows and the line chain's."""
    beyond = 0 if mesh.beyond_gap_mm is None else int(mesh.beyond_gap_mm.shape[-1])
    return LineMeshTable(
        **mesh_law_table(mesh).__dict__, line_rows=line_rows(mesh),
        slices=int(mesh.line_gap_mm.shape[-1]), beyond=beyond,
        beyond_width_mm=0.0 if beyond == 0 else float(mesh.beyond_width_mm
                                                      * mesh.beyond_stiffness))


class _LineLaw(_Law):
    """The twin's line-law arguments for one table (:class:`~.mesh_law._Law`'s, the
    curvature source the line chain's, twin.model's layout)."""

    def __init__(self, tab: LineMeshTable):
        super().__init__(tab)
        self.prm[L.P_STAGEC] = L.LINE_SOURCE_CODE
        self.prm[L.P_NSLICE] = tab.slices
        self.prm[L.P_NBEYOND] = tab.beyond
        self.prm[L.P_BEYOND_W] = tab.beyond_width_mm
        m = tab.slices + 2 * tab.beyond
        rows = tab.line_rows
        self.bent = tab.bending_mm_per_n is not None
        self.prm[L.P_SLICE_CB] = float(self.bent)
        # rigid teeth: their bending Gram (zeros) after the rows, as the twin stacks them
        self.cv = (rows if self.bent else np.concatenate(
            [rows, np.zeros(rows.shape[:2] + (m * m,))], axis=-1))[None]
        self.fit = self.fit + (line_law_constants(),)
        # one slot of the coupled law's warm start (unused: the FMU has no previous
        # step, so every preview is fresh, ``cb0 <= 0``)
        self.pv = np.zeros(L.preview_scratch(self.prm, 1))

    def law(self, j, i, f, d, backend, cb0=-0.0):
        """``(law, pv)`` of pair j at (i, f) and the approach d (kernel._elastic's
        preview: pv preset, the Newton start 1 N; ``cb0`` minus the uniform load's
        bending compliance, mm/N: a fresh preview, the coupled law from the series
        state)."""
        pv = self.pv
        pv[3] = pv[4] = pv[L.PV_LINE_OFFSET] = 0.0
        pv[L.PV_LOAD] = W_EVAL_MIN_N
        pv[L.PV_LINE_BENDING] = -1.0
        lam = _line_law(0, 0, j, i, f, d, cb0, W_EVAL_MIN_N, self.prm, self.cv, backend,
                        self.pow_lut, self.cbrt_lut, self.cst, self.trace, self.tcount,
                        self.fit, pv)
        return lam, pv



def line_mesh_outputs(tab: LineMeshTable, phi_pinion_rad: float, phi_gear_rad: float,
                      omega_pinion_rad_s: float, omega_gear_rad_s: float, *, backend: str,
                      mesh_damping_n_s_per_mm: float = 0.0) -> MeshOutputs:
    """Outputs of a cylindrical pair's mesh FMU at one instant (module docstring;
    parameters as :func:`~.mesh_law.mesh_outputs`)."""
    law = law_of(tab, _LineLaw)
    code = BACKENDS[backend]
    i, f, de, theta, theta_dot, te = _kinematics(tab, phi_pinion_rad, phi_gear_rad,
                                                 omega_pinion_rad_s, omega_gear_rad_s)
    if theta < 0.0:
        return MeshOutputs(0.0, 0.0, 0.0, te, 0.0, 0.0, 0.0, 0, 0, 0)
    t_el = w_tot = w_max = 0.0
    abp = (0.0, 0.0, 0.0)
    pairs = 0
    cbs = tab.bending_mm_per_n
    tc = law.tcount
    before = int(tc[3]), int(tc[5])     # every closed pair's preview counted, as the twin
    for j, lv, d in closed_pairs(tab, i, f, theta):
        cb0 = -0.0 if cbs is None else -(cbs[j, i] + f * (cbs[j, i + 1] - cbs[j, i]))
        lam, pv = law.law(j, i, f, d, code, cb0)
        if lam <= 0.0:      # no contact law (a saddle): the pair carries nothing
            continue
        we = pv[L.PV_LOAD]
        # the coupled law's secant bending compliance in series (0: rigid teeth)
        cb = pv[L.PV_LINE_BENDING] if pv[L.PV_LINE_BENDING] > 0.0 else 0.0
        line = pv[3] == MODE_LINE
        if line:
            d -= pv[L.PV_LINE_OFFSET]
            if d <= 0.0:
                continue
            w = line_pair_load(d, lam, pv[4], cb, we)
        else:
            w = _pair_load(d, lam, cb, 0.0)[0]
        t_el += 1e-3 * w * lv
        w_tot += w
        pairs += 1
        if w > w_max:
            w_max = w
            # similarity (kernel._elastic): Hertz a, b, p ~ W^(1/3); line b, p ~ W^(1/2)
            scale = (w / we) ** (0.5 if line else 1.0 / 3.0)
            abp = (pv[0] * (1.0 if line else scale), pv[1] * scale, pv[2] * scale)
    return _outputs(tab, t_el, w_tot, abp, pairs, de, theta_dot, te,
                    mesh_damping_n_s_per_mm,
                    counts=(int(tc[3]) - before[0], int(tc[5]) - before[1]))
