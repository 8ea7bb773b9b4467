"""Generated hardware files that depend only on the design: no absolute paths, dates or
memory-address orderings (issue 12: byte-identical result files across identical runs).

Amaranth writes the Python source location of every signal into the Verilog
(``(* src = "/abs/path/gearcontact/preview/gap/rtl.py:191" *)``), so the text depends on
where the package is installed (and on which work tree filled the Verilog cache of
:mod:`.harness_cores`); LiteX stamps its outputs with the wall-clock date, lists the
black-box instances of its hierarchy comment in memory-address order and writes
absolute paths into the Yosys script. The functions here rewrite exactly those parts.
"""

from __future__ import annotations

import os
import re
from pathlib import Path

__all__ = ["portable_src", "without_dates", "sorted_blackboxes", "relative_paths",
           "reproducible_tree"]

_SRC = re.compile(r'(\(\* src = ")([^"]*)(" \*\))')
#: Directories after which a source path is import-relative (``gearcontact/...``).
_ROOTS = ("/site-packages/", "/dist-packages/", "/src/")


def _portable(location: str) -> str:
    if not location.startswith("/"):
        return location
    for root in _ROOTS:
        at = location.rfind(root)
        if at >= 0:
            return location[at + len(root):]
    return location.rsplit("/", 1)[-1]


def portable_src(verilog: str) -> str:
    """``verilog`` with every ``src`` attribute's paths made import-relative
    (``gearcontact/preview/gap/rtl.py:191``); Yosys joins several with ``|``."""
    return _SRC.sub(lambda m: m[1] + "|".join(_portable(p) for p in m[2].split("|"))
                    + m[3], verilog)


_DATE = re.compile(r"(?: on)? \d{4}-\d\d-\d\d \d\d:\d\d:\d\d")


def without_dates(text: str) -> str:
    """LiteX's generation banners without their wall-clock date."""
    return _DATE.sub("", text)


_BLACKBOX = re.compile(r"^(?:│    )*└─── \[[^\]]*\]$")


def sorted_blackboxes(text: str) -> str:
    """The black-box lines of LiteX's hierarchy comment (``└─── [FDPE]``), which LiteX
    orders by object address, sorted within each run of consecutive such lines."""
    lines = text.split("\n")
    i = 0
    while i < len(lines):
        if _BLACKBOX.match(lines[i]):
            j = i
            while j < len(lines) and _BLACKBOX.match(lines[j]):
                j += 1
            lines[i:j] = sorted(lines[i:j])
            i = j
        else:
            i += 1
    return "\n".join(lines)


def relative_paths(text: str, base: Path, here: Path) -> str:
    """``text`` with absolute paths under ``base`` rewritten relative to ``here`` (the
    directory the script runs in, e.g. LiteX's ``gateware/``)."""
    base, here = Path(base).resolve(), Path(here).resolve()
    pattern = re.compile(re.escape(str(base)) + r"(?=/|[\s\"']|$)(/[^\s\"']*)?")

    def rel(m: re.Match) -> str:
        target = Path(str(base) + (m[1] or ""))
        return Path(os.path.relpath(target, here)).as_posix()

    return pattern.sub(rel, text)


def reproducible_tree(root, *, here) -> None:
    """Rewrite every generated text file under ``root`` in place: import-relative
    ``src`` paths, no dates, sorted black boxes, paths under ``root`` relative to
    ``here`` (where the scripts run)."""
    for path in sorted(Path(root).rglob("*")):
        if not path.is_file():
            continue
        try:
            text = path.read_text(encoding="utf-8")
        except UnicodeDecodeError:
            continue                      # binary: nothing of the above in it
        new = relative_paths(sorted_blackboxes(without_dates(portable_src(text))),
                             root, here)
        if new != text:
            path.write_text(new, encoding="utf-8")
