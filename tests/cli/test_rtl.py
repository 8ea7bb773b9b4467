"""``gearcontact rtl sim`` / ``rtl verilog`` through gearcontact.cli.main."""

import dataclasses
import json

import numpy as np
import pytest

from gearcontact.cli import main
from gearcontact.hw import harness_cores as hc
from gearcontact.hw import verilator as vl

needs_verilator = pytest.mark.skipif(
    not vl.verilator_available(), reason=f"Verilator toolchain not installed: {vl.INSTALL_HINT}")


def _json(capsys) -> dict:
    return json.loads(capsys.readouterr().out)


@needs_verilator
def test_sim_json_fit(capsys):
    assert main(["rtl", "sim", "--core", "fit", "--vectors", "200", "--seed", "3",
                 "--json"]) == 0
    out = _json(capsys)
    assert out["core"] == "fit" and out["simulator"] == "verilator"
    assert out["cycles"] == out["cycles_expected"] == 52
    assert out["vectors"] == 200 + out["corner_vectors"] and out["corner_vectors"] > 5
    assert out["mismatches"] == 0 and out["ok"] and out["seed"] == 3
    assert out["cycles_per_second"] > 0 and "Verilator" in out["simulator_version"]


@needs_verilator
def test_sim_json_hertz_pipe(capsys):
    """The II = 1 core: today's keys plus initiation_interval (measured, 1 edge) and
    latency_cycles (90, the pipeline depth); the serialized core reports 756 for both."""
    assert main(["rtl", "sim", "--core", "hertz_pipe", "--vectors", "100", "--json"]) == 0
    out = _json(capsys)
    assert out["mismatches"] == 0 and out["ok"]
    assert out["initiation_interval"] == 1.0
    assert out["latency_cycles"] == out["cycles"] == out["cycles_expected"] == 90
    assert main(["rtl", "sim", "--core", "hertz", "--vectors", "0", "--json"]) == 0
    out = _json(capsys)
    assert out["initiation_interval"] == out["latency_cycles"] == 756


@needs_verilator
def test_sim_text_hertz(capsys):
    assert main(["rtl", "sim", "--core", "hertz", "--vectors", "20"]) == 0
    text = capsys.readouterr().out
    assert "756 per evaluation (expected 756, data independent)" in text
    assert "mismatches   0" in text and "cycles/s" in text


@needs_verilator
def test_sim_gap_other_length(capsys):
    assert main(["rtl", "sim", "--core", "gap", "--vectors", "30", "--samples", "40",
                 "--no-corners", "--json"]) == 0
    out = _json(capsys)
    assert out["vectors"] == 30 and out["corner_vectors"] == 0
    assert out["cycles"] == 16 + 3 + 4 + 5          # L + ceil(N/L) + log2 L + 5


def test_sim_amaranth_simulator(capsys):
    assert main(["rtl", "sim", "--core", "fit", "--vectors", "3", "--no-corners",
                 "--simulator", "amaranth", "--json"]) == 0
    out = _json(capsys)
    assert out["simulator"] == "amaranth" and out["simulator_version"] is None
    assert out["vectors"] == 3 and out["mismatches"] == 0 and out["cycles"] == 52


@pytest.mark.parametrize("simulator", ["verilator", "amaranth"])
def test_sim_mismatch_exits_nonzero(capsys, monkeypatch, simulator):
    if simulator == "verilator" and not vl.verilator_available():
        pytest.skip(f"Verilator toolchain not installed: {vl.INSTALL_HINT}")
    bench = hc.get_bench("fit")

    def wrong(st):
        cols = bench.golden(st)
        cols["flags"] = cols["flags"] ^ (np.arange(len(st)) == 1)
        return cols

    monkeypatch.setitem(hc.BENCHES, "fit", dataclasses.replace(bench, golden=wrong))
    assert main(["rtl", "sim", "--core", "fit", "--vectors", "2", "--no-corners",
                 "--simulator", simulator, "--json"]) == 4
    out = _json(capsys)
    assert out["mismatches"] == 1 and not out["ok"]
    assert out["mismatch_examples"][0]["vector"] == 1
    assert out["mismatch_examples"][0]["port"] == "flags"


def test_sim_without_verilator_names_the_package(capsys, monkeypatch):
    monkeypatch.setattr(vl.shutil, "which", lambda name: None)
    assert main(["rtl", "sim", "--core", "gap", "--vectors", "1",
                 "--simulator", "verilator"]) == 2
    err = capsys.readouterr().err
    assert "gearcontact rtl sim: error:" in err and "apt-get install" in err
    assert "verilator" in err


def test_sim_bad_arguments(capsys):
    assert main(["rtl", "sim", "--core", "fit", "--samples", "8"]) == 2
    assert "--samples = 8" in capsys.readouterr().err
    assert main(["rtl", "sim", "--core", "fit", "--vectors", "-1"]) == 2
    with pytest.raises(SystemExit):
        main(["rtl", "sim", "--core", "nope"])


def test_verilog_export(tmp_path, capsys):
    assert main(["rtl", "verilog", "--core", "hertz", "--out", str(tmp_path)]) == 0
    v = (tmp_path / "hertz_core.v").read_text()
    assert "module hertz_core(" in v
    readme = (tmp_path / "hertz_core.README.md").read_text()
    for row in ("| A | input | 32 |", "| flags | output | 7 |", "| go | input | 1 |"):
        assert row in readme
    assert "756 cycles" in readme
    assert "hertz_core.v" in capsys.readouterr().out
    assert list(tmp_path.iterdir()) and not (tmp_path / "obj").exists()


def test_verilog_export_stencil_core_readme(tmp_path):
    assert main(["rtl", "verilog", "--core", "fit", "--out", str(tmp_path / "new")]) == 0
    readme = (tmp_path / "new" / "fit_core.README.md").read_text()
    assert "`wr_en` high, after a one-cycle `wr_rst` pulse: wr_data" in readme


def test_verilog_export_stream_core_readme(tmp_path):
    assert main(["rtl", "verilog", "--core", "hertz_pipe", "--out", str(tmp_path)]) == 0
    readme = (tmp_path / "hertz_pipe.README.md").read_text()
    assert "Protocol (stream, initiation interval 1)" in readme
    assert "`out_valid` 90 edges later" in readme
    assert "| in_ready | output | 1 |" in readme and "| A | input | 32 |" in readme


@needs_verilator
def test_sim_gap_lean(capsys):
    """The 15-DSP gap lane: bit-exact against its golden model, the gap core's cycles."""
    assert main(["rtl", "sim", "--core", "gap_lean", "--vectors", "60", "--samples", "40",
                 "--json"]) == 0
    out = _json(capsys)
    assert out["mismatches"] == 0 and out["vectors"] == 60 + out["corner_vectors"]
    assert out["cycles"] == 16 + 3 + 4 + 5          # L + ceil(N/L) + log2 L + 5


@pytest.mark.parametrize("argv, named", [
    (["--core", "hertz", "--timeout", "-1"], "--timeout (s) = -1.0"),
    (["--core", "hertz", "--timeout", "nan"], "--timeout (s) = nan"),
    # --lanes sets the gap sweep only: on another core it was ignored (a long run of
    # the fixed netlist instead)
    (["--core", "tri_core", "--lanes", "5"], "--core tri_core has a fixed netlist")])
def test_synth_options_checked_before_yosys(tmp_path, capsys, argv, named):
    from gearcontact.hw import synth as S
    try:
        S.require_yosys()
    except RuntimeError:
        pytest.skip("no yosys: the tool check comes first")
    out = tmp_path / "o"
    assert main(["rtl", "synth", "--out", str(out), *argv]) == 2
    assert named in capsys.readouterr().err
    assert not out.exists()
