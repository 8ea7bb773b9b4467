"""The derived blade curvature as `design` writes it (geometry.written_blade;
docs/machine_settings.md sec. 5, "The blade curvature written").

The finding (session 26, careless; reproduced here): a gear typed alone with a curved
blade whose radius is the standard crowning's, typed to 4 decimals (728.7113 mm: the
published pair's pinion radius 728.7113339..., a careless copy), gets a standard pinion
whose blade curvature is the mate's -1/728.7113 plus the crowning's +1/728.71133...: a
sum of 6.4e-11 1/mm, written `profile_radius_mm = -15647690833.2` (measured). The same
sum arises in the local synthesis (the mate plus the searched blade curvature).

Truths:
- a circular blade departs from its tangent at the reference point by
  (1 - cos(k s)) / k <= |k| s^2 / 2 at the arc distance s (geometry);
- the flank a blade generates is the boundary of the volume the blade sweeps; two blades
  within d of each other sweep volumes within d, so their flanks are within d along the
  normal (the envelope nodes' own residual, 1e-9 mm or less, added);
- the TOML the writer produces reads back to the same settings, bit for bit (17 digits).
"""

import dataclasses
from pathlib import Path

import numpy as np
import pytest

from gearcontact.geometry.blade import blade_profile
from gearcontact.geometry.generated import generated_pinion_flank
from gearcontact.geometry.pair import load_pair, pair_to_toml
from gearcontact.geometry.typed_pinion import typed_gear_cut
from gearcontact.geometry.written_blade import (GRINDABLE_DEVIATION_MM, STRAIGHT_DEVIATION_MM,
                                                profile_deviation_mm, straight_blade,
                                                working_length_mm, written_pair)

SHEETS = Path(__file__).resolve().parent / "summary_sheets"


def _gear_alone(tmp_path, radius: str) -> Path:
    """The published pair's blank with its gear page's tables typed alone, each gear
    blade given ``profile_radius_mm = radius``."""
    pair = (SHEETS / "hypoid_10x41_no16_pair.toml").read_text()
    head = pair[:pair.index("\n[print.gear]") + 1]
    gear = (SHEETS / "hypoid_10x41_no16_gear.toml").read_text()
    tables = gear[gear.index("[machine.gear.drive]"):]
    tables = tables.replace("edge_radius_mm = 1.016\n",
                            f"edge_radius_mm = 1.016\nprofile_radius_mm = {radius}\n")
    path = tmp_path / f"gear_{radius}.toml"
    path.write_text(head + tables)
    return path


def _cut(path):
    pair = load_pair(path, gear_alone=True)
    gear = {s.side: s for s in pair.typed_gear}
    blank = dataclasses.replace(pair, machine=(), typed_gear=())
    return typed_gear_cut(blank, gear)[0]


@pytest.fixture(scope="module")
def cancelled(tmp_path_factory):
    """The standard pinion of the gear whose curved blade cancels the crowning."""
    return _cut(_gear_alone(tmp_path_factory.mktemp("wb"), "728.7113"))


def test_a_cancelled_curvature_is_written_straight_and_reads_back(cancelled, tmp_path):
    pinion = {s.side: s for s in cancelled.machine if s.member == "pinion"}
    # the finding reproduced: a radius of 1e10 mm, a departure of 1e-11 mm
    assert all(abs(s.blade.profile_radius_mm) > 1e9 for s in pinion.values())
    written, notes = written_pair(cancelled)
    assert len(notes) == 2 and all("written straight (0)" in n for n in notes)
    path = tmp_path / "machine_settings.toml"
    path.write_text(pair_to_toml(written))
    assert "profile_radius_mm = 0.0" in path.read_text()
    back = {s.side: s for s in load_pair(path).machine if s.member == "pinion"}
    ours = {s.side: s for s in written.machine if s.member == "pinion"}
    for side, derived in pinion.items():
        assert back[side].blade == ours[side].blade        # read back bit for bit
        assert back[side].blade.profile_radius_mm == 0.0
        assert back[side].settings == derived.settings      # only the blade changes
        # the blade: the straight one within the bound of the derived circular one over
        # the working length (exact geometry: |k| s^2 / 2 <= STRAIGHT_DEVIATION_MM)
        length = working_length_mm(cancelled, derived.blade)
        l_ref = derived.blade.profile_reference_mm
        ls = np.linspace(max(l_ref - length, 0.0), l_ref + length, 201)
        rho_d, z_d, alpha_d, _ = blade_profile(derived.blade, ls)
        rho_w, z_w, alpha_w, _ = blade_profile(back[side].blade, ls)
        # distance from each derived point to the written straight line, along the
        # line's normal (cos alpha, sigma sin alpha) in the (rho, z) half-plane
        a = float(alpha_w[0])
        gap = (np.asarray(rho_d) - rho_w[0]) * np.cos(a) \
            + derived.blade.sigma * (np.asarray(z_d) - z_w[0]) * np.sin(a)
        dev = profile_deviation_mm(derived.blade, length)     # measured 1.1e-8 mm
        assert dev < STRAIGHT_DEVIATION_MM
        assert np.max(np.abs(gap)) <= dev
        # the flank: the nodes of the two generated flanks within the blade's departure
        # along the normal (swept volumes within d), plus 1e-9 mm for the nodes' own
        # solves (residuals measured 6e-14 mm); measured 1.7e-9 / 1.6e-9 mm
        f_d = generated_pinion_flank(derived, cancelled.blank, n_u=9, n_v=11,
                                     pinion_face_width_mm=cancelled.pinion_face_width_mm)[1]
        f_w = generated_pinion_flank(back[side], cancelled.blank, n_u=9, n_v=11,
                                     pinion_face_width_mm=cancelled.pinion_face_width_mm)[1]
        assert f_d.converged.all() and f_w.converged.all()
        normal_gap = np.einsum("...i,...i", f_w.x_mm - f_d.x_mm, f_d.n)
        assert np.max(np.abs(normal_gap)) <= dev + 1e-9, \
            np.max(np.abs(normal_gap))


def test_the_threshold_is_the_departure_over_the_working_length(cancelled):
    """The bands of the module docstring on one derived blade, its radius scaled: the
    straight blade's departure is |k| L^2 / 2 (a real curvature is never straightened:
    a radius of 1e5 mm departs 1.7 um over the 18.6 mm working length)."""
    blade = next(s.blade for s in cancelled.machine if s.member == "pinion")
    length = working_length_mm(cancelled, blade)
    for radius, band in ((0.5 * length ** 2 / (0.5 * STRAIGHT_DEVIATION_MM), "straight"),
                         (0.5 * length ** 2 / (2.0 * STRAIGHT_DEVIATION_MM), "named"),
                         (0.5 * length ** 2 / (0.5 * GRINDABLE_DEVIATION_MM), "named"),
                         (0.5 * length ** 2 / (2.0 * GRINDABLE_DEVIATION_MM), "silent"),
                         (1e5, "silent"), (-1e5, "silent")):
        b = dataclasses.replace(blade, profile_radius_mm=radius)
        dev = profile_deviation_mm(b, length)
        pair = dataclasses.replace(cancelled, machine=tuple(
            dataclasses.replace(s, blade=b) if s.member == "pinion" else s
            for s in cancelled.machine))
        written, notes = written_pair(pair)
        radii = [s.blade.profile_radius_mm for s in written.machine if s.member == "pinion"]
        if band == "straight":
            assert dev < STRAIGHT_DEVIATION_MM and radii == [0.0, 0.0]
            assert all("written straight" in n for n in notes)
        elif band == "named":
            assert radii == [radius, radius] and len(notes) == 2
            assert all("kept as computed" in n for n in notes)
        else:
            assert radii == [radius, radius] and notes == []


def test_the_straight_blade_is_the_tangent_at_the_reference(cancelled):
    """Same point and same profile angle at the reference point (to rounding, 1e-12 mm /
    1e-12 rad: blade_through_point's root solve is to 1e-14 mm)."""
    blade = next(s.blade for s in cancelled.machine if s.member == "pinion")
    b = dataclasses.replace(blade, profile_radius_mm=400.0)
    s = straight_blade(b)
    rho, z, alpha, _ = blade_profile(b, b.profile_reference_mm)
    rho_s, z_s, alpha_s, _ = blade_profile(s, s.profile_reference_mm)
    assert abs(rho - rho_s) < 1e-12 and abs(z - z_s) < 1e-12
    assert abs(alpha - alpha_s) < 1e-12


def test_a_fitted_profile_of_rounding_is_written_straight(cancelled):
    """The ease-off fit of a side with nothing to fit (s0003's drive, its ease-off table
    all zero; session 28's audit): radius -1.04e10 mm and cubic 1.1e-10 1/mm^2, written
    as a curved blade. Truths: the departure bound |k| L^2 / 2 + |c_3| L^3 / 6 holds
    against the profile computed by quadrature (blade_profile's, 1e-12 mm: the bound is
    |sin x| <= |x| integrated, so no margin is needed beyond rounding); below 1 nm the
    blade is written straight, every term 0, the tangent at the reference (1e-12 mm /
    rad); the note names both keys."""
    setup = next(s for s in cancelled.machine if s.member == "pinion")
    fitted = dataclasses.replace(setup.blade, profile_radius_mm=-10433548259.72101,
                                 profile_cubic_per_mm2=1.1186337251482102e-10)
    length = working_length_mm(cancelled, fitted)
    dev = profile_deviation_mm(fitted, length)
    assert dev == pytest.approx(0.5 * length ** 2 / 10433548259.72101
                                + 1.1186337251482102e-10 * length ** 3 / 6.0, rel=1e-15)
    assert dev < STRAIGHT_DEVIATION_MM
    pair = dataclasses.replace(cancelled, machine=tuple(
        dataclasses.replace(s, blade=fitted) if s is setup else s for s in cancelled.machine))
    written, notes = written_pair(pair)
    blade = next(s.blade for s in written.machine if (s.member, s.side) ==
                 (setup.member, setup.side))
    assert (blade.profile_radius_mm, blade.profile_cubic_per_mm2,
            blade.profile_quartic_per_mm3) == (0.0, 0.0, 0.0)
    assert any(n.startswith(f"blade.pinion.{setup.side}.profile_radius_mm / "
                            "profile_cubic_per_mm2: the derived profile (radius -1.04e+10 mm, "
                            "cubic 1.12e-10 1/mm^2) departs") and "written straight" in n
               for n in notes), notes
    rho, z, alpha, _ = blade_profile(fitted, fitted.profile_reference_mm)
    rho_s, z_s, alpha_s, _ = blade_profile(blade, blade.profile_reference_mm)
    assert abs(rho - rho_s) < 1e-12 and abs(z - z_s) < 1e-12 and abs(alpha - alpha_s) < 1e-12


def test_the_higher_order_bound_holds_against_the_profile(cancelled):
    """The departure bound of a cubic and a quartic term large enough to be seen
    (c_3 = 1e-4 1/mm^2, c_4 = -2e-5 1/mm^3): the straight tangent's distance to the
    quadrature profile over the working length is within the bound (+1e-12 mm of
    rounding) for each term alone and for both; a term alone reaches its bound at the
    far end s = L to within 1 % (the bound is |sin x| <= |x| integrated and the angle
    stays below 0.05 rad, so the first-order loss is below 1e-3)."""
    blade = next(s.blade for s in cancelled.machine if s.member == "pinion")
    for c3, c4, tight in ((1e-4, 0.0, True), (0.0, -2e-5, True), (1e-4, -2e-5, False)):
        b = dataclasses.replace(blade, profile_radius_mm=0.0, profile_cubic_per_mm2=c3,
                                profile_quartic_per_mm3=c4)
        length = working_length_mm(cancelled, b)
        s_ref = b.profile_reference_mm
        ls = np.linspace(s_ref, s_ref + length, 401)
        rho, z, _, _ = blade_profile(b, ls)
        rho0, z0, a0, _ = blade_profile(b, s_ref)
        gap = np.abs((np.asarray(rho) - rho0) * np.cos(a0)
                     + b.sigma * (np.asarray(z) - z0) * np.sin(a0))
        dev = profile_deviation_mm(b, length)
        assert np.max(gap) <= dev + 1e-12, (c3, c4)
        if tight:
            assert gap[-1] >= 0.99 * dev, (c3, c4, gap[-1], dev)


@pytest.mark.slow
def test_design_writes_the_cancelled_curvature_straight(tmp_path):
    """Through the console script (~1 min at load 16): `design --machine-settings` on
    the gear typed alone writes the pinion blades straight and names them in the head
    comment; the file reads back (exit 0)."""
    from console_script import run_console

    out = tmp_path / "out"
    code, _, err = run_console("design", "--pair", _gear_alone(tmp_path, "728.7113"),
                               "--machine-settings", "--out", out)
    assert code == 0, err
    text = (out / "machine_settings.toml").read_text()
    radii = [float(line.split("=")[1]) for line in text.splitlines()
             if line.startswith("profile_radius_mm")]
    assert radii and all(abs(r) < 1e4 for r in radii), radii     # the gear's 728.7113 kept
    for side in ("drive", "coast"):
        assert f"# blade.pinion.{side}.profile_radius_mm: the derived radius -1.56e+10 mm" \
            in text
    back = load_pair(out / "machine_settings.toml")
    assert all(s.blade.profile_radius_mm == 0.0 for s in back.machine if s.member == "pinion")
