"""The table twin (offline loaded TE over phase x torque, interpolated).

Truth:

* built from the preview's loaded TE (``TE_pre``: the same Hertzian pairs as the
  reference twin), the table twin reproduces the reference twin up to the table's
  interpolation in torque and phase;
* built from the LTCA (``TE_LCP``), its quasi-static TE at a ladder torque is the loaded
  TE of :func:`gearcontact.ltca.lte.loaded_te` at that torque (rows of the phase
  grid), i.e. the table is read back at the right phase and rotation; so with tooth
  bending in the table's LCP and the truth's;
* the table law read back on a synthetic law ``theta = a T + b T^(2/3)``.
"""

import math

import numpy as np
import pytest
from dataclasses import replace

from gearcontact.ltca.lte import loaded_te
from gearcontact.twin.ltca_table import torque_table
from gearcontact.twin.mesh import mesh_table
from gearcontact.twin.params import default_drivetrain
from gearcontact.twin.simulate import build_model, simulate
from gearcontact.validation import InputRangeError

from .conftest import TORQUE_NM, quasi_static_bound_arcsec

CELLS = 16
LADDER = (0.25, 0.5, 1.0, 1.5, 2.0)


@pytest.fixture(scope="module")
def tables(s0003_twin):
    pair, tca, flanks, _ = s0003_twin
    mesh = mesh_table(tca, flanks, pair, torque_nm=TORQUE_NM, cells=CELLS,
                      edge_law=False)
    out = {src: torque_table(tca, flanks, pair, mesh, TORQUE_NM, source=src, ladder=LADDER,
                             cells=CELLS) for src in ("preview", "lcp")}
    return mesh, out


def test_preview_table_twin_equals_the_reference_twin(s0003_twin, tables):
    pair = s0003_twin[0]
    mesh, tab = tables
    dt = default_drivetrain(pair)
    runs = {}
    for be, table in (("reference", None), ("table", tab["preview"])):
        m = build_model(mesh, dt, TORQUE_NM, backend=be, table=table,
                        curvatures="exact")     # the preview table's law
        runs[be] = simulate(m, speed_rpm=3000.0, duration_s=0.01, step_s=10e-6)
    r, t = runs["reference"].columns, runs["table"].columns
    # same static point at the first phase (the table is exact at the ladder torques)
    w0 = runs["reference"].summary["static_mesh_load_n"]
    # T^(2/3) linear in theta between ladder torques is exact for one Hertzian pair;
    # with 3-4 pairs sharing, the load split bends it: <= 0.5 % of the load over the run;
    # in phase the table interpolates the rotation, the reference twin the geometry
    # (levers, openings, curvatures): where an edge pair enters, the two part by up to
    # 0.08 arcsec between rows (the bound of the quasi-static test, test_simulate);
    # measured 0.083 arcsec in this run: bound 0.12 arcsec (6 % of the TE p-p 2.0)
    assert np.abs(t["mesh_load_n"] - r["mesh_load_n"]).max() < 5e-3 * w0
    assert np.abs(t["te_arcsec"] - r["te_arcsec"]).max() < 0.12
    assert runs["table"].summary["dynamic_factor"] == pytest.approx(
        runs["reference"].summary["dynamic_factor"], abs=2e-3)


@pytest.mark.parametrize("bending", [False, True])
def test_lcp_table_quasi_static_is_the_loaded_te(s0003_twin, s0003_drive_bending, tables,
                                                 bending):
    """At the rows of a 60 rpm run, the table twin's TE is the loaded TE (rigid teeth,
    or with the shell bending of both teeth in the table's LCP and the truth's, bound
    with exponent 1: ``--bending``; measured 0.0135 arcsec with bending)."""
    pair, tca, flanks, _ = s0003_twin
    mesh, tab = tables
    bend = s0003_drive_bending if bending else None
    if bending:
        mesh = mesh_table(tca, flanks, pair, torque_nm=TORQUE_NM, cells=CELLS, bending=bend,
                          edge_law=False)
        tab = {"lcp": torque_table(tca, flanks, pair, mesh, TORQUE_NM, source="lcp",
                                   ladder=LADDER[1:4], cells=CELLS, bending=bend)}
    lte = loaded_te(tca, flanks, pair, TORQUE_NM, cells=CELLS, bending=bend)
    dt = replace(default_drivetrain(pair), input_damping_ratio=0.3, output_damping_ratio=0.3,
                 mesh_damping_ratio=0.02)
    m = build_model(mesh, dt, TORQUE_NM, backend="table", table=tab["lcp"])
    pitch = mesh.pitch_rad
    res = simulate(m, speed_rpm=60.0, duration_s=2 * pitch / (2 * math.pi), step_s=10e-6)
    c = res.columns
    order = np.arange(len(mesh.psi_rad))[::mesh.motion_sign]
    psi = np.mod(c["psi_p_rad"], pitch)
    rows = np.abs(psi / mesh.step_rad - np.round(psi / mesh.step_rad)) < 0.01
    second = c["t_s"] >= 0.5 * res.summary["duration_s"]
    ref = np.interp(psi, mesh.psi_rad, lte.te_lcp_arcsec[order])
    bound = quasi_static_bound_arcsec(mesh, lte.rotation_lcp_arcsec.mean(),
                                      exponent=1.0 if bending else 2.0 / 3.0)
    assert np.abs(c["te_arcsec"] - ref)[second & rows].max() < bound
    # and the LCP table is not the preview: their TE differ by the LTE's own margin
    assert lte.te_lcp_pp_arcsec != pytest.approx(lte.te_pre_pp_arcsec, rel=1e-3)


def test_table_errors(s0003_twin):
    pair, tca, flanks, mesh = s0003_twin
    with pytest.raises(InputRangeError, match="table source"):
        torque_table(tca, flanks, pair, mesh, TORQUE_NM, source="fem")
    with pytest.raises(InputRangeError, match="ladder"):
        torque_table(tca, flanks, pair, mesh, TORQUE_NM, ladder=(1.0, 0.5))


@pytest.mark.parametrize("share, tol_all, tol_half", [(0.0, 1e-12, 1e-12),
                                                      (0.5, 0.02, 0.004),
                                                      (1.0, 0.05, 0.007)])
def test_table_law_reads_back_a_bent_hertzian_law(share, tol_all, tol_half):
    """The table law (``T^(2/3)`` linear in theta between the rungs of the default
    ladder) read back on the synthetic law ``theta = a T + b T^(2/3)``, ``share`` the
    linear (tooth bending) part of theta at the nominal torque: exact in the Hertzian
    limit (share 0; 1e-12: round-off); for a bending share of 1/2 and in the linear
    limit the chord of ``T^(2/3)`` between rungs gives the relative torque error,
    largest on the widest rung ratio (0.05 -> 0.15, 3x) and small from 0.5x nominal on
    (rung ratios <= 1.5). Tolerances: measured maxima 1.97e-2 / 3.83e-3 (share 1/2) and
    4.84e-2 / 6.81e-3 (linear limit) over 400 torques, rounded up."""
    from gearcontact.twin.contact_law import _table_torque
    from gearcontact.twin.ltca_table import DEFAULT_LADDER

    t0 = 64.5
    rungs = np.asarray(DEFAULT_LADDER) * t0
    a, b = share * 1e-5 / t0, (1.0 - share) * 1e-5 / t0 ** (2.0 / 3.0)   # theta(t0) 1e-5 rad

    def theta(t):
        return a * t + b * t ** (2.0 / 3.0)

    tab_theta = np.tile(theta(rungs), (2, 1))
    tab_t23 = np.tile(rungs ** (2.0 / 3.0), (2, 1))
    torques = np.geomspace(rungs[0], rungs[-1], 400)
    err = np.array([_table_torque(theta(t), 0, 0.0, tab_theta, tab_t23, tab_t23)[0] / t - 1.0
                    for t in torques])
    assert np.abs(err).max() <= tol_all
    assert np.abs(err[torques >= 0.5 * t0]).max() <= tol_half
