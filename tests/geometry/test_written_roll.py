"""The fitted roll as `design` writes it (geometry.written_roll; docs/machine_settings.md
sec. 5, "The written roll (session 29)").

The finding (session 28's audit): `design --pair s0003 --machine-settings` fits the drive
side to s0003's all-zero `[easeoff.drive]` and wrote its roll as ratio 10.000000000270727,
2C -1.2229209666587484e-11, 6D -8.745328398663583e-11: the fit's rounding, claimed as a
modified roll. The drive set-up below is the one it wrote (every value copied from the
file, 17 digits); its seed is the same set-up with the conjugate pinion's roll (ratio
z2 / z1 = 70 / 7 = 10, no modified roll: s0003's gear is formate, its own generating gear).

Truths:
- brute force: the flank generated with the fitted roll against the flank generated with
  the seed's, at the same exact nodes (the same active box, so the same axial positions
  and radii), their largest distance along the normal, for the finding and for each term
  of the motion alone at a size well above the nodes' accuracy (1e-14 mm residuals);
- the rule's bound is at least that (first order in the departure; the second order of
  a 1e-6 departure is 1e-12 of it) and the first-order displacement it bounds,
  dphi(psi) (x_axis x X) . n at each node, equals the brute force to 1e-12 mm (the
  nodes' own residual, 1e-13 mm, and the second order, 1e-12 at 1e-6 mm);
- the writer replaces the roll, and only the roll, bit for bit, mirrored for a left-hand
  pair (the modified roll's even terms change sign, machine.mirror_setup).
"""

import dataclasses
from types import SimpleNamespace

import numpy as np
import pytest

from gearcontact.geometry.generated import generated_pinion_box, generated_pinion_flank
from gearcontact.geometry.machine import mirror_setup, setup_from_tables
from gearcontact.geometry.pair import load_pair
from gearcontact.geometry.written_blade import STRAIGHT_DEVIATION_MM
from gearcontact.geometry.written_roll import (motion_departure_mm, roll_coefficients,
                                               roll_reach, written_rolls)

#: [machine.pinion.drive] as `design --pair s0003 --machine-settings` wrote it (d8602d27).
FITTED = dict(radial_distance_mm=48.680562012150595, cradle_angle_deg=87.45873494149679,
              machine_root_angle_deg=0.0, machine_centre_to_back_mm=-17.949616491294215,
              sliding_base_mm=3.078924362560924, blank_offset_mm=19.0,
              ratio_of_roll=10.000000000270727, tilt_deg=6.849999999999996,
              swivel_deg=-59.90597528931133,
              modified_roll_2c_per_rad=-1.2229209666587484e-11,
              modified_roll_6d_per_rad2=-8.745328398663583e-11)
BLADE = dict(kind="outside", blade_angle_deg=15.67448655617995,
             point_radius_mm=43.66259551713336, edge_radius_mm=0.1, profile_radius_mm=0.0,
             profile_reference_mm=0.7313967978387466)


@pytest.fixture(scope="module")
def drive():
    """s0003, its fitted drive set-up, the seed's, the seed's node grid (9 x 11 exact
    nodes on its active box) and the rule's reach (Psi, r_max) of the fitted set-up."""
    pair = load_pair("s0003")
    fitted = setup_from_tables("pinion", "drive", FITTED, BLADE)
    exact = dict(FITTED, ratio_of_roll=70 / 7)
    del exact["modified_roll_2c_per_rad"], exact["modified_roll_6d_per_rad2"]
    seed = setup_from_tables("pinion", "drive", exact, BLADE)
    kw = dict(pinion_face_width_mm=pair.pinion_face_width_mm)
    _, box, _ = generated_pinion_box(seed, pair.blank, **kw)

    def nodes(setup):
        return generated_pinion_flank(setup, pair.blank, n_u=9, n_v=11, box=box, **kw)[1]

    reach = roll_reach(fitted, pair.blank, **kw)
    return SimpleNamespace(pair=pair, fitted=fitted, seed=seed, nodes=nodes, base=nodes(seed),
                           reach=reach)


def _measured(drive, setup):
    """(brute-force largest normal distance, first-order prediction's largest error,
    largest node residual), mm."""
    n0, n1 = drive.base, drive.nodes(setup)
    dist = np.einsum("...i,...i", n1.x_mm - n0.x_mm, n0.n)
    a, b = roll_coefficients(setup, drive.seed)
    dphi = sum(ak * n0.psi_rad ** (k + 1) for k, ak in enumerate(a))
    dv = sum(bk * n0.psi_rad ** (k + 1) for k, bk in enumerate(b))
    turn = np.einsum("...i,...i", np.cross([1.0, 0.0, 0.0], n0.x_mm), n0.n)  # pinion axis x
    resid = max(np.abs(n0.residual).max(), np.abs(n1.residual).max())
    return np.abs(dist).max(), np.abs(np.abs(dist) - np.abs(dphi * turn)).max(), resid, dv


def test_the_finding_within_its_bound_and_below_the_rule(drive):
    psi_max, radius = drive.reach
    # the reach read from the node grid: the roll and the radius the flank spans
    assert 0.1 < psi_max < 0.5 and 8.0 < radius < 10.0
    bound = motion_departure_mm(drive.fitted, drive.seed, psi_max_rad=psi_max,
                                radius_mm=radius)
    dist, err, resid, _ = _measured(drive, drive.fitted)
    # measured 2.24e-10 mm against the bound 5.28e-10 mm; the nodes' residuals 5e-14 mm
    assert dist <= bound + resid
    assert bound < STRAIGHT_DEVIATION_MM
    assert err < 1e-12


@pytest.mark.parametrize("change", [dict(ratio_of_roll=10.0 + 1e-6),
                                    dict(modified_roll=(1e-6,)),
                                    dict(modified_roll=(0.0, 1e-5)),
                                    dict(helical_motion=(1e-5,))],
                         ids=["ratio", "2C", "6D", "V1"])
def test_each_term_of_the_motion_within_the_bound(drive, change):
    # each term alone moves the flank by ~1e-6 mm, 1e7 times the nodes' residual
    setup = dataclasses.replace(drive.seed, settings=dataclasses.replace(
        drive.seed.settings, **change))
    psi_max, radius = drive.reach
    bound = motion_departure_mm(setup, drive.seed, psi_max_rad=psi_max, radius_mm=radius)
    dist, err, resid, dv = _measured(drive, setup)
    assert 3e-7 < dist <= bound
    # not vacuous: measured 2.15 for the roll's terms (the flank normal's cosine with the
    # turn's direction at the extreme roll, and r_max against the radius there), 4.2
    # for the slide (the normal's cosine with the cradle axis)
    assert bound < 5.0 * dist
    if "helical_motion" not in change:   # the turn's first order, node by node
        assert err < 1e-12


@dataclasses.dataclass(frozen=True)
class _Cut:
    """What the writer reads of a pair (a GearPair holds all four flanks' tables)."""
    machine: tuple
    blank: object
    pinion_face_width_mm: float
    pinion_hand: str = "right"


def test_writer_replaces_the_roll_only(drive):
    cut = _Cut((drive.fitted,), drive.pair.blank, drive.pair.pinion_face_width_mm)
    fit = SimpleNamespace(setup=drive.fitted, seed=drive.seed)
    written, notes = written_rolls(cut, {"drive": fit})
    (w,) = written.machine
    assert w.settings == drive.seed.settings and w.blade == drive.fitted.blade
    assert len(notes) == 1 and notes[0].startswith(
        "machine.pinion.drive: the fitted motion (ratio of roll 10.0000000003, 2C -1.22e-11, "
        "6D -8.75e-11) departs 5e-07 um")
    # a departure above the rule (2C 1e-6: 1.9e-6 mm bound) is written as fitted
    crowned = dataclasses.replace(drive.fitted, settings=dataclasses.replace(
        drive.fitted.settings, modified_roll=(1e-6,)))
    kept, notes = written_rolls(dataclasses.replace(cut, machine=(crowned,)), {
        "drive": SimpleNamespace(setup=crowned, seed=drive.seed)})
    assert kept.machine == (crowned,) and notes == []


def test_writer_mirrors_the_seed_for_a_left_hand_pair(drive):
    # a seed with a modified roll of its own (a hypoid with a generated gear: its crown
    # pinion fitted to the conjugate first) and a fit's rounding on top, on the
    # right-hand twin; the left-hand pair writes their mirror images
    seed = dataclasses.replace(drive.seed, settings=dataclasses.replace(
        drive.seed.settings, modified_roll=(0.01, 0.002)))
    fitted = dataclasses.replace(seed, settings=dataclasses.replace(
        seed.settings, ratio_of_roll=10.0 + 3e-10, modified_roll=(0.01 - 1e-11, 0.002)))
    cut = _Cut((mirror_setup(fitted),), drive.pair.blank, drive.pair.pinion_face_width_mm,
               pinion_hand="left")
    written, notes = written_rolls(cut, {"drive": SimpleNamespace(setup=fitted, seed=seed)})
    assert written.machine == (mirror_setup(seed),) and len(notes) == 1
    assert written.machine[0].settings.modified_roll == (-0.01, 0.002)
