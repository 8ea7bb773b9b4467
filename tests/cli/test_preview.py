"""``gearcontact preview`` end to end through the console entry point."""

import json

import numpy as np
import pytest

from gearcontact.analytic.hertz import hamrock_brewe_hertz
from gearcontact.cli import main
from gearcontact.contract.stencil import stencil_coordinates, write_stencil_csv


def _run(capsys, *argv):
    code = main(list(argv))
    out = capsys.readouterr()
    return code, out.out, out.err


@pytest.mark.parametrize("backend", ["reference", "golden"])
def test_json_keys_and_values(capsys, backend):
    code, out, _ = _run(capsys, "preview", "--curvatures", "0.25", "0.005", "--load", "1971",
                        "--backend", backend, "--json")
    assert code == 0
    d = json.loads(out)
    assert {"a_mm", "b_mm", "k", "p_max_mpa", "backend"} <= set(d)
    assert d["backend"] == backend
    hb = hamrock_brewe_hertz(0.25, 0.005, 1971.0, e_prime_mpa=209000 / (1 - 0.09))
    # reference: same closed form; golden: within its 0.5 % acceptance bound
    assert d["p_max_mpa"] == pytest.approx(hb.p_max_mpa, rel=1e-12 if backend == "reference" else 5e-3)
    if backend == "golden":
        assert d["cycles"] == 756 and d["flags"] == [] and d["codes"]["p_max"] > 0


def test_text_output_shows_codes_for_golden(capsys):
    code, out, _ = _run(capsys, "preview", "--curvatures", "0.25", "0.005", "--load", "1971",
                        "--backend", "golden")
    assert code == 0
    assert "p_max" in out and "codes" in out and "cycles         756" in out


def test_modulus_option(capsys):
    code, out, _ = _run(capsys, "preview", "--curvatures", "0.1", "0.01", "--load", "100",
                        "--modulus", "110", "--poisson", "0.34", "--json")
    hb = hamrock_brewe_hertz(0.1, 0.01, 100.0, e_prime_mpa=110000 / (1 - 0.34 ** 2))
    assert json.loads(out)["p_max_mpa"] == pytest.approx(hb.p_max_mpa, rel=1e-12)


@pytest.mark.parametrize("argv,needle", [
    (["--curvatures", "0.25", "0", "--load", "10"], "B_minus"),
    (["--curvatures", "0.25", "0.01", "--load", "-1"], "load_n"),
    (["--curvatures", "0.25", "0.01", "--load", "1e9", "--backend", "golden"], "load_n"),
    (["--curvatures", "0.25", "0.01", "--load", "10", "--poisson", "0.6"], "poisson"),
])
def test_bad_input_one_line_error(capsys, argv, needle):
    code, out, err = _run(capsys, "preview", *argv)
    assert code == 2
    assert needle in err and "Traceback" not in err


def test_stencil_file(tmp_path, capsys):
    s, t = stencil_coordinates()
    path = write_stencil_csv(tmp_path / "st.csv", 0.002 + 0.2 * s ** 2 + 0.01 * t ** 2)
    code, out, _ = _run(capsys, "preview", "--stencil", str(path), "--load", "500", "--json")
    d = json.loads(out)
    assert code == 0
    assert d["A_minus_per_mm"] == pytest.approx(0.2, rel=1e-9)
    assert d["B_minus_per_mm"] == pytest.approx(0.01, rel=1e-9)
    code, out, _ = _run(capsys, "preview", "--stencil", str(path), "--load", "500",
                        "--backend", "golden", "--json")
    assert code == 0 and json.loads(out)["cycles"] == 806


def test_stencil_file_wrong_length(tmp_path, capsys):
    path = tmp_path / "short.csv"
    s, t = stencil_coordinates()
    rows = ["s_mm,t_mm,gap_mm"] + [f"{a},{b},0.1" for a, b in zip(s[:48], t[:48])]
    path.write_text("\n".join(rows) + "\n")
    code, _, err = _run(capsys, "preview", "--stencil", str(path), "--load", "10")
    assert code == 2 and "number of samples" in err and "49" in err


def test_flagged_golden_exit_code(tmp_path, capsys):
    s, t = stencil_coordinates()
    path = write_stencil_csv(tmp_path / "saddle.csv", 0.2 * s ** 2 - 0.01 * t ** 2)
    code, out, _ = _run(capsys, "preview", "--stencil", str(path), "--load", "10",
                        "--backend", "golden")
    assert code == 3 and "fit_not_elliptic" in out


def test_hertz_form_exact(capsys):
    """--hertz-form exact: the golden datapath's exact tables against analytic exact
    Hertz (1e-3: measured end-to-end 5.4e-4); the published form is 3 % off here."""
    from gearcontact.analytic.hertz import exact_elliptic_hertz
    code, out, _ = _run(capsys, "preview", "--curvatures", "0.25", "0.03", "--load", "1971",
                        "--backend", "golden", "--hertz-form", "exact", "--json")
    assert code == 0
    d = json.loads(out)
    ex = exact_elliptic_hertz(0.25, 0.03, 1971.0, e_prime_mpa=209000 / (1 - 0.09))
    assert d["hertz_form"] == "exact" and d["cycles"] == 756
    assert d["k"] == pytest.approx(ex.k, rel=1e-3)
    assert d["p_max_mpa"] == pytest.approx(ex.p_max_mpa, rel=1e-3)


def test_hertz_form_exact_on_rtl_soc_reads_back_the_exact_tables(capsys):
    """The SoC backend in the exact form: the values read from its registers are the
    exact-form golden values (stage D in the simulated bhseq_core, 756 cycles)."""
    args = ("preview", "--curvatures", "0.25", "0.03", "--load", "100", "--hertz-form",
            "exact", "--json")
    code, out, _ = _run(capsys, *args, "--backend", "rtl-soc")
    assert code == 0
    soc = json.loads(out)
    code, out, _ = _run(capsys, *args, "--backend", "golden")
    gold = json.loads(out)
    assert soc["backend"] == "rtl-soc" and soc["hertz_form"] == "exact"
    assert soc["cycles"] == 756
    for k in ("a_mm", "b_mm", "k", "p_max_mpa"):
        assert soc[k] == gold[k], k


@pytest.mark.parametrize("column", [0, 1, 2])
def test_nan_in_any_stencil_column_is_named(tmp_path, capsys, column):
    """Issue 28 probe: `nan` in the s_mm column was accepted (exit 0): NaN passes every
    |s - s_grid| > 1e-9 test. Exit 2 naming the file, the row and the column."""
    s, t = stencil_coordinates()
    data = np.column_stack([s, t, 0.01 * (s ** 2 + t ** 2)]).astype(object)
    data[4, column] = "nan"
    path = tmp_path / "nan.csv"
    path.write_text("s_mm,t_mm,gap_mm\n" + "".join(",".join(map(str, r)) + "\n"
                                                    for r in data))
    code, out, err = _run(capsys, "preview", "--stencil", str(path), "--load", "10")
    name = ("s_mm", "t_mm", "gap_mm")[column]
    assert code == 2 and out == ""
    assert f"{path}: row 5 (sample 4), column {name} = nan is outside" in err


def test_gap_beyond_the_datapath_format_is_bad_input_for_fixed_point_only(tmp_path, capsys):
    """A gap outside STENCIL_GAP Q(32,21) ([-1024, 1024 - 2^-21] mm, stage C's input
    format) is the file's value for the fixed-point backends (exit 2 naming file and row;
    it was exit 1); fp64 takes it. -2000 mm fitted the former Q(32,16) input."""
    s, t = stencil_coordinates()
    gaps = 0.01 * (s ** 2 + t ** 2)
    gaps[0] = -2000.0
    path = write_stencil_csv(tmp_path / "deep.csv", gaps)
    for backend in ("golden", "rtl"):
        code, _, err = _run(capsys, "preview", "--stencil", str(path), "--load", "10",
                            "--backend", backend)
        assert code == 2 and f"{path}: row 1 (sample 0), column gap_mm = -2000.0" in err
        assert f"the Q(32,21) stencil gap format of the --backend {backend} datapath" in err
    # at the format's end the fixed-point path runs (no FixedPointOverflow)
    gaps[0] = -1024.0
    path = write_stencil_csv(tmp_path / "edge.csv", gaps)
    code, _, err = _run(capsys, "preview", "--stencil", str(path), "--load", "10",
                        "--backend", "golden")
    assert code in (0, 3) and "gap_mm" not in err


# ---- --line-length-mm: the line core -------------------------------------------------
E_STEEL = 209000 / (1 - 0.09)       # E' = 2 E* of the CLI's default steel pair, MPa


@pytest.mark.parametrize("backend", ["reference", "golden"])
def test_line_length_runs_the_line_core(capsys, backend):
    """A long ellipse (B- = 1e-6 1/mm along the line) on a 10 mm contact line: the Hertz
    line contact of length L (Johnson 1985 sec. 4.3). Golden: within the input rounding
    of A- (2^-21 / 0.0246 = 1.9e-5, half of it in p) and one output LSB."""
    from gearcontact.analytic.hertz import line_contact_hertz
    code, out, _ = _run(capsys, "preview", "--curvatures", "0.0246", "1e-6", "--load", "2000",
                        "--line-length-mm", "10", "--backend", backend, "--json")
    assert code == 0
    d = json.loads(out)
    truth = line_contact_hertz(0.5 / 0.0246, 2000.0, 10.0, e_prime_mpa=E_STEEL)
    assert d["mode"] == "line" and d["a_mm"] == pytest.approx(5.0, abs=2 ** -20)
    if backend == "reference":
        assert d["p_max_mpa"] == pytest.approx(truth.p_max_mpa, rel=1e-12)
    else:
        assert d["cycles"] == 759 and d["codes"]["mode"] == 1 and d["codes"]["scale"] == 3
        assert abs(d["p_max_mpa"] - truth.p_max_mpa) <= 1e-5 * truth.p_max_mpa + 2 ** -8


def test_line_length_text_output_says_the_mode(capsys):
    code, out, _ = _run(capsys, "preview", "--curvatures", "0.1", "0.02", "--load", "1000",
                        "--line-length-mm", "50", "--backend", "golden")
    assert code == 0
    assert "mode           elliptic   (contact line L = 50 mm)" in out
    assert "cycles         759" in out
    code, out, _ = _run(capsys, "preview", "--curvatures", "0.1", "0.02", "--load", "1000")
    assert "mode           elliptic\n" in out                # the published core


def test_line_length_with_a_stencil(tmp_path, capsys):
    # a cylinder's stencil (B- = 0): line chain, 811 cycles, the line contact of L
    from gearcontact.analytic.hertz import line_contact_hertz
    from gearcontact.preview.fit.pinv import coefficient_error_bound
    s, t = stencil_coordinates()
    path = write_stencil_csv(tmp_path / "cyl.csv", 0.0246 * s ** 2)
    c = coefficient_error_bound(0.0246 * s ** 2)
    for backend in ("reference", "golden"):
        code, out, _ = _run(capsys, "preview", "--stencil", str(path), "--load", "2000",
                            "--line-length-mm", "10", "--backend", backend, "--json")
        d = json.loads(out)
        assert code == 0 and d["mode"] == "line", d
        truth = line_contact_hertz(0.5 / 0.0246, 2000.0, 10.0, e_prime_mpa=E_STEEL)
        # golden: the fit's A- error (its rigorous bound |dc3| + |dc5| + |dc4|/2: 2.0e-3
        # of A- with the degree-6 ROM's noise gain; measured 3.1e-4) at half weight in
        # p0 ~ sqrt(A-), plus one output LSB
        rel = 0.5 * (c[3] + c[5] + c[4] / 2) / 0.0246
        assert d["p_max_mpa"] == pytest.approx(truth.p_max_mpa, rel=rel, abs=2 ** -8)
    assert d["cycles"] == 811


@pytest.mark.parametrize("value", ["0.0039", "0", "2000", "nan", "-3"])
def test_line_length_outside_its_range_is_named_before_work(capsys, value):
    # the lift's floor is 2^-8 = 0.00390625 mm (preview.hertz.line.LIFT_MAX_SHIFT)
    code, out, err = _run(capsys, "preview", "--curvatures", "0.1", "0.02", "--load", "1000",
                          "--line-length-mm", value, "--backend", "golden")
    assert code == 2 and out == ""
    assert f"--line-length-mm (mm) = {float(value)}" in err
    assert "[1, 1024] mm, or down to 2^-8 = 0.00390625 mm" in err or "finite" in err


@pytest.mark.parametrize("length, lift", [(0.5, 1), (0.25, 2), (2.0 ** -8, 8)])
@pytest.mark.parametrize("backend", ["reference", "golden"])
def test_short_line_runs_the_lifted_line_core(capsys, backend, length, lift):
    """A line below the core's 1 mm (exact in Q(32,20)) through the host's lift
    (docs/hertz.md sec. 6): the Hertz line contact of length L (Johnson 1985 sec. 4.3),
    a = L/2 exactly; golden on (2^s W, 2^s L) (``codes``: the lifted L, ``lift`` = s),
    p within the input rounding of A- (1.9e-5, half of it in p) and one output LSB."""
    from gearcontact.analytic.hertz import line_contact_hertz
    code, out, _ = _run(capsys, "preview", "--curvatures", "0.0246", "1e-6", "--load", "400",
                        "--line-length-mm", repr(length), "--backend", backend, "--json")
    assert code == 0
    d = json.loads(out)
    truth = line_contact_hertz(0.5 / 0.0246, 400.0, length, e_prime_mpa=E_STEEL)
    assert d["mode"] == "line" and d["flags"] == [] and d["a_mm"] == length / 2
    if backend == "reference":
        assert d["p_max_mpa"] == pytest.approx(truth.p_max_mpa, rel=1e-12)
        assert d["b_mm"] == pytest.approx(truth.b_mm, rel=1e-12)
    else:
        assert d["codes"]["lift"] == lift and d["codes"]["L"] == round(length * 2 ** 20) << lift
        assert abs(d["p_max_mpa"] - truth.p_max_mpa) <= 1e-5 * truth.p_max_mpa + 2 ** -8


@pytest.mark.parametrize("argv, needle", [
    (["--curvatures", "0.0246", "1e-6", "--load", "1000", "--line-length-mm", "0.004"],
     "load_n x 2^s <= 131072 N"),
    (["--curvatures", "0.1", "0.05", "--load", "100", "--line-length-mm", "0.4"],
     "where the ellipse is kept")])
def test_short_line_outside_the_lift(capsys, argv, needle):
    """In the option's range but not answered: 2^8 x 1000 N is beyond the load envelope
    (no lift), and a lifted run that keeps its ellipse (2 a = 0.41 mm > L unlifted, but
    the ellipse of 4 W fits 4 L): the reference refuses the length (exit 2, its range
    named), the golden datapath flags length_range (exit 3)."""
    code, out, err = _run(capsys, "preview", *argv, "--backend", "reference")
    assert code == 2 and out == "" and f"line_length_mm = {float(argv[-1])}" in err
    assert needle in err
    code, out, err = _run(capsys, "preview", *argv, "--backend", "golden")
    assert code == 3 and "flags          length_range" in out and "length_range" in err


def test_line_length_refused_on_the_soc_backend(capsys):
    code, out, err = _run(capsys, "preview", "--curvatures", "0.1", "0.02", "--load", "1000",
                          "--line-length-mm", "20", "--backend", "rtl-soc")
    assert code == 2 and out == ""
    assert "--backend (with --line-length-mm) = 'rtl-soc'" in err and "golden" in err
