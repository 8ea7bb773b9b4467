"""``gearcontact export``: the preview datapath for use outside Python.

``gearcontact export c --out DIR`` writes a self-contained C99 library of the preview
datapath (golden fixed point and fp64) with a Makefile and the checker
``gearcontact_check VECTOR_DIR``, which compares it with the files of
``gearcontact vectors`` (:mod:`gearcontact.export.c_library`; docs/export.md).
"""

from __future__ import annotations

from .outdir import add_out_argument, final_path


def register(sub) -> None:
    p = sub.add_parser("export", help="export the preview datapath (C99 library)",
                       description=__doc__.split("\n\n")[1])
    cmds = p.add_subparsers(dest="export_command", metavar="ACTION", required=True)
    c = cmds.add_parser("c", help="C99 library of the datapath (golden fixed point and "
                                  "fp64) with a Makefile and the vector checker")
    add_out_argument(c)
    c.set_defaults(func=run_c)


def run_c(args) -> int:
    from ..export.c_library import export_c_library
    for path in export_c_library(args.out):
        print(final_path(args, path))
    return 0
