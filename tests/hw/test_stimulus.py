"""The shared seeded stimulus (gearcontact.preview.stimulus): deterministic, in contract
for every core's input formats, and covering the documented corner cases."""

import numpy as np
import pytest

from gearcontact.hw.harness_cores import CORE_NAMES, get_bench
from gearcontact.preview import stimulus as S
from gearcontact.preview.gap.golden import GapVector, check_vector, gap_golden_codes
from gearcontact.preview.hertz import formats as HF
from gearcontact.contract.qformat import STENCIL_GAP
from gearcontact.validation import InputRangeError


@pytest.mark.parametrize("core", CORE_NAMES)
def test_seeded_and_deterministic(core):
    a, b, c = (S.stimulus(core, 64, seed) for seed in (5, 5, 6))
    assert a.labels == b.labels and len(a) == 64 + a.n_corner
    for k in a.fields:
        assert a.fields[k].dtype == np.int64
        np.testing.assert_array_equal(a.fields[k], b.fields[k])
    assert any(not np.array_equal(a.fields[k], c.fields[k]) for k in a.fields)
    assert set(a.labels[a.n_corner:]) <= {"random", "raw"}
    assert S.stimulus(core, 10, 1, corners=False).n_corner == 0


@pytest.mark.parametrize("n_samples", [1, 16, 37, 256])
def test_gap_codes_in_contract(n_samples):
    st = S.gap_stimulus(64, 3, n_samples=n_samples)
    f = st.fields
    assert f["g"].shape == (len(st), n_samples, 3)
    for i in range(len(st)):
        check_vector(GapVector(f["r"][i], f["t"][i], f["p"][i], f["g"][i], f["nrm"][i],
                               int(f["tau2"][i])))


def test_gap_corner_cases_do_what_they_say():
    st = S.gap_stimulus(0, 0, n_samples=16)
    f = st.fields
    out = {lab: gap_golden_codes(GapVector(f["r"][i], f["t"][i], f["p"][i], f["g"][i],
                                           f["nrm"][i], int(f["tau2"][i])))
           for i, lab in enumerate(st.labels)}
    assert not out["gate rejects every lane"].valid
    assert out["posed point overflows Q(24,16)"].overflow
    assert out["negative gaps (penetration)"].min_gap_code < 0
    assert out["winner is the last sample"].min_idx == 15
    assert out["every sample identical (rho and |g| ties)"].min_idx == 0
    assert out["+-g ties across lanes"].min_idx == 0


def test_stencil_codes_and_flag_coverage():
    st = S.fit_stimulus(2000, 1)
    g = st.fields["gaps"]
    assert g.shape == (len(st), 49) and STENCIL_GAP.fits(g).all()
    flags = get_bench("fit").golden(st)["flags"]
    assert {0, 1, 8} <= set(np.unique(flags).tolist())       # valid, overflow, saddle


def test_hertz_inputs_cover_envelope_and_flags():
    st = S.hertz_stimulus(3000, 2)
    f = st.fields
    for k in ("A", "B", "W", "e_prime"):
        assert ((f[k] >= -(2 ** 31)) & (f[k] < 2 ** 31)).all()
    labels = set(st.labels)
    for want in ("minimum load", "maximum load", "alpha = 128 exactly (POW LUT end)",
                 "A = B (alpha = 1, sort tie)", "all zero (go without data)"):
        assert want in labels
    flags = get_bench("hertz").golden(st)["flags"]
    assert (flags == 0).mean() > 0.7
    for bit in (HF.FLAG_NOT_ELLIPTIC, HF.FLAG_CURV_RANGE, HF.FLAG_LOAD_RANGE,
                HF.FLAG_E_PRIME_RANGE, HF.FLAG_ALPHA_RANGE):
        assert (flags & bit).any(), bit


def test_chain_inputs():
    st = S.chain_stimulus(500, 4)
    assert st.fields["gaps"].shape == (len(st), 49)
    assert st.fields["W"].shape == st.fields["e_prime"].shape == (len(st),)
    assert any("maximum load" in lab for lab in st.labels)
    assert (st.fields["e_prime"] == S.STEEL_E_PRIME_CODE).mean() > 0.5


def test_take_and_bad_arguments():
    st = S.hertz_stimulus(10, 0)
    sub = st.take(slice(2, 5))
    assert len(sub) == 3 and sub.labels == st.labels[2:5]
    with pytest.raises(InputRangeError, match="core"):
        S.stimulus("nope", 1)
    with pytest.raises(InputRangeError, match="n_samples"):
        S.gap_stimulus(1, n_samples=0)
    with pytest.raises(InputRangeError, match="random vectors"):
        S.fit_stimulus(-1)
