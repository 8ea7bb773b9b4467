"""LiteX board flow for the XC7K480T card (optional extra ``board``: LiteX, Migen).

:mod:`.platform` describes the board, :mod:`.board` builds the SoC (jtagbone bridge as
the only bus master, the Amaranth datapath as an ``Instance``, CSRs generated from
:mod:`gearcontact.hw.regmap`) and :func:`.board.generate` writes the Verilog,
constraints, ``csr.csv`` / ``csr.json`` and the openXC7 build script without running
any vendor tool. Importing this package does not import LiteX.
"""

__all__ = ["LITEX_PIN", "generate"]

from ..driver import LITEX_PIN


def generate(*args, **kwargs):
    """Lazy alias of :func:`gearcontact.hw.litex.board.generate`."""
    from .board import generate as _generate
    return _generate(*args, **kwargs)
