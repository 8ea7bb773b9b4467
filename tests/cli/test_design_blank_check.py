"""``gearcontact design`` and ``analyze`` check a pair's machine settings against its own
blank tables when the pair is loaded (geometry.blank_check, report.design_mean_point;
docs/machine_settings.md sec. 2, "The check when a pair is loaded"). The installed
console script, default options.

Truths: the ISO 23509 F.2 example (examples/machine_settings/iso23509_f2_machine.toml,
the standard settings of its blank typed to 4 decimals) agrees with its blank; the same
file with one sign word flipped (written here) is caught, the flipped key named (the
flip is the truth). Tolerances: geometry.blank_check's (the typed rounding propagated),
tested in tests/geometry/test_blank_check.py.
"""

import json
import re
from pathlib import Path

import pytest
from console_script import run_console

ROOT = Path(__file__).resolve().parents[2]
F2_MACHINE = ROOT / "examples" / "machine_settings" / "iso23509_f2_machine.toml"


def _flipped(tmp_path, table: str, key: str, fn) -> Path:
    """The example with ``key`` changed by ``fn`` in every table whose name starts with
    ``table`` (a sheet word misread for both flanks of a member)."""
    out, cur = [], None
    for line in F2_MACHINE.read_text(encoding="utf-8").splitlines():
        m = re.match(r"\[(.*)\]", line)
        cur = m.group(1) if m else cur
        if table == "design" and cur == "design" and line.startswith(key):
            line = fn(line)
        elif cur and cur.startswith(table) and line.startswith(f"{key} ="):
            line = f"{key} = {fn(float(line.split('=')[1]))!r}"
        out.append(line)
    path = tmp_path / f"{table}_{key}.toml"
    path.write_text("\n".join(out) + "\n", encoding="utf-8")
    return path


def test_design_says_the_example_agrees():
    code, out, err = run_console("design", "--pair", F2_MACHINE)
    assert code == 0, err
    assert "warning" not in err
    assert "machine settings against the blank: every flank agrees within the typed" in out
    code, out, err = run_console("design", "--pair", F2_MACHINE, "--json")
    assert code == 0, err
    got = json.loads(out)["blank_check"]
    assert got["agrees"] is True and got["hand_slip"] is False
    gear = {c["quantity"]: c for c in got["flanks"]["gear"]["drive"]["comparisons"]}
    assert gear["spiral angle"]["stated"] == 35.0 and gear["spiral angle"]["within"]
    assert gear["hand"]["measured"] == "left"


SLIPS = [
    # (table, key, flip, exit code, the key named)
    ("machine.gear", "cradle_angle_deg", lambda x: -x, 2,
     "machine.gear.drive.cradle_angle_deg = 80.4732 is outside the allowed range"),
    # warned as a slip, then refused: the settings cut a pointed pinion (settings_top_land)
    ("machine.pinion", "sliding_base_mm", lambda x: -x, 2,
     "likely machine.pinion.drive.sliding_base_mm"),
    ("design", "pinion_hand", lambda line: 'pinion_hand = "left"', 2,
     "design.pinion_hand = 'left' is outside the allowed range"),
]


@pytest.mark.parametrize("table,key,flip,code,named", SLIPS, ids=[k for _, k, _, _, _ in SLIPS])
def test_design_names_the_flipped_key(tmp_path, table, key, flip, code, named):
    got, out, err = run_console("design", "--pair", _flipped(tmp_path, table, key, flip))
    assert got == code, err
    assert named in err
    if code == 0:      # a warning, and design says so below its table
        assert "machine settings against the blank: pinion drive, pinion coast do not " \
               "agree" in out


def test_analyze_refuses_a_wrong_hand_before_any_work(tmp_path):
    # the check runs in analyze's argument check: exit 2 in the time of a design call
    path = _flipped(tmp_path, "machine.gear", "cradle_angle_deg", lambda x: -x)
    code, out, err = run_console("analyze", "--pair", path, "--quiet", "--out",
                                 tmp_path / "a", timeout=60.0)
    assert code == 2, err
    assert "machine.gear.drive.cradle_angle_deg = 80.4732" in err
    assert not (tmp_path / "a").exists()


@pytest.fixture(scope="module")
def hypoid_generated(tmp_path_factory):
    """The 11 x 41 hypoid's standard settings with the gear generated (what design
    --machine-settings writes, full precision) as a pair file, and its blank's pitch
    apexes from the crossing point (the MD datum)."""
    from gearcontact.geometry.basic_settings import standard_machine_pair
    from gearcontact.geometry.blank_statement import stated_blank
    from gearcontact.geometry.pair import load_pair, pair_to_toml

    pair = standard_machine_pair(load_pair(ROOT / "examples" / "hypoid_11x41_rear_axle.toml"),
                                 gear_generation="generated")
    path = tmp_path_factory.mktemp("hypoid") / "hypoid_generated.toml"
    path.write_text(pair_to_toml(pair), encoding="utf-8")
    return path, stated_blank(pair).mctb_datum_mm


HYPOID_SLIPS = [
    # (key flipped on both gear flanks, exit code, what stderr says): the ratio of roll
    # typed as its reciprocal (1.0637 -> 0.9401): the gear flanks miss their mean point,
    # the key named, then the gear's generation refuses its flank (exit 2); the MD word
    # read from the crossing point with the other sign (X_D 0 -> 0.573 mm): the pitch
    # point of generation 2.4 / 1.2 mm off (tolerance 0.63), a warning naming the key
    ("ratio_of_roll", lambda x, a: 1.0 / x, 2,
     ("likely machine.gear.drive.ratio_of_roll", "a node the generated envelope reaches")),
    ("machine_centre_to_back_mm", lambda x, a: 2.0 * a - x, 0,
     ("likely machine.gear.drive.machine_centre_to_back_mm (with the other MD sign, MD "
      "read from the crossing point", "pitch point 2.3")),
]


def test_design_says_the_generated_hypoid_agrees(hypoid_generated):
    code, out, err = run_console("design", "--pair", hypoid_generated[0])
    assert code == 0, err
    assert "warning" not in err
    assert "the pitch point of its generating roll" in out


@pytest.mark.parametrize("key,flip,code,said", HYPOID_SLIPS, ids=[k for k, *_ in HYPOID_SLIPS])
def test_design_names_a_gear_roll_slip(tmp_path, hypoid_generated, key, flip, code, said):
    src, datum = hypoid_generated
    out_lines, cur = [], None
    for line in src.read_text(encoding="utf-8").splitlines():
        m = re.match(r"\[(.*)\]", line)
        cur = m.group(1) if m else cur
        if cur and cur.startswith("machine.gear") and line.startswith(f"{key} ="):
            line = f"{key} = {flip(float(line.split('=')[1]), datum['gear'])!r}"
        out_lines.append(line)
    path = tmp_path / f"gear_{key}.toml"
    path.write_text("\n".join(out_lines) + "\n", encoding="utf-8")
    got, out, err = run_console("design", "--pair", path)
    assert got == code, err
    assert all(s in err for s in said), err
