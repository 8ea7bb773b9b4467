"""Golden-vector export for other HDL flows (JSON lines + ``$readmemh`` hex + README).

For each core (``gap`` with N = 16 samples, ``fit``, ``hertz``, ``chain``) the export
takes the corner cases and ``count`` seeded random vectors of
:mod:`gearcontact.preview.stimulus` (the single source of operands), computes the
expected outputs with the vectorized golden model of the core's bench
(:attr:`gearcontact.hw.harness_cores.CoreBench.golden`, the same function the
Verilator equivalence tests use) and writes, per core:

``<core>.jsonl``
    One JSON object per vector: ``core``, ``index`` (0-based, corner cases first),
    ``label`` (corner-case name, ``random`` or ``raw``), ``inputs`` {port: int or
    (nested) list}, ``outputs`` {port: int}, ``cycles`` (go -> done, constant per core).
``<core>_in.hex``, ``<core>_out.hex``
    ``$readmemh`` files, line ``k`` = vector ``k``: the fields of :func:`vector_layout`
    concatenated, first field leftmost (most significant). Every element is a
    fixed-width hex word of ``ceil(bits / 4)`` digits holding the element's two's
    complement (signed fields, sign-extended to the padded width) or its binary value
    (unsigned fields); array elements follow in index order, element 0 leftmost.
``README.md``
    Every file, field order, width, Q format, unit, seed, count and how to
    regenerate (:func:`readme_text`).

Field names are the RTL port names of the core (:mod:`gearcontact.hw.harness_cores`):
inputs are the burst-write fields (streamed one beat per clock before ``go``) followed
by the operand ports; outputs are the ports the equivalence tests check.

The line cores (:data:`LINE_CORES`, on request) describe the host's path around the
core (:attr:`gearcontact.preview.core.CoreDescriptor.host`): stimulus with contact
lines shorter than the core's 1 mm (:mod:`gearcontact.preview.stimulus_lift`), the
outputs after the host's lift and one more output field, ``lift`` (the README explains
how to drive the RTL core with a lifted line).
"""

from __future__ import annotations

import json
from importlib import import_module
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

from ..preview.chain import FIT_FLAG_SHIFT, chain_flag_names
from ..preview.hertz.formats import FLAG_NAMES as HERTZ_FLAG_NAMES
from ..preview.hertz.line import LINE_FLAG_NAMES
from ..preview.stimulus import STIMULUS_CORES, Stimulus
from ..validation import InputRangeError
from .harness import Port
from .harness_cores import get_bench

__all__ = ["VECTOR_CORES", "VARIANT_CORES", "LINE_CORES", "EXPORT_CORES",
           "GAP_VECTOR_SAMPLES", "DEFAULT_COUNT", "MAX_COUNT", "HexField",
           "vector_layout", "vector_stimulus", "golden_outputs", "encode_hex",
           "decode_hex", "read_hex", "read_jsonl", "readme_text", "export_vectors"]

#: Cores exported by default, in file order.
VECTOR_CORES = ("gap", "fit", "hertz", "chain")
#: Variants exported on request (``cores=``), each with the ports and stimulus of its
#: base core and its own golden model: the lean gap lane, stage D and the C -> D chain
#: with the exact-Hertz tables.
VARIANT_CORES = {"gap_lean": "gap", "hertz_exact": "hertz", "chain_exact": "chain"}
#: Line-contact cores exported on request: the line core of stage D in both Hertz forms
#: and the C -> line-core chain. Their vectors are the host's path
#: (:attr:`gearcontact.preview.core.CoreDescriptor.host`): a line shorter than the
#: core's 1 mm runs lifted, the outputs unlifted, and the lift is one more output.
LINE_CORES = ("hertz_line", "hertz_line_exact", "chain_line")
#: Every exportable core, in file order.
EXPORT_CORES = VECTOR_CORES + tuple(VARIANT_CORES) + LINE_CORES
#: Gear samples per gap pass (one beat per sample, L = 16 lanes: 26 cycles).
GAP_VECTOR_SAMPLES = 16
#: Default number of seeded random vectors per core (corner cases come on top).
DEFAULT_COUNT = 1000
#: Most random vectors per core: about 0.43 GB of hex and JSON lines for the default
#: cores (4.3 kB per vector, measured; the line cores on request: 0.20 GB written,
#: 0.42 GB peak, 65 s). The files are written in blocks of
#: :data:`WRITE_BLOCK` vectors, so memory holds the stimulus codes and one block.
#: (1,000,000 was documented before: 13.8 GB of memory, 4.1 GB written.)
MAX_COUNT = 100_000
#: Vectors formatted and written at a time (bounds the memory of the text).
WRITE_BLOCK = 10_000

# Q format, unit and meaning of every port (README and HexField); ``flags`` per core.
_S = "the 49 gap samples, stencil order i = 7 j + k (s fastest, gearcontact." \
     "contract.stencil); beat i = sample i"
_PORT_DOC = {
    "r": ("Q(21,19)", "1", "rotation R, row-major (R00 R01 R02 R10 .. R22), "
          "|code| <= 2^19"),
    "t": ("Q(24,16)", "mm", "translation t (x, y, z); p' = R p + t"),
    "p": ("Q(24,16)", "mm", "body point p (x, y, z)"),
    "tau2": ("UQ(64,32)", "mm^2", "gate tau^2 (a lane passes if rho < tau2)"),
    "n_samples": ("UQ(16,0)", "1", "samples N streamed (16)"),
    "w_g": ("Q(24,16)", "mm", "gear samples g_i (x, y, z); beat i = sample i"),
    "w_n": ("Q(21,19)", "1", "unit normals n_i (x, y, z); beat i = sample i"),
    "gap": ("Q(32,16)", "mm", "winning signed gap g*; 0x7FFFFFFF if not valid"),
    "idx": ("UQ(16,0)", "1", "winning sample index i*; 0xFFFF if not valid"),
    "valid": ("UQ(1,0)", "1", "a lane passed the gate and p' did not overflow"),
    "overflow": ("UQ(1,0)", "1", "p' = R p + t left Q(24,16)"),
    "wr_data": ("Q(32,21)", "mm", _S),
    "c0": ("Q(32,20)", "mm", "fitted coefficient c0 (offset)"),
    "c1": ("Q(32,20)", "1", "fitted coefficient c1 (slope along s)"),
    "c2": ("Q(32,20)", "1", "fitted coefficient c2 (slope along t)"),
    "c3": ("Q(32,20)", "1/mm", "fitted coefficient c3 (s^2)"),
    "c4": ("Q(32,20)", "1/mm", "fitted coefficient c4 (s t)"),
    "c5": ("Q(32,20)", "1/mm", "fitted coefficient c5 (t^2)"),
    "a_minus": ("Q(32,20)", "1/mm", "fitted half relative curvature A- (A- >= B-)"),
    "b_minus": ("Q(32,20)", "1/mm", "fitted half relative curvature B-"),
    "A": ("Q(32,20)", "1/mm", "half relative principal curvature A"),
    "B": ("Q(32,20)", "1/mm", "half relative principal curvature B"),
    "W": ("Q(32,8)", "N", "normal load W"),
    "e_prime": ("Q(32,0)", "MPa", "effective modulus E' = 2 E*"),
    "a": ("Q(32,20)", "mm", "contact-ellipse semi-axis a"),
    "b": ("Q(32,20)", "mm", "contact-ellipse semi-axis b"),
    "p_max": ("Q(32,8)", "MPa", "peak Hertzian pressure"),
    "k": ("Q(32,20)", "1", "ellipticity k = a/b"),
    "A_min": ("Q(32,20)", "1/mm", "sorted curvature min(A, B)"),
    "B_max": ("Q(32,20)", "1/mm", "sorted curvature max(A, B)"),
    "R_x": ("Q(32,20)", "mm", "R_x = 1/(2 A_min)"),
    "R_y": ("Q(32,20)", "mm", "R_y = 1/(2 B_max)"),
    "alpha": ("UQ(32,24)", "1", "curvature ratio alpha = R_x/R_y"),
    "L": ("Q(32,20)", "mm", "length of the contact line on the flank through the contact "
          "point, along the ellipse's major axis; the core takes [1, 1024] mm, the host "
          "lifts a shorter line (`lift`)"),
    "mode": ("UQ(1,0)", "1", "0 elliptic, 1 line contact (0 when flagged)"),
    "scale": ("UQ(2,0)", "1", "Hertz similarity exponent n: curvatures scaled by 8^n"),
    "lift": ("UQ(4,0)", "1", "the host's lift s of a line shorter than 1 mm (0..8; "
             "the paragraph above): the core ran on W << s, L << s"),
}
#: Line cores: their a, b, k (either mode).
_LINE_PORT_DOC = {
    "a": ("Q(32,20)", "mm", "semi-axis a (elliptic) or L/2 (line mode)"),
    "b": ("Q(32,20)", "mm", "semi-axis b (elliptic) or the line's half-width"),
    "k": ("Q(32,20)", "1", "ellipticity a/b (elliptic; 0 in line mode)"),
}


def _flag_bits(core: str, nbits: int, port: str = "flags") -> list[str]:
    """Name of each bit of the core's flags word (bit 0 first; "-" if unused)."""
    core = VARIANT_CORES.get(core, core)
    if core in ("hertz_line", "hertz_line_exact"):
        return [LINE_FLAG_NAMES.get(1 << i, "-") for i in range(nbits)]
    if core == "chain_line" and port == "flags":
        return [", ".join(chain_flag_names(1 << i, line=True)) or "-" for i in range(nbits)]
    if core == "hertz":
        return [HERTZ_FLAG_NAMES.get(1 << i, "-") for i in range(nbits)]
    if core == "chain":
        return [", ".join(chain_flag_names(1 << i)) or "-" for i in range(nbits)]
    if core in ("fit", "chain_line"):       # the chain's fit_flags: the fit's word
        return [", ".join(chain_flag_names(1 << (i + FIT_FLAG_SHIFT))).replace("fit_", "")
                or "-" for i in range(nbits)]
    return ["-"] * nbits


def _doc(core: str, port) -> tuple[str, str, str]:
    if port.name in ("flags", "fit_flags"):
        listing = "; ".join(f"bit {i} {n}" for i, n in
                            enumerate(_flag_bits(core, port.bits, port.name)) if n != "-")
        what = "the fit core's flags word" if port.name == "fit_flags" else "flags word"
        return f"UQ({port.bits},0)", "1", f"{what}, 0 = valid ({listing})"
    if core in LINE_CORES and port.name in _LINE_PORT_DOC:
        return _LINE_PORT_DOC[port.name]
    return _PORT_DOC.get(port.name, ("-", "-", "see gearcontact.hw.harness_cores"))


@dataclass(frozen=True)
class HexField:
    """One field of a hex line (a core port).

    Attributes
    ----------
    name : str
        Port name (also the JSON key).
    bits : int
        Element width of the port, bits.
    shape : tuple of int
        Element shape per vector (``()`` for a scalar; JSON nests lists this way).
    signed : bool
        Two's complement (sign-extended to the padded width in the hex file).
    qformat, unit, meaning : str
        Documentation: Q format (``Q(m,f)`` signed, ``UQ(m,f)`` unsigned), unit, text.
    """

    name: str
    bits: int
    shape: tuple
    signed: bool
    qformat: str
    unit: str
    meaning: str

    @property
    def count(self) -> int:
        """Elements per vector."""
        return int(np.prod(self.shape, dtype=np.int64))

    @property
    def digits(self) -> int:
        """Hex digits per element, ``ceil(bits / 4)``."""
        return -(-self.bits // 4)

    @property
    def width(self) -> int:
        """Bits the field takes in a hex line (``4 digits count``)."""
        return 4 * self.digits * self.count

    def check(self, values: np.ndarray) -> None:
        """Raise InputRangeError if a value does not fit ``bits`` (never wrap)."""
        lo, hi = ((-(1 << (self.bits - 1)), (1 << (self.bits - 1)) - 1) if self.signed
                  else (0, (1 << self.bits) - 1))
        bad = (values < lo) | (values > hi)
        if bad.any():
            i = tuple(int(j) for j in np.argwhere(bad)[0])
            raise InputRangeError(f"{self.name}{list(i)}", int(values[i]),
                                  f"[{lo}, {hi}] ({self.bits}-bit port)")


def _port_field(core: str, port, shape: tuple) -> HexField:
    return HexField(port.name, port.bits, tuple(shape), bool(port.signed), *_doc(core, port))


def vector_layout(core: str) -> tuple[tuple[HexField, ...], tuple[HexField, ...]]:
    """Input and output fields of ``core``, in hex-line order (first = leftmost).

    Inputs: the burst-write fields (shape (beats, elements)), then the operand ports;
    outputs: the checked output ports. Widths and signedness are the core's ports
    (:mod:`gearcontact.hw.harness_cores`).
    """
    spec = get_bench(_check_core(core)).spec
    ins = []
    if spec.write is not None:
        beats = GAP_VECTOR_SAMPLES if _base(core) == "gap" else spec.write.max_beats
        for p in spec.write.fields:
            ins.append(_port_field(core, p, (beats, p.count) if p.count > 1 else (beats,)))
    ins += [_port_field(core, p, (p.count,) if p.count > 1 else ()) for p in spec.inputs]
    outs = [_port_field(core, p, (p.count,) if p.count > 1 else ()) for p in spec.outputs]
    host = get_bench(core).host
    outs += [_port_field(core, Port(name, bits, 1, False), ())
             for name, bits in (host.outputs if host is not None else ())]
    return tuple(ins), tuple(outs)


def _check_core(core: str) -> str:
    if core not in EXPORT_CORES:
        raise InputRangeError("core", core, f"one of {list(EXPORT_CORES)}")
    return core


def _base(core: str) -> str:
    """The core whose ports and stimulus a variant shares (itself if not a variant)."""
    return VARIANT_CORES.get(core, core)


def vector_stimulus(core: str, count: int, seed: int) -> Stimulus:
    """Corner cases + ``count`` seeded random vectors of ``core`` (gap cores: N = 16; the
    line cores: their host path's stimulus); ``Stimulus.core`` names ``core`` (a variant
    keeps its own name and golden model)."""
    bench = get_bench(_check_core(core))
    if bench.host is not None:
        return replace(bench.host.stimulus(count, seed), core=core)
    kw = {"n_samples": GAP_VECTOR_SAMPLES} if _base(core) == "gap" else {}
    return replace(bench.stimulus(count, seed, **kw), core=core)


def golden_outputs(stim: Stimulus) -> dict[str, np.ndarray]:
    """Expected outputs {port: int64 array} of a stimulus: the core bench's golden model
    (:attr:`gearcontact.hw.harness_cores.CoreBench.golden`; the line cores: the host's
    path, :attr:`~gearcontact.preview.core.CoreDescriptor.host`), re-exported here."""
    bench = get_bench(stim.core)
    return (bench.host or bench).golden(stim)


def _input_arrays(stim: Stimulus) -> dict[str, np.ndarray]:
    inputs, beats, _ = get_bench(stim.core).ports(stim)
    return {**(beats or {}), **inputs}


def encode_hex(values: dict, fields) -> list[str]:
    """Hex lines (one per vector) of ``values`` {name: int array, first axis = vector}.

    Raises
    ------
    InputRangeError
        A value does not fit its field (nothing wraps), or a field is missing.
    """
    cols = []
    n = None
    for f in fields:
        if f.name not in values:
            raise InputRangeError("field", f.name, f"one of {sorted(values)}")
        v = np.asarray(values[f.name], dtype=np.int64)
        n = v.shape[0] if n is None else n
        v = v.reshape(n, f.count)
        f.check(v)
        u = v.astype(np.uint64)          # two's complement, sign-extended to 64 bits
        if 4 * f.digits < 64:
            u &= np.uint64((1 << (4 * f.digits)) - 1)
        shifts = np.arange(4 * (f.digits - 1), -1, -4, dtype=np.uint64)
        cols.append(((u[:, :, None] >> shifts) & np.uint64(15)).reshape(n, -1))
    if n is None:
        return []
    nib = np.concatenate(cols, axis=1).astype(np.uint8)
    chars = np.frombuffer(b"0123456789abcdef", np.uint8)[nib]
    return [row.tobytes().decode("ascii") for row in chars]


def decode_hex(lines, fields) -> dict[str, np.ndarray]:
    """Inverse of :func:`encode_hex`: {name: int64 array of shape (n,) + field.shape}."""
    lines = [ln.strip() for ln in lines if ln.strip()]
    total = sum(f.digits * f.count for f in fields)
    raw = np.frombuffer("".join(lines).encode("ascii"), np.uint8).reshape(len(lines), -1) \
        if lines else np.zeros((0, total), np.uint8)
    if raw.shape[1] != total:
        raise InputRangeError("hex line length", raw.shape[1], f"{total} digits")
    lut = np.full(256, 255, np.uint8)
    for i, c in enumerate(b"0123456789abcdef"):
        lut[c] = lut[ord(chr(c).upper())] = i
    nib = lut[raw].astype(np.uint64)
    if (nib == 255).any():
        raise InputRangeError("hex digit", "non-hex character", "0-9, a-f")
    out, pos = {}, 0
    for f in fields:
        k = f.digits * f.count
        d = nib[:, pos:pos + k].reshape(len(lines), f.count, f.digits)
        pos += k
        u = np.zeros(d.shape[:2], np.uint64)
        for j in range(f.digits):
            u = (u << np.uint64(4)) | d[:, :, j]
        w = 4 * f.digits
        if f.signed and w < 64:
            v = u.astype(np.int64) - ((u >> np.uint64(w - 1)).astype(np.int64) << w)
        else:
            v = u.astype(np.int64)
        out[f.name] = v.reshape((len(lines),) + f.shape)
    return out


def read_hex(path, core: str, which: str) -> dict[str, np.ndarray]:
    """Read ``<core>_in.hex`` (``which="in"``) or ``<core>_out.hex`` (``"out"``)."""
    ins, outs = vector_layout(core)
    fields = {"in": ins, "out": outs}[which]
    return decode_hex(Path(path).read_text().splitlines(), fields)


def read_jsonl(path) -> list[dict]:
    """Read a ``<core>.jsonl`` file: one dict per vector."""
    return [json.loads(ln) for ln in Path(path).read_text().splitlines() if ln.strip()]


def _jsonl_lines(stim: Stimulus, inputs: dict, outputs: dict, ins, outs,
                 cycles: int, first: int = 0) -> list[str]:
    in_lists = {f.name: np.asarray(inputs[f.name]).tolist() for f in ins}
    out_lists = {f.name: np.asarray(outputs[f.name]).tolist() for f in outs}
    return [json.dumps({"core": stim.core, "index": first + k, "label": stim.labels[k],
                        "inputs": {n: v[k] for n, v in in_lists.items()},
                        "outputs": {n: v[k] for n, v in out_lists.items()},
                        "cycles": cycles}, separators=(",", ":"))
            for k in range(len(stim))]


def _field_table(fields) -> list[str]:
    rows = ["| # | field | bits [hi:lo] in line | element bits (hex digits) | elements "
            "| signed | Q format | unit | meaning |",
            "|---|---|---|---|---|---|---|---|---|"]
    hi = sum(f.width for f in fields) - 1
    for i, f in enumerate(fields):
        shape = " x ".join(map(str, f.shape)) if f.shape else "1"
        rows.append(f"| {i} | `{f.name}` | [{hi}:{hi - f.width + 1}] | {f.bits} "
                    f"({f.digits}) | {shape} | {'yes' if f.signed else 'no'} | "
                    f"{f.qformat} | {f.unit} | {f.meaning} |")
        hi -= f.width
    return rows


def readme_text(summary: dict, *, count: int, seed: int) -> str:
    """README.md of an export; ``summary`` maps core -> {vectors, corners, cycles,
    labels}."""
    from .. import __version__
    cores = list(summary)
    lines = [
        "# gearcontact golden vectors", "",
        f"Generated by gearcontact {__version__}: expected outputs of the bit-exact "
        "fixed-point golden model for the preview cores, to check any HDL "
        "implementation or simulator against.", "",
        f"* seed: **{seed}** (numpy `default_rng`), random vectors per core: **{count}**, "
        "plus the corner cases of each core (listed below, first in every file)",
        f"* cores: {', '.join(cores)}",
        "* regenerate (bit-identical for the same version, seed and count):", "",
        "```sh",
        f"gearcontact vectors --out DIR --count {count} --seed {seed} "
        f"--cores {','.join(cores)}",
        "```", "",
        "or in Python: `gearcontact.hw.vectors.export_vectors(DIR, "
        f"cores={tuple(cores)!r}, count={count}, seed={seed})`.", "",
        "## Files", "",
        "| file | content |", "|---|---|",
        "| `README.md` | this description |"]
    for c in cores:
        n = summary[c]["vectors"]
        lines += [f"| `{c}.jsonl` | {n} JSON objects, one per line (vector) |",
                  f"| `{c}_in.hex` | {n} lines: input fields of vector k on line k |",
                  f"| `{c}_out.hex` | {n} lines: expected outputs of vector k on line k |"]
    lines += [
        "", "## Conventions", "",
        "* `Q(m,f)`: m-bit two's-complement word with f fraction bits, value = code "
        "2^-f; `UQ(m,f)`: unsigned. Codes are integers everywhere (no floating point).",
        "* JSON lines: `{\"core\", \"index\", \"label\", \"inputs\": {field: int or "
        "list}, \"outputs\": {field: int}, \"cycles\"}`; `index` is the 0-based line "
        "number in every file of the core, `label` the corner-case name, `random` "
        "(plausible operands) or `raw` (codes over the whole word range), `cycles` the "
        "clock edges from the edge sampling `go` to the edge after which `done` reads "
        "1 (data independent). Array fields are (nested) lists in index order.",
        "* Hex lines (`$readmemh`): the fields of the tables below concatenated, field "
        "0 leftmost (most significant). Each element is a fixed-width word of `ceil(bits"
        "/4)` hex digits, MSB first: signed elements sign-extended to that width "
        "(two's complement), unsigned ones zero-extended. Array elements follow in "
        "index order, element 0 leftmost (for a (beats, 3) field: beat 0 x, y, z, beat "
        "1 x, ...), so element j of a field whose bit range is [hi:lo] with element "
        "width w = 4 digits sits at [hi - j w : hi - (j + 1) w + 1]. No comments, no "
        "address markers: line k is memory word k.",
        "* Inputs: burst-write fields first (written one beat per clock, beat i at "
        "address i, before `go`), then the operand ports (held with `go`). Field "
        "names are the RTL port names.", "",
        f"Verilog example ({cores[0]} core, N = {summary[cores[0]]['vectors']}):", "",
        "```verilog",
        f"reg [{summary[cores[0]]['in_bits'] - 1}:0] vin  [0:N-1];",
        f"reg [{summary[cores[0]]['out_bits'] - 1}:0] vout [0:N-1];",
        f"initial begin $readmemh(\"{cores[0]}_in.hex\", vin); "
        f"$readmemh(\"{cores[0]}_out.hex\", vout); end",
        "```", ""]
    for c in cores:
        s = summary[c]
        bench = get_bench(c)
        ins, outs = vector_layout(c)
        gen = _generator(c)
        how = " ".join((gen.__doc__ or "").split("Parameters\n")[0].split())
        lines += [f"## {c}", "", f"{bench.summary}. {s['vectors']} vectors: "
                  f"{s['corners']} corner cases (lines 0..{s['corners'] - 1}) + {count} "
                  f"random; {s['cycles']} cycles per vector.", "",
                  f"Operands: `{gen.__module__}.{gen.__name__}` -- {how}", ""]
        if bench.host is not None:
            lines += [_LIFT_TEXT, ""]
        lines += [f"### `{c}_in.hex`: {s['in_bits']} bits per line "
                  f"({s['in_bits'] // 4} hex digits)", ""]
        lines += _field_table(ins)
        lines += ["", f"### `{c}_out.hex`: {s['out_bits']} bits per line "
                  f"({s['out_bits'] // 4} hex digits)", ""]
        lines += _field_table(outs)
        lines += ["", "### Corner cases", ""]
        lines += [f"{i}. {lab}" for i, lab in enumerate(s["labels"][:s["corners"]])]
        lines += [""]
    return "\n".join(lines)


#: README paragraph of the line cores (the host's lift, docs/hertz.md sec. 6).
_LIFT_TEXT = (
    "The host's path (`gearcontact.preview.hertz.line`, *Short lines*; what the preview "
    "engine and the C library's `gc_line_golden` compute): the inputs are the host's, "
    "and a line shorter than the core's 1 mm (L in [2^-8, 1) mm, W << s in the load "
    "envelope) runs on `W << lift`, `L << lift` with the least `lift` that brings L to "
    "1 mm. Line mode: the outputs are the lifted run's with `a = (a + 2^(lift-1)) >> "
    "lift` (every line register depends on W/L alone); a lifted run that keeps the "
    "ellipse answers another load and is flagged `length_range` with outputs 0. "
    "Vectors with `lift` = 0 are the core's registers as they are; to drive the RTL "
    "core from these files, feed `W << lift` and `L << lift` and compare after that "
    "unlift.")


def _generator(core: str):
    """The stimulus generator of ``core``'s vectors (a function with a docstring)."""
    host = get_bench(core).host
    if host is None:
        return STIMULUS_CORES[core]
    module, name = host.stimulus.__name__.rsplit(".", 1)       # a preview.core.lazy call
    return getattr(import_module(f"gearcontact.preview.{module}"), name)


def _check_int(name: str, value, lo: int, hi: int | None = None) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < lo \
            or (hi is not None and value > hi):
        raise InputRangeError(name, value, f"an integer >= {lo}" if hi is None
                              else f"an integer in [{lo}, {hi}]")
    return int(value)


def export_vectors(out_dir, *, cores=VECTOR_CORES, count: int = DEFAULT_COUNT,
                   seed: int = 0) -> list[Path]:
    """Write the golden vectors of ``cores`` into ``out_dir`` (created if missing).

    Parameters
    ----------
    out_dir : str or Path
        Output directory.
    cores : sequence of str, keyword-only
        Subset of :data:`EXPORT_CORES` (default :data:`VECTOR_CORES`; file order follows
        :data:`EXPORT_CORES`).
    count : int, keyword-only
        Seeded random vectors per core (the corner cases come on top).
    seed : int, keyword-only
        Seed of the random part (same seed, same files).

    Returns
    -------
    list of Path
        The files written: per core ``<core>.jsonl``, ``<core>_in.hex``,
        ``<core>_out.hex``, then ``README.md``.

    Raises
    ------
    InputRangeError
        Unknown core, count outside [0, MAX_COUNT], negative seed, or a value that does not fit its port.
    """
    wanted = [cores] if isinstance(cores, str) else list(cores)
    if not wanted:
        raise InputRangeError("cores", cores, f"a non-empty subset of {list(EXPORT_CORES)}")
    for c in wanted:
        _check_core(c)
    count = _check_int("count", count, 0, MAX_COUNT)
    seed = _check_int("seed", seed, 0, 2 ** 63 - 1)
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    files, summary = [], {}
    for core in (c for c in EXPORT_CORES if c in wanted):
        stim = vector_stimulus(core, count, seed)
        ins, outs = vector_layout(core)
        cycles = int(get_bench(core).cycles(stim))
        paths = (out / f"{core}.jsonl", out / f"{core}_in.hex", out / f"{core}_out.hex")
        with (paths[0].open("w") as jf, paths[1].open("w") as inf,
              paths[2].open("w") as outf):
            for first in range(0, len(stim), WRITE_BLOCK):      # golden model per vector
                block = stim.take(slice(first, first + WRITE_BLOCK))
                inputs, outputs = _input_arrays(block), golden_outputs(block)
                texts = (_jsonl_lines(block, inputs, outputs, ins, outs, cycles, first),
                         encode_hex(inputs, ins), encode_hex(outputs, outs))
                for fh, text in zip((jf, inf, outf), texts):
                    fh.write("".join(t + "\n" for t in text))
        files += paths
        summary[core] = {"vectors": len(stim), "corners": stim.n_corner, "cycles": cycles,
                         "labels": stim.labels, "in_bits": sum(f.width for f in ins),
                         "out_bits": sum(f.width for f in outs)}
    readme = out / "README.md"
    readme.write_text(readme_text(summary, count=count, seed=seed))
    return files + [readme]
