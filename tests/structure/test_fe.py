"""3D finite elements of a tooth (gearcontact.structure.fe) and shell vs FE.

Truths:
- P2 tetrahedra on a clamped cantilever plate: the far-field deflection (mid-length,
  bottom face, under a tip line of point loads on the top face) against the Timoshenko
  beam: within 6 % (a 3D clamp is stiffer than a beam's: -3 % per BENDING background;
  the coarse default mesh adds ~1-2 %);
- the same for the shell (independent code): shell and FE agree within 3 % there;
- Maxwell-Betti symmetry of the FE compliance before symmetrization (1e-9 relative);
- shell vs FE on the real teeth of both s0003 pairs (s0003-centred and the calibrated
  s0003, whose teeth are 24 % deeper), the FE on the teeth's real roots (the default,
  structure.root_fillet; docs/bending.md sec. 10), under distributed loads (segment
  loads of 5 node columns around a 3 x 3 lattice of the design flank and line loads
  over the face at its three heights; deflection of the back-flank points behind the
  loaded ones). Default mesh: shell / FE within 0.84 .. 1.19, the calibration's own
  band: the rim factor (structure.shell.RIM_STIFFENING, 1.49) is the one minimizing
  the largest |log(shell / FE)| over eight teeth on this mesh (these four and the
  F.2 pinions and gear; benchmarks/bench_rim_calibration.py), which leaves 0.842 ..
  1.186 (the F.2 machine pinion lowest, the s0003 pinion highest), rounded outward to
  two digits: the band states the model's accuracy on its calibration set; no single
  factor fits these teeth within the former 15 % (at every factor from 1.3 to 1.8 the
  s0003 pinion's largest ratio is 1.38..1.44 x the F.2 pinion's smallest, the 15 %
  band spans 1.15 / 0.85 = 1.35). Measured here: s0003-centred pinion
  1.005..1.129, its gear 0.911..1.002, the s0003 gear 0.868..0.936, the s0003 pinion
  1.090..1.186. The s0003 pinion's slot closes in a V at the toe (its fillets cross
  above the root cone, structure.root_fillet): its real root is meshed, no fallback,
  no warning. Finer mesh 20 x 8 x 4 + 6 (slow suite): 30 % (measured s0003-centred
  pinion 1.02..1.29 with the factor 1.45, the largest at the segment loads low on the
  flank: the factor is fitted on the default mesh, where a real-root tooth costs
  seconds instead of 18 minutes here, and the finer mesh spreads the ratios as it did
  for the ellipse-root calibration, 0.82..1.22 against 0.89..1.11; with 1.49: that
  pinion 0.996..1.265, its gear 0.898..1.084, the s0003 gear 0.854..0.994); the s0003
  pinion spreads further there, 1.057..1.302, outside the 30 % at its highest load: a
  strict xfail with the plate's rim, reported (docs/bending.md sec. 10), not tolerated;
  with the rim block as a Ritz solid (structure.shell.RIM_BLOCK, the default since
  docs/bending.md sec. 13) the shell's default rim factor is 1.175 and that pinion is
  inside the 30 % (0.944..1.208): asserted.
  Point loads are not compared: neither model has a
  converged local value under a point load (Mindlin: log-singular, grows with the
  Ritz order; 3D: 1/r, grows with mesh refinement) and the local part is the
  half-space's in the LTCA. What remains: the plate (no membrane-curvature coupling,
  no through-thickness compression) follows the FE's whole-face line load low on the
  flank less well than its short segment loads (docs/bending.md sec. 3); the FE rim
  segment (free sides, clamped bottom) is itself a model of the real rim;
- bad input: mesh sizes, rim / fillet sizes -> InputRangeError (before meshing); a
  body with crossing faces -> InputRangeError "FE mesh" (inverted cells).
"""

import warnings

import numpy as np
import pytest

from gearcontact.materials import Material
from gearcontact.structure.compliance import (EllipseRootWarning, FeMesh, concat_points,
                                              flank_compliance)
from gearcontact.structure.fe import build_fe
from gearcontact.structure.shell import RIM_BLOCK, build_shell
from gearcontact.structure.tooth import RectangularPlate
from gearcontact.validation import InputRangeError

pytest.importorskip("skfem")

E_MPA, NU = 200_000.0, 0.3


def test_cantilever_far_field_against_beam_and_shell():
    L, W, t = 10.0, 4.0, 2.0
    plate = RectangularPlate(L, W, t, Material(E_MPA, NU))
    fe = build_fe(plate, n_xi=4, n_eta=20, n_zeta=2, n_rim=0)
    xi = fe.xi_levels
    tip, vt = fe.node_points("drive", xi, np.ones_like(xi))
    mid, vm = fe.node_points("coast", xi, np.zeros_like(xi))
    pts = concat_points(tip, mid)
    G = fe.compliance(pts, np.concatenate([vt, vm]))
    Gs = build_shell(plate, order=8).compliance(pts).matrix()
    k = len(xi)
    w = np.full(k, 1.0)
    w[[0, -1]] = 0.5
    w /= w.sum()
    # tip load down (-z), mid-length point measured along +z (coast inward): minus sign
    fe_mid, shell_mid = -(w @ G[k:, :k] @ w), -(w @ Gs[k:, :k] @ w)
    I, A, a = W * t ** 3 / 12, W * t, L / 2
    beam = a ** 2 * (3 * L - a) / (6 * E_MPA * I) + a / (5 / 6 * E_MPA / (2 * (1 + NU)) * A)
    assert fe_mid == pytest.approx(beam, rel=0.06)
    assert fe_mid == pytest.approx(shell_mid, rel=0.03)


def test_fe_reciprocity():
    plate = RectangularPlate(6.0, 4.0, 2.0, Material(E_MPA, NU))
    fe = build_fe(plate, n_xi=4, n_eta=6, n_zeta=2, n_rim=0)
    pts, v = fe.node_points("drive", [-1.0, 0.0, 0.5], [1.0, 0.0, -0.33])
    n_dofs = fe.n_dofs
    F = np.zeros((n_dofs, 3))
    for c, (vi, d) in enumerate(zip(v, pts.direction)):
        F[fe._nodal_dofs[:, vi], c] = d
    U = np.zeros_like(F)
    U[fe._free] = fe._lu.solve(np.ascontiguousarray(F[fe._free]))
    raw = F.T @ U
    assert np.allclose(raw, raw.T, rtol=1e-9, atol=0)


#: Shell / FE under distributed loads: the calibration's band on the default mesh (the
#: eight-tooth fit's 0.842 .. 1.186 rounded outward), 30 % on the finer mesh (module
#: docstring).
BAND = (0.84, 1.19)
TOLERANCE_FINE = 0.30


#: The teeth of both s0003 pairs.
TEETH = [("s0003-centred", "pinion"), ("s0003-centred", "gear"), ("s0003", "gear"),
         ("s0003", "pinion")]
#: On the finer mesh the s0003 pinion (V-slot root) leaves the 30 % with the plate's rim
#: (1.057..1.302): a strict xfail there; with the block model (structure.shell.RIM_BLOCK,
#: docs/bending.md sec. 13) it is inside (0.944..1.208): the rim stiffness growing with
#: the 7-tooth pinion's wrap that the plate's rim lacked, its gear's ratios rising the
#: while (not a uniform factor shift), so the test asserts the unchanged 30 % there.
TEETH_FINE = TEETH[:3] + [pytest.param("s0003", "pinion", marks=pytest.mark.xfail(
    not RIM_BLOCK, strict=True, raises=AssertionError,
    reason="the plate's rim: shell / FE 1.057..1.302 on 20 x 8 x 4 + 6 on the V-slot "
           "real root (docs/bending.md sec. 10)"))]


def _shell_vs_fe(pair, flanks, name, member, **kw):
    """flank_compliance with the FE, which meshes the tooth's real root (no warning)."""
    with warnings.catch_warnings():
        warnings.simplefilter("error", EllipseRootWarning)
        res = flank_compliance(pair, member, flanks=flanks, fe=True, **kw)
    assert res.fe_root == "cutter" and res.fe_root_note is None
    return res


@pytest.mark.parametrize("name, member", TEETH)
def test_shell_vs_fe_coarse(pairs, name, member):
    pair, flanks = pairs[name]
    res = _shell_vs_fe(pair, flanks, name, member, fe_mesh=FeMesh(12, 6, 3, 4))
    # the FE point-load matrix is symmetric and its diagonal (with the local
    # indentation of a point load) exceeds the segment-load deflections
    assert np.allclose(res.fe_mm_per_n, res.fe_mm_per_n.T)
    assert np.all(np.diag(res.fe_mm_per_n) > res.segment_fe_mm_per_n)
    ratio = res.ratios()
    assert np.all((ratio >= BAND[0]) & (ratio <= BAND[1])), ratio


def test_a_root_that_cannot_be_built_falls_back_to_the_ellipse(s0003_centred):
    # where the real root cannot be built (here: no fillet for the member) the FE meshes
    # the ellipse root, warns and says why; the same numbers as the ellipse asked for
    # (one FE model, built twice: equal to rounding, 1e-12 relative)
    from gearcontact.structure.compliance import compare_on_root
    from gearcontact.structure.shell import tooth_shell

    pair, flanks = s0003_centred
    shell = tooth_shell(flanks, "gear", material=pair.gear_material)
    kw = dict(name="s0003-centred", side="drive", xi=(0.0,), eta=(0.0,), fe=True,
              fe_mesh=FeMesh(6, 2, 1, 1, 1, 1))
    with pytest.warns(EllipseRootWarning, match="s0003-centred gear: FE on the ellipse root"):
        res = compare_on_root(shell, lambda: (None, "no cutter"), fe_root="cutter", **kw)
    assert res.fe_root == "ellipse" and res.fe_root_note == "no cutter"
    ref = compare_on_root(shell, None, fe_root="ellipse", **kw)
    assert res.line_fe_mm_per_n == pytest.approx(ref.line_fe_mm_per_n, rel=1e-12)


@pytest.mark.slow
@pytest.mark.parametrize("name, member", TEETH_FINE)
def test_shell_vs_fe_fine(pairs, name, member):
    pair, flanks = pairs[name]
    res = _shell_vs_fe(pair, flanks, name, member, xi=(-0.5, 0.0, 0.5),
                       eta=(-0.5, 0.0, 0.5), fe_mesh=FeMesh(20, 8, 4, 6))
    ratio = res.ratios()
    assert np.all((ratio >= 1.0 - TOLERANCE_FINE) & (ratio <= 1.0 + TOLERANCE_FINE)), ratio


def test_bad_input(s0003_centred):
    plate = RectangularPlate(6.0, 4.0, 2.0, Material(E_MPA, NU))
    with pytest.raises(InputRangeError, match="n_eta"):
        build_fe(plate, n_eta=1, n_rim=0)
    with pytest.raises(InputRangeError, match="n_rim"):
        build_fe(plate, n_rim=2)            # a plate has no member axis for a rim
    # a body whose faces cross (thickness < 0 towards the tip): inverted cells
    with pytest.raises(InputRangeError, match="FE mesh"):
        build_fe(_Crossing(Material(E_MPA, NU)), n_xi=2, n_eta=4, n_zeta=1, n_rim=0)
    pair, flanks = s0003_centred
    from gearcontact.structure.tooth import tooth_geometry

    tooth = tooth_geometry(flanks, "gear", material=pair.gear_material)
    with pytest.raises(InputRangeError, match="rim_depth_mm"):
        build_fe(tooth, n_xi=2, n_eta=2, n_zeta=1, n_rim=2, rim_depth_mm=-1.0)
    with pytest.raises(InputRangeError, match="fillet_mm"):
        build_fe(tooth, n_xi=2, n_eta=2, n_zeta=1, n_rim=2, fillet_mm=0.0)


class _Crossing(RectangularPlate):
    """A plate whose thickness goes negative towards the tip (faces crossing)."""

    def __init__(self, mat):
        super().__init__(10.0, 4.0, 1.0, mat)

    def _thickness(self, eta):
        return 1.0 - 1.5 * (np.asarray(eta) + 1.0) / 2.0
