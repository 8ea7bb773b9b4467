"""Which gear a pair's flanks start from: the formate gear, or a generated gear when the
formate gear undercuts its conjugate pinion.

A pair without machine settings gets its gear flanks from the blank and the cutter
(docs/geometry.md, docs/machine_settings.md sec. 4) and its pinion flanks as their
exact conjugates (:mod:`.conjugate`) with the pair's ease-off. Two gears are possible:

- ``"formate"``: each flank a copy of the straight blade (:mod:`.formate`); exact,
  compiled in TCA. At low ratios the formate profile is far from the profile a rolled
  gear has, and its tip zone undercuts the conjugate pinion (the envelope's limit line,
  :func:`~.conjugate.pinion_active_box`): 20/20 and 20/30 with ISO 23509 F.2's data lose
  77 % and more of the gear addendum.
- ``"generated"``: each flank the envelope of the same blade rolled on the crown gear
  of the gear's pitch plane (:func:`~.basic_settings.generated_gear_setups`: the formate
  settings with ratio of roll ``1/sin(delta2)``, no modified roll; Litvin & Fuentes
  2004, sec. 20.2-20.3), a :class:`~.sheet.GearSheet`. The pitch cone rolls on the
  cradle plane, so on the pitch cone the flank is the cutter circle rolled onto it:
  pressure angle = blade angle, spiral angle that of the cutter circle
  (tests/geometry/test_gear_generation.py). Its conjugate pinion
  (:class:`SheetGenerator` feeds the sheet to the meshing solver of :mod:`.conjugate`)
  is, for a spiral bevel pair, the pinion the same crown gear generates: the classic
  generated pair (F.3's data, u 1-2.5: undercut left only at z1 = 5, E = 0;
  docs/geometry.md sec. 7.6).

Rule (:func:`gear_generation`, deterministic): the formate gear unless the active-box
step of its conjugate pinion (:func:`~.conjugate.pinion_active_box`, no node grid)
refuses either flank with an :class:`~.conjugate.UndercutError`; then the generated
gear. Every pair that generated before keeps its formate gear bit for bit.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from .basic_settings import generated_gear_setups
from .conjugate import NODE_MARGIN_MM, UndercutError, pinion_active_box
from .cutter import BladeEval
from .formate import SIDES, FlankBoundary, gear_flanks
from .generated import generated_gear_flank
from .sheet import GearSheet

__all__ = ["GEAR_GENERATIONS", "PairGeneration", "SheetGenerator", "gear_generation",
           "generated_gear_sheets", "generating_sheet", "generation_of", "generation_text",
           "pair_gear_flanks", "pair_generation"]

#: The two gear generations of a pair without machine settings (module docstring).
GEAR_GENERATIONS = ("formate", "generated")


@dataclass(frozen=True, eq=False)
class SheetGenerator:
    """A generated gear flank (:class:`~.sheet.GearSheet`) in the role of the blade cone
    of :class:`~.conjugate.MeshingSolver`: ``h = h_f2 - u`` (depth below the pitch cone,
    as a formate flank's) and ``theta = v / R2`` (rad, ``R2`` the mean cone distance, so
    that the solver's step limits keep their scale). The normal's derivatives follow
    from the sheet's second derivatives (Weingarten equations, do Carmo 1976,
    sec. 3-3)."""

    sheet: GearSheet

    @property
    def side(self) -> str:
        return self.sheet.side

    @property
    def boundary(self) -> FlankBoundary:
        return self.sheet.boundary

    @property
    def blade(self) -> "SheetGenerator":
        return self

    def blade_parameters(self, u, v):
        """(h, theta) of the sheet point (u, v) (:meth:`~.sheet.GearSheet.blade_parameters`)."""
        return self.sheet.blade_parameters(u, v)

    def surface_parameters(self, h_mm, theta_rad):
        """(u, v) of the solver's (h, theta), mm."""
        return self.sheet.surface_parameters(h_mm, theta_rad)

    def evaluate(self, h_mm, theta_rad) -> BladeEval:
        """Point, derivatives w.r.t. (h, theta) and unit normal (broadcast arrays)."""
        s = self.sheet.evaluate(*self.surface_parameters(np.asarray(h_mm, dtype=float),
                                                         np.asarray(theta_rad, dtype=float)),
                                second=True)
        g11, g12, g22 = (np.einsum("...i,...i->...", a, b)
                         for a, b in ((s.r_u, s.r_u), (s.r_u, s.r_v), (s.r_v, s.r_v)))
        l11, l12, l22 = (np.einsum("...i,...i->...", a, s.n) for a in (s.r_uu, s.r_uv, s.r_vv))
        det = g11 * g22 - g12 * g12
        col = lambda a: a[..., None]  # noqa: E731
        n_u = col((l12 * g12 - l11 * g22) / det) * s.r_u + col((l11 * g12 - l12 * g11) / det) * s.r_v
        n_v = col((l22 * g12 - l12 * g22) / det) * s.r_u + col((l12 * g12 - l22 * g11) / det) * s.r_v
        k = float(self.sheet.cone.mean_cone_distance_mm)   # dv/dtheta
        return BladeEval(x=s.r, x_h=-s.r_u, x_t=k * s.r_v, x_tt=k * k * s.r_vv,
                         x_ht=-k * s.r_uv, n=s.n, n_t=k * n_v,
                         rho=np.linalg.norm(s.r[..., :2], axis=-1), n_h=-n_u)


#: Profile node margin of a generating gear sheet beyond its active box, mm (twice the
#: pinion's :data:`~.conjugate.NODE_MARGIN_MM`).
GENERATOR_MARGIN_MM = 2.0 * NODE_MARGIN_MM[0]
#: Lengthwise extension of a generating gear sheet beyond each end of the face, as a
#: fraction of the gear face width (the 20/20 pair with F.2's data needs 0.3 at the heel,
#: 5/6 with beta1 46 deg 0.64).
GENERATOR_EXTENSION = 1.0
_EXTENSION_STEPS = 16
#: The envelope's extension ends where |det J| of the gear's node equations falls below
#: this fraction of the mean node's (the generated gear's own limit line, blade tip).
_EXTENSION_CUSP = 0.1


#: Shares of the traced lengthwise extension tried in turn when the node grid's
#: continuation loses the envelope inside it (the trace follows three node rows only;
#: measured on 9/9, E = 0: the gear's toe tip corner): the last, 0, keeps the default
#: node margins and continues every row by its Taylor polynomial.
_EXTENSION_TRIALS = (1.0, 0.5, 0.0)


def generator_node_box(solver, box: FlankBoundary, mean, *, share: float = 1.0
                       ) -> FlankBoundary:
    """The enveloped node box of a generating gear sheet: ``box`` widened by
    ``GENERATOR_MARGIN_MM`` in profile and, towards toe and heel, by ``share`` of the
    length over which the gear's envelope stays regular on its lowest, mean and highest
    node rows (up to ``GENERATOR_EXTENSION`` of the face width; see
    :func:`generated_gear_sheets`)."""
    margin = GENERATOR_MARGIN_MM if share > 0.0 else NODE_MARGIN_MM[0]
    u_lo, u_hi = box.u_root - margin, box.u_tip + margin
    rows = np.array([u_lo, float(solver.cone.dedendum_mm), u_hi])
    det_min = _EXTENSION_CUSP * abs(float(mean.jacobian_det))
    ends = []
    for end in (box.v_toe, box.v_heel):
        q, last = _rows_at_mean(solver, rows, mean), 0.0
        far = end + np.sign(end) * GENERATOR_EXTENSION * (box.v_heel - box.v_toe)
        for v in np.linspace(0.0, far, _EXTENSION_STEPS + 1)[1:]:
            s = solver.solve(rows, np.full_like(rows, v), q, strict=False)
            if not np.all(s.converged & (np.abs(s.jacobian_det) >= det_min)):
                break
            q, last = s.q, v
        ends.append(last)
    toe, heel = box.v_toe - NODE_MARGIN_MM[1], box.v_heel + NODE_MARGIN_MM[1]
    return FlankBoundary(u_root=u_lo, u_tip=u_hi,
                         v_toe=float(min(toe + share * (ends[0] - toe), toe)),
                         v_heel=float(max(heel + share * (ends[1] - heel), heel)))


def _rows_at_mean(solver, rows: np.ndarray, mean) -> np.ndarray:
    """Node solutions on the mean section at the heights ``rows``, continued from the
    mean node in small steps along the profile."""
    out = []
    for u_end in rows:
        q = mean.q
        for u in np.linspace(float(solver.cone.dedendum_mm), u_end, 9)[1:]:
            q = solver.solve(u, 0.0, q).q
        out.append(q)
    return np.stack(out)


def _extended(sheet: GearSheet, v_toe: float, v_heel: float) -> GearSheet:
    """``sheet`` with node columns appended, at its node spacing, out to ``v_toe`` and
    ``v_heel``: each row continued by the second-order Taylor polynomial in v of the
    sheet at its end column (C2 at the junction)."""
    vs = sheet.v_nodes
    dv = float(vs[1] - vs[0])
    lo = vs[0] - dv * np.arange(int(np.ceil((vs[0] - v_toe) / dv)), 0, -1)
    hi = vs[-1] + dv * np.arange(1, int(np.ceil((v_heel - vs[-1]) / dv)) + 1)
    us = sheet.u_nodes
    cols = [sheet.psi_nodes]
    for new, v_end, where in ((lo, vs[0], 0), (hi, vs[-1], 1)):
        if len(new) == 0:
            continue
        ue = np.full_like(us, v_end)
        p, pv, pvv = (sheet.psi(us, ue, dv=k) for k in (0, 1, 2))
        d = new[None, :] - v_end
        block = p[:, None] + pv[:, None] * d + 0.5 * pvv[:, None] * d * d
        cols.insert(0 if where == 0 else len(cols), block)
    return dataclasses.replace(sheet, v_nodes=np.concatenate([lo, vs, hi]),
                               psi_nodes=np.concatenate(cols, axis=1))


#: Node grid (profile x lengthwise) of a generating gear sheet: its quintic spline
#: departs from the exact envelope by 9e-11 mm (40 x 60 against the 120 x 150 nodes on
#: the 20/20 pair; 30 x 40: 2.8e-9 mm), at a fifth of the cost.
GENERATOR_GRID = (40, 60)


def generated_gear_sheets(pair) -> dict:
    """``{side: GearSheet}``: the gear flanks rolled on the crown gear of the pitch plane
    (:func:`~.basic_settings.generated_gear_setups`), as generators of the conjugate
    pinion (:func:`generating_sheet` of each).

    Raises
    ------
    UndercutError
        The envelope does not reach the generating sheet's nodes at any extension,
        naming the tooth numbers (the inner error chained).
    """
    setups = generated_gear_setups(pair)
    out = {}
    for side in SIDES:
        try:
            out[side] = generating_sheet(setups[side], pair.blank,
                                         gear_face_width_mm=pair.gear_face_width_mm)
        except UndercutError as err:
            raise UndercutError(
                "pinion_teeth / gear_teeth", (pair.pinion_teeth, pair.gear_teeth),
                "a pair whose gear the formate cut or the crown gear generates: the "
                "formate gear undercuts the pinion, and the generated gear's "
                f"envelope does not reach its {err.field} (undercut / limit line of "
                "the gear; raise the tooth numbers or the spiral angle)") from err
    return out


def generating_sheet(setup, blank, *, gear_face_width_mm: float,
                     n_u: int = GENERATOR_GRID[0], n_v: int = GENERATOR_GRID[1],
                     box: FlankBoundary | None = None) -> GearSheet:
    """The generated gear flank ``setup`` cuts as a generator of the conjugate pinion
    (wrap it in a :class:`SheetGenerator`), on an n_u x n_v envelope node grid.

    The pinion's corners lie beyond the gear's face in contact (a long pinion addendum
    at the heel tip: 7.5 mm past the heel of the 20/20 pair with F.2's gear addendum
    factor), so its nodes there are generated by the gear surface continued beyond the
    face (a formate gear's cone continues exactly; a spline extrapolates badly). The
    sheet's nodes cover :func:`generator_node_box`; where the envelope itself ends short
    of ``GENERATOR_EXTENSION`` (its limit line near the blade tip, at the toe), the node
    rows continue by their Taylor polynomial (:func:`_extended`). That continuation lies
    beyond the gear face, where the gear has no flank in contact: its boundary stays the
    active box. ``box``: the flank's active box if already traced
    (:func:`~.generated.generated_gear_box` of ``setup``, a smooth blade's: the same
    sheet bit for bit), else traced here.

    Raises
    ------
    UndercutError
        The envelope does not reach the nodes even at the default node margins (the
        last of ``_EXTENSION_TRIALS``).
    """
    for share in _EXTENSION_TRIALS:
        try:
            sheet = generated_gear_flank(
                setup, blank, gear_face_width_mm=gear_face_width_mm, n_u=n_u, n_v=n_v,
                node_box=lambda *a, share=share: generator_node_box(*a, share=share),
                box=box)[0]
            break
        except UndercutError:
            if share == _EXTENSION_TRIALS[-1]:
                raise
    b, ext = sheet.boundary, GENERATOR_EXTENSION * gear_face_width_mm
    return _extended(sheet, b.v_toe - ext, b.v_heel + ext)


def gear_generation(pair) -> tuple[str, dict | None]:
    """The gear generation of the right-hand ``pair`` without machine settings (module
    docstring) and, for a formate gear, its pinion active boxes
    ``{side: (solver, box, gear_tip_undercut_mm)}`` (:func:`~.conjugate.pinion_active_box`,
    reused by the flank generation); ``None`` for a generated gear."""
    kin = pair.kinematics(with_errors=False)
    boxes = {}
    for side, gear in gear_flanks(pair)[1].items():
        try:
            boxes[side] = pinion_active_box(gear, blank=pair.blank, kinematics=kin,
                                            pinion_face_width_mm=pair.pinion_face_width_mm)
        except UndercutError:
            return "generated", None
    return "formate", boxes


def pair_gear_flanks(pair, generation: str):
    """``(placement, {side: gear flank}, {side: generator})`` of ``generation``: the
    formate flanks (each its own generator) or the generated sheets
    (:func:`generated_gear_sheets`, each wrapped in a :class:`SheetGenerator`); the
    cutter placement is the formate cut's (the generated gear rolls the same cutter)."""
    placement, formate = gear_flanks(pair)
    if generation == "formate":
        return placement, formate, formate
    sheets = generated_gear_sheets(pair)
    return placement, sheets, {side: SheetGenerator(s) for side, s in sheets.items()}


@dataclass(frozen=True, eq=False)
class PairGeneration:
    """The gear flanks of a right-hand pair without machine settings and the first step
    of its conjugate pinion generation (:func:`pair_generation`): what
    :func:`~.generation.check_generation` computes and :func:`~.flank.build_flanks`
    reuses, so that a command builds a generated gear's sheets once.

    Attributes
    ----------
    pair : GearPair
        The pair it was made for (right-hand, no machine settings).
    generation : str
        ``"formate"`` or ``"generated"`` (:func:`gear_generation`).
    placement : CutterPlacement
        The formate cut's cutter placement.
    gear, generators : dict
        ``{side: gear flank}`` and ``{side: generator}`` (:func:`pair_gear_flanks`).
    active : dict
        ``{side: (solver, box, gear_tip_undercut_mm)}``
        (:func:`~.conjugate.pinion_active_box` of each generator).
    """

    pair: object
    generation: str
    placement: object
    gear: dict
    generators: dict
    active: dict

    def serves(self, pair) -> bool:
        """``pair`` has the same flank geometry as :attr:`pair` (it may differ in what
        the gear flanks and the conjugate pinion do not depend on: name, ease-off,
        assembly errors, materials, design side)."""
        return _geometry(pair) == _geometry(self.pair)


#: GearPair fields the gear flanks and the conjugate pinion's active box do not depend on.
_NOT_GEOMETRY = frozenset({"name", "easeoff_drive", "easeoff_coast", "assembly",
                           "pinion_material", "gear_material", "design_side",
                           "easeoff_tables"})


def _geometry(pair) -> tuple:
    return tuple((f.name, getattr(pair, f.name)) for f in dataclasses.fields(pair)
                 if f.name not in _NOT_GEOMETRY)


def pair_generation(pair) -> PairGeneration:
    """The :class:`PairGeneration` of the right-hand ``pair`` without machine settings:
    its gear generation (:func:`gear_generation`), gear flanks (:func:`pair_gear_flanks`)
    and the pinion active box of each side (reused from :func:`gear_generation` for a
    formate gear).

    Raises
    ------
    UndercutError
        As :func:`~.conjugate.pinion_active_box` on the generated gear.
    """
    generation, boxes = gear_generation(pair)
    placement, gear, generators = pair_gear_flanks(pair, generation)
    if boxes is None:
        kin = pair.kinematics(with_errors=False)
        boxes = {side: pinion_active_box(gen, blank=pair.blank, kinematics=kin,
                                         pinion_face_width_mm=pair.pinion_face_width_mm)
                 for side, gen in generators.items()}
    return PairGeneration(pair=pair, generation=generation, placement=placement, gear=gear,
                          generators=generators, active=boxes)


def generation_of(boxes: dict) -> str:
    """The gear generation recorded in :func:`~.generation.check_generation`'s result:
    ``"formate"``, ``"generated"`` or ``"machine"`` (a pair cut from machine settings)."""
    return boxes["drive"].get("gear_generation", "machine")


def generation_text(generation: str, pair) -> str:
    """One line saying how the gear flanks of ``pair`` are made (``design`` prints it)."""
    if generation == "formate":
        return "formate (each flank a copy of the straight blade; conjugate pinion)"
    if generation == "generated":
        r_a = 1.0 / np.sin(np.radians(pair.blank.pitch_angle_gear_deg))
        return ("generated (the blade rolled on the crown gear of the pitch plane, ratio of "
                f"roll 1/sin(delta2) = {r_a:.4f}; conjugate pinion): the formate gear would "
                "undercut the pinion (docs/machine_settings.md sec. 5)")
    return "cut from the pair's machine settings"
