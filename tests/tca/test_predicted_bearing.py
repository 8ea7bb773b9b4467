"""The bearing the ease-off synthesis will make, predicted for ``design``'s contact-path
check (gearcontact.tca.predicted_bearing; docs/geometry.md sec. 7.7, docs/synthesis.md).

Truths: the TCA of the eased flanks (the mesh cycle: the run of one pair's surface
mating points, an independent computation from the contact path's Lagrange points) of
the predicted bearing and of the ease-off the synthesis makes; ``analyze`` exits 0 on
the pairs the prediction newly accepts; the synthesis names TE0 unreachable on a pair
the prediction says it will (slow suite: the synthesis of a low-ratio pair takes
minutes).
"""

import json
from dataclasses import replace

import pytest

import gearcontact.tca.predicted_bearing as predicted_bearing
from design_space import bare_candidate, design_space_candidate
from gearcontact.geometry.contact_path import DEFAULT_BEARING, path_contact_ratio
from gearcontact.geometry.contact_ratio import MIN_CONTACT_RATIO, check_contact_ratio
from gearcontact.geometry.generation import check_generation
from gearcontact.geometry.pair import EaseOffCoefficients
from gearcontact.tca.predicted_bearing import BearingPredictor, predict_bearing
from gearcontact.tca.synthesis_targets import SynthesisTargets
from gearcontact.validation import InputRangeError

#: Agreement of eps_p with the TCA's surface count: the path's own (-0.033 .. +0.002
#: against the TCA's interior contact, tests/geometry/test_contact_ratio.py: 1/40 + 0.02)
#: plus the count's resolution, one step of the 31-phase mesh cycle (1/30).
TCA_AGREEMENT = 1 / 40 + 0.02 + 1 / 30


def _boxes(flanks):
    """``check_generation``'s boxes of the contact path, from built flanks (their active
    boxes and meshing solvers are the check's)."""
    return {side: {"solver": flanks.pinion_conjugate.side(side).solver,
                   "active_box": flanks.pinion_conjugate.side(side).boundary}
            for side in ("drive", "coast")}


def _bare(pair):
    """``pair`` as read from a file without ease-off tables."""
    zero = EaseOffCoefficients()
    return replace(pair, easeoff_drive=zero, easeoff_coast=zero, easeoff_tables=())


def test_a_pair_with_its_table_keeps_it_without_flank_work(monkeypatch):
    """The synthesis does not run where the pair has a table of the side (prepare_pair),
    and the setting synthesis turns no short path: nothing is predicted, no flank is
    built."""
    def refuse(*args, **kwargs):
        raise AssertionError("flanks built")
    monkeypatch.setattr(predicted_bearing, "build_flanks", refuse)
    pair = replace(design_space_candidate(10, 1.5, 0.0, 35.0, 0.3, "drive"),
                   easeoff_tables=("drive", "coast"))
    assert predict_bearing(pair, boxes={}) is None
    bare = replace(pair, easeoff_tables=())
    got = predict_bearing(bare, boxes={}, turns_short_paths=False)
    assert got.coefficients is None and got.source == DEFAULT_BEARING


#: s0003-centred drive without its table, path-angle target -5 deg: the TCA (full, edge
#: contact, pairs -2..2, 31 phases) of the predicted bearing (the first-order design)
#: counts 2.333 pitches of one pair's surface contact and draws the path at -5.03 deg
#: on the gear flank (re-measured by test_path_angle_bearing_against_the_tca, --runslow);
#: the default bearing's path covers 2.82 pitches.
S0003_ANGLE_DEG, S0003_TCA_SURFACE = -5.0, 2.333


def test_a_path_angle_target_is_the_bearing_checked(s0003_centred):
    """The check sees the user's path angle (design --path-angle-deg): its eps_p is the
    TCA's surface count of that bearing, not the default bearing's (2.82)."""
    pair, flanks = s0003_centred
    bare = _bare(pair)
    boxes = _boxes(flanks)
    targets = SynthesisTargets(path_angle_deg=S0003_ANGLE_DEG)
    got = check_contact_ratio(bare, boxes=boxes, bearing_of=lambda p, b: predict_bearing(
        p, boxes=b, targets=targets, flanks=flanks))
    assert got.bearing == ("the synthesis' first-order bearing along the path angle -5 deg")
    assert got.total == pytest.approx(S0003_TCA_SURFACE, abs=TCA_AGREEMENT)
    default = path_contact_ratio(bare, boxes=boxes)
    assert default.bearing == DEFAULT_BEARING
    assert default.total - got.total > 0.3


@pytest.mark.slow
def test_path_angle_bearing_against_the_tca(s0003_centred):
    """Re-measures S0003_TCA_SURFACE (5-15 s)."""
    from gearcontact.tca.design_point import conjugate_contact, eased_design_point
    from gearcontact.tca.predicted_bearing import synthesis_start

    pair, flanks = s0003_centred
    bare = _bare(pair)
    targets = SynthesisTargets(path_angle_deg=S0003_ANGLE_DEG)
    bearing = predict_bearing(bare, boxes=_boxes(flanks), targets=targets, flanks=flanks)
    start = synthesis_start(bare, side="drive", targets=targets, flanks=flanks)
    conj, gear = flanks.pinion_conjugate.side("drive"), flanks.flank("gear", "drive")
    (uc, vc), b = start.centre_uv_mm, conj.boundary
    starts = [conjugate_contact(conj, gear, bare, uc - f * (b.u_tip - b.u_root), vc)
              for f in (0.0, 0.03, 0.1, 0.25)]
    dp = eased_design_point(bearing.coefficients, conj, gear, bare, starts,
                            mean_uv=start.mean_uv_mm, limit_um=flanks.easeoff_limit_um,
                            torque_nm=64.5, phases=31)
    assert dp.surface_contact_ratio == pytest.approx(S0003_TCA_SURFACE, abs=0.5 / 30)
    assert dp.path_angle_deg == pytest.approx(S0003_ANGLE_DEG, abs=0.5)
