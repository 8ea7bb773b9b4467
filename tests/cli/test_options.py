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
