"""Test helper: two results of the same call compared bit for bit, every number.

The determinism tests (tests/*/test_determinism.py) call a library entry point twice in
one process and assert that the two results are equal to the last bit: no tolerance,
because identical inputs must give identical results (docs/architecture.md, "Rules").
Timings are the one thing allowed to differ; they are skipped by name.
"""

import dataclasses
import math

import numpy as np

from gearcontact.tca.export import TIMING_KEYS

#: Names of timing fields (wall clock, allowed to differ between identical calls).
TIMING_NAMES = frozenset(TIMING_KEYS) | {"solve_time_ms", "timings_s", "timings", "latency",
                                           "build_s", "fe_build_s"}


def differences(a, b, path: str = "result", *, skip=TIMING_NAMES, seen=None) -> list[str]:
    """Paths at which ``a`` and ``b`` differ (empty: bit-identical).

    Walks dataclasses (their fields, also ``compare=False`` ones), dicts, lists and
    tuples, numpy arrays (``np.array_equal``, NaN equal to NaN in float arrays) and
    scalars (floats by ``==``, a NaN equal to a NaN); objects of other types are compared
    by their ``__dict__`` when they have one, else by ``==``. Fields named in ``skip``
    are left out.
    """
    seen = set() if seen is None else seen
    if a is b or id(a) in seen:            # one object, shared sub-objects, cycles: walked once
        return []
    if type(a) is not type(b):
        return [f"{path}: type {type(a).__name__} != {type(b).__name__}"]
    if isinstance(a, np.ndarray):
        if a.shape != b.shape:
            return [f"{path}: shape {a.shape} != {b.shape}"]
        nan = a.dtype.kind in "fc"
        if not np.array_equal(a, b, equal_nan=nan):
            if a.dtype.kind in "fc":
                d = np.nanmax(np.abs(a - b)) if a.size else 0.0
                return [f"{path}: array differs (max |diff| {d:.3e})"]
            return [f"{path}: array differs"]
        return []
    if isinstance(a, float):
        same = a == b or (math.isnan(a) and math.isnan(b))
        return [] if same else [f"{path}: {a!r} != {b!r} (diff {b - a:.3e})"]
    if isinstance(a, (str, bytes, int, bool, type(None), np.generic)):
        same = a == b or (isinstance(a, np.floating) and np.isnan(a) and np.isnan(b))
        return [] if same else [f"{path}: {a!r} != {b!r}"]
    seen.add(id(a))
    if dataclasses.is_dataclass(a):
        out = []
        for f in dataclasses.fields(a):
            if f.name not in skip:
                out += differences(getattr(a, f.name), getattr(b, f.name),
                                   f"{path}.{f.name}", skip=skip, seen=seen)
        return out
    if isinstance(a, dict):
        if list(a) != list(b):
            return [f"{path}: keys {list(a)} != {list(b)}"]
        out = []
        for k in a:
            if k not in skip:
                out += differences(a[k], b[k], f"{path}[{k!r}]", skip=skip, seen=seen)
        return out
    if isinstance(a, (list, tuple)):
        if len(a) != len(b):
            return [f"{path}: length {len(a)} != {len(b)}"]
        out = []
        for i, (x, y) in enumerate(zip(a, b)):
            out += differences(x, y, f"{path}[{i}]", skip=skip, seen=seen)
        return out
    if hasattr(a, "__dict__"):
        return differences(vars(a), vars(b), path, skip=skip, seen=seen)
    return [] if a == b else [f"{path}: {a!r} != {b!r}"]


def assert_same(a, b, *, skip=TIMING_NAMES) -> None:
    """Assert that ``a`` and ``b`` are bit-identical (timings aside), naming each
    difference."""
    diff = differences(a, b, skip=skip)
    assert not diff, "differ at:\n" + "\n".join(diff[:40])
