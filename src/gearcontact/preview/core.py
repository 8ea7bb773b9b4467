"""One description per RTL core: component, golden batch model, stimulus, cycle count.

Every stage folder exports the :class:`CoreDescriptor` of its cores (``gap.cores``,
``fit.cores``, ``hertz.cores``; ``chain_cores`` for the C -> D and combinational
cores). Every core speaks one protocol: ``go`` starts a run when the core is idle,
``busy`` is high while it runs, ``done`` rises on the last edge and holds until the
next accepted ``go``, ``done_pulse`` marks its first cycle (streaming cores use
valid/ready instead). A descriptor names the Amaranth component
and its protocol ports but never repeats a port width: everything that needs widths
(the Verilator harness, the vector layouts, the port README) derives them from the
component's ``signature.members`` (:func:`gearcontact.hw.harness_cores.derive_spec`).
The hardware side (:mod:`gearcontact.hw`) consumes the descriptors; nothing here
imports it.

:func:`core_descriptors` collects them in a fixed order (the order of
``gearcontact rtl sim --core`` and of the bulk tests).
"""

from __future__ import annotations

import importlib
from collections.abc import Callable
from dataclasses import dataclass, field
from functools import cache

from ..validation import InputRangeError
from .stimulus import Stimulus, stimulus

__all__ = ["WriteNames", "HostPath", "CoreDescriptor", "core_descriptors", "lazy", "DESCRIPTOR_MODULES"]

#: Modules exporting ``DESCRIPTORS`` (tuples of :class:`CoreDescriptor`), in order.
DESCRIPTOR_MODULES = ("gearcontact.preview.gap.cores", "gearcontact.preview.fit.cores",
                      "gearcontact.preview.hertz.cores", "gearcontact.preview.chain_cores")


@dataclass(frozen=True)
class WriteNames:
    """A burst write port by its port names (widths come from the signature).

    Attributes
    ----------
    strobe : str
        Write-enable input, high during the burst.
    fields : tuple of str
        Data inputs driven with each beat.
    max_beats : int
        Capacity of the burst (words).
    addr, clear : str, optional
        Beat-index input; one-cycle clear pulse before the burst.
    """

    strobe: str
    fields: tuple
    max_beats: int
    addr: str | None = None
    clear: str | None = None


@dataclass(frozen=True)
class HostPath:
    """What the host does around a core, which its golden vectors describe: the line
    cores' vectors are the host's path (a line shorter than the core's 1 mm lifted and
    the outputs unlifted, :mod:`.hertz.line`), what a driver and the C library compute.

    Attributes
    ----------
    stimulus : callable
        ``stimulus(n, seed) -> Stimulus``: corner cases + ``n`` seeded random vectors.
    golden : callable
        ``Stimulus -> {output port: int64 array}``: the core's checked outputs of the
        host's path, then the :attr:`outputs`.
    outputs : tuple of (str, int)
        ``(name, bits)`` of the unsigned outputs the host adds after the core's (the
        line cores: ``lift``, the shift s).
    """

    stimulus: Callable
    golden: Callable
    outputs: tuple = ()


@dataclass(frozen=True)
class CoreDescriptor:
    """How the rest of the package sees one RTL core.

    Attributes
    ----------
    name : str
        Core name (``gearcontact rtl sim --core NAME``).
    module : str
        RTL module under :mod:`gearcontact.preview` with ``convert_verilog``.
    component : callable
        ``component(**verilog_kwargs)`` -> the Amaranth ``wiring.Component`` (its
        ``signature.members`` give every port width).
    top : str
        Verilog top module name.
    ports : callable
        ``Stimulus -> (inputs, beats, n_beats)``: stimulus fields onto port names.
    golden : callable
        ``Stimulus -> {checked output port: int64 array}`` (vectorized golden model).
    amaranth : callable
        ``Stimulus -> ({port: int64 array}, cycles[, initiation interval])`` through the
        Amaranth simulator.
    cycles : callable
        ``Stimulus -> expected cycles per vector`` (go -> done, or the latency of a
        streaming core).
    go, done : str
        Start strobe and completion output (``in_valid`` / ``out_valid`` when
        ``stream``).
    control : tuple of str
        Ports that are neither operand inputs nor checked outputs (strobes, status).
    max_cycles : int
        Edges after which a simulation gives up on a vector.
    write : WriteNames, optional
        Burst write port driven before ``go``.
    stream : bool
        Valid/ready streaming core (``in_valid``, ``in_ready``, ``out_valid``,
        ``out_ready``).
    verilog_kwargs, stimulus_kwargs : dict
        Extra keyword arguments of ``component``/``convert_verilog`` and of the
        stimulus generator.
    stimulus_core : str
        Generator name in :data:`.stimulus.STIMULUS_CORES` (default: ``name``).
    summary : str
        One line for ``--help`` and the port README.
    host : HostPath, optional
        The host's path around the core, for the golden-vector export
        (:mod:`gearcontact.hw.vectors`; default: the core alone).
    """

    name: str
    module: str
    component: Callable
    top: str
    ports: Callable
    golden: Callable
    amaranth: Callable
    cycles: Callable
    go: str = "go"
    done: str = "done"
    control: tuple = ()
    max_cycles: int = 2000
    write: WriteNames | None = None
    stream: bool = False
    verilog_kwargs: dict = field(default_factory=dict)
    stimulus_kwargs: dict = field(default_factory=dict)
    stimulus_core: str | None = None
    summary: str = ""
    host: HostPath | None = None

    def stimulus(self, n: int, seed: int = 0, **kwargs) -> Stimulus:
        """Corner cases + ``n`` random vectors (:mod:`gearcontact.preview.stimulus`)."""
        return stimulus(self.stimulus_core or self.name, n, seed,
                        **{**self.stimulus_kwargs, **kwargs})

    def make_component(self):
        """A fresh instance of the component (not elaborated)."""
        return self.component(**self.verilog_kwargs)


@cache
def core_descriptors() -> dict[str, CoreDescriptor]:
    """Every core's descriptor by name, in :data:`DESCRIPTOR_MODULES` order.

    A module whose RTL is missing from the checkout is skipped only if it raises
    ImportError; a duplicate name is an error.
    """
    out: dict[str, CoreDescriptor] = {}
    for mod in DESCRIPTOR_MODULES:
        for d in importlib.import_module(mod).DESCRIPTORS:
            if d.name in out:
                raise InputRangeError("core descriptor name", d.name, "unique")
            out[d.name] = d
    return out


def lazy(module: str, attr: str) -> Callable:
    """``f(*args, **kwargs)`` calling ``gearcontact.preview.<module>.<attr>``, imported on
    the first call (descriptors are cheap to import; Amaranth and numba load only when a
    core is built or its golden model runs)."""
    def call(*args, **kwargs):
        fn = getattr(importlib.import_module(f"gearcontact.preview.{module}"), attr)
        return fn(*args, **kwargs)
    call.__qualname__ = call.__name__ = f"{module}.{attr}"
    return call
