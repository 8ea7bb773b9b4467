"""Deprecated: the stencil geometry moved to :mod:`gearcontact.contract.stencil`.

The 7 x 7 stencil is part of the host <-> datapath data contract, below the host TCA
and stage C; every module of the package imports it from there. The old names still
resolve here for one release and emit a :class:`DeprecationWarning`.
"""

from ...deprecation import moved_names

__all__: list[str] = []

__getattr__ = moved_names(__name__, {
    name: f"gearcontact.contract.stencil:{name}"
    for name in ("STENCIL_SIDE", "STENCIL_SIZE", "STENCIL_SPACING_MM",
                 "stencil_coordinates", "read_stencil_csv", "write_stencil_csv")})
