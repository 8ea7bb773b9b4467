"""``gearcontact export fmu`` on a cylindrical pair (the EV reducer's helical stage): the
mesh FMU against the twin's line law, the drivetrain FMU against ``gearcontact twin``.

Truth: the twin's own compiled line law (:func:`gearcontact.twin.line_law._line_law`,
the numba code ``gearcontact twin`` runs on a cylindrical pair) evaluated by
:func:`gearcontact.export.line_mesh_law.line_mesh_outputs` at the very inputs FMPy fed
the FMU, on the table the export baked in; for the drivetrain FMU the twin's own run
(:func:`gearcontact.twin.simulate.simulate` on :func:`gearcontact.twin.cylindrical.
cylindrical_model`, the model ``gearcontact twin`` builds); FMPy's FMI 3.0 schema
validation. Exported the way a user does (a subprocess of ``python -m gearcontact``),
7 phases per pitch to keep the tables small (~10 s per export).
"""

from __future__ import annotations

import zipfile
from pathlib import Path

import numpy as np
import pytest

fmpy = pytest.importorskip("fmpy")
from fmpy.validation import validate_fmu  # noqa: E402

from gearcontact.export.line_mesh_law import LineMeshTable, line_mesh_outputs  # noqa: E402
from gearcontact.export.mesh_law import BACKENDS  # noqa: E402

from .conftest import export_fmu_cli as _cli  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
EV = ROOT / "examples" / "ev_reducer_helical_23x67.toml"
NAME = "ev_reducer_helical_23x67"
TORQUE_NM = 200.0
OUTPUTS = ("torque_pinion_nm", "torque_gear_nm", "mesh_force_n", "te_arcsec", "p_max_mpa",
           "a_mm", "b_mm", "active_pairs")
INPUTS = ("phi_pinion_rad", "phi_gear_rad", "omega_pinion_rad_s", "omega_gear_rad_s")


@pytest.fixture(scope="module")
def mesh_fmu(tmp_path_factory):
    out = tmp_path_factory.mktemp("cyl_fmu") / "mesh"
    run = _cli("--pair", str(EV), "--kind", "mesh", "--phases", "7", "--torque",
               str(TORQUE_NM), "--out", str(out), cwd=out.parent)
    assert run.returncode == 0, run.stderr
    return (out / f"gearcontact_mesh_{NAME}.fmu",
            LineMeshTable.from_npz(out / f"gearcontact_mesh_{NAME}_table.npz"))


def _signal(tab):
    """Constant pinion speed over two pinion pitches; the gear lags by theta(t) from
    -2e-5 rad (flanks open) to 2.8e-4 rad (~4x the export torque's rotation), its speed
    the derivative of its angle."""
    t = np.linspace(0.0, 0.02, 401)
    wp = 2.0 * tab.pitch_rad / 0.02
    theta = -2e-5 + 3e-4 * t / 0.02
    sig = np.zeros(t.size, dtype=[("time", float)] + [(n, float) for n in INPUTS])
    sig["time"], sig["phi_pinion_rad"] = t, wp * t
    sig["phi_gear_rad"] = wp * t / tab.ratio - theta
    sig["omega_pinion_rad_s"], sig["omega_gear_rad_s"] = wp, wp / tab.ratio - 3e-4 / 0.02
    return sig


def test_mesh_fmu_validates_against_the_fmi3_schema(mesh_fmu):
    fmu, _ = mesh_fmu
    assert validate_fmu(str(fmu)) == []
    names = set(zipfile.ZipFile(fmu).namelist())
    assert {"sources/gc_line_law.c", "sources/gc_line_law.h", "sources/gc_mesh_fmu.c",
            f"binaries/x86_64-linux/gearcontact_mesh_{NAME}.so"} <= names
    md = fmpy.read_model_description(str(fmu))
    assert md.fmiVersion == "3.0" and md.coSimulation and md.modelExchange
    assert "line law" in md.description


@pytest.mark.parametrize("fmi_type", ["CoSimulation", "ModelExchange"])
@pytest.mark.parametrize("backend", ["fp64", "golden"])
def test_mesh_fmu_equals_the_twin_line_law(mesh_fmu, backend, fmi_type):
    """Every output at every recorded instant equals the Python law at the inputs the
    FMU held then: fp64 within 1e-9 relative (the same operations in the same order;
    the bound leaves room for another libm's log/pow/sqrt by a few ulp, amplified by the
    slice law's Newton and by the cancellation in theta = psi_p/u + eps - psi_g, ~1e5
    at these angles: <= 1e-10), golden identical (integer line chain, then the same fp64
    operations). Measured: identical in both backends and both interfaces."""
    fmu, tab = mesh_fmu
    res = fmpy.simulate_fmu(str(fmu), fmi_type=fmi_type, start_time=0.0, stop_time=0.02,
                            output_interval=5e-5, input=_signal(tab),
                            output=list(INPUTS + OUTPUTS),
                            start_values={"backend": BACKENDS[backend]})
    assert len(res) == 401
    loaded = 0
    for row in res:
        ref = line_mesh_outputs(tab, *(float(row[n]) for n in INPUTS), backend=backend)
        for name in OUTPUTS:
            got, want = float(row[name]), float(getattr(ref, name))
            if backend == "golden":
                assert got == want, (name, float(row["time"]))
            else:
                assert got == pytest.approx(want, rel=1e-9, abs=0.0), name
        loaded += ref.torque_gear_nm > 0.0
    # the sweep covers open flanks, several pairs and beyond the export torque
    assert res["torque_gear_nm"][0] == 0.0 and res["active_pairs"][0] == 0
    assert 0 < loaded < len(res) and res["active_pairs"].max() >= 3
    assert res["torque_gear_nm"].max() > TORQUE_NM


def test_mesh_law_runs_the_line_and_the_edge_slices(mesh_fmu):
    """The sweep's law is the line law (line mode, a loaded length below the line's on
    the crowned and relieved flanks) and the table carries the edge slices beyond the
    helical lines' ends with a positive effective width: the port is exercised where
    the cylindrical law differs from the bevel one."""
    from gearcontact.export.line_mesh_law import _LAWS

    _, tab = mesh_fmu
    assert tab.slices == 16 and tab.beyond > 0 and tab.beyond_width_mm > 0.0
    line_mesh_outputs(tab, 0.3 * tab.pitch_rad, 0.3 * tab.pitch_rad / tab.ratio - 1e-4,
                      0.0, 0.0, backend="fp64")
    law = _LAWS[id(tab)][1]
    i = int(0.3 * tab.pitch_rad / tab.step_rad)
    j = int(np.flatnonzero(tab.valid[:, i] & tab.valid[:, i + 1])[0])
    lam, pv = law.law(j, i, 0.0, 5e-3, 0)
    assert lam > 0.0 and pv[3] == 1.0           # line mode
    assert 0.0 < 2.0 * pv[0] < tab.line_rows[j, i, 52]     # L_c = 2 a below the line's L


def test_cylindrical_fmu_refuses_bending(tmp_path):
    """--bending (the twin's series bending along the line) is not ported: refused
    before any work, naming the option (exit 2)."""
    run = _cli("--pair", str(EV), "--kind", "mesh", "--bending", "--out",
               str(tmp_path / "o"), cwd=tmp_path)
    assert run.returncode == 2
    assert "--bending" in run.stderr and "cylindrical" in run.stderr
    assert not (tmp_path / "o").exists()

