"""Shared TCA fixtures on the built-in s0003-centred pair (tests/conftest.py builds the
pair and its flanks once per session)."""

import math
from types import SimpleNamespace

import numpy as np
import pytest

from gearcontact.geometry.cylindrical.pair import CylindricalPair, ToothModifications
from gearcontact.tca.cylindrical_cycle import cylindrical_mesh_cycle

from gearcontact.tca.analysis import analyze_pair
from gearcontact.tca.solve import solve_tca


@pytest.fixture(scope="session")
def s0003_drive(s0003_centred):
    """The full unloaded analysis of the drive side (61 phases per pitch)."""
    s0003_pair, s0003_flanks = s0003_centred
    return analyze_pair(s0003_pair, side="drive", flanks=s0003_flanks)[0]


@pytest.fixture(scope="session")
def full_path(s0003_centred, s0003_drive):
    """The nominal drive path of one pair over the mesh cycle's phases with its whole
    edge tails (no TE0 limit: the mesh cycle cuts tails that cannot carry)."""
    s0003_pair, s0003_flanks = s0003_centred
    pinion = s0003_flanks.flank("pinion", "drive")
    gear = s0003_flanks.flank("gear", "drive")
    return solve_tca(pinion, gear, s0003_pair.kinematics(), s0003_drive.cycle.path.phi1_rad,
                     start=s0003_drive.mean_point.as_guess(), edge_te_limit_arcsec=np.inf)


def spur_23x67(**kw):
    """The 23/67 m_n 2 spur pair (x = 0.3 / 0.1, b = 20 mm, zero backlash) of the
    cylindrical TCA tests."""
    return CylindricalPair(name="t", pinion_teeth=23, gear_teeth=67, normal_module_mm=2.0,
                           pinion_face_width_mm=20.0, gear_face_width_mm=20.0,
                           helix_angle_deg=0.0, pinion_hand=None, profile_shift_pinion=0.3,
                           profile_shift_gear=0.1, **kw)


@pytest.fixture(scope="session")
def spur_tip_relief():
    """:func:`spur_23x67` with a pinion tip relief C_a = 20 um from u_Ca midway between
    the lowest (u_a1 - p_bt) and the highest (u_Nf1 + p_bt) point of single contact,
    and its 121-phase cycle (cw), with the roll lengths the closed forms need."""
    g = spur_23x67().geometry
    rolls = g.roll_lengths_mm("pinion")
    p_bt = g.transverse_base_pitch_mm
    lo, hi = rolls["tip"] - p_bt, rolls["active_start"] + p_bt
    u_ca = 0.5 * (lo + hi)
    rb1, rb2 = 0.5 * g.base_diameter_pinion_mm, 0.5 * g.base_diameter_gear_mm
    c_a = 20.0e-3
    pair = spur_23x67(modifications_pinion=ToothModifications(
        tip_relief_um=c_a * 1e3, tip_relief_start_diameter_mm=2 * math.hypot(u_ca, rb1)))
    return SimpleNamespace(pair=pair, cycle=cylindrical_mesh_cycle(pair, phases=121),
                           c_a=c_a, u_ca=u_ca, lo=lo, hi=hi, rolls=rolls, p_bt=p_bt,
                           rb1=rb1, rb2=rb2)


@pytest.fixture(scope="session")
def generated_hypoid_problem():
    """The local synthesis' fixed part (tca.setting_synthesis.SynthesisProblem, 40 x 50
    nodes) of the 13/26 hypoid whose gear is generated (tests/design_space.py), built
    once per session for the synthesis' and its reach model's tests."""
    from design_space import generated_hypoid

    from gearcontact.tca.setting_synthesis import SynthesisProblem

    return SynthesisProblem(generated_hypoid())
