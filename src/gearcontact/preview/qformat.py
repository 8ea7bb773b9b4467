"""Fixed-point Q formats of the preview datapath: the data contract's formats.

Defined in :mod:`gearcontact.contract.qformat` (below the host and the datapath, which
both use them); the datapath's modules name them from here.
"""

from ..contract.qformat import (COORD, CURVATURE, GAP, LOAD, NORMAL, PMAX, SEMI_AXIS,
                                FixedPointOverflow, QFormat, round_shift, sq, uq)

__all__ = ["QFormat", "FixedPointOverflow", "round_shift", "sq", "uq",
           "COORD", "NORMAL", "LOAD", "CURVATURE", "SEMI_AXIS", "PMAX", "GAP"]
