"""The contact law of the twin's rows whose patch a flank boundary cuts: Hertz scaled
to the loaded TE's LCP.

At an edge row of the mesh table (:data:`.mesh.CONTACT_MODES` ``edge``: an edge of one
flank touching the other, :mod:`gearcontact.tca.edge_contact`; or ``posed field``) the
contact region is bounded by the edge: no pressure acts beyond it. The Hertzian law of
the pair's nearest surface contact (the curvatures the row carries) does not see that
bound and is too stiff there. A Hertzian contact cut through its centre carries ``W``
on half its ellipse and needs at most the approach of the whole ellipse under ``2 W``
(Boussinesq's kernel is positive; Johnson 1985 sec. 3.4), ``2^(2/3) = 1.59`` times its
own; deeper on the edge, where the surfaces recede from the edge linearly (its inward
slope), and at a corner, more. The same holds, less, for a surface row whose ellipse
overhangs a flank boundary (a bearing at the tip, a path end). No closed form covers
those, so the law is calibrated on the loaded TE's own contact model at the row: the
pair's field of :class:`gearcontact.ltca.lte_pairs.PairFields` (the one ``analyze``'s
``TE_LCP`` solves on, posed as the pair stands unloaded so that it holds the pair's
opening ``g``; at an edge contact fitted to the edge, :func:`gearcontact.tca.edge_field.
edge_gap_field`), rigid teeth, the half-space LCP (:func:`gearcontact.halfspace.lcp.
solve_lcp`) at the loads ``W_i = f_i T / l`` (:data:`EDGE_LOAD_FRACTIONS` of the pair
carrying the table's torque alone), approach ``delta_i = delta_LCP(W_i) - g`` from the
row's closing datum, against a reference ``delta_ref(W_i)``:

* an edge or posed-field row: the Hamrock–Brewe approach ``delta_H`` of the row's
  curvatures (the law the row would have without its edge);
* a surface row whose Hertzian ellipse under the whole torque leaves a flank
  (:func:`ellipse_leaves_flank`): the same LCP on the same field with its off-flank
  cells filled by the osculating quadric ``g + A s^2 + B t^2`` of the row's curvatures
  (the untrimmed patch; the flanks' own continuation beyond their boxes is no surface
  and can interfere by millimetres), so that the grid's own error cancels; where that
  patch stays on the flanks the trimmed problem has the same solution and the row keeps
  ``c = 1`` exactly (:func:`trim_compliance`).

*Datum.* Every edge row counts its LCP approach from its opening ``g``, its true first
contact (:func:`edge_datum_mm`): at an edge contact of the TCA the exact touch of the
edge, at a posed-field row the touch of its posed flanks searched over the whole flank
(:func:`.patch_field.touch_gap_mm`); the coupled LCP counts from the same ``g``. The
approach is taken on fields fitted to the patch (below), whose cells resolve it: the
first cell's centred gap, half a cell inside an edge, is the cell's mean of a gap rising
linearly from the edge, so the LCP's approach is in the gap's own coordinates, zero at
the touch. (Sessions 15-27 counted the TCA's edge rows from the least gap of the last
fitted field, the "grid floor", introduced on unfitted 40-cell fields; against the
coupled LCP both datums are within the declared bound on s0003 coast's edge rows:
docs/twin.md, "The TCA's edge rows: the approach from the touch?".)

*Patch resolution.* The loaded TE's field of an edge row is sized by the ellipse of the
whole torque; the patch at an edge is a strip a few of its cells across (s0003 coast's
tip and heel-corner rows: 1-3 of 40 rows up to ``T/4``), and on a posed field it lay at
the field's border two cells wide (the entering pair). The calibration's LCP therefore
solves each load again on fields fitted to its patch (:func:`.patch_field.
patch_approach`, the same flanks in the same frame, a few times finer where the
pressure is; its least gap the datum). Measured 40 vs 80 cells (issue 28, session 16):
s0003 coast's edge rows at ``T/16, T/4, T`` within 1.4 % (before 5-13 % on the TCA's
edge rows and 14-63 % on the posed rows, whose opening moved by 1-11 um), the twin
table's static approach of every row carrying at least ``T/16`` within 1.8 % (s0003)
and 0.4 % (the 15/15 miter pair; before 3.0 %). docs/twin.md, "Edge rows on fields
fitted to the patch".

The row's compliance scale is the LCP's ratio at the load the row carries: ``c(W) =
delta_LCP(W) / delta_ref(W)``, ``ln c`` interpolated linearly in ``ln W`` between the
calibration loads (:meth:`EdgeCompliance.scale_at`; constant above them; below the
least, ``delta ~ W^m`` with ``m`` = :attr:`EdgeCompliance.low_exponent`: 2/3, the
scale held, unless the caller knows the touch's asymptote -- a corner's 1/2,
:mod:`.off_flank`), taken at the
row's *operating load* (:func:`operating_scales`): its share of the torque in the
quasi-static mesh of the table's own law (the Hertzian balance of the loaded TE's
preview, :func:`gearcontact.ltca.lte_phase.preview_balance`, with the scaled rows;
iterated, as the shares depend on the scales), at least the smallest calibration load
(a row that carries nothing at rest first carries little when the mesh deflects;
``TE_pre`` takes the same, docs/twin.md). A
pair entering or leaving the mesh carries a fraction of the torque, and the LCP's power
of the load ``n`` differs from 2/3 (0.55-0.8 on cut patches), so a scale fitted over
``T/4 .. T`` was off there by ``|n - 2/3| ln(W_fit / W)`` (the 7/60 pair's approaching
pair: 6.5-22 %); at the operating load the law is the LCP's to the interpolation
between calibration loads (within 1.4 % at T/8 on s0003). ``EdgeCompliance.scale``
keeps the fit at the twin's exponent over the calibration loads, ``exponent`` the free
power fit ``delta = C W^n`` (how far the LCP is from ``n = 2/3``, i.e. how fast the
law departs from it away from the operating load).

The row's law is then ``delta = c kappa W^(2/3)``. It reaches every backend unchanged as
*equivalent curvatures*: the Hertzian approach of a fixed ellipticity scales as the
cube root of the curvature sum (Hamrock & Brewe 1983: ``delta ~ (W^2 / (E'^2 R))^(1/3)``,
``k`` and the elliptic integrals depend only on ``B/A``), so the row's A-, B- and its
7 x 7 stencil (stage C's fit is linear in the samples) are multiplied by ``c^3``
(:func:`equivalent_curvature_factor`) in the mesh table itself: the fp64 law, the golden
and RTL stage D, the C of the FMUs and the table the FMU bakes all evaluate the same
law with no change to their datapath. What that does not keep: the ellipse the
preview reports at such a row is the equivalent one (semi-axes ``/ c``, ``p_max * c^2``),
not the trimmed patch (whose pressure is singular at a sharp edge).

References
----------
K. L. Johnson, *Contact Mechanics*, 1985, sec. 3.4, 4.2, 5.2.
B. J. Hamrock, D. E. Brewe, J. Lubrication Technol. 105 (1983) 171-177.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..analytic.hertz import hamrock_brewe_hertz
from ..halfspace.lcp import solve_lcp
from ..ltca.lte_phase import preview_balance
from ..tca.stencil import gap_at
from .patch_field import patch_approach

__all__ = ["EDGE_LOAD_FRACTIONS", "ELLIPSE_PROBES", "EdgeCompliance", "edge_compliance",
           "edge_datum_mm", "ellipse_leaves_flank", "equivalent_curvature_factor",
           "operating_scales", "trim_compliance"]

#: Points on the Hertzian ellipse's border that decide whether a surface row's patch is
#: cut by a flank boundary (:func:`ellipse_leaves_flank`).
ELLIPSE_PROBES = 16

#: Loads of the calibration as fractions of the pair carrying the table's torque alone
#: (a row carries at most that at rest), a factor 4 apart: ``ln delta`` is smooth enough
#: in ``ln W`` that interpolating between them is within 1.4 % of the LCP at the loads
#: between (s0003 coast's edge rows at T/8). The least is T/16: there the contact patch
#: spans about 10 of the field's 40 cells across (the field is sized by the ellipse
#: under the whole torque, patch sizes go as ``W^(1/3)``) and the LCP's approach is
#: within 0.5 % of an 80-cell field's on surface rows (edge rows are solved on fields
#: fitted to their patch at each load, "patch resolution" below); at T/64 8-17 %. Below
#: T/16 the law keeps the scale at T/16.
EDGE_LOAD_FRACTIONS = (0.0625, 0.25, 1.0)
#: Passes of the operating loads and scales (:func:`operating_scales`): a relative change
#: of a row's load moves its scale by ``|n - 2/3|`` (0-0.15) of it, so each pass shrinks
#: the change by that factor or more.
OPERATING_PASSES = 3


@dataclass(frozen=True, eq=False)
class EdgeCompliance:
    """The LCP calibration of one edge row (module docstring).

    Attributes
    ----------
    loads_n : ndarray (n,)
        Calibration loads ``W_i`` at which the LCPs converged (at least two of
        :data:`EDGE_LOAD_FRACTIONS`), N.
    approach_lcp_mm, approach_ref_mm : ndarray (n,)
        ``delta_LCP(W_i) - g`` on the row's (trimmed) field and the reference approach
        (Hamrock–Brewe's ``delta_H(W_i)`` of the row's curvatures, or the LCP on the
        continued flanks), mm.
    scale : float
        The fit of ``delta = c delta_ref`` over the calibration loads at fixed exponent
        2/3 (the law's scale is :meth:`scale_at` the row's operating load).
    exponent : float
        ``n`` of the free fit ``delta = C W^n`` to the LCP approaches.
    low_exponent : float
        ``m`` of the law below the least calibration load, ``delta = delta(W_lo) (W /
        W_lo)^m`` against a Hertzian reference (``c ~ W^(m - 2/3)``): 2/3 holds the
        scale (the default); 1/2 is a corner's asymptote (docs/twin.md, "below the
        calibration, the corner's law").
    """

    loads_n: np.ndarray
    approach_lcp_mm: np.ndarray
    approach_ref_mm: np.ndarray
    scale: float
    exponent: float
    low_exponent: float = 2.0 / 3.0

    @property
    def ratio(self) -> np.ndarray:
        """``delta_LCP / delta_ref`` at each load."""
        return self.approach_lcp_mm / self.approach_ref_mm

    @property
    def low_local_exponent(self) -> float:
        """``n_lo``: the LCP's local exponent ``d ln delta / d ln W`` between the two least
        calibration loads."""
        return float(np.log(self.approach_lcp_mm[1] / self.approach_lcp_mm[0])
                     / np.log(self.loads_n[1] / self.loads_n[0]))

    def scale_at(self, load_n):
        """``c(W) = delta_LCP(W) / delta_ref(W)``: ``ln c`` linear in ``ln W`` between the
        calibration loads, constant above them, ``c(W_lo) (W / W_lo)^(m - 2/3)`` below
        the least (``m`` = :attr:`low_exponent`; module docstring); 1 exactly where the
        row's patch stayed on the flanks."""
        ln_w = np.log(load_n)
        ln_c = np.interp(ln_w, np.log(self.loads_n), np.log(self.ratio))
        if self.low_exponent == 2.0 / 3.0:     # the scale held: the law as calibrated
            return np.exp(ln_c)
        below = np.minimum(ln_w - np.log(self.loads_n[0]), 0.0)
        return np.exp(ln_c + (self.low_exponent - 2.0 / 3.0) * below)


def edge_compliance(fields, pc, *, materials, torque_nmm: float) -> EdgeCompliance:
    """Calibrate the edge (or posed-field) row ``pc`` on its field against the Hertzian
    law of its curvatures (module docstring).

    Parameters
    ----------
    fields : gearcontact.ltca.lte_pairs.PairFields
        The mesh table's fields (the loaded TE's, sized at ``torque_nmm``).
    pc : gearcontact.ltca.lte_pairs.PairContact
        The row's contact; its ``A_minus_per_mm``, ``B_minus_per_mm`` are the row's
        Hertzian curvatures.
    materials : (Material, Material)
        Pinion and gear materials (the LCP's modulus).
    torque_nmm : float
        Torque that sets the loads, N·mm.

    Raises
    ------
    ArithmeticError
        The LCP converged at fewer than two loads, or the pair does not close under load
        (the row's law would be unfounded).
    """
    loads = _loads(pc, torque_nmm)
    lcp, warm = np.full(loads.size, np.nan), None
    for i, w in enumerate(loads):
        lcp[i], warm = patch_approach(fields, pc, float(w), materials, warm=warm,
                                      datum_mm=edge_datum_mm(pc))
    _check_approaches(lcp, loads, pc)
    hz = np.array([hamrock_brewe_hertz(pc.A_minus_per_mm, pc.B_minus_per_mm, float(w),
                                       e_prime_mpa=fields.e_prime).approach_mm
                   for w in loads])
    return _fit(loads, lcp, hz)


def trim_compliance(fields, pc, *, materials, torque_nmm: float) -> EdgeCompliance:
    """Calibrate a surface row ``pc`` whose patch may overhang a flank boundary: its
    field trimmed at the boundary (the loaded TE's) against the same field with its
    off-flank cells on the osculating quadric of the row's curvatures (its principal
    frame: ``s`` along the direction of least curvature); ``c = 1`` (and ``n = 2/3``)
    where that patch stays on the flanks at every load (module docstring). Parameters
    and errors as :func:`edge_compliance`."""
    gap, grid, off, _ = fields.get(pc)
    loads = _loads(pc, torque_nmm)
    s, t = np.meshgrid(grid.x_mm, grid.y_mm)
    lo, hi = sorted((pc.A_minus_per_mm, pc.B_minus_per_mm))
    quadric = pc.offset_mm + lo * s ** 2 + hi * t ** 2
    cont, masks = _approaches(np.where(off, quadric, gap), grid, loads, pc, materials,
                              masks=True)
    ok = np.isfinite(cont)
    if not any((m & off).any() for m, conv in zip(masks, ok) if conv):
        return EdgeCompliance(loads[ok], cont[ok], cont[ok], 1.0, 2.0 / 3.0)
    return _fit(loads, _approaches(gap, grid, loads, pc, materials), cont)


def edge_datum_mm(pc) -> float:
    """The closing datum of an edge row's LCP approach (mm): its opening ``pc.offset_mm``,
    the row's true first contact (module docstring, "Datum"), whatever the field the
    approach is solved on."""
    return pc.offset_mm


def _loads(pc, torque_nmm: float) -> np.ndarray:
    return np.array([f * torque_nmm / pc.lever_mm for f in EDGE_LOAD_FRACTIONS])


def _approaches(gap, grid, loads, pc, materials, *, masks: bool = False,
                datum_mm: float | None = None):
    """LCP approaches ``delta_LCP(W_i) - datum`` (mm; datum: the row's opening ``g``) on
    one field (and the contact masks). A solve warm-started from the previous load that
    does not converge is repeated cold; a load at which it still does not converge is
    NaN (dropped by :func:`_fit`)."""
    datum = pc.offset_mm if datum_mm is None else datum_mm
    out, contact, warm = np.full(loads.size, np.nan), [], None
    for i, w in enumerate(loads):
        res = solve_lcp(gap, grid, float(w), materials=materials, warm_start=warm,
                        warn_coarse=False)
        if not res.converged and warm is not None:
            res = solve_lcp(gap, grid, float(w), materials=materials, warn_coarse=False)
        contact.append(res.contact_mask)
        if res.converged:
            warm = res
            out[i] = float(res.delta_mm) - datum
    _check_approaches(out, loads, pc)
    return (out, contact) if masks else out


def _check_approaches(out, loads, pc) -> None:
    """Raise ArithmeticError unless at least two loads converged with a positive
    approach."""
    if np.isfinite(out).sum() < 2:
        raise ArithmeticError(f"edge_law: the LCP of the row at path index {pc.path_index} "
                              f"converged at fewer than two of the loads {loads} N")
    if not (out[np.isfinite(out)] > 0.0).all():
        raise ArithmeticError(f"edge_law: the row at path index {pc.path_index} closes by "
                              f"{np.nanmin(out):.3g} mm <= 0 under load (its field does not "
                              f"hold its opening)")


def _fit(loads, approach, reference) -> EdgeCompliance:
    """The calibration over the loads where both approaches are known."""
    ok = np.isfinite(approach) & np.isfinite(reference)
    if ok.sum() < 2:
        raise ArithmeticError(f"edge_law: fewer than two calibration loads converged "
                              f"({loads} N)")
    loads, approach, reference = loads[ok], approach[ok], reference[ok]
    n = float(np.polyfit(np.log(loads), np.log(approach), 1)[0])
    return EdgeCompliance(loads, approach, reference,
                          float(np.exp(np.mean(np.log(approach / reference)))), n)


def operating_scales(laws, lever_mm, opening_mm, kappa, valid, *, torque_nmm: float
                     ) -> tuple[np.ndarray, np.ndarray]:
    """The scales ``c`` of the rows at their operating loads (module docstring).

    Parameters
    ----------
    laws : ndarray (P, K) of EdgeCompliance or None
        Each row's calibration (None: the Hertzian law, ``c = 1``).
    lever_mm, opening_mm, kappa : ndarray (P, K)
        The rows' levers, openings (one 0 per phase) and unscaled Hertzian approach
        coefficients ``delta = kappa W^(2/3)`` (mm/N^(2/3)).
    valid : ndarray (P, K) of bool
    torque_nmm : float
        The table's torque, N·mm.

    Returns
    -------
    (scale, load_n) : ndarray (P, K)
        ``c`` (1 where ``laws`` holds None) and the operating load (N; 0 at rows that do
        not carry at rest) of the last pass.
    """
    cut = np.array([[law is not None for law in row] for row in laws], bool)
    scale, load = np.ones(valid.shape), np.zeros(valid.shape)
    if not cut.any():
        return scale, load
    for i, k in zip(*np.nonzero(cut)):
        scale[i, k] = laws[i, k].scale
    for _ in range(OPERATING_PASSES):
        for k in np.flatnonzero(valid.any(axis=0)):
            on = valid[:, k]
            _, w = preview_balance(lever_mm[on, k], opening_mm[on, k],
                                   scale[on, k] * kappa[on, k], torque_nmm)
            load[on, k] = w
        for i, k in zip(*np.nonzero(cut)):
            floor = EDGE_LOAD_FRACTIONS[0] * torque_nmm / lever_mm[i, k]
            scale[i, k] = float(laws[i, k].scale_at(max(load[i, k], floor)))
    return scale, load


def equivalent_curvature_factor(scale: float) -> float:
    """Factor ``c^3`` on A-, B- and the stencil that multiplies a Hertzian approach
    coefficient by ``scale = c`` at the same ellipticity (module docstring)."""
    return float(scale) ** 3


def ellipse_leaves_flank(pinion, gear, kin, mp, pc, *, torque_nmm: float,
                         e_prime_mpa: float) -> bool:
    """Whether the Hertzian ellipse of a surface row's pair carrying ``torque_nmm``
    alone (Hamrock–Brewe semi-axes ``a`` along the principal direction of least
    curvature, ``b``) reaches beyond either flank: any of :data:`ELLIPSE_PROBES` points
    of its border off a flank (:func:`gearcontact.tca.stencil.gap_at`, principal frame
    at ``mp``, the row's mating point posed as the pair stands): a cheap filter before
    :func:`trim_compliance` builds the row's field."""
    hz = hamrock_brewe_hertz(pc.A_minus_per_mm, pc.B_minus_per_mm, torque_nmm / pc.lever_mm,
                             e_prime_mpa=e_prime_mpa)
    angle = np.linspace(0.0, 2.0 * np.pi, ELLIPSE_PROBES, endpoint=False)
    probe = gap_at(pinion, gear, kin, mp, hz.a_mm * np.cos(angle), hz.b_mm * np.sin(angle),
                   frame="principal", allow_outside=True)
    return not bool(probe.on_flank.all())
