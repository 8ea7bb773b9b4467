"""The bearing the ease-off synthesis will make, predicted before any TCA, for the
contact-ratio check of the commands (docs/geometry.md sec. 7.7, docs/synthesis.md).

A pair whose file has no ease-off table of its design side gets one from the local
synthesis (:mod:`.synthesis`) in every command that analyzes it. ``design``'s
contact-path check (:func:`~gearcontact.geometry.contact_path.path_contact_ratio`, below
tca) must see the bearing that synthesis will make, not a fixed one: where the user
prescribes a path angle the synthesis starts from its first-order design
(:meth:`~.path_reach.PathAngleRange.start`), and where the zero-bias path's surface
contact lasts less than a pinion pitch it turns the path to the reachable angle of the
longest overlap (:func:`~.path_reach.overlap_choice`). :func:`predict_bearing` makes
the same choices without a TCA: the synthesis' start (:func:`synthesis_start`) is
judged by its contact path inside the flanks (eps_p follows the TCA's surface contact
to -0.033 .. +0.002, docs/geometry.md sec. 7.7) instead of the first full TCA, and the
bearing checked is the first-order design of the angle chosen (the synthesis meets it
with crownings within 1-5 % of it, :mod:`.path_reach`). :class:`BearingPredictor`
hands it to :func:`~gearcontact.geometry.generation.check_generation` (``bearing_of``).
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from ..geometry.contact_path import (DEFAULT_BEARING, SYNTHESIS_PATTERN_RATIO,
                                     SYNTHESIS_TE0_ARCSEC, Bearing, path_contact_ratio)
from ..geometry.flank import build_flanks
from ..geometry.pair import EaseOffCoefficients
from .design_point import centred_coefficients, turn_relief
from .path_reach import OVERLAP_MARGIN, check_path_angle, overlap_choice
from .synthesis_targets import SynthesisTargets

__all__ = ["SynthesisStart", "synthesis_start", "predict_bearing", "target_bearing",
           "BearingPredictor"]


@dataclass(frozen=True)
class SynthesisStart:
    """Where the ease-off synthesis of one side starts (:func:`synthesis_start`).

    Attributes
    ----------
    centre_uv_mm : (float, float)
        Target bearing centre (pinion u, v), mm.
    mean_uv_mm : (float, float)
        The pinion's mean node, mm (the ease-off's origin).
    turn : ndarray (5,)
        :func:`~.design_point.turn_relief` at the mean node.
    curvature_scale : float
        ``(12 mm / face)^2``: the crownings scale with it (1).
    x : ndarray (5,)
        The start in the centre form of :func:`~.design_point.centred_coefficients`
        (eta_c, xi_c, mm; profile and lengthwise crowning, bias, um/mm^2).
    """

    centre_uv_mm: tuple
    mean_uv_mm: tuple
    turn: np.ndarray
    curvature_scale: float
    x: np.ndarray

    def coefficients(self, x=None) -> EaseOffCoefficients:
        """The five-term ease-off of ``x`` (default the start), the centre's relief a
        rigid turn."""
        return centred_coefficients(*(self.x if x is None else x), turn=self.turn)


#: Exact grid of the flanks built by :func:`predict_bearing` (the quintic sheet only
#: guesses the exact node solves it uses, and evaluates the rigid turn's lever): 16 x 16
#: gives the default grid's coefficients to 5e-5 relative and the same eps_p to 1e-12
#: (10/15 and 13/13 hypoid of tests/design_space.py, 35 deg, face 0.3 R_m), in 0.4-0.8 s
#: instead of 4.3 s.
_FLANK_GRID = 16


def synthesis_start(pair, *, side: str, targets: SynthesisTargets, flanks) -> SynthesisStart:
    """The start of :func:`~.synthesis.synthesize_easeoff` on ``side``: the bearing
    centre of ``targets`` on the conjugate pinion's active box and, without a path-angle
    target, crownings of 8 and 0.15 ``(12 mm / face)^2`` um/mm^2 without bias (s0003's
    centred design, scaled with the face); with one, its first-order design
    (:meth:`~.path_reach.PathAngleRange.start`; an angle the synthesis cannot reach is
    refused here, :func:`~.path_reach.check_path_angle`).

    Raises
    ------
    InputRangeError
        A path angle the synthesis cannot reach on ``side``.
    """
    conj = flanks.pinion_conjugate.side(side)
    u_m, v_m = (float(x) for x in flanks.mean_contact[side]["pinion_uv"])
    b = conj.boundary
    centre = (b.u_root + targets.centre_profile * (b.u_tip - b.u_root),
              b.v_toe + targets.centre_face * (b.v_heel - b.v_toe))
    k = (12.0 / pair.gear_face_width_mm) ** 2
    eta_c, xi_c = centre[0] - u_m, centre[1] - v_m
    x = np.array([eta_c, xi_c, 8.0 * k, 0.15 * k, 0.0])
    if targets.path_angle_deg is not None:
        reach = check_path_angle(pair, targets=targets, flanks=flanks, sides=(side,))[side]
        x = np.array([eta_c, xi_c, *reach.start(targets.path_angle_deg)])
    # the relief at the centre is a rigid turn, so that the TE0 vertex stays there
    # (design_point.centred_coefficients)
    return SynthesisStart(centre, (u_m, v_m), turn_relief(conj, (u_m, v_m)), k, x)


def predict_bearing(pair, *, boxes: dict, targets=SynthesisTargets(),
                    side: str | None = None, flanks=None,
                    turns_short_paths: bool = True) -> Bearing | None:
    """The ease-off the synthesis will make on ``side`` (default the design side) of
    ``pair``, to first order, or None where the pair's table stands. ``Bearing(None,
    ...)`` is the synthesis' zero-bias first-order bearing at the targets' TE0 level and
    pattern length (:func:`target_bearing`; at the default targets
    :func:`~gearcontact.geometry.contact_path.path_contact_ratio`'s default for a pair
    without a table).

    As :func:`~.synthesis.synthesize_easeoff` decides (module docstring): a pair with a
    table of ``side`` keeps it (None); a path-angle target gives its first-order design;
    without one, if the start's contact path (:func:`synthesis_start`) covers less than
    a pitch even with one phase step of the synthesis' TCA added (``OVERLAP_MARGIN``),
    the first-order design of the reachable path angle of the longest overlap
    (:func:`~.path_reach.overlap_choice`) if that overlaps, else the zero-bias bearing
    (the synthesis names TE0 unreachable and keeps it); where it covers a pitch, the
    zero-bias bearing. Every first-order bearing is that of the targets' TE0 level and
    pattern length (:func:`target_bearing`; the path-angle designs of
    :mod:`.path_reach` take them too). ``turns_short_paths=False`` for the
    machine-setting synthesis (:mod:`.setting_synthesis`), which does not turn a short
    path: its path-angle target, TE0 level and pattern length are seen.

    Parameters
    ----------
    pair : GearPair
        Right-hand, as :func:`~gearcontact.geometry.generation.check_generation` checks it.
    boxes : dict
        That check's result for ``pair`` (without the contact ratio).
    targets : SynthesisTargets or mapping side -> SynthesisTargets
    flanks : FlankSet, optional
        ``build_flanks(pair)``, if already built (else built here on a ``_FLANK_GRID``
        grid).

    Raises
    ------
    InputRangeError
        A path-angle target the synthesis cannot reach on ``side``.
    """
    side = pair.design_side if side is None else side
    if side in pair.easeoff_tables:
        return None
    t = targets[side] if isinstance(targets, Mapping) else targets
    zero_bias = target_bearing(t)
    if t.path_angle_deg is None and not turns_short_paths:
        return zero_bias
    if flanks is None:
        flanks = build_flanks(pair, n_u=_FLANK_GRID, n_v=_FLANK_GRID, checked=boxes)
    start = synthesis_start(pair, side=side, targets=t, flanks=flanks)
    if t.path_angle_deg is not None:
        return Bearing(start.coefficients(), "the synthesis' first-order bearing along "
                       f"the path angle {t.path_angle_deg:g} deg")
    first = path_contact_ratio(pair, boxes=boxes, side=side,
                               bearing=Bearing(start.coefficients(), "the synthesis' start"))
    if first.total + OVERLAP_MARGIN >= 1.0:
        return zero_bias
    angle, ratio, overlaps = overlap_choice(pair, side=side, targets=t, flanks=flanks)
    if not overlaps:
        return dataclasses.replace(
            zero_bias, source=f"{zero_bias.source} (TE0 unreachable: its start's path "
            f"covers {first.total:.2f} pitch, "
            + (f"the longest reachable overlap {ratio:.2f}" if math.isfinite(ratio) else
               "no path angle reachable")      # overlap_path_angle's NaN: no angle
            + ", docs/synthesis.md)")
    turned = synthesis_start(pair, side=side, flanks=flanks,
                             targets=dataclasses.replace(t, path_angle_deg=angle))
    return Bearing(turned.coefficients(), "the synthesis' first-order bearing along the "
                   f"overlap path angle {angle:.1f} deg (its zero-bias start's path covers "
                   f"{first.total:.2f} pitch, the turned one {ratio:.2f} to first order)")


def target_bearing(targets: SynthesisTargets) -> Bearing:
    """The synthesis' zero-bias first-order bearing at the TE0 level and pattern length
    of ``targets`` (:class:`~gearcontact.geometry.contact_path.Bearing` without
    coefficients: the contact path builds it on the pair's box); at the default targets
    its source is :data:`~gearcontact.geometry.contact_path.DEFAULT_BEARING`."""
    te0, ratio = float(targets.te0_pp_arcsec), float(targets.pattern_length_ratio)
    if (te0, ratio) == (SYNTHESIS_TE0_ARCSEC, SYNTHESIS_PATTERN_RATIO):
        return Bearing(None, DEFAULT_BEARING)
    return Bearing(None, f"the synthesis' first-order bearing at TE0 {te0:g} arcsec and a "
                   f"pattern {ratio:g} x the face", te0_pp_arcsec=te0,
                   pattern_length_ratio=ratio)


class BearingPredictor:
    """:func:`predict_bearing` with fixed ``targets``, as the ``bearing_of`` of
    :func:`~gearcontact.geometry.generation.check_generation` (called with each pair it
    checks: the pair, then the trial pairs of a fix)."""

    def __init__(self, targets=SynthesisTargets(), *, turns_short_paths: bool = True):
        self.targets = targets
        self.turns_short_paths = turns_short_paths

    def __call__(self, pair, boxes) -> Bearing | None:
        return predict_bearing(pair, boxes=boxes, targets=self.targets,
                               turns_short_paths=self.turns_short_paths)
