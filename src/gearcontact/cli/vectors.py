"""``gearcontact vectors``: export golden vectors for other HDL flows.

Writes, per core, the seeded random and corner-case vectors with the golden model's
expected outputs as JSON lines and ``$readmemh`` hex files, plus a README.md that
describes every file, field order, width and Q format
(:mod:`gearcontact.hw.vectors`).
"""

from __future__ import annotations

from ..hw.vectors import (DEFAULT_COUNT, EXPORT_CORES, MAX_COUNT, VECTOR_CORES,
                          export_vectors)
from ..validation import InputRangeError
from .options import check_count
from .outdir import add_out_argument, final_path


def _cores(text: str) -> tuple[str, ...]:
    cores = tuple(c.strip() for c in text.split(",") if c.strip())
    bad = [c for c in cores if c not in EXPORT_CORES]
    if bad or not cores:
        raise InputRangeError("--cores", text,
                              f"a comma-separated subset of {','.join(EXPORT_CORES)}")
    return cores


def register(sub) -> None:
    p = sub.add_parser("vectors", help="export golden vectors (JSON lines + $readmemh hex)",
                       description=__doc__.split("\n\n")[1])
    add_out_argument(p)
    p.add_argument("--count", type=int, default=DEFAULT_COUNT, metavar="N",
                   help=f"seeded random vectors per core, corner cases on top, 0 to "
                        f"{MAX_COUNT} (default {DEFAULT_COUNT})")
    p.add_argument("--seed", type=int, default=0, metavar="S",
                   help="seed of the random vectors (default 0)")
    p.add_argument("--cores", default=",".join(VECTOR_CORES), metavar="LIST",
                   help=f"comma-separated cores (default {','.join(VECTOR_CORES)}; also "
                        f"{','.join(c for c in EXPORT_CORES if c not in VECTOR_CORES)})")
    p.set_defaults(func=run, check=check)


def check(args) -> None:
    """Every option, before any work."""
    _cores(args.cores)
    check_count("--count", args.count, 0, MAX_COUNT)
    check_count("--seed", args.seed, 0, 2 ** 63 - 1)


def run(args) -> int:
    files = export_vectors(args.out, cores=_cores(args.cores), count=args.count,
                           seed=args.seed)
    for path in files:
        print(final_path(args, path))
    return 0
