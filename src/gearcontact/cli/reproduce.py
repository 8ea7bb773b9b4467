"""``gearcontact reproduce``: the evaluation of docs/spec.md sec. 8 regenerated for s0003
into one directory: report.html (table of contents, figures beside it), report.md and
report.json (one key per item).
"""

from __future__ import annotations

import sys

from ..report.reproduce import run_reproduce


def register(sub) -> None:
    p = sub.add_parser("reproduce", help="regenerate every evaluation table and figure into "
                                         "one HTML report",
                       description=__doc__.split("\n\n")[0].split(": ", 1)[1])
    p.add_argument("--out", required=True, help="output directory")
    p.add_argument("--quick", action="store_true",
                   help="reduced sizes (15 TCA phases, 8 loaded-TE phases, smaller surrogate "
                        "sets); under 2 minutes on 2 cores")
    p.add_argument("--synth", action="store_true",
                   help="run the gap-core synthesis sweep (slow; needs gearcontact[synth]) "
                        "instead of reading committed results")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p.set_defaults(func=run)


def run(args) -> int:
    try:
        rep = run_reproduce(args.out, quick=args.quick, synth=args.synth,
                            progress=not args.quiet)
    except ModuleNotFoundError as exc:      # the 'report' (or 'synth') extra is missing
        print(f"gearcontact reproduce: error: {exc}", file=sys.stderr)
        return 2
    status = ", ".join(f"{s.key} {s.status}" for s in rep.sections)
    print(f"{rep.meta['pair']}: {status}; {rep.meta['total_s']:.0f} s -> "
          f"{rep.out_dir / 'report.html'}")
    return 0
