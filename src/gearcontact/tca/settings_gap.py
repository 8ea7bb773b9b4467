"""The mesh gap of machine settings before ``design --machine-settings`` writes them:
the TCA that ``tca`` runs on the settings (docs/machine_settings.md sec. 5, "The
contact-ratio check of machine settings").

Where the blank's predicted contact path (the conjugate pinion with the synthesis'
first-order bearing, :func:`~gearcontact.geometry.contact_path.path_contact_ratio`)
covers fewer than :data:`~gearcontact.geometry.contact_ratio.MIN_CONTACT_RATIO` pitches,
the prediction cannot say whether the settings' own bearing leaves a gap (measured on a
family of 52 pairs: gapped and gap-free pairs overlap at eps_p 0.303-0.551, docs sec.
5). There :func:`check_settings_gap` runs the settings' TCA itself -- the flanks as
every command builds them (:func:`~.synthesis.prepare_pair`), then
:func:`~.analysis.analyze_pair` with ``tca``'s defaults (:data:`GAP_CHECK_PHASES`
phases per pitch, :data:`GAP_CHECK_PAIRS` neighbour pairs, edge contact followed) -- and
refuses settings whose mesh has a gap (:class:`~.edges.ContactGap`), before they are
written. The check is then ``tca``'s own verdict, not a prediction; a coarser count was
measured and not taken (docs sec. 5: the flank build is 73-91 % of the check's cost,
and the narrowest gap measured covers 4 of 120 phase steps of a pitch).

A pair whose prediction reaches the threshold pays nothing: no TCA is run.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from tqdm import tqdm

from ..geometry.contact_path import PathContactRatio, path_contact_ratio
from ..geometry.contact_ratio import MIN_CONTACT_RATIO, virtual_contact_ratio
from ..geometry.flank import right_hand_twin
from ..geometry.generation import check_generation
from ..validation import InputRangeError
from .analysis import analyze_pair
from .edges import ContactGap
from .line_contact import LineContact
from .synthesis import prepare_pair

__all__ = ["GAP_CHECK_PAIRS", "GAP_CHECK_PHASES", "MeshGap", "SettingsGapCheck",
           "check_settings_gap", "settings_mesh_gap"]

#: Phases per pitch of the check: ``tca``'s default (61, both ends), so that the check
#: is the verdict ``tca`` gives on the written file. Not a coarser count: the phases cost
#: 0.23-0.87 s CPU of the check's 2-4 s (the flank build is the rest; 31 phases would
#: save 2-13 %), the continuation takes 30 substeps per pitch below 31 phases anyway
#: (:data:`~.mesh.CONTINUATION_STEPS_PER_PITCH`), and the narrowest gaps measured on the
#: family cover 4 of 120 phase steps, 2 of 60, 1 of 30: 15 steps miss three of the 14
#: gaps (docs/machine_settings.md sec. 5, "The settings' own TCA in `design`").
GAP_CHECK_PHASES = 61
#: Neighbour tooth pairs on each side: ``tca``'s default.
GAP_CHECK_PAIRS = 3


@dataclass(frozen=True)
class MeshGap:
    """The TCA's measured mesh of machine settings (:func:`settings_mesh_gap`).

    Attributes
    ----------
    gap_phases : int
        Phase steps of the pitch at which no tooth pair touches (0: no gap).
    phases_per_pitch : int
        Phase steps per pitch of the run.
    phi1_deg : float or None
        First pinion phase without a contact, deg (None: no gap).
    mean_pairs_in_contact : float or None
        Mean number of pairs in contact over the pitch (None: a gap, the run stopped;
        or line contact).
    """

    gap_phases: int
    phases_per_pitch: int
    phi1_deg: float | None
    mean_pairs_in_contact: float | None

    @property
    def pitch_fraction(self) -> float:
        """The share of the pitch without a contact (1), ``gap_phases / phases_per_pitch``
        (the gap's width to one phase step)."""
        return self.gap_phases / self.phases_per_pitch


@dataclass(frozen=True)
class SettingsGapCheck:
    """What :func:`check_settings_gap` found on settings it did not refuse.

    Attributes
    ----------
    predicted : PathContactRatio
        The blank's predicted contact path (the TCA runs below ``MIN_CONTACT_RATIO``).
    mesh : MeshGap or None
        The settings' TCA (no gap), or None where the prediction did not call for it.
    """

    predicted: PathContactRatio
    mesh: MeshGap | None

    def line(self) -> str | None:
        """One line for ``design``'s stderr where the TCA ran, else None."""
        if self.mesh is None:
            return None
        pairs = ("line contact" if self.mesh.mean_pairs_in_contact is None else
                 f"{self.mesh.mean_pairs_in_contact:.2f} tooth pairs in contact on mean")
        return (f"the blank's predicted contact ratio eps_p = {self.predicted.total:.3f} < "
                f"{MIN_CONTACT_RATIO:g}: the TCA of the settings ({self.mesh.phases_per_pitch + 1} "
                f"phases, edge contact followed, as `tca` runs it) has no gap ({pairs})")


def settings_mesh_gap(pair, *, phases: int = GAP_CHECK_PHASES, pairs: int = GAP_CHECK_PAIRS,
                      progress=None) -> MeshGap:
    """The mesh of ``pair`` (cut from machine settings) as ``tca`` measures it on its
    design side: the flanks of :func:`~.synthesis.prepare_pair` (its generation check
    without the contact-ratio check, which this replaces), then
    :func:`~.analysis.analyze_pair` with edge contact followed.

    Parameters
    ----------
    pair : GearPair
        A pair cut from machine settings.
    phases, pairs : int, keyword-only
        As ``tca --phases`` / ``--pairs``.
    progress : tqdm, optional
        A bar advanced by one after the flanks and one after the mesh.

    Returns
    -------
    MeshGap
        ``gap_phases`` 0 where every phase has a pair in contact.
    """
    prepared = prepare_pair(pair, checked=check_generation(pair, contact_ratio=False))
    flanks = prepared.flank_set()
    if progress is not None:
        progress.update(1)
    try:
        result, _ = analyze_pair(prepared.pair, phases=phases, pairs=pairs, flanks=flanks)
    except ContactGap as gap:
        return MeshGap(gap.gap_phases, gap.phases_per_pitch, math.degrees(gap.phi1_rad), None)
    except LineContact:       # conjugate flanks: every contact line is in contact
        return MeshGap(0, phases - 1, None, None)
    finally:
        if progress is not None:
            progress.update(1)
    return MeshGap(0, phases - 1, None, float(result.cycle.pairs_in_contact[:-1].mean()))


def check_settings_gap(blank, cut, *, boxes: dict, progress: bool = False) -> SettingsGapCheck:
    """``design --machine-settings``' contact-ratio check of the settings ``cut`` about to
    be written for ``blank`` (docs/machine_settings.md sec. 5): the blank's predicted
    contact path (``boxes``: its :func:`~gearcontact.geometry.generation.check_generation`
    result); below :data:`~gearcontact.geometry.contact_ratio.MIN_CONTACT_RATIO` the
    settings' own TCA (:func:`settings_mesh_gap`), a gap refused.

    Parameters
    ----------
    blank : GearPair
        The pair without machine settings (its design fields are named); its ease-off
        table, where it has one, is the predicted bearing
        (:func:`~gearcontact.geometry.contact_path.path_contact_ratio`).
    cut : GearPair
        ``blank`` cut from the settings about to be written (standard, a typed gear with
        its standard pinion, the local synthesis', or the fit of ``blank``'s ease-off:
        ``cli.design_modes.refuse_gap``).
    boxes : dict, keyword-only
        ``check_generation(blank, contact_ratio=False)``.
    progress : bool, keyword-only
        A tqdm bar on stderr while the TCA runs.

    Returns
    -------
    SettingsGapCheck

    Raises
    ------
    InputRangeError
        The settings' mesh has a gap: names ``design.gear_face_width_mm /
        design.pinion_spiral_angle_deg``, the gap (phase steps, share of a pitch), the
        prediction and the fixes measured on the family.
    """
    twin = right_hand_twin(blank) if blank.pinion_hand == "left" else blank
    predicted = path_contact_ratio(twin, boxes=boxes)
    if predicted.total >= MIN_CONTACT_RATIO:
        return SettingsGapCheck(predicted, None)
    with tqdm(total=2, desc="design: the TCA of the settings", unit="step",
              disable=not progress, leave=False) as bar:
        mesh = settings_mesh_gap(cut, progress=bar)
    if mesh.gap_phases == 0:
        return SettingsGapCheck(predicted, mesh)
    v = virtual_contact_ratio(blank.blank, gear_face_width_mm=blank.gear_face_width_mm,
                              side=blank.design_side)
    raise InputRangeError(
        "design.gear_face_width_mm / design.pinion_spiral_angle_deg",
        (blank.gear_face_width_mm, blank.pinion_spiral_angle_deg),
        f"machine settings whose mesh has no gap: the TCA of these settings "
        f"({mesh.phases_per_pitch + 1} phases, edge contact followed, {GAP_CHECK_PAIRS} "
        f"neighbour pairs, as `tca` runs it) finds no tooth pair in contact on "
        f"{mesh.gap_phases} of {mesh.phases_per_pitch} phase steps of the {blank.design_side} "
        f"side ({mesh.pitch_fraction:.1%} of a pitch, from phi1 = {mesh.phi1_deg:.4f} deg); "
        f"the blank's predicted contact ratio eps_p = {predicted.total:.3f} (leaving through "
        f"the {predicted.ends[0]} and the {predicted.ends[1]}), ISO 10300-1 eps_vg "
        f"{v.total:.3f}, eps_va {v.transverse:.3f}, eps_vb {v.face:.3f}; a wider face, a "
        "smaller spiral angle, a larger working depth factor or more teeth close the gap on "
        "the family measured (docs/machine_settings.md sec. 5; no fix verified here)")
