"""Phase table: JSON and fixed-point binary round trips, layout and error handling.

Truth: the binary must decode to the round-half-up quantization of the double table
(|error| <= 1/2 LSB of each documented Q format) at the documented offsets and size.
"""

import struct
import zlib

import numpy as np
import pytest

from gearcontact.contract.qformat import COORD, CURVATURE, FixedPointOverflow
from gearcontact.tca.mesh import mesh_cycle
from gearcontact.tca.phase_table import (ELLIPSE_ANGLE, HEADER_BYTES, RECORD_BYTES, TE0,
                                         PhaseTable, decode_binary, encode_binary,
                                         phase_table, read_json, write_json)
from gearcontact.tca.types import ContactGuess

from .analytic import sphere_torus_case


@pytest.fixture(scope="module")
def table():
    case = sphere_torus_case()
    start = ContactGuess(np.pi / 2, 0.0, case.tube_angle, 0.0, 0.0, 0.0)
    cyc = mesh_cycle(case.pinion, case.gear, case.kin, pinion_teeth=120, start=start,
                     phases=61, pairs=1, center="start")
    return phase_table(cyc)


def test_binary_round_trip_within_half_lsb(table):
    data = encode_binary(table, max_records=16)
    # 60 distinct phases, stride ceil(60/16) = 4 -> 15 records
    assert len(data) == HEADER_BYTES + 15 * RECORD_BYTES == 358
    dec = decode_binary(data)
    rows = np.arange(0, 60, 4)
    assert (dec.pinion_teeth, dec.gear_teeth) == (120, 1200)
    # start and step are each within 1/2 LSB (2^-21 deg): phase k within (k + 1) 2^-21
    np.testing.assert_allclose(dec.phi1_deg, table.phi1_deg[rows], atol=15 * 2 ** -21)
    np.testing.assert_allclose(dec.point_mm, table.point_mm[rows], atol=COORD.lsb / 2)
    np.testing.assert_allclose(dec.te0_arcsec, table.te0_arcsec[rows], atol=TE0.lsb / 2)
    np.testing.assert_allclose(dec.A_minus_per_mm, table.A_minus_per_mm[rows],
                               atol=CURVATURE.lsb / 2)
    np.testing.assert_allclose(dec.B_minus_per_mm, table.B_minus_per_mm[rows],
                               atol=CURVATURE.lsb / 2)
    np.testing.assert_allclose(dec.ellipse_angle_deg, table.ellipse_angle_deg[rows],
                               atol=ELLIPSE_ANGLE.lsb / 2)
    assert dec.te0_pp_arcsec == pytest.approx(table.te0_pp_arcsec, abs=2 ** -20)


def test_binary_layout_by_hand(table):
    data = encode_binary(table, max_records=60)
    assert data[:4] == b"GCPT" and data[4] == 1 and data[5] == RECORD_BYTES
    assert struct.unpack_from("<H", data, 6)[0] == 60
    assert struct.unpack_from("<I", data, 24)[0] == zlib.crc32(data[HEADER_BYTES:])
    rec = data[HEADER_BYTES + 7 * RECORD_BYTES:HEADER_BYTES + 8 * RECORD_BYTES]
    x_code = int.from_bytes(rec[0:3], "little", signed=True)
    assert x_code == int(np.floor(table.point_mm[7, 0] * 2 ** 16 + 0.5))
    a_code = int.from_bytes(rec[12:16], "little", signed=True)
    assert a_code == int(np.floor(table.A_minus_per_mm[7] * 2 ** 20 + 0.5))


def test_binary_rejects_corruption_and_overflow(table):
    data = bytearray(encode_binary(table))
    data[HEADER_BYTES + 3] ^= 0x01
    with pytest.raises(ValueError, match="CRC"):
        decode_binary(bytes(data))
    with pytest.raises(ValueError, match="not a version-1"):
        decode_binary(b"XXXX" + bytes(data[4:]))
    with pytest.raises(ValueError, match="too short"):
        decode_binary(b"GCPT")
    far = PhaseTable(table.phi1_deg, table.point_mm + 200.0, table.te0_arcsec,
                     table.A_minus_per_mm, table.B_minus_per_mm, table.ellipse_angle_deg,
                     table.pair, 120, 1200, table.te0_pp_arcsec)
    with pytest.raises(FixedPointOverflow, match=r"point_mm\[0, 0\]"):
        encode_binary(far)


def test_json_round_trip_is_exact(table, tmp_path):
    back = read_json(write_json(table, tmp_path / "phase_table.json"))
    for name in ("phi1_deg", "point_mm", "te0_arcsec", "A_minus_per_mm", "B_minus_per_mm",
                 "ellipse_angle_deg", "pair"):
        np.testing.assert_array_equal(getattr(back, name), getattr(table, name))
    assert len(table.phi1_deg) == 61
