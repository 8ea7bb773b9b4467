"""Loaded transmission error of a cylindrical pair over a mesh cycle, with the shell
bending of both teeth or rigid teeth (docs/cylindrical.md sec. 7, docs/bending.md sec. 9).

At each phase of the unloaded cycle (:func:`~gearcontact.tca.cylindrical_cycle.
cylindrical_mesh_cycle`) every tooth pair with a contact line in the zone of action is
one block of the torque-constrained LCP of :mod:`.mesh_lcp` (all pairs in one solve, the
shared gear rotation ``theta`` its multiplier: loaded TE = TE0 plus ``theta``).

Grid. The contact line of an involute pair lies in the plane of action; its common
tangent plane contains the line and is perpendicular to that plane. Each pair gets a
uniform grid in it: ``y`` along the line (``y = z / cos(beta_b)`` over the pinion face,
the same for every pair and phase, cells off the line in the zone get a separation of
:data:`OFF_LINE_GAP_MM`) and ``x`` across it (the profile direction). The gap is

    h(x, y) = cos(beta_b) (g(z) - g_j) + x^2 / (2 R(z)),
    1 / R = cos(beta_b) (1 / u1 + 1 / u2),

with ``g(z)`` the gap along the transverse line of action of the unloaded cycle
(:func:`~gearcontact.tca.cylindrical_cycle.contact_line_gaps`; ``cos(beta_b)`` turns it
into the normal), ``g_j`` its least value on the line and ``R`` the relative radius of
curvature normal to the line (transverse radii ``u1``, ``u2``, the roll lengths, over
``cos(beta_b)``: ISO 6336-2's normal-section radii). The pair's opening is
``cos(beta_b) (g_j - g_c)`` (``g_c`` the mesh's closing gap, a tip edge's where one
touches first) and its lever about the gear axis ``r_b2 cos(beta_b)``
(a gear rotation moves its flank by ``r_b2`` along the transverse line of action).
The profile modifications enter through ``g(z)`` along the line only: across the strip
(a few tenths of a mm) their change is neglected, and a contact is not truncated at the
tip across the strip (a loaded cell in the first or last column of the grid is
reported, ``edge_touch``).

End-loaded lines. A misaligned (or helix-sloped) uncrowned line closes over part of
the face from one end, a wedge: its load runs up to that end, where a face end (or a
tip or form circle) cuts the flank off sharply. The strip is sized for the mean line
load; where a loaded cell then lies on its border, it is widened (to twice, or to
:data:`END_PEAK_MARGIN` times the closed form's peak line load of the end-loaded lines,
:func:`~gearcontact.analytic.face_load.end_loaded_line`) and the cycle solved again, at
most :data:`MAX_WIDENINGS` times (``edge_touch`` then says it stayed too narrow).
Line ends: a line loaded in its end row (``line_end_loaded``) ends at a sharp edge of
the half-space model, where the pressure is singular (a flat punch's edge), as on a
tip-edge block: the peak pressure there (``peak_at_edge``) and the end row's line load grow with the rows
(about 2^(1/2) per halving), while the loaded length (``loaded_length_mm``) and the
approach converge (docs/cylindrical.md sec. 7, "End-loaded lines").

Tip-edge contact. A pair without a line in the zone whose tip edge touches the mating
flank within reach (the cycle's ``tip``, :mod:`~gearcontact.tca.cylindrical_tip`) is a
block along that edge: rows at the grid's axial positions with the edge points' normal
gap ``(lever / |rate|) (g_e(z) - g_e)`` (:func:`~gearcontact.tca.cylindrical_tip.
tip_edge_gaps`), across only ``x >= 0`` into the edge's own flank (no material beyond
the edge) with ``sin(angle between the flanks) x + x^2 / (2 R)``; lever the touched
normal's about the gear axis, opening that lever times its closing turn behind the
mesh's; bending at the touch's roll lengths (:mod:`.cylindrical_edges`). This is the
extended contact of deflected teeth at the tip of the driven tooth (start of mesh) and
of the driver (end). On a helical pair whose line is in the zone, the tooth's sections
beyond its tip end (the line crosses the zone diagonally) are such edge rows too, joined
to the line's block (elastic and bending coupling with the line, the line's lever): the
rows at the grid's axial positions beyond the line's end (:func:`~gearcontact.tca.
cylindrical_tip.beyond_line_edge_gaps`), entering by the same rule (``beyond_*``
fields).

Loads: the gear torque ``T2`` (the package's convention, as :mod:`.lte`) gives the
normal load ``F_n = T2 / (r_b2 cos(beta_b))`` (ISO 6336-1: ``T1 / (r_b1 cos(beta_b))``).
The Harris map's default torques (:func:`harris_torques_nm`) are those of the ISO 6336
line loads ``F_t / b`` = 50 to 400 N/mm (``F_t = 2 T2 / d2`` at the reference circle;
Method B's stiffness holds from 100 N/mm). Mesh stiffness per
phase is the secant ``k = F_n / delta`` with ``delta = r_b2 cos(beta_b) theta`` the normal
approach from the unloaded rest, given per unit face width in N/(mm·µm) (the unit of
ISO 6336-1's c' and c_gamma).

Tooth bending (``bending=True``, the default as for bevel pairs' ``gearcontact lte``):
each pair's block carries the shell compliance of its pinion and gear tooth along the
line (:mod:`.cylindrical_bending`; G_pinion + G_gear, block diagonal across pairs) beside
the Love half-space; ``bending=False`` gives rigid teeth, the contact's compliance
alone.

References
----------
K. L. Johnson, *Contact Mechanics*, 1985, sec. 4.3 (line contact).
ISO 6336-1:2006 (normal load, c', c_gamma); ISO 6336-2:2006 (normal radii of curvature).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, replace

import numpy as np

from ..geometry.cylindrical.pair import CylindricalPair
from ..halfspace.grid import TangentGrid
from ..halfspace.lcp import resolve_e_star
from ..tca.cylindrical_cycle import CylindricalMeshCycle, contact_line_gaps, \
    cylindrical_mesh_cycle
from ..tca.cylindrical_tip import beyond_line_edge_gaps, tip_edge_gaps
from ..tca.plane_of_action import PlaneOfAction
from ..tca.types import ARCSEC_PER_RAD
from ..validation import InputRangeError, check_positive
from .cylindrical_bending import cylindrical_bending, line_bending_factor
from .cylindrical_edges import OFF_LINE_GAP_MM, BeyondLoads, beyond_rows, closing_turn_rad, \
    edge_block, join_beyond
from .cylindrical_strip import END_PEAK_MARGIN, across_extent_mm, wedge_line
from .mesh_lcp import PairBlock, solve_mesh_lcp

__all__ = ["HARRIS_LINE_LOADS_N_PER_MM", "OFF_LINE_GAP_MM", "CylindricalLoadedTE", "HarrisMap",
           "axial_rows_mm", "check_cells", "cylindrical_loaded_te", "cylindrical_loaded_te_models",
           "harris_map", "harris_tip_reliefs_um", "harris_torques_nm", "normal_load_n",
           "wedge_line", "END_PEAK_MARGIN", "MAX_WIDENINGS", "STRIP_TOO_NARROW"]

#: Times the strip is widened (and the cycle solved again) while a loaded cell lies on
#: its border.
MAX_WIDENINGS = 3
#: What the commands tell the user when ``edge_touch`` stays set (one line on stderr).
STRIP_TOO_NARROW = (
    f"loaded cells on the border of the strip across a contact line after widening it "
    f"{MAX_WIDENINGS} times: the LCP cuts the contact off across there (pressure and line "
    "load too low in those rows; line_load.csv shows where). The load is concentrated "
    "far above its mean, as on a line end-loaded by misalignment: reduce [assembly] "
    "axis_inclination_um / axis_deviation_um, or centre the load with [modifications."
    "pinion] lead_crowning_um or a helix_slope_um that cancels the misalignment")


def normal_load_n(pair: CylindricalPair, torque_nm: float) -> float:
    """Normal tooth load of the gear torque, ``T2 / (r_b2 cos(beta_b))`` (N; ISO 6336-1)."""
    t = check_positive("torque_nm", torque_nm)
    g = pair.geometry
    return 2e3 * t / (g.base_diameter_gear_mm * math.cos(math.radians(g.base_helix_angle_deg)))


#: Line loads F_t / b of the default Harris-map torques, N/mm.
HARRIS_LINE_LOADS_N_PER_MM = (50.0, 100.0, 200.0, 300.0, 400.0)


def harris_torques_nm(pair: CylindricalPair, line_loads_n_per_mm=HARRIS_LINE_LOADS_N_PER_MM
                      ) -> np.ndarray:
    """Gear torques (N·m) of the tangential line loads ``F_t / b`` (N/mm) at the gear's
    reference circle, ``T2 = (F_t / b) b d2 / 2000``."""
    g = pair.geometry
    w = np.asarray(line_loads_n_per_mm, dtype=float)
    return w * g.face_width_mm * g.reference_diameter_gear_mm / 2e3


def harris_tip_reliefs_um(pair: CylindricalPair) -> np.ndarray:
    """Default tip reliefs of the Harris map: 0, 1/2, 1, 3/2 and 2 times the pinion's C_a
    (µm; 0 to 20 µm in steps of 5 when the pair has none)."""
    c = pair.modifications_pinion.tip_relief_um
    return np.array([0.0, 0.5, 1.0, 1.5, 2.0]) * (c if c > 0.0 else 10.0)


@dataclass(frozen=True)
class CylindricalLoadedTE:
    """Loaded TE of a cylindrical pair over one pinion pitch.

    Shapes: K phases, P tooth pairs (``pair_offsets``, as the unloaded cycle), N cells
    along the face (``z_mm``).

    Attributes
    ----------
    phi1_rad : ndarray (K,)
    pair_offsets : tuple of int
    torque_nm : float
        Gear torque, N·m.
    normal_load_n : float
        ``F_n``, N.
    te0_arcsec, lte_arcsec : ndarray (K,)
        Unloaded and loaded TE, arcsec (the TCA's sign: negative, the gear lags).
    load_share : ndarray (P, K)
        Normal load of each pair over ``F_n`` (0 for a pair out of the zone). They sum
        to 1 where only lines carry; a tip edge's normal has its own lever (``lever_mm``):
        the torque balance is ``sum_j share_j lever_j = r_b2 cos(beta_b)``.
    max_pressure_mpa : ndarray (K,)
        Largest cell pressure, MPa.
    z_mm : ndarray (N,)
        Axial cell centres on the pinion face, mm.
    line_load_n_per_mm : ndarray (P, K, N)
        Load per unit face width along each contact line, N/mm.
    line_pressure_mpa : ndarray (P, K, N)
        Peak pressure across each line (the largest cell of each row), MPa.
    stiffness_n_per_mm_um : ndarray (K,)
        Secant mesh stiffness per unit face width, N/(mm·µm) (module docstring).
    face_width_mm : float
        Common face width b, mm.
    grid_dx_mm, grid_dy_mm : float
        Cell widths across and along the lines, mm.
    edge_touch : bool
        A loaded cell on the grid's first or last column across (strip too narrow).
    iterations : ndarray (K,) of int
    converged : bool
        Every phase's LCP converged.
    solve_time_s : float
        CPU time of the LCP solves, s.
    bending : bool
        Tooth bending was in the LCP (else rigid teeth).
    edge_label : ndarray (P, K) of str
        ``"pinion tip"`` / ``"gear tip"`` where the pair's block is its tip edge touching
        the mating flank beyond the path of contact (an ``edge`` row), else ``""``.
    lever_mm : ndarray (P, K)
        Lever of each pair's normal force about the gear axis, mm (``r_b2 cos(beta_b)``
        for a line, the touch's own for a tip edge; 0 for a pair without a block).
    loaded_length_mm : ndarray (P, K)
        Length of each line's loaded rows, mm (0 for a tip edge or no block).
    line_end_loaded : ndarray (P, K) of bool
        The line carries load in its end row at either end (a face end, or where a tip
        or form circle cuts it): a sharp end of the contact (module docstring, "Line
        ends").
    peak_at_edge : ndarray (K,) of bool
        The phase's largest pressure lies in such an end row or on a tip-edge block: a
        sharp edge's singular pressure, which grows with refinement
        (``max_pressure_mpa`` is then no design value; the loaded length and the
        approach converge).
    beyond_load_share : ndarray (P, K, 2)
        Normal load over ``F_n`` of each tip edge (pinion, gear: ``TIP_EDGES``) beyond
        pair ``j``'s line (a helical pair's sections past its tip end while the line is
        in the zone; module docstring, "Tip-edge contact"); its rows' loads are in
        ``line_load_n_per_mm`` where ``beyond_rows`` >= 0. The torque balance is then
        ``sum (share lever) + sum (beyond_share beyond_lever) = r_b2 cos(beta_b)``.
    beyond_lever_mm : ndarray (P, K, 2)
        Its lever about the gear axis, mm: the line's, whose block the rows join (0
        where none was in the LCP).
    beyond_rows : ndarray (P, K, N) of int8
        The edge (index into ``TIP_EDGES``) of each face cell's row beyond the line
        that was in the LCP, else -1.
    rotation_rad : ndarray (K,)
        Gear rotation the load adds to the unloaded rest (the mesh LCP's multiplier
        ``theta``), rad; the normal approach is ``r_b2 cos(beta_b) theta``.
    fields_phase : int or None
        The phase whose cell pressures ``phase_pressure_mpa`` holds (``fields_at``).
    phase_pressure_mpa : ndarray (P, N, M) or None
        Cell pressures of every pair at ``fields_phase``, MPa (0 for a pair without a
        block): rows at ``z_mm``, ``M`` columns across the line of width ``grid_dx_mm``
        centred on it (the grid of every block of the phase).
    """

    phi1_rad: np.ndarray
    pair_offsets: tuple[int, ...]
    torque_nm: float
    normal_load_n: float
    te0_arcsec: np.ndarray
    lte_arcsec: np.ndarray
    load_share: np.ndarray
    max_pressure_mpa: np.ndarray
    z_mm: np.ndarray
    line_load_n_per_mm: np.ndarray
    line_pressure_mpa: np.ndarray
    stiffness_n_per_mm_um: np.ndarray
    face_width_mm: float
    grid_dx_mm: float
    grid_dy_mm: float
    edge_touch: bool
    iterations: np.ndarray
    converged: bool
    solve_time_s: float
    bending: bool = False
    edge_label: np.ndarray | None = None
    lever_mm: np.ndarray | None = None
    loaded_length_mm: np.ndarray | None = None
    line_end_loaded: np.ndarray | None = None
    peak_at_edge: np.ndarray | None = None
    beyond_load_share: np.ndarray | None = None
    beyond_lever_mm: np.ndarray | None = None
    beyond_rows: np.ndarray | None = None
    rotation_rad: np.ndarray | None = None
    fields_phase: int | None = None
    phase_pressure_mpa: np.ndarray | None = None

    @property
    def lte_pp_arcsec(self) -> float:
        """Peak-to-peak loaded TE over the pitch, arcsec."""
        return float(self.lte_arcsec.max() - self.lte_arcsec.min())

    @property
    def mean_stiffness_n_per_mm_um(self) -> float:
        """Mean secant mesh stiffness over the pitch (one end left out: periodic)."""
        return float(np.mean(self.stiffness_n_per_mm_um[:-1]))


def check_cells(field: str, n) -> int:
    """``n`` cells of a pair's grid along one axis: an integer >= 4, else
    :class:`~gearcontact.validation.InputRangeError` naming ``field``."""
    if isinstance(n, bool) or int(n) != n or n < 4:
        raise InputRangeError(field, n, "an integer >= 4")
    return int(n)


def axial_rows_mm(cycle: CylindricalMeshCycle, cells_along: int) -> np.ndarray:
    """Axial positions (mm) of the grid's ``cells_along`` rows (:func:`check_cells`):
    the cell centres of a uniform division of the cycle's pinion face (module
    docstring, Grid)."""
    cells_along = check_cells("cells_along", cells_along)
    z0, z1 = cycle.pinion_v_range_mm
    dz = (z1 - z0) / cells_along
    return z0 + dz * (np.arange(cells_along) + 0.5)


def cylindrical_loaded_te(pair: CylindricalPair, torque_nm: float, *,
                          cycle: CylindricalMeshCycle | None = None, facing: str = "cw",
                          phases: int = 61, cells_across: int = 24, cells_along: int = 64,
                          extent_factor: float = 2.0, tol: float = 1e-8,
                          bending: bool = True,
                          fields_at: int | None = None) -> CylindricalLoadedTE:
    """Loaded TE, load sharing, pressure and mesh stiffness over one pinion pitch.

    Parameters
    ----------
    pair : CylindricalPair
    torque_nm : float
        Gear torque, N·m (> 0).
    cycle : CylindricalMeshCycle, optional
        The unloaded cycle of ``pair`` (computed with ``facing``, ``phases`` if None).
    facing, phases
        As :func:`~gearcontact.tca.cylindrical_cycle.cylindrical_mesh_cycle`.
    cells_across, cells_along : int
        Grid cells across the lines (>= 4) and along the pinion face (>= 4).
    extent_factor : float
        Strip half-width in Hertz half-widths of the whole load on the shortest total
        line length (> 0; module docstring).
    tol : float
        LCP tolerance (:func:`.mesh_lcp.solve_mesh_lcp`).
    bending : bool
        Add the shell bending compliance of both teeth (module docstring; default);
        False: rigid teeth.
    fields_at : int, optional
        Keep the cell pressures of every pair at this phase index (0 to K - 1) in
        ``phase_pressure_mpa`` (observed from the same solve: no effect on the rest).
    """
    load = normal_load_n(pair, torque_nm)
    for key, n in (("cells_across", cells_across), ("cells_along", cells_along)):
        check_cells(key, n)
    check_positive("extent_factor", extent_factor)
    if cycle is None:
        cycle = cylindrical_mesh_cycle(pair, facing=facing, phases=phases)
    if fields_at is not None and not (isinstance(fields_at, int | np.integer)
                                      and 0 <= fields_at < len(cycle.phi1_rad)):
        raise InputRangeError("fields_at", fields_at,
                              f"a phase index in [0, {len(cycle.phi1_rad) - 1}]")
    teeth = cylindrical_bending(pair, facing=cycle.facing) if bending else None
    g = pair.geometry
    cb = math.cos(math.radians(g.base_helix_angle_deg))
    e_star = resolve_e_star((pair.pinion_material, pair.gear_material))
    z = axial_rows_mm(cycle, cells_along)
    dz = (cycle.pinion_v_range_mm[1] - cycle.pinion_v_range_mm[0]) / cells_along
    lg = contact_line_gaps(pair, cycle, z)
    poa = PlaneOfAction(pair, cycle.facing)
    beyond = beyond_line_edge_gaps(poa, cycle, z)
    half = across_extent_mm(pair, cycle, load, e_star, extent_factor)
    t0 = time.process_time()
    for widened in range(MAX_WIDENINGS + 1):
        nx = int(cells_across)
        dx = 2.0 * half / nx
        grid = TangentGrid.uniform(nx, cells_along, dx_mm=dx, dy_mm=dz / cb,
                                   x0_mm=-half + 0.5 * dx, y0_mm=z[0] / cb)
        x2 = (grid.x_mm ** 2)[None, :]
        lever = 0.5 * g.base_diameter_gear_mm * cb
        gear_torque = load * lever
        n_pairs, n_phase = lg.gap_mm.shape[:2]
        share = np.zeros((n_pairs, n_phase))
        line_load = np.zeros((n_pairs, n_phase, cells_along))
        line_p = np.zeros_like(line_load)
        lte, pmax = np.zeros(n_phase), np.zeros(n_phase)
        stiff, iters = np.zeros(n_phase), np.zeros(n_phase, dtype=int)
        turned = np.zeros(n_phase)
        fields = None
        ok, edge = True, False
        warm: dict[int, np.ndarray] = {}
        tip_rows = np.zeros((n_pairs, n_phase), bool)
        levers = np.zeros((n_pairs, n_phase))
        loaded_len = np.zeros((n_pairs, n_phase))
        end_loaded = np.zeros((n_pairs, n_phase), bool)
        end_peak = np.zeros(n_phase, bool)
        tally = BeyondLoads(n_pairs, n_phase, cells_along)
        theta_last = np.inf
        for k in range(n_phase):
            live = [j for j in range(n_pairs) if np.isfinite(lg.gap_mm[j, k]).any()]
            tipped = [j for j in range(n_pairs)
                      if j not in live and np.isfinite(cycle.tip.gap_mm[j, k])]
            g_line = {j: lg.gap_mm[j, k] for j in live}
            g_env = float(cycle.closing_gap_mm[k])
            gj = {j: max(float(np.nanmin(g_line[j])), g_env) for j in live}

            def line_block(j, rows):
                """Pair j's line block, with the edge rows ``rows`` beyond its ends."""
                on = np.isfinite(g_line[j])
                inv_r = np.where(on, cb * (1.0 / lg.pinion_roll_mm[j, k]
                                           + 1.0 / lg.gear_roll_mm[j, k]), 0.0)
                h = np.where(on[:, None], cb * np.where(on, g_line[j] - gj[j], 0.0)[:, None]
                             + 0.5 * inv_r[:, None] * x2, OFF_LINE_GAP_MM)
                u1, u2 = lg.pinion_roll_mm[j, k].copy(), lg.gear_roll_mm[j, k].copy()
                join_beyond(h, u1, u2, rows, beyond, j, k, grid.x_mm, lever,
                            cb * (gj[j] - g_env), g_env)
                factor = None if teeth is None else line_bending_factor(teeth, z, u1, u2, nx)
                return PairBlock(h, grid, lever, cb * (gj[j] - g_env), bending_factor=factor)
            # a tip edge may close where its closing turn is below twice the last phase's
            # rotation, and any other whose turn the solved rotation exceeds (then solved
            # again), so that those left out stand open (complementarity): a pair without a
            # line is a block along its edge, edge rows beyond a line join the line's block
            turn = {j: closing_turn_rad(cycle.tip.gap_mm[j, k], g_env,
                                        cycle.tip.rate_mm_per_rad[j, k]) for j in tipped}
            take = [j for j in tipped if turn[j] < 2.0 * theta_last]
            rows = {j: beyond_rows(beyond, j, k, g_env, 2.0 * theta_last) for j in live}
            lines = {j: line_block(j, rows[j]) for j in live}
            while True:
                where = np.zeros((n_pairs, n_phase), bool)
                where[take, k] = True
                tg = tip_edge_gaps(poa, cycle, z, where=where) if take else None
                blocks = [lines[j] for j in live] + [
                    edge_block(tg, j, k, grid, min(float(cycle.tip.gap_mm[j, k]),
                                                   float(np.nanmin(tg.gap_mm[j, k]))),
                               g_env, teeth, nx) for j in take]
                res = solve_mesh_lcp(blocks, gear_torque, e_star_mpa=e_star, tol=tol,
                                     warm_start=[warm.get(j) for j in live + take])
                late = [j for j in tipped if j not in take and turn[j] < res.rotation_rad]
                grown = {}
                for j in live:
                    more = beyond_rows(beyond, j, k, g_env, res.rotation_rad)
                    if ((more >= 0) & (rows[j] < 0)).any():
                        grown[j] = np.maximum(rows[j], more)
                if not late and not grown:
                    break
                take += late
                for j, r_j in grown.items():
                    rows[j], lines[j] = r_j, line_block(j, r_j)
            theta_last = res.rotation_rad
            tip_rows[take, k] = True
            keys = live + take
            ok &= res.converged
            iters[k] = res.iterations
            press = res.pressures_mpa(blocks)
            warm = dict(zip(keys, press))
            turned[k] = res.rotation_rad
            if k == fields_at:
                fields = np.zeros((n_pairs, cells_along, nx))
                for i, j in enumerate(keys):
                    fields[j] = press[i]
            for i, j in enumerate(keys):
                w = res.loads_n[i]
                edge |= bool(res.contact_masks[i][:, [0, -1]].any())
                beyond_n = 0.0
                for e in range(len(beyond)) if j in rows else ():
                    on_e = rows[j] == e
                    if on_e.any():
                        tally.add(j, k, e, on_e, float(w[on_e].sum()) / load, lever)
                        beyond_n += float(w[on_e].sum())
                share[j, k] = (res.pair_loads_n[i] - beyond_n) / load
                levers[j, k] = blocks[i].lever_mm
                line_load[j, k] = w.sum(axis=1) / dz
                line_p[j, k] = press[i].max(axis=1)
            pmax[k] = max(float(p.max()) for p in press)
            for i, j in enumerate(live):     # a line reaching its end loaded
                ends = np.nonzero(np.isfinite(lg.gap_mm[j, k]))[0][[0, -1]]
                hit = res.contact_masks[i].any(axis=1) & (rows[j] < 0)
                loaded_len[j, k] = hit.sum() * dz / cb
                end_loaded[j, k] = bool(hit[ends].any())
                end_peak[k] |= end_loaded[j, k] and float(press[i][ends].max()) >= pmax[k]
            end_peak[k] |= any(float(p.max()) >= pmax[k] for p in press[len(live):]) or any(
                float(p[rows[j] >= 0].max(initial=0.0)) >= pmax[k] for p, j in zip(press, live))
            rate = float(np.nanmean(lg.rate_mm_per_rad[live[0], k]))
            # the gear lags (TE0 < 0 on the cw facing): the load turns it further the same way
            lte[k] = (cycle.envelope_arcsec[k]
                      - math.copysign(res.rotation_rad, rate) * ARCSEC_PER_RAD)
            stiff[k] = load / (lever * res.rotation_rad * 1e3 * g.face_width_mm)
            if edge and widened < MAX_WIDENINGS:
                break                   # the strip is widened: the phases start again
        if not edge or widened == MAX_WIDENINGS:
            break
        # a loaded cell on the strip's border (an end-loaded line's peak): widen, solve again
        half = max(2.0 * half, across_extent_mm(pair, cycle, load, e_star, extent_factor, lg))
    return CylindricalLoadedTE(
        phi1_rad=cycle.phi1_rad, pair_offsets=cycle.pair_offsets, torque_nm=float(torque_nm),
        normal_load_n=load, te0_arcsec=cycle.envelope_arcsec, lte_arcsec=lte,
        load_share=share, max_pressure_mpa=pmax, z_mm=z, line_load_n_per_mm=line_load,
        line_pressure_mpa=line_p,
        stiffness_n_per_mm_um=stiff, face_width_mm=g.face_width_mm, grid_dx_mm=dx,
        grid_dy_mm=dz / cb, edge_touch=edge, iterations=iters, converged=bool(ok),
        solve_time_s=time.process_time() - t0, bending=teeth is not None,
        edge_label=np.where(tip_rows, cycle.tip.labels(), ""), lever_mm=levers,
        loaded_length_mm=loaded_len, line_end_loaded=end_loaded, peak_at_edge=end_peak,
        beyond_load_share=tally.share, beyond_lever_mm=tally.lever_mm, beyond_rows=tally.rows,
        rotation_rad=turned, fields_phase=fields_at, phase_pressure_mpa=fields)


def cylindrical_loaded_te_models(pair: CylindricalPair, torque_nm: float, *,
                                 bending: bool = True, facing: str = "cw", phases: int = 61,
                                 **options) -> tuple[CylindricalLoadedTE,
                                                     CylindricalLoadedTE | None]:
    """The loaded TE with ``bending`` and, when that is True, the rigid-tooth one beside
    it on the same unloaded cycle (what ``gearcontact lte`` writes side by side);
    ``options`` as :func:`cylindrical_loaded_te`. Returns ``(result, rigid or None)``."""
    normal_load_n(pair, torque_nm)                       # checked before the cycle
    cycle = cylindrical_mesh_cycle(pair, facing=facing, phases=phases)
    res = cylindrical_loaded_te(pair, torque_nm, cycle=cycle, bending=bending, **options)
    rigid = cylindrical_loaded_te(pair, torque_nm, cycle=cycle, bending=False,
                                  **options) if bending else None
    return res, rigid


@dataclass(frozen=True)
class HarrisMap:
    """Loaded-TE peak-to-peak vs torque for several tip-relief amounts.

    Attributes
    ----------
    torques_nm : ndarray (T,)
        Gear torques, N·m.
    tip_reliefs_um : ndarray (R,)
        Tip relief C_a applied to both members (at their own start diameters), µm.
    lte_pp_arcsec : ndarray (R, T)
        Loaded TE peak-to-peak, arcsec.
    te0_pp_arcsec : ndarray (R,)
        Unloaded TE peak-to-peak, arcsec.
    mean_stiffness_n_per_mm_um : ndarray (R, T)
        Mean secant mesh stiffness, N/(mm·µm).
    edge_touch : bool
        Some solve loaded the edge of its strip across a line.
    converged : bool
    bending : bool
        Tooth bending was in the LCPs (else rigid teeth).
    """

    torques_nm: np.ndarray
    tip_reliefs_um: np.ndarray
    lte_pp_arcsec: np.ndarray
    te0_pp_arcsec: np.ndarray
    mean_stiffness_n_per_mm_um: np.ndarray
    edge_touch: bool
    converged: bool
    bending: bool = False


def _with_tip_relief(pair: CylindricalPair, relief_um: float) -> CylindricalPair:
    """``pair`` with C_a = ``relief_um`` on both members, from their start diameters; a
    member without one (0) gets the short relief, from its highest point of single tooth
    contact (:meth:`~gearcontact.geometry.cylindrical.iso21771.InvoluteGeometry.single_contact_tip_diameter_mm`)."""
    mods = {}
    for member in ("pinion", "gear"):
        m = getattr(pair, f"modifications_{member}")
        start = m.tip_relief_start_diameter_mm
        if relief_um > 0.0 and start == 0.0:
            start = pair.geometry.single_contact_tip_diameter_mm(member)
        mods[f"modifications_{member}"] = replace(m, tip_relief_um=float(relief_um),
                                                  tip_relief_start_diameter_mm=start)
    return replace(pair, **mods)


def harris_map(pair: CylindricalPair, torques_nm, tip_reliefs_um, *, facing: str = "cw",
               phases: int = 61, **options) -> HarrisMap:
    """The Harris map: loaded TE p-p vs gear torque for each tip relief.

    Parameters
    ----------
    pair : CylindricalPair
        Its tip-relief start diameters are kept (a member without one: the short relief,
        from its highest point of single tooth contact); C_a is set on both members.
    torques_nm : array_like (T,)
        Gear torques, N·m (> 0).
    tip_reliefs_um : array_like (R,)
        C_a, µm (>= 0).
    facing, phases, **options
        As :func:`cylindrical_loaded_te`.
    """
    torques = np.asarray(torques_nm, dtype=float).ravel()
    reliefs = np.asarray(tip_reliefs_um, dtype=float).ravel()
    if torques.size == 0 or not (np.isfinite(torques).all() and (torques > 0).all()):
        raise InputRangeError("torques_nm", torques_nm, "a non-empty list of torques > 0 N·m")
    if reliefs.size == 0 or not (np.isfinite(reliefs).all() and (reliefs >= 0).all()):
        raise InputRangeError("tip_reliefs_um", tip_reliefs_um,
                              "a non-empty list of tip reliefs >= 0 um")
    pairs = [_with_tip_relief(pair, c) for c in reliefs]   # all checked before any solve
    pp = np.zeros((reliefs.size, torques.size))
    stiff = np.zeros_like(pp)
    te0 = np.zeros(reliefs.size)
    ok, edge, bent = True, False, False
    for r, p in enumerate(pairs):
        cycle = cylindrical_mesh_cycle(p, facing=facing, phases=phases)
        te0[r] = cycle.te0_pp_arcsec
        for t, torque in enumerate(torques):
            res = cylindrical_loaded_te(p, torque, cycle=cycle, **options)
            pp[r, t] = res.lte_pp_arcsec
            stiff[r, t] = res.mean_stiffness_n_per_mm_um
            ok &= res.converged
            edge |= res.edge_touch
            bent = res.bending
    return HarrisMap(torques_nm=torques, tip_reliefs_um=reliefs, lte_pp_arcsec=pp,
                     te0_pp_arcsec=te0, mean_stiffness_n_per_mm_um=stiff, edge_touch=edge,
                     converged=bool(ok), bending=bent)
