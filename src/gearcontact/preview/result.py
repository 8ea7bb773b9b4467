"""What a preview answers: :class:`PreviewResult` (one contact) and
:class:`PreviewBatch` (many), the stage-D :data:`MODES` and their law status; every
backend of :mod:`.engine` returns these."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .hertz.formats import DEFAULT_HERTZ_FORM
from .hertz.reference import law_status


#: Stage-D modes a :class:`PreviewResult` names (``mode``).
MODES = ("elliptic", "line", "flagged")


@dataclass(frozen=True)
class PreviewResult:
    """The preview of one contact, whatever backend computed it.

    Attributes
    ----------
    backend : str
        Name of the backend.
    load_n : float
        Normal load W, N.
    A_minus_per_mm, B_minus_per_mm : float
        Half relative principal curvatures that entered stage D, 1/mm, sorted so that
        A- >= B- (the stage-C convention; given, fitted, or decoded from the codes).
    a_mm, b_mm : float
        Contact-ellipse semi-axes, mm (a >= b).
    k : float
        Ellipticity a/b.
    p_max_mpa : float
        Peak Hertzian pressure, MPa.
    angle_deg : float or None
        Stencil path only: direction of the A- axis from the stencil s axis, deg
        (reference backend; None otherwise).
    codes : dict or None
        Raw register codes (golden/rtl): inputs and outputs by name, with Q formats in
        :mod:`.hertz.formats` / :mod:`gearcontact.contract.qformat`.
    flags : tuple of str
        Names of raised datapath flags; empty when valid. Outputs are 0 when flagged.
    cycles : int or None
        Hardware cycles of the evaluated path (golden/rtl), data independent.
    hertz_form : str
        Stage-D Hertz form that produced the result (:data:`.hertz.formats.HERTZ_FORMS`).
    mode : str
        What evaluated stage D (:data:`MODES`): ``"elliptic"`` (Hertz ellipse),
        ``"line"`` (the ellipse is longer than the flank's contact line: Hertz line
        contact of that length, :mod:`.hertz.line`) or ``"flagged"`` (the datapath
        flags the input; outputs 0).
    """

    backend: str
    load_n: float
    A_minus_per_mm: float
    B_minus_per_mm: float
    a_mm: float
    b_mm: float
    k: float
    p_max_mpa: float
    angle_deg: float | None = None
    codes: dict | None = None
    flags: tuple = ()
    cycles: int | None = None
    hertz_form: str = DEFAULT_HERTZ_FORM
    mode: str = "elliptic"

    @property
    def valid(self) -> bool:
        """True when no datapath flag is raised."""
        return not self.flags

    @property
    def law_status(self) -> str:
        """``"ok"`` or ``"beyond_hamrock_brewe_range"``: a Hamrock–Brewe ellipse beyond
        the ratio where its law is within 5 % of exact Hertz (a reported result;
        :func:`.hertz.reference.law_status`, docs/hertz.md sec. 7)."""
        return law_status(self.A_minus_per_mm, self.B_minus_per_mm,
                          hertz_form=self.hertz_form, mode=self.mode)

    def as_dict(self) -> dict:
        """JSON-ready dict (keys a_mm, b_mm, k, p_max_mpa, backend, ...)."""
        return {"backend": self.backend, "load_n": self.load_n,
                "A_minus_per_mm": self.A_minus_per_mm, "B_minus_per_mm": self.B_minus_per_mm,
                "a_mm": self.a_mm, "b_mm": self.b_mm, "k": self.k,
                "p_max_mpa": self.p_max_mpa, "angle_deg": self.angle_deg,
                "codes": self.codes, "flags": list(self.flags), "cycles": self.cycles,
                "hertz_form": self.hertz_form, "mode": self.mode,
                "law_status": self.law_status}


@dataclass(frozen=True)
class PreviewBatch:
    """Previews of many contacts (float64 arrays of one shape; flags as int words,
    0 = valid, 0 everywhere for the reference; ``mode`` a str array of :data:`MODES`,
    what evaluated each element; in line mode ``a_mm`` is L/2 and ``k`` = a/b)."""

    backend: str
    a_mm: np.ndarray
    b_mm: np.ndarray
    k: np.ndarray
    p_max_mpa: np.ndarray
    flags: np.ndarray = field(default=None)
    mode: np.ndarray = field(default=None)


def elliptic_modes(shape, flags=None) -> np.ndarray:
    """The :data:`MODES` array of a batch evaluated by the published (elliptic) core:
    ``"elliptic"``, ``"flagged"`` where ``flags`` (int words) are not 0."""
    mode = np.full(shape, "elliptic", dtype="<U8")
    if flags is not None:
        mode[np.asarray(flags) != 0] = "flagged"
    return mode
