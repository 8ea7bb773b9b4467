"""The operating envelope of the datapath's contact stage (stage D): input codes it accepts.

Inclusive code ranges of the stage D inputs (docs/spec.md sec. 6; their formats in
:mod:`.qformat`). Outside them stage D flags the run instead of computing; inside them
no register can overflow (the bounds of :mod:`gearcontact.preview.hertz.formats`).
Part of the data contract: the stage checks them and the stimulus generator, which
feeds every stage, draws codes up to and one beyond them, so they live below both.
"""

from __future__ import annotations

from .qformat import CURVATURE, LOAD

__all__ = ["CURV_MIN_CODE", "CURV_MAX_CODE", "LOAD_MIN_CODE", "LOAD_MAX_CODE",
           "E_PRIME_MIN_CODE", "E_PRIME_MAX_CODE"]

CURV_MIN_CODE = 1 << (CURVATURE.frac - 11)     #: 2^-11 1/mm
CURV_MAX_CODE = 1 << (CURVATURE.frac + 4)      #: 16 1/mm
LOAD_MIN_CODE = 1 << LOAD.frac                 #: 1 N
LOAD_MAX_CODE = 1 << (LOAD.frac + 17)          #: 131 072 N
E_PRIME_MIN_CODE = 1 << 12                     #: 4 096 MPa
E_PRIME_MAX_CODE = 1 << 21                     #: 2 097 152 MPa
