"""The typed-settings check of a pair as it is loaded: a bevel pair cut from machine
settings (``[machine.*]`` / ``[blade.*]`` tables) against its own blank tables
(:func:`~.blank_check.check_pair_blank`), run once before any flank work by the library
entry point that takes the pair (:func:`gearcontact.tca.synthesis.prepare_pair`, the
one pair preparation of every pair command and of
:func:`gearcontact.report.analyze.run_analysis`; the library calls that build a raw
pair's flanks when given none, :func:`checked_settings`), or by the caller who hands
its result in (the command line runs it in its argument check;
docs/machine_settings.md sec. 2, "The check when a pair is loaded").

A gross mismatch (a hand, a generating spiral angle or pressure angle far off, a
generating mean point off the gear's face: the flanks are not the blank's tooth) raises :class:`~gearcontact.validation.InputRangeError`
naming the likely key; any other flank outside its tolerance is a warning naming the
flank, the measured and stated values and the likely key
(:attr:`SettingsCheck.warnings`), and the work goes on. Where the warnings go is the
caller's: the library emits them as :class:`SettingsWarning` (:meth:`SettingsCheck.warn`),
the command line prints them on stderr, ``analyze`` repeats them in summary.md.

After the comparison with the blank the check measures each pinion flank's ease-off
against the typed gear's conjugate pinion (:func:`~.easeoff_shape.check_easeoff_shape`,
a different check: not against the blank); a flank hollow beyond its bound is a warning
line of its own (:attr:`SettingsCheck.hollow_warnings`: edge contact expected), emitted
as :class:`~.easeoff_shape.HollowEaseOffWarning` (docs/machine_settings.md sec. 2, "The
hollow ease-off warning"). A generated gear's pinions are measured after the reader's
generation check (:func:`~.generation.check_generation`), on the gear boxes it traces
(:func:`completed_settings`, run by :func:`~gearcontact.tca.synthesis.prepare_pair`):
the same verdict as ``design``'s, which traces them itself.
"""

from __future__ import annotations

import dataclasses
import time
import warnings
from dataclasses import dataclass, field

from ..validation import InputRangeError
from .blank_check import check_pair_blank
from .blank_verdict import BlankCheck, slip_renamed
from .easeoff_shape import EaseOffShapeCheck, check_easeoff_shape
from .edge_check import check_edge_rounds
from .flank_angles import measure_pair_mean_points

__all__ = ["SettingsCheck", "SettingsWarning", "check_settings", "checked_settings",
           "completed_settings"]


class SettingsWarning(UserWarning):
    """A flank cut from a pair's typed machine settings does not agree with its blank
    (not gross: the work goes on on the flanks the settings cut)."""


@dataclass(frozen=True)
class SettingsCheck:
    """The result of :func:`check_settings` on a pair cut from machine settings.

    Attributes
    ----------
    blank : BlankCheck
        Every flank's comparison with the blank (:func:`~.blank_check.check_pair_blank`).
    warnings : tuple of str
        One line per flank outside its tolerance, naming the likely key
        (:meth:`~.blank_verdict.BlankCheck.warnings`, each ``"warning: ..."``); empty when
        every flank agrees (a hollow pinion flank's lines are
        :attr:`hollow_warnings`).
    seconds : float
        Wall time of the check, s (a timing: run.json only; not compared).
    easeoff : EaseOffShapeCheck or None
        The pinion flanks' ease-off shapes against the typed gear's conjugate
        (:func:`~.easeoff_shape.check_easeoff_shape`; None without pinion settings).
    """

    blank: BlankCheck
    warnings: tuple[str, ...]
    seconds: float = field(default=0.0, compare=False)
    easeoff: EaseOffShapeCheck | None = None

    @property
    def agrees(self) -> bool:
        """Every flank agrees with the blank within its tolerance."""
        return self.blank.agrees

    @property
    def hollow_warnings(self) -> tuple[str, ...]:
        """One line per pinion flank hollow beyond its bound
        (:meth:`~.easeoff_shape.EaseOffShapeCheck.warnings`, each ``"warning: ..."``)."""
        return () if self.easeoff is None else self.easeoff.warnings()

    def warn(self, *, stacklevel: int = 2) -> None:
        """Emit each of :attr:`warnings` as a :class:`SettingsWarning`, then each of
        :attr:`hollow_warnings` as a :class:`~.easeoff_shape.HollowEaseOffWarning`
        (without the ``"warning: "`` prefix); ``stacklevel`` as :func:`warnings.warn`'s,
        counted from the caller of this method."""
        for line in self.warnings:
            warnings.warn(line.removeprefix("warning: "), SettingsWarning,
                          stacklevel=stacklevel + 1)
        if self.easeoff is not None:
            self.easeoff.warn(stacklevel=stacklevel + 1)


def check_settings(pair, *, measured=None, easeoff_generated: bool = False,
                   on_blank=None) -> SettingsCheck | None:
    """The typed-settings check of ``pair`` (module docstring): None for a pair without
    machine settings (a cylindrical pair has none), else its :class:`SettingsCheck`.
    Nothing is printed or warned here (:meth:`SettingsCheck.warn`). Validate, then
    compute: the comparison with the blank (its refusal, its warnings) comes before any
    flank work, which is the ease-off shape's (its flanks; docs/machine_settings.md
    sec. 2, "The order of the check").

    Parameters
    ----------
    pair : GearPair
    measured : tuple of FlankMeanPoint, optional
        The pair's :func:`~.flank_angles.measure_pair_mean_points`, when already
        measured (``design`` prints them): no flank is measured again.
    easeoff_generated : bool
        Measure the ease-off of pinions whose gear is generated too
        (:func:`~.easeoff_shape.check_easeoff_shape` with ``generated=True``: about 0.55 s
        CPU a pair, against 0.18 s for a formate gear's; ``design`` measures them so). By
        default they are left to :func:`completed_settings` (``deferred``), which measures
        them on the gear boxes the reader's generation check traces anyway.
    on_blank : callable, optional
        Called with the check as it stands before the ease-off shape's flank work (its
        :attr:`SettingsCheck.blank` and :attr:`SettingsCheck.warnings`, ``easeoff``
        None), so that the caller shows the blank's warnings first; an error of that work
        can then be named by them (``cli.settings_slip``) without measuring again.

    Raises
    ------
    InputRangeError
        A gross mismatch, naming the likely key
        (:meth:`~.blank_verdict.BlankCheck.raise_if_gross`); a blade edge round that ends
        above its flank's mean point (:func:`~.edge_check.check_edge_rounds`), named by
        the likely slip of a flank off its blank where there is one
        (:func:`~.blank_verdict.slip_renamed`: a sliding base typed in inches puts the
        mean point in the round, docs/machine_settings.md sec. 2). The
        ease-off shape is measured after both (a flank it cannot measure is named in
        its ``missing``, never raised).
    """
    if not getattr(pair, "machine", None):
        return None
    t0 = time.perf_counter()
    measured = measured if measured is not None else measure_pair_mean_points(pair)
    got = check_pair_blank(pair, measured=measured)
    got.raise_if_gross()
    blank = SettingsCheck(got, tuple(got.warnings()), time.perf_counter() - t0)
    if on_blank is not None:
        on_blank(blank)
    try:
        check_edge_rounds(pair.machine, measured)
    except InputRangeError as exc:      # a slip's consequence: named by the slip
        raise slip_renamed(exc, got, failed="the check of its flanks") from None
    shape = check_easeoff_shape(pair, generated=easeoff_generated)     # the flank work
    return dataclasses.replace(blank, seconds=time.perf_counter() - t0, easeoff=shape)


def checked_settings(pair, *, stacklevel: int = 2, deferred: bool = False
                     ) -> SettingsCheck | None:
    """:func:`check_settings` of ``pair`` with its warnings emitted as
    :class:`SettingsWarning`, before the ease-off shape's flank work, and a hollow pinion
    flank's after it as :class:`~.easeoff_shape.HollowEaseOffWarning` (``stacklevel``
    counted from the caller of this function):
    what a library call runs where it takes a pair and builds its flanks itself
    (:func:`~gearcontact.tca.synthesis.prepare_pair`, and
    :func:`~gearcontact.tca.analysis.analyze_pair`,
    :func:`~gearcontact.structure.compliance.flank_compliance`,
    :func:`~gearcontact.sweep.run.run_sweep`,
    :func:`~gearcontact.export.flanks.export_flanks` when given no flanks: flanks handed
    in were built by the caller, a prepared pair's after this check).

    A generated gear's pinions are measured here as ``design`` measures them
    (``easeoff_generated``, the gear boxes traced: the same verdict as
    :func:`completed_settings` on the reader's boxes, bit for bit), unless ``deferred``:
    the caller runs the pair's generation check next and completes the check on its gear
    boxes (:func:`completed_settings`; :func:`~gearcontact.tca.synthesis.prepare_pair`),
    so that the boxes are traced once.

    Raises
    ------
    InputRangeError
        A gross mismatch, naming the likely key.
    """
    def first(blank: SettingsCheck) -> None:    # called by check_settings, called here
        blank.warn(stacklevel=stacklevel + 3)

    got = check_settings(pair, easeoff_generated=not deferred, on_blank=first)
    if got is not None and got.easeoff is not None:
        got.easeoff.warn(stacklevel=stacklevel + 1)
    return got


def completed_settings(pair, check: SettingsCheck | None, boxes: dict, *,
                       warn: bool = True, stacklevel: int = 2) -> SettingsCheck | None:
    """``check`` (:func:`check_settings` of ``pair``) with the pinion ease-off of its
    generated gear flanks measured (its ``easeoff.deferred`` sides,
    :func:`~.easeoff_shape.check_easeoff_shape`) on the gear boxes of ``boxes``, the
    reader's :func:`~.generation.check_generation` result for ``pair`` (its
    ``"gear_box"``: the box ``design``'s own measurement traces, the same bit for bit, so
    the verdict is ``design``'s; docs/machine_settings.md sec. 2, "The hollow ease-off
    warning"). Their hollow lines are emitted as
    :class:`~.easeoff_shape.HollowEaseOffWarning` (``warn``; ``stacklevel`` counted from
    the caller of this function). ``check`` itself where nothing was deferred (no
    settings, a formate gear, or measured already).
    """
    shape = None if check is None else check.easeoff
    if shape is None or not shape.deferred:
        return check
    t0 = time.perf_counter()
    gear_boxes = {side: boxes[side]["gear_box"] for side in shape.deferred
                  if "gear_box" in boxes.get(side, {})}
    more = check_easeoff_shape(pair, gear_boxes=gear_boxes if len(gear_boxes) == len(
        shape.deferred) else None, sides=shape.deferred)
    if warn:
        more.warn(stacklevel=stacklevel + 1)
    return dataclasses.replace(check, easeoff=shape.completed(more),
                               seconds=check.seconds + time.perf_counter() - t0)
