"""One grid point of a sweep: the TCA (and per torque the LTCA) of the pair with its
assembly errors replaced, reduced to the scalars of :data:`CELL_VARIABLES`.

The pattern is read on the gear flank in its surface parameters (mm along the flank;
:mod:`gearcontact.geometry.surface`: ``u`` root -> tip, ``v`` toe -> heel) over the
transmitting contacts of one pinion pitch: its centre is the middle of their extent,
its size the extent itself (the path of the ellipse centres; the paint ellipse at P0
adds ``2 a`` along its major axis). Errors a wild set-up raises (the mating point
leaves the flank, Newton does not converge, the load leaves the preview envelope) are
the point's result, recorded by name, not a failure of the sweep.
"""

from __future__ import annotations

import dataclasses
import warnings

import numpy as np

from ..halfspace.ellipse import CoarseGridWarning
from ..halfspace.patch import ContactAtEdgeWarning
from ..tca.types import EdgeContact, TcaConvergenceError
from ..validation import InputRangeError

__all__ = ["CELL_VARIABLES", "LTE_CELLS", "LTE_PHASES", "lte_stride", "TCA_VARIABLES", "LTCA_VARIABLES", "RECORDED_ERRORS",
           "BOOL_VARIABLES",
           "compute_point"]

#: Phases of the loaded TE of a cell, about (every ``stride``-th phase of the TCA
#: cycle, ``stride = round((phases - 1) / (LTE_PHASES - 1))``, plus P0): measured on
#: s0003-centred at 64.5 N·m, 11 phases give TE_LCP p-p 2.468 arcsec against 2.473 with
#: all 61 (0.2 %) at a fifth of the cost (0.48 s against 2.4 s per torque).
LTE_PHASES = 11
#: Cells per side of the loaded TE's fields (40: the minor semi-axis of the fully
#: loaded pair resolved by about 10 cells, the approach within ~1 %;
#: :func:`gearcontact.ltca.lte.loaded_te`).
LTE_CELLS = 40
#: Per grid point (TCA does not depend on torque): name -> (unit, description).
TCA_VARIABLES = {
    "te0_pp_arcsec": ("arcsec", "unloaded transmission error, peak to peak"),
    "pattern_face_mm": ("mm", "pattern centre along the gear face (v2, toe -> heel)"),
    "pattern_height_mm": ("mm", "pattern centre along the gear profile (u2, root -> tip)"),
    "pattern_length_mm": ("mm", "extent of the transmitting path along the face"),
    "pattern_depth_mm": ("mm", "extent of the transmitting path along the profile"),
    "paint_major_mm": ("mm", "paint-ellipse major axis 2a at P0"),
    "pattern_on_flank": ("1", "every transmitting paint ellipse lies on both flanks"),
    "edge_contact": ("1", "a transmitting phase is an edge touching the other flank, or "
                          "has no mating point"),
}
#: Per cell with ``ltca``.
LTCA_VARIABLES = {
    "preview_p_max_mpa": ("MPa", "Hertzian preview peak pressure at P0"),
    "lcp_p90_mpa": ("MPa", "LCP pressure, 90th percentile of loaded cells"),
    "lcp_peak_mpa": ("MPa", "LCP peak pressure"),
    "ltca_edge_contact": ("1", "loaded contact truncated by a flank edge"),
    "lcp_coarse_grid": ("1", "fewer than 8 cells per minor semi-axis (raise --cells)"),
    "lte_lcp_pp_arcsec": ("arcsec", "loaded TE (LCP, rigid teeth), peak to peak over "
                                    "about LTE_PHASES phases of a pitch"),
    "lte_preview_pp_arcsec": ("arcsec", "loaded TE (Hertzian preview), peak to peak"),
    "lte_edge_contact": ("1", "a phase of the loaded TE has edge contact"),
}
CELL_VARIABLES = {**TCA_VARIABLES, **LTCA_VARIABLES}
#: Errors recorded as a point's result (named errors of the library).
RECORDED_ERRORS = (EdgeContact, TcaConvergenceError, InputRangeError)
BOOL_VARIABLES = {"pattern_on_flank", "edge_contact", "ltca_edge_contact",
                  "lcp_coarse_grid", "lte_edge_contact"}


def lte_stride(phases: int) -> int:
    """Stride over the TCA's ``phases`` giving about :data:`LTE_PHASES` LTE phases."""
    return max(1, round((phases - 1) / (LTE_PHASES - 1)))


def _tca_values(res) -> dict:
    cyc = res.cycle
    # every phase with a contact (an edge touching the other flank included: it is where
    # the pattern runs); ``edge`` phases have no mating point and NaN fields
    inner = [mp for mp in cyc.contact if not mp.edge]
    u2 = np.array([mp.u2 for mp in inner])
    v2 = np.array([mp.v2 for mp in inner])
    return {"te0_pp_arcsec": float(cyc.te0_pp_arcsec),
            "pattern_face_mm": float(0.5 * (v2.min() + v2.max())),
            "pattern_height_mm": float(0.5 * (u2.min() + u2.max())),
            "pattern_length_mm": float(np.ptp(v2)), "pattern_depth_mm": float(np.ptp(u2)),
            "paint_major_mm": float(2.0 * res.mean_ellipse.semi_major_mm),
            "pattern_on_flank": bool(res.pattern_on_flank.all()),
            "edge_contact": any(mp.edge or mp.edge_contact for mp in cyc.contact)}


def compute_point(pair, flanks, assembly: dict, torques_nm, *, side: str, compute: tuple,
                  phases: int = 61, cells: int = 80, solver: str = "pk_cg") -> dict:
    """Results of one grid point.

    Parameters
    ----------
    pair : GearPair
        The pair; ``assembly`` replaces fields of its assembly errors.
    flanks : FlankSet
        Its flanks (generated without assembly errors: built once per design variant).
    assembly : dict
        AssemblyErrors field -> value (mm, deg).
    torques_nm : sequence of float
        Gear torques, N·m (LTCA only).
    side : str
        ``"drive"`` or ``"coast"``.
    compute : tuple of str
        ``("tca",)`` or ``("tca", "ltca")`` (the LTCA at P0 and the loaded TE over
        about :data:`LTE_PHASES` phases, :data:`LTE_CELLS` cells per side).
    phases, cells, solver
        TCA phases per pitch, LTCA cells per side, LCP solver.

    Returns
    -------
    dict
        ``variable -> list over torques`` (:data:`CELL_VARIABLES` computed; the TCA
        values repeated per torque) and ``error``: ``""`` or ``"Name: message"``.
    """
    from ..ltca.lte import loaded_te
    from ..ltca.pair_ltca import single_pair_ltca
    from ..tca.analysis import analyze_pair

    n = len(torques_nm)
    names = list(TCA_VARIABLES) + (list(LTCA_VARIABLES) if "ltca" in compute else [])
    out = {k: [False if k in BOOL_VARIABLES else np.nan] * n for k in names}
    out["error"] = [""] * n
    moved = dataclasses.replace(pair, assembly=dataclasses.replace(pair.assembly, **assembly))
    try:
        res, _ = analyze_pair(moved, side=side, phases=phases, flanks=flanks)
    except RECORDED_ERRORS as exc:
        out["error"] = [f"{type(exc).__name__}: {exc}"] * n
        return out
    for k, v in _tca_values(res).items():
        out[k] = [v] * n
    if "ltca" not in compute:
        return out
    for i, torque in enumerate(torques_nm):
        try:
            with warnings.catch_warnings(record=True) as caught:   # recorded below,
                warnings.simplefilter("always")                       # not one line per cell
                case = single_pair_ltca(res, flanks, moved, float(torque), side=side,
                                        cells=cells, solver=solver)
            for w in caught:
                if not issubclass(w.category, (ContactAtEdgeWarning, CoarseGridWarning)):
                    warnings.warn_explicit(w.message, w.category, w.filename, w.lineno)
        except RECORDED_ERRORS as exc:
            out["error"][i] = f"{type(exc).__name__}: {exc}"
            continue
        out["preview_p_max_mpa"][i] = float(case.preview.p_max_mpa)
        out["lcp_p90_mpa"][i] = float(case.patch.p90_mpa)
        out["lcp_peak_mpa"][i] = float(case.patch.p_peak_mpa)
        out["ltca_edge_contact"][i] = bool(case.edge_contact)
        out["lcp_coarse_grid"][i] = any(issubclass(w.category, CoarseGridWarning)
                                        for w in caught)
        if not case.patch.converged:
            out["error"][i] = f"LCPNotConverged: {case.patch.lcp.status}"
        try:
            lte = loaded_te(res, flanks, moved, float(torque), side=side, cells=LTE_CELLS,
                            stride=lte_stride(phases))
        except RECORDED_ERRORS as exc:
            out["error"][i] = out["error"][i] or f"{type(exc).__name__}: {exc}"
            continue
        out["lte_lcp_pp_arcsec"][i] = lte.te_lcp_pp_arcsec
        out["lte_preview_pp_arcsec"][i] = lte.te_pre_pp_arcsec
        out["lte_edge_contact"][i] = bool(lte.edge_contact.any())
        if not lte.converged and not out["error"][i]:
            failed = sorted(set(lte.status) - {"converged"})
            out["error"][i] = f"LTENotConverged: {', '.join(failed)}"
    return out
