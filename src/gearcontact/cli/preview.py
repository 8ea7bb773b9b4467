"""``gearcontact preview``: the physics-direct preview of one contact.

Either from half relative curvatures and a load (stage D), or from a 49-sample gap
stencil file (stage C then D). With --line-length-mm L (the contact line's length on
the flank, mm) stage D is the line core: an ellipse longer than the flank is truncated
to a Hertz line contact of length L. Prints a, b, k, p_max, the stage-D mode that
evaluated them (elliptic | line) and, for the fixed-point backends, raw codes, flags and
cycles; --json prints one JSON object instead. When the fixed-point datapath flags the
input, the flags are printed on stderr and the exit code is 3.
"""

from __future__ import annotations

import json

from ..errors import DatapathFlagged
from ..materials import STEEL, Material
from ..hw import backends as _hardware_backends  # noqa: F401 (registers rtl, rtl-soc)
from ..preview.engine import BACKENDS, get_engine
from ..contract.stencil import read_stencil_csv
from ..preview.hertz.formats import DEFAULT_HERTZ_FORM, HERTZ_FORMS
from ..contract.qformat import STENCIL_GAP, FixedPointOverflow
from ..preview.hertz.reference import LINE_LENGTH_RANGE, LINE_LENGTH_RANGE_MM
from ..validation import InputRangeError, check_finite, format_range

#: Backends with the line core (``--line-length-mm``).
LINE_BACKENDS = ("reference", "golden", "rtl")


def register(sub) -> None:
    p = sub.add_parser("preview", help="physics-direct contact preview (Hertz stage D, "
                                       "or stencil fit C -> D)",
                       description=__doc__.split("\n\n")[1])
    src = p.add_mutually_exclusive_group(required=True)
    src.add_argument("--curvatures", nargs=2, type=float, metavar=("A", "B"),
                     help="half relative principal curvatures A-, B- in 1/mm")
    src.add_argument("--stencil", metavar="FILE",
                     help="49-sample gap stencil CSV (s_mm,t_mm,gap_mm; see "
                          "gearcontact.contract.stencil)")
    p.add_argument("--load", type=float, required=True, metavar="W", help="normal load, N")
    p.add_argument("--modulus", type=float, default=STEEL.youngs_modulus_mpa / 1e3,
                   metavar="E_GPA", help="Young's modulus of both bodies, GPa (default 209)")
    p.add_argument("--poisson", type=float, default=STEEL.poisson_ratio, metavar="NU",
                   help="Poisson's ratio of both bodies (default 0.3)")
    p.add_argument("--backend", choices=sorted(BACKENDS), default="reference",
                   help="which representation evaluates the preview (default reference)")
    p.add_argument("--hertz-form", choices=HERTZ_FORMS, default=DEFAULT_HERTZ_FORM,
                   help="stage-D Hertz form: the published simplified forms (default) or "
                        "exact elliptic Hertz in the same tables (not for rtl-soc)")
    p.add_argument("--line-length-mm", type=float, default=None, metavar="L",
                   help="length of the contact line on the flank through the contact "
                        f"point, in {LINE_LENGTH_RANGE}: stage D is the line core (an "
                        "ellipse longer than L is truncated to a Hertz line contact; not "
                        "for rtl-soc). Default: the published elliptic core")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.set_defaults(func=run, check=check)


def check(args) -> None:
    """Material and stencil file before any engine is built (the engine validates the
    curvatures and the load, the same domain for every backend)."""
    args.material = Material.from_gpa(args.modulus, args.poisson, name="cli")
    if args.line_length_mm is not None:
        lo, hi = LINE_LENGTH_RANGE_MM      # below 1 mm: the line core's host lift
        if not lo <= check_finite("--line-length-mm (mm)", args.line_length_mm) <= hi:
            raise InputRangeError("--line-length-mm (mm)", args.line_length_mm,
                                  LINE_LENGTH_RANGE)
        if args.backend not in LINE_BACKENDS:
            raise InputRangeError("--backend (with --line-length-mm)", args.backend,
                                  f"one of {list(LINE_BACKENDS)}: the backends with the "
                                  "line core")
    args.gaps_mm = None if args.stencil is None else read_stencil_csv(args.stencil)
    if args.gaps_mm is not None and args.backend != "reference":
        # the fixed-point backends take the gaps in STENCIL_GAP Q(32,21): one that does
        # not fit is the file's value, named with its row, not a datapath result
        for i, gap in enumerate(args.gaps_mm):
            try:
                STENCIL_GAP.quantize(gap, field="gap_mm")
            except FixedPointOverflow:
                raise InputRangeError(
                    f"{args.stencil}: row {i + 1} (sample {i}), column gap_mm", float(gap),
                    f"{format_range(STENCIL_GAP.min_value, STENCIL_GAP.max_value)} mm, the "
                    f"{STENCIL_GAP} stencil gap format of the --backend {args.backend} "
                    "datapath") from None


def run(args) -> int:
    if getattr(args, "material", None) is None:
        check(args)
    engine = get_engine(args.backend, material=args.material, hertz_form=args.hertz_form)
    line = {} if args.line_length_mm is None else {"line_length_mm": args.line_length_mm}
    if args.gaps_mm is not None:
        res = engine.stencil(args.gaps_mm, args.load, **line)
    else:
        res = engine.hertz(args.curvatures[0], args.curvatures[1], args.load, **line)
    if args.json:
        print(json.dumps(res.as_dict(), indent=2))
    else:
        print(f"backend        {res.backend}")
        print(f"load           {res.load_n:.6g} N")
        print(f"A-, B-         {res.A_minus_per_mm:.6g}, {res.B_minus_per_mm:.6g} 1/mm")
        print(f"a, b           {res.a_mm:.6g}, {res.b_mm:.6g} mm   "
              f"(2a x 2b = {2 * res.a_mm:.4g} x {2 * res.b_mm:.4g} mm)")
        print(f"k = a/b        {res.k:.6g}")
        print(f"p_max          {res.p_max_mpa:.6g} MPa")
        length = "" if args.line_length_mm is None else \
            f"   (contact line L = {args.line_length_mm:.6g} mm)"
        print(f"mode           {res.mode}{length}")
        print(f"law            {res.law_status}")
        if res.angle_deg is not None:
            print(f"A- axis        {res.angle_deg:.4g} deg from the stencil s axis")
        if res.codes is not None:
            print("codes          " + ", ".join(f"{k}={v}" for k, v in res.codes.items()))
            print(f"cycles         {res.cycles}")
        print(f"flags          {', '.join(res.flags) if res.flags else 'none'}")
    if res.flags:            # the outputs are invalid (zero): exit 3, said on stderr
        raise DatapathFlagged(f"{', '.join(res.flags)} (outputs invalid)")
    return 0
