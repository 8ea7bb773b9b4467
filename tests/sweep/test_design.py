"""Design variants of a sweep (:mod:`gearcontact.sweep.design`, their scheduling in
:mod:`gearcontact.sweep.run`).

Truths:

* a variant is the pair with exactly the named TOML key replaced; an impossible value
  is a named error before any flank is built;
* a sweep over lengthwise crowning x E on a LocalCluster of 2 workers equals the serial
  in-process sweep bit for bit (same code, same inputs), and every cell of a variant
  reports the same flank build (one build per variant, shared by its points);
* physics of lengthwise crowning ``c_LC`` (ease-off ``E += c_LC xi^2``, um, xi mm
  along the face): the relief along the path is parabolic in the mesh phase with a
  curvature proportional to ``c_LC``, so the TE0 parabola of each pair, hence the
  envelope's peak to peak ``k (T/2)^2`` over a pitch ``T``, grows proportionally to
  ``c_LC`` (the other ease-off terms of this set-up, profile crowning along the
  valley the path follows, leave no TE; Litvin & Fuentes 2004, sec. 15.5, the
  parabolic function of TE produced by the mismatch along the path); and the relief
  adds ``2 c_LC 1e-3`` 1/mm to the relative curvature along xi, so the paint ellipse
  ``2a = 2 sqrt(2 delta / kappa_min)`` shortens, by at most the factor
  ``sqrt(kappa / (kappa + 2e-3 dc_LC))`` (the whole added curvature acting along the
  major axis): more crowning, larger TE0 and a shorter pattern;
* an ease-off variant applied to the nominal pair's conjugate flanks is the full build
  of the varied pair, bit for bit (the conjugate flanks do not depend on the ease-off);
* a variant whose flanks cannot be built is recorded by name on its cells only.
"""

import numpy as np
import pytest

pytest.importorskip("distributed")
xr = pytest.importorskip("xarray")

from gearcontact.sweep.design import (  # noqa: E402
    Variant,
    build_variant,
    check_variants,
    vary_design,
)
from gearcontact.sweep.grid import SweepGrid, parse_vary  # noqa: E402
from gearcontact.sweep.run import run_sweep  # noqa: E402
from gearcontact.tca.curvature import PAINT_THICKNESS_MM  # noqa: E402
from gearcontact.validation import InputRangeError  # noqa: E402

PHASES = 21
KEY = "easeoff.drive.lengthwise_crowning_um_per_mm2"
DIM = KEY.replace(".", "_")
GRID = SweepGrid((parse_vary("ease-off.drive.lengthwise_crowning_um_per_mm2=0.08:0.16:3"),
                  parse_vary("E=-0.01:0.01:2")), (64.5,))


def _open(report):
    return xr.open_zarr(report.store, consolidated=False).load()


@pytest.fixture(scope="module")
def serial(s0003_centred, tmp_path_factory):
    pair = s0003_centred[0]
    rep = run_sweep(pair, GRID, out=tmp_path_factory.mktemp("serial"), side="drive",
                    phases=PHASES, workers=0, progress=False)
    return rep, _open(rep)


def test_variant_replaces_exactly_the_named_key(s0003_centred):
    pair = s0003_centred[0]
    v = vary_design(pair, {KEY: 0.2, "cutter.radius_mm": 44.0})
    assert v.easeoff_drive.lengthwise_crowning_um_per_mm2 == 0.2
    assert v.cutter.radius_mm == 44.0
    assert v.easeoff_coast == pair.easeoff_coast and v.assembly == pair.assembly
    assert v.easeoff_drive.profile_crowning_um_per_mm2 == \
        pair.easeoff_drive.profile_crowning_um_per_mm2
    # the cutter radius enters the blank design (ISO 23509 Method 1): it changes
    assert v.blank.spiral_angle_gear_deg != pair.blank.spiral_angle_gear_deg
    assert vary_design(pair, {}) is pair


@pytest.mark.parametrize("spec,named", [
    ("cutter.radius_mm=-1:45:2", "cutter.radius_mm"),
    ("cutter.edge_radius_mm=0.1:0.3:2", "cutter.edge_radius_mm"),
    ("easeoff.coast.bias_um_per_mm2=0:2000:2", "easeoff.bias_um_per_mm2")])
def test_impossible_variant_is_named_before_any_build(s0003_centred, spec, named):
    pair = s0003_centred[0]
    grid = SweepGrid((parse_vary(spec),), (64.5,))
    with pytest.raises(InputRangeError) as exc:
        check_variants(pair, grid)
    assert f"--vary {spec.split('=')[0]}=" in str(exc.value) and named in str(exc.value)


def test_cluster_equals_serial_with_one_build_per_variant(s0003_centred, client,
                                                          serial, tmp_path):
    pair = s0003_centred[0]
    rep_s, ds_s = serial
    rep = run_sweep(pair, GRID, out=tmp_path, side="drive", phases=PHASES, client=client,
                    progress=False)
    assert (rep.computed, rep.failed) == (6, 0) and rep_s.computed == 6
    ds = _open(rep)
    assert ds[DIM].attrs == {"units": "um/mm^2", "key": KEY}
    # the build times are timings (they differ between runs); all else bit for bit
    xr.testing.assert_identical(ds.drop_vars("flank_build_s"),
                                ds_s.drop_vars("flank_build_s"))
    for d in (ds, ds_s):
        t = d["flank_build_s"].values
        assert (t > 0).all()
        # one build per variant: every cell of a variant carries the same build time
        assert (t == t[:, :1, :1]).all()
        assert len(np.unique(t)) == 3


def test_lengthwise_crowning_raises_te0_linearly_and_shortens_the_paint(serial):
    _, ds = serial
    c = ds[DIM].values
    for e in range(2):
        te = ds["te0_pp_arcsec"].isel(E_mm=e, torque_nm=0).values
        assert np.all(np.diff(te) > 0)
        # proportional to c_LC: TE0 / c_LC the same at every value within 8 % (the peak
        # to peak is read on 21 sampled phases, which miss the envelope's cusps by a
        # few %: measured spread +-5 % over c_LC = 0.04 .. 0.20 at 21 phases, +-3 % at 61)
        ratio = te / c
        np.testing.assert_allclose(ratio, ratio.mean(), rtol=0.08)
        a = 0.5 * ds["paint_major_mm"].isel(E_mm=e, torque_nm=0).values
        assert np.all(np.diff(a) < 0)
        kappa = 2 * PAINT_THICKNESS_MM / a[0] ** 2
        bound = np.sqrt(kappa / (kappa + 2e-3 * (c[2] - c[0])))
        assert bound <= a[2] / a[0] < 1.0


def test_failed_variant_is_recorded_on_its_cells_only(s0003_centred, tmp_path):
    # 1000 um/mm^2 of profile crowning is far beyond the ease-off limit (5 % of the
    # tooth thickness, geometry.easeoff): that variant's flank build fails by name
    pair = s0003_centred[0]
    grid = SweepGrid((parse_vary("easeoff.drive.profile_crowning_um_per_mm2=8:1000:2"),),
                     (64.5,))
    rep = run_sweep(pair, grid, out=tmp_path, side="drive", phases=PHASES, workers=0,
                    progress=False)
    ds = _open(rep)
    assert ds["status"].values.ravel().tolist() == [1, 2]
    assert ds["error"].values[0, 0] == ""
    assert ds["error"].values[1, 0].startswith("InputRangeError: ")
    assert "ease-off" in ds["error"].values[1, 0].lower() or \
        "easeoff" in ds["error"].values[1, 0].lower()


def test_easeoff_variant_on_the_nominal_conjugate_flanks_is_the_full_build(s0003_centred):
    pair, flanks = s0003_centred
    design = ((KEY, 0.2), ("easeoff.coast.bias_um_per_mm2", 0.5))
    quick = build_variant(pair, design, Variant(pair, flanks, 0.0))
    full = build_variant(pair, design)
    assert quick.error == full.error == ""
    assert quick.flanks.pinion_conjugate is flanks.pinion_conjugate     # reused
    for side in ("drive", "coast"):
        a, b = quick.flanks.flank("pinion", side), full.flanks.flank("pinion", side)
        (u0, u1), (v0, v1) = a.u_range, a.v_range
        u, v = np.meshgrid(np.linspace(u0, u1, 7), np.linspace(v0, v1, 9))
        ea, eb = a.evaluate(u, v), b.evaluate(u, v)
        for name in ("r", "r_u", "r_v", "r_uu", "n"):
            np.testing.assert_array_equal(getattr(ea, name), getattr(eb, name), err_msg=name)
        # and it is not the nominal ease-off (both sides' coefficients differ)
        assert not np.array_equal(ea.r, flanks.flank("pinion", side).evaluate(u, v).r)
