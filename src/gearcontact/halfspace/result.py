"""The one result type of the normal-contact solvers, and its status enum.

Every solver of the contact family returns a :class:`ContactResult`, as every scipy
minimiser returns one ``OptimizeResult`` and ContactMechanics' solvers one result
object: the single-body load-constrained LCP (:func:`.lcp.solve_lcp`, all three
solvers), the torque-constrained LCP of several tooth pairs
(:func:`gearcontact.ltca.mesh_lcp.solve_mesh_lcp`) and the constrained conjugate
gradient both run on (:func:`.constrained_cg.constrained_cg`). The solve record
(``status``, ``message``, ``solver``, ``iterations``, ``solve_time_ms``) is filled by
every solver; the solution fields by the problems that have them (None elsewhere):

========================  ==================================================
problem                   fields
========================  ==================================================
one body, load ``W``      ``pressure_mpa``, ``loads_n`` (ny, nx), ``delta_mm``,
                          ``contact_mask``, ``load_n``, ``load_residual``,
                          ``complementarity_residual``, ``window``
tooth pairs, torque       ``rotation_rad``, ``loads_n`` (tuple per pair),
``T``                     ``pair_loads_n``, ``approach_mm``, ``contact_masks``,
                          ``torque_nmm``, ``torque_residual``,
                          ``complementarity_residual``
the CG on a stack         ``x_stack``, ``u_stack_mm``
========================  ==================================================

:class:`.patch.PatchContact` is not a solver result but the statistics of a solved patch
(mean / p90 / peak pressure, ellipse); it holds the :class:`ContactResult` as ``lcp``.

The former per-solver names ``LcpResult`` (:mod:`.lcp`), ``CgOutcome``
(:mod:`.constrained_cg`) and ``MeshLcpResult`` (:mod:`gearcontact.ltca.mesh_lcp`), and the
kernel's fields ``x`` and ``u``, still work for one release and emit a
:class:`DeprecationWarning`.
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import StrEnum

import numpy as np

from ..deprecation import warn_deprecated

__all__ = ["SolveStatus", "ContactResult"]


class SolveStatus(StrEnum):
    """Outcome of a contact solve (a ``str``: JSON/CSV files show the value)."""

    #: Converged; complementarity residual within the requested tolerance.
    CONVERGED = "converged"
    #: The iteration cap was reached.
    MAX_ITER = "max_iter"
    #: Stopped otherwise: lost descent, residual above tolerance, a linear-algebra
    #: failure of a direct solver, or windows that kept growing (see the message).
    FAILED = "failed"


@dataclass(frozen=True, eq=False, kw_only=True)
class ContactResult:
    """Result of a normal-contact solve (see the module docstring for which solver
    fills which field; a field a problem does not have is None).

    Attributes
    ----------
    status : SolveStatus
        CONVERGED, MAX_ITER or FAILED (a ``str`` enum). A finished iteration whose
        complementarity residual exceeds the solver's ``residual_tol`` is FAILED.
    iterations : int
        Solver iterations (pk_cg: CG steps; nnls: NNLS solves; active_set: pivots),
        summed over window rounds.
    solver : str
        Solver name (``"pk_cg"``, ``"nnls"``, ``"active_set"``).
    message : str
        Human-readable account of the solve (window, certificate, failure cause).
    solve_time_ms : float or None
        Wall time of the solve, ms (None for the bare CG iteration).
    complementarity_residual : float or None
        Natural residual ``max_i |min(w_i / max(w), s_i / (approach - min h))|`` over all
        cells, dimensionless (penetration, negative loads and open loaded cells).
    pressure_mpa : ndarray (ny, nx) or None
        One body: cell pressures, MPa (``loads_n / cell area``).
    loads_n : ndarray (ny, nx), or tuple of ndarray, or None
        Nodal loads, N: one body, the field; tooth pairs, one field per pair.
    delta_mm : float or None
        One body: rigid approach ``delta``, mm (same datum as the gap).
    contact_mask : ndarray of bool (ny, nx) or None
        One body: cells carrying load (``w > 0``).
    load_n : float or None
        One body: prescribed total load ``W``, N.
    load_residual : float or None
        One body: ``|sum(w) - W| / W``.
    window : tuple of int or None
        One body: ``(j0, j1, i0, i1)``, rows ``j0:j1`` and columns ``i0:i1`` of the
        final window.
    rotation_rad : float or None
        Tooth pairs: shared gear rotation ``theta`` from the unloaded rest position, rad.
    pair_loads_n : ndarray (P,) or None
        Tooth pairs: total normal load per pair, N.
    approach_mm : ndarray (P,) or None
        Tooth pairs: ``delta_j = l_j theta - g_j`` per pair, mm (negative: open).
    contact_masks : tuple of ndarray of bool, or None
        Tooth pairs: loaded cells per pair.
    torque_nmm : float or None
        Tooth pairs: prescribed torque ``T``, N·mm.
    torque_residual : float or None
        Tooth pairs: ``|sum_j l_j W_j - T| / T``.
    x_stack : ndarray (blocks, ny, nx) or None
        The CG on a stack: solution in the units of its input (N, or N·mm for torque
        shares).
    u_stack_mm : ndarray (blocks, ny, nx) or None
        The CG on a stack: ``C x`` on the whole fields, computed exactly at the end, mm.
    """

    status: SolveStatus
    iterations: int
    solver: str = "pk_cg"
    message: str = ""
    solve_time_ms: float | None = None
    complementarity_residual: float | None = None
    # one body under a load
    pressure_mpa: np.ndarray | None = None
    loads_n: np.ndarray | tuple | None = None
    delta_mm: float | None = None
    contact_mask: np.ndarray | None = None
    load_n: float | None = None
    load_residual: float | None = None
    window: tuple[int, int, int, int] | None = None
    # tooth pairs under a torque
    rotation_rad: float | None = None
    pair_loads_n: np.ndarray | None = None
    approach_mm: np.ndarray | None = None
    contact_masks: tuple | None = None
    torque_nmm: float | None = None
    torque_residual: float | None = None
    # the constrained CG on a stack
    x_stack: np.ndarray | None = None
    u_stack_mm: np.ndarray | None = None

    @property
    def converged(self) -> bool:
        """True when ``status`` is CONVERGED."""
        return self.status is SolveStatus.CONVERGED

    @property
    def n_contact_cells(self) -> int:
        """Number of cells carrying load (all pairs together for tooth pairs)."""
        masks = (self.contact_mask,) if self.contact_mask is not None else \
            (self.contact_masks or ())
        return int(sum(int(m.sum()) for m in masks))

    def pressures_mpa(self, blocks) -> tuple:
        """Tooth pairs: pressure maps (MPa) per pair on the blocks' grids."""
        return tuple(w / b.grid.cell_area_mm2 for w, b in zip(self.loads_n, blocks))

    @property
    def x(self) -> np.ndarray:
        """Deprecated: :attr:`x_stack`."""
        warn_deprecated("ContactResult.x", "ContactResult.x_stack")
        return self.x_stack

    @property
    def u(self) -> np.ndarray:
        """Deprecated: :attr:`u_stack_mm`."""
        warn_deprecated("ContactResult.u", "ContactResult.u_stack_mm")
        return self.u_stack_mm
