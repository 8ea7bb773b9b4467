"""Loaded contact of one tooth pair at a mesh phase (the single-pair LTCA of docs/spec.md sec. 5).

The unloaded TCA gives the mating point P0, the common normal and the relative
curvatures; from them:

1. the member torque becomes the normal load through the contact geometry
   (:mod:`..tca.load`, gear axis);
2. the Hertzian preview (reference backend) at that load sizes the tangent-plane field:
   an ``n x n`` cell-centred grid in the principal frame (s along the long axis) with half
   extents ``extent_factor`` times the preview semi-axes, so that the minor semi-axis is
   resolved by ``n / (2 extent_factor[1])`` cells (20 for the defaults, >= 16 as the
   analytic-Hertz solver tests require for 1 % peak accuracy);
3. the gap between the real flanks over that grid (:func:`gearcontact.tca.stencil.gap_field`,
   exact intersections, never extrapolated) is solved as the load-constrained LCP
   (:func:`..halfspace.patch.solve_patch`). Cells whose normal line misses a flank (beyond the tooth
   tip, root or ends) carry no material: they get the separation
   :data:`OFF_FLANK_GAP_MM`, which no load in the operating range can close (the
   approach is tens of micrometres; checked after every solve), so the patch is trimmed
   at the flank boundary exactly as the published pipeline trims boundary-inadmissible
   cells; a loaded cell next to such a cell is reported as edge contact.

References
----------
K. L. Johnson, *Contact Mechanics*, 1985, ch. 4; docs/spec.md sec. 5.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..analytic.hertz import hamrock_brewe_hertz
from ..halfspace.ellipse import ContactEllipse
from ..halfspace.grid import TangentGrid
from ..halfspace.line_peak import LinePeak, line_contact_peak, trimmed_gap
from ..halfspace.patch import PatchContact, solve_patch
from ..materials import effective_modulus_mpa
from ..preview.engine import PreviewResult, ReferenceEngine
from ..preview.hertz.reference import ENVELOPE
from ..tca.load import normal_load_from_torque, torque_lever_mm
from ..tca.types import ARCSEC_PER_RAD
from ..tca.stencil import gap_field
from ..validation import InputRangeError, check_positive, check_range

__all__ = ["PairLoadCase", "single_pair_ltca", "preview_ellipse", "OFF_FLANK_GAP_MM"]

#: Separation given to tangent-plane cells that lie off a flank, mm (no material there).
OFF_FLANK_GAP_MM = 1.0


@dataclass(frozen=True, eq=False)
class PairLoadCase:
    """One torque on one tooth pair at the reference mesh phase.

    Attributes
    ----------
    torque_nm : float
        Gear torque, N·m.
    lever_mm : float
        Effective lever of the normal force about the gear axis, mm.
    load_n : float
        Normal load W = 1000 torque / lever, N.
    preview : PreviewResult
        Hertzian preview (reference backend) from the TCA curvatures at W.
    patch : PatchContact
        LCP solution on the real gap field (pressure map, statistics, delta).
    mesh_rotation_arcsec : float
        Gear rotation taken up by the rigid approach: delta / lever, arcsec.
    preview_mesh_rotation_arcsec : float
        The same from the preview's Hertzian approach, arcsec.
    off_flank_cells : int
        Cells of the field that lie beyond a flank boundary (no material).
    edge_contact : bool
        A loaded cell borders an off-flank cell: the contact is truncated by the flank
        edge (tooth tip, root or end).
    gap_mm : ndarray (ny, nx) or None
        The gap the LCP solved, mm (off-flank cells set to ``OFF_FLANK_GAP_MM``).
    on_flank : ndarray of bool (ny, nx) or None
        Cells whose normal line meets both flanks.
    peak : LinePeak or None
        Line-contact peak ``CP_max`` of the solution, boundary-inadmissible cells
        trimmed afterwards (:mod:`..halfspace.line_peak`).
    resolved : PatchContact or None
        The LCP re-solved without the flank's boundary row (:func:`..halfspace.line_peak.trimmed_gap`)
        when the solution loaded it; None: no boundary cell carried load.
    peak_resolved : LinePeak or None
        Line-contact peak of ``resolved`` (None when not re-solved).
    """

    torque_nm: float
    lever_mm: float
    load_n: float
    preview: PreviewResult
    patch: PatchContact
    mesh_rotation_arcsec: float
    preview_mesh_rotation_arcsec: float
    off_flank_cells: int = 0
    edge_contact: bool = False
    gap_mm: np.ndarray | None = None
    on_flank: np.ndarray | None = None
    peak: LinePeak | None = None
    resolved: PatchContact | None = None
    peak_resolved: LinePeak | None = None

    def edge_summary(self) -> dict:
        """Raw cell peak, trimmed-and-re-solved peak and ``CP_max`` (MPa), trimmed
        cells and their raw load (N); the re-solved values equal the raw ones when no
        boundary cell carried load."""
        if self.peak is None:
            return {}
        res = self.resolved if self.resolved is not None else self.patch
        pk = self.peak_resolved if self.peak_resolved is not None else self.peak
        return {"p_peak_cell_mpa": self.peak.p_peak_cell_mpa,
                "p_peak_trimmed_resolved_mpa": float(res.lcp.pressure_mpa.max()),
                "cp_max_mpa": self.peak.cp_max_mpa,
                "cp_max_resolved_mpa": pk.cp_max_mpa,
                "trimmed_cells": self.peak.trimmed_cells,
                "trimmed_load_n": self.peak.trimmed_load_n,
                "edge_resolved": self.resolved is not None,
                "mesh_rotation_resolved_arcsec": res.delta_mm / self.lever_mm
                * ARCSEC_PER_RAD}

    def summary(self) -> dict:
        """Flat JSON-ready dict (the keys of ``ltca.json``)."""
        d = {"torque_nm": self.torque_nm, "lever_mm": self.lever_mm}
        d.update(self.patch.summary())
        d.update(mesh_rotation_arcsec=self.mesh_rotation_arcsec,
                 preview_p_max_mpa=self.preview.p_max_mpa,
                 preview_a_mm=self.preview.a_mm, preview_b_mm=self.preview.b_mm,
                 preview_mesh_rotation_arcsec=self.preview_mesh_rotation_arcsec,
                 off_flank_cells=self.off_flank_cells, edge_contact=self.edge_contact)
        d.update(self.edge_summary())
        return d


def preview_ellipse(preview: PreviewResult, grid: TangentGrid) -> ContactEllipse:
    """The preview's contact ellipse in the principal frame of the gap field (centred at
    P0, major axis along s) for overlays on the pressure map."""
    dy = float(np.mean(grid.dy_mm))
    return ContactEllipse(center_x_mm=0.0, center_y_mm=0.0, semi_major_mm=preview.a_mm,
                          semi_minor_mm=preview.b_mm, angle_rad=0.0,
                          area_mm2=float(np.pi * preview.a_mm * preview.b_mm),
                          cells_per_semi_minor=preview.b_mm / dy)


def single_pair_ltca(tca, flanks, pair, torque_nm: float, *, side: str | None = None,
                     cells: int = 80, extent_factor: tuple[float, float] = (1.6, 2.0),
                     solver: str = "pk_cg", warm_start: PatchContact | None = None
                     ) -> PairLoadCase:
    """Loaded contact of the reference tooth pair at P0 under a gear torque.

    Parameters
    ----------
    tca : gearcontact.tca.analysis.TcaAnalysis
        Unloaded analysis (mean mating point, relative curvature).
    flanks : gearcontact.geometry.flank.FlankSet
        The flanks the TCA ran on.
    pair : gearcontact.geometry.pair.GearPair
        The pair (kinematics with assembly errors, material).
    torque_nm : float
        Gear torque, N·m (> 0).
    side : str, optional
        ``"drive"`` or ``"coast"`` (the side the TCA ran on); default the pair's
        ``design_side``.
    cells : int
        Cells per side of the square tangent-plane grid (>= 16).
    extent_factor : (float, float)
        Half extents of the field in preview semi-axes (major, minor), each >= 1.1.
    solver : str
        LCP solver (:func:`gearcontact.halfspace.lcp.solve_lcp`).
    warm_start : PatchContact, optional
        Previous solution on the same grid (ignored when the grid differs). The result
        then ends within the LCP's tolerance of the cold solve, not on its bits: a
        caller that wants results independent of call history leaves it None
        (docs/architecture.md "Determinism").
    """
    side = pair.design_side if side is None else side
    t = check_positive("torque_nm (N·m)", torque_nm)
    if int(cells) < 16:
        raise InputRangeError("cells", cells, ">= 16 per side")
    for i, f in enumerate(extent_factor):
        if not f >= 1.1:
            raise InputRangeError(f"extent_factor[{i}]", f, ">= 1.1 preview semi-axes")
    mp, rc = tca.mean_point, tca.mean_curvature
    lever = torque_lever_mm(mp.point_mm, mp.normal)
    load = normal_load_from_torque(t, mp.point_mm, mp.normal)
    # the load keeps the preview's range (the torque the CLI names); the curvatures may
    # leave it: host-side fp64 preview without the datapath envelope (a large gear's B-
    # lies below the fixed-point range; the golden/RTL stages report that themselves)
    check_range("load_n (N)", load, *ENVELOPE["load_n"])
    engine = ReferenceEngine(material=pair.pinion_material, material2=pair.gear_material,
                             envelope=False)
    pre = engine.hertz(rc.A_minus_per_mm, rc.B_minus_per_mm, load)
    kin = pair.kinematics()
    field = gap_field(flanks.flank("pinion", side), flanks.flank("gear", side), kin, mp,
                      half_extent_mm=(extent_factor[0] * pre.a_mm, extent_factor[1] * pre.b_mm),
                      side=int(cells), frame="principal",
                      # same values and mask on the flanks; lines beyond them converge on
                      # the continuation instead of being pinned (measured 1.5-2.4 ms less)
                      allow_outside=True)
    off = ~field.on_flank
    # the four cells around P0: all off means P0 is not on the flanks; an edge contact
    # (tca.edge_contact) has P0 on a flank boundary, with cells on one side of it
    j, k = field.gap_mm.shape[0] // 2, field.gap_mm.shape[1] // 2
    if off[j - 1:j + 1, k - 1:k + 1].all():
        raise InputRangeError("mating point P0", tuple(mp.point_mm), "a point on both flanks")
    gap = np.where(off, OFF_FLANK_GAP_MM, field.gap_mm)
    s_axis, t_axis = field.s_mm[0, :], field.t_mm[:, 0]
    grid = TangentGrid.uniform(len(s_axis), len(t_axis), dx_mm=float(s_axis[1] - s_axis[0]),
                               dy_mm=float(t_axis[1] - t_axis[0]), x0_mm=float(s_axis[0]),
                               y0_mm=float(t_axis[0]))
    if warm_start is not None and warm_start.grid.x_mm.shape != grid.x_mm.shape:
        warm_start = None
    patch = solve_patch(gap, grid, load, materials=(pair.pinion_material, pair.gear_material), solver=solver,
                        warm_start=warm_start)
    loaded = patch.lcp.contact_mask
    if (loaded & off).any() or patch.delta_mm - float(field.gap_mm[~off].min()) >= OFF_FLANK_GAP_MM:
        raise InputRangeError(f"torque_nm = {t:g}: approach (mm)", patch.delta_mm,
                              f"< {OFF_FLANK_GAP_MM} mm (load closes the off-flank separation)")
    near_off = off.copy()
    near_off[1:, :] |= off[:-1, :]
    near_off[:-1, :] |= off[1:, :]
    near_off[:, 1:] |= off[:, :-1]
    near_off[:, :-1] |= off[:, 1:]
    # boundary-inadmissible cells (docs/spec.md sec. 5): trimmed, and the LCP re-solved
    # without the flank's boundary row when it carried load (warm from the raw solution)
    gap2 = trimmed_gap(gap, off, loaded, OFF_FLANK_GAP_MM)
    resolved = peak_resolved = None
    if gap2 is not None:
        resolved = solve_patch(gap2, grid, load, materials=(pair.pinion_material,
                                                           pair.gear_material),
                               solver=solver, warm_start=np.where(
                                   gap2 < OFF_FLANK_GAP_MM, patch.lcp.pressure_mpa, 0.0),
                               warn_edge=False, warn_coarse=False)
        peak_resolved = line_contact_peak(resolved.lcp.loads_n, grid, gap2 >= OFF_FLANK_GAP_MM)
    # approach of the (rigid) teeth along the normal -> gear rotation about its axis
    return PairLoadCase(off_flank_cells=int(off.sum()), gap_mm=gap, on_flank=~off,
                        peak=line_contact_peak(patch.lcp.loads_n, grid, off),
                        resolved=resolved, peak_resolved=peak_resolved,
                        edge_contact=bool((loaded & near_off).any()),
torque_nm=t, lever_mm=lever, load_n=load, preview=pre, patch=patch,
                        mesh_rotation_arcsec=patch.delta_mm / lever * ARCSEC_PER_RAD,
                        preview_mesh_rotation_arcsec=_preview_approach(pre, rc, pair, load)
                        / lever * ARCSEC_PER_RAD)


def _preview_approach(pre: PreviewResult, rc, pair, load: float) -> float:
    """Hertzian approach of the preview (Hamrock–Brewe), mm."""
    hb = hamrock_brewe_hertz(rc.A_minus_per_mm, rc.B_minus_per_mm, load,
                             e_prime_mpa=effective_modulus_mpa(pair.pinion_material,
                                                                pair.gear_material))
    return hb.approach_mm
