"""The loaded-TE table's published column holds the pair's published values only
(report.summary.lte_rows; docs/machine_settings.md sec. 5, "Ordinary pairs, measured":
every pair's summary.md printed s0003's "3 engaged" and "74.6 / 22.6 / 2.8 (with
bending)" as published, a 15/30 hypoid cut from its settings included)."""

from __future__ import annotations

import json
from importlib import resources
from types import SimpleNamespace

import numpy as np

from gearcontact.report.summary import lte_rows

#: A stand-in loaded TE (the attributes lte_rows reads; numbers arbitrary, not compared).
LTE = SimpleNamespace(
    te0_pp_arcsec=23.9, te_lcp_pp_arcsec=12.5, te_pre_pp_arcsec=12.1,
    compliance_lcp_mm_per_n=5.8e-6, compliance_pre_mm_per_n=3.5e-6,
    mesh_compliance_lcp_mm_per_n=5.8e-6, mesh_compliance_pre_mm_per_n=3.5e-6,
    rotation_lcp_arcsec=np.array([29.9]), rotation_pre_arcsec=np.array([29.8]),
    active_lcp=np.array([1, 2]), pair_offsets=(0, 1),
    pair_loads_lcp_n=np.array([[1118.0], [0.0]]), reference_index=0,
    edge_contact=np.array([False]), converged=True, dropped_load_n=np.array([0.0]))


def test_a_pair_without_published_values_gets_none():
    """No published values: no row of the published column is filled."""
    assert all(row[2] is None for row in lte_rows(LTE, {}))


def test_s0003_gets_its_published_shares_from_the_data_file():
    """s0003: the engaged pairs and the shares are those of data/published/s0003.json
    (the independent record), in the text the summary printed before."""
    pub = json.loads(resources.files("gearcontact").joinpath(
        "data/published/s0003.json").read_text())
    rows = {row[0]: row[2] for row in lte_rows(LTE, pub)}
    shares = pub["multi_tooth_load_share_pct"]
    assert rows["active pairs (LCP)"] == f"{len(shares)} engaged" == "3 engaged"
    assert rows["load shares at P0 (LCP, %)"] == "74.6 / 22.6 / 2.8 (with bending)"
