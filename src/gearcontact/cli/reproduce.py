"""``gearcontact reproduce``: the evaluation of docs/spec.md sec. 8 regenerated for s0003
into one directory: report.html (table of contents, figures beside it), report.md and
report.json (one key per item).
"""

from __future__ import annotations

import importlib.util

from ..report.reproduce import run_reproduce
from .options import run_timings
from .outdir import add_out_argument, final_path
from ..errors import ToolUnavailable


def register(sub) -> None:
    p = sub.add_parser("reproduce", help="regenerate every evaluation table and figure into "
                                         "one HTML report",
                       description=__doc__.split("\n\n")[0].split(": ", 1)[1])
    add_out_argument(p)
    p.add_argument("--quick", action="store_true",
                   help="reduced sizes (15 TCA phases, 8 loaded-TE phases, smaller surrogate "
                        "sets and studies); under 2 minutes on 2 cores")
    p.add_argument("--synth", action="store_true",
                   help="run the gap-core synthesis sweep (slow; needs gearcontact[synth]) "
                        "instead of reading the committed results")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p.set_defaults(func=run, check=check)


def check(args) -> None:
    """The optional tools the report needs, before any work (missing: exit 2)."""
    missing = [m for m in ("sklearn", "jinja2") if importlib.util.find_spec(m) is None]
    if missing:
        raise ToolUnavailable(f"gearcontact reproduce needs {', '.join(missing)}: "
                              "pip install 'gearcontact[report]'")
    if args.synth:
        from ..hw.synth import require_yosys
        require_yosys()                     # missing: ToolUnavailable (exit 2)


def run(args) -> int:
    rep = run_reproduce(args.out, quick=args.quick, synth=args.synth,
                        progress=not args.quiet)
    run_timings(args, **rep.timings_s)
    status = ", ".join(f"{s.key} {s.status}" for s in rep.sections)
    print(f"{rep.meta['pair']}: {status}; {rep.timings_s['total_s']:.0f} s -> "
          f"{final_path(args, rep.out_dir / 'report.html')}")
    return 0
