"""``gearcontact vectors``: export golden vectors for other HDL flows.

Writes, per core, the seeded random and corner-case vectors with the golden model's
expected outputs as JSON lines and ``$readmemh`` hex files, plus a README.md that
describes every file, field order, width and Q format
(:mod:`gearcontact.preview.vectors`).
"""

from __future__ import annotations

from ..preview.vectors import DEFAULT_COUNT, VECTOR_CORES, export_vectors
from ..validation import InputRangeError


def _cores(text: str) -> tuple[str, ...]:
    cores = tuple(c.strip() for c in text.split(",") if c.strip())
    bad = [c for c in cores if c not in VECTOR_CORES]
    if bad or not cores:
        raise InputRangeError("--cores", text,
                              f"a comma-separated subset of {','.join(VECTOR_CORES)}")
    return cores


def register(sub) -> None:
    p = sub.add_parser("vectors", help="export golden vectors (JSON lines + $readmemh hex)",
                       description=__doc__.split("\n\n")[1])
    p.add_argument("--out", required=True, metavar="DIR", help="output directory")
    p.add_argument("--count", type=int, default=DEFAULT_COUNT, metavar="N",
                   help=f"seeded random vectors per core, corner cases on top "
                        f"(default {DEFAULT_COUNT})")
    p.add_argument("--seed", type=int, default=0, metavar="S",
                   help="seed of the random vectors (default 0)")
    p.add_argument("--cores", default=",".join(VECTOR_CORES), metavar="LIST",
                   help=f"comma-separated cores (default {','.join(VECTOR_CORES)})")
    p.set_defaults(func=run)


def run(args) -> int:
    files = export_vectors(args.out, cores=_cores(args.cores), count=args.count,
                           seed=args.seed)
    for path in files:
        print(path)
    return 0
