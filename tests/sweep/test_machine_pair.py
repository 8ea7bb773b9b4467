"""A sweep over an assembly error on a pair whose flanks are cut from machine settings
(issue 27 item 1: the generated flanks go through the same Surface contract, so sweeps
work unchanged).

Pair: examples/machine_settings/iso23509_f2_machine.toml (ISO 23509 F.2, all four flanks
cut from typed settings); the audit's line ``gearcontact sweep --pair ... --vary
E=-0.05:0.05:3 --compute tca``, in this process (``workers=0``).

Truths:

1. each sweep point is the stand-alone TCA of the pair with that error typed into its
   file: the pair written with ``[assembly] E_mm`` (``pair_to_toml``), loaded back, its
   flanks cut again from the settings and analysed (the sweep instead reuses one flank
   set and replaces the error in memory); bit for bit, and E = 0 is the plain TCA of the
   example file;
2. an offset error moves the pattern along the face in the direction of the first-order
   kinematics (tests/sweep/test_cell.py: the pinion moved by ``d = (0, -E, 0)`` is taken
   up by a gear rotation that tilts each pair's TE and moves the contact at a held
   phase, :func:`.conftest.predicted_face_shift_mm`): for F.2, +E moves it toward the
   toe; its size on F.2 differs from the first order (strict xfail below).
"""

import dataclasses
from pathlib import Path

import numpy as np
import pytest

xr = pytest.importorskip("xarray")

from gearcontact.geometry.flank import build_flanks  # noqa: E402
from gearcontact.geometry.pair import load_pair, pair_to_toml  # noqa: E402
from gearcontact.sweep.cell import TCA_VARIABLES, _tca_values, compute_point  # noqa: E402
from gearcontact.sweep.grid import SweepGrid, parse_vary  # noqa: E402
from gearcontact.sweep.run import run_sweep  # noqa: E402
from gearcontact.tca.analysis import analyze_pair  # noqa: E402

from .conftest import predicted_face_shift_mm  # noqa: E402

F2 = Path(__file__).resolve().parents[2] / "examples" / "machine_settings" / \
    "iso23509_f2_machine.toml"
PHASES = 21      # as tests/sweep/test_run.py: a cycle at ~1 s per point on F.2
GRID = SweepGrid((parse_vary("E=-0.05:0.05:3"),), (64.5,))


def _with_error_typed(pair, e_mm: float, tmp_path):
    """The pair written with ``E_mm`` in its ``[assembly]`` table and loaded back."""
    moved = dataclasses.replace(pair, assembly=dataclasses.replace(pair.assembly, E_mm=e_mm))
    path = tmp_path / f"f2_E{e_mm:+g}.toml"
    path.write_text(pair_to_toml(moved))
    loaded = load_pair(path)
    assert loaded.assembly.E_mm == e_mm and len(loaded.machine) == 4
    return loaded


def test_sweep_points_are_the_tca_of_the_typed_error(tmp_path):
    pair = load_pair(F2)
    rep = run_sweep(pair, GRID, out=tmp_path / "sweep", side="drive", phases=PHASES,
                    workers=0, progress=False)
    assert (rep.computed, rep.failed) == (3, 0)
    ds = xr.open_zarr(rep.store, consolidated=False).load()
    assert list(ds["E_mm"].values) == [-0.05, 0.0, 0.05]
    flanks = build_flanks(pair)
    face = {}
    for i, e in enumerate(ds["E_mm"].values):
        # E = 0: the example file's own TCA; else the file with the error typed in
        typed = _with_error_typed(pair, float(e), tmp_path) if e else pair
        res, _ = analyze_pair(typed, side="drive", phases=PHASES,
                              flanks=build_flanks(typed) if e else flanks)
        want = _tca_values(res)
        for name in TCA_VARIABLES:          # bit for bit
            np.testing.assert_array_equal(ds.isel(E_mm=i)[name].values, [want[name]],
                                          err_msg=name)
        face[float(e)] = want["pattern_face_mm"]
        if not e:
            nominal = res
    # the first-order kinematics' direction: +E toward the toe (v2 down), -E toward the
    # heel, by a real move (tenths of a mm for 50 um)
    d = np.array([0.0, -0.05, 0.0])
    predicted = predicted_face_shift_mm(nominal, pair, flanks, d)
    assert predicted < -0.1
    assert face[0.05] - face[0.0] < -0.1 and face[-0.05] - face[0.0] > 0.1


@pytest.mark.slow
@pytest.mark.xfail(strict=True, reason=(
    "differs (measured): F.2's symmetrised face shift per 10 um of E is -0.147 mm "
    "against the first order's -0.278 (P: 0.439 against 0.191; s0003 within 10 %). Not "
    "explained here; a candidate: the model's path term bounds the transmitting segment "
    "by the crossings of neighbouring TE parabolas, while F.2's entering pair closes at "
    "an edge of its posed field (tests/twin/test_machine_pair.py)"))
def test_offset_error_moves_the_pattern_by_the_first_order():
    # tests/sweep/test_cell.py's check (10 um, 61 phases, symmetrised, 10 %) on F.2;
    # about 8 s
    pair = load_pair(F2)
    flanks = build_flanks(pair)
    res, _ = analyze_pair(pair, side="drive", phases=61, flanks=flanks)
    base = compute_point(pair, flanks, {}, [64.5], side="drive", compute=("tca",), phases=61)
    want = predicted_face_shift_mm(res, pair, flanks, np.array([0.0, -0.01, 0.0]))
    got = [compute_point(pair, flanks, {"E_mm": s * 0.01}, [64.5], side="drive",
                         compute=("tca",), phases=61)["pattern_face_mm"][0]
           - base["pattern_face_mm"][0] for s in (1, -1)]
    assert 0.5 * (got[0] - got[1]) == pytest.approx(want, rel=0.10)
