"""Geometry of the hardware curvature-fit stencil (stage C) and its file format.

Defined in :mod:`gearcontact.contract.stencil` (below the host TCA, which samples the
gap on it, and stage C, which fits it); the datapath's modules name it from here.
"""

from ...contract.stencil import (STENCIL_SIDE, STENCIL_SIZE, STENCIL_SPACING_MM,
                                 read_stencil_csv, stencil_coordinates, write_stencil_csv)

__all__ = ["STENCIL_SIDE", "STENCIL_SIZE", "STENCIL_SPACING_MM", "stencil_coordinates",
           "read_stencil_csv", "write_stencil_csv"]
