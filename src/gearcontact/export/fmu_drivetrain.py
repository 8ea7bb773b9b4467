"""``gearcontact export fmu --kind drivetrain``: the drivetrain twin as an FMI 3.0
co-simulation FMU in plain C.

:func:`export_drivetrain_fmu` builds the twin's model of the pair exactly as
``gearcontact twin`` does (:func:`gearcontact.twin.model.model_for_pair`: the loaded
flank's TCA and mesh table, the reverse flank's own table or the mirrored law, the
``[drivetrain]`` parameters, the preview's curvature source ``stencil`` or ``exact``;
rigid teeth, or with ``bending`` the tooth bending of both members in series with the
Hertzian law, as ``gearcontact twin --bending``), bakes its per-flank arrays and constants into
``data/templates/fmu/gc_drivetrain_fmu.c.j2`` -- a port of
the twin's step loop (:mod:`gearcontact.twin.kernel`), static point, mesh damping and
speed controller (:mod:`gearcontact.twin.statics`) and start
(:func:`gearcontact.twin.simulate.simulate`), operation by operation -- beside the
contact law the mesh FMU uses (``gc_contact_law.c``: stage D, and for the stencil
source stage C, of the preview's C library), and
builds the FMU with :func:`.fmu.build_fmu`. Parameters ``backend`` (fp64 = the twin's
``reference``, golden), ``speed_rpm``, ``torque_nm``, ``step_us``; the mesh table's
edge-pair fields are sized at the export torque (``--torque``), as the twin sizes them at
its run's, and cover every load up to it: a ``torque_nm`` above it is refused at
initialisation (and is the variable's ``max``). Importer facts: docs/export.md.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..contract.qformat import STENCIL_GAP
from ..ltca.pair_ltca import ARCSEC_PER_RAD
from ..preview.hertz.formats import DEFAULT_HERTZ_FORM
from .c_constants import fit_linear_safe_code
from .fmu import (COMMON_IMPLEMENTED, build_fmu, c_double, fmi3_header_dir, fmu_context,
                  model_token)

__all__ = ["DRIVETRAIN_VARIABLES", "DrivetrainFmu", "export_drivetrain_fmu",
           "write_drivetrain_fmu", "drivetrain_fmu_model"]

#: (name, value reference, type, causality, variability, unit, description).
DRIVETRAIN_VARIABLES = (
    ("time", 0, "Float64", "independent", "continuous", "s", "simulation time"),
    ("pinion_speed_rpm", 1, "Float64", "output", "continuous", "rpm", "pinion speed"),
    ("pinion_speed_rad_s", 2, "Float64", "output", "continuous", "rad/s", "pinion speed"),
    ("gear_speed_rad_s", 3, "Float64", "output", "continuous", "rad/s", "gear speed"),
    ("dte_arcsec", 4, "Float64", "output", "continuous", "arcsec",
     "dynamic transmission error, TCA sign (twin's te_arcsec)"),
    ("mesh_rotation_rad", 5, "Float64", "output", "continuous", "rad",
     "mesh rotation theta of the loaded flank"),
    ("mesh_torque_nm", 6, "Float64", "output", "continuous", "N.m",
     "mesh torque on the gear along the motion (loaded minus reverse flank)"),
    ("mesh_force_n", 7, "Float64", "output", "continuous", "N",
     "total normal load of both flanks"),
    ("p_max_mpa", 8, "Float64", "output", "continuous", "MPa",
     "peak pressure of the most loaded pair"),
    ("a_mm", 9, "Float64", "output", "continuous", "mm", "its semi-axis a"),
    ("b_mm", 10, "Float64", "output", "continuous", "mm", "its semi-axis b"),
    ("pairs_loaded", 11, "Int32", "output", "discrete", "", "pairs carrying load"),
    ("backend", 12, "Enumeration", "parameter", "fixed", "",
     "contact law: fp64 (the twin's reference backend) or golden (fixed-point stage D)"),
    ("speed_rpm", 13, "Float64", "parameter", "fixed", "rpm",
     "nominal pinion (motor) speed, 0 to 1e5"),
    ("torque_nm", 14, "Float64", "parameter", "fixed", "N.m",
     "load torque on the gear, > 0 and at most the export torque (the mesh table's size)"),
    ("step_us", 15, "Float64", "parameter", "fixed", "us",
     "fixed RK4 step, 1 to 50 us and h omega_max <= 2"),
    # Int64: a step forms up to ~10 previews; at 1e5 steps/s (10 us) ~1e6 previews/s
    # would pass Int32's 2^31 - 1 after ~36 min of (hardware-in-the-loop: real) time
    ("previews_outside_datapath", 16, "Int64", "output", "discrete", "",
     "previews since initialization outside the fixed-point datapath's domain, "
     "evaluated by the fp64 law (the twin's summary key)"),
    ("steps_outside_datapath", 17, "Int64", "output", "discrete", "",
     "steps since initialization with at least one such preview (the twin's)"),
    ("previews_without_contact_law", 18, "Int64", "output", "discrete", "",
     "previews since initialization without a contact law (a saddle, or a curvature "
     "ratio beyond the exact Hertz table): the pair carries no load (the twin's)"),
)
#: FMI functions the drivetrain model implements beside the shared ones.
_TRIVIAL = ("fmi3Terminate", "fmi3EnterStepMode", "fmi3EnterConfigurationMode",
            "fmi3ExitConfigurationMode")
_IMPLEMENTED = COMMON_IMPLEMENTED | set(_TRIVIAL) | {
    "fmi3EnterInitializationMode", "fmi3ExitInitializationMode", "fmi3GetFloat64",
    "fmi3SetFloat64", "fmi3GetInt32", "fmi3GetInt64", "fmi3SetInt64", "fmi3DoStep",
    "fmi3InstantiateModelExchange"}


@dataclass(frozen=True)
class DrivetrainFmu:
    """What :func:`export_drivetrain_fmu` wrote.

    Attributes
    ----------
    fmu_path : Path
        The ``.fmu`` archive.
    model_identifier : str
        The shared library's name (without ``.so``).
    torque_nm : float
        The export torque (the ``torque_nm`` parameter's start value), N·m.
    """

    fmu_path: Path
    model_identifier: str
    torque_nm: float


def drivetrain_fmu_model(pair, *, side: str, phases: int, torque_nm: float,
                         drivetrain=None, curvatures: str = "stencil", bending: bool = False,
                         flanks=None, hertz_form: str = DEFAULT_HERTZ_FORM):
    """The twin's model the drivetrain FMU bakes: :func:`~gearcontact.twin.model.
    model_for_pair` with rigid teeth (or tooth bending, ``bending``) and the preview's
    curvature source ``curvatures``
    (the reference backend's arrays; the golden backend's stencil samples are added by
    :func:`export_drivetrain_fmu`); ``flanks``: the pair's, if already built;
    ``hertz_form``: the fp64 law's Hertz form, as ``gearcontact twin --hertz-form``."""
    from ..twin.model import model_for_pair

    return model_for_pair(pair, torque_nm=torque_nm, backend="reference",
                          drivetrain=drivetrain, side=side, phases=phases,
                          curvatures=curvatures, bending=bending, flanks=flanks,
                          hertz_form=hertz_form)


def _constants(model) -> list[tuple[str, str]]:
    from ..twin import layout as L
    from ..twin.model import _prm
    from ..twin.simulate import MAX_SPEED_RPM, STABILITY_LIMIT, STEP_RANGE_US

    prm = _prm(model, 0.0)
    m, dt = model.mesh, model.drivetrain
    c = c_double
    return [
        ("RATIO", c(prm[L.P_U])), ("L0_MM", c(prm[L.P_L0])), ("J_M", c(prm[L.P_JM])),
        ("J_P", c(prm[L.P_JP])), ("J_G", c(prm[L.P_JG])), ("J_L", c(prm[L.P_JL])),
        ("K1", c(prm[L.P_K1])), ("K2", c(prm[L.P_K2])), ("C1", c(prm[L.P_C1])),
        ("C2", c(prm[L.P_C2])), ("THETA_B_RAD", c(prm[L.P_THB])),
        ("E_PRIME_MPA", c(prm[L.P_EP])), ("E_CODE", str(int(prm[L.P_ECODE]))),
        ("DPSI_RAD", c(prm[L.P_DPSI])), ("PITCH_RAD", c(prm[L.P_PITCH])),
        ("NROW", str(int(prm[L.P_NROW]))), ("DPSI_R_RAD", c(prm[L.P_DPSIR])),
        ("NROW_R", str(int(prm[L.P_NROWR]))), ("PSI_R_RAD", c(prm[L.P_PSIR])),
        ("C_R_RAD", c(prm[L.P_CR])), ("MIRROR", str(int(prm[L.P_MIRROR] != 0.0))),
        ("PITCH0_RAD", c(m.pitch_rad)), ("MOTION_SIGN", c(float(m.motion_sign))),
        ("ARCSEC_PER_RAD", c(ARCSEC_PER_RAD)), ("PI", c(math.pi)),
        ("MESH_DAMPING_RATIO", c(dt.mesh_damping_ratio)),
        ("SPEED_CONTROL_HZ", c(dt.speed_control_bandwidth_hz)),
        ("STABILITY_LIMIT", c(STABILITY_LIMIT)), ("MAX_SPEED_RPM", c(MAX_SPEED_RPM)),
        ("STEP_US_MIN", c(STEP_RANGE_US[0])), ("STEP_US_MAX", c(STEP_RANGE_US[1])),
        ("SPEED_RPM_START", c(3000.0)), ("TORQUE_NM_START", c(model.torque_nm)),
        ("TORQUE_NM_MAX", c(model.torque_nm)),
        ("STEP_US_START", c(10.0))]


def _cv_bound_mm() -> float:
    """The largest |sample| (mm) of the stencil table for which gc_contact_law.c skips
    the golden quantization's range test and the fit's c0..c2: 256 mm (the range
    test's argument), or below it the samples whose interpolation at -1/2 <= f <= 3/2
    (within twice the larger of its two rows' samples, plus one code in the rounding)
    stays within :func:`.c_constants.fit_linear_safe_code`."""
    return min(256.0, math.ldexp((fit_linear_safe_code() - 1) // 2, -STENCIL_GAP.frac))


def _row_pairs(valid) -> list:
    """Per table and row interval ``(i, i + 1)`` (the last row's padded with zeros): the
    count of pairs valid at both rows, then those pairs ascending, padded to
    ``pairs + 1`` entries (the C loop's list, ``ROW_PAIRS``)."""
    valid = np.asarray(valid, bool)
    n_p, n_k = valid.shape[1], valid.shape[2]
    rows = []
    for side in valid:
        both = side[:, :-1] & side[:, 1:]
        lists = [[int(j) for j in np.flatnonzero(both[:, i])] for i in range(n_k - 1)] + [[]]
        rows.append([[len(x), *x] + [0] * (n_p - len(x)) for x in lists])
    return rows


def _row_law(lever, opening, valid) -> list:
    """Per table, row interval ``(i, i + 1)`` and entry of :func:`_row_pairs`' list (pair
    ``j``): ``lever[j, i]``, ``lever[j, i + 1] - lever[j, i]``, ``opening[j, i]``,
    ``opening[j, i + 1] - opening[j, i]`` as C literals, padded with zeros to ``pairs``
    records (the C loop's ``ROW_LAW``: the twin's interpolation operands, its
    differences formed here in IEEE double as :func:`gearcontact.twin.kernel._elastic`
    forms them, the same doubles)."""
    lever, opening = np.asarray(lever, float), np.asarray(opening, float)
    n_p, n_k = lever.shape[1], lever.shape[2]
    zero = [c_double(0.0)] * 4
    tables = []
    for s, side in enumerate(_row_pairs(valid)):
        rows = []
        for i, entry in enumerate(side):
            recs = [[c_double(float(x)) for x in (
                lever[s, j, i], lever[s, j, i + 1] - lever[s, j, i],
                opening[s, j, i], opening[s, j, i + 1] - opening[s, j, i])]
                for j in entry[1:1 + entry[0]]]
            rows.append(recs + [zero] * (n_p - len(recs)))
        assert len(rows) == n_k
        tables.append(rows)
    return tables


def _e_rec(eps, ratio: float, dpsi: tuple[float, float]) -> list:
    """Per table and row interval ``(i, i + 1)``: ``eps[i]``, ``eps[i + 1] - eps[i]`` and
    ``1 / u + (eps[i + 1] - eps[i]) / dpsi`` as C literals (the last row: ``eps``, 0,
    ``1 / u``): :func:`gearcontact.twin.kernel._deriv`'s interpolation operands and
    factor ``d theta / d psi_p``, formed in IEEE double as it forms them (the C loop's
    ``E_REC``: the same doubles)."""
    eps = np.asarray(eps, float)
    inv_u = 1.0 / float(ratio)
    tables = []
    for s, row in enumerate(eps):
        d = [float(row[i + 1]) - float(row[i]) for i in range(len(row) - 1)] + [0.0]
        tables.append([[c_double(float(row[i])), c_double(d[i]),
                        c_double(inv_u + d[i] / float(dpsi[s]))] for i in range(len(row))])
    return tables


def export_drivetrain_fmu(pair, out_dir, *, pair_name: str, side: str, phases: int = 61,
                          torque_nm: float = 64.5, drivetrain=None,
                          curvatures: str = "stencil", bending: bool = False,
                          flanks=None, hertz_form: str = DEFAULT_HERTZ_FORM) -> DrivetrainFmu:
    """Write the drivetrain FMU of ``pair`` into ``out_dir`` (module docstring; a
    cylindrical pair: its twin's model :func:`~gearcontact.twin.cylindrical.
    cylindrical_model` with the line law, :mod:`.fmu_cylindrical`).

    Parameters
    ----------
    pair : gearcontact.geometry.pair.GearPair or CylindricalPair
        The pair, prepared (an ease-off table on ``side``; a cylindrical pair as loaded).
    out_dir : str or Path
        Output directory (created if missing).
    pair_name : str
        Name of the pair in the model name and description.
    side : str
        ``"drive"`` or ``"coast"``: the loaded flank.
    phases : int
        TCA phases per pinion pitch.
    torque_nm : float
        Gear torque sizing the mesh table (as ``gearcontact twin --torque``) and the
        start value of the FMU's ``torque_nm``, N·m.
    drivetrain : gearcontact.twin.params.DrivetrainParams or None
        The ``[drivetrain]`` parameters (None: the pair's defaults).
    curvatures : str
        The preview's curvature source, as ``gearcontact twin --curvatures``:
        ``"stencil"`` (the twin's default: stage C on the 7 x 7 gap stencil, then stage
        D) or ``"exact"`` (the TCA's curvatures).
    bending : bool
        Tooth bending of both members in series with the Hertzian law (the mesh table's
        pair bending compliances, as ``gearcontact twin --bending``); rigid teeth by
        default.
    flanks : FlankSet or None
        ``build_flanks(pair)`` if already built (a prepared pair's,
        :meth:`~gearcontact.tca.synthesis.PreparedPair.flank_set`); None: built here.
    hertz_form : str
        The fp64 law's Hertz form, as ``gearcontact twin --hertz-form``:
        ``"hamrock-brewe"`` (default) or ``"exact"`` (the twin's exact Hertz, its table
        and cubic in C; the FMU's backend fp64 only; bevel and hypoid pairs).

    Returns
    -------
    DrivetrainFmu

    Raises
    ------
    ToolUnavailable
        Jinja2, FMPy's headers or a C compiler missing.
    InputRangeError
        A curvature source other than ``stencil`` on a cylindrical pair
        (:func:`.fmu_cylindrical.check_cylindrical_fmu`); a Hertz form the twin refuses
        (the exact form on a cylindrical pair, a mesh row beyond the exact table:
        :func:`gearcontact.twin.model.build_model`).
    """
    from .c_library import _environment

    header_dir = fmi3_header_dir()
    _environment()      # Jinja2 before the TCA
    from ..geometry.pair import CYLINDRICAL
    from ..twin.cylindrical import cylindrical_model
    from ..twin.model import CURVATURE_SOURCES
    from .fmu_cylindrical import check_cylindrical_fmu
    from ..validation import InputRangeError

    if getattr(pair, "kind", None) == CYLINDRICAL:
        # the twin's line chain (.fmu_cylindrical), before the TCA
        check_cylindrical_fmu(curvatures=curvatures, hertz_form=hertz_form)
        model = cylindrical_model(pair, torque_nm=torque_nm, drivetrain=drivetrain,
                                  side=side, phases=phases, bending=bending)
    else:
        if curvatures not in CURVATURE_SOURCES:     # before the TCA
            raise InputRangeError("curvatures", curvatures,
                                  f"one of {list(CURVATURE_SOURCES)}")
        model = drivetrain_fmu_model(pair, side=side, phases=phases, torque_nm=torque_nm,
                                     drivetrain=drivetrain, curvatures=curvatures,
                                     bending=bending, flanks=flanks,
                                     hertz_form=hertz_form)
    return write_drivetrain_fmu(model, out_dir, pair_name=pair_name, side=side,
                                bending=bending, header_dir=header_dir)


def write_drivetrain_fmu(model, out_dir, *, pair_name: str, side: str, bending: bool,
                         header_dir: Path) -> DrivetrainFmu:
    """Write the drivetrain FMU of the twin's ``model`` (reference backend; its curvature
    source and Hertz form are the FMU's; ``bending``: the model's tables carry the
    pairs' bending compliance) into ``out_dir``: :func:`export_drivetrain_fmu`'s
    second half, for a model built by the caller (a test's edited mesh table)."""
    from ..twin import layout as L
    from ..twin.model import _prm, _stack
    from ..twin.simulate import _CHUNK
    from .fmu_cylindrical import line_drivetrain_context

    line = model.curvature_source == L.LINE_SOURCE
    curvatures = L.LINE_SOURCE if line else model.curvatures
    hertz_form = model.hertz_form
    a, m = model.arrays, model.mesh
    stencil = curvatures == "stencil"
    # exact A-, B- always (the static start's bracket); the stencil source as the golden
    # twin stacks it: the 49 samples, then the fp64 fit's c3, c4, c5
    rev = model.reverse if model.reverse is not None else m
    exact = _stack(m, rev, "exact", golden=False)["cv"]
    cv = _stack(m, rev, "stencil", golden=True)["cv"] if stencil else None
    ident = "gearcontact_drivetrain_" + re.sub(r"\W", "_", pair_name)

    def hexes(x):
        x = np.asarray(x, float)
        return [c_double(v) for v in x] if x.ndim == 1 else [hexes(r) for r in x]

    consts = _constants(model)
    prm = _prm(model, 0.0)
    line_ctx = line_drivetrain_context(model) if line else {}
    # an absent array digests as "" (np.asarray(None).tobytes() would be the address of
    # None: another token on every run)
    baked = repr((consts, curvatures, ["" if x is None else np.asarray(x).tobytes().hex()
                                       for x in (a["eps"], a["lever"], a["opening"],
                                                 a["valid"], exact, cv,
                                                 a["cb"] if bending else None)])
                 + ((line_ctx["line_token"],) if line else ())).encode()
    ctx = fmu_context(
        model_identifier=ident, token=model_token(baked), header_dir=header_dir,
        variables=DRIVETRAIN_VARIABLES, implemented=_IMPLEMENTED, trivial=_TRIVIAL,
        model_source="gc_drivetrain_fmu.c", hertz_form=hertz_form,
        description=f"Drivetrain twin of {pair_name} ({side} flank loaded): motor, input "
                    "shaft, pinion, mesh (the gearcontact preview's contact law on the "
                    f"{'7 x 7 gap stencil' if stencil else 'TCA'}'s curvatures, both flanks"
                    f"{'; exact Hertz, fp64 only' if hertz_form != DEFAULT_HERTZ_FORM else ''}"
                    f"{'; tooth bending in series' if bending else ''}), "
                    "gear, output shaft, load; RK4 at step_us, PI speed control per "
                    "[drivetrain]")
    ctx.update({
        "pair_name": pair_name, "side": side, "constants": consts,
        "n_pairs": a["lever"].shape[1], "n_rows": a["lever"].shape[2],
        "n_rows0": len(m.psi_rad),
        "tables": [("LEVER", hexes(a["lever"])), ("OPENING", hexes(a["opening"])),
                   ("A_MINUS", hexes(exact[..., 0])), ("B_MINUS", hexes(exact[..., 1]))],
        "stencil": stencil, "curvatures": curvatures, "bending": bool(bending),
        "cb": hexes(a["cb"]) if bending else [], "block_steps": _CHUNK,
        "cv": [[hexes(p) for p in sd] for sd in cv] if stencil else [],
        # the golden quantization's range test is void where every sample is finite and
        # within +-256 mm (gc_contact_law.c's gap_codes, the bound's argument), and the
        # fit's c0..c2 cannot overflow where every interpolated sample (at -1/2 <= f <=
        # 3/2: within twice the larger of its rows', plus one code) stays within
        # GC_FIT_LINEAR_SAFE_CODE (gc_fit_golden_curvatures)
        "cv_in_range": stencil and bool(np.all(np.abs(cv[..., :-3]) <= _cv_bound_mm())),
        "cv_bound_mm": repr(_cv_bound_mm()),
        "valid": [[[int(v) for v in r] for r in s] for s in a["valid"]],
        "row_pairs": _row_pairs(a["valid"]),
        "e_rec": _e_rec(a["eps"], prm[L.P_U], (prm[L.P_DPSI], prm[L.P_DPSIR])),
        "row_law": _row_law(a["lever"], a["opening"], a["valid"]),
        "psi0": hexes(m.psi_rad), "eps0": hexes(m.eps_rad),
        "default_step": "1e-05", "default_stop": "0.05",
        "starts": {"speed_rpm": "3000", "torque_nm": repr(float(model.torque_nm)),
                   "step_us": "10"},
        "maxima": {"torque_nm": repr(float(model.torque_nm))},
        "initial_dependencies": "12 13 14 15", "n_cache": 7})
    if line:
        # with bending the coupled law's warm start per pair and flank after the
        # kernel's columns: the last effective ease-off (m slices) and its row
        m_sl = int(m.line_gap_mm.shape[-1]) + 2 * int(line_ctx["line"]["beyond"])
        ctx.update(line_ctx, n_cache=L.N_CACHE + (m_sl + 1 if bending else 0))
        ctx["c_sources"] = ctx["c_sources"][:2] + ["gc_line_law.c"] + ctx["c_sources"][2:]
        ctx["tables"] = ctx["tables"][:2]       # LEVER, OPENING: the law is the line rows'
        ctx["description"] = (
            f"Drivetrain twin of the cylindrical pair {pair_name} ({side} flank loaded): "
            "motor, input shaft, pinion, mesh (the gearcontact twin's line law: the "
            "preview's line chain on the 7 x 7 gap stencil, the slice law on the ease-off "
            f"along the line; {'tooth bending in series' if bending else 'rigid teeth'}; "
            "the reverse flank its law mirrored about the "
            "backlash), gear, output shaft, load; RK4 at step_us, PI speed control per "
            "[drivetrain]")
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    fmu_path = out / f"{ident}.fmu"
    build_fmu(fmu_path, ctx, header_dir)
    return DrivetrainFmu(fmu_path, ident, float(model.torque_nm))
