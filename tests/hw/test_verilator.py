"""Bulk RTL equivalence through Verilator (generic C++ harness) against the golden models.

Default run: every core (gap L = 16, fit, hertz, chain, comb) on its corner cases plus
1,000 seeded random vectors (the line chain and the exact-form line core: 10,000), zero mismatches on every checked output port and the same,
expected cycle count for every vector. ``python -m pytest --runslow tests/hw`` adds the
100,000-vector sweeps. Builds are cached (``~/.cache/gearcontact/verilator``), so only
the first run on a machine pays for them.

Tests that need Verilator skip, with the apt command in the reason, only when
``verilator``/``g++``/``make`` are really absent (CI installs them: ``.ci/run``).
"""

import dataclasses
import os
import subprocess
from pathlib import Path

import numpy as np
import pytest

from gearcontact.hw import harness_cores as hc
from gearcontact.hw import verilator as vl
from gearcontact.hw.harness import (
    HarnessSpec,
    Port,
    WritePort,
    generate_harness,
    pack_port,
    pack_stimulus,
    unpack_port,
    unpack_results,
)
from gearcontact.preview.gap.golden import gap_latency
from gearcontact.preview.gap.cores import GAP_LANES

needs_verilator = pytest.mark.skipif(
    not vl.verilator_available(), reason=f"Verilator toolchain not installed: {vl.INSTALL_HINT}")

DEFAULT_VECTORS = 1_000
SLOW_VECTORS = 100_000
SEED = 20_261_122
REPO = Path(__file__).resolve().parents[2]


def _report(core: str, n: int, seed: int, **kwargs) -> hc.EquivalenceReport:
    try:
        return hc.run_equivalence(core, n, seed, **kwargs)
    except hc.CoreUnavailable as exc:         # RTL of this core not in the checkout
        pytest.skip(str(exc))


def _assert_equivalent(rep: hc.EquivalenceReport, n: int) -> None:
    assert rep.vectors == n + rep.corner_vectors
    assert rep.mismatches == 0, rep.mismatch_examples
    assert rep.cycle_counts == {rep.cycles_expected: rep.vectors}
    assert rep.ok


# ---------------------------------------------------------------------------------
# harness generator and stream packing (no Verilator needed)
# ---------------------------------------------------------------------------------
@pytest.mark.parametrize("port", [Port("a", 1), Port("b", 32, signed=True), Port("c", 33),
                                  Port("d", 64), Port("e", 21, 9, True), Port("f", 24, 3, True),
                                  Port("g", 63, signed=True)])
def test_pack_unpack_roundtrip(port):
    rng = np.random.default_rng(1)
    lo = -(1 << (port.bits - 1)) if port.signed else 0
    hi = (1 << (port.bits - 1)) - 1 if port.signed else (1 << min(port.bits, 63)) - 1
    shape = (50,) if port.count == 1 else (50, port.count)
    vals = rng.integers(lo, hi, shape, endpoint=True)
    vals.flat[:2] = [lo, hi]
    words = pack_port(port, vals, (50,))
    assert words.shape == (50, port.words) and words.dtype == np.dtype("<u4")
    np.testing.assert_array_equal(unpack_port(port, words), vals)


def test_pack_layout_element_zero_in_low_bits():
    w = pack_port(Port("r", 21, 9, True), np.array([[1, -1] + [0] * 7]), (1,))
    assert w.shape == (1, 6)
    assert int(w[0, 0]) == 1 | (((1 << 11) - 1) << 21)      # element 1 = all ones
    assert int(w[0, 1]) == (1 << 10) - 1


def test_pack_rejects_out_of_range_codes():
    with pytest.raises(ValueError, match="x codes"):
        pack_port(Port("x", 8, signed=True), np.array([200]), (1,))


def test_stream_variable_beats():
    spec = HarnessSpec(top="t", inputs=(Port("x", 40),), outputs=(Port("y", 8),), go="go",
                       done="done", max_cycles=10,
                       write=WritePort(strobe="we", fields=(Port("d", 16),), max_beats=4))
    stream, n = pack_stimulus(spec, {"x": np.array([5, 6])},
                              {"d": np.array([[1, 2, 3], [4, 5, 6]])}, n_beats=[1, 3])
    assert n == 2
    assert stream.tolist() == [1, 1, 5, 0, 3, 4, 5, 6, 6, 0]
    out, cycles = unpack_results(spec, np.array([7, 11, 8, 12], "<u4"), 2)
    assert out["y"].tolist() == [7, 8] and cycles.tolist() == [11, 12]


def test_generated_harness_drives_the_described_ports():
    src = generate_harness(hc.get_bench("gap").spec)
    for needle in ("#include \"Vgap_core.h\"", "top->w_valid = 1;", "top->w_addr = b;",
                   "top->r[i] = w[0 + i];", "top->go = 1;", "while (!top->done)",
                   "top->tau2 = (uint64_t)w["):
        assert needle in src
    fit = generate_harness(hc.get_bench("fit").spec)
    assert "top->wr_rst = 1;" in fit and "top->wr_data = bw[0];" in fit


def test_missing_toolchain_names_the_packages(monkeypatch):
    monkeypatch.setattr(vl.shutil, "which", lambda name: None)
    assert not vl.verilator_available()
    with pytest.raises(vl.VerilatorNotFound, match="apt-get install .*verilator"):
        vl.require_verilator()
    with pytest.raises(vl.VerilatorNotFound, match="'verilator'"):
        vl.build_model(hc.get_bench("fit").spec, "module fit_core; endmodule")


def test_verilog_is_cached_by_source_digest():
    text = hc.get_bench("fit").verilog()
    cached = list((vl.cache_root().parent / "verilog").glob("fit_core-*.v"))
    assert "module fit_core(" in text and any(p.read_text() == text for p in cached)
    assert len(hc._source_digest()) == 64


def test_cache_root_outside_the_source_tree(monkeypatch, tmp_path):
    assert REPO not in vl.cache_root().parents
    monkeypatch.setenv("GEARCONTACT_CACHE_DIR", str(tmp_path))
    assert vl.cache_root() == tmp_path / "verilator"


# ---------------------------------------------------------------------------------
# generic harness on a small hand-written core (wide ports, bursts, timing)
# ---------------------------------------------------------------------------------
TOY_VERILOG = """
module toy(input clk, input rst, input go, input wr_rst, input wr_en,
           input [31:0] wr_data, input [99:0] x, input [47:0] y,
           output reg done, output reg [99:0] xo, output reg [47:0] yo,
           output reg [31:0] sum, output reg [7:0] nw);
  reg [3:0] cnt;
  reg busy;
  always @(posedge clk) begin
    if (rst) begin
      done <= 0; busy <= 0; cnt <= 0; sum <= 0; nw <= 0; xo <= 0; yo <= 0;
    end else begin
      if (wr_rst) begin sum <= 0; nw <= 0; end
      else if (wr_en) begin sum <= sum + wr_data; nw <= nw + 1; end
      if (go && !busy) begin busy <= 1; done <= 0; cnt <= 1; xo <= ~x; yo <= y + 1; end
      else if (busy) begin
        cnt <= cnt + 1;
        if (cnt == 4) begin busy <= 0; done <= 1; end
      end
    end
  end
endmodule
"""
TOY_SPEC = HarnessSpec(
    top="toy", go="go", done="done", max_cycles=50,
    inputs=(Port("x", 50, 2), Port("y", 48, signed=True)),
    outputs=(Port("xo", 50, 2), Port("yo", 48, signed=True), Port("sum", 32, signed=True),
             Port("nw", 8)),
    write=WritePort(strobe="wr_en", clear="wr_rst", fields=(Port("wr_data", 32, signed=True),),
                    max_beats=20))


@pytest.fixture(scope="module")
def toy_model():
    if not vl.verilator_available():
        pytest.skip(f"Verilator toolchain not installed: {vl.INSTALL_HINT}")
    return vl.build_model(TOY_SPEC, TOY_VERILOG)


def test_toy_core_wide_ports_bursts_and_cycles(toy_model):
    rng = np.random.default_rng(7)
    n = 300
    x = rng.integers(0, 1 << 50, (n, 2))
    y = rng.integers(-(1 << 47), 1 << 47, n)
    y[:2] = [(1 << 47) - 1, -1]
    data = rng.integers(-(1 << 31), 1 << 31, (n, 20))
    nb = rng.integers(0, 21, n)
    run = toy_model.run({"x": x, "y": y}, {"wr_data": data}, nb)
    np.testing.assert_array_equal(run.outputs["xo"], x ^ ((1 << 50) - 1))
    want_y = (y + 1 + (1 << 47)) % (1 << 48) - (1 << 47)
    np.testing.assert_array_equal(run.outputs["yo"], want_y)
    masked = np.where(np.arange(20) < nb[:, None], data, 0)
    want_sum = (masked.sum(axis=1) + (1 << 31)) % (1 << 32) - (1 << 31)
    np.testing.assert_array_equal(run.outputs["sum"], want_sum)
    np.testing.assert_array_equal(run.outputs["nw"], nb)
    assert run.cycles.tolist() == [5] * n
    assert run.sim_cycles == 2 + int((nb + 1).sum()) + 5 * n
    assert run.cycles_per_second > 0
    split = toy_model.run({"x": x, "y": y}, {"wr_data": data}, nb, jobs=3)
    assert split.processes == 3 and split.sim_cycles == run.sim_cycles + 2 * 2
    for name in run.outputs:
        np.testing.assert_array_equal(split.outputs[name], run.outputs[name])
    np.testing.assert_array_equal(split.cycles, run.cycles)


def test_toy_core_second_build_is_cached(toy_model):
    again = vl.build_model(TOY_SPEC, TOY_VERILOG)
    assert again.cached and again.binary == toy_model.binary and again.build_seconds == 0.0
    assert vl.cache_root() in again.binary.parents


def test_toy_core_timeout_is_an_error(toy_model):
    slow = dataclasses.replace(TOY_SPEC, max_cycles=3)
    model = dataclasses.replace(toy_model, spec=slow)
    with pytest.raises(RuntimeError, match="no done within"):
        model.run({"x": np.zeros((1, 2), np.int64), "y": np.zeros(1, np.int64)},
                  {"wr_data": np.zeros((1, 1), np.int64)})


@needs_verilator
def test_build_error_carries_the_log(tmp_path, monkeypatch):
    monkeypatch.setenv("GEARCONTACT_CACHE_DIR", str(tmp_path))
    with pytest.raises(vl.VerilatorBuildError, match="toy"):
        vl.build_model(TOY_SPEC, "module toy(input clk); syntax error here endmodule")
    assert not list((tmp_path / "verilator").glob("toy-*"))       # nothing half-built


# ---------------------------------------------------------------------------------
# the real cores: default bulk equivalence (>= 1,000 random vectors + corners)
# ---------------------------------------------------------------------------------
#: chain_exact differs from chain only by the HertzCore ROMs that hertz_exact already
#: checks here; its own 1,000-vector run (an 18 s Verilator build on a fresh machine)
#: is in the slow suite, and tests/preview/test_rtl_engine.py runs it on a stencil.
#: hertz_pipe_exact likewise differs from hertz_pipe by the tables only (the Amaranth
#: tests run it under stalls, tests/preview/hertz/test_rtl_pipe.py).
#: chain_pipe is the fit core + hertz_pipe, both checked here (its Amaranth test runs in
#: tests/preview/test_chain_pipe.py).
#: comb_exact likewise (16 s with its build; slow suite here, 1,000 vectors passing);
#: tests/preview/test_chain_rtl.py checks it in the Amaranth simulator by default.
#: hertz_line wraps the HertzCore checked here (its own build takes ~45 s; 100,017
#: vectors passing, docs/hertz.md sec. 6); tests/preview/hertz/test_rtl_line.py checks it
#: in the Amaranth simulator by default.
_SLOW_BUILDS = ("chain_exact", "hertz_pipe_exact", "chain_pipe", "comb_exact", "hertz_line")
#: Cores with their own 10,000-vector default run (test_line_cores_10k).
_LINE_CORES = {"chain_line": 811, "hertz_line_exact": 759}
_DEFAULT_CORES = [pytest.param(c, marks=pytest.mark.slow) if c in _SLOW_BUILDS else c
                  for c in hc.CORE_NAMES if c not in _LINE_CORES]
LINE_VECTORS = 10_000


@needs_verilator
@pytest.mark.parametrize("core", _DEFAULT_CORES)
def test_bulk_equivalence(core):
    _assert_equivalent(_report(core, DEFAULT_VECTORS, SEED), DEFAULT_VECTORS)


@needs_verilator
@pytest.mark.parametrize("core", sorted(_LINE_CORES))
def test_line_cores_10k(core):
    """The line chain (fit core -> line core, preview.chain_line_rtl.ChainLineCore) and
    the line core with the exact Hertz tables: RTL == golden bit for bit on every output
    port over 10,000 seeded random vectors + the corner cases, and the cycle count of the
    design for every vector (811 = 52 fit + 759 line core; 759). Their Verilator builds
    take ~1-3 min on a fresh machine (cached afterwards, then ~10-30 s each here)."""
    rep = _report(core, LINE_VECTORS, SEED + 28)
    _assert_equivalent(rep, LINE_VECTORS)
    assert rep.cycles_expected == _LINE_CORES[core]


@needs_verilator
def test_pipe_streams_one_input_per_clock():
    """hertz_pipe back to back: II = 1 measured in the binary, latency = pipe_latency."""
    from gearcontact.preview.hertz.rtl_pipe import pipe_latency
    rep = _report("hertz_pipe", 200, SEED + 5)
    assert rep.streaming and rep.measured_ii == 1.0
    assert rep.cycles == pipe_latency() == 90
    # the serialized core needs its whole run per evaluation
    assert _report("hertz", 0, SEED).initiation_interval == 756


@needs_verilator
def test_pipe_under_random_bubbles_and_stalls():
    """Random in_valid bubbles and out_ready stalls in the Verilator harness: every result
    bit-exact and in order, latency never below the pipeline depth and above it only
    when stalls occurred."""
    from gearcontact.preview.hertz.rtl_pipe import pipe_latency
    bench = hc.get_bench("hertz_pipe")
    st = bench.stimulus(2_000, SEED + 6)
    run = hc.verilator_model("hertz_pipe").run(*bench.ports(st), bubble_per_mille=300,
                                               stall_per_mille=300, seed=9)
    gold = bench.golden(st)
    for port, want in gold.items():
        np.testing.assert_array_equal(run.outputs[port], want, err_msg=port)
    assert run.cycles.min() == pipe_latency() and run.cycles.max() > pipe_latency()
    assert run.initiation_interval > 1.0


@needs_verilator
@pytest.mark.parametrize("n_samples", [1, 37, 256])
def test_gap_other_pass_lengths(n_samples):
    rep = _report("gap", 100, SEED + n_samples, n_samples=n_samples)
    _assert_equivalent(rep, 100)
    assert rep.cycles == gap_latency(n_samples, GAP_LANES)


@needs_verilator
def test_a_wrong_golden_is_reported(monkeypatch):
    bench = hc.get_bench("fit")

    def off_by_one(st):
        cols = bench.golden(st)
        cols["c4"] = cols["c4"] + (np.arange(len(st)) == 3)
        return cols

    monkeypatch.setitem(hc.BENCHES, "fit", dataclasses.replace(bench, golden=off_by_one))
    rep = _report("fit", 10, SEED)
    assert rep.mismatches == 1 and not rep.ok
    assert rep.mismatch_examples[0]["vector"] == 3
    assert rep.mismatch_examples[0]["port"] == "c4"


@needs_verilator
def test_verilator_and_amaranth_agree_on_fit_corners():
    st = hc.get_bench("fit").stimulus(0, SEED)
    a = _report("fit", 0, SEED, simulator="amaranth", stim=st)
    v = _report("fit", 0, SEED, stim=st)
    _assert_equivalent(a, 0)
    _assert_equivalent(v, 0)


def test_binary_run_from_a_shell_prints_its_speed():
    if not vl.verilator_available():
        pytest.skip(f"Verilator toolchain not installed: {vl.INSTALL_HINT}")
    model = hc.verilator_model("fit")
    proc = subprocess.run([str(model.binary)], capture_output=True, text=True, check=False)
    assert proc.returncode == 2 and "usage" in proc.stderr


# ---------------------------------------------------------------------------------
# slow suite: >= 100,000 random vectors per core (python -m pytest --runslow tests/hw)
# ---------------------------------------------------------------------------------
@pytest.mark.slow
@needs_verilator
@pytest.mark.parametrize("core", hc.CORE_NAMES)
def test_bulk_equivalence_100k(core):
    rep = _report(core, SLOW_VECTORS, SEED + 1, jobs=os.cpu_count() or 1)
    _assert_equivalent(rep, SLOW_VECTORS)


# ---------------------------------------------------------------------------------
# descriptors: every harness width derived from the component's signature
# ---------------------------------------------------------------------------------
@pytest.mark.parametrize("core", ["gap", "fit", "hertz", "hertz_pipe", "chain", "hertz_line",
                                  "chain_line"])
def test_derived_spec_matches_the_verilog_ports(core):
    """Each derived port (operands, burst fields, outputs) has the direction and total
    width of the exported Verilog's port (independent truth: Amaranth's backend), and
    the spec names every Verilog port except the declared control/protocol ones."""
    from gearcontact.hw.verilog_export import verilog_ports
    bench = hc.get_bench(core)
    spec = bench.spec
    ports = {n: (d, w) for d, n, w in verilog_ports(bench.verilog(), spec.top)}
    fields = spec.write.fields if spec.write else ()
    for p in spec.inputs + fields:
        assert ports[p.name] == ("input", p.width), p
    for p in spec.outputs:
        assert ports[p.name] == ("output", p.width), p
    named = {p.name for p in spec.inputs + spec.outputs + fields} | set(bench.control) \
        | {spec.go, spec.done, spec.clock, spec.reset}
    if spec.write:
        named |= {spec.write.strobe, spec.write.addr, spec.write.clear}
    if spec.stream:
        named |= set(dataclasses.astuple(spec.stream))
    assert set(ports) <= named, set(ports) - named


def test_derived_spec_signedness_and_arrays():
    gap = hc.get_bench("gap").spec
    assert Port("r", 21, 9, True) in gap.inputs and Port("tau2", 64) in gap.inputs
    assert gap.write.fields == (Port("w_g", 24, 3, True), Port("w_n", 21, 3, True))
    hz = {p.name: p for p in hc.get_bench("hertz").spec.outputs}
    assert hz["alpha"] == Port("alpha", 32) and hz["a"] == Port("a", 32, signed=True)
    assert hz["flags"] == Port("flags", 7)


def test_descriptor_with_an_unknown_port_is_refused():
    bench = dataclasses.replace(hc.get_bench("hertz"), control=("go_chain", "no_such"))
    with pytest.raises(ValueError, match="no_such"):
        hc.derive_spec(bench)


#: The line cores' vector files through their RTL: (core, random vectors); the default
#: suite runs the line chain (fit + line core; its Verilator build test_line_cores_10k
#: caches), ~5 s; the slow suite every line core on 10,000.
_LINE_FILES = [("chain_line", 300),
               *(pytest.param(c, 10_000, marks=pytest.mark.slow)
                 for c in ("hertz_line", "hertz_line_exact", "chain_line"))]


@needs_verilator
@pytest.mark.parametrize("core, count", _LINE_FILES)
def test_line_cores_rtl_equals_their_vector_files(tmp_path, core, count):
    """``gearcontact vectors``' line-core files (the host's path: inputs, outputs, lift)
    drive the RTL as the README beside them says: the core on ``W << lift``,
    ``L << lift`` (Verilator), its outputs unlifted (``unlift_line_array``: a rounding
    shift of a in line mode, a lifted ellipse flagged ``length_range``; the chain's fit
    bits kept) equal every expected output field bit for bit, and every vector takes
    the file's cycle count."""
    from gearcontact.hw.vectors import export_vectors, read_hex, read_jsonl
    from gearcontact.preview.hertz.line_vec import LineCodesArray, unlift_line_array
    from gearcontact.preview.stimulus import Stimulus

    export_vectors(tmp_path, cores=(core,), count=count, seed=SEED)
    x = read_hex(tmp_path / f"{core}_in.hex", core, "in")
    y = read_hex(tmp_path / f"{core}_out.hex", core, "out")
    recs = read_jsonl(tmp_path / f"{core}.jsonl")
    lift = y["lift"]
    fields = {"W": x["W"] << lift, "L": x["L"] << lift, "e_prime": x["e_prime"]}
    fields.update({"gaps": x["wr_data"]} if core == "chain_line"
                  else {"A": x["A"], "B": x["B"]})
    st = Stimulus(core, fields, tuple(r["label"] for r in recs), SEED)
    try:
        outs, cycles, *_ = hc.simulate(hc.get_bench(core), st)
    except hc.CoreUnavailable as exc:
        pytest.skip(str(exc))
    outs = {k: np.asarray(v, np.int64) for k, v in outs.items()}
    fit_bits = outs["flags"] & ~0xFF
    raw = LineCodesArray(outs["a"], outs["b"], outs["p_max"], outs["k"], outs["A_min"],
                         outs["B_max"], outs["mode"], outs["scale"], outs["flags"] & 0xFF)
    got = unlift_line_array(raw, lift)
    outs.update(a=got.a_code, b=got.b_code, p_max=got.p_max_code, k=got.k_code,
                mode=got.mode, flags=got.flags | fit_bits)
    assert (lift > 0).sum() >= count // 20
    for name in (f.name for f in hc.get_bench(core).spec.outputs):
        bad = np.flatnonzero(outs[name] != y[name])
        assert bad.size == 0, (name, bad[:5], outs[name][bad[:5]], y[name][bad[:5]])
    assert set(np.asarray(cycles).tolist()) == {recs[0]["cycles"]}
