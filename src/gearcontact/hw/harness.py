"""Port descriptions of an RTL core and the generic C++ Verilator harness built from them.

One harness generator serves every core: a :class:`HarnessSpec` says which input ports
carry a vector's operands, which write port (if any) streams a burst of words into the
core before ``go``, which strobe starts a run, which output signals completion and
which outputs to read. :func:`generate_harness` turns it into one C++ ``main`` that

1. holds ``rst`` for two cycles;
2. for each vector of the stimulus stream: optionally pulses the write port's
   ``clear`` input for one cycle, drives the burst beat by beat (``strobe`` high, the
   ``addr`` port = beat index, the beat's data fields), drives the operand inputs and
   ``go`` for one cycle, then clocks until ``done`` reads 1 (failing after
   ``max_cycles``, a command-line argument), and records the outputs and the cycle count;
3. writes the outputs and prints ``{"vectors", "sim_cycles", "seconds"}`` as JSON.

The cycle count is the number of rising clock edges from the edge that samples
``go`` (counted as 1) to the edge after which ``done`` reads 1 -- the convention of the
Amaranth runners (``simulate_*_core``) and of the golden timing models.

A *streaming* core (``HarnessSpec.stream``, a :class:`Stream` of valid/ready names,
e.g. the II = 1 stage D) gets a different loop: on every clock the next pending vector
is offered on the operand inputs with ``in_valid`` (unless a random bubble withholds
it), ``out_ready`` is driven (low on a random stall), and a result is taken whenever
``out_valid`` and ``out_ready`` are both 1; the record's cycle word is then the
latency, edges from the accepting edge (edge 1) to the edge after which the result
first showed ``out_valid``. Bubble and stall probabilities (per mille) and the seed
of the harness' xorshift generator are optional arguments 5-7 of the binary (default 0:
back to back); the JSON line adds ``first_accept`` and ``last_accept`` (edge indices),
from which the initiation interval follows.

Stimulus and result files are flat little-endian ``uint32`` streams. Stimulus, per
vector: ``[n_beats]`` and ``n_beats`` x (beat fields) if the spec has a write port,
then the operand inputs. Result, per vector: the outputs, then the cycle count. A port
of ``w`` bits takes ``ceil(w / 32)`` words, least-significant word first; a port made
of ``count`` elements (an Amaranth ``ArrayLayout``) holds element 0 in its low bits.
:func:`pack_stimulus` and :func:`unpack_results` do the numpy side.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..validation import InputRangeError

__all__ = ["Port", "WritePort", "Stream", "HarnessSpec", "generate_harness", "pack_stimulus",
           "unpack_results", "pack_port", "unpack_port"]


@dataclass(frozen=True)
class Port:
    """A top-level port of the exported Verilog.

    Parameters
    ----------
    name : str
        Port name (as in the Verilog and the Verilator model).
    bits : int
        Element width.
    count : int
        Number of elements (>1 for an Amaranth ``ArrayLayout`` port, element 0 in the
        low bits); the port is ``bits * count`` wide.
    signed : bool
        Decode elements as two's complement (outputs); inputs are masked either way.
    """

    name: str
    bits: int
    count: int = 1
    signed: bool = False

    def __post_init__(self):
        if not 1 <= self.bits <= 64 or self.count < 1:
            raise InputRangeError(f"port {self.name} bits/count", (self.bits, self.count),
                                  "bits in [1, 64], count >= 1")

    @property
    def width(self) -> int:
        """Total port width in bits."""
        return self.bits * self.count

    @property
    def words(self) -> int:
        """32-bit words the port takes in a stimulus/result record."""
        return -(-self.width // 32)


@dataclass(frozen=True)
class WritePort:
    """A burst write port driven before ``go`` (one beat per clock).

    Parameters
    ----------
    strobe : str
        Write-enable input, high during the burst.
    fields : tuple of Port
        Data inputs driven with each beat.
    max_beats : int
        Capacity (the harness rejects longer bursts).
    addr : str, optional
        Input driven with the beat index.
    clear : str, optional
        Input pulsed for one cycle before the burst (e.g. a write-pointer reset).
    """

    strobe: str
    fields: tuple
    max_beats: int
    addr: str | None = None
    clear: str | None = None

    @property
    def beat_words(self) -> int:
        return sum(p.words for p in self.fields)


@dataclass(frozen=True)
class Stream:
    """Valid/ready port names of a streaming core (one input set per accepted edge).

    Parameters
    ----------
    in_valid, in_ready, out_valid, out_ready : str
        The handshake ports: an input set is accepted on an edge where ``in_valid`` and
        ``in_ready`` are 1; a result is consumed on an edge where ``out_valid`` and
        ``out_ready`` are 1.
    """

    in_valid: str = "in_valid"
    in_ready: str = "in_ready"
    out_valid: str = "out_valid"
    out_ready: str = "out_ready"


@dataclass(frozen=True)
class HarnessSpec:
    """Everything the generic harness needs to know about a core.

    Parameters
    ----------
    top : str
        Verilog top module name.
    inputs : tuple of Port
        Operand inputs, driven with ``go`` and held afterwards.
    outputs : tuple of Port
        Outputs read after ``done``.
    go : str
        One-cycle start strobe.
    done : str
        Completion output (a pulse or a level cleared by the accepted ``go``).
    max_cycles : int
        Give up on a vector after this many edges without ``done`` (a run-time argument
        of the harness binary, not compiled in).
    write : WritePort, optional
        Burst write port driven before ``go``.
    stream : Stream, optional
        Streaming handshake instead of ``go``/``done`` (then ``go`` and ``done`` name
        ``in_valid`` and ``out_valid``, ``max_cycles`` bounds the edges between two
        results, and there is no write port).
    clock, reset : str
        Clock and synchronous active-high reset inputs (Amaranth: ``clk``, ``rst``).
    """

    top: str
    inputs: tuple
    outputs: tuple
    go: str
    done: str
    max_cycles: int
    write: WritePort | None = None
    stream: Stream | None = None
    clock: str = "clk"
    reset: str = "rst"

    def __post_init__(self):
        if self.stream is not None and self.write is not None:
            raise InputRangeError("HarnessSpec.write", self.write, "None for a stream core")

    @property
    def input_words(self) -> int:
        return sum(p.words for p in self.inputs)

    @property
    def output_words(self) -> int:
        """Words per result record (outputs + the cycle count)."""
        return sum(p.words for p in self.outputs) + 1


# ---------------------------------------------------------------------------------
# C++ generation
# ---------------------------------------------------------------------------------
def _c_set(port: Port, src: str, offset: str) -> str:
    """C++ statement driving ``port`` from ``src[offset ...]``."""
    name = f"top->{port.name}"
    if port.width <= 32:
        return f"{name} = {src}[{offset}];"
    if port.width <= 64:
        return (f"{name} = (uint64_t){src}[{offset}] | "
                f"((uint64_t){src}[{offset} + 1] << 32);")
    return (f"for (int i = 0; i < {port.words}; ++i) "
            f"{name}[i] = {src}[{offset} + i];")


def _c_get(port: Port, dst: str, offset: int) -> str:
    """C++ statement storing ``port`` into ``dst[offset ...]``."""
    name = f"top->{port.name}"
    if port.width <= 32:
        return f"{dst}[{offset}] = (uint32_t){name};"
    if port.width <= 64:
        return (f"{dst}[{offset}] = (uint32_t){name}; "
                f"{dst}[{offset + 1}] = (uint32_t)((uint64_t){name} >> 32);")
    return f"for (int i = 0; i < {port.words}; ++i) {dst}[{offset} + i] = {name}[i];"


_TEMPLATE = r"""// Generated by gearcontact.hw.harness for module {top}; do not edit.
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "verilated.h"
#include "V{top}.h"

static V{top}* top;
static uint64_t sim_cycles = 0;

static inline void tick() {{
    top->{clock} = 1;
    top->eval();
    top->{clock} = 0;
    top->eval();
    ++sim_cycles;
}}

static std::vector<uint32_t> read_words(const char* path) {{
    std::vector<uint32_t> buf;
    FILE* f = std::fopen(path, "rb");
    if (!f) {{ std::fprintf(stderr, "cannot open %s\n", path); std::exit(2); }}
    uint32_t chunk[4096];
    size_t n;
    while ((n = std::fread(chunk, sizeof(uint32_t), 4096, f)) > 0)
        buf.insert(buf.end(), chunk, chunk + n);
    std::fclose(f);
    return buf;
}}

int main(int argc, char** argv) {{
    if ({argc_check}) {{
        std::fprintf(stderr, "usage: %s STIMULUS RESULTS N_VECTORS MAX_CYCLES{usage_extra}\n", argv[0]);
        return 2;
    }}
    const std::vector<uint32_t> stim = read_words(argv[1]);
    const long n_vec = std::atol(argv[3]);
    const uint32_t max_cycles = (uint32_t)std::atol(argv[4]);
    const size_t OUT_WORDS = {out_words};
    std::vector<uint32_t> out((size_t)n_vec * OUT_WORDS);

    VerilatedContext* ctx = new VerilatedContext;
    top = new V{top}{{ctx}};
    top->{clock} = 0;
    top->{reset} = 1;
    top->eval();
    tick();
    tick();
    top->{reset} = 0;
    top->eval();

{loop}    FILE* f = std::fopen(argv[2], "wb");
    if (!f || std::fwrite(out.data(), sizeof(uint32_t), out.size(), f) != out.size()) {{
        std::fprintf(stderr, "cannot write %s\n", argv[2]);
        return 2;
    }}
    std::fclose(f);
    const double secs = std::chrono::duration<double>(t1 - t0).count();
    std::printf("{{\"vectors\": %ld, \"sim_cycles\": %llu, \"seconds\": %.6f{stats_fmt}}}\n",
                n_vec, (unsigned long long)sim_cycles, secs{stats_args});
    top->final();
    delete top;
    delete ctx;
    return 0;
}}
"""

_GO_LOOP = r"""    size_t pos = 0;
    auto t0 = std::chrono::steady_clock::now();
    for (long v = 0; v < n_vec; ++v) {{
        uint32_t* o = &out[(size_t)v * OUT_WORDS];
{write_block}
        if (pos + {in_words} > stim.size()) {{
            std::fprintf(stderr, "vector %ld: stimulus file too short\n", v);
            return 2;
        }}
        const uint32_t* w = &stim[pos];
{set_inputs}
        pos += {in_words};
        top->{go} = 1;
        tick();
        top->{go} = 0;
        uint32_t count = 1;
        while (!top->{done}) {{
            if (count >= max_cycles) {{
                std::fprintf(stderr, "vector %ld: no {done} within %u cycles\n", v, max_cycles);
                return 3;
            }}
            tick();
            ++count;
        }}
{get_outputs}
        o[OUT_WORDS - 1] = count;
    }}
    auto t1 = std::chrono::steady_clock::now();
    if (pos != stim.size()) {{
        std::fprintf(stderr, "stimulus has %zu unused words\n", stim.size() - pos);
        return 2;
    }}
"""

_STREAM_LOOP = r"""    const uint32_t bubble = argc > 5 ? (uint32_t)std::atol(argv[5]) : 0u;   // per mille
    const uint32_t stall = argc > 6 ? (uint32_t)std::atol(argv[6]) : 0u;    // per mille
    uint64_t rng = argc > 7 ? (uint64_t)std::atoll(argv[7]) * 2654435761u + 1u : 1u;
    auto chance = [&rng](uint32_t per_mille) {{             // xorshift64
        rng ^= rng << 13; rng ^= rng >> 7; rng ^= rng << 17;
        return per_mille > 0 && (uint32_t)(rng % 1000u) < per_mille;
    }};
    if ((size_t)n_vec * {in_words} != stim.size()) {{
        std::fprintf(stderr, "stimulus has %zu words, expected %ld x {in_words}\n",
                     stim.size(), n_vec);
        return 2;
    }}
    std::vector<uint64_t> accepted((size_t)n_vec);
    long next_in = 0, next_out = 0;
    bool shown = false;
    uint64_t appear = 0, progress = sim_cycles, first_acc = 0, last_acc = 0;
    auto t0 = std::chrono::steady_clock::now();
    while (next_out < n_vec) {{
        if (sim_cycles - progress > max_cycles) {{
            std::fprintf(stderr, "result %ld: no {out_valid} within %u cycles\n", next_out,
                         max_cycles);
            return 3;
        }}
        const bool send = next_in < n_vec && !chance(bubble);
        if (send) {{
            const uint32_t* w = &stim[(size_t)next_in * {in_words}];
{set_inputs}
        }}
        top->{in_valid} = send;
        top->{out_ready} = !chance(stall);
        top->eval();
        if (top->{out_valid}) {{
            if (!shown) {{ appear = sim_cycles; shown = true; }}
            if (top->{out_ready}) {{
                uint32_t* o = &out[(size_t)next_out * OUT_WORDS];
{get_outputs}
                o[OUT_WORDS - 1] = (uint32_t)(appear - accepted[(size_t)next_out] + 1);
                ++next_out;
                shown = false;
                progress = sim_cycles;
            }}
        }}
        if (send && top->{in_ready}) {{
            accepted[(size_t)next_in] = sim_cycles + 1;
            if (next_in == 0) first_acc = sim_cycles + 1;
            last_acc = sim_cycles + 1;
            ++next_in;
        }}
        tick();
    }}
    auto t1 = std::chrono::steady_clock::now();
"""

_WRITE_TEMPLATE = r"""        {{
            const uint32_t n_beats = stim.at(pos++);
            if (n_beats > {max_beats}u) {{
                std::fprintf(stderr, "vector %ld: %u beats > {max_beats}\n", v, n_beats);
                return 2;
            }}
            if (pos + (size_t)n_beats * {beat_words} > stim.size()) {{
                std::fprintf(stderr, "vector %ld: stimulus file too short\n", v);
                return 2;
            }}
{clear}            top->{strobe} = 1;
            for (uint32_t b = 0; b < n_beats; ++b) {{
                const uint32_t* bw = &stim[pos + (size_t)b * {beat_words}];
{addr}{fields}
                tick();
            }}
            top->{strobe} = 0;
            pos += (size_t)n_beats * {beat_words};
        }}"""


def _offsets(ports) -> list[int]:
    out, k = [], 0
    for p in ports:
        out.append(k)
        k += p.words
    return out


def generate_harness(spec: HarnessSpec) -> str:
    """C++ source of the Verilator ``main`` for ``spec`` (see the module docstring)."""
    pad = " " * 8
    write_block = ""
    if spec.write is not None:
        wp = spec.write
        clear = (f"{pad}    top->{wp.clear} = 1;\n{pad}    tick();\n"
                 f"{pad}    top->{wp.clear} = 0;\n") if wp.clear else ""
        addr = f"{pad}        top->{wp.addr} = b;\n" if wp.addr else ""
        fields = "\n".join(f"{pad}        {_c_set(p, 'bw', str(k))}"
                           for p, k in zip(wp.fields, _offsets(wp.fields)))
        write_block = _WRITE_TEMPLATE.format(max_beats=wp.max_beats,
                                             beat_words=wp.beat_words, clear=clear,
                                             strobe=wp.strobe, addr=addr, fields=fields)
    if spec.stream is not None:
        st, pad2 = spec.stream, pad + "    "
        loop = _STREAM_LOOP.format(
            in_words=spec.input_words, in_valid=st.in_valid, in_ready=st.in_ready,
            out_valid=st.out_valid, out_ready=st.out_ready,
            set_inputs="\n".join(f"{pad2}{_c_set(p, 'w', str(k))}"
                                  for p, k in zip(spec.inputs, _offsets(spec.inputs)))
            or pad2 + ";",
            get_outputs="\n".join(f"{pad2}{_c_get(p, 'o', k)}"
                                   for p, k in zip(spec.outputs, _offsets(spec.outputs))))
        extra = dict(argc_check="argc < 5 || argc > 8", usage_extra=" [BUBBLE_PER_MILLE STALL_PER_MILLE SEED]",
                     stats_fmt=', \\"first_accept\\": %llu, \\"last_accept\\": %llu',
                     stats_args=", (unsigned long long)first_acc, (unsigned long long)last_acc")
    else:
        set_inputs = "\n".join(f"{pad}{_c_set(p, 'w', str(k))}"
                               for p, k in zip(spec.inputs, _offsets(spec.inputs)))
        get_outputs = "\n".join(f"{pad}{_c_get(p, 'o', k)}"
                                for p, k in zip(spec.outputs, _offsets(spec.outputs)))
        loop = _GO_LOOP.format(in_words=spec.input_words, write_block=write_block,
                               set_inputs=set_inputs or pad + ";", go=spec.go,
                               done=spec.done, get_outputs=get_outputs)
        extra = dict(argc_check="argc != 5", usage_extra="", stats_fmt="", stats_args="")
    return _TEMPLATE.format(top=spec.top, clock=spec.clock, reset=spec.reset,
                            out_words=spec.output_words, loop=loop, **extra)


# ---------------------------------------------------------------------------------
# numpy side: stimulus and result streams
# ---------------------------------------------------------------------------------
def _as_codes(port: Port, values, lead: tuple) -> np.ndarray:
    """``values`` as int64 of shape ``lead + (count,)`` (checked against the port)."""
    a = np.asarray(values)
    if a.dtype.kind not in "iu":
        raise InputRangeError(f"{port.name} codes", f"dtype {a.dtype}", "integer codes")
    want = lead + ((port.count,) if port.count > 1 else ())
    if a.shape != want:
        raise InputRangeError(f"{port.name}.shape", a.shape, str(want))
    a = a.reshape(lead + (port.count,))
    lo = -(1 << (port.bits - 1)) if port.signed else 0
    hi = (1 << port.bits) - 1 if not port.signed else (1 << (port.bits - 1)) - 1
    if a.size and (int(a.min()) < lo or int(a.max()) > hi):
        raise InputRangeError(f"{port.name} codes", (int(a.min()), int(a.max())),
                              f"[{lo}, {hi}] ({port.bits}-bit "
                              f"{'signed' if port.signed else 'unsigned'})")
    return a


def pack_port(port: Port, values, lead: tuple) -> np.ndarray:
    """Pack codes of shape ``lead (+ (count,))`` into uint32 words ``lead + (words,)``."""
    a = _as_codes(port, values, lead).astype(np.int64).view(np.uint64)
    shifts = np.arange(port.bits, dtype=np.uint64)
    bits = ((a[..., None] >> shifts) & np.uint64(1)).astype(np.uint8)
    bits = bits.reshape(lead + (port.width,))
    pad = port.words * 32 - port.width
    if pad:
        bits = np.concatenate([bits, np.zeros(lead + (pad,), np.uint8)], axis=-1)
    packed = np.packbits(bits, axis=-1, bitorder="little")
    return np.ascontiguousarray(packed).view("<u4").reshape(lead + (port.words,))


def unpack_port(port: Port, words) -> np.ndarray:
    """Decode uint32 words ``(n, words)`` into int64 codes ``(n,)`` or ``(n, count)``."""
    w = np.ascontiguousarray(np.asarray(words, dtype="<u4"))
    n = w.shape[0]
    bits = np.unpackbits(w.view(np.uint8).reshape(n, -1), axis=-1, bitorder="little")
    bits = bits[:, :port.width].reshape(n, port.count, port.bits).astype(np.uint64)
    vals = (bits << np.arange(port.bits, dtype=np.uint64)).sum(axis=-1, dtype=np.uint64)
    if port.signed:
        top = np.uint64(1) << np.uint64(port.bits - 1)
        vals = (vals ^ top).view(np.int64) - np.int64(top) if port.bits < 64 \
            else vals.view(np.int64)
    else:
        vals = vals.view(np.int64)
    return vals[:, 0] if port.count == 1 else vals


def pack_stimulus(spec: HarnessSpec, inputs: dict, beats: dict | None = None,
                  n_beats=None) -> tuple[np.ndarray, int]:
    """Build the stimulus stream for ``spec``.

    Parameters
    ----------
    spec : HarnessSpec
    inputs : dict
        Port name -> codes of shape ``(n,)`` or ``(n, count)`` for every operand input.
    beats : dict, optional
        Write-port field name -> codes ``(n, max_n_beats[, count])`` (required when the
        spec has a write port).
    n_beats : array_like of int, optional
        Beats per vector (default: all ``max_n_beats``); padding beyond it is ignored.

    Returns
    -------
    (stream, n)
        ``uint32`` stream and the number of vectors.
    """
    missing = {p.name for p in spec.inputs} - set(inputs)
    if missing:
        raise InputRangeError("stimulus inputs", sorted(inputs), f"all of {sorted(missing)}")
    if spec.inputs:
        n = len(np.asarray(inputs[spec.inputs[0].name]))
    else:
        n = len(np.asarray(beats[spec.write.fields[0].name]))
    cols = [pack_port(p, inputs[p.name], (n,)) for p in spec.inputs]
    if spec.write is None:
        rec = np.concatenate(cols, axis=1) if cols else np.zeros((n, 0), "<u4")
        return rec.ravel(), n
    wp = spec.write
    if beats is None or set(beats) != {p.name for p in wp.fields}:
        raise InputRangeError("stimulus beats", None if beats is None else sorted(beats),
                              f"exactly {sorted(p.name for p in wp.fields)}")
    nb_max = np.asarray(beats[wp.fields[0].name]).shape[1]
    counts = np.full(n, nb_max, np.int64) if n_beats is None else \
        np.asarray(n_beats, dtype=np.int64)
    if counts.shape != (n,) or (counts < 0).any() or (counts > min(nb_max, wp.max_beats)).any():
        raise InputRangeError("n_beats", counts.tolist()[:8],
                              f"(n,) integers in [0, {min(nb_max, wp.max_beats)}]")
    beat_cols = [pack_port(p, beats[p.name], (n, nb_max)) for p in wp.fields]
    beat_words = np.concatenate(beat_cols, axis=2).reshape(n, nb_max * wp.beat_words)
    rec = np.concatenate([counts.astype("<u4")[:, None], beat_words] + cols, axis=1)
    if (counts == nb_max).all():
        return rec.ravel(), n
    used = np.arange(nb_max * wp.beat_words)[None, :] < (counts * wp.beat_words)[:, None]
    mask = np.concatenate([np.ones((n, 1), bool), used,
                           np.ones((n, spec.input_words), bool)], axis=1)
    return rec[mask], n


def unpack_results(spec: HarnessSpec, words, n: int) -> tuple[dict, np.ndarray]:
    """Split a result stream into ``({output name: codes}, cycles (n,))``."""
    w = np.asarray(words, dtype="<u4")
    if w.size != n * spec.output_words:
        raise InputRangeError("result words", w.size, f"{n} x {spec.output_words}")
    w = w.reshape(n, spec.output_words)
    out, k = {}, 0
    for p in spec.outputs:
        out[p.name] = unpack_port(p, w[:, k:k + p.words])
        k += p.words
    return out, w[:, -1].astype(np.int64)
