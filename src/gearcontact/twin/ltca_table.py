"""The conventional twin's input: an offline loaded-TE table over phase x torque.

The loaded TE of :func:`gearcontact.ltca.lte.loaded_te` is run at a ladder of gear
torques ``T_i``; at every phase it gives the mesh rotation ``theta(phase, T_i)`` (gear
lag behind the unloaded pose, rad) and the total normal load. The twin then needs the
inverse, the mesh torque at the current rotation: per phase, ``T^(2/3)`` is
interpolated linearly in ``theta`` through ``(0, 0)`` and the ladder (exact for a single
Hertzian pair, ``theta ~ T^(2/3)``; extrapolated with the last segment beyond the
largest torque), then linearly in phase. Exact at the rungs; between them, with tooth
bending (local ``d ln theta / d ln T`` 0.50-0.75 on the EV helical example, between
Hertz and linear) the torque reads back within 0.6 % from 0.6x nominal on, 4-7 % at
0.1-0.2x; on ``theta = a T + b T^(2/3)`` the linear limit is off by at most 4.8 %
(0.7 % from 0.5x on; tests/twin/test_ltca_table.py). A per-segment power law (exact
in both limits) measured no closer on the pair's own tables (docs/cylindrical.md sec.
10). Two sources over the same runs:

* ``"lcp"`` -- the half-space LCP of all pairs in reach (``TE_LCP``, the conventional
  loaded TCA), the default;
* ``"preview"`` -- the Hamrock–Brewe balance of the same pairs (``TE_pre``), the same
  contact model as the preview twin: the two twins must then agree up to the table's
  interpolation (a test). With the edge law where the mesh table has it
  (``edge_compliance_scale``; :mod:`gearcontact.ltca.edge_rows`, calibrated at each
  ladder torque, where the mesh table's is calibrated at its own), else the untruncated
  law.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..ltca.lte import loaded_te
from ..ltca.pair_ltca import ARCSEC_PER_RAD
from ..errors import CheckFailed
from ..validation import InputRangeError, check_positive

__all__ = ["TorqueTable", "torque_table", "TABLE_SOURCES", "DEFAULT_LADDER"]

TABLE_SOURCES = ("lcp", "preview")
#: Torques of the ladder as fractions of the nominal gear torque (dense at light load,
#: where T^(2/3) bends most with the number of pairs in contact; 2.5x covers dynamic
#: factors up to 2.5 without extrapolation).
DEFAULT_LADDER = (0.05, 0.15, 0.3, 0.5, 0.75, 1.0, 1.4, 1.9, 2.5)


@dataclass(frozen=True, eq=False)
class TorqueTable:
    """Mesh rotation vs gear torque at each phase, rows in the motion order of a
    :class:`~.mesh.MeshTable` (same phases).

    Attributes
    ----------
    torques_nm : ndarray (T,)
        Gear torques of the ladder, N·m, increasing.
    theta_rad : ndarray (K, T)
        Mesh rotation at each phase and torque, rad.
    load_n : ndarray (K, T)
        Total normal load of the pairs, N.
    source : str
        ``"lcp"`` or ``"preview"``.
    """

    torques_nm: np.ndarray
    theta_rad: np.ndarray
    load_n: np.ndarray
    source: str


def torque_table(tca, flanks, pair, mesh, torque_nm: float, *, side: str = "drive",
                 source: str = "lcp", ladder=DEFAULT_LADDER, cells: int = 32,
                 bending=None, progress: bool = False) -> TorqueTable:
    """Run the loaded TE at ``ladder x torque_nm`` and tabulate (module docstring).

    Parameters
    ----------
    tca, flanks, pair
        As for :func:`gearcontact.ltca.lte.loaded_te` (``tca`` the analysis the
        ``mesh`` was built from).
    mesh : gearcontact.twin.mesh.MeshTable
        Sets the row order (motion).
    torque_nm : float
        Nominal gear torque, N·m.
    source : str
        One of :data:`TABLE_SOURCES`.
    ladder : sequence of float
        Torque fractions, increasing, > 0.
    cells : int
        Cells per side of each pair's field (32 puts the rotation within ~1-2 % of the
        converged LCP, :func:`~gearcontact.ltca.lte.loaded_te`).
    bending : ToothBending or None
        Tooth bending in the LCP (``lcp`` source; the ``preview`` source is the rigid
        Hertzian TE_pre of the loaded TE, so bending is refused there).
    """
    t = check_positive("torque_nm (N·m)", torque_nm)
    if source not in TABLE_SOURCES:
        raise InputRangeError("table source", source, f"one of {TABLE_SOURCES}")
    if bending is not None and source != "lcp":
        raise InputRangeError("table source", source, "'lcp' with tooth bending")
    lad = np.asarray(ladder, float)
    if lad.ndim != 1 or lad.size < 2 or not (np.all(lad > 0) and np.all(np.diff(lad) > 0)):
        raise InputRangeError("table ladder", ladder, "at least 2 increasing fractions > 0")
    order = np.arange(len(mesh.psi_rad)) if mesh.motion_sign == 1 else \
        np.arange(len(mesh.psi_rad))[::-1]
    theta = np.zeros((len(order), lad.size))
    load = np.zeros_like(theta)
    for i, f in enumerate(lad):
        res = loaded_te(tca, flanks, pair, f * t, side=side, cells=cells, bending=bending,
                        edge_law=mesh.edge_compliance_scale is not None, progress=progress)
        if source == "lcp":
            if not res.converged:
                raise CheckFailed(f"loaded TE at {f * t:g} N·m did not converge")
            rot, w = res.rotation_lcp_arcsec, res.pair_loads_lcp_n
        else:
            rot, w = res.rotation_pre_arcsec, res.pair_loads_pre_n
        theta[:, i] = rot[order] / ARCSEC_PER_RAD
        load[:, i] = w.sum(axis=0)[order]
    return TorqueTable(lad * t, theta, load, source)
