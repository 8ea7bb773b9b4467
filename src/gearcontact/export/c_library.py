"""``gearcontact export c``: the preview datapath as a self-contained C99 library.

:func:`export_c_library` renders the Jinja2 templates of ``data/templates/c`` with the
package's own tables (:mod:`.c_constants`) and vector layouts (:mod:`.c_checker`) into
one directory: the public header ``gearcontact.h``, the internal ``gc_tables.h`` /
``gc_tables.c`` (constants and ROM words), ``gc_arith.h`` (shift helpers),
``gc_cbrt.h`` (the fp64 cube root) and ``gc_hertz_hb.h`` (the Hamrock-Brewe terms), both
shared inline with the FMUs' contact law, ``gc_hertz_preview.h`` (the preview's
Hamrock-Brewe terms and envelope, the same work for every input), one
source per stage and flavour, the
checker ``gearcontact_check.c`` and a ``Makefile`` (``make`` builds
``libgearcontact.a``, ``libgearcontact.so`` and ``gearcontact_check``). No file holds a
time stamp or a path: identical package versions write identical files.

``hertz_form="exact"`` (``gearcontact export c --hertz-form exact``) adds the twin's
exact Hertz law (:mod:`gearcontact.twin.exact_hertz`: its table, :func:`.c_constants.
exact_hertz_table_constants`, and its cubic interpolation) as
``gc_hertz_exact_table.h`` / ``gc_hertz_exact_table.c`` and the public
``gc_hertz_exact_table_fp64``; the default export (Hamrock-Brewe) is unchanged, byte
for byte (:data:`EXACT_FILES`).

The golden sources use integer arithmetic only and constant loop counts; the fp64
sources follow the fp64 reference formulas operation by operation, except the fit's dot
products (four lanes of the pseudo-inverse's own words, the same bits with or without
SIMD, summed as a tree) and the preview's Hamrock-Brewe terms (the cube root, a seed
polynomial and one Halley step, beside the logarithm and the exponential instead of
after them; on clamped operands, masked by the flags), both within 1e-12 of the
reference.
How to build and use the library, and the determinism argument: docs/export.md.
"""

from __future__ import annotations

from importlib import resources
from pathlib import Path

from ..errors import ToolUnavailable
from ..contract.stencil import STENCIL_SIDE
from ..preview.hertz.formats import DEFAULT_HERTZ_FORM, check_hertz_form
from .c_checker import checker_cores, other_cores
from .c_constants import (fit_constants, fit_flags, fit_isqrt_seeds, fit_mac_plan,
                          fit_mac_ops, fit_mac_schedule, fit_lanes_fp64, cbrt_seed,
                          fit_weight_codes, exact_hertz_table_constants,
                          gap_constants, hertz_constants, hertz_flags,
                          hertz_roms, line_constants)

__all__ = ["C_FILES", "HEADERS", "GOLDEN_SOURCES", "FP64_SOURCES", "EXACT_FILES",
           "library_files", "render_c_library", "export_c_library"]

#: Golden fixed-point sources (integer arithmetic only).
GOLDEN_SOURCES = ("gc_gap_golden.c", "gc_fit_golden.c", "gc_hertz_golden.c", "gc_tables.c")
#: fp64 sources.
FP64_SOURCES = ("gc_gap_fp64.c", "gc_fit_fp64.c", "gc_hertz_fp64.c")
#: Headers (the public one first; the others internal).
HEADERS = ("gearcontact.h", "gc_tables.h", "gc_arith.h", "gc_cbrt.h", "gc_hertz_hb.h",
           "gc_hertz_preview.h")
#: Every file of an export, in write order (each rendered from ``<name>.j2``).
C_FILES = HEADERS + GOLDEN_SOURCES + FP64_SOURCES \
    + ("gearcontact_check.c", "Makefile")
#: The files ``hertz_form="exact"`` adds: (header, fp64 source).
EXACT_FILES = ("gc_hertz_exact_table.h", "gc_hertz_exact_table.c")


def library_files(hertz_form: str = DEFAULT_HERTZ_FORM) -> tuple[tuple, tuple, tuple]:
    """``(headers, golden sources, fp64 sources)`` of the library of ``hertz_form``
    (:data:`HEADERS`, :data:`GOLDEN_SOURCES`, :data:`FP64_SOURCES`, with the exact form
    :data:`EXACT_FILES` after them)."""
    if check_hertz_form(hertz_form) == DEFAULT_HERTZ_FORM:
        return HEADERS, GOLDEN_SOURCES, FP64_SOURCES
    return HEADERS + EXACT_FILES[:1], GOLDEN_SOURCES, FP64_SOURCES + EXACT_FILES[1:]


def _c_files(hertz_form: str) -> tuple:
    """Every file of an export of ``hertz_form``, in write order."""
    headers, golden, fp64 = library_files(hertz_form)
    return headers + golden + fp64 + C_FILES[-2:]


#: Stages in this export (the header lists them).
STAGES = ("stage A/B gap kernel (golden: published and lean datapaths; fp64)",
          "stage C curvature fit (golden, fp64)",
          "stage D elliptic Hertz (Hamrock-Brewe and exact Hertz; golden, fp64)",
          "stage D line core (near-line contact; golden, fp64)",
          "the C -> D chain (both Hertz forms; golden, fp64)",
          "the C -> line-core chain (golden)")


def _environment():
    try:
        from jinja2 import Environment, StrictUndefined
    except ImportError as exc:
        raise ToolUnavailable("gearcontact export c needs Jinja2: pip install "
                              "'gearcontact[export]' (or jinja2>=3.1)") from exc
    env = Environment(trim_blocks=True, lstrip_blocks=True, keep_trailing_newline=True,
                      undefined=StrictUndefined, autoescape=False)
    env.filters["c_hex32"] = lambda w: f"0x{int(w):08x}u"
    return env


def _fit_variant(plan: dict, needed) -> dict:
    """The coefficients ``needed`` of a golden fit (gc_fit_golden.c) with the forms of
    :func:`.c_constants.fit_mac_plan` they read and those forms' orbit-sum parities."""
    forms = sorted({k for j in needed for _, k in plan["coeffs"][j]["parts"]})
    parities = sorted({tuple(plan["forms"][k]["parity"]) for k in forms
                       if plan["forms"][k]["parity"] is not None})
    return {"needed": list(needed), "forms": forms, "parities": [list(p) for p in parities]}


def _exact_table_context() -> dict:
    """The exact form's table and constants (:func:`.c_constants.
    exact_hertz_table_constants`) and its flag: the bit after stage D's."""
    return {**exact_hertz_table_constants(), "flag": 2 * max(b for _, b in hertz_flags())}


def _context(hertz_form: str = DEFAULT_HERTZ_FORM) -> dict:
    from .. import __version__
    cores = checker_cores()
    digits = [sum(f.digits * f.count for f in fs) for c in cores for fs in (c["ins"], c["outs"])]
    values = [sum(f.count for f in fs) for c in cores for fs in (c["ins"], c["outs"])]
    plan = fit_mac_plan()
    return {"version": __version__, "stages": STAGES, "hertz_flags": hertz_flags(),
            "hertz_constants": hertz_constants(), "hertz_roms": hertz_roms(),
            "gap_constants": gap_constants(), "line_constants": line_constants(), "fit_constants": fit_constants(), "fit_flags": fit_flags(),
            "fit_weights": fit_weight_codes(), "fit_fp64": fit_lanes_fp64(), "cbrt": cbrt_seed(),
            "fit_isqrt_seeds": fit_isqrt_seeds(), "fit_mac_plan": plan, "stencil_side": STENCIL_SIDE,
            "fit_mac_orbits": any(f["parity"] for f in plan["forms"]),
            "fit_mac_ops": fit_mac_ops(plan), "fit_mac_schedule": fit_mac_schedule(plan),
            # gc_fit_golden and gc_fit_golden_curvatures (c3, c4, c5 and A-, B- alone)
            "fit_variants": {"full": _fit_variant(plan, range(len(plan["coeffs"]))),
                             "curvatures": _fit_variant(plan, range(3, len(plan["coeffs"])))},
            "cores": cores, "other_cores": other_cores(), "max_digits": max(digits),
            "max_values": max(values), "sources": sum(library_files(hertz_form)[1:], ()),
            "exact_table": (_exact_table_context() if hertz_form != DEFAULT_HERTZ_FORM
                            else None)}


def render_c_library(*, hertz_form: str = DEFAULT_HERTZ_FORM) -> dict[str, str]:
    """Every file of the C library: {file name: text} in :data:`C_FILES` order (with
    ``hertz_form="exact"`` :data:`EXACT_FILES` too, module docstring).

    Raises
    ------
    ToolUnavailable
        Jinja2 is not installed.
    InputRangeError
        ``hertz_form`` not one of :data:`~gearcontact.preview.hertz.formats.HERTZ_FORMS`.
    """
    names = _c_files(hertz_form)
    env = _environment()
    ctx = _context(hertz_form)
    folder = resources.files("gearcontact").joinpath("data/templates/c")
    return {name: env.from_string(folder.joinpath(f"{name}.j2").read_text()).render(ctx)
            for name in names}


def export_c_library(out_dir, *, hertz_form: str = DEFAULT_HERTZ_FORM) -> list[Path]:
    """Write the C library into ``out_dir`` (created if missing).

    Parameters
    ----------
    out_dir : str or Path
        Output directory.
    hertz_form : str
        ``"hamrock-brewe"`` (default) or ``"exact"``: the library adds the twin's exact
        Hertz law (module docstring).

    Returns
    -------
    list of Path
        The files written, :data:`C_FILES` order (the exact form's files after the
        headers and the fp64 sources).

    Raises
    ------
    ToolUnavailable
        Jinja2 is not installed.
    InputRangeError
        ``hertz_form`` not one of :data:`~gearcontact.preview.hertz.formats.HERTZ_FORMS`.
    """
    texts = render_c_library(hertz_form=hertz_form)
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    paths = []
    for name, text in texts.items():
        path = out / name
        path.write_text(text)
        paths.append(path)
    return paths
