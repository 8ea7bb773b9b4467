"""``gearcontact export fmu --kind mesh``: an FMI 3.0 FMU of one gear mesh in plain C.

:func:`export_mesh_fmu` runs the twin's unloaded TCA (the edge-contact one, as
``analyze``) and builds the loaded flank's mesh table
(:func:`gearcontact.twin.mesh.pair_mesh_table`), bakes
it into the C model (``data/templates/fmu``) beside the preview's C library
(:mod:`.c_library`: stage D golden and fp64), compiles the shared library with the
system C compiler (``-std=c99 -Wall -Wextra -Werror``) against the FMI 3.0 headers
FMPy ships, and zips ``modelDescription.xml``, ``sources/`` (with
``buildDescription.xml``) and ``binaries/x86_64-linux/<model>.so``. No Python inside
the FMU; its law is :mod:`.mesh_law` (the twin's contact law at one instant).
``hertz_form="exact"`` (``--hertz-form exact``): the fp64 law is the twin's exact Hertz
form (:mod:`gearcontact.twin.exact_hertz`, its table and cubic in C:
:data:`.c_library.EXACT_FILES`), the backend fp64 only (the golden backend's stage D is
Hamrock-Brewe's; the FMU refuses it), as ``gearcontact twin --hertz-form exact``.
Importer facts (variables, units, causality, step sizes): docs/export.md.
"""

from __future__ import annotations

import hashlib
import math
import re
import shutil
import subprocess
import tempfile
import zipfile
from dataclasses import dataclass
from importlib import resources
from pathlib import Path

from ..errors import ToolUnavailable
from ..preview.hertz.formats import DEFAULT_HERTZ_FORM, check_hertz_form
from ..tca.types import ARCSEC_PER_RAD
from ..twin.contact_law import W_EVAL_MIN_N, _W_EVAL_MAX_N
from ..validation import InputRangeError
from .c_library import _environment, library_files, render_c_library
from .mesh_law import BACKENDS, MeshLawTable, mesh_law_table

__all__ = ["FMU_KINDS", "MESH_VARIABLES", "DOMAIN_COUNTS", "MeshFmu",
           "export_mesh_fmu", "write_mesh_fmu", "check_fmu_kind",
           "fmi3_header_dir", "build_fmu", "fmu_context", "model_token", "c_double",
           "COMMON_IMPLEMENTED", "UNITS", "LAW_FILES", "LINE_LAW_FILES"]

#: ``--kind`` values (``drivetrain``: :mod:`.fmu_drivetrain`).
FMU_KINDS = ("mesh", "drivetrain")
#: (name, value reference, type, causality, variability, unit, description).
MESH_VARIABLES = (
    ("time", 0, "Float64", "independent", "continuous", "s", "simulation time"),
    ("phi_pinion_rad", 1, "Float64", "input", "continuous", "rad",
     "pinion angle along the motion (twin's psi_p)"),
    ("phi_gear_rad", 2, "Float64", "input", "continuous", "rad",
     "gear angle along the motion (twin's psi_g)"),
    ("omega_pinion_rad_s", 3, "Float64", "input", "continuous", "rad/s", "pinion speed"),
    ("omega_gear_rad_s", 4, "Float64", "input", "continuous", "rad/s", "gear speed"),
    ("torque_pinion_nm", 5, "Float64", "output", "continuous", "N.m",
     "mesh torque on the pinion along the motion"),
    ("torque_gear_nm", 6, "Float64", "output", "continuous", "N.m",
     "mesh torque on the gear along the motion"),
    ("mesh_force_n", 7, "Float64", "output", "continuous", "N", "total normal load"),
    ("te_arcsec", 8, "Float64", "output", "continuous", "arcsec",
     "loaded transmission error, TCA sign"),
    ("p_max_mpa", 9, "Float64", "output", "continuous", "MPa",
     "peak pressure of the most loaded pair"),
    ("a_mm", 10, "Float64", "output", "continuous", "mm", "its semi-axis a"),
    ("b_mm", 11, "Float64", "output", "continuous", "mm", "its semi-axis b"),
    ("active_pairs", 12, "Int32", "output", "discrete", "", "pairs carrying load"),
    ("backend", 13, "Enumeration", "parameter", "fixed", "",
     "contact law: fp64 or golden (fixed-point stage D)"),
    ("mesh_damping_n_s_per_mm", 14, "Float64", "parameter", "fixed", "N.s/mm",
     "mesh damping on the line of action"),
    ("pairs_outside_datapath", 15, "Int32", "output", "discrete", "",
     "closed pairs whose preview lies outside the fixed-point datapath's domain (the "
     "fp64 law evaluates it)"),
    ("pairs_without_contact_law", 16, "Int32", "output", "discrete", "",
     "closed pairs without a contact law (a saddle, or a curvature ratio beyond the "
     "exact Hertz table): they carry no load"),
)
#: The outputs that count previews outside the datapath's domain and without a contact
#: law, as the twin does (``gearcontact.twin.contact_law._fp64_law``; a cylindrical
#: pair's ``gearcontact.twin.line_law._line_fp64``).
DOMAIN_COUNTS = ("pairs_outside_datapath", "pairs_without_contact_law",
                 "previews_outside_datapath", "steps_outside_datapath",
                 "previews_without_contact_law")
#: FMI functions of the shared interface (``data/templates/fmu/fmi3_common.c.j2``).
COMMON_IMPLEMENTED = frozenset({
    "fmi3GetVersion", "fmi3SetDebugLogging", "fmi3InstantiateCoSimulation",
    "fmi3InstantiateScheduledExecution", "fmi3FreeInstance", "fmi3Reset"})
#: Functions the mesh model implements beside them (trivial: return fmi3OK); every other
#: one is a stub returning fmi3Error.
_MESH_TRIVIAL = ("fmi3ExitInitializationMode", "fmi3EnterEventMode", "fmi3Terminate",
                 "fmi3EnterContinuousTimeMode", "fmi3EnterStepMode",
                 "fmi3EnterConfigurationMode", "fmi3ExitConfigurationMode",
                 "fmi3EvaluateDiscreteStates")
_MESH_IMPLEMENTED = COMMON_IMPLEMENTED | set(_MESH_TRIVIAL) | {
    "fmi3InstantiateModelExchange", "fmi3EnterInitializationMode", "fmi3GetFloat64",
    "fmi3SetFloat64", "fmi3GetInt32", "fmi3GetInt64", "fmi3SetInt64", "fmi3DoStep",
    "fmi3SetTime", "fmi3UpdateDiscreteStates", "fmi3CompletedIntegratorStep",
    "fmi3GetNumberOfContinuousStates", "fmi3GetNumberOfEventIndicators",
    "fmi3SetContinuousStates", "fmi3GetContinuousStates",
    "fmi3GetContinuousStateDerivatives", "fmi3GetNominalsOfContinuousStates",
    "fmi3GetEventIndicators"}
#: Units of the FMUs' variables: name -> BaseUnit attributes.
UNITS = {
    "s": 's="1"', "rad": 'rad="1"', "rad/s": 's="-1" rad="1"', "rpm": 's="-1" rad="1" '
    'factor="0.10471975511965977"', "us": 's="1" factor="1e-06"',
    "N.m": 'kg="1" m="2" s="-2"', "N": 'kg="1" m="1" s="-2"',
    "arcsec": 'rad="1" factor="4.84813681109536e-06"',
    "MPa": 'kg="1" m="-1" s="-2" factor="1000000"', "mm": 'm="1" factor="0.001"',
    "N.s/mm": 'kg="1" s="-1" factor="1000"'}
#: The shared contact-law sources inside every FMU (``data/templates/fmu``).
LAW_FILES = ("gc_contact_law.h", "gc_contact_law.c")
#: The line law's sources beside them in a cylindrical pair's FMUs (:mod:`.fmu_cylindrical`).
LINE_LAW_FILES = ("gc_line_law.h", "gc_line_law.c")
#: The compiler flags of an FMU's binary built at export (with ``-fPIC -shared``): C99,
#: strict warnings, ``-O2`` and no FMA contraction (the twin's roundings). (``-O3`` gives
#: the same bits and ~7 % fewer instructions per drivetrain step, but measured no faster.)
FMU_CFLAGS = ("-std=c99", "-Wall", "-Wextra", "-Werror", "-O2", "-ffp-contract=off")
_CFLAGS = FMU_CFLAGS + ("-fPIC", "-shared", "-fvisibility=default")


@dataclass(frozen=True)
class MeshFmu:
    """What :func:`export_mesh_fmu` wrote.

    Attributes
    ----------
    fmu_path : Path
        The ``.fmu`` archive.
    table_path : Path
        The baked table as ``.npz`` (:meth:`MeshLawTable.from_npz`), beside the FMU.
    model_identifier : str
        The shared library's name (without ``.so``).
    """

    fmu_path: Path
    table_path: Path
    model_identifier: str


def check_fmu_kind(kind: str) -> str:
    """``kind`` if the export can build it, else :class:`InputRangeError` naming it."""
    if kind not in FMU_KINDS:
        raise InputRangeError("--kind", kind, f"one of {list(FMU_KINDS)}")
    return kind


def fmi3_header_dir() -> Path:
    """The FMI 3.0 headers (``fmi3Functions.h`` ...) inside the installed FMPy.

    Raises
    ------
    ToolUnavailable
        FMPy is not installed or ships no FMI 3.0 headers.
    """
    try:
        import fmpy
    except ImportError as exc:
        raise ToolUnavailable("gearcontact export fmu needs FMPy's FMI 3.0 headers: pip "
                              "install 'gearcontact[fmu]' (or fmpy)") from exc
    d = Path(fmpy.__file__).parent / "c-code"
    if not (d / "fmi3Functions.h").is_file():
        raise ToolUnavailable(f"FMPy {fmpy.__version__} ships no fmi3Functions.h in {d}")
    return d


def _unsupported(header_dir: Path, implemented) -> list[tuple[str, str, list[str]]]:
    """(name, parameter list, parameter names) of every FMI 3.0 function returning
    fmi3Status not in ``implemented``, parsed from fmi3FunctionTypes.h."""
    text = (header_dir / "fmi3FunctionTypes.h").read_text()
    out = []
    for name, args in re.findall(r"typedef\s+fmi3Status\s+(fmi3\w+)TYPE\s*\(([^;]*?)\)\s*;",
                                 text, re.S):
        if name in implemented:
            continue
        args = " ".join(args.split())
        names = [re.findall(r"(\w+)\s*(?:\[\])?$", a.strip())[0] for a in args.split(",")]
        out.append((name, args, names))
    return out


def c_double(x) -> str:
    """Exact C99 hexadecimal literal of a double."""
    return float(x).hex()


def fmu_context(*, model_identifier: str, token: str, header_dir: Path, variables,
                implemented, trivial, description: str, model_source: str,
                hertz_form: str = DEFAULT_HERTZ_FORM) -> dict:
    """The template context every FMU shares: identity, the variable table (``(name,
    value reference, type, causality, variability, unit, description)``), the units it
    uses, the FMI functions to stub, the C sources and the contact law's constants
    (``hertz_form``: its fp64 Hertz form, module docstring)."""
    from .. import __version__
    from ..preview.hertz.reference import ENVELOPE
    from ..twin.contact_law import _HB_E, _S_GAP

    units = sorted({v[5] for v in variables if v[5]})
    return {
        "version": __version__, "model_identifier": model_identifier, "token": token,
        "description": description, "model_variables": tuple(variables),
        "variables": [{"name": v[0], "vr": v[1]} for v in variables],
        "units": [(u, UNITS[u]) for u in units], "backends": BACKENDS,
        "unsupported": _unsupported(header_dir, implemented), "trivial": tuple(trivial),
        "c_sources": [model_source, "gc_contact_law.c",
                      *sum(library_files(hertz_form)[1:], ())],
        "hertz_form": hertz_form, "exact_hertz": hertz_form != DEFAULT_HERTZ_FORM,
        "pi": c_double(math.pi), "hb_e": c_double(_HB_E), "s_gap": c_double(_S_GAP),
        "w_eval_min": c_double(W_EVAL_MIN_N), "w_eval_max": c_double(_W_EVAL_MAX_N),
        # the datapath's domain the twin counts previews outside of (model._prm's P_CLO,
        # P_CHI, P_AHI)
        "curv_lo": c_double(ENVELOPE["curvature_per_mm"][0]),
        "curv_hi": c_double(ENVELOPE["curvature_per_mm"][1]),
        "alpha_max": c_double(ENVELOPE["alpha"][1]),
        "model_exchange": False, "fixed_step": None, "default_step": None, "starts": {},
        "output_dependencies": None, "initial_dependencies": "", "line_law": False}


def _mesh_context(tab: MeshLawTable, *, pair_name: str, side: str, token: str,
                  ident: str, header_dir: Path) -> dict:
    from ..preview.hertz.golden import encode_e_prime

    def rows(a):
        return [[c_double(v) for v in r] for r in a]

    n_rows, n_pairs = tab.eps_rad.shape[0], tab.lever_mm.shape[0]
    bending = tab.bending_mm_per_n is not None
    ctx = fmu_context(
        model_identifier=ident, token=token, header_dir=header_dir,
        variables=MESH_VARIABLES, implemented=_MESH_IMPLEMENTED, trivial=_MESH_TRIVIAL,
        model_source="gc_mesh_fmu.c", hertz_form=tab.hertz_form,
        description=f"Gear mesh element of {pair_name} ({side} flank): the gearcontact "
                    "twin's contact law (preview stage D on the TCA's curvatures, "
                    f"{'exact Hertz, fp64 only, ' if tab.hertz_form != DEFAULT_HERTZ_FORM else ''}"
                    f"{'tooth bending in series' if bending else 'rigid teeth'}), table of "
                    f"{n_rows} phases x {n_pairs} pairs baked in")
    ctx.update({
        "pair_name": pair_name, "side": side, "n_rows": n_rows, "n_pairs": n_pairs,
        "step_rad": c_double(tab.step_rad), "pitch_rad": c_double(tab.pitch_rad),
        "ratio": c_double(tab.ratio), "lever0_mm": c_double(tab.reference_lever_mm),
        "e_prime_mpa": c_double(tab.e_prime_mpa), "e_code": int(encode_e_prime(tab.e_prime_mpa)),
        "motion_sign": int(tab.motion_sign), "arcsec_per_rad": c_double(ARCSEC_PER_RAD),
        "eps": [c_double(v) for v in tab.eps_rad],
        "tables": [("LEVER_MM", rows(tab.lever_mm)), ("OPENING_MM", rows(tab.opening_mm)),
                   ("A_MINUS", rows(tab.A_minus_per_mm)), ("B_MINUS", rows(tab.B_minus_per_mm))],
        "valid": [[int(v) for v in r] for r in tab.valid],
        "bending": bending, "cb": rows(tab.bending_mm_per_n) if bending else [],
        "model_exchange": True, "output_dependencies": "1 2 3 4 13 14",
        "initial_dependencies": "1 2 3 4 13 14"})
    return ctx


def _environment_fmu():
    """The C library's Jinja2 environment, loading ``{% include %}`` from the FMU
    templates."""
    from jinja2 import FunctionLoader

    env = _environment()
    folder = resources.files("gearcontact").joinpath("data/templates/fmu")
    env.loader = FunctionLoader(lambda name: folder.joinpath(name).read_text())
    return env


def _render(env, name: str, ctx: dict) -> str:
    return env.get_template(f"{name}.j2").render(ctx)


def model_token(data: bytes) -> str:
    """The instantiation token: a GUID-shaped digest of the baked data."""
    d = hashlib.sha256(data).hexdigest()
    return "{%s-%s-%s-%s-%s}" % (d[:8], d[8:12], d[12:16], d[16:20], d[20:32])


def build_fmu(fmu_path: Path, ctx: dict, header_dir: Path) -> None:
    """Render the model source ``ctx["c_sources"][0]`` with the shared contact law and
    the preview's C library, compile the shared library and zip the FMU at
    ``fmu_path`` (``modelDescription.xml``, ``sources/``, ``binaries/x86_64-linux/``)."""
    env = _environment_fmu()
    c_files = render_c_library(hertz_form=ctx["hertz_form"])
    lib = sum(library_files(ctx["hertz_form"]), ())
    ident, model_source = ctx["model_identifier"], ctx["c_sources"][0]
    with tempfile.TemporaryDirectory() as tmp:
        src = Path(tmp) / "sources"
        src.mkdir()
        for name in lib:
            (src / name).write_text(c_files[name])
        law = LAW_FILES + (LINE_LAW_FILES if ctx["line_law"] else ())
        for name in law + (model_source, "buildDescription.xml"):
            (src / name).write_text(_render(env, name, ctx))
        so = Path(tmp) / f"{ident}.so"
        _compile(src, ctx["c_sources"], header_dir, so)
        with zipfile.ZipFile(fmu_path, "w", zipfile.ZIP_DEFLATED) as z:
            z.writestr(_entry("modelDescription.xml"),
                       _render(env, "modelDescription.xml", ctx))
            for p in sorted(src.iterdir()):
                z.writestr(_entry(f"sources/{p.name}"), p.read_bytes())
            z.writestr(_entry(f"binaries/x86_64-linux/{ident}.so"), so.read_bytes())


def _compile(src_dir: Path, sources: list[str], header_dir: Path, so_path: Path) -> None:
    cc = shutil.which("gcc") or shutil.which("cc")
    if cc is None:
        raise ToolUnavailable("gearcontact export fmu needs a C compiler (gcc or cc) on PATH")
    cmd = [cc, *_CFLAGS, "-I", str(src_dir), "-I", str(header_dir), "-o", str(so_path),
           *[str(src_dir / s) for s in sources], "-lm"]
    run = subprocess.run(cmd, capture_output=True, text=True)
    if run.returncode != 0:     # a bug of the generator, never the user's input
        raise RuntimeError(f"compiling the FMU failed:\n{' '.join(cmd)}\n{run.stderr}")


def export_mesh_fmu(pair, out_dir, *, pair_name: str, side: str, phases: int = 61,
                    torque_nm: float = 64.5, bending: bool = False,
                    flanks=None, hertz_form: str = DEFAULT_HERTZ_FORM) -> MeshFmu:
    """Write the mesh FMU of ``pair`` into ``out_dir`` (module docstring).

    Parameters
    ----------
    pair : gearcontact.geometry.pair.GearPair
        The pair, prepared (an ease-off table on ``side``).
    out_dir : str or Path
        Output directory (created if missing).
    pair_name : str
        Name of the pair in the model name and description.
    side : str
        ``"drive"`` or ``"coast"``: the loaded flank.
    phases : int
        TCA phases per pinion pitch (rows of the baked table).
    torque_nm : float
        Gear torque sizing the posed fields of edge pairs (:func:`~gearcontact.twin.
        mesh.mesh_table`), N·m; the FMU's law holds at any load in the envelope.
    bending : bool
        Tooth bending of both members in series with the Hertzian law (each pair's
        bending compliance in the table, as ``gearcontact twin --bending``); rigid teeth
        by default.
    flanks : FlankSet or None
        ``build_flanks(pair)`` if already built (a prepared pair's,
        :meth:`~gearcontact.tca.synthesis.PreparedPair.flank_set`); None: built here.
    hertz_form : str
        The fp64 law's Hertz form, ``"hamrock-brewe"`` (default) or ``"exact"`` (module
        docstring).

    Returns
    -------
    MeshFmu

    Raises
    ------
    ToolUnavailable
        Jinja2, FMPy's headers or a C compiler missing.
    InputRangeError
        ``hertz_form`` not one of the forms; with ``"exact"``, a mesh row whose
        curvature ratio lies beyond the exact table (as the twin's build_model).
    """
    from ..twin.mesh import pair_mesh_table
    from ..twin.model import exact_form_mesh

    check_hertz_form(hertz_form)
    header_dir = fmi3_header_dir()
    _environment()      # Jinja2 before the TCA
    # the twin's own mesh table (edge-contact TCA, docs/twin.md); with the exact form
    # its edge rows re-based on exact Hertz, as the twin's model
    mesh = pair_mesh_table(pair, side=side, torque_nm=torque_nm, phases=phases,
                           flanks=flanks, bending=bending)[2]
    tab = mesh_law_table(exact_form_mesh(mesh, hertz_form), hertz_form=hertz_form)
    return write_mesh_fmu(tab, out_dir, pair_name=pair_name, side=side,
                          header_dir=header_dir)


def write_mesh_fmu(tab, out_dir, *, pair_name: str, side: str, header_dir: Path,
                   adapt=None) -> MeshFmu:
    """Write the mesh FMU of the baked table ``tab`` (and the table as ``.npz``) into
    ``out_dir``: the template context of :func:`_mesh_context`, changed in place by
    ``adapt(ctx)`` if given (a cylindrical pair's line law, :mod:`.fmu_cylindrical`)."""
    ident = "gearcontact_mesh_" + re.sub(r"\W", "_", pair_name)
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    table_path = out / f"{ident}_table.npz"
    tab.to_npz(table_path)
    ctx = _mesh_context(tab, pair_name=pair_name, side=side, ident=ident,
                        token=model_token(table_path.read_bytes()), header_dir=header_dir)
    if adapt is not None:
        adapt(ctx)
    fmu_path = out / f"{ident}.fmu"
    build_fmu(fmu_path, ctx, header_dir)
    return MeshFmu(fmu_path, table_path, ident)


def _entry(name: str) -> zipfile.ZipInfo:
    """A zip entry with a fixed time stamp (identical exports, identical archives but
    for the compiler's binary)."""
    info = zipfile.ZipInfo(name, date_time=(1980, 1, 1, 0, 0, 0))
    info.compress_type = zipfile.ZIP_DEFLATED
    info.external_attr = 0o644 << 16
    return info
