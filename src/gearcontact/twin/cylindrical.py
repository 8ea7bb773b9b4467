"""The twin of a cylindrical pair: its mesh table, the conventional loaded-TE table and
the model (docs/cylindrical.md sec. 10).

Mesh (:func:`cylindrical_mesh_table`): from the unloaded cycle and the preview's inputs
(:mod:`gearcontact.tca.cylindrical_stencil`) per phase and tooth pair: the lever
``r_b2 cos(beta_b)`` of the normal about the gear axis, the opening ``cos(beta_b)(g_j -
min g)``, the exact curvatures, the 7 x 7 stencil; the unloaded TE envelope along the
motion. The motion sign ``m`` is the sign of ``d g / d phi2`` (the gear lags by
``theta`` under load, so ``TE = TE0_env - m theta`` as the loaded TE of
:func:`gearcontact.ltca.cylindrical_lte.cylindrical_loaded_te` gives it).

Tip-edge rows (:func:`tip_rows`): where a pair closes first at a tip edge (the cycle's
``tip_first``: before its line enters, after it leaves, or before the line closes), its
row is an ``edge`` row (``contact_mode`` 1, ``edge_label`` the edge) with the touch's
own lever and opening, so it closes where the edge really touches; the law's inputs
(stencil, curvatures, line length, ease-off, bending) are those of the same tooth
pair's nearest line in the zone, as the bevel twin's edge rows take their nearest
surface contact's (:mod:`.mesh`). On a helical pair only where the pair has no line in
the zone: its own tip edge beyond a line in the zone closes in the line's edge slices.

Edge slices beyond a helical line (:func:`~gearcontact.ltca.cylindrical_edges.
beyond_slices`, the table's ``beyond_gap_mm``): the tip edge past either end of the
line, its gap at the line's lever over the line's least, on slices that the line law's
slice law adds to the line's loaded length and interference (:mod:`.line_law`), the
loaded TE's edge rows beyond a line (docs/cylindrical.md sec. 7, 10).

Contact law, per backend (``--backend``, as the bevel twin's):

* ``reference`` (fp64), ``golden`` (the bit-exact fixed point), ``rtl`` (the golden
  run replayed on the ChainLineCore, :func:`.cosim.replay_on_rtl`) and ``soc`` (the
  golden run replayed through the host driver on the line_core SoC,
  :func:`.cosim.replay_on_soc`): the preview's *line
  chain* per loaded pair and step (stage C on the pair's 7 x 7 stencil into the line
  core with the pair's contact-line length, docs/cylindrical.md sec. 8), whose answer
  gives the pair's law -- Hertz ``d = kappa W^(2/3)`` where the ellipse fits, the
  approach of the finite line contact on the half-spaces where the line core answers
  in line mode (:mod:`.line_law`);
* ``table``: the loaded TE (LCP; rigid teeth, or with tooth bending as the twin's
  ``bending`` option) over the phase at a torque ladder
  (:func:`cylindrical_torque_table`, the conventional twin's input).

The ease-off along each pair's line (:func:`~gearcontact.tca.cylindrical_stencil.
contact_line_slices`, its normal gap over the line's least at 16 slice centres; mesh
table ``line_gap_mm``) gives the line law its loaded length (:mod:`.line_law`): a
crowned, relieved or misaligned line carries load only where its gap lies below the
approach.

Tooth bending (``bending``): the ``table`` backend's loaded TE carries it in its LCP;
the preview backends run the coupled slice law (:mod:`gearcontact.ltca.
coupled_slice_law`, ``w = K (d - h - G f)``, the preview's law with bending) with the
Gram matrix ``G`` of the pinion and gear tooth shells at the line's slices
(:func:`line_bending_gram`, the loaded TE's factor rows, :func:`gearcontact.ltca.
cylindrical_bending.line_bending_factor`), once per pair and step at its approach, and
hold its secant ``d = d_c(W) + c_b W`` over the step (:mod:`.line_law`); the mesh
table's ``bending_mm_per_n`` reports the uniform-load compliance.
"""

from __future__ import annotations

import math

import numpy as np

from ..geometry.cylindrical.pair import CylindricalPair
from ..ltca.coupled_slice_law import line_bending_compliance
from ..ltca.cylindrical_bending import cylindrical_bending, line_bending_factor
from ..ltca.cylindrical_edges import BeyondSlices, beyond_slices, edge_row_slices
from ..ltca.cylindrical_lte import check_cells, cylindrical_loaded_te
from ..ltca.edge_section import edge_stiffness_factor
from ..ltca.slice_law import line_easeoff_mm
from ..ltca.tooth_bending import ToothBending
from ..materials import effective_modulus_mpa
from ..tca.cylindrical_cycle import (FACING_OF_SIDE, CylindricalMeshCycle, LineGaps,
                                     contact_line_gaps, cylindrical_mesh_cycle)
from ..tca.parallel_axes import parallel_kinematics
from ..tca.cylindrical_stencil import LINE_SLICES, CylindricalStencils, cylindrical_stencils
from ..tca.types import ARCSEC_PER_RAD
from ..errors import CheckFailed
from ..validation import InputRangeError, check_positive
from .layout import LINE_SOURCE
from .ltca_table import DEFAULT_LADDER, TorqueTable
from .mesh import MeshTable
from .model import TwinModel, build_model
from .params import DrivetrainParams, default_drivetrain

__all__ = ["CYLINDRICAL_BACKENDS", "beyond_stiffness", "cylindrical_mesh_table", "cylindrical_torque_table",
           "cylindrical_model", "cylindrical_sweep_models", "line_bending_gram",
           "motion_sign", "tip_rows"]

#: The twin backends a cylindrical pair runs (module docstring).
CYLINDRICAL_BACKENDS = ("reference", "golden", "rtl", "soc", "table")


def motion_sign(pair: CylindricalPair, cycle: CylindricalMeshCycle) -> int:
    """``m``: the sign of ``d g / d phi2`` on the cycle's lines (+1 on the cw facing)."""
    z0, z1 = cycle.pinion_v_range_mm
    rate = contact_line_gaps(pair, cycle, [0.5 * (z0 + z1)]).rate_mm_per_rad
    return 1 if float(np.nanmean(rate)) > 0.0 else -1


def _order(m: int, n: int) -> np.ndarray:
    return np.arange(n) if m == 1 else np.arange(n)[::-1]


def line_bending_gram(bending: ToothBending, slices: LineGaps,
                      beyond: BeyondSlices | None = None) -> np.ndarray:
    """Bending Gram matrices ``G = F F^T`` (P, K, m, m), mm/N, of the pinion and gear
    shells at each pair's line slices (:func:`~gearcontact.tca.cylindrical_stencil.
    contact_line_slices`; the shells' factor rows of the loaded TE,
    :func:`~gearcontact.ltca.cylindrical_bending.line_bending_factor`), then at the
    ``2 nb`` slices of the tip edge beyond its ends (``beyond``, at the edge touch's
    roll lengths, as the loaded TE's rows beyond a line; ``m = n + 2 nb``): the
    deflection at slice a under a unit load at slice b; zeros where the pair has no
    line or no edge point."""
    n_p, n_k, n = slices.gap_mm.shape
    nb2 = 0 if beyond is None else beyond.gap_mm.shape[-2] * beyond.gap_mm.shape[-1]
    out = np.zeros((n_p, n_k, n + nb2, n + nb2))
    for j in range(n_p):
        for k in range(n_k):
            on = np.isfinite(slices.pinion_roll_mm[j, k]) & np.isfinite(slices.gear_roll_mm[j, k])
            if on.all():
                out[j, k, :n, :n] = line_bending_compliance(bending, slices, j, k)
                if nb2 and np.isfinite(beyond.u1_mm[j, k]).any():
                    # the edge's blocks on one factor of line and edge points (the
                    # compressed factor's rank is the call's); the line's block as above
                    fc = line_bending_factor(
                        bending, np.concatenate([slices.z_mm[j, k], beyond.z_mm[j, k].ravel()]),
                        np.concatenate([slices.pinion_roll_mm[j, k], beyond.u1_mm[j, k].ravel()]),
                        np.concatenate([slices.gear_roll_mm[j, k], beyond.u2_mm[j, k].ravel()]),
                        1)[:, 0].astype(float)
                    out[j, k, n:] = fc[n:] @ fc.T
                    out[j, k, :n, n:] = out[j, k, n:, :n].T
    return out


def _edge_row_gram(bending: ToothBending, gram, rows, line_z_mm, beyond_z_mm, u1_mm,
                   u2_mm) -> np.ndarray:
    """``gram`` (P, K, m, m) with each edge row's (``rows``) own: the shells' Gram at
    the row's slices (``line_z_mm`` (P, K, n), ``beyond_z_mm`` (P, K, 2, nb): its
    nearest line's) with the roll lengths of its tip touch ``u1_mm``, ``u2_mm`` (P, K)
    at every slice, as the loaded TE's edge block takes them."""
    out = np.array(gram)
    for j, k in zip(*np.nonzero(rows)):
        z = np.concatenate([line_z_mm[j, k], beyond_z_mm[j, k].ravel()])
        f = line_bending_factor(bending, z, np.full(z.shape, u1_mm[j, k]),
                                np.full(z.shape, u2_mm[j, k]), 1)[:, 0].astype(float)
        out[j, k] = f @ f.T
    return out


def beyond_stiffness(beyond: BeyondSlices, stencils: CylindricalStencils, load_n: float,
                      e_prime_mpa: float) -> tuple[float, float, float]:
    """``(g / (g + Delta), Delta, chi)`` of the edge slices beyond the lines at the normal
    load ``load_n`` (N; :func:`~gearcontact.ltca.edge_section.edge_stiffness_factor`,
    docs/cylindrical.md sec. 10): the line's ``g`` at the mean load per length over the
    lines in the zone (``load_n`` over their mean summed length), their mean length and
    the median radius across them (``1 / (2 B)``, B the larger of the exact curvatures'
    half sums); the edge's section at the median slope and radius across of the edges'
    first touches beyond the lines. (1, 0, 0) where no edge touches beyond a line."""
    slope = beyond.slope[np.isfinite(beyond.slope)]
    inv_r = beyond.inv_radius_per_mm[np.isfinite(beyond.inv_radius_per_mm)]
    valid = stencils.valid
    if slope.size == 0 or not valid.any():
        return 1.0, 0.0, 0.0
    length = np.where(valid, stencils.line_length_mm, 0.0)
    across = np.maximum(stencils.A_minus_per_mm, stencils.B_minus_per_mm)[valid]
    return edge_stiffness_factor(
        slope=float(np.median(slope)), edge_radius_mm=1.0 / float(np.median(inv_r)),
        line_load_n_per_mm=load_n / float(length.sum(axis=0).mean()),
        line_length_mm=float(stencils.line_length_mm[valid].mean()),
        line_radius_mm=0.5 / float(np.median(across)), e_prime_mpa=e_prime_mpa)


def tip_rows(pair: CylindricalPair, cycle: CylindricalMeshCycle, valid: np.ndarray):
    """The edge rows of a cylindrical mesh table (module docstring, "Tip-edge rows"):
    ``(rows, opening_mm, lever_mm, nearest)`` per pair and phase of ``cycle``: where the
    pair closes first at a tip edge (``cycle.tip_first``), the touch's lever
    ``|(a2 x X) . n|`` about the gear axis and the opening ``lever theta_j`` with
    ``theta_j = m (TE0_env - TE0_j)`` its closing turn behind the envelope; ``nearest``
    (P, K, 2) the row ``(j', k')`` of the pair's nearest line in the zone (``valid``),
    the same tooth pair by its phase ``phi1 + j pitch``."""
    rows = np.asarray(cycle.tip_first, bool)
    m = motion_sign(pair, cycle)
    theta = m * (cycle.envelope_arcsec[None, :] - cycle.te0_pairs_arcsec) / ARCSEC_PER_RAD
    axis = parallel_kinematics(pair).gear_axis
    lever = np.abs(np.einsum("...i,...i->...", np.cross(axis, cycle.tip.point_mm),
                             cycle.tip.normal))
    opening = np.where(rows, lever * np.maximum(np.where(rows, theta, 0.0), 0.0), 0.0)
    pitch = 2.0 * math.pi / cycle.pinion_teeth
    phase = cycle.phi1_rad[None, :] + pitch * np.asarray(cycle.pair_offsets, float)[:, None]
    jl, kl = np.nonzero(valid)
    nearest = np.zeros(rows.shape + (2,), int)
    for j, k in zip(*np.nonzero(rows)):
        i = int(np.argmin(np.abs(phase[jl, kl] - phase[j, k])))
        nearest[j, k] = jl[i], kl[i]
    return rows, opening, np.where(rows, lever, 0.0), nearest


def cylindrical_mesh_table(pair: CylindricalPair, cycle: CylindricalMeshCycle,
                           stencils: CylindricalStencils | None = None, *,
                           side: str = "drive", bending: ToothBending | None = None,
                           slices: int = LINE_SLICES, torque_nm: float | None = None
                           ) -> MeshTable:
    """The twin's :class:`~.mesh.MeshTable` of a cylindrical pair (module docstring):
    the ease-off along each pair's line at ``slices`` slices
    (:func:`~gearcontact.tca.cylindrical_stencil.contact_line_slices`, its normal gap
    over the line's least); ``bending``: the tooth shells
    (:func:`~gearcontact.ltca.cylindrical_bending.cylindrical_bending` on the cycle's
    facing), whose :func:`line_bending_gram` at the slices goes into
    ``line_bending_gram_mm_per_n`` and its uniform-load compliance ``sum(G) / n^2`` into
    ``bending_mm_per_n`` (reported); None: rigid teeth. ``torque_nm`` (gear, N·m): the
    edge slices' own law at that load (:func:`beyond_stiffness`); None: the line's."""
    st = stencils if stencils is not None else cylindrical_stencils(pair, cycle)
    m = motion_sign(pair, cycle)
    order = _order(m, len(cycle.phi1_rad))
    ease, sl = line_easeoff_mm(pair, cycle, st.valid, slices=slices)
    beyond = beyond_slices(pair, cycle, st.valid, st.opening_mm, float(st.lever_mm))
    rows, tip_open, tip_lever, near = tip_rows(pair, cycle, st.valid)
    nj, nk = near[..., 0], near[..., 1]
    beyond_gap, own_rows = None, None
    if beyond is not None:      # a helical line's own tip edge closes in its edge slices
        rows &= ~st.valid
        beyond_gap = beyond.gap_mm
        if rows.any():          # an edge row: its own edge on its nearest line's slices
            own_line, own_beyond, u1, u2 = edge_row_slices(pair, cycle, rows, near, sl.z_mm,
                                                           beyond)
            ease = np.where(rows[..., None], own_line, ease)
            beyond_gap = np.where(rows[..., None, None], own_beyond, beyond_gap)
            own_rows = (u1, u2)
    gram, cb = None, np.zeros(st.valid.shape)
    if bending is not None:
        gram = np.where(st.valid[..., None, None], line_bending_gram(bending, sl, beyond), 0.0)
        if own_rows is not None:
            gram = _edge_row_gram(bending, gram, rows, sl.z_mm[nj, nk], beyond.z_mm[nj, nk],
                                  *own_rows)
        n = sl.gap_mm.shape[-1]
        # the line's block as a contiguous array: its sum's rounding the one without
        # edge slices (the coupled law's start on a fresh preview, .line_law)
        cb = np.ascontiguousarray(gram[..., :n, :n]).sum(axis=(2, 3)) / n ** 2
    phi1 = np.asarray(cycle.phi1_rad, float)[order]
    env = np.asarray(cycle.envelope_arcsec, float)[order]
    k0 = len(order) // 2

    def law(a, own=False):
        # an edge row takes its pair's nearest line's law inputs (``own``: its own)
        if own:
            return a[:, order]
        r = rows.reshape(rows.shape + (1,) * (a.ndim - 2))
        return np.where(r, a[nj, nk], a)[:, order]

    length = np.where(st.valid, st.line_length_mm, 0.0)
    e_prime = float(effective_modulus_mpa(pair.pinion_material, pair.gear_material))
    stiff = 1.0
    if beyond is not None and torque_nm is not None:
        stiff = beyond_stiffness(beyond, st, 1e3 * torque_nm / float(st.lever_mm), e_prime)[0]
    return MeshTable(
        psi_rad=m * (phi1 - phi1[0]), eps_rad=m * env / ARCSEC_PER_RAD,
        lever_mm=np.where(rows, tip_lever, np.where(st.valid, st.lever_mm, 0.0))[:, order],
        opening_mm=np.where(rows, tip_open, st.opening_mm)[:, order],
        A_minus_per_mm=law(st.A_minus_per_mm), B_minus_per_mm=law(st.B_minus_per_mm),
        valid=(st.valid | rows)[:, order],
        motion_sign=m, ratio=float(pair.ratio), pinion_teeth=int(pair.pinion_teeth),
        reference_lever_mm=float(st.lever_mm), reference_index=int(k0),
        e_prime_mpa=e_prime, phi1_rad=phi1, te0_arcsec=env, gear_datum_rad=0.0, side=side,
        bending_mm_per_n=law(cb, own=own_rows is not None), stencil_gaps_mm=law(st.gaps_mm),
        line_length_mm=law(length), contact_mode=rows.astype(np.int8)[:, order],
        edge_label=np.where(rows, cycle.tip.labels(), "")[:, order],
        line_gap_mm=law(ease, own=beyond is not None),
        line_bending_gram_mm_per_n=None if gram is None else law(gram,
                                                                  own=own_rows is not None),
        # an edge row takes its nearest line's edge slices with the rest of its law (the
        # kernel interpolates between rows: a line row's edge slices would open within
        # the interval to an edge row without them, its edge load with them)
        beyond_gap_mm=None if beyond_gap is None else law(beyond_gap, own=True),
        beyond_width_mm=None if beyond is None else beyond.width_mm, beyond_stiffness=stiff)


def cylindrical_torque_table(pair: CylindricalPair, cycle: CylindricalMeshCycle,
                             mesh: MeshTable, torque_nm: float, *, ladder=DEFAULT_LADDER,
                             cells_along: int = 40, bending: bool = False) -> TorqueTable:
    """The loaded TE (LCP; rigid teeth, or with tooth bending when ``bending``) at
    ``ladder x torque_nm``, as the mesh rotation ``theta = |TE - TE0| `` (rad) per phase
    in the motion order of ``mesh``."""
    t = check_positive("torque_nm (N·m)", torque_nm)
    lad = np.asarray(ladder, float)
    if lad.ndim != 1 or lad.size < 2 or not (np.all(lad > 0) and np.all(np.diff(lad) > 0)):
        raise InputRangeError("table ladder", ladder, "at least 2 increasing fractions > 0")
    order = _order(mesh.motion_sign, len(mesh.psi_rad))
    theta = np.zeros((len(order), lad.size))
    load = np.zeros_like(theta)
    for i, f in enumerate(lad):
        res = cylindrical_loaded_te(pair, f * t, cycle=cycle, cells_along=cells_along,
                                    bending=bending)
        if not res.converged:
            raise CheckFailed(f"loaded TE at {f * t:g} N·m did not converge")
        # TE = TE0 - m theta (module docstring)
        theta[:, i] = (mesh.motion_sign * (res.te0_arcsec - res.lte_arcsec)
                       / ARCSEC_PER_RAD)[order]
        load[:, i] = res.normal_load_n
    return TorqueTable(lad * t, theta, load, "lcp")


def cylindrical_model(pair: CylindricalPair, *, torque_nm: float, backend: str = "reference",
                      drivetrain: DrivetrainParams | None = None, side: str = "drive",
                      phases: int = 61, table_cells: int = 40,
                      bending: bool = False) -> TwinModel:
    """Cycle and mesh table of ``pair`` (and for the ``table`` backend the loaded-TE
    table), then :func:`~.model.build_model` (module docstring; the reverse flank is the
    loaded law mirrored about the backlash). The preview backends run the line chain
    (curvature source :data:`~.layout.LINE_SOURCE`). ``bending``: the shell bending of
    both teeth (rigid teeth by default, as the bevel twin's ``bending``): in the
    loaded-TE table's LCP (``table``, ``table_cells`` rows along the face) and, for
    every backend, each pair's :func:`line_bending_gram` at its line's slices in the
    mesh table (the preview backends' coupled slice law; the table backend only reports
    the uniform-load compliance).

    Raises
    ------
    InputRangeError
        A backend other than :data:`CYLINDRICAL_BACKENDS`, ``table_cells`` not an
        integer >= 4 for the table backend (before any work), a bad side.
    """
    t = check_positive("torque_nm (N·m)", torque_nm)
    if backend not in CYLINDRICAL_BACKENDS:
        raise InputRangeError("backend", backend, f"one of {list(CYLINDRICAL_BACKENDS)} for a "
                                                  "cylindrical pair (docs/cylindrical.md "
                                                  "sec. 10)")
    if backend == "table":
        check_cells("table_cells", table_cells)
    facing = FACING_OF_SIDE.get(side)
    if facing is None:
        raise InputRangeError("side", side, "'drive' or 'coast'")
    cycle = cylindrical_mesh_cycle(pair, facing=facing, phases=phases)
    teeth = cylindrical_bending(pair, facing=facing) if bending else None
    mesh = cylindrical_mesh_table(pair, cycle, side=side, bending=teeth, torque_nm=t)
    table = None
    if backend == "table":
        table = cylindrical_torque_table(pair, cycle, mesh, t, cells_along=table_cells,
                                         bending=bending)
    return build_model(mesh, drivetrain or default_drivetrain(pair), t, backend=backend,
                       table=table, curvatures="exact" if table is not None else LINE_SOURCE,
                       reverse_note="loaded side's law mirrored about backlash_mm (the "
                                    "other facing's own table is not built for a "
                                    "cylindrical pair)")


def cylindrical_sweep_models(pair: CylindricalPair, *, torque_nm: float, backend: str,
                             drivetrain: DrivetrainParams | None = None, side: str = "drive",
                             phases: int = 61, table_cells: int = 40,
                             bending: bool = False) -> dict:
    """The models of a speed sweep (:func:`.sweep.speed_sweep`): the preview twin of
    ``backend`` (``reference`` or ``golden``) beside the table twin, on one cycle and
    mesh table (rigid teeth, or both with tooth bending: ``bending`` as
    :func:`cylindrical_model`).

    Raises
    ------
    InputRangeError
        Another backend (before any work); as :func:`cylindrical_model`.
    """
    if backend not in ("reference", "golden"):
        raise InputRangeError("backend", backend, "reference or golden for a speed sweep "
                                                  "(the table twin runs beside it)")
    table = cylindrical_model(pair, torque_nm=torque_nm, backend="table", drivetrain=drivetrain,
                              side=side, phases=phases, table_cells=table_cells,
                              bending=bending)
    preview = build_model(table.mesh, table.drivetrain, table.torque_nm, backend=backend,
                          curvatures=LINE_SOURCE, reverse_note=table.reverse_note)
    return {backend: preview, "table": table}
