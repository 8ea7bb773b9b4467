"""``gearcontact export flanks``: the flanks of both members as STEP and as CMM grids.

:func:`pair_flanks` collects the surfaces a pair's analysis uses (the Surface contract
of :mod:`gearcontact.geometry.surface`), each member in its own axis frame (axis along
z, mm):

- bevel / hypoid pairs (:func:`gearcontact.geometry.flank.build_flanks`: formate gear
  and conjugate pinion with the pair's ease-off, or all four flanks cut from the pair's
  machine settings): the drive and coast flanks of gear and pinion over their active
  boxes. The gear keeps its body frame (axis z); the pinion body frame (axis x,
  docs/geometry.md sec. 1) is turned by the cyclic permutation
  ``(X, Y, Z) = (y, z, x)`` (a rotation: right-handed, lengths and normals kept).
  Below each flank of a member whose cutter is known (a formate gear, every member
  cut from machine settings) the root fillet its blade's edge round cuts
  (:func:`gearcontact.geometry.fillet.pair_fillets`), ``<member>_fillet_<side>``; the
  conjugate pinion has none (``flanks.json`` says why, as for a zero edge radius);
- cylindrical pairs (:mod:`gearcontact.geometry.cylindrical`): the cw and ccw
  involute-helicoid flanks of the tooth on +x and their trochoidal root fillets, in
  the member frame of :mod:`~gearcontact.geometry.cylindrical.flank` (already axis z).

:func:`export_flanks` writes per member a STEP file of bicubic B-spline faces
(:mod:`.flank_step`) and per flank a CSV grid in the Gleason / CMM style: ``rows``
lines along the face width (row 1 at the root, the last at the tip) by ``cols``
points along each (col 1 at the toe / v_min), uniform in the flank's own ``(u, v)``
over its active box (edges included), each with its point and unit normal (out of
the tooth material) in the member's axis frame. ``flanks.json`` records the frames,
the grids and the measured fit error of every STEP face. A bevel flank also gets
``<member>_<flank>_measuring.csv``: the same grid in a measuring machine's coordinates
(axial position L, radius R; :mod:`gearcontact.geometry.measuring_grid`), the nominal
a measured deviation file refers to (``design --target-flank``). File layout and how
to load them in CAD: docs/export.md.

A flank cut by a relieved blade (:class:`~gearcontact.geometry.kinked.KinkedFlank`)
leaves as one STEP face per smooth piece, split along the kink (:func:`step_faces`;
the faces share the kink edge's poles), and its CSV grids name each point's piece
(column ``piece``, ``#`` lines with the kink's ``u`` at every column); docs/export.md,
"Kinked flanks".
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..errors import BadInput
from ..geometry.kinked import KinkedFlank
from ..geometry.measuring_grid import AXIS_FRAMES, NOMINAL_COLUMNS, measuring_grid
from ..geometry.pair import CYLINDRICAL
from ..validation import InputRangeError
from .flank_step import FIT_TARGET_MM, fit_bspline_groups, fit_bsplines, write_step

__all__ = ["GRID_LIMITS", "ExportFlank", "FlankExport", "parse_grid", "pair_flanks",
           "pair_surfaces", "flank_grid", "grid_csv", "measuring_csv", "step_faces",
           "export_flanks"]

#: Smallest and largest row / column count of ``--grid``.
GRID_LIMITS = (2, 201)
#: Pinion body frame (axis x) -> axis frame (axis z): (X, Y, Z) = (y, z, x).
PINION_TO_AXIS = AXIS_FRAMES["pinion"]
MEMBERS = ("pinion", "gear")


def parse_grid(text: str, *, field: str = "--grid") -> tuple[int, int]:
    """``"5x9"`` -> ``(5, 9)``: rows (lines along the face width, spaced root -> tip) x
    columns (points on each line, toe -> heel).

    Raises
    ------
    InputRangeError
        Naming ``field`` unless both are integers in :data:`GRID_LIMITS`.
    """
    lo, hi = GRID_LIMITS
    allowed = f"ROWSxCOLS, each an integer in [{lo}, {hi}] (e.g. 5x9)"
    parts = str(text).lower().split("x")
    if len(parts) != 2 or not all(p.strip().isdigit() for p in parts):
        raise InputRangeError(field, text, allowed)
    rows, cols = (int(p) for p in parts)
    if not (lo <= rows <= hi and lo <= cols <= hi):
        raise InputRangeError(field, text, allowed)
    return rows, cols


@dataclass(frozen=True)
class ExportFlank:
    """One surface to export: ``surface`` (Surface contract, body frame) and the
    rotation ``to_axis`` from its body frame to the member's axis frame."""

    member: str
    flank: str          # drive, coast, cw, ccw, fillet_cw, fillet_ccw
    surface: object
    to_axis: np.ndarray

    @property
    def name(self) -> str:
        """``<member>_<flank>``: the file stem and the STEP product name."""
        return f"{self.member}_{self.flank}"

    def points(self, u, v) -> tuple[np.ndarray, np.ndarray]:
        """Points (mm) and unit normals (..., 3) at ``(u, v)`` in the axis frame."""
        s = self.surface.evaluate(u, v)
        return s.r @ self.to_axis.T, s.n @ self.to_axis.T

    @property
    def kinked(self) -> bool:
        """Cut by a relieved blade (:class:`~gearcontact.geometry.kinked.KinkedFlank`)."""
        return isinstance(self.surface, KinkedFlank)


def pair_flanks(pair, *, flanks=None) -> list[ExportFlank]:
    """The flanks (and fillets) of both members of ``pair`` (module docstring), pinion
    first.

    ``flanks`` : a :class:`~gearcontact.geometry.flank.FlankSet` already built for a
    bevel ``pair`` (default: built here, after the pair's typed machine settings are
    checked, :func:`~gearcontact.geometry.settings_check.checked_settings`).
    """
    return pair_surfaces(pair, flanks=flanks)[0]


def pair_surfaces(pair, *, flanks=None) -> tuple[list[ExportFlank], dict]:
    """:func:`pair_flanks` and ``{name: why}`` of the bevel root fillets not exported."""
    if getattr(pair, "kind", None) == CYLINDRICAL:
        from ..geometry.cylindrical.fillet import root_fillet
        from ..geometry.cylindrical.flank import FACINGS, involute_flank

        out = []
        for member in MEMBERS:
            out += [ExportFlank(member, f, involute_flank(pair, member, f), np.eye(3))
                    for f in FACINGS]
            out += [ExportFlank(member, f"fillet_{f}", root_fillet(pair, member, f),
                                np.eye(3)) for f in FACINGS]
        return out, {}
    from ..geometry.fillet import pair_fillets
    from ..geometry.flank import build_flanks
    from ..geometry.formate import SIDES
    from ..geometry.settings_check import checked_settings

    if flanks is None:      # built here: the pair's typed settings checked first
        checked_settings(pair, stacklevel=3)
        flanks = build_flanks(pair)
    fillets, missing = pair_fillets(pair, flanks)
    out = []
    for member in MEMBERS:
        out += [ExportFlank(member, side, flanks.flank(member, side), AXIS_FRAMES[member])
                for side in SIDES]
        out += [ExportFlank(member, f"fillet_{side}", fillets[member, side],
                            AXIS_FRAMES[member]) for side in SIDES if (member, side) in fillets]
    return out, {f"{m}_fillet_{s}": why for (m, s), why in missing.items()}


def flank_grid(flank: ExportFlank, rows: int, cols: int):
    """The CMM grid of ``flank``: ``(u (rows,), v (cols,), points, normals)``, the
    arrays (rows, cols, 3) in the axis frame; row i at ``u_i``, column j at ``v_j``."""
    u = np.linspace(*flank.surface.u_range, rows)
    v = np.linspace(*flank.surface.v_range, cols)
    r, n = flank.points(*np.meshgrid(u, v, indexing="ij"))
    return u, v, r, n


def _kink_lines(flank: ExportFlank, v) -> list[str]:
    """``#`` lines of a kinked flank's CSV: each kink's ``u_k`` at the columns' ``v``."""
    surf = flank.surface
    out = []
    for kink in surf.kinks:
        below, above = surf.names[kink.lower], surf.names[kink.lower + 1]
        u_k = ", ".join(repr(float(x)) for x in kink.u(v))
        out.append(f"# kink {kink.name}: the blade's relief kink, u = u_k(v_j) at cols "
                   f"1..{len(v)}: {u_k} (a point with u <= u_k lies on the '{below}' piece, "
                   f"u > u_k on the '{above}' piece; column piece names it, its normal is "
                   "that piece's)")
    return out


def grid_csv(flank: ExportFlank, rows: int, cols: int, *, pair_name: str) -> str:
    """The CSV text of ``flank``'s grid: ``#`` header lines (frame, grid, units), then
    ``row,col,u,v,x_mm,y_mm,z_mm,nx,ny,nz`` (every number with all its digits); a kinked
    flank (relieved blade) adds the column ``piece`` (``toprem``, ``main``,
    ``flankrem``: the smooth piece whose point and normal the line gives) and a ``#``
    line per kink with its ``u_k`` at every column."""
    u, v, r, n = flank_grid(flank, rows, cols)
    pieces = None
    if flank.kinked:
        U, V = np.meshgrid(u, v, indexing="ij")
        pieces = np.asarray(flank.surface.names)[flank.surface.piece_index(U, V)]
    top = "the flank's start" if flank.flank.startswith("fillet") else "tip"
    head = [
        f"# gearcontact export flanks: {pair_name}, {flank.name} "
        f"({type(flank.surface).__name__})",
        f"# grid {rows} x {cols}: row i = a line along the face width at u_i (row 1 "
        f"root .. row {rows} {top}), col j = the point at v_j on it (col 1 at v_min), "
        "uniform in (u, v), edges included",
        f"# u in [{float(u[0])!r}, {float(u[-1])!r}], v in [{float(v[0])!r}, {float(v[-1])!r}] "
        "(the flank's own parameters, docs/export.md)",
        "# frame: the member's axis frame, axis along +z, mm"
        + (" (pinion body frame turned: X = y, Y = z, Z = x)"
           if flank.to_axis is PINION_TO_AXIS else ""),
        "# normal: unit, out of the tooth material into the tooth space",
        *(_kink_lines(flank, v) if pieces is not None else []),
        "row,col,u,v,x_mm,y_mm,z_mm,nx,ny,nz" + (",piece" if pieces is not None else ""),
    ]
    lines = [",".join([str(i + 1), str(j + 1), repr(float(u[i])), repr(float(v[j]))]
                      + [repr(float(x)) for x in (*r[i, j], *n[i, j])]
                      + ([] if pieces is None else [str(pieces[i, j])]))
             for i in range(rows) for j in range(cols)]
    return "\n".join(head + lines) + "\n"


def measuring_csv(flank: ExportFlank, rows: int, cols: int, *, pair_name: str) -> str:
    """The CSV text of ``flank``'s nominal measuring grid in machine coordinates (axial
    position L, radius R; :mod:`gearcontact.geometry.measuring_grid`): ``#`` header
    lines, then :data:`~gearcontact.geometry.measuring_grid.NOMINAL_COLUMNS`."""
    g = measuring_grid(flank.surface, member=flank.member, flank=flank.flank, rows=rows,
                       cols=cols)
    head = [
        f"# gearcontact export flanks: {pair_name}, {flank.name} nominal measuring grid",
        f"# grid {rows} x {cols}: row 1 root .. row {rows} tip, col 1 toe .. col {cols} heel "
        "(uniform in the flank's (u, v) over its active box, edges included)",
        "# L_mm: axial position along the member axis (+Z) from the crossing point; R_mm: "
        "radius about the axis; x, y, z: the member's axis frame, mm (docs/export.md)",
        "# normal: unit, out of the tooth; a measured deviation_um is along it, "
        "+ = material added",
        *(_kink_lines(flank, np.linspace(*flank.surface.v_range, cols))
          if flank.kinked else []),
        ",".join(NOMINAL_COLUMNS),
    ]
    lines = [",".join([flank.member, flank.flank, str(int(g.row[k])), str(int(g.col[k]))]
                      + [repr(float(x)) for x in (g.L_mm[k], g.R_mm[k], *g.xyz_mm[k],
                                                   *g.normal[k])])
             for k in range(len(g.row))]
    return "\n".join(head + lines) + "\n"


#: Lengthwise samples on which a kink line is checked to run over the whole face width.
KINK_CHECK_SAMPLES = 201


def step_faces(flank: ExportFlank) -> tuple[list, dict]:
    """The B-spline faces of ``flank`` (:mod:`.flank_step`) and ``{face name: (piece,
    v_range)}`` (piece None for a smooth flank).

    A smooth flank is one face over its own ``(u, v)`` box. A kinked flank (a relieved
    blade, :class:`~gearcontact.geometry.kinked.KinkedFlank`) is one face per smooth
    piece, named ``<member>_<flank>`` (the main piece) and ``<member>_<flank>_<piece>``
    (``toprem``, ``flankrem``), root -> tip; face ``k`` at ``(t, v)``, ``t`` in [0, 1],
    is piece ``k`` at ``u = u_a(v) + t (u_b(v) - u_a(v))`` (``u_a``, ``u_b``: the kink
    lines below and above it, else the box's ends). Adjacent faces share their edge on
    the kink: the kink points ``u_k(v)`` of the lower piece, the same poles
    (:func:`~.flank_step.fit_bspline_groups`). A kink outside the box over the whole
    face width leaves one piece: one face over the flank's ``(u, v)``.

    A kink that crosses the box's root or tip line within the face width splits the
    flank along ``v`` at the crossings (:func:`_kink_cuts`): between two cuts each piece
    that is there is one face as above over that ``v`` interval (a piece that ends at a
    crossing collapses to the crossing point there: a three-sided face with one edge
    of zero length), and a piece on both sides of a cut is two faces sharing the cut's
    edge (the same poles); such faces are numbered toe -> heel, ``..._1``, ``..._2``.

    Raises
    ------
    BadInput
        Kinks crossing each other on the flank (a piece between them vanishes inside an
        interval between crossings), naming the blade's relief keys.
    """
    surf = flank.surface
    if not flank.kinked:
        fits = fit_bsplines([flank.name], [lambda U, V: flank.points(U, V)[0]],
                            surf.u_range, surf.v_range)
        return fits, {flank.name: (None, tuple(map(float, surf.v_range)))}
    cuts = [float(surf.v_range[0]), *_kink_cuts(surf), float(surf.v_range[1])]
    intervals = []
    for va, vb in zip(cuts[:-1], cuts[1:]):
        v = np.linspace(va, vb, KINK_CHECK_SAMPLES)[1:-1]
        widths = [np.subtract(*surf.piece_bounds(i, v)[::-1]) for i in range(len(surf.pieces))]
        present = [i for i, w in enumerate(widths) if (w > 0.0).all()]
        if (any((w > 0.0).any() and not (w > 0.0).all() for w in widths) or not present
                or present != list(range(present[0], present[-1] + 1))):
            raise BadInput(f"[blade.{flank.member}.{flank.flank}] {_relief_keys(surf)}: "
                           f"a piece of {flank.name} vanishes inside a part of the face "
                           "width away from a crossing of the root or tip line (kinks "
                           "crossing each other on the flank): not written as STEP faces")
        intervals.append(((va, vb), present))
    if len(intervals) == 1 and len(intervals[0][1]) == 1:
        fits = fit_bsplines([flank.name], [lambda U, V: flank.points(U, V)[0]],
                            surf.u_range, surf.v_range)
        return fits, {flank.name: (surf.names[intervals[0][1][0]],
                                   tuple(map(float, surf.v_range)))}

    def piece(i, field):
        def of(T, V):
            a, b = surf.piece_bounds(i, V)
            got = getattr(surf.evaluate_piece(i, a + T * (b - a), V, second=False), field)
            if field == "n":     # a collapsed edge (a piece ending at a crossing) has none
                got = np.where((b > a)[..., None], got, np.nan)
            return got @ flank.to_axis.T
        return of

    count = {i: sum(i in p for _, p in intervals) for i in range(len(surf.pieces))}
    seen: dict = {}
    groups, faces, joins = [], {}, []
    for g, (v_range, present) in enumerate(intervals):
        names = []
        for k, i in enumerate(present):
            base = flank.name if surf.names[i] == "main" else f"{flank.name}_{surf.names[i]}"
            if i in seen and seen[i][0] == g - 1:
                joins.append((seen[i], (g, k)))
            seen[i] = (g, k)
            number = sum(i in p for _, p in intervals[:g + 1])
            names.append(base if count[i] == 1 else f"{base}_{number}")
            faces[names[-1]] = (surf.names[i], tuple(map(float, v_range)))
        groups.append((names, [piece(i, "r") for i in present], v_range,
                       [piece(i, "n") for i in present]))
    fitted = fit_bspline_groups(groups, (0.0, 1.0), joins=joins)
    return [fit for group in fitted for fit in group], faces


def _relief_keys(surf) -> str:
    """The blade keys of a kinked flank's reliefs (``toprem_depth_mm, ...``)."""
    return ", ".join(f"{n}_depth_mm" for n in surf.names if n != "main")


def _kink_cuts(surf) -> list[float]:
    """The ``v`` inside the face width where a kink line crosses the box's root or tip
    line (its finite nodes next to an infinite one: the crossing nodes of
    :func:`~gearcontact.geometry.kinked.kinked_flank`), ascending."""
    v0, v1 = surf.v_range
    cuts = set()
    for kink in surf.kinks:
        finite = np.isfinite(kink.u_nodes)
        for j in np.flatnonzero(finite):
            ends = [finite[k] for k in (j - 1, j + 1) if 0 <= k < finite.size]
            if not all(ends) and v0 < kink.v_nodes[j] < v1:
                cuts.add(float(kink.v_nodes[j]))
    return sorted(cuts)


@dataclass(frozen=True)
class FlankExport:
    """What :func:`export_flanks` wrote: the STEP files, the CSV files, the summary
    ``flanks.json`` and the largest fit error of the STEP faces (mm)."""

    step_paths: tuple[Path, ...]
    csv_paths: tuple[Path, ...]
    summary_path: Path
    fit_error_mm: float


def _kink_range(surf, kink) -> tuple[float, float]:
    """Smallest and largest ``u_k`` of ``kink`` over the face width (clipped to the box)."""
    u = np.clip(kink.u(np.linspace(*surf.v_range, KINK_CHECK_SAMPLES)), *surf.u_range)
    return float(u.min()), float(u.max())


def _safe(text: str) -> str:
    """A name fit for a STEP string (no quotes, no backslashes)."""
    return "".join(c if c.isalnum() or c in " ._-" else "_" for c in str(text))


def export_flanks(pair, out_dir, *, pair_name: str, grid: tuple[int, int] = (5, 9),
                  flanks=None) -> FlankExport:
    """Write the flanks of ``pair`` into ``out_dir`` (module docstring): per member
    ``<member>_flanks.step``, per flank ``<member>_<flank>.csv`` (a bevel flank also
    ``<member>_<flank>_measuring.csv``), and ``flanks.json``.

    Parameters
    ----------
    pair : GearPair or CylindricalPair
    out_dir : path
    pair_name : str
        Name written into the headers.
    grid : (int, int)
        CSV rows (lines along the face width, root -> tip) x columns (points on each
        line), each in :data:`GRID_LIMITS`.
    flanks : FlankSet, optional
        Already built flanks of a bevel ``pair`` (a prepared pair's,
        :class:`~gearcontact.tca.synthesis.PreparedPair`); built here otherwise, after
        the pair's typed machine settings are checked against its blank
        (:func:`~gearcontact.geometry.settings_check.checked_settings`).

    Raises
    ------
    InputRangeError
        A bad grid, or typed machine settings with a gross slip (before any work).
    """
    rows, cols = parse_grid(f"{grid[0]}x{grid[1]}", field="grid")
    out = Path(out_dir)
    items, missing = pair_surfaces(pair, flanks=flanks)
    csvs, steps, summary = [], [], {"pair": pair_name, "grid": [rows, cols],
                                    "fit_target_um": FIT_TARGET_MM * 1e3, "flanks": {}}
    if missing:
        summary["fillets_not_exported"] = missing
    for f in items:
        path = out / f"{f.name}.csv"
        path.write_text(grid_csv(f, rows, cols, pair_name=pair_name))
        csvs.append(path)
        if getattr(pair, "kind", None) != CYLINDRICAL and not f.flank.startswith("fillet"):
            path = out / f"{f.name}_measuring.csv"
            path.write_text(measuring_csv(f, rows, cols, pair_name=pair_name))
            csvs.append(path)
    worst = 0.0
    for member in MEMBERS:
        fits = []
        for f in (f for f in items if f.member == member):
            faces, pieces = step_faces(f)
            fits += faces
            error = max(fit.fit_error_mm for fit in faces)
            worst = max(worst, error)
            summary["flanks"][f.name] = {
                "surface": type(f.surface).__name__,
                "u_range": [float(x) for x in f.surface.u_range],
                "v_range": [float(x) for x in f.surface.v_range],
                "to_axis_frame": f.to_axis.tolist(),
                "step_file": f"{member}_flanks.step", "csv_file": f"{f.name}.csv",
                "bspline_nodes": list(faces[0].nodes),
                "fit_error_um": round(error * 1e3, 6)}
            if f.kinked:
                summary["flanks"][f.name]["step_faces"] = {
                    fit.name: {"piece": pieces[fit.name][0],
                               "v_range": list(pieces[fit.name][1]),
                               "fit_error_um": round(fit.fit_error_mm * 1e3, 6)}
                    for fit in faces}
                summary["flanks"][f.name]["kinks"] = {
                    k.name: [float(x) for x in _kink_range(f.surface, k)]
                    for k in f.surface.kinks}
        steps.append(write_step(out / f"{member}_flanks.step", fits,
                                title=_safe(f"{pair_name} {member} flanks")))
    summary_path = out / "flanks.json"
    summary_path.write_text(json.dumps(summary, indent=2) + "\n")
    return FlankExport(tuple(steps), tuple(csvs), summary_path, worst)
