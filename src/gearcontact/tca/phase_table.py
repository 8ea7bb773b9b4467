"""The phase table: per mesh phase over one pinion pitch, the unloaded contact state
that the device evaluates instead of searching the flanks (docs/spec.md sec. 2).

Per phase: pinion phase, mating point (meshing frame), TE0, the Hertz-stage relative
curvatures A- >= B- and the orientation of the contact ellipse (angle from the gear's
lengthwise direction to the major axis, :mod:`.curvature`).

JSON (``phase_table.json``): every TCA phase of the pitch, full double precision::

    {"format": "gearcontact.phase_table", "version": 1, "pinion_teeth": z1,
     "gear_teeth": z2, "te0_pp_arcsec": ..., "columns": [...], "rows": [[...], ...]}

Binary (``phase_table.bin``, little-endian, a few hundred bytes). The table is periodic
in the pinion pitch; it holds ``n_records`` phases at the uniform step
``phi1_step_deg`` starting at ``phi1_start_deg`` (a subset of the TCA phases, every
``stride``-th, chosen so that at most ``max_records`` records are written).

Header, 28 bytes:

======  ======  =========================  =======================================
offset  bytes   field                      encoding
======  ======  =========================  =======================================
0       4       magic                      ASCII ``GCPT``
4       1       version                    u8 = 1
5       1       record_bytes               u8 = 22
6       2       n_records                  u16
8       2       z1                         u16
10      2       z2                         u16
12      4       phi1_start_deg             Q(32,20) (:data:`ANGLE`)
16      4       phi1_step_deg              Q(32,20)
20      4       te0_pp_arcsec              Q(32,20)
24      4       crc32 of the record bytes  u32 (zlib)
======  ======  =========================  =======================================

Record, 22 bytes:

======  ======  =================  ===========================================
offset  bytes   field              format (:mod:`gearcontact.contract.qformat`)
======  ======  =================  ===========================================
0       9       x, y, z            3 x COORD Q(24,16), mm
9       3       te0                Q(24,12), arcsec (:data:`TE0`)
12      4       A-                 CURVATURE Q(32,20), 1/mm
16      4       B-                 CURVATURE Q(32,20), 1/mm
20      2       ellipse angle      Q(16,7), deg (:data:`ELLIPSE_ANGLE`)
======  ======  =================  ===========================================

Multi-byte fields are two's complement, little-endian; quantization is
round-half-up (:meth:`QFormat.quantize`); out-of-range values raise
:class:`~gearcontact.contract.qformat.FixedPointOverflow`, never wrap.
"""

from __future__ import annotations

import json
import math
import struct
import zlib
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..contract.qformat import COORD, CURVATURE, QFormat, sq
from .mesh import MeshCycle

__all__ = ["PhaseTable", "DecodedPhaseTable", "ANGLE", "TE0", "ELLIPSE_ANGLE",
           "HEADER_BYTES", "RECORD_BYTES", "MAGIC", "phase_table", "encode_binary",
           "decode_binary", "write_json", "read_json"]

MAGIC = b"GCPT"
VERSION = 1
HEADER_BYTES = 28
RECORD_BYTES = 22
#: Header angles (phase start/step, deg) and TE0 p-p (arcsec).
ANGLE = sq(32, 20)
#: Transmission error, arcsec: range +-2048, LSB 2.4e-4 arcsec.
TE0 = sq(24, 12)
#: Ellipse orientation, deg: range +-256, LSB 0.0078 deg.
ELLIPSE_ANGLE = sq(16, 7)
_HEADER = struct.Struct("<4sBBHHHiiiI")

COLUMNS = ("phi1_deg", "x_mm", "y_mm", "z_mm", "te0_arcsec", "A_minus_per_mm",
           "B_minus_per_mm", "ellipse_angle_deg", "pair")


@dataclass(frozen=True)
class PhaseTable:
    """Per-phase contact state over one pinion pitch (double precision).

    Attributes
    ----------
    phi1_deg : ndarray (K,)
        Pinion phases, deg (uniform step, both ends of the pitch).
    point_mm : ndarray (K, 3)
        Mating points in the meshing frame, mm.
    te0_arcsec, A_minus_per_mm, B_minus_per_mm, ellipse_angle_deg : ndarray (K,)
    pair : ndarray (K,) of int
        Offset of the transmitting tooth pair.
    pinion_teeth, gear_teeth : int
    te0_pp_arcsec : float
    """

    phi1_deg: np.ndarray
    point_mm: np.ndarray
    te0_arcsec: np.ndarray
    A_minus_per_mm: np.ndarray
    B_minus_per_mm: np.ndarray
    ellipse_angle_deg: np.ndarray
    pair: np.ndarray
    pinion_teeth: int
    gear_teeth: int
    te0_pp_arcsec: float


@dataclass(frozen=True)
class DecodedPhaseTable:
    """A binary phase table read back (values are the dequantized codes)."""

    phi1_start_deg: float
    phi1_step_deg: float
    te0_pp_arcsec: float
    pinion_teeth: int
    gear_teeth: int
    point_mm: np.ndarray
    te0_arcsec: np.ndarray
    A_minus_per_mm: np.ndarray
    B_minus_per_mm: np.ndarray
    ellipse_angle_deg: np.ndarray

    @property
    def phi1_deg(self) -> np.ndarray:
        return self.phi1_start_deg + self.phi1_step_deg * np.arange(len(self.te0_arcsec))


def phase_table(cycle: MeshCycle) -> PhaseTable:
    """Tabulate a :class:`MeshCycle` (all its phases over the pitch)."""
    return PhaseTable(
        np.degrees(cycle.phi1_rad),
        np.array([mp.point_mm for mp in cycle.contact]),
        np.asarray(cycle.envelope_arcsec, float),
        np.array([rc.A_minus_per_mm for rc in cycle.curvature]),
        np.array([rc.B_minus_per_mm for rc in cycle.curvature]),
        np.array([e.angle_deg for e in cycle.ellipse]),
        np.asarray(cycle.active_pair, int), cycle.pinion_teeth, cycle.gear_teeth,
        float(cycle.te0_pp_arcsec))


def _put(fmt: QFormat, value: float, field: str) -> bytes:
    code = fmt.quantize(value, field=field)
    return (code & ((1 << fmt.bits) - 1)).to_bytes(fmt.bits // 8, "little")


def _get(fmt: QFormat, raw: bytes) -> float:
    return fmt.to_float(fmt.from_bits(int.from_bytes(raw, "little")))


def encode_binary(table: PhaseTable, *, max_records: int = 16) -> bytes:
    """Encode the table in the documented binary layout.

    The periodic pitch holds ``K - 1`` distinct phases (the last equals the first of
    the next pitch); every ``stride = ceil((K - 1) / max_records)``-th is written.
    """
    if max_records < 1:
        raise ValueError(f"max_records = {max_records!r} must be >= 1")
    distinct = len(table.phi1_deg) - 1
    stride = max(1, math.ceil(distinct / max_records))
    rows = np.arange(0, distinct, stride)
    records = bytearray()
    for i in rows:
        for axis in range(3):
            records += _put(COORD, table.point_mm[i, axis], f"point_mm[{i}, {axis}]")
        records += _put(TE0, table.te0_arcsec[i], f"te0_arcsec[{i}]")
        records += _put(CURVATURE, table.A_minus_per_mm[i], f"A_minus_per_mm[{i}]")
        records += _put(CURVATURE, table.B_minus_per_mm[i], f"B_minus_per_mm[{i}]")
        records += _put(ELLIPSE_ANGLE, table.ellipse_angle_deg[i], f"ellipse_angle_deg[{i}]")
    step = (table.phi1_deg[-1] - table.phi1_deg[0]) / distinct * stride
    header = _HEADER.pack(MAGIC, VERSION, RECORD_BYTES, len(rows), table.pinion_teeth,
                          table.gear_teeth,
                          ANGLE.quantize(table.phi1_deg[0], field="phi1_start_deg"),
                          ANGLE.quantize(step, field="phi1_step_deg"),
                          ANGLE.quantize(table.te0_pp_arcsec, field="te0_pp_arcsec"),
                          zlib.crc32(bytes(records)))
    return header + bytes(records)


def decode_binary(data: bytes) -> DecodedPhaseTable:
    """Read a binary phase table; raises ``ValueError`` on a malformed file."""
    if len(data) < HEADER_BYTES:
        raise ValueError(f"phase table too short: {len(data)} bytes < {HEADER_BYTES}")
    (magic, version, rec_bytes, n, z1, z2, start, step, pp,
     crc) = _HEADER.unpack_from(data, 0)
    if magic != MAGIC or version != VERSION or rec_bytes != RECORD_BYTES:
        raise ValueError(f"not a version-{VERSION} phase table (magic {magic!r}, "
                         f"version {version}, record size {rec_bytes})")
    body = data[HEADER_BYTES:]
    if len(body) != n * RECORD_BYTES:
        raise ValueError(f"phase table body has {len(body)} bytes, header says "
                         f"{n} x {RECORD_BYTES}")
    if zlib.crc32(body) != crc:
        raise ValueError("phase table CRC mismatch (corrupted records)")
    fields = np.zeros((n, 7))
    for i in range(n):
        r = body[i * RECORD_BYTES:(i + 1) * RECORD_BYTES]
        fields[i] = [_get(COORD, r[0:3]), _get(COORD, r[3:6]), _get(COORD, r[6:9]),
                     _get(TE0, r[9:12]), _get(CURVATURE, r[12:16]),
                     _get(CURVATURE, r[16:20]), _get(ELLIPSE_ANGLE, r[20:22])]
    return DecodedPhaseTable(ANGLE.to_float(start), ANGLE.to_float(step), ANGLE.to_float(pp),
                             z1, z2, fields[:, :3], fields[:, 3], fields[:, 4], fields[:, 5],
                             fields[:, 6])


def write_json(table: PhaseTable, path, *, edges=()) -> Path:
    """Write ``phase_table.json`` (all phases, double precision); ``edges`` (one string
    per phase, ``""`` inside the flanks) is written as the list ``"edges"``."""
    rows = [[float(table.phi1_deg[i]), *map(float, table.point_mm[i]),
             float(table.te0_arcsec[i]), float(table.A_minus_per_mm[i]),
             float(table.B_minus_per_mm[i]), float(table.ellipse_angle_deg[i]),
             int(table.pair[i])] for i in range(len(table.phi1_deg))]
    doc = {"format": "gearcontact.phase_table", "version": VERSION,
           "pinion_teeth": table.pinion_teeth, "gear_teeth": table.gear_teeth,
           "te0_pp_arcsec": table.te0_pp_arcsec, "columns": list(COLUMNS), "rows": rows}
    if len(edges):
        doc["edges"] = [str(e) for e in edges]
    path = Path(path)
    path.write_text(json.dumps(doc, indent=1))
    return path


def read_json(path) -> PhaseTable:
    """Read ``phase_table.json`` back into a :class:`PhaseTable`."""
    doc = json.loads(Path(path).read_text())
    if doc.get("format") != "gearcontact.phase_table" or doc.get("columns") != list(COLUMNS):
        raise ValueError(f"{path}: not a gearcontact phase table")
    a = np.array(doc["rows"], dtype=float)
    return PhaseTable(a[:, 0], a[:, 1:4], a[:, 4], a[:, 5], a[:, 6], a[:, 7],
                      a[:, 8].astype(int), int(doc["pinion_teeth"]), int(doc["gear_teeth"]),
                      float(doc["te0_pp_arcsec"]))
