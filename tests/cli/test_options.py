"""Shared options, limits and warnings of the pair commands (:mod:`gearcontact.cli.options`).

Truths: the LTE edge-contact warning is one line whose phase list is the set of edge
phases written as runs (expanding the runs gives the set back); the torque bound of a
pair is the preview envelope's largest load times the lever (131072 N x lever / 1000).
"""

import types

import numpy as np
import pytest

from gearcontact.cli.options import lte_warnings, torque_limit_nm
from gearcontact.geometry.pair import load_pair


def _expand(text):
    out = []
    for part in text.split(", "):
        a, _, b = part.partition("-")
        out += list(range(int(a), int(b or a) + 1))
    return out


@pytest.mark.parametrize("mask", [[1, 1, 1, 0, 1, 0, 0, 1, 1], [1] * 61, [0, 1], [1, 0]])
def test_lte_edge_warning_is_one_line_of_runs(mask):
    lte = types.SimpleNamespace(torque_nm=64.5, edge_contact=np.array(mask, bool))
    (line,) = lte_warnings(lte)
    runs = line[line.rindex("(") + 1:-1]
    assert _expand(runs) == list(np.flatnonzero(mask))
    assert f"{sum(mask)} of {len(mask)} phases" in line


def test_no_edge_no_warning():
    assert lte_warnings(types.SimpleNamespace(torque_nm=1.0, edge_contact=np.zeros(5, bool))) == []


def test_torque_limit_is_envelope_load_times_lever():
    pair = load_pair("s0003-centred")
    assert torque_limit_nm(pair, 36.7) == pytest.approx(131072 * 36.7 / 1e3, rel=1e-12)
    outer = pair.blank.mean_pitch_radius_gear_mm + 0.5 * pair.gear_face_width_mm
    assert torque_limit_nm(pair) == pytest.approx(131.072 * outer, rel=1e-12)


def test_torque_floor_is_envelope_load_times_inner_radius(capsys):
    from gearcontact.cli.options import torque_floor_nm

    pair = load_pair("s0003")
    inner = pair.blank.mean_pitch_radius_gear_mm - 0.5 * pair.gear_face_width_mm
    assert torque_floor_nm(pair) == pytest.approx(1.0 * inner / 1e3, rel=1e-12)
    assert main(["lte", "--out", "unused", "--torque", "0.03"]) == 2
    err = capsys.readouterr().err
    assert "[0.0338, 6159.02]" in err and "[1, 131072] N" in err


# --misalignment: parsing, named errors, override of the TOML [assembly] table ---------

from gearcontact.cli import main  # noqa: E402
from gearcontact.cli.options import parse_misalignment  # noqa: E402
from gearcontact.validation import InputRangeError  # noqa: E402


def test_misalignment_parses_all_keys_in_their_units():
    assert parse_misalignment("E=0.05,P=-0.02,G=0.03,alpha=0.01") == {
        "E_mm": 0.05, "P_mm": -0.02, "G_mm": 0.03, "alpha_deg": 0.01}
    assert parse_misalignment(" P = -1 ") == {"P_mm": -1.0}     # the limit is inclusive


@pytest.mark.parametrize("text,named", [
    ("Q=0.1", "KEY one of E, P, G, alpha"), ("E0.1", "KEY=VALUE"),
    ("E=abc", "--misalignment E = 'abc'"), ("E=nan", "[-1, 1] mm"),
    ("P=1.5", "--misalignment P (mm) = 1.5"), ("alpha=-0.6", "[-0.5, 0.5] deg"),
    ("E=0.1,E=0.2", "E repeated")])
def test_misalignment_errors_name_the_item(text, named):
    with pytest.raises(InputRangeError) as exc:
        parse_misalignment(text)
    assert named in str(exc.value)


def test_misalignment_bad_input_exits_2_before_work(tmp_path, capsys):
    assert main(["tca", "--misalignment", "G=2", "--out", str(tmp_path / "o")]) == 2
    assert "--misalignment G (mm) = 2.0" in capsys.readouterr().err
    assert not (tmp_path / "o").exists()


def test_misalignment_overrides_only_the_keys_given(tmp_path):
    from gearcontact.cli.tca import check
    from gearcontact.geometry.pair import pair_to_toml
    import dataclasses
    import types

    base = load_pair("s0003-centred")
    toml = tmp_path / "p.toml"
    toml.write_text(pair_to_toml(dataclasses.replace(
        base, assembly=dataclasses.replace(base.assembly, E_mm=0.04, G_mm=-0.01))))
    args = types.SimpleNamespace(pair=str(toml), misalignment="P=0.03,G=0.02", phases=21,
                                 side=None, pairs=2, table_records=16)
    check(args)
    a = args.gear_pair.assembly
    assert (a.E_mm, a.P_mm, a.G_mm, a.alpha_deg) == (0.04, 0.03, 0.02, 0.0)


def test_tca_json_records_the_misalignment_used(tmp_path):
    import json

    out = tmp_path / "tca"
    assert main(["tca", "--pair", "s0003-centred", "--phases", "21", "--no-figures",
                 "--quiet", "--misalignment", "E=0.05,alpha=-0.01", "--out", str(out)]) == 0
    assert json.loads((out / "tca.json").read_text())["assembly"] == {
        "E_mm": 0.05, "P_mm": 0.0, "G_mm": 0.0, "alpha_deg": -0.01}


@pytest.mark.parametrize("command,extra,name", [
    ("ltca", ["--cells", "32"], "ltca.json"),
    ("lte", ["--cells", "16", "--phases", "5", "--quiet"], "lte.json")])
@pytest.mark.filterwarnings("ignore")     # coarse grids: only the record is under test
def test_loaded_json_records_the_misalignment_used(tmp_path, command, extra, name):
    import json

    out = tmp_path / command
    code = main([command, "--pair", "s0003-centred", "--no-figures", *extra,
                 "--misalignment", "P=0.01,G=-0.01", "--out", str(out)])
    assert code in (0, 4)       # 4: an LCP on the coarse test grid may not converge
    assert json.loads((out / name).read_text())["assembly"] == {
        "E_mm": 0.0, "P_mm": 0.01, "G_mm": -0.01, "alpha_deg": 0.0}
