"""Reuse of flank work between pairs that share a flank's inputs: opt-in, exact-keyed.

A sweep over the machine settings of a pair (``gearcontact sweep --vary
machine.pinion.drive.tilt_deg=...``) prepares each variant as every command prepares a
pair, so without reuse every variant cuts all four flanks again, though a key of one
flank's ``[machine.*]`` / ``[blade.*]`` tables leaves the other three flanks' inputs as
they were. Inside :func:`reusing_flanks` the functions decorated by :func:`reused` (the
flank a set-up cuts, :func:`~.kinked.machine_flank`, and the active box a generated
flank's set-up traces, :func:`~.generated.generated_pinion_box` /
:func:`~.generated.generated_gear_box`) return the result they returned before for
the same inputs instead of computing it again; outside it they compute, as before.

The key of a call is its inputs themselves, exactly (:func:`exact_key`): the function,
and every argument bound to its signature with the defaults applied, each as its type
and content, down to the bytes of every float (``-0.0`` is not ``0.0``; one ulp apart
are two keys) and of every array. A flank set-up's inputs are the typed tables of its
member and flank (its :class:`~.machine.MachineSetup`: the machine settings and the
blade), the blank (:class:`~.blank.BlankDesign`, every field), the member's face width
and the node grid; nothing else enters these functions (they read no other state but
module constants). The cache compares keys whole (a dict key, equality after the hash):
no digest stands for the inputs, so two inputs that differ in any bit never share an
entry. What the pair does with a flank after it is cut (the pinion's turn onto the
design side's mean contact, the mean contacts, the tooth thickness: they depend on the
mate, :func:`~.flank.build_machine_flanks`) is computed every time from the flanks.

The warnings a call emits are part of its result: recorded when it is computed and
emitted again by every call the entry serves. A call that raises is not stored (the
next call with its inputs raises again), nor is a call with an argument
:func:`exact_key` cannot tell exactly (computed, counted in
:attr:`FlankCache.unkeyed`). Results are shared, not copied: the flanks
and boxes are immutable by contract (frozen dataclasses; the pinion's turn makes a new
sheet).

The entries are held in a :class:`FlankCache` of bounded size (least recently used
out first); the sweep keeps one per process (:mod:`gearcontact.sweep.settings_keys`).
Measured on the F.2 settings pair: docs/sweeps.md, "A pair cut from machine
settings".
"""

from __future__ import annotations

import contextlib
import contextvars
import dataclasses
import functools
import inspect
import struct
import threading
import warnings
from collections import OrderedDict

import numpy as np

__all__ = ["FlankCache", "exact_key", "reused", "reusing_flanks"]

_ACTIVE: contextvars.ContextVar = contextvars.ContextVar("gearcontact_flank_reuse",
                                                         default=None)


class FlankCache:
    """Results of :func:`reused` functions by their exact inputs, at most
    ``max_entries`` of them (the least recently used dropped first).

    Attributes
    ----------
    hits, misses, unkeyed : dict
        Per function (``module.qualname``): calls served from an entry, calls computed
        and stored, and calls computed without a key (an argument :func:`exact_key`
        cannot tell exactly: never served, never stored).
    """

    def __init__(self, *, max_entries: int = 24):
        if int(max_entries) != max_entries or max_entries < 1:
            raise ValueError(f"max_entries = {max_entries!r}: an integer >= 1")
        self.max_entries = int(max_entries)
        self._entries: OrderedDict = OrderedDict()
        self._lock = threading.Lock()
        self.hits: dict = {}
        self.misses: dict = {}
        self.unkeyed: dict = {}

    def __len__(self) -> int:
        return len(self._entries)

    def clear(self) -> None:
        """Drop every entry and the counts."""
        with self._lock:
            self._entries.clear()
            for counts in (self.hits, self.misses, self.unkeyed):
                counts.clear()

    def _count(self, counts: dict, name: str) -> None:
        with self._lock:
            counts[name] = counts.get(name, 0) + 1

    def _get(self, key):
        with self._lock:
            got = self._entries.get(key)
            if got is not None:
                self._entries.move_to_end(key)
                self.hits[key[0]] = self.hits.get(key[0], 0) + 1
            return got

    def _put(self, key, entry) -> None:
        self._count(self.misses, key[0])
        with self._lock:
            self._entries[key] = entry
            self._entries.move_to_end(key)
            while len(self._entries) > self.max_entries:
                self._entries.popitem(last=False)


@contextlib.contextmanager
def reusing_flanks(cache: FlankCache | None):
    """Within this block (this thread / task), :func:`reused` functions are served by
    ``cache``; ``None``: computed every time (as outside any block)."""
    token = _ACTIVE.set(cache)
    try:
        yield cache
    finally:
        _ACTIVE.reset(token)


def reused(fn):
    """``fn`` served by the active :class:`FlankCache` (:func:`reusing_flanks`), keyed by
    its exact inputs (:func:`exact_key` of the arguments bound to its signature, defaults
    applied), its warnings recorded and emitted again on every call; computed as
    ``fn`` itself outside such a block."""
    signature = inspect.signature(fn)
    name = f"{fn.__module__}.{fn.__qualname__}"

    @functools.wraps(fn)
    def wrapper(*args, **kwargs):
        cache = _ACTIVE.get()
        if cache is None:
            return fn(*args, **kwargs)
        bound = signature.bind(*args, **kwargs)
        bound.apply_defaults()
        try:
            key = (name, exact_key(tuple(bound.arguments.items())))
        except TypeError:           # inputs not told exactly: computed, never served
            cache._count(cache.unkeyed, name)
            return fn(*args, **kwargs)
        entry = cache._get(key)
        if entry is None:
            with warnings.catch_warnings(record=True) as caught:
                warnings.simplefilter("always")
                value = fn(*args, **kwargs)
            entry = (value, tuple(caught))
            cache._put(key, entry)
        value, caught = entry
        for w in caught:
            warnings.warn_explicit(w.message, w.category, w.filename, w.lineno,
                                   source=w.source)
        return value

    return wrapper


def exact_key(value):
    """A hashable key equal for two values exactly when they are the same inputs: the
    type (module and name) and content of ``value``, recursively through dataclasses
    (every field, in order), tuples, lists and dicts; a float by its eight bytes, an
    array by its dtype, shape and bytes.

    Raises
    ------
    TypeError
        A value of another kind (its content could not be told exactly; a caller must
        not be served on it).
    """
    kind = type(value)
    name = f"{kind.__module__}.{kind.__qualname__}"
    if value is None or isinstance(value, (bool, int, str, bytes)):
        return (name, value)
    if isinstance(value, (float, np.floating)):
        return (name, struct.pack("<d", float(value)))
    if isinstance(value, np.integer | np.bool_):
        return (name, value.item())
    if isinstance(value, np.ndarray):
        if value.dtype == object:
            return (name, value.shape, tuple(exact_key(v) for v in value.ravel()))
        return (name, value.dtype.str, value.shape, np.ascontiguousarray(value).tobytes())
    if isinstance(value, (tuple, list)):
        return (name, tuple(exact_key(v) for v in value))
    if isinstance(value, dict):
        items = sorted((exact_key(k), exact_key(v)) for k, v in value.items())
        return (name, tuple(items))
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        return (name, tuple((f.name, exact_key(getattr(value, f.name)))
                            for f in dataclasses.fields(value)))
    raise TypeError(f"exact_key: a {name} is not keyed exactly (dataclasses, numbers, "
                    "strings, arrays, tuples, lists and dicts are)")
