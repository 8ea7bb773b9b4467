"""Issue 28's design space of hypoid pairs: a hypothesis strategy and the pair builder
shared by tests/geometry/test_flank.py (design accepts or names the condition) and
tests/report/test_design_space.py and tests/twin/test_design_space.py (every accepted
pair runs ``analyze`` / ``twin`` to exit 0: :func:`command_on_accepted_pair`)."""

import shutil
import subprocess
import tempfile
import time
from contextlib import contextmanager
from dataclasses import replace
from pathlib import Path

from hypothesis import assume
from hypothesis import strategies as st

from gearcontact.geometry.formate import SIDES
from gearcontact.geometry.generation import check_generation
from gearcontact.geometry.pair import EaseOffCoefficients, load_pair, pair_to_toml
from gearcontact.validation import InputRangeError

#: Fields a refused design may name (ISO 23509 conditions: offset limit, pitch cones
#: with rho_lim = r_c0, pointed teeth, pinion root, face width; undercut of the pinion).
#: Where the formate gear undercuts its pinion the pair gets a generated gear
#: (docs/geometry.md sec. 7.6): low ratios are accepted (F.3's data at beta1 35 deg,
#: face 0.3 R_m: 29 of 32 pairs with z1 5-20, u 1-2.5, E 0 and 0.3 r2, 23 of them on the
#: generated gear; counted before the contact-ratio check); an undercut left with the
#: generated gear names the gear addendum factor or the tooth numbers, as the formate
#: gear's did. A contact path covering less than the threshold (docs/geometry.md
#: sec. 7.7: eps_p < 0.85; of the 32 pairs above 23 pass it) names the face width, the
#: spiral angle or the tooth numbers.
#: The 7/60 design-space pair whose contact leaves the pinion's flank over its root edge
#: (issue 28: the edge-contact TCA and the loaded TE on the edge's own field,
#: docs/twin.md "Edge contact"): tests/twin/test_design_space.py and
#: tests/ltca/test_lte_edge_contact.py.
CHATTER_PAIR = (7, 8.53011882343041, 0.043555845328246544, 25.0, 0.3203125, "drive",
                "right")

#: A 15/15 miter spiral bevel pair (left hand, drive, 23 deg, face 0.25 R_m; the slow
#: twin property test's examples at 23 / 25.9 deg): one pair carries the whole torque
#: over most of the pitch and hands over through the pinion's edge rows, and at 3000 rpm
#: the mesh rattles (docs/twin.md "The law of a cut patch"): tests/twin/test_edge_law.py
#: and tests/twin/test_design_space.py.
MITER_PAIR = (15, 1.0, 0.0, 23.0, 0.25, "drive", "left")

DESIGN_FIELDS = {"offset_mm", "pinion_spiral_angle_deg",
                 "pinion_spiral_angle_deg / cutter_radius_mm", "gear_addendum_factor",
                 # the generation check's undercut, named as the pair file spells it
                 "design.gear_addendum_factor",
                 "pinion_teeth / gear_teeth", "design.working_depth_factor",
                 "cutter.point_width_mm", "design.gear_face_width_mm",
                 # the contact-ratio check's, named as the pair file spells them
                 "design.pinion_spiral_angle_deg", "teeth.pinion / teeth.gear"}


def design_space_pair(z1, ratio, offset_frac, beta, face_frac, side, hand="right"):
    """An F.3-like pair (r2 = 70.94 mm, r_c0 = 63.5 mm) at a point of issue 28's design
    space, with a crowning of about 10 um at the flank corners (so that TCA has an
    ease-off), or the InputRangeError that ``design`` raises for it; ``hand``: the
    pinion's ("left": the mirror image of the right-hand pair)."""
    pair = design_space_candidate(z1, ratio, offset_frac, beta, face_frac, side, hand)
    check_generation(pair)
    return pair


def generated_hypoid():
    """13/26, E = 0.3 r2 = 21.3 mm, beta1 35 deg, face 0.3 R_m: F.3's data at a point of
    the design space where the formate gear undercuts its pinion, so the default gear is
    generated; no ease-off (the standard settings, docs/machine_settings.md sec. 4-5)."""
    pair = design_space_candidate(13, 2.0, 0.3, 35.0, 0.3, "drive")
    return replace(pair, name="hypoid_13x26_generated", easeoff_drive=EaseOffCoefficients(),
                   easeoff_coast=EaseOffCoefficients())


def bare_candidate(z1, ratio, offset_frac, beta, face_frac, side, hand="right"):
    """:func:`design_space_candidate` without ease-off tables: the commands synthesize
    its ease-off (``tca.synthesis.prepare_pair``), and ``design``'s contact-path check
    takes the bearing the synthesis will make (``tca.predicted_bearing``)."""
    pair = design_space_candidate(z1, ratio, offset_frac, beta, face_frac, side, hand)
    return replace(pair, easeoff_drive=EaseOffCoefficients(),
                   easeoff_coast=EaseOffCoefficients(), easeoff_tables=())


def design_space_candidate(z1, ratio, offset_frac, beta, face_frac, side, hand="right"):
    """:func:`design_space_pair` before ``design``'s checks (the pitch-cone design's own
    refusals only)."""
    base = load_pair(Path(__file__).resolve().parents[1] / "examples" / "iso23509_f3.toml")
    z2 = max(z1, int(round(z1 * ratio)))
    r2 = base.gear_mean_pitch_radius_mm
    pair = replace(base, pinion_teeth=z1, gear_teeth=z2, offset_mm=offset_frac * r2,
                   pinion_spiral_angle_deg=beta, gear_face_width_mm=10.0,
                   pinion_face_width_mm=10.5, design_side=side, pinion_hand=hand)
    # face width up to the standard limit F <= 0.3 R_e (R_e = R_m + F/2)
    face = face_frac * pair.blank.mean_cone_distance_gear_mm
    b = pair.blank
    crown = EaseOffCoefficients(profile_crowning_um_per_mm2=10.0 / (0.5 * b.working_depth_mm) ** 2,
                                lengthwise_crowning_um_per_mm2=10.0 / (0.5 * face) ** 2)
    pair = replace(pair, gear_face_width_mm=face, pinion_face_width_mm=1.05 * face,
                   easeoff_drive=crown, easeoff_coast=crown)
    return pair


#: The ranges of issue 28 item 1 (z1 5-20, ratio 1-10, offset up to 0.55 r2, spiral
#: angle 20-55 deg, face width up to the standard limit, design side).
SPACE = dict(z1=st.integers(5, 20),
             ratio=st.one_of(st.just(1.0), st.floats(1.0, 10.0)),
             offset_frac=st.one_of(st.just(0.0), st.floats(0.0, 0.55)),
             beta=st.floats(20.0, 55.0), face_frac=st.floats(0.15, 0.353),
             side=st.sampled_from(SIDES))
#: Both hands (issue 28 item 1), drawn besides :data:`SPACE` by the tests that run
#: whole commands on the pairs.
HANDS = st.sampled_from(("right", "left"))


@contextmanager
def command_on_accepted_pair(command, point, *, options=()):
    """Run ``gearcontact COMMAND --pair FILE --out DIR --quiet OPTIONS`` (the console
    script, a real process) on the :func:`design_space_pair` of ``point`` (its
    arguments in order) written to a temporary TOML file; yield ``(pair, run, out)``
    (the CompletedProcess and the output directory, removed afterwards). A pair that
    ``design`` refuses (named: tests/geometry/test_flank.py) is rejected from the
    hypothesis draw."""
    try:
        pair = design_space_pair(*point)
    except InputRangeError:
        assume(False)
    exe = shutil.which("gearcontact")
    assert exe, "the gearcontact console script is installed"
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        (tmp / "pair.toml").write_text(pair_to_toml(pair))
        out = tmp / "out"
        t0 = time.perf_counter()
        run = subprocess.run([exe, command, "--pair", str(tmp / "pair.toml"), "--out",
                              str(out), "--quiet", *options], capture_output=True, text=True)
        # the pair and the wall time, for the record (shown by pytest -s)
        z1, _, offset_frac, beta, face_frac, *rest = point
        print(f"{command} z1={z1} z2={pair.gear_teeth} offset={offset_frac:.4f} r2 "
              f"beta1={beta:.3f} face={face_frac:.4f} R_m {' '.join(rest)}: exit "
              f"{run.returncode}, {time.perf_counter() - t0:.1f} s")
        yield pair, run, out
