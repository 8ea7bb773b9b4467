"""Stage A/B gap core in Amaranth 0.5: ``GapCore(lanes=L)``, bit-exact and cycle-exact.

The core implements :mod:`.golden` (formats, rounding, tie rules) with the schedule of
:func:`.golden.gap_latency`; every register below is named after the golden model's
intermediate it holds. Only the default word formats (docs/spec.md sec. 6) are built.

Interface (all synchronous to the ``sync`` domain, active-high synchronous reset)

=============  =====  ==================  ==========================================
port           dir    shape               meaning (format)
=============  =====  ==================  ==========================================
w_valid        in     1                   write one gear sample this cycle
w_ready        out    1                   ``~busy``: a write happens on valid & ready
w_addr         in     log2(max_samples)   sample index i (bank i mod L, word i div L)
w_g            in     3 x signed(24)      sample position g_i, Q(24,16) mm
w_n            in     3 x signed(21)      sample normal n_i, Q(21,19), ``|c| <= 2^19``
r              in     9 x signed(21)      rotation, row-major, Q(21,19), ``|c| <= 2^19``
t, p           in     3 x signed(24)      translation and body point, Q(24,16) mm
tau2           in     unsigned(64)        gate tau^2, UQ(64,32) mm^2 (``ceil``-rounded)
n_samples      in     unsigned(16)        N, 1 <= N <= max_samples
go             in     1                   start: accepted when ``~busy`` and N in range
busy           out    1                   a pass is running (from accept to done)
done           out    1                   the last pass completed (held until next go)
done_pulse     out    1                   first cycle of ``done``: outputs below new
gap            out    signed(32)          min_gap, Q(32,16) mm; 0x7FFFFFFF if ~valid
idx            out    unsigned(16)        min_idx; 0xFFFF if ~valid
valid          out    1                   a lane passed the gate and no overflow
overflow       out    1                   p' = R p + t left Q(24,16) (forces ~valid)
n_error        out    1                   last go had N outside [1, max_samples]
=============  =====  ==================  ==========================================

Operands r, t, p, tau2 and n_samples are captured on the accepting edge and may change
afterwards; the sample banks must not change during a pass (``w_ready`` is low while
busy, so writes wait). The input contract ``|r|, |n| <= 2^19`` is the host's job
(:func:`.golden.quantize_pass` / :func:`.golden.check_codes` enforce it); the
datapath widths are sized for it.

Behaviour on protocol corner cases
    * the protocol of every core (:mod:`gearcontact.preview.core`): accepting ``go``
      clears ``done``; ``done`` is set on the last edge and stays 1 until the next
      accepted ``go``; ``done_pulse`` is 1 for exactly its first cycle. The outputs
      change only on that edge.
    * ``go`` while busy is ignored (no restart, no queueing); the running pass
      completes with its own operands and latency.
    * ``go`` with N = 0 or N > max_samples is refused: the core stays idle, ``done``
      keeps its value and ``n_error`` rises (held until the next accepted go) instead
      of a pass running.
    * synchronous reset mid-run abandons the pass: busy, done, done_pulse, valid and
      overflow go to 0 and gap/idx to their sentinels; the sample banks keep their
      contents (memories are not reset), so the next go runs a full, correct pass.

Schedule (edge E1 accepts go; see :mod:`.golden` for the count)
    E1 capture; E2 nine R p products (44 b); E3 48-b accumulate + round -> p' and
    overflow; p' shifts one lane per cycle (lane l has it after E(3+l)); lane l reads
    its bank word k so that stage A (d, gamma) registers at E(4+l+k) and stage B
    (e, rho, running-minimum update) at E(5+l+k); keys register at E(L+K+4); the
    log2(L) tree levels at E(L+K+5) ...; outputs and ``done`` at E(L+K+5+log2 L).
    Stage B chains gamma n_k (32 x 21 b), the round-shift add, e_k^2 (27 x 27 b), the
    3-input sum and the 64-bit compare: it is the core's critical path (the paper's
    "perp^2 multiplier chain", docs/spec.md sec. 7 -- constrain the clock). In steady state
    (N >> L) the lanes consume L samples per cycle.

DSP48E1 per lane (``synth_xilinx -family xc7``; the pose adds 9 x 2 = 18 per core)
    ``split_products=True`` (default) writes gamma n_k and e_k^2 as exact split partial
    products (:mod:`.rtl_mul`): 3 x (n.d 2 + gamma n 2 + e^2 3) = 21 per lane. With
    ``split_products=False`` they are plain ``*`` as in the published design, which
    Yosys tiles into 4 slices each: 3 x (2 + 4 + 4) = 30 per lane (DSP = 30 L + 18).
    Outputs and cycle counts are identical; only the netlist differs.
    ``variant="lean"`` (:mod:`.variants`) squares e_k in 18 bits with a saturation flag:
    3 x (2 + 2 + 1) = 15 per lane (DSP = 15 L + 18), same cycles; its residual register
    is 36 bits wide and the gate compares against ``min(tau2, 2^36 - 1)``.
"""

from __future__ import annotations

from amaranth.hdl import Array, C, Module, Mux, Signal, signed, unsigned
from amaranth.lib import data, memory, wiring
from amaranth.lib.wiring import In, Out

from ...validation import InputRangeError
from ..simulation import read_ports, run_testbench, run_to_done
from .golden import DEFAULT_FORMAT, IDX_BITS, IDX_SENTINEL, GapCodes, gap_latency
from .reference import check_lanes
from .rtl_mul import split_mul, split_square
from .variants import LEAN_E_BITS, check_variant

__all__ = ["GapCore", "GapLaneProbe", "convert_verilog", "lane_verilog", "load_gap_vector",
           "read_gap_codes", "simulate_gap_core"]

_F = DEFAULT_FORMAT
CW, NW, RF = _F.coord_bits, _F.normal.bits, _F.normal_frac      # 24, 21, 19
COORD3 = data.ArrayLayout(signed(CW), 3)
NORM3 = data.ArrayLayout(signed(NW), 3)
SAMPLE = data.StructLayout({"g": COORD3, "n": NORM3})


class GapCore(wiring.Component):
    """Gap kernel with ``lanes`` lanes and per-lane sample banks (see module docstring).

    Parameters
    ----------
    lanes : int
        Lane count L, power of two in [8, 64].
    max_samples : int
        Sample capacity, a power of two >= 2 L (default ``16 L``); each lane owns a
        bank of ``max_samples / L`` words of 135 bits.
    split_products : bool
        Build stage B's gamma n_k and e_k^2 from split partial products (21 DSP48E1
        per lane instead of 30; bit- and cycle-identical). False gives the published
        netlist with plain multipliers, for side-by-side synthesis.
    variant : {"published", "lean"}
        Datapath variant (:mod:`.variants`): ``"lean"`` is 15 DSP48E1 per lane and
        matches ``gap_golden_codes(..., variant="lean")``; it needs split products.
    """

    def __init__(self, *, lanes: int = 16, max_samples: int | None = None,
                 split_products: bool = True, variant: str = "published"):
        self.lanes = check_lanes(lanes)
        self.split_products = bool(split_products)
        self.variant = check_variant(variant)
        if self.variant == "lean" and not self.split_products:
            raise InputRangeError("split_products", split_products,
                                  "True with variant='lean' (its gamma n is split)")
        self.max_samples = 16 * self.lanes if max_samples is None else max_samples
        ms = self.max_samples
        if isinstance(ms, bool) or not isinstance(ms, int) or ms < 2 * self.lanes \
                or ms & (ms - 1) or ms > 1 << (IDX_BITS - 1):
            raise InputRangeError("max_samples", ms,
                                  f"a power of two in [{2 * self.lanes}, {1 << (IDX_BITS - 1)}]")
        self.lane_bits = self.lanes.bit_length() - 1
        self.depth = ms // self.lanes
        # lane residual register: 64 b, or 36 b (lean: 3 e^2 < 3 2^34 < its all-ones)
        self.rho_bits = 2 * LEAN_E_BITS if self.variant == "lean" else 64
        super().__init__({
            "w_valid": In(1), "w_ready": Out(1),
            "w_addr": In(unsigned(ms.bit_length() - 1)),
            "w_g": In(COORD3), "w_n": In(NORM3),
            "r": In(data.ArrayLayout(signed(NW), 9)), "t": In(COORD3), "p": In(COORD3),
            "tau2": In(unsigned(64)), "n_samples": In(unsigned(IDX_BITS)),
            "go": In(1), "busy": Out(1), "done": Out(1), "done_pulse": Out(1),
            "gap": Out(signed(_F.gap_bits), init=_F.gap_sentinel),
            "idx": Out(unsigned(IDX_BITS), init=IDX_SENTINEL),
            "valid": Out(1), "overflow": Out(1), "n_error": Out(1),
        })

    def elaborate(self, platform):
        m = Module()
        L, lb = self.lanes, self.lane_bits
        cyc_w = gap_latency(self.max_samples, L).bit_length() + 1
        kw = max(1, (self.depth - 1).bit_length())

        # ---- control: accept, capture, cycle counter --------------------------------
        busy, cyc = Signal(), Signal(cyc_w)
        r_q = Signal(data.ArrayLayout(signed(NW), 9))
        t_q, p_q = Signal(COORD3), Signal(COORD3)
        tau2_q, n_q = Signal(64), Signal(IDX_BITS)
        beats = Signal(IDX_BITS)                    # K = ceil(N / L), from n_q
        m.d.comb += [beats.eq((n_q + (L - 1)) >> lb), self.busy.eq(busy),
                     self.w_ready.eq(~busy)]
        n_ok = (self.n_samples >= 1) & (self.n_samples <= self.max_samples)
        accept = self.go & ~busy & n_ok
        out_now = busy & (cyc == L + beats + 4 + lb)
        fin_now = busy & (cyc == L + beats + 3)
        m.d.sync += self.done_pulse.eq(out_now)
        with m.If(accept):
            m.d.sync += [busy.eq(1), cyc.eq(1), r_q.eq(self.r), t_q.eq(self.t),
                         p_q.eq(self.p), tau2_q.eq(self.tau2), n_q.eq(self.n_samples),
                         self.n_error.eq(0), self.done.eq(0)]
        with m.Elif(self.go & ~busy):
            m.d.sync += self.n_error.eq(1)
        with m.Elif(out_now):
            m.d.sync += [busy.eq(0), cyc.eq(0), self.done.eq(1)]
        with m.Elif(busy):
            m.d.sync += cyc.eq(cyc + 1)

        # ---- shared pose transform: E2 products, E3 accumulate + round ---------------
        prod = [[Signal(signed(_F.product_bits), name=f"prod_{i}{j}") for j in range(3)]
                for i in range(3)]
        pp0, ovf = Signal(COORD3), Signal()
        ovf_i = []
        for i in range(3):
            for j in range(3):
                m.d.sync += prod[i][j].eq(r_q[3 * i + j] * p_q[j])
            acc = Signal(signed(_F.acc_bits), name=f"acc_{i}")
            x = Signal(signed(_F.acc_bits - RF + 1), name=f"pp_{i}")
            m.d.comb += [acc.eq(prod[i][0] + prod[i][1] + prod[i][2] + (t_q[i] << RF)),
                         x.eq((acc + (1 << (RF - 1))) >> RF)]
            m.d.sync += pp0[i].eq(x)
            ovf_i.append((x > _F.coord.max_code) | (x < _F.coord.min_code))
        m.d.sync += ovf.eq(ovf_i[0] | ovf_i[1] | ovf_i[2])

        # ---- systolic p' chain and beat tokens ---------------------------------------
        tok_layout = data.StructLayout({"act": 1, "k": unsigned(kw)})
        pch = [pp0] + [Signal(COORD3, name=f"pch_{l}") for l in range(1, L)]
        tok = [Signal(tok_layout, name=f"tok_{l}") for l in range(L + 1)]
        m.d.comb += [tok[0].act.eq(busy & (cyc >= 2) & (cyc < 2 + beats)),
                     tok[0].k.eq(cyc - 2)]
        for l in range(1, L):
            m.d.sync += pch[l].eq(pch[l - 1])
        for l in range(1, L + 1):
            m.d.sync += tok[l].eq(tok[l - 1])

        # ---- lanes -------------------------------------------------------------------
        rho_inf = (1 << self.rho_bits) - 1
        l_rho = [Signal(self.rho_bits, name=f"l_rho_{l}", init=rho_inf) for l in range(L)]
        l_gam = [Signal(signed(_F.gap_bits), name=f"l_gam_{l}") for l in range(L)]
        l_idx = [Signal(IDX_BITS, name=f"l_idx_{l}") for l in range(L)]
        wr = self.w_valid & ~busy
        for l in range(L):
            bank = memory.Memory(shape=SAMPLE, depth=self.depth, init=[])
            m.submodules[f"bank_{l}"] = bank
            wp, rp = bank.write_port(), bank.read_port()
            m.d.comb += [wp.addr.eq(self.w_addr >> lb), wp.data.g.eq(self.w_g),
                         wp.data.n.eq(self.w_n),
                         wp.en.eq(wr & ((self.w_addr & (L - 1)) == l)),
                         rp.addr.eq(tok[l].k)]
            self._lane(m, l, pch[l], rp.data, tok[l + 1], n_q, accept,
                       l_rho[l], l_gam[l], l_idx[l])

        # ---- finalize (gate -> key) and registered comparator tree -------------------
        key_inf = _F.key_inf
        keys = [Signal(_F.gap_bits, name=f"key_{l}", init=key_inf) for l in range(L)]
        gate = tau2_q
        if self.rho_bits < 64:          # lean: min(tau2, rho_inf); a held rho_inf fails
            gate = Signal(self.rho_bits, name="gate")
            m.d.comb += gate.eq(Mux(tau2_q > rho_inf, rho_inf, tau2_q))
        with m.If(fin_now):
            for l in range(L):
                mag = Mux(l_gam[l] < 0, -l_gam[l], l_gam[l])
                m.d.sync += keys[l].eq(Mux(l_rho[l] < gate, mag, key_inf))
        level = [(keys[l], C(l, max(1, lb))) for l in range(L)]
        for v in range(1, lb + 1):
            nxt = []
            for j in range(len(level) // 2):
                (ka, la), (kb, lb_) = level[2 * j], level[2 * j + 1]
                k_r = Signal(_F.gap_bits, name=f"tree{v}_{j}_key", init=key_inf)
                l_r = Signal(max(1, lb), name=f"tree{v}_{j}_lane")
                right = kb < ka                       # ties keep the lower lane
                m.d.sync += [k_r.eq(Mux(right, kb, ka)), l_r.eq(Mux(right, lb_, la))]
                nxt.append((k_r, l_r))
            level = nxt
        root_key, root_lane = level[0]

        # ---- out: re-select the signed gap of the winning lane ------------------------
        win_ok = (root_key != key_inf) & ~ovf
        with m.If(out_now):
            m.d.sync += [
                self.valid.eq(win_ok), self.overflow.eq(ovf),
                self.gap.eq(Mux(win_ok, Array(l_gam)[root_lane], _F.gap_sentinel)),
                self.idx.eq(Mux(win_ok, Array(l_idx)[root_lane], IDX_SENTINEL))]
        return m

    def _lane(self, m, l, pp, smp, tok, n_q, accept, l_rho, l_gam, l_idx):
        """Lane ``l``: stage A (d, gamma), stage B (e, rho, running minimum)."""
        half = 1 << (RF - 1)
        a_valid = Signal(name=f"a_valid_{l}")
        a_k = Signal.like(tok.k, name=f"a_k_{l}")
        a_d = Signal(data.ArrayLayout(signed(_F.diff_bits), 3), name=f"a_d_{l}")
        a_n = Signal(NORM3, name=f"a_n_{l}")
        a_gam = Signal(signed(_F.gap_bits), name=f"a_gam_{l}")
        d = [Signal(signed(_F.diff_bits), name=f"d_{l}_{k}") for k in range(3)]
        dot = Signal(signed(_F.dot_bits), name=f"dot_{l}")
        m.d.comb += [d[k].eq(pp[k] - smp.g[k]) for k in range(3)]
        m.d.comb += dot.eq(smp.n[0] * d[0] + smp.n[1] * d[1] + smp.n[2] * d[2])
        in_range = ((tok.k << self.lane_bits) | l) < n_q
        m.d.sync += [a_valid.eq(tok.act & in_range), a_k.eq(tok.k), a_n.eq(smp.n),
                     a_gam.eq((C(half, RF) - dot) >> RF)]
        m.d.sync += [a_d[k].eq(d[k]) for k in range(3)]
        # stage B: |gamma| < 2^26 structurally, so its low 27 bits feed the multipliers
        gam27 = a_gam[:CW + 3].as_signed()
        rho = Signal(self.rho_bits, name=f"rho_{l}")
        lean = self.variant == "lean"
        sq, fits = [], []
        for k in range(3):
            # gn: Q(46,35) mm (|gamma n| fits 46 b structurally); e: Q(27,16) mm
            gn = Signal(signed(_F.dot_bits), name=f"gn_{l}_{k}")
            e = Signal(signed(_F.e_bits), name=f"e_{l}_{k}")
            if self.split_products:             # n on the A port, gamma's parts on B
                m.d.comb += gn.eq(split_mul(gam27, a_n[k]))
            else:
                m.d.comb += gn.eq(gam27 * a_n[k])
            m.d.comb += e.eq(a_d[k] + ((gn + half) >> RF))
            if lean:                            # e in 18 b: one B port, one slice
                e18 = e[:LEAN_E_BITS].as_signed()
                fits.append(e18 == e)
                sq.append(e18 * e18)
            else:                               # e^2: Q(54,32) mm^2, >= 0, exact either way
                sq.append(split_square(e) if self.split_products else e * e)
        total = sq[0] + sq[1] + sq[2]
        rho_inf = (1 << self.rho_bits) - 1
        m.d.comb += rho.eq(Mux(fits[0] & fits[1] & fits[2], total, rho_inf) if lean else total)
        with m.If(accept):
            m.d.sync += l_rho.eq(rho_inf)
        with m.Elif(a_valid & (rho < l_rho)):        # strict: earliest sample keeps a tie
            m.d.sync += [l_rho.eq(rho), l_gam.eq(a_gam),
                         l_idx.eq((a_k << self.lane_bits) | l)]


class GapLaneProbe(wiring.Component):
    """One lane of :class:`GapCore` (stages A and B, running minimum) with its operands
    as ports: the unit of the per-lane resource count (``hw.synth.lane_dsp``).

    Parameters
    ----------
    split_products, variant : keyword-only
        As in :class:`GapCore`.
    """

    def __init__(self, *, split_products: bool = True, variant: str = "published"):
        self.core = GapCore(lanes=8, split_products=split_products, variant=variant)
        self.core._MustUse__silence = True        # only its _lane is elaborated
        self._kw = max(1, (self.core.depth - 1).bit_length())
        super().__init__({
            "pp": In(COORD3), "smp": In(SAMPLE), "act": In(1), "k": In(self._kw),
            "n_q": In(IDX_BITS), "accept": In(1), "rho": Out(self.core.rho_bits),
            "gam": Out(signed(_F.gap_bits)), "idx": Out(IDX_BITS)})

    def elaborate(self, platform):
        m = Module()
        tok = Signal(data.StructLayout({"act": 1, "k": unsigned(self._kw)}))
        l_rho = Signal(self.core.rho_bits, init=(1 << self.core.rho_bits) - 1)
        l_gam, l_idx = Signal(signed(_F.gap_bits)), Signal(IDX_BITS)
        m.d.comb += [tok.act.eq(self.act), tok.k.eq(self.k), self.rho.eq(l_rho),
                     self.gam.eq(l_gam), self.idx.eq(l_idx)]
        self.core._lane(m, 0, self.pp, self.smp, tok, self.n_q, self.accept,
                        l_rho, l_gam, l_idx)
        return m


def lane_verilog(*, split_products: bool = True, variant: str = "published",
                 name: str = "core") -> str:
    """Verilog of one :class:`GapLaneProbe` (top ``name``)."""
    from amaranth.back import verilog
    return verilog.convert(GapLaneProbe(split_products=split_products, variant=variant),
                           name=name, strip_internal_attrs=True)


def convert_verilog(*, lanes: int = 16, max_samples: int | None = None,
                    name: str = "gap_core", split_products: bool = True,
                    variant: str = "published") -> str:
    """Verilog of ``GapCore(lanes=..., max_samples=..., split_products=..., variant=...)``.

    Internal attributes are stripped; ``split_products=False`` is the published netlist.
    """
    from amaranth.back import verilog
    core = GapCore(lanes=lanes, max_samples=max_samples, split_products=split_products,
                   variant=variant)
    return verilog.convert(core, name=name, strip_internal_attrs=True)


async def load_gap_vector(ctx, dut, vec) -> None:
    """Write the samples of ``vec`` (one per edge) and drive its pass operands.

    Parameters
    ----------
    ctx : SimulatorContext
        Testbench context.
    dut : GapCore
        Device under test.
    vec : :class:`.golden.GapVector`
        Pass operands; sample i goes to address i. ``go`` is left to the caller.
    """
    for i in range(vec.n_samples):
        ctx.set(dut.w_valid, 1)
        ctx.set(dut.w_addr, i)
        ctx.set(dut.w_g, [int(x) for x in vec.g_code[i]])
        ctx.set(dut.w_n, [int(x) for x in vec.n_code[i]])
        await ctx.tick()
    ctx.set(dut.w_valid, 0)
    ctx.set(dut.r, [int(x) for x in vec.r_code.ravel()])
    ctx.set(dut.t, [int(x) for x in vec.t_code])
    ctx.set(dut.p, [int(x) for x in vec.p_code])
    ctx.set(dut.tau2, int(vec.tau2_code))
    ctx.set(dut.n_samples, vec.n_samples)


def read_gap_codes(ctx, dut) -> GapCodes:
    """The output registers of a :class:`GapCore` as :class:`.golden.GapCodes`."""
    v = read_ports(ctx, dut, {"gap": "gap", "idx": "idx", "valid": "valid",
                              "overflow": "overflow"})
    return GapCodes(min_gap_code=v["gap"], min_idx=v["idx"], valid=bool(v["valid"]),
                    overflow=bool(v["overflow"]))


def simulate_gap_core(vectors, *, lanes: int = 16, max_samples: int | None = None,
                      vcd_path: str | None = None, split_products: bool = True,
                      variant: str = "published"):
    """Run passes on the RTL in the Amaranth simulator.

    Parameters
    ----------
    vectors : sequence of :class:`.golden.GapVector`
        Operands (default formats); each pass first writes its N samples through the
        write port (one per cycle), then pulses ``go``.
    lanes, max_samples, split_products, variant : keyword-only
        Core parameters (see :class:`GapCore`).
    vcd_path : str, optional
        Write a VCD waveform there.

    Returns
    -------
    outputs : list of GapCodes
        The output registers after each pass's ``done``.
    cycles : list of int
        Cycles from the edge accepting ``go`` to the edge raising ``done``.
    """
    from .golden import check_vector
    dut = GapCore(lanes=lanes, max_samples=max_samples, split_products=split_products,
                  variant=variant)
    for vec in vectors:
        check_vector(vec)
        if vec.n_samples > dut.max_samples:
            raise InputRangeError("n_samples", vec.n_samples, f"[1, {dut.max_samples}]")
    outputs, cycles = [], []
    limit = gap_latency(dut.max_samples, dut.lanes) + 4

    async def bench(ctx):
        for vec in vectors:
            await load_gap_vector(ctx, dut, vec)
            cycles.append(await run_to_done(ctx, dut.go, dut.done, max_cycles=limit + 1,
                                            what="gap core"))
            outputs.append(read_gap_codes(ctx, dut))

    run_testbench(dut, bench, vcd_path=vcd_path)
    return outputs, cycles
