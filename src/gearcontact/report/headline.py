"""The status of a reproduce item, computed from its headline quantities
(docs/reproduce.md sec. 5).

Each item of ``gearcontact reproduce`` names its headline quantities, the published
value of each and the tolerance it is judged against, with the reason, in
``data/published/<pair>_headlines.json`` beside the published values. The item's
builder supplies only what it measured (and the published value, which is checked
against ``<pair>.json`` where it is a plain key); :func:`judge` builds the
:class:`Headline` rows and :func:`item_status` applies the rule:

* ``reproduced`` — every headline quantity within its tolerance;
* ``differs`` — no key headline within its tolerance (or, for an item without key
  quantities, no headline at all);
* ``partial`` — otherwise.

``not available`` is the status of an item that measured nothing (its physics or its
data is missing); it has no headlines.
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass
from importlib import resources

import numpy as np

from ..tca.calibration import CalibrationTargets
from .document import Section, Table, format_cell

__all__ = ["HEADLINE_HEADER", "STATUSES", "Headline", "explain", "headline_rows",
           "headline_spec", "item_status", "judge", "judged_section", "status_counts",
           "summary_line"]

#: Statuses an item can have, in the order the summary counts them.
STATUSES = ("reproduced", "partial", "differs", "not available")
#: Columns of :func:`headline_rows`.
HEADLINE_HEADER = ["headline quantity", "ours", "published", "tolerance", "within", "key",
                   "why this tolerance"]


@dataclass(frozen=True)
class Headline:
    """One headline quantity of an item, measured against its published value.

    Attributes
    ----------
    id : str
        Key in the item's list of ``<pair>_headlines.json``.
    quantity : str
        Readable name with the unit.
    measured : float or sequence of float or None
        Our value (a sequence: one per torque / lane, each must be within); None when
        the run did not measure it (never within).
    published : float or tuple of float
        The published value; ``(lo, hi)`` for a published interval.
    low, high : float
        The accepted interval (published value and tolerance), same unit as ``measured``.
    tolerance : str
        The tolerance as stated (e.g. ``"10 % of the value"``).
    reason : str
        Why this tolerance.
    key : bool
        A key quantity of the item (see :func:`item_status`).
    """

    id: str
    quantity: str
    measured: object
    published: object
    low: float
    high: float
    tolerance: str
    reason: str
    key: bool

    @property
    def values(self) -> tuple:
        """The measured values as a tuple (empty when not measured)."""
        if self.measured is None:
            return ()
        return tuple(np.atleast_1d(np.asarray(self.measured, dtype=float)).tolist())

    @property
    def within(self) -> bool:
        """Every measured value finite and inside ``[low, high]``."""
        v = self.values
        return bool(v) and all(math.isfinite(x) and self.low <= x <= self.high for x in v)

    def as_dict(self) -> dict:
        """Plain-JSON view (``report.json[item]["headlines"]``)."""
        m = self.values
        scalar = np.ndim(self.measured) == 0
        return {"id": self.id, "quantity": self.quantity,
                "measured": None if not m else (m[0] if scalar else list(m)),
                "published": (list(self.published) if isinstance(self.published, tuple)
                              else self.published),
                "low": self.low, "high": self.high, "tolerance": self.tolerance,
                "reason": self.reason, "key": self.key, "within": self.within}


def item_status(headlines) -> str:
    """``reproduced``, ``partial`` or ``differs`` from an item's headlines (module
    docstring); raises ValueError for an item without headlines."""
    headlines = tuple(headlines)
    if not headlines:
        raise ValueError("an item without headline quantities has no computed status")
    if all(h.within for h in headlines):
        return "reproduced"
    decisive = [h for h in headlines if h.key] or headlines
    return "differs" if not any(h.within for h in decisive) else "partial"


def status_counts(statuses) -> dict:
    """Number of items per status (every status of :data:`STATUSES`, zeros included)."""
    statuses = list(statuses)
    unknown = set(statuses) - set(STATUSES)
    if unknown:
        raise ValueError(f"unknown item status {sorted(unknown)}; known: {STATUSES}")
    return {s: statuses.count(s) for s in STATUSES}


def summary_line(counts: dict) -> str:
    """``"n reproduced, n partial, n differs"`` (and ``n not available`` when any) of
    :func:`status_counts`."""
    return ", ".join(f"{counts[s]} {s}" for s in STATUSES
                     if s != "not available" or counts[s])


def headline_spec(pair: str = "s0003") -> dict:
    """The committed headline quantities and tolerances of ``pair`` (item -> list)."""
    res = resources.files("gearcontact").joinpath(f"data/published/{pair}_headlines.json")
    return {k: v for k, v in json.loads(res.read_text()).items() if not k.startswith("_")}


def _lookup(pub: dict, dotted: str):
    x = pub
    for part in dotted.split("."):
        x = x[part]
    return x


def _interval(tol: dict, published) -> tuple[float, float, str]:
    """(low, high, stated tolerance) of a tolerance entry around ``published``."""
    (kind, arg), = tol.items()
    if kind == "calibration":
        value = getattr(CalibrationTargets, arg)          # the dataclass default
        kind, arg = ("relative", value) if arg.endswith("_rel") else ("absolute", value)
    if kind == "range":
        lo, hi = (float(x) for x in published)
        return lo, hi, f"inside [{lo:g}, {hi:g}]"
    p = float(published)
    if kind == "relative":
        d = float(arg) * abs(p)
        return p - d, p + d, f"±{100 * float(arg):g} % of the value"
    if kind == "absolute":
        return p - float(arg), p + float(arg), f"±{float(arg):g}"
    if kind == "exact":
        return p, p, "exact"
    raise ValueError(f"unknown tolerance kind {kind!r}")


def judge(item: str, measured: dict, pub: dict, *, spec: dict | None = None
          ) -> tuple[Headline, ...]:
    """The headlines of ``item`` from what the run measured.

    Parameters
    ----------
    item : str
        Item key (``reproduce.ITEMS``).
    measured : dict
        ``id -> (measured, published)`` for every headline of the item (measured: a
        number, a sequence of numbers or None).
    pub : dict
        The pair's published values (``data/published/<pair>.json``); a headline with a
        ``published_key`` must be given exactly that value.
    spec : dict, optional
        Item -> headline entries; default :func:`headline_spec` of s0003.
    """
    entries = (headline_spec() if spec is None else spec)[item]
    ids = [e["id"] for e in entries]
    if set(ids) != set(measured):
        raise ValueError(f"item {item}: headlines {sorted(ids)} committed, "
                         f"{sorted(measured)} measured")
    out = []
    for e in entries:
        value, published = measured[e["id"]]
        if "published_key" in e:
            ref = _lookup(pub, e["published_key"])
            if np.ndim(ref) != np.ndim(published) or not np.allclose(ref, published,
                                                                     rtol=1e-12, atol=0):
                raise ValueError(f"item {item}, {e['id']}: published {published} is not "
                                 f"{e['published_key']} = {ref}")
        published = tuple(published) if np.ndim(published) else float(published)
        low, high, stated = _interval(e["tolerance"], published)
        out.append(Headline(e["id"], e["quantity"], value, published, low, high, stated,
                            e["reason"], bool(e["key"])))
    return tuple(out)


def _fmt(x, *, interval: bool = False) -> str:
    if x is None:
        return "not measured"
    if interval:
        return f"[{format_cell(float(x[0]))}, {format_cell(float(x[1]))}]"
    if np.ndim(x):
        return ", ".join(format_cell(float(v)) for v in np.ravel(x))
    return format_cell(float(x))


def explain(headlines) -> str:
    """One paragraph: the computed status, how many headlines are within and, for each
    one outside its tolerance, ours against the published value and the accepted
    interval."""
    headlines = tuple(headlines)
    status = item_status(headlines)
    n_in = sum(h.within for h in headlines)
    head = (f"{status.capitalize()}: {n_in} of {len(headlines)} headline quantities "
            f"within their tolerance")
    outside = [h for h in headlines if not h.within]
    if not outside:
        return head + "."
    parts = [f"{h.quantity}{' (key)' if h.key else ''}: ours {_fmt(h.measured)} against "
             + (f"the published interval {_fmt(h.published, interval=True)}"
                if isinstance(h.published, tuple)
                else f"the published {_fmt(h.published)}, tolerance {h.tolerance} "
                     f"({format_cell(h.low)} to {format_cell(h.high)})")
             for h in outside]
    return (head + "; outside: " + "; ".join(parts) + ". Why each tolerance: table "
            "'headline quantities'.")


def headline_rows(headlines) -> Table:
    """The headlines as a report table (:data:`HEADLINE_HEADER`)."""
    return Table("Headline quantities: the status is computed from these",
                 HEADLINE_HEADER,
                 [[h.quantity, _fmt(h.measured),
                   _fmt(h.published, interval=isinstance(h.published, tuple)), h.tolerance,
                   h.within, h.key, h.reason] for h in headlines])


def judged_section(key: str, number: int, title: str, headlines, text, tables, figures,
                   data) -> Section:
    """A report item whose status is computed from ``headlines`` (:func:`item_status`):
    the explanation (:func:`explain`) is its first paragraph, the headline table
    (:func:`headline_rows`) its first table."""
    headlines = tuple(headlines)
    return Section(key, number, title, item_status(headlines),
                   [explain(headlines)] + list(text),
                   [headline_rows(headlines)] + list(tables), list(figures), data, headlines)
