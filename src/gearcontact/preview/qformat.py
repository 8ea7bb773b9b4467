"""Deprecated: the Q formats moved to :mod:`gearcontact.contract.qformat`.

The data contract's formats live below the host and the datapath; every module of the
package imports them from there. The old names still resolve here for one release and
emit a :class:`DeprecationWarning`.
"""

from ..deprecation import moved_names

__all__: list[str] = []

__getattr__ = moved_names(__name__, {
    name: f"gearcontact.contract.qformat:{name}"
    for name in ("QFormat", "FixedPointOverflow", "round_shift", "sq", "uq", "COORD",
                 "NORMAL", "LOAD", "CURVATURE", "SEMI_AXIS", "PMAX", "GAP")})
