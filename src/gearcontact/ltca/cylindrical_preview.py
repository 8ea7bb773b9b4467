"""The preview (stages C -> D, the line chain) on the contact of a cylindrical pair, per
phase and loaded tooth pair (docs/cylindrical.md sec. 8).

Per phase of the unloaded cycle and tooth pair carrying load: the pair's 7 x 7 gap
stencil at the least-gap point of its contact line (:mod:`gearcontact.tca.
cylindrical_stencil`), its load ``W`` and the equivalent length ``L_eq`` of its contact
line (below) go through the *line chain* of the datapath (:func:`gearcontact.preview.
chain.chain_line_reference`, ``chain_line_golden``; the fit core into the line core of
stage D, :mod:`gearcontact.preview.hertz.line`): the curvature fit, then the Hertz
ellipse where it fits the line or else the Hertz line contact of ``W`` on ``L_eq``
(Johnson 1985 sec. 4.3), which is what the unmodified and the lightly crowned flanks of
a spur or helical pair give. Every backend of :mod:`gearcontact.preview.engine`
evaluates the same stencils (``reference``: fp64; ``golden``: the bit-exact fixed point;
``rtl`` once :mod:`gearcontact.hw.backends` is imported: the ChainLineCore in
simulation).

The line's load (``face_load``, :class:`LineFaceLoad`) is the twin's
(:mod:`gearcontact.twin.line_law`) on rigid teeth, and with the loaded TE's tooth
bending the coupled slice law (:mod:`.coupled_slice_law`: the same law on the ease-off
plus the shells' deflection under the slice loads, G at the line's slices): the slice law (:func:`.slice_law.loaded_line`) at
``W`` on the ease-off along the line (crowning, relief, misalignment, helix slope:
:func:`.slice_law.line_easeoff_mm`, the gap at the line's 16 slices) across the fitted
curvature ``B_max`` (the fp64 stage C of the stencil) gives the loaded length ``L_c``
(the part of the line's length ``L`` in the zone of action whose gap the approach
closes; ``L_c = L`` on a flat line), the peak line load ``w_peak = W d_c / I`` where the
line's gap is least, and with it ``L_eq = W / w_peak`` (:func:`.slice_law.
equivalent_length`): the line chain's uniform line of ``W`` over ``L_eq`` carries
``w_peak``, so its ``p_max`` is the Hertz pressure of the peak line load (ISO's contact
stress with the contact's own face load factor ``w_peak L / W``). A flat line gives
``L_eq = L_c = L``; a saddle fit (``B_max <= 0``) keeps ``L``. A line whose gap is least
at one of its ends and whose load ends inside it (a misalignment's or helix slope's
wedge, which crowning may lengthen but not centre) is *end-loaded*: the pressure at
that sharp face end is singular on the half-space, an edge result, which the LCP's
peak there shows (growing with its rows; docs/cylindrical.md sec. 7). On a straight gap
the slice law is the closed form of
:func:`gearcontact.analytic.face_load.end_loaded_line` within its slices
(docs/cylindrical.md sec. 8). The line core's domain starts at ``L = 1`` mm: a shorter
``L_eq`` (a short end-loaded line, ``L_c`` below about 2 mm) is run by the engines on
``(2^s W, 2^s L_eq)`` (the host's lift, :func:`gearcontact.preview.hertz.line.
length_lift`), whose line-mode answer is exactly that of ``(W, L_eq)``.

Loads. With a loaded TE (:func:`.cylindrical_lte.cylindrical_loaded_te` at the same
torque and cycle) each pair carries its LCP load share of ``F_n``; without it the pairs
touching unloaded share ``F_n`` in proportion to their line lengths (rigid flanks in
line contact close by the same approach, and the line contact's approach is, to its
logarithmic term, that of the load per unit length); at a phase where a tip edge
alone touches (docs/cylindrical.md sec. 6), the lines next to close share it. An input outside a backend's
domain is a result, not an abort: the reference's refusal is kept as text in
``errors``, the fixed point's flags as mode ``"flagged"``.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..geometry.cylindrical.pair import CylindricalPair
from ..materials import effective_modulus_mpa
from ..preview.engine import PreviewResult, get_engine
from ..preview.fit.reference import fitted_coefficients, principal_curvatures
from ..tca.cylindrical_cycle import CylindricalMeshCycle, cylindrical_mesh_cycle
from ..tca.cylindrical_stencil import CylindricalStencils, cylindrical_stencils
from ..errors import BadInput
from ..validation import InputRangeError
from ..analytic.hertz import line_contact_terms
from .coupled_slice_law import coupled_line, line_bending_compliance
from .cylindrical_bending import cylindrical_bending
from .cylindrical_lte import CylindricalLoadedTE, normal_load_n
from .slice_law import equivalent_length, line_easeoff_mm, loaded_length_mm
from .tooth_bending import ToothBending

__all__ = ["CylindricalPreview", "LineFaceLoad", "cylindrical_preview", "line_face_loads",
           "pair_loads_n"]


@dataclass(frozen=True)
class LineFaceLoad:
    """The slice law's line load of every loaded pair (module docstring), arrays (P, K);
    NaN (False) where a pair is not loaded.

    Attributes
    ----------
    end_loaded : ndarray of bool
        The line's gap (at its slices) is least at one of its ends and the load ends
        inside the line (``L_c < L``): its peak sits on the line's closed end (a face
        end under a misalignment's or helix slope's wedge).
    loaded_length_mm : ndarray
        ``L_c``, mm.
    equivalent_length_mm : ndarray
        ``L_eq = W / w_peak``, mm: the line chain's ``L``.
    peak_line_load_n_per_mm : ndarray
        ``w_peak``, the line load where the line's gap is least, N/mm.
    face_load_factor : ndarray
        Peak over the mean line load ``W / L`` (ISO's ``K_Hbeta`` of the contact alone).
    hertz_pressure_mpa : ndarray
        Hertz line-contact pressure of the peak line load across the fp64 stage C's
        larger curvature, MPa (the reference chain's ``p_max`` in line mode; not a face
        end's singular pressure). NaN on a saddle fit.
    """

    end_loaded: np.ndarray
    loaded_length_mm: np.ndarray
    equivalent_length_mm: np.ndarray
    peak_line_load_n_per_mm: np.ndarray
    face_load_factor: np.ndarray
    hertz_pressure_mpa: np.ndarray


def line_face_loads(pair: CylindricalPair, cycle: CylindricalMeshCycle,
                    stencils: CylindricalStencils, loads_n: np.ndarray,
                    loaded: np.ndarray, *, teeth: ToothBending | None = None
                    ) -> LineFaceLoad:
    """:class:`LineFaceLoad` of every ``loaded`` pair at its load (``loads_n``, N, (P,
    K)): the slice law (:func:`.slice_law.loaded_line`) on the line's ease-off
    (:func:`.slice_law.line_easeoff_mm`) across the fp64 stage C's larger curvature of
    the stencil (the twin's inputs, row for row: :func:`gearcontact.twin.model.
    build_model`). A saddle fit (``B_max <= 0``) keeps the whole line, uniform.
    ``teeth``: the coupled slice law with the teeth's bending compliance at the line's
    slices (:mod:`.coupled_slice_law`; None: the half-space foundation alone, the
    twin's law)."""
    ease, slices = line_easeoff_mm(pair, cycle, stencils.valid)
    coeff = fitted_coefficients(stencils.gaps_mm)
    e_prime = effective_modulus_mpa(pair.pinion_material, pair.gear_material)
    out = {f: np.full(loaded.shape, np.nan) for f in LineFaceLoad.__dataclass_fields__}
    out["end_loaded"] = np.zeros(loaded.shape, bool)
    for j, k in zip(*np.nonzero(loaded)):
        length, w = float(stencils.line_length_mm[j, k]), float(loads_n[j, k])
        b_max = max(principal_curvatures(*map(float, coeff[j, k]))[:2])
        l_c = l_eq = length
        if b_max > 0.0:
            h = ease[j, k]
            if teeth is None:
                d_c, l_c, area = loaded_length_mm(h, length, w, b_max, e_prime)
            else:
                line = coupled_line(h, length, w, b_max, e_prime,
                                    line_bending_compliance(teeth, slices, j, k))
                d_c, l_c, area = line.approach_mm, line.loaded_length_mm, \
                    line.interference_mm2
                h = line.effective_ease_mm
            l_eq = equivalent_length(d_c, area, length)
            out["end_loaded"][j, k] = l_c < length and int(np.argmin(h)) in (0, h.size - 1)
            out["hertz_pressure_mpa"][j, k] = line_contact_terms(b_max, w / l_eq, 1.0,
                                                                 e_prime)[0]
        out["loaded_length_mm"][j, k] = l_c
        out["equivalent_length_mm"][j, k] = l_eq
        out["peak_line_load_n_per_mm"][j, k] = w / l_eq
        out["face_load_factor"][j, k] = length / l_eq
    return LineFaceLoad(**out)


@dataclass(frozen=True)
class CylindricalPreview:
    """The preview of every loaded pair over one pinion pitch, per backend.

    Shapes (P, K) as the cycle's; ``loaded`` marks the evaluated entries.

    Attributes
    ----------
    torque_nm : float
        Gear torque, N·m.
    normal_load_n : float
        ``F_n``, N.
    load_source : str
        ``"ltca"`` (LCP load shares) or ``"line_length"`` (module docstring).
    load_n : ndarray (P, K)
        Normal load of each pair, N (0 where not loaded).
    loaded : ndarray (P, K) of bool
    stencils : CylindricalStencils
        The inputs (stencils, exact curvatures, line lengths).
    loaded_length_mm : ndarray (P, K)
        ``L_c`` of the slice law at each evaluated entry (module docstring), mm; NaN
        elsewhere.
    results : dict
        Backend name -> nested list (P rows of K) of :class:`PreviewResult` or None.
    errors : dict
        ``(backend, j, k)`` -> the refusal's text, where a backend raised.
    face_load : LineFaceLoad or None
        The slice law's line load of the loaded pairs (module docstring).
    """

    torque_nm: float
    normal_load_n: float
    load_source: str
    load_n: np.ndarray
    loaded: np.ndarray
    stencils: CylindricalStencils
    loaded_length_mm: np.ndarray
    results: dict = field(repr=False)
    errors: dict = field(default_factory=dict)
    face_load: LineFaceLoad | None = None

    @property
    def backends(self) -> tuple[str, ...]:
        return tuple(self.results)

    def values(self, backend: str, name: str) -> np.ndarray:
        """(P, K) array of a :class:`PreviewResult` field (``p_max_mpa``, ``a_mm``,
        ``b_mm``, ...) of ``backend``; NaN where not evaluated or refused."""
        rows = self.results[backend]
        return np.array([[np.nan if r is None else float(getattr(r, name)) for r in row]
                         for row in rows])

    def modes(self, backend: str) -> np.ndarray:
        """(P, K) array of the modes (``"elliptic"``, ``"line"``, ``"flagged"``; ``""``
        where not evaluated, ``"refused"`` where the backend raised)."""
        out = np.full(self.load_n.shape, "", dtype=object)
        for j, row in enumerate(self.results[backend]):
            for k, r in enumerate(row):
                if r is not None:
                    out[j, k] = r.mode
                elif (backend, j, k) in self.errors:
                    out[j, k] = "refused"
        return out

    def max_pressure_mpa(self, backend: str) -> np.ndarray:
        """(K,) largest previewed peak pressure over the loaded pairs, MPa."""
        p = np.where(self.loaded, self.values(backend, "p_max_mpa"), np.nan)
        return np.nanmax(np.where(np.isnan(p), -np.inf, p), axis=0)


def pair_loads_n(stencils: CylindricalStencils, normal_load: float,
                 loaded_te: CylindricalLoadedTE | None = None) -> tuple[np.ndarray, str]:
    """Normal load per pair and phase (N) and its source (module docstring)."""
    if loaded_te is not None:
        if loaded_te.load_share.shape != stencils.valid.shape:
            raise InputRangeError("loaded_te.load_share shape", loaded_te.load_share.shape,
                                  f"{stencils.valid.shape} (the cycle's pairs x phases)")
        return np.where(stencils.valid, loaded_te.load_share * normal_load, 0.0), "ltca"
    touch = stencils.in_contact
    # where a tip edge alone touches (no line closed unloaded), the lines next to close
    opening = np.where(stencils.valid, stencils.opening_mm, np.inf)
    nearest = stencils.valid & (opening <= opening.min(axis=0)[None, :])
    touch = np.where(touch.any(axis=0)[None, :], touch, nearest)
    length = np.where(touch, stencils.line_length_mm, 0.0)
    return normal_load * length / length.sum(axis=0)[None, :], "line_length"


def cylindrical_preview(pair: CylindricalPair, torque_nm: float, *,
                        cycle: CylindricalMeshCycle | None = None,
                        stencils: CylindricalStencils | None = None,
                        loaded_te: CylindricalLoadedTE | None = None,
                        backends=("reference", "golden"), phases: int = 61,
                        min_share: float = 1e-3, bending: bool | None = None
                        ) -> CylindricalPreview:
    """The line-chain preview of every loaded pair at every phase (module docstring).

    Parameters
    ----------
    pair : CylindricalPair
        With its micro-geometry and misalignment.
    torque_nm : float
        Gear torque (> 0), N·m, the package's convention (as the loaded TE's).
    cycle : CylindricalMeshCycle, optional
        The unloaded cycle (computed with ``phases`` if None).
    stencils : CylindricalStencils, optional
        Its stencils (computed if None).
    loaded_te : CylindricalLoadedTE, optional
        Loaded TE of the same cycle and torque: its load shares (module docstring).
    backends : sequence of str
        Preview backends (:func:`gearcontact.preview.engine.get_engine` names).
    min_share : float
        A pair is previewed when it carries at least this share of ``F_n``.
    bending : bool, optional
        The slice law with the teeth's bending (:mod:`.coupled_slice_law`, the shells of
        :func:`.cylindrical_bending.cylindrical_bending` on the cycle's facing) or on the
        half-space foundation alone; None: as ``loaded_te`` (its ``bending``; without
        it, the foundation alone).
    """
    load = normal_load_n(pair, torque_nm)
    engines = {name: get_engine(name, material=pair.pinion_material,
                                material2=pair.gear_material) for name in backends}
    if not 0.0 <= min_share < 1.0:
        raise InputRangeError("min_share", min_share, "in [0, 1)")
    if loaded_te is not None and abs(loaded_te.torque_nm - float(torque_nm)) > 1e-12 * load:
        raise InputRangeError("loaded_te.torque_nm", loaded_te.torque_nm,
                              f"{float(torque_nm)!r} N·m (the preview's torque)")
    if cycle is None:
        cycle = cylindrical_mesh_cycle(pair, phases=phases)
    if stencils is None:
        stencils = cylindrical_stencils(pair, cycle)
    loads, source = pair_loads_n(stencils, load, loaded_te)
    loaded = stencils.valid & (loads >= min_share * load) & (loads > 0.0)
    n_p, n_k = loaded.shape
    if bending is not None and not isinstance(bending, bool):
        raise InputRangeError("bending", bending, "True, False or None")
    if bending is None:
        bending = loaded_te is not None and loaded_te.bending
    teeth = cylindrical_bending(pair, facing=cycle.facing) if bending else None
    face = line_face_loads(pair, cycle, stencils, loads, loaded, teeth=teeth)
    results: dict[str, list[list[PreviewResult | None]]] = {}
    errors: dict[tuple[str, int, int], str] = {}
    for name, engine in engines.items():
        rows = [[None] * n_k for _ in range(n_p)]
        for j, k in zip(*np.nonzero(loaded)):
            try:
                rows[j][k] = engine.stencil(
                    stencils.gaps_mm[j, k], float(loads[j, k]),
                    line_length_mm=float(face.equivalent_length_mm[j, k]))
            except BadInput as exc:       # outside this backend's domain: a result
                errors[(name, int(j), int(k))] = str(exc)
        results[name] = rows
    pair_load = np.where(loaded, loads, 0.0)
    return CylindricalPreview(torque_nm=float(torque_nm), normal_load_n=load,
                              load_source=source, load_n=pair_load,
                              loaded=loaded, stencils=stencils,
                              loaded_length_mm=face.loaded_length_mm, results=results,
                              errors=errors, face_load=face)

