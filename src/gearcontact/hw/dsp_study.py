"""The DSP48E1 per-lane study: where the gap core's 30 L + 18 comes from, and its exact
split forms.

:data:`DSP_STUDY_VERILOG` holds one registered multiplier per module at the gap core's
operand widths, in the published form and as partial products fitting the DSP48E1's
25 x 18 signed multiplier; :func:`dsp_study` synthesizes it with Yosys
(``synth_xilinx -family xc7``, :func:`gearcontact.hw.synth.require_yosys`), one kept
module per multiplier, and counts the slices per lane and per core. ``GapCore`` builds
the split forms with :mod:`gearcontact.preview.gap.rtl_mul`; this keeps them in Verilog
(docs/hardware.md).
"""

from __future__ import annotations

import re
import subprocess
from pathlib import Path

from .synth import parse_stat, require_yosys

__all__ = ["DSP_STUDY_VERILOG", "DSP_STUDY_COUNTS", "parse_stat_modules", "dsp_study"]

#: One registered multiplier per module, at the gap core's operand widths
#: (:mod:`gearcontact.preview.gap.golden` formats): ``pose`` R p (21 x 24, 9 per core),
#: ``dot`` n . d (21 x 25, 3 per lane), ``gn`` gamma n (27 x 21, 3 per lane), ``sq``
#: e^2 (27 x 27, 3 per lane); ``gn_split`` / ``sq_split`` are the same products written
#: as partial products that fit the DSP48E1's 25 x 18 signed multiplier (gamma and e
#: split at bit 17 = the DSP cascade shift). The split forms are exact identities:
#: g n = (g_hi 2^17 + g_lo) n and e^2 = e_hi^2 2^34 + e_hi e_lo 2^18 + e_lo^2.
DSP_STUDY_VERILOG = """
module pose(input clk, input signed [20:0] a, input signed [23:0] b, output reg signed [44:0] p);
  reg signed [20:0] ra; reg signed [23:0] rb;
  always @(posedge clk) begin ra <= a; rb <= b; p <= ra * rb; end
endmodule
module dot(input clk, input signed [20:0] a, input signed [24:0] b, output reg signed [45:0] p);
  reg signed [20:0] ra; reg signed [24:0] rb;
  always @(posedge clk) begin ra <= a; rb <= b; p <= ra * rb; end
endmodule
module gn(input clk, input signed [26:0] a, input signed [20:0] b, output reg signed [47:0] p);
  reg signed [26:0] ra; reg signed [20:0] rb;
  always @(posedge clk) begin ra <= a; rb <= b; p <= ra * rb; end
endmodule
module sq(input clk, input signed [26:0] a, output reg [53:0] p);
  reg signed [26:0] ra;
  always @(posedge clk) begin ra <= a; p <= ra * ra; end
endmodule
module gn_split(input clk, input signed [26:0] a, input signed [20:0] b,
                output reg signed [47:0] p);
  reg signed [26:0] ra; reg signed [20:0] rb;
  wire signed [17:0] lo = $signed({1'b0, ra[16:0]});
  wire signed [9:0] hi = ra[26:17];
  wire signed [38:0] p_lo = lo * rb;
  wire signed [30:0] p_hi = hi * rb;
  always @(posedge clk) begin ra <= a; rb <= b; p <= (p_hi <<< 17) + p_lo; end
endmodule
module sq_split(input clk, input signed [26:0] a, output reg [53:0] p);
  reg signed [26:0] ra;
  wire signed [17:0] lo = $signed({1'b0, ra[16:0]});
  wire signed [9:0] hi = ra[26:17];
  wire signed [35:0] p_ll = lo * lo;
  wire signed [27:0] p_hl = hi * lo;
  wire signed [19:0] p_hh = hi * hi;
  always @(posedge clk) begin ra <= a; p <= (p_hh <<< 34) + (p_hl <<< 18) + p_ll; end
endmodule
module core(input clk, input signed [26:0] a, input signed [26:0] b, output [44:0] o0,
            output [45:0] o1, output [47:0] o2, output [53:0] o3, output [47:0] o4,
            output [53:0] o5);
  pose u0(clk, a[20:0], b[23:0], o0);
  dot u1(clk, a[20:0], b[24:0], o1);
  gn u2(clk, a, b[20:0], o2);
  sq u3(clk, a, o3);
  gn_split u4(clk, a, b[20:0], o4);
  sq_split u5(clk, a, o5);
endmodule
"""
#: Multipliers of each kind in the gap core (``per_lane``, ``per_core``).
DSP_STUDY_COUNTS = {"pose": (0, 9), "dot": (3, 0), "gn": (3, 0), "sq": (3, 0),
                    "gn_split": (3, 0), "sq_split": (3, 0)}


def parse_stat_modules(text: str) -> dict:
    """``{module: parse_stat(block)}`` for a hierarchical ``stat`` report."""
    out, name, block = {}, None, []
    for line in text.splitlines() + ["=== end ==="]:
        mt = re.match(r"^=== (.+) ===$", line.strip())
        if mt:
            if name is not None:
                out[name] = parse_stat("\n".join(block))
            name, block = mt.group(1), []
        else:
            block.append(line)
    return out


def dsp_study(workdir, *, timeout: float | None = None) -> dict:
    """Synthesize :data:`DSP_STUDY_VERILOG` with one kept module per multiplier.

    Returns
    -------
    dict
        ``{module: cell counts}`` plus ``"per_lane"`` (published form ``dot + gn + sq``)
        and ``"per_lane_split"`` (``dot + gn_split + sq_split``) DSP48E1 counts and
        ``"per_core"`` (the nine pose products).
    """
    cmd = require_yosys()
    work = Path(workdir)
    work.mkdir(parents=True, exist_ok=True)
    (work / "core.v").write_text(DSP_STUDY_VERILOG)
    mods = " ".join(DSP_STUDY_COUNTS)
    script = (f"read_verilog core.v; setattr -mod -set keep_hierarchy 1 {mods}; "
              "synth_xilinx -family xc7 -top core -noiopad; tee -q -o stat.txt stat")
    proc = subprocess.run(cmd + ["-q", "-l", "yosys.log", "-p", script], cwd=work,
                          capture_output=True, text=True, timeout=timeout, check=False)
    if proc.returncode != 0:
        raise RuntimeError(f"yosys failed on the DSP study: {(proc.stderr or proc.stdout)[-2000:]}")
    res = parse_stat_modules((work / "stat.txt").read_text())
    d = {m: res[m]["DSP48E1"] for m in DSP_STUDY_COUNTS}
    res["per_lane"] = 3 * (d["dot"] + d["gn"] + d["sq"])
    res["per_lane_split"] = 3 * (d["dot"] + d["gn_split"] + d["sq_split"])
    res["per_core"] = 9 * d["pose"]
    return res
