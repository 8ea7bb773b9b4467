"""``gearcontact export fmu`` on a cylindrical pair: the mesh and drivetrain FMUs of a
spur or helical pair in plain C, with the twin's line law (docs/export.md, "Cylindrical
pairs"; docs/cylindrical.md sec. 10).

The twin of a cylindrical pair runs the preview's *line chain* per loaded pair and step
(:mod:`gearcontact.twin.line_law`: stage C on the 7 x 7 stencil into the line core, the
slice law's loaded length on the ease-off along the line and the edge slices beyond a
helical line's ends, the finite line's approach on the half-spaces). Its C port is
``data/templates/fmu/gc_line_law.c.j2``, beside the preview's C library
(the golden line chain ``gc_chain_line_golden``) and the bevel FMUs' shared law
(``gc_contact_law.c``: the principal curvatures, the Hertz load); the mesh table's rows
and the slice law's constants are the twin's own (:func:`gearcontact.twin.cylindrical.
cylindrical_model`), baked at export:

* :func:`export_cylindrical_mesh_fmu`: ``--kind mesh``, the law of
  :mod:`.line_mesh_law` in ``gc_mesh_fmu.c.j2`` (``gc_line_mesh_law.c.j2``);
* :func:`line_drivetrain_context`: what ``--kind drivetrain`` adds for a cylindrical pair
  to :func:`.fmu_drivetrain.export_drivetrain_fmu` (the twin's step loop with the line
  law, ``gc_line_elastic.c.j2``; the reverse flank the loaded law mirrored about the
  backlash, as the twin's).

Tooth bending (``--bending``, as ``gearcontact twin --bending``): the twin's coupled
slice law (:func:`gearcontact.ltca.coupled_slice_law.coupled_solve` at the pair's
approach, Newton with the exact Jacobian on the loaded slices, the shells' Gram at the
slices baked per row; its secant compliance held in series over the step, the pair's
last effective ease-off its next start; docs/cylindrical.md sec. 8, 10) is ported with
the rest (``gc_coupled_slice_law.c.j2``, included by ``gc_line_law.c.j2``).
:func:`check_cylindrical_fmu` refuses a curvature source other than the line chain's.

Both FMUs output the bevel FMUs' domain counts (:data:`.fmu.DOMAIN_COUNTS`), counted as
the twin's line law counts previews (:func:`gearcontact.twin.line_law._line_fp64`):
``gc_line_law.c.j2``'s domain test on the C library's lift (``gc_line_lift_fp64``,
``gc_line_lifted_keeps_ellipse``: :func:`gearcontact.preview.hertz.reference.
line_lift`, ``lifted_keeps_ellipse``).
"""

from __future__ import annotations

import numpy as np

from ..validation import InputRangeError
from ..preview.hertz.formats import DEFAULT_HERTZ_FORM
from .fmu import MeshFmu, c_double, fmi3_header_dir, write_mesh_fmu

__all__ = ["check_cylindrical_fmu", "export_cylindrical_mesh_fmu", "line_law_context",
           "line_drivetrain_context"]


def check_cylindrical_fmu(*, curvatures: str | None,
                          hertz_form: str = DEFAULT_HERTZ_FORM) -> None:
    """Refuse what a cylindrical pair's FMUs do not build (before any work).

    Raises
    ------
    InputRangeError
        A curvature source other than the line chain's stencil; a Hertz form other
        than Hamrock-Brewe (the line chain's law, as ``gearcontact twin`` has it).
    """
    if curvatures not in (None, "stencil"):
        raise InputRangeError("--curvatures", curvatures, "stencil for a cylindrical pair "
                                                          "(the line chain: stage C on the "
                                                          "stencil per step)")
    if hertz_form != DEFAULT_HERTZ_FORM:
        raise InputRangeError("--hertz-form", hertz_form,
                              f"{DEFAULT_HERTZ_FORM} for a cylindrical pair (the line "
                              "chain's law; gearcontact twin refuses it too)")


def line_law_context(mesh, *, line_sources: bool = True) -> dict:
    """The template context of ``gc_line_law.{h,c}`` for a cylindrical pair's
    :class:`~gearcontact.twin.mesh.MeshTable`: the slice counts, the edge slices'
    effective width (``prm[P_BEYOND_W]``), whether the teeth bend (the table's slice
    Gram), E' and its code, the datapath's alpha_max, the line core's longest line, the
    fit's B- resolution and the coupled slice law's iteration cap (:data:`~gearcontact.ltca.coupled_slice_law.
    MAX_STEPS`; a test of the FMU's non-convergence path renders a lower one)."""
    from ..ltca.coupled_slice_law import MAX_STEPS
    from ..preview.chain import LINE_B_ZERO_CODES
    from ..contract.qformat import CURVATURE
    from ..preview.hertz.golden import encode_e_prime
    from ..preview.hertz.reference import ENVELOPE, LINE_ENVELOPE

    beyond = 0 if mesh.beyond_gap_mm is None else int(mesh.beyond_gap_mm.shape[-1])
    width = 0.0 if beyond == 0 else mesh.beyond_width_mm * mesh.beyond_stiffness
    return {"line_law": True, "line": {
        "slices": int(mesh.line_gap_mm.shape[-1]), "beyond": beyond,
        "bent": mesh.line_bending_gram_mm_per_n is not None,
        "beyond_w": c_double(width), "e_prime": c_double(mesh.e_prime_mpa),
        "e_code": int(encode_e_prime(mesh.e_prime_mpa)),
        "alpha_hi": c_double(ENVELOPE["alpha"][1]),
        "l_hi": c_double(LINE_ENVELOPE["line_length_mm"][1]),
        "b_zero": c_double(LINE_B_ZERO_CODES * CURVATURE.lsb),
        "max_steps": MAX_STEPS}}


def _with_line_sources(ctx: dict) -> list:
    """The FMU's C sources with the line law after the shared contact law."""
    src = list(ctx["c_sources"])
    return src[:2] + ["gc_line_law.c"] + src[2:]


def export_cylindrical_mesh_fmu(pair, out_dir, *, pair_name: str, side: str,
                                phases: int = 61, torque_nm: float = 64.5,
                                bending: bool = False) -> MeshFmu:
    """Write the mesh FMU of the cylindrical ``pair`` into ``out_dir`` (module docstring):
    the twin's mesh table (:func:`~gearcontact.twin.cylindrical.
    cylindrical_model` at ``phases`` per pitch, its edge slices' stiffness at
    ``torque_nm``, N·m of the gear; rigid teeth, or with ``bending`` the teeth's
    shells at the line slices, as ``gearcontact twin --bending``) as
    :class:`.line_mesh_law.LineMeshTable` (``.npz`` beside the FMU), the law of
    :func:`.line_mesh_law.line_mesh_outputs` in C.

    Raises
    ------
    ToolUnavailable
        Jinja2, FMPy's headers or a C compiler missing.
    """
    from ..twin.cylindrical import cylindrical_model
    from .c_library import _environment
    from .line_mesh_law import line_mesh_table

    header_dir = fmi3_header_dir()
    _environment()      # Jinja2 before the TCA
    mesh = cylindrical_model(pair, torque_nm=torque_nm, side=side, phases=phases,
                             bending=bending).mesh
    tab = line_mesh_table(mesh)

    def adapt(ctx):
        ctx.update(line_law_context(mesh))
        ctx["c_sources"] = _with_line_sources(ctx)
        ctx["tables"] = [t for t in ctx["tables"] if t[0] in ("LEVER_MM", "OPENING_MM")]
        ctx["line_rows"] = [[[c_double(v) for v in row] for row in p] for p in tab.line_rows]
        ctx["description"] = (
            f"Gear mesh element of the cylindrical pair {pair_name} ({side} flank): the "
            "gearcontact twin's line law (the preview's line chain on the 7 x 7 gap "
            "stencil, the slice law on the ease-off along the line; "
            f"{'tooth bending: the coupled slice law' if bending else 'rigid teeth'}), "
            "table of "
            f"{tab.eps_rad.shape[0]} phases x {tab.lever_mm.shape[0]} pairs baked in")

    return write_mesh_fmu(tab, out_dir, pair_name=pair_name, side=side,
                          header_dir=header_dir, adapt=adapt)


def line_drivetrain_context(model) -> dict:
    """What the drivetrain FMU of a cylindrical pair's twin ``model`` (reference backend)
    adds to its template context: the line law's constants, the golden line
    rows of the loaded flank (the only table: the reverse flank is its law mirrored), and
    the static bracket's inputs per pair at the first row (``B_max``, the line's length:
    :func:`gearcontact.twin.statics.static_rotation`)."""
    from .line_mesh_law import line_rows

    m = model.mesh
    rows = line_rows(m)
    b_max = np.maximum(m.A_minus_per_mm[:, 0], m.B_minus_per_mm[:, 0])
    n_p = model.arrays["lever"].shape[1]
    pad = np.zeros((n_p,) + rows.shape[1:])
    pad[:rows.shape[0]] = rows

    def hexes(x):
        return [c_double(v) for v in np.ravel(x)]

    b0 = np.zeros(n_p)
    b0[:b_max.size] = b_max
    l0 = np.zeros(n_p)
    l0[:m.line_length_mm.shape[0]] = np.nan_to_num(m.line_length_mm[:, 0])
    return {**line_law_context(m), "line_rows": [[hexes(r) for r in p] for p in pad],
            "line_b_max0": hexes(b0), "line_length0": hexes(l0),
            "line_token": np.ascontiguousarray(pad).tobytes().hex()}
