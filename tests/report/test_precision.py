"""Gap-kernel precision in the report (:mod:`gearcontact.report.precision`).

Truth: the first-order error bound of docs/spec.md sec. 8 item 8
(:func:`gearcontact.preview.gap.golden.gap_error_bound_mm`) holds at every width, the
error shrinks as the widths grow (halving per bit until the Q(32,16) gap output's own
rounding floor), and the CSV carries exactly the sweeps' numbers.
"""

import csv

import pytest

from gearcontact.report.precision import (COORD_FRACS, NORMAL_FRACS,
                                          write_precision_outputs)


@pytest.fixture(scope="module")
def written(tmp_path_factory):
    out = tmp_path_factory.mktemp("precision")
    return out, write_precision_outputs(out, figures=True, n_samples=400)


def test_bound_holds_and_error_falls_with_width(written):
    _, (by_coord, by_normal) = written
    assert [p.coord_frac for p in by_coord] == list(COORD_FRACS)
    assert [p.normal_frac for p in by_normal] == list(NORMAL_FRACS)
    for p in by_coord + by_normal:
        assert p.max_bound_ratio <= 1.0
        assert 0.0 < p.rms_error_mm <= p.max_error_mm <= p.bound_mm
    # narrow normals dominate: 12 -> 16 fraction bits cut the error by > 8x (2^4 = 16
    # for the 3 ||d|| 2^-(rf+1) term, less the coordinate terms that stay)
    assert by_normal[0].max_error_mm > 8.0 * by_normal[2].max_error_mm
    assert by_coord[0].max_error_mm > by_coord[-1].max_error_mm


def test_csv_matches_the_sweeps(written):
    out, (by_coord, by_normal) = written
    with open(out / "precision.csv") as fh:
        rows = list(csv.DictReader(fh))
    assert len(rows) == len(by_coord) + len(by_normal)
    for row, p in zip(rows, by_coord + by_normal):
        assert int(row["coord_frac_bits"]) == p.coord_frac
        assert int(row["normal_frac_bits"]) == p.normal_frac
        # the CSV keeps 12 significant digits: rounding <= 5e-12 relative
        assert int(row["coord_width_bits"]) == 8 + p.coord_frac
        assert float(row["max_error_um"]) == pytest.approx(p.max_error_mm * 1e3, rel=5e-12)
        assert float(row["bound_um"]) == pytest.approx(p.bound_mm * 1e3, rel=5e-12)
    assert (out / "precision.png").stat().st_size > 0
