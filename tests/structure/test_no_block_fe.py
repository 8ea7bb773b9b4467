"""Teeth without a rim block below the fillet against the 3D FE (docs/bending.md sec. 13,
"The factor on a tooth without a block, against the FE", session 24).

Sec. 13's rule gives a tooth whose rim leaves no block below the fillet the plate through
the fillet at the block model's factor (``rim_block.BLOCK_RIM_STIFFENING``, 1.175),
carried over by continuity from the eight block teeth of the calibration. Here it is
measured.

Truth: the P2 FE (``structure.fe``) of the tooth on its real root (the calibration's
truth, docs/bending.md sec. 10). Both models clamp the rim's bottom at the same depth D
below the root line, D being the shell's own fillet height: the shell's block has depth
0 exactly, and the FE keeps the thin rim D - cone depth below its slot bottoms
(0.28 mm on the s0003-centred gear). The three gears of the calibration pairs are the
teeth whose real root ends above their fillet height. Loads are the calibration's 12
distributed loads.

Declared before measuring: "calibrated" if every shell / FE ratio lies in the band the
block teeth are held to on the default mesh, 0.84 .. 1.19 (``test_fe.BAND``; the eight
block teeth give 0.880 .. 1.145 there).

Measured: it differs. The shell is 1.22 .. 2.04 times the FE, and no factor fits: even
1000, an almost rigid fillet, leaves 1.00 .. 1.44. The slow test is therefore a strict
xfail with those ratios. The default-suite test asserts the measured side on a coarse
mesh instead: the shell stays softer than the band by more than the coarse mesh's
measured error (docs/bending.md).

Session 25 located the surplus (docs/bending.md sec. 13, "Where the no-block surplus
sits"): it is the plate tooth's own transverse shear within a thickness of a rigid clamp,
a property of the Mindlin plate against 3D elasticity that a flat plate shows too
(:func:`test_thick_plate_near_a_clamp_is_softer_than_the_solid`).
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from gearcontact.materials import Material
from gearcontact.structure.compliance import (EllipseRootWarning, FeMesh, _cutter_fillets,
                                              _distributed, _load_sets, compare_on_root,
                                              concat_points, shell_compliance)
from gearcontact.structure.rim import rim_segment
from gearcontact.structure.rim_block import BLOCK_RIM_STIFFENING, NoBlockWarning, has_block
from gearcontact.structure.fe import build_fe
from gearcontact.structure.shell import ORDER, ORDER_FACE, build_shell, tooth_shell
from gearcontact.structure.tooth import RectangularPlate, tooth_geometry

pytest.importorskip("skfem")

#: The band the block teeth are held to on the default FE mesh (test_fe.BAND: the
#: calibration's own band, the eight-tooth fit rounded outward).
BAND = (0.84, 1.19)
#: The coarse mesh of the default-suite test: n_eta 6 keeps the lattice heights
#: -1/3, 0, 1/3 on node lines.
COARSE = FeMesh(8, 6, 2, 2, 2, 1)
#: Mesh error of COARSE: the largest |log(ratio_coarse / ratio_default)| over the 12
#: loads of the three gears (measured 0.092, at the F.2 gear's segment loads, whose 5
#: node columns are longer on 8 columns than on 12), rounded up to 0.01
#: (docs/bending.md).
COARSE_LOG_ERROR = 0.10
#: Shell / FE of the three gears on the default mesh at 1.175 (docs/bending.md): the
#: strict xfail's reason.
MEASURED = {"s0003-centred gear": (1.350, 2.037), "s0003 gear": (1.223, 1.799),
            "F.2 gear": (1.293, 2.015)}


def no_block_ratios(pair, flanks, member: str, fe_mesh: FeMesh, *,
                    solid_tooth: bool = False, both: bool = False):
    """Shell / FE of ``member`` under the 12 distributed loads, both models clamped at the
    shell's fillet height (no block below the fillet). The shell is the default model
    (``tooth_shell``, the block model at its factor), with ``solid_tooth`` the tooth as
    the Ritz solid of ``structure.tooth_solid`` (session 25); the FE is on the real
    root."""
    material = getattr(pair, f"{member}_material")
    tooth = tooth_geometry(flanks, member, material=material)
    rim = rim_segment(tooth, depth_mm=rim_segment(tooth).fillet_mm,
                      stiffening=BLOCK_RIM_STIFFENING)
    assert not has_block(rim) and rim.depth_mm == rim.fillet_mm
    if both:        # (plate, solid) on one FE: the solid's shell values over the plate's FE
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", NoBlockWarning)
            plate = tooth_shell(flanks, member, material=material, rim=rim)
        res = no_block_result(pair, flanks, member, fe_mesh, rim, plate)
        solid = shell_compliance(build_shell(tooth, order=ORDER, order_face=ORDER_FACE,
                                             rim=rim, rim_block=True, solid_tooth=True),
                                 side=pair.design_side, xi=LATTICE[0], eta=LATTICE[1],
                                 fe_mesh=fe_mesh)
        fe = np.concatenate([res.segment_fe_mm_per_n, res.line_fe_mm_per_n])
        return res.ratios(), np.concatenate([solid.segment_shell_mm_per_n,
                                             solid.line_shell_mm_per_n]) / fe
    with warnings.catch_warnings():
        # the shell says it has no block (NoBlockWarning, tested in test_rim_block.py);
        # tooth_shell is cached, so it says so on the first call only
        warnings.simplefilter("ignore", NoBlockWarning)
        shell = (build_shell(tooth, order=ORDER, order_face=ORDER_FACE, rim=rim,
                             rim_block=True, solid_tooth=True) if solid_tooth
                 else tooth_shell(flanks, member, material=material, rim=rim))
    return no_block_result(pair, flanks, member, fe_mesh, rim, shell).ratios()


#: The lattice (xi, eta) of the 12 loads (the calibration's).
LATTICE = ((-0.5, 0.0, 0.5), (-1 / 3, 0.0, 1 / 3))


def no_block_result(pair, flanks, member, fe_mesh, rim, shell):
    """``shell`` and the FE on the real root under the 12 loads (:func:`no_block_ratios`)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", NoBlockWarning)         # see no_block_ratios
        warnings.simplefilter("error", EllipseRootWarning)      # the real root or nothing
        res = compare_on_root(shell, lambda: _cutter_fillets(pair, flanks, member),
                              name=pair.name, side=pair.design_side, xi=LATTICE[0],
                              eta=LATTICE[1], fe=True, fe_mesh=fe_mesh, fe_root="cutter")
    assert res.fe_root == "cutter"
    return res


@pytest.fixture(scope="module")
def coarse_centred(s0003_centred):
    """(plate, solid) shell / FE of the s0003-centred gear without a block on COARSE, one FE
    for both (seconds)."""
    pair, flanks = s0003_centred
    return no_block_ratios(pair, flanks, "gear", COARSE, both=True)


def test_no_block_shell_is_softer_than_the_band_on_a_coarse_mesh(coarse_centred):
    """The s0003-centred gear on COARSE (seconds). Shell / FE at every load is above
    the band's top by more than the coarse mesh's measured error: it is at least
    BAND[1] * exp(COARSE_LOG_ERROR) = 1.315 (measured 1.362 .. 1.919). The shell is
    softer than the FE, and the declared "calibrated" does not hold."""
    r = coarse_centred[0]
    assert np.all(r >= BAND[1] * np.exp(COARSE_LOG_ERROR)), r


def test_solid_tooth_is_inside_the_band_on_a_coarse_mesh(coarse_centred):
    """The declared second attempt (docs/bending.md sec. 13, session 25): the s0003-centred
    gear without a block as the Ritz solid on COARSE. Every shell / FE ratio within the
    band widened on each side by the coarse mesh's error (declared before this test ran:
    [0.84 exp(-0.10), 1.19 exp(0.10)] = [0.760, 1.315]; on the default mesh the solid
    gives 0.969 .. 0.982 on this gear)."""
    r = coarse_centred[1]
    lo, hi = BAND[0] * np.exp(-COARSE_LOG_ERROR), BAND[1] * np.exp(COARSE_LOG_ERROR)
    assert np.all((r >= lo) & (r <= hi)), r


@pytest.mark.slow
@pytest.mark.parametrize("label", list(MEASURED))
def test_solid_tooth_within_the_calibration_band(gears, label):
    """The declared criterion for the solid tooth: on the default mesh every shell / FE
    ratio of the three no-block gears lies in BAND (measured 0.969 .. 0.982, 0.948 ..
    0.968, 0.935 .. 0.969; degrees one step up, (14, 10, 4): 0.886 .. 0.968)."""
    pair, flanks = gears[label]
    r = no_block_ratios(pair, flanks, "gear", FeMesh(), solid_tooth=True)
    assert np.all((r >= BAND[0]) & (r <= BAND[1])), r


@pytest.mark.slow
@pytest.mark.parametrize("label", [pytest.param(k, marks=pytest.mark.xfail(
    strict=True, raises=AssertionError,
    reason=f"the no-block shell at 1.175 is {lo}..{hi} x the FE on the default mesh "
           "(docs/bending.md sec. 13, session 24): not calibrated"))
    for k, (lo, hi) in MEASURED.items()])
def test_no_block_teeth_within_the_calibration_band(gears, label):
    """The declared criterion: on the default mesh (the calibration's), every shell / FE
    ratio of the no-block tooth lies in BAND (the block teeth's band)."""
    pair, flanks = gears[label]
    r = no_block_ratios(pair, flanks, "gear", FeMesh())
    assert np.all((r >= BAND[0]) & (r <= BAND[1])), r


def _flat_plate_line_ratios(thickness_mm: float) -> np.ndarray:
    """Shell / FE of a flat plate 2.4 mm long and 8 mm wide, clamped at its root, under
    the line loads at eta = -1/3, 0, 1/3 (a = 0.8, 1.2, 1.6 mm above the clamp): the
    mean back-face deflection behind the loaded front-face nodes of the FE's interior
    columns, as :func:`~gearcontact.structure.compliance.shell_compliance` compares;
    FE 6 x 6 x 2 (P2, clamped at the root line), shell orders 6 / 6 (seconds)."""
    plate = RectangularPlate(2.4, 8.0, thickness_mm, Material(209000.0, 0.3))
    fe = build_fe(plate, n_xi=6, n_eta=6, n_zeta=2, n_rim=0)
    shell = build_shell(plate, order=6, order_face=6)
    levels = np.linspace(-1.0, 1.0, 7)
    rows = np.abs(np.array([-1 / 3, 0.0, 1 / 3])[:, None] - levels).argmin(1)
    nodes, sets, _ = _load_sets(np.full(3, 3), rows, 6)
    nx, ny = levels[nodes[:, 0]], levels[nodes[:, 1]]
    pd, vd = fe.node_points("drive", nx, ny)
    pc, vc = fe.node_points("coast", nx, ny)
    G_fe = fe.compliance(concat_points(pd, pc), np.concatenate([vd, vc]))
    both = concat_points(plate.points_at("drive", nx, ny), plate.points_at("coast", nx, ny))
    G_shell = shell.compliance(both).matrix()
    return _distributed(G_shell, sets[3:]) / _distributed(G_fe, sets[3:])


def test_thick_plate_near_a_clamp_is_softer_than_the_solid():
    """The diagnosis' generic fact (docs/bending.md sec. 13, session 25), on a flat plate
    with closed-form faces: for a plate as thick as it is long (t = L = 2.4 mm) the
    Mindlin plate's deflection is larger than the 3D solid's back-face deflection under a
    face load within a thickness of its rigid clamp, the more the nearer (docs: mostly
    because there the section's mean deflection exceeds the back face's) (measured 1.606, 1.335, 1.227 at a / t = 1/3, 1/2, 2/3 on this mesh; 1.539,
    1.286, 1.190 on 12 x 12 x 4 with orders 12 / 12); a thin one (t = L / 4) agrees with
    the FE. Tolerances: the thick plate's ratio at a / t = 1/3 at least 1.4, 0.09 in log
    below the fine mesh's 1.539, twice the mesh error 0.043 (so the test asserts the
    surplus beyond mesh error); the thin plate within 6 % (measured 1.009 .. 1.027 here,
    1.022 .. 1.045 on the fine mesh: its largest ratio plus the mesh error 0.036)."""
    thick = _flat_plate_line_ratios(2.4)
    assert thick[0] >= 1.4, thick
    assert np.all(np.diff(thick) < 0.0), thick             # fading with the height
    thin = _flat_plate_line_ratios(0.6)
    assert np.all(np.abs(thin - 1.0) <= 0.06), thin
