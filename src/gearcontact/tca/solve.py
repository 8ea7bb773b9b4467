"""Unloaded tooth contact analysis (TCA) of one tooth pair over the mesh phases.

:func:`solve_tca` follows the mating point of two flanks (:mod:`.mating`, Newton per
phase) along the pinion phases by continuation, and through edge-to-surface contact
(:mod:`.edge_contact`) where the surface mating point leaves a flank or an edge touches
before it (:mod:`.edge_screen`). The types, the
constants and the errors of the TCA are in :mod:`.types`, the mating-point solver in
:mod:`.mating` (their former names here are deprecated).

Transmission error (docs/geometry.md sec. 4):
``TE0 = (phi2 - phi2_0) - (z1/z2)(phi1 - phi1_0)`` converted to arcsec
(x 206264.806), relative to the reference (mean) mating point ``(phi1_0, phi2_0)``.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
from tqdm import tqdm

from ..deprecation import moved_names
from ..geometry.kinematics import MeshKinematics
from ..geometry.surface import Surface
from .edge_contact import contact_state, inward_slope, pushes_forward, solve_edge_contact
from .edge_screen import edge_first, leads
from .edges import solver_boundary
from .mating import solve_mating_point
from .types import (ARCSEC_PER_RAD, EDGE_TE_LIMIT_ARCSEC, ContactGuess, EdgeContact,
                    MatingPoint, TcaConvergenceError, TcaPath)

__all__ = ["solve_tca"]

#: Deprecated for one release: the TCA's types are in :mod:`.types`, the mating point's
#: functions in :mod:`.mating`.
__getattr__ = moved_names(__name__, {
    "VARIABLES": "gearcontact.tca.types:VARIABLES",
    "posed_point": "gearcontact.tca.mating:posed_point",
    "normal_derivatives": "gearcontact.tca.mating:normal_derivatives"})


def _predict(prev: MatingPoint, prev2: MatingPoint | None, phi1: float,
             ratio: float) -> ContactGuess:
    """Continuation predictor at ``phi1``: secant through the last two solutions, or
    the last one turned by the nominal ratio."""
    x_prev = prev.as_guess().vector()
    if prev2 is None:
        x_pred = x_prev.copy()
        x_pred[5] += (phi1 - x_prev[4]) / ratio
    else:
        x_old = prev2.as_guess().vector()
        x_pred = x_prev + (x_prev - x_old) * (phi1 - x_prev[4]) / (x_prev[4] - x_old[4])
    x_pred[4] = phi1
    return ContactGuess.from_vector(x_pred)


def solve_tca(pinion: Surface, gear: Surface, kin: MeshKinematics, phi1_rad,
              *, start: ContactGuess, start_fixed: str = "phi1", tol_mm: float = 1e-10,
              max_iter: int = 40, max_step_rad: float | None = None,
              edges: bool = True, edge_te_limit_arcsec: float = EDGE_TE_LIMIT_ARCSEC,
              edge_check: bool = True, progress: bool = False) -> TcaPath:
    """TCA of one tooth pair over the mesh phases ``phi1_rad`` by continuation.

    The reference (mean) mating point is solved first from ``start`` with
    ``start_fixed`` held (``"phi1"``: at ``start.phi1_rad``; ``"u2"``: the path point
    through the gear's profile parameter ``start.u2``). The path is then continued
    from it upwards and downwards in ``phi1`` with a secant predictor. Where the
    surface mating point leaves a flank, the path switches to edge-to-surface contact
    (:mod:`gearcontact.tca.edge_contact`; ``edges=True``): at each further phase the
    first of the edge contact and a surface mating point (re-entry) to touch is kept,
    until no edge touches the other flank either; all further phases in that direction
    are then phases without contact (never extrapolated). With ``edges=False`` the
    path stops at the first boundary (surface contact only).

    Parameters
    ----------
    pinion, gear : Surface
        The two flanks (see :func:`solve_mating_point`).
    kin : MeshKinematics
        Kinematics with assembly errors.
    phi1_rad : array_like
        Strictly increasing pinion phases, rad.
    start : ContactGuess
        Guess of the reference mating point.
    start_fixed : str
        Variable held fixed while solving the reference point (an edge contact, when the
        surface point lies beyond a flank, holds ``phi1``).
    max_step_rad : float, optional
        Largest continuation step in ``phi1``: a wider gap between two requested
        phases is crossed in equal unrecorded substeps (a coarse phase grid then
        follows the path as far as a fine one; a too wide secant step can run into a
        parameter box early and end the path there). Default: no substeps.
    edges : bool
        Continue through edge-to-surface contact (default) or stop at the boundary.
    edge_check : bool
        With ``edges``: at every phase whose surface mating point lies inside both
        flanks, ask whether an edge touches before it
        (:func:`~gearcontact.tca.edge_screen.edge_first`) and keep the edge contact if
        so; the surface point is then followed on beside the edge until it touches
        first again or leaves a flank (default). False: edges only where the surface
        point has left a flank.
    edge_te_limit_arcsec : float
        An edge contact whose TE0 lies more than this behind the path's first touch so
        far (its TE0 extreme) ends the path in that direction: it can carry only if the
        mesh's TE0 peak-to-peak exceeds the limit (:func:`~gearcontact.tca.mesh.mesh_cycle`
        then widens it). Keeps the cost of the edge tails bounded.
    progress : bool
        Show a tqdm progress bar over the phases.

    Returns
    -------
    TcaPath
        With TE0 relative to the reference point, arcsec.
    """
    phis = np.asarray(phi1_rad, dtype=float).ravel()
    if phis.size == 0 or np.any(np.diff(phis) <= 0.0):
        raise ValueError("phi1_rad must be a non-empty, strictly increasing sequence")
    if edges:
        ref = contact_state(pinion, gear, kin, start, fixed=start_fixed, tol_mm=tol_mm,
                            max_iter=max_iter)
    else:
        ref = solve_mating_point(pinion, gear, kin, start, fixed=start_fixed,
                                 tol_mm=tol_mm, max_iter=max_iter)
    forward = pushes_forward(gear, kin, ref.as_guess())
    results: list[MatingPoint | None] = [None] * phis.size
    i0 = int(np.searchsorted(phis, ref.phi1_rad))
    bar = tqdm(total=phis.size, desc="TCA phases", disable=not progress, leave=False)

    def first_touch(a: MatingPoint | None, b: MatingPoint | None) -> MatingPoint | None:
        if a is None or b is None:
            return a if b is None else b
        return a if (a.phi2_rad >= b.phi2_rad) == forward else b

    check = edges and edge_check
    screen_memo: dict = {}      # the edge screen's Newton starts along the path

    def checked(surface: MatingPoint) -> MatingPoint:
        return edge_first(pinion, gear, kin, surface, forward=forward, tol_mm=tol_mm,
                          memo=screen_memo)

    for direction, indices in ((+1, range(i0, phis.size)), (-1, range(i0 - 1, -1, -1))):
        prev, prev2 = ref, None
        # the surface point (and its predecessor) while an edge that touched before it
        # carries: it lay inside both flanks then and is followed on
        shadow: tuple | None = None
        stopped: str | None = None
        best = 0.0                  # the path's first touch so far (TE0 extreme), arcsec
        for i in indices:
            bar.update(1)
            if stopped is not None:
                results[i] = MatingPoint.edge_phase(phis[i], stopped)
                continue
            mp = None
            if not prev.edge_contact:
                gap = phis[i] - prev.phi1_rad
                subs = 1 if max_step_rad is None else max(1, int(np.ceil(abs(gap) / max_step_rad)))
                try:
                    for j in range(1, subs + 1):
                        phi = phis[i] if j == subs else prev.phi1_rad + gap / (subs - j + 1)
                        step = solve_mating_point(pinion, gear, kin,
                                                  _predict(prev, prev2, phi, kin.ratio),
                                                  tol_mm=tol_mm, max_iter=max_iter)
                        if abs(step.phi1_rad - prev.phi1_rad) > 0.0:
                            prev2 = prev
                        prev = step
                        gap = phis[i] - prev.phi1_rad
                    mp = checked(step) if check else step
                    if mp is not step:
                        shadow = (prev, prev2)
                except (EdgeContact, TcaConvergenceError) as exc:
                    if isinstance(exc, EdgeContact):
                        where = exc.where
                    else:
                        # no surface mating point: the path may have folded back in
                        # phi1 (a turning point near the limit line, the Jacobian
                        # singular there) while an edge takes over the contact; only if
                        # no edge touches either is it a failure of the solve
                        where = "no convergence"
                        mp = solve_edge_contact(pinion, gear, kin, phis[i],
                                                guess=prev.as_guess(), forward=forward,
                                                tol_mm=tol_mm)
                        if mp is None:
                            raise
                    if not edges:       # surface contact only: the path ends here
                        stopped = (where if mp is None
                                   else solver_boundary(mp.edge_contact))
                        results[i] = MatingPoint.edge_phase(phis[i], stopped)
                        continue
                    if isinstance(exc, EdgeContact):
                        mp = solve_edge_contact(pinion, gear, kin, phis[i],
                                                guess=prev.as_guess(), forward=forward,
                                                tol_mm=tol_mm)
            else:
                # edge mode: the edge contact, or the surface point if it is back on the
                # flanks and touches first
                where = solver_boundary(prev.edge_contact)
                edge = solve_edge_contact(pinion, gear, kin, phis[i], guess=prev.as_guess(),
                                          forward=forward, tol_mm=tol_mm)
                surface = None
                if shadow is not None:
                    s_prev, s_prev2 = shadow
                    shadow = None
                    try:
                        surface = solve_mating_point(
                            pinion, gear, kin, _predict(s_prev, s_prev2, phis[i], kin.ratio),
                            tol_mm=tol_mm, max_iter=max_iter)
                    except (EdgeContact, TcaConvergenceError):
                        pass    # it has left a flank: the edge mode below
                    if surface is not None:
                        mp = checked(surface)
                        if edge is not None and leads(edge, mp, forward=forward):
                            mp = edge
                        if mp is not surface:
                            shadow = (surface, s_prev)
                # the flank behind the edge dips towards the other flank: the surface
                # contact is back inside the flanks
                if surface is None and (edge is None
                                        or inward_slope(pinion, gear, kin, edge) < 0.0):
                    guess = replace(prev.as_guess(), phi1_rad=phis[i], phi2_rad=prev.phi2_rad
                                    + (phis[i] - prev.phi1_rad) / kin.ratio)
                    try:
                        surface = solve_mating_point(pinion, gear, kin, guess, tol_mm=tol_mm,
                                                     max_iter=max_iter)
                    except (EdgeContact, TcaConvergenceError):
                        pass
                    mp = first_touch(surface, edge)
                    if check and mp is surface and surface is not None:
                        mp = checked(surface)
                        if mp is not surface:
                            shadow = (surface, None)
                elif surface is None:
                    mp = edge
            if mp is None:
                stopped = where
                results[i] = MatingPoint.edge_phase(phis[i], stopped)
                continue
            te = ((mp.phi2_rad - ref.phi2_rad) - (mp.phi1_rad - ref.phi1_rad) / kin.ratio)
            te *= ARCSEC_PER_RAD
            if mp.edge_contact and (best - te if forward else te - best) > edge_te_limit_arcsec:
                # an edge contact this far behind the path's first touch cannot carry
                stopped = solver_boundary(mp.edge_contact)
                results[i] = MatingPoint.edge_phase(phis[i], stopped)
                continue
            best = max(best, te) if forward else min(best, te)
            if prev is not mp:      # a switch between surface and edge contact
                prev2, prev = None, mp
            results[i] = replace(mp, te0_arcsec=te)
    bar.close()
    if check:
        _surface_returns(pinion, gear, kin, results, ref, checked=checked, forward=forward,
                         tol_mm=tol_mm, max_iter=max_iter)
    return TcaPath(tuple(results), ref.phi1_rad, ref.phi2_rad, kin.ratio)


def _is_surface(mp: MatingPoint) -> bool:
    return not mp.edge and not mp.edge_contact


def _surface_returns(pinion: Surface, gear: Surface, kin: MeshKinematics, results: list,
                     ref: MatingPoint, *, checked, forward: bool, tol_mm: float,
                     max_iter: int) -> None:
    """Continue each surface stretch of a path into the edge (or contactless) phases next
    to it, from its own end, against the sweep's direction too: a surface point inside
    both flanks (checked for an edge touching before it, ``checked``) that touches
    before the phase's edge contact replaces it, phase by phase, until one does not
    (docs/machine_settings.md sec. 5, "The edge check while the surface contact is
    inside"). ``results`` is edited in place."""
    n = len(results)
    for step in (+1, -1):
        for i in range(n) if step > 0 else range(n - 1, -1, -1):
            j, back = i + step, i - step
            if not (0 <= j < n) or not _is_surface(results[i]) or _is_surface(results[j]):
                continue
            prev = results[i]
            prev2 = results[back] if 0 <= back < n and _is_surface(results[back]) else None
            while 0 <= j < n and not _is_surface(results[j]):
                try:
                    surface = solve_mating_point(
                        pinion, gear, kin, _predict(prev, prev2, results[j].phi1_rad,
                                                    kin.ratio), tol_mm=tol_mm,
                        max_iter=max_iter)
                except (EdgeContact, TcaConvergenceError):
                    break
                mp = checked(surface)
                if not results[j].edge and not leads(mp, results[j], forward=forward):
                    break
                te = ((mp.phi2_rad - ref.phi2_rad) - (mp.phi1_rad - ref.phi1_rad) / kin.ratio)
                results[j] = replace(mp, te0_arcsec=te * ARCSEC_PER_RAD)
                prev2, prev = prev, surface
                j += step
