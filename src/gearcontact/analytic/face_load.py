"""The face load of a misaligned line contact: loaded length and peak line load of a
contact line whose gap opens linearly along it (an uncrowned line under a mesh
misalignment or helix slope deviation, ISO 6336-1's effective misalignment F_beta_y),
as closed forms (docs/cylindrical.md sec. 7, "End-loaded lines").

The gap along the line (length ``L``, mm) is ``h(y) = s y`` (``s`` the slope, mm/mm;
``y = 0`` the closed end). Pressed by ``d`` at ``y = 0`` the line carries load where
``h < d``: the whole line (``s L < d``) or a *loaded length* ``L_c = d / s`` from the
closed end, which is then a face end of the flank (the line is *end-loaded*). Each law
below carries the load per unit length in proportion to the local interference
``d - h(y)`` (a Winkler foundation), so the line load is a trapezoid or, end-loaded, a
triangle of peak ``2 W / L_c``:

* :func:`linear_spring_face_load`: constant mesh stiffness per unit face width
  ``c_gamma`` (N/(mm·µm)), ISO 6336-1:2006 sec. 7.6 (the face load factor of the linear
  spring model, method C): with ``x = F_beta_y c_gamma / (2 F_m / b)``, ``K_Hbeta = 1 +
  x`` for ``x <= 1``, else ``K_Hbeta = sqrt(2 F_beta_y c_gamma / (F_m / b))`` and the
  loaded fraction of the face ``b_cal / b = 2 / K_Hbeta``.
* :func:`end_loaded_line`: the Hertz line contact's own compliance, the finite line's
  approach on the two half-spaces (:func:`~.hertz.line_contact_approach_mm`, Johnson
  1985 sec. 4.3) on the loaded length: the interference ``I = integral(max(d - h, 0) dy)``
  equals ``4 W / (pi E') (ln(4 L_c / b) - 3/4)`` with ``b`` the half-width of ``W`` on
  ``L_c`` (:func:`~.hertz.line_contact_terms`). This is the twin's slice law
  (:mod:`gearcontact.twin.line_law`) on a straight gap, solved exactly.

What neither carries: the pressure at a sharp face end. On the elastic half-space the
pressure under a body that ends at a sharp edge is singular there (the flat punch's
inverse square root, Johnson 1985 sec. 5.2), so the half-space LCP's peak pressure and
end-row line load at a loaded face end grow with grid refinement (about 2^(1/2) per
halving of the rows: docs/cylindrical.md sec. 7); its loaded length and approach
converge. Measured on the spur 20/40 (rigid teeth, 1144 N, gear axis inclined by
50-300 µm): the LCP's approach at the closed end is :func:`end_loaded_line`'s within
1.4 %, its loaded length 0.83-0.89 of it (the half-space deflects beside the load too,
which lifts the surface at the contact's end; tests/ltca/test_cylindrical_lte.py).

References
----------
ISO 6336-1:2006, sec. 7 (face load factors, K_Hbeta by the linear spring model).
K. L. Johnson, *Contact Mechanics*, 1985, sec. 4.3 (line contact), sec. 5.2 (punch).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from scipy.optimize import brentq

from ..validation import InputRangeError, check_positive
from .hertz import line_contact_terms

__all__ = ["EndLoadedLine", "end_loaded_line", "linear_spring_face_load"]

#: The line law's least ``ln(4 L_c / b) - 3/4`` (a contact as wide as 0.7 of its
#: length: the point contact's regime, where the line law ends).
_G_MIN = 1.0


def linear_spring_face_load(*, mean_line_load_n_per_mm: float, misalignment_um: float,
                            stiffness_n_per_mm_um: float) -> tuple[float, float]:
    """ISO 6336-1's face load factor of the linear spring model (module docstring):
    ``(K_Hbeta, b_cal / b)`` of the mean line load ``F_m / b`` (N/mm, > 0), the
    effective misalignment ``F_beta_y`` over the face (µm, >= 0) and the mesh stiffness
    ``c_gamma`` (N/(mm·µm), > 0). ``K_Hbeta`` is the peak line load over the mean."""
    w_m = check_positive("mean_line_load_n_per_mm", mean_line_load_n_per_mm)
    c = check_positive("stiffness_n_per_mm_um", stiffness_n_per_mm_um)
    f = float(misalignment_um)
    if not (math.isfinite(f) and f >= 0.0):
        raise InputRangeError("misalignment_um", misalignment_um, "a finite value >= 0 um")
    x = f * c / (2.0 * w_m)
    if x <= 1.0:
        return 1.0 + x, 1.0
    k = math.sqrt(2.0 * f * c / w_m)
    return k, 2.0 / k


@dataclass(frozen=True)
class EndLoadedLine:
    """The finite Hertz line on a straight gap (:func:`end_loaded_line`).

    Attributes
    ----------
    loaded_length_mm : float
        ``L_c``, mm (``L`` where the whole line carries).
    approach_mm : float
        ``d``: the approach at the closed end, mm.
    peak_line_load_n_per_mm : float
        Line load at the closed end, ``W d / I``, N/mm (``2 W / L_c`` end-loaded).
    face_load_factor : float
        Peak over the mean line load ``W / L`` (ISO's ``K_Hbeta`` of the contact alone).
    end_loaded : bool
        ``L_c < L``: the load ends inside the line, and its peak sits on the closed end.
    hertz_pressure_mpa : float
        Hertz line-contact pressure of the peak line load, ``(w E' B_max / pi)^(1/2)``,
        MPa: the ISO-style contact stress, not the pressure at a sharp face end (module
        docstring).
    """

    loaded_length_mm: float
    approach_mm: float
    peak_line_load_n_per_mm: float
    face_load_factor: float
    end_loaded: bool
    hertz_pressure_mpa: float


def end_loaded_line(*, load_n: float, slope: float, length_mm: float, b_max_per_mm: float,
                    e_prime_mpa: float) -> EndLoadedLine:
    """Loaded length, approach and peak line load of the finite Hertz line of length
    ``length_mm`` whose gap opens by ``slope`` (mm per mm along it, >= 0) from its
    closed end, under ``load_n`` (N) with the half relative curvature ``b_max_per_mm``
    across it (1/mm) and the plane-strain modulus ``e_prime_mpa`` (MPa): the module
    docstring's law, ``I(d) = 4 W / (pi E') g(L_c)`` with ``g = ln(4 L_c / b) - 3/4``,
    solved for ``L_c`` (Brent, to 1e-13 relative). Refuses a slope so steep that the
    loaded length would leave the line law's range (``g < 1``: a point contact)."""
    w = check_positive("load_n", load_n)
    length = check_positive("length_mm", length_mm)
    b_max = check_positive("b_max_per_mm", b_max_per_mm)
    e_prime = check_positive("e_prime_mpa", e_prime_mpa)
    s = float(slope)
    if not (math.isfinite(s) and s >= 0.0):
        raise InputRangeError("slope", slope, "a finite value >= 0 (mm per mm)")
    lam = 4.0 * w / (math.pi * e_prime)

    def g(lc: float) -> float:
        _, b = line_contact_terms(b_max, w, lc, e_prime)
        return math.log(4.0 * lc / b) - 0.75

    need = lam * g(length)                      # I the whole line needs
    if 0.5 * s * length * length <= need:       # the whole line carries: a trapezoid
        lc = length
        d = need / length + 0.5 * s * length
        area = need
    else:
        # g grows like 1.5 ln(L_c): the least L_c of the law, then the wedge's root
        lo = length * math.exp((_G_MIN - g(length)) / 1.5)
        if 0.5 * s * lo * lo >= lam * g(lo):
            raise InputRangeError("slope", slope, f"below {2.0 * lam * g(lo) / lo ** 2!r} "
                                  "(steeper, the loaded length leaves the line law)")
        lc = brentq(lambda x: 0.5 * s * x * x - lam * g(x), lo, length, xtol=1e-13 * length,
                    rtol=1e-13)
        d = s * lc
        area = 0.5 * s * lc * lc
    peak = w * d / area
    p_h, _ = line_contact_terms(b_max, peak, 1.0, e_prime)
    return EndLoadedLine(loaded_length_mm=lc, approach_mm=d, peak_line_load_n_per_mm=peak,
                         face_load_factor=peak * length / w, end_loaded=lc < length,
                         hertz_pressure_mpa=p_h)
