"""One phase of the loaded mesh: the pairs' shared rotation under a torque.

The loaded TE (:mod:`.lte`) and the multi-tooth LTCA (:mod:`.multitooth`) solve each
phase the same way:

* **preview** (:func:`preview_balance`): Hamrock–Brewe Hertz per pair, ``W_j =
  ((l_j theta - g_j)_+ / kappa_j)^(3/2)``, and the torque balance ``sum_j W_j l_j = T``,
  a monotone scalar equation in the shared rotation ``theta`` (Brent's method); with
  the edge law (:func:`.edge_rows.preview_edge_balance`) ``kappa_j`` of a contact a
  flank boundary cuts is scaled by its LCP-calibrated ``c`` (the twin's law);
* **LCP** (:func:`solve_phase`): the half-space LCP of every pair within reach of the
  preview's rotation, all pairs coupled by the torque (:func:`.mesh_lcp.solve_mesh_lcp`),
  pairs found closed after the solve added and the phase solved again;
* the checks of a solved phase: no load on an off-flank cell (:func:`check_loaded`),
  a TCA pair window wide enough for the loaded mesh (:func:`check_pair_window`), a
  contact inside its field (:func:`field_edge_reached`);
* the contact and mesh compliances at the reference phase by central differences in
  torque (:func:`reference_compliances`).

References
----------
B. J. Hamrock, D. E. Brewe, J. Lubrication Technol. 105 (1983) 171-177.
K. L. Johnson, *Contact Mechanics*, 1985, ch. 3-4. docs/spec.md sec. 5.
"""

from __future__ import annotations


import numpy as np
from scipy.optimize import brentq

from ..analytic.series_contact import series_pair_load
from ..errors import CheckFailed
from ..halfspace.result import ContactResult
from ..validation import InputRangeError, UnusableInput, check_positive
from .lte_pairs import PairFields
from .mesh_lcp import solve_mesh_lcp
from .pair_ltca import ARCSEC_PER_RAD, OFF_FLANK_GAP_MM

__all__ = ["ACTIVE_SHARE", "preview_balance", "solve_phase", "check_loaded",
           "check_pair_window", "field_edge_reached", "reference_compliances"]

#: A pair counts as active when it carries more than this share of the total load.
ACTIVE_SHARE = 1e-6
#: Pairs whose opening exceeds this multiple of the preview rotation get no field.
_REACH_FACTOR = 3.0


def preview_balance(levers_mm, offsets_mm, kappas, torque_nmm: float, *,
                    bending_mm_per_n=None) -> tuple[float, np.ndarray]:
    """Shared rotation and pair loads of Hertzian pairs under a torque.

    Solves ``sum_j l_j ((l_j theta - g_j)_+ / kappa_j)^(3/2) = T`` (monotone in
    ``theta``) by Brent's method; with ``bending_mm_per_n`` each pair's load at its
    approach ``d_j = l_j theta - g_j`` solves ``d = kappa W^(2/3) + c_b W`` instead (the
    teeth's bending in series, the twin's law: :func:`gearcontact.analytic.
    series_contact.series_pair_load`).

    Parameters
    ----------
    levers_mm, offsets_mm, kappas : array_like (P,)
        Levers ``l_j`` (mm), initial separations ``g_j`` (mm, >= 0, one of them 0 for the
        transmitting pair) and approach coefficients ``kappa_j`` (mm/N^(2/3)).
    torque_nmm : float
        Gear torque, N·mm.
    bending_mm_per_n : array_like (P,), optional
        Bending compliance ``c_b`` of each pair's teeth (mm/N, >= 0;
        :func:`gearcontact.ltca.tooth_bending.pair_bending_compliance`); None: rigid.

    Returns
    -------
    (theta_rad, loads_n)
    """
    lv = np.asarray(levers_mm, float)
    g = np.asarray(offsets_mm, float)
    kap = np.asarray(kappas, float)
    t = check_positive("torque_nmm", torque_nmm)
    cb = None if bending_mm_per_n is None else np.asarray(bending_mm_per_n, float)

    def loads(theta):
        d = np.maximum(lv * theta - g, 0.0)
        if cb is None:
            return (d / kap) ** 1.5
        return np.array([series_pair_load(dj, kj, cj, 0.0)[0] if dj > 0.0 else 0.0
                         for dj, kj, cj in zip(d, kap, cb)])

    lo = float(np.min(g / lv))
    # the pair open least carries the whole torque at this rotation: an upper bound
    j = int(np.argmin(g / lv))
    w_all = t / lv[j]
    hi = lo + 1.01 * (kap[j] * w_all ** (2.0 / 3.0)
                      + (0.0 if cb is None else cb[j] * w_all)) / lv[j]
    theta = brentq(lambda th: loads(th) @ lv - t, lo, hi, xtol=1e-16, rtol=1e-14)
    return float(theta), loads(theta)


def _near(mask: np.ndarray) -> np.ndarray:
    """Cells of ``mask`` and their 4-neighbours."""
    out = mask.copy()
    out[1:, :] |= mask[:-1, :]
    out[:-1, :] |= mask[1:, :]
    out[:, 1:] |= mask[:, :-1]
    out[:, :-1] |= mask[:, 1:]
    return out


def solve_phase(contacts, fields: PairFields, torque_nmm: float, materials, *, tol: float,
                 warm: dict, theta_pre: float, rigid: bool = False):
    """Torque-constrained LCP over the pairs within reach (``rigid``: without the
    bending factors); returns (result, used contacts, blocks, off masks). Pairs left out
    are checked open."""
    reach = [pc for pc in contacts
             if pc.opening_arcsec / ARCSEC_PER_RAD <= _REACH_FACTOR * theta_pre]
    while True:
        built = [fields.block(pc, rigid=rigid) for pc in reach]
        blocks = [b for b, _ in built]
        res = solve_mesh_lcp(blocks, torque_nmm, materials=materials, tol=tol,
                             warm_start=[_warm(warm.get(pc.offset), off)
                                         for pc, (_, off) in zip(reach, built)],
                             rotation_guess_rad=theta_pre)
        late = [pc for pc in contacts if pc not in reach
                and pc.opening_arcsec / ARCSEC_PER_RAD < res.rotation_rad]
        if not late:
            return res, reach, blocks, [o for _, o in built]
        reach = reach + late


def _warm(p, off):
    """A warm-start pressure map without load on the field's off-flank cells."""
    return None if p is None or p.shape != off.shape else np.where(off, 0.0, p)


def check_loaded(res: ContactResult, reach, offs, torque_nm: float) -> bool:
    """Raise if a load closes an off-flank cell; return the edge-contact flag."""
    edge = False
    for pc, mask, off, d in zip(reach, res.contact_masks, offs, res.approach_mm):
        if (mask & off).any() or d >= OFF_FLANK_GAP_MM:
            raise InputRangeError(f"torque_nm = {torque_nm:g}: approach of pair "
                                  f"{pc.offset:+d} (mm)", float(d),
                                  f"< {OFF_FLANK_GAP_MM} mm (load closes the off-flank "
                                  "separation)")
        edge |= bool((mask & _near(off)).any())
    return edge


def check_pair_window(loads_n: np.ndarray, offsets) -> None:
    """Raise :class:`~gearcontact.validation.UnusableInput` when the TCA's pair window
    is too narrow for the loaded mesh.

    Over one pitch pair j at the last phase is pair j + 1 at the first (the next pitch
    starts there), so the pair beyond the window's negative end is loaded at the last
    phase exactly when the outermost negative pair is loaded at the first, and likewise
    on the positive side. A missing loaded pair makes the others carry its load: the
    loaded TE stops being periodic (s0003 with pairs -2..2: TE_LCP -60.51 arcsec at the
    first phase against -61.44 at the last, with bending -98.6 against -108.0).

    Parameters
    ----------
    loads_n : ndarray (P, K)
        Pair loads along the phase, N (rows in the order of ``offsets``).
    offsets : sequence of int
        Pair offsets of the TCA's mesh cycle.
    """
    if loads_n.shape[1] < 2:
        return
    total = loads_n.sum(axis=0)
    for row, col, beyond in ((0, 0, offsets[0] - 1), (-1, -1, offsets[-1] + 1)):
        w = float(loads_n[row, col])
        if w > ACTIVE_SHARE * float(total[col]):
            raise UnusableInput(
                f"the TCA's pair window {offsets[0]}..{offsets[-1]} is too narrow for "
                f"this mesh: pair {offsets[row]} carries {w:.3g} N at the "
                f"{'first' if col == 0 else 'last'} phase of the pitch, so pair {beyond} "
                f"is loaded at the {'last' if col == 0 else 'first'}; run the TCA with "
                f"pairs >= {max(-offsets[0], offsets[-1]) + 1} (analyze_pair(pairs=...), "
                f"gearcontact tca --pairs)")


def field_edge_reached(masks) -> bool:
    """A contact mask reaches the border of its field (the field may be too small)."""
    return any(m[0, :].any() or m[-1, :].any() or m[:, 0].any() or m[:, -1].any()
               for m in masks)


def reference_compliances(ref, fields: PairFields, torque: float, eps: float, materials,
                 tol: float) -> dict:
    """Contact and mesh compliances at the reference phase by central differences.

    ``c = l0^2 (theta(T+) - theta(T-)) / (T+ - T-)`` with ``T+- = T (1 +- eps)``: with the
    transmitting pair alone (contact compliance ``d delta / d W`` of that pair) and
    with all pairs within reach (mesh compliance), for LCP and preview. ``ref``:
    (contacts, preview contacts, pressures per pair offset) of the reference phase;
    the solves start from those pressures.
    """
    contacts, valid, warm = ref
    main = next(pc for pc in valid if pc.opening_arcsec == 0.0 and not pc.edge)
    l0 = main.lever_mm
    out = {"reference_lever_mm": float(l0)}
    for key, group, hertz in (("", [main], [main]), ("mesh_", contacts, valid)):
        lv = np.array([pc.lever_mm for pc in hertz])
        gs = np.array([pc.offset_mm for pc in hertz])
        kap = np.array([pc.kappa_mm_per_n23 for pc in hertz])
        th_lcp, th_pre = [], []
        for sgn in (1.0, -1.0):
            tq = torque * (1.0 + sgn * eps)
            th = preview_balance(lv, gs, kap, tq)[0]
            res, *_ = solve_phase(group, fields, tq, materials, tol=tol, warm=warm,
                                   theta_pre=th)
            if not res.converged:
                raise CheckFailed(f"compliance at {tq / 1e3:g} N·m: {res.message}")
            th_lcp.append(res.rotation_rad)
            th_pre.append(th)
        d_t = 2.0 * eps * torque
        out[f"{key}compliance_lcp_mm_per_n"] = float(l0 ** 2 * (th_lcp[0] - th_lcp[1]) / d_t)
        out[f"{key}compliance_pre_mm_per_n"] = float(l0 ** 2 * (th_pre[0] - th_pre[1]) / d_t)
    return out
