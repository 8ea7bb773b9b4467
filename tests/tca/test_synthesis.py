"""Local synthesis of the ease-off (gearcontact.tca.synthesis).

Truth: a known ease-off's own TCA design point (bearing centre, TE0, paint-ellipse
length) taken as the targets must give that ease-off back - the synthesis inverts the
TCA, so the round trip is the independent check. The search runs on a reduced TCA
(surface contact, pairs -1..1); every synthesized ease-off is run again here through
the full TCA (edge contact, pairs -2..2, 31 phases), from the synthesis's own start
contacts, and must meet the targets there and reproduce the reported design point.
"""

import dataclasses

import numpy as np
import pytest

from gearcontact.geometry.kinematics import AssemblyErrors
from gearcontact.tca.design_point import conjugate_contact, eased_design_point
from gearcontact.tca.synthesis import (SynthesisTargets, easeoff_toml, prepare_pair,
                                       synthesize_easeoff)
from gearcontact.validation import InputRangeError


def full_tca_check(pair, flanks, side, syn):
    """The full TCA (edge contact, pairs -2..2, 31 phases) of ``syn``'s ease-off, and
    the target misses in tolerances (bearing centre u, v; TE0; paint-ellipse 2a), at
    the nominal mounting the ease-off is designed for."""
    pair = dataclasses.replace(pair, assembly=AssemblyErrors())
    conj = flanks.pinion_conjugate.side(side)
    gear = flanks.flank("gear", side)
    b = conj.boundary
    u_m, v_m = flanks.mean_contact[side]["pinion_uv"]
    t = syn.targets
    centre = (b.u_root + t.centre_profile * (b.u_tip - b.u_root),
              b.v_toe + t.centre_face * (b.v_heel - b.v_toe))
    length = t.pattern_length_ratio * pair.gear_face_width_mm
    starts = [conjugate_contact(conj, gear, pair, centre[0] - f * (b.u_tip - b.u_root),
                                centre[1]) for f in (0.0, 0.03, 0.1, 0.25)]
    dp = eased_design_point(syn.coefficients, conj, gear, pair, starts, mean_uv=(u_m, v_m),
                            limit_um=flanks.easeoff_limit_um, torque_nm=64.5, phases=31,
                            pairs=2, edge_contact=True)
    misses = [(dp.pinion_uv[0] - centre[0]) / t.tol_centre_mm,
              (dp.pinion_uv[1] - centre[1]) / t.tol_centre_mm,
              (dp.te0_pp_arcsec / t.te0_pp_arcsec - 1.0) / t.tol_te0_rel,
              (dp.paint_length_mm / length - 1.0) / t.tol_length_rel]
    return dp, misses


def assert_met_by_full_tca(pair, flanks, side, syn):
    """Every target met by the full TCA of the synthesized ease-off, and that TCA is the
    reported design point (same function, same inputs: equal to 1e-9)."""
    dp, misses = full_tca_check(pair, flanks, side, syn)
    assert max(abs(m) for m in misses) <= 1.0, (misses, syn.table())
    assert dp.te0_pp_arcsec == pytest.approx(syn.point.te0_pp_arcsec, rel=1e-9)
    assert dp.paint_length_mm == pytest.approx(syn.point.paint_length_mm, rel=1e-9)
    assert dp.pinion_uv == pytest.approx(syn.point.pinion_uv, rel=1e-9)


@pytest.fixture(scope="module")
def round_trip(s0003_centred):
    s0003_pair, s0003_flanks = s0003_centred
    side = "drive"
    conj = s0003_flanks.pinion_conjugate.side(side)
    gear = s0003_flanks.flank("gear", side)
    b = conj.boundary
    u_m, v_m = s0003_flanks.mean_contact[side]["pinion_uv"]
    starts = [conjugate_contact(conj, gear, s0003_pair, 0.5 * (b.u_root + b.u_tip) - d, v_m)
              for d in (0.0, 0.3)]
    known = s0003_pair.easeoff_drive
    dp = eased_design_point(known, conj, gear, s0003_pair, starts, mean_uv=(u_m, v_m),
                            limit_um=s0003_flanks.easeoff_limit_um, torque_nm=64.5,
                            phases=31)
    targets = SynthesisTargets(
        te0_pp_arcsec=dp.te0_pp_arcsec,
        pattern_length_ratio=dp.paint_length_mm / s0003_pair.gear_face_width_mm,
        centre_face=(dp.pinion_uv[1] - b.v_toe) / (b.v_heel - b.v_toe),
        centre_profile=(dp.pinion_uv[0] - b.u_root) / (b.u_tip - b.u_root))
    return known, synthesize_easeoff(s0003_pair, side=side, targets=targets,
                                     flanks=s0003_flanks)


def test_synthesis_recovers_a_known_easeoff(round_trip):
    """s0003-centred's drive ease-off from its own design point: the crownings within
    2 % and 5 % (measured 0.1 % and 3 %: TE0 p-p over 31 phases is a discrete peak-to-
    peak, so the lengthwise crowning is the least determined), the profile angle
    (bearing height) within 0.3 um/mm, bias and spiral angle near their zero."""
    known, syn = round_trip
    c = syn.coefficients
    assert syn.met
    assert c.profile_crowning_um_per_mm2 == pytest.approx(known.profile_crowning_um_per_mm2,
                                                          rel=0.02)
    assert c.lengthwise_crowning_um_per_mm2 == pytest.approx(
        known.lengthwise_crowning_um_per_mm2, rel=0.05)
    assert c.profile_angle_um_per_mm == pytest.approx(known.profile_angle_um_per_mm, abs=0.3)
    assert abs(c.spiral_angle_um_per_mm) < 0.1 and abs(c.bias_um_per_mm2) < 0.05


def test_round_trip_targets_met_by_the_full_tca(round_trip, s0003_centred):
    """The synthesized s0003-centred drive ease-off meets every target in the full TCA
    (tolerances of SynthesisTargets: centre 0.05 mm, TE0 and 2a 5 %), which is the
    design point the synthesis reports."""
    s0003_pair, s0003_flanks = s0003_centred
    assert_met_by_full_tca(s0003_pair, s0003_flanks, "drive", round_trip[1])


def test_synthesized_toml_is_a_pair_table(round_trip, s0003_centred):
    """The printed block parses as the pair format's [easeoff.<side>] table and holds
    the synthesized coefficients."""
    import tomllib

    s0003_pair = s0003_centred[0]
    _, syn = round_trip
    doc = tomllib.loads(easeoff_toml({"drive": syn}, pair_name=s0003_pair.name))
    got = doc["easeoff"]["drive"]
    for k, v in dataclasses.asdict(syn.coefficients).items():
        assert got[k] == pytest.approx(v, rel=1e-5, abs=1e-12)


def test_prepare_pair_leaves_a_pair_with_its_table_alone(s0003_centred):
    """A pair with its table is left alone: nothing synthesized, no note, no timing."""
    s0003_pair = s0003_centred[0]
    prepared = prepare_pair(s0003_pair, side="drive")
    assert prepared.pair is s0003_pair and not prepared.synthesized
    assert prepared.note == "" and prepared.timings_s == {}


@pytest.mark.parametrize("field, value", [("te0_pp_arcsec", 0.0),
                                          ("pattern_length_ratio", 0.95),
                                          ("path_angle_deg", 120.0),
                                          ("centre_face", 0.0)])
def test_bad_targets_name_the_field(field, value):
    with pytest.raises(InputRangeError, match=field):
        SynthesisTargets(**{field: value})


@pytest.mark.slow
def test_synthesis_near_the_calibrated_tip_edge_preset():
    """s0003 (calibrated coast ease-off, tip-edge bearing 0.05 mm below the tip): its
    own design point, path angle included, as targets, gives the calibrated ease-off
    back: every target met, crownings within 2 % and 10 %, and the relief within 5 % of
    the calibrated one's largest |E| everywhere on the flank (the share to which TE0 and
    the pattern length, whose tolerances are 5 %, fix it), up to a rigid turn of the
    pinion. Measured: crownings 0.5 % and 4.4 %, relief 0.87 um (3.9 % of 22.5 um;
    session 12, the centre's relief carried as a turn: 1.20 um with the turn, 0.56 um
    = 2.5 % without it). The bias alone is not fixed to better than
    that: -0.023 against -0.0057 um/mm^2 (session 10, with the path angle in space:
    within 0.01); the path angle on the gear flank moves by 7.2 deg per um/mm^2 of bias
    here (0.12 deg for that difference, its tolerance 2 deg) and the crownings take the
    rest."""
    from gearcontact.geometry.flank import build_flanks
    from gearcontact.geometry.easeoff import EaseOff, max_relief_um
    from gearcontact.geometry.pair import EaseOffCoefficients, load_pair
    from gearcontact.tca.design_point import turn_relief

    pair = load_pair("s0003")
    side = "coast"
    flanks = build_flanks(pair)
    conj, gear = flanks.pinion_conjugate.side(side), flanks.flank("gear", side)
    b = conj.boundary
    u_m, v_m = flanks.mean_contact[side]["pinion_uv"]
    starts = [conjugate_contact(conj, gear, pair, b.u_tip - d, 41.679) for d in (0.15, 0.35)]
    known = pair.easeoff_coast
    dp = eased_design_point(known, conj, gear, pair, starts, mean_uv=(u_m, v_m),
                            limit_um=flanks.easeoff_limit_um, torque_nm=64.5, phases=31)
    targets = SynthesisTargets(
        te0_pp_arcsec=dp.te0_pp_arcsec,
        pattern_length_ratio=dp.paint_length_mm / pair.gear_face_width_mm,
        path_angle_deg=dp.path_angle_deg,
        centre_face=(dp.pinion_uv[1] - b.v_toe) / (b.v_heel - b.v_toe),
        centre_profile=(dp.pinion_uv[0] - b.u_root) / (b.u_tip - b.u_root))
    syn = synthesize_easeoff(pair, side=side, targets=targets, flanks=flanks)
    assert syn.met
    assert_met_by_full_tca(pair, flanks, side, syn)
    c = syn.coefficients
    assert c.profile_crowning_um_per_mm2 == pytest.approx(known.profile_crowning_um_per_mm2,
                                                          rel=0.02)
    assert c.lengthwise_crowning_um_per_mm2 == pytest.approx(
        known.lengthwise_crowning_um_per_mm2, rel=0.10)
    # an ease-off is a flank up to a rigid turn of the pinion (its relief L(p) dpsi only
    # shifts TE0; the synthesis carries the relief at its centre as one: design_point.
    # turn_relief): the difference is compared without its turn component (least
    # squares over a 9 x 9 grid of the flank)
    names = list(dataclasses.asdict(c))
    diff = np.array([getattr(c, k) - getattr(known, k) for k in names])
    turn = turn_relief(conj, (u_m, v_m))
    U, V = np.meshgrid(np.linspace(b.u_root, b.u_tip, 9), np.linspace(b.v_toe, b.v_heel, 9))

    def relief(x):
        return EaseOff.from_coefficients(EaseOffCoefficients(**dict(zip(names, x))),
                                         u_mean_mm=u_m, v_mean_mm=v_m).relief_mm(U, V).ravel()

    share = float(np.linalg.lstsq(relief(turn)[:, None], relief(diff), rcond=None)[0][0])
    rest = EaseOffCoefficients(**dict(zip(names, diff - share * turn)))
    relief = [max_relief_um(EaseOff.from_coefficients(x, u_mean_mm=u_m, v_mean_mm=v_m), b)[0]
              for x in (rest, known)]
    assert relief[0] <= 0.05 * relief[1], relief


@pytest.mark.slow
@pytest.mark.parametrize("side", ["drive", "coast"])
@pytest.mark.parametrize("example", ["iso23509_f3", "hypoid_11x41_rear_axle",
                                     "iso23509_f2_spiral_bevel"])
def test_every_shipped_example_side_meets_the_default_targets(example, side):
    """The default targets (TE0 3 arcsec, pattern 0.35 x face, centred bearing) met on
    both sides of the three shipped examples, in the full TCA (4-13 TCA runs each,
    docs/synthesis.md; the F2 spiral bevel coast needs the decoupled rounds: before them
    it stopped at TE0 4.54 arcsec and a 16.8 mm pattern against 8.9)."""
    from pathlib import Path

    from gearcontact.geometry.flank import build_flanks
    from gearcontact.geometry.pair import load_pair

    root = Path(__file__).resolve().parents[2] / "examples"
    pair = load_pair(str(root / f"{example}.toml"))
    flanks = build_flanks(pair)
    syn = synthesize_easeoff(pair, side=side, flanks=flanks)
    assert syn.met, syn.table()
    assert_met_by_full_tca(pair, flanks, side, syn)


@pytest.fixture(scope="module")
def miter():
    """Issue 28's 20/20 miter: ISO 23509 F.2's data with 20/20 teeth and 25 mm faces
    (its gear is generated, geometry.gear_generation), and its flanks."""
    from pathlib import Path

    from gearcontact.geometry.flank import build_flanks
    from gearcontact.geometry.pair import load_pair

    root = Path(__file__).resolve().parents[2] / "examples"
    pair = dataclasses.replace(load_pair(str(root / "iso23509_f2_spiral_bevel.toml")),
                               pinion_teeth=20, gear_teeth=20, gear_face_width_mm=25.0,
                               pinion_face_width_mm=25.0)
    return pair, build_flanks(pair)


@pytest.mark.slow
def test_miter_synthesis_turns_its_path_to_an_overlap(miter):
    """The 20/20 miter's zero-bias path runs nearly along its contact lines (path angle
    0.1 deg): one pair's surface contact lasts 0.93 of a pitch, so TE0 was an edge
    contact's and the search missed (207 TCA runs: TE0 4.73 arcsec, 2a 13.2 mm against 3
    and 8.75). The synthesis turns the path to the reachable angle of the longest
    overlap (closed form 1.71 pitches at 19.3 deg) and meets every target in the full
    TCA; the closed form's overlap agrees with the TCA's count of surface phases within
    two phase steps (2/30: the count's resolution is one step, the closed form is first
    order; measured 1.71 against 1.73). Measured 51 TCA runs, 33 s at load 8."""
    pair, flanks = miter
    syn = synthesize_easeoff(pair, side="drive", flanks=flanks)
    assert syn.met, syn.table()
    assert syn.targets.path_angle_deg == pytest.approx(19.3, abs=1.0)
    assert "0.93 of a pinion pitch" in syn.path_choice and syn.unreachable == ""
    closed_form = float(syn.path_choice.split(" it lasts ")[1].split(" pitches")[0])
    assert syn.point.surface_contact_ratio == pytest.approx(closed_form, abs=2.0 / 30.0)
    assert syn.evaluations < 120
    assert_met_by_full_tca(pair, flanks, "drive", syn)


@pytest.mark.slow
def test_miter_synthesis_names_a_te0_it_cannot_reach(miter, monkeypatch):
    """Where no reachable path angle gives an overlap either (here: the closed form made
    to say 0.8 pitches; a real pair: tests/tca/test_predicted_bearing.py), the synthesis says so at its first full TCA and stops after the
    decoupled rounds (2 + 12 TCA runs at most) instead of searching: the bearing centre
    and the pattern length are still met, TE0 is not, and the reason names the zero-bias
    path's 0.93 pitches and the best angle's 0.80."""
    import gearcontact.tca.path_reach as path_reach

    pair, flanks = miter
    monkeypatch.setattr(path_reach, "overlap_path_angle", lambda *a, **k: (19.3, 0.8))
    syn = synthesize_easeoff(pair, side="drive", flanks=flanks)
    assert not syn.met and syn.path_choice == ""
    assert "lasts 0.93 of a pinion pitch" in syn.unreachable
    assert "along 19.3 deg, lasts 0.80" in syn.unreachable
    assert syn.evaluations <= 14
    met = {row[0]: row[5] for row in syn.rows}
    assert met["bearing centre pinion u"] and met["bearing centre pinion v"]
    assert met["paint ellipse 2a"] and not met["TE0 peak-to-peak"]
