"""Conjugate flanks (zero ease-off, no assembly errors): line contact, reported.

The pinion flanks are generated conjugate to the gear flanks (equation of meshing,
:mod:`gearcontact.geometry.conjugate`), so without an ease-off and mounted without
errors the two flanks touch along a *line* at every phase and the transmission error
vanishes identically (Litvin & Fuentes 2004, sec. 9.3 and ch. 15: a mismatch is what
turns the line into a point and gives the parabolic TE). The point-contact Newton solve
of :mod:`.solve` is singular there (a one-parameter family of solutions), so TCA does
not run it: :func:`line_contact` follows the contact line instead, with the phase and
the gear's lengthwise parameter ``v2`` both held (five equations in four unknowns,
consistent on the line, solved by Gauss-Newton), and checks ``TE0 = 0`` along the
pitch. The result is reported as :class:`LineContact`, an error for the loaded stages
(no contact ellipse; the pair needs an ease-off) and a result for ``gearcontact tca``.

References
----------
F. L. Litvin, A. Fuentes, *Gear Geometry and Applied Theory*, 2nd ed., 2004,
sec. 9.3 (line contact of conjugate surfaces), ch. 15.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from ..geometry.kinematics import MeshKinematics
from ..geometry.surface import Surface
from ..validation import InputRangeError, UnusableInput
from .mating import solve_mating_point
from .types import ARCSEC_PER_RAD, ContactGuess, EdgeContact, TcaConvergenceError

__all__ = ["CROWNING_ADVICE", "LINE_TOLERANCE_MM", "LINE_CURVATURE_PER_MM", "LineContactResult", "LineContact", "line_contact", "is_conjugate",
           "found_line_contact", "check_loadable"]

#: Residual tolerance of the contact-line solve, mm: the pinion sheets interpolate the
#: exact conjugate nodes with C2 quintic splines, so the flanks are conjugate only to
#: the interpolation accuracy (residuals ~1e-9 mm measured on s0003), not to 1e-10 mm.
LINE_TOLERANCE_MM = 1e-7

#: Below this smaller relative curvature B- at the reference point, 1/mm, the
#: point-contact TCA has found line contact (flanks cut from machine settings are not
#: known to be conjugate beforehand): the sheets' interpolation leaves B- ~1e-12 1/mm on
#: a conjugate pair (5.2e-13 measured on F.2's uncrowned standard settings), while 1 um
#: of crowning over a 30 mm face already gives ~1e-5 1/mm. At 1e-9 the paint ellipse
#: would be metres long. (The point solve's TE0 is no test there: singular on the line,
#: it gave 1.4e-4 arcsec p-p on that pair; the line's own TE0 is reported.)
LINE_CURVATURE_PER_MM = 1e-9

#: What to do with line contact the TCA found (:class:`LineContact`'s message, and
#: ``design``'s note on the uncrowned settings it writes,
#: :mod:`.settings_line_contact`).
CROWNING_ADVICE = ("Crown the pinion: an ease-off, or for machine settings `gearcontact "
                   "design --machine-settings` with its crowning options, modified roll or "
                   "a curved blade (docs/machine_settings.md).")


@dataclass(frozen=True)
class LineContactResult:
    """Line contact of a conjugate flank pair.

    Attributes
    ----------
    phi1_rad : ndarray (K,)
        Phases of one pinion pitch, rad.
    te0_arcsec : ndarray (K,)
        TE0 at the middle of the contact line at each phase, arcsec (0 up to the
        interpolation accuracy of the flanks).
    line_mm : ndarray (N, 3)
        Points of the contact line at the mean phase, meshing frame, mm (toe -> heel).
    line_length_mm : float
        Length of that line inside both flanks (polyline), mm.
    te0_max_abs_arcsec : float
        Largest |TE0| over the pitch, arcsec.
    """

    phi1_rad: np.ndarray
    te0_arcsec: np.ndarray
    line_mm: np.ndarray
    line_length_mm: float
    te0_max_abs_arcsec: float

    def as_dict(self) -> dict:
        return {"line_contact": True, "te0_max_abs_arcsec": self.te0_max_abs_arcsec,
                "line_length_mm": self.line_length_mm,
                "phi1_deg": [float(x) for x in np.degrees(self.phi1_rad)],
                "te0_arcsec": [float(x) for x in self.te0_arcsec],
                "line_mm": [[float(c) for c in p] for p in self.line_mm]}


class LineContact(UnusableInput):
    """The flanks are conjugate: line contact, TE0 = 0 (see the module docstring).

    Attributes
    ----------
    result : LineContactResult
    """

    def __init__(self, result: LineContactResult, *, side: str = "",
                 found: float | None = None):
        self.result = result
        self.found = found
        where = f"line contact{f' on the {side} side' if side else ''}: "
        line = (f"TE0 = 0 within {max(result.te0_max_abs_arcsec, 1e-9):.1e} arcsec, contact "
                f"line {result.line_length_mm:.2f} mm long); there is no contact ellipse to "
                "load. ")
        if found is None:
            super().__init__(where + "zero ease-off and no assembly errors make the flanks "
                             "conjugate (" + line + "Give an [easeoff.*] table, or omit it "
                             "to have one synthesized.")
        else:
            super().__init__(
                where + f"the TCA found the flanks touching along a line (smaller relative "
                f"curvature B- {found:.1e} 1/mm at the mean point; along the pitch "
                + line + CROWNING_ADVICE)


def is_conjugate(pair, side: str) -> bool:
    """True if ``side`` of ``pair`` has zero ease-off and no assembly errors (flanks cut
    from machine settings, ``pair.machine``, are not known to be conjugate: False)."""
    if getattr(pair, "machine", ()):
        return False
    c = dataclasses.astuple(getattr(pair, f"easeoff_{side}"))
    a = pair.assembly
    return (not any(c)) and not any((a.E_mm, a.P_mm, a.G_mm, a.alpha_deg))


def found_line_contact(b_minus_per_mm: float) -> bool:
    """True if a point-contact TCA's smaller relative curvature B- at its reference
    point says the flanks touch along a line there (:data:`LINE_CURVATURE_PER_MM`):
    line contact found, not known beforehand."""
    return abs(float(b_minus_per_mm)) <= LINE_CURVATURE_PER_MM


def check_loadable(pair, side: str) -> None:
    """Refuse, before any flank work, to load ``side`` of ``pair`` when the pair file
    gives that side a zero ease-off and no assembly errors (:func:`is_conjugate`): the
    TCA would find line contact (:class:`LineContact`), which has no contact ellipse to
    load. A side without an ``[easeoff.<side>]`` table passes (its ease-off is
    synthesized, :func:`~gearcontact.tca.synthesis.prepare_pair`).

    Raises
    ------
    InputRangeError
        Naming the table, its value and the two ways out.
    """
    if side in getattr(pair, "easeoff_tables", ()) and is_conjugate(pair, side):
        raise InputRangeError(f"[easeoff.{side}]", "all coefficients 0, no assembly errors",
                              "a non-zero ease-off, or no [easeoff.%s] table to have one "
                              "synthesized (zero ease-off makes the flanks conjugate: line "
                              "contact, no contact ellipse to load)" % side)


def _line_point(pinion, gear, kin, guess: ContactGuess):
    return solve_mating_point(pinion, gear, kin, guess, fixed=("phi1", "v2"),
                              tol_mm=LINE_TOLERANCE_MM)


#: Sections of the gear face tried for the line's first point at a start's phase.
_START_SECTIONS = 9


def _first_line_point(pinion, gear, kin, starts):
    """The line's point at the first of ``starts`` (phase and ``v2`` held) on both
    flanks; where none is, the line's point at a start's phase through the nearest of
    :data:`_START_SECTIONS` gear face sections that is (a start on a flank edge, e.g. at
    the toe: F.2's coast fitted to a zero ease-off). Raises the first start's error
    where the line misses the flanks at every start's phase."""
    errors = []
    for guess in starts:
        try:
            return _line_point(pinion, gear, kin, guess)
        except (EdgeContact, TcaConvergenceError) as exc:
            errors.append(exc)
    v_lo, v_hi = gear.v_range
    sections = np.linspace(v_lo, v_hi, _START_SECTIONS + 2)[1:-1]
    for guess in starts:
        for v2 in sorted(sections, key=lambda v: abs(v - guess.v2)):
            try:
                return _line_point(pinion, gear, kin, dataclasses.replace(guess, v2=float(v2)))
            except (EdgeContact, TcaConvergenceError):
                continue
    raise errors[0]         # the start's: where the line was asked for


def line_contact(pinion: Surface, gear: Surface, kin: MeshKinematics, start: ContactGuess,
                 *, pinion_teeth: int, phases: int = 61, line_points: int = 25,
                 also: tuple[ContactGuess, ...] = ()) -> LineContactResult:
    """Follow the contact line of conjugate flanks and TE0 over one pitch.

    Parameters
    ----------
    pinion, gear : Surface
    kin : MeshKinematics
    start : ContactGuess
        A contact state on the line (e.g. the conjugate mean contact of
        :func:`~gearcontact.geometry.flank.build_flanks`); its phase is the mean phase.
    pinion_teeth : int
    phases : int
        Phases of the pitch (both ends included), centred on the start phase.
    line_points : int
        Samples of ``v2`` over the gear face for the contact line.
    also : tuple of ContactGuess
        Further starts, tried in turn where the line's point at ``start`` (its phase and
        ``v2``) lies off a flank: the point TCA's reference on line contact is a point
        of the line picked by a singular solve, and can sit beyond a flank edge (F.2's
        uncrowned standard settings, coast: below the pinion root); then the line at
        each start's phase through the gear face's sections (:func:`_first_line_point`).
    """
    ref = _first_line_point(pinion, gear, kin, (start, *also))
    # the contact line at the mean phase: march v2 from the start to each end
    v_lo, v_hi = gear.v_range
    line = {0.0: ref.point_mm}
    for end in (v_lo, v_hi):
        prev = ref.as_guess()
        for v2 in np.linspace(ref.v2, end, int(line_points) // 2 + 1)[1:]:
            try:
                mp = _line_point(pinion, gear, kin, dataclasses.replace(prev, v2=float(v2)))
            except (EdgeContact, TcaConvergenceError):
                break
            prev = mp.as_guess()
            line[float(v2 - ref.v2)] = mp.point_mm
    pts = np.array([line[k] for k in sorted(line)])
    length = float(np.linalg.norm(np.diff(pts, axis=0), axis=1).sum())
    # TE0 along the pitch at the middle of the line (v2 held), continued in phase
    step = 2.0 * np.pi / int(pinion_teeth) / (int(phases) - 1)
    ks = np.arange(int(phases)) - (int(phases) - 1) // 2
    te = np.full(len(ks), np.nan)
    for direction in (+1, -1):
        prev = ref.as_guess()
        for k in (ks[ks >= 0] if direction > 0 else ks[ks < 0][::-1]):
            phi1 = ref.phi1_rad + k * step
            guess = dataclasses.replace(prev, phi1_rad=phi1,
                                        phi2_rad=prev.phi2_rad + (phi1 - prev.phi1_rad) / kin.ratio)
            try:
                mp = _line_point(pinion, gear, kin, guess)
            except (EdgeContact, TcaConvergenceError):
                break
            prev = mp.as_guess()
            te[np.flatnonzero(ks == k)[0]] = ARCSEC_PER_RAD * (
                (mp.phi2_rad - ref.phi2_rad) - (mp.phi1_rad - ref.phi1_rad) / kin.ratio)
    finite = te[np.isfinite(te)]
    return LineContactResult(ref.phi1_rad + step * ks, te, pts, length,
                             float(np.max(np.abs(finite))) if finite.size else float("nan"))
