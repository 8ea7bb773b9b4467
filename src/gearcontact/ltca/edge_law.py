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

The compliance scale ``c = exp(mean_i ln(delta_i / delta_ref(W_i)))`` is the
least-squares fit of ``ln delta = ln(c kappa) + (2/3) ln W`` at the twin's exponent; the
free power fit ``delta = C W^n`` is kept to say how far the LCP is from ``n = 2/3``.

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
from ..tca.stencil import gap_at

__all__ = ["EDGE_LOAD_FRACTIONS", "ELLIPSE_PROBES", "EdgeCompliance", "edge_compliance",
           "ellipse_leaves_flank", "equivalent_curvature_factor", "trim_compliance"]

#: Points on the Hertzian ellipse's border that decide whether a surface row's patch is
#: cut by a flank boundary (:func:`ellipse_leaves_flank`).
ELLIPSE_PROBES = 16

#: Loads of the calibration as fractions of the pair carrying the table's torque alone
#: (a row carries at most that). Below a quarter the LCP's approach on the loaded TE's
#: 40-cell edge field nears the separation half a cell inside the edge (0.15-0.4 um on
#: the 7/60 pair), a floor of the grid rather than of the contact: the law extrapolates
#: the fitted power there.
EDGE_LOAD_FRACTIONS = (0.25, 0.5, 1.0)


@dataclass(frozen=True, eq=False)
class EdgeCompliance:
    """The LCP calibration of one edge row (module docstring).

    Attributes
    ----------
    loads_n : ndarray (3,)
        Calibration loads ``W_i``, N.
    approach_lcp_mm, approach_ref_mm : ndarray (3,)
        ``delta_LCP(W_i) - g`` on the row's (trimmed) field and the reference approach
        (Hamrock–Brewe's ``delta_H(W_i)`` of the row's curvatures, or the LCP on the
        continued flanks), mm.
    scale : float
        ``c``: the row's approach over the Hertzian one at fixed exponent 2/3.
    exponent : float
        ``n`` of the free fit ``delta = C W^n`` to the LCP approaches.
    """

    loads_n: np.ndarray
    approach_lcp_mm: np.ndarray
    approach_ref_mm: np.ndarray
    scale: float
    exponent: float

    @property
    def ratio(self) -> np.ndarray:
        """``delta_LCP / delta_ref`` at each load."""
        return self.approach_lcp_mm / self.approach_ref_mm


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
        An LCP did not converge, or the pair does not close under load (the row's law
        would be unfounded).
    """
    gap, grid, _, _ = fields.get(pc)
    loads = _loads(pc, torque_nmm)
    lcp = _approaches(gap, grid, loads, pc, materials)
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
    if not any((m & off).any() for m in masks):
        return EdgeCompliance(loads, cont, cont, 1.0, 2.0 / 3.0)
    return _fit(loads, _approaches(gap, grid, loads, pc, materials), cont)


def _loads(pc, torque_nmm: float) -> np.ndarray:
    return np.array([f * torque_nmm / pc.lever_mm for f in EDGE_LOAD_FRACTIONS])


def _approaches(gap, grid, loads, pc, materials, *, masks: bool = False):
    """LCP approaches ``delta_LCP(W_i) - g`` (mm) on one field (and the contact masks)."""
    out, contact, warm = np.empty(loads.size), [], None
    for i, w in enumerate(loads):
        res = solve_lcp(gap, grid, float(w), materials=materials, warm_start=warm,
                        warn_coarse=False)
        if not res.converged:
            raise ArithmeticError(f"edge_law: the LCP of the row at path index "
                                  f"{pc.path_index} did not converge at {w:.4g} N "
                                  f"({res.message})")
        warm = res
        out[i] = float(res.delta_mm) - pc.offset_mm
        contact.append(res.contact_mask)
    if not (out > 0.0).all():
        raise ArithmeticError(f"edge_law: the row at path index {pc.path_index} closes by "
                              f"{out.min():.3g} mm <= 0 under load (its field does not "
                              f"hold its opening)")
    return (out, contact) if masks else out


def _fit(loads, approach, reference) -> EdgeCompliance:
    n = float(np.polyfit(np.log(loads), np.log(approach), 1)[0])
    return EdgeCompliance(loads, approach, reference,
                          float(np.exp(np.mean(np.log(approach / reference)))), n)


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
