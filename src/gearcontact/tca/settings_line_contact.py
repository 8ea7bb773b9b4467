"""Line contact of machine settings before ``design --machine-settings`` writes them:
settings that cut the pinion without crowning (docs/machine_settings.md sec. 4, "Uncrowned
settings in `design`").

A pinion cut by the generating surface complementary to the gear's, with the exact
ratio of roll and no crowning of its own, is conjugate to the gear: the flanks touch
along a line (Litvin & Fuentes 2004, sec. 9.3). ``tca`` reports that line; the loaded
commands (``analyze``, ``ltca``, ``lte``, ``twin``, ``sweep``, ``bending``'s load,
``export fmu``) refuse the pair, because there is no contact ellipse to load
(:class:`~.line_contact.LineContact`, found by the TCA where B- at its reference point is
below :data:`~.line_contact.LINE_CURVATURE_PER_MM`). ``design`` does not refuse such
settings: a conjugate pair is a valid request (a reference for ``tca``, flanks for CAD),
and what the TCA finds on it is a result, not an input error. It measures them with the
same TCA the loaded commands run (:func:`settings_line_contact`) and says so on stderr,
in the written file's head comment and in ``run.json``, with the refusal's own text
(which names the crowning to give).

The check runs only where the settings are uncrowned by construction (the caller says
which sides: both crowning options below :data:`UNCROWNED_UM`, or a side fitted to a zero
ease-off); a crowned pinion has B- of order 1e-5 1/mm per um of crowning, four orders
above the bound, and pays nothing.

References
----------
F. L. Litvin, A. Fuentes, *Gear Geometry and Applied Theory*, 2nd ed., 2004, sec. 9.3.
"""

from __future__ import annotations

from ..geometry.flank import build_flanks
from ..geometry.formate import SIDES
from ..geometry.generation import check_generation
from .analysis import analyze_pair
from .edges import ContactGap, PatternOffFlank
from .line_contact import LineContact
from .settings_gap import GAP_CHECK_PAIRS, GAP_CHECK_PHASES

__all__ = ["UNCROWNED_UM", "settings_line_contact"]

#: Crowning (both options, um) below which ``design`` runs the check: 1 um of crowning
#: gives B- ~1e-5 1/mm (:data:`~.line_contact.LINE_CURVATURE_PER_MM`'s reason), so 1 nm
#: gives ~1e-8, ten times the bound; every crowning the TCA could find in line contact
#: is checked (0 typed, or 1e-300 typed).
UNCROWNED_UM = 1e-3


def settings_line_contact(cut, *, sides=SIDES, phases: int = GAP_CHECK_PHASES,
                          pairs: int = GAP_CHECK_PAIRS) -> dict[str, LineContact]:
    """The sides of ``cut`` (a pair cut from machine settings) on which the TCA finds
    line contact, as ``tca`` runs it (``phases`` per pitch, ``pairs`` neighbour pairs,
    edge contact followed: the verdict the loaded commands give on the written file).

    Parameters
    ----------
    cut : GearPair
        The pair with the machine settings about to be written.
    sides : tuple of str, keyword-only
        The sides to run (each one TCA after one flank build).
    phases, pairs : int, keyword-only
        As ``tca --phases`` / ``--pairs`` (defaults: ``tca``'s).

    Returns
    -------
    dict
        ``{side: LineContact}`` (the exception the loaded commands raise, its message
        naming the side, B- and the crowning to give); a side in point contact (its
        mesh, a gap or a bearing off the flank included) is absent.
    """
    flanks = build_flanks(cut, checked=check_generation(cut, contact_ratio=False))
    found = {}
    for side in sides:
        try:
            analyze_pair(cut, side=side, phases=phases, pairs=pairs, flanks=flanks)
        except LineContact as line:
            found[side] = line
        except (ContactGap, PatternOffFlank):
            # point contact after all, whose gap or bearing `tca` reports on the written
            # file (the design-side gap is refused by tca.settings_gap beforehand)
            continue
    return found
