"""The active box of a flank cut from machine settings where the envelope folds within
the node margin below the blade edge line (geometry.generated_box).

The standard pinion of the published 10 x 41 hypoid print's blank
(tests/geometry/summary_sheets/README.md; `design --machine-settings` on the blank) has
its coast (convex) flank near an undercut at the toe root: the envelope of the blade
profile continued past the edge round's top folds 0.03 mm below the node grid's bottom
row as it was (the toe-root corner node, 0.08 mm below the edge line and 0.16 mm beyond
the toe), and every command refused the pair ("a node the generated envelope
reaches"). Truths: the nodes lie inside the envelope, above its fold found by an
independent fine march; the mean node and normal are the conjugate pinion's (the
crowning keeps them, docs/machine_settings.md sec. 5); slow: the TCA of the written
pair runs through the mean point with its TE0 vertex there.
"""

import dataclasses

import numpy as np
import pytest

from gearcontact.geometry.basic_settings import complementary_pinion_setups, standard_setups
from gearcontact.geometry.conjugate import NODE_MARGIN_MM, nominal_pinion_box
from gearcontact.geometry.generated import EnvelopeSolver, generated_pinion_flank
from gearcontact.geometry.pair import load_pair

PRINT = "tests/geometry/summary_sheets/hypoid_10x41_no16_pair.toml"


@pytest.fixture(scope="module")
def blank_pair():
    """The print's blank alone (no machine tables), as `design --machine-settings` takes
    it; its right-hand twin (a left-hand pair's settings are the twin's mirrored)."""
    with pytest.warns(UserWarning):     # the print's MD datum against the pair's blank
        pair = load_pair(PRINT)
    return dataclasses.replace(pair, pinion_hand="right", machine=(), print_gear=())


def _fold_height(solver, mean, u_m, v_m, v, u_end):
    """The lowest height where the envelope of section ``v`` still has a solution,
    marched down from the mean node in 0.005 mm steps to ``u_end`` (independent of the
    box's own march: no Jacobian threshold, only convergence of the node equations);
    -inf where it reaches ``u_end``."""
    q = mean.q
    for vv in np.linspace(v_m, v, 40):
        q = solver.solve(u_m, vv, q).q
    last = u_m
    for u in np.arange(u_m, u_end, -0.005):
        s = solver.solve(u, v, q, strict=False)
        if not bool(s.converged):
            return last
        q, last = s.q, u
    return -np.inf


def test_standard_pinion_of_the_print_blank_is_cut_inside_its_envelope(blank_pair):
    pair = blank_pair
    blank = pair.blank
    std = standard_setups(pair)
    cone, _ = nominal_pinion_box(blank, pair.pinion_face_width_mm)
    u_m, v_m = float(cone.root_offset_mm), float(blank.pitch_point_mm[0])
    conj = complementary_pinion_setups(pair)
    for side in ("drive", "coast"):
        flank, nodes = generated_pinion_flank(std["pinion", side], blank,
                                              pinion_face_width_mm=pair.pinion_face_width_mm,
                                              n_u=12, n_v=16)
        b = flank.boundary
        bottom = b.u_root - NODE_MARGIN_MM[0]
        solver = EnvelopeSolver(std["pinion", side], blank, cone)
        mean = solver.solve(u_m, v_m, solver.initial_guess(u_m, v_m))
        # the bottom row's toe-corner node (a margin below the box and beyond the toe)
        # lies above the fold of its section (the envelope exists there): measured on
        # the coast side, fold 1.745 mm, bottom row 1.777 mm (it was 1.736: below the
        # fold, the refusal); the drive side has no fold within 0.3 mm below its row
        fold = _fold_height(solver, mean, u_m, v_m, b.v_toe - NODE_MARGIN_MM[1], bottom - 0.3)
        assert fold < bottom
        if side == "coast":        # not vacuous: the fold lies within the margin's reach
            assert fold > bottom - NODE_MARGIN_MM[0]
        # the mean node and normal of the crowned pinion are the conjugate pinion's
        # (exact node solves to 1e-10; 1e-9 mm / 1e-12 asserted as in test_basic_settings)
        ref = EnvelopeSolver(conj[side], blank, cone)
        m0 = ref.solve(u_m, v_m, ref.initial_guess(u_m, v_m))
        assert np.abs(mean.x_mm - m0.x_mm).max() < 1e-9
        assert np.abs(mean.n - m0.n).max() < 1e-12
        assert np.all(nodes.converged)


@pytest.mark.slow
def test_tca_of_the_print_blanks_standard_settings_has_its_vertex_at_the_mean_point(blank_pair):
    # what `design --machine-settings` writes for the print's blank (left hand, as typed)
    # and `tca` then runs (it was refused at the coast toe-root node). The crowning keeps
    # the conjugate pinion's mean node and normal and relieves the pinion everywhere
    # else, so the mean node is the contact at the reference phase (P0, a surface
    # contact: mating-point solve to 1e-10; 1e-6 mm asserted) and the TE0 over the pitch
    # has its vertex there: every other phase's TE0 on one side of 0 (measured: drive
    # 0 to 11.42 arcsec, coast -7.29 to 0, 31 phases, the vertex at the middle phase;
    # 1e-6 arcsec asserted, the TE0 solves' rounding)
    from gearcontact.geometry.basic_settings import standard_machine_pair
    from gearcontact.tca.analysis import analyze_pair

    pair = dataclasses.replace(blank_pair, pinion_hand="left")
    cut = standard_machine_pair(pair)
    for side, sign in (("drive", 1.0), ("coast", -1.0)):
        res, flanks = analyze_pair(cut, side=side, phases=31)
        p0, mean = res.mean_point, flanks.mean_contact[side]
        assert abs(p0.u1 - mean["pinion_uv"][0]) < 1e-6
        assert abs(p0.v1 - mean["pinion_uv"][1]) < 1e-6
        assert not p0.edge_contact
        env = sign * np.asarray(res.cycle.envelope_arcsec)
        k = int(np.argmin(np.abs(res.cycle.phi1_rad - p0.phi1_rad)))
        assert abs(env[k]) < 1e-6 and env.min() > -1e-6
        assert res.cycle.te0_pp_arcsec > 1.0          # crowned: not the line contact


@pytest.mark.slow
def test_te0_of_the_print_blanks_standard_settings_is_bracketed_by_the_relief(blank_pair):
    # First order, the TE0 of the crowned pinion at a phase is the least relief, over
    # the lever, of the crowned pinion against the exactly conjugate (complementary,
    # uncrowned) one along the conjugate contact line of that phase; the relief about
    # the pinion axis over the lever is the angle between the two sheets, so TE0 =
    # min over the line of (psi_conj - psi_std) / ratio (gear rad). The TCA's contact
    # lies off that line, where the conjugate pair's own separation adds to the relief:
    # the relief at the TCA's contact point is a lower bound, the least relief over the
    # line (sampled at 61 points of the gear face: the sample can only overshoot) an
    # upper bound. Measured on the right-hand twin, 31 phases: lower 0.5 to 0.8 % under
    # the TE0, upper 0.65 to 6.5 % over it (the sampling), both sides; each bound asserted
    # within 1e-3 arcsec (the sheets' interpolation, 1e-6 mm over a ~35 mm lever: 0.006
    # arcsec of pinion, 0.0015 of gear, compared as a difference of two sheets at one point)
    import math

    from gearcontact.geometry.basic_settings import standard_machine_pair
    from gearcontact.geometry.flank import build_flanks
    from gearcontact.tca.analysis import analyze_pair
    from gearcontact.tca.line_contact import _line_point
    from gearcontact.tca.types import ContactGuess, EdgeContact, TcaConvergenceError

    arcsec = 180.0 * 3600.0 / math.pi / blank_pair.ratio        # gear arcsec per pinion rad
    conj = build_flanks(standard_machine_pair(blank_pair, lengthwise_crowning_um=0.0,
                                              blade_profile_crowning_um=0.0))
    kin = blank_pair.kinematics()
    for side in ("drive", "coast"):
        res, flanks = analyze_pair(standard_machine_pair(blank_pair), side=side, phases=31)
        crowned, exact, gear = (flanks.pinion.side(side), conj.pinion.side(side),
                                conj.gear.side(side))
        checked = 0
        for k in range(0, 31, 3):
            c = res.cycle.contact[k]
            if c.edge_contact:
                continue
            te = abs(float(res.cycle.envelope_arcsec[k]))
            lower = abs(float(exact.psi(c.u1, c.v1) - crowned.psi(c.u1, c.v1))) * arcsec
            guess = ContactGuess(c.u1, c.v1, c.u2, c.v2, c.phi1_rad, c.phi2_rad)
            upper = np.inf
            for v2 in np.linspace(*gear.v_range, 61):
                try:
                    mp = _line_point(exact, gear, kin, dataclasses.replace(guess, v2=float(v2)))
                except (EdgeContact, TcaConvergenceError):   # no line point at this v2
                    continue
                if exact.boundary.contains(mp.u1, mp.v1):
                    upper = min(upper, abs(float(exact.psi(mp.u1, mp.v1)
                                                 - crowned.psi(mp.u1, mp.v1))) * arcsec)
            assert lower <= te + 1e-3 and te <= upper + 1e-3, (side, k, lower, te, upper)
            checked += 1
        assert checked >= 8
