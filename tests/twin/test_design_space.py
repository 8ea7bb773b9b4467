"""Issue 28 item 6: ``gearcontact twin --pair FILE --out DIR`` on the design space.

Every pair of tests/design_space.py that ``design`` accepts (both design sides, both
hands) runs the twin with its default options (reference backend, stencil curvatures,
3000 rpm, 64.5 N·m, 50 ms at 10 us, the s0003-scaled drivetrain) to exit 0, and its
files obey truths the twin does not impose on itself:

- the mesh carries the load torque: the mean mesh torque over the whole mesh periods of
  the second half of the run (``twin.csv``; the periods from the run's own mesh
  frequency, counted back from its end) is the set torque within 1 % (the load
  inertia's change of angular momentum over 25 ms: measured at most 2.3e-3 on 12 probe
  pairs) plus twice the standard error of that mean from the scatter of the per-period
  means (:func:`mesh_torque_mean`). A pair whose mesh rattles (contact loss) carries the
  torque in impacts, so a 25 ms mean has a sampling error of its own, and the plain
  second-half mean adds a partial period's impacts: the property test's 15/15 miter
  pair at 25.9 deg (contact loss 34 %) has per-period means scattering by 4.6 N·m (7 %;
  lag-1 correlation -0.14, so twice the standard error is not optimistic), a
  whole-period mean of 64.91 N·m (+0.63 %, bound 2.83 N·m) and a plain second-half
  mean of 65.07 (+0.88 %; with session 14's edge law 65.24, +1.15 %, which failed the
  old 1 % bound; over 150 ms the later windows' means lie within 0.3 %); the 12/12
  pair at 27.7 deg (contact loss 70 %, dynamic factor 12) 64.78 N·m, bound 3.86. A
  quiet pair's per-period means agree to ~0.1 %, so its bound stays 1 % (measured
  0.66-0.77 N·m on the other examples); ``twin.json``'s second-half mean is the set
  torque within the same bound plus one partial mesh period's share of the torque's
  range;
- the normal load's lever about the gear axis at the static operating point
  (``twin.json``: torque / static mesh load) is the mean pitch radius times
  cos(alpha_n) cos(beta_m2) of ISO 10300-1 (F_n = F_mt / (cos alpha_n cos beta_m))
  within 5 %: the TCA's mean contact lies off the mean pitch point by a few per cent of
  the cone distance (measured 0-3.6 % on 12 probe pairs; along the path, row by row,
  the lever follows the contact from toe to heel, +-20 % on the widest faces);
- the pinion turns at the set speed (mean within 1e-3; measured at most 2.5e-5) and
  the gear at the pinion speed / u on the mean (1e-3: the TE change over the run's
  duration bounds the difference; measured at most 7.4e-6);
- the mesh frequency is z1 n / 60; no value of ``twin.csv`` is NaN, every preview had
  a contact law.

An approaching pair that touches first at a flank edge (issue 28, :data:`CHATTER_PAIR`):
the twin's mesh is the edge-contact TCA of ``analyze`` (docs/twin.md "Edge contact"), so

- its unloaded TE envelope (``mesh.csv``) is ``analyze``'s TE0: on CHATTER_PAIR's drive
  side (61 phases) p-p 8.670 arcsec, the pinion's root edge carrying 18 of the 61 rows
  (measured with ``gearcontact analyze`` / ``tca.analysis.analyze_pair``; the former
  surface-only TCA had 24.07 arcsec, the twin's envelope 19.30 after its posed-field
  first touch), within 0.01 arcsec (the same TCA; its envelope is not moved by a
  posed-field pair);
- at 3000 rpm the mesh stays closed: the mesh frequency (350 Hz) is twice the first
  elastic mode (175 Hz), where a linear mesh's deflection answers a TE excitation of
  amplitude e with at most r^2 / (r^2 - 1) e = 4/3 e (r = 2; higher mesh orders less),
  i.e. +-5.8 arcsec for the 8.7 arcsec p-p, below the mesh rotation under the static
  load (11.8 arcsec): contact loss 0 (measured 0, the rotation swinging 7.0-18.4
  arcsec; before 10.4 %, dynamic factor 2.94, with the 19.3-arcsec surface-only
  envelope), and the mean mesh torque is the set torque within 1 % as above (measured
  +0.09 %; before -1.12 %).

Cost (2 shared cores, warm numba cache): 15-60 s per twin with default options (two
TCAs of 61 phases: the loaded side and the reverse flank). The default test runs one
pair, the slow one eight random accepted pairs (both hands), every option at its
default, and CHATTER_PAIR at 3000 rpm (about 50 s).
"""

import csv
import json
import math
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings

from design_space import CHATTER_PAIR, HANDS, MITER_PAIR, SPACE, command_on_accepted_pair

#: The twin's defaults the checks use (gearcontact.cli.twin).
SPEED_RPM, TORQUE_NM = 3000.0, 64.5


def _twin_accepted_pair(phases, *point):
    options = () if phases is None else ("--phases", str(phases))
    with command_on_accepted_pair("twin", point, options=options) as (pair, run, out):
        assert run.returncode == 0, run.stderr
        check_twin_outputs(out, pair)


def check_twin_outputs(out: Path, pair):
    """The truths of the module docstring on a twin run's files in ``out``."""
    s = json.loads((out / "twin.json").read_text())
    with (out / "twin.csv").open(newline="") as f:
        rows = list(csv.DictReader(f))
    c = {k: np.array([float(r[k]) for r in rows]) for k in rows[0]}
    assert all(np.all(np.isfinite(v)) for v in c.values())
    assert s["previews_without_contact_law"] == 0
    assert s["speed_rpm"] == SPEED_RPM and s["torque_nm"] == TORQUE_NM
    assert s["mesh_frequency_hz"] == pytest.approx(pair.pinion_teeth * SPEED_RPM / 60.0,
                                                   rel=1e-12)
    # the mesh carries the load torque on the mean of the second half's whole periods
    mean, bound, partial = mesh_torque_mean(c["t_s"], c["mesh_torque_nm"],
                                            s["mesh_frequency_hz"], 0.5 * s["duration_s"])
    print(f"mean mesh torque over whole periods {mean:.3f} N·m (bound {bound:.3f}), "
          f"second half {s['mean_mesh_torque_nm']:.3f}, dynamic factor "
          f"{s['dynamic_factor']:.3f}, contact loss {s['contact_loss']:.3f}")
    assert abs(mean - TORQUE_NM) <= bound
    assert abs(s["mean_mesh_torque_nm"] - TORQUE_NM) <= bound + partial
    # the lever of the normal load: ISO 10300-1's r_m2 cos(alpha_n) cos(beta_m2)
    b = pair.blank
    alpha = b.pressure_angle_drive_deg if s["side"] == "drive" else b.pressure_angle_coast_deg
    lever = (b.mean_pitch_radius_gear_mm * math.cos(math.radians(alpha))
             * math.cos(math.radians(b.spiral_angle_gear_deg)))
    assert 1e3 * TORQUE_NM / s["static_mesh_load_n"] == pytest.approx(lever, rel=0.05)
    # speeds: the pinion at the set speed, the gear at the pinion speed / u (means)
    w = SPEED_RPM * 2.0 * math.pi / 60.0
    assert c["pinion_speed_rad_s"].mean() == pytest.approx(w, rel=1e-3)
    u = pair.gear_teeth / pair.pinion_teeth
    assert u * c["gear_speed_rad_s"].mean() == pytest.approx(c["pinion_speed_rad_s"].mean(),
                                                             rel=1e-3)


def mesh_torque_mean(t_s, torque_nm, mesh_frequency_hz: float, start_s: float):
    """``(mean, bound, partial)`` of the mesh torque over the whole mesh periods from
    ``start_s`` to the end of the record (N·m; module docstring): ``bound`` = 1 % of the
    set torque + twice the standard error of the mean from the per-period means' scatter,
    ``partial`` = the range of the torque times the share of the rest (the part of a
    period before the first whole one) in the time from ``start_s``."""
    step = t_s[1] - t_s[0]
    end = t_s[-1] + step                # rows are the states at the steps' starts
    n = int((end - start_s) * mesh_frequency_hz)
    edges = end - np.arange(n, -1, -1) / mesh_frequency_hz
    at = np.searchsorted(t_s, edges - 0.5 * step)
    means = np.array([torque_nm[a:b].mean() for a, b in zip(at[:-1], at[1:])])
    bound = 0.01 * TORQUE_NM + 2.0 * means.std(ddof=1) / np.sqrt(n)
    rest = (end - start_s - n / mesh_frequency_hz) / (end - start_s)
    return float(means.mean()), float(bound), float(rest * np.ptp(torque_nm))


#: 7/70 teeth, offset 0.49 r2 (the ISO 23509 limit is 0.5 r2), 50 deg: the drive
#: path of a neighbouring pair folds back in phi1 near the pinion root, which stopped
#: this twin's surface TCA with exit 4 (tests/tca/test_solve.py).
FOLDING_PAIR = (7, 10.0, 0.49, 50.0, 0.3, "drive", "right")


def test_twin_default_options_on_a_folding_pair():
    _twin_accepted_pair(None, *FOLDING_PAIR)


#: 9/9 spiral bevel, 55 deg, face 0.1933 R_m, designed for coast, left hand: found by the
#: slow property test (session 17's audit). ``design`` checks the contact ratio of the
#: design side; the drive flanks' unloaded mesh has a gap (no pair in contact at phi1 =
#: -11.54 deg), so the reverse flank's TCA raised ContactGap after the loaded side's
#: table was built: exit 2 after the work. The reverse flank now takes the loaded side's
#: law mirrored about the backlash, as for a reverse side in line contact, and says so.
REVERSE_GAP_PAIR = (9, 1.0, 0.0, 55.0, 0.19328974711495756, "coast", "left")


@pytest.mark.slow
def test_twin_runs_a_pair_whose_reverse_flanks_have_a_gap():
    """Exit 0 and the module docstring's truths (measured: dynamic factor 2.52, contact
    loss 7.0 %, mean mesh torque 64.67 N·m; about 30 s CPU); ``twin.json`` names the
    gap of the drive flanks as the reason for the mirrored reverse law."""
    with command_on_accepted_pair("twin", REVERSE_GAP_PAIR, options=("--no-figures",)) as (
            pair, run, out):
        assert run.returncode == 0, run.stderr
        check_twin_outputs(out, pair)
        s = json.loads((out / "twin.json").read_text())
    assert s["reverse_flank"].startswith("loaded side's law mirrored about backlash_mm: "
                                         "the drive flanks' unloaded mesh has a gap")


# CHATTER_PAIR (tests/design_space.py): 7/60 teeth, offset 0.0436 r2, 25 deg, face
# 0.32 R_m: found by the slow property test
# (mean mesh torque 63.41 N·m at 3000 rpm, dynamic factor 4.18, contact loss 11.5 %;
# after the first-touch fix 63.78 N·m, 2.94, 10.4 %; with the edge-contact TCA 64.56
# N·m, 1.26, 0).
# Its drive paths end at the pinion root/toe, and the next pair, resolved as an edge
# pair on its posed field, touches up to 6.9 um before the surface envelope's pair
# (twin.mesh._first_touch): pre-loaded off the envelope, it pushed the gear at no cost
# to the pinion, and the run lost contact and hammered even at 100 rpm.


@pytest.mark.slow
def test_quasi_static_twin_keeps_contact():
    # 100 rpm: mesh 11.7 Hz, 15 times below the first elastic mode (174 Hz), so the run
    # is quasi-static (250 ms: the second half, which twin.json sums up, holds the edge
    # pair's phase at 2.2 pitches): the load never leaves the flanks and the mesh torque
    # stays within the loaded TE's own variation of the static torque (measured:
    # dynamic factor 1.014 with the twin's edge-contact TCA; 1.047 with the surface-only
    # one after the first-touch fix, 1.045 with exact curvatures; before that fix 3.48
    # with 2.9 % contact loss, with a 2 us step too; bound 1.1)
    with command_on_accepted_pair("twin", CHATTER_PAIR, options=(
            "--speed-rpm", "100", "--duration-ms", "250", "--no-figures")) as (_, run, out):
        assert run.returncode == 0, run.stderr
        s = json.loads((out / "twin.json").read_text())
    assert s["contact_loss"] == 0.0
    assert s["dynamic_factor"] < 1.1


#: analyze's edge-contact TCA of CHATTER_PAIR (drive, 61 phases): TE0 p-p (arcsec) and
#: the rows whose transmitting contact is the pinion's root edge (module docstring).
CHATTER_TE0_PP_ARCSEC, CHATTER_EDGE_ROWS = 8.670, 18


@pytest.mark.slow
def test_edge_contact_pair_keeps_contact_at_3000_rpm():
    with command_on_accepted_pair("twin", CHATTER_PAIR, options=("--no-figures",)) as (
            pair, run, out):
        assert run.returncode == 0, run.stderr
        check_twin_outputs(out, pair)       # the mean mesh torque within 1 %
        s = json.loads((out / "twin.json").read_text())
        with (out / "mesh.csv").open(newline="") as f:
            rows = list(csv.DictReader(f))
    te0 = {int(r["row"]): float(r["te0_arcsec"]) for r in rows}
    assert np.ptp(list(te0.values())) == pytest.approx(CHATTER_TE0_PP_ARCSEC, abs=0.01)
    carrying = {int(r["row"]) for r in rows if float(r["opening_um"]) == 0.0
                and r["mode"] == "edge" and r["edge"] == "pinion root"}
    assert len(carrying) == CHATTER_EDGE_ROWS == s["transmitting_edge_phases"]
    assert s["mesh_edge_rows"]["pinion root"] >= CHATTER_EDGE_ROWS
    assert s["contact_loss"] == 0.0


@pytest.mark.slow
@settings(max_examples=8, deadline=None, derandomize=True, database=None,
          suppress_health_check=[HealthCheck.filter_too_much, HealthCheck.too_slow])
@given(**SPACE, hand=HANDS)
def test_accepted_pairs_run_twin_default_options_slow(z1, ratio, offset_frac, beta, face_frac,
                                                      side, hand):
    _twin_accepted_pair(None, z1, ratio, offset_frac, beta, face_frac, side, hand)


@pytest.mark.slow
def test_rattling_miter_pair_carries_the_torque():
    """MITER_PAIR (tests/design_space.py) with default options: its mesh rattles at 3000
    rpm (one pair carries over most of the pitch and hands over through edge rows; the
    mesh frequency 750 Hz is 3.7 times the first elastic mode) and still carries the set
    torque on the mean of whole mesh periods within the bound from its own scatter
    (module docstring; measured: contact loss 19.3 %, dynamic factor 2.90, per-period
    means 64.0-65.4 N·m, their mean 64.70 N·m, bound 0.83; with session 14's edge law
    42.3 %, 5.69 and 65.04 N·m, bound 2.56). About 2 min."""
    with command_on_accepted_pair("twin", MITER_PAIR, options=("--no-figures",)) as (
            pair, run, out):
        assert run.returncode == 0, run.stderr
        check_twin_outputs(out, pair)
        s = json.loads((out / "twin.json").read_text())
    assert s["contact_loss"] > 0.0


#: The slow property test's 12/12 draw (docs/twin.md "The 12/12 pair"): TE0 46-48 arcsec
#: p-p, one pair carrying over the whole pitch.
RATTLING_12_PAIR = (12, 1.0, 0.0, 27.74456822895699, 0.1893217700722522, "drive", "left")


@pytest.mark.slow
def test_rattle_of_the_12_pair_is_the_pairs_not_the_edge_laws():
    """`twin --speed-sweep` on the 12/12 pair stopped with exit 4 (the LCP table's loaded
    TE at T/20 did not converge at the hand-over; ltca.mesh_lcp now retries from the
    cold start, tests/ltca/test_mesh_lcp.py). Now it runs, and the table twin, whose law
    is the LCP's loaded TE (no Hertzian rows, no edge-law scales), also loses contact
    over 2500-3500 rpm: the rattle is the pair's unloaded TE (docs/twin.md). Measured
    (session 16): contact loss reference 0.70 / 0.74 / 0.67, table 0.51 / 0.42 / 0.63;
    bound: more than 0.2 at every speed for both (half the least measured). About 30 s
    CPU."""
    with command_on_accepted_pair("twin", RATTLING_12_PAIR, options=(
            "--speed-sweep", "2500:3500:500", "--workers", "1", "--no-figures")) as (
            _, run, out):
        assert run.returncode == 0, run.stderr
        with (out / "sweep.csv").open(newline="") as f:
            rows = list(csv.DictReader(f))
    assert [float(r["speed_rpm"]) for r in rows] == [2500.0, 3000.0, 3500.0]
    for r in rows:
        assert float(r["reference_contact_loss"]) > 0.2
        assert float(r["table_contact_loss"]) > 0.2
