"""The files of ``gearcontact design --calibrate``, written by report.design.

Truth: the s0003 preset is what the calibration of s0003-centred writes
(docs/calibration.md), so a :class:`Calibration` holding the s0003 preset must write a
``calibrated.toml`` that parses back to exactly that preset (every field equal: the TOML
carries the floats in round-trip digits) under the preset's name, and a
``calibration.json`` that is the calibration's plain-JSON view. The calibration run
itself (about a minute) is the slow test of tests/cli/test_design.py.
"""

import dataclasses
import json
import tomllib

import numpy as np
import pytest

from gearcontact.geometry.pair import load_pair, parse_pair
from gearcontact.report.design import calibrate_to_published, write_calibration
from gearcontact.tca.calibration import Calibration, CalibrationRow, DesignPoint
from gearcontact.validation import InputRangeError


def _calibration(pair) -> Calibration:
    point = DesignPoint(point_mm=np.array([1.0, 2.0, 3.0]), normal=np.array([0.0, 0.0, 1.0]),
                        invariants_mm=np.zeros(4), pinion_uv=(0.0, 0.0), gear_uv=(0.0, 0.0),
                        te0_pp_arcsec=3.0, load_n=1805.0, ellipse_length_mm=6.0,
                        ellipse_width_mm=0.4, ellipse_angle_deg=-20.0, easeoff_max_um=30.0)
    rows = (CalibrationRow("TE0", "arcsec", 3.0, 2.96, 0.3, True),)
    return Calibration(pair=pair, side="coast", soa_offset_mm={"drive": 0.5, "coast": 0.0},
                       tip_margin_mm=0.1, point=point, rows=rows, evaluations=9,
                       seconds=1.0)


def test_write_calibration_round_trips_the_preset(tmp_path):
    preset = load_pair("s0003")
    centred = dataclasses.replace(preset, name="s0003-centred")   # what calibrate_pair keeps
    cal = _calibration(centred)
    path = write_calibration(cal, tmp_path / "out")               # created if missing
    assert path == tmp_path / "out" / "calibrated.toml"
    got = parse_pair(tomllib.loads(path.read_text()))
    assert got.name == preset.name == "s0003"                     # named as the preset
    assert got == preset                                          # every field
    text = (tmp_path / "out" / "calibration.json").read_text()
    assert text == json.dumps(cal.as_dict(), indent=2)
    assert sorted(p.name for p in (tmp_path / "out").iterdir()) == [
        "calibrated.toml", "calibration.json"]


def test_calibrate_to_published_refuses_a_pair_without_published_values():
    pair = dataclasses.replace(load_pair("s0003"), name="my-pair")
    with pytest.raises(InputRangeError, match="published values"):
        calibrate_to_published(pair)
