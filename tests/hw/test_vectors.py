"""Golden-vector export: the files parse as their README documents them, and the
inputs read back from the files reproduce the exported outputs bit for bit.

Truths (independent of the exporter): the README's field tables decoded with Python
big integers (not :func:`decode_hex`), the golden models called directly on the
decoded inputs (vectorized on every vector; scalar on every corner case and every
7th random vector), :mod:`gearcontact.preview.stimulus` for the operands and labels,
and the cycle counts of docs/spec.md sec. 6 (26 / 52 / 756 / 806). Tolerance: none --
every code, flag and cycle count must be equal.
"""

import json
import re

import numpy as np
import pytest

from gearcontact.hw.harness_cores import get_bench
from gearcontact.preview.chain import chain_golden, chain_golden_batch, chain_line_golden
from gearcontact.preview.fit.golden import golden_fit, golden_fit_batch
from gearcontact.preview.gap.fast import gap_golden_batch
from gearcontact.preview.gap.golden import GapVector, gap_golden_codes
from gearcontact.preview.hertz.golden import hertz_golden
from gearcontact.preview.hertz.golden_vec import hertz_golden_array
from gearcontact.preview.hertz.line import length_lift, line_golden, unlift_line_codes
from gearcontact.preview.stimulus import stimulus
from gearcontact.preview.stimulus_lift import host_chain_line_stimulus, host_line_stimulus
from gearcontact.hw.vectors import (LINE_CORES, VECTOR_CORES, HexField, decode_hex,
                                    encode_hex, export_vectors, read_hex, read_jsonl,
                                    vector_layout)
from gearcontact.validation import InputRangeError

COUNT, SEED = 150, 7
LINE_COUNT = 120                 # the line cores: scalar host path on every vector
CYCLES = {"gap": 26, "fit": 52, "hertz": 756, "chain": 806}     # docs/spec.md sec. 6
HERTZ = ("a", "b", "p_max", "k", "A_min", "B_max", "R_x", "R_y", "alpha")


@pytest.fixture(scope="module")
def export(tmp_path_factory):
    out = tmp_path_factory.mktemp("vectors")
    return out, export_vectors(out, count=COUNT, seed=SEED)


# ------------------------------------------------------------------ README as the spec
def _documented_layout(readme: str, filename: str) -> tuple[int, list[dict]]:
    """Bits per line and the field rows of ``filename``'s table in the README."""
    sec = readme.split(f"### `{filename}`: ")[1]
    bits = int(re.match(r"(\d+) bits per line", sec).group(1))
    rows = []
    for line in sec.split("\n\n")[1].splitlines()[2:]:
        cells = [c.strip() for c in line.strip("|").split("|")]
        hi, lo = map(int, re.match(r"\[(\d+):(\d+)\]", cells[2]).groups())
        ebits, digits = map(int, re.match(r"(\d+) \((\d+)\)", cells[3]).groups())
        shape = () if cells[4] == "1" else tuple(int(x) for x in cells[4].split(" x "))
        rows.append({"name": cells[1].strip("`"), "hi": hi, "lo": lo, "bits": ebits,
                     "digits": digits, "shape": shape, "signed": cells[5] == "yes",
                     "q": cells[6], "unit": cells[7]})
    return bits, rows


def _decode_documented(path, readme, filename) -> dict:
    """Decode a hex file with Python ints, following only the README table."""
    bits, rows = _documented_layout(readme, filename)
    lines = path.read_text().splitlines()
    out = {r["name"]: [] for r in rows}
    for line in lines:
        assert len(line) * 4 == bits and re.fullmatch(r"[0-9a-f]+", line)
        word = int(line, 16)
        for r in rows:
            w = 4 * r["digits"]
            n = int(np.prod(r["shape"], dtype=int))
            assert r["hi"] - r["lo"] + 1 == n * w
            vals = []
            for j in range(n):
                x = (word >> (r["hi"] - (j + 1) * w + 1)) & ((1 << w) - 1)
                if r["signed"] and x >> (w - 1):
                    x -= 1 << w
                # the element fits its documented port width
                assert (-(1 << (r["bits"] - 1)) <= x < (1 << (r["bits"] - 1))) \
                    if r["signed"] else (0 <= x < (1 << r["bits"]))
                vals.append(x)
            out[r["name"]].append(vals)
    return {r["name"]: np.array(out[r["name"]], np.int64).reshape((len(lines),) + r["shape"])
            for r in rows}


# ---------------------------------------------------------------- fresh golden models
def _fresh_vectorized(core, x) -> dict:
    if core == "gap":
        cols = {k: [] for k in ("gap", "idx", "valid", "overflow")}
        for i in range(len(x["r"])):
            o = gap_golden_batch(x["r"][i:i + 1].reshape(1, 3, 3), x["t"][i:i + 1],
                                 x["p"][i:i + 1], x["w_g"][i], x["w_n"][i],
                                 int(x["tau2"][i]), lanes=16)
            for k, v in zip(cols, (o.min_gap_code, o.min_idx, o.valid, o.overflow)):
                cols[k].append(int(v[0]))
        return {k: np.array(v, np.int64) for k, v in cols.items()}
    if core == "fit":
        f = golden_fit_batch(x["wr_data"])
        return {**{f"c{j}": f.c_codes[:, j] for j in range(6)}, "a_minus": f.a_minus_codes,
                "b_minus": f.b_minus_codes, "flags": f.flags}
    if core == "hertz":
        h = hertz_golden_array(x["A"], x["B"], x["W"], e_prime_code=x["e_prime"])
        return {**{n: getattr(h, n + "_code") for n in HERTZ}, "flags": h.flags}
    r = chain_golden_batch(x["wr_data"], x["W"], e_prime_code=x["e_prime"])
    return {**{n: getattr(r.hertz, n + "_code") for n in HERTZ},
            **{f"c{j}": r.fit.c_codes[:, j] for j in range(6)},
            "a_minus": r.fit.a_minus_codes, "b_minus": r.fit.b_minus_codes, "flags": r.flags}


def _fresh_scalar(core, x, i) -> dict:
    if core == "gap":
        o = gap_golden_codes(GapVector(x["r"][i].reshape(3, 3), x["t"][i], x["p"][i],
                                       x["w_g"][i], x["w_n"][i], int(x["tau2"][i])), lanes=16)
        return {"gap": o.min_gap_code, "idx": o.min_idx, "valid": int(o.valid),
                "overflow": int(o.overflow)}
    if core == "fit":
        f = golden_fit([int(v) for v in x["wr_data"][i]], bitwise=True)
        return {**{f"c{j}": f.c_codes[j] for j in range(6)}, "a_minus": f.a_minus_code,
                "b_minus": f.b_minus_code, "flags": f.flags}
    if core == "hertz":
        h = hertz_golden(int(x["A"][i]), int(x["B"][i]), int(x["W"][i]),
                         e_prime_code=int(x["e_prime"][i]), bit_serial=True)
        return {**{n: getattr(h, n + "_code") for n in HERTZ}, "flags": h.flags}
    r = chain_golden([int(v) for v in x["wr_data"][i]], int(x["W"][i]),
                     e_prime_code=int(x["e_prime"][i]))
    return {**{n: getattr(r.hertz, n + "_code") for n in HERTZ},
            **{f"c{j}": r.fit.c_codes[j] for j in range(6)},
            "a_minus": r.fit.a_minus_code, "b_minus": r.fit.b_minus_code, "flags": r.flags}


# ------------------------------------------------------------------------------ tests
def test_file_list(export):
    out, files = export
    names = [p.name for p in files]
    assert names == [f"{c}{s}" for c in VECTOR_CORES for s in (".jsonl", "_in.hex",
                                                               "_out.hex")] + ["README.md"]
    assert all(p.parent == out and p.is_file() for p in files)


@pytest.mark.parametrize("core", VECTOR_CORES)
def test_files_reproduce_golden_bit_for_bit(export, core):
    out, _ = export
    readme = (out / "README.md").read_text()
    x = _decode_documented(out / f"{core}_in.hex", readme, f"{core}_in.hex")
    y = _decode_documented(out / f"{core}_out.hex", readme, f"{core}_out.hex")
    recs = read_jsonl(out / f"{core}.jsonl")
    st = stimulus(core, COUNT, SEED, **({"n_samples": 16} if core == "gap" else {}))
    n = len(st)
    assert len(recs) == n and all(len(v) == n for v in (*x.values(), *y.values()))
    # JSON lines carry the same codes as the hex files, and the documented keys
    for k, rec in enumerate(recs):
        assert set(rec) == {"core", "index", "label", "inputs", "outputs", "cycles"}
        assert (rec["core"], rec["index"], rec["label"]) == (core, k, st.labels[k])
        assert rec["cycles"] == CYCLES[core]
        assert set(rec["inputs"]) == set(x) and set(rec["outputs"]) == set(y)
    for name, v in x.items():
        assert np.array_equal(np.array([r["inputs"][name] for r in recs], np.int64), v)
    for name, v in y.items():
        assert np.array_equal(np.array([r["outputs"][name] for r in recs], np.int64), v)
    # the inputs are the stimulus operands
    same = {"gap": {"w_g": "g", "w_n": "nrm", "t": "t", "p": "p", "tau2": "tau2"},
            "fit": {"wr_data": "gaps"}, "hertz": {k: k for k in ("A", "B", "W", "e_prime")},
            "chain": {"wr_data": "gaps", "W": "W", "e_prime": "e_prime"}}[core]
    for port, field in same.items():
        assert np.array_equal(x[port], st.fields[field]), port
    if core == "gap":
        assert np.array_equal(x["r"].reshape(n, 3, 3), st.fields["r"])
        assert (x["n_samples"] == 16).all()
    # vectorized golden on every vector
    fresh = _fresh_vectorized(core, x)
    assert {"flags"} <= set(y) or core == "gap"
    for name, v in y.items():
        assert np.array_equal(np.asarray(fresh[name], np.int64), v), name
    # scalar golden on every corner case and every 7th random vector
    for i in list(range(st.n_corner)) + list(range(st.n_corner, n, 7)):
        s = _fresh_scalar(core, x, i)
        assert {name: int(v[i]) for name, v in y.items()} == \
            {name: int(s[name]) for name in y}, (core, i, st.labels[i])


def test_paths_are_exercised(export):
    out, _ = export
    y = {c: read_hex(out / f"{c}_out.hex", c, "out") for c in VECTOR_CORES}
    assert y["gap"]["valid"].any() and not y["gap"]["valid"].all()
    assert y["gap"]["overflow"].any()
    for c in ("fit", "hertz", "chain"):
        assert (y[c]["flags"] == 0).sum() > COUNT // 2, c
        assert (y[c]["flags"] != 0).any(), c


@pytest.mark.parametrize("core", VECTOR_CORES)
def test_corner_labels_first_and_documented(export, core):
    out, _ = export
    readme = (out / "README.md").read_text()
    st = stimulus(core, 0, SEED, **({"n_samples": 16} if core == "gap" else {}))
    labels = [r["label"] for r in read_jsonl(out / f"{core}.jsonl")]
    assert labels[:len(st)] == list(st.labels) and len(st) >= 10
    assert set(labels[len(st):]) <= {"random", "raw"}
    sec = readme.split(f"\n## {core}\n")[1].split("\n## ")[0]
    for i, lab in enumerate(st.labels):
        assert f"\n{i}. {lab}\n" in sec
    assert f"{CYCLES[core]} cycles per vector" in sec


def test_readme_documents_every_field_and_the_run(export):
    out, files = export
    readme = (out / "README.md").read_text()
    assert f"seed: **{SEED}**" in readme and f"random vectors per core: **{COUNT}**" in readme
    assert f"gearcontact vectors --out DIR --count {COUNT} --seed {SEED} " \
           "--cores gap,fit,hertz,chain" in readme
    for p in files[:-1]:
        assert f"| `{p.name}` |" in readme
    for core in VECTOR_CORES:
        for which, fields in zip(("in", "out"), vector_layout(core)):
            bits, rows = _documented_layout(readme, f"{core}_{which}.hex")
            assert [r["name"] for r in rows] == [f.name for f in fields]
            assert bits == sum(f.width for f in fields) == rows[0]["hi"] + 1
            assert rows[-1]["lo"] == 0
            for r in rows:         # every field has a Q format and a unit
                assert re.fullmatch(r"U?Q\(\d+,\d+\)", r["q"]) and r["unit"] not in ("", "-")
                assert int(re.match(r"U?Q\((\d+)", r["q"]).group(1)) == r["bits"]
                assert r["q"].startswith("Q") == r["signed"]


def test_deterministic_for_a_seed(export, tmp_path):
    out, files = export
    again = export_vectors(tmp_path / "a", count=COUNT, seed=SEED)
    for p, q in zip(files, again):
        assert p.read_bytes() == q.read_bytes(), p.name
    other = export_vectors(tmp_path / "b", cores=("hertz",), count=COUNT, seed=SEED + 1)
    a = read_jsonl(out / "hertz.jsonl")
    b = read_jsonl(other[0])
    n_corner = sum(r["label"] not in ("random", "raw") for r in a)
    assert a[:n_corner] == b[:n_corner] and a[n_corner:] != b[n_corner:]
    assert [p.name for p in other] == ["hertz.jsonl", "hertz_in.hex", "hertz_out.hex",
                                       "README.md"]


def test_hex_codec_extremes_and_no_wrap():
    fields = (HexField("s21", 21, (2,), True, "Q(21,19)", "1", ""),
              HexField("u64", 64, (), False, "UQ(64,32)", "1", ""),
              HexField("u1", 1, (), False, "UQ(1,0)", "1", ""),
              HexField("s32", 32, (), True, "Q(32,0)", "1", ""))
    vals = {"s21": np.array([[-(1 << 20), (1 << 20) - 1], [-1, 0]]),
            "u64": np.array([(1 << 63) - 1, 0]), "u1": np.array([1, 0]),
            "s32": np.array([-(1 << 31), (1 << 31) - 1])}
    lines = encode_hex(vals, fields)
    assert lines[0] == "f00000" "0fffff" "7fffffffffffffff" "1" "80000000"
    assert lines[1] == "ffffff" "000000" "0000000000000000" "0" "7fffffff"
    back = decode_hex(lines, fields)
    for k, v in vals.items():
        assert np.array_equal(back[k], v)
    assert np.array_equal(decode_hex([ln.upper() for ln in lines], fields)["s32"],
                          vals["s32"])
    for name, bad in (("s21", [[1 << 20, 0], [0, 0]]), ("u1", [2, 0]), ("s32", [1 << 31, 0])):
        with pytest.raises(InputRangeError, match=name):
            encode_hex({**vals, name: np.array(bad)}, fields)
    with pytest.raises(InputRangeError):
        decode_hex(["00"], fields)


def test_bad_arguments(tmp_path):
    with pytest.raises(InputRangeError, match="core"):
        export_vectors(tmp_path, cores=("gap", "comb"))
    with pytest.raises(InputRangeError, match="count"):
        export_vectors(tmp_path, count=-1)
    with pytest.raises(InputRangeError, match="seed"):
        export_vectors(tmp_path, seed=1.5)
    with pytest.raises(InputRangeError, match="cores"):
        export_vectors(tmp_path, cores=())


def test_jsonl_is_strict_json(export):
    out, _ = export
    for line in (out / "gap.jsonl").read_text().splitlines()[:5]:
        rec = json.loads(line)
        assert np.array(rec["inputs"]["w_g"]).shape == (16, 3)
        assert np.array(rec["inputs"]["r"]).shape == (9,)


def test_variant_cores_export_their_own_golden_model(tmp_path):
    """gap_lean and hertz_exact (on request only): same fields and operands as their base
    cores, outputs of their own golden models read back from the hex files."""
    files = export_vectors(tmp_path, cores=("hertz_exact", "gap_lean"), count=40, seed=SEED)
    assert [p.name for p in files[:6]] == ["gap_lean.jsonl", "gap_lean_in.hex",
                                           "gap_lean_out.hex", "hertz_exact.jsonl",
                                           "hertz_exact_in.hex", "hertz_exact_out.hex"]
    assert vector_layout("gap_lean") == vector_layout("gap")
    rows = read_jsonl(tmp_path / "hertz_exact.jsonl")
    assert {r["core"] for r in rows} == {"hertz_exact"} and rows[0]["cycles"] == 756
    x = read_hex(tmp_path / "hertz_exact_in.hex", "hertz_exact", "in")
    y = read_hex(tmp_path / "hertz_exact_out.hex", "hertz_exact", "out")
    want = hertz_golden_array(x["A"], x["B"], x["W"], e_prime_code=x["e_prime"],
                              hertz_form="exact")
    published = hertz_golden_array(x["A"], x["B"], x["W"], e_prime_code=x["e_prime"])
    assert np.array_equal(y["k"], want.k_code)
    assert not np.array_equal(y["k"], published.k_code)        # the exact tables differ
    x = read_hex(tmp_path / "gap_lean_in.hex", "gap_lean", "in")
    y = read_hex(tmp_path / "gap_lean_out.hex", "gap_lean", "out")
    rows = read_jsonl(tmp_path / "gap_lean.jsonl")
    assert rows[0]["cycles"] == 26
    for i in range(0, len(rows), 3):
        vec = GapVector(x["r"][i].reshape(3, 3), x["t"][i], x["p"][i], x["w_g"][i],
                        x["w_n"][i], int(x["tau2"][i]))
        got = gap_golden_codes(vec, variant="lean")
        assert (y["gap"][i], y["idx"][i], y["valid"][i]) == \
            (got.min_gap_code, got.min_idx, got.valid)
    with pytest.raises(InputRangeError, match="core = 'comb'"):
        export_vectors(tmp_path, cores=("comb",), count=1)


# ------------------------------------------------------------------ the line cores
def _host_line_scalar(core: str, x: dict, i: int) -> dict:
    """The host's path on vector ``i`` by the scalar models: ``length_lift``, the line
    core (:func:`line_golden`; the chain: :func:`chain_line_golden`) on the lifted
    ``(W << s, L << s)``, ``unlift_line_codes``; the chain's flags recomposed from the
    unlifted line flags and the fit's overflow bits (preview.engine's rule)."""
    w, length, e = int(x["W"][i]), int(x["L"][i]), int(x["e_prime"][i])
    s = int(length_lift(w, length))
    out = {"lift": s}
    if core == "chain_line":
        r = chain_line_golden([int(g) for g in x["wr_data"][i]], w << s, length << s,
                              e_prime_code=e)
        lc = unlift_line_codes(r.hertz, s)
        out.update({f"c{j}": r.fit.c_codes[j] for j in range(6)}, a_minus=r.fit.a_minus_code,
                   b_minus=r.fit.b_minus_code, fit_flags=r.fit.flags,
                   flags=lc.flags | (r.flags & ~0xFF))
    else:
        lc = unlift_line_codes(line_golden(int(x["A"][i]), int(x["B"][i]), w << s,
                                           length << s, e_prime_code=e,
                                           hertz_form="exact" if core.endswith("exact")
                                           else "hamrock-brewe"), s)
        out["flags"] = lc.flags
    out.update(a=lc.a_code, b=lc.b_code, p_max=lc.p_max_code, k=lc.k_code,
               A_min=lc.A_min_code, B_max=lc.B_max_code, mode=lc.mode, scale=lc.scale)
    return out


@pytest.fixture(scope="module")
def line_export(tmp_path_factory):
    out = tmp_path_factory.mktemp("line_vectors")
    return out, export_vectors(out, cores=LINE_CORES, count=LINE_COUNT, seed=SEED)


@pytest.mark.parametrize("core", LINE_CORES)
def test_line_cores_are_the_host_path_bit_for_bit(line_export, core):
    """The line cores' files (on request): decoded with the README's own table (Python
    ints), the inputs are the host stimulus's operands, the outputs the scalar host path
    (:func:`_host_line_scalar`) on every vector, ``lift`` the last output (UQ(4,0)), and
    where ``lift`` = 0 the outputs are the RTL core's golden registers unchanged (the
    bench's golden on the same operands, no lift)."""
    out, _ = line_export
    readme = (out / "README.md").read_text()
    x = _decode_documented(out / f"{core}_in.hex", readme, f"{core}_in.hex")
    y = _decode_documented(out / f"{core}_out.hex", readme, f"{core}_out.hex")
    ins, outs = vector_layout(core)
    assert list(y) == [f.name for f in outs] and outs[-1].name == "lift"
    assert (outs[-1].qformat, outs[-1].signed) == ("UQ(4,0)", False)
    st = (host_chain_line_stimulus if core == "chain_line" else host_line_stimulus)(
        LINE_COUNT, SEED)
    assert (x["wr_data"] if core == "chain_line" else x["A"]).shape[0] == len(st)
    for port, field in ({"wr_data": "gaps", "W": "W", "L": "L", "e_prime": "e_prime"}
                        if core == "chain_line" else {k: k for k in st.fields}).items():
        assert np.array_equal(x[port], st.fields[field]), port
    recs = read_jsonl(out / f"{core}.jsonl")
    assert [r["label"] for r in recs] == list(st.labels)
    assert {r["cycles"] for r in recs} == {{"chain_line": 811}.get(core, 759)}
    for i in range(len(st)):
        want = _host_line_scalar(core, x, i)
        assert {k: int(v[i]) for k, v in y.items()} == want, (core, i, st.labels[i])
    assert (y["lift"] > 0).any() and (y["lift"] == 0).any()
    core_only = get_bench(core).golden(st)
    rows = y["lift"] == 0
    for name, v in core_only.items():
        assert np.array_equal(np.asarray(v)[rows], y[name][rows]), name
    assert f"## {core}\n" in readme and "`W << lift` and `L << lift`" in readme
