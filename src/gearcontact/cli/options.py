"""Options shared by the commands that analyse a gear pair (tca, ltca, lte, analyze)."""

from __future__ import annotations

from pathlib import Path

from ..validation import InputRangeError, check_positive

__all__ = ["add_pair_arguments", "check_pair_arguments", "load_pair_for"]


def add_pair_arguments(p, *, torque: bool = False, cells: int | None = None) -> None:
    """Add ``--pair --out --side --phases --no-figures`` (and ``--torque``, ``--cells``)."""
    p.add_argument("--pair", default="s0003", help="preset name or TOML file (default s0003)")
    p.add_argument("--out", required=True, type=Path, help="output directory")
    if torque:
        p.add_argument("--torque", type=float, default=64.5,
                       help="gear torque in N·m (default 64.5)")
    p.add_argument("--side", default=None, choices=("drive", "coast"),
                   help="flank pair (default: the pair's design_side; s0003: coast, the "
                        "published design point)")
    p.add_argument("--phases", type=int, default=61,
                   help="TCA mesh phases per pinion pitch, both ends included (default 61)")
    if cells is not None:
        p.add_argument("--cells", type=int, default=cells,
                       help=f"cells per side of the tangent-plane gap field (default {cells})")
    p.add_argument("--no-figures", action="store_true", help="skip the PNG figures")


def check_pair_arguments(args) -> None:
    """Cheap checks before the expensive stages (the library checks again)."""
    if args.phases < 3:
        raise InputRangeError("--phases", args.phases, ">= 3")
    if getattr(args, "torque", None) is not None:
        check_positive("torque_nm (N·m)", args.torque)
    if getattr(args, "cells", None) is not None and args.cells < 16:
        raise InputRangeError("cells", args.cells, ">= 16 per side")


def load_pair_for(args):
    """The pair of ``--pair`` with ``args.side`` set (default its design side) and, if
    the pair file has no ease-off table for that side, the synthesized one (printed)."""
    from ..geometry.pair import load_pair
    from ..tca.synthesis import with_easeoff

    pair = load_pair(args.pair)
    args.side = args.side or pair.design_side
    pair, note = with_easeoff(pair, side=args.side)
    if note:
        print(note)
    return pair
