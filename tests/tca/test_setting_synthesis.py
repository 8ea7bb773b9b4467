"""Local synthesis of the pinion machine settings at the mean point (tca.setting_synthesis)
on the 13/26 hypoid whose gear is generated (tests/design_space.py: generated_hypoid).

Truths: the roll about the mean node's roll in closed form (value, slope and curvature
of the written series), the mean point and its normal kept by every correction (exact
envelope node solves), TE0 = 0 of the uncorrected crown gear's pinion (its TE curvature
at M vanishes), and for the synthesized settings the targets at M, the full TCA's TE0
vertex at M and no paint ellipse at a flank edge in the central phases; a left-hand
pair's settings and TCA are its right-hand twin's mirrored (flanks cut directly by the
machine chain); a coast path-angle target keeps the full TCA's pattern off the root.
"""

import math

import numpy as np
import pytest
from design_space import generated_hypoid

from gearcontact.geometry.basic_settings import member_setups
from gearcontact.geometry.formate import SIDES
from gearcontact.geometry.generated import EnvelopeSolver
from gearcontact.geometry.machine import MachineSettings
from gearcontact.tca.setting_synthesis import (SynthesisProblem, corrected_setup, roll_about,
                                               synthesize_settings)
from gearcontact.tca.synthesis import SynthesisTargets
from gearcontact.validation import InputRangeError


@pytest.fixture(scope="module")
def problem(generated_hypoid_problem):
    return generated_hypoid_problem


def test_roll_about_the_mean_roll():
    # the work roll as a function of the base's cradle position, W(psi) = phi(psi - d)
    # with d the cradle-angle change (the cradle rolled by d), phi the written series
    # R_a (s - 2C s^2 / 2): value and slope of the linear base roll at psi_m, second
    # derivative -R_a0 c (closed form; 1e-12 relative: float rounding)
    base = MachineSettings(radial_distance_mm=80.0, cradle_angle_deg=50.0,
                           machine_root_angle_deg=30.0, ratio_of_roll=2.4)
    for psi_m, c in ((-0.037, 0.0156), (0.055, -0.0133), (0.2, 0.5)):
        new = roll_about(base, psi_m=psi_m, roll_curvature=c)
        d = math.radians(new.cradle_angle_deg - base.cradle_angle_deg)
        s, r_a, c2 = psi_m - d, new.ratio_of_roll, new.modified_roll[0]
        assert r_a * (s - c2 * s * s / 2.0) == pytest.approx(2.4 * psi_m, rel=1e-12)
        assert r_a * (1.0 - c2 * s) == pytest.approx(2.4, rel=1e-12)
        assert -r_a * c2 == pytest.approx(-2.4 * c, rel=1e-12)
    assert roll_about(base, psi_m=0.1, roll_curvature=0.0) == base
    with pytest.raises(InputRangeError, match="roll_curvature"):
        roll_about(base, psi_m=0.1, roll_curvature=-6.0)     # 1 + 2 c psi_m < 0


def test_corrections_keep_the_mean_point_and_normal(problem):
    # every correction pivots on the generation of M: the envelope node at M of the
    # corrected settings equals the base's (crown gear's pinion) within 1e-9 mm and its
    # normal within 1e-12 (node solves to 1e-10; measured ~3e-14). Not vacuous: the
    # settings change (cradle angle, radial, ratio of roll, blade).
    pair = problem.pair
    for side in SIDES:
        base = problem.base[side]
        solver = EnvelopeSolver(base, pair.blank, problem.cone)
        u, v = problem.mean_uv[side]
        m0 = solver.solve(u, v, solver.initial_guess(u, v))
        for x in ([0.02, 0.0, 0.0], [0.0, 1e-3, 0.0], [0.0, 0.0, 1.5], [-0.015, 8e-4, -2.0]):
            s = corrected_setup(base, x, mean=problem.means[side])
            m1 = EnvelopeSolver(s, pair.blank, problem.cone).solve(u, v, m0.q)
            assert np.abs(m1.x_mm - m0.x_mm).max() < 1e-9
            assert np.abs(m1.n - m0.n).max() < 1e-12
            assert s != base


def test_crown_pinion_has_no_te_curvature_and_the_crowning_has(problem):
    # the uncorrected crown gear's pinion: TE0 = 0 along its path (Litvin & Fuentes 2004,
    # sec. 20.2), so its TE curvature at M is 0 (|level| < 1e-3 arcsec, measured ~1e-5:
    # the five-point difference of node-interpolated flanks) and the contact at M's phase
    # is M (1e-6 mm); the standard crowning's is a parabola of ~20 arcsec (not vacuous)
    for side in SIDES:
        m = problem.contact(side, np.zeros(3))
        assert m.te_level_arcsec < 1e-3
        assert abs(m.te_slope_arcsec_per_rad) < 1e-2
        assert np.hypot(m.point.pinion_uv[0] - problem.mean_uv[side][0],
                        m.point.pinion_uv[1] - problem.mean_uv[side][1]) < 1e-6
        assert problem.contact(side, problem.standard[side]).te_level_arcsec > 10.0


def test_refused_before_any_flank():
    # a left-hand pair (its right-hand twin is synthesized and mirrored) and an unknown
    # gear generation are refused naming the field, before any flank. A spiral bevel
    # (offset 0) or a formate gear is no longer refused: its base pinion is line-contact
    # conjugate and M the blank's mean point (tests/tca/test_setting_synthesis_line_contact.py)
    from dataclasses import replace

    pair = generated_hypoid()
    with pytest.raises(InputRangeError, match="gear_generation"):
        SynthesisProblem(pair, gear_generation="hobbed")
    with pytest.raises(InputRangeError, match="pinion_hand"):
        SynthesisProblem(replace(pair, pinion_hand="left"))


@pytest.mark.slow
def test_synthesized_settings_meet_the_targets(problem):
    # ~1 min. Default targets (TE0 3 arcsec, paint ellipse 0.35 x face, path angle free):
    # (a) at M (local TCA): TE level and ellipse length within the synthesis' tolerances
    #     (5 %; measured within 1e-5 relative);
    # (b) full TCA over one pitch (31 phases, edge contact, pairs -2..2): TE0 vertex at M
    #     within 1e-6 mm (M keeps point, normal and ratio; measured 1.7e-8 / 4.4e-9 mm),
    #     TE0 p-p within 30 % of the parabolic level (the TE function is not a parabola
    #     over a whole pitch: measured 2.25 / 2.73 arcsec drive / coast), and no paint
    #     ellipse at a flank edge in the central 11 phases (the standard settings had the
    #     coast bearing on the pinion root edge at 9 of 31 phases; measured: drive none,
    #     coast pinion root at 2 phases, 12-13 after the vertex);
    # (c) the TE parabola has the standard crowning's sign (a localized bearing)
    targets = SynthesisTargets()
    done = synthesize_settings(problem.pair, problem=problem)
    for side in SIDES:
        r = done[side]
        assert r.met, r.table()
        assert r.vertex_offset_mm < 1e-6
        assert r.tca_te0_pp_arcsec == pytest.approx(targets.te0_pp_arcsec, rel=0.3)
        k = len(r.edges) // 2
        assert not any(r.edges[k - 5:k + 6]), r.edges
        curv = problem.contact(side, r.x).te_curvature_arcsec_per_rad2
        std = problem.contact(side, problem.standard[side]).te_curvature_arcsec_per_rad2
        assert np.sign(curv) == np.sign(std)


@pytest.mark.slow
def test_design_local_synthesis_writes_the_settings(tmp_path):
    # the CLI (~1.5 min): design --machine-settings --local-synthesis writes the
    # generated gear's settings (as --machine-settings) and pinion settings with a
    # modified roll; the written pinion keeps M and its normal against the crown gear's
    # pinion (1e-9 mm / 1e-12, read back from the TOML: its 17 digits keep them)
    from gearcontact.cli import main
    from gearcontact.geometry.pair import load_pair, pair_to_toml

    pair = generated_hypoid()
    path = tmp_path / "hypoid.toml"
    path.write_text(pair_to_toml(pair))
    out = tmp_path / "out"
    assert main(["design", "--pair", str(path), "--machine-settings", "--local-synthesis",
                 "--out", str(out)]) == 0
    text = (out / "machine_settings.toml").read_text()
    assert "local synthesis" in text
    written = load_pair(out / "machine_settings.toml")
    setups = {(s.member, s.side): s for s in written.machine}
    gear, crown = member_setups(pair, "generated")
    prob = SynthesisProblem(pair)
    for side in SIDES:
        assert setups["gear", side] == gear[side]
        pin = setups["pinion", side]
        assert pin.settings.modified_roll[0] != 0.0
        cone = prob.cone
        u, v = prob.mean_uv[side]
        a = EnvelopeSolver(crown[side], pair.blank, cone)
        m0 = a.solve(u, v, a.initial_guess(u, v))
        m1 = EnvelopeSolver(pin, pair.blank, cone).solve(u, v, m0.q)
        assert np.abs(m1.x_mm - m0.x_mm).max() < 1e-9
        assert np.abs(m1.n - m0.n).max() < 1e-12


@pytest.mark.slow
def test_left_hand_settings_are_the_mirror_image(tmp_path):
    # ~1 min. A left-hand pair is the mirror image (y -> -y) of its right-hand twin
    # (geometry.mirror): its local synthesis synthesizes the twin and mirrors the settings
    # (mirror_setup, docs/machine_settings.md sec. 1). The search is cut to 6 local TCAs
    # per side (the symmetry does not need the targets met). Truths:
    # (a) the written left-hand file holds the twin's settings with the documented signs:
    #     cradle angle, swivel, blank offset and 2C negated, the rest equal (exact: a
    #     sign flip and the TOML's 17 digits);
    # (b) those settings run directly through the machine chain with the reflected blank
    #     (no twin in between) cut the reflected pinion flank of the twin's settings at
    #     every node (1e-9 mm, exact envelope solves; test_machine.py's tolerance);
    # (c) TCA of the left-hand written file (analyze_pair, 11 phases, edge contact) equals
    #     the right-hand one's, per side: TE0 per phase to 1e-6 arcsec (Newton stops at
    #     1e-11 mm), contact points mirrored to 1e-6 mm, the same flank edges per phase
    #     (the pattern mirrored; tests/geometry/test_mirror.py's tolerances).
    from dataclasses import replace

    from gearcontact.geometry.generated import generated_pinion_flank
    from gearcontact.geometry.machine import mirror_setup
    from gearcontact.geometry.mirror import MIRROR
    from gearcontact.geometry.pair import load_pair
    from gearcontact.report.design import local_synthesis_toml
    from gearcontact.tca.analysis import analyze_pair
    from gearcontact.tca.setting_synthesis import synthesized_machine_pair

    right = generated_hypoid()
    left = replace(right, pinion_hand="left")
    cut, done = synthesized_machine_pair(left, max_evaluations=6, phases=5)
    (tmp_path / "left.toml").write_text(local_synthesis_toml(cut, done))
    written = load_pair(tmp_path / "left.toml")
    assert written.pinion_hand == "left"
    gear, _ = member_setups(right, "generated")
    twin = replace(right, machine=tuple(gear[s] for s in SIDES)
                   + tuple(done[s].setup for s in SIDES), easeoff_tables=("drive", "coast"))
    setups = {(s.member, s.side): s for s in written.machine}
    for s in twin.machine:
        w, st = setups[s.member, s.side], s.settings
        assert w == mirror_setup(s)
        assert (w.settings.cradle_angle_deg, w.settings.swivel_deg,
                w.settings.blank_offset_mm) == (-st.cradle_angle_deg, -st.swivel_deg,
                                                 -st.blank_offset_mm)
        assert w.settings.modified_roll == tuple(-c for c in st.modified_roll[:1]) \
            + st.modified_roll[1:]
        assert (w.settings.ratio_of_roll, w.blade) == (st.ratio_of_roll, s.blade)
    assert any(setups["pinion", s].settings.modified_roll for s in SIDES)   # not vacuous
    b = right.blank
    P = b.pitch_point_mm
    mb = replace(b, pitch_point_mm=(P[0], -P[1], P[2]))
    kw = dict(pinion_face_width_mm=right.pinion_face_width_mm, n_u=8, n_v=10)
    for side in SIDES:
        _, n_right = generated_pinion_flank(done[side].setup, b, **kw)
        _, n_left = generated_pinion_flank(setups["pinion", side], mb, **kw)
        assert np.abs(n_left.x_mm - n_right.x_mm @ MIRROR).max() < 1e-9
    for side in SIDES:
        a = analyze_pair(twin, side=side, phases=11)[0]
        m = analyze_pair(written, side=side, phases=11)[0]
        ta, tm = a.table, m.table
        assert np.array_equal(np.isnan(ta.te0_arcsec), np.isnan(tm.te0_arcsec))
        assert np.nanmax(np.abs(ta.te0_arcsec - tm.te0_arcsec)) < 1e-6
        assert np.nanmax(np.abs(ta.point_mm @ MIRROR - tm.point_mm)) < 1e-6
        assert a.edges == m.edges
        assert ta.te0_pp_arcsec > 0.5           # not vacuous: crowned, not conjugate


@pytest.mark.slow
def test_design_coast_path_angle_lifts_the_bearing_off_the_pinion_root(tmp_path, capsys):
    # ~5 min on a loaded machine (the coast search with three corrections: 62 local TCAs).
    # With the path free the coast path runs along the profile (-89 deg at M) and the
    # pattern reaches the pinion root at the end of the pitch (1-2 of 31 phases, test
    # above). `design --machine-settings --local-synthesis --path-angle-coast-deg 40` on
    # the LEFT-hand pair (the CLI options, the mirror and the target end to end): exit 0
    # (all targets met at M, the path angle within 2 deg), and the full TCA of the written
    # file (analyze_pair, 31 phases, edge contact: independent of the synthesis' local
    # TCA) has the coast pattern inside the flanks at every phase (measured: no edge at
    # 31 of 31) and a TE0 p-p between half the parabolic level at M and that level
    # (3 arcsec: the pairs change before half a pitch either side of M; measured 2.02
    # arcsec, 2.05 in the synthesis' own check at 40 x 50 nodes)
    from dataclasses import replace

    from gearcontact.cli import main
    from gearcontact.geometry.pair import load_pair, pair_to_toml
    from gearcontact.tca.analysis import analyze_pair

    path = tmp_path / "left.toml"
    path.write_text(pair_to_toml(replace(generated_hypoid(), pinion_hand="left")))
    out = tmp_path / "out"
    assert main(["design", "--pair", str(path), "--machine-settings", "--local-synthesis",
                 "--path-angle-coast-deg", "40", "--out", str(out)]) == 0
    assert "| coast path angle from lengthwise (deg) | 40 | 40 |" in capsys.readouterr().out
    written = load_pair(out / "machine_settings.toml")
    assert written.pinion_hand == "left"
    a = analyze_pair(written, side="coast", phases=31)[0]
    assert len(a.edges) == 31 and not any(a.edges), a.edges
    assert 1.5 < a.table.te0_pp_arcsec <= 3.0
