"""Amaranth simulator plumbing shared by the preview cores' runners and tests.

The RTL cores (:mod:`.gap.rtl`, :mod:`.fit.rtl`, :mod:`.hertz.rtl`, :mod:`.chain_rtl`,
:mod:`.comb_rtl`) are driven the same way: a clocked testbench pulses a start strobe,
counts the edges until ``done`` reads 1 (the start edge is edge 1), and reads the
output ports into the golden model's dataclass. This module holds those steps once:

* :func:`run_testbench` / :func:`simulate_bench` -- a ``sync`` clock (10 ns period)
  plus one async testbench, optionally with a drivable synchronous reset or a VCD;
* :func:`pulse`, :func:`wait_done`, :func:`run_to_done` and :class:`CycleCounter` --
  start strobes and go -> done edge counting (polling, or ``tick().until`` on a
  free-running counter);
* :func:`write_stencil` -- the fit write port sequence (``wr_rst``, 49 ``wr_en``);
* :func:`read_ports` / :func:`read_record` -- output ports into dataclasses.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence

from amaranth import ClockDomain, Module, Signal

__all__ = [
    "CLOCK_PERIOD",
    "CycleCounter",
    "pulse",
    "read_ports",
    "read_record",
    "run_testbench",
    "run_to_done",
    "simulate_bench",
    "wait_done",
    "write_stencil",
]

#: Simulated ``sync`` clock period, s (the value only scales VCD time stamps).
CLOCK_PERIOD = 1e-8


def run_testbench(top, bench: Callable, *, vcd_path: str | None = None) -> None:
    """Simulate ``top`` with a ``sync`` clock and the async testbench ``bench``.

    Parameters
    ----------
    top : Elaboratable
        Design to simulate (a core, or a module holding it).
    bench : callable
        ``async def bench(ctx)``; the simulation ends when it returns.
    vcd_path : str, optional
        Write a VCD waveform there.
    """
    from amaranth.sim import Simulator
    sim = Simulator(top)
    sim.add_clock(CLOCK_PERIOD)
    sim.add_testbench(bench)
    if vcd_path:
        with sim.write_vcd(vcd_path):
            sim.run()
    else:
        sim.run()


def simulate_bench(dut, bench: Callable, *, with_reset: bool = False) -> None:
    """Run ``await bench(ctx, dut, cd)`` on ``dut``.

    Parameters
    ----------
    dut : Elaboratable
        Device under test (uses the ``sync`` domain).
    bench : callable
        ``async def bench(ctx, dut, cd)``.
    with_reset : bool, keyword-only
        Wrap ``dut`` in a module that declares the ``sync`` domain, so that the
        testbench can drive its synchronous reset through ``cd.rst``; otherwise
        ``cd`` is None.
    """
    top, cd = dut, None
    if with_reset:
        top = Module()
        top.domains.sync = cd = ClockDomain("sync")
        top.submodules.dut = dut

    async def testbench(ctx):
        await bench(ctx, dut, cd)

    run_testbench(top, testbench)


async def pulse(ctx, strobe) -> None:
    """Hold ``strobe`` at 1 for one clock edge, then drop it."""
    ctx.set(strobe, 1)
    await ctx.tick()
    ctx.set(strobe, 0)


async def wait_done(ctx, done, *, max_cycles: int, what: str = "core") -> int:
    """Edges from a start edge (already taken: edge 1) to the edge after which ``done``
    reads 1, polling once per edge.

    Parameters
    ----------
    ctx : SimulatorContext
        Testbench context.
    done : Value
        Completion signal.
    max_cycles : int, keyword-only
        Raise once this many edges have passed without ``done``.
    what : str, keyword-only
        Name for the error message.

    Returns
    -------
    int
        The edge count (1 if ``done`` already reads 1).

    Raises
    ------
    RuntimeError
        ``done`` did not rise within ``max_cycles`` edges.
    """
    n = 1
    while not ctx.get(done):
        if n >= max_cycles:
            raise RuntimeError(f"{what}: no done after {n} cycles")
        await ctx.tick()
        n += 1
    return n


async def run_to_done(ctx, strobe, done, *, max_cycles: int, what: str = "core") -> int:
    """:func:`pulse` ``strobe``, then :func:`wait_done`; returns the edge count."""
    await pulse(ctx, strobe)
    return await wait_done(ctx, done, max_cycles=max_cycles, what=what)


class CycleCounter:
    """Simulation helper: a free-running edge counter beside a device under test.

    ``wait_done`` lets the simulator run to ``done`` without waking the Python
    testbench on every edge (``tick().until``, ~25 % faster than polling) and still
    returns the exact count of edges from the start edge to the one after which
    ``done`` reads 1.

    Parameters
    ----------
    dut : Elaboratable
        Device under test; simulate :attr:`top`, which holds it and the counter.
    """

    def __init__(self, dut):
        self.top = Module()
        self.top.submodules.dut = dut
        self.count = Signal(32)
        self.deadline = Signal(32)
        self.top.d.sync += self.count.eq(self.count + 1)

    async def start(self, ctx, strobe) -> int:
        """Pulse ``strobe`` for one edge; returns the count at that edge's end."""
        await pulse(ctx, strobe)
        return ctx.get(self.count)

    async def wait_done(self, ctx, done, t_go: int, max_cycles: int, what: str) -> int:
        """Edges from the start edge (edge 1, ending at count ``t_go``) to ``done``."""
        if not ctx.get(done):
            ctx.set(self.deadline, t_go + max_cycles)
            # until() samples before each edge: it returns one edge after done rose
            await ctx.tick().until(done | (self.count >= self.deadline))
            if not ctx.get(done):
                raise RuntimeError(f"{what}: no done after {max_cycles} cycles")
            return ctx.get(self.count) - t_go
        return 1


async def write_stencil(ctx, dut, row) -> None:
    """Pulse ``wr_rst`` and write the 49 STENCIL_GAP codes of ``row`` (one per edge).

    Parameters
    ----------
    ctx : SimulatorContext
        Testbench context.
    dut : FitCore or a core with its write port (``wr_rst``, ``wr_en``, ``wr_data``)
        Device under test.
    row : sequence of int
        STENCIL_GAP Q(32,21) codes, written from address 0 up.
    """
    await pulse(ctx, dut.wr_rst)
    ctx.set(dut.wr_en, 1)
    for x in row:
        ctx.set(dut.wr_data, int(x))
        await ctx.tick()
    ctx.set(dut.wr_en, 0)


def read_ports(ctx, dut, fields: Mapping[str, str | Sequence[str]]) -> dict:
    """Output port values of ``dut`` by field name (inside a testbench).

    Parameters
    ----------
    ctx : SimulatorContext
        Testbench context.
    dut : Component
        Device under test.
    fields : mapping of str to str or sequence of str
        ``field -> port name``, or ``field -> port names`` for a tuple-valued field.

    Returns
    -------
    dict
        ``field -> int`` (``tuple`` of int for a sequence of ports).
    """
    def get(port):
        return int(ctx.get(getattr(dut, port)))
    return {f: get(p) if isinstance(p, str) else tuple(get(x) for x in p)
            for f, p in fields.items()}


def read_record(ctx, dut, cls, fields: Mapping[str, str | Sequence[str]]):
    """``cls(**read_ports(ctx, dut, fields))``: output ports as a golden dataclass."""
    return cls(**read_ports(ctx, dut, fields))
